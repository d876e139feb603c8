//! Output writers: CSV/JSON path tables, VTU files parsed back with `vtkio`, PNG/SVG plots.

use std::f64::consts::PI;
use std::io;
use std::path::{Path, PathBuf};
use vtkio::model::{Attribute, CellType, DataSet, Piece, VertexNumbers, Vtk};
use wrinkle::output::{
    Curve, CurveStyle, PATH_CSV_COLUMNS, PathPoint, Progress, VerticalMarker, grid_cell_centres,
    plot_map, plot_profiles, plot_response, write_fields_vtu, write_path_csv, write_surface_vtu,
};
use wrinkle_runtime::fem::Mesh;

/// A fresh directory under the system temporary directory, unique per test and process.
fn scratch_dir(test: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("wrinkle-output-{}-{test}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn sample_points() -> Vec<PathPoint> {
    vec![
        PathPoint {
            step: 0,
            interior: false,
            lambda: 0.0,
            n_x: Some(-0.0),
            max_envelope: 0.0,
            max_envelope_over_h: 0.0,
            center_envelope_over_h: 0.0,
            residual: 0.0,
            elliptic: true,
            closed_form_envelope_over_h: None,
        },
        PathPoint {
            step: 1,
            interior: true,
            lambda: 0.1 + 1.0 / 3.0,
            n_x: None,
            max_envelope: 1.234_567_890_123e-7,
            max_envelope_over_h: 2.5e12,
            center_envelope_over_h: -0.37,
            residual: 3.3e-9,
            elliptic: false,
            closed_form_envelope_over_h: Some(0.123_456_789),
        },
    ]
}

#[test]
fn path_csv_header_is_the_field_names_and_rows_parse_back_exactly() {
    let dir = scratch_dir("csv");
    let file = dir.join("path.csv");
    let points = sample_points();
    write_path_csv(&file, &points).unwrap();
    let text = std::fs::read_to_string(&file).unwrap();
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    assert_eq!(header, PATH_CSV_COLUMNS);
    // The header is the list of serde field names, in declaration order.
    let json = serde_json::to_value(&points[1]).unwrap();
    let keys: Vec<&str> = json
        .as_object()
        .unwrap()
        .keys()
        .map(String::as_str)
        .collect();
    let mut sorted_header = header.clone();
    sorted_header.sort_unstable();
    let mut sorted_keys = keys.clone();
    sorted_keys.sort_unstable();
    assert_eq!(sorted_header, sorted_keys);

    let rows: Vec<Vec<&str>> = lines.map(|line| line.split(',').collect()).collect();
    assert_eq!(rows.len(), points.len());
    let number = |cell: &str| cell.parse::<f64>().unwrap();
    let optional = |cell: &str| (!cell.is_empty()).then(|| number(cell));
    for (row, point) in rows.iter().zip(&points) {
        assert_eq!(row.len(), header.len());
        let parsed = PathPoint {
            step: row[0].parse().unwrap(),
            interior: row[1].parse().unwrap(),
            lambda: number(row[2]),
            n_x: optional(row[3]),
            max_envelope: number(row[4]),
            max_envelope_over_h: number(row[5]),
            center_envelope_over_h: number(row[6]),
            residual: number(row[7]),
            elliptic: row[8].parse().unwrap(),
            closed_form_envelope_over_h: optional(row[9]),
        };
        assert_eq!(&parsed, point);
        assert_eq!(parsed.lambda.to_bits(), point.lambda.to_bits());
    }
    assert_eq!(rows[1][3], "", "None is an empty cell");
    assert_eq!(rows[0][9], "");
}

#[test]
fn path_point_json_round_trips_with_null_for_none() {
    let points = sample_points();
    let json = serde_json::to_string(&points).unwrap();
    let value: serde_json::Value = serde_json::from_str(&json).unwrap();
    assert!(value[1]["n_x"].is_null());
    assert_eq!(value[1]["closed_form_envelope_over_h"], 0.123_456_789);
    let back: Vec<PathPoint> = serde_json::from_str(&json).unwrap();
    assert_eq!(back, points);
}

#[test]
fn path_csv_into_missing_directory_names_the_file() {
    let dir = scratch_dir("csv-missing");
    let file = dir.join("no-such-dir").join("path.csv");
    let error = write_path_csv(&file, &sample_points()).unwrap_err();
    assert_eq!(error.kind(), io::ErrorKind::NotFound);
    assert!(error.to_string().contains("no-such-dir"), "{error}");
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
    let attribute = piece
        .data
        .point
        .iter()
        .find(|a| a.name() == name)
        .unwrap_or_else(|| panic!("no point array `{name}`"));
    let Attribute::DataArray(array) = attribute else {
        panic!("`{name}` is not a data array");
    };
    array.data.clone().cast_into::<f64>().unwrap()
}

#[test]
fn fields_vtu_of_a_q8_mesh_parses_back() {
    let dir = scratch_dir("fields-vtu");
    let file = dir.join("fields.vtu");
    let mesh = Mesh::rectangle(3.0, 2.0, 3, 2, 1.0).unwrap();
    let node_count = mesh.nodes.len();
    assert_eq!(node_count, 7 * 5 - 6);
    // Two fields, u = X + 2Y and v = XY, interleaved node-major; one extra array.
    let mut nodal = Vec::new();
    for &[x, y] in &mesh.nodes {
        nodal.extend([x + 2.0 * y, x * y]);
    }
    let mode: Vec<f64> = mesh
        .nodes
        .iter()
        .map(|&[x, _]| (x * PI / 3.0).sin())
        .collect();
    write_fields_vtu(&file, &mesh, &["u", "v"], &nodal, &[("mode", mode.clone())]).unwrap();

    let text = std::fs::read_to_string(&file).unwrap();
    assert!(text.contains("UnstructuredGrid"));
    assert!(text.contains(&format!("NumberOfPoints=\"{node_count}\"")));
    assert!(text.contains("NumberOfCells=\"6\""));

    let piece = read_piece(&file);
    let points = piece.points.clone().cast_into::<f64>().unwrap();
    assert_eq!(points.len(), 3 * node_count);
    for (n, &[x, y]) in mesh.nodes.iter().enumerate() {
        assert_eq!(points[3 * n..3 * n + 3], [x, y, 0.0]);
    }
    assert_eq!(piece.cells.types, vec![CellType::QuadraticQuad; 6]);
    assert_eq!(CellType::QuadraticQuad as u8, 23);
    let (connectivity, offsets) = match piece.cells.cell_verts.clone() {
        VertexNumbers::XML {
            connectivity,
            offsets,
        } => (connectivity, offsets),
        VertexNumbers::Legacy { .. } => panic!("legacy cells in an XML file"),
    };
    let expected: Vec<u64> = mesh.elements.iter().flatten().map(|&n| n as u64).collect();
    assert_eq!(connectivity, expected);
    assert_eq!(offsets, vec![8, 16, 24, 32, 40, 48]);

    let names: Vec<&str> = piece.data.point.iter().map(Attribute::name).collect();
    assert_eq!(names, ["u", "v", "mode"]);
    let u = point_array(&piece, "u");
    let v = point_array(&piece, "v");
    for (n, &[x, y]) in mesh.nodes.iter().enumerate() {
        assert_eq!(u[n], x + 2.0 * y);
        assert_eq!(v[n], x * y);
    }
    assert_eq!(point_array(&piece, "mode"), mode);
}

#[test]
fn fields_vtu_rejects_inconsistent_input() {
    let dir = scratch_dir("fields-vtu-errors");
    let file = dir.join("bad.vtu");
    let mesh = Mesh::rectangle(3.0, 2.0, 3, 2, 1.0).unwrap();
    let node_count = mesh.nodes.len();
    let values = vec![0.0; 2 * node_count];

    let error = write_fields_vtu(&file, &mesh, &["u"], &values, &[]).unwrap_err();
    assert_eq!(error.kind(), io::ErrorKind::InvalidInput);
    assert!(
        error
            .to_string()
            .contains(&format!("expected {node_count}")),
        "{error}"
    );

    let error = write_fields_vtu(&file, &mesh, &["u", "u"], &values, &[]).unwrap_err();
    assert_eq!(error.kind(), io::ErrorKind::InvalidInput);
    assert!(error.to_string().contains("`u`"), "{error}");

    let error = write_fields_vtu(
        &file,
        &mesh,
        &["u", "v"],
        &values,
        &[("mode", vec![1.0; 3])],
    )
    .unwrap_err();
    assert!(error.to_string().contains("mode"), "{error}");

    let mut broken = mesh.clone();
    broken.elements[2][5] = node_count + 4;
    let error = write_fields_vtu(&file, &broken, &["u", "v"], &values, &[]).unwrap_err();
    assert!(error.to_string().contains("element 2"), "{error}");
    assert!(!file.exists(), "no file is written for bad input");
}

#[test]
fn surface_vtu_reconstructs_twice_the_envelope() {
    let dir = scratch_dir("surface-vtu");
    let file = dir.join("surface.vtu");
    let (length, width, amplitude) = (400.0, 200.0, 1.5);
    let envelope =
        move |x: f64, y: f64| amplitude * (PI * x / length).sin() * (PI * y / width).sin();
    // Eight wavelengths over the length: the centre (200, 100) is a crest of cos(Q X).
    let wavenumber = 2.0 * PI * 8.0 / length;
    let (nx, ny, scale) = (80, 40, 3.0);
    write_surface_vtu(
        &file,
        [0.0, length, 0.0, width],
        nx,
        ny,
        &envelope,
        wavenumber,
        0.0,
        scale,
    )
    .unwrap();

    let piece = read_piece(&file);
    let point_count = (nx + 1) * (ny + 1);
    assert_eq!(piece.cells.types, vec![CellType::Quad; nx * ny]);
    let points = piece.points.clone().cast_into::<f64>().unwrap();
    assert_eq!(points.len(), 3 * point_count);
    let w = point_array(&piece, "w");
    let env = point_array(&piece, "envelope");
    assert_eq!((w.len(), env.len()), (point_count, point_count));
    let max_z = points.chunks(3).fold(0.0f64, |m, p| m.max(p[2].abs()));
    let max_envelope = env.iter().fold(0.0f64, |m, e| m.max(e.abs()));
    assert!((max_envelope - amplitude).abs() < 1e-12);
    assert!(
        (max_z - scale * 2.0 * amplitude).abs() < 1e-9,
        "max |z| = {max_z}"
    );
    for (k, p) in points.chunks(3).enumerate() {
        let (x, y) = (p[0], p[1]);
        let expected = 2.0 * envelope(x, y) * (wavenumber * x).cos();
        assert!((w[k] - expected).abs() < 1e-12);
        assert!((p[2] - scale * expected).abs() < 1e-12);
        assert!((env[k] - envelope(x, y)).abs() < 1e-15);
    }
    let text = std::fs::read_to_string(&file).unwrap();
    assert!(text.contains(&format!("NumberOfCells=\"{}\"", nx * ny)));

    // Waves along Y when the direction is π/2.
    let file = dir.join("surface-y.vtu");
    write_surface_vtu(
        &file,
        [0.0, length, 0.0, width],
        10,
        20,
        &envelope,
        0.3,
        PI / 2.0,
        1.0,
    )
    .unwrap();
    let piece = read_piece(&file);
    let points = piece.points.clone().cast_into::<f64>().unwrap();
    let w = point_array(&piece, "w");
    for (k, p) in points.chunks(3).enumerate() {
        let expected = 2.0 * envelope(p[0], p[1]) * (0.3 * p[1]).cos();
        assert!((w[k] - expected).abs() < 1e-12);
    }
}

#[test]
fn surface_vtu_rejects_bad_grids_and_non_finite_envelopes() {
    let dir = scratch_dir("surface-vtu-errors");
    let file = dir.join("bad.vtu");
    let one = |_: f64, _: f64| 1.0;
    for (bounds, nx) in [
        ([0.0, 1.0, 0.0, 1.0], 0),
        ([1.0, 0.0, 0.0, 1.0], 4),
        ([0.0, f64::NAN, 0.0, 1.0], 4),
    ] {
        let error = write_surface_vtu(&file, bounds, nx, 4, &one, 1.0, 0.0, 1.0).unwrap_err();
        assert_eq!(error.kind(), io::ErrorKind::InvalidInput);
    }
    let singular = |x: f64, _: f64| 1.0 / (x - 0.5);
    let error =
        write_surface_vtu(&file, [0.0, 1.0, 0.0, 1.0], 2, 2, &singular, 1.0, 0.0, 1.0).unwrap_err();
    assert!(error.to_string().contains("envelope"), "{error}");
}

/// Width and height from the IHDR chunk, after checking the PNG signature.
fn png_size(file: &Path) -> (u32, u32) {
    let bytes = std::fs::read(file).unwrap();
    assert_eq!(bytes[..8], [0x89, b'P', b'N', b'G', 0x0d, 0x0a, 0x1a, 0x0a]);
    assert_eq!(&bytes[12..16], b"IHDR");
    let word = |at: usize| u32::from_be_bytes(bytes[at..at + 4].try_into().unwrap());
    (word(16), word(20))
}

#[test]
fn response_plot_writes_png_and_svg_with_axis_labels() {
    let dir = scratch_dir("response-plot");
    let stem = dir.join("response");
    let fe: Vec<(f64, f64)> = (0..=40)
        .map(|k| {
            let lambda = 0.05 + 0.005 * k as f64;
            (lambda, (lambda - 0.09).max(0.0).sqrt())
        })
        .collect();
    let steps: Vec<(f64, f64)> = fe.iter().step_by(8).copied().collect();
    let curves = [
        Curve {
            label: "FE (ANM)".into(),
            points: fe.clone(),
            style: CurveStyle::LineWithMarkers(steps),
        },
        Curve::dashed("closed form", fe),
    ];
    let markers = [VerticalMarker {
        label: "bifurcation".into(),
        x: 0.09,
    }];
    plot_response(&stem, "Response", &curves, "load λ", "w_env / h", &markers).unwrap();
    assert_eq!(png_size(&dir.join("response.png")), (1200, 800));
    let svg = std::fs::read_to_string(dir.join("response.svg")).unwrap();
    assert!(svg.starts_with("<svg"));
    for text in [
        "load λ",
        "w_env / h",
        "closed form",
        "bifurcation",
        "Response",
    ] {
        assert!(svg.contains(text), "SVG lacks `{text}`");
    }

    let error =
        plot_response(&stem, "t", &[Curve::line("empty", vec![])], "x", "y", &[]).unwrap_err();
    assert_eq!(error.kind(), io::ErrorKind::InvalidInput);
}

#[test]
fn profiles_plot_keeps_a_dot_in_the_stem() {
    let dir = scratch_dir("profiles-plot");
    let stem = dir.join("profile.at.center");
    let profiles: Vec<Curve> = (1..=3)
        .map(|k| {
            let points = (0..=50)
                .map(|i| (i as f64, k as f64 * (i as f64 / 8.0).sin()))
                .collect();
            Curve::line(format!("λ = {k}"), points)
        })
        .collect();
    plot_profiles(&stem, "Profiles", "X (mm)", &profiles).unwrap();
    assert_eq!(png_size(&dir.join("profile.at.center.png")), (1200, 700));
    let svg = std::fs::read_to_string(dir.join("profile.at.center.svg")).unwrap();
    assert!(svg.contains("X (mm)") && svg.contains("λ = 3"));
}

#[test]
fn map_plot_keeps_the_aspect_ratio_of_the_domain() {
    let dir = scratch_dir("map-plot");
    for (length, name) in [(400.0, "short"), (1400.0, "long")] {
        let bounds = [0.0, length, 0.0, 200.0];
        let (nx, ny) = (200, 40);
        let values: Vec<f64> = grid_cell_centres(bounds, nx, ny)
            .into_iter()
            .map(|(x, y)| (PI * x / length).sin() * (PI * y / 200.0).sin() * (0.24 * x).cos())
            .collect();
        let stem = dir.join(name);
        plot_map(&stem, "w (mm)", bounds, nx, ny, &values).unwrap();
        let (width, height) = png_size(&dir.join(format!("{name}.png")));
        // Plot area plus fixed label areas: 310 px horizontally and 155 px vertically.
        let (plot_width, plot_height) = (width as f64 - 310.0, height as f64 - 155.0);
        let aspect = plot_width / plot_height;
        assert!(
            (aspect - length / 200.0).abs() < 0.02 * length / 200.0,
            "{width} × {height}"
        );
        let svg = std::fs::read_to_string(dir.join(format!("{name}.svg"))).unwrap();
        assert!(svg.contains("X (mm)") && svg.contains("Y (mm)"));
        // The cells are one embedded PNG image, not one element per cell.
        assert_eq!(svg.matches("href=\"data:image/png;base64,").count(), 1);
        assert!(svg.len() < 2_000_000, "SVG of {} bytes", svg.len());
    }
    let error = plot_map(&dir.join("bad"), "t", [0.0, 1.0, 0.0, 1.0], 3, 3, &[0.0; 8]).unwrap_err();
    assert_eq!(error.kind(), io::ErrorKind::InvalidInput);
}

#[test]
fn cell_centres_are_in_value_order() {
    let centres = grid_cell_centres([0.0, 4.0, 10.0, 12.0], 4, 2);
    assert_eq!(centres.len(), 8);
    assert_eq!(centres[0], (0.5, 10.5));
    assert_eq!(centres[1], (1.5, 10.5));
    assert_eq!(centres[4], (0.5, 11.5));
    assert_eq!(centres[7], (3.5, 11.5));
}

#[test]
fn progress_is_silent_unless_stderr_is_a_terminal() {
    use std::io::IsTerminal;
    let progress = Progress::new(10, "test");
    assert_eq!(progress.is_visible(), std::io::stderr().is_terminal());
    let hidden = Progress::hidden();
    assert!(!hidden.is_visible());
    hidden.update(12, "past the hint");
    hidden.finish("done");
}
