//! What the original ARS API (`ars.model`, in Python) runs in native code because its
//! programs call it every step.

use pyo3::prelude::*;
use pyo3::types::PySet;

use crate::views::Joint;

/// `add_torque(torque)` of a rotary joint of `ars.model`, as one native call (a
/// method, so that Python calls it with its fast calling convention): while no one
/// listens (`heard`, `ars.dispatch`'s set of heard signals, holds none of
/// `signals`) the torque goes straight to `joint`; otherwise, or when the joint
/// refuses it (nothing is then applied), `fallback(torque)` runs the Python method
/// with its signals, its `JointError` and its logging.
#[pyclass(module = "ars._native", frozen, name = "_JointTorque")]
pub struct JointTorque {
    joint: Py<Joint>,
    heard: Py<PySet>,
    signals: Vec<Py<PyAny>>,
    fallback: Py<PyAny>,
}

#[pymethods]
impl JointTorque {
    #[new]
    fn new(joint: Py<Joint>, heard: Py<PySet>, signals: Vec<Py<PyAny>>, fallback: Py<PyAny>) -> Self {
        JointTorque { joint, heard, signals, fallback }
    }

    fn add_torque(&self, py: Python<'_>, torque: &Bound<'_, PyAny>) -> PyResult<Py<PyAny>> {
        let heard = self.heard.bind(py);
        let mut listened = false;
        for signal in &self.signals {
            listened |= heard.contains(signal)?;
        }
        if !listened
            && let Ok(torque) = torque.extract::<f64>()
            && self.joint.get().add_torque(py, torque).is_ok()
        {
            return Ok(py.None());
        }
        self.fallback.call1(py, (torque,))
    }
}
