//! Geometry verification: minimum curvature (`drillpath::geometry`) against hand-computed arcs,
//! published / real-well survey reports and properties that must hold for every valid survey.
//!
//! Run with `cargo test --release --test verification geometry:: -- --nocapture` to see the measured errors.
//!
//! Data files under `/work/shared/data` are located beside the repository
//! (`$CARGO_MANIFEST_DIR/../shared/data/...`); if one is absent the test prints a note and returns.

use std::f64::consts::{FRAC_PI_2, PI};
use std::path::{Path, PathBuf};

use drillpath::geometry::{Frame, Station, Survey, Vec3, WellPath};
use drillpath::io::survey::{read_survey, SurveyUnits};
use drillpath::units::lookup;
use proptest::prelude::*;
use proptest::test_runner::FileFailurePersistence;

use crate::common::example_dir;

// ----------------------------------------------------------------------------------------------
// Shared helpers
// ----------------------------------------------------------------------------------------------

/// Path of a file in the shared data directory beside the repository.
macro_rules! shared_data {
    ($rel:literal) => {
        concat!(env!("CARGO_MANIFEST_DIR"), "/../shared/data/", $rel)
    };
}

/// `Some(path)` if the file exists, else print a note (the test then returns early).
fn present(path: &str) -> Option<PathBuf> {
    let p = PathBuf::from(path);
    if p.is_file() {
        Some(p)
    } else {
        println!("NOTE: {} is absent: test skipped", p.display());
        None
    }
}

/// One foot in metres, from the library's unit table.
fn ft() -> f64 {
    lookup("ft").expect("ft is a known unit").to_si
}

/// Well path from `(md, inc_deg, azi_deg)` triples (md in m).
fn path_deg(st: &[(f64, f64, f64)], origin: Vec3) -> WellPath {
    let survey = Survey::new(st.iter().map(|&(m, i, a)| Station::from_deg(m, i, a)).collect()).expect("valid survey");
    WellPath::new(&survey, origin).expect("valid well path")
}

/// Unit tangent (north, east, down) from degrees.
fn tangent_deg(inc_deg: f64, azi_deg: f64) -> Vec3 {
    let (i, a) = (inc_deg.to_radians(), azi_deg.to_radians());
    Vec3::new(i.sin() * a.cos(), i.sin() * a.sin(), i.cos())
}

/// sin(x)/x, 1 at 0.
fn sinc(x: f64) -> f64 {
    if x.abs() < 1e-8 {
        1.0 - x * x / 6.0
    } else {
        x.sin() / x
    }
}

/// Angle difference wrapped to [-pi, pi].
fn wrap(d: f64) -> f64 {
    (d + PI).rem_euclid(2.0 * PI) - PI
}

/// Largest absolute error of a series of comparisons, with where it happened.
struct MaxErr {
    what: &'static str,
    max: f64,
    at: f64,
    count: usize,
}

impl MaxErr {
    fn new(what: &'static str) -> Self {
        MaxErr {
            what,
            max: 0.0,
            at: f64::NAN,
            count: 0,
        }
    }

    /// Record `computed - reference` at measured depth `at`.
    fn add(&mut self, err: f64, at: f64) {
        self.count += 1;
        // NaN counts as an infinite error
        let e = if err.is_nan() { f64::INFINITY } else { err.abs() };
        if e > self.max {
            self.max = e;
            self.at = at;
        }
    }

    /// Print the measured maximum and assert it is within `tol`.
    fn check(&self, tol: f64, unit: &str) {
        println!(
            "{:<44} max |err| = {:.3e} {unit} at MD {} ({} values, tolerance {tol:e} {unit})",
            self.what, self.max, self.at, self.count
        );
        assert!(self.count > 0, "{}: nothing compared", self.what);
        assert!(
            self.max <= tol,
            "{}: max error {} {unit} at MD {} exceeds {tol} {unit}",
            self.what,
            self.max,
            self.at
        );
    }
}

/// Non-blank, non-comment lines of a text file, BOM and CR removed.
fn data_lines(text: &str) -> Vec<&str> {
    text.strip_prefix('\u{feff}')
        .unwrap_or(text)
        .lines()
        .map(|l| l.strip_suffix('\r').unwrap_or(l))
        .filter(|l| !l.trim().is_empty() && !l.trim_start().starts_with('#'))
        .collect()
}

/// A tiny comma-separated table reader (no quoting needed for these files): header and rows.
fn read_table(path: &Path) -> (Vec<String>, Vec<Vec<String>>) {
    let text = std::fs::read_to_string(path).unwrap_or_else(|e| panic!("cannot read {}: {e}", path.display()));
    let lines = data_lines(&text);
    let split = |l: &str| l.split(',').map(|f| f.trim().to_string()).collect::<Vec<_>>();
    let header = split(lines[0]);
    let rows = lines[1..].iter().map(|l| split(l)).collect();
    (header, rows)
}

