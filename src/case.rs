//! A validated case: well, mud, operation, string, bit-rock law and solver settings, all SI.
//!
//! Built from a TOML case file by [`crate::io::case_toml::load_case`]; every check that needs a
//! user-facing message is done there, so the mechanics can trust these values.

use crate::geometry::{HoleSize, WellPath};
use crate::io::survey_csv::SurveyFile;
use crate::string::DrillString;
use std::path::PathBuf;

/// Load case: what the string is doing (interface.md `[operation] mode`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Mode {
    /// Rotating on bottom.
    Drilling,
    /// Sliding on bottom (no rotation).
    Sliding,
    /// Rotating off bottom (no axial motion, WOB 0).
    RotatingOffBottom,
    /// Running in (moving down, off bottom).
    TripIn,
    /// Pulling out (moving up, off bottom).
    TripOut,
}

impl Mode {
    /// Parse the case-file name.
    pub fn parse(s: &str) -> Option<Mode> {
        Some(match s {
            "drilling" => Mode::Drilling,
            "sliding" => Mode::Sliding,
            "rotating_off_bottom" => Mode::RotatingOffBottom,
            "trip_in" => Mode::TripIn,
            "trip_out" => Mode::TripOut,
            _ => return None,
        })
    }
    /// Name as in case files and `loads.csv`.
    pub fn name(self) -> &'static str {
        match self {
            Mode::Drilling => "drilling",
            Mode::Sliding => "sliding",
            Mode::RotatingOffBottom => "rotating_off_bottom",
            Mode::TripIn => "trip_in",
            Mode::TripOut => "trip_out",
        }
    }
    /// True when the bit is on bottom (WOB applies).
    pub fn on_bottom(self) -> bool {
        matches!(self, Mode::Drilling | Mode::Sliding)
    }
    /// Accepted names, for messages.
    pub const NAMES: &'static str = "drilling, sliding, rotating_off_bottom, trip_in, trip_out";
}

/// The well: path by minimum curvature and hole size.
#[derive(Debug, Clone)]
pub struct Well {
    /// Survey file as read (with the units assumed).
    pub survey: SurveyFile,
    /// Survey file path.
    pub survey_path: PathBuf,
    /// Hole axis.
    pub path: WellPath,
    /// Hole diameter by MD.
    pub hole: HoleSize,
}

/// Drilling fluid.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Mud {
    /// Density, kg/m3 (same inside and outside the string).
    pub density_kg_m3: f64,
    /// Plastic viscosity for the mud drag torque, Pa.s.
    pub plastic_viscosity_pa_s: f64,
}

/// Operating parameters, SI.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Operation {
    /// Load case.
    pub mode: Mode,
    /// Bit measured depth, m.
    pub bit_md_m: f64,
    /// Weight on bit, N (0 off bottom). When `hook_load_n` is given this is the starting guess.
    pub wob_n: f64,
    /// Hook load given instead of WOB, N.
    pub hook_load_n: Option<f64>,
    /// Surface rotary speed, rev/min (0 = no rotation).
    pub rpm: f64,
    /// Rate of penetration, m/s.
    pub rop_m_s: f64,
    /// Axial speed when tripping, m/s (positive).
    pub trip_speed_m_s: f64,
    /// Wall friction coefficient (sections may override it).
    pub friction: f64,
    /// Bit torque, N.m, if given (else from the bit law).
    pub bit_torque_nm: Option<f64>,
    /// Mud drag torque on the rotating string on/off.
    pub viscous_torque: bool,
}

