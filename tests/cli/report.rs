//! HTML reports (`--report`), `drillpath init` and `--units`, through the built binary.
//!
//! Every report must be one self-contained HTML file whose inline SVG figures are well-formed XML
//! (parsed with roxmltree), hold the expected named series (legend text) with drawn data, and
//! never show NaN or infinity. Reference for the unit test: exact definitions (1 lbf =
//! 4.4482216152605 N, 1 ft = 0.3048 m) against the SI summary.json of the same solve.

use std::path::Path;
use tempfile::TempDir;

use crate::common::{example_case, root, run_in, run_ok, Run};

/// `drillpath args` in `dir`; it must succeed.
fn run(args: &[&str], dir: &Path) -> Run {
    run_ok(dir, args)
}

/// (figure id, svg text) of every `<figure id="..">` of the report.
fn figures(html: &str) -> Vec<(String, String)> {
    let mut out = Vec::new();
    let mut rest = html;
    while let Some(i) = rest.find("<figure id=\"") {
        rest = &rest[i + 12..];
        let id = rest[..rest.find('"').expect("id ends")].to_string();
        let a = rest.find("<svg").expect("figure has an svg");
        let b = rest.find("</svg>").expect("svg ends") + 6;
        out.push((id, rest[a..b].to_string()));
        rest = &rest[b..];
    }
    out
}

/// Parse `svg`; return its text contents (legend names, labels) and the number of drawn data
/// elements (polylines and circles).
fn parse_svg(id: &str, svg: &str) -> (Vec<String>, usize) {
    let doc = roxmltree::Document::parse(svg).unwrap_or_else(|e| panic!("figure {id}: SVG is not well-formed: {e}"));
    assert_eq!(doc.root_element().tag_name().name(), "svg", "figure {id}");
    let texts = doc
        .descendants()
        .filter(|n| n.has_tag_name("text"))
        .filter_map(|n| n.text().map(|t| t.trim().to_string()))
        .collect();
    let drawn = doc
        .descendants()
        .filter(|n| n.has_tag_name("polyline") || n.has_tag_name("circle") || n.has_tag_name("rect"))
        .count();
    (texts, drawn)
}

/// Check a report: well-formed figures with `expected` (figure id, series names), no NaN/inf.
fn check_report(html: &str, expected: &[(&str, &[&str])]) {
    assert!(html.starts_with("<!DOCTYPE html>") && html.trim_end().ends_with("</html>"));
    for bad in ["NaN", ">inf", " inf ", "-inf", "http://", "https://"] {
        // the SVG namespace URI is the one allowed address (no fetch: it is an identifier)
        let n = html.matches(bad).count()
            - html.matches("http://www.w3.org/2000/svg").count() * (bad == "http://") as usize;
        assert_eq!(n, 0, "report contains `{bad}`");
    }
    assert!(!html.contains("<script") && !html.contains("<link") && !html.contains("<img"));
    let figs = figures(html);
    for (id, series) in expected {
        let (_, svg) = figs
            .iter()
            .find(|(f, _)| f == id)
            .unwrap_or_else(|| panic!("no figure `{id}`"));
        let (texts, drawn) = parse_svg(id, svg);
        assert!(drawn > 3, "figure {id}: nothing drawn");
        for s in *series {
            assert!(
                texts.iter().any(|t| t == s),
                "figure {id}: no series `{s}` in {texts:?}"
            );
        }
    }
    for (id, svg) in &figs {
        parse_svg(id, svg);
    }
}

const SOLVE_SERIES: &[(&str, &[&str])] = &[
    ("bha-schematic", &["hole wall"]),
    ("contact-force", &["contact force"]),
    (
        "deflection-high",
        &["string axis", "wall (+ radial clearance)", "wall (- radial clearance)"],
    ),
    (
        "deflection-right",
        &["string axis", "wall (+ radial clearance)", "wall (- radial clearance)"],
    ),
    ("axial-force", &["axial force"]),
    ("torque", &["torque"]),
    ("bending-stress", &["bending stress", "von Mises"]),
];

const PREDICT_SERIES: &[(&str, &[&str])] = &[
    ("inclination", &["predicted", "measured"]),
    ("azimuth", &["predicted", "measured"]),
    ("plan-view", &["predicted", "measured"]),
    ("vertical-section", &["predicted", "measured"]),
    ("bit-forces", &["build force", "walk force"]),
    ("bit-tilt", &["tilt inclination", "tilt azimuth"]),
    ("errors", &["inclination error", "azimuth error"]),
];

