//! The HTML report of a run (`report.html`): one self-contained page — the summary table, the
//! warnings, the plots (PNG embedded as `data:` URIs), the scene and the list of files — with no
//! network access, no external style sheet or script, readable on screen and on paper.
//!
//! The same summary rows print as a plain-text table for the terminal
//! ([`SummaryTable::to_text`]).

use super::files::write_atomically;
use super::quantity::{Quantity, format_significant};
use std::io;
use std::path::{Path, PathBuf};

/// One line of the summary table: a label, its value with the unit, and a note shown beside it
/// (e.g. the closed form beside the computed critical load).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct SummaryRow {
    /// What the row is, e.g. `"critical load λ_c"`.
    pub label: String,
    /// The value with its unit, e.g. `"0.089521 N/mm"`.
    pub value: String,
    /// Context, e.g. `"closed form (42): 0.089521 N/mm, difference +0.0001 %"`; may be empty.
    pub note: String,
}

impl SummaryRow {
    /// A row from its three texts.
    pub fn new(
        label: impl Into<String>,
        value: impl Into<String>,
        note: impl Into<String>,
    ) -> Self {
        SummaryRow {
            label: label.into(),
            value: value.into(),
            note: note.into(),
        }
    }
}

/// The summary table of a run: the numbers a researcher looks for first, already computed by
/// the run (the result's [`crate::results::RunSummary`]), as the report and the terminal show
/// them.
#[derive(Clone, Debug, PartialEq)]
pub struct SummaryTable {
    /// Model name, e.g. `"reference-envelope"`.
    pub model: String,
    /// Solver, e.g. `"ANM"` or `"Riks"`.
    pub method: String,
    /// Number of free unknowns.
    pub dofs: usize,
    /// Wavenumber $`Q`$ (1/mm) of envelope models; `None` for a full plate.
    pub wavenumber: Option<f64>,
    /// Wavelength (mm): $`2\pi/Q`$ of an envelope model, read from the buckling mode for a
    /// plate (shown without a wavenumber then).
    pub wavelength: Option<f64>,
    /// The load $`\lambda`$ (labels and unit of every load below).
    pub load: Quantity,
    /// Critical load $`\lambda_c`$ of linear buckling.
    pub critical_load: Option<f64>,
    /// Closed-form critical load, when one applies; shown beside $`\lambda_c`$.
    pub closed_form_critical_load: Option<f64>,
    /// Equation the closed form comes from, e.g. `"eq. (42)"`.
    pub closed_form_source: String,
    /// Load at the last point of the path.
    pub final_load: Option<f64>,
    /// Largest physical amplitude over the thickness at the last point.
    pub final_amplitude_over_h: Option<f64>,
    /// The amplitude asked for (the target of the path), if any.
    pub target_amplitude_over_h: Option<f64>,
    /// Thickness $`h`$ (mm), to give the amplitude in mm too.
    pub thickness: Option<f64>,
    /// Solver steps.
    pub steps: usize,
    /// Matrix factorisations.
    pub factorizations: usize,
    /// Wall-clock time of the whole run (s).
    pub seconds: f64,
    /// Peak resident memory of the run (bytes), where the platform reports it.
    pub peak_memory_bytes: Option<u64>,
    /// Why the path stopped, in words.
    pub stop: String,
    /// Whether the run reached what was asked (the page shows a green or a red banner).
    pub reached_target: bool,
}

