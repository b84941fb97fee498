//! The live ROS 2 bridge: a [`Simulation`](ars_core::Simulation) (or a program's
//! [`ProgramRunner`](ars_core::ProgramRunner)) as a ROS 2 node, with no ROS installation
//! (RustDDS through `ros2-client`).
//!
//! It publishes what the [`Publisher`](crate::Publisher) makes, the topics, types, QoS
//! and frames an MCAP recording holds ([`crate::publish`]'s table: `/clock`, `/tf`,
//! `/tf_static`, `/robot_description`, `/joint_states`, `/odom`, `/scan`, `/range`,
//! `/imu`, depth images and their `CameraInfo`), and takes and serves:
//!
//! | name | type | QoS |
//! | --- | --- | --- |
//! | `/cmd_vel` (taken) | `geometry_msgs/Twist` | best effort (takes from either) |
//! | `/position_controller/commands`, `/velocity_controller/commands`, `/effort_controller/commands` (taken) | `std_msgs/Float64MultiArray` | best effort |
//! | `/joint_commands` (taken) | `sensor_msgs/JointState` | best effort |
//! | `/ars/get_simulator_features`, `/ars/step_simulation`, `/ars/reset_simulation`, `/ars/set_simulation_state`, `/ars/get_simulation_state` | `simulation_interfaces/srv/...` | reliable |
//!
//! The state is published every `1 / rate` simulated seconds (stamped with simulated
//! time) and, in lock step, after every `StepSimulation` call as well; sensors at
//! their own rates. Messages are handed to a publishing thread, so that DDS's writers
//! do not hold the steps (a bounded queue: the simulation waits only when DDS cannot
//! keep up). The forward command controllers each take one value per joint of
//! `/joint_states`, in its order; `/joint_commands` takes named joints.
//!
//! Two modes: real time (playing, paced to the wall clock) and lock step (paused: the
//! simulation advances only by `StepSimulation`, and gives the same bits as the same
//! steps run headless). `SetSimulationState` switches between them.
//!
//! Bad input (a message that does not read as its type, a NaN, a wrong length, an
//! unknown joint, commands faster than steps) is ignored with a logged warning.

pub mod cli;
pub mod commands;
pub mod core;
mod node;
pub mod sim_interfaces;
pub mod wire;

#[cfg(test)]
mod tests;

use crate::mcap::FrameStepper;
use crate::publish::RosOptions;

pub use self::commands::{CommandGains, CommandKind, DiffDrive};
pub use self::core::BridgeCore;

/// Which ROS 2 middleware's service calls the bridge answers: the two put a
/// request's identity in different places on the wire (topics are the same for all).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum ServiceRmw {
    /// `rmw_fastrtps_cpp`, ROS 2's default (and RTPS's own request identity).
    #[default]
    FastRtps,
    /// `rmw_cyclonedds_cpp` (and plain Cyclone DDS clients): the identity in the data.
    CycloneDds,
}

impl ServiceRmw {
    fn mapping(self) -> ros2_client::ServiceMapping {
        match self {
            ServiceRmw::FastRtps => ros2_client::ServiceMapping::Enhanced,
            ServiceRmw::CycloneDds => ros2_client::ServiceMapping::Cyclone,
        }
    }

    /// The middleware that `RMW_IMPLEMENTATION` names (Cyclone DDS if it says
    /// "cyclonedds"), else the default.
    pub fn from_env() -> ServiceRmw {
        match std::env::var("RMW_IMPLEMENTATION") {
            Ok(rmw) if rmw.contains("cyclonedds") => ServiceRmw::CycloneDds,
            _ => ServiceRmw::FastRtps,
        }
    }
}

/// How the bridge runs.
#[derive(Clone, Debug, PartialEq)]
pub struct BridgeOptions {
    /// The ROS domain (0..=232; `ROS_DOMAIN_ID`).
    pub domain_id: u16,
    /// Start paused, advancing only by `StepSimulation` (lock step).
    pub lock_step: bool,
    /// State publications (`/clock`, `/tf`, `/joint_states`, `/odom`) per simulated
    /// second (default 50, an ARS frame).
    pub rate: f64,
    /// The node's name (its services are under `/<name>/`).
    pub node_name: String,
    /// Whose service calls to answer.
    pub services: ServiceRmw,
    /// The differential drive's wheel joints (left, right); `None`: found by name.
    pub drive: Option<(String, String)>,
    /// The most torque a drive wheel's motor puts out, N·m.
    pub wheel_torque: f64,
    /// How joint commands are followed.
    pub gains: CommandGains,
    /// Stop after this many simulated seconds (`None`: until Ctrl-C or quit).
    pub duration: Option<f64>,
}

impl Default for BridgeOptions {
    fn default() -> Self {
        BridgeOptions {
            domain_id: 0,
            lock_step: false,
            rate: RosOptions::default().state_rate,
            node_name: "ars".into(),
            services: ServiceRmw::default(),
            drive: None,
            wheel_torque: 30.0,
            gains: CommandGains::default(),
            duration: None,
        }
    }
}

