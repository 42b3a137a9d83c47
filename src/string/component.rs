//! String components (bit, stabilizer, collar, pipe, ...) and their section properties.

use super::material::Material;
use crate::units::G;
use std::f64::consts::PI;

/// Kind of string component.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ComponentKind {
    /// Drill bit (centred on the hole axis at its face; above the face it touches the wall only
    /// along its gauge, if it has one).
    Bit,
    /// Stabilizer: touches the wall with its blade OD along its blades, centred on its length
    /// (at its middle only with `[solver] stabilizer_contact = "point"`).
    Stabilizer,
    /// Drill collar.
    Collar,
    /// Drill pipe (tool joints optional).
    Pipe,
    /// Heavy-weight drill pipe.
    Hwdp,
    /// Downhole motor (straight, or with a bent housing: [`Component::bend`]).
    Motor,
    /// MWD tool.
    Mwd,
    /// Sub or crossover.
    Sub,
    /// Drilling jar.
    Jar,
    /// Rotary steerable system: push-the-bit or point-the-bit ([`Component::rss`]).
    Rss,
}

impl ComponentKind {
    /// Parse the case-file name.
    pub fn parse(s: &str) -> Option<ComponentKind> {
        Some(match s.to_ascii_lowercase().as_str() {
            "bit" => ComponentKind::Bit,
            "stabilizer" | "stabiliser" | "stab" => ComponentKind::Stabilizer,
            "collar" | "dc" => ComponentKind::Collar,
            "pipe" | "dp" => ComponentKind::Pipe,
            "hwdp" => ComponentKind::Hwdp,
            "motor" => ComponentKind::Motor,
            "mwd" => ComponentKind::Mwd,
            "sub" => ComponentKind::Sub,
            "jar" => ComponentKind::Jar,
            "rss" => ComponentKind::Rss,
            _ => return None,
        })
    }
    /// Name as written in case files.
    pub fn name(self) -> &'static str {
        match self {
            ComponentKind::Bit => "bit",
            ComponentKind::Stabilizer => "stabilizer",
            ComponentKind::Collar => "collar",
            ComponentKind::Pipe => "pipe",
            ComponentKind::Hwdp => "hwdp",
            ComponentKind::Motor => "motor",
            ComponentKind::Mwd => "mwd",
            ComponentKind::Sub => "sub",
            ComponentKind::Jar => "jar",
            ComponentKind::Rss => "rss",
        }
    }
    /// Accepted names, for messages.
    pub const NAMES: &'static str = "bit, stabilizer, collar, pipe, hwdp, motor, mwd, sub, jar, rss";
}

/// Fraction of a stabilizer's length its blades take when `blade_length` is not given.
pub const DEFAULT_BLADE_FRACTION: f64 = 0.25;
/// Shortest default blade, m (12 in), or the whole stabilizer if it is shorter.
pub const MIN_DEFAULT_BLADE_M: f64 = 0.3;

/// Blade length of a stabilizer `length_m` long whose case gives none, m: a quarter of its
/// length, at least 0.3 m (the whole stabilizer when shorter). Typical of integral-blade string
/// and near-bit stabilizers, whose gauge blades of about 0.4-0.45 m (16-18 in) sit on bodies of
/// 1.5-1.8 m (docs/guide.md, `[[string]]`; a typical value, not a catalogue's).
pub fn default_blade_length_m(length_m: f64) -> f64 {
    (DEFAULT_BLADE_FRACTION * length_m).max(MIN_DEFAULT_BLADE_M.min(length_m))
}