impl SummaryTable {
    /// The summary as table rows, in the order of the report.
    pub fn rows(&self) -> Vec<SummaryRow> {
        let mut rows = vec![
            SummaryRow::new("model", &self.model, format!("solver: {}", self.method)),
            SummaryRow::new("unknowns", group_thousands(self.dofs), ""),
        ];
        rows.extend(self.wavenumber_rows());
        rows.extend(self.critical_load_row());
        rows.extend(self.final_rows());
        rows.push(SummaryRow::new(
            "cost",
            format!(
                "{} steps, {} factorisations",
                self.steps, self.factorizations
            ),
            format!("{} s", format_significant(self.seconds, 3)),
        ));
        if let Some(bytes) = self.peak_memory_bytes {
            rows.push(SummaryRow::new(
                "peak memory",
                format!("{} MB", format_significant(bytes as f64 / 1e6, 3)),
                "resident, during the run",
            ));
        }
        rows.push(SummaryRow::new(
            "stop",
            &self.stop,
            if self.reached_target {
                "reached what was asked"
            } else {
                "did not reach what was asked"
            },
        ));
        rows
    }

    /// $`Q`$ and $`2\pi/Q`$ of an envelope model; a plate's wavelength read from its mode.
    fn wavenumber_rows(&self) -> Vec<SummaryRow> {
        let Some(q) = self.wavenumber.filter(|q| q.is_finite() && *q > 0.0) else {
            return self
                .wavelength
                .filter(|l| l.is_finite() && *l > 0.0)
                .map(|wavelength| {
                    SummaryRow::new(
                        "wavelength",
                        format!("{} mm", format_significant(wavelength, 4)),
                        "read from the buckling mode",
                    )
                })
                .into_iter()
                .collect();
        };
        vec![
            SummaryRow::new(
                "wavenumber Q",
                format!("{} /mm", format_significant(q, 5)),
                "",
            ),
            SummaryRow::new(
                "wavelength 2π/Q",
                format!("{} mm", format_significant(std::f64::consts::TAU / q, 4)),
                "",
            ),
        ]
    }

    /// $`\lambda_c`$ with the closed form beside it.
    fn critical_load_row(&self) -> Option<SummaryRow> {
        let critical = self.critical_load?;
        let note = match self.closed_form_critical_load {
            Some(closed) => format!(
                "closed form{}: {} (difference {} %)",
                if self.closed_form_source.is_empty() {
                    String::new()
                } else {
                    format!(" {}", self.closed_form_source)
                },
                self.load.format_value(closed),
                signed(format_significant(100.0 * (critical - closed) / closed, 2))
            ),
            None => "no closed form for this case".to_string(),
        };
        Some(SummaryRow::new(
            "critical load λ_c",
            self.load.format_value(critical),
            note,
        ))
    }

    /// The final load (with $`\lambda/\lambda_c`$) and amplitude (in mm, with the target).
    fn final_rows(&self) -> Vec<SummaryRow> {
        let mut rows = Vec::new();
        if let Some(load) = self.final_load {
            let note = self
                .critical_load
                .filter(|c| *c != 0.0)
                .map(|c| format!("λ / λ_c = {}", format_significant(load / c, 4)))
                .unwrap_or_default();
            rows.push(SummaryRow::new(
                format!("final load {}", self.load.short_name()),
                self.load.format_value(load),
                note,
            ));
        }
        if let Some(amplitude) = self.final_amplitude_over_h {
            let mut notes = Vec::new();
            if let Some(h) = self.thickness {
                notes.push(format!(
                    "max |w| = {} mm",
                    format_significant(amplitude * h, 4)
                ));
            }
            if let Some(target) = self.target_amplitude_over_h {
                notes.push(format!("target {}", format_significant(target, 3)));
            }
            rows.push(SummaryRow::new(
                "final physical amplitude max |w| / h",
                format_significant(amplitude, 4),
                notes.join("; "),
            ));
        }
        rows
    }

    /// The rows as an aligned plain-text table (three columns), for the terminal.
    pub fn to_text(&self) -> String {
        format_rows(&self.rows())
    }
}

/// `+` before a number that has no sign.
fn signed(number: String) -> String {
    if number.starts_with('-') {
        number
    } else {
        format!("+{number}")
    }
}

/// Values longer than this (a stop reason, a long warning) are not padded to and do not widen
/// the value column: one long reason would otherwise push every note of the table far right.
const ALIGNED_VALUE_WIDTH: usize = 48;

