//! The [`World`]: the one owner of every ODE object of a simulation.

use std::fmt;

use nalgebra::Vector3;
use ode_sys as ffi;

pub mod body;
pub mod contact;
pub mod geom;
mod grid;
pub mod joint;
pub(crate) mod mesh_tree;
pub mod raycast;
pub(crate) mod state;

use body::BodyData;
use contact::{CollisionState, ConvexSizes};
use geom::GeomData;

use crate::convert;
use crate::error::{Error, Result};
use crate::guard;
use crate::handle::{Arena, BodyHandle, RawHandle, SpaceHandle, WorldId};
use crate::init::{ensure_ode_ready, lock_ode_global_state};
use crate::limits;
use crate::validate;
use joint::JointData;

/// The ARS default gravity: 9.81 m/s² down the Y axis (Y is up).
pub const DEFAULT_GRAVITY: Vector3<f64> = Vector3::new(0.0, -9.81, 0.0);
/// The ARS (and ODE double-precision) default global error reduction parameter.
pub const DEFAULT_ERP: f64 = 0.2;
/// The ARS (and ODE double-precision) default global constraint force mixing.
pub const DEFAULT_CFM: f64 = 1e-10;

/// A broad-phase collision space: how ODE finds the pairs of geoms whose bounding
/// boxes overlap before it calls their colliders.
///
/// The kinds find the same pairs (up to the sweep and prune's rounding, below); they
/// differ in cost and in the order they report them, and that order is the order of the contact joints, so the same scene steps
/// to different last bits in different spaces. Programs that must reproduce the
/// original ARS bit for bit use [`SpaceKind::Simple`].
///
/// ODE's quadtree space is not offered: it is built for Z up (it splits X and Y,
/// while ARS's ground is the X–Z plane), needs the scene's extent in advance, and
/// cannot list its geoms (`dSpaceGetGeom` is not implemented for it).
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[non_exhaustive]
pub enum SpaceKind {
    /// Tests every pair of geoms (O(n²)); what the original ARS used.
    Simple,
    /// A multi-resolution hash table; the cell sizes are powers of two between
    /// `2^min_level` and `2^max_level` metres. Coordinates are limited to what its
    /// integer cells hold (checked when it collides; see [`World::collide`]).
    Hash {
        /// Smallest cell size exponent (ODE's default is -3).
        min_level: i32,
        /// Largest cell size exponent (ODE's default is 10).
        max_level: i32,
    },
    /// Sweep and prune (`dSweepAndPruneSpaceCreate`): every collision sorts the
    /// geoms' bounding boxes along the first axis of `axes` (a radix sort, linear in
    /// the geoms) and tests the boxes that overlap along it on the other two axes.
    /// Geoms with an infinite extent along the first axis (planes) are tested against
    /// all the others. The sort is on single-precision (`f32`) coordinates: a pair
    /// whose boxes overlap along the first axis by less than about 6e-8 of their
    /// coordinate (60 µm at 1 km from the origin) may be found a step late.
    SweepAndPrune {
        /// The axis to sort on first, then the other two in the order tested.
        axes: AxisOrder,
    },
    /// ARS's own broad phase, in Rust: a uniform grid whose cell is twice the median
    /// geom's size, rebuilt at every collision over the geoms of a simple ODE space.
    /// Linear in the number of geoms however they are spread (10,000 to 100,000
    /// spaced spheres: see the README's "Scale"); geoms much larger than a cell and
    /// planes are tested against all the others. Pairs come in the order the geoms
    /// were created, under ODE's own rules (enabled geoms, not on one body, category
    /// and collide bits that match).
    Grid,
}

impl SpaceKind {
    /// A hash space with ODE's default levels (cells from 1/8 m to 1024 m).
    pub const HASH: SpaceKind = SpaceKind::Hash { min_level: -3, max_level: 10 };
    /// Sweep and prune sorting along X, then Z, then Y: Y is up, so scenes spread
    /// over the ground are sorted along a horizontal axis. The default space of a new
    /// [`Simulation`](crate::Simulation).
    pub const SWEEP_AND_PRUNE: SpaceKind = SpaceKind::SweepAndPrune { axes: AxisOrder::Xzy };
}

/// The order of the axes of a [`SpaceKind::SweepAndPrune`] space: the first is the
/// one it sorts along (best the one along which the scene spreads most), the other
/// two are tested in this order.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, serde::Serialize, serde::Deserialize)]
pub enum AxisOrder {
    /// X, Y, Z.
    Xyz,
    /// X, Z, Y (ODE's advice, and ARS's default: Y is up).
    Xzy,
    /// Y, X, Z.
    Yxz,
    /// Y, Z, X.
    Yzx,
    /// Z, X, Y.
    Zxy,
    /// Z, Y, X.
    Zyx,
}

impl AxisOrder {
    /// The three axes (0 = X, 1 = Y, 2 = Z), first to last.
    pub const fn axes(self) -> [u8; 3] {
        match self {
            AxisOrder::Xyz => [0, 1, 2],
            AxisOrder::Xzy => [0, 2, 1],
            AxisOrder::Yxz => [1, 0, 2],
            AxisOrder::Yzx => [1, 2, 0],
            AxisOrder::Zxy => [2, 0, 1],
            AxisOrder::Zyx => [2, 1, 0],
        }
    }

