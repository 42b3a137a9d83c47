//! The soft-string torque-and-drag chart: for each bit depth and each load case, hook load,
//! surface torque, largest contact force, buckling and yield (one [`LoadRow`] each).
//!
//! Each depth refits the string once ([`crate::string::DrillString::at_depth`]) and runs the five load cases
//! on it (Johancsik soft string, [`crate::models::softstring::from_case`]). A soft-string pass is a
//! single explicit sweep from the bit up, so there is nothing to iterate and no state to warm
//! start; the only reuse is the refitted string and case per depth.
//!
//! Contact force: the soft string gives a normal force per length `q` (N/m); the reported
//! contact force is `q` times the component's joint length (the force one tool joint carries
//! when the pipe touches the wall at its joints, 9.144 m by default), comparable with the
//! nodal contact forces of the stiff model; `max_side_force_n_per_m` keeps `q` itself.

use super::limits::{buckling_along, combined_torque_limit, max_stress_ratio, yield_limits};
use super::row::{LoadRow, RowLoads, RowYield};
use super::{set_row_operation, ChartOperation, MODES};
use crate::case::Case;
use crate::models::helical_drag::helical_soft_string_with;
use crate::models::softstring::{at_zero_hook_load, from_case, SoftStringResult};
use crate::string::DrillString;

/// Settings of a soft-string chart.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ChartSettings {
    /// WOB and RPM of the rows.
    pub op: ChartOperation,
    /// Longest soft-string element, m (> 0).
    pub max_element_m: f64,
}

/// Soft-string loads of a result for `string` with its bit at `bit_md_m`.
pub fn soft_loads(res: &SoftStringResult, string: &DrillString, bit_md_m: f64) -> RowLoads {
    let mut max_f: f64 = 0.0;
    let mut max_q: f64 = 0.0;
    for (k, p) in res.points.iter().enumerate().skip(1) {
        // points[k] carries the element just below it (between points k-1 and k)
        let mid = 0.5 * (p.md_m + res.points[k - 1].md_m);
        let c = string.component_at((bit_md_m - mid).max(0.0));
        max_q = max_q.max(p.normal_force_per_m);
        max_f = max_f.max(p.normal_force_per_m * c.joint_length_m);
    }
    RowLoads {
        hook_load_n: res.hook_load_n,
        surface_torque_nm: res.surface_torque_nm,
        max_contact_force_n: max_f,
        max_side_force_n_per_m: max_q,
    }
}

/// Hook load (N) within which an on-bottom row's hook load at its reduced WOB counts as zero
/// (the secant of `softstring::at_zero_hook_load` ends within 1e-9 N of it).
const ZERO_HOOK_LOAD_TOLERANCE_N: f64 = 1e-6;

/// The soft-string row of `case` (string and operation already set for the row).
///
/// On bottom, a WOB larger than the string can give (hook load below zero) is not achievable:
/// the row then uses the WOB that brings the hook load to zero (the row's `wob_n` says so), or,
/// where even a zero WOB leaves the hook load below zero (the string cannot be put on bottom),
/// a zero WOB with that hook load.
pub fn soft_row(case: &Case, max_element_m: f64) -> LoadRow {
    let op = &case.operation;
    let mut res = from_case(case, max_element_m);
    if op.mode.on_bottom() && res.hook_load_n < 0.0 {
        res = at_zero_hook_load(case, max_element_m);
        // zero within the secant's tolerance (1e-9 N); below it, even a zero WOB needs the
        // surface to push (the string cannot be put on bottom): the row keeps that hook load
        if res.hook_load_n > -ZERO_HOOK_LOAD_TOLERANCE_N {
            res.hook_load_n = res.hook_load_n.max(0.0);
        }
    }
    let wob_n = -res.points[0].tension_n;
    let loads = soft_loads(&res, &case.string, op.bit_md_m);
    let buckling = buckling_along(
        &res,
        &case.string,
        &case.well.path,
        &case.well.hole,
        op.bit_md_m,
        case.mud.density_kg_m3,
    );
    let top = case.string.components.last().expect("a string has components");
    let yield_ = RowYield {
        tension_limit_n: yield_limits(top).map(|y| y.tension_n),
        torque_limit_nm: yield_limits(top).map(|y| y.torque_nm),
        combined_torque_limit_nm: combined_torque_limit(top, res.hook_load_n),
        max_stress_ratio: max_stress_ratio(&res, &case.string, &case.well.path, op.bit_md_m, case.mud.density_kg_m3),
    };
    let helical_drag_hook_load_n = if buckling.helical_length_m > 0.0 {
        let mut c = case.clone();
        c.operation.wob_n = wob_n;
        c.operation.hook_load_n = None;
        helical_soft_string_with(&c, max_element_m).hook_load_n
    } else {
        res.hook_load_n
    };
    LoadRow {
        bit_md_m: op.bit_md_m,
        mode: op.mode,
        wob_n,
        soft: loads,
        helical_drag_hook_load_n,
        buckling,
        yield_,
        stiff: None,
        stiff_level: None,
    }
}

/// Soft-string chart of `case` at the bit depths `depths` (m, each inside the surveyed hole),
/// rows in depth order, load cases in [`MODES`] order.
///
/// # Panics
/// If the case has no string components or `settings.max_element_m` is not positive.
pub fn soft_chart(case: &Case, depths: &[f64], settings: &ChartSettings) -> Vec<LoadRow> {
    let mut rows = Vec::with_capacity(depths.len() * MODES.len());
    for &d in depths {
        let mut c = case.at_bit_depth(d);
        for mode in MODES {
            set_row_operation(&mut c, d, mode, &settings.op);
            rows.push(soft_row(&c, settings.max_element_m));
        }
    }
    rows
}