/// Rows as an aligned plain-text table: label, value, note. The notes are aligned after the
/// values of up to 48 characters (`ALIGNED_VALUE_WIDTH`); a longer value is followed by its note
/// directly.
pub fn format_rows(rows: &[SummaryRow]) -> String {
    let width = |text: &str| text.chars().count();
    let label_width = rows.iter().map(|r| width(&r.label)).max().unwrap_or(0);
    let value_width = rows
        .iter()
        .map(|r| width(&r.value))
        .filter(|&w| w <= ALIGNED_VALUE_WIDTH)
        .max()
        .unwrap_or(0);
    let mut text = String::new();
    for row in rows {
        let line = format!(
            "{:label_width$}  {:value_width$}  {}",
            row.label, row.value, row.note
        );
        text.push_str(line.trim_end());
        text.push('\n');
    }
    text
}

/// How serious a [`Warning`] is; serialised as its [`Severity::label`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Severity {
    /// Worth knowing (e.g. a fixed wavenumber near the edge of the valid range).
    Note,
    /// The results need care (e.g. loss of ellipticity, a mode not resolved by the mesh).
    Warning,
    /// The run failed or stopped early.
    Failure,
}

impl Severity {
    /// `note`, `warning` or `failure`: the terminal line's prefix and the report's CSS class.
    pub fn label(self) -> &'static str {
        match self {
            Severity::Note => "note",
            Severity::Warning => "warning",
            Severity::Failure => "failure",
        }
    }
}

/// A warning shown prominently near the top of the report (serialised as
/// `{severity, title, detail}` in `summary.json`'s `notes`).
#[derive(Clone, Debug, PartialEq, Eq, serde::Serialize)]
pub struct Warning {
    /// How serious.
    pub severity: Severity,
    /// One line, e.g. `"loss of ellipticity at λ = 0.1032 N/mm"`.
    pub title: String,
    /// Details: where, how much, what it means; may be empty.
    pub detail: String,
}

impl Warning {
    /// A warning of the given severity.
    pub fn new(severity: Severity, title: impl Into<String>, detail: impl Into<String>) -> Self {
        Warning {
            severity,
            title: title.into(),
            detail: detail.into(),
        }
    }
}

/// A PNG shown in the report with its caption.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ReportFigure {
    /// The PNG file (read and embedded when the report is written).
    pub png: PathBuf,
    /// Caption under the picture.
    pub caption: String,
}

impl ReportFigure {
    /// A figure from a PNG file and a caption.
    pub fn png(png: impl Into<PathBuf>, caption: impl Into<String>) -> Self {
        ReportFigure {
            png: png.into(),
            caption: caption.into(),
        }
    }
}

/// Everything the report shows.
#[derive(Clone, Debug, PartialEq)]
pub struct Report {
    /// Page title, e.g. `"reference-envelope on clamped_biaxial.toml"`.
    pub title: String,
    /// Line under the title (scene source, date, …); may be empty.
    pub subtitle: String,
    /// Whether the run reached what was asked (green or red status line).
    pub reached_target: bool,
    /// Status line, e.g. the stop criterion.
    pub status: String,
    /// The summary table.
    pub rows: Vec<SummaryRow>,
    /// Warnings, shown above the table.
    pub warnings: Vec<Warning>,
    /// Plots, in order.
    pub figures: Vec<ReportFigure>,
    /// The effective scene as TOML.
    pub scene_toml: String,
    /// The files of the run directory (names relative to it).
    pub files: Vec<String>,
}

impl Report {
    /// A report with the summary's rows, status and title `"MODEL"`, and nothing else.
    pub fn from_summary(summary: &SummaryTable) -> Self {
        Report {
            title: summary.model.clone(),
            subtitle: String::new(),
            reached_target: summary.reached_target,
            status: summary.stop.clone(),
            rows: summary.rows(),
            warnings: Vec::new(),
            figures: Vec::new(),
            scene_toml: String::new(),
            files: Vec::new(),
        }
    }
}

