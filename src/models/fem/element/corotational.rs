//! Co-rotational kinematics of the 3D beam (Crisfield 1990; Battini & Pacoste 2002).
//!
//! Each element carries a rigid frame `R_r = [r1 r2 r3]` that follows its chord: `r1` along
//! `x_B - x_A`, `r2`, `r3` from the mean of the nodal triads' second axes made orthogonal to
//! `r1`. The local element of [`super::beam`] acts on the deformation in that frame:
//! `u = l - l0`, `theta_A = log(R_r^T Lambda_A)`, `theta_B = log(R_r^T Lambda_B)`.
//! The variation `dp_local = B dp_global` uses the spin of the element frame `G^T`
//! (derived in the module tests by finite differences) and `T_s^-1`. The internal force
//! `B^T f_local` is exact (it is the gradient of the strain energy). Two tangents: the
//! consistent one, `B^T K_local B + (dB^T/dp) f_local` with the second term in closed form
//! ([`element_response`] with `consistent = true`; needed under torque), and the approximate
//! `B^T K_local B + N/l (I - r1 r1^T)` on the translations, which omits the moments times the
//! frame variations (relative size ~ theta), so Newton converges slightly less than
//! quadratically but to the exact solution.
//!
//! Global DOFs per node: 3 displacements and 3 spins, both expressed in the node's fixed basis
//! `Q` (columns: the hole tangent and two normals at the node's reference position).

use super::beam::{local_response, BeamSection};
use super::rotation::{log_so3, skew, tangent_inverse};
use crate::geometry::Vec3;
use nalgebra::{Matrix3, SMatrix, SVector};

/// 12-vector (element global DOFs, node bases).
pub type Vec12 = SVector<f64, 12>;
/// 12x12 matrix.
pub type Mat12 = SMatrix<f64, 12, 12>;

/// Current state of an element's two nodes.
#[derive(Debug, Clone, Copy)]
pub struct ElementState<'a> {
    /// Position of node A (the upper node, away from the bit, in [`crate::models::fem::model::Model`]'s
    /// assembly: the chord A -> B points down the hole), m.
    pub x_a: &'a Vec3,
    /// Position of node B, m.
    pub x_b: &'a Vec3,
    /// Material triad of node A (columns; first = section normal / string axis).
    pub lam_a: &'a Matrix3<f64>,
    /// Material triad of node B.
    pub lam_b: &'a Matrix3<f64>,
    /// DOF basis of node A.
    pub q_a: &'a Matrix3<f64>,
    /// DOF basis of node B.
    pub q_b: &'a Matrix3<f64>,
}

/// Element response in node-basis global DOFs.
#[derive(Debug, Clone)]
pub struct ElementResponse {
    /// Internal force `dU/dp` (forces N, moments N.m).
    pub force: Vec12,
    /// Tangent stiffness (approximate, see module docs).
    pub tangent: Mat12,
    /// Axial force N, tension positive.
    pub axial_force: f64,
    /// Local end moments `[mA1, mA2, mA3, mB1, mB2, mB3]` in the element frame, N.m
    /// (index 0/3: torque; the others bending).
    pub local_moments: [f64; 6],
    /// Element frame (columns r1, r2, r3).
    pub frame: Matrix3<f64>,
    /// Current chord length, m.
    pub length: f64,
}

/// Element response without the tangent: what the evaluation keeps per element.
#[derive(Debug, Clone)]
pub struct ElementForces {
    /// Internal force `dU/dp` (forces N, moments N.m), node-basis DOFs `[uA, wA, uB, wB]`.
    pub force: Vec12,
    /// Axial force N, tension positive.
    pub axial_force: f64,
    /// Local end moments `[mA1, mA2, mA3, mB1, mB2, mB3]` in the element frame, N.m
    /// (index 0/3: torque; the others bending).
    pub local_moments: [f64; 6],
    /// Element frame (columns r1, r2, r3).
    pub frame: Matrix3<f64>,
    /// Current chord length, m.
    pub length: f64,
}

/// Element frame and local deformations, shared by the force and its finite-difference test.
struct Kinematics {
    rr: Matrix3<f64>,
    ln: f64,
    p: [f64; 7],
    th_a: Vec3,
    th_b: Vec3,
    q_loc: Vec3,
    qa_loc: Vec3,
    qb_loc: Vec3,
    /// `T_s^-1(theta_A)`, `T_s^-1(theta_B)` (used by `B` and by the geometric tangent).
    ti_a: Matrix3<f64>,
    ti_b: Matrix3<f64>,
}

#[inline(always)]
fn kinematics(st: &ElementState, l0: f64) -> Kinematics {
    let d = st.x_b - st.x_a;
    let ln = d.norm();
    let r1 = d / ln;
    let qa = st.lam_a.column(1).into_owned();
    let qb = st.lam_b.column(1).into_owned();
    let q = (qa + qb) * 0.5;
    let r3 = r1.cross(&q).normalize();
    let r2 = r3.cross(&r1);
    let rr = Matrix3::from_columns(&[r1, r2, r3]);
    let th_a = log_so3(&(rr.transpose() * st.lam_a));
    let th_b = log_so3(&(rr.transpose() * st.lam_b));
    let p = [ln - l0, th_a.x, th_a.y, th_a.z, th_b.x, th_b.y, th_b.z];
    Kinematics {
        rr,
        ln,
        p,
        th_a,
        th_b,
        q_loc: rr.transpose() * q,
        qa_loc: rr.transpose() * qa,
        qb_loc: rr.transpose() * qb,
        ti_a: tangent_inverse(&th_a),
        ti_b: tangent_inverse(&th_b),
    }
}

/// Strain energy of the element in the state `st` (J), for tests.
pub fn strain_energy(st: &ElementState, s: &BeamSection) -> f64 {
    let k = kinematics(st, s.l0);
    // closed form of the local energy (f.p/2 is not exact with the geometric term)
    let [u, ta1, ta2, ta3, tb1, tb2, tb3] = k.p;
    let l0 = s.l0;
    let eps =
        u / l0 + (2.0 * ta2 * ta2 - ta2 * tb2 + 2.0 * tb2 * tb2 + 2.0 * ta3 * ta3 - ta3 * tb3 + 2.0 * tb3 * tb3) / 30.0;
    0.5 * s.ea * l0 * eps * eps
        + s.ei / l0
            * (2.0 * ta2 * ta2
                + 2.0 * ta2 * tb2
                + 2.0 * tb2 * tb2
                + 2.0 * ta3 * ta3
                + 2.0 * ta3 * tb3
                + 2.0 * tb3 * tb3)
        + 0.5 * s.gj / l0 * (tb1 - ta1).powi(2)
}

