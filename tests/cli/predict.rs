//! Command-line handling of `drillpath predict` and `drillpath backanalyze`: bad options and
//! unsuitable cases exit 2 with one `error:` line naming the option or key and leave no output;
//! good runs write the interface's `trajectory.csv` columns and `summary.json` keys, no NaN.

use std::path::Path;
use std::sync::LazyLock;
use tempfile::TempDir;

use crate::common::{assert_error_names, case_dir, collar, run_in, stabilizer, Run, BIT, PIPE_TUBE};

/// Straight 20 deg hole with stations every 10 m below 200 m.
fn survey() -> String {
    let mut s = String::from("md_m,inc_deg,azi_deg\n0,20,30\n100,20,30\n200,20,30\n");
    for k in 1..=4 {
        s.push_str(&format!(
            "{},{},{}\n",
            200 + 10 * k,
            20.0 + 0.1 * k as f64,
            30.0 + 0.05 * k as f64
        ));
    }
    s
}

/// Bit, full-gauge near-bit stabilizer, 40 m of 6.5 in collars and 5 in pipe ([`PIPE_TUBE`]),
/// drilling at 80 kN from 200 m, 2 m prediction steps.
static CASE: LazyLock<String> = LazyLock::new(|| {
    format!(
        r#"name = "predict cli test"
[well]
survey = "survey.csv"
hole = [{{ to_md = "1000 m", diameter = "8.5 in" }}]
[mud]
density = "1.2 sg"
[operation]
mode = "drilling"
bit_md = "200 m"
wob = "80 kN"
rpm = 60
friction = 0.2
{BIT}{}{}{PIPE_TUBE}[bit_rock]
step = "2 m"
"#,
        stabilizer("8.5 in"),
        collar("40 m")
    )
});

fn setup(case: &str) -> TempDir {
    case_dir(&survey(), case)
}

/// `drillpath cmd case.toml args` in `dir`.
fn run(dir: &Path, cmd: &str, args: &[&str]) -> Run {
    run_in(dir, &[&[cmd, "case.toml"], args].concat())
}

/// Exit code 2, one stderr line starting `error:` containing every needle, no panic
/// ([`assert_error_names`]), no `out/`.
fn assert_error(dir: &Path, out: &Run, needles: &[&str]) {
    assert_eq!(out.code(), Some(2), "stderr: {}", out.stderr);
    assert_error_names(out, needles);
    assert!(!dir.join("out").exists(), "no output on error");
}

#[test]
fn predict_bad_options_are_named() {
    let dir = setup(&CASE);
    let o = run(dir.path(), "predict", &["--from", "200", "--to", "150", "--out", "out"]);
    assert_error(dir.path(), &o, &["--to", "150"]);
    let o = run(dir.path(), "predict", &["--from", "500", "--to", "600", "--out", "out"]);
    assert_error(dir.path(), &o, &["--from", "outside the survey"]);
    let o = run(
        dir.path(),
        "predict",
        &["--ahead", "10 m", "--step", "0.05 m", "--out", "out"],
    );
    assert_error(dir.path(), &o, &["--step"]);
    // the fine march of --extrapolate would run below the shortest step: refused, not raised
    let o = run(
        dir.path(),
        "predict",
        &["--ahead", "10 m", "--step", "0.3 m", "--extrapolate", "--out", "out"],
    );
    assert_error(dir.path(), &o, &["--extrapolate", "0.4 m"]);
    let o = run(dir.path(), "predict", &["--ahead", "10 kN", "--out", "out"]);
    assert_error(dir.path(), &o, &["--ahead"]);
    // neither --to nor --ahead: the argument parser refuses with its usage text
    let o = run(dir.path(), "predict", &["--out", "out"]);
    assert_eq!(o.code(), Some(2));
    assert!(!dir.path().join("out").exists());
}

