//! Stiff-string buckling (issue 5): the FEM's own sinusoidal onset against Dawson & Paslay
//! (1984), and the buckling marks of `drillpath::models::buckling` on the FEM's axial force.
//!
//! Run with `cargo test --release --test verification buckling:: -- --nocapture` to see the ramp.

use drillpath::analytical::buckling::sinusoidal_dawson_paslay;
use drillpath::case::Case;
use drillpath::models::buckling::{stiff_marks, BuckleState};
use drillpath::models::fem::model::{Model, State};
use drillpath::models::fem::results::{extract, SolveResults};
use drillpath::models::fem::solve::{solve, solve_interior_point_from, Solution, SolveControls};
use drillpath::models::string_solve::{pitch_warning, StringSolve};
use std::f64::consts::FRAC_PI_2;

use crate::common::{load_temp_case, pipe_properties, slid_bit_on_pipe, solve_whole, DRILL_PIPE_BODY};

/// The 5 in pipe body ([`DRILL_PIPE_BODY`]: no tool joints, 29 kg/m, 1.2 sg) in a horizontal
/// 8.5 in hole from the surface, 245 m long, with a seeded imperfection (azimuth alternating
/// 90 / 90.05 deg every 7 m), frictionless, 0.5 m elements, WOB `wob_n`.
fn horizontal_case(wob_n: f64) -> Case {
    let mut survey = String::from("md_m,inc_deg,azi_deg\n");
    for k in 0..=35 {
        let a = if k % 2 == 0 { 90.0 } else { 90.05 };
        survey.push_str(&format!("{},90,{a}\n", 7 * k));
    }
    let toml = format!(
        r#"
[well]
survey = "survey.csv"
hole = [{{ to_md = "245 m", diameter = "8.5 in" }}]
[mud]
density = "1.2 sg"
[operation]
mode = "sliding"
bit_md = "245 m"
wob = "{} kN"
rop = "0 m/h"
friction = 0.0
{DRILL_PIPE_BODY}[solver]
element_length = "0.5 m"
bha_element_length = "0.5 m"
"#,
        wob_n / 1e3
    );
    load_temp_case(&survey, &toml)
}

/// One load step of a continuation: the model of `case` solved from `prev` (the last step's
/// state) with the interior-point Newton, or cold for the first step.
fn continuation_step(case: &Case, prev: Option<State>, ctl: &SolveControls) -> (Model, Solution) {
    let mut model = Model::from_case(case);
    let sol = match prev {
        None => solve(&model, ctl).unwrap(),
        Some(st) => {
            model.consistent_tangent = true;
            solve_interior_point_from(&model, st, ctl).unwrap()
        }
    };
    (model, sol)
}

/// Largest turn of the contact point away from the low side (deg) over nodes in contact.
fn max_roll_deg(res: &SolveResults) -> f64 {
    res.nodes
        .iter()
        .filter(|n| n.contact_force_n > 0.0)
        .map(|n| (n.contact_angle_deg - 180.0).abs())
        .fold(0.0, f64::max)
}

