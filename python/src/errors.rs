//! The library's errors as Python exceptions: a scene or usage error is a `SceneError`
//! (a `ValueError`) whose message names the key and where it was set; an I/O error an
//! `OSError`; anything else a `SolverError` or `WrinkleError` (`RuntimeError`s). Each carries
//! `exit_code`, the code the CLI would exit with.

use pyo3::create_exception;
use pyo3::exceptions::{PyOSError, PyRuntimeError, PyValueError};
use pyo3::prelude::*;

create_exception!(
    _native,
    WrinkleError,
    PyRuntimeError,
    "A run that could not be done; `exit_code` is the CLI's."
);
create_exception!(
    _native,
    SceneError,
    PyValueError,
    "A bad scene: unknown key, wrong type, value out of range. `key` names the key."
);
create_exception!(
    _native,
    SolverError,
    WrinkleError,
    "A solver failure (singular tangent, no convergence)."
);

/// The Python exception of `error`, with `exit_code` (and `key`, `source` for a scene error)
/// set on it.
pub fn to_python(py: Python<'_>, error: wrinkle::Error) -> PyErr {
    let exit_code = error.exit_code();
    let message = error.to_string();
    let (exception, key, source) = match &error {
        wrinkle::Error::Scene { key, source, .. } => (
            SceneError::new_err(message),
            Some(key.clone()),
            Some(source.clone()),
        ),
        wrinkle::Error::Usage(_) => (SceneError::new_err(message), None, None),
        wrinkle::Error::Io { .. } => (PyOSError::new_err(message), None, None),
        wrinkle::Error::Solver(_) => (SolverError::new_err(message), None, None),
        _ => (WrinkleError::new_err(message), None, None),
    };
    let value = exception.value(py);
    let _ = value.setattr("exit_code", exit_code);
    let _ = value.setattr("key", key);
    let _ = value.setattr("source", source);
    exception
}

/// A `ValueError` for a malformed argument of the Python layer (not a scene's).
pub fn bad_argument(what: impl std::fmt::Display) -> PyErr {
    PyValueError::new_err(what.to_string())
}