/// Index of the header column named `name` (exact).
fn col(header: &[String], name: &str) -> usize {
    header
        .iter()
        .position(|h| h == name)
        .unwrap_or_else(|| panic!("column `{name}` not in header {header:?}"))
}

fn num(s: &str) -> f64 {
    s.trim().parse().unwrap_or_else(|_| panic!("`{s}` is not a number"))
}

// ----------------------------------------------------------------------------------------------
// 1. Hand-computed arcs
// ----------------------------------------------------------------------------------------------

#[test]
fn hand_computed_build_arc_500m_0_to_30deg() {
    // Reference: circle geometry by hand. A 500 m arc building 0 -> 30 deg in the vertical plane
    // of azimuth 0 has radius R = 500/(pi/6); TVD = R sin 30, north = R (1 - cos 30), east 0.
    // Tolerance 1 mm (also at the mid-arc point, 15 deg).
    let w = path_deg(&[(0.0, 0.0, 0.0), (500.0, 30.0, 0.0)], Vec3::zeros());
    let r = 500.0 / (PI / 6.0);
    let p = w.station_position(1);
    let mut e = MaxErr::new("build arc 0->30 deg: TVD, north, east");
    e.add(p.z - r * 0.5, 500.0);
    e.add(p.x - r * (1.0 - 30f64.to_radians().cos()), 500.0);
    e.add(p.y, 500.0);
    let m = w.point_at(250.0);
    e.add(m.position.z - r * 15f64.to_radians().sin(), 250.0);
    e.add(m.position.x - r * (1.0 - 15f64.to_radians().cos()), 250.0);
    e.add(m.inc_rad.to_degrees() - 15.0, 250.0);
    e.check(1e-3, "m");
    // DLS: 30 deg over 500 m.
    let dls_err = w.dls_before(1) - (PI / 6.0) / 500.0;
    assert!(dls_err.abs() < 1e-12, "DLS error {dls_err}");
    assert!((w.max_dls().0 - (PI / 6.0) / 500.0).abs() < 1e-12 && w.max_dls().1 == 500.0);
}

#[test]
fn hand_computed_horizontal_circle_turn() {
    // Reference: circle geometry by hand. At inclination 90 deg, turning azimuth 0 -> 90 -> 180
    // -> 270 -> 360 over 4 courses of L = 100 m each is a horizontal circle of radius
    // R = L/(pi/2) with centre (0, R): a quarter circle has chord R sqrt(2) and ends at (R, R);
    // after 360 deg of azimuth the path closes on itself; TVD stays 0. Tolerance 1 mm (the
    // computed values agree to ~1e-12 m).
    let l = 100.0;
    let w = path_deg(
        &[
            (0.0, 90.0, 0.0),
            (l, 90.0, 90.0),
            (2.0 * l, 90.0, 180.0),
            (3.0 * l, 90.0, 270.0),
            (4.0 * l, 90.0, 360.0),
        ],
        Vec3::zeros(),
    );
    let r = l / FRAC_PI_2;
    let centre = Vec3::new(0.0, r, 0.0);
    let mut e = MaxErr::new("horizontal circle: chord, ends, closure");
    e.add(w.station_position(1).norm() - r * 2f64.sqrt(), l);
    e.add((w.station_position(1) - Vec3::new(r, r, 0.0)).norm(), l);
    e.add((w.station_position(2) - Vec3::new(0.0, 2.0 * r, 0.0)).norm(), 2.0 * l);
    e.add((w.station_position(3) - Vec3::new(-r, r, 0.0)).norm(), 3.0 * l);
    // closes on itself
    e.add(w.station_position(4).norm(), 4.0 * l);
    // every interpolated point lies on the circle, at TVD 0, with azimuth s/R
    for i in 0..=400 {
        let s = i as f64;
        let p = w.point_at(s);
        e.add((p.position - centre).norm() - r, s);
        e.add(p.position.z, s);
        e.add(wrap(p.azi_rad - s / r) * r, s);
    }
    e.check(1e-3, "m");
    for k in 1..5 {
        assert!((w.dogleg_before(k) - FRAC_PI_2).abs() < 1e-12);
    }
}

// ----------------------------------------------------------------------------------------------
// 2. ISCWSA MWD error-model example wells #1 (m) and #2 (ft)
// ----------------------------------------------------------------------------------------------

/// (md, inc, azi, tvd) of ISCWSA example well `well` ("1" or "2"), in the file's depth unit.
fn iscwsa_well(path: &Path, well: &str) -> Vec<[f64; 4]> {
    let (h, rows) = read_table(path);
    let (cw, cm, ci, ca, ct) = (
        col(&h, "well"),
        col(&h, "md"),
        col(&h, "inc [deg]"),
        col(&h, "azi [deg]"),
        col(&h, "tvd"),
    );
    rows.iter()
        .filter(|r| r[cw] == well)
        .map(|r| [num(&r[cm]), num(&r[ci]), num(&r[ca]), num(&r[ct])])
        .collect()
}

