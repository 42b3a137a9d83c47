//! Stiff rows of the chart: the whole-string FEM ([`crate::models::fem`]), or the stiff bottom-hole
//! assembly with the soft string above ([`crate::models::levels`] `hybrid`), for each load case at a
//! bit depth.
//!
//! **Warm starts** (whole string). Each load case starts the interior-point contact Newton
//! ([`solve_interior_point_from`], at most [`WARM_MAX_ITERATIONS`] iterations) from the same
//! load case's converged state at the previous bit depth, carried onto the new mesh by
//! [`transport_to_depth`] (the string is longer there: its top component is lengthened,
//! [`crate::string::DrillString::at_depth`]); at the first depth, or when that case has no converged state,
//! from the previous load case's state at the same depth (same mesh, other loads). Whenever a
//! warm start does not converge, [`solve`] runs from its own cold start;
//! the outcome says which start converged. Measured (docs/performance.md): the same load case
//! one depth up is the better start (3-4 iterations a row on the example wells, against 4-8
//! from the previous load case and 6-15 cold).
//!
//! **Surface torque of the non-rotating rows** (trip in, trip out, sliding). Without rotation
//! the friction force opposes the axial motion: at each contact it is parallel to the pipe's
//! axis and has no moment about it, so the surface torque is zero. The FEM gives a small
//! nonzero value: in a plane well below 1e-7 N.m (round-off; the mirror symmetry makes it
//! zero), in a 3D well a converged value of either sign that does not change with the solver
//! tolerances (same at residual tolerance 1e-7 and 1e-10, gap tolerance 1e-3 and 1e-5) but
//! shrinks as the mesh is refined (seed-daqing trip in at 500 m: 0.59 / 0.14 / 0.06 N.m with
//! the fast / default / precise presets): a discretization artefact (the gap element's friction
//! acts along the hole axis at the node, not along the deflected element), not round-off and
//! not a sign error. Measured at the bit depth of the six example wells it is at most 1.1e-3
//! (default preset) and 3.2e-3 (fast) of `T_f = sum f N r_c` over the contacts, the torque
//! the same contacts would give when rotating. A non-rotating row's torque below
//! [`NONROTATING_TORQUE_FRACTION`] x `T_f` (plus [`ZERO_TORQUE_FRACTION`] x hook load x top
//! radius for round-off) is reported as exactly 0 ([`clean_torque`]); a larger one is kept
//! (it would mean something else is wrong).
//!
//! A solve that does not converge gives [`StiffOutcome::NotConverged`]: no numbers are
//! reported for it.

use super::chart::soft_loads;
use super::row::{RowLoads, Start, StiffOutcome};
use super::{set_row_operation, ChartOperation, MODES};
use crate::case::fidelity::{choose, Level};
use crate::case::Case;
use crate::models::buckled_start;
use crate::models::buckling::{stiff_marks, unbuckled_helical_runs, Mark};
use crate::models::checks::locked_at_zero_wob;
use crate::models::fem::model::{Model, State};
use crate::models::fem::results::{extract, NodeResult, SolveResults};
use crate::models::fem::solve::continuation::ClimbEnd;
use crate::models::fem::solve::toolface::solve_holding_toolface;
use crate::models::fem::solve::{continuation, solve, solve_interior_point_from, Solution, SolveControls, SolveStats};
use crate::models::fem::warm::{source_by_distance, transport_mapped, Source};
use crate::models::helical_lock_up::{self, Climbed};
use crate::models::levels::coarse_for_helix_pitch;
use crate::models::levels::run as run_level;
use crate::models::whirl::whirl_intervals;
use crate::string::DrillString;

/// Iteration limit of a warm-started solve: beyond it the cold start (about 5-10 iterations on
/// the example wells) is cheaper than going on.
pub const WARM_MAX_ITERATIONS: usize = 20;

/// A converged solve kept for warm starts: its model and state.
pub type Solved = (Model, State);

