//! The tendency filter: a Kalman filter on what the model does not explain of the hole's turn.
//!
//! The measured turn of an interval of length `L`, in the frame of the predicted direction at
//! its end (components toward the high side and toward the right, rad), is the model's turn plus
//!
//! ```text
//! turn = b L + a g(L) + J dp + process noise within the interval + survey noise,
//! g(L) = l_c (1 - exp(-L / l_c))
//! ```
//!
//! per component, with the state `x = [b_h, b_r, a_h, a_r, p_1 .. p_n]`:
//! - `b`: a slow tendency offset (rad/m), a random walk that may change by its prior standard
//!   deviation over the forgetting length;
//! - `a`: a fast fluctuation (rad/m), an Ornstein-Uhlenbeck process with correlation length
//!   `l_c` (what changes from one stand to the next, steering above all); its variance is
//!   adapted to the well's own innovations (covariance matching, from the stations already
//!   drilled only);
//! - `p`: bit-rock law parameters in the calibration's unbounded variables, with `J` the
//!   sensitivity of the predicted end direction to them (by differences of marches).
//!
//! Survey noise enters from both ends of the interval (the march starts on the measured
//! direction at its start). A prediction ahead uses the state's mean: `b L + a g(L)`, the fast
//! part fading over the correlation length.

use crate::case::bit_rock::LawParameter;
use crate::case::tracking::TrackingSettings;
use nalgebra::{DMatrix, DVector, Matrix2};

/// Prior weight of the fluctuation variance in its adaptation, in intervals.
pub const FLUCTUATION_PRIOR_WEIGHT: f64 = 3.0;

/// Smallest fluctuation standard deviation the adaptation may reach, as a fraction of the prior.
pub const MIN_FLUCTUATION_FRACTION: f64 = 0.05;

/// A parameter counts as identified when the data shrank its standard deviation below this
/// fraction of the prior's.
pub const IDENTIFIED_BELOW: f64 = 0.5;

/// `l (1 - exp(-L / l))`, m: the integral over `L` of a fluctuation fading over `l`.
pub fn fade(l_m: f64, len_m: f64) -> f64 {
    l_m * (1.0 - (-len_m / l_m).exp())
}

/// Variance of the turn over `L` from an Ornstein-Uhlenbeck fluctuation of variance `var` and
/// correlation length `l`, given its value at the start: `var l^2 (2x - 3 + 4 e^-x - e^-2x)`,
/// `x = L / l`.
fn fluctuation_turn_variance(var: f64, l_m: f64, len_m: f64) -> f64 {
    let x = len_m / l_m;
    var * l_m * l_m * (2.0 * x - 3.0 + 4.0 * (-x).exp() - (-2.0 * x).exp()).max(0.0)
}

/// The filter's state and settings.
#[derive(Debug, Clone)]
pub struct TendencyFilter {
    /// State mean `[b_h, b_r, a_h, a_r, p..]`.
    x: DVector<f64>,
    /// State covariance.
    p: DMatrix<f64>,
    /// Fluctuation variance per component (h, r), (rad/m)^2, adapted.
    fluctuation_var: [f64; 2],
    /// Prior fluctuation variance, (rad/m)^2.
    prior_fluctuation_var: f64,
    /// Forgetting-weighted sum of the innovations' weights in the adaptation.
    sum_weight: f64,
    /// Forgetting-weighted sum of the fluctuation variances the innovations indicate, per
    /// component.
    sum_indicated: [f64; 2],
    /// Random-walk intensity of the slow offset, (rad/m)^2 per m.
    slow_intensity: f64,
    /// Correlation length of the fluctuation, m.
    correlation_m: f64,
    /// Forgetting length, m.
    forgetting_m: f64,
    /// The law parameters in the state, with their prior means and standard deviations
    /// (unbounded variables).
    parameters: Vec<(LawParameter, f64, f64)>,
}

