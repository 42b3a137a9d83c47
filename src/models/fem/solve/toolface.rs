//! A bent housing held at its toolface: the toolface of the housing in a solved state and the
//! solve that turns the kink ([`crate::models::fem::kink`]) against the string's twist
//! (docs/theory.md 9.9).

use super::{solve, solve_interior_point_from, Solution, SolveControls, SolveError};
use crate::geometry::frame::toolface_direction;
use crate::geometry::survey::wrap_pi;
use crate::models::fem::kink::Kink;
use crate::models::fem::model::{Model, State};

impl Model {
    /// Set the bent housing's toolface to `toolface_rad` (rad): the kink turned to it about the
    /// unloaded triads (no effect on a straight string). The state of a solve at another
    /// toolface is not a solution of this model.
    pub fn set_toolface(&mut self, toolface_rad: f64) {
        self.loads.toolface_rad = toolface_rad;
        self.kink = Kink::of_mesh(&self.mesh, &self.basis, toolface_rad);
    }

    /// Turn the bent housing's kink to `orientation_rad` (rad) about the unloaded triads, the
    /// model's toolface unchanged (a first guess of [`solve_holding_toolface`]: the toolface
    /// plus the twist of a similar solved state).
    pub fn turn_kink(&mut self, orientation_rad: f64) {
        self.kink = Kink::of_mesh(&self.mesh, &self.basis, orientation_rad);
    }

    /// The kink's turn beyond the model's toolface, rad (0 for a straight string): what
    /// [`solve_holding_toolface`] found for the string's twist.
    pub fn kink_correction_rad(&self) -> f64 {
        self.kink
            .map(|k| k.orientation_rad - self.loads.toolface_rad)
            .unwrap_or(0.0)
    }

    /// The toolface of the bent housing in `state`, rad in (-pi, pi] (None for a straight
    /// string): the direction the section below the bend points off the section above it,
    /// in the toolface reference of the hole at the bend node's axis point
    /// ([`crate::geometry::frame::toolface_direction`]).
    pub fn housing_toolface(&self, state: &State) -> Option<f64> {
        let k = self.kink?;
        let lam = &state.triads[k.node];
        let above = lam.column(0).into_owned();
        let below = (lam * k.offset).column(0).into_owned();
        let d = below - above * above.dot(&below);
        let t = self.path.axis_at(state.md[k.node]).tangent;
        let h = toolface_direction(&t, 0.0);
        let r = toolface_direction(&t, std::f64::consts::FRAC_PI_2);
        Some(d.dot(&r).atan2(d.dot(&h)))
    }
}

/// Largest difference between the toolface asked for and that of the solved state that
/// [`solve_holding_toolface`] accepts, rad (0.005 deg: at a motor yield of 15 deg/30 m it
/// turns the drilling direction by 0.001 deg/30 m).
pub const TOOLFACE_TOLERANCE_RAD: f64 = 0.005 * std::f64::consts::PI / 180.0;

/// Miss of the housing toolface above which the interior-point Newton turns the kink as it
/// iterates ([`Model::toolface_hold_rad`]), rad: a tenth of [`TOOLFACE_TOLERANCE_RAD`], so
/// that the last Newton steps, which move the housing a little after its last turn, leave it
/// within the tolerance (docs/performance.md, "The toolface held inside the Newton
/// iteration").
pub const HOLD_TURN_RAD: f64 = 0.1 * TOOLFACE_TOLERANCE_RAD;

/// Largest miss of the housing toolface by which the interior-point Newton turns the kink as
/// it iterates, rad: a larger one is the twist of a long string still winding up under its
/// torque (radians over a whole string), left to [`solve_holding_toolface`]'s further solves.
/// The predictor's cut models miss by up to 0.12 rad (a cold start after a slide); turning by
/// any miss, the whole-string solve of `wells/horizontal/steered.toml` did not converge, with
/// this cap (or 0.05 to 0.5 rad) it did.
pub const HOLD_TURN_MAX_RAD: f64 = 0.2;

/// Solves [`solve_holding_toolface`] may add to turn the housing.
pub const MAX_TOOLFACE_SOLVES: usize = 10;

/// Rounds of [`solve_holding_toolface`]'s fixed point on the reactive torque's turn: the
/// turn depends on the contacts, which depend on the toolface.
pub const MAX_REACTIVE_ROUNDS: usize = 4;

