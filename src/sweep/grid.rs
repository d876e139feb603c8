//! The points of a sweep: a grid of scene keys and values (`--grid KEY=a,b,c`, or a Python
//! `dict`), crossed in order ([`Grid::points`]), or a list of scenes given one by one.

use super::recipe::SceneRecipe;
use crate::error::Error;

/// Most points one sweep may have (the product of the grid's value counts).
pub const MAX_POINTS: usize = 100_000;

/// One key of a grid and its values, each a TOML value as `--set` reads it (`0.25`, `"auto"`,
/// `auto`, `[1, 2]`).
#[derive(Clone, Debug, PartialEq)]
pub struct GridAxis {
    /// Dotted scene key.
    pub key: String,
    /// Its values, in order.
    pub values: Vec<String>,
}

/// The keys of a sweep with their values; the points are every combination, the first key
/// varying slowest.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Grid {
    /// The axes, in the order given.
    pub axes: Vec<GridAxis>,
}

/// One point of a sweep before it runs: its place in the sweep, the values it was given, and
/// how its scene is made.
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct PlannedPoint {
    /// Index in the sweep, from 0.
    pub index: usize,
    /// `(key, value)` of each grid axis at this point (empty for a list of scenes).
    pub inputs: Vec<(String, String)>,
    /// Its scene.
    pub recipe: SceneRecipe,
}

impl Grid {
    /// Parses `--grid KEY=a,b,c` arguments: a dotted key, `=`, values separated by commas (a
    /// comma inside brackets, braces or quotes belongs to the value: `KEY=[1,2],[3,4]` is two
    /// values). A key given twice, an empty key or value, or more than [`MAX_POINTS`] points is
    /// a usage error naming the argument.
    pub fn parse(arguments: &[String]) -> Result<Grid, Error> {
        let mut axes: Vec<GridAxis> = Vec::new();
        for argument in arguments {
            let bad = |why: &str| Error::Usage(format!("--grid {argument}: {why}"));
            let (key, list) = argument
                .split_once('=')
                .ok_or_else(|| bad("expected KEY=a,b,c"))?;
            let key = key.trim();
            if key.is_empty() || key.split('.').any(str::is_empty) {
                return Err(bad("expected a dotted scene key such as load.tension_y"));
            }
            if axes.iter().any(|axis| axis.key == key) {
                return Err(bad(
                    "the key is given twice: give all its values in one --grid",
                ));
            }
            let values = split_values(list);
            if values.iter().any(String::is_empty) {
                return Err(bad("a value is empty (a trailing or doubled comma?)"));
            }
            axes.push(GridAxis {
                key: key.to_string(),
                values,
            });
        }
        let grid = Grid { axes };
        grid.point_count()?;
        Ok(grid)
    }

    /// The number of points: the product of the value counts (1 for no axis), at most
    /// [`MAX_POINTS`].
    pub fn point_count(&self) -> Result<usize, Error> {
        self.axes
            .iter()
            .try_fold(1usize, |count, axis| count.checked_mul(axis.values.len()))
            .filter(|&count| count <= MAX_POINTS)
            .ok_or_else(|| {
                Error::Usage(format!(
                    "the grid has more than {MAX_POINTS} points: split the sweep"
                ))
            })
    }

    /// Every point of the grid over `base`, the first axis varying slowest: point $`i`$ sets
    /// each axis's value with an override `KEY=VALUE` after the base's own.
    pub fn points(&self, base: &SceneRecipe) -> Result<Vec<PlannedPoint>, Error> {
        let count = self.point_count()?;
        let points = (0..count)
            .map(|index| {
                let mut rest = index;
                let mut inputs = vec![(String::new(), String::new()); self.axes.len()];
                for (slot, axis) in inputs.iter_mut().zip(&self.axes).rev() {
                    let value = &axis.values[rest % axis.values.len()];
                    rest /= axis.values.len();
                    *slot = (axis.key.clone(), value.clone());
                }
                let mut recipe = base.clone();
                recipe
                    .overrides
                    .extend(inputs.iter().map(|(key, value)| format!("{key}={value}")));
                PlannedPoint {
                    index,
                    inputs,
                    recipe,
                }
            })
            .collect();
        Ok(points)
    }
}

/// The points of a list of scenes, one each, in order.
pub fn listed_points(recipes: Vec<SceneRecipe>) -> Vec<PlannedPoint> {
    recipes
        .into_iter()
        .enumerate()
        .map(|(index, recipe)| PlannedPoint {
            index,
            inputs: Vec::new(),
            recipe,
        })
        .collect()
}

/// Splits `a,b,c` at the commas outside brackets, braces and quotes; each value trimmed.
fn split_values(list: &str) -> Vec<String> {
    let mut values = Vec::new();
    let mut current = String::new();
    let mut depth = 0usize;
    let mut quote: Option<char> = None;
    for character in list.chars() {
        match (quote, character) {
            (Some(open), c) if c == open => quote = None,
            (Some(_), _) => {}
            (None, '"' | '\'') => quote = Some(character),
            (None, '[' | '{') => depth += 1,
            (None, ']' | '}') => depth = depth.saturating_sub(1),
            (None, ',') if depth == 0 => {
                values.push(current.trim().to_string());
                current.clear();
                continue;
            }
            _ => {}
        }
        current.push(character);
    }
    values.push(current.trim().to_string());
    values
}

#[cfg(test)]
mod tests {
    use super::*;

    fn grid(arguments: &[&str]) -> Result<Grid, Error> {
        Grid::parse(&arguments.iter().map(|a| a.to_string()).collect::<Vec<_>>())
    }

    #[test]
    fn values_split_at_top_level_commas_only() {
        assert_eq!(split_values("1, 2,3"), ["1", "2", "3"]);
        assert_eq!(split_values("[1,2],[3,4]"), ["[1,2]", "[3,4]"]);
        assert_eq!(split_values("\"a,b\",c"), ["\"a,b\"", "c"]);
        assert_eq!(split_values("{ q = 1.0, r = 2 }"), ["{ q = 1.0, r = 2 }"]);
    }

    #[test]
    fn points_cross_the_axes_first_slowest() {
        let grid = grid(&["load.tension_y=5,10", "geometry.lx=300,400,500"]).unwrap();
        let points = grid.points(&SceneRecipe::built_in()).unwrap();
        assert_eq!(points.len(), 6);
        assert_eq!(points[4].index, 4);
        assert_eq!(
            points[4].inputs,
            [
                ("load.tension_y".to_string(), "10".to_string()),
                ("geometry.lx".to_string(), "400".to_string())
            ]
        );
        assert_eq!(
            points[4].recipe.overrides,
            ["load.tension_y=10", "geometry.lx=400"]
        );
    }

    #[test]
    fn bad_grids_are_usage_errors_naming_the_argument() {
        for (arguments, expected) in [
            (vec!["load.tension_y"], "expected KEY=a,b,c"),
            (vec!["=1,2"], "dotted scene key"),
            (vec!["mesh.nx=1,,2"], "a value is empty"),
            (vec!["mesh.nx=1", "mesh.nx=2"], "given twice"),
        ] {
            let error = grid(&arguments).unwrap_err().to_string();
            assert!(error.contains(expected), "{arguments:?}: {error}");
            assert!(error.contains("--grid"), "{error}");
        }
        let huge: Vec<String> = (0..4)
            .map(|i| format!("k{i}.x={}", "1,".repeat(20) + "1"))
            .collect();
        assert!(Grid::parse(&huge).is_err());
    }
}
