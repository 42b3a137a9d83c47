//! Delimited survey files: the first line that is not blank or a comment is the header, an
//! optional units line follows, then one row per station.

use std::path::Path;

use super::header::{apply_units_line, column_units, find_columns, is_units_line, Column};
use super::{finish, parse_number, read_row, Found, Line, SurveyUnits};
use crate::case::{AzimuthReference, SurveyFile};
use crate::error::{InputError, InputResult};

/// Why a file is not a survey CSV.
#[derive(Debug)]
pub(super) enum Failure {
    /// Its first line does not name the three columns (the file may be a text report).
    Header(InputError),
    /// Anything else: the file is a CSV with a problem.
    Other(InputError),
}

/// Read `lines` (the file's non-blank, non-comment lines) as a delimited survey.
pub(super) fn parse(lines: &[Line], path: &Path, units: &SurveyUnits) -> Result<SurveyFile, Failure> {
    let Some(header_line) = lines.first() else {
        return Err(Failure::Other(InputError::file(
            path,
            "the survey file has no header row",
        )));
    };
    let delim = detect_delimiter(header_line.text);
    let decimal_comma = delim != ',';
    let number = |h: &str| h.is_empty() || parse_number(h, decimal_comma).is_some();
    if header_line.text.split_whitespace().all(number) {
        return Err(no_header(path, header_line.no, header_line.text));
    }
    let rows: Vec<Fields> = lines
        .iter()
        .map(|l| Fields {
            no: l.no,
            fields: split_fields(l.text, delim),
        })
        .collect();
    parse_fields(&rows, decimal_comma, path, units)
}

/// One row already split into fields (trimmed): its 1-based line (or sheet row) number.
#[derive(Debug, Clone)]
pub(super) struct Fields {
    pub(super) no: usize,
    pub(super) fields: Vec<String>,
}

/// The "no header row" failure for the first row `text` on line `no`.
fn no_header(path: &Path, no: usize, text: &str) -> Failure {
    Failure::Header(InputError::line(
        path,
        no,
        None,
        format!(
            "no header row: `{}` looks like data; the first line that is not a comment must name the columns, e.g. `md [m],inc [deg],azi [deg]`",
            text.trim()
        ),
    ))
}

/// Read `rows` (the non-blank, non-comment rows, split into fields) as a survey table: the
/// first is the header, an optional units row follows, then one row per station. The rules of
/// CSV files, shared by spreadsheets ([`super::sheet`]).
pub(super) fn parse_fields(
    rows: &[Fields],
    decimal_comma: bool,
    path: &Path,
    units: &SurveyUnits,
) -> Result<SurveyFile, Failure> {
    let Some((header, rest)) = rows.split_first() else {
        return Err(Failure::Other(InputError::file(
            path,
            "the survey file has no header row",
        )));
    };
    let number = |h: &str| h.is_empty() || parse_number(h, decimal_comma).is_some();
    if header.fields.iter().all(|h| number(h)) {
        return Err(no_header(path, header.no, &header.fields.join(",")));
    }
    let columns = find_columns(&header.fields, path, header.no).map_err(Failure::Header)?;
    read(columns, header.no, rest, decimal_comma, path, units).map_err(Failure::Other)
}

/// The survey from the rows after the header (`rest`), whose columns are `columns`.
fn read(
    mut columns: [Column; 3],
    header_no: usize,
    mut rest: &[Fields],
    decimal_comma: bool,
    path: &Path,
    units: &SurveyUnits,
) -> InputResult<SurveyFile> {
    if let Some((first, after)) = rest.split_first() {
        if is_units_line(&first.fields) {
            apply_units_line(&mut columns, &first.fields, path, first.no)?;
            rest = after;
        }
    }
    let mut notes = Vec::new();
    let col_units = column_units(&columns, units, path, &mut notes)?;
    let factors = col_units.map(|u| u.to_si);
    let mut rows = Vec::new();
    for row in rest {
        if row.fields.iter().all(|f| f.is_empty()) {
            continue; // e.g. `,,,` written by spreadsheets after the last row
        }
        let fields: Vec<&str> = row.fields.iter().map(String::as_str).collect();
        rows.push(read_row(row.no, &fields, &columns, factors, decimal_comma, path)?);
    }
    let azi = &columns[2];
    let reference = match azi.reference {
        AzimuthReference::Unspecified => (AzimuthReference::Unspecified, String::new()),
        r => (r, format!("column `{}`", azi.header)),
    };
    finish(
        Found {
            columns,
            units: col_units,
            rows,
            notes,
            reference,
            header_line: header_no,
        },
        path,
    )
}

