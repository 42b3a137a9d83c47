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
    /// Toolface of a bent motor, rad in [0, 2 pi): gravity toolface (from the high side,
    /// positive to the right looking down the hole), magnetic (from north) where the hole is
    /// within [`crate::geometry::frame::MAGNETIC_TOOLFACE_BELOW_RAD`] of vertical
    /// ([`crate::geometry::frame::toolface_direction`]). Fixed when sliding; a rotating string
    /// turns it (docs/theory.md, "Bent motors").
    pub toolface_rad: f64,
    /// Let the motor's reactive torque turn a sliding bent housing's toolface to the left
    /// (docs/theory.md 9.9, "Reactive torque"; off by default: the toolface is the one held
    /// downhole).
    pub reactive_torque: bool,
}

impl Operation {
    /// The motion of the string that sets the direction of wall friction in every model (soft
    /// string, stiff BHA, hybrid, whole string; `solve`, `loads` and the predictor): the one rule
    /// of docs/theory.md 1, "Motion".
    ///
    /// - Rotary speed: [`Operation::omega_rad_s`] (the case's rpm when drilling or rotating off
    ///   bottom, 0 when sliding or tripping).
    /// - Axial direction: the one the mode implies: down the hole on bottom (drilling, sliding)
    ///   and running in, up the hole pulling out, none rotating off bottom.
    /// - Axial speed: the ROP on bottom and the trip speed tripping, when positive. When the
    ///   case gives none (ROP 0, the default) the speed depends on the rotation: a string that
    ///   does not rotate moves at [`NOMINAL_AXIAL_SPEED_M_S`] (only the direction matters then,
    ///   so sliding at ROP 0 has the full axial drag `f N`, as at any ROP); a rotating string
    ///   has axial speed 0 (its ROP is negligible against the surface speed, 12 m/h against
    ///   0.5 m/s at 60 rpm: all the friction is circumferential, no axial drag).
    pub fn motion(&self) -> Motion {
        let omega = self.omega_rad_s();
        let (direction, given) = match self.mode {
            Mode::Drilling | Mode::Sliding => (1.0, self.rop_m_s),
            Mode::TripIn => (1.0, self.trip_speed_m_s),
            Mode::TripOut => (-1.0, self.trip_speed_m_s),
            Mode::RotatingOffBottom => (0.0, 0.0),
        };
        let speed = if given > 0.0 {
            given
        } else if omega == 0.0 {
            NOMINAL_AXIAL_SPEED_M_S
        } else {
            0.0
        };
        Motion {
            axial_speed_m_s: direction * speed,
            omega_rad_s: omega,
        }
    }
    /// True when the string turns (rotary speed above 0): a bent housing then turns with it
    /// and its tendency is the average over a revolution; otherwise its toolface is fixed.
    pub fn rotates(&self) -> bool {
        self.omega_rad_s() > 0.0
    }
    /// Rotary speed in rad/s used by the mechanics (0 when sliding or tripping).
    pub fn omega_rad_s(&self) -> f64 {
        match self.mode {
            Mode::Sliding | Mode::TripIn | Mode::TripOut => 0.0,
            _ => self.rpm * std::f64::consts::TAU / 60.0,
        }
    }
}

/// Axial speed of a string that does not rotate and whose operation implies an axial motion
/// without giving its speed (sliding or drilling at ROP 0, tripping at trip speed 0), m/s:
/// 1 m/h. Without rotation the friction is `f N` against the direction of motion whatever the
/// speed, so the value only needs to be positive.
pub const NOMINAL_AXIAL_SPEED_M_S: f64 = 1.0 / 3600.0;

/// Slowest sliding speed of the string surface on the wall at which friction acts, m/s: below it
/// the direction of friction is undetermined and friction is left out (no static friction).
pub const MIN_FRICTION_SPEED_M_S: f64 = 1e-12;

/// The motion of the string against the wall (docs/theory.md 1, "Motion"), SI: from a case by
/// [`Operation::motion`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Motion {
    /// Axial speed, m/s, positive down the hole (running in, drilling ahead), negative pulling
    /// out.
    pub axial_speed_m_s: f64,
    /// Rotary speed, rad/s (>= 0, clockwise seen from above; 0 = not rotating).
    pub omega_rad_s: f64,
}

/// How wall friction `f N` divides at a contact between the axial and the circumferential
/// direction: the shares of the unit sliding velocity of the string surface, dimensionless.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FrictionSplit {
    /// Axial share `v_a/|v|`, in [-1, 1]: positive when the string moves down the hole (the
    /// friction on the string then acts up the hole).
    pub axial: f64,
    /// Circumferential share `Omega R_c/|v|`, in [0, 1]: the friction torque is
    /// `f N R_c x tangential`.
    pub tangential: f64,
}

impl FrictionSplit {
    /// No friction (no motion).
    pub const NONE: FrictionSplit = FrictionSplit {
        axial: 0.0,
        tangential: 0.0,
    };
    /// True when friction acts (some motion at the contact).
    pub fn acts(&self) -> bool {
        self.axial != 0.0 || self.tangential != 0.0
    }
}

