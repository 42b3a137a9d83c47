//! # drillpath
//!
//! Drillstring mechanics and well-trajectory prediction: a whole-string 3D quasi-static finite
//! element model with contact and friction against the borehole wall, after Zhang, Chen & Liu
//! (1990), "Finite element analysis of the contact and friction of a whole drillpipe string",
//! a soft-string torque-and-drag model beside it, and a forward-marching trajectory predictor
//! with an anisotropic bit-rock law. `docs/theory.md` gives the mechanics and the numerical
//! methods with their verification references; `docs/guide.md` is the user's manual;
//! `docs/architecture.md` states the rules this map follows (checked by
//! `tests/verification/architecture.rs`).
//!
//! ## The pipeline
//!
//! survey stations -> hole axis by minimum curvature ([`geometry::WellPath`]) and hole sizes
//! ([`geometry::HoleSize`]) -> the string from the bit up ([`string::DrillString`]) -> a
//! validated [`case::Case`] (read by [`io::case_toml::load_case`]) -> a model of the string in
//! the hole at a fidelity level ([`models::levels`]: the soft string
//! [`models::softstring`], the stiff bottom-hole assembly or whole string [`models::fem`]) ->
//! bit forces and tilt -> the bit-rock law ([`predict::law`]) and the march
//! ([`predict::march`]).
//!
//! ## Layers
//!
//! Each module imports only from the layers below it:
//!
//! | layer | modules | job |
//! |---|---|---|
//! | edges | [`cli`] | parse arguments into validated settings, check the output paths against the inputs, call one library function, write all outputs together and print |
//! | | [`report`] | summaries (JSON, CSV), stdout text and HTML reports drawn from typed results |
//! | | [`analytical`] | closed-form references for the tests (independent of the models) |
//! | | [`io`] | files in: case TOML, survey CSV or text report, measured loads |
//! | workflows | [`predict`], [`loads`] | prediction, tracking, back-analysis, calibration; the torque-and-drag chart |
//! | mechanics | [`models`] | soft string, buckling, stiff FEM, fidelity levels, diagnostics, checks against what a real string can do (yield, lock-up) |
//! | the case | [`case`] | well, string, mud, operation, bit-rock law, solver and fidelity settings |
//! | data | [`geometry`], [`string`] | hole axis and sizes; components and sections |
//! | base | [`units`], [`error`], [`numerics`] | quantities and SI factors; input errors; least squares |
//!
//! ## One entry point per command
//!
//! | command | library call | typed result |
//! |---|---|---|
//! | `survey` | [`io::case_toml::load_case`] or [`io::survey::read_survey`] | [`geometry::WellPath`] |
//! | `solve` | [`models::string_solve::solve_string`] | [`models::string_solve::StringSolve`] |
//! | `predict` | [`predict::forecast::forecast`] | [`predict::forecast::Forecast`] |
//! | `backanalyze` | [`predict::backanalysis::plan`], [`predict::backanalysis::run`] | [`predict::backanalysis::Backanalysis`] |
//! | `loads` | [`loads::run::plan`], [`loads::run::run`] | [`loads::run::Chart`] |
//!
//! ## Units
//!
//! SI inside (m, N, N.m, Pa, kg/m3, rad, s); names carry the unit where it could be read two
//! ways (`md_m`, `wob_n`, `inc_rad`). Conversions happen only at the edges: [`units`] parses
//! the user's quantities, [`report`] writes the interface's column names (which carry units).
//!
//! ## Example
//!
//! Solve the stiff bottom-hole assembly of an example well and read the bit's side forces:
//!
//! ```
//! use drillpath::case::fidelity::{choose, Fidelity, Level, Purpose};
//! use drillpath::io::case_toml::{load_case, CaseOverrides};
//! use drillpath::models::fem::solve::SolveControls;
//! use drillpath::models::levels::run;
//!
//! let file = concat!(env!("CARGO_MANIFEST_DIR"), "/wells/j-shape/case.toml");
//! let case = load_case(std::path::Path::new(file), &CaseOverrides::default()).unwrap();
//! let choice = choose(Fidelity::Level(Level::Bha), Purpose::Solve);
//! let result = run(&case, choice, &SolveControls::from_settings(&case.solver)).unwrap();
//! assert!(result.converged);
//! let bit = result.bit.unwrap();
//! println!("build {:.3} kN, walk {:.3} kN", bit.build_force_n / 1e3, bit.walk_force_n / 1e3);
//! ```

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
