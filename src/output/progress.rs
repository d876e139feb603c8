//! Progress reporting on standard error.
//!
//! * [`Progress`] follows one quantity toward a target (the amplitude $`\max|w|/h`$ toward the
//!   requested amplitude, or the load toward a maximum load): the bar's position is
//!   $`(v - v_0)/(v_\text{target} - v_0)`$ and the text shows the value and the target with
//!   their unit. With a critical load ([`ProgressTarget::with_critical_load`]) the first half
//!   of the bar follows the load up to $`\lambda_c`$ (where the amplitude barely moves) and
//!   the second half the amplitude, so the bar moves from the first step.
//! * [`SearchProgress`] counts the evaluations of a search whose end is not known in advance
//!   (`wavenumber search: evaluation 7, Q = 0.2354/mm, λ_c = 0.08952 N/mm`).
//!
//! Where the reports go ([`ProgressSink`]): an [`indicatif`] bar or spinner when standard error is
//! a terminal; plain lines when it is not (logs, pipes, CI), at most one every
//! [`DEFAULT_LINE_INTERVAL`] plus one at the start and one at the end; nothing when `quiet`.
//!
//! On a terminal every line fits its width (80 columns when it cannot be read): the bar's text is
//! split into parts — `λ/λ_c = 1.019`, `max |w| / h = 0.2716 of 1.000` on the label's line;
//! `step 7`, `λ = 9.3e-2` after the bar; the search's evaluation on the line below its spinner —
//! and a part that does not fit is left out whole ([`fit_parts`]), never cut in the middle.
//! Write errors (a closed pipe) are ignored: progress never stops a computation.

use super::quantity::{Quantity, format_significant};
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressState, ProgressStyle};
use std::io::{IsTerminal, Write};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

/// Writes `text` and a newline on standard error, ignoring a failed write: what `eprintln!`
/// does, except that a standard error that cannot be written (a full disk, `2> /dev/full`) is
/// not a panic. Every message of the command line outside the progress reports goes through
/// it; the exit code still says how the command ended.
pub fn message_line(text: &str) {
    let mut stderr = std::io::stderr().lock();
    let _ = writeln!(stderr, "{text}");
}

/// Shortest time between two plain progress lines (not counting the start and end lines).
pub const DEFAULT_LINE_INTERVAL: Duration = Duration::from_secs(2);

/// Resolution of the bar (positions per full bar); an implementation detail, never shown.
const BAR_RESOLUTION: u64 = 10_000;

/// Width of a terminal whose width cannot be read.
const DEFAULT_COLUMNS: usize = 80;

/// Columns of the bar's line besides the detail: two spaces, the bar of 36 between brackets,
/// ` 100 % `, the elapsed time between brackets (up to `59m 59s`) and a space.
const BAR_LINE_COLUMNS: usize = 2 + 38 + 7 + 9 + 1;

/// Columns of standard error when it is a terminal ([`DEFAULT_COLUMNS`] when that cannot be
/// read): what indicatif cuts its lines to.
fn terminal_columns() -> usize {
    // SAFETY: TIOCGWINSZ fills the `winsize` passed by pointer and nothing else; on failure
    // (not a terminal) the zeroed value is left and ignored.
    let mut size: libc::winsize = unsafe { std::mem::zeroed() };
    let read = unsafe { libc::ioctl(libc::STDERR_FILENO, libc::TIOCGWINSZ, &mut size) } == 0;
    if read && size.ws_col > 0 {
        size.ws_col as usize
    } else {
        DEFAULT_COLUMNS
    }
}

/// The `parts` that fit in `width` columns (characters), in order, joined by `, `: a part that
/// does not fit is left out whole and the next ones are still tried; when not even the first
/// fits, it is cut with `…`.
pub fn fit_parts(parts: &[String], width: usize) -> String {
    let mut text = String::new();
    let mut used = 0;
    for part in parts.iter().filter(|p| !p.is_empty()) {
        let length = part.chars().count();
        let needed = if text.is_empty() { length } else { length + 2 };
        if used + needed <= width {
            if !text.is_empty() {
                text.push_str(", ");
            }
            text.push_str(part);
            used += needed;
        }
    }
    if text.is_empty()
        && let Some(first) = parts.iter().find(|p| !p.is_empty())
        && width > 0
    {
        text = first.chars().take(width - 1).collect();
        text.push('…');
    }
    text
}

