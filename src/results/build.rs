//! [`RunSummary::new`]: the run's result decided from its context and trace — how it ended
//! (the exit code), what the user must be told, the closed form beside the path — before any
//! file is written.

use super::summary::{
    AnmStepRecord, DetectedBifurcation, FINAL_FIELDS_FILE, FINAL_SURFACE_FILE, LossOfEllipticity,
    Memory, PathCounts, RunSummary, Timings, VtuFile, fields_file_at,
};
use super::{RunContext, RunOutcome, Trace};
use crate::output::{Severity, Warning};
use crate::scene::Imperfection;
use crate::threshold::{ThresholdSummary, load_unit};
use wrinkle_runtime::solve::anm::AnmStep;

impl RunSummary {
    /// The result of a run from what it knows (`context`) and what its path recorded (`trace`).
    pub fn new(context: &RunContext, trace: &Trace) -> RunSummary {
        let scene = context.scene;
        let stats = &trace.result.statistics;
        let critical = context.threshold.critical_load();
        let threshold = ThresholdSummary::new(scene, context.threshold);
        let closed_form_amplitudes = closed_form_amplitudes(context, trace, &threshold);
        RunSummary {
            model: context.spec.name,
            method: scene.solver.method.as_str(),
            dofs: context.dofs,
            wavenumber: context.threshold.wavenumber,
            wavelength: context.threshold.wavelength,
            load_kind: scene.load.kind.as_str(),
            load_unit: load_unit(scene),
            linear_buckling_load: critical,
            closed_form_critical_load: threshold.closed_form.closed_form_critical_load,
            threshold,
            detected_bifurcation: trace.result.bifurcation.map(|(load, step)| {
                DetectedBifurcation {
                    load,
                    step,
                    relative_difference_to_linear_buckling: (load - critical) / critical,
                }
            }),
            loss_of_ellipticity: trace.loss_of_ellipticity.as_ref().map(|(load, report)| {
                LossOfEllipticity {
                    load: *load,
                    location: report.location,
                    direction_rad: report.direction,
                    field: report.field,
                    margin: report.worst_margin,
                    area_fraction: report.violated_fraction,
                }
            }),
            imperfection_amplitude: context.imperfection,
            imperfection_shape: context.imperfection_shape.as_str(),
            stop: if trace.interrupted {
                "interrupted by the user (Ctrl-C)".to_string()
            } else {
                trace.result.stop.describe()
            },
            outcome: outcome(context, trace),
            steps: stats.steps,
            statistics: PathCounts {
                factorizations: stats.factorizations,
                prediction_factorizations: stats.prediction_factorizations,
                tangent_assemblies: stats.tangent_assemblies,
                residual_assemblies: stats.residual_assemblies,
                series_assemblies: stats.series_assemblies,
                corrections: stats.corrections,
                rejected_steps: stats.rejected_steps,
            },
            timings: timings(context, trace),
            memory: Memory {
                peak_resident_bytes: context.peak_memory,
                taylor_tape_bytes: stats.tape_bytes,
                factor_nonzeros: stats.factor_nonzeros,
            },
            solver_warnings: trace.result.warnings.clone(),
            anm_steps: trace.anm_steps.iter().map(anm_step_record).collect(),
            vtu: vtu_files(context, trace),
            unreached_vtu_loads: trace.unreached_vtu_loads.clone(),
            path: trace.points.clone(),
            scene: scene.echo_json(),
            notices: notices(context, trace),
            closed_form_amplitudes,
        }
    }
}

/// Exit status of the run (see [`RunOutcome`]): a solver failure, an interruption, a perfect
/// bifurcation passed without wrinkling, the target not reached, a validity check the scene
/// does not accept, or reached.
fn outcome(context: &RunContext, trace: &Trace) -> RunOutcome {
    let stop = &trace.result.stop;
    if stop.is_failure() {
        return RunOutcome::Failed(stop.describe());
    }
    if trace.interrupted {
        let at = trace.points.last().map_or_else(
            || "before the first point".to_string(),
            |p| {
                format!(
                    "at λ = {} (max |w|/h = {:.4})",
                    context.load_quantity().format_value(p.lambda),
                    p.max_amplitude_over_h
                )
            },
        );
        return RunOutcome::Interrupted(format!(
            "stopped by the user (Ctrl-C) {at} after {} points; every completed point is in path.csv",
            trace.points.len()
        ));
    }
    if let Some(load) = trace.passed_perfect_bifurcation {
        let loads = context.load_quantity();
        return RunOutcome::Incomplete(format!(
            "no imperfection (solver.perturbation = 0): past λ_c = {} the path stays flat on the unstable fundamental branch (max |w| = 0 at λ = {}); set solver.perturbation (e.g. 1e-4) to wrinkle, or solver.max_load to follow that branch",
            loads.format_value(context.threshold.critical_load()),
            loads.format_value(load)
        ));
    }
    let target = context.scene.solver.max_amplitude_over_thickness;
    let reached = trace
        .points
        .last()
        .is_some_and(|p| p.max_amplitude_over_h >= target);
    if !reached {
        let wrinkled = trace.result.bifurcation.is_some()
            || trace
                .points
                .last()
                .is_some_and(|p| p.lambda > context.threshold.critical_load());
        let why = if wrinkled {
            stop.describe()
        } else {
            format!(
                "{} before the path left the fundamental branch",
                stop.describe()
            )
        };
        return RunOutcome::Incomplete(format!(
            "{why}: the amplitude target max |w|/h = {target} was not reached"
        ));
    }
    match context.threshold.validity_failure(&context.scene.validity) {
        Some(reason) => RunOutcome::Invalid(reason),
        None => RunOutcome::Reached,
    }
}

