//! Weight-on-bit continuation: the loading path of a string that the direct solve cannot
//! reach from its start.
//!
//! A compressed string with wall friction (a lateral slid with a high WOB, pipe buckled
//! against the wall) has an equilibrium that depends on how it was reached, and the Newton
//! iteration from the string lying on the hole axis can stall far from it (the residual flat
//! at 1e-4 to 1e-3 of the load scale for hundreds of iterations). The rig reaches it by
//! slacking off: the string hangs in tension, then the driller lowers it and the WOB rises.
//! The continuation does the same: it solves the string at a tenth of the WOB (bit torque in
//! proportion), then raises the WOB in steps, each solved from the previous equilibrium with
//! the operation's friction against the motion; a step that does not converge within
//! [`STEP_ITERATIONS`] is halved, one that does lets the next grow by [`STEP_GROWTH`].

use super::interior_point_newton::{solve_interior_point, solve_interior_point_from};
use super::{Solution, SolveControls, SolveError, SolveStats};
use crate::models::fem::model::Model;
use std::time::Instant;

/// The first WOB of the path, as a fraction of the target.
pub const START_FRACTION: f64 = 0.1;

/// Newton iterations allowed to one step of the path.
pub const STEP_ITERATIONS: usize = 20;

/// Newton iterations in a row whose contact subproblem ends at its iteration limit after which
/// a step of a path is given up as not converging (and halved): on the buckled 2,000 m slides of
/// the acceptance grid the steps that converge have none, and the steps that reach it go on to
/// fail after [`STEP_ITERATIONS`] with every subproblem at the limit (docs/performance.md).
pub const STEP_CAPPED_SUBPROBLEMS: usize = 3;

/// Factor on the WOB step after a converged step.
pub const STEP_GROWTH: f64 = 1.5;

/// Smallest WOB step, as a fraction of the target: below it the path has met a limit (a
/// string that cannot take more WOB, or a jump to another buckled shape) and stops.
pub const MIN_STEP_FRACTION: f64 = 1e-3;

/// How a path steps: its first step and smallest step (in the path parameter, which runs to
/// 1), the iteration limit of one step, and the growth of the step after a converged one (a
/// step that does not converge is halved).
#[derive(Debug, Clone, Copy)]
pub struct PathSteps {
    /// First step.
    pub first: f64,
    /// Smallest step: below it the path stops.
    pub smallest: f64,
    /// Newton iterations allowed to one step.
    pub step_iterations: usize,
    /// Factor on the step after a converged one.
    pub growth: f64,
}

/// The WOB and friction paths' steps: [`START_FRACTION`], [`MIN_STEP_FRACTION`],
/// [`STEP_ITERATIONS`], [`STEP_GROWTH`].
pub const CONTINUATION_STEPS: PathSteps = PathSteps {
    first: START_FRACTION,
    smallest: MIN_STEP_FRACTION,
    step_iterations: STEP_ITERATIONS,
    growth: STEP_GROWTH,
};

/// Whether the continuation applies to `model`: a WOB-driven model with a positive WOB.
pub fn applies(model: &Model) -> bool {
    model.loads.hook_load_n.is_none() && model.loads.wob_n > 0.0
}

/// `model` with its WOB at `wob_n` and its bit torque in proportion (N, N.m).
pub fn at_wob(model: &Model, wob_n: f64) -> Model {
    let mut m = model.clone();
    let share = wob_n / model.loads.wob_n;
    m.loads.wob_n = wob_n;
    m.loads.bit_torque_nm = model.loads.bit_torque_nm * share;
    m
}

/// A path's first step: `start` (the path's first model) solved cold (at most four steps'
/// iterations), and `model` with the full tangent, on which the later steps are solved
/// warm-started.
fn first_step(start: &Model, model: &Model, ctl: &SolveControls) -> Result<(Solution, Model), SolveError> {
    let first_ctl = SolveControls {
        max_iterations: ctl.max_iterations.min(4 * STEP_ITERATIONS),
        ..*ctl
    };
    let sol = solve_interior_point(start, &first_ctl)?;
    let mut consistent = model.clone();
    consistent.consistent_tangent = true;
    Ok((sol, consistent))
}