/// Round-off allowance of a zero surface torque as a fraction of `hook load x top radius`:
/// 10 x the solver's residual tolerance relative to the load scale (1e-7,
/// [`SolveControls::default`]).
pub const ZERO_TORQUE_FRACTION: f64 = 1e-6;

/// Discretization allowance of a non-rotating row's zero surface torque, as a fraction of the
/// contacts' rotating friction torque `sum f N r_c` (3 x the largest measured artefact, module
/// documentation).
pub const NONROTATING_TORQUE_FRACTION: f64 = 1e-2;

/// `sum_i f_i N_i r_c,i` (N.m) over the contacts of nodes `0..=last` of a solved `model`: the
/// surface torque the same contacts would give a rotating string (friction factor, normal
/// force, contact radius).
pub fn rotating_friction_torque(model: &Model, res: &SolveResults, last: usize) -> f64 {
    (0..=last.min(model.nodes() - 1))
        .map(|i| model.friction[i] * res.nodes[i].contact_force_n.max(0.0) * model.mesh.nodes[i].contact_od_m / 2.0)
        .sum()
}

/// The surface torque `torque_nm` of a row: exactly 0 when the string does not rotate
/// (`omega_rad_s == 0`) and `|torque| <= NONROTATING_TORQUE_FRACTION x friction_torque_nm +
/// ZERO_TORQUE_FRACTION x |hook load| x top radius` (`friction_torque_nm` from
/// [`rotating_friction_torque`]); otherwise unchanged.
pub fn clean_torque(
    torque_nm: f64,
    omega_rad_s: f64,
    friction_torque_nm: f64,
    hook_load_n: f64,
    top_radius_m: f64,
) -> f64 {
    let allowance =
        NONROTATING_TORQUE_FRACTION * friction_torque_nm + ZERO_TORQUE_FRACTION * hook_load_n.abs() * top_radius_m;
    if omega_rad_s == 0.0 && torque_nm.abs() <= allowance {
        0.0
    } else {
        torque_nm
    }
}

/// The state of the converged solve `prev` (bit at another depth) carried onto `model`, the
/// model of `string` (see the module documentation). With `d` the bit's move:
///
/// - in the top component (the drill pipe, lengthened by `d`), from `d` above its bottom up,
///   each node takes the state of the previous string at the same MD (interpolated between
///   nodes; offsets unscaled so that the pipe's shape along the hole stays smooth): the pipe
///   keeps its place in the hole (on the low side in a tangent, on the high side of a build
///   under tension, across a casing shoe);
/// - below it (the bottom-hole assembly, and the first `d` of pipe), each node takes the state
///   of the point at its distance from the bit, its lateral offset scaled to its clearance:
///   the assembly keeps its shape relative to the bit. Its triads are turned about the hole
///   axis by the twist between the two rules at the lowest node of the first, and the first
///   rule's nodes are moved along the hole by the difference of the two rules' axial offsets
///   there, so that twist and stretch stay continuous along the string;
/// - a node above the previous string's top takes the top node's state.
pub fn transport_to_depth(prev: &Solved, model: &Model, string: &DrillString) -> State {
    let (pm, ps) = prev;
    let top_source = Source::node(pm.nodes() - 1);
    let by_distance = |i: usize| -> Source {
        match source_by_distance(pm, model.mesh.nodes[i].s_m) {
            Some(src) => Source {
                scale_to_clearance: true,
                ..src
            },
            None => top_source,
        }
    };
    let same_top = pm.mesh.nodes.last().map(|n| n.component) == model.mesh.nodes.last().map(|n| n.component);
    let d = model.bit_md_m - pm.bit_md_m;
    let pipe_bottom = string.components.last().map_or(f64::INFINITY, |c| c.bottom_m);
    let by_md = |i: usize| -> Option<Source> {
        let s = model.mesh.nodes[i].s_m - d;
        (same_top && d > 0.0 && s >= pipe_bottom - 1e-9).then(|| source_by_distance(pm, s).unwrap_or(top_source))
    };
    let mut st = transport_mapped(pm, ps, model, |i| Some(by_md(i).unwrap_or_else(|| by_distance(i))));
    // continuity of twist and stretch at the lowest node of the MD rule, carried by both rules
    let Some(k) = (0..model.nodes()).find(|&i| by_md(i).is_some()) else {
        return st;
    };
    let alt = transport_mapped(pm, ps, model, |i| (i == k).then(|| by_distance(i)));
    let t = model.basis[k].column(0).into_owned();
    let (a, b) = (
        alt.triads[k].column(1).into_owned(),
        st.triads[k].column(1).into_owned(),
    );
    let (a, b) = (a - t * t.dot(&a), b - t * t.dot(&b));
    let twist = t.dot(&a.cross(&b)).atan2(a.dot(&b));
    for i in 0..k {
        let axis = nalgebra::Unit::new_normalize(model.basis[i].column(0).into_owned());
        let r = nalgebra::Rotation3::from_axis_angle(&axis, twist);
        st.triads[i] = r.matrix() * st.triads[i];
    }
    let stretch = t.dot(&(alt.x[k] - st.x[k]));
    for i in k..model.nodes() {
        st.x[i] += model.basis[i].column(0) * stretch;
        st.md[i] += stretch;
    }
    st
}

