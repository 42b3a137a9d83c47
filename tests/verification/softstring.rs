//! Soft-string torque and drag (`drillpath::models::softstring`) against docs/theory.md 10.5: the worked
//! example (Johancsik, Friesen & Dawson 1984 model), the exact checks (a) hanging weight,
//! (b) straight inclined section, (c) capstan, and the ordering property
//! trip out >= rotating >= trip in.
//!
//! Run with `cargo test --release --test verification softstring:: -- --nocapture` to see the numbers.

use drillpath::case::{Case, Mode};
use drillpath::geometry::{HoleSize, Station, Survey, Vec3, WellPath};
use drillpath::models::softstring::{
    from_case, soft_string, soft_string_stiff_contact, SoftStringInput, SoftStringResult,
};
use drillpath::string::material::steel;
use drillpath::string::{Component, ComponentKind, DrillString};
use drillpath::units::G;
use proptest::prelude::*;
use proptest::test_runner::FileFailurePersistence;
use std::f64::consts::{FRAC_PI_2, TAU};

use crate::common::{example, load_temp_case, pipe_properties, DRILL_PIPE};

// ----------------------------------------------------------------------------------------------
// Helpers
// ----------------------------------------------------------------------------------------------

fn path(st: &[(f64, f64, f64)]) -> WellPath {
    let s = Survey::new(st.iter().map(|&(m, i, a)| Station::from_deg(m, i, a)).collect()).unwrap();
    WellPath::new(&s, Vec3::zeros()).unwrap()
}

/// 5 in drill pipe (4.276 in bore), steel, given weight in air (N/m) and tool-joint OD (m).
fn pipe(len: f64, w_air: f64, tj: Option<f64>) -> Component {
    Component {
        kind: ComponentKind::Pipe,
        name: "5 in pipe".into(),
        length_m: len,
        bottom_m: 0.0,
        body_od_m: 0.127,
        contact_od_m: 0.127,
        contact_length_m: 0.0,
        id_m: 4.276 * 0.0254,
        tool_joint_od_m: tj,
        joint_length_m: 9.144,
        material: steel(),
        weight_air_n_per_m: w_air,
        sensor_to_bit_m: None,
        bend: None,
        rss: None,
    }
}

/// The straight section of docs/theory.md 10.5 exact check (b): 1,200 m of 300 N/m pipe (contact
/// radius `R_C`, its tool joints) hanging from 100 m MD in a straight 40 deg hole (azimuth
/// 30 deg) of 8.5 in, 1.1 sg mud, friction `F`, bit at 1,300 m, no WOB or bit torque, 3.3 m
/// elements.
struct StraightSection {
    p: WellPath,
    hole: HoleSize,
    s: DrillString,
    /// Inclination, rad.
    inc: f64,
    /// Buoyed weight, N/m.
    w_b: f64,
}

impl StraightSection {
    const L: f64 = 1200.0;
    const F: f64 = 0.3;
    const R_C: f64 = 0.0841375;

    fn new() -> StraightSection {
        StraightSection {
            p: path(&[(0.0, 40.0, 30.0), (1500.0, 40.0, 30.0)]),
            hole: HoleSize::uniform(0.2159),
            s: DrillString {
                components: vec![pipe(Self::L, 300.0, Some(2.0 * Self::R_C))],
            },
            inc: 40f64.to_radians(),
            w_b: 300.0 * (1.0 - 1100.0 / 7850.0),
        }
    }

    /// Inclination (rad), pipe length (m), friction, contact radius (m) and buoyed weight
    /// (N/m), in that order.
    fn values(&self) -> (f64, f64, f64, f64, f64) {
        (self.inc, Self::L, Self::F, Self::R_C, self.w_b)
    }

