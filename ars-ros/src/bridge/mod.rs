//! The live ROS 2 bridge: a [`Simulation`] as a ROS 2 node, with no ROS installation
//! (RustDDS through `ros2-client`).
//!
//! | name | type | QoS |
//! | --- | --- | --- |
//! | `/clock` (published) | `rosgraph_msgs/Clock` | best effort, keep last 1 (rclcpp's `ClockQoS`) |
//! | `/joint_states` (published) | `sensor_msgs/JointState` | reliable, volatile, keep last 10 |
//! | `/tf` (published) | `tf2_msgs/TFMessage` | reliable, volatile, keep last 100 |
//! | `/tf_static` (published) | `tf2_msgs/TFMessage` | reliable, transient local, keep last 1 |
//! | `/robot_description` (published, URDF only) | `std_msgs/String` | reliable, transient local, keep last 1 |
//! | `/cmd_vel` (taken) | `geometry_msgs/Twist` | best effort (takes from either) |
//! | `/position_controller/commands`, `/velocity_controller/commands`, `/effort_controller/commands` (taken) | `std_msgs/Float64MultiArray` | best effort |
//! | `/joint_commands` (taken) | `sensor_msgs/JointState` | best effort |
//! | `/ars/get_simulator_features`, `/ars/step_simulation`, `/ars/reset_simulation`, `/ars/set_simulation_state`, `/ars/get_simulation_state` | `simulation_interfaces/srv/...` | reliable |
//!
//! State is published every `1 / rate` simulated seconds and after every
//! `StepSimulation` call, stamped with simulated time. The forward command controllers
//! each take one value per joint of `/joint_states`, in its order; `/joint_commands`
//! takes named joints. Frames: see [`frames`].
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
pub mod frames;
mod node;
pub mod sim_interfaces;
pub mod wire;

#[cfg(test)]
mod tests;

use ars_core::Simulation;

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
    /// State publications per simulated second.
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
    /// The robot's URDF text, for `/robot_description`.
    pub robot_description: Option<String>,
}

impl Default for BridgeOptions {
    fn default() -> Self {
        BridgeOptions {
            domain_id: 0,
            lock_step: false,
            rate: 100.0,
            node_name: "ars".into(),
            services: ServiceRmw::default(),
            drive: None,
            wheel_torque: 30.0,
            gains: CommandGains::default(),
            duration: None,
            robot_description: None,
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
    /// Ctrl-C, in the middle of a `StepSimulation` (an end, not a failure, for [`run`]).
    #[error("interrupted (Ctrl-C)")]
    Interrupted,
}

/// Checks the options, finds the drive and makes the core (no network yet).
pub fn prepare(sim: Simulation, options: &BridgeOptions) -> Result<BridgeCore, BridgeError> {
    if options.domain_id > 232 {
        return Err(BridgeError::Setup(format!("domain ID {}: ROS 2 domains are 0 to 232", options.domain_id)));
    }
    if !(options.rate.is_finite() && options.rate > 0.0) {
        return Err(BridgeError::Setup(format!("rate {}: must be a positive number per second", options.rate)));
    }
    if options.duration.is_some_and(|d| !(d.is_finite() && d >= 0.0)) {
        return Err(BridgeError::Setup(format!("duration {:?}: must be a number of seconds ≥ 0", options.duration)));
    }
    let names = options.drive.as_ref().map(|(l, r)| (l.as_str(), r.as_str()));
    let drive = DiffDrive::find(sim.scene(), names, options.wheel_torque).map_err(BridgeError::Setup)?;
    Ok(BridgeCore::new(sim, drive, options.gains, options.lock_step)?)
}

/// Runs `sim` as a ROS 2 node until Ctrl-C (once
/// [`stop_on_ctrl_c`](ars_core::interrupt::stop_on_ctrl_c) is set; see
/// [`interrupt::requested`](ars_core::interrupt::requested)), a `SetSimulationState` to
/// quit, or `options.duration`; gives the simulation back, as it is then.
pub fn run(sim: Simulation, options: &BridgeOptions) -> Result<Simulation, BridgeError> {
    run_prepared(prepare(sim, options)?, options)
}

/// [`run`] with a core made by [`prepare`] with the same `options`.
pub fn run_prepared(mut core: BridgeCore, options: &BridgeOptions) -> Result<Simulation, BridgeError> {
    check_network()?;
    let node = node::BridgeNode::new(options)?;
    node.publish_latched(&core, options.robot_description.as_deref())?;
    match node::run_loop(&node, &mut core, options) {
        Ok(()) | Err(BridgeError::Interrupted) => Ok(core.into_simulation()),
        Err(e) => Err(e),
    }
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
