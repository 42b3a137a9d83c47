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