#[test]
fn predict_refuses_cases_without_wob_on_bottom() {
    let dir = setup(&CASE.replace("wob = \"80 kN\"", "hook_load = \"300 kN\""));
    let o = run(dir.path(), "predict", &["--ahead", "10 m", "--out", "out"]);
    assert_error(dir.path(), &o, &["operation.wob"]);
    let dir = setup(&CASE.replace("mode = \"drilling\"", "mode = \"trip_in\""));
    let o = run(dir.path(), "predict", &["--ahead", "10 m", "--out", "out"]);
    assert_error(dir.path(), &o, &["operation.mode", "trip_in"]);
}

#[test]
fn backanalyze_bad_options_are_named() {
    let dir = setup(&CASE);
    let o = run(
        dir.path(),
        "backanalyze",
        &["--calibrate", "--fit", "beta", "--out", "out"],
    );
    assert_error(dir.path(), &o, &["--fit", "beta"]);
    let o = run(dir.path(), "backanalyze", &["--split", "1.5", "--out", "out"]);
    assert_error(dir.path(), &o, &["--split"]);
    let o = run(
        dir.path(),
        "backanalyze",
        &["--from", "230", "--calibrate", "--out", "out"],
    );
    assert_error(dir.path(), &o, &["interval"]);
}

/// Several BHA runs: out of the order of their bit depths, on different surveys, or with a
/// calibration, they are refused with the reason and the files named.
#[test]
fn backanalyze_bad_runs_are_named() {
    let dir = setup(&CASE);
    let deeper = CASE.replace("bit_md = \"200 m\"", "bit_md = \"230 m\"");
    std::fs::write(dir.path().join("run2.toml"), &deeper).unwrap();
    let o = run_in(dir.path(), &["backanalyze", "run2.toml", "case.toml", "--out", "out"]);
    assert_error(dir.path(), &o, &["order of their bit depths", "case.toml", "run2.toml"]);
    let o = run_in(
        dir.path(),
        &["backanalyze", "case.toml", "run2.toml", "--calibrate", "--out", "out"],
    );
    assert_error(dir.path(), &o, &["calibration", "one BHA run"]);
    let other = survey().replace("230,20.3", "230,20.9");
    std::fs::write(dir.path().join("other.csv"), other).unwrap();
    std::fs::write(
        dir.path().join("run3.toml"),
        deeper.replace("survey = \"survey.csv\"", "survey = \"other.csv\""),
    )
    .unwrap();
    let o = run_in(dir.path(), &["backanalyze", "case.toml", "run3.toml", "--out", "out"]);
    assert_error(dir.path(), &o, &["share one survey", "run3.toml"]);
    // in order on one survey: both runs listed in the summary
    let o = run_in(
        dir.path(),
        &["backanalyze", "case.toml", "run2.toml", "--from", "200", "--out", "out"],
    );
    assert!(o.success(), "{}", o.describe());
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.path().join("out/summary.json")).unwrap()).unwrap();
    let runs = summary["runs"].as_array().unwrap();
    assert_eq!(runs.len(), 2);
    assert_eq!(runs[1]["case_file"], "run2.toml");
    assert_eq!(runs[1]["bit_md_m"], 230.0);
}

/// The interface columns of `trajectory.csv`.
const TRAJECTORY_COLUMNS: &str = "md_m,inc_deg,azi_deg,tvd_m,north_m,east_m,inc_meas_deg,azi_meas_deg,inc_err_deg,azi_err_deg,build_force_kN,walk_force_kN,tilt_inc_deg,tilt_azi_deg,wob_kN";

/// The direction-error columns back-analysis appends.
const REFERENCE_COLUMNS: &str = "dir_err_deg,hold_dir_err_deg,rates_30m_dir_err_deg,rates_60m_dir_err_deg,rates_90m_dir_err_deg,statistic_dir_err_deg";

fn check_csv(text: &str, rows_at_least: usize) {
    check_csv_columns(text, rows_at_least, TRAJECTORY_COLUMNS);
}