    /// ODE's code for the order (`dSAP_AXES_XZY`...).
    const fn ode_code(self) -> i32 {
        (match self {
            AxisOrder::Xyz => ffi::dSAP_AXES_XYZ,
            AxisOrder::Xzy => ffi::dSAP_AXES_XZY,
            AxisOrder::Yxz => ffi::dSAP_AXES_YXZ,
            AxisOrder::Yzx => ffi::dSAP_AXES_YZX,
            AxisOrder::Zxy => ffi::dSAP_AXES_ZXY,
            AxisOrder::Zyx => ffi::dSAP_AXES_ZYX,
        }) as i32
    }
}

pub(crate) struct SpaceData {
    pub(crate) raw: ffi::dSpaceID,
    pub(crate) kind: SpaceKind,
}

/// The ODE stepper that advances the world.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default, serde::Serialize, serde::Deserialize)]
#[non_exhaustive]
pub enum Stepper {
    /// `dWorldStep`: the exact ("big matrix", Dantzig LCP) stepper; the ARS default.
    #[default]
    Exact,
    /// `dWorldQuickStep` with this many iterations (SOR/PGS): faster for large scenes,
    /// approximate.
    Quick {
        /// Iterations per step (ODE's default is 20).
        iterations: u32,
    },
}

/// An ODE world with its bodies, geoms, joints, spaces and the group of contact joints.
///
/// The world owns every ODE object and frees them all when dropped; users hold small
/// `Copy` handles ([`BodyHandle`], [`GeomHandle`](crate::GeomHandle),
/// [`JointHandle`](crate::JointHandle), [`SpaceHandle`]). A handle of a removed object
/// or of another world is an `Err`, never a dangling pointer.
///
/// A world can be moved to another thread ([`Send`]); ODE's process-wide state used
/// by triangle-mesh collision and by QuickStep is locked around those calls, so worlds
/// on different threads do not race.
///
/// ```
/// use ars_core::{World, SpaceKind, BodyBuilder, GeomBuilder, MassSpec};
/// use nalgebra::{Point3, Vector3};
///
/// let mut world = World::new();
/// let space = world.create_space(SpaceKind::Simple)?;
/// world.insert_geom(space, GeomBuilder::plane(Vector3::y(), 0.0))?;
/// let ball = world.insert_body(
///     BodyBuilder::new().position(Point3::new(1.0, 1.0, 1.0)).mass(MassSpec::sphere_total(1.0, 0.5)),
/// )?;
/// world.insert_geom(space, GeomBuilder::sphere(0.5).attached_to(ball))?;
/// for _ in 0..2500 {
///     world.collide(space)?;
///     world.step(0.0004)?;
///     world.clear_contacts();
/// }
/// assert!((world.body(ball)?.position().y - 0.5).abs() < 1e-3);
/// # Ok::<(), ars_core::Error>(())
/// ```
pub struct World {
    pub(crate) id: WorldId,
    pub(crate) raw: ffi::dWorldID,
    pub(crate) contact_group: ffi::dJointGroupID,
    threading: ffi::dThreadingImplementationID,
    pub(crate) bodies: Arena<BodyData>,
    pub(crate) geoms: Arena<GeomData>,
    pub(crate) joints: Arena<JointData>,
    pub(crate) spaces: Arena<SpaceData>,
    pub(crate) collision: CollisionState,
    /// The grid broad phase's buffers, reused from one collision to the next.
    pub(crate) grid: grid::Grid,
    /// Triangle-mesh geoms in the world: ODE's trimesh colliders share a process-wide
    /// cache, so collision takes the global lock while there are any.
    pub(crate) trimesh_count: usize,
    /// Ray geoms in the world: while there are none (and nothing else needs the Rust
    /// near callback), collision runs the plain near callback in C.
    pub(crate) ray_geoms: usize,
    /// The sizes of the world's cylinders and capsules (see [`ConvexSizes`]).
    pub(crate) convex_sizes: ConvexSizes,
    stepper: Stepper,
    /// Seed of ODE's process-wide random generator as this world left it: restored
    /// before each QuickStep and saved after it, under the global lock, so that a
    /// world's QuickStep sequence does not depend on other worlds.
    random_seed: std::ffi::c_ulong,
    /// Sum of the time steps taken, s.
    time: f64,
    /// The body that failed the last state check, if any; while set, every step
    /// first checks the whole state again.
    pub(crate) diverged: Option<BodyHandle>,
    pub(crate) poison: Option<Poison>,
    /// A bound on every body's largest absolute coordinate (exact after each step,
    /// raised by every position set in between), for the hash spaces' check: while
    /// the world has no hash space, steps do not measure it and leave it infinite
    /// (unknown), so that a hash space created later checks exactly until a step has
    /// measured it.
    max_body_coordinate: f64,
    /// The space of the last collision ([`RawHandle::NONE`] before the first), with its
    /// ODE id and kind (see [`World::look_up_collision_space`]).
    collided_space: SpaceHandle,
    collided_space_raw: ffi::dSpaceID,
    collided_space_kind: SpaceKind,
    /// The same space when it is a simple or sweep-and-prune one, which the plain path
    /// collides as it is (a hash space's size and bounds are checked at every
    /// collision; the grid lists its pairs in Rust), else [`RawHandle::NONE`].
    plain_space: SpaceHandle,
    /// Whether the world has a hash space (spaces are never removed).
    has_hash_space: bool,
    /// Why a step cannot take the plain one-call path, if it cannot (see
    /// [`StepGate`]); among them whether a force or torque was added.
    pub(crate) gate: StepGate,
    /// Most contacts in one island that the exact stepper takes.
    exact_step_contacts: usize,
    /// Bodies, geoms and joints created so far (each gets the next number: their
    /// creation order, which slot order is not once slots are reused).
    serials: u64,
    /// A bound on how far any geom reaches beyond its body (or, for a geom without a
    /// body, from the origin); it never decreases. With `max_body_coordinate` it lets
    /// a hash space skip its exact bounds check when everything is well inside.
    geom_reach: f64,
}

