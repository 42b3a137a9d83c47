//! `drillpath solve`: static whole-string solve at the bit depth.

use super::args::SolveArgs;
use super::parse_length_option;
use super::solve_levels::BitLines;
use crate::error::InputError;
use crate::io::case_toml::{load_case, CaseOverrides};
use crate::models::fem::model::Model;
use crate::models::fem::results::extract;
use crate::models::fem::solve::{solve, SolveControls};
use crate::report::display_units::fixed;
use crate::report::solve_output::{string_csv, summary_json};
use crate::report::write_atomic;
use anyhow::{bail, Context};
use std::io::Write;

/// Run the command (`quiet`: no progress bar).
pub fn run(a: SolveArgs, quiet: bool) -> anyhow::Result<()> {
    let bit_md = a
        .bit_md
        .as_deref()
        .map(|t| parse_length_option("--bit-md", t))
        .transpose()?;
    let mut case = load_case(
        &a.case,
        &CaseOverrides {
            survey_md_unit: None,
            bit_md_m: bit_md,
        },
    )?;
    if case.string.components.is_empty() {
        bail!("{}: the case has no [[string]] components to solve", a.case.display());
    }
    let choice = super::solve_levels::configure(&a, &mut case)?;
    if choice.level != crate::case::fidelity::Level::Whole {
        if a.view.report.is_some() && choice.level == crate::case::fidelity::Level::Soft {
            return Err(InputError::option(
                "--report",
                "fidelity soft has no stiff results to draw (contacts, deflection, stresses along the string); use bha, hybrid or whole",
            )
            .into());
        }
        return super::solve_levels::run(&a, &case, choice, quiet);
    }
    let model = Model::from_case(&case);
    let ctl = SolveControls::from_settings(&case.solver);
    let sol = solve(&model, &ctl).with_context(|| format!("{}: solve failed", a.case.display()))?;
    let res = extract(&model, &sol, case.mud.density_kg_m3);
    if !sol.converged && !a.allow_unconverged {
        let hist = &sol.stats.residual_history;
        let tail: Vec<String> = hist.iter().rev().take(5).rev().map(|r| format!("{r:.2e}")).collect();
        let chatter: Vec<String> = sol
            .stats
            .chattering_nodes
            .iter()
            .take(10)
            .map(|&i| format!("{:.1} m", model.md_ref[i]))
            .collect();
        bail!(
            "{}: the solve did not converge in {} iterations (last relative residuals {}; max penetration {:.2e} of clearance; contacts switching at MD {}); no results written (use --allow-unconverged to write flagged results, or --fidelity hybrid for the bit forces from the stiff bottom-hole assembly with the soft string above){}",
            a.case.display(),
            sol.stats.iterations,
            tail.join(", "),
            sol.stats.max_penetration,
            if chatter.is_empty() { "none".into() } else { chatter.join(", ") },
            hints_suffix(&case)
        );
    }
    let mut summary = summary_json(&res, &sol.stats, sol.converged, model.dofs(), model.nodes() - 1)
        .map_err(|e| anyhow::anyhow!("internal error: {e}"))?;
    let csv = string_csv(&res).map_err(|e| anyhow::anyhow!("internal error: {e}"))?;
    let (csv, marks) =
        super::solve_levels::annotate_whole(&case, &choice, &model, &res, sol.stats.seconds, &mut summary, csv)?;
    write_outputs(a.out.as_deref(), &summary, &csv)?;
    if let Some(file) = &a.view.report {
        crate::report::solve_report::write(
            file,
            &case,
            &res,
            &marks,
            &sol.stats,
            sol.converged,
            &crate::report::solve_report::ReportOptions {
                units: a.view.units,
                ..Default::default()
            },
        )?;
    }
    let mut out = std::io::stdout().lock();
    if a.view.json {
        writeln!(out, "{}", serde_json::to_string_pretty(&summary)?)?;
        return Ok(());
    }
    let (du, fu) = (a.view.units.depth(), a.view.units.force());
    let b = &res.bit;
    let contacts: Vec<_> = res.nodes.iter().filter(|n| n.contact_force_n > 1.0).collect();
    writeln!(out, "solve: {} ({})", case.name, a.case.display())?;
    writeln!(out, "  fidelity whole: {}", choice.reason)?;
    if !sol.converged {
        writeln!(
            out,
            "  WARNING: NOT CONVERGED - results below are flagged and not valid"
        )?;
    }
    let lines = BitLines {
        units: a.view.units,
        case: &case,
        wob_n: b.wob_n,
        bit: Some(b),
        bit_torque_nm: b.torque_nm,
    };
    lines.write(&mut out)?;
    writeln!(
        out,
        "  surface: hook load {}, torque {}",
        fu.fmt(res.hook_load_n, 1),
        a.view.units.torque().fmt(res.surface_torque_nm, 2)
    )?;
    if let (Some(first), Some(last)) = (contacts.first(), contacts.last()) {
        let near: Vec<String> = contacts
            .iter()
            .filter(|n| b.md_m - n.md_m < 60.0)
            .take(6)
            .map(|n| {
                format!(
                    "{}: {} at {} deg",
                    du.fmt(b.md_m - n.md_m, 1),
                    fu.fmt(n.contact_force_n, 2),
                    fixed(n.contact_angle_deg, 0)
                )
            })
            .collect();
        writeln!(
            out,
            "  contacts: {} nodes between {} and {} MD; max {}",
            contacts.len(),
            du.fmt(last.md_m, 1),
            du.fmt(first.md_m, 1),
            fu.fmt(contacts.iter().map(|n| n.contact_force_n).fold(0.0, f64::max), 2)
        )?;
        if !near.is_empty() {
            writeln!(out, "  near the bit (distance above bit): {}", near.join("; "))?;
        }
    } else {
        writeln!(out, "  contacts: none")?;
    }
    writeln!(out, "  solver: {} iterations, {} factorizations, {} DOF, {} elements, {:.3} s, equilibrium error {:.1e} of the largest force",
        sol.stats.iterations, sol.stats.factorizations, model.dofs(), model.nodes() - 1, sol.stats.seconds,
        res.force_imbalance_n.norm() / res.largest_force_n.max(1.0))?;
    if let Some(dir) = &a.out {
        writeln!(out, "  wrote {}/summary.json and string.csv", dir.display())?;
    }
    Ok(())
}

/// The soft-string hints on a non-converged solve ([`crate::models::diagnose`]), as a message suffix.
pub fn hints_suffix(case: &crate::case::Case) -> String {
    crate::models::diagnose::nonconvergence_hints(case)
        .iter()
        .map(|h| format!("; {h}"))
        .collect()
}

/// Write `summary.json` and `string.csv` into `dir` (each atomically), when `--out` is given.
pub fn write_outputs(dir: Option<&std::path::Path>, summary: &serde_json::Value, csv: &str) -> anyhow::Result<()> {
    let Some(dir) = dir else { return Ok(()) };
    write_atomic(
        &dir.join("summary.json"),
        serde_json::to_string_pretty(summary)?.as_bytes(),
    )
    .with_context(|| format!("cannot write {}", dir.display()))?;
    write_atomic(&dir.join("string.csv"), csv.as_bytes()).with_context(|| format!("cannot write {}", dir.display()))
}
