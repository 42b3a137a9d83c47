//! A whole-string solve that found no equilibrium, started again from the buckled shape
//! (issue 16; docs/theory.md 7.5).
//!
//! The failures of the acceptance grid's uphill laterals are the pipe above the kick-off
//! point: a vertical section in large casing that the lateral's WOB and weight compress far
//! beyond the helical onset (a floor of `5.55 (EI w_b^2)^(1/3)` there). Its straight shape on
//! the hole axis is an equilibrium past its stability limit with no lateral restoring load,
//! and the contact Newton from it (the direct solve, the WOB and friction paths) wanders: the
//! residual stays at 1e-4 to 1e-2 of the load scale with the worst node in that section.
//!
//! [`solve_from_buckled_start`] runs after those stages fail (a sliding string tries its damped
//! strategy right after the direct solve, before the paths: [`early_damped`]): the soft string
//! of the case (its friction, motion and WOB) gives the axial force at the model's nodes and the
//! runs beyond the helical onset ([`soft_helical_runs`]); the cold start is solved with a
//! pseudo-transient lateral damping held full until the residual is small
//! ([`Strategy::Damped`]), then, if that fails, moved onto a helix along the wall there and
//! solved as the helix re-solve is ([`Strategy::Helix`], [`helix::solve_from_helix`]). A result
//! is kept only if it converged with global equilibrium within [`EQUILIBRIUM`] of the largest
//! force, penetration within the gap tolerance and a hook load not below zero. A case whose soft
//! string is locked up is left to the lock-up answer, and one that the soft string with the
//! helix's drag finds locked up ([`crate::models::helical_drag`]) is not re-solved: no
//! equilibrium holds it there.

use crate::case::Case;
use crate::models::buckling::{helical_runs, marks, MIN_HELICAL_RUN_M};
use crate::models::fem::model::{Model, State, TopCondition};
use crate::models::fem::results::extract;
use crate::models::fem::solve::start::cold_start;
use crate::models::fem::solve::{
    helix, solve_interior_point, solve_interior_point_from, solve_unless, Solution, SolveControls, SolveError,
    SolveStats,
};
use crate::models::helical_drag;
use crate::models::softstring;
use std::time::Instant;

/// Relative equilibrium (force imbalance over the largest force) a re-solve must meet.
pub const EQUILIBRIUM: f64 = 1e-6;

/// The soft string's effective axial force at each node of `model` (the whole string of
/// `case`, N, tension positive, bit first; linear between the soft-string points) and the
/// runs of nodes (index ranges from the bit, inclusive) where it is beyond the helical onset
/// over at least [`MIN_HELICAL_RUN_M`]; none where the soft string is locked up (its hook load
/// below zero: the lock-up is the answer, `models::string_solve`).
pub fn soft_helical_runs(case: &Case, model: &Model) -> (Vec<f64>, Vec<(usize, usize)>) {
    let soft = softstring::from_case(case, softstring::segment_length_m(&case.solver));
    if soft.hook_load_n < 0.0 {
        return (Vec::new(), Vec::new());
    }
    let pts = &soft.points;
    // points run from the bit upward: MD falls
    let at = |md: f64| -> f64 {
        let k = pts.partition_point(|p| p.md_m > md);
        if k == 0 {
            return pts[0].tension_n;
        }
        if k >= pts.len() {
            return pts[pts.len() - 1].tension_n;
        }
        let (a, b) = (&pts[k - 1], &pts[k]);
        let f = if a.md_m > b.md_m {
            (a.md_m - md) / (a.md_m - b.md_m)
        } else {
            0.0
        };
        a.tension_n + f * (b.tension_n - a.tension_n)
    };
    let axial: Vec<f64> = model.md_ref.iter().map(|&md| at(md)).collect();
    let nodes = (0..model.nodes()).map(|i| (model.md_ref[i], model.mesh.nodes[i].s_m, axial[i]));
    let m = marks(
        nodes,
        &case.string,
        &case.well.path,
        &case.well.hole,
        case.mud.density_kg_m3,
    );
    let runs = helical_runs(&m)
        .into_iter()
        .filter(|&(a, b)| model.mesh.nodes[b].s_m - model.mesh.nodes[a].s_m >= MIN_HELICAL_RUN_M)
        .collect();
    (axial, runs)
}

