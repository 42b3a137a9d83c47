//! Rotary steerable systems (docs/theory.md 9.10): push-the-bit pads and the point-the-bit
//! hinge in the stiff model, their steering tendency, against references stated per test.

use crate::common::{load_temp_case, STEERING_UPPER_STRING};
use crate::steering::motor_case_with;
use drillpath::case::Case;
use drillpath::models::fem::solve::SolveControls;
use drillpath::predict::steer::{steady_turn, SteadyTurn};

/// Degrees per 30 m of a curvature in rad/m.
fn deg30(k: f64) -> f64 {
    k.to_degrees() * 30.0
}

/// The lower string of the RSS assembly: 8.5 in bit 0.25 m, then `rss` (the tool's table
/// lines, between the bit and a 8.375 in string stabilizer 0.5 m long at 4.0-4.5 m), MWD,
/// collar, HWDP and pipe to surface (the stiff parts as the motor assembly of
/// tests/verification/steering.rs).
pub fn rss_string(rss: &str) -> String {
    format!(
        r#"
[[string]]
type = "bit"
od = "8.5 in"
length = "0.25 m"
{rss}
[[string]]
type = "stabilizer"
od = "8.375 in"
body_od = "6.75 in"
id = "3.5 in"
length = "0.5 m"
{STEERING_UPPER_STRING}"#
    )
}

/// A push-the-bit tool 3.75 m long (0.25-4.0 m above the bit), pads 1 m above the bit.
pub fn push_tool(force_kn: f64, ratio: f64) -> String {
    format!(
        "[[string]]\ntype = \"rss\"\nrss_type = \"push-the-bit\"\nod = \"6.75 in\"\nid = \"3.5 in\"\nlength = \"3.75 m\"\npad_force = \"{force_kn} kN\"\npad_position = \"1 m\"\nratio = {ratio}"
    )
}

/// A point-the-bit tool 3.75 m long, the hinge 1 m above the bit.
pub fn point_tool(deflection_deg: f64, ratio: f64) -> String {
    format!(
        "[[string]]\ntype = \"rss\"\nrss_type = \"point-the-bit\"\nod = \"6.75 in\"\nid = \"3.5 in\"\nlength = \"3.75 m\"\ndeflection_angle = \"{deflection_deg} deg\"\nhinge_position = \"1 m\"\nratio = {ratio}"
    )
}

/// The same body as two subs split 1 m above the bit (the tool's node, without the tool).
fn plain_tool() -> String {
    "[[string]]\ntype = \"sub\"\nod = \"6.75 in\"\nid = \"3.5 in\"\nlength = \"0.75 m\"\n[[string]]\ntype = \"sub\"\nod = \"6.75 in\"\nid = \"3.5 in\"\nlength = \"3 m\"".into()
}

/// The assembly with `tool` in the straight hole of the motor tests (inclination `inc_deg`,
/// azimuth 45 deg, bit at 2,000 m, 60 kN, friction 0.25, isotropic law), `mode` at toolface
/// `toolface_deg`.
fn rss_case(inc_deg: f64, tool: &str, mode: &str, toolface_deg: f64) -> Case {
    let azi = if inc_deg == 0.0 { 0.0 } else { 45.0 };
    motor_case_with(inc_deg, azi, &rss_string(tool), mode, toolface_deg, "60 kN")
}

fn turn(case: &Case) -> SteadyTurn {
    steady_turn(case, &case.bit_rock, &SolveControls::from_settings(&case.solver)).unwrap()
}

