//! The string solved with the bit at one position: at each state a steerable string is solved
//! in (the toolfaces of a rotating bent housing, the steering and neutral shares of a rotary
//! steerable system; docs/theory.md 9.9, 9.10), the states in parallel, each warm-started from
//! its own last solve, and the bit-rock law's drilling direction averaged over them.

use super::PredictError;
use crate::case::{BitRock, Case};
use crate::geometry::{HoleSize, Vec3, WellPath};
use crate::models::buckled_start::{solve_damped_before_paths, solve_from_buckled_start};
use crate::models::fem::bha::{bha_model, cut_is_whole};
use crate::models::fem::model::{Model, State};
use crate::models::fem::results::{bit_with_sensor, BitResult};
use crate::models::fem::solve::toolface::solve_holding_toolface;
use crate::models::fem::solve::{solve, solve_interior_point_from, Solution, SolveControls};
use crate::models::fem::warm::transport_state;
use crate::models::whirl::whirl_intervals;
use crate::predict::law::BitAction;
use crate::predict::law::{drilling_direction, LawParams};
use crate::predict::revolution::{mean_bit, mean_direction, SteerState};
use rayon::prelude::*;

/// Newton iterations a state's solve warm-started from the same state's last solve may take
/// before the cold start takes over (such warm starts of `wells/horizontal/steered.toml`'s
/// toolfaces converge in 1-9; one that has not in 25 is a poor start: docs/performance.md,
/// "Toolfaces over a revolution").
pub const OWN_WARM_MAX_ITERATIONS: usize = 25;

/// A solved string kept to warm-start the next solve (the next step of a march, the next
/// evaluation of a step, the next curvature of a steady-dogleg search).
#[derive(Debug, Clone)]
pub struct Warm {
    /// The model at the first state solved (its mesh, node bases and axis points are every
    /// state's).
    pub model: Model,
    /// Its solved state.
    pub state: State,
    /// The solved strings at the other states, in order (empty for one state).
    pub others: Vec<StateStart>,
}

/// A state's solved string, kept to warm-start the next solve at the same state.
#[derive(Debug, Clone)]
pub struct StateStart {
    /// The state it was solved at.
    pub steer: SteerState,
    /// The solved state (on the mesh of [`Warm::model`]).
    pub state: State,
    /// The bent housing's kink turn beyond the toolface found by the solve, rad
    /// ([`Model::kink_correction_rad`]; 0 for a straight string).
    pub kink_correction_rad: f64,
}

/// One solved bit position: the model, the solution's state, the bit results and the
/// drilling direction.
pub(crate) struct BitSolve {
    /// The model (at the first state solved).
    pub(crate) model: Model,
    /// Its solved state.
    pub(crate) state: State,
    /// The solved strings at the other states.
    pub(crate) others: Vec<StateStart>,
    /// Bit forces and tilt (the mean over the toolfaces of a rotating bent housing,
    /// [`crate::predict::revolution::mean_bit`]).
    pub(crate) bit: BitResult,
    /// Drilling direction of the bit-rock law (global unit vector; the mean over the
    /// toolfaces of a rotating bent housing, [`crate::predict::revolution::mean_direction`]).
    pub(crate) direction: Vec3,
    /// Newton iterations of the solves.
    pub(crate) iterations: usize,
    /// The turn of a sliding bent housing's toolface by the motor's reactive torque, rad
    /// (the first state's; None when `reactive_torque` is off or the string rotates).
    pub(crate) reactive_turn_rad: Option<f64>,
    /// Whether a state's solve came from the re-solve from the buckled shape.
    pub(crate) buckled_start: bool,
}

impl BitSolve {
    /// The solve kept as a warm start.
    pub(crate) fn into_warm(self) -> Warm {
        Warm {
            model: self.model,
            state: self.state,
            others: self.others,
        }
    }

    /// A copy of the solve as a warm start for the other states (None for one state: there
    /// are none).
    pub(crate) fn warm_copy(&self) -> Option<Warm> {
        (!self.others.is_empty()).then(|| Warm {
            model: self.model.clone(),
            state: self.state.clone(),
            others: self.others.clone(),
        })
    }
}

/// The bit action seen by the law.
pub fn bit_action(bit: &BitResult) -> BitAction {
    BitAction {
        wob_n: bit.wob_n,
        build_force_n: bit.build_force_n,
        walk_force_n: bit.walk_force_n,
        tilt_inc_rad: bit.tilt_inc_rad,
        tilt_azi_rad: bit.tilt_azi_rad,
    }
}

