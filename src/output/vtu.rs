//! VTK XML unstructured-grid files (`.vtu`, binary inline base64, readable by ParaView and
//! meshio): finite element fields on the Q8 mesh ([`write_fields_vtu`]) and a sampled surface
//! ([`write_surface_vtu`]).
//!
//! Every file carries [`FieldData`] — at least the load $`\lambda`$ and its unit
//! ([`FieldData::load`]) — as the dataset's `<FieldData>`, and any extra point arrays the caller
//! computed ([`PointArray`]: stress resultants, the physical deflection, …). vtkio 0.6 does not
//! write field data, so the block is inserted into its output; vtkio's reader skips it, VTK's and
//! meshio's read it.
//!
//! Field data holds numbers only, because meshio (the common Python reader) refuses a file with a
//! `String` array ("Illegal data type 'String'"): a number is a one-tuple `Float64` array, a text
//! a `UInt8` array of its UTF-8 bytes (in Python: `bytes(mesh.field_data["model"]).decode()`).

use super::files::write_atomically;
use super::grid::GridField;
use super::{OutputError, check_length, invalid};
use std::collections::BTreeSet;
use std::io;
use std::path::Path;
use vtkio::model::{
    Attribute, Attributes, ByteOrder, CellType, Cells, DataArray, DataSet, UnstructuredGridPiece,
    Version, VertexNumbers, Vtk,
};
use wrinkle_runtime::fem::Mesh;

/// One point array: `components` values per point, point after point.
#[derive(Clone, Debug, PartialEq)]
pub struct PointArray {
    /// Array name shown by ParaView, e.g. `"N_X"`; unique within a file.
    pub name: String,
    /// Values per point: 1 (scalar) or 3 (vector).
    pub components: u32,
    /// `components × points` values.
    pub values: Vec<f64>,
}

impl PointArray {
    /// A scalar array (one value per point).
    pub fn scalar(name: impl Into<String>, values: Vec<f64>) -> Self {
        PointArray {
            name: name.into(),
            components: 1,
            values,
        }
    }

    /// A vector array (three values per point).
    pub fn vector(name: impl Into<String>, values: &[[f64; 3]]) -> Self {
        PointArray {
            name: name.into(),
            components: 3,
            values: values.iter().flatten().copied().collect(),
        }
    }
}

/// One value of the dataset's field data.
#[derive(Clone, Debug, PartialEq)]
pub enum FieldValue {
    /// A number (a `Float64` array of one tuple).
    Number(f64),
    /// A text (a `UInt8` array of its UTF-8 bytes, one tuple per byte: meshio rejects the VTK
    /// type `String`).
    Text(String),
}

/// Values attached to the whole dataset (VTK field data), in order, e.g. the load and its unit.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct FieldData {
    /// `(name, value)` pairs; names unique.
    pub entries: Vec<(String, FieldValue)>,
}

impl FieldData {
    /// No entries.
    pub fn new() -> Self {
        FieldData::default()
    }

    /// `load` = $`\lambda`$ and `load_unit` = `unit` (e.g. `"N/mm"` for the biaxial load, `"mm"`
    /// for an end displacement).
    pub fn load(load: f64, unit: impl Into<String>) -> Self {
        FieldData::new()
            .with_number("load", load)
            .with_text("load_unit", unit)
    }

    /// Adds a number.
    pub fn with_number(mut self, name: impl Into<String>, value: f64) -> Self {
        self.entries.push((name.into(), FieldValue::Number(value)));
        self
    }

    /// Adds a text.
    pub fn with_text(mut self, name: impl Into<String>, value: impl Into<String>) -> Self {
        self.entries
            .push((name.into(), FieldValue::Text(value.into())));
        self
    }

