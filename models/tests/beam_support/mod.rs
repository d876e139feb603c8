//! Beams on a Winkler foundation for the beam tests: problems of the three beam models under an
//! axial end force $`\lambda`$, closed forms, Newton continuation in the load, and amplitudes.
//!
//! Units are scaled so that $`EI = c = 1`$: $`Q = (c/EI)^{1/4} = 1`$, wavelength $`2\pi`$,
//! $`\lambda_c = 2\sqrt{EI\,c} = 2`$. The beam's thickness $`h`$ enters through
//! $`ES = 12\,EI/h^2`$ (a rectangular section), $`h = 0.1`$.

#![allow(dead_code)]

use std::f64::consts::PI;
use std::sync::Arc;

use wrinkle_models::{BeamComplexEnvelope, BeamEnvelope, BeamFull};
use wrinkle_runtime::EnergyModel;
use wrinkle_runtime::fem::{
    DirichletCondition, ElementKind, Loads, Mesh, NodalComponent, PointLoad,
};
use wrinkle_runtime::linear::SparseFactorization;
use wrinkle_runtime::problem::Problem;
use wrinkle_runtime::solve::buckling::{LinearBuckling, LinearBucklingOptions, linear_buckling};
use wrinkle_runtime::solve::newton::{NewtonOptions, newton};

/// Bending stiffness $`EI`$.
pub const EI: f64 = 1.0;
/// Foundation stiffness $`c`$.
pub const C: f64 = 1.0;
/// Thickness $`h`$ of the beam: $`ES = 12 EI/h^2`$.
pub const THICKNESS: f64 = 0.1;
/// Axial stiffness $`ES`$.
pub const ES: f64 = 12.0 * EI / (THICKNESS * THICKNESS);

/// $`Q = (c/EI)^{1/4}`$ (3).
pub fn critical_wavenumber() -> f64 {
    (C / EI).powf(0.25)
}

/// $`\lambda_c = 2\sqrt{EI\,c}`$ (3).
pub fn critical_load() -> f64 {
    2.0 * (EI * C).sqrt()
}

/// Length of `wavelengths` waves of the critical wavenumber.
pub fn length_of(wavelengths: f64) -> f64 {
    wavelengths * 2.0 * PI / critical_wavenumber()
}

/// How the deflection is held at both ends.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Ends {
    /// $`v = 0`$ (the moment free).
    SimplySupported,
    /// $`v = v' = 0`$.
    Clamped,
}

/// The simply supported full beam's critical load, $`\min_n EI k_n^2 + c/k_n^2`$,
/// $`k_n = n\pi/L`$, and its $`k_n`$.
pub fn full_simply_supported_closed_form(length: f64) -> (f64, f64) {
    (1..100_000)
        .map(|n| {
            let k = n as f64 * PI / length;
            (EI * k * k + C / (k * k), k)
        })
        .fold(
            (f64::INFINITY, 0.0),
            |best, x| if x.0 < best.0 { x } else { best },
        )
}

/// The real envelope's critical load on $`[0, L]`$ with $`v_1 = 0`$ at both ends:
/// $`v_1 = \sin(kX)`$, $`k = \pi/L`$, in the linearised (14):
/// $`\lambda = (6EIQ^2k^2 + EIQ^4 + c)/(Q^2 + k^2)`$.
pub fn envelope_closed_form(length: f64, wavenumber: f64) -> f64 {
    let (q2, k2) = (wavenumber * wavenumber, (PI / length).powi(2));
    (6.0 * EI * q2 * k2 + EI * q2 * q2 + C) / (q2 + k2)
}

