//! Command-line handling of `drillpath loads`: bad options and bad measured files exit non-zero
//! with one `error:` line naming the option or the file, line and column, and leave no output
//! file; a good run writes `loads.csv` with the interface's columns first.

use std::path::Path;
use std::sync::LazyLock;
use tempfile::TempDir;

use crate::common::{assert_error_names, case_dir, collar, run_in, slid_bit_on_pipe, Run, DRILL_PIPE};

const SURVEY: &str = "md_m,inc_deg,azi_deg\n0,0,0\n300,0,0\n600,20,45\n1000,30,45\n";

/// 60 m of 6.5 in collars and the 5 in drill pipe, grade S-135, drilling at 50 kN.
static CASE: LazyLock<String> = LazyLock::new(|| {
    format!(
        r#"name = "loads cli test"
[well]
survey = "survey.csv"
hole = [
  {{ to_md = "500 m", diameter = "12.25 in", friction = 0.2 }},
  {{ to_md = "1000 m", diameter = "8.5 in" }},
]
[mud]
density = "1.2 sg"
[operation]
mode = "drilling"
wob = "50 kN"
rpm = 60
friction = 0.3
{}{DRILL_PIPE}grade = "S-135"
"#,
        collar("60 m")
    )
});

fn setup() -> TempDir {
    case_dir(SURVEY, &CASE)
}

/// `drillpath loads case.toml args` in `dir`.
fn run(dir: &Path, args: &[&str]) -> Run {
    run_in(dir, &[&["loads", "case.toml"], args].concat())
}

/// Exit code 2, exactly one stderr line starting `error:` containing every `needles` item, no
/// panic ([`assert_error_names`]), and no `out/` directory content.
fn assert_error(dir: &Path, out: &Run, needles: &[&str]) {
    assert_eq!(out.code(), Some(2), "stderr: {}", out.stderr);
    assert_error_names(out, needles);
    assert!(!dir.join("out/loads.csv").exists(), "partial output left behind");
    assert!(!dir.join("out/calibration.csv").exists(), "partial output left behind");
}

#[test]
fn good_run_writes_interface_columns() {
    let dir = setup();
    let out = run(dir.path(), &["--every", "100 m", "--out", "out"]);
    assert!(out.success(), "{}", out.stderr);
    let csv = std::fs::read_to_string(dir.path().join("out/loads.csv")).unwrap();
    let header = csv.lines().next().unwrap();
    assert!(header.starts_with("bit_md_m,mode,hook_load_kN,surface_torque_kNm,max_contact_force_kN,buckled_length_m,"));
    // 10 depths (100 ... 1000 m) x 5 load cases
    assert_eq!(csv.lines().count(), 1 + 10 * 5);
    assert!(!csv.contains("NaN") && !csv.contains("inf"));
    // yield limits present (grade given): 5 in 19.5 lb/ft S-135 body 3167.4 kN
    let last = csv.lines().last().unwrap();
    assert!(last.contains(",3167."), "{last}");
}

#[test]
fn bad_options_name_the_option() {
    let dir = setup();
    let out = run(dir.path(), &["--every", "0", "--out", "out"]);
    assert_error(dir.path(), &out, &["--every", "positive"]);
    let out = run(dir.path(), &["--to", "1500 m", "--out", "out"]);
    assert_error(dir.path(), &out, &["--to", "below the surveyed hole"]);
    let out = run(dir.path(), &["--to", "12 furlongs", "--out", "out"]);
    assert_error(dir.path(), &out, &["--to", "furlongs"]);
    let out = run(dir.path(), &["--from", "900", "--to", "800", "--out", "out"]);
    assert_error(dir.path(), &out, &["--to", "above --from"]);
    let out = run(dir.path(), &["--wob", "20 m", "--out", "out"]);
    assert_error(dir.path(), &out, &["--wob"]);
}

#[test]
fn bad_measured_files_name_file_line_and_column() {
    let dir = setup();
    let cases: [(&str, &[&str]); 5] = [
        (
            "bit_md_m,mode,hook_load_kN\n500,trip_in,100\n600,trip_out,abc\n",
            &["measured.csv", "line 3", "hook_load_kN", "not a number"],
        ),
        (
            "bit_md_m,mode,hook_load_kN\n500,trip_in,100\n600,backwards,120\n",
            &["measured.csv", "line 3", "mode", "unknown load case"],
        ),
        (
            "# rig log\nbit_md_m,mode,hook_load_kN\n1500,trip_in,100\n",
            &["measured.csv", "line 3", "bit_md_m", "outside the surveyed hole"],
        ),
        (
            "bit_md_m,mode\n500,trip_in\n",
            &["measured.csv", "line 1", "no hook load"],
        ),
        (
            "bit_md_m,mode,hook_load_kN\n500,trip_in,-5\n",
            &["measured.csv", "line 2", "hook_load_kN", "positive"],
        ),
    ];
    for (text, needles) in cases {
        std::fs::write(dir.path().join("measured.csv"), text).unwrap();
        let out = run(dir.path(), &["--measured", "measured.csv", "--out", "out"]);
        assert_error(dir.path(), &out, needles);
    }
    let out = run(dir.path(), &["--measured", "missing.csv", "--out", "out"]);
    assert_error(dir.path(), &out, &["missing.csv", "cannot read"]);
}