    /// The pass's input with axial speed `v_a` (m/s) and rotary speed `omega` (rad/s).
    fn input(&self, v_a: f64, omega: f64) -> SoftStringInput<'_> {
        SoftStringInput {
            path: &self.p,
            hole: &self.hole,
            string: &self.s,
            mud_density_kg_m3: 1100.0,
            bit_md_m: 1300.0,
            wob_n: 0.0,
            bit_torque_nm: 0.0,
            axial_speed_m_s: v_a,
            omega_rad_s: omega,
            friction: Self::F,
            max_element_m: 3.3,
        }
    }
}

fn rel(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs()
}

/// docs/theory.md 10.5 worked example written as a case (survey CSV + TOML) in a temp dir:
/// [`DRILL_PIPE`] from the bit at 2,500 m to the surface.
fn worked_example_case() -> Case {
    load_temp_case(
        "md_m,inc_deg,azi_deg\n0,0,0\n500,0,0\n950,45,0\n2500,45,0\n",
        &format!(
            r#"
name = "docs/theory.md 10.5 worked example"
[well]
survey = "survey.csv"
hole = [ {{ to_md = "2500 m", diameter = "8.5 in" }} ]
[mud]
density = "1.2 sg"
[operation]
mode = "trip_out"
bit_md = "2500 m"
friction = 0.25
{DRILL_PIPE}"#
        ),
    )
}

/// The worked example's inputs built directly (R_c = 84.14 mm exactly as in docs/theory.md).
struct Worked {
    path: WellPath,
    hole: HoleSize,
    string: DrillString,
}

fn worked_direct() -> Worked {
    Worked {
        path: path(&[
            (0.0, 0.0, 0.0),
            (500.0, 0.0, 0.0),
            (950.0, 45.0, 0.0),
            (2500.0, 45.0, 0.0),
        ]),
        hole: HoleSize::uniform(8.5 * 0.0254),
        string: DrillString {
            components: vec![pipe(2500.0, 29.0 * G, Some(2.0 * 0.08414))],
        },
    }
}

impl Worked {
    fn run(&self, wob: f64, tb: f64, v_a: f64, omega: f64, el: f64) -> SoftStringResult {
        soft_string(&SoftStringInput {
            path: &self.path,
            hole: &self.hole,
            string: &self.string,
            mud_density_kg_m3: 1200.0,
            bit_md_m: 2500.0,
            wob_n: wob,
            bit_torque_nm: tb,
            axial_speed_m_s: v_a,
            omega_rad_s: omega,
            friction: 0.25,
            max_element_m: el,
        })
    }
}

const RPM60: f64 = TAU; // 60 rpm in rad/s
const ROP12: f64 = 12.0 / 3600.0; // 12 m/h in m/s

// ----------------------------------------------------------------------------------------------
// 1. docs/theory.md 10.5 worked example
// ----------------------------------------------------------------------------------------------

/// docs/theory.md 10.5: pulling out 617.85 kN, running in 381.20 kN, rotating 482.13 kN with
/// 9.827 kN.m (1 m elements); drilling (WOB 50 kN, T_b 2 kN.m, 60 rpm, 12 m/h) 431.45 kN and
/// 10.99 kN.m. Tolerance 0.1 % (the published numbers have 4-5 digits).
#[test]
fn worked_example_1m_elements() {
    let w = worked_direct();
    let out = w.run(0.0, 0.0, -0.3, 0.0, 1.0);
    let inn = w.run(0.0, 0.0, 0.3, 0.0, 1.0);
    let rot = w.run(0.0, 0.0, 0.0, RPM60, 1.0);
    let dri = w.run(50e3, 2e3, ROP12, RPM60, 1.0);
    println!(
        "1 m: out {:.3} kN, in {:.3} kN, rot {:.3} kN / {:.4} kN.m, drilling {:.3} kN / {:.4} kN.m",
        out.hook_load_n / 1e3,
        inn.hook_load_n / 1e3,
        rot.hook_load_n / 1e3,
        rot.surface_torque_nm / 1e3,
        dri.hook_load_n / 1e3,
        dri.surface_torque_nm / 1e3
    );
    assert!(rel(out.hook_load_n, 617.85e3) < 1e-3);
    assert!(rel(inn.hook_load_n, 381.20e3) < 1e-3);
    assert!(rel(rot.hook_load_n, 482.13e3) < 1e-3);
    assert!(rel(rot.surface_torque_nm, 9.827e3) < 1e-3);
    assert!(rel(dri.hook_load_n, 431.45e3) < 1e-3);
    assert!(rel(dri.surface_torque_nm, 10.99e3) < 1e-3);
    // tripping without rotation: no torque; boundary values at the bit
    assert_eq!(out.surface_torque_nm, 0.0);
    assert!(!out.frictionless && !rot.frictionless);
    assert_eq!(dri.points[0].tension_n, -50e3);
    assert_eq!(dri.points[0].torque_nm, 2e3);
    assert_eq!(out.points.len(), 2501);
    assert!((out.points[0].md_m - 2500.0).abs() < 1e-12 && out.points[2500].md_m.abs() < 1e-9);
}