/// `text` has the header `header`, at least `rows_at_least` rows, as many cells in each, no NaN.
fn check_csv_columns(text: &str, rows_at_least: usize, header: &str) {
    let mut lines = text.lines();
    assert_eq!(lines.next().unwrap(), header);
    let rows: Vec<&str> = lines.collect();
    assert!(rows.len() >= rows_at_least, "{} rows", rows.len());
    let n = header.split(',').count();
    for r in rows {
        assert_eq!(r.split(',').count(), n, "{r}");
        assert!(!r.to_lowercase().contains("nan") && !r.contains("inf"), "{r}");
    }
}

#[test]
fn predict_tracking_writes_the_interface_outputs() {
    let dir = setup(&CASE);
    let o = run(dir.path(), "predict", &["--from", "200", "--to", "240", "--out", "out"]);
    assert!(o.success(), "{}", o.stderr);
    let csv = std::fs::read_to_string(dir.path().join("out/trajectory.csv")).unwrap();
    check_csv(&csv, 21);
    // measured stations at 210..240 have measured and error columns filled
    let measured = csv
        .lines()
        .skip(1)
        .filter(|l| l.split(',').nth(6).is_some_and(|c| !c.is_empty()));
    assert_eq!(measured.count(), 5);
    let s: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.path().join("out/summary.json")).unwrap()).unwrap();
    assert_eq!(s["tracking"]["stations_compared"], 4);
    assert_eq!(s["azimuth_reference"], "unspecified");
    assert!(s["tracking"]["inc_err_per_100m_deg"].as_f64().unwrap().is_finite());
    assert!(s["rates"]["build_rate_deg_per_30m"].as_f64().unwrap().is_finite());
}

#[test]
fn backanalyze_writes_errors_per_100m() {
    let dir = setup(&CASE);
    let o = run(dir.path(), "backanalyze", &["--from", "200", "--out", "out"]);
    assert!(o.success(), "{}", o.stderr);
    let csv = std::fs::read_to_string(dir.path().join("out/trajectory.csv")).unwrap();
    check_csv_columns(&csv, 4, &format!("{TRAJECTORY_COLUMNS},{REFERENCE_COLUMNS}"));
    let s: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.path().join("out/summary.json")).unwrap()).unwrap();
    assert_eq!(s["intervals"], 4);
    assert!(s["inc_err_per_100m_deg"].as_f64().unwrap() >= 0.0);
    assert!(s["azi_err_per_100m_deg"].as_f64().unwrap() >= 0.0);
    assert!(s["bit_rock"]["lateral_drillability"].as_f64().is_some());
}

/// The azimuth reference a survey states (issue 18: here a `true azi` column) is carried to
/// `summary.json` of `predict` and `backanalyze` as the new key `azimuth_reference`.
#[test]
fn summaries_name_the_azimuth_reference() {
    let dir = case_dir(&survey().replacen("azi_deg", "true azi [deg]", 1), &CASE);
    let o = run(dir.path(), "predict", &["--from", "200", "--to", "220", "--out", "out"]);
    assert!(o.success(), "{}", o.stderr);
    assert_eq!(summary(dir.path())["azimuth_reference"], "true");
    std::fs::remove_dir_all(dir.path().join("out")).unwrap();
    let o = run(dir.path(), "backanalyze", &["--from", "200", "--out", "out"]);
    assert!(o.success(), "{}", o.stderr);
    assert_eq!(summary(dir.path())["azimuth_reference"], "true");
}

