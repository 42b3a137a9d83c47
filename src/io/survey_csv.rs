//! Survey CSV reader: measured depth, inclination and azimuth columns found by name, converted
//! to SI and validated into a [`Survey`].
//!
//! The contract (docs/guide.md, "Survey CSV"):
//! - a UTF-8 BOM is stripped, CRLF is accepted, blank lines and lines whose first non-space
//!   character is `#` are skipped; the first remaining line is the header;
//! - the delimiter is a comma, or `;` / tab when the header has no comma but has one of those;
//! - columns are found by whole name, case-insensitive, ignoring spaces, underscores and a unit
//!   in brackets (`MD [ft]`, `md (m)`) or as a suffix (`md_ft`, `inc_deg`, `azi_rad`);
//! - a column without a unit takes the caller's override ([`SurveyUnits`]), else m / deg;
//! - every error names the file, the 1-based line of the original file and the column.

use std::f64::consts::PI;
use std::path::Path;

use crate::case::SurveyFile;
use crate::error::{InputError, InputResult};
use crate::geometry::survey::{Station, Survey, SurveyProblem};
use crate::units::{lookup_dim, Dimension, Unit};

/// Units to assume for columns whose header carries no unit (from the case file or command line).
#[derive(Debug, Clone, Default)]
pub struct SurveyUnits {
    /// Unit of a measured-depth column without a unit in its header (a length unit).
    pub md: Option<Unit>,
    /// Unit of inclination / azimuth columns without a unit in their header (an angle unit).
    pub angle: Option<Unit>,
}

/// Read and validate the survey CSV file at `path` (see the module documentation).
///
/// A file that is not valid UTF-8 is read as Latin-1 (so a `°` written by a legacy tool still
/// works), with a note saying so.
pub fn read_survey_csv(path: &Path, units: &SurveyUnits) -> InputResult<SurveyFile> {
    let bytes = std::fs::read(path).map_err(|e| InputError::file(path, format!("cannot read the survey file: {e}")))?;
    match String::from_utf8(bytes) {
        Ok(text) => parse_survey_csv(&text, path, units),
        Err(e) => {
            let text: String = e.into_bytes().iter().map(|&b| char::from(b)).collect();
            let mut file = parse_survey_csv(&text, path, units)?;
            file.notes
                .push("the file is not valid UTF-8 text: it was read as Latin-1 (ISO 8859-1)".into());
            Ok(file)
        }
    }
}

