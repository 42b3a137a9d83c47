//! `drillpath solve` through the built binary at each fidelity level and accuracy preset: the
//! interface files it writes, the options that override the case, and the errors for unknown
//! names. The levels' numbers against each other are checked in tests/verification/fidelity.rs.

use crate::common::{
    assert_error_names, case_dir, collar_properties, example_dir, root, run_in, try_load_temp_case, BIT,
    COLLAR_TO_SURFACE,
};

#[test]
fn fidelity_cli_levels_write_the_interface_files() {
    // Reference: docs/guide.md `solve` outputs: summary.json keys (null where the level does not
    // compute a value), string.csv header + buckling columns, no NaN; `--fidelity` overrides
    // the case; an unknown level is one clear error naming the option, non-zero exit.
    let case = "wells/seed-daqing/case.toml";
    for level in ["soft", "bha", "hybrid", "whole"] {
        let dir = tempfile::tempdir().unwrap();
        let out = run_in(
            root(),
            &[
                "solve",
                case,
                "--fidelity",
                level,
                "--out",
                dir.path().to_str().unwrap(),
            ],
        );
        assert!(out.success(), "{level}: {}", out.stderr);
        let stdout = &out.stdout;
        assert!(stdout.contains(&format!("fidelity {level}")), "{stdout}");
        let s: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(dir.path().join("summary.json")).unwrap()).unwrap();
        assert_eq!(s["fidelity"]["used"], level);
        assert!(s["buckling"]["sinusoidal_length_m"].is_number());
        for key in [
            "md_m",
            "wob_kN",
            "build_force_kN",
            "walk_force_kN",
            "tilt_inc_deg",
            "tilt_azi_deg",
            "torque_kNm",
        ] {
            let v = &s["bit"][key];
            assert!(
                v.is_number() || (level == "soft" && v.is_null()),
                "{level} bit.{key} = {v}"
            );
        }
        for key in ["hook_load_kN", "torque_kNm"] {
            let v = &s["surface"][key];
            assert!(
                v.is_number() || (level == "bha" && v.is_null()),
                "{level} surface.{key} = {v}"
            );
        }
        assert!(s["solver"]["converged"].as_bool().unwrap());
        let csv = std::fs::read_to_string(dir.path().join("string.csv")).unwrap();
        let mut lines = csv.lines();
        let header = lines.next().unwrap();
        assert!(header.starts_with("md_m,north_m,east_m,tvd_m,disp_high_mm,disp_right_mm,clearance_mm,contact_force_kN,contact_angle_deg,axial_force_kN,torque_kNm,bending_moment_kNm,von_mises_MPa,"));
        assert!(header.ends_with(
            ",sinusoidal_onset_kN,helical_onset_kN,buckling,tilt_high_deg,tilt_right_deg,helical_wall_force_N_per_m"
        ));
        let n = header.split(',').count();
        let mut rows = 0;
        for l in lines {
            assert_eq!(l.split(',').count(), n, "{level}: {l}");
            assert!(!l.to_lowercase().contains("nan") && !l.contains("inf"), "{level}: {l}");
            rows += 1;
        }
        assert!(rows > 10, "{level}: {rows} rows");
    }
    let out = run_in(root(), &["solve", case, "--fidelity", "fast"]);
    assert!(!out.success());
    let err = &out.stderr;
    assert!(
        err.contains("--fidelity") && err.contains("fast") && !err.contains("panicked"),
        "{err}"
    );
}

