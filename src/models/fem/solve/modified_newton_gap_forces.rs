//! The seed paper's contact solution (`[solver] method = "paper"`, physics.md 4.1-4.5): a
//! modified Newton iteration on the structure with gap springs in its stiffness matrix `K1`,
//! and gap forces updated between its solves by the contact-state checks of Table 1 and the
//! approximate-gradient update of eq. 15.
//!
//! - **Gap element**: each gap node has a radial spring `k_g` ([`GAP_SPRING_FACTOR`] times the
//!   string's own lateral stiffness there) and an additional force `P = p n` along its outward
//!   normal `n`; the wall force is `R = k_g s - p` (`s` the radial distance from the hole axis),
//!   held as the multiplier `k_g EO - p` so that `R = multiplier + k_g (s - EO)`. Zero-clearance
//!   gaps (pins) carry a vector `P`.
//! - **Structural iteration**: modified Newton steps `K1 du = -r` (bordered with the hook-load
//!   equation), `K1` with springs at the closed gaps only, refactored when a contact state
//!   changes, every [`REFRESH_EVERY`] steps and after a step that did not lower the residual;
//!   steps capped ([`MAX_LATERAL_STEP`] of the clearance, the bending rotation cap) and halved
//!   while the residual grows by more than [`BACKTRACK_GROWTH`]. Gap nodes on the wall move
//!   along it (`gap_springs::arc_step`). Open and frozen gaps follow the unilateral law
//!   `R = max(0, multiplier + k_g (s - EO))`, so that no node crosses the wall between checks.
//! - **Contact checks** (Table 1), at equilibrium for the current `P` (the structural residual
//!   below a tolerance tied to the contact error, [`INNER_TOLERANCE_FACTOR`]), or when the
//!   structural iteration stalls ([`STALL_STEPS`]) or after [`INNER_STEPS`] steps: an open gap
//!   that penetrates beyond the tolerance band, or carries a force, closes; a closed gap with a
//!   negative reaction opens. A gap that changed state [`MAX_FLIPS`] times is frozen to the
//!   unilateral law.
//! - **Gap forces** (eq. 15, at equilibrium only): `P2 = P1 + alpha (dP1/dS1) dS2` for every
//!   closed gap, `dS2 = EO - s` the radial correction still needed and `dP1/dS1` the secant of
//!   the last update, clamped to `[k_g, min(K1 radial diagonal, k_g / alpha)]`; `P` never moves
//!   the spring's anchor beyond the wall. Pins: `P += alpha k_g d`, `d` the lateral offset.
//! - **Friction** (Table 1: `T = f R`, `m = (D/2) T`): a follower load `f R_lag` against the
//!   sliding velocity (`gap_springs::add_lagged_friction`), `R_lag` the normal force of the last check
//!   under-relaxed ([`FRICTION_RELAXATION`]); an opened gap drops it at once.
//! - **Start**: the interior-point Newton's soft-string start (contact sides, smoothed, wound
//!   up), a gap closed where the smoothed node is at least [`START_CLOSED_FRACTION`] of its
//!   clearance off the axis, with `P` carrying its soft-string force.
//! - **Converged** when no state changes, every closed gap and pin is within the tolerance
//!   band, the residual and the friction mismatch `f |R - R_lag|` are below the residual
//!   tolerance. The final evaluation gives each closed gap exactly its reaction.
//!
//! The iteration is slow (175-260 steps on the example wells, docs/performance.md "Paper scheme
//! vs default") and agrees with the interior-point Newton within 2e-5 on bit forces, WOB, hook
//! load and surface torque.
//!
//! [`GAP_SPRING_FACTOR`]: super::gap_springs::GAP_SPRING_FACTOR

use super::controls::SolveControls;
use super::convergence::{load_scale, MIN_REFERENCE_CLEARANCE_M};
use super::gap_springs::{add_lagged_friction, arc_step, gap_springs, lateral_offset, node_kinds, residual_of, Kind};
use super::hook_load_system::{bit_row, bordered_step};
use super::matrix_and_factor::MatrixAndFactor;
use super::solution::{Solution, SolveError, SolveStats};
use super::start::{smooth_start, soft_string_start, wind_up_start};
use super::step_caps::{LATERAL_CAP_FLOOR_M, MAX_BENDING_ROTATION_STEP};
use crate::models::fem::model::{Evaluation, GapTreatment, Model, State};
use std::time::Instant;