/// Default start of back-analysis: below the hole sections more than 1 in wider than the bit
/// (drilled by another BHA). Reference: the survey's stations; 12.25 in hole to 210 m above the
/// 8.5 in bit's hole leaves the intervals 210-220-230-240 m (3); the same case without the wide
/// section starts at 100 m (the first inclined station 30 m below the top: 5 intervals);
/// `--from` overrides the rule.
#[test]
fn backanalyze_starts_below_the_wider_hole_by_default() {
    let wide = CASE.replace(
        r#"hole = [{ to_md = "1000 m", diameter = "8.5 in" }]"#,
        r#"hole = [{ to_md = "210 m", diameter = "12.25 in" }, { to_md = "1000 m", diameter = "8.5 in" }]"#,
    );
    assert_ne!(wide, *CASE);
    let intervals = |case: &str, args: &[&str]| -> (u64, String) {
        let dir = setup(case);
        let mut all = vec!["--out", "out"];
        all.extend_from_slice(args);
        let o = run(dir.path(), "backanalyze", &all);
        assert!(o.success(), "{}", o.stderr);
        let s: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(dir.path().join("out/summary.json")).unwrap()).unwrap();
        (s["intervals"].as_u64().unwrap(), o.stdout.clone())
    };
    let (n, stdout) = intervals(&wide, &[]);
    assert_eq!(n, 3, "{stdout}");
    assert!(stdout.contains("from: the hole below 210.0 m"), "{stdout}");
    let (n, stdout) = intervals(&CASE, &[]);
    assert_eq!(n, 5, "{stdout}");
    assert!(!stdout.contains("from: the hole below"), "{stdout}");
    let (n, stdout) = intervals(&wide, &["--from", "200"]);
    assert_eq!(n, 4, "{stdout}");
    assert!(!stdout.contains("from: the hole below"), "{stdout}");
    // a string without a bit component (a 6.5 in collar at the bottom) is measured against the
    // hole at the bottom of the survey (8.5 in), not against its lowest component: same 3
    // intervals
    let bitless = wide.replace(&format!("{BIT}{}", stabilizer("8.5 in")), "");
    assert!(!bitless.contains("type = \"bit\""));
    let (n, stdout) = intervals(&bitless, &[]);
    assert_eq!(n, 3, "{stdout}");
    assert!(stdout.contains("from: the hole below 210.0 m"), "{stdout}");
}

/// Design comparison: two BHAs (the case and a copy whose near-bit stabilizer is replaced by a
/// collar, a pendulum-like string) over the same interval give one comparison table; the
/// stabilized one builds more (textbook, docs/theory.md 9.3).
#[test]
fn predict_compares_several_bhas() {
    let dir = setup(&CASE);
    let slick = CASE.replace("name = \"predict cli test\"", "name = \"slick\"").replace(
        "type = \"stabilizer\"\nod = \"8.5 in\"\nbody_od = \"6.5 in\"",
        "type = \"collar\"\nod = \"6.5 in\"",
    );
    std::fs::write(dir.path().join("slick.toml"), slick).unwrap();
    let o = run_in(
        dir.path(),
        &["predict", "case.toml", "slick.toml", "--ahead", "20 m", "--out", "out"],
    );
    assert!(o.success(), "{}", o.stderr);
    let table = std::fs::read_to_string(dir.path().join("out/comparison.csv")).unwrap();
    let rows: Vec<Vec<&str>> = table.lines().skip(1).map(|l| l.split(',').collect()).collect();
    assert_eq!(rows.len(), 2, "{table}");
    assert_eq!(rows[0][0], "predict cli test");
    assert_eq!(rows[1][0], "slick");
    let build = |r: &Vec<&str>| r[3].parse::<f64>().unwrap();
    assert!(build(&rows[0]) > build(&rows[1]), "{table}");
    for k in 1..=2 {
        let csv = std::fs::read_to_string(dir.path().join(format!("out/case{k}/trajectory.csv"))).unwrap();
        check_csv(&csv, 10);
    }
    let s: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.path().join("out/summary.json")).unwrap()).unwrap();
    assert_eq!(s["cases"].as_array().unwrap().len(), 2);
}

fn summary(dir: &Path) -> serde_json::Value {
    serde_json::from_str(&std::fs::read_to_string(dir.join("out/summary.json")).unwrap()).unwrap()
}