/// Acceptance: an RSS at zero pad force, or zero deflection, reproduces the plain string (the
/// same body as subs, a node at the tool's position) to the last bit: `solve` at `bha`,
/// `hybrid` and `whole`, rotating, a steady tendency and a 20 m prediction. The pad force and
/// the kink are the only things the tool adds (at zero: nothing); any other difference (the
/// mesh, the averaging of the ratio's neutral share) would show here. At ratio 1 every number
/// is equal; at ratio 0.6 the mean of the steering and neutral directions (equal here) rounds
/// differently, which the curvature's finite-difference Jacobian (step 1e-5 rad/m) amplifies:
/// 1e-9 rad/m (2e-6 deg/30 m) allowed on the tendency; the march's implicit steps stop at their
/// own tolerance, so the predicted direction after 20 m may move by 1e-8 rad (measured 1.1e-9)
/// and its bit force by the string solve's tolerance (not compared there).
#[test]
fn zero_force_and_zero_deflection_reproduce_the_plain_string() {
    use drillpath::case::fidelity::{Choice, Fidelity, Level};
    use drillpath::models::levels::run;
    use drillpath::predict::march::{predict, MarchSettings};
    let plain = rss_case(30.0, &plain_tool(), "drilling", 40.0);
    let ctl = SolveControls::from_settings(&plain.solver);
    let end = |p: &drillpath::predict::march::Prediction| {
        let s = p.steps.last().unwrap();
        (s.inc_rad, s.azi_rad, s.bit.build_force_n)
    };
    let settings = MarchSettings::from_case(&plain);
    let p_plain = end(&predict(&plain, 1900.0, 1920.0, &settings, &mut |_| {}).unwrap());
    let t_plain = turn(&plain);
    for tool in [
        push_tool(0.0, 1.0),
        point_tool(0.0, 1.0),
        push_tool(0.0, 0.6),
        point_tool(0.0, 0.6),
    ] {
        let exact = !tool.ends_with("0.6");
        let c = rss_case(30.0, &tool, "drilling", 40.0);
        assert!(c.string.rss().is_some());
        for level in [Level::Bha, Level::Hybrid, Level::Whole] {
            let choice = Choice {
                requested: Fidelity::Level(level),
                level,
                reason: String::new(),
            };
            let a = run(&c, choice.clone(), &ctl).unwrap();
            let b = run(&plain, choice, &ctl).unwrap();
            let bit = |r: &drillpath::models::levels::LevelResult| {
                r.bit
                    .map(|b| (b.wob_n, b.build_force_n, b.walk_force_n, b.tilt_inc_rad, b.torque_nm))
            };
            assert_eq!(bit(&a), bit(&b), "{level:?}");
            assert_eq!(a.hook_load_n, b.hook_load_n, "{level:?}");
        }
        let t = turn(&c);
        let p = end(&predict(&c, 1900.0, 1920.0, &settings, &mut |_| {}).unwrap());
        if exact {
            assert_eq!(
                (t.build_rad_per_m, t.right_rad_per_m),
                (t_plain.build_rad_per_m, t_plain.right_rad_per_m)
            );
            assert_eq!(p, p_plain);
        } else {
            assert!(
                (t.build_rad_per_m - t_plain.build_rad_per_m).abs() < 1e-9,
                "{t:?} {t_plain:?}"
            );
            assert!(
                (t.right_rad_per_m - t_plain.right_rad_per_m).abs() < 1e-9,
                "{t:?} {t_plain:?}"
            );
            assert!(
                (p.0 - p_plain.0).abs() < 1e-8 && (p.1 - p_plain.1).abs() < 1e-8,
                "{p:?} {p_plain:?}"
            );
        }
    }
}

/// Acceptance: mirror symmetry. At 30 deg inclination (azimuth 45 deg) toolfaces 90 and 270 deg
/// give the same build and opposite walk; in a vertical hole (magnetic toolface) 0 and 180 deg
/// give opposite build and no turn; for both kinds, the string sliding (axial friction, which
/// is symmetric about the vertical plane through the hole, as gravity is; rotation's tangential
/// friction is not). Exact up to the solver's tolerance: 0.005 deg/30 m allowed.
#[test]
fn rss_toolface_mirror_symmetry() {
    for tool in [push_tool(20.0, 1.0), point_tool(1.0, 1.0)] {
        let a = turn(&rss_case(30.0, &tool, "sliding", 90.0));
        let b = turn(&rss_case(30.0, &tool, "sliding", 270.0));
        println!(
            "tf 90: build {:.4} right {:.4}; tf 270: build {:.4} right {:.4} deg/30 m",
            deg30(a.build_rad_per_m),
            deg30(a.right_rad_per_m),
            deg30(b.build_rad_per_m),
            deg30(b.right_rad_per_m)
        );
        assert!(deg30(a.right_rad_per_m) > 0.5, "toolface 90 turns right");
        assert!(deg30(a.build_rad_per_m - b.build_rad_per_m).abs() < 0.005);
        assert!(deg30(a.right_rad_per_m + b.right_rad_per_m).abs() < 0.005);
        let n = turn(&rss_case(0.0, &tool, "sliding", 0.0));
        let s = turn(&rss_case(0.0, &tool, "sliding", 180.0));
        println!(
            "vertical tf 0: build {:.4} right {:.4}; tf 180: build {:.4} right {:.4} deg/30 m",
            deg30(n.build_rad_per_m),
            deg30(n.right_rad_per_m),
            deg30(s.build_rad_per_m),
            deg30(s.right_rad_per_m)
        );
        assert!(deg30(n.build_rad_per_m) > 0.5, "toolface 0 (north) builds toward north");
        assert!(deg30(n.build_rad_per_m + s.build_rad_per_m).abs() < 0.005);
        assert!(deg30(n.right_rad_per_m).abs() < 0.005 && deg30(s.right_rad_per_m).abs() < 0.005);
    }
}