#[test]
fn iscwsa_example_well_1_metres() {
    // Reference: ISCWSA MWD Rev 5 example spreadsheet, well "ISCWSA Test #1" (sheet TVD, 2
    // decimals): TVD at every station within 5 mm. North/east/TVD at MD 2100, 5100, 5190, 5400,
    // 6000, 8000 m from welleng's ISCWSA_code_ex1.csv (3 decimals, table in SOURCE.md): 1 mm.
    let Some(path) = present(shared_data!(
        "iscwsa-error-model-example-wells/iscwsa_example_wells_1_2.csv"
    )) else {
        return;
    };
    let rows = iscwsa_well(&path, "1");
    assert_eq!(rows.len(), 268, "well 1 has 268 stations");
    let w = path_deg(
        &rows.iter().map(|r| (r[0], r[1], r[2])).collect::<Vec<_>>(),
        Vec3::zeros(),
    );
    let mut e = MaxErr::new("ISCWSA #1 TVD vs sheet");
    for (k, r) in rows.iter().enumerate() {
        e.add(w.station_position(k).z - r[3], r[0]);
    }
    e.check(5e-3, "m");

    let table = [
        (2100.0, 111.219, 415.076, 1944.294),
        (5100.0, 783.651, 2924.625, 3444.294),
        (5190.0, 804.654, 3003.009, 3483.000),
        (5400.0, 857.797, 3201.342, 3521.056),
        (6000.0, 1013.089, 3780.898, 3521.056),
        (8000.0, 1530.727, 5712.749, 3521.056),
    ];
    let mut e = MaxErr::new("ISCWSA #1 N/E/TVD vs welleng");
    for &(md, n, ea, tvd) in &table {
        let k = rows.iter().position(|r| r[0] == md).expect("table MD is a station");
        let p = w.station_position(k);
        e.add(p.x - n, md);
        e.add(p.y - ea, md);
        e.add(p.z - tvd, md);
        // point_at at the station gives the same
        assert!((w.point_at(md).position - p).norm() < 1e-9);
    }
    e.check(1e-3, "m");
}

#[test]
fn iscwsa_example_well_2_feet() {
    // Reference: ISCWSA MWD Rev 5 example spreadsheet, well "ISCWSA Test #2" (feet, sheet TVD
    // with 2 decimals; the sheet's turn angles are rounded to 2 decimals): TVD at every station
    // within 0.034 ft (SOURCE.md). MD converted ft -> m with the library's unit table.
    let Some(path) = present(shared_data!(
        "iscwsa-error-model-example-wells/iscwsa_example_wells_1_2.csv"
    )) else {
        return;
    };
    let rows = iscwsa_well(&path, "2");
    assert_eq!(rows.len(), 131, "well 2 has 131 stations");
    let f = ft();
    let w = path_deg(
        &rows.iter().map(|r| (r[0] * f, r[1], r[2])).collect::<Vec<_>>(),
        Vec3::zeros(),
    );
    let mut e = MaxErr::new("ISCWSA #2 TVD vs sheet");
    for (k, r) in rows.iter().enumerate() {
        e.add(w.station_position(k).z / f - r[3], r[0]);
    }
    e.check(0.034, "ft");
}

// ----------------------------------------------------------------------------------------------
// 3. Volve 15/9-F-10 and 15/9-F-5 (real-time WITSML trajectories, metres)
// ----------------------------------------------------------------------------------------------

/// Read a Volve trajectory with `read_survey`, start at `origin` and compare the file's own
/// tvd/north/east columns at every station.
fn check_volve(path: &Path, origin: Vec3, tol_m: f64, label: &'static str) {
    let file = read_survey(path, &SurveyUnits::default()).expect("Volve survey reads");
    assert_eq!(file.md_unit, "m");
    assert_eq!(file.inc_unit, "deg");
    assert_eq!(file.azi_unit, "deg");
    let w = WellPath::new(&file.survey, origin).expect("valid well path");

    let (h, rows) = read_table(path);
    let (cm, ct, cn, ce) = (
        col(&h, "md [m]"),
        col(&h, "tvd [m]"),
        col(&h, "north [m]"),
        col(&h, "east [m]"),
    );
    assert_eq!(rows.len(), file.survey.len(), "every row is a station");
    // the tie-in row is the origin
    assert_eq!(num(&rows[0][cn]), origin.x);
    assert_eq!(num(&rows[0][ce]), origin.y);
    assert_eq!(num(&rows[0][ct]), origin.z);
    let mut e = MaxErr::new(label);
    for (k, r) in rows.iter().enumerate() {
        let md = num(&r[cm]);
        assert!((file.survey.stations()[k].md_m - md).abs() < 1e-9);
        let p = w.station_position(k);
        e.add(p.z - num(&r[ct]), md);
        e.add(p.x - num(&r[cn]), md);
        e.add(p.y - num(&r[ce]), md);
    }
    e.check(tol_m, "m");
}