/// A failed [`World::collide_and_step`]: the collision's error (nothing was stepped)
/// or the step's.
#[derive(Debug)]
pub(crate) enum CollideStepError {
    /// The collision failed; the world did not step.
    Collide(Error),
    /// The collision went through and the step failed.
    Step(Error),
}

/// What [`World::collide_and_step`] returns: the rare failure is boxed, so that a step
/// that goes through returns one word.
pub(crate) type CollideStepResult = std::result::Result<(), Box<CollideStepError>>;

#[cold]
fn collide_failed(error: Error) -> Box<CollideStepError> {
    Box::new(CollideStepError::Collide(error))
}

#[cold]
fn step_failed(error: Error) -> Box<CollideStepError> {
    Box::new(CollideStepError::Step(error))
}

/// One byte for each reason a step cannot take the plain one-call path of
/// [`World::collide_and_step`], side by side so that the path is one test. Each mirrors
/// fields of the world and is written with them ([`World::poison`],
/// [`World::set_diverged`], [`World::refresh_gate`] after the rarer changes), except
/// `forces_added`, which is the world's own flag; debug builds check the mirror at
/// every plain step.
#[repr(C, align(8))]
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub(crate) struct StepGate {
    /// The stepper is QuickStep.
    quick: bool,
    /// The world has rays (the Rust near callback records their hits).
    rays: bool,
    /// Contact forces are reported (the Rust near callback sets up the feedback).
    feedback: bool,
    /// Cylinders or capsules whose sizes need libccd's check, pair by pair.
    convex: bool,
    /// A body failed the state check (every step checks it first).
    pub(crate) diverged: bool,
    /// A force or torque was added through the API since the last step (ODE clears the
    /// accumulators after each step; nothing else fills them): the step checks them.
    pub(crate) forces_added: bool,
    /// An ODE internal error poisoned the world.
    pub(crate) poisoned: bool,
    /// The world has triangle meshes (the collision takes the global lock).
    trimesh: bool,
}

impl StepGate {
    /// Nothing keeps a step off the plain path.
    #[inline(always)]
    fn is_open(&self) -> bool {
        let reasons = [
            self.quick,
            self.rays,
            self.feedback,
            self.convex,
            self.diverged,
            self.forces_added,
            self.poisoned,
            self.trimesh,
        ];
        u64::from_ne_bytes(reasons.map(u8::from)) == 0
    }
}

/// Why a world refuses to go on after an ODE internal error.
#[derive(Clone, Debug)]
pub(crate) enum Poison {
    /// Caught during a step: the world's state is half-integrated; it can be dropped.
    Step(String),
    /// Caught during `dSpaceCollide`: the space stays locked inside ODE, and
    /// destroying its geoms would assert; the world's ODE objects are leaked on drop.
    Collide(String),
}

// SAFETY: the ODE objects of a world are reachable only through the `World` (shared
// access for reads, exclusive access for changes), so moving the world moves all of
// them. Each world has its own step job queue. ODE's process-wide state (the trimesh
// collider cache, the RNG) is guarded by `init::lock_ode_global_state`, and every entry
// point that creates objects or collides prepares ODE's per-thread data
// (`ensure_ode_ready`) on the calling thread.
unsafe impl Send for World {}

impl Default for World {
    fn default() -> Self {
        World::new()
    }
}

impl fmt::Debug for World {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("World")
            .field("id", &self.id)
            .field("bodies", &self.bodies.len())
            .field("geoms", &self.geoms.len())
            .field("joints", &self.joints.len())
            .field("spaces", &self.spaces.len())
            .finish()
    }
}

impl World {
    /// A new world with the ARS defaults: gravity (0, −9.81, 0), ERP 0.2, CFM 1e-10,
    /// the exact stepper (`dWorldStep`), no damping, no auto-disable.
    pub fn new() -> Self {
        ensure_ode_ready();
        // SAFETY: ODE is initialised; the world, its threading implementation and the
        // joint group are freed in Drop. Each world gets its own self-threaded step job
        // queue: ODE's default queue is process-wide and not safe across threads.
        let (raw, contact_group, threading) = unsafe {
            let w = ffi::dWorldCreate();
            ffi::dWorldSetGravity(w, DEFAULT_GRAVITY.x, DEFAULT_GRAVITY.y, DEFAULT_GRAVITY.z);
            ffi::dWorldSetERP(w, DEFAULT_ERP);
            ffi::dWorldSetCFM(w, DEFAULT_CFM);
            let threading = ffi::dThreadingAllocateSelfThreadedImplementation();
            assert!(!threading.is_null(), "ODE could not allocate a threading implementation");
            ffi::dWorldSetStepThreadingImplementation(
                w,
                ffi::dThreadingImplementationGetFunctions(threading),
                threading,
            );
            (w, ffi::dJointGroupCreate(0), threading)
        };
        let id = WorldId::next();
        let collision = CollisionState::new(raw, contact_group);
        World {
            id,
            raw,
            contact_group,
            threading,
            bodies: Arena::new(id),
            geoms: Arena::new(id),
            joints: Arena::new(id),
            spaces: Arena::new(id),
            collision,
            grid: grid::Grid::default(),
            trimesh_count: 0,
            ray_geoms: 0,
            convex_sizes: ConvexSizes::default(),
            stepper: Stepper::Exact,
            random_seed: 0,
            time: 0.0,
            diverged: None,
            poison: None,
            max_body_coordinate: 0.0,
            has_hash_space: false,
            collided_space: SpaceHandle(RawHandle::NONE),
            collided_space_raw: std::ptr::null_mut(),
            collided_space_kind: SpaceKind::Simple,
            plain_space: SpaceHandle(RawHandle::NONE),
            exact_step_contacts: limits::DEFAULT_EXACT_STEP_CONTACTS,
            gate: StepGate::default(),
            geom_reach: 0.0,
            serials: 0,
        }
    }

