//! Azimuths converted from the north the survey file states to the one the case asks for
//! (`[well] azimuth_reference`).
//!
//! Sign conventions (docs/guide.md, "Azimuth reference"), the usual ones of directional
//! surveying and of WITSML's `magDeclUsed` / `gridCorUsed`:
//! - magnetic declination `D`, east positive: `azi_true = azi_magnetic + D`;
//! - grid convergence `C`, the angle from true north to grid north, clockwise (east) positive:
//!   `azi_grid = azi_true - C`, so `azi_true = azi_grid + C`;
//! - so `azi_grid = azi_magnetic + D - C` (the "total correction" `D - C`).

use crate::case::{AzimuthReference, SurveyFile};
use crate::geometry::survey::normalize_azimuth;
use crate::geometry::{Station, Survey};
use crate::units::message_number;

/// The angle (rad) to add to an azimuth from `r` to make it an azimuth from true north, with the
/// name of the element it comes from; `Err` names what the file does not give.
fn to_true(r: AzimuthReference, file: &SurveyFile) -> Result<(f64, &'static str), String> {
    match r {
        AzimuthReference::True => Ok((0.0, "")),
        AzimuthReference::Grid => file
            .grid_convergence_rad
            .map(|c| (c, "gridCorUsed"))
            .ok_or_else(|| "the survey file gives no grid convergence (WITSML `gridCorUsed`)".to_string()),
        AzimuthReference::Magnetic => file
            .magnetic_declination_rad
            .map(|d| (d, "magDeclUsed"))
            .ok_or_else(|| "the survey file gives no magnetic declination (WITSML `magDeclUsed`)".to_string()),
        AzimuthReference::Unspecified => Err("the survey file does not state the north its azimuths are measured from (a qualified azimuth column such as `Azimuth Grid`, a report's `NORTH REF` line or a WITSML `aziRef`)".to_string()),
    }
}

/// Convert the azimuths of `file` (stations and projected stations) to `to`; a note says by how
/// much and why. `Err` says what is missing to do it.
pub fn convert_reference(file: &mut SurveyFile, to: AzimuthReference) -> Result<(), String> {
    let from = file.azimuth_reference;
    if from == to {
        return Ok(());
    }
    let cannot = |why: String| {
        format!(
            "cannot convert the azimuths from {} to {}: {why}",
            from.describe(),
            to.describe()
        )
    };
    let (a, a_name) = to_true(from, file).map_err(cannot)?;
    let (b, b_name) = to_true(to, file).map_err(cannot)?;
    let shift = a - b;
    let turn = |s: &Station| Station {
        azi_rad: normalize_azimuth(s.azi_rad + shift),
        ..*s
    };
    let stations: Vec<Station> = file.survey.stations().iter().map(turn).collect();
    file.survey = Survey::new(stations).map_err(|p| cannot(p.message))?;
    for (s, _) in &mut file.projected {
        *s = turn(s);
    }
    let mut terms = Vec::new();
    if !a_name.is_empty() {
        terms.push(format!("+ {a_name} {} deg", message_number(a.to_degrees())));
    }
    if !b_name.is_empty() {
        terms.push(format!("- {b_name} {} deg", message_number(b.to_degrees())));
    }
    file.notes.push(format!(
        "azimuths converted from {} to {} (case key `azimuth_reference`): {} = {} deg added to every azimuth",
        from.describe(),
        to.describe(),
        terms.join(" "),
        message_number(shift.to_degrees())
    ));
    let was = if file.azimuth_reference_source.is_empty() {
        from.describe().to_string()
    } else {
        format!("{}, {}", from.describe(), file.azimuth_reference_source)
    };
    file.azimuth_reference_source = format!("`[well] azimuth_reference`, converted from {was}");
    file.azimuth_reference = to;
    Ok(())
}

/// The reference named by a case value: `true`, `grid`, `magnetic` (also `true north`, ...).
pub fn parse_reference(text: &str) -> Option<AzimuthReference> {
    super::header::reference_word(text).filter(|r| *r != AzimuthReference::Unspecified)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn file(reference: AzimuthReference, decl: Option<f64>, conv: Option<f64>, azi_deg: f64) -> SurveyFile {
        SurveyFile {
            survey: Survey::new(vec![
                Station::from_deg(0.0, 0.0, 0.0),
                Station::from_deg(100.0, 10.0, azi_deg),
            ])
            .unwrap(),
            md_unit: "m".into(),
            inc_unit: "deg".into(),
            azi_unit: "deg".into(),
            notes: vec![],
            station_lines: vec![1, 2],
            azimuth_reference: reference,
            azimuth_reference_source: String::new(),
            magnetic_declination_rad: decl.map(f64::to_radians),
            grid_convergence_rad: conv.map(f64::to_radians),
            origin: None,
            station_info: vec![],
            projected: vec![],
        }
    }

    fn azi(f: &SurveyFile) -> f64 {
        f.survey.stations()[1].azi_rad.to_degrees()
    }

    /// The sign conventions: at Volve (west of UTM 31's central meridian, convergence -0.95
    /// deg, declination -2.21 deg), grid 100 deg is true 99.05 deg and magnetic 101.26 deg.
    #[test]
    fn sign_conventions() {
        use AzimuthReference::*;
        let cases = [
            (Grid, True, 100.0, 99.05),
            (True, Grid, 99.05, 100.0),
            (Magnetic, True, 101.26, 99.05),
            (True, Magnetic, 99.05, 101.26),
            (Magnetic, Grid, 101.26, 100.0),
            (Grid, Magnetic, 100.0, 101.26),
            (Grid, Grid, 100.0, 100.0),
        ];
        for (from, to, a, b) in cases {
            let mut f = file(from, Some(-2.21), Some(-0.95), a);
            convert_reference(&mut f, to).unwrap();
            assert!((azi(&f) - b).abs() < 1e-9, "{from:?} -> {to:?}: {} != {b}", azi(&f));
            assert_eq!(f.azimuth_reference, to);
        }
        // wrap through north
        let mut f = file(Grid, None, Some(-0.95), 0.5);
        convert_reference(&mut f, True).unwrap();
        assert!((azi(&f) - 359.55).abs() < 1e-9, "{}", azi(&f));
        assert!(
            f.notes[0].contains("+ gridCorUsed -0.95 deg") && f.notes[0].contains("-0.95 deg added"),
            "{:?}",
            f.notes
        );
    }

    #[test]
    fn missing_angles_are_named() {
        let mut f = file(AzimuthReference::Grid, Some(-2.21), None, 10.0);
        let e = convert_reference(&mut f, AzimuthReference::True).unwrap_err();
        assert!(
            e.contains("gridCorUsed") && e.contains("from grid north to true north"),
            "{e}"
        );
        let mut f = file(AzimuthReference::Unspecified, Some(1.0), Some(1.0), 10.0);
        let e = convert_reference(&mut f, AzimuthReference::True).unwrap_err();
        assert!(e.contains("does not state the north"), "{e}");
    }
}
