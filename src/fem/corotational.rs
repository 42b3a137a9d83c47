//! Co-rotational kinematics of the 3D beam (Crisfield 1990; Battini & Pacoste 2002).
//!
//! Each element carries a rigid frame `R_r = [r1 r2 r3]` that follows its chord: `r1` along
//! `x_B - x_A`, `r2`, `r3` from the mean of the nodal triads' second axes made orthogonal to
//! `r1`. The local element of [`super::beam`] acts on the deformation in that frame:
//! `u = l - l0`, `theta_A = log(R_r^T Lambda_A)`, `theta_B = log(R_r^T Lambda_B)`.
//! The variation `dp_local = B dp_global` uses the spin of the element frame `G^T`
//! (derived in the module tests by finite differences) and `T_s^-1`. The internal force
//! `B^T f_local` is exact (it is the gradient of the strain energy); the tangent used here is
//! `B^T K_local B + N/l (I - r1 r1^T)` on the translations, which omits the small terms of the
//! moments times frame variations (relative size ~ theta, below 1e-2 for a string in a hole),
//! so Newton converges slightly less than quadratically but to the exact solution.
//!
//! Global DOFs per node: 3 displacements and 3 spins, both expressed in the node's fixed basis
//! `Q` (columns: the hole tangent and two normals at the node's reference position).

use super::beam::{local_response, BeamSection};
use super::rotation::{log_so3, tangent_inverse};
use crate::geometry::Vec3;
use nalgebra::{Matrix3, SMatrix, SVector};

/// 12-vector (element global DOFs, node bases).
pub type Vec12 = SVector<f64, 12>;
/// 12x12 matrix.
pub type Mat12 = SMatrix<f64, 12, 12>;

/// Current state of an element's two nodes.
#[derive(Debug, Clone, Copy)]
pub struct ElementState<'a> {
    /// Position of node A (lower, toward the bit), m.
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
}

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

/// Internal force and tangent of the element in node-basis DOFs `[uA, wA, uB, wB]`.
/// The matrix `B = d p_local / d p_global` (7 x 12, node-basis global DOFs) and the kinematics.
fn b_matrix(st: &ElementState, l0: f64) -> (SMatrix<f64, 7, 12>, Kinematics) {
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
    let ta = tangent_inverse(&k.th_a) * pa;
    let tb = tangent_inverse(&k.th_b) * pb;
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

/// Internal force and tangent of the element in node-basis DOFs `[uA, wA, uB, wB]`.
///
/// `consistent = true` adds the full geometric part of the tangent, `(dB^T/dp) f_local`
/// (moments and torque times the variation of the co-rotational map), by central differences
/// of `B^T f_local` at fixed `f_local`; otherwise only its axial-force part `N/l (I - r1 r1^T)`.
/// The consistent form matters when the string carries torque (rotary friction).
pub fn element_response(st: &ElementState, s: &BeamSection, with_geometric: bool, consistent: bool) -> ElementResponse {
    response(st, s, with_geometric, consistent, true)
}

/// Internal force only (the tangent is left zero): for residual evaluations in line searches.
pub fn element_force(st: &ElementState, s: &BeamSection, with_geometric: bool) -> ElementResponse {
    response(st, s, with_geometric, false, false)
}

fn response(
    st: &ElementState,
    s: &BeamSection,
    with_geometric: bool,
    consistent: bool,
    need_tangent: bool,
) -> ElementResponse {
    let (b, k) = b_matrix(st, s.l0);
    let loc = local_response(s, &k.p, with_geometric);
    let rr = k.rr;
    let ln = k.ln;
    let fl = SVector::<f64, 7>::from_row_slice(&loc.force);
    let kl = SMatrix::<f64, 7, 7>::from_fn(|i, j| loc.tangent[i][j]);
    let force = b.transpose() * fl;
    let n = loc.axial_force;
    if !need_tangent {
        return ElementResponse {
            force,
            tangent: Mat12::zeros(),
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
    }
    let mut tangent = b.transpose() * kl * b;
    if consistent {
        tangent += geometric_by_differences(st, s.l0, &fl);
        return ElementResponse {
            force,
            tangent,
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
    ElementResponse {
        force,
        tangent,
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

/// `(dB^T/dp_global) f_local` by central differences (f_local fixed).
fn geometric_by_differences(st: &ElementState, l0: f64, fl: &SVector<f64, 7>) -> Mat12 {
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
}