    /// Bodies were put where a snapshot had them: the bound on their coordinates is
    /// unknown until the next step measures it.
    pub(crate) fn restored_coordinates(&mut self) {
        self.max_body_coordinate = f64::INFINITY;
    }

    /// A body is placed at a coordinate of this magnitude.
    #[inline]
    pub(crate) fn note_body_coordinate(&mut self, coordinate: f64) {
        self.max_body_coordinate = self.max_body_coordinate.max(coordinate);
    }

    /// A geom reaches this far (see `geom_reach`).
    #[inline]
    pub(crate) fn note_geom_reach(&mut self, reach: f64) {
        self.geom_reach = self.geom_reach.max(reach);
    }

    /// The largest coordinate any geom may have (a bound).
    #[inline]
    pub(crate) fn coordinate_bound(&self) -> f64 {
        self.max_body_coordinate + self.geom_reach
    }

    /// `Err` once an ODE internal error has poisoned the world.
    #[inline]
    pub(crate) fn check_usable(&self) -> Result<()> {
        match &self.poison {
            None => Ok(()),
            Some(Poison::Step(m) | Poison::Collide(m)) => Err(Error::Poisoned(m.clone())),
        }
    }

    /// Whether an ODE internal error has poisoned the world (it then refuses every
    /// step, collision and change, and can only be dropped).
    pub fn is_poisoned(&self) -> bool {
        self.poison.is_some()
    }

    /// Sum of the time steps taken by [`World::step`], s.
    pub fn time(&self) -> f64 {
        self.time
    }

    /// The body whose state failed the last check (see [`Error::Diverged`]), until it
    /// is reset or removed.
    pub fn diverged_body(&self) -> Option<BodyHandle> {
        self.diverged
    }

    /// This world's id; every handle it issues carries it.
    pub fn id(&self) -> WorldId {
        self.id
    }

    /// Gravity, in m/s².
    pub fn gravity(&self) -> Vector3<f64> {
        let mut g = [0.0; 4];
        // SAFETY: the world is live; `g` has room for a dVector3.
        unsafe { ffi::dWorldGetGravity(self.raw, g.as_mut_ptr()) };
        convert::vector_from_ode(&g)
    }

    /// Sets gravity, in m/s² (at most [`limits::MAX_ACCELERATION`]).
    pub fn set_gravity(&mut self, gravity: Vector3<f64>) -> Result<()> {
        let g = limits::vector_within("gravity", &gravity, limits::MAX_ACCELERATION, "m/s²")?;
        // SAFETY: the world is live.
        unsafe { ffi::dWorldSetGravity(self.raw, g.x, g.y, g.z) };
        Ok(())
    }

    /// The global error reduction parameter (ERP).
    pub fn erp(&self) -> f64 {
        // SAFETY: the world is live.
        unsafe { ffi::dWorldGetERP(self.raw) }
    }

    /// Sets the global ERP, in [0, 1].
    pub fn set_erp(&mut self, erp: f64) -> Result<()> {
        if !(0.0..=1.0).contains(&erp) {
            return Err(Error::OutOfRange { what: "ERP", detail: format!("must be within [0, 1], got {erp}") });
        }
        // SAFETY: the world is live.
        unsafe { ffi::dWorldSetERP(self.raw, erp) };
        Ok(())
    }

    /// The global constraint force mixing (CFM).
    pub fn cfm(&self) -> f64 {
        // SAFETY: the world is live.
        unsafe { ffi::dWorldGetCFM(self.raw) }
    }

    /// Sets the global CFM (finite, ≥ 0).
    pub fn set_cfm(&mut self, cfm: f64) -> Result<()> {
        validate::non_negative("CFM", cfm)?;
        // SAFETY: the world is live.
        unsafe { ffi::dWorldSetCFM(self.raw, cfm) };
        Ok(())
    }

    /// The stepper used by [`World::step`].
    pub fn stepper(&self) -> Stepper {
        self.stepper
    }

    /// Chooses the stepper used by [`World::step`].
    pub fn set_stepper(&mut self, stepper: Stepper) -> Result<()> {
        if let Stepper::Quick { iterations } = stepper {
            // A bound keeps one step finite in time (ODE's default is 20).
            if !(1..=100_000).contains(&iterations) {
                return Err(Error::OutOfRange {
                    what: "QuickStep iterations",
                    detail: format!("must be 1 to 100000, got {iterations}"),
                });
            }
            let n = iterations as i32;
            // SAFETY: the world is live.
            unsafe { ffi::dWorldSetQuickStepNumIterations(self.raw, n) };
        }
        self.stepper = stepper;
        self.refresh_gate();
        Ok(())
    }