/// Why the bridge stopped or could not start.
#[derive(Debug, thiserror::Error)]
pub enum BridgeError {
    /// No network to put DDS on.
    #[error("no network: {0}")]
    Network(String),
    /// An option or a name the bridge cannot use.
    #[error("{0}")]
    Setup(String),
    /// The simulation failed.
    #[error(transparent)]
    Simulation(#[from] ars_core::Error),
    /// Publishing failed.
    #[error(transparent)]
    Ros(#[from] crate::RosError),
    /// Ctrl-C, in the middle of a `StepSimulation` (an end, not a failure, for [`run`]).
    #[error("interrupted (Ctrl-C)")]
    Interrupted,
}

/// Checks the options, finds the drive and makes the core (no network yet).
/// `stepper` is a [`Simulation`](ars_core::Simulation) or a [`ProgramRunner`](ars_core::ProgramRunner).
pub fn prepare<S: FrameStepper>(stepper: S, options: &BridgeOptions) -> Result<BridgeCore<S>, BridgeError> {
    let (ros, drive) = checked(stepper.simulation().scene(), options)?;
    Ok(BridgeCore::new(stepper, &ros, drive, options.gains, options.lock_step)?)
}

/// What [`run`] refuses before it takes the simulation: `options` on `scene` (the
/// domain, the rate, the duration, the drive) and the network. A front end that hands
/// a simulation over (Python's `sim.ros`) asks first, so that a refusal leaves the
/// simulation with it.
pub fn check(scene: &ars_core::Scene, options: &BridgeOptions) -> Result<(), BridgeError> {
    checked(scene, options)?;
    check_network()
}

/// The publisher's options and the drive of `options` on `scene`, once checked.
fn checked(scene: &ars_core::Scene, options: &BridgeOptions) -> Result<(RosOptions, Option<DiffDrive>), BridgeError> {
    if options.domain_id > 232 {
        return Err(BridgeError::Setup(format!("domain ID {}: ROS 2 domains are 0 to 232", options.domain_id)));
    }
    let ros = RosOptions { state_rate: options.rate, ..RosOptions::for_scene(scene) };
    ros.check().map_err(|e| BridgeError::Setup(e.to_string()))?;
    if options.duration.is_some_and(|d| !(d.is_finite() && d >= 0.0)) {
        return Err(BridgeError::Setup(format!("duration {:?}: must be a number of seconds ≥ 0", options.duration)));
    }
    let names = options.drive.as_ref().map(|(l, r)| (l.as_str(), r.as_str()));
    let drive = DiffDrive::find(scene, names, options.wheel_torque).map_err(BridgeError::Setup)?;
    Ok((ros, drive))
}

/// Runs `stepper` (a [`Simulation`](ars_core::Simulation) or a [`ProgramRunner`](ars_core::ProgramRunner)) as
/// a ROS 2 node until Ctrl-C (once
/// [`stop_on_ctrl_c`](ars_core::interrupt::stop_on_ctrl_c) is set; see
/// [`interrupt::requested`](ars_core::interrupt::requested)), a `SetSimulationState` to
/// quit, or `options.duration`; gives it back, as it is then.
pub fn run<S: FrameStepper>(stepper: S, options: &BridgeOptions) -> Result<S, BridgeError> {
    run_prepared(prepare(stepper, options)?, options)
}

/// [`run`] with a core made by [`prepare`] with the same `options`.
pub fn run_prepared<S: FrameStepper>(mut core: BridgeCore<S>, options: &BridgeOptions) -> Result<S, BridgeError> {
    check_network()?;
    let node = node::BridgeNode::new(options, core.topics())?;
    match node::run_loop(&node, &mut core, options) {
        Ok(()) | Err(BridgeError::Interrupted) => Ok(core.into_stepper()),
        Err(e) => Err(e),
    }
}

/// What the bridge of `core` is, in a line: its node, domain and mode, the drive
/// `/cmd_vel` turns and the joints the forward controllers take, in their order.
pub fn describe<S: FrameStepper>(core: &BridgeCore<S>, options: &BridgeOptions) -> String {
    let name = |id| core.sim().scene().joint(id).map(|j| j.name().to_string()).unwrap_or_default();
    let drive = match core.drive() {
        Some(d) => format!("/cmd_vel drives {} (left) and {} (right)", name(d.left.0), name(d.right.0)),
        None => "no differential drive for /cmd_vel (--drive LEFT,RIGHT names one)".into(),
    };
    let joints: Vec<&str> = core.joints().iter().map(|(n, _)| n.as_str()).collect();
    format!(
        "ars ros: node /{} on ROS domain {}, {}; {drive}; joints (the forward controllers' order): {}",
        options.node_name,
        options.domain_id,
        if options.lock_step { "lock step (paused until /ars/step_simulation)" } else { "real time" },
        if joints.is_empty() { "none".into() } else { joints.join(", ") }
    )
}

/// A clear error where DDS would have no network: not even the loopback is up.
fn check_network() -> Result<(), BridgeError> {
    let socket = std::net::UdpSocket::bind(("0.0.0.0", 0))
        .map_err(|e| BridgeError::Network(format!("cannot open a UDP socket ({e})")))?;
    // Connecting a UDP socket sends nothing: it only finds a route.
    socket.connect(("127.0.0.1", 7400)).map_err(|e| {
        BridgeError::Network(format!(
            "no network interface is up, not even the loopback ({e}); DDS needs one (`ip link set lo up`)"
        ))
    })
}

/// Prints the bridge's warnings on standard error, for programs with no logger of
/// their own. Does nothing if a logger is already set. RustDDS's own log is left out:
/// it logs errors it recovers from (one per endpoint when a node is dropped), and a
/// failure that matters reaches the bridge as an `Err`, which it logs.
pub fn log_to_stderr() {
    struct Stderr;
    impl log::Log for Stderr {
        fn enabled(&self, meta: &log::Metadata) -> bool {
            meta.target().starts_with("ars_ros") && meta.level() <= log::Level::Warn
        }
        fn log(&self, record: &log::Record) {
            if self.enabled(record.metadata()) {
                eprintln!("ars ros: {}: {}", record.level().as_str().to_lowercase(), record.args());
            }
        }
        fn flush(&self) {}
    }
    if log::set_boxed_logger(Box::new(Stderr)).is_ok() {
        log::set_max_level(log::LevelFilter::Warn);
    }
}
