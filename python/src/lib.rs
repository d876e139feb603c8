//! `wrinkle._native`: the library crate as a Python extension module (PyO3, abi3).
//!
//! Every function takes and returns plain strings (JSON, TOML): the pure-Python layer
//! (`python/wrinkle/`) turns them into typed objects and NumPy arrays. A scene travels as a
//! recipe ([`wrinkle::sweep::SceneRecipe`] as JSON: base TOML text and `KEY=VALUE` overrides),
//! so that a Python run is the run `wrinkle run SCENE --set KEY=VALUE` does. Solving happens
//! with the GIL released, on a worker thread, while the calling thread checks Python's signals
//! ([`interruptible`]): Ctrl-C stops the path after its current point, as in the CLI.
//!
//! Modules: [`convert`] (Python values as JSON → TOML), [`errors`] (the library's errors as
//! Python exceptions), [`vtu`] (VTU files read back as arrays), [`commands`] (the functions
//! the module exports).

mod commands;
mod convert;
mod errors;
mod vtu;

use pyo3::prelude::*;

/// The module `wrinkle._native`.
#[pymodule]
fn _native(module: &Bound<'_, PyModule>) -> PyResult<()> {
    let py = module.py();
    module.add("__version__", env!("CARGO_PKG_VERSION"))?;
    module.add("WrinkleError", py.get_type::<errors::WrinkleError>())?;
    module.add("SceneError", py.get_type::<errors::SceneError>())?;
    module.add("SolverError", py.get_type::<errors::SolverError>())?;
    commands::register(module)
}