/// The matrix `B = d p_local / d p_global` (7 x 12, node-basis global DOFs) and the kinematics.
///
/// `B = [e1-row; T_s^-1(theta_A) P_A; T_s^-1(theta_B) P_B] M` with `P_A = [0 I 0 0] - G^T`,
/// `P_B = [0 0 0 I] - G^T` (`G^T` the spin of the element frame, local components) and
/// `M = diag(R_r^T Q_A, R_r^T Q_A, R_r^T Q_B, R_r^T Q_B)`. Formed over the structural
/// non-zeros only (`G^T` has 10 of 36, `P_A`/`P_B` zero columns 0, 6 and 11 or 5), each
/// entry summed in the same order as the dense products (`b_matrix_dense` in the tests), so
/// the result is bit for bit the dense one: a product with an exact zero adds nothing.
fn b_matrix(st: &ElementState, l0: f64) -> (SMatrix<f64, 7, 12>, Kinematics) {
    let mut b = SMatrix::<f64, 7, 12>::zeros();
    let k = b_matrix_into(st, l0, &mut b);
    (b, k)
}

/// [`b_matrix`] written into `b` (every entry set), the kinematics returned: no 7 x 12
/// temporary moved around.
#[inline(always)]
fn b_matrix_into(st: &ElementState, l0: f64, b: &mut SMatrix<f64, 7, 12>) -> Kinematics {
    let k = kinematics(st, l0);
    let rr = k.rr;
    let ln = k.ln;
    let ma = rr.transpose() * st.q_a;
    let mb = rr.transpose() * st.q_b;
    let q2 = k.q_loc.y;
    let eta = k.q_loc.x / q2;
    let (e11, e12) = (k.qa_loc.x / q2, k.qa_loc.y / q2);
    let (e21, e22) = (k.qb_loc.x / q2, k.qb_loc.y / q2);
    // the non-zeros of -G^T (entries of P_A and P_B off their identity blocks)
    let g02 = -(eta / ln);
    let g03 = -(e12 / 2.0);
    let g04 = -(-e11 / 2.0);
    let g08 = -(-eta / ln);
    let g09 = -(e22 / 2.0);
    let g0a = -(-e21 / 2.0);
    let g12 = -(1.0 / ln);
    let g18 = -(-1.0 / ln);
    let g21 = -(-1.0 / ln);
    let g27 = -(1.0 / ln);
    // T P (3 x 12) for one end: `a3`/`a4`/`a5` are the P entries of the identity block
    // columns 3..6 (A end) or 9..12 (B end); columns with a zero P column stay zero
    let tp = |ti: &Matrix3<f64>, end_b: bool| -> [[f64; 12]; 3] {
        let mut t = [[0.0; 12]; 3];
        for (i, row) in t.iter_mut().enumerate() {
            let (c0, c1, c2) = (ti[(i, 0)], ti[(i, 1)], ti[(i, 2)]);
            row[1] = c2 * g21;
            row[2] = c0 * g02 + c1 * g12;
            row[7] = c2 * g27;
            row[8] = c0 * g08 + c1 * g18;
            if end_b {
                row[3] = c0 * g03;
                row[4] = c0 * g04;
                row[9] = c0 * (g09 + 1.0);
                row[10] = c0 * g0a + c1;
                row[11] = c2;
            } else {
                row[3] = c0 * (g03 + 1.0);
                row[4] = c0 * g04 + c1;
                row[5] = c2;
                row[9] = c0 * g09;
                row[10] = c0 * g0a;
            }
        }
        t
    };
    let ta = tp(&k.ti_a, false);
    let tb = tp(&k.ti_b, true);
    // du = r1 . (duB - duA): the first row of M for each end
    for c in 0..3 {
        b[(0, c)] = 0.0 + -ma[(0, c)];
        b[(0, 3 + c)] = 0.0;
        b[(0, 6 + c)] = 0.0 + mb[(0, c)];
        b[(0, 9 + c)] = 0.0;
    }
    // rows (T P) M, block by block over the rows of M that meet a non-zero of T P (the
    // zero columns: 0, 6, 11 at the A end, 0, 5, 6 at the B end)
    for i in 0..3 {
        let (a, bb) = (&ta[i], &tb[i]);
        for c in 0..3 {
            b[(1 + i, c)] = 0.0 + a[1] * ma[(1, c)] + a[2] * ma[(2, c)];
            b[(1 + i, 3 + c)] = 0.0 + a[3] * ma[(0, c)] + a[4] * ma[(1, c)] + a[5] * ma[(2, c)];
            b[(1 + i, 6 + c)] = 0.0 + a[7] * mb[(1, c)] + a[8] * mb[(2, c)];
            b[(1 + i, 9 + c)] = 0.0 + a[9] * mb[(0, c)] + a[10] * mb[(1, c)];
            b[(4 + i, c)] = 0.0 + bb[1] * ma[(1, c)] + bb[2] * ma[(2, c)];
            b[(4 + i, 3 + c)] = 0.0 + bb[3] * ma[(0, c)] + bb[4] * ma[(1, c)];
            b[(4 + i, 6 + c)] = 0.0 + bb[7] * mb[(1, c)] + bb[8] * mb[(2, c)];
            b[(4 + i, 9 + c)] = 0.0 + bb[9] * mb[(0, c)] + bb[10] * mb[(1, c)] + bb[11] * mb[(2, c)];
        }
    }
    k
}

/// Internal force and tangent of the element in node-basis DOFs `[uA, wA, uB, wB]`.
///
/// `consistent = true` adds the full geometric part of the tangent, `(dB^T/dp) f_local`
/// (moments and torque times the variation of the co-rotational map), in closed form
/// (`geometric_tangent`; its finite-difference oracle is [`geometric_tangent_by_differences`]);
/// otherwise only its axial-force part `N/l (I - r1 r1^T)`.
/// The consistent form matters when the string carries torque (rotary friction).
pub fn element_response(st: &ElementState, s: &BeamSection, with_geometric: bool, consistent: bool) -> ElementResponse {
    let mut tangent = Mat12::zeros();
    let f = element_response_into(st, s, with_geometric, consistent, &mut tangent);
    ElementResponse {
        force: f.force,
        tangent,
        axial_force: f.axial_force,
        local_moments: f.local_moments,
        frame: f.frame,
        length: f.length,
    }
}

/// [`element_response`] with the tangent written into `tangent` (overwritten) and the rest
/// returned: the assembly keeps the forces per element but not the 12x12.
pub fn element_response_into(
    st: &ElementState,
    s: &BeamSection,
    with_geometric: bool,
    consistent: bool,
    tangent: &mut Mat12,
) -> ElementForces {
    response(st, s, with_geometric, consistent, Some(tangent))
}

/// Internal force only (the tangent is left zero): for residual evaluations in line searches.
pub fn element_force(st: &ElementState, s: &BeamSection, with_geometric: bool) -> ElementResponse {
    let f = element_forces(st, s, with_geometric);
    ElementResponse {
        force: f.force,
        tangent: Mat12::zeros(),
        axial_force: f.axial_force,
        local_moments: f.local_moments,
        frame: f.frame,
        length: f.length,
    }
}

