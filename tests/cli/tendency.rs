//! `drillpath tendency` (docs/guide.md "Tendency charts"): the table against single solves,
//! the chart, and bad options.

use crate::common::{assert_error_names, root, run_in, run_ok};

/// Cells of `tendency.csv` by column name, per row.
fn rows(csv: &str) -> Vec<std::collections::HashMap<String, String>> {
    let mut lines = csv.lines();
    let head: Vec<&str> = lines.next().unwrap().split(',').collect();
    lines
        .map(|l| {
            head.iter()
                .map(|h| h.to_string())
                .zip(l.split(',').map(str::to_string))
                .collect()
        })
        .collect()
}

/// The table is right for one point: the capability row of `wells/horizontal/steered.toml`'s own
/// bend (1.5 deg), WOB (60 kN) and pad (8.375 in, 1/8 in under gauge) is `solve`'s motor yield, and the rotary row at the case's
/// inclination at the bit (92.5 deg) its rotating tendency (the same steady dogleg of the same
/// assembly; equal to the CSV's 4 decimals, 1e-4 deg/30 m). The chart has both panels and a
/// line per WOB; the RSS example sweeps ratios.
#[test]
fn the_table_matches_a_single_solve() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("t");
    let o = out.to_str().unwrap();
    let case = "wells/horizontal/steered.toml";
    run_ok(
        root(),
        &[
            "tendency", case, "--bends", "1,1.5", "--wobs", "60 kN", "--incs", "92.5", "--out", o,
        ],
    );
    let solve = run_ok(root(), &["solve", case, "--fidelity", "bha", "--json"]);
    let s: serde_json::Value = serde_json::from_str(&solve.stdout).unwrap();
    let csv = std::fs::read_to_string(out.join("tendency.csv")).unwrap();
    let r = rows(&csv);
    let cap = r
        .iter()
        .find(|r| r["sweep"] == "capability" && r["bend_deg"] == "1.500" && r["pad_under_gauge_in"] == "0.1250")
        .unwrap();
    assert_eq!(cap["pad_od_in"], "8.3750");
    // the default pads: full gauge, 1/16, 1/8, 1/4 in under gauge, each bend
    assert_eq!(r.iter().filter(|r| r["sweep"] == "capability").count(), 2 * 4, "{csv}");
    let y: f64 = cap["dogleg_deg_per_30m"].parse().unwrap();
    assert!(
        (y - s["motor_yield_deg_per_30m"].as_f64().unwrap()).abs() < 1e-4,
        "{csv}"
    );
    let rot = r.iter().find(|r| r["sweep"] == "rotary").unwrap();
    for (col, key) in [("build_deg_per_30m", "build"), ("right_deg_per_30m", "right")] {
        let v: f64 = rot[col].parse().unwrap();
        let want = s["rotating_tendency_deg_per_30m"][key].as_f64().unwrap();
        assert!((v - want).abs() < 1e-4, "{col}: {v} vs {want}");
    }
    let svg = std::fs::read_to_string(out.join("tendency.svg")).unwrap();
    assert!(svg.contains("Motor yield") && svg.contains("Rotary tendency") && svg.contains("WOB 60 kN"));
    let rss = run_ok(
        root(),
        &[
            "tendency",
            "wells/horizontal/rss.toml",
            "--ratios",
            "0,1",
            "--wobs",
            "60",
            "--incs",
            "90",
            "--out",
            o,
        ],
    );
    assert!(
        rss.stdout.contains("RSS dogleg capability at WOB 60 kN"),
        "{}",
        rss.stdout
    );
}

/// Bad options are one error naming the option (or the case), nothing written.
#[test]
fn bad_tendency_options_are_named() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("t");
    let o = out.to_str().unwrap();
    let cases: [(&str, &[&str], &[&str]); 9] = [
        (
            "wells/horizontal/steered.toml",
            &["--pads", "0,2"],
            &["--pads", "outside [0, 1.75]"],
        ),
        ("wells/horizontal/rss.toml", &["--pads", "0.125"], &["--pads", "RSS"]),
        (
            "wells/horizontal/steered.toml",
            &["--bends", "5"],
            &["--bends", "outside [0, 4]"],
        ),
        (
            "wells/horizontal/steered.toml",
            &["--ratios", "0.5"],
            &["--ratios", "bent motor"],
        ),
        ("wells/horizontal/rss.toml", &["--bends", "1"], &["--bends", "RSS"]),
        (
            "wells/horizontal/rss.toml",
            &["--ratios", "0,1.5"],
            &["--ratios", "outside [0, 1]"],
        ),
        (
            "wells/horizontal/steered.toml",
            &["--wobs", "-10 kN"],
            &["--wobs", "outside"],
        ),
        (
            "wells/horizontal/steered.toml",
            &["--incs", "30,,60"],
            &["--incs", "empty"],
        ),
        ("wells/horizontal/case.toml", &[], &["case.toml", "no bent housing"]),
    ];
    for (case, opts, names) in cases {
        let mut args = vec!["tendency", case, "--out", o];
        args.extend_from_slice(opts);
        let r = run_in(root(), &args);
        assert_error_names(&r, names);
        assert!(!out.exists(), "{case} {opts:?}: output written");
    }
}
