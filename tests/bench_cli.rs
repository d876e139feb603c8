//! `wrinkle bench --quick` on the built-in scene (the paper's example 1, reference envelope):
//! the files of docs/benchmarks.md exist, the CSV has the documented columns, every error is
//! finite and non-negative, the reference row has zero error, and — an independent truth — the
//! error in $`\lambda_c`$ falls monotonically as the mesh is refined (mesh convergence).

use std::path::{Path, PathBuf};
use std::process::Command;

const COLUMNS: [&str; 35] = [
    "model",
    "sweep",
    "method",
    "outcome",
    "nx",
    "ny",
    "dofs",
    "order",
    "series_tolerance",
    "wavenumber",
    "wavenumber_fixed",
    "steps",
    "factorizations",
    "prediction_factorizations",
    "time_threshold",
    "time_path",
    "time_total",
    "time_assembly",
    "time_factorization",
    "time_series",
    "time_series_solves",
    "time_residual_checks",
    "time_bifurcation",
    "time_recording",
    "time_step_floor",
    "peak_memory_mb",
    "tape_mb",
    "factor_nonzeros",
    "critical_load",
    "error_critical_load",
    "error_critical_load_closed_form",
    "load_at_amplitude_1",
    "error_load_at_amplitude_1",
    "amplitude_at_1_1",
    "error_amplitude_at_1_1",
];

const ERRORS: [&str; 4] = [
    "error_critical_load",
    "error_critical_load_closed_form",
    "error_load_at_amplitude_1",
    "error_amplitude_at_1_1",
];

/// Largest relative spread of λ(a/h = 1) between ANM+Padé, ANM and Riks on one mesh.
const METHOD_AGREEMENT: f64 = 1e-3;

