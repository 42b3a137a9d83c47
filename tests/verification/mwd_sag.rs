//! MWD sag angle of a real rotary-steerable assembly with stabilizer blades (issue 20), against
//! an independent beam-column with contact along the wall (`analytical::contact_beam`), and
//! beside the published sag of the same assembly.
//!
//! The assembly is the public test case `bha_rss` of mwdstdcore (github.com/mwdstd/mwdstdcore,
//! `tests/params.py`: a 6-1/8 in RSS assembly with six blade sets, D&I sensor 7.85 m above the
//! bit; its test `test_sag.py` asserts a sag of -0.15 +/- 0.005 deg at 90 deg in 1.29 sg mud;
//! -0.148 deg as computed there). Its data are used as mwdstdcore reads them: each component's
//! linear weight is its weight over its length, its bending stiffness that of a tube of its OD
//! and the bore its weight implies (`ID^2 = OD^2 - 4 q / (pi 7850)`), E = 190 GPa for
//! non-magnetic steel and 205 GPa for steel, and the hole is the bit's diameter enlarged by 2.5%
//! of it (its default without a bend). Above the assembly, 4 in drill pipe to the surface (in
//! the reference: 100 m of it lying on the wall). Straight horizontal hole, no WOB, no friction.
//!
//! Run with `cargo test --release --test verification mwd_sag:: -- --nocapture`.

use drillpath::analytical::contact_beam::{solve as reference, ContactBeam, Piece, TopEnd};
use drillpath::case::{choose, Case, Fidelity, Level, Purpose};
use drillpath::models::fem::results::sensor_results;
use drillpath::models::fem::solve::SolveControls;
use drillpath::models::levels::run;
use std::f64::consts::PI;

use crate::common::load_temp_case;

const G: f64 = 9.80665;
const STEEL_RHO: f64 = 7850.0;
const MUD_RHO: f64 = 1290.0;
/// Bit diameter, m.
const BIT_OD: f64 = 0.1556;
/// Hole diameter, m: the bit's enlarged by 2.5% of it.
const HOLE: f64 = BIT_OD * 1.025;
/// Distance from the bit face to the D&I sensor, m.
const SENSOR_M: f64 = 7.85;
/// The published sag of the assembly at 90 deg, deg (mwdstdcore).
const PUBLISHED_SAG_DEG: f64 = -0.148;