/// `"YYYY-MM-DD HH:MM UTC"` of `time` (the report's date; no time-zone database needed).
pub fn utc_timestamp(time: std::time::SystemTime) -> String {
    let seconds = time
        .duration_since(std::time::UNIX_EPOCH)
        .map_or(0, |d| d.as_secs()) as i64;
    let (days, rest) = (seconds.div_euclid(86_400), seconds.rem_euclid(86_400));
    // Civil date of a day count since 1970-01-01 (H. Hinnant's `civil_from_days`).
    let z = days + 719_468;
    let era = z.div_euclid(146_097);
    let day_of_era = z - era * 146_097;
    let year_of_era =
        (day_of_era - day_of_era / 1460 + day_of_era / 36_524 - day_of_era / 146_096) / 365;
    let day_of_year = day_of_era - (365 * year_of_era + year_of_era / 4 - year_of_era / 100);
    let month_index = (5 * day_of_year + 2) / 153;
    let day = day_of_year - (153 * month_index + 2) / 5 + 1;
    let month = if month_index < 10 {
        month_index + 3
    } else {
        month_index - 9
    };
    let year = year_of_era + era * 400 + i64::from(month <= 2);
    format!(
        "{year:04}-{month:02}-{day:02} {:02}:{:02} UTC",
        rest / 3600,
        rest % 3600 / 60
    )
}

/// Writes `report` as one self-contained HTML page to `path` (atomically): every picture is read
/// and embedded as a `data:image/png;base64,…` URI; the style sheet is inline; nothing refers to
/// the network.
///
/// Errors: a figure that cannot be read, a failure writing the file.
pub fn write_report(path: &Path, report: &Report) -> io::Result<()> {
    let html = render_html(report)?;
    write_atomically(path, |writer| writer.write_all(html.as_bytes()))
}

/// The page as a string (see [`write_report`]).
pub fn render_html(report: &Report) -> io::Result<String> {
    let mut html = String::with_capacity(1 << 16);
    html.push_str("<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n");
    html.push_str("<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n");
    html.push_str(&format!(
        "<title>{} — wrinkle report</title>\n",
        escape(&report.title)
    ));
    html.push_str("<style>\n");
    html.push_str(STYLE);
    html.push_str("</style>\n</head>\n<body>\n<main>\n<header>\n");
    html.push_str(&format!("<h1>{}</h1>\n", escape(&report.title)));
    if !report.subtitle.is_empty() {
        html.push_str(&format!(
            "<p class=\"subtitle\">{}</p>\n",
            escape(&report.subtitle)
        ));
    }
    let (class, word) = if report.reached_target {
        ("status ok", "Completed")
    } else {
        ("status failed", "Stopped early")
    };
    html.push_str(&format!(
        "<p class=\"{class}\"><strong>{word}:</strong> {}</p>\n</header>\n",
        escape(&report.status)
    ));
    push_warnings(&mut html, &report.warnings);
    push_table(&mut html, &report.rows);
    push_figures(&mut html, &report.figures)?;
    if !report.scene_toml.is_empty() {
        html.push_str("<section>\n<h2>Scene</h2>\n<pre class=\"scene\">");
        html.push_str(&escape(report.scene_toml.trim_end()));
        html.push_str("</pre>\n</section>\n");
    }
    if !report.files.is_empty() {
        html.push_str("<section class=\"files\">\n<h2>Files of this run</h2>\n<ul>\n");
        for name in &report.files {
            // Relative links: the page sits in the run directory beside its files.
            html.push_str(&format!(
                "<li><a href=\"{}\"><code>{}</code></a></li>\n",
                escape(name),
                escape(name)
            ));
        }
        html.push_str("</ul>\n</section>\n");
    }
    html.push_str(&format!(
        "<footer>Written by wrinkle {}.</footer>\n</main>\n</body>\n</html>\n",
        env!("CARGO_PKG_VERSION")
    ));
    Ok(html)
}

