//! `wrinkle buckle --out DIR` on the long strip (the shipped scene, 56 × 16 graded toward the
//! corners): the wavenumber search runs on two meshes — its first level on the half mesh
//! (28 × 8), its refinement on the scene's — and `wavenumber_search.csv` says which for every
//! analysis. Truths: the threshold of `buckle.json` is one of the scene's rows to the last
//! digit and their minimum to the search's tolerance; the half mesh's rows come first and
//! their minimum lies below it (a coarser mesh of the same conforming elements is softer here:
//! 13.44 against 14.38 mm), which is why the plot draws the two as separate curves.

use std::path::PathBuf;
use std::process::Command;

#[test]
fn the_strip_search_csv_names_the_mesh_of_each_analysis() {
    let dir: PathBuf =
        std::env::temp_dir().join(format!("wrinkle-buckle-search-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    let output = Command::new(env!("CARGO_BIN_EXE_wrinkle"))
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .args(["buckle", "examples/scenes/long_strip.toml", "-q", "--out"])
        .arg(&dir)
        .output()
        .unwrap();
    assert_eq!(
        output.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
    let buckle: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("buckle.json")).unwrap()).unwrap();
    let critical = buckle["critical_load"].as_f64().unwrap();
    let csv = std::fs::read_to_string(dir.join("wavenumber_search.csv")).unwrap();
    let mut lines = csv.lines();
    assert_eq!(
        lines.next(),
        Some("wavenumber,critical_load,phase,mesh,rejected")
    );
    let rows: Vec<Vec<&str>> = lines.map(|l| l.splitn(5, ',').collect()).collect();
    let minimum = |mesh: &str| {
        rows.iter()
            .filter(|r| r[3] == mesh && !r[1].is_empty())
            .map(|r| r[1].parse::<f64>().unwrap())
            .fold(f64::INFINITY, f64::min)
    };
    let first_scene = rows.iter().position(|r| r[3] == "scene").unwrap();
    assert!(first_scene > 0, "the half mesh's level comes first");
    assert!(
        rows[first_scene..].iter().all(|r| r[3] == "scene"),
        "every analysis after the first level is on the scene's mesh"
    );
    // The threshold is one of the scene's analyses, to the last digit; the curve's own scan
    // about it may land a hair lower (5e-10 relative here: the minimisation's tolerance).
    assert!(
        rows.iter()
            .any(|r| r[3] == "scene" && r[1].parse::<f64>().ok() == Some(critical))
    );
    assert!((minimum("scene") - critical).abs() <= 1e-8 * critical);
    assert!(minimum("half") < critical, "{} {critical}", minimum("half"));
    assert!(dir.join("wavenumber_search.png").is_file());
    let _ = std::fs::remove_dir_all(&dir);
}
