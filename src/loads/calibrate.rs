//! Friction calibration: fit the wall friction factor of each hole section to measured hook
//! loads (and surface torques) by least squares.
//!
//! Model: the soft-string row of each measured point ([`super::chart::soft_row`], bit at the
//! point's depth, its load case, WOB from the point or the chart). Parameters: one friction
//! factor per hole section (cased and open hole are sections of `[well] hole`). A section is
//! fitted only where the data constrain it: the column of the Jacobian of that section must
//! carry at least [`MIN_RELATIVE_SENSITIVITY`] of the largest column's norm; other sections keep
//! their case value and are reported as not fitted.
//!
//! Residuals are relative, `(model - measured) / max(|measured|, floor)` (floors
//! [`HOOK_LOAD_FLOOR_N`], [`TORQUE_FLOOR_NM`]), so hook loads and torques weigh alike and a
//! multiplicative measurement error gives equal variances. Torque residuals enter for rotating
//! points (drilling, rotating off bottom) where a torque is given.
//!
//! Solver: Levenberg-Marquardt with a forward-difference Jacobian (step
//! [`JACOBIAN_STEP`]), friction kept in `[0, 1.5]`. Standard errors from the linearized
//! covariance `s^2 (J^T J)^-1`, `s^2 = RSS / (m - p)`.

use super::chart::soft_row;
use super::{set_row_operation, ChartOperation};
use crate::case::{Case, Mode};
use crate::geometry::{HoleSection, HoleSize};
use crate::numerics::least_squares::{
    forward_difference_jacobian, levenberg_marquardt, standard_deviations, LeastSquares, LmSettings,
};
use nalgebra::{DMatrix, DVector};

/// One measured point, SI.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MeasuredPoint {
    /// 1-based line in the file.
    pub line: usize,
    /// Bit measured depth, m.
    pub bit_md_m: f64,
    /// Load case.
    pub mode: Mode,
    /// Measured hook load, N.
    pub hook_load_n: f64,
    /// Measured surface torque, N.m, if given.
    pub torque_nm: Option<f64>,
    /// Weight on bit, N, if given.
    pub wob_n: Option<f64>,
}

/// Hook-load scale floor of the relative residuals, N.
pub const HOOK_LOAD_FLOOR_N: f64 = 10e3;
/// Torque scale floor of the relative residuals, N.m.
pub const TORQUE_FLOOR_NM: f64 = 500.0;
/// Finite-difference step of the friction factor.
pub const JACOBIAN_STEP: f64 = 1e-5;
/// Sections whose Jacobian column is below this fraction of the largest are not fitted.
pub const MIN_RELATIVE_SENSITIVITY: f64 = 1e-3;
/// Largest friction factor accepted.
pub const MAX_FRICTION: f64 = 1.5;

/// One fitted (or kept) friction factor.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FrictionParameter {
    /// Hole section index (top down).
    pub section: usize,
    /// Top of the section, m MD.
    pub from_md_m: f64,
    /// Bottom of the section, m MD.
    pub to_md_m: f64,
    /// Hole diameter of the section, m.
    pub diameter_m: f64,
    /// Friction factor of the case.
    pub initial: f64,
    /// Fitted value (the initial one when not fitted).
    pub value: f64,
    /// Standard error of the fitted value (`None` when not fitted or no redundancy).
    pub std_error: Option<f64>,
    /// Whether the data constrained this section.
    pub fitted: bool,
}

/// Measured against modelled values at one point.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct OverlayPoint {
    /// The measurement.
    pub measured: MeasuredPoint,
    /// Hook load with the case's friction, N.
    pub initial_hook_load_n: f64,
    /// Hook load with the fitted friction, N.
    pub fitted_hook_load_n: f64,
    /// Surface torque with the case's friction, N.m.
    pub initial_torque_nm: f64,
    /// Surface torque with the fitted friction, N.m.
    pub fitted_torque_nm: f64,
}

/// Result of a calibration.
#[derive(Debug, Clone, PartialEq)]
pub struct Calibration {
    /// One entry per hole section.
    pub parameters: Vec<FrictionParameter>,
    /// Overlay of measured and modelled values.
    pub points: Vec<OverlayPoint>,
    /// Root-mean-square hook-load residual after the fit, N.
    pub rms_hook_load_n: f64,
    /// Root-mean-square torque residual after the fit, N.m (`None` without torques used).
    pub rms_torque_nm: Option<f64>,
    /// Number of residuals.
    pub residuals: usize,
    /// LM iterations.
    pub iterations: usize,
    /// Whether the iteration met its step/cost criteria.
    pub converged: bool,
}

