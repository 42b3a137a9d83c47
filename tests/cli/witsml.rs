//! WITSML trajectories and spreadsheets on the command line: a case whose survey is the real Volve F-5 WITSML
//! file gives the same positions and solve as the example case on the CSV extracted from it;
//! the azimuth reference is converted when the case asks; a trajectory is chosen by name.
//! The data files are in `../shared/data/` beside the repository (or beside a worktree's
//! folder); if absent the test prints a note and returns.

use std::path::{Path, PathBuf};

use crate::common::{assert_error_names, example_dir, run_in, run_ok};

/// A file of the shared data directory, if present.
fn shared(name: &str) -> Option<PathBuf> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let found = ["../shared/data", "../../shared/data"]
        .iter()
        .map(|d| root.join(d).join(name))
        .find(|p| p.is_file());
    if found.is_none() {
        println!("NOTE: {name} is absent from ../shared/data: test skipped");
    }
    found
}

/// A copy of the volve-f5 example case in a temporary directory, reading the WITSML file
/// instead of the CSV, with no `origin` (the tie-in position comes from the file) and `extra`
/// added to `[well]`.
fn f5_case(xml: &Path, extra: &str) -> tempfile::TempDir {
    let text = std::fs::read_to_string(example_dir("volve-f5").join("case.toml")).unwrap();
    let mut out = String::new();
    for line in text.lines() {
        if line.starts_with("survey = ") {
            out += &format!("survey = \"{}\"\n{extra}\n", xml.display());
        } else if !line.starts_with("origin = ") {
            out += line;
            out.push('\n');
        }
    }
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("case.toml"), out).unwrap();
    dir
}

#[test]
fn the_f5_witsml_case_equals_the_csv_case() {
    let Some(xml) = shared("volve-witsml/15_9-F-5_trajectory_slb.xml") else {
        return;
    };
    let dir = f5_case(&xml, "");
    let csv_case = example_dir("volve-f5").join("case.toml");
    let csv_case = csv_case.to_str().unwrap();
    let a = run_ok(".", &["survey", csv_case, "--csv"]);
    let b = run_ok(dir.path(), &["survey", "case.toml", "--csv"]);
    assert_eq!(
        a.stdout, b.stdout,
        "the same positions from the XML (tie-in from the file) and the CSV (origin in the case)"
    );
    let s = run_ok(dir.path(), &["survey", "case.toml"]);
    assert!(
        s.stdout.contains("azimuth reference: grid north (from element `aziRef` `grid north`; magDeclUsed -2.21 deg, gridCorUsed -0.95 deg)"),
        "{}",
        s.stdout
    );
    let a = run_ok(".", &["solve", csv_case, "--json"]);
    let b = run_ok(dir.path(), &["solve", "case.toml", "--json"]);
    let bit = |r: &str| {
        let j: serde_json::Value = serde_json::from_str(r).unwrap();
        (j["bit"].clone(), j["surface"].clone())
    };
    assert_eq!(bit(&a.stdout), bit(&b.stdout));
    // the prediction's WITSML carries the survey's north, declination and convergence
    run_ok(
        dir.path(),
        &[
            "predict",
            "case.toml",
            "--from",
            "1300",
            "--ahead",
            "10 m",
            "--witsml",
            "p.xml",
        ],
    );
    let back = drillpath::io::survey::read_survey(&dir.path().join("p.xml"), &Default::default()).unwrap();
    assert_eq!(back.azimuth_reference, drillpath::case::AzimuthReference::Grid);
    assert!((back.magnetic_declination_rad.unwrap().to_degrees() + 2.21).abs() < 1e-9);
    assert!((back.grid_convergence_rad.unwrap().to_degrees() + 0.95).abs() < 1e-9);
}

