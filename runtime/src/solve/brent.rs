//! Brent's derivative-free scalar minimiser: golden-section search safeguarding successive
//! parabolic interpolation (R. P. Brent, *Algorithms for Minimization without Derivatives*, 1973,
//! procedure `localmin`).

/// Result of [`minimize_scalar`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ScalarMinimum {
    /// Approximate minimiser $`x^\ast`$ (the best point evaluated).
    pub argument: f64,
    /// $`f(x^\ast)`$.
    pub value: f64,
    /// Number of evaluations of $`f`$.
    pub evaluations: usize,
    /// Whether the bracket shrank below the tolerance (otherwise the evaluation budget ran out,
    /// or the bounds were not finite).
    pub converged: bool,
}

/// $`(3 - \sqrt 5)/2`$, the golden-section fraction.
const GOLDEN: f64 = 0.381_966_011_250_105_1;

/// Minimises $`f`$ on $`[a, b]`$ with Brent's method (golden section + parabolic interpolation).
///
/// Stops when the bracket around the best point is below `x_tolerance` (absolute; a relative
/// floor of $`2\sqrt{\epsilon}|x|`$ prevents asking for more than the floating-point resolution)
/// or after `max_evaluations` evaluations (`converged = false`). A failing evaluation aborts and
/// returns its error. NaN values of $`f`$ are treated as $`+\infty`$. The bounds may be given in
/// either order; non-finite bounds return `converged = false` without evaluating $`f`$.
pub fn minimize_scalar<E>(
    mut f: impl FnMut(f64) -> Result<f64, E>,
    a: f64,
    b: f64,
    x_tolerance: f64,
    max_evaluations: usize,
) -> Result<ScalarMinimum, E> {
    if !(a.is_finite() && b.is_finite()) || max_evaluations == 0 {
        return Ok(ScalarMinimum {
            argument: 0.5 * (a + b),
            value: f64::NAN,
            evaluations: 0,
            converged: false,
        });
    }
    let mut evaluate = |x: f64| -> Result<f64, E> {
        let value = f(x)?;
        Ok(if value.is_nan() { f64::INFINITY } else { value })
    };
    let (mut lower, mut upper) = if a <= b { (a, b) } else { (b, a) };
    let tolerance = x_tolerance.abs();
    let relative = 2.0 * f64::EPSILON.sqrt();
    // x: best point; w: second best; v: previous value of w.
    let mut x = lower + GOLDEN * (upper - lower);
    let mut w = x;
    let mut v = x;
    let mut fx = evaluate(x)?;
    let mut fw = fx;
    let mut fv = fx;
    let mut evaluations = 1;
    // d: last step; e: step before last.
    let mut d: f64 = 0.0;
    let mut e: f64 = 0.0;
    loop {
        let middle = 0.5 * (lower + upper);
        let tolerance1 = relative * x.abs() + tolerance / 2.0;
        let tolerance2 = 2.0 * tolerance1;
        if (x - middle).abs() <= tolerance2 - 0.5 * (upper - lower) {
            return Ok(ScalarMinimum {
                argument: x,
                value: fx,
                evaluations,
                converged: true,
            });
        }
        if evaluations >= max_evaluations {
            return Ok(ScalarMinimum {
                argument: x,
                value: fx,
                evaluations,
                converged: false,
            });
        }
        let mut golden_step = true;
        if e.abs() > tolerance1 {
            // Parabola through (v, fv), (w, fw), (x, fx).
            let r = (x - w) * (fx - fv);
            let mut q = (x - v) * (fx - fw);
            let mut p = (x - v) * q - (x - w) * r;
            q = 2.0 * (q - r);
            if q > 0.0 {
                p = -p;
            }
            q = q.abs();
            let previous = e;
            e = d;
            if p.abs() < (0.5 * q * previous).abs() && p > q * (lower - x) && p < q * (upper - x) {
                d = p / q;
                let u = x + d;
                if u - lower < tolerance2 || upper - u < tolerance2 {
                    d = if x < middle { tolerance1 } else { -tolerance1 };
                }
                golden_step = false;
            }
        }
        if golden_step {
            e = if x < middle { upper - x } else { lower - x };
            d = GOLDEN * e;
        }
        let u = if d.abs() >= tolerance1 {
            x + d
        } else if d > 0.0 {
            x + tolerance1
        } else {
            x - tolerance1
        };
        let fu = evaluate(u)?;
        evaluations += 1;
        if fu <= fx {
            if u < x {
                upper = x;
            } else {
                lower = x;
            }
            v = w;
            fv = fw;
            w = x;
            fw = fx;
            x = u;
            fx = fu;
        } else {
            if u < x {
                lower = u;
            } else {
                upper = u;
            }
            if fu <= fw || w == x {
                v = w;
                fv = fw;
                w = u;
                fw = fu;
            } else if fu <= fv || v == x || v == w {
                v = u;
                fv = fu;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn quadratic_minimum_found_to_tolerance() {
        let result = minimize_scalar(
            |x| Ok::<_, ()>((x - 2.0) * (x - 2.0) + 1.0),
            0.0,
            5.0,
            1e-10,
            200,
        )
        .unwrap();
        assert!(result.converged);
        assert!((result.argument - 2.0).abs() < 1e-9, "{result:?}");
        assert!((result.value - 1.0).abs() < 1e-15);
        // Parabolic steps make a quadratic converge in a handful of evaluations.
        assert!(result.evaluations < 20, "{result:?}");
    }

    #[test]
    fn cosine_minimum_is_pi() {
        let result = minimize_scalar(|x: f64| Ok::<_, ()>(x.cos()), 2.0, 4.0, 1e-12, 200).unwrap();
        assert!(result.converged);
        // cos is flat at π: |x − π| ≈ √(2 ε) from values alone; the bracket gives ≤ 1e-8 here.
        assert!(
            (result.argument - std::f64::consts::PI).abs() < 1e-7,
            "{result:?}"
        );
        assert!((result.value + 1.0).abs() < 1e-15);
    }

    #[test]
    fn reversed_bounds_and_boundary_minimum() {
        // Minimum of x on [1, 3] (given reversed) is at the boundary 1.
        let result = minimize_scalar(Ok::<_, ()>, 3.0, 1.0, 1e-8, 200).unwrap();
        assert!(result.converged);
        assert!((result.argument - 1.0).abs() < 1e-7, "{result:?}");
    }

    #[test]
    fn failing_evaluation_is_propagated() {
        let mut calls = 0;
        let result = minimize_scalar(
            |x| {
                calls += 1;
                if calls == 4 {
                    Err(format!("model failed at x = {x}"))
                } else {
                    Ok((x - 1.0) * (x - 1.0))
                }
            },
            0.0,
            3.0,
            1e-10,
            100,
        );
        assert!(matches!(result, Err(message) if message.starts_with("model failed")));
        assert_eq!(calls, 4);
    }

    #[test]
    fn evaluation_budget_reports_non_convergence() {
        let result =
            minimize_scalar(|x: f64| Ok::<_, ()>((x - 0.3).abs()), 0.0, 1.0, 1e-14, 6).unwrap();
        assert!(!result.converged);
        assert_eq!(result.evaluations, 6);
        let invalid = minimize_scalar(Ok::<_, ()>, f64::NAN, 1.0, 1e-8, 10).unwrap();
        assert!(!invalid.converged);
        assert_eq!(invalid.evaluations, 0);
    }
}
