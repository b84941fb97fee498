//! # ars-core
//!
//! The core of ARS, a robotics simulator on the Open Dynamics Engine (ODE): the
//! simulation model of the original ARS (named objects and joints, sensors, actuators,
//! programs) on a safe layer over ODE, with the original's defaults (Y up,
//! g = 9.81 m/s², ERP 0.2, CFM 1e-10, `dWorldStep`, contacts with bounce 0.2 and a
//! 500 N friction limit).
//!
//! ## Quick start: the thesis' hello world
//!
//! A program adds its objects; everything else has the original's defaults (floor
//! y = 0, 0.4 ms steps, g = 9.81 m/s²). A 1 kg ball of radius 0.5 m dropped from a
//! centre height of 1 m bounces and comes to rest on the floor:
//!
//! ```
//! use ars_core::{Hooks, Mass, Program, Result, Simulation};
//!
//! struct HelloWorld;
//! impl Hooks for HelloWorld {}
//! impl Program for HelloWorld {
//!     fn create_sim_objects(&mut self, sim: &mut Simulation) -> Result<()> {
//!         sim.scene_mut().add_sphere(0.5, [1.0, 1.0, 1.0], Mass::Total(1.0)).map(drop)
//!     }
//! }
//!
//! let sim = HelloWorld.run_headless(1.0)?;
//! let y = sim.scene().object("sphere")?.position()?.y; // named access returns a view
//! assert!((y - 0.5).abs() < 1e-3, "the ball rests on the floor, y = {y}");
//! # Ok::<(), ars_core::Error>(())
//! ```
//!
//! [`Simulation`] names every object and joint, runs hooks and [`sensors`] around each
//! step, and offers the original's joints, actuators and [`control`]lers; [`Program`]
//! adds key bindings and the run loop.
//!
//! ## The safe ODE layer
//!
//! Underneath, [`World`] owns every ODE object and hands out `Copy` handles; the same
//! ball, step by step:
//!
//! ```
//! use ars_core::{BodyBuilder, GeomBuilder, MassSpec, SpaceKind, World};
//! use nalgebra::{Point3, Vector3};
//!
//! let mut world = World::new();
//! let space = world.create_space(SpaceKind::Simple)?;
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
//! assert!((world.body(ball)?.position().y - 0.5).abs() < 1e-3);
//! # Ok::<(), ars_core::Error>(())
//! ```
//!
//! Bad input is an [`Error`], never a crash: a negative radius, a NaN position, a
//! handle of a removed body or of another world, a joint from a body to itself, a
//! number outside the documented [`limits`]... A body whose state diverges is
//! [`Error::Diverged`], and an internal error that ODE reports anyway is caught by the
//! [`guard`] ([`Error::OdeInternal`]): nothing reachable from safe code aborts.
//!
//! ```
//! use ars_core::{BodyBuilder, Error, GeomBuilder, SpaceKind, World};
//! let mut world = World::new();
//! let space = world.create_space(SpaceKind::Simple)?;
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
//! step job queue. Each world keeps its own QuickStep random seed, so QuickStep is
//! deterministic per world even when worlds run concurrently.

pub mod control;
pub mod convert;
pub mod error;
pub mod formats;
pub mod guard;
pub mod handle;
mod hull;
mod init;
pub mod interrupt;
pub mod limits;
mod mesh_mass;
mod panic;
pub mod platform;
pub mod program;
pub mod random;
pub mod scene;
pub mod sensors;
pub mod shape;
pub mod simulation;
mod validate;
pub mod world;
pub use world::{body, contact, geom, joint};

pub use body::{BodyBuilder, BodyKind, BodyMut, BodyRef, Mass, MassSpec};
pub use contact::{CollisionHooks, ContactPoint, ContactSurface, DefaultHooks, GeomPair, MAX_CONTACTS_LIMIT, RayHit};
pub use control::{
    Actuator, ActuatorKind, DcMotor, JointController, JointState, Pid, PositionServo, Profile, SavedController,
    TorqueMotor, VelocityServo,
};
pub use error::{Error, Result};
pub use formats::mjcf::{MjcfActuator, MjcfFile, MjcfKeyframe, MjcfModel, MjcfOptions, MjcfSensor};
pub use formats::open::{FileFormat, OpenedFile};
pub use formats::urdf::{UpAxis, UrdfFile, UrdfOptions, UrdfRobot};
pub use geom::{GeomBuilder, GeomMut, GeomRef};
pub use handle::{BodyHandle, GeomHandle, JointHandle, JointId, ObjectId, SpaceHandle, WorldId};
pub use init::{ensure_ode_ready, lock_ode_global_state};
pub use joint::{AxisFrame, JointBuilder, JointFeedback, JointKind, JointMut, JointParam, JointRef};
pub use program::{
    Action, ActionMap, Key, KeyEvent, KeyScript, Program, ProgramRunner, RenderQuality, Repeat, WindowSettings,
};
pub use scene::{
    ActuatorLimits, Color, GeomContact, GeomOf, GroupJoint, GroupRest, Heightfield, JointEfforts, JointEnd, JointType,
    Mimic, Scene, SimJoint, Visual, heightfield_triangles,
};
pub use sensors::{Probe, Record, Sample, SampleAt, Sensor, SensorId, SensorKind, SensorLog};
pub use shape::{CONE_SEGMENTS, Shape};
pub use simulation::hooks::{self, HookId, HookPoint, Hooks, PostFrame, PostStep, PreFrame, PreStep};
pub use simulation::scene_state::{SNAPSHOT_VERSION, SceneState};
pub use simulation::snapshot::Snapshot;
pub use simulation::{DEFAULT_SPACE, DEFAULT_STEPS_PER_FRAME, DEFAULT_TIME_STEP, Floor, Simulation, SimulationBuilder};
pub use world::{AxisOrder, DEFAULT_CFM, DEFAULT_ERP, DEFAULT_GRAVITY, SpaceKind, Stepper, World};

pub use nalgebra;
pub use scene::colors;
