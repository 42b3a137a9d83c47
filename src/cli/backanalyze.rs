//! `drillpath backanalyze`: post-drill back-analysis over the survey, with optional
//! calibration of the bit-rock law (calibrated on the first part, scored on the rest).

use super::args::BackanalyzeArgs;
use super::outputs::{names, Outputs};
use super::predict::{load_for_prediction, prediction_choice, settings_for};
use super::progress::Progress;
use super::{bare_unit, length_opt, parse_length_option};
use crate::case::Case;
use crate::predict::backanalysis::Progress as Stage;
use crate::predict::backanalysis::{plan, run as run_backanalysis, BackanalysisRequest, CalibrationRequest};
use crate::predict::calibrate::FitParameter;
use crate::predict::march::MIN_STEP_M;
use crate::report::fitted_case::fitted_case_toml;
use crate::report::json_text;
use crate::report::predict_output::{backanalysis_csv, fitted_toml, BackanalysisRun, BackanalysisSummary};
use crate::report::predict_report::backanalyze_html;
use crate::report::predict_text::write_backanalysis;
use crate::report::witsml_out::{trajectories_xml, OutStation, OutTrajectory};
use anyhow::{anyhow, bail};
use std::io::Write;
use std::path::Path;

/// The back-analysis asked by the command line (options validated, SI; bare numbers in `unit`).
fn request(a: &BackanalyzeArgs, unit: &str) -> anyhow::Result<BackanalysisRequest> {
    let from_md_m = a
        .from
        .as_deref()
        .map(|t| parse_length_option("--from", t, unit))
        .transpose()?;
    let to_md_m =
        a.to.as_deref()
            .map(|t| parse_length_option("--to", t, unit))
            .transpose()?;
    let horizon_m = length_opt("--horizon", &a.horizon, 0.0, unit)?.unwrap_or(0.0);
    if !(a.split > 0.0 && a.split < 1.0) {
        bail!("option `--split`: {} must lie strictly between 0 and 1", a.split);
    }
    let parameters: Vec<FitParameter> = a
        .fit
        .split(',')
        .map(|s| s.trim())
        .filter(|s| !s.is_empty())
        .map(|s| {
            FitParameter::parse(s).ok_or_else(|| {
                anyhow!(
                    "option `--fit`: unknown parameter `{s}` (expected {})",
                    FitParameter::NAMES
                )
            })
        })
        .collect::<anyhow::Result<_>>()?;
    if a.calibrate && parameters.is_empty() {
        bail!("option `--fit`: no parameter to fit");
    }
    Ok(BackanalysisRequest {
        from_md_m,
        to_md_m,
        horizon_m,
        assimilate: a.assimilate,
        calibration: a.calibrate.then_some(CalibrationRequest {
            parameters,
            split: a.split,
        }),
    })
}

/// The predicted interval ends of `b` as a WITSML trajectory, tied in at the first interval's
/// start on the measured hole of `case`.
fn backanalysis_witsml(case: &Case, b: &crate::predict::backanalysis::Backanalysis) -> Result<String, String> {
    let mut stations = Vec::with_capacity(b.results.len() + 1);
    if let Some(first) = b.results.first() {
        let p = case.well.path.point_at(first.interval.from_md_m);
        stations.push(OutStation {
            md_m: p.md_m,
            inc_rad: p.inc_rad,
            azi_rad: p.azi_rad,
            position: p.position,
        });
    }
    for r in &b.results {
        if stations
            .last()
            .is_some_and(|s: &OutStation| r.interval.to_md_m <= s.md_m)
        {
            continue;
        }
        stations.push(OutStation {
            md_m: r.interval.to_md_m,
            inc_rad: r.inc_rad,
            azi_rad: r.azi_rad,
            position: r.position,
        });
    }
    trajectories_xml(&[OutTrajectory {
        name: format!("{} (back-analysis)", case.name),
        stations,
        survey: &case.well.survey,
    }])
}

/// The run's outputs, checked against its inputs before any work.
fn declared_outputs(a: &BackanalyzeArgs, cases: &[Case]) -> anyhow::Result<Outputs> {
    let mut outputs = Outputs::new();
    for c in cases {
        outputs.case_inputs(c);
    }
    if let Some(dir) = &a.out {
        let mut files = vec!["trajectory.csv", "summary.json"];
        if a.calibrate {
            files.extend(["bit_rock_fitted.toml", "case_fitted.toml"]);
        }
        outputs.dir("--out", dir, &names(&files))?;
    }
    if let Some(file) = &a.view.report {
        outputs.file("--report", file)?;
    }
    if let Some(file) = &a.witsml {
        outputs.file("--witsml", file)?;
    }
    Ok(outputs)
}

