//! `drillpath loads`: torque-and-drag chart, limits, optional stiff rows and friction
//! calibration (computed by [`crate::loads::run`], printed by [`crate::report::loads_text`]).

use super::args::LoadsArgs;
use super::outputs::{names, Outputs};
use super::progress::Progress;
use super::{apply_accuracy_option, fidelity_option, length_opt};
use crate::case::fidelity::{choose, Choice, Level, Purpose};
use crate::case::{Case, Fidelity};
use crate::error::InputError;
use crate::io::case_toml::{load_case, CaseOverrides};
use crate::io::measured_csv::read_measured_csv;
use crate::loads::run::{bit_depth_range, plan, run as run_chart, ChartError, ChartRequest};
use crate::report::json_text;
use crate::report::loads_output::{loads_csv, overlay_csv, CalibrationSummary};
use crate::report::loads_text::write_loads;
use crate::units::{parse_quantity, Dimension};
use std::io::Write;
use std::path::Path;

/// Default bit-depth step, m.
pub const DEFAULT_EVERY_M: f64 = 30.0;

/// The bit-depth options of the command line, validated, SI: from, to, every (m) and WOB (N).
type DepthOptions = (f64, Option<f64>, f64, Option<f64>);

/// Parse and check `--from`, `--to`, `--every` (bare numbers in `unit`) and `--wob`.
fn depth_options(a: &LoadsArgs, unit: &str) -> anyhow::Result<DepthOptions> {
    let from_md_m = length_opt("--from", &a.from, 0.0, unit)?.unwrap_or(0.0);
    let to_md_m = length_opt("--to", &a.to, f64::NEG_INFINITY, unit)?;
    let every_m = length_opt("--every", &a.every, f64::NEG_INFINITY, unit)?.unwrap_or(DEFAULT_EVERY_M);
    let wob_n = a
        .wob
        .as_deref()
        .map(|t| parse_quantity(t, Dimension::Force, "kN").map_err(|m| InputError::option("--wob", m)))
        .transpose()?;
    if every_m <= 0.0 {
        return Err(InputError::option("--every", "the bit-depth step must be positive").into());
    }
    if wob_n.is_some_and(|w| w < 0.0) {
        return Err(InputError::option("--wob", "the weight on bit must not be negative").into());
    }
    Ok((from_md_m, to_md_m, every_m, wob_n))
}

/// The chart asked by the command line for `case` (the measured file read).
fn request(a: &LoadsArgs, case: &Case, options: DepthOptions) -> anyhow::Result<ChartRequest> {
    let (from_md_m, to_md_m, every_m, wob_n) = options;
    let measured = match &a.measured {
        Some(m) => {
            let (md_start, deepest) = bit_depth_range(case);
            read_measured_csv(m, md_start, deepest)?
        }
        None => Vec::new(),
    };
    Ok(ChartRequest {
        from_md_m,
        to_md_m,
        every_m,
        wob_n,
        choice: chart_fidelity(a, case)?,
        measured,
    })
}

/// The error of a chart that cannot be computed, named by the option or file it comes from.
fn chart_error(e: ChartError, a: &LoadsArgs) -> anyhow::Error {
    let measured = a.measured.as_deref().unwrap_or(Path::new("measured.csv"));
    match e {
        ChartError::NoString => anyhow::anyhow!("{}: {e}", a.case.display()),
        ChartError::TooManyDepths(_) => InputError::option("--every", e.to_string()).into(),
        ChartError::MeasuredDoesNotFit { line, message } => InputError::line(measured, line, None, message).into(),
        ChartError::Calibration(c) => {
            anyhow::Error::new(c).context(format!("{}: friction calibration", measured.display()))
        }
        _ => InputError::option("--to", e.to_string()).into(),
    }
}

