//! What the string is doing: the load case, the operating parameters and the drilling fluid, SI.

/// Load case: what the string is doing (docs/guide.md `[operation] mode`).
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
