//! `drillpath solve --fidelity soft|bha|hybrid` (and `[solver] fidelity`): the levels other
//! than the whole string, and the fidelity/buckling additions to the whole-string outputs.

use super::args::SolveArgs;
use super::progress::Progress;
use crate::case::fidelity::{Choice, Level, Purpose};
use crate::case::Case;
use crate::error::InputError;
use crate::models::buckling::Mark;
use crate::models::fem::model::Model;
use crate::models::fem::results::BitResult;
use crate::models::fem::results::SolveResults;
use crate::models::levels::{run_with_progress, stages, LevelResult};
use crate::report::display_units::{fixed, signed, UnitSystem};
use crate::report::levels_output::{append_buckling_columns, buckling_json, levels_csv, levels_summary};
use anyhow::{bail, Context};
use std::io::Write;

/// Apply `--accuracy` to `case` and choose the level `solve` runs: `--fidelity` over the
/// case's `[solver] fidelity`.
pub fn configure(a: &SolveArgs, case: &mut Case) -> Result<Choice, InputError> {
    super::model_choice(a.fidelity.as_deref(), a.accuracy.as_deref(), case, Purpose::Solve)
}

/// Add the `fidelity`, `buckling` and `notes` keys to the whole-string `summary` and the buckling
/// columns to its `string.csv` text; returns that text and the buckling marks at the nodes.
pub fn annotate_whole(
    case: &Case,
    choice: &Choice,
    model: &Model,
    res: &SolveResults,
    seconds: f64,
    summary: &mut serde_json::Value,
    csv: String,
) -> anyhow::Result<(String, Vec<Mark>)> {
    let marks = crate::models::buckling::stiff_marks(case, model, &res.nodes);
    summary["fidelity"] = serde_json::json!({
        "requested": choice.requested.name(),
        "used": Level::Whole.name(),
        "reason": choice.reason,
        "surface_values_from": "stiff whole string",
        "not_computed": [],
        "seconds": seconds,
    });
    summary["buckling"] = buckling_json(&marks, "stiff FEM").map_err(|e| anyhow::anyhow!("internal error: {e}"))?;
    summary["notes"] = serde_json::json!(case.string_above_survey_note().into_iter().collect::<Vec<_>>());
    let csv = append_buckling_columns(&csv, &marks).map_err(|e| anyhow::anyhow!("internal error: {e}"))?;
    Ok((csv, marks))
}

/// Run `case` at a level other than `whole` and write/print its outputs; a progress bar over
/// the stages when there are several (hybrid) and stderr is a terminal, unless `quiet`.
pub fn run(a: &SolveArgs, case: &Case, choice: Choice, quiet: bool) -> anyhow::Result<()> {
    let n = stages(choice.level);
    let progress = if n > 1 {
        Progress::new(n as u64, &format!("solve {}", a.case.display()), quiet)
    } else {
        Progress::hidden()
    };
    let lr = run_with_progress(
        case,
        choice,
        &crate::models::fem::solve::SolveControls::from_settings(&case.solver),
        &mut |k, _, what| progress.set(k as u64, what),
    );
    progress.finish();
    let lr = lr.with_context(|| format!("{}: solve failed", a.case.display()))?;
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
    super::solve::write_outputs(a.out.as_deref(), &summary, &csv)?;
    if let Some(file) = &a.view.report {
        write_level_report(file, a, case, &lr)?;
    }
    let mut out = std::io::stdout().lock();
    if a.view.json {
        writeln!(out, "{}", serde_json::to_string_pretty(&summary)?)?;
        return Ok(());
    }
    print_summary(a, case, &lr, &summary, &mut out)?;
    Ok(())
}

/// The lines every level prints about the operation and the bit: mode, bit MD, WOB, rpm; bit
/// side forces, tilt and torque (or only the torque for the soft string).
pub struct BitLines<'a> {
    /// Units shown.
    pub units: UnitSystem,
    /// The case solved.
    pub case: &'a Case,
    /// Weight on bit, N.
    pub wob_n: f64,
    /// Bit forces and tilt (None for the soft string).
    pub bit: Option<&'a BitResult>,
    /// Bit torque, N.m.
    pub bit_torque_nm: f64,
}