/// Fidelity for prediction (issue 5): soft is refused, naming the option or the case key;
/// `--cut` with `whole` is refused; hybrid runs the bha model and says why; `whole` solves the
/// whole string at every step and, since the cut model is built to reproduce its bit forces
/// (fem::bha, 1e-4 agreement), predicts the same build rate as `bha` within 0.02 deg/30 m
/// (reference: the whole-string model itself; tolerance: the cut's bit-force agreement times the
/// law's sensitivity over 10 m, with margin).
#[test]
fn predict_fidelity_levels() {
    let dir = setup(&CASE);
    let o = run(
        dir.path(),
        "predict",
        &["--ahead", "10 m", "--fidelity", "soft", "--out", "out"],
    );
    assert_error(dir.path(), &o, &["--fidelity", "soft cannot predict"]);
    let o = run(
        dir.path(),
        "predict",
        &["--ahead", "10 m", "--fidelity", "stiff", "--out", "out"],
    );
    assert_error(dir.path(), &o, &["--fidelity", "stiff"]);
    let o = run(
        dir.path(),
        "predict",
        &[
            "--ahead",
            "10 m",
            "--fidelity",
            "whole",
            "--cut",
            "30 m",
            "--out",
            "out",
        ],
    );
    assert_error(dir.path(), &o, &["--cut", "whole"]);
    let soft_case = setup(&CASE.replace("[bit_rock]", "[solver]\nfidelity = \"soft\"\n[bit_rock]"));
    let o = run(soft_case.path(), "predict", &["--ahead", "10 m", "--out", "out"]);
    assert_error(soft_case.path(), &o, &["solver.fidelity", "soft cannot predict"]);

    let mut rate = Vec::new();
    for level in ["hybrid", "whole", "bha"] {
        let _ = std::fs::remove_dir_all(dir.path().join("out"));
        let o = run(
            dir.path(),
            "predict",
            &["--ahead", "10 m", "--fidelity", level, "--out", "out"],
        );
        assert!(o.success(), "{level}: {}", o.stderr);
        let s = summary(dir.path());
        let used = if level == "whole" { "whole" } else { "bha" };
        assert_eq!(s["model"]["fidelity"], used, "{level}");
        assert_eq!(s["model"]["fidelity_choice"]["requested"], level);
        assert!(!s["model"]["fidelity_choice"]["reason"].as_str().unwrap().is_empty());
        rate.push(s["rates"]["build_rate_deg_per_30m"].as_f64().unwrap());
    }
    assert_eq!(rate[0], rate[2], "hybrid runs bha");
    assert!((rate[1] - rate[2]).abs() < 0.02, "whole {} vs bha {}", rate[1], rate[2]);
}

/// Accuracy presets set the prediction step (src/case/accuracy.rs table): `--accuracy fast` gives
/// 2 m, `precise` 0.5 m, an explicit `--step` wins; in the case file `[solver] accuracy` gives
/// the step only where `[bit_rock] step` is absent.
#[test]
fn predict_accuracy_sets_the_step() {
    let step_of = |case: &str, args: &[&str]| {
        let dir = setup(case);
        let mut all = vec!["--ahead", "4 m", "--out", "out"];
        all.extend_from_slice(args);
        let o = run(dir.path(), "predict", &all);
        assert!(o.success(), "{args:?}: {}", o.stderr);
        summary(dir.path())["step_m"].as_f64().unwrap()
    };
    assert_eq!(step_of(&CASE, &[]), 2.0, "the case's [bit_rock] step");
    assert_eq!(step_of(&CASE, &["--accuracy", "precise"]), 0.5);
    assert_eq!(step_of(&CASE, &["--accuracy", "precise", "--step", "1 m"]), 1.0);
    let preset = CASE.replace("[bit_rock]\nstep = \"2 m\"", "[solver]\naccuracy = \"precise\"");
    assert_eq!(
        step_of(&preset, &[]),
        0.5,
        "preset step where [bit_rock] step is absent"
    );
    let both = CASE.replace("[bit_rock]", "[solver]\naccuracy = \"precise\"\n[bit_rock]");
    assert_eq!(step_of(&both, &[]), 2.0, "explicit [bit_rock] step wins");
    let dir = setup(&CASE);
    let o = run(
        dir.path(),
        "predict",
        &["--ahead", "4 m", "--accuracy", "rough", "--out", "out"],
    );
    assert_error(dir.path(), &o, &["--accuracy", "rough"]);
}