#[test]
fn solve_report_for_every_example_well() {
    let tmp = TempDir::new().unwrap();
    let mut n = 0;
    for e in std::fs::read_dir(root().join("wells")).unwrap() {
        let case = e.unwrap().path().join("case.toml");
        if !case.exists() {
            continue;
        }
        let name = case
            .parent()
            .unwrap()
            .file_name()
            .unwrap()
            .to_string_lossy()
            .to_string();
        let report = tmp.path().join(format!("{name}.html"));
        run(
            &["solve", case.to_str().unwrap(), "--report", report.to_str().unwrap()],
            tmp.path(),
        );
        let html = std::fs::read_to_string(&report).unwrap();
        check_report(&html, SOLVE_SERIES);
        assert_eq!(
            figures(&html).len(),
            drillpath::report::solve_report::SOLVE_FIGURES.len(),
            "{name}"
        );
        n += 1;
    }
    assert!(n >= 6, "only {n} example wells found");
}

#[test]
fn oilfield_units_in_the_solve_report_match_the_si_summary() {
    let tmp = TempDir::new().unwrap();
    let case = example_case("j-shape");
    let out = run(
        &[
            "solve",
            case.to_str().unwrap(),
            "--bit-md",
            "1500 m",
            "--json",
            "--report",
            "r.html",
            "--units",
            "oilfield",
        ],
        tmp.path(),
    );
    let summary: serde_json::Value = serde_json::from_str(&out.stdout).unwrap();
    let html = std::fs::read_to_string(tmp.path().join("r.html")).unwrap();
    check_report(&html, SOLVE_SERIES);
    let value = |key: &str, unit: &str| -> f64 {
        let i = html
            .find(&format!("<th>{key}</th>"))
            .unwrap_or_else(|| panic!("no `{key}` row"));
        let cell = &html[i..];
        let a = cell.find("<td class=\"n\">").unwrap() + 14;
        let b = cell[a..]
            .find(&format!(" {unit}</td>"))
            .unwrap_or_else(|| panic!("`{key}` not in {unit}"));
        cell[a..a + b].parse().unwrap()
    };
    let lbf = 4.448_221_615_260_5;
    // hook load shown with 1 decimal in klbf, bit MD with 2 decimals in ft
    let hook_kn = summary["surface"]["hook_load_kN"].as_f64().unwrap();
    assert!((value("hook load", "klbf") * lbf - hook_kn).abs() < 0.05 * lbf + 1e-9);
    assert!((value("bit MD", "ft") * 0.3048 - 1500.0).abs() < 0.005 * 0.3048 + 1e-9);
    assert!(html.contains("MD [ft]") && html.contains("[klbf]") && html.contains("[ksi]"));
    assert!(!html.contains("[kN]") && !html.contains("MD [m]"));
}

/// Buckling on the axial-force plot: the j-shape BHA at 300 m (vertical hole, 120 kN WOB) is
/// buckled over about 100 m by the summary's own marks (sinusoidal and helical): both zones are
/// in the legend with the onset curves; at 1500 m nothing is buckled and no zone is drawn or
/// listed.
#[test]
fn axial_force_plot_shows_buckled_zones_only_when_buckled() {
    let tmp = TempDir::new().unwrap();
    let case = example_case("j-shape");
    for md in ["300 m", "1500 m"] {
        let out = run(
            &[
                "solve",
                case.to_str().unwrap(),
                "--bit-md",
                md,
                "--json",
                "--report",
                "r.html",
            ],
            tmp.path(),
        );
        let s: serde_json::Value = serde_json::from_str(&out.stdout).unwrap();
        let sin = s["buckling"]["sinusoidal_length_m"].as_f64().unwrap();
        let hel = s["buckling"]["helical_length_m"].as_f64().unwrap();
        if md == "300 m" {
            assert!(sin > 50.0 && hel > 0.0, "the test case must buckle: {sin} m, {hel} m");
        } else {
            assert!(sin == 0.0 && hel == 0.0, "the test case must not buckle");
        }
        let html = std::fs::read_to_string(tmp.path().join("r.html")).unwrap();
        check_report(&html, SOLVE_SERIES);
        let (_, svg) = figures(&html).into_iter().find(|(id, _)| id == "axial-force").unwrap();
        let (texts, _) = parse_svg("axial-force", &svg);
        let has = |name: &str| texts.iter().any(|t| t == name);
        assert_eq!(has("sinusoidal buckling"), sin > 0.0, "{md}: {texts:?}");
        assert_eq!(has("helical buckling"), hel > 0.0, "{md}: {texts:?}");
        if hel > 0.0 {
            assert!(has("sinusoidal onset") && has("helical onset"), "{md}: {texts:?}");
        }
    }
}

