//! The path table: CSV written atomically, every number parsing back bit for bit; JSON through
//! serde.

use std::io;
use std::path::PathBuf;
use wrinkle::output::{PATH_CSV_COLUMNS, PathPoint, write_path_csv};

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
            max_amplitude: 0.0,
            max_amplitude_over_h: 0.0,
            centre_amplitude_over_h: 0.0,
            residual: 0.0,
            elliptic: true,
            closed_form_amplitude_over_h: None,
        },
        PathPoint {
            step: 1,
            interior: true,
            lambda: 0.1 + 1.0 / 3.0,
            n_x: None,
            max_amplitude: 1.234_567_890_123e-7,
            max_amplitude_over_h: 2.5e12,
            centre_amplitude_over_h: -0.37,
            residual: 3.3e-9,
            elliptic: false,
            closed_form_amplitude_over_h: Some(0.123_456_789),
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
            max_amplitude: number(row[4]),
            max_amplitude_over_h: number(row[5]),
            centre_amplitude_over_h: number(row[6]),
            residual: number(row[7]),
            elliptic: row[8].parse().unwrap(),
            closed_form_amplitude_over_h: optional(row[9]),
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
    assert_eq!(value[1]["closed_form_amplitude_over_h"], 0.123_456_789);
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
