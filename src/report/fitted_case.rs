//! The case with the calibrated bit-rock law (`case_fitted.toml` of `backanalyze --calibrate`):
//! the case file's own text, comments kept, with the fitted `[bit_rock]` keys set and the
//! paths of its survey and caliper made to point from the output directory to the same files.

use crate::io::paths::resolve;
use crate::predict::calibrate::{Calibration, FitParameter};
use std::path::{Component, Path, PathBuf};
use toml_edit::{value, DocumentMut, Item, Table};

/// The text of the case `case_text` (read from the directory `case_dir`) with the fitted
/// values of `c` in its `[bit_rock]` table, to be written into `out_dir`.
pub fn fitted_case_toml(case_text: &str, case_dir: &Path, out_dir: &Path, c: &Calibration) -> Result<String, String> {
    let mut doc: DocumentMut = case_text
        .parse()
        .map_err(|e| format!("the case file does not parse: {e}"))?;
    if let Some(well) = doc.get_mut("well").and_then(Item::as_table_like_mut) {
        for key in ["survey", "caliper"] {
            if let Some(rel) = well.get(key).and_then(Item::as_str).map(str::to_string) {
                let moved = relative_to(&resolve(&case_dir.join(&rel)), &resolve(out_dir));
                well.insert(key, value(moved.to_string_lossy().replace('\\', "/")));
            }
        }
    }
    if doc.get("bit_rock").is_none() {
        doc.insert("bit_rock", Item::Table(Table::new()));
    }
    let table = doc
        .get_mut("bit_rock")
        .and_then(Item::as_table_like_mut)
        .ok_or("the case's `bit_rock` is not a table")?;
    for &(p, v, _) in &c.fitted {
        match p {
            FitParameter::WalkAngle => table.insert(p.name(), value(format!("{:.4} deg", v.to_degrees()))),
            _ => table.insert(p.name(), value((v * 1e6).round() / 1e6)),
        };
    }
    let header = "# the case with the bit-rock law fitted by drillpath backanalyze --calibrate (the\n# fitted keys of [bit_rock] set, the survey and caliper paths pointing from this folder)\n";
    Ok(format!("{header}{doc}"))
}

/// The path of `target` seen from the directory `from` (both absolute).
fn relative_to(target: &Path, from: &Path) -> PathBuf {
    let t: Vec<Component> = target.components().collect();
    let f: Vec<Component> = from.components().collect();
    let common = t.iter().zip(&f).take_while(|(a, b)| a == b).count();
    let mut out = PathBuf::new();
    for _ in common..f.len() {
        out.push("..");
    }
    for c in &t[common..] {
        out.push(c.as_os_str());
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn paths_point_from_the_output_directory() {
        let r = relative_to(Path::new("/a/wells/x/survey.csv"), Path::new("/a/out/run"));
        assert_eq!(r, PathBuf::from("../../wells/x/survey.csv"));
        assert_eq!(
            relative_to(Path::new("/a/s.csv"), Path::new("/a")),
            PathBuf::from("s.csv")
        );
    }
}