/// One way from the cold start to the buckled equilibrium (docs/performance.md, "Acceptance
/// grid", measures them against each other).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Strategy {
    /// Pseudo-transient continuation alone: the cold start solved with the lateral damping
    /// [`helix::instability_stiffness`] of the soft string's helical runs, falling with the
    /// residual ([`SolveControls::lateral_damping_n_per_m`]).
    Damped,
    /// The cold start moved onto a helix along the wall in the soft string's helical runs and
    /// solved as the helix re-solve does ([`helix::solve_from_helix`]: damped, the friction at
    /// once, then along a friction path).
    Helix,
}

/// Relative outer residual above which the damping of [`Strategy::Damped`] is full
/// ([`SolveControls::damping_reference_residual`]).
pub const DAMPING_REFERENCE_RESIDUAL: f64 = 1e-3;

/// Iteration limit of [`Strategy::Damped`], in `max_iterations`: a pseudo-transient iteration
/// moves slowly while its damping is full (the rescued grid cases take 190-440 iterations).
pub const DAMPED_ITERATION_FACTOR: usize = 3;

/// Factor on the residual tolerance of a buckled string's solve that has to meet
/// [`EQUILIBRIUM`]: the continued solve of a damped re-solve that converged with its global
/// equilibrium beyond it ([`Strategy::Damped`]), and the refined re-solve of an answer climbed
/// from the buckled shape (`models::string_solve`). Thousands of residual entries below the
/// tolerance can add up to a few 1e-6 of the largest force on a 1,000-2,000 m lateral.
pub const EQUILIBRIUM_RESIDUAL_FACTOR: f64 = 0.1;

/// Iteration limit of that continued solve (it starts from a converged state).
pub const POLISH_ITERATIONS: usize = 30;

/// The strategies [`solve_from_buckled_start`] tries, in order (the cheaper first).
pub const STRATEGIES: [Strategy; 2] = [Strategy::Damped, Strategy::Helix];

/// The solve `sol` of `model` (of `case`) if it converged, ran out of time, or `model` is not
/// the whole string; otherwise the re-solve from the buckled start (module docs) by each of
/// [`STRATEGIES`] in turn, the first kept, else `sol` with their work added
/// ([`SolveStats::buckled_start`] says which).
pub fn solve_from_buckled_start(case: &Case, model: &Model, sol: Solution, ctl: &SolveControls) -> Solution {
    solve_from_buckled_start_by(case, model, sol, ctl, &STRATEGIES)
}

/// `model` (of `case`) solved from the buckled start alone (module docs), without the direct
/// solve and its paths before it: one cold iteration, then [`solve_from_buckled_start`]. For a
/// string known to be helically buckled (the lock-up answer, `models::string_solve`), where the
/// direct solve's stages only spend time.
pub fn solve_buckled(case: &Case, model: &Model, ctl: &SolveControls) -> Result<Solution, SolveError> {
    let one = SolveControls {
        max_iterations: 1,
        ..*ctl
    };
    let sol = solve_interior_point(model, &one)?;
    Ok(solve_from_buckled_start(case, model, sol, ctl))
}

