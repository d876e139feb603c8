//! A table of points $`(X_k, p_k)`$ with strictly increasing $`X_k`$: a parameter's profile
//! along a line (`model.profiles`).

use super::number::Float;
use super::value::{Scalar, item_message};
use crate::scene::text::{describe, toml_float};
use toml::Value;

/// Most points of one profile.
pub const MAX_PROFILE_POINTS: usize = 10_000;

/// `[[X0, p0], [X1, p1], …]`: finite numbers, $`X`$ strictly increasing, 1 to
/// [`MAX_PROFILE_POINTS`] points.
#[derive(Clone, Copy, Debug)]
pub struct PointTable;

impl Scalar for PointTable {
    type Value = Vec<[f64; 2]>;

    fn read(&self, value: &Value) -> Result<Vec<[f64; 2]>, String> {
        let expected = || {
            format!(
                "expected an array of [X, value] pairs, got {}",
                describe(value)
            )
        };
        let Value::Array(items) = value else {
            return Err(expected());
        };
        items
            .iter()
            .enumerate()
            .map(|(index, item)| {
                match item {
                    Value::Array(pair) if pair.len() == 2 => {
                        let number = |v: &Value| Float::finite().read(v);
                        Ok([number(&pair[0])?, number(&pair[1])?])
                    }
                    other => Err(format!(
                        "expected a pair [X, value], got {}",
                        describe(other)
                    )),
                }
                .map_err(|m| item_message(index, m))
            })
            .collect()
    }

    fn within_bounds(&self, value: &Vec<[f64; 2]>) -> Result<(), String> {
        if value.is_empty() || value.len() > MAX_PROFILE_POINTS {
            return Err(format!(
                "a profile has 1 to {MAX_PROFILE_POINTS} points, got {}",
                value.len()
            ));
        }
        for (index, point) in value.iter().enumerate() {
            if !point.iter().all(|v| v.is_finite()) {
                return Err(item_message(index, "must be finite".into()));
            }
            if index > 0 && point[0] <= value[index - 1][0] {
                return Err(item_message(
                    index,
                    format!(
                        "X must increase strictly: {} does not come after {}",
                        point[0],
                        value[index - 1][0]
                    ),
                ));
            }
        }
        Ok(())
    }

    fn text(&self, value: &Vec<[f64; 2]>) -> String {
        let pairs: Vec<String> = value
            .iter()
            .map(|[x, p]| format!("[{}, {}]", toml_float(*x), toml_float(*p)))
            .collect();
        format!("[{}]", pairs.join(", "))
    }

    fn unit_applies(&self, _value: &Vec<[f64; 2]>) -> bool {
        false
    }

    fn json_value(&self, value: &Vec<[f64; 2]>) -> serde_json::Value {
        serde_json::Value::from(value.iter().map(|p| p.to_vec()).collect::<Vec<_>>())
    }

    fn bounds_text(&self) -> String {
        format!(
            "array of 1 to {MAX_PROFILE_POINTS} pairs `[X, value]` of finite numbers, X (mm) strictly increasing"
        )
    }
}
