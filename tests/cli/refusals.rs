//! What drillpath refuses, and why (README "What drillpath refuses, and why"): an output that
//! is an input, work without bounds, impossible geometry and stresses, predictions that leave
//! the earth, partial outputs of a failed run, negative option values, errors that do not say
//! why, bare depths in a survey's own unit, a hook load below zero. Each test states what a
//! correct run does; the input files are compared byte for byte after every refused run.

use std::path::Path;
use std::time::{Duration, Instant};
use tempfile::TempDir;

use crate::common::{
    assert_error_names, case_dir, drillpath, example_case, run_in, slid_horizontal, Run, BIT, DRILL_PIPE,
};

/// Vertical to 300 m, a build of 3 deg/30 m to 30 deg, then a hold to 600 m.
const SURVEY: &str = "md_m,inc_deg,azi_deg\n0,0,0\n300,0,0\n400,10,0\n600,30,0\n";

/// Vertical to 300 m, a 90 deg/30 m dogleg to 30 deg, then a hold to 600 m.
const SHARP: &str = "md_m,inc_deg,azi_deg\n0,0,0\n300,0,0\n310,30,0\n600,30,0\n";

/// A vertical hole to 600 m.
const VERTICAL: &str = "md_m,inc_deg,azi_deg\n0,0,0\n600,0,0\n";

/// A slick BHA (bit, 30 m of 6.5 in collars) and drill pipe in an 8.5 in hole, 1.2 sg mud,
/// drilling at `wob` (e.g. `"50 kN"`) with the bit at 600 m; `solver` is the `[solver]` body.
fn case_text(wob: &str, solver: &str) -> String {
    format!(
        r#"name = "refusals"

[well]
survey = "survey.csv"
hole = [ {{ to_md = "600 m", diameter = "8.5 in" }} ]

[mud]
density = "1.2 sg"

[operation]
mode = "drilling"
bit_md = "600 m"
wob = "{wob}"
rpm = 60

{BIT}
[[string]]
type = "collar"
od = "6.5 in"
id = "2.8125 in"
length = "30 m"

{DRILL_PIPE}
[solver]
element_length = "1 m"
{solver}
"#
    )
}

/// A directory with the gentle survey and a case at 50 kN.
fn fixture() -> TempDir {
    case_dir(SURVEY, &case_text("50 kN", ""))
}

/// The bytes of every file in `dir` (sorted by name), to compare before and after a run.
fn snapshot(dir: &Path) -> Vec<(String, Vec<u8>)> {
    let mut files: Vec<(String, Vec<u8>)> = std::fs::read_dir(dir)
        .unwrap()
        .flatten()
        .filter(|e| e.path().is_file())
        .map(|e| {
            (
                e.file_name().to_string_lossy().into_owned(),
                std::fs::read(e.path()).unwrap(),
            )
        })
        .collect();
    files.sort();
    files
}

/// Run `drillpath args` in `dir` under hard bounds: 4 GB of address space (`ulimit -v`) and
/// 30 s of wall clock (killed after). Returns the run and its wall-clock time.
fn run_bounded(dir: &Path, args: &[&str]) -> (Run, Duration) {
    let exe = env!("CARGO_BIN_EXE_drillpath");
    let mut cmd = drillpath();
    let mut sh = std::process::Command::new("sh");
    sh.arg("-c")
        .arg("ulimit -v 4000000 && exec \"$0\" \"$@\"")
        .arg(exe)
        .args(args)
        .current_dir(dir)
        .envs(cmd.get_envs().filter_map(|(k, v)| Some((k, v?))))
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped());
    let _ = &mut cmd;
    let t0 = Instant::now();
    let mut child = sh.spawn().expect("cannot start sh");
    while child.try_wait().unwrap().is_none() {
        if t0.elapsed() > Duration::from_secs(30) {
            child.kill().unwrap();
            panic!("drillpath {args:?} ran for more than 30 s");
        }
        std::thread::sleep(Duration::from_millis(10));
    }
    let out = child.wait_with_output().unwrap();
    let elapsed = t0.elapsed();
    let run = Run {
        status: out.status,
        stdout: String::from_utf8(out.stdout).unwrap(),
        stderr: String::from_utf8(out.stderr).unwrap(),
    };
    (run, elapsed)
}

