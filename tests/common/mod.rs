//! The reference scenes twice: in C against native ODE (`tests/c`, built by the root
//! `build.rs`) and through `ars-core`, with the same ODE calls in the same order.
//! Shared by the native-comparison tests and the benchmarks.
#![allow(dead_code)]

pub mod native;
pub mod scenes;
