//! The [`Simulation`]: named objects and joints on a [`World`], floors, sensors, hooks
//! and the step loop of the original ARS.
//!
//! ## The step
//! One [`Simulation::step`] of `time_step` seconds does, in this order:
//! 1. pre-step [`Hooks`] (the program's, the actions of held keys, then those added
//!    with [`Simulation::add_hooks`] in the order added), with [`Simulation::time`] at
//!    the start of the step;
//! 2. joint controllers and viscous joint friction (torques from the rates at the start
//!    of the step); sensors note the state before the step;
//! 3. collision on the poses before the step (`dSpaceCollide`): rays record hits, other
//!    pairs get contact joints, bodies joined by a joint do not collide;
//! 4. `dWorldStep` (or QuickStep, if chosen);
//! 5. `time += time_step` (repeated addition, as the original, so it drifts in the last
//!    digits exactly as the original's did);
//! 6. the contact joints are destroyed;
//! 7. sensors sample, then post-step hooks run, with the time at the end of the step.
//!
//! A frame ([`Simulation::step_frame`]) is pre-frame hooks, `steps_per_frame` steps,
//! post-frame hooks. Forces and torques added through the API act during the next step
//! only (ODE clears its accumulators after each step).

pub mod colors;
mod floor;
mod joints;
mod names;
mod objects;

use std::any::Any;
use std::panic::{AssertUnwindSafe, catch_unwind};

use nalgebra::Vector3;

pub use floor::{Heightfield, MAX_GRID_VERTICES, heightfield_faces};
pub use joints::{JointEfforts, JointEnd, JointType, SimJoint};
pub use objects::{CONE_SEGMENTS, Color, ObjectShape};

use crate::contact::ContactSurface;
use crate::error::{Error, Result};
use crate::handle::{Arena, JointId, ObjectId, SpaceHandle, WorldId};
use crate::hooks::{HookPoint, HookSet, Hooks};
use crate::limits;
use crate::sensors::SensorSet;
use crate::validate;
use crate::world::{DEFAULT_CFM, DEFAULT_ERP, DEFAULT_GRAVITY, SpaceKind, Stepper, World};
use joints::JointData;
use names::Names;
use objects::ObjectData;

/// The ARS default time step: 0.4 ms (the original's 1 / (50 frames/s × 50 steps/frame)).
pub const DEFAULT_TIME_STEP: f64 = 0.0004;
/// The ARS default number of steps per frame.
pub const DEFAULT_STEPS_PER_FRAME: u32 = 50;

/// The message of a caught panic.
fn panic_message(payload: Box<dyn Any + Send>) -> String {
    let message = match payload.downcast_ref::<&str>() {
        Some(s) => (*s).to_owned(),
        None => match payload.downcast_ref::<String>() {
            Some(s) => s.clone(),
            None => "(a panic without a message)".to_owned(),
        },
    };
    // Dropping a payload runs user code that may panic again: leak it instead.
    std::mem::forget(payload);
    message
}

/// Runs user code, turning a panic into [`Error::Panicked`].
pub(crate) fn contain(during: impl FnOnce() -> String, f: impl FnOnce() -> Result<()>) -> Result<()> {
    catch_unwind(AssertUnwindSafe(f))
        .unwrap_or_else(|payload| Err(Error::Panicked { during: during(), message: panic_message(payload) }))
}

/// The floor a simulation starts with.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub enum Floor {
    /// No floor.
    None,
    /// The infinite plane `normal · x = distance` (the original's default: y = 0).
    Plane {
        /// Plane normal (pointing up, out of the ground).
        normal: Vector3<f64>,
        /// Offset along the normal, m.
        distance: f64,
    },
}

/// Parameters of a new [`Simulation`]; the defaults are the original ARS'.
#[derive(Clone, Debug)]
#[must_use]
pub struct SimulationBuilder {
    gravity: Vector3<f64>,
    time_step: f64,
    steps_per_frame: u32,
    erp: f64,
    cfm: f64,
    stepper: Stepper,
    surface: ContactSurface,
    space: SpaceKind,
    floor: Floor,
    seed: Option<u32>,
}