#[test]
fn unconstrained_calibration_is_an_error_not_a_number() {
    // rotating-off-bottom hook loads without torque do not depend on friction
    let dir = setup();
    std::fs::write(
        dir.path().join("measured.csv"),
        "bit_md_m,mode,hook_load_kN\n800,rotating_off_bottom,150\n900,rotating_off_bottom,160\n",
    )
    .unwrap();
    let out = run(dir.path(), &["--measured", "measured.csv", "--out", "out"]);
    assert_error(dir.path(), &out, &["measured.csv", "nothing to fit"]);
}

#[test]
fn calibration_writes_overlay() {
    let dir = setup();
    std::fs::write(
        dir.path().join("measured.csv"),
        "Bit depth [m],Load case,Hook load [kN],Torque [kN.m]\n\
         700,trip_out,200,\n800,trip_out,225,\n900,trip_out,250,\n1000,trip_out,270,\n\
         700,trip_in,160,\n800,trip_in,170,\n900,trip_in,180,\n1000,trip_in,190,\n\
         1000,rotating_off_bottom,225,4\n",
    )
    .unwrap();
    let out = run(
        dir.path(),
        &["--measured", "measured.csv", "--every", "100", "--out", "out"],
    );
    assert!(out.success(), "{}", out.stderr);
    let overlay = std::fs::read_to_string(dir.path().join("out/calibration.csv")).unwrap();
    assert_eq!(overlay.lines().count(), 10);
    assert!(overlay.starts_with("line,bit_md_m,mode,measured_hook_load_kN"));
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.path().join("out/calibration.json")).unwrap()).unwrap();
    assert_eq!(json["sections"].as_array().unwrap().len(), 2);
    assert!(dir.path().join("out/loads.csv").exists());
}

#[test]
fn fidelity_options_are_checked_and_reported() {
    let dir = setup();
    // bha has no surface values: refused, naming the option; --stiff is --fidelity whole
    let out = run(dir.path(), &["--fidelity", "bha", "--out", "out"]);
    assert_error(dir.path(), &out, &["--fidelity", "bha", "hook load"]);
    let out = run(dir.path(), &["--stiff", "--fidelity", "soft", "--out", "out"]);
    assert_error(dir.path(), &out, &["--stiff", "--fidelity soft"]);
    let out = run(dir.path(), &["--fidelity", "stiffest", "--out", "out"]);
    assert_error(dir.path(), &out, &["--fidelity", "stiffest"]);
    let out = run(dir.path(), &["--accuracy", "sloppy", "--out", "out"]);
    assert_error(dir.path(), &out, &["--accuracy", "sloppy"]);
    // [solver] fidelity = "bha" in the case: the error names the file and the key
    let bha = format!("{}[solver]\nfidelity = \"bha\"\n", *CASE);
    std::fs::write(dir.path().join("case.toml"), &bha).unwrap();
    let out = run(dir.path(), &["--out", "out"]);
    assert_error(dir.path(), &out, &["case.toml", "solver.fidelity", "bha"]);
    // ... and --fidelity overrides it: hybrid rows carry stiff_model = hybrid
    let out = run(
        dir.path(),
        &[
            "--fidelity",
            "hybrid",
            "--from",
            "900 m",
            "--every",
            "100 m",
            "--out",
            "out",
        ],
    );
    assert!(out.success(), "{}", out.stderr);
    let stdout = &out.stdout;
    assert!(stdout.contains("fidelity hybrid: requested"), "{stdout}");
    let csv = std::fs::read_to_string(dir.path().join("out/loads.csv")).unwrap();
    assert!(csv.lines().next().unwrap().ends_with(
        ",stiff_model,stiff_lock_up_wob_kN,stiff_unbuckled_helical_m,stiff_whirl_m,helical_drag_hook_load_kN,stiff_buckled_start,helical_drag_diverges,stiff_coarse_for_pitch_m"
    ));
    assert_eq!(
        csv.lines()
            .filter(|l| l.ends_with(",converged,") || l.contains(",converged,"))
            .count(),
        2 * 5
    );
    assert!(csv.lines().skip(1).all(|l| l.contains(",hybrid,,0.0,0.0,")), "{csv}");
    // [solver] fidelity = "whole" in the case runs the whole string; auto runs soft and says why
    let whole = format!("{}[solver]\nfidelity = \"whole\"\n", *CASE);
    std::fs::write(dir.path().join("case.toml"), &whole).unwrap();
    let out = run(
        dir.path(),
        &[
            "--from",
            "900 m",
            "--every",
            "100 m",
            "--accuracy",
            "fast",
            "--out",
            "out",
        ],
    );
    assert!(out.success(), "{}", out.stderr);
    let csv = std::fs::read_to_string(dir.path().join("out/loads.csv")).unwrap();
    assert!(csv.lines().skip(1).all(|l| l.contains(",whole,,0.0,0.0,")), "{csv}");
    // stdout prints a second table with the stiff values: its last line (1,000 m) shows the
    // stiff trip-out hook load of loads.csv (reference: the CSV, to the printed 0.1 kN), which
    // differs from the soft one printed in the first table
    let stdout = &out.stdout;
    let tables: Vec<&str> = stdout
        .lines()
        .filter(|l| l.trim_start().starts_with("1000.0 |"))
        .collect();
    assert_eq!(tables.len(), 2, "{stdout}");
    let trip_out = |line: &str| -> f64 {
        line.split('|')
            .nth(1)
            .unwrap()
            .split_whitespace()
            .nth(1)
            .unwrap()
            .parse()
            .unwrap()
    };
    let column = |row: &str, name: &str| -> f64 {
        let header: Vec<&str> = csv.lines().next().unwrap().split(',').collect();
        let k = header.iter().position(|h| *h == name).unwrap();
        row.split(',').nth(k).unwrap().parse().unwrap()
    };
    let row = csv.lines().find(|l| l.starts_with("1000.00,trip_out,")).unwrap();
    assert!(
        (trip_out(tables[1]) - column(row, "stiff_hook_load_kN")).abs() <= 0.051,
        "{stdout}"
    );
    assert!(
        (trip_out(tables[0]) - column(row, "hook_load_kN")).abs() <= 0.051,
        "{stdout}"
    );
    assert!((trip_out(tables[0]) - trip_out(tables[1])).abs() > 0.2, "{stdout}");
    let out = run(dir.path(), &["--fidelity", "auto", "--out", "out"]);
    let stdout = &out.stdout;
    assert!(stdout.contains("fidelity soft: auto:"), "{stdout}");
    let csv = std::fs::read_to_string(dir.path().join("out/loads.csv")).unwrap();
    // the eight stiff_* columns (16th to 23rd) empty
    assert!(
        csv.lines()
            .skip(1)
            .all(|l| l.split(',').skip(15).take(8).all(str::is_empty)),
        "soft only: empty stiff columns"
    );
}

