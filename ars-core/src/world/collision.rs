//! The collision pass: `dSpaceCollide` with a Rust near callback.
//!
//! For every candidate pair of geoms ODE reports, the callback (1) skips pairs whose
//! bodies are joined by a (non-contact) joint, (2) records ray hits without creating
//! contact joints, (3) asks [`CollisionHooks::contact_surface`] for the surface of the
//! pair (the world's default surface unless the hooks say otherwise, or `None` to skip
//! it; a plane's pair with a geom whose bounding box lies wholly above it is skipped
//! before, as it makes no contact) and (4) creates one contact joint per contact point in the world's contact
//! group. [`World::clear_contacts`] empties the group; the original ARS did it after
//! every step.
//!
//! Collision takes the process-wide ODE lock ([`crate::lock_ode_global_state`])
//! only while the world holds triangle meshes, whose colliders share a cache.
//!
//! A panic in user hooks never unwinds into ODE: the callback catches it, ignores the
//! remaining pairs, and re-raises it once `dSpaceCollide` has returned.
//!
//! **The plain collision.** A world without rays, collision hooks (the default
//! surface for every pair), contact feedback, or cylinders and capsules whose sizes
//! are far enough apart to need the libccd check (see `ConvexSizes`) needs none of
//! the Rust callback's branches: its pairs go to the same callback written in C
//! (`plain_near` in ode-sys's `guard.c`), the same checks in the same order, so the
//! contact joints and every later bit are the same. It records each point with its two
//! ODE geoms; [`World::contacts`] turns the records into [`ContactPoint`]s when first
//! read (a geom is removed only after that). A
//! [`Simulation`](crate::Simulation) step collides and steps in one guarded C call
//! (`World::collide_and_step`).

use std::any::Any;
use std::cell::{Cell, OnceCell};
use std::ffi::c_void;
use std::panic::{AssertUnwindSafe, catch_unwind, resume_unwind};

use nalgebra::Vector3;
use ode_sys as ffi;

use super::contact::{
    CollisionHooks, ContactPoint, ContactSurface, DefaultHooks, GeomPair, MAX_CONTACTS_LIMIT, RayHit, geom_slot_in,
};
use super::pair_checks::{above_plane, convex_pair_ratio, pair_may_touch};
use super::{Poison, SpaceKind, World};
use crate::convert;
use crate::error::{Error, Result};
use crate::guard::{self, OdeFailure};
use crate::handle::{GeomHandle, SpaceHandle};
use crate::init::{ensure_ode_ready, lock_ode_global_state};

/// Scratch buffers and the results of the last collision pass.
#[derive(Default)]
pub(crate) struct CollisionState {
    pub(crate) default_surface: ContactSurface,
    /// The contact points of the last pass: set when the Rust near callback ends, or
    /// made from the plain collision's `records` when first read (most steps nobody
    /// reads them). A geom is removed only once they are made (`World::remove_geom`).
    pub(super) points: OnceCell<Vec<ContactPoint>>,
    /// The points the Rust near callback is making.
    building: Vec<ContactPoint>,
    /// An emptied vector of points whose allocation the next pass reuses.
    pub(super) spare_points: Cell<Vec<ContactPoint>>,
    pub(super) ray_hits: Vec<RayHit>,
    scratch: Vec<ffi::dContactGeom>,
    /// The plain collision's parameters (among them the contact joint's parameters
    /// with `default_surface` as ODE takes it, which each contact point of a default
    /// pair writes its geometry into) and the contact points it recorded.
    pub(crate) plain: PlainCollision,
    /// Where ODE writes the contact joints' forces, when asked.
    pub(crate) feedback: ContactFeedback,
}

/// What the plain near callback (in C, `guard.c`) works with: the world, its contact
/// group, the default contact and the scratch buffer, and what it leaves: the contact
/// points it recorded (in an array that `guard.c` grows) and why it stopped. Kept from
/// one collision to the next, so that a collision passes one pointer; nothing in it
/// points into it (the contact, the records and the failure report are inline), so
/// it moves with the world.
pub(crate) struct PlainCollision(pub(crate) ffi::odesys_plain_collision);

