//! Stiff rows of the chart: the whole-string FEM ([`crate::fem`]) for each load case at a bit
//! depth.
//!
//! Warm start: at one bit depth the five load cases share the mesh and the geometry, only the
//! loads differ, so each case after the first starts the interior-point contact Newton
//! ([`solve_ip_from`]) from the previous case's converged state (positions, triads, contact
//! multipliers); if that does not converge the full strategy chain of [`solve`] runs from a
//! cold start. Between bit depths the mesh changes (the string is longer), so each depth's
//! first case starts cold.
//!
//! A solve that does not converge gives [`StiffOutcome::NotConverged`]: no numbers are
//! reported for it.

use super::chart::RowLoads;
use super::{set_row_operation, ChartOperation, MODES};
use crate::case::Case;
use crate::fem::model::{Model, State};
use crate::fem::results::extract;
use crate::fem::solve::{solve, solve_ip_from, SolveControls};

/// Result of the stiff model for one row.
#[derive(Debug, Clone, PartialEq)]
pub enum StiffOutcome {
    /// Converged solve.
    Converged {
        /// Surface loads and largest nodal contact force.
        loads: RowLoads,
        /// Newton iterations (all attempts).
        iterations: usize,
        /// Wall-clock time, s.
        seconds: f64,
        /// True when the warm start from the previous load case converged.
        warm: bool,
    },
    /// The solver stopped without meeting its criteria: no valid numbers.
    NotConverged {
        /// Newton iterations (all attempts).
        iterations: usize,
        /// Last relative residual.
        residual: f64,
    },
    /// The solver failed (e.g. singular stiffness); the message says why.
    Failed(String),
}

impl StiffOutcome {
    /// The loads when converged.
    pub fn loads(&self) -> Option<&RowLoads> {
        match self {
            StiffOutcome::Converged { loads, .. } => Some(loads),
            _ => None,
        }
    }
    /// Status word for `loads.csv`: `converged`, `not_converged` or `failed`.
    pub fn status(&self) -> &'static str {
        match self {
            StiffOutcome::Converged { .. } => "converged",
            StiffOutcome::NotConverged { .. } => "not_converged",
            StiffOutcome::Failed(_) => "failed",
        }
    }
}

/// Stiff solve of `case` (string and operation set for the row), warm-started from `warm` when
/// given; returns the outcome and the converged state (for the next warm start).
pub fn stiff_row(case: &Case, warm: Option<State>) -> (StiffOutcome, Option<State>) {
    let model = Model::from_case(case);
    let ctl = SolveControls::from_settings(&case.solver);
    let mut iterations = 0;
    let t0 = std::time::Instant::now();
    if let Some(state) = warm {
        let mut consistent = model.clone();
        consistent.consistent_tangent = true;
        match solve_ip_from(&consistent, state, &ctl) {
            Ok(sol) if sol.converged => {
                let res = extract(&model, &sol, case.mud.density_kg_m3);
                return (
                    converged(&res, sol.stats.iterations, t0.elapsed().as_secs_f64(), true),
                    Some(sol.state),
                );
            }
            Ok(sol) => {
                iterations += sol.stats.iterations;
                tracing::info!("warm start did not converge; cold start");
            }
            Err(e) => tracing::info!("warm start failed ({e}); cold start"),
        }
    }
    match solve(&model, &ctl) {
        Ok(sol) if sol.converged => {
            let res = extract(&model, &sol, case.mud.density_kg_m3);
            (
                converged(
                    &res,
                    iterations + sol.stats.iterations,
                    t0.elapsed().as_secs_f64(),
                    false,
                ),
                Some(sol.state),
            )
        }
        Ok(sol) => (
            StiffOutcome::NotConverged {
                iterations: iterations + sol.stats.iterations,
                residual: sol.stats.residual_history.last().copied().unwrap_or(f64::NAN),
            },
            None,
        ),
        Err(e) => (StiffOutcome::Failed(e.to_string()), None),
    }
}

fn converged(res: &crate::fem::results::SolveResults, iterations: usize, seconds: f64, warm: bool) -> StiffOutcome {
    let max_f = res.nodes.iter().map(|n| n.contact_force_n).fold(0.0, f64::max);
    StiffOutcome::Converged {
        loads: RowLoads {
            hook_load_n: res.hook_load_n,
            surface_torque_nm: res.surface_torque_nm,
            max_contact_force_n: max_f,
            max_side_force_n_per_m: 0.0,
        },
        iterations,
        seconds,
        warm,
    }
}

/// Stiff outcomes of the five load cases ([`MODES`] order) for `case` with its string already
/// refitted to `bit_md_m` (see [`super::chart::case_at_depth`]), each case warm-started from
/// the previous converged one. `wob_n[j]` is the WOB of case `MODES[j]` (the soft rows' WOB,
/// which may be below the chart's where the string cannot give it).
pub fn stiff_depth(case: &Case, bit_md_m: f64, op: &ChartOperation, wob_n: &[f64]) -> Vec<StiffOutcome> {
    let mut c = case.clone();
    let mut warm: Option<State> = None;
    let mut out = Vec::with_capacity(MODES.len());
    for (j, mode) in MODES.into_iter().enumerate() {
        set_row_operation(&mut c, bit_md_m, mode, op);
        c.operation.wob_n = wob_n.get(j).copied().unwrap_or(c.operation.wob_n);
        let (outcome, state) = stiff_row(&c, warm.take());
        warm = state;
        out.push(outcome);
    }
    out
}
