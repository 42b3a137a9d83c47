//! The tendency filter: a Kalman filter on what the model does not explain of the hole's turn.
//!
//! The hole is observed between measured stations, in steps of about the tracking interval
//! `D` (30 m by default). Over such a step of length `d`, the measured turn (toward the high side
//! and toward the right, rad) is the model's turn plus
//!
//! ```text
//! (b + a) d + J (p - p_lin) + e_new - e_old
//! ```
//!
//! per component, with the state `x = [b_h, b_r, a_h, a_r, e_h, e_r, p_1 .. p_n]`:
//! - `b`: a slow tendency offset (rad/m), a random walk that may drift by a quarter of its prior
//!   standard deviation over the forgetting length ([`SLOW_DRIFT_FRACTION`]);
//! - `a`: the fast fluctuation (rad/m): the mean unexplained curvature of the last step, an
//!   autoregressive process, `a' = phi a + w` with `phi = exp(-d / l_c)` (correlation length
//!   `l_c`); its variance is adapted to the well's own innovations (covariance matching, from
//!   the stations already drilled only);
//! - `e`: the survey error of the last station's direction (rad); each step's turn carries the
//!   difference of its two stations' errors, so consecutive steps share one, which the state
//!   keeps exact;
//! - `p`: bit-rock law parameters in the calibration's unbounded variables, with `J` the
//!   sensitivity of the model's turn to them (by differences of marches) and `p_lin` the values
//!   the model's turn was computed with (the bank's estimate when the interval was predicted;
//!   the caller hands in `z + J p_lin`, see [`super::bank::FilterBank::observe`]).
//!
//! A prediction over `L` from the last station is the model's (started on the measured, noisy
//! direction) corrected by `b L + a G(L) - e`, with `G(L) = d phi (1 - phi^n) / (1 - phi)` over
//! `n` steps of `d = L / n` (`n` the nearest whole number of tracking intervals): the
//! fluctuation fades step by step.

use crate::case::bit_rock::LawParameter;
use crate::case::tracking::TrackingSettings;
use nalgebra::{DMatrix, DVector, Matrix2};

/// Prior weight of the fluctuation variance in its adaptation, in observations.
pub const FLUCTUATION_PRIOR_WEIGHT: f64 = 1.0;

/// Smallest fluctuation standard deviation the adaptation may reach, as a fraction of the prior.
pub const MIN_FLUCTUATION_FRACTION: f64 = 0.05;

/// Drift of the slow offset over the forgetting length, as a fraction of its prior standard
/// deviation (its random-walk intensity is `(f sd)^2 / forgetting length`).
pub const SLOW_DRIFT_FRACTION: f64 = 0.25;

/// A parameter counts as identified when the data shrank its standard deviation below this
/// fraction of the prior's.
pub const IDENTIFIED_BELOW: f64 = 0.5;

/// Index of the slow offset `b` (2 components) in the state.
const B: usize = 0;
/// Index of the fluctuation `a`.
const A: usize = 2;
/// Index of the last station's error `e`.
const E: usize = 4;
/// Index of the first law parameter.
const P: usize = 6;

/// The filter's state and settings.
#[derive(Debug, Clone)]
pub struct TendencyFilter {
    /// State mean `[b, a, e, p..]`.
    x: DVector<f64>,
    /// State covariance.
    p: DMatrix<f64>,
    /// Fluctuation variance per component (h, r), (rad/m)^2, adapted.
    fluctuation_var: [f64; 2],
    /// Prior fluctuation variance, (rad/m)^2.
    prior_fluctuation_var: f64,
    /// Forgetting-weighted sum of the observations' weights in the adaptation.
    sum_weight: f64,
    /// The prior's weight in the adaptation, forgotten like the observations.
    prior_weight: f64,
    /// Forgetting-weighted sum of the fluctuation variances the observations indicate.
    sum_indicated: [f64; 2],
    /// Random-walk intensity of the slow offset, (rad/m)^2 per m.
    slow_intensity: f64,
    /// Correlation length of the fluctuation, m.
    correlation_m: f64,
    /// Tracking interval (the step of the fluctuation's fading), m.
    interval_m: f64,
    /// Forgetting length, m.
    forgetting_m: f64,
    /// The law parameters in the state with their prior means and standard deviations
    /// (unbounded variables).
    parameters: Vec<(LawParameter, f64, f64)>,
}

