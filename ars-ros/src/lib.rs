//! ARS speaks ROS 2: the standard messages a simulation turns into ([`msg`]), what a
//! simulation publishes at a time ([`topics`]), and MCAP recordings of them
//! ([`mcap`]), which Foxglove, `ros2 bag` and Rerun open. No ROS installation is
//! needed: messages are CDR-encoded here.
//!
//! ARS's world is Y-up; ROS's is Z-up (REP 103). See [`frames`] for how poses are
//! turned.

pub mod error;
pub mod msg;

pub use error::{RosError, RosResult};