    /// The `<FieldData>` XML block (empty string when there are no entries).
    fn to_xml(&self) -> io::Result<String> {
        if self.entries.is_empty() {
            return Ok(String::new());
        }
        check_unique_names(self.entries.iter().map(|(name, _)| name.as_str()))?;
        let mut xml = String::from("<FieldData>");
        for (name, value) in &self.entries {
            let name = escape_attribute(name);
            match value {
                FieldValue::Number(number) => {
                    if !number.is_finite() {
                        return Err(invalid(
                            format!("field data `{name}`"),
                            format!("must be finite, got {number}"),
                        ));
                    }
                    xml.push_str(&format!(
                        "<DataArray type=\"Float64\" Name=\"{name}\" NumberOfTuples=\"1\" \
                         format=\"ascii\">{number:e}</DataArray>"
                    ));
                }
                FieldValue::Text(text) => {
                    if text.is_empty() {
                        // meshio fails on an empty array (its text is missing).
                        return Err(invalid(format!("field data `{name}`"), "must not be empty"));
                    }
                    let bytes: Vec<String> = text.bytes().map(|b| b.to_string()).collect();
                    xml.push_str(&format!(
                        "<DataArray type=\"UInt8\" Name=\"{name}\" NumberOfTuples=\"{}\" \
                         format=\"ascii\">{}</DataArray>",
                        bytes.len(),
                        bytes.join(" ")
                    ));
                }
            }
        }
        xml.push_str("</FieldData>");
        Ok(xml)
    }
}

/// Writes fields of a Q8 mesh as a `.vtu` file: `POINTS` at $`(X, Y, 0)`$, one cell of VTK type 23
/// (`QuadraticQuad`, corners then mid-sides, the order of [`Mesh::elements`]) per element, one
/// scalar point array per unknown field, the `extra` point arrays, and `field_data`.
///
/// `nodal_values` is node-major: the value of field `f` at node `n` is
/// `nodal_values[n * field_names.len() + f]`.
///
/// Errors (kind [`io::ErrorKind::InvalidInput`]): wrong array lengths, empty or repeated names,
/// an element referring to a missing node, a non-finite coordinate or field-data number.
pub fn write_fields_vtu(
    path: &Path,
    mesh: &Mesh,
    field_names: &[&str],
    nodal_values: &[f64],
    extra: &[PointArray],
    field_data: &FieldData,
) -> io::Result<()> {
    write_fields_vtu_with_cells(
        path,
        mesh,
        field_names,
        nodal_values,
        extra,
        &[],
        field_data,
    )
}

/// [`write_fields_vtu`] with cell arrays besides: `cells` hold one value (or three) per
/// element, in the order of [`Mesh::elements`] (e.g. element means of the stress resultants).
pub fn write_fields_vtu_with_cells(
    path: &Path,
    mesh: &Mesh,
    field_names: &[&str],
    nodal_values: &[f64],
    extra: &[PointArray],
    cells: &[PointArray],
    field_data: &FieldData,
) -> io::Result<()> {
    check_arrays(cells, mesh.element_count())?;
    check_unique_names(cells.iter().map(|array| array.name.as_str()))?;
    let node_count = mesh.nodes.len();
    let field_count = field_names.len();
    check_length("nodal values", node_count * field_count, nodal_values.len())?;
    check_unique_names(
        field_names
            .iter()
            .copied()
            .chain(extra.iter().map(|array| array.name.as_str())),
    )?;
    check_arrays(extra, node_count)?;
    if mesh.nodes.iter().flatten().any(|c| !c.is_finite()) {
        return Err(invalid("mesh", "node coordinates must be finite"));
    }
    let mut connectivity = Vec::with_capacity(mesh.connectivity.len());
    for (element, nodes) in mesh.elements().enumerate() {
        for &node in nodes {
            if node >= node_count {
                return Err(OutputError::NodeOutOfRange {
                    element,
                    node,
                    node_count,
                }
                .into());
            }
            connectivity.push(node as u64);
        }
    }
    let per_element = mesh.kind.nodes() as u64;
    let offsets = (1..=mesh.element_count() as u64)
        .map(|e| per_element * e)
        .collect();
    let points: Vec<f64> = mesh.nodes.iter().flat_map(|&[x, y]| [x, y, 0.0]).collect();

    let mut point_arrays = Vec::with_capacity(field_count + extra.len());
    for (f, name) in field_names.iter().enumerate() {
        let values: Vec<f64> = (0..node_count)
            .map(|n| nodal_values[n * field_count + f])
            .collect();
        point_arrays.push(scalar_array(name, values));
    }
    point_arrays.extend(extra.iter().map(data_array));
    let piece = UnstructuredGridPiece {
        points: points.into(),
        cells: Cells {
            cell_verts: VertexNumbers::XML {
                connectivity,
                offsets,
            },
            types: vec![cell_type(mesh.kind.vtk_cell_type())?; mesh.element_count()],
        },
        data: Attributes {
            point: point_arrays,
            cell: cells.iter().map(data_array).collect(),
        },
    };
    write_piece(path, "wrinkle finite element fields", piece, field_data)
}

