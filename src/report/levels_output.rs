//! `solve` outputs for every fidelity level: the `fidelity` and `buckling` keys of
//! `summary.json`, the buckling columns appended to `string.csv`, and the whole summary and
//! string table of the `soft`, `bha` and `hybrid` levels (values a level does not compute are
//! `null` in JSON and empty cells in CSV).

use super::solve_output::{CONTACT_THRESHOLD_N, STRING_HEADER};
use super::{finite, num};
use crate::case::Case;
use crate::case::Level;
use crate::models::buckling::{soft_marks, stiff_marks, zones, BuckleState, Mark};
use crate::models::levels::{coupling_node, FemPart, LevelResult};
use crate::models::softstring::SoftStringResult;
use serde_json::{json, Value};

/// Columns appended to `string.csv` after the interface's (kN; empty where the component
/// cannot buckle).
pub const BUCKLING_COLUMNS: &str = "sinusoidal_onset_kN,helical_onset_kN,buckling";

fn opt(x: Option<f64>, scale: f64) -> Result<Value, String> {
    x.map(|v| finite(v * scale).map(Value::from))
        .transpose()
        .map(|v| v.unwrap_or(Value::Null))
}

/// Buckling marks at the nodes of the stiff part `part` (up to node `last` included).
pub fn fem_marks(case: &Case, part: &FemPart, last: usize) -> Vec<Mark> {
    stiff_marks(case, &part.model, &part.results.nodes[..=last])
}

fn mark_cells(m: &Mark) -> Result<String, String> {
    let f = |x: Option<f64>| x.map(|v| num(v / 1e3, 3)).transpose().map(|v| v.unwrap_or_default());
    Ok(format!("{},{},{}", f(m.sinusoidal_n)?, f(m.helical_n)?, m.state.name()))
}

/// Append the buckling columns to the CSV text `csv` (header + one row per mark, in order).
pub fn append_buckling_columns(csv: &str, marks: &[Mark]) -> Result<String, String> {
    let mut out = String::with_capacity(csv.len() * 3 / 2);
    let mut lines = csv.lines();
    let header = lines.next().ok_or("empty string table")?;
    out.push_str(header);
    out.push(',');
    out.push_str(BUCKLING_COLUMNS);
    out.push('\n');
    let rows: Vec<&str> = lines.collect();
    if rows.len() != marks.len() {
        return Err(format!("{} rows but {} buckling marks", rows.len(), marks.len()));
    }
    for (row, m) in rows.iter().zip(marks) {
        out.push_str(row);
        out.push(',');
        out.push_str(&mark_cells(m)?);
        out.push('\n');
    }
    Ok(out)
}

/// Tributary length (m) of each mark along the string: half the distance to each neighbour.
fn tributary(marks: &[Mark]) -> Vec<f64> {
    (0..marks.len())
        .map(|i| {
            let lo = if i > 0 {
                (marks[i].md_m - marks[i - 1].md_m).abs()
            } else {
                0.0
            };
            let up = if i + 1 < marks.len() {
                (marks[i + 1].md_m - marks[i].md_m).abs()
            } else {
                0.0
            };
            0.5 * (lo + up)
        })
        .collect()
}

/// The `buckling` key of `summary.json`: model compared, buckled lengths, zones.
pub fn buckling_json(marks: &[Mark], model: &str) -> Result<Value, String> {
    let w = tributary(marks);
    let mut sin_len = 0.0;
    let mut hel_len = 0.0;
    for (m, l) in marks.iter().zip(&w) {
        match m.state {
            BuckleState::Sinusoidal => sin_len += l,
            BuckleState::Helical => {
                sin_len += l;
                hel_len += l;
            }
            _ => {}
        }
    }
    let max_c = marks.iter().map(|m| m.compression_n).fold(0.0, f64::max);
    let zones: Vec<Value> = zones(marks)
        .iter()
        .map(|z| {
            Ok(json!({
                "top_md_m": finite(z.top_md_m)?,
                "bottom_md_m": finite(z.bottom_md_m)?,
                "state": z.state.name(),
                "max_compression_over_sinusoidal_onset": finite(z.max_ratio)?,
            }))
        })
        .collect::<Result<_, String>>()?;
    Ok(json!({
        "axial_force_from": model,
        "onsets": "Dawson-Paslay / Chen-Lin-Cheatham with the curved-hole wall load, vertical-hole floor 2.55 / 5.55 (EI w_b^2)^(1/3)",
        "sinusoidal_length_m": finite(sin_len)?,
        "helical_length_m": finite(hel_len)?,
        "max_compression_kN": finite(max_c / 1e3)?,
        "zones": zones,
    }))
}