/// A refused run: one error line naming `must_name`, within `REFUSAL_BOUND` (the bound says
/// the work was refused before it was done, with room for a loaded machine; not a benchmark),
/// the directory's files unchanged and no new file.
fn assert_refused(dir: &Path, args: &[&str], must_name: &[&str]) -> String {
    let before = snapshot(dir);
    let entries_before = std::fs::read_dir(dir).unwrap().count();
    let (r, elapsed) = run_bounded(dir, args);
    let line = assert_error_names(&r, must_name).to_string();
    assert!(elapsed < REFUSAL_BOUND, "{args:?} took {elapsed:?} to be refused");
    assert_eq!(snapshot(dir), before, "{args:?} changed an input file");
    assert_eq!(
        std::fs::read_dir(dir).unwrap().count(),
        entries_before,
        "{args:?} left a new entry"
    );
    line
}

/// Time within which a refused run answers (the issue asks under 1 s; 3 s leaves room for a
/// loaded CI machine; a run that does the refused work takes minutes or exhausts memory).
const REFUSAL_BOUND: Duration = Duration::from_secs(3);

#[test]
fn an_output_that_is_an_input_is_refused() {
    let f = fixture();
    let d = f.path();
    assert_refused(
        d,
        &["solve", "case.toml", "--report", "case.toml"],
        &["--report", "case.toml", "input"],
    );
    assert_refused(
        d,
        &["solve", "case.toml", "--report", "survey.csv"],
        &["--report", "survey.csv", "input"],
    );
    assert_refused(d, &["survey", "survey.csv", "--out", "survey.csv"], &["--out", "input"]);
    std::fs::create_dir(d.join("sub")).unwrap();
    assert_refused(
        d,
        &["survey", "case.toml", "--out", "sub/../survey.csv"],
        &["--out", "input"],
    );
    #[cfg(unix)]
    {
        std::os::unix::fs::symlink(d, d.join("here")).unwrap();
        assert_refused(
            d,
            &["survey", "case.toml", "--out", "here/survey.csv"],
            &["--out", "input"],
        );
        std::os::unix::fs::symlink(d.join("case.toml"), d.join("link.html")).unwrap();
        assert_refused(
            d,
            &["solve", "case.toml", "--report", "link.html"],
            &["--report", "input"],
        );
    }
    // an --out folder one of whose files is an input: a survey named trajectory.csv
    let t = case_dir(SURVEY, &case_text("50 kN", "").replace("survey.csv", "trajectory.csv"));
    std::fs::rename(t.path().join("survey.csv"), t.path().join("trajectory.csv")).unwrap();
    assert_refused(
        t.path(),
        &["predict", "case.toml", "--from", "500", "--ahead", "5 m", "--out", "."],
        &["--out", "trajectory.csv", "input"],
    );
    // two outputs on one file
    assert_refused(
        d,
        &["solve", "case.toml", "--out", "res", "--report", "res/summary.json"],
        &["--report", "--out", "different paths"],
    );
}

#[test]
fn a_failed_run_writes_nothing() {
    let f = fixture();
    let d = f.path();
    std::fs::create_dir(d.join("existing_dir")).unwrap();
    assert_refused(
        d,
        &["solve", "case.toml", "--out", "res", "--report", "existing_dir"],
        &["--report", "existing_dir", "directory"],
    );
    assert!(!d.join("res").exists());
    // a previous run's results are left as they were by a run that fails after its work
    std::fs::create_dir(d.join("res")).unwrap();
    std::fs::write(d.join("res/summary.json"), "old").unwrap();
    std::fs::write(d.join("blocker"), "a file where a folder is needed").unwrap();
    let r = run_in(d, &["solve", "case.toml", "--out", "res", "--report", "blocker/r.html"]);
    assert_error_names(&r, &["--report", "blocker"]);
    assert_eq!(std::fs::read_to_string(d.join("res/summary.json")).unwrap(), "old");
    assert!(!d.join("res/string.csv").exists());
}

