//! Does the string fit the hole? Each component's widest diameter against the hole where it
//! sits, with the bit at a given depth (the case reader at the case's bit depth, the
//! torque-and-drag chart at every depth it computes).

use crate::geometry::HoleSize;
use crate::string::{ComponentKind, DrillString};

/// How much wider than the hole a bit or stabilizer may be (gauge within 1 mm), m.
pub const GAUGE_ALLOWANCE_M: f64 = 1e-3;

/// A component wider than the hole.
#[derive(Debug, Clone, PartialEq)]
pub struct Misfit {
    /// Index of the component from the bit.
    pub component: usize,
    /// The case-file key of the diameter that does not fit: `od` or `tool_joint_od`.
    pub key: &'static str,
    /// The component's widest diameter, m.
    pub widest_m: f64,
    /// The hole's diameter there, m.
    pub hole_m: f64,
    /// Where, m MD.
    pub md_m: f64,
}

/// The first component of `string` (bit at `bit_md_m`, m) wider than `hole` where it sits,
/// checked every metre along it and at its ends; a bit or stabilizer may be
/// [`GAUGE_ALLOWANCE_M`] wider.
pub fn first_misfit(string: &DrillString, hole: &HoleSize, bit_md_m: f64) -> Option<Misfit> {
    for (k, c) in string.components.iter().enumerate() {
        let widest = c.contact_od_m.max(c.tool_joint_od_m.unwrap_or(0.0));
        let allowance = if matches!(c.kind, ComponentKind::Bit | ComponentKind::Stabilizer) {
            GAUGE_ALLOWANCE_M
        } else {
            0.0
        };
        let (top, bottom) = ((bit_md_m - c.top_m()).max(0.0), bit_md_m - c.bottom_m);
        let mut md = top;
        loop {
            let d = hole.diameter_at(md);
            if widest > d + allowance {
                return Some(Misfit {
                    component: k,
                    key: if c.tool_joint_od_m.is_some_and(|t| t > c.contact_od_m) {
                        "tool_joint_od"
                    } else {
                        "od"
                    },
                    widest_m: widest,
                    hole_m: d,
                    md_m: md,
                });
            }
            if md >= bottom {
                break;
            }
            md = (md + 1.0).min(bottom);
        }
    }
    None
}

impl Misfit {
    /// "component `name` (x in) is wider than the hole (y in) at MD z m" for `string`.
    pub fn describe(&self, string: &DrillString) -> String {
        format!(
            "component `{}` ({:.3} in) is wider than the hole ({:.3} in) at MD {:.1} m",
            string.components[self.component].name,
            self.widest_m / 0.0254,
            self.hole_m / 0.0254,
            self.md_m
        )
    }
}