fn directory(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("wrinkle-test-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    dir
}

/// The CSV as rows of `(column, cell)` maps.
fn read_csv(path: &Path) -> (Vec<String>, Vec<Vec<String>>) {
    let text = std::fs::read_to_string(path).unwrap();
    let mut lines = text.lines();
    let header: Vec<String> = lines
        .next()
        .unwrap()
        .split(',')
        .map(str::to_string)
        .collect();
    let rows = lines
        .map(|l| l.split(',').map(str::to_string).collect())
        .collect();
    (header, rows)
}

/// The path's time split: every part is a non-negative share of the path's time, and they do
/// not add up to more than it; the series' solves are part of the series; the tape and the
/// factor are resident, so the peak memory holds them.
fn check_cost_split(row: &[String], number: &dyn Fn(&str) -> Option<f64>) {
    let path = number("time_path").unwrap();
    let parts = [
        "time_assembly",
        "time_factorization",
        "time_series",
        "time_residual_checks",
        "time_bifurcation",
        "time_recording",
    ];
    let mut sum = 0.0;
    for part in parts {
        let t = number(part).unwrap_or_else(|| panic!("{part} empty in {row:?}"));
        assert!(t >= 0.0 && t <= path, "{part} = {t} against path {path}");
        sum += t;
    }
    assert!(sum <= path * 1.001, "parts {sum} > path {path}: {row:?}");
    let (series, solves) = (
        number("time_series").unwrap(),
        number("time_series_solves").unwrap(),
    );
    assert!((0.0..=series).contains(&solves), "{row:?}");
    // The predictions' factorisations are some of the path's, timed apart.
    let factorizations = number("factorizations").unwrap();
    let predictions = number("prediction_factorizations").unwrap();
    assert!((0.0..=factorizations).contains(&predictions), "{row:?}");
    let dofs = number("dofs").unwrap();
    let factor = number("factor_nonzeros").unwrap();
    assert!(
        factor >= dofs,
        "a factor holds at least the diagonal: {row:?}"
    );
    let riks = row.iter().any(|c| c == "riks");
    let tape = number("tape_mb");
    assert_eq!(tape.is_none(), riks, "a tape for the ANM only: {row:?}");
    if cfg!(target_os = "linux") {
        let peak = number("peak_memory_mb").expect("Linux reports the peak resident set");
        let held = tape.unwrap_or(0.0) + factor * 8e-6;
        assert!(
            peak >= held,
            "peak {peak} MB below tape + factor {held} MB: {row:?}"
        );
    }
}

#[test]
fn quick_bench_converges_with_the_mesh_and_measures_against_its_reference() {
    let out = directory("bench");
    let output = Command::new(env!("CARGO_BIN_EXE_wrinkle"))
        .args(["bench", "--quick", "--out"])
        .arg(&out)
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert_eq!(output.status.code(), Some(0), "stderr:\n{stderr}");
    let stdout = String::from_utf8_lossy(&output.stdout);
    assert!(stdout.contains("reference reference-envelope"), "{stdout}");
    for file in [
        "bench.csv",
        "bench.md",
        "bench.json",
        "bench.png",
        "bench.svg",
    ] {
        assert!(out.join(file).is_file(), "missing {file}");
    }

    let (header, rows) = read_csv(&out.join("bench.csv"));
    assert_eq!(header, COLUMNS);
    let column = |name: &str| header.iter().position(|c| c == name).unwrap();
    let number = |row: &[String], name: &str| -> Option<f64> {
        let cell = &row[column(name)];
        (!cell.is_empty()).then(|| cell.parse().unwrap())
    };
    assert!(rows.len() >= 5, "{rows:?}");
    for row in &rows {
        assert_eq!(row.len(), COLUMNS.len(), "{row:?}");
        assert_eq!(row[column("outcome")], "reached", "{row:?}\n{stderr}");
        for name in ERRORS {
            let error = number(row, name).unwrap_or_else(|| panic!("{name} empty in {row:?}"));
            assert!(error.is_finite() && error >= 0.0, "{name} = {error}");
        }
        check_cost_split(row, &|name| number(row, name));
    }
    let markdown = std::fs::read_to_string(out.join("bench.md")).unwrap();
    let table_rows = markdown.lines().filter(|l| l.starts_with("| ")).count();
    assert_eq!(
        table_rows,
        rows.len() + 1,
        "header and one line per row:\n{markdown}"
    );

    let reference: Vec<_> = rows
        .iter()
        .filter(|r| r[column("sweep")] == "reference")
        .collect();
    assert_eq!(reference.len(), 1);
    for name in [
        "error_critical_load",
        "error_load_at_amplitude_1",
        "error_amplitude_at_1_1",
    ] {
        assert_eq!(number(reference[0], name), Some(0.0), "{name}");
    }
    // The closed form (42) is an independent truth: the converged reference is close to it.
    let closed_form = number(reference[0], "error_critical_load_closed_form").unwrap();
    assert!(closed_form < 1e-2, "reference vs eq. (42): {closed_form}");

    // Mesh convergence: coarse to fine, then the reference (the finest mesh, default method).
    assert_eq!(reference[0][column("method")], "anm-pade");
    let mut mesh: Vec<(f64, f64)> = rows
        .iter()
        .filter(|r| r[column("sweep")] == "mesh" && r[column("method")] == "anm-pade")
        .chain(reference.iter().copied())
        .map(|r| {
            (
                number(r, "dofs").unwrap(),
                number(r, "error_critical_load").unwrap(),
            )
        })
        .collect();
    mesh.sort_by(|a, b| a.0.total_cmp(&b.0));
    assert!(mesh.len() >= 3, "{mesh:?}");
    assert!(
        mesh.windows(2).all(|pair| pair[1].1 < pair[0].1),
        "λ_c error does not decrease with the mesh: {mesh:?}"
    );

    // Three independent path methods on each mesh: the same load at a/h = 1 (every point of
    // each is at the residual tolerance; what differs is where the points fall).
    let mesh_rows = || {
        rows.iter()
            .filter(|r| matches!(r[column("sweep")].as_str(), "mesh" | "reference"))
    };
    let mut meshes: Vec<&str> = mesh_rows().map(|r| r[column("dofs")].as_str()).collect();
    meshes.sort();
    meshes.dedup();
    for dofs in meshes {
        let loads: Vec<(String, f64)> = mesh_rows()
            .filter(|r| r[column("dofs")] == dofs)
            .map(|r| {
                let load = number(r, "load_at_amplitude_1").unwrap();
                (r[column("method")].clone(), load)
            })
            .collect();
        let methods: Vec<&str> = loads.iter().map(|(m, _)| m.as_str()).collect();
        assert_eq!(methods.len(), 3, "{dofs} dofs: {loads:?}");
        for method in ["anm-pade", "anm", "riks"] {
            assert!(methods.contains(&method), "{dofs} dofs: {loads:?}");
        }
        let (low, high) = loads
            .iter()
            .fold((f64::INFINITY, 0.0_f64), |(l, h), (_, x)| {
                (l.min(*x), h.max(*x))
            });
        assert!(
            (high - low) / low < METHOD_AGREEMENT,
            "{dofs} dofs: methods disagree on λ(a/h = 1): {loads:?}"
        );
    }

    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("bench.json")).unwrap()).unwrap();
    assert_eq!(json["rows"].as_array().unwrap().len(), rows.len());
    assert_eq!(json["quick"], true);
    let _ = std::fs::remove_dir_all(&out);
}
