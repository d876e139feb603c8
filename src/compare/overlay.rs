//! The models' wrinkles at one load, overlaid (`compare_profiles.png/.svg`): along the wave
//! direction through the largest wrinkle, the plate's physical deflection $`w/h`$ and, for each
//! envelope model, the band $`\pm 2|w_1|/h`$ its carrier fills — the picture that says whether
//! an envelope follows the plate's wrinkles, not only its load–amplitude curve.
//!
//! The states are read back from the `fields_load_L.vtu` each run wrote at the common load
//! (`output.vtu_loads`), through the model's field roles ([`crate::physics::Layout`]): nothing is
//! recomputed.

use crate::error::{Error, io_error};
use crate::output::{Profile, ProfilePlot, Quantity, plot_profiles};
use crate::physics::{Layout, Snapshot};
use crate::results::fields_file_at;
use crate::scene::Scene;
use std::path::Path;
use wrinkle_runtime::fem::{ElementKind, Mesh};

/// A model's state at one load, read back from its VTU file ([`read_state`]).
pub struct ModelState {
    /// Registry name of the model.
    pub model: String,
    /// The Q8 mesh of the file.
    pub mesh: Mesh,
    /// The model's fields by role.
    pub layout: Layout,
    /// The fields, node-major.
    pub values: Vec<f64>,
    /// The carrier wavenumber (0 for a plate).
    pub wavenumber: f64,
}

impl ModelState {
    /// The state with the wave direction `direction` (radians from X).
    pub fn snapshot<'a>(&'a self, direction: f64) -> Snapshot<'a> {
        Snapshot {
            mesh: &self.mesh,
            layout: &self.layout,
            values: &self.values,
            wavenumber: self.wavenumber,
            direction,
        }
    }
}

/// Reads `MODEL/fields_load_L.vtu`: the Q8 mesh, the model's fields node-major, the carrier
/// wavenumber of the field data (0 for a plate). `None` when the file is missing (the path did
/// not reach the load) or not readable.
pub fn read_state(
    directory: &Path,
    model: &str,
    load: f64,
    requested: &[f64],
) -> Option<ModelState> {
    use vtkio::model::{Attribute, DataSet, Piece, VertexNumbers};
    let spec = wrinkle_models::catalogue()
        .into_iter()
        .find(|spec| spec.name == model)?;
    let layout = Layout::from_spec(spec).ok()?;
    let path = directory.join(model).join(fields_file_at(load, requested));
    let xml = std::fs::read_to_string(&path).ok()?;
    let vtk = vtkio::Vtk::parse_xml(xml.as_bytes()).ok()?;
    let DataSet::UnstructuredGrid { pieces, .. } = vtk.data else {
        return None;
    };
    let Piece::Inline(piece) = pieces.into_iter().next()? else {
        return None;
    };
    let points: Vec<f64> = piece.points.cast_into()?;
    let nodes: Vec<[f64; 2]> = points.chunks(3).map(|p| [p[0], p[1]]).collect();
    let VertexNumbers::XML { connectivity, .. } = piece.cells.cell_verts else {
        return None;
    };
    let connectivity = connectivity.into_iter().map(|n| n as usize).collect();
    let mesh = Mesh::new(ElementKind::Quad8, nodes, connectivity).ok()?;
    let fields = spec.fields;
    let mut values = vec![0.0; mesh.nodes.len() * fields.len()];
    for (f, name) in fields.iter().enumerate() {
        let array = piece
            .data
            .point
            .iter()
            .find_map(|attribute| match attribute {
                Attribute::DataArray(array) if array.name == *name => {
                    array.data.clone().cast_into::<f64>()
                }
                _ => None,
            })?;
        for (n, value) in array.into_iter().enumerate() {
            values[n * fields.len() + f] = value;
        }
    }
    let wavenumber = field_data_number(&xml, "wavenumber").unwrap_or(0.0);
    Some(ModelState {
        model: model.to_string(),
        mesh,
        layout,
        values,
        wavenumber,
    })
}

/// A number of the file's `<FieldData>` (vtkio does not read field data).
fn field_data_number(xml: &str, name: &str) -> Option<f64> {
    let block = &xml[xml.find("<FieldData>")?..xml.find("</FieldData>")?];
    let at = block.find(&format!("Name=\"{name}\""))?;
    let text = &block[at..];
    text[text.find('>')? + 1..text.find('<')?]
        .trim()
        .parse()
        .ok()
}

