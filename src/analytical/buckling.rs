//! Buckling loads of a pipe in a straight hole (docs/theory.md 5.3 and 6.4).
//!
//! All forces here are **effective compressive** axial forces, N (compression positive; the
//! crate's `F_eff` is tension positive, so compare with `-F_eff`). Inclined-hole criteria use
//! the lateral weight `q = w_b sin I` (`w_b` buoyed weight per length N/m, `I` inclination rad
//! from vertical) and the radial clearance `r` m between pipe and hole.
//!
//! References: Euler (pinned-pinned column, Timoshenko & Gere 1961); Dawson & Paslay (1984),
//! "Drillpipe buckling in inclined holes", JPT, after Paslay & Bogy (1964); Chen, Lin &
//! Cheatham (1990), "Tubing and casing buckling in horizontal wells", JPT; Wu & Juvkam-Wold
//! (1993, helical buckling in horizontal and extended-reach wells; bibliographic details
//! uncertain); Lubinski (1950) for vertical holes; Lubinski, Althouse & Logan (1962) and
//! Mitchell (1986) for the helix contact force and pitch.

use super::{require_non_negative, require_positive, AnalyticalError};
use std::f64::consts::{PI, SQRT_2};

/// Euler load of a pinned-pinned column `P_E = pi^2 EI / l^2`, N (compression), for bending
/// stiffness `ei` N.m2 and span `l` m (docs/theory.md 5.3, 6.3).
pub fn euler_pinned(ei: f64, l: f64) -> f64 {
    PI * PI * ei / (l * l)
}

/// `sqrt(EI q / r)` with `q = w_b sin I`, N: the common scale of the inclined-hole criteria.
fn inclined_scale(ei: f64, w_b: f64, inclination: f64, r: f64) -> Result<f64, AnalyticalError> {
    require_positive("ei", ei)?;
    require_positive("w_b", w_b)?;
    require_positive("r", r)?;
    let q = w_b * inclination.sin();
    if q.is_nan() || q <= 0.0 {
        return Err(AnalyticalError::InvalidInput(
            "inclination",
            format!(
                "needs 0 < I < pi so that w_b sin I > 0 (got I = {inclination} rad); \
                 use the vertical-hole coefficients instead"
            ),
        ));
    }
    Ok((ei * q / r).sqrt())
}

/// Sinusoidal (lateral) buckling load in an inclined hole, Dawson & Paslay (1984):
/// `F_s = 2 sqrt(EI w_b sin I / r)`, N compression (docs/theory.md 7.1). Inputs: `ei` N.m2, `w_b`
/// N/m (> 0), `inclination` rad in (0, pi), `r` radial clearance m (> 0).
pub fn sinusoidal_dawson_paslay(ei: f64, w_b: f64, inclination: f64, r: f64) -> Result<f64, AnalyticalError> {
    Ok(2.0 * inclined_scale(ei, w_b, inclination, r)?)
}

/// Wavelength of the critical sinusoidal mode, `2 pi (EI r / q)^(1/4)` with `q = w_b sin I`, m
/// (from `k^4 = q/(r EI)`, docs/theory.md 7.1). Inputs as [`sinusoidal_dawson_paslay`].
pub fn sinusoidal_wavelength(ei: f64, w_b: f64, inclination: f64, r: f64) -> Result<f64, AnalyticalError> {
    let s = inclined_scale(ei, w_b, inclination, r)?; // sqrt(EI q / r)
                                                      // (EI r / q)^(1/4) = sqrt(EI / s)
    Ok(2.0 * PI * (ei / s).sqrt())
}

/// Helical buckling load, Chen, Lin & Cheatham (1990) (derived for horizontal holes, used with
/// `sin I`): `F_h = 2 sqrt(2) sqrt(EI w_b sin I / r)`, N compression (docs/theory.md 7.1).
pub fn helical_chen_lin_cheatham(ei: f64, w_b: f64, inclination: f64, r: f64) -> Result<f64, AnalyticalError> {
    Ok(2.0 * SQRT_2 * inclined_scale(ei, w_b, inclination, r)?)
}

