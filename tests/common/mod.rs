//! Shared by the two test binaries (`tests/verification`, `tests/cli`; each includes this
//! module): the one runner of the `drillpath` binary ([`run`]), cases written to a temporary
//! directory and read as users' cases are, and the slick 6.5 in collar of the closed-form checks
//! (docs/theory.md 9.2). Each binary uses a part of this module.
#![allow(dead_code)]

mod run;
#[allow(unused_imports)] // the verification binary runs no command
pub use run::{assert_error_names, drillpath, root, run_in, run_ok, Run};

use drillpath::analytical::section::Tube;
use drillpath::case::Case;
use drillpath::io::case_toml::{load_case, CaseOverrides};

/// Collar outside diameter, 6.5 in, m.
pub const OD: f64 = 6.5 * 0.0254;
/// Collar bore, 2-13/16 in, m.
pub const ID: f64 = 2.8125 * 0.0254;
/// Hole diameter, 8.5 in, m.
pub const HOLE: f64 = 8.5 * 0.0254;

/// Write `survey` (as `survey.csv`) and `case_toml` (as `case.toml`) into a fresh directory
/// and read the case as users do.
pub fn load_temp_case(survey: &str, case_toml: &str) -> Case {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("survey.csv"), survey).unwrap();
    std::fs::write(dir.path().join("case.toml"), case_toml).unwrap();
    load_case(&dir.path().join("case.toml"), &CaseOverrides::default()).unwrap()
}

/// Bending stiffness EI (N.m2, E = 207 GPa), buoyed weight (N/m, steel 7,850 kg/m3 in 1.2 sg
/// mud) and radial clearance (m) of the slick collar in its hole.
pub fn collar_properties() -> (f64, f64, f64) {
    let tube = Tube::new(OD, ID).unwrap();
    let ei = 207e9 * tube.second_moment();
    let w_b = tube.air_weight(7850.0) * (1.0 - 1200.0 / 7850.0);
    (ei, w_b, (HOLE - OD) / 2.0)
}

/// A slick collar string `length_m` long in a straight 8.5 in hole of inclination `inc_deg`
/// and azimuth `azi_deg`, 1.2 sg mud, sliding without friction at `wob_kn`, elements of
/// `element_m` everywhere; `solver_extra` is appended to the `[solver]` table (e.g.
/// `method = "paper"`).
pub fn slick_collar_case(
    inc_deg: f64,
    azi_deg: f64,
    length_m: f64,
    wob_kn: f64,
    element_m: f64,
    solver_extra: &str,
) -> Case {
    let survey = format!("md_m,inc_deg,azi_deg\n0,{inc_deg},{azi_deg}\n{length_m},{inc_deg},{azi_deg}\n");
    let case = format!(
        r#"
[well]
survey = "survey.csv"
hole = [{{ to_md = "{length_m} m", diameter = "8.5 in" }}]
[mud]
density = "1.2 sg"
[operation]
mode = "sliding"
wob = "{wob_kn} kN"
rop = "0 m/h"
friction = 0.0
[[string]]
type = "collar"
od = "6.5 in"
id = "2.8125 in"
[solver]
element_length = "{element_m} m"
bha_element_length = "{element_m} m"
{solver_extra}
"#
    );
    load_temp_case(&survey, &case)
}
