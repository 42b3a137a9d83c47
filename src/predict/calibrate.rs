//! Calibration of the bit-rock law's parameters on a back-analysis (physics.md 7.7):
//! Levenberg-Marquardt on the per-100 m interval errors, finite-difference Jacobian (one
//! re-prediction of all intervals per parameter), bounds by reparametrization, a weak prior
//! toward the starting values, covariance `s^2 (J^T J)^-1` with `s^2 = SSR / (m - n)`.

use super::intervals::{run_intervals, Interval, IntervalResult};
use super::march::{MarchSettings, PredictError, WarmStart};
use crate::case::{BitRock, Case};
use nalgebra::{DMatrix, DVector};

/// A law parameter that calibration may fit.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FitParameter {
    /// beta_b in (0, 1], through `beta = 1e-3 + (1 - 1e-3) logistic(u)`.
    LateralDrillability,
    /// chi_w, rad, unbounded.
    WalkAngle,
    /// I_r in (-0.5, 0.5), through `I_r = 0.5 tanh(u)` (the `[bit_rock]` default and every
    /// formation interval take the same value).
    RockAnisotropy,
}

impl FitParameter {
    /// Name as in `[bit_rock]`.
    pub fn name(self) -> &'static str {
        match self {
            FitParameter::LateralDrillability => "lateral_drillability",
            FitParameter::WalkAngle => "walk_angle",
            FitParameter::RockAnisotropy => "rock_anisotropy",
        }
    }
    /// Parse a name of `[bit_rock]`.
    pub fn parse(s: &str) -> Option<FitParameter> {
        Some(match s {
            "lateral_drillability" => FitParameter::LateralDrillability,
            "walk_angle" => FitParameter::WalkAngle,
            "rock_anisotropy" => FitParameter::RockAnisotropy,
            _ => return None,
        })
    }
    /// Accepted names, for messages.
    pub const NAMES: &'static str = "lateral_drillability, walk_angle, rock_anisotropy";
    fn value(self, br: &BitRock) -> f64 {
        match self {
            FitParameter::LateralDrillability => br.lateral_drillability,
            FitParameter::WalkAngle => br.walk_angle_rad,
            FitParameter::RockAnisotropy => br.rock_anisotropy,
        }
    }
    fn set(self, br: &mut BitRock, v: f64) {
        match self {
            FitParameter::LateralDrillability => br.lateral_drillability = v,
            FitParameter::WalkAngle => br.walk_angle_rad = v,
            FitParameter::RockAnisotropy => {
                br.rock_anisotropy = v;
                for f in &mut br.formations {
                    f.rock_anisotropy = v;
                }
            }
        }
    }
    /// Natural value of the unbounded variable `u`.
    fn natural(self, u: f64) -> f64 {
        match self {
            FitParameter::LateralDrillability => BETA_MIN + (1.0 - BETA_MIN) / (1.0 + (-u).exp()),
            FitParameter::WalkAngle => u,
            FitParameter::RockAnisotropy => 0.5 * u.tanh(),
        }
    }
    /// Unbounded variable of a natural value (clamped inside the bounds).
    fn unbounded(self, v: f64) -> f64 {
        match self {
            FitParameter::LateralDrillability => {
                // started at most at BETA_START_MAX: the logistic is flat near 1
                let x = ((v.min(BETA_START_MAX) - BETA_MIN) / (1.0 - BETA_MIN)).clamp(1e-4, 1.0 - 1e-4);
                (x / (1.0 - x)).ln()
            }
            FitParameter::WalkAngle => v,
            FitParameter::RockAnisotropy => (2.0 * v).clamp(-0.9999, 0.9999).atanh(),
        }
    }
    /// d(natural)/du at `u`.
    fn slope(self, u: f64) -> f64 {
        match self {
            FitParameter::LateralDrillability => {
                let l = 1.0 / (1.0 + (-u).exp());
                (1.0 - BETA_MIN) * l * (1.0 - l)
            }
            FitParameter::WalkAngle => 1.0,
            FitParameter::RockAnisotropy => 0.5 * (1.0 - u.tanh().powi(2)),
        }
    }
    /// Standard deviation above which a fitted value is reported as not identifiable (natural
    /// units; about the parameter's useful range).
    pub fn identifiable_below(self) -> f64 {
        match self {
            FitParameter::LateralDrillability => 0.5,
            FitParameter::WalkAngle => 0.35,
            FitParameter::RockAnisotropy => 0.25,
        }
    }
    /// Prior standard deviation of the weak prior toward the start value (natural units).
    fn prior_sigma(self) -> f64 {
        match self {
            FitParameter::LateralDrillability => 2.0,
            FitParameter::WalkAngle => 1.0,
            FitParameter::RockAnisotropy => 1.0,
        }
    }
}