impl Default for PlainCollision {
    fn default() -> Self {
        let surface = ContactSurface::default();
        PlainCollision(ffi::odesys_plain_collision {
            // Set by `CollisionState::new`.
            world: std::ptr::null_mut(),
            group: std::ptr::null_mut(),
            contact: contact_with(&surface),
            max_contacts: surface.max_contacts as std::ffi::c_int,
            scratch: std::ptr::null_mut(),
            out: ffi::odesys_contact_records { items: std::ptr::null_mut(), len: 0, capacity: 0 },
            stopped: 0,
            failed: [std::ptr::null_mut(); 2],
            pair_failure: ffi::odesys_failure::default(),
            space: std::ptr::null_mut(),
            step_size: 0.0,
            contact_limit: 0,
            phase: 0,
            failure: ffi::odesys_failure::default(),
        })
    }
}

impl PlainCollision {
    /// Contacts of default pairs get `surface` from now on.
    pub(super) fn set_surface(&mut self, surface: &ContactSurface) {
        self.0.contact = contact_with(surface);
        self.0.max_contacts = surface.max_contacts as std::ffi::c_int;
    }

    /// The contact points recorded by the last plain collision.
    pub(super) fn records(&self) -> &[ffi::odesys_contact_record] {
        let out = &self.0.out;
        if out.items.is_null() {
            return &[];
        }
        // SAFETY: `guard.c` allocated `capacity` records at `items` and wrote the first
        // `len`; nothing else changes them while `self` is borrowed.
        unsafe { std::slice::from_raw_parts(out.items, out.len) }
    }
}

impl Drop for PlainCollision {
    fn drop(&mut self) {
        // SAFETY: the array is `guard.c`'s (or empty), freed once here.
        unsafe { ffi::odesys_contact_records_free(&mut self.0.out) };
    }
}

/// Contact feedback buffers in blocks of this many.
const FEEDBACK_BLOCK: usize = 256;

/// The buffers ODE writes each contact joint's forces into during a step (one per
/// contact point, in the order of [`World::contacts`]), when turned on. Blocks are
/// boxed and kept: a buffer's address stays the same while the world lives.
#[derive(Default)]
pub(crate) struct ContactFeedback {
    pub(crate) on: bool,
    blocks: Vec<Box<[ffi::dJointFeedback; FEEDBACK_BLOCK]>>,
    /// Whether contact `i`'s joint has its first geom's body as its first body (ODE
    /// reports the force on the joint's first body).
    first_attached: Vec<bool>,
}

impl ContactFeedback {
    /// Buffer `i`, zeroed (its block made if needed), of a joint whose first body is
    /// the first geom's when `first_attached`.
    fn slot(&mut self, i: usize, first_attached: bool) -> *mut ffi::dJointFeedback {
        while self.blocks.len() * FEEDBACK_BLOCK <= i {
            self.blocks.push(Box::new([ffi::dJointFeedback::default(); FEEDBACK_BLOCK]));
        }
        if self.first_attached.len() <= i {
            self.first_attached.resize(i + 1, true);
        }
        self.first_attached[i] = first_attached;
        let slot = &mut self.blocks[i / FEEDBACK_BLOCK][i % FEEDBACK_BLOCK];
        *slot = ffi::dJointFeedback::default();
        slot
    }
}

impl CollisionState {
    /// Copies the forces ODE wrote during the step into the contact points (when
    /// asked for: the test is inlined into every step).
    #[inline]
    pub(crate) fn read_contact_forces(&mut self) {
        if self.feedback.on {
            self.copy_contact_forces();
        }
    }