    /// Advances the world by `dt` seconds with the chosen stepper (`dWorldStep` by
    /// default). Contact joints created by [`World::collide`] take part; forces and
    /// torques added since the last step act during this one and are then cleared.
    ///
    /// Before the step, every body's accumulated force and torque must be finite and
    /// within [`limits::MAX_FORCE`] and [`limits::MAX_TORQUE`]; after it, every body's
    /// state must be finite and within the [`limits`]. Otherwise the step returns
    /// [`Error::Diverged`] naming the body, and the world refuses to step until that
    /// body is reset or removed. An ODE internal error during the step is caught by the
    /// [`guard`]: [`Error::OdeInternal`], and the world is poisoned.
    pub fn step(&mut self, dt: f64) -> Result<()> {
        self.check_usable()?;
        limits::time_step(dt)?;
        self.check_before_step()?;
        if self.stepper == Stepper::Exact && self.collision.contact_count() > self.exact_step_contacts {
            self.check_island_sizes()?;
        }
        // No `ensure_ode_ready` here: ODE's per-thread data is collision data only
        // (`dAllocateFlagCollisionData`), prepared by `collide` on the calling thread.
        let stepped = match self.stepper {
            // SAFETY: the world is live, every object in it is owned by `self`, and its
            // step threading implementation is its own self-threaded one.
            Stepper::Exact => unsafe { guard::world_step(self.raw, dt, false) },
            Stepper::Quick { .. } => {
                // QuickStep shuffles constraints with ODE's process-wide RNG: give it
                // this world's seed, and keep where the world left it.
                let _guard = lock_ode_global_state();
                // SAFETY: as above; the generator is guarded by the global lock.
                unsafe {
                    ffi::dRandSetSeed(self.random_seed);
                    let stepped = guard::world_step(self.raw, dt, true);
                    self.random_seed = ffi::dRandGetSeed();
                    stepped
                }
            }
        };
        self.finish_step(dt, stepped)
    }

    /// After ODE's step: its failure, or the time, the contact forces and the check of
    /// the new state.
    #[inline(always)]
    fn finish_step(&mut self, dt: f64, stepped: std::result::Result<bool, guard::OdeFailure>) -> Result<()> {
        self.step_taken(dt, stepped)?;
        self.collision.read_contact_forces();
        self.check_after_step()
    }

    /// [`World::finish_step`] after the plain collision's step, which runs without
    /// contact feedback: no contact forces to read.
    #[inline(always)]
    fn finish_plain_step(&mut self, dt: f64, stepped: std::result::Result<bool, guard::OdeFailure>) -> Result<()> {
        self.step_taken(dt, stepped)?;
        debug_assert!(!self.collision.feedback.on, "the plain collision runs without contact feedback");
        self.check_after_step()
    }

    /// ODE's failure, or the time and the accumulators (ODE cleared them) after its step.
    #[inline(always)]
    fn step_taken(&mut self, dt: f64, stepped: std::result::Result<bool, guard::OdeFailure>) -> Result<()> {
        match stepped {
            Ok(true) => {}
            Ok(false) => return Err(Error::Ode("step the world (out of memory)")),
            Err(failure) => {
                self.poison(Poison::Step(failure.message.clone()));
                return Err(Error::OdeInternal { during: "step", message: failure.message });
            }
        }
        self.time += dt;
        self.gate.forces_added = false;
        Ok(())
    }

    /// [`World::collide`] on `space`, then [`World::step`] by `dt`, then (once the world
    /// has stepped) [`World::clear_contacts`]: the error says which of the two failed
    /// (a failed collision stepped nothing; after a failed step the contact joints may
    /// be left). Every check of the two is made, in the same order. With the exact
    /// stepper, a world the plain near callback serves (see
    /// [`World::plain_collision_applies`]) and a step whose checks before ODE pass,
    /// ODE collides, steps and destroys the contact joints in one guarded call
    /// (`guard.c`).
    #[inline(always)]
    pub(crate) fn collide_and_step(&mut self, space: &SpaceHandle, dt: limits::TimeStep) -> CollideStepResult {
        // The time step was checked when it was made (`World::step` checks it again on
        // the separate path, as it always does).
        let dt = dt.get();
        if !(self.gate.is_open() && self.plain_space.0.same_as(space.0)) {
            return self.collide_and_step_gated(*space, dt);
        }
        // Nothing in the gate: the exact stepper, a world the plain near callback serves
        // and no triangle mesh (no lock), not poisoned, no diverged body and no force
        // added (the step's checks before ODE pass), and `space` is the last collision's
        // space, a simple or sweep-and-prune one (nothing to check before colliding it).
        debug_assert_eq!(self.gate, self.gate_from_fields(), "the step gate mirrors the world");
        ensure_ode_ready();
        self.start_collision_pass();
        // SAFETY: as in `collide_plain` (the space is live and its geoms are this
        // world's, the parameters are this world's); the world's step threading
        // implementation is its own self-threaded one.
        let done = unsafe {
            guard::collide_and_step(self.collided_space_raw, &mut self.collision.plain.0, dt, self.exact_step_contacts)
        };
        self.end_collide_and_step(done, dt)
    }

