//! Whitespace-separated survey reports, as exported by directional-survey software:
//!
//! ```text
//! WELL        : 16B(78)-32
//! NORTH REF   : Grid
//! SURVEY
//! MD         INC       AZI       TVD
//! (ft)      (deg)     (deg)      (ft)
//! 0.00       0.00     0.00      0.00
//! 25.00      0.22     52.11     25.00
//! ```
//!
//! Lines before the header are free text or `KEY : value` metadata (a `NORTH REF` /
//! `NORTH REFERENCE` / `AZIMUTH REFERENCE` key states the azimuth reference); the header is
//! the first line whose whitespace-separated names include the measured depth, inclination
//! and azimuth; a units line may follow (one bracketed unit per column); every later line is a
//! station with one value per column.

use std::path::Path;

use super::header::{apply_units_line, column_units, find_columns, is_units_line, names_all_roles, reference_word};
use super::{finish, parse_number, read_row, Found, Line, SurveyUnits};
use crate::case::{AzimuthReference, SurveyFile};
use crate::error::{InputError, InputResult};

/// Read `lines` (the file's non-blank, non-comment lines) as a text report; `None` if they
/// are not one (no header line before the first line of numbers).
pub(super) fn parse(lines: &[Line], path: &Path, units: &SurveyUnits) -> Option<InputResult<SurveyFile>> {
    let mut metadata = Vec::new();
    for (i, line) in lines.iter().enumerate() {
        if let Some((key, value)) = line.text.split_once(':') {
            metadata.push((*line, key, value));
            continue;
        }
        let tokens = header_tokens(line.text);
        if tokens.iter().all(|t| parse_number(t, true).is_some()) {
            return None; // numbers before any header: not a report
        }
        if names_all_roles(&tokens) {
            return Some(read(*line, &lines[i + 1..], &tokens, &metadata, path, units));
        }
    }
    None
}

/// The report from its `header` line (split into `names`) on; `rest` are the lines after it.
fn read(
    header: Line,
    mut rest: &[Line],
    names: &[String],
    metadata: &[(Line, &str, &str)],
    path: &Path,
    units: &SurveyUnits,
) -> InputResult<SurveyFile> {
    let mut columns = find_columns(names, path, header.no)?;
    let mut notes = vec![format!(
        "read as a whitespace-separated survey report: header on line {}",
        header.no
    )];
    if let Some((first, after)) = rest.split_first() {
        let unit_tokens = split_tokens(first.text);
        if is_units_line(&unit_tokens) {
            if unit_tokens.len() != names.len() {
                return Err(InputError::line(
                    path,
                    first.no,
                    None,
                    format!(
                        "the units line has {} units but the header on line {} names {} columns; write one unit in brackets under each column, e.g. `(ft)`",
                        unit_tokens.len(),
                        header.no,
                        names.len()
                    ),
                ));
            }
            apply_units_line(&mut columns, &unit_tokens, path, first.no)?;
            notes[0].push_str(&format!(", units on line {}", first.no));
            rest = after;
        }
    }
    let reference = azimuth_reference(&columns[2], header.no, metadata, path, &mut notes)?;
    let col_units = column_units(&columns, units, path, &mut notes)?;
    let factors = col_units.map(|u| u.to_si);
    let mut rows = Vec::new();
    for line in rest {
        let fields: Vec<&str> = line.text.split_whitespace().collect();
        if fields.len() != names.len() {
            let shown: String = line.text.trim().chars().take(60).collect();
            return Err(InputError::line(
                path,
                line.no,
                None,
                format!(
                    "`{shown}` has {} field{} but the header on line {} names {} columns; every line after the header must be a station with one value under each column (write a column name that has spaces as one word, e.g. `Azimuth_Grid`)",
                    fields.len(),
                    if fields.len() == 1 { "" } else { "s" },
                    header.no,
                    names.len()
                ),
            ));
        }
        rows.push(read_row(line.no, &fields, &columns, factors, true, path)?);
    }
    finish(
        Found {
            columns,
            units: col_units,
            rows,
            notes,
            reference,
            header_line: header.no,
        },
        path,
    )
}

