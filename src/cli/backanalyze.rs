//! `drillpath backanalyze`: post-drill back-analysis over the survey, with optional
//! calibration of the bit-rock law (calibrated on the first part, scored on the rest).

use super::args::BackanalyzeArgs;
use super::predict::{fidelity_json, load_for_prediction, prediction_choice, settings_for};
use super::progress::Progress;
use super::{length_opt, parse_length_option};
use crate::predict::backanalysis::{
    error_stats, intervals, run_intervals, run_intervals_skipping, Interval, IntervalPlan,
};
use crate::predict::calibrate::{calibrate, FitParameter};
use crate::predict::law::LawParams;
use crate::predict::march::{MIN_MODEL_LENGTH_M, MIN_STEP_M};
use crate::report::display_units::fixed;
use crate::report::predict_output::{backanalysis_csv, calibration_json, error_stats_json, fitted_toml, law_json};
use crate::report::write_atomic;
use anyhow::{bail, Context};
use serde_json::json;
use std::io::Write;

/// By default back-analysis starts at the first station this inclined, deg: in a vertical
/// hole the bit forces have no direction to predict (a kick-off is steered, not predicted).
pub const DEFAULT_MIN_INCLINATION_DEG: f64 = 3.0;

/// Hole above the first interval's start by default, m.
pub const DEFAULT_START_DEPTH_M: f64 = 30.0;

