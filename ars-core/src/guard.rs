//! The last line of defence: ODE's internal errors become `Err`, not `abort`.
//!
//! Validation ([`limits`](crate::limits)) keeps bad input away from ODE, but a valid
//! scene can still drive ODE's solver into an internal assertion (a badly conditioned
//! constraint system that yields NaN, say), and ODE answers every internal error by
//! calling its process-wide debug or error handler and then `abort`/`exit`. The only
//! way on is a handler that does not return.
//!
//! ## Design
//! `ode-sys` compiles a small C shim (`ode-sys/src/guard.c`). It installs ODE's debug
//! and error handlers once, and wraps the four ODE entry points that run ODE's
//! numerical code: `dWorldStep`, `dWorldQuickStep`, `dSpaceCollide` and `dCollide`.
//! Each wrapper `setjmp`s into a frame of its own and arms it as the calling thread's
//! jump target; the handlers, when a target is armed, copy the message and `longjmp`
//! to it, and the wrapper returns "caught".
//!
//! ## Why the jumps are sound
//! - **No Rust frame is jumped over.** A target is armed only by a C wrapper, and only
//!   for the duration of the one ODE call it makes; the frames between the failure and
//!   the wrapper are ODE's and libccd's. `dSpaceCollide` calls back into Rust (the near
//!   callback): the C trampoline *disarms* the outer target for the duration of the
//!   callback, and the callback's own `dCollide` arms a nested target that jumps back
//!   into the nested wrapper, inside the callback. A failure in an unguarded ODE call
//!   made from Rust (none is known: their preconditions are checked) aborts as ODE
//!   would, rather than jump over Rust.
//! - **Targets are per thread** (`_Thread_local` in C); handlers are process-wide, so a
//!   failure on one thread never jumps into another thread's stack.
//! - **ODE's frames hold no resources that must be released for memory safety.** ODE
//!   is C++, and `longjmp` skips C++ destructors. On the step and collision paths the
//!   frames at an assertion hold plain data in the world's step arena, which is then
//!   never returned (a leak of about 64 KiB per caught failure); the hash space's
//!   collide holds `std::vector`s (leaked). The world's internal state is left
//!   half-updated: it is **poisoned** (see below), never stepped or collided again.
//! - **A poisoned world only gets dropped.** After a caught step failure the world
//!   refuses every further step, collision and change ([`Error::Poisoned`](crate::Error::Poisoned)); dropping it
//!   destroys its ODE objects as usual (measured: valgrind clean apart from the leak).
//!   After a caught `dSpaceCollide` failure the space stays locked inside ODE, and
//!   destroying or moving a geom of a locked space asserts: such a world is dropped
//!   without calling ODE at all (its ODE objects are leaked).
//!
//! - **The plain collision's near callback is C.** For a world that needs nothing
//!   of the Rust near callback (no rays, hooks or contact feedback; see
//!   `world/contact.rs`), `guard.c` runs its own callback: no Rust frame lies between
//!   the guard of `dSpaceCollide` and ODE at all, and each pair's `dCollide` still has
//!   a nested guard (a pair's failure is an `Err`, not a poisoned world).
//!   `odesys_guarded_collide_and_step` runs that collision and then `dWorldStep` under
//!   one guard, recording which of the two was running (`phase`, in memory) so that
//!   the world is poisoned the right way.
//!
//! Only ODE's self-threaded step implementation is used (each world has its own), so
//! every stage of a step runs on the calling thread, under its target.

use std::ffi::{CStr, c_char, c_int, c_void};
use std::panic::{AssertUnwindSafe, catch_unwind};

use ode_sys as ffi;

/// An internal error that ODE reported during a guarded call.
#[derive(Clone, Debug, PartialEq, Eq)]
pub(crate) struct OdeFailure {
    /// ODE's message number.
    pub(crate) number: i32,
    /// ODE's message.
    pub(crate) message: String,
}

impl OdeFailure {
    /// The failure a guard (or the plain near callback) recorded in `raw`.
    pub(crate) fn from_raw(raw: &ffi::odesys_failure) -> Self {
        // SAFETY: the C side always NUL-terminates the message within its buffer
        // (snprintf/vsnprintf); the buffer was zero-initialised before the call.
        let message = unsafe { CStr::from_ptr(raw.message.as_ptr()) }.to_string_lossy().into_owned();
        let kind = if raw.kind == ffi::ODESYS_FAILURE_ERROR as c_int { "error" } else { "internal assertion" };
        OdeFailure { number: raw.number, message: format!("{kind} {}: {message}", raw.number) }
    }
}