#[test]
fn volve_15_9_f10_every_station() {
    // Reference: Equinor Volve 15/9-F-10 WITSML trajectory (Schlumberger), columns tvd, dispNs,
    // dispEw; started at the tie-in (N -3.9099744, E 2.2299168, TVD 0). Tolerance 3.4 mm
    // (SOURCE.md's stated agreement).
    let Some(path) = present(shared_data!("volve-15_9-F-10/15_9-F-10_actual_trajectory.csv")) else {
        return;
    };
    check_volve(
        &path,
        Vec3::new(-3.9099744, 2.2299168, 0.0),
        3.4e-3,
        "Volve 15/9-F-10 TVD/N/E vs WITSML",
    );
}

#[test]
fn volve_15_9_f5_every_station() {
    // Reference: Equinor Volve 15/9-F-5 17.5 in section WITSML trajectory (Schlumberger),
    // columns tvd, dispNs, dispEw; started at the tie-in (N -4.6500288, E 0.9198864, TVD 0).
    // Tolerance 1.0 mm (SOURCE.md).
    let Some(path) = present(shared_data!("volve-15_9-F-5/15_9-F-5_actual_trajectory_17.5in.csv")) else {
        return;
    };
    check_volve(
        &path,
        Vec3::new(-4.6500288, 0.9198864, 0.0),
        1.0e-3,
        "Volve 15/9-F-5 TVD/N/E vs WITSML",
    );
}

// ----------------------------------------------------------------------------------------------
// 4. Utah FORGE 16A(78)-32 and 16B(78)-32 (feet)
// ----------------------------------------------------------------------------------------------

#[test]
fn forge_16a_every_station() {
    // Reference: Utah FORGE 16A(78)-32 directional survey (GDR submission 1283, COMPASS export,
    // 2 decimals, feet): TVD, NS, EW within 0.005 ft at every station; final station TVD
    // 8,558.83 ft, NS -1,039.83 ft, EW 3,901.17 ft (0.005 ft). The header has no units: MD is
    // read as feet through `SurveyUnits`. DLS (deg/100 ft, 2 decimals) is also compared: 0.05.
    let path = example_dir("forge-16a").join("Directional_Survey16A-32.csv");
    let Some(path) = present(path.to_str().unwrap()) else {
        return;
    };
    let units = SurveyUnits {
        md: lookup("ft"),
        ..Default::default()
    };
    let file = read_survey(&path, &units).expect("FORGE 16A survey reads");
    assert_eq!(file.md_unit, "ft");
    assert_eq!(file.survey.len(), 422);
    let w = WellPath::new(&file.survey, Vec3::zeros()).expect("valid well path");
    let f = ft();

    let (h, rows) = read_table(&path);
    let (cm, ct, cn, ce, cd) = (
        col(&h, "Measured depth"),
        col(&h, "TVD"),
        col(&h, "NS"),
        col(&h, "EW"),
        col(&h, "DLS"),
    );
    assert_eq!(rows.len(), 422);
    let mut e = MaxErr::new("FORGE 16A TVD/NS/EW vs file");
    let mut ed = MaxErr::new("FORGE 16A DLS vs file");
    for (k, r) in rows.iter().enumerate() {
        let md = num(&r[cm]);
        assert!((w.stations()[k].md_m / f - md).abs() < 1e-9);
        let p = w.station_position(k) / f;
        e.add(p.z - num(&r[ct]), md);
        e.add(p.x - num(&r[cn]), md);
        e.add(p.y - num(&r[ce]), md);
        ed.add(w.dls_before(k).to_degrees() * 100.0 * f - num(&r[cd]), md);
    }
    e.check(0.005, "ft");
    ed.check(0.05, "deg/100ft");

    let last = w.station_position(421) / f;
    assert!((w.md_end() / f - 10955.0).abs() < 1e-9);
    assert!((last.z - 8558.83).abs() <= 0.005, "final TVD {}", last.z);
    assert!((last.x + 1039.83).abs() <= 0.005, "final NS {}", last.x);
    assert!((last.y - 3901.17).abs() <= 0.005, "final EW {}", last.y);
    // max DLS 15.0 deg/100 ft at 7,987 ft (SOURCE.md)
    let (dls, at) = w.max_dls();
    println!(
        "FORGE 16A max DLS {:.3} deg/100ft at {:.1} ft",
        dls.to_degrees() * 100.0 * f,
        at / f
    );
    assert!((at / f - 7987.0).abs() < 1e-6);
    assert!((dls.to_degrees() * 100.0 * f - 15.0).abs() < 0.05);
}