#[test]
fn work_beyond_the_bounds_is_refused_before_it_is_done() {
    for (key, value) in [
        ("element_length", "1e-6 m"),
        ("element_length", "1e-3 m"),
        ("element_length", "0.01 m"),
        ("bha_element_length", "1e-4 m"),
    ] {
        let text = case_text("50 kN", "").replace("element_length = \"1 m\"", &format!("{key} = \"{value}\""));
        let dir = case_dir(SURVEY, &text);
        let line = assert_refused(
            dir.path(),
            &["solve", "case.toml"],
            &[&format!("solver.{key}"), "elements", "longer"],
        );
        assert!(line.contains("50000"), "{line}");
    }
    let f = fixture();
    assert_refused(
        f.path(),
        &["loads", "case.toml", "--every", "1e-6 m"],
        &["--every", "bit depths", "longer step"],
    );
    assert_refused(
        f.path(),
        &["predict", "case.toml", "--from", "500", "--ahead", "1e7 m"],
        &["steps", "shorter interval", "longer step"],
    );
}

#[test]
fn a_time_limit_stops_a_solve_and_says_so() {
    let dir = case_dir(SURVEY, &case_text("50 kN", "time_limit = \"1e-6 s\""));
    let r = run_in(dir.path(), &["solve", "case.toml", "--fidelity", "whole"]);
    assert_error_names(&r, &["did not converge", "time limit", "solver] time_limit"]);
}

#[test]
fn an_impossible_dogleg_and_a_stress_beyond_yield_are_flagged() {
    let f = case_dir(SHARP, &case_text("50 kN", ""));
    let r = run_in(f.path(), &["solve", "case.toml", "--fidelity", "whole", "--json"]);
    assert!(r.success(), "{}", r.describe());
    let j: serde_json::Value = serde_json::from_str(&r.stdout).unwrap();
    // bending alone: a 6.5 in steel collar yields (E-75 assumed, 517 MPa) at
    // 517e6 / (207e9 x 0.0826) = 0.0302 rad/m = 52 deg/30 m, below the survey's 90 deg/30 m
    let y = &j["yield"];
    assert_eq!(y["exceeded"], true, "{y}");
    assert_eq!(y["yield_strength_assumed"], true, "{y}");
    assert!((y["yield_strength_MPa"].as_f64().unwrap() - 517.1).abs() < 0.1, "{y}");
    let md = y["at_md_m"].as_f64().unwrap();
    assert!((295.0..320.0).contains(&md), "the highest stress is in the dogleg: {y}");
    let warnings = j["warnings"].as_array().unwrap();
    assert!(warnings[0].as_str().unwrap().contains("52.0 deg/30 m"), "{warnings:?}");
    let text = run_in(f.path(), &["solve", "case.toml", "--fidelity", "whole"]);
    assert!(text.stdout.contains("WARNING: von Mises stress"), "{}", text.stdout);
    // grade S-135 (931 MPa) given to the collar and the pipe: the same bend (at most
    // E r kappa = 207 GPa x 63.5 mm x 0.0524 rad/m = 689 MPa in the pipe, plus the axial and
    // torsional parts) stays below it
    let graded = case_text("50 kN", "")
        .replace("length = \"30 m\"", "length = \"30 m\"\ngrade = \"S-135\"")
        .replace(
            "tool_joint_od = \"6.625 in\"",
            "tool_joint_od = \"6.625 in\"\ngrade = \"S-135\"",
        );
    let g = case_dir(SHARP, &graded);
    let r = run_in(g.path(), &["solve", "case.toml", "--fidelity", "whole", "--json"]);
    assert!(r.success(), "{}", r.describe());
    let j: serde_json::Value = serde_json::from_str(&r.stdout).unwrap();
    let y = &j["yield"];
    assert_eq!(y["yield_strength_assumed"], false, "{y}");
    assert!((y["yield_strength_MPa"].as_f64().unwrap() - 930.8).abs() < 0.5, "{y}");
    assert_eq!(y["exceeded"], false, "{y}");
    assert!(y["max_von_mises_MPa"].as_f64().unwrap() > 689.0, "{y}");
}