/// Stiff whole-string solve of `case` (string and operation set for the row), warm-started
/// from `warm` when given (`(state's model, state, how it relates)`: the same mesh for
/// [`Start::PreviousCase`], carried by [`transport_to_depth`] for [`Start::PreviousDepth`]);
/// returns the outcome and the converged solve (for the next warm start).
pub fn stiff_row(case: &Case, warm: Option<(&Solved, Start)>) -> (StiffOutcome, Option<Solved>) {
    let mut model = Model::from_case(case);
    model.whirl_md_m = whirl_intervals(case, &model);
    let ctl = SolveControls::from_settings(&case.solver);
    let mut iterations = 0;
    let t0 = std::time::Instant::now();
    if let Some((prev, start)) = warm {
        let state = if start == Start::PreviousCase && prev.0.nodes() == model.nodes() {
            prev.1.clone()
        } else {
            transport_to_depth(prev, &model, &case.string)
        };
        let mut consistent = model.clone();
        consistent.consistent_tangent = true;
        let warm_ctl = SolveControls {
            max_iterations: ctl.max_iterations.min(WARM_MAX_ITERATIONS),
            ..ctl
        };
        // a bent housing is held at its toolface against the string's twist
        match solve_holding_toolface(&mut consistent, &warm_ctl, |m| {
            solve_interior_point_from(m, state, &warm_ctl)
        }) {
            Ok(sol) if sol.converged => {
                let mut model = model;
                model.kink = consistent.kink;
                let out = converged(
                    case,
                    &model,
                    &sol,
                    sol.stats.iterations,
                    t0.elapsed().as_secs_f64(),
                    start,
                    None,
                );
                return (out, Some((model, sol.state)));
            }
            Ok(sol) => {
                iterations += sol.stats.iterations;
                tracing::info!("warm start ({start:?}) did not converge; cold start");
            }
            Err(e) => tracing::info!("warm start ({start:?}) failed ({e}); cold start"),
        }
    }
    // a slide locked up by the helix's drag is solved below that lock-up first, as `solve` does
    let mut early = None;
    if helical_lock_up::searched_first(case) {
        let mut spent = SolveStats::default();
        let found = helical_lock_up::below_helical_lock_up(case, &ctl, &mut spent).map(|b| b.climbed);
        iterations += spent.iterations;
        match found {
            Some(c) if helical_lock_up::at_largest_wob(c.climb_end) => {
                return (climbed_row(case, &c, iterations, t0, true), None);
            }
            mut found => {
                // counted here whether or not the row ends up answered from it
                if let Some(c) = found.as_mut() {
                    iterations += c.solution.stats.iterations;
                    c.solution.stats.iterations = 0;
                }
                early = Some(found);
            }
        }
    }
    // the row's solve has the time the search left
    let ctl = match early {
        Some(_) => ctl.with_time_left(t0),
        None => ctl,
    };
    // a string that cannot be put on bottom at any WOB is not followed along the paths (decided
    // once, where the solve first asks)
    let locked = std::cell::OnceCell::new();
    let locked_up = || *locked.get_or_init(|| locked_at_zero_wob(case));
    let cold = |m: &Model| buckled_start::solve_damped_before_paths(case, m, &ctl, locked_up).map(|(sol, _)| sol);
    match solve_holding_toolface(&mut model, &ctl, cold) {
        Ok(sol) if sol.converged => {
            // the damped re-solve from the buckled shape may answer before the paths
            let start = match sol.stats.buckled_start {
                Some(true) => Start::BuckledShape,
                _ => Start::Cold,
            };
            let out = converged(
                case,
                &model,
                &sol,
                iterations + sol.stats.iterations,
                t0.elapsed().as_secs_f64(),
                start,
                None,
            );
            (out, Some((model, sol.state)))
        }
        Ok(sol) => {
            let before = iterations;
            let iterations = before + sol.stats.iterations;
            if locked_up() {
                // no equilibrium on bottom exists: no WOB path or climb can reach one
                return (StiffOutcome::LockedAtZeroWob { iterations }, None);
            }
            // the work of the stages below that ran and did not answer
            let mut spent = SolveStats::default();
            if let Some(out) = at_lock_up(case, &model, &ctl, iterations, t0, &mut spent) {
                return (out, None);
            }
            // its statistics count the cold solve's work and its own
            let sol = buckled_start::solve_from_buckled_start(case, &model, sol, &ctl);
            // the row's iterations: the warm tries', the solves' so far and `spent`
            let total = |spent: &SolveStats| before + sol.stats.iterations + spent.iterations;
            if sol.converged {
                let seconds = t0.elapsed().as_secs_f64();
                let out = converged(case, &model, &sol, total(&spent), seconds, Start::BuckledShape, None);
                return (out, Some((model, sol.state)));
            }
            if let Some(out) = at_helical_lock_up(case, &ctl, total(&spent), t0, &mut spent, early.take()) {
                return (out, None);
            }
            match helical_lock_up::climbed_to_wob(case, &ctl.with_time_left(t0), &mut spent) {
                Some(c) if c.climb_end == ClimbEnd::Target => {
                    let out = climbed_row(case, &c, total(&spent), t0, false);
                    return (out, Some((c.model, c.solution.state)));
                }
                Some(c) => spent.add_work(&c.solution.stats),
                None => {}
            }
            let residual = sol.stats.residual_history.last().copied().unwrap_or(f64::NAN);
            let iterations = total(&spent);
            (StiffOutcome::NotConverged { iterations, residual }, None)
        }
        Err(e) => (StiffOutcome::Failed(e.to_string()), None),
    }
}

