//! Spreadsheet surveys (`.xlsx`, via `calamine`) against the CSV they were saved from: the
//! example wells' survey CSVs written cell by cell to a workbook (with `rust_xlsxwriter`, as a
//! spreadsheet program saves a CSV it opened: numbers as numbers, text as text) read back to
//! identical stations, with the CSV reader's header, unit and error rules.

use std::path::{Path, PathBuf};

use drillpath::io::survey::{read_survey, SurveyUnits};
use drillpath::units::lookup;
use rust_xlsxwriter::Workbook;

use crate::common::example_dir;

/// Write the CSV file `csv` as sheet `name` of a new workbook at `out`, after a first sheet
/// `Notes` with no survey header (so the survey sheet must be found).
fn save_as_xlsx(csv: &Path, out: &Path, name: &str) {
    let text = std::fs::read_to_string(csv).unwrap();
    let text = text.trim_start_matches('\u{feff}'); // a spreadsheet program drops the BOM
    let mut book = Workbook::new();
    let notes = book.add_worksheet().set_name("Notes").unwrap();
    notes.write_string(0, 0, "Survey of an example well").unwrap();
    notes.write_string(1, 0, "md").unwrap();
    notes.write_number(2, 0, 1.0).unwrap();
    let sheet = book.add_worksheet().set_name(name).unwrap();
    for (r, line) in text.lines().enumerate() {
        if line.starts_with('#') {
            sheet.write_string(r as u32, 0, line).unwrap();
            continue;
        }
        for (c, field) in line.split(',').enumerate() {
            match field.trim().parse::<f64>() {
                Ok(v) => sheet.write_number(r as u32, c as u16, v).unwrap(),
                Err(_) => sheet.write_string(r as u32, c as u16, field).unwrap(),
            };
        }
    }
    book.save(out).unwrap();
}

fn saved(csv: &Path, name: &str) -> (tempfile::TempDir, PathBuf) {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("survey.xlsx");
    save_as_xlsx(csv, &out, name);
    (dir, out)
}

#[test]
fn example_csvs_saved_as_xlsx_give_identical_stations() {
    // Reference: the CSV reader on the same file; stations equal bit for bit, same units.
    for (well, file, md) in [
        ("volve-f10", "15_9-F-10_actual_trajectory.csv", None),
        ("j-shape", "survey.csv", None),
        ("forge-16a", "Directional_Survey16A-32.csv", Some("ft")),
    ] {
        let csv = example_dir(well).join(file);
        let (_dir, xlsx) = saved(&csv, "Survey");
        let units = SurveyUnits {
            md: md.and_then(lookup),
            ..Default::default()
        };
        let a = read_survey(&csv, &units).unwrap();
        let b = read_survey(&xlsx, &units).unwrap_or_else(|e| panic!("{well}: {e}"));
        assert_eq!(a.survey.stations(), b.survey.stations(), "{well}");
        assert_eq!(
            (&a.md_unit, &a.inc_unit, &a.azi_unit),
            (&b.md_unit, &b.inc_unit, &b.azi_unit)
        );
        assert_eq!(
            a.station_lines, b.station_lines,
            "{well}: the sheet's rows are the CSV's lines"
        );
        assert_eq!(a.azimuth_reference, b.azimuth_reference);
        assert!(b.notes[0].contains("read sheet `Survey`"), "{:?}", b.notes);
        println!("{well}: {} stations identical", a.survey.len());
    }
}

#[test]
fn the_sheet_is_chosen_by_name_and_errors_name_row_and_column() {
    let csv = example_dir("j-shape").join("survey.csv");
    let (_dir, xlsx) = saved(&csv, "Directional survey");
    let with_sheet = |s: &str| SurveyUnits {
        sheet: Some(s.into()),
        ..Default::default()
    };
    assert!(read_survey(&xlsx, &with_sheet("Directional survey")).is_ok());
    let e = read_survey(&xlsx, &with_sheet("Nope")).unwrap_err().to_string();
    assert!(
        e.contains("no sheet named `Nope`; the sheets are `Notes`, `Directional survey`"),
        "{e}"
    );
    let e = read_survey(&xlsx, &with_sheet("Notes")).unwrap_err().to_string();
    assert!(
        e.contains("survey.xlsx: line 1") && e.contains("the header has no"),
        "{e}"
    );

    // a text cell where a number belongs: the row and the column as the header writes it
    let dir = tempfile::tempdir().unwrap();
    let bad = dir.path().join("bad.xlsx");
    let mut book = Workbook::new();
    let s = book.add_worksheet();
    for (c, h) in ["MD [ft]", "Inc", "Azi"].iter().enumerate() {
        s.write_string(2, c as u16, *h).unwrap();
    }
    s.write_string(3, 0, "(ft)").unwrap();
    s.write_string(3, 1, "(deg)").unwrap();
    s.write_string(3, 2, "(deg)").unwrap();
    s.write_number(4, 0, 0.0).unwrap();
    s.write_number(4, 1, 0.0).unwrap();
    s.write_number(4, 2, 0.0).unwrap();
    s.write_number(5, 0, 100.0).unwrap();
    s.write_string(5, 1, "ten").unwrap();
    s.write_number(5, 2, 3.0).unwrap();
    book.save(&bad).unwrap();
    let e = read_survey(&bad, &SurveyUnits::default()).unwrap_err().to_string();
    assert!(
        e.starts_with(&format!("{}: line 6, column `Inc`", bad.display())),
        "{e}"
    );
    assert!(e.contains("the inclination value `ten` is not a number"), "{e}");
    // a file that is not a spreadsheet
    let fake = dir.path().join("fake.xlsx");
    std::fs::write(&fake, "md,inc,azi\n0,0,0\n").unwrap();
    let e = read_survey(&fake, &SurveyUnits::default()).unwrap_err().to_string();
    assert!(
        e.starts_with(&format!("{}: cannot read the spreadsheet", fake.display())),
        "{e}"
    );
}

#[test]
fn a_decompression_bomb_is_refused_before_it_is_read() {
    // a zip named .xlsx whose sheet part decompresses to 260 MiB of zeros (a 260 kB file): the
    // guard reads the sizes the zip declares and refuses it before any part is inflated
    use std::io::Write;
    let dir = tempfile::tempdir().unwrap();
    let bomb = dir.path().join("bomb.xlsx");
    let mut zip = zip::ZipWriter::new(std::fs::File::create(&bomb).unwrap());
    let options = zip::write::SimpleFileOptions::default().compression_method(zip::CompressionMethod::Deflated);
    zip.start_file("xl/worksheets/sheet1.xml", options).unwrap();
    let zeros = vec![0u8; 1 << 20];
    for _ in 0..260 {
        zip.write_all(&zeros).unwrap();
    }
    zip.finish().unwrap();
    let t0 = std::time::Instant::now();
    let e = read_survey(&bomb, &SurveyUnits::default()).unwrap_err().to_string();
    assert!(t0.elapsed() < std::time::Duration::from_secs(1));
    assert!(
        e.contains("decompress to 260 MiB") && e.contains("more than the 256 MiB"),
        "{e}"
    );
}
