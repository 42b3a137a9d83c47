//! `drillpath solve --fidelity soft|bha|hybrid` (and `[solver] fidelity`): the levels other
//! than the whole string, and the fidelity/buckling additions to the whole-string outputs.

use super::args::SolveArgs;
use crate::case::Case;
use crate::error::InputError;
use crate::fem::model::Model;
use crate::fem::results::SolveResults;
use crate::fidelity::{run as run_level, Choice, Level, LevelResult, Purpose};
use crate::report::levels_output::{
    append_buckling_columns, buckling_json, levels_csv, levels_summary, requested_name,
};
use crate::report::write_atomic;
use anyhow::{bail, Context};

/// Apply `--accuracy` to `case` and choose the level `solve` runs: `--fidelity` over the
/// case's `[solver] fidelity`.
pub fn configure(a: &SolveArgs, case: &mut Case) -> Result<Choice, InputError> {
    super::model_choice(a.fidelity.as_deref(), a.accuracy.as_deref(), case, Purpose::Solve)
}

/// Add the `fidelity` and `buckling` keys to the whole-string `summary` and the buckling
/// columns to its `string.csv` text.
pub fn annotate_whole(
    case: &Case,
    choice: &Choice,
    model: &Model,
    res: &SolveResults,
    seconds: f64,
    summary: &mut serde_json::Value,
    csv: String,
) -> anyhow::Result<String> {
    let nodes = res
        .nodes
        .iter()
        .zip(&model.mesh.nodes)
        .map(|(n, m)| (n.md_m, m.s_m, n.axial_force_n));
    let marks = crate::buckling_marks::marks(
        nodes,
        &case.string,
        &case.well.path,
        &case.well.hole,
        case.mud.density_kg_m3,
    );
    summary["fidelity"] = serde_json::json!({
        "requested": requested_name(choice.requested),
        "used": Level::Whole.name(),
        "reason": choice.reason,
        "surface_values_from": "stiff whole string",
        "not_computed": [],
        "seconds": seconds,
    });
    summary["buckling"] = buckling_json(&marks, "stiff FEM").map_err(|e| anyhow::anyhow!("internal error: {e}"))?;
    append_buckling_columns(&csv, &marks).map_err(|e| anyhow::anyhow!("internal error: {e}"))
}

/// Run `case` at a level other than `whole` and write/print its outputs.
pub fn run(a: &SolveArgs, case: &Case, choice: Choice) -> anyhow::Result<()> {
    let lr = run_level(
        case,
        choice,
        &crate::fem::solve::SolveControls::from_settings(&case.solver),
    )
    .with_context(|| format!("{}: solve failed", a.case.display()))?;
    if !lr.converged && !a.allow_unconverged {
        let it = lr.fem.as_ref().map(|f| f.stats.iterations).unwrap_or(0);
        bail!(
            "{}: the stiff bottom-hole-assembly solve did not converge in {it} iterations; no results written (use --allow-unconverged to write flagged results, or --fidelity soft){}",
            a.case.display(),
            super::solve::hints_suffix(case)
        );
    }
    let (csv, marks) = levels_csv(case, &lr).map_err(|e| anyhow::anyhow!("internal error: {e}"))?;
    let summary = levels_summary(case, &lr, &marks).map_err(|e| anyhow::anyhow!("internal error: {e}"))?;
    if let Some(dir) = &a.out {
        write_atomic(
            &dir.join("summary.json"),
            serde_json::to_string_pretty(&summary)?.as_bytes(),
        )
        .with_context(|| format!("cannot write {}", dir.display()))?;
        write_atomic(&dir.join("string.csv"), csv.as_bytes())
            .with_context(|| format!("cannot write {}", dir.display()))?;
    }
    if a.json {
        println!("{}", serde_json::to_string_pretty(&summary)?);
        return Ok(());
    }
    print_summary(a, case, &lr, &summary);
    Ok(())
}

fn print_summary(a: &SolveArgs, case: &Case, lr: &LevelResult, summary: &serde_json::Value) {
    println!("solve: {} ({})", case.name, a.case.display());
    println!("  fidelity {}: {}", lr.choice.level.name(), lr.choice.reason);
    if let Some(cut) = lr.cut_m {
        println!(
            "  stiff model cut {cut:.1} m above the bit (on the wall, parallel to the hole); results reported up to {:.1} m above the bit",
            summary["fidelity"]["coupling_m"].as_f64().unwrap_or(cut)
        );
    }
    if !lr.converged {
        println!("  WARNING: NOT CONVERGED - results below are flagged and not valid");
    }
    println!(
        "  mode {}, bit at {:.2} m MD, WOB {:.1} kN, {:.0} rpm",
        case.operation.mode.name(),
        case.operation.bit_md_m,
        lr.wob_n / 1e3 + 0.0,
        case.operation.rpm
    );
    match &lr.bit {
        Some(b) => println!(
            "  bit: build force {:+.3} kN, walk force {:+.3} kN, tilt inc {:+.4} deg, tilt azi {:+.4} deg, torque {:.2} kN.m",
            b.build_force_n / 1e3,
            b.walk_force_n / 1e3,
            b.tilt_inc_rad.to_degrees(),
            b.tilt_azi_rad.to_degrees(),
            b.torque_nm / 1e3
        ),
        None => println!(
            "  bit: torque {:.2} kN.m; side forces and tilt not computed (soft string: no bending)",
            lr.bit_torque_nm / 1e3
        ),
    }
    match (lr.hook_load_n, lr.surface_torque_nm) {
        (Some(h), Some(t)) => println!("  surface: hook load {:.1} kN, torque {:.2} kN.m", h / 1e3, t / 1e3),
        _ => println!("  surface: not computed (bha: the stiff model ends at the cut; use hybrid or whole)"),
    }
    let b = &summary["buckling"];
    println!(
        "  buckling: sinusoidal over {:.1} m, helical over {:.1} m (max compression {:.1} kN)",
        b["sinusoidal_length_m"].as_f64().unwrap_or(0.0),
        b["helical_length_m"].as_f64().unwrap_or(0.0),
        b["max_compression_kN"].as_f64().unwrap_or(0.0)
    );
    println!("  time {:.4} s", lr.seconds);
    if let Some(dir) = &a.out {
        println!("  wrote {}/summary.json and string.csv", dir.display());
    }
}
