//! The forward-marching loop (physics.md 7.6): solve the stiff bottom-hole assembly with the
//! bit at `s`, apply the bit-rock law, extend the hole by one minimum-curvature arc to the
//! drilling direction, move the bit, re-solve warm-started from the previous state.

use super::law::{deviation, drilling_direction, BitAction, LawParams};
use crate::case::{BitRock, Case};
use crate::geometry::frame::inc_azi;
use crate::geometry::{Frame, HoleSection, HoleSize, Station, Survey, Vec3, WellPath};
use crate::models::fem::bha::{bha_model, default_cut_m};
use crate::models::fem::model::{Model, State};
use crate::models::fem::results::{extract, BitResult};
use crate::models::fem::solve::{solve, solve_interior_point_from, SolveControls};
use nalgebra::{Matrix2, Vector2};
use std::time::Instant;

pub use crate::case::bit_rock::MIN_STEP_M;

/// Trailing length of predicted hole over which the ripple of the hole direction is measured,
/// m: the chord directions of the last steps are fitted by a straight line in MD (the trend)
/// and the ripple is the largest deviation from it (see [`Prediction::ripple_deg`]).
pub const RIPPLE_WINDOW_M: f64 = 6.0;

/// Ripple (deg) at which a prediction carries a warning: the end inclination and azimuth move
/// by up to this much with the phase of the ripple.
pub const RIPPLE_WARN_DEG: f64 = 0.15;

/// Ripple (deg) at which a prediction stops with [`PredictError::Ripple`] when it also grew
/// by [`RIPPLE_GROWTH`] over the last [`RIPPLE_GROWTH_LENGTH_M`] (a growing ripple, not the
/// decaying transient of the first steps).
pub const RIPPLE_FAIL_DEG: f64 = 1.0;

/// Growth factor of the ripple over [`RIPPLE_GROWTH_LENGTH_M`] that marks it as growing.
pub const RIPPLE_GROWTH: f64 = 1.5;

/// Length over which the growth of the ripple is judged, m.
pub const RIPPLE_GROWTH_LENGTH_M: f64 = 10.0;

/// Steps per ripple wavelength below which the march damps a ripple: the step suggested when
/// a growing ripple stops a prediction is at least its wavelength over this. Measured
/// (docs/performance.md, "Step convergence"): the 2.3 m ripple of the horizontal example grows
/// at 0.45 m steps (5.1 per wavelength) and decays at 0.5 m (4.6); with its near-bit
/// stabilizer 0.9 m higher, the 3.3 m ripple grows at 0.5 m (6.6) and decays at 0.75 m (4.4).
pub const RIPPLE_STEPS_PER_WAVELENGTH: f64 = 4.0;

/// Step suggested against a ripple of wavelength `wavelength_m` (None: not measured) met at
/// step `step_m`, m: a quarter of the wavelength rounded up to 0.1 m
/// ([`RIPPLE_STEPS_PER_WAVELENGTH`]), at least 1.5 x the step; twice the step and at least
/// 0.5 m without a wavelength.
pub fn ripple_safe_step_m(wavelength_m: Option<f64>, step_m: f64) -> f64 {
    let up = |x: f64| (x * 10.0 - 1e-9).ceil() / 10.0;
    match wavelength_m {
        Some(w) => up(w / RIPPLE_STEPS_PER_WAVELENGTH).max(up(1.5 * step_m)),
        None => up(2.0 * step_m).max(0.5),
    }
}

/// Shortest string model (bit to cut or to the top of the hole), m.
pub const MIN_MODEL_LENGTH_M: f64 = 10.0;

/// Settings of a prediction.
#[derive(Debug, Clone, Copy)]
pub struct MarchSettings {
    /// Step length, m.
    pub step_m: f64,
    /// Cut distance of the bottom-hole-assembly model above the bit, m (None: the default rule
    /// of [`crate::models::fem::bha`]).
    pub cut_m: Option<f64>,
    /// Solver controls.
    pub controls: SolveControls,
    /// How a step extends the hole (see [`StepScheme`]).
    pub scheme: StepScheme,
}

/// How a step of the march shapes the hole near the bit. In both, the chord of the new step
/// follows the drilling direction the bit has at the end of the step (implicit, see
/// [`predict_from`]) and an interior station's tangent lies between its two chords.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum StepScheme {
    /// The tangent at the bit is the last chord: the last step bends half as much as a circle
    /// through the chords, so the bottom-hole assembly sees a hole that lags its own path by
    /// half a step near the bit. Error ~0.9 deg of inclination after 100 m at 1 m steps on the
    /// j-shape example (docs/performance.md); the scheme before 2026-11, kept for comparison.
    Chord,
    /// The tangent at the bit is extrapolated from the last two chords (from the start tangent
    /// and the first chord on the first step) as on a circle: a hole of constant curvature is
    /// represented exactly up to the bit. Error ~0.02 deg after 100 m at 1 m steps on j-shape.
    #[default]
    Arc,
}