#[test]
fn stiff_sinusoidal_onset_within_10_percent_of_dawson_paslay() {
    // Reference: Dawson & Paslay (1984), F_s = 2 sqrt(EI w_b sin I / r) (docs/theory.md 7.1, "FEM
    // check": ramp compression on a long horizontal pipe with a tiny imperfection; it leaves the
    // low side near F_s). The compression is ramped in 1% steps, each solve warm-started from
    // the last (continuation keeps the stable branch). Onset: first load at which the contact
    // point rolls more than 5 deg off the low side (the imperfection alone gives < 2 deg).
    // Tolerance: 10% (the issue); measured onset 1.02 F_s (finite length, 0.5 m elements).
    let (ei, w_b, r) = pipe_properties();
    let fs = sinusoidal_dawson_paslay(ei, w_b, FRAC_PI_2, r).unwrap();
    let ctl = SolveControls::default();
    let mut prev: Option<State> = None;
    let mut onset = None;
    for k in 0..=40 {
        let frac = 0.85 + 0.01 * k as f64;
        let case = horizontal_case(frac * fs);
        let (model, sol) = continuation_step(&case, prev.take(), &ctl);
        assert!(sol.converged, "not converged at {frac} F_s");
        let res = extract(&model, &sol, case.mud.density_kg_m3);
        let roll = max_roll_deg(&res);
        println!("F / F_s = {frac:.2}: contact roll {roll:.2} deg");
        if frac < 0.95 {
            assert!(roll < 2.0, "rolled {roll} deg already at {frac} F_s");
        }
        if roll > 5.0 {
            onset = Some(frac);
            // the marks on the FEM's axial force call the pipe buckled where it has rolled
            let m = stiff_marks(&case, &model, &res.nodes);
            let inner = &m[20..m.len() - 20];
            assert!(
                inner.iter().all(|x| x.state == BuckleState::Sinusoidal),
                "marks: {:?}",
                inner.iter().map(|x| x.state).collect::<Vec<_>>()
            );
            break;
        }
        prev = Some(sol.state);
    }
    let onset = onset.expect("no buckling up to 1.25 F_s");
    println!("stiff onset {onset:.2} F_s (F_s = {:.1} kN)", fs / 1e3);
    assert!((onset - 1.0).abs() < 0.10, "stiff onset {onset} F_s");
}

#[test]
fn marks_below_onset_are_not_buckled() {
    // Reference: Dawson & Paslay in the same horizontal hole: at 0.9 F_s the FEM's axial force
    // stays below the onset everywhere (marks `none`, the bit itself too since the pipe
    // reaches the face), and the pipe lies on the low side (roll < 2 deg).
    let (ei, w_b, r) = pipe_properties();
    let fs = sinusoidal_dawson_paslay(ei, w_b, FRAC_PI_2, r).unwrap();
    let case = horizontal_case(0.9 * fs);
    let model = Model::from_case(&case);
    let sol = solve(&model, &SolveControls::default()).unwrap();
    assert!(sol.converged);
    let res = extract(&model, &sol, case.mud.density_kg_m3);
    assert!(max_roll_deg(&res) < 2.0);
    let m = stiff_marks(&case, &model, &res.nodes);
    assert!(m.iter().all(|x| x.state == BuckleState::None));
    let worst = m
        .iter()
        .map(|x| x.compression_n / x.sinusoidal_n.unwrap())
        .fold(0.0, f64::max);
    assert!((worst - 0.9).abs() < 0.01, "largest compression / onset {worst}");
}

/// Post-buckling (issue 3, "compression beyond the helical buckling load: the string must lie
/// in contact in changing directions, not fly through the wall"): the horizontal pipe of the
/// onset test, compression ramped by continuation (each solve warm-started from the last) from
/// 0.9 F_s to 1.6 x the Chen-Lin-Cheatham helical load (2.26 F_s). References and tolerances:
/// every step converges with global equilibrium within 1e-6 of the largest force and
/// penetration within the contact tolerance (1e-4 of the clearance); beyond the helical load
/// the contact points spread round the wall, more than 60 deg either side of the low side
/// (docs/theory.md 7.1: the buckled pipe climbs the wall), while nodes stay inside the hole.
/// Measured: at 1.57 x helical the contact points roll 90 deg off the low side (contact angles
/// 90-270 deg). Beyond about 1.8 x helical
/// the quasi-static branch has a limit point (the snap to a full helix), where load
/// continuation stops: that case ends flagged non-converged (tests/verification/extremes.rs).
#[test]
fn post_buckled_pipe_lies_on_the_wall_beyond_the_helical_load() {
    let (ei, w_b, r) = pipe_properties();
    let fs = sinusoidal_dawson_paslay(ei, w_b, FRAC_PI_2, r).unwrap();
    let fh = std::f64::consts::SQRT_2 * fs; // Chen-Lin-Cheatham helical onset, horizontal
    let ctl = SolveControls::default();
    let mut prev: Option<State> = None;
    let mut frac = 0.9;
    let target = 1.6 * fh / fs;
    let mut spread = 0.0;
    while frac <= target + 1e-9 {
        let case = horizontal_case(frac * fs);
        let (model, sol) = continuation_step(&case, prev.take(), &ctl);
        assert!(sol.converged, "not converged at {frac:.2} F_s");
        assert!(
            sol.stats.max_penetration <= ctl.gap_tolerance,
            "penetration at {frac:.2} F_s"
        );
        let res = extract(&model, &sol, case.mud.density_kg_m3);
        let eq = res.force_imbalance_n.norm() / res.largest_force_n;
        assert!(eq < 1e-6, "equilibrium {eq:e} at {frac:.2} F_s");
        let clearance = (8.5 - 5.0) * 0.0254 / 2.0;
        for n in &res.nodes {
            let off = n.disp_high_m.hypot(n.disp_right_m);
            assert!(
                off <= clearance * (1.0 + 1e-3),
                "node at {:.1} m outside the hole: {off} m",
                n.md_m
            );
        }
        spread = max_roll_deg(&res);
        println!(
            "F / F_s = {frac:.2} ({:.2} helical): contact roll up to {spread:.0} deg",
            frac * fs / fh
        );
        prev = Some(sol.state);
        frac += if frac < 1.2 { 0.025 } else { 0.05 };
    }
    assert!(spread > 60.0, "contact roll only {spread} deg beyond the helical load");
}

