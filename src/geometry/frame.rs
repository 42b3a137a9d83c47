//! The borehole frame (t, h, r) and small vector helpers.
//!
//! Global frame NED: x = north, y = east, z = true vertical depth (down); gravity along +z.
//! `t` is the unit tangent down the hole, `h` the high side (perpendicular to `t`, pointing
//! up-hole in the vertical plane through `t`), `r = t x h` the right side (toward increasing
//! azimuth). docs/theory.md 2.4; docs/guide.md, Conventions.

use nalgebra::Vector3;

/// 3-vector of f64 (global NED components unless stated otherwise).
pub type Vec3 = Vector3<f64>;

/// Below this value of sin(inclination) a direction counts as vertical and the high side is
/// taken from a reference azimuth instead of the tangent.
pub const VERTICAL_SIN_INC: f64 = 1e-6;

/// Unit tangent from inclination and azimuth (rad): (sin I cos A, sin I sin A, cos I).
pub fn tangent(inc_rad: f64, azi_rad: f64) -> Vec3 {
    let (si, ci) = inc_rad.sin_cos();
    let (sa, ca) = azi_rad.sin_cos();
    Vec3::new(si * ca, si * sa, ci)
}

/// Inclination (rad, [0, pi]) and azimuth (rad, [0, 2 pi)) of a direction; the azimuth of a
/// vertical direction is `fallback_azi_rad`.
pub fn inc_azi(t: &Vec3, fallback_azi_rad: f64) -> (f64, f64) {
    let n = t.norm();
    let (x, y, z) = (t.x / n, t.y / n, t.z / n);
    let horiz = (x * x + y * y).sqrt();
    let inc = horiz.atan2(z);
    let azi = if horiz < VERTICAL_SIN_INC {
        fallback_azi_rad
    } else {
        crate::geometry::survey::normalize_azimuth(y.atan2(x))
    };
    (inc, azi)
}

/// Orthonormal borehole frame at a point of the hole axis.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Frame {
    /// Tangent, down the hole.
    pub t: Vec3,
    /// High side.
    pub h: Vec3,
    /// Right side, `t x h`.
    pub r: Vec3,
}

impl Frame {
    /// Frame of the unit tangent `t`. Where the hole is vertical (sin I < [`VERTICAL_SIN_INC`])
    /// `h` points toward `ref_azi_rad` (at inclination 0; away from it at 180 deg), as
    /// docs/guide.md prescribes.
    pub fn from_tangent(t: &Vec3, ref_azi_rad: f64) -> Frame {
        let t = t.normalize();
        let horiz = (t.x * t.x + t.y * t.y).sqrt();
        let h = if horiz >= VERTICAL_SIN_INC {
            // h = dt/dI = (cos I cos A, cos I sin A, -sin I) = -(e_D - (e_D.t) t)/sin I
            let ed = Vec3::new(0.0, 0.0, 1.0);
            -(ed - t * t.z) / horiz
        } else {
            let (sa, ca) = ref_azi_rad.sin_cos();
            let ci = t.z.signum();
            // (cos I cos A, cos I sin A, -sin I) with sin I ~ 0, then made exactly orthogonal to t
            let h0 = Vec3::new(ci * ca, ci * sa, 0.0);
            (h0 - t * t.dot(&h0)).normalize()
        };
        let r = t.cross(&h);
        Frame { t, h, r }
    }

    /// Frame from inclination and azimuth (rad); the azimuth also serves as reference when vertical.
    pub fn from_inc_azi(inc_rad: f64, azi_rad: f64) -> Frame {
        Frame::from_tangent(&tangent(inc_rad, azi_rad), azi_rad)
    }
}

/// Inclination below which a toolface is read as magnetic toolface (from north) instead of
/// gravity toolface (from the high side), rad: 5 deg, where the high side of a survey tool
/// becomes poorly defined (MWD tools switch near there).
pub const MAGNETIC_TOOLFACE_BELOW_RAD: f64 = 5.0 * std::f64::consts::PI / 180.0;