impl MarchSettings {
    /// Settings from `case`: `[bit_rock] step`, `[solver]` tolerance and iteration limit.
    pub fn from_case(case: &Case) -> MarchSettings {
        MarchSettings {
            step_m: case.bit_rock.step_m,
            cut_m: None,
            controls: SolveControls::from_settings(&case.solver),
            scheme: StepScheme::default(),
        }
    }
}

/// One solved bit position of a prediction.
#[derive(Debug, Clone, Copy)]
pub struct StepRecord {
    /// Bit MD, m.
    pub md_m: f64,
    /// Hole inclination at the bit, rad.
    pub inc_rad: f64,
    /// Hole azimuth at the bit, rad.
    pub azi_rad: f64,
    /// Bit position (north, east, tvd), m.
    pub position: Vec3,
    /// Bit forces and tilt from the string solve.
    pub bit: BitResult,
    /// Drilling direction from the law (global unit vector; equal to the hole tangent after the
    /// first record, within the implicit step's tolerance).
    pub direction: Vec3,
    /// Newton iterations of this step's solve.
    pub iterations: usize,
}

/// A prediction from `from_md_m` to `to_md_m`.
#[derive(Debug, Clone)]
pub struct Prediction {
    /// The hole: measured stations up to the start, then one predicted station per step.
    pub path: WellPath,
    /// Solved bit positions, the start first and the end last.
    pub steps: Vec<StepRecord>,
    /// Start MD, m.
    pub from_md_m: f64,
    /// End MD, m.
    pub to_md_m: f64,
    /// Cut distance of the model, m.
    pub cut_m: f64,
    /// Degrees of freedom of the model.
    pub dofs: usize,
    /// Newton iterations over all steps.
    pub iterations: usize,
    /// Wall-clock time, s.
    pub seconds: f64,
    /// The model and solved state at the start (a warm start for predicting again from there).
    pub start_warm: WarmStart,
    /// Ripple of the predicted hole direction at the end, deg: the largest deviation of the
    /// chord directions of the last [`RIPPLE_WINDOW_M`] from their straight-line trend in MD
    /// (0 when the prediction is shorter than that). A warning is due from
    /// [`RIPPLE_WARN_DEG`].
    pub ripple_deg: f64,
}

/// Why a prediction stopped.
#[derive(Debug, thiserror::Error)]
pub enum PredictError {
    /// The string solve at a bit position did not converge.
    #[error("the string solve with the bit at {md_m:.2} m MD did not converge after {iterations} iterations (residual {residual:.1e}, penetration {penetration:.1e} of the clearance){detail}")]
    NotConverged {
        /// Bit MD, m.
        md_m: f64,
        /// Iterations done.
        iterations: usize,
        /// Last relative residual.
        residual: f64,
        /// Largest penetration relative to the clearance.
        penetration: f64,
        /// Chattering contacts, if any.
        detail: String,
    },
    /// The string solve failed (singular system).
    #[error("the string solve with the bit at {md_m:.2} m MD failed: {source}")]
    Solve {
        /// Bit MD, m.
        md_m: f64,
        /// The solver's error.
        source: crate::models::fem::solve::SolveError,
    },
    /// The implicit step found no hole direction consistent with the law, also at the
    /// shortest step the march tried (a failing step is halved while it stays at least
    /// [`MIN_STEP_M`]).
    #[error("no drilling direction consistent with the bit-rock law was found for the {step_m:.2} m step ending at {md_m:.2} m MD (deviation left {residual_rad:.1e} rad; a failing step is halved as long as it stays at least {MIN_STEP_M} m){hint}")]
    NoDirection {
        /// End MD of the step, m.
        md_m: f64,
        /// Deviation between drilling direction and hole tangent left, rad.
        residual_rad: f64,
        /// Length of the last step tried, m.
        step_m: f64,
        /// What the march saw that may explain it (empty when nothing), with its remedy.
        hint: String,
    },
    /// The predicted hole ripples around its trend by more than [`RIPPLE_FAIL_DEG`], and the
    /// ripple grows: the step resolves a directional instability of the bottom-hole assembly
    /// with the bit-rock law (docs/performance.md, "Step convergence").
    #[error("the predicted hole ripples around its trend by {ripple_deg:.2} deg at {md_m:.2} m MD{wavelength}, grown from {earlier_deg:.2} deg over the last {RIPPLE_GROWTH_LENGTH_M} m: at a {step_m} m step the march resolves a directional instability of this bottom-hole assembly with this bit-rock law and the trend is lost; use a step of at least {suggested_m} m (a quarter of the ripple's wavelength or more damps it)")]
    Ripple {
        /// Bit MD where the ripple was found, m.
        md_m: f64,
        /// Ripple, deg (see [`Prediction::ripple_deg`]).
        ripple_deg: f64,
        /// Ripple [`RIPPLE_GROWTH_LENGTH_M`] earlier, deg.
        earlier_deg: f64,
        /// ", wavelength about X m" when it could be measured, else empty.
        wavelength: String,
        /// Step of the prediction, m.
        step_m: f64,
        /// Step to use instead, m.
        suggested_m: f64,
    },
    /// The step is shorter than [`MIN_STEP_M`].
    #[error("the prediction step {step_m} m is shorter than the shortest step accepted, {MIN_STEP_M} m")]
    StepTooShort {
        /// The step asked for, m.
        step_m: f64,
    },
    /// Too little hole above the bit for the string model.
    #[error("the bit at {md_m:.2} m MD has only {length_m:.1} m of hole above it; the string model needs at least {MIN_MODEL_LENGTH_M} m")]
    TooShallow {
        /// Bit MD, m.
        md_m: f64,
        /// Hole length above the bit, m.
        length_m: f64,
    },
    /// The hole could not be built (bad stations).
    #[error("{0}")]
    Geometry(String),
}