/// The 5 in pipe body ([`DRILL_PIPE_BODY`]) below a 0.3 m bit (5 in, no stabilizer) in a
/// straight 8.5 in hole `length_m` long of inclination `inc_deg` (a hole at 0.5 deg turns from
/// vertical over the first 10 m; a steeper one starts at the surface), 1.2 sg mud, sliding
/// with `wob_kn` on the bit and wall friction `friction`, elements of `element` (e.g. "1 m";
/// None: the default mesh).
pub(crate) fn straight_hole_case(
    inc_deg: f64,
    length_m: f64,
    wob_kn: f64,
    friction: f64,
    element: Option<&str>,
) -> Case {
    let survey = if inc_deg < 1.0 {
        format!("md_m,inc_deg,azi_deg\n0,0,0\n10,{inc_deg},0\n{length_m},{inc_deg},0\n")
    } else {
        format!("md_m,inc_deg,azi_deg\n0,{inc_deg},0\n{length_m},{inc_deg},0\n")
    };
    let mesh = element.map_or(String::new(), |e| format!("element_length = \"{e}\"\n"));
    let string = slid_bit_on_pipe(length_m, wob_kn, friction);
    let text = format!(
        r#"
[well]
survey = "survey.csv"
hole = [{{ to_md = "{length_m} m", diameter = "8.5 in" }}]
{string}[solver]
{mesh}"#
    );
    load_temp_case(&survey, &text)
}

/// Mean wall force per length (N/m) and mean compression (N) of the reported nodes of `s`
/// strictly between `top_md` and `bottom_md` (m): the nodes' wall forces over the window's
/// length.
fn window(s: &drillpath::models::string_solve::StringSolve, top_md: f64, bottom_md: f64) -> (f64, f64) {
    let sel: Vec<_> = s
        .reported_nodes()
        .iter()
        .filter(|n| n.md_m > top_md && n.md_m < bottom_md)
        .collect();
    let wall = sel.iter().map(|n| n.contact_force_n).sum::<f64>() / (bottom_md - top_md);
    let f = -sel.iter().map(|n| n.axial_force_n).sum::<f64>() / sel.len() as f64;
    (wall, f)
}

