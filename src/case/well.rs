//! The well: survey as read, hole axis by minimum curvature and hole size.

use crate::geometry::{HoleSize, Survey, WellPath};
use std::path::PathBuf;

/// The well: path by minimum curvature and hole size.
#[derive(Debug, Clone)]
pub struct Well {
    /// Survey file as read (with the units assumed).
    pub survey: SurveyFile,
    /// Survey file path.
    pub survey_path: PathBuf,
    /// Caliper file path, when the case names one.
    pub caliper_path: Option<PathBuf>,
    /// Hole axis.
    pub path: WellPath,
    /// Hole diameter by MD.
    pub hole: HoleSize,
}

/// What was read, with the units that were used for each column (so the CLI can print them).
#[derive(Debug, Clone)]
pub struct SurveyFile {
    /// The validated survey, SI (m, rad), azimuth normalized to [0, 2 pi).
    pub survey: Survey,
    /// Canonical name of the unit the measured depths were read in, e.g. `"ft"`.
    pub md_unit: String,
    /// Canonical name of the unit the inclinations were read in, e.g. `"deg"`.
    pub inc_unit: String,
    /// Canonical name of the unit the azimuths were read in, e.g. `"deg"`.
    pub azi_unit: String,
    /// Human notes, e.g. "md column `Measured depth` has no unit in its header: assumed ft (from the case file)".
    pub notes: Vec<String>,
    /// 1-based line number of each station in the file (for errors found after reading).
    pub station_lines: Vec<usize>,
}