/// Modified Newton steps between refreshes of the structural part of `K1` (co-rotational
/// tangent with the current axial forces); `K1` is also refactored whenever a contact state
/// changes and after a step that did not lower the residual.
pub const REFRESH_EVERY: usize = 5;

/// State changes after which a gap is frozen to the unilateral law (chattering).
pub const MAX_FLIPS: usize = 3;

/// Nodes whose state changed within this many iterations of the end are reported as chattering
/// when the solve does not converge.
pub const CHATTER_WINDOW: usize = 10;

/// Largest lateral move of a gap node per iteration, fraction of its clearance (physics.md 4.5).
pub const MAX_LATERAL_STEP: f64 = 0.5;

/// A secant `dP/dS` is only trusted when the radial move `dS` exceeds this fraction of the
/// gap tolerance band; below it the first-secant (diagonal) estimate is used.
pub const SECANT_MIN_STEP: f64 = 0.1;

/// Closed gaps open when their reaction is below minus this fraction of the residual
/// tolerance (times the load scale).
pub const RELEASE_FRACTION: f64 = 0.1;

/// The contact states are checked and P, friction updated once the structural residual (relative
/// to the load scale) is below `clamp(INNER_TOLERANCE_FACTOR x contact error, residual tolerance,
/// INNER_TOLERANCE_MAX)`, the contact error being the largest gap error relative to the clearance
/// or the friction-load mismatch relative to the load scale: the structure is solved about as
/// accurately as the current contact forces deserve.
pub const INNER_TOLERANCE_FACTOR: f64 = 1e-2;

/// Upper bound of the inner (structural) tolerance, see [`INNER_TOLERANCE_FACTOR`].
pub const INNER_TOLERANCE_MAX: f64 = 1e-3;

/// The contact states are also checked when the structural iteration stalls: the residual
/// norm after [`STALL_STEPS`] steps is above [`STALL_RATIO`] times its value before them (a
/// closed gap pulled toward the wall is a saddle of the energy, where the structural iteration
/// drifts until Table 1 opens the gap).
pub const STALL_STEPS: usize = 4;

/// See [`STALL_STEPS`].
pub const STALL_RATIO: f64 = 0.7;

/// Modified Newton steps allowed before the contact states are checked anyway.
pub const INNER_STEPS: usize = 30;

/// Under-relaxation of the lagged friction load: after each contact check the normal force used
/// by friction moves this fraction of the way to the current normal force.
pub const FRICTION_RELAXATION: f64 = 0.7;

/// Halvings of a modified Newton step tried while the residual norm grows beyond
/// [`BACKTRACK_GROWTH`] times its value; then K1 is refreshed (or, if fresh, the step taken).
pub const BACKTRACK_STEPS: usize = 6;

/// Largest growth of the residual norm accepted for one modified Newton step.
pub const BACKTRACK_GROWTH: f64 = 1.2;

/// A gap starts closed when the soft string lies on the wall there and the smoothed start
/// left the node at least this fraction of its clearance off the hole axis.
pub const START_CLOSED_FRACTION: f64 = 0.5;

/// Solve the static problem of `model` by the modified Newton with gap forces (see the module
/// documentation). Returns a flagged (`converged == false`) solution when the iteration limit
/// is reached.
pub fn solve_modified_newton(model: &Model, ctl: &SolveControls) -> Result<Solution, SolveError> {
    let t0 = Instant::now();
    let (mut mn, mut state) = ModifiedNewton::new(model, ctl);
    let mut stats = SolveStats::default();
    let mut converged = false;
    let mut ev;
    loop {
        // residual of K1 d = F0 + P (+ lagged friction) at the current state
        ev = mn.evaluate(&mut state, &mut stats)?;
        let (r, c, rn) = residual_of(model, &ev, &state, &mn.r_lag, &mn.constrained, mn.scale);
        mn.passes += 1;
        if !rn.is_finite() {
            tracing::warn!("paper scheme: residual not finite; stopping");
            stats.residual_history.push(rn);
            break;
        }
        if stats.iterations >= ctl.max_iterations || mn.passes > 3 * ctl.max_iterations + 10 {
            stats.residual_history.push(rn);
            break;
        }
        if t0.elapsed().as_secs_f64() > ctl.time_limit_s {
            stats.timed_out = true;
            stats.residual_history.push(rn);
            break;
        }
        // gaps under the unilateral law (open and frozen): K1 is refreshed when one switches
        if mn.unilateral_switched(&ev) {
            mn.need_refresh = true;
            continue;
        }
        // near equilibrium for the current P: contact-state checks (Table 1), then eq. 15 and
        // the friction loads
        if mn.check_due(rn) {
            if mn.contact_check(&mut state, &ev, rn, &mut stats) {
                converged = true;
                stats.residual_history.push(rn);
                break;
            }
            continue;
        }
        mn.structural_step(&mut state, &ev, &r, c, rn, &mut stats);
    }
    stats.chattering_nodes = (0..model.nodes())
        .filter(|&i| {
            mn.frozen[i] || (!converged && mn.last_change[i].is_some_and(|k| k + CHATTER_WINDOW > stats.iterations))
        })
        .collect();
    let eval = mn.final_evaluation(&mut state, &ev);
    stats.seconds = t0.elapsed().as_secs_f64();
    Ok(Solution {
        state,
        eval,
        converged,
        stats,
        last_linearization: None,
    })
}