#[test]
fn the_case_converts_grid_to_true_north() {
    let Some(xml) = shared("volve-witsml/15_9-F-5_trajectory_slb.xml") else {
        return;
    };
    let grid = run_ok(".", &["survey", xml.to_str().unwrap(), "--csv"]);
    let dir = f5_case(&xml, "azimuth_reference = \"true\"");
    let r = run_ok(dir.path(), &["survey", "case.toml", "--csv"]);
    let azi = |text: &str| -> Vec<f64> {
        text.lines()
            .skip(1)
            .map(|l| l.split(',').nth(2).unwrap().parse().unwrap())
            .collect()
    };
    let (g, t) = (azi(&grid.stdout), azi(&r.stdout));
    // true = grid + gridCorUsed (-0.95 deg); the tie-in's azimuth 0 wraps to 359.05
    for (k, (g, t)) in g.iter().zip(&t).enumerate() {
        let d = (t - g + 540.0).rem_euclid(360.0) - 180.0;
        assert!((d + 0.95).abs() < 1.5e-4, "station {k}: grid {g}, true {t}");
    }
    let s = run_ok(dir.path(), &["survey", "case.toml"]);
    assert!(
        s.stdout
            .contains("azimuth reference: true north (from `[well] azimuth_reference`, converted from grid north"),
        "{}",
        s.stdout
    );
    assert!(
        s.stdout
            .contains("+ gridCorUsed -0.95 deg = -0.95 deg added to every azimuth"),
        "{}",
        s.stdout
    );
    let dir = f5_case(&xml, "azimuth_reference = \"east\"");
    let r = run_in(dir.path(), &["survey", "case.toml"]);
    assert_error_names(
        &r,
        &["case.toml: key `well.azimuth_reference`", "`east` is not a north"],
    );
}

#[test]
fn a_trajectory_is_chosen_by_name_and_f4_is_refused() {
    let Some(xml) = shared("volve-witsml/15_9-F-9A_2016_trajectory_bhi.xml") else {
        return;
    };
    let x = xml.to_str().unwrap();
    run_ok(".", &["survey", x, "--trajectory", "MWD-15/9-F-9 A"]);
    let r = run_in(".", &["survey", x, "--trajectory", "nope"]);
    assert_error_names(
        &r,
        &[
            "root element `trajectorys`",
            "no `trajectory` named or with uid `nope`",
            "`MWD-15/9-F-9 A` (uid `4VIRG33`)",
        ],
    );
    assert_eq!(r.code(), Some(2));
    let Some(f4) = shared("volve-witsml/15_9-F-4_2008_trajectory_slb.xml") else {
        return;
    };
    let r = run_in(".", &["survey", f4.to_str().unwrap()]);
    assert_error_names(
        &r,
        &[
            "line 17, element `azi` of station `S-0` (MD 0 m)",
            "67 of the 68 stations",
        ],
    );
    assert_eq!(r.code(), Some(2));
}

#[test]
fn a_spreadsheet_survey_on_the_command_line_and_in_a_case() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let csv = example_dir("j-shape").join("survey.csv");
    let text = std::fs::read_to_string(&csv).unwrap();
    let mut book = rust_xlsxwriter::Workbook::new();
    let sheet = book.add_worksheet().set_name("Survey").unwrap();
    for (r, line) in text.lines().filter(|l| !l.starts_with('#')).enumerate() {
        for (c, f) in line.split(',').enumerate() {
            match f.parse::<f64>() {
                Ok(v) => sheet.write_number(r as u32, c as u16, v).unwrap(),
                Err(_) => sheet.write_string(r as u32, c as u16, f).unwrap(),
            };
        }
    }
    book.save(d.join("s.xlsx")).unwrap();
    let a = run_ok(".", &["survey", csv.to_str().unwrap(), "--csv"]);
    let b = run_ok(d, &["survey", "s.xlsx", "--csv", "--sheet", "Survey"]);
    assert_eq!(a.stdout, b.stdout);
    let r = run_in(d, &["survey", "s.xlsx", "--sheet", "Other"]);
    assert_error_names(&r, &["s.xlsx: no sheet named `Other`", "`Survey`"]);
    let r = run_in(".", &["survey", csv.to_str().unwrap(), "--sheet", "Survey"]);
    assert_error_names(&r, &["option --sheet", "spreadsheet survey file only"]);
    let r = run_in(".", &["survey", csv.to_str().unwrap(), "--trajectory", "T"]);
    assert_error_names(&r, &["option --trajectory", "WITSML survey file only"]);
    let case = std::fs::read_to_string(example_dir("j-shape").join("case.toml")).unwrap();
    let survey_line = case.lines().find(|l| l.starts_with("survey = ")).unwrap();
    std::fs::write(
        d.join("case.toml"),
        case.replace(survey_line, "survey = \"s.xlsx\"\nsurvey_sheet = \"Survey\""),
    )
    .unwrap();
    let c = run_ok(d, &["survey", "case.toml", "--csv"]);
    assert_eq!(a.stdout, c.stdout);
    std::fs::write(
        d.join("case.toml"),
        case.replace(
            survey_line,
            &format!("survey = \"{}\"\nsurvey_sheet = \"Survey\"", csv.display()),
        ),
    )
    .unwrap();
    let r = run_in(d, &["survey", "case.toml"]);
    assert_error_names(&r, &["case.toml: key `well.survey_sheet`", "not a spreadsheet"]);
}