/// docs/theory.md 10.5, 10 m elements: 617.50 / 381.31 / 482.13 kN, 9.810 kN.m (0.1 %); the
/// 1 m -> 10 m change itself must have the published sign and size (pulling out drops by
/// about 0.35 kN, running in rises by about 0.11 kN).
#[test]
fn worked_example_10m_elements() {
    let w = worked_direct();
    let out = w.run(0.0, 0.0, -0.3, 0.0, 10.0);
    let inn = w.run(0.0, 0.0, 0.3, 0.0, 10.0);
    let rot = w.run(0.0, 0.0, 0.0, RPM60, 10.0);
    println!(
        "10 m: out {:.3} kN, in {:.3} kN, rot {:.3} kN / {:.4} kN.m",
        out.hook_load_n / 1e3,
        inn.hook_load_n / 1e3,
        rot.hook_load_n / 1e3,
        rot.surface_torque_nm / 1e3
    );
    assert!(rel(out.hook_load_n, 617.50e3) < 1e-3);
    assert!(rel(inn.hook_load_n, 381.31e3) < 1e-3);
    assert!(rel(rot.hook_load_n, 482.13e3) < 1e-3);
    assert!(rel(rot.surface_torque_nm, 9.810e3) < 1e-3);
    let out1 = w.run(0.0, 0.0, -0.3, 0.0, 1.0);
    let inn1 = w.run(0.0, 0.0, 0.3, 0.0, 1.0);
    let d_out = out1.hook_load_n - out.hook_load_n;
    let d_in = inn.hook_load_n - inn1.hook_load_n;
    println!("1 m - 10 m: out {d_out:.1} N, in {:.1} N", -d_in);
    assert!((d_out - 350.0).abs() < 100.0, "{d_out}");
    assert!((d_in - 110.0).abs() < 60.0, "{d_in}");
}

