//! Outputs: CSV and JSON files with the interface's names, written atomically.

pub mod case_writer;
pub mod display_units;
pub mod fitted_case;
pub mod html;
pub mod inputs;
pub mod loads_output;
pub mod loads_text;
pub mod plots;
pub mod predict_output;
pub mod predict_report;
pub mod predict_text;
pub mod schematic;
pub mod solve_output;
pub mod solve_report;
pub mod solve_text;
pub mod survey_table;
pub mod tendency_output;
pub mod tracking_output;
pub mod witsml_out;

use std::path::Path;

/// Write `contents` to `path` atomically: a temporary file in the same directory
/// ([`crate::io::paths::write_temp`]), then a rename, so a failed run never leaves a
/// half-written file that looks complete. Missing directories are created.
pub fn write_atomic(path: &Path, contents: &[u8]) -> std::io::Result<()> {
    if let Some(dir) = path.parent().filter(|p| !p.as_os_str().is_empty()) {
        std::fs::create_dir_all(dir)?;
    }
    let tmp = crate::io::paths::write_temp(path, contents)?;
    std::fs::rename(&tmp, path).inspect_err(|_| {
        let _ = std::fs::remove_file(&tmp);
    })
}

/// A finite number for JSON output; NaN or infinity is an internal error, never written.
pub fn finite(x: f64) -> Result<f64, String> {
    if x.is_finite() {
        Ok(x)
    } else {
        Err(format!("non-finite value {x} in output"))
    }
}

/// A number for JSON output: a finite value serializes as a number; NaN or infinity is an
/// internal error (the serialization fails), never written.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Finite(pub f64);

impl serde::Serialize for Finite {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        if self.0.is_finite() {
            s.serialize_f64(self.0)
        } else {
            Err(serde::ser::Error::custom(format!(
                "non-finite value {} in output",
                self.0
            )))
        }
    }
}

/// `Some(Finite(x / si_per_unit))`, or None: an optional SI value for JSON output in a unit
/// (`si_per_unit`: 1e3 for kN from N; None is `null`).
pub fn in_unit(x: Option<f64>, si_per_unit: f64) -> Option<Finite> {
    x.map(|v| Finite(v / si_per_unit))
}

/// Pretty JSON text of `value` with its object keys in alphabetical order (the order of every
/// `summary.json`); a non-finite number is an error naming it.
pub fn json_text<T: serde::Serialize>(value: &T) -> Result<String, String> {
    let v = serde_json::to_value(value).map_err(|e| e.to_string())?;
    serde_json::to_string_pretty(&v).map_err(|e| e.to_string())
}

/// Format a finite number for CSV output; NaN or infinity is an internal error, never printed.
pub fn num(x: f64, decimals: usize) -> Result<String, String> {
    Ok(display_units::fixed(finite(x)?, decimals))
}