/// Outcome of a contact check's examination of the gaps (Table 1).
struct ContactCheck {
    /// Every closed gap and pin within the tolerance band.
    in_band: bool,
    /// Largest gap error relative to the clearance.
    pen: f64,
    /// Closed gaps pulled off the wall.
    to_open: Vec<usize>,
    /// Open gaps that penetrate or carry a force.
    to_close: Vec<usize>,
    /// Largest friction mismatch `f |R - R_lag|` relative to the load scale.
    friction_gap: f64,
}

/// The modified Newton's system, contact states and gap-force history.
struct ModifiedNewton<'a> {
    model: &'a Model,
    ctl: &'a SolveControls,
    /// The model with the gap springs and without friction (K1's model).
    work: Model,
    /// K1 and its factor.
    lin: MatrixAndFactor,
    /// Held DOFs.
    constrained: Vec<usize>,
    /// The hook load is unknown (the system is bordered by the WOB equation).
    bordered: bool,
    /// The hook-load column ([`Model::hook_column`]).
    hook: Vec<(usize, f64)>,
    /// Load scale, N.
    scale: f64,
    /// A closed gap opens when its reaction is below minus this, N.
    release: f64,
    /// Kind of each node's gap.
    kind: Vec<Kind>,
    /// Gap spring per node, N/m.
    k_g: Vec<f64>,
    /// Closed gaps (Table 1).
    closed: Vec<bool>,
    /// Gaps frozen to the unilateral law.
    frozen: Vec<bool>,
    /// Gaps under the unilateral law (open and frozen).
    free: Vec<bool>,
    /// Unilateral gaps carrying a force at the last evaluation.
    free_active: Vec<bool>,
    /// The gaps' treatment in the evaluation.
    gaps: GapTreatment,
    /// Normal force of each gap used by friction, N.
    r_lag: Vec<f64>,
    /// Radial diagonal of K1 per node, N/m.
    k1_radial: Vec<f64>,
    /// The bit's axial row of K1 over the free columns.
    kb: Vec<(usize, f64)>,
    /// State changes per node.
    flips: Vec<usize>,
    /// Iteration of each node's last state change.
    last_change: Vec<Option<usize>>,
    /// Eq. 15 history per gap: previous increment of P (N) and radial distance after it (m).
    last_dp: Vec<f64>,
    last_s: Vec<f64>,
    /// K1 must be refactored before the next step.
    need_refresh: bool,
    /// Modified Newton steps since K1 was factored.
    since_refresh: usize,
    /// Evaluations made.
    passes: usize,
    /// Modified Newton steps since the last contact check.
    inner: usize,
    /// Contact checks made.
    outer: usize,
    /// Contact error of the last check (largest gap error / clearance, friction mismatch /
    /// load scale).
    contact_error: f64,
    /// Residual norm before the last step.
    last_rn: f64,
    /// Residual norms of the modified Newton steps since the last contact check.
    inner_history: Vec<f64>,
}

