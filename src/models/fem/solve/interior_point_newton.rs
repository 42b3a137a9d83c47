//! The interior-point contact Newton (`method = "newton"`, the default): Newton iterations on
//! the co-rotational model with the consistent tangent, each step solving the linearized
//! contact problem of all gaps but the pins by the interior-point method of
//! [`super::interior_point`].
//!
//! Friction enters the residual exactly: it is proportional to the unknown normal force (the
//! equilibrium columns of [`super::contacts`]); the rotation of the contact normal enters the
//! tangent as the circle stiffness `(R/s)(I - t t^T - n n^T)` and the rotation of the friction
//! direction as the gaps' geometric stiffness at the previous multipliers. The zero-clearance
//! gaps (pins) are penalty springs until the outer residual falls below
//! [`PIN_EXACT_RESIDUAL`], then exact constraints ([`super::pins`]): held on the hole axis by
//! their lateral DOFs (the step at the switch prescribes the lateral increments that take them
//! from the penalty's give onto the axis), their force the reaction with its friction
//! linearized; no augmented-Lagrangian phase. The hook load is found with the bordered system
//! of [`super::hook_load_system`]; each step is capped ([`super::step_caps`]). A step that is
//! likely the last is followed by an evaluation without the tangent
//! ([`super::convergence::LIKELY_CONVERGED_RESIDUAL`]). The linearization is checked against
//! central differences in `interior_point_newton_tests.rs`.

use super::contacts::{add_circle_stiffness, contact_columns, contact_residual, ContactColumns, ContactSet};
use super::controls::SolveControls;
use super::convergence::{largest_entry, likely_converged, load_scale, rounding_floor, Measures, OuterResidual};
use super::hook_load_system::{bit_row, free_residual};
use super::interior_point::{
    constraint_scale, contact_clearances, contact_dofs, ip_tolerance, previous_multipliers, ContactSubproblem,
    ACTIVE_SET_RESIDUAL, MAX_IP_ITERATIONS,
};
use super::matrix_and_factor::MatrixAndFactor;
use super::pins::{add_pin_coupling, constrained_with_pins, hold_pins_on_axis, pin_moves, PIN_EXACT_RESIDUAL};
use super::solution::{LastLinearization, Solution, SolveError, SolveStats};
use super::start::cold_start;
use super::step_caps::step_cap;
use super::toolface::{HOLD_TURN_MAX_RAD, HOLD_TURN_RAD};
use crate::geometry::survey::wrap_pi;
use crate::geometry::Vec3;
use crate::models::fem::model::{Evaluation, GapTreatment, Model, State};
use std::time::Instant;

/// Solve the static problem of `model` from its start ([`cold_start`]) by the interior-point
/// contact Newton with the fully consistent co-rotational tangent; an unconverged solve is
/// returned flagged (`converged == false`).
pub fn solve_interior_point(model: &Model, ctl: &SolveControls) -> Result<Solution, SolveError> {
    let t0 = Instant::now();
    let mut consistent = model.clone();
    consistent.consistent_tangent = true;
    let state = cold_start(model);
    let mut sol = solve_interior_point_from(&consistent, state, ctl)?;
    sol.stats.seconds = t0.elapsed().as_secs_f64();
    Ok(sol)
}

/// Solve the static problem of `model` by the interior-point contact Newton from `state` (a
/// start, or a warm start carried from a neighbouring solution; one that carries the pins'
/// forces holds the pins exactly from the first iteration).
pub fn solve_interior_point_from(model: &Model, mut state: State, ctl: &SolveControls) -> Result<Solution, SolveError> {
    let t0 = Instant::now();
    let mut newton = InteriorPointNewton::new(model, ctl, &state);
    let end = newton_loop(&mut newton, &mut state, ctl, false)?;
    let mut stats = end.stats;
    let ev = end
        .ev
        .expect("a loop that does not stop at a likely step ends evaluated");
    let eval = newton.final_evaluation(&mut state, ev);
    stats.kink_turned_to_rad = newton.held.as_ref().and_then(|m| m.kink).map(|k| k.orientation_rad);
    stats.seconds = t0.elapsed().as_secs_f64();
    let last_linearization = newton.into_last_linearization();
    Ok(Solution {
        state,
        eval,
        converged: end.converged,
        stats,
        last_linearization,
    })
}

