//! The [`World`]: the one owner of every ODE object of a simulation.

use std::fmt;

use nalgebra::Vector3;
use ode_sys as ffi;

pub mod body;
mod collision;
pub mod contact;
pub mod geom;
mod grid;
pub mod joint;
pub(crate) mod limit_rows;
pub(crate) mod mesh_tree;
mod pair_checks;
pub mod raycast;
mod spread;
pub(crate) mod state;
mod step;

use body::BodyData;
use collision::CollisionState;
use geom::GeomData;
use pair_checks::ConvexSizes;

use crate::convert;
use crate::error::{Error, Result};

use crate::handle::{Arena, BodyHandle, RawHandle, SpaceHandle, WorldId};
use crate::init::ensure_ode_ready;
use crate::limits;
use crate::validate;
use joint::JointData;
pub(crate) use step::{CollideStepError, CollideStepResult, StepGate};

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
    /// Tests every pair of geoms (O(n²)); what the original ARS used. ARS runs ODE's
    /// loop in ODE's order (so the contacts, and every bit after them, are ODE's) on a
    /// compact copy of the geoms' boxes, leaving out the pairs of two static geoms,
    /// which never touch. (In every kind of space, a geom whose category and collide
    /// bits are both 0 is left out of ODE's space: it touches nothing.)
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
    /// The one-sided rows of the next step (see `limit_rows`), and how many there are.
    limit_group: ffi::dJointGroupID,
    limit_rows: usize,
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
        let (raw, contact_group, limit_group, threading) = unsafe {
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
            (w, ffi::dJointGroupCreate(0), ffi::dJointGroupCreate(0), threading)
        };
        let id = WorldId::next();
        let collision = CollisionState::new(raw, contact_group);
        World {
            id,
            raw,
            contact_group,
            limit_group,
            limit_rows: 0,
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
            ffi::dJointGroupEmpty(self.limit_group);
            ffi::dJointGroupDestroy(self.limit_group);
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
