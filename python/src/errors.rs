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

/// The Python exception for an ARS error, one class per cause (see `ars/_errors.py`):
/// a bad value is an `ars.InputError` (also a `ValueError`), an unknown kind an
/// `ars.UnknownKindError` and a malformed file an `ars.FormatError` (both kinds of
/// `InputError`), an unknown name or removed object an `ars.UnknownNameError` (also a
/// `KeyError`), a file that cannot be read or written an `ars.FileError` (also an
/// `OSError`), a simulation that cannot go on an `ars.SimulationError` (the first time
/// and every later time), hooks reaching themselves an `ars.BusyError`, a panic an
/// `ars.InternalError`; all are `ars.ArsError`s.
pub(crate) fn to_py(py: Python<'_>, error: Error) -> PyErr {
    let message = error.to_string();
    let class = match &error {
        Error::Interrupted { .. } => return pyo3::exceptions::PyKeyboardInterrupt::new_err(message),
        Error::Io { path, errno, .. } => return file_error(py, *errno, message, path),
        Error::Format { file, element, line, column, .. } => {
            let location = ars_core::error::format_location(element, *line, *column);
            return format_error(py, message, file, &location, element, *line);
        }
        Error::UnknownName { .. } | Error::StaleHandle { .. } => "UnknownNameError",
        Error::UnknownKind { .. } => "UnknownKindError",
        Error::Diverged { .. } | Error::OdeInternal { .. } | Error::Ode(_) | Error::Poisoned(_) => "SimulationError",
        Error::Busy(_) => "BusyError",
        Error::Panicked { .. } => "InternalError",
        Error::User(_) => "ArsError",
        Error::SnapshotMismatch { .. } => "SnapshotMismatchError",
        Error::SnapshotVersion { .. } => "SnapshotVersionError",
        Error::SnapshotCorrupt { .. } => "SnapshotCorruptError",
        Error::NotCapturable { .. } => "NotCapturableError",
        _ => "InputError",
    };
    raise(py, class, message)
}

/// An `ars.FileError` (an `OSError`): `errno`, `strerror` (the message) and `filename`.
pub(crate) fn file_error(py: Python<'_>, errno: Option<i32>, message: String, path: &str) -> PyErr {
    match class(py, "FileError").and_then(|cls| cls.call1((errno, message, path))) {
        Ok(error) => PyErr::from_value(error),
        Err(e) => e,
    }
}

/// An `ars.FileError` for `error` met on `path`: its `errno` is the system's error
/// number, or for a failure ARS saw itself before asking the system (a missing folder,
/// a path that is a folder) the number of its kind (`ENOENT`, `EISDIR`...).
pub(crate) fn io_file_error(py: Python<'_>, error: &std::io::Error, message: String, path: &str) -> PyErr {
    let errno = error.raw_os_error().or_else(|| errno_of_kind(py, error.kind()));
    file_error(py, errno, message, path)
}

/// Python's error number (`errno.ENOENT`...) for the kinds of failure ARS reports
/// itself.
fn errno_of_kind(py: Python<'_>, kind: std::io::ErrorKind) -> Option<i32> {
    use std::io::ErrorKind;
    let name = match kind {
        ErrorKind::NotFound => "ENOENT",
        ErrorKind::PermissionDenied => "EACCES",
        ErrorKind::IsADirectory => "EISDIR",
        ErrorKind::NotADirectory => "ENOTDIR",
        ErrorKind::AlreadyExists => "EEXIST",
        _ => return None,
    };
    py.import("errno").and_then(|m| m.getattr(name)).and_then(|n| n.extract()).ok()
}

/// An `ars.FormatError` with its `filename` and `position`.
fn format_error(
    py: Python<'_>,
    message: String,
    file: &str,
    location: &str,
    element: &str,
    line: Option<u32>,
) -> PyErr {
    let made = class(py, "FormatError").and_then(|cls| {
        let error = cls.call1((message,))?;
        error.setattr("filename", file)?;
        error.setattr("position", location)?;
        error.setattr("element", element)?;
        error.setattr("line", line)?;
        Ok(error)
    });
    match made {
        Ok(error) => PyErr::from_value(error),
        Err(e) => e,
    }
}

/// `value` as a count (of steps, frames, pixels...) of type `T`: a negative or too large
/// number is an `ars.InputError` naming `what`, where a conversion by PyO3 would raise
/// `OverflowError`.
pub(crate) fn count<T: TryFrom<i64>>(py: Python<'_>, what: &str, value: impl Into<i64>) -> PyResult<T> {
    let value = value.into();
    T::try_from(value).map_err(|_| {
        let bound = if value < 0 { "must be 0 or more" } else { "is too large" };
        raise(py, "InputError", format!("{what} {bound}, got {value}"))
    })
}

/// A Python argument of type `T` whose wrong value is an `ars.InputError`: a sequence
/// of the wrong length, or an integer beyond `T`'s range, where PyO3 raises a plain
/// `ValueError` or `OverflowError` (a value of the wrong type stays a `TypeError`).
/// PyO3 adds the argument's name as a note ("while processing 'center'").
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Checked<T>(pub T);

impl<'py, T: pyo3::conversion::FromPyObjectOwned<'py>> FromPyObject<'_, 'py> for Checked<T> {
    type Error = PyErr;

    fn extract(obj: pyo3::Borrowed<'_, 'py, PyAny>) -> PyResult<Self> {
        let py = obj.py();
        obj.extract::<T>().map(Checked).map_err(|e| as_input_error(py, &obj, e.into()))
    }
}

impl From<Checked<i64>> for i64 {
    fn from(value: Checked<i64>) -> Self {
        value.0
    }
}

/// `error`, met converting `value`, as an `ars.InputError` if it is a plain
/// `ValueError` (a wrong length) or an `OverflowError` (an integer out of range);
/// any other error unchanged.
pub(crate) fn as_input_error(py: Python<'_>, value: &Bound<'_, PyAny>, error: PyErr) -> PyErr {
    use pyo3::exceptions::{PyOverflowError, PyValueError};
    let ty = error.get_type(py);
    if ty.is(py.get_type::<PyOverflowError>()) {
        let shown = value.repr().map(|r| r.to_string()).unwrap_or_default();
        let shown = if shown.chars().count() > 40 {
            format!("{}...", shown.chars().take(40).collect::<String>())
        } else {
            shown
        };
        return raise(py, "InputError", format!("the integer {shown} is out of range: {}", error.value(py)));
    }
    if ty.is(py.get_type::<PyValueError>()) {
        return raise(py, "InputError", error.value(py).to_string());
    }
    error
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
