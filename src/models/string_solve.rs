//! One static solve of a case as `drillpath solve` reports it ([`solve_string`]): the level's
//! result ([`crate::models::levels`]) with the buckling marks, the checks (yield, lock-up), the
//! survey sensors and the soft string beside it; and the answers of a whole-string solve that
//! found no equilibrium at the WOB asked for: the whole string at the largest WOB it delivers
//! (a lock-up), below its lock-up by the helix's drag ([`crate::models::helical_lock_up`]), or
//! climbed to its WOB from its buckled shape.

use crate::case::fidelity::{Choice, Level};
use crate::case::{Case, Mode};
use crate::models::buckled_start::EQUILIBRIUM_RESIDUAL_FACTOR;
use crate::models::buckling::{soft_marks, stiff_marks, unbuckled_helical_runs, Mark};
use crate::models::checks::{
    dogleg_warning, lock_up, locked_at_zero_wob, running_in_lock_up, soft_lock_up, soft_lock_up_at, yield_check,
    LockUp, YieldCheck,
};
use crate::models::fem::model::Model;
use crate::models::fem::results::{sensor_results, NodeResult, SensorResult};
use crate::models::fem::solve::continuation::{self, ClimbEnd};
use crate::models::fem::solve::{helix, SolveControls, SolveStats};
use crate::models::helical_drag;
use crate::models::helical_lock_up;
use crate::models::levels::{coarse_for_helix_pitch, fem_part_by, run_with_progress, FidelityError, LevelResult};
use crate::models::soft_comparison::{soft_comparison, SoftComparison};
use crate::models::whirl::whirl_intervals;
use std::time::Instant;

/// The warning of an answer that came from the re-solve from the buckled shape
/// ([`crate::models::buckled_start`]).
pub const BUCKLED_START_WARNING: &str = "the whole string found no equilibrium from its usual start and this answer is an equilibrium solved from a buckled shape (docs/theory.md 7.5): with wall friction a buckled string has more than one equilibrium: this one starts from a formed helix, and a string slacked off to the same WOB can keep less of its helix, its hook load measured up to 38% higher (a known limit, docs/guide.md)";

/// The warning of a stiff model `model` whose helically buckled pipe (the runs of `marks` beyond
/// the helical onset, at the node results `nodes` from the bit) has elements longer than an
/// eighth of the helix's pitch there ([`coarse_for_helix_pitch`], the pitch
/// `2 pi sqrt(2 EI / F)` at the nodes' compression): its helix, contacts and drag are then
/// coarsely resolved. None where the mesh resolves the pitch. A whole-string answer is solved
/// again on a refined mesh first (`models::levels`); the warning stays where that fails.
pub fn pitch_warning(model: &Model, nodes: &[NodeResult], marks: &[Mark]) -> Option<String> {
    let (long, h) = coarse_for_helix_pitch(model, nodes, marks)?;
    let s = |i: usize| model.mesh.nodes[i].s_m;
    let longest = long.iter().map(|&e| s(e + 1) - s(e)).fold(0.0, f64::max);
    let md = |e: usize| nodes[e].md_m;
    let (top, bottom) = long
        .iter()
        .map(|&e| (md(e + 1).min(md(e)), md(e + 1).max(md(e))))
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), (c, d)| {
            (a.min(c), b.max(d))
        });
    Some(format!(
        "the helically buckled pipe at {top:.0}-{bottom:.0} m MD has elements of up to {longest:.2} m, longer than an eighth of the helix's pitch there (2 pi sqrt(2 EI / F): {:.1} m at its largest compression): its helix, wall contacts and drag there are coarsely resolved; `element_length` at most {h:.2} m (or `--accuracy precise`) resolves them (docs/theory.md 7.5)",
        h * helix::ELEMENTS_PER_PITCH
    ))
}