/// Issue 16, a mesh too coarse for the helix's pitch: the near-vertical string of
/// [`vertical_helix_wall_force_within_15_percent_of_mitchell`] (100 kN on the bit) with 6 m
/// elements, longer than an eighth of the pitch `2 pi sqrt(2 EI / F)` (30.5 m at 100 kN).
/// Solved straight on that mesh, `string_solve::pitch_warning` names the pitch within 2% of the
/// formula at the largest compression, and its longest element (at most 6 m, above an eighth of
/// the pitch). `solve` answers on a refined mesh instead (the 6 m mesh's own buckled answer has
/// 0.56 and 0.15 of Mitchell's wall force, docs/performance.md "Pipe mesh"): its helical pipe's
/// elements resolve the pitch (no warning), and the answer is the 1 m mesh's (mesh
/// convergence): wall force per length within 15% of Mitchell's in the same two windows, total
/// wall force within 5% and hook load within 1 kN of the 1 m mesh's.
#[test]
fn a_mesh_too_coarse_for_the_helix_pitch_is_refined() {
    let case = straight_hole_case(0.5, 1000.0, 100.0, 0.0, Some("6 m"));
    let (ei, _, r) = pipe_properties();
    // the straight solve on the coarse mesh: the warning's content
    let (model, sol) = continuation_step(&case, None, &SolveControls::from_settings(&case.solver));
    let res = extract(&model, &sol, case.mud.density_kg_m3);
    let marks = stiff_marks(&case, &model, &res.nodes);
    let pitch = pitch_warning(&model, &res.nodes, &marks).expect("a 6 m mesh is too coarse");
    let f = res.nodes.iter().map(|n| -n.axial_force_n).fold(0.0, f64::max);
    let expected = 2.0 * std::f64::consts::PI * (2.0 * ei / f).sqrt();
    let number_after = |key: &str| -> f64 {
        pitch
            .split(key)
            .nth(1)
            .and_then(|t| t.split(" m").next())
            .and_then(|t| t.parse().ok())
            .unwrap_or_else(|| panic!("{pitch}"))
    };
    let named = number_after("sqrt(2 EI / F): ");
    assert!((named / expected - 1.0).abs() < 0.02, "{named} vs {expected}: {pitch}");
    let longest = number_after("elements of up to ");
    assert!(longest > expected / 8.0 && longest <= 6.0, "{pitch}");
    // solve answers on a refined mesh
    let coarse = solve_whole(&case);
    assert!(coarse.level.converged);
    let w = coarse.warnings(&case);
    assert!(!w.iter().any(|x| x.contains("coarsely resolved")), "{w:?}");
    let fem = coarse.level.fem.as_ref().unwrap();
    assert!(fem.model.nodes() > model.nodes(), "not refined");
    let res = &fem.results;
    assert!(res.force_imbalance_n.norm() / res.largest_force_n < 1e-6);
    for (a, b) in [(890.0, 990.0), (700.0, 800.0)] {
        let (wall, f) = window(&coarse, a, b);
        let mitchell = r * f * f / (4.0 * ei);
        assert!((wall / mitchell - 1.0).abs() < 0.15, "{a}-{b} m: {wall} vs {mitchell}");
    }
    let fine = solve_whole(&straight_hole_case(0.5, 1000.0, 100.0, 0.0, Some("1 m")));
    let total = |s: &StringSolve| -> f64 { s.reported_nodes().iter().map(|n| n.contact_force_n).sum() };
    let hook = |s: &StringSolve| s.level.fem.as_ref().unwrap().results.hook_load_n;
    println!(
        "refined 6 m mesh: {} nodes, wall force {:.1} kN, hook load {:.2} kN; 1 m mesh: {:.1} kN, {:.2} kN",
        fem.model.nodes(),
        total(&coarse) / 1e3,
        hook(&coarse) / 1e3,
        total(&fine) / 1e3,
        hook(&fine) / 1e3
    );
    assert!((total(&coarse) / total(&fine) - 1.0).abs() < 0.05);
    assert!((hook(&coarse) - hook(&fine)).abs() < 1e3);
}

