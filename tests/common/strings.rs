//! Drill-string components and BHAs that more than one test uses, for an 8.5 in hole: as
//! `[[string]]` entries of a case file (TOML text in the case file's own units, lengths in m and
//! diameters in in, listed from the bit up; each entry ends with a newline, so entries join by
//! concatenation), and as section properties in SI units for the closed-form references.

use drillpath::analytical::section::Tube;

// ---------------------------------------------------------------------------------------------
// Components, as case-file entries

/// The 8.5 in bit, 0.3 m long.
pub const BIT: &str = r#"[[string]]
type = "bit"
od = "8.5 in"
length = "0.3 m"
"#;

/// A stabilizer with blades of diameter `od` (`"8.5 in"`: full gauge in the 8.5 in hole, zero
/// clearance) on a 6.5 in body with a 2-13/16 in bore, 1.5 m long.
pub fn stabilizer(od: &str) -> String {
    format!(
        r#"[[string]]
type = "stabilizer"
od = "{od}"
body_od = "6.5 in"
id = "2.8125 in"
length = "1.5 m"
"#
    )
}

/// A 6.5 in drill collar (2-13/16 in bore; steel, weight from the tube), `length` long
/// (`"60 m"`).
pub fn collar(length: &str) -> String {
    format!("{COLLAR_TO_SURFACE}length = \"{length}\"\n")
}

/// The string above the steerable assemblies of tests/verification/steering.rs and rss.rs:
/// MWD 9 m and non-magnetic collar 9.2 m (6.75 in), 280 m of 5 in HWDP (49.3 lb/ft, 6.5 in tool
/// joints), 5 in drill pipe to the surface (33.6 kg/m, 6-5/8 in tool joints).
pub const STEERING_UPPER_STRING: &str = r#"[[string]]
type = "mwd"
od = "6.75 in"
id = "3.25 in"
length = "9 m"
[[string]]
type = "collar"
od = "6.75 in"
id = "2.8125 in"
length = "9.2 m"
[[string]]
type = "hwdp"
od = "5 in"
id = "3 in"
length = "280 m"
weight = "49.3 lb/ft"
tool_joint_od = "6.5 in"
[[string]]
type = "pipe"
od = "5 in"
id = "4.276 in"
weight = "33.6 kg/m"
tool_joint_od = "6.625 in"
"#;

/// The 6.5 in drill collar of [`collar`] without a length: it fills the string to the surface.
pub const COLLAR_TO_SURFACE: &str = r#"[[string]]
type = "collar"
od = "6.5 in"
id = "2.8125 in"
"#;

/// 5 in drill pipe to the surface: 4.276 in bore, 29 kg/m in air (19.5 lb/ft nominal), 6-5/8 in
/// tool joints (the contact diameter of the soft string).
pub const DRILL_PIPE: &str = r#"[[string]]
type = "pipe"
od = "5 in"
id = "4.276 in"
weight = "29 kg/m"
tool_joint_od = "6.625 in"
"#;

/// The pipe body of [`DRILL_PIPE`] without tool joints: 5 in, 4.276 in bore, 29 kg/m in air,
/// to the surface. Its section properties: [`pipe_properties`].
pub const DRILL_PIPE_BODY: &str = r#"[[string]]
type = "pipe"
od = "5 in"
id = "4.276 in"
weight = "29 kg/m"
"#;

/// 5 in pipe (4.276 in bore) with no weight given, so weighing what its steel tube weighs
/// (26.7 kg/m, no allowance for joints), without tool joints, to the surface.
pub const PIPE_TUBE: &str = r#"[[string]]
type = "pipe"
od = "5 in"
id = "4.276 in"
"#;

// ---------------------------------------------------------------------------------------------
// The textbook BHAs (Lubinski & Woods; Millheim et al.; docs/theory.md 9.3): bit, 6.5 in collars
// and full-gauge 8.5 in stabilizers, without the pipe above them

/// Fulcrum (builds): full-gauge near-bit stabilizer, 60 m of collars above.
pub fn fulcrum_bha() -> String {
    format!("{BIT}{}{}", stabilizer("8.5 in"), collar("60 m"))
}

/// Pendulum (drops): the first (full-gauge) stabilizer 18.3-19.8 m above the bit, 45 m of
/// collars above it.
pub fn pendulum_bha() -> String {
    let stab = stabilizer("8.5 in");
    format!("{BIT}{}{stab}{}", collar("18 m"), collar("45 m"))
}