/// [`solve_from_buckled_start`] with the strategies `strategies`.
pub fn solve_from_buckled_start_by(
    case: &Case,
    model: &Model,
    mut sol: Solution,
    ctl: &SolveControls,
    strategies: &[Strategy],
) -> Solution {
    if sol.converged || sol.stats.timed_out || matches!(model.top, TopCondition::Cut { .. }) {
        return sol;
    }
    let (axial, runs) = soft_helical_runs(case, model);
    if runs.is_empty() || helically_locked(case) {
        return sol;
    }
    let t0 = Instant::now();
    let accept = |h: &Solution| acceptable(case, model, ctl, h);
    let mut work = SolveStats::default();
    let repeated = |s: &Strategy| *s == Strategy::Damped && sol.stats.damped_start_exhausted;
    for &strategy in strategies.iter().filter(|s| !repeated(s)) {
        let left = SolveControls {
            time_limit_s: ctl.time_limit_s - sol.stats.seconds - t0.elapsed().as_secs_f64(),
            ..*ctl
        };
        if left.time_limit_s <= 0.0 {
            break;
        }
        let start = cold_start(model);
        let (kept, w) = match strategy {
            Strategy::Damped => {
                let limit = DAMPED_ITERATION_FACTOR * left.max_iterations;
                damped(model, start, &axial, &runs, &left, limit, accept)
            }
            Strategy::Helix => helix::solve_from_helix(model, &start, &axial, &runs, &left, accept),
        };
        work.add_work(&w);
        tracing::info!(
            ?strategy,
            kept = kept.is_some(),
            iterations = w.iterations,
            "re-solve from a buckled start"
        );
        if let Some(mut h) = kept {
            // the kept solve's own work is in `work`
            h.stats.iterations = 0;
            h.stats.factorizations = 0;
            h.stats.seconds = 0.0;
            h.stats.add_work(&sol.stats);
            h.stats.add_work(&work);
            // the answer did not come from the paths that ran before
            h.stats.wob_continuation_n = None;
            h.stats.friction_continuation = None;
            h.stats.buckled_start = Some(true);
            return h;
        }
    }
    sol.stats.add_work(&work);
    sol.stats.buckled_start = Some(false);
    sol
}

/// Whether the re-solve `h` of `model` (of `case`) is an answer: converged, penetration within
/// the gap tolerance, global equilibrium within [`EQUILIBRIUM`] of the largest force, and a hook
/// load not below zero (the surface pushing is a lock-up, not an answer).
fn acceptable(case: &Case, model: &Model, ctl: &SolveControls, h: &Solution) -> bool {
    let pushed = model.loads.hook_load_n.is_none() && h.state.hook_load_n < 0.0;
    if !h.converged || h.stats.max_penetration > ctl.gap_tolerance || pushed {
        return false;
    }
    let r = extract(model, h, case.mud.density_kg_m3);
    let eq = r.equilibrium_error();
    tracing::info!(equilibrium = eq, "re-solve from a buckled start converged");
    eq <= EQUILIBRIUM
}

/// Newton steps in a row whose contact subproblem ends at its iteration limit after which the
/// early damped re-solve gives up ([`early_damped`]; the damped solves that answer the grid's
/// buckled 2,000 m slides have no two in a row, the one that fails on 2,000 m, 92 deg, 20 kN
/// has 140 from its 260th iteration on).
pub const EARLY_DAMPED_CAPPED_SUBPROBLEMS: usize = 3;

/// The damped re-solve from the buckled start ([`Strategy::Damped`], its iteration limit) of a
/// whole string of `case` that slides (no rotation) with its soft string helically buckled and
/// not locked up by the helix's drag, run as soon as the direct solve `direct` of `model` has
/// failed, before the WOB and friction paths: where it answers, it is the answer the full
/// re-solve after those paths would give (the same cold start and iterations), without their
/// time. Returns the kept solution (its statistics counting `direct`'s work and its own) or None,
/// and the work of a solve not kept ([`SolveStats::damped_start_exhausted`] set where it ran to
/// its limit).
pub fn early_damped(
    case: &Case,
    model: &Model,
    direct: &Solution,
    ctl: &SolveControls,
) -> (Option<Solution>, SolveStats) {
    if direct.converged || direct.stats.timed_out || !sliding_whole_string(model) {
        return (None, SolveStats::default());
    }
    let (axial, runs) = soft_helical_runs(case, model);
    if runs.is_empty() || helically_locked(case) {
        return (None, SolveStats::default());
    }
    let left = SolveControls {
        time_limit_s: ctl.time_limit_s - direct.stats.seconds,
        stop_after_capped_subproblems: EARLY_DAMPED_CAPPED_SUBPROBLEMS,
        ..*ctl
    };
    let accept = |h: &Solution| acceptable(case, model, ctl, h);
    let limit = DAMPED_ITERATION_FACTOR * ctl.max_iterations;
    let (kept, mut work) = damped(model, cold_start(model), &axial, &runs, &left, limit, accept);
    work.damped_start_exhausted = kept.is_none() && work.iterations >= limit;
    tracing::info!(
        kept = kept.is_some(),
        iterations = work.iterations,
        "early damped re-solve from a buckled start"
    );
    match kept {
        Some(mut h) => {
            h.stats.add_work(&direct.stats);
            h.stats.buckled_start = Some(true);
            (Some(h), SolveStats::default())
        }
        None => (None, work),
    }
}