/// MD intervals `(top, bottom)` (m) as a warning lists them: "a-b m MD", joined by commas.
fn md_intervals(intervals: &[(f64, f64)]) -> String {
    let each: Vec<String> = intervals.iter().map(|(a, b)| format!("{a:.0}-{b:.0} m MD")).collect();
    each.join(", ")
}

/// The warning of a rotating string that whirls in the MD intervals `whirl_md_m` (m,
/// [`crate::models::whirl`]).
pub fn whirl_warning(whirl_md_m: &[(f64, f64)]) -> String {
    format!(
        "the rotating pipe is helically buckled at {} (soft string beyond the helical onset): a real string whirls there, and the model keeps the wall friction's torque and drag there but not its lateral push round the wall, which has no static equilibrium on a helix (docs/theory.md 7.5); the wall forces there are a static helix's",
        md_intervals(whirl_md_m)
    )
}

/// A static solve of a case at a fidelity level with what `drillpath solve` reports: the
/// level's result, the nodes of its stiff part that are reported (the stiff part of a cut model
/// is reported up to the coupling point, [`crate::models::levels::FemPart::coupling`]), the buckling marks there and
/// along the soft part above, and the assumptions the user should know of.
pub struct StringSolve {
    /// The level's result.
    pub level: LevelResult,
    /// Index of the last reported node of the stiff part (None without a stiff part).
    pub last_reported_node: Option<usize>,
    /// Distance of the coupling point above the bit, m (a cut `bha` or `hybrid` model).
    pub coupling_m: Option<f64>,
    /// Buckling marks: the stiff part's reported nodes from the bit up, then the soft
    /// string's points above them.
    pub marks: Vec<Mark>,
    /// Assumptions stated in the outputs (e.g. the hole above the first survey station).
    pub notes: Vec<String>,
    /// The highest stress against the yield strength (None without a stiff part).
    pub yield_check: Option<YieldCheck>,
    /// A hook load below zero on bottom (None otherwise).
    pub lock_up: Option<LockUp>,
    /// The survey sensors on the stiff part's reported nodes, with their sag angles.
    pub sensors: Vec<SensorResult>,
    /// The soft string at the same WOB beside a converged `whole` or `hybrid` solve.
    pub soft_comparison: Option<SoftComparison>,
}

impl StringSolve {
    /// Warnings about results a real string cannot give: stress beyond yield, lock-up.
    pub fn warnings(&self, case: &Case) -> Vec<String> {
        let mut w: Vec<String> = dogleg_warning(case).into_iter().collect();
        w.extend(self.yield_check.and_then(|y| y.warning()));
        if let Some(l) = &self.lock_up {
            w.push(l.warning(case.operation.mode.name()));
        }
        if self
            .level
            .fem
            .as_ref()
            .is_some_and(|p| p.stats.buckled_start == Some(true))
        {
            w.push(BUCKLED_START_WARNING.to_string());
        }
        if let Some(p) = self.level.fem.as_ref().filter(|p| !p.model.whirl_md_m.is_empty()) {
            w.push(whirl_warning(&p.model.whirl_md_m));
        }
        w.extend(self.pitch_warning());
        let runs = unbuckled_helical_runs(self.stiff_marks(), self.reported_nodes());
        if !runs.is_empty() {
            w.push(format!(
                "the stiff pipe is compressed beyond the helical buckling onset at {} but the solve found it unbuckled there (its wall contacts stay on one side): its wall force and drag there are those of straight pipe and miss the helix's (Mitchell's r F^2/(4 EI)); treat the hook load and torque with caution (a known limit, docs/guide.md)",
                md_intervals(&runs)
            ));
        }
        w
    }
}

impl StringSolve {
    /// The warning of a stiff part whose helically buckled pipe is on a mesh too coarse for
    /// the helix's pitch ([`pitch_warning`]).
    fn pitch_warning(&self) -> Option<String> {
        let part = self.level.fem.as_ref()?;
        pitch_warning(&part.model, self.reported_nodes(), self.stiff_marks())
    }