#[cfg(test)]
fn empty_failure() -> ffi::odesys_failure {
    ffi::odesys_failure { kind: 0, number: 0, message: [0; 512] }
}

/// Room for a failure report, written by the C side only when it catches one (so it
/// is not zeroed on the hot path).
type FailureSlot = std::mem::MaybeUninit<ffi::odesys_failure>;

/// The report of a caught failure.
///
/// # Safety
/// The C side returned `ODESYS_CAUGHT` for the call that was given `slot`, and so
/// wrote every field of it (`record` in guard.c).
unsafe fn caught(slot: &FailureSlot) -> OdeFailure {
    // SAFETY: the caller's contract: the slot is initialised.
    OdeFailure::from_raw(unsafe { slot.assume_init_ref() })
}

/// Installs the handlers (once per process, from `init`).
pub(crate) fn install_handlers() {
    // SAFETY: `report` is an `extern "C"` function that never unwinds.
    unsafe { ffi::odesys_install_handlers(Some(report)) };
}

/// ODE's warnings, and failures no guard caught (just before the C side aborts). A
/// panicking logger is contained here: nothing unwinds into C.
unsafe extern "C" fn report(kind: c_int, number: c_int, message: *const c_char) {
    let text = if message.is_null() {
        String::from("(no message)")
    } else {
        // SAFETY: the C side passes a NUL-terminated buffer that lives during the call.
        unsafe { CStr::from_ptr(message) }.to_string_lossy().into_owned()
    };
    let logged = catch_unwind(AssertUnwindSafe(|| {
        if kind == ffi::ODESYS_MESSAGE as c_int {
            log::warn!(target: "ode", "ODE message {number}: {text}");
        } else {
            log::error!(target: "ode", "ODE internal error {number} outside any guard: {text}");
        }
    }));
    if let Err(payload) = logged {
        // Dropping a panic payload can itself panic; leak it instead.
        std::mem::forget(payload);
    }
}

/// `dWorldStep` (or `dWorldQuickStep`) under a guard: `Ok(false)` when ODE reports that
/// it ran out of memory.
///
/// # Safety
/// `world` must be a live world whose step threading implementation is
/// self-threaded (or unset).
#[inline]
pub(crate) unsafe fn world_step(world: ffi::dWorldID, dt: f64, quick: bool) -> Result<bool, OdeFailure> {
    let mut failure = FailureSlot::uninit();
    // SAFETY: the caller's contract; `failure` outlives the call.
    let r = unsafe { ffi::odesys_guarded_world_step(world, dt, quick.into(), failure.as_mut_ptr()) };
    match r {
        // SAFETY: caught: the C side filled the slot.
        r if r == ffi::ODESYS_CAUGHT => Err(unsafe { caught(&failure) }),
        r => Ok(r == ffi::ODESYS_OK as c_int),
    }
}

/// `dSpaceCollide` under a guard.
///
/// # Safety
/// `space` must be live, and `callback` must accept `data` for the duration of the call;
/// the callback must not unwind.
#[inline]
pub(crate) unsafe fn space_collide(
    space: ffi::dSpaceID,
    data: *mut c_void,
    callback: unsafe extern "C" fn(*mut c_void, ffi::dGeomID, ffi::dGeomID),
) -> Result<(), OdeFailure> {
    let mut failure = FailureSlot::uninit();
    // SAFETY: the caller's contract; `failure` outlives the call.
    let r = unsafe { ffi::odesys_guarded_space_collide(space, data, Some(callback), failure.as_mut_ptr()) };
    // SAFETY: caught: the C side filled the slot.
    if r == ffi::ODESYS_CAUGHT { Err(unsafe { caught(&failure) }) } else { Ok(()) }
}

/// `dCollide` under a guard: the number of contacts written.
///
/// # Safety
/// Both geoms must be live; `contacts` must have room for `max` entries.
#[inline]
pub(crate) unsafe fn collide(
    o1: ffi::dGeomID,
    o2: ffi::dGeomID,
    max: c_int,
    contacts: *mut ffi::dContactGeom,
) -> Result<usize, OdeFailure> {
    let mut failure = FailureSlot::uninit();
    let mut count = 0;
    let stride = size_of::<ffi::dContactGeom>() as c_int;
    // SAFETY: the caller's contract; `failure` and `count` outlive the call.
    let r = unsafe { ffi::odesys_guarded_collide(o1, o2, max, contacts, stride, &mut count, failure.as_mut_ptr()) };
    // SAFETY: caught: the C side filled the slot.
    if r == ffi::ODESYS_CAUGHT { Err(unsafe { caught(&failure) }) } else { Ok(count.max(0) as usize) }
}