/// Acceptance: the dogleg capability rises monotonically with the pad force, the deflection and
/// the steering ratio (rotating at 60 rpm, toolface 0, 30 deg inclination): each step at least
/// 0.05 deg/30 m above the last.
#[test]
fn rss_dogleg_rises_with_force_deflection_and_ratio() {
    let dogleg = |tool: String| {
        let t = turn(&rss_case(30.0, &tool, "drilling", 0.0));
        deg30(t.dogleg_rad_per_m())
    };
    let series: [(&str, Vec<String>); 3] = [
        (
            "pad force 0-40 kN",
            [0.0, 5.0, 10.0, 20.0, 40.0].map(|f| push_tool(f, 1.0)).to_vec(),
        ),
        (
            "deflection 0-1 deg",
            [0.0, 0.1, 0.25, 0.5, 1.0].map(|d| point_tool(d, 1.0)).to_vec(),
        ),
        (
            "ratio 0-1",
            [0.0, 0.25, 0.5, 0.75, 1.0].map(|r| push_tool(20.0, r)).to_vec(),
        ),
    ];
    for (what, tools) in series {
        let d: Vec<f64> = tools.into_iter().map(dogleg).collect();
        println!("{what}: {d:.3?} deg/30 m");
        for w in d.windows(2) {
            assert!(w[1] > w[0] + 0.05, "{what}: {d:?}");
        }
    }
}

/// The lateral deflection (m, along the toolface direction) at the tool's node of a 10 m `rss`
/// string alone (6.75 in x 3.5 in, the tool at 4 m from the bit) in a horizontal frictionless
/// hole 1 m wide (no wall contact), pushed by `wob_kn` (kN), toolface 90 deg, the whole-string
/// model: the bit held on the axis and free to tilt, the top held on the axis laterally and free
/// to tilt, a simply supported beam-column under a constant axial force. Returned: the
/// deflection with the tool minus that with the tool neutral (removing gravity's sag, which is
/// vertical and, at constant axial force, superposes), and the tool body's EI (N.m2).
fn lateral_at_tool(tool_keys: &str, wob_kn: f64) -> (f64, f64) {
    use drillpath::models::fem::model::Model;
    use drillpath::models::fem::solve::solve;
    let survey = "md_m,inc_deg,azi_deg\n0,90,0\n10,90,0\n";
    let case = format!(
        r#"
[well]
survey = "survey.csv"
hole = [{{ to_md = "10 m", diameter = "1 m" }}]
[mud]
density = "1.2 sg"
[operation]
mode = "sliding"
wob = "{wob_kn} kN"
toolface = "90 deg"
friction = 0
viscous_torque = false
[[string]]
type = "rss"
od = "6.75 in"
id = "3.5 in"
length = "10 m"
{tool_keys}
[solver]
element_length = "0.25 m"
bha_element_length = "0.25 m"
"#
    );
    let c = load_temp_case(survey, &case);
    let mut neutral = c.clone();
    neutral.string = c.string.rss_neutral();
    let ctl = SolveControls::from_settings(&c.solver);
    let at = |case: &Case| {
        let model = Model::from_case(case);
        let sol = solve(&model, &ctl).unwrap();
        assert!(sol.converged);
        let node = model
            .mesh
            .pad
            .map(|p| p.node)
            .or(model.mesh.bend.map(|b| b.node))
            .unwrap();
        assert!((model.mesh.nodes[node].s_m - 4.0).abs() < 1e-9);
        let t = model.basis[node].column(0).into_owned();
        let d = drillpath::geometry::frame::toolface_direction(&t, 90f64.to_radians());
        (sol.state.x[node] - model.axis_ref[node]).dot(&d)
    };
    (at(&c) - at(&neutral), c.string.components[0].ei_nm2())
}

