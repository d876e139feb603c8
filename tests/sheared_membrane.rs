//! The sheared membrane of Wong & Pellegrino (`examples/scenes/sheared_membrane.toml`, Kapton
//! 380 × 128 mm, h = 25 µm; bottom edge clamped, top edge clamped, lifted by the pre-stretch
//! $`v_0 = 0.05`$ mm and moved by the shear $`\lambda`$ along X; short sides free), reduced for
//! CI from the study of `examples/sheared_membrane.rs` (`docs/validation.md` §4c).
//!
//! The independent truth is the band's closed form. Far from the free short sides the clamped
//! band is in **simple shear plus stretch**: $`u = \lambda Y/H`$, $`v = v_0 Y/H`$, so
//! $`\varepsilon_X = 0`$, $`\varepsilon_Y = v_0/H`$, $`\gamma = \lambda/H`$ and, with
//! $`C = Eh/(1-\nu^2)`$ and $`G = E/(2(1+\nu))`$,
//! ```math
//! N_X = C\nu\,v_0/H,\qquad N_Y = C\,v_0/H,\qquad N_{XY} = G h\,\lambda/H .
//! ```
//! Its principal compression is at $`\theta_c`$ with $`\tan 2\theta_c = 2N_{XY}/(N_X - N_Y)`$
//! (the branch in $`(-90°, 0°)`$): −31.7° at λ = 0.1 mm, tending to −45° as the shear dominates
//! the pre-stretch. Tension-field theory says wrinkles carry no compression: past the threshold
//! the crests lie along the principal tension, i.e. the wave vector of the central wrinkles is
//! along $`\theta_c`$ of the pre-buckling state at the same shear.
//!
//! * Before the threshold (λ = 0.04 mm, a coarse plate) the stress resultants the run stores in
//!   the central region are the closed form's.
//! * Past it, the plate's central wrinkles have the closed form's direction, and it turns with
//!   the shear (measured on the path, `wrinkle::region_measures`): on the shipped 60 × 24
//!   mesh at 0.08 mm in CI, to 0.2 mm opt-in (the study goes to 3 mm on 120 × 48; a 40 × 16
//!   plate does not resolve the wrinkles and its path stalls before 0.1 mm).

use std::path::{Path, PathBuf};
use vtkio::model::{Attribute, DataSet, Piece, Vtk};
use wrinkle::Scene;
use wrinkle::compare::read_state;
use wrinkle::region_measures::{Region, measure_region};

const LENGTH: f64 = 380.0;
const HEIGHT: f64 = 128.0;
const YOUNG: f64 = 3530.0;
const POISSON: f64 = 0.3;
const THICKNESS: f64 = 0.025;
const PRE_STRETCH: f64 = 0.05;

/// $`(N_X, N_Y, N_{XY})`$ of the band at shear `shear` (mm).
fn band_forces(shear: f64) -> [f64; 3] {
    let c = YOUNG * THICKNESS / (1.0 - POISSON * POISSON);
    let g = YOUNG / (2.0 * (1.0 + POISSON));
    [
        c * POISSON * PRE_STRETCH / HEIGHT,
        c * PRE_STRETCH / HEIGHT,
        g * THICKNESS * shear / HEIGHT,
    ]
}

/// The principal compression direction of the band (degrees from X, in (−90°, 0°)).
fn band_compression_degrees(shear: f64) -> f64 {
    let [n_x, n_y, n_xy] = band_forces(shear);
    // The eigenvector of the smaller principal force: θ = ½ atan2(−2N_XY, N_Y − N_X) rotated.
    let tension = 0.5 * (2.0 * n_xy).atan2(n_x - n_y);
    (tension - std::f64::consts::FRAC_PI_2).to_degrees()
}

fn scene() -> Scene {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/scenes/sheared_membrane.toml");
    Scene::load(path).unwrap()
}