/// Internal force and section results only (no tangent).
pub fn element_forces(st: &ElementState, s: &BeamSection, with_geometric: bool) -> ElementForces {
    response(st, s, with_geometric, false, None)
}

/// Local DOFs coupled by the local tangent: the axial force and bending (elongation and the
/// bending rotations) and the twist; [`super::beam::local_response`] couples no DOF of one group
/// to one of the other (the axial strain does not depend on the twist).
const AXIAL_BENDING: [usize; 5] = [0, 2, 3, 5, 6];
const TWIST: [usize; 2] = [1, 4];

/// `B^T K B` for a symmetric 7x7 `K`, written into `out`: only the upper triangle of the (symmetric) result is
/// formed and mirrored (hand-written: about 2/3 of the multiplications of the plain product).
/// `K B` runs over the non-zeros of `K` only ([`AXIAL_BENDING`], [`TWIST`]), summed in the
/// dense product's order, so the result is bit for bit that of `(K * B)`.
#[inline(always)]
fn congruence(b: &SMatrix<f64, 7, 12>, kl: &SMatrix<f64, 7, 7>, out: &mut Mat12) {
    debug_assert!(AXIAL_BENDING
        .iter()
        .all(|&i| TWIST.iter().all(|&r| kl[(i, r)] == 0.0 && kl[(r, i)] == 0.0)));
    let mut c = SMatrix::<f64, 7, 12>::zeros();
    let [a0, a1, a2, a3, a4] = AXIAL_BENDING;
    let [t0, t1] = TWIST;
    for j in 0..12 {
        let bj = b.column(j);
        for i in AXIAL_BENDING {
            c[(i, j)] = kl[(i, a0)] * bj[a0]
                + kl[(i, a1)] * bj[a1]
                + kl[(i, a2)] * bj[a2]
                + kl[(i, a3)] * bj[a3]
                + kl[(i, a4)] * bj[a4];
        }
        for i in TWIST {
            c[(i, j)] = kl[(i, t0)] * bj[t0] + kl[(i, t1)] * bj[t1];
        }
    }
    // B^T C column by column (each entry summed over r in order, as the triangular loop of
    // the first version did; the full product vectorizes where the triangle did not), then
    // the upper triangle mirrored
    let bt = b.transpose();
    for j in 0..12 {
        let mut col = [0.0; 12];
        for r in 0..7 {
            let crj = c[(r, j)];
            for (x, &v) in col.iter_mut().zip(bt.column(r).iter()) {
                *x += v * crj;
            }
        }
        for (i, &v) in col.iter().enumerate().take(j + 1) {
            out[(i, j)] = v;
            out[(j, i)] = v;
        }
    }
}

/// The element's forces and section results, and its tangent into `tangent_out` when given
/// (see [`element_response`]). Compiled also for AVX2 and selected at run time where the
/// processor has it (the same operations in the same order: the same results bit for bit).
#[multiversion::multiversion(targets("x86_64+avx2+fma"))]
fn response(
    st: &ElementState,
    s: &BeamSection,
    with_geometric: bool,
    consistent: bool,
    tangent_out: Option<&mut Mat12>,
) -> ElementForces {
    let mut b = SMatrix::<f64, 7, 12>::zeros();
    let k = b_matrix_into(st, s.l0, &mut b);
    let loc = local_response(s, &k.p, with_geometric);
    let rr = k.rr;
    let ln = k.ln;
    let fl = SVector::<f64, 7>::from_row_slice(&loc.force);
    let force = b.transpose() * fl;
    let n = loc.axial_force;
    let forces = ElementForces {
        force,
        axial_force: n,
        local_moments: [
            loc.force[1],
            loc.force[2],
            loc.force[3],
            loc.force[4],
            loc.force[5],
            loc.force[6],
        ],
        frame: rr,
        length: ln,
    };
    let Some(tangent) = tangent_out else {
        return forces;
    };
    let kl = SMatrix::<f64, 7, 7>::from_fn(|i, j| loc.tangent[i][j]);
    congruence(&b, &kl, tangent);
    if consistent {
        add_geometric_tangent(st, &k, &fl, tangent);
        return forces;
    }
    // Geometric term of the elongation: N/l (I - r1 r1^T) on the translations (node bases).
    let r1 = rr.column(0).into_owned();
    let proj = (Matrix3::identity() - r1 * r1.transpose()) * (n / ln);
    let blocks = [(0usize, st.q_a), (6usize, st.q_b)];
    for &(oi, qi) in &blocks {
        for &(oj, qj) in &blocks {
            let sign = if oi == oj { 1.0 } else { -1.0 };
            let kb = qi.transpose() * proj * qj * sign;
            for r in 0..3 {
                for c in 0..3 {
                    tangent[(oi + r, oj + c)] += kb[(r, c)];
                }
            }
        }
    }
    forces
}

/// `d(T^-T(theta) m)/d(theta)` for the inverse tangent operator of [`tangent_inverse`]
/// (`T^-T m = m + theta x m / 2 + eta(a) theta x (theta x m)`, `a = |theta|`).
#[inline(always)]
fn d_tinv_t_m(theta: &Vec3, m: &Vec3) -> Matrix3<f64> {
    let a = theta.norm();
    // eta(a) = (1 - (a/2) cot(a/2)) / a^2 and mu = eta'(a) / a, by series for small a
    let (eta, mu) = if a < 0.05 {
        let a2 = a * a;
        (1.0 / 12.0 + a2 / 720.0 + a2 * a2 / 30240.0, 1.0 / 360.0 + a2 / 7560.0)
    } else {
        let h = 1.0 - 0.5 * a / (0.5 * a).tan();
        let s2 = (0.5 * a).sin().powi(2);
        let dh = -0.5 / (0.5 * a).tan() + a / (4.0 * s2);
        (h / (a * a), dh / a.powi(3) - 2.0 * h / a.powi(4))
    };
    let tm = theta.dot(m);
    let u = theta * tm - m * (a * a);
    -skew(m) * 0.5
        + u * theta.transpose() * mu
        + (Matrix3::identity() * tm + theta * m.transpose() - m * theta.transpose() * 2.0) * eta
}

