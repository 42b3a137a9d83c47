//! # drillpath
//!
//! Drillstring mechanics and well-trajectory prediction, after Zhang, Chen & Liu (1990),
//! "Finite element analysis of the contact and friction of a whole drillpipe string".
//!
//! Pipeline: survey stations -> [`geometry::WellPath`] (minimum curvature) -> drill string
//! ([`string`]) -> whole-string FEM with contact-friction gap elements ([`models::fem`]) -> bit forces
//! and tilt -> bit-rock law and forward-marching prediction.
//!
//! Units: SI inside (m, N, N.m, Pa, kg/m3, rad, s). Conversions only at the edges: [`units`]
//! parses user quantities, [`report`] writes the interface's column names (which carry units).

#![warn(missing_docs)]

pub mod analytical;
pub mod case;
pub mod cli;
pub mod error;
pub mod geometry;
pub mod io;
pub mod loads;
pub mod models;
pub mod numerics;
pub mod predict;
pub mod report;
pub mod string;
pub mod units;

pub use error::{InputError, Location};
pub use geometry::{Station, Survey};
