//! Lock-up by the helix's drag as an answer (issue 16; docs/theory.md 7.7): where the whole
//! string finds no equilibrium at the WOB asked for, the plain soft string delivers that WOB and
//! the soft string with the helix's drag does not ([`helical_drag::helical_lock_up`]), the whole
//! string solved below the lock-up ([`below_helical_lock_up`]): from its buckled shape
//! ([`solve_buckled`]) at a fraction of that soft string's largest WOB, then slacked off toward
//! it ([`continuation::climb_wob`]) until its hook load is near zero or the path meets a limit.
//! `solve` (`models::string_solve`) and the whole-string rows of `loads` answer with it; a
//! slide so locked up tries it before its usual solve ([`searched_first`]).

use crate::case::{Case, Mode};
use crate::models::buckled_start::{solve_buckled, EQUILIBRIUM};
use crate::models::checks::locked_at_zero_wob;
use crate::models::fem::model::Model;
use crate::models::fem::results::extract;
use crate::models::fem::solve::continuation::{self, ClimbEnd};
use crate::models::fem::solve::toolface::solve_holding_toolface;
use crate::models::fem::solve::{Solution, SolveControls, SolveStats};
use crate::models::helical_drag;
use crate::models::whirl::whirl_intervals;
use std::time::Instant;

/// Fractions of the largest WOB of the soft string with the helix's drag from which
/// [`below_helical_lock_up`] starts the whole string, in turn (docs/performance.md, "Lock-up by
/// the helix's drag as an answer").
pub const HELICAL_LOCK_UP_FRACTIONS: [f64; 2] = [0.5, 0.25];

/// The whole string climbed from its buckled shape ([`climb_from_buckled_shape`]).
pub struct Climbed {
    /// The WOB the whole string was solved at, N.
    pub wob_n: f64,
    /// The model at that WOB (its kink turned as solved).
    pub model: Model,
    /// The converged solution there, its hook load not below zero.
    pub solution: Solution,
    /// How the WOB climb from the start ended.
    pub climb_end: ClimbEnd,
}

/// The whole string below its lock-up by the helix's drag ([`below_helical_lock_up`]).
pub struct BelowLockUp {
    /// The lock-up of the soft string with the helix's drag.
    pub lock_up: helical_drag::HelicalLockUp,
    /// The whole string climbed toward that soft string's largest WOB.
    pub climbed: Climbed,
}

/// Whether the whole string of `case` looks for its lock-up by the helix's drag
/// ([`below_helical_lock_up`]) before its usual solve: a slide on bottom (no rotation, WOB given)
/// that the plain soft string delivers and the soft string with the helix's drag does not, and
/// that can be put on bottom at zero WOB. Where that search ends at the largest WOB the string
/// delivers (its hook load near zero, or bracketed), it is the answer; where it stops short, the
/// usual solve and its paths run as for any case (docs/theory.md 7.7).
pub fn searched_first(case: &Case) -> bool {
    let op = &case.operation;
    // the soft passes only for a slide, the zero-WOB check only for a helical lock-up
    op.mode == Mode::Sliding
        && helical_drag::helical_lock_up(case).is_some_and(|h| h.max_wob_n > 0.0)
        && !locked_at_zero_wob(case)
}

/// Whether a climb that ended so reached the largest WOB the string delivers along its path:
/// its hook load near zero, or turning negative within the bracket.
pub fn at_largest_wob(end: ClimbEnd) -> bool {
    matches!(end, ClimbEnd::HookLoad | ClimbEnd::Bracketed)
}

/// Lock-up by the helix's drag as an answer: when the plain soft string of `case` delivers its
/// WOB and the soft string with the helix's drag does not ([`helical_drag::helical_lock_up`]),
/// the whole string climbed from its buckled shape ([`climb_from_buckled_shape`]) toward that
/// soft string's largest WOB until the hook load falls within
/// [`continuation::lock_up_hook_tolerance_n`] of zero or the path meets a limit. None when the
/// case is not so locked up, that largest WOB is zero, or no start converged. `work` gets the
/// work of the starts that did not converge.
pub fn below_helical_lock_up(case: &Case, ctl: &SolveControls, work: &mut SolveStats) -> Option<BelowLockUp> {
    let h = helical_drag::helical_lock_up(case)?;
    let tolerance = continuation::lock_up_hook_tolerance_n(h.max_wob_n);
    let climbed = climb_from_buckled_shape(case, h.max_wob_n, tolerance, ctl, work)?;
    Some(BelowLockUp { lock_up: h, climbed })
}

