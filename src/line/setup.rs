//! From a line scene to a discrete [`Problem`]: the mesh of $`[0, L]`$, the element the model
//! needs, supports and the axial load by field role, parameters and their profiles.
//!
//! * **Element**: the cubic Hermite line (`Hermite2`, $`C^1`$) when the model reads a second
//!   derivative, the quadratic Lagrange line (`Line3`) otherwise.
//! * **Ends** `left` ($`X = 0`$) and `right` ($`X = L`$), each `[load.boundary.NAME]`
//!   (`load.kind = "boundaries"`): `transverse = "clamped"` holds every transverse field with
//!   all its nodal components (value and slope on Hermite2), `"simply_supported"` their
//!   values, `"free"` nothing; `in_plane` acts on the axial displacement: `"fixed"`,
//!   `{ displacement = [u, "free"], displacement_per_load = [du, "free"] }` (end shortening
//!   $`\propto\lambda`$) or `{ traction = [t, 0], traction_per_load = [dt, 0] }`, the end
//!   force along the outward normal ($`-X`$ at `left`, $`+X`$ at `right`; negative
//!   compresses).
//! * **Parameters** as on a plane ([`crate::setup::configure_model`]), and
//!   `[model.profiles] NAME = [[X, value], …]`: a parameter declared `[varying]` as a
//!   piecewise-linear function of $`X`$ ([`ParameterProfile`]); its `model.parameters` value,
//!   when absent, is the profile's first.

use super::layout::LineLayout;
use crate::error::Error;
use crate::scene::{BoundarySpec, Component, InPlane, LoadKind, Scene, Transverse, Wavenumber};
use crate::setup::scene_error;
use std::sync::Arc;
use wrinkle_runtime::fem::{
    DirichletCondition, ElementKind, Loads, Mesh, NodalComponent, ParameterProfile, PointLoad,
    ProfileAxis,
};
use wrinkle_runtime::problem::{Problem, ProblemError};
use wrinkle_runtime::{Derivative, EnergyModel};

/// The ends of a line mesh and their outward normals along X.
const ENDS: [(&str, f64); 2] = [("left", -1.0), ("right", 1.0)];

/// The layout of `M` on a line, or a scene error naming `model.name`.
pub fn line_layout_of<M: EnergyModel>(scene: &Scene) -> Result<LineLayout, Error> {
    LineLayout::from_spec(M::SPEC).map_err(|message| scene_error(scene, "model.name", message))
}

/// The element a model needs on a line: Hermite2 when its jet reads a second derivative.
pub fn line_element_of(spec: &wrinkle_runtime::ModelSpec) -> ElementKind {
    let second = spec
        .jet
        .iter()
        .any(|entry| !matches!(entry.derivative, Derivative::Value | Derivative::X));
    if second {
        ElementKind::Hermite2
    } else {
        ElementKind::Line3
    }
}

/// The carrier wavenumber $`Q`$ of a line scene: `model.wavenumber`, which must be a number.
pub fn line_wavenumber(scene: &Scene) -> Result<f64, Error> {
    match scene.model.wavenumber {
        Wavenumber::Fixed(q) => Ok(q),
        Wavenumber::Auto => Err(scene_error(
            scene,
            "model.wavenumber",
            "a line domain needs a fixed wavenumber Q (1/mm): the envelopes' carrier and the \
             window of the resolved deflection's local amplitude (\"auto\" is for plane domains)",
        )),
    }
}

/// The problem of a line scene for a model instance with its parameters set
/// ([`configure_line_model`]), without imperfection.
pub fn build_line_problem<M: EnergyModel>(scene: &Scene, model: M) -> Result<Problem<M>, Error> {
    let layout = line_layout_of::<M>(scene)?;
    if scene.load.kind != LoadKind::Boundaries {
        return Err(scene_error(
            scene,
            "load.kind",
            "a line domain takes its supports and load from [load.boundary.left] and \
             [load.boundary.right] only: set load.kind = \"boundaries\"",
        ));
    }
    let kind = line_element_of(M::SPEC);
    let mesh = Mesh::line(
        scene.geometry.length_x,
        scene.mesh.elements_x,
        scene.mesh.grading,
        kind,
    )
    .map_err(|e| scene_error(scene, "mesh", e.to_string()))?;
    let (conditions, loads) = pose_ends(scene, &layout, kind)?;
    let mut problem = Problem::new(model, Arc::new(mesh), &conditions, &loads)
        .map_err(|e| problem_error(scene, "load.boundary", e))?;
    problem
        .set_parameter_profiles(profiles(scene)?)
        .map_err(|e| problem_error(scene, "model.profiles", e))?;
    Ok(problem)
}

