//! Sliding drag (issue 20, item 2): a sliding string moves down the hole whatever the ROP, so
//! wall friction acts up the hole in full (`f N`); a rotating string at ROP 0 has no axial drag.
//! One rule (`Operation::motion`, `Motion::friction_split`) in the soft string, the stiff
//! models and the predictor. `solve` against `loads` on the same case: tests/cli/drag.rs.
//!
//! Run with `cargo test --release --test verification sliding:: -- --nocapture` to see the numbers.

use drillpath::case::{choose, Case, Fidelity, Level, Purpose};
use drillpath::models::fem::solve::SolveControls;
use drillpath::models::levels::{run, LevelResult};
use drillpath::predict::march::{predict, MarchSettings};

use crate::common::{fulcrum_bha, load_temp_case, pipe_properties, DRILL_PIPE, DRILL_PIPE_BODY, PIPE_TUBE};

/// Inclination of the straight hole, deg.
const INC_DEG: f64 = 45.0;
/// Length of the straight hole and of the string, m.
const LENGTH_M: f64 = 2000.0;
/// Friction coefficient.
const FRICTION: f64 = 0.25;
/// Weight on bit, kN.
const WOB_KN: f64 = 50.0;

/// Plain 5 in pipe body ([`DRILL_PIPE_BODY`], contact radius 63.5 mm) from the bit at 2,000 m
/// to the surface in a straight 45 deg hole of 8.5 in, 1.2 sg mud, friction 0.25, 50 kN WOB,
/// bit torque 0, no mud drag, in `mode` at 60 rpm and ROP `rop`.
fn straight_case(mode: &str, rop: &str) -> Case {
    let survey = format!("md_m,inc_deg,azi_deg\n0,{INC_DEG},30\n{LENGTH_M},{INC_DEG},30\n");
    load_temp_case(
        &survey,
        &format!(
            r#"
[well]
survey = "survey.csv"
hole = [{{ to_md = "{LENGTH_M} m", diameter = "8.5 in" }}]
[mud]
density = "1.2 sg"
[operation]
mode = "{mode}"
wob = "{WOB_KN} kN"
rpm = 60
rop = "{rop}"
friction = {FRICTION}
bit_torque = "0 kN.m"
viscous_torque = false
{DRILL_PIPE_BODY}[solver]
element_length = "2 m"
bha_element_length = "2 m"
max_iterations = 500
"#
        ),
    )
}

fn at(case: &Case, level: Level) -> LevelResult {
    let r = run(
        case,
        choose(Fidelity::Level(level), Purpose::Solve),
        &SolveControls::from_settings(&case.solver),
    )
    .unwrap();
    assert!(r.converged, "{level:?} did not converge");
    r
}

/// Reference: docs/theory.md 10.5 exact check (b) with the bit load: a straight section of
/// length `L` at inclination `I` carries the buoyed weight `w_b = w (1 - rho_mud/rho_steel)`
/// per length; its wall force is `w_b sin I` per length. Sliding (moving down, friction up the
/// hole) the hook load is `H = w_b L (cos I - f sin I) - WOB`; rotating at ROP 0 there is no
/// axial drag, `H = w_b L cos I - WOB`, and the soft string's torque is `f w_b sin I L R_c`.
/// Tolerance: soft 1e-9 (exact to round-off); whole 0.5% (the stiff pipe lifts off the wall
/// over about 12 m at the bit and at the top, where it is held on the axis: about 0.3%,
/// tests/verification/loads.rs). A sliding string without axial friction at ROP 0 would give the
/// rotating hook load, 41% higher here.
#[test]
fn straight_inclined_hole_sliding_drag_matches_closed_form() {
    let (_, w_b, _) = pipe_properties();
    let (i, l, f, wob) = (INC_DEG.to_radians(), LENGTH_M, FRICTION, WOB_KN * 1e3);
    let sliding = w_b * l * (i.cos() - f * i.sin()) - wob;
    let rotating = w_b * l * i.cos() - wob;
    let torque = f * w_b * i.sin() * l * 0.127 / 2.0;
    let slide = straight_case("sliding", "0 m/h");
    let drill = straight_case("drilling", "0 m/h");
    for (level, tol) in [(Level::Soft, 1e-9), (Level::Whole, 0.005)] {
        let s = at(&slide, level).hook_load_n.unwrap();
        let r = at(&drill, level);
        let h = r.hook_load_n.unwrap();
        let (es, er) = (s / sliding - 1.0, h / rotating - 1.0);
        println!(
            "{:<5} sliding {:.3} kN (closed form {:.3}, {:+.4}%), rotating {:.3} kN ({:.3}, {:+.4}%), torque {:.4} kN.m",
            level.name(),
            s / 1e3,
            sliding / 1e3,
            100.0 * es,
            h / 1e3,
            rotating / 1e3,
            100.0 * er,
            r.surface_torque_nm.unwrap() / 1e3
        );
        assert!(es.abs() < tol, "{level:?} sliding off by {:.4}%", 100.0 * es);
        assert!(er.abs() < tol, "{level:?} rotating off by {:.4}%", 100.0 * er);
        if level == Level::Soft {
            let t = r.surface_torque_nm.unwrap();
            assert!((t / torque - 1.0).abs() < 1e-9, "soft torque {t} vs {torque}");
        }
    }
}

