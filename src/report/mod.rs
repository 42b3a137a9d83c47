//! Outputs: CSV and JSON files with the interface's names, written atomically.

pub mod display_units;
pub mod html;
pub mod inputs;
pub mod levels_output;
pub mod loads_output;
pub mod plots;
pub mod predict_output;
pub mod predict_report;
pub mod schematic;
pub mod solve_output;
pub mod solve_report;
pub mod survey_table;

use std::io::Write;
use std::path::Path;

/// Write `contents` to `path` atomically: a temporary file in the same directory, then a
/// rename, so a failed run never leaves a half-written file that looks complete.
pub fn write_atomic(path: &Path, contents: &[u8]) -> std::io::Result<()> {
    let dir = path
        .parent()
        .filter(|p| !p.as_os_str().is_empty())
        .unwrap_or(Path::new("."));
    std::fs::create_dir_all(dir)?;
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_else(|| "out".into());
    let tmp = dir.join(format!(".{name}.tmp{}", std::process::id()));
    let result = (|| {
        let mut f = std::fs::File::create(&tmp)?;
        f.write_all(contents)?;
        f.sync_all()?;
        std::fs::rename(&tmp, path)
    })();
    if result.is_err() {
        let _ = std::fs::remove_file(&tmp);
    }
    result
}

/// A finite number for JSON output; NaN or infinity is an internal error, never written.
pub fn finite(x: f64) -> Result<f64, String> {
    if x.is_finite() {
        Ok(x)
    } else {
        Err(format!("non-finite value {x} in output"))
    }
}

/// Format a finite number for CSV output; NaN or infinity is an internal error, never printed.
pub fn num(x: f64, decimals: usize) -> Result<String, String> {
    Ok(display_units::fixed(finite(x)?, decimals))
}
