//! The arc-length corrector and its geometry, shared by Riks, the ANM and the landing.
//!
//! Points $`(U, \lambda)`$ are measured in the arc-length metric
//! $$`\langle (a, \alpha), (b, \beta)\rangle = a\cdot b + \psi^2\alpha\beta,`$$
//! with $`\psi`$ the weight of the load parameter ([`ArcCorrectorOptions::load_scale`]).
//! From an origin $`(U_0, \lambda_0)`$ and a predicted increment
//! $`(\Delta U, \Delta\lambda)`$ of length $`\ell`$, the corrector runs full Newton on the
//! bordered system
//! $$`\begin{pmatrix} K_t & \partial_\lambda R \\ 2\Delta U^\top & 2\psi^2\Delta\lambda\end{pmatrix}
//! \begin{pmatrix}\delta U\\ \delta\lambda\end{pmatrix} = -\begin{pmatrix} R \\ g\end{pmatrix},
//! \qquad g = \|\Delta U\|^2 + \psi^2\Delta\lambda^2 - \ell^2,`$$
//! by the two-solve (Batoz–Dhatt) trick with the factorised $`K_t`$ only:
//! $`\delta U = \delta U_R + \delta\lambda\,\delta U_F`$ with $`K_t\,\delta U_R = -R`$ and
//! $`K_t\,\delta U_F = -\partial_\lambda R`$, and $`\delta\lambda`$ from the linearised constraint
//! ([`ArcLengthConstraint::Linearized`]) or from the exact sphere
//! ([`ArcLengthConstraint::Spherical`], Crisfield: the root closest in angle to the current
//! increment). The tangent is reassembled and refactorised every iteration. Unlike Newton at
//! fixed load it converges through limit points.
//!
//! * [`correct_on_arc`]: the corrector for a predicted point (an ANM step's end, a landing's
//!   chord point), on the sphere about the origin through it.
//! * `correct`: the corrector along a unit direction with a given arc length (Riks' steps).
//! * [`increment`], [`orientation`], [`arc_dot`]: the chord between two points, the sign that
//!   orients a path tangent along it, and the metric.

use super::error::SolveError;
use super::linearization::Linearization;
use super::path::PathState;
use crate::linear::LinearError;
use crate::linear::vector::dot;
use crate::model::EnergyModel;

/// Which arc-length equation the corrector enforces.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ArcLengthConstraint {
    /// Newton on the constraint: $`\delta\lambda`$ from its linearisation at the current
    /// iterate (Riks–Wempner). Always solvable unless the bordered system is singular; the
    /// converged point lies on the sphere.
    Linearized,
    /// Crisfield's spherical constraint: $`\delta\lambda`$ solves the quadratic
    /// $`\|\Delta U + \delta U_R + \delta\lambda\,\delta U_F\|^2 + \psi^2(\Delta\lambda + \delta\lambda)^2 = \ell^2`$
    /// exactly (a step without real root is rejected).
    Spherical,
}

/// Settings of the arc-length corrector.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ArcCorrectorOptions {
    /// Accept an iterate when its relative residual
    /// ([`Problem::residual_with_relative`](crate::problem::Problem::residual_with_relative))
    /// is at most this.
    pub tolerance: f64,
    /// Newton iterations allowed.
    pub max_iterations: usize,
    /// Weight $`\psi`$ of the load parameter in the arc length (0 = displacements only).
    pub load_scale: f64,
    /// The constraint enforced.
    pub constraint: ArcLengthConstraint,
}

/// A converged arc-length correction.
#[derive(Clone, Debug)]
pub struct ArcCorrection {
    /// The corrected equilibrium point.
    pub state: PathState,
    /// Newton iterations (= tangent factorisations) used.
    pub iterations: usize,
    /// Relative residual reached.
    pub relative_residual: f64,
}

/// Why a correction failed.
pub(crate) enum CorrectorFailure {
    /// The corrector did not reach the tolerance.
    NoConvergence { iterations: usize, residual: f64 },
    /// The tangent could not be factorised (or solved with).
    Singular {
        load: f64,
        iteration: usize,
        source: LinearError,
    },
    /// NaN or infinity appeared.
    NonFinite { location: String },
    /// The spherical constraint has no real root, or the bordered system is singular.
    Constraint { message: String },
}

