//! The contacts of the interior-point Newton: which gaps it manages, and their linearization
//! at one evaluation (normals, equilibrium columns with the friction proportional to the
//! normal force, gaps, the whole wall of tight gaps), the contact forces of given multipliers
//! and the circle stiffness of the normal's rotation.

use super::step_caps::LATERAL_CAP_FLOOR_M;
use crate::geometry::Vec3;
use crate::models::fem::model::{Evaluation, Model, State, StiffnessSink};

/// Gap nodes with a clearance below this (m) get the whole wall as constraints of the
/// linearized contact problem ([`WALL_PLANES`] supporting planes of the hole circle, the
/// current wall's among them): the linearized gap bounds only the motion toward the current
/// wall, and the lateral step cap (two clearances, but at least [`LATERAL_CAP_FLOOR_M`] of
/// clearance) would let a stabilizer with a clearance of a millimetre move around or across
/// its hole and out through the wall by more than a clearance in one step. Wider gaps stay
/// within about a clearance of the wall under the cap.
pub const FAR_WALL_CLEARANCE_M: f64 = LATERAL_CAP_FLOOR_M;

/// Supporting planes of the hole circle per tight gap (see [`FAR_WALL_CLEARANCE_M`]); the
/// square leaves at most `1 / cos(pi / WALL_PLANES) - 1` of the clearance (41%) of penetration
/// (8 planes, 8%, needed more Newton iterations on the example wells, not fewer).
pub const WALL_PLANES: usize = 4;

/// Extra constraints of a tight gap besides its current wall's (see [`FAR_WALL_CLEARANCE_M`]).
pub(crate) const FAR_PLANES: usize = WALL_PLANES - 1;

/// The gap nodes of the interior-point Newton: the managed gaps (whose contact forces the
/// interior point decides) and the pins (zero-clearance gaps).
pub(crate) struct ContactSet {
    /// Whether each node's gap is managed.
    pub(crate) managed: Vec<bool>,
    /// Managed gap nodes, bit first: contact `j` is node `qidx[j]`.
    pub(crate) qidx: Vec<usize>,
    /// Zero-clearance gap nodes (pins), held by their vector multipliers outside the interior
    /// point.
    pub(crate) pins: Vec<usize>,
    /// Contact index of each node (`usize::MAX`: none).
    pub(crate) contact_at: Vec<usize>,
}

impl ContactSet {
    /// The managed gaps and pins of `model`.
    pub(crate) fn of(model: &Model) -> ContactSet {
        let nn = model.nodes();
        let managed = managed_gaps(model);
        let qidx: Vec<usize> = (0..nn).filter(|&i| managed[i]).collect();
        let pins: Vec<usize> = (0..nn)
            .filter(|&i| model.mesh.nodes[i].has_gap && !managed[i])
            .collect();
        let mut contact_at = vec![usize::MAX; nn];
        for (j, &i) in qidx.iter().enumerate() {
            contact_at[i] = j;
        }
        ContactSet {
            managed,
            qidx,
            pins,
            contact_at,
        }
    }
}

/// Gap nodes whose contact the interior point manages (`true`): every gap but the
/// zero-clearance ones (pins, held by vector multipliers).
pub(crate) fn managed_gaps(model: &Model) -> Vec<bool> {
    (0..model.nodes())
        .map(|i| {
            model.mesh.nodes[i].has_gap
                && model.clearance(i, model.md_ref[i]) > crate::models::fem::contact::gap::ZERO_CLEARANCE_M
        })
        .collect()
}

/// Where a gap node sits relative to the hole: outward unit normal (global; the previous one
/// when the node is on the axis), radial distance minus clearance, and the axis tangent.
pub(crate) struct GapGeometry {
    /// Outward unit normal (global).
    pub(crate) normal: Vec3,
    /// Radial distance minus clearance, m.
    pub(crate) gap: f64,
    /// Unit tangent of the hole axis.
    pub(crate) tangent: Vec3,
    /// Radial distance from the hole axis, m.
    pub(crate) radial: f64,
}

