//! The speed/accuracy trade (issue 5): every fidelity level and accuracy preset on the example
//! wells, errors against the converged `whole` + `precise` solve, time per solve; prediction
//! per 100 m by preset; cost against string length (1,000 / 3,000 / 10,000 m).
//!
//! ```text
//! cargo run --release --example tradeoff -- [OUT_DIR]        (default docs/tradeoff)
//! ```
//!
//! Writes `OUT_DIR/tradeoff.csv`, `OUT_DIR/prediction.csv`, `OUT_DIR/scaling.csv` and
//! `OUT_DIR/tradeoff.svg` (bit-force error against time, log-log, with the Pareto front).
//! Errors: bit build and walk force relative to the reference's lateral bit force
//! `sqrt(F_b^2 + F_w^2)`, tilt relative to the reference tilt magnitude, hook load and surface
//! torque relative to the reference values; all in percent. Times: median of repeated solves
//! (at least 0.3 s of repeats, at most 15), wall clock, one thread.

use drillpath::case::accuracy::Accuracy;
use drillpath::case::{choose, Case, Fidelity, Level, Purpose};
use drillpath::io::case_toml::{load_case, CaseOverrides};
use drillpath::models::fem::solve::SolveControls;
use drillpath::models::levels::{run, LevelResult};
use drillpath::predict::march::{predict, MarchSettings};
use drillpath::report::write_atomic;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::time::Instant;

const WELLS: [&str; 6] = [
    "seed-daqing",
    "s-shape",
    "forge-16a",
    "j-shape",
    "horizontal",
    "volve-f10",
];
const LEVELS: [Fidelity; 4] = [
    Fidelity::Level(Level::Soft),
    Fidelity::Level(Level::Bha),
    Fidelity::Level(Level::Hybrid),
    Fidelity::Level(Level::Whole),
];

fn with_preset(case: &Case, p: Accuracy) -> Case {
    let mut c = case.clone();
    c.solver.apply_preset(p);
    c.bit_rock.step_m = p.knobs().step_m;
    c
}

/// Median time of repeated runs and the last result.
fn timed(case: &Case, level: Fidelity) -> (f64, LevelResult) {
    let mut times = Vec::new();
    let mut total = 0.0;
    loop {
        let t0 = Instant::now();
        let r = run(
            case,
            choose(level, Purpose::Solve),
            &SolveControls::from_settings(&case.solver),
        )
        .expect("solve failed");
        let dt = t0.elapsed().as_secs_f64();
        times.push(dt);
        total += dt;
        if total > 0.3 || times.len() >= 15 {
            times.sort_by(f64::total_cmp);
            return (times[times.len() / 2], r);
        }
    }
}

fn pct(x: f64, reference: f64) -> f64 {
    100.0 * x / reference.abs().max(1e-12)
}

struct Point {
    level: &'static str,
    preset: &'static str,
    seconds: f64,
    bit_err: f64,
}

