//! ROS 2 recordings from Python: `sim.record_mcap(path, duration)` runs the simulation
//! and writes its ROS 2 messages into an MCAP file (see [`ars_ros::mcap`]).

use std::path::PathBuf;
use std::sync::{Mutex, PoisonError};

use ars_ros::{RosError, RosOptions};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::errors::raise;
use crate::interrupt::python_signals_per_frame;
use crate::simulation::PySimulation;

/// `ars.Simulation`'s ROS 2 recordings: `record_mcap`.
#[pymethods]
impl PySimulation {
    /// Runs for `duration` seconds of simulated time and records the ROS 2 messages
    /// ARS publishes into the MCAP file at `path`, as `ros2 bag` writes them: `/clock`,
    /// `/tf` (every `1/state_rate` simulated seconds, default 50 a second),
    /// `/tf_static`, `/robot_description` (URDF robots), `/joint_states`, `/odom` (the
    /// vehicles, objects named `chassis`), `/scan` (lidars, each sample), `/imu`
    /// (IMUs) and `/camera/depth/image_raw` (depth cameras), CDR-encoded and stamped with simulated time; ARS's Y-up world is ROS's
    /// Z-up `map` frame. The file opens in Foxglove, `ros2 bag` and Rerun (docs/ros2.md).
    /// Returns `{"path", "messages": {topic: count}, "end_time"}`. More than an hour
    /// of simulated time needs `allow_long=True`. A folder that does not exist is an
    /// `ars.FileError`. Ctrl-C stops it before the next frame with
    /// `KeyboardInterrupt`, leaving no file; the simulation can be run on. The
    /// simulation keeps the recorder's joint states sensor (a sensor table named
    /// `JointStates`).
    #[pyo3(signature = (path, duration, *, state_rate=50.0, allow_long=false))]
    fn record_mcap(
        &self,
        py: Python<'_>,
        path: PathBuf,
        duration: f64,
        state_rate: f64,
        allow_long: bool,
    ) -> PyResult<Py<PyDict>> {
        if !(duration.is_finite() && duration >= 0.0) {
            return Err(raise(py, "InputError", format!("duration must be a number of seconds ≥ 0, got {duration}")));
        }
        crate::limits::check_recording(duration, None, allow_long).map_err(|m| raise(py, "InputError", m))?;
        let interrupt: Mutex<Option<PyErr>> = Mutex::new(None);
        let mut recorded = None;
        let mut refused = None;
        let ran = self.advance(py, |sim| {
            let options = RosOptions { state_rate, ..RosOptions::for_scene(sim.scene()) };
            match ars_ros::record_mcap(sim, &path, duration, &options, python_signals_per_frame(&interrupt)) {
                Ok(summary) => recorded = Some(summary),
                Err(RosError::Simulation(e)) => return Err(e),
                Err(other) => refused = Some(other.to_string()),
            }
            Ok(())
        });
        if ran.is_err() || refused.is_some() {
            // What was written is dropped: the file is whole only when the run is (a
            // file that could not be created is not there to remove).
            let _ = std::fs::remove_file(&path);
        }
        if let Some(e) = interrupt.into_inner().unwrap_or_else(PoisonError::into_inner) {
            return Err(e);
        }
        ran?;
        if let Some(message) = refused {
            return Err(raise(py, "ArsError", message));
        }
        let Some(summary) = recorded else {
            return Err(raise(py, "InternalError", "the recording ended with neither a result nor an error".into()));
        };
        let result = PyDict::new(py);
        result.set_item("path", summary.path.display().to_string())?;
        let messages = PyDict::new(py);
        for (topic, count) in &summary.messages {
            messages.set_item(topic, count)?;
        }
        result.set_item("messages", messages)?;
        result.set_item("end_time", summary.end_time)?;
        Ok(result.unbind())
    }
}
