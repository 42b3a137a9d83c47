//! Convergence measures of the contact Newton: the load scale that makes residuals relative,
//! the residual norms, and the criteria of a converged solution (force residual, net force,
//! penetration, complementarity, pins on the hole axis).

use super::contacts::{ContactColumns, ContactSet};
use super::controls::SolveControls;
use super::pins::pin_offset_m;
use crate::geometry::Vec3;
use crate::models::fem::model::{Evaluation, Model, State};

/// Smallest clearance the gap tolerance is measured against, m: a gap's penetration counts
/// relative to `max(clearance, this)`, and a pin's offset relative to this.
pub(crate) const MIN_REFERENCE_CLEARANCE_M: f64 = 1e-3;

/// Net force of the residual allowed at convergence, in units of the residual tolerance (both
/// relative to the load scale): every entry below the tolerance is not enough when thousands
/// of nodes' small imbalances add up in the global equilibrium check.
pub const NET_FORCE_TOLERANCE: f64 = 1.0;

/// Net force of the residual allowed at convergence relative to the largest applied force (an
/// element's weight, a contact force, the WOB or the hook load), in units of the residual
/// tolerance: 1e-6 at the default tolerance, the global equilibrium error that `solve` reports
/// ("equilibrium error ... of the largest force"). On a long string the load scale (its whole
/// weight) is tens of times its largest single force, so [`NET_FORCE_TOLERANCE`] alone let a
/// solve end at 3e-6 of the largest force (docs/performance.md, "Converged means within 1e-6 of
/// the largest force").
pub const NET_FORCE_OF_LARGEST: f64 = 10.0;

/// Largest complementarity `|R min(gap, 0)|` allowed at convergence, relative to the load scale
/// times the clearance.
const COMPLEMENTARITY_TOLERANCE: f64 = 1e-6;

/// Outer residual (relative to the load scale) below which a full Newton step of the
/// interior-point Newton is expected to converge: the next evaluation is then made without
/// the tangent first (the converged one needs none), and redone with it if the expectation
/// fails. Newton converges quadratically here (e.g. 8e-3, 8e-5, 3e-8 on a 3,000 m string).
pub const LIKELY_CONVERGED_RESIDUAL: f64 = 1e-3;

/// After two Newton iterations, a full step is expected to converge only if the next residual
/// predicted from the last contraction (`rn^2 / rn_prev`) is below this many residual
/// tolerances (the cold BHA's 0.05, 7.6e-4, 5e-6: the step from 7.6e-4 is not probed).
pub const LIKELY_CONVERGED_FACTOR: f64 = 10.0;

/// Load scale used for relative residuals: total buoyed weight plus WOB (and a given hook
/// load) plus 1 kN, N.
pub fn load_scale(model: &Model) -> f64 {
    let w: f64 = model
        .mesh
        .elements
        .iter()
        .zip(&model.sections)
        .map(|(e, s)| e.buoyed_weight_n_per_m.abs() * s.l0)
        .sum();
    w + model.loads.wob_n.abs() + model.loads.hook_load_n.unwrap_or(0.0).abs() + 1e3
}

/// Rounding floor of the residual of `model` at `state`, relative to the load scale `scale`
/// (N): the largest over the nodes of `eps |x_i| sum_e (EA/l0 + 12 EI/l0^3)`, the change of a
/// node's residual when its position moves by its rounding (`eps |x_i|`, the model frame's
/// origin at the bit), summed over its elements' axial and lateral stiffnesses. A residual
/// cannot be computed more closely than this, so the interior-point Newton's residual
/// tolerance is at least this floor. It grows as `l^-3` (the `12 EI / l^3` term below ~0.2 m
/// elements): on the fulcrum BHA of docs/performance.md (Fine BHA meshes) 1.4e-9 at 0.5 m
/// elements, 2.1e-8 at 0.1 m (below the default tolerance, 1e-7, down to ~0.055 m), 1.3e-7 at
/// 0.05 m, 1.9e-6 at 0.02 m and 1.5e-5 at 0.01 m, where the Newton iterations had stalled at
/// 0.3-0.4 times the floor (7e-7 at 0.02 m, 6e-6 at 0.01 m).
pub(crate) fn rounding_floor(model: &Model, state: &State, scale: f64) -> f64 {
    let ne = model.sections.len();
    let stiffness = |e: usize| {
        let s = &model.sections[e];
        if s.l0 > 0.0 {
            s.ea / s.l0 + 12.0 * s.ei / s.l0.powi(3)
        } else {
            0.0
        }
    };
    (0..model.nodes())
        .map(|i| {
            let k: f64 = [i.checked_sub(1), (i < ne).then_some(i)]
                .into_iter()
                .flatten()
                .map(stiffness)
                .sum();
            f64::EPSILON * state.x[i].norm() * k
        })
        .fold(0.0, f64::max)
        / scale
}

