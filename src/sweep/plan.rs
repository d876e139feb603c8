//! What a sweep still has to do ([`SweepPlan`]): each point's scene made and hashed once, the
//! points that share an effective scene run once, the points an earlier sweep finished read
//! back — and the table's rows once the rest has run ([`SweepPlan::rows`]). The local runner
//! ([`super::local`]) and the Python package (Dask) both work from it.

use super::grid::PlannedPoint;
use super::point::{
    POINTS_DIRECTORY, PointResult, SweepCommand, point_directory, point_name, read_done,
};
use super::recipe::{SceneRecipe, content_hash};
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;
use std::path::Path;

/// One run a sweep still has to do: a scene no earlier sweep finished, and the points that
/// share it.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct PendingRun {
    /// The point's name, `COMMAND-HASH` (its directory under `points/`).
    pub name: String,
    /// Its scene.
    pub recipe: SceneRecipe,
    /// Indices of the sweep's points with this scene.
    pub indices: Vec<usize>,
}

/// A sweep's points and what is left to do.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct SweepPlan {
    /// What each point runs.
    pub command: SweepCommand,
    /// The points, in order.
    pub points: Vec<PlannedPoint>,
    /// Each point's name (`COMMAND-HASH`), or its result when its scene cannot be made.
    pub names: Vec<Result<String, Box<PointResult>>>,
    /// Results already there, by name: finished by an earlier sweep into the same directory.
    pub done: BTreeMap<String, PointResult>,
    /// The runs left, one per distinct scene, in the order of their first point.
    pub pending: Vec<PendingRun>,
}

/// One row of a sweep's table: a point's inputs and its result.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct SweepRow {
    /// Index in the sweep, from 0.
    pub index: usize,
    /// `(key, value)` of each grid axis at this point.
    pub inputs: Vec<(String, String)>,
    /// Its result.
    pub result: PointResult,
}

impl SweepPlan {
    /// The plan of `points` run with `command` into the sweep directory `sweep`: every scene
    /// made (an invalid one is its point's result, outcome `error`, exit code 2) and hashed;
    /// final results found under `sweep/points/` reused.
    pub fn new(points: Vec<PlannedPoint>, command: SweepCommand, sweep: &Path) -> Self {
        let mut done = BTreeMap::new();
        let mut pending: Vec<PendingRun> = Vec::new();
        let names = points
            .iter()
            .map(|point| {
                let scene = point
                    .recipe
                    .build()
                    .map_err(|error| Box::new(PointResult::error("", "", &error, 0.0)))?;
                let hash = content_hash(&scene);
                let name = point_name(command, &hash);
                if done.contains_key(&name) {
                    return Ok(name);
                }
                if let Some(run) = pending.iter_mut().find(|run| run.name == name) {
                    run.indices.push(point.index);
                } else if let Some(result) = read_done(&point_directory(sweep, &name), &hash) {
                    done.insert(name.clone(), result);
                } else {
                    pending.push(PendingRun {
                        name: name.clone(),
                        recipe: point.recipe.clone(),
                        indices: vec![point.index],
                    });
                }
                Ok(name)
            })
            .collect();
        SweepPlan {
            command,
            points,
            names,
            done,
            pending,
        }
    }

    /// The table's rows, in point order, from the reused results and `results` of the pending
    /// runs (by name); a pending run without a result is `lost` (its process ended without
    /// one).
    pub fn rows(&self, results: &BTreeMap<String, PointResult>) -> Vec<SweepRow> {
        self.points
            .iter()
            .zip(&self.names)
            .map(|(point, name)| {
                let result = match name {
                    Err(invalid) => (**invalid).clone(),
                    Ok(name) => match results.get(name).or_else(|| self.done.get(name)) {
                        Some(result) => result.clone(),
                        None => PointResult::lost(
                            name.split_once('-').map_or("", |(_, hash)| hash),
                            &format!("{POINTS_DIRECTORY}/{name}"),
                            "no result came back for this point".into(),
                            0.0,
                        ),
                    },
                };
                SweepRow {
                    index: point.index,
                    inputs: point.inputs.clone(),
                    result,
                }
            })
            .collect()
    }
}
