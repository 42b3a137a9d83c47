//! Richardson extrapolation of a prediction in the step length.
//!
//! Where the march's error goes with the square of the step, combining the same prediction at
//! steps `h` and `h/2` cancels the leading term:
//!
//! ```text
//! t = normalize((4 t_{h/2} - t_h) / 3)      (hole tangent at each station of the coarse march)
//! ```
//!
//! and `|t_{h/2} - t_h| / 3` estimates the error left in the fine march. The
//! [`StepScheme::Chord`](super::march::StepScheme::Chord) march is in that regime (j-shape
//! example over 100 m: the end inclination moves by 2.55, 0.71 and 0.16 deg between steps of 2,
//! 1, 0.5 and 0.25 m, ratios 3.6 and 4.4; the extrapolation of 1 m and 0.5 m lands within
//! 0.03 deg of the 0.5/0.25 m one). The default
//! [`StepScheme::Arc`](super::march::StepScheme::Arc) march is already within about 0.02 deg
//! of the step limit at 1 m on the examples (docs/performance.md), where its remaining error is
//! not dominated by the step^2 term: there the extrapolation gains little and its estimate is
//! mainly a check that the step is fine enough. The extrapolated hole is the minimum-curvature
//! path through the extrapolated stations (positions follow from the tangents, as for a
//! survey); the bit forces are those of the fine march.

use super::march::{PredictError, Prediction, StepRecord};
use super::track::bit_at;
use crate::geometry::frame::inc_azi;
use crate::geometry::{Station, Survey, WellPath};

/// The step-error estimate of an extrapolated prediction, rad.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StepError {
    /// Coarse step, m.
    pub coarse_step_m: f64,
    /// Fine step, m.
    pub fine_step_m: f64,
    /// Largest |fine - coarse| / 3 inclination over the stations: the estimated step error of
    /// the fine march (the extrapolation removes most of it), rad.
    pub max_inc_rad: f64,
    /// Largest azimuth estimate, rad (wrapped differences; the azimuth of a near-vertical hole
    /// is not counted below 1 deg of inclination).
    pub max_azi_rad: f64,
}

/// Combine predictions over the same interval at steps `coarse_step_m` and half of it (`fine`)
/// into the extrapolated prediction and its step-error estimate; `start` is the hole before the
/// prediction (its stations are kept). Fails only if the extrapolated stations do not make a
/// survey (not expected: the MDs are those of the coarse march).
pub fn richardson(
    start: &WellPath,
    coarse: &Prediction,
    fine: &Prediction,
    coarse_step_m: f64,
) -> Result<(Prediction, StepError), PredictError> {
    let mut stations: Vec<Station> = start
        .stations()
        .iter()
        .copied()
        .filter(|s| s.md_m < coarse.from_md_m - 1e-9)
        .collect();
    let mut est = StepError {
        coarse_step_m,
        fine_step_m: coarse_step_m / 2.0,
        max_inc_rad: 0.0,
        max_azi_rad: 0.0,
    };
    for r in &coarse.steps {
        let c = coarse.path.point_at(r.md_m);
        let f = fine.path.point_at(r.md_m);
        let t = (f.tangent * 4.0 - c.tangent) / 3.0;
        let (inc, azi) = inc_azi(&t, f.azi_rad);
        stations.push(Station {
            md_m: r.md_m,
            inc_rad: inc,
            azi_rad: azi,
        });
        est.max_inc_rad = est.max_inc_rad.max((f.inc_rad - c.inc_rad).abs() / 3.0);
        if f.inc_rad.min(c.inc_rad) > 1f64.to_radians() {
            let d = crate::geometry::survey::wrap_pi(f.azi_rad - c.azi_rad);
            est.max_azi_rad = est.max_azi_rad.max(d.abs() / 3.0);
        }
    }
    let survey = Survey::new(stations).map_err(|p| PredictError::Geometry(p.message))?;
    let path = WellPath::new(&survey, start.station_position(0)).map_err(|p| PredictError::Geometry(p.message))?;
    let steps = coarse
        .steps
        .iter()
        .map(|r| {
            let p = path.point_at(r.md_m);
            let bit = bit_at(&fine.steps, r.md_m);
            StepRecord {
                md_m: r.md_m,
                inc_rad: p.inc_rad,
                azi_rad: p.azi_rad,
                position: p.position,
                bit,
                direction: p.tangent,
                iterations: r.iterations,
                steer: r.steer,
                reactive_turn_rad: r.reactive_turn_rad,
            }
        })
        .collect();
    Ok((
        Prediction {
            path,
            steps,
            from_md_m: coarse.from_md_m,
            to_md_m: coarse.to_md_m,
            cut_m: fine.cut_m,
            dofs: fine.dofs,
            iterations: coarse.iterations + fine.iterations,
            seconds: coarse.seconds + fine.seconds,
            start_warm: coarse.start_warm.clone(),
            ripple_deg: coarse.ripple_deg.max(fine.ripple_deg),
            whirl_md_m: coarse.whirl_md_m.clone(),
            buckled_start_md_m: match (coarse.buckled_start_md_m, fine.buckled_start_md_m) {
                (Some(a), Some(b)) => Some(a.min(b)),
                (a, b) => a.or(b),
            },
        },
        est,
    ))
}

/// Predict `case` from `from_md_m` to `to_md_m` at the step of `settings` and at half of it,
/// and combine the two by [`richardson`]; `on_step` hears the bit MDs of both marches (the
/// coarse one first).
pub fn predict_extrapolated(
    case: &crate::case::Case,
    from_md_m: f64,
    to_md_m: f64,
    settings: &super::march::MarchSettings,
    on_step: &mut dyn FnMut(f64),
) -> Result<(Prediction, StepError), PredictError> {
    let start = super::march::hole_to(&case.well.path, from_md_m)?;
    // the fine march runs at half the step: no silent change of either
    let h = settings.step_m;
    if h.is_nan() || h / 2.0 < super::march::MIN_STEP_M - 1e-9 {
        return Err(PredictError::StepTooShort { step_m: h / 2.0 });
    }
    let coarse_settings = super::march::MarchSettings { step_m: h, ..*settings };
    let fine_settings = super::march::MarchSettings {
        step_m: h / 2.0,
        ..*settings
    };
    let coarse = super::march::predict_from(
        case,
        &case.bit_rock,
        &start,
        to_md_m,
        &coarse_settings,
        &mut None,
        on_step,
    )?;
    let fine = super::march::predict_from(
        case,
        &case.bit_rock,
        &start,
        to_md_m,
        &fine_settings,
        &mut None,
        on_step,
    )?;
    richardson(&start, &coarse, &fine, h)
}