/// `model` with its wall friction times `share`.
pub(crate) fn with_friction(model: &Model, share: f64) -> Model {
    let mut m = model.clone();
    m.friction.iter_mut().for_each(|f| *f *= share);
    m
}

/// Solve `model` along the WOB path from [`START_FRACTION`] of its WOB, within `ctl`'s
/// iteration limit (all steps together) and time limit. Returns the last converged solution
/// and the WOB it carries (N): the model's WOB if the path reached it, less if it stopped
/// (then the solution is flagged not converged); `Ok(None)` if even the first step failed
/// (its iterations are then not counted: a path that never started is not reported).
pub fn solve_by_wob_continuation(model: &Model, ctl: &SolveControls) -> Result<Option<(Solution, f64)>, SolveError> {
    let t0 = Instant::now();
    let target = model.loads.wob_n;
    let start = at_wob(model, START_FRACTION * target);
    let (first, consistent) = first_step(&start, model, ctl)?;
    if !first.converged {
        return Ok(None);
    }
    let (sol, share) = follow_path(
        |share| at_wob(&consistent, share * target),
        first,
        START_FRACTION,
        ctl,
        CONTINUATION_STEPS,
        t0,
    );
    Ok(Some((sol, share * target)))
}

/// Solve `model` along a friction path: frictionless first (cold, at most four steps'
/// iterations), then the wall friction raised in steps from zero to the model's, each solved
/// from the previous equilibrium. Friction makes the contact problem unsymmetric and, on very
/// fine meshes, the direct Newton iteration can wander (docs/performance.md, "Fine BHA
/// meshes"); the frictionless problem is the symmetric one, and the path keeps each step near
/// an equilibrium. The friction of a rotating or sliding string is set by the motion, not by
/// the path, so the end of the path is the model's equilibrium. Returns the last converged
/// solution and the share of the model's friction it carries (1 if the path reached it, then
/// the solution is converged); `Ok(None)` if the frictionless solve failed.
pub fn solve_by_friction_continuation(
    model: &Model,
    ctl: &SolveControls,
) -> Result<Option<(Solution, f64)>, SolveError> {
    let t0 = Instant::now();
    let (first, consistent) = first_step(&with_friction(model, 0.0), model, ctl)?;
    if !first.converged {
        return Ok(None);
    }
    let at = |share: f64| with_friction(&consistent, share);
    Ok(Some(follow_path(at, first, 0.0, ctl, CONTINUATION_STEPS, t0)))
}

/// Follow a path of models `at(t)` from `t = from` (whose solution is `first`) to `t = 1` in
/// the steps of `steps`, each solved from the previous equilibrium, until `t = 1`, a step
/// below `steps.smallest`, or `ctl`'s iteration limit (all steps together, `first`'s included)
/// or time limit (from `t0`). Returns the last converged solution (flagged converged only at
/// `t = 1`, its statistics the whole path's) and its `t`.
pub(crate) fn follow_path(
    at: impl Fn(f64) -> Model,
    first: Solution,
    from: f64,
    ctl: &SolveControls,
    steps: PathSteps,
    t0: Instant,
) -> (Solution, f64) {
    let mut t = from;
    let mut sol = first;
    let mut iterations = sol.stats.iterations;
    let mut factorizations = sol.stats.factorizations;
    let mut step = steps.first;
    while t < 1.0 && step >= steps.smallest {
        let elapsed = t0.elapsed().as_secs_f64();
        if iterations >= ctl.max_iterations || elapsed > ctl.time_limit_s {
            break;
        }
        let next = (t + step).min(1.0);
        let step_ctl = SolveControls {
            max_iterations: steps.step_iterations.min(ctl.max_iterations - iterations),
            time_limit_s: ctl.time_limit_s - elapsed,
            stop_after_capped_subproblems: STEP_CAPPED_SUBPROBLEMS,
            ..*ctl
        };
        let result = solve_interior_point_from(&at(next), sol.state.clone(), &step_ctl);
        log_step("path step", t, next, &result);
        match result {
            Ok(s) if s.converged => {
                iterations += s.stats.iterations;
                factorizations += s.stats.factorizations;
                sol = s;
                t = next;
                step *= steps.growth;
            }
            Ok(s) => {
                iterations += s.stats.iterations;
                factorizations += s.stats.factorizations;
                step *= 0.5;
            }
            Err(e) => {
                tracing::debug!(path_parameter = next, error = %e, "continuation step failed");
                step *= 0.5;
            }
        }
    }
    sol.converged = t >= 1.0;
    sol.stats.iterations = iterations;
    sol.stats.factorizations = factorizations;
    sol.stats.seconds = t0.elapsed().as_secs_f64();
    sol.stats.timed_out = t0.elapsed().as_secs_f64() > ctl.time_limit_s;
    (sol, t)
}