fn problem_error(scene: &Scene, key: &str, error: ProblemError) -> Error {
    match &error {
        ProblemError::ParameterNotVarying { parameter, .. } => {
            scene_error(scene, &format!("{key}.{parameter}"), error.to_string())
        }
        ProblemError::Dofs(_) => scene_error(scene, key, error.to_string()),
        other => Error::Solver(format!("setting up the problem: {other}")),
    }
}

/// The scene's profiles along X.
fn profiles(scene: &Scene) -> Result<Vec<(String, ParameterProfile)>, Error> {
    scene
        .model
        .profiles
        .iter()
        .map(|(name, table)| {
            ParameterProfile::new(ProfileAxis::X, table.clone())
                .map(|profile| (name.clone(), profile))
                .map_err(|e| scene_error(scene, &format!("model.profiles.{name}"), e.to_string()))
        })
        .collect()
}

/// Sets the model's parameters ([`crate::setup::configure_model`] with $`Q`$), a profiled
/// parameter absent from `model.parameters` taking its profile's first value.
pub fn configure_line_model<M: EnergyModel>(
    scene: &Scene,
    model: &mut M,
    wavenumber: f64,
) -> Result<(), Error> {
    let mut completed = scene.clone();
    for (name, table) in &scene.model.profiles {
        if let Some(first) = table.first()
            && M::SPEC.parameter_index(name).is_some()
        {
            completed
                .model
                .parameters
                .entry(name.clone())
                .or_insert(first[1]);
        }
    }
    crate::setup::configure_model(&completed, model, wavenumber)
}

/// Conditions and loads of the two ends (module documentation).
fn pose_ends(
    scene: &Scene,
    layout: &LineLayout,
    kind: ElementKind,
) -> Result<(Vec<DirichletCondition>, Loads), Error> {
    if let Some(name) = scene
        .load
        .boundary
        .keys()
        .find(|name| ENDS.iter().all(|(end, _)| end != name))
    {
        return Err(scene_error(
            scene,
            &format!("load.boundary.{name}"),
            format!("a line has two ends, `left` and `right`; no boundary `{name}`"),
        ));
    }
    let (mut conditions, mut loads) = (Vec::new(), Loads::default());
    for (end, normal) in ENDS {
        let Some(spec) = scene.load.boundary.get(end) else {
            continue;
        };
        conditions.extend(transverse_conditions(spec, layout, kind, end));
        axial_conditions(
            scene,
            spec,
            layout.axial,
            (end, normal),
            &mut conditions,
            &mut loads,
        )?;
    }
    Ok((conditions, loads))
}

fn transverse_conditions(
    spec: &BoundarySpec,
    layout: &LineLayout,
    kind: ElementKind,
    end: &str,
) -> Vec<DirichletCondition> {
    let fields = layout.transverse();
    match spec.transverse.unwrap_or(Transverse::Free) {
        Transverse::Clamped => fields
            .iter()
            .flat_map(|&f| DirichletCondition::clamped(end, f, kind))
            .collect(),
        Transverse::SimplySupported => fields
            .iter()
            .map(|&f| DirichletCondition::fixed(end, f))
            .collect(),
        Transverse::Free => Vec::new(),
    }
}

fn axial_conditions(
    scene: &Scene,
    spec: &BoundarySpec,
    axial: usize,
    (end, normal): (&str, f64),
    conditions: &mut Vec<DirichletCondition>,
    loads: &mut Loads,
) -> Result<(), Error> {
    match spec.in_plane.unwrap_or(InPlane::Free) {
        InPlane::Free => {}
        InPlane::Fixed => conditions.push(DirichletCondition::fixed(end, axial)),
        InPlane::Displacement([along, _]) => {
            if let Component::Prescribed { value, per_load } = along {
                conditions.push(DirichletCondition::prescribed(end, axial, value, per_load));
            }
        }
        InPlane::Traction { value, per_load } => {
            if value[1] != 0.0 || per_load[1] != 0.0 {
                return Err(scene_error(
                    scene,
                    &format!("load.boundary.{end}"),
                    "a line's end force acts along the beam: the tangential traction must be 0",
                ));
            }
            for (force, proportional) in [(value[0], false), (per_load[0], true)] {
                if force != 0.0 {
                    loads.point_loads.push(PointLoad {
                        point: end.to_string(),
                        field: axial,
                        component: NodalComponent::Value,
                        value: normal * force,
                        proportional,
                    });
                }
            }
        }
    }
    Ok(())
}