/// The same example read from a case file (`load_case`, 6-5/8 in joints: R_c = 84.1375 mm)
/// through `from_case` for every mode; 0.1 % of docs/theory.md 10.5.
#[test]
fn worked_example_from_case_file() {
    let base = worked_example_case();
    let run = |mode: Mode, wob: f64, tb: Option<f64>| {
        let mut c = base.clone();
        c.operation.mode = mode;
        c.operation.wob_n = wob;
        c.operation.bit_torque_nm = tb;
        c.operation.rpm = 60.0;
        c.operation.rop_m_s = ROP12;
        from_case(&c, 1.0)
    };
    let out = run(Mode::TripOut, 0.0, None);
    let inn = run(Mode::TripIn, 0.0, None);
    let rot = run(Mode::RotatingOffBottom, 0.0, None);
    let dri = run(Mode::Drilling, 50e3, Some(2e3));
    assert!(rel(out.hook_load_n, 617.85e3) < 1e-3, "{}", out.hook_load_n);
    assert!(rel(inn.hook_load_n, 381.20e3) < 1e-3, "{}", inn.hook_load_n);
    assert!(rel(rot.hook_load_n, 482.13e3) < 1e-3, "{}", rot.hook_load_n);
    assert!(rel(rot.surface_torque_nm, 9.827e3) < 1e-3, "{}", rot.surface_torque_nm);
    assert!(rel(dri.hook_load_n, 431.45e3) < 1e-3, "{}", dri.hook_load_n);
    assert!(rel(dri.surface_torque_nm, 10.99e3) < 1e-3, "{}", dri.surface_torque_nm);

    // Bit torque by Pessier & Fear when not given: mu_b W D_b / 3 (no bit component here:
    // D_b = hole diameter 8.5 in), exact at the bit node.
    let pf = run(Mode::Drilling, 50e3, None);
    let expect = base.bit_rock.bit_friction * 50e3 * 8.5 * 0.0254 / 3.0;
    assert!(rel(pf.points[0].torque_nm, expect) < 1e-12);
    // Sliding: no rotation, motion down at ROP: friction fully axial, no friction torque.
    let sl = run(Mode::Sliding, 50e3, None);
    assert_eq!(sl.surface_torque_nm, 0.0);
    assert!(sl.hook_load_n < dri.hook_load_n);

    // Hook load given instead of WOB: the WOB is solved for (back to 50 kN within 1 N).
    let mut c = base.clone();
    c.operation.mode = Mode::Drilling;
    c.operation.rpm = 60.0;
    c.operation.rop_m_s = ROP12;
    c.operation.bit_torque_nm = Some(2e3);
    c.operation.wob_n = 0.0;
    c.operation.hook_load_n = Some(dri.hook_load_n);
    let solved = from_case(&c, 1.0);
    assert!(
        (solved.points[0].tension_n + 50e3).abs() < 1.0,
        "{}",
        solved.points[0].tension_n
    );
}

// ----------------------------------------------------------------------------------------------
// 2. Exact checks
// ----------------------------------------------------------------------------------------------

/// Sum over components of w_b (TVD at the component's bottom - TVD at its top), N.
fn hanging_weight(p: &WellPath, s: &DrillString, mud: f64, bit_md: f64) -> f64 {
    s.components
        .iter()
        .map(|c| {
            let z_bot = p.point_at(bit_md - c.bottom_m).position.z;
            let z_top = p.point_at(bit_md - c.top_m()).position.z;
            c.buoyed_weight_n_per_m(mud) * (z_bot - z_top)
        })
        .sum()
}

/// docs/theory.md 10.5 exact check (a): rotating without axial motion, hook load = sum w_b dTVD
/// (1e-9 relative) on the 3D j-shape well (mixed BHA, hole sections with their own friction,
/// azimuth walk) and a 3D random-ish survey; the worked example gives 482.12 kN (docs/theory.md:
/// 482.129 kN; 240.92 N/m x 2001.158 m = 482.12 kN).
#[test]
fn exact_hanging_weight_when_rotating() {
    let case = example("j-shape");
    let mut c = case.clone();
    c.operation.mode = Mode::RotatingOffBottom;
    for el in [1.0, 9.0, 30.0] {
        let r = from_case(&c, el);
        let w = hanging_weight(&c.well.path, &c.string, c.mud.density_kg_m3, c.operation.bit_md_m);
        println!(
            "j-shape rotating ({el} m): {:.3} kN vs {:.3} kN, {:.3} kN.m",
            r.hook_load_n / 1e3,
            w / 1e3,
            r.surface_torque_nm / 1e3
        );
        assert!(rel(r.hook_load_n, w) < 1e-9);
        assert!(r.surface_torque_nm > 0.0);
    }

    let p = path(&[
        (0.0, 0.0, 0.0),
        (300.0, 0.0, 0.0),
        (700.0, 25.0, 40.0),
        (1100.0, 60.0, 95.0),
        (1500.0, 88.0, 150.0),
        (1900.0, 70.0, 260.0),
        (2300.0, 95.0, 300.0),
    ]);
    let mut dc = pipe(150.0, 1300.0, None);
    dc.kind = ComponentKind::Collar;
    dc.body_od_m = 0.1651;
    dc.contact_od_m = 0.1651;
    let mut dp = pipe(2100.0, 33.6 * G, Some(0.1683));
    dp.bottom_m = 150.0;
    let s = DrillString {
        components: vec![dc, dp],
    };
    let hole = HoleSize::uniform(0.2159);
    let r = soft_string(&SoftStringInput {
        path: &p,
        hole: &hole,
        string: &s,
        mud_density_kg_m3: 1300.0,
        bit_md_m: 2250.0,
        wob_n: 0.0,
        bit_torque_nm: 0.0,
        axial_speed_m_s: 0.0,
        omega_rad_s: 12.0,
        friction: 0.35,
        max_element_m: 7.3,
    });
    let w = hanging_weight(&p, &s, 1300.0, 2250.0);
    assert!(rel(r.hook_load_n, w) < 1e-9, "{} vs {w}", r.hook_load_n);

    let ex = worked_direct().run(0.0, 0.0, 0.0, RPM60, 10.0);
    let (_, w_b, _) = pipe_properties();
    assert!(rel(ex.hook_load_n, w_b * 2001.158) < 1e-6);
}

