//! The macros that turn the declarations of `schema.rs` into Rust: `scene_schema!` writes the
//! section structs, [`Scene`](super::Scene), their defaults, `SECTIONS`, `KEYS` and the
//! schema's key table; `scene_enum!` writes an enumeration spelled as strings in a scene.

/// Declares the scene: for each section `[name] Struct { … }` and, in it, each key as
///
/// ```text
/// /// Meaning (Markdown; the doc comment of the field and the `meaning` column of the docs).
/// key => field: Type = default, kind, unit [, note "constraint involving other keys"];
/// ```
///
/// and generates the section structs (one field per key, documented with its meaning and key),
/// their `Default` impls, the [`Scene`](super::Scene) struct with one field per section, and
/// `SECTIONS`, `KEYS` and `KEY_SPECS` (each key bound to its field by accessors the compiler
/// checks against the kind's type).
macro_rules! scene_schema {
    (
        $(
            $(#[doc = $section_doc:literal])*
            [$section:ident] $Section:ident {
                $(
                    $(#[doc = $meaning:literal])*
                    $key:ident => $field:ident: $type:ty = $default:expr,
                        $kind:expr, $unit:expr $(, note $note:literal)?;
                )*
            }
        )*
    ) => {
        $(
            $(#[doc = $section_doc])*
            #[derive(Clone, Debug, PartialEq)]
            pub struct $Section {
                $(
                    $(#[doc = $meaning])*
                    #[doc = ""]
                    #[doc = concat!("Key `", stringify!($section), ".", stringify!($key), "`.")]
                    pub $field: $type,
                )*
            }

            impl Default for $Section {
                /// Every key of the table at its declared default.
                fn default() -> Self {
                    $Section {
                        $($field: $default,)*
                    }
                }
            }
        )*

        /// A complete, validated description of one computation.
        #[derive(Clone, Debug)]
        pub struct Scene {
            $(
                #[doc = concat!("Table `[", stringify!($section), "]`.")]
                pub $section: $Section,
            )*
            /// File the scene was read from, or [`BUILT_IN_SOURCE`].
            pub source: String,
            /// Keys set by `--set`, each with the assignment that set it last: an error about
            /// such a key names the override, not the file ([`Scene::origin_of`]).
            pub overridden: ::std::collections::BTreeMap<String, String>,
            /// Keys given explicitly, by the scene file or `--set`, each with its spelling and
            /// origin (a key at its default is not given). Two spellings of one key — a key and
            /// its older alias, `material.young` and `model.parameters.young` — are refused
            /// ([`Scene::apply_override`]); the notes of values not used as given are only
            /// about keys given.
            pub given: ::std::collections::BTreeMap<String, $crate::scene::Given>,
        }

        /// Two scenes are equal when they describe the same computation: where their keys were
        /// set ([`Scene::overridden`]) does not matter.
        impl PartialEq for Scene {
            fn eq(&self, other: &Self) -> bool {
                $(self.$section == other.$section &&)* self.source == other.source
            }
        }

        impl Default for Scene {
            /// The paper's example 1 (THEORY.md §9): clamped 400 × 200 mm rectangle,
            /// $`h = 0.05`$ mm, $`E = 70000`$ MPa, $`\nu = 0.3`$, $`N_Y = 10`$ N/mm, reference
            /// envelope model — every key at its declared default.
            fn default() -> Self {
                Scene {
                    $($section: $Section::default(),)*
                    source: BUILT_IN_SOURCE.to_string(),
                    overridden: ::std::collections::BTreeMap::new(),
                    given: ::std::collections::BTreeMap::new(),
                }
            }
        }

        /// Tables a scene may contain, in document order.
        pub const SECTIONS: &[&str] = &[$(stringify!($section)),*];

        /// Every key a scene may contain, in document order (`model.parameters` is a table of
        /// free-form names).
        pub const KEYS: &[&str] = &[
            $($(concat!(stringify!($section), ".", stringify!($key)),)*)*
        ];

        /// Every key's declaration, bound to its field.
        static KEY_SPECS: &[$crate::scene::keys::KeySpec<Scene>] = &[
            $($(
                $crate::scene::keys::KeySpec {
                    section: stringify!($section),
                    name: stringify!($key),
                    key: concat!(stringify!($section), ".", stringify!($key)),
                    unit: $unit,
                    meaning: concat!($($meaning, "\n",)*),
                    note: concat!("" $(, $note)?),
                    binding: &$crate::scene::keys::Field::<Scene, _> {
                        kind: $kind,
                        get: |scene| &scene.$section.$field,
                        get_mut: |scene| &mut scene.$section.$field,
                    },
                },
            )*)*
        ];
    };
}

/// Declares an enumeration whose values a scene spells as strings:
/// `Variant = "spelling",` for each, with doc comments. Generates the enum, its `as_str` and
/// its [`Choices`](super::kinds::Choices).
macro_rules! scene_enum {
    (
        $(#[doc = $doc:literal])*
        pub enum $Enum:ident {
            $(
                $(#[doc = $variant_doc:literal])*
                $Variant:ident = $spelling:literal,
            )*
        }
    ) => {
        $(#[doc = $doc])*
        #[derive(Clone, Copy, Debug, PartialEq, Eq)]
        pub enum $Enum {
            $(
                $(#[doc = $variant_doc])*
                $Variant,
            )*
        }

        impl $Enum {
            /// The scene spelling.
            pub fn as_str(self) -> &'static str {
                match self {
                    $($Enum::$Variant => $spelling,)*
                }
            }
        }

        impl $crate::scene::kinds::Choices for $Enum {
            const CHOICES: &'static [(&'static str, Self)] = &[$(($spelling, $Enum::$Variant)),*];
        }
    };
}

pub(super) use {scene_enum, scene_schema};