/// The parts of a detail text such as `step 7, λ = 9.3e-2`.
fn detail_parts(detail: &str) -> Vec<String> {
    detail.split(", ").map(str::to_string).collect()
}

/// Where progress reports go.
#[derive(Clone)]
pub enum ProgressSink {
    /// Nowhere.
    Quiet,
    /// An [`indicatif`] bar (or spinner) redrawn in place on standard error.
    Terminal,
    /// Plain lines to a writer, at most one every `interval` besides the start and end lines.
    Lines {
        /// The destination (standard error, or a buffer in tests).
        writer: Arc<Mutex<dyn Write + Send>>,
        /// Shortest time between two periodic lines.
        interval: Duration,
    },
}

impl std::fmt::Debug for ProgressSink {
    fn fmt(&self, formatter: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            ProgressSink::Quiet => formatter.write_str("Quiet"),
            ProgressSink::Terminal => formatter.write_str("Terminal"),
            ProgressSink::Lines { interval, .. } => formatter
                .debug_struct("Lines")
                .field("interval", interval)
                .finish_non_exhaustive(),
        }
    }
}

impl ProgressSink {
    /// The usual choice: nothing when `quiet`, a bar when standard error is a terminal, plain
    /// lines on standard error every [`DEFAULT_LINE_INTERVAL`] otherwise.
    pub fn standard_error(quiet: bool) -> Self {
        if quiet {
            ProgressSink::Quiet
        } else if std::io::stderr().is_terminal() {
            ProgressSink::Terminal
        } else {
            ProgressSink::Lines {
                writer: Arc::new(Mutex::new(std::io::stderr())),
                interval: DEFAULT_LINE_INTERVAL,
            }
        }
    }

    /// Plain lines into `writer`, at most one every `interval` (start and end lines always).
    pub fn lines(writer: Arc<Mutex<dyn Write + Send>>, interval: Duration) -> Self {
        ProgressSink::Lines { writer, interval }
    }
}

/// A quantity followed toward a target, e.g. `max |w| / h` from 0 to 2.
#[derive(Clone, Debug, PartialEq)]
pub struct ProgressTarget {
    /// What is followed (its symbol and unit label the reports).
    pub quantity: Quantity,
    /// Value at the start (the empty bar).
    pub start: f64,
    /// Value at which the work is done (the full bar).
    pub target: f64,
    /// Critical load $`\lambda_c`$, when the bar's first half follows the load up to it.
    pub critical_load: Option<f64>,
}

impl ProgressTarget {
    /// `quantity` from `start` to `target`.
    pub fn new(quantity: Quantity, start: f64, target: f64) -> Self {
        ProgressTarget {
            quantity,
            start,
            target,
            critical_load: None,
        }
    }

    /// The first half of the bar follows the load $`\lambda`$ from 0 to `critical_load`, the
    /// second half the quantity from `start` to `target` (see [`Self::fraction_at_load`]).
    pub fn with_critical_load(mut self, critical_load: f64) -> Self {
        self.critical_load = Some(critical_load).filter(|l| l.is_finite() && *l > 0.0);
        self
    }

    /// Fraction of the way at `value` and load `load`:
    /// $`\tfrac12\min(\lambda/\lambda_c, 1) + \tfrac12 f(v)`$ with a critical load, $`f(v)`$
    /// ([`Self::fraction`]) without.
    pub fn fraction_at_load(&self, value: f64, load: f64) -> f64 {
        match self.critical_load {
            Some(critical) if load.is_finite() => {
                0.5 * (load / critical).clamp(0.0, 1.0) + 0.5 * self.fraction(value)
            }
            _ => self.fraction(value),
        }
    }

    /// Fraction of the way, clamped to $`[0, 1]`$ (0 when start and target coincide).
    pub fn fraction(&self, value: f64) -> f64 {
        let span = self.target - self.start;
        if span == 0.0 || !span.is_finite() || !value.is_finite() {
            0.0
        } else {
            ((value - self.start) / span).clamp(0.0, 1.0)
        }
    }

