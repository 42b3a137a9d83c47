//! Step probe (study tool of docs/performance.md, "Step convergence"): one prediction with the
//! step scheme and a few case settings overridden, every step printed.
//!
//! ```text
//! cargo run --release --example stepprobe -- CASE STEP [arc|chord] [BETA] [BHA_ELEMENT_M] [AHEAD_M] [FROM_MD_M]
//! ```
//!
//! `BETA` overrides `[bit_rock] lateral_drillability`, `BHA_ELEMENT_M` the BHA element length
//! (`x` or nothing: the case's); `AHEAD_M` defaults to 100, `FROM_MD_M` to the case's bit MD.
//! Prints `md inc_deg azi_deg build_force_kN walk_force_kN` per step on stdout; on stderr the
//! counts and the end ripple, and when the march fails, the error and the march up to the last
//! accepted step.
use drillpath::io::case_toml::{load_case, CaseOverrides};
use drillpath::predict::march::{predict, MarchSettings, StepScheme};
use std::path::Path;

fn main() {
    let a: Vec<String> = std::env::args().collect();
    let mut case = load_case(Path::new(&a[1]), &CaseOverrides::default()).expect("case");
    let step: f64 = a[2].parse().unwrap();
    let scheme = match a.get(3).map(|s| s.as_str()) {
        Some("chord") => StepScheme::Chord,
        _ => StepScheme::Arc,
    };
    if let Some(b) = a.get(4).and_then(|s| s.parse::<f64>().ok()) {
        case.bit_rock.lateral_drillability = b;
    }
    if let Some(m) = a.get(5).and_then(|s| s.parse::<f64>().ok()) {
        case.solver.bha_element_length_m = m;
    }
    let ahead: f64 = a.get(6).and_then(|s| s.parse().ok()).unwrap_or(100.0);
    let from = a.get(7).and_then(|s| s.parse().ok()).unwrap_or(case.operation.bit_md_m);
    let mut st = MarchSettings::from_case(&case);
    st.step_m = step;
    st.scheme = scheme;
    let mut to = from + ahead;
    let mut last_md = from;
    let first = predict(&case, from, to, &st, &mut |md| last_md = md);
    let res = match first {
        Ok(p) => Ok(p),
        Err(e) => {
            eprintln!("error: {e} (last accepted {last_md:.2} m)");
            to = last_md;
            predict(&case, from, to, &st, &mut |_| {})
        }
    };
    match res {
        Ok(p) => {
            for r in &p.steps {
                println!(
                    "{:.3} {:.5} {:.5} {:.4} {:.4}",
                    r.md_m,
                    r.inc_rad.to_degrees(),
                    r.azi_rad.to_degrees(),
                    r.bit.build_force_n / 1e3,
                    r.bit.walk_force_n / 1e3
                );
            }
            eprintln!(
                "{} steps, {} iterations, {:.2} s, ripple {:.3} deg",
                p.steps.len(),
                p.iterations,
                p.seconds,
                p.ripple_deg
            );
        }
        Err(e) => eprintln!("error: {e}"),
    }
}