    /// The stiff part's node results from the bit to the last reported node (empty without
    /// a stiff part).
    pub fn reported_nodes(&self) -> &[NodeResult] {
        match (&self.level.fem, self.last_reported_node) {
            (Some(part), Some(last)) => &part.results.nodes[..=last],
            _ => &[],
        }
    }
    /// The buckling marks of the stiff part's reported nodes.
    pub fn stiff_marks(&self) -> &[Mark] {
        &self.marks[..self.reported_nodes().len()]
    }
}

/// Solve `case` at the level of `choice` ([`run_with_progress`]) and add what the outputs of
/// `drillpath solve` show ([`StringSolve`]).
pub fn solve_string(
    case: &Case,
    choice: Choice,
    ctl: &SolveControls,
    on_stage: &mut dyn FnMut(usize, usize, &str),
) -> Result<StringSolve, FidelityError> {
    let (level, delivered, from_soft_string) = answered_level(case, choice, ctl, on_stage)?;
    let coupling = level.fem.as_ref().and_then(|part| part.coupling);
    let last_reported_node = level
        .fem
        .as_ref()
        .map(|part| coupling.unwrap_or(part.model.nodes() - 1));
    let coupling_m = level
        .fem
        .as_ref()
        .zip(coupling)
        .map(|(part, k)| part.model.mesh.nodes[k].s_m);
    let mut marks = Vec::new();
    if let (Some(part), Some(last)) = (&level.fem, last_reported_node) {
        marks.extend(stiff_marks(case, &part.model, &part.results.nodes[..=last]));
    }
    if let Some(soft) = &level.soft {
        marks.extend(soft_marks(case, soft, usize::from(level.fem.is_some())));
    }
    let yield_check = level
        .fem
        .as_ref()
        .zip(last_reported_node)
        .and_then(|(part, last)| yield_check(case, &part.model, &part.results.nodes[..=last]));
    let lock_up = delivered
        .or_else(|| lock_up(case, level.hook_load_n, level.wob_n).map(|l| by_helix_if_so(case, l)))
        .or_else(|| helix_missed(case, &level))
        .or_else(|| running_in_lock_up(case, level.hook_load_n))
        .or_else(|| without_hook_load(case, &level))
        .map(|l| LockUp {
            results_from_soft_string: from_soft_string,
            ..l.with_depths(case)
        });
    let sensors = level
        .fem
        .as_ref()
        .zip(last_reported_node)
        .map(|(part, last)| sensor_results(&case.string, &part.model, &part.results.nodes[..=last]))
        .unwrap_or_default();
    let soft_comparison = beside_soft(case, &level);
    Ok(StringSolve {
        level,
        last_reported_node,
        coupling_m,
        marks,
        notes: case.string_above_survey_note().into_iter().collect(),
        yield_check,
        lock_up,
        sensors,
        soft_comparison,
    })
}

