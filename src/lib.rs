//! # wrinkle
//!
//! Multi-scale membrane wrinkling after Damil, Potier-Ferry & Hu (2014): envelope models of
//! wrinkled membranes declared as energy densities, discretised with Q8 finite elements and
//! solved by linear buckling analysis and path following (ANM, Riks).
//!
//! This crate is the front end, in layers that import only downwards:
//! * [`cli`] parses arguments and prints; [`commands`] (`buckle`, `run`, `models`),
//!   [`compare`], [`bench`](mod@bench) and [`analytic`] are what the subcommands compute; `compare` and
//!   `bench` share [`study`] (loads at amplitudes, crossings, relative errors);
//! * [`threshold`] finds the wrinkling threshold (its wavenumber by the model's capability and
//!   the scene's `model.wavenumber_model`), [`run`] the path: scene → problem → threshold →
//!   imperfection → path → result;
//! * [`results`] decides a run's result ([`results::RunSummary`]: outcome and exit code,
//!   threshold with its closed form, path, statistics, notices) before anything is written;
//!   [`run_outputs`] writes it with the writers of [`output`];
//! * [`setup`] builds the problem of a scene, [`physics`] reads what the model's fields mean from
//!   their roles, [`scene`] parses and validates scene files (TOML plus `--set KEY=VALUE`),
//!   [`closed_form`] holds the independent analytic truths of the clamped rectangle
//!   (THEORY.md §8); [`error`], [`input`] (every file read with a size cap), [`interrupt`]
//!   and [`memory`] serve every layer;
//! * [`line`](mod@line) is the same pipeline on a line domain (`geometry.kind = "line"`, a
//!   beam), which `buckle`, `run` and `compare` hand a line scene to.
//! * [`sweep`] runs a scene over a grid of key values (`wrinkle sweep`, and the Python
//!   package's Dask sweeps).

pub mod analytic;
pub mod bench;
pub mod buckle_outputs;
pub mod cli;
pub mod closed_form;
pub mod commands;
pub mod compare;
pub mod error;
pub mod input;
pub mod interrupt;
pub mod line;
pub mod memory;
pub mod output;
pub mod physics;
pub mod region_measures;
pub mod results;
pub mod run;
pub mod run_figures;
pub mod run_outputs;
pub mod scene;
pub mod setup;
pub mod study;
pub mod sweep;
pub mod threshold;

pub use error::{EXIT_INTERRUPTED, Error};
pub use scene::Scene;