/// `(md, inc, azi)` of each row of a `trajectory.csv` as printed, and the same read back from
/// the WITSML file `xml` (tie-in then the predicted stations), deg and m.
fn printed_and_read_back(csv: &Path, xml: &Path) -> (Vec<[f64; 3]>, Vec<[f64; 3]>) {
    let text = std::fs::read_to_string(csv).unwrap();
    let printed: Vec<[f64; 3]> = text
        .lines()
        .skip(1)
        .map(|l| {
            let f: Vec<f64> = l.split(',').take(3).map(|x| x.parse().unwrap()).collect();
            [f[0], f[1], f[2]]
        })
        .collect();
    let file = drillpath::io::survey::read_survey(xml, &Default::default()).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(file.survey.len(), 1, "only the tie-in is a measurement");
    assert_eq!(file.station_info[0].kind, "tie in point");
    assert!(file.projected.iter().all(|(_, i)| i.kind == "N E and TVD"));
    let back = file
        .survey
        .stations()
        .iter()
        .chain(file.projected.iter().map(|(s, _)| s))
        .map(|s| [s.md_m, s.inc_rad.to_degrees(), s.azi_rad.to_degrees()])
        .collect();
    (printed, back)
}

fn same_to_printed_digits(printed: &[[f64; 3]], back: &[[f64; 3]]) {
    for (p, b) in printed.iter().zip(back) {
        assert!(
            (p[0] - b[0]).abs() < 1e-9 && (p[1] - b[1]).abs() < 1e-9,
            "{p:?} against {b:?}"
        );
        let d = (p[2] - b[2] + 540.0).rem_euclid(360.0) - 180.0;
        assert!(d.abs() < 1e-9, "{p:?} against {b:?}");
    }
}

#[test]
fn predict_and_backanalyze_write_witsml_that_reads_back_to_the_printed_stations() {
    let d = tempfile::tempdir().unwrap();
    let case = example_dir("seed-daqing").join("case.toml");
    let case = case.to_str().unwrap();
    run_ok(
        d.path(),
        &[
            "predict", case, "--from", "292", "--to", "413", "--out", "p", "--witsml", "p.xml",
        ],
    );
    let (printed, back) = printed_and_read_back(&d.path().join("p/trajectory.csv"), &d.path().join("p.xml"));
    let mut unique = printed.clone();
    unique.dedup_by(|a, b| a[0] == b[0]);
    assert_eq!(unique.len(), back.len());
    same_to_printed_digits(&unique, &back);
    let text = std::fs::read_to_string(d.path().join("p.xml")).unwrap();
    assert!(
        text.contains("<typeSurveyTool>drillpath prediction</typeSurveyTool><md uom=\"m\">293.000</md>"),
        "{text}"
    );

    run_ok(d.path(), &["backanalyze", case, "--out", "b", "--witsml", "b.xml"]);
    let (printed, back) = printed_and_read_back(&d.path().join("b/trajectory.csv"), &d.path().join("b.xml"));
    assert_eq!(
        printed.len() + 1,
        back.len(),
        "the tie-in, then one station per interval"
    );
    same_to_printed_digits(&printed, &back[1..]);

    // an output on an input is refused, and nothing is written
    let r = run_in(
        d.path(),
        &[
            "predict", case, "--from", "292", "--to", "300", "--witsml", case, "--out", "q",
        ],
    );
    assert_error_names(&r, &["option `--witsml`", "is an input of this run"]);
    assert!(!d.path().join("q").exists());
}