/// The `fidelity` key of `summary.json`.
pub fn fidelity_json(lr: &LevelResult, case: &Case) -> Result<Value, String> {
    let c = &lr.choice;
    let coupling = lr
        .fem
        .as_ref()
        .filter(|_| matches!(c.level, Level::Bha | Level::Hybrid) && lr.cut_m.is_some())
        .map(|f| f.model.mesh.nodes[coupling_node(case, &f.model)].s_m);
    let whole_stiff = matches!(c.level, Level::Bha | Level::Hybrid) && lr.cut_m.is_none();
    let (surface, missing): (&str, Vec<&str>) = match c.level {
        _ if whole_stiff => ("stiff whole string (not longer than the cut)", vec![]),
        Level::Soft => (
            "soft string",
            vec![
                "bit build and walk force",
                "bit tilt",
                "contacts",
                "bending moment",
                "von Mises stress",
            ],
        ),
        Level::Bha => (
            "not computed (the stiff model ends at the cut)",
            vec!["hook load", "surface torque", "string above the coupling point"],
        ),
        Level::Hybrid => (
            "soft string from the coupling point up, started from the stiff model's axial force and torque there",
            vec!["bending, contacts and stresses above the coupling point"],
        ),
        Level::Whole => ("stiff whole string", vec![]),
    };
    Ok(json!({
        "requested": c.requested.name(),
        "used": c.level.name(),
        "reason": c.reason,
        "cut_m": opt(lr.cut_m, 1.0)?,
        "coupling_m": opt(coupling, 1.0)?,
        "surface_values_from": surface,
        "not_computed": missing,
        "seconds": finite(lr.seconds)?,
    }))
}

/// Last node of the stiff part whose results are reported: the coupling node of a cut model,
/// else the top.
fn last_reported(case: &Case, lr: &LevelResult, part: &FemPart) -> usize {
    if lr.cut_m.is_some() && lr.choice.level != Level::Whole {
        coupling_node(case, &part.model)
    } else {
        part.model.nodes() - 1
    }
}

/// One `string.csv` row of a soft-string point (columns the soft string does not compute
/// left empty; the contact force is the wall load per length times the point's share of the
/// string).
fn soft_row(case: &Case, soft: &SoftStringResult, i: usize) -> Result<String, String> {
    let p = &soft.points[i];
    let pos = case.well.path.point_at(p.md_m).position;
    let lo = if i > 0 {
        (soft.points[i - 1].md_m - p.md_m).abs()
    } else {
        0.0
    };
    let up = soft.points.get(i + 1).map(|q| (p.md_m - q.md_m).abs()).unwrap_or(0.0);
    let contact = p.normal_force_per_m * 0.5 * (lo + up);
    Ok([
        num(p.md_m, 3)?,
        num(pos.x, 4)?,
        num(pos.y, 4)?,
        num(pos.z, 4)?,
        String::new(),
        String::new(),
        String::new(),
        num(contact / 1e3, 4)?,
        String::new(),
        num(p.tension_n / 1e3, 3)?,
        num(p.torque_nm / 1e3, 4)?,
        String::new(),
        String::new(),
    ]
    .join(","))
}

/// `string.csv` and the buckling marks of a `soft`, `bha` or `hybrid` result: stiff rows from
/// the bit to the coupling point, soft-string rows above it.
pub fn levels_csv(case: &Case, lr: &LevelResult) -> Result<(String, Vec<Mark>), String> {
    let mut csv = String::from(STRING_HEADER);
    csv.push('\n');
    let mut all_marks = Vec::new();
    if let Some(part) = &lr.fem {
        let last = last_reported(case, lr, part);
        let partial = crate::models::fem::results::SolveResults {
            nodes: part.results.nodes[..=last].to_vec(),
            ..part.results.clone()
        };
        let text = super::solve_output::string_csv(&partial)?;
        csv.push_str(text.split_once('\n').map(|x| x.1).unwrap_or(""));
        all_marks.extend(fem_marks(case, part, last));
    }
    if let Some(soft) = &lr.soft {
        let skip = usize::from(lr.fem.is_some());
        for i in skip..soft.points.len() {
            csv.push_str(&soft_row(case, soft, i)?);
            csv.push('\n');
        }
        all_marks.extend(soft_marks(case, soft, skip));
    }
    let csv = append_buckling_columns(&csv, &all_marks)?;
    Ok((csv, all_marks))
}