/// A component of the assembly: type, OD (m), weight (kg), length (m), non-magnetic.
struct Part(&'static str, f64, f64, f64, bool);

/// `bha_rss`'s structure from the bit up.
const PARTS: [Part; 15] = [
    Part("bit", 0.1556, 30.0, 0.15, false),
    Part("sub", 0.133, 310.0, 2.93, true), // the RSS
    Part("mwd", 0.1308, 600.0, 6.11, true),
    Part("sub", 0.127, 100.0, 1.00, true),  // string stabilizer body
    Part("sub", 0.1308, 330.0, 3.37, true), // LWD
    Part("sub", 0.1207, 122.0, 1.99, true),
    Part("sub", 0.127, 100.0, 0.88, true),
    Part("sub", 0.1347, 430.0, 4.39, true), // LWD
    Part("sub", 0.1347, 170.0, 1.59, true),
    Part("sub", 0.1355, 560.0, 5.2, true),
    Part("sub", 0.1347, 170.0, 1.58, true),
    Part("sub", 0.127, 70.0, 0.77, true),
    Part("collar", 0.1238, 120.0, 1.82, true),
    Part("sub", 0.127, 70.0, 0.61, true),
    Part("collar", 0.127, 770.0, 9.45, true),
];

/// `bha_rss`'s blades: OD (m), centre above the bit face (m), length (m).
const BLADES: [(f64, f64, f64); 6] = [
    (0.1524, 1.0, 0.36),
    (0.1492, 9.79, 0.36),
    (0.1492, 16.0, 0.36),
    (0.1461, 18.6, 0.36),
    (0.152, 21.6, 0.36),
    (0.1461, 29.0, 0.36),
];

/// A uniform length of the assembly from `bottom` to `top` (m above the bit): its part and, on a
/// blade, the blade's OD.
struct Segment {
    bottom: f64,
    top: f64,
    part: usize,
    blade_od: Option<f64>,
}

/// The assembly cut at every part end, blade edge and at the sensor.
fn segments() -> Vec<Segment> {
    let mut cuts = vec![0.0, SENSOR_M];
    let mut s = 0.0;
    for p in &PARTS {
        s += p.3;
        cuts.push(s);
    }
    for (_, c, l) in BLADES {
        cuts.extend([c - l / 2.0, c + l / 2.0]);
    }
    cuts.sort_by(f64::total_cmp);
    cuts.dedup_by(|a, b| (*a - *b).abs() < 1e-9);
    let part_at = |x: f64| {
        let mut top = 0.0;
        PARTS
            .iter()
            .position(|p| {
                top += p.3;
                x < top
            })
            .unwrap()
    };
    cuts.windows(2)
        .map(|w| {
            let mid = 0.5 * (w[0] + w[1]);
            let blade = BLADES.iter().find(|(_, c, l)| (mid - c).abs() < l / 2.0);
            Segment {
                bottom: w[0],
                top: w[1],
                part: part_at(mid),
                blade_od: blade.map(|b| b.0),
            }
        })
        .collect()
}

/// Linear mass (kg/m), the bore its weight implies (m) and E (Pa) of part `k`.
fn properties(k: usize) -> (f64, f64, f64) {
    let p = &PARTS[k];
    let q = p.2 / p.3;
    let id2 = p.1 * p.1 - 4.0 * q / (PI * STEEL_RHO);
    let e = if p.4 { 190e9 } else { 205e9 };
    (q, id2.max(0.0).sqrt(), e)
}

/// The drillpath case: each segment a component (a stabilizer on a blade), the sensor on the
/// MWD, 4 in pipe to the surface in a 1,000 m straight horizontal hole.
fn case(bha_element_m: f64, wob_kn: f64) -> Case {
    let mut string = String::new();
    for (i, s) in segments().iter().enumerate() {
        let p = &PARTS[s.part];
        let (q, id, e) = properties(s.part);
        let kind = match (s.blade_od, i) {
            (_, 0) => "bit",
            (Some(_), _) => "stabilizer",
            (None, _) => p.0,
        };
        let od = s.blade_od.unwrap_or(p.1);
        let body = if s.blade_od.is_some() {
            format!("body_od = \"{} m\"\nblade_length = \"{} m\"\n", p.1, s.top - s.bottom)
        } else {
            String::new()
        };
        let sensor = if p.0 == "mwd" && (s.top - SENSOR_M).abs() < 1e-9 {
            format!("sensor_to_bit = \"{SENSOR_M} m\"\n")
        } else {
            String::new()
        };
        string += &format!(
            "[[string]]\ntype = \"{kind}\"\nod = \"{od} m\"\n{body}id = \"{id} m\"\nlength = \"{} m\"\n\
             weight = {q}\nyoungs_modulus = \"{} GPa\"\nmaterial_density = \"{STEEL_RHO} kg/m3\"\n{sensor}",
            s.top - s.bottom,
            e / 1e9
        );
    }
    string += "[[string]]\ntype = \"pipe\"\nod = \"4 in\"\nid = \"3.34 in\"\n";
    let survey = "md_m,inc_deg,azi_deg\n0,90,0\n1000,90,0\n";
    let text = format!(
        r#"
[well]
survey = "survey.csv"
hole = [{{ to_md = "1000 m", diameter = "{HOLE} m" }}]
[mud]
density = "{MUD_RHO} kg/m3"
[operation]
mode = "sliding"
wob = "{wob_kn} kN"
rop = "0 m/h"
friction = 0.0
{string}[solver]
stabilizer_contact = "blade"
bha_element_length = "{bha_element_m} m"
tolerance = 1e-6
"#
    );
    load_temp_case(survey, &text)
}

/// The reference: the same segments as beam-column pieces (blades with their clearance, the bit
/// without contact), then 100 m of the 4 in pipe lying on the wall; 5 mm elements.
fn reference_sag_rad(wob_n: f64) -> f64 {
    let buoyancy = 1.0 - MUD_RHO / STEEL_RHO;
    let mut pieces: Vec<Piece> = segments()
        .iter()
        .enumerate()
        .map(|(i, s)| {
            let p = &PARTS[s.part];
            let (q, id, e) = properties(s.part);
            let od = s.blade_od.unwrap_or(p.1);
            Piece {
                length: s.top - s.bottom,
                ei: e * PI / 64.0 * (p.1.powi(4) - id.powi(4)),
                weight: q * G * buoyancy,
                clearance: (i > 0).then_some((HOLE - od) / 2.0),
            }
        })
        .collect();
    let (od, id): (f64, f64) = (4.0 * 0.0254, 3.34 * 0.0254);
    pieces.push(Piece {
        length: 100.0,
        ei: 207e9 * PI / 64.0 * (od.powi(4) - id.powi(4)),
        weight: STEEL_RHO * PI / 4.0 * (od * od - id * id) * G * buoyancy,
        clearance: Some((HOLE - od) / 2.0),
    });
    let sol = reference(&ContactBeam {
        pieces,
        inclination: PI / 2.0,
        wob: wob_n,
        top: TopEnd::OnWall,
        element: 0.005,
    })
    .unwrap();
    let i = sol
        .x
        .iter()
        .position(|&x| (x - SENSOR_M).abs() < 1e-6)
        .expect("a reference node at the sensor");
    sol.slope[i]
}

/// drillpath's sag at the sensor, rad, at stiff level `level`.
fn drillpath_sag_rad(case: &Case, level: Level) -> f64 {
    let r = run(
        case,
        choose(Fidelity::Level(level), Purpose::Solve),
        &SolveControls::from_settings(&case.solver),
    )
    .unwrap();
    assert!(r.converged, "{level:?} did not converge");
    let fem = r.fem.expect("a stiff model");
    let sensors = sensor_results(&case.string, &fem.model, &fem.results.nodes);
    assert_eq!(sensors.len(), 1, "one sensor");
    assert!((sensors[0].sensor_to_bit_m - SENSOR_M).abs() < 1e-9);
    sensors[0].sag_rad
}

/// Reference: the beam-column with contact along the wall, same assembly and inputs. Tolerance:
/// 1% of the reference's sag (the issue's bar), at `bha` and `whole`, at BHA meshes of 0.1 m
/// and the default 0.5 m, without WOB and at 40 kN. The published -0.148 deg (no WOB) is printed
/// beside them, not asserted: it comes from a coarser model (0.75 m grid, the slope averaged
/// over two grid intervals, a bit free in its clearance, blades stiffened by their section, 25 m
/// of the assembly above the sensor).
#[test]
fn rss_sensor_sag_matches_the_contact_beam_reference() {
    for wob_kn in [0.0, 40.0] {
        let expected = reference_sag_rad(wob_kn * 1e3);
        for mesh in [0.1, 0.5] {
            let case = case(mesh, wob_kn);
            for level in [Level::Bha, Level::Whole] {
                let sag = drillpath_sag_rad(&case, level);
                let err = sag / expected - 1.0;
                println!(
                    "bha_rss at 90 deg, WOB {wob_kn} kN, {mesh} m BHA mesh, {}: sag {:+.5} deg, reference {:+.5} deg ({:+.3}%), published (no WOB) {PUBLISHED_SAG_DEG:+.3} deg",
                    level.name(),
                    sag.to_degrees(),
                    expected.to_degrees(),
                    100.0 * err
                );
                assert!(
                    err.abs() < 0.01,
                    "{wob_kn} kN {mesh} m {level:?}: {sag} rad vs {expected} rad"
                );
            }
        }
    }
}
