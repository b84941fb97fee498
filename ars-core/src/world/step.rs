//! Stepping a [`World`]: the one-call collide-and-step path and its gate, the checks
//! before and after each step (forces, divergence, island sizes).

use ode_sys as ffi;

use super::{Poison, SpaceKind, Stepper, World};
use crate::error::{Error, Result};
use crate::guard;
use crate::handle::{BodyHandle, SpaceHandle};
use crate::init::{ensure_ode_ready, lock_ode_global_state};
use crate::limits;

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

impl World {
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
