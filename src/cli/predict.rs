//! `drillpath predict`: forward-marching prediction, tracking against the survey, and the
//! comparison of several BHAs.

use super::args::PredictArgs;
use super::progress::Progress;
use super::{length_opt, parse_length_option};
use crate::case::fidelity::{Choice, Level, Purpose};
use crate::case::Case;
use crate::io::case_toml::{load_case, CaseOverrides};
use crate::predict::forecast::{forecast, settings_at_level, Forecast, ForecastRequest};
use crate::predict::march::{MarchSettings, MIN_STEP_M};
use crate::report::display_units::UnitSystem;
use crate::report::predict_output::{comparison_csv, forecast_csv, ComparisonSummary, PredictSummary};
use crate::report::predict_text::{comparison_table, write_forecast};
use crate::report::{json_text, write_atomic};
use anyhow::{bail, Context};
use std::io::Write;
use std::path::Path;

/// A case checked for prediction: a string, on bottom, with a positive WOB.
pub fn load_for_prediction(path: &Path) -> anyhow::Result<Case> {
    let case = load_case(path, &CaseOverrides::default())?;
    if case.string.components.is_empty() {
        bail!("{}: the case has no [[string]] components", path.display());
    }
    if !case.operation.mode.on_bottom() {
        bail!(
            "{}: key `operation.mode`: prediction needs the bit on bottom (drilling or sliding), not `{}`",
            path.display(),
            case.operation.mode.name()
        );
    }
    if case.operation.hook_load_n.is_some() || case.operation.wob_n <= 0.0 {
        bail!(
            "{}: key `operation.wob`: prediction needs a positive weight on bit (a hook load alone does not fix the bit forces)",
            path.display()
        );
    }
    Ok(case)
}

/// March settings of `case` with the command line's step and cut, for the model level of
/// `choice` ([`settings_at_level`]); `--cut` with fidelity whole and fidelity soft are refused.
pub fn settings_for(
    case: &Case,
    step: Option<f64>,
    cut: Option<f64>,
    choice: &Choice,
) -> anyhow::Result<MarchSettings> {
    if choice.level == Level::Whole && cut.is_some() {
        bail!("options `--cut` and fidelity whole exclude each other (whole solves the string to its top)");
    }
    settings_at_level(case, choice.level, step, cut)
        .ok_or_else(|| anyhow::anyhow!("fidelity soft cannot predict (no bit side forces)"))
}

/// The model choice of `predict`/`backanalyze` (`--fidelity`, `--accuracy`, the case's
/// `[solver]` table) applied to `case`.
pub fn prediction_choice(
    case: &mut Case,
    fidelity: &Option<String>,
    accuracy: &Option<String>,
) -> anyhow::Result<Choice> {
    let choice = super::model_choice(fidelity.as_deref(), accuracy.as_deref(), case, Purpose::Predict)?;
    if choice.level == Level::Soft {
        let origin = match fidelity {
            Some(_) => "option `--fidelity`".to_string(),
            None => format!("{}: key `solver.fidelity`", case.path.display()),
        };
        bail!(
            "{origin}: soft cannot predict: the soft string has no bending stiffness, hence no bit side forces or tilt; use auto, bha, hybrid or whole"
        );
    }
    Ok(choice)
}

/// Number of march steps from `from` to `to` of length `step` (the last may be shorter), for
/// the progress bar.
pub fn step_count(from: f64, to: f64, step: f64) -> u64 {
    ((to - from) / step.max(MIN_STEP_M) - 1e-9).ceil().max(1.0) as u64
}

/// One case's forecast with its model choice.
struct CaseRun {
    case: Case,
    choice: Choice,
    forecast: Forecast,
}

fn run_case(path: &Path, a: &PredictArgs, label: &str, quiet: bool) -> anyhow::Result<CaseRun> {
    let mut case = load_for_prediction(path)?;
    let choice = prediction_choice(&mut case, &a.model.fidelity, &a.model.accuracy)?;
    let survey = &case.well.path;
    let from = match &a.from {
        Some(t) => parse_length_option("--from", t)?,
        None => survey.md_end(),
    };
    if from < survey.md_start() - 1e-9 || from > survey.md_end() + 1e-9 {
        bail!(
            "option `--from`: {from:.2} m is outside the survey of {} ({:.2} to {:.2} m)",
            path.display(),
            survey.md_start(),
            survey.md_end()
        );
    }
    let to = match (&a.to, &a.ahead) {
        (Some(t), _) => parse_length_option("--to", t)?,
        (None, Some(t)) => from + parse_length_option("--ahead", t)?,
        (None, None) => bail!("give --to or --ahead"),
    };
    if to < from {
        bail!("option `--to`: {to:.2} m is above the start {from:.2} m");
    }
    let step = length_opt("--step", &a.step, MIN_STEP_M)?;
    let cut = length_opt("--cut", &a.cut, crate::predict::march::MIN_MODEL_LENGTH_M)?;
    let settings = settings_for(&case, step, cut, &choice)?;
    let step_m = settings.step_m;
    if a.extrapolate && step_m < 2.0 * MIN_STEP_M - 1e-9 {
        bail!(
            "option `--extrapolate`: it also marches at half the step, {} m, shorter than the shortest step accepted, {MIN_STEP_M} m; give --step {} m or longer",
            step_m / 2.0,
            2.0 * MIN_STEP_M
        );
    }
    let request = ForecastRequest {
        from_md_m: from,
        to_md_m: to,
        settings,
        extrapolate: a.extrapolate,
        assimilate: a.assimilate,
    };
    let progress = StepProgress::new(&request, label, a.view.units, quiet);
    let result = forecast(&case, &request, &mut |md| progress.step(md));
    progress.finish();
    let forecast = result.map_err(|e| anyhow::anyhow!("{}: {e}", path.display()))?;
    Ok(CaseRun { case, choice, forecast })
}

