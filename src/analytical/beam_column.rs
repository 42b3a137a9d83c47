//! Simply supported beam-column under uniform lateral load and axial force (docs/theory.md 10.3;
//! Timoshenko & Gere 1961, Theory of Elastic Stability, section 1.11).
//!
//! Span `l` m, pinned at both ends, uniform lateral load `q` N/m, axial force `p` N,
//! **compression positive** (tension negative). With `u = (l/2) sqrt(|P|/EI)`:
//! ```text
//! compression: delta_max = (5 q l^4 / 384 EI) * 12 (2 sec u - 2 - u^2) / (5 u^4)
//!              M_max     = (q l^2 / 8)        * 2 (sec u - 1) / u^2   = (q EI / P)(sec u - 1)
//! tension:     the same with sec -> sech and u^2 -> -u^2
//! approximate: amplification 1 / (1 - P/P_E), P_E = pi^2 EI / l^2
//! ```
//! Deflection and moment are at mid-span, in the direction of `q` (sagging positive).
//! Compression at or above `P_E` is rejected. Near `u = 0` the factors are evaluated from their
//! Taylor series in `s = P l^2 / (4 EI)` (Euler/secant numbers), avoiding cancellation.

use super::buckling::euler_pinned;
use super::{require_finite, require_positive, AnalyticalError};

/// Secant (Euler zigzag) numbers E_0..E_9: sec u = sum E_n u^(2n) / (2n)!.
const SECANT: [f64; 10] = [
    1.0,
    1.0,
    5.0,
    61.0,
    1385.0,
    50521.0,
    2702765.0,
    199360981.0,
    19391512145.0,
    2404879675441.0,
];

/// (2n)! for n = 0..9.
fn fact2(n: usize) -> f64 {
    (1..=2 * n).map(|k| k as f64).product()
}

/// Signed load parameter `s = P l^2 / (4 EI)` (`= u^2` in compression, `-u^2` in tension).
fn load_parameter(ei: f64, l: f64, p: f64) -> f64 {
    p * l * l / (4.0 * ei)
}

/// Deflection amplification factor `12 (2 sec u - 2 - u^2) / (5 u^4)` as a function of the
/// signed `s = P l^2/(4 EI)` (dimensionless; 1 at `s = 0`; tension branch with sech).
/// Valid for `s < (pi/2)^2`.
pub fn deflection_amplification(s: f64) -> f64 {
    if s.abs() < 0.0625 {
        // sum_k (24/5) E_{k+2} / (2k+4)! s^k
        (0..8)
            .rev()
            .fold(0.0, |acc, k| acc * s + 24.0 / 5.0 * SECANT[k + 2] / fact2(k + 2))
    } else if s > 0.0 {
        let u = s.sqrt();
        12.0 * (2.0 / u.cos() - 2.0 - s) / (5.0 * s * s)
    } else {
        let u = (-s).sqrt();
        12.0 * (2.0 / u.cosh() - 2.0 - s) / (5.0 * s * s)
    }
}

/// Moment amplification factor `2 (sec u - 1) / u^2` as a function of the signed
/// `s = P l^2/(4 EI)` (dimensionless; 1 at `s = 0`; tension: `2 (1 - sech u)/u^2`).
/// Valid for `s < (pi/2)^2`.
pub fn moment_amplification(s: f64) -> f64 {
    if s.abs() < 0.0625 {
        // sum_k 2 E_{k+1} / (2k+2)! s^k
        (0..9)
            .rev()
            .fold(0.0, |acc, k| acc * s + 2.0 * SECANT[k + 1] / fact2(k + 1))
    } else if s > 0.0 {
        2.0 * (1.0 / s.sqrt().cos() - 1.0) / s
    } else {
        2.0 * (1.0 / (-s).sqrt().cosh() - 1.0) / s
    }
}

