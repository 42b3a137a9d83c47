//! Solve timings (issues 3 and 5): converged `solve` at the default mesh of
//! - a BHA-only model (~100 m: bit, near-bit stabilizer, collars, string stabilizer, collars,
//!   42 m of HWDP; its top node is the top of the model) at 3,000 m in the 3,000 m well, cold
//!   and warm-started from the previous solution after a 5% WOB change;
//! - the trajectory predictor's own BHA model of wells/j-shape at its bit depth
//!   (`fem::bha::bha_model` at the default cut, 84.8 m, the top node held on the wall:
//!   `TopCondition::Cut`), cold and warm-started the predictor's way (the state solved with
//!   the bit 1 m shallower, carried over by `warm::transport_state`), which is what the
//!   predictor does for every solve of a step;
//! - 1,000, 3,000 and 10,000 m strings (the cost against length) and an 8,000 m string (the
//!   same BHA, 140 m HWDP, 5 in drill pipe to surface) in generated build-and-hold wells
//!   (vertical to 600 m, 2.5 deg/30 m to 35 deg, or 60 deg for 8,000 m, hold to TD;
//!   12.25 in casing to 1,000 m, or to half the depth when that is shallower, 8.5 in open
//!   hole), rotating on bottom;
//! - two example wells (seed-daqing 727 m, s-shape 1,650 m);
//! - one soft-string pass (`softstring::from_case`) over the 3,000 m string.
//!
//! Before timing, each case prints one line `case: DOF, Newton iterations, factorizations`.
//! Run: `cargo bench --bench solve -- --warm-up-time 1 --measurement-time 10` (a filter such
//! as `string_3000m` after `--` times one case; the set-up solves of all cases still run).

use criterion::{criterion_group, criterion_main, Criterion};
use drillpath::case::Case;
use drillpath::io::case_toml::{load_case, CaseOverrides};
use drillpath::models::fem::bha::{bha_model, default_cut_m};
use drillpath::models::fem::model::{Model, TopCondition};
use drillpath::models::fem::refine;
use drillpath::models::fem::solve::{solve, solve_interior_point_from, SolveControls};
use drillpath::models::fem::warm::transport_state;
use drillpath::models::softstring;
use std::fmt::Write;
use std::path::Path;

/// Survey CSV of a build-and-hold well: vertical to 600 m, 2.5 deg/30 m at azimuth 45 deg to
/// `hold_deg`, hold to `td_m`; stations every 30 m.
fn build_and_hold_survey(td_m: f64, hold_deg: f64) -> String {
    let mut s = String::from("md_m,inc_deg,azi_deg\n");
    let mut md: f64 = 0.0;
    while md < td_m + 1e-9 {
        let inc = ((md - 600.0).max(0.0) * 2.5 / 30.0).min(hold_deg);
        writeln!(s, "{md},{inc},45").unwrap();
        md += 30.0;
    }
    if (md - 30.0 - td_m).abs() > 1e-9 {
        writeln!(s, "{td_m},{hold_deg},45").unwrap();
    }
    s
}

/// The 8.5 in rotary BHA (~100 m with 42 m of HWDP when `hwdp_m` = 42).
fn bha(hwdp_m: f64) -> String {
    format!(
        r#"
[[string]]
type = "bit"
od = "8.5 in"
length = "0.3 m"
[[string]]
type = "stabilizer"
od = "8.5 in"
body_od = "6.5 in"
id = "2.8125 in"
length = "1.6 m"
[[string]]
type = "collar"
od = "6.5 in"
id = "2.8125 in"
length = "27.6 m"
[[string]]
type = "stabilizer"
od = "8.4375 in"
body_od = "6.5 in"
id = "2.8125 in"
length = "1.6 m"
[[string]]
type = "collar"
od = "6.5 in"
id = "2.8125 in"
length = "27.6 m"
[[string]]
type = "hwdp"
od = "5 in"
id = "3 in"
length = "{hwdp_m} m"
weight = "49.3 lb/ft"
tool_joint_od = "6.5 in"
joint_length = "30 ft"
"#
    )
}

const DRILL_PIPE: &str = r#"
[[string]]
type = "pipe"
od = "5 in"
id = "4.276 in"
weight = "33.6 kg/m"
tool_joint_od = "6.625 in"
joint_length = "30 ft"
"#;

