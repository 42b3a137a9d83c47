//! The ripple of the predicted hole: the deviation of the last chord directions from their
//! trend, which a march at too short a step can grow (docs/performance.md, "Step convergence").

use super::PredictError;
use crate::geometry::Vec3;

/// Trailing length of predicted hole over which the ripple of the hole direction is measured,
/// m: the chord directions of the last steps are fitted by a straight line in MD (the trend)
/// and the ripple is the largest deviation from it (see [`super::Prediction::ripple_deg`]).
pub const RIPPLE_WINDOW_M: f64 = 6.0;

/// Ripple (deg) at which a prediction carries a warning: the end inclination and azimuth move
/// by up to this much with the phase of the ripple.
pub const RIPPLE_WARN_DEG: f64 = 0.15;

/// Ripple (deg) at which a prediction stops with [`PredictError::Ripple`] when it also grew
/// by [`RIPPLE_GROWTH`] over the last [`RIPPLE_GROWTH_LENGTH_M`] (a growing ripple, not the
/// decaying transient of the first steps).
pub const RIPPLE_FAIL_DEG: f64 = 1.0;

/// Growth factor of the ripple over [`RIPPLE_GROWTH_LENGTH_M`] that marks it as growing.
pub const RIPPLE_GROWTH: f64 = 1.5;

/// Length over which the growth of the ripple is judged, m.
pub const RIPPLE_GROWTH_LENGTH_M: f64 = 10.0;

/// Steps per ripple wavelength below which the march damps a ripple: the step suggested when
/// a growing ripple stops a prediction is at least its wavelength over this. Measured
/// (docs/performance.md, "Step convergence"): the 2.3 m ripple of the horizontal example grows
/// at 0.45 m steps (5.1 per wavelength) and decays at 0.5 m (4.6); with its near-bit
/// stabilizer 0.9 m higher, the 3.3 m ripple grows at 0.5 m (6.6) and decays at 0.75 m (4.4).
pub const RIPPLE_STEPS_PER_WAVELENGTH: f64 = 4.0;

/// Step suggested against a ripple of wavelength `wavelength_m` (None: not measured) met at
/// step `step_m`, m: a quarter of the wavelength rounded up to 0.1 m
/// ([`RIPPLE_STEPS_PER_WAVELENGTH`]), at least 1.5 x the step; twice the step and at least
/// 0.5 m without a wavelength.
pub fn ripple_safe_step_m(wavelength_m: Option<f64>, step_m: f64) -> f64 {
    let up = |x: f64| (x * 10.0 - 1e-9).ceil() / 10.0;
    match wavelength_m {
        Some(w) => up(w / RIPPLE_STEPS_PER_WAVELENGTH).max(up(1.5 * step_m)),
        None => up(2.0 * step_m).max(0.5),
    }
}