fn push_warnings(html: &mut String, warnings: &[Warning]) {
    if warnings.is_empty() {
        html.push_str("<p class=\"no-warnings\">No warnings.</p>\n");
        return;
    }
    html.push_str("<section class=\"warnings\">\n<h2>Warnings</h2>\n");
    for warning in warnings {
        let class = warning.severity.label();
        html.push_str(&format!(
            "<div class=\"{class}\"><strong>{}</strong>",
            escape(&warning.title)
        ));
        if !warning.detail.is_empty() {
            html.push_str(&format!("<p>{}</p>", escape(&warning.detail)));
        }
        html.push_str("</div>\n");
    }
    html.push_str("</section>\n");
}

fn push_table(html: &mut String, rows: &[SummaryRow]) {
    if rows.is_empty() {
        return;
    }
    html.push_str("<section>\n<h2>Summary</h2>\n<table class=\"summary\">\n<tbody>\n");
    for row in rows {
        html.push_str(&format!(
            "<tr><th scope=\"row\">{}</th><td class=\"value\">{}</td><td class=\"note\">{}</td></tr>\n",
            escape(&row.label),
            escape(&row.value),
            escape(&row.note)
        ));
    }
    html.push_str("</tbody>\n</table>\n</section>\n");
}

fn push_figures(html: &mut String, figures: &[ReportFigure]) -> io::Result<()> {
    if figures.is_empty() {
        return Ok(());
    }
    html.push_str("<section>\n<h2>Plots</h2>\n");
    for figure in figures {
        let bytes = crate::input::read_capped(&figure.png, crate::input::MAX_FIGURE_BYTES)
            .map_err(|error| {
                io::Error::new(error.kind(), format!("{}: {error}", figure.png.display()))
            })?;
        html.push_str(&format!(
            "<figure><img alt=\"{}\" src=\"data:image/png;base64,{}\"><figcaption>{}</figcaption></figure>\n",
            escape(&figure.caption),
            base64(&bytes),
            escape(&figure.caption)
        ));
    }
    html.push_str("</section>\n");
    Ok(())
}

/// HTML text and attribute escaping.
pub fn escape(text: &str) -> String {
    let mut escaped = String::with_capacity(text.len());
    for c in text.chars() {
        match c {
            '&' => escaped.push_str("&amp;"),
            '<' => escaped.push_str("&lt;"),
            '>' => escaped.push_str("&gt;"),
            '"' => escaped.push_str("&quot;"),
            '\'' => escaped.push_str("&#39;"),
            _ => escaped.push(c),
        }
    }
    escaped
}

/// Standard base64 with padding (RFC 4648).
fn base64(bytes: &[u8]) -> String {
    const ALPHABET: &[u8; 64] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    let mut text = String::with_capacity(bytes.len().div_ceil(3) * 4);
    for chunk in bytes.chunks(3) {
        let triple = (chunk[0] as u32) << 16
            | (*chunk.get(1).unwrap_or(&0) as u32) << 8
            | *chunk.get(2).unwrap_or(&0) as u32;
        for k in 0..4 {
            if k <= chunk.len() {
                text.push(ALPHABET[(triple >> (18 - 6 * k) & 63) as usize] as char);
            } else {
                text.push('=');
            }
        }
    }
    text
}

/// `4704` → `"4 704"` (thin grouping, as in the paper's tables).
fn group_thousands(value: usize) -> String {
    let digits = value.to_string();
    let mut grouped = String::new();
    for (index, c) in digits.chars().enumerate() {
        if index > 0 && (digits.len() - index).is_multiple_of(3) {
            grouped.push('\u{202f}');
        }
        grouped.push(c);
    }
    grouped
}

const STYLE: &str = r#"
:root { color-scheme: light; }
body { margin: 0; background: #f4f5f7; color: #1d1f23;
  font: 16px/1.5 system-ui, -apple-system, "Segoe UI", Roboto, "DejaVu Sans", sans-serif; }