/// A generated case: `td_m` bit depth, `hold_deg` hold inclination, the string table; casing
/// to 1,000 m (to `td_m / 2` when shallower).
fn generated_case(td_m: f64, hold_deg: f64, strings: &str) -> Case {
    let shoe_m = 1000.0f64.min(0.5 * td_m);
    let case = format!(
        r#"
[well]
survey = "survey.csv"
hole = [
  {{ to_md = "{shoe_m} m", diameter = "12.25 in", friction = 0.2 }},
  {{ to_md = "{td_m} m", diameter = "8.5 in" }},
]
[mud]
density = "1.2 sg"
plastic_viscosity = "20 cP"
[operation]
mode = "drilling"
bit_md = "{td_m} m"
wob = "100 kN"
rpm = 60
rop = "12 m/h"
friction = 0.25
{strings}
[solver]
element_length = "3 m"
bha_element_length = "0.5 m"
"#
    );
    let dir = tempfile::tempdir().expect("temporary directory");
    std::fs::write(dir.path().join("survey.csv"), build_and_hold_survey(td_m, hold_deg)).expect("write survey");
    std::fs::write(dir.path().join("case.toml"), case).expect("write case");
    load_case(&dir.path().join("case.toml"), &CaseOverrides::default()).expect("generated case loads")
}

/// The case cut to its bottom-hole assembly and HWDP (components starting below 100 m from the
/// bit): the top node of the model is then ~100 m above the bit, as in the predictor's BHA
/// models (the input format itself requires strings that reach the surface).
fn bha_only(mut case: Case) -> Case {
    case.string.components.retain(|c| c.bottom_m < 100.0);
    case
}

fn example_case(well: &str) -> Case {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("wells")
        .join(well)
        .join("case.toml");
    load_case(&path, &CaseOverrides::default()).expect("example case loads")
}

fn controls(case: &Case) -> SolveControls {
    SolveControls {
        max_iterations: case.solver.max_iterations,
        ..Default::default()
    }
}

fn bench_solve(c: &mut Criterion) {
    let mut group = c.benchmark_group("solve");
    group.sample_size(10);
    let cases = [
        (
            "bha_100m",
            bha_only(generated_case(3000.0, 35.0, &(bha(42.0) + DRILL_PIPE))),
        ),
        ("string_1000m", generated_case(1000.0, 35.0, &(bha(140.0) + DRILL_PIPE))),
        ("string_3000m", generated_case(3000.0, 35.0, &(bha(140.0) + DRILL_PIPE))),
        (
            "string_10000m",
            generated_case(10000.0, 35.0, &(bha(140.0) + DRILL_PIPE)),
        ),
        ("string_8000m", generated_case(8000.0, 60.0, &(bha(140.0) + DRILL_PIPE))),
        ("seed-daqing", example_case("seed-daqing")),
        ("s-shape", example_case("s-shape")),
    ];
    for (name, case) in &cases {
        let model = Model::from_case(case);
        let ctl = controls(case);
        let sol = solve(&model, &ctl).expect("solves");
        assert!(sol.converged, "{name} converges");
        println!(
            "{name}: {} m string, {} DOF, {} Newton iterations, {} factorizations",
            case.string.length_m(),
            model.dofs(),
            sol.stats.iterations,
            sol.stats.factorizations
        );
        group.bench_function(*name, |b| {
            b.iter(|| {
                let sol = solve(&model, &ctl).expect("solves");
                assert!(sol.converged);
                sol.stats.iterations
            })
        });
        if *name == "bha_100m" {
            bench_refined(&mut group, "bha_100m_refined", &model, &ctl, case);
            // warm start: the converged state of the solve above, WOB changed by 5%
            let mut warm = model.clone();
            warm.consistent_tangent = true;
            warm.loads.wob_n *= 1.05;
            let sol_w = solve_interior_point_from(&warm, sol.state.clone(), &ctl).expect("solves");
            assert!(sol_w.converged, "warm BHA solve converges");
            println!(
                "bha_100m_warm: {} DOF, {} Newton iterations, {} factorizations",
                warm.dofs(),
                sol_w.stats.iterations,
                sol_w.stats.factorizations
            );
            group.bench_function("bha_100m_warm", |b| {
                b.iter(|| {
                    let s = solve_interior_point_from(&warm, sol.state.clone(), &ctl).expect("solves");
                    assert!(s.converged);
                    s.stats.iterations
                })
            });
        }
    }
    bench_bha_cut(&mut group);
    // soft-string pass over the 3,000 m string (issue 5 target: < 0.5 ms)
    let soft = generated_case(3000.0, 35.0, &(bha(140.0) + DRILL_PIPE));
    let r = softstring::from_case(&soft, softstring::segment_length_m(&soft.solver));
    println!(
        "softstring_3000m: hook load {:.1} kN, {} points",
        r.hook_load_n / 1e3,
        r.points.len()
    );
    group.sample_size(50);
    group.bench_function("softstring_3000m", |b| {
        b.iter(|| softstring::from_case(&soft, softstring::segment_length_m(&soft.solver)).hook_load_n)
    });
    group.finish();
}