/// One component of the string, SI units. Positions are distances from the bit face, m.
#[derive(Debug, Clone, PartialEq)]
pub struct Component {
    /// Kind.
    pub kind: ComponentKind,
    /// User label (or the kind's name).
    pub name: String,
    /// Length, m.
    pub length_m: f64,
    /// Distance from the bit face to the component's bottom, m.
    pub bottom_m: f64,
    /// Body outer diameter used for stiffness, weight and contact, m.
    pub body_od_m: f64,
    /// Contact diameter where the component touches the wall: stabilizer blade OD, bit OD, else body OD, m.
    pub contact_od_m: f64,
    /// Length over which the contact OD touches the wall, m: a stabilizer's blades (centred on
    /// the component), a bit's gauge (from the face up; 0: the face only); 0 for the other
    /// kinds, whose whole body may touch (docs/theory.md 3.4).
    pub contact_length_m: f64,
    /// Inner diameter, m (0 for a solid body).
    pub id_m: f64,
    /// Tool-joint outer diameter, m, if the component has tool joints.
    pub tool_joint_od_m: Option<f64>,
    /// Joint spacing, m (default 9.144 m = 30 ft).
    pub joint_length_m: f64,
    /// Material (after per-component overrides).
    pub material: Material,
    /// Weight in air per length, N/m (given adjusted weight, or from the body and density).
    pub weight_air_n_per_m: f64,
    /// Distance from the bit face to the survey sensor of an `mwd` component, m (None: no
    /// sensor given).
    pub sensor_to_bit_m: Option<f64>,
    /// Bent housing of a `motor` component (None: straight; also for a zero bend angle).
    pub bend: Option<MotorBend>,
    /// Steering of an `rss` component (None for the other kinds).
    pub rss: Option<RssTool>,
}

/// How a rotary steerable system steers (docs/theory.md 9.10), SI.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum RssSteer {
    /// Push-the-bit: pads push the tool toward the set toolface with a force of set
    /// magnitude `pad_force_n` (N, >= 0) at `pad_to_bit_m` (m above the bit face, on the
    /// `rss` component).
    PushTheBit {
        /// Pad force, N.
        pad_force_n: f64,
        /// Distance from the bit face to the pads, m.
        pad_to_bit_m: f64,
    },
    /// Point-the-bit: the bit shaft is deflected by `deflection_rad` (rad, >= 0) at a hinge
    /// `hinge_to_bit_m` (m above the bit face, on the `rss` component), toward the toolface.
    PointTheBit {
        /// Deflection of the bit shaft, rad.
        deflection_rad: f64,
        /// Distance from the bit face to the hinge, m.
        hinge_to_bit_m: f64,
    },
}

/// A rotary steerable system: its steering and its steering ratio (the share of the time it
/// steers at the set toolface; the rest of the time it is neutral).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RssTool {
    /// Push-the-bit or point-the-bit.
    pub steer: RssSteer,
    /// Steering ratio (duty cycle), in [0, 1].
    pub ratio: f64,
}

impl RssTool {
    /// The same tool neutral: no pad force, no deflection (positions kept, so the mesh is the
    /// same).
    pub fn neutral(&self) -> RssTool {
        let steer = match self.steer {
            RssSteer::PushTheBit { pad_to_bit_m, .. } => RssSteer::PushTheBit {
                pad_force_n: 0.0,
                pad_to_bit_m,
            },
            RssSteer::PointTheBit { hinge_to_bit_m, .. } => RssSteer::PointTheBit {
                deflection_rad: 0.0,
                hinge_to_bit_m,
            },
        };
        RssTool {
            steer,
            ratio: self.ratio,
        }
    }
    /// Distance from the bit face to the pads or the hinge, m.
    pub fn position_to_bit_m(&self) -> f64 {
        match self.steer {
            RssSteer::PushTheBit { pad_to_bit_m, .. } => pad_to_bit_m,
            RssSteer::PointTheBit { hinge_to_bit_m, .. } => hinge_to_bit_m,
        }
    }
    /// The kink of the unloaded axis of a point-the-bit tool (None for push-the-bit).
    pub fn kink(&self) -> Option<MotorBend> {
        match self.steer {
            RssSteer::PointTheBit {
                deflection_rad,
                hinge_to_bit_m,
            } => Some(MotorBend {
                angle_rad: deflection_rad,
                to_bit_m: hinge_to_bit_m,
            }),
            RssSteer::PushTheBit { .. } => None,
        }
    }
    /// Name of the kind as written in case files (`push-the-bit`, `point-the-bit`).
    pub fn kind_name(&self) -> &'static str {
        match self.steer {
            RssSteer::PushTheBit { .. } => "push-the-bit",
            RssSteer::PointTheBit { .. } => "point-the-bit",
        }
    }
}