/// The measured hole up to `md_m`: the survey's stations up to it, plus a station
/// interpolated at `md_m` if it falls between stations.
pub fn hole_to(path: &WellPath, md_m: f64) -> Result<WellPath, PredictError> {
    let mut st: Vec<Station> = path
        .stations()
        .iter()
        .copied()
        .filter(|s| s.md_m <= md_m + 1e-9)
        .collect();
    if st.last().is_none_or(|s| md_m - s.md_m > 1e-6) {
        let p = path.point_at(md_m);
        st.push(Station {
            md_m,
            inc_rad: p.inc_rad,
            azi_rad: p.azi_rad,
        });
    }
    let survey = Survey::new(st).map_err(|p| PredictError::Geometry(p.message))?;
    WellPath::new(&survey, path.station_position(0)).map_err(|p| PredictError::Geometry(p.message))
}

/// Hole size for a prediction to `to_md_m`: the case's sections, continued below the deepest
/// one at the bit diameter (the new hole is drilled by this bit).
pub fn hole_for_prediction(case: &Case, to_md_m: f64) -> HoleSize {
    let hole = &case.well.hole;
    if hole.deepest_md() >= to_md_m {
        return hole.clone();
    }
    let mut sections = hole.sections().to_vec();
    let friction = sections.last().and_then(|s| s.friction);
    sections.push(HoleSection {
        to_md_m,
        diameter_m: case.string.components[0].contact_od_m,
        friction,
    });
    HoleSize::new(sections, hole.caliper().to_vec())
}

pub use crate::models::fem::warm::transport_state;

