//! Survey file reader: measured depth, inclination and azimuth columns found by name in a
//! delimited (CSV) file, a whitespace-separated text report or a spreadsheet (module `sheet`,
//! the CSV rules on one sheet's cells), converted to SI and validated into a [`Survey`]; a
//! WITSML trajectory is read by [`crate::io::witsml::trajectory`].
//!
//! The contract (docs/guide.md, "Survey file rules"):
//! - a UTF-8 BOM is stripped, CRLF is accepted, a file that is not UTF-8 is read as Latin-1;
//!   blank lines and lines whose first non-space character is `#` are skipped;
//! - **CSV** (module `csv`): the first remaining line is the header; the delimiter is a comma, or
//!   `;` / tab when the header has no comma but has one of those;
//! - **text report** (module `text_report`): when that first line does not name the three columns,
//!   the file is read as a whitespace-separated report if some later line does: free-text and
//!   `KEY : value` lines before it (a `NORTH REF : Grid` line states the azimuth reference),
//!   then the header line, then the stations, one per line;
//! - in both, an optional units line right after the header (`(ft) (deg) (deg)`) gives the
//!   units of the columns;
//! - columns are found by name (module `header`): case-insensitive, ignoring spaces, underscores,
//!   hyphens, dots and a unit in brackets or as a suffix; an azimuth column may be qualified
//!   `grid`, `true` or `magnetic`, which sets the [`AzimuthReference`] carried by the result;
//! - a column without a unit takes the caller's override ([`SurveyUnits`]), else m / deg;
//! - every error names the file and, past the header, the 1-based line of the original file
//!   and the column.

mod csv;
mod header;
mod north;
mod sheet;
mod text_report;

pub use north::{convert_reference, parse_reference};

use std::path::Path;

use crate::case::{AzimuthReference, SurveyFile};
use crate::error::{InputError, InputResult};
use crate::geometry::survey::{Station, Survey, SurveyProblem};
use crate::units::Unit;
use header::{Column, Role};

pub(crate) use csv::{detect_delimiter, split_fields};
pub(crate) use header::{normalize_name, split_header_unit};

/// Units to assume for columns whose header carries no unit (from the case file or command line).
#[derive(Debug, Clone, Default)]
pub struct SurveyUnits {
    /// Unit of a measured-depth column without a unit in its header (a length unit).
    pub md: Option<Unit>,
    /// Unit of inclination / azimuth columns without a unit in their header (an angle unit).
    pub angle: Option<Unit>,
    /// Which trajectory of a WITSML file to read, by name or uid (`None`: the only one); not
    /// used for other files (callers refuse it there, naming their key or option).
    pub trajectory: Option<String>,
    /// Which sheet of a spreadsheet to read, by name (`None`: the first with a survey header);
    /// not used for other files (callers refuse it there).
    pub sheet: Option<String>,
}

/// The kinds of survey file, which decide the reader.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SurveyFormat {
    /// A WITSML 1.4.1.1 trajectory (`.xml`, or contents starting with `<`).
    Witsml,
    /// A spreadsheet (`.xlsx`, `.xlsm`, `.xlsb`, `.xls`, `.ods`).
    Spreadsheet,
    /// A CSV or a whitespace-separated text report (anything else).
    Text,
}

/// The format of the survey file at `path`, by its extension, else by its first bytes (a file
/// that cannot be read is `Text`: the reader then says why).
pub fn survey_format(path: &Path) -> SurveyFormat {
    let ext = path
        .extension()
        .and_then(|e| e.to_str())
        .unwrap_or("")
        .to_ascii_lowercase();
    match ext.as_str() {
        "xml" => SurveyFormat::Witsml,
        "xlsx" | "xlsm" | "xlsb" | "xls" | "ods" => SurveyFormat::Spreadsheet,
        _ => {
            use std::io::Read;
            let mut head = Vec::new();
            let read = std::fs::File::open(path).and_then(|f| f.take(256).read_to_end(&mut head));
            if read.is_ok() && crate::io::witsml::looks_like_xml(&head) {
                SurveyFormat::Witsml
            } else {
                SurveyFormat::Text
            }
        }
    }
}

/// Read and validate the survey file at `path`: a WITSML 1.4.1.1 trajectory (extension `.xml`,
/// or contents starting with `<`; [`crate::io::witsml::trajectory`]), a spreadsheet (`.xlsx`,
/// `.xlsm`, `.xlsb`, `.xls`, `.ods`: one sheet read with the CSV rules), or a CSV or text
/// report (see the module documentation).
pub fn read_survey(path: &Path, units: &SurveyUnits) -> InputResult<SurveyFile> {
    let ext = path
        .extension()
        .and_then(|e| e.to_str())
        .unwrap_or("")
        .to_ascii_lowercase();
    if ext == "xml" {
        let text = crate::io::witsml::read_text(path)?;
        return read_trajectory(&text, path, units);
    }
    if survey_format(path) == SurveyFormat::Spreadsheet {
        return sheet::read_sheet(path, units);
    }
    let bytes = std::fs::read(path).map_err(|e| InputError::file(path, format!("cannot read the survey file: {e}")))?;
    parse_survey(&bytes, path, units)
}