impl TendencyFilter {
    /// A filter at its prior: no offset, no fluctuation, the first station's error of
    /// covariance `first_station`, `parameters` at their prior means with their standard
    /// deviations (unbounded variables).
    pub fn new(
        settings: &TrackingSettings,
        parameters: &[(LawParameter, f64, f64)],
        first_station: &Matrix2<f64>,
    ) -> TendencyFilter {
        let n = P + parameters.len();
        let mut x = DVector::zeros(n);
        let mut p = DMatrix::zeros(n, n);
        let sb = settings.tendency_sd_rad_per_m;
        let sa = settings.fluctuation_sd_rad_per_m;
        for c in 0..2 {
            p[(B + c, B + c)] = sb * sb;
            p[(A + c, A + c)] = sa * sa;
            for d in 0..2 {
                p[(E + c, E + d)] = first_station[(c, d)];
            }
        }
        for (j, &(_, mean, sd)) in parameters.iter().enumerate() {
            x[P + j] = mean;
            p[(P + j, P + j)] = sd * sd;
        }
        TendencyFilter {
            x,
            p,
            fluctuation_var: [sa * sa; 2],
            prior_fluctuation_var: sa * sa,
            sum_weight: 0.0,
            prior_weight: FLUCTUATION_PRIOR_WEIGHT,
            sum_indicated: [0.0; 2],
            slow_intensity: (SLOW_DRIFT_FRACTION * sb).powi(2) / settings.forgetting_length_m,
            correlation_m: settings.correlation_length_m,
            interval_m: settings.interval_m,
            forgetting_m: settings.forgetting_length_m,
            parameters: parameters.to_vec(),
        }
    }

    /// Number of law parameters in the state.
    pub fn parameter_count(&self) -> usize {
        self.parameters.len()
    }

    /// The fluctuation's fading over one step of `d_m`.
    fn phi(&self, d_m: f64) -> f64 {
        (-d_m / self.correlation_m).exp()
    }

    /// The steps of a prediction over `len_m`: (count, length of each, fading per step).
    fn steps(&self, len_m: f64) -> (usize, f64, f64) {
        let n = ((len_m / self.interval_m).round() as usize).max(1);
        let d = len_m / n as f64;
        (n, d, self.phi(d))
    }

    /// `G(L)`: the turn over `len_m` per unit of the current fluctuation, m.
    fn fade(&self, len_m: f64) -> f64 {
        let (n, d, phi) = self.steps(len_m);
        (1..=n).map(|i| d * phi.powi(i as i32)).sum()
    }

    /// Move to the next step of `d_m` (before observing it): the fluctuation fades and takes
    /// its new innovation, the slow offset random-walks, the parameters drift over the
    /// forgetting length.
    pub fn advance(&mut self, d_m: f64) {
        let phi = self.phi(d_m);
        let n = self.x.len();
        let mut f = DMatrix::identity(n, n);
        for c in 0..2 {
            self.x[A + c] *= phi;
            f[(A + c, A + c)] = phi;
        }
        self.p = &f * &self.p * f.transpose();
        for c in 0..2 {
            self.p[(B + c, B + c)] += self.slow_intensity * d_m;
            self.p[(A + c, A + c)] += self.fluctuation_var[c] * (1.0 - phi * phi);
        }
        for (j, &(_, _, sd)) in self.parameters.iter().enumerate() {
            self.p[(P + j, P + j)] += sd * sd * d_m / self.forgetting_m;
        }
    }

