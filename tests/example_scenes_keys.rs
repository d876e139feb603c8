//! The example scenes are written with the current keys: `solver.max_amplitude_over_h` (the
//! physical amplitude), not the older `max_envelope_over_h` (docs/scenes.md keeps it only for old
//! files).

#[test]
fn example_scenes_use_no_older_key() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/scenes");
    let mut checked = 0;
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().is_some_and(|e| e == "toml") {
            let text = std::fs::read_to_string(&path).unwrap();
            assert!(
                !text.contains("max_envelope_over_h"),
                "{} uses the older key max_envelope_over_h",
                path.display()
            );
            checked += 1;
        }
    }
    assert!(checked >= 2);
}