/// Lock-up as a row's answer: where the stiff solve of `model` (an on-bottom row of `case`,
/// WOB-driven) found no equilibrium, the largest WOB with a non-negative hook load along the
/// WOB path ([`continuation::wob_at_zero_hook_load`], the hook load within 1% of the row's
/// WOB or 0.5 kN), and the string solved there: the row's loads at that WOB (the converged
/// solve's; `iterations` before it added). None when the model is not WOB-driven, the hook
/// load does not turn negative below the row's WOB, or the solve there does not converge.
fn at_lock_up(
    case: &Case,
    model: &Model,
    ctl: &SolveControls,
    iterations: usize,
    t0: std::time::Instant,
    spent: &mut SolveStats,
) -> Option<StiffOutcome> {
    if !continuation::applies(model) {
        return None;
    }
    let tolerance = continuation::lock_up_hook_tolerance_n(model.loads.wob_n);
    let mut search = SolveStats::default();
    let found = continuation::wob_at_zero_hook_load(model, ctl, tolerance, &mut search);
    let Some((wob, _)) = found else {
        spent.add_work(&search);
        return None;
    };
    let mut c = case.clone();
    c.operation.wob_n = wob;
    let mut m = Model::from_case(&c);
    m.whirl_md_m = whirl_intervals(&c, &m);
    let sol = solve_holding_toolface(&mut m, ctl, |m| solve(m, ctl)).ok()?;
    if !sol.converged {
        spent.add_work(&search);
        spent.add_work(&sol.stats);
        return None;
    }
    tracing::info!(
        wob_n = wob,
        "lock-up: the row's loads at the largest WOB the string delivers"
    );
    let seconds = t0.elapsed().as_secs_f64();
    let its = iterations + search.iterations + sol.stats.iterations;
    Some(converged(&c, &m, &sol, its, seconds, Start::Cold, Some(wob)))
}

