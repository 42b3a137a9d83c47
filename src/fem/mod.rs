//! Finite element model of the whole string.

pub mod band;
pub mod band_lu;
pub mod beam;
pub mod bha;
pub mod buffers;
pub mod corotational;
pub mod mesh;
pub mod model;
pub mod paper;
pub mod results;
pub mod rotation;
pub mod solve;
pub mod sparse_faer;
