//! The forward-marching loop (docs/theory.md 9.4): solve the stiff bottom-hole assembly with the
//! bit at `s`, apply the bit-rock law, extend the hole by one minimum-curvature arc to the
//! drilling direction, move the bit, re-solve warm-started from the previous state.

mod bit;
mod hole;
mod ripple;
mod step;

pub use bit::{bit_action, StateStart, Warm, OWN_WARM_MAX_ITERATIONS};
pub(crate) use bit::{solve_bit, BitSolve};
pub use hole::{hole_for_prediction, hole_to};
pub use ripple::{
    ripple_safe_step_m, RIPPLE_FAIL_DEG, RIPPLE_GROWTH, RIPPLE_GROWTH_LENGTH_M, RIPPLE_STEPS_PER_WAVELENGTH,
    RIPPLE_WARN_DEG, RIPPLE_WINDOW_M,
};
pub use step::{
    DIRECTION_TOLERANCE_RAD, MAX_DIRECTION_ITERATIONS, MAX_TURN_CHANGE_RAD, TURN_PERTURBATION_RAD, TURN_TOLERANCE_RAD,
};

use super::law::deviation;
use crate::case::{BitRock, Case};
use crate::geometry::{Frame, HoleSize, Vec3, WellPath};
use crate::models::fem::bha::default_cut_m;
use crate::models::fem::results::BitResult;
use crate::models::fem::solve::SolveControls;
use hole::PredictedHole;
use nalgebra::Matrix2;
use ripple::RippleWatch;
use std::cell::RefCell;
use std::time::Instant;
use step::{backtracking_step, implicit_step, StepOutcome};

pub use crate::case::bit_rock::MIN_STEP_M;

/// Shortest string model (bit to cut or to the top of the hole), m.
pub const MIN_MODEL_LENGTH_M: f64 = 10.0;

/// Most steps one march may take (the interval over the step); a longer march is refused
/// before any solve, with the remedy.
pub const MAX_MARCH_STEPS: f64 = 20_000.0;

/// Inclination at which a predicted hole points up the well and the march stops, rad (179 deg).
pub const MAX_PREDICTED_INCLINATION_RAD: f64 = 179.0 * std::f64::consts::PI / 180.0;

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
    /// A tendency the bit-rock law does not hold (a formation push, a bit walk), added to the
    /// drilling direction of every step (zero: none).
    pub tendency: Tendency,
}

/// A turn of the hole per length beyond what the bottom-hole assembly and the bit-rock law
/// drill (a formation push, a washout, a hidden walk), rad/m: after each step's implicit solve,
/// its chord is turned by `build * ds` toward the high side and `right * ds` toward the right of
/// the step's reference frame, and the march drills on in the hole so turned (the bit results
/// recorded at the step are those of the solve before the turn). The assembly straightens such
/// a hole: on the example wells the end direction after 60 m turns by 7-46% of `tendency x
/// 60 m` (the synthetic wells of the tracking tests use it as their hidden tendency).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Tendency {
    /// Turn toward the high side (build), rad/m.
    pub build_rad_per_m: f64,
    /// Turn toward the right, rad/m (the azimuth rate is this over sin I).
    pub right_rad_per_m: f64,
}

impl Tendency {
    /// True when both components are zero.
    pub fn is_zero(&self) -> bool {
        self.build_rad_per_m == 0.0 && self.right_rad_per_m == 0.0
    }
}

/// How a step of the march shapes the hole near the bit. In both, the chord of the new step
/// follows the drilling direction the bit has at the end of the step (implicit, see
/// [`predict_from`]) and an interior station's tangent lies between its two chords.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum StepScheme {
    /// The tangent at the bit is the last chord: the last step bends half as much as a circle
    /// through the chords, so the bottom-hole assembly sees a hole that lags its own path by
    /// half a step near the bit. Error ~0.9 deg of inclination after 100 m at 1 m steps on the
    /// j-shape example (docs/performance.md); kept for comparison.
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
            tendency: Tendency::default(),
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
    /// How a bent housing or a rotary steerable system drilled the step (None: a string with
    /// neither).
    pub steer: Option<StepSteer>,
    /// The turn to the left of a sliding bent housing's toolface by the motor's reactive
    /// torque in this step's solve, rad (None: `reactive_torque` off, or the string rotates).
    pub reactive_turn_rad: Option<f64>,
}

/// How a bent housing (or a rotary steerable system) drills: sliding at a toolface or rotating.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StepSteer {
    /// The string rotates (the housing turns with it, the drilling direction is the mean over
    /// a revolution); else it slides.
    pub rotating: bool,
    /// The toolface set, rad ([`crate::case::Operation::toolface_rad`]; the first of the
    /// revolution when rotating).
    pub toolface_rad: f64,
    /// The steering ratio of a rotary steerable system (None for a bent housing).
    pub ratio: Option<f64>,
}

