//! # drillpath
//!
//! Drillstring mechanics and well-trajectory prediction, after Zhang, Chen & Liu (1990),
//! "Finite element analysis of the contact and friction of a whole drillpipe string".
//!
//! Pipeline: survey stations -> [`geometry::WellPath`] (minimum curvature) -> drill string
//! ([`string`]) -> whole-string FEM with contact-friction gap elements ([`fem`]) -> bit forces
//! and tilt -> bit-rock law and forward-marching prediction.
//!
//! Units: SI inside (m, N, N.m, Pa, kg/m3, rad, s). Conversions only at the edges: [`units`]
//! parses user quantities, [`report`] writes the interface's column names (which carry units).

#![warn(missing_docs)]

pub mod accuracy;
pub mod analytical;
pub mod buckling_marks;
pub mod case;
pub mod cli;
pub mod contact;
pub mod diagnose;
pub mod error;
pub mod fem;
pub mod fidelity;
pub mod geometry;
pub mod io;
pub mod loads;
pub mod predict;
pub mod report;
pub mod softstring;
pub mod string;
pub mod units;
pub mod warm;

pub use error::{InputError, Location};
pub use geometry::{Station, Survey};
