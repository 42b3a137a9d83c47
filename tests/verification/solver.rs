//! Verification of the whole-string FEM (`drillpath solve`) against independent references.
//!
//! Each test states its reference and tolerance. The closed forms come from
//! `drillpath::analytical` (written and tested separately from the FEM, docs/theory.md 10).

use drillpath::analytical::pendulum::{
    axial_gradient, constant_compression, constant_compression_slope, lateral_load, variable_compression,
};
use drillpath::models::fem::model::{GapTreatment, Model};
use drillpath::models::fem::results::{extract, SolveResults};
use drillpath::models::fem::solve::{solve, SolveControls};

use crate::common::{
    collar, collar_properties, example, load_temp_case, slick_collar_case, COLLAR_TO_SURFACE, DRILL_PIPE,
    DRILL_PIPE_BODY,
};

struct Run {
    res: SolveResults,
    model: Model,
}

/// Solve a slick collar string in a straight hole of inclination `inc_deg`, azimuth `azi_deg`,
/// `length_m` long, with `wob_kn` and BHA element length `el_m`.
fn slick_collar(inc_deg: f64, azi_deg: f64, length_m: f64, wob_kn: f64, el_m: f64, geometric: bool) -> Run {
    let case = slick_collar_case(inc_deg, azi_deg, length_m, wob_kn, el_m, "max_iterations = 1000");
    let mut model = Model::from_case(&case);
    model.geometric_stiffness = geometric;
    let sol = solve(
        &model,
        &SolveControls {
            max_iterations: 1000,
            ..Default::default()
        },
    )
    .unwrap();
    assert!(
        sol.converged,
        "solve did not converge: {:?}",
        sol.stats.residual_history.last()
    );
    let res = extract(&model, &sol, case.mud.density_kg_m3);
    Run { res, model }
}

#[test]
fn pendulum_bha_matches_lubinski_with_variable_axial_force() {
    // Reference: Lubinski (1953) pendulum, beam-column with the axial force varying with the
    // axial weight, P(x) = WOB - w_b cos(I) x (docs/theory.md 9.2, analytical::pendulum).
    // Tolerance: 0.5% on side force and tilt (the issue asks 2%, aiming at 0.5%); measured
    // agreement is better than 0.05% with 0.25 m elements.
    let (ei, w_b, r) = collar_properties();
    for &inc in &[3.0_f64, 10.0, 30.0, 60.0] {
        for &wob_kn in &[0.0, 100.0] {
            let run = slick_collar(inc, 45.0, 80.0, wob_kn, 0.25, true);
            let i = inc.to_radians();
            let reference =
                variable_compression(ei, lateral_load(w_b, i), axial_gradient(w_b, i), wob_kn * 1e3, r).unwrap();
            let fem_side = -run.res.bit.build_force_n; // bit pushes the rock to the low side
            let fem_tilt = run.res.bit.tilt_inc_rad;
            let e_f = (fem_side - reference.side_force) / reference.side_force;
            let e_t = (fem_tilt - reference.tilt) / reference.tilt;
            println!(
                "inc {inc:>4} WOB {wob_kn:>5} kN: side force FEM {:.4} kN ref {:.4} kN ({:+.3}%), tilt FEM {:.5} deg ref {:.5} deg ({:+.3}%)",
                fem_side / 1e3,
                reference.side_force / 1e3,
                100.0 * e_f,
                fem_tilt.to_degrees(),
                reference.tilt.to_degrees(),
                100.0 * e_t
            );
            assert!(
                e_f.abs() < 0.005,
                "side force off by {:.2}% at {inc} deg, WOB {wob_kn} kN",
                100.0 * e_f
            );
            assert!(
                e_t.abs() < 0.005,
                "tilt off by {:.2}% at {inc} deg, WOB {wob_kn} kN",
                100.0 * e_t
            );
            assert!(
                run.res.bit.walk_force_n.abs() < 1e-3,
                "no walk force in a plane problem"
            );
            let scale = w_b * 80.0 + wob_kn * 1e3;
            assert!(
                (run.res.bit.wob_n - wob_kn * 1e3).abs() < 1e-5 * scale,
                "WOB enforced: {}",
                run.res.bit.wob_n
            );
        }
    }
}