/// Writes `compare_profiles.png/.svg` for the `models` that reached `load` (at least two), or
/// nothing; says whether it wrote them. The line runs along the wave direction through the
/// largest envelope amplitude of the first envelope model (the plate's largest $`|w|`$ when
/// there is none), at `direction_degrees` from X.
pub fn write_profile_overlay(
    scene: &Scene,
    models: &[String],
    load: f64,
    direction_degrees: f64,
    directory: &Path,
) -> Result<bool, Error> {
    let direction = direction_degrees.to_radians();
    // Every model ran with the scene's VTU loads and `load` after them: the file names come
    // from that list (`fields_file_at` keeps them distinct).
    let requested: Vec<f64> = scene
        .output
        .vtu_loads
        .iter()
        .copied()
        .chain([load])
        .collect();
    let states: Vec<ModelState> = models
        .iter()
        .filter_map(|model| read_state(directory, model, load, &requested))
        .collect();
    if states.len() < 2 {
        return Ok(false);
    }
    let h = scene.material.thickness;
    let Some((peak, along_y)) = line_through_peak(&states, direction) else {
        return Ok(false);
    };
    let bounds = states[0].mesh.bounds();
    let axis = usize::from(along_y);
    let (low, high) = (bounds[2 * axis], bounds[2 * axis + 1]);
    let samples = 1600;
    let positions: Vec<f64> = (0..=samples)
        .map(|k| low + (high - low) * k as f64 / samples as f64)
        .collect();
    let point = |s: f64| if along_y { [peak[0], s] } else { [s, peak[1]] };
    let mut profiles = Vec::new();
    for state in &states {
        let snapshot = state.snapshot(direction);
        if state.layout.is_envelope() {
            // The band ±2|w₁|/h as one outline: along the top, back along the bottom.
            let top: Vec<(f64, f64)> = positions
                .iter()
                .filter_map(|&s| Some((s, snapshot.envelope_amplitude(point(s))? / h)))
                .collect();
            let mut outline = top.clone();
            outline.extend(top.iter().rev().map(|&(s, a)| (s, -a)));
            profiles.push(Profile {
                label: format!("{}: ±2|w₁| / h (the band its wrinkles fill)", state.model),
                points: outline,
            });
        } else {
            profiles.push(Profile {
                label: format!("{}: w / h", state.model),
                points: positions
                    .iter()
                    .map(|&s| (s, snapshot.deflection(point(s)) / h))
                    .collect(),
            });
        }
    }
    let coordinate = if along_y { "Y" } else { "X" };
    let (fixed, at) = if along_y {
        ("X", peak[0])
    } else {
        ("Y", peak[1])
    };
    let load_quantity = crate::results::load_quantity(scene);
    let plot = ProfilePlot {
        abscissa: Quantity::coordinate(coordinate),
        ordinate: Quantity::deflection_over_thickness(),
        location: format!(
            "along {coordinate} at {fixed} = {at:.1} mm (through the largest wrinkle), λ = {}",
            load_quantity.format_value(load)
        ),
        profiles,
    };
    let stem = directory.join("compare_profiles");
    plot_profiles(&stem, "Wrinkles of each model at the same load", &plot)
        .map_err(io_error(&stem))?;
    Ok(true)
}

/// The point of the largest envelope amplitude of the first envelope model (else the largest
/// $`|w|`$ of the first state) on a 201 × 201 grid, and whether the waves run along Y.
fn line_through_peak(states: &[ModelState], direction: f64) -> Option<([f64; 2], bool)> {
    let state = states
        .iter()
        .find(|s| s.layout.is_envelope())
        .unwrap_or(&states[0]);
    let snapshot = state.snapshot(direction);
    let bounds = state.mesh.bounds();
    let mut best: Option<([f64; 2], f64)> = None;
    for j in 0..=200 {
        for i in 0..=200 {
            let p = [
                bounds[0] + (bounds[1] - bounds[0]) * i as f64 / 200.0,
                bounds[2] + (bounds[3] - bounds[2]) * j as f64 / 200.0,
            ];
            let v = snapshot
                .envelope_amplitude(p)
                .unwrap_or_else(|| snapshot.deflection(p).abs());
            if best.is_none_or(|(_, b)| v > b) {
                best = Some((p, v));
            }
        }
    }
    let along_y = direction.sin().abs() > direction.cos().abs();
    best.map(|(p, _)| (p, along_y))
}