/// The level result of `case` at `choice`'s level, with the answer of a whole string that finds
/// no equilibrium at the WOB asked for: the soft string's results where it cannot be put on
/// bottom at any WOB ([`soft_answer`]), else [`answer_without_equilibrium`]. A slide locked up by
/// the helix's drag ([`helical_lock_up::searched_first`]) is first solved below that lock-up
/// ([`whole_at_helical_lock_up`]), the answer where it reaches the largest WOB the string
/// delivers; otherwise its result is kept for [`answer_without_equilibrium`] and the usual solve
/// runs, its statistics counting that search's work. Returns the result, the lock-up it delivers
/// and whether its results are the soft string's.
fn answered_level(
    case: &Case,
    choice: Choice,
    ctl: &SolveControls,
    on_stage: &mut dyn FnMut(usize, usize, &str),
) -> Result<(LevelResult, Option<LockUp>, bool), FidelityError> {
    let t0 = Instant::now();
    let mut early = None;
    let mut early_work = SolveStats::default();
    if choice.level == Level::Whole && helical_lock_up::searched_first(case) {
        match whole_at_helical_lock_up(case, choice.clone(), ctl, on_stage, &mut early_work) {
            Some((l, mut r)) if l.results_at_largest_wob => {
                if let Some(part) = r.fem.as_mut() {
                    part.stats.add_work(&early_work);
                }
                r.seconds = t0.elapsed().as_secs_f64();
                return Ok((r, Some(l), false));
            }
            found => early = Some(found),
        }
    }
    let searched = early.is_some();
    // the usual solve has the time the search left
    let ctl = &ctl.with_time_left(t0);
    let mut level = run_with_progress(case, choice.clone(), ctl, on_stage)?;
    let mut delivered = None;
    let mut from_soft_string = false;
    let no_equilibrium = !level.converged && choice.level == Level::Whole;
    if no_equilibrium && locked_at_zero_wob(case) {
        if let Some(r) = soft_answer(case, &choice, ctl, &level, on_stage) {
            from_soft_string = true;
            level = r;
        }
    } else if no_equilibrium {
        let (answer, lock_up) = answer_without_equilibrium(case, choice, ctl, &mut level, on_stage, &mut early);
        if let Some(mut r) = answer {
            // the statistics count the solve that found no equilibrium too
            if let (Some(new), Some(failed)) = (r.fem.as_mut(), level.fem.as_ref()) {
                new.stats.add_work(&failed.stats);
            }
            r.seconds += level.seconds;
            delivered = lock_up;
            level = r;
        }
    }
    if searched {
        // the search before the usual solve ran: its starts that did not converge, and its
        // result where that was not taken for the answer
        if let Some(part) = early.flatten().as_ref().and_then(|(_, r)| r.fem.as_ref()) {
            early_work.add_work(&part.stats);
        }
        let failed = !level.converged;
        if let Some(part) = level.fem.as_mut() {
            part.stats.add_work(&early_work);
            if failed {
                let stages = early_work.unanswered_stages.iter().copied();
                part.stats.unanswered_stages.extend(stages);
            }
        }
        level.seconds = t0.elapsed().as_secs_f64();
    }
    Ok((level, delivered, from_soft_string))
}

/// The lock-up `l` of a solve of `case` whose hook load is below zero at the WOB asked for, as a
/// lock-up by the helix's drag where the plain soft string delivers that WOB and the soft string
/// with the helix's drag does not (the plain soft string's largest WOB, above the WOB asked for,
/// would contradict the solve); `l` otherwise.
fn by_helix_if_so(case: &Case, l: LockUp) -> LockUp {
    helical_drag::helical_lock_up(case).map_or(l, |h| LockUp {
        wob_n: l.wob_n,
        ..LockUp::by_helix(&h)
    })
}

/// The lock-up by the helix's drag of `case` (on bottom, or running in) where `level`'s results
/// come from a soft string without it (`soft`, `hybrid`) and their hook load is not below zero:
/// the helix's drag makes that hook load one the string cannot give. None otherwise (a `whole`
/// string forms its helix).
fn helix_missed(case: &Case, level: &LevelResult) -> Option<LockUp> {
    let soft_above = matches!(level.choice.level, Level::Soft | Level::Hybrid);
    if !soft_above || level.hook_load_n? < 0.0 {
        return None;
    }
    let running_in = case.operation.mode == Mode::TripIn;
    let h = match running_in {
        true => helical_drag::helical_running_in_lock_up(case),
        false => helical_drag::helical_lock_up(case),
    };
    h.map(|h| LockUp {
        results_without_helical_drag: true,
        running_in,
        ..LockUp::by_helix(&h)
    })
}

/// The lock-up of `case` at its WOB for a level without a hook load (`bha`): the soft string's
/// (named as the helix's where only the soft string with the helix's drag is locked up), its
/// results flagged as the bottom-hole assembly's at a WOB the string cannot deliver.
fn without_hook_load(case: &Case, level: &LevelResult) -> Option<LockUp> {
    if level.hook_load_n.is_some() || !level.converged {
        return None;
    }
    Some(LockUp {
        results_without_hook_load: true,
        ..soft_lock_up(case)?
    })
}

