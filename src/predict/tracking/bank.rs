//! A bank of tendency filters that differ in how the unexplained turn behaves (how long a
//! fluctuation lasts, whether a lasting offset exists), weighted by how well each predicted
//! the measured hole so far over the prediction's own horizon.
//!
//! Wells differ: a well steered stand by stand keeps its fluctuations for a few tens of metres,
//! a rotary run in a formation that pushes keeps an offset for hundreds. No single setting fits
//! both, and none is fitted to a well: each filter's weight is its predictive likelihood over the
//! past predictions (only stations already drilled; older ones forgotten over the forgetting
//! length), and the bank predicts the weighted mixture (its mean, and its covariance with the
//! spread between the filters). The variants are the correlation length of
//! `[tracking]` and a third and three times it, each with and without a lasting offset.

use super::estimator::TendencyFilter;
use crate::case::bit_rock::LawParameter;
use crate::case::tracking::TrackingSettings;
use nalgebra::{DMatrix, Matrix2};

/// Factors on the correlation length of the bank's variants.
pub const CORRELATION_FACTORS: [f64; 3] = [1.0 / 3.0, 1.0, 3.0];

/// Prior standard deviation of the lasting offset in the variants without one, as a fraction of
/// `[tracking] tendency_sd`.
pub const NO_OFFSET_FRACTION: f64 = 0.01;

/// The bank.
#[derive(Debug, Clone)]
pub struct FilterBank {
    /// The filters.
    filters: Vec<TendencyFilter>,
    /// Each filter's settings (for the outputs).
    variants: Vec<(f64, bool)>,
    /// Forgetting-weighted log-likelihood of each filter's past predictions.
    score: Vec<f64>,
    /// Forgetting length, m.
    forgetting_m: f64,
}

impl FilterBank {
    /// The bank for `settings`, its filters at their prior (see [`TendencyFilter::new`]).
    pub fn new(
        settings: &TrackingSettings,
        parameters: &[(LawParameter, f64, f64)],
        first_station: &Matrix2<f64>,
    ) -> FilterBank {
        let mut filters = Vec::new();
        let mut variants = Vec::new();
        for factor in CORRELATION_FACTORS {
            for offset in [true, false] {
                let s = TrackingSettings {
                    correlation_length_m: settings.correlation_length_m * factor,
                    tendency_sd_rad_per_m: if offset {
                        settings.tendency_sd_rad_per_m
                    } else {
                        settings.tendency_sd_rad_per_m * NO_OFFSET_FRACTION
                    },
                    ..settings.clone()
                };
                filters.push(TendencyFilter::new(&s, parameters, first_station));
                variants.push((s.correlation_length_m, offset));
            }
        }
        let n = filters.len();
        FilterBank {
            filters,
            variants,
            score: vec![0.0; n],
            forgetting_m: settings.forgetting_length_m,
        }
    }

    /// The filters' weights (summing to 1).
    pub fn weights(&self) -> Vec<f64> {
        let top = self.score.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        let w: Vec<f64> = self.score.iter().map(|s| (s - top).exp()).collect();
        let sum: f64 = w.iter().sum();
        w.into_iter().map(|x| x / sum).collect()
    }

    /// Each filter's (correlation length m, lasting offset or not) with its weight.
    pub fn variants(&self) -> Vec<(f64, bool, f64)> {
        self.variants
            .iter()
            .zip(self.weights())
            .map(|(&(l, o), w)| (l, o, w))
            .collect()
    }

    /// Number of law parameters in the filters.
    pub fn parameter_count(&self) -> usize {
        self.filters[0].parameter_count()
    }

    /// The weighted mean of `f` over the filters.
    fn mean2(&self, f: impl Fn(&TendencyFilter) -> [f64; 2]) -> [f64; 2] {
        let mut m = [0.0; 2];
        for (flt, w) in self.filters.iter().zip(self.weights()) {
            let v = f(flt);
            m[0] += w * v[0];
            m[1] += w * v[1];
        }
        m
    }

    /// The mixture's expected correction over the next `len_m`, rad.
    pub fn predicted_turn(&self, len_m: f64) -> [f64; 2] {
        self.mean2(|f| f.predicted_turn(len_m))
    }

    /// The mixture's expected sideways offset after `len_m`, m.
    pub fn predicted_offset(&self, len_m: f64) -> [f64; 2] {
        self.mean2(|f| f.predicted_offset(len_m))
    }

    /// The mixture's covariance of the correction over `len_m`: each filter's, plus the spread
    /// of their means, rad^2 (without the end station's survey noise).
    pub fn turn_covariance(&self, len_m: f64, sensitivity: &DMatrix<f64>) -> Matrix2<f64> {
        let mean = self.predicted_turn(len_m);
        let mut c = Matrix2::zeros();
        for (f, w) in self.filters.iter().zip(self.weights()) {
            let t = f.predicted_turn(len_m);
            let d = nalgebra::Vector2::new(t[0] - mean[0], t[1] - mean[1]);
            c += (f.turn_covariance(len_m, sensitivity) + d * d.transpose()) * w;
        }
        c
    }

