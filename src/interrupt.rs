//! Ctrl-C during `wrinkle run`: the path stops after the point it is computing, and every
//! output is written from the points completed so far (exit code
//! [`crate::error::EXIT_INTERRUPTED`]).
//!
//! The handler ([`install`]) only sets a flag while a path is being traced or written
//! ([`PathPhase`]); the path recorder reads it ([`requested`]) after each point. Outside that
//! phase (the threshold search, which writes nothing) and on a second Ctrl-C the process exits
//! at once with 130, the shell's convention for SIGINT.

use std::sync::atomic::{AtomicBool, Ordering};

static REQUESTED: AtomicBool = AtomicBool::new(false);
static PATH_ACTIVE: AtomicBool = AtomicBool::new(false);

/// Installs the Ctrl-C handler (once per process; later calls do nothing).
pub fn install() {
    let _ = ctrlc::set_handler(|| {
        if PATH_ACTIVE.load(Ordering::SeqCst) && !REQUESTED.swap(true, Ordering::SeqCst) {
            crate::output::message_line(
                "\ninterrupt: stopping after the current point and writing every completed point (Ctrl-C again to abort)",
            );
        } else {
            crate::output::message_line("\ninterrupted");
            std::process::exit(crate::error::EXIT_INTERRUPTED);
        }
    });
}

/// Whether the user asked to stop.
pub fn requested() -> bool {
    REQUESTED.load(Ordering::SeqCst)
}

/// Asks the path being traced to stop after its current point, as a Ctrl-C during the path
/// does — for a host that catches the interrupt itself (the Python package checks Python's
/// signals while a run works on another thread).
pub fn request() {
    REQUESTED.store(true, Ordering::SeqCst);
}

/// Forgets an earlier request, before the next run of a process that runs many (the Python
/// package); the command line runs one and never needs it.
pub fn clear() {
    REQUESTED.store(false, Ordering::SeqCst);
}

/// While alive, a Ctrl-C asks the path to stop instead of ending the process.
pub struct PathPhase(());

impl PathPhase {
    /// Enters the phase.
    pub fn enter() -> Self {
        PATH_ACTIVE.store(true, Ordering::SeqCst);
        PathPhase(())
    }
}

impl Drop for PathPhase {
    fn drop(&mut self) {
        PATH_ACTIVE.store(false, Ordering::SeqCst);
    }
}
