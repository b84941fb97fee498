//! The reference scenes three times: in plain C against native ODE ([`native`],
//! compiled from `c/` by this crate's build script), through `ars-core`'s `World`
//! ([`world_scenes`]) and through its `Simulation` ([`sim_scenes`]), with the same ODE
//! calls in the same order. The tests and benchmarks of the root
//! crate hold the Rust port against native ODE with them, bit for bit. Not published:
//! a dev-dependency only, so that no user of `ars` compiles test C.

pub mod native;
pub mod sim_scenes;
pub mod world_scenes;

pub use native::{BodyState, CScene, drop_pile_position};
pub use sim_scenes::SimScene;
pub use world_scenes::RustScene;