/// The pad force and the hinge against closed-form beam-columns (analytical::beam_column,
/// Timoshenko & Gere 1961: a point load `f` at `a` on a simply supported span `l` under axial
/// force `P`, `y(a) = f [sin(ka) sin(kb)/(k sin kl) - ab/l]/P`; an imposed rotation `theta` at
/// the hinge, `y(a) = theta sin(ka) sin(kb)/(k sin kl)`, toward the side opposite the
/// toolface), without axial force and at 30% of the Euler load: within 0.5% (measured 0.03%; the co-rotational
/// elements of 0.25 m and the geometric nonlinearity of a 0.2-1% rotation).
#[test]
fn pad_force_and_hinge_match_closed_form_beam_columns() {
    use drillpath::analytical::beam_column::{hinge_rotation_deflection, point_load_deflection};
    use drillpath::analytical::buckling::euler_pinned;
    for frac in [0.0, 0.3] {
        let push = "rss_type = \"push-the-bit\"\npad_force = \"10 kN\"\npad_position = \"4 m\"";
        let (_, ei) = lateral_at_tool(push, 1.0);
        let p = frac * euler_pinned(ei, 10.0);
        let (y_pad, _) = lateral_at_tool(push, p.max(1.0) / 1e3);
        let ref_pad = point_load_deflection(ei, 10.0, 10e3, 4.0, p.max(1.0)).unwrap();
        let point = "rss_type = \"point-the-bit\"\ndeflection_angle = \"0.5 deg\"\nhinge_position = \"4 m\"";
        let (y_hinge, _) = lateral_at_tool(point, p.max(1.0) / 1e3);
        let ref_hinge = -hinge_rotation_deflection(ei, 10.0, 0.5f64.to_radians(), 4.0, p.max(1.0)).unwrap();
        println!(
            "P = {:.0} kN: pad {:.3} mm (closed form {:.3}); hinge {:.3} mm (closed form {:.3})",
            p / 1e3,
            y_pad * 1e3,
            ref_pad * 1e3,
            y_hinge * 1e3,
            ref_hinge * 1e3
        );
        assert!(((y_pad - ref_pad) / ref_pad).abs() < 0.005, "pad {y_pad} vs {ref_pad}");
        assert!(
            ((y_hinge - ref_hinge) / ref_hinge).abs() < 0.005,
            "hinge {y_hinge} vs {ref_hinge}"
        );
    }
}

/// Bad steering input names its key: a `[[steering]]` ratio outside [0, 1], a ratio for a
/// string without an RSS, and a string with both a bent housing and an RSS.
#[test]
fn bad_rss_plans_are_named() {
    use crate::common::try_load_temp_case;
    use crate::steering::motor_string;
    let survey = "md_m,inc_deg,azi_deg\n0,0,45\n500,0,45\n1000,30,45\n2000,30,45\n";
    let case = |string: &str, plan: &str| {
        format!(
            "[well]\nsurvey = \"survey.csv\"\nhole = [{{ to_md = \"2000 m\", diameter = \"8.5 in\" }}]\n[operation]\nmode = \"drilling\"\nwob = \"60 kN\"\nrpm = 60\n{string}\n{plan}\n"
        )
    };
    let err = |string: &str, plan: &str| {
        try_load_temp_case(survey, &case(string, plan))
            .expect_err("an error")
            .to_string()
    };
    let plan = |r: f64| format!("[[steering]]\nfrom_md = 1900\nto_md = 1950\nmode = \"rotate\"\nratio = {r}\n");
    assert!(try_load_temp_case(survey, &case(&rss_string(&push_tool(10.0, 0.2)), &plan(0.7))).is_ok());
    let e = err(&rss_string(&push_tool(10.0, 0.2)), &plan(1.2));
    assert!(e.contains("`steering[0].ratio`") && e.contains("outside [0, 1]"), "{e}");
    let e = err(&motor_string(1.5, 2.0, 8.375), &plan(0.5));
    assert!(
        e.contains("`steering[0].ratio`") && e.contains("needs a rotary steerable system"),
        "{e}"
    );
    let both = motor_string(1.5, 2.0, 8.375).replacen(
        "[[string]]\ntype = \"sub\"",
        "[[string]]\ntype = \"rss\"\nrss_type = \"push-the-bit\"\npad_force = \"10 kN\"\npad_position = \"8.5 m\"\nod = \"6.75 in\"\nid = \"3.5 in\"\nlength = \"0.5 m\"\n[[string]]\ntype = \"sub\"",
        1,
    );
    let e = err(&both, "");
    assert!(e.contains("rss_type") && e.contains("one steering tool"), "{e}");
}

