//! The controls of a solve: iteration limit, tolerances, contact scheme.

use crate::case::{Method, SolverSettings};
use std::time::Instant;

/// Solver controls.
#[derive(Debug, Clone, Copy)]
pub struct SolveControls {
    /// Iteration limit.
    pub max_iterations: usize,
    /// Allowed penetration relative to the clearance (interface `tolerance`).
    pub gap_tolerance: f64,
    /// Residual tolerance relative to the load scale.
    pub residual_tolerance: f64,
    /// Contact scheme.
    pub method: Method,
    /// Relaxation `alpha` of the modified Newton's gap-force update (`method = "paper"`, eq. 15).
    pub alpha: f64,
    /// Wall-clock limit of one solve, s: a solve still iterating then stops unconverged
    /// ([`super::SolveStats::timed_out`]).
    pub time_limit_s: f64,
    /// Pseudo-transient damping of the interior-point Newton, N/m: a stiffness added to both
    /// lateral translations of every node, falling with the residual (`d_k = d_0 r_k / r_0`,
    /// switched-evolution relaxation) so that it vanishes at convergence and leaves the
    /// equilibrium unchanged. It makes the steps of an indefinite tangent (a string past its
    /// buckling load) go downhill in energy; 0 (the default) for a plain Newton.
    pub lateral_damping_n_per_m: f64,
    /// Relative outer residual at and above which the pseudo-transient damping is full: below
    /// it the damping falls in proportion to the residual (`d_k = d_0 min(1, r_k / r_ref)`);
    /// 0 (the default) takes the first step's residual as `r_ref`.
    pub damping_reference_residual: f64,
    /// The start is a converged solution carried onto a refined mesh
    /// ([`crate::models::fem::refine`]): the interior point starts
    /// [`super::interior_point::CARRIED_START_SHIFT_FACTOR`] times closer to the boundary and
    /// makes no active-set step (the refined contact runs have pairs with force and gap both
    /// near zero, which switch sides at every try).
    pub carried_start: bool,
    /// Stop (not converged) after this many Newton steps in a row whose contact subproblem
    /// ended at its iteration limit ([`super::interior_point::MAX_IP_ITERATIONS`]): a solve
    /// stalled near an equilibrium it cannot reach (the IP cycling), for a tentative solve
    /// that something else follows; 0 (the default) never.
    pub stop_after_capped_subproblems: usize,
    /// The start is likely an equilibrium already (a state assembled from converged parts,
    /// [`crate::models::fem::refine`]): the first evaluation is made without the tangent, as
    /// after a step that was likely the last.
    pub likely_converged_start: bool,
}

impl SolveControls {
    /// These controls with the time left of their limit since `t0` (s).
    pub fn with_time_left(&self, t0: Instant) -> SolveControls {
        SolveControls {
            time_limit_s: self.time_limit_s - t0.elapsed().as_secs_f64(),
            ..*self
        }
    }

    /// Controls from a case's `[solver]` table (iteration limit, gap tolerance, scheme, alpha).
    pub fn from_settings(s: &SolverSettings) -> SolveControls {
        SolveControls {
            max_iterations: s.max_iterations,
            gap_tolerance: s.tolerance,
            method: s.method,
            alpha: s.alpha,
            time_limit_s: s.time_limit_s,
            ..SolveControls::default()
        }
    }
}

impl Default for SolveControls {
    fn default() -> Self {
        SolveControls {
            max_iterations: 300,
            gap_tolerance: 1e-4,
            residual_tolerance: 1e-7,
            method: Method::Newton,
            alpha: 0.7,
            time_limit_s: crate::case::solver::DEFAULT_TIME_LIMIT_S,
            lateral_damping_n_per_m: 0.0,
            damping_reference_residual: 0.0,
            carried_start: false,
            stop_after_capped_subproblems: 0,
            likely_converged_start: false,
        }
    }
}