/// `--extrapolate`: the summary gains `step_extrapolation` with the coarse step (the given one),
/// the fine step (half) and finite error estimates; rows are those of the coarse march.
#[test]
fn predict_extrapolate_reports_the_step_error() {
    let dir = setup(&CASE);
    let o = run(
        dir.path(),
        "predict",
        &["--ahead", "8 m", "--extrapolate", "--out", "out"],
    );
    assert!(o.success(), "{}", o.stderr);
    let s = summary(dir.path());
    let e = &s["step_extrapolation"];
    assert_eq!(e["coarse_step_m"], 2.0);
    assert_eq!(e["fine_step_m"], 1.0);
    assert!(e["est_inc_err_deg"].as_f64().unwrap() >= 0.0);
    assert!(e["est_azi_err_deg"].as_f64().unwrap() >= 0.0);
    let csv = std::fs::read_to_string(dir.path().join("out/trajectory.csv")).unwrap();
    check_csv(&csv, 5);
    assert!(o.stdout.contains("step extrapolation"));
    let dir = setup(&CASE);
    let o = run(dir.path(), "predict", &["--ahead", "8 m", "--out", "out"]);
    assert!(o.success());
    assert!(summary(dir.path())["step_extrapolation"].is_null());
}

/// `backanalyze --calibrate` writes `case_fitted.toml`, a case that runs as it is from the
/// output folder with the fitted law (its `[bit_rock]` keys equal to `bit_rock_fitted.toml`'s),
/// and its report shows the errors in the units asked for.
#[test]
fn backanalyze_writes_a_fitted_case_that_runs_and_a_report_in_the_units_asked() {
    let dir = setup(&CASE);
    let o = run(
        dir.path(),
        "backanalyze",
        &[
            "--from",
            "200",
            "--calibrate",
            "--out",
            "out",
            "--report",
            "b.html",
            "--units",
            "oilfield",
        ],
    );
    assert!(o.success(), "{}", o.stderr);
    assert!(
        o.stdout.contains("case_fitted.toml") && o.stdout.contains("wrote b.html"),
        "{}",
        o.stdout
    );
    let fitted = std::fs::read_to_string(dir.path().join("out/case_fitted.toml")).unwrap();
    let keys = std::fs::read_to_string(dir.path().join("out/bit_rock_fitted.toml")).unwrap();
    let value = |text: &str, key: &str| -> String {
        let line = text
            .lines()
            .find(|l| l.starts_with(key))
            .unwrap_or_else(|| panic!("no {key}"));
        line.split('=')
            .nth(1)
            .unwrap()
            .split('#')
            .next()
            .unwrap()
            .trim()
            .to_string()
    };
    let (a, b): (f64, f64) = (
        value(&fitted, "lateral_drillability").parse().unwrap(),
        value(&keys, "lateral_drillability").parse().unwrap(),
    );
    assert!((a - b).abs() < 1e-6, "{a} against {b}");
    let out = dir.path().join("out");
    let s = crate::common::run_ok(&out, &["solve", "case_fitted.toml", "--fidelity", "bha", "--json"]);
    assert!(s.stdout.contains("\"converged\": true"), "{}", s.stdout);
    let html = std::fs::read_to_string(dir.path().join("b.html")).unwrap();
    assert!(
        html.contains("deg/100 ft") && !html.contains("deg/100 m"),
        "report not in oilfield units"
    );
}