/// The RSS works at every stiff level: the bit side forces of a push-the-bit (20 kN) and a
/// point-the-bit (1 deg) tool at toolface 40 deg, rotating at 60 rpm, from `bha`, `hybrid` and
/// `whole` agree within 1% of the largest (the pad force is fixed in space and the hinge held at
/// its toolface, whatever the whole string's wind-up), each solve converged, and the whole
/// string's global balance includes the pad force (equilibrium error below 1e-6 of the largest
/// force).
#[test]
fn rss_at_every_stiff_level() {
    use drillpath::case::fidelity::{Choice, Fidelity, Level};
    use drillpath::models::levels::run;
    for tool in [push_tool(20.0, 1.0), point_tool(1.0, 1.0)] {
        let c = rss_case(30.0, &tool, "drilling", 40.0);
        let ctl = SolveControls::from_settings(&c.solver);
        let forces: Vec<(f64, f64)> = [Level::Bha, Level::Hybrid, Level::Whole]
            .into_iter()
            .map(|level| {
                let choice = Choice {
                    requested: Fidelity::Level(level),
                    level,
                    reason: String::new(),
                };
                let r = run(&c, choice, &ctl).unwrap();
                assert!(r.converged, "{level:?}");
                if let (Level::Whole, Some(f)) = (level, r.fem.as_ref()) {
                    let e = f.results.force_imbalance_n.norm() / f.results.largest_force_n;
                    assert!(e < 1e-6, "equilibrium error {e}");
                }
                let b = r.bit.unwrap();
                println!(
                    "{level:?}: build {:.3} walk {:.3} kN",
                    b.build_force_n / 1e3,
                    b.walk_force_n / 1e3
                );
                (b.build_force_n, b.walk_force_n)
            })
            .collect();
        let scale = forces.iter().map(|f| f.0.hypot(f.1)).fold(0.0, f64::max);
        for f in &forces[1..] {
            assert!(
                (f.0 - forces[0].0).hypot(f.1 - forces[0].1) < 0.01 * scale,
                "{forces:?}"
            );
        }
    }
}

/// A slide sheet's optional `ratio` column sets an RSS's ratio per interval (an empty cell keeps
/// the tool's); a ratio outside [0, 1], or for a string without an RSS, is an error naming the
/// sheet's line and the column.
#[test]
fn slide_sheet_ratio_column() {
    use crate::common::case_dir;
    use crate::steering::motor_string;
    let survey = "md_m,inc_deg,azi_deg\n0,0,45\n500,0,45\n1000,30,45\n2000,30,45\n";
    let load = |string: &str, sheet: &str| {
        let case = format!(
            "slide_sheet = \"sheet.csv\"\n[well]\nsurvey = \"survey.csv\"\nhole = [{{ to_md = \"2000 m\", diameter = \"8.5 in\" }}]\n[operation]\nmode = \"drilling\"\nwob = \"60 kN\"\nrpm = 60\n{string}\n"
        );
        let dir = case_dir(survey, &case);
        std::fs::write(dir.path().join("sheet.csv"), sheet).unwrap();
        drillpath::io::case_toml::load_case(&dir.path().join("case.toml"), &Default::default())
    };
    let rss = rss_string(&push_tool(10.0, 0.2));
    let c = load(
        &rss,
        "md_from,md_to,mode,toolface_deg,ratio\n1900,1920,rotate,0,0.7\n1920,1950,rotate,90,\n",
    )
    .unwrap();
    let ratios: Vec<Option<f64>> = c.steering.intervals.iter().map(|iv| iv.ratio).collect();
    assert_eq!(ratios, vec![Some(0.7), None]);
    assert_eq!(c.steered(&c.steering.intervals[0]).string.rss().unwrap().ratio, 0.7);
    assert_eq!(c.steered(&c.steering.intervals[1]).string.rss().unwrap().ratio, 0.2);
    let e = load(&rss, "md_from,md_to,mode,toolface_deg,ratio\n1900,1920,rotate,0,1.3\n")
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("sheet.csv") && e.contains("line 2") && e.contains("ratio") && e.contains("outside [0, 1]"),
        "{e}"
    );
    let e = load(
        &motor_string(1.5, 2.0, 8.375),
        "md_from,md_to,mode,toolface_deg,ratio\n1900,1920,slide,0,0.5\n",
    )
    .unwrap_err()
    .to_string();
    assert!(
        e.contains("line 2") && e.contains("needs a rotary steerable system"),
        "{e}"
    );
}