/// The vtkio cell type of a VTK cell type number (those of the runtime's elements).
fn cell_type(number: u8) -> io::Result<CellType> {
    match number {
        3 => Ok(CellType::Line),
        21 => Ok(CellType::QuadraticEdge),
        23 => Ok(CellType::QuadraticQuad),
        other => Err(invalid(
            "mesh",
            format!("no VTK cell of type {other} is written"),
        )),
    }
}

/// Writes a sampled surface as a `.vtu` file: the grid points of `surface` placed at
/// $`(X, Y, s\,v)`$ with $`v`$ the sampled value (typically the physical deflection $`w`$ in mm)
/// and $`s`$ = `vertical_scale`, `(columns − 1) × (rows − 1)` cells of type 9 (`Quad`), the point
/// array of the unscaled values named after the quantity's description in snake case
/// (`physical_deflection` for [`crate::output::Quantity::deflection`]: not its symbol `w`, which
/// names the envelope in the fields' files), the `extra` point arrays (one value or vector per grid
/// point, in the order of [`GridField::values`]) and `field_data`.
///
/// The points already sit at the sampled height: the surface needs no warping (warping it by its
/// own array would double the height).
///
/// Errors (kind [`io::ErrorKind::InvalidInput`]): an invalid grid, non-finite values or scale,
/// wrong array lengths, repeated names.
pub fn write_surface_vtu(
    path: &Path,
    surface: &GridField,
    vertical_scale: f64,
    extra: &[PointArray],
    field_data: &FieldData,
) -> io::Result<()> {
    surface.validate()?;
    if !vertical_scale.is_finite() {
        return Err(invalid(
            "vertical scale",
            format!("must be finite, got {vertical_scale}"),
        ));
    }
    if let Some(index) = surface.values.iter().position(|v| !v.is_finite()) {
        let (i, j) = (index % surface.columns, index / surface.columns);
        return Err(invalid(
            format!("surface `{}`", surface.quantity.short_name()),
            format!(
                "not finite at (X, Y) = {:?}: {}",
                surface.point(i, j),
                surface.values[index]
            ),
        ));
    }
    let name = array_name(&surface.quantity);
    check_unique_names(
        std::iter::once(name.as_str()).chain(extra.iter().map(|a| a.name.as_str())),
    )?;
    let (columns, rows) = (surface.columns, surface.rows);
    check_arrays(extra, columns * rows)?;
    let mut points = Vec::with_capacity(3 * columns * rows);
    for j in 0..rows {
        for i in 0..columns {
            let [x, y] = surface.point(i, j);
            points.extend([x, y, vertical_scale * surface.values[j * columns + i]]);
        }
    }
    let corner = |i: usize, j: usize| (j * columns + i) as u64;
    let cell_count = (columns - 1) * (rows - 1);
    let mut connectivity = Vec::with_capacity(4 * cell_count);
    for j in 0..rows - 1 {
        for i in 0..columns - 1 {
            connectivity.extend([
                corner(i, j),
                corner(i + 1, j),
                corner(i + 1, j + 1),
                corner(i, j + 1),
            ]);
        }
    }
    let offsets = (1..=cell_count as u64).map(|c| 4 * c).collect();
    let mut point_arrays = vec![scalar_array(&name, surface.values.clone())];
    point_arrays.extend(extra.iter().map(data_array));
    let piece = UnstructuredGridPiece {
        points: points.into(),
        cells: Cells {
            cell_verts: VertexNumbers::XML {
                connectivity,
                offsets,
            },
            types: vec![CellType::Quad; cell_count],
        },
        data: Attributes {
            point: point_arrays,
            cell: Vec::new(),
        },
    };
    write_piece(path, "wrinkle sampled surface", piece, field_data)
}