/// The complex envelope's critical load on $`[0, L]`$ with $`v_1 = 0`$ at both ends. A plane
/// wave $`e^{imX}`$ of the linearised energy has $`\alpha m^2 + \beta m + \gamma = 0`$ with
/// $`\alpha = 6EIQ^2 - \lambda`$, $`\beta = 4EIQ^3 - 2\lambda Q`$,
/// $`\gamma = EIQ^4 + c - \lambda Q^2`$; $`v_1 = e^{im_1X} - e^{im_2X}`$ vanishes at both ends
/// when $`m_1 - m_2 = 2\pi/L`$, i.e. $`\beta^2 - 4\alpha\gamma = \alpha^2(2\pi/L)^2`$: the root
/// above $`\lambda = EIQ^2 + c/Q^2`$, by bisection.
pub fn complex_envelope_closed_form(length: f64, wavenumber: f64) -> f64 {
    let q = wavenumber;
    let gap = |lambda: f64| {
        let alpha = 6.0 * EI * q * q - lambda;
        let beta = 4.0 * EI * q.powi(3) - 2.0 * lambda * q;
        let gamma = EI * q.powi(4) + C - lambda * q * q;
        beta * beta - 4.0 * alpha * gamma - alpha * alpha * (2.0 * PI / length).powi(2)
    };
    let (mut low, mut high) = (EI * q * q + C / (q * q), 3.0 * EI * q * q);
    assert!(gap(low) < 0.0 && gap(high) > 0.0, "bracket");
    for _ in 0..200 {
        let middle = 0.5 * (low + high);
        if gap(middle) < 0.0 {
            low = middle;
        } else {
            high = middle;
        }
    }
    0.5 * (low + high)
}

/// Axial force $`\lambda`$ (compressive) on `u` at the right end.
fn end_force() -> Loads {
    Loads {
        point_loads: vec![PointLoad {
            point: "right".into(),
            field: 0,
            component: NodalComponent::Value,
            value: -1.0,
            proportional: true,
        }],
        ..Loads::default()
    }
}

/// `u = 0` at the left end, and every transverse field held at both ends as `ends` says.
fn conditions(kind: ElementKind, transverse: &[usize], ends: Ends) -> Vec<DirichletCondition> {
    let mut conditions = vec![DirichletCondition::fixed("left", 0)];
    for &field in transverse {
        for end in ["left", "right"] {
            match ends {
                Ends::SimplySupported => conditions.push(DirichletCondition::fixed(end, field)),
                Ends::Clamped => conditions.extend(DirichletCondition::clamped(end, field, kind)),
            }
        }
    }
    conditions
}

/// `beam-full` on `elements` Hermite2 elements of $`[0, L]`$.
pub fn full(length: f64, elements: usize, cubic: f64, ends: Ends) -> Problem<BeamFull> {
    let kind = ElementKind::Hermite2;
    let mesh = Arc::new(Mesh::line(length, elements, 1.0, kind).unwrap());
    let model = BeamFull::new(EI, ES, C, cubic);
    Problem::new(model, mesh, &conditions(kind, &[1], ends), &end_force()).unwrap()
}

/// `beam-envelope` at the critical wavenumber on `elements` Line3 elements, $`v_1 = 0`$ at the
/// ends.
pub fn envelope(length: f64, elements: usize, cubic: f64) -> Problem<BeamEnvelope> {
    let kind = ElementKind::Line3;
    let mesh = Arc::new(Mesh::line(length, elements, 1.0, kind).unwrap());
    let model = BeamEnvelope::new(EI, ES, C, cubic, critical_wavenumber());
    let conditions = conditions(kind, &[1], Ends::SimplySupported);
    Problem::new(model, mesh, &conditions, &end_force()).unwrap()
}

/// `beam-complex-envelope` at the critical wavenumber on `elements` Line3 elements,
/// $`a = b = 0`$ at the ends. The energy is invariant under a constant phase
/// $`v_1 \mapsto e^{i\phi}v_1`$, which the ends do not fix: the thresholds are two-fold and the
/// tangent on a buckled state is singular along $`(-b, a)`$. Newton converged on every state
/// below regardless (the null direction does not change the residual); pinning $`b = 0`$ at
/// the middle node instead sent the softening branch to a packet away from the middle.
pub fn complex_envelope(length: f64, elements: usize, cubic: f64) -> Problem<BeamComplexEnvelope> {
    let kind = ElementKind::Line3;
    let mesh = Arc::new(Mesh::line(length, elements, 1.0, kind).unwrap());
    let model = BeamComplexEnvelope::new(EI, ES, C, cubic, critical_wavenumber());
    let conditions = conditions(kind, &[1, 2], Ends::SimplySupported);
    Problem::new(model, mesh, &conditions, &end_force()).unwrap()
}