/// Packed (holds): full-gauge stabilizers at the bit, 5 m and 15 m above it, 45 m of collars
/// above the last.
pub fn packed_bha() -> String {
    let stab = stabilizer("8.5 in");
    format!(
        "{BIT}{stab}{}{stab}{}{stab}{}",
        collar("3 m"),
        collar("8.5 m"),
        collar("45 m")
    )
}

/// Slick: the bit and 80 m of collars, no stabilizer.
pub fn slick_bha() -> String {
    format!("{BIT}{}", collar("80 m"))
}

// ---------------------------------------------------------------------------------------------
// Section properties, SI

/// Collar outside diameter, 6.5 in, m.
pub const OD: f64 = 6.5 * 0.0254;
/// Collar bore, 2-13/16 in, m.
pub const ID: f64 = 2.8125 * 0.0254;
/// Hole diameter, 8.5 in, m.
pub const HOLE: f64 = 8.5 * 0.0254;

/// Bending stiffness EI (N.m2, E = 207 GPa), buoyed weight (N/m, steel 7,850 kg/m3 in 1.2 sg
/// mud) and radial clearance (m) of the slick collar in its hole.
pub fn collar_properties() -> (f64, f64, f64) {
    let tube = Tube::new(OD, ID).unwrap();
    let ei = 207e9 * tube.second_moment();
    let w_b = tube.air_weight(7850.0) * (1.0 - 1200.0 / 7850.0);
    (ei, w_b, (HOLE - OD) / 2.0)
}

/// The `[mud]`, `[operation]` and `[[string]]` tables of a 0.3 m, 5 in bit on the 5 in pipe body
/// ([`DRILL_PIPE_BODY`]) in 1.2 sg mud, sliding with the bit at `bit_md_m` (m), `wob_kn` (kN) and
/// wall friction `friction`: the string of the straight-hole and lateral tests.
pub fn slid_bit_on_pipe(bit_md_m: f64, wob_kn: f64, friction: f64) -> String {
    format!(
        r#"[mud]
density = "1.2 sg"
[operation]
mode = "sliding"
bit_md = "{bit_md_m} m"
wob = "{wob_kn} kN"
friction = {friction}
[[string]]
type = "bit"
od = "5 in"
length = "0.3 m"
{DRILL_PIPE_BODY}"#
    )
}

/// Bending stiffness EI (N.m2, E = 207 GPa, the body only), buoyed weight (N/m: 29 kg/m of
/// steel, 7,850 kg/m3, in 1.2 sg mud) and radial clearance of the body in the 8.5 in hole (m)
/// of the 5 in drill pipe ([`DRILL_PIPE_BODY`]).
pub fn pipe_properties() -> (f64, f64, f64) {
    let ei = 207e9 * std::f64::consts::PI / 64.0 * (0.127f64.powi(4) - (4.276f64 * 0.0254).powi(4));
    let w_b = 29.0 * 9.80665 * (1.0 - 1200.0 / 7850.0);
    (ei, w_b, (8.5 - 5.0) * 0.0254 / 2.0)
}

/// The slid horizontal of the WOB-path and lock-up tests (issue 16): vertical to 300 m, a
/// 6 deg/30 m build to 90 deg (stations every 10 m), 300 m level (bit at 1,050 m), 8.5 in
/// hole; bit, 1/16 in under-gauge near-bit stabilizer, 54 m of 6.5 in collars, 5 in pipe with
/// tool joints; 1.2 sg, sliding with `wob_kn`, friction 0.25, 1 m pipe elements. Returns the
/// survey CSV and the case file's text.
pub fn slid_horizontal(wob_kn: f64) -> (String, String) {
    let mut csv = String::from("md_m,inc_deg,azi_deg\n0,0,0\n300,0,0\n");
    let build = 90.0 / 6.0 * 30.0;
    let n = (build / 10.0_f64).ceil() as usize;
    for k in 1..=n {
        let f = k as f64 / n as f64;
        csv += &format!("{},{},0\n", 300.0 + f * build, f * 90.0);
    }
    let md = 300.0 + build + 300.0;
    csv += &format!("{md},90,0\n");
    let toml = format!(
        r#"
[well]
survey = "survey.csv"
hole = [{{ to_md = "{md} m", diameter = "8.5 in" }}]
[mud]
density = "1.2 sg"
[operation]
mode = "sliding"
bit_md = "{md} m"
wob = "{wob_kn} kN"
rop = "12 m/h"
friction = 0.25
{BIT}{}{}{DRILL_PIPE}[solver]
element_length = "1 m"
bha_element_length = "0.5 m"
"#,
        stabilizer("8.4375 in"),
        collar("54 m")
    );
    (csv, toml)
}