/// Analytic geometric part of the consistent tangent, `(dB^T/dp_global) f_local` at fixed
/// `f_local` (node-basis DOFs): the derivative of the internal force `B^T f_local` through the
/// element frame, the inverse tangent operators and the node triads (Crisfield 1990;
/// Battini & Pacoste 2002, here for the frame whose second axis follows the mean of the nodal
/// second axes). Derived in spatial components, with DOF order `[xA, wA, xB, wB]`:
/// `f . dp = N r1 . dd + vA . (wA - w_r) + vB . (wB - w_r)`, `dd = dxB - dxA`,
/// `v = R_r T^-T m`, frame spin `w_r = Omega dp = r1 x dd / l + r1 E`,
/// `E = e . dp = [w . dq - (q1 / l) w . dd] / c^2` (`q` the mean second axis, `w = r1 x q`,
/// `c = |w|`, `q1 = q . r1`); each factor is then varied in turn.
///
/// Hand-optimized (the largest single cost of a whole-string solve otherwise): the 12x12 is kept
/// as 4x4 spatial 3x3 blocks; the chord map `ld = [-I, 0, I, 0]`, the node-spin maps and the
/// `dq` map are block-sparse, so their products are formed block by block; `Omega` is applied
/// as its 3x3 pattern plus the rank-one part `r1 e^T` (a matrix-vector product and an outer
/// product instead of a 3x3 product); the rank-one terms of the variation of `E` and of `e`
/// are gathered into one `e z^T` and one chord-row term before they touch the blocks; the
/// node bases are applied once at the end. The dense 3 x 12 form of the same derivation
/// (`geometric_tangent_dense` in the tests) and central differences
/// ([`geometric_tangent_by_differences`]) check it.
#[cfg(test)]
fn geometric_tangent(st: &ElementState, k: &Kinematics, fl: &SVector<f64, 7>) -> Mat12 {
    let mut out = Mat12::zeros();
    add_geometric_tangent(st, k, fl, &mut out);
    out
}

/// `out += (dB^T/dp_global) f_local` (see `geometric_tangent`, its test form, for the
/// derivation), each entry added once (no 12x12 temporary).
#[inline(always)]
fn add_geometric_tangent(st: &ElementState, k: &Kinematics, fl: &SVector<f64, 7>, out: &mut Mat12) {
    type Blocks = [[Matrix3<f64>; 4]; 4];
    let rr = k.rr;
    let l = k.ln;
    let r1: Vec3 = rr.column(0).into_owned();
    let qa: Vec3 = st.lam_a.column(1).into_owned();
    let qb: Vec3 = st.lam_b.column(1).into_owned();
    let q = (qa + qb) * 0.5;
    let q1 = q.dot(&r1);
    let w = r1.cross(&q);
    let c2 = w.dot(&w);
    let eye = Matrix3::identity();
    let p = eye - r1 * r1.transpose();
    let s1 = skew(&r1);
    let n = fl[0];
    let m_a = Vec3::new(fl[1], fl[2], fl[3]);
    let m_b = Vec3::new(fl[4], fl[5], fl[6]);
    let (sqa, sqb) = (skew(&qa) * 0.5, skew(&qb) * 0.5);
    // e = [lq^T w - (q1/l) ld^T w] / c^2 by blocks (lq^T u = [0, S(qa) u/2, 0, S(qb) u/2])
    let e0 = w * (q1 / (l * c2));
    let eb = [e0, sqa * w / c2, -e0, sqb * w / c2];
    let ti_a = k.ti_a;
    let ti_b = k.ti_b;
    let v_a = rr * (ti_a.transpose() * m_a);
    let v_b = rr * (ti_b.transpose() * m_b);
    let v = v_a + v_b;
    // X = R_r (d(T^-T m)/d theta) T^-1 R_r^T: moments times the variation of T^-T
    let x_a = rr * (d_tinv_t_m(&k.th_a, &m_a) * ti_a) * rr.transpose();
    let x_b = rr * (d_tinv_t_m(&k.th_b, &m_b) * ti_b) * rr.transpose();
    let mut kb: Blocks = [[Matrix3::zeros(); 4]; 4];
    // ld^T m ld: `m` on the (xA, xA) and (xB, xB) blocks, `-m` on the (xA, xB) pair
    let chord = |kb: &mut Blocks, m: &Matrix3<f64>| {
        kb[0][0] += m;
        kb[2][2] += m;
        kb[0][2] -= m;
        kb[2][0] -= m;
    };
    // 1. axial force times the chord rotation, plus the frame-spin terms
    //    Omega^T S(v) ... of item 4 that have the chord pattern
    let y = x_a + x_b + skew(&v);
    let chord_sum =
        p * (n / l) + (s1.transpose() * y * s1) / (l * l) - (skew(&v) * p - v.cross(&r1) * r1.transpose()) / (l * l);
    chord(&mut kb, &chord_sum);
    // 2.-3. (wA - w_r)^T X_A (wA - w_r) + (B) - wA^T S(vA) w_r - wB^T S(vB) w_r, with
    // Omega_j = D_j + r1 e_j^T, D = [-S(r1)/l, 0, S(r1)/l, 0]
    kb[1][1] += x_a;
    kb[3][3] += x_b;
    for (row, x) in [(1usize, x_a), (3usize, x_b)] {
        let v_node = if row == 1 { v_a } else { v_b };
        let xs = x + skew(&v_node);
        let xs_d = xs * s1 / l;
        let xs_r1 = xs * r1;
        let xt_r1 = x.transpose() * r1;
        let xt_d = s1.transpose() * x / l; // D_0^T X = -this, D_2^T X = this
        for j in 0..4 {
            // row block: -(X + S(v)) Omega_j
            kb[row][j] -= xs_r1 * eb[j].transpose();
            // column block: -(X^T Omega_j)^T = -Omega_j^T X
            kb[j][row] -= eb[j] * xt_r1.transpose();
        }
        kb[row][0] += xs_d;
        kb[row][2] -= xs_d;
        kb[0][row] += xt_d;
        kb[2][row] -= xt_d;
    }
    // 4. -V . (variation of the frame-spin map) dp: the block part of -(vr/c^2) dnum,
    // dnum = L lw with L = [(q1/l) I, S(qa)/2, -(q1/l) I, S(qb)/2] (block column) and the
    // variation of w, lw = [-S(q) P/l... ] (block row), plus w . (variation of dq)
    let vr = v.dot(&r1);
    let f = vr / c2;
    let sqp = skew(&q) * p / l;
    let lw = [sqp, -(s1 * sqa), -sqp, -(s1 * sqb)];
    for j in 0..4 {
        let t = lw[j] * (f * q1 / l);
        kb[0][j] -= t;
        kb[2][j] += t;
        kb[1][j] -= sqa * lw[j] * f;
        kb[3][j] -= sqb * lw[j] * f;
    }
    kb[1][1] -= (qa * w.transpose() - eye * w.dot(&qa)) * (0.5 * f);
    kb[3][3] -= (qb * w.transpose() - eye * w.dot(&qb)) * (0.5 * f);
    // rank-one terms, gathered:
    //   Omega^T Y Omega:  ld^T a e^T + e b^T ld + (r1 . Y r1) e e^T,
    //                     a = S(r1)^T Y r1 / l, b = S(r1)^T Y^T r1 / l
    //   -(vr/c^2) dnum:   ld^T w z2^T, z2 = (vr / (c^2 l)) (lq1 - (q1/l) ld^T r1)
    //   nvec lc^T vr/c^4: e lc^T (vr/c^2)
    //   -e (ld^T P v / l)^T
    // = e z1^T + ld^T H, H = a e^T + w z2^T (3 x 12)
    let a = s1.transpose() * (y * r1) / l;
    let b = s1.transpose() * (y.transpose() * r1) / l;
    let c0 = r1.dot(&(y * r1));
    let pq = p * q / l;
    let pv = p * v / l;
    // lq1 = lq^T r1 + ld^T P q / l, lc = 2 (lq^T q - q1 lq1)
    let lq1 = [-pq, sqa * r1, pq, sqb * r1];
    let lc = [
        pq * (2.0 * q1),
        (sqa * q - sqa * r1 * q1) * 2.0,
        pq * (-2.0 * q1),
        (sqb * q - sqb * r1 * q1) * 2.0,
    ];
    let g2 = vr / (c2 * l);
    let r1q = r1 * (q1 / l);
    let z2 = [(lq1[0] + r1q) * g2, lq1[1] * g2, (lq1[2] - r1q) * g2, lq1[3] * g2];
    let z1 = [
        -b + eb[0] * c0 + lc[0] * f + pv,
        eb[1] * c0 + lc[1] * f,
        b + eb[2] * c0 + lc[2] * f - pv,
        eb[3] * c0 + lc[3] * f,
    ];
    for i in 0..4 {
        for j in 0..4 {
            kb[i][j] += eb[i] * z1[j].transpose();
        }
    }
    for j in 0..4 {
        let h = a * eb[j].transpose() + w * z2[j].transpose();
        kb[0][j] -= h;
        kb[2][j] += h;
    }
    // to node bases: K = Qblk^T K_s Qblk
    let qs = [st.q_a, st.q_a, st.q_b, st.q_b];
    for (bi, row) in kb.iter().enumerate() {
        for pair in [0usize, 2] {
            add_congruence_pair(qs[bi], qs[pair], &row[pair], &row[pair + 1], out, 3 * bi, 3 * pair);
        }
    }
}

