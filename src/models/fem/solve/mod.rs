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
pub mod continuation;
pub mod controls;
pub mod convergence;
pub mod errors;
pub mod gap_springs;
pub mod helix;
pub mod hook_load_system;
pub mod interior_point;
pub mod interior_point_newton;
pub mod matrix_and_factor;
pub mod modified_newton_gap_forces;
pub mod pins;
pub mod reactive_turn;
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

/// Iterations of the direct interior-point solve before a WOB-driven model that has not
/// converged turns to the WOB continuation (cases that converge directly take 5-40).
pub const DIRECT_BEFORE_CONTINUATION: usize = 60;

/// Solve the static problem of `model` from its start with the contact scheme of `ctl`
/// ([`solve_interior_point`] or [`solve_modified_newton`]). A WOB-driven interior-point solve
/// that has not converged in [`DIRECT_BEFORE_CONTINUATION`] iterations turns to the WOB
/// continuation ([`continuation::solve_by_wob_continuation`], its own `max_iterations`, the
/// time left); if that does not reach the model's WOB, the direct solve resumes for the rest
/// of its iterations. [`SolveStats::wob_continuation_n`] says how far the path got.
pub fn solve(model: &Model, ctl: &SolveControls) -> Result<Solution, SolveError> {
    solve_unless(model, ctl, || false, |_| (None, SolveStats::default())).map(|(sol, _)| sol)
}

/// [`solve`], stopped after the direct solve's first [`DIRECT_BEFORE_CONTINUATION`] iterations
/// when they did not converge and `give_up` (asked only then) says no path can help (a string
/// that cannot be put on bottom at any WOB: every path would end with the surface pushing). A
/// model without a WOB path (running in, off bottom) asks `give_up` first and is then limited to
/// those iterations. Otherwise `early` runs on the direct solve that did not converge, before the
/// paths: its solution, if it returns one, is the answer, and its work (the returned statistics)
/// is added to the paths' where it does not. Returns the solution and whether it gave up.
pub fn solve_unless(
    model: &Model,
    ctl: &SolveControls,
    give_up: impl FnOnce() -> bool,
    early: impl FnOnce(&Solution) -> (Option<Solution>, SolveStats),
) -> Result<(Solution, bool), SolveError> {
    match ctl.method {
        Method::Paper => Ok((solve_modified_newton(model, ctl)?, false)),
        Method::Newton if !continuation::applies(model) => {
            let gave_up = give_up();
            let own = SolveControls {
                max_iterations: match gave_up {
                    true => ctl.max_iterations.min(DIRECT_BEFORE_CONTINUATION),
                    false => ctl.max_iterations,
                },
                ..*ctl
            };
            let sol = solve_interior_point(model, &own)?;
            let gave_up = gave_up && !sol.converged;
            Ok((sol, gave_up))
        }
        Method::Newton => {
            let first = SolveControls {
                max_iterations: ctl.max_iterations.min(DIRECT_BEFORE_CONTINUATION),
                ..*ctl
            };
            let direct = solve_interior_point(model, &first)?;
            if direct.converged || direct.stats.timed_out {
                return Ok((direct, false));
            }
            if give_up() {
                return Ok((direct, true));
            }
            let (kept, spent) = early(&direct);
            if let Some(sol) = kept {
                return Ok((sol, false));
            }
            let rest = SolveControls {
                time_limit_s: ctl.time_limit_s - spent.seconds,
                ..*ctl
            };
            let mut sol = continued(model, &rest, direct)?;
            sol.stats.add_work(&spent);
            sol.stats.damped_start_exhausted = spent.damped_start_exhausted;
            Ok((sol, false))
        }
    }
}

/// The continuation paths after the first iterations `direct` of `model`'s direct solve did
/// not converge: the WOB path, then (friction acting on a moving string) the friction path,
/// then the rest of the direct solve. The statistics count the work of every stage that ran.
fn continued(model: &Model, ctl: &SolveControls, direct: Solution) -> Result<Solution, SolveError> {
    let target = model.loads.wob_n;
    let left = |spent: f64| SolveControls {
        time_limit_s: ctl.time_limit_s - spent,
        ..*ctl
    };
    // the work of the paths that did not converge
    let mut paths = SolveStats::default();
    let wob_path = continuation::solve_by_wob_continuation(model, &left(direct.stats.seconds)).unwrap_or(None);
    let reached = wob_path.as_ref().map(|(_, wob)| (*wob, target));
    let first = direct.stats.clone();
    let done = |mut sol: Solution, paths: &SolveStats, friction: Option<f64>| {
        sol.stats.add_work(&first);
        sol.stats.add_work(paths);
        sol.stats.wob_continuation_n = reached;
        sol.stats.friction_continuation = friction;
        sol
    };
    if let Some((sol, _)) = wob_path {
        if sol.converged {
            return Ok(done(sol, &paths, None));
        }
        paths.add_work(&sol.stats);
    }
    let mut friction_reached = None;
    if model.needs_unsymmetric() && direct.stats.seconds + paths.seconds < ctl.time_limit_s {
        let spent = direct.stats.seconds + paths.seconds;
        if let Some((sol, share)) = continuation::solve_by_friction_continuation(model, &left(spent)).unwrap_or(None) {
            if sol.converged {
                return Ok(done(sol, &paths, Some(share)));
            }
            paths.add_work(&sol.stats);
            friction_reached = Some(share);
        }
    }
    let spent = direct.stats.seconds + paths.seconds;
    let rest = ctl.max_iterations.saturating_sub(direct.stats.iterations);
    let mut out = if rest > 0 && spent < ctl.time_limit_s {
        let mut consistent = model.clone();
        consistent.consistent_tangent = true;
        let resume_ctl = SolveControls {
            max_iterations: rest,
            ..left(spent)
        };
        let mut again = solve_interior_point_from(&consistent, direct.state, &resume_ctl)?;
        again.stats.add_work(&direct.stats);
        again
    } else {
        direct
    };
    out.stats.add_work(&paths);
    out.stats.wob_continuation_n = reached;
    out.stats.friction_continuation = friction_reached;
    Ok(out)
}