/// Parse and validate survey CSV `text`; `path` is used only in messages.
pub fn parse_survey_csv(text: &str, path: &Path, units: &SurveyUnits) -> InputResult<SurveyFile> {
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);

    // (1-based line number, line) of every non-blank, non-comment line.
    let mut lines = text
        .lines()
        .enumerate()
        .map(|(i, l)| (i + 1, l.strip_suffix('\r').unwrap_or(l)))
        .filter(|(_, l)| {
            let t = l.trim();
            !t.is_empty() && !t.starts_with('#')
        });

    let (header_line, header_text) = match lines.next() {
        Some(h) => h,
        None if text.trim().is_empty() => {
            return Err(InputError::file(path, "the survey file is empty: expected a header row such as `md [m],inc [deg],azi [deg]` followed by one row per station"));
        }
        None => {
            return Err(InputError::file(path, "the survey file contains only comments and blank lines: expected a header row such as `md [m],inc [deg],azi [deg]` followed by one row per station"));
        }
    };

    let delim = detect_delimiter(header_text);
    let header = split_fields(header_text, delim);
    if header.iter().all(|h| h.is_empty() || parse_number(h, delim).is_some()) {
        return Err(InputError::line(
            path,
            header_line,
            None,
            format!(
                "no header row: `{}` looks like data; the first line that is not a comment must name the columns, e.g. `md [m],inc [deg],azi [deg]`",
                header_text.trim()
            ),
        ));
    }

    let columns = find_columns(&header, path, header_line)?;
    let mut notes = Vec::new();
    let md_unit = column_unit(&columns[0], units, path, header_line, &mut notes)?;
    let inc_unit = column_unit(&columns[1], units, path, header_line, &mut notes)?;
    let azi_unit = column_unit(&columns[2], units, path, header_line, &mut notes)?;
    let factors = [md_unit.to_si, inc_unit.to_si, azi_unit.to_si];

    let mut rows: Vec<Row> = Vec::new();
    for (line_no, line) in lines {
        let fields = split_fields(line, delim);
        if fields.iter().all(|f| f.is_empty()) {
            continue; // e.g. `,,,` written by spreadsheets after the last row
        }
        let mut raw: [String; 3] = Default::default();
        let mut si = [0.0; 3];
        for (k, col) in columns.iter().enumerate() {
            let Some(txt) = fields.get(col.index) else {
                return Err(InputError::line(
                    path,
                    line_no,
                    Some(&col.header),
                    format!(
                        "too few fields: the row has {} field{} but the {} column `{}` is field {} of the header",
                        fields.len(),
                        if fields.len() == 1 { "" } else { "s" },
                        col.role.what(),
                        col.header,
                        col.index + 1
                    ),
                ));
            };
            let what = col.role.what();
            if txt.is_empty() {
                return Err(InputError::line(
                    path,
                    line_no,
                    Some(&col.header),
                    format!("the {what} value is missing (empty field)"),
                ));
            }
            let v = parse_number(txt, delim).ok_or_else(|| {
                InputError::line(
                    path,
                    line_no,
                    Some(&col.header),
                    format!("the {what} value `{txt}` is not a number"),
                )
            })?;
            if !v.is_finite() {
                return Err(InputError::line(
                    path,
                    line_no,
                    Some(&col.header),
                    format!("the {what} value `{txt}` is not a finite number (NaN or infinite)"),
                ));
            }
            raw[k] = txt.clone();
            si[k] = v * factors[k];
        }
        rows.push(Row { line: line_no, raw, si });
    }

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
    let units_used = [md_unit.name, inc_unit.name, azi_unit.name];
    let survey = Survey::new(stations).map_err(|p| problem_to_error(&p, &rows, &columns, &units_used, path))?;

    Ok(SurveyFile {
        survey,
        md_unit: md_unit.name.to_string(),
        inc_unit: inc_unit.name.to_string(),
        azi_unit: azi_unit.name.to_string(),
        notes,
        station_lines: rows.iter().map(|r| r.line).collect(),
    })
}

/// The three columns the reader needs.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Role {
    Md,
    Inc,
    Azi,
}

impl Role {
    const ALL: [Role; 3] = [Role::Md, Role::Inc, Role::Azi];

    /// Short name, as in [`SurveyProblem::field`].
    fn key(self) -> &'static str {
        match self {
            Role::Md => "md",
            Role::Inc => "inc",
            Role::Azi => "azi",
        }
    }

    fn what(self) -> &'static str {
        match self {
            Role::Md => "measured depth",
            Role::Inc => "inclination",
            Role::Azi => "azimuth",
        }
    }

    /// Accepted header names after [`normalize_name`].
    fn names(self) -> &'static [&'static str] {
        match self {
            Role::Md => &["md", "measureddepth", "depth"],
            Role::Inc => &["inc", "incl", "inclination"],
            Role::Azi => &["azi", "az", "azim", "azimuth"],
        }
    }

    /// The same names as written in messages.
    fn spellings(self) -> &'static str {
        match self {
            Role::Md => "`md`, `measured depth`, `measured_depth` or `depth`",
            Role::Inc => "`inc`, `incl` or `inclination`",
            Role::Azi => "`azi`, `az`, `azim` or `azimuth`",
        }
    }

    fn dimension(self) -> Dimension {
        match self {
            Role::Md => Dimension::Length,
            Role::Inc | Role::Azi => Dimension::Angle,
        }
    }

    fn default_unit(self) -> Unit {
        match self {
            Role::Md => Unit {
                name: "m",
                dimension: Dimension::Length,
                to_si: 1.0,
            },
            Role::Inc | Role::Azi => Unit {
                name: "deg",
                dimension: Dimension::Angle,
                to_si: PI / 180.0,
            },
        }
    }

    fn override_unit(self, units: &SurveyUnits) -> Option<Unit> {
        match self {
            Role::Md => units.md,
            Role::Inc | Role::Azi => units.angle,
        }
    }
}

/// A column found in the header.
#[derive(Debug, Clone)]
struct Column {
    role: Role,
    /// 0-based field index.
    index: usize,
    /// Header text as written (quotes removed, trimmed).
    header: String,
    /// Unit written in the header, if any.
    unit: Option<String>,
}

/// One data row: its line, the three texts as written and their SI values.
#[derive(Debug, Clone)]
struct Row {
    line: usize,
    raw: [String; 3],
    si: [f64; 3],
}