impl<'a> ModifiedNewton<'a> {
    /// The iteration of `model` and its start. K1 is assembled without friction (friction is
    /// a lagged follower load, see [`add_lagged_friction`]), with LU and the consistent
    /// co-rotational tangent when the string carries torque. The start is the interior-point
    /// Newton's (soft-string contact sides, smoothed, torsional wind-up); the soft-string normal
    /// forces are the first P of the closed gaps and the first friction loads.
    fn new(model: &'a Model, ctl: &'a SolveControls) -> (ModifiedNewton<'a>, State) {
        let nn = model.nodes();
        let scale = load_scale(model);
        let kind = node_kinds(model);
        let k_g = gap_springs(model, &kind);
        let torque = model.needs_unsymmetric() || model.loads.bit_torque_nm != 0.0;
        let mut work = model.clone();
        work.k_n = k_g.clone();
        work.friction.iter_mut().for_each(|f| *f = 0.0);
        work.consistent_tangent = torque;
        let lin = if torque {
            MatrixAndFactor::general(model.dofs())
        } else {
            MatrixAndFactor::for_model(&work)
        };
        let mut state = model.initial_state();
        soft_string_start(model, &mut state);
        smooth_start(model, &mut state);
        wind_up_start(model, &mut state);
        let r_lag: Vec<f64> = (0..nn)
            .map(|i| {
                if kind[i] == Kind::None {
                    0.0
                } else {
                    state.multipliers[i].max(0.0)
                }
            })
            .collect();
        let closed = start_closed(model, &kind, &k_g, &mut state);
        let frozen = vec![false; nn];
        let free = free_of(&kind, &closed, &frozen);
        let gaps = GapTreatment {
            closed: Some(closed.clone()),
            unilateral: Some(free.clone()),
            ..GapTreatment::default()
        };
        let mn = ModifiedNewton {
            model,
            ctl,
            work,
            lin,
            constrained: model.constrained_dofs(),
            bordered: model.loads.hook_load_n.is_none(),
            hook: model.hook_column(),
            scale,
            // a closed gap opens when its reaction is below -release (Table 1: R >= 0);
            // dropping a reaction smaller than that keeps the residual within its tolerance
            release: RELEASE_FRACTION * ctl.residual_tolerance * scale,
            kind,
            k_g,
            closed,
            frozen,
            free,
            free_active: vec![false; nn],
            gaps,
            r_lag,
            k1_radial: vec![0.0; nn],
            kb: Vec::new(),
            flips: vec![0; nn],
            last_change: vec![None; nn],
            last_dp: vec![0.0; nn],
            last_s: vec![f64::NAN; nn],
            need_refresh: true,
            since_refresh: 0,
            passes: 0,
            inner: 0,
            outer: 0,
            contact_error: 1.0,
            last_rn: f64::INFINITY,
            inner_history: Vec::new(),
        };
        (mn, state)
    }

    /// Evaluate `work` at `state`; when K1 needs a refresh, assemble and factor it (counted in
    /// `stats`) with its bit row, radial diagonals, the lagged friction's direction stiffness
    /// and `|R|/s` at closed gaps pulled toward the wall.
    fn evaluate(&mut self, state: &mut State, stats: &mut SolveStats) -> Result<Evaluation, SolveError> {
        if !self.need_refresh {
            return Ok(self.work.evaluate(state, &self.gaps, None));
        }
        let model = self.model;
        let ev = self.work.evaluate(state, &self.gaps, Some(self.lin.sink()));
        self.kb = bit_row(model, &self.lin, &self.constrained);
        for i in 0..model.nodes() {
            if self.kind[i] != Kind::None {
                // radial diagonal of K1 in the current contact direction (node basis)
                let nrm = model.basis[i].transpose() * state.normal[i];
                let mut kr = 0.0;
                for a in 0..3 {
                    for b in 0..3 {
                        kr += nrm[a] * self.lin.get(model.dof(i, a), model.dof(i, b)) * nrm[b];
                    }
                }
                self.k1_radial[i] = kr.max(self.k_g[i]);
            }
        }
        // the lagged friction's direction turns with the contact normal
        add_lagged_friction(
            model,
            state,
            &ev,
            &self.r_lag,
            &mut vec![0.0; model.dofs()],
            Some(self.lin.sink()),
        );
        // a closed gap pulled toward the wall (R < 0, about to open) has a negative circle
        // stiffness (R/s)(I - t t^T - n n^T) in the tangent: K1 takes |R|/s instead
        for (i, g) in ev.gaps.iter().enumerate() {
            let Some(g) = g else { continue };
            let s = g.penetration + ev.clearance[i];
            if self.kind[i] == Kind::Gap && g.normal_force < 0.0 && s > 1e-9 {
                let t = model.path.point_at(state.md[i]).tangent;
                let pt = nalgebra::Matrix3::identity() - t * t.transpose() - g.normal * g.normal.transpose();
                let kl = model.basis[i].transpose() * pt * model.basis[i] * (-2.0 * g.normal_force / s);
                let dofs: [usize; 3] = std::array::from_fn(|k| model.dof(i, k));
                self.lin.sink().add_block(&dofs, kl.transpose().as_slice(), 3);
            }
        }
        self.lin.constrain_and_factor(model, &self.constrained)?;
        stats.factorizations += 1;
        self.need_refresh = false;
        self.since_refresh = 0;
        Ok(ev)
    }

