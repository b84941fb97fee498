//! Cause: ODE reports warnings through its message handler, which called the `log`
//! facade unguarded; a logger that panics made the panic reach C ("panic in a
//! function that cannot unwind"): SIGABRT. Now the handler contains the panic.

use std::sync::atomic::{AtomicU32, Ordering};

use ars_core::nalgebra::Point3;
use ars_core::*;

static ODE_MESSAGES: AtomicU32 = AtomicU32::new(0);

struct PanickingLogger;

impl log::Log for PanickingLogger {
    fn enabled(&self, _: &log::Metadata<'_>) -> bool {
        true
    }
    fn log(&self, record: &log::Record<'_>) {
        if record.target() == "ode" {
            ODE_MESSAGES.fetch_add(1, Ordering::Relaxed);
            panic!("this logger panics on ODE's messages");
        }
    }
    fn flush(&self) {}
}

#[test]
fn a_panicking_logger_does_not_abort() {
    log::set_logger(&PanickingLogger).expect("no other logger in this test binary");
    log::set_max_level(log::LevelFilter::Trace);
    let mut world = World::new(); // installs ARS's handlers in ODE
    // ODE's warnings (such as "LCP internal error, s <= 0" from a degenerate contact
    // problem) all go through `dMessage`; send one the same way.
    // SAFETY: ODE is initialised (by `World::new`); the format and its argument are
    // NUL-terminated strings that outlive the call.
    unsafe { ode_sys::dMessage(3, c"%s".as_ptr(), c"a warning from ODE".as_ptr()) };
    assert_eq!(ODE_MESSAGES.load(Ordering::Relaxed), 1, "the message reached the logger, which panicked");
    // And the process, the world and ODE go on.
    let b = world.insert_body(BodyBuilder::new().position(Point3::new(0.0, 1.0, 0.0))).unwrap();
    world.step(0.0004).unwrap();
    assert!(world.body(b).unwrap().linear_velocity().y < 0.0);
}