/// Check inputs and return the signed load parameter `s`.
fn checked_parameter(ei: f64, l: f64, q: f64, p: f64) -> Result<f64, AnalyticalError> {
    require_positive("ei", ei)?;
    require_positive("l", l)?;
    require_finite("q", q)?;
    require_finite("p", p)?;
    let pe = euler_pinned(ei, l);
    if p >= pe {
        return Err(AnalyticalError::Buckled(format!(
            "compression {p} N >= Euler load {pe} N of the {l} m span"
        )));
    }
    Ok(load_parameter(ei, l, p))
}

/// Exact mid-span (maximum) deflection of the simply supported beam-column, m, in the
/// direction of `q` (Timoshenko & Gere 1961; docs/theory.md 10.3). `ei` N.m2, `l` m, `q` N/m,
/// `p` N compression positive (must be below `pi^2 EI/l^2`).
pub fn max_deflection(ei: f64, l: f64, q: f64, p: f64) -> Result<f64, AnalyticalError> {
    let s = checked_parameter(ei, l, q, p)?;
    Ok(5.0 * q * l.powi(4) / (384.0 * ei) * deflection_amplification(s))
}

/// Exact mid-span (maximum) bending moment of the simply supported beam-column, N.m, sagging
/// positive for `q > 0` (`(q EI / P)(sec u - 1)`; docs/theory.md 10.3). Inputs as
/// [`max_deflection`].
pub fn max_moment(ei: f64, l: f64, q: f64, p: f64) -> Result<f64, AnalyticalError> {
    let s = checked_parameter(ei, l, q, p)?;
    Ok(q * l * l / 8.0 * moment_amplification(s))
}

/// Approximate amplification `1 / (1 - P/P_E)`, `P_E = pi^2 EI/l^2` (dimensionless;
/// docs/theory.md 10.3). `p` N compression positive, below `P_E`.
pub fn approximate_amplification(ei: f64, l: f64, p: f64) -> Result<f64, AnalyticalError> {
    checked_parameter(ei, l, 0.0, p)?;
    Ok(1.0 / (1.0 - p / euler_pinned(ei, l)))
}

/// `sin(k a) sin(k b) / (k sin(k l))` in compression (`k = sqrt(P/EI)`), its `sinh` form in
/// tension, `a b / l` without axial force (the limit of both), m: the deflection at `a` per unit
/// kink of the simply supported beam-column (see [`hinge_rotation_deflection`]). Near `k l = 0`
/// the series `a b / l (1 + s_k a b / 3)` with `s_k = P/EI` (signed) is used.
fn kink_factor(ei: f64, l: f64, a: f64, p: f64) -> f64 {
    let b = l - a;
    let sk = p / ei;
    if (sk * l * l).abs() < 1e-6 {
        return a * b / l * (1.0 + sk * a * b / 3.0);
    }
    let k = sk.abs().sqrt();
    if p > 0.0 {
        (k * a).sin() * (k * b).sin() / (k * (k * l).sin())
    } else {
        (k * a).sinh() * (k * b).sinh() / (k * (k * l).sinh())
    }
}

/// Check a span `l`, a position `a` on it and an axial force `p` (below the Euler load).
fn checked_span(ei: f64, l: f64, a: f64, p: f64) -> Result<(), AnalyticalError> {
    require_positive("ei", ei)?;
    require_positive("l", l)?;
    require_finite("p", p)?;
    if !(a > 0.0 && a < l) {
        return Err(AnalyticalError::InvalidInput(
            "a",
            format!("{a} m is not inside the {l} m span"),
        ));
    }
    let pe = euler_pinned(ei, l);
    if p >= pe {
        return Err(AnalyticalError::Buckled(format!(
            "compression {p} N >= Euler load {pe} N of the {l} m span"
        )));
    }
    Ok(())
}

