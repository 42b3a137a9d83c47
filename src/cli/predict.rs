//! `drillpath predict`: forward-marching prediction, tracking against the survey, and the
//! comparison of several BHAs.

use super::args::PredictArgs;
use super::{length_opt, parse_length_option};
use crate::case::Case;
use crate::io::case_toml::{load_case, CaseOverrides};
use crate::predict::law::LawParams;
use crate::predict::march::{predict, MarchSettings, Prediction, MIN_STEP_M};
use crate::predict::track::{interval_rates, tracking_errors, trajectory_rows};
use crate::report::predict_output::{law_json, rates_json, tracking_json, trajectory_csv};
use crate::report::{num, write_atomic};
use anyhow::{bail, Context};
use serde_json::json;
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

/// March settings of `case` with the command line's step and cut.
pub fn settings_for(case: &Case, step: Option<f64>, cut: Option<f64>) -> MarchSettings {
    let mut s = MarchSettings::from_case(case);
    if let Some(st) = step {
        s.step_m = st;
    }
    s.cut_m = cut;
    s
}

/// Progress on stderr when it is a terminal (silent otherwise).
pub fn progress_line(msg: &str) {
    use std::io::IsTerminal;
    if std::io::stderr().is_terminal() {
        eprint!("\r\x1b[K{msg}");
    }
}

/// Clear the progress line.
pub fn progress_done() {
    use std::io::IsTerminal;
    if std::io::stderr().is_terminal() {
        eprint!("\r\x1b[K");
    }
}

struct CaseRun {
    case: Case,
    pred: Prediction,
    summary: serde_json::Value,
    csv: String,
}

fn run_case(path: &Path, a: &PredictArgs) -> anyhow::Result<CaseRun> {
    let case = load_for_prediction(path)?;
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
    let settings = settings_for(&case, step, cut);
    let name = path.display().to_string();
    let mut on_step = |md: f64| progress_line(&format!("predict {name}: bit at {md:.1} m of {to:.1} m"));
    let pred = predict(&case, from, to, &settings, &mut on_step);
    progress_done();
    let pred = pred.map_err(|e| anyhow::anyhow!("{}: {e}", path.display()))?;
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
            "step_m": fin(settings.step_m.max(MIN_STEP_M))?,
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
            "model": {
                "fidelity": "bha",
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

/// Run the command.
pub fn run(a: PredictArgs) -> anyhow::Result<()> {
    let mut runs = Vec::new();
    for (k, path) in a.cases.iter().enumerate() {
        progress_line(&format!("predict: case {}/{} {}", k + 1, a.cases.len(), path.display()));
        runs.push(run_case(path, &a)?);
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
    if let Some(file) = &a.report {
        let list: Vec<_> = runs.iter().map(|r| (&r.case, &r.pred)).collect();
        crate::report::predict_report::write_predict(file, &list, a.units)?;
    }
    if a.json {
        println!("{}", serde_json::to_string_pretty(&summary)?);
        return Ok(());
    }
    for r in &runs {
        print_case(r);
    }
    if !single {
        println!("comparison (build/walk rates over the interval, means of the solved steps):");
        for line in comparison.lines() {
            println!("  {line}");
        }
    }
    if let Some(dir) = &a.out {
        println!("wrote {}", dir.display());
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

fn print_case(r: &CaseRun) {
    let p = &r.pred;
    let rt = interval_rates(p);
    let first = &p.steps[0];
    let end = p.steps.last().expect("start record");
    println!("predict: {} ({})", r.case.name, r.case.path.display());
    println!(
        "  from {:.2} m (I {:.3} deg, A {:.3} deg) to {:.2} m: I {:.3} deg, A {:.3} deg, TVD {:.2} m, N {:.2} m, E {:.2} m",
        p.from_md_m,
        first.inc_rad.to_degrees(),
        first.azi_rad.to_degrees(),
        p.to_md_m,
        end.inc_rad.to_degrees(),
        end.azi_rad.to_degrees().rem_euclid(360.0),
        end.position.z,
        end.position.x,
        end.position.y
    );
    println!(
        "  build rate {:+.3} deg/30 m, walk rate {:+.3} deg/30 m; bit at start: build force {:+.3} kN, walk force {:+.3} kN, tilt {:+.4}/{:+.4} deg; mean over the steps: {:+.3} kN, {:+.3} kN",
        rt.build_rate_rad_per_30m.to_degrees(),
        rt.walk_rate_rad_per_30m.to_degrees(),
        first.bit.build_force_n / 1e3,
        first.bit.walk_force_n / 1e3,
        first.bit.tilt_inc_rad.to_degrees(),
        first.bit.tilt_azi_rad.to_degrees(),
        rt.mean_build_force_n / 1e3,
        rt.mean_walk_force_n / 1e3
    );
    if let Some(t) = r.summary.get("tracking").filter(|t| !t.is_null()) {
        println!(
            "  tracking: {} measured stations; at {:.1} m error inc {:+.3} deg, azi {:+.3} deg = {:.3} and {:.3} deg/100 m (seed paper metric)",
            t["stations_compared"],
            t["end_md_m"].as_f64().unwrap_or(0.0),
            t["end_inc_err_deg"].as_f64().unwrap_or(0.0),
            t["end_azi_err_deg"].as_f64().unwrap_or(0.0),
            t["inc_err_per_100m_deg"].as_f64().unwrap_or(0.0),
            t["azi_err_per_100m_deg"].as_f64().unwrap_or(0.0)
        );
    }
    println!(
        "  model: stiff BHA cut {:.1} m above the bit, {} DOF; {} steps, {} solver iterations, {:.2} s",
        p.cut_m,
        p.dofs,
        p.steps.len() - 1,
        p.iterations,
        p.seconds
    );
}