impl CorrectorFailure {
    /// What went wrong, against the corrector's `tolerance`.
    pub(crate) fn describe(&self, tolerance: f64) -> String {
        match self {
            CorrectorFailure::NoConvergence {
                iterations,
                residual,
            } => format!(
                "no convergence after {iterations} iterations (relative residual {residual:.3e}, \
                 tolerance {tolerance:.1e})"
            ),
            CorrectorFailure::Singular {
                load,
                iteration,
                source,
            } => format!("singular tangent at load {load:.6e}, iteration {iteration}: {source}"),
            CorrectorFailure::NonFinite { location } => {
                format!("non-finite values (NaN or infinity) in {location}")
            }
            CorrectorFailure::Constraint { message } => message.clone(),
        }
    }
}

/// The arc-length inner product $`u\cdot v + \psi^2 \alpha\beta`$ of $`(u, \alpha)`$ and
/// $`(v, \beta)`$, with $`\psi`$ = `load_scale`.
pub fn arc_dot(u: &[f64], load_u: f64, v: &[f64], load_v: f64, load_scale: f64) -> f64 {
    dot(u, v) + load_scale * load_scale * load_u * load_v
}

/// The increment $`(\Delta U, \Delta\lambda)`$ from `from` to `to`.
pub fn increment(from: &PathState, to: &PathState) -> (Vec<f64>, f64) {
    let displacement = to
        .displacement
        .iter()
        .zip(&from.displacement)
        .map(|(new, old)| new - old)
        .collect();
    (displacement, to.load - from.load)
}

/// $`\pm 1`$: the sign that orients the path tangent $`(\delta U_F, 1)`$ along the increment
/// $`(\Delta U, \Delta\lambda)`$ in the arc-length metric (+1 when they are orthogonal).
pub fn orientation(
    increment: &[f64],
    load_increment: f64,
    tangent: &[f64],
    load_scale: f64,
) -> f64 {
    if arc_dot(increment, load_increment, tangent, 1.0, load_scale) < 0.0 {
        -1.0
    } else {
        1.0
    }
}

/// Riks corrector for a predicted point, e.g. the end of an ANM step: Newton on the bordered
/// system with the arc-length constraint (of radius $`\|(\Delta U, \psi\Delta\lambda)\|`$ about
/// `origin`) passing through `predicted` (see the [module](self)).
///
/// It refactorises `linearization`'s factor; its tangent assemblies, factorisations and
/// residuals are added to `linearization`'s counters, its Newton iterations are not (they are
/// [`ArcCorrection::iterations`]).
pub fn correct_on_arc<M: EnergyModel>(
    linearization: &mut Linearization<'_, M>,
    origin: &PathState,
    predicted: &PathState,
    options: &ArcCorrectorOptions,
) -> Result<ArcCorrection, SolveError> {
    let (increment, load_increment) = increment(origin, predicted);
    let arc_length = arc_dot(
        &increment,
        load_increment,
        &increment,
        load_increment,
        options.load_scale,
    )
    .sqrt();
    if !(arc_length > 0.0 && arc_length.is_finite()) {
        return Err(SolveError::Path {
            load: origin.load,
            message: format!("arc-length correction: degenerate increment (length {arc_length:e})"),
        });
    }
    let direction: Vec<f64> = increment.iter().map(|d| d / arc_length).collect();
    let result = linearization.nested(|nested| {
        correct(
            nested,
            origin,
            &direction,
            load_increment / arc_length,
            arc_length,
            options,
        )
    });
    result.map_err(|failure| SolveError::Path {
        load: predicted.load,
        message: format!(
            "arc-length correction: {}",
            failure.describe(options.tolerance)
        ),
    })
}

/// A corrector iterate: the point and its increment from the origin.
struct ArcIterate {
    displacement: Vec<f64>,
    load: f64,
    /// $`\Delta U`$ from the origin.
    increment: Vec<f64>,
    /// $`\Delta\lambda`$ from the origin.
    load_increment: f64,
}