    #[inline(never)]
    fn copy_contact_forces(&mut self) {
        // Feedback is on only on the Rust path, which sets the points.
        let Some(points) = self.points.get_mut() else { return };
        for (i, c) in points.iter_mut().enumerate() {
            let Some(block) = self.feedback.blocks.get(i / FEEDBACK_BLOCK) else { break };
            let f = convert::vector_from_ode(&block[i % FEEDBACK_BLOCK].f1);
            // ODE attaches a joint whose first body is static (or a kinematic body at
            // rest, attached as the world) to the second body alone, and reports the
            // force on it.
            let first = self.feedback.first_attached.get(i).copied().unwrap_or(c.pair.body1.is_some());
            c.force = if first { f } else { -f };
        }
    }
}

impl CollisionState {
    /// The collision state of a new world: room for a pair's contact points (made once
    /// and never resized, so that the plain collision keeps its address), and the
    /// plain collision's world and contact group.
    pub(crate) fn new(world: ffi::dWorldID, group: ffi::dJointGroupID) -> Self {
        let mut state = CollisionState {
            scratch: vec![ffi::dContactGeom::default(); MAX_CONTACTS_LIMIT],
            ..CollisionState::default()
        };
        let plain = &mut state.plain.0;
        (plain.world, plain.group, plain.scratch) = (world, group, state.scratch.as_mut_ptr());
        state
    }

    /// Number of contact points of the last collision pass.
    #[inline]
    pub(crate) fn contact_count(&self) -> usize {
        self.points.get().map_or(self.plain.0.out.len, Vec::len)
    }
}

/// A contact joint's parameters with `surface` (its geometry to be written per point).
fn contact_with(surface: &ContactSurface) -> ffi::dContact {
    ffi::dContact { surface: surface.to_ode(), geom: ffi::dContactGeom::default(), fdir1: [0.0; 4] }
}

/// The surface of a pair's contacts.
enum PairSurface {
    /// A ray: hits are recorded, no contact joint.
    Ray,
    /// The world's default surface.
    Default,
    /// A surface chosen by the hooks, as ODE takes it, with its most contacts.
    Chosen(ffi::dSurfaceParameters, usize),
}

/// The largest absolute coordinate a hash space with this `min_level` holds: ODE puts
/// a geom in integer cells of at least `2^min_level` m, and aborts beyond `i32::MAX`
/// cells (`aabbBound`).
fn hash_limit(min_level: i32) -> f64 {
    f64::from(i32::MAX) * 2f64.powi(min_level)
}

/// The refusal of a hash space holding more than [`crate::limits::MAX_HASH_SPACE_GEOMS`].
#[cold]
fn too_many_hash_geoms(geoms: std::ffi::c_int) -> Error {
    Error::OutOfRange {
        what: "geoms in a hash space",
        detail: format!(
            "{geoms} geoms; a hash space collides at most {} (ODE clears a table of one bit per pair at every collision, and its index overflows beyond about 131,000): use SpaceKind::SWEEP_AND_PRUNE",
            crate::limits::MAX_HASH_SPACE_GEOMS
        ),
    }
}

/// Why a pair stopped the collision pass.
enum PairFailure {
    /// Its collider failed inside ODE (caught by the guard).
    Ode(GeomHandle, GeomHandle, OdeFailure),
    /// Its sizes are too far apart for libccd to finish: never handed to ODE.
    Refused(GeomHandle, GeomHandle, f64),
}

/// What the near callback sees through its `void*`.
struct NearContext<'a, H: CollisionHooks + ?Sized> {
    world: &'a mut World,
    hooks: &'a mut H,
    panic: Option<Box<dyn Any + Send>>,
    /// The first pair whose `dCollide` failed inside ODE (caught by its guard).
    failure: Option<PairFailure>,
}

impl World {
    /// Finds the contacts in `space` (on the current poses) and creates their contact
    /// joints, with the default surface for every pair.
    pub fn collide(&mut self, space: SpaceHandle) -> Result<()> {
        self.collide_with(space, &mut DefaultHooks)
    }

