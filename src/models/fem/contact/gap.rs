//! The spatial multi-directional contact-friction gap element (the paper's Table 1, docs/theory.md 6).
//!
//! A node at position `x` whose nearest hole-axis point is `p` with tangent `t` has the lateral
//! offset `d = x - p` (perpendicular to `t`), radial distance `s = |d|` and outward normal
//! `n = d/s`. With radial clearance `EO`, the gap is open while `s < EO`. The wall reaction on
//! the string is `-R n` with `R >= 0`; here `R = max(0, lambda + k_n (s - EO))`, a penalty
//! regularized by the augmented-Lagrangian multiplier `lambda` (updated by the solver so that the
//! penetration `s - EO` falls below the tolerance). Friction `-f R v/|v|` opposes the sliding
//! velocity of the string surface at the contact point, `v = v_a t + Omega R_c (t x n)`
//! (axial speed `v_a`, positive down; spin `Omega` about `t`, positive clockwise from above),
//! and acts at the contact point `x + R_c n`, so it also applies the moment
//! `R_c n x F_friction` (its `t` component is the friction torque `-f R R_c` when rotating).

use crate::case::Motion;
use crate::geometry::Vec3;
use nalgebra::Matrix3;

/// Inputs of one gap evaluation (SI).
#[derive(Debug, Clone, Copy)]
pub struct GapInput {
    /// Lateral offset of the node from the hole axis, perpendicular to `t`, m.
    pub offset: Vec3,
    /// Hole tangent at the nearest axis point.
    pub t: Vec3,
    /// Radial clearance EO, m (>= 0).
    pub clearance: f64,
    /// Contact radius R_c (half the contact OD), m.
    pub contact_radius: f64,
    /// Augmented-Lagrangian multiplier, N (>= 0).
    pub lambda: f64,
    /// Penalty stiffness, N/m.
    pub k_n: f64,
    /// Friction coefficient.
    pub friction: f64,
    /// Axial speed of the string, m/s (positive down the hole).
    pub axial_speed: f64,
    /// Spin of the string about `t`, rad/s.
    pub omega: f64,
    /// Normal to use when the offset is ~0 (previous contact direction).
    pub fallback_normal: Vec3,
    /// Contact status imposed by an active-set solver: `Some(true)` makes the gap bilateral
    /// (the force `lambda + k_n g` may turn negative, telling the solver to release it),
    /// `Some(false)` makes it carry nothing; `None` uses the unilateral law.
    pub status: Option<bool>,
    /// Vector multiplier (N) of a zero-clearance gap (full-gauge stabilizer or bit), which acts
    /// as a frictional pin: force `-(lambda_vec + k_n d)`, smooth through `d = 0`.
    pub lambda_vec: Vec3,
    /// Normal force used for friction, N: the multiplier of the previous outer iteration, so
    /// friction is constant while Newton converges (docs/theory.md 6.2: "lag the friction"), and
    /// exact at convergence where the multiplier equals the normal force. `None`: use the
    /// current normal force.
    pub friction_load: Option<f64>,
    /// The string whirls here (`crate::models::whirl`): the friction force keeps its axial
    /// part only (its moment, the friction torque, is kept whole).
    pub whirl: bool,
}

/// Result of one gap evaluation, global frame.
#[derive(Debug, Clone, Copy)]
pub struct GapResponse {
    /// Wall normal reaction R (N; >= 0 except for a closed gap held by an active-set solver,
    /// where a negative value means the gap wants to open).
    pub normal_force: f64,
    /// Outward unit normal n (from the axis toward the contact).
    pub normal: Vec3,
    /// Total wall force on the string (normal + friction), N.
    pub force: Vec3,
    /// Moment of the friction force about the node, N.m.
    pub moment: Vec3,
    /// Stiffness `-dF/dx` of the total wall force (normal and friction), N/m; unsymmetric
    /// when friction acts.
    pub stiffness: Matrix3<f64>,
    /// `-dM/dx` of the friction moment with respect to the node position, N.
    pub moment_stiffness: Matrix3<f64>,
    /// Contact carries a force above a negligible level.
    pub active: bool,
    /// Radial distance minus clearance, m (> 0: penetration).
    pub penetration: f64,
}

impl GapResponse {
    /// The normal (wall) part of the force on the string, N: `-R n`.
    pub fn force_normal(&self) -> Vec3 {
        -self.normal * self.normal_force
    }
}

/// Clearances at or below this (m) make the gap a pin (vector augmented Lagrangian).
pub const ZERO_CLEARANCE_M: f64 = 1e-6;

