//! Units shown to the user (reports and the readable summaries on stdout): SI or oilfield.
//! Values stay SI inside; these are the conversions at the edge, and the one place that formats
//! a number for a reader ([`fixed`], [`signed`]: never "-0.0"). CSV and JSON files keep the
//! interface's SI names.

/// Unit system for what is shown to the user.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, clap::ValueEnum)]
pub enum UnitSystem {
    /// m, mm, kN, kN.m, MPa, kg/m3, deg/30 m.
    #[default]
    Si,
    /// ft, in, klbf, ft.lbf, ksi, ppg, deg/100 ft.
    Oilfield,
}

/// `x` with `decimals` decimals for a reader: a value that rounds to zero is shown without a
/// sign ("0.0", never "-0.0"); NaN or infinity is shown as "n/a".
pub fn fixed(x: f64, decimals: usize) -> String {
    if !x.is_finite() {
        return "n/a".into();
    }
    let s = format!("{x:.decimals$}");
    match s.strip_prefix('-') {
        Some(rest) if rest.chars().all(|c| c == '0' || c == '.') => rest.to_string(),
        _ => s,
    }
}

/// Like [`fixed`] with an explicit sign: "+1.25", "-0.50"; a value that rounds to zero is "+0.00".
pub fn signed(x: f64, decimals: usize) -> String {
    let s = fixed(x, decimals);
    if s.starts_with('-') || s == "n/a" {
        s
    } else {
        format!("+{s}")
    }
}

/// One display unit: label, the factor from SI (shown = SI value / `si_per_unit`) and the
/// decimals it needs beyond those of the SI unit for the same resolution.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DisplayUnit {
    /// Label, e.g. "kN".
    pub label: &'static str,
    /// SI value of one shown unit (e.g. 1000 for kN, 0.3048 for ft).
    pub si_per_unit: f64,
    /// Decimals to add to those asked for the SI unit (negative: fewer), e.g. +2 for inches
    /// against millimetres, -2 for ft.lbf against kN.m.
    pub extra_decimals: i32,
}

impl DisplayUnit {
    /// The unit `label` with its SI factor from the crate's one unit table ([`crate::units`]).
    fn new(label: &'static str, extra_decimals: i32) -> DisplayUnit {
        let unit = crate::units::lookup(label)
            .unwrap_or_else(|| panic!("internal: display unit `{label}` missing from the unit table"));
        DisplayUnit {
            label,
            si_per_unit: unit.to_si,
            extra_decimals,
        }
    }
    /// Convert an SI value to this unit.
    pub fn show(&self, si: f64) -> f64 {
        si / self.si_per_unit
    }
    /// Decimals shown in this unit for `decimals` asked in the SI unit.
    pub fn decimals(&self, decimals: usize) -> usize {
        (decimals as i32 + self.extra_decimals).max(0) as usize
    }
    /// The number alone (no label): an SI value in this unit, `decimals` as for the SI unit.
    pub fn num(&self, si: f64, decimals: usize) -> String {
        fixed(self.show(si), self.decimals(decimals))
    }
    /// An SI value in this unit followed by the label, `decimals` as for the SI unit.
    pub fn fmt(&self, si: f64, decimals: usize) -> String {
        format!("{} {}", self.num(si, decimals), self.label)
    }
    /// Like [`DisplayUnit::fmt`] with an explicit sign.
    pub fn fmt_signed(&self, si: f64, decimals: usize) -> String {
        format!("{} {}", signed(self.show(si), self.decimals(decimals)), self.label)
    }
}

