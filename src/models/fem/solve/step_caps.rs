//! Step caps of the contact Newton: a Newton step is scaled down so that no bending rotation
//! and no lateral motion of a gap node exceeds its cap.

use crate::geometry::Vec3;
use crate::models::fem::model::{Evaluation, Model};

/// Largest lateral motion of a gap node per interior-point Newton step, in clearances.
pub const MAX_LATERAL_STEP_CLEARANCES: f64 = 2.0;

/// Largest bending rotation increment allowed per iteration, rad.
pub const MAX_BENDING_ROTATION_STEP: f64 = 0.02;

/// Smallest clearance the lateral step cap counts with, m (a tighter gap would hold the whole
/// step to a fraction of a millimetre).
pub const LATERAL_CAP_FLOOR_M: f64 = 2e-3;

/// Part of node `i`'s translation (`k0` = 0) or rotation (`k0` = 3) increment in `du` (the
/// displacement increment, DOF order, node bases) normal to the hole axis at the node's
/// nearest axis point (its DOF basis axis for a node without a gap): the lateral motion (m)
/// and the bending rotation (rad) that the step caps limit. Not the basis components 1-2 or
/// 4-5: where the string has slid along a curved hole the hole tangent is off the basis
/// tangent (by 1 deg after 12 m of stretch in a 2.5 deg/30 m build), so axial sliding would
/// count as lateral motion and a twist increment of a rotating string (radians per step on a
/// string kilometres long) as bending.
fn increment_across(model: &Model, ev: &Evaluation, du: &[f64], i: usize, k0: usize) -> f64 {
    let q = &model.basis[i];
    let v = q * Vec3::new(du[model.dof(i, k0)], du[model.dof(i, k0 + 1)], du[model.dof(i, k0 + 2)]);
    let t = if model.mesh.nodes[i].has_gap {
        ev.axis[i].1
    } else {
        q.column(0).into_owned()
    };
    (v - t * t.dot(&v)).norm()
}

/// The scale of a Newton step and the caps that set it.
pub(crate) struct StepCap {
    /// Step scale in (0, 1].
    pub(crate) alpha: f64,
    /// Largest bending rotation over its cap.
    pub(crate) rot_ratio: f64,
    /// Node with the largest bending rotation.
    pub(crate) rot_node: usize,
    /// Largest lateral motion of a gap node over its cap.
    pub(crate) lat_ratio: f64,
    /// Node with the largest lateral motion.
    pub(crate) lat_node: usize,
}

/// Cap of the displacement increment `du` (DOF order, node bases) at the evaluation `ev`:
/// bending rotations to [`MAX_BENDING_ROTATION_STEP`], and the lateral motion of the gap nodes
/// `qidx` to [`MAX_LATERAL_STEP_CLEARANCES`] clearances (at least [`LATERAL_CAP_FLOOR_M`]):
/// the linearized gaps bound only the motion along each node's current normal, so a long step
/// can carry nodes around and through the wall.
pub(crate) fn step_cap(model: &Model, ev: &Evaluation, du: &[f64], qidx: &[usize]) -> StepCap {
    let (mut rot_ratio, mut rot_node): (f64, usize) = (0.0, 0);
    for i in 0..model.nodes() {
        let rot = increment_across(model, ev, du, i, 3);
        if rot / MAX_BENDING_ROTATION_STEP > rot_ratio {
            (rot_ratio, rot_node) = (rot / MAX_BENDING_ROTATION_STEP, i);
        }
    }
    let (mut lat_ratio, mut lat_node): (f64, usize) = (0.0, 0);
    for &i in qidx {
        let lat = increment_across(model, ev, du, i, 0);
        let r = lat / (MAX_LATERAL_STEP_CLEARANCES * ev.clearance[i].max(LATERAL_CAP_FLOOR_M));
        if r > lat_ratio {
            (lat_ratio, lat_node) = (r, i);
        }
    }
    let ratio = rot_ratio.max(lat_ratio);
    StepCap {
        alpha: if ratio > 1.0 { 1.0 / ratio } else { 1.0 },
        rot_ratio,
        rot_node,
        lat_ratio,
        lat_node,
    }
}