/// The answer of a whole-string solve `failed` of `case` that found no equilibrium where the
/// string is locked up at zero WOB ([`locked_at_zero_wob`]): the `soft` level at the WOB asked
/// for, with the time of the failed solve, the reason naming the lock-up. None if the soft level
/// fails.
fn soft_answer(
    case: &Case,
    choice: &Choice,
    ctl: &SolveControls,
    failed: &LevelResult,
    on_stage: &mut dyn FnMut(usize, usize, &str),
) -> Option<LevelResult> {
    let soft = Choice {
        requested: choice.requested,
        level: Level::Soft,
        reason: format!(
            "requested {}: the whole string finds no equilibrium ({} Newton iterations) and the string {}, so the soft string runs",
            choice.requested.name(),
            failed.fem.as_ref().map_or(0, |p| p.stats.iterations),
            if case.operation.mode == Mode::TripIn {
                "cannot be run in to this bit depth (lock-up running in)"
            } else {
                "cannot be put on bottom at any WOB at this bit depth (lock-up at zero WOB)"
            }
        ),
    };
    let mut r = run_with_progress(case, soft, ctl, on_stage).ok()?;
    r.seconds += failed.seconds;
    Some(r)
}

/// The soft string beside `level`'s solve of `case`: for a converged `whole` or `hybrid` solve
/// (the levels that give surface values from a stiff part), None otherwise.
fn beside_soft(case: &Case, level: &LevelResult) -> Option<SoftComparison> {
    if !matches!(level.choice.level, Level::Whole | Level::Hybrid) || !level.converged {
        return None;
    }
    Some(soft_comparison(
        case,
        level.wob_n,
        level.hook_load_n?,
        level.surface_torque_nm?,
    ))
}

/// Lock-up as an answer: when the whole string found no equilibrium at `case`'s WOB and the
/// soft string is locked up there (its hook load below zero), the whole string solved at the
/// largest WOB it delivers, its hook load zero: found by the WOB path
/// ([`crate::models::fem::solve::continuation::wob_at_zero_hook_load`], the hook load within 1%
/// of the soft string's lock-up WOB or 0.5 kN), then solved there as any case. Returns the
/// lock-up (the results' WOB in it) and the result; None when the case is not locked up, the
/// path finds no such WOB or the solve there does not converge; `spent` then gets the work that
/// ran.
fn whole_at_lock_up(
    case: &Case,
    choice: Choice,
    ctl: &SolveControls,
    on_stage: &mut dyn FnMut(usize, usize, &str),
    spent: &mut SolveStats,
) -> Option<(LockUp, LevelResult)> {
    let soft = soft_lock_up_at(case, case.operation.wob_n)?;
    let mut model = Model::from_case(case);
    // the string whirls where it is helical at the WOB it can deliver
    let mut delivered = case.clone();
    delivered.operation.wob_n = soft.max_wob_n;
    model.whirl_md_m = whirl_intervals(&delivered, &model);
    let tolerance = continuation::lock_up_hook_tolerance_n(soft.max_wob_n);
    let mut search = SolveStats::default();
    let found = continuation::wob_at_zero_hook_load(&model, ctl, tolerance, &mut search);
    let Some((wob, hook)) = found else {
        spent.add_work(&search);
        spent.unanswered_stages.push(LOCK_UP_SEARCH_STAGE);
        return None;
    };
    tracing::info!(
        wob_n = wob,
        hook_n = hook,
        "lock-up: the largest WOB with a non-negative hook load"
    );
    let mut c = case.clone();
    c.operation.wob_n = wob;
    let mut r = run_with_progress(&c, choice, ctl, on_stage).ok()?;
    if let Some(part) = r.fem.as_mut() {
        match r.converged {
            true => part.stats.add_work(&search),
            false => {
                spent.add_work(&search);
                spent.add_work(&part.stats);
                spent.unanswered_stages.push(LOCK_UP_SEARCH_STAGE);
            }
        }
    }
    let l = LockUp {
        results_at_wob_n: Some(wob),
        results_at_largest_wob: true,
        ..soft
    };
    r.converged.then_some((l, r))
}