    /// As [`World::collide`], with `hooks` choosing the surface of each pair.
    ///
    /// A panic in `hooks` is re-raised once ODE has returned (the remaining pairs are
    /// skipped). An `Err` leaves no contact joint behind: a hash space whose geoms
    /// reach beyond what its integer cells hold, or that holds more than
    /// [`limits::MAX_HASH_SPACE_GEOMS`](crate::limits::MAX_HASH_SPACE_GEOMS) geoms, is
    /// refused before ODE is called; a pair whose collider fails inside ODE is
    /// reported ([`Error::OdeInternal`], the world stays usable); a failure of the
    /// space itself poisons the world.
    pub fn collide_with<H: CollisionHooks + ?Sized>(&mut self, space: SpaceHandle, hooks: &mut H) -> Result<()> {
        let (raw_space, kind) = self.begin_collision(space)?;
        // ODE's trimesh colliders share one process-wide cache in this build of ODE;
        // every other collider only touches the geoms it is given.
        let needs_lock = self.trimesh_count > 0;
        // The grid is ARS's own broad phase: it lists the pairs, the near callback
        // takes them as it takes ODE's.
        if hooks.always_default() && !matches!(kind, SpaceKind::Grid) && self.plain_collision_applies() {
            return self.collide_plain(raw_space, needs_lock);
        }
        let mut grid = matches!(kind, SpaceKind::Grid).then(|| std::mem::take(&mut self.grid));
        let grid_pairs = grid.as_mut().map(|g| g.candidate_pairs(self, space));
        self.collision.building = self.collision.spare_points.take();
        let mut ctx = NearContext { world: self, hooks, panic: None, failure: None };
        let collided = {
            let _guard = needs_lock.then(lock_ode_global_state);
            let data = (&raw mut ctx).cast::<c_void>();
            match grid_pairs {
                Some(pairs) => {
                    for &(o1, o2) in pairs {
                        // SAFETY: `data` is `ctx`, alive and only accessed by the
                        // callback; both geoms are live geoms of this world (listed just
                        // now); the callback never unwinds (it catches panics).
                        unsafe { near_callback::<H>(data, o1, o2) };
                    }
                    Ok(())
                }
                // SAFETY: the space is live; `ctx` outlives the call and is only
                // accessed by `near_callback`, which ODE calls synchronously on this
                // thread and which never unwinds (it catches panics).
                None => unsafe { guard::space_collide(raw_space, data, near_callback::<H>) },
            }
        };
        let (panic, pair_failure) = (ctx.panic, ctx.failure);
        let built = std::mem::take(&mut self.collision.building);
        // The points were taken out when the pass began: the cell is empty.
        let _ = self.collision.points.set(built);
        if let Some(grid) = grid {
            self.grid = grid;
        }
        if let Err(failure) = collided {
            return Err(self.collision_failed(failure));
        }
        if let Some(payload) = panic {
            self.clear_contacts();
            resume_unwind(payload);
        }
        match pair_failure {
            None => Ok(()),
            Some(PairFailure::Ode(g1, g2, failure)) => {
                self.clear_contacts();
                Err(Error::OdeInternal {
                    during: "collision",
                    message: format!("colliding {g1} and {g2}: {}", failure.message),
                })
            }
            Some(PairFailure::Refused(g1, g2, ratio)) => {
                self.clear_contacts();
                Err(Error::OutOfRange {
                    what: "the sizes of two touching shapes",
                    detail: format!(
                        "must differ by a factor of at most {:e} (beyond it ODE's cylinder collider, libccd, may never finish); the radii and lengths of {g1} and {g2} differ by {ratio:e}",
                        crate::limits::MAX_CONVEX_PAIR_RATIO
                    ),
                })
            }
        }
    }