impl StepSteer {
    /// How `case`'s string drills (None for a string without a bent housing or a rotary
    /// steerable system).
    pub fn of_case(case: &Case) -> Option<StepSteer> {
        let s = &case.string;
        (s.bend().is_some() || s.rss().is_some()).then(|| StepSteer {
            rotating: case.operation.rotates(),
            toolface_rad: case.operation.toolface_rad,
            ratio: s.rss().map(|r| r.ratio),
        })
    }
    /// `slide` or `rotate`.
    pub fn mode_name(&self) -> &'static str {
        if self.rotating {
            "rotate"
        } else {
            "slide"
        }
    }
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
    /// MD intervals `(top, bottom)`, m, where the rotating whole string whirls at the start
    /// ([`crate::models::whirl`]; empty for a cut model or a string without a rotating helix).
    pub whirl_md_m: Vec<(f64, f64)>,
    /// The first bit MD, m, whose whole-string solve found no equilibrium from its usual start
    /// and was solved from the buckled shape ([`crate::models::buckled_start`]); None if none.
    pub buckled_start_md_m: Option<f64>,
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
    /// The march would take more than [`MAX_MARCH_STEPS`] steps.
    #[error("the prediction from {from_md_m:.2} m to {to_md_m:.2} m MD is {steps:.0} steps of {step_m} m, more than the {MAX_MARCH_STEPS} a march may take; predict a shorter interval or take a longer step")]
    TooManySteps {
        /// Start MD, m.
        from_md_m: f64,
        /// End MD, m.
        to_md_m: f64,
        /// Step, m.
        step_m: f64,
        /// Steps it would take.
        steps: f64,
    },
    /// The predicted hole left the earth: it rose above the surface (the survey's TVD datum) or
    /// turned to point up the well.
    #[error("the predicted hole {what} at {md_m:.2} m MD (inclination {inc_deg:.1} deg, TVD {tvd_m:.1} m); the march stopped there: a bottom-hole assembly whose tendency turns the hole this far is outside what the model predicts; predict a shorter interval")]
    LeftTheEarth {
        /// Bit MD where it happened, m.
        md_m: f64,
        /// What happened.
        what: &'static str,
        /// Inclination there, deg.
        inc_deg: f64,
        /// TVD there, m.
        tvd_m: f64,
    },
}

/// Refuse a predicted hole at `md_m` that rose above the surface (TVD below zero) or points up
/// the well (inclination beyond [`MAX_PREDICTED_INCLINATION_RAD`]).
fn check_on_earth(path: &WellPath, md_m: f64) -> Result<(), PredictError> {
    let p = path.point_at(md_m);
    let what = if p.position.z < 0.0 {
        "rose above the surface"
    } else if p.inc_rad > MAX_PREDICTED_INCLINATION_RAD {
        "turned to point up the well (inclination beyond 179 deg)"
    } else {
        return Ok(());
    };
    Err(PredictError::LeftTheEarth {
        md_m,
        what,
        inc_deg: p.inc_rad.to_degrees(),
        tvd_m: p.position.z,
    })
}

/// Refuse a march from `from_md_m` to `to_md_m` at `step_m` longer than [`MAX_MARCH_STEPS`].
pub fn check_step_count(from_md_m: f64, to_md_m: f64, step_m: f64) -> Result<(), PredictError> {
    let steps = ((to_md_m - from_md_m) / step_m).ceil();
    if steps > MAX_MARCH_STEPS {
        return Err(PredictError::TooManySteps {
            from_md_m,
            to_md_m,
            step_m,
            steps,
        });
    }
    Ok(())
}