#[test]
fn a_hook_load_below_zero_is_lock_up() {
    // vertical hole: the largest WOB is the string's buoyed weight (no wall contact, no friction)
    let dir = case_dir(VERTICAL, &case_text("250 kN", ""));
    let r = run_in(dir.path(), &["solve", "case.toml", "--fidelity", "soft", "--json"]);
    assert!(r.success(), "{}", r.describe());
    let j: serde_json::Value = serde_json::from_str(&r.stdout).unwrap();
    let g = 9.80665;
    let buoyancy = 1.0 - 1200.0 / 7850.0;
    let area = |od: f64, id: f64| std::f64::consts::PI / 4.0 * ((od * 0.0254).powi(2) - (id * 0.0254).powi(2));
    let weight =
        (area(8.5, 0.0) * 0.3 * 7850.0 + area(6.5, 2.8125) * 30.0 * 7850.0 + 29.0 * (600.0 - 30.3)) * g * buoyancy;
    let l = &j["lock_up"];
    let max_wob = l["max_wob_kN"].as_f64().unwrap() * 1e3;
    assert!(
        (max_wob - weight).abs() < 1e-3 * weight,
        "{max_wob} N against {weight} N"
    );
    assert!((l["hook_load_kN"].as_f64().unwrap() * 1e3 - (weight - 250e3)).abs() < 1e-3 * weight);
    assert!(j["warnings"][0].as_str().unwrap().contains("lock-up"));
    let text = run_in(dir.path(), &["solve", "case.toml", "--fidelity", "soft"]);
    assert!(text.stdout.contains("WARNING: lock-up"), "{}", text.stdout);
    // predict warns before marching with a WOB the string cannot deliver
    let p = run_in(
        dir.path(),
        &["predict", "case.toml", "--from", "580", "--ahead", "5 m", "--json"],
    );
    assert!(p.success(), "{}", p.describe());
    let j: serde_json::Value = serde_json::from_str(&p.stdout).unwrap();
    assert!(
        j["warnings"][0].as_str().unwrap().contains("lock-up"),
        "{}",
        j["warnings"]
    );
    // within the string's weight: no flag
    let ok = case_dir(VERTICAL, &case_text("150 kN", ""));
    let r = run_in(ok.path(), &["solve", "case.toml", "--fidelity", "soft", "--json"]);
    let j: serde_json::Value = serde_json::from_str(&r.stdout).unwrap();
    assert!(
        j["lock_up"].is_null() && j["warnings"].as_array().unwrap().is_empty(),
        "{j}"
    );
}

#[test]
fn a_prediction_that_leaves_the_earth_stops_with_the_md() {
    // the j-shape's fulcrum assembly builds on: from 35 deg it turns the hole over within 5 km
    let (r, _) = run_bounded(
        &crate::common::root(),
        &[
            "predict",
            example_case("j-shape").to_str().unwrap(),
            "--ahead",
            "5000 m",
            "--step",
            "10 m",
            "-q",
        ],
    );
    let line = assert_error_names(&r, &["the predicted hole", "m MD", "shorter interval"]);
    assert!(
        line.contains("rose above the surface") || line.contains("point up the well"),
        "{line}"
    );
}

#[test]
fn a_prediction_below_the_deepest_hole_section_is_warned() {
    let f = fixture();
    let r = run_in(
        f.path(),
        &[
            "predict",
            "case.toml",
            "--from",
            "590",
            "--ahead",
            "20 m",
            "--step",
            "5 m",
        ],
    );
    assert!(r.success(), "{}", r.describe());
    assert!(
        r.stderr.contains("below the deepest hole section (600.00 m MD)"),
        "{}",
        r.stderr
    );
    assert!(
        !r.stderr.contains('\u{1b}'),
        "colour codes in redirected stderr: {:?}",
        r.stderr
    );
}