/// Gap geometry of node `i` from the axis point that the evaluation `ev` of `state` used
/// (its nearest axis point: no new search along the path).
fn gap_geometry(state: &State, ev: &Evaluation, i: usize) -> GapGeometry {
    let (position, tangent) = ev.axis[i];
    let d = state.x[i] - position;
    let d = d - tangent * tangent.dot(&d);
    let s = d.norm();
    let normal = if s > 1e-9 { d / s } else { state.normal[i] };
    GapGeometry {
        normal,
        gap: s - ev.clearance[i],
        tangent,
        radial: s,
    }
}

/// Node-basis normal and equilibrium column of a wall contact at node `i` with outward normal
/// `nrm` and hole tangent `tangent` (global): the force and moment on the node per newton of
/// normal force, `[n + f v^ ; f R_c n x v^]` (friction opposing the sliding velocity `v^` of the
/// contact point, proportional to the normal force).
fn wall_column(model: &Model, i: usize, nrm: Vec3, tangent: Vec3) -> (Vec3, [f64; 6]) {
    let q = &model.basis[i];
    let rc = model.mesh.nodes[i].contact_od_m / 2.0;
    let split = model.loads.motion().friction_split(rc);
    let (fv, fm) = if model.friction[i] > 0.0 && split.acts() {
        let vh = tangent * split.axial + tangent.cross(&nrm) * split.tangential;
        // a whirling string: the friction force without its lateral push, its torque whole
        let pushed = if model.whirls(i) { tangent * split.axial } else { vh };
        (pushed * model.friction[i], nrm.cross(&vh) * (model.friction[i] * rc))
    } else {
        (Vec3::zeros(), Vec3::zeros())
    };
    let et = q.transpose() * (nrm + fv);
    let em = q.transpose() * fm;
    (q.transpose() * nrm, [et.x, et.y, et.z, em.x, em.y, em.z])
}

/// The linearized contacts of the interior-point Newton's managed gaps at one evaluation:
/// contact `j < qidx.len()` is managed gap `j`'s current wall, the others the far-wall planes of
/// the tight gaps ([`ContactColumns::add_far_walls`]).
pub(crate) struct ContactColumns {
    /// Node-basis outward normal per contact.
    pub(crate) normals: Vec<Vec3>,
    /// Equilibrium column per contact (see [`wall_column`]).
    pub(crate) eq_cols: Vec<[f64; 6]>,
    /// Linearized gap per contact (negative: open), m.
    pub(crate) gaps0: Vec<f64>,
    /// Gap geometry per managed gap.
    pub(crate) geometry: Vec<GapGeometry>,
    /// Node of each contact.
    pub(crate) node: Vec<usize>,
    /// First far-wall contact of each node ([`FAR_PLANES`] in a row; `usize::MAX`: none).
    pub(crate) far_at: Vec<usize>,
}

/// Contact normals, equilibrium columns and gaps of the managed gap nodes `qidx` at the
/// evaluation `ev` of `state` (whose contact normals it updates).
pub(crate) fn contact_columns(model: &Model, state: &mut State, ev: &Evaluation, qidx: &[usize]) -> ContactColumns {
    let m = qidx.len();
    let mut cc = ContactColumns {
        normals: Vec::with_capacity(m),
        eq_cols: Vec::with_capacity(m),
        gaps0: Vec::with_capacity(m),
        geometry: Vec::with_capacity(m),
        node: qidx.to_vec(),
        far_at: vec![usize::MAX; model.nodes()],
    };
    for &i in qidx {
        let g = gap_geometry(state, ev, i);
        state.normal[i] = g.normal;
        let (nl, col) = wall_column(model, i, g.normal, g.tangent);
        cc.normals.push(nl);
        cc.eq_cols.push(col);
        cc.gaps0.push(g.gap);
        cc.geometry.push(g);
    }
    cc
}

impl ContactColumns {
    /// Number of contacts (managed gaps and far-wall planes).
    pub(crate) fn len(&self) -> usize {
        self.normals.len()
    }