/// The interior-point Newton of `model` from `state` (as [`solve_interior_point_from`]) up to
/// its first step that is likely the last ([`likely_converged`]), without the evaluation that
/// would check it: for a part whose solution a solve of the whole model checks next
/// ([`crate::models::fem::condense`]). Returns the state, the work, and whether it stopped at
/// such a step or converged (false: it failed to).
pub(crate) fn steps_until_likely(
    model: &Model,
    mut state: State,
    ctl: &SolveControls,
) -> Result<(State, SolveStats, bool), SolveError> {
    let t0 = Instant::now();
    let mut newton = InteriorPointNewton::new(model, ctl, &state);
    let end = newton_loop(&mut newton, &mut state, ctl, true)?;
    let mut stats = end.stats;
    stats.seconds = t0.elapsed().as_secs_f64();
    Ok((state, stats, end.converged || end.ev.is_none()))
}

/// How [`newton_loop`] ended.
struct LoopEnd {
    /// The last evaluation (None: stopped after a step likely the last, unevaluated).
    ev: Option<Evaluation>,
    /// Whether the last evaluation met every convergence criterion.
    converged: bool,
    /// The work.
    stats: SolveStats,
}

/// The Newton iterations of `newton` on `state` under `ctl` until converged, out of
/// iterations, time or capped contact subproblems, or, with `stop_at_likely`, right after a
/// step that is likely the last.
fn newton_loop(
    newton: &mut InteriorPointNewton,
    state: &mut State,
    ctl: &SolveControls,
    stop_at_likely: bool,
) -> Result<LoopEnd, SolveError> {
    let t0 = Instant::now();
    let mut stats = SolveStats::default();
    let mut converged = false;
    // the previous Newton step was full and its outer residual small: this evaluation is
    // likely the converged one, so it is first made without the tangent (then redone with it
    // if the solution is not converged after all)
    let mut likely = ctl.likely_converged_start;
    let mut redo = false;
    let mut ev;
    loop {
        if newton.hold_toolface(state) {
            // the kink turned: the state is no longer near this model's equilibrium
            likely = false;
        }
        let skip_tangent = likely && !redo;
        redo = false;
        let switching = newton.switch_or_hold_pins(state, &stats.residual_history);
        ev = newton.evaluate(state, !skip_tangent);
        let lz = newton.linearize(state, &ev, switching);
        let equilibrium = lz.measures.equilibrium(&newton.ctl);
        let done = equilibrium && lz.measures.pins_held(&newton.ctl) && newton.gaps.exact_pins;
        if skip_tangent && !done && stats.iterations < ctl.max_iterations {
            redo = true;
            continue;
        }
        stats.residual_history.push(lz.measures.rn);
        stats.max_penetration = lz.measures.pen.max(0.0);
        newton.log_iteration(&lz, stats.iterations);
        if done {
            converged = true;
            break;
        }
        if stats.iterations >= ctl.max_iterations {
            break;
        }
        if t0.elapsed().as_secs_f64() > ctl.time_limit_s {
            stats.timed_out = true;
            break;
        }
        if ctl.stop_after_capped_subproblems > 0 && newton.capped_in_a_row >= ctl.stop_after_capped_subproblems {
            break;
        }
        if equilibrium && !newton.gaps.exact_pins {
            // in equilibrium about penalty pins (a step went straight from above
            // `PIN_EXACT_RESIDUAL` to the tolerance): the next evaluation holds them exactly
            stats.iterations += 1;
            likely = false;
            continue;
        }
        likely = newton.step(state, &ev, &lz, &mut stats)?;
        stats.iterations += 1;
        if likely && stop_at_likely {
            return Ok(LoopEnd {
                ev: None,
                converged: false,
                stats,
            });
        }
    }
    Ok(LoopEnd {
        ev: Some(ev),
        converged,
        stats,
    })
}