    /// The checks before ODE collides `space` (a usable world; a hash space's size and
    /// bounds), then the start of a pass: no contact points, no ray hits. The space's
    /// ODE id and kind.
    #[inline(always)]
    pub(crate) fn begin_collision(&mut self, space: SpaceHandle) -> Result<(ffi::dSpaceID, SpaceKind)> {
        self.check_usable()?;
        ensure_ode_ready();
        if !self.collided_space.0.same_as(space.0) {
            self.look_up_collision_space(space)?;
        }
        let (raw_space, kind) = (self.collided_space_raw, self.collided_space_kind);
        if let SpaceKind::Hash { min_level, .. } = kind {
            // SAFETY: the space is live.
            let geoms = unsafe { ffi::dSpaceGetNumGeoms(raw_space) };
            if usize::try_from(geoms).unwrap_or(usize::MAX) > crate::limits::MAX_HASH_SPACE_GEOMS {
                return Err(too_many_hash_geoms(geoms));
            }
            if self.coordinate_bound() >= 0.5 * hash_limit(min_level) {
                self.check_hash_bounds(space, min_level)?;
            }
        }
        self.start_collision_pass();
        Ok((raw_space, kind))
    }

    /// The start of a collision pass: no contact points, no ray hits.
    #[inline(always)]
    pub(crate) fn start_collision_pass(&mut self) {
        if let Some(mut old) = self.collision.points.take() {
            old.clear();
            self.collision.spare_points.set(old);
        }
        self.collision.plain.0.out.len = 0;
        self.collision.ray_hits.clear();
    }

    /// Looks `space` up in the arena and keeps its ODE id and kind for the next
    /// collisions (in `collided_space`): spaces are never removed, so a handle found
    /// once is found for good, and the collisions that follow only compare handles.
    #[inline(never)]
    fn look_up_collision_space(&mut self, space: SpaceHandle) -> Result<()> {
        let (raw, kind) = self.space_data(space).map(|d| (d.raw, d.kind))?;
        (self.collided_space, self.collided_space_raw, self.collided_space_kind) = (space, raw, kind);
        let plain = matches!(kind, SpaceKind::Simple | SpaceKind::SweepAndPrune { .. });
        self.plain_space = if plain { space } else { SpaceHandle(crate::handle::RawHandle::NONE) };
        Ok(())
    }

    /// Whether every pair would take the plain path of the near callback: the
    /// callback in C (`guard.c`) does what [`World::near`] does for such pairs (no ray
    /// in the world, no contact feedback, no cylinder–cylinder or capsule–cylinder
    /// pair whose sizes need the libccd check).
    #[inline]
    pub(crate) fn plain_collision_applies(&self) -> bool {
        self.ray_geoms == 0 && !self.collision.feedback.on && self.convex_sizes.all_pairs_fine()
    }

    /// [`World::collide_with`] for default hooks when [`Self::plain_collision_applies`]:
    /// ODE's pairs go to the near callback in C, which creates the contact joints and
    /// records the points; their handles are looked up here, once per pair.
    fn collide_plain(&mut self, raw_space: ffi::dSpaceID, needs_lock: bool) -> Result<()> {
        let collided = {
            let _guard = needs_lock.then(lock_ode_global_state);
            // SAFETY: the space is live and its geoms are this world's; the parameters
            // hold this world and its contact group (live), the default contact, and
            // `scratch` with MAX_CONTACTS_LIMIT ≥ max_contacts entries (made with the
            // world); the records are guard.c's.
            unsafe { guard::collide_plain(raw_space, &mut self.collision.plain.0) }
        };
        if let Err(failure) = collided {
            return Err(self.collision_failed(failure));
        }
        self.end_plain_collision()
    }

    /// A failure inside `dSpaceCollide`: the space stays locked, the world is poisoned.
    #[cold]
    pub(crate) fn collision_failed(&mut self, failure: OdeFailure) -> Error {
        self.poison(Poison::Collide(failure.message.clone()));
        Error::OdeInternal { during: "collision", message: failure.message }
    }

    /// After a plain collision that ODE finished: an `Err` (and no contact joint) when
    /// a pair stopped it; else its recorded points become [`ContactPoint`]s.
    #[inline(always)]
    pub(crate) fn end_plain_collision(&mut self) -> Result<()> {
        if self.collision.plain.0.stopped == 0 { Ok(()) } else { Err(self.plain_collision_stopped()) }
    }

