//! How a sweep point's scene is made ([`SceneRecipe`]) and the content hash of the scene it
//! makes ([`content_hash`]).
//!
//! A point is not handed around as its effective scene but as the recipe that made it — the base
//! scene's TOML text and the `KEY=VALUE` overrides in order — so that the run of a point is the
//! run `wrinkle run SCENE --set KEY=VALUE ...` would do, key for key: a scene rebuilt from its
//! effective TOML would mark every key as given, and notes about keys given but unused would
//! differ.

use crate::error::Error;
use crate::scene::Scene;
use serde::{Deserialize, Serialize};

/// A scene as a base and overrides: what a sweep sends to whoever runs one of its points (a
/// child process, a Dask worker), as JSON.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct SceneRecipe {
    /// The base scene's TOML text; `None` for the built-in default scene.
    pub text: Option<String>,
    /// Where the base came from (a file's path), quoted in errors as `scene SOURCE`.
    pub source: String,
    /// `KEY=VALUE` overrides applied in order, as `--set` applies them.
    pub overrides: Vec<String>,
}

impl SceneRecipe {
    /// The recipe of the built-in default scene.
    pub fn built_in() -> Self {
        SceneRecipe {
            text: None,
            source: crate::scene::BUILT_IN_SOURCE.to_string(),
            overrides: Vec::new(),
        }
    }

    /// The recipe of a scene file (its text is read now, with the size cap of scene files).
    pub fn from_file(path: &std::path::Path) -> Result<Self, Error> {
        // Reading through `Scene::load` gives the same errors as `wrinkle run` for a missing or
        // oversized file; the text is then read again (it was just read, and is small).
        Scene::load(path)?;
        let text = crate::input::read_capped_text(path, crate::scene::MAX_SCENE_BYTES)
            .map_err(crate::error::io_error(path))?;
        Ok(SceneRecipe {
            text: Some(text),
            source: path.display().to_string(),
            overrides: Vec::new(),
        })
    }

    /// This recipe with one more override `KEY=VALUE`.
    pub fn with_override(&self, assignment: impl Into<String>) -> Self {
        let mut recipe = self.clone();
        recipe.overrides.push(assignment.into());
        recipe
    }

    /// The scene: the base parsed and validated, each override applied in order, validated
    /// again — errors name the key and the file or the `--set KEY=VALUE` that set it.
    pub fn build(&self) -> Result<Scene, Error> {
        let mut scene = match &self.text {
            Some(text) => Scene::from_toml_str(text, &self.source)?,
            None => Scene::default(),
        };
        for assignment in &self.overrides {
            scene.apply_override(assignment)?;
        }
        scene.validate()?;
        Ok(scene)
    }
}

/// Hex digits of a [`content_hash`].
pub const CONTENT_HASH_DIGITS: usize = 16;

/// The content hash of a scene: the first [`CONTENT_HASH_DIGITS`] hexadecimal digits of the
/// 128-bit FNV-1a hash of its effective TOML ([`Scene::to_toml_string`], every key in schema
/// order, floats in shortest round-trip form) without its source line and with
/// `output.directory` cleared — two recipes that make the same scene have the same hash, and a
/// point's results do not depend on where they are written. Not a cryptographic hash: it names
/// the directories of one sweep, where $`2^{64}`$ values leave a collision among $`10^4`$ points
/// at odds of about $`10^{-11}`$.
pub fn content_hash(scene: &Scene) -> String {
    let mut canonical = scene.clone();
    canonical.output.directory = String::new();
    let text = canonical.to_toml_string();
    let body = text.split_once('\n').map_or("", |(_, rest)| rest);
    let hash = fnv1a_128(body.as_bytes());
    format!("{hash:032x}")[..CONTENT_HASH_DIGITS].to_string()
}

/// The 128-bit FNV-1a hash of `bytes`.
fn fnv1a_128(bytes: &[u8]) -> u128 {
    const OFFSET: u128 = 0x6c62_272e_07bb_0142_62b8_2175_6295_c58d;
    const PRIME: u128 = 0x0000_0000_0100_0000_0000_0000_0000_013b;
    bytes.iter().fold(OFFSET, |hash, &byte| {
        (hash ^ u128::from(byte)).wrapping_mul(PRIME)
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fnv1a_128_of_the_empty_input_is_its_offset_basis() {
        assert_eq!(fnv1a_128(b""), 0x6c62_272e_07bb_0142_62b8_2175_6295_c58d);
        // Published test vector of FNV-1a 128 ("a").
        assert_eq!(fnv1a_128(b"a"), 0xd228_cb69_6f1a_8caf_7891_2b70_4e4a_8964);
    }

    #[test]
    fn the_hash_follows_the_effective_scene_not_the_recipe() {
        let default = SceneRecipe::built_in();
        let same = default.with_override("material.poisson=0.3");
        let other = default.with_override("material.poisson=0.25");
        let moved = default.with_override("output.directory=\"elsewhere\"");
        let hash = |recipe: &SceneRecipe| content_hash(&recipe.build().unwrap());
        assert_eq!(hash(&default), hash(&same));
        assert_eq!(hash(&default), hash(&moved));
        assert_ne!(hash(&default), hash(&other));
        assert_eq!(hash(&default).len(), CONTENT_HASH_DIGITS);
    }
}