/// `dSpaceCollide` with the plain near callback of `guard.c` (ARS's near callback in
/// C for worlds without rays, collision hooks or contact feedback), under a guard. The
/// callback's own `dCollide` calls have nested guards: a pair's failure is not an
/// `Err` here but `plain.stopped == ODESYS_PLAIN_PAIR_FAILED`, with the pair in
/// `plain.failed` and ODE's report in `plain.pair_failure`.
///
/// # Safety
/// `space` must be live; every pointer in `plain` must be valid for the call (world
/// and contact group live, `scratch` with room for `max_contacts` entries, `out` a
/// record array that `guard.c` allocated or an empty one), and the space's geoms must
/// belong to `plain.world`.
#[inline]
pub(crate) unsafe fn collide_plain(
    space: ffi::dSpaceID,
    plain: &mut ffi::odesys_plain_collision,
) -> Result<(), OdeFailure> {
    let mut failure = FailureSlot::uninit();
    // SAFETY: the caller's contract; `failure` and `plain` outlive the call.
    let r = unsafe { ffi::odesys_guarded_collide_plain(space, plain, failure.as_mut_ptr()) };
    // SAFETY: caught: the C side filled the slot.
    if r == ffi::ODESYS_CAUGHT { Err(unsafe { caught(&failure) }) } else { Ok(()) }
}

/// What [`collide_and_step`] did.
#[derive(Clone, Copy, PartialEq, Eq)]
pub(crate) enum CollideStep {
    /// Collided and stepped; `false` when the step ran out of memory.
    Stepped(bool),
    /// Collided without stepping: the collision stopped early (see
    /// `odesys_plain_collision::stopped`) or made more contact points than the limit.
    NotStepped,
    /// ODE failed inside the collision (`dSpaceCollide`): [`collide_and_step_failure`]
    /// says how.
    CollideFailed,
    /// ODE failed inside the step (`dWorldStep`): [`collide_and_step_failure`] says
    /// how.
    StepFailed,
}

/// The plain collision (see [`collide_plain`]) and then `dWorldStep`, in one guarded
/// call: the step is taken when the collision went through and made at most
/// `contact_limit` contact points, and then the contact joints are destroyed.
///
/// # Safety
/// As [`collide_plain`]; moreover `plain.world` must be a live world whose step
/// threading implementation is self-threaded (or unset).
#[inline]
pub(crate) unsafe fn collide_and_step(
    space: ffi::dSpaceID,
    plain: &mut ffi::odesys_plain_collision,
    dt: f64,
    contact_limit: usize,
) -> CollideStep {
    (plain.space, plain.step_size, plain.contact_limit) = (space, dt, contact_limit);
    // SAFETY: the caller's contract; `plain` outlives the call.
    let r = unsafe { ffi::odesys_guarded_collide_and_step(plain) };
    match r {
        r if r == ffi::ODESYS_OK as c_int => CollideStep::Stepped(true),
        ffi::ODESYS_CAUGHT if plain.phase == ffi::ODESYS_PHASE_STEP as c_int => CollideStep::StepFailed,
        ffi::ODESYS_CAUGHT => CollideStep::CollideFailed,
        r if r == ffi::ODESYS_NOT_STEPPED as c_int => CollideStep::NotStepped,
        _ => CollideStep::Stepped(false),
    }
}

/// The failure that [`collide_and_step`] caught (when it returned
/// [`CollideStep::CollideFailed`] or [`CollideStep::StepFailed`]).
#[cold]
pub(crate) fn collide_and_step_failure(plain: &ffi::odesys_plain_collision) -> OdeFailure {
    // The C side wrote the report when it caught the failure (`record` in guard.c);
    // before any, the report is zeroed (an empty message).
    OdeFailure::from_raw(&plain.failure)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_ode_internal_error_under_a_guard_becomes_an_err() {
        crate::init::ensure_ode_ready();
        let mut failure = empty_failure();
        // SAFETY: the message is NUL-terminated; `failure` outlives the call.
        let r = unsafe { ffi::odesys_guarded_debug_report(7, c"provoked".as_ptr(), &mut failure) };
        assert_eq!(r, ffi::ODESYS_CAUGHT);
        let f = OdeFailure::from_raw(&failure);
        assert_eq!(f.number, 7);
        assert!(f.message.contains("provoked"), "{}", f.message);
        // The guard is disarmed again and works a second time on the same thread.
        let mut again = empty_failure();
        // SAFETY: as above.
        let r = unsafe { ffi::odesys_guarded_debug_report(8, c"again".as_ptr(), &mut again) };
        assert_eq!(r, ffi::ODESYS_CAUGHT);
        assert_eq!(OdeFailure::from_raw(&again).number, 8);
    }
}
