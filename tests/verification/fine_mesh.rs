//! Fine BHA meshes (issue 20, item 3): the cut (`bha`) model of the fulcrum, pendulum and
//! packed BHAs converges with `bha_element_length` down to 0.02 m (0.01 m on the fulcrum and
//! packed BHAs), and its bit forces and tilt converge with the mesh.
//!
//! Run with `cargo test --release --test verification fine_mesh:: -- --nocapture` to see the
//! numbers.

use drillpath::case::{choose, Case, Fidelity, Level, Purpose};
use drillpath::models::fem::solve::SolveControls;
use drillpath::models::levels::run;

use crate::common::{fulcrum_bha, load_temp_case, packed_bha, pendulum_bha, DRILL_PIPE};

/// The bit's build force, walk force (N) and inclination tilt (rad), Newton iterations.
struct Bit {
    build: f64,
    walk: f64,
    tilt: f64,
    iterations: usize,
}

/// `bha` drilling in a straight 8.5 in hole at 30 deg (3,000 m, bit at TD), 80 kN WOB, 60 rpm,
/// friction 0.25, drill pipe above the assembly, BHA elements of `bel` m.
fn case(bha: &str, bel: f64) -> Case {
    let survey = "md_m,inc_deg,azi_deg\n0,30,0\n3000,30,0\n";
    let toml = format!(
        r#"
[well]
survey = "survey.csv"
hole = [{{ to_md = "3000 m", diameter = "8.5 in" }}]
[mud]
density = "1.2 sg"
[operation]
mode = "drilling"
bit_md = "3000 m"
wob = "80 kN"
rpm = 60
rop = "10 m/h"
friction = 0.25
{bha}{DRILL_PIPE}[solver]
bha_element_length = "{bel} m"
"#
    );
    load_temp_case(survey, &toml)
}

fn solve(bha: &str, bel: f64) -> Bit {
    let case = case(bha, bel);
    let r = run(
        &case,
        choose(Fidelity::Level(Level::Bha), Purpose::Solve),
        &SolveControls::from_settings(&case.solver),
    )
    .unwrap();
    assert!(r.converged, "bha_element_length {bel} m did not converge");
    let b = r.bit.unwrap();
    Bit {
        build: b.build_force_n,
        walk: b.walk_force_n,
        tilt: b.tilt_inc_rad,
        iterations: r.fem.as_ref().unwrap().stats.iterations,
    }
}

#[test]
fn fine_mesh_bha_converges_and_bit_answers_converge_with_the_mesh() {
    // Reference: the finest mesh of each BHA (0.01 m; 0.02 m on the pendulum, whose 0.01 m
    // mesh does not converge: open point, docs/performance.md). Tolerances: every mesh from
    // 0.1 m down within 0.05% of the reference's lateral bit force and of its tilt (measured:
    // at most 0.029%, the packed BHA's 0.1 m mesh, 0.03 N of its 0.1 kN; the pendulum's 0.1-
    // 0.03 m meshes agree within 1e-6 and its 0.02 m reference is 0.015% off them: the
    // residual tolerance of the finest meshes is their rounding floor, 2e-6 of the load scale
    // at 0.02 m); the
    // default 0.5 m mesh within 0.5% (measured: 0.36% build force and 0.30% tilt on the
    // pendulum, 0.016% and 0.013% on the fulcrum; the issue's 0.1% target is not met, see
    // docs/performance.md); at most 30 Newton iterations (measured 5-23).
    let bhas = [
        ("fulcrum", fulcrum_bha(), 0.01),
        ("pendulum", pendulum_bha(), 0.02),
        ("packed", packed_bha(), 0.01),
    ];
    for (name, bha, finest) in bhas {
        let reference = solve(&bha, finest);
        let lateral = reference.build.hypot(reference.walk);
        for bel in [0.5, 0.1, 0.05, 0.04, 0.03, 0.02] {
            if bel < finest {
                continue;
            }
            let b = solve(&bha, bel);
            let (eb, ew, et) = (
                (b.build - reference.build) / lateral,
                (b.walk - reference.walk) / lateral,
                (b.tilt - reference.tilt) / reference.tilt.abs(),
            );
            println!(
                "{name:<9} {bel:>5} m: {:>3} iterations, build {:+.4} kN ({:+.4}%), walk {:+.4} kN ({:+.4}%), tilt {:+.6} deg ({:+.4}%)",
                b.iterations,
                b.build / 1e3,
                100.0 * eb,
                b.walk / 1e3,
                100.0 * ew,
                b.tilt.to_degrees(),
                100.0 * et
            );
            let tol = if bel > 0.1 { 5e-3 } else { 5e-4 };
            for e in [eb, ew, et] {
                assert!(
                    e.abs() < tol,
                    "{name} at {bel} m: {:.4}% from the {finest} m mesh",
                    100.0 * e
                );
            }
            assert!(b.iterations <= 30, "{name} at {bel} m: {} iterations", b.iterations);
        }
        println!(
            "{name:<9} {finest:>5} m: {:>3} iterations (reference)",
            reference.iterations
        );
        assert!(reference.iterations <= 30);
    }
}