/// Largest force applied to `model` in `state`, N: an element's weight, a contact or pin
/// force, the WOB or the hook load (at most the largest force of the reported equilibrium
/// check, whose contact forces include their friction).
fn largest_applied_force(model: &Model, state: &State) -> f64 {
    let weights = model
        .mesh
        .elements
        .iter()
        .zip(&model.sections)
        .map(|(e, s)| (e.buoyed_weight_n_per_m * s.l0).abs());
    let contacts = state
        .multipliers
        .iter()
        .copied()
        .chain(state.pin_multipliers.iter().map(|p| p.norm()));
    weights
        .chain(contacts)
        .fold(model.loads.wob_n.abs().max(state.hook_load_n.abs()), f64::max)
}

/// Largest residual entry relative to the load scale `scale` (N).
pub(crate) fn residual_norm(r: &[f64], scale: f64) -> f64 {
    r.iter().fold(0.0f64, |m, v| m.max(v.abs())) / scale
}

/// Index of the entry of `r` largest in magnitude (0 for an empty `r`).
pub(crate) fn largest_entry(r: &[f64]) -> usize {
    r.iter()
        .enumerate()
        .max_by(|a, b| a.1.abs().total_cmp(&b.1.abs()))
        .map(|(d, _)| d)
        .unwrap_or(0)
}

/// The outer residual of one linearization of the interior-point Newton.
pub(crate) struct OuterResidual {
    /// The residual with the multipliers as the managed gaps' contact forces and the
    /// constrained entries zeroed, N and N.m (DOF order).
    pub(crate) forces: Vec<f64>,
    /// The WOB equation's residual (axial reaction at the bit + WOB), N; 0 when the hook load
    /// is given.
    pub(crate) wob: f64,
}

/// How far one linearization of the interior-point Newton is from a solution.
pub(crate) struct Measures {
    /// Outer residual: largest entry of the residual with the multipliers as contact forces,
    /// or of the WOB equation, relative to the load scale.
    pub(crate) rn: f64,
    /// Largest penetration of a managed gap relative to its clearance (at least
    /// [`MIN_REFERENCE_CLEARANCE_M`]); negative when all are open.
    pub(crate) pen: f64,
    /// Distance from the bit of the node with the largest penetration (for the log), m.
    pub(crate) pen_s: f64,
    /// Largest complementarity `|R min(gap, 0)|` relative to the load scale times the clearance.
    pub(crate) compl: f64,
    /// Net force of the residual (the global equilibrium error of physics.md 6.7) relative to
    /// the load scale: the entries are each below the tolerance, but thousands of them may add up.
    pub(crate) net: f64,
    /// Largest offset of a pin from the hole axis, m.
    pub(crate) pin_offset: f64,
    /// Largest applied force (an element's weight, a contact or pin force, the WOB or the hook
    /// load) relative to the load scale.
    pub(crate) largest: f64,
}