/// The kick-off of `wells/horizontal/landing.toml` (docs/guide.md, "Example wells"): its slide
/// sheet slides at toolface 135 deg off the vertical hole (magnetic: toward azimuth 135 below 5
/// deg at the bend) and hands over to the high side (gravity toolface 0) once the hole at the bend
/// is past 5 deg. Reference: the plan's direction, azimuth 135 deg: the predicted hole keeps it
/// within 0.5 deg from 1,094 m (5.3 deg) to 1,110 m while the inclination rises past 5 deg.
#[test]
fn landing_example_kicks_off_toward_the_plan() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("p");
    let r = crate::common::run_ok(
        crate::common::root(),
        &[
            "predict",
            "wells/horizontal/landing.toml",
            "--from",
            "1080",
            "--to",
            "1110",
            "--step",
            "2",
            "--out",
            out.to_str().unwrap(),
        ],
    );
    let csv = std::fs::read_to_string(out.join("trajectory.csv")).unwrap();
    let rows: Vec<Vec<f64>> = csv
        .lines()
        .skip(1)
        .map(|l| l.split(',').take(3).map(|v| v.parse().unwrap()).collect())
        .collect();
    let last = rows.last().unwrap();
    assert!(last[1] > 6.0, "{}", r.stdout);
    for row in rows.iter().filter(|r| r[0] >= 1094.0) {
        assert!((row[2] - 135.0).abs() < 0.5, "{row:?}\n{csv}");
    }
}

/// The reactive torque along a prediction (docs/guide.md, `trajectory.csv`): with
/// `reactive_torque = true` on the sliding bent motor of `wells/horizontal/steered.toml` (6 kN.m,
/// toolface 30 deg, below the slide sheet's intervals) `trajectory.csv` ends with
/// `reactive_toolface_turn_deg`, positive on every sliding row, its first row (the start's
/// solve) the turn `solve --fidelity bha` reports at the same bit MD (reference: that command,
/// to the CSV's 0.001 deg); without the option the column is absent.
#[test]
fn a_sliding_prediction_lists_the_reactive_turn_per_step() {
    let root = crate::common::root();
    let dir = TempDir::new().unwrap();
    for f in ["survey.csv", "slides.csv"] {
        std::fs::copy(root.join("wells/horizontal").join(f), dir.path().join(f)).unwrap();
    }
    let case = std::fs::read_to_string(root.join("wells/horizontal/steered.toml"))
        .unwrap()
        .replace(
            "mode = \"drilling\"",
            "mode = \"sliding\"\nreactive_torque = true\nbit_torque = \"6 kN.m\"\ntoolface = \"30 deg\"",
        );
    std::fs::write(dir.path().join("case.toml"), case).unwrap();
    let args = ["predict", "case.toml", "--from", "3000", "--to", "3005", "--out", "out"];
    let out = run_in(dir.path(), &args);
    assert!(out.success(), "{}", out.stderr);
    let csv = std::fs::read_to_string(dir.path().join("out/trajectory.csv")).unwrap();
    assert!(
        csv.lines()
            .next()
            .unwrap()
            .ends_with(",mode,toolface_deg,reactive_toolface_turn_deg"),
        "{csv}"
    );
    let turns: Vec<f64> = csv
        .lines()
        .skip(1)
        .map(|l| l.rsplit(',').next().unwrap().parse().unwrap())
        .collect();
    assert!(turns.len() >= 5 && turns.iter().all(|t| *t > 0.0), "{csv}");
    let solve = run_in(
        dir.path(),
        &["solve", "case.toml", "--bit-md", "3000", "--fidelity", "bha", "--json"],
    );
    let j: serde_json::Value = serde_json::from_str(&solve.stdout).unwrap();
    let turn = j["steering"]["reactive_toolface_turn_deg"].as_f64().unwrap();
    assert!((turns[0] - turn).abs() <= 0.0005 + 1e-9, "{} vs {turn}", turns[0]);
    let plain = dir.path().join("plain");
    let off = run_in(
        &root,
        &[
            "predict",
            "wells/horizontal/steered.toml",
            "--from",
            "2900",
            "--to",
            "2902",
            "--out",
            plain.to_str().unwrap(),
        ],
    );
    assert!(off.success(), "{}", off.stderr);
    let csv = std::fs::read_to_string(plain.join("trajectory.csv")).unwrap();
    assert!(csv.lines().next().unwrap().ends_with(",mode,toolface_deg"), "{csv}");
}
