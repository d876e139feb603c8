//! The paper's example 1 on Gmsh meshes (`examples/meshes/`, made by Gmsh 4.15 from the `.geo`
//! files beside them).
//!
//! * `example1_rectangle.msh` (ASCII) and `example1_rectangle_binary.msh` hold the nodes and
//!   elements of the built-in 32 × 16 mesh, numbered differently: the critical load (wavenumber
//!   searched) equals the built-in one to 1e-10 relative.
//! * `example1_unstructured_{25,12,6}.msh`: unstructured quadrilaterals of about 25, 12.5 and
//!   6.25 mm. At the closed form's critical wavenumber the error of $`\lambda_c(Q)`$ against
//!   eq. (42) falls at the rate of the element: measured errors and rates are printed and
//!   bounded below.

use wrinkle::commands::buckle;
use wrinkle::scene::Scene;

fn mesh_file(name: &str) -> String {
    format!("{}/examples/meshes/{name}", env!("CARGO_MANIFEST_DIR"))
}

fn scene_on(file: Option<&str>, settings: &[String]) -> Scene {
    let mut scene = Scene::default();
    if let Some(name) = file {
        scene
            .apply_override(&format!("mesh.file=\"{}\"", mesh_file(name)))
            .unwrap();
    }
    for setting in settings {
        scene.apply_override(setting).unwrap();
    }
    scene.validate().unwrap();
    scene
}

#[test]
fn gmsh_file_of_the_built_in_mesh_gives_the_same_critical_load() {
    let built_in = buckle(&scene_on(None, &[]), true).unwrap();
    for file in ["example1_rectangle.msh", "example1_rectangle_binary.msh"] {
        let report = buckle(&scene_on(Some(file), &[]), true).unwrap();
        let difference = (report.critical_load() / built_in.critical_load() - 1.0).abs();
        eprintln!(
            "{file}: λ_c {:.15e} (built-in {:.15e}, relative difference {difference:.2e}), {} dofs",
            report.critical_load(),
            built_in.critical_load(),
            report.dofs
        );
        assert_eq!(report.dofs, built_in.dofs);
        assert!(difference < 1e-10, "{file}: {difference:e}");
        let q = (report.wavenumber.unwrap() / built_in.wavenumber.unwrap() - 1.0).abs();
        assert!(q < 1e-8, "{file}: wavenumber differs by {q:e}");
    }
}

#[test]
fn unstructured_gmsh_meshes_converge_to_the_closed_form() {
    let base = Scene::default();
    let (_, q) = base.clamped_rectangle().critical_point().unwrap();
    let exact = base.clamped_rectangle().neutral_curve(q);
    let mut errors = Vec::new();
    for file in [
        "example1_unstructured_25.msh",
        "example1_unstructured_12.msh",
        "example1_unstructured_6.msh",
    ] {
        let scene = scene_on(Some(file), &[format!("model.wavenumber={q}")]);
        let report = buckle(&scene, true).unwrap();
        let error = (report.critical_load() - exact).abs() / exact;
        eprintln!(
            "{file}: {} dofs, λ_c(Q) {:.12e}, eq. (42) {exact:.12e}, relative error {error:.3e}",
            report.dofs,
            report.critical_load()
        );
        errors.push(error);
    }
    let rates: Vec<f64> = errors.windows(2).map(|e| (e[0] / e[1]).log2()).collect();
    eprintln!("observed rates (per halving of the element size) {rates:?}");
    for rate in &rates {
        assert!(*rate > 3.0, "observed rate {rate}");
    }
}