/// `summary.json` of a `soft`, `bha` or `hybrid` result (the interface's keys; `null` where
/// the level does not compute a value), with the `fidelity` and `buckling` keys.
pub fn levels_summary(case: &Case, lr: &LevelResult, marks: &[Mark]) -> Result<Value, String> {
    let bit = lr.bit;
    let md = case.operation.bit_md_m;
    let contacts: Vec<Value> = match &lr.fem {
        Some(part) => {
            let last = last_reported(case, lr, part);
            part.results.nodes[..=last]
                .iter()
                .filter(|n| n.contact_force_n > CONTACT_THRESHOLD_N)
                .map(|n| Ok(json!({"md_m": finite(n.md_m)?, "force_kN": finite(n.contact_force_n / 1e3)?, "angle_deg": finite(n.contact_angle_deg)?})))
                .collect::<Result<_, String>>()?
        }
        None => vec![],
    };
    let solver = match &lr.fem {
        Some(p) => json!({
            "converged": p.converged,
            "iterations": p.stats.iterations,
            "factorizations": p.stats.factorizations,
            "dofs": p.model.dofs(),
            "elements": p.model.nodes() - 1,
            "seconds": finite(lr.seconds)?,
            "final_residual": finite(*p.stats.residual_history.last().unwrap_or(&0.0))?,
            "max_penetration_rel": finite(p.stats.max_penetration)?,
        }),
        None => json!({
            "converged": true,
            "iterations": 0,
            "dofs": 0,
            "elements": lr.soft.as_ref().map(|s| s.points.len().saturating_sub(1)).unwrap_or(0),
            "seconds": finite(lr.seconds)?,
        }),
    };
    let equilibrium = match &lr.fem {
        Some(p) => json!({
            "force_imbalance_kN": finite(p.results.force_imbalance_n.norm() / 1e3)?,
            "moment_imbalance_kNm": finite(p.results.moment_imbalance_nm.norm() / 1e3)?,
            "largest_force_kN": finite(p.results.largest_force_n / 1e3)?,
        }),
        None => Value::Null,
    };
    let model = match lr.choice.level {
        Level::Soft => "soft string",
        Level::Bha => "stiff FEM below the coupling point",
        Level::Hybrid => "stiff FEM below the coupling point, soft string above",
        Level::Whole => "stiff FEM",
    };
    Ok(json!({
        "bit": {
            "md_m": finite(md)?,
            "wob_kN": finite(lr.wob_n / 1e3)?,
            "build_force_kN": opt(bit.map(|b| b.build_force_n), 1e-3)?,
            "walk_force_kN": opt(bit.map(|b| b.walk_force_n), 1e-3)?,
            "tilt_inc_deg": opt(bit.map(|b| b.tilt_inc_rad.to_degrees()), 1.0)?,
            "tilt_azi_deg": opt(bit.map(|b| b.tilt_azi_rad.to_degrees()), 1.0)?,
            "torque_kNm": finite(lr.bit_torque_nm / 1e3)?,
        },
        "surface": {
            "hook_load_kN": opt(lr.hook_load_n, 1e-3)?,
            "torque_kNm": opt(lr.surface_torque_nm, 1e-3)?,
        },
        "contacts": contacts,
        "equilibrium": equilibrium,
        "solver": solver,
        "fidelity": fidelity_json(lr, case)?,
        "buckling": buckling_json(marks, model)?,
        "notes": case.string_above_survey_note().into_iter().collect::<Vec<_>>(),
    }))
}

/// The stiff results of a `bha` or `hybrid` result as the solve report shows them: the FEM
/// nodes from the bit to the coupling point with their buckling marks; for `hybrid` the hook
/// load and surface torque are the level's (soft string above the cut), for `bha` they are not
/// computed (`surface_values` false). None for `soft` (no stiff part).
pub fn reported_stiff_part(
    case: &Case,
    lr: &LevelResult,
) -> Option<(crate::models::fem::results::SolveResults, Vec<Mark>, bool)> {
    let part = lr.fem.as_ref()?;
    let last = last_reported(case, lr, part);
    let mut res = crate::models::fem::results::SolveResults {
        nodes: part.results.nodes[..=last].to_vec(),
        ..part.results.clone()
    };
    let surface = match (lr.hook_load_n, lr.surface_torque_nm) {
        (Some(h), Some(t)) => {
            res.hook_load_n = h;
            res.surface_torque_nm = t;
            true
        }
        _ => false,
    };
    Some((res, fem_marks(case, part, last), surface))
}