    /// Take in the turn `z` (measured minus the model's, rad, toward the high side and the
    /// right) over the step of `d_m` just advanced to, with `sensitivity` (2 x n, rad per
    /// unbounded unit) of the model's turn to the parameters and `new_station` the survey
    /// noise covariance of the station ending it.
    pub fn observe(&mut self, z: [f64; 2], d_m: f64, sensitivity: &DMatrix<f64>, new_station: &Matrix2<f64>) {
        // augmented with the new station's error as the last two states
        let n = self.x.len();
        let mut xa = DVector::zeros(n + 2);
        xa.rows_mut(0, n).copy_from(&self.x);
        let mut pa = DMatrix::zeros(n + 2, n + 2);
        pa.view_mut((0, 0), (n, n)).copy_from(&self.p);
        for c in 0..2 {
            for d in 0..2 {
                pa[(n + c, n + d)] = new_station[(c, d)];
            }
        }
        let mut h = DMatrix::zeros(2, n + 2);
        for c in 0..2 {
            h[(c, B + c)] = d_m;
            h[(c, A + c)] = d_m;
            h[(c, E + c)] = -1.0;
            h[(c, n + c)] = 1.0;
            for j in 0..self.parameters.len() {
                h[(c, P + j)] = sensitivity[(c, j)];
            }
        }
        let s = &h * &pa * h.transpose();
        let innovation = DVector::from_row_slice(&z) - &h * &xa;
        self.adapt(&innovation, &s, d_m);
        let Some(s_inv) = s.clone().try_inverse() else {
            return;
        };
        let k = &pa * h.transpose() * s_inv;
        xa += &k * innovation;
        let ikh = DMatrix::identity(n + 2, n + 2) - &k * &h;
        pa = &ikh * &pa;
        pa = (&pa + pa.transpose()) * 0.5;
        // the new station's error replaces the old one
        for c in 0..2 {
            xa.swap_rows(E + c, n + c);
            pa.swap_rows(E + c, n + c);
            pa.swap_columns(E + c, n + c);
        }
        self.x = xa.rows(0, n).into_owned();
        self.p = pa.view((0, 0), (n, n)).into_owned();
    }

    /// A new station of survey covariance `new_station` ends the step just advanced to, with no
    /// turn observed over it (the model could not predict it): the state learns nothing, and
    /// the last station's error becomes the new station's, unknown but for its covariance.
    pub fn pass_station(&mut self, new_station: &Matrix2<f64>) {
        let n = self.x.len();
        for c in 0..2 {
            self.x[E + c] = 0.0;
            for j in 0..n {
                self.p[(E + c, j)] = 0.0;
                self.p[(j, E + c)] = 0.0;
            }
        }
        for c in 0..2 {
            for d in 0..2 {
                self.p[(E + c, E + d)] = new_station[(c, d)];
            }
        }
    }

    /// Covariance matching: each observation indicates the fluctuation variance that would
    /// explain its innovation (its square less the rest of its predicted variance, over the
    /// variance one unit of fluctuation variance adds to it); the fluctuation variance is the
    /// mean of these and of the prior (worth [`FLUCTUATION_PRIOR_WEIGHT`] observations at the
    /// start), all forgotten over the forgetting length. The state's fluctuation variance
    /// follows.
    fn adapt(&mut self, innovation: &DVector<f64>, s: &DMatrix<f64>, d_m: f64) {
        let phi = self.phi(d_m);
        let per_var = d_m * d_m * (1.0 - phi * phi);
        let keep = (-d_m / self.forgetting_m).exp();
        self.sum_weight = self.sum_weight * keep + 1.0;
        self.prior_weight *= keep;
        let floor = self.prior_fluctuation_var * MIN_FLUCTUATION_FRACTION * MIN_FLUCTUATION_FRACTION;
        for c in 0..2 {
            let old = self.fluctuation_var[c];
            let rest = s[(c, c)] - old * per_var;
            let indicated = ((innovation[c] * innovation[c] - rest) / per_var).max(0.0);
            self.sum_indicated[c] = self.sum_indicated[c] * keep + indicated;
            let w0 = self.prior_weight;
            let new = ((w0 * self.prior_fluctuation_var + self.sum_indicated[c]) / (w0 + self.sum_weight)).max(floor);
            self.fluctuation_var[c] = new;
            // the fresh part of the state's fluctuation variance follows the new level
            self.p[(A + c, A + c)] += (new - old) * (1.0 - phi * phi);
            self.p[(A + c, A + c)] = self.p[(A + c, A + c)].max(0.0);
        }
    }

