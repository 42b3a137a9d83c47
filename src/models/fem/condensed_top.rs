//! The string above a model's top node condensed onto it: the linearized force of that part
//! on the node ([`CondensedTop`], the top condition `models::fem::model::TopCondition::
//! Condensed` of a lower part, `models::fem::model_top`). The refined solve of the assembly's
//! mesh solves such a lower part (`models::fem::condense`, docs/theory.md 5.2).

use super::element::rotation::log_so3;
use crate::geometry::Vec3;
use nalgebra::{Matrix3, Matrix6, Vector6};

/// The string above a model's top node, condensed onto it at a reference state: its force on
/// the node linearized in the node's DOF increments from the reference and in the hook load.
/// All in the node's DOF basis (three translations, three rotations; N and N.m per m and rad).
#[derive(Debug, Clone, PartialEq)]
pub struct CondensedTop {
    /// Residual of the part above at the node at the reference (its internal force less its
    /// loads, the part above itself in equilibrium to first order), N and N.m.
    pub force: Vector6<f64>,
    /// Condensed tangent stiffness of the part above at the node (the Schur complement of its
    /// tangent with the contact stiffness of its last linear solve).
    pub stiffness: Matrix6<f64>,
    /// Change of the residual at the node per newton of hook load (the hook load acting at the
    /// top of the part above, transmitted through it), 1.
    pub hook_column: Vector6<f64>,
    /// Reference position of the node (model frame), m.
    pub x0: Vec3,
    /// Reference triad of the node.
    pub triad0: Matrix3<f64>,
    /// Reference hook load, N.
    pub hook_load0_n: f64,
}

impl CondensedTop {
    /// DOF increment (node basis `q`) of a node at `x` (m) with `triad` from the reference:
    /// `q^T (x - x0)` and `q^T log(triad triad0^T)` (the spin the solver's updates apply).
    pub fn increment(&self, q: &Matrix3<f64>, x: &Vec3, triad: &Matrix3<f64>) -> Vector6<f64> {
        let dx = q.transpose() * (x - self.x0);
        let dw = q.transpose() * log_so3(&(triad * self.triad0.transpose()));
        Vector6::new(dx[0], dx[1], dx[2], dw[0], dw[1], dw[2])
    }

    /// The residual of the part above at the node (DOF basis `q`) at `x`, `triad` and the hook
    /// load `hook_load_n`: `force + stiffness du + hook_column (H - H0)`.
    pub fn residual(&self, q: &Matrix3<f64>, x: &Vec3, triad: &Matrix3<f64>, hook_load_n: f64) -> Vector6<f64> {
        self.force + self.stiffness * self.increment(q, x, triad) + self.hook_column * (hook_load_n - self.hook_load0_n)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::models::fem::element::rotation::exp_so3;

    /// A node moved by `q dx` and turned by the spin `q dw` (as the solver's update applies
    /// them) has the increment `(dx, dw)` (reference: the update's own definition; 1e-12), and
    /// the residual is `force + stiffness (dx, dw) + hook_column dH`.
    #[test]
    fn increment_and_residual_follow_the_solver_update() {
        let q = exp_so3(&Vec3::new(0.3, -0.2, 0.5));
        let triad0 = exp_so3(&Vec3::new(-0.1, 0.7, 0.2));
        let top = CondensedTop {
            force: Vector6::new(1.0, -2.0, 3.0, 0.5, -0.25, 4.0),
            stiffness: Matrix6::from_fn(|r, c| {
                if r == c {
                    10.0 + r as f64
                } else {
                    0.1 * (r + 2 * c) as f64
                }
            }),
            hook_column: Vector6::new(1.0, 0.01, -0.02, 0.0, 0.003, 0.0),
            x0: Vec3::new(10.0, -3.0, 2.0),
            triad0,
            hook_load0_n: 5e4,
        };
        let (dx, dw) = (Vec3::new(1e-3, -2e-4, 5e-5), Vec3::new(2e-4, -1e-3, 3e-4));
        let x = top.x0 + q * dx;
        let triad = exp_so3(&(q * dw)) * triad0;
        let inc = top.increment(&q, &x, &triad);
        let want = Vector6::new(dx[0], dx[1], dx[2], dw[0], dw[1], dw[2]);
        assert!((inc - want).amax() < 1e-12, "{inc:?} vs {want:?}");
        assert!((top.residual(&q, &top.x0, &triad0, 5e4) - top.force).amax() < 1e-12);
        let r = top.residual(&q, &x, &triad, 5e4 + 100.0);
        let expected = top.force + top.stiffness * want + top.hook_column * 100.0;
        assert!((r - expected).amax() < 1e-9, "{r:?} vs {expected:?}");
    }
}