#[test]
fn accuracy_preset_in_case_file_and_on_the_command_line() {
    // Reference: the preset table of src/case/accuracy.rs; explicit keys win over `[solver]
    // accuracy`; `--accuracy` wins over the case; unknown names are one clear error.
    use drillpath::case::accuracy::Accuracy;
    let src = example_dir("seed-daqing");
    let text: String = std::fs::read_to_string(src.join("case.toml"))
        .unwrap()
        .lines()
        .filter(|l| {
            !l.starts_with("element_length") && !l.starts_with("bha_element_length") && !l.starts_with("tolerance")
        })
        .map(|l| format!("{l}\n"))
        .collect();
    let survey = std::fs::read_to_string(src.join("survey.csv")).unwrap();
    let write = |solver: &str| {
        let t = text.replace("[solver]\n", &format!("[solver]\n{solver}\n"));
        try_load_temp_case(&survey, &t)
    };
    let precise = write("accuracy = \"precise\"").unwrap();
    let k = Accuracy::Precise.knobs();
    assert_eq!(precise.solver.element_length_m, k.element_length_m);
    assert_eq!(precise.solver.bha_element_length_m, k.bha_element_length_m);
    assert_eq!(precise.solver.tolerance, k.tolerance);
    let explicit = write("accuracy = \"precise\"\nelement_length = \"2 m\"").unwrap();
    assert_eq!(explicit.solver.element_length_m, 2.0);
    assert_eq!(explicit.solver.tolerance, k.tolerance);
    let err = write("accuracy = \"medium\"").unwrap_err().to_string();
    assert!(
        err.contains("accuracy") && err.contains("medium") && err.contains("case.toml"),
        "{err}"
    );
    let out = run_in(
        root(),
        &["solve", "wells/seed-daqing/case.toml", "--accuracy", "fast", "--json"],
    );
    assert!(out.success());
    let s: serde_json::Value = serde_json::from_str(&out.stdout).unwrap();
    let fast_elements = s["solver"]["elements"].as_u64().unwrap();
    let out = run_in(root(), &["solve", "wells/seed-daqing/case.toml", "--json"]);
    let s: serde_json::Value = serde_json::from_str(&out.stdout).unwrap();
    assert!(fast_elements < s["solver"]["elements"].as_u64().unwrap());
}

#[test]
fn string_csv_clearance_is_empty_without_a_gap_element() {
    // Reference: the mesh's gap elements (docs/guide.md, outputs of `solve`): every stiff node
    // has one except the bit face, the bit's body above it and the top node of the whole
    // string, held on the hole axis; their `clearance_mm` cell is empty (not 0), the
    // others give the radial clearance (>= 0). seed-daqing at `whole`: exactly the first and
    // the last row empty (its bit, 0.3 m long, has no node inside).
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path().to_str().unwrap();
    let case = "wells/seed-daqing/case.toml";
    let out = run_in(root(), &["solve", case, "--fidelity", "whole", "--out", d, "-q"]);
    assert!(out.success(), "{}", out.describe());
    let csv = std::fs::read_to_string(dir.path().join("string.csv")).unwrap();
    let mut lines = csv.lines();
    let col = lines
        .next()
        .unwrap()
        .split(',')
        .position(|h| h == "clearance_mm")
        .unwrap();
    let cells: Vec<String> = lines.map(|l| l.split(',').nth(col).unwrap().to_string()).collect();
    let empty: Vec<usize> = (0..cells.len()).filter(|&i| cells[i].is_empty()).collect();
    assert_eq!(empty, vec![0, cells.len() - 1], "rows with an empty clearance");
    for c in &cells[1..cells.len() - 1] {
        assert!(c.parse::<f64>().unwrap() >= 0.0, "{c}");
    }
}

/// An `mwd` component with `sensor_to_bit`: `solve` reports the sag angle at the sensor
/// (`sensors` in summary.json, a stdout line) and `predict` adds `sensor_sag_deg` to
/// trajectory.csv. Reference: the mwd has the collars' section, so the string is a slick
/// collar in a horizontal hole, where the constant-compression pendulum is exact: the sag at
/// 4 m is its slope there (analytical::pendulum), within 1%. A sensor off its component and a
/// sensor on another type are refused with the key.
#[test]
fn a_survey_sensor_reports_its_sag() {
    use drillpath::analytical::pendulum::{constant_compression, constant_compression_slope};
    let survey = "md_m,inc_deg,azi_deg\n0,0,0\n500,90,0\n800,90,0\n";
    let case = |sensor: &str, kind: &str| {
        format!(
            r#"[well]
survey = "survey.csv"
hole = [{{ to_md = "800 m", diameter = "8.5 in" }}]
[mud]
density = "1.2 sg"
[operation]
mode = "drilling"
wob = "50 kN"
rpm = 60
rop = "10 m/h"
friction = 0.0
{BIT}[[string]]
type = "{kind}"
name = "MWD"
od = "6.5 in"
id = "2.8125 in"
length = "9 m"
{sensor}
{COLLAR_TO_SURFACE}length = "80 m"
{COLLAR_TO_SURFACE}[solver]
bha_element_length = "0.25 m"
"#
        )
    };
    let dir = case_dir(survey, &case("sensor_to_bit = \"4.3 m\"", "mwd"));
    let out = run_in(dir.path(), &["solve", "case.toml", "--fidelity", "bha", "--json"]);
    assert!(out.success(), "{}", out.describe());
    let s: serde_json::Value = serde_json::from_str(&out.stdout).unwrap();
    let sensor = &s["sensors"][0];
    assert_eq!(sensor["component"], "MWD");
    let (ei, w_b, r) = collar_properties();
    let reference = constant_compression(ei, w_b, r, 50e3).unwrap();
    let slope = constant_compression_slope(ei, w_b, 50e3, &reference, 4.3).unwrap();
    let sag = sensor["sag_deg"].as_f64().unwrap().to_radians();
    assert!(
        ((sag - slope) / slope).abs() < 0.01,
        "sag {sag} rad against {slope} rad"
    );
    let text = run_in(dir.path(), &["solve", "case.toml", "--fidelity", "bha"]);
    assert!(
        text.stdout.contains("sensor of `MWD` at 4.30 m from the bit"),
        "{}",
        text.stdout
    );
    let p = run_in(
        dir.path(),
        &[
            "predict",
            "case.toml",
            "--from",
            "780 m",
            "--ahead",
            "4 m",
            "--step",
            "2 m",
            "--out",
            "p",
        ],
    );
    assert!(p.success(), "{}", p.describe());
    let csv = std::fs::read_to_string(dir.path().join("p/trajectory.csv")).unwrap();
    assert!(csv.lines().next().unwrap().ends_with(",sensor_sag_deg"), "{csv}");
    for (k, t) in [
        ("sensor_to_bit = \"20 m\"", "mwd"),
        ("sensor_to_bit = \"4 m\"", "collar"),
    ] {
        let bad = case_dir(survey, &case(k, t));
        let r = run_in(bad.path(), &["solve", "case.toml"]);
        assert_error_names(&r, &["string[1].sensor_to_bit"]);
    }
}

