//! BHA schematic: components drawn to scale along the string (distance from the bit) with their
//! diameters to scale on a separate radial axis, inside the hole wall.

use super::display_units::UnitSystem;
use super::plots::{render_blocks, Block, Chart, Series, Style};
use crate::string::{ComponentKind, DrillString};

/// Extra string drawn above the BHA's top, m.
pub const ABOVE_BHA_M: f64 = 10.0;

fn color(kind: ComponentKind) -> usize {
    match kind {
        ComponentKind::Bit => 6,
        ComponentKind::Stabilizer => 1,
        ComponentKind::Collar => 0,
        ComponentKind::Pipe | ComponentKind::Hwdp => 7,
        _ => 2,
    }
}

/// Length of string shown in the schematic: the BHA plus [`ABOVE_BHA_M`], at most the string, m.
pub fn shown_length_m(string: &DrillString) -> f64 {
    (string.bha_length_m() + ABOVE_BHA_M).min(string.length_m())
}

/// SVG of the bottom of `string` in a hole of `hole_diameter_m`.
pub fn bha_svg(string: &DrillString, hole_diameter_m: f64, units: UnitSystem) -> Result<String, String> {
    let (depth_unit, small_unit) = (units.depth(), units.small_length());
    let len = shown_length_m(string);
    let mut blocks = Vec::new();
    for c in &string.components {
        if c.bottom_m >= len {
            break;
        }
        let x0 = depth_unit.show(c.bottom_m);
        let x1 = depth_unit.show(c.top_m().min(len));
        let body = small_unit.show(c.body_od_m / 2.0);
        blocks.push(Block {
            from: (x0, -body),
            to: (x1, body),
            color: color(c.kind),
        });
        if c.contact_od_m > c.body_od_m + 1e-9 {
            // blades (or bit) over the middle 60 % of the component
            let r = small_unit.show(c.contact_od_m / 2.0);
            let (a, b) = (x0 + 0.2 * (x1 - x0), x0 + 0.8 * (x1 - x0));
            blocks.push(Block {
                from: (a, body),
                to: (b, r),
                color: color(c.kind),
            });
            blocks.push(Block {
                from: (a, -r),
                to: (b, -body),
                color: color(c.kind),
            });
        }
    }
    let r = small_unit.show(hole_diameter_m / 2.0);
    let xe = depth_unit.show(len);
    let mut chart = Chart::new(
        "BHA schematic (lengths to scale along the string, diameters to scale across)",
        &format!("distance from the bit [{}]", depth_unit.label),
        &format!("radius [{}]", small_unit.label),
    )
    .with(Series::new("hole wall", vec![(0.0, r), (xe, r)], Style::Thin, 6))
    .with(Series::new(
        "hole wall (low)",
        vec![(0.0, -r), (xe, -r)],
        Style::Thin,
        6,
    ));
    chart.size = (860, 260);
    render_blocks(&chart, &blocks)
}