impl Default for SimulationBuilder {
    fn default() -> Self {
        SimulationBuilder {
            gravity: DEFAULT_GRAVITY,
            time_step: DEFAULT_TIME_STEP,
            steps_per_frame: DEFAULT_STEPS_PER_FRAME,
            erp: DEFAULT_ERP,
            cfm: DEFAULT_CFM,
            stepper: Stepper::Exact,
            surface: ContactSurface::default(),
            space: SpaceKind::Simple,
            floor: Floor::None,
            seed: None,
        }
    }
}

impl SimulationBuilder {
    /// Gravity, m/s² (default (0, −9.81, 0)).
    pub fn gravity(mut self, g: Vector3<f64>) -> Self {
        self.gravity = g;
        self
    }
    /// Time step, s (default 0.4 ms).
    pub fn time_step(mut self, dt: f64) -> Self {
        self.time_step = dt;
        self
    }
    /// Steps per frame (default 50).
    pub fn steps_per_frame(mut self, n: u32) -> Self {
        self.steps_per_frame = n;
        self
    }
    /// Global ERP (default 0.2).
    pub fn erp(mut self, erp: f64) -> Self {
        self.erp = erp;
        self
    }
    /// Global CFM (default 1e-10).
    pub fn cfm(mut self, cfm: f64) -> Self {
        self.cfm = cfm;
        self
    }
    /// The stepper (default `dWorldStep`).
    pub fn stepper(mut self, stepper: Stepper) -> Self {
        self.stepper = stepper;
        self
    }
    /// The contact surface of every pair (default bounce 0.2, mu 500, 150 contacts).
    pub fn contact_surface(mut self, surface: ContactSurface) -> Self {
        self.surface = surface;
        self
    }
    /// Restitution coefficient of the default surface (and its velocity threshold).
    pub fn bounce(mut self, bounce: f64, bounce_velocity: f64) -> Self {
        self.surface.bounce = Some((bounce, bounce_velocity));
        self
    }
    /// Friction limit of the default surface.
    pub fn mu(mut self, mu: f64) -> Self {
        self.surface.mu = mu;
        self
    }
    /// The broad-phase space (default simple, as the original).
    pub fn space(mut self, kind: SpaceKind) -> Self {
        self.space = kind;
        self
    }
    /// The starting floor (default none; [`Program`](crate::Program)s get the plane y = 0).
    pub fn floor(mut self, floor: Floor) -> Self {
        self.floor = floor;
        self
    }
    /// The plane floor `normal · x = distance`.
    pub fn floor_plane(self, normal: Vector3<f64>, distance: f64) -> Self {
        self.floor(Floor::Plane { normal, distance })
    }
    /// Seeds the random generator of QuickStep for this simulation (see
    /// [`World::set_random_seed`]: each world keeps its own seed).
    pub fn seed(mut self, seed: u32) -> Self {
        self.seed = Some(seed);
        self
    }

    /// Creates the simulation: world, contact group, space, then the floor.
    pub fn build(self) -> Result<Simulation> {
        limits::time_step(self.time_step)?;
        if self.steps_per_frame == 0 {
            return Err(Error::OutOfRange { what: "steps per frame", detail: "must be at least 1".into() });
        }
        self.surface.validate()?;
        let mut world = World::new();
        world.set_gravity(self.gravity)?;
        world.set_erp(self.erp)?;
        world.set_cfm(self.cfm)?;
        world.set_stepper(self.stepper)?;
        world.set_default_surface(self.surface)?;
        if let Some(seed) = self.seed {
            world.set_random_seed(seed);
        }
        let space = world.create_space(self.space)?;
        let id = world.id();
        let mut sim = Simulation {
            world,
            space,
            objects: Arena::new(id),
            object_names: Names::new("object"),
            joints: Arena::new(id),
            joint_names: Names::new("joint"),
            driven_joints: Vec::new(),
            sensors: SensorSet::new(id),
            hooks: HookSet::new(id),
            time: 0.0,
            step_count: 0,
            frame_count: 0,
            time_step: self.time_step,
            steps_per_frame: self.steps_per_frame,
        };
        if let Floor::Plane { normal, distance } = self.floor {
            sim.add_floor_plane(normal, distance)?;
        }
        Ok(sim)
    }
}