/// Issue 16, a `loads` row on a mesh too coarse for the helix's pitch: the 6 m mesh of
/// [`a_mesh_too_coarse_for_the_helix_pitch_is_refined`] (100 kN on the bit, pitch about 30 m,
/// an eighth of it 3.8 m) solved as a whole-string `loads` row, which is not refined, flags
/// its helically buckled pipe (`stiff_coarse_for_pitch_m`). Reference: the pipe compressed
/// beyond the Chen-Lin-Cheatham helical onset `F_h` at the hole's 0.5 deg, the compression
/// falling by the buoyed weight `w` per metre above the bit: `(WOB - F_h) / w`; tolerance two
/// elements plus 10% of `F_h / w` (the model's onset near vertical is not exactly that
/// formula's; measured 8 m short of 326 m). The 1 m mesh
/// of the same row (an eighth of the pitch resolved) flags nothing.
#[test]
fn a_loads_row_too_coarse_for_the_helix_pitch_is_flagged() {
    use drillpath::analytical::buckling::helical_chen_lin_cheatham;
    use drillpath::loads::stiff::stiff_row;
    let (ei, w_b, r) = pipe_properties();
    let flagged = |element: &str| -> f64 {
        let case = straight_hole_case(0.5, 1000.0, 100.0, 0.0, Some(element));
        let (out, _) = stiff_row(&case, None);
        out.coarse_for_pitch_m().unwrap_or_else(|| panic!("{element}: {out:?}"))
    };
    let coarse = flagged("6 m");
    let onset = helical_chen_lin_cheatham(ei, w_b, 0.5f64.to_radians(), r).unwrap();
    let expected = (100e3 - onset) / w_b;
    println!(
        "6 m mesh: {coarse:.1} m flagged; (WOB - F_h) / w = {expected:.1} m (F_h {:.1} kN)",
        onset / 1e3
    );
    assert!(
        (coarse - expected).abs() < 12.0 + 0.1 * onset / w_b,
        "{coarse} vs {expected}"
    );
    assert_eq!(flagged("1 m"), 0.0);
}

/// Issue 16, the straight branch left: 5 in pipe compressed far beyond the helical onset in a
/// near-vertical hole (0.5 deg, 100 kN on the bit, 8.5 in hole, no friction). The Newton solve
/// first finds the straight pipe on the low side (about 2 N/m of wall force, an equilibrium past
/// its stability limit); the solve then re-solves from a helix along the wall
/// (`models::fem::solve::helix`) and keeps the buckled equilibrium. Reference: Mitchell (1988),
/// helical contact force per length `w_c = r F^2 / (4 EI)` in a vertical hole; tolerance 15%
/// (the issue) in two 100 m windows (compression about 87 and 40 kN: measured -7% and 0%), and
/// for the total wall force against the soft string's Mitchell force shown beside the solve.
/// Equilibrium within 1e-6 of the largest force, penetration within the gap tolerance, and no
/// warning of an unbuckled run.
#[test]
fn vertical_helix_wall_force_within_15_percent_of_mitchell() {
    let case = straight_hole_case(0.5, 1000.0, 100.0, 0.0, Some("1 m"));
    let s = solve_whole(&case);
    assert!(s.level.converged);
    let fem = s.level.fem.as_ref().unwrap();
    assert_eq!(fem.stats.helix_restart, Some(true));
    let res = &fem.results;
    assert!(res.force_imbalance_n.norm() / res.largest_force_n < 1e-6);
    assert!(fem.stats.max_penetration <= case.solver.tolerance);
    let (ei, _, r) = pipe_properties();
    for (a, b) in [(890.0, 990.0), (700.0, 800.0)] {
        let (wall, f) = window(&s, a, b);
        let mitchell = r * f * f / (4.0 * ei);
        println!(
            "{a}-{b} m: compression {:.1} kN, wall force {wall:.1} N/m, Mitchell {mitchell:.1} N/m",
            f / 1e3
        );
        assert!((wall / mitchell - 1.0).abs() < 0.15, "{a}-{b} m: {wall} vs {mitchell}");
    }
    let w = s.warnings(&case);
    assert!(!w.iter().any(|x| x.contains("unbuckled")), "{w:?}");
    assert!(!w.iter().any(|x| x.contains("coarsely resolved")), "{w:?}");
    // the soft string beside it (summary.json `soft_string_comparison`): without friction the
    // helix adds no drag (hook loads within 0.1 kN: both are the buoyed weight less the WOB), and
    // the soft string's Mitchell wall force summed over its helical length is the whole
    // string's total wall force within the same 15%
    let c = s
        .soft_comparison
        .expect("a converged whole solve shows the soft string");
    let total_wall: f64 = s.reported_nodes().iter().map(|n| n.contact_force_n).sum();
    println!(
        "hook load whole - soft {:.3} kN; wall force whole {:.1} kN, soft (Mitchell) {:.1} kN over {:.0} m",
        c.hook_load_difference_n() / 1e3,
        total_wall / 1e3,
        c.helical_wall_force_n / 1e3,
        c.helical_length_m
    );
    assert!(c.hook_load_difference_n().abs() < 100.0, "{c:?}");
    // and the soft string with the helix's drag has no more drag without friction (1e-9)
    assert!((c.helical_drag_hook_load_n - c.hook_load_n).abs() < 1e-9 * c.hook_load_n.abs().max(1.0));
    assert!(
        (total_wall / c.helical_wall_force_n - 1.0).abs() < 0.15,
        "{total_wall} vs {c:?}"
    );
    // the report's contact-force plot marks the helix: the helical intervals shaded and
    // Mitchell's force per node, which sums to the stiff marks' helical wall force (1e-9)
    use drillpath::report::display_units::UnitSystem;
    use drillpath::report::plots::legend_names;
    use drillpath::report::solve_report::{contact_force_chart, HELIX_SERIES};
    let si = UnitSystem::Si;
    let chart = contact_force_chart(&fem.results, &s.marks, si.depth(), si.force());
    assert!(HELIX_SERIES.iter().all(|h| legend_names(&chart).contains(h)));
    let per_node: f64 = chart.series[1].points.iter().map(|p| p.1).sum();
    let total = drillpath::models::buckling::helical_wall_force_n(&s.marks) / 1e3;
    assert!((per_node - total).abs() < 1e-9 * total, "{per_node} vs {total} kN");
}

