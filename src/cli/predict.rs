//! `drillpath predict`: forward-marching prediction, tracking against the survey, and the
//! comparison of several BHAs.

use super::args::PredictArgs;
use super::outputs::{names, Outputs};
use super::progress::Progress;
use super::{bare_unit, length_opt, parse_length_option};
use crate::case::fidelity::{Choice, Level, Purpose};
use crate::case::Case;
use crate::io::case_toml::{load_case, CaseOverrides};
use crate::predict::forecast::{forecast, settings_at_level, Forecast, ForecastRequest};
use crate::predict::march::{check_step_count, MarchSettings, MIN_STEP_M};
use crate::report::display_units::UnitSystem;
use crate::report::json_text;
use crate::report::predict_output::{comparison_csv, forecast_csv, ComparisonSummary, PredictSummary};
use crate::report::predict_report::predict_html;
use crate::report::predict_text::{comparison_table, write_forecast};
use crate::report::witsml_out::{trajectories_xml, OutStation, OutTrajectory};
use anyhow::bail;
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

/// A case loaded with its model choice, before the march.
struct Loaded {
    case: Case,
    choice: Choice,
}

fn load(path: &Path, a: &PredictArgs) -> anyhow::Result<Loaded> {
    let mut case = load_for_prediction(path)?;
    let choice = prediction_choice(&mut case, &a.model.fidelity, &a.model.accuracy)?;
    Ok(Loaded { case, choice })
}

fn run_case(loaded: Loaded, path: &Path, a: &PredictArgs, label: &str, quiet: bool) -> anyhow::Result<CaseRun> {
    let Loaded { case, choice } = loaded;
    let survey = &case.well.path;
    let unit = bare_unit(&case);
    let from = match &a.from {
        Some(t) => parse_length_option("--from", t, unit)?,
        None => case.operation.bit_md_m,
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
        (Some(t), _) => parse_length_option("--to", t, unit)?,
        (None, Some(t)) => {
            let ahead = parse_length_option("--ahead", t, unit)?;
            if ahead.is_nan() || ahead <= 0.0 {
                bail!("option `--ahead`: the length to drill ahead must be positive, not {ahead} m");
            }
            from + ahead
        }
        (None, None) => bail!("give --to or --ahead"),
    };
    if to <= from {
        bail!("option `--to`: {to:.2} m is not below the start {from:.2} m");
    }
    let step = length_opt("--step", &a.step, MIN_STEP_M, unit)?;
    let cut = length_opt("--cut", &a.cut, crate::predict::march::MIN_MODEL_LENGTH_M, unit)?;
    let settings = settings_for(&case, step, cut, &choice)?;
    let step_m = settings.step_m;
    check_step_count(from, to, step_m).map_err(|e| anyhow::anyhow!("{}: {e}", path.display()))?;
    let deepest = case.well.hole.deepest_md();
    if to > deepest + 1e-6 {
        tracing::warn!(
            "{}: the bit runs below the deepest hole section ({deepest:.2} m MD) to {to:.2} m: the hole there is taken as the bit's diameter",
            path.display()
        );
    }

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

/// The run's outputs, checked against its inputs before any work.
fn declared_outputs(a: &PredictArgs, loaded: &[Loaded]) -> anyhow::Result<Outputs> {
    let mut outputs = Outputs::new();
    for l in loaded {
        outputs.case_inputs(&l.case);
    }
    if let Some(dir) = &a.out {
        let mut files = names(&["trajectory.csv", "summary.json"]);
        if loaded.len() > 1 {
            files = vec!["summary.json".into(), "comparison.csv".into()];
            for k in 1..=loaded.len() {
                files.push(format!("case{k}/trajectory.csv"));
                files.push(format!("case{k}/summary.json"));
            }
        }
        outputs.dir("--out", dir, &files)?;
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
pub fn run(a: PredictArgs, quiet: bool) -> anyhow::Result<()> {
    let loaded = a
        .cases
        .iter()
        .map(|p| load(p, &a))
        .collect::<anyhow::Result<Vec<_>>>()?;
    let mut outputs = declared_outputs(&a, &loaded)?;
    let mut runs = Vec::new();
    for ((k, path), l) in a.cases.iter().enumerate().zip(loaded) {
        let label = if a.cases.len() > 1 {
            format!("predict {}/{} {}", k + 1, a.cases.len(), path.display())
        } else {
            format!("predict {}", path.display())
        };
        runs.push(run_case(l, path, &a, &label, quiet)?);
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
        let csv = |f: &Forecast| forecast_csv(f).map_err(internal);
        if single {
            outputs.stage(dir.join("trajectory.csv"), csv(&runs[0].forecast)?);
        } else {
            for (k, (r, s)) in runs.iter().zip(&summaries).enumerate() {
                let sub = dir.join(format!("case{}", k + 1));
                outputs.stage(sub.join("trajectory.csv"), csv(&r.forecast)?);
                outputs.stage(sub.join("summary.json"), json_text(s).map_err(internal)?);
            }
            outputs.stage(dir.join("comparison.csv"), comparison_csv(&pairs).map_err(internal)?);
        }
        outputs.stage(dir.join("summary.json"), summary.as_bytes());
    }
    if let Some(file) = &a.view.report {
        outputs.stage(file.clone(), predict_html(&pairs, a.view.units)?);
    }
    if let Some(file) = &a.witsml {
        let trajectories: Vec<OutTrajectory> = pairs
            .iter()
            .map(|(c, f)| OutTrajectory {
                name: c.name.clone(),
                stations: f
                    .rows
                    .iter()
                    .map(|r| OutStation {
                        md_m: r.md_m,
                        inc_rad: r.inc_rad,
                        azi_rad: r.azi_rad,
                        position: r.position,
                    })
                    .collect(),
                survey: &c.well.survey,
            })
            .collect();
        outputs.stage(file.clone(), trajectories_xml(&trajectories).map_err(internal)?);
    }
    outputs.commit()?;
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
    if let Some(file) = &a.view.report {
        writeln!(out, "wrote {}", file.display())?;
    }
    Ok(())
}
