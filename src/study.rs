//! What `wrinkle compare` and `wrinkle bench` share: the loads and amplitudes read off a path
//! at a crossing ([`value_at_crossing`], [`load_at_amplitude`], [`amplitude_at_load`]), relative
//! errors ([`relative_error`]), the number cells of their CSV files ([`number_cell`]), and the
//! check of their `--models` list before any work ([`check_model_list`]).

use crate::error::Error;
use crate::output::PathPoint;

/// Checks a `--models` list before any work: every entry names a registered model, none is
/// empty (`--models a,` or `a,,b`) and none repeats (each model writes one directory). The
/// error names the entry, counted from 1.
pub fn check_model_list(models: &[String]) -> Result<(), Error> {
    let known = wrinkle_models::names();
    for (index, model) in models.iter().enumerate() {
        let entry = format!("--models entry {} (`{model}`)", index + 1);
        if model.trim().is_empty() {
            return Err(Error::Usage(format!(
                "{entry} is empty (a trailing or doubled comma?): give model names separated by commas, e.g. --models {}",
                known.join(",")
            )));
        }
        if !known.contains(&model.as_str()) {
            return Err(Error::Usage(format!(
                "{entry}: unknown model (models: {})",
                known.join(", ")
            )));
        }
        if let Some(first) = models[..index].iter().position(|other| other == model) {
            return Err(Error::Usage(format!(
                "{entry} repeats entry {}: each model is run once",
                first + 1
            )));
        }
    }
    Ok(())
}

/// $`\lvert x - x_\text{ref}\rvert / \lvert x_\text{ref}\rvert`$; `None` when either is missing,
/// not finite, or the reference is zero.
pub fn relative_error(value: Option<f64>, reference: Option<f64>) -> Option<f64> {
    let (x, r) = (value?, reference?);
    let error = (x - r).abs() / r.abs();
    (x.is_finite() && r != 0.0 && error.is_finite()).then_some(error)
}

/// Where `x` first reaches `target` along `samples` (pairs $`(x, y)`$ in path order), the
/// value of $`y`$ there: the cubic (Lagrange) through the two samples on either side of the
/// crossing, skipping samples that repeat an abscissa (the end of one step is the start of the
/// next); linear between the two around the crossing when there are not four. The path's dense
/// output is a few points per step along a curved response, so linear interpolation alone adds
/// an error (about $`10^{-4}`$ in $`a/h`$ at $`1.1\lambda_c`$) larger than the solver's.
///
/// The cubic is kept only when it lies between the two values around the crossing (where a
/// response monotone between two samples must be): across a step much longer than its
/// neighbours — Riks' one step over the knee of the long strip, $`a/h`$ from 0.02 to 1.49 —
/// the cubic through such unevenly spaced samples overshoots (it gave $`\lambda(a/h = 1)`$ =
/// 27.9 where the bracket is 13.9–16.0), and the linear value is used instead.
pub fn value_at_crossing(samples: &[(f64, f64)], target: f64) -> Option<f64> {
    let i = samples
        .windows(2)
        .position(|pair| pair[0].0 < target && pair[1].0 >= target)?;
    let (a, b) = (samples[i], samples[i + 1]);
    let linear = a.1 + (target - a.0) / (b.0 - a.0) * (b.1 - a.1);
    let mut before = vec![a];
    for &sample in samples[..i].iter().rev() {
        if before.len() == 2 {
            break;
        }
        if sample.0 < before[before.len() - 1].0 {
            before.push(sample);
        }
    }
    let mut nodes: Vec<(f64, f64)> = before.into_iter().rev().collect();
    nodes.push(b);
    for &sample in &samples[i + 2..] {
        if nodes.len() == 4 {
            break;
        }
        if sample.0 > nodes[nodes.len() - 1].0 {
            nodes.push(sample);
        }
    }
    if nodes.len() < 4 {
        return Some(linear);
    }
    let cubic: f64 = nodes
        .iter()
        .enumerate()
        .map(|(j, &(xj, yj))| {
            let basis: f64 = nodes
                .iter()
                .enumerate()
                .filter(|&(k, _)| k != j)
                .map(|(_, &(xk, _))| (target - xk) / (xj - xk))
                .product();
            yj * basis
        })
        .sum();
    let (low, high) = (a.1.min(b.1), a.1.max(b.1));
    Some(if cubic.is_finite() && (low..=high).contains(&cubic) {
        cubic
    } else {
        linear
    })
}