impl Operation {
    /// Axial speed of the string, m/s, positive down the hole (ROP on bottom, +/- trip speed).
    pub fn axial_speed_m_s(&self) -> f64 {
        match self.mode {
            Mode::Drilling | Mode::Sliding => self.rop_m_s,
            Mode::RotatingOffBottom => 0.0,
            Mode::TripIn => self.trip_speed_m_s,
            Mode::TripOut => -self.trip_speed_m_s,
        }
    }
    /// Rotary speed in rad/s used by the mechanics (0 when sliding or tripping).
    pub fn omega_rad_s(&self) -> f64 {
        match self.mode {
            Mode::Sliding | Mode::TripIn | Mode::TripOut => 0.0,
            _ => self.rpm * std::f64::consts::TAU / 60.0,
        }
    }
}

/// One formation interval of the bit-rock law.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Formation {
    /// Top of the interval, m MD.
    pub from_md_m: f64,
    /// Bottom of the interval, m MD.
    pub to_md_m: f64,
    /// Rock anisotropy index I_r (physics.md 7.2).
    pub rock_anisotropy: f64,
    /// Bedding dip, rad.
    pub dip_rad: f64,
    /// Dip direction (azimuth of steepest descent), rad.
    pub dip_direction_rad: f64,
}

/// Bit-rock interaction law and its parameters (physics.md 7.2).
#[derive(Debug, Clone, PartialEq)]
pub struct BitRock {
    /// Law name (`ho`).
    pub law: String,
    /// Lateral/axial bit drillability ratio beta_b in (0, 1].
    pub lateral_drillability: f64,
    /// Bit walk angle chi_w, rad.
    pub walk_angle_rad: f64,
    /// Rock anisotropy index I_r outside any formation interval.
    pub rock_anisotropy: f64,
    /// Bedding dip, rad.
    pub dip_rad: f64,
    /// Dip direction, rad.
    pub dip_direction_rad: f64,
    /// Formation intervals overriding the defaults.
    pub formations: Vec<Formation>,
    /// Prediction step length, m.
    pub step_m: f64,
    /// Bit friction coefficient mu_b of the bit torque law T_b = mu_b W D_b / 3.
    pub bit_friction: f64,
}

/// Model fidelity (physics and speed trade).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Fidelity {
    /// Choose per command.
    Auto,
    /// Soft string (no bending stiffness).
    Soft,
    /// Stiff bottom-hole assembly only.
    Bha,
    /// Stiff bottom-hole assembly plus soft string above the cut.
    Hybrid,
    /// Whole stiff string.
    Whole,
}

/// Contact solution scheme.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Method {
    /// Newton with penalty/augmented-Lagrangian contact (robust default).
    Newton,
    /// The seed paper's modified Newton with gap additional forces (eq. 15).
    Paper,
}

/// Solver settings.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SolverSettings {
    /// Longest element in the pipe, m.
    pub element_length_m: f64,
    /// Longest element in the bottom-hole assembly, m.
    pub bha_element_length_m: f64,
    /// Contact gap tolerance relative to the local clearance.
    pub tolerance: f64,
    /// Fidelity.
    pub fidelity: Fidelity,
    /// Contact scheme.
    pub method: Method,
    /// Iteration limit.
    pub max_iterations: usize,
    /// Paper scheme's gradient-update factor alpha in (0, 1).
    pub alpha: f64,
    /// The accuracy preset that set the defaults above (`[solver] accuracy` or `--accuracy`),
    /// None when the documented defaults and explicit keys apply.
    pub accuracy: Option<crate::accuracy::Accuracy>,
}

impl Default for SolverSettings {
    fn default() -> Self {
        SolverSettings {
            element_length_m: 3.0,
            bha_element_length_m: 0.5,
            tolerance: 1e-4,
            fidelity: Fidelity::Auto,
            method: Method::Newton,
            max_iterations: 300,
            alpha: 0.7,
            accuracy: None,
        }
    }
}

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
    /// Bit-rock law.
    pub bit_rock: BitRock,
    /// Solver settings.
    pub solver: SolverSettings,
}

/// How far the string may reach above the first survey station before the straight
/// extrapolation there is worth a warning, m.
pub const ABOVE_SURVEY_NOTE_M: f64 = 1.0;

impl Case {
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