/// Metadata keys that state the azimuth reference, after lower-casing and keeping letters.
const NORTH_KEYS: &[&str] = &[
    "northref",
    "northreference",
    "azimuthref",
    "azimuthreference",
    "azimuthsto",
];

/// The azimuth reference from the azimuth column's qualifier and the `NORTH REF` metadata;
/// they must agree.
fn azimuth_reference(
    azi: &super::header::Column,
    header_no: usize,
    metadata: &[(Line, &str, &str)],
    path: &Path,
    notes: &mut Vec<String>,
) -> InputResult<(AzimuthReference, String)> {
    let mut found = match azi.reference {
        AzimuthReference::Unspecified => None,
        r => Some((r, format!("column `{}` (line {header_no})", azi.header))),
    };
    for (line, key, value) in metadata {
        let key: String = key.chars().filter(char::is_ascii_alphabetic).collect();
        if !NORTH_KEYS.contains(&key.to_ascii_lowercase().as_str()) {
            continue;
        }
        let value = value.trim();
        let Some(r) = north_value(value) else {
            notes.push(format!(
                "line {}: the north reference `{value}` is not grid, true or magnetic: it is not used",
                line.no
            ));
            continue;
        };
        let text = line.text.split_whitespace().collect::<Vec<_>>().join(" ");
        let source = format!("line {} `{text}`", line.no);
        match &found {
            None => found = Some((r, source)),
            Some((prev, _)) if *prev == r => {}
            Some((prev, prev_source)) => {
                return Err(InputError::line(
                    path,
                    line.no,
                    None,
                    format!(
                        "the north reference `{value}` ({}) contradicts {prev_source} ({}); make them agree",
                        r.describe(),
                        prev.describe()
                    ),
                ));
            }
        }
    }
    Ok(found.unwrap_or((AzimuthReference::Unspecified, String::new())))
}

/// The reference named by a metadata value: `Grid`, `True North`, `Magnetic`, `Grid North
/// (UTM)`.
fn north_value(value: &str) -> Option<AzimuthReference> {
    if let Some(r) = reference_word(value) {
        return Some(r);
    }
    let letters: String = value
        .chars()
        .filter(char::is_ascii_alphabetic)
        .collect::<String>()
        .to_ascii_lowercase();
    [
        ("grid", AzimuthReference::Grid),
        ("true", AzimuthReference::True),
        ("magnetic", AzimuthReference::Magnetic),
    ]
    .into_iter()
    .find(|(w, _)| letters.starts_with(w))
    .map(|(_, r)| r)
}

/// Whitespace-separated tokens, a bracketed group (`( ft )`) kept whole.
fn split_tokens(line: &str) -> Vec<String> {
    let mut out = Vec::new();
    let mut cur = String::new();
    let mut closing: Option<char> = None;
    for c in line.chars() {
        if let Some(close) = closing {
            cur.push(c);
            if c == close {
                closing = None;
            }
        } else if c.is_whitespace() {
            if !cur.is_empty() {
                out.push(std::mem::take(&mut cur));
            }
        } else {
            closing = match c {
                '(' => Some(')'),
                '[' => Some(']'),
                _ => None,
            };
            cur.push(c);
        }
    }
    if !cur.is_empty() {
        out.push(cur);
    }
    out
}

