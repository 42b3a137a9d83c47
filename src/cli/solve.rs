//! `drillpath solve`: a static solve of the string at the bit depth, at a fidelity level.

use super::args::SolveArgs;
use super::outputs::{names, Outputs};
use super::parse_length_option;
use super::progress::Progress;
use crate::case::{Case, Level, Purpose};
use crate::error::InputError;
use crate::io::case_toml::{load_case, CaseOverrides};
use crate::models::diagnose::{known_limit_hints, nonconvergence_hints, solve_state_summary, stop_phrase};
use crate::models::fem::solve::SolveControls;
use crate::models::levels::stages;
use crate::models::string_solve::{solve_string, StringSolve};
use crate::report::json_text;
use crate::report::solve_output::{string_csv, SolveSummary};
use crate::report::solve_report::solve_html;
use crate::report::solve_text::{write_summary, SolveView};
use anyhow::{anyhow, bail, Context};
use std::io::Write;

/// Run the command (`quiet`: no progress bar).
pub fn run(a: SolveArgs, quiet: bool) -> anyhow::Result<()> {
    let mut case = load(&a)?;
    let choice = super::model_choice(a.fidelity.as_deref(), a.accuracy.as_deref(), &mut case, Purpose::Solve)?;
    let mut outputs = Outputs::new();
    outputs.case_inputs(&case);
    if let Some(dir) = &a.out {
        outputs.dir("--out", dir, &names(&["summary.json", "string.csv"]))?;
    }
    if let Some(file) = &a.view.report {
        outputs.file("--report", file)?;
    }
    if a.view.report.is_some() && choice.level == Level::Soft {
        return Err(InputError::option(
            "--report",
            "fidelity soft has no stiff results to draw (contacts, deflection, stresses along the string); use bha, hybrid or whole",
        )
        .into());
    }
    let n = stages(choice.level);
    // one stage: a spinner, so that a long whole-string solve shows it is working
    let progress = if n > 1 {
        Progress::new(n as u64, &format!("solve {}", a.case.display()), quiet)
    } else {
        Progress::spinner(&format!("solve {}: {}", a.case.display(), choice.level.name()), quiet)
    };
    let solved = solve_string(
        &case,
        choice,
        &SolveControls::from_settings(&case.solver),
        &mut |k, _, what| progress.set(k as u64, what),
    );
    progress.finish();
    let s = solved.with_context(|| format!("{}: solve failed", a.case.display()))?;
    if !s.level.converged && !a.allow_unconverged {
        bail!("{}", not_converged_message(&a, &case, &s));
    }
    let steering = crate::predict::steer::steering(&case, &SolveControls::from_settings(&case.solver)).map(|mut st| {
        st.reactive_turn = s.level.fem.as_ref().and_then(|p| p.stats.reactive_turn);
        st
    });
    let rss = crate::predict::steer::rss_steering(&case, &SolveControls::from_settings(&case.solver));
    let summary = json_text(
        &SolveSummary::new(&case, &s)
            .with_steering(steering.as_ref())
            .with_rss(rss.as_ref()),
    )
    .map_err(|e| anyhow!("internal error: {e}"))?;
    if let Some(dir) = &a.out {
        let csv = string_csv(&case, &s).map_err(|e| anyhow!("internal error: {e}"))?;
        outputs.stage(dir.join("summary.json"), summary.as_bytes());
        outputs.stage(dir.join("string.csv"), csv);
    }
    // a whole solve answered by the soft string (lock-up at zero WOB) has nothing to draw
    let report = a.view.report.as_ref().filter(|_| s.level.fem.is_some());
    if let Some(file) = report {
        outputs.stage(
            file.clone(),
            solve_html(&case, &s, a.view.units, steering.as_ref(), rss.as_ref())?,
        );
    }
    outputs.commit()?;
    if let (Some(file), None) = (&a.view.report, report) {
        eprintln!(
            "note: {} not written: the answer is the soft string's (lock-up at zero WOB), which has no stiff results to draw",
            file.display()
        );
    }
    let mut out = std::io::stdout().lock();
    if a.view.json {
        writeln!(out, "{summary}")?;
        return Ok(());
    }
    let view = SolveView {
        case_file: &a.case,
        units: a.view.units,
        out_dir: a.out.as_deref(),
        report: report.map(|p| p.as_path()),
        steering: steering.as_ref(),
        rss: rss.as_ref(),
    };
    write_summary(&mut out, &case, &s, &view)?;
    Ok(())
}

/// The case with `--bit-md` applied (a bare number in the survey's depth unit: the case is
/// read once to know it); it must have a string.
fn load(a: &SolveArgs) -> anyhow::Result<Case> {
    let mut case = load_case(&a.case, &CaseOverrides::default())?;
    if let Some(t) = a.bit_md.as_deref() {
        let bit_md = parse_length_option("--bit-md", t, super::bare_unit(&case))?;
        case = load_case(
            &a.case,
            &CaseOverrides {
                survey_md_unit: None,
                bit_md_m: Some(bit_md),
            },
        )?;
    }
    if case.string.components.is_empty() {
        bail!("{}: the case has no [[string]] components to solve", a.case.display());
    }
    Ok(case)
}

/// The error of a solve that did not converge: where it stopped, what the soft string says
/// about the case, and what the user can do.
fn not_converged_message(a: &SolveArgs, case: &Case, s: &StringSolve) -> String {
    let hints: String = known_limit_hints(case)
        .into_iter()
        .chain(nonconvergence_hints(case))
        .map(|h| format!("; {h}"))
        .collect();
    let lr = &s.level;
    let ctl = SolveControls::from_settings(&case.solver);
    let stop = lr.fem.as_ref().map(|f| stop_phrase(&f.stats, &ctl)).unwrap_or_default();
    match (&lr.fem, lr.choice.level) {
        (Some(part), Level::Whole) => format!(
            "{}: the solve did not converge {stop} ({}); no results written (use --allow-unconverged to write flagged results, or --fidelity hybrid for the bit forces from the stiff bottom-hole assembly with the soft string above){hints}",
            a.case.display(),
            solve_state_summary(part),
        ),
        _ => format!(
            "{}: the stiff bottom-hole-assembly solve did not converge {stop}; no results written (use --allow-unconverged to write flagged results, or --fidelity soft){hints}",
            a.case.display(),
        ),
    }
}
