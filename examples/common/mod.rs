//! What the examples share: their command line and their plots.
#![allow(dead_code)]

pub mod args;
pub mod plot;