/// Solve `model` (by `first`, from its own start) and, for a bent housing, turn its kink about
/// the unloaded triads until the housing's toolface in the solved state
/// ([`Model::housing_toolface`]) is the model's `loads.toolface_rad` within
/// [`TOOLFACE_TOLERANCE_RAD`], each further solve warm-started from the last: the string
/// twists under torque (the bit's, the wall's friction), which turns the housing, and the
/// toolface a driller sets and reads is the one downhole. With the motor's reactive torque on
/// ([`Model::reactive`]) the housing is held at the toolface less the turn
/// ([`Model::reactive_turn`]) of the solved state, repeated until the turn changes by less
/// than the tolerance (at most [`MAX_REACTIVE_ROUNDS`]); the turn is in the statistics. A
/// first solve whose Newton held the toolface as it iterated ([`Model::toolface_hold_rad`], set
/// by the caller: the predictor's) is taken with the kink where that Newton left it, and
/// usually needs no further solve; the further solves hold it between solves. A straight
/// string is solved once. Returns the last solution (not converged when a turned
/// solve did not converge), its iteration count that of all the solves.
pub fn solve_holding_toolface(
    model: &mut Model,
    ctl: &SolveControls,
    first: impl FnOnce(&Model) -> Result<Solution, SolveError>,
) -> Result<Solution, SolveError> {
    let set = model.loads.toolface_rad;
    let sol = held_solution(model, first(model))?;
    let mut iterations = sol.stats.iterations;
    // the first turn from the first state (its kink at the caller's guess, e.g. the last
    // step's turned kink), so that a good guess costs one hold
    let mut turn = model.reactive_turn(&sol).filter(|_| sol.converged);
    let mut sol = hold(model, ctl, sol, set - turn.map_or(0.0, |t| t.turn_rad), &mut iterations)?;
    for _ in 0..MAX_REACTIVE_ROUNDS {
        let Some(last) = turn else {
            break;
        };
        let Some(t) = model.reactive_turn(&sol).filter(|_| sol.converged) else {
            break;
        };
        turn = Some(t);
        if (t.turn_rad - last.turn_rad).abs() <= TOOLFACE_TOLERANCE_RAD {
            break;
        }
        sol = hold(model, ctl, sol, set - t.turn_rad, &mut iterations)?;
    }
    sol.stats.iterations = iterations;
    sol.stats.reactive_turn = turn;
    Ok(sol)
}

/// The first solution `sol` of `model` in [`solve_holding_toolface`]: when its Newton held
/// [`Model::toolface_hold_rad`], `model`'s kink turned to where that Newton left it
/// ([`super::SolveStats::kink_turned_to_rad`]), so that `sol` is a solution of `model`; the
/// toolface no longer held inside the Newton (the further solves turn the kink between solves).
fn held_solution(model: &mut Model, sol: Result<Solution, SolveError>) -> Result<Solution, SolveError> {
    model.toolface_hold_rad = None;
    let sol = sol?;
    if let Some(o) = sol.stats.kink_turned_to_rad {
        model.turn_kink(o);
    }
    Ok(sol)
}

/// Turn `model`'s kink until the housing's toolface in the solution is `target` (rad) within
/// [`TOOLFACE_TOLERANCE_RAD`], from `sol` (at most [`MAX_TOOLFACE_SOLVES`] solves, each
/// warm-started from the last, their iterations added to `iterations`).
fn hold(
    model: &mut Model,
    ctl: &SolveControls,
    mut sol: Solution,
    target: f64,
    iterations: &mut usize,
) -> Result<Solution, SolveError> {
    for _ in 0..MAX_TOOLFACE_SOLVES {
        let (Some(k), Some(actual)) = (model.kink, model.housing_toolface(&sol.state)) else {
            break;
        };
        let miss = wrap_pi(target - actual);
        tracing::debug!(
            target_deg = target.to_degrees(),
            miss_deg = miss.to_degrees(),
            "housing toolface"
        );
        if miss.abs() <= TOOLFACE_TOLERANCE_RAD || !sol.converged {
            break;
        }
        model.kink = Kink::of_mesh(&model.mesh, &model.basis, k.orientation_rad + miss);
        sol = match solve_interior_point_from(model, sol.state.clone(), ctl) {
            Ok(s) if s.converged => s,
            _ => solve(model, ctl)?,
        };
        *iterations += sol.stats.iterations;
    }
    Ok(sol)
}
