//! The motor's reactive torque turning a sliding bent housing's toolface (`[operation]
//! reactive_torque`, docs/theory.md 9.9 "Reactive torque"): against the closed-form twist of a
//! free string, the FEM's own torsion, the sense of the turn and its growth with WOB.

use crate::common::{load_temp_case, try_load_temp_case};
use crate::steering::motor_string;
use drillpath::case::Case;
use drillpath::models::fem::solve::{Solution, SolveControls};
use drillpath::models::fem::{bha, model::Model, solve::solve, solve::toolface::solve_holding_toolface};

/// The motor of [`motor_string`] (1.5 deg, pad 8.375 in) on the bottom of a well whose survey is
/// `survey`, bit at `md` m, sliding at toolface 0 with `wob`, friction `friction`, the operation
/// lines `extra` (e.g. a given `bit_torque`), 1.2 sg mud.
fn case(survey: &str, md: f64, wob: &str, friction: f64, extra: &str) -> Case {
    let text = format!(
        r#"
[well]
survey = "survey.csv"
hole = [{{ to_md = "{md} m", diameter = "8.5 in" }}]
[mud]
density = "1.2 sg"
[operation]
mode = "sliding"
bit_md = "{md} m"
wob = "{wob}"
friction = {friction}
reactive_torque = true
{extra}
{}
[solver]
element_length = "3 m"
bha_element_length = "0.5 m"
tolerance = 1e-4
"#,
        motor_string(1.5, 2.0, 8.375)
    );
    load_temp_case(survey, &text)
}

/// Solve `model` holding its toolface (with the reactive turn).
fn held(model: &mut Model, case: &Case) -> Solution {
    let ctl = SolveControls::from_settings(&case.solver);
    let sol = solve_holding_toolface(model, &ctl, |m| solve(m, &ctl)).unwrap();
    assert!(sol.converged);
    sol
}

/// A free string: a vertical well without wall friction (no capacity to hold the torque), 2
/// kN.m given, the whole string from the bit at 600 m. Reference: the closed form of a shaft
/// held at the top, `Δ = T Σ L_k / (G J_k)` over the components from the bend (2 m above the
/// bit) to the surface, `J = π (OD⁴ − ID⁴) / 32`, `G` steel's; 1% allowed (measured to
/// round-off). Second reference, independent of the reactive model: the FEM's own twist of the
/// string under the same torque at the bit (sliding carries it to the rotary table), which the
/// turn must equal for the housing to sit at the set toolface less the turn with its kink
/// unturned: the kink's correction within 1% of the turn (measured 0: the first solve's housing
/// is already within the toolface tolerance, 0.005 deg, of the set toolface less the turn).
#[test]
fn free_string_turns_by_the_closed_form_twist() {
    let survey = "md_m,inc_deg,azi_deg\n0,0,0\n600,0,0\n";
    let c = case(survey, 600.0, "5 kN", 0.0, "bit_torque = \"2 kN.m\"");
    let mut model = Model::from_case(&c);
    let sol = held(&mut model, &c);
    let t = sol.stats.reactive_turn.expect("a reactive turn");
    let g = drillpath::string::material::steel().shear_modulus_pa;
    let j =
        |od_in: f64, id_in: f64| std::f64::consts::PI / 32.0 * ((od_in * 0.0254).powi(4) - (id_in * 0.0254).powi(4));
    // from the bend (2 m above the bit) up: the rest of the 7.25 m motor, sub, MWD, collar,
    // HWDP, drill pipe to the surface
    let legs = [
        (0.25 + 0.45 + 0.3 + 7.25 - 2.0, j(6.75, 3.5)),
        (0.9, j(6.75, 2.8125)),
        (9.0, j(6.75, 3.25)),
        (9.2, j(6.75, 2.8125)),
        (280.0, j(5.0, 3.0)),
    ];
    let below_pipe: f64 = 0.25 + 0.45 + 0.3 + 7.25 + 0.9 + 9.0 + 9.2 + 280.0;
    let pipe = (600.0 - below_pipe, j(5.0, 4.276));
    let closed: f64 = legs.iter().chain([&pipe]).map(|(l, jj)| 2000.0 * l / (g * jj)).sum();
    let fem = model.kink_correction_rad();
    println!(
        "turn {:.5} rad, closed form {closed:.5} rad, held {:?}; kink correction {fem:.2e} rad",
        t.turn_rad, t.held_m
    );
    assert!(
        (t.turn_rad - closed).abs() < 0.01 * closed,
        "{} vs {closed}",
        t.turn_rad
    );
    assert!(t.held_m.is_none(), "a free string is held by the rotary table");
    assert!(
        fem.abs() < 0.01 * closed,
        "the FEM's twist differs from the turn by {fem} rad"
    );
    let tf = model.housing_toolface(&sol.state).unwrap();
    assert!(
        (tf + t.turn_rad).abs() < 1e-4,
        "housing at {tf} rad, not the set 0 less the turn"
    );
}