/// docs/theory.md 10.5 exact check (b): straight section of length L at inclination I from zero
/// tension: F = w_b L (cos I +/- f sin I), torque f w_b L sin I R_c (1e-9 relative).
#[test]
fn exact_straight_inclined_section() {
    let sec = StraightSection::new();
    let (inc, l, f, r_c, w_b) = sec.values();
    let run = |v_a: f64, omega: f64| soft_string(&sec.input(v_a, omega));
    let out = run(-0.5, 0.0);
    let inn = run(0.5, 0.0);
    let rot = run(0.0, 5.0);
    assert!(rel(out.hook_load_n, w_b * l * (inc.cos() + f * inc.sin())) < 1e-9);
    assert!(rel(inn.hook_load_n, w_b * l * (inc.cos() - f * inc.sin())) < 1e-9);
    assert!(rel(rot.hook_load_n, w_b * l * inc.cos()) < 1e-9);
    assert!(rel(rot.surface_torque_nm, f * w_b * l * inc.sin() * r_c) < 1e-9);
    // the pipe presses the low side: normal direction = -(high side), force w_b sin I per m
    let low = Vec3::new(
        inc.cos() * 30f64.to_radians().cos(),
        inc.cos() * 30f64.to_radians().sin(),
        -inc.sin(),
    ) * -1.0;
    for pt in &rot.points {
        assert!((pt.normal_dir - low).norm() < 1e-9);
        assert!(rel(pt.normal_force_per_m, w_b * inc.sin()) < 1e-9);
    }
}

