//! Shared by the two test binaries (`tests/verification`, `tests/cli`; each includes this
//! module): the one runner of the `drillpath` binary ([`run`]), the drill strings and BHAs used
//! by more than one test ([`strings`]), the example wells, and cases written to a temporary
//! directory and read as users' cases are. Each binary uses a part of this module.
#![allow(dead_code)]

mod run;
mod strings;
#[allow(unused_imports)] // each binary uses a part
pub use run::{assert_error_names, drillpath, root, run_in, run_ok, Run};
#[allow(unused_imports)]
pub use strings::*;

use drillpath::case::Case;
use drillpath::error::InputResult;
use drillpath::io::case_toml::{load_case, CaseOverrides};
use std::path::PathBuf;
use tempfile::TempDir;

/// The directory of example well `name` (`wells/<name>`: its case file, survey and data).
pub fn example_dir(name: &str) -> PathBuf {
    root().join("wells").join(name)
}

/// The case file of example well `name` (`wells/<name>/case.toml`).
pub fn example_case(name: &str) -> PathBuf {
    example_dir(name).join("case.toml")
}

/// Example well `name` read as users' cases are (`wells/<name>/case.toml`, no overrides).
pub fn example(name: &str) -> Case {
    load_case(&example_case(name), &CaseOverrides::default()).unwrap()
}

/// A fresh temporary directory holding `survey` as `survey.csv` and `case_toml` as `case.toml`
/// (a case whose `[well] survey` is `"survey.csv"`).
pub fn case_dir(survey: &str, case_toml: &str) -> TempDir {
    let dir = tempfile::tempdir().expect("cannot create a temporary directory");
    std::fs::write(dir.path().join("survey.csv"), survey).expect("cannot write survey.csv");
    std::fs::write(dir.path().join("case.toml"), case_toml).expect("cannot write case.toml");
    dir
}

/// Write `survey` and `case_toml` to a fresh directory ([`case_dir`]) and read the case as users
/// do, errors included.
pub fn try_load_temp_case(survey: &str, case_toml: &str) -> InputResult<Case> {
    let dir = case_dir(survey, case_toml);
    load_case(&dir.path().join("case.toml"), &CaseOverrides::default())
}

/// [`try_load_temp_case`] of a valid case.
pub fn load_temp_case(survey: &str, case_toml: &str) -> Case {
    try_load_temp_case(survey, case_toml).unwrap()
}

/// `bha` drilling in a straight 8.5 in hole at 30 deg (3,000 m, bit at TD), 80 kN WOB, 60 rpm,
/// friction 0.25, drill pipe above the assembly, BHA elements of `bel` m.
pub fn bha_at_30_deg(bha: &str, bel: f64) -> Case {
    let survey = "md_m,inc_deg,azi_deg\n0,30,0\n3000,30,0\n";
    let toml = format!(
        r#"
[well]
survey = "survey.csv"
hole = [{{ to_md = "3000 m", diameter = "8.5 in" }}]
[mud]
density = "1.2 sg"
[operation]
mode = "drilling"
bit_md = "3000 m"
wob = "80 kN"
rpm = 60
rop = "10 m/h"
friction = 0.25
{bha}{DRILL_PIPE}[solver]
bha_element_length = "{bel} m"
"#
    );
    load_temp_case(survey, &toml)
}

/// The `bha` model of `case` cut at the default length above its stabilizers.
pub fn bha_of(case: &Case) -> drillpath::models::fem::model::Model {
    use drillpath::models::fem::bha::{bha_model, default_cut_m};
    let (path, hole, bit) = (&case.well.path, &case.well.hole, case.operation.bit_md_m);
    let cut = default_cut_m(
        &case.string,
        hole.diameter_at(bit),
        path.point_at(bit).inc_rad,
        case.mud.density_kg_m3,
    );
    bha_model(case, path, hole, bit, cut)
}

/// A slick collar string ([`COLLAR_TO_SURFACE`], properties [`collar_properties`]) `length_m`
/// long in a straight 8.5 in hole of inclination `inc_deg` and azimuth `azi_deg` (deg), 1.2 sg
/// mud, sliding without friction at `wob_kn` (kN), elements of `element_m` (m) everywhere;
/// `solver_extra` is appended to the `[solver]` table (e.g. `method = "paper"`).
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
{COLLAR_TO_SURFACE}[solver]
element_length = "{element_m} m"
bha_element_length = "{element_m} m"
{solver_extra}
"#
    );
    load_temp_case(&survey, &case)
}

/// `case` solved as `drillpath solve --fidelity whole` solves it (the case's own controls).
pub fn solve_whole(case: &Case) -> drillpath::models::string_solve::StringSolve {
    use drillpath::case::{choose, Fidelity, Level, Purpose};
    let ctl = drillpath::models::fem::solve::SolveControls::from_settings(&case.solver);
    let choice = choose(Fidelity::Level(Level::Whole), Purpose::Solve);
    drillpath::models::string_solve::solve_string(case, choice, &ctl, &mut |_, _, _| {}).unwrap()
}
