//! `drillpath solve`: static whole-string solve at the bit depth.

use super::args::SolveArgs;
use super::parse_length_option;
use crate::fem::model::Model;
use crate::fem::results::extract;
use crate::fem::solve::{solve, SolveControls};
use crate::io::case_toml::{load_case, CaseOverrides};
use crate::report::solve_output::{string_csv, summary_json};
use crate::report::write_atomic;
use anyhow::{bail, Context};

/// Run the command.
pub fn run(a: SolveArgs) -> anyhow::Result<()> {
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
    if choice.level != crate::fidelity::Level::Whole {
        return super::solve_levels::run(&a, &case, choice);
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
            "{}: the solve did not converge in {} iterations (last relative residuals {}; max penetration {:.2e} of clearance; contacts switching at MD {}); no results written (use --allow-unconverged to write flagged results){}",
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
    let csv = super::solve_levels::annotate_whole(&case, &choice, &model, &res, sol.stats.seconds, &mut summary, csv)?;
    if let Some(dir) = &a.out {
        write_atomic(
            &dir.join("summary.json"),
            serde_json::to_string_pretty(&summary)?.as_bytes(),
        )
        .with_context(|| format!("cannot write {}", dir.display()))?;
        write_atomic(&dir.join("string.csv"), csv.as_bytes())
            .with_context(|| format!("cannot write {}", dir.display()))?;
    }
    if let Some(file) = &a.report {
        crate::report::solve_report::write(file, &case, &res, &sol.stats, sol.converged, a.units)?;
    }
    if a.json {
        println!("{}", serde_json::to_string_pretty(&summary)?);
        return Ok(());
    }
    let b = &res.bit;
    let contacts: Vec<_> = res.nodes.iter().filter(|n| n.contact_force_n > 1.0).collect();
    println!("solve: {} ({})", case.name, a.case.display());
    println!("  fidelity whole: {}", choice.reason);
    if !sol.converged {
        println!("  WARNING: NOT CONVERGED - results below are flagged and not valid");
    }
    println!(
        "  mode {}, bit at {:.2} m MD, WOB {:.1} kN, {:.0} rpm",
        case.operation.mode.name(),
        b.md_m,
        b.wob_n / 1e3 + 0.0,
        case.operation.rpm
    );
    println!("  bit: build force {:+.3} kN, walk force {:+.3} kN, tilt inc {:+.4} deg, tilt azi {:+.4} deg, torque {:.2} kN.m",
        b.build_force_n / 1e3, b.walk_force_n / 1e3, b.tilt_inc_rad.to_degrees(), b.tilt_azi_rad.to_degrees(), b.torque_nm / 1e3);
    println!(
        "  surface: hook load {:.1} kN, torque {:.2} kN.m",
        res.hook_load_n / 1e3,
        res.surface_torque_nm / 1e3
    );
    if let (Some(first), Some(last)) = (contacts.first(), contacts.last()) {
        let near: Vec<String> = contacts
            .iter()
            .filter(|n| b.md_m - n.md_m < 60.0)
            .take(6)
            .map(|n| {
                format!(
                    "{:.1} m: {:.2} kN at {:.0} deg",
                    b.md_m - n.md_m,
                    n.contact_force_n / 1e3,
                    n.contact_angle_deg
                )
            })
            .collect();
        println!(
            "  contacts: {} nodes between {:.1} m and {:.1} m MD; max {:.2} kN",
            contacts.len(),
            last.md_m,
            first.md_m,
            contacts.iter().map(|n| n.contact_force_n).fold(0.0, f64::max) / 1e3
        );
        if !near.is_empty() {
            println!("  near the bit (distance above bit): {}", near.join("; "));
        }
    } else {
        println!("  contacts: none");
    }
    println!("  solver: {} iterations, {} factorizations, {} DOF, {} elements, {:.3} s, equilibrium error {:.1e} of the largest force",
        sol.stats.iterations, sol.stats.factorizations, model.dofs(), model.nodes() - 1, sol.stats.seconds,
        res.force_imbalance_n.norm() / res.largest_force_n.max(1.0));
    if let Some(dir) = &a.out {
        println!("  wrote {}/summary.json and string.csv", dir.display());
    }
    Ok(())
}

/// The soft-string hints on a non-converged solve ([`crate::diagnose`]), as a message suffix.
pub fn hints_suffix(case: &crate::case::Case) -> String {
    crate::diagnose::nonconvergence_hints(case)
        .iter()
        .map(|h| format!("; {h}"))
        .collect()
}