/// Maximum physical $`a/h`$ where the path first reaches the load `load`
/// ([`value_at_crossing`]); `None` if the path stops before.
pub fn amplitude_at_load(points: &[PathPoint], load: f64) -> Option<f64> {
    let samples: Vec<(f64, f64)> = points
        .iter()
        .map(|p| (p.lambda, p.max_amplitude_over_h))
        .collect();
    value_at_crossing(&samples, load)
}

/// Load where the maximum physical $`a/h`$ first reaches `amplitude` ([`value_at_crossing`];
/// `None` if never.
pub fn load_at_amplitude(points: &[PathPoint], amplitude: f64) -> Option<f64> {
    let samples: Vec<(f64, f64)> = points
        .iter()
        .map(|p| (p.max_amplitude_over_h, p.lambda))
        .collect();
    value_at_crossing(&samples, amplitude)
}

/// A number of a CSV cell, to ten significant digits after the first; empty when absent.
pub fn number_cell(value: Option<f64>) -> String {
    value.map(|v| format!("{v:.10e}")).unwrap_or_default()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn point(lambda: f64, amplitude: f64) -> PathPoint {
        PathPoint {
            step: 0,
            interior: false,
            lambda,
            n_x: None,
            max_amplitude: amplitude,
            max_amplitude_over_h: amplitude,
            centre_amplitude_over_h: amplitude,
            residual: 0.0,
            elliptic: true,
            closed_form_amplitude_over_h: None,
        }
    }

    #[test]
    fn amplitude_is_interpolated_at_the_first_crossing() {
        let path = [point(0.0, 0.0), point(1.0, 0.5), point(2.0, 1.5)];
        assert_eq!(amplitude_at_load(&path, 1.5), Some(1.0));
        assert_eq!(amplitude_at_load(&path, 3.0), None);
        assert_eq!(load_at_amplitude(&path, 1.0), Some(1.5));
    }

    /// A cubic response is reproduced exactly, even with a repeated step end in the samples;
    /// linear interpolation of the same samples is off by about 0.03.
    #[test]
    fn cubic_interpolation_reproduces_a_cubic() {
        let f = |x: f64| 0.2 + x - 0.7 * x * x + 0.3 * x * x * x;
        let xs = [0.0, 0.5, 1.0, 1.0, 1.6, 2.0, 2.5];
        let samples: Vec<(f64, f64)> = xs.iter().map(|&x| (x, f(x))).collect();
        let value = value_at_crossing(&samples, 1.3).unwrap();
        assert!((value - f(1.3)).abs() < 1e-12, "{value} vs {}", f(1.3));
        let linear = f(1.0) + 0.5 * (f(1.6) - f(1.0));
        assert!((linear - f(1.3)).abs() > 1e-2);
    }

    /// Riks' path of the long strip at 16 × 8 steps over the knee in one step (a/h from 0.02
    /// to 1.49): the cubic through the four samples around a/h = 1 leaves that step's load
    /// bracket, and the value falls back to the linear one inside it.
    #[test]
    fn a_cubic_that_overshoots_a_long_step_falls_back_to_linear() {
        let path = [
            point(9.421, 0.0005),
            point(12.396, 0.0016),
            point(13.883, 0.0205),
            point(15.987, 1.4943),
            point(17.474, 2.0442),
            point(19.192, 2.5930),
        ];
        let load = load_at_amplitude(&path, 1.0).unwrap();
        let linear = 13.883 + (1.0 - 0.0205) / (1.4943 - 0.0205) * (15.987 - 13.883);
        assert!((load - linear).abs() < 1e-12, "{load} vs {linear}");
        // Where the cubic stays inside its bracket it is kept (it differs from the linear value).
        let amplitude = amplitude_at_load(&path, 17.0).unwrap();
        let linear = 1.4943 + (17.0 - 15.987) / (17.474 - 15.987) * (2.0442 - 1.4943);
        assert!((1.4943..=2.0442).contains(&amplitude), "{amplitude}");
        assert!((amplitude - linear).abs() > 1e-3, "{amplitude} vs {linear}");
    }

    #[test]
    fn relative_errors_are_finite_or_absent() {
        assert_eq!(
            relative_error(Some(1.1), Some(1.0)).map(|e| (e * 1e6).round()),
            Some(1e5)
        );
        assert_eq!(relative_error(Some(1.0), Some(0.0)), None);
        assert_eq!(relative_error(None, Some(1.0)), None);
        assert_eq!(relative_error(Some(f64::NAN), Some(1.0)), None);
    }
}