/// Solve the model warm-started from `warm`; without one, or when the warm start fails, the
/// full cold [`solve`] (its own start).
fn solve_step(
    model: &Model,
    warm: Option<State>,
    ctl: &SolveControls,
) -> Result<crate::models::fem::solve::Solution, PredictError> {
    let md = model.bit_md_m;
    let wrap = |source| PredictError::Solve { md_m: md, source };
    if let Some(state) = warm {
        // a failed warm start (not converged, or a singular system from a poor start) falls
        // back to the cold start below
        match solve_interior_point_from(model, state, ctl) {
            Ok(sol) if sol.converged => return Ok(sol),
            Ok(_) => tracing::info!(md, "warm-started solve did not converge; solving from scratch"),
            Err(e) => tracing::info!(md, error = %e, "warm-started solve failed; solving from scratch"),
        }
    }
    let sol = solve(model, ctl).map_err(wrap)?;
    if sol.converged {
        return Ok(sol);
    }
    let detail = if sol.stats.chattering_nodes.is_empty() {
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
    Err(PredictError::NotConverged {
        md_m: md,
        iterations: sol.stats.iterations,
        residual: sol.stats.residual_history.last().copied().unwrap_or(f64::NAN),
        penetration: sol.stats.max_penetration,
        detail,
    })
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

/// Warm-start memory between calls: the last model and its solved state.
pub type WarmStart = Option<(Model, State)>;

/// Convergence tolerance of the implicit step on the deviation between the drilling direction
/// and the hole tangent at the bit, rad.
pub const DIRECTION_TOLERANCE_RAD: f64 = 1e-5;

/// The implicit step also stops when its last update of the turn angles is below this (rad)
/// and the deviation below 10 x [`DIRECTION_TOLERANCE_RAD`]: contact switching makes the
/// deviation non-smooth at the 1e-5 rad level.
pub const TURN_TOLERANCE_RAD: f64 = 2e-5;

/// Newton iterations allowed per implicit step.
pub const MAX_DIRECTION_ITERATIONS: usize = 12;

/// Largest change of the step's turn angles per Newton iteration, rad.
pub const MAX_TURN_CHANGE_RAD: f64 = 0.05;

/// Finite-difference perturbation of the turn angles for the direction Jacobian, rad.
pub const TURN_PERTURBATION_RAD: f64 = 1e-4;

/// One solved bit position: the model, the solution's state and the bit results.
struct BitSolve {
    model: Model,
    state: State,
    bit: BitResult,
    iterations: usize,
}

/// Solve the string with the bit at `md_m` in `path`, warm-started from `warm`.
fn solve_at(
    case: &Case,
    path: &WellPath,
    hole: &HoleSize,
    md_m: f64,
    cut_m: f64,
    warm: &WarmStart,
    ctl: &SolveControls,
) -> Result<BitSolve, PredictError> {
    let mut model = bha_model(case, path, hole, md_m, cut_m);
    model.consistent_tangent = true;
    let warm_state = warm
        .as_ref()
        .filter(|(m, _)| m.nodes() == model.nodes())
        .map(|(m, st)| transport_state(m, st, &model));
    let sol = solve_step(&model, warm_state, ctl)?;
    let bit = extract(&model, &sol, case.mud.density_kg_m3).bit;
    Ok(BitSolve {
        model,
        iterations: sol.stats.iterations,
        state: sol.state,
        bit,
    })
}

/// The predicted hole: the measured stations up to the start, then one point per step joined
/// by minimum-curvature arcs whose station tangents follow the bit's motion: at an interior
/// predicted station the chord directions interpolated linearly in MD between the middles of
/// the adjacent steps (their mean for equal steps); at the bit the last chord direction
/// ([`StepScheme::Chord`]) or its linear extrapolation from the previous chord
/// ([`StepScheme::Arc`]).
struct PredictedHole {
    measured: Vec<Station>,
    origin: Vec3,
    /// MD (m) and hole tangent at the start of the prediction.
    start: (f64, Vec3),
    /// (end MD of the segment, chord direction) per predicted segment.
    chords: Vec<(f64, Vec3)>,
    scheme: StepScheme,
}

impl PredictedHole {
    fn path_with(&self, extra: Option<(f64, Vec3)>) -> Result<WellPath, PredictError> {
        let mut st = self.measured.clone();
        let chords: Vec<(f64, Vec3)> = self.chords.iter().copied().chain(extra).collect();
        let fallback = st.last().map(|s| s.azi_rad).unwrap_or(0.0);
        // (middle MD, direction) of segment k; the start tangent counts as a chord at the start MD
        let mid = |k: usize| -> (f64, Vec3) {
            let begin = if k == 0 { self.start.0 } else { chords[k - 1].0 };
            ((begin + chords[k].0) / 2.0, chords[k].1)
        };
        for (k, &(md, c)) in chords.iter().enumerate() {
            let t = match (self.scheme, chords.get(k + 1)) {
                (StepScheme::Chord, Some(&(_, next))) => (c + next).normalize(),
                (StepScheme::Chord, None) => c,
                (StepScheme::Arc, Some(_)) => {
                    // direction linear in MD between the middles of the adjacent chords
                    let ((m0, c0), (m1, c1)) = (mid(k), mid(k + 1));
                    (c0 + (c1 - c0) * ((md - m0) / (m1 - m0))).normalize()
                }
                (StepScheme::Arc, None) => {
                    // extrapolated from the previous chord (or the start tangent) and this one
                    let (m1, c1) = mid(k);
                    let (m0, c0) = if k == 0 { self.start } else { mid(k - 1) };
                    (c1 + (c1 - c0) * ((md - m1) / (m1 - m0))).normalize()
                }
            };
            let (inc, azi) = inc_azi(&t, fallback);
            st.push(Station {
                md_m: md,
                inc_rad: inc,
                azi_rad: azi,
            });
        }
        let survey = Survey::new(st).map_err(|p| PredictError::Geometry(p.message))?;
        WellPath::new(&survey, self.origin).map_err(|p| PredictError::Geometry(p.message))
    }
}

/// Ripple of the predicted hole at the end of `chords` ((end MD, unit direction) per predicted
/// segment, the first beginning at `start_md`): the chords whose middles lie within
/// [`RIPPLE_WINDOW_M`] of the last end are fitted by a straight line in MD (component-wise) and
/// the ripple is the largest deviation from it, rad (about the angle); with the wavelength,
/// m, from the spacing of the sign changes of the deviations along the largest one (when there
/// are at least three). None until the predicted hole is [`RIPPLE_WINDOW_M`] long.
fn ripple(start_md: f64, chords: &[(f64, Vec3)]) -> Option<(f64, Option<f64>)> {
    let end = chords.last()?.0;
    if end - start_md < RIPPLE_WINDOW_M - 1e-9 {
        return None;
    }
    let mut pts: Vec<(f64, Vec3)> = Vec::new();
    for k in (0..chords.len()).rev() {
        let begin = if k == 0 { start_md } else { chords[k - 1].0 };
        let mid = 0.5 * (begin + chords[k].0);
        if mid < end - RIPPLE_WINDOW_M {
            break;
        }
        pts.push((mid, chords[k].1));
    }
    if pts.len() < 4 {
        return None;
    }
    let n = pts.len() as f64;
    let xm = pts.iter().map(|p| p.0).sum::<f64>() / n;
    let vm = pts.iter().fold(Vec3::zeros(), |a, p| a + p.1) / n;
    let sxx: f64 = pts.iter().map(|p| (p.0 - xm).powi(2)).sum();
    let sxv = pts.iter().fold(Vec3::zeros(), |a, p| a + (p.1 - vm) * (p.0 - xm));
    let slope = if sxx > 0.0 { sxv / sxx } else { Vec3::zeros() };
    let dev: Vec<Vec3> = pts.iter().map(|p| p.1 - vm - slope * (p.0 - xm)).collect();
    let (largest, r) = dev
        .iter()
        .enumerate()
        .map(|(i, d)| (i, d.norm()))
        .fold((0, 0.0), |a, x| if x.1 > a.1 { x } else { a });
    let u = dev[largest];
    let crossings: Vec<f64> = pts
        .windows(2)
        .zip(dev.windows(2))
        .filter(|(_, d)| d[0].dot(&u) * d[1].dot(&u) < 0.0)
        .map(|(p, _)| 0.5 * (p[0].0 + p[1].0))
        .collect();
    let wavelength = (crossings.len() >= 3)
        .then(|| 2.0 * (crossings[0] - crossings[crossings.len() - 1]).abs() / (crossings.len() - 1) as f64);
    Some((r, wavelength))
}

/// ", wavelength about X m" or nothing.
fn wavelength_text(w: Option<f64>) -> String {
    w.map(|w| format!(", wavelength about {w:.1} m")).unwrap_or_default()
}

/// Result of one implicit step's Newton iteration on the turn angles.
struct StepOutcome {
    /// The deviation reached the tolerance.
    converged: bool,
    /// Turn angles of the chord from the reference direction, rad.
    turn: [f64; 2],
    /// The hole with this chord.
    path: WellPath,
    /// The string solved in it.
    solve: BitSolve,
    /// Deviation left, rad.
    residual: [f64; 2],
    /// Drilling direction at the new bit position.
    direction: Vec3,
    /// Newton iterations of the string solves.
    iterations: usize,
}

/// The deviation of one implicit step as a function of the turn angles: the hole, the string
/// solved in it, the deviation (rad) and the drilling direction.
type StepResidual<'a> = dyn Fn([f64; 2], &WarmStart) -> Result<(WellPath, BitSolve, [f64; 2], Vec3), PredictError> + 'a;

/// Newton's method on the turn angles of the step ending at `md_m` from `turn`, with the
/// Jacobian `jac` kept between steps (finite differences where missing or after poor progress,
/// Broyden updates otherwise).
fn implicit_step(
    eval: &StepResidual,
    mut turn: [f64; 2],
    jac: &mut Option<Matrix2<f64>>,
    warm: &WarmStart,
    md_m: f64,
) -> Result<StepOutcome, PredictError> {
    let (mut p1, mut sol1, mut res, mut dir) = eval(turn, warm)?;
    let mut step_iterations = sol1.iterations;
    let mut converged = false;
    let mut last_update = f64::INFINITY;
    for _ in 0..MAX_DIRECTION_ITERATIONS {
        tracing::debug!(
            md = md_m,
            turn_h = turn[0],
            turn_r = turn[1],
            res_h = res[0],
            res_r = res[1],
            "direction iteration"
        );
        let r_norm = res[0].abs().max(res[1].abs());
        if r_norm < DIRECTION_TOLERANCE_RAD
            || (last_update < TURN_TOLERANCE_RAD && r_norm < 10.0 * DIRECTION_TOLERANCE_RAD)
        {
            converged = true;
            break;
        }
        let j = match *jac {
            Some(j) => j,
            None => {
                let mut j = Matrix2::zeros();
                for c in 0..2 {
                    let mut tp = turn;
                    tp[c] += TURN_PERTURBATION_RAD;
                    let (_, sp, rp, _) = eval(tp, warm)?;
                    step_iterations += sp.iterations;
                    for r in 0..2 {
                        j[(r, c)] = (rp[r] - res[r]) / TURN_PERTURBATION_RAD;
                    }
                }
                *jac = Some(j);
                j
            }
        };
        let Some(jinv) = j.try_inverse() else {
            *jac = None;
            continue;
        };
        let mut dt = -(jinv * Vector2::new(res[0], res[1]));
        let big = dt.amax();
        if big > MAX_TURN_CHANGE_RAD {
            dt *= MAX_TURN_CHANGE_RAD / big;
        }
        let new_turn = [turn[0] + dt[0], turn[1] + dt[1]];
        last_update = dt.amax();
        let (p, sol, r, d) = eval(new_turn, warm)?;
        step_iterations += sol.iterations;
        let norm = |x: &[f64; 2]| x[0].abs().max(x[1].abs());
        if norm(&r) > 0.5 * norm(&res) {
            // poor progress: rebuild the Jacobian by differences at the new point
            *jac = None;
        } else {
            // Broyden update of the kept Jacobian
            let dr = Vector2::new(r[0] - res[0], r[1] - res[1]);
            let denom = dt.dot(&dt);
            if denom > 0.0 {
                *jac = Some(j + (dr - j * dt) * dt.transpose() / denom);
            }
        }
        (turn, p1, sol1, res, dir) = (new_turn, p, sol, r, d);
    }
    Ok(StepOutcome {
        converged,
        turn,
        path: p1,
        solve: sol1,
        residual: res,
        direction: dir,
        iterations: step_iterations,
    })
}

/// Predict from the end of `start` (the hole drilled so far; its last station is the bit) to
/// `to_md_m`, with the law parameters of `bit_rock` (the case's unless overridden, for
/// calibration). `warm` carries the last solved state between calls.
///
/// Each step is implicit (backward Euler on the bit's position): the bit moves from `s` to
/// `s + ds` along the drilling direction it has when it arrives there. The unknown is the
/// direction of the step's chord; Newton's method with a finite-difference Jacobian kept
/// between steps (Broyden updates) drives the deviation between the law's drilling direction
/// at the new bit position and the chord to zero. Station tangents follow the chords (see
/// `PredictedHole`), so the hole is smooth; with [`StepScheme::Arc`] (the default) the tangent
/// at the bit is that of the circle through the last two chords, so a hole of constant
/// curvature is represented exactly up to the bit, where the stiff bit-to-stabilizer span makes
/// the drilling direction most sensitive to the hole's shape (with [`StepScheme::Chord`] the
/// tangent at the bit lags by half a step's turn, the main step error of that scheme). A step
/// that fails (no direction found, or a string solve failing on the way) is retried at half
/// the length, down to [`MIN_STEP_M`]. Why not simpler schemes: the bit side force
/// answers a lateral move of the bit with a stiffness of order 3 EI / a^3 (a: bit to first
/// stabilizer), so "new tangent = drilling direction computed before the step" (explicit) is
/// unstable unless `ds < 4 W a^3 / (3 EI)` (centimetres for a near-bit stabilizer), and
/// "new tangent = drilling direction after the step" with arcs between tangents (trapezoidal)
/// leaves an undamped zig-zag of the station tangents.
pub fn predict_from(
    case: &Case,
    bit_rock: &BitRock,
    start: &WellPath,
    to_md_m: f64,
    settings: &MarchSettings,
    warm: &mut WarmStart,
    on_step: &mut dyn FnMut(f64),
) -> Result<Prediction, PredictError> {
    let t0 = Instant::now();
    let from = start.md_end();
    let hole = hole_for_prediction(case, to_md_m);
    if settings.step_m.is_nan() || settings.step_m < MIN_STEP_M - 1e-9 {
        return Err(PredictError::StepTooShort {
            step_m: settings.step_m,
        });
    }
    let step = settings.step_m;
    let ctl = &settings.controls;
    let cut = settings
        .cut_m
        .unwrap_or_else(|| {
            let p = start.point_at(from);
            default_cut_m(&case.string, hole.diameter_at(from), p.inc_rad, case.mud.density_kg_m3)
        })
        .min(from - start.md_start());
    if cut < MIN_MODEL_LENGTH_M {
        return Err(PredictError::TooShallow {
            md_m: from,
            length_m: cut,
        });
    }
    let direction_at = |path: &WellPath, md: f64, bit: &BitResult| -> Vec3 {
        let frame = path.frame_at(md);
        drilling_direction(&frame, &bit_action(bit), &LawParams::at(bit_rock, md))
    };
    let mut s = from;
    let first = solve_at(case, start, &hole, s, cut, warm, ctl)?;
    let mut iterations = first.iterations;
    let dofs = first.model.dofs();
    let mut records = vec![(s, first.bit, direction_at(start, s, &first.bit), first.iterations)];
    *warm = Some((first.model, first.state));
    let start_warm = warm.clone();
    let mut hole_pred = PredictedHole {
        measured: start.stations().to_vec(),
        origin: start.station_position(0),
        start: (from, start.point_at(from).tangent),
        chords: Vec::new(),
        scheme: settings.scheme,
    };
    let mut jac: Option<Matrix2<f64>> = None;
    let mut last_turn = [0.0f64; 2];
    let mut last_ds = step;
    // reference direction of the next chord: the last chord (the start tangent at first)
    let mut last_chord = hole_pred.start.1;
    let mut path = start.clone();
    // the step in use: halved where the implicit step fails, grown back after a success
    let mut cur_step = step;
    // (bit MD, ripple in rad) after each step, and the last ripple with its wavelength
    let mut ripples: Vec<(f64, f64)> = Vec::new();
    let mut ripple_now: (f64, Option<f64>) = (0.0, None);
    let ripple_hint = |r: (f64, Option<f64>)| -> String {
        if r.0.to_degrees() < RIPPLE_WARN_DEG {
            return String::new();
        }
        format!(
            "; the predicted hole ripples around its trend by {:.2} deg{} here: a longer step (at least {} m) damps such a ripple",
            r.0.to_degrees(),
            wavelength_text(r.1),
            ripple_safe_step_m(r.1, step)
        )
    };
    while s < to_md_m - 1e-9 {
        // the last step ends exactly at the target; a sliver shorter than half the minimum
        // step is merged into this one
        let mut ds = cur_step.min(to_md_m - s);
        if to_md_m - (s + ds) < MIN_STEP_M * 0.5 {
            ds = to_md_m - s;
        }
        let s1 = s + ds;
        let reference = Frame::from_tangent(&last_chord, path.point_at(s).azi_rad);
        let x0 = path.point_at(s).position;
        let chord_of = |turn: [f64; 2]| -> Vec3 {
            (reference.t + reference.h * turn[0].tan() + reference.r * turn[1].tan()).normalize()
        };
        // residual: drilling direction at the new bit position minus the actual chord, in the
        // reference frame (rad)
        let eval = |turn: [f64; 2], warm: &WarmStart| -> Result<(WellPath, BitSolve, [f64; 2], Vec3), PredictError> {
            let p = hole_pred.path_with(Some((s1, chord_of(turn))))?;
            let sol = solve_at(case, &p, &hole, s1, cut, warm, ctl)?;
            let d = direction_at(&p, s1, &sol.bit);
            let chord = (p.point_at(s1).position - x0).normalize();
            let (dh, dr) = deviation(&reference, &d);
            let (ch, cr) = deviation(&reference, &chord);
            Ok((p, sol, [dh - ch, dr - cr], d))
        };
        // predictor: the previous step's turn per length (constant curvature), except after
        // the first step, whose turn is the start transient
        let turn = if hole_pred.chords.len() >= 2 {
            [last_turn[0] * ds / last_ds, last_turn[1] * ds / last_ds]
        } else {
            [0.0f64; 2]
        };
        let outcome = match implicit_step(&eval, turn, &mut jac, warm, s1) {
            Ok(o) if o.converged => o,
            failed => {
                // a failed implicit step, or a string solve that failed on the way: a shorter step
                if ds / 2.0 >= MIN_STEP_M {
                    match &failed {
                        Ok(_) => tracing::info!(md = s1, step = ds / 2.0, "implicit step failed; halving the step"),
                        Err(e) => tracing::info!(md = s1, step = ds / 2.0, error = %e, "halving the step"),
                    }
                    cur_step = ds / 2.0;
                    jac = None;
                    continue;
                }
                let o = match failed {
                    Ok(o) => o,
                    Err(PredictError::NotConverged {
                        md_m,
                        iterations,
                        residual,
                        penetration,
                        detail,
                    }) => {
                        return Err(PredictError::NotConverged {
                            md_m,
                            iterations,
                            residual,
                            penetration,
                            detail: detail + &ripple_hint(ripple_now),
                        })
                    }
                    Err(e) => return Err(e),
                };
                return Err(PredictError::NoDirection {
                    md_m: s1,
                    residual_rad: o.residual[0].abs().max(o.residual[1].abs()),
                    step_m: ds,
                    hint: ripple_hint(ripple_now),
                });
            }
        };
        let StepOutcome {
            turn,
            path: p1,
            solve: sol1,
            direction: dir,
            iterations: step_iterations,
            ..
        } = outcome;
        iterations += step_iterations;
        cur_step = (cur_step * 2.0).min(step);
        last_turn = turn;
        last_ds = ds;
        last_chord = chord_of(turn);
        hole_pred.chords.push((s1, last_chord));
        if let Some(r) = ripple(from, &hole_pred.chords) {
            let earlier = ripples
                .iter()
                .rev()
                .find(|(md, _)| *md <= s1 - RIPPLE_GROWTH_LENGTH_M + 1e-9)
                .map(|x| x.1);
            ripples.push((s1, r.0));
            ripple_now = r;
            if let Some(e) = earlier {
                if r.0.to_degrees() >= RIPPLE_FAIL_DEG && r.0 >= RIPPLE_GROWTH * e {
                    return Err(PredictError::Ripple {
                        md_m: s1,
                        ripple_deg: r.0.to_degrees(),
                        earlier_deg: e.to_degrees(),
                        wavelength: wavelength_text(r.1),
                        step_m: step,
                        suggested_m: ripple_safe_step_m(r.1, step),
                    });
                }
            }
        }
        path = p1;
        s = s1;
        records.push((s, sol1.bit, dir, step_iterations));
        on_step(s);
        *warm = Some((sol1.model, sol1.state));
    }
    if ripple_now.0.to_degrees() >= RIPPLE_WARN_DEG {
        tracing::warn!(
            "the predicted hole ripples around its trend by {:.2} deg at the end{} (step {} m): the end inclination and azimuth move by up to that much with the ripple's phase",
            ripple_now.0.to_degrees(),
            wavelength_text(ripple_now.1),
            step
        );
    }
    // stations reported on the final hole
    let steps = records
        .into_iter()
        .map(|(md, bit, direction, iterations)| {
            let p = path.point_at(md);
            StepRecord {
                md_m: md,
                inc_rad: p.inc_rad,
                azi_rad: p.azi_rad,
                position: p.position,
                bit,
                direction,
                iterations,
            }
        })
        .collect();
    Ok(Prediction {
        path,
        steps,
        from_md_m: from,
        to_md_m,
        cut_m: cut,
        dofs,
        iterations,
        seconds: t0.elapsed().as_secs_f64(),
        start_warm,
        ripple_deg: ripple_now.0.to_degrees(),
    })
}

/// Predict `case` from `from_md_m` on its survey (the measured hole behind) to `to_md_m`;
/// `on_step` hears each new bit MD (for progress).
pub fn predict(
    case: &Case,
    from_md_m: f64,
    to_md_m: f64,
    settings: &MarchSettings,
    on_step: &mut dyn FnMut(f64),
) -> Result<Prediction, PredictError> {
    let start = hole_to(&case.well.path, from_md_m)?;
    predict_from(case, &case.bit_rock, &start, to_md_m, settings, &mut None, on_step)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Chords of 0.25 m from MD 100 whose direction turns at `kappa` rad/m in the vertical
    /// plane and carries a ripple `amp * sin(2 pi s / wavelength)` rad sideways.
    fn chords(length: f64, kappa: f64, amp: f64, wavelength: f64) -> Vec<(f64, Vec3)> {
        let n = (length / 0.25).round() as usize;
        (1..=n)
            .map(|k| {
                let mid = 0.25 * (k as f64 - 0.5);
                let a = kappa * mid;
                let r = amp * (2.0 * std::f64::consts::PI * mid / wavelength).sin();
                let d = Vec3::new(a.cos() * r.cos(), r.sin(), a.sin() * r.cos());
                (100.0 + 0.25 * k as f64, d)
            })
            .collect()
    }

    /// Reference: the ripple put in (amplitude and wavelength of a sine on the chord
    /// directions); the sampling at 0.25 m can miss the crest by at most 1 - cos(pi 0.125/2.4)
    /// (3 %), the fit window of 6 m holds 2.5 wavelengths (a few % of the amplitude leak into
    /// the fitted line). A constant-curvature hole of 10 deg/30 m has no ripple: its directions
    /// leave a straight line in MD by kappa^2 L^2 / 8 ~ 2e-4 rad over the window.
    #[test]
    fn ripple_measures_the_put_in_sine_and_ignores_a_steady_turn() {
        let kappa = 10f64.to_radians() / 30.0;
        let (r, w) = ripple(100.0, &chords(20.0, kappa, 0.01, 2.4)).unwrap();
        assert!((r - 0.01).abs() < 0.001, "ripple {r}");
        let w = w.unwrap();
        assert!((w - 2.4).abs() < 0.25, "wavelength {w}");
        let (r, _) = ripple(100.0, &chords(20.0, kappa, 0.0, 2.4)).unwrap();
        assert!(
            r.to_degrees() < 0.01 && r.to_degrees() < RIPPLE_WARN_DEG / 10.0,
            "steady turn: {r}"
        );
        // shorter than the window: not measured
        assert!(ripple(100.0, &chords(RIPPLE_WINDOW_M - 0.5, kappa, 0.01, 2.4)).is_none());
    }

    /// Reference: the rule of [`ripple_safe_step_m`] by hand (quarter wavelength rounded up to
    /// 0.1 m, at least 1.5 x the step; without a wavelength 2 x the step, at least 0.5 m).
    #[test]
    fn safe_step_is_a_quarter_wavelength_rounded_up() {
        assert_eq!(ripple_safe_step_m(Some(2.3), 0.25), 0.6);
        assert_eq!(ripple_safe_step_m(Some(3.3), 0.5), 0.9);
        assert_eq!(ripple_safe_step_m(Some(2.0), 0.4), 0.6);
        assert_eq!(ripple_safe_step_m(Some(1.2), 0.2), 0.3);
        assert_eq!(ripple_safe_step_m(None, 0.2), 0.5);
        assert_eq!(ripple_safe_step_m(None, 0.4), 0.8);
    }
}
