//! # ARS: a physically accurate robotics simulator on the Open Dynamics Engine
//!
//! This crate gathers the ARS crates under one name:
//! - [`core`] (`ars-core`): the safe ODE layer and the simulation model;
//! - [`viewer`] (`ars-viewer`, default feature `viewer`): the 3D viewer;
//! - [`ros`] (`ars-ros`, default feature `ros`): ROS 2 messages and MCAP recordings;
//! - [`cli`]: the command-line options that the `ars` command and the examples share.
//!
//! The items of `ars-core` are also re-exported at the top level.
//!
//! ```
//! use ars::{BodyBuilder, GeomBuilder, MassSpec, SpaceKind, World};
//! use ars::nalgebra::{Point3, Vector3};
//!
//! let mut world = World::new();
//! let space = world.create_space(SpaceKind::Simple)?;
//! world.insert_geom(space, GeomBuilder::plane(Vector3::y(), 0.0))?;
//! let ball = world.insert_body(
//!     BodyBuilder::new().position(Point3::new(1.0, 1.0, 1.0)).mass(MassSpec::sphere_total(1.0, 0.5)),
//! )?;
//! world.insert_geom(space, GeomBuilder::sphere(0.5).attached_to(ball))?;
//! world.collide(space)?;
//! world.step(0.0004)?;
//! world.clear_contacts();
//! # Ok::<(), ars::Error>(())
//! ```

pub mod cli;

pub use ars_core as core;
pub use ars_core::*;

/// The 3D viewer (`ars-viewer`).
#[cfg(feature = "viewer")]
pub use ars_viewer as viewer;

/// ROS 2 messages and MCAP recordings (`ars-ros`).
#[cfg(feature = "ros")]
pub use ars_ros as ros;
