//! From a scene to a discrete [`Problem`]: mesh, boundary conditions, loads, model parameters.
//!
//! **Boundaries.** Every condition and load is stated on a named boundary
//! (`load.boundary.NAME`, [`BoundarySpec`]): a transverse condition by field role and an
//! in-plane condition or traction (`docs/scenes.md`, "Boundaries"). The load kinds are presets
//! of such specifications ([`preset`]); a scene's `load.boundary` entries replace, part by
//! part, the preset's entry of the same boundary:
//! * `biaxial` (the paper's example 1): the normal traction $`t_n = -\lambda`$ (compression
//!   $`N_X = -\lambda`$, N/mm) on `left`/`right`, $`t_n = N_Y`$ (fixed) on `bottom`/`top`, the
//!   four edges clamped; the in-plane rigid-body motions removed at two points only
//!   ($`u = v = 0`$ at `centre`, $`v = 0`$ at `right_middle`), so the pre-buckling membrane state
//!   is exactly uniform and the problem symmetric;
//! * `strip` (example 2): `left` clamped and fixed, `right` clamped with $`u = \lambda`$ (mm) and
//!   $`v = 0`$; long sides free;
//! * `boundaries`: no preset.
//!
//! A boundary the mesh does not name, a traction on a point set, conflicting values at a node
//! and an in-plane problem left singular (a rigid motion nothing prevents) are scene errors
//! naming the key.

use crate::error::Error;
use crate::physics::Layout;
use crate::scene::{BoundarySpec, Component, InPlane, LoadKind, Scene, Transverse};
use std::collections::BTreeMap;
use std::sync::Arc;
use wrinkle_runtime::EnergyModel;
use wrinkle_runtime::fem::dofs::RigidMotion;
use wrinkle_runtime::fem::{DirichletCondition, Loads, Mesh, NormalTraction};
use wrinkle_runtime::problem::{Problem, ProblemError};

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
            "direction" => scene
                .model
                .direction
                .fixed_degrees()
                .unwrap_or(0.0)
                .to_radians(),
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
    Layout::from_spec(M::SPEC).map_err(|message| {
        let message = if crate::line::LineLayout::from_spec(M::SPEC).is_ok() {
            format!(
                "model `{}` is a line model and the scene's domain is a plane: set \
                 geometry.kind = \"line\" ({message})",
                M::SPEC.name
            )
        } else {
            message
        };
        scene_error(scene, "model.name", message)
    })
}

/// The boundary specifications of a load preset (module documentation), by boundary name.
pub fn preset(kind: LoadKind, tension_y: f64) -> BTreeMap<String, BoundarySpec> {
    let clamped = |in_plane| BoundarySpec {
        transverse: Some(Transverse::Clamped),
        in_plane: Some(in_plane),
    };
    let held = |in_plane| BoundarySpec {
        transverse: None,
        in_plane: Some(in_plane),
    };
    let fixed_component = Component::Prescribed {
        value: 0.0,
        per_load: 0.0,
    };
    let compressed = InPlane::Traction {
        value: [0.0, 0.0],
        per_load: [-1.0, 0.0],
    };
    let pulled = InPlane::Traction {
        value: [tension_y, 0.0],
        per_load: [0.0, 0.0],
    };
    let entries = match kind {
        LoadKind::Biaxial => vec![
            ("left", clamped(compressed)),
            ("right", clamped(compressed)),
            ("bottom", clamped(pulled)),
            ("top", clamped(pulled)),
            ("centre", held(InPlane::Fixed)),
            (
                "right_middle",
                held(InPlane::Displacement([Component::Free, fixed_component])),
            ),
        ],
        LoadKind::Strip => vec![
            ("left", clamped(InPlane::Fixed)),
            (
                "right",
                clamped(InPlane::Displacement([
                    Component::Prescribed {
                        value: 0.0,
                        per_load: 1.0,
                    },
                    fixed_component,
                ])),
            ),
        ],
        LoadKind::Boundaries => Vec::new(),
    };
    entries
        .into_iter()
        .map(|(name, spec)| (name.to_string(), spec))
        .collect()
}

/// The scene's boundary specifications: its preset, each entry of `load.boundary` replacing
/// the preset's `transverse` and `in_plane` where it gives them.
pub fn boundary_specs(scene: &Scene) -> BTreeMap<String, BoundarySpec> {
    let mut specs = preset(scene.load.kind, scene.load.tension_y);
    for (name, given) in &scene.load.boundary {
        let spec = specs.entry(name.clone()).or_default();
        spec.transverse = given.transverse.or(spec.transverse);
        spec.in_plane = given.in_plane.or(spec.in_plane);
    }
    specs
}

