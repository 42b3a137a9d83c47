//! Bit-rock interaction: the direction the bit drills from the forces on it, its tilt and the
//! formation (docs/theory.md 9.3, Ho-type anisotropic drillability law, full vector form).
//!
//! ```text
//! F    = W t + F_b h + F_w r                 bit on rock, hole frame at the bit
//! e_b  = unit(t + tan(theta_inc) h + tan(theta_azi) r)      bit axis
//! F_ax = (F.e_b) e_b,  F_lat = F - F_ax
//! d_b  = F_ax + beta_b R(e_b, chi_w) F_lat    bit anisotropy (beta_b = 1: isotropic)
//! d    = (1 - I_r) d_b + I_r (d_b.n_f) n_f    rock anisotropy, n_f the bedding normal
//! ```
//! `beta_b = 1, I_r = 0` drills along the resultant force; `beta_b -> 0` drills along the bit
//! axis. `I_r > 0` drills more easily normal to the bedding (up-dip tendency).

use crate::case::BitRock;
use crate::geometry::{Frame, Vec3};
use nalgebra::{Rotation3, Unit};

/// Parameters of the law at one depth.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LawParams {
    /// Lateral/axial bit drillability ratio beta_b in (0, 1] (1 - Ho's bit anisotropy index, to
    /// our reading).
    pub lateral_drillability: f64,
    /// Bit walk angle chi_w, rad (rotation of the lateral drilling about the bit axis; positive
    /// turns a build tendency to the right).
    pub walk_angle_rad: f64,
    /// Rock anisotropy index I_r (dimensionless, 0 = isotropic).
    pub rock_anisotropy: f64,
    /// Bedding dip, rad.
    pub dip_rad: f64,
    /// Dip direction (azimuth of steepest descent), rad.
    pub dip_direction_rad: f64,
}

impl LawParams {
    /// The case's parameters at bit depth `md_m` (the formation interval holding it, else the
    /// `[bit_rock]` defaults).
    pub fn at(bit_rock: &BitRock, md_m: f64) -> LawParams {
        let mut p = LawParams {
            lateral_drillability: bit_rock.lateral_drillability,
            walk_angle_rad: bit_rock.walk_angle_rad,
            rock_anisotropy: bit_rock.rock_anisotropy,
            dip_rad: bit_rock.dip_rad,
            dip_direction_rad: bit_rock.dip_direction_rad,
        };
        if let Some(f) = bit_rock
            .formations
            .iter()
            .find(|f| md_m >= f.from_md_m && md_m < f.to_md_m)
        {
            p.rock_anisotropy = f.rock_anisotropy;
            p.dip_rad = f.dip_rad;
            p.dip_direction_rad = f.dip_direction_rad;
        }
        p
    }
}

/// What the bit does: forces of the bit on the rock (N) and tilt of its axis (rad) in the hole
/// frame at the bit (docs/guide.md sign conventions).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BitAction {
    /// Weight on bit (along t), N.
    pub wob_n: f64,
    /// Build force (along h), N.
    pub build_force_n: f64,
    /// Walk force (along r), N.
    pub walk_force_n: f64,
    /// Tilt toward higher inclination, rad.
    pub tilt_inc_rad: f64,
    /// Tilt to the right, rad.
    pub tilt_azi_rad: f64,
}

/// Unit normal to bedding dipping `dip_rad` toward azimuth `dip_direction_rad`, in (north,
/// east, down) coordinates, pointing down and up-dip (docs/theory.md 9.3).
pub fn bedding_normal(dip_rad: f64, dip_direction_rad: f64) -> Vec3 {
    let (sd, cd) = dip_rad.sin_cos();
    Vec3::new(-sd * dip_direction_rad.cos(), -sd * dip_direction_rad.sin(), cd)
}

/// Unit drilling direction (global, north-east-down) of the Ho-type law for a bit acting as
/// `bit` in the hole frame `frame`. Falls back to the bit axis when the force vanishes
/// (no WOB and no side force).
pub fn drilling_direction(frame: &Frame, bit: &BitAction, p: &LawParams) -> Vec3 {
    let eb = (frame.t + frame.h * bit.tilt_inc_rad.tan() + frame.r * bit.tilt_azi_rad.tan()).normalize();
    let f = frame.t * bit.wob_n + frame.h * bit.build_force_n + frame.r * bit.walk_force_n;
    let f_ax = eb * f.dot(&eb);
    let f_lat = f - f_ax;
    let rot = Rotation3::from_axis_angle(&Unit::new_normalize(eb), p.walk_angle_rad);
    let d_b = f_ax + (rot * f_lat) * p.lateral_drillability;
    let nf = bedding_normal(p.dip_rad, p.dip_direction_rad);
    let d = d_b * (1.0 - p.rock_anisotropy) + nf * (p.rock_anisotropy * d_b.dot(&nf));
    // the bit drills forward: a direction against the hole tangent means no usable force
    if d.norm() < 1e-9 * (1.0 + f.norm()) || d.dot(&frame.t) <= 0.0 {
        return eb;
    }
    d.normalize()
}

