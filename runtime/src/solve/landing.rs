//! Landing a path on its target: the point where a measure of the path (an amplitude the
//! application defines, or the load) reaches a given value, instead of the first computed point
//! past it.
//!
//! * [`land`]: equilibrium points on spheres about the last point below the target
//!   ([`correct_on_arc`]) through the chord between the two points that bracket it, the
//!   bracket narrowed by regula falsi (Illinois) until the measure lies within the target's
//!   window ([`LandingTarget`]). Any path method's last two points will do: Riks' step ends,
//!   the ANM's dense output.
//! * [`land_on_step`]: the ANM's landing on an amplitude inside the step it stopped in, on the
//!   step's own approximant (regula falsi on the path parameter, one residual check): no
//!   correction, hence no factorisation, unless that fails and [`land`] takes over.
//! * [`parameter_at_load`]: the ANM's landing on `max_load` inside a step, where the series
//!   is evaluated at any path parameter: bisection for $`\lambda(a) = \lambda_\text{max}`$.

use super::anm::StepTail;
use super::arc_length::{ArcCorrection, ArcCorrectorOptions, correct_on_arc};
use super::linearization::Linearization;
use super::path::PathState;
use crate::model::EnergyModel;

/// Relative distance above an amplitude target within which a point is taken as landed on it.
pub const AMPLITUDE_LANDING_TOLERANCE: f64 = 1e-3;

/// The same for a load target (`max_load`), which the ANM meets exactly.
pub const LOAD_LANDING_TOLERANCE: f64 = 1e-9;

/// Arc-length corrections tried to land on a target.
pub const MAX_LANDING_CORRECTIONS: usize = 8;

/// Bisection steps of [`parameter_at_load`].
const LOAD_BISECTION_STEPS: usize = 60;

/// What a path's last point is moved back onto.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum LandingTarget {
    /// An amplitude, in the application's measure (e.g. $`\max|w|/h`$).
    Amplitude(f64),
    /// A load parameter value (Riks stopped by `max_load`).
    Load(f64),
}

impl LandingTarget {
    /// The target value.
    pub fn value(self) -> f64 {
        match self {
            LandingTarget::Amplitude(value) | LandingTarget::Load(value) => value,
        }
    }

    /// The relative width of the accepted window $`[t, t(1 + \text{tolerance})]`$ above the
    /// target $`t`$: [`AMPLITUDE_LANDING_TOLERANCE`] or [`LOAD_LANDING_TOLERANCE`].
    pub fn tolerance(self) -> f64 {
        match self {
            LandingTarget::Amplitude(_) => AMPLITUDE_LANDING_TOLERANCE,
            LandingTarget::Load(_) => LOAD_LANDING_TOLERANCE,
        }
    }
}

/// Moves a path's last point `above`, which overshot `target` in `measure`, back onto it: the
/// landed equilibrium point, or `None` when `below` (the point before) is not below the
/// target, `above` is within the window already, or no correction lands within
/// [`MAX_LANDING_CORRECTIONS`].
///
/// Each correction takes the point of the chord between the bracketing points where the
/// measure, interpolated linearly, meets the middle of the window, and corrects it onto the
/// path on the sphere about `below` through it ([`correct_on_arc`] with `corrector`); the
/// corrected point replaces the bracket's end on its side, and an end kept twice has its value
/// halved (Illinois). The work is counted in `linearization`.
pub fn land<M: EnergyModel>(
    linearization: &mut Linearization<'_, M>,
    below: &PathState,
    above: &PathState,
    target: LandingTarget,
    measure: &dyn Fn(&PathState) -> f64,
    corrector: &ArcCorrectorOptions,
) -> Option<ArcCorrection> {
    let value = target.value();
    let window = target.tolerance() * value.abs();
    let overshoot = measure(above);
    let undershoot = measure(below);
    if !(overshoot > value + window && undershoot < value) {
        return None;
    }
    // Aim at the middle of the accepted window [target, target + window].
    let aim = value + 0.5 * window;
    let mut bracket = Bracket {
        low: (undershoot - aim, below.clone()),
        high: (overshoot - aim, above.clone()),
        side: 0,
    };
    for _ in 0..MAX_LANDING_CORRECTIONS {
        let predicted = bracket.chord_point();
        let corrected = correct_on_arc(linearization, below, &predicted, corrector).ok()?;
        let miss = measure(&corrected.state) - aim;
        if miss.abs() <= 0.5 * window {
            return Some(corrected);
        }
        bracket.narrow(miss, corrected.state);
    }
    None
}

/// Regula falsi steps of [`parameter_on_step`].
const MAX_STEP_LANDING_ITERATIONS: usize = 40;

/// Lands on an amplitude `target` inside the ANM step the path stopped in: the point of the
/// step's own approximant ([`StepTail`]) between the last two points reported where `measure`
/// meets the middle of the target's window ([`parameter_on_step`]) — no correction, no
/// factorisation: the step evaluates it as it evaluated its points. `None` (then [`land`]
/// corrects a chord) when the two points do not bracket the aim on the approximant, no
/// parameter lands within [`MAX_STEP_LANDING_ITERATIONS`], or the point's relative residual
/// (counted in `linearization`) is above `tolerance`.
pub fn land_on_step<M: EnergyModel>(
    linearization: &mut Linearization<'_, M>,
    tail: &StepTail,
    target: LandingTarget,
    measure: &dyn Fn(&PathState) -> f64,
    tolerance: f64,
) -> Option<ArcCorrection> {
    let LandingTarget::Amplitude(value) = target else {
        return None;
    };
    let window = target.tolerance() * value.abs();
    let evaluate = |a: f64| tail.evaluate(a);
    let state = parameter_on_step(
        &evaluate,
        measure,
        tail.bracket,
        value + 0.5 * window,
        0.5 * window,
    )?;
    let relative = linearization.relative_residual(&state.displacement, state.load);
    (relative <= tolerance).then_some(ArcCorrection {
        state,
        iterations: 0,
        relative_residual: relative,
    })
}

