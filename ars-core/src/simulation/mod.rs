//! The [`Simulation`]: a [`Scene`] (named objects and joints on a [`World`], floors,
//! the clock) with its sensors and [`hooks`], and the step loop of the original ARS.
//! The step borrows the three apart: sensors read the scene, hooks get the whole
//! simulation.
//!
//! ## The step
//! One [`Simulation::step`] of `time_step` seconds does, in this order:
//! 1. pre-step [`Hooks`] (the program's, the actions of held keys, then those added
//!    with [`Simulation::add_hooks`] in the order added), with [`Scene::time`] at
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

pub mod hooks;
pub mod scene_state;
mod sensor_kinds;
pub mod snapshot;

use nalgebra::Vector3;

use crate::contact::ContactSurface;
use crate::error::{Error, Result};
use crate::handle::{JointId, ObjectId};
use crate::limits;
use crate::scene::Scene;
use crate::sensors::{Sensor, SensorId, SensorLog, SensorSet};
use crate::world::{CollideStepError, DEFAULT_CFM, DEFAULT_ERP, DEFAULT_GRAVITY, SpaceKind, Stepper, World};
use hooks::{HookPoint, HookSet, Hooks};

/// The ARS default time step: 0.4 ms (the original's 1 / (50 frames/s × 50 steps/frame)).
pub const DEFAULT_TIME_STEP: f64 = 0.0004;
/// The ARS default number of steps per frame.
pub const DEFAULT_STEPS_PER_FRAME: u32 = 50;
/// The broad-phase space of a new [`Simulation`]: ARS's grid ([`SpaceKind::Grid`]),
/// whose cost grows linearly with the geoms (the original's simple space tests every
/// pair; ODE's sweep and prune grows as n·√n on a scene spread over the ground). [`Program`](crate::Program)s start from
/// [`SpaceKind::Simple`], the original's, so that they step bit for bit as it did.
pub const DEFAULT_SPACE: SpaceKind = SpaceKind::Grid;

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

/// Parameters of a new [`Simulation`]; the defaults are the original ARS', except the
/// broad-phase space ([`DEFAULT_SPACE`], the grid, where the original tested
/// every pair: `.space(SpaceKind::Simple)` gives the original's).
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
            space: DEFAULT_SPACE,
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
    /// The broad-phase space (default [`DEFAULT_SPACE`], the grid;
    /// [`SpaceKind::Simple`] is the original's, and steps bit for bit as it).
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
        let time_step = limits::TimeStep::new(self.time_step)?;
        if self.steps_per_frame == 0 {
            return Err(Error::OutOfRange { what: "steps per frame", detail: "must be at least 1, got 0".into() });
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
            scene: Scene::new(world, (space, self.space), time_step, self.steps_per_frame),
            sensors: SensorSet::new(id),
            hooks: HookSet::new(id),
        };
        if let Floor::Plane { normal, distance } = self.floor {
            sim.scene_mut().add_floor_plane(normal, distance)?;
        }
        Ok(sim)
    }
}

/// A simulation: a [`Scene`] (a [`World`] with named objects and joints), sensors,
/// hooks, and the step loop of the original ARS (see the [module docs](self)).
///
/// What involves the step, the sensors or the hooks is a method of the simulation;
/// the objects, joints and clock are the scene's, reached through
/// [`scene`](Self::scene) and [`scene_mut`](Self::scene_mut).
///
/// ```
/// use ars_core::{Mass, Simulation};
///
/// let mut sim = Simulation::builder().floor_plane(nalgebra::Vector3::y(), 0.0).build()?;
/// let ball = sim.scene_mut().add_sphere(0.5, [1.0, 1.0, 1.0], Mass::Total(1.0))?;
/// sim.run_for(1.0)?;
/// assert!((sim.scene().body(ball)?.position().y - 0.5).abs() < 1e-3);
/// assert_eq!(sim.scene().object(ball).map(|o| o.name())?, "sphere");
/// # Ok::<(), ars_core::Error>(())
/// ```
pub struct Simulation {
    pub(crate) scene: Scene,
    pub(crate) sensors: SensorSet,
    pub(crate) hooks: HookSet,
}

