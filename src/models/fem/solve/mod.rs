//! Static solution of the stiff string with contact and friction.
//!
//! [`solve`] runs the scheme the controls name:
//! - [`interior_point_newton`]: Newton iterations with the consistent co-rotational tangent,
//!   the contact forces of each step from an interior-point complementarity solve
//!   (`method = "newton"`, the default);
//! - [`modified_newton_gap_forces`]: the seed paper's modified Newton with gap springs and
//!   gradient-updated gap forces (`method = "paper"`, eq. 15).
//!
//! Their parts, one job per file:
//! - [`start`]: the start heuristics (stretch, soft-string contact sides, smoothing, wind-up);
//! - [`interior_point`]: the contact subproblem of one Newton step (interior point, active-set
//!   step);
//! - [`contacts`]: the managed gaps and their linearized contacts;
//! - [`pins`]: the zero-clearance gaps held exactly;
//! - [`matrix_and_factor`]: the band tangent and its factorization;
//! - [`hook_load_system`]: the bordered hook-load system;
//! - [`convergence`]: load scale, residual norms and convergence criteria;
//! - [`step_caps`]: the lateral and bending-rotation caps of a step;
//! - [`gap_springs`]: the modified Newton's gap springs, lagged friction and arc step;
//! - [`controls`], [`solution`]: what a solve takes and returns.
//!
//! In the solvers `du` is the displacement increment of a Newton step: 6 entries per node (3
//! translations, m; 3 rotations, rad) in DOF order (surface first), node bases.

pub mod contacts;
pub mod controls;
pub mod convergence;
pub mod gap_springs;
pub mod hook_load_system;
pub mod interior_point;
pub mod interior_point_newton;
pub mod matrix_and_factor;
pub mod modified_newton_gap_forces;
pub mod pins;
pub mod solution;
pub mod start;
pub mod step_caps;
pub mod toolface;

pub use controls::SolveControls;
pub use interior_point_newton::{solve_interior_point, solve_interior_point_from};
pub use modified_newton_gap_forces::solve_modified_newton;
pub use solution::{Solution, SolveError, SolveStats};

use crate::case::Method;
use crate::models::fem::model::Model;

/// Solve the static problem of `model` from its start with the contact scheme of `ctl`
/// ([`solve_interior_point`] or [`solve_modified_newton`]).
pub fn solve(model: &Model, ctl: &SolveControls) -> Result<Solution, SolveError> {
    match ctl.method {
        Method::Paper => solve_modified_newton(model, ctl),
        Method::Newton => solve_interior_point(model, ctl),
    }
}
