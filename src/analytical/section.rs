//! Tube section properties and buoyed weight (docs/theory.md 3.1, 2.2).
//!
//! References: elementary strength of materials for area and moments; Cowper (1966), "The
//! shear coefficient in Timoshenko's beam theory", J. Appl. Mech., for the hollow-circle shear
//! coefficient; Lubinski's effective-force/buoyancy argument for the buoyed weight.
//! Independent of the FEM's own section code (the constants are repeated here on purpose).

use super::{require_non_negative, require_positive, AnalyticalError};
use std::f64::consts::PI;

/// Standard gravity, m/s2 (docs/theory.md 1; repeated here so the references stand alone).
pub const STANDARD_GRAVITY: f64 = 9.80665;
/// Young's modulus of steel used in docs/theory.md, Pa.
pub const STEEL_YOUNG_MODULUS: f64 = 207.0e9;
/// Shear modulus of steel used in docs/theory.md, Pa.
pub const STEEL_SHEAR_MODULUS: f64 = 79.6e9;
/// Density of steel used in docs/theory.md, kg/m3.
pub const STEEL_DENSITY: f64 = 7850.0;

/// Poisson ratio from isotropic moduli, `nu = E/(2G) - 1` (dimensionless; steel of docs/theory.md
/// 2.1: 0.300).
pub fn poisson_ratio(young_modulus: f64, shear_modulus: f64) -> f64 {
    young_modulus / (2.0 * shear_modulus) - 1.0
}

/// Circular tube of outer diameter `od` and inner diameter `id` (m), `0 <= id < od`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Tube {
    /// Outer diameter D, m.
    pub od: f64,
    /// Inner diameter d, m (0 for a solid bar).
    pub id: f64,
}

impl Tube {
    /// Build a tube, checking `od > 0` and `0 <= id < od` (m).
    pub fn new(od: f64, id: f64) -> Result<Self, AnalyticalError> {
        require_positive("od", od)?;
        require_non_negative("id", id)?;
        if id >= od {
            return Err(AnalyticalError::InvalidInput(
                "id",
                format!("inner diameter {id} must be smaller than outer diameter {od}"),
            ));
        }
        Ok(Tube { od, id })
    }

    /// Steel cross-section area `A_s = pi (D^2 - d^2)/4`, m2 (docs/theory.md 3.1).
    pub fn area(&self) -> f64 {
        PI * (self.od * self.od - self.id * self.id) / 4.0
    }

    /// Bore area `A_i = pi d^2/4`, m2 (docs/theory.md 3.3).
    pub fn inner_area(&self) -> f64 {
        PI * self.id * self.id / 4.0
    }

    /// Area enclosed by the outer surface `A_o = pi D^2/4`, m2 (docs/theory.md 3.3).
    pub fn outer_area(&self) -> f64 {
        PI * self.od * self.od / 4.0
    }

    /// Second moment of area about a diameter `I = pi (D^4 - d^4)/64`, m4 (docs/theory.md 3.1).
    pub fn second_moment(&self) -> f64 {
        PI * (self.od.powi(4) - self.id.powi(4)) / 64.0
    }

    /// Polar moment (torsion constant of a circular tube) `J = 2I = pi (D^4 - d^4)/32`, m4.
    pub fn polar_moment(&self) -> f64 {
        PI * (self.od.powi(4) - self.id.powi(4)) / 32.0
    }

    /// Timoshenko shear coefficient of a hollow circle, Cowper (1966), with `m = d/D`:
    /// `k_s = 6(1+nu)(1+m^2)^2 / [(7+6nu)(1+m^2)^2 + (20+12nu) m^2]` (dimensionless;
    /// docs/theory.md 3.1). Limits: solid `6(1+nu)/(7+6nu)`, thin wall `2(1+nu)/(4+3nu)`.
    pub fn cowper_shear_coefficient(&self, poisson: f64) -> f64 {
        let m = self.id / self.od;
        let m2 = m * m;
        let a = (1.0 + m2) * (1.0 + m2);
        6.0 * (1.0 + poisson) * a / ((7.0 + 6.0 * poisson) * a + (20.0 + 12.0 * poisson) * m2)
    }

    /// Weight per length in air `w_air = rho_s g A_s`, N/m (steel density `rho_steel` kg/m3).
    pub fn air_weight(&self, rho_steel: f64) -> f64 {
        rho_steel * STANDARD_GRAVITY * self.area()
    }

    /// Buoyed weight per length with different mud densities inside and outside (docs/theory.md
    /// 2.2): `w_b = g (rho_s A_s + rho_i A_i - rho_o A_o)`, N/m, positive downward. Densities
    /// in kg/m3.
    pub fn buoyed_weight(&self, rho_steel: f64, rho_inside: f64, rho_outside: f64) -> f64 {
        buoyed_weight_two_densities(
            rho_steel,
            self.area(),
            rho_inside,
            self.inner_area(),
            rho_outside,
            self.outer_area(),
        )
    }
}

/// Buoyed weight per length in a single mud, `w_b = w_air (1 - rho_mud/rho_steel)`, N/m
/// (docs/theory.md 3.3). `w_air` N/m may be an adjusted weight including tool joints; densities in
/// kg/m3. Positive downward.
pub fn buoyed_weight_same_mud(w_air: f64, rho_mud: f64, rho_steel: f64) -> f64 {
    w_air * (1.0 - rho_mud / rho_steel)
}

