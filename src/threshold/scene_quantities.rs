//! What the threshold takes from the scene alone: the wavenumber range of the search, the
//! unit of the load, and the closed form of the clamped rectangle (THEORY.md §8, eq. 42) where
//! it applies.

use super::validity::MIN_WAVELENGTH_OVER_THICKNESS;
use crate::scene::{Direction, LoadKind, Scene};
use std::f64::consts::PI;

/// Wavenumber range $`[2\pi/L_\min, 2\pi/(20h)]`$ (1/mm) the search scans.
pub fn wavenumber_range(scene: &Scene) -> (f64, f64) {
    let shortest = scene.geometry.length_x.min(scene.geometry.length_y);
    let thickness = scene.material.thickness;
    let low = 2.0 * PI / shortest;
    let high = 2.0 * PI / (MIN_WAVELENGTH_OVER_THICKNESS * thickness);
    (low, high.max(4.0 * low))
}

/// Unit of the load $`\lambda`$: N/mm (biaxial) or mm (strip).
pub fn load_unit(scene: &Scene) -> &'static str {
    match scene.load.kind {
        LoadKind::Biaxial => "N/mm",
        LoadKind::Strip => "mm",
        LoadKind::Boundaries if crate::setup::load_is_displacement(scene) => "mm",
        LoadKind::Boundaries => "N/mm",
    }
}

/// The closed-form threshold (THEORY.md §8, eq. 42 minimised) and its wavenumber when the scene
/// is a clamped rectangle under biaxial load with waves along X: boundary conditions that are
/// the `biaxial` preset's, whether written by the preset or by hand.
pub fn closed_form_threshold(scene: &Scene) -> Option<(f64, f64)> {
    (crate::setup::is_biaxial_rectangle(scene) && scene.model.direction == Direction::Fixed(0.0))
        .then(|| scene.clamped_rectangle().critical_point())
        .flatten()
}

/// The critical load of eq. (42) at the wavenumber `q` (the neutral curve), where the closed
/// form applies to the scene ([`closed_form_threshold`]): a guess the analysis at a fixed $`Q`$
/// is shifted about (0.98 times it, kept only when the tangent there has no negative pivot, so
/// a guess above the model's own threshold costs one factorisation and changes nothing). On
/// example 1 at 40 × 20 it takes the analysis from 55 Lanczos operator applications to 16.
pub(super) fn closed_form_load_at(scene: &Scene, q: f64) -> Option<f64> {
    closed_form_threshold(scene)?;
    Some(scene.clamped_rectangle().neutral_curve(q)).filter(|l| l.is_finite() && *l > 0.0)
}
