//! Progress off a terminal: a start line, periodic lines no more often than the interval, an end
//! line; the value and target with their unit; nothing when quiet; the search variant.

use std::io::Write;
use std::sync::{Arc, Mutex};
use std::time::Duration;
use wrinkle::output::{Progress, ProgressSink, ProgressTarget, Quantity, SearchProgress};

/// A writer whose text the test can read.
#[derive(Clone, Default)]
struct Captured(Arc<Mutex<Vec<u8>>>);

impl Write for Captured {
    fn write(&mut self, bytes: &[u8]) -> std::io::Result<usize> {
        self.0.lock().unwrap().extend_from_slice(bytes);
        Ok(bytes.len())
    }
    fn flush(&mut self) -> std::io::Result<()> {
        Ok(())
    }
}

impl Captured {
    fn text(&self) -> String {
        String::from_utf8(self.0.lock().unwrap().clone()).unwrap()
    }
    fn sink(&self, interval: Duration) -> ProgressSink {
        ProgressSink::lines(Arc::new(Mutex::new(self.clone())), interval)
    }
}

fn amplitude_target() -> ProgressTarget {
    ProgressTarget::new(Quantity::max_amplitude_over_thickness(), 0.0, 4.0)
}

#[test]
fn lines_are_throttled_to_the_interval_plus_start_and_end() {
    let captured = Captured::default();
    let progress = Progress::new(
        "wrinkle run",
        amplitude_target(),
        captured.sink(Duration::from_secs(3600)),
    );
    assert!(progress.is_visible());
    for step in 0..100 {
        progress.update(0.04 * step as f64, &format!("step {step}"));
    }
    progress.finish("stop criterion reached (20 steps)");
    let text = captured.text();
    let lines: Vec<&str> = text.lines().collect();
    assert_eq!(lines.len(), 2, "{text}");
    assert_eq!(
        lines[0],
        "wrinkle run: started; target max |w| / h = 4.0000"
    );
    assert!(
        lines[1].starts_with("wrinkle run: finished in "),
        "{}",
        lines[1]
    );
    assert!(
        lines[1].ends_with("s: stop criterion reached (20 steps)"),
        "{}",
        lines[1]
    );
}

#[test]
fn each_line_gives_value_target_and_fraction_with_the_unit() {
    let captured = Captured::default();
    let load = ProgressTarget::new(Quantity::biaxial_load(), 0.0, 0.2);
    let progress = Progress::new("wrinkle run", load, captured.sink(Duration::ZERO));
    progress.update(0.05, "step 3");
    progress.update(0.5, "");
    let text = captured.text();
    let lines: Vec<&str> = text.lines().collect();
    assert_eq!(lines.len(), 3, "{text}");
    assert!(
        lines[1].ends_with("λ = −N_X = 0.05000 N/mm of 0.2000 N/mm (25 %), step 3"),
        "{}",
        lines[1]
    );
    assert!(
        lines[2].contains("(100 %)"),
        "past the target the bar is full"
    );
}

#[test]
fn quiet_progress_shows_nothing() {
    let progress = Progress::new("wrinkle run", amplitude_target(), ProgressSink::Quiet);
    assert!(!progress.is_visible());
    progress.update(1.0, "step 1");
    progress.finish("done");
    assert!(!Progress::hidden().is_visible());
    assert!(matches!(
        ProgressSink::standard_error(true),
        ProgressSink::Quiet
    ));
}

#[test]
fn search_progress_counts_evaluations() {
    let captured = Captured::default();
    let search = SearchProgress::new("wavenumber search", captured.sink(Duration::ZERO));
    search.evaluation(7, "Q = 0.2354/mm, λ_c = 0.08952 N/mm");
    search.finish("Q = 0.23543/mm after 23 evaluations");
    let text = captured.text();
    assert!(text.contains("wavenumber search: started\n"), "{text}");
    assert!(
        text.contains("] evaluation 7, Q = 0.2354/mm, λ_c = 0.08952 N/mm\n"),
        "{text}"
    );
    assert!(text.contains("Q = 0.23543/mm after 23 evaluations"));
}

#[test]
fn fraction_is_clamped_and_safe() {
    let target = amplitude_target();
    assert_eq!(target.fraction(-1.0), 0.0);
    assert_eq!(target.fraction(2.0), 0.5);
    assert_eq!(target.fraction(9.0), 1.0);
    assert_eq!(target.fraction(f64::NAN), 0.0);
    let degenerate = ProgressTarget::new(Quantity::biaxial_load(), 1.0, 1.0);
    assert_eq!(degenerate.fraction(1.0), 0.0);
}

/// With a critical load the bar does not sit empty while the amplitude barely moves: its first
/// half follows the load up to λ_c, its second half the amplitude; the text gives λ/λ_c first.
#[test]
fn the_bar_follows_the_load_up_to_the_critical_load() {
    let target = amplitude_target().with_critical_load(0.09);
    assert_eq!(target.fraction_at_load(0.0, 0.0), 0.0);
    assert!((target.fraction_at_load(0.0, 0.045) - 0.25).abs() < 1e-12);
    assert!((target.fraction_at_load(0.0, 0.09) - 0.5).abs() < 1e-12);
    assert!((target.fraction_at_load(2.0, 0.1) - 0.75).abs() < 1e-12);
    assert_eq!(target.fraction_at_load(4.0, 0.12), 1.0);
    // Without a critical load: the amplitude alone.
    assert_eq!(amplitude_target().fraction_at_load(2.0, 0.0), 0.5);

    let captured = Captured::default();
    let progress = Progress::new("wrinkle run", target, captured.sink(Duration::ZERO));
    progress.update_at_load(0.01, 0.045, "step 3");
    let text = captured.text();
    assert!(
        text.lines()
            .nth(1)
            .unwrap()
            .contains("λ/λ_c = 0.500, max |w| / h = 0.01000 of 4.000 (0 %), step 3"),
        "{text}"
    );
}