/// Run the command (`quiet`: no progress bar).
pub fn run(a: BackanalyzeArgs, quiet: bool) -> anyhow::Result<()> {
    let mut cases = Vec::with_capacity(a.cases.len());
    let mut settings = Vec::with_capacity(a.cases.len());
    let mut choices = Vec::with_capacity(a.cases.len());
    for path in &a.cases {
        let mut c = load_for_prediction(path)?;
        let step = length_opt("--step", &a.step, MIN_STEP_M, bare_unit(&c))?;
        let choice = prediction_choice(&mut c, &a.model.fidelity, &a.model.accuracy)?;
        settings.push(settings_for(&c, step, None, &choice)?);
        choices.push(choice);
        cases.push(c);
    }
    let (case, choice) = (&cases[0], &choices[0]);
    let case_file = &a.cases[0];
    let req = request(&a, bare_unit(case))?;
    let mut outputs = declared_outputs(&a, &cases)?;
    let name = case_file.display().to_string();
    let plan = plan(case, &req).map_err(|e| anyhow!("{name}: {e}"))?;
    plan.check_size(settings[0].step_m)
        .map_err(|e| anyhow!("{name}: {e}"))?;
    let bar = Progress::new(plan.intervals.len() as u64, &format!("backanalyze {name}"), quiet);
    let mut spinner: Option<Progress> = None;
    let mut bar = Some(bar);
    let result = run_backanalysis(&cases, &plan, &settings, &mut |stage| match stage {
        Stage::Interval { done, of } => {
            if let Some(b) = &bar {
                b.set(done as u64, &format!("interval {done}/{of}"));
            }
        }
        Stage::CalibrationStarted => {
            if let Some(b) = bar.take() {
                b.finish();
            }
            // the calibration's number of evaluations is not known ahead: a spinner
            spinner = Some(Progress::spinner(&format!("backanalyze {name}: calibration"), quiet));
        }
        Stage::Calibration(m) => {
            if let Some(s) = &spinner {
                s.message(m);
            }
        }
    });
    for p in bar.into_iter().chain(spinner) {
        p.finish();
    }
    let b = result.map_err(|e| anyhow!("{name}: {e}"))?;
    let later: Vec<(&Case, &Path)> = cases[1..]
        .iter()
        .zip(&a.cases[1..])
        .map(|(c, f)| (c, f.as_path()))
        .collect();
    let shown = BackanalysisRun {
        case,
        case_file,
        plan: &plan,
        step_m: settings[0].step_m,
        choice,
        result: &b,
        later_runs: &later,
    };
    let internal = |e: String| anyhow!("internal error: {e}");
    let summary = json_text(&BackanalysisSummary::new(&shown)).map_err(internal)?;
    if let Some(dir) = &a.out {
        outputs.stage(dir.join("trajectory.csv"), backanalysis_csv(&b).map_err(internal)?);
        if let Some(c) = &b.calibration {
            outputs.stage(dir.join("bit_rock_fitted.toml"), fitted_toml(&c.calibration));
            let text = std::fs::read_to_string(case_file)
                .map_err(|e| anyhow!("{}: cannot read it again: {e}", case_file.display()))?;
            let case_dir = case_file.parent().unwrap_or(Path::new(""));
            let fitted = fitted_case_toml(&text, case_dir, dir, &c.calibration)
                .map_err(|e| anyhow!("{}: {e}", case_file.display()))?;
            outputs.stage(dir.join("case_fitted.toml"), fitted);
        }
        outputs.stage(dir.join("summary.json"), summary.as_bytes());
    }
    if let Some(file) = &a.view.report {
        outputs.stage(file.clone(), backanalyze_html(case, &b, a.view.units)?);
    }
    if let Some(file) = &a.witsml {
        outputs.stage(file.clone(), backanalysis_witsml(case, &b).map_err(internal)?);
    }
    outputs.commit()?;
    let mut out = std::io::stdout().lock();
    if a.view.json {
        writeln!(out, "{summary}")?;
        return Ok(());
    }
    write_backanalysis(&mut out, &shown, a.view.units)?;
    if let Some(dir) = &a.out {
        writeln!(out, "  wrote {}", dir.display())?;
        if b.calibration.is_some() {
            writeln!(
                out,
                "  {}: the case with the fitted law, to run as it is (bit_rock_fitted.toml: the fitted keys alone, to set in a case's [bit_rock] table)",
                dir.join("case_fitted.toml").display()
            )?;
        }
    }
    if let Some(file) = &a.view.report {
        writeln!(out, "  wrote {}", file.display())?;
    }
    Ok(())
}