/// Lock-up by the helix's drag as a row's answer ([`helical_lock_up::below_helical_lock_up`]):
/// where the stiff solve of an on-bottom row of `case` found no equilibrium and the soft string
/// with the helix's drag is locked up while the plain one is not, the whole string below that
/// lock-up: the row's loads there (`lock_up_wob_n` that WOB, `iterations` before it added).
/// None when no such solve converges with a hook load not below zero. `early`: that search's
/// result where it ran before the row's solve (its work already in `iterations`), taken instead
/// of running it again.
fn at_helical_lock_up(
    case: &Case,
    ctl: &SolveControls,
    iterations: usize,
    t0: std::time::Instant,
    spent: &mut SolveStats,
    early: Option<Option<Climbed>>,
) -> Option<StiffOutcome> {
    let before = spent.iterations;
    let below = match early {
        Some(found) => found?,
        None => helical_lock_up::below_helical_lock_up(case, &ctl.with_time_left(t0), spent)?.climbed,
    };
    // the starts that did not converge before the one climbed from
    let iterations = iterations + spent.iterations - before;
    Some(climbed_row(case, &below, iterations, t0, true))
}

/// The row of `case` from the whole string climbed from its buckled shape `c`, at its WOB
/// (`lock_up`: as the row's lock-up WOB; `iterations` before the climb added).
fn climbed_row(case: &Case, c: &Climbed, iterations: usize, t0: std::time::Instant, lock_up: bool) -> StiffOutcome {
    let mut at = case.clone();
    at.operation.wob_n = c.wob_n;
    let its = iterations + c.solution.stats.iterations;
    let seconds = t0.elapsed().as_secs_f64();
    let lock_up_wob_n = lock_up.then_some(c.wob_n);
    converged(
        &at,
        &c.model,
        &c.solution,
        its,
        seconds,
        Start::BuckledShape,
        lock_up_wob_n,
    )
}

fn top_radius(case: &Case) -> f64 {
    case.string.components.last().map_or(0.0, |c| c.body_od_m / 2.0)
}

/// The length of `model`'s whirling intervals ([`Model::whirl_md_m`]), m.
fn whirl_length_m(model: &Model) -> f64 {
    model.whirl_md_m.iter().map(|(top, bottom)| bottom - top).sum()
}

/// The row of a converged whole-string solve `sol` of `model` (`iterations` over its attempts).
fn converged(
    case: &Case,
    model: &Model,
    sol: &Solution,
    iterations: usize,
    seconds: f64,
    start: Start,
    lock_up_wob_n: Option<f64>,
) -> StiffOutcome {
    let res = extract(model, sol, case.mud.density_kg_m3);
    let marks = stiff_marks(case, model, &res.nodes);
    let unbuckled_helical_m = unbuckled_length_m(&marks, &res.nodes);
    let coarse_for_pitch_m = coarse_for_pitch_length_m(model, &res.nodes, &marks, model.nodes() - 1);
    let friction_torque_nm = rotating_friction_torque(model, &res, model.nodes() - 1);
    let max_f = res.nodes.iter().map(|n| n.contact_force_n).fold(0.0, f64::max);
    StiffOutcome::Converged {
        loads: RowLoads {
            hook_load_n: res.hook_load_n,
            surface_torque_nm: clean_torque(
                res.surface_torque_nm,
                case.operation.omega_rad_s(),
                friction_torque_nm,
                res.hook_load_n,
                top_radius(case),
            ),
            max_contact_force_n: max_f,
            max_side_force_n_per_m: 0.0,
        },
        iterations,
        seconds,
        start,
        lock_up_wob_n,
        unbuckled_helical_m,
        whirl_m: whirl_length_m(model),
        coarse_for_pitch_m,
    }
}

