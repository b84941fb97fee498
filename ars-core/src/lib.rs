//! # ars-core
//!
//! The safe core of ARS, a robotics simulator on the Open Dynamics Engine (ODE):
//! a [`World`] that owns every ODE object (bodies, geoms, joints, spaces, contacts) and
//! hands out small `Copy` handles, with ODE's semantics and ARS' defaults (Y up,
//! g = 9.81 m/s², ERP 0.2, CFM 1e-10, `dWorldStep`, contacts with bounce 0.2 and a
//! 500 N friction limit).
//!
//! ## Quick start: the thesis' falling ball
//!
//! A 1 kg ball of radius 0.5 m dropped from a centre height of 1 m onto the plane
//! y = 0, stepped at 0.4 ms for one second, comes to rest on the floor:
//!
//! ```
//! use ars_core::{BodyBuilder, GeomBuilder, MassSpec, SpaceKind, World};
//! use nalgebra::{Point3, Vector3};
//!
//! let mut world = World::new();
//! let space = world.create_space(SpaceKind::Simple);
//! world.insert_geom(space, GeomBuilder::plane(Vector3::y(), 0.0))?;
//! let ball = world.insert_body(
//!     BodyBuilder::new().position(Point3::new(1.0, 1.0, 1.0)).mass(MassSpec::sphere_total(1.0, 0.5)),
//! )?;
//! world.insert_geom(space, GeomBuilder::sphere(0.5).attached_to(ball))?;
//!
//! for _ in 0..2500 {
//!     world.collide(space)?; // contacts on the poses before the step
//!     world.step(0.0004)?; // dWorldStep
//!     world.clear_contacts();
//! }
//! let y = world.body(ball)?.position().y;
//! assert!((y - 0.5).abs() < 1e-3, "the ball rests on the floor, y = {y}");
//! # Ok::<(), ars_core::Error>(())
//! ```
//!
//! Bad input is an [`Error`], never a crash: a negative radius, a NaN position, a
//! handle of a removed body or of another world, a joint from a body to itself...
//!
//! ```
//! use ars_core::{BodyBuilder, Error, GeomBuilder, SpaceKind, World};
//! let mut world = World::new();
//! let space = world.create_space(SpaceKind::Simple);
//! let err = world.insert_geom(space, GeomBuilder::sphere(-1.0)).unwrap_err();
//! assert!(matches!(err, Error::NotPositive { what: "sphere radius", .. }));
//! let body = world.insert_body(BodyBuilder::new())?;
//! world.remove_body(body)?;
//! assert!(matches!(world.body(body), Err(Error::StaleHandle { .. })));
//! # Ok::<(), ars_core::Error>(())
//! ```
//!
//! ## Threads
//! A [`World`] is `Send`: several worlds may run on different threads. The Debian build
//! of ODE keeps some state per process (the trimesh collider cache, the random
//! generator), so trimesh collision and QuickStep are serialised by a process-wide lock
//! ([`lock_ode_global_state`]); `dWorldStep` runs in parallel, each world with its own
//! step job queue.

pub mod body;
pub mod contact;
pub mod control;
pub mod convert;
pub mod error;
pub mod geom;
pub mod handle;
mod init;
pub mod joint;
pub mod program;
pub mod sensors;
pub mod simulation;
mod validate;
pub mod world;

pub use body::{BodyBuilder, BodyKind, BodyMut, BodyRef, Mass, MassSpec};
pub use contact::{CollisionHooks, ContactPoint, ContactSurface, DefaultHooks, GeomPair, MAX_CONTACTS_LIMIT, RayHit};
pub use control::{DcMotor, JointController, JointState, Pid, PositionServo, Profile, TorqueMotor, VelocityServo};
pub use error::{Error, Result};
pub use geom::{GeomBuilder, GeomMut, GeomRef, Shape};
pub use handle::{BodyHandle, GeomHandle, JointHandle, JointId, ObjectId, SpaceHandle, WorldId};
pub use init::{ensure_ode_ready, lock_ode_global_state};
pub use joint::{AxisFrame, JointBuilder, JointFeedback, JointKind, JointMut, JointParam, JointRef};
pub use program::{Action, ActionMap, Key, Program, ProgramRunner, Repeat};
pub use sensors::{Record, Sample, Sensor, SensorId, SensorLog};
pub use simulation::{
    CONE_SEGMENTS, Color, DEFAULT_STEPS_PER_FRAME, DEFAULT_TIME_STEP, Floor, Heightfield, Hook, JointEnd, JointType,
    NoHooks, ObjectShape, SimJoint, Simulation, SimulationBuilder, StepHooks, heightfield_faces,
};
pub use world::{DEFAULT_CFM, DEFAULT_ERP, DEFAULT_GRAVITY, SpaceKind, Stepper, World};

pub use nalgebra;