/// A bent motor's outputs (docs/guide.md "Bent motors", "Outputs of solve"): the example
/// `wells/horizontal/steered.toml` at `bha` prints the `bent motor:` line and writes the motor
/// yield in the published range for a 1.5 deg bend (8-18 deg/30 m), the rotating tendency
/// (build and right, below a quarter of the yield) and the `steering` key; the straight
/// `case.toml` writes them `null`.
#[test]
fn a_bent_motor_reports_its_yield_and_rotating_tendency() {
    let json = |file: &str| -> serde_json::Value {
        let out = run_in(root(), &["solve", file, "--fidelity", "bha", "--json"]);
        assert!(out.success(), "{file}: {}", out.stderr);
        serde_json::from_str(&out.stdout).unwrap()
    };
    let bent = json("wells/horizontal/steered.toml");
    let y = bent["motor_yield_deg_per_30m"].as_f64().unwrap();
    assert!((8.0..=18.0).contains(&y), "{y}");
    let rot = &bent["rotating_tendency_deg_per_30m"];
    let (b, r) = (rot["build"].as_f64().unwrap(), rot["right"].as_f64().unwrap());
    assert!(b.hypot(r) < 0.25 * y, "{b} {r} against {y}");
    assert_eq!(bent["steering"]["toolface_reference"], "gravity");
    assert_eq!(bent["steering"]["rotating_toolfaces"], 12);
    assert!(bent["steering"]["not_computed"].is_null());
    let straight = json("wells/horizontal/case.toml");
    for key in ["motor_yield_deg_per_30m", "rotating_tendency_deg_per_30m", "steering"] {
        assert!(straight[key].is_null(), "{key}");
    }
    let text = run_in(root(), &["solve", "wells/horizontal/steered.toml", "--fidelity", "bha"]);
    assert!(
        text.stdout
            .contains("bent motor: 1.50 deg at 2.00 m from the bit, toolface 0.0 deg (gravity); motor yield sliding"),
        "{}",
        text.stdout
    );
}