/// Ripple of the predicted hole at the end of `chords` ((end MD, unit direction) per predicted
/// segment, the first beginning at `start_md`): the chords whose middles lie within
/// [`RIPPLE_WINDOW_M`] of the last end are fitted by a straight line in MD (component-wise) and
/// the ripple is the largest deviation from it, rad (about the angle); with the wavelength,
/// m, from the spacing of the sign changes of the deviations along the largest one (when there
/// are at least three). None until the predicted hole is [`RIPPLE_WINDOW_M`] long.
pub(super) fn ripple(start_md: f64, chords: &[(f64, Vec3)]) -> Option<(f64, Option<f64>)> {
    let end = chords.last()?.0;
    if end - start_md < RIPPLE_WINDOW_M - 1e-9 {
        return None;
    }
    let mut pts: Vec<(f64, Vec3)> = Vec::new();
    for k in (0..chords.len()).rev() {
        let begin = if k == 0 { start_md } else { chords[k - 1].0 };
        let mid = 0.5 * (begin + chords[k].0);
        if mid < end - RIPPLE_WINDOW_M {
            break;
        }
        pts.push((mid, chords[k].1));
    }
    if pts.len() < 4 {
        return None;
    }
    let n = pts.len() as f64;
    let xm = pts.iter().map(|p| p.0).sum::<f64>() / n;
    let vm = pts.iter().fold(Vec3::zeros(), |a, p| a + p.1) / n;
    let sxx: f64 = pts.iter().map(|p| (p.0 - xm).powi(2)).sum();
    let sxv = pts.iter().fold(Vec3::zeros(), |a, p| a + (p.1 - vm) * (p.0 - xm));
    let slope = if sxx > 0.0 { sxv / sxx } else { Vec3::zeros() };
    let dev: Vec<Vec3> = pts.iter().map(|p| p.1 - vm - slope * (p.0 - xm)).collect();
    let (largest, r) = dev
        .iter()
        .enumerate()
        .map(|(i, d)| (i, d.norm()))
        .fold((0, 0.0), |a, x| if x.1 > a.1 { x } else { a });
    let u = dev[largest];
    let crossings: Vec<f64> = pts
        .windows(2)
        .zip(dev.windows(2))
        .filter(|(_, d)| d[0].dot(&u) * d[1].dot(&u) < 0.0)
        .map(|(p, _)| 0.5 * (p[0].0 + p[1].0))
        .collect();
    let wavelength = (crossings.len() >= 3)
        .then(|| 2.0 * (crossings[0] - crossings[crossings.len() - 1]).abs() / (crossings.len() - 1) as f64);
    Some((r, wavelength))
}

/// ", wavelength about X m" or nothing.
pub(super) fn wavelength_text(w: Option<f64>) -> String {
    w.map(|w| format!(", wavelength about {w:.1} m")).unwrap_or_default()
}

/// The ripple of a march, measured after each step.
pub(super) struct RippleWatch {
    /// Start MD of the prediction, m.
    start_md: f64,
    /// Step of the prediction, m.
    step_m: f64,
    /// (bit MD, ripple in rad) after each step.
    history: Vec<(f64, f64)>,
    /// The last ripple (rad) with its wavelength (m).
    pub(super) now: (f64, Option<f64>),
}

impl RippleWatch {
    /// No ripple yet on a march from `start_md` at `step_m`.
    pub(super) fn new(start_md: f64, step_m: f64) -> RippleWatch {
        RippleWatch {
            start_md,
            step_m,
            history: Vec::new(),
            now: (0.0, None),
        }
    }

    /// Measure the ripple after the step ending at `md_m` (`chords` so far); a ripple above
    /// [`RIPPLE_FAIL_DEG`] that grew by [`RIPPLE_GROWTH`] over [`RIPPLE_GROWTH_LENGTH_M`] stops
    /// the march.
    pub(super) fn after_step(&mut self, md_m: f64, chords: &[(f64, Vec3)]) -> Result<(), PredictError> {
        let Some(r) = ripple(self.start_md, chords) else {
            return Ok(());
        };
        let earlier = self
            .history
            .iter()
            .rev()
            .find(|(md, _)| *md <= md_m - RIPPLE_GROWTH_LENGTH_M + 1e-9)
            .map(|x| x.1);
        self.history.push((md_m, r.0));
        self.now = r;
        if let Some(e) = earlier {
            if r.0.to_degrees() >= RIPPLE_FAIL_DEG && r.0 >= RIPPLE_GROWTH * e {
                return Err(PredictError::Ripple {
                    md_m,
                    ripple_deg: r.0.to_degrees(),
                    earlier_deg: e.to_degrees(),
                    wavelength: wavelength_text(r.1),
                    step_m: self.step_m,
                    suggested_m: ripple_safe_step_m(r.1, self.step_m),
                });
            }
        }
        Ok(())
    }