/// `out[r0.., c0..] += Q_r^T K_0 Q_c` and `out[r0.., c0 + 3..] += Q_r^T K_1 Q_c`: two 3x3
/// blocks with the same bases, computed side by side (two lanes; vectorizes), each entry
/// summed in the order of nalgebra's `(Q_r^T * K) * Q_c` (so bit for bit that product).
#[inline(always)]
fn add_congruence_pair(
    q_r: &Matrix3<f64>,
    q_c: &Matrix3<f64>,
    k0: &Matrix3<f64>,
    k1: &Matrix3<f64>,
    out: &mut Mat12,
    r0: usize,
    c0: usize,
) {
    // T = Q_r^T K (lanes: K_0, K_1); T[i][j] = sum_r Q_r[r][i] K[r][j]
    let mut t = [[[0.0f64; 2]; 3]; 3];
    for i in 0..3 {
        for j in 0..3 {
            let (a0, a1, a2) = (q_r[(0, i)], q_r[(1, i)], q_r[(2, i)]);
            t[i][j] = [
                a0 * k0[(0, j)] + a1 * k0[(1, j)] + a2 * k0[(2, j)],
                a0 * k1[(0, j)] + a1 * k1[(1, j)] + a2 * k1[(2, j)],
            ];
        }
    }
    for i in 0..3 {
        for j in 0..3 {
            let (b0, b1, b2) = (q_c[(0, j)], q_c[(1, j)], q_c[(2, j)]);
            let r = [
                t[i][0][0] * b0 + t[i][1][0] * b1 + t[i][2][0] * b2,
                t[i][0][1] * b0 + t[i][1][1] * b1 + t[i][2][1] * b2,
            ];
            out[(r0 + i, c0 + j)] += r[0];
            out[(r0 + i, c0 + 3 + j)] += r[1];
        }
    }
}

/// Node positions and triads of `st` moved by `h` along global DOF `j` (0..12, node bases):
/// translations added, spins applied as `exp(Q e) Lambda`.
pub fn perturbed(st: &ElementState, j: usize, h: f64) -> (Vec3, Vec3, Matrix3<f64>, Matrix3<f64>) {
    let (mut xa, mut xb, mut la, mut lb) = (*st.x_a, *st.x_b, *st.lam_a, *st.lam_b);
    let mut e = Vec3::zeros();
    e[j % 3] = h;
    match j / 3 {
        0 => xa += st.q_a * e,
        1 => la = super::rotation::exp_so3(&(st.q_a * e)) * la,
        2 => xb += st.q_b * e,
        _ => lb = super::rotation::exp_so3(&(st.q_b * e)) * lb,
    }
    (xa, xb, la, lb)
}

/// `(dB^T/dp_global) f_local` by central differences (f_local fixed): 24 evaluations of `B`.
/// The test oracle of the analytic `geometric_tangent`.
pub fn geometric_tangent_by_differences(st: &ElementState, l0: f64, fl: &SVector<f64, 7>) -> Mat12 {
    let mut kg = Mat12::zeros();
    let h = 1e-7;
    for j in 0..12 {
        let mut col = Vec12::zeros();
        for (sign, w) in [(1.0, 0.5 / h), (-1.0, -0.5 / h)] {
            let (xa, xb, la, lb) = perturbed(st, j, sign * h);
            let pst = ElementState {
                x_a: &xa,
                x_b: &xb,
                lam_a: &la,
                lam_b: &lb,
                q_a: st.q_a,
                q_b: st.q_b,
            };
            let (bp, _) = b_matrix(&pst, l0);
            col += bp.transpose() * fl * w;
        }
        kg.set_column(j, &col);
    }
    kg
}

#[cfg(test)]
mod tests {
    use super::super::rotation::exp_so3;
    use super::*;

    /// 3 x 12 matrix with `blk` at columns `3 c .. 3 c + 3`.
    fn place(blk: &Matrix3<f64>, c: usize) -> SMatrix<f64, 3, 12> {
        let mut m = SMatrix::<f64, 3, 12>::zeros();
        m.fixed_view_mut::<3, 3>(0, 3 * c).copy_from(blk);
        m
    }

