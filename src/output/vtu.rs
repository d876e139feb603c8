//! VTK XML unstructured-grid files (`.vtu`, binary inline base64, readable by ParaView):
//! finite element fields on the Q8 mesh ([`write_fields_vtu`]) and the reconstructed wrinkled
//! surface on a refined structured grid ([`write_surface_vtu`]).

use super::path_table::with_path;
use super::{OutputError, check_length, invalid};
use std::collections::BTreeSet;
use std::fs::File;
use std::io::{self, BufWriter, Write};
use std::path::Path;
use vtkio::model::{
    Attribute, Attributes, ByteOrder, CellType, Cells, DataArray, DataSet, UnstructuredGridPiece,
    Version, VertexNumbers, Vtk,
};
use wrinkle_runtime::fem::Mesh;

/// Writes fields of a Q8 mesh as a `.vtu` file: `POINTS` at $`(X, Y, 0)`$, one cell of VTK type 23
/// (`QuadraticQuad`, corners then mid-sides, the order of [`Mesh::elements`]) per element, and one
/// scalar point array per field.
///
/// `nodal_values` is node-major: the value of field `f` at node `n` is
/// `nodal_values[n * field_names.len() + f]`. Each `extra` entry is one more scalar point array
/// (one value per node), e.g. a mode shape or an ellipticity indicator.
///
/// Errors (kind [`io::ErrorKind::InvalidInput`]): wrong array lengths, empty or repeated array
/// names, an element referring to a missing node, a non-finite coordinate.
pub fn write_fields_vtu(
    path: &Path,
    mesh: &Mesh,
    field_names: &[&str],
    nodal_values: &[f64],
    extra: &[(&str, Vec<f64>)],
) -> io::Result<()> {
    let node_count = mesh.nodes.len();
    let field_count = field_names.len();
    check_length("nodal values", node_count * field_count, nodal_values.len())?;
    check_unique_names(
        field_names
            .iter()
            .copied()
            .chain(extra.iter().map(|(name, _)| *name)),
    )?;
    for (name, values) in extra {
        check_length(format!("point array `{name}`"), node_count, values.len())?;
    }
    if mesh.nodes.iter().flatten().any(|c| !c.is_finite()) {
        return Err(invalid("mesh", "node coordinates must be finite"));
    }
    let mut connectivity = Vec::with_capacity(8 * mesh.elements.len());
    for (element, nodes) in mesh.elements.iter().enumerate() {
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
    let offsets = (1..=mesh.elements.len() as u64).map(|e| 8 * e).collect();
    let points: Vec<f64> = mesh.nodes.iter().flat_map(|&[x, y]| [x, y, 0.0]).collect();

    let mut point_arrays = Vec::with_capacity(field_count + extra.len());
    for (f, name) in field_names.iter().enumerate() {
        let values: Vec<f64> = (0..node_count)
            .map(|n| nodal_values[n * field_count + f])
            .collect();
        point_arrays.push(scalar_array(name, values));
    }
    for (name, values) in extra {
        point_arrays.push(scalar_array(name, values.clone()));
    }
    let piece = UnstructuredGridPiece {
        points: points.into(),
        cells: Cells {
            cell_verts: VertexNumbers::XML {
                connectivity,
                offsets,
            },
            types: vec![CellType::QuadraticQuad; mesh.elements.len()],
        },
        data: Attributes {
            point: point_arrays,
            cell: Vec::new(),
        },
    };
    write_piece(path, "wrinkle finite element fields", piece)
}

/// Writes the reconstructed physical surface on a structured grid of `nx × ny` Quad4 cells
/// (VTK type 9) covering `bounds = [x0, x1, y0, y1]`.
///
/// At every grid point $`\mathbf{X} = (X, Y)`$ the deflection is
/// $`w = 2\, A(\mathbf{X}) \cos(Q\, \mathbf{e} \cdot \mathbf{X})`$ with the envelope
/// $`A = `$ `envelope(X, Y)` (the caller interpolates its finite element field), the wavenumber
/// $`Q`$ and the wave direction $`\mathbf{e} = (\cos\theta, \sin\theta)`$, $`\theta`$ =
/// `direction` in radians. The points are placed at $`(X, Y, s\, w)`$ with $`s`$ =
/// `vertical_scale`; the point arrays `w` and `envelope` hold the unscaled values.
///
/// Errors (kind [`io::ErrorKind::InvalidInput`]): `nx` or `ny` zero, bounds not finite and
/// increasing, non-finite wavenumber, direction or scale, an envelope value that is not finite.
// The signature is the documented interface of `wrinkle run`; the scalars are independent inputs.
#[allow(clippy::too_many_arguments)]
pub fn write_surface_vtu(
    path: &Path,
    bounds: [f64; 4],
    nx: usize,
    ny: usize,
    envelope: &dyn Fn(f64, f64) -> f64,
    wavenumber: f64,
    direction: f64,
    vertical_scale: f64,
) -> io::Result<()> {
    check_bounds(bounds)?;
    if nx == 0 || ny == 0 {
        return Err(invalid(
            "surface grid",
            format!("needs at least one cell in each direction, got {nx} × {ny}"),
        ));
    }
    for (what, value) in [
        ("wavenumber", wavenumber),
        ("direction", direction),
        ("vertical scale", vertical_scale),
    ] {
        if !value.is_finite() {
            return Err(invalid(what, format!("must be finite, got {value}")));
        }
    }
    let [x0, x1, y0, y1] = bounds;
    let (cos_theta, sin_theta) = (direction.cos(), direction.sin());
    let point_count = (nx + 1) * (ny + 1);
    let mut points = Vec::with_capacity(3 * point_count);
    let mut deflection = Vec::with_capacity(point_count);
    let mut envelope_values = Vec::with_capacity(point_count);
    for j in 0..=ny {
        let y = y0 + (y1 - y0) * j as f64 / ny as f64;
        for i in 0..=nx {
            let x = x0 + (x1 - x0) * i as f64 / nx as f64;
            let amplitude = envelope(x, y);
            if !amplitude.is_finite() {
                return Err(invalid(
                    "envelope",
                    format!("not finite at (X, Y) = ({x}, {y}): {amplitude}"),
                ));
            }
            let w = 2.0 * amplitude * (wavenumber * (cos_theta * x + sin_theta * y)).cos();
            points.extend([x, y, vertical_scale * w]);
            deflection.push(w);
            envelope_values.push(amplitude);
        }
    }
    let corner = |i: usize, j: usize| (j * (nx + 1) + i) as u64;
    let mut connectivity = Vec::with_capacity(4 * nx * ny);
    for j in 0..ny {
        for i in 0..nx {
            connectivity.extend([
                corner(i, j),
                corner(i + 1, j),
                corner(i + 1, j + 1),
                corner(i, j + 1),
            ]);
        }
    }
    let offsets = (1..=(nx * ny) as u64).map(|c| 4 * c).collect();
    let piece = UnstructuredGridPiece {
        points: points.into(),
        cells: Cells {
            cell_verts: VertexNumbers::XML {
                connectivity,
                offsets,
            },
            types: vec![CellType::Quad; nx * ny],
        },
        data: Attributes {
            point: vec![
                scalar_array("w", deflection),
                scalar_array("envelope", envelope_values),
            ],
            cell: Vec::new(),
        },
    };
    write_piece(path, "wrinkle reconstructed surface", piece)
}

/// `bounds = [x0, x1, y0, y1]` must be finite with `x0 < x1` and `y0 < y1`.
pub(crate) fn check_bounds(bounds: [f64; 4]) -> io::Result<()> {
    let [x0, x1, y0, y1] = bounds;
    if bounds.iter().all(|b| b.is_finite()) && x0 < x1 && y0 < y1 {
        Ok(())
    } else {
        Err(invalid(
            "bounds",
            format!("need finite x0 < x1 and y0 < y1, got {bounds:?}"),
        ))
    }
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

fn write_piece(path: &Path, title: &str, piece: UnstructuredGridPiece) -> io::Result<()> {
    let vtk = Vtk {
        version: Version::new((1, 0)),
        title: title.to_string(),
        byte_order: ByteOrder::native(),
        data: DataSet::inline(piece),
        file_path: None,
    };
    let file = File::create(path).map_err(|error| with_path(path, error))?;
    let mut writer = BufWriter::new(file);
    vtk.write_xml(&mut writer)
        .map_err(|error| OutputError::Library {
            library: "vtkio",
            message: format!("{}: {error}", path.display()),
        })?;
    writer.flush().map_err(|error| with_path(path, error))
}