    /// [`World::collide_and_step`] when something in the gate is set: every check
    /// decides which way the step goes.
    #[inline(never)]
    fn collide_and_step_gated(&mut self, space: SpaceHandle, dt: f64) -> CollideStepResult {
        let one_call = matches!(self.stepper, Stepper::Exact)
            && self.plain_collision_applies()
            // The step's checks that read the bodies only (a collision changes none):
            // when one fails, the separate calls below report it as they always do.
            && self.check_before_step().is_ok();
        if !one_call {
            return self.collide_then_step(space, dt);
        }
        let (raw_space, kind) = self.begin_collision(space).map_err(collide_failed)?;
        if matches!(kind, SpaceKind::Grid) {
            // ARS's own broad phase lists the pairs in Rust.
            return self.collide_then_step(space, dt);
        }
        let (plain, limit) = (&mut self.collision.plain.0, self.exact_step_contacts);
        // Two calls rather than an optional lock guard, whose drop is not free.
        let done = if self.trimesh_count > 0 {
            let _guard = lock_ode_global_state();
            // SAFETY: as in `collide_plain` (the space is live and its geoms are this
            // world's, the parameters are this world's); the world's step threading
            // implementation is its own self-threaded one.
            unsafe { guard::collide_and_step(raw_space, plain, dt, limit) }
        } else {
            // SAFETY: as above.
            unsafe { guard::collide_and_step(raw_space, plain, dt, limit) }
        };
        self.end_collide_and_step(done, dt)
    }

    /// After the guarded collide-and-step: its result, the world's state checked.
    #[inline(always)]
    fn end_collide_and_step(&mut self, done: guard::CollideStep, dt: f64) -> CollideStepResult {
        match done {
            guard::CollideStep::Stepped(stepped) => {
                // The C side steps only after a collision that no pair stopped.
                debug_assert_eq!(self.collision.plain.0.stopped, 0, "a stepped world's collision went through");
                self.finish_plain_step(dt, Ok(stepped)).map_err(step_failed)
            }
            guard::CollideStep::CollideFailed => {
                let failure = guard::collide_and_step_failure(&self.collision.plain.0);
                Err(collide_failed(self.collision_failed(failure)))
            }
            guard::CollideStep::NotStepped => {
                self.end_plain_collision().map_err(collide_failed)?;
                // More contact points than the exact stepper's limit: the island check
                // decides, in the separate step.
                self.step(dt).map_err(step_failed)?;
                self.clear_contacts();
                Ok(())
            }
            guard::CollideStep::StepFailed => {
                self.end_plain_collision().map_err(collide_failed)?;
                let failure = guard::collide_and_step_failure(&self.collision.plain.0);
                self.finish_plain_step(dt, Err(failure)).map_err(step_failed)
            }
        }
    }

    /// [`World::collide`], then [`World::step`]: what [`World::collide_and_step`] does
    /// when ODE cannot do both in one call.
    #[inline(never)]
    fn collide_then_step(&mut self, space: SpaceHandle, dt: f64) -> CollideStepResult {
        self.collide(space).map_err(collide_failed)?;
        self.step(dt).map_err(step_failed)?;
        self.clear_contacts();
        Ok(())
    }

    /// The gate as the world's fields say (see [`StepGate`]).
    fn gate_from_fields(&self) -> StepGate {
        StepGate {
            quick: !matches!(self.stepper, Stepper::Exact),
            rays: self.ray_geoms > 0,
            feedback: self.collision.feedback.on,
            convex: !self.convex_sizes.all_pairs_fine(),
            diverged: self.diverged.is_some(),
            forces_added: self.gate.forces_added,
            poisoned: self.poison.is_some(),
            trimesh: self.trimesh_count > 0,
        }
    }

    /// Brings the gate in line with the fields it mirrors, after one of them changed.
    pub(crate) fn refresh_gate(&mut self) {
        self.gate = self.gate_from_fields();
    }

    /// Refuses everything from now on, for `why` (the gate with it).
    #[cold]
    pub(crate) fn poison(&mut self, why: Poison) {
        self.poison = Some(why);
        self.gate.poisoned = true;
    }

    /// The body that failed the state check, if one did (the gate with it).
    #[inline(always)]
    pub(crate) fn set_diverged(&mut self, body: Option<BodyHandle>) {
        self.diverged = body;
        self.gate.diverged = body.is_some();
    }

    /// The accumulators (and, after a divergence, the whole state) of every body.
    #[inline(always)]
    fn check_before_step(&mut self) -> Result<()> {
        if self.diverged.is_some() {
            self.check_after_step()?;
        }
        if !self.gate.forces_added {
            return Ok(());
        }
        // SAFETY: every body in the arena is live, so are its state pointers.
        let fine = self.bodies.values().all(|b| unsafe { accumulators_fine(&b.state) });
        if fine { Ok(()) } else { Err(self.divergence(accumulators_fine, true)) }
    }

    /// Position, orientation and velocities of every body: finite and within limits.
    #[inline(always)]
    fn check_after_step(&mut self) -> Result<()> {
        let mut fine = true;
        if self.has_hash_space {
            let mut far = 0.0_f64;
            for b in self.bodies.values() {
                // SAFETY: every body in the arena is live, so are its state pointers.
                fine &= unsafe { state_fine(&b.state) };
                // The bound for the hash spaces' cheap check (NaN never counts: `fine`
                // fails). SAFETY: as above.
                for c in unsafe { &*b.state.position } {
                    if c.abs() > far {
                        far = c.abs();
                    }
                }
            }
            self.max_body_coordinate = far;
        } else {
            // SAFETY: every body in the arena is live, so are its state pointers.
            fine = self.bodies.values().all(|b| unsafe { state_fine(&b.state) });
            self.max_body_coordinate = f64::INFINITY;
        }
        if fine {
            self.set_diverged(None);
            Ok(())
        } else {
            Err(self.divergence(state_fine, false))
        }
    }