/// The names of a header line: [`split_tokens`], a bracketed unit joined to the name before
/// it (`MD (ft)`).
fn header_tokens(line: &str) -> Vec<String> {
    let mut out: Vec<String> = Vec::new();
    for t in split_tokens(line) {
        match out.last_mut() {
            Some(prev) if t.starts_with(['(', '[']) => {
                prev.push(' ');
                prev.push_str(&t);
            }
            _ => out.push(t),
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::super::{parse_survey, read_survey, SurveyUnits};
    use crate::case::{AzimuthReference, SurveyFile};
    use crate::error::InputResult;
    use crate::units::lookup;
    use std::path::Path;

    const FILE: &str = "report.txt";

    /// A made-up report: metadata (true north), a title, the header, a units line, blank lines,
    /// stations with one more column than read, CRLF line ends and a tab.
    const REPORT: &str = "COMPANY      : Example Drilling\r\n\
        NORTH REFERENCE : True North\r\n\
        DATE\t: 1/2/2024\r\n\
        \r\n\
        Definitive survey\r\n\
        MD       Incl.    Azim     TVD\r\n\
        (m)      (deg)    (deg)    (m)\r\n\
        \r\n\
        0.0      0.00     0.00     0.0\r\n\
        150.0    1,50     45.0     149.98\r\n\
        300.0    3.00     50.0     299.9\r\n";

    fn parse(text: &str) -> InputResult<SurveyFile> {
        parse_survey(text.as_bytes(), Path::new(FILE), &SurveyUnits::default())
    }

    /// The error's full text, which must name the file and `line {line}`.
    fn err_at(text: &str, line: usize) -> String {
        let e = parse(text).map(|f| f.survey.len()).unwrap_err().to_string();
        assert!(
            e.starts_with(&format!("{FILE}: line {line}")),
            "expected line {line}: {e}"
        );
        e
    }

    #[test]
    fn made_up_report() {
        // A report whose first line is metadata, not a CSV header.
        let f = parse(REPORT).unwrap();
        let st: Vec<(f64, f64, f64)> = f
            .survey
            .stations()
            .iter()
            .map(|s| (s.md_m, s.inc_rad.to_degrees(), s.azi_rad.to_degrees()))
            .collect();
        assert_eq!(st.len(), 3);
        assert!((st[1].0 - 150.0).abs() < 1e-12 && (st[1].1 - 1.5).abs() < 1e-12 && (st[1].2 - 45.0).abs() < 1e-12);
        assert_eq!(f.station_lines, vec![9, 10, 11]);
        assert_eq!((f.md_unit.as_str(), f.inc_unit.as_str()), ("m", "deg"));
        assert_eq!(f.azimuth_reference, AzimuthReference::True);
        assert_eq!(f.azimuth_reference_source, "line 2 `NORTH REFERENCE : True North`");
        assert_eq!(
            f.notes,
            vec!["read as a whitespace-separated survey report: header on line 6, units on line 7"]
        );
    }

    #[test]
    fn forge_16b_report_reads_as_its_derived_csv() {
        // Reference: wells/forge-16b/16B78-32_survey.csv, derived from the report value for
        // value by wells/tools/forge16b_survey.py (which checks it against the report): the
        // same 428 stations, bit for bit (feet converted by the same factor).
        let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("wells/forge-16b");
        let report = read_survey(&dir.join("16B78-32_Final_Survey_Report.txt"), &SurveyUnits::default()).unwrap();
        let csv = read_survey(&dir.join("16B78-32_survey.csv"), &SurveyUnits::default()).unwrap();
        assert_eq!(report.survey.len(), 428);
        assert_eq!(report.survey.stations(), csv.survey.stations());
        assert_eq!(report.md_unit, "ft");
        assert_eq!(report.azimuth_reference, AzimuthReference::Grid);
        assert_eq!(report.azimuth_reference_source, "line 14 `NORTH REF : Grid`");
        assert_eq!(report.station_lines.first(), Some(&25));
        assert_eq!(
            report.notes,
            vec!["read as a whitespace-separated survey report: header on line 21, units on line 22"]
        );
        let last = report.survey.stations().last().map(|s| s.md_m).unwrap_or(f64::NAN);
        assert_eq!(last, 10947.0 * lookup("ft").map(|u| u.to_si).unwrap_or(f64::NAN));
    }

    #[test]
    fn header_with_attached_units_and_no_metadata() {
        let f = parse("MD (ft)  INC [deg]  AZI( deg )\n0 0 0\n100 1 2\n").unwrap();
        assert!((f.survey.stations()[1].md_m - 30.48).abs() < 1e-12);
        assert_eq!(f.azimuth_reference, AzimuthReference::Unspecified);
        // qualified azimuth column, consistent with the metadata
        let f = parse("North Ref: grid\nMD INC AZI_GRID\n0 0 0\n").unwrap();
        assert_eq!(f.azimuth_reference, AzimuthReference::Grid);
        assert_eq!(f.azimuth_reference_source, "column `AZI_GRID` (line 2)");
    }

    #[test]
    fn north_reference_against_the_column_or_another_line() {
        let e = err_at("NORTH REF : Grid\nMD INC AZI_TRUE\n0 0 0\n", 1);
        assert!(
            e.contains("`Grid` (grid north) contradicts column `AZI_TRUE` (line 2) (true north)"),
            "{e}"
        );
        let e = err_at("NORTH REF : Grid\nAzimuth reference: magnetic\nMD INC AZI\n0 0 0\n", 2);
        assert!(e.contains("contradicts line 1 `NORTH REF : Grid`"), "{e}");
        let f = parse("NORTH REF : local\nMD INC AZI\n0 0 0\n").unwrap();
        assert_eq!(f.azimuth_reference, AzimuthReference::Unspecified);
        assert!(
            f.notes.iter().any(|n| n.contains("line 1") && n.contains("`local`")),
            "{:?}",
            f.notes
        );
    }

    #[test]
    fn errors_name_the_line() {
        // a row with a missing value would shift the columns: refused
        let e = err_at("MD INC AZI TVD\n(m) (deg) (deg) (m)\n0 0 0 0\n10 1 2\n", 4);
        assert!(
            e.contains("has 3 fields but the header on line 1 names 4 columns"),
            "{e}"
        );
        // a footer
        let e = err_at("MD INC AZI\n0 0 0\nChecked by J. Smith\n", 3);
        assert!(e.contains("`Checked by J. Smith`"), "{e}");
        // the units line must have one unit per column
        let e = err_at("WELL: x\nMD INC AZI TVD\n(m) (deg) (deg)\n0 0 0 0\n", 3);
        assert!(e.contains("3 units but the header on line 2 names 4 columns"), "{e}");
        // a bad unit in the units line
        let e = err_at("MD INC AZI\n(furlong) (deg) (deg)\n0 0 0\n", 2);
        assert!(e.contains("column `MD`") && e.contains("furlong"), "{e}");
        // a value that is not a number, one out of range, MD not increasing
        let e = err_at("MD INC AZI\n0 0 0\n10 x 0\n", 3);
        assert!(e.contains("column `INC`") && e.contains("`x` is not a number"), "{e}");
        let e = err_at("MD INC AZI\n0 0 0\n10 190 0\n", 3);
        assert!(e.contains("[0, 180]"), "{e}");
        let e = err_at("\n\nMD INC AZI\n0 0 0\n# c\n0 1 0\n", 6);
        assert!(e.contains("line 4") && e.contains("strictly increase"), "{e}");
        // no stations
        let e = err_at("TITLE\nMD INC AZI\n(ft) (deg) (deg)\n", 2);
        assert!(e.contains("no data rows"), "{e}");
        // two azimuth columns
        let e = err_at("MD INC AZI_GRID AZI_TRUE\n0 0 0 0\n", 1);
        assert!(e.contains("two azimuth columns"), "{e}");
    }

    #[test]
    fn not_a_report_keeps_the_csv_error() {
        // numbers before any header, or no header at all: the CSV reader's message
        let e = err_at("0 0 0\nMD INC AZI\n1 1 1\n", 1);
        assert!(e.contains("no header row"), "{e}");
        let e = err_at("WELL: x\nMD INC\n0 0\n", 1);
        assert!(e.contains("no measured depth column"), "{e}");
    }

    #[test]
    fn tokens() {
        assert_eq!(
            super::split_tokens(" (ft)  ( deg ) [deg/100 ft]x y"),
            vec!["(ft)", "( deg )", "[deg/100 ft]x", "y"]
        );
        assert_eq!(
            super::header_tokens("MD (ft) INC( deg ) (x"),
            vec!["MD (ft)", "INC( deg ) (x"]
        );
        assert_eq!(super::header_tokens("(ft) MD"), vec!["(ft)", "MD"]);
    }
}