/// Whether the scene's boundaries are the `biaxial` preset's (by the preset or written out):
/// the clamped rectangle of the closed form (42), when the mesh is the rectangle.
pub fn is_biaxial_rectangle(scene: &Scene) -> bool {
    boundary_specs(scene) == preset(LoadKind::Biaxial, scene.load.tension_y)
}

/// Whether $`\lambda`$ scales a prescribed displacement (mm) rather than a traction (N/mm):
/// some displacement component has a non-zero rate.
pub fn load_is_displacement(scene: &Scene) -> bool {
    boundary_specs(scene).values().any(|spec| {
        matches!(spec.in_plane, Some(InPlane::Displacement(components))
            if components.iter().any(|c| matches!(c, Component::Prescribed { per_load, .. } if *per_load != 0.0)))
    })
}

/// The mesh of the scene: the file of `mesh.file` (relative to the scene file) or the
/// structured rectangle.
pub fn build_mesh(scene: &Scene) -> Result<Mesh, Error> {
    if scene.mesh.file.is_empty() {
        return Mesh::graded_rectangle(
            [scene.geometry.length_x, scene.geometry.length_y],
            [scene.mesh.elements_x, scene.mesh.elements_y],
            scene.mesh.axis_gradings(),
        )
        .map_err(|e| scene_error(scene, "mesh", e.to_string()));
    }
    let path = mesh_file_path(scene);
    let error = |message: String| scene_error(scene, "mesh.file", message);
    let bytes = std::fs::read(&path)
        .map_err(|e| error(format!("cannot read `{}`: {e}", path.display())))?;
    let mesh = wrinkle_runtime::fem::gmsh::read_msh(&bytes)
        .map_err(|e| error(format!("`{}`: {e}", path.display())))?;
    check_extents(scene, &mesh)?;
    Ok(mesh)
}

/// `mesh.file` resolved against the scene file's folder (as given for a built-in scene).
pub fn mesh_file_path(scene: &Scene) -> std::path::PathBuf {
    let file = std::path::Path::new(&scene.mesh.file);
    if file.is_absolute() || scene.source == crate::scene::BUILT_IN_SOURCE {
        return file.to_path_buf();
    }
    std::path::Path::new(&scene.source)
        .parent()
        .map_or_else(|| file.to_path_buf(), |folder| folder.join(file))
}

/// `geometry.lx` and `geometry.ly` must be the extents of a file's mesh: they set the
/// wavenumber search range, the closed form and the validity checks.
fn check_extents(scene: &Scene, mesh: &Mesh) -> Result<(), Error> {
    let [x0, x1, y0, y1] = mesh.bounds();
    for (key, given, extent) in [
        ("geometry.lx", scene.geometry.length_x, x1 - x0),
        ("geometry.ly", scene.geometry.length_y, y1 - y0),
    ] {
        if (given - extent).abs() > 1e-9 * extent.abs().max(given.abs()) {
            return Err(scene_error(
                scene,
                key,
                format!(
                    "the mesh file `{}` spans {extent} mm here; set {key} = {extent}",
                    scene.mesh.file
                ),
            ));
        }
    }
    Ok(())
}

/// The conditions and loads of the boundary specifications, checked against the mesh.
struct Posed {
    conditions: Vec<DirichletCondition>,
    loads: Loads,
}

/// The error of boundary `name`: attributed to its `load.boundary` entry when the scene has
/// one, to the preset (`load.kind`) otherwise.
fn boundary_error(scene: &Scene, name: &str, message: String) -> Error {
    if scene.load.boundary.contains_key(name) {
        scene_error(scene, &format!("load.boundary.{name}"), message)
    } else {
        let preset = scene.load.kind.as_str();
        scene_error(scene, "load.kind", format!("preset `{preset}`: {message}"))
    }
}