/// Smallest lateral drillability calibration may reach.
pub const BETA_MIN: f64 = 1e-3;

/// Largest starting lateral drillability (the reparametrization is flat at 1, where a fit
/// started there could not move).
pub const BETA_START_MAX: f64 = 0.9;

/// Levenberg-Marquardt iterations allowed.
pub const MAX_LM_ITERATIONS: usize = 20;

/// Damping increases tried per iteration before giving up.
pub const MAX_LAMBDA_INCREASES: usize = 6;

/// Largest change of an unbounded variable per iteration (trust region).
pub const MAX_STEP_U: f64 = 1.5;

/// Relative decrease of the sum of squares below which the fit stops.
pub const SSR_RELATIVE_TOLERANCE: f64 = 1e-4;

/// Finite-difference step in the unbounded variables.
pub const FD_STEP: f64 = 0.03;

/// Result of a calibration.
#[derive(Debug, Clone)]
pub struct Calibration {
    /// The fitted law.
    pub bit_rock: BitRock,
    /// Fitted parameters: (parameter, value, standard deviation), natural units (rad for the
    /// walk angle). A standard deviation larger than [`FitParameter::identifiable_below`]
    /// means the data do not determine the parameter.
    pub fitted: Vec<(FitParameter, f64, f64)>,
    /// Sum of squared residuals at the start and at the end ((deg/100 m)^2).
    pub ssr_start: f64,
    /// Final sum of squared residuals ((deg/100 m)^2).
    pub ssr_end: f64,
    /// LM iterations done.
    pub iterations: usize,
    /// Interval results with the fitted law.
    pub results: Vec<IntervalResult>,
}

/// Data residuals of interval results: inclination and sin(I)-weighted azimuth errors per
/// 100 m, in degrees (physics.md 7.7).
pub fn residuals(results: &[IntervalResult]) -> Vec<f64> {
    let mut r = Vec::with_capacity(2 * results.len());
    for x in results {
        let per = 100.0 / x.length_m();
        let sin_i = (0.5 * (x.inc_rad + x.interval.measured.0)).sin();
        r.push(x.inc_err_rad().to_degrees() * per);
        r.push(sin_i * x.azi_err_rad().to_degrees() * per);
    }
    r
}