impl TendencyFilter {
    /// A filter at its prior: no offset, no fluctuation, `parameters` at their `prior_means`
    /// (unbounded variables) with standard deviations `prior_sds`.
    pub fn new(settings: &TrackingSettings, parameters: &[(LawParameter, f64, f64)]) -> TendencyFilter {
        let n = 4 + parameters.len();
        let mut x = DVector::zeros(n);
        let mut p = DMatrix::zeros(n, n);
        let sb = settings.tendency_sd_rad_per_m;
        let sa = settings.fluctuation_sd_rad_per_m;
        for c in 0..2 {
            p[(c, c)] = sb * sb;
            p[(2 + c, 2 + c)] = sa * sa;
        }
        for (j, &(_, mean, sd)) in parameters.iter().enumerate() {
            x[4 + j] = mean;
            p[(4 + j, 4 + j)] = sd * sd;
        }
        TendencyFilter {
            x,
            p,
            fluctuation_var: [sa * sa; 2],
            prior_fluctuation_var: sa * sa,
            sum_weight: 0.0,
            sum_indicated: [0.0; 2],
            slow_intensity: sb * sb / settings.forgetting_length_m,
            correlation_m: settings.correlation_length_m,
            forgetting_m: settings.forgetting_length_m,
            parameters: parameters.to_vec(),
        }
    }

    /// The expected extra turn (h, r) over the next `len_m` of hole, rad.
    pub fn predicted_turn(&self, len_m: f64) -> [f64; 2] {
        let g = fade(self.correlation_m, len_m);
        [self.x[0] * len_m + self.x[2] * g, self.x[1] * len_m + self.x[3] * g]
    }

    /// The expected extra sideways offset (h, r) after `len_m`, m: the integral of the turn.
    pub fn predicted_offset(&self, len_m: f64) -> [f64; 2] {
        let l = self.correlation_m;
        let gi = l * (len_m - fade(l, len_m));
        [
            self.x[0] * len_m * len_m / 2.0 + self.x[2] * gi,
            self.x[1] * len_m * len_m / 2.0 + self.x[3] * gi,
        ]
    }

    /// Observation matrix of the turn over `len_m` (2 x state): `[L I, g I, J]`, `J` the 2 x n
    /// sensitivity of the end direction to the parameters (rad per unbounded unit).
    pub fn observation(&self, len_m: f64, sensitivity: &DMatrix<f64>) -> DMatrix<f64> {
        let n = self.x.len();
        let g = fade(self.correlation_m, len_m);
        let mut h = DMatrix::zeros(2, n);
        for c in 0..2 {
            h[(c, c)] = len_m;
            h[(c, 2 + c)] = g;
        }
        for j in 0..self.parameters.len() {
            for c in 0..2 {
                h[(c, 4 + j)] = sensitivity[(c, j)];
            }
        }
        h
    }

    /// Variance of the turn over `len_m` from the process noise within it (slow random walk
    /// and fluctuation), per component, rad^2.
    pub fn process_turn_variance(&self, len_m: f64) -> [f64; 2] {
        let slow = self.slow_intensity * len_m.powi(3) / 3.0;
        [0, 1].map(|c| slow + fluctuation_turn_variance(self.fluctuation_var[c], self.correlation_m, len_m))
    }

    /// Covariance of the predicted turn (h, r) over `len_m` with observation matrix `h`,
    /// without survey noise, rad^2.
    pub fn turn_covariance(&self, len_m: f64, h: &DMatrix<f64>) -> Matrix2<f64> {
        let hp = h * &self.p * h.transpose();
        let q = self.process_turn_variance(len_m);
        Matrix2::new(hp[(0, 0)] + q[0], hp[(0, 1)], hp[(1, 0)], hp[(1, 1)] + q[1])
    }