/// Evaluate the gap element: normal force law, friction, and their consistent derivatives.
pub fn evaluate(g: &GapInput) -> GapResponse {
    let t = g.t;
    let ptt = Matrix3::identity() - t * t.transpose();
    let d = ptt * g.offset;
    let s = d.norm();
    let tiny = 1e-12;
    // Normal law: R, n, dR/dx (as a vector) and dn/dx.
    let (r, n, dr_dx, dn_dx, active) = if g.clearance <= ZERO_CLEARANCE_M {
        // pin: p = lambda_perp + k_n d, R = |p|, n = p / R
        let p = ptt * g.lambda_vec + d * g.k_n;
        let r = p.norm();
        if r > tiny {
            let n = p / r;
            (r, n, n * g.k_n, (ptt - n * n.transpose()) * (g.k_n / r), true)
        } else {
            (0.0, g.fallback_normal, Vec3::zeros(), ptt * 0.0, true)
        }
    } else {
        let n = if s > tiny { d / s } else { g.fallback_normal };
        let dn = if s > tiny {
            (ptt - n * n.transpose()) / s
        } else {
            Matrix3::zeros()
        };
        let trial = g.lambda + g.k_n * (s - g.clearance);
        let (r, dr) = if let Some(closed) = g.status {
            if closed {
                (trial, g.k_n)
            } else {
                (0.0, 0.0)
            }
        } else if trial > 0.0 {
            (trial, g.k_n)
        } else {
            (0.0, 0.0)
        };
        let active = r > 0.0;
        (r, n, n * dr, dn, active)
    };
    let mut stiffness = n * dr_dx.transpose() + dn_dx * r;
    if g.clearance > ZERO_CLEARANCE_M && s <= tiny && dr_dx.norm() > 0.0 {
        // closed gap sitting on the axis: isotropic lateral spring
        stiffness = ptt * dr_dx.norm();
    }
    if g.clearance <= ZERO_CLEARANCE_M && r <= tiny {
        // pin without force (on the axis, no multiplier): n dR^T + R dn = k_n (I - t t^T) for
        // every p != 0, so the same lateral spring here (not zero: a pin that a Newton step
        // could move freely)
        stiffness = ptt * g.k_n;
    }
    let mut force = -n * r;
    let mut moment = Vec3::zeros();
    let mut moment_stiffness = Matrix3::zeros();
    // Friction load: the current normal force, or (status open with a given load) the
    // multiplier of a contact whose normal force an outer complementarity solve decides.
    let lagged = g.status == Some(false) && g.friction_load.is_some();
    let rf = if lagged {
        g.friction_load.unwrap_or(0.0).max(0.0)
    } else {
        r.max(0.0)
    };
    let dr_dx = if lagged { Vec3::zeros() } else { dr_dx };
    if rf > 0.0 && g.friction > 0.0 {
        // unit sliding velocity v^ = (v_a t + Omega R_c t x n)/|v| from the shared split (|v|
        // does not change with n, so dv^/dx = (I - v^ v^T) [t]x dn/dx Omega R_c/|v|)
        let motion = Motion {
            axial_speed_m_s: g.axial_speed,
            omega_rad_s: g.omega,
        };
        let split = motion.friction_split(g.contact_radius);
        if split.acts() {
            let vh = t * split.axial + t.cross(&n) * split.tangential;
            let dv = skew(&t) * dn_dx * split.tangential;
            let dvh = (Matrix3::identity() - vh * vh.transpose()) * dv;
            let ff = -vh * (g.friction * rf);
            // dF_f/dx = -f (vh dR^T + R dvh)
            let dff = -(vh * dr_dx.transpose() + dvh * rf) * g.friction;
            // a whirling string: the friction's lateral push round the wall left out
            let kept = if g.whirl {
                t * t.transpose()
            } else {
                Matrix3::identity()
            };
            force += kept * ff;
            stiffness -= kept * dff;
            let rn = n * g.contact_radius;
            moment = rn.cross(&ff);
            // dM/dx = R_c ([n]x dF_f - [F_f]x dn)
            let dm = (skew(&n) * dff - skew(&ff) * dn_dx) * g.contact_radius;
            moment_stiffness = -dm;
        }
    }
    GapResponse {
        normal_force: r,
        normal: n,
        force,
        moment,
        stiffness,
        moment_stiffness,
        active,
        penetration: s - g.clearance,
    }
}

