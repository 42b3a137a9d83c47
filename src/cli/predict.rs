//! `drillpath predict`: forward-marching prediction, tracking against the survey, and the
//! comparison of several BHAs.

use super::args::PredictArgs;
use super::progress::Progress;
use super::{length_opt, parse_length_option};
use crate::case::fidelity::{Choice, Level, Purpose};
use crate::case::Case;
use crate::io::case_toml::{load_case, CaseOverrides};
use crate::predict::extrapolate::predict_extrapolated;
use crate::predict::law::LawParams;
use crate::predict::march::{predict, MarchSettings, Prediction, MIN_STEP_M, RIPPLE_WARN_DEG, RIPPLE_WINDOW_M};
use crate::predict::track::{interval_rates, tracking_errors, trajectory_rows};
use crate::report::display_units::{fixed, signed, UnitSystem};
use crate::report::predict_output::{law_json, rates_json, tracking_json, trajectory_csv};
use crate::report::{num, write_atomic};
use anyhow::{bail, Context};
use serde_json::json;
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
/// `choice`: `bha` (the cut model), `whole` (the cut at the string's top, so the whole string
/// is solved at every step); `soft` cannot predict (no bit side forces).
pub fn settings_for(
    case: &Case,
    step: Option<f64>,
    cut: Option<f64>,
    choice: &Choice,
) -> anyhow::Result<MarchSettings> {
    let mut s = MarchSettings::from_case(case);
    if let Some(st) = step {
        s.step_m = st;
    }
    s.cut_m = match choice.level {
        Level::Soft => bail!("fidelity soft cannot predict (no bit side forces)"),
        Level::Whole if cut.is_some() => {
            bail!("options `--cut` and fidelity whole exclude each other (whole solves the string to its top)")
        }
        Level::Whole => Some(case.string.length_m()),
        Level::Bha | Level::Hybrid => cut,
    };
    Ok(s)
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

/// The `model.fidelity` object of a prediction summary.
pub fn fidelity_json(choice: &Choice) -> serde_json::Value {
    json!({
        "requested": choice.requested.name(),
        "used": choice.level.name(),
        "reason": choice.reason,
    })
}

struct CaseRun {
    case: Case,
    pred: Prediction,
    summary: serde_json::Value,
    csv: String,
}

/// Number of march steps from `from` to `to` of length `step` (the last may be shorter), for
/// the progress bar.
pub fn step_count(from: f64, to: f64, step: f64) -> u64 {
    ((to - from) / step.max(MIN_STEP_M) - 1e-9).ceil().max(1.0) as u64
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
    let du = a.view.units.depth();
    let step_m = settings.step_m;
    if a.extrapolate && step_m < 2.0 * MIN_STEP_M - 1e-9 {
        bail!(
            "option `--extrapolate`: it also marches at half the step, {} m, shorter than the shortest step accepted, {MIN_STEP_M} m; give --step {} m or longer",
            step_m / 2.0,
            2.0 * MIN_STEP_M
        );
    }
    let n = step_count(from, to, step_m);
    // with --extrapolate: the march at the step (n steps), then at half of it (2n steps)
    let total = if a.extrapolate { 3 * n } else { n };
    let progress = Progress::new(total, label, quiet);
    let mut done_before = 0u64;
    let mut last_md = f64::NEG_INFINITY;
    let mut on_step = |md: f64| {
        if md < last_md {
            // the second (fine) march started
            done_before = n;
        }
        last_md = md;
        let per = if done_before > 0 { step_m / 2.0 } else { step_m };
        let k = ((md - from) / per - 1e-6).ceil().max(0.0) as u64;
        progress.set(
            (done_before + k).min(total),
            &format!("bit at {} of {}", du.fmt(md, 1), du.fmt(to, 1)),
        );
    };
    let result = if a.extrapolate {
        predict_extrapolated(&case, from, to, &settings, &mut on_step).map(|(p, e)| (p, Some(e)))
    } else {
        predict(&case, from, to, &settings, &mut on_step).map(|p| (p, None))
    };
    progress.finish();
    let (pred, step_error) = result.map_err(|e| anyhow::anyhow!("{}: {e}", path.display()))?;
    let rows = trajectory_rows(&pred, Some(survey));
    let csv = trajectory_csv(&rows).map_err(|e| anyhow::anyhow!("internal error: {e}"))?;
    let rates = interval_rates(&pred);
    let tracking = tracking_errors(&rows, from);
    let end = pred.steps.last().expect("a prediction has a start record");
    let law = LawParams::at(&case.bit_rock, from);
    let fin = crate::report::finite;
    let summary = (|| -> Result<serde_json::Value, String> {
        Ok(json!({
            "case": case.name,
            "case_file": path.display().to_string(),
            "from_md_m": fin(pred.from_md_m)?,
            "to_md_m": fin(pred.to_md_m)?,
            "step_m": fin(settings.step_m)?,
            "ripple_deg": fin(pred.ripple_deg)?,
            "end": {
                "md_m": fin(end.md_m)?,
                "inc_deg": fin(end.inc_rad.to_degrees())?,
                "azi_deg": fin(end.azi_rad.to_degrees().rem_euclid(360.0))?,
                "tvd_m": fin(end.position.z)?,
                "north_m": fin(end.position.x)?,
                "east_m": fin(end.position.y)?,
            },
            "rates": rates_json(&rates)?,
            "tracking": tracking.as_ref().map(tracking_json).transpose()?,
            "bit_rock": law_json(&case.bit_rock.law, &law, case.bit_rock.formations.len())?,
            "step_extrapolation": match &step_error {
                None => serde_json::Value::Null,
                Some(e) => json!({
                    "coarse_step_m": fin(e.coarse_step_m)?,
                    "fine_step_m": fin(e.fine_step_m)?,
                    "est_inc_err_deg": fin(e.max_inc_rad.to_degrees())?,
                    "est_azi_err_deg": fin(e.max_azi_rad.to_degrees())?,
                }),
            },
            "model": {
                "fidelity": choice.level.name(),
                "fidelity_choice": fidelity_json(&choice),
                "cut_m": fin(pred.cut_m)?,
                "dofs": pred.dofs,
                "steps": pred.steps.len() - 1,
                "solver_iterations": pred.iterations,
                "seconds": fin(pred.seconds)?,
            }
        }))
    })()
    .map_err(|e| anyhow::anyhow!("internal error: {e}"))?;
    Ok(CaseRun {
        case,
        pred,
        summary,
        csv,
    })
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
    let single = runs.len() == 1;
    let summary = if single {
        runs[0].summary.clone()
    } else {
        json!({ "cases": runs.iter().map(|r| r.summary.clone()).collect::<Vec<_>>() })
    };
    let comparison = comparison_csv(&runs).map_err(|e| anyhow::anyhow!("internal error: {e}"))?;
    if let Some(dir) = &a.out {
        let ctx = || format!("cannot write into {}", dir.display());
        if single {
            write_atomic(&dir.join("trajectory.csv"), runs[0].csv.as_bytes()).with_context(ctx)?;
        } else {
            for (k, r) in runs.iter().enumerate() {
                let sub = dir.join(format!("case{}", k + 1));
                write_atomic(&sub.join("trajectory.csv"), r.csv.as_bytes()).with_context(ctx)?;
                write_atomic(
                    &sub.join("summary.json"),
                    serde_json::to_string_pretty(&r.summary)?.as_bytes(),
                )
                .with_context(ctx)?;
            }
            write_atomic(&dir.join("comparison.csv"), comparison.as_bytes()).with_context(ctx)?;
        }
        write_atomic(
            &dir.join("summary.json"),
            serde_json::to_string_pretty(&summary)?.as_bytes(),
        )
        .with_context(ctx)?;
    }
    if let Some(file) = &a.view.report {
        let list: Vec<_> = runs.iter().map(|r| (&r.case, &r.pred)).collect();
        crate::report::predict_report::write_predict(file, &list, a.view.units)?;
    }
    let mut out = std::io::stdout().lock();
    if a.view.json {
        writeln!(out, "{}", serde_json::to_string_pretty(&summary)?)?;
        return Ok(());
    }
    for r in &runs {
        print_case(r, a.view.units, &mut out)?;
    }
    if !single {
        writeln!(
            out,
            "comparison (build/walk rates over the interval, means of the solved steps; comparison.csv in SI):"
        )?;
        for line in comparison_table(&runs, a.view.units).lines() {
            writeln!(out, "  {line}")?;
        }
    }
    if let Some(dir) = &a.out {
        writeln!(out, "wrote {}", dir.display())?;
    }
    Ok(())
}

/// Header of `comparison.csv`.
pub const COMPARISON_HEADER: &str = "case,from_md_m,to_md_m,build_rate_deg_per_30m,walk_rate_deg_per_30m,mean_build_force_kN,mean_walk_force_kN,mean_tilt_inc_deg,mean_tilt_azi_deg,end_inc_deg,end_azi_deg";

fn comparison_csv(runs: &[CaseRun]) -> Result<String, String> {
    let mut out = format!("{COMPARISON_HEADER}\n");
    for r in runs {
        let rt = interval_rates(&r.pred);
        let end = r.pred.steps.last().expect("start record");
        let name = r.case.name.replace([',', '"', '\n'], " ");
        out.push_str(&format!(
            "{},{},{},{},{},{},{},{},{},{},{}\n",
            name,
            num(r.pred.from_md_m, 2)?,
            num(r.pred.to_md_m, 2)?,
            num(rt.build_rate_rad_per_30m.to_degrees(), 4)?,
            num(rt.walk_rate_rad_per_30m.to_degrees(), 4)?,
            num(rt.mean_build_force_n / 1e3, 4)?,
            num(rt.mean_walk_force_n / 1e3, 4)?,
            num(rt.mean_tilt_inc_rad.to_degrees(), 5)?,
            num(rt.mean_tilt_azi_rad.to_degrees(), 5)?,
            num(end.inc_rad.to_degrees(), 4)?,
            num(end.azi_rad.to_degrees().rem_euclid(360.0), 4)?,
        ));
    }
    Ok(out)
}

/// The comparison as a readable table in `units` (the CSV stays SI).
fn comparison_table(runs: &[CaseRun], units: UnitSystem) -> String {
    let (du, fu, ru) = (units.depth(), units.force(), units.dogleg());
    let mut out = format!(
        "case | from {d} | to {d} | build {r} | walk {r} | mean build force {f} | mean walk force {f} | end inc deg | end azi deg\n",
        d = du.label,
        r = ru.label,
        f = fu.label
    );
    for r in runs {
        let rt = interval_rates(&r.pred);
        let end = r.pred.steps.last().expect("start record");
        out.push_str(&format!(
            "{} | {} | {} | {} | {} | {} | {} | {} | {}\n",
            r.case.name,
            du.num(r.pred.from_md_m, 2),
            du.num(r.pred.to_md_m, 2),
            signed(ru.show(rt.build_rate_rad_per_30m / 30.0), ru.decimals(3)),
            signed(ru.show(rt.walk_rate_rad_per_30m / 30.0), ru.decimals(3)),
            signed(fu.show(rt.mean_build_force_n), fu.decimals(3)),
            signed(fu.show(rt.mean_walk_force_n), fu.decimals(3)),
            fixed(end.inc_rad.to_degrees(), 3),
            fixed(end.azi_rad.to_degrees().rem_euclid(360.0), 3),
        ));
    }
    out
}

fn print_case(r: &CaseRun, units: UnitSystem, out: &mut impl Write) -> std::io::Result<()> {
    let (du, fu, ru, eu) = (units.depth(), units.force(), units.dogleg(), units.per_100());
    let p = &r.pred;
    let rt = interval_rates(p);
    let first = &p.steps[0];
    let end = p.steps.last().expect("start record");
    writeln!(out, "predict: {} ({})", r.case.name, r.case.path.display())?;
    let f = &r.summary["model"]["fidelity_choice"];
    writeln!(
        out,
        "  fidelity {}: {}",
        f["used"].as_str().unwrap_or(""),
        f["reason"].as_str().unwrap_or("")
    )?;
    writeln!(
        out,
        "  from {} (I {} deg, A {} deg) to {}: I {} deg, A {} deg, TVD {}, N {}, E {}",
        du.fmt(p.from_md_m, 2),
        fixed(first.inc_rad.to_degrees(), 3),
        fixed(first.azi_rad.to_degrees().rem_euclid(360.0), 3),
        du.fmt(p.to_md_m, 2),
        fixed(end.inc_rad.to_degrees(), 3),
        fixed(end.azi_rad.to_degrees().rem_euclid(360.0), 3),
        du.fmt(end.position.z, 2),
        du.fmt(end.position.x, 2),
        du.fmt(end.position.y, 2)
    )?;
    writeln!(
        out,
        "  build rate {}, walk rate {}; bit at start: build force {}, walk force {}, tilt {}/{} deg; mean over the steps: {}, {}",
        ru.fmt_signed(rt.build_rate_rad_per_30m / 30.0, 3),
        ru.fmt_signed(rt.walk_rate_rad_per_30m / 30.0, 3),
        fu.fmt_signed(first.bit.build_force_n, 3),
        fu.fmt_signed(first.bit.walk_force_n, 3),
        signed(first.bit.tilt_inc_rad.to_degrees(), 4),
        signed(first.bit.tilt_azi_rad.to_degrees(), 4),
        fu.fmt_signed(rt.mean_build_force_n, 3),
        fu.fmt_signed(rt.mean_walk_force_n, 3)
    )?;
    if let Some(t) = r.summary.get("tracking").filter(|t| !t.is_null()) {
        let v = |k: &str| t[k].as_f64().unwrap_or(f64::NAN);
        // the summary holds degrees per 100 m
        let rate = |k: &str| v(k).to_radians() / 100.0;
        writeln!(
            out,
            "  tracking: {} measured stations; at {} error inc {} deg, azi {} deg = {} and {} (seed paper metric)",
            t["stations_compared"],
            du.fmt(v("end_md_m"), 1),
            signed(v("end_inc_err_deg"), 3),
            signed(v("end_azi_err_deg"), 3),
            eu.fmt(rate("inc_err_per_100m_deg"), 3),
            eu.fmt(rate("azi_err_per_100m_deg"), 3)
        )?;
    }
    if let Some(e) = r.summary.get("step_extrapolation").filter(|e| !e.is_null()) {
        let v = |k: &str| e[k].as_f64().unwrap_or(f64::NAN);
        writeln!(
            out,
            "  step extrapolation: marches at {} and {} combined (Richardson); step error left in the finer one, estimated: inc {} deg, azi {} deg",
            du.fmt(v("coarse_step_m"), 2),
            du.fmt(v("fine_step_m"), 2),
            fixed(v("est_inc_err_deg"), 3),
            fixed(v("est_azi_err_deg"), 3)
        )?;
    }
    if p.ripple_deg >= RIPPLE_WARN_DEG {
        writeln!(
            out,
            "  warning: the predicted hole ripples around its trend by {} deg at the end (over the last {}): the end inclination and azimuth move by up to that much with the ripple's phase; a longer step damps it (docs/performance.md, \"Step convergence\")",
            fixed(p.ripple_deg, 2),
            du.fmt(RIPPLE_WINDOW_M, 0)
        )?;
    }
    let model = if r.summary["model"]["fidelity"] == "whole" {
        "stiff whole string".to_string()
    } else {
        format!("stiff BHA cut {} above the bit", du.fmt(p.cut_m, 1))
    };
    writeln!(
        out,
        "  model: {model}, {} DOF; {} steps, {} solver iterations, {:.2} s",
        p.dofs,
        p.steps.len() - 1,
        p.iterations,
        p.seconds
    )
}
