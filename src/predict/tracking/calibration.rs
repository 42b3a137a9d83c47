//! Calibration of the stated uncertainty: the mixture's predictive covariance scaled, per
//! component, by how large its past errors were against it.
//!
//! The filters' covariances follow from their assumptions (the fluctuation's variance adapted
//! to the innovations, the offset's prior, the spread between the members); where the hole
//! behind was drilled otherwise than the hole ahead (a warm-up over a build held at one model
//! tendency) they may be too wide or too narrow for a while. Each scored prediction's absolute
//! error over its predicted standard deviation (toward the high side, toward the right), divided
//! by a standard normal variable's mean absolute value ([`GAUSSIAN_MEAN_ABS`]: 1 on average for
//! a calibrated Gaussian prediction), is averaged with a prior of 1 worth [`PRIOR_WEIGHT`]
//! predictions, all forgotten over the forgetting length; the stated standard deviations are the
//! predicted ones times that mean. The mean absolute error, not the mean square, so that the
//! few large errors of steered wells (heavier tails than a Gaussian's) do not widen the
//! one-standard-deviation bounds beyond the share a Gaussian's hold (68%). Only predictions
//! already scored count (no look-ahead), and the scale changes the stated bounds only, not the
//! predictions or the members' weights.

use nalgebra::{Matrix2, Vector2};

/// Mean absolute value of a standard normal variable, `sqrt(2 / pi)`.
pub const GAUSSIAN_MEAN_ABS: f64 = 0.797_884_560_802_865_4;

/// Prior weight of the scale 1, in predictions.
pub const PRIOR_WEIGHT: f64 = 1.0;

/// The scale's state.
#[derive(Debug, Clone)]
pub struct Calibration {
    /// Forgetting-weighted sums of the normalized squared errors (toward the high side, toward
    /// the right).
    sum: [f64; 2],
    /// Forgetting-weighted count of the predictions.
    count: f64,
    /// The prior's weight, forgotten like the predictions.
    prior_weight: f64,
    /// Forgetting length, m.
    forgetting_m: f64,
}

impl Calibration {
    /// No prediction scored yet: the scale is 1; older predictions forgotten over
    /// `forgetting_m` (m).
    pub fn new(forgetting_m: f64) -> Calibration {
        Calibration {
            sum: [0.0; 2],
            count: 0.0,
            prior_weight: PRIOR_WEIGHT,
            forgetting_m,
        }
    }

    /// Take in a prediction over `len_m` (m) whose error was `y` (rad) against its predicted
    /// covariance `cov` (rad^2, survey noise of the end station included): its absolute errors
    /// over the standard deviations, over [`GAUSSIAN_MEAN_ABS`].
    pub fn observe(&mut self, y: &Vector2<f64>, cov: &Matrix2<f64>, len_m: f64) {
        let keep = (-len_m / self.forgetting_m).exp();
        self.count = self.count * keep + 1.0;
        self.prior_weight *= keep;
        for c in 0..2 {
            let e = if cov[(c, c)] > 0.0 {
                y[c].abs() / cov[(c, c)].sqrt() / GAUSSIAN_MEAN_ABS
            } else {
                1.0
            };
            self.sum[c] = self.sum[c] * keep + e;
        }
    }

    /// The variance scales (toward the high side, toward the right): the squares of the
    /// standard deviations' scales.
    pub fn scales(&self) -> [f64; 2] {
        self.sum
            .map(|s| ((self.prior_weight + s) / (self.prior_weight + self.count)).powi(2))
    }

    /// The covariance `cov` (rad^2) scaled: component by component by [`Calibration::scales`].
    pub fn scaled(&self, cov: &Matrix2<f64>) -> Matrix2<f64> {
        let s = self.scales().map(f64::sqrt);
        Matrix2::new(
            cov[(0, 0)] * s[0] * s[0],
            cov[(0, 1)] * s[0] * s[1],
            cov[(1, 0)] * s[1] * s[0],
            cov[(1, 1)] * s[1] * s[1],
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Reference, by hand: errors of exactly half the predicted standard deviation on both
    /// components, many times over a long memory: the standard deviations are scaled by
    /// `0.5 / sqrt(2 / pi) = 0.6267`, so the scaled covariance of diag(4, 16) is diag(1.5708,
    /// 6.2832) (`pi / 2` and `2 pi`; within 1%).
    #[test]
    fn errors_of_half_the_stated_spread_narrow_it() {
        let mut c = Calibration::new(1e9);
        let cov = Matrix2::new(4.0, 0.0, 0.0, 16.0);
        for _ in 0..1000 {
            c.observe(&Vector2::new(1.0, 2.0), &cov, 30.0);
        }
        let s = c.scaled(&cov);
        let pi = std::f64::consts::PI;
        assert!(
            (s[(0, 0)] / (pi / 2.0) - 1.0).abs() < 0.01 && (s[(1, 1)] / (2.0 * pi) - 1.0).abs() < 0.01,
            "{s}"
        );
    }
}
