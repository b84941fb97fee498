//! What `python -m ars.verify` and the sweeps' provenance need from the native side:
//! the platform, the build, and the golden runs of the Rust programs with the
//! committed table (`ars_programs::golden`).

use ars_programs::golden::{GoldenEntry, GoldenTable, runs};
use pyo3::prelude::*;
use pyo3::types::{PyBytes, PyDict};

use crate::errors::raise;

/// The platform this process computes on, and the build of ARS it runs: a dict with
/// `ars_version`, `ars_commit`, `libode_version`, `libode_configuration`, `cpu`,
/// `libc`, `os`.
#[pyfunction]
#[pyo3(name = "_platform")]
pub(crate) fn platform(py: Python<'_>) -> PyResult<Bound<'_, PyDict>> {
    let p = ars_core::platform::Platform::current();
    let dict = PyDict::new(py);
    dict.set_item("ars_version", env!("CARGO_PKG_VERSION"))?;
    dict.set_item("ars_commit", env!("ARS_GIT_COMMIT"))?;
    dict.set_item("libode_version", p.libode_version)?;
    dict.set_item("libode_configuration", p.libode_configuration)?;
    dict.set_item("cpu", p.cpu)?;
    dict.set_item("libc", p.libc)?;
    dict.set_item("os", p.os)?;
    Ok(dict)
}

/// The golden runs of the Rust programs: `[(name, what, duration), ...]`.
#[pyfunction]
#[pyo3(name = "_golden_runs")]
pub(crate) fn golden_runs() -> Vec<(&'static str, &'static str, f64)> {
    runs().into_iter().map(|r| (r.name, r.what, r.duration)).collect()
}

/// The output (CSV bytes) of the golden run `name`, computed now (without the GIL).
#[pyfunction]
#[pyo3(name = "_golden_output")]
pub(crate) fn golden_output<'py>(py: Python<'py>, name: &str) -> PyResult<Bound<'py, PyBytes>> {
    let Some(run) = runs().into_iter().find(|r| r.name == name) else {
        return Err(raise(py, "InputError", format!("there is no golden run {name:?}")));
    };
    let output = crate::errors::guarded(py, || py.detach(|| run.output()))?;
    Ok(PyBytes::new(py, &output))
}

/// How `output` of run `name` compares with `table` (JSON text; the table compiled in
/// when `None`): `"identical"`, or where it first differs.
#[pyfunction]
#[pyo3(name = "_golden_compare", signature = (name, output, table=None))]
pub(crate) fn golden_compare(py: Python<'_>, name: &str, output: &[u8], table: Option<&str>) -> PyResult<String> {
    Ok(table_of(py, table)?.compare(name, output).to_string())
}

/// `table` (JSON text; the compiled-in one when `None`) with run `name`'s entry made
/// from `output`, as JSON text.
#[pyfunction]
#[pyo3(name = "_golden_with", signature = (name, duration, output, table=None))]
pub(crate) fn golden_with(
    py: Python<'_>,
    name: &str,
    duration: f64,
    output: &[u8],
    table: Option<&str>,
) -> PyResult<String> {
    let mut table = table_of(py, table)?;
    table.set(GoldenEntry::of(name, duration, output));
    Ok(table.to_json())
}

/// The table in `text` (JSON), or the one compiled in.
fn table_of(py: Python<'_>, text: Option<&str>) -> PyResult<GoldenTable> {
    crate::errors::guarded(py, || text.map_or_else(|| Ok(GoldenTable::committed()), GoldenTable::parse))
}