/// Why a calibration cannot be done.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum CalibrationError {
    /// No section's friction changes the modelled values.
    #[error("the measured loads do not depend on any section's friction (only rotating-off-bottom hook loads, or vertical hole?): nothing to fit")]
    Unconstrained,
    /// Fewer residuals than parameters.
    #[error("{residuals} measured values cannot determine {parameters} friction factors")]
    TooFewData {
        /// Residuals.
        residuals: usize,
        /// Parameters.
        parameters: usize,
    },
    /// The model gave a non-finite value.
    #[error("the model gave a non-finite load at bit depth {0:.2} m")]
    NonFinite(f64),
}

/// The hole of `case` with friction factor `friction[k]` in section `k`.
pub fn hole_with_friction(hole: &HoleSize, friction: &[f64]) -> HoleSize {
    let sections: Vec<HoleSection> = hole
        .sections()
        .iter()
        .zip(friction)
        .map(|(s, &f)| HoleSection {
            friction: Some(f),
            ..*s
        })
        .collect();
    HoleSize::new(sections, hole.caliper().to_vec())
}

/// The friction factor of each hole section of `case` (the operation's where none is given).
pub fn section_friction(case: &Case) -> Vec<f64> {
    case.well
        .hole
        .sections()
        .iter()
        .map(|s| s.friction.unwrap_or(case.operation.friction))
        .collect()
}

/// Modelled hook load and torque at each point.
struct Evaluator {
    cases: Vec<Case>,
    base_hole: HoleSize,
    max_element_m: f64,
}

impl Evaluator {
    fn new(case: &Case, data: &[MeasuredPoint], op: &ChartOperation, max_element_m: f64) -> Evaluator {
        let cases = data
            .iter()
            .map(|p| {
                let mut c = case.at_bit_depth(p.bit_md_m);
                let mut o = *op;
                if let Some(w) = p.wob_n {
                    o.wob_n = w;
                }
                set_row_operation(&mut c, p.bit_md_m, p.mode, &o);
                c
            })
            .collect();
        Evaluator {
            cases,
            base_hole: case.well.hole.clone(),
            max_element_m,
        }
    }
    fn loads(&mut self, friction: &[f64]) -> Vec<(f64, f64)> {
        let hole = hole_with_friction(&self.base_hole, friction);
        self.cases
            .iter_mut()
            .map(|c| {
                c.well.hole = hole.clone();
                let r = soft_row(c, self.max_element_m);
                (r.soft.hook_load_n, r.soft.surface_torque_nm)
            })
            .collect()
    }
}

fn uses_torque(p: &MeasuredPoint) -> bool {
    p.torque_nm.is_some() && matches!(p.mode, Mode::Drilling | Mode::RotatingOffBottom)
}

fn residuals(data: &[MeasuredPoint], loads: &[(f64, f64)]) -> Result<DVector<f64>, CalibrationError> {
    let mut r = Vec::with_capacity(2 * data.len());
    for (p, &(h, t)) in data.iter().zip(loads) {
        if !(h.is_finite() && t.is_finite()) {
            return Err(CalibrationError::NonFinite(p.bit_md_m));
        }
        r.push((h - p.hook_load_n) / p.hook_load_n.abs().max(HOOK_LOAD_FLOOR_N));
        if uses_torque(p) {
            let m = p.torque_nm.expect("checked");
            r.push((t - m) / m.abs().max(TORQUE_FLOOR_NM));
        }
    }
    Ok(DVector::from_vec(r))
}

/// The friction fit as a least-squares problem in the fitted sections' friction factors.
struct FrictionFit<'a> {
    evaluator: Evaluator,
    data: &'a [MeasuredPoint],
    /// Friction of every section (the fitted ones replaced by the trial values).
    all: Vec<f64>,
    /// Fitted sections.
    free: Vec<usize>,
}

impl FrictionFit<'_> {
    /// Every section's friction with the fitted ones at `x`.
    fn friction(&self, x: &[f64]) -> Vec<f64> {
        let mut f = self.all.clone();
        for (&k, &v) in self.free.iter().zip(x) {
            f[k] = v;
        }
        f
    }
}

impl LeastSquares for FrictionFit<'_> {
    type Error = CalibrationError;
    type Outcome = Vec<(f64, f64)>;
    fn evaluate(&mut self, x: &[f64]) -> Result<(DVector<f64>, Vec<(f64, f64)>), CalibrationError> {
        let l = self.evaluator.loads(&self.friction(x));
        Ok((residuals(self.data, &l)?, l))
    }
    fn jacobian(&mut self, x: &[f64], r: &DVector<f64>) -> Result<DMatrix<f64>, CalibrationError> {
        // steps away from the upper bound
        let step = |k: usize, x: &[f64]| {
            if x[k] + JACOBIAN_STEP > MAX_FRICTION {
                -JACOBIAN_STEP
            } else {
                JACOBIAN_STEP
            }
        };
        forward_difference_jacobian(x, r, step, |xp| self.evaluate(xp).map(|e| e.0))
    }
    fn constrain(&self, x: &mut [f64]) {
        for v in x {
            *v = v.clamp(0.0, MAX_FRICTION);
        }
    }
}