/// One Newton iteration's linearization at an evaluation.
struct Linearization {
    /// The residual with the constrained entries zeroed, N and N.m (DOF order).
    r0: Vec<f64>,
    /// Prescribed increments of held DOFs (DOF, m): the switching pins' lateral moves onto
    /// the hole axis.
    pin_move: Vec<(usize, f64)>,
    /// The managed gaps' linearized contacts.
    cols: ContactColumns,
    /// The outer residual with the multipliers as the contact forces.
    outer: OuterResidual,
    /// Its convergence measures.
    measures: Measures,
}

/// The interior-point Newton's settings and system for one model.
struct InteriorPointNewton<'a> {
    model: &'a Model,
    /// The controls, the residual tolerance raised to the residual's rounding floor
    /// ([`rounding_floor`]) where that is higher.
    ctl: SolveControls,
    /// Load scale, N.
    scale: f64,
    /// The hook load is unknown (the system is bordered by the WOB equation).
    bordered: bool,
    /// The hook-load column ([`Model::hook_column`]).
    hook: Vec<(usize, f64)>,
    /// The managed gaps and the pins.
    contacts: ContactSet,
    /// The model's held DOFs plus the pins' lateral DOFs.
    pin_constrained: Vec<usize>,
    /// The DOFs held now.
    constrained: Vec<usize>,
    /// How the evaluation treats the gaps.
    gaps: GapTreatment,
    /// The tangent and its factor.
    lin: MatrixAndFactor,
    /// The outer residual of the first step (the reference of the pseudo-transient damping,
    /// [`SolveControls::lateral_damping_n_per_m`]).
    first_residual: Option<f64>,
    /// The housing toolface held, rad ([`Model::toolface_hold_rad`] of a model with a kink).
    hold_rad: Option<f64>,
    /// The model with its kink turned to hold the toolface (None until it is first turned):
    /// the model of the evaluations.
    held: Option<Model>,
    /// Newton steps in a row whose contact subproblem ended at [`MAX_IP_ITERATIONS`].
    capped_in_a_row: usize,
    /// The last step's contacts (`R / s` of its last factorization, normals and nodes), the
    /// state its tangent was assembled at and the DOFs it held, the factor in [`Self::lin`]
    /// being that step's (an assembly after it writes the matrix, not the factor); None before
    /// the first step and in a solve that does not hand it out
    /// ([`Self::hands_out_last_step`]).
    last_contacts: Option<LastStep>,
}

/// The last Newton step's contacts and state ([`LastLinearization`] without the matrix).
struct LastStep {
    /// `R / s` per contact of the step's last factorization, N/m.
    ratio: Vec<f64>,
    /// Outward normal per contact (node basis).
    normals: Vec<Vec3>,
    /// Node per contact.
    node: Vec<usize>,
    /// The state the step's tangent was assembled at.
    state: State,
    /// The DOFs the step held.
    constrained: Vec<usize>,
}