/// Where the time went.
fn timings(context: &RunContext, trace: &Trace) -> Timings {
    let stats = &trace.result.statistics;
    Timings {
        threshold: context.threshold.seconds,
        assembly: stats.assembly_seconds,
        factorization: stats.factorization_seconds,
        series: stats.series_seconds,
        series_solves: stats.series_solve_seconds,
        bifurcation_prediction: stats.bifurcation_seconds,
        residual_checks: stats.residual_seconds,
        ellipticity: trace.ellipticity_seconds,
        recording: trace.recording_seconds,
        path: stats.total_seconds,
        total: context.seconds,
    }
}

fn anm_step_record(step: &AnmStep) -> AnmStepRecord {
    AnmStepRecord {
        step: step.step,
        load_start: step.load_range.0,
        load_end: step.load_range.1,
        step_length: step.step_length,
        series_step_length: step.series_step_length,
        pade_step_length: step.pade_step_length,
        mapped_step_length: step.mapped_step_length,
        singularity_behind: step.singularity_behind,
        end_residual: step.end_residual,
        correction_iterations: step.correction_iterations,
        crossings_redone: step.crossings_redone,
        geometric_radius: step.geometric_radius,
        predicted_bifurcation: step.predicted_bifurcation,
        negative_pivots: step.negative_pivots,
        completed: step.completed,
        mode_parameter: step.mode_parameter,
    }
}

/// The VTU files the scene asks for, each with its load: the fields at the last point and at
/// every requested load reached (`output.vtu`), the sampled surface (`output.surface`).
fn vtu_files(context: &RunContext, trace: &Trace) -> Vec<VtuFile> {
    let output = &context.scene.output;
    let file = |load: f64, name: String| VtuFile { load, file: name };
    let mut files = Vec::new();
    if output.vtu {
        files.push(file(trace.last.load, FINAL_FIELDS_FILE.into()));
        files.extend(
            trace
                .requested
                .iter()
                .map(|s| file(s.load, fields_file_at(s.load, &output.vtu_loads))),
        );
    }
    if output.surface {
        files.push(file(trace.last.load, FINAL_SURFACE_FILE.into()));
    }
    files
}

/// Samples of the one-mode closed form over the path's load range.
const CLOSED_FORM_SAMPLES: usize = 200;

/// The physical closed-form amplitude $`2a/h`$ (eq. 62) against $`\lambda/\lambda_c`$ from 1 to
/// the path's last load (at least 1.001), where the closed form applies to the scene and
/// describes the model: an envelope whose gradient is stiff (one that selects its own
/// wavelength, or a complex envelope, which reduces to it without phase) — not a plate, whose
/// wrinkles are fields of the mesh, nor a pure membrane.
fn closed_form_amplitudes(
    context: &RunContext,
    trace: &Trace,
    threshold: &ThresholdSummary,
) -> Option<Vec<(f64, f64)>> {
    threshold.closed_form.closed_form_critical_load?;
    use wrinkle_runtime::wavelength::{CarriedBecause, WavelengthSelection};
    if !matches!(
        context.spec.wavelength_selection(),
        WavelengthSelection::OwnMinimum | WavelengthSelection::Carried(CarriedBecause::Phase)
    ) {
        return None;
    }
    let scene = context.scene;
    let critical = context.threshold.critical_load();
    let rectangle = scene.clamped_rectangle();
    let nu = scene.material.poisson_ratio;
    let last = trace.points.last().map_or(critical, |p| p.lambda);
    let top = (last / critical).max(1.001);
    let samples = CLOSED_FORM_SAMPLES as f64;
    let curve = (0..=CLOSED_FORM_SAMPLES)
        .map(|k| {
            let ratio = 1.0 + (top - 1.0) * k as f64 / samples;
            let a =
                crate::closed_form::amplitude_from_load_ratio(rectangle.aspect_ratio(), nu, ratio);
            (ratio, 2.0 * a)
        })
        .collect();
    Some(curve)
}