    /// Score every filter on an observed correction `z` (the measured turn over `len_m` less the
    /// model's, rad) that each predicted from the current state: its log-likelihood under that
    /// filter's prediction (covariance plus the end station's survey noise `end_station`) is
    /// added to its score, the older scores forgotten over the forgetting length.
    pub fn score(&mut self, z: [f64; 2], len_m: f64, sensitivity: &DMatrix<f64>, end_station: &Matrix2<f64>) {
        let keep = (-len_m / self.forgetting_m).exp();
        for (f, s) in self.filters.iter().zip(self.score.iter_mut()) {
            let t = f.predicted_turn(len_m);
            let y = nalgebra::Vector2::new(z[0] - t[0], z[1] - t[1]);
            let cov = f.turn_covariance(len_m, sensitivity) + end_station;
            let ll = match cov.try_inverse() {
                Some(inv) => -0.5 * ((y.transpose() * inv * y)[(0, 0)] + cov.determinant().max(1e-300).ln()),
                None => 0.0,
            };
            *s = *s * keep + ll;
        }
    }

    /// Advance every filter by a step of `d_m` (see [`TendencyFilter::advance`]).
    pub fn advance(&mut self, d_m: f64) {
        for f in &mut self.filters {
            f.advance(d_m);
        }
    }

    /// Take in a step's observation in every filter (see [`TendencyFilter::observe`]).
    pub fn observe(&mut self, z: [f64; 2], d_m: f64, sensitivity: &DMatrix<f64>, new_station: &Matrix2<f64>) {
        for f in &mut self.filters {
            f.observe(z, d_m, sensitivity, new_station);
        }
    }

    /// The mixture's lasting offset (toward the high side, toward the right), rad/m, with its
    /// standard deviations.
    pub fn offset(&self) -> ([f64; 2], [f64; 2]) {
        let mean = self.mean2(|f| f.offset().0);
        let var = self.mean2(|f| {
            let (m, sd) = f.offset();
            [0, 1].map(|c| sd[c] * sd[c] + (m[c] - mean[c]).powi(2))
        });
        (mean, var.map(f64::sqrt))
    }

    /// The mixture's current fluctuation, rad/m.
    pub fn fluctuation(&self) -> [f64; 2] {
        self.mean2(|f| f.fluctuation())
    }

    /// The weighted adapted fluctuation standard deviations, rad/m.
    pub fn fluctuation_sd(&self) -> [f64; 2] {
        self.mean2(|f| f.fluctuation_sd().map(|s| s * s)).map(f64::sqrt)
    }

    /// The law parameters: (parameter, mixture mean, mixture standard deviation, prior standard
    /// deviation) in unbounded variables.
    pub fn parameters(&self) -> Vec<(LawParameter, f64, f64, f64)> {
        let w = self.weights();
        let per: Vec<Vec<(LawParameter, f64, f64, f64)>> = self.filters.iter().map(|f| f.parameters()).collect();
        (0..self.parameter_count())
            .map(|j| {
                let (p, _, _, prior) = per[0][j];
                let mean: f64 = per.iter().zip(&w).map(|(v, w)| w * v[j].1).sum();
                let var: f64 = per
                    .iter()
                    .zip(&w)
                    .map(|(v, w)| w * (v[j].2 * v[j].2 + (v[j].1 - mean).powi(2)))
                    .sum();
                (p, mean, var.sqrt(), prior)
            })
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Reference: the likelihood prefers the variant that matches the data. Noiseless 30 m steps
    /// with a lasting offset of 1 deg/30 m toward the right, scored on their 30 m predictions:
    /// the variants with a lasting offset end with nearly all the weight (above 0.9), and the
    /// bank's correction over 30 m is the offset within 5%.
    #[test]
    fn the_weights_favour_the_variant_that_predicts() {
        let s = TrackingSettings::default();
        let tiny = Matrix2::from_diagonal_element(1e-12);
        let mut bank = FilterBank::new(&s, &[], &tiny);
        let k = 1f64.to_radians() / 30.0;
        let none = DMatrix::zeros(2, 0);
        for _ in 0..30 {
            bank.score([0.0, k * 30.0], 30.0, &none, &tiny);
            bank.advance(30.0);
            bank.observe([0.0, k * 30.0], 30.0, &none, &tiny);
        }
        let lasting: f64 = bank.variants().iter().filter(|v| v.1).map(|v| v.2).sum();
        assert!(lasting > 0.9, "{:?}", bank.variants());
        let t = bank.predicted_turn(30.0);
        assert!((t[1] / (k * 30.0) - 1.0).abs() < 0.05, "{t:?}");
    }
}