fn main() {
    let out: PathBuf = std::env::args()
        .nth(1)
        .map(PathBuf::from)
        .unwrap_or("docs/tradeoff".into());
    let mut table = String::from("well,fidelity,accuracy,dofs,seconds_per_solve,converged,build_force_err_pct,walk_force_err_pct,tilt_err_pct,hook_load_err_pct,surface_torque_err_pct\n");
    let mut points: Vec<Point> = Vec::new();
    for well in WELLS {
        let base = load_case(
            &Path::new("wells").join(well).join("case.toml"),
            &CaseOverrides::default(),
        )
        .expect("example case");
        let reference_case = with_preset(&base, Accuracy::Precise);
        let (_, reference) = timed(&reference_case, Fidelity::Level(Level::Whole));
        assert!(reference.converged, "{well}: reference did not converge");
        let rb = reference.bit.unwrap();
        let lateral = rb.build_force_n.hypot(rb.walk_force_n);
        let tilt = rb.tilt_inc_rad.hypot(rb.tilt_azi_rad);
        for preset in Accuracy::ALL {
            let case = with_preset(&base, preset);
            for level in LEVELS {
                let (sec, r) = timed(&case, level);
                let cell = |v: Option<f64>| v.map(|x| format!("{x:.5}")).unwrap_or_default();
                let (eb, ew, et) = match r.bit {
                    Some(b) => (
                        Some(pct(b.build_force_n - rb.build_force_n, lateral)),
                        Some(pct(b.walk_force_n - rb.walk_force_n, lateral)),
                        Some(pct(
                            (b.tilt_inc_rad - rb.tilt_inc_rad).hypot(b.tilt_azi_rad - rb.tilt_azi_rad),
                            tilt,
                        )),
                    ),
                    None => (None, None, None),
                };
                let eh = r
                    .hook_load_n
                    .map(|h| pct(h - reference.hook_load_n.unwrap(), reference.hook_load_n.unwrap()));
                let eq = r.surface_torque_nm.map(|t| {
                    pct(
                        t - reference.surface_torque_nm.unwrap(),
                        reference.surface_torque_nm.unwrap(),
                    )
                });
                let dofs = r.fem.as_ref().map(|f| f.model.dofs()).unwrap_or(0);
                let name = level.name();
                writeln!(
                    table,
                    "{well},{name},{},{dofs},{sec:.6},{},{},{},{},{},{}",
                    preset.name(),
                    r.converged,
                    cell(eb),
                    cell(ew),
                    cell(et),
                    cell(eh),
                    cell(eq)
                )
                .unwrap();
                if let (Some(b), Some(w)) = (eb, ew) {
                    points.push(Point {
                        level: name,
                        preset: preset.name(),
                        seconds: sec,
                        bit_err: b.abs().max(w.abs()),
                    });
                }
                eprintln!("{well:<12} {:<8} {name:<7} {sec:9.5} s", preset.name());
            }
        }
    }
    let prediction = prediction_table();
    let scaling = scaling_table();
    let svg = plot(&points);
    for (name, text) in [
        ("tradeoff.csv", &table),
        ("prediction.csv", &prediction),
        ("scaling.csv", &scaling),
        ("tradeoff.svg", &svg),
    ] {
        write_atomic(&out.join(name), text.as_bytes()).expect("write");
    }
    eprintln!(
        "wrote {}/tradeoff.csv, prediction.csv, scaling.csv, tradeoff.svg",
        out.display()
    );
}

/// Prediction of 100 m from the case's bit depth with the `bha` model (the predictor's model)
/// at each preset: inclination and azimuth after 100 m, and their error against the `precise`
/// prediction.
fn prediction_table() -> String {
    let mut t = String::from("well,accuracy,step_m,seconds_per_100m,inc_end_deg,azi_end_deg,inc_err_deg,azi_err_deg\n");
    for well in [
        "seed-daqing",
        "j-shape",
        "horizontal",
        "s-shape",
        "volve-f10",
        "forge-16a",
    ] {
        let base = load_case(
            &Path::new("wells").join(well).join("case.toml"),
            &CaseOverrides::default(),
        )
        .unwrap();
        let from = base.operation.bit_md_m.min(base.well.path.md_end());
        let mut results = Vec::new();
        for preset in Accuracy::ALL {
            let case = with_preset(&base, preset);
            let settings = MarchSettings::from_case(&case);
            let t0 = Instant::now();
            let p = predict(&case, from, from + 100.0, &settings, &mut |_| {});
            let sec = t0.elapsed().as_secs_f64();
            if let Err(e) = &p {
                eprintln!("predict {well} {}: {e}", preset.name());
            }
            results.push((preset, sec, p.ok().map(|p| *p.steps.last().unwrap())));
        }
        let reference = results[2].2;
        for (preset, sec, end) in &results {
            let (inc, azi) = match end {
                Some(e) => (
                    format!("{:.4}", e.inc_rad.to_degrees()),
                    format!("{:.4}", e.azi_rad.to_degrees()),
                ),
                None => ("failed".into(), "failed".into()),
            };
            let (ei, ea) = match (end, reference) {
                (Some(e), Some(r)) => (
                    format!("{:.5}", (e.inc_rad - r.inc_rad).to_degrees()),
                    format!(
                        "{:.5}",
                        drillpath::geometry::survey::wrap_pi(e.azi_rad - r.azi_rad).to_degrees()
                    ),
                ),
                (None, _) => ("failed".into(), "failed".into()),
                (_, None) => ("no reference".into(), "no reference".into()),
            };
            writeln!(
                t,
                "{well},{},{},{sec:.4},{inc},{azi},{ei},{ea}",
                preset.name(),
                preset.knobs().step_m
            )
            .unwrap();
            eprintln!("predict {well:<12} {:<8} {sec:.3} s / 100 m", preset.name());
        }
    }
    t
}