/// The progress bar of one case's march (both marches when extrapolating: the fine one has
/// twice the steps).
struct StepProgress {
    bar: Progress,
    from: f64,
    to: f64,
    step_m: f64,
    n: u64,
    total: u64,
    units: UnitSystem,
    state: std::cell::Cell<(u64, f64)>,
}

impl StepProgress {
    fn new(r: &ForecastRequest, label: &str, units: UnitSystem, quiet: bool) -> StepProgress {
        let n = step_count(r.from_md_m, r.to_md_m, r.settings.step_m);
        let total = if r.extrapolate { 3 * n } else { n };
        StepProgress {
            bar: Progress::new(total, label, quiet),
            from: r.from_md_m,
            to: r.to_md_m,
            step_m: r.settings.step_m,
            n,
            total,
            units,
            state: std::cell::Cell::new((0, f64::NEG_INFINITY)),
        }
    }
    /// The bit reached `md` (m).
    fn step(&self, md: f64) {
        let (mut done_before, last_md) = self.state.get();
        if md < last_md {
            // the second (fine) march started
            done_before = self.n;
        }
        self.state.set((done_before, md));
        let per = if done_before > 0 {
            self.step_m / 2.0
        } else {
            self.step_m
        };
        let k = ((md - self.from) / per - 1e-6).ceil().max(0.0) as u64;
        let depth_unit = self.units.depth();
        self.bar.set(
            (done_before + k).min(self.total),
            &format!("bit at {} of {}", depth_unit.fmt(md, 1), depth_unit.fmt(self.to, 1)),
        );
    }
    fn finish(self) {
        self.bar.finish();
    }
}

/// Run the command (`quiet`: no progress bar).
pub fn run(a: PredictArgs, quiet: bool) -> anyhow::Result<()> {
    let mut runs = Vec::new();
    for (k, path) in a.cases.iter().enumerate() {
        let label = if a.cases.len() > 1 {
            format!("predict {}/{} {}", k + 1, a.cases.len(), path.display())
        } else {
            format!("predict {}", path.display())
        };
        runs.push(run_case(path, &a, &label, quiet)?);
    }
    let internal = |e: String| anyhow::anyhow!("internal error: {e}");
    let single = runs.len() == 1;
    let summaries: Vec<PredictSummary> = runs
        .iter()
        .zip(&a.cases)
        .map(|(r, path)| PredictSummary::new(&r.case, path, &r.choice, &r.forecast))
        .collect();
    let summary = if single {
        json_text(&summaries[0])
    } else {
        json_text(&ComparisonSummary { cases: &summaries })
    }
    .map_err(internal)?;
    let pairs: Vec<(&Case, &Forecast)> = runs.iter().map(|r| (&r.case, &r.forecast)).collect();
    if let Some(dir) = &a.out {
        let ctx = || format!("cannot write into {}", dir.display());
        let csv = |f: &Forecast| forecast_csv(f).map_err(internal);
        if single {
            write_atomic(&dir.join("trajectory.csv"), csv(&runs[0].forecast)?.as_bytes()).with_context(ctx)?;
        } else {
            for (k, (r, s)) in runs.iter().zip(&summaries).enumerate() {
                let sub = dir.join(format!("case{}", k + 1));
                write_atomic(&sub.join("trajectory.csv"), csv(&r.forecast)?.as_bytes()).with_context(ctx)?;
                write_atomic(&sub.join("summary.json"), json_text(s).map_err(internal)?.as_bytes())
                    .with_context(ctx)?;
            }
            let comparison = comparison_csv(&pairs).map_err(internal)?;
            write_atomic(&dir.join("comparison.csv"), comparison.as_bytes()).with_context(ctx)?;
        }
        write_atomic(&dir.join("summary.json"), summary.as_bytes()).with_context(ctx)?;
    }
    if let Some(file) = &a.view.report {
        let list: Vec<_> = runs.iter().map(|r| (&r.case, &r.forecast)).collect();
        crate::report::predict_report::write_predict(file, &list, a.view.units)?;
    }
    let mut out = std::io::stdout().lock();
    if a.view.json {
        writeln!(out, "{summary}")?;
        return Ok(());
    }
    for r in &runs {
        write_forecast(&mut out, &r.case, &r.choice, &r.forecast, a.view.units)?;
    }
    if !single {
        writeln!(
            out,
            "comparison (build/walk rates over the interval, means of the solved steps; comparison.csv in SI):"
        )?;
        for line in comparison_table(&pairs, a.view.units).lines() {
            writeln!(out, "  {line}")?;
        }
    }
    if let Some(dir) = &a.out {
        writeln!(out, "wrote {}", dir.display())?;
    }
    Ok(())
}