impl std::fmt::Debug for Simulation {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Simulation")
            .field("scene", &self.scene)
            .field("sensors", &self.sensors.len())
            .field("hooks", &self.hooks.len())
            .finish()
    }
}

impl Simulation {
    /// A simulation with the ARS defaults, no floor, and the default broad-phase
    /// space ([`DEFAULT_SPACE`]).
    pub fn new() -> Result<Simulation> {
        SimulationBuilder::default().build()
    }

    /// A builder for the simulation parameters.
    pub fn builder() -> SimulationBuilder {
        SimulationBuilder::default()
    }

    /// The scene: objects, joints, world and clock.
    pub fn scene(&self) -> &Scene {
        &self.scene
    }

    /// The scene, mutably.
    pub fn scene_mut(&mut self) -> &mut Scene {
        &mut self.scene
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
    #[inline]
    pub fn step(&mut self) -> Result<()> {
        self.step_driven(None::<&mut ()>)
    }

    /// `n` steps (no frame hooks).
    pub fn step_n(&mut self, n: u64) -> Result<()> {
        self.step_n_until(n, || false)
    }

    /// `n` steps, asking `stop` before each one: when it says yes, the steps end there
    /// with [`Error::Interrupted`] (an interpreter's Ctrl-C check, a wall-clock
    /// budget...).
    pub fn step_n_until(&mut self, n: u64, mut stop: impl FnMut() -> bool) -> Result<()> {
        for _ in 0..n {
            if stop() {
                return Err(self.interrupted());
            }
            self.step()?;
        }
        Ok(())
    }

    /// The error of a run stopped now.
    fn interrupted(&self) -> Error {
        Error::Interrupted { time: self.scene.time(), steps: self.scene.step_count() }
    }

    /// One frame: pre-frame hooks, `steps_per_frame` steps, post-frame hooks.
    pub fn step_frame(&mut self) -> Result<()> {
        let steps = self.scene.steps_per_frame();
        self.frame_driven(None::<&mut ()>, steps)
    }

    /// As [`step_frame`](Self::step_frame), showing the simulation to `after_step`
    /// after each step: a video recorder takes its pictures at the steps it wants (an
    /// error from it ends the frame there).
    pub fn step_frame_observed(&mut self, after_step: &mut dyn FnMut(&Simulation) -> Result<()>) -> Result<()> {
        let steps = self.scene.steps_per_frame();
        self.frame_observed(None::<&mut ()>, steps, after_step)
    }

    /// Runs for `duration` seconds of simulated time (rounded to whole steps), in
    /// frames of `steps_per_frame` steps (the last frame may be shorter). A stop
    /// requested through [`interrupt`](crate::interrupt) (Ctrl-C) ends it between two
    /// frames with [`Error::Interrupted`].
    pub fn run_for(&mut self, duration: f64) -> Result<()> {
        self.run_for_until(duration, crate::interrupt::requested)
    }

    /// As [`run_for`](Self::run_for), asking `stop` (instead of the Ctrl-C request)
    /// before each frame: when it says yes, the run ends there with
    /// [`Error::Interrupted`].
    pub fn run_for_until(&mut self, duration: f64, mut stop: impl FnMut() -> bool) -> Result<()> {
        let steps = self.scene.steps_in(duration)?;
        self.run_driven(None::<&mut ()>, steps, &mut stop)
    }

    /// One step driven by `program` (a [`Program`](crate::Program) with its held keys),
    /// whose hooks run before the added ones.
    #[inline]
    pub(crate) fn step_driven<H: Hooks + ?Sized>(&mut self, mut program: Option<&mut H>) -> Result<()> {
        if let Some(program) = program.as_deref_mut() {
            HookPoint::PreStep.run(program, self, &"the program")?;
        }
        self.run_added_hooks(HookPoint::PreStep)?;
        self.scene.apply_joint_drives()?;
        self.sensors.before_step(&self.scene)?;
        let scene = &mut self.scene;
        let time_before = scene.world().time();
        // The contact joints are destroyed once the world has stepped.
        if let Err(failed) = scene.collide_and_step() {
            return Err(failed_step(scene, *failed, time_before));
        }
        advance_clock(scene, time_before);
        if self.sensors.sample_after_step() {
            let sampled = self.sensors.after_step(&self.scene);
            self.scene.end_joint_step();
            sampled?;
        } else {
            self.scene.end_joint_step();
        }
        if let Some(program) = program {
            HookPoint::PostStep.run(program, self, &"the program")?;
        }
        self.run_added_hooks(HookPoint::PostStep)
    }

    /// A frame of `steps` steps driven by `program`.
    pub(crate) fn frame_driven<H: Hooks + ?Sized>(&mut self, program: Option<&mut H>, steps: u32) -> Result<()> {
        self.frame_observed(program, steps, &mut |_| Ok(()))
    }

    /// A frame of `steps` steps driven by `program`, showing the simulation to
    /// `after_step` after each step (once the step's hooks have run).
    /// Generic in `after_step`, so that a plain frame's does nothing at no cost.
    pub(crate) fn frame_observed<H: Hooks + ?Sized, F: FnMut(&Simulation) -> Result<()> + ?Sized>(
        &mut self,
        mut program: Option<&mut H>,
        steps: u32,
        after_step: &mut F,
    ) -> Result<()> {
        self.scene.frame_count += 1;
        if let Some(program) = program.as_deref_mut() {
            HookPoint::PreFrame.run(program, self, &"the program")?;
        }
        self.run_added_hooks(HookPoint::PreFrame)?;
        for _ in 0..steps {
            self.step_driven(program.as_deref_mut())?;
            after_step(self)?;
        }
        if let Some(program) = program {
            HookPoint::PostFrame.run(program, self, &"the program")?;
        }
        self.run_added_hooks(HookPoint::PostFrame)
    }

    /// `steps` steps in frames of `steps_per_frame` (the last may be shorter), driven by
    /// `program`, asking `stop` before each frame.
    pub(crate) fn run_driven<H: Hooks + ?Sized>(
        &mut self,
        mut program: Option<&mut H>,
        mut steps: u64,
        stop: &mut dyn FnMut() -> bool,
    ) -> Result<()> {
        let per_frame = u64::from(self.scene.steps_per_frame());
        while steps > 0 {
            if stop() {
                return Err(self.interrupted());
            }
            let n = steps.min(per_frame);
            self.frame_driven(program.as_deref_mut(), n as u32)?;
            steps -= n;
        }
        Ok(())
    }

    /// Removes an object with its body and geom; joints attached to it are removed too,
    /// and sensors reading it stop.
    pub fn remove_object(&mut self, id: ObjectId) -> Result<()> {
        self.scene.world().check_usable()?;
        self.scene.object(id)?;
        for joint in self.scene.joints_of_object(id) {
            // A joint of a group went with an earlier one of its group.
            if self.scene.joint(joint).is_ok() {
                self.remove_joint(joint)?;
            }
        }
        self.sensors.forget_object(id);
        self.scene.remove_object(id)
    }

    /// Removes a joint; sensors reading it stop. A joint of a group (see
    /// [`Scene::add_joint_group`]) is removed with its whole group.
    pub fn remove_joint(&mut self, id: JointId) -> Result<()> {
        self.scene.world().check_usable()?;
        for joint in self.scene.joints_removed_with(id)? {
            self.sensors.forget_joint(joint);
        }
        self.scene.remove_joint(id)
    }

    /// Adds a sensor that samples after every step (or at the start, if it says so:
    /// see [`Sensor::sample_at`]).
    pub fn add_sensor<S: Sensor>(&mut self, sensor: S) -> Result<SensorId<S>> {
        self.sensors.insert(&mut self.scene, sensor, None)
    }

    /// Adds a sensor that samples every `period` seconds of simulated time (at the
    /// first step ending at or after each multiple of the period).
    pub fn add_sensor_every<S: Sensor>(&mut self, sensor: S, period: f64) -> Result<SensorId<S>> {
        crate::validate::positive("sensor period", period)?;
        self.sensors.insert(&mut self.scene, sensor, Some(period))
    }

    /// Removes a sensor and hands back its samples.
    pub fn remove_sensor<S: Sensor>(&mut self, id: SensorId<S>) -> Result<SensorLog<S::Record>> {
        self.sensors.remove(id)
    }

    /// The samples of a sensor.
    pub fn records<S: Sensor>(&self, id: SensorId<S>) -> Result<&SensorLog<S::Record>> {
        self.sensors.log(id)
    }

    /// How often a sensor samples, in simulated seconds (`None`: after every step);
    /// what [`add_sensor_every`](Self::add_sensor_every) was given.
    pub fn sensor_period<S: Sensor>(&self, id: SensorId<S>) -> Result<Option<f64>> {
        self.sensors.period(id)
    }

    /// Forgets the samples of a sensor so far.
    pub fn clear_records<S: Sensor>(&mut self, id: SensorId<S>) -> Result<()> {
        self.sensors.clear(id)
    }

    /// The sensor itself (its configuration).
    pub fn sensor<S: Sensor>(&self, id: SensorId<S>) -> Result<&S> {
        self.sensors.sensor(id)
    }

    /// Every sensor of type `S` (its configuration), in the order added: what a viewer
    /// shows of, say, every depth camera without holding their ids.
    ///
    /// ```
    /// use ars_core::sensors::DepthCamera;
    /// use ars_core::Simulation;
    ///
    /// let mut sim = Simulation::new()?;
    /// assert_eq!(sim.sensors_of::<DepthCamera>().count(), 0);
    /// sim.add_sensor(DepthCamera::new(64, 48, 1.0, 0.1, 10.0)?)?;
    /// assert_eq!(sim.sensors_of::<DepthCamera>().count(), 1);
    /// # Ok::<(), ars_core::Error>(())
    /// ```
    pub fn sensors_of<S: Sensor>(&self) -> impl Iterator<Item = &S> + '_ {
        self.sensors.of_type::<S>()
    }