    /// The error naming the first body that fails `fine` (the slow path of the
    /// checks); a state (not accumulator) failure marks the body as diverged.
    #[cold]
    fn divergence(&mut self, fine: unsafe fn(&crate::body::StatePointers) -> bool, accumulators: bool) -> Error {
        // SAFETY: every body in the arena is live, so are its state pointers.
        let Some((h, data)) = self.bodies.iter().find(|(_, b)| !unsafe { fine(&b.state) }) else {
            return Error::Ode("find the diverged body");
        };
        let s = &data.state;
        // SAFETY: the body is live (just found in the arena), so are its pointers.
        let (p, q, v, w, f, t) =
            unsafe { (*s.position, *s.quaternion, *s.linear_velocity, *s.angular_velocity, *s.force, *s.torque) };
        let body = BodyHandle(h);
        let detail = if accumulators {
            limits::state_problem("accumulated force", &f, limits::MAX_FORCE, "N")
                .or_else(|| limits::state_problem("accumulated torque", &t, limits::MAX_TORQUE, "N·m"))
                .map(|d| format!("{d} (clear it with BodyMut::clear_forces)"))
        } else {
            self.set_diverged(Some(body));
            limits::state_problem("position", &p, limits::MAX_COORDINATE, "m")
                .or_else(|| limits::state_problem("orientation quaternion", &q, 1.5, ""))
                .or_else(|| limits::state_problem("linear velocity", &v, limits::MAX_SPEED, "m/s"))
                .or_else(|| limits::state_problem("angular velocity", &w, limits::MAX_ANGULAR_SPEED, "rad/s"))
        };
        Error::Diverged { body: body.to_string(), time: self.time, detail: detail.unwrap_or_default() }
    }

    /// The largest number of contacts in one island the exact stepper takes (see
    /// [`World::set_exact_step_contact_limit`]).
    pub fn exact_step_contact_limit(&self) -> usize {
        self.exact_step_contacts
    }

    /// Sets the largest number of contact points that one island (bodies linked by
    /// contacts) may hold for the exact stepper (default
    /// [`limits::DEFAULT_EXACT_STEP_CONTACTS`]). `dWorldStep` solves an island as one
    /// dense problem whose cost grows with the cube of its size; beyond the limit
    /// [`World::step`] returns an `Err` instead of computing for minutes. QuickStep has
    /// no such limit (its cost is linear). Scenes of separate islands are unaffected.
    pub fn set_exact_step_contact_limit(&mut self, limit: usize) {
        self.exact_step_contacts = limit;
    }

    /// Counts the contacts of each island (union–find over the bodies of the contact
    /// points); runs only when the contacts in all exceed the limit.
    #[cold]
    fn check_island_sizes(&self) -> Result<()> {
        let slots = self.bodies.iter().map(|(h, _)| h.index as usize + 1).max().unwrap_or(0);
        let mut parent: Vec<usize> = (0..slots).collect();
        fn root(parent: &mut [usize], mut i: usize) -> usize {
            while parent[i] != i {
                parent[i] = parent[parent[i]];
                i = parent[i];
            }
            i
        }
        let contacts = self.contacts();
        for c in contacts {
            if let (Some(a), Some(b)) = (c.pair.body1, c.pair.body2) {
                let (ra, rb) = (root(&mut parent, a.0.index as usize), root(&mut parent, b.0.index as usize));
                parent[ra] = rb;
            }
        }
        let mut count = vec![0usize; slots];
        for c in contacts {
            if let Some(b) = c.pair.body1.or(c.pair.body2) {
                let r = root(&mut parent, b.0.index as usize);
                count[r] += 1;
                if count[r] > self.exact_step_contacts {
                    return Err(Error::OutOfRange {
                        what: "the contacts in one island for the exact stepper",
                        detail: format!(
                            "must number at most {0}: more than {0} contact points link the bodies around {b}; dWorldStep's time grows with the cube of that number (1,640 take 43 s per step). Use Stepper::Quick, fewer contacts per pair (ContactSurface::max_contacts), or World::set_exact_step_contact_limit",
                            self.exact_step_contacts
                        ),
                    });
                }
            }
        }
        Ok(())
    }

    /// Seeds ODE's random number generator for this world's QuickSteps. Each world
    /// keeps its own seed (ODE's generator is process-wide: the world restores its
    /// seed before each QuickStep and saves it after), so QuickStep is deterministic
    /// per world whatever other worlds do on other threads. The default seed is 0.
    pub fn set_random_seed(&mut self, seed: u32) {
        self.random_seed = seed.into();
    }