fn scratch(test: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("wrinkle-sheared-{}-{test}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    dir
}

/// Cell array `name` of a fields file, with the cells' centres (mean of their corner nodes).
fn cell_values(file: &Path, name: &str) -> Vec<([f64; 2], f64)> {
    let vtk = Vtk::import(file).unwrap();
    let DataSet::UnstructuredGrid { pieces, .. } = vtk.data else {
        panic!("not an unstructured grid");
    };
    let Piece::Inline(piece) = pieces.into_iter().next().unwrap() else {
        panic!("piece not inline");
    };
    let points: Vec<f64> = piece.points.cast_into().unwrap();
    let vtkio::model::VertexNumbers::XML { connectivity, .. } = piece.cells.cell_verts else {
        panic!("not XML connectivity");
    };
    let attribute = piece
        .data
        .cell
        .iter()
        .find(|a| a.name() == name)
        .unwrap_or_else(|| panic!("no cell array {name}"));
    let Attribute::DataArray(array) = attribute else {
        panic!("{name} is not a data array");
    };
    let values: Vec<f64> = array.data.clone().cast_into().unwrap();
    connectivity
        .chunks(8)
        .zip(values)
        .map(|(cell, value)| {
            let mut centre = [0.0; 2];
            for &node in &cell[..4] {
                centre[0] += 0.25 * points[3 * node as usize];
                centre[1] += 0.25 * points[3 * node as usize + 1];
            }
            (centre, value)
        })
        .collect()
}

#[test]
fn the_sheared_band_is_in_simple_shear_plus_stretch_away_from_its_free_sides() {
    let out = scratch("prebuckling");
    let mut scene = scene();
    for setting in [
        "mesh.nx=30",
        "mesh.ny=12",
        "output.vtu_loads=[0.04]",
        "solver.max_load=0.04",
        "output.plots=false",
        "output.surface=false",
    ] {
        scene.apply_override(setting).unwrap();
    }
    scene.validate().unwrap();
    // Stops at λ = 0.04 mm, below the threshold: the run reports the load limit, not an error.
    let _ = wrinkle::run::run(&scene, &out, true);
    let file = out.join("fields_load_0.040000.vtu");
    assert!(file.is_file(), "no {}", file.display());
    let expected = band_forces(0.04);
    let mut means = [0.0; 3];
    for (k, name) in ["N_X", "N_Y", "N_XY"].into_iter().enumerate() {
        let central: Vec<f64> = cell_values(&file, name)
            .into_iter()
            .filter(|([x, y], _)| {
                (0.4 * LENGTH..0.6 * LENGTH).contains(x)
                    && (0.25 * HEIGHT..0.75 * HEIGHT).contains(y)
            })
            .map(|(_, value)| value)
            .collect();
        assert!(
            central.len() >= 12,
            "{name}: {} central cells",
            central.len()
        );
        means[k] = central.iter().sum::<f64>() / central.len() as f64;
        eprintln!(
            "{name}: {central:.5?}, mean {:.5e}, band {:.5e}",
            means[k], expected[k]
        );
    }
    // The stretch and the shear carried across the centre are the band's; N_X, which vanishes
    // on the free sides 1.5 H away, has not fully recovered there (measured −17 %).
    for k in [1, 2] {
        assert!(
            (means[k] - expected[k]).abs() < 1e-2 * expected[k],
            "{k}: {:.5e} against {:.5e}",
            means[k],
            expected[k]
        );
    }
    assert!(
        means[0] > 0.7 * expected[0] && means[0] < expected[0],
        "{:.5e} against {:.5e}",
        means[0],
        expected[0]
    );
    // The principal compression of the central state: the band's direction to 1°.
    let [n_x, n_y, n_xy] = means;
    let central = (0.5 * (2.0 * n_xy).atan2(n_x - n_y) - std::f64::consts::FRAC_PI_2).to_degrees();
    let band = band_compression_degrees(0.04);
    assert!(
        (central - band).abs() < 1.0,
        "{central:.2}° against {band:.2}°"
    );
    let _ = std::fs::remove_dir_all(&out);
}

/// Runs the plate on the shipped 60 × 24 mesh to the last of `shears` and checks its central
/// wrinkles at each against the band's principal compression (2°), turning with the shear.
fn central_wrinkles_follow_the_band(test: &str, shears: &[f64]) {
    let out = scratch(test);
    let last = shears.iter().copied().fold(0.0, f64::max);
    let mut scene = scene();
    for setting in [
        format!("output.vtu_loads={shears:?}"),
        format!("solver.max_load={last}"),
        "solver.max_amplitude_over_h=100".to_string(),
        "validity.accept=[\"all\"]".to_string(),
        "output.plots=false".to_string(),
        "output.surface=false".to_string(),
    ] {
        scene.apply_override(&setting).unwrap();
    }
    scene.validate().unwrap();
    let _ = wrinkle::run::run(&scene, &out.join("fvk-plate"), true);
    let region = Region {
        x: [0.25 * LENGTH, 0.75 * LENGTH],
        y: [0.25 * HEIGHT, 0.75 * HEIGHT],
    };
    let mut previous = 0.0;
    for &shear in shears {
        let state = read_state(&out, "fvk-plate", shear, shears)
            .unwrap_or_else(|| panic!("no state at {shear} mm"));
        let measures = measure_region(&state.snapshot(0.0), &region, 0.5)
            .unwrap_or_else(|| panic!("flat at {shear} mm"));
        let band = band_compression_degrees(shear);
        eprintln!("shear {shear}: {measures:?}, band {band:.2}°");
        assert!(measures.amplitude > 0.1 * THICKNESS, "{measures:?}");
        assert!(measures.coherence > 0.9, "{measures:?}");
        assert!(
            (measures.direction_degrees - band).abs() < 2.0,
            "central wave vector {:.2}° against the band's compression {band:.2}°",
            measures.direction_degrees
        );
        assert!(measures.direction_degrees < previous, "{measures:?}");
        previous = measures.direction_degrees;
    }
    let _ = std::fs::remove_dir_all(&out);
}

/// CI: just past the centre's onset of compression (0.0785 mm), 17 steps.
#[test]
fn the_plates_central_wrinkles_lie_along_the_principal_tension_of_the_band() {
    central_wrinkles_follow_the_band("path", &[0.08]);
}

/// Opt-in (about a minute in release, more in debug): the direction turning from −29° to −38°
/// between 0.08 and 0.2 mm. `cargo test --release --test sheared_membrane -- --ignored`.
#[test]
#[ignore = "heavy: the plate's path to 0.2 mm of shear"]
fn the_plates_central_wrinkles_turn_with_the_principal_tension_of_the_band() {
    central_wrinkles_follow_the_band("turning", &[0.08, 0.1, 0.15, 0.2]);
}

#[test]
fn the_bands_compression_turns_from_the_pre_stretch_to_the_diagonal() {
    // Pure shear (no pre-stretch) compresses at −45°: the limit of large shears.
    assert!((band_compression_degrees(1e6) + 45.0).abs() < 1e-3);
    assert!((band_compression_degrees(0.1) + 31.7).abs() < 0.1);
    assert!(band_compression_degrees(0.2) < band_compression_degrees(0.1));
}