/// Warm-start memory between calls: the last solved string.
pub type WarmStart = Option<Warm>;

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
    check_step_count(from, to_md_m, step)?;
    let ctl = &settings.controls;
    let tendency = settings.tendency;
    let cut = model_cut_m(case, start, &hole, settings)?;
    let bent = case.string.bend().is_some() || case.string.rss().is_some();
    let mut s = from;
    let start_case = steered_at(case, s);
    let faces = crate::predict::revolution::toolfaces(&start_case);
    let first = solve_bit(&start_case, bit_rock, start, &hole, s, cut, (warm, &None), ctl, &faces)?;
    let (whirl_md_m, mut buckled_start_md_m) = (first.model.whirl_md_m.clone(), first.buckled_start.then_some(s));
    let (mut iterations, dofs) = (first.iterations, first.model.dofs());
    let mut records = vec![(
        s,
        first.bit,
        first.direction,
        first.iterations,
        StepSteer::of_case(&start_case),
        first.reactive_turn_rad,
    )];
    *warm = Some(first.into_warm());
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
    let mut ripple = RippleWatch::new(from, step);
    let mut last_steer = StepSteer::of_case(&start_case);
    while s < to_md_m - 1e-9 {
        let ds = step_length(case, s, cur_step, to_md_m);
        let s1 = s + ds;
        // the step drills as the steering interval at its middle says
        let step_case = steered_at(case, s + 0.5 * ds);
        let faces = crate::predict::revolution::toolfaces(&step_case);
        let reference = Frame::from_tangent(&last_chord, path.point_at(s).azi_rad);
        let x0 = path.point_at(s).position;
        let chord_of = |turn: [f64; 2]| -> Vec3 {
            (reference.t + reference.h * turn[0].tan() + reference.r * turn[1].tan()).normalize()
        };
        // residual: drilling direction at the new bit position minus the actual chord, in the
        // reference frame (rad)
        // the last evaluation of this step: where the other states of a revolution start
        let latest: RefCell<WarmStart> = RefCell::new(None);
        let eval = |turn: [f64; 2], warm: &WarmStart| -> Result<(WellPath, BitSolve, [f64; 2], Vec3), PredictError> {
            let p = hole_pred.path_with(Some((s1, chord_of(turn))))?;
            let sol = solve_bit(
                &step_case,
                bit_rock,
                &p,
                &hole,
                s1,
                cut,
                (warm, &latest.borrow()),
                ctl,
                &faces,
            )?;
            *latest.borrow_mut() = sol.warm_copy();
            let d = sol.direction;
            let chord = (p.point_at(s1).position - x0).normalize();
            let (dh, dr) = deviation(&reference, &d);
            let (ch, cr) = deviation(&reference, &chord);
            Ok((p, sol, [dh - ch, dr - cr], d))
        };
        // predictor: the previous step's turn per length (constant curvature), except after
        // the first step, whose turn is the start transient
        let turn = match hole_pred.chords.len() >= 2 {
            true => [last_turn[0] * ds / last_ds, last_turn[1] * ds / last_ds],
            false => [0.0f64; 2],
        };
        let outcome = match step_with_retry(&eval, turn, &mut jac, warm, s1, bent) {
            Ok(o) if o.converged => o,
            failed => {
                // a failed implicit step, or a string solve that failed on the way: a shorter step
                if ds / 2.0 >= MIN_STEP_M {
                    log_halving(&failed, s1, ds / 2.0);
                    (cur_step, jac) = (ds / 2.0, None);
                    continue;
                }
                return Err(failed_step_error(failed, s1, ds, ripple.hint()));
            }
        };
        let (turn, p1, sol1) = (outcome.turn, outcome.path, outcome.solve);
        let (dir, step_iterations) = (outcome.direction, outcome.iterations);
        iterations += step_iterations;
        (cur_step, last_turn, last_ds) = ((cur_step * 2.0).min(step), turn, ds);
        last_chord = chord_of([
            turn[0] + tendency.build_rad_per_m * ds,
            turn[1] + tendency.right_rad_per_m * ds,
        ]);
        hole_pred.chords.push((s1, last_chord));
        let p1 = if tendency.is_zero() {
            p1
        } else {
            hole_pred.path_with(None)?
        };
        let steer = StepSteer::of_case(&step_case);
        restart_on_steering_change(&mut ripple, &mut last_steer, steer, s, step);
        ripple.after_step(s1, &hole_pred.chords)?;
        check_on_earth(&p1, s1)?;
        buckled_start_md_m = buckled_start_md_m.or(sol1.buckled_start.then_some(s1));
        (path, s) = (p1, s1);
        records.push((s, sol1.bit, dir, step_iterations, steer, sol1.reactive_turn_rad));
        on_step(s);
        *warm = Some(sol1.into_warm());
    }
    ripple.warn_at_end();
    let steps = step_records(records, &path);
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
        ripple_deg: ripple.now.0.to_degrees(),
        whirl_md_m,
        buckled_start_md_m,
    })
}

/// Log why the step ending at `md_m` is retried at half its length, `half_m` (m): the implicit
/// step `failed` did not converge, or a string solve on the way failed.
fn log_halving(failed: &Result<StepOutcome, PredictError>, md_m: f64, half_m: f64) {
    match failed {
        Ok(_) => tracing::info!(md = md_m, step = half_m, "implicit step failed; halving the step"),
        Err(e) => tracing::info!(md = md_m, step = half_m, error = %e, "halving the step"),
    }
}