/// A simulation: a [`World`] with named objects and joints, sensors, hooks, and the
/// step loop of the original ARS (see the [module docs](self)).
///
/// ```
/// use ars_core::{Mass, Simulation};
///
/// let mut sim = Simulation::builder().floor_plane(nalgebra::Vector3::y(), 0.0).build()?;
/// let ball = sim.add_sphere(0.5, [1.0, 1.0, 1.0], Mass::Total(1.0))?;
/// sim.run_for(1.0)?;
/// assert!((sim.body(ball)?.position().y - 0.5).abs() < 1e-3);
/// assert_eq!(sim.name(ball)?, "sphere");
/// # Ok::<(), ars_core::Error>(())
/// ```
pub struct Simulation {
    world: World,
    space: SpaceHandle,
    objects: Arena<ObjectData>,
    object_names: Names<ObjectId>,
    joints: Arena<JointData>,
    joint_names: Names<JointId>,
    /// Joints with viscous friction or a controller, in creation order.
    driven_joints: Vec<JointId>,
    pub(crate) sensors: SensorSet,
    pub(crate) hooks: HookSet,
    time: f64,
    step_count: u64,
    frame_count: u64,
    time_step: f64,
    steps_per_frame: u32,
}

impl std::fmt::Debug for Simulation {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Simulation")
            .field("time", &self.time)
            .field("steps", &self.step_count)
            .field("objects", &self.objects.len())
            .field("joints", &self.joints.len())
            .finish()
    }
}

impl Simulation {
    /// A simulation with the ARS defaults and no floor.
    pub fn new() -> Result<Simulation> {
        SimulationBuilder::default().build()
    }

    /// A builder for the simulation parameters.
    pub fn builder() -> SimulationBuilder {
        SimulationBuilder::default()
    }

    /// The underlying world (for everything the simulation layer does not wrap).
    pub fn world(&self) -> &World {
        &self.world
    }

    /// The underlying world, mutably. Objects and joints created directly in it are
    /// not named or tracked by the simulation.
    pub fn world_mut(&mut self) -> &mut World {
        &mut self.world
    }

    /// The collision space of the simulation.
    pub fn space(&self) -> SpaceHandle {
        self.space
    }

    /// Id of the world (and of every handle of this simulation).
    pub fn world_id(&self) -> WorldId {
        self.world.id()
    }

    /// Simulated time, s: the sum of the time steps taken so far.
    pub fn time(&self) -> f64 {
        self.time
    }

    /// Time step, s.
    pub fn time_step(&self) -> f64 {
        self.time_step
    }

    /// Changes the time step for the next steps.
    pub fn set_time_step(&mut self, dt: f64) -> Result<()> {
        self.time_step = limits::time_step(dt)?;
        Ok(())
    }

    /// Steps per frame.
    pub fn steps_per_frame(&self) -> u32 {
        self.steps_per_frame
    }

    /// Steps taken so far.
    pub fn step_count(&self) -> u64 {
        self.step_count
    }

    /// Frames started so far.
    pub fn frame_count(&self) -> u64 {
        self.frame_count
    }

    /// Gravity, m/s².
    pub fn gravity(&self) -> Vector3<f64> {
        self.world.gravity()
    }

    /// One step (see the [module docs](self)).
    ///
    /// Errors end the step where they happen; nothing registered is lost:
    /// - a hook or sensor that panics is reported as [`Error::Panicked`] (hooks after it
    ///   at the same point do not run for this step; other sensors still sample);
    /// - a body whose state cannot be integrated is [`Error::Diverged`], named: before
    ///   the step nothing happened; after it, time has advanced but the sensors did not
    ///   sample the diverged state. Steps are refused until the body is reset or
    ///   removed; the records so far stay readable.
    pub fn step(&mut self) -> Result<()> {
        self.step_driven(&mut ())
    }

