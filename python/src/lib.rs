//! ARS for Python: the extension module `ars._native`, over `ars-core`. The Python
//! package `ars` (in `python/ars`) re-exports it with the exception classes.
//!
//! Every call goes through one boundary (`errors::guarded`): ARS errors become
//! `ars.ArsError` subclasses and a panic `ars.InternalError`; nothing unwinds into
//! Python.

// Python methods take the original's positional and keyword arguments one by one.
#![allow(clippy::too_many_arguments)]

mod classic;
mod errors;
mod interrupt;
mod kinds;
mod limits;
mod many;
mod mcap;
mod replay;
mod ros;
mod sensors;
mod simulation;
mod verify;
mod video;
mod viewer;
mod views;

use pyo3::prelude::*;

/// The native part of the `ars` package.
#[pymodule]
fn _native(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<simulation::PySimulation>()?;
    m.add_class::<views::Body>()?;
    m.add_class::<views::Joint>()?;
    m.add_class::<classic::JointTorque>()?;
    m.add_class::<sensors::PySensor>()?;
    m.add_class::<viewer::PyRenderer>()?;
    m.add_class::<video::PyVideoWriter>()?;
    m.add_function(wrap_pyfunction!(many::step_many, m)?)?;
    m.add_function(wrap_pyfunction!(viewer::show_program, m)?)?;
    m.add_function(wrap_pyfunction!(viewer::has_display, m)?)?;
    m.add_function(wrap_pyfunction!(viewer::device_select_would_print, m)?)?;
    m.add_function(wrap_pyfunction!(viewer::release_viewer, m)?)?;
    m.add_function(wrap_pyfunction!(verify::platform, m)?)?;
    m.add_function(wrap_pyfunction!(verify::golden_runs, m)?)?;
    m.add_function(wrap_pyfunction!(verify::golden_output, m)?)?;
    m.add_function(wrap_pyfunction!(verify::golden_compare, m)?)?;
    m.add_function(wrap_pyfunction!(verify::golden_with, m)?)?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    m.add_function(wrap_pyfunction!(panic_for_tests, m)?)?;
    Ok(())
}

/// Panics inside the boundary every call goes through: what a bug in ARS would do.
/// For the tests that show a panic arrives as `ars.InternalError` and the interpreter
/// lives on.
#[pyfunction]
#[pyo3(name = "_panic_for_tests")]
fn panic_for_tests(py: Python<'_>, message: &str) -> PyResult<()> {
    errors::guarded(py, || -> ars_core::Result<()> { panic!("{message}") })
}