    /// Take in the innovation `y` (measured - predicted turn, (h, r), rad) of an interval of
    /// `len_m` with observation matrix `h` and survey noise covariance `r`, and adapt the
    /// fluctuation variance to it.
    pub fn update(&mut self, y: [f64; 2], len_m: f64, h: &DMatrix<f64>, r: &Matrix2<f64>) {
        self.adapt(y, len_m, &(self.turn_covariance(len_m, h) + r));
        let hph = h * &self.p * h.transpose();
        let q = self.process_turn_variance(len_m);
        // the noise not in the state: survey noise and the process noise within the interval
        let noise = DMatrix::from_row_slice(2, 2, &[r[(0, 0)] + q[0], r[(0, 1)], r[(1, 0)], r[(1, 1)] + q[1]]);
        let s = &hph + &noise;
        let Some(s_inv) = s.try_inverse() else {
            return;
        };
        let k = &self.p * h.transpose() * s_inv;
        self.x += &k * DVector::from_row_slice(&y);
        let n = self.x.len();
        // Joseph form: keeps P symmetric and positive
        let ikh = DMatrix::identity(n, n) - &k * h;
        self.p = &ikh * &self.p * ikh.transpose() + &k * noise * k.transpose();
        self.p = (&self.p + self.p.transpose()) * 0.5;
    }

    /// Covariance matching: each innovation indicates the fluctuation variance that would
    /// explain it (its square less the rest of its predicted variance, over the variance one
    /// unit of fluctuation variance adds); the fluctuation variance is the mean of these, weighted
    /// with [`FLUCTUATION_PRIOR_WEIGHT`] intervals at the prior and forgotten over the
    /// forgetting length.
    fn adapt(&mut self, y: [f64; 2], len_m: f64, s: &Matrix2<f64>) {
        let g = fade(self.correlation_m, len_m);
        let per_var = fluctuation_turn_variance(1.0, self.correlation_m, len_m);
        let keep = (-len_m / self.forgetting_m).exp();
        self.sum_weight = self.sum_weight * keep + 1.0;
        let floor = self.prior_fluctuation_var * MIN_FLUCTUATION_FRACTION * MIN_FLUCTUATION_FRACTION;
        for c in 0..2 {
            let old = self.fluctuation_var[c];
            // share of the state's fluctuation variance still unknown
            let unknown = (self.p[(2 + c, 2 + c)] / old).clamp(0.0, 1.0);
            let d = per_var + g * g * unknown;
            let rest = s[(c, c)] - old * d;
            let indicated = ((y[c] * y[c] - rest) / d).max(0.0);
            self.sum_indicated[c] = self.sum_indicated[c] * keep + indicated;
            let w0 = FLUCTUATION_PRIOR_WEIGHT;
            let new = ((w0 * self.prior_fluctuation_var + self.sum_indicated[c]) / (w0 + self.sum_weight)).max(floor);
            self.fluctuation_var[c] = new;
            // the state's fluctuation variance follows
            self.p[(2 + c, 2 + c)] *= new / old;
        }
    }

    /// Move the state over `len_m` of hole: the slow offset random-walks, the fluctuation fades
    /// toward zero, the parameters drift over the forgetting length.
    pub fn propagate(&mut self, len_m: f64) {
        let n = self.x.len();
        let phi = (-len_m / self.correlation_m).exp();
        for c in 0..2 {
            self.x[2 + c] *= phi;
        }
        let mut f = DMatrix::identity(n, n);
        f[(2, 2)] = phi;
        f[(3, 3)] = phi;
        self.p = &f * &self.p * f.transpose();
        for c in 0..2 {
            self.p[(c, c)] += self.slow_intensity * len_m;
            self.p[(2 + c, 2 + c)] += self.fluctuation_var[c] * (1.0 - phi * phi);
        }
        for (j, &(_, _, sd)) in self.parameters.iter().enumerate() {
            self.p[(4 + j, 4 + j)] += sd * sd * len_m / self.forgetting_m;
        }
    }

    /// The slow offset (h, r), rad/m, with its standard deviations.
    pub fn offset(&self) -> ([f64; 2], [f64; 2]) {
        ([self.x[0], self.x[1]], [self.p[(0, 0)].sqrt(), self.p[(1, 1)].sqrt()])
    }

    /// The adapted fluctuation standard deviations (h, r), rad/m.
    pub fn fluctuation_sd(&self) -> [f64; 2] {
        self.fluctuation_var.map(f64::sqrt)
    }

