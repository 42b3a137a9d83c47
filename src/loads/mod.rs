//! Torque-and-drag chart (`drillpath loads`): hook load and surface torque against bit depth
//! for the five load cases, buckling onset and yield limits, stiff (whole-string FEM) results
//! on request, and friction calibration from measured hook loads.
//!
//! - [`chart`]: the soft-string chart (Johancsik, [`crate::models::softstring`]) over a list of bit
//!   depths, one row per depth and load case;
//! - [`stiff`]: the same rows from the whole-string FEM, warm-started;
//! - [`limits`]: buckling onset (sinusoidal, helical) along the string and pipe-body yield
//!   limits (tension, torsion, combined);
//! - [`calibrate`]: least-squares fit of the friction factor per hole section;
//! - [`run`]: one chart as `drillpath loads` computes it (bit depths, calibration, rows).
//!
//! The case gives the string at its own bit depth. At another bit depth the string is the same
//! from the bit upward and its topmost component is lengthened or shortened so that it reaches
//! the surface ([`DrillString::at_depth`]); when the bit is shallower than the components below the
//! top one, the string is cut at the surface.

pub mod calibrate;
pub mod chart;
pub mod limits;
pub mod row;
pub mod run;
pub mod stiff;

use crate::case::{Case, Mode};
use crate::string::DrillString;

/// The load cases of a chart, in the order of `loads.csv`.
pub const MODES: [Mode; 5] = [
    Mode::TripIn,
    Mode::TripOut,
    Mode::RotatingOffBottom,
    Mode::Drilling,
    Mode::Sliding,
];

/// Rotary speed used for the rotating rows when the case gives none, rev/min (stated in the
/// command's output). Off bottom only the direction matters; drilling, the ratio ROP/RPM splits
/// friction between axial and tangential.
pub const DEFAULT_CHART_RPM: f64 = 60.0;

/// Operating values shared by all rows of a chart, SI.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ChartOperation {
    /// Weight on bit of the on-bottom rows (drilling, sliding), N.
    pub wob_n: f64,
    /// Surface rotary speed of the rotating rows (drilling, rotating off bottom), rev/min (> 0).
    pub rpm: f64,
    /// Rate of penetration of the on-bottom rows, m/s (>= 0).
    pub rop_m_s: f64,
}

impl ChartOperation {
    /// From the case: its WOB and ROP, and its RPM or [`DEFAULT_CHART_RPM`] when it gives none.
    pub fn from_case(case: &Case) -> ChartOperation {
        let rpm = if case.operation.rpm > 0.0 {
            case.operation.rpm
        } else {
            DEFAULT_CHART_RPM
        };
        ChartOperation {
            wob_n: case.operation.wob_n,
            rpm,
            rop_m_s: case.operation.rop_m_s,
        }
    }
}

/// Bit depths from `from_m` to `to_m` every `every_m` (m): `from, from + every, ...` and `to`
/// itself, keeping only depths strictly below `md_start` (the top of the survey, where the
/// string has no length). `every_m` must be positive and `to_m >= from_m`.
pub fn depth_list(from_m: f64, to_m: f64, every_m: f64, md_start: f64) -> Vec<f64> {
    let mut out = Vec::new();
    if every_m.is_nan() || every_m <= 0.0 || to_m.is_nan() || to_m < from_m {
        return out;
    }
    let n = ((to_m - from_m) / every_m + 1e-9).floor() as usize;
    for k in 0..=n {
        let d = from_m + k as f64 * every_m;
        if d > md_start + 1e-9 && d < to_m - 1e-6 {
            out.push(d);
        }
    }
    if to_m > md_start + 1e-9 {
        out.push(to_m);
    }
    out
}

/// The case for one row of the chart: bit at `bit_md_m`, string refitted by
/// [`DrillString::at_depth`], operation set for `mode` with the chart's WOB and RPM (on-bottom rows
/// take `op.wob_n`; off bottom WOB 0; the friction's direction follows from the row's mode,
/// [`crate::case::Operation::motion`], as in `solve`); a hook load given in the case is not used.
pub fn case_for_row(base: &Case, string: &DrillString, bit_md_m: f64, mode: Mode, op: &ChartOperation) -> Case {
    let mut c = base.clone();
    c.string = string.clone();
    set_row_operation(&mut c, bit_md_m, mode, op);
    c
}

/// Set the operation of `case` for one row (see [`case_for_row`]); the string is not touched.
pub fn set_row_operation(case: &mut Case, bit_md_m: f64, mode: Mode, op: &ChartOperation) {
    let o = &mut case.operation;
    o.mode = mode;
    o.bit_md_m = bit_md_m;
    o.hook_load_n = None;
    o.wob_n = if mode.on_bottom() { op.wob_n } else { 0.0 };
    o.rpm = op.rpm;
    o.rop_m_s = op.rop_m_s;
}

/// Check that every component of `string` (bit at `bit_md_m`) fits the hole where it sits (as
/// the case reader does at the case's bit depth: a bit or stabilizer may be gauge within 1 mm);
/// the error names the component, the MD and the diameters.
pub fn check_fits(string: &DrillString, hole: &crate::geometry::HoleSize, bit_md_m: f64) -> Result<(), String> {
    match crate::case::fit::first_misfit(string, hole, bit_md_m) {
        Some(m) => Err(format!("with the bit at {bit_md_m:.1} m, {}", m.describe(string))),
        None => Ok(()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::string::material::steel;
    use crate::string::{Component, ComponentKind};

    fn comp(kind: ComponentKind, bottom: f64, len: f64) -> Component {
        Component {
            kind,
            name: kind.name().into(),
            length_m: len,
            bottom_m: bottom,
            body_od_m: 0.127,
            contact_od_m: 0.127,
            contact_length_m: 0.0,
            id_m: 0.1,
            tool_joint_od_m: None,
            joint_length_m: 9.144,
            material: steel(),
            weight_air_n_per_m: 300.0,
            sensor_to_bit_m: None,
            bend: None,
            rss: None,
        }
    }

    #[test]
    fn depth_list_includes_end_and_skips_surface() {
        let d = depth_list(0.0, 100.0, 30.0, 0.0);
        assert_eq!(d, vec![30.0, 60.0, 90.0, 100.0]);
        let d = depth_list(0.0, 90.0, 30.0, 0.0);
        assert_eq!(d, vec![30.0, 60.0, 90.0]);
        assert!(depth_list(10.0, 5.0, 1.0, 0.0).is_empty());
    }

    #[test]
    fn string_is_refitted_to_reach_surface() {
        let s = DrillString {
            components: vec![
                comp(ComponentKind::Collar, 0.0, 50.0),
                comp(ComponentKind::Hwdp, 50.0, 100.0),
                comp(ComponentKind::Pipe, 150.0, 850.0),
            ],
        };
        let deep = s.at_depth(2000.0);
        assert_eq!(deep.components.len(), 3);
        assert!((deep.length_m() - 2000.0).abs() < 1e-9);
        let shallow = s.at_depth(120.0);
        assert_eq!(shallow.components.len(), 2);
        assert!((shallow.length_m() - 120.0).abs() < 1e-9);
        assert_eq!(shallow.components[1].kind, ComponentKind::Hwdp);
        let tiny = s.at_depth(30.0);
        assert_eq!(tiny.components.len(), 1);
        assert!((tiny.length_m() - 30.0).abs() < 1e-9);
    }
}