/// Buoyed weight per length from areas and densities (docs/theory.md 3.3, Lubinski effective
/// force): `w_b = g (rho_s A_s + rho_i A_i - rho_o A_o)`, N/m, positive downward. Areas in m2
/// (steel, bore, outer), densities in kg/m3.
pub fn buoyed_weight_two_densities(
    rho_steel: f64,
    steel_area: f64,
    rho_inside: f64,
    inner_area: f64,
    rho_outside: f64,
    outer_area: f64,
) -> f64 {
    STANDARD_GRAVITY * (rho_steel * steel_area + rho_inside * inner_area - rho_outside * outer_area)
}

#[cfg(test)]
mod tests {
    use super::*;

    const INCH: f64 = 0.0254;

    /// Relative difference |a/b - 1|.
    fn rel(a: f64, b: f64) -> f64 {
        (a / b - 1.0).abs()
    }

    /// Round to `sig` significant digits, for "to its printed digits" comparisons.
    fn round_sig(x: f64, sig: i32) -> f64 {
        let e = x.abs().log10().floor() as i32;
        let k = sig - 1 - e;
        if k >= 0 {
            let s = 10f64.powi(k);
            (x * s).round() / s
        } else {
            let s = 10f64.powi(-k);
            (x / s).round() * s
        }
    }

    /// Reference: docs/theory.md 3.1 table (A_s, EI, GJ, EA, w_air, w_b, k_s), recomputed there from
    /// the formulas of 2.1-2.2 (Cowper 1966 for k_s). Tolerance: equality after rounding to
    /// the printed significant digits (5 for A_s..w_air except 4 for the 3-figure w_b/w_air of
    /// the pipe, 3 decimals for k_s).
    #[test]
    fn analytical_section_table_2_1() {
        let nu = poisson_ratio(STEEL_YOUNG_MODULUS, STEEL_SHEAR_MODULUS);
        assert!((nu - 0.3).abs() < 5e-4, "nu = {nu}");
        // (D, d, A_s, EI, GJ, EA, w_air, w_b, k_s)
        let rows = [
            (
                8.0, 2.8125, 2.8421e-2, 1.7059e7, 1.3120e7, 5.8832e9, 2187.9, 1853.5, 0.702,
            ),
            (
                6.5, 2.8125, 1.7400e-2, 7.2850e6, 5.6028e6, 3.6019e9, 1339.5, 1134.7, 0.654,
            ),
            (5.0, 4.276, 3.4030e-3, 1.2294e6, 9.4553e5, 7.0441e8, 262.0, 221.9, 0.536),
        ];
        for (d_o, d_i, a_s, ei, gj, ea, w_air, w_b, k_s) in rows {
            let t = Tube::new(d_o * INCH, d_i * INCH).unwrap();
            let e = STEEL_YOUNG_MODULUS;
            let g = STEEL_SHEAR_MODULUS;
            assert_eq!(round_sig(t.area(), 5), a_s, "A_s {d_o} in");
            assert_eq!(round_sig(e * t.second_moment(), 5), ei, "EI {d_o} in");
            assert_eq!(round_sig(g * t.polar_moment(), 5), gj, "GJ {d_o} in");
            assert_eq!(round_sig(e * t.area(), 5), ea, "EA {d_o} in");
            let wa = t.air_weight(STEEL_DENSITY);
            let wb = buoyed_weight_same_mud(wa, 1200.0, STEEL_DENSITY);
            let sig = if wa < 1000.0 { 4 } else { 5 };
            assert_eq!(round_sig(wa, sig), w_air, "w_air {d_o} in");
            assert_eq!(round_sig(wb, sig), w_b, "w_b {d_o} in");
            // Same mud inside and outside: two-density form must agree with the factor form.
            assert!(rel(t.buoyed_weight(STEEL_DENSITY, 1200.0, 1200.0), wb) < 1e-13);
            assert_eq!((t.cowper_shear_coefficient(nu) * 1000.0).round() / 1000.0, k_s);
            assert!(rel(t.polar_moment(), 2.0 * t.second_moment()) < 1e-15);
        }
        // Buoyancy factor quoted under the table: 1 - 1200/7850 = 0.84713.
        let bf = buoyed_weight_same_mud(1.0, 1200.0, STEEL_DENSITY);
        assert_eq!((bf * 1e5).round() / 1e5, 0.84713);
    }

    /// Reference: docs/theory.md 3.3 example, 8 in x 2-13/16 in collar, 1.2 sg inside, 1.25 sg
    /// outside: 1837.6 N/m (instead of 1853.5). Tolerance: 0.05 N/m (printed digits).
    #[test]
    fn analytical_section_two_density_example() {
        let t = Tube::new(8.0 * INCH, 2.8125 * INCH).unwrap();
        let wb = t.buoyed_weight(STEEL_DENSITY, 1200.0, 1250.0);
        assert!((wb - 1837.6).abs() < 0.05, "w_b = {wb}");
    }

    /// Reference: Cowper (1966) limits quoted in docs/theory.md 3.1: solid 6(1+nu)/(7+6nu), thin wall
    /// 2(1+nu)/(4+3nu). Tolerance 1e-12 / 1e-6 (thin-wall limit approached at m = 1 - 1e-7).
    #[test]
    fn analytical_section_cowper_limits() {
        let nu = 0.3;
        let solid = Tube::new(0.1, 0.0).unwrap();
        assert!((solid.cowper_shear_coefficient(nu) - 6.0 * 1.3 / (7.0 + 1.8)).abs() < 1e-12);
        let thin = Tube::new(0.1, 0.1 * (1.0 - 1e-7)).unwrap();
        assert!((thin.cowper_shear_coefficient(nu) - 2.6 / 4.9).abs() < 1e-6);
        assert!(Tube::new(0.1, 0.1).is_err());
        assert!(Tube::new(-0.1, 0.0).is_err());
    }
}
