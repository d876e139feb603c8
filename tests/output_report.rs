//! The HTML report is self-contained (no network reference, images embedded as data URIs, inline
//! style only) and shows the summary with units, the warnings, the plots and the scene.

use std::path::PathBuf;
use wrinkle::output::report::render_html;
use wrinkle::output::{
    Quantity, Report, ReportFigure, Response, ResponsePoint, Severity, SummaryTable, Warning,
    plot_response, write_report,
};

fn scratch_dir(test: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("wrinkle-report-{}-{test}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn default_scene_summary() -> SummaryTable {
    SummaryTable {
        model: "reference-envelope".into(),
        method: "ANM".into(),
        dofs: 4704,
        wavenumber: Some(0.2354347),
        wavelength: Some(std::f64::consts::TAU / 0.2354347),
        load: Quantity::biaxial_load(),
        critical_load: Some(0.0895213338),
        closed_form_critical_load: Some(0.0895212413),
        closed_form_source: "eq. (42)".into(),
        final_load: Some(0.1117055),
        final_amplitude_over_h: Some(4.044087),
        target_amplitude_over_h: Some(4.0),
        thickness: Some(0.05),
        steps: 20,
        factorizations: 21,
        seconds: 31.2,
        peak_memory_bytes: Some(79_126_528),
        stop: "stop criterion reached".into(),
        reached_target: true,
    }
}

#[test]
fn summary_rows_carry_units_and_the_closed_form_beside_the_critical_load() {
    let rows = default_scene_summary().rows();
    let row = |label: &str| {
        rows.iter()
            .find(|r| r.label == label)
            .unwrap_or_else(|| panic!("no row `{label}` in {rows:?}"))
    };
    assert_eq!(row("critical load λ_c").value, "0.089521 N/mm");
    assert!(
        row("critical load λ_c")
            .note
            .starts_with("closed form eq. (42): 0.089521 N/mm (difference +0.00010 %)"),
        "{:?}",
        row("critical load λ_c")
    );
    assert_eq!(row("wavenumber Q").value, "0.23543 /mm");
    assert_eq!(row("wavelength 2π/Q").value, "26.69 mm");
    assert_eq!(row("final load λ = −N_X").value, "0.11171 N/mm");
    assert_eq!(row("final load λ = −N_X").note, "λ / λ_c = 1.248");
    assert_eq!(row("final physical amplitude max |w| / h").value, "4.044");
    assert!(
        row("final physical amplitude max |w| / h")
            .note
            .contains("0.2022 mm")
    );
    assert_eq!(row("cost").value, "20 steps, 21 factorisations");
    assert_eq!(row("peak memory").value, "79.1 MB");
    assert_eq!(row("stop").value, "stop criterion reached");
    let text = default_scene_summary().to_text();
    assert!(text.contains("critical load λ_c"));
    assert_eq!(text.lines().count(), rows.len());
}

/// A long stop reason does not widen the table: the other rows' notes keep the column of the
/// short values, and the long value is followed by its note after two spaces.
/// A plate has no carrier wavenumber; its table still shows the wavelength read from its mode
/// (26.641 mm on example 1), and no `wavenumber Q` row.
#[test]
fn a_plate_table_shows_the_wavelength_of_its_mode() {
    let table = SummaryTable {
        model: "fvk-plate".into(),
        wavenumber: None,
        wavelength: Some(26.641),
        ..default_scene_summary()
    };
    let rows = table.rows();
    assert!(rows.iter().all(|r| r.label != "wavenumber Q"), "{rows:?}");
    let row = rows.iter().find(|r| r.label == "wavelength").unwrap();
    assert_eq!(row.value, "26.64 mm");
    assert_eq!(row.note, "read from the buckling mode");
}

#[test]
fn a_long_stop_reason_keeps_the_table_narrow() {
    let mut summary = default_scene_summary();
    let short = summary.to_text();
    let note_column = |text: &str, label: &str| {
        let line = text.lines().find(|l| l.starts_with(label)).unwrap();
        line.find("λ / λ_c")
            .map(|byte| line[..byte].chars().count())
    };
    summary.stop = "no imperfection (solver.perturbation = 0): past λ_c the path stays flat on the unstable fundamental branch".into();
    summary.reached_target = false;
    let long = summary.to_text();
    assert_eq!(
        note_column(&long, "final load"),
        note_column(&short, "final load")
    );
    assert!(long.contains(&format!("{}  did not reach what was asked", summary.stop)));
}

#[test]
fn report_is_self_contained_with_embedded_images_and_warnings() {
    let dir = scratch_dir("report");
    let points = (0..=50)
        .map(|k| ResponsePoint {
            load: 0.002 * k as f64,
            max_amplitude_over_h: (0.002 * k as f64 - 0.09).max(0.0).sqrt(),
            centre_amplitude_over_h: None,
            step_end: k % 10 == 0,
        })
        .collect();
    let response = Response::new("reference-envelope", Quantity::biaxial_load(), 0.09, points);
    let plot = plot_response(&dir.join("response"), "Response", &response).unwrap();

    let summary = default_scene_summary();
    let mut report = Report::from_summary(&summary);
    report.title = "reference-envelope — <built-in default scene>".into();
    report.warnings = vec![
        Warning::new(
            Severity::Warning,
            "loss of ellipticity at λ = 0.1032 N/mm",
            "on 2.3 % of the area, near (12.5, 100) mm",
        ),
        Warning::new(Severity::Note, "no bifurcation detected on the path", ""),
    ];
    report.figures = vec![ReportFigure::png(&plot.files[0], "Response & zoom")];
    report.scene_toml = "[geometry]\nlx = 400.0  # mm <- length\n".into();
    report.files = vec!["path.csv".into(), "report.html".into()];
    let path = dir.join("report.html");
    write_report(&path, &report).unwrap();
    let html = std::fs::read_to_string(&path).unwrap();

    assert!(html.starts_with("<!DOCTYPE html>"));
    for forbidden in ["http://", "https://", "<link", "<script", "@import", "url("] {
        assert!(
            !html.contains(forbidden),
            "the report contains `{forbidden}`"
        );
    }
    assert_eq!(html.matches("src=\"data:image/png;base64,").count(), 1);
    assert_eq!(html.matches("<img").count(), 1);
    for text in [
        "0.089521 N/mm",
        "closed form eq. (42)",
        "stop criterion reached",
        "loss of ellipticity at λ = 0.1032 N/mm",
        "class=\"warning\"",
        "Response &amp; zoom",
        "&lt;built-in default scene&gt;",
        "lx = 400.0  # mm &lt;- length",
        "<code>path.csv</code>",
    ] {
        assert!(html.contains(text), "report lacks `{text}`");
    }
    // Warnings come before the summary table, which comes before the plots.
    let at = |text: &str| html.find(text).unwrap();
    assert!(at("<h2>Warnings</h2>") < at("<h2>Summary</h2>"));
    assert!(at("<h2>Summary</h2>") < at("<h2>Plots</h2>"));
    assert!(at("<h2>Plots</h2>") < at("<h2>Scene</h2>"));
    let temporary_left = std::fs::read_dir(&dir)
        .unwrap()
        .any(|e| e.unwrap().file_name().to_string_lossy().starts_with('.'));
    assert!(!temporary_left);
}

#[test]
fn a_run_that_stopped_early_says_so_and_a_missing_figure_is_an_error() {
    let mut summary = default_scene_summary();
    summary.reached_target = false;
    summary.stop = "max_steps reached".into();
    let report = Report::from_summary(&summary);
    let html = render_html(&report).unwrap();
    assert!(html.contains("class=\"status failed\""));
    assert!(html.contains("Stopped early"));
    assert!(html.contains("max_steps reached"));
    assert!(html.contains("No warnings."));

    let mut report = report;
    report.figures = vec![ReportFigure::png("/nonexistent/plot.png", "missing")];
    let error = render_html(&report).unwrap_err();
    assert!(
        error.to_string().contains("/nonexistent/plot.png"),
        "{error}"
    );
}