impl ArcIterate {
    /// The predictor: `origin` plus `arc_length` times the unit direction.
    fn predicted(
        origin: &PathState,
        direction: &[f64],
        load_direction: f64,
        arc_length: f64,
    ) -> ArcIterate {
        let increment: Vec<f64> = direction.iter().map(|d| arc_length * d).collect();
        let load_increment = arc_length * load_direction;
        let displacement: Vec<f64> = origin
            .displacement
            .iter()
            .zip(&increment)
            .map(|(u, d)| u + d)
            .collect();
        ArcIterate {
            displacement,
            load: origin.load + load_increment,
            increment,
            load_increment,
        }
    }

    /// Adds $`\delta U = \delta U_R + \delta\lambda\,\delta U_F`$ and $`\delta\lambda`$ to
    /// the point and its increment.
    fn apply(&mut self, residual_correction: &[f64], load_tangent: &[f64], load_correction: f64) {
        for ((u, delta), (r, f)) in self
            .displacement
            .iter_mut()
            .zip(self.increment.iter_mut())
            .zip(residual_correction.iter().zip(load_tangent))
        {
            let change = r + load_correction * f;
            *u += change;
            *delta += change;
        }
        self.load += load_correction;
        self.load_increment += load_correction;
    }

    fn is_finite(&self) -> bool {
        self.load.is_finite() && self.displacement.iter().all(|u| u.is_finite())
    }
}

/// One correction: a predictor of length `arc_length` along the unit direction
/// `(direction, load_direction)` from `origin`, then full Newton on the bordered system (see
/// the [module](self)). Every Newton iteration counts as one of `linearization`'s
/// `corrections`.
pub(crate) fn correct<M: EnergyModel>(
    linearization: &mut Linearization<'_, M>,
    origin: &PathState,
    direction: &[f64],
    load_direction: f64,
    arc_length: f64,
    options: &ArcCorrectorOptions,
) -> Result<ArcCorrection, CorrectorFailure> {
    let mut iterate = ArcIterate::predicted(origin, direction, load_direction, arc_length);
    let mut iterations = 0;
    loop {
        let (residual, relative) = linearization.residual(&iterate.displacement, iterate.load);
        if !relative.is_finite() {
            return Err(CorrectorFailure::NonFinite {
                location: format!(
                    "the residual at load {:.6e}, iteration {iterations}",
                    iterate.load
                ),
            });
        }
        if relative <= options.tolerance {
            return Ok(ArcCorrection {
                state: PathState {
                    displacement: iterate.displacement,
                    load: iterate.load,
                },
                iterations,
                relative_residual: relative,
            });
        }
        if iterations == options.max_iterations {
            return Err(CorrectorFailure::NoConvergence {
                iterations,
                residual: relative,
            });
        }
        let (residual_correction, load_tangent) =
            bordered_solves(linearization, &iterate, residual, iterations)?;
        let load_correction = load_correction(
            &iterate,
            &residual_correction,
            &load_tangent,
            arc_length,
            options,
            iterations,
        )?;
        iterate.apply(&residual_correction, &load_tangent, load_correction);
        iterations += 1;
        linearization.statistics.corrections += 1;
        if !iterate.is_finite() {
            return Err(CorrectorFailure::NonFinite {
                location: format!("the corrector iterate {iterations}"),
            });
        }
    }
}

/// The two solves of the bordered system at `iterate` with `residual` $`R`$ there:
/// $`\delta U_R = -K_t^{-1}R`$ and $`\delta U_F = -K_t^{-1}\partial_\lambda R`$, with the
/// tangent assembled and factorised at the iterate.
fn bordered_solves<M: EnergyModel>(
    linearization: &mut Linearization<'_, M>,
    iterate: &ArcIterate,
    mut residual: Vec<f64>,
    iteration: usize,
) -> Result<(Vec<f64>, Vec<f64>), CorrectorFailure> {
    let load = iterate.load;
    let singular = |source| CorrectorFailure::Singular {
        load,
        iteration,
        source,
    };
    linearization
        .factorize(&iterate.displacement, load)
        .map_err(singular)?;
    for value in residual.iter_mut() {
        *value = -*value;
    }
    linearization
        .solve_in_place(&mut residual)
        .map_err(singular)?;
    let load_tangent = linearization
        .load_tangent(&iterate.displacement, load)
        .map_err(singular)?;
    Ok((residual, load_tangent))
}