#[test]
fn negative_option_values_meet_the_options_own_rule() {
    let f = fixture();
    let d = f.path();
    let cases: &[(&[&str], &[&str])] = &[
        (&["predict", "case.toml", "--ahead", "-10 m"], &["--ahead", "positive"]),
        (&["predict", "case.toml", "--ahead=-10m"], &["--ahead", "positive"]),
        (
            &["predict", "case.toml", "--ahead", "10 m", "--step", "-1"],
            &["--step", "smallest"],
        ),
        (
            &["predict", "case.toml", "--ahead", "10 m", "--cut", "-5"],
            &["--cut", "smallest"],
        ),
        (
            &["backanalyze", "case.toml", "--horizon", "-5"],
            &["--horizon", "smallest"],
        ),
        (&["loads", "case.toml", "--every", "-1"], &["--every", "positive"]),
        (&["loads", "case.toml", "--wob", "-5"], &["--wob", "negative"]),
        (&["solve", "case.toml", "--bit-md", "-5"], &["--bit-md", "outside"]),
    ];
    for (args, names) in cases {
        let line = assert_refused(d, args, names);
        assert!(!line.contains("unexpected argument"), "{line}");
    }
}

#[test]
fn errors_say_why() {
    let tiny = case_dir(SURVEY, &case_text("50 kN", "tolerance = 1e-300"));
    assert_refused(
        tiny.path(),
        &["solve", "case.toml"],
        &["solver.tolerance", "1e-300", "double precision"],
    );
    for runs in ["0", "2.5"] {
        let bad = case_dir(SURVEY, &case_text("50 kN", &format!("refine_runs = {runs}")));
        assert_refused(
            bad.path(),
            &["solve", "case.toml"],
            &["solver.refine_runs", "whole number"],
        );
    }
    let one = case_dir(SURVEY, &case_text("50 kN", "max_iterations = 1"));
    let r = run_in(one.path(), &["solve", "case.toml", "--fidelity", "whole"]);
    // the direct solve's iteration and one for each of the two starts from the buckled shape
    // below the WOB (`HELICAL_LOCK_UP_FRACTIONS`), which the message names
    let line = assert_error_names(
        &r,
        &[
            "in 3 iterations, with a start from the buckled shape below the WOB for a climb that did not converge",
            "max_iterations` = 1",
        ],
    );
    assert!(!line.contains("5 iterations"), "{line}");
}

#[test]
fn a_hold_beyond_90_deg_names_the_known_limit() {
    // vertical to 1,200 m, built to 120 deg at 1,600 m, held to the bit at 1,700 m: the string
    // delivers the WOB (it converges with the default limit); two iterations make it fail
    let survey = "md_m,inc_deg,azi_deg\n0,0,0\n1200,0,0\n1300,30,0\n1400,60,0\n1500,90,0\n1600,120,0\n1700,120,0\n";
    let text = case_text("20 kN", "max_iterations = 2").replace("600 m", "1700 m");
    let dir = case_dir(survey, &text);
    let r = run_in(dir.path(), &["solve", "case.toml", "--fidelity", "whole"]);
    assert_error_names(
        &r,
        &[
            "max_iterations` = 2",
            "120.0 deg",
            "beyond 90 deg is a known limit",
            "Limits",
        ],
    );
    // drilled up to 180 deg for 700 m below 200 m of vertical hole, the string cannot be put on
    // bottom at any WOB: not a refusal but a lock-up, answered with the soft string (exit 0)
    let survey = "md_m,inc_deg,azi_deg\n0,0,0\n200,0,0\n300,30,0\n400,60,0\n500,90,0\n600,120,0\n700,150,0\n800,180,0\n1500,180,0\n";
    let text = case_text("20 kN", "max_iterations = 20").replace("600 m", "1500 m");
    let dir = case_dir(survey, &text);
    let r = run_in(dir.path(), &["solve", "case.toml", "--fidelity", "whole"]);
    assert!(r.success(), "{}", r.describe());
    assert!(
        r.stdout.contains("fidelity soft: requested whole") && r.stdout.contains("cannot be put on bottom at any WOB"),
        "{}",
        r.describe()
    );
}

