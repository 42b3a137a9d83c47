//! What a solve returns: the solution with its statistics (why it failed:
//! [`super::errors`], re-exported here).

pub use super::errors::SolveError;
use crate::models::fem::model::{Evaluation, State};

/// Statistics of a solve.
#[derive(Debug, Clone, Default)]
pub struct SolveStats {
    /// Iterations done.
    pub iterations: usize,
    /// Factorizations done.
    pub factorizations: usize,
    /// Residual norm (relative to the load scale) per iteration.
    pub residual_history: Vec<f64>,
    /// Largest penetration relative to the clearance at the end.
    pub max_penetration: f64,
    /// Wall-clock time, s.
    pub seconds: f64,
    /// Nodes whose contact state changed in the last iterations (modified Newton).
    pub chattering_nodes: Vec<usize>,
    /// The solve stopped at its time limit ([`super::SolveControls::time_limit_s`]).
    pub timed_out: bool,
    /// The WOB continuation that followed a direct solve that did not converge
    /// ([`super::continuation`]): the WOB it reached and the model's WOB, N (equal when it
    /// converged); None when none ran.
    pub wob_continuation_n: Option<(f64, f64)>,
    /// The friction continuation that followed the direct solve and the WOB continuation
    /// when neither converged ([`super::continuation::solve_by_friction_continuation`]): the
    /// share of the model's friction it reached (1 when the solution came from it); None when
    /// none ran or its frictionless start failed.
    pub friction_continuation: Option<f64>,
    /// Whether a re-solve from a helix along the wall followed a converged solve that lay
    /// straight beyond the helical onset (`models::levels`, [`super::helix`]): `Some(true)` kept
    /// (the answer is the buckled string), `Some(false)` tried and not kept; None when none ran.
    pub helix_restart: Option<bool>,
    /// The turn of a sliding bent housing's toolface by the motor's reactive torque that the
    /// solve held it at ([`super::toolface::solve_holding_toolface`]); None when off.
    pub reactive_turn: Option<crate::models::fem::reactive::ReactiveTurn>,
    /// The orientation (rad) the interior-point Newton turned the bent housing's kink to,
    /// holding the model's [`crate::models::fem::model::Model::toolface_hold_rad`]: the
    /// solution is of the model with its kink turned there
    /// ([`crate::models::fem::model::Model::turn_kink`]); None when the kink was not turned.
    pub kink_turned_to_rad: Option<f64>,
    /// Whether a whole-string solve that found no equilibrium was solved again from its buckled
    /// shape (`models::buckled_start`): `Some(true)` kept (the answer came from it),
    /// `Some(false)` tried and not kept; None when none ran.
    pub buckled_start: Option<bool>,
    /// The damped re-solve from the buckled shape ran before the WOB and friction paths
    /// (`models::buckled_start::early_damped`) to its full iteration limit without an answer:
    /// the re-solve after the paths, which would repeat it step for step, leaves it out.
    pub damped_start_exhausted: bool,
    /// The refined solve of the assembly's mesh solved its lower part with the string above
    /// condensed ([`crate::models::fem::condense`]) and the whole refined model converged from
    /// there.
    pub lower_part_refined: bool,
    /// The climb from the buckled shape toward the WOB (`models::helical_lock_up::climbed_to_wob`)
    /// that followed a whole-string solve that found no equilibrium and did not reach it: the
    /// WOB it reached and the WOB aimed at, N; None when none ran or it reached the WOB.
    pub buckled_climb_n: Option<(f64, f64)>,
    /// Stages that ran after a whole-string solve found no equilibrium and did not answer,
    /// besides those above, as the failure message names them (`models::string_solve`); their
    /// work is in the counts.
    pub unanswered_stages: Vec<&'static str>,
}

impl SolveStats {
    /// Add the work of `other` (another solve of the same problem: its iterations,
    /// factorizations and time) to these statistics.
    pub fn add_work(&mut self, other: &SolveStats) {
        self.iterations += other.iterations;
        self.factorizations += other.factorizations;
        self.seconds += other.seconds;
    }

    /// These statistics of a solve that continued `first` (a re-solve of its solution on a
    /// refined mesh, or from a helix): `first`'s work added ([`SolveStats::add_work`]) and the
    /// path it took to its solution kept (WOB and friction continuation, buckled start).
    pub fn continue_from(&mut self, first: &SolveStats) {
        self.add_work(first);
        self.wob_continuation_n = first.wob_continuation_n;
        self.friction_continuation = first.friction_continuation;
        self.buckled_start = first.buckled_start;
    }
}

/// A converged (or flagged unconverged) solution.
pub struct Solution {
    /// Final state.
    pub state: State,
    /// Evaluation at the final state.
    pub eval: Evaluation,
    /// Whether all convergence criteria were met.
    pub converged: bool,
    /// Statistics.
    pub stats: SolveStats,
    /// The matrix and factor of the last Newton step of an undamped interior-point solve with
    /// the LU, and its contacts ([`LastLinearization`]); None otherwise.
    pub(crate) last_linearization: Option<Box<LastLinearization>>,
}

/// The last Newton step's linear system of an interior-point solve: what a part of the model
/// can be condensed with ([`crate::models::fem::condense`]).
pub(crate) struct LastLinearization {
    /// The LU of the last step's reduced matrix `K + N diag(R/s) N^T`, held DOFs held (the
    /// matrix beside it may have been assembled again since).
    pub(crate) lin: super::matrix_and_factor::MatrixAndFactor,
    /// Per contact of that step: `R / s` of the factored matrix, N/m.
    pub(crate) ratio: Vec<f64>,
    /// Per contact: outward normal in the node basis.
    pub(crate) normals: Vec<crate::geometry::Vec3>,
    /// Per contact: its node.
    pub(crate) node: Vec<usize>,
    /// The DOFs held in that step (their rows and columns zeroed in the factor).
    pub(crate) constrained: Vec<usize>,
    /// The state the step's tangent was assembled at.
    pub(crate) state: State,
}