/// Solve the model warm-started from `warm` with at most `warm_iterations` Newton iterations;
/// without one, or when the warm start fails, the full cold [`solve`] (its own start), and
/// where that finds no equilibrium on a whole-string model, the re-solve from the buckled shape
/// ([`solve_from_buckled_start`]; `whole_case`: the case refitted to the model's bit depth and
/// path, None for a cut model).
fn solve_step(
    model: &Model,
    warm: Option<State>,
    warm_iterations: usize,
    ctl: &SolveControls,
    whole_case: Option<&Case>,
) -> Result<Solution, PredictError> {
    let md = model.bit_md_m;
    let wrap = |source| PredictError::Solve { md_m: md, source };
    if let Some(state) = warm {
        // a failed warm start (not converged, or a singular system from a poor start) falls
        // back to the cold start below
        let warm_ctl = SolveControls {
            max_iterations: ctl.max_iterations.min(warm_iterations),
            ..*ctl
        };
        match solve_interior_point_from(model, state, &warm_ctl) {
            Ok(sol) if sol.converged => return Ok(sol),
            Ok(_) => tracing::info!(md, "warm-started solve did not converge; solving from scratch"),
            Err(e) => tracing::info!(md, error = %e, "warm-started solve failed; solving from scratch"),
        }
    }
    // a buckled slide tries the damped re-solve before the paths, as `solve` does
    let mut sol = match whole_case {
        Some(case) => solve_damped_before_paths(case, model, ctl, || false).map(|(sol, _)| sol),
        None => solve(model, ctl),
    }
    .map_err(wrap)?;
    if let (false, Some(case)) = (sol.converged, whole_case) {
        sol = solve_from_buckled_start(case, model, sol, ctl);
    }
    if sol.converged {
        return Ok(sol);
    }
    Err(not_converged(model, &sol, ctl))
}

/// The error of the solve `sol` of `model` that did not converge.
fn not_converged(model: &Model, sol: &Solution, ctl: &SolveControls) -> PredictError {
    let limit = if sol.stats.timed_out {
        format!("; {}", crate::models::diagnose::time_limit_phrase(ctl))
    } else {
        String::new()
    };
    let detail = limit
        + &if sol.stats.chattering_nodes.is_empty() {
            String::new()
        } else {
            let near: Vec<String> = sol
                .stats
                .chattering_nodes
                .iter()
                .take(8)
                .map(|&i| format!("{:.2} m", model.md_ref[i]))
                .collect();
            format!("; contacts changing state at {}", near.join(", "))
        };
    PredictError::NotConverged {
        md_m: model.bit_md_m,
        iterations: sol.stats.iterations,
        residual: sol.stats.residual_history.last().copied().unwrap_or(f64::NAN),
        penetration: sol.stats.max_penetration,
        detail,
    }
}

/// Where one state's solve starts: a solved state on the mesh of `model` (None: cold), the
/// kink's first turn beyond the toolface (rad), and the iterations the warm start may take.
struct Start<'a> {
    from: Option<(&'a Model, &'a State)>,
    kink_correction_rad: f64,
    warm_iterations: usize,
}

/// The start of the solve at state `k` of `faces`: the first from `warm` (its solved state,
/// its kink turn, the full iterations); another from its own last solve, in `latest` or else
/// in `warm`, when one of them was solved at the same states (its kink turn, at most
/// [`OWN_WARM_MAX_ITERATIONS`]); else cold, the kink turned as `warm`'s.
fn start_of<'a>(k: usize, faces: &[SteerState], warm: &'a Option<Warm>, latest: &'a Option<Warm>) -> Start<'a> {
    let warm_turn = warm.as_ref().map(|w| w.model.kink_correction_rad()).unwrap_or(0.0);
    if k == 0 {
        return Start {
            from: warm.as_ref().map(|w| (&w.model, &w.state)),
            kink_correction_rad: warm_turn,
            warm_iterations: usize::MAX,
        };
    }
    let same_states =
        |w: &&Warm| w.others.len() + 1 == faces.len() && w.others.iter().zip(&faces[1..]).all(|(o, f)| o.steer == *f);
    let own = [latest, warm].into_iter().flatten().find(same_states);
    match own {
        Some(w) => {
            let o = &w.others[k - 1];
            Start {
                from: Some((&w.model, &o.state)),
                kink_correction_rad: o.kink_correction_rad,
                warm_iterations: OWN_WARM_MAX_ITERATIONS,
            }
        }
        None => Start {
            from: None,
            kink_correction_rad: warm_turn,
            warm_iterations: 0,
        },
    }
}

/// One state's solve: the model, its solved state, the bit results, the iterations.
struct StateSolve {
    model: Model,
    state: State,
    bit: BitResult,
    iterations: usize,
    reactive_turn_rad: Option<f64>,
    buckled_start: bool,
}