#[test]
fn global_equilibrium_holds() {
    // Reference: statics of the whole string (docs/theory.md 10.4). The sum of all external forces
    // (weight, wall, bit and top reactions, hook load) vanishes to 1e-6 of the largest term.
    let run = slick_collar(30.0, 120.0, 80.0, 100.0, 0.25, true);
    let rel = run.res.force_imbalance_n.norm() / run.res.largest_force_n;
    println!("force imbalance {rel:.2e} of the largest force");
    assert!(rel < 1e-6, "force imbalance {rel:e}");
    let mrel = run.res.moment_imbalance_nm.norm() / (run.res.largest_force_n * 80.0);
    println!("moment imbalance {mrel:.2e} of largest force x length");
    assert!(mrel < 1e-6, "moment imbalance {mrel:e}");
}

#[test]
fn mesh_convergence_of_bit_side_force() {
    // Reference: the FEM itself under refinement; halving the element length at the default
    // BHA mesh (0.25-0.5 m) changes the bit side force by less than 0.5%.
    let sides: Vec<f64> = [1.0, 0.5, 0.25, 0.125]
        .iter()
        .map(|&el| {
            let run = slick_collar(10.0, 0.0, 80.0, 100.0, el, true);
            println!(
                "element {el} m: side force {:.5} kN, tilt {:.5} deg",
                -run.res.bit.build_force_n / 1e3,
                run.res.bit.tilt_inc_rad.to_degrees()
            );
            -run.res.bit.build_force_n
        })
        .collect();
    for k in 1..sides.len() {
        println!("change {:.4}%", 100.0 * (sides[k] - sides[k - 1]) / sides[k]);
    }
    let change = ((sides[2] - sides[1]) / sides[2]).abs();
    assert!(
        change < 0.005,
        "0.5 -> 0.25 m changes side force by {:.3}%",
        100.0 * change
    );
    let change = ((sides[3] - sides[2]) / sides[3]).abs();
    assert!(
        change < 0.005,
        "0.25 -> 0.125 m changes side force by {:.3}%",
        100.0 * change
    );
}

#[test]
fn vertical_hole_has_no_side_force_or_tilt() {
    // Reference: symmetry (docs/theory.md 10.4): vertical hole, no rotation -> zero build and walk
    // force and tilt (< 1e-6 kN); hook load = buoyed weight - WOB exactly.
    let run = slick_collar(0.0, 0.0, 80.0, 50.0, 0.5, true);
    assert!(run.res.bit.build_force_n.abs() < 1e-3 && run.res.bit.walk_force_n.abs() < 1e-3);
    assert!(run.res.bit.tilt_inc_rad.abs() < 1e-9 && run.res.bit.tilt_azi_rad.abs() < 1e-9);
    let (_, w_b, _) = collar_properties();
    let weight = w_b * 80.0;
    assert!(
        (run.res.hook_load_n - (weight - 50e3)).abs() < 1e-6 * weight,
        "hook load {}",
        run.res.hook_load_n
    );
    let _ = &run.model;
}

#[test]
fn azimuth_rotation_leaves_bit_forces_unchanged() {
    // Reference: frame invariance (docs/theory.md 10.4): rotating the whole well in azimuth leaves
    // build force, walk force and tilts unchanged (tolerance 1e-6 relative).
    let a = slick_collar(25.0, 10.0, 80.0, 80.0, 0.5, true);
    let b = slick_collar(25.0, 247.0, 80.0, 80.0, 0.5, true);
    let rel = |x: f64, y: f64| (x - y).abs() / x.abs().max(1.0);
    assert!(rel(a.res.bit.build_force_n, b.res.bit.build_force_n) < 1e-6);
    assert!((a.res.bit.walk_force_n - b.res.bit.walk_force_n).abs() < 1e-3);
    assert!(rel(a.res.bit.tilt_inc_rad, b.res.bit.tilt_inc_rad) < 1e-6);
    assert!(rel(a.res.hook_load_n, b.res.hook_load_n) < 1e-9);
}

#[test]
fn axial_force_effect_on_side_force_matches_beam_column() {
    // The axial force's effect on bending (geometric stiffness) is what makes WOB change BHA
    // side forces: a model without it gives the same side force at any WOB. Reference: the
    // change of the Lubinski side force from WOB 0 to 100 kN at 10 and 30 deg
    // (analytical::pendulum, variable axial force); tolerance 2% of that change.
    let (ei, w_b, r) = collar_properties();
    for &inc in &[10.0_f64, 30.0] {
        let i = inc.to_radians();
        let r0 = variable_compression(ei, lateral_load(w_b, i), axial_gradient(w_b, i), 0.0, r).unwrap();
        let r1 = variable_compression(ei, lateral_load(w_b, i), axial_gradient(w_b, i), 100e3, r).unwrap();
        let f0 = -slick_collar(inc, 0.0, 80.0, 0.0, 0.25, true).res.bit.build_force_n;
        let f1 = -slick_collar(inc, 0.0, 80.0, 100.0, 0.25, true).res.bit.build_force_n;
        let (d_fem, d_ref) = (f1 - f0, r1.side_force - r0.side_force);
        println!(
            "inc {inc}: side force change with 100 kN WOB: FEM {:.4} kN, reference {:.4} kN",
            d_fem / 1e3,
            d_ref / 1e3
        );
        assert!(d_ref.abs() > 0.1 * r0.side_force, "the reference effect is significant");
        assert!(
            ((d_fem - d_ref) / d_ref).abs() < 0.02,
            "WOB effect off: {d_fem} vs {d_ref}"
        );
    }
}

