//! Band LDLᵀ, band LU and faer sparse LDLᵀ on drill-string chain matrices.
//!
//! `cargo bench --bench band -- --warm-up-time 1 --measurement-time 2`

use std::hint::black_box;

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion};
use drillpath::models::fem::linalg::band::{chain_test_matrix, BandLdlt};
use drillpath::models::fem::linalg::band_lu::{BandLu, GeneralBand};
use drillpath::models::fem::linalg::sparse_faer::FaerLdlt;

fn bench_band(c: &mut Criterion) {
    let mut g = c.benchmark_group("band");
    for nodes in [1000usize, 3000, 16000] {
        let a = chain_test_matrix(nodes);
        let n = a.n();
        let b: Vec<f64> = (0..n)
            .map(|i| if i < 6 { 0.0 } else { (i as f64).sin() * 1e3 })
            .collect();

        let mut f = BandLdlt::new(n, a.half_bandwidth());
        f.factor(&a).unwrap();
        g.bench_with_input(BenchmarkId::new("band_factor", n), &a, |bch, a| {
            bch.iter(|| f.factor(black_box(a)).unwrap())
        });
        g.bench_with_input(BenchmarkId::new("band_refactor_tail600", n), &a, |bch, a| {
            bch.iter(|| f.refactor_from(black_box(a), n - 600).unwrap())
        });
        let mut x = b.clone();
        g.bench_function(BenchmarkId::new("band_solve", n), |bch| {
            bch.iter(|| {
                x.copy_from_slice(&b);
                f.solve_in_place(black_box(&mut x));
            })
        });

        // the same matrix in general band storage, LU (the friction path of the solver)
        let hb = a.half_bandwidth();
        let mut ga = GeneralBand::zeros(n, hb);
        for i in 0..n {
            for j in i.saturating_sub(hb)..=(i + hb).min(n - 1) {
                ga.add(i, j, a.get(i, j));
            }
        }
        let mut lu = BandLu::new(n, hb);
        lu.factor(&ga).unwrap();
        g.bench_with_input(BenchmarkId::new("lu_factor", n), &ga, |bch, ga| {
            bch.iter(|| lu.factor(black_box(ga)).unwrap())
        });
        g.bench_function(BenchmarkId::new("lu_solve", n), |bch| {
            bch.iter(|| {
                x.copy_from_slice(&b);
                lu.solve_in_place(black_box(&mut x));
            })
        });

        let mut fl = FaerLdlt::new(&a);
        fl.factor(&a).unwrap();
        g.bench_with_input(BenchmarkId::new("faer_factor", n), &a, |bch, a| {
            bch.iter(|| fl.factor(black_box(a)).unwrap())
        });
        g.bench_function(BenchmarkId::new("faer_solve", n), |bch| {
            bch.iter(|| {
                x.copy_from_slice(&b);
                fl.solve_in_place(black_box(&mut x));
            })
        });
    }
    g.finish();
}

criterion_group!(benches, bench_band);
criterion_main!(benches);
