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
    let (lower, upper) = if a <= b { (a, b) } else { (b, a) };
    let tolerance = x_tolerance.abs();
    let relative = 2.0 * f64::EPSILON.sqrt();
    let x = lower + GOLDEN * (upper - lower);
    let mut state = BrentState::new(lower, upper, x, evaluate(x)?);
    let mut evaluations = 1;
    loop {
        let middle = 0.5 * (state.lower + state.upper);
        let tolerance1 = relative * state.x.abs() + tolerance / 2.0;
        let tolerance2 = 2.0 * tolerance1;
        let converged = (state.x - middle).abs() <= tolerance2 - 0.5 * (state.upper - state.lower);
        if converged || evaluations >= max_evaluations {
            return Ok(ScalarMinimum {
                argument: state.x,
                value: state.fx,
                evaluations,
                converged,
            });
        }
        let u = state.next_point(middle, tolerance1, tolerance2);
        let fu = evaluate(u)?;
        evaluations += 1;
        state.update(u, fu);
    }
}

/// The bracket and the three best points of [`minimize_scalar`] (Brent's notation).
struct BrentState {
    lower: f64,
    upper: f64,
    /// Best point so far.
    x: f64,
    /// Second best.
    w: f64,
    /// Previous value of `w`.
    v: f64,
    fx: f64,
    fw: f64,
    fv: f64,
    /// Last step.
    d: f64,
    /// Step before last.
    e: f64,
}

impl BrentState {
    fn new(lower: f64, upper: f64, x: f64, fx: f64) -> Self {
        BrentState {
            lower,
            upper,
            x,
            w: x,
            v: x,
            fx,
            fw: fx,
            fv: fx,
            d: 0.0,
            e: 0.0,
        }
    }

    /// The next point to evaluate: the parabola's minimum through $`v, w, x`$ when it is
    /// acceptable (inside the bracket, a step under half the one before last), else a golden
    /// section step into the larger part of the bracket; never closer than `tolerance1` to
    /// $`x`$.
    fn next_point(&mut self, middle: f64, tolerance1: f64, tolerance2: f64) -> f64 {
        let (x, lower, upper) = (self.x, self.lower, self.upper);
        let mut golden_step = true;
        if self.e.abs() > tolerance1 {
            // Parabola through (v, fv), (w, fw), (x, fx).
            let r = (x - self.w) * (self.fx - self.fv);
            let mut q = (x - self.v) * (self.fx - self.fw);
            let mut p = (x - self.v) * q - (x - self.w) * r;
            q = 2.0 * (q - r);
            if q > 0.0 {
                p = -p;
            }
            q = q.abs();
            let previous = self.e;
            self.e = self.d;
            if p.abs() < (0.5 * q * previous).abs() && p > q * (lower - x) && p < q * (upper - x) {
                self.d = p / q;
                let u = x + self.d;
                if u - lower < tolerance2 || upper - u < tolerance2 {
                    self.d = if x < middle { tolerance1 } else { -tolerance1 };
                }
                golden_step = false;
            }
        }
        if golden_step {
            self.e = if x < middle { upper - x } else { lower - x };
            self.d = GOLDEN * self.e;
        }
        if self.d.abs() >= tolerance1 {
            x + self.d
        } else if self.d > 0.0 {
            x + tolerance1
        } else {
            x - tolerance1
        }
    }

    /// Narrows the bracket with $`f(u)`$ and updates the best points.
    fn update(&mut self, u: f64, fu: f64) {
        let x = self.x;
        if fu <= self.fx {
            if u < x {
                self.upper = x;
            } else {
                self.lower = x;
            }
            self.v = self.w;
            self.fv = self.fw;
            self.w = x;
            self.fw = self.fx;
            self.x = u;
            self.fx = fu;
        } else {
            if u < x {
                self.lower = u;
            } else {
                self.upper = u;
            }
            if fu <= self.fw || self.w == x {
                self.v = self.w;
                self.fv = self.fw;
                self.w = u;
                self.fw = fu;
            } else if fu <= self.fv || self.v == x || self.v == self.w {
                self.v = u;
                self.fv = fu;
            }
        }
    }
}

/// Downhill moves [`local_parabolic_minimum`] makes to bracket the minimum before giving up.
const MAX_BRACKETING_MOVES: usize = 6;

