//! Nonlinear least squares by Levenberg-Marquardt, with a forward-difference Jacobian.
//!
//! Minimizes `|r(x)|^2` for a residual vector `r` of a few parameters `x` (the bit-rock law's
//! calibration, the friction calibration of the torque-and-drag chart). Each iteration takes the
//! Jacobian `J` at the current point and tries steps `(J^T J + lambda D) dx = -J^T r`, with
//! `D = diag(J^T J)` (Marquardt's scaling, each entry at least 1e-12), raising the damping
//! `lambda` until the cost does not increase; a step that is accepted lowers it. Bounds are the
//! problem's: it may project a trial point ([`LeastSquares::constrain`]) or reparametrize.

use nalgebra::{DMatrix, DVector};

/// A least-squares problem: residuals (with what else the model computed at the point) and
/// their Jacobian.
pub trait LeastSquares {
    /// Why an evaluation failed.
    type Error;
    /// What an evaluation computed besides the residuals (kept for the accepted point).
    type Outcome;
    /// Residual vector at `x` and the evaluation's other results.
    fn evaluate(&mut self, x: &[f64]) -> Result<(DVector<f64>, Self::Outcome), Self::Error>;
    /// Jacobian `dr/dx` at `x`, whose residuals are `r` (one column per parameter).
    fn jacobian(&mut self, x: &[f64], r: &DVector<f64>) -> Result<DMatrix<f64>, Self::Error>;
    /// Project a trial point into the feasible set (default: none).
    fn constrain(&self, _x: &mut [f64]) {}
    /// Called after each accepted step with the iteration (from 1) and the new cost `|r|^2`.
    fn accepted(&mut self, _iteration: usize, _cost: f64) {}
}

/// Settings of [`levenberg_marquardt`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LmSettings {
    /// Iterations allowed (each one Jacobian).
    pub max_iterations: usize,
    /// Damping increases tried per iteration before the iteration gives up.
    pub max_damping_increases: usize,
    /// Damping of the first iteration.
    pub initial_damping: f64,
    /// Factor dividing the damping after an accepted step.
    pub damping_decrease: f64,
    /// Factor multiplying the damping after a rejected step (or a failed factorization).
    pub damping_increase: f64,
    /// Smallest damping.
    pub min_damping: f64,
    /// Largest step entry (max norm); a longer step is scaled down (None: no limit).
    pub max_step: Option<f64>,
    /// Converged when an accepted step moves every parameter by less than this.
    pub min_move: f64,
    /// Converged when an accepted step lowers the cost by at most this fraction of the cost
    /// before it.
    pub min_relative_decrease: f64,
}

/// Result of [`levenberg_marquardt`].
#[derive(Debug, Clone)]
pub struct LmResult<T> {
    /// Parameters at the end.
    pub x: Vec<f64>,
    /// Residuals at `x`.
    pub residuals: DVector<f64>,
    /// The evaluation's other results at `x`.
    pub outcome: T,
    /// The last Jacobian computed (at the start of the last iteration).
    pub jacobian: DMatrix<f64>,
    /// Cost `|r|^2` at the start.
    pub initial_cost: f64,
    /// Iterations done.
    pub iterations: usize,
    /// Whether a convergence criterion was met (a short step, a small decrease, or no
    /// decrease possible from the point); false when the iterations ran out.
    pub converged: bool,
}

/// Minimize `|r(x)|^2` from `x0` (see the module documentation). `jacobian0` is the Jacobian at
/// `x0` when the caller already has it.
pub fn levenberg_marquardt<P: LeastSquares>(
    problem: &mut P,
    x0: &[f64],
    jacobian0: Option<DMatrix<f64>>,
    settings: &LmSettings,
) -> Result<LmResult<P::Outcome>, P::Error> {
    let mut x = x0.to_vec();
    let (mut r, mut outcome) = problem.evaluate(&x)?;
    let initial_cost = sum_of_squares(&r);
    let mut cost = initial_cost;
    let mut lambda = settings.initial_damping;
    let mut iterations = 0;
    let mut converged = false;
    let mut next_jacobian = jacobian0;
    let mut jac = DMatrix::zeros(r.len(), x.len());
    for it in 0..settings.max_iterations {
        iterations = it + 1;
        jac = match next_jacobian.take() {
            Some(j) => j,
            None => problem.jacobian(&x, &r)?,
        };
        let jtj = jac.transpose() * &jac;
        let g = jac.transpose() * &r;
        let mut accepted = false;
        for _ in 0..settings.max_damping_increases {
            let Some(step) = damped_step(&jtj, &g, lambda, settings.max_step) else {
                lambda *= settings.damping_increase;
                continue;
            };
            let mut trial: Vec<f64> = x.iter().zip(step.iter()).map(|(a, b)| a + b).collect();
            problem.constrain(&mut trial);
            let (rt, ot) = problem.evaluate(&trial)?;
            let ct = sum_of_squares(&rt);
            if ct <= cost {
                let moved = x.iter().zip(&trial).map(|(a, b)| (b - a).abs()).fold(0.0, f64::max);
                let small = moved < settings.min_move || cost - ct <= settings.min_relative_decrease * cost.max(1e-30);
                x = trial;
                r = rt;
                outcome = ot;
                cost = ct;
                lambda = (lambda / settings.damping_decrease).max(settings.min_damping);
                accepted = true;
                problem.accepted(iterations, cost);
                converged = small;
                break;
            }
            lambda *= settings.damping_increase;
        }
        if !accepted {
            // no decrease possible from here: a (local) minimum within the bounds
            converged = true;
        }
        if converged {
            break;
        }
    }
    Ok(LmResult {
        x,
        residuals: r,
        outcome,
        jacobian: jac,
        initial_cost,
        iterations,
        converged,
    })
}