    /// `"max |w| / h = 0.532 of 2.00"`, with the unit when there is one: the value and the
    /// target, without the fraction (the bar shows it).
    pub fn describe_briefly(&self, value: f64) -> String {
        let unit = if self.quantity.unit.is_empty() {
            String::new()
        } else {
            format!(" {}", self.quantity.unit)
        };
        format!(
            "{} = {}{unit} of {}{unit}",
            self.quantity.short_name(),
            format_significant(value, 4),
            format_significant(self.target, 4),
        )
    }

    /// `"max |w| / h = 0.532 of 2.00 (27 %)"`, with the unit when there is one.
    pub fn describe(&self, value: f64) -> String {
        let unit = if self.quantity.unit.is_empty() {
            String::new()
        } else {
            format!(" {}", self.quantity.unit)
        };
        format!(
            "{} = {}{unit} of {}{unit} ({:.0} %)",
            self.quantity.short_name(),
            format_significant(value, 4),
            format_significant(self.target, 4),
            100.0 * self.fraction(value)
        )
    }
}

/// Shared machinery of [`Progress`] and [`SearchProgress`]: the bar or the throttled lines.
struct Reporter {
    label: String,
    begin: Instant,
    output: Output,
}

enum Output {
    Quiet,
    /// The bar, the columns before its message on the message's line, and the text after the
    /// bar (the template's `{detail}`).
    Bar {
        bar: ProgressBar,
        message_offset: usize,
        detail: Arc<Mutex<String>>,
    },
    Lines {
        writer: Arc<Mutex<dyn Write + Send>>,
        interval: Duration,
        last: Mutex<Instant>,
    },
}

impl std::fmt::Debug for Reporter {
    fn fmt(&self, formatter: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let output = match self.output {
            Output::Quiet => "quiet",
            Output::Bar { .. } => "terminal",
            Output::Lines { .. } => "lines",
        };
        formatter
            .debug_struct("Reporter")
            .field("label", &self.label)
            .field("output", &output)
            .finish()
    }
}

impl Reporter {
    /// `bar` makes the terminal's bar; it is given the text after the bar, for its template's
    /// `{detail}` key; its message starts `message_offset` columns into its line.
    fn new(
        label: &str,
        sink: ProgressSink,
        message_offset: usize,
        bar: impl FnOnce(Arc<Mutex<String>>) -> ProgressBar,
    ) -> Self {
        let begin = Instant::now();
        let output = match sink {
            ProgressSink::Quiet => Output::Quiet,
            ProgressSink::Terminal => {
                let detail = Arc::new(Mutex::new(String::new()));
                let bar = bar(detail.clone());
                bar.set_prefix(label.to_string());
                bar.enable_steady_tick(Duration::from_millis(250));
                Output::Bar {
                    bar,
                    message_offset,
                    detail,
                }
            }
            ProgressSink::Lines { writer, interval } => Output::Lines {
                writer,
                interval,
                last: Mutex::new(begin),
            },
        };
        Reporter {
            label: label.to_string(),
            begin,
            output,
        }
    }

    /// One line now (start and end), whatever the interval.
    fn line(&self, text: &str) {
        if let Output::Lines { writer, .. } = &self.output
            && let Ok(mut writer) = writer.lock()
        {
            // A closed standard error must not stop the computation.
            let _ = writeln!(writer, "{}: {text}", self.label);
            let _ = writer.flush();
        }
    }

    /// A periodic line, if the interval has passed since the last one.
    fn periodic_line(&self, text: impl FnOnce() -> String) {
        if let Output::Lines { interval, last, .. } = &self.output {
            let now = Instant::now();
            let due = match last.lock() {
                Ok(mut last) if now.duration_since(*last) >= *interval => {
                    *last = now;
                    true
                }
                _ => false,
            };
            if due {
                let elapsed = now.duration_since(self.begin).as_secs_f64();
                self.line(&format!("[{elapsed:.0} s] {}", text()));
            }
        }
    }

    fn finish(&self, summary: &str) {
        match &self.output {
            Output::Quiet => {}
            Output::Bar {
                bar,
                message_offset,
                ..
            } => {
                bar.disable_steady_tick();
                let width = terminal_columns().saturating_sub(*message_offset);
                bar.finish_with_message(fit_parts(&detail_parts(summary), width));
                // indicatif leaves the cursor at the end of the bar's line: what the program
                // prints next must start on a line of its own.
                let _ = writeln!(std::io::stderr());
            }
            Output::Lines { .. } => {
                let elapsed = self.begin.elapsed().as_secs_f64();
                self.line(&format!("finished in {elapsed:.1} s: {summary}"));
            }
        }
    }
}

