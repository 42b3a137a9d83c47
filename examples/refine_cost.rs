//! Cost of the contact-aware refinement (docs/performance.md, "Contact-aware refinement"):
//! each example well solved at `bha` and `whole` with `refine_contacts` off and on,
//! alternately (20 / 4 solves each), the fastest of each printed.
//!
//! ```text
//! cargo run --release --example refine_cost
//! ```
use drillpath::case::{choose, Fidelity, Level, Purpose};
use drillpath::io::case_toml::{load_case, CaseOverrides};
use drillpath::models::fem::solve::SolveControls;
use drillpath::models::levels::run;
use std::path::Path;
fn main() {
    for w in [
        "seed-daqing",
        "j-shape",
        "s-shape",
        "forge-16a",
        "volve-f10",
        "horizontal",
    ] {
        let p = format!("wells/{w}/case.toml");
        let mut case = load_case(Path::new(&p), &CaseOverrides::default()).unwrap();
        for level in [Level::Bha, Level::Whole] {
            let mut best = [f64::MAX; 2];
            for k in 0..(if level == Level::Bha { 40 } else { 8 }) {
                let refine = k % 2 == 0;
                case.solver.refine_contacts = refine;
                let ctl = SolveControls::from_settings(&case.solver);
                let t = std::time::Instant::now();
                let r = run(&case, choose(Fidelity::Level(level), Purpose::Solve), &ctl).unwrap();
                assert!(r.converged);
                let s = t.elapsed().as_secs_f64();
                let i = usize::from(refine);
                best[i] = best[i].min(s);
            }
            println!(
                "{w} {level:?}: plain {:.2} ms, refined {:.2} ms, x{:.2}",
                best[0] * 1e3,
                best[1] * 1e3,
                best[1] / best[0]
            );
        }
    }
}
