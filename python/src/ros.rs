//! The live ROS 2 bridge from Python: `sim.ros(...)` runs the simulation as a ROS 2
//! node ([`ars_ros::bridge`]) until `duration` simulated seconds, a
//! `SetSimulationState` to quit, or Ctrl-C.
//!
//! The bridge takes the simulation by value ([`bridge::run`]) and gives it back when it
//! ends. It runs on a thread of its own, which holds the simulation's lock throughout
//! (other Python threads wait for it, as for a `step`), while the calling thread, with
//! the GIL released, runs Python's signal handlers every few milliseconds. Ctrl-C there
//! asks the bridge to stop through the flag it watches
//! ([`ars_core::interrupt::request`]), waits for it to give the simulation back,
//! withdraws the request and raises `KeyboardInterrupt`.
//!
//! The bridge drops the simulation when it fails (DDS cannot start, a step fails, a
//! Python hook raises). What it would refuse at its start is checked here first, with
//! the simulation still in hand; a failure after that leaves the Python object without
//! its simulation ([`PySimulation::mark_lost`]), and the error says so.

use std::panic::{AssertUnwindSafe, catch_unwind};
use std::sync::Mutex;
use std::sync::mpsc::{Receiver, RecvTimeoutError};

use ars_core::Simulation;
use ars_ros::RosError;
use ars_ros::bridge::{self, BridgeError, BridgeOptions, ServiceRmw};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::errors::{Checked, panic_message, raise, to_py};
use crate::simulation::{Int, PySimulation, SIGNAL_CHECK_PERIOD, signal_raised};

/// The highest ROS 2 domain ID.
const MAX_DOMAIN_ID: i64 = 232;

/// `sim.ros`'s keywords, as given (`None`: the bridge's default).
pub(crate) struct RosKeywords {
    pub duration: Option<f64>,
    pub lock_step: bool,
    pub rate: Option<f64>,
    pub domain_id: Option<i64>,
    pub node_name: String,
    pub services: Option<String>,
    pub drive: Option<(String, String)>,
    pub wheel_torque: Option<f64>,
}

impl RosKeywords {
    /// The bridge's options, or why not (naming the keyword). What is not given is the
    /// bridge's default; the domain ID is then `ROS_DOMAIN_ID`, else 0, as `ars ros`'s.
    pub(crate) fn options(self) -> Result<BridgeOptions, String> {
        let defaults = BridgeOptions::default();
        if let Some(d) = self.duration
            && !(d.is_finite() && d >= 0.0)
        {
            return Err(format!("duration must be a number of simulated seconds ≥ 0 (or None: no end), got {d}"));
        }
        let rate = positive("rate", "of publications per simulated second", self.rate, defaults.rate)?;
        let wheel_torque = positive("wheel_torque", "of N·m", self.wheel_torque, defaults.wheel_torque)?;
        let domain_id = match self.domain_id {
            Some(id) => {
                domain(id).ok_or(format!("domain_id must be a ROS domain ID, 0 to {MAX_DOMAIN_ID}, got {id}"))?
            }
            None => domain_from_env()?.unwrap_or(defaults.domain_id),
        };
        check_node_name(&self.node_name)?;
        let services = match self.services.as_deref() {
            None => ServiceRmw::from_env(),
            Some(name) => rmw(name)?,
        };
        if let Some((left, right)) = &self.drive
            && (left.is_empty() || right.is_empty())
        {
            return Err(format!("drive must name two wheel joints (left, right), got ({left:?}, {right:?})"));
        }
        Ok(BridgeOptions {
            domain_id,
            lock_step: self.lock_step,
            rate,
            node_name: self.node_name,
            services,
            drive: self.drive,
            wheel_torque,
            duration: self.duration,
            ..defaults
        })
    }
}

/// `value` if given, else `default`; `Err` naming `what` unless a positive number.
fn positive(what: &str, unit: &str, value: Option<f64>, default: f64) -> Result<f64, String> {
    match value {
        None => Ok(default),
        Some(v) if v.is_finite() && v > 0.0 => Ok(v),
        Some(v) => Err(format!("{what} must be a positive number {unit}, got {v}")),
    }
}

/// `id` as a ROS domain ID, if it is one.
fn domain(id: i64) -> Option<u16> {
    u16::try_from(id).ok().filter(|d| i64::from(*d) <= MAX_DOMAIN_ID)
}

/// The domain ID `ROS_DOMAIN_ID` gives, if it is set and not blank.
fn domain_from_env() -> Result<Option<u16>, String> {
    match std::env::var("ROS_DOMAIN_ID") {
        Ok(text) if !text.trim().is_empty() => text
            .trim()
            .parse()
            .ok()
            .and_then(domain)
            .map(Some)
            .ok_or(format!("ROS_DOMAIN_ID={text:?} is not a ROS domain ID (0 to {MAX_DOMAIN_ID}); give domain_id")),
        _ => Ok(None),
    }
}

