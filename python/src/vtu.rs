//! A run's VTU file read back as arrays (JSON for the Python layer, which makes NumPy arrays of
//! them): node coordinates, cell connectivity (Q8: 8 nodes each, VTK type 23), and every point
//! and cell data array with its component count.

use serde_json::{Value, json};
use std::path::Path;
use vtkio::model::{Attribute, DataSet, Piece, VertexNumbers, Vtk};

/// The arrays of the VTU file `path` as a JSON object: `points` (flat, 3 per node),
/// `connectivity` and `offsets` (VTK's), `cell_types`, `point_data` and `cell_data` (each name
/// → `{components, values}`).
pub fn read_vtu(path: &Path) -> Result<Value, String> {
    let vtk = Vtk::import(path).map_err(|e| format!("{}: {e}", path.display()))?;
    let DataSet::UnstructuredGrid { pieces, .. } = vtk.data else {
        return Err(format!("{}: not an unstructured grid", path.display()));
    };
    let Some(Piece::Inline(piece)) = pieces.into_iter().next() else {
        return Err(format!("{}: no inline piece", path.display()));
    };
    let points = piece.points.cast_into::<f64>().unwrap_or_default();
    let (connectivity, offsets) = match piece.cells.cell_verts {
        VertexNumbers::XML {
            connectivity,
            offsets,
        } => (connectivity, offsets),
        VertexNumbers::Legacy { vertices, .. } => legacy_cells(&vertices),
    };
    let cell_types: Vec<u8> = piece.cells.types.iter().map(|t| *t as u8).collect();
    Ok(json!({
        "points": points,
        "connectivity": connectivity,
        "offsets": offsets,
        "cell_types": cell_types,
        "point_data": arrays(&piece.data.point),
        "cell_data": arrays(&piece.data.cell),
    }))
}

/// Legacy `n v1 … vn` cell lists as XML connectivity and offsets.
fn legacy_cells(vertices: &[u32]) -> (Vec<u64>, Vec<u64>) {
    let (mut connectivity, mut offsets) = (Vec::new(), Vec::new());
    let mut at = 0;
    while at < vertices.len() {
        let count = vertices[at] as usize;
        let end = (at + 1 + count).min(vertices.len());
        connectivity.extend(vertices[at + 1..end].iter().map(|&v| u64::from(v)));
        offsets.push(connectivity.len() as u64);
        at = end;
    }
    (connectivity, offsets)
}

/// Data arrays by name: `{components, values}` (values flat, `components` per tuple).
fn arrays(attributes: &[Attribute]) -> Value {
    let mut map = serde_json::Map::new();
    for attribute in attributes {
        if let Attribute::DataArray(array) = attribute {
            let Some(values) = array.data.clone().cast_into::<f64>() else {
                continue;
            };
            map.insert(
                array.name.clone(),
                json!({"components": array.elem.num_comp(), "values": values}),
            );
        }
    }
    Value::Object(map)
}