/// Progress of a computation toward a target value of one quantity (see the module
/// documentation).
#[derive(Debug)]
pub struct Progress {
    target: ProgressTarget,
    reporter: Reporter,
}

impl Progress {
    /// Reports labelled `label` (e.g. `"wrinkle run"`) of `target` into `sink`; in line mode a
    /// start line is written at once.
    pub fn new(label: &str, target: ProgressTarget, sink: ProgressSink) -> Self {
        let reporter = Reporter::new(label, sink, label.chars().count() + 1, |detail| {
            let bar =
                ProgressBar::with_draw_target(Some(BAR_RESOLUTION), ProgressDrawTarget::stderr());
            let after_bar = move |_: &ProgressState, text: &mut dyn std::fmt::Write| {
                if let Ok(detail) = detail.lock() {
                    let _ = text.write_str(&detail);
                }
            };
            bar.set_style(
                // Two lines, each fitted to the terminal's width (see the module documentation).
                ProgressStyle::with_template(
                    "{prefix:.bold} {msg}\n  [{bar:36.cyan/blue}] {percent:>3} % [{elapsed}] {detail}",
                )
                .unwrap_or_else(|_| ProgressStyle::default_bar())
                .with_key("detail", after_bar)
                .progress_chars("=> "),
            );
            bar
        });
        reporter.line(&format!(
            "started; target {} = {}",
            target.quantity.short_name(),
            target.quantity.format_value(target.target)
        ));
        Progress { target, reporter }
    }

    /// Reports that draw nothing.
    pub fn hidden() -> Self {
        Progress::new(
            "",
            ProgressTarget::new(Quantity::new("", "", ""), 0.0, 1.0),
            ProgressSink::Quiet,
        )
    }

    /// Whether anything is shown.
    pub fn is_visible(&self) -> bool {
        !matches!(self.reporter.output, Output::Quiet)
    }

    /// The followed quantity now has `value`; `detail` is shown after it (e.g.
    /// `"step 7, λ = 0.09121 N/mm"`).
    pub fn update(&self, value: f64, detail: &str) {
        self.show(self.target.fraction(value), value, None, detail);
    }

    /// [`Self::update`] at load `load`: with a critical load
    /// ([`ProgressTarget::with_critical_load`]) the bar follows the load up to it, and the text
    /// gives $`\lambda/\lambda_c`$ first.
    pub fn update_at_load(&self, value: f64, load: f64, detail: &str) {
        let ratio = self.target.critical_load.map(|critical| load / critical);
        self.show(
            self.target.fraction_at_load(value, load),
            value,
            ratio,
            detail,
        );
    }

    fn show(&self, fraction: f64, value: f64, ratio: Option<f64>, detail: &str) {
        let describe = || {
            let mut text = ratio.map_or(String::new(), |r| format!("λ/λ_c = {r:.3}, "));
            text.push_str(&self.target.describe(value));
            if !detail.is_empty() {
                text.push_str(", ");
                text.push_str(detail);
            }
            text
        };
        match &self.reporter.output {
            Output::Quiet => {}
            Output::Bar {
                bar,
                message_offset,
                detail: after_bar,
            } => {
                let columns = terminal_columns();
                let ratio = ratio.map(|r| format!("λ/λ_c = {r:.3}"));
                let parts = [
                    ratio.unwrap_or_default(),
                    self.target.describe_briefly(value),
                ];
                let width = columns.saturating_sub(*message_offset);
                bar.set_position((fraction * BAR_RESOLUTION as f64) as u64);
                if let Ok(mut after_bar) = after_bar.lock() {
                    *after_bar = fit_parts(
                        &detail_parts(detail),
                        columns.saturating_sub(BAR_LINE_COLUMNS),
                    );
                }
                bar.set_message(fit_parts(&parts, width));
            }
            Output::Lines { .. } => self.reporter.periodic_line(describe),
        }
    }

