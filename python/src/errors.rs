//! Rust errors and panics as Python exceptions.
//!
//! The classes are defined in Python (`ars/_errors.py`, importable as `ars.ArsError`
//! and so on) so that they can also derive from Python's own `ValueError` and
//! `KeyError`, and so that Ray rebuilds them as the same classes in other processes.

use std::panic::{AssertUnwindSafe, catch_unwind};

use ars_core::Error;
use pyo3::prelude::*;
use pyo3::types::PyType;

/// The Python class `ars.NAME`.
fn class<'py>(py: Python<'py>, name: &str) -> PyResult<Bound<'py, PyType>> {
    Ok(py.import("ars._errors")?.getattr(name)?.cast_into::<PyType>()?)
}

/// An exception of class `ars.NAME` carrying `message`.
pub(crate) fn raise(py: Python<'_>, name: &str, message: String) -> PyErr {
    match class(py, name) {
        Ok(cls) => PyErr::from_type(cls, message),
        Err(e) => e,
    }
}

/// The Python exception for an ARS error: bad input is an `ars.InputError` (also a
/// `ValueError`), an unknown name an `ars.UnknownNameError` (also a `KeyError`), a
/// simulation that cannot go on an `ars.SimulationError`, a panic an
/// `ars.InternalError`; all are `ars.ArsError`s.
pub(crate) fn to_py(py: Python<'_>, error: Error) -> PyErr {
    let class = match &error {
        Error::Interrupted { .. } => return pyo3::exceptions::PyKeyboardInterrupt::new_err(error.to_string()),
        Error::UnknownName { .. } => "UnknownNameError",
        Error::Diverged { .. } | Error::OdeInternal { .. } | Error::Ode(_) => "SimulationError",
        Error::Panicked { .. } | Error::Poisoned(_) => "InternalError",
        Error::User(_) => "ArsError",
        _ => "InputError",
    };
    raise(py, class, error.to_string())
}

/// Runs `f`, turning an ARS error into its Python exception and a panic into
/// `ars.InternalError` (never PyO3's `PanicException`, which is a `BaseException`).
pub(crate) fn guarded<R>(py: Python<'_>, f: impl FnOnce() -> Result<R, Error>) -> PyResult<R> {
    outcome(py, catch_unwind(AssertUnwindSafe(f)))
}

/// What [`guarded`] returns for the outcome of a call caught with `catch_unwind`.
pub(crate) fn outcome<R>(py: Python<'_>, caught: std::thread::Result<Result<R, Error>>) -> PyResult<R> {
    match caught {
        Ok(Ok(r)) => Ok(r),
        Ok(Err(e)) => Err(to_py(py, e)),
        Err(panic) => Err(raise(py, "InternalError", format!("ARS panicked: {}", panic_message(&panic)))),
    }
}

/// The message of a panic payload.
pub(crate) fn panic_message(panic: &Box<dyn std::any::Any + Send>) -> String {
    if let Some(s) = panic.downcast_ref::<&str>() {
        (*s).to_string()
    } else if let Some(s) = panic.downcast_ref::<String>() {
        s.clone()
    } else {
        "(no message)".into()
    }
}