/// Drill pipe only (5 in, 29 kg/m, 6-5/8 in joints) in a smooth build-and-hold well: vertical to
/// 300 m, build 3 deg/30 m to 30 deg, hold to 1,500 m (azimuth 20 deg), 8.5 in hole, 1.2 sg.
fn pipe_in_build_and_hold(mode: &str, friction: f64) -> (drillpath::case::Case, SolveResults) {
    let mut rows = vec!["md_m,inc_deg,azi_deg".to_string()];
    let mut md = 0.0;
    while md < 300.0 {
        rows.push(format!("{md},0,0"));
        md += 30.0;
    }
    rows.push("300,0,0".into());
    let mut md = 300.0_f64;
    while md < 600.0 {
        md = (md + 30.0).min(600.0);
        rows.push(format!("{md},{},20", (md - 300.0) * 3.0 / 30.0));
    }
    while md < 1500.0 {
        md = (md + 30.0).min(1500.0);
        rows.push(format!("{md},30,20"));
    }
    let case = format!(
        r#"
[well]
survey = "survey.csv"
hole = [{{ to_md = "3000 m", diameter = "8.5 in" }}]
[mud]
density = "1.2 sg"
[operation]
mode = "{mode}"
rpm = 60
friction = {friction}
viscous_torque = false
trip_speed = "0.3 m/s"
{DRILL_PIPE}[solver]
element_length = "2 m"
"#
    );
    let case = load_temp_case(&(rows.join("\n") + "\n"), &case);
    let model = Model::from_case(&case);
    let sol = solve(
        &model,
        &SolveControls {
            max_iterations: 500,
            ..Default::default()
        },
    )
    .unwrap();
    assert!(sol.converged, "{mode} f={friction} did not converge");
    let res = extract(&model, &sol, case.mud.density_kg_m3);
    (case, res)
}

#[test]
fn soft_string_limit_in_a_smooth_well() {
    // Reference: Johancsik et al. (1984) soft-string torque and drag (drillpath::models::softstring,
    // verified separately against docs/theory.md 10.5). Hook loads within 0.5% (measured
    // 0.00%, +0.19%, -0.20%: the same weight and friction, the contact pattern differs); torque
    // within 5%: a stiff string that rotates on the wall carries 1/sqrt(1+f^2) of the soft-string
    // torque (docs/theory.md 4, -3% at f = 0.25; measured -4.2% in this build and hold).
    for mode in ["rotating_off_bottom", "trip_in", "trip_out"] {
        let (case, fem) = pipe_in_build_and_hold(mode, 0.25);
        let soft = drillpath::models::softstring::from_case(&case, 1.0);
        let e_h = (fem.hook_load_n - soft.hook_load_n) / soft.hook_load_n;
        println!(
            "{mode}: hook load FEM {:.2} kN, soft {:.2} kN ({:+.2}%); torque FEM {:.3} kN.m, soft {:.3} kN.m",
            fem.hook_load_n / 1e3,
            soft.hook_load_n / 1e3,
            100.0 * e_h,
            fem.surface_torque_nm / 1e3,
            soft.surface_torque_nm / 1e3
        );
        assert!(e_h.abs() < 0.005, "{mode}: hook load off by {:.2}%", 100.0 * e_h);
        if soft.surface_torque_nm > 1.0 {
            let e_t = (fem.surface_torque_nm - soft.surface_torque_nm) / soft.surface_torque_nm;
            assert!(e_t.abs() < 0.05, "{mode}: torque off by {:.2}%", 100.0 * e_t);
        }
    }
}

