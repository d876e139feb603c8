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

use crate::Error;
use crate::scene::{LoadKind, Scene};
use std::sync::Arc;
use wrinkle_runtime::EnergyModel;
use wrinkle_runtime::fem::{BodyLoad, DirichletCondition, EdgeTraction, Mesh};
use wrinkle_runtime::problem::Problem;

pub(crate) fn scene_error(scene: &Scene, key: &str, message: impl Into<String>) -> Error {
    Error::scene(format!("scene {}", scene.source), key, message)
}

/// Sets the model's parameters from the scene: `young`, `poisson`, `thickness` from
/// `material.*`, `direction` (radians) from `model.direction` (degrees), `wavenumber` when fixed,
/// then every `model.parameters.NAME`. A parameter the model declares but the scene cannot set
/// is an error naming it.
pub fn configure_model<M: EnergyModel>(
    scene: &Scene,
    model: &mut M,
    wavenumber: f64,
) -> Result<(), Error> {
    let spec = M::SPEC;
    for name in spec.parameters {
        let value = match *name {
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

/// Field index by name, or a scene error saying the load kind needs it.
fn field(scene: &Scene, spec: &wrinkle_runtime::ModelSpec, name: &str) -> Result<usize, Error> {
    spec.field_index(name).ok_or_else(|| {
        scene_error(
            scene,
            "load.kind",
            format!(
                "load kind `{}` needs a field `{name}`, model `{}` has fields {}",
                scene.load.kind.as_str(),
                spec.name,
                spec.fields.join(", ")
            ),
        )
    })
}

/// Builds the problem of `scene` for `model` (parameters already set).
/// `perturbation` adds a uniform fixed load on `w` (the envelope), used to follow the wrinkled
/// branch in path following.
pub fn build_problem<M: EnergyModel>(
    scene: &Scene,
    model: M,
    perturbation: f64,
) -> Result<Problem<M>, Error> {
    let spec = M::SPEC;
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
    let u = field(scene, spec, "u")?;
    let v = field(scene, spec, "v")?;
    let w = field(scene, spec, "w")?;
    let fixed = |edge: &str, field: usize, value: f64| DirichletCondition {
        edge: edge.into(),
        field,
        value,
        value_per_load: 0.0,
    };
    let mut conditions = Vec::new();
    let mut tractions = Vec::new();
    match scene.load.kind {
        LoadKind::Biaxial => {
            conditions.push(fixed("centre", u, 0.0));
            conditions.push(fixed("centre", v, 0.0));
            conditions.push(fixed("right_middle", v, 0.0));
            for edge in ["left", "right", "bottom", "top"] {
                conditions.push(fixed(edge, w, 0.0));
            }
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
        }
        LoadKind::Strip => {
            for edge in ["left", "right"] {
                conditions.push(fixed(edge, v, 0.0));
                conditions.push(fixed(edge, w, 0.0));
            }
            conditions.push(fixed("left", u, 0.0));
            conditions.push(DirichletCondition {
                edge: "right".into(),
                field: u,
                value: 0.0,
                value_per_load: 1.0,
            });
        }
    }
    // Any further field (rotations of a plate model, imaginary envelope, mean deflection) is
    // clamped like the envelope on every edge where the envelope is.
    let envelope_edges: Vec<String> = conditions
        .iter()
        .filter(|c| c.field == w)
        .map(|c| c.edge.clone())
        .collect();
    for (k, _) in spec
        .fields
        .iter()
        .enumerate()
        .filter(|(k, _)| ![u, v, w].contains(k))
    {
        let edges = envelope_edges.clone();
        for edge in edges {
            conditions.push(fixed(&edge, k, 0.0));
        }
    }
    let body = if perturbation != 0.0 {
        vec![BodyLoad {
            field: w,
            value: perturbation,
            proportional: false,
        }]
    } else {
        vec![]
    };
    Problem::new(model, mesh, &conditions, &tractions, &body)
        .map_err(|e| Error::Solver(format!("setting up the problem: {e}")))
}
