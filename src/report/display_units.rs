//! Units shown to the user (reports and readable output): SI or oilfield. Values stay SI inside;
//! these are the conversions at the edge. CSV and JSON files keep the interface's SI names.

/// Unit system for what is shown to the user.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, clap::ValueEnum)]
pub enum UnitSystem {
    /// m, mm, kN, kN.m, MPa, kg/m3, deg/30 m.
    #[default]
    Si,
    /// ft, in, klbf, kft.lbf, ksi, ppg, deg/100 ft.
    Oilfield,
}

/// One display unit: label and the factor from SI (shown = SI value / `si_per_unit`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DisplayUnit {
    /// Label, e.g. "kN".
    pub label: &'static str,
    /// SI value of one shown unit (e.g. 1000 for kN, 0.3048 for ft).
    pub si_per_unit: f64,
}

impl DisplayUnit {
    /// Convert an SI value to this unit.
    pub fn show(&self, si: f64) -> f64 {
        si / self.si_per_unit
    }
    /// Format an SI value in this unit with `decimals`, followed by the label.
    pub fn fmt(&self, si: f64, decimals: usize) -> String {
        format!("{:.*} {}", decimals, self.show(si), self.label)
    }
}

const LBF_N: f64 = 4.448_221_615_260_5;
const FT_M: f64 = 0.3048;

impl UnitSystem {
    /// Depths and long lengths (SI m).
    pub fn depth(self) -> DisplayUnit {
        match self {
            UnitSystem::Si => DisplayUnit {
                label: "m",
                si_per_unit: 1.0,
            },
            UnitSystem::Oilfield => DisplayUnit {
                label: "ft",
                si_per_unit: FT_M,
            },
        }
    }
    /// Diameters, displacements and clearances (SI m).
    pub fn small_length(self) -> DisplayUnit {
        match self {
            UnitSystem::Si => DisplayUnit {
                label: "mm",
                si_per_unit: 1e-3,
            },
            UnitSystem::Oilfield => DisplayUnit {
                label: "in",
                si_per_unit: 0.0254,
            },
        }
    }
    /// Forces (SI N).
    pub fn force(self) -> DisplayUnit {
        match self {
            UnitSystem::Si => DisplayUnit {
                label: "kN",
                si_per_unit: 1e3,
            },
            UnitSystem::Oilfield => DisplayUnit {
                label: "klbf",
                si_per_unit: 1e3 * LBF_N,
            },
        }
    }
    /// Torques and bending moments (SI N.m).
    pub fn torque(self) -> DisplayUnit {
        match self {
            UnitSystem::Si => DisplayUnit {
                label: "kN.m",
                si_per_unit: 1e3,
            },
            UnitSystem::Oilfield => DisplayUnit {
                label: "kft.lbf",
                si_per_unit: 1e3 * LBF_N * FT_M,
            },
        }
    }
    /// Stresses (SI Pa).
    pub fn stress(self) -> DisplayUnit {
        match self {
            UnitSystem::Si => DisplayUnit {
                label: "MPa",
                si_per_unit: 1e6,
            },
            UnitSystem::Oilfield => DisplayUnit {
                label: "ksi",
                si_per_unit: 1e3 * LBF_N / (0.0254 * 0.0254),
            },
        }
    }
    /// Mud density (SI kg/m3).
    pub fn density(self) -> DisplayUnit {
        match self {
            UnitSystem::Si => DisplayUnit {
                label: "kg/m3",
                si_per_unit: 1.0,
            },
            // 1 lb/US gal = 0.45359237 kg / 3.785411784e-3 m3
            UnitSystem::Oilfield => DisplayUnit {
                label: "ppg",
                si_per_unit: 0.453_592_37 / 3.785_411_784e-3,
            },
        }
    }
    /// Curvature rates (SI rad/m), shown in deg per 30 m or deg per 100 ft.
    pub fn dogleg(self) -> DisplayUnit {
        match self {
            UnitSystem::Si => DisplayUnit {
                label: "deg/30 m",
                si_per_unit: 1f64.to_radians() / 30.0,
            },
            UnitSystem::Oilfield => DisplayUnit {
                label: "deg/100 ft",
                si_per_unit: 1f64.to_radians() / (100.0 * FT_M),
            },
        }
    }
    /// Speeds (SI m/s), shown per hour.
    pub fn rop(self) -> DisplayUnit {
        match self {
            UnitSystem::Si => DisplayUnit {
                label: "m/h",
                si_per_unit: 1.0 / 3600.0,
            },
            UnitSystem::Oilfield => DisplayUnit {
                label: "ft/h",
                si_per_unit: FT_M / 3600.0,
            },
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Reference: exact definitions (1 ft = 0.3048 m, 1 lbf = 4.4482216152605 N, 1 in = 25.4 mm);
    /// 1 ksi = 6.894757 MPa, 1 ppg = 119.826 kg/m3, 1 kft.lbf = 1.355818 kN.m (rounded handbook values).
    #[test]
    fn oilfield_factors_match_handbook_values() {
        let o = UnitSystem::Oilfield;
        assert!((o.depth().show(304.8) - 1000.0).abs() < 1e-9);
        assert!((o.force().show(4448.2216152605) - 1.0).abs() < 1e-12);
        assert!((o.stress().si_per_unit / 6.894_757e6 - 1.0).abs() < 1e-6);
        assert!((o.density().si_per_unit / 119.826 - 1.0).abs() < 1e-5);
        assert!((o.torque().si_per_unit / 1355.818 - 1.0).abs() < 1e-6);
        assert!((o.small_length().show(0.2159) - 8.5).abs() < 1e-12);
        // 3 deg/100 ft = 2.9528 deg/30 m
        let rate = 3f64.to_radians() / 30.48;
        assert!((o.dogleg().show(rate) - 3.0).abs() < 1e-12);
        assert!((UnitSystem::Si.dogleg().show(rate) - 2.952_755_9).abs() < 1e-6);
    }
}