/// The whole string of `case` climbed toward its own WOB by [`climb_from_buckled_shape`]: for a
/// solve that found no equilibrium at that WOB from its usual start, where no lock-up applies.
/// The climb (an answer at the case's WOB where it ended at [`ClimbEnd::Target`]); None off
/// bottom, with a hook-load input, or when no start converged. `work` gets the work of the
/// starts that did not converge.
pub fn climbed_to_wob(case: &Case, ctl: &SolveControls, work: &mut SolveStats) -> Option<Climbed> {
    let op = &case.operation;
    if !op.mode.on_bottom() || op.hook_load_n.is_some() || op.wob_n <= 0.0 {
        return None;
    }
    climb_from_buckled_shape(case, op.wob_n, 0.0, ctl, work)
}

/// The whole string of `case` climbed from its buckled shape toward the WOB `target_n` (N): solved
/// from the buckled shape ([`solve_buckled`], the toolface held) at
/// [`HELICAL_LOCK_UP_FRACTIONS`] of `target_n` in turn; from the first that converges with a
/// hook load not below zero, the WOB raised toward `target_n` ([`continuation::climb_wob`],
/// warm-started steps, each step's global equilibrium within [`EQUILIBRIUM`] of the largest
/// force) until the hook load falls below `hook_tolerance_n` (N), turns negative, the target is
/// reached or the path meets a limit; all within `ctl`'s time limit. The string whirls where it
/// would at `target_n` ([`whirl_intervals`]). The WOB reached with its model and converged
/// solution (its statistics the start's and the climb's work), and how the climb ended; None
/// when no start converged. `work` gets the work of the starts that did not converge.
pub fn climb_from_buckled_shape(
    case: &Case,
    target_n: f64,
    hook_tolerance_n: f64,
    ctl: &SolveControls,
    work: &mut SolveStats,
) -> Option<Climbed> {
    let t0 = Instant::now();
    let mut at_target = case.clone();
    at_target.operation.wob_n = target_n;
    for fraction in HELICAL_LOCK_UP_FRACTIONS {
        let left = ctl.with_time_left(t0);
        let wob = fraction * target_n;
        if wob <= 0.0 || left.time_limit_s <= 0.0 {
            break;
        }
        let mut c = case.clone();
        c.operation.wob_n = wob;
        let mut model = Model::from_case(&c);
        model.whirl_md_m = whirl_intervals(&at_target, &model);
        let start = solve_holding_toolface(&mut model, &left, |m| solve_buckled(&c, m, &left));
        let converged = match start {
            Ok(s) if s.converged && s.state.hook_load_n >= 0.0 => Some(s),
            Ok(s) => {
                work.add_work(&s.stats);
                None
            }
            Err(_) => None,
        };
        tracing::info!(
            wob_n = wob,
            converged = converged.is_some(),
            "whole string from its buckled shape below the WOB aimed at"
        );
        let Some(sol) = converged else {
            continue;
        };
        let mut toward = continuation::at_wob(&model, target_n);
        toward.consistent_tangent = true;
        let in_equilibrium =
            |m: &Model, s: &Solution| extract(m, s, case.mud.density_kg_m3).equilibrium_error() <= EQUILIBRIUM;
        // the climb's time limit counts from `t0`, as `ctl`'s
        let climb = continuation::climb_wob(&toward, sol, wob, ctl, hook_tolerance_n, t0, in_equilibrium);
        tracing::info!(wob_n = climb.wob_n, end = ?climb.end, "WOB climb from the buckled shape");
        let mut solution = climb.solution;
        solution.converged = true;
        solution.stats.buckled_start = Some(true);
        return Some(Climbed {
            wob_n: climb.wob_n,
            model: continuation::at_wob(&model, climb.wob_n),
            solution,
            climb_end: climb.end,
        });
    }
    None
}
