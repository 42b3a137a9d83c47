//! The well: survey as read, hole axis by minimum curvature and hole size.

use crate::geometry::{HoleSize, Station, Survey, WellPath};
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
    /// The WITSML wbGeometry file the hole sections were read from (`hole_from`), if any.
    pub hole_from: Option<PathBuf>,
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
    /// Magnetic declination the file says was applied to its azimuths (WITSML `magDeclUsed`),
    /// rad, east positive; `None` when the file does not say.
    pub magnetic_declination_rad: Option<f64>,
    /// Grid convergence the file says was applied (WITSML `gridCorUsed`), rad: the angle from
    /// true north to grid north, clockwise positive (east of the central meridian in the
    /// northern hemisphere); `None` when the file does not say.
    pub grid_convergence_rad: Option<f64>,
    /// Position of the first station as the file states it (a WITSML tie-in point's `dispNs`,
    /// `dispEw`, `tvd`): `[north, east, tvd]`, m; `None` when the file does not give it.
    pub origin: Option<[f64; 3]>,
    /// Per station of `survey` (same order), what the file says of it beyond MD, inclination
    /// and azimuth; empty for files that say nothing more (CSV, text reports, spreadsheets).
    pub station_info: Vec<StationInfo>,
    /// Stations of the file that are not measurements (WITSML projected, planned or
    /// interpolated stations): kept here, not in `survey`.
    pub projected: Vec<(Station, StationInfo)>,
}

/// What a survey file says of one station beyond its MD, inclination and azimuth (WITSML
/// `trajectoryStation`).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct StationInfo {
    /// The station's identifier in the file (WITSML `uid`), empty when none.
    pub uid: String,
    /// The station type as written (WITSML `typeTrajStation`: `tie in point`, `magnetic MWD`,
    /// `gyro north seeking`, ...), `unknown` when not given.
    pub kind: String,
    /// Gravity toolface (WITSML `gtf`), rad; `None` when not given.
    pub gtf_rad: Option<f64>,
    /// Magnetic toolface (WITSML `mtf`), rad; `None` when not given.
    pub mtf_rad: Option<f64>,
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
