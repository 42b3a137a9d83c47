//! Whole-string solve timings (issue 3): a converged `solve` of example wells at default mesh.
//! Run: `cargo bench --bench solve -- --warm-up-time 1 --measurement-time 10`.

use criterion::{criterion_group, criterion_main, Criterion};
use drillpath::fem::model::Model;
use drillpath::fem::solve::{solve, SolveControls};
use drillpath::io::case_toml::{load_case, CaseOverrides};
use std::path::Path;

fn bench_solve(c: &mut Criterion) {
    let mut group = c.benchmark_group("solve");
    group.sample_size(10);
    for well in ["seed-daqing", "s-shape"] {
        let path = Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("wells")
            .join(well)
            .join("case.toml");
        let case = load_case(&path, &CaseOverrides::default()).expect("example case loads");
        let model = Model::from_case(&case);
        let ctl = SolveControls {
            max_iterations: case.solver.max_iterations,
            ..Default::default()
        };
        group.bench_function(well, |b| {
            b.iter(|| {
                let sol = solve(&model, &ctl).expect("solves");
                assert!(sol.converged);
                sol.stats.iterations
            })
        });
    }
    group.finish();
}

criterion_group!(benches, bench_solve);
criterion_main!(benches);