/// `|r|^2`, summed in order.
pub fn sum_of_squares(r: &DVector<f64>) -> f64 {
    r.iter().map(|x| x * x).sum()
}

/// The step `-(J^T J + lambda D)^-1 J^T r` from the normal equations `jtj`, `g = J^T r`, scaled
/// down to `max_step` in max norm; None when the damped matrix is singular.
fn damped_step(jtj: &DMatrix<f64>, g: &DVector<f64>, lambda: f64, max_step: Option<f64>) -> Option<DVector<f64>> {
    let mut a = jtj.clone();
    for d in 0..a.nrows() {
        a[(d, d)] += lambda * jtj[(d, d)].max(1e-12);
    }
    let mut step = a.lu().solve(&(-g))?;
    if let Some(m) = max_step {
        if step.amax() > m {
            step *= m / step.amax();
        }
    }
    Some(step)
}

/// Forward-difference Jacobian of `residuals` at `x` (residuals `r` there): column `k` is
/// `(r(x + h_k e_k) - r) / h_k` with `h_k = step(k, x)`.
pub fn forward_difference_jacobian<E>(
    x: &[f64],
    r: &DVector<f64>,
    step: impl Fn(usize, &[f64]) -> f64,
    mut residuals: impl FnMut(&[f64]) -> Result<DVector<f64>, E>,
) -> Result<DMatrix<f64>, E> {
    let mut j = DMatrix::zeros(r.len(), x.len());
    for k in 0..x.len() {
        let h = step(k, x);
        let mut xp = x.to_vec();
        xp[k] += h;
        let rp = residuals(&xp)?;
        j.set_column(k, &((rp - r) / h));
    }
    Ok(j)
}

/// Standard deviations of the parameters from the linearized covariance `s^2 (J^T J)^-1`, with
/// `s^2 = |r|^2 / (m - n)` for `m` residuals in `r` and `n` parameters (at least 1 degree of
/// freedom). None when `J^T J` is singular.
pub fn standard_deviations(jacobian: &DMatrix<f64>, r: &[f64]) -> Option<Vec<f64>> {
    let (m, n) = (r.len(), jacobian.ncols());
    let dof = m.saturating_sub(n).max(1);
    let s2 = r.iter().map(|x| x * x).sum::<f64>() / dof as f64;
    let cov = (jacobian.transpose() * jacobian).try_inverse()?;
    Some((0..n).map(|k| (s2 * cov[(k, k)]).max(0.0).sqrt()).collect())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Exponential decay `y = a exp(-b t)` sampled without noise: the fit must return `a`, `b`.
    struct Decay {
        t: Vec<f64>,
        y: Vec<f64>,
    }

    impl LeastSquares for Decay {
        type Error = ();
        type Outcome = ();
        fn evaluate(&mut self, x: &[f64]) -> Result<(DVector<f64>, ()), ()> {
            let r = self.t.iter().zip(&self.y).map(|(t, y)| x[0] * (-x[1] * t).exp() - y);
            Ok((DVector::from_iterator(self.t.len(), r), ()))
        }
        fn jacobian(&mut self, x: &[f64], r: &DVector<f64>) -> Result<DMatrix<f64>, ()> {
            forward_difference_jacobian(x, r, |_, _| 1e-7, |xp| self.evaluate(xp).map(|e| e.0))
        }
    }

    fn settings() -> LmSettings {
        LmSettings {
            max_iterations: 100,
            max_damping_increases: 30,
            initial_damping: 1e-3,
            damping_decrease: 3.0,
            damping_increase: 4.0,
            min_damping: 1e-12,
            max_step: None,
            min_move: 1e-10,
            min_relative_decrease: 1e-14,
        }
    }

    #[test]
    fn fits_an_exponential_decay_exactly() {
        // Reference: the data's own parameters (a = 2.5, b = 0.7); tolerance 1e-6 relative.
        let t: Vec<f64> = (0..20).map(|k| 0.25 * k as f64).collect();
        let y = t.iter().map(|t| 2.5 * (-0.7 * t).exp()).collect();
        let mut p = Decay { t, y };
        let fit = levenberg_marquardt(&mut p, &[1.0, 0.2], None, &settings()).unwrap();
        assert!(fit.converged, "{fit:?}");
        assert!(
            (fit.x[0] / 2.5 - 1.0).abs() < 1e-6 && (fit.x[1] / 0.7 - 1.0).abs() < 1e-6,
            "{:?}",
            fit.x
        );
        assert!(fit.residuals.norm() < 1e-6);
    }

    #[test]
    fn covariance_of_a_straight_line_fit() {
        // Reference: ordinary least squares of y = c0 + c1 x on x = 0, 1, 2, 3 with residuals
        // (1, -1, -1, 1): s^2 = 4 / 2, (X^T X)^-1 = [[0.7, -0.3], [-0.3, 0.2]], so the standard
        // deviations are sqrt(1.4) and sqrt(0.4). Tolerance 1e-12.
        let j = DMatrix::from_row_slice(4, 2, &[1.0, 0.0, 1.0, 1.0, 1.0, 2.0, 1.0, 3.0]);
        let sd = standard_deviations(&j, &[1.0, -1.0, -1.0, 1.0]).unwrap();
        assert!(
            (sd[0] - 1.4f64.sqrt()).abs() < 1e-12 && (sd[1] - 0.4f64.sqrt()).abs() < 1e-12,
            "{sd:?}"
        );
    }
}