/// Restart the ripple watch `ripple` at `s` (m MD; step `step`, m) when the steering of the
/// step `steer` differs from the last step's `last`: a change of the steering plan turns the
/// hole on purpose, so the ripple is measured from there on.
fn restart_on_steering_change(
    ripple: &mut RippleWatch,
    last: &mut Option<StepSteer>,
    steer: Option<StepSteer>,
    s: f64,
    step: f64,
) {
    if steer != *last {
        (*ripple, *last) = (RippleWatch::new(s, step), steer);
    }
}

/// Length of the step from `s` (m MD) at the step in use `cur_step` (m) toward `to_md_m`: the
/// last step ends exactly at the target (a sliver shorter than half the minimum step is merged
/// into it), and a step ends at the next end of one of `case`'s steering intervals at least a
/// minimum step ahead.
fn step_length(case: &Case, s: f64, cur_step: f64, to_md_m: f64) -> f64 {
    let mut ds = cur_step.min(to_md_m - s);
    if to_md_m - (s + ds) < MIN_STEP_M * 0.5 {
        ds = to_md_m - s;
    }
    if let Some(b) = case.steering.next_boundary(s, MIN_STEP_M - 1e-9) {
        ds = ds.min(b - s);
    }
    ds
}

/// [`implicit_step`] ending at `s1` from `turn`; for a string with a bent housing (`bent`)
/// retried by [`backtracking_step`] when it fails (the kept Jacobian `jac` then dropped).
fn step_with_retry(
    eval: &step::StepResidual,
    turn: [f64; 2],
    jac: &mut Option<Matrix2<f64>>,
    warm: &WarmStart,
    s1: f64,
    bent: bool,
) -> Result<StepOutcome, PredictError> {
    let result = implicit_step(eval, turn, jac, warm, s1);
    if bent && !matches!(&result, Ok(o) if o.converged) {
        // a bent housing's deviation swings steeply with the turn: Newton with backtracking
        let retry = backtracking_step(eval, turn, warm, s1);
        if matches!(&retry, Ok(o) if o.converged) {
            *jac = None;
            return retry;
        }
    }
    result
}

/// Cut distance of the string model above the bit at the start of `start` (the settings' or
/// the default rule's, at most the hole above the bit), m; refused below
/// [`MIN_MODEL_LENGTH_M`].
fn model_cut_m(case: &Case, start: &WellPath, hole: &HoleSize, settings: &MarchSettings) -> Result<f64, PredictError> {
    let from = start.md_end();
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
    Ok(cut)
}

/// The error of an implicit step ending at `md_m` that failed at the shortest step `step_m`:
/// the string solve's own error (with the ripple's `hint` when it did not converge), or no
/// direction found.
fn failed_step_error(failed: Result<StepOutcome, PredictError>, md_m: f64, step_m: f64, hint: String) -> PredictError {
    match failed {
        Ok(o) => PredictError::NoDirection {
            md_m,
            residual_rad: o.residual[0].abs().max(o.residual[1].abs()),
            step_m,
            hint,
        },
        Err(PredictError::NotConverged {
            md_m,
            iterations,
            residual,
            penetration,
            detail,
        }) => PredictError::NotConverged {
            md_m,
            iterations,
            residual,
            penetration,
            detail: detail + &hint,
        },
        Err(e) => e,
    }
}

/// The step records on the final hole `path` from (bit MD, bit results, drilling direction,
/// iterations, how a bent housing drilled it, the reactive torque's toolface turn) per solved
/// step.
fn step_records(records: Vec<StepData>, path: &WellPath) -> Vec<StepRecord> {
    records
        .into_iter()
        .map(|(md, bit, direction, iterations, steer, reactive_turn_rad)| {
            let p = path.point_at(md);
            StepRecord {
                md_m: md,
                inc_rad: p.inc_rad,
                azi_rad: p.azi_rad,
                position: p.position,
                bit,
                direction,
                iterations,
                steer,
                reactive_turn_rad,
            }
        })
        .collect()
}

/// What the march keeps of a solved step: bit MD, bit results, drilling direction, iterations,
/// how a bent housing drilled it, the reactive torque's toolface turn (rad).
type StepData = (f64, BitResult, Vec3, usize, Option<StepSteer>, Option<f64>);

/// `case` drilling as its steering plan says at `md_m` (its own operation where no interval
/// covers it).
fn steered_at(case: &Case, md_m: f64) -> std::borrow::Cow<'_, Case> {
    match case.steering.at(md_m) {
        Some(iv) => std::borrow::Cow::Owned(case.steered(iv)),
        None => std::borrow::Cow::Borrowed(case),
    }
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