/// The point `evaluate(a)` of a step's approximant, $`a`$ between the path parameters
/// `(low, high)`, where `measure` is within `half_window` of `aim`: regula falsi (Illinois) on
/// $`a`$, at most [`MAX_STEP_LANDING_ITERATIONS`] evaluations. `None` when the ends do not
/// bracket the aim (measure below it at `low`, above it at `high`), a measure is not finite, or
/// no parameter lands. The measure may have kinks (a maximum over nodes whose node changes):
/// the bracket still narrows onto the crossing, where an interpolation between sampled points
/// would not see the kink.
pub fn parameter_on_step(
    evaluate: &dyn Fn(f64) -> PathState,
    measure: &dyn Fn(&PathState) -> f64,
    (low, high): (f64, f64),
    aim: f64,
    half_window: f64,
) -> Option<PathState> {
    let mut bracket = Bracket {
        low: (measure(&evaluate(low)) - aim, low),
        high: (measure(&evaluate(high)) - aim, high),
        side: 0,
    };
    if !(bracket.low.0 < 0.0 && bracket.high.0 > 0.0) {
        return None;
    }
    for _ in 0..MAX_STEP_LANDING_ITERATIONS {
        let a = bracket.chord_parameter();
        let state = evaluate(a);
        let miss = measure(&state) - aim;
        if !miss.is_finite() {
            return None;
        }
        if miss.abs() <= half_window {
            return Some(state);
        }
        bracket.narrow(miss, a);
    }
    None
}

/// Two points about the aim, each with its measure minus the aim (negative below, positive
/// above): path states ([`land`]) or path parameters ([`land_on_step`]).
struct Bracket<T> {
    low: (f64, T),
    high: (f64, T),
    /// The side replaced last: -1 low, +1 high, 0 none yet.
    side: i8,
}

impl<T> Bracket<T> {
    /// The fraction of the way from the low end to the high one where the linear
    /// interpolation of the measure meets the aim.
    fn fraction(&self) -> f64 {
        self.low.0 / (self.low.0 - self.high.0)
    }

    /// Replaces the end on the side of `miss` by `point`; halves the other end's value when
    /// the same side is replaced twice in a row (Illinois).
    fn narrow(&mut self, miss: f64, point: T) {
        if miss > 0.0 {
            self.high = (miss, point);
            if self.side == 1 {
                self.low.0 *= 0.5;
            }
            self.side = 1;
        } else {
            self.low = (miss, point);
            if self.side == -1 {
                self.high.0 *= 0.5;
            }
            self.side = -1;
        }
    }
}

impl Bracket<PathState> {
    /// The point of the chord where the linear interpolation of the measure meets the aim.
    fn chord_point(&self) -> PathState {
        let (low, high) = (&self.low.1, &self.high.1);
        let fraction = self.fraction();
        PathState {
            displacement: low
                .displacement
                .iter()
                .zip(&high.displacement)
                .map(|(a, b)| a + fraction * (b - a))
                .collect(),
            load: low.load + fraction * (high.load - low.load),
        }
    }
}

impl Bracket<f64> {
    /// The path parameter where the linear interpolation of the measure meets the aim.
    fn chord_parameter(&self) -> f64 {
        let (low, high) = (self.low.1, self.high.1);
        low + self.fraction() * (high - low)
    }
}

/// The path parameter in $`(0, a]`$ where `load_at` reaches `max_load`, by bisection from
/// $`[0, a]`$ with `load_at(a)` $`\ge`$ `max_load` (the upper end of the last bracket, so that
/// the load there is at least `max_load`).
pub fn parameter_at_load(load_at: impl Fn(f64) -> f64, a: f64, max_load: f64) -> f64 {
    let (mut low, mut high) = (0.0, a);
    for _ in 0..LOAD_BISECTION_STEPS {
        let middle = 0.5 * (low + high);
        if load_at(middle) < max_load {
            low = middle
        } else {
            high = middle
        }
    }
    high
}

#[cfg(test)]
mod tests {
    use super::*;

    fn point(load: f64) -> PathState {
        PathState {
            displacement: vec![2.0 * load],
            load,
        }
    }

    /// The bisection ends on the side at or above the load, to the last bit of the bracket.
    #[test]
    fn parameter_at_load_lands_at_or_above_the_load() {
        let a = parameter_at_load(|a| a * a, 4.0, 2.0);
        assert!(a * a >= 2.0);
        assert!((a - 2f64.sqrt()).abs() <= 1e-15);
    }

    /// The chord point interpolates the measure linearly; an end kept twice has its value
    /// halved (Illinois), which moves the next chord point towards it.
    #[test]
    fn bracket_interpolates_and_halves_a_stale_end() {
        let mut bracket = Bracket {
            low: (-1.0, point(0.0)),
            high: (3.0, point(4.0)),
            side: 0,
        };
        let chord = bracket.chord_point();
        assert_eq!((chord.load, chord.displacement[0]), (1.0, 2.0));
        bracket.narrow(1.0, point(2.0));
        assert_eq!((bracket.low.0, bracket.high.0), (-1.0, 1.0));
        bracket.narrow(0.5, point(1.5));
        assert_eq!((bracket.low.0, bracket.high.0), (-0.5, 0.5));
        assert_eq!(bracket.chord_point().load, 0.75);
    }
}