/// The end shortening $`\lambda`$ (mm) prescribed on `u` at the right end: displacement
/// control, $`u(L) = -\lambda`$.
fn end_shortening() -> DirichletCondition {
    DirichletCondition {
        value_per_load: -1.0,
        ..DirichletCondition::fixed("right", 0)
    }
}

/// `beam-full` as [`full`] but compressed by the end shortening $`\lambda`$ instead of a force.
pub fn full_shortened(length: f64, elements: usize, ends: Ends) -> Problem<BeamFull> {
    let kind = ElementKind::Hermite2;
    let mesh = Arc::new(Mesh::line(length, elements, 1.0, kind).unwrap());
    let mut conditions = conditions(kind, &[1], ends);
    conditions.push(end_shortening());
    let model = BeamFull::new(EI, ES, C, 0.0);
    Problem::new(model, mesh, &conditions, &Loads::default()).unwrap()
}

/// `beam-envelope` as [`envelope`] but compressed by the end shortening $`\lambda`$.
pub fn envelope_shortened(length: f64, elements: usize) -> Problem<BeamEnvelope> {
    let kind = ElementKind::Line3;
    let mesh = Arc::new(Mesh::line(length, elements, 1.0, kind).unwrap());
    let mut conditions = conditions(kind, &[1], Ends::SimplySupported);
    conditions.push(end_shortening());
    let model = BeamEnvelope::new(EI, ES, C, 0.0, critical_wavenumber());
    Problem::new(model, mesh, &conditions, &Loads::default()).unwrap()
}

/// Linear buckling of `problem` (its first mode). A long beam's critical loads cluster
/// (neighbouring wave counts differ by $`4EI(\pi/L)^2`$): a Krylov basis of 150.
pub fn buckle<M: EnergyModel>(problem: &Problem<M>) -> LinearBuckling {
    let mut factor = SparseFactorization::analyze(problem.assembler.pattern()).unwrap();
    let mut options = LinearBucklingOptions::default();
    options.eigen.max_krylov = 150;
    linear_buckling(problem, &mut factor, &options).unwrap()
}

/// The global dof vector (prescribed values included) of the free values `free` at `load`.
pub fn global<M: EnergyModel>(problem: &Problem<M>, free: &[f64], load: f64) -> Vec<f64> {
    problem.dofs().expand(free, load)
}

/// Value of field `field` at `x`.
pub fn value_at<M: EnergyModel>(problem: &Problem<M>, global: &[f64], field: usize, x: f64) -> f64 {
    let mesh = problem.assembler.mesh();
    mesh.interpolate(global, problem.dofs().field_count, field, [x, 0.0])
        .unwrap()
}

/// Physical wave amplitude of a model's state at `x`, in the model's own terms: for `beam-full`
/// the largest $`|v|`$ over one wavelength centred on `x` (sampled at 200 points); for an
/// envelope model $`2|v_1(x)|`$.
pub trait Amplitude {
    /// The amplitude at `x` of the global state `global`.
    fn amplitude_at(&self, global: &[f64], x: f64) -> f64;
}

impl Amplitude for Problem<BeamFull> {
    fn amplitude_at(&self, global: &[f64], x: f64) -> f64 {
        let half = PI / critical_wavenumber();
        let length = self.assembler.mesh().bounds()[1];
        (0..=200)
            .map(|i| (x - half + 2.0 * half * i as f64 / 200.0).clamp(0.0, length))
            .map(|s| value_at(self, global, 1, s).abs())
            .fold(0.0, f64::max)
    }
}

impl Amplitude for Problem<BeamEnvelope> {
    fn amplitude_at(&self, global: &[f64], x: f64) -> f64 {
        2.0 * value_at(self, global, 1, x).abs()
    }
}

impl Amplitude for Problem<BeamComplexEnvelope> {
    fn amplitude_at(&self, global: &[f64], x: f64) -> f64 {
        2.0 * value_at(self, global, 1, x).hypot(value_at(self, global, 2, x))
    }
}