/// The bent housing of a motor: a kink of the unloaded string axis (docs/theory.md, "Bent
/// motors"), SI.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MotorBend {
    /// Bend angle between the axes below and above the bend, rad (positive, at most
    /// [`MAX_BEND_ANGLE_RAD`]).
    pub angle_rad: f64,
    /// Distance from the bit face to the bend, m (on the motor component).
    pub to_bit_m: f64,
}

/// Largest bend angle accepted, rad (4 deg: adjustable housings go to about 3 deg).
pub const MAX_BEND_ANGLE_RAD: f64 = 4.0 * std::f64::consts::PI / 180.0;

impl Component {
    /// Distance from the bit face to the component's top, m.
    pub fn top_m(&self) -> f64 {
        self.bottom_m + self.length_m
    }
    /// Steel cross-section area, m2.
    pub fn area_m2(&self) -> f64 {
        PI / 4.0 * (self.body_od_m.powi(2) - self.id_m.powi(2))
    }
    /// Second moment of area, m4.
    pub fn inertia_m4(&self) -> f64 {
        PI / 64.0 * (self.body_od_m.powi(4) - self.id_m.powi(4))
    }
    /// Bending stress at the outer fibre of the body under bending moment `moment_nm` (N.m),
    /// `M (OD/2) / I`, Pa (0 for a section without inertia).
    pub fn bending_stress_pa(&self, moment_nm: f64) -> f64 {
        let i = self.inertia_m4();
        if i > 0.0 {
            moment_nm * self.body_od_m / 2.0 / i
        } else {
            0.0
        }
    }
    /// Axial stiffness EA, N.
    pub fn ea_n(&self) -> f64 {
        self.material.youngs_modulus_pa * self.area_m2()
    }
    /// Bending stiffness EI, N.m2.
    pub fn ei_nm2(&self) -> f64 {
        self.material.youngs_modulus_pa * self.inertia_m4()
    }
    /// Torsional stiffness GJ (J = 2I), N.m2.
    pub fn gj_nm2(&self) -> f64 {
        self.material.shear_modulus_pa * 2.0 * self.inertia_m4()
    }
    /// Buoyed weight per length for mud of `mud_density_kg_m3` inside and outside (docs/guide.md):
    /// `w_air (1 - rho_mud / rho_material)`, N/m.
    pub fn buoyed_weight_n_per_m(&self, mud_density_kg_m3: f64) -> f64 {
        self.weight_air_n_per_m * (1.0 - mud_density_kg_m3 / self.material.density_kg_m3)
    }
    /// Weight in air per length of the plain body, N/m.
    pub fn body_weight_n_per_m(&self) -> f64 {
        self.area_m2() * self.material.density_kg_m3 * G
    }
    /// Where the contact OD touches the wall along a blade or gauge: distances from the bit face
    /// of its lower and upper ends, m. A stabilizer's blades are centred on it; a bit's gauge
    /// starts at the face. None for the other kinds and for a bit without gauge.
    pub fn contact_zone_m(&self) -> Option<(f64, f64)> {
        match self.kind {
            ComponentKind::Stabilizer => {
                let mid = self.bottom_m + self.length_m / 2.0;
                let half = self.contact_length_m.min(self.length_m) / 2.0;
                Some((mid - half, mid + half))
            }
            ComponentKind::Bit if self.contact_length_m > 0.0 => {
                Some((self.bottom_m, self.bottom_m + self.contact_length_m.min(self.length_m)))
            }
            _ => None,
        }
    }
    /// True for components meshed as part of the stiff bottom-hole assembly (not pipe/HWDP).
    pub fn is_bha(&self) -> bool {
        !matches!(self.kind, ComponentKind::Pipe | ComponentKind::Hwdp)
    }
}