/// Synthetic build-and-hold well to 10,000 m (vertical to 500 m, 3 deg/30 m to 60 deg), the
/// standard BHA and 5 in pipe, bit at `bit_md` m.
fn synthetic(dir: &Path, bit_md: f64) -> Case {
    let mut s = String::from("md_m,inc_deg,azi_deg\n0,0,30\n500,0,30\n");
    for k in 1..=60 {
        s.push_str(&format!("{},{},30\n", 500.0 + 10.0 * k as f64, k as f64));
    }
    s.push_str("10000,60,30\n");
    std::fs::write(dir.join("survey.csv"), s).unwrap();
    let toml = format!(
        r#"
[well]
survey = "survey.csv"
hole = [{{ to_md = "10000 m", diameter = "8.5 in" }}]
[mud]
density = "1.2 sg"
[operation]
mode = "drilling"
bit_md = "{bit_md} m"
wob = "100 kN"
rpm = 60
rop = "12 m/h"
friction = 0.25
[[string]]
type = "bit"
od = "8.5 in"
length = "0.3 m"
[[string]]
type = "stabilizer"
od = "8.4375 in"
body_od = "6.5 in"
id = "2.8125 in"
length = "1.5 m"
[[string]]
type = "collar"
od = "6.5 in"
id = "2.8125 in"
length = "54 m"
[[string]]
type = "pipe"
od = "5 in"
id = "4.276 in"
weight = "29 kg/m"
tool_joint_od = "6.625 in"
"#
    );
    std::fs::write(dir.join("case.toml"), toml).unwrap();
    load_case(&dir.join("case.toml"), &CaseOverrides::default()).unwrap()
}