fn detect_delimiter(header: &str) -> char {
    if header.contains(',') {
        ','
    } else if header.contains(';') {
        ';'
    } else if header.contains('\t') {
        '\t'
    } else {
        ','
    }
}

/// Split a line on `delim`, honouring double quotes (`""` inside quotes is a quote); fields are
/// trimmed.
fn split_fields(line: &str, delim: char) -> Vec<String> {
    let mut fields = Vec::new();
    let mut cur = String::new();
    let mut in_quotes = false;
    let mut chars = line.chars().peekable();
    while let Some(c) = chars.next() {
        if in_quotes {
            if c == '"' {
                if chars.peek() == Some(&'"') {
                    cur.push('"');
                    chars.next();
                } else {
                    in_quotes = false;
                }
            } else {
                cur.push(c);
            }
        } else if c == '"' && cur.trim().is_empty() {
            cur.clear();
            in_quotes = true;
        } else if c == delim {
            fields.push(cur.trim().to_string());
            cur.clear();
        } else {
            cur.push(c);
        }
    }
    fields.push(cur.trim().to_string());
    fields
}

/// Parse a number; with a `;` or tab delimiter a decimal comma (`12,5`) is accepted too.
fn parse_number(text: &str, delim: char) -> Option<f64> {
    if let Ok(v) = text.parse::<f64>() {
        return Some(v);
    }
    if delim != ',' && text.matches(',').count() == 1 && !text.contains('.') {
        return text.replace(',', ".").parse::<f64>().ok();
    }
    None
}

/// Split a header into (name, unit text): `MD [ft]`, `md (m)`, `md_ft`, `inc_deg`, `azi_rad`.
fn split_header_unit(header: &str) -> (&str, Option<&str>) {
    let t = header.trim();
    for (open, close) in [('[', ']'), ('(', ')')] {
        if let Some(inner) = t.strip_suffix(close) {
            if let Some(p) = inner.rfind(open) {
                return (&inner[..p], Some(inner[p + open.len_utf8()..].trim()));
            }
        }
    }
    for suffix in ["_ft", "_m", "_deg", "_rad"] {
        if t.len() > suffix.len() && t.is_char_boundary(t.len() - suffix.len()) {
            let (name, tail) = t.split_at(t.len() - suffix.len());
            if tail.eq_ignore_ascii_case(suffix) {
                return (name, Some(&tail[1..]));
            }
        }
    }
    (t, None)
}

/// Lower case, without spaces, underscores and hyphens.
fn normalize_name(name: &str) -> String {
    name.chars()
        .filter(|c| !c.is_whitespace() && *c != '_' && *c != '-')
        .flat_map(char::to_lowercase)
        .collect()
}

/// Find the md, inc and azi columns (in that order).
fn find_columns(header: &[String], path: &Path, line: usize) -> InputResult<[Column; 3]> {
    let mut found: [Option<Column>; 3] = [None, None, None];
    for (index, h) in header.iter().enumerate() {
        let (name, unit) = split_header_unit(h);
        let norm = normalize_name(name);
        let Some(k) = Role::ALL.iter().position(|r| r.names().contains(&norm.as_str())) else {
            continue;
        };
        let role = Role::ALL[k];
        if let Some(prev) = &found[k] {
            return Err(InputError::line(
                path,
                line,
                Some(h),
                format!(
                    "two columns look like the {} column: `{}` (field {}) and `{}` (field {}); rename or remove one of them",
                    role.what(),
                    prev.header,
                    prev.index + 1,
                    h,
                    index + 1
                ),
            ));
        }
        found[k] = Some(Column {
            role,
            index,
            header: h.clone(),
            unit: unit.map(str::to_string),
        });
    }
    if let Some(k) = found.iter().position(Option::is_none) {
        let role = Role::ALL[k];
        let listed = header.iter().map(|h| format!("`{h}`")).collect::<Vec<_>>().join(", ");
        return Err(InputError::line(
            path,
            line,
            None,
            format!(
                "the header has no {} column (named {}, optionally with a unit such as `{} [{}]`); the header's columns are: {listed}",
                role.what(),
                role.spellings(),
                role.key(),
                role.default_unit().name,
            ),
        ));
    }
    match found {
        [Some(md), Some(inc), Some(azi)] => Ok([md, inc, azi]),
        _ => Err(InputError::line(
            path,
            line,
            None,
            "the header lacks a measured depth, inclination or azimuth column",
        )),
    }
}