/// The predictor's BHA model (`bha_model` at `default_cut_m`) of wells/j-shape, cold and
/// warm-started from the solution with the bit 1 m shallower (`transport_state`).
fn bench_bha_cut(group: &mut criterion::BenchmarkGroup<criterion::measurement::WallTime>) {
    let case = example_case("j-shape");
    let path = &case.well.path;
    let hole = &case.well.hole;
    let bit = case.operation.bit_md_m;
    let cut = default_cut_m(
        &case.string,
        hole.diameter_at(bit),
        path.point_at(bit).inc_rad,
        case.mud.density_kg_m3,
    );
    let model_at = |md: f64| {
        let mut m = bha_model(&case, path, hole, md, cut);
        m.consistent_tangent = true;
        m
    };
    let (before, model) = (model_at(bit - 1.0), model_at(bit));
    assert!(matches!(model.top, TopCondition::Cut { .. }), "the BHA model is cut");
    let ctl = controls(&case);
    let sol = solve(&model, &ctl).expect("solves");
    assert!(sol.converged, "cut BHA model converges");
    println!(
        "bha_cut: cut {cut:.1} m above the bit, {} DOF, {} Newton iterations, {} factorizations",
        model.dofs(),
        sol.stats.iterations,
        sol.stats.factorizations
    );
    group.bench_function("bha_cut", |b| {
        b.iter(|| {
            let sol = solve(&model, &ctl).expect("solves");
            assert!(sol.converged);
            sol.stats.iterations
        })
    });
    let mut cold = model.clone();
    cold.consistent_tangent = false;
    bench_refined(group, "bha_cut_refined", &cold, &ctl, &case);
    let prev = solve(&before, &ctl).expect("solves");
    assert!(prev.converged, "cut BHA model 1 m shallower converges");
    let start = transport_state(&before, &prev.state, &model);
    let sol_w = solve_interior_point_from(&model, start.clone(), &ctl).expect("solves");
    assert!(sol_w.converged, "warm cut BHA solve converges");
    println!(
        "bha_cut_warm: {} DOF, {} Newton iterations, {} factorizations",
        model.dofs(),
        sol_w.stats.iterations,
        sol_w.stats.factorizations
    );
    group.bench_function("bha_cut_warm", |b| {
        b.iter(|| {
            let s = solve_interior_point_from(&model, start.clone(), &ctl).expect("solves");
            assert!(s.converged);
            s.stats.iterations
        })
    });
}

/// The cold solve of `model` followed by the contact-aware refinement and its warm solve
/// (`refine::solve_refined`, what `solve` runs by default), as bench `name`.
fn bench_refined(
    group: &mut criterion::BenchmarkGroup<criterion::measurement::WallTime>,
    name: &str,
    model: &Model,
    ctl: &SolveControls,
    case: &Case,
) {
    let scope = refine::Scope::of(&case.string, case.solver.refine_runs);
    let h = refine::REFINED_FRACTION * case.solver.bha_element_length_m;
    let (fine, sol) = refine::solve_refined(model.clone(), ctl, &scope, h).expect("solves");
    assert!(sol.converged, "{name} converges");
    println!(
        "{name}: {} -> {} DOF, {} Newton iterations, {} factorizations in all",
        model.dofs(),
        fine.dofs(),
        sol.stats.iterations,
        sol.stats.factorizations
    );
    group.bench_function(name, |b| {
        b.iter(|| {
            let (_, s) = refine::solve_refined(model.clone(), ctl, &scope, h).expect("solves");
            assert!(s.converged);
            s.stats.iterations
        })
    });
}

criterion_group!(benches, bench_solve);
criterion_main!(benches);