    /// The closed form with dense 3 x 12 products (the first version), a cross-check of the
    /// block-structured [`geometric_tangent`].
    /// Analytic geometric part of the consistent tangent, `(dB^T/dp_global) f_local` at fixed
    /// `f_local` (node-basis DOFs): the derivative of the internal force `B^T f_local` through the
    /// element frame, the inverse tangent operators and the node triads (Crisfield 1990;
    /// Battini & Pacoste 2002, here for the frame whose second axis follows the mean of the nodal
    /// second axes). Derived in spatial components, with DOF order `[xA, wA, xB, wB]`:
    /// `f . dp = N r1 . dd + vA . (wA - w_r) + vB . (wB - w_r)`, `dd = dxB - dxA`,
    /// `v = R_r T^-T m`, frame spin `w_r = r1 x dd / l + r1 E`,
    /// `E = [w . dq - (q1 / l) w . dd] / c^2` (`q` the mean second axis, `w = r1 x q`,
    /// `c = |w|`, `q1 = q . r1`); each factor is then varied in turn. Checked against
    /// [`geometric_tangent_by_differences`] in the tests.
    fn geometric_tangent_dense(st: &ElementState, k: &Kinematics, fl: &SVector<f64, 7>) -> Mat12 {
        let rr = k.rr;
        let l = k.ln;
        let r1: Vec3 = rr.column(0).into_owned();
        let qa: Vec3 = st.lam_a.column(1).into_owned();
        let qb: Vec3 = st.lam_b.column(1).into_owned();
        let q = (qa + qb) * 0.5;
        let q1 = q.dot(&r1);
        let w = r1.cross(&q);
        let c2 = w.dot(&w);
        let eye = Matrix3::identity();
        let p = eye - r1 * r1.transpose();
        let n = fl[0];
        let m_a = Vec3::new(fl[1], fl[2], fl[3]);
        let m_b = Vec3::new(fl[4], fl[5], fl[6]);
        // virtual-displacement maps (3 x 12, spatial): dd, dq, and the node spins
        let ld = place(&(-eye), 0) + place(&eye, 2);
        let lq = place(&(skew(&qa) * -0.5), 1) + place(&(skew(&qb) * -0.5), 3);
        let lw_a = place(&eye, 1);
        let lw_b = place(&eye, 3);
        // frame spin w_r = Omega dp
        let nvec: SVector<f64, 12> = lq.transpose() * w - ld.transpose() * w * (q1 / l);
        let omega = skew(&r1) * ld / l + r1 * (nvec / c2).transpose();
        // local rotation increments: dtheta = T^-1 R_r^T (w_node - w_r)
        let pa = rr.transpose() * (lw_a - omega);
        let pb = rr.transpose() * (lw_b - omega);
        let ti_a = tangent_inverse(&k.th_a);
        let ti_b = tangent_inverse(&k.th_b);
        let v_a = rr * ti_a.transpose() * m_a;
        let v_b = rr * ti_b.transpose() * m_b;
        let v = v_a + v_b;
        // 1. axial force times the chord rotation
        let mut kg: Mat12 = ld.transpose() * p * ld * (n / l);
        // 2. moments times the variation of T^-T (through theta)
        kg += pa.transpose() * d_tinv_t_m(&k.th_a, &m_a) * ti_a * pa;
        kg += pb.transpose() * d_tinv_t_m(&k.th_b, &m_b) * ti_b * pb;
        // 3. moments times the rotation of the frame R_r in v = R_r T^-T m
        kg -= lw_a.transpose() * skew(&v_a) * omega + lw_b.transpose() * skew(&v_b) * omega;
        kg += omega.transpose() * skew(&v) * omega;
        // 4. -V . (variation of the frame-spin map) dp
        let lw = -skew(&q) * p * ld / l + skew(&r1) * lq; // variation of w
        let lq1: SVector<f64, 12> = lq.transpose() * r1 + ld.transpose() * (p * q) / l;
        let lc: SVector<f64, 12> = (lq.transpose() * q - lq1 * q1) * 2.0;
        let mut hqq = Mat12::zeros();
        let ha = (qa * w.transpose() - eye * w.dot(&qa)) * 0.5;
        let hb = (qb * w.transpose() - eye * w.dot(&qb)) * 0.5;
        hqq.fixed_view_mut::<3, 3>(3, 3).copy_from(&ha);
        hqq.fixed_view_mut::<3, 3>(9, 9).copy_from(&hb);
        let ldw: SVector<f64, 12> = ld.transpose() * w;
        let r1ld: SVector<f64, 12> = ld.transpose() * r1;
        let dnum: Mat12 = lq.transpose() * lw + hqq - ldw * lq1.transpose() / l - ld.transpose() * lw * (q1 / l)
            + ldw * r1ld.transpose() * (q1 / (l * l));
        let de: Mat12 = dnum / c2 - nvec * lc.transpose() / (c2 * c2);
        let hframe: Mat12 = ld.transpose() * (skew(&v) * p - v.cross(&r1) * r1.transpose()) * ld / (l * l)
            + (nvec / c2) * (ld.transpose() * (p * v) / l).transpose()
            + de * v.dot(&r1);
        kg -= hframe;
        // to node bases: K = Qblk^T K_s Qblk
        let qs = [st.q_a, st.q_a, st.q_b, st.q_b];
        let mut out = Mat12::zeros();
        for bi in 0..4 {
            for bj in 0..4 {
                let blk = qs[bi].transpose() * kg.fixed_view::<3, 3>(3 * bi, 3 * bj) * qs[bj];
                out.fixed_view_mut::<3, 3>(3 * bi, 3 * bj).copy_from(&blk);
            }
        }
        out
    }

    type Setup = (
        Vec3,
        Vec3,
        Matrix3<f64>,
        Matrix3<f64>,
        Matrix3<f64>,
        Matrix3<f64>,
        BeamSection,
    );

    fn setup() -> Setup {
        // A slightly bent, twisted, stretched element in a general orientation.
        let q_a = exp_so3(&Vec3::new(0.3, -0.5, 0.2));
        let q_b = exp_so3(&Vec3::new(0.31, -0.52, 0.21));
        let x_a = Vec3::new(1.0, 2.0, 3.0);
        let x_b = x_a + q_a.column(0) * 0.7003 + q_a.column(1) * 0.004;
        let lam_a = exp_so3(&Vec3::new(0.01, 0.02, -0.015)) * q_a;
        let lam_b = exp_so3(&Vec3::new(-0.02, 0.01, 0.03)) * q_a;
        let s = BeamSection {
            l0: 0.7,
            ea: 3.6e9,
            ei: 7.3e6,
            gj: 5.6e6,
        };
        (x_a, x_b, lam_a, lam_b, q_a, q_b, s)
    }

    #[test]
    fn internal_force_is_energy_gradient() {
        // Finite differences of the strain energy under dx additive and spins R <- exp(dw) R,
        // both in node bases: checks B (G^T, T_s^-1, the frame definition) exactly.
        let (x_a, x_b, lam_a, lam_b, q_a, q_b, s) = setup();
        let st = ElementState {
            x_a: &x_a,
            x_b: &x_b,
            lam_a: &lam_a,
            lam_b: &lam_b,
            q_a: &q_a,
            q_b: &q_b,
        };
        let r = element_response(&st, &s, true, false);
        let h = 1e-7;
        for j in 0..12 {
            let energy = |sign: f64| {
                let (xa, xb, la, lb) = perturbed(&st, j, sign * h);
                let st = ElementState {
                    x_a: &xa,
                    x_b: &xb,
                    lam_a: &la,
                    lam_b: &lb,
                    q_a: &q_a,
                    q_b: &q_b,
                };
                strain_energy(&st, &s)
            };
            let fd = (energy(1.0) - energy(-1.0)) / (2.0 * h);
            let scale = r.force.abs().max().max(1.0);
            assert!(
                (fd - r.force[j]).abs() < 1e-6 * scale,
                "dof {j}: fd {fd} vs {}",
                r.force[j]
            );
        }
    }

