//! Closed-form and quasi-closed-form references for verifying the models (docs/theory.md 3,
//! 9.2, 10.3 and 7.1).
//!
//! Everything here is written independently of the production mechanics ([`crate::models`],
//! [`crate::string`], [`crate::geometry`]): each formula from its source, no code, constant or
//! helper shared, so that agreement between the two is evidence, not tautology. The module
//! only depends on `std`.
//!
//! Units are SI throughout (m, N, N.m, Pa, kg/m3, rad). Axial forces in this module are
//! **compression positive** (`P`, WOB, `F` in the buckling formulas), as in the classical
//! references; the rest of the crate uses effective tension positive, so `P = -F_eff`.
//!
//! - [`section`]: tube properties, buoyed weight (docs/theory.md 3.1, 2.2).
//! - [`pendulum`]: Lubinski pendulum BHA, constant and linearly varying compression (6.2).
//! - [`beam_column`]: simply supported beam-column under uniform load (6.3).
//! - [`buckling`]: Euler, sinusoidal and helical buckling loads in inclined holes (6.4).
//! - [`contact_beam`]: planar beam-column with unilateral wall contact at every point, for
//!   stabilizer blades and bit gauges touching along their length (3.4).

pub mod beam_column;
pub mod buckling;
pub mod contact_beam;
pub mod pendulum;
pub mod section;

use std::fmt;

/// Why a closed-form reference could not be evaluated.
#[derive(Debug, Clone, PartialEq)]
pub enum AnalyticalError {
    /// An input is out of its physical range (name of the input, explanation).
    InvalidInput(&'static str, String),
    /// The compressive load reaches or exceeds a buckling load where the formula breaks down.
    Buckled(String),
    /// An iterative solve (root finding, shooting) did not converge.
    NoConvergence(String),
}

impl fmt::Display for AnalyticalError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            AnalyticalError::InvalidInput(name, why) => write!(f, "invalid input `{name}`: {why}"),
            AnalyticalError::Buckled(why) => write!(f, "beyond buckling: {why}"),
            AnalyticalError::NoConvergence(why) => write!(f, "no convergence: {why}"),
        }
    }
}

impl std::error::Error for AnalyticalError {}

/// Check that `value` is finite and strictly positive.
pub(crate) fn require_positive(name: &'static str, value: f64) -> Result<(), AnalyticalError> {
    if value.is_finite() && value > 0.0 {
        Ok(())
    } else {
        Err(AnalyticalError::InvalidInput(
            name,
            format!("must be finite and > 0, got {value}"),
        ))
    }
}

/// Check that `value` is finite and non-negative.
pub(crate) fn require_non_negative(name: &'static str, value: f64) -> Result<(), AnalyticalError> {
    if value.is_finite() && value >= 0.0 {
        Ok(())
    } else {
        Err(AnalyticalError::InvalidInput(
            name,
            format!("must be finite and >= 0, got {value}"),
        ))
    }
}

/// Check that `value` is finite.
pub(crate) fn require_finite(name: &'static str, value: f64) -> Result<(), AnalyticalError> {
    if value.is_finite() {
        Ok(())
    } else {
        Err(AnalyticalError::InvalidInput(
            name,
            format!("must be finite, got {value}"),
        ))
    }
}

/// Brent's root finder (Brent 1973, as in Numerical Recipes `zbrent`) on `[a, b]` where `f(a)`
/// and `f(b)` have opposite signs (or one is zero). Converges to an absolute tolerance
/// `2 eps |x| + tol/2`. Private to the analytical references.
pub(crate) fn brent<F: FnMut(f64) -> f64>(
    mut f: F,
    a: f64,
    b: f64,
    tol: f64,
    max_iter: usize,
) -> Result<f64, AnalyticalError> {
    let (mut a, mut b) = (a, b);
    let (mut fa, mut fb) = (f(a), f(b));
    if fa == 0.0 {
        return Ok(a);
    }
    if fb == 0.0 {
        return Ok(b);
    }
    if !(fa.is_finite() && fb.is_finite()) || fa.signum() == fb.signum() {
        return Err(AnalyticalError::NoConvergence(format!(
            "root not bracketed on [{a}, {b}]: f = {fa}, {fb}"
        )));
    }
    let (mut c, mut fc) = (b, fb);
    let (mut d, mut e) = (b - a, b - a);
    for _ in 0..max_iter {
        if (fb > 0.0 && fc > 0.0) || (fb < 0.0 && fc < 0.0) {
            c = a;
            fc = fa;
            d = b - a;
            e = d;
        }
        if fc.abs() < fb.abs() {
            a = b;
            b = c;
            c = a;
            fa = fb;
            fb = fc;
            fc = fa;
        }
        let tol1 = 2.0 * f64::EPSILON * b.abs() + 0.5 * tol;
        let xm = 0.5 * (c - b);
        if xm.abs() <= tol1 || fb == 0.0 {
            return Ok(b);
        }
        if e.abs() >= tol1 && fa.abs() > fb.abs() {
            let s = fb / fa;
            let (mut p, mut q);
            if a == c {
                p = 2.0 * xm * s;
                q = 1.0 - s;
            } else {
                let qq = fa / fc;
                let r = fb / fc;
                p = s * (2.0 * xm * qq * (qq - r) - (b - a) * (r - 1.0));
                q = (qq - 1.0) * (r - 1.0) * (s - 1.0);
            }
            if p > 0.0 {
                q = -q;
            }
            p = p.abs();
            let min1 = 3.0 * xm * q - (tol1 * q).abs();
            let min2 = (e * q).abs();
            if 2.0 * p < min1.min(min2) {
                e = d;
                d = p / q;
            } else {
                d = xm;
                e = d;
            }
        } else {
            d = xm;
            e = d;
        }
        a = b;
        fa = fb;
        if d.abs() > tol1 {
            b += d;
        } else {
            b += tol1.copysign(xm);
        }
        fb = f(b);
    }
    Err(AnalyticalError::NoConvergence(format!(
        "Brent: {max_iter} iterations, x = {b}"
    )))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Brent on a cubic with a known root (sqrt 2 of x^2 - 2), tolerance 1e-14.
    #[test]
    fn analytical_brent_finds_sqrt2() {
        let x = brent(|x| x * x - 2.0, 0.0, 2.0, 1e-15, 200).unwrap();
        assert!((x - 2f64.sqrt()).abs() < 1e-14);
        assert!(brent(|x| x * x + 1.0, 0.0, 2.0, 1e-15, 200).is_err());
    }
}