main { max-width: 1180px; margin: 0 auto; padding: 28px 32px 40px; background: #fff; }
h1 { font-size: 1.7rem; margin: 0 0 4px; }
h2 { font-size: 1.2rem; margin: 32px 0 10px; padding-bottom: 4px; border-bottom: 1px solid #dde0e5; }
.subtitle { margin: 0 0 12px; color: #555b65; }
.status { margin: 12px 0 0; padding: 10px 14px; border-radius: 6px; }
.status.ok { background: #e7f5ea; border-left: 6px solid #2e8b47; }
.status.failed { background: #fdecec; border-left: 6px solid #c0392b; }
.no-warnings { margin: 8px 0 0; color: #2e8b47; }
.warnings div { margin: 8px 0; padding: 10px 14px; border-radius: 6px; }
.warnings div p { margin: 4px 0 0; }
.warnings .warning { background: #fff5dc; border-left: 6px solid #d99a00; }
.warnings .failure { background: #fdecec; border-left: 6px solid #c0392b; }
.warnings .note { background: #eef3fb; border-left: 6px solid #4a78c2; }
table.summary { border-collapse: collapse; width: 100%; }
table.summary th, table.summary td { text-align: left; vertical-align: top; padding: 7px 12px;
  border-bottom: 1px solid #e6e8ec; }
table.summary th { font-weight: 600; white-space: nowrap; width: 1%; }
table.summary td.value { font-variant-numeric: tabular-nums; white-space: nowrap; width: 1%; }
table.summary td.note { color: #555b65; }
figure { margin: 18px 0 28px; }
figure img { display: block; max-width: 100%; height: auto; margin: 0 auto;
  border: 1px solid #e6e8ec; }
figcaption { margin-top: 6px; color: #454b55; font-size: 0.95rem; text-align: center; }
pre.scene { background: #f6f7f9; border: 1px solid #e6e8ec; border-radius: 6px; padding: 12px 14px;
  overflow-x: auto; font-size: 0.9rem; line-height: 1.4; }
.files ul { columns: 3 14em; padding-left: 1.2em; font-size: 0.9rem; }
footer { margin-top: 36px; color: #8a909a; font-size: 0.85rem; }
@media print {
  body { background: #fff; font-size: 11pt; }
  main { max-width: none; padding: 0; }
  figure, table, .warnings div, pre { break-inside: avoid; }
  h2 { break-after: avoid; }
}
"#;

#[cfg(test)]
mod tests {
    use super::*;

    /// The report's date: the epoch, a leap day, the end of a century year.
    #[test]
    fn utc_timestamps_are_civil_dates() {
        use std::time::{Duration, UNIX_EPOCH};
        let at = |seconds: u64| utc_timestamp(UNIX_EPOCH + Duration::from_secs(seconds));
        assert_eq!(at(0), "1970-01-01 00:00 UTC");
        assert_eq!(at(951_782_400 + 3_600 + 120), "2000-02-29 01:02 UTC");
        assert_eq!(at(978_307_199), "2000-12-31 23:59 UTC");
        assert_eq!(at(1_796_083_200), "2026-12-01 00:00 UTC");
    }

    #[test]
    fn base64_matches_rfc_4648_vectors() {
        for (input, expected) in [
            ("", ""),
            ("f", "Zg=="),
            ("fo", "Zm8="),
            ("foo", "Zm9v"),
            ("foob", "Zm9vYg=="),
            ("fooba", "Zm9vYmE="),
            ("foobar", "Zm9vYmFy"),
        ] {
            assert_eq!(base64(input.as_bytes()), expected);
        }
    }

    #[test]
    fn thousands_are_grouped() {
        assert_eq!(group_thousands(4704), "4\u{202f}704");
        assert_eq!(group_thousands(999), "999");
        assert_eq!(group_thousands(1234567), "1\u{202f}234\u{202f}567");
    }
}
