//! Calibration of the bit-rock law's parameters on a back-analysis (docs/theory.md 9.6):
//! Levenberg-Marquardt on the per-100 m interval errors, finite-difference Jacobian (one
//! re-prediction of all intervals per parameter), bounds by reparametrization, a weak prior
//! toward the starting values, covariance `s^2 (J^T J)^-1` with `s^2 = SSR / (m - n)`.

use super::intervals::{run_intervals, Interval, IntervalResult, RunModel};
use super::march::{MarchSettings, PredictError, WarmStart};
use crate::case::{BitRock, Case};
use crate::numerics::least_squares::{
    forward_difference_jacobian, levenberg_marquardt, standard_deviations, sum_of_squares, LeastSquares, LmSettings,
};
use nalgebra::{DMatrix, DVector};

pub use crate::case::bit_rock::LawParameter as FitParameter;

/// The reparametrization and prior of a law parameter in a fit: beta_b through
/// `beta = 1e-3 + (1 - 1e-3) logistic(u)`, chi_w unbounded, I_r through `I_r = 0.5 tanh(u)`.
impl FitParameter {
    /// Natural value of the unbounded variable `u`.
    pub fn natural(self, u: f64) -> f64 {
        match self {
            FitParameter::LateralDrillability => BETA_MIN + (1.0 - BETA_MIN) / (1.0 + (-u).exp()),
            FitParameter::WalkAngle => u,
            FitParameter::RockAnisotropy => 0.5 * u.tanh(),
        }
    }
    /// Unbounded variable of a natural value (clamped inside the bounds).
    pub fn unbounded(self, v: f64) -> f64 {
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
    pub fn slope(self, u: f64) -> f64 {
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
/// 100 m, in degrees (docs/theory.md 9.6).
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

/// The calibration as a least-squares problem in the unbounded variables: the data residuals
/// of the re-predicted intervals plus the weak prior toward the start values.
struct LawFit<'a, F: FnMut(&str)> {
    case: &'a Case,
    params: &'a [FitParameter],
    list: &'a [Interval],
    settings: &'a MarchSettings,
    /// Natural values at the start (the prior's centre).
    start_values: Vec<f64>,
    /// Warm starts of the interval solves, carried from one evaluation to the next.
    warm: Vec<WarmStart>,
    progress: F,
}

impl<F: FnMut(&str)> LawFit<'_, F> {
    /// The case's law with the parameters at the unbounded values `u`.
    fn law(&self, u: &[f64]) -> BitRock {
        let mut br = self.case.bit_rock.clone();
        for (p, &x) in self.params.iter().zip(u) {
            p.set(&mut br, p.natural(x));
        }
        br
    }
}

impl<F: FnMut(&str)> LeastSquares for LawFit<'_, F> {
    type Error = PredictError;
    type Outcome = Vec<IntervalResult>;
    fn evaluate(&mut self, u: &[f64]) -> Result<(DVector<f64>, Vec<IntervalResult>), PredictError> {
        let law = self.law(u);
        let run = RunModel {
            case: self.case,
            bit_rock: &law,
            settings: self.settings,
        };
        let res = run_intervals(&[run], self.list, &mut self.warm, |_, _| {})?;
        let mut r = residuals(&res);
        for (k, p) in self.params.iter().enumerate() {
            r.push((p.natural(u[k]) - self.start_values[k]) / p.prior_sigma());
        }
        Ok((DVector::from_vec(r), res))
    }
    fn jacobian(&mut self, u: &[f64], r: &DVector<f64>) -> Result<DMatrix<f64>, PredictError> {
        forward_difference_jacobian(u, r, |_, _| FD_STEP, |up| self.evaluate(up).map(|e| e.0))
    }
    fn accepted(&mut self, iteration: usize, cost: f64) {
        (self.progress)(&format!(
            "calibration iteration {iteration}: SSR {cost:.4e} (deg/100 m)^2"
        ));
    }
}

/// Levenberg-Marquardt settings of the law's calibration.
pub const LM_SETTINGS: LmSettings = LmSettings {
    max_iterations: MAX_LM_ITERATIONS,
    max_damping_increases: MAX_LAMBDA_INCREASES,
    initial_damping: 1e-3,
    damping_decrease: 10.0,
    damping_increase: 10.0,
    min_damping: 1e-9,
    max_step: Some(MAX_STEP_U),
    min_move: 1e-4,
    min_relative_decrease: SSR_RELATIVE_TOLERANCE,
};

/// Fit `params` of `case`'s law on `list` by Levenberg-Marquardt ([`LM_SETTINGS`]).
pub fn calibrate(
    case: &Case,
    params: &[FitParameter],
    list: &[Interval],
    settings: &MarchSettings,
    progress: impl FnMut(&str),
) -> Result<Calibration, PredictError> {
    let start = &case.bit_rock;
    let u0: Vec<f64> = params.iter().map(|p| p.unbounded(p.value(start))).collect();
    let mut fit = LawFit {
        case,
        params,
        list,
        settings,
        start_values: params.iter().map(|p| p.value(start)).collect(),
        warm: Vec::new(),
        progress,
    };
    let lm = levenberg_marquardt(&mut fit, &u0, None, &LM_SETTINGS)?;
    // the covariance of the data rows only (not the prior's)
    let m = lm.residuals.len() - params.len();
    let sd = standard_deviations(&lm.jacobian.rows(0, m).into_owned(), &lm.residuals.as_slice()[..m]);
    let fitted = params
        .iter()
        .enumerate()
        .map(|(k, p)| {
            let sd_u = sd.as_ref().map_or(f64::INFINITY, |s| s[k]);
            (*p, p.natural(lm.x[k]), sd_u * p.slope(lm.x[k]).abs())
        })
        .collect();
    Ok(Calibration {
        bit_rock: fit.law(&lm.x),
        fitted,
        ssr_start: lm.initial_cost,
        ssr_end: sum_of_squares(&lm.residuals),
        iterations: lm.iterations,
        results: lm.outcome,
    })
}
