//! The validity checks of a threshold (module documentation of [`crate::threshold`]): scale
//! separation, strong ellipticity, mode resolution and well-posedness beyond the threshold.

use super::result::{Threshold, ValidityWarning};
use crate::physics::Layout;
use crate::scene::Scene;
use wrinkle_runtime::EnergyModel;
use wrinkle_runtime::fem::Mesh;
use wrinkle_runtime::problem::Problem;
use wrinkle_runtime::solve::buckling::LinearBuckling;

/// Shortest wavelength an envelope model accepts, in thicknesses.
pub const MIN_WAVELENGTH_OVER_THICKNESS: f64 = 20.0;
/// Fewest wavelengths across the shorter side of the domain for an envelope model's scale
/// separation.
pub const MIN_WAVES_PER_DOMAIN: f64 = 4.0;
/// Area fraction where strong ellipticity may fail at the threshold (stress singularities at
/// clamped–free corners) before the threshold is flagged.
pub const MAX_NON_ELLIPTIC_FRACTION: f64 = 1e-2;
/// Fewest Q8 elements per wavelength for a resolved plate mode.
pub const MIN_ELEMENTS_PER_WAVELENGTH: f64 = 8.0;

/// Load factor, relative to $`\lambda_c`$, at which the fundamental branch is checked for
/// pointwise well-posedness.
pub const WELL_POSEDNESS_LOAD_RATIO: f64 = 1.05;

/// A model without gradient stiffness in a transverse field (the pure membrane) is ill-posed
/// beyond its threshold: the fundamental branch at $`1.05\lambda_c`$ is pointwise unstable over
/// most of the area at once, so there is no length scale and the post-buckling solution depends
/// on the mesh. Checked on the fundamental state extrapolated to $`1.05\lambda_c`$.
pub(super) fn well_posedness_beyond<M: EnergyModel>(
    problem: &Problem<M>,
    buckling: &LinearBuckling,
    reference_load: f64,
) -> Option<ValidityWarning> {
    let load = WELL_POSEDNESS_LOAD_RATIO * buckling.critical_loads[0];
    let state = buckling.state_at(reference_load, load);
    let report = wrinkle_runtime::solve::ellipticity::legendre_hadamard(problem, &state, load);
    let worst = report
        .gradient_free
        .iter()
        .filter(|f| !f.stable)
        .max_by(|a, b| a.violated_fraction.total_cmp(&b.violated_fraction))?;
    (worst.violated_fraction > 0.5).then(|| ValidityWarning {
        check: "well_posedness",
        message: format!(
            "field `{}` has no gradient stiffness and is pointwise unstable over {:.0} % of the area just beyond the threshold (λ = {WELL_POSEDNESS_LOAD_RATIO} λ_c): the model is ill-posed there — no length scale, post-buckling results depend on the mesh",
            worst.field,
            100.0 * worst.violated_fraction
        ),
    })
}

/// A count below a limit, with two decimals rounded down, so that a count just below the limit
/// is never printed as the limit itself (7.994 was shown as "8.0 … (at least 8)").
fn below_limit_text(value: f64) -> String {
    format!("{:.2}", (100.0 * value).floor() / 100.0)
}

/// The validity checks of the module documentation.
pub(super) fn validity_warnings(
    scene: &Scene,
    layout: &Layout,
    threshold: &Threshold,
    mode: &ModeOnMesh,
) -> Vec<ValidityWarning> {
    let mut warnings = Vec::new();
    let h = scene.material.thickness;
    let shortest = scene.geometry.length_x.min(scene.geometry.length_y);
    if let (Some(l), true) = (threshold.wavelength, layout.is_envelope()) {
        if l > shortest / MIN_WAVES_PER_DOMAIN {
            warnings.push(ValidityWarning {
                check: "scale_separation",
                message: format!(
                    "wavelength {l:.4e} mm is not small against the domain (shorter side {shortest} mm, at most 1/{MIN_WAVES_PER_DOMAIN} of it): the envelope model's slowly-varying assumption does not hold"
                ),
            });
        }
        if l < MIN_WAVELENGTH_OVER_THICKNESS * h {
            warnings.push(ValidityWarning {
                check: "scale_separation",
                message: format!(
                    "wavelength {l:.4e} mm is below {MIN_WAVELENGTH_OVER_THICKNESS} thicknesses (h = {h} mm): outside thin-plate theory"
                ),
            });
        }
    }
    let e = &threshold.ellipticity;
    if e.violated_fraction > MAX_NON_ELLIPTIC_FRACTION {
        warnings.push(ValidityWarning {
            check: "ellipticity",
            message: format!(
                "not strongly elliptic at the threshold over {:.1} % of the area (worst at ({:.4}, {:.4}) mm, field `{}`): the critical load is a mesh-scale mode, not a threshold of the model",
                100.0 * e.violated_fraction, e.location[0], e.location[1], e.field
            ),
        });
    }
    if let (Some(l), false) = (threshold.wavelength, layout.is_envelope()) {
        warnings.extend(mode_resolution(scene, threshold, mode, l));
    }
    warnings
}