/// The unit of a column: from its header, else from the override, else the default; notes
/// say which was assumed and why.
fn column_unit(
    col: &Column,
    units: &SurveyUnits,
    path: &Path,
    line: usize,
    notes: &mut Vec<String>,
) -> InputResult<Unit> {
    let dim = col.role.dimension();
    let over = col.role.override_unit(units);
    if let Some(o) = over {
        if o.dimension != dim {
            return Err(InputError::file(
                path,
                format!(
                    "the {} unit given by the case file or command line, `{}`, is a {} unit, expected a {dim} unit",
                    col.role.what(),
                    o.name,
                    o.dimension
                ),
            ));
        }
    }
    match (&col.unit, over) {
        (Some(text), over) => {
            let u = lookup_dim(text, dim).map_err(|m| {
                InputError::line(
                    path,
                    line,
                    Some(&col.header),
                    format!("{m} in the header of the {} column", col.role.what()),
                )
            })?;
            if let Some(o) = over {
                if o.name != u.name {
                    return Err(InputError::line(
                        path,
                        line,
                        Some(&col.header),
                        format!(
                            "the header says the {} is in {} but the case file or command line says {}; remove one of them or make them agree",
                            col.role.what(),
                            u.name,
                            o.name
                        ),
                    ));
                }
            }
            Ok(u)
        }
        (None, Some(o)) => {
            notes.push(format!(
                "{} column `{}` has no unit in its header: assumed {} (from the case file or command line)",
                col.role.key(),
                col.header,
                o.name
            ));
            Ok(o)
        }
        (None, None) => {
            let d = col.role.default_unit();
            notes.push(format!(
                "{} column `{}` has no unit in its header: assumed {} (the default; write e.g. `{} [{}]` in the header or give the unit in the case file to change it)",
                col.role.key(),
                col.header,
                d.name,
                col.role.key(),
                if col.role == Role::Md { "ft" } else { "rad" }
            ));
            Ok(d)
        }
    }
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
    use crate::units::lookup;
    use std::io::Write;

    const FILE: &str = "survey.csv";

    fn parse(text: &str) -> InputResult<SurveyFile> {
        parse_survey_csv(text, Path::new(FILE), &SurveyUnits::default())
    }

    fn parse_with(text: &str, md: Option<&str>, angle: Option<&str>) -> InputResult<SurveyFile> {
        let units = SurveyUnits {
            md: md.and_then(lookup),
            angle: angle.and_then(lookup),
        };
        parse_survey_csv(text, Path::new(FILE), &units)
    }

    /// The error's full text, which must name the file.
    fn err(text: &str) -> String {
        match parse(text) {
            Ok(f) => panic!("expected an error, got {} stations", f.survey.len()),
            Err(e) => {
                let s = e.to_string();
                assert!(s.contains(FILE), "error does not name the file: {s}");
                s
            }
        }
    }

    fn assert_at(msg: &str, line: usize, column: &str) {
        assert!(
            msg.contains(&format!("line {line}, column `{column}`")),
            "expected line {line}, column `{column}` in: {msg}"
        );
    }

    fn close(a: f64, b: f64) -> bool {
        (a - b).abs() <= 1e-9 * (1.0 + b.abs())
    }

    fn mds(f: &SurveyFile) -> Vec<f64> {
        f.survey.stations().iter().map(|s| s.md_m).collect()
    }

    #[test]
    fn suffix_units_md_m_inc_deg_azi_deg() {
        let f = parse("md_m,inc_deg,azi_deg\n0,0,0\n100,10,45\n200,20.5,90\n").unwrap();
        assert_eq!(f.survey.len(), 3);
        assert_eq!(mds(&f), vec![0.0, 100.0, 200.0]);
        let s = f.survey.stations()[2];
        assert!(close(s.inc_rad, 20.5_f64.to_radians()));
        assert!(close(s.azi_rad, 90_f64.to_radians()));
        assert_eq!(
            (f.md_unit.as_str(), f.inc_unit.as_str(), f.azi_unit.as_str()),
            ("m", "deg", "deg")
        );
        assert!(f.notes.is_empty(), "{:?}", f.notes);
    }

    #[test]
    fn suffix_ft_and_rad() {
        let f = parse("MD_FT,Inc_Rad,azi_rad\n0,0,0\n1000,0.5,1\n").unwrap();
        assert!(close(f.survey.stations()[1].md_m, 304.8));
        assert!(close(f.survey.stations()[1].inc_rad, 0.5));
        assert_eq!((f.md_unit.as_str(), f.inc_unit.as_str()), ("ft", "rad"));
    }

    #[test]
    fn bracket_unit_and_default_angles_with_notes() {
        let f = parse("MD [ft],Inc,Azi\n0,0,0\n100,3,30\n").unwrap();
        assert!(close(f.survey.stations()[1].md_m, 30.48));
        assert!(close(f.survey.stations()[1].inc_rad, 3_f64.to_radians()));
        assert_eq!(f.md_unit, "ft");
        assert_eq!(f.notes.len(), 2, "{:?}", f.notes);
        assert!(f.notes[0].contains("`Inc`") && f.notes[0].contains("deg") && f.notes[0].contains("default"));
        assert!(f.notes[1].contains("`Azi`") && f.notes[1].contains("default"));
    }

    #[test]
    fn parenthesis_unit_and_spaced_underscored_names() {
        let f = parse("Measured_Depth (ft), INCLINATION (deg) ,AZIM(deg)\n0,0,0\n10,1,2\n").unwrap();
        assert!(close(f.survey.stations()[1].md_m, 3.048));
        assert!(f.notes.is_empty());
        let f = parse("measured depth,incl,az\n5,1,2\n").unwrap();
        assert_eq!(mds(&f), vec![5.0]);
        let f = parse("Depth,Inclination,Azimuth\n5,1,2\n").unwrap();
        assert_eq!(mds(&f), vec![5.0]);
    }

    #[test]
    fn unitless_md_defaults_to_metres_with_note() {
        let f = parse("md,inc,azi\n0,0,0\n100,1,1\n").unwrap();
        assert_eq!(mds(&f), vec![0.0, 100.0]);
        assert_eq!(f.md_unit, "m");
        assert!(
            f.notes[0].starts_with("md column `md` has no unit in its header: assumed m (the default"),
            "{:?}",
            f.notes
        );
    }

    #[test]
    fn volve_like_header_extra_columns_ignored() {
        let text =
            "# comment\nmd [m],inc [deg],azi [deg],tvd [m],north [m],east [m],dls [deg/m],station_type,time_utc\n\
                    0,0,0,0,-4.65,0.91,0,tie in point,2007-11-11T15:51:12.000Z\n\
                    150.6589824,0.57,182.02,150.65,-5.39,0.89,0.0037,magnetic MWD,2007-11-16T04:43:28.000Z\n";
        let f = parse(text).unwrap();
        assert_eq!(mds(&f), vec![0.0, 150.6589824]);
        assert!(close(f.survey.stations()[1].azi_rad, 182.02_f64.to_radians()));
        assert!(f.notes.is_empty());
    }

    #[test]
    fn forge_like_bom_crlf_feet_from_override() {
        let text =
            "\u{feff}Measured depth,Incl,Azimuth,Course length,TVD,Vertica sectionl,NS,EW,Total displ,At Azim,DLS\r\n\
                    0,0,0,0,0,0,0,0,0,0,0\r\n\
                    80,0.34,324.91,80,80,-0.18,0.19,-0.14,0.24,111.5,0.42\r\n\
                    175,0.33,322.79,95,175,-0.61,0.64,-0.46,0.79,222.5,0.02\r\n";
        let f = parse_with(text, Some("ft"), None).unwrap();
        assert_eq!(f.survey.len(), 3);
        let md = mds(&f);
        assert!(close(md[1], 24.384) && close(md[2], 53.34), "{md:?}");
        // `Azimuth`, not `At Azim`
        assert!(close(f.survey.stations()[1].azi_rad, 324.91_f64.to_radians()));
        assert!(close(f.survey.stations()[2].inc_rad, 0.33_f64.to_radians()));
        assert_eq!(f.md_unit, "ft");
        assert_eq!(
            f.notes[0],
            "md column `Measured depth` has no unit in its header: assumed ft (from the case file or command line)"
        );
        assert_eq!(f.notes.len(), 3);
    }

    #[test]
    fn tvd_and_depth_unit_are_not_md() {
        let f = parse("well,md,inc [deg],azi [deg],tvd,depth_unit\n1,0,0,0,0,m\n1,30,0,0,30,m\n").unwrap();
        assert_eq!(mds(&f), vec![0.0, 30.0]);
        let e = err("tvd,inc,azi,depth_unit,at azim\n0,0,0,m,0\n");
        assert!(e.contains("no measured depth column") && e.contains("line 1"), "{e}");
    }

    #[test]
    fn angle_override_applies_to_unitless_angles() {
        let f = parse_with("md,inc,azi\n0,0,0\n10,0.1,0.2\n", None, Some("rad")).unwrap();
        assert!(close(f.survey.stations()[1].inc_rad, 0.1));
        assert!(close(f.survey.stations()[1].azi_rad, 0.2));
        assert_eq!((f.inc_unit.as_str(), f.azi_unit.as_str()), ("rad", "rad"));
        assert!(
            f.notes[1..].iter().all(|n| n.contains("case file or command line")),
            "{:?}",
            f.notes
        );
    }

    #[test]
    fn override_agreeing_with_header_is_fine() {
        let f = parse_with(
            "md [feet],inc [deg],azi [deg]\n0,0,0\n10,1,1\n",
            Some("ft"),
            Some("deg"),
        )
        .unwrap();
        assert_eq!(f.md_unit, "ft");
        assert!(f.notes.is_empty());
    }

    #[test]
    fn override_conflicting_with_header_is_an_error() {
        let e = parse_with("md,inc,azi\n0,0,0\n", None, None).map(|_| ());
        assert!(e.is_ok());
        let e = parse_with("# c\nMD [m],inc,azi\n0,0,0\n", Some("ft"), None)
            .unwrap_err()
            .to_string();
        assert_at(&e, 2, "MD [m]");
        assert!(e.contains(" m ") && e.contains("ft"), "{e}");
        let e = parse_with("md,inc [deg],azi\n0,0,0\n", None, Some("rad"))
            .unwrap_err()
            .to_string();
        assert_at(&e, 1, "inc [deg]");
        assert!(e.contains("deg") && e.contains("rad"), "{e}");
    }

    #[test]
    fn override_of_wrong_dimension_is_an_error() {
        let e = parse_with("md,inc,azi\n0,0,0\n", Some("deg"), None)
            .unwrap_err()
            .to_string();
        assert!(e.contains("measured depth unit") && e.contains("deg"), "{e}");
    }

    #[test]
    fn unknown_or_wrong_unit_in_header() {
        let e = err("md [furlong],inc,azi\n0,0,0\n");
        assert_at(&e, 1, "md [furlong]");
        assert!(e.contains("unknown unit `furlong`"), "{e}");
        let e = err("md,inc [m],azi\n0,0,0\n");
        assert_at(&e, 1, "inc [m]");
        assert!(e.contains("length unit"), "{e}");
        let e = err("md,inc,azi_m\n0,0,0\n");
        assert_at(&e, 1, "azi_m");
        // units of ignored columns do not matter
        parse("md,inc,azi,dls [deg/furlong]\n0,0,0,0\n").unwrap();
    }

    #[test]
    fn comments_blank_lines_and_line_numbers() {
        let text =
            "# header comment\n\n   # indented comment\nmd,inc,azi\n0,0,0\n\n# mid comment\n100,1,1\n  \n200,x,1\n";
        let e = err(text);
        assert_at(&e, 10, "inc");
        let ok = "# c\n\nmd,inc,azi\n0,0,0\n# c\n\n100,1,1\n";
        assert_eq!(parse(ok).unwrap().survey.len(), 2);
    }

    #[test]
    fn semicolon_and_tab_delimiters() {
        let f = parse("md [m];inc [deg];azi [deg]\n0;0;0\n100,5;2,5;10\n").unwrap();
        assert_eq!(mds(&f), vec![0.0, 100.5]);
        assert!(close(f.survey.stations()[1].inc_rad, 2.5_f64.to_radians()));
        let f = parse("md\tinc\tazi\n0\t0\t0\n50\t1\t2\n").unwrap();
        assert_eq!(mds(&f), vec![0.0, 50.0]);
    }

    #[test]
    fn quoted_fields() {
        let f = parse("\"MD [ft]\",\"Inc\",\"Azi\",\"Note\"\n0,0,0,\"tie, in\"\n100,1,2,\"x\"\n").unwrap();
        assert!(close(f.survey.stations()[1].md_m, 30.48));
    }

    #[test]
    fn short_rows_fine_if_needed_fields_present_and_empty_rows_skipped() {
        let f = parse("md,inc,azi,tvd,north\n0,0,0\n10,1,1,10\n,,,,\n").unwrap();
        assert_eq!(f.survey.len(), 2);
    }

    #[test]
    fn duplicate_role_is_an_error_naming_both() {
        let e = err("md,Depth,inc,azi\n0,0,0,0\n");
        assert_at(&e, 1, "Depth");
        assert!(e.contains("`md`") && e.contains("`Depth`"), "{e}");
        let e = err("md,az,inc,azimuth\n0,0,0,0\n");
        assert!(e.contains("`az`") && e.contains("`azimuth`"), "{e}");
    }

    #[test]
    fn error_empty_file() {
        for text in ["", "\u{feff}", "\n\r\n  \n"] {
            let e = err(text);
            assert!(e.contains("empty"), "{e}");
        }
    }

    #[test]
    fn error_only_comments() {
        let e = err("# nothing\n\n#more\n");
        assert!(e.contains("only comments"), "{e}");
    }

    #[test]
    fn error_no_header() {
        let e = err("# c\n0,0,0\n100,1,1\n");
        assert!(e.contains("line 2") && e.contains("no header row"), "{e}");
    }

    #[test]
    fn error_missing_column_lists_columns() {
        let e = err("\n#c\nmd [m],inc [deg],tvd [m]\n0,0,0\n");
        assert!(e.contains("line 3"), "{e}");
        assert!(e.contains("no azimuth column"), "{e}");
        assert!(e.contains("`md [m]`, `inc [deg]`, `tvd [m]`"), "{e}");
        let e = err("md,azi\n0,0\n");
        assert!(e.contains("no inclination column") && e.contains("line 1"), "{e}");
    }

    #[test]
    fn error_too_few_fields() {
        let e = err("md,inc,azi\n0,0,0\n100,1\n");
        assert_at(&e, 3, "azi");
        assert!(e.contains("too few fields"), "{e}");
    }

    #[test]
    fn error_non_numeric_quotes_the_text() {
        let e = err("md,inc,azi\n0,0,0\n100,1,north\n");
        assert_at(&e, 3, "azi");
        assert!(e.contains("`north` is not a number"), "{e}");
        let e = err("md,inc,azi\n0,,0\n");
        assert_at(&e, 2, "inc");
        assert!(e.contains("empty"), "{e}");
    }

    #[test]
    fn error_nan_and_infinite() {
        for v in ["NaN", "inf", "-infinity"] {
            let e = err(&format!("md_m,inc,azi\n0,0,0\n{v},1,1\n"));
            assert_at(&e, 3, "md_m");
            assert!(
                e.contains(&format!("`{v}`")) && e.contains("not a finite number"),
                "{e}"
            );
        }
    }

    #[test]
    fn error_header_without_data() {
        let e = err("# c\nmd,inc,azi\n\n# end\n");
        assert!(e.contains("line 2") && e.contains("no data rows"), "{e}");
    }

    #[test]
    fn error_md_not_increasing() {
        let e = err("MD [ft],inc,azi\n0,0,0\n100,1,1\n# c\n95,1,1\n");
        assert_at(&e, 5, "MD [ft]");
        assert!(
            e.contains("95 ft") && e.contains("100 ft") && e.contains("line 3"),
            "{e}"
        );
        let e = err("md,inc,azi\n0,0,0\n0,1,1\n");
        assert_at(&e, 3, "md");
        assert!(e.contains("strictly increase"), "{e}");
    }

    #[test]
    fn error_inclination_out_of_range() {
        let e = err("md,incl,azi\n0,0,0\n100,200,1\n");
        assert_at(&e, 3, "incl");
        assert!(e.contains("inclination 200 deg is outside [0, 180] deg"), "{e}");
        let e = err("md,inc,azi\n0,-1,0\n");
        assert_at(&e, 2, "inc");
        let e = err("md,inc_rad,azi\n0,3.2,0\n");
        assert_at(&e, 2, "inc_rad");
        assert!(e.contains("183.3"), "{e}");
        // 180 deg exactly is allowed
        parse("md,inc,azi\n0,180,0\n").unwrap();
    }

    #[test]
    fn problem_mapping_fallbacks() {
        let rows = vec![Row {
            line: 7,
            raw: ["1e308".into(), "0".into(), "0".into()],
            si: [f64::INFINITY, 0.0, 0.0],
        }];
        let cols = [
            Column {
                role: Role::Md,
                index: 0,
                header: "md [km]".into(),
                unit: Some("km".into()),
            },
            Column {
                role: Role::Inc,
                index: 1,
                header: "inc".into(),
                unit: None,
            },
            Column {
                role: Role::Azi,
                index: 2,
                header: "azi".into(),
                unit: None,
            },
        ];
        let p = SurveyProblem {
            index: 0,
            field: "md",
            message: "measured depth is not finite".into(),
        };
        let e = problem_to_error(&p, &rows, &cols, &["km", "deg", "deg"], Path::new(FILE)).to_string();
        assert_at(&e, 7, "md [km]");
        assert!(e.contains("not finite"), "{e}");
        let p = SurveyProblem {
            index: 3,
            field: "",
            message: "whole".into(),
        };
        let e = problem_to_error(&p, &rows, &cols, &["km", "deg", "deg"], Path::new(FILE)).to_string();
        assert!(e.contains("whole"));
        // and the real path through the parser
        let e = err("md [km],inc,azi\n1e308,0,0\n");
        assert_at(&e, 2, "md [km]");
    }

    #[test]
    fn azimuth_is_normalized() {
        let f = parse("md,inc,azi\n0,5,370\n10,5,-10\n20,5,360\n").unwrap();
        let az: Vec<f64> = f.survey.stations().iter().map(|s| s.azi_rad.to_degrees()).collect();
        assert!(
            (az[0] - 10.0).abs() < 1e-9 && (az[1] - 350.0).abs() < 1e-9 && az[2].abs() < 1e-9,
            "{az:?}"
        );
    }

    #[test]
    fn no_panics_on_odd_input() {
        let inputs = [
            "\"",
            "md,inc,azi\n\"",
            ",,,",
            "md,inc,azi\n,,,",
            "İnc_m,ß_deg,azi_\u{1F600}\n1,2,3",
            "md_,inc(,azi[\n1,2,3",
            "md [],inc ( ),azi [ deg ]\n1,2,3",
            "_m,_deg,_rad\n1,2,3",
            "md;inc;azi\n1,,2;3;4",
            "md,inc,azi\n1,2,3\n\"1\",\"2\",\"3\"\"\n",
            "\r\r\n\r",
            "#",
        ];
        for t in inputs {
            let _ = parse(t);
            let _ = parse_with(t, Some("ft"), Some("rad"));
        }
    }

    #[test]
    fn read_from_temp_file_and_missing_file() {
        let mut tmp = tempfile::NamedTempFile::new().unwrap();
        write!(tmp, "md_ft,inc_deg,azi_deg\r\n0,0,0\r\n1000,10,20\r\n").unwrap();
        tmp.flush().unwrap();
        let f = read_survey_csv(tmp.path(), &SurveyUnits::default()).unwrap();
        assert!(close(f.survey.stations()[1].md_m, 304.8));

        let missing = tmp.path().with_extension("does-not-exist");
        let e = read_survey_csv(&missing, &SurveyUnits::default())
            .unwrap_err()
            .to_string();
        assert!(e.contains("cannot read the survey file"), "{e}");
    }

    #[test]
    fn latin1_file_is_read_with_note() {
        let mut tmp = tempfile::NamedTempFile::new().unwrap();
        tmp.write_all(b"md [m],inc [\xB0],azi [\xB0]\n0,0,0\n10,1,2\n").unwrap();
        tmp.flush().unwrap();
        let f = read_survey_csv(tmp.path(), &SurveyUnits::default()).unwrap();
        assert_eq!(f.inc_unit, "deg");
        assert!(f.notes.iter().any(|n| n.contains("Latin-1")), "{:?}", f.notes);
    }

    #[test]
    fn real_volve_file_if_present() {
        let path = Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("../shared/data/volve-15_9-F-10/15_9-F-10_actual_trajectory.csv");
        if !path.exists() {
            return;
        }
        let f = read_survey_csv(&path, &SurveyUnits::default()).unwrap();
        assert_eq!(f.survey.len(), 479);
        let last = f.survey.stations().last().map(|s| s.md_m).unwrap_or(f64::NAN);
        assert!((last - 5300.0653968).abs() < 1e-9, "{last}");
        assert_eq!(
            (f.md_unit.as_str(), f.inc_unit.as_str(), f.azi_unit.as_str()),
            ("m", "deg", "deg")
        );
        assert!(f.notes.is_empty());
    }
}