/// Deviation of the drilling direction from the hole tangent toward h and r, rad.
pub fn deviation(frame: &Frame, d: &Vec3) -> (f64, f64) {
    let dt = d.dot(&frame.t);
    (d.dot(&frame.h).atan2(dt), d.dot(&frame.r).atan2(dt))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::frame::tangent;

    fn frame(inc_deg: f64, azi_deg: f64) -> Frame {
        Frame::from_tangent(&tangent(inc_deg.to_radians(), azi_deg.to_radians()), 0.0)
    }

    fn iso(beta: f64) -> LawParams {
        LawParams {
            lateral_drillability: beta,
            walk_angle_rad: 0.0,
            rock_anisotropy: 0.0,
            dip_rad: 0.0,
            dip_direction_rad: 0.0,
        }
    }

    #[test]
    fn resultant_force_law_and_small_angle_form() {
        // docs/theory.md 9.3 small-angle form: psi_h = (1-beta) theta + beta F_b/W (I_r = 0)
        let fr = frame(20.0, 40.0);
        let bit = BitAction {
            wob_n: 100e3,
            build_force_n: -1.68e3,
            walk_force_n: 0.5e3,
            tilt_inc_rad: 0.0051,
            tilt_azi_rad: -0.001,
        };
        for beta in [0.1, 0.2, 0.5, 1.0] {
            let d = drilling_direction(&fr, &bit, &iso(beta));
            let (ph, pr) = deviation(&fr, &d);
            let eh = (1.0 - beta) * 0.0051 + beta * (-0.0168);
            let er = (1.0 - beta) * (-0.001) + beta * 0.005;
            // second-order terms of size theta * F/W ~ 1e-4 of the angles
            assert!((ph - eh).abs() < 2e-5, "beta {beta}: {ph} vs {eh}");
            assert!((pr - er).abs() < 2e-5, "beta {beta}: {pr} vs {er}");
        }
        // docs/theory.md 9.3 worked values for the pendulum: +0.0029, +0.0007, -0.0059, -0.0168 rad
        let bit = BitAction {
            wob_n: 100e3,
            build_force_n: -1.68e3,
            walk_force_n: 0.0,
            tilt_inc_rad: 0.0051,
            tilt_azi_rad: 0.0,
        };
        for (beta, want) in [(0.1, 0.0029), (0.2, 0.0007), (0.5, -0.0059), (1.0, -0.0168)] {
            let (ph, _) = deviation(&fr, &drilling_direction(&fr, &bit, &iso(beta)));
            assert!((ph - want).abs() < 1.5e-4, "beta {beta}: {ph} vs {want}");
        }
    }

    #[test]
    fn rock_anisotropy_pulls_toward_the_bedding_normal() {
        // bit drilling along the hole axis with no side force; bedding dipping 30 deg toward
        // north, hole at 45 deg toward north (drilling down-dip): the angle between the hole and
        // the (down, up-dip pointing) normal is 45 + 30 = 75 deg; its tangent shrinks by (1-I_r)
        let fr = frame(45.0, 0.0);
        let bit = BitAction {
            wob_n: 100e3,
            build_force_n: 0.0,
            walk_force_n: 0.0,
            tilt_inc_rad: 0.0,
            tilt_azi_rad: 0.0,
        };
        let mut p = iso(1.0);
        p.dip_rad = 30f64.to_radians();
        p.dip_direction_rad = 0.0;
        let nf = bedding_normal(p.dip_rad, p.dip_direction_rad);
        for ir in [0.0, 0.01, 0.05, 0.1] {
            p.rock_anisotropy = ir;
            let d = drilling_direction(&fr, &bit, &p);
            // angle to the normal: tan(phi_d) = (1 - I_r) tan(phi) (the form docs/theory.md 9.3 reads)
            let phi = fr.t.dot(&nf).acos();
            let phi_d = d.dot(&nf).acos();
            assert!(((phi_d.tan()) - (1.0 - ir) * phi.tan()).abs() < 1e-9 * phi.tan().abs().max(1.0));
            // the direction stays in the vertical plane (no walk), and builds toward the normal
            let (ph, pr) = deviation(&fr, &d);
            assert!(pr.abs() < 1e-12);
            if ir == 0.0 {
                assert!(ph.abs() < 1e-12);
            } else {
                // n_f.h < 0 here: the normal (toward vertical, up-dip) lies on the low side, so
                // the hole drops toward it, i.e. turns up-dip
                assert!(ph < 0.0, "I_r {ir}: {ph}");
                // small-angle form of docs/theory.md 9.3: psi_h = I_r (n.t)(n.h) = -(I_r/2) sin 2phi
                if ir <= 0.01 {
                    let want = ir * nf.dot(&fr.t) * nf.dot(&fr.h);
                    assert!((want + ir / 2.0 * (2.0 * phi).sin()).abs() < 1e-12);
                    assert!((ph - want).abs() < 0.02 * want.abs(), "{ph} vs {want}");
                }
            }
        }
    }

    #[test]
    fn walk_angle_rotates_the_lateral_drilling_to_the_right() {
        let fr = frame(30.0, 100.0);
        let bit = BitAction {
            wob_n: 80e3,
            build_force_n: 2e3,
            walk_force_n: 0.0,
            tilt_inc_rad: 0.0,
            tilt_azi_rad: 0.0,
        };
        let mut p = iso(1.0);
        p.walk_angle_rad = 10f64.to_radians();
        let (ph, pr) = deviation(&fr, &drilling_direction(&fr, &bit, &p));
        let psi = 2e3 / 80e3;
        assert!((ph - psi * 10f64.to_radians().cos()).abs() < 1e-4);
        assert!((pr - psi * 10f64.to_radians().sin()).abs() < 1e-4 && pr > 0.0);
    }

    #[test]
    fn vanishing_force_drills_along_the_bit_axis() {
        let fr = frame(10.0, 0.0);
        let bit = BitAction {
            wob_n: 0.0,
            build_force_n: 0.0,
            walk_force_n: 0.0,
            tilt_inc_rad: 0.01,
            tilt_azi_rad: 0.0,
        };
        let d = drilling_direction(&fr, &bit, &iso(1.0));
        let (ph, _) = deviation(&fr, &d);
        assert!((ph - 0.01).abs() < 1e-9);
    }
}
