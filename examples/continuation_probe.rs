use drillpath::io::case_toml::{load_case, CaseOverrides};
use drillpath::models::fem::model::Model;
use drillpath::models::fem::solve::{solve, solve_interior_point_from, SolveControls};
use std::path::Path;
fn main() {
    let a: Vec<String> = std::env::args().collect();
    let case = load_case(Path::new(&a[1]), &CaseOverrides::default()).expect("case");
    let target = case.operation.wob_n;
    let mut model = Model::from_case(&case);
    model.consistent_tangent = true;
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
    model.loads.wob_n = wob;
    let mut sol = solve(&model, &ctl).expect("first");
    println!(
        "start wob {:.1} kN: {} {}",
        wob / 1e3,
        sol.converged,
        sol.stats.iterations
    );
    let mut step = 0.1 * target;
    let mut total = sol.stats.iterations;
    while wob < target - 1e-6 && step > 1e-4 * target {
        let next = (wob + step).min(target);
        let mut m = model.clone();
        m.loads.wob_n = next;
        match solve_interior_point_from(&m, sol.state.clone(), &ctl) {
            Ok(s) if s.converged => {
                total += s.stats.iterations;
                println!("  wob {:.1} kN ok in {} it", next / 1e3, s.stats.iterations);
                wob = next;
                sol = s;
                model = m;
                step *= 1.5;
            }
            Ok(s) => {
                total += s.stats.iterations;
                println!("  wob {:.1} kN failed ({} it)", next / 1e3, s.stats.iterations);
                step *= 0.5;
            }
            Err(e) => {
                println!("  wob {:.1} kN error {e}", next / 1e3);
                step *= 0.5;
            }
        }
    }
    println!(
        "continuation: reached {:.1} of {:.1} kN, {} iterations, {:.2} s, hook {:.1} kN",
        wob / 1e3,
        target / 1e3,
        total,
        t0.elapsed().as_secs_f64(),
        sol.state.hook_load_n / 1e3
    );
}
