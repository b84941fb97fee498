//! Containing panics of user code (hooks, sensors, controllers) so that none unwinds
//! through the simulation or into C.

use std::any::Any;
use std::panic::{AssertUnwindSafe, catch_unwind};

use crate::error::{Error, Result};

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