/// [`solve_unless`] of `model` (of `case`) with the damped re-solve from the buckled start tried
/// right after the direct solve, before the paths ([`early_damped`]): the solve of a whole string
/// in `solve`, `loads` and `predict`. Returns the solution and whether it gave up.
pub fn solve_damped_before_paths(
    case: &Case,
    model: &Model,
    ctl: &SolveControls,
    give_up: impl FnOnce() -> bool,
) -> Result<(Solution, bool), SolveError> {
    solve_unless(model, ctl, give_up, |direct| early_damped(case, model, direct, ctl))
}

/// Whether `model` is a whole string (not a part cut at a coupling point) that slides: no
/// rotation.
fn sliding_whole_string(model: &Model) -> bool {
    model.loads.omega_rad_s <= 0.0 && !matches!(model.top, TopCondition::Cut { .. })
}

/// Whether `case` (on bottom, WOB given) is locked up by the helix's drag: the soft string with
/// Mitchell's helical contact force ([`helical_drag`]) has a negative hook load. The whole
/// string then has no equilibrium at the case's WOB with the surface holding the string (it
/// lies below that soft string's hook load in every converged sliding case of the acceptance
/// grid, docs/performance.md); the solve's hints name the helical lock-up instead
/// (`models::diagnose`).
fn helically_locked(case: &Case) -> bool {
    let op = &case.operation;
    op.mode.on_bottom() && op.hook_load_n.is_none() && helical_drag::helical_soft_string(case).hook_load_n < 0.0
}

/// [`Strategy::Damped`]: `model` solved from `start` (consistent tangent) under `ctl` with at
/// most `max_iterations` and the lateral damping of [`helix::instability_stiffness`] in `runs`
/// (`axial` the soft string's axial forces at the nodes, N); the solution if `accept` takes it,
/// and the work.
fn damped(
    model: &Model,
    start: State,
    axial: &[f64],
    runs: &[(usize, usize)],
    ctl: &SolveControls,
    max_iterations: usize,
    accept: impl Fn(&Solution) -> bool,
) -> (Option<Solution>, SolveStats) {
    let mut m = model.clone();
    m.consistent_tangent = true;
    let c = SolveControls {
        max_iterations,
        lateral_damping_n_per_m: helix::instability_stiffness(model, axial, runs),
        damping_reference_residual: DAMPING_REFERENCE_RESIDUAL,
        ..*ctl
    };
    let mut work = SolveStats::default();
    let Ok(mut sol) = solve_interior_point_from(&m, start, &c) else {
        return (None, work);
    };
    work.add_work(&sol.stats);
    let mut kept = sol.converged && accept(&sol);
    if sol.converged && !kept {
        // converged, but its residual entries may add up beyond the global equilibrium asked
        // for: continued at a tighter residual tolerance
        let tighter = SolveControls {
            residual_tolerance: EQUILIBRIUM_RESIDUAL_FACTOR * c.residual_tolerance,
            max_iterations: POLISH_ITERATIONS,
            ..c
        };
        if let Ok(polished) = solve_interior_point_from(&m, sol.state.clone(), &tighter) {
            work.add_work(&polished.stats);
            if polished.converged {
                kept = accept(&polished);
                sol = polished;
            }
        }
    }
    tracing::info!(
        converged = sol.converged,
        hook_load_n = sol.state.hook_load_n,
        "damped re-solve from a buckled start"
    );
    (Some(sol).filter(|_| kept), work)
}
