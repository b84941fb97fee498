//! ARS speaks ROS 2: the standard messages a simulation turns into ([`msg`]), what a
//! simulation publishes at a time ([`publish`]: topics, types, QoS, frames), and MCAP
//! recordings of them ([`mcap`]), which Foxglove, `ros2 bag` and Rerun open; and
//! [`bridge`], which runs a [`Simulation`](ars_core::Simulation) as a live ROS 2 node
//! (topics and the Simulation Interfaces services) over RustDDS. No ROS installation
//! is needed: messages are CDR-encoded here.
//!
//! ARS's world is Y-up; ROS's is Z-up (REP 103). See [`frames`] for how poses are
//! turned.

pub mod bridge;
pub mod camera;
pub mod error;
pub mod frames;
pub mod joint_states;
pub mod mcap;
pub mod msg;
pub mod publish;
pub mod tf_tree;
pub mod topics;

pub use error::{RosError, RosResult};
pub use joint_states::{JointStates, JointStatesReading};
pub use mcap::{FrameStepper, McapRecorder, McapSummary, record_mcap};
pub use publish::{Publisher, RosOptions};
pub use topics::{Durability, Message, Outgoing, Qos, Reliability, Topic};