    /// What the ripple may explain of a failing step, with its remedy (empty below
    /// [`RIPPLE_WARN_DEG`]).
    pub(super) fn hint(&self) -> String {
        let r = self.now;
        if r.0.to_degrees() < RIPPLE_WARN_DEG {
            return String::new();
        }
        format!(
            "; the predicted hole ripples around its trend by {:.2} deg{} here: a longer step (at least {} m) damps such a ripple",
            r.0.to_degrees(),
            wavelength_text(r.1),
            ripple_safe_step_m(r.1, self.step_m)
        )
    }

    /// Log a warning when the march ends with a ripple of [`RIPPLE_WARN_DEG`] or more.
    pub(super) fn warn_at_end(&self) {
        if self.now.0.to_degrees() >= RIPPLE_WARN_DEG {
            tracing::warn!(
                "the predicted hole ripples around its trend by {:.2} deg at the end{} (step {} m): the end inclination and azimuth move by up to that much with the ripple's phase",
                self.now.0.to_degrees(),
                wavelength_text(self.now.1),
                self.step_m
            );
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Chords of 0.25 m from MD 100 whose direction turns at `kappa` rad/m in the vertical
    /// plane and carries a ripple `amp * sin(2 pi s / wavelength)` rad sideways.
    fn chords(length: f64, kappa: f64, amp: f64, wavelength: f64) -> Vec<(f64, Vec3)> {
        let n = (length / 0.25).round() as usize;
        (1..=n)
            .map(|k| {
                let mid = 0.25 * (k as f64 - 0.5);
                let a = kappa * mid;
                let r = amp * (2.0 * std::f64::consts::PI * mid / wavelength).sin();
                let d = Vec3::new(a.cos() * r.cos(), r.sin(), a.sin() * r.cos());
                (100.0 + 0.25 * k as f64, d)
            })
            .collect()
    }

    /// Reference: the ripple put in (amplitude and wavelength of a sine on the chord
    /// directions); the sampling at 0.25 m can miss the crest by at most 1 - cos(pi 0.125/2.4)
    /// (3 %), the fit window of 6 m holds 2.5 wavelengths (a few % of the amplitude leak into
    /// the fitted line). A constant-curvature hole of 10 deg/30 m has no ripple: its directions
    /// leave a straight line in MD by kappa^2 L^2 / 8 ~ 2e-4 rad over the window.
    #[test]
    fn ripple_measures_the_put_in_sine_and_ignores_a_steady_turn() {
        let kappa = 10f64.to_radians() / 30.0;
        let (r, w) = ripple(100.0, &chords(20.0, kappa, 0.01, 2.4)).unwrap();
        assert!((r - 0.01).abs() < 0.001, "ripple {r}");
        let w = w.unwrap();
        assert!((w - 2.4).abs() < 0.25, "wavelength {w}");
        let (r, _) = ripple(100.0, &chords(20.0, kappa, 0.0, 2.4)).unwrap();
        assert!(
            r.to_degrees() < 0.01 && r.to_degrees() < RIPPLE_WARN_DEG / 10.0,
            "steady turn: {r}"
        );
        // shorter than the window: not measured
        assert!(ripple(100.0, &chords(RIPPLE_WINDOW_M - 0.5, kappa, 0.01, 2.4)).is_none());
    }

    /// Reference: the rule of [`ripple_safe_step_m`] by hand (quarter wavelength rounded up to
    /// 0.1 m, at least 1.5 x the step; without a wavelength 2 x the step, at least 0.5 m).
    #[test]
    fn safe_step_is_a_quarter_wavelength_rounded_up() {
        assert_eq!(ripple_safe_step_m(Some(2.3), 0.25), 0.6);
        assert_eq!(ripple_safe_step_m(Some(3.3), 0.5), 0.9);
        assert_eq!(ripple_safe_step_m(Some(2.0), 0.4), 0.6);
        assert_eq!(ripple_safe_step_m(Some(1.2), 0.2), 0.3);
        assert_eq!(ripple_safe_step_m(None, 0.2), 0.5);
        assert_eq!(ripple_safe_step_m(None, 0.4), 0.8);
    }
}