/// Data rows of the 16B report: lines of exactly 11 whitespace-separated numbers.
/// Columns: MD INC AZI TVD SSTVD N/S NORTHING E/W EASTING VSEC DLS.
fn forge_16b_rows(path: &Path) -> Vec<[f64; 11]> {
    let text = std::fs::read_to_string(path).expect("readable");
    text.lines()
        .filter_map(|l| {
            let v: Vec<f64> = l.split_whitespace().map_while(|t| t.parse::<f64>().ok()).collect();
            let n = l.split_whitespace().count();
            (n == 11 && v.len() == 11).then(|| v.try_into().unwrap())
        })
        .collect()
}

#[test]
fn forge_16b_every_station() {
    // Reference: Utah FORGE 16B(78)-32 final survey report (GDR submission 1516, minimum
    // curvature, grid north, 2 decimals, feet): TVD, N/S, E/W within 0.0066 ft at every
    // station (SOURCE.md says 0.0065, a rounded figure: any exact minimum-curvature
    // implementation, e.g. an independent Python one, gives 0.0065056 ft, TVD at 10,798 ft);
    // DLS within 0.05 deg/100 ft (the 17 ft survey-tie course ending at 10,417 ft is
    // compared too: it matches); final TVD 8,391.36, N/S -1,139.23, E/W 4,203.77 ft; VSEC
    // along 106.85 deg within 0.0066 ft as an extra check of N/E.
    let Some(path) = present(shared_data!("forge-16b78-32/16B78-32_Final_Survey_Report.txt")) else {
        return;
    };
    let rows = forge_16b_rows(&path);
    assert_eq!(rows.len(), 428, "428 stations");
    let f = ft();
    let w = path_deg(
        &rows.iter().map(|r| (r[0] * f, r[1], r[2])).collect::<Vec<_>>(),
        Vec3::zeros(),
    );
    let vs = 106.85f64.to_radians();
    let mut e = MaxErr::new("FORGE 16B TVD/NS/EW vs report");
    let mut ev = MaxErr::new("FORGE 16B VSEC vs report");
    let mut ed = MaxErr::new("FORGE 16B DLS vs report");
    let mut tie = f64::NAN;
    for (k, r) in rows.iter().enumerate() {
        let p = w.station_position(k) / f;
        e.add(p.z - r[3], r[0]);
        e.add(p.x - r[5], r[0]);
        e.add(p.y - r[7], r[0]);
        ev.add(p.x * vs.cos() + p.y * vs.sin() - r[9], r[0]);
        let dls = w.dls_before(k).to_degrees() * 100.0 * f;
        if r[0] == 10417.0 {
            tie = dls - r[10];
        }
        ed.add(dls - r[10], r[0]);
    }
    e.check(0.0066, "ft");
    ev.check(0.0066, "ft");
    println!("FORGE 16B DLS at the 10,417 ft survey tie: error {tie:.4} deg/100ft (report 15.73)");
    ed.check(0.05, "deg/100ft");
    let last = w.station_position(rows.len() - 1) / f;
    assert!((last.z - 8391.36).abs() <= 0.0066 && (last.x + 1139.23).abs() <= 0.0066);
    assert!((last.y - 4203.77).abs() <= 0.0066);
}

// ----------------------------------------------------------------------------------------------
// 5. Properties of every valid survey
// ----------------------------------------------------------------------------------------------

/// Inclination (deg): often exactly 0 or 180, sometimes within the near-vertical threshold
/// (sin I ~ 1e-6, i.e. ~6e-5 deg), else uniform.
fn inc_deg() -> impl Strategy<Value = f64> {
    prop_oneof![
        2 => Just(0.0),
        2 => Just(180.0),
        1 => 0.0..2e-4f64,
        1 => (180.0 - 2e-4)..180.0f64,
        8 => 0.0..=180.0f64,
    ]
}

fn azi_deg() -> impl Strategy<Value = f64> {
    prop_oneof![1 => Just(0.0), 1 => Just(360.0), 8 => 0.0..360.0f64]
}

/// (md m, inc deg, azi deg) of 3-12 stations, MD steps 1-200 m, no consecutive pair with a
/// dogleg above 179 deg (such a station is replaced by a 30 deg turn at the previous
/// inclination: an exact 180-deg reversal has no minimum-curvature arc).
fn survey_deg() -> impl Strategy<Value = Vec<(f64, f64, f64)>> {
    (
        -500.0..3000.0f64,
        prop::collection::vec((1.0..200.0f64, inc_deg(), azi_deg()), 3..=12),
    )
        .prop_map(|(md0, raw)| {
            let mut out: Vec<(f64, f64, f64)> = Vec::with_capacity(raw.len());
            let mut md = md0;
            for (k, (step, inc, azi)) in raw.into_iter().enumerate() {
                if k > 0 {
                    md += step;
                }
                let (mut inc, mut azi) = (inc, azi);
                if let Some(&(_, pi, pa)) = out.last() {
                    if tangent_deg(pi, pa).dot(&tangent_deg(inc, azi)) < 179f64.to_radians().cos() {
                        inc = pi;
                        azi = pa + 30.0;
                    }
                }
                out.push((md, inc, azi));
            }
            out
        })
}

