//! `wrinkle compare` on a line scene: every line model (the registry's models whose roles fit
//! a line, [`super::LineLayout::from_spec`], written by hand) — or the ones named — on the same
//! beam; the first is the reference. It runs to `solver.max_amplitude_over_h` (or
//! `solver.max_load`) and sets the load $`\lambda^*`$ of its last point; every other model runs
//! to $`\lambda^*`$. The overlay `compare_profiles.png` draws the resolved deflection $`w/h`$
//! with the envelopes' $`\pm2|v_1|/h`$ at that load (not their reconstructed $`w`$, which over a
//! hundred waves would hide the resolved one); `compare.csv`/`compare.json` list each
//! model's dofs, threshold, last load and amplitudes, steps and time.

use super::outputs::{envelope_lines, profile_lines};
use super::path::{LineRun, follow_line};
use super::threshold::set_up_line;
use crate::error::{Error, io_error};
use crate::output::{ProfilePlot, Quantity, plot_profiles, write_atomically, write_json};
use crate::scene::Scene;
use std::path::Path;
use std::time::Instant;
use wrinkle_models::ModelVisitor;
use wrinkle_runtime::EnergyModel;

/// One model of a line comparison.
#[derive(Clone, Debug, serde::Serialize)]
pub struct LineComparisonRow {
    /// The run (threshold, path, last profile).
    pub run: LineRun,
    /// Seconds of the whole model (threshold and path).
    pub seconds: f64,
}

/// A line comparison.
#[derive(Clone, Debug, serde::Serialize)]
pub struct LineComparison {
    /// The common load $`\lambda^*`$: the reference model's last.
    pub load: f64,
    /// One row per model, the reference first.
    pub rows: Vec<LineComparisonRow>,
}

/// The default models of a line comparison: the hand-written models whose roles fit a line.
pub fn line_models() -> Vec<String> {
    wrinkle_models::catalogue()
        .into_iter()
        .filter(|spec| super::LineLayout::from_spec(spec).is_ok() && spec.derivation.is_none())
        .map(|spec| spec.name.to_string())
        .collect()
}

fn run_model(scene: &Scene, name: &str) -> Result<LineComparisonRow, Error> {
    struct Run<'a>(&'a Scene);
    impl ModelVisitor for Run<'_> {
        type Output = Result<LineRun, Error>;
        fn visit<M: EnergyModel>(self, model: M) -> Self::Output {
            follow_line(self.0, set_up_line(self.0, model)?, None)
        }
    }
    let mut scene = scene.clone();
    scene.model.name = name.to_string();
    let started = Instant::now();
    let run = wrinkle_models::with_model(name, Run(&scene))
        .unwrap_or_else(|| Err(crate::setup::unknown_model(&scene)))?;
    Ok(LineComparisonRow {
        run,
        seconds: started.elapsed().as_secs_f64(),
    })
}

/// Runs the comparison (module documentation) and writes its files into `directory`.
pub fn compare_line(
    scene: &Scene,
    models: &[String],
    directory: &Path,
) -> Result<LineComparison, Error> {
    let models = if models.is_empty() {
        line_models()
    } else {
        models.to_vec()
    };
    let Some((reference, others)) = models.split_first() else {
        return Err(Error::Usage("no model to compare".into()));
    };
    let first = run_model(scene, reference)?;
    let load = first.run.points.last().map_or(0.0, |p| p.lambda);
    let mut at_load = scene.clone();
    at_load.solver.max_load = load;
    at_load.solver.max_amplitude_over_thickness = 100.0;
    let mut rows = vec![first];
    for name in others {
        rows.push(run_model(&at_load, name)?);
    }
    let comparison = LineComparison { load, rows };
    write_comparison(directory, &comparison).map_err(io_error(directory))?;
    Ok(comparison)
}

fn write_comparison(directory: &Path, comparison: &LineComparison) -> std::io::Result<()> {
    std::fs::create_dir_all(directory)?;
    write_json(&directory.join("compare.json"), comparison)?;
    write_atomically(&directory.join("compare.csv"), |out| {
        writeln!(
            out,
            "model,element,free_dofs,critical_load,last_load,centre_amplitude_over_h,max_amplitude_over_h,steps,factorizations,seconds"
        )?;
        for row in &comparison.rows {
            let (run, last) = (&row.run, row.run.points.last());
            writeln!(
                out,
                "{},{},{},{},{},{},{},{},{},{:.3}",
                run.threshold.model,
                run.threshold.element,
                run.threshold.free_dofs,
                run.threshold.critical_load,
                last.map_or(f64::NAN, |p| p.lambda),
                last.map_or(f64::NAN, |p| p.centre_amplitude_over_h),
                last.map_or(f64::NAN, |p| p.max_amplitude_over_h),
                run.steps,
                run.factorizations,
                row.seconds
            )?;
        }
        Ok(())
    })?;
    let profiles = comparison
        .rows
        .iter()
        .flat_map(|row| {
            let last = row.run.points.last().map_or(0.0, |p| p.lambda);
            let label = format!("{} (λ = {last:.5})", row.run.threshold.model);
            let envelopes = envelope_lines(&label, &row.run.profile);
            if envelopes.is_empty() {
                profile_lines(&label, &row.run.profile)
            } else {
                envelopes
            }
        })
        .collect();
    let plot = ProfilePlot {
        abscissa: Quantity::coordinate("X"),
        ordinate: Quantity::deflection_over_thickness(),
        location: format!(
            "along the beam at λ = {:.6} (the reference's last load)",
            comparison.load
        ),
        profiles,
    };
    let title = "line models: resolved deflection and envelopes ±2|v₁|";
    plot_profiles(&directory.join("compare_profiles"), title, &plot)?;
    Ok(())
}

/// The table `wrinkle compare` prints for a line scene.
pub fn line_comparison_text(comparison: &LineComparison) -> String {
    let mut text = format!(
        "{:<24} {:>9} {:>10} {:>14} {:>12} {:>10} {:>10} {:>8}\n",
        "model", "element", "free dofs", "λ_c", "last λ", "centre a/h", "max a/h", "seconds"
    );
    for row in &comparison.rows {
        let (run, last) = (&row.run, row.run.points.last());
        text.push_str(&format!(
            "{:<24} {:>9} {:>10} {:>14.8} {:>12.6} {:>10.4} {:>10.4} {:>8.2}\n",
            run.threshold.model,
            run.threshold.element,
            run.threshold.free_dofs,
            run.threshold.critical_load,
            last.map_or(f64::NAN, |p| p.lambda),
            last.map_or(f64::NAN, |p| p.centre_amplitude_over_h),
            last.map_or(f64::NAN, |p| p.max_amplitude_over_h),
            row.seconds
        ));
    }
    text
}