/// ROS 2's rule for a node's name (it also names the services' namespace): letters,
/// digits and underscores, not starting with a digit.
fn check_node_name(name: &str) -> Result<(), String> {
    let mut chars = name.chars();
    let first_ok = chars.next().is_some_and(|c| c.is_ascii_alphabetic() || c == '_');
    if first_ok && chars.all(|c| c.is_ascii_alphanumeric() || c == '_') {
        return Ok(());
    }
    Err(format!(
        "node_name must be a ROS 2 node name (letters, digits and underscores, not starting with a digit), got {name:?}"
    ))
}

/// The middleware whose service calls to answer, by name.
fn rmw(name: &str) -> Result<ServiceRmw, String> {
    match name.to_lowercase().as_str() {
        "fastrtps" | "rmw_fastrtps_cpp" | "fastdds" => Ok(ServiceRmw::FastRtps),
        "cyclonedds" | "rmw_cyclonedds_cpp" => Ok(ServiceRmw::CycloneDds),
        _ => Err(format!(
            "services must be \"fastrtps\" or \"cyclonedds\" (or None: from RMW_IMPLEMENTATION), got {name:?}"
        )),
    }
}

/// How a bridge run ended.
enum Ended {
    /// It ran and gave the simulation back, at this time and step count.
    Ran { end_time: f64, steps: u64 },
    /// Refused before the simulation was handed over (it is untouched): a bad option
    /// for this scene.
    BadOption(String),
    /// Refused before the simulation was handed over: no network for DDS.
    NoNetwork(String),
    /// Refused before the simulation was handed over: the simulation cannot be
    /// bridged (an ARS error).
    Refused(ars_core::Error),
    /// The bridge failed after taking the simulation, which is gone with it.
    Failed(BridgeError),
    /// A panic (the simulation is gone if the bridge had it).
    Panicked(String),
}

/// What the bridge would refuse ([`bridge::check`]: the options, the network), and a
/// simulation it could not reset to, checked with the simulation still in hand.
fn check_before(sim: &Simulation, options: &BridgeOptions) -> Result<(), Ended> {
    bridge::check(sim.scene(), options).map_err(|e| match e {
        BridgeError::Network(_) => Ended::NoNetwork(e.to_string()),
        other => Ended::BadOption(other.to_string()),
    })?;
    sim.snapshot().map(drop).map_err(Ended::Refused)
}

/// Runs the bridge on `owner`'s simulation, locked throughout; gives it back to
/// `owner` when the bridge ends, or marks it lost when the bridge fails.
fn serve(owner: &PySimulation, options: BridgeOptions) -> Ended {
    let mut sim = owner.locked();
    if let Err(refused) = check_before(&sim, &options) {
        return refused;
    }
    let stand_in = match Simulation::builder().build() {
        Ok(empty) => empty,
        Err(e) => return Ended::Refused(e),
    };
    let taken = std::mem::replace(&mut *sim, stand_in);
    match catch_unwind(AssertUnwindSafe(|| bridge::run(taken, &options))) {
        Ok(Ok(back)) => {
            *sim = back;
            Ended::Ran { end_time: sim.scene().time(), steps: sim.scene().step_count() }
        }
        Ok(Err(e)) => {
            owner.mark_lost(format!("sim.ros failed and the ROS 2 bridge dropped it ({e})"));
            Ended::Failed(e)
        }
        Err(panic) => {
            let message = panic_message(&panic);
            owner.mark_lost(format!("the ROS 2 bridge panicked with it ({message})"));
            Ended::Panicked(message)
        }
    }
}

/// Waits for the bridge's end, running Python's signal handlers every
/// [`SIGNAL_CHECK_PERIOD`] (call it without the GIL); when one raises (Ctrl-C), keeps
/// its exception in `raised` and asks the bridge to stop, then withdraws the request
/// once it has.
fn wait_watching_signals(ended: &Receiver<Ended>, raised: &Mutex<Option<PyErr>>) -> Option<Ended> {
    let mut asked = false;
    let outcome = loop {
        match ended.recv_timeout(SIGNAL_CHECK_PERIOD) {
            Ok(end) => break Some(end),
            Err(RecvTimeoutError::Disconnected) => break None,
            Err(RecvTimeoutError::Timeout) => {
                if !asked && signal_raised(raised) {
                    ars_core::interrupt::request();
                    asked = true;
                }
            }
        }
    };
    if asked {
        ars_core::interrupt::clear();
    }
    outcome
}