/// `cases` cases; a failing case is saved beside this file, to
/// `tests/verification/geometry.proptest-regressions` (proptest's default source-parallel
/// location would be `tests/proptest-regressions/geometry.txt`).
fn config(cases: u32) -> ProptestConfig {
    ProptestConfig {
        cases,
        failure_persistence: Some(Box::new(FileFailurePersistence::WithSource("proptest-regressions"))),
        ..ProptestConfig::default()
    }
}

/// Largest dogleg severity (rad/m) of the path.
fn kmax(w: &WellPath) -> f64 {
    w.max_dls().0
}

/// Sample measured depths: every station, interior points, and a little beyond both ends.
fn sample_mds(w: &WellPath, per_interval: usize) -> Vec<f64> {
    let md: Vec<f64> = w.stations().iter().map(|s| s.md_m).collect();
    let mut out = vec![md[0] - 25.0, md[md.len() - 1] + 25.0];
    for k in 0..md.len() {
        out.push(md[k]);
        if k + 1 < md.len() {
            for i in 1..per_interval {
                out.push(md[k] + (md[k + 1] - md[k]) * i as f64 / per_interval as f64);
            }
        }
    }
    out
}

fn assert_orthonormal_right_handed(t: &Vec3, a: &Vec3, b: &Vec3, what: &str, md: f64) -> Result<(), TestCaseError> {
    const TOL: f64 = 1e-9;
    for (v, n) in [(t, "t"), (a, "second"), (b, "third")] {
        prop_assert!((v.norm() - 1.0).abs() < TOL, "{what} at {md}: |{n}| = {}", v.norm());
    }
    prop_assert!(t.dot(a).abs() < TOL, "{what} at {md}: t.2nd = {}", t.dot(a));
    prop_assert!(t.dot(b).abs() < TOL, "{what} at {md}: t.3rd = {}", t.dot(b));
    prop_assert!(a.dot(b).abs() < TOL, "{what} at {md}: 2nd.3rd = {}", a.dot(b));
    prop_assert!((t.cross(a) - b).norm() < TOL, "{what} at {md}: t x 2nd != 3rd");
    let det = t.dot(&a.cross(b));
    prop_assert!((det - 1.0).abs() < TOL, "{what} at {md}: det = {det}");
    Ok(())
}