/// Run the command (`quiet`: no progress bar).
pub fn run(a: BackanalyzeArgs, quiet: bool) -> anyhow::Result<()> {
    let mut case = load_for_prediction(&a.case)?;
    let choice = prediction_choice(&mut case, &a.model.fidelity, &a.model.accuracy)?;
    let survey = &case.well.path;
    // by default, only the hole this bit drilled: below the earlier (wider) hole sections (a
    // string without a bit: the hole at the bottom of the survey gives the bit size)
    let bit_diameter_m = case
        .string
        .bit_diameter_m()
        .unwrap_or_else(|| case.well.hole.diameter_at(survey.md_end()));
    let previous_hole = case.well.hole.previous_hole_bottom_md(bit_diameter_m);
    let from = match &a.from {
        Some(t) => parse_length_option("--from", t)?,
        None => survey
            .stations()
            .iter()
            .find(|s| s.inc_rad >= DEFAULT_MIN_INCLINATION_DEG.to_radians() && s.md_m >= previous_hole.unwrap_or(0.0))
            .map(|s| s.md_m)
            .unwrap_or(survey.md_end())
            .max(survey.md_start() + DEFAULT_START_DEPTH_M),
    }
    .max(survey.md_start() + MIN_MODEL_LENGTH_M);
    let to = match &a.to {
        Some(t) => parse_length_option("--to", t)?,
        None => survey.md_end(),
    };
    let horizon = length_opt("--horizon", &a.horizon, 0.0)?.unwrap_or(0.0);
    let step = length_opt("--step", &a.step, MIN_STEP_M)?;
    if !(a.split > 0.0 && a.split < 1.0) {
        bail!("option `--split`: {} must lie strictly between 0 and 1", a.split);
    }
    let params: Vec<FitParameter> = a
        .fit
        .split(',')
        .map(|s| s.trim())
        .filter(|s| !s.is_empty())
        .map(|s| {
            FitParameter::parse(s).ok_or_else(|| {
                anyhow::anyhow!(
                    "option `--fit`: unknown parameter `{s}` (expected {})",
                    FitParameter::NAMES
                )
            })
        })
        .collect::<anyhow::Result<_>>()?;
    if a.calibrate && params.is_empty() {
        bail!("option `--fit`: no parameter to fit");
    }
    let list = intervals(
        survey,
        &IntervalPlan {
            from_md_m: from,
            to_md_m: to,
            horizon_m: horizon,
        },
    );
    let min_intervals = if a.calibrate { 4 } else { 1 };
    if list.len() < min_intervals {
        bail!(
            "{}: only {} survey interval(s) between {from:.1} m and {to:.1} m; back-analysis needs {min_intervals}{}",
            a.case.display(),
            list.len(),
            if a.calibrate {
                " to calibrate on half and score on the other half"
            } else {
                ""
            }
        );
    }
    let settings = settings_for(&case, step, None, &choice)?;
    let name = a.case.display().to_string();
    let t0 = std::time::Instant::now();
    let fail = |e: crate::predict::march::PredictError| anyhow::anyhow!("{name}: {e}");
    let mut warm = Vec::new();
    let progress = Progress::new(list.len() as u64, &format!("backanalyze {name}"), quiet);
    let (base, skipped) = run_intervals_skipping(
        &case,
        &case.bit_rock,
        &list,
        &settings,
        &mut warm,
        |k, n| progress.set(k as u64, &format!("interval {k}/{n}")),
        false,
    );
    progress.finish();
    if base.is_empty() {
        let (iv, e) = &skipped[0];
        bail!(
            "{name}: no interval could be predicted; the first ({:.1}-{:.1} m): {e}",
            iv.from_md_m,
            iv.to_md_m
        );
    }
    // calibration and scoring use the intervals that could be predicted with the case's law
    let predicted = |iv: &Interval| !skipped.iter().any(|(s, _)| s.from_md_m == iv.from_md_m);
    let mut warm: Vec<_> = list
        .iter()
        .zip(warm)
        .filter(|(iv, _)| predicted(iv))
        .map(|(_, w)| w)
        .collect();
    let list: Vec<Interval> = base.iter().map(|r| r.interval).collect();
    if a.calibrate && list.len() < min_intervals {
        bail!(
            "{name}: only {} interval(s) could be predicted; calibration needs {min_intervals}",
            list.len()
        );
    }
    // calibration intervals (at least 2, and 2 left to score); used only with --calibrate, which
    // needs 4 or more intervals (checked above)
    let ncal = if list.len() >= 4 {
        ((list.len() as f64 * a.split).round() as usize).clamp(2, list.len() - 2)
    } else {
        0
    };
    let split_md = list[ncal].from_md_m;
    let stats_all = error_stats(&base);
    let mut summary = json!({
        "case": case.name,
        "case_file": name,
        "intervals": base.len(),
        "from_md_m": list[0].from_md_m,
        "to_md_m": list[list.len() - 1].to_md_m,
        "horizon_m": horizon,
        "step_m": settings.step_m,
        "fidelity": fidelity_json(&choice),
        "inc_err_per_100m_deg": stats_all.inc_mean_abs_per_100m_rad.to_degrees(),
        "azi_err_per_100m_deg": stats_all.azi_mean_abs_per_100m_rad.to_degrees(),
        "errors": error_stats_json(&stats_all).map_err(|e| anyhow::anyhow!("internal error: {e}"))?,
        "skipped_intervals": skipped.iter().map(|(iv, e)| json!({"from_md_m": iv.from_md_m, "to_md_m": iv.to_md_m, "reason": e.to_string()})).collect::<Vec<_>>(),
        "bit_rock": law_json(&case.bit_rock.law, &LawParams::at(&case.bit_rock, from), case.bit_rock.formations.len()).map_err(|e| anyhow::anyhow!("internal error: {e}"))?,
    });
    let mut results = base.clone();
    let mut fitted_text = None;
    if a.calibrate {
        let (cal_list, score_list): (&[Interval], &[Interval]) = list.split_at(ncal);
        // the calibration's number of evaluations is not known ahead: a spinner with its messages
        let progress = Progress::spinner(&format!("backanalyze {name}: calibration"), quiet);
        let cal = calibrate(&case, &params, cal_list, &settings, |m| progress.message(m));
        progress.finish();
        let cal = cal.map_err(fail)?;
        let mut warm2 = warm.split_off(ncal.min(warm.len()));
        let scored = run_intervals(&case, &cal.bit_rock, score_list, &settings, &mut warm2, |_, _| {}).map_err(fail)?;
        let e = |r: &[crate::predict::backanalysis::IntervalResult]| {
            error_stats_json(&error_stats(r)).map_err(|e| anyhow::anyhow!("internal error: {e}"))
        };
        summary["calibration"] = json!({
            "parameters": calibration_json(&cal).map_err(|e| anyhow::anyhow!("internal error: {e}"))?,
            "calibrated_on": {"from_md_m": list[0].from_md_m, "to_md_m": split_md},
            "scored_on": {"from_md_m": split_md, "to_md_m": list[list.len() - 1].to_md_m},
            "in_sample_default": e(&base[..ncal])?,
            "in_sample_fitted": e(&cal.results)?,
            "out_of_sample_default": e(&base[ncal..])?,
            "out_of_sample_fitted": e(&scored)?,
        });
        results = cal.results.clone();
        results.extend(scored);
        fitted_text = Some(fitted_toml(&cal));
    }
    summary["seconds"] = json!(t0.elapsed().as_secs_f64());
    let csv = backanalysis_csv(&results).map_err(|e| anyhow::anyhow!("internal error: {e}"))?;
    if let Some(dir) = &a.out {
        let ctx = || format!("cannot write into {}", dir.display());
        write_atomic(&dir.join("trajectory.csv"), csv.as_bytes()).with_context(ctx)?;
        if let Some(t) = &fitted_text {
            write_atomic(&dir.join("bit_rock_fitted.toml"), t.as_bytes()).with_context(ctx)?;
        }
        write_atomic(
            &dir.join("summary.json"),
            serde_json::to_string_pretty(&summary)?.as_bytes(),
        )
        .with_context(ctx)?;
    }
    if let Some(file) = &a.view.report {
        let split = a.calibrate.then_some(split_md);
        crate::report::predict_report::write_backanalyze(file, &case, &results, split, a.view.units)?;
    }
    let mut out = std::io::stdout().lock();
    if a.view.json {
        writeln!(out, "{}", serde_json::to_string_pretty(&summary)?)?;
        return Ok(());
    }
    let (du, eu) = (a.view.units.depth(), a.view.units.per_100());
    // error rates of the summary are in degrees per 100 m
    let rate = |deg_per_100m: f64| eu.fmt(deg_per_100m.to_radians() / 100.0, 3);
    writeln!(out, "backanalyze: {} ({})", case.name, name)?;
    writeln!(out, "  fidelity {}: {}", choice.level.name(), choice.reason)?;
    if let (None, Some(shoe)) = (&a.from, previous_hole) {
        writeln!(
            out,
            "  from: the hole below {} (the wider hole above was drilled by another bit; give --from to include it)",
            du.fmt(shoe, 1)
        )?;
    }
    for (iv, e) in &skipped {
        writeln!(
            out,
            "  WARNING: interval {}-{} skipped (not in the errors): {e}",
            du.num(iv.from_md_m, 1),
            du.fmt(iv.to_md_m, 1)
        )?;
    }
    writeln!(
        out,
        "  {} intervals from {} to {} (step {}): mean |error|: inclination {}, azimuth {} (RMS {} and {})",
        base.len(),
        du.fmt(list[0].from_md_m, 1),
        du.fmt(list[list.len() - 1].to_md_m, 1),
        du.fmt(settings.step_m, 2),
        eu.fmt(stats_all.inc_mean_abs_per_100m_rad / 100.0, 3),
        eu.fmt(stats_all.azi_mean_abs_per_100m_rad / 100.0, 3),
        eu.fmt(stats_all.inc_rms_per_100m_rad / 100.0, 3),
        eu.fmt(stats_all.azi_rms_per_100m_rad / 100.0, 3)
    )?;
    if let Some(c) = summary.get("calibration") {
        for f in c["parameters"]["fitted"].as_array().into_iter().flatten() {
            writeln!(
                out,
                "  fitted {} = {} +/- {}{}",
                f["name"].as_str().unwrap_or("?"),
                fixed(f["value"].as_f64().unwrap_or(f64::NAN), 5),
                f["std_dev"]
                    .as_f64()
                    .map(|v| fixed(v, 5))
                    .unwrap_or_else(|| "n/a".into()),
                if f["identifiable"].as_bool() == Some(true) {
                    ""
                } else {
                    "  (NOT identifiable from these intervals: the predictions barely depend on it)"
                }
            )?;
        }
        writeln!(
            out,
            "  calibrated on {}-{}, scored on {}-{}:",
            du.num(list[0].from_md_m, 1),
            du.fmt(split_md, 1),
            du.num(split_md, 1),
            du.fmt(list[list.len() - 1].to_md_m, 1)
        )?;
        for (k, label) in [
            ("in_sample_default", "  calibration part, case law "),
            ("in_sample_fitted", "  calibration part, fitted law"),
            ("out_of_sample_default", "  scoring part, case law     "),
            ("out_of_sample_fitted", "  scoring part, fitted law   "),
        ] {
            let v = |key: &str| c[k][key].as_f64().unwrap_or(f64::NAN);
            writeln!(
                out,
                "  {label}: inclination {}, azimuth {}",
                rate(v("inc_err_per_100m_deg")),
                rate(v("azi_err_per_100m_deg"))
            )?;
        }
    }
    writeln!(out, "  {:.2} s", t0.elapsed().as_secs_f64())?;
    if let Some(dir) = &a.out {
        writeln!(out, "  wrote {}", dir.display())?;
    }
    Ok(())
}