/// Unit direction perpendicular to the hole tangent `t` that toolface `toolface_rad` (rad)
/// points to, global: `cos(tf) h + sin(tf) r` (gravity toolface, from the high side `h`,
/// positive toward the right side `r = t x h`) when the inclination is at least
/// [`MAGNETIC_TOOLFACE_BELOW_RAD`]; below it `cos(tf) n + sin(tf) t x n` with `n` north made
/// perpendicular to `t` (magnetic toolface, from the survey's north).
pub fn toolface_direction(t: &Vec3, toolface_rad: f64) -> Vec3 {
    let t = t.normalize();
    let (s, c) = toolface_rad.sin_cos();
    let inc = (t.x * t.x + t.y * t.y).sqrt().atan2(t.z);
    if inc >= MAGNETIC_TOOLFACE_BELOW_RAD {
        let f = Frame::from_tangent(&t, 0.0);
        f.h * c + f.r * s
    } else {
        let north = Vec3::new(1.0, 0.0, 0.0);
        let n = (north - t * t.dot(&north)).normalize();
        n * c + t.cross(&n) * s
    }
}

/// Rotate `v` about the unit axis `a` by `angle` rad (Rodrigues).
pub fn rotate_about(v: &Vec3, a: &Vec3, angle: f64) -> Vec3 {
    let (s, c) = angle.sin_cos();
    v * c + a.cross(v) * s + a * (a.dot(v) * (1.0 - c))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn assert_orthonormal(f: &Frame) {
        assert!((f.t.norm() - 1.0).abs() < 1e-12);
        assert!((f.h.norm() - 1.0).abs() < 1e-12);
        assert!((f.r.norm() - 1.0).abs() < 1e-12);
        assert!(f.t.dot(&f.h).abs() < 1e-12);
        assert!(f.t.dot(&f.r).abs() < 1e-12);
        assert!((f.t.cross(&f.h) - f.r).norm() < 1e-12);
    }

    /// Gravity toolface from the high side toward the right; magnetic (from north, toward
    /// east) within 5 deg of vertical.
    #[test]
    fn toolface_directions() {
        let t = tangent(30f64.to_radians(), 45f64.to_radians());
        let f = Frame::from_tangent(&t, 0.0);
        let hp = std::f64::consts::FRAC_PI_2;
        assert!((toolface_direction(&t, 0.0) - f.h).norm() < 1e-12);
        assert!((toolface_direction(&t, hp) - f.r).norm() < 1e-12);
        assert!((toolface_direction(&t, std::f64::consts::PI) + f.h).norm() < 1e-12);
        let v = tangent(2f64.to_radians(), 200f64.to_radians());
        let n = toolface_direction(&v, 0.0);
        let e = toolface_direction(&v, hp);
        assert!(n.x > 0.999 && n.dot(&v).abs() < 1e-12, "{n:?}");
        assert!(e.y > 0.999 && e.dot(&v).abs() < 1e-12, "{e:?}");
        let down = Vec3::new(0.0, 0.0, 1.0);
        assert!((toolface_direction(&down, 0.0) - Vec3::new(1.0, 0.0, 0.0)).norm() < 1e-12);
    }

    #[test]
    fn frame_matches_physics_formulas() {
        // docs/theory.md 2.4: h = (cos I cos A, cos I sin A, -sin I), r = (-sin A, cos A, 0).
        let (i, a) = (0.7_f64, 2.1_f64);
        let f = Frame::from_inc_azi(i, a);
        assert_orthonormal(&f);
        assert!((f.h - Vec3::new(i.cos() * a.cos(), i.cos() * a.sin(), -i.sin())).norm() < 1e-12);
        assert!((f.r - Vec3::new(-a.sin(), a.cos(), 0.0)).norm() < 1e-12);
    }

    #[test]
    fn vertical_frames_use_reference_azimuth() {
        let f = Frame::from_inc_azi(0.0, 90f64.to_radians());
        assert_orthonormal(&f);
        // h toward east, r = t x h = down x east = -north... check r = (-sin A, cos A, 0)
        assert!((f.h - Vec3::new(0.0, 1.0, 0.0)).norm() < 1e-12);
        assert!((f.r - Vec3::new(-1.0, 0.0, 0.0)).norm() < 1e-12);
        let f = Frame::from_inc_azi(std::f64::consts::PI, 0.0);
        assert_orthonormal(&f);
    }

    #[test]
    fn inc_azi_roundtrip() {
        for &(i, a) in &[(0.3, 0.2), (1.5, 6.0), (2.9, 3.3)] {
            let (i2, a2) = inc_azi(&tangent(i, a), 0.0);
            assert!((i - i2).abs() < 1e-12 && (a - a2).abs() < 1e-12);
        }
        assert_eq!(inc_azi(&Vec3::new(0.0, 0.0, 1.0), 1.25), (0.0, 1.25));
    }
}
