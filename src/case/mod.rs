//! A validated case: well, mud, operation, string, bit-rock law and solver settings, all SI.
//!
//! Built from a TOML case file by [`crate::io::case_toml::load_case`]; every check that needs a
//! user-facing message is done there, so the mechanics can trust these values.

pub mod accuracy;
pub mod bit_rock;
pub mod fidelity;
pub mod fit;
pub mod operation;
pub mod solver;
pub mod steering;
pub mod tracking;
pub mod well;

pub use accuracy::Accuracy;
pub use bit_rock::{BitRock, Formation};
pub use fidelity::{choose, Choice, Fidelity, Level, Purpose};
pub use operation::{FrictionSplit, Mode, Motion, Mud, Operation};
pub use solver::{Method, SolverSettings, StabilizerContact};
pub use steering::{SteeringInterval, SteeringPlan};
pub use tracking::TrackingSettings;
pub use well::{AzimuthReference, StationInfo, SurveyFile, Well};

use crate::string::DrillString;
use std::path::PathBuf;

/// A complete validated case.
#[derive(Debug, Clone)]
pub struct Case {
    /// Case name.
    pub name: String,
    /// Free description.
    pub description: String,
    /// Case file path (or the survey CSV when a bare CSV was given).
    pub path: PathBuf,
    /// Well geometry.
    pub well: Well,
    /// Mud.
    pub mud: Mud,
    /// Operation.
    pub operation: Operation,
    /// The string (empty when only a survey was given).
    pub string: DrillString,
    /// The WITSML tubular file the string was read from (`string_from`), if any.
    pub string_from: Option<PathBuf>,
    /// Bit-rock law.
    pub bit_rock: BitRock,
    /// Solver settings.
    pub solver: SolverSettings,
    /// Survey assimilation settings (`[tracking]`).
    pub tracking: TrackingSettings,
    /// Where a bent housing slides and where it rotates (`[[steering]]`, `slide_sheet`).
    pub steering: SteeringPlan,
}

/// Rotary speed of a rotating steering interval (and of the rotating tendency) when the case
/// gives none, rev/min.
pub const DEFAULT_ROTATING_RPM: f64 = 60.0;

/// How far the string may reach above the first survey station before the straight
/// extrapolation there is worth a warning, m.
pub const ABOVE_SURVEY_NOTE_M: f64 = 1.0;

impl Case {
    /// The case with its string refitted to the bit depth `bit_md_m` (m,
    /// [`crate::string::DrillString::at_depth`]: the pipe shortened or lengthened at the surface)
    /// and its operation's bit depth set there; nothing else changed.
    pub fn at_bit_depth(&self, bit_md_m: f64) -> Case {
        let mut c = self.clone();
        c.string = self.string.at_depth(bit_md_m);
        c.operation.bit_md_m = bit_md_m;
        c
    }

    /// Every file the case was read from: the case file, its survey, its caliper, and the
    /// WITSML wbGeometry of its hole and tubular of its string.
    pub fn input_files(&self) -> Vec<PathBuf> {
        let mut files = vec![self.path.clone(), self.well.survey_path.clone()];
        files.extend(self.well.caliper_path.clone());
        files.extend(self.well.hole_from.clone());
        files.extend(self.string_from.clone());
        files.extend(self.steering.sheet_path.clone());
        files
    }

    /// This case drilling as the steering interval `iv` says: sliding at its toolface, or
    /// rotating (drilling at the case's rpm, 60 rpm when it gives none); a rotary steerable
    /// system at the interval's ratio when it gives one.
    pub fn steered(&self, iv: &SteeringInterval) -> Case {
        let mut c = self.on_bottom(iv.rotating);
        c.operation.toolface_rad = iv.toolface_rad;
        if let Some(r) = iv.ratio {
            c.string = c.string.with_rss_ratio(r);
        }
        c
    }

    /// This case drilling on bottom: rotating (mode `drilling` at the case's rpm,
    /// [`DEFAULT_ROTATING_RPM`] when it gives none) or sliding.
    pub fn on_bottom(&self, rotating: bool) -> Case {
        let mut c = self.clone();
        if rotating {
            c.operation.mode = Mode::Drilling;
            if c.operation.rpm <= 0.0 {
                c.operation.rpm = DEFAULT_ROTATING_RPM;
            }
        } else {
            c.operation.mode = Mode::Sliding;
        }
        c
    }

    /// The assumption made when the string reaches above the first survey station (a survey
    /// that starts at a tie-in): the hole there is the straight line along the first
    /// station's direction ([`crate::geometry::WellPath::point_at`]), which the hook load,
    /// surface torque and the contacts above depend on. None when the survey covers the string.
    pub fn string_above_survey_note(&self) -> Option<String> {
        let top_md_m = self.operation.bit_md_m - self.string.length_m();
        let first = self.well.path.stations().first()?;
        let above_m = first.md_m - top_md_m;
        if self.string.components.is_empty() || above_m <= ABOVE_SURVEY_NOTE_M {
            return None;
        }
        Some(format!(
            "the survey starts at {:.1} m MD but the string reaches up to {:.1} m MD: the hole above the first station is taken as a straight line along its direction (inclination {:.2} deg, azimuth {:.2} deg), and the hook load, surface torque and contacts there depend on that assumption; add the survey stations above {:.1} m MD (a vertical hole from surface: a station at 0 m with inclination 0)",
            first.md_m,
            top_md_m.max(0.0),
            first.inc_rad.to_degrees(),
            first.azi_rad.to_degrees(),
            first.md_m
        ))
    }
}
