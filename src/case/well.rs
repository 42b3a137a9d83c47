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
    /// The north the azimuths are measured from, as the file states it (a qualified azimuth
    /// column such as `Azimuth Grid`, or a report's `NORTH REF : Grid` line); the azimuths are
    /// used as written, never converted.
    pub azimuth_reference: AzimuthReference,
    /// Where the file states the azimuth reference, e.g. "column `Azimuth Grid ( deg )`" or
    /// "line 14 `NORTH REF : Grid`"; empty when it does not.
    pub azimuth_reference_source: String,
}

/// The north a survey's azimuths are measured from, as stated by the survey file.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum AzimuthReference {
    /// The file does not say.
    #[default]
    Unspecified,
    /// True (geographic) north.
    True,
    /// Grid north of the map projection.
    Grid,
    /// Magnetic north.
    Magnetic,
}

impl AzimuthReference {
    /// Name in outputs (`summary.json` `azimuth_reference`): `unspecified`, `true`, `grid` or
    /// `magnetic`.
    pub fn name(self) -> &'static str {
        match self {
            AzimuthReference::Unspecified => "unspecified",
            AzimuthReference::True => "true",
            AzimuthReference::Grid => "grid",
            AzimuthReference::Magnetic => "magnetic",
        }
    }

    /// Words for people, e.g. `grid north`.
    pub fn describe(self) -> &'static str {
        match self {
            AzimuthReference::Unspecified => "not stated in the survey file",
            AzimuthReference::True => "true north",
            AzimuthReference::Grid => "grid north",
            AzimuthReference::Magnetic => "magnetic north",
        }
    }
}
