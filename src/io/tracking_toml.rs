//! The `[tracking]` table of a case file: survey assimilation settings
//! ([`crate::case::tracking::TrackingSettings`]), every value checked and named on error.

use super::toml_reader::Section;
use crate::case::bit_rock::LawParameter;
use crate::case::tracking::TrackingSettings;
use crate::error::InputResult;
use crate::units::Dimension as D;

/// Keys accepted in the tracking table (checked before any is read, so a typo is named).
pub const TRACKING_KEYS: &[&str] = &[
    "survey_noise_inc",
    "survey_noise_azi",
    "tendency_sd",
    "forgetting_length",
    "fluctuation_sd",
    "correlation_length",
    "window",
    "interval",
    "estimate",
];

/// `[tracking]`, the defaults where a key is left out; `survey_length_m` bounds the window.
pub fn read_tracking(s: &Section, survey_length_m: f64) -> InputResult<TrackingSettings> {
    s.check_known(TRACKING_KEYS)?;
    let d = TrackingSettings::default();
    let positive = |key: &str, dim: D, unit: &str, default: f64| -> InputResult<f64> {
        Ok(s.positive(key, dim, unit, false)?.unwrap_or(default))
    };
    // the default window is at most the survey; a window given longer is an error
    let window_m = positive("window", D::Length, "m", d.window_m.min(survey_length_m))?;
    if window_m > survey_length_m + 1e-6 {
        return Err(s.error(
            "window",
            format!("{window_m:.1} m is longer than the survey ({survey_length_m:.1} m of hole)"),
        ));
    }
    let parameters = match s.strings("estimate")? {
        None => d.parameters.clone(),
        Some(names) => names
            .iter()
            .map(|n| {
                LawParameter::parse(n.trim()).ok_or_else(|| {
                    s.error(
                        "estimate",
                        format!("unknown parameter `{n}` (expected {})", LawParameter::NAMES),
                    )
                })
            })
            .collect::<InputResult<Vec<_>>>()?,
    };
    Ok(TrackingSettings {
        inc_noise_rad: positive("survey_noise_inc", D::Angle, "deg", d.inc_noise_rad)?,
        azi_noise_rad: positive("survey_noise_azi", D::Angle, "deg", d.azi_noise_rad)?,
        tendency_sd_rad_per_m: positive("tendency_sd", D::Curvature, "deg/30m", d.tendency_sd_rad_per_m)?,
        forgetting_length_m: positive("forgetting_length", D::Length, "m", d.forgetting_length_m)?,
        fluctuation_sd_rad_per_m: positive("fluctuation_sd", D::Curvature, "deg/30m", d.fluctuation_sd_rad_per_m)?,
        correlation_length_m: positive("correlation_length", D::Length, "m", d.correlation_length_m)?,
        window_m,
        interval_m: positive("interval", D::Length, "m", d.interval_m)?,
        parameters,
    })
}
