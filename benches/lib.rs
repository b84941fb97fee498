//! ARS's benchmarks live in `benches/` (`cargo bench -p ars-benches --bench NAME`):
//! `native_comparison` (criterion: Rust against native ODE, in seconds), `step_cost`
//! (callgrind: instructions per step, Rust against native ODE), `scale` (ms per step
//! from 1,000 to 100,000 spheres in each broad-phase space) and `viewer_fps` (the
//! viewer's frame rates without a GPU). This library is empty: the package exists so
//! that building the demo or the tests never builds criterion.