/// The stiff-contact variant used above the stiff part of `hybrid`
/// (`soft_string_stiff_contact`): docs/theory.md 4, rotating pipe lying in a straight inclined
/// hole: the wall carries the lateral weight with the normal force and the circumferential
/// friction together, so N = w_b sin I / sqrt(1 + f^2) and the torque is 1/sqrt(1 + f^2) of
/// Johancsik's (1e-9); with a combined velocity only the circumferential share of the friction
/// enters (N = w_b sin I / sqrt(1 + (f v_t/|v|)^2)); sliding without rotation is Johancsik's.
#[test]
fn stiff_contact_variant_straight_inclined_section() {
    let sec = StraightSection::new();
    let (inc, l, f, r_c, w_b) = sec.values();
    let input = |v_a: f64, omega: f64| sec.input(v_a, omega);
    let rot = soft_string_stiff_contact(&input(0.0, 5.0));
    let n = w_b * inc.sin() / (1.0 + f * f).sqrt();
    assert!(rel(rot.surface_torque_nm, f * n * l * r_c) < 1e-9);
    assert!(rel(rot.hook_load_n, w_b * l * inc.cos()) < 1e-9);
    assert!(rot.points.iter().all(|pt| rel(pt.normal_force_per_m, n) < 1e-9));
    let slide = soft_string_stiff_contact(&input(0.5, 0.0));
    assert!(rel(slide.hook_load_n, soft_string(&input(0.5, 0.0)).hook_load_n) < 1e-12);
    // drilling: v_a = 0.5 m/s, v_t = 5 r_c: share v_t/|v|
    let (v_a, v_t) = (0.5, 5.0 * r_c);
    let share = v_t / f64::hypot(v_a, v_t);
    let drill = soft_string_stiff_contact(&input(v_a, 5.0));
    let n = w_b * inc.sin() / (1.0 + (f * share).powi(2)).sqrt();
    assert!(rel(drill.surface_torque_nm, f * n * share * l * r_c) < 1e-9);
    let drag = f * n * (v_a / f64::hypot(v_a, v_t)) * l;
    assert!(rel(drill.hook_load_n, w_b * l * inc.cos() - drag) < 1e-9);
}

/// docs/theory.md 10.5 exact check (c): weightless pipe around an arc of 90 deg, capstan law
/// F_out = F_in e^(f dtheta) = 1.4810 F_in for f = 0.25 pulling out (0.1 %; 0.1 m elements,
/// discretisation error ~ f^2 dtheta dl kappa / 2 = 8e-5), and e^(-f dtheta) running in.
#[test]
fn exact_capstan_weightless_arc() {
    let f = 0.25;
    let expect = (f * FRAC_PI_2).exp();
    assert!((expect - 1.4810).abs() < 5e-5);
    let p = path(&[(0.0, 0.0, 0.0), (100.0, 90.0, 0.0)]);
    let hole = HoleSize::uniform(0.2159);
    let s = DrillString {
        components: vec![pipe(100.0, 0.0, Some(0.168))],
    };
    let run = |v_a: f64| {
        soft_string(&SoftStringInput {
            path: &p,
            hole: &hole,
            string: &s,
            mud_density_kg_m3: 1200.0,
            bit_md_m: 100.0,
            wob_n: -10e3, // 10 kN pull at the lower end
            bit_torque_nm: 0.0,
            axial_speed_m_s: v_a,
            omega_rad_s: 0.0,
            friction: f,
            max_element_m: 0.1,
        })
    };
    let out = run(-0.3);
    let inn = run(0.3);
    println!(
        "capstan: out/in {:.6} (e^(f pi/2) = {expect:.6})",
        out.hook_load_n / 10e3
    );
    assert!(rel(out.hook_load_n / 10e3, expect) < 1e-3);
    assert!(rel(inn.hook_load_n / 10e3, 1.0 / expect) < 1e-3);
    // tension pulls the pipe to the inside of the bend: north-up at 45 deg at mid-arc (the
    // node at MD 50 m carries the element 50.0-50.1 m below it: 0.8 mrad off the mid-arc)
    let mid = &out.points[500];
    let inside = Vec3::new(1.0, 0.0, -1.0) / 2f64.sqrt();
    assert!((mid.normal_dir - inside).norm() < 1e-3, "{:?}", mid.normal_dir);
}

/// No motion at all: frictionless and flagged so.
#[test]
fn no_motion_is_frictionless() {
    let w = worked_direct();
    let r = w.run(0.0, 1500.0, 0.0, 0.0, 1.0);
    assert!(r.frictionless);
    assert_eq!(r.surface_torque_nm, 1500.0);
    let rot = w.run(0.0, 0.0, 0.0, RPM60, 1.0);
    assert!(rel(r.hook_load_n, rot.hook_load_n) < 1e-12);
}