    /// Whether a gap under the unilateral law switched between carrying a force and not at
    /// the evaluation `ev` (then K1 needs a refresh).
    fn unilateral_switched(&mut self, ev: &Evaluation) -> bool {
        let mut switched = false;
        for i in 0..self.model.nodes() {
            if self.free[i] {
                let on = ev.gaps[i].as_ref().is_some_and(|g| g.normal_force > 0.0);
                switched |= on != self.free_active[i];
                self.free_active[i] = on;
            }
        }
        switched
    }

    /// Structural tolerance of the current contact error (see [`INNER_TOLERANCE_FACTOR`]).
    fn inner_tolerance(&self) -> f64 {
        (INNER_TOLERANCE_FACTOR * self.contact_error).clamp(self.ctl.residual_tolerance, INNER_TOLERANCE_MAX)
    }

    /// Whether the contact states are checked at the residual norm `rn`: at equilibrium for
    /// the current P, after [`INNER_STEPS`] steps, or when the structural iteration stalls.
    fn check_due(&self, rn: f64) -> bool {
        let inner = self.inner;
        let stalled = inner >= STALL_STEPS && rn > STALL_RATIO * self.inner_history[inner - STALL_STEPS];
        rn < self.inner_tolerance() || inner >= INNER_STEPS || stalled
    }

    /// Examine every gap at the evaluation `ev` (Table 1).
    fn check_states(&self, ev: &Evaluation) -> ContactCheck {
        let (model, ctl) = (self.model, self.ctl);
        let mut check = ContactCheck {
            in_band: true,
            pen: 0.0,
            to_open: Vec::new(),
            to_close: Vec::new(),
            friction_gap: 0.0,
        };
        for i in 0..model.nodes() {
            let Some(g) = &ev.gaps[i] else { continue };
            let eo = ev.clearance[i].max(MIN_REFERENCE_CLEARANCE_M);
            let tol = ctl.gap_tolerance * eo;
            if model.friction[i] > 0.0 {
                check.friction_gap = check
                    .friction_gap
                    .max(model.friction[i] * (g.normal_force.max(0.0) - self.r_lag[i]).abs());
            }
            match self.kind[i] {
                Kind::None => {}
                Kind::Pin => {
                    let s = g.penetration + ev.clearance[i];
                    check.pen = check.pen.max(s / eo);
                    check.in_band &= s <= tol;
                }
                Kind::Gap => {
                    let e = g.penetration;
                    if self.frozen[i] {
                        // unilateral law: R = max(0, lambda + k_g (s - EO))
                        let err = if g.normal_force > 0.0 { e.abs() } else { e.max(0.0) };
                        check.pen = check.pen.max(err / eo);
                        check.in_band &= err <= tol;
                    } else if self.closed[i] {
                        check.pen = check.pen.max(e.abs() / eo);
                        check.in_band &= e.abs() <= tol;
                        if g.normal_force < -self.release {
                            check.to_open.push(i);
                        }
                    } else {
                        check.pen = check.pen.max(e.max(0.0) / eo);
                        // Table 1: closed once it penetrates beyond the band, or carries a
                        // (unilateral) force within it
                        if e > tol || g.normal_force > self.release {
                            check.to_close.push(i);
                        }
                    }
                }
            }
        }
        check.friction_gap /= self.scale;
        check
    }