/// The run's outputs, checked against its inputs (the case and the measured file) before any
/// work.
fn declared_outputs(a: &LoadsArgs, case: &Case) -> anyhow::Result<Outputs> {
    let mut outputs = Outputs::new();
    outputs.case_inputs(case);
    if let Some(m) = &a.measured {
        outputs.input(m);
    }
    if let Some(dir) = &a.out {
        let mut files = vec!["loads.csv"];
        if a.measured.is_some() {
            files.extend(["calibration.csv", "calibration.json"]);
        }
        outputs.dir("--out", dir, &names(&files))?;
    }
    Ok(outputs)
}

/// Run the command (`quiet`: no progress bar).
pub fn run(a: LoadsArgs, quiet: bool) -> anyhow::Result<()> {
    let mut case = load_case(&a.case, &CaseOverrides::default())?;
    let options = depth_options(&a, super::bare_unit(&case))?;
    if case.string.components.is_empty() {
        return Err(chart_error(ChartError::NoString, &a));
    }
    apply_accuracy_option(a.accuracy.as_deref(), &mut case.solver)?;
    let mut outputs = declared_outputs(&a, &case)?;
    let req = request(&a, &case, options)?;
    let plan = plan(&case, &req).map_err(|e| chart_error(e, &a))?;
    let depth_unit = a.units.depth();
    let progress = (plan.choice.level != Level::Soft).then(|| {
        Progress::new(
            plan.depths.len() as u64,
            &format!("loads {}: {}", a.case.display(), plan.choice.level.name()),
            quiet,
        )
    });
    let chart = run_chart(&case, &plan, &mut |k, d| {
        if let Some(p) = &progress {
            p.set(k as u64, &format!("bit at {}", depth_unit.fmt(d, 1)));
        }
    });
    if let Some(p) = progress {
        p.finish();
    }
    let chart = chart.map_err(|e| chart_error(e, &a))?;
    let internal = |e: String| anyhow::anyhow!("internal error: {e}");
    if let Some(dir) = &a.out {
        if let Some(cal) = &chart.calibration {
            outputs.stage(dir.join("calibration.csv"), overlay_csv(cal).map_err(internal)?);
            let json = json_text(&CalibrationSummary::new(cal)).map_err(internal)?;
            outputs.stage(dir.join("calibration.json"), json);
        }
        outputs.stage(dir.join("loads.csv"), loads_csv(&chart.rows).map_err(internal)?);
    }
    outputs.commit()?;
    let mut out = std::io::stdout().lock();
    write_loads(&mut out, &case, &a.case, &plan, &chart, a.units)?;
    match &a.out {
        Some(dir) => writeln!(out, "  wrote {}/loads.csv", dir.display())?,
        None => writeln!(out, "  (use --out DIR to write loads.csv)")?,
    }
    Ok(())
}

/// The level the chart runs: `--fidelity` (or `--stiff` = whole) over the case's `[solver]
/// fidelity`, `auto` = soft; `bha` (no surface values) is refused.
fn chart_fidelity(a: &LoadsArgs, case: &Case) -> Result<Choice, InputError> {
    if a.stiff {
        if let Some(f) = a.fidelity.as_deref().filter(|f| f.trim() != "whole") {
            return Err(InputError::option(
                "--stiff",
                format!("--stiff is --fidelity whole; it cannot be combined with --fidelity {f}"),
            ));
        }
    }
    let requested = if a.stiff {
        Fidelity::Level(Level::Whole)
    } else {
        fidelity_option(a.fidelity.as_deref(), case.solver.fidelity)?
    };
    let choice = choose(requested, Purpose::Loads);
    if choice.level == Level::Bha {
        let msg = "fidelity bha has no hook load or surface torque (the stiff model ends at the cut above the bottom-hole assembly), which the chart is made of: use soft, hybrid or whole";
        return Err(if a.fidelity.is_some() {
            InputError::option("--fidelity", msg)
        } else {
            InputError::key(
                &case.path,
                "solver.fidelity",
                format!("{msg} (or override with --fidelity)"),
            )
        });
    }
    Ok(choice)
}
