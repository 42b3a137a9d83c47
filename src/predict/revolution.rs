//! The toolfaces over a revolution of a rotating bent housing, and the means over them
//! (docs/theory.md 9.9): the drilling direction is averaged, not the forces.

use crate::case::Case;
use crate::geometry::Vec3;
use crate::models::fem::results::BitResult;

/// Toolfaces over a revolution at which a rotating bent housing is solved (equally spaced from
/// the operation's). Measured on the 1.5 deg motor of tests/verification/steering.rs at 30 and
/// 90 deg inclination (docs/theory.md, "Bent motors"): against 72 toolfaces, the rotating
/// tendency is within 0.006 deg/30 m for every number tested from 18 to 48, within 0.009 at 12
/// but 0.016 at 16 (contacts that open and close as the housing turns make the mean converge
/// unevenly); 24 keeps a margin under 0.01 deg/30 m.
pub const ROTATING_TOOLFACES: usize = 24;

/// The toolfaces (rad) at which `case`'s string is solved: [`ROTATING_TOOLFACES`] equally
/// spaced from the operation's toolface when the string has a bent housing and rotates, else
/// the operation's toolface alone.
pub fn toolfaces(case: &Case) -> Vec<f64> {
    toolfaces_n(case, ROTATING_TOOLFACES)
}

/// [`toolfaces`] with `n` toolfaces over a revolution (at least 1) for a rotating bent housing.
pub fn toolfaces_n(case: &Case, n: usize) -> Vec<f64> {
    let op = &case.operation;
    if case.string.bend().is_some() && op.rotates() {
        let n = n.max(1);
        (0..n)
            .map(|k| (op.toolface_rad + std::f64::consts::TAU * k as f64 / n as f64).rem_euclid(std::f64::consts::TAU))
            .collect()
    } else {
        vec![op.toolface_rad]
    }
}

/// Mean of the unit drilling directions `d` (global), made unit: the direction a bit drills
/// when it turns through them at a steady rate. The first one when there is one.
pub fn mean_direction(d: &[Vec3]) -> Vec3 {
    if d.len() == 1 {
        return d[0];
    }
    let s: Vec3 = d.iter().sum();
    s.normalize()
}

/// Mean of the bit results `bits` over a revolution (forces, tilts, torque; the sensor sag of
/// the first): for display only, the drilling direction is averaged, not the forces. The
/// first one when there is one.
pub fn mean_bit(bits: &[BitResult]) -> BitResult {
    let mut m = bits[0];
    if bits.len() == 1 {
        return m;
    }
    let n = bits.len() as f64;
    let mean = |f: fn(&BitResult) -> f64| bits.iter().map(f).sum::<f64>() / n;
    m.wob_n = mean(|b| b.wob_n);
    m.build_force_n = mean(|b| b.build_force_n);
    m.walk_force_n = mean(|b| b.walk_force_n);
    m.tilt_inc_rad = mean(|b| b.tilt_inc_rad);
    m.tilt_azi_rad = mean(|b| b.tilt_azi_rad);
    m.torque_nm = mean(|b| b.torque_nm);
    m
}
