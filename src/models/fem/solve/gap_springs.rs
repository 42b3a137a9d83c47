//! The gap model of the modified Newton (`method = "paper"`,
//! [`super::modified_newton_gap_forces`]): the kind of each node's gap, the gap springs `k_g`,
//! the friction as a lagged follower load and the residual with it, and the arc step that
//! moves the gap nodes on the wall along it.

use super::convergence::residual_norm;
use super::matrix_and_factor::MatrixAndFactor;
use crate::geometry::Vec3;
use crate::models::fem::contact::gap::{evaluate as gap_evaluate, GapInput, ZERO_CLEARANCE_M};
use crate::models::fem::model::{Evaluation, GapTreatment, Model, State, StiffnessSink};

/// Gap spring `k_g` of a node as a multiple of the string's own lateral stiffness there (the
/// diagonal of the structural stiffness at the start, at least the model's penalty stiffness).
pub const GAP_SPRING_FACTOR: f64 = 1.0;

/// Kind of contact node.
#[derive(Clone, Copy, PartialEq)]
pub(crate) enum Kind {
    /// No gap element.
    None,
    /// Gap with clearance: open/closed states of Table 1.
    Gap,
    /// Zero clearance (full-gauge stabilizer): always closed, radial displacement must vanish.
    Pin,
}

/// Kind of each node's gap.
pub(crate) fn node_kinds(model: &Model) -> Vec<Kind> {
    (0..model.nodes())
        .map(|i| {
            if !model.mesh.nodes[i].has_gap {
                Kind::None
            } else if model.clearance(i, model.md_ref[i]) <= ZERO_CLEARANCE_M {
                Kind::Pin
            } else {
                Kind::Gap
            }
        })
        .collect()
}

/// Gap springs `k_g` (N/m): [`GAP_SPRING_FACTOR`] x the lateral diagonal of the structural
/// stiffness at the start (gaps open), at least the model's penalty stiffness; zero where there
/// is no gap.
pub(crate) fn gap_springs(model: &Model, kind: &[Kind]) -> Vec<f64> {
    let nn = model.nodes();
    let mut lin = MatrixAndFactor::for_model(model);
    let mut bare = model.clone();
    bare.k_n.iter_mut().for_each(|k| *k = 0.0);
    bare.friction.iter_mut().for_each(|f| *f = 0.0);
    let mut s0 = model.initial_state();
    let open = GapTreatment {
        closed: Some(vec![false; nn]),
        ..GapTreatment::default()
    };
    bare.evaluate(&mut s0, &open, Some(lin.sink()));
    (0..nn)
        .map(|i| {
            if kind[i] == Kind::None {
                return model.k_n[i];
            }
            let s_ii = 0.5 * (lin.get(model.dof(i, 1), model.dof(i, 1)) + lin.get(model.dof(i, 2), model.dof(i, 2)));
            GAP_SPRING_FACTOR * s_ii.max(model.k_n[i])
        })
        .collect()
}