#[test]
fn friction_acts_against_the_motion() {
    // Reference: docs/theory.md 6.1 / 6.5 exact checks. Rotation without axial motion: friction is
    // purely tangential, so the hook load equals the frictionless one (1%) while the surface
    // torque rises; running in with friction lowers the hook load, pulling out raises it.
    let (_, free) = pipe_in_build_and_hold("rotating_off_bottom", 0.0);
    let (_, rot) = pipe_in_build_and_hold("rotating_off_bottom", 0.25);
    let (_, down) = pipe_in_build_and_hold("trip_in", 0.25);
    let (_, up) = pipe_in_build_and_hold("trip_out", 0.25);
    assert!((rot.hook_load_n - free.hook_load_n).abs() < 0.01 * free.hook_load_n);
    assert!(
        free.surface_torque_nm.abs() < 1.0 && rot.surface_torque_nm > 1e3,
        "torque {}",
        rot.surface_torque_nm
    );
    assert!(
        down.hook_load_n < 0.95 * free.hook_load_n,
        "running in: {}",
        down.hook_load_n
    );
    assert!(
        up.hook_load_n > 1.05 * free.hook_load_n,
        "pulling out: {}",
        up.hook_load_n
    );
    assert!(
        down.surface_torque_nm.abs() < 1.0 && up.surface_torque_nm.abs() < 1.0,
        "no torque without rotation"
    );
}

#[test]
fn interior_point_contact_step_converges_in_few_iterations() {
    // The interior-point contact Newton (fem::solve::solve_interior_point_from) settles all contacts of a
    // short pendulum at once: same answer as the reference (0.5%), few Newton iterations.
    let case = slick_collar_case(30.0, 0.0, 40.0, 0.0, 0.5, "");
    let model = Model::from_case(&case);
    let mut state = model.initial_state();
    drillpath::models::fem::solve::start::soft_string_start(&model, &mut state);
    let sol =
        drillpath::models::fem::solve::solve_interior_point_from(&model, state, &SolveControls::default()).unwrap();
    assert!(sol.converged);
    println!(
        "interior-point contact Newton: {} iterations, {} factorizations",
        sol.stats.iterations, sol.stats.factorizations
    );
    assert!(sol.stats.iterations <= 12, "{} iterations", sol.stats.iterations);
    // warm-started Mehrotra interior point: a few factorizations per Newton step (it was ~20
    // to 60 before; issue 3)
    assert!(
        sol.stats.factorizations <= 4 * sol.stats.iterations,
        "{} factorizations",
        sol.stats.factorizations
    );
    let res = extract(&model, &sol, case.mud.density_kg_m3);
    let (ei, w_b, r) = collar_properties();
    let i = 30f64.to_radians();
    let reference = variable_compression(ei, lateral_load(w_b, i), axial_gradient(w_b, i), 0.0, r).unwrap();
    let e = (-res.bit.build_force_n - reference.side_force) / reference.side_force;
    assert!(e.abs() < 0.005, "side force off by {:.3}%", 100.0 * e);
}

/// Solve a generic case given survey rows and a string table; returns (converged, results).
fn solve_case(survey: &str, hole_in: f64, wob_kn: f64, strings: &str, extra_op: &str) -> Option<(bool, SolveResults)> {
    let case = format!(
        r#"
[well]
survey = "survey.csv"
hole = [{{ to_md = "20000 m", diameter = "{hole_in} in" }}]
[mud]
density = "1.2 sg"
[operation]
mode = "sliding"
wob = "{wob_kn} kN"
friction = 0.0
{extra_op}
{strings}
[solver]
max_iterations = 150
"#
    );
    let case = load_temp_case(survey, &case);
    let model = Model::from_case(&case);
    match solve(
        &model,
        &SolveControls {
            max_iterations: 150,
            ..Default::default()
        },
    ) {
        Ok(sol) => {
            let res = extract(&model, &sol, case.mud.density_kg_m3);
            Some((sol.converged, res))
        }
        Err(_) => None,
    }
}

/// The slick collar filling the 60 m test wells' strings to the surface.
const COLLAR_60M: &str = COLLAR_TO_SURFACE;

/// A converged result must be finite and in equilibrium; a failure must be reported, never a
/// panic (the caller gets `None` or `converged = false`, which the CLI turns into exit 2).
fn check_extreme(label: &str, out: Option<(bool, SolveResults)>) {
    match out {
        Some((true, res)) => {
            let rel = res.force_imbalance_n.norm() / res.largest_force_n;
            println!(
                "{label}: converged, build {:.3} kN, walk {:.3} kN, equilibrium {rel:.1e}",
                res.bit.build_force_n / 1e3,
                res.bit.walk_force_n / 1e3
            );
            assert!(rel < 1e-6, "{label}: equilibrium {rel:e}");
            for n in &res.nodes {
                assert!(
                    n.contact_force_n.is_finite() && n.axial_force_n.is_finite() && n.von_mises_pa.is_finite(),
                    "{label}: NaN"
                );
            }
        }
        Some((false, _)) => println!("{label}: did not converge (reported)"),
        None => println!("{label}: solve error (reported)"),
    }
}

