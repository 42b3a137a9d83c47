//! Finite element model of the whole string.

pub mod band;
pub mod sparse_faer;
