//! Progress reporting on standard error: an [`indicatif`] bar when standard error is a terminal,
//! nothing otherwise (logs and pipes stay clean).

use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use std::io::IsTerminal;

/// A progress bar on standard error, silent when standard error is not a terminal.
///
/// Positions are counted in whatever unit the caller chooses (ANM steps, load increments, …);
/// `total_hint` is the expected number, and the bar grows if the position goes past it.
#[derive(Debug)]
pub struct Progress {
    bar: Option<ProgressBar>,
}

impl Progress {
    /// A bar labelled `label` expecting `total_hint` units of work (`0`: unknown, a spinner is
    /// shown). Draws only if standard error is a terminal.
    pub fn new(total_hint: u64, label: &str) -> Self {
        if std::io::stderr().is_terminal() {
            Self::visible(total_hint, label)
        } else {
            Self::hidden()
        }
    }

    /// A progress reporter that never draws.
    pub fn hidden() -> Self {
        Progress { bar: None }
    }

    /// A bar that draws on standard error whether or not it is a terminal.
    pub fn visible(total_hint: u64, label: &str) -> Self {
        let bar = if total_hint == 0 {
            let bar = ProgressBar::with_draw_target(None, ProgressDrawTarget::stderr());
            bar.set_style(
                ProgressStyle::with_template("{prefix:.bold} {spinner} {pos} [{elapsed}] {msg}")
                    .unwrap_or_else(|_| ProgressStyle::default_spinner()),
            );
            bar
        } else {
            let bar = ProgressBar::with_draw_target(Some(total_hint), ProgressDrawTarget::stderr());
            bar.set_style(
                ProgressStyle::with_template(
                    "{prefix:.bold} [{bar:30.cyan/blue}] {pos}/{len} [{elapsed}] {msg}",
                )
                .unwrap_or_else(|_| ProgressStyle::default_bar())
                .progress_chars("=> "),
            );
            bar
        };
        bar.set_prefix(label.to_string());
        Progress { bar: Some(bar) }
    }

    /// Whether anything is drawn.
    pub fn is_visible(&self) -> bool {
        self.bar.is_some()
    }

    /// Moves the bar to `position` and shows `message` next to it.
    pub fn update(&self, position: u64, message: &str) {
        if let Some(bar) = &self.bar {
            if let Some(length) = bar.length()
                && position > length
            {
                bar.set_length(position);
            }
            bar.set_position(position);
            bar.set_message(message.to_string());
        }
    }

    /// Stops the bar, leaving `message` on screen.
    pub fn finish(&self, message: &str) {
        if let Some(bar) = &self.bar {
            bar.finish_with_message(message.to_string());
        }
    }
}