#[test]
fn extremes_converge_or_fail_clearly() {
    // Issue 3 extremes: inclination 0, 90, 120 deg; DLS 20 deg/30 m; clearance 1 mm and
    // 100 mm. Each converges to a finite, equilibrated result or reports failure.
    for inc in [0.0, 90.0, 120.0] {
        let survey = format!("md_m,inc_deg,azi_deg\n0,{inc},30\n60,{inc},30\n");
        check_extreme(
            &format!("inclination {inc}"),
            solve_case(&survey, 8.5, 50.0, COLLAR_60M, ""),
        );
    }
    // 20 deg/30 m build from 10 to 50 deg over 60 m
    let survey = "md_m,inc_deg,azi_deg\n0,10,0\n60,50,0\n";
    check_extreme("DLS 20 deg/30 m", solve_case(survey, 8.5, 50.0, COLLAR_60M, ""));
    // clearance 1 mm (hole = collar + 2 mm) and 100 mm (hole = collar + 200 mm)
    let survey = "md_m,inc_deg,azi_deg\n0,30,0\n60,30,0\n";
    check_extreme(
        "clearance 1 mm",
        solve_case(survey, 6.5 + 2.0 / 25.4, 50.0, COLLAR_60M, ""),
    );
    check_extreme(
        "clearance 100 mm",
        solve_case(survey, 6.5 + 200.0 / 25.4, 50.0, COLLAR_60M, ""),
    );
    // all of the cases above must at least run to a reported end (no panic): reaching here
}

#[test]
fn compression_beyond_helical_buckling_keeps_the_pipe_in_the_hole() {
    // 5 in pipe in a horizontal 8.5 in hole under 3x the Chen-Lin-Cheatham helical load
    // (docs/theory.md 7.1: 230.9 kN at 90 deg): the pipe must lie in contact in changing
    // directions, never outside the hole.
    // a slightly wavy hole (+-0.2 deg every 10 m) seeds the buckling modes
    let mut survey = String::from("md_m,inc_deg,azi_deg\n");
    for k in 0..=12 {
        let w = if k % 2 == 0 { 0.2 } else { -0.2 };
        survey.push_str(&format!("{},{},{}\n", 10 * k, 90.0 + w, w));
    }
    let survey = survey.as_str();
    let out = solve_case(survey, 8.5, 3.0 * 230.9, DRILL_PIPE_BODY, "");
    if let Some((true, res)) = &out {
        // nodes with a gap (clearance > 0): the top node has none, it is held on the axis at
        // its reference MD by the boundary condition, and after the buckled pipe's axial
        // shortening it sits a few micrometres off the wavy axis at its new MD
        let max_off = res
            .nodes
            .iter()
            .filter_map(|n| n.clearance_m.filter(|&c| c > 0.0).map(|c| (n, c)))
            .map(|(n, c)| (n.disp_high_m.hypot(n.disp_right_m) - c) / c)
            .fold(f64::MIN, f64::max);
        let angles: Vec<f64> = res
            .nodes
            .iter()
            .filter(|n| n.contact_force_n > 1.0)
            .map(|n| n.contact_angle_deg)
            .collect();
        let spread = angles.iter().cloned().fold(f64::MIN, f64::max) - angles.iter().cloned().fold(f64::MAX, f64::min);
        println!("buckled pipe: max radial excess {max_off:.2e} of clearance, contact angle spread {spread:.1} deg, {} contacts", angles.len());
        assert!(max_off < 1e-3, "pipe outside the hole: {max_off}");
        assert!(spread > 30.0, "contacts should wander around the wall when buckled");
    }
    check_extreme("3x helical buckling load", out);
}