pub(crate) fn detect_delimiter(header: &str) -> char {
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
pub(crate) fn split_fields(line: &str, delim: char) -> Vec<String> {
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

#[cfg(test)]
mod tests {
    use super::super::{parse_survey, read_survey, SurveyUnits};
    use crate::case::{AzimuthReference, SurveyFile};
    use crate::error::InputResult;
    use crate::units::lookup;
    use std::io::Write;
    use std::path::Path;

    const FILE: &str = "survey.csv";

    fn parse(text: &str) -> InputResult<SurveyFile> {
        parse_survey(text.as_bytes(), Path::new(FILE), &SurveyUnits::default())
    }

    fn parse_with(text: &str, md: Option<&str>, angle: Option<&str>) -> InputResult<SurveyFile> {
        let units = SurveyUnits {
            md: md.and_then(lookup),
            angle: angle.and_then(lookup),
            ..Default::default()
        };
        parse_survey(text.as_bytes(), Path::new(FILE), &units)
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
    fn exported_report_headers_issue_18() {
        // Exported report headers: `Incl.`, `Azimuth Grid`, units in spaced brackets.
        let f = parse("Measured Depth ( ft ),Incl. ( deg ),Azimuth Grid ( deg ),TVD ( ft ),DLS (deg/100ft)\n0,0,0,0,0\n100,2,45,99.98,2\n").unwrap();
        assert!(close(f.survey.stations()[1].md_m, 30.48));
        assert!(close(f.survey.stations()[1].inc_rad, 2_f64.to_radians()));
        assert!(close(f.survey.stations()[1].azi_rad, 45_f64.to_radians()));
        assert_eq!(f.azimuth_reference, AzimuthReference::Grid);
        assert_eq!(f.azimuth_reference_source, "column `Azimuth Grid ( deg )`");
        assert!(f.notes.is_empty(), "{:?}", f.notes);
        let f = parse("MD [m],Inc,Azimuth True\n0,0,0\n10,1,2\n").unwrap();
        assert_eq!(f.azimuth_reference, AzimuthReference::True);
        let f = parse("md,incl.,azi. (magnetic)\n0,0,0\n").unwrap();
        assert_eq!(f.azimuth_reference, AzimuthReference::Magnetic);
        let f = parse("md,inc,azi\n0,0,0\n").unwrap();
        assert_eq!(f.azimuth_reference, AzimuthReference::Unspecified);
        assert_eq!(f.azimuth_reference_source, "");
    }

    #[test]
    fn grid_and_true_azimuth_columns_are_refused_naming_both() {
        let e = err("MD (ft),Inc (deg),Azimuth Grid (deg),Azimuth True (deg)\n0,0,0,0\n");
        assert_at(&e, 1, "Azimuth True (deg)");
        assert!(
            e.contains("`Azimuth Grid (deg)` (field 3, grid north)")
                && e.contains("`Azimuth True (deg)` (field 4, true north)")
                && e.contains("delete the column you do not want"),
            "{e}"
        );
        // a column renamed away from an azimuth name is ignored
        let f = parse("MD (ft),Inc (deg),Azimuth Grid (deg),unused (deg)\n0,0,0,0\n").unwrap();
        assert_eq!(f.azimuth_reference, AzimuthReference::Grid);
    }

    #[test]
    fn units_line_after_the_header() {
        let f = parse("MD,Inc,Azi,TVD\n(ft),(deg),(deg),(ft)\n0,0,0,0\n100,1,2,100\n").unwrap();
        assert!(close(f.survey.stations()[1].md_m, 30.48));
        assert_eq!(f.md_unit, "ft");
        assert!(f.notes.is_empty(), "{:?}", f.notes);
        assert_eq!(f.station_lines, vec![3, 4]);
        // a units line against the header's unit, and an unknown unit there, name the line
        let e = err("MD [m],Inc,Azi\n[ft],[deg],[deg]\n0,0,0\n");
        assert_at(&e, 2, "MD [m]");
        let e = err("# c\nMD,Inc,Azi\n(ft),(furlong),(deg)\n0,0,0\n");
        assert_at(&e, 3, "Inc");
        assert!(e.contains("furlong"), "{e}");
        // with the case's unit that disagrees
        let e = parse_with("MD,Inc,Azi\n(ft),(deg),(deg)\n0,0,0\n", Some("m"), None)
            .unwrap_err()
            .to_string();
        assert_at(&e, 2, "MD");
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
        let f = read_survey(tmp.path(), &SurveyUnits::default()).unwrap();
        assert!(close(f.survey.stations()[1].md_m, 304.8));

        let missing = tmp.path().with_extension("does-not-exist");
        let e = read_survey(&missing, &SurveyUnits::default()).unwrap_err().to_string();
        assert!(e.contains("cannot read the survey file"), "{e}");
    }

    #[test]
    fn latin1_file_is_read_with_note() {
        let mut tmp = tempfile::NamedTempFile::new().unwrap();
        tmp.write_all(b"md [m],inc [\xB0],azi [\xB0]\n0,0,0\n10,1,2\n").unwrap();
        tmp.flush().unwrap();
        let f = read_survey(tmp.path(), &SurveyUnits::default()).unwrap();
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
        let f = read_survey(&path, &SurveyUnits::default()).unwrap();
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