/// A rotary steerable system's outputs (docs/guide.md "Rotary steerable systems", "Outputs of
/// solve"): `wells/horizontal/rss.toml` at `bha` prints the `rss (push-the-bit)` line and writes
/// `rss_dogleg_deg_per_30m` (equal to the rates' magnitude) and the `rss` key; the straight
/// `case.toml` writes them `null`, and the RSS case's motor keys are `null`.
#[test]
fn an_rss_reports_its_dogleg() {
    let json = |file: &str| -> serde_json::Value {
        let out = run_in(root(), &["solve", file, "--fidelity", "bha", "--json"]);
        assert!(out.success(), "{file}: {}", out.stderr);
        serde_json::from_str(&out.stdout).unwrap()
    };
    let rss = json("wells/horizontal/rss.toml");
    let d = rss["rss_dogleg_deg_per_30m"].as_f64().unwrap();
    let rate = &rss["rss"]["rate_deg_per_30m"];
    let (b, r) = (rate["build"].as_f64().unwrap(), rate["right"].as_f64().unwrap());
    assert!((b.hypot(r) - d).abs() < 1e-9, "{d} {b} {r}");
    assert_eq!(rss["rss"]["rss_type"], "push-the-bit");
    assert_eq!(rss["rss"]["pad_force_kN"], 15.0);
    assert_eq!(rss["rss"]["ratio"], 0.15);
    assert!(rss["rss"]["deflection_angle_deg"].is_null() && rss["motor_yield_deg_per_30m"].is_null());
    let straight = json("wells/horizontal/case.toml");
    for key in ["rss_dogleg_deg_per_30m", "rss"] {
        assert!(straight[key].is_null(), "{key}");
    }
    let text = run_in(root(), &["solve", "wells/horizontal/rss.toml", "--fidelity", "bha"]);
    assert!(
        text.stdout
            .contains("rss (push-the-bit): pad force 15.0 kN at 0.90 m from the bit, ratio 0.15, toolface 0.0 deg (gravity); dogleg rotating"),
        "{}",
        text.stdout
    );
}

#[test]
fn whole_and_hybrid_solves_show_the_soft_string_beside_them() {
    // Reference: the soft string run on its own (`--fidelity soft`, an independent run of the
    // soft level) gives the hook load and surface torque that `soft_string_comparison` shows
    // beside the whole and hybrid solves (the same WOB: the case's), to 1e-9 relative; the
    // differences are the stiff values minus those (1e-9 kN); the key is null for `bha` and
    // `soft`, whose surface values are not a stiff solve's.
    let json = |fidelity: &str| -> serde_json::Value {
        let out = run_in(
            root(),
            &["solve", "wells/seed-daqing/case.toml", "--fidelity", fidelity, "--json"],
        );
        assert!(out.success(), "{}", out.stderr);
        serde_json::from_str(&out.stdout).unwrap()
    };
    let soft = json("soft");
    let f = |v: &serde_json::Value| v.as_f64().unwrap();
    let close = |a: f64, b: f64| (a - b).abs() <= 1e-9 * b.abs().max(1.0);
    for fidelity in ["whole", "hybrid"] {
        let s = json(fidelity);
        let c = &s["soft_string_comparison"];
        assert!(
            close(f(&c["hook_load_kN"]), f(&soft["surface"]["hook_load_kN"])),
            "{fidelity}: {c}"
        );
        assert!(
            close(f(&c["surface_torque_kNm"]), f(&soft["surface"]["torque_kNm"])),
            "{fidelity}: {c}"
        );
        assert!(close(f(&c["wob_kN"]), f(&s["bit"]["wob_kN"])), "{fidelity}: {c}");
        let dh = f(&s["surface"]["hook_load_kN"]) - f(&c["hook_load_kN"]);
        assert!((f(&c["hook_load_difference_kN"]) - dh).abs() < 1e-9, "{fidelity}: {c}");
        let dt = f(&s["surface"]["torque_kNm"]) - f(&c["surface_torque_kNm"]);
        assert!(
            (f(&c["surface_torque_difference_kNm"]) - dt).abs() < 1e-9,
            "{fidelity}: {c}"
        );
        assert_eq!(
            f(&c["helical_wall_force_kN"]),
            0.0,
            "{fidelity}: no helix on this well: {c}"
        );
    }
    assert!(json("bha")["soft_string_comparison"].is_null());
    assert!(soft["soft_string_comparison"].is_null());
}

