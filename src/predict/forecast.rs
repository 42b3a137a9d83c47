//! One prediction of a case over an interval (`drillpath predict`): the march, or the pair of
//! marches combined by Richardson extrapolation, with what its outputs show: the trajectory
//! rows against the survey stations drilled ahead, the build and walk rates, the tracking
//! errors and the law's parameters at the start.

use super::extrapolate::{predict_extrapolated, StepError};
use super::law::LawParams;
use super::march::{predict, MarchSettings, PredictError, Prediction};
use super::track::{interval_rates, tracking_errors, trajectory_rows, IntervalRates, TrackingErrors, TrajectoryRow};
use crate::case::{Case, Level};

/// What to predict.
#[derive(Debug, Clone, Copy)]
pub struct ForecastRequest {
    /// Start MD: the hole is the survey up to here, m.
    pub from_md_m: f64,
    /// End MD, m.
    pub to_md_m: f64,
    /// March settings (step, cut, solver controls).
    pub settings: MarchSettings,
    /// March at the step and at half of it and combine the two ([`predict_extrapolated`]).
    pub extrapolate: bool,
}

/// A prediction and what its outputs show, SI.
pub struct Forecast {
    /// The march (the coarse one when extrapolated, with the fine one's bit forces).
    pub prediction: Prediction,
    /// The step error estimated by the extrapolation, when asked for.
    pub step_error: Option<StepError>,
    /// One row per step and per measured station in the interval.
    pub rows: Vec<TrajectoryRow>,
    /// Build and walk rates and mean bit values over the interval.
    pub rates: IntervalRates,
    /// Errors at the survey stations drilled ahead (None when there are none).
    pub tracking: Option<TrackingErrors>,
    /// The bit-rock law's parameters at the start.
    pub law: LawParams,
    /// The settings the march ran with.
    pub settings: MarchSettings,
}

/// March settings of `case` for the model `level` with an explicit `step_m` and `cut_m`
/// (None: the case's step, the default cut): `bha` and `hybrid` solve the bottom-hole assembly
/// cut where it lies on the wall; `whole` cuts at the string's top (the whole string at every
/// step). `soft` has no bit side forces: None.
pub fn settings_at_level(case: &Case, level: Level, step_m: Option<f64>, cut_m: Option<f64>) -> Option<MarchSettings> {
    let mut s = MarchSettings::from_case(case);
    if let Some(st) = step_m {
        s.step_m = st;
    }
    s.cut_m = match level {
        Level::Soft => return None,
        Level::Whole => Some(case.string.length_m()),
        Level::Bha | Level::Hybrid => cut_m,
    };
    Some(s)
}

/// Predict `case` as `req` asks; `on_step` hears the bit MD after each step (of both marches
/// when extrapolating, the coarse one first).
pub fn forecast(case: &Case, req: &ForecastRequest, on_step: &mut dyn FnMut(f64)) -> Result<Forecast, PredictError> {
    let (from, to, settings) = (req.from_md_m, req.to_md_m, &req.settings);
    let (prediction, step_error) = if req.extrapolate {
        predict_extrapolated(case, from, to, settings, on_step).map(|(p, e)| (p, Some(e)))?
    } else {
        (predict(case, from, to, settings, on_step)?, None)
    };
    let rows = trajectory_rows(&prediction, Some(&case.well.path));
    let rates = interval_rates(&prediction);
    let tracking = tracking_errors(&rows, from);
    Ok(Forecast {
        step_error,
        rows,
        rates,
        tracking,
        law: LawParams::at(&case.bit_rock, from),
        settings: *settings,
        prediction,
    })
}