    /// Add the rest of the wall of the tight managed gaps `qidx` (see [`FAR_WALL_CLEARANCE_M`])
    /// at the evaluation `ev`: the supporting planes of the hole circle with outward normals
    /// `e = n cos(a) + b sin(a)`, `b = t x n`, at the angles `a = 2 pi k / WALL_PLANES` from the
    /// current normal: `e . (radial n + du) <= clearance`.
    pub(crate) fn add_far_walls(&mut self, model: &Model, ev: &Evaluation, qidx: &[usize]) {
        let m = qidx.len();
        let far: Vec<usize> = (0..m)
            .filter(|&j| ev.clearance[qidx[j]] < FAR_WALL_CLEARANCE_M)
            .collect();
        for (k, &j) in far.iter().enumerate() {
            let i = qidx[j];
            let g = &self.geometry[j];
            let b = g.tangent.cross(&g.normal);
            let eo = ev.clearance[i];
            for k in 1..WALL_PLANES {
                let a = std::f64::consts::TAU * k as f64 / WALL_PLANES as f64;
                let (nrm, gap) = (g.normal * a.cos() + b * a.sin(), g.radial * a.cos() - eo);
                let (nl, col) = wall_column(model, i, nrm, g.tangent);
                self.normals.push(nl);
                self.eq_cols.push(col);
                self.gaps0.push(gap);
                self.node.push(i);
            }
            self.far_at[i] = m + FAR_PLANES * k;
        }
    }

    /// The contacts of node `node` (its managed gap's index in `contact_at`, then its far-wall
    /// planes), in that order.
    pub(crate) fn of_node(&self, contact_at: &[usize], node: usize) -> impl Iterator<Item = usize> {
        let first = self.far_at[node];
        let extra = if first == usize::MAX {
            0..0
        } else {
            first..first + FAR_PLANES
        };
        std::iter::once(contact_at[node])
            .chain(extra)
            .filter(|&j| j != usize::MAX)
    }

    /// Normal force on managed gap `j` at node `i` from the contact forces `r_f` (N): its
    /// current wall's plus its far-wall planes' (a node that crossed to the far wall carries
    /// the far multiplier into the next linearization, whose normal then points at that wall).
    pub(crate) fn node_force(&self, r_f: &[f64], j: usize, i: usize) -> f64 {
        match self.far_at[i] {
            usize::MAX => r_f[j],
            f => r_f[j] + r_f[f..f + FAR_PLANES].iter().sum::<f64>(),
        }
    }
}

/// Residual `r0` (constrained entries zeroed) plus the contact forces of the multipliers
/// `lambda` (N, per node) along the equilibrium columns `eq_cols` of the managed gaps `qidx`.
pub(crate) fn contact_residual(
    model: &Model,
    r0: &[f64],
    qidx: &[usize],
    eq_cols: &[[f64; 6]],
    lambda: &[f64],
    constrained: &[usize],
) -> Vec<f64> {
    let mut rt = r0.to_vec();
    for (j, &i) in qidx.iter().enumerate() {
        for k in 0..6 {
            rt[model.dof(i, k)] += lambda[i] * eq_cols[j][k];
        }
    }
    for &d in constrained {
        rt[d] = 0.0;
    }
    rt
}

/// Add the circle stiffness of the managed gaps' contact forces `lambda` (N, per node): the
/// rotation of the normal `n` with the lateral motion, `(R / s)(I - t t^T - n n^T)`.
pub(crate) fn add_circle_stiffness(
    model: &Model,
    sink: &mut dyn StiffnessSink,
    qidx: &[usize],
    geometry: &[GapGeometry],
    lambda: &[f64],
) {
    for (j, &i) in qidx.iter().enumerate() {
        let (g, lam) = (&geometry[j], lambda[i]);
        if lam > 0.0 && g.radial > 1e-9 {
            let (t, nrm) = (g.tangent, g.normal);
            let kc = (nalgebra::Matrix3::identity() - t * t.transpose() - nrm * nrm.transpose()) * (lam / g.radial);
            let q = &model.basis[i];
            let kl = q.transpose() * kc * q;
            let dofs: [usize; 3] = std::array::from_fn(|k| model.dof(i, k));
            sink.add_block(&dofs, kl.transpose().as_slice(), 3);
        }
    }
}