/// What a researcher must see besides the numbers: validity checks (accepted ones as notes),
/// loss of ellipticity, an unstable branch, the threshold's notes, requested loads not reached,
/// the solver's warnings.
fn notices(context: &RunContext, trace: &Trace) -> Vec<Warning> {
    let mut warnings: Vec<Warning> = context
        .threshold
        .warnings
        .iter()
        .map(|w| {
            if context.scene.validity.accepts(w.check) {
                Warning::new(
                    Severity::Note,
                    w.check,
                    format!("{} (accepted by `validity.accept`)", w.message),
                )
            } else {
                Warning::new(Severity::Warning, w.check, w.message.clone())
            }
        })
        .collect();
    if let Some((load, report)) = &trace.loss_of_ellipticity {
        warnings.push(Warning::new(
            Severity::Warning,
            "loss of ellipticity",
            format!(
                "from λ = {} on {} % of the area (worst at ({:.4}, {:.4}) mm, field `{}`): beyond it the model's solutions depend on the mesh there",
                context.load_quantity().format_value(*load),
                crate::output::quantity::format_significant(100.0 * report.violated_fraction, 2),
                report.location[0],
                report.location[1],
                report.field
            ),
        ));
    }
    if let Some(step) = trace
        .anm_steps
        .iter()
        .find(|s| s.negative_pivots.is_some_and(|n| n > 0))
    {
        warnings.push(Warning::new(
            Severity::Warning,
            "unstable branch",
            format!(
                "the tangent had {} negative eigenvalue(s) at the start of step {} (λ = {}): the path is on an unstable equilibrium branch — {}",
                step.negative_pivots.unwrap_or(0),
                step.step,
                context.load_quantity().format_value(step.load_range.0),
                if context.scene.solver.perturbation == 0.0 {
                    "without an imperfection (solver.perturbation = 0) it stays on the fundamental branch past the bifurcation"
                } else {
                    "past a secondary bifurcation, or a step jumped over one (a tighter solver.series_tolerance tells which)"
                }
            ),
        ));
    }
    for note in &context.threshold.notes {
        warnings.push(Warning::new(Severity::Note, "threshold", note.clone()));
    }
    warnings.extend(imperfection_note(context));
    warnings.extend(unreached_vtu_loads_notes(context, trace));
    for warning in &trace.result.warnings {
        warnings.push(Warning::new(Severity::Warning, "solver", warning.clone()));
    }
    warnings
}

/// A note when the imperfection's shape is not the one `solver.imperfection` asked for (a
/// uniform imperfection needs an envelope model's wavenumber).
fn imperfection_note(context: &RunContext) -> Option<Warning> {
    let asked = context.scene.solver.imperfection;
    let used = context.imperfection_shape;
    if asked == Imperfection::Auto || asked == used {
        return None;
    }
    Some(Warning::new(
        Severity::Note,
        "solver.imperfection",
        format!(
            "\"{}\" was asked, but `{}` has no wavenumber to shape a uniform load on its envelope: the \"{}\" imperfection was used (imperfection_shape in summary.json)",
            asked.as_str(),
            context.spec.name,
            used.as_str()
        ),
    ))
}

/// Notes for the `output.vtu_loads` without a file: below the path's first load, or beyond
/// where it ended.
fn unreached_vtu_loads_notes(context: &RunContext, trace: &Trace) -> Vec<Warning> {
    let load = context.load_quantity();
    let start = trace.points.first().map(|p| p.lambda);
    let (below, beyond): (Vec<f64>, Vec<f64>) = trace
        .unreached_vtu_loads
        .iter()
        .partition(|&&l| start.is_some_and(|start| l < start));
    let listed = |loads: &[f64]| -> String {
        let texts: Vec<String> = loads.iter().map(|&l| load.format_value(l)).collect();
        texts.join(", ")
    };
    let pronoun = |loads: &[f64]| if loads.len() == 1 { "it" } else { "them" };
    let mut notes = Vec::new();
    if let (false, Some(start)) = (below.is_empty(), start) {
        notes.push(Warning::new(
            Severity::Note,
            "output.vtu_loads",
            format!(
                "λ = {} lies below the path's first load λ = {}: no fields_load_*.vtu written for {}",
                listed(&below),
                load.format_value(start),
                pronoun(&below)
            ),
        ));
    }
    if !beyond.is_empty() {
        let end = trace.points.last().map_or_else(String::new, |p| {
            format!(" at λ = {}", load.format_value(p.lambda))
        });
        notes.push(Warning::new(
            Severity::Note,
            "output.vtu_loads",
            format!(
                "λ = {} not reached (the path ended{end}): no fields_load_*.vtu written for {}",
                listed(&beyond),
                pronoun(&beyond)
            ),
        ));
    }
    notes
}
