//! `docs/scenes.md`'s key tables are the scene schema's (`src/scene/schema.rs`): this test fails
//! when a table and the declarations differ, and `WRINKLE_BLESS=1 cargo test --test scene_docs`
//! rewrites the tables in place (the prose around them is left as written).

use std::path::PathBuf;
use wrinkle::scene::{SECTIONS, key_table, refresh_key_tables};

fn scenes_md() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("docs/scenes.md")
}

#[test]
fn docs_key_tables_are_the_schemas() {
    let path = scenes_md();
    let written = std::fs::read_to_string(&path).expect("docs/scenes.md is readable");
    let generated = refresh_key_tables(&written).unwrap_or_else(|error| panic!("{error}"));
    if generated == written {
        return;
    }
    if std::env::var_os("WRINKLE_BLESS").is_some() {
        std::fs::write(&path, &generated).expect("docs/scenes.md is writable");
        return;
    }
    let first = written
        .lines()
        .zip(generated.lines())
        .position(|(old, new)| old != new)
        .map_or(
            written.lines().count().min(generated.lines().count()),
            |i| i,
        );
    panic!(
        "docs/scenes.md's key tables differ from the schema from line {}:\n  written:   {}\n  generated: {}\n\
         run `WRINKLE_BLESS=1 cargo test --test scene_docs` to rewrite them",
        first + 1,
        written.lines().nth(first).unwrap_or("<end of file>"),
        generated.lines().nth(first).unwrap_or("<end of file>"),
    );
}

#[test]
fn every_table_lists_every_key_with_its_default() {
    for section in SECTIONS {
        let table = key_table(section);
        let rows: Vec<&str> = table.lines().skip(2).collect();
        let keys = wrinkle::scene::KEYS
            .iter()
            .filter(|key| key.split_once('.').is_some_and(|(s, _)| s == *section));
        for key in keys {
            let name = key.split_once('.').unwrap().1;
            assert!(
                rows.iter()
                    .any(|row| row.starts_with(&format!("| `{name}` |"))),
                "{key} missing from\n{table}"
            );
        }
    }
    let model = key_table("model");
    assert!(
        model.contains("| `wavenumber_model` |") && model.contains("`\"reference-envelope\"`"),
        "{model}"
    );
    let solver = key_table("solver");
    assert!(solver.contains("| `max_envelope_over_h` |"), "{solver}");
    assert!(solver.contains(r"(\varepsilon\|U_1\|/\|U_N\|)"), "{solver}");
    assert!(solver.contains(r"$`\max\|w\|/h`$"), "{solver}");
}

#[test]
fn markers_must_name_a_table_and_be_closed() {
    let unknown = "<!-- keys nowhere -->\n<!-- /keys -->\n";
    assert!(refresh_key_tables(unknown).unwrap_err().contains("nowhere"));
    let unclosed = "<!-- keys geometry -->\n| old |\n";
    assert!(
        refresh_key_tables(unclosed)
            .unwrap_err()
            .contains("not closed")
    );
    let missing = "<!-- keys geometry -->\n<!-- /keys -->\n";
    assert!(
        refresh_key_tables(missing)
            .unwrap_err()
            .contains("[material]")
    );
}