/// Deflection under a point load of the simply supported beam-column, m, in the direction of
/// the load: span `l` m, bending stiffness `ei` N.m2, lateral point load `f` N at `a` m from one
/// support, axial force `p` N (compression positive, below `pi^2 EI/l^2`; tension negative).
/// Compression (Timoshenko & Gere 1961, section 1.10): `y(a) = f [sin(k b) sin(k a) / (k sin(k l))
/// - a b / l] / P` with `k = sqrt(P/EI)`, `b = l - a`; tension: the same with `sinh` and the
/// opposite sign; `f a^2 b^2 / (3 EI l)` without axial force.
pub fn point_load_deflection(ei: f64, l: f64, f: f64, a: f64, p: f64) -> Result<f64, AnalyticalError> {
    checked_span(ei, l, a, p)?;
    require_finite("f", f)?;
    let b = l - a;
    if (p / ei * l * l).abs() < 1e-4 {
        // series in P: f a^2 b^2 / (3 EI l) (1 + P (a^2 + b^2 ... )): the first term is enough
        // to 1e-5 at |P l^2/EI| < 1e-4
        return Ok(f * a * a * b * b / (3.0 * ei * l));
    }
    Ok(f * (kink_factor(ei, l, a, p) - a * b / l) / p)
}

/// Deflection at the hinge of a simply supported beam-column whose unloaded axis kinks by
/// `theta` rad at `a` m from one support (an imposed relative rotation: the part beyond the
/// hinge turned by `theta` toward a side), m, away from that side: span `l` m, `ei` N.m2, axial
/// force `p` N (compression positive, below the Euler load). `y(a) = theta sin(k a) sin(k b) /
/// (k sin(k l))` in compression (`sinh` in tension), `theta a b / l` without axial force: the
/// two straight legs of a stress-free kinked beam on its supports, amplified by compression.
/// Derivation: `y'' + k^2 y = 0` on each side, `y` continuous at the hinge, the slope jumping by
/// `theta` there, zero at both supports.
pub fn hinge_rotation_deflection(ei: f64, l: f64, theta: f64, a: f64, p: f64) -> Result<f64, AnalyticalError> {
    checked_span(ei, l, a, p)?;
    require_finite("theta", theta)?;
    Ok(theta * kink_factor(ei, l, a, p))
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    /// EI of the 6.5 in x 2-13/16 in collar (docs/theory.md 3.1: 7.2850e6 N.m2), computed directly.
    fn ei_collar() -> f64 {
        207e9 * PI * ((6.5f64 * 0.0254).powi(4) - (2.8125f64 * 0.0254).powi(4)) / 64.0
    }

    fn round_to(x: f64, decimals: i32) -> f64 {
        let s = 10f64.powi(decimals);
        (x * s).round() / s
    }

    /// Reference: docs/theory.md 10.3 worked example (Timoshenko & Gere 1961): 6.5 in collar,
    /// l = 9 m, q = 388.1 N/m, P = 100 kN: u = 0.52723, delta0 = 4.5511 mm, factor 1.12740,
    /// delta_max = 5.1309 mm, M0 = 3929.5 N.m, M_max = 4442.6 N.m (x1.13057),
    /// 1/(1-P/P_E) = 1.12696. Tolerance: printed digits. Cross-check: the 16-element FE value
    /// quoted there, 5.13094 mm, within 1e-5 mm.
    #[test]
    fn analytical_beam_column_example_6_3() {
        let (ei, l, q, p) = (ei_collar(), 9.0, 388.1, 100e3);
        let s = load_parameter(ei, l, p);
        assert_eq!(round_to(s.sqrt(), 5), 0.52723);
        assert_eq!(round_to(5.0 * q * l.powi(4) / (384.0 * ei) * 1e3, 4), 4.5511);
        assert_eq!(round_to(deflection_amplification(s), 5), 1.12740);
        let d = max_deflection(ei, l, q, p).unwrap();
        assert_eq!(round_to(d * 1e3, 4), 5.1309);
        assert!((d * 1e3 - 5.13094).abs() < 1e-5, "{d}");
        assert_eq!(round_to(q * l * l / 8.0, 1), 3929.5);
        let m = max_moment(ei, l, q, p).unwrap();
        assert_eq!(round_to(m, 1), 4442.6);
        assert_eq!(round_to(moment_amplification(s), 5), 1.13057);
        // Closed form (q EI / P)(sec u - 1), 1e-13 relative.
        assert!((m / (q * ei / p * (1.0 / s.sqrt().cos() - 1.0)) - 1.0).abs() < 1e-13);
        assert_eq!(round_to(approximate_amplification(ei, l, p).unwrap(), 5), 1.12696);
    }

    /// Reference: continuity of the series and closed-form branches at |s| = 1/16 and the
    /// limits delta0 = 5ql^4/384EI, M0 = ql^2/8 at P = 0 (Timoshenko & Gere 1961). Tension
    /// branch: direct check of the sech form. Tolerance 1e-12 relative.
    #[test]
    fn analytical_beam_column_branches() {
        for s in [0.0625f64, -0.0625] {
            let (a, b) = (s * (1.0 - 1e-12), s * (1.0 + 1e-12));
            assert!((deflection_amplification(a) / deflection_amplification(b) - 1.0).abs() < 1e-12);
            assert!((moment_amplification(a) / moment_amplification(b) - 1.0).abs() < 1e-12);
        }
        assert_eq!(deflection_amplification(0.0), 1.0);
        assert_eq!(moment_amplification(0.0), 1.0);
        let (ei, l, q) = (ei_collar(), 9.0, 388.1);
        let d0 = max_deflection(ei, l, q, 0.0).unwrap();
        assert!((d0 / (5.0 * q * l.powi(4) / (384.0 * ei)) - 1.0).abs() < 1e-15);
        // Tension 100 kN: amplification below 1; sech closed form.
        let u = (l / 2.0) * (100e3 / ei).sqrt();
        let m = max_moment(ei, l, q, -100e3).unwrap();
        assert!((m / (q * ei / 100e3 * (1.0 - 1.0 / u.cosh())) - 1.0).abs() < 1e-12);
        assert!(m < q * l * l / 8.0);
        assert!(max_deflection(ei, l, q, euler_pinned(ei, l)).is_err());
    }

    /// The point load and the hinge: the static limits by hand (a 10 m span, load 4 m from a
    /// support: `f a^2 b^2/(3 EI l)` = 1 kN x 16 x 36 / (3 x 1e6 x 10) = 19.2 mm; hinge
    /// `theta a b / l` = 0.01 x 24 / 10 = 24 mm), continuous through zero axial force (within
    /// 1e-3 at +-100 N for the load, 1e-5 at +-1 N for the hinge: the axial force's own effect
    /// is 3e-4 and 8e-6 there), and the compression amplification near the first-mode estimate
    /// `1 / (1 - P/P_E)` at a load near mid-span (within 2% at P = P_E / 2).
    #[test]
    fn point_load_and_hinge_deflections() {
        let (ei, l, a) = (1e6, 10.0, 4.0);
        let y0 = point_load_deflection(ei, l, 1e3, a, 0.0).unwrap();
        assert!((y0 - 0.0192).abs() < 1e-12);
        let h0 = hinge_rotation_deflection(ei, l, 0.01, a, 0.0).unwrap();
        assert!((h0 - 0.024).abs() < 1e-12);
        for p in [-1.0, 1.0] {
            let y = point_load_deflection(ei, l, 1e3, a, p * 1e2).unwrap();
            assert!(((y - y0) / y0).abs() < 1e-3, "{y} {y0}");
            let h = hinge_rotation_deflection(ei, l, 0.01, a, p).unwrap();
            assert!(((h - h0) / h0).abs() < 1e-5);
        }
        let pe = euler_pinned(ei, l);
        let ym = point_load_deflection(ei, l, 1e3, 5.0, pe / 2.0).unwrap()
            / point_load_deflection(ei, l, 1e3, 5.0, 0.0).unwrap();
        assert!((ym - 2.0).abs() < 0.04, "{ym}");
        let yt = point_load_deflection(ei, l, 1e3, a, -pe).unwrap();
        assert!(yt > 0.0 && yt < y0);
        assert!(point_load_deflection(ei, l, 1e3, 11.0, 0.0).is_err());
        assert!(hinge_rotation_deflection(ei, l, 0.01, a, 1.01 * pe).is_err());
    }
}