/// Total length (m) of the elements of `model` below node `top` (results `nodes` and their
/// [`stiff_marks`] `marks`, from the bit up) in its helically buckled pipe that are longer than
/// an eighth of the helix's pitch there ([`coarse_for_helix_pitch`]).
fn coarse_for_pitch_length_m(model: &Model, nodes: &[NodeResult], marks: &[Mark], top: usize) -> f64 {
    coarse_for_helix_pitch(model, nodes, marks).map_or(0.0, |(elements, _)| {
        elements
            .iter()
            .filter(|&&e| e < top)
            .map(|&e| model.mesh.nodes[e + 1].s_m - model.mesh.nodes[e].s_m)
            .sum()
    })
}

/// Total length (m) of the runs of `nodes` (a stiff solve's results from the bit up, `marks`
/// their [`stiff_marks`]) compressed beyond the helical onset where the solved string lies
/// unbuckled ([`unbuckled_helical_runs`]).
fn unbuckled_length_m(marks: &[Mark], nodes: &[NodeResult]) -> f64 {
    unbuckled_helical_runs(marks, nodes)
        .iter()
        .map(|(top, bottom)| bottom - top)
        .sum()
}

/// Stiff outcomes of the five load cases ([`MODES`] order) for `case` with its string already
/// refitted to `bit_md_m` (see [`Case::at_bit_depth`]). `wob_n[j]` is the WOB of case
/// `MODES[j]` (the soft rows' WOB, which may be below the chart's where the string cannot give
/// it). `previous_depth[j]` is case `MODES[j]`'s converged solve at the previous bit depth
/// (empty or `None`: none); each case starts from it, or else from the last converged case of
/// this depth (module documentation). The converged solves of this depth are returned for the
/// next one.
pub fn stiff_depth(
    case: &Case,
    bit_md_m: f64,
    op: &ChartOperation,
    wob_n: &[f64],
    previous_depth: &[Option<Solved>],
) -> (Vec<StiffOutcome>, Vec<Option<Solved>>) {
    let mut c = case.clone();
    let mut solved_here: Vec<Option<Solved>> = Vec::with_capacity(MODES.len());
    let mut out = Vec::with_capacity(MODES.len());
    for (j, mode) in MODES.into_iter().enumerate() {
        set_row_operation(&mut c, bit_md_m, mode, op);
        c.operation.wob_n = wob_n.get(j).copied().unwrap_or(c.operation.wob_n);
        // a case that did not converge leaves the last converged state for the next one
        let last = solved_here.iter().rev().find_map(|s| s.as_ref());
        let prev = previous_depth.get(j).and_then(|p| p.as_ref());
        let warm = match (prev, last) {
            (Some(p), _) => Some((p, Start::PreviousDepth)),
            (None, Some(l)) => Some((l, Start::PreviousCase)),
            (None, None) => None,
        };
        let (outcome, solved) = stiff_row(&c, warm);
        solved_here.push(solved);
        out.push(outcome);
    }
    (out, solved_here)
}