/// Turns the boundary specifications into conditions by field role and loads.
fn pose(
    scene: &Scene,
    mesh: &Mesh,
    layout: &Layout,
    specs: &BTreeMap<String, BoundarySpec>,
) -> Result<Posed, Error> {
    let [u, v] = layout.in_plane;
    let mut posed = Posed {
        conditions: Vec::new(),
        loads: Loads::default(),
    };
    for (name, spec) in specs {
        if mesh.boundary_nodes(name).is_none() {
            let available = mesh.boundary_names().join(", ");
            let message = format!("the mesh has no boundary `{name}` (boundaries: {available})");
            return Err(boundary_error(scene, name, message));
        }
        let transverse_fields = match spec.transverse.unwrap_or(Transverse::Free) {
            Transverse::Clamped => layout.transverse.clone(),
            Transverse::SimplySupported => layout.deflection_fields(),
            Transverse::Free => Vec::new(),
        };
        posed.conditions.extend(
            transverse_fields
                .iter()
                .map(|&f| DirichletCondition::fixed(name, f)),
        );
        match spec.in_plane.unwrap_or(InPlane::Free) {
            InPlane::Free => {}
            InPlane::Fixed => posed.conditions.extend([
                DirichletCondition::fixed(name, u),
                DirichletCondition::fixed(name, v),
            ]),
            InPlane::Displacement(components) => {
                for (field, component) in [u, v].into_iter().zip(components) {
                    if let Component::Prescribed { value, per_load } = component {
                        posed
                            .conditions
                            .push(DirichletCondition::prescribed(name, field, value, per_load));
                    }
                }
            }
            InPlane::Traction { value, per_load } => {
                if !mesh.edges.contains_key(name) {
                    let message = format!(
                        "a traction acts on an edge; `{name}` is a point set (hold it with a displacement, or load an edge)"
                    );
                    return Err(boundary_error(scene, name, message));
                }
                for (pair, proportional) in [(value, false), (per_load, true)] {
                    if pair != [0.0, 0.0] {
                        posed.loads.normal_tractions.push(NormalTraction {
                            edge: name.clone(),
                            fields: [u, v],
                            normal: pair[0],
                            tangential: pair[1],
                            proportional,
                        });
                    }
                }
            }
        }
    }
    Ok(posed)
}

/// Builds the problem of `scene` for `model` (parameters already set), without imperfection:
/// the mesh ([`build_mesh`]), the boundary specifications ([`boundary_specs`]) turned into
/// conditions by field role and loads, and the checks that the in-plane problem holds.
pub fn build_problem<M: EnergyModel>(scene: &Scene, model: M) -> Result<Problem<M>, Error> {
    let layout = layout_of::<M>(scene)?;
    let mesh = build_mesh(scene)?;
    let specs = boundary_specs(scene);
    let posed = pose(scene, &mesh, &layout, &specs)?;
    let problem = Problem::new(model, Arc::new(mesh), &posed.conditions, &posed.loads)
        .map_err(|e| problem_error(scene, e))?;
    check_rigid_motions(scene, &problem, &layout)?;
    Ok(problem)
}

/// A conflict between conditions is the scene's; anything else the solver's.
fn problem_error(scene: &Scene, error: ProblemError) -> Error {
    match error {
        ProblemError::Dofs(dofs) => scene_error(
            scene,
            "load.boundary",
            format!("the boundary conditions do not fit together: {dofs}"),
        ),
        other => Error::Solver(format!("setting up the problem: {other}")),
    }
}

/// A scene error when the conditions leave a rigid in-plane motion free (the in-plane
/// stiffness would be singular), or a plate's deflection held nowhere.
fn check_rigid_motions<M: EnergyModel>(
    scene: &Scene,
    problem: &Problem<M>,
    layout: &Layout,
) -> Result<(), Error> {
    let mesh = problem.assembler.mesh();
    let free = problem.dofs().free_rigid_motions(mesh, layout.in_plane);
    if let Some(motion) = free.first() {
        let what = match motion {
            RigidMotion::TranslationX => "a rigid translation along X".to_string(),
            RigidMotion::TranslationY => "a rigid translation along Y".to_string(),
            RigidMotion::Rotation { centre } => format!(
                "a rigid rotation in the plane (about ({:.6}, {:.6}))",
                centre[0], centre[1]
            ),
        };
        return Err(scene_error(
            scene,
            "load.boundary",
            format!(
                "the in-plane problem is singular: nothing prevents {what}; hold a boundary in its plane (`in_plane = \"fixed\"` or a displacement) or a point, e.g. `[load.boundary.centre] in_plane = \"fixed\"` with `[load.boundary.right_middle] in_plane = {{ displacement = [\"free\", 0.0] }}`"
            ),
        ));
    }
    if let crate::physics::DeflectionKind::Plate { deflection } = layout.kind {
        let held = (0..mesh.nodes.len()).any(|n| problem.dofs().free(n, deflection).is_none());
        if !held {
            return Err(scene_error(
                scene,
                "load.boundary",
                "the plate's deflection is held nowhere (every boundary transversally free): \
                 clamp or simply support a boundary",
            ));
        }
    }
    Ok(())
}
