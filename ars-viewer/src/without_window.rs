//! The window's entry points in a build without the `window` feature: each says so
//! ([`ViewerError::NotBuilt`]) before anything opens. Off-screen rendering, the
//! recorders and the replay are the same in every build.

use std::time::Duration;

use ars_core::{Program, WindowSettings};

use crate::ViewerOptions;
use crate::driver::Driver;
use crate::error::{Result, ViewerError};
use crate::video::WindowVideo;
use crate::window::WindowReport;

/// What every window entry point returns in this build.
fn not_built<T>() -> Result<T> {
    Err(ViewerError::NotBuilt { feature: "window", what: "a window" })
}

/// As the window's `run_window`: [`ViewerError::NotBuilt`].
pub(crate) fn run_window<P: Program>(_: &mut P, _: &ViewerOptions) -> Result<ars_core::Simulation> {
    not_built()
}

/// As the window's `run_window_until`: [`ViewerError::NotBuilt`].
pub(crate) fn run_window_until<P: Program>(
    _: &mut P,
    _: &ViewerOptions,
    _: Option<Duration>,
) -> Result<(ars_core::Simulation, WindowReport)> {
    not_built()
}

/// As the window's `drive_window`: [`ViewerError::NotBuilt`].
pub(crate) fn drive_window<D: Driver>(
    _: &mut D,
    _: &WindowSettings,
    _: &ViewerOptions,
    _: Option<Duration>,
    _: Option<&mut WindowVideo>,
) -> Result<WindowReport> {
    not_built()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_window_in_a_build_without_it_is_not_built_naming_the_feature() {
        let mut sim = ars_core::Simulation::new().unwrap();
        let mut driven = crate::driver::BareSimulation(&mut sim);
        // Whether or not a display is named.
        let error = crate::run_window(&mut driven, &WindowSettings::default(), None).unwrap_err();
        assert!(matches!(error, ViewerError::NotBuilt { feature: "window", .. }), "{error:?}");
        assert!(error.to_string().contains("`window` feature"), "{error}");
        struct Empty;
        impl ars_core::Hooks for Empty {}
        impl Program for Empty {
            fn create_sim_objects(&mut self, _: &mut ars_core::Simulation) -> ars_core::Result<()> {
                Ok(())
            }
        }
        use crate::ProgramViewer;
        let error = Empty.show().err().unwrap();
        assert!(matches!(error, ViewerError::NotBuilt { feature: "window", .. }), "{error:?}");
    }
}