/// A vertical 2,000 m hole, 5 in pipe body sliding with 300 kN on the bit at friction 0.35: the
/// plain soft string delivers it (hook load about 180 kN) while the compression of the soft
/// string with the helix's drag diverges about 1,800 m above the bit (the closed form's `coth`,
/// tests/verification/helical_drag.rs). The sliding row flags it (`helical_drag_diverges` true,
/// `helical_drag_hook_load_kN` below -10,000) and stdout names it in a `WARNING` line; the
/// drilling row (rotation turns most of the friction round the pipe, and its helix's drag stays
/// finite) and the rows off bottom (the pipe hangs in tension) do not.
#[test]
fn diverging_helix_drag_is_flagged_not_given_as_a_load() {
    let survey = "md_m,inc_deg,azi_deg\n0,0,0\n2000,0,0\n";
    let case = format!(
        "[well]\nsurvey = \"survey.csv\"\nhole = [{{ to_md = \"2000 m\", diameter = \"8.5 in\" }}]\n{}",
        slid_bit_on_pipe(2000.0, 300.0, 0.35)
    );
    let dir = case_dir(survey, &case);
    let out = run(dir.path(), &["--from", "2000 m", "--out", "out"]);
    assert!(out.success(), "{}", out.stderr);
    assert!(
        out.stdout.contains("WARNING: the helix's drag diverges: in 1 rows") && out.stdout.contains("2000 m sliding"),
        "{}",
        out.stdout
    );
    let csv = std::fs::read_to_string(dir.path().join("out/loads.csv")).unwrap();
    let header: Vec<&str> = csv.lines().next().unwrap().split(',').collect();
    let col = |name: &str| header.iter().position(|h| *h == name).unwrap();
    let (mode, hook, helical, diverges) = (
        col("mode"),
        col("hook_load_kN"),
        col("helical_drag_hook_load_kN"),
        col("helical_drag_diverges"),
    );
    let rows: Vec<Vec<&str>> = csv.lines().skip(1).map(|l| l.split(',').collect()).collect();
    assert_eq!(rows.len(), 5, "{csv}");
    for r in &rows {
        let sliding = r[mode] == "sliding";
        assert_eq!(r[diverges], sliding.to_string(), "{csv}");
        let value: f64 = r[helical].parse().unwrap();
        assert_eq!(value < -10_000.0, sliding, "{csv}");
        if sliding {
            assert!(r[hook].parse::<f64>().unwrap() > 0.0, "{csv}");
        }
    }
}