fn skew(v: &Vec3) -> Matrix3<f64> {
    Matrix3::new(0.0, -v.z, v.y, v.z, 0.0, -v.x, -v.y, v.x, 0.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn input() -> GapInput {
        GapInput {
            offset: Vec3::new(0.0, 0.0201, 0.0),
            t: Vec3::new(1.0, 0.0, 0.0),
            clearance: 0.02,
            contact_radius: 0.08,
            lambda: 0.0,
            k_n: 1e8,
            friction: 0.3,
            axial_speed: 0.0,
            omega: 6.0,
            fallback_normal: Vec3::new(0.0, 1.0, 0.0),
            status: None,
            whirl: false,
            lambda_vec: Vec3::zeros(),
            friction_load: None,
        }
    }

    #[test]
    fn open_gap_carries_nothing() {
        let mut g = input();
        g.offset = Vec3::new(0.0, 0.01, 0.0);
        let r = evaluate(&g);
        assert_eq!(r.normal_force, 0.0);
        assert_eq!(r.force, Vec3::zeros());
        assert!(!r.active);
    }

    #[test]
    fn rotating_contact_gives_paper_friction_torque() {
        // Table 1: T = f R, m = (D/2) T, opposing the rotation; no axial drag without axial motion.
        let r = evaluate(&input());
        let rn = 1e8 * 1e-4;
        assert!((r.normal_force - rn).abs() < 1e-6);
        let torque = r.moment.dot(&Vec3::new(1.0, 0.0, 0.0));
        assert!((torque + 0.3 * rn * 0.08).abs() < 1e-9);
        assert!(r.force.x.abs() < 1e-12);
    }

    /// A whirling contact (`crate::models::whirl`): the friction force keeps only its axial
    /// part `-f R v_a/|v| t` and the moment is the full law's (its torque `-f R R_c Omega R_c/|v|`
    /// about `t`); reference: the full law's evaluation of the same contact.
    #[test]
    fn whirling_contact_keeps_torque_and_drag_but_not_the_push() {
        let mut g = input();
        g.axial_speed = 0.05;
        let full = evaluate(&g);
        g.whirl = true;
        let w = evaluate(&g);
        let t = g.t;
        let normal = -full.normal * full.normal_force;
        let axial_full = t * t.dot(&(full.force - normal));
        assert!((w.force - normal - axial_full).norm() < 1e-9 * full.normal_force);
        assert!((full.force - w.force).norm() > 0.1 * 0.3 * full.normal_force);
        assert!((w.moment - full.moment).norm() < 1e-12);
    }

    #[test]
    fn stiffness_matches_finite_differences_of_normal_force() {
        let mut g = input();
        g.friction = 0.0;
        g.offset = Vec3::new(0.0, 0.0203, -0.004);
        let r = evaluate(&g);
        let h = 1e-9;
        for j in 0..3 {
            let mut gp = g;
            let mut gm = g;
            gp.offset[j] += h;
            gm.offset[j] -= h;
            let col = -(evaluate(&gp).force - evaluate(&gm).force) / (2.0 * h);
            for i in 0..3 {
                assert!((col[i] - r.stiffness[(i, j)]).abs() < 1e-4 * 1e8, "{i}{j}");
            }
        }
    }

    #[test]
    fn frictional_stiffness_and_moment_match_finite_differences() {
        // Consistent tangent of the frictional gap (normal + friction force and friction
        // moment), rotating and sliding, unilateral and pin, whirling: central differences.
        for (clearance, axial, omega, whirl) in [
            (0.02, 0.0, 6.0, false),
            (0.02, 0.3, 0.0, false),
            (0.02, 0.01, 6.0, false),
            (0.0, 0.0, 6.0, false),
            (0.02, 0.01, 6.0, true),
        ] {
            let mut g = input();
            g.whirl = whirl;
            g.clearance = clearance;
            g.axial_speed = axial;
            g.omega = omega;
            g.offset = Vec3::new(0.01, 0.0203, -0.004);
            g.lambda_vec = Vec3::new(0.0, 300.0, 100.0);
            let r = evaluate(&g);
            let h = 1e-10;
            for j in 0..3 {
                let mut gp = g;
                let mut gm = g;
                gp.offset[j] += h;
                gm.offset[j] -= h;
                let (rp, rm) = (evaluate(&gp), evaluate(&gm));
                let col_f = -(rp.force - rm.force) / (2.0 * h);
                let col_m = -(rp.moment - rm.moment) / (2.0 * h);
                for i in 0..3 {
                    assert!(
                        (col_f[i] - r.stiffness[(i, j)]).abs() < 1e-5 * 1e8,
                        "force {i}{j}: {} vs {}",
                        col_f[i],
                        r.stiffness[(i, j)]
                    );
                    assert!(
                        (col_m[i] - r.moment_stiffness[(i, j)]).abs() < 1e-5 * 1e8,
                        "moment {i}{j}"
                    );
                }
            }
        }
    }
}