/// Add the lagged friction of every gap to the residual `r`: a follower load `f R_lag` against
/// the sliding velocity of the string surface (axial speed and rotation combined, with the
/// current contact normal) and its moment about the node (the friction torque `(D/2) T`),
/// Table 1 with the normal force `R_lag` of the previous contact check. Uses the gap element's
/// own friction law ([`crate::models::fem::contact::gap::evaluate`]) with the normal force given.
/// With `k`, the stiffness of these loads (their direction turns with the contact normal) is
/// added to it.
pub(crate) fn add_lagged_friction(
    model: &Model,
    state: &State,
    ev: &Evaluation,
    r_lag: &[f64],
    r: &mut [f64],
    mut k: Option<&mut dyn StiffnessSink>,
) {
    for i in 0..model.nodes() {
        let Some(g) = &ev.gaps[i] else { continue };
        if r_lag[i] <= 0.0 || model.friction[i] <= 0.0 {
            continue;
        }
        let p = model.path.point_at(state.md[i]);
        let fr = gap_evaluate(&GapInput {
            offset: state.x[i] - p.position,
            t: p.tangent,
            clearance: ev.clearance[i],
            contact_radius: model.mesh.nodes[i].contact_od_m / 2.0,
            lambda: 0.0,
            k_n: 0.0,
            friction: model.friction[i],
            axial_speed: model.loads.axial_speed_m_s,
            omega: model.loads.omega_rad_s,
            fallback_normal: g.normal,
            status: Some(false),
            // a pin takes its normal from the vector multiplier: the current direction
            lambda_vec: g.normal * r_lag[i],
            friction_load: Some(r_lag[i]),
            whirl: model.whirls(i),
        });
        // friction part only (a pin's evaluation also returns the normal force given)
        let f = model.basis[i].transpose() * (fr.force - fr.force_normal());
        let m = model.basis[i].transpose() * fr.moment;
        for c in 0..3 {
            r[model.dof(i, c)] -= f[c];
            r[model.dof(i, 3 + c)] -= m[c];
        }
        if let Some(km) = k.as_deref_mut() {
            let q = &model.basis[i];
            let kt = q.transpose() * fr.stiffness * q;
            let kr = q.transpose() * fr.moment_stiffness * q;
            let mut blk = [0.0; 36];
            for a in 0..3 {
                for b in 0..3 {
                    blk[a * 6 + b] = kt[(a, b)];
                    blk[(a + 3) * 6 + b] = kr[(a, b)];
                }
            }
            let d: [usize; 6] = std::array::from_fn(|c| model.dof(i, c));
            km.add_block(&d, &blk, 6);
        }
    }
}

/// Lateral offset of node `i` from its nearest hole-axis point (global, m); `state.md` must
/// hold the nearest-axis MD, as [`Model::evaluate`] leaves it.
pub(crate) fn lateral_offset(model: &Model, state: &State, i: usize) -> Vec3 {
    let p = model.path.point_at(state.md[i]);
    let d = state.x[i] - p.position;
    d - p.tangent * p.tangent.dot(&d)
}

/// Curvilinear step of the gap nodes held on the wall (`on_wall`): after `du` (scaled by
/// `beta`) has been applied to `after` (from `before`), each such node is moved radially so that
/// its radial distance from the hole axis is the linearized one, `s0 + n0 . du`. A straight
/// step of a node sliding round the wall (circumferential move `dt`) lands `dt^2 / (2 s)`
/// outside its circle, and the stiff gap spring turns that into a force error growing with
/// the square of the step; moving along the arc instead leaves the radial error third-order.
pub(crate) fn arc_step(model: &Model, before: &State, after: &mut State, du: &[f64], beta: f64, on_wall: &[bool]) {
    for (i, &on) in on_wall.iter().enumerate() {
        if !on {
            continue;
        }
        let d0 = lateral_offset(model, before, i);
        let s0 = d0.norm();
        if s0 < 1e-9 {
            continue;
        }
        let n0 = d0 / s0;
        let dx = Vec3::new(du[model.dof(i, 0)], du[model.dof(i, 1)], du[model.dof(i, 2)]);
        let target = s0 + n0.dot(&(model.basis[i] * dx)) * beta;
        let (_, p) = model.path.nearest_axis(&after.x[i], before.md[i]);
        let d = after.x[i] - p.position;
        let d1 = d - p.tangent * p.tangent.dot(&d);
        let s1 = d1.norm();
        if s1 > 1e-9 && target > 0.0 {
            after.x[i] += d1 * ((target - s1) / s1);
        }
    }
}

/// Residual at `ev` (of `state`) with the lagged friction of `r_lag` added and the constrained
/// entries zeroed, the WOB equation's residual (bordered system), and the norm of both relative
/// to `scale`.
pub(crate) fn residual_of(
    model: &Model,
    ev: &Evaluation,
    state: &State,
    r_lag: &[f64],
    constrained: &[usize],
    scale: f64,
) -> (Vec<f64>, f64, f64) {
    let mut r = ev.residual.clone();
    add_lagged_friction(model, state, ev, r_lag, &mut r, None);
    let c = if model.loads.hook_load_n.is_none() {
        r[model.dof(0, 0)] + model.loads.wob_n
    } else {
        0.0
    };
    for &d in constrained {
        r[d] = 0.0;
    }
    let rn = residual_norm(&r, scale).max(c.abs() / scale);
    (r, c, rn)
}