    /// `n` steps (no frame hooks).
    pub fn step_n(&mut self, n: u64) -> Result<()> {
        (0..n).try_for_each(|_| self.step())
    }

    /// One frame: pre-frame hooks, `steps_per_frame` steps, post-frame hooks.
    pub fn step_frame(&mut self) -> Result<()> {
        let steps = self.steps_per_frame;
        self.frame_driven(&mut (), steps)
    }

    /// Runs for `duration` seconds of simulated time (rounded to whole steps), in
    /// frames of `steps_per_frame` steps (the last frame may be shorter).
    pub fn run_for(&mut self, duration: f64) -> Result<()> {
        let steps = self.steps_in(duration)?;
        self.run_driven(&mut (), steps)
    }

    /// Number of whole steps in `duration` seconds (rounded to the nearest).
    pub fn steps_in(&self, duration: f64) -> Result<u64> {
        validate::non_negative("duration", duration)?;
        Ok((duration / self.time_step).round() as u64)
    }

    /// One step driven by `program` (a [`Program`](crate::Program) with its held keys),
    /// whose hooks run before the added ones.
    pub(crate) fn step_driven<H: Hooks + ?Sized>(&mut self, program: &mut H) -> Result<()> {
        HookPoint::PreStep.run(program, self, &"the program")?;
        self.run_added_hooks(HookPoint::PreStep)?;
        self.apply_joint_drives()?;
        let mut sensors = std::mem::replace(&mut self.sensors, SensorSet::new(self.world.id()));
        let before = sensors.before_step(self);
        self.sensors = sensors;
        before?;
        self.world.collide(self.space)?;
        let time_before = self.world.time();
        let stepped = self.world.step(self.time_step);
        self.world.clear_contacts();
        if self.world.time() != time_before {
            self.time += self.time_step;
            self.step_count += 1;
        }
        stepped.map_err(|e| self.name_diverged_body(e))?;
        let mut sensors = std::mem::replace(&mut self.sensors, SensorSet::new(self.world.id()));
        let sampled = sensors.after_step(self);
        self.sensors = sensors;
        self.end_joint_step();
        sampled?;
        HookPoint::PostStep.run(program, self, &"the program")?;
        self.run_added_hooks(HookPoint::PostStep)
    }

    /// A frame of `steps` steps driven by `program`.
    pub(crate) fn frame_driven<H: Hooks + ?Sized>(&mut self, program: &mut H, steps: u32) -> Result<()> {
        self.frame_count += 1;
        HookPoint::PreFrame.run(program, self, &"the program")?;
        self.run_added_hooks(HookPoint::PreFrame)?;
        for _ in 0..steps {
            self.step_driven(program)?;
        }
        HookPoint::PostFrame.run(program, self, &"the program")?;
        self.run_added_hooks(HookPoint::PostFrame)
    }

    /// `steps` steps in frames of `steps_per_frame` (the last may be shorter), driven by `program`.
    pub(crate) fn run_driven<H: Hooks + ?Sized>(&mut self, program: &mut H, mut steps: u64) -> Result<()> {
        while steps > 0 {
            let n = steps.min(u64::from(self.steps_per_frame));
            self.frame_driven(program, n as u32)?;
            steps -= n;
        }
        Ok(())
    }

    /// Puts the object's name in a [`Error::Diverged`] from the world.
    fn name_diverged_body(&self, error: Error) -> Error {
        match (error, self.world.diverged_body()) {
            (Error::Diverged { body, time, detail }, Some(handle)) => {
                let name = self
                    .objects
                    .iter()
                    .find(|(_, o)| o.body == Some(handle))
                    .and_then(|(id, _)| self.name(ObjectId(id)).ok());
                let body = match name {
                    Some(name) => format!("{name:?} ({body})"),
                    None => body,
                };
                Error::Diverged { body, time, detail }
            }
            (error, _) => error,
        }
    }
}
