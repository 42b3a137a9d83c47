//! The bit's own loads, shared by every model (soft string, stiff FEM, every fidelity).

use crate::case::{Case, Mode};

/// Bit torque of `case`'s operation at weight on bit `wob_n` (N), N.m, in the sense of rotation:
///
/// - the case's `bit_torque` when given, on bottom (drilling; sliding, where it is the
///   motor's reactive torque carried by the string);
/// - else, drilling: Pessier & Fear (1992) `T_b = mu_b WOB D_b / 3`, with `mu_b` the case's
///   `bit_friction` and `D_b` the bit diameter (the hole diameter at the bit when the string
///   has no bit component);
/// - else 0 (sliding without a given torque, and off bottom).
pub fn bit_torque_nm(case: &Case, wob_n: f64) -> f64 {
    let op = &case.operation;
    match op.mode {
        Mode::Drilling => motor_torque_nm(case, wob_n),
        Mode::Sliding => op.bit_torque_nm.unwrap_or(0.0),
        Mode::RotatingOffBottom | Mode::TripIn | Mode::TripOut => 0.0,
    }
}

/// Torque of the rock on a turning bit at weight on bit `wob_n` (N), N.m: the case's
/// `bit_torque` when given, else Pessier & Fear (1992) `T_b = mu_b WOB D_b / 3`, whatever the
/// mode. Sliding, the motor turns the bit and this is the reactive torque on its housing
/// ([`crate::models::fem::reactive`]).
pub fn motor_torque_nm(case: &Case, wob_n: f64) -> f64 {
    case.operation
        .bit_torque_nm
        .unwrap_or_else(|| case.bit_rock.bit_friction * wob_n * bit_diameter_m(case) / 3.0)
}

/// Diameter the bit drills, m: the bit component's, else the hole's at the bit.
pub fn bit_diameter_m(case: &Case) -> f64 {
    case.string
        .bit_diameter_m()
        .unwrap_or_else(|| case.well.hole.diameter_at(case.operation.bit_md_m))
}