/// Issue 16, inclined and horizontal holes: 600 m of 5 in pipe in a straight hole at 90 and
/// 60 deg from the surface, no friction, compressed uniformly (90 deg) by 280 and 460 kN (1.2
/// and 2.0 x the Chen-Lin-Cheatham helical onset, 231 kN) or 300 kN at 60 deg, on the default
/// mesh (3 m elements: the solve splits them to an eighth of the helix pitch, 2.3-1.8 m).
/// Reference: Mitchell's helical contact force `w_c = r F^2 / (4 EI)` taken as the mean wall
/// force per length in an inclined hole too: the helix's wall force far exceeds the weight's
/// lateral share `w_b sin I` (241 N/m; w_c 700-1900 N/m), whose projection on the turning
/// contact normal averages out over a pitch (Mitchell, "Simple frictional analysis of helical
/// buckling of tubing", SPE Drilling Engineering 1986, the form for a helix that wraps fully
/// round; \[uncertain] as a statement of that paper's inclined-hole result: the additive form
/// `w_c + w_b sin I` of some torque-and-drag codes lies 11-34% above the measured means).
/// Tolerance 15% over 100 m windows away from the ends; measured within 4%.
#[test]
fn inclined_helix_wall_force_within_15_percent_of_mitchell() {
    let (ei, _, r) = pipe_properties();
    for (inc, wob) in [(90.0, 280.0), (90.0, 460.0), (60.0, 300.0)] {
        let case = straight_hole_case(inc, 600.0, wob, 0.0, None);
        let t0 = std::time::Instant::now();
        let s = solve_whole(&case);
        let fem = s.level.fem.as_ref().unwrap();
        assert!(s.level.converged, "{inc} deg, {wob} kN");
        assert_eq!(fem.stats.helix_restart, Some(true), "{inc} deg, {wob} kN");
        let res = &fem.results;
        assert!(res.force_imbalance_n.norm() / res.largest_force_n < 1e-6);
        assert!(fem.stats.max_penetration <= case.solver.tolerance);
        for (a, b) in [(450.0, 550.0), (250.0, 350.0)] {
            let (wall, f) = window(&s, a, b);
            let mitchell = r * f * f / (4.0 * ei);
            println!(
                "{inc} deg, {wob} kN, {a}-{b} m: compression {:.1} kN, wall force {wall:.1} N/m, Mitchell {mitchell:.1} N/m ({} nodes, {:.2} s)",
                f / 1e3,
                fem.model.nodes(),
                t0.elapsed().as_secs_f64()
            );
            assert!(
                (wall / mitchell - 1.0).abs() < 0.15,
                "{inc} deg {wob} kN {a}-{b} m: {wall} vs {mitchell}"
            );
        }
    }
}