    /// A contact check at the evaluation `ev` of `state` with the residual norm `rn`: Table 1's
    /// state changes, and at equilibrium for the current P the friction loads and eq. 15.
    /// Returns whether the solution is converged.
    fn contact_check(&mut self, state: &mut State, ev: &Evaluation, rn: f64, stats: &mut SolveStats) -> bool {
        let eta = self.inner_tolerance();
        self.inner_history.clear();
        let check = self.check_states(ev);
        stats.max_penetration = check.pen;
        self.contact_error = check.pen.max(check.friction_gap);
        tracing::debug!(
            outer = self.outer,
            iteration = stats.iterations,
            residual = rn,
            penetration = check.pen,
            friction_gap = check.friction_gap,
            opening = check.to_open.len(),
            closing = check.to_close.len(),
            hook_load = state.hook_load_n,
            "paper contact check"
        );
        let ctl = self.ctl;
        let changes = check.to_open.len() + check.to_close.len();
        if changes == 0 && check.in_band && rn < ctl.residual_tolerance && check.friction_gap < ctl.residual_tolerance {
            return true;
        }
        self.outer += 1;
        self.inner = 0;
        // P and the friction loads are updated only at equilibrium for the current P (the
        // paper's K1 solves are exact): a stalled structural iteration only gets its contact
        // states checked
        let at_equilibrium = rn < eta;
        if at_equilibrium {
            // friction loads: under-relaxed toward the current normal forces
            for (rl, g) in self.r_lag.iter_mut().zip(&ev.gaps) {
                if let Some(g) = g {
                    *rl += FRICTION_RELAXATION * (g.normal_force.max(0.0) - *rl);
                }
            }
        }
        if changes > 0 {
            let switching: Vec<usize> = check.to_open.iter().chain(&check.to_close).copied().collect();
            self.switch_states(state, ev, &switching, stats.iterations);
        }
        if !at_equilibrium {
            if changes == 0 {
                // nothing to switch: a fresh K1 must take the structural iteration further
                self.need_refresh = true;
            }
            return false;
        }
        self.update_gap_forces(state, ev, stats.iterations);
        false
    }

    /// Switch the contact state of the gaps `switching` at the evaluation `ev` (iteration
    /// `iteration`): Table 1, an opened gap carrying no friction; a gap that changed state
    /// [`MAX_FLIPS`] times is frozen to the unilateral law.
    fn switch_states(&mut self, state: &mut State, ev: &Evaluation, switching: &[usize], iteration: usize) {
        for &i in switching {
            self.closed[i] = !self.closed[i];
            state.multipliers[i] = 0.0;
            if !self.closed[i] {
                // Table 1: an open gap carries no friction (T = 0, m = 0)
                self.r_lag[i] = 0.0;
            }
            self.last_dp[i] = 0.0;
            self.flips[i] += 1;
            self.last_change[i] = Some(iteration);
            if self.flips[i] >= MAX_FLIPS {
                self.frozen[i] = true;
                self.free_active[i] = self.closed[i];
            }
        }
        self.gaps.closed = Some(self.closed.clone());
        self.free = free_of(&self.kind, &self.closed, &self.frozen);
        for i in 0..self.model.nodes() {
            if self.free[i] && !self.frozen[i] {
                // a gap just opened starts in the unilateral law's current branch
                self.free_active[i] = ev.gaps[i].as_ref().is_some_and(|g| g.normal_force > 0.0);
            }
        }
        self.gaps.unilateral = Some(self.free.clone());
        self.need_refresh = true;
    }