/// The motor's reactive torque in `solve`'s outputs (docs/guide.md "Bent motors", "Reactive
/// torque"): `wells/horizontal/steered.toml` sliding with `reactive_torque = true` and a 6 kN.m
/// motor torque turns the toolface left: `reactive_toolface_turn_deg` > 0, the effective toolface
/// the set one less it (mod 360, to the JSON's round-off), the torque the given one, and the
/// `bent motor:` line says so; without the option (the example as it is) the keys are `null`.
#[test]
fn the_reactive_torque_turns_the_toolface_in_solve() {
    let dir = tempfile::tempdir().unwrap();
    for f in ["survey.csv", "slides.csv"] {
        std::fs::copy(root().join("wells/horizontal").join(f), dir.path().join(f)).unwrap();
    }
    let case = std::fs::read_to_string(root().join("wells/horizontal/steered.toml"))
        .unwrap()
        .replace(
            "mode = \"drilling\"",
            "mode = \"sliding\"\nreactive_torque = true\nbit_torque = \"6 kN.m\"\ntoolface = \"30 deg\"",
        );
    std::fs::write(dir.path().join("case.toml"), case).unwrap();
    let out = run_in(dir.path(), &["solve", "case.toml", "--fidelity", "bha", "--json"]);
    assert!(out.success(), "{}", out.stderr);
    let j: serde_json::Value = serde_json::from_str(&out.stdout).unwrap();
    let st = &j["steering"];
    let turn = st["reactive_toolface_turn_deg"].as_f64().unwrap();
    let eff = st["effective_toolface_deg"].as_f64().unwrap();
    assert!(turn > 0.0, "{st}");
    assert!(((30.0 - turn).rem_euclid(360.0) - eff).abs() < 1e-9, "{st}");
    assert!((st["reactive_torque_kNm"].as_f64().unwrap() - 6.0).abs() < 1e-9);
    let text = run_in(dir.path(), &["solve", "case.toml", "--fidelity", "bha"]);
    assert!(
        text.stdout.contains("left by the motor's reactive torque 6.00 kN.m"),
        "{}",
        text.stdout
    );
    let off = run_in(
        root(),
        &["solve", "wells/horizontal/steered.toml", "--fidelity", "bha", "--json"],
    );
    let j: serde_json::Value = serde_json::from_str(&off.stdout).unwrap();
    for key in [
        "reactive_toolface_turn_deg",
        "effective_toolface_deg",
        "reactive_torque_kNm",
    ] {
        assert!(j["steering"][key].is_null(), "{key}");
    }
}

/// A whole-string solve that finds no equilibrium where the string cannot be put on bottom at any
/// WOB answers with the soft string and exit 0 (the library's answer is checked in
/// tests/verification/lock_up_depth.rs): `fidelity.used` soft, `lock_up.results_from_soft_string`,
/// `summary.json` and `string.csv` written without NaN, and the report asked for not written
/// (nothing stiff to draw) with a note on stderr. The case: vertical to 300 m, a 90 deg build of
/// radius 100 m, a lateral to 1,500 m slid at 30 kN with friction 0.5 below 460 m (locked up at
/// zero WOB from about 1,260 m); the whole solve is made to fail by an iteration limit of 2.
#[test]
fn whole_locked_at_zero_wob_answers_with_the_soft_string() {
    let dir = tempfile::tempdir().unwrap();
    let build_end = 300.0 + 100.0 * std::f64::consts::FRAC_PI_2;
    let survey = format!("md_m,inc_deg,azi_deg\n0,0,0\n300,0,0\n{build_end},90,0\n1500,90,0\n");
    std::fs::write(dir.path().join("survey.csv"), survey).unwrap();
    let case = format!(
        "[well]\nsurvey = \"survey.csv\"\nhole = [{{ to_md = \"460 m\", diameter = \"8.5 in\", friction = 0 }}, {{ to_md = \"1500 m\", diameter = \"8.5 in\" }}]\n[solver]\nmax_iterations = 2\n{}",
        crate::common::slid_bit_on_pipe(1500.0, 30.0, 0.5)
    );
    std::fs::write(dir.path().join("case.toml"), case).unwrap();
    let out = run_in(
        dir.path(),
        &[
            "solve",
            "case.toml",
            "--fidelity",
            "whole",
            "--out",
            "out",
            "--report",
            "r.html",
        ],
    );
    assert!(out.success(), "{}", out.describe());
    assert!(out.stderr.contains("r.html not written"), "{}", out.describe());
    assert!(!dir.path().join("r.html").exists());
    let s: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.path().join("out/summary.json")).unwrap()).unwrap();
    assert_eq!(
        (s["fidelity"]["requested"].as_str(), s["fidelity"]["used"].as_str()),
        (Some("whole"), Some("soft"))
    );
    assert_eq!(s["lock_up"]["results_from_soft_string"], true);
    assert_eq!(s["lock_up"]["max_wob_kN"], 0.0);
    assert!(s["surface"]["hook_load_kN"].as_f64().unwrap() < 0.0);
    let csv = std::fs::read_to_string(dir.path().join("out/string.csv")).unwrap();
    assert!(csv.lines().count() > 10 && !csv.to_lowercase().contains("nan"));
}
