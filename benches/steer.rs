//! Bent-motor timings (issue 17): the predictor's stiff BHA model of
//! wells/horizontal/steered.toml (1.5 deg bent motor, cut model at the bit's depth, 4,000 m),
//! cold-solved
//! - sliding at toolface 0, the housing held at its toolface against the twist
//!   (`solve_holding_toolface`), against
//! - rotating at one toolface (a rotary solve of the same assembly; a rotating step of the
//!   predictor solves 24 of them), and
//! - the same assembly with a straight housing, rotating (wells/horizontal/case.toml's motor);
//!
//! and the motor yield and rotating tendency of `solve` (`predict::steer::steering`).
//!
//! Run: `cargo bench --bench steer -- --warm-up-time 1 --measurement-time 5`.

use criterion::{criterion_group, criterion_main, Criterion};
use drillpath::case::{Case, Mode};
use drillpath::io::case_toml::{load_case, CaseOverrides};
use drillpath::models::fem::bha::{bha_model, default_cut_m};
use drillpath::models::fem::model::Model;
use drillpath::models::fem::solve::toolface::solve_holding_toolface;
use drillpath::models::fem::solve::{solve, SolveControls};
use drillpath::predict::steer::steering;
use std::hint::black_box;
use std::path::Path;

fn case(file: &str, mode: Mode) -> Case {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("wells/horizontal")
        .join(file);
    let mut c = load_case(&path, &CaseOverrides::default()).unwrap();
    c.operation.mode = mode;
    c
}

fn cut_model(c: &Case) -> Model {
    let md = c.operation.bit_md_m;
    let p = c.well.path.point_at(md);
    let cut = default_cut_m(&c.string, c.well.hole.diameter_at(md), p.inc_rad, c.mud.density_kg_m3);
    let mut m = bha_model(c, &c.well.path, &c.well.hole, md, cut);
    m.consistent_tangent = true;
    m
}

fn bench_steer(cr: &mut Criterion) {
    let mut group = cr.benchmark_group("steer");
    for (name, file, mode) in [
        ("bent_slide_bha", "steered.toml", Mode::Sliding),
        ("bent_rotary_bha", "steered.toml", Mode::Drilling),
        ("straight_rotary_bha", "case.toml", Mode::Drilling),
    ] {
        let c = case(file, mode);
        let ctl = SolveControls::from_settings(&c.solver);
        let model = cut_model(&c);
        let mut m = model.clone();
        let sol = solve_holding_toolface(&mut m, &ctl, |m| solve(m, &ctl)).unwrap();
        println!(
            "{name}: {} DOF, {} Newton iterations, converged {}",
            m.dofs(),
            sol.stats.iterations,
            sol.converged
        );
        group.bench_function(name, |b| {
            b.iter(|| {
                let mut m = model.clone();
                black_box(solve_holding_toolface(&mut m, &ctl, |m| solve(m, &ctl)).unwrap())
            })
        });
    }
    let c = case("steered.toml", Mode::Drilling);
    let ctl = SolveControls::from_settings(&c.solver);
    group.sample_size(10);
    group.bench_function("yield_and_rotating_tendency", |b| {
        b.iter(|| black_box(steering(&c, &ctl)))
    });
    group.finish();
}

criterion_group!(benches, bench_steer);
criterion_main!(benches);