/// How a failure message names a search for the largest WOB with a non-negative hook load
/// ([`whole_at_lock_up`]) that did not answer.
const LOCK_UP_SEARCH_STAGE: &str =
    "a search along the WOB path for the largest WOB with a non-negative hook load (lock-up)";

/// How a failure message names a solve below the lock-up by the helix's drag
/// ([`whole_at_helical_lock_up`]) whose starts from the buckled shape did not converge.
const HELICAL_LOCK_UP_STAGE: &str =
    "a solve from the buckled shape below the lock-up by the helix's drag that did not converge";

/// How a failure message names a climb from the buckled shape ([`whole_climbed_to_wob`]) whose
/// starts did not converge.
const CLIMB_STARTS_STAGE: &str = "a start from the buckled shape below the WOB for a climb that did not converge";

/// The answer of a whole-string solve `level` of `case` that found no equilibrium at its WOB, in
/// the time left of `ctl`'s limit: the whole string at the largest WOB it delivers
/// ([`whole_at_lock_up`]), below its lock-up by the helix's drag ([`whole_at_helical_lock_up`]),
/// or climbed to its WOB from its buckled shape ([`whole_climbed_to_wob`]), the first that
/// applies and answers, with its lock-up. None without one; a climb that stopped below the WOB
/// is recorded in `level`'s statistics ([`crate::models::fem::solve::SolveStats::buckled_climb_n`]) for the message.
/// `early` holds the result of [`whole_at_helical_lock_up`] where it ran before the solve
/// ([`answered_level`]): it is taken (left None) instead of running it again.
fn answer_without_equilibrium(
    case: &Case,
    choice: Choice,
    ctl: &SolveControls,
    level: &mut LevelResult,
    on_stage: &mut dyn FnMut(usize, usize, &str),
    early: &mut Option<Option<(LockUp, LevelResult)>>,
) -> (Option<LevelResult>, Option<LockUp>) {
    let left = SolveControls {
        time_limit_s: ctl.time_limit_s - level.seconds,
        ..*ctl
    };
    // the work of the stages that ran and did not answer, counted in the failed level's
    // statistics (which the answer's count too, `solve_string`)
    let mut spent = SolveStats::default();
    let locked = whole_at_lock_up(case, choice.clone(), &left, on_stage, &mut spent).or_else(|| match early.take() {
        Some(found) => found,
        None => whole_at_helical_lock_up(case, choice.clone(), &left, on_stage, &mut spent),
    });
    let (answer, lock_up) = match locked {
        Some((l, r)) => (Some(r), Some(l)),
        None => (whole_climbed_to_wob(case, choice, &left, on_stage, &mut spent), None),
    };
    if let Some(part) = level.fem.as_mut() {
        if answer.is_none() {
            part.stats.buckled_climb_n = spent.buckled_climb_n;
            part.stats
                .unanswered_stages
                .extend(spent.unanswered_stages.iter().copied());
        }
        part.stats.add_work(&spent);
    }
    (answer, lock_up)
}

