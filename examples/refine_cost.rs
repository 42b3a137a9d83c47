//! Cost of the contact-aware refinement (docs/performance.md, "Contact-aware refinement"):
//! each example well solved at `bha` and `whole` with `refine_contacts` off and on,
//! alternately (20 / 4 solves each), the fastest of each printed.
//!
//! ```text
//! cargo run --release --example refine_cost
//! cargo run --release --example refine_cost -- WELL RUNS [REFINE_RUNS]
//! ```
//!
//! With a well and a run count: that well's `bha` solve only, plain and refined alternately,
//! RUNS each, the fastest of each with its Newton iterations, factorizations and nodes (the
//! form the baseline comparison against an older build uses); REFINE_RUNS sets
//! `[solver] refine_runs` (default 3; 100000 refines every contact run).
use drillpath::case::{choose, Case, Fidelity, Level, Purpose};
use drillpath::io::case_toml::{load_case, CaseOverrides};
use drillpath::models::fem::solve::SolveControls;
use drillpath::models::levels::run;
use std::path::Path;

const WELLS: [&str; 6] = [
    "seed-daqing",
    "j-shape",
    "s-shape",
    "forge-16a",
    "volve-f10",
    "horizontal",
];

/// The fastest of `runs` solves at `level` with `refine_contacts` off and on (alternately), s,
/// and the last solves' (iterations, factorizations, nodes).
fn fastest(case: &mut Case, level: Level, runs: usize) -> ([f64; 2], [(usize, usize, usize); 2]) {
    let mut best = [f64::MAX; 2];
    let mut work = [(0, 0, 0); 2];
    for k in 0..2 * runs {
        let refine = k % 2 == 0;
        case.solver.refine_contacts = refine;
        let ctl = SolveControls::from_settings(&case.solver);
        let t = std::time::Instant::now();
        let r = run(case, choose(Fidelity::Level(level), Purpose::Solve), &ctl).unwrap();
        let s = t.elapsed().as_secs_f64();
        assert!(r.converged);
        let i = usize::from(refine);
        best[i] = best[i].min(s);
        let f = r.fem.as_ref().unwrap();
        work[i] = (f.stats.iterations, f.stats.factorizations, f.model.nodes());
    }
    (best, work)
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    if let [w, runs, rest @ ..] = args.as_slice() {
        let p = format!("wells/{w}/case.toml");
        let mut case = load_case(Path::new(&p), &CaseOverrides::default()).unwrap();
        if let Some(r) = rest.first() {
            case.solver.refine_runs = r.parse().unwrap();
        }
        let (best, work) = fastest(&mut case, Level::Bha, runs.parse().unwrap());
        for (i, name) in ["plain", "refined"].iter().enumerate() {
            let (it, fa, nodes) = work[i];
            println!("{w} {name} {:.3} ms it/fact {it}/{fa} nodes {nodes}", best[i] * 1e3);
        }
        return;
    }
    for w in WELLS {
        let p = format!("wells/{w}/case.toml");
        let mut case = load_case(Path::new(&p), &CaseOverrides::default()).unwrap();
        for level in [Level::Bha, Level::Whole] {
            let (best, _) = fastest(&mut case, level, if level == Level::Bha { 20 } else { 4 });
            println!(
                "{w} {level:?}: plain {:.2} ms, refined {:.2} ms, x{:.2}",
                best[0] * 1e3,
                best[1] * 1e3,
                best[1] / best[0]
            );
        }
    }
}