    #[test]
    fn rigid_motion_gives_no_force_and_tangent_is_close_to_fd() {
        let (x_a, x_b, lam_a, lam_b, q_a, q_b, s) = setup();
        let st = ElementState {
            x_a: &x_a,
            x_b: &x_b,
            lam_a: &lam_a,
            lam_b: &lam_b,
            q_a: &q_a,
            q_b: &q_b,
        };
        let r0 = element_response(&st, &s, true, false);
        // Rigid rotation + translation of the whole element leaves the energy unchanged.
        let rot = exp_so3(&Vec3::new(0.7, -0.2, 1.1));
        let c = Vec3::new(5.0, -3.0, 2.0);
        let (xa2, xb2) = (rot * x_a + c, rot * x_b + c);
        let (la2, lb2) = (rot * lam_a, rot * lam_b);
        let st2 = ElementState {
            x_a: &xa2,
            x_b: &xb2,
            lam_a: &la2,
            lam_b: &lb2,
            q_a: &q_a,
            q_b: &q_b,
        };
        assert!((strain_energy(&st, &s) - strain_energy(&st2, &s)).abs() < 1e-9 * strain_energy(&st, &s));
        assert!(
            (element_response(&st2, &s, true, false).axial_force - r0.axial_force).abs() < 1e-6 * r0.axial_force.abs()
        );
        // Tangent vs finite differences of the force: approximate tangent within 2% of the largest entry.
        let h = 1e-7;
        let kmax = r0.tangent.abs().max();
        for j in 0..12 {
            let force = |sign: f64| {
                let (xa, xb, la, lb) = perturbed(&st, j, sign * h);
                let st = ElementState {
                    x_a: &xa,
                    x_b: &xb,
                    lam_a: &la,
                    lam_b: &lb,
                    q_a: &q_a,
                    q_b: &q_b,
                };
                element_response(&st, &s, true, false).force
            };
            let col = (force(1.0) - force(-1.0)) / (2.0 * h);
            for i in 0..12 {
                assert!(
                    (col[i] - r0.tangent[(i, j)]).abs() < 2e-2 * kmax,
                    "K[{i}][{j}] fd {} vs {}",
                    col[i],
                    r0.tangent[(i, j)]
                );
            }
        }
    }
    /// The dense form of [`b_matrix`] (its first version): the bit-for-bit oracle of the sparse
    /// one.
    fn b_matrix_dense(st: &ElementState, l0: f64) -> (SMatrix<f64, 7, 12>, Kinematics) {
        let k = kinematics(st, l0);
        let rr = k.rr;
        let ln = k.ln;
        // Local-component DOFs: p_loc = M p_hat, M = diag(R_r^T Q_A, R_r^T Q_A, R_r^T Q_B, R_r^T Q_B).
        let ma = rr.transpose() * st.q_a;
        let mb = rr.transpose() * st.q_b;
        // G^T: spin of the element frame in local components, acting on local-component DOFs.
        let q2 = k.q_loc.y;
        let eta = k.q_loc.x / q2;
        let (e11, e12) = (k.qa_loc.x / q2, k.qa_loc.y / q2);
        let (e21, e22) = (k.qb_loc.x / q2, k.qb_loc.y / q2);
        let mut gt = SMatrix::<f64, 3, 12>::zeros();
        gt[(0, 2)] = eta / ln;
        gt[(0, 3)] = e12 / 2.0;
        gt[(0, 4)] = -e11 / 2.0;
        gt[(0, 8)] = -eta / ln;
        gt[(0, 9)] = e22 / 2.0;
        gt[(0, 10)] = -e21 / 2.0;
        gt[(1, 2)] = 1.0 / ln;
        gt[(1, 8)] = -1.0 / ln;
        gt[(2, 1)] = -1.0 / ln;
        gt[(2, 7)] = 1.0 / ln;
        // P_A = [0 I 0 0] - G^T, P_B = [0 0 0 I] - G^T, then T_s^-1.
        let mut pa = -gt;
        let mut pb = -gt;
        for i in 0..3 {
            pa[(i, 3 + i)] += 1.0;
            pb[(i, 9 + i)] += 1.0;
        }
        let ta = k.ti_a * pa;
        let tb = k.ti_b * pb;
        // B in local-component DOFs (7 x 12), then to node bases by M.
        let mut bl = SMatrix::<f64, 7, 12>::zeros();
        // du = r1 . (duB - duA): in local components r1 = e1.
        bl[(0, 0)] = -1.0;
        bl[(0, 6)] = 1.0;
        for j in 0..12 {
            for i in 0..3 {
                bl[(1 + i, j)] = ta[(i, j)];
                bl[(4 + i, j)] = tb[(i, j)];
            }
        }
        let mut b = SMatrix::<f64, 7, 12>::zeros();
        for blk in 0..4 {
            let m = if blk < 2 { &ma } else { &mb };
            for i in 0..7 {
                for c in 0..3 {
                    let mut acc = 0.0;
                    for r in 0..3 {
                        acc += bl[(i, 3 * blk + r)] * m[(r, c)];
                    }
                    b[(i, 3 * blk + c)] = acc;
                }
            }
        }
        (b, k)
    }

    /// Deterministic pseudo-random numbers in [-1, 1) (64-bit LCG, top bits).
    struct Lcg(u64);
    impl Lcg {
        fn next(&mut self) -> f64 {
            self.0 = self
                .0
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            ((self.0 >> 11) as f64 / (1u64 << 53) as f64) * 2.0 - 1.0
        }
        fn vec(&mut self, scale: f64) -> Vec3 {
            Vec3::new(self.next(), self.next(), self.next()) * scale
        }
    }

