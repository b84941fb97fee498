//! ODE's process-wide initialisation, its per-thread data and its message handlers.
//!
//! ODE is initialised once per process (`dInitODE2`), and every thread that calls into
//! ODE first allocates ODE's per-thread data (`dAllocateODEDataForThread`). ODE's
//! messages (warnings) go to [`log::warn!`]. ODE's errors and internal-assertion
//! failures are fatal inside ODE itself (it calls `exit`/`abort` once the handler
//! returns): the handlers log them and abort with the message, and the safe layer
//! validates its inputs so that no call can reach them.
//!
//! The Debian build of ODE 0.16 is not built with `ODE_EXT_mt_collisions`, so its
//! trimesh collider cache and its random number generator are process-wide:
//! [`lock_ode_global_state`] serialises the calls that use them (collision of worlds
//! holding triangle meshes, and QuickStep) across threads.

use std::cell::Cell;
use std::sync::{Mutex, MutexGuard, Once};

use ode_sys as ffi;

static INIT: Once = Once::new();
static GLOBAL_STATE: Mutex<()> = Mutex::new(());

thread_local! {
    /// Set once ODE is initialised and this thread's data is allocated.
    static THREAD_READY: Cell<bool> = const { Cell::new(false) };
}

/// Makes ODE ready for use on the calling thread: initialises the library once per
/// process and allocates ODE's per-thread data once per thread. Cheap after the first
/// call (one thread-local flag, read at every collision); every constructor of the
/// safe layer calls it.
#[inline]
pub fn ensure_ode_ready() {
    // The flag is set only once both are done, so that the process-wide `Once` is not
    // consulted again on a thread that is ready.
    if !THREAD_READY.get() {
        prepare_thread();
    }
}

/// The slow path of [`ensure_ode_ready`]: the process-wide initialisation (once), then
/// this thread's data.
#[cold]
#[inline(never)]
fn prepare_thread() {
    INIT.call_once(|| {
        // SAFETY: first and only initialisation of the library.
        let ok = unsafe { ffi::dInitODE2(0) };
        crate::guard::install_handlers();
        assert!(ok != 0, "ODE failed to initialise (dInitODE2)");
        // SAFETY: ODE is initialised (above) and no other thread uses it yet (this is
        // the process-wide `Once`); registering the class writes ODE's global tables.
        let hull_class = unsafe { ffi::odesys_hull_register() };
        assert!(hull_class >= 0, "ODE refused the convex hull geom class");
        // SAFETY: the configuration string is NUL-terminated and static.
        let double = unsafe { ffi::dCheckConfiguration(c"ODE_double_precision".as_ptr()) };
        assert!(double == 1, "the loaded libode is not double precision");
    });
    // SAFETY: ODE is initialised (above); allocating the current thread's data is what
    // ODE requires before a thread uses it.
    let ok = unsafe { ffi::dAllocateODEDataForThread(ffi::dAllocateODEDataFlags_dAllocateMaskAll as u32) };
    assert!(ok != 0, "ODE failed to allocate its per-thread data");
    THREAD_READY.set(true);
}

/// Serialises the ODE calls that touch process-wide state (the trimesh collider cache,
/// the random number generator). `ars-core` holds it for the duration of one
/// `dSpaceCollide` of a world with triangle meshes, or of one QuickStep.
///
/// Code that calls ODE's collision or QuickStep functions directly (through `ode-sys`)
/// while worlds run on other threads must hold it too. It is not reentrant: do not
/// call `ars-core` while holding it.
pub fn lock_ode_global_state() -> MutexGuard<'static, ()> {
    // A panic while the lock is held happens in Rust code only (the near callback
    // catches panics), never halfway through an ODE call, so the state is consistent.
    GLOBAL_STATE.lock().unwrap_or_else(|poisoned| poisoned.into_inner())
}