/// Solve the string of `base` (the cut model of the case at the state `st`: the RSS neutral or
/// not, its consistent tangent on; `case` gives the mud and the sensors) at the state `st` from
/// `start`; a bent housing's kink is held at the state's toolface ([`solve_holding_toolface`]).
/// `whole_case`: for a whole-string `base`, the case refitted to its bit depth and path (for
/// the re-solve from the buckled shape, [`solve_step`]).
fn solve_state(
    case: &Case,
    base: &Model,
    st: &SteerState,
    start: Start<'_>,
    ctl: &SolveControls,
    whole_case: Option<&Case>,
) -> Result<StateSolve, PredictError> {
    let md_m = base.bit_md_m;
    let mut model = base.clone();
    model.set_toolface(st.toolface_rad);
    model.turn_kink(st.toolface_rad + start.kink_correction_rad);
    let warm_state = start
        .from
        .filter(|(m, _)| m.nodes() == model.nodes())
        .map(|(m, s)| transport_state(m, s, &model));
    // the Newton holds the housing at the state's toolface as it iterates
    model.toolface_hold_rad = model.kink.and(model.reactive.is_none().then_some(st.toolface_rad));
    let mut sol = solve_step(&model, warm_state, start.warm_iterations, ctl, whole_case)?;
    if model.kink.is_some() {
        // the housing turned back to its toolface against the string's twist
        sol = solve_holding_toolface(&mut model, ctl, |_| Ok(sol))
            .map_err(|source| PredictError::Solve { md_m, source })?;
        if !sol.converged {
            return Err(not_converged(&model, &sol, ctl));
        }
    }
    let bit = bit_with_sensor(&case.string, &model, &sol, case.mud.density_kg_m3);
    Ok(StateSolve {
        model,
        reactive_turn_rad: sol.stats.reactive_turn.map(|t| t.turn_rad),
        buckled_start: sol.stats.buckled_start == Some(true),
        state: sol.state,
        bit,
        iterations: sol.stats.iterations,
    })
}

/// Solve the string of `case` with the bit at `md_m` in `path` at each of the states `faces`
/// ([`crate::predict::revolution::toolfaces`]) and apply the bit-rock law of `bit_rock` to
/// each: the first state's model and state, the others' solved states, the mean bit results
/// and the mean drilling direction. The states are solved in parallel (rayon's pool) and
/// independently, so the answer does not depend on the threads: the first warm-started from
/// `warm`, each other from its own last solve (in `latest`, the last evaluation of the same
/// step, or else in `warm`) or, without one, from scratch with the kink turned as `warm`'s; a
/// bent housing's kink is held at its toolface ([`solve_holding_toolface`]).
#[allow(clippy::too_many_arguments)]
pub(crate) fn solve_bit(
    case: &Case,
    bit_rock: &BitRock,
    path: &WellPath,
    hole: &HoleSize,
    md_m: f64,
    cut_m: f64,
    (warm, latest): (&Option<Warm>, &Option<Warm>),
    ctl: &SolveControls,
    faces: &[SteerState],
) -> Result<BitSolve, PredictError> {
    // the cut model of the case, and of the case with its rotary steerable system neutral for
    // the share of the time it does not steer, each built once for its states; a whole string
    // whirls where its rotating pipe is helically buckled, as in `solve`
    let whole_case = cut_is_whole(&case.string, cut_m).then(|| {
        let mut c = case.at_bit_depth(md_m);
        c.well.path = path.clone();
        c
    });
    let model_of = |c: &Case| {
        let mut m = bha_model(c, path, hole, md_m, cut_m);
        m.consistent_tangent = true;
        if let Some(w) = &whole_case {
            m.whirl_md_m = whirl_intervals(w, &m);
        }
        m
    };
    let steering = faces.iter().any(|f| !f.neutral).then(|| model_of(case));
    let neutral = faces.iter().any(|f| f.neutral).then(|| {
        let mut c = case.clone();
        c.string = c.string.rss_neutral();
        model_of(&c)
    });
    let solve_at = |k: usize, st: &SteerState| {
        let base = if st.neutral { &neutral } else { &steering };
        let base = base.as_ref().expect("a model for each kind of state");
        solve_state(
            case,
            base,
            st,
            start_of(k, faces, warm, latest),
            ctl,
            whole_case.as_ref(),
        )
    };
    let solved: Vec<Result<StateSolve, PredictError>> = if faces.len() == 1 {
        vec![solve_at(0, &faces[0])]
    } else {
        faces.par_iter().enumerate().map(|(k, st)| solve_at(k, st)).collect()
    };
    // the first error in the states' order
    let solved = solved.into_iter().collect::<Result<Vec<_>, _>>()?;
    let frame = path.frame_at(md_m);
    let params = LawParams::at(bit_rock, md_m);
    let bits: Vec<BitResult> = solved.iter().map(|s| s.bit).collect();
    let dirs: Vec<Vec3> = bits
        .iter()
        .map(|b| drilling_direction(&frame, &bit_action(b), &params))
        .collect();
    let w: Vec<f64> = faces.iter().map(|f| f.weight).collect();
    let iterations = solved.iter().map(|s| s.iterations).sum();
    let buckled_start = solved.iter().any(|s| s.buckled_start);
    let mut solved = solved.into_iter();
    let first = solved.next().expect("at least one state");
    let others = solved
        .zip(&faces[1..])
        .map(|(s, st)| StateStart {
            steer: *st,
            kink_correction_rad: s.model.kink_correction_rad(),
            state: s.state,
        })
        .collect();
    Ok(BitSolve {
        reactive_turn_rad: first.reactive_turn_rad,
        buckled_start,
        model: first.model,
        state: first.state,
        others,
        bit: mean_bit(&bits, &w),
        direction: mean_direction(&dirs, &w),
        iterations,
    })
}