impl Motion {
    /// True when the string moves at all (axial or rotary speed nonzero); a string at rest is
    /// frictionless in every model.
    pub fn is_moving(&self) -> bool {
        self.axial_speed_m_s != 0.0 || self.omega_rad_s != 0.0
    }
    /// The split of wall friction at a contact of radius `contact_radius_m` (m, the surface
    /// that slides on the wall): the sliding velocity is `v = v_a t + Omega R_c (t x n)`, so the
    /// shares are `v_a/|v|` and `Omega R_c/|v|` with `|v| = sqrt(v_a^2 + (Omega R_c)^2)`;
    /// [`FrictionSplit::NONE`] when `|v| <= MIN_FRICTION_SPEED_M_S`. The one rule of every
    /// model (soft string, gap elements, pins, the contact Newton's columns and its start).
    pub fn friction_split(&self, contact_radius_m: f64) -> FrictionSplit {
        let v_t = self.omega_rad_s * contact_radius_m;
        let speed = self.axial_speed_m_s.hypot(v_t);
        if speed > MIN_FRICTION_SPEED_M_S {
            FrictionSplit {
                axial: self.axial_speed_m_s / speed,
                tangential: v_t / speed,
            }
        } else {
            FrictionSplit::NONE
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn op(mode: Mode, rpm: f64, rop_m_h: f64, trip_m_s: f64) -> Operation {
        Operation {
            mode,
            bit_md_m: 1000.0,
            wob_n: 0.0,
            hook_load_n: None,
            rpm,
            rop_m_s: rop_m_h / 3600.0,
            trip_speed_m_s: trip_m_s,
            friction: 0.25,
            bit_torque_nm: None,
            viscous_torque: false,
            reactive_torque: false,
            toolface_rad: 0.0,
        }
    }

    /// The motion rule of docs/theory.md 1, "Motion", case by case: the direction is the mode's,
    /// the speed the case's when given, else nominal without rotation and 0 with rotation.
    #[test]
    fn motion_follows_the_mode_and_the_given_speeds() {
        let w60 = std::f64::consts::TAU;
        let nominal = NOMINAL_AXIAL_SPEED_M_S;
        let cases = [
            (op(Mode::Drilling, 60.0, 12.0, 0.3), 12.0 / 3600.0, w60),
            (op(Mode::Drilling, 60.0, 0.0, 0.3), 0.0, w60),
            (op(Mode::Drilling, 0.0, 0.0, 0.3), nominal, 0.0),
            (op(Mode::Sliding, 60.0, 12.0, 0.3), 12.0 / 3600.0, 0.0),
            (op(Mode::Sliding, 60.0, 0.0, 0.3), nominal, 0.0),
            (op(Mode::RotatingOffBottom, 60.0, 12.0, 0.3), 0.0, w60),
            (op(Mode::RotatingOffBottom, 0.0, 12.0, 0.3), 0.0, 0.0),
            (op(Mode::TripIn, 60.0, 12.0, 0.3), 0.3, 0.0),
            (op(Mode::TripIn, 60.0, 12.0, 0.0), nominal, 0.0),
            (op(Mode::TripOut, 60.0, 12.0, 0.3), -0.3, 0.0),
            (op(Mode::TripOut, 0.0, 0.0, 0.0), -nominal, 0.0),
        ];
        for (o, v_a, omega) in cases {
            let m = o.motion();
            assert_eq!(m.axial_speed_m_s, v_a, "{:?}", o);
            assert!((m.omega_rad_s - omega).abs() < 1e-12, "{:?}", o);
        }
    }

    /// The split: shares of the unit sliding velocity `(v_a, Omega R_c)/|v|`; pure directions
    /// without rotation or without axial motion; none at rest.
    #[test]
    fn friction_split_is_the_unit_sliding_velocity() {
        let m = Motion {
            axial_speed_m_s: 0.3,
            omega_rad_s: 5.0,
        };
        let s = m.friction_split(0.08);
        assert!((s.axial - 0.6).abs() < 1e-15 && (s.tangential - 0.8).abs() < 1e-15);
        let slide = op(Mode::Sliding, 0.0, 0.0, 0.3).motion().friction_split(0.08);
        assert_eq!(
            slide,
            FrictionSplit {
                axial: 1.0,
                tangential: 0.0
            }
        );
        let out = op(Mode::TripOut, 0.0, 0.0, 0.0).motion().friction_split(0.08);
        assert_eq!(
            out,
            FrictionSplit {
                axial: -1.0,
                tangential: 0.0
            }
        );
        let rot = op(Mode::Drilling, 60.0, 0.0, 0.0).motion().friction_split(0.08);
        assert_eq!(
            rot,
            FrictionSplit {
                axial: 0.0,
                tangential: 1.0
            }
        );
        let rest = op(Mode::RotatingOffBottom, 0.0, 0.0, 0.0).motion();
        assert!(!rest.is_moving());
        assert_eq!(rest.friction_split(0.08), FrictionSplit::NONE);
        assert!(!FrictionSplit::NONE.acts());
    }
}