/// Helical buckling load, Wu & Juvkam-Wold (1993):
/// `F_h = 2 (2 sqrt(2) - 1) sqrt(EI w_b sin I / r)`, N compression (docs/theory.md 7.1).
pub fn helical_wu_juvkam_wold(ei: f64, w_b: f64, inclination: f64, r: f64) -> Result<f64, AnalyticalError> {
    Ok(2.0 * (2.0 * SQRT_2 - 1.0) * inclined_scale(ei, w_b, inclination, r)?)
}

/// Force unit of vertical-hole buckling `(EI w_b^2)^(1/3)`, N, for bending stiffness `ei` N.m2
/// and buoyed weight `w_b` N/m (Lubinski 1950; Wu et al.).
pub fn vertical_force_unit(ei: f64, w_b: f64) -> f64 {
    (ei * w_b * w_b).powf(1.0 / 3.0)
}

/// Vertical hole, Lubinski (1950) first-order buckling: `1.94 (EI w_b^2)^(1/3)` (dimensionless
/// coefficient). **\[uncertain\]** commonly quoted value (docs/theory.md 7.1, 10), to confirm against
/// the original before a test relies on it.
pub const LUBINSKI_VERTICAL_FIRST: f64 = 1.94;

/// Vertical hole, sinusoidal buckling after Wu et al.: `2.55 (EI w_b^2)^(1/3)` (dimensionless
/// coefficient). **\[uncertain\]** commonly quoted value (docs/theory.md, buckling).
pub const WU_VERTICAL_SINUSOIDAL: f64 = 2.55;

/// Vertical hole, helical buckling after Wu et al.: `5.55 (EI w_b^2)^(1/3)` (dimensionless
/// coefficient). **\[uncertain\]** commonly quoted value (docs/theory.md, buckling).
pub const WU_VERTICAL_HELICAL: f64 = 5.55;

/// Wall contact force per length of a weightless helically buckled pipe,
/// `w_c = r F^2 / (4 EI)`, N/m (Lubinski, Althouse & Logan 1962; Mitchell 1986; docs/theory.md 7.1).
/// `r` radial clearance m, `f` effective compression N (>= 0), `ei` N.m2.
pub fn helical_contact_force(ei: f64, r: f64, f: f64) -> Result<f64, AnalyticalError> {
    require_positive("ei", ei)?;
    require_non_negative("r", r)?;
    require_non_negative("f", f)?;
    Ok(r * f * f / (4.0 * ei))
}