/// $`\delta\lambda`$ from the constraint of `options` (linearised, or the spherical root).
fn load_correction(
    iterate: &ArcIterate,
    residual_correction: &[f64],
    load_tangent: &[f64],
    arc_length: f64,
    options: &ArcCorrectorOptions,
    iteration: usize,
) -> Result<f64, CorrectorFailure> {
    let (increment, load_increment) = (&iterate.increment, iterate.load_increment);
    let load = iterate.load;
    let load_scale = options.load_scale;
    let weight = load_scale * load_scale;
    match options.constraint {
        ArcLengthConstraint::Linearized => {
            let mismatch = arc_dot(
                increment,
                load_increment,
                increment,
                load_increment,
                load_scale,
            ) - arc_length * arc_length;
            let numerator = -0.5 * mismatch - dot(increment, residual_correction);
            let denominator = dot(increment, load_tangent) + weight * load_increment;
            let correction = numerator / denominator;
            if !correction.is_finite() {
                return Err(CorrectorFailure::Constraint {
                    message: format!(
                        "singular bordered system at load {load:.6e} (constraint row \
                         {denominator:.3e} against the load tangent)"
                    ),
                });
            }
            Ok(correction)
        }
        ArcLengthConstraint::Spherical => {
            let shifted: Vec<f64> = increment
                .iter()
                .zip(residual_correction)
                .map(|(a, b)| a + b)
                .collect();
            let a = dot(load_tangent, load_tangent) + weight;
            let b = 2.0 * (dot(&shifted, load_tangent) + weight * load_increment);
            let c = dot(&shifted, &shifted) + weight * load_increment * load_increment
                - arc_length * arc_length;
            spherical_root([a, b, c], iterate, &shifted, load_tangent, load_scale).map_err(
                |message| CorrectorFailure::Constraint {
                    message: format!("{message} at load {load:.6e}, iteration {iteration}"),
                },
            )
        }
    }
}

/// Root $`\delta\lambda`$ of $`a\,\delta\lambda^2 + b\,\delta\lambda + c = 0`$ whose new
/// increment $`(s + \delta\lambda f, \Delta\lambda + \delta\lambda)`$ ($`s`$ = `shifted`,
/// $`f`$ = `load_tangent`) makes the smallest angle with the current increment
/// $`(\Delta U, \Delta\lambda)`$ of `iterate` (Crisfield's choice).
fn spherical_root(
    [a, b, c]: [f64; 3],
    iterate: &ArcIterate,
    shifted: &[f64],
    load_tangent: &[f64],
    load_scale: f64,
) -> Result<f64, String> {
    let discriminant = b * b - 4.0 * a * c;
    if !discriminant.is_finite() || !a.is_finite() {
        return Err("non-finite coefficients of the spherical constraint".into());
    }
    if discriminant < 0.0 {
        return Err(format!(
            "the spherical arc-length constraint has no real root (discriminant {discriminant:.3e})"
        ));
    }
    if a == 0.0 {
        // Linear constraint (no load weight and no load tangent).
        let root = -c / b;
        return if root.is_finite() {
            Ok(root)
        } else {
            Err("degenerate spherical arc-length constraint".into())
        };
    }
    // Numerically stable pair of roots.
    let q = -0.5 * (b + b.signum() * discriminant.sqrt());
    let roots = if q == 0.0 { [0.0, 0.0] } else { [q / a, c / q] };
    let load_increment = iterate.load_increment;
    let alignment = |root: f64| {
        let moved: f64 = iterate
            .increment
            .iter()
            .zip(shifted.iter().zip(load_tangent))
            .map(|(d, (s, f))| d * (s + root * f))
            .sum();
        moved + load_scale * load_scale * load_increment * (load_increment + root)
    };
    let chosen = if alignment(roots[0]) >= alignment(roots[1]) {
        roots[0]
    } else {
        roots[1]
    };
    if chosen.is_finite() {
        Ok(chosen)
    } else {
        Err("degenerate spherical arc-length constraint".into())
    }
}