proptest! {
    #![proptest_config(config(256))]

    #[test]
    fn prop_positions_continuous_in_md(st in survey_deg(), fracs in prop::collection::vec(0.0..1.0f64, 16)) {
        // Reference: the axis is an arc-length-parametrized C1 curve, so a chord is never longer
        // than its arc: |p(s+h) - p(s)| <= h (1 + 1e-9) + 1e-10 m (round-off on coordinates of
        // up to ~3 km) for h from 1e-7 m to 50 m, at random s, across stations and beyond both
        // ends; the tangent moves by at most kappa_max h (+1e-9).
        let w = path_deg(&st, Vec3::new(10.0, -20.0, 30.0));
        let (a, b) = (w.md_start() - 50.0, w.md_end() + 50.0);
        let km = kmax(&w);
        let mut ss: Vec<f64> = fracs.iter().map(|u| a + (b - a) * u).collect();
        for s in w.stations() {
            ss.push(s.md_m - 5e-8);
            ss.push(s.md_m);
        }
        for &s in &ss {
            let p0 = w.point_at(s);
            for h in [1e-7, 1e-4, 0.1, 3.0, 50.0] {
                let p1 = w.point_at(s + h);
                let d = (p1.position - p0.position).norm();
                prop_assert!(d <= h * (1.0 + 1e-9) + 1e-10, "chord {d} > h {h} at s {s}");
                let dt = (p1.tangent - p0.tangent).norm();
                prop_assert!(dt <= km * h * (1.0 + 1e-9) + 1e-9, "tangent jump {dt} > kappa h at s {s}, h {h}");
            }
        }
    }

    #[test]
    fn prop_point_at_station_returns_station(st in survey_deg()) {
        // Reference: interpolation at a station's MD must return that station (docs/theory.md 2.2):
        // position == station_position(k), tangent == (sin I cos A, sin I sin A, cos I),
        // inclination and (non-vertical) azimuth as surveyed; 1e-9.
        let w = path_deg(&st, Vec3::new(-3.0, 2.0, 0.5));
        for (k, s) in w.stations().iter().enumerate() {
            let p = w.point_at(s.md_m);
            prop_assert_eq!(p.md_m, s.md_m);
            prop_assert!((p.position - w.station_position(k)).norm() < 1e-9, "position at station {}", k);
            let t = Vec3::new(s.inc_rad.sin() * s.azi_rad.cos(), s.inc_rad.sin() * s.azi_rad.sin(), s.inc_rad.cos());
            prop_assert!((p.tangent - t).norm() < 1e-9, "tangent at station {}", k);
            prop_assert!((p.inc_rad - s.inc_rad).abs() < 1e-9, "inc at station {}: {} vs {}", k, p.inc_rad, s.inc_rad);
            if s.inc_rad.sin() > 1e-3 {
                prop_assert!(wrap(p.azi_rad - s.azi_rad).abs() < 1e-9, "azi at station {}", k);
            }
        }
        prop_assert_eq!(w.station_position(0), Vec3::new(-3.0, 2.0, 0.5));
    }

    #[test]
    fn prop_azimuth_shift_rotates_north_east(st in survey_deg(), shift in prop_oneof![Just(360.0), -720.0..720.0f64]) {
        // Reference: minimum curvature is invariant under rotation about the vertical: adding
        // `shift` to every azimuth rotates (north, east) by `shift` about the origin and leaves
        // TVD, doglegs and DLS unchanged; 1e-9 m / 1e-9 rad(/m), at stations and between them.
        let w1 = path_deg(&st, Vec3::zeros());
        let rotated: Vec<_> = st.iter().map(|&(m, i, a)| (m, i, a + shift)).collect();
        let w2 = path_deg(&rotated, Vec3::zeros());
        let (sc, cc) = shift.to_radians().sin_cos();
        let rot = |p: Vec3| Vec3::new(cc * p.x - sc * p.y, sc * p.x + cc * p.y, p.z);
        for (k, _) in st.iter().enumerate() {
            let (p1, p2) = (w1.station_position(k), w2.station_position(k));
            prop_assert!((rot(p1) - p2).norm() < 1e-9, "station {}: {:?} vs {:?}", k, rot(p1), p2);
            prop_assert!((p1.z - p2.z).abs() < 1e-9);
            prop_assert!((w1.dls_before(k) - w2.dls_before(k)).abs() < 1e-9);
            prop_assert!((w1.dogleg_before(k) - w2.dogleg_before(k)).abs() < 1e-9);
        }
        prop_assert!((w1.max_dls().0 - w2.max_dls().0).abs() < 1e-9);
        for s in sample_mds(&w1, 5) {
            let (a, b) = (w1.point_at(s), w2.point_at(s));
            prop_assert!((rot(a.position) - b.position).norm() < 1e-9, "point at {}", s);
            prop_assert!((rot(a.tangent) - b.tangent).norm() < 1e-9, "tangent at {}", s);
            prop_assert!((a.curvature_per_m - b.curvature_per_m).abs() < 1e-9);
        }
    }

    #[test]
    fn prop_frames_orthonormal_right_handed(st in survey_deg(), fracs in prop::collection::vec(0.0..1.0f64, 8)) {
        // Reference: frame_at = (t, h, r) and bishop_at = (t, b1, b2) are orthonormal with
        // t x h = r, t x b1 = b2, det +1, everywhere incl. inclination 0 and 180 (1e-9); t is the
        // axis tangent; away from vertical h points up-hole (h_z = -sin I) and r is horizontal;
        // at an exactly vertical station h points to the surveyed azimuth (inc 0) or away
        // from it (inc 180) (docs/guide.md, Conventions); the Bishop frame does not twist: over a
        // step h, |b1(s+h).b2(s)| <= (kappa_max h)^2/2 (+1e-9). Within one arc b1 turns about
        // the arc's binormal by a = kappa h and b2.b1' = (n.b1)(n.b2)(1 - cos a) <= a^2/4; a
        // step across a station composes two such turns a and b about different axes, whose
        // second-order cross term adds up to a b: a^2/4 + b^2/4 + a b <= (a + b)^2/2.
        let w = path_deg(&st, Vec3::zeros());
        let km = kmax(&w);
        let mut ss = sample_mds(&w, 7);
        let (a, b) = (w.md_start() - 10.0, w.md_end() + 10.0);
        ss.extend(fracs.iter().map(|u| a + (b - a) * u));
        for &s in &ss {
            let p = w.point_at(s);
            let f: Frame = w.frame_at(s);
            assert_orthonormal_right_handed(&f.t, &f.h, &f.r, "frame_at", s)?;
            prop_assert!((f.t - p.tangent).norm() < 1e-9, "frame t != tangent at {}", s);
            let sin_i = (f.t.x * f.t.x + f.t.y * f.t.y).sqrt();
            if sin_i > 1e-6 {
                prop_assert!((f.h.z + sin_i).abs() < 1e-9, "h not high side at {}: {:?}", s, f.h);
                prop_assert!(f.r.z.abs() < 1e-9, "r not horizontal at {}: {:?}", s, f.r);
            }
            let (t, b1, b2) = w.bishop_at(s);
            assert_orthonormal_right_handed(&t, &b1, &b2, "bishop_at", s)?;
            prop_assert!((t - p.tangent).norm() < 1e-9, "bishop t != tangent at {}", s);
            for hstep in [1e-3, 0.5] {
                let (_, b1n, _) = w.bishop_at(s + hstep);
                let twist = b1n.dot(&b2).abs();
                prop_assert!(twist <= (km * hstep).powi(2) / 2.0 + 1e-9, "Bishop twist {} at {}", twist, s);
            }
        }
        for s in w.stations() {
            let f = w.frame_at(s.md_m);
            let toward = Vec3::new(s.azi_rad.cos(), s.azi_rad.sin(), 0.0);
            if s.inc_rad == 0.0 {
                prop_assert!((f.h - toward).norm() < 1e-9, "h at vertical station {}", s.md_m);
            } else if s.inc_rad == PI {
                prop_assert!((f.h + toward).norm() < 1e-9, "h at inverted station {}", s.md_m);
            }
        }
    }

    #[test]
    fn prop_arc_length_equals_md(st in survey_deg(), pairs in prop::collection::vec((0.0..1.0f64, 0.0..1.0f64), 6)) {
        // Reference: each interval is a circular arc of length dM and dogleg beta, so the
        // chord is dM sin(beta/2)/(beta/2) (1e-9 m), also for any sub-arc inside an interval;
        // beta is the angle between the station tangents, 2 asin(|t2 - t1|/2) (1e-9 rad); the
        // sum of N = 512 sub-chords (numerical integral of |dp/ds|) equals dM within its
        // discretization error dM beta^2/(24 N^2) + 1e-9 m.
        let w = path_deg(&st, Vec3::new(1.0, 1.0, 1.0));
        let sts = w.stations();
        for k in 0..sts.len() - 1 {
            let (m0, m1) = (sts[k].md_m, sts[k + 1].md_m);
            let dm = m1 - m0;
            let beta = w.dogleg_before(k + 1);
            let t0 = tangent_deg(st[k].1, st[k].2);
            let t1 = tangent_deg(st[k + 1].1, st[k + 1].2);
            let beta_ref = 2.0 * ((t1 - t0).norm() / 2.0).min(1.0).asin();
            prop_assert!((beta - beta_ref).abs() < 1e-9, "dogleg {} vs {}", beta, beta_ref);
            prop_assert!((w.dls_before(k + 1) - beta / dm).abs() < 1e-12);
            let chord = (w.station_position(k + 1) - w.station_position(k)).norm();
            prop_assert!((chord - dm * sinc(beta / 2.0)).abs() < 1e-9, "chord {} vs {}", chord, dm * sinc(beta / 2.0));
            let kappa = beta / dm;
            for &(u, v) in &pairs {
                let (sa, sb) = (m0 + dm * u.min(v), m0 + dm * u.max(v));
                let c = (w.point_at(sb).position - w.point_at(sa).position).norm();
                let l = sb - sa;
                let c_ref = l * sinc(kappa * l / 2.0);
                prop_assert!((c - c_ref).abs() < 1e-9, "sub-chord {} vs {}", c, c_ref);
            }
            let n = 512;
            let mut len = 0.0;
            let mut prev = w.point_at(m0).position;
            for i in 1..=n {
                let p = w.point_at(m0 + dm * i as f64 / n as f64).position;
                len += (p - prev).norm();
                prev = p;
            }
            let disc = dm * beta * beta / (24.0 * (n * n) as f64);
            prop_assert!((len - dm).abs() <= disc * 1.01 + 1e-9, "arc length {} vs dM {} (disc {})", len, dm, disc);
        }
    }
}

#[test]
fn reversal_is_rejected_and_near_reversal_is_an_arc() {
    // Reference: an exact 180-deg dogleg has no minimum-curvature arc (WellPath::new must
    // fail, not produce NaN); a 179 deg dogleg is an arc of length dM: chord
    // dM sin(beta/2)/(beta/2) within 1e-9 m and unit tangents (1e-9) all along.
    let s = Survey::new(vec![
        Station::from_deg(0.0, 90.0, 10.0),
        Station::from_deg(50.0, 90.0, 190.0),
    ])
    .unwrap();
    assert!(WellPath::new(&s, Vec3::zeros()).is_err());
    let w = path_deg(&[(0.0, 0.0, 0.0), (100.0, 179.0, 45.0)], Vec3::zeros());
    let beta = w.dogleg_before(1);
    assert!((beta - 179f64.to_radians()).abs() < 1e-12);
    assert!((w.station_position(1).norm() - 100.0 * sinc(beta / 2.0)).abs() < 1e-9);
    for i in 0..=100 {
        let p = w.point_at(i as f64);
        assert!((p.tangent.norm() - 1.0).abs() < 1e-9);
    }
}
