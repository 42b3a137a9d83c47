//! The bit-rock interaction law's parameters and its formation intervals, SI.

/// Shortest prediction step accepted, m. A shorter step is an error
/// ([`crate::predict::march::PredictError::StepTooShort`]), never silently raised.
pub const MIN_STEP_M: f64 = 0.2;

/// One formation interval of the bit-rock law.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Formation {
    /// Top of the interval, m MD.
    pub from_md_m: f64,
    /// Bottom of the interval, m MD.
    pub to_md_m: f64,
    /// Rock anisotropy index I_r (docs/theory.md 9.3).
    pub rock_anisotropy: f64,
    /// Bedding dip, rad.
    pub dip_rad: f64,
    /// Dip direction (azimuth of steepest descent), rad.
    pub dip_direction_rad: f64,
}

/// Bit-rock interaction law and its parameters (docs/theory.md 9.3).
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

/// A parameter of the bit-rock law that calibration and tracking may estimate.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum LawParameter {
    /// The lateral drillability beta_b, in (0, 1].
    LateralDrillability,
    /// The walk angle chi_w, rad.
    WalkAngle,
    /// The rock anisotropy I_r, in (-0.5, 0.5) (the `[bit_rock]` default and every formation
    /// interval take the same value).
    RockAnisotropy,
}

impl LawParameter {
    /// Name as in `[bit_rock]`.
    pub fn name(self) -> &'static str {
        match self {
            LawParameter::LateralDrillability => "lateral_drillability",
            LawParameter::WalkAngle => "walk_angle",
            LawParameter::RockAnisotropy => "rock_anisotropy",
        }
    }
    /// Parse a name of `[bit_rock]`.
    pub fn parse(s: &str) -> Option<LawParameter> {
        Some(match s {
            "lateral_drillability" => LawParameter::LateralDrillability,
            "walk_angle" => LawParameter::WalkAngle,
            "rock_anisotropy" => LawParameter::RockAnisotropy,
            _ => return None,
        })
    }
    /// Accepted names, for messages.
    pub const NAMES: &'static str = "lateral_drillability, walk_angle, rock_anisotropy";
    /// Its value in `br` (natural units: rad for the walk angle).
    pub fn value(self, br: &BitRock) -> f64 {
        match self {
            LawParameter::LateralDrillability => br.lateral_drillability,
            LawParameter::WalkAngle => br.walk_angle_rad,
            LawParameter::RockAnisotropy => br.rock_anisotropy,
        }
    }
    /// Set it in `br` (the rock anisotropy in every formation interval too).
    pub fn set(self, br: &mut BitRock, v: f64) {
        match self {
            LawParameter::LateralDrillability => br.lateral_drillability = v,
            LawParameter::WalkAngle => br.walk_angle_rad = v,
            LawParameter::RockAnisotropy => {
                br.rock_anisotropy = v;
                for f in &mut br.formations {
                    f.rock_anisotropy = v;
                }
            }
        }
    }
}