/// The turn is to the left and grows with the WOB: the 30 deg well of the steering tests (bit at
/// 2,000 m), friction 0.25, the motor's torque from the bit law with `bit_friction` 1 (Pessier &
/// Fear: 2.9, 4.3, 5.8 kN.m at 40, 60, 80 kN), the predictor's cut model. Reference: the sense
/// of the reactive torque (counter-clockwise seen from above: the gravity toolface falls) and
/// the monotonic torque; the housing in the solved state at the set toolface less the turn
/// within the toolface tolerance; the hole drilled at the motor yield turns left (negative
/// right-turn rate) where the reactive torque is off gives none (0.01 deg/30 m).
#[test]
fn the_turn_is_left_and_grows_with_wob() {
    use drillpath::predict::steer::steady_turn;
    let survey = "md_m,inc_deg,azi_deg\n0,0,45\n500,0,45\n1000,30,45\n2000,30,45\n";
    let mut last = 0.0;
    for wob in ["40 kN", "60 kN", "80 kN"] {
        let c = case(survey, 2000.0, wob, 0.25, "");
        let mut c = c.clone();
        c.bit_rock.bit_friction = 1.0;
        let md = c.operation.bit_md_m;
        let cut = bha::default_cut_m(&c.string, 0.2159, 30f64.to_radians(), c.mud.density_kg_m3);
        let mut model = bha::bha_model(&c, &c.well.path, &c.well.hole, md, cut);
        model.consistent_tangent = true;
        let sol = held(&mut model, &c);
        let t = sol.stats.reactive_turn.expect("a reactive turn");
        let tf = model.housing_toolface(&sol.state).unwrap();
        println!(
            "WOB {wob}: torque {:.2} kN.m, turn {:.3} deg, held at {:?} m; housing at {:.3} deg",
            t.torque_nm / 1e3,
            t.turn_rad.to_degrees(),
            t.held_m,
            tf.to_degrees()
        );
        assert!(t.turn_rad > last, "{wob}: turn {} not above {last}", t.turn_rad);
        assert!((tf + t.turn_rad).abs() < 1e-4, "housing at {tf}, turn {}", t.turn_rad);
        last = t.turn_rad;
        if wob == "60 kN" {
            let ctl = SolveControls::from_settings(&c.solver);
            let on = steady_turn(&c, &c.bit_rock, &ctl).unwrap();
            let mut off = c.clone();
            off.operation.reactive_torque = false;
            let off = steady_turn(&off, &c.bit_rock, &ctl).unwrap();
            let d = |k: f64| k.to_degrees() * 30.0;
            println!(
                "yield on: build {:.3} right {:.3}; off: build {:.3} right {:.3} deg/30 m",
                d(on.build_rad_per_m),
                d(on.right_rad_per_m),
                d(off.build_rad_per_m),
                d(off.right_rad_per_m)
            );
            assert!(d(on.right_rad_per_m) < -0.01 && d(off.right_rad_per_m).abs() < 0.01);
        }
    }
}

/// `reactive_torque` not a boolean is one error naming the key.
#[test]
fn bad_reactive_torque_is_named() {
    let survey = "md_m,inc_deg,azi_deg\n0,0,0\n600,0,0\n";
    let text = format!(
        "[well]\nsurvey = \"survey.csv\"\nhole = [{{ to_md = \"600 m\", diameter = \"8.5 in\" }}]\n[operation]\nmode = \"sliding\"\nwob = \"5 kN\"\nreactive_torque = \"yes\"\n{}",
        motor_string(1.5, 2.0, 8.375)
    );
    let e = try_load_temp_case(survey, &text).unwrap_err().to_string();
    assert!(e.contains("reactive_torque") && e.contains("true or false"), "{e}");
}