#[test]
fn bare_depths_are_in_the_surveys_unit() {
    // forge-16a's survey is in feet: a bare --bit-md is read in ft, and a note says so
    let case = example_case("forge-16a");
    let r = run_in(
        crate::common::root(),
        &[
            "solve",
            case.to_str().unwrap(),
            "--bit-md",
            "8000",
            "--fidelity",
            "soft",
            "--json",
        ],
    );
    assert!(r.success(), "{}", r.describe());
    let j: serde_json::Value = serde_json::from_str(&r.stdout).unwrap();
    assert!(
        (j["bit"]["md_m"].as_f64().unwrap() - 8000.0 * 0.3048).abs() < 1e-9,
        "{}",
        j["bit"]
    );
    assert!(r.stderr.contains("read in ft"), "{}", r.stderr);
    // with a unit, no note
    let r = run_in(
        crate::common::root(),
        &[
            "solve",
            case.to_str().unwrap(),
            "--bit-md",
            "2438.4 m",
            "--fidelity",
            "soft",
            "--json",
        ],
    );
    assert!(r.success() && !r.stderr.contains("read in ft"), "{}", r.describe());
}

#[test]
fn predict_starts_where_solve_puts_the_bit() {
    let text = case_text("50 kN", "").replace("bit_md = \"600 m\"", "bit_md = \"500 m\"");
    let dir = case_dir(SURVEY, &text);
    let r = run_in(dir.path(), &["predict", "case.toml", "--ahead", "10 m", "--json"]);
    assert!(r.success(), "{}", r.describe());
    let j: serde_json::Value = serde_json::from_str(&r.stdout).unwrap();
    assert_eq!(j["from_md_m"].as_f64().unwrap(), 500.0, "{j}");
}

#[test]
fn the_wrote_lines_name_the_report() {
    let f = fixture();
    let r = run_in(
        f.path(),
        &[
            "solve",
            "case.toml",
            "--fidelity",
            "bha",
            "--out",
            "res",
            "--report",
            "r.html",
        ],
    );
    assert!(r.success(), "{}", r.describe());
    assert!(
        r.stdout.contains("wrote res/summary.json") && r.stdout.contains("wrote r.html"),
        "{}",
        r.stdout
    );
}

/// A WITSML trajectory of three stations in the WITSML 1.x namespace; `before_root` goes
/// between the XML declaration and the root (a DTD), `name` is the trajectory's name.
fn witsml_text(before_root: &str, name: &str) -> String {
    let station = |uid: &str, md: f64, incl: f64| {
        format!(
            r#"<trajectoryStation uid="{uid}"><typeTrajStation>magnetic MWD</typeTrajStation><md uom="m">{md}</md><incl uom="dega">{incl}</incl><azi uom="dega">0</azi></trajectoryStation>"#
        )
    };
    format!(
        "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n{before_root}\n<trajectorys xmlns=\"http://www.witsml.org/schemas/1series\" version=\"1.4.1.1\">\n<trajectory uid=\"T\"><name>{name}</name><aziRef>grid north</aziRef>\n{}\n{}\n{}\n</trajectory>\n</trajectorys>\n",
        station("a", 0.0, 0.0),
        station("b", 300.0, 0.0),
        station("c", 600.0, 30.0)
    )
}