/// Log (debug) a step of a path or climb from `from` to `to` (its parameter), as `what`.
fn log_step(what: &str, from: f64, to: f64, result: &Result<Solution, SolveError>) {
    if let Ok(s) = result {
        tracing::debug!(
            from,
            to,
            converged = s.converged,
            iterations = s.stats.iterations,
            hook_load_n = s.state.hook_load_n,
            "{what}"
        );
    }
}

/// Iteration budget of [`wob_at_zero_hook_load`], in `max_iterations`.
pub const SEARCH_BUDGET_FACTOR: usize = 3;

/// The largest WOB of `model`'s string with a non-negative hook load, by the same WOB path
/// (at most [`SEARCH_BUDGET_FACTOR`] x `max_iterations` iterations in all):
/// from [`START_FRACTION`] of the model's WOB upward by [`climb_wob`]. Returns that WOB
/// (N) and the hook load there (N); None when the path's first step fails or the hook load
/// never turns negative below the model's WOB. `work` gets the search's work either way.
pub fn wob_at_zero_hook_load(
    model: &Model,
    ctl: &SolveControls,
    hook_tolerance_n: f64,
    work: &mut SolveStats,
) -> Option<(f64, f64)> {
    let t0 = Instant::now();
    let target = model.loads.wob_n;
    let lo = START_FRACTION * target;
    let (first, consistent) = first_step(&at_wob(model, lo), model, ctl).ok()?;
    if !(first.converged && first.state.hook_load_n >= 0.0) {
        work.add_work(&first.stats);
        return None;
    }
    let climb = climb_wob(&consistent, first, lo, ctl, hook_tolerance_n, t0, |_, _| true);
    work.add_work(&climb.solution.stats);
    match climb.end {
        ClimbEnd::Bracketed | ClimbEnd::HookLoad => Some((climb.wob_n, climb.solution.state.hook_load_n)),
        ClimbEnd::Target | ClimbEnd::Stalled => None,
    }
}

/// Hook load at which a search for the largest WOB stops (lock-up), as a fraction of that WOB
/// (at least [`LOCK_UP_HOOK_TOLERANCE_N`]).
pub const LOCK_UP_HOOK_TOLERANCE: f64 = 0.01;

/// Smallest hook load at which a search for the largest WOB stops, N.
pub const LOCK_UP_HOOK_TOLERANCE_N: f64 = 500.0;

/// The hook load (N) within which a search for the largest WOB, about `wob_n` (N), stops:
/// [`LOCK_UP_HOOK_TOLERANCE`] of it, at least [`LOCK_UP_HOOK_TOLERANCE_N`].
pub fn lock_up_hook_tolerance_n(wob_n: f64) -> f64 {
    (LOCK_UP_HOOK_TOLERANCE * wob_n).max(LOCK_UP_HOOK_TOLERANCE_N)
}

/// How a [`climb_wob`] ended.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ClimbEnd {
    /// The hook load fell below the tolerance.
    HookLoad,
    /// The hook load turned negative beyond the WOB reached, bisected to the smallest step.
    Bracketed,
    /// The target WOB was reached with a hook load above the tolerance.
    Target,
    /// No step converged (below the smallest step, or out of iterations or time): a limit of the
    /// path.
    Stalled,
}