/// Minimises $`f`$ near `centre` by successive parabolic interpolation, for a minimum known to
/// within a few `step` of `centre` (e.g. from a coarser discretisation): $`f`$ is evaluated at
/// `centre` and `centre` $`\pm`$ `step`, the bracket is moved downhill (doubling the step) until
/// its middle point is the lowest, then the vertex of the parabola through the bracket is
/// evaluated and the bracket tightened around the best point, until the next vertex lies within
/// `x_tolerance` of the best point evaluated (which is returned).
///
/// On a smooth minimum this takes four or five evaluations where Brent's method, which must
/// shrink the bracket itself below the tolerance, takes eight or nine. Returns `Ok(None)` when
/// the minimum could not be bracketed within `MAX_BRACKETING_MOVES` moves, when an
/// evaluation is not finite (the caller then falls back to a global search), or when the
/// inputs are not finite; `converged = false` when the budget `max_evaluations` ran out after
/// bracketing. A failing evaluation aborts and returns its error.
pub fn local_parabolic_minimum<E>(
    mut f: impl FnMut(f64) -> Result<f64, E>,
    centre: f64,
    step: f64,
    x_tolerance: f64,
    max_evaluations: usize,
) -> Result<Option<ScalarMinimum>, E> {
    if !(centre.is_finite() && step.is_finite() && step > 0.0) || max_evaluations < 4 {
        return Ok(None);
    }
    let mut evaluations = 0;
    let mut evaluate = |x: f64, evaluations: &mut usize| -> Result<(f64, f64), E> {
        *evaluations += 1;
        let value = f(x)?;
        Ok((x, if value.is_nan() { f64::INFINITY } else { value }))
    };
    let mut b = evaluate(centre, &mut evaluations)?;
    let mut a = evaluate(centre - step, &mut evaluations)?;
    let mut c = evaluate(centre + step, &mut evaluations)?;
    let mut moves = 0;
    loop {
        if ![a.1, b.1, c.1].iter().all(|v| v.is_finite()) {
            return Ok(None);
        }
        if b.1 <= a.1 && b.1 <= c.1 {
            break;
        }
        if moves >= MAX_BRACKETING_MOVES || evaluations >= max_evaluations {
            return Ok(None);
        }
        moves += 1;
        if a.1 < c.1 {
            let next = evaluate(a.0 - 2.0 * (b.0 - a.0), &mut evaluations)?;
            c = b;
            b = a;
            a = next;
        } else {
            let next = evaluate(c.0 + 2.0 * (c.0 - b.0), &mut evaluations)?;
            a = b;
            b = c;
            c = next;
        }
    }
    Ok(Some(parabolic_refinement(
        f,
        [a, b, c],
        evaluations,
        x_tolerance,
        max_evaluations,
    )?))
}

/// Successive parabolic interpolation from a bracket `[a, b, c]` of `(x, f(x))` pairs with
/// $`a_x < b_x < c_x`$ and $`f(b) \le f(a), f(c)`$, all finite (e.g. three points of a scan):
/// the vertex of the parabola through the bracket is evaluated and the bracket tightened around
/// the best point, until the next vertex lies within `x_tolerance` of the best point evaluated
/// (`converged`) or `max_evaluations` (counting the `spent` ones) are used. Returns the best
/// point; an evaluation that is not finite inside the bracket stops the refinement there
/// (`converged = false`).
pub fn parabolic_refinement<E>(
    mut f: impl FnMut(f64) -> Result<f64, E>,
    [mut a, mut b, mut c]: [(f64, f64); 3],
    spent: usize,
    x_tolerance: f64,
    max_evaluations: usize,
) -> Result<ScalarMinimum, E> {
    let mut evaluations = spent;
    let tolerance = x_tolerance.abs().max(2.0 * f64::EPSILON.sqrt() * b.0.abs());
    loop {
        // Vertex of the parabola through a, b, c (inside [a, c] since f(b) is the lowest).
        let (p, q) = (
            (b.0 - a.0).powi(2) * (b.1 - c.1) - (b.0 - c.0).powi(2) * (b.1 - a.1),
            (b.0 - a.0) * (b.1 - c.1) - (b.0 - c.0) * (b.1 - a.1),
        );
        let vertex = if q != 0.0 { b.0 - 0.5 * p / q } else { b.0 };
        let vertex = if vertex.is_finite() {
            vertex.clamp(a.0, c.0)
        } else {
            b.0
        };
        let converged = (vertex - b.0).abs() <= tolerance;
        if converged || evaluations >= max_evaluations {
            return Ok(ScalarMinimum {
                argument: b.0,
                value: b.1,
                evaluations,
                converged,
            });
        }
        evaluations += 1;
        let value = f(vertex)?;
        if !value.is_finite() {
            // Rejected inside the bracket: no parabola through it; the best point stands.
            return Ok(ScalarMinimum {
                argument: b.0,
                value: b.1,
                evaluations,
                converged: false,
            });
        }
        let u = (vertex, value);
        if u.1 <= b.1 {
            if u.0 < b.0 {
                c = b;
            } else {
                a = b;
            }
            b = u;
        } else if u.0 < b.0 {
            a = u;
        } else {
            c = u;
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
    fn local_parabolic_finds_a_smooth_minimum_in_few_evaluations() {
        // λ(Q) = Q² + 1/Q² in x = ln Q: minimum at x = 0 (cosh shape), started 1.5 % off.
        let f = |x: f64| Ok::<_, ()>((2.0 * x).exp() + (-2.0 * x).exp());
        let result = local_parabolic_minimum(f, 0.015, 0.02, 1e-3, 20)
            .unwrap()
            .unwrap();
        assert!(result.converged);
        assert!(result.argument.abs() < 1e-3, "{result:?}");
        assert!(result.evaluations <= 5, "{result:?}");
        // A minimum 10 steps away is bracketed by doubling moves, then refined.
        let g = |x: f64| Ok::<_, ()>((x - 0.3).powi(2) + 0.1 * (x - 0.3).powi(3));
        let far = local_parabolic_minimum(g, 0.0, 0.03, 1e-6, 40)
            .unwrap()
            .unwrap();
        assert!(far.converged);
        assert!((far.argument - 0.3).abs() < 1e-5, "{far:?}");
    }

    #[test]
    fn local_parabolic_gives_up_on_an_unbracketed_or_rejected_minimum() {
        // Monotone: no minimum within six doubling moves.
        assert!(
            local_parabolic_minimum(|x: f64| Ok::<_, ()>(x), 0.0, 0.01, 1e-6, 50)
                .unwrap()
                .is_none()
        );
        // A rejected (infinite) evaluation sends the caller back to its global search.
        let rejected = |x: f64| Ok::<_, ()>(if x < 0.0 { f64::INFINITY } else { x * x });
        assert!(
            local_parabolic_minimum(rejected, 0.0, 0.1, 1e-6, 50)
                .unwrap()
                .is_none()
        );
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