#[test]
fn hostile_witsml_is_refused_and_nothing_is_written() {
    // issue 22: an external entity is never resolved, nested entities answer at once, truncated
    // or malformed XML, a wrong root and a file over the size limit are refused naming the
    // file and the place; exit 2, inputs unchanged, no output written
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    std::fs::write(d.join("secret.txt"), "TOPSECRET").unwrap();
    let secret = d.join("secret.txt");
    let xxe = witsml_text(
        &format!(
            "<!DOCTYPE trajectorys [<!ENTITY x SYSTEM \"file://{}\">]>",
            secret.display()
        ),
        "&x;",
    );
    std::fs::write(d.join("xxe.xml"), &xxe).unwrap();
    let mut lol = String::from("<!DOCTYPE trajectorys [<!ENTITY l0 \"lol\">");
    for k in 1..10 {
        lol += &format!("<!ENTITY l{k} \"{}\">", format!("&l{};", k - 1).repeat(10));
    }
    lol += "]>";
    std::fs::write(d.join("laughs.xml"), witsml_text(&lol, "&l9;")).unwrap();
    let good = witsml_text("", "t");
    std::fs::write(d.join("truncated.xml"), &good[..good.len() - 40]).unwrap();
    std::fs::write(d.join("malformed.xml"), good.replace("</md>", "</mdd>")).unwrap();
    std::fs::write(d.join("root.xml"), good.replace("trajectorys", "wbGeometrys")).unwrap();
    let big = std::fs::File::create(d.join("big.xml")).unwrap();
    big.set_len(16 * 1024 * 1024 + 1).unwrap();
    std::fs::write(d.join("good.xml"), &good).unwrap();
    std::fs::write(
        d.join("case.toml"),
        case_text("50 kN", "").replace("survey = \"survey.csv\"", "survey = \"xxe.xml\""),
    )
    .unwrap();
    let cases: &[(&str, &[&str])] = &[
        (
            "xxe.xml",
            &[
                "xxe.xml: line 2",
                "document type declaration",
                "never expanded or fetched",
            ],
        ),
        ("laughs.xml", &["laughs.xml: line 2", "document type declaration"]),
        ("truncated.xml", &["truncated.xml: line 7", "truncated"]),
        ("malformed.xml", &["malformed.xml: line 5", "not well-formed XML"]),
        (
            "root.xml",
            &["root.xml: line 3, root element `wbGeometrys`", "expected `trajectorys`"],
        ),
        ("big.xml", &["big.xml", "larger than 16 MiB"]),
    ];
    for (file, must) in cases {
        let line = assert_refused(d, &["survey", file, "--out", "positions.csv"], must);
        assert!(!line.contains("TOPSECRET"), "{line}");
        assert_eq!(run_bounded(d, &["survey", file]).0.code(), Some(2));
    }
    let line = assert_refused(d, &["solve", "case.toml", "--out", "res"], &["xxe.xml: line 2"]);
    assert!(!line.contains("TOPSECRET"), "{line}");
    let r = run_in(d, &["survey", "good.xml", "--csv"]);
    assert!(r.success(), "{}", r.describe());
    assert_eq!(r.stdout.lines().count(), 4, "{}", r.stdout);
}

#[test]
fn a_whole_string_locked_up_answers_at_the_wob_it_delivers() {
    // 300 m of horizontal hole after a 6 deg/30 m build, slid with 114 kN asked for: about
    // twice what the string delivers (soft string 57 kN at hook load zero). The whole-string
    // solve finds no equilibrium at 114 kN; it answers with the whole string at the largest
    // WOB it delivers (its hook load zero), exit 0, the warning naming both WOBs
    // (tests/verification/slack_off.rs checks the mechanics).
    let (survey, text) = slid_horizontal(114.0);
    let dir = case_dir(&survey, &text);
    let r = run_in(dir.path(), &["solve", "case.toml", "--fidelity", "whole", "--json"]);
    assert!(r.success(), "{}", r.describe());
    let j: serde_json::Value = serde_json::from_str(&r.stdout).unwrap();
    let l = &j["lock_up"];
    let at = l["results_at_wob_kN"].as_f64().expect("results_at_wob_kN");
    assert!((l["wob_kN"].as_f64().unwrap() - 114.0).abs() < 1e-6);
    assert!(at > 40.0 && at < l["max_wob_kN"].as_f64().unwrap(), "{at}");
    assert!((j["bit"]["wob_kN"].as_f64().unwrap() - at).abs() < 1e-6, "{}", j["bit"]);
    let warning = j["warnings"][0].as_str().unwrap();
    assert!(
        warning.contains("lock-up") && warning.contains("largest WOB it delivers"),
        "{warning}"
    );
}
