//! Parameter sweeps: one scene over a grid of key values (or a list of scenes), one run per
//! point, each point in its own directory named by the content hash of its effective scene,
//! and a tidy table of the results (`sweep.csv`, columns in `docs/outputs.md`).
//!
//! * [`recipe`]: how a point's scene is made (base TOML and `KEY=VALUE` overrides) and its
//!   content hash;
//! * [`grid`]: the points of a grid (`--grid KEY=a,b,c`) or of a list of scenes;
//! * [`point`]: one point run (`run` or `buckle`) and its result, `point.json` — read back by a
//!   later sweep instead of running the point again;
//! * [`plan`]: what a sweep still has to do, and its rows once done;
//! * [`table`]: the table's columns and cells, `sweep.csv`;
//! * [`local`]: the local runner of `wrinkle sweep` (a child process per point);
//! * [`command`]: `wrinkle sweep` and `wrinkle sweep-point`.
//!
//! The Python package (`python/`, docs/python.md) plans with [`plan::SweepPlan`], runs each
//! pending point with [`point::run_point`] as a Dask task, and writes the same table.

pub mod command;
pub mod grid;
pub mod local;
pub mod plan;
pub mod point;
pub mod recipe;
pub mod table;

pub use command::{SweepArguments, SweepPointArguments};
pub use grid::{Grid, GridAxis, PlannedPoint, listed_points};
pub use plan::{PendingRun, SweepPlan, SweepRow};
pub use point::{PointResult, SweepCommand, run_point};
pub use recipe::{SceneRecipe, content_hash};
pub use table::{TABLE_FILE, table_csv, write_table_csv};