    /// Eq. 15, `P2 = P1 + alpha (dP1/dS1) dS2`, for every closed gap that did not change state
    /// at iteration `iteration` (the frozen ones by `alpha k_g` times their error, the pins in
    /// vector form), at the evaluation `ev` of `state`.
    fn update_gap_forces(&mut self, state: &mut State, ev: &Evaluation, iteration: usize) {
        let (model, alpha) = (self.model, self.ctl.alpha);
        for i in 0..model.nodes() {
            let Some(g) = &ev.gaps[i] else { continue };
            let eo = ev.clearance[i].max(MIN_REFERENCE_CLEARANCE_M);
            let tol = self.ctl.gap_tolerance * eo;
            let k_g = self.k_g[i];
            match self.kind[i] {
                Kind::None => {}
                Kind::Pin => {
                    // vector form: drive the lateral offset d to zero (the pin force is
                    // -(lambda_vec + k_g d); its direction is not that of d)
                    let d = lateral_offset(model, state, i);
                    state.pin_multipliers[i] += d * (alpha * k_g);
                }
                Kind::Gap if self.frozen[i] => {
                    let e = g.penetration;
                    if g.normal_force > 0.0 || e > 0.0 {
                        state.multipliers[i] = (state.multipliers[i] + alpha * k_g * e).max(0.0);
                    }
                }
                Kind::Gap if self.closed[i] && self.last_change[i] != Some(iteration) => {
                    let s = g.penetration + ev.clearance[i];
                    let ds1 = s - self.last_s[i];
                    let k_max = self.k1_radial[i].min(k_g / alpha);
                    let last_dp = self.last_dp[i];
                    let secant = if last_dp != 0.0 && ds1.is_finite() && ds1.abs() > SECANT_MIN_STEP * tol {
                        (last_dp / ds1).clamp(k_g, k_max)
                    } else {
                        k_g
                    };
                    // dS2 = EO - s, the radial correction still needed; P = k_g EO - lambda
                    // along the outward normal (R = k_g s - P); P never moves the spring's
                    // anchor beyond the wall (lambda >= 0)
                    let ds2 = -g.penetration;
                    let dp = (alpha * secant * ds2).min(state.multipliers[i]);
                    state.multipliers[i] -= dp;
                    self.last_dp[i] = dp;
                    self.last_s[i] = s;
                }
                Kind::Gap => {}
            }
        }
    }

    /// Scale of the displacement increment `du` (DOF order, node bases) at the evaluation
    /// `ev`: lateral moves of gap nodes to [`MAX_LATERAL_STEP`] of the clearance, bending
    /// rotations to [`MAX_BENDING_ROTATION_STEP`]; and the node that sets it.
    fn step_cap(&self, ev: &Evaluation, du: &[f64]) -> (f64, usize) {
        let model = self.model;
        let mut ratio: f64 = 0.0;
        let mut worst = 0usize;
        for i in 0..model.nodes() {
            if self.kind[i] != Kind::None {
                let lat = du[model.dof(i, 1)].hypot(du[model.dof(i, 2)]);
                let q = lat / (MAX_LATERAL_STEP * ev.clearance[i].max(LATERAL_CAP_FLOOR_M));
                if q > ratio {
                    ratio = q;
                    worst = i;
                }
            }
            let rot = du[model.dof(i, 4)].hypot(du[model.dof(i, 5)]);
            if rot / MAX_BENDING_ROTATION_STEP > ratio {
                ratio = rot / MAX_BENDING_ROTATION_STEP;
                worst = i;
            }
        }
        (if ratio > 1.0 { 1.0 / ratio } else { 1.0 }, worst)
    }

    /// A modified Newton step with the factored K1 (bordered with the hook-load equation) from
    /// `state` at its evaluation `ev` with the residual `r`, the WOB equation's residual `c`
    /// (N) and their norm `rn`: capped, then halved while the residual grows by more than
    /// [`BACKTRACK_GROWTH`]; K1 is refreshed instead when it is stale and no longer contracts.
    fn structural_step(
        &mut self,
        state: &mut State,
        ev: &Evaluation,
        r: &[f64],
        c: f64,
        rn: f64,
        stats: &mut SolveStats,
    ) {
        if rn >= self.last_rn && self.since_refresh > 0 {
            // the stale K1 no longer contracts: refresh it
            self.last_rn = f64::INFINITY;
            self.need_refresh = true;
            return;
        }
        self.last_rn = rn;
        self.inner_history.push(rn);
        stats.iterations += 1;
        stats.residual_history.push(rn);
        self.inner += 1;
        let model = self.model;
        let nn = model.nodes();
        let (du, dh) = bordered_step(&self.lin, r, &self.kb, c, &self.hook, self.bordered);
        let (mut beta, worst) = self.step_cap(ev, &du);
        let worst_res = (0..model.dofs())
            .max_by(|&a, &b| r[a].abs().total_cmp(&r[b].abs()))
            .unwrap_or(0);
        tracing::trace!(
            iteration = stats.iterations,
            residual = rn,
            beta,
            worst_s = model.mesh.nodes[worst].s_m,
            worst_closed = self.closed[worst],
            worst_kind = self.kind[worst] as u8,
            res_s = model.mesh.nodes[nn - 1 - worst_res / 6].s_m,
            res_dof = worst_res % 6,
            fresh = self.since_refresh,
            "paper step"
        );
        // backtracking on the residual norm: a modified Newton step with a stale K1 (or a full
        // step into a strongly nonlinear region) may raise the residual many times over
        let mut accepted = false;
        // gap nodes on the wall move along it (see `arc_step`)
        let on_wall: Vec<bool> = (0..nn)
            .map(|i| {
                self.kind[i] == Kind::Gap
                    && if self.free[i] {
                        self.free_active[i]
                    } else {
                        self.closed[i]
                    }
            })
            .collect();
        for _ in 0..BACKTRACK_STEPS {
            let mut trial = state.clone();
            trial.hook_load_n += beta * dh;
            self.work.update(&mut trial, &du, beta);
            arc_step(model, state, &mut trial, &du, beta, &on_wall);
            let tev = self.work.evaluate(&mut trial, &self.gaps, None);
            let (_, _, rt) = residual_of(model, &tev, &trial, &self.r_lag, &self.constrained, self.scale);
            if rt <= BACKTRACK_GROWTH * rn {
                tracing::trace!(beta, residual = rt, "paper step accepted");
                *state = trial;
                accepted = true;
                break;
            }
            beta *= 0.5;
        }
        if !accepted {
            if self.since_refresh > 0 {
                self.need_refresh = true;
                self.last_rn = f64::INFINITY;
                return;
            }
            let before = state.clone();
            state.hook_load_n += beta * dh;
            self.work.update(state, &du, beta);
            arc_step(model, &before, state, &du, beta, &on_wall);
        }
        self.since_refresh += 1;
        if self.since_refresh >= REFRESH_EVERY {
            self.need_refresh = true;
        }
    }