/// `sim.ros(...)`: see its docstring.
pub(crate) fn ros(py: Python<'_>, slf: &Bound<'_, PySimulation>, keywords: RosKeywords) -> PyResult<Py<PyDict>> {
    let sim = slf.get();
    sim.check_not_lost(py)?;
    if sim.in_own_hook() {
        return Err(raise(py, "BusyError", "a hook cannot run the simulation it runs in as a ROS 2 node".into()));
    }
    let options = keywords.options().map_err(|m| raise(py, "InputError", format!("sim.ros: {m}")))?;
    bridge::log_to_stderr();
    let (sender, receiver) = std::sync::mpsc::channel();
    let owner = slf.clone().unbind();
    let worker = std::thread::Builder::new().name("ars-ros".into()).spawn(move || {
        let _ = sender.send(serve(owner.get(), options));
    });
    let worker =
        worker.map_err(|e| raise(py, "ArsError", format!("sim.ros: the bridge's thread could not start: {e}")))?;
    let raised: Mutex<Option<PyErr>> = Mutex::new(None);
    let watched = &raised;
    let ended = py.detach(move || {
        let ended = wait_watching_signals(&receiver, watched);
        let _ = worker.join();
        ended
    });
    // Ctrl-C first, then a Python hook's own exception, then the bridge's end.
    if let Some(e) = raised.into_inner().unwrap_or_else(std::sync::PoisonError::into_inner) {
        sim.take_hook_exception();
        return Err(e);
    }
    if let Some(e) = sim.take_hook_exception() {
        return Err(e);
    }
    match ended {
        Some(Ended::Ran { end_time, steps }) => {
            let summary = PyDict::new(py);
            summary.set_item("end_time", end_time)?;
            summary.set_item("steps", steps)?;
            Ok(summary.unbind())
        }
        Some(Ended::BadOption(m)) => Err(raise(py, "InputError", format!("sim.ros: {m}"))),
        Some(Ended::NoNetwork(m)) => Err(raise(py, "ArsError", format!("sim.ros: {m}"))),
        Some(Ended::Refused(e)) => Err(to_py(py, e)),
        Some(Ended::Failed(BridgeError::Simulation(e) | BridgeError::Ros(RosError::Simulation(e)))) => {
            Err(to_py(py, e))
        }
        Some(Ended::Failed(e)) => Err(raise(py, "ArsError", format!("sim.ros: {e} (the simulation is gone with it)"))),
        Some(Ended::Panicked(m)) => Err(raise(py, "InternalError", format!("ARS panicked in sim.ros: {m}"))),
        None => Err(raise(py, "InternalError", "sim.ros: the bridge's thread ended without a result".into())),
    }
}

/// `ars.Simulation.ros`.
#[pymethods]
impl PySimulation {
    /// Runs the simulation as a live ROS 2 node (no ROS installation needed: the
    /// bridge speaks DDS itself; topics, services, QoS and frames in docs/ros2.md): it
    /// publishes what `record_mcap` records (`/clock`, `/tf`, `/joint_states`, `/odom`
    /// every `1/rate` simulated seconds; `/tf_static`, each URDF robot's
    /// `/robot_description`; the sensors' topics), takes `/cmd_vel` and the joint
    /// commands, and serves the Simulation Interfaces calls under `/<node_name>/`.
    /// Real time (paced to the wall clock), or with `lock_step=True` paused, advancing
    /// only through the `StepSimulation` service (the same bits as the same steps run
    /// headless). Blocks, with the GIL released, until `duration` simulated seconds
    /// have run (`None`: no end), a `SetSimulationState` to quit, or Ctrl-C; returns
    /// `{"end_time", "steps"}` (the simulation's time and step count then). The
    /// simulation keeps the bridge's joint states sensor (a sensor table named
    /// `JointStates`).
    ///
    /// Defaults as `ars ros`'s: `rate` as recordings' (50 a second), `domain_id`
    /// `ROS_DOMAIN_ID` else 0, `services` (whose service calls to answer:
    /// `"fastrtps"` or `"cyclonedds"`) from `RMW_IMPLEMENTATION`, `drive` (the two
    /// wheel joints `/cmd_vel` turns, left and right) found by name, `wheel_torque` 30
    /// N·m. A bad option is an `ars.InputError` (a `ValueError`) naming it; no network
    /// for DDS an `ars.ArsError`. Ctrl-C (in the main thread) stops it with
    /// `KeyboardInterrupt`, the simulation as it was then, usable; it stops every
    /// `sim.ros` running in the process. If the bridge fails once running (DDS cannot
    /// start, the simulation fails, a Python hook raises), the error is raised and the
    /// simulation is gone: later calls raise `ars.SimulationError`.
    #[pyo3(signature = (duration=None, *, lock_step=false, rate=None, domain_id=None, node_name="ars".to_string(),
                        services=None, drive=None, wheel_torque=None))]
    fn ros(
        slf: &Bound<'_, Self>,
        py: Python<'_>,
        duration: Option<f64>,
        lock_step: bool,
        rate: Option<f64>,
        domain_id: Option<Int>,
        node_name: String,
        services: Option<String>,
        drive: Option<Checked<(String, String)>>,
        wheel_torque: Option<f64>,
    ) -> PyResult<Py<PyDict>> {
        let keywords = RosKeywords {
            duration,
            lock_step,
            rate,
            domain_id: domain_id.map(|id| id.0),
            node_name,
            services,
            drive: drive.map(|d| d.0),
            wheel_torque,
        };
        ros(py, slf, keywords)
    }
}