#[test]
fn mirrored_well_flips_the_walk_force() {
    // Reference: symmetry (docs/theory.md 10.4): mirroring the well (azimuth -> -azimuth) with
    // rotation off flips the walk force and the azimuthal tilt, leaves build force and
    // inclination tilt unchanged (tolerance 1e-6 relative to the side force).
    let a = "md_m,inc_deg,azi_deg\n0,20,10\n30,24,16\n60,28,22\n";
    let b = "md_m,inc_deg,azi_deg\n0,20,-10\n30,24,-16\n60,28,-22\n";
    let (ca, ra) = solve_case(a, 8.5, 60.0, COLLAR_60M, "").expect("solves");
    let (cb, rb) = solve_case(b, 8.5, 60.0, COLLAR_60M, "").expect("solves");
    assert!(ca && cb, "both converge");
    let scale = ra.bit.build_force_n.hypot(ra.bit.walk_force_n);
    println!(
        "walk {:.4} / {:.4} kN, build {:.4} / {:.4} kN",
        ra.bit.walk_force_n / 1e3,
        rb.bit.walk_force_n / 1e3,
        ra.bit.build_force_n / 1e3,
        rb.bit.build_force_n / 1e3
    );
    assert!(ra.bit.walk_force_n.abs() > 1e-3 * scale, "the 3D well has a walk force");
    assert!((ra.bit.walk_force_n + rb.bit.walk_force_n).abs() < 1e-6 * scale);
    assert!((ra.bit.build_force_n - rb.bit.build_force_n).abs() < 1e-6 * scale);
    assert!((ra.bit.tilt_azi_rad + rb.bit.tilt_azi_rad).abs() < 1e-6 * ra.bit.tilt_azi_rad.abs().max(1e-6));
}

#[test]
fn paper_method_runs_the_paper_scheme_not_the_default() {
    // `[solver] method = "paper"` must run the paper's scheme (fem::solve::solve_modified_newton),
    // not the default one under the user's choice: `solve` returns exactly what
    // solve_modified_newton does.
    let case = load_temp_case(
        "md_m,inc_deg,azi_deg\n0,10,0\n40,10,0\n",
        &format!(
            "[well]\nsurvey = \"survey.csv\"\nhole = [{{ to_md = \"40 m\", diameter = \"8.5 in\" }}]\n{COLLAR_TO_SURFACE}[solver]\nmethod = \"paper\"\n"
        ),
    );
    let model = Model::from_case(&case);
    let ctl = SolveControls {
        method: case.solver.method,
        ..Default::default()
    };
    let via_solve = solve(&model, &ctl).expect("paper scheme runs");
    let direct = drillpath::models::fem::solve::solve_modified_newton(&model, &ctl).expect("paper scheme runs");
    assert!(via_solve.converged);
    assert_eq!(via_solve.stats.iterations, direct.stats.iterations);
    assert_eq!(via_solve.stats.residual_history, direct.stats.residual_history);
    let a = extract(&model, &via_solve, case.mud.density_kg_m3);
    let b = extract(&model, &direct, case.mud.density_kg_m3);
    assert_eq!(a.bit.build_force_n, b.bit.build_force_n);
}

#[test]
fn wind_up_start_and_solution_match_saint_venant_torsion() {
    // Reference: Saint-Venant torsion of a uniform shaft fixed in twist at the top, with a bit
    // torque T and a uniform mud drag q per length (no wall friction): twist at the bit =
    // -(T L + q L^2 / 2) / GJ about the hole tangent. The start helper must give it to 1e-9
    // (it integrates the same torque exactly); the converged FEM solution to 1e-3 (a straight
    // vertical hole, no contact forces).
    let case = load_temp_case(
        "md_m,inc_deg,azi_deg\n0,0,0\n300,0,0\n",
        &format!(
            r#"
[well]
survey = "survey.csv"
hole = [{{ to_md = "300 m", diameter = "8.5 in" }}]
[mud]
density = "1.2 sg"
[operation]
mode = "drilling"
wob = "20 kN"
rpm = 60
bit_torque = "4 kN.m"
friction = 0.0
{COLLAR_TO_SURFACE}[solver]
element_length = "2 m"
bha_element_length = "2 m"
"#
        ),
    );
    let model = Model::from_case(&case);
    let gj = model.sections[0].gj;
    let length: f64 = model.sections.iter().map(|s| s.l0).sum();
    let q = model.mud_torque(0, 150.0);
    assert!(q > 0.0, "the default mud drag is on");
    let expected = -(4e3 * length + q * length * length / 2.0) / gj;
    let mut state = model.initial_state();
    drillpath::models::fem::solve::start::wind_up_start(&model, &mut state);
    let twist = |lam: &nalgebra::Matrix3<f64>| {
        let r = model.basis[0].transpose() * lam;
        drillpath::models::fem::element::rotation::log_so3(&r).x
    };
    let start = twist(&state.triads[0]);
    assert!(
        (start - expected).abs() < 1e-9 * expected.abs(),
        "start twist {start} vs {expected}"
    );
    let sol = solve(&model, &SolveControls::default()).unwrap();
    assert!(sol.converged);
    let fem = twist(&sol.state.triads[0]);
    println!("bit twist: FEM {fem:.6} rad, Saint-Venant {expected:.6} rad");
    assert!(
        (fem - expected).abs() < 1e-3 * expected.abs(),
        "FEM twist {fem} vs {expected}"
    );
}