    /// The expected correction (toward the high side, toward the right) of a model's turn over
    /// the next `len_m` from the last station, rad: `b L + a G(L) - e`.
    pub fn predicted_turn(&self, len_m: f64) -> [f64; 2] {
        let g = self.fade(len_m);
        [0, 1].map(|c| self.x[B + c] * len_m + self.x[A + c] * g - self.x[E + c])
    }

    /// The expected sideways offset (toward the high side, toward the right) after `len_m`, m:
    /// the integral of the correction's turn.
    pub fn predicted_offset(&self, len_m: f64) -> [f64; 2] {
        let (n, d, phi) = self.steps(len_m);
        [0, 1].map(|c| {
            let fluct: f64 = (1..=n)
                .map(|i| d * phi.powi(i as i32) * (len_m - (i as f64 - 0.5) * d))
                .sum();
            self.x[B + c] * len_m * len_m / 2.0 + self.x[A + c] * fluct - self.x[E + c] * len_m
        })
    }

    /// Covariance of the correction over `len_m` (toward the high side, toward the right),
    /// rad^2: the state's uncertainty through `[L, G(L), -1, J]` and the process noise within
    /// the interval; without the survey noise of the station at its end.
    pub fn turn_covariance(&self, len_m: f64, sensitivity: &DMatrix<f64>) -> Matrix2<f64> {
        let n = self.x.len();
        let g = self.fade(len_m);
        let mut h = DMatrix::zeros(2, n);
        for c in 0..2 {
            h[(c, B + c)] = len_m;
            h[(c, A + c)] = g;
            h[(c, E + c)] = -1.0;
            for j in 0..self.parameters.len() {
                h[(c, P + j)] = sensitivity[(c, j)];
            }
        }
        let hp = &h * &self.p * h.transpose();
        let q = self.process_turn_variance(len_m);
        Matrix2::new(hp[(0, 0)] + q[0], hp[(0, 1)], hp[(1, 0)], hp[(1, 1)] + q[1])
    }

    /// Variance of the turn over `len_m` from the process noise within it: the slow offset's
    /// random walk and the fluctuation's innovations step by step, rad^2.
    pub fn process_turn_variance(&self, len_m: f64) -> [f64; 2] {
        let (n, d, phi) = self.steps(len_m);
        let slow = self.slow_intensity * len_m.powi(3) / 3.0;
        // innovation k (of variance var (1 - phi^2)) reaches steps k..n, weighted phi^(i-k)
        let reach: f64 = (1..=n)
            .map(|k| {
                let s: f64 = (0..=(n - k)).map(|i| phi.powi(i as i32)).sum();
                s * s
            })
            .sum();
        [0, 1].map(|c| slow + self.fluctuation_var[c] * (1.0 - phi * phi) * d * d * reach)
    }

    /// The slow offset (toward the high side, toward the right), rad/m, with its standard
    /// deviations.
    pub fn offset(&self) -> ([f64; 2], [f64; 2]) {
        (
            [self.x[B], self.x[B + 1]],
            [self.p[(B, B)].sqrt(), self.p[(B + 1, B + 1)].sqrt()],
        )
    }

    /// The current fluctuation (toward the high side, toward the right), rad/m.
    pub fn fluctuation(&self) -> [f64; 2] {
        [self.x[A], self.x[A + 1]]
    }

    /// The adapted fluctuation standard deviations, rad/m.
    pub fn fluctuation_sd(&self) -> [f64; 2] {
        self.fluctuation_var.map(f64::sqrt)
    }