/// A WITSML trajectory read with `units`' choice of trajectory; the unit overrides do not apply
/// (every WITSML measure carries its unit) and a sheet name is refused.
fn read_trajectory(text: &str, path: &Path, units: &SurveyUnits) -> InputResult<SurveyFile> {
    let mut file = crate::io::witsml::trajectory::parse_trajectory(text, path, units.trajectory.as_deref())?;
    if units.md.is_some() {
        file.notes.push(
            "the MD unit given by the case file or command line is not used: every WITSML measure carries its own `uom`".into(),
        );
    }
    Ok(file)
}

/// Parse and validate the survey file contents `bytes`; `path` is used only in messages.
///
/// Bytes that are not valid UTF-8 are read as Latin-1 (so a `°` written by a legacy tool still
/// works), with a note saying so.
pub fn parse_survey(bytes: &[u8], path: &Path, units: &SurveyUnits) -> InputResult<SurveyFile> {
    if crate::io::witsml::looks_like_xml(bytes) {
        let text = crate::io::witsml::text_of(bytes.to_vec(), path)?;
        return read_trajectory(&text, path, units);
    }
    match std::str::from_utf8(bytes) {
        Ok(text) => parse_text(text, path, units),
        Err(_) => {
            let text: String = bytes.iter().map(|&b| char::from(b)).collect();
            let mut file = parse_text(&text, path, units)?;
            file.notes
                .push("the file is not valid UTF-8 text: it was read as Latin-1 (ISO 8859-1)".into());
            Ok(file)
        }
    }
}

/// A line of the file that is neither blank nor a comment: its 1-based number in the original
/// file and its text without the line end.
#[derive(Debug, Clone, Copy)]
struct Line<'a> {
    no: usize,
    text: &'a str,
}

fn parse_text(text: &str, path: &Path, units: &SurveyUnits) -> InputResult<SurveyFile> {
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    let lines: Vec<Line> = text
        .lines()
        .enumerate()
        .map(|(i, l)| Line {
            no: i + 1,
            text: l.strip_suffix('\r').unwrap_or(l),
        })
        .filter(|l| {
            let t = l.text.trim();
            !t.is_empty() && !t.starts_with('#')
        })
        .collect();
    if lines.is_empty() {
        let what = if text.trim().is_empty() {
            "the survey file is empty"
        } else {
            "the survey file contains only comments and blank lines"
        };
        return Err(InputError::file(
            path,
            format!(
                "{what}: expected a header row such as `md [m],inc [deg],azi [deg]` followed by one row per station"
            ),
        ));
    }
    match csv::parse(&lines, path, units) {
        Ok(file) => Ok(file),
        Err(csv::Failure::Header(e)) => text_report::parse(&lines, path, units).unwrap_or(Err(e)),
        Err(csv::Failure::Other(e)) => Err(e),
    }
}

/// One data row: its line, the three texts as written and their SI values.
#[derive(Debug, Clone)]
struct Row {
    line: usize,
    raw: [String; 3],
    si: [f64; 3],
}

/// Parse a number; with `decimal_comma` a single comma as the decimal sign (`12,5`) is
/// accepted too.
fn parse_number(text: &str, decimal_comma: bool) -> Option<f64> {
    if let Ok(v) = text.parse::<f64>() {
        return Some(v);
    }
    if decimal_comma && text.matches(',').count() == 1 && !text.contains('.') {
        return text.replace(',', ".").parse::<f64>().ok();
    }
    None
}

/// The md, inc and azi values of the data row `fields` on line `line`, converted with the
/// columns' SI `factors`.
fn read_row(
    line: usize,
    fields: &[&str],
    columns: &[Column; 3],
    factors: [f64; 3],
    decimal_comma: bool,
    path: &Path,
) -> InputResult<Row> {
    let mut raw: [String; 3] = Default::default();
    let mut si = [0.0; 3];
    for (k, col) in columns.iter().enumerate() {
        let what = col.role.what();
        let at = |message: String| InputError::line(path, line, Some(&col.header), message);
        let Some(&txt) = fields.get(col.index) else {
            return Err(at(format!(
                "too few fields: the row has {} field{} but the {what} column `{}` is field {} of the header",
                fields.len(),
                if fields.len() == 1 { "" } else { "s" },
                col.header,
                col.index + 1
            )));
        };
        if txt.is_empty() {
            return Err(at(format!("the {what} value is missing (empty field)")));
        }
        let v =
            parse_number(txt, decimal_comma).ok_or_else(|| at(format!("the {what} value `{txt}` is not a number")))?;
        if !v.is_finite() {
            return Err(at(format!(
                "the {what} value `{txt}` is not a finite number (NaN or infinite)"
            )));
        }
        raw[k] = txt.to_string();
        si[k] = v * factors[k];
    }
    Ok(Row { line, raw, si })
}

/// What a reader found, before validation.
struct Found {
    columns: [Column; 3],
    units: [Unit; 3],
    rows: Vec<Row>,
    notes: Vec<String>,
    /// The azimuth reference and where the file states it ("" if it does not).
    reference: (AzimuthReference, String),
    /// Line of the header (for "no data rows").
    header_line: usize,
}