/// A J-well (vertical to 600 m, 2.5 deg/30 m to 35 deg, hold to 2,000 m) with a fulcrum BHA
/// and 5 in pipe in 8.5 in hole, sliding at 50 kN WOB with friction 0.3 and ROP `rop`.
fn j_well_sliding(rop: &str, friction: f64) -> Case {
    let mut survey = vec!["md_m,inc_deg,azi_deg".to_string()];
    for k in 0..=200 {
        let md = 10.0 * k as f64;
        survey.push(format!("{md},{},45", ((md - 600.0) * 2.5 / 30.0).clamp(0.0, 35.0)));
    }
    load_temp_case(
        &(survey.join("\n") + "\n"),
        &format!(
            r#"
[well]
survey = "survey.csv"
hole = [{{ to_md = "2000 m", diameter = "8.5 in" }}]
[mud]
density = "1.2 sg"
[operation]
mode = "sliding"
wob = "50 kN"
rop = "{rop}"
friction = {friction}
{}{DRILL_PIPE}"#,
            fulcrum_bha()
        ),
    )
}

/// Reference: without rotation the friction is `f N` against the direction of motion whatever
/// the speed (docs/theory.md 1, "Motion"), so a sliding string gives the same hook load at
/// ROP 0 (the default) as at any ROP. Tolerance 1e-9 relative (the same equations). Without
/// friction at ROP 0 the hook load would be 428.5 kN against 355.1 kN at 10 m/h (soft; whole
/// 428.5 against 352.4 kN).
#[test]
fn sliding_loads_do_not_depend_on_the_rop() {
    let zero = j_well_sliding("0 m/h", 0.3);
    let ten = j_well_sliding("10 m/h", 0.3);
    for level in [Level::Soft, Level::Hybrid, Level::Whole] {
        let (a, b) = (
            at(&zero, level).hook_load_n.unwrap(),
            at(&ten, level).hook_load_n.unwrap(),
        );
        println!(
            "{:<6} sliding hook load: ROP 0 {:.3} kN, ROP 10 m/h {:.3} kN",
            level.name(),
            a / 1e3,
            b / 1e3
        );
        assert!((a / b - 1.0).abs() < 1e-9, "{level:?}: {a} vs {b}");
    }
}

/// A fulcrum BHA and 5 in pipe sliding at 80 kN WOB in a straight 20 deg hole to 300 m,
/// friction `friction`, ROP `rop`.
fn predictor_case(rop: &str, friction: f64) -> Case {
    load_temp_case(
        "md_m,inc_deg,azi_deg\n0,20,0\n300,20,0\n",
        &format!(
            r#"
[well]
survey = "survey.csv"
hole = [{{ to_md = "2000 m", diameter = "8.5 in" }}]
[mud]
density = "1.2 sg"
[operation]
mode = "sliding"
wob = "80 kN"
rop = "{rop}"
friction = {friction}
{}{PIPE_TUBE}tool_joint_od = "6.625 in"
"#,
            fulcrum_bha()
        ),
    )
}

/// Reference: the same rule in the predictor (its stiff BHA model takes the operation's motion):
/// a sliding prediction does not depend on the ROP, 1e-9 relative on the bit's build force and
/// the predicted inclination after 30 m. The friction-free prediction is printed for scale.
#[test]
fn sliding_prediction_does_not_depend_on_the_rop() {
    let go = |case: &Case| {
        let mut s = MarchSettings::from_case(case);
        s.step_m = 5.0;
        let p = predict(case, 300.0, 330.0, &s, &mut |_| {}).unwrap();
        let last = p.steps.last().unwrap();
        (p.steps[0].bit.build_force_n, last.inc_rad.to_degrees())
    };
    let (f0, i0) = go(&predictor_case("0 m/h", 0.25));
    let (f10, i10) = go(&predictor_case("10 m/h", 0.25));
    let (ff, i_f) = go(&predictor_case("0 m/h", 0.0));
    println!(
        "sliding prediction: build force {:.4} / {:.4} kN (frictionless {:.4}), inclination at 330 m {:.5} / {:.5} deg (frictionless {:.5})",
        f0 / 1e3,
        f10 / 1e3,
        ff / 1e3,
        i0,
        i10,
        i_f
    );
    assert!((f0 / f10 - 1.0).abs() < 1e-9, "build force {f0} vs {f10}");
    assert!((i0 / i10 - 1.0).abs() < 1e-9, "inclination {i0} vs {i10}");
}