    /// The error of a plain collision that a pair stopped; its contact joints are
    /// destroyed.
    #[cold]
    fn plain_collision_stopped(&mut self) -> Error {
        self.clear_contacts();
        let plain = &self.collision.plain.0;
        if plain.stopped as u32 != ffi::ODESYS_PLAIN_PAIR_FAILED {
            return Error::Ode("record the contact points (out of memory)");
        }
        // The pair failed, so its report was written.
        let failure = OdeFailure::from_raw(&plain.pair_failure);
        let name = |raw| match geom_slot_in(&self.geoms, raw) {
            Some((h, _)) => h.to_string(),
            None => String::from("a geom"),
        };
        Error::OdeInternal {
            during: "collision",
            message: format!("colliding {} and {}: {}", name(plain.failed[0]), name(plain.failed[1]), failure.message),
        }
    }

    /// ODE's hash space puts each geom in integer cells of size `2^level`, at least
    /// `2^min_level`; a coordinate beyond `i32::MAX` cells aborts inside ODE
    /// (`aabbBound`). Refuse such a geom before colliding (O(geoms), hash spaces only).
    fn check_hash_bounds(&self, space: SpaceHandle, min_level: i32) -> Result<()> {
        let limit = hash_limit(min_level);
        for (h, g) in self.geoms.iter() {
            if g.space != space || matches!(g.shape, crate::shape::Shape::Plane { .. }) {
                continue;
            }
            let mut a = [0.0; 6];
            // SAFETY: the geom is live; `a` holds 6 reals.
            unsafe { ffi::dGeomGetAABB(g.raw, a.as_mut_ptr()) };
            if a.iter().any(|c| c.is_nan() || c.abs() >= limit) {
                return Err(Error::OutOfRange {
                    what: "a shape's position in a hash space",
                    detail: format!(
                        "must be within ±{limit:e} m for min_level {min_level} (use a simple space, or a larger min_level); {} reaches {:e} m",
                        GeomHandle(h),
                        a.iter().fold(0.0_f64, |m, c| m.max(c.abs()))
                    ),
                });
            }
        }
        Ok(())
    }

    /// The handle and data of a geom that ODE reports (`None`: not this world's). The
    /// data is read where it is needed, not copied out up front: most pairs stop at
    /// the first checks.
    #[inline]
    fn geom_slot(&self, raw: ffi::dGeomID) -> Option<(GeomHandle, &super::geom::GeomData)> {
        geom_slot_in(&self.geoms, raw)
    }

