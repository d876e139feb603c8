//! Where a model's threshold takes its wavenumber from is a capability derived from its roles
//! and jet (`wrinkle_runtime::wavelength`), and the model that gives $`Q`$ to the others is the
//! scene's `model.wavenumber_model` — never a model name compared in the application.
//!
//! Registered models and their expected capability (THEORY.md §3–§6): the reference envelope
//! (real envelope with gradient) selects its own wavelength; the pure membrane (no envelope
//! gradient, threshold $`DQ^2`$) and the complex envelope (a phase) carry it; the plate (no
//! `wavenumber` parameter) resolves its wrinkles on the mesh. Scene: example 1 on 8 × 4, where a
//! threshold takes a fraction of a second.

use wrinkle::{Error, Scene};
use wrinkle_runtime::wavelength::{CarriedBecause, WavelengthSelection};

fn selection_of(name: &str) -> WavelengthSelection {
    wrinkle_models::catalogue()
        .into_iter()
        .find(|spec| spec.name == name)
        .unwrap_or_else(|| panic!("`{name}` is registered"))
        .wavelength_selection()
}

#[test]
fn the_four_registered_models_have_the_capability_their_roles_give() {
    assert_eq!(
        selection_of("reference-envelope"),
        WavelengthSelection::OwnMinimum
    );
    assert_eq!(
        selection_of("pure-membrane"),
        WavelengthSelection::Carried(CarriedBecause::NoEnvelopeGradient)
    );
    assert_eq!(
        selection_of("complex-envelope"),
        WavelengthSelection::Carried(CarriedBecause::Phase)
    );
    assert_eq!(
        selection_of("fvk-plate"),
        WavelengthSelection::ResolvedByMesh
    );
    assert!(selection_of(wrinkle_models::REFERENCE_MODEL).selects_its_own());
}

fn coarse(settings: &[&str]) -> Scene {
    let mut scene = Scene::default();
    for setting in ["mesh.nx=8", "mesh.ny=4"].iter().chain(settings) {
        scene.apply_override(setting).unwrap();
    }
    scene.validate().unwrap();
    scene
}

/// A wavenumber model that does not select its own wavelength is a scene error naming the key,
/// for the model that would use it and for the model itself.
#[test]
fn a_wavenumber_model_without_its_own_selection_is_refused_naming_the_key() {
    for (model, helper) in [
        ("pure-membrane", "complex-envelope"),
        ("reference-envelope", "fvk-plate"),
        ("complex-envelope", "complex-envelope"),
    ] {
        let scene = coarse(&[
            &format!("model.name={model}"),
            &format!("model.wavenumber_model={helper}"),
        ]);
        match wrinkle::commands::buckle(&scene, true) {
            Err(Error::Scene { key, message, .. }) => {
                assert_eq!(key, "model.wavenumber_model", "{message}");
                assert!(
                    message.contains(&format!("`{helper}` does not select its own wavelength"))
                        && message.contains("reference-envelope"),
                    "{message}"
                );
            }
            other => panic!("{model} with {helper}: expected a scene error, got {other:?}"),
        }
    }
}

/// A carried wavenumber is the wavenumber model's minimiser, bit for bit, and the notes name
/// that model; the wavenumber model's own threshold has no such note.
#[test]
fn a_carried_wavenumber_is_the_wavenumber_models_minimiser_and_the_note_names_it() {
    let reference = wrinkle::commands::buckle(&coarse(&[]), true).unwrap();
    assert_eq!(reference.wavenumber_source, "auto");
    assert!(reference.notes.is_empty(), "{:?}", reference.notes);
    for model in ["pure-membrane", "complex-envelope"] {
        let carried =
            wrinkle::commands::buckle(&coarse(&[&format!("model.name={model}")]), true).unwrap();
        assert_eq!(carried.wavenumber, reference.wavenumber, "{model}");
        assert_eq!(carried.wavenumber_source, "auto (reference-envelope)");
        assert!(
            carried
                .notes
                .iter()
                .any(|n| n.contains("is the reference-envelope minimiser on the same scene")),
            "{model}: {:?}",
            carried.notes
        );
    }
}