    /// Creates a collision space. A hash space needs
    /// `-30 ≤ min_level ≤ max_level ≤ 30` (cells from about 1 nm to 1e9 m); a simple
    /// or sweep-and-prune space takes no numbers that could be wrong.
    pub fn create_space(&mut self, kind: SpaceKind) -> Result<SpaceHandle> {
        self.check_usable()?;
        if let SpaceKind::Hash { min_level, max_level } = kind
            && !(-30..=30).contains(&min_level) | !(-30..=30).contains(&max_level) | (min_level > max_level)
        {
            return Err(Error::OutOfRange {
                what: "hash space levels",
                detail: format!("must satisfy -30 ≤ min_level ≤ max_level ≤ 30, got min {min_level}, max {max_level}"),
            });
        }
        ensure_ode_ready();
        // SAFETY: a top-level space (no parent); cleanup is turned off because the
        // world destroys the geoms itself; the space is freed in Drop.
        let raw = unsafe {
            let s = match kind {
                SpaceKind::Simple => ffi::dSimpleSpaceCreate(std::ptr::null_mut()),
                SpaceKind::Hash { min_level, max_level } => {
                    let s = ffi::dHashSpaceCreate(std::ptr::null_mut());
                    ffi::dHashSpaceSetLevels(s, min_level, max_level);
                    s
                }
                SpaceKind::SweepAndPrune { axes } => {
                    ffi::dSweepAndPruneSpaceCreate(std::ptr::null_mut(), axes.ode_code())
                }
                // The grid keeps its geoms in a simple space (rays and the geoms' own
                // calls need one) and never asks it for pairs.
                SpaceKind::Grid => ffi::dSimpleSpaceCreate(std::ptr::null_mut()),
            };
            ffi::dSpaceSetCleanup(s, 0);
            s
        };
        self.has_hash_space |= matches!(kind, SpaceKind::Hash { .. });
        Ok(SpaceHandle(self.spaces.insert(SpaceData { raw, kind })))
    }

    /// The kind of a space.
    pub fn space_kind(&self, space: SpaceHandle) -> Result<SpaceKind> {
        Ok(self.space_data(space)?.kind)
    }

    #[inline]
    pub(crate) fn space_data(&self, space: SpaceHandle) -> Result<&SpaceData> {
        self.spaces.get(space.0, SpaceHandle::KIND)
    }

    /// Number of bodies in the world.
    pub fn body_count(&self) -> usize {
        self.bodies.len()
    }

    /// Number of geoms in the world.
    pub fn geom_count(&self) -> usize {
        self.geoms.len()
    }

    /// Number of joints in the world (contact joints are not counted).
    pub fn joint_count(&self) -> usize {
        self.joints.len()
    }
}

/// Every component within ±`max` (false for NaN).
#[inline(always)]
fn within<const N: usize>(values: &[f64; N], max: f64) -> bool {
    let mut ok = true;
    for c in values {
        ok &= c.abs() <= max;
    }
    ok
}

/// Force and torque accumulators finite and within limits.
///
/// # Safety
/// The pointers belong to a live body.
#[inline(always)]
unsafe fn accumulators_fine(s: &crate::body::StatePointers) -> bool {
    // SAFETY: the caller's contract.
    unsafe { within(&*s.force, limits::MAX_FORCE) & within(&*s.torque, limits::MAX_TORQUE) }
}

/// Position, orientation and velocities finite and within limits.
///
/// # Safety
/// The pointers belong to a live body.
#[inline(always)]
// `!(x <= max)` is meant: a NaN is outside (as in `within`).
#[allow(clippy::neg_cmp_op_on_partial_ord)]
unsafe fn state_fine(s: &crate::body::StatePointers) -> bool {
    // SAFETY: the caller's contract.
    let (p, q, v, w) = unsafe { (&*s.position, &*s.quaternion, &*s.linear_velocity, &*s.angular_velocity) };
    // The 13 components side by side (the last repeated to an even count), each
    // against its own bound: the comparisons go two at a time.
    let values = [p[0], p[1], p[2], q[0], q[1], q[2], q[3], v[0], v[1], v[2], w[0], w[1], w[2], w[2]];
    let mut outside = 0_u64;
    for (x, max) in values.iter().zip(STATE_LIMITS) {
        // Not `x.abs() > max`, which a NaN passes.
        outside |= u64::from(!(x.abs() <= max));
    }
    outside == 0
}

/// The bound of each component of [`state_fine`]'s values.
const STATE_LIMITS: [f64; 14] = {
    let (c, s, a) = (limits::MAX_COORDINATE, limits::MAX_SPEED, limits::MAX_ANGULAR_SPEED);
    [c, c, c, 1.5, 1.5, 1.5, 1.5, s, s, s, a, a, a, a]
};

impl Drop for World {
    fn drop(&mut self) {
        if let Some(Poison::Collide(_)) = self.poison {
            // A space is still locked inside ODE: destroying anything in it would
            // assert. Leak the world's ODE objects and the buffers they point into.
            std::mem::forget(self.geoms.drain());
            std::mem::forget(self.joints.drain());
            return;
        }
        ensure_ode_ready();
        // Joints first (their feedback buffers are freed after them), then geoms
        // (before their trimesh data and their spaces), then spaces, then the world,
        // which destroys the bodies.
        // SAFETY: every id below was created by this world and is destroyed once.
        unsafe {
            ffi::dJointGroupEmpty(self.contact_group);
            ffi::dJointGroupDestroy(self.contact_group);
            for joint in self.joints.drain() {
                ffi::dJointDestroy(joint.raw);
            }
            for geom in self.geoms.drain() {
                ffi::dGeomDestroy(geom.raw);
                drop(geom);
            }
            for space in self.spaces.drain() {
                ffi::dSpaceDestroy(space.raw);
            }
            for body in self.bodies.drain() {
                ffi::dBodyDestroy(body.raw);
            }
            ffi::dWorldSetStepThreadingImplementation(self.raw, std::ptr::null(), std::ptr::null_mut());
            // A step left by the guard leaves stale jobs in the world's job list,
            // and freeing the list asserts on them: leak it (a few hundred bytes).
            if self.poison.is_none() {
                ffi::dThreadingFreeImplementation(self.threading);
            }
            ffi::dWorldDestroy(self.raw);
        }
    }
}