impl Measures {
    /// Measures of the outer residual `outer` at the evaluation `ev`, with the managed gaps of
    /// `contacts` at the gaps of `cols` and the multipliers, pin forces and hook load of
    /// `state`, relative to the load scale `scale` (N).
    pub(crate) fn of(
        model: &Model,
        ev: &Evaluation,
        contacts: &ContactSet,
        cols: &ContactColumns,
        outer: &OuterResidual,
        state: &State,
        scale: f64,
    ) -> Measures {
        let multipliers = &state.multipliers;
        let (rt, gaps0) = (&outer.forces, &cols.gaps0);
        let rn = residual_norm(rt, scale).max(outer.wob.abs() / scale);
        let mut pen: f64 = 0.0;
        let mut compl: f64 = 0.0;
        let mut pen_s = 0.0;
        for (j, &i) in contacts.qidx.iter().enumerate() {
            let eo = ev.clearance[i].max(MIN_REFERENCE_CLEARANCE_M);
            if gaps0[j] / eo > pen {
                pen_s = model.mesh.nodes[i].s_m;
            }
            pen = pen.max(gaps0[j] / eo);
            compl = compl.max((multipliers[i] * gaps0[j].min(0.0)).abs() / (scale * eo));
        }
        let net = (0..model.nodes())
            .map(|i| model.basis[i] * Vec3::new(rt[model.dof(i, 0)], rt[model.dof(i, 1)], rt[model.dof(i, 2)]))
            .sum::<Vec3>()
            .norm()
            / scale;
        Measures {
            rn,
            pen,
            pen_s,
            compl,
            net,
            pin_offset: pin_offset_m(ev, &contacts.pins),
            largest: largest_applied_force(model, state) / scale,
        }
    }

    /// Equilibrium within the controls' tolerances: residual, net force, penetration and
    /// complementarity.
    pub(crate) fn equilibrium(&self, ctl: &SolveControls) -> bool {
        self.rn < ctl.residual_tolerance
            && self.net < NET_FORCE_TOLERANCE * ctl.residual_tolerance
            && self.net < NET_FORCE_OF_LARGEST * ctl.residual_tolerance * self.largest
            && self.pen <= ctl.gap_tolerance
            && self.compl < COMPLEMENTARITY_TOLERANCE
    }

    /// The pins (zero-clearance gaps, full-gauge stabilizers) are on the hole axis within the
    /// gap tolerance of the smallest clearance the managed gaps are measured against.
    pub(crate) fn pins_held(&self, ctl: &SolveControls) -> bool {
        self.pin_offset <= ctl.gap_tolerance * MIN_REFERENCE_CLEARANCE_M
    }
}

/// Whether the Newton step just taken (scaled by `alpha`, from the outer residual `rn` after
/// the residuals `history`) is expected to converge: full, from below
/// [`LIKELY_CONVERGED_RESIDUAL`], and, after a previous iteration, its contraction (the next
/// residual predicted as `rn^2 / rn_prev`) says so too. A probe that fails costs a
/// residual-only evaluation.
pub(crate) fn likely_converged(alpha: f64, rn: f64, history: &[f64], ctl: &SolveControls) -> bool {
    let predicted = match history.len() {
        0 | 1 => 0.0,
        k => rn * rn / history[k - 2],
    };
    alpha == 1.0 && rn < LIKELY_CONVERGED_RESIDUAL && predicted < LIKELY_CONVERGED_FACTOR * ctl.residual_tolerance
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The measures of the grid's 95 deg, 2,000 m slide at 20 kN where its refined solve had
    /// stopped (docs/performance.md, "Converged means within 1e-6 of the largest force"): every
    /// entry and the net force below the tolerance of the 914 kN load scale, but the net force
    /// 3.0e-6 of the largest applied force (24.3 kN) is not converged; 3.8e-7 of it is.
    #[test]
    fn net_force_is_measured_against_the_largest_force_too() {
        let ctl = SolveControls::default();
        let tol = ctl.residual_tolerance;
        let largest = 24.3 / 914.0;
        let at = |net: f64| Measures {
            rn: 6.6e-8,
            pen: 0.0,
            pen_s: 0.0,
            compl: 0.0,
            net,
            pin_offset: 0.0,
            largest,
        };
        assert!(
            (tol - 1e-7).abs() < 1e-20,
            "the case is stated at the default tolerance"
        );
        assert!(7.9e-8 < NET_FORCE_TOLERANCE * tol);
        assert!(!at(7.9e-8).equilibrium(&ctl));
        assert!(at(1e-8).equilibrium(&ctl));
        // the bound: ten tolerances of the largest force
        let bound = NET_FORCE_OF_LARGEST * tol * largest;
        assert!(at(0.99 * bound).equilibrium(&ctl) && !at(1.01 * bound).equilibrium(&ctl));
    }
}