/// Where a [`climb_wob`] ended: the last converged solution with a hook load not below zero,
/// its WOB (N), and why it stopped.
pub struct Climb {
    /// The last converged solution with a hook load not below zero.
    pub solution: Solution,
    /// Its WOB, N.
    pub wob_n: f64,
    /// Why the climb stopped.
    pub end: ClimbEnd,
}

/// The WOB of `model` (full tangent; its WOB the target) raised from `from_n` (N), where `sol`
/// converged with a hook load not below zero, in steps from `from_n` growing by [`STEP_GROWTH`]
/// after a converged step and halved after one that does not converge, each warm-started with
/// [`STEP_ITERATIONS`], until the hook load falls below `hook_tolerance_n` (N), turns negative
/// (then bisected between the last step with a non-negative hook load and the first without,
/// until the bracket is within [`MIN_STEP_FRACTION`] of the target), the target is reached, or
/// the step falls below [`MIN_STEP_FRACTION`] of the target; at most [`SEARCH_BUDGET_FACTOR`]
/// x `max_iterations` iterations and `ctl`'s time limit from `t0`. A step counts as converged
/// only if `accept` takes its solution (and its model). The solution's statistics count `sol`'s
/// work and the climb's.
pub fn climb_wob(
    model: &Model,
    sol: Solution,
    from_n: f64,
    ctl: &SolveControls,
    hook_tolerance_n: f64,
    t0: Instant,
    accept: impl Fn(&Model, &Solution) -> bool,
) -> Climb {
    let target = model.loads.wob_n;
    let climb_t0 = Instant::now();
    let (it0, f0, s0) = (sol.stats.iterations, sol.stats.factorizations, sol.stats.seconds);
    let (mut lo, mut best) = (from_n, sol);
    let mut hi: Option<f64> = None;
    let mut step = from_n;
    let (mut iterations, mut factorizations) = (0, 0);
    let end = loop {
        let elapsed = t0.elapsed().as_secs_f64();
        if iterations >= SEARCH_BUDGET_FACTOR * ctl.max_iterations
            || elapsed > ctl.time_limit_s
            || step < MIN_STEP_FRACTION * target
        {
            break if hi.is_some() {
                ClimbEnd::Bracketed
            } else {
                ClimbEnd::Stalled
            };
        }
        let next = match hi {
            Some(h) => 0.5 * (lo + h),
            None => (lo + step).min(target),
        };
        let step_ctl = SolveControls {
            max_iterations: STEP_ITERATIONS,
            time_limit_s: ctl.time_limit_s - elapsed,
            stop_after_capped_subproblems: STEP_CAPPED_SUBPROBLEMS,
            ..*ctl
        };
        let at = at_wob(model, next);
        let solved = solve_interior_point_from(&at, best.state.clone(), &step_ctl).map(|mut s| {
            s.converged = s.converged && accept(&at, &s);
            s
        });
        log_step("climb step (WOB, N)", lo, next, &solved);
        match solved {
            Ok(s) if s.converged && s.state.hook_load_n >= 0.0 => {
                iterations += s.stats.iterations;
                factorizations += s.stats.factorizations;
                lo = next;
                let hook = s.state.hook_load_n;
                best = s;
                if hook < hook_tolerance_n {
                    break ClimbEnd::HookLoad;
                }
                step *= STEP_GROWTH;
            }
            Ok(s) if s.converged => {
                iterations += s.stats.iterations;
                factorizations += s.stats.factorizations;
                hi = Some(next);
            }
            other => {
                let (i, f) = other.map_or((0, 0), |s| (s.stats.iterations, s.stats.factorizations));
                iterations += i;
                factorizations += f;
                match hi {
                    Some(_) => hi = Some(next),
                    None => step *= 0.5,
                }
            }
        }
        if let Some(h) = hi {
            if h - lo < MIN_STEP_FRACTION * target {
                break ClimbEnd::Bracketed;
            }
        }
        if lo >= target {
            break ClimbEnd::Target;
        }
    };
    // the solution's statistics: the start's and the climb's work
    best.stats.iterations = it0 + iterations;
    best.stats.factorizations = f0 + factorizations;
    best.stats.seconds = s0 + climb_t0.elapsed().as_secs_f64();
    Climb {
        solution: best,
        wob_n: lo,
        end,
    }
}
