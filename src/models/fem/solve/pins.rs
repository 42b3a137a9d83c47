//! Pins: the zero-clearance gaps (full-gauge stabilizers). The interior-point Newton holds
//! them as penalty springs about their vector multipliers until the outer residual falls
//! below [`PIN_EXACT_RESIDUAL`], then exactly: on the hole axis by their lateral DOFs, their
//! wall force the reaction to everything else ([`GapTreatment::exact_pins`]) with its friction
//! linearized.
//!
//! [`GapTreatment::exact_pins`]: crate::models::fem::model::GapTreatment::exact_pins

use super::matrix_and_factor::MatrixAndFactor;
use crate::models::fem::model::{Evaluation, Model, State};

/// Largest offset from the hole axis of the `pins` (zero-clearance gap nodes), m.
pub(crate) fn pin_offset_m(ev: &Evaluation, pins: &[usize]) -> f64 {
    pins.iter()
        .filter_map(|&i| ev.gaps[i].as_ref().map(|g| (g.penetration + ev.clearance[i]).max(0.0)))
        .fold(0.0, f64::max)
}

/// Outer residual (relative to the load scale) below which the interior-point Newton holds the
/// pins (zero-clearance gaps) exactly; above it they are penalty springs. Exact from the start,
/// a pin's force is the reaction to whatever lateral residual its neighbours carry, and its
/// friction (proportional to that force) made long rotating strings wander: the 10,000 m bench
/// string took 7-49 Newton iterations depending on its casing shoe depth (800-1,500 m),
/// against 10-12 with penalty pins and an augmented-Lagrangian phase, and 9-10 with this
/// switch. At the switch the Newton step prescribes the pins' lateral increments that take
/// them from the penalty's give (~15 um) onto the axis (moving the pins alone cost the cold BHA
/// solve an iteration: their neighbours' residual jumped); 0.3 brought the wandering back (17
/// iterations).
pub const PIN_EXACT_RESIDUAL: f64 = 0.1;

/// The model's held DOFs plus the lateral DOFs (basis 1 and 2) of the exact `pins`.
pub(crate) fn constrained_with_pins(model: &Model, pins: &[usize]) -> Vec<usize> {
    let mut constrained = model.constrained_dofs();
    for &i in pins {
        for k in 1..3 {
            if !constrained.contains(&model.dof(i, k)) {
                constrained.push(model.dof(i, k));
            }
        }
    }
    constrained
}

/// Linearization of the exact pins' friction (`GapTreatment::exact_pins`): a pin's wall force
/// `p` is the reaction to the lateral residual `a = -(I - t t^T)(Q1 r1 + Q2 r2)` of everything
/// else (`p = M a`, [`Model::pin_reaction`]), and its friction force and moment depend on `p`
/// (`F = -p - (f/|v|)(v_a |p| t + Omega R_c t x p)`,
/// `M = -(f R_c/|v|)(v_a p x t + Omega R_c |p| t)`), so the pin node's rows of the residual get
/// `Q^T (dG/dp) M (Q1 K1 + Q2 K2)`, `K1, K2` the tangent's rows of the lateral DOFs. Only
/// with friction and motion (the unsymmetric tangent); the lateral rows themselves are held.
pub(crate) fn add_pin_coupling(
    model: &Model,
    lin: &mut MatrixAndFactor,
    ev: &Evaluation,
    state: &State,
    pins: &[usize],
) {
    let MatrixAndFactor::General(k, _) = lin else {
        return;
    };
    let n = model.dofs();
    for &i in pins {
        let f = model.friction[i];
        let rc = model.mesh.nodes[i].contact_od_m / 2.0;
        // axial and circumferential shares v_a/|v|, Omega R_c/|v| of the sliding velocity
        let split = model.loads.motion().friction_split(rc);
        let (ax, tg) = (split.axial, split.tangential);
        let p = state.pin_multipliers[i];
        let pn = p.norm();
        if f <= 0.0 || !split.acts() || pn <= 1e-12 {
            continue;
        }
        let q = &model.basis[i];
        let t = ev.axis[i].1;
        let id = nalgebra::Matrix3::identity();
        let tx = t.cross_matrix();
        let fp = f * tg;
        let mf = (id - t * t.transpose() - tx * fp) / (1.0 + fp * fp);
        let ph = p / pn;
        let dgf = -id - (t * ph.transpose() * ax + tx * tg) * f;
        let dgm = -(t * ph.transpose() * tg - tx * ax) * (f * rc);
        let lat = nalgebra::Matrix3x2::from_columns(&[q.column(1).into_owned(), q.column(2).into_owned()]);
        let bf = q.transpose() * dgf * mf * lat;
        let bm = q.transpose() * dgm * mf * lat;
        let base = model.dof(i, 0);
        let rows = [(0, bf.row(0)), (3, bm.row(0)), (4, bm.row(1)), (5, bm.row(2))];
        for c in base.saturating_sub(6)..(base + 12).min(n) {
            let (k1, k2) = (k.get(base + 1, c), k.get(base + 2, c));
            for (r, b) in rows {
                k.add(base + r, c, b[0] * k1 + b[1] * k2);
            }
        }
    }
}

/// Put the `pins` (zero-clearance gap nodes) on the hole axis: each loses its lateral offset
/// from its nearest axis point (their lateral DOFs are held, so this only removes what sliding
/// along a curved axis leaves, and a warm start's offset; at the switch from penalty pins the
/// Newton step moves them instead).
pub(crate) fn hold_pins_on_axis(model: &Model, state: &mut State, pins: &[usize]) {
    for &i in pins {
        let (_, p) = model.path.nearest_axis(&state.x[i], state.md[i]);
        let d = state.x[i] - p.position;
        let lateral = d - p.tangent * p.tangent.dot(&d);
        if lateral.norm() > PIN_SNAP_FLOOR_M {
            state.x[i] -= lateral;
        }
    }
}

/// Lateral offset from the hole axis below which the pin hold (`hold_pins_on_axis`) leaves a pin where it is,
/// m. The axis point is computed from survey stations kilometres away (the bit at 3,000 m MD:
/// positions and MDs rounded to ~5e-13 m), so snapping every iteration moved the pin by a few
/// 1e-14 m each time: next to a pin on 0.01 m elements (`12 EI / l^3` ~ 1e14 N/m) that is a
/// force of ~3 N on its neighbours, a residual floor of 2e-5 of the load scale that no
/// Newton step removed. 1e-11 m is ten times the rounding of the axis at 10 km MD and four
/// orders below the held tolerance (`tolerance` x 1 mm).
pub const PIN_SNAP_FLOOR_M: f64 = 1e-11;

/// Prescribed lateral increments (DOF, m) that take the `pins` from their offset at the
/// evaluation `ev` of `state` onto the hole axis: the Newton step at the switch to exact pins
/// (non-homogeneous constraints of the held lateral DOFs; their coupling enters through
/// `K du`).
pub(crate) fn pin_moves(model: &Model, state: &State, ev: &Evaluation, pins: &[usize]) -> Vec<(usize, f64)> {
    pins.iter()
        .flat_map(|&i| {
            let d = state.x[i] - ev.axis[i].0;
            let q = &model.basis[i];
            [
                (model.dof(i, 1), -q.column(1).dot(&d)),
                (model.dof(i, 2), -q.column(2).dot(&d)),
            ]
        })
        .collect()
}