    /// Ends the reports with `summary` (e.g. the stop criterion), left on screen.
    pub fn finish(&self, summary: &str) {
        self.reporter.finish(summary);
    }
}

/// Progress of a search whose number of evaluations is not known in advance (see the module
/// documentation).
#[derive(Debug)]
pub struct SearchProgress {
    reporter: Reporter,
}

impl SearchProgress {
    /// Reports labelled `label` (e.g. `"wavenumber search"`) into `sink`.
    pub fn new(label: &str, sink: ProgressSink) -> Self {
        let reporter = Reporter::new(label, sink, 2, |_| {
            let bar = ProgressBar::with_draw_target(None, ProgressDrawTarget::stderr());
            bar.set_style(
                // The evaluation on a line of its own, fitted to the terminal's width.
                ProgressStyle::with_template("{prefix:.bold} {spinner} [{elapsed}]\n  {msg}")
                    .unwrap_or_else(|_| ProgressStyle::default_spinner()),
            );
            bar
        });
        reporter.line("started");
        SearchProgress { reporter }
    }

    /// Evaluation number `index` (from 1) has been done; `detail` says what it gave, e.g.
    /// `"Q = 0.2354/mm, λ_c = 0.08952 N/mm"`.
    pub fn evaluation(&self, index: usize, detail: &str) {
        let describe = || {
            if detail.is_empty() {
                format!("evaluation {index}")
            } else {
                format!("evaluation {index}, {detail}")
            }
        };
        match &self.reporter.output {
            Output::Quiet => {}
            Output::Bar {
                bar,
                message_offset,
                ..
            } => {
                let mut parts = vec![format!("evaluation {index}")];
                parts.extend(detail_parts(detail));
                let width = terminal_columns().saturating_sub(*message_offset);
                bar.set_position(index as u64);
                bar.set_message(fit_parts(&parts, width));
            }
            Output::Lines { .. } => self.reporter.periodic_line(describe),
        }
    }

    /// Ends the reports with `summary` (e.g. the minimum found).
    pub fn finish(&self, summary: &str) {
        self.reporter.finish(summary);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parts(texts: &[&str]) -> Vec<String> {
        texts.iter().map(|t| t.to_string()).collect()
    }

    /// The bar's first line of the plate on 80 columns (issue 32: it was cut after
    /// `max |w| / h = 0.0`): the label, λ/λ_c and the amplitude fit; on 60 columns the
    /// amplitude is left out whole.
    #[test]
    fn the_bar_text_fits_the_terminal_in_whole_parts() {
        let label = "wrinkle run (reference-envelope)";
        let target = ProgressTarget::new(Quantity::max_amplitude_over_thickness(), 0.0, 1.0);
        let text = parts(&["λ/λ_c = 1.019", &target.describe_briefly(0.2716)]);
        let line = fit_parts(&text, 80 - label.chars().count() - 1);
        assert_eq!(line, "λ/λ_c = 1.019, max |w| / h = 0.2716 of 1.000");
        assert!(label.chars().count() + 1 + line.chars().count() <= 80);
        assert_eq!(fit_parts(&text, 60 - 33), "λ/λ_c = 1.019");
        // After the bar (80 − BAR_LINE_COLUMNS columns): the step and the load.
        let after_bar = fit_parts(
            &detail_parts("step 7, λ = 9.300000e-2"),
            80 - BAR_LINE_COLUMNS,
        );
        assert_eq!(after_bar, "step 7, λ = 9.300000e-2");
    }

    /// A part that does not fit is skipped and the next ones are tried; when none fits, the
    /// first is cut with an ellipsis; nothing fits in no room.
    #[test]
    fn parts_that_do_not_fit_are_left_out_whole() {
        let text = parts(&["a long first part", "b", "cc"]);
        assert_eq!(fit_parts(&text, 100), "a long first part, b, cc");
        assert_eq!(fit_parts(&text, 20), "a long first part, b");
        assert_eq!(fit_parts(&text, 18), "a long first part");
        assert_eq!(fit_parts(&text, 6), "b, cc");
        assert_eq!(fit_parts(&parts(&["a long first part"]), 6), "a lon…");
        assert_eq!(fit_parts(&parts(&["", "b"]), 5), "b");
        assert_eq!(fit_parts(&text, 0), "");
    }
}
