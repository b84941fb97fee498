//! # ars-ros
//!
//! ARS speaks ROS 2 without a ROS installation: [`bridge`] runs a
//! [`Simulation`](ars_core::Simulation) as a ROS 2 node (live topics and the Simulation
//! Interfaces services) over RustDDS.

pub mod bridge;