    /// The final evaluation with the original model at `state`, whose last evaluation is `ev`:
    /// closed gaps carry exactly their wall reaction, pins the same force with the model's
    /// penalty stiffness.
    fn final_evaluation(&self, state: &mut State, ev: &Evaluation) -> Evaluation {
        let model = self.model;
        let nn = model.nodes();
        let mut closed_final = vec![false; nn];
        for (i, closed) in closed_final.iter_mut().enumerate() {
            match (self.kind[i], &ev.gaps[i]) {
                (Kind::Gap, Some(g)) => {
                    let on = (self.closed[i] || self.frozen[i]) && g.normal_force > 0.0;
                    *closed = on;
                    state.multipliers[i] = if on { g.normal_force } else { 0.0 };
                }
                (Kind::Pin, Some(_)) => {
                    // same pin force with the model's penalty stiffness
                    let d = lateral_offset(model, state, i);
                    state.pin_multipliers[i] += d * (self.k_g[i] - model.k_n[i]);
                }
                _ => {}
            }
        }
        let final_gaps = GapTreatment {
            closed: Some(closed_final),
            exact_multipliers: true,
            ..GapTreatment::default()
        };
        model.evaluate(state, &final_gaps, None)
    }
}

/// Gaps under the unilateral law `R = max(0, multiplier + k_g (s - EO))` during the structural
/// iteration: the `frozen` ones and every gap of kind `kind` not `closed` (with multiplier 0).
fn free_of(kind: &[Kind], closed: &[bool], frozen: &[bool]) -> Vec<bool> {
    (0..kind.len())
        .map(|i| frozen[i] || (kind[i] == Kind::Gap && !closed[i]))
        .collect()
}

/// The start's closed gaps: a gap starts closed where the soft string lies on the wall and the
/// smoothed start left the node at least [`START_CLOSED_FRACTION`] of its clearance off the
/// axis (a closed gap near the hole axis has no defined contact direction); P is set so that
/// the gap carries its soft-string force at the start (`R = multiplier + k_g (s - EO)`). The
/// other gaps' multipliers are zeroed.
fn start_closed(model: &Model, kind: &[Kind], k_g: &[f64], state: &mut State) -> Vec<bool> {
    let mut closed = vec![false; model.nodes()];
    for i in 0..model.nodes() {
        if kind[i] == Kind::Gap && state.multipliers[i] > 0.0 {
            let (md, p) = model.path.nearest_axis(&state.x[i], state.md[i]);
            let d = state.x[i] - p.position;
            let s = (d - p.tangent * p.tangent.dot(&d)).norm();
            let eo = model.clearance(i, md);
            if s >= START_CLOSED_FRACTION * eo {
                closed[i] = true;
                state.multipliers[i] += k_g[i] * (eo - s).max(0.0);
            }
        }
        if !closed[i] {
            state.multipliers[i] = 0.0;
        }
    }
    closed
}
