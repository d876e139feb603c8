//! Kinds of scene values: how each is read from TOML, checked against its bounds, written back
//! (the effective-scene TOML and the JSON echo) and described in `docs/scenes.md`'s key tables.
//!
//! A leaf kind implements [`Scalar`] (one value: a bounded float or integer, a flag, a string,
//! a choice, a list); every [`Scalar`] is a [`ValueKind`], and so is a [`Table`] of named
//! scalars (`model.parameters`). A new kind of value is one more type here; a new key of an
//! existing kind is one declaration in `schema.rs`. `value` holds the two traits and what
//! every kind shares; `number`, `name` and `collection` the kinds themselves.

mod boundary;
mod collection;
mod name;
mod number;
mod points;
mod value;

pub use boundary::{Boundary, BoundarySpec, Component, InPlane, OptionalPath, Transverse};
pub use collection::{ChoiceList, FloatList, Table};
pub use name::{Choices, Flag, ModelName, Text, one_of};
pub use number::{AutoOrNumber, Count, Float, number_or_auto};
pub use points::PointTable;
pub use value::{Problem, Scalar, ValueKind, Written};
