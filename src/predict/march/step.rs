//! One step of the march: the implicit step's Newton iteration on the direction of the step's
//! chord, each evaluation a string solved with the bit at the step's end ([`super::bit`]).

use super::bit::BitSolve;
use super::{PredictError, WarmStart};
use crate::geometry::{Vec3, WellPath};
use nalgebra::{Matrix2, Vector2};

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

/// Result of one implicit step's Newton iteration on the turn angles.
pub(super) struct StepOutcome {
    /// The deviation reached the tolerance.
    pub(super) converged: bool,
    /// Turn angles of the chord from the reference direction, rad.
    pub(super) turn: [f64; 2],
    /// The hole with this chord.
    pub(super) path: WellPath,
    /// The string solved in it.
    pub(super) solve: BitSolve,
    /// Deviation left, rad.
    pub(super) residual: [f64; 2],
    /// Drilling direction at the new bit position.
    pub(super) direction: Vec3,
    /// Newton iterations of the string solves.
    pub(super) iterations: usize,
}

/// The deviation of one implicit step as a function of the turn angles: the hole, the string
/// solved in it, the deviation (rad) and the drilling direction.
pub(super) type StepResidual<'a> =
    dyn Fn([f64; 2], &WarmStart) -> Result<(WellPath, BitSolve, [f64; 2], Vec3), PredictError> + 'a;

/// Largest component of a deviation or turn, rad.
fn max_abs(x: &[f64; 2]) -> f64 {
    x[0].abs().max(x[1].abs())
}

/// Whether the direction iteration has converged: the deviation `res` within
/// [`DIRECTION_TOLERANCE_RAD`], or within ten times it after an update below
/// [`TURN_TOLERANCE_RAD`] (`last_update`, rad).
fn direction_converged(res: &[f64; 2], last_update: f64) -> bool {
    let r_norm = max_abs(res);
    r_norm < DIRECTION_TOLERANCE_RAD || (last_update < TURN_TOLERANCE_RAD && r_norm < 10.0 * DIRECTION_TOLERANCE_RAD)
}

/// The Jacobian of the deviation at `turn` (where it is `res`) by forward differences of
/// [`TURN_PERTURBATION_RAD`], and the Newton iterations of its string solves.
fn jacobian_by_differences(
    eval: &StepResidual,
    turn: [f64; 2],
    res: [f64; 2],
    warm: &WarmStart,
) -> Result<(Matrix2<f64>, usize), PredictError> {
    let mut j = Matrix2::zeros();
    let mut iterations = 0;
    for c in 0..2 {
        let mut tp = turn;
        tp[c] += TURN_PERTURBATION_RAD;
        let (_, sp, rp, _) = eval(tp, warm)?;
        iterations += sp.iterations;
        for r in 0..2 {
            j[(r, c)] = (rp[r] - res[r]) / TURN_PERTURBATION_RAD;
        }
    }
    Ok((j, iterations))
}

/// The Newton update `-J^-1 res` of the turn angles, scaled down to at most
/// [`MAX_TURN_CHANGE_RAD`] in its largest component.
fn capped_newton_update(jinv: &Matrix2<f64>, res: [f64; 2]) -> Vector2<f64> {
    let mut dt = -(jinv * Vector2::new(res[0], res[1]));
    let big = dt.amax();
    if big > MAX_TURN_CHANGE_RAD {
        dt *= MAX_TURN_CHANGE_RAD / big;
    }
    dt
}

/// Newton's method on the turn angles of the step ending at `md_m` from `turn`, with the
/// Jacobian `jac` kept between steps (finite differences where missing or after poor progress,
/// Broyden updates otherwise).
pub(super) fn implicit_step(
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
        if direction_converged(&res, last_update) {
            converged = true;
            break;
        }
        let j = match *jac {
            Some(j) => j,
            None => {
                let (j, its) = jacobian_by_differences(eval, turn, res, warm)?;
                step_iterations += its;
                *jac = Some(j);
                j
            }
        };
        let Some(jinv) = j.try_inverse() else {
            *jac = None;
            continue;
        };
        let dt = capped_newton_update(&jinv, res);
        let new_turn = [turn[0] + dt[0], turn[1] + dt[1]];
        last_update = dt.amax();
        let (p, sol, r, d) = eval(new_turn, warm)?;
        step_iterations += sol.iterations;
        if max_abs(&r) > 0.5 * max_abs(&res) {
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

/// Newton iterations allowed in [`backtracking_step`].
pub const MAX_BACKTRACKING_ITERATIONS: usize = 30;

/// Halvings of one Newton update in [`backtracking_step`].
pub const MAX_BACKTRACKING_HALVINGS: usize = 30;

/// The implicit step of a bent housing when [`implicit_step`] fails: Newton's method on the turn
/// angles from `turn` with the Jacobian by differences at every iterate and each update halved
/// until the deviation falls. A bent housing's deviation swings steeply with the turn (its side
/// force is of the size of the WOB and changes sign within a fraction of a degree), where the
/// plain iteration, its update capped, jumps across the root back and forth.
pub(super) fn backtracking_step(
    eval: &StepResidual,
    mut turn: [f64; 2],
    warm: &WarmStart,
    md_m: f64,
) -> Result<StepOutcome, PredictError> {
    let (mut p1, mut sol1, mut res, mut dir) = eval(turn, warm)?;
    let mut iterations = sol1.iterations;
    let mut converged = false;
    let mut last_update = f64::INFINITY;
    for _ in 0..MAX_BACKTRACKING_ITERATIONS {
        if direction_converged(&res, last_update) {
            converged = true;
            break;
        }
        let r_norm = max_abs(&res);
        let (j, its) = jacobian_by_differences(eval, turn, res, warm)?;
        iterations += its;
        let Some(jinv) = j.try_inverse() else {
            break;
        };
        let mut dt = capped_newton_update(&jinv, res);
        let mut accepted = false;
        for _ in 0..MAX_BACKTRACKING_HALVINGS {
            let new_turn = [turn[0] + dt[0], turn[1] + dt[1]];
            let (p, sol, r, d) = eval(new_turn, warm)?;
            iterations += sol.iterations;
            if max_abs(&r) < r_norm {
                last_update = dt.amax();
                (turn, p1, sol1, res, dir) = (new_turn, p, sol, r, d);
                accepted = true;
                break;
            }
            dt *= 0.5;
        }
        if !accepted {
            break;
        }
    }
    tracing::debug!(
        md = md_m,
        converged,
        residual = max_abs(&res),
        "backtracking implicit step"
    );
    Ok(StepOutcome {
        converged,
        turn,
        path: p1,
        solve: sol1,
        residual: res,
        direction: dir,
        iterations,
    })
}
