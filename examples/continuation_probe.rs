//! Continuation probe (study tool of docs/performance.md, "The WOB continuation"): the
//! whole-string solve of a case directly (300 iterations), then along a load path from a tenth
//! of the load, every step printed.
//!
//! ```text
//! cargo run --release --example continuation_probe -- CASE [wob|wob+friction]
//! ```
//!
//! `wob` (the default) raises the WOB, as the solver's own continuation does; `wob+friction`
//! raises the wall friction with it (friction in proportion to the load factor).
use drillpath::io::case_toml::{load_case, CaseOverrides};
use drillpath::models::fem::model::Model;
use drillpath::models::fem::solve::{solve, solve_interior_point_from, SolveControls};
use std::path::Path;

fn main() {
    let a: Vec<String> = std::env::args().collect();
    let case = load_case(Path::new(&a[1]), &CaseOverrides::default()).expect("case");
    let with_friction = a.get(2).map(|s| s.as_str()) == Some("wob+friction");
    let target = case.operation.wob_n;
    let mut model = Model::from_case(&case);
    model.consistent_tangent = true;
    let friction = model.friction.clone();
    let at = |m: &Model, wob: f64| {
        let mut m = m.clone();
        m.loads.wob_n = wob;
        if with_friction {
            for (f, f0) in m.friction.iter_mut().zip(&friction) {
                *f = f0 * wob / target;
            }
        }
        m
    };
    let ctl = SolveControls {
        max_iterations: 60,
        ..SolveControls::from_settings(&case.solver)
    };
    let t0 = std::time::Instant::now();
    let direct = solve(
        &model,
        &SolveControls {
            max_iterations: 300,
            ..ctl
        },
    );
    println!(
        "direct: {:?} in {:.2} s",
        direct
            .as_ref()
            .map(|s| (s.converged, s.stats.iterations))
            .map_err(|e| e.to_string()),
        t0.elapsed().as_secs_f64()
    );
    let t0 = std::time::Instant::now();
    let mut wob = 0.1 * target;
    model = at(&model, wob);
    let mut sol = solve(&model, &ctl).expect("first step");
    println!(
        "start {:.1} kN: converged {}, {} it",
        wob / 1e3,
        sol.converged,
        sol.stats.iterations
    );
    let (mut step, mut total) = (0.1 * target, sol.stats.iterations);
    while wob < target - 1e-6 && step > 1e-4 * target {
        let next = (wob + step).min(target);
        let m = at(&model, next);
        match solve_interior_point_from(&m, sol.state.clone(), &ctl) {
            Ok(s) if s.converged => {
                total += s.stats.iterations;
                println!("  {:.1} kN: converged in {} it", next / 1e3, s.stats.iterations);
                (wob, sol, step) = (next, s, step * 1.5);
            }
            Ok(s) => {
                total += s.stats.iterations;
                println!("  {:.1} kN: not converged ({} it)", next / 1e3, s.stats.iterations);
                step *= 0.5;
            }
            Err(e) => {
                println!("  {:.1} kN: {e}", next / 1e3);
                step *= 0.5;
            }
        }
    }
    println!(
        "path: reached {:.1} of {:.1} kN, {total} iterations, {:.2} s, hook load {:.1} kN",
        wob / 1e3,
        target / 1e3,
        t0.elapsed().as_secs_f64(),
        sol.state.hook_load_n / 1e3
    );
}
