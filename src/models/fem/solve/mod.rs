//! Static solution of the stiff string with contact and friction.
//!
//! - [`newton`]: Newton iterations with the consistent co-rotational tangent, the contact forces
//!   of each step from an interior-point complementarity solve (`method = "newton"`, the
//!   default);
//! - [`paper`]: the seed paper's modified Newton with gradient-updated gap forces
//!   (`method = "paper"`, eq. 15).
//!
//! [`solve`] runs the scheme the controls name.

pub mod newton;
pub mod paper;

pub use newton::{solve_ip_from, Solution, SolveControls, SolveError, SolveStats};

use crate::case::Method;
use crate::models::fem::model::Model;

/// Solve the static problem of `model` from its initial state with the contact scheme of
/// `ctl` ([`newton::solve_newton`] or [`paper::solve_paper`]).
pub fn solve(model: &Model, ctl: &SolveControls) -> Result<Solution, SolveError> {
    match ctl.method {
        Method::Paper => paper::solve_paper(model, ctl),
        Method::Newton => newton::solve_newton(model, ctl),
    }
}
