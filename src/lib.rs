//! # wrinkle
//!
//! Multi-scale membrane wrinkling after Damil, Potier-Ferry & Hu (2014): envelope models of
//! wrinkled membranes declared as energy densities, discretised with Q8 finite elements and
//! solved by linear buckling analysis and path following (ANM, Riks).
//!
//! This crate is the front end: [`scene`] parses and validates scene files (TOML plus
//! `--set KEY=VALUE` overrides), [`closed_form`] holds the independent analytic truths of the
//! clamped rectangle (THEORY.md §8) and [`analytic`] reports them for a scene, [`commands`] glues
//! scenes to the physics, and [`cli`] is the command-line interface of the `wrinkle` binary.

pub mod analytic;
pub mod bench;
pub mod cli;
pub mod closed_form;
pub mod commands;
pub mod compare;
pub mod error;
pub mod interrupt;
pub mod memory;
pub mod output;
pub mod physics;
pub mod results;
pub mod run;
pub mod run_outputs;
pub mod scene;
pub mod setup;
pub mod study;
pub mod threshold;

pub use error::{EXIT_INTERRUPTED, Error};
pub use scene::Scene;
