//! The refined solve of the assembly's lower part with the string above condensed
//! (`models::fem::condense`) against the whole refined model solved from the same carried
//! state: the two are solutions of the same equations to the same residual tolerance, so their
//! answers must agree to a small fraction of what that tolerance allows.
//!
//! Reference: the whole refined solve (`refine::refined_model`, `refine::carried_state`, the
//! interior-point Newton from there), the path taken where the condensation does not apply.
//! Tolerances: bit build and walk forces within 1e-3 N, the bit tilt within 1e-9 rad, every
//! wall contact force within 1e-2 N and the cut's axial force (or hook load) within 1e-2 N;
//! the residual tolerance (1e-7 of a load scale of 1e5-1e6 N) allows 0.01-0.1 N.

use drillpath::case::Case;
use drillpath::models::fem::model::Model;
use drillpath::models::fem::refine::{
    carried_state, near_bit_elements, refined_model, solve_refined, Scope, REFINED_FRACTION,
};
use drillpath::models::fem::results::extract;
use drillpath::models::fem::solve::{solve, solve_interior_point_from, SolveControls};

use crate::common::{bha_at_30_deg, bha_of, collar, example, fulcrum_bha, packed_bha, pendulum_bha};

/// Differences between the refined solve of `model` by its lower part and the whole refined
/// solve from the same carried state (bit side forces relative to the lateral bit force, tilt
/// relative to itself, total wall force relative to itself, top axial force N) and the lateral
/// bit force (N); None where the refined solve did not take the lower part.
fn differences(case: &Case, model: &Model, name: &str) -> Option<[f64; 5]> {
    let ctl = SolveControls::from_settings(&case.solver);
    let scope = Scope::of(&case.string, case.solver.refine_runs);
    let h = REFINED_FRACTION * case.solver.bha_element_length_m;
    let (fine, by_lower) = solve_refined(model.clone(), &ctl, &scope, h).unwrap();
    assert!(by_lower.converged, "{name}: not converged");
    if !by_lower.stats.lower_part_refined {
        return None;
    }
    let plain = solve(model, &ctl).unwrap();
    let split = near_bit_elements(model, &plain.state, &scope, h);
    let mut whole_fine = refined_model(model, &split, h);
    whole_fine.consistent_tangent = true;
    assert_eq!(whole_fine.nodes(), fine.nodes(), "{name}: the same refined mesh");
    let start = carried_state(model, &plain.state, &whole_fine);
    let carried = SolveControls {
        carried_start: true,
        ..ctl
    };
    let whole = solve_interior_point_from(&whole_fine, start, &carried).unwrap();
    assert!(whole.converged, "{name}: the whole refined solve did not converge");
    let rho = case.mud.density_kg_m3;
    let (a, b) = (extract(&fine, &by_lower, rho), extract(&whole_fine, &whole, rho));
    let (ba, bb) = (a.bit, b.bit);
    let lateral = ba.build_force_n.hypot(ba.walk_force_n);
    let tilt = ba.tilt_inc_rad.hypot(ba.tilt_azi_rad);
    let wall = |sol: &drillpath::models::fem::solve::Solution| {
        let s = &sol.state;
        s.multipliers.iter().sum::<f64>() + s.pin_multipliers.iter().map(|p| p.norm()).sum::<f64>()
    };
    let (wa, wb) = (wall(&by_lower), wall(&whole));
    Some([
        (ba.build_force_n - bb.build_force_n)
            .abs()
            .max((ba.walk_force_n - bb.walk_force_n).abs())
            / lateral,
        (ba.tilt_inc_rad - bb.tilt_inc_rad).hypot(ba.tilt_azi_rad - bb.tilt_azi_rad) / tilt,
        (wa - wb).abs() / wb,
        (by_lower.state.hook_load_n - whole.state.hook_load_n).abs(),
        lateral,
    ])
}

fn assert_close(d: [f64; 5], name: &str) {
    let [force, tilt, wall, top, _] = d;
    assert!(
        force <= 1e-4,
        "{name}: bit side forces {force:.2e} of the lateral force apart"
    );
    assert!(tilt <= 1e-4, "{name}: bit tilt {tilt:.2e} of itself apart");
    assert!(wall <= 1e-4, "{name}: total wall force {wall:.2e} of itself apart");
    assert!(top <= 1e-2, "{name}: top axial force {top:.2e} N apart");
}

/// The three test BHAs of `fine_mesh.rs` and the pendulum with 10 m more collars, at the 0.5 m
/// and the 1 m mesh: every one takes the lower part and gives the whole refined answer.
#[test]
fn the_lower_part_refined_solve_gives_the_whole_refined_answer_on_the_test_bhas() {
    let pendulum_collars = format!("{}{}", pendulum_bha(), collar("10 m"));
    for (name, bha) in [
        ("fulcrum", fulcrum_bha()),
        ("pendulum", pendulum_bha()),
        ("packed", packed_bha()),
        ("pendulum + collars", pendulum_collars),
    ] {
        for bel in [0.5, 1.0] {
            let case = bha_at_30_deg(&bha, bel);
            let label = format!("{name} at {bel} m");
            let d = differences(&case, &bha_of(&case), &label);
            eprintln!("{label}: {d:?}");
            assert_close(d.unwrap_or_else(|| panic!("{label}: the lower part not taken")), &label);
        }
    }
}

/// The example wells whose models the comparisons run on.
const WELLS: [&str; 6] = [
    "seed-daqing",
    "j-shape",
    "s-shape",
    "forge-16a",
    "volve-f10",
    "horizontal",
];

/// Each of [`WELLS`]' model built by `model` (named `label`) takes the lower part and gives the
/// whole refined answer.
fn wells_agree(model: impl Fn(&Case) -> Model, label: &str) {
    for name in WELLS {
        let case = example(name);
        let d = differences(&case, &model(&case), name);
        eprintln!("{name} {label}: {d:?}");
        let d = d.unwrap_or_else(|| panic!("{name} {label}: the lower part not taken"));
        assert_close(d, &format!("{name} {label}"));
    }
}

/// The six example wells' `bha` models: every one takes the lower part and gives the whole
/// refined answer.
#[test]
fn the_lower_part_refined_solve_gives_the_whole_refined_answer_on_the_example_wells() {
    wells_agree(bha_of, "bha");
}

/// The six example wells' whole strings. On s-shape the lower solve twists the cut by 5e-4 rad
/// (the string above is torsionally soft) and the part above's linear response misses the
/// twist's second-order bending terms (1.3 N at the cut): the check of the whole model takes
/// one more Newton iteration there (as on forge-16a and volve-f10; docs/performance.md), and
/// the answer is the whole refined solve's all the same.
#[test]
fn whole_strings_take_the_lower_part_and_give_the_whole_refined_answer() {
    wells_agree(Model::from_case, "whole");
}