    /// The id of every sensor of type `S`: what reads the records of, say, every lidar
    /// of a simulation without holding their ids (a ROS bridge publishing each one's
    /// scans).
    ///
    /// ```
    /// use ars_core::sensors::Lidar;
    /// use ars_core::Simulation;
    ///
    /// let mut sim = Simulation::new()?;
    /// let lidar = sim.add_sensor(Lidar::new(8, 1.0, 5.0)?)?;
    /// sim.step()?;
    /// let ids = sim.sensor_ids_of::<Lidar>();
    /// assert_eq!(ids.len(), 1);
    /// assert_eq!(sim.records(ids[0])?.len(), sim.records(lidar)?.len());
    /// # Ok::<(), ars_core::Error>(())
    /// ```
    pub fn sensor_ids_of<S: Sensor>(&self) -> Vec<SensorId<S>> {
        self.sensors.ids_of::<S>()
    }

    /// Line segments (world frame) showing the latest record of every sensor that draws
    /// (see [`Sensor::lines`]): what a viewer overlays.
    pub fn sensor_lines(&self) -> Vec<(nalgebra::Point3<f64>, nalgebra::Point3<f64>)> {
        self.sensors.lines()
    }

    /// Every sensor's records, whatever their type: the sensor's type name (`"Gps"`)
    /// and its log seen through its CSV columns, in the order the sensors were added.
    /// What a viewer plots.
    pub fn sensor_tables(&self) -> Vec<(String, &dyn crate::sensors::CsvColumns)> {
        self.sensors.tables()
    }

    /// Whether a sensor stopped sampling because an object or joint it reads was removed.
    pub fn is_sensor_detached<S: Sensor>(&self, id: SensorId<S>) -> Result<bool> {
        self.sensors.is_detached(id)
    }
}

/// The clock after a step: the scene's time advances by its time step when the
/// world's did (a failed step may not have advanced it).
#[inline(always)]
fn advance_clock(scene: &mut Scene, world_time_before: f64) {
    if scene.world().time() != world_time_before {
        scene.time += scene.time_step();
        scene.step_count += 1;
    }
}

/// The error of a step whose collision or step failed, with the scene's names: after
/// a failed collision nothing changed; after a failed step the contact joints are
/// destroyed and the clock is where the world's is.
#[cold]
fn failed_step(scene: &mut Scene, failed: CollideStepError, world_time_before: f64) -> Error {
    match failed {
        CollideStepError::Collide(e) => scene.name_handles(e),
        CollideStepError::Step(e) => {
            scene.world_mut().clear_contacts();
            advance_clock(scene, world_time_before);
            scene.name_handles(e)
        }
    }
}
