//! From a scene to a discrete [`Problem`]: mesh, boundary conditions, loads, model parameters.
//!
//! Load kinds (key `load.kind`):
//! * `biaxial` (the paper's example 1): self-equilibrated tractions on all four edges —
//!   $`(\pm\lambda, 0)`$ on `left`/`right` (compression $`N_X = -\lambda`$, N/mm, proportional),
//!   $`(0, \pm N_Y)`$ on `bottom`/`top` (fixed) — with the in-plane rigid-body motions removed at
//!   two points only ($`u = v = 0`$ at the centre, $`v = 0`$ at the middle of the right edge), so the
//!   pre-buckling membrane state is exactly uniform and the problem symmetric; envelope
//!   $`w = 0`$ on every edge (clamped plate).
//! * `strip` (example 2): short sides clamped, $`u = 0`$ on `left`, $`u = \lambda`$ on `right`
//!   (mm), $`v = w = 0`$ on both; long sides free.

use crate::error::Error;
use crate::physics::Layout;
use crate::scene::{LoadKind, Scene};
use std::sync::Arc;
use wrinkle_runtime::EnergyModel;
use wrinkle_runtime::fem::{DirichletCondition, EdgeTraction, Loads, Mesh};
use wrinkle_runtime::problem::Problem;

pub(crate) fn scene_error(scene: &Scene, key: &str, message: impl Into<String>) -> Error {
    Error::scene(scene.origin_of(key), key, message)
}

/// Sets the model's parameters from the scene: `young`, `poisson`, `thickness` from
/// `material.*`, `direction` (radians) from `model.direction` (degrees), `wavenumber` when fixed,
/// then every `model.parameters.NAME` (which wins over the standard source: `[model.parameters]
/// young = 1.0` sets $`E`$ for this model). A parameter the model declares but the scene cannot
/// set is an error naming it, and so is a `model.parameters` entry the model does not declare.
/// Standard quantities a model does not declare (a plate has no `wavenumber`) are not passed.
pub fn configure_model<M: EnergyModel>(
    scene: &Scene,
    model: &mut M,
    wavenumber: f64,
) -> Result<(), Error> {
    let spec = M::SPEC;
    for name in spec.parameters {
        let value = match *name {
            other if scene.model.parameters.contains_key(other) => scene.model.parameters[other],
            "young" => scene.material.young_modulus,
            "poisson" => scene.material.poisson_ratio,
            "thickness" => scene.material.thickness,
            "direction" => scene.model.direction_degrees.to_radians(),
            "wavenumber" => wavenumber,
            other => match scene.model.parameters.get(other) {
                Some(v) => *v,
                None => {
                    return Err(scene_error(
                        scene,
                        &format!("model.parameters.{other}"),
                        format!(
                            "model `{}` needs parameter `{other}`; set it in [model.parameters]",
                            spec.name
                        ),
                    ));
                }
            },
        };
        model
            .set_parameter(name, value)
            .map_err(|m| scene_error(scene, "model.name", m))?;
    }
    for key in scene.model.parameters.keys() {
        if spec.parameter_index(key).is_none() {
            return Err(scene_error(
                scene,
                &format!("model.parameters.{key}"),
                format!(
                    "model `{}` has no parameter `{key}` (parameters: {})",
                    spec.name,
                    spec.parameters.join(", ")
                ),
            ));
        }
    }
    Ok(())
}

/// The scene error for a `model.name` that is not in the registry.
pub fn unknown_model(scene: &Scene) -> Error {
    scene_error(
        scene,
        "model.name",
        format!(
            "unknown model `{}` (models: {})",
            scene.model.name,
            wrinkle_models::names().join(", ")
        ),
    )
}

/// The field layout of `M` from its declared roles, or a scene error naming `model.name`.
pub fn layout_of<M: EnergyModel>(scene: &Scene) -> Result<Layout, Error> {
    Layout::from_spec(M::SPEC).map_err(|message| scene_error(scene, "model.name", message))
}

/// Builds the problem of `scene` for `model` (parameters already set), without imperfection.
///
/// The conditions follow from the field roles ([`Layout`]): a clamped edge sets every
/// transverse field (deflection, rotations, envelopes, mean deflection) to zero; the in-plane
/// conditions and loads are those of the load kind (module documentation).
pub fn build_problem<M: EnergyModel>(scene: &Scene, model: M) -> Result<Problem<M>, Error> {
    let layout = layout_of::<M>(scene)?;
    let mesh = Arc::new(
        Mesh::rectangle(
            scene.geometry.length_x,
            scene.geometry.length_y,
            scene.mesh.elements_x,
            scene.mesh.elements_y,
            scene.mesh.grading,
        )
        .map_err(|e| scene_error(scene, "mesh", e.to_string()))?,
    );
    let [u, v] = layout.in_plane;
    let fixed = DirichletCondition::fixed;
    let mut conditions = Vec::new();
    let mut tractions = Vec::new();
    let clamped_edges: &[&str] = match scene.load.kind {
        LoadKind::Biaxial => {
            conditions.extend([
                fixed("centre", u),
                fixed("centre", v),
                fixed("right_middle", v),
            ]);
            for (edge, traction, proportional) in [
                ("left", [1.0, 0.0], true),
                ("right", [-1.0, 0.0], true),
                ("bottom", [0.0, -scene.load.tension_y], false),
                ("top", [0.0, scene.load.tension_y], false),
            ] {
                tractions.push(EdgeTraction {
                    edge: edge.into(),
                    fields: [u, v],
                    traction,
                    proportional,
                });
            }
            &["left", "right", "bottom", "top"]
        }
        LoadKind::Strip => {
            conditions.extend([fixed("left", u), fixed("left", v), fixed("right", v)]);
            conditions.push(DirichletCondition {
                value_per_load: 1.0,
                ..fixed("right", u)
            });
            &["left", "right"]
        }
    };
    for edge in clamped_edges {
        conditions.extend(layout.transverse.iter().map(|&f| fixed(edge, f)));
    }
    let loads = Loads {
        tractions,
        ..Loads::default()
    };
    Problem::new(model, mesh, &conditions, &loads)
        .map_err(|e| Error::Solver(format!("setting up the problem: {e}")))
}
