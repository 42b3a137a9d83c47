//! Survey stations: measured depth, inclination and azimuth, validated.

use std::f64::consts::{PI, TAU};

/// One survey station, SI: measured depth in m, angles in rad.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Station {
    /// Measured depth along the hole, m.
    pub md_m: f64,
    /// Inclination from vertical-down, rad, in [0, pi].
    pub inc_rad: f64,
    /// Azimuth clockwise from north, rad, normalized to [0, 2 pi).
    pub azi_rad: f64,
}

impl Station {
    /// Station from degrees (for tests and examples); azimuth is normalized.
    pub fn from_deg(md_m: f64, inc_deg: f64, azi_deg: f64) -> Self {
        Self {
            md_m,
            inc_rad: inc_deg.to_radians(),
            azi_rad: normalize_azimuth(azi_deg.to_radians()),
        }
    }
}

/// Wrap an azimuth (rad) into [0, 2 pi).
pub fn normalize_azimuth(azi_rad: f64) -> f64 {
    let a = azi_rad.rem_euclid(TAU);
    if a >= TAU {
        0.0
    } else {
        a
    }
}

/// An angle (deg) wrapped into [0, 360) as it is written with `decimals` decimals: an angle
/// that would be written as 360 (just short of a full turn, e.g. an azimuth of -1e-13 deg) is
/// 0, so that north reads 0 and never 360.
pub fn degrees_in_turn(deg: f64, decimals: i32) -> f64 {
    let d = deg.rem_euclid(360.0);
    if 360.0 - d < 0.5 * 10f64.powi(-decimals) {
        0.0
    } else {
        d
    }
}

/// Decimals to which [`degrees_in_turn`] wraps an angle written with every digit (JSON).
pub const FULL_PRECISION_DECIMALS: i32 = 9;

/// Wrap an angle difference (rad) into (-pi, pi].
pub fn wrap_pi(d: f64) -> f64 {
    let mut a = d.rem_euclid(TAU);
    if a > PI {
        a -= TAU;
    }
    a
}

/// Why a list of stations is not a valid survey; `index` is the 0-based station index.
#[derive(Debug, Clone, PartialEq)]
pub struct SurveyProblem {
    /// 0-based index of the offending station.
    pub index: usize,
    /// Which field: `"md"`, `"inc"` or `"azi"` (empty for the survey as a whole).
    pub field: &'static str,
    /// What is wrong.
    pub message: String,
}

/// A validated survey: at least one station, MD strictly increasing, inclination in [0, 180]
/// degrees, finite azimuth normalized to [0, 360).
#[derive(Debug, Clone, PartialEq)]
pub struct Survey {
    stations: Vec<Station>,
}

impl Survey {
    /// Validate and normalize `stations`.
    pub fn new(mut stations: Vec<Station>) -> Result<Self, SurveyProblem> {
        if stations.is_empty() {
            return Err(SurveyProblem {
                index: 0,
                field: "",
                message: "the survey has no stations".into(),
            });
        }
        for (i, s) in stations.iter_mut().enumerate() {
            if !s.md_m.is_finite() {
                return Err(SurveyProblem {
                    index: i,
                    field: "md",
                    message: "measured depth is not finite".into(),
                });
            }
            if !s.inc_rad.is_finite() || s.inc_rad < -1e-12 || s.inc_rad > PI + 1e-12 {
                return Err(SurveyProblem {
                    index: i,
                    field: "inc",
                    message: format!("inclination {:.4} deg is outside [0, 180] deg", s.inc_rad.to_degrees()),
                });
            }
            s.inc_rad = s.inc_rad.clamp(0.0, PI);
            if !s.azi_rad.is_finite() {
                return Err(SurveyProblem {
                    index: i,
                    field: "azi",
                    message: "azimuth is not finite".into(),
                });
            }
            s.azi_rad = normalize_azimuth(s.azi_rad);
        }
        for i in 1..stations.len() {
            if stations[i].md_m <= stations[i - 1].md_m {
                return Err(SurveyProblem {
                    index: i,
                    field: "md",
                    message: format!(
                        "measured depth {} m does not increase (previous station {} m); MD must strictly increase",
                        stations[i].md_m,
                        stations[i - 1].md_m
                    ),
                });
            }
        }
        Ok(Self { stations })
    }

    /// The stations, in increasing MD.
    pub fn stations(&self) -> &[Station] {
        &self.stations
    }

    /// Number of stations.
    pub fn len(&self) -> usize {
        self.stations.len()
    }

    /// Always false: a survey has at least one station.
    pub fn is_empty(&self) -> bool {
        self.stations.is_empty()
    }

    /// The stations up to and including `md_m` (for tracking from a given depth).
    pub fn truncated(&self, md_m: f64) -> Option<Survey> {
        let st: Vec<Station> = self
            .stations
            .iter()
            .copied()
            .filter(|s| s.md_m <= md_m + 1e-9)
            .collect();
        Survey::new(st).ok()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// An angle just short of a full turn is written as 0 at the decimals it would round to 360
    /// at, and kept where it does not (reference: the rounding of `format!("{:.4}")`).
    #[test]
    fn an_angle_that_would_be_written_as_360_is_0() {
        for (deg, decimals) in [(-1e-13_f64, 4), (359.99996, 4), (359.96, 1), (720.0 - 1e-10, 9)] {
            assert_eq!(
                format!("{:.*}", decimals as usize, deg.rem_euclid(360.0)),
                format!("{:.*}", decimals as usize, 360.0)
            );
            assert_eq!(degrees_in_turn(deg, decimals), 0.0, "{deg} at {decimals} decimals");
        }
        for (deg, decimals, want) in [
            (359.9999, 4, 359.9999),
            (-0.5, 1, 359.5),
            (360.0, 3, 0.0),
            (45.0, 0, 45.0),
        ] {
            assert_eq!(degrees_in_turn(deg, decimals), want, "{deg} at {decimals} decimals");
        }
    }
}
