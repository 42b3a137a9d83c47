//! The naive members of the mixture: projections a directional driller makes by hand (no
//! correction of the model, the damped statistic, hold), competing with the bank's filters taken
//! as one member, each weighted by its predictive likelihood over the predictions so far (only
//! stations already drilled; older ones forgotten over the forgetting length).
//!
//! The filters assume how the unexplained turn behaves; where none of their assumptions holds
//! (a well steered by settings the survey history does not show), a naive projection may
//! predict better, and the likelihood says so from the well's own past. Each naive member's
//! predictive covariance is the variance of its own past errors beyond the survey noise of the
//! end station (per metre of interval, squared: its error grows with the interval), adapted as
//! the filter's fluctuation variance is (see [`super::estimator`]), its prior the fluctuation's
//! prior.

use super::estimator::MIN_FLUCTUATION_FRACTION;
use super::references::Reference;
use nalgebra::{Matrix2, Vector2};

/// A naive member of the mixture.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Naive {
    /// The model's prediction as it is (no correction).
    NoCorrection,
    /// A reference projection (see [`super::references::project`]).
    Reference(Reference),
}

impl Naive {
    /// Name in the outputs: `no_correction`, or the reference's name.
    pub fn name(self) -> String {
        match self {
            Naive::NoCorrection => "no_correction".into(),
            Naive::Reference(r) => r.name(),
        }
    }
}

/// The naive members, in the order of the corrections handed to the bank.
pub const MEMBERS: [Naive; 3] = [
    Naive::NoCorrection,
    Naive::Reference(Reference::Statistic),
    Naive::Reference(Reference::Hold),
];

/// Prior weight of a naive member's error variance in its adaptation, in observations.
pub const VARIANCE_PRIOR_WEIGHT: f64 = 1.0;

/// The naive members' state: the scores of the bank (as one member) and of each naive member,
/// and the naive members' adapted error variances.
#[derive(Debug, Clone)]
pub struct NaiveMembers {
    /// Forgetting-weighted log-likelihoods: the bank first, then [`MEMBERS`].
    score: Vec<f64>,
    /// Forgetting-weighted sums of the squared errors beyond the end station's noise, per
    /// metre of interval squared, per member and component (toward the high side, toward the
    /// right), (rad/m)^2.
    sum_indicated: Vec<[f64; 2]>,
    /// Forgetting-weighted count of the observations.
    sum_weight: f64,
    /// The prior's weight, forgotten like the observations.
    prior_weight: f64,
    /// Prior error variance per metre squared, (rad/m)^2.
    prior_var: f64,
    /// Forgetting length, m.
    forgetting_m: f64,
}

impl NaiveMembers {
    /// The members at their prior: equal weights, error variance `prior_sd_rad_per_m^2` per
    /// metre of interval squared; scores forgotten over `forgetting_m` (m).
    pub fn new(prior_sd_rad_per_m: f64, forgetting_m: f64) -> NaiveMembers {
        NaiveMembers {
            score: vec![0.0; MEMBERS.len() + 1],
            sum_indicated: vec![[0.0; 2]; MEMBERS.len()],
            sum_weight: 0.0,
            prior_weight: VARIANCE_PRIOR_WEIGHT,
            prior_var: prior_sd_rad_per_m * prior_sd_rad_per_m,
            forgetting_m,
        }
    }

    /// The weights (summing to 1): the bank's first, then the naive members'.
    pub fn weights(&self) -> Vec<f64> {
        let top = self.score.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        let w: Vec<f64> = self.score.iter().map(|s| (s - top).exp()).collect();
        let sum: f64 = w.iter().sum();
        w.into_iter().map(|x| x / sum).collect()
    }

    /// Covariance of naive member `k`'s correction over `len_m` (without the end station's
    /// survey noise), rad^2: its adapted error variance per metre squared (not below
    /// [`MIN_FLUCTUATION_FRACTION`] of the prior's standard deviation) times `len_m^2`.
    pub fn covariance(&self, k: usize, len_m: f64) -> Matrix2<f64> {
        let floor = self.prior_var * MIN_FLUCTUATION_FRACTION * MIN_FLUCTUATION_FRACTION;
        let v = |c: usize| {
            ((self.prior_weight * self.prior_var + self.sum_indicated[k][c]) / (self.prior_weight + self.sum_weight))
                .max(floor)
        };
        Matrix2::new(v(0), 0.0, 0.0, v(1)) * (len_m * len_m)
    }

    /// Score the bank (its log-likelihood `bank_ll` of the observation) and each naive member
    /// on the observed correction `z` (rad) over `len_m` (m), the members having predicted the
    /// corrections `naive` (rad, in the order of [`MEMBERS`]), with the end station's survey
    /// covariance `end_station`; then take their errors into their variances.
    pub fn score(&mut self, bank_ll: f64, z: [f64; 2], naive: &[[f64; 2]], len_m: f64, end_station: &Matrix2<f64>) {
        let keep = (-len_m / self.forgetting_m).exp();
        self.score[0] = self.score[0] * keep + bank_ll;
        for (k, c) in naive.iter().enumerate().take(MEMBERS.len()) {
            let y = Vector2::new(z[0] - c[0], z[1] - c[1]);
            let ll = log_likelihood(&y, &(self.covariance(k, len_m) + end_station));
            self.score[k + 1] = self.score[k + 1] * keep + ll;
        }
        self.sum_weight = self.sum_weight * keep + 1.0;
        self.prior_weight *= keep;
        for (k, c) in naive.iter().enumerate().take(MEMBERS.len()) {
            for d in 0..2 {
                let e = z[d] - c[d];
                let indicated = (e * e - end_station[(d, d)]).max(0.0) / (len_m * len_m);
                self.sum_indicated[k][d] = self.sum_indicated[k][d] * keep + indicated;
            }
        }
    }
}

/// The Gaussian log-likelihood (without the constant) of the residual `y` of covariance `cov`
/// (0 where the covariance is singular).
pub fn log_likelihood(y: &Vector2<f64>, cov: &Matrix2<f64>) -> f64 {
    match cov.try_inverse() {
        Some(inv) => -0.5 * ((y.transpose() * inv * y)[(0, 0)] + cov.determinant().max(1e-300).ln()),
        None => 0.0,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Reference: the likelihood favours the naive member that predicts. The observed
    /// correction is always that of the statistic (1 deg over 30 m toward the right), the
    /// bank's likelihood a poor one (-10 per interval; a well-calibrated member of 1 deg error
    /// scores about +4): after 10 intervals the statistic holds above 0.9 of the weight.
    #[test]
    fn the_member_that_predicts_takes_the_weight() {
        let mut m = NaiveMembers::new(1f64.to_radians() / 30.0, 300.0);
        let r = Matrix2::from_diagonal_element(0.1f64.to_radians().powi(2));
        let stat = [0.0, 1f64.to_radians()];
        for _ in 0..10 {
            m.score(-10.0, stat, &[[0.0; 2], stat, [0.0, -1f64.to_radians()]], 30.0, &r);
        }
        let w = m.weights();
        assert!(w[2] > 0.9, "{w:?}");
    }
}
