//! Finite rotations: exponential and logarithm maps of SO(3) and the inverse tangent operator.
//!
//! Nodal triads are updated multiplicatively, `R <- exp(dw) R` with `dw` a spatial spin
//! (docs/theory.md 5.3), never by adding rotation vectors.

use nalgebra::Matrix3;

use crate::geometry::Vec3;

/// Skew-symmetric matrix of `v` (so that `skew(v) x = v x x`).
pub fn skew(v: &Vec3) -> Matrix3<f64> {
    Matrix3::new(0.0, -v.z, v.y, v.z, 0.0, -v.x, -v.y, v.x, 0.0)
}

/// Rotation matrix of the rotation vector `theta` (Rodrigues).
pub fn exp_so3(theta: &Vec3) -> Matrix3<f64> {
    let a = theta.norm();
    let k = skew(theta);
    let (c1, c2) = if a < 1e-6 {
        (1.0 - a * a / 6.0, 0.5 - a * a / 24.0)
    } else {
        (a.sin() / a, (1.0 - a.cos()) / (a * a))
    };
    Matrix3::identity() + k * c1 + k * k * c2
}

/// Rotation vector of a rotation matrix (angle < pi), robust for small angles.
#[inline(always)]
pub fn log_so3(r: &Matrix3<f64>) -> Vec3 {
    let v = Vec3::new(r[(2, 1)] - r[(1, 2)], r[(0, 2)] - r[(2, 0)], r[(1, 0)] - r[(0, 1)]) * 0.5;
    let s = v.norm();
    let c = 0.5 * (r.trace() - 1.0);
    let a = s.atan2(c);
    if s < 1e-12 {
        v
    } else {
        v * (a / s)
    }
}

/// Inverse of the tangent operator T_s: `d(theta) = T_s^-1(theta) dw` for a spatial spin `dw`
/// of `R = exp(theta)` (Battini & Pacoste 2002):
/// `T_s^-1 = I - Theta/2 + (1 - (a/2) cot(a/2)) / a^2 Theta^2`.
#[inline(always)]
pub fn tangent_inverse(theta: &Vec3) -> Matrix3<f64> {
    let a = theta.norm();
    let k = skew(theta);
    let eta = if a < 1e-4 {
        1.0 / 12.0 + a * a / 720.0
    } else {
        (1.0 - 0.5 * a / (0.5 * a).tan()) / (a * a)
    };
    Matrix3::identity() - k * 0.5 + k * k * eta
}

/// Re-orthonormalize a near-rotation matrix (columns), keeping the first column's direction.
pub fn orthonormalize(r: &Matrix3<f64>) -> Matrix3<f64> {
    let c0 = r.column(0).normalize();
    let c1 = (r.column(1) - c0 * c0.dot(&r.column(1))).normalize();
    let c2 = c0.cross(&c1);
    Matrix3::from_columns(&[c0, c1, c2])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn exp_log_roundtrip() {
        for v in [
            Vec3::new(0.1, -0.2, 0.3),
            Vec3::new(1e-9, 0.0, 2e-9),
            Vec3::new(2.0, 1.0, -0.5),
        ] {
            let r = exp_so3(&v);
            assert!((r.transpose() * r - Matrix3::identity()).norm() < 1e-13);
            assert!((log_so3(&r) - v).norm() < 1e-12);
        }
    }

    #[test]
    fn tangent_inverse_matches_finite_differences() {
        // d log(exp(h e_k) R) / dh at h = 0 equals column k of T_s^-1(theta).
        let th = Vec3::new(0.3, -0.4, 0.2);
        let r = exp_so3(&th);
        let ti = tangent_inverse(&th);
        let h = 1e-6;
        for k in 0..3 {
            let mut e = Vec3::zeros();
            e[k] = h;
            let fd = (log_so3(&(exp_so3(&e) * r)) - log_so3(&(exp_so3(&(-e)) * r))) / (2.0 * h);
            assert!(
                (fd - ti.column(k)).norm() < 1e-8,
                "column {k}: {fd} vs {}",
                ti.column(k)
            );
        }
    }
}