/// The `hybrid` row of `case` (string and operation set for the row): the stiff bottom-hole
/// assembly cut where it lies on the wall, and the soft string from the coupling point to the
/// surface ([`crate::models::levels`]); cold-started (the cut model is short). The largest contact
/// force is the larger of the FEM's largest nodal force and the soft string's per-joint force.
pub fn hybrid_row(case: &Case) -> StiffOutcome {
    let ctl = SolveControls::from_settings(&case.solver);
    let t0 = std::time::Instant::now();
    let lr = match run_level(
        case,
        choose(
            crate::case::Fidelity::Level(Level::Hybrid),
            crate::case::fidelity::Purpose::Loads,
        ),
        &ctl,
    ) {
        Ok(lr) => lr,
        Err(e) => return StiffOutcome::Failed(e.to_string()),
    };
    debug_assert_eq!(lr.choice.level, Level::Hybrid);
    let iterations = lr.fem.as_ref().map_or(0, |f| f.stats.iterations);
    if !lr.converged {
        let residual = lr
            .fem
            .as_ref()
            .and_then(|f| f.stats.residual_history.last().copied())
            .unwrap_or(f64::NAN);
        return StiffOutcome::NotConverged { iterations, residual };
    }
    let (Some(hook), Some(torque)) = (lr.hook_load_n, lr.surface_torque_nm) else {
        return StiffOutcome::Failed("the hybrid level gave no surface values".into());
    };
    // stiff results are reported up to the coupling node (above it the cut's clamp disturbs
    // them); the soft string above adds no torque without rotation
    let (mut max_f, friction_torque, unbuckled_helical_m, coarse_for_pitch_m) =
        lr.fem.as_ref().map_or((0.0, 0.0, 0.0, 0.0), |f| {
            let k = f.coupling.unwrap_or(f.model.nodes() - 1);
            let marks = stiff_marks(case, &f.model, &f.results.nodes);
            let max_f = f.results.nodes[..=k]
                .iter()
                .map(|n| n.contact_force_n)
                .fold(0.0, f64::max);
            (
                max_f,
                rotating_friction_torque(&f.model, &f.results, k),
                unbuckled_length_m(&marks[..=k], &f.results.nodes[..=k]),
                coarse_for_pitch_length_m(&f.model, &f.results.nodes, &marks, k),
            )
        });
    if let Some(s) = &lr.soft {
        max_f = max_f.max(soft_loads(s, &case.string, case.operation.bit_md_m).max_contact_force_n);
    }
    StiffOutcome::Converged {
        loads: RowLoads {
            hook_load_n: hook,
            surface_torque_nm: clean_torque(
                torque,
                case.operation.omega_rad_s(),
                friction_torque,
                hook,
                top_radius(case),
            ),
            max_contact_force_n: max_f,
            max_side_force_n_per_m: 0.0,
        },
        iterations,
        seconds: t0.elapsed().as_secs_f64(),
        start: Start::Cold,
        lock_up_wob_n: None,
        unbuckled_helical_m,
        whirl_m: lr.fem.as_ref().map_or(0.0, |f| whirl_length_m(&f.model)),
        coarse_for_pitch_m,
    }
}

/// The [`hybrid_row`]s of the five load cases ([`MODES`] order) for `case` with its string
/// already refitted to `bit_md_m`; `wob_n` as in [`stiff_depth`].
pub fn hybrid_depth(case: &Case, bit_md_m: f64, op: &ChartOperation, wob_n: &[f64]) -> Vec<StiffOutcome> {
    let mut c = case.clone();
    MODES
        .into_iter()
        .enumerate()
        .map(|(j, mode)| {
            set_row_operation(&mut c, bit_md_m, mode, op);
            c.operation.wob_n = wob_n.get(j).copied().unwrap_or(c.operation.wob_n);
            hybrid_row(&c)
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Reference: the rule of [`clean_torque`] by hand. Hook load 300 kN, top radius 0.0635 m,
    /// contacts' rotating friction torque 3.5 kN.m: allowance 0.01 x 3500 + 1e-6 x 300e3 x
    /// 0.0635 = 35.019 N.m.
    #[test]
    fn non_rotating_torque_is_cleaned_within_the_allowance_only() {
        let (h, r, tf) = (300e3, 0.0635, 3500.0);
        assert_eq!(clean_torque(-0.64, 0.0, tf, h, r), 0.0);
        assert_eq!(clean_torque(35.0, 0.0, tf, h, r), 0.0);
        assert_eq!(clean_torque(35.1, 0.0, tf, h, r), 35.1);
        assert_eq!(clean_torque(-0.64, 7.0, tf, h, r), -0.64);
    }
}