    #[test]
    fn sparse_b_and_congruence_equal_the_dense_products_bit_for_bit() {
        // Oracle: the dense products of the first version (`b_matrix_dense`, `K * B` by
        // nalgebra); tolerance: none (every entry identical), on random states far from the
        // node bases with bending, twist and stretch, with and without the geometric term.
        let mut rng = Lcg(777);
        for case in 0..300 {
            let q_a = exp_so3(&rng.vec(3.0));
            let q_b = exp_so3(&rng.vec(0.05)) * q_a;
            let rigid = exp_so3(&rng.vec(2.5));
            let l0 = 0.5 + rng.next().abs();
            let x_a = rng.vec(10.0);
            let x_b = x_a + rigid * (q_a.column(0) * (l0 * (1.0 + 1e-3 * rng.next())) + rng.vec(0.05 * l0));
            let lam_a = rigid * exp_so3(&rng.vec(0.3)) * q_a;
            let lam_b = rigid * exp_so3(&(rng.vec(0.3) + q_a.column(0) * 0.5 * rng.next())) * q_a;
            let st = ElementState {
                x_a: &x_a,
                x_b: &x_b,
                lam_a: &lam_a,
                lam_b: &lam_b,
                q_a: &q_a,
                q_b: &q_b,
            };
            let (b, k) = b_matrix(&st, l0);
            let (bd, _) = b_matrix_dense(&st, l0);
            for (x, y) in b.iter().zip(bd.iter()) {
                assert_eq!(x.to_bits(), y.to_bits(), "case {case}: B {b} vs dense {bd}");
            }
            let s = BeamSection {
                l0,
                ea: 3.6e9,
                ei: 7.3e6,
                gj: 5.6e6,
            };
            let loc = local_response(&s, &k.p, case % 3 != 0);
            let kl = SMatrix::<f64, 7, 7>::from_fn(|i, j| loc.tangent[i][j]);
            let c = kl * b;
            let mut dense = Mat12::zeros();
            for j in 0..12 {
                for i in 0..=j {
                    let mut acc = 0.0;
                    for r in 0..7 {
                        acc += b[(r, i)] * c[(r, j)];
                    }
                    dense[(i, j)] = acc;
                    dense[(j, i)] = acc;
                }
            }
            let mut sparse = Mat12::zeros();
            congruence(&b, &kl, &mut sparse);
            for (x, y) in sparse.iter().zip(dense.iter()) {
                assert_eq!(x.to_bits(), y.to_bits(), "case {case}: B^T K B");
            }
        }
    }

    #[test]
    fn paired_block_congruence_equals_nalgebra_products_bit_for_bit() {
        // Oracle: nalgebra's `(Q_r^T * K) * Q_c` added to the output, as the first version of
        // the geometric tangent's change to node bases did; tolerance: none.
        let mut rng = Lcg(4242);
        for _ in 0..200 {
            let q_r = exp_so3(&rng.vec(3.0));
            let q_c = exp_so3(&rng.vec(3.0));
            let k0 = Matrix3::from_fn(|_, _| 1e6 * rng.next());
            let k1 = Matrix3::from_fn(|_, _| 1e3 * rng.next());
            let base = Mat12::from_fn(|_, _| rng.next());
            let mut out = base;
            add_congruence_pair(&q_r, &q_c, &k0, &k1, &mut out, 3, 6);
            let mut reference = base;
            let mut d0 = reference.fixed_view_mut::<3, 3>(3, 6);
            d0 += q_r.transpose() * k0 * q_c;
            let mut d1 = reference.fixed_view_mut::<3, 3>(3, 9);
            d1 += q_r.transpose() * k1 * q_c;
            for (x, y) in out.iter().zip(reference.iter()) {
                assert_eq!(x.to_bits(), y.to_bits());
            }
        }
    }

    #[test]
    fn analytic_geometric_tangent_matches_finite_differences() {
        // Oracle: geometric_tangent_by_differences (central differences of B^T f_local, h = 1e-7).
        // Random states: node bases and the whole element rotated far from them (rigid
        // rotations up to ~3 rad), local bending rotations up to 0.3 rad, twist up to 0.5 rad
        // between the ends (torque), stretch, and random local forces. Tolerance 1e-6 of the
        // largest entry.
        let mut rng = Lcg(12345);
        let mut worst: f64 = 0.0;
        for case in 0..200 {
            let q_a = exp_so3(&rng.vec(3.0));
            let q_b = exp_so3(&rng.vec(0.05)) * q_a;
            let rigid = exp_so3(&rng.vec(if case % 2 == 0 { 2.5 } else { 0.1 }));
            let l0 = 0.5 + rng.next().abs();
            let x_a = rng.vec(10.0);
            let x_b = x_a + rigid * (q_a.column(0) * (l0 * (1.0 + 1e-3 * rng.next())) + rng.vec(0.05 * l0));
            let twist = 0.5 * rng.next();
            let lam_a = rigid * exp_so3(&rng.vec(0.3)) * q_a;
            let lam_b = rigid * exp_so3(&(rng.vec(0.3) + q_a.column(0) * twist)) * q_a;
            let st = ElementState {
                x_a: &x_a,
                x_b: &x_b,
                lam_a: &lam_a,
                lam_b: &lam_b,
                q_a: &q_a,
                q_b: &q_b,
            };
            let fl = SVector::<f64, 7>::from_fn(|i, _| if i == 0 { 1e5 * rng.next() } else { 1e4 * rng.next() });
            let k = kinematics(&st, l0);
            let analytic = geometric_tangent(&st, &k, &fl);
            let dense = geometric_tangent_dense(&st, &k, &fl);
            let d = (analytic - dense).abs().max() / dense.abs().max();
            assert!(d < 1e-12, "case {case}: block form vs dense form {d:e}");
            let fd = geometric_tangent_by_differences(&st, l0, &fl);
            let scale = fd.abs().max();
            let err = (analytic - fd).abs().max() / scale;
            worst = worst.max(err);
            assert!(
                err < 1e-6,
                "case {case}: relative error {err:e}\nanalytic {analytic}\nfd {fd}"
            );
        }
        println!("worst relative error {worst:e}");
    }

    #[test]
    fn consistent_tangent_is_the_derivative_of_the_force() {
        // Oracle: central differences of the internal force itself (energy gradient, checked in
        // internal_force_is_energy_gradient), on a twisted, bent element rotated far from its
        // node bases. Tolerance 1e-6 of the largest entry.
        let (x_a, x_b, lam_a, lam_b, q_a, q_b, s) = setup();
        let rigid = exp_so3(&Vec3::new(1.2, -0.7, 2.0));
        let (x_a, x_b) = (rigid * x_a, rigid * x_b);
        let lam_a = rigid * exp_so3(&(q_a.column(0) * 0.4)) * lam_a;
        let lam_b = rigid * lam_b;
        let st = ElementState {
            x_a: &x_a,
            x_b: &x_b,
            lam_a: &lam_a,
            lam_b: &lam_b,
            q_a: &q_a,
            q_b: &q_b,
        };
        let r0 = element_response(&st, &s, true, true);
        let h = 1e-7;
        let kmax = r0.tangent.abs().max();
        for j in 0..12 {
            let force = |sign: f64| {
                let (xa, xb, la, lb) = perturbed(&st, j, sign * h);
                let st = ElementState {
                    x_a: &xa,
                    x_b: &xb,
                    lam_a: &la,
                    lam_b: &lb,
                    q_a: &q_a,
                    q_b: &q_b,
                };
                element_force(&st, &s, true).force
            };
            let col = (force(1.0) - force(-1.0)) / (2.0 * h);
            for i in 0..12 {
                assert!(
                    (col[i] - r0.tangent[(i, j)]).abs() < 1e-6 * kmax,
                    "K[{i}][{j}] fd {} vs {}",
                    col[i],
                    r0.tangent[(i, j)]
                );
            }
        }
    }
}