    /// One candidate pair: everything the near callback does, in Rust. `Err` when the
    /// pair's collider failed inside ODE.
    fn near<H: CollisionHooks + ?Sized>(
        &mut self,
        hooks: &mut H,
        o1: ffi::dGeomID,
        o2: ffi::dGeomID,
    ) -> Result<(), PairFailure> {
        let (Some((g1, d1)), Some((g2, d2))) = (self.geom_slot(o1), self.geom_slot(o2)) else {
            log::error!("collision reported a geom that this world does not own; pair skipped");
            return Ok(());
        };
        let (shape1, shape2, b1, b2) = (&d1.shape, &d2.shape, d1.body_raw, d2.body_raw);
        let ray1 = matches!(shape1, crate::shape::Shape::Ray { .. });
        let ray2 = matches!(shape2, crate::shape::Shape::Ray { .. });
        // SAFETY: the bodies of the pair's geoms, live or null (static geoms).
        if !unsafe { pair_may_touch(b1, b2, ray1, ray2) } {
            return Ok(());
        }
        if let Some(ratio) = convex_pair_ratio(shape1, shape2)
            && ratio > crate::limits::MAX_CONVEX_PAIR_RATIO
        {
            return Err(PairFailure::Refused(g1, g2, ratio));
        }
        // SAFETY: both geoms are live.
        if !ray1 && !ray2 && unsafe { above_plane(o1, shape1, o2) || above_plane(o2, shape2, o1) } {
            return Ok(());
        }
        let pair = GeomPair { geom1: g1, geom2: g2, body1: d1.body, body2: d2.body };
        let Some(surface) = self.pair_surface(hooks, &pair, ray1 || ray2) else {
            return Ok(());
        };
        let (asked, max) = self.contact_counts(&surface);
        let scratch = &mut self.collision.scratch;
        // SAFETY: both geoms are live; `scratch` holds MAX_CONTACTS_LIMIT ≥ `asked`
        // entries of dContactGeom.
        let found = match unsafe { guard::collide(o1, o2, asked as i32, scratch.as_mut_ptr()) } {
            Ok(n) => n.min(asked),
            Err(failure) => return Err(PairFailure::Ode(g1, g2, failure)),
        };
        let n = if found > max { super::spread::keep_spread(&mut scratch[..found], max) } else { found };
        match surface {
            PairSurface::Ray => {
                let (ray, other, flip) = if ray1 { (g1, g2, false) } else { (g2, g1, true) };
                self.record_ray_hits(ray, other, flip, n);
            }
            PairSurface::Default | PairSurface::Chosen(..) => {
                let state = &mut self.collision;
                // A chosen surface is written once for the pair; each point only changes
                // the geometry (ODE copies the whole dContact into the joint it creates).
                let mut chosen;
                let contact = match surface {
                    PairSurface::Chosen(surface, _) => {
                        chosen = ffi::dContact { surface, geom: ffi::dContactGeom::default(), fdir1: [0.0; 4] };
                        &mut chosen
                    }
                    _ => &mut state.plain.0.contact,
                };
                // SAFETY: world and contact group are live; the bodies are those of the
                // pair's geoms, live or null (static environment).
                unsafe {
                    create_contacts(
                        self.raw,
                        self.contact_group,
                        &pair,
                        (b1, b2),
                        contact,
                        &state.scratch[..n],
                        &mut state.building,
                        state.feedback.on.then_some(&mut state.feedback),
                    )
                };
            }
        }
        Ok(())
    }

    /// How many points to ask the collider for, and how many to keep. A surface the
    /// hooks chose keeps its most points spread over all the collider finds (`spread`);
    /// the default surface keeps ODE's first, as the plain collision in C does.
    #[inline]
    fn contact_counts(&self, surface: &PairSurface) -> (usize, usize) {
        match surface {
            PairSurface::Ray => (MAX_CONTACTS_LIMIT, MAX_CONTACTS_LIMIT),
            PairSurface::Default => {
                let max = self.collision.default_surface.max_contacts;
                (max, max)
            }
            PairSurface::Chosen(_, max) => (MAX_CONTACTS_LIMIT, *max),
        }
    }

    /// The surface of a pair's contacts: a ray's hits, the default surface, or the one
    /// the hooks choose; `None` when the hooks skip the pair (or give an invalid
    /// surface, which is logged).
    #[inline]
    fn pair_surface<H: CollisionHooks + ?Sized>(
        &self,
        hooks: &mut H,
        pair: &GeomPair,
        ray: bool,
    ) -> Option<PairSurface> {
        if ray {
            Some(PairSurface::Ray)
        } else if hooks.always_default() {
            Some(PairSurface::Default)
        } else {
            match hooks.contact_surface(pair, &self.collision.default_surface) {
                Some(s) if s.validate().is_ok() => Some(PairSurface::Chosen(s.to_ode(), s.max_contacts)),
                Some(s) => {
                    log::error!("contact hooks returned an invalid surface {s:?}; pair skipped");
                    None
                }
                None => None,
            }
        }
    }

    /// Records the first `n` points of the scratch buffer as hits of `ray` on `other`
    /// (the normals turned when ODE gave the ray second).
    fn record_ray_hits(&mut self, ray: GeomHandle, other: GeomHandle, flip: bool, n: usize) {
        for c in self.collision.scratch[..n].iter().filter(|c| contact_is_finite(c)) {
            let normal = convert::vector_from_ode(&c.normal);
            self.collision.ray_hits.push(RayHit {
                ray,
                other,
                position: convert::point_from_ode(&c.pos),
                normal: if flip { -normal } else { normal },
                distance: c.depth,
            });
        }
    }
}