/// Reference: the segment rule (elements of at most `max_element_m`, nodes at component ends):
/// a 3,000 m single-component string in 1 m elements has 3,001 nodes, the last at the surface.
/// Its speed is measured by the benchmark `softstring_3000m` (`cargo bench --bench solve`),
/// not here.
#[test]
fn pass_of_3000m_has_a_node_every_metre() {
    let p = path(&[
        (0.0, 0.0, 0.0),
        (800.0, 0.0, 0.0),
        (1400.0, 60.0, 30.0),
        (3000.0, 60.0, 35.0),
    ]);
    let hole = HoleSize::uniform(0.2159);
    let s = DrillString {
        components: vec![pipe(3000.0, 33.6 * G, Some(0.1683))],
    };
    let input = SoftStringInput {
        path: &p,
        hole: &hole,
        string: &s,
        mud_density_kg_m3: 1200.0,
        bit_md_m: 3000.0,
        wob_n: 80e3,
        bit_torque_nm: 3e3,
        axial_speed_m_s: ROP12,
        omega_rad_s: RPM60,
        friction: 0.25,
        max_element_m: 1.0,
    };
    let r = soft_string(&input);
    assert_eq!(r.points.len(), 3001);
    assert!(r.points[3000].md_m.abs() < 1e-9, "{}", r.points[3000].md_m);
    assert!(r.points.windows(2).all(|w| (w[0].md_m - w[1].md_m - 1.0).abs() < 1e-9));
}

// ----------------------------------------------------------------------------------------------
// 3. Property: trip out >= rotating >= trip in
// ----------------------------------------------------------------------------------------------

fn survey_strategy() -> impl Strategy<Value = Vec<(f64, f64, f64)>> {
    prop::collection::vec((50.0..600.0f64, 0.0..85.0f64, 0.0..360.0f64), 2..7).prop_map(|v| {
        let mut md = 0.0;
        let mut st = vec![(0.0, 0.0, 0.0)];
        for (dm, i, a) in v {
            md += dm;
            st.push((md, i, a));
        }
        st
    })
}

proptest! {
    #![proptest_config(ProptestConfig {
        cases: 200,
        failure_persistence: Some(Box::new(FileFailurePersistence::Off)),
        ..ProptestConfig::default()
    })]

    /// For any survey, f >= 0 and WOB: hook load tripping out >= rotating >= tripping in
    /// (each element adds f N >= 0 to the difference; 1e-9 relative round-off allowance), and
    /// rotating equals sum w_b dTVD - WOB.
    #[test]
    fn trip_out_ge_rotating_ge_trip_in(
        st in survey_strategy(),
        f in 0.0..0.6f64,
        wob in 0.0..100e3f64,
        frac in 0.3..1.0f64,
        el in 0.5..15.0f64,
    ) {
        let p = path(&st);
        let bit_md = p.md_end() * frac;
        let hole = HoleSize::uniform(0.2159);
        let s = DrillString { components: vec![pipe(bit_md, 33.6 * G, Some(0.1683))] };
        let run = |v_a: f64, omega: f64| soft_string(&SoftStringInput {
            path: &p, hole: &hole, string: &s, mud_density_kg_m3: 1200.0, bit_md_m: bit_md,
            wob_n: wob, bit_torque_nm: 0.0, axial_speed_m_s: v_a, omega_rad_s: omega,
            friction: f, max_element_m: el,
        });
        let out = run(-0.3, 0.0).hook_load_n;
        let rot = run(0.0, RPM60).hook_load_n;
        let inn = run(0.3, 0.0).hook_load_n;
        let tol = 1e-9 * (out.abs() + rot.abs() + inn.abs() + 1.0);
        prop_assert!(out >= rot - tol, "out {out} < rot {rot}");
        prop_assert!(rot >= inn - tol, "rot {rot} < in {inn}");
        let hang = hanging_weight(&p, &s, 1200.0, bit_md) - wob;
        prop_assert!((rot - hang).abs() <= tol, "rot {rot} vs {hang}");
    }
}