/// A limit (issue 16): with wall friction the re-solve from a helix does not converge (the
/// friction path stops at about 0.9 of the friction in this case) and the answer stays the
/// straight pipe past its stability limit: 5 in pipe at 100 kN in the near-vertical hole of
/// [`vertical_helix_wall_force_within_15_percent_of_mitchell`] with friction 0.3. Its wall
/// force per length is the weight's lateral share (about 4 N/m, below half Mitchell's `r F^2 /
/// (4 EI)`, 68 N/m) and the outputs say so: a warning names the run beyond the helical onset
/// where the contacts stay on one side (no such warning on the example wells, whose answers are
/// checked elsewhere). Update this test when the helix is reached with friction.
#[test]
fn an_unbuckled_solve_beyond_the_helical_onset_is_flagged() {
    let case = straight_hole_case(0.5, 1000.0, 100.0, 0.3, Some("1 m"));
    let s = solve_whole(&case);
    assert!(s.level.converged);
    assert_eq!(s.level.fem.as_ref().unwrap().stats.helix_restart, Some(false));
    let (ei, _, r) = pipe_properties();
    let (wall, f) = window(&s, 890.0, 990.0);
    let mitchell = r * f * f / (4.0 * ei);
    println!(
        "890-990 m: compression {:.1} kN, wall force {wall:.1} N/m, Mitchell {mitchell:.1} N/m",
        f / 1e3
    );
    assert!(
        wall < 0.5 * mitchell,
        "the solve found a buckled shape: update this test and the warning"
    );
    let w = s.warnings(&case);
    assert!(
        w.iter()
            .any(|x| x.contains("helical buckling onset") && x.contains("unbuckled")),
        "{w:?}"
    );
}

/// `loads` flags its stiff rows on the straight branch too (it does not re-solve from a helix):
/// the sliding row of the case of [`an_unbuckled_solve_beyond_the_helical_onset_is_flagged`]
/// (friction 0.3) and of the frictionless one (which `solve` re-solves into a helix) converge to
/// the straight pipe and give `stiff_unbuckled_helical_m` > 0. Reference: the helically
/// buckled length of the same solve's marks (the compression beyond the helical onset, the
/// interval the straight pipe lies unbuckled over), within the one-node spacing of the mark runs
/// (5 m); and 0 on a string in tension (the same hole pulled up: trip-out row at 0 WOB).
#[test]
fn a_loads_row_on_the_straight_branch_is_flagged() {
    use drillpath::loads::row::StiffOutcome;
    use drillpath::loads::stiff::stiff_row;
    use drillpath::models::buckling::summarize;
    for friction in [0.3, 0.0] {
        let case = straight_hole_case(0.5, 1000.0, 100.0, friction, Some("1 m"));
        let (out, solved) = stiff_row(&case, None);
        let unbuckled = out.unbuckled_helical_m().expect("converged");
        // the marks of the row's own converged state (its axial force)
        let (model, state) = solved.expect("converged");
        let ctl = SolveControls::from_settings(&case.solver);
        let sol = solve_interior_point_from(&model, state, &ctl).unwrap();
        assert!(sol.converged);
        let res = extract(&model, &sol, case.mud.density_kg_m3);
        let helical = summarize(&stiff_marks(&case, &model, &res.nodes)).helical_length_m;
        println!("friction {friction}: unbuckled {unbuckled:.1} m, helical {helical:.1} m");
        assert!(
            helical > 100.0 && (unbuckled - helical).abs() < 5.0,
            "{unbuckled} vs {helical}"
        );
    }
    let mut case = straight_hole_case(0.5, 1000.0, 0.0, 0.3, Some("1 m"));
    case.operation.mode = drillpath::case::Mode::TripOut;
    let (out, _) = stiff_row(&case, None);
    assert!(matches!(out, StiffOutcome::Converged { .. }), "{out:?}");
    assert_eq!(out.unbuckled_helical_m(), Some(0.0));
}