/// One contact joint per finite contact point, with `contact`'s surface, attached to
/// `bodies`; each point is recorded in `out`, and given a feedback buffer of
/// `feedback` (at its index in `out`) when there is one.
///
/// # Safety
/// `world` and `group` are live; the bodies are live or null.
#[inline]
#[allow(clippy::too_many_arguments)]
unsafe fn create_contacts(
    world: ffi::dWorldID,
    group: ffi::dJointGroupID,
    pair: &GeomPair,
    bodies: (ffi::dBodyID, ffi::dBodyID),
    contact: &mut ffi::dContact,
    points: &[ffi::dContactGeom],
    out: &mut Vec<ContactPoint>,
    mut feedback: Option<&mut ContactFeedback>,
) {
    // A kinematic body at rest is attached as the world (`odesys_contact_body`), as the
    // plain collision does.
    // SAFETY: the bodies are live or null (the caller's contract).
    let attached = unsafe { (ffi::odesys_contact_body(bodies.0), ffi::odesys_contact_body(bodies.1)) };
    // Between two bodies that cannot move (kinematic at rest, or one static) a contact
    // joint would do nothing but join them in an island: its points are recorded only.
    let joined = !(attached.0.is_null() && attached.1.is_null());
    // Colliders given degenerate geometry (a deep overlap of tiny shapes) can return a
    // NaN normal, which would turn the whole step into NaN.
    for c in points.iter().filter(|c| contact_is_finite(c)) {
        // ODE copies the whole dContact into the joint it creates: only the geometry
        // changes from one point to the next.
        contact.geom = *c;
        if !joined {
            if let Some(feedback) = feedback.as_deref_mut() {
                // No joint: no force (its buffer zeroed).
                feedback.slot(out.len(), true);
            }
        } else {
            // SAFETY: the caller's contract; `contact` is fully initialised.
            unsafe {
                let j = ffi::dJointCreateContact(world, group, contact);
                ffi::dJointAttach(j, attached.0, attached.1);
                if let Some(feedback) = feedback.as_deref_mut() {
                    // The buffer stays in place while the world lives (boxed block), and
                    // the joint is destroyed at the end of the step.
                    ffi::dJointSetFeedback(j, feedback.slot(out.len(), !attached.0.is_null()));
                }
            }
        }
        out.push(ContactPoint {
            pair: *pair,
            position: convert::point_from_ode(&c.pos),
            normal: convert::vector_from_ode(&c.normal),
            depth: c.depth,
            force: Vector3::zeros(),
        });
    }
}

/// Position, normal and depth all finite, and the normal not zero.
#[inline]
fn contact_is_finite(c: &ffi::dContactGeom) -> bool {
    let (p, n) = (&c.pos, &c.normal);
    // A NaN or an infinity anywhere makes the sum NaN or infinite (the values are far
    // too small to overflow a finite sum).
    let sum = p[0] + p[1] + p[2] + n[0] + n[1] + n[2] + c.depth;
    sum.is_finite() && n[0] * n[0] + n[1] * n[1] + n[2] * n[2] > 0.5
}

unsafe extern "C" fn near_callback<H: CollisionHooks + ?Sized>(data: *mut c_void, o1: ffi::dGeomID, o2: ffi::dGeomID) {
    // SAFETY: `data` is the `NearContext<H>` that `collide_with::<H>` passed to
    // dSpaceCollide, alive and not otherwise borrowed for the duration of the call.
    let ctx = unsafe { &mut *data.cast::<NearContext<'_, H>>() };
    if ctx.panic.is_some() || ctx.failure.is_some() {
        return;
    }
    let world = &mut *ctx.world;
    let hooks = &mut *ctx.hooks;
    match catch_unwind(AssertUnwindSafe(|| world.near(hooks, o1, o2))) {
        Ok(Ok(())) => {}
        Ok(Err(failure)) => ctx.failure = Some(failure),
        Err(payload) => ctx.panic = Some(payload),
    }
}