/// Pitch of the helix of a weightless buckled pipe, `pi sqrt(8 EI / F)`, m (Lubinski et al.
/// 1962; docs/theory.md 7.1). `ei` N.m2, `f` effective compression N (> 0).
pub fn helical_pitch(ei: f64, f: f64) -> Result<f64, AnalyticalError> {
    require_positive("ei", ei)?;
    require_positive("f", f)?;
    Ok(PI * (8.0 * ei / f).sqrt())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// 5 in pipe of docs/theory.md 7.1: EI = 1.2294e6 N.m2, w_b = 240.9 N/m, r = 44.45 mm.
    const EI: f64 = 1.2294e6;
    const W_B: f64 = 240.9;
    const R: f64 = 0.04445;

    fn kn1(x: f64) -> f64 {
        (x / 100.0).round() / 10.0
    }

    /// Reference: docs/theory.md 7.1 example (Dawson & Paslay 1984; Chen, Lin & Cheatham 1990; Wu &
    /// Juvkam-Wold 1993): I = 45 deg: 137.3 / 194.2 / 251.0 kN, I = 90 deg: 163.3 / 230.9 /
    /// 298.5 kN. Tolerance: equality after rounding to 0.1 kN (printed digits). The CLC value at
    /// 45 deg with the printed inputs (EI = 1.2294e6, w_b = 240.9) is 194.141 kN, i.e. 194.1;
    /// the notes' 194.2 comes from the unrounded inputs (EI = 1.22943e6, w_b = 240.919:
    /// 194.1507 kN) rounded up (docs/theory.md, "Corrections to the early notes"), so 194.1 is
    /// asserted. Also checks the inputs: 29.0 kg/m in 1.2 sg mud -> 240.9 N/m and r = (8.5 - 5)/2 in.
    #[test]
    fn analytical_buckling_inclined_example_6_4() {
        let w: f64 = 29.0 * 9.80665 * (1.0 - 1200.0 / 7850.0);
        assert_eq!((w * 10.0).round() / 10.0, W_B);
        assert!(((8.5 - 5.0) * 0.0254 / 2.0 - R).abs() < 1e-15);
        for (deg, fs, fclc, fwjw) in [(45.0, 137.3, 194.1, 251.0), (90.0, 163.3, 230.9, 298.5)] {
            let i = f64::to_radians(deg);
            assert_eq!(kn1(sinusoidal_dawson_paslay(EI, W_B, i, R).unwrap()), fs);
            assert_eq!(kn1(helical_chen_lin_cheatham(EI, W_B, i, R).unwrap()), fclc);
            assert_eq!(kn1(helical_wu_juvkam_wold(EI, W_B, i, R).unwrap()), fwjw);
        }
        assert!(sinusoidal_dawson_paslay(EI, W_B, 0.0, R).is_err());
    }

    /// Reference: docs/theory.md 7.1 vertical example: (EI w_b^2)^(1/3) = 4.148 kN (3 decimals) and
    /// 8.05 / 10.58 / 23.02 kN with the \[uncertain\] coefficients 1.94 / 2.55 / 5.55 (Lubinski
    /// 1950; Wu et al.). Tolerance: printed digits. Only the arithmetic is verified here, not
    /// the coefficients themselves.
    #[test]
    fn analytical_buckling_vertical_unit_6_4() {
        let u = vertical_force_unit(EI, W_B);
        assert_eq!((u).round() / 1000.0, 4.148);
        let kn2 = |c: f64| (c * u / 10.0).round() / 100.0;
        assert_eq!(kn2(LUBINSKI_VERTICAL_FIRST), 8.05);
        assert_eq!(kn2(WU_VERTICAL_SINUSOIDAL), 10.58);
        assert_eq!(kn2(WU_VERTICAL_HELICAL), 23.02);
    }

    /// Reference: docs/theory.md 7.1 derivation: F(k) = EI k^2 + q/(r k^2) is minimal at
    /// k^4 = q/(r EI) with value F_s, and the wavelength is 2 pi / k. Tolerance 1e-12 relative
    /// (and F(k) >= F_s on a grid).
    #[test]
    fn analytical_buckling_sinusoidal_minimum() {
        let i = 60f64.to_radians();
        let q = W_B * i.sin();
        let fs = sinusoidal_dawson_paslay(EI, W_B, i, R).unwrap();
        let lam = sinusoidal_wavelength(EI, W_B, i, R).unwrap();
        let k = 2.0 * PI / lam;
        let f = |k: f64| EI * k * k + q / (R * k * k);
        assert!((f(k) / fs - 1.0).abs() < 1e-12);
        assert!((k.powi(4) * R * EI / q - 1.0).abs() < 1e-12);
        for j in 1..200 {
            let kk = k * (0.5 + j as f64 / 200.0);
            assert!(f(kk) >= fs * (1.0 - 1e-14));
        }
    }

    /// Reference: docs/theory.md 5.3, pinned-pinned 9 m 6.5 in collar (EI = 7.2850e6 N.m2 from
    /// 2.1): pi^2 EI / l^2 = 887.66 kN (printed digits, 0.01 kN); helix formulas of 6.4
    /// (Lubinski et al. 1962) checked against the helix geometry: a helix of radius r and
    /// pitch p has curvature kappa = r b^2/(r^2 b^2 + 1), b = 2 pi/p, and for r b << 1 the
    /// contact force is EI r b^4 ~ r F^2 / (4EI) with b^2 = F/(2EI). Tolerance 1e-12 relative.
    #[test]
    fn analytical_buckling_euler_and_helix() {
        let e_i = 207e9 * PI * ((6.5f64 * 0.0254).powi(4) - (2.8125f64 * 0.0254).powi(4)) / 64.0;
        assert_eq!((euler_pinned(e_i, 9.0) / 10.0).round() / 100.0, 887.66);
        let f = 200e3;
        let p = helical_pitch(EI, f).unwrap();
        let b = 2.0 * PI / p;
        assert!((b * b * 2.0 * EI / f - 1.0).abs() < 1e-12);
        let wc = helical_contact_force(EI, R, f).unwrap();
        assert!((wc / (EI * R * b.powi(4)) - 1.0).abs() < 1e-12);
        assert!(helical_pitch(EI, 0.0).is_err());
    }
}