/// Validate the rows into a [`SurveyFile`]; problems are mapped back to their line and column.
fn finish(found: Found, path: &Path) -> InputResult<SurveyFile> {
    let Found {
        columns,
        units,
        rows,
        notes,
        reference,
        header_line,
    } = found;
    if rows.is_empty() {
        return Err(InputError::line(
            path,
            header_line,
            None,
            "the header is followed by no data rows: the survey needs at least one station",
        ));
    }
    let stations: Vec<Station> = rows
        .iter()
        .map(|r| Station {
            md_m: r.si[0],
            inc_rad: r.si[1],
            azi_rad: r.si[2],
        })
        .collect();
    let names = [units[0].name, units[1].name, units[2].name];
    let survey = Survey::new(stations).map_err(|p| problem_to_error(&p, &rows, &columns, &names, path))?;
    Ok(SurveyFile {
        survey,
        md_unit: names[0].to_string(),
        inc_unit: names[1].to_string(),
        azi_unit: names[2].to_string(),
        notes,
        station_lines: rows.iter().map(|r| r.line).collect(),
        azimuth_reference: reference.0,
        azimuth_reference_source: reference.1,
        magnetic_declination_rad: None,
        grid_convergence_rad: None,
        origin: None,
        station_info: Vec::new(),
        projected: Vec::new(),
    })
}

/// Map a [`SurveyProblem`] back to the line and column of the offending station, with the
/// values as written in the file.
fn problem_to_error(p: &SurveyProblem, rows: &[Row], cols: &[Column; 3], units: &[&str; 3], path: &Path) -> InputError {
    let Some(row) = rows.get(p.index) else {
        return InputError::file(path, p.message.clone());
    };
    let Some(k) = Role::ALL.iter().position(|r| r.key() == p.field) else {
        return InputError::line(path, row.line, None, p.message.clone());
    };
    let col = &cols[k];
    let message = match col.role {
        Role::Md => match p.index.checked_sub(1).and_then(|i| rows.get(i)) {
            Some(prev) if row.si[0].is_finite() && row.si[0] <= prev.si[0] => format!(
                "measured depth {} {u} is not greater than {} {u} on line {} (the previous station); MD must strictly increase down the file",
                row.raw[0],
                prev.raw[0],
                prev.line,
                u = units[0]
            ),
            _ => format!("measured depth {} {}: {}", row.raw[0], units[0], p.message),
        },
        Role::Inc => {
            let deg = if units[1] == "deg" { String::new() } else { format!(" ({:.4} deg)", row.si[1].to_degrees()) };
            format!("inclination {} {}{deg} is outside [0, 180] deg", row.raw[1], units[1])
        }
        Role::Azi => format!("azimuth {} {}: {}", row.raw[2], units[2], p.message),
    };
    InputError::line(path, row.line, Some(&col.header), message)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A column without azimuth qualifier.
    fn column(role: Role, index: usize, header: &str, unit: Option<&str>) -> Column {
        Column {
            role,
            index,
            header: header.into(),
            unit: unit.map(str::to_string),
            unit_line: 1,
            reference: AzimuthReference::Unspecified,
        }
    }

    #[test]
    fn problem_mapping_fallbacks() {
        let rows = vec![Row {
            line: 7,
            raw: ["1e308".into(), "0".into(), "0".into()],
            si: [f64::INFINITY, 0.0, 0.0],
        }];
        let cols = [
            column(Role::Md, 0, "md [km]", Some("km")),
            column(Role::Inc, 1, "inc", None),
            column(Role::Azi, 2, "azi", None),
        ];
        let p = SurveyProblem {
            index: 0,
            field: "md",
            message: "measured depth is not finite".into(),
        };
        let e = problem_to_error(&p, &rows, &cols, &["km", "deg", "deg"], Path::new("s.csv")).to_string();
        assert!(
            e.contains("s.csv: line 7, column `md [km]`") && e.contains("not finite"),
            "{e}"
        );
        let p = SurveyProblem {
            index: 3,
            field: "",
            message: "whole".into(),
        };
        let e = problem_to_error(&p, &rows, &cols, &["km", "deg", "deg"], Path::new("s.csv")).to_string();
        assert!(e.contains("whole"));
        let p = SurveyProblem {
            index: 0,
            field: "",
            message: "row".into(),
        };
        let e = problem_to_error(&p, &rows, &cols, &["km", "deg", "deg"], Path::new("s.csv")).to_string();
        assert!(e.contains("s.csv: line 7: row"), "{e}");
    }

    #[test]
    fn numbers_with_and_without_decimal_comma() {
        assert_eq!(parse_number("12.5", false), Some(12.5));
        assert_eq!(parse_number("12,5", false), None);
        assert_eq!(parse_number("12,5", true), Some(12.5));
        assert_eq!(parse_number("1,2,5", true), None);
        assert_eq!(parse_number("1.2,5", true), None);
        assert_eq!(parse_number("", true), None);
    }
}