#[test]
fn predict_and_backanalyze_reports_on_the_seed_well() {
    let tmp = TempDir::new().unwrap();
    let case = example_case("seed-daqing");
    let c = case.to_str().unwrap();
    run(
        &[
            "predict", c, "--from", "292", "--to", "413", "--step", "5m", "--report", "p.html",
        ],
        tmp.path(),
    );
    check_report(
        &std::fs::read_to_string(tmp.path().join("p.html")).unwrap(),
        PREDICT_SERIES,
    );
    run(&["backanalyze", c, "--step", "5m", "--report", "b.html"], tmp.path());
    let mut back = PREDICT_SERIES.to_vec();
    for e in back.iter_mut().take(4) {
        e.1 = &["predicted (interval ends)", "measured"];
    }
    let html = std::fs::read_to_string(tmp.path().join("b.html")).unwrap();
    check_report(&html, &back);
}

#[test]
fn init_writes_a_case_that_solve_and_predict_run_on() {
    let tmp = TempDir::new().unwrap();
    run(&["init", "new/case.toml"], tmp.path());
    let dir = tmp.path().join("new");
    assert!(dir.join("case.toml").exists() && dir.join("survey.csv").exists());
    let text = std::fs::read_to_string(dir.join("case.toml")).unwrap();
    for table in ["[well]", "[mud]", "[operation]", "[[string]]", "[bit_rock]", "[solver]"] {
        assert!(text.contains(table), "starter case lacks {table}");
    }
    let out = run(&["solve", "case.toml", "--json", "--report", "r.html"], &dir);
    let s: serde_json::Value = serde_json::from_str(&out.stdout).unwrap();
    assert_eq!(s["solver"]["converged"], true);
    assert!((s["bit"]["md_m"].as_f64().unwrap() - 1000.0).abs() < 1e-9);
    check_report(&std::fs::read_to_string(dir.join("r.html")).unwrap(), SOLVE_SERIES);
    let out = run(
        &["predict", "case.toml", "--ahead", "30m", "--step", "3m", "--json"],
        &dir,
    );
    let p: serde_json::Value = serde_json::from_str(&out.stdout).unwrap();
    assert!((p["end"]["md_m"].as_f64().unwrap() - 1030.0).abs() < 1e-6);
    // a second init refuses to overwrite
    let again = run_in(tmp.path(), &["init", "new/case.toml"]);
    assert!(!again.success());
    assert!(again.stderr.contains("exists"));
}

#[test]
fn unwritable_report_is_one_error_and_no_file() {
    let tmp = TempDir::new().unwrap();
    std::fs::write(tmp.path().join("blocker"), "a file, not a directory").unwrap();
    let case = example_case("seed-daqing");
    let out = run_in(
        tmp.path(),
        &["solve", case.to_str().unwrap(), "--report", "blocker/r.html"],
    );
    assert_eq!(out.code(), Some(2));
    let err = &out.stderr;
    assert!(err.starts_with("error: ") && err.contains("blocker/r.html"), "{err}");
    assert!(!err.contains("panicked"));
}

/// Every option of every subcommand names its default in `--help` (clap's `[default: ..]` or one
/// written in the help text), and every subcommand's help shows an example.
#[test]
fn every_option_lists_its_default_and_every_command_an_example() {
    use clap::CommandFactory;
    let mut cli = drillpath::cli::args::Cli::command();
    cli.build();
    let mut missing = Vec::new();
    for sub in cli.get_subcommands() {
        let about = sub
            .get_long_about()
            .or(sub.get_about())
            .map(|s| s.to_string())
            .unwrap_or_default();
        if sub.get_name() != "help" && !about.contains("Example: drillpath") {
            missing.push(format!("{}: no example", sub.get_name()));
        }
        for arg in sub.get_arguments() {
            if arg.is_positional() || ["help", "version"].contains(&arg.get_id().as_str()) {
                continue;
            }
            let help = arg.get_help().map(|s| s.to_string()).unwrap_or_default();
            if arg.get_default_values().is_empty() && !help.contains("[default: ") {
                missing.push(format!("{} --{}", sub.get_name(), arg.get_id()));
            }
        }
    }
    assert!(missing.is_empty(), "options without a default in --help: {missing:?}");
}
