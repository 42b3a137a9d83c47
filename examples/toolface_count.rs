//! How many toolfaces over a revolution the rotating tendency of a bent motor needs
//! (docs/performance.md, "Toolfaces over a revolution"): the steady rotating dogleg of
//! `wells/horizontal/steered.toml`'s 1.5 deg motor at its bit (92.5 deg) and in straight holes of
//! 30 and 60 deg (`predict::tendency::at_inclination`), with N = 4, 6, 8, 12, 16, 24, 48
//! toolfaces against 72; the largest of the build and right errors, deg/30 m, and the CPU time.
//!
//! Run: `cargo run --release --example toolface_count`.

use drillpath::case::Mode;
use drillpath::io::case_toml::{load_case, CaseOverrides};
use drillpath::models::fem::solve::SolveControls;
use drillpath::predict::steer::{steady_turn_at, toolfaces_n};
use drillpath::predict::tendency::at_inclination;
use std::path::Path;

fn main() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("wells/horizontal/steered.toml");
    let mut base = load_case(&path, &CaseOverrides::default()).unwrap();
    base.operation.mode = Mode::Drilling;
    let ns = [4usize, 6, 8, 12, 16, 24, 48];
    println!("| hole | {} |", ns.map(|n| format!("N = {n}")).join(" | "));
    for inc in [None, Some(30.0f64), Some(60.0)] {
        let c = match inc {
            Some(i) => at_inclination(&base, i.to_radians()).unwrap(),
            None => base.clone(),
        };
        let ctl = SolveControls::from_settings(&c.solver);
        let at = |n: usize| {
            let t0 = std::time::Instant::now();
            let t = steady_turn_at(&c, &c.bit_rock, &ctl, &toolfaces_n(&c, n)).unwrap();
            (t, t0.elapsed().as_secs_f64())
        };
        let (r, _) = at(72);
        let d = |k: f64| k.to_degrees() * 30.0;
        let cells: Vec<String> = ns
            .iter()
            .map(|&n| {
                let (t, s) = at(n);
                let e = d(t.build_rad_per_m - r.build_rad_per_m)
                    .abs()
                    .max(d(t.right_rad_per_m - r.right_rad_per_m).abs());
                format!("{e:.4} ({s:.2} s)")
            })
            .collect();
        let name = inc.map(|i| format!("{i} deg")).unwrap_or("92.5 deg (TD)".into());
        println!(
            "| {name} (N = 72: build {:+.4}, right {:+.4}) | {} |",
            d(r.build_rad_per_m),
            d(r.right_rad_per_m),
            cells.join(" | ")
        );
    }
}
