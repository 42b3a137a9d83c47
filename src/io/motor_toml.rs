//! The steering keys of a case file: a motor's bent housing (`bend_angle`, `bend_to_bit` on a
//! `[[string]]` component of `type = "motor"`) and the toolface of `[operation]`
//! (docs/guide.md, "Bent motors and toolface").

use super::toml_reader::Section;
use crate::error::InputResult;
use crate::string::{ComponentKind, MotorBend, MAX_BEND_ANGLE_RAD};
use crate::units::Dimension as D;

/// The bent housing of component table `c` of kind `kind`, starting `bottom_m` above the bit
/// and `length` long (None: the topmost, filled to the surface): `bend_angle` (deg) and
/// `bend_to_bit` (m from the bit face, on this component). None without a bend or with a zero
/// bend angle (a straight housing); errors name the key.
pub fn read_bend(
    c: &Section,
    kind: ComponentKind,
    bottom_m: f64,
    length: Option<f64>,
) -> InputResult<Option<MotorBend>> {
    let angle = c.quantity("bend_angle", D::Angle, "deg")?;
    let to_bit = c.quantity("bend_to_bit", D::Length, "m")?;
    if angle.is_none() && to_bit.is_none() {
        return Ok(None);
    }
    let key = if angle.is_some() { "bend_angle" } else { "bend_to_bit" };
    if kind != ComponentKind::Motor {
        return Err(c.error(key, "only a `motor` component has a bent housing"));
    }
    let Some(angle) = angle else {
        return Err(c.error(
            "bend_to_bit",
            "bend_to_bit needs bend_angle (the bend of the housing, deg)",
        ));
    };
    if !(0.0..=MAX_BEND_ANGLE_RAD + 1e-12).contains(&angle) {
        return Err(c.error(
            "bend_angle",
            format!(
                "bend angle {} deg outside [0, {}] deg",
                crate::units::message_number(angle.to_degrees()),
                crate::units::message_number(MAX_BEND_ANGLE_RAD.to_degrees())
            ),
        ));
    }
    let Some(x) = to_bit else {
        return Err(c.error(
            "bend_to_bit",
            "missing bend_to_bit (the distance from the bit face to the bend, m)",
        ));
    };
    let top = bottom_m + length.unwrap_or(f64::INFINITY);
    if x < bottom_m - 1e-9 || x > top + 1e-9 {
        return Err(c.error(
            "bend_to_bit",
            format!("{x:.3} m from the bit is not on this motor ({bottom_m:.3} to {top:.3} m from the bit)"),
        ));
    }
    Ok((angle > 0.0).then_some(MotorBend {
        angle_rad: angle,
        to_bit_m: x,
    }))
}

/// `[operation] toolface` in rad, in [0, 2 pi) (0 without the key): gravity toolface from the
/// high side, positive to the right; magnetic (from north) where the hole is near vertical
/// ([`crate::geometry::frame::MAGNETIC_TOOLFACE_BELOW_RAD`]).
pub fn read_toolface(s: &Section) -> InputResult<f64> {
    let tf = s.quantity("toolface", D::Angle, "deg")?.unwrap_or(0.0);
    Ok(tf.rem_euclid(std::f64::consts::TAU))
}