    /// The law parameters: (parameter, mean, standard deviation, prior standard deviation) in
    /// unbounded variables.
    pub fn parameters(&self) -> Vec<(LawParameter, f64, f64, f64)> {
        self.parameters
            .iter()
            .enumerate()
            .map(|(j, &(q, _, prior_sd))| (q, self.x[4 + j], self.p[(4 + j, 4 + j)].sqrt(), prior_sd))
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn settings() -> TrackingSettings {
        TrackingSettings::default()
    }

    /// Reference: the limits of the Ornstein-Uhlenbeck integral: the conditional variance of
    /// the turn over L tends to `2 var l L` for L >> l (a random walk of intensity `2 var l`) and
    /// to `2 var L^3 / (3 l)` for L << l (the integral of the fluctuation's own random walk, of
    /// intensity `2 var / l`). Tolerance 2%.
    #[test]
    fn fluctuation_turn_variance_limits() {
        let (var, l) = (1.0, 30.0);
        let long = fluctuation_turn_variance(var, l, 3000.0);
        assert!((long / (2.0 * l * 3000.0) - 1.0).abs() < 0.02, "{long}");
        let short = fluctuation_turn_variance(var, l, 0.3);
        assert!(
            (short / (2.0 * 0.3f64.powi(3) / (3.0 * l)) - 1.0).abs() < 0.02,
            "{short}"
        );
    }

    /// Reference: a constant hidden offset of 1 deg/30 m toward the right seen through
    /// noiseless 30 m intervals: the filter's slow offset converges to it (within 5% after 20
    /// intervals) and its predicted turn over 30 m to 1 deg.
    #[test]
    fn learns_a_constant_offset() {
        let mut f = TendencyFilter::new(&settings(), &[]);
        let k = 1f64.to_radians() / 30.0;
        let r = Matrix2::from_diagonal_element(1e-10);
        for _ in 0..20 {
            let h = f.observation(30.0, &DMatrix::zeros(2, 0));
            let pred = f.predicted_turn(30.0);
            f.update([0.0 - pred[0], k * 30.0 - pred[1]], 30.0, &h, &r);
            f.propagate(30.0);
        }
        let t = f.predicted_turn(30.0);
        assert!((t[1] / (k * 30.0) - 1.0).abs() < 0.05, "{:?}", t);
        assert!(t[0].abs() < 0.05 * k * 30.0);
    }

    /// Reference: with pure survey noise (no tendency) the innovations indicate no fluctuation,
    /// and the adapted fluctuation variance falls to the prior's share of the weights:
    /// `3 / (3 + 1 / (1 - exp(-30/300)))` = 0.22 of the prior variance (0.47 of its standard
    /// deviation) after many 30 m intervals; the predicted turn stays within a tenth of a degree.
    #[test]
    fn noise_alone_shrinks_the_fluctuation() {
        let s = settings();
        let mut f = TendencyFilter::new(&s, &[]);
        let sd = 0.1f64.to_radians();
        let r = Matrix2::from_diagonal_element(2.0 * sd * sd);
        // a deterministic +-1 sd sequence
        for k in 0..40 {
            let e = if k % 2 == 0 { sd } else { -sd };
            let h = f.observation(30.0, &DMatrix::zeros(2, 0));
            let pred = f.predicted_turn(30.0);
            f.update([e - pred[0], -e - pred[1]], 30.0, &h, &r);
            f.propagate(30.0);
        }
        let fl = f.fluctuation_sd();
        let share = (3.0 / (3.0 + 1.0 / (1.0 - (-0.1f64).exp()))).sqrt();
        assert!(
            (fl[0] / s.fluctuation_sd_rad_per_m - share).abs() < 0.02,
            "{fl:?} {share}"
        );
        let t = f.predicted_turn(30.0);
        assert!(t[0].abs().to_degrees() < 0.1 && t[1].abs().to_degrees() < 0.1, "{t:?}");
    }
}
