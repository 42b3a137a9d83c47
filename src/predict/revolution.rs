//! The states a steerable string is solved in (the toolfaces over a revolution of a rotating
//! bent housing, the steering and neutral shares of a rotary steerable system), and the means
//! over them (docs/theory.md 9.9, 9.10): the drilling direction is averaged, not the forces.

use crate::case::Case;
use crate::geometry::Vec3;
use crate::models::fem::results::BitResult;

/// Toolfaces over a revolution at which a rotating bent housing is solved (equally spaced from
/// the operation's): the smallest of N = 4, 6, 8, 12, 24, 48 whose rotating tendency is within
/// 0.01 deg/30 m of N = 72 on `wells/horizontal/steered.toml` at 30, 60 and 92.5 deg (largest
/// error 0.0066 deg/30 m at 30 deg; N = 8 gives 0.011) and on the 1.5 deg motor of
/// tests/verification/steering.rs at 30 and 90 deg (0.009; N = 8 gives 0.012 and 0.022)
/// (docs/performance.md, "Toolfaces over a revolution"; `examples/toolface_count.rs`).
pub const ROTATING_TOOLFACES: usize = 12;

/// One state in which the predictor solves a steerable string, and the share of the time the
/// bit drills in it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SteerState {
    /// Toolface of the bent housing or of the rotary steerable system, rad.
    pub toolface_rad: f64,
    /// Share of the time, in (0, 1]; the states of a step sum to 1.
    pub weight: f64,
    /// The rotary steerable system is neutral (no pad force, no deflection): the share of
    /// the time it does not steer ([`crate::string::RssTool::ratio`]).
    pub neutral: bool,
}

/// The states at which `case`'s string is solved: a rotating bent housing at
/// [`ROTATING_TOOLFACES`] toolfaces equally spaced from the operation's; a rotary steerable
/// system steering at the operation's toolface for the share `ratio` of the time and neutral
/// for the rest (a state of zero share left out); else the operation's toolface alone.
pub fn toolfaces(case: &Case) -> Vec<SteerState> {
    toolfaces_n(case, ROTATING_TOOLFACES)
}

/// [`toolfaces`] with `n` toolfaces over a revolution (at least 1) for a rotating bent housing.
pub fn toolfaces_n(case: &Case, n: usize) -> Vec<SteerState> {
    let op = &case.operation;
    let at = |toolface_rad: f64, weight: f64, neutral: bool| SteerState {
        toolface_rad,
        weight,
        neutral,
    };
    if let Some(r) = case.string.rss() {
        return [(r.ratio, false), (1.0 - r.ratio, true)]
            .into_iter()
            .filter(|&(w, _)| w > 0.0)
            .map(|(w, neutral)| at(op.toolface_rad, w, neutral))
            .collect();
    }
    if case.string.bend().is_some() && op.rotates() {
        let n = n.max(1);
        (0..n)
            .map(|k| {
                let tf =
                    (op.toolface_rad + std::f64::consts::TAU * k as f64 / n as f64).rem_euclid(std::f64::consts::TAU);
                at(tf, 1.0 / n as f64, false)
            })
            .collect()
    } else {
        vec![at(op.toolface_rad, 1.0, false)]
    }
}

/// Whether the shares `w` are all equal.
fn equal(w: &[f64]) -> bool {
    w.windows(2).all(|p| p[0] == p[1])
}

/// Mean of the unit drilling directions `d` (global) weighted by the shares `w` (summing to
/// 1), made unit: the direction a bit drills when it spends the share `w[k]` of the time
/// drilling along `d[k]` (the toolfaces of a revolution, an RSS's steering and neutral
/// shares). The first one when there is one.
pub fn mean_direction(d: &[Vec3], w: &[f64]) -> Vec3 {
    if d.len() == 1 {
        return d[0];
    }
    let s: Vec3 = if equal(w) {
        // equal shares (a revolution's toolfaces): the plain sum, no rounding of the weights
        d.iter().sum()
    } else {
        d.iter().zip(w).map(|(d, w)| d * *w).sum()
    };
    s.normalize()
}

/// Mean of the bit results `bits` weighted by the shares `w` (summing to 1) (forces, tilts,
/// torque; the sensor sag of the first): for display only, the drilling direction is
/// averaged, not the forces. The first one when there is one.
pub fn mean_bit(bits: &[BitResult], w: &[f64]) -> BitResult {
    let mut m = bits[0];
    if bits.len() == 1 {
        return m;
    }
    let n = bits.len() as f64;
    let eq = equal(w);
    let mean = |f: fn(&BitResult) -> f64| {
        if eq {
            bits.iter().map(f).sum::<f64>() / n
        } else {
            bits.iter().zip(w).map(|(b, w)| f(b) * w).sum::<f64>()
        }
    };
    m.wob_n = mean(|b| b.wob_n);
    m.build_force_n = mean(|b| b.build_force_n);
    m.walk_force_n = mean(|b| b.walk_force_n);
    m.tilt_inc_rad = mean(|b| b.tilt_inc_rad);
    m.tilt_azi_rad = mean(|b| b.tilt_azi_rad);
    m.torque_nm = mean(|b| b.torque_nm);
    m
}
