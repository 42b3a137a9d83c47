//! `solve` outputs: `summary.json` and `string.csv` with the interface's names (kN, kN.m, mm, deg, MPa).

use super::{finite, num};
use crate::models::fem::results::SolveResults;
use crate::models::fem::solve::SolveStats;
use serde_json::json;

/// Header of `string.csv` (interface.md).
pub const STRING_HEADER: &str = "md_m,north_m,east_m,tvd_m,disp_high_mm,disp_right_mm,clearance_mm,contact_force_kN,contact_angle_deg,axial_force_kN,torque_kNm,bending_moment_kNm,von_mises_MPa";

/// Contacts reported in the summary: nodes with a normal force above this, N.
pub const CONTACT_THRESHOLD_N: f64 = 1.0;

/// `string.csv` text, one row per node from the bit up.
pub fn string_csv(res: &SolveResults) -> Result<String, String> {
    let mut out = String::from(STRING_HEADER);
    out.push('\n');
    for n in &res.nodes {
        let row = [
            num(n.md_m, 3)?,
            num(n.position.x, 4)?,
            num(n.position.y, 4)?,
            num(n.position.z, 4)?,
            num(n.disp_high_m * 1e3, 3)?,
            num(n.disp_right_m * 1e3, 3)?,
            num(n.clearance_m * 1e3, 3)?,
            num(n.contact_force_n / 1e3, 4)?,
            num(n.contact_angle_deg, 2)?,
            num(n.axial_force_n / 1e3, 3)?,
            num(n.torque_nm / 1e3, 4)?,
            num(n.bending_moment_nm / 1e3, 4)?,
            num(n.von_mises_pa / 1e6, 3)?,
        ];
        out.push_str(&row.join(","));
        out.push('\n');
    }
    Ok(out)
}

/// `summary.json` value.
pub fn summary_json(
    res: &SolveResults,
    stats: &SolveStats,
    converged: bool,
    dofs: usize,
    elements: usize,
) -> Result<serde_json::Value, String> {
    let b = &res.bit;
    let contacts: Vec<serde_json::Value> = res
        .nodes
        .iter()
        .filter(|n| n.contact_force_n > CONTACT_THRESHOLD_N)
        .map(|n| Ok(json!({"md_m": finite(n.md_m)?, "force_kN": finite(n.contact_force_n / 1e3)?, "angle_deg": finite(n.contact_angle_deg)?})))
        .collect::<Result<_, String>>()?;
    Ok(json!({
        "bit": {
            "md_m": finite(b.md_m)?,
            "wob_kN": finite(b.wob_n / 1e3)?,
            "build_force_kN": finite(b.build_force_n / 1e3)?,
            "walk_force_kN": finite(b.walk_force_n / 1e3)?,
            "tilt_inc_deg": finite(b.tilt_inc_rad.to_degrees())?,
            "tilt_azi_deg": finite(b.tilt_azi_rad.to_degrees())?,
            "torque_kNm": finite(b.torque_nm / 1e3)?,
        },
        "surface": {
            "hook_load_kN": finite(res.hook_load_n / 1e3)?,
            "torque_kNm": finite(res.surface_torque_nm / 1e3)?,
        },
        "contacts": contacts,
        "equilibrium": {
            "force_imbalance_kN": finite(res.force_imbalance_n.norm() / 1e3)?,
            "moment_imbalance_kNm": finite(res.moment_imbalance_nm.norm() / 1e3)?,
            "largest_force_kN": finite(res.largest_force_n / 1e3)?,
        },
        "solver": {
            "converged": converged,
            "iterations": stats.iterations,
            "factorizations": stats.factorizations,
            "dofs": dofs,
            "elements": elements,
            "seconds": finite(stats.seconds)?,
            "final_residual": finite(*stats.residual_history.last().unwrap_or(&0.0))?,
            "max_penetration_rel": finite(stats.max_penetration)?,
        }
    }))
}