#[test]
fn smoothed_start_limits_the_lateral_slope() {
    // The smoothed start (fem::solve::start::smooth_start) keeps each node's offset direction, never
    // moves a node farther from the axis, and leaves neighbouring offsets within
    // 2 START_MAX_SLOPE times their distance (one slope for the size of the offset, one for
    // its direction). Case: the J-shape example (stabilizers between collars, a side change at
    // the end of the build).
    let case = example("j-shape");
    let model = Model::from_case(&case);
    let mut raw = model.initial_state();
    drillpath::models::fem::solve::start::soft_string_start(&model, &mut raw);
    let mut smooth = raw.clone();
    drillpath::models::fem::solve::start::smooth_start(&model, &mut smooth);
    let axis: Vec<_> = (0..model.nodes())
        .map(|i| model.path.point_at(model.md_ref[i]).position)
        .collect();
    let mut worst_raw: f64 = 0.0;
    for (i, a) in axis.iter().enumerate() {
        let (d0, d1) = (raw.x[i] - a, smooth.x[i] - a);
        assert!(d1.norm() <= d0.norm() + 1e-12, "node {i} moved outward");
        assert!(d1.norm() < 1e-12 || d1.normalize().dot(&d0.normalize()) > 1.0 - 1e-9);
    }
    for e in 0..model.nodes() - 1 {
        let l = model.sections[e].l0;
        let lat = |x: &drillpath::geometry::Vec3, i: usize| x - axis[i];
        let jump = (lat(&smooth.x[e + 1], e + 1) - lat(&smooth.x[e], e)).norm();
        worst_raw = worst_raw.max((lat(&raw.x[e + 1], e + 1) - lat(&raw.x[e], e)).norm() / l);
        assert!(
            jump <= 2.0 * drillpath::models::fem::solve::start::START_MAX_SLOPE * l * (1.0 + 1e-9),
            "element {e}: lateral jump {jump} m over {l} m"
        );
    }
    // the raw start does have the kinks this removes
    assert!(
        worst_raw > 10.0 * drillpath::models::fem::solve::start::START_MAX_SLOPE,
        "{worst_raw}"
    );
}

#[test]
fn evaluation_reusing_element_responses_equals_a_fresh_one_bit_for_bit() {
    // Reference: `Model::evaluate` itself. The solver's final evaluation takes the element
    // responses of the previous evaluation at the same positions and triads
    // (`evaluate_reusing_elements`); residual, gap forces and nearest-axis MDs must be
    // identical to the last bit (rotating string with wall friction and mud drag torque, whose
    // lumped moments depend on the MDs the evaluation updates).
    let case = example("seed-daqing");
    let model = Model::from_case(&case);
    assert!(model.loads.omega_rad_s > 0.0 && model.loads.mud_viscosity_pa_s > 0.0);
    let sol = solve(&model, &SolveControls::default()).unwrap();
    assert!(sol.converged);
    // a state off the solution: positions and triads moved, MDs not yet updated
    let mut state = sol.state.clone();
    model.update(&mut state, &vec![1e-4; model.dofs()], 1.0);
    let gaps = GapTreatment::default();
    let prev = model.evaluate(&mut state.clone(), &gaps, None).elements;
    let (mut a, mut b) = (state.clone(), state);
    let ea = model.evaluate(&mut a, &gaps, None);
    let eb = model.evaluate_reusing_elements(&mut b, &gaps, prev);
    let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
    assert_eq!(bits(&ea.residual), bits(&eb.residual));
    assert_eq!(bits(&a.md), bits(&b.md));
    for (ga, gb) in ea.gaps.iter().zip(&eb.gaps) {
        assert_eq!(
            ga.as_ref().map(|g| g.normal_force.to_bits()),
            gb.as_ref().map(|g| g.normal_force.to_bits())
        );
    }
}