/// Fit `params` of `case`'s law on `list` by Levenberg-Marquardt.
pub fn calibrate(
    case: &Case,
    params: &[FitParameter],
    list: &[Interval],
    settings: &MarchSettings,
    mut progress: impl FnMut(&str),
) -> Result<Calibration, PredictError> {
    let np = params.len();
    let start = case.bit_rock.clone();
    let u0: Vec<f64> = params.iter().map(|p| p.unbounded(p.value(&start))).collect();
    let v0: Vec<f64> = params.iter().map(|p| p.value(&start)).collect();
    let mut warm: Vec<WarmStart> = Vec::new();
    let law_of = |u: &[f64]| {
        let mut br = start.clone();
        for (p, &x) in params.iter().zip(u) {
            p.set(&mut br, p.natural(x));
        }
        br
    };
    // full residual: data plus the weak prior (natural units over the prior sigma)
    let full = |u: &[f64], res: &[IntervalResult]| -> Vec<f64> {
        let mut r = residuals(res);
        for (k, p) in params.iter().enumerate() {
            r.push((p.natural(u[k]) - v0[k]) / p.prior_sigma());
        }
        r
    };
    let evaluate = |u: &[f64], warm: &mut Vec<WarmStart>| -> Result<(Vec<f64>, Vec<IntervalResult>), PredictError> {
        let res = run_intervals(case, &law_of(u), list, settings, warm, |_, _| {})?;
        Ok((full(u, &res), res))
    };
    let mut u = u0.clone();
    let (mut r, mut res) = evaluate(&u, &mut warm)?;
    let ssr = |r: &[f64]| r.iter().map(|x| x * x).sum::<f64>();
    let ssr_start = ssr(&r);
    let mut lambda = 1e-3;
    let mut iterations = 0;
    let mut jac = DMatrix::zeros(r.len(), np);
    for it in 0..MAX_LM_ITERATIONS {
        iterations = it + 1;
        for c in 0..np {
            let mut up = u.clone();
            up[c] += FD_STEP;
            let (rp, _) = evaluate(&up, &mut warm)?;
            for k in 0..r.len() {
                jac[(k, c)] = (rp[k] - r[k]) / FD_STEP;
            }
        }
        let jt = jac.transpose();
        let jtj = &jt * &jac;
        let g = &jt * DVector::from_vec(r.clone());
        let mut improved = false;
        for _ in 0..MAX_LAMBDA_INCREASES {
            let mut a = jtj.clone();
            for d in 0..np {
                a[(d, d)] += lambda * jtj[(d, d)].max(1e-12);
            }
            let Some(mut step) = a.lu().solve(&(-&g)) else {
                lambda *= 10.0;
                continue;
            };
            // trust region in the unbounded variables
            if step.amax() > MAX_STEP_U {
                step *= MAX_STEP_U / step.amax();
            }
            let un: Vec<f64> = u.iter().zip(step.iter()).map(|(a, b)| a + b).collect();
            let (rn, resn) = evaluate(&un, &mut warm)?;
            if ssr(&rn) < ssr(&r) {
                let small = step.amax() < 1e-4 || (ssr(&r) - ssr(&rn)) < SSR_RELATIVE_TOLERANCE * ssr(&r).max(1e-30);
                u = un;
                r = rn;
                res = resn;
                lambda = (lambda / 10.0).max(1e-9);
                improved = true;
                progress(&format!(
                    "calibration iteration {}: SSR {:.4e} (deg/100 m)^2",
                    it + 1,
                    ssr(&r)
                ));
                if small {
                    return Ok(finish(params, &u, &jac, &r, res, law_of(&u), ssr_start, iterations));
                }
                break;
            }
            lambda *= 10.0;
        }
        if !improved {
            break;
        }
    }
    let br = law_of(&u);
    Ok(finish(params, &u, &jac, &r, res, br, ssr_start, iterations))
}

#[allow(clippy::too_many_arguments)]
fn finish(
    params: &[FitParameter],
    u: &[f64],
    jac: &DMatrix<f64>,
    r: &[f64],
    results: Vec<IntervalResult>,
    bit_rock: BitRock,
    ssr_start: f64,
    iterations: usize,
) -> Calibration {
    let np = params.len();
    // data rows only for the covariance
    let m = r.len() - np;
    let jd = jac.rows(0, m).into_owned();
    let ssr_data: f64 = r[..m].iter().map(|x| x * x).sum();
    let dof = m.saturating_sub(np).max(1);
    let s2 = ssr_data / dof as f64;
    let cov = (jd.transpose() * &jd).try_inverse();
    let fitted = params
        .iter()
        .enumerate()
        .map(|(k, p)| {
            let sd_u = cov
                .as_ref()
                .map(|c| (s2 * c[(k, k)]).max(0.0).sqrt())
                .unwrap_or(f64::INFINITY);
            (*p, p.natural(u[k]), sd_u * p.slope(u[k]).abs())
        })
        .collect();
    Calibration {
        bit_rock,
        fitted,
        ssr_start,
        ssr_end: r.iter().map(|x| x * x).sum(),
        iterations,
        results,
    }
}