/// Levenberg-Marquardt settings of the friction fit (the initial damping is set from the
/// Jacobian: 1e-3 of its largest squared column norm).
pub const LM_SETTINGS: LmSettings = LmSettings {
    max_iterations: 100,
    max_damping_increases: 30,
    initial_damping: 1e-3,
    damping_decrease: 3.0,
    damping_increase: 4.0,
    min_damping: 1e-12,
    max_step: None,
    min_move: 1e-7,
    min_relative_decrease: 1e-14,
};

/// Fit the friction factor per hole section of `case` to `data` (see the module
/// documentation). `op` gives the WOB of on-bottom points without their own and the RPM;
/// `max_element_m` the soft-string element length.
pub fn calibrate(
    case: &Case,
    data: &[MeasuredPoint],
    op: &ChartOperation,
    max_element_m: f64,
) -> Result<Calibration, CalibrationError> {
    let initial = section_friction(case);
    let np_all = initial.len();
    let mut fit = FrictionFit {
        evaluator: Evaluator::new(case, data, op, max_element_m),
        data,
        all: initial.clone(),
        free: (0..np_all).collect(),
    };
    // which sections the data constrain
    let (r0, loads0) = fit.evaluate(&initial)?;
    let m = r0.len();
    let j_all = fit.jacobian(&initial, &r0)?;
    let norms: Vec<f64> = (0..np_all).map(|k| j_all.column(k).norm()).collect();
    let max_norm = norms.iter().copied().fold(0.0, f64::max);
    if max_norm.is_nan() || max_norm <= 0.0 {
        return Err(CalibrationError::Unconstrained);
    }
    fit.free = (0..np_all)
        .filter(|&k| norms[k] >= MIN_RELATIVE_SENSITIVITY * max_norm)
        .collect();
    let free = fit.free.clone();
    let p = free.len();
    if m <= p {
        return Err(CalibrationError::TooFewData {
            residuals: m,
            parameters: p,
        });
    }
    let j0 = j_all.select_columns(&free);
    let settings = LmSettings {
        initial_damping: LM_SETTINGS.initial_damping * (0..p).map(|c| j0.column(c).norm_squared()).fold(0.0, f64::max),
        ..LM_SETTINGS
    };
    let x0: Vec<f64> = free.iter().map(|&k| initial[k]).collect();
    let lm = levenberg_marquardt(&mut fit, &x0, Some(j0), &settings)?;
    let f = fit.friction(&lm.x);
    let (iterations, converged) = (lm.iterations, lm.converged);
    let loads1 = lm.outcome;
    // uncertainty at the solution
    let j = fit.jacobian(&lm.x, &lm.residuals)?;
    let sd = standard_deviations(&j, lm.residuals.as_slice());
    let sections = case.well.hole.sections();
    let parameters = (0..np_all)
        .map(|k| {
            let col = free.iter().position(|&x| x == k);
            FrictionParameter {
                section: k,
                from_md_m: if k == 0 {
                    case.well.path.md_start()
                } else {
                    sections[k - 1].to_md_m
                },
                to_md_m: sections[k].to_md_m,
                diameter_m: sections[k].diameter_m,
                initial: initial[k],
                value: f[k],
                std_error: col.and_then(|c| sd.as_ref().map(|sd| sd[c])),
                fitted: col.is_some(),
            }
        })
        .collect();
    let points: Vec<OverlayPoint> = data
        .iter()
        .zip(loads0.iter().zip(&loads1))
        .map(|(p, (a, b))| OverlayPoint {
            measured: *p,
            initial_hook_load_n: a.0,
            fitted_hook_load_n: b.0,
            initial_torque_nm: a.1,
            fitted_torque_nm: b.1,
        })
        .collect();
    let rms_hook = (points
        .iter()
        .map(|q| (q.fitted_hook_load_n - q.measured.hook_load_n).powi(2))
        .sum::<f64>()
        / points.len() as f64)
        .sqrt();
    let tq: Vec<f64> = points
        .iter()
        .filter(|q| uses_torque(&q.measured))
        .map(|q| q.fitted_torque_nm - q.measured.torque_nm.expect("checked"))
        .collect();
    let rms_torque = (!tq.is_empty()).then(|| (tq.iter().map(|x| x * x).sum::<f64>() / tq.len() as f64).sqrt());
    Ok(Calibration {
        parameters,
        points,
        rms_hook_load_n: rms_hook,
        rms_torque_nm: rms_torque,
        residuals: m,
        iterations,
        converged,
    })
}

/// The case with the friction factors of `cal` in its hole sections.
pub fn calibrated_case(case: &Case, cal: &Calibration) -> Case {
    let f: Vec<f64> = cal.parameters.iter().map(|p| p.value).collect();
    let mut c = case.clone();
    c.well.hole = hole_with_friction(&case.well.hole, &f);
    c
}