/// Local wavenumber of the full beam's deflection around `x`: $`\pi`$ over the mean spacing of
/// the zeros of $`v`$ in the four wavelengths centred on `x` (sampled at 800 points, zeros by
/// linear interpolation).
pub fn local_wavenumber(problem: &Problem<BeamFull>, global: &[f64], x: f64) -> f64 {
    let span = 4.0 * PI / critical_wavenumber();
    let samples: Vec<(f64, f64)> = (0..=800)
        .map(|i| x - span + 2.0 * span * i as f64 / 800.0)
        .map(|s| (s, value_at(problem, global, 1, s)))
        .collect();
    let zeros: Vec<f64> = samples
        .windows(2)
        .filter(|p| p[0].1 * p[1].1 < 0.0)
        .map(|p| p[0].0 - p[0].1 * (p[1].0 - p[0].0) / (p[1].1 - p[0].1))
        .collect();
    PI * (zeros.len() - 1) as f64 / (zeros[zeros.len() - 1] - zeros[0])
}

/// One converged state of a load continuation.
#[derive(Clone, Debug)]
pub struct Equilibrium {
    /// The load $`\lambda`$.
    pub load: f64,
    /// Free dofs.
    pub state: Vec<f64>,
    /// Amplitude at the middle of the beam.
    pub amplitude: f64,
}

/// A load continuation on the branch of the first buckling mode: Newton at each load of
/// `loads` in turn. A supercritical branch ($`\alpha > 0`$) is entered close to the threshold
/// $`\lambda_1`$, at $`10^{-4}`$ of the way to the first load (a subcritical one at the first
/// load), from the pre-buckling state plus the mode with the
/// amplitude of the Landau law $`\lambda - \lambda_1 = \alpha a^2`$ (`landau` is
/// $`\alpha`$), then followed to the first load in 16 geometric steps (not recorded: on a long
/// beam the mode turns into a plateau with boundary layers well before it). Each guess is the
/// pre-buckling state at the new load plus the last solution's deviation from its own, scaled by
/// the Landau ratio $`\sqrt{(\lambda - \lambda_1)/(\lambda_\text{prev} - \lambda_1)}`$; a
/// failed step is halved (up to 8 times). Stops at the first load that cannot be reached,
/// returning the path so far and the failure.
pub fn continuation<M: EnergyModel>(
    problem: &Problem<M>,
    buckling: &LinearBuckling,
    landau: f64,
    loads: &[f64],
) -> (Vec<Equilibrium>, Option<String>)
where
    Problem<M>: Amplitude,
{
    continuation_to(problem, buckling, landau, loads, 1e-10)
}

/// [`continuation`] with Newton's relative-residual `tolerance` (1e-10 there; 1e-8 on the
/// longest beams, where the field-balanced residual stalls between 1e-9 and 1e-8 as waves
/// enter at the ends and the tangent is nearly singular).
pub fn continuation_to<M: EnergyModel>(
    problem: &Problem<M>,
    buckling: &LinearBuckling,
    landau: f64,
    loads: &[f64],
    tolerance: f64,
) -> (Vec<Equilibrium>, Option<String>)
where
    Problem<M>: Amplitude,
{
    let critical = buckling.critical_loads[0];
    // A subcritical branch (α < 0) localises instead of forming a plateau: entered directly.
    let entry_fraction: f64 = if landau > 0.0 { 1e-4 } else { 1.0 };
    let entry = critical + entry_fraction * (loads[0] - critical);
    let mut stepper = Stepper {
        problem,
        buckling,
        factor: SparseFactorization::analyze(problem.assembler.pattern()).unwrap(),
        matrix: problem.new_matrix(),
        deviation: scaled_mode(
            problem,
            &buckling.modes[0],
            ((entry - critical) / landau).sqrt(),
        ),
        load: None,
        // The entry steps are not recorded: a looser tolerance near the threshold, where the
        // tangent is nearly singular.
        tolerance: tolerance.max(1e-8),
    };
    let entry_steps = if landau > 0.0 { 16 } else { 0 };
    for i in 0..entry_steps {
        let load = critical + (loads[0] - critical) * 10f64.powf(-4.0 * (1.0 - i as f64 / 16.0));
        if let Err(error) = stepper.step(load) {
            return (Vec::new(), Some(format!("entering the branch: {error}")));
        }
    }
    stepper.tolerance = tolerance;
    let middle = 0.5 * problem.assembler.mesh().bounds()[1];
    let mut path = Vec::new();
    for &target in loads {
        let mut halvings = 0;
        let state = loop {
            let start = stepper.load.unwrap_or(target);
            let load = start + (target - start) / f64::powi(2.0, halvings);
            match stepper.step(load) {
                Ok(state) if load == target => break state,
                Ok(_) => halvings = 0,
                Err(error) if halvings < 8 => {
                    halvings += 1;
                    let _ = error;
                }
                Err(error) => return (path, Some(error)),
            }
        };
        let amplitude = problem.amplitude_at(&global(problem, &state, target), middle);
        path.push(Equilibrium {
            load: target,
            state,
            amplitude,
        });
    }
    (path, None)
}