    /// The law parameters: (parameter, mean, standard deviation, prior standard deviation) in
    /// unbounded variables.
    pub fn parameters(&self) -> Vec<(LawParameter, f64, f64, f64)> {
        self.parameters
            .iter()
            .enumerate()
            .map(|(j, &(q, _, prior_sd))| (q, self.x[P + j], self.p[(P + j, P + j)].sqrt(), prior_sd))
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn settings() -> TrackingSettings {
        TrackingSettings::default()
    }

    fn noise(sd_rad: f64) -> Matrix2<f64> {
        Matrix2::from_diagonal_element(sd_rad * sd_rad)
    }

    fn none() -> DMatrix<f64> {
        DMatrix::zeros(2, 0)
    }

    /// Reference: a constant hidden offset of 1 deg/30 m toward the right seen through
    /// noiseless 30 m steps: the predicted correction over the next 30 m converges to 1 deg
    /// toward the right (within 3% after 20 steps), none toward the high side.
    #[test]
    fn learns_a_constant_offset() {
        let mut f = TendencyFilter::new(&settings(), &[], &noise(1e-6));
        let k = 1f64.to_radians() / 30.0;
        for _ in 0..20 {
            f.advance(30.0);
            f.observe([0.0, k * 30.0], 30.0, &none(), &noise(1e-6));
        }
        let t = f.predicted_turn(30.0);
        assert!((t[1] / (k * 30.0) - 1.0).abs() < 0.03, "{t:?}");
        assert!(t[0].abs() < 0.03 * k * 30.0, "{t:?}");
    }

    /// Reference: the steps' sums by hand: over one interval `G(D) = D phi`, and the process
    /// variance of one step is `var (1 - phi^2) D^2` plus the slow walk `q D^3 / 3`. Tolerance
    /// 1e-12 relative.
    #[test]
    fn one_step_sums() {
        let s = settings();
        let f = TendencyFilter::new(&s, &[], &noise(1e-3));
        let phi = (-30.0f64 / s.correlation_length_m).exp();
        assert!((f.fade(30.0) / (30.0 * phi) - 1.0).abs() < 1e-12);
        let var = s.fluctuation_sd_rad_per_m.powi(2);
        let q = (SLOW_DRIFT_FRACTION * s.tendency_sd_rad_per_m).powi(2) / s.forgetting_length_m;
        let want = var * (1.0 - phi * phi) * 900.0 + q * 27000.0 / 3.0;
        assert!((f.process_turn_variance(30.0)[0] / want - 1.0).abs() < 1e-12);
    }

    /// Reference: a station error is not a tendency. In a quiet straight hole (fluctuation and
    /// offset priors of 0.1 deg/30 m), one station 0.3 deg off toward the high side: the jump
    /// out and back is read as station errors and a passing fluctuation, not as a lasting
    /// tendency: right after the jump the filter already expects part of it back (a correction
    /// toward the low side); after the return the slow offset stays below 0.02 deg per 30 m,
    /// and two quiet steps later the predicted correction is below 0.02 deg over 30 m.
    #[test]
    fn a_station_error_is_not_taken_for_a_tendency() {
        let sd = 0.1f64.to_radians();
        let quiet = TrackingSettings {
            fluctuation_sd_rad_per_m: 0.1f64.to_radians() / 30.0,
            tendency_sd_rad_per_m: 0.1f64.to_radians() / 30.0,
            ..settings()
        };
        let mut f = TendencyFilter::new(&quiet, &[], &noise(sd));
        for _ in 0..10 {
            f.advance(30.0);
            f.observe([0.0, 0.0], 30.0, &none(), &noise(sd));
        }
        let jump = 0.3f64.to_radians();
        f.advance(30.0);
        f.observe([jump, 0.0], 30.0, &none(), &noise(sd));
        let after_jump = f.predicted_turn(30.0);
        f.advance(30.0);
        f.observe([-jump, 0.0], 30.0, &none(), &noise(sd));
        assert!(after_jump[0] < 0.0, "{after_jump:?}");
        assert!((f.offset().0[0] * 30.0).abs().to_degrees() < 0.02, "{:?}", f.offset());
        for _ in 0..2 {
            f.advance(30.0);
            f.observe([0.0, 0.0], 30.0, &none(), &noise(sd));
        }
        let t = f.predicted_turn(30.0);
        assert!(t[0].abs().to_degrees() < 0.02, "{t:?}");
    }
}