/// The whole string of `case` at its WOB climbed from its buckled shape
/// ([`helical_lock_up::climbed_to_wob`]) when the solve found no equilibrium there from its
/// usual start and no lock-up applies ([`whole_from_climb`]). None where no climb ran, its
/// answer did not converge, or it stopped below the WOB: then `spent` gets the work that ran, and
/// for a climb that stopped the WOB it reached with the case's ([`SolveStats::buckled_climb_n`]).
fn whole_climbed_to_wob(
    case: &Case,
    choice: Choice,
    ctl: &SolveControls,
    on_stage: &mut dyn FnMut(usize, usize, &str),
    spent: &mut SolveStats,
) -> Option<LevelResult> {
    let t0 = Instant::now();
    on_stage(0, 1, "stiff whole string climbed from its buckled shape");
    let before = spent.iterations;
    let Some(climbed) = helical_lock_up::climbed_to_wob(case, ctl, spent) else {
        if spent.iterations > before {
            spent.unanswered_stages.push(CLIMB_STARTS_STAGE);
        }
        return None;
    };
    if climbed.climb_end != ClimbEnd::Target {
        spent.add_work(&climbed.solution.stats);
        spent.buckled_climb_n = Some((climbed.wob_n, case.operation.wob_n));
        return None;
    }
    whole_from_climb(case, choice, climbed, ctl, t0, spent)
}

/// The level result of the whole string of `case` climbed from its buckled shape (`climbed`, its
/// WOB the results'): refined and taken off the straight branch as any solve ([`fem_part_by`],
/// the residual tolerance times [`EQUILIBRIUM_RESIDUAL_FACTOR`], in the time left of `ctl`'s limit
/// since `t0`). None when that does not converge or the hook load is below zero; `spent` then
/// gets the climb's work and the re-solve's.
fn whole_from_climb(
    case: &Case,
    choice: Choice,
    climbed: helical_lock_up::Climbed,
    ctl: &SolveControls,
    t0: Instant,
    spent: &mut SolveStats,
) -> Option<LevelResult> {
    let mut c = case.clone();
    c.operation.wob_n = climbed.wob_n;
    // the refined re-solve of a buckled string at the usual residual tolerance can leave the
    // global equilibrium at a few 1e-6 of the largest force (the grid's 110 deg, 1,000 m slide)
    let left = SolveControls {
        residual_tolerance: EQUILIBRIUM_RESIDUAL_FACTOR * ctl.residual_tolerance,
        ..ctl.with_time_left(t0)
    };
    let solution = climbed.solution;
    let climb_work = solution.stats.clone();
    let Ok(part) = fem_part_by(climbed.model, &c, &left, None, |_| Ok(solution)) else {
        spent.add_work(&climb_work);
        return None;
    };
    if !part.converged || part.results.hook_load_n < 0.0 {
        spent.add_work(&part.stats);
        return None;
    }
    let mut out = LevelResult::empty(choice, climbed.wob_n);
    out.fill_from_whole(part);
    out.seconds = t0.elapsed().as_secs_f64();
    Some(out)
}

/// Lock-up by the helix's drag as an answer ([`helical_lock_up::below_helical_lock_up`]): when
/// the whole string found no equilibrium at `case`'s WOB, the whole string below that lock-up
/// ([`whole_from_climb`]). Returns the
/// lock-up (the results' WOB in it) and the result.
fn whole_at_helical_lock_up(
    case: &Case,
    choice: Choice,
    ctl: &SolveControls,
    on_stage: &mut dyn FnMut(usize, usize, &str),
    spent: &mut SolveStats,
) -> Option<(LockUp, LevelResult)> {
    let t0 = Instant::now();
    on_stage(0, 1, "stiff whole string below its helical lock-up");
    let before = spent.iterations;
    let Some(below) = helical_lock_up::below_helical_lock_up(case, ctl, spent) else {
        if spent.iterations > before {
            spent.unanswered_stages.push(HELICAL_LOCK_UP_STAGE);
        }
        return None;
    };
    let (h, climbed) = (below.lock_up, below.climbed);
    let l = LockUp {
        results_at_wob_n: Some(climbed.wob_n),
        results_at_largest_wob: helical_lock_up::at_largest_wob(climbed.climb_end),
        ..LockUp::by_helix(&h)
    };
    let out = whole_from_climb(case, choice, climbed, ctl, t0, spent)?;
    Some((l, out))
}