impl BitLines<'_> {
    /// Write the two lines to `out`.
    pub fn write(&self, out: &mut impl Write) -> std::io::Result<()> {
        let (du, fu, tu) = (self.units.depth(), self.units.force(), self.units.torque());
        let op = &self.case.operation;
        // the string turns only when the mode rotates it (sliding and tripping: the rpm of the
        // case is not applied, Operation::omega_rad_s)
        let rotation = if op.omega_rad_s() > 0.0 {
            format!("{} rpm", fixed(op.rpm, 0))
        } else {
            "string not rotating".to_string()
        };
        writeln!(
            out,
            "  mode {}, bit at {} MD, WOB {}, {rotation}",
            op.mode.name(),
            du.fmt(op.bit_md_m, 2),
            fu.fmt(self.wob_n, 1),
        )?;
        match self.bit {
            Some(b) => writeln!(
                out,
                "  bit: build force {}, walk force {}, tilt inc {} deg, tilt azi {} deg, torque {}",
                fu.fmt_signed(b.build_force_n, 3),
                fu.fmt_signed(b.walk_force_n, 3),
                signed(b.tilt_inc_rad.to_degrees(), 4),
                signed(b.tilt_azi_rad.to_degrees(), 4),
                tu.fmt(b.torque_nm, 2)
            ),
            None => writeln!(
                out,
                "  bit: torque {}; side forces and tilt not computed (soft string: no bending)",
                tu.fmt(self.bit_torque_nm, 2)
            ),
        }
    }
}

fn print_summary(
    a: &SolveArgs,
    case: &Case,
    lr: &LevelResult,
    summary: &serde_json::Value,
    out: &mut impl Write,
) -> std::io::Result<()> {
    let (du, fu, tu) = (a.view.units.depth(), a.view.units.force(), a.view.units.torque());
    writeln!(out, "solve: {} ({})", case.name, a.case.display())?;
    writeln!(out, "  fidelity {}: {}", lr.choice.level.name(), lr.choice.reason)?;
    if let Some(cut) = lr.cut_m {
        writeln!(
            out,
            "  stiff model cut {} above the bit (on the wall, parallel to the hole); results reported up to {} above the bit",
            du.fmt(cut, 1),
            du.fmt(summary["fidelity"]["coupling_m"].as_f64().unwrap_or(cut), 1)
        )?;
    }
    if !lr.converged {
        writeln!(
            out,
            "  WARNING: NOT CONVERGED - results below are flagged and not valid"
        )?;
    }
    BitLines {
        units: a.view.units,
        case,
        wob_n: lr.wob_n,
        bit: lr.bit.as_ref(),
        bit_torque_nm: lr.bit_torque_nm,
    }
    .write(out)?;
    match (lr.hook_load_n, lr.surface_torque_nm) {
        (Some(h), Some(t)) => writeln!(out, "  surface: hook load {}, torque {}", fu.fmt(h, 1), tu.fmt(t, 2))?,
        _ => writeln!(
            out,
            "  surface: not computed (bha: the stiff model ends at the cut; use hybrid or whole)"
        )?,
    }
    let b = &summary["buckling"];
    let km = |k: &str| b[k].as_f64().unwrap_or(0.0);
    writeln!(
        out,
        "  buckling: sinusoidal over {}, helical over {} (max compression {})",
        du.fmt(km("sinusoidal_length_m"), 1),
        du.fmt(km("helical_length_m"), 1),
        fu.fmt(km("max_compression_kN") * 1e3, 1)
    )?;
    writeln!(out, "  time {:.4} s", lr.seconds)?;
    if let Some(dir) = &a.out {
        writeln!(out, "  wrote {}/summary.json and string.csv", dir.display())?;
    }
    Ok(())
}

/// The solve report of a `bha` or `hybrid` result: the stiff part from the bit to the coupling
/// point, with the level's hook load and surface torque (hybrid) or none (bha).
fn write_level_report(file: &std::path::Path, a: &SolveArgs, case: &Case, lr: &LevelResult) -> anyhow::Result<()> {
    // soft is refused before the solve (cli::solve)
    let Some((res, marks, surface)) = crate::report::levels_output::reported_stiff_part(case, lr) else {
        bail!(
            "internal error: no stiff part to report for fidelity {}",
            lr.choice.level.name()
        );
    };
    let fem = lr.fem.as_ref().expect("a stiff part");
    let shown = res
        .nodes
        .last()
        .map(|n| case.operation.bit_md_m - n.md_m)
        .unwrap_or(0.0);
    let note = format!(
        "Fidelity {}: stiff model of the bottom {} of the string only (cut {} above the bit, results shown up to the coupling point); {}",
        lr.choice.level.name(),
        a.view.units.depth().fmt(shown, 1),
        a.view.units.depth().fmt(lr.cut_m.unwrap_or(shown), 1),
        if surface {
            "hook load and surface torque from the soft string above the coupling point."
        } else {
            "no hook load or surface torque (use hybrid or whole)."
        }
    );
    let scope = crate::report::solve_report::ReportOptions {
        units: a.view.units,
        note: Some(note),
        no_surface_values: !surface,
    };
    crate::report::solve_report::write(file, case, &res, &marks, &fem.stats, lr.converged, &scope)
}
