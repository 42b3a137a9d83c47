//! Settings of survey assimilation (`[tracking]` in the case file), SI.
//!
//! The estimator (`predict::tracking`) corrects the model's predicted hole direction by a
//! tendency it learns from the measured hole behind the bit: a slow offset (what the model
//! does not explain, kept over the forgetting length) and a fast fluctuation (what changes
//! from one stand to the next, such as steering, correlated over the correlation length), and
//! optionally the bit-rock law's parameters. The defaults are typical values, the same for
//! every well; docs/theory.md 9.8 gives the model and docs/guide.md the keys.

use super::bit_rock::LawParameter;

/// Assimilation settings.
#[derive(Debug, Clone, PartialEq)]
pub struct TrackingSettings {
    /// Survey noise of an inclination, rad (1 standard deviation).
    pub inc_noise_rad: f64,
    /// Survey noise of an azimuth at high inclination, rad; the sideways direction error of a
    /// station is `sqrt((azi_noise sin I)^2 + inc_noise^2)`.
    pub azi_noise_rad: f64,
    /// Prior standard deviation of the slow tendency offset, rad/m.
    pub tendency_sd_rad_per_m: f64,
    /// Length over which the slow offset may change by its prior standard deviation (the
    /// estimator's memory), m.
    pub forgetting_length_m: f64,
    /// Prior standard deviation of the fast fluctuation, rad/m (adapted to the well's own
    /// measured fluctuations as the stations come).
    pub fluctuation_sd_rad_per_m: f64,
    /// Correlation length of the fast fluctuation, m.
    pub correlation_length_m: f64,
    /// Hole behind the start that `predict --assimilate` assimilates, m.
    pub window_m: f64,
    /// Shortest interval between the assimilated stations of `predict --assimilate`, m.
    pub interval_m: f64,
    /// Bit-rock law parameters estimated with the tendency (each costs one more march per
    /// interval).
    pub parameters: Vec<LawParameter>,
}

impl Default for TrackingSettings {
    fn default() -> Self {
        let deg = std::f64::consts::PI / 180.0;
        TrackingSettings {
            inc_noise_rad: 0.1 * deg,
            azi_noise_rad: 0.4 * deg,
            tendency_sd_rad_per_m: 2.0 * deg / 30.0,
            forgetting_length_m: 300.0,
            fluctuation_sd_rad_per_m: 1.0 * deg / 30.0,
            correlation_length_m: 30.0,
            window_m: 300.0,
            interval_m: 30.0,
            parameters: Vec::new(),
        }
    }
}
