//! The motor's reactive torque turning a sliding bent housing's toolface (docs/theory.md 9.9,
//! "Reactive torque"; `[operation] reactive_torque`, off by default).
//!
//! The motor drives the bit clockwise (seen from above); the rock's torque on the bit, the
//! motor's torque `T`, reacts on the stator and turns the housing and the non-rotating string
//! above it to the left. The wall's friction takes the torque up: each contact holds at most
//! `μ N r` (its normal force `N`, friction `μ`, contact radius `r`). The housing below the bend
//! turns as one piece with its contacts; above the bend the torque falls by each contact's
//! capacity until the wall has taken it all (the string above does not turn), and the toolface
//! turns left by the twist between: `Δ = ∫ T(s) / (G J(s)) ds` from the bend up.

use crate::case::Case;
use crate::string::DrillString;

/// A piece of the string above the bit for the torque's path beyond a model's top, SI.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TorquePiece {
    /// Distance from the bit face to the piece's bottom, m.
    pub bottom_m: f64,
    /// Distance from the bit face to the piece's top, m.
    pub top_m: f64,
    /// Torsional stiffness G J, N.m2.
    pub gj_nm2: f64,
    /// The wall's friction torque capacity per length, N.m/m: `μ w_b sin(inc) r`, the string
    /// lying on the low side under its buoyed weight `w_b` (no tension or curvature terms).
    pub capacity_nm_per_m: f64,
}

/// The reactive torque of a sliding bent housing: the motor's torque and the string above
/// the bit for the part of its path above a cut model's top.
#[derive(Debug, Clone, PartialEq)]
pub struct ReactiveTorque {
    /// The motor's torque, N.m (> 0): [`crate::models::bit::motor_torque_nm`] at the case's WOB.
    pub torque_nm: f64,
    /// The string from the bit to the surface in pieces of at most [`PIECE_M`].
    pub string: Vec<TorquePiece>,
}

/// The turn of the toolface by the reactive torque in a solved state
/// (`Model::reactive_turn`, `models::fem::solve::reactive_turn`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ReactiveTurn {
    /// The motor's torque, N.m.
    pub torque_nm: f64,
    /// The toolface's turn to the left (counter-clockwise seen from above), rad (>= 0).
    pub turn_rad: f64,
    /// Distance from the bit face to where the wall has taken up the torque, m (None: not
    /// within the string; the rotary table holds the rest).
    pub held_m: Option<f64>,
}

/// Longest piece of [`ReactiveTorque::string`], m.
pub const PIECE_M: f64 = 10.0;

/// The reactive torque of `case` with `string` (bit first) and the bit at `bit_md_m`: Some
/// when `[operation] reactive_torque` is on, the string slides (does not rotate) on bottom,
/// it has a bent housing and the motor's torque is positive.
pub fn reactive_torque(case: &Case, string: &DrillString, bit_md_m: f64) -> Option<ReactiveTorque> {
    let op = &case.operation;
    if !op.reactive_torque || op.rotates() || !op.mode.on_bottom() || string.bend().is_none() {
        return None;
    }
    let torque_nm = crate::models::bit::motor_torque_nm(case, op.wob_n);
    if torque_nm <= 0.0 {
        return None;
    }
    let mut pieces = Vec::new();
    let full = string.at_depth(bit_md_m);
    for c in &full.components {
        let n = (c.length_m / PIECE_M).ceil().max(1.0) as usize;
        let h = c.length_m / n as f64;
        for k in 0..n {
            let (bottom_m, top_m) = (c.bottom_m + h * k as f64, c.bottom_m + h * (k + 1) as f64);
            let md = bit_md_m - 0.5 * (bottom_m + top_m);
            let inc = case.well.path.point_at(md).inc_rad;
            let mu = case.well.hole.friction_at(md).unwrap_or(op.friction);
            let r = c.tool_joint_od_m.unwrap_or(c.contact_od_m).max(c.body_od_m) / 2.0;
            pieces.push(TorquePiece {
                bottom_m,
                top_m,
                gj_nm2: c.gj_nm2(),
                capacity_nm_per_m: mu * c.buoyed_weight_n_per_m(case.mud.density_kg_m3) * inc.sin() * r,
            });
        }
    }
    Some(ReactiveTorque {
        torque_nm,
        string: pieces,
    })
}