/// Cost against string length at the default preset, plus the 3,000 m acceptance pair
/// (`bha` default against `whole` precise).
fn scaling_table() -> String {
    let dir = tempfile_dir();
    let mut t = String::from("string_m,fidelity,accuracy,seconds_per_solve,dofs,bit_force_err_vs_whole_precise_pct\n");
    for md in [1000.0, 3000.0, 10000.0] {
        let case = synthetic(&dir, md);
        let precise = with_preset(&case, Accuracy::Precise);
        let (_, reference) = timed(&precise, Fidelity::Level(Level::Whole));
        let rb = reference.bit.unwrap();
        let lateral = rb.build_force_n.hypot(rb.walk_force_n);
        for (level, preset) in [
            (Fidelity::Level(Level::Soft), Accuracy::Default),
            (Fidelity::Level(Level::Bha), Accuracy::Default),
            (Fidelity::Level(Level::Hybrid), Accuracy::Default),
            (Fidelity::Level(Level::Whole), Accuracy::Default),
            (Fidelity::Level(Level::Whole), Accuracy::Precise),
        ] {
            let c = with_preset(&case, preset);
            let (sec, r) = timed(&c, level);
            let err = r
                .bit
                .map(|b| {
                    format!(
                        "{:.5}",
                        pct(
                            (b.build_force_n - rb.build_force_n).hypot(b.walk_force_n - rb.walk_force_n),
                            lateral
                        )
                    )
                })
                .unwrap_or_default();
            let name = level.name();
            writeln!(
                t,
                "{md},{name},{},{sec:.6},{},{err}",
                preset.name(),
                r.fem.as_ref().map(|f| f.model.dofs()).unwrap_or(0)
            )
            .unwrap();
            eprintln!("scaling {md:>6} m {name:<7} {:<8} {sec:.5} s", preset.name());
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
    t
}

fn tempfile_dir() -> PathBuf {
    let d = std::env::temp_dir().join(format!("drillpath-tradeoff-{}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// Log-log scatter of the largest bit-force error against time per solve, one colour per
/// level, one marker size per preset, with the Pareto front (no other point both faster and
/// more accurate) joined by a line.
fn plot(points: &[Point]) -> String {
    let (w, h, m) = (720.0, 480.0, 70.0);
    let floor = 1e-4;
    let lx = |s: f64| s.max(1e-5).log10();
    let ly = |e: f64| e.max(floor).log10();
    let (x0, x1) = (
        points
            .iter()
            .map(|p| lx(p.seconds))
            .fold(f64::INFINITY, f64::min)
            .floor(),
        points
            .iter()
            .map(|p| lx(p.seconds))
            .fold(f64::NEG_INFINITY, f64::max)
            .ceil(),
    );
    let (y0, y1) = (
        ly(floor),
        points.iter().map(|p| ly(p.bit_err)).fold(0.0, f64::max).ceil().max(1.0),
    );
    let px = |s: f64| m + (lx(s) - x0) / (x1 - x0).max(1e-9) * (w - 2.0 * m);
    let py = |e: f64| h - m - (ly(e) - y0) / (y1 - y0).max(1e-9) * (h - 2.0 * m);
    let colour = |l: &str| match l {
        "bha" => "#1f77b4",
        "hybrid" => "#2ca02c",
        "whole" => "#d62728",
        _ => "#7f7f7f",
    };
    let size = |p: &str| match p {
        "fast" => 3.0,
        "default" => 5.0,
        _ => 7.0,
    };
    let mut s = format!("<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{w}\" height=\"{h}\" font-family=\"sans-serif\" font-size=\"12\">\n<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n");
    for d in (x0 as i32)..=(x1 as i32) {
        let x = px(10f64.powi(d));
        let _ = writeln!(s, "<line x1=\"{x}\" y1=\"{}\" x2=\"{x}\" y2=\"{}\" stroke=\"#ddd\"/><text x=\"{x}\" y=\"{}\" text-anchor=\"middle\">1e{d} s</text>", m, h - m, h - m + 16.0);
    }
    for d in (y0 as i32)..=(y1 as i32) {
        let y = py(10f64.powi(d));
        let _ = writeln!(s, "<line x1=\"{m}\" y1=\"{y}\" x2=\"{}\" y2=\"{y}\" stroke=\"#ddd\"/><text x=\"{}\" y=\"{}\" text-anchor=\"end\">1e{d} %</text>", w - m, m - 6.0, y + 4.0);
    }
    let _ = writeln!(
        s,
        "<text x=\"{}\" y=\"{}\" text-anchor=\"middle\">time per solve (median), all example wells</text>",
        w / 2.0,
        h - 20.0
    );
    let _ = writeln!(s, "<text x=\"16\" y=\"{}\" transform=\"rotate(-90 16 {})\" text-anchor=\"middle\">largest bit build/walk force error, % of lateral bit force (floor 1e-4)</text>", h / 2.0, h / 2.0);
    for p in points {
        let _ = writeln!(
            s,
            "<circle cx=\"{:.1}\" cy=\"{:.1}\" r=\"{}\" fill=\"{}\" fill-opacity=\"0.7\"><title>{} {} {:.4} s {:.4}%</title></circle>",
            px(p.seconds),
            py(p.bit_err),
            size(p.preset),
            colour(p.level),
            p.level,
            p.preset,
            p.seconds,
            p.bit_err
        );
    }
    let mut sorted: Vec<&Point> = points.iter().collect();
    sorted.sort_by(|a, b| a.seconds.total_cmp(&b.seconds));
    let mut front = Vec::new();
    let mut best = f64::INFINITY;
    for p in sorted {
        if p.bit_err.max(floor) < best {
            best = p.bit_err.max(floor);
            front.push(format!("{:.1},{:.1}", px(p.seconds), py(p.bit_err)));
        }
    }
    let _ = writeln!(
        s,
        "<polyline points=\"{}\" fill=\"none\" stroke=\"black\" stroke-dasharray=\"4 3\"/>",
        front.join(" ")
    );
    for (i, (l, c)) in [("bha", "#1f77b4"), ("hybrid", "#2ca02c"), ("whole", "#d62728")]
        .iter()
        .enumerate()
    {
        let y = m + 16.0 * i as f64;
        let _ = writeln!(
            s,
            "<circle cx=\"{}\" cy=\"{y}\" r=\"5\" fill=\"{c}\"/><text x=\"{}\" y=\"{}\">{l}</text>",
            w - m - 90.0,
            w - m - 80.0,
            y + 4.0
        );
    }
    let _ = writeln!(
        s,
        "<text x=\"{}\" y=\"{}\">size: fast / default / precise; dashed: Pareto front</text>",
        w - m - 330.0,
        m + 52.0
    );
    s.push_str("</svg>\n");
    s
}
