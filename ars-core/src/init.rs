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
use std::ffi::{CStr, c_char, c_int};
use std::sync::{Mutex, MutexGuard, Once};

use ode_sys as ffi;

static INIT: Once = Once::new();
static GLOBAL_STATE: Mutex<()> = Mutex::new(());

thread_local! {
    static THREAD_READY: Cell<bool> = const { Cell::new(false) };
}

/// Makes ODE ready for use on the calling thread: initialises the library once per
/// process and allocates ODE's per-thread data once per thread. Cheap after the first
/// call; every constructor of the safe layer calls it.
pub fn ensure_ode_ready() {
    INIT.call_once(|| {
        // SAFETY: first and only initialisation of the library; the handlers are
        // `extern "C"` functions that never unwind.
        let ok = unsafe {
            let ok = ffi::dInitODE2(0);
            ffi::dSetMessageHandler(Some(on_ode_message));
            ffi::dSetDebugHandler(Some(on_ode_debug));
            ffi::dSetErrorHandler(Some(on_ode_error));
            ok
        };
        assert!(ok != 0, "ODE failed to initialise (dInitODE2)");
        // SAFETY: the configuration string is NUL-terminated and static.
        let double = unsafe { ffi::dCheckConfiguration(c"ODE_double_precision".as_ptr()) };
        assert!(double == 1, "the loaded libode is not double precision");
    });
    THREAD_READY.with(|ready| {
        if !ready.get() {
            // SAFETY: ODE is initialised (above); allocating the current thread's data
            // is what ODE requires before a thread uses it.
            let ok = unsafe { ffi::dAllocateODEDataForThread(ffi::dAllocateODEDataFlags_dAllocateMaskAll as u32) };
            assert!(ok != 0, "ODE failed to allocate its per-thread data");
            ready.set(true);
        }
    });
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

/// Formats ODE's printf-style message.
///
/// # Safety
/// `msg` must be a valid format string and `ap` the matching `va_list`, as ODE passes.
unsafe fn format_message(msg: *const c_char, ap: *mut ffi::__va_list_tag) -> String {
    if msg.is_null() {
        return String::from("(no message)");
    }
    let mut buf = [0 as c_char; 1024];
    // SAFETY: the buffer is writable for its full length and vsnprintf NUL-terminates
    // within it; the format and va_list come from ODE (caller's contract).
    let n = unsafe { ffi::vsnprintf(buf.as_mut_ptr(), buf.len() as _, msg, ap) };
    if n < 0 {
        // SAFETY: ODE's format strings are NUL-terminated.
        return unsafe { CStr::from_ptr(msg) }.to_string_lossy().into_owned();
    }
    // SAFETY: vsnprintf wrote a NUL-terminated string into `buf`.
    unsafe { CStr::from_ptr(buf.as_ptr()) }.to_string_lossy().into_owned()
}

unsafe extern "C" fn on_ode_message(num: c_int, msg: *const c_char, ap: *mut ffi::__va_list_tag) {
    // SAFETY: arguments as ODE passes them to its message handler.
    let text = unsafe { format_message(msg, ap) };
    log::warn!(target: "ode", "ODE message {num}: {text}");
}

unsafe extern "C" fn on_ode_debug(num: c_int, msg: *const c_char, ap: *mut ffi::__va_list_tag) {
    // SAFETY: arguments as ODE passes them to its debug handler.
    let text = unsafe { format_message(msg, ap) };
    fatal("internal error", num, &text);
}

unsafe extern "C" fn on_ode_error(num: c_int, msg: *const c_char, ap: *mut ffi::__va_list_tag) {
    // SAFETY: arguments as ODE passes them to its error handler.
    let text = unsafe { format_message(msg, ap) };
    fatal("error", num, &text);
}

/// ODE terminates the process when an error or debug handler returns; do it here,
/// with the message, rather than return into ODE.
fn fatal(kind: &str, num: c_int, text: &str) -> ! {
    log::error!(target: "ode", "ODE {kind} {num}: {text}");
    eprintln!("ODE {kind} {num}: {text}\nThis is a bug in ars-core: invalid input reached ODE. Aborting.");
    std::process::abort();
}