impl<'a> InteriorPointNewton<'a> {
    /// The Newton of `model` from `state`: the managed gaps' forces come from the interior
    /// point, the other gaps are open (pins aside). The pins become exact constraints once the
    /// outer residual is below [`PIN_EXACT_RESIDUAL`] (held on the hole axis by their lateral
    /// DOFs, their wall force the reaction, [`Model::pin_reaction`], set by each evaluation);
    /// before that they are penalty springs about their vector multipliers. A warm start that
    /// carries the pins' forces starts exact.
    fn new(model: &'a Model, ctl: &SolveControls, state: &State) -> InteriorPointNewton<'a> {
        let nn = model.nodes();
        let contacts = ContactSet::of(model);
        let pins = &contacts.pins;
        let pin_constrained = constrained_with_pins(model, pins);
        let exact_pins = pins.is_empty() || pins.iter().any(|&i| state.pin_multipliers[i] != Vec3::zeros());
        let gaps = GapTreatment {
            closed: Some(vec![false; nn]),
            unilateral: None,
            solver_contacts: Some(contacts.managed.clone()),
            exact_multipliers: false,
            exact_pins,
        };
        let constrained = if exact_pins {
            pin_constrained.clone()
        } else {
            model.constrained_dofs()
        };
        let scale = load_scale(model);
        let floor = rounding_floor(model, state, scale);
        tracing::debug!(floor, "rounding floor of the residual (relative to the load scale)");
        InteriorPointNewton {
            model,
            ctl: SolveControls {
                residual_tolerance: ctl.residual_tolerance.max(floor),
                ..*ctl
            },
            scale,
            bordered: model.loads.hook_load_n.is_none(),
            hook: model.hook_column(),
            contacts,
            pin_constrained,
            constrained,
            gaps,
            lin: MatrixAndFactor::for_model(model),
            first_residual: None,
            hold_rad: model.toolface_hold_rad.filter(|_| model.kink.is_some()),
            held: None,
            capped_in_a_row: 0,
            last_contacts: None,
        }
    }

    /// Switch to exact pins once the last outer residual in `history` is below
    /// [`PIN_EXACT_RESIDUAL`] (returns `true`; the pins are not moved onto the axis by
    /// themselves, their neighbours would carry the jump into the residual: the Newton step
    /// prescribes their lateral increments instead); exact pins already: put them back on the
    /// hole axis.
    fn switch_or_hold_pins(&mut self, state: &mut State, history: &[f64]) -> bool {
        let switching = !self.gaps.exact_pins && history.last().is_some_and(|&r| r < PIN_EXACT_RESIDUAL);
        if switching {
            self.gaps.exact_pins = true;
            self.constrained.clone_from(&self.pin_constrained);
        } else if self.gaps.exact_pins {
            hold_pins_on_axis(self.model, state, &self.contacts.pins);
        }
        switching
    }

    /// Hold the housing toolface ([`Model::toolface_hold_rad`]) in `state`: when the housing
    /// in `state` misses it by more than [`HOLD_TURN_RAD`] and at most [`HOLD_TURN_MAX_RAD`],
    /// turn the kink by the miss (the housing turns with it, to first order, by as much:
    /// docs/theory.md 9.9, "Holding the toolface as the Newton iterates"). Returns whether the
    /// kink turned.
    fn hold_toolface(&mut self, state: &State) -> bool {
        let Some(target) = self.hold_rad else {
            return false;
        };
        let m = self.held.as_ref().unwrap_or(self.model);
        let (Some(k), Some(actual)) = (m.kink, m.housing_toolface(state)) else {
            return false;
        };
        let miss = wrap_pi(target - actual);
        if miss.abs() <= HOLD_TURN_RAD || miss.abs() > HOLD_TURN_MAX_RAD {
            return false;
        }
        self.held
            .get_or_insert_with(|| self.model.clone())
            .turn_kink(k.orientation_rad + miss);
        true
    }

    /// The model of the evaluations: the one solved, its kink turned where the toolface is
    /// held.
    fn evaluated(&self) -> &Model {
        self.held.as_ref().unwrap_or(self.model)
    }

    /// Evaluate `state`, assembling the tangent when `with_tangent`.
    fn evaluate(&mut self, state: &mut State, with_tangent: bool) -> Evaluation {
        let m = self.held.as_ref().unwrap_or(self.model);
        if with_tangent {
            m.evaluate(state, &self.gaps, Some(self.lin.sink()))
        } else {
            m.evaluate(state, &self.gaps, None)
        }
    }

    /// The linearization at the evaluation `ev` of `state` (whose contact normals it updates);
    /// `switching`: the pins become exact at this iteration.
    fn linearize(&self, state: &mut State, ev: &Evaluation, switching: bool) -> Linearization {
        let (model, qidx) = (self.model, &self.contacts.qidx);
        let (c, r0) = free_residual(model, ev, &self.constrained);
        let pin_move = if switching {
            pin_moves(model, state, ev, &self.contacts.pins)
        } else {
            Vec::new()
        };
        let mut cols = contact_columns(model, state, ev, qidx);
        cols.add_far_walls(model, ev, qidx);
        let outer = OuterResidual {
            forces: contact_residual(model, &r0, qidx, &cols.eq_cols, &state.multipliers, &self.constrained),
            wob: c,
        };
        let measures = Measures::of(model, ev, &self.contacts, &cols, &outer, state, self.scale);
        Linearization {
            r0,
            pin_move,
            cols,
            outer,
            measures,
        }
    }

    /// Debug log of iteration `iteration` at the linearization `lz`.
    fn log_iteration(&self, lz: &Linearization, iteration: usize) {
        if tracing::enabled!(tracing::Level::DEBUG) {
            // the largest residual entry: a scan over every DOF, made only for the log
            let worst = largest_entry(&lz.outer.forces);
            let m = &lz.measures;
            tracing::debug!(
                iteration,
                worst_s = self.model.mesh.nodes[self.model.nodes() - 1 - worst / 6].s_m,
                worst_dof = worst % 6,
                pen_s = m.pen_s,
                residual = m.rn,
                net = m.net,
                penetration = m.pen,
                compl = m.compl,
                "ip newton"
            );
        }
    }

    /// One Newton step from the linearization `lz` at the evaluation `ev` (whose tangent is
    /// assembled): the contact subproblem solved by the interior point (its factorizations
    /// counted in `stats`), the step capped and applied to `state` with the new multipliers.
    /// Returns whether the next evaluation is likely the converged one.
    fn step(
        &mut self,
        state: &mut State,
        ev: &Evaluation,
        lz: &Linearization,
        stats: &mut SolveStats,
    ) -> Result<bool, SolveError> {
        self.add_damping(lz.measures.rn);
        let model = self.model;
        let qidx = &self.contacts.qidx;
        // circle stiffness of the current contact forces
        add_circle_stiffness(model, self.lin.sink(), qidx, &lz.cols.geometry, &state.multipliers);
        if self.gaps.exact_pins {
            add_pin_coupling(model, &mut self.lin, ev, state, &self.contacts.pins);
        }
        let kb = bit_row(model, &self.lin, &self.constrained);
        // the base matrix K (before interior-point terms) is kept to rebuild each iteration
        let base = self.lin.keep_base();
        let rn = lz.measures.rn;
        let sub = ContactSubproblem {
            model,
            cols: &lz.cols,
            contact_at: &self.contacts.contact_at,
            r0: &lz.r0,
            c: lz.outer.wob,
            kb: &kb,
            hook: &self.hook,
            bordered: self.bordered,
            constrained: &self.constrained,
            pin_move: &lz.pin_move,
            base: base.as_ref(),
            constraint_scale: constraint_scale(base.as_ref().unwrap_or(&self.lin), model.dofs()),
            scale: self.scale,
            eta: ip_tolerance(rn),
            lam_prev: previous_multipliers(&lz.cols, qidx, &state.multipliers),
            clr: contact_clearances(&lz.cols, ev),
            dofs6: contact_dofs(model, &lz.cols),
            carried_start: self.ctl.carried_start,
            recentre_blockers: self.ctl.lateral_damping_n_per_m > 0.0,
        };
        // the active-set step near convergence, not at the pins' switch (their prescribed
        // move changes the contact set), nor on a refined mesh (its degenerate pairs switch)
        let try_active_set =
            stats.iterations > 0 && lz.pin_move.is_empty() && rn < ACTIVE_SET_RESIDUAL && !self.ctl.carried_start;
        let mut ip = sub.solve(&mut self.lin, stats, rn, try_active_set)?;
        if self.hands_out_last_step() {
            self.last_contacts = Some(LastStep {
                ratio: std::mem::take(&mut ip.factored_ratio),
                normals: lz.cols.normals.clone(),
                node: lz.cols.node.clone(),
                state: state.clone(),
                constrained: self.constrained.clone(),
            });
        }
        self.capped_in_a_row = match ip.iterations >= MAX_IP_ITERATIONS {
            true => self.capped_in_a_row + 1,
            false => 0,
        };
        let cap = step_cap(model, ev, &ip.iterate.du, qidx);
        tracing::debug!(
            ip_iters = ip.iterations,
            alpha = cap.alpha,
            rot_ratio = cap.rot_ratio,
            rot_s = model.mesh.nodes[cap.rot_node].s_m,
            lat_ratio = cap.lat_ratio,
            lat_s = model.mesh.nodes[cap.lat_node].s_m,
            "interior-point iterations and step cap (bending-rotation and lateral caps: ratio and \
             distance from the bit of the node that sets each)"
        );
        let likely = likely_converged(cap.alpha, rn, &stats.residual_history, &self.ctl);
        state.hook_load_n += cap.alpha * ip.iterate.dh;
        model.update(state, &ip.iterate.du, cap.alpha);
        for (j, &i) in qidx.iter().enumerate() {
            let rj = lz.cols.node_force(&ip.iterate.r, j, i);
            state.multipliers[i] = if rj > 1e-9 * self.scale { rj } else { 0.0 };
        }
        Ok(likely)
    }

    /// Add the pseudo-transient damping at the outer residual `rn` to both lateral
    /// translations of every node ([`SolveControls::lateral_damping_n_per_m`],
    /// [`SolveControls::damping_reference_residual`]).
    fn add_damping(&mut self, rn: f64) {
        let d0 = self.ctl.lateral_damping_n_per_m;
        if d0 <= 0.0 {
            return;
        }
        let first = *self.first_residual.get_or_insert(rn);
        let r_ref = match self.ctl.damping_reference_residual {
            r if r > 0.0 => r,
            _ => first,
        };
        let d = d0 * (rn / r_ref).min(1.0);
        let sink = self.lin.sink();
        for i in 0..self.model.nodes() {
            for k in [1, 2] {
                sink.add_block(&[self.model.dof(i, k)], &[d], 1);
            }
        }
    }

    /// Whether the solve hands out its last step's linear system ([`LastLinearization`]): an
    /// undamped solve with the LU, its kink not turned (the damping and a turned kink are in
    /// the factored matrix); the steps of other solves keep nothing.
    fn hands_out_last_step(&self) -> bool {
        let lu = matches!(self.lin, MatrixAndFactor::General(..));
        lu && self.ctl.lateral_damping_n_per_m == 0.0 && self.held.is_none()
    }

    /// The last step's linear system ([`LastLinearization`]) where the solve hands it out
    /// ([`Self::hands_out_last_step`]) and made a step; None otherwise.
    fn into_last_linearization(self) -> Option<Box<LastLinearization>> {
        if !self.hands_out_last_step() {
            return None;
        }
        let last = self.last_contacts?;
        Some(Box::new(LastLinearization {
            lin: self.lin,
            ratio: last.ratio,
            normals: last.normals,
            node: last.node,
            constrained: last.constrained,
            state: last.state,
        }))
    }

    /// The final evaluation of `state`, whose last evaluation is `ev`: contacts with force are
    /// closed at exactly their multipliers; same positions and triads, so `ev`'s element
    /// responses are reused.
    fn final_evaluation(&self, state: &mut State, ev: Evaluation) -> Evaluation {
        let managed = &self.contacts.managed;
        let closed: Vec<bool> = (0..self.model.nodes())
            .map(|i| managed[i] && state.multipliers[i] > 0.0)
            .collect();
        let final_gaps = GapTreatment {
            closed: Some(closed),
            exact_multipliers: true,
            ..GapTreatment::default()
        };
        self.evaluated()
            .evaluate_reusing_elements(state, &final_gaps, ev.elements)
    }
}

#[cfg(test)]
#[path = "interior_point_newton_tests.rs"]
mod tests;