/// A VTU array name for a quantity: its description in snake case (`physical_deflection`), else
/// its symbol, else `value`.
fn array_name(quantity: &crate::output::Quantity) -> String {
    let words: Vec<&str> = quantity.description.split_whitespace().collect();
    if !words.is_empty() {
        words.join("_")
    } else if !quantity.symbol.trim().is_empty() {
        quantity.symbol.clone()
    } else {
        "value".to_string()
    }
}

fn check_arrays(arrays: &[PointArray], point_count: usize) -> io::Result<()> {
    for array in arrays {
        if !matches!(array.components, 1 | 3) {
            return Err(invalid(
                format!("point array `{}`", array.name),
                format!("needs 1 or 3 components, got {}", array.components),
            ));
        }
        check_length(
            format!("point array `{}`", array.name),
            array.components as usize * point_count,
            array.values.len(),
        )?;
    }
    Ok(())
}

fn check_unique_names<'a>(names: impl Iterator<Item = &'a str>) -> io::Result<()> {
    let mut seen = BTreeSet::new();
    for name in names {
        if name.trim().is_empty() || !seen.insert(name) {
            return Err(OutputError::BadArrayName(name.to_string()).into());
        }
    }
    Ok(())
}

fn scalar_array(name: &str, values: Vec<f64>) -> Attribute {
    Attribute::DataArray(DataArray::scalars(name, 1).with_data(values))
}

fn data_array(array: &PointArray) -> Attribute {
    let data = if array.components == 3 {
        DataArray::vectors(array.name.as_str())
    } else {
        DataArray::scalars(array.name.as_str(), 1)
    };
    Attribute::DataArray(data.with_data(array.values.clone()))
}

fn escape_attribute(text: &str) -> String {
    text.replace('&', "&amp;")
        .replace('"', "&quot;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
}

/// Encodes the file with vtkio, inserts the field data after the dataset's opening tag and
/// writes it atomically.
fn write_piece(
    path: &Path,
    title: &str,
    piece: UnstructuredGridPiece,
    field_data: &FieldData,
) -> io::Result<()> {
    let field_xml = field_data.to_xml()?;
    let vtk = Vtk {
        version: Version::new((1, 0)),
        title: title.to_string(),
        byte_order: ByteOrder::native(),
        data: DataSet::inline(piece),
        file_path: None,
    };
    let mut bytes = Vec::new();
    vtk.write_xml(&mut bytes)
        .map_err(|error| OutputError::Library {
            library: "vtkio",
            message: error.to_string(),
        })?;
    let mut xml = String::from_utf8(bytes).map_err(|error| OutputError::Library {
        library: "vtkio",
        message: format!("output is not UTF-8: {error}"),
    })?;
    if !field_xml.is_empty() {
        const OPENING: &str = "<UnstructuredGrid>";
        let at = xml.find(OPENING).ok_or_else(|| OutputError::Library {
            library: "vtkio",
            message: "no <UnstructuredGrid> element in the output".into(),
        })? + OPENING.len();
        xml.insert_str(at, &field_xml);
    }
    write_atomically(path, |writer| writer.write_all(xml.as_bytes()))
}
