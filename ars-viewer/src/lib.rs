//! The ARS 3D viewer.
//!
//! Not built yet: the on-screen window and off-screen screenshot recorder arrive with
//! the viewer issue. The crate exists so that the workspace layout and the `viewer`
//! feature of the root `ars` crate are already in place.

pub use ars_core;