#[test]
fn stretched_start_and_solution_match_the_hanging_string_stretch() {
    // Reference: a string hanging in a straight vertical hole with WOB W at the bit, which is
    // held: the axial force of element e is N_e = -W + (buoyed weight below its centre), and
    // the top rises by u = sum N_e l0_e / EA_e (linear elasticity, no contact). The stretched
    // start (fem::solve::start::stretch_start) must put the top node there to 1e-9 (it integrates
    // the same forces); the converged FEM solution to 1e-3 (the co-rotational axial strain).
    let case = load_temp_case(
        "md_m,inc_deg,azi_deg\n0,0,0\n2000,0,0\n",
        &format!(
            r#"
[well]
survey = "survey.csv"
hole = [{{ to_md = "2000 m", diameter = "8.5 in" }}]
[mud]
density = "1.2 sg"
[operation]
mode = "drilling"
wob = "50 kN"
rpm = 60
friction = 0.0
{}{DRILL_PIPE}[solver]
element_length = "2 m"
bha_element_length = "1 m"
"#,
            collar("100 m")
        ),
    );
    let model = Model::from_case(&case);
    let top = model.nodes() - 1;
    let mut below = -model.loads.wob_n;
    let mut expected = 0.0;
    for (e, s) in model.sections.iter().enumerate() {
        let w = model.mesh.elements[e].buoyed_weight_n_per_m * s.l0;
        expected += (below + 0.5 * w) * s.l0 / s.ea;
        below += w;
    }
    assert!(
        expected > 0.1,
        "a 2 km string in tension stretches by decimetres: {expected} m"
    );
    let mut state = model.initial_state();
    drillpath::models::fem::solve::start::stretch_start(&model, &mut state);
    let z0 = model.path.point_at(model.md_ref[top]).position.z;
    let start = z0 - state.x[top].z;
    assert!(
        (start - expected).abs() < 1e-9 * expected,
        "start stretch {start} m vs {expected} m"
    );
    let sol = solve(&model, &SolveControls::default()).unwrap();
    assert!(sol.converged);
    let fem = z0 - sol.state.x[top].z;
    println!("top rise: FEM {fem:.6} m, start {start:.6} m, closed form {expected:.6} m");
    assert!(
        (fem - expected).abs() < 1e-3 * expected,
        "FEM stretch {fem} m vs {expected} m"
    );
}

#[test]
fn the_axis_tilt_along_a_pendulum_matches_the_closed_form_slope() {
    // Reference: the constant-compression pendulum (Lubinski 1953; analytical::pendulum) is
    // exact in a horizontal hole, where the axial force is the WOB all along the span: its slope
    // y'(x) is the tilt of the collar's axis toward the high side at x above the bit, the sag
    // angle a survey sensor there reads. Tolerance: 1% of the bit tilt at every node of the
    // span, and 1% at the nodes nearest 0.25 L and 0.5 L (0.25 m elements; measured below
    // 0.2%).
    let (ei, w_b, r) = collar_properties();
    let wob = 50e3;
    let run = slick_collar(90.0, 30.0, 80.0, wob / 1e3, 0.25, true);
    let reference = constant_compression(ei, w_b, r, wob).unwrap();
    let l = reference.tangency_length;
    let scale = reference.tilt.abs();
    for (i, n) in run.res.nodes.iter().enumerate() {
        let x = run.model.mesh.nodes[i].s_m;
        if x > l {
            break;
        }
        let slope = constant_compression_slope(ei, w_b, wob, &reference, x).unwrap();
        assert!(
            (n.tilt_high_rad - slope).abs() < 0.01 * scale,
            "x {x:.2} m: FEM {:.5} deg, reference {:.5} deg",
            n.tilt_high_rad.to_degrees(),
            slope.to_degrees()
        );
        assert!(
            n.tilt_right_rad.abs() < 1e-6 * scale,
            "no tilt out of the vertical plane"
        );
    }
    for fraction in [0.25, 0.5] {
        let (i, x) = run
            .model
            .mesh
            .nodes
            .iter()
            .enumerate()
            .map(|(i, m)| (i, m.s_m))
            .min_by(|a, b| (a.1 - fraction * l).abs().total_cmp(&(b.1 - fraction * l).abs()))
            .unwrap();
        let slope = constant_compression_slope(ei, w_b, wob, &reference, x).unwrap();
        let fem = run.res.nodes[i].tilt_high_rad;
        println!(
            "sag at {x:.2} m of {l:.2} m: FEM {:.5} deg, reference {:.5} deg ({:+.3}%)",
            fem.to_degrees(),
            slope.to_degrees(),
            100.0 * (fem - slope) / slope
        );
        assert!(((fem - slope) / slope).abs() < 0.01);
    }
}