impl UnitSystem {
    /// Depths and long lengths (SI m).
    pub fn depth(self) -> DisplayUnit {
        match self {
            UnitSystem::Si => DisplayUnit::new("m", 0),
            UnitSystem::Oilfield => DisplayUnit::new("ft", 0),
        }
    }
    /// Diameters, displacements and clearances (SI m).
    pub fn small_length(self) -> DisplayUnit {
        match self {
            UnitSystem::Si => DisplayUnit::new("mm", 0),
            UnitSystem::Oilfield => DisplayUnit::new("in", 2),
        }
    }
    /// Forces (SI N).
    pub fn force(self) -> DisplayUnit {
        match self {
            UnitSystem::Si => DisplayUnit::new("kN", 0),
            UnitSystem::Oilfield => DisplayUnit::new("klbf", 0),
        }
    }
    /// Torques and bending moments (SI N.m).
    pub fn torque(self) -> DisplayUnit {
        match self {
            UnitSystem::Si => DisplayUnit::new("kN.m", 0),
            UnitSystem::Oilfield => DisplayUnit::new("ft.lbf", -2),
        }
    }
    /// Stresses (SI Pa).
    pub fn stress(self) -> DisplayUnit {
        match self {
            UnitSystem::Si => DisplayUnit::new("MPa", 0),
            UnitSystem::Oilfield => DisplayUnit::new("ksi", 1),
        }
    }
    /// Mud density (SI kg/m3).
    pub fn density(self) -> DisplayUnit {
        match self {
            UnitSystem::Si => DisplayUnit::new("kg/m3", 0),
            UnitSystem::Oilfield => DisplayUnit::new("ppg", 1),
        }
    }
    /// Curvature rates (SI rad/m), shown in deg per 30 m or deg per 100 ft.
    pub fn dogleg(self) -> DisplayUnit {
        match self {
            UnitSystem::Si => DisplayUnit::new("deg/30 m", 0),
            UnitSystem::Oilfield => DisplayUnit::new("deg/100 ft", 0),
        }
    }
    /// Angle changes or errors per length (SI rad/m), shown per 100 m or per 100 ft (the seed
    /// paper's error metric is per 100 m).
    pub fn per_100(self) -> DisplayUnit {
        match self {
            UnitSystem::Si => DisplayUnit::new("deg/100 m", 0),
            UnitSystem::Oilfield => DisplayUnit::new("deg/100 ft", 0),
        }
    }
    /// Speeds (SI m/s), shown per hour.
    pub fn rop(self) -> DisplayUnit {
        match self {
            UnitSystem::Si => DisplayUnit::new("m/h", 0),
            UnitSystem::Oilfield => DisplayUnit::new("ft/h", 0),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Reference: exact definitions (1 ft = 0.3048 m, 1 lbf = 4.4482216152605 N, 1 in = 25.4 mm);
    /// 1 ksi = 6.894757 MPa, 1 ppg = 119.826 kg/m3, 1 ft.lbf = 1.355818 N.m (rounded handbook values).
    #[test]
    fn oilfield_factors_match_handbook_values() {
        let o = UnitSystem::Oilfield;
        assert!((o.depth().show(304.8) - 1000.0).abs() < 1e-9);
        assert!((o.force().show(4448.2216152605) - 1.0).abs() < 1e-12);
        assert!((o.stress().si_per_unit / 6.894_757e6 - 1.0).abs() < 1e-6);
        assert!((o.density().si_per_unit / 119.826 - 1.0).abs() < 1e-5);
        assert!((o.torque().si_per_unit / 1.355_818 - 1.0).abs() < 1e-6);
        assert!((o.per_100().show(1f64.to_radians() / 30.48) - 1.0).abs() < 1e-12);
        assert!((o.small_length().show(0.2159) - 8.5).abs() < 1e-12);
        // 3 deg/100 ft = 2.9528 deg/30 m
        let rate = 3f64.to_radians() / 30.48;
        assert!((o.dogleg().show(rate) - 3.0).abs() < 1e-12);
        assert!((UnitSystem::Si.dogleg().show(rate) - 2.952_755_9).abs() < 1e-6);
    }

    /// Reference: the same resolution in both systems (0.01 kN.m = 7.4 ft.lbf, shown to 1 ft.lbf;
    /// 0.1 mm = 0.004 in, shown to 0.001 in) and no negative zero.
    #[test]
    fn decimals_follow_the_unit_and_zero_has_no_sign() {
        let (si, o) = (UnitSystem::Si, UnitSystem::Oilfield);
        assert_eq!(si.torque().fmt(12_345.0, 2), "12.35 kN.m");
        assert_eq!(o.torque().fmt(12_345.0, 2), "9105 ft.lbf");
        assert_eq!(o.small_length().fmt(0.2159, 1), "8.500 in");
        assert_eq!(si.force().fmt(-40.0, 1), "0.0 kN");
        assert_eq!(si.force().fmt(-60.0, 1), "-0.1 kN");
        assert_eq!(si.force().fmt_signed(-1e-9, 3), "+0.000 kN");
        assert_eq!(si.force().fmt_signed(1500.0, 3), "+1.500 kN");
        assert_eq!(fixed(-0.0, 0), "0");
        assert_eq!(fixed(-0.004, 2), "0.00");
        assert_eq!(fixed(-0.005_1, 2), "-0.01");
        assert_eq!(signed(-0.0, 1), "+0.0");
        assert_eq!(fixed(f64::NAN, 2), "n/a");
        assert_eq!(signed(f64::INFINITY, 2), "n/a");
    }
}