/// The mode-resolution check of a model that resolves its waves on the mesh: the wavelength
/// `l` over the element size along the wave direction $`\mathbf e`$, measured on the elements
/// themselves — the largest extent along $`\mathbf e`$ of the elements where the mode is at
/// least [`MODE_SUPPORT_FRACTION`] of its peak (a graded or a file mesh is judged where its
/// wrinkles are, not by $`L/n`$).
fn mode_resolution(
    scene: &Scene,
    threshold: &Threshold,
    mode: &ModeOnMesh,
    l: f64,
) -> Option<ValidityWarning> {
    let theta = threshold.direction_degrees.to_radians();
    let (cos, sin) = (theta.cos(), theta.sin());
    let element = mode.element_size_along([cos, sin]);
    let per_wavelength = l / element;
    if per_wavelength >= MIN_ELEMENTS_PER_WAVELENGTH {
        return None;
    }
    let (along, refine) = if !scene.mesh.file.is_empty() {
        (
            format!(
                "along the wave direction ({}° from X)",
                threshold.direction_degrees
            ),
            format!("refine the mesh file `{}`", scene.mesh.file),
        )
    } else if sin.abs() > cos.abs() {
        ("along Y".to_string(), "refine mesh.ny".to_string())
    } else {
        ("along X".to_string(), "refine mesh.nx".to_string())
    };
    Some(ValidityWarning {
        check: "mode_resolution",
        message: format!(
            "{} elements per wavelength ({l:.4e} mm) {along}: the plate's mode is not resolved (at least {MIN_ELEMENTS_PER_WAVELENGTH}; {refine})",
            below_limit_text(per_wavelength),
        ),
    })
}

/// Elements whose largest nodal $`|w|`$ of the mode is at least this fraction of the mode's
/// peak carry the mode, for [`mode_resolution`].
pub const MODE_SUPPORT_FRACTION: f64 = 0.1;

/// A buckling mode on its mesh: the nodal values of the primary (deflection) field.
pub(super) struct ModeOnMesh<'a> {
    /// The mesh.
    pub mesh: &'a Mesh,
    /// The mode's primary field at each node (empty: no mode; every element counts).
    pub nodal: Vec<f64>,
}

impl ModeOnMesh<'_> {
    /// The largest extent along `direction` of the elements that carry the mode
    /// ([`MODE_SUPPORT_FRACTION`]); of every element when there is no mode.
    fn element_size_along(&self, direction: [f64; 2]) -> f64 {
        let peak = self.nodal.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        let carries = |e: usize| {
            peak == 0.0
                || self.mesh.element_nodes(e).iter().any(|&n| {
                    self.nodal
                        .get(n)
                        .is_some_and(|v| v.abs() >= MODE_SUPPORT_FRACTION * peak)
                })
        };
        (0..self.mesh.element_count())
            .filter(|&e| carries(e))
            .map(|e| self.mesh.element_extent_along(e, direction))
            .fold(0.0, f64::max)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_count_just_below_the_resolution_limit_is_not_printed_as_the_limit() {
        // 120 × 30 elements on example 1's 400 mm: 26.649 mm / 3.333 mm = 7.9947 elements.
        assert_eq!(below_limit_text(26.649_139 / (400.0 / 120.0)), "7.99");
        assert_eq!(below_limit_text(6.4), "6.40");
        assert_eq!(below_limit_text(2.0), "2.00");
        assert_eq!(below_limit_text(7.999_999), "7.99");
    }
}
