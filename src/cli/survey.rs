//! `drillpath survey`: minimum-curvature positions and a short summary.

use super::args::SurveyArgs;
use super::outputs::Outputs;
use super::parse_length_unit;
use crate::geometry::{Vec3, WellPath};
use crate::io::case_toml::{load_case, CaseOverrides};
use crate::io::survey::{read_survey, survey_format, SurveyFormat, SurveyUnits};
use crate::report::survey_table::survey_csv;
use std::io::Write;

/// Run the command.
pub fn run(a: SurveyArgs) -> anyhow::Result<()> {
    let md_unit = a
        .md_unit
        .as_deref()
        .map(|u| parse_length_unit("--md-unit", u))
        .transpose()?;
    let is_toml = a.input.extension().is_some_and(|e| e.eq_ignore_ascii_case("toml"));
    let format = survey_format(&a.input);
    if a.trajectory.is_some() && (is_toml || format != SurveyFormat::Witsml) {
        return Err(crate::InputError::option(
            "--trajectory",
            "applies to a WITSML survey file only (in a case file, choose with `[well] survey_trajectory`)",
        )
        .into());
    }
    if a.sheet.is_some() && (is_toml || format != SurveyFormat::Spreadsheet) {
        return Err(crate::InputError::option(
            "--sheet",
            "applies to a spreadsheet survey file only (in a case file, choose with `[well] survey_sheet`)",
        )
        .into());
    }
    let mut outputs = Outputs::new();
    let (path, file, label) = if is_toml {
        let case = load_case(
            &a.input,
            &CaseOverrides {
                survey_md_unit: md_unit,
                bit_md_m: None,
            },
        )?;
        let label = format!("{} ({})", case.name, case.well.survey_path.display());
        outputs.case_inputs(&case);
        if let Some(w) = crate::models::checks::dogleg_warning(&case) {
            tracing::warn!("{}: {w}", a.input.display());
        }
        (case.well.path, case.well.survey, label)
    } else {
        let sf = read_survey(
            &a.input,
            &SurveyUnits {
                md: md_unit,
                angle: None,
                trajectory: a.trajectory.clone(),
                sheet: a.sheet.clone(),
            },
        )?;
        let origin = sf.origin.map_or_else(Vec3::zeros, |o| Vec3::new(o[0], o[1], o[2]));
        let wp = WellPath::new(&sf.survey, origin).map_err(|p| {
            let line = sf.station_lines.get(p.index).copied().unwrap_or(0);
            crate::InputError::line(&a.input, line, Some("inc/azi"), p.message)
        })?;
        outputs.input(&a.input);
        (wp, sf, a.input.display().to_string())
    };
    if let Some(out) = &a.out {
        outputs.file("--out", out)?;
    }
    let table = survey_csv(&path).map_err(|e| anyhow::anyhow!("internal error: {e}"))?;
    if let Some(out) = &a.out {
        outputs.stage(out.clone(), table.as_bytes());
    }
    outputs.commit()?;
    let mut out = std::io::stdout().lock();
    if a.csv {
        out.write_all(table.as_bytes())?;
        return Ok(());
    }
    let n = path.stations().len();
    let last = path.station_position(n - 1);
    let (max_dls, at) = path.max_dls();
    writeln!(out, "survey: {label}")?;
    for note in &file.notes {
        writeln!(out, "  note: {note}")?;
    }
    let reference = file.azimuth_reference.describe();
    match file.azimuth_reference_source.as_str() {
        "" => writeln!(out, "  azimuth reference: {reference} (azimuths used as written)")?,
        source => writeln!(out, "  azimuth reference: {reference} (from {source})")?,
    }
    writeln!(
        out,
        "  stations: {n}, MD {:.2} m to {:.2} m",
        path.md_start(),
        path.md_end()
    )?;
    writeln!(out, "  total depth: {:.2} m MD, {:.2} m TVD", path.md_end(), last.z)?;
    writeln!(
        out,
        "  max DLS: {:.2} deg/30m in the interval ending at {:.2} m MD",
        max_dls.to_degrees() * 30.0,
        at
    )?;
    writeln!(
        out,
        "  final position: north {:.2} m, east {:.2} m, TVD {:.2} m (horizontal displacement {:.2} m)",
        last.x,
        last.y,
        last.z,
        (last.x * last.x + last.y * last.y).sqrt()
    )?;
    if let Some(file) = &a.out {
        writeln!(out, "  wrote {}", file.display())?;
    }
    Ok(())
}
