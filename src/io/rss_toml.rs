//! The rotary steerable system keys of a `[[string]]` component of `type = "rss"`
//! (docs/guide.md, "Rotary steerable systems"): `rss_type`, the push-the-bit pads
//! (`pad_force`, `pad_position`), the point-the-bit hinge (`deflection_angle`,
//! `hinge_position`) and the steering `ratio`.

use super::toml_reader::Section;
use crate::error::InputResult;
use crate::string::{ComponentKind, RssSteer, RssTool, MAX_BEND_ANGLE_RAD};
use crate::units::{message_number, Dimension as D};

/// The keys of an `rss` component.
pub const RSS_KEYS: &[&str] = &[
    "rss_type",
    "pad_force",
    "pad_position",
    "deflection_angle",
    "hinge_position",
    "ratio",
];

/// Largest pad force accepted, N (1 MN: pads push with tens of kN).
pub const MAX_PAD_FORCE_N: f64 = 1e6;

/// `rss_type`: `push-the-bit` (true) or `point-the-bit` (false); `_`, spaces and case ignored.
fn parse_rss_type(s: &str) -> Option<bool> {
    match s.trim().to_ascii_lowercase().replace(['_', ' '], "-").as_str() {
        "push-the-bit" | "push" => Some(true),
        "point-the-bit" | "point" => Some(false),
        _ => None,
    }
}

/// A ratio key `key` of table `c` (a plain number in [0, 1]), None when not given.
pub fn read_ratio(c: &Section, key: &str) -> InputResult<Option<f64>> {
    let Some(r) = c.number(key)? else {
        return Ok(None);
    };
    if !(0.0..=1.0).contains(&r) {
        return Err(c.error(
            key,
            format!(
                "steering ratio {} outside [0, 1] (the share of the time the tool steers at the toolface)",
                message_number(r)
            ),
        ));
    }
    Ok(Some(r))
}

/// The rotary steerable system of component table `c` of kind `kind`, starting `bottom_m`
/// above the bit and `length` long (None: the topmost, filled to the surface). None for a
/// component of another kind without RSS keys; errors name the key (an RSS key on another
/// kind, a missing `rss_type`, a pad force without its position, a deflection on a
/// push-the-bit tool, a position off the component, a ratio outside [0, 1]).
pub fn read_rss(c: &Section, kind: ComponentKind, bottom_m: f64, length: Option<f64>) -> InputResult<Option<RssTool>> {
    if kind != ComponentKind::Rss {
        if let Some(k) = RSS_KEYS.iter().find(|k| c.has(k)) {
            return Err(c.error(k, "only an `rss` component (rotary steerable system) takes this key"));
        }
        return Ok(None);
    }
    let ty = c.string("rss_type")?.ok_or_else(|| {
        c.error(
            "rss_type",
            "missing rss_type (push-the-bit or point-the-bit) on an `rss` component",
        )
    })?;
    let push = parse_rss_type(&ty).ok_or_else(|| {
        c.error(
            "rss_type",
            format!("unknown rss_type `{ty}` (expected push-the-bit or point-the-bit)"),
        )
    })?;
    let (own, other) = if push {
        (["pad_force", "pad_position"], ["deflection_angle", "hinge_position"])
    } else {
        (["deflection_angle", "hinge_position"], ["pad_force", "pad_position"])
    };
    if let Some(k) = other.iter().find(|k| c.has(k)) {
        return Err(c.error(
            k,
            format!(
                "{k} belongs to the other kind of RSS; this one is {}",
                if push { "push-the-bit" } else { "point-the-bit" }
            ),
        ));
    }
    let top = bottom_m + length.unwrap_or(f64::INFINITY);
    let (amount, position) = if push {
        (
            c.positive("pad_force", D::Force, "kN", true)?,
            c.positive("pad_position", D::Length, "m", true)?,
        )
    } else {
        (
            c.positive("deflection_angle", D::Angle, "deg", true)?,
            c.positive("hinge_position", D::Length, "m", true)?,
        )
    };
    let Some(amount) = amount else {
        return Err(c.error(own[0], format!("missing {} on a {ty} rss", own[0])));
    };
    let Some(x) = position else {
        return Err(c.error(
            own[1],
            format!("{} without {} (the distance from the bit face, m)", own[0], own[1]),
        ));
    };
    let limit = if push { MAX_PAD_FORCE_N } else { MAX_BEND_ANGLE_RAD };
    if amount > limit + 1e-12 {
        let (v, l, u) = if push {
            (amount / 1e3, limit / 1e3, "kN")
        } else {
            (amount.to_degrees(), limit.to_degrees(), "deg")
        };
        return Err(c.error(
            own[0],
            format!(
                "{} {} {u} above the largest accepted, {} {u}",
                own[0],
                message_number(v),
                message_number(l)
            ),
        ));
    }
    if x < bottom_m - 1e-9 || x > top + 1e-9 {
        return Err(c.error(
            own[1],
            format!("{x:.3} m from the bit is not on this rss ({bottom_m:.3} to {top:.3} m from the bit)"),
        ));
    }
    let steer = if push {
        RssSteer::PushTheBit {
            pad_force_n: amount,
            pad_to_bit_m: x,
        }
    } else {
        RssSteer::PointTheBit {
            deflection_rad: amount,
            hinge_to_bit_m: x,
        }
    };
    let ratio = read_ratio(c, "ratio")?.unwrap_or(1.0);
    Ok(Some(RssTool { steer, ratio }))
}
