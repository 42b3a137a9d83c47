//! Spreadsheet survey files (`.xlsx`, `.xlsm`, `.xlsb`, `.xls`, `.ods`), read with `calamine`:
//! one sheet's rows become fields and follow exactly the CSV rules ([`super::csv`]): rows
//! that are empty or whose first non-empty cell starts with `#` are skipped, the first other
//! row is the header, an optional units row follows, then one row per station. Line numbers in
//! messages are the sheet's row numbers (1-based, as the spreadsheet shows them).
//!
//! A file over 16 MiB, or a zip-based one whose parts declare more than 256 MiB once
//! decompressed, is refused before it is read.
//!
//! The sheet is the one named (`[well] survey_sheet`, `--sheet`), else the first whose first
//! row (after empty and comment rows) names the MD, inclination and azimuth columns.

use std::path::Path;

use calamine::{open_workbook_auto, Data, Reader};

use super::csv::{parse_fields, Failure, Fields};
use super::header::names_all_roles;
use super::SurveyUnits;
use crate::case::SurveyFile;
use crate::error::{InputError, InputResult};

/// Largest spreadsheet file read, bytes (16 MiB, as WITSML files).
const MAX_SHEET_BYTES: u64 = 16 * 1024 * 1024;

/// Largest total of the sizes a zip-based spreadsheet (`.xlsx`, `.xlsm`, `.xlsb`, `.ods`)
/// declares for its parts once decompressed, bytes (256 MiB): a guard against decompression
/// bombs, checked before the parts are read.
const MAX_UNZIPPED_BYTES: u128 = 256 * 1024 * 1024;

/// Refuse a zip-based spreadsheet whose parts declare more than [`MAX_UNZIPPED_BYTES`]
/// decompressed (parts that do not declare their size are not counted: the guard cannot see
/// them).
fn check_unzipped_size(path: &Path) -> InputResult<()> {
    let ext = path
        .extension()
        .and_then(|e| e.to_str())
        .unwrap_or("")
        .to_ascii_lowercase();
    if !matches!(ext.as_str(), "xlsx" | "xlsm" | "xlsb" | "ods") {
        return Ok(());
    }
    let Ok(file) = std::fs::File::open(path) else {
        return Ok(()); // the reader says why
    };
    let Ok(archive) = zip::ZipArchive::new(file) else {
        return Ok(()); // not a zip: the reader says so
    };
    match archive.decompressed_size() {
        Some(n) if n > MAX_UNZIPPED_BYTES => Err(InputError::file(
            path,
            format!(
                "the spreadsheet's parts decompress to {} MiB, more than the {} MiB drillpath reads (a decompression bomb?); save the survey sheet alone",
                n / (1024 * 1024),
                MAX_UNZIPPED_BYTES / (1024 * 1024)
            ),
        )),
        _ => Ok(()),
    }
}

/// A cell as text: numbers in Rust's shortest round-trip form (so the value read back is the
/// cell's, bit for bit), text trimmed, empty cells empty; an error cell as its code (`#N/A`).
fn cell_text(c: &Data) -> String {
    match c {
        Data::Empty => String::new(),
        Data::Float(f) => f.to_string(),
        Data::Int(i) => i.to_string(),
        Data::String(s) | Data::DateTimeIso(s) | Data::DurationIso(s) => s.trim().to_string(),
        Data::Bool(b) => b.to_string().to_uppercase(),
        Data::DateTime(d) => d.as_f64().to_string(),
        Data::Error(e) => format!("{e}"),
    }
}

/// The rows of a sheet that are neither empty nor comments, with their 1-based row numbers.
fn rows(range: &calamine::Range<Data>) -> Vec<Fields> {
    let first_row = range.start().map_or(0, |(r, _)| r as usize);
    let first_col = range.start().map_or(0, |(_, c)| c as usize);
    range
        .rows()
        .enumerate()
        .map(|(k, cells)| Fields {
            no: first_row + k + 1,
            // cells left of the used range are empty: keep the columns where the sheet has them
            fields: std::iter::repeat_n(String::new(), first_col)
                .chain(cells.iter().map(cell_text))
                .collect(),
        })
        .filter(|r| {
            let first = r.fields.iter().find(|f| !f.is_empty());
            first.is_some_and(|f| !f.starts_with('#'))
        })
        .collect()
}

/// Read and validate the survey in the spreadsheet at `path` (see the module documentation).
pub(super) fn read_sheet(path: &Path, units: &SurveyUnits) -> InputResult<SurveyFile> {
    let size = std::fs::metadata(path)
        .map_err(|e| InputError::file(path, format!("cannot read the spreadsheet: {e}")))?
        .len();
    if size > MAX_SHEET_BYTES {
        return Err(InputError::file(
            path,
            format!(
                "the spreadsheet is larger than {} MiB, the limit drillpath reads; save the survey sheet alone",
                MAX_SHEET_BYTES / (1024 * 1024)
            ),
        ));
    }
    check_unzipped_size(path)?;
    let mut book =
        open_workbook_auto(path).map_err(|e| InputError::file(path, format!("cannot read the spreadsheet: {e}")))?;
    let names = book.sheet_names();
    let listed = || names.iter().map(|n| format!("`{n}`")).collect::<Vec<_>>().join(", ");
    let mut range_of = |name: &str| {
        book.worksheet_range(name)
            .map_err(|e| InputError::file(path, format!("cannot read sheet `{name}`: {e}")))
    };
    let (name, table) = match &units.sheet {
        Some(wanted) => {
            let Some(name) = names.iter().find(|n| n.trim() == wanted.trim()) else {
                return Err(InputError::file(
                    path,
                    format!("no sheet named `{wanted}`; the sheets are {}", listed()),
                ));
            };
            (name.clone(), rows(&range_of(name)?))
        }
        None => {
            let mut found = None;
            for name in &names {
                let table = rows(&range_of(name)?);
                if table.first().is_some_and(|r| names_all_roles(&r.fields)) {
                    found = Some((name.clone(), table));
                    break;
                }
            }
            found.ok_or_else(|| {
                InputError::file(
                    path,
                    format!(
                        "no sheet has a survey header (a first row naming the MD, inclination and azimuth columns, e.g. `md [m]`, `inc [deg]`, `azi [deg]`); the sheets are {}",
                        listed()
                    ),
                )
            })?
        }
    };
    if table.is_empty() {
        return Err(InputError::file(path, format!("sheet `{name}` is empty")));
    }
    let mut file = match parse_fields(&table, false, path, units) {
        Ok(f) => f,
        Err(Failure::Header(e) | Failure::Other(e)) => return Err(e),
    };
    file.notes.insert(
        0,
        format!("read sheet `{name}` of the spreadsheet (line numbers are its row numbers)"),
    );
    Ok(file)
}
