//! The annulus under differential radial tension (`examples/scenes/annulus.toml`, Gmsh mesh
//! `examples/meshes/annulus*.msh` from `annulus.geo`): inner radius 75 mm, outer 150 mm, outer
//! rim clamped and held, inner rim free and pulled toward the centre by λ N/mm; `fvk-plate`.
//! The Lamé state compresses the hoop direction near the inner rim and the sheet wrinkles in
//! radial folds (9 waves around on the shipped mesh, `docs/validation.md`, "Annulus").
//!
//! Reduced for CI: the coarse mesh `annulus_coarse.msh` (48 elements around, 4 across) to an
//! amplitude of one thickness, with plots: the wrinkle map is masked in the hole and the
//! profile along a line through the hole (`output.profile_line`) has empty cells there. And the
//! mode-resolution check on a file mesh measures the elements themselves: example 1 on the
//! unstructured 25 mm Gmsh mesh resolves the plate's mode with about 2 elements per wavelength
//! (measured 2.03: the largest extent along X of the elements under the mode is 12.5 mm) and
//! says so, naming the file.

use std::path::Path;
use std::process::Command;
use wrinkle::commands::buckle;
use wrinkle::scene::Scene;

fn example(path: &str) -> String {
    format!("{}/examples/{path}", env!("CARGO_MANIFEST_DIR"))
}

#[test]
fn the_annulus_wrinkles_and_its_map_and_line_profile_leave_the_hole_blank() {
    let out = std::env::temp_dir().join(format!("wrinkle-annulus-{}", std::process::id()));
    let output = Command::new(env!("CARGO_BIN_EXE_wrinkle"))
        .args(["run", "-q", &example("scenes/annulus.toml"), "--out"])
        .arg(&out)
        .args([
            "--set",
            "mesh.file=\"../meshes/annulus_coarse.msh\"",
            "--set",
            "solver.max_amplitude_over_h=1",
            "--set",
            "output.profile_line=[-150, 0, 150, 0]",
            "--set",
            "output.surface=false",
        ])
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(
        matches!(output.status.code(), Some(0 | 4)),
        "{:?}: {stderr}",
        output.status
    );
    for file in ["wrinkles.png", "profile_line.png", "membrane_force_N_X.png"] {
        assert!(out.join(file).is_file(), "{file}");
    }
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    let critical = summary["linear_buckling_load"].as_f64().unwrap();
    assert!(critical > 0.0 && critical.is_finite(), "{critical}");
    check_line_profile(&out.join("profile_line.csv"));
    std::fs::remove_dir_all(&out).ok();
}

/// Empty cells inside the hole ($`|X| < 75`$ mm) and finite ones on the sheet.
fn check_line_profile(path: &Path) {
    let text = std::fs::read_to_string(path).unwrap();
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    assert_eq!(&header[..3], ["s_mm", "x_mm", "y_mm"]);
    assert!(header[3].starts_with("w_over_h_at_"), "{header:?}");
    let (mut blank, mut filled) = (0, 0);
    for line in lines {
        let cells: Vec<&str> = line.split(',').collect();
        assert_eq!(cells.len(), header.len(), "{line}");
        let x: f64 = cells[1].parse().unwrap();
        if x.abs() < 74.0 {
            assert!(cells[3..].iter().all(|c| c.is_empty()), "{line}");
            blank += 1;
        } else if x.abs() > 76.0 {
            assert!(
                cells[3..]
                    .iter()
                    .all(|c| c.parse::<f64>().unwrap().is_finite())
            );
            filled += 1;
        }
    }
    assert!(blank > 100 && filled > 100, "{blank} {filled}");
}

#[test]
fn a_file_mesh_is_judged_on_its_elements_for_mode_resolution() {
    let mut scene = Scene::default();
    for setting in [
        format!(
            "mesh.file=\"{}\"",
            example("meshes/example1_unstructured_25.msh")
        ),
        "model.name=\"fvk-plate\"".to_string(),
    ] {
        scene.apply_override(&setting).unwrap();
    }
    scene.validate().unwrap();
    let threshold = buckle(&scene, true).unwrap();
    let warning = threshold
        .warnings
        .iter()
        .find(|w| w.check == "mode_resolution")
        .expect("a 25 mm mesh does not resolve a 27 mm wave");
    eprintln!("{}", warning.message);
    assert!(
        warning.message.contains("refine the mesh file"),
        "{}",
        warning.message
    );
    let count: f64 = warning.message.split(' ').next().unwrap().parse().unwrap();
    assert!((1.5..3.0).contains(&count), "{}", warning.message);
}