/// Newton steps of [`continuation`]: the last solution's deviation from the pre-buckling
/// state, and its load.
struct Stepper<'a, M: EnergyModel> {
    problem: &'a Problem<M>,
    buckling: &'a LinearBuckling,
    factor: SparseFactorization,
    matrix: wrinkle_runtime::linear::SparseMatrix,
    deviation: Vec<f64>,
    load: Option<f64>,
    tolerance: f64,
}

impl<M: EnergyModel> Stepper<'_, M> {
    /// Newton at `load` from the scaled deviation; on success the solution becomes the last.
    fn step(&mut self, load: f64) -> Result<Vec<f64>, String> {
        let critical = self.buckling.critical_loads[0];
        let ratio = self.load.map_or(1.0, |last| {
            ((load - critical) / (last - critical)).abs().sqrt()
        });
        let prebuckling = self.buckling.state_at(0.0, load);
        let guess: Vec<f64> = prebuckling
            .iter()
            .zip(&self.deviation)
            .map(|(p, d)| p + ratio * d)
            .collect();
        let options = NewtonOptions {
            tolerance: self.tolerance,
            max_iterations: 25,
        };
        let problem = self.problem;
        let solution = newton(
            problem,
            guess,
            load,
            &mut self.factor,
            &mut self.matrix,
            &options,
        )
        .map_err(|error| format!("Newton at λ = {load}: {error}"))?
        .solution;
        self.deviation = solution
            .iter()
            .zip(&prebuckling)
            .map(|(s, p)| s - p)
            .collect();
        self.load = Some(load);
        Ok(solution)
    }
}

/// Full width at half maximum of the amplitude profile of `state`: the length of the part of
/// the beam where the amplitude ([`Amplitude::amplitude_at`], sampled every quarter
/// wavelength) is at least half its largest sampled value; and that largest value.
pub fn width_at_half_maximum<M: EnergyModel>(
    problem: &Problem<M>,
    state: &Equilibrium,
) -> (f64, f64)
where
    Problem<M>: Amplitude,
{
    let length = problem.assembler.mesh().bounds()[1];
    let step = 0.5 * PI / critical_wavenumber();
    let global = global(problem, &state.state, state.load);
    let samples: Vec<f64> = (0..=((length / step) as usize))
        .map(|i| problem.amplitude_at(&global, (i as f64 * step).min(length)))
        .collect();
    let peak = samples.iter().cloned().fold(0.0, f64::max);
    let above = samples.iter().filter(|&&a| a >= 0.5 * peak).count();
    (above as f64 * step, peak)
}

/// The buckling mode scaled so that the amplitude at the middle is `amplitude`.
pub fn scaled_mode<M: EnergyModel>(problem: &Problem<M>, mode: &[f64], amplitude: f64) -> Vec<f64>
where
    Problem<M>: Amplitude,
{
    let middle = 0.5 * problem.assembler.mesh().bounds()[1];
    let unit = problem.amplitude_at(&global(problem, mode, 0.0), middle);
    mode.iter().map(|m| m * amplitude / unit).collect()
}
