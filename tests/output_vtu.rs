//! VTU files read back with vtkio: Q8 cells (VTK type 23), the unknown fields, the extra point
//! arrays given by the caller (stress resultants, physical deflection), and the field data (the
//! load and its unit) found in the XML.

use std::f64::consts::PI;
use std::io;
use std::path::{Path, PathBuf};
use vtkio::model::{Attribute, CellType, DataSet, Piece, VertexNumbers, Vtk};
use wrinkle::output::{
    FieldData, GridField, PointArray, Quantity, write_fields_vtu, write_surface_vtu,
};
use wrinkle_runtime::fem::Mesh;

fn scratch_dir(test: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("wrinkle-vtu-{}-{test}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// The single unstructured-grid piece of a `.vtu` file.
fn read_piece(file: &Path) -> vtkio::model::UnstructuredGridPiece {
    let vtk = Vtk::import(file).unwrap();
    let DataSet::UnstructuredGrid { pieces, .. } = vtk.data else {
        panic!("not an unstructured grid");
    };
    assert_eq!(pieces.len(), 1);
    let Piece::Inline(piece) = pieces.into_iter().next().unwrap() else {
        panic!("piece not inline");
    };
    *piece
}

fn point_array(piece: &vtkio::model::UnstructuredGridPiece, name: &str) -> Vec<f64> {
    data_array(&piece.data.point, "point", name)
}

/// The values of the data array `name` among `attributes` (point or cell data, `kind`).
fn data_array(attributes: &[Attribute], kind: &str, name: &str) -> Vec<f64> {
    let attribute = attributes
        .iter()
        .find(|a| a.name() == name)
        .unwrap_or_else(|| panic!("no {kind} array `{name}`"));
    let Attribute::DataArray(array) = attribute else {
        panic!("`{name}` is not a data array");
    };
    array.data.clone().cast_into::<f64>().unwrap()
}

/// The `<DataArray>` named `name` inside `<FieldData>`: its type and its text.
fn field_data_array(xml: &str, name: &str) -> (String, String) {
    let start = xml.find("<FieldData>").expect("no <FieldData>");
    let end = xml.find("</FieldData>").expect("no </FieldData>");
    let block = &xml[start..end];
    let at = block
        .find(&format!("Name=\"{name}\""))
        .unwrap_or_else(|| panic!("no field data `{name}` in {block}"));
    let open = block[..at].rfind("<DataArray").unwrap();
    let tag_end = open + block[open..].find('>').unwrap();
    let tag = &block[open..tag_end];
    let kind = tag
        .split("type=\"")
        .nth(1)
        .unwrap()
        .split('"')
        .next()
        .unwrap();
    let close = tag_end + block[tag_end..].find("</DataArray>").unwrap();
    (
        kind.to_string(),
        block[tag_end + 1..close].trim().to_string(),
    )
}

/// A text of the field data (a `UInt8` array of its UTF-8 bytes) back as text.
fn decode_string(text: &str) -> String {
    let bytes: Vec<u8> = text
        .split_whitespace()
        .map(|b| b.parse::<u8>().unwrap())
        .collect();
    String::from_utf8(bytes).unwrap()
}

#[test]
fn fields_vtu_of_a_q8_mesh_round_trips_arrays_and_field_data() {
    let dir = scratch_dir("fields");
    let file = dir.join("fields.vtu");
    let mesh = Mesh::rectangle(3.0, 2.0, 3, 2, 1.0).unwrap();
    let node_count = mesh.nodes.len();
    assert_eq!(node_count, 7 * 5 - 6);
    // Two fields, u = X + 2Y and v = XY, interleaved node-major.
    let mut nodal = Vec::new();
    for &[x, y] in &mesh.nodes {
        nodal.extend([x + 2.0 * y, x * y]);
    }
    let per_node =
        |f: fn(f64, f64) -> f64| -> Vec<f64> { mesh.nodes.iter().map(|&[x, y]| f(x, y)).collect() };
    let n_x = per_node(|x, _| -0.0952 + 0.001 * x);
    let n_y = per_node(|_, y| 10.0 - 0.01 * y);
    let n_xy = per_node(|x, y| 1e-4 * x * y);
    let w = per_node(|x, y| 0.1 * (PI * x / 3.0).sin() * (PI * y / 2.0).sin());
    let normals: Vec<[f64; 3]> = mesh.nodes.iter().map(|&[x, _]| [x, 0.0, 1.0]).collect();
    let extra = [
        PointArray::scalar("N_X", n_x.clone()),
        PointArray::scalar("N_Y", n_y.clone()),
        PointArray::scalar("N_XY", n_xy.clone()),
        PointArray::scalar("w (physical)", w.clone()),
        PointArray::vector("direction", &normals),
    ];
    let field_data = FieldData::load(0.0952, "N/mm")
        .with_text("model", "reference-envelope")
        .with_number("critical_load", 0.089521);
    write_fields_vtu(&file, &mesh, &["u", "v"], &nodal, &extra, &field_data).unwrap();

    let piece = read_piece(&file);
    let points = piece.points.clone().cast_into::<f64>().unwrap();
    assert_eq!(points.len(), 3 * node_count);
    for (n, &[x, y]) in mesh.nodes.iter().enumerate() {
        assert_eq!(points[3 * n..3 * n + 3], [x, y, 0.0]);
    }
    assert_eq!(piece.cells.types, vec![CellType::QuadraticQuad; 6]);
    assert_eq!(CellType::QuadraticQuad as u8, 23);
    let VertexNumbers::XML {
        connectivity,
        offsets,
    } = piece.cells.cell_verts.clone()
    else {
        panic!("legacy cells in an XML file");
    };
    let expected: Vec<u64> = mesh.connectivity.iter().map(|&n| n as u64).collect();
    assert_eq!(connectivity, expected);
    assert_eq!(offsets, vec![8, 16, 24, 32, 40, 48]);

    let names: Vec<&str> = piece.data.point.iter().map(Attribute::name).collect();
    assert_eq!(
        names,
        ["u", "v", "N_X", "N_Y", "N_XY", "w (physical)", "direction"]
    );
    let u = point_array(&piece, "u");
    let v = point_array(&piece, "v");
    for (n, &[x, y]) in mesh.nodes.iter().enumerate() {
        assert_eq!(u[n], x + 2.0 * y);
        assert_eq!(v[n], x * y);
    }
    assert_eq!(point_array(&piece, "N_X"), n_x);
    assert_eq!(point_array(&piece, "N_Y"), n_y);
    assert_eq!(point_array(&piece, "N_XY"), n_xy);
    assert_eq!(point_array(&piece, "w (physical)"), w);
    let flat: Vec<f64> = normals.iter().flatten().copied().collect();
    assert_eq!(point_array(&piece, "direction"), flat);

    // Field data: the load and its unit, a text and another number.
    let xml = std::fs::read_to_string(&file).unwrap();
    let (kind, text) = field_data_array(&xml, "load");
    assert_eq!(kind, "Float64");
    assert_eq!(text.parse::<f64>().unwrap(), 0.0952);
    let (kind, text) = field_data_array(&xml, "load_unit");
    // Not `String`: meshio refuses it ("Illegal data type 'String'").
    assert_eq!(kind, "UInt8");
    assert!(!xml.contains("type=\"String\""));
    assert_eq!(decode_string(&text), "N/mm");
    assert_eq!(
        decode_string(&field_data_array(&xml, "model").1),
        "reference-envelope"
    );
    let (_, text) = field_data_array(&xml, "critical_load");
    assert_eq!(text.parse::<f64>().unwrap(), 0.089521);
    // The field data belongs to the dataset, before its piece.
    assert!(xml.find("<FieldData>").unwrap() < xml.find("<Piece").unwrap());
}

#[test]
fn fields_vtu_rejects_inconsistent_input_and_writes_nothing() {
    let dir = scratch_dir("fields-errors");
    let file = dir.join("bad.vtu");
    let mesh = Mesh::rectangle(3.0, 2.0, 3, 2, 1.0).unwrap();
    let node_count = mesh.nodes.len();
    let values = vec![0.0; 2 * node_count];
    let load = FieldData::load(1.0, "mm");

    let error = write_fields_vtu(&file, &mesh, &["u"], &values, &[], &load).unwrap_err();
    assert_eq!(error.kind(), io::ErrorKind::InvalidInput);
    assert!(
        error
            .to_string()
            .contains(&format!("expected {node_count}")),
        "{error}"
    );

    let error = write_fields_vtu(&file, &mesh, &["u", "u"], &values, &[], &load).unwrap_err();
    assert!(error.to_string().contains("`u`"), "{error}");

    let short = [PointArray::scalar("N_X", vec![1.0; 3])];
    let error = write_fields_vtu(&file, &mesh, &["u", "v"], &values, &short, &load).unwrap_err();
    assert!(error.to_string().contains("N_X"), "{error}");

    let clash = [PointArray::scalar("v", vec![1.0; node_count])];
    let error = write_fields_vtu(&file, &mesh, &["u", "v"], &values, &clash, &load).unwrap_err();
    assert!(error.to_string().contains("`v`"), "{error}");

    let bad_load = FieldData::load(f64::NAN, "mm");
    let error = write_fields_vtu(&file, &mesh, &["u", "v"], &values, &[], &bad_load).unwrap_err();
    assert!(error.to_string().contains("load"), "{error}");

    let mut broken = mesh.clone();
    broken.connectivity[2 * 8 + 5] = node_count + 4;
    let error = write_fields_vtu(&file, &broken, &["u", "v"], &values, &[], &load).unwrap_err();
    assert!(error.to_string().contains("element 2"), "{error}");
    assert_eq!(
        std::fs::read_dir(&dir).unwrap().count(),
        0,
        "no file (not even a temporary one) is left for bad input"
    );
}

#[test]
fn surface_vtu_places_points_at_the_sampled_deflection() {
    let dir = scratch_dir("surface");
    let file = dir.join("surface.vtu");
    let (length, width, amplitude) = (400.0, 200.0, 0.1);
    let envelope = |x: f64, y: f64| amplitude * (PI * x / length).sin() * (PI * y / width).sin();
    let wavenumber = 2.0 * PI * 8.0 / length;
    let (columns, rows, scale) = (81, 41, 3.0);
    let deflection = GridField::sample(
        Quantity::deflection(),
        [0.0, length, 0.0, width],
        columns,
        rows,
        |x, y| 2.0 * envelope(x, y) * (wavenumber * x).cos(),
    );
    let envelope_values = GridField::sample(
        Quantity::deflection(),
        deflection.bounds,
        columns,
        rows,
        envelope,
    )
    .values;
    write_surface_vtu(
        &file,
        &deflection,
        scale,
        &[PointArray::scalar("envelope", envelope_values.clone())],
        &FieldData::load(0.11, "N/mm"),
    )
    .unwrap();

    let piece = read_piece(&file);
    let point_count = columns * rows;
    assert_eq!(
        piece.cells.types,
        vec![CellType::Quad; (columns - 1) * (rows - 1)]
    );
    let points = piece.points.clone().cast_into::<f64>().unwrap();
    assert_eq!(points.len(), 3 * point_count);
    // Named after the quantity, not `w` (the envelope's name in the fields' files).
    let w = point_array(&piece, "physical_deflection");
    assert_eq!(w, deflection.values);
    assert_eq!(point_array(&piece, "envelope"), envelope_values);
    for (k, p) in points.chunks(3).enumerate() {
        let [x, y] = deflection.point(k % columns, k / columns);
        assert_eq!((p[0], p[1]), (x, y));
        assert!((p[2] - scale * w[k]).abs() < 1e-15);
    }
    let max_z = points.chunks(3).fold(0.0f64, |m, p| m.max(p[2].abs()));
    assert!((max_z - scale * 2.0 * amplitude).abs() < 1e-12, "{max_z}");
    let xml = std::fs::read_to_string(&file).unwrap();
    assert_eq!(
        decode_string(&field_data_array(&xml, "load_unit").1),
        "N/mm"
    );
}

#[test]
fn surface_vtu_rejects_bad_grids_and_non_finite_values() {
    let dir = scratch_dir("surface-errors");
    let file = dir.join("bad.vtu");
    let load = FieldData::load(0.0, "N/mm");
    for (bounds, columns) in [
        ([0.0, 1.0, 0.0, 1.0], 1),
        ([1.0, 0.0, 0.0, 1.0], 4),
        ([0.0, f64::NAN, 0.0, 1.0], 4),
    ] {
        let field = GridField::sample(Quantity::deflection(), bounds, columns, 4, |_, _| 1.0);
        let error = write_surface_vtu(&file, &field, 1.0, &[], &load).unwrap_err();
        assert_eq!(error.kind(), io::ErrorKind::InvalidInput, "{error}");
    }
    let singular = GridField::sample(
        Quantity::deflection(),
        [0.0, 1.0, 0.0, 1.0],
        3,
        3,
        |x, _| 1.0 / (x - 0.5),
    );
    let error = write_surface_vtu(&file, &singular, 1.0, &[], &load).unwrap_err();
    assert!(error.to_string().contains("not finite"), "{error}");
    assert!(!file.exists());
}

fn cell_array(piece: &vtkio::model::UnstructuredGridPiece, name: &str) -> Vec<f64> {
    data_array(&piece.data.cell, "cell", name)
}

/// The stress resultants `wrinkle run` stores per element (N_X = ∂ψ/∂u_X, N_Y = ∂ψ/∂v_Y,
/// N_XY = ∂ψ/∂u_Y) balance the applied edge loads: uniform N_X = −λ, N_Y = 10 N/mm before
/// buckling; after it, N_X varies over the wrinkled zone but its mean over the (uniform) mesh is
/// still −λ, the mean of N_Y is still N_Y, and N_XY averages to zero. A requested load the
/// path does not reach (1 N/mm) gets no file, is listed in `summary.json` and named in a note.
#[test]
fn stress_resultants_in_run_vtu_balance_the_applied_loads() {
    let dir = scratch_dir("resultants");
    let output = std::process::Command::new(env!("CARGO_BIN_EXE_wrinkle"))
        .args(["run", "--quiet", "--out", dir.to_str().unwrap()])
        .args(["--set", "solver.max_amplitude_over_h=2"])
        .args([
            "--set",
            "output.vtu_loads=[0.05, 1.0]",
            "--set",
            "output.plots=false",
        ])
        .output()
        .unwrap();
    assert_eq!(
        output.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
    let stdout = String::from_utf8_lossy(&output.stdout);
    assert!(
        stdout.contains("note: output.vtu_loads: λ = 1.0000 N/mm not reached"),
        "{stdout}"
    );
    assert!(!dir.join("fields_load_1.000000.vtu").exists());
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("summary.json")).unwrap()).unwrap();
    assert_eq!(summary["unreached_vtu_loads"], serde_json::json!([1.0]));
    let mean = |values: &[f64]| values.iter().sum::<f64>() / values.len() as f64;
    let before = read_piece(&dir.join("fields_load_0.050000.vtu"));
    for (name, expected) in [("N_X", -0.05), ("N_Y", 10.0), ("N_XY", 0.0)] {
        let values = cell_array(&before, name);
        assert_eq!(values.len(), 32 * 16);
        for value in values {
            assert!(
                (value - expected).abs() < 1e-8,
                "{name} = {value} before buckling"
            );
        }
    }
    let xml = std::fs::read_to_string(dir.join("fields_final.vtu")).unwrap();
    let load: f64 = field_data_array(&xml, "load").1.trim().parse().unwrap();
    assert!(load > 0.1, "the final state is post-buckled, λ = {load}");
    let after = read_piece(&dir.join("fields_final.vtu"));
    let n_x = cell_array(&after, "N_X");
    let spread =
        n_x.iter().cloned().fold(f64::MIN, f64::max) - n_x.iter().cloned().fold(f64::MAX, f64::min);
    assert!(
        spread > 0.1 * load,
        "wrinkles redistribute N_X (spread {spread})"
    );
    assert!(
        (mean(&n_x) + load).abs() < 1e-6 * load,
        "mean N_X {} vs −λ {}",
        mean(&n_x),
        -load
    );
    assert!((mean(&cell_array(&after, "N_Y")) - 10.0).abs() < 1e-6 * 10.0);
    assert!(mean(&cell_array(&after, "N_XY")).abs() < 1e-9);
    let _ = std::fs::remove_dir_all(&dir);
}
