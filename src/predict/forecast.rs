//! One prediction of a case over an interval (`drillpath predict`): the march, or the pair of
//! marches combined by Richardson extrapolation, with what its outputs show: the trajectory
//! rows against the survey stations drilled ahead, the build and walk rates, the tracking
//! errors and the law's parameters at the start.

use super::extrapolate::{predict_extrapolated, StepError};
use super::law::LawParams;
use super::march::{predict, MarchSettings, PredictError, Prediction};
use super::track::{interval_rates, tracking_errors, trajectory_rows, IntervalRates, TrackingErrors, TrajectoryRow};
use super::tracking::project::{project, Projection};
use super::tracking::references::{project as project_reference, Direction, Reference};
use super::tracking::skill::{skill, EndDirections, Skill};
use crate::case::{Case, Level};
use crate::models::checks::lock_up;
use crate::models::lock_up_depth::{lock_up_depth_m, Drag};
use crate::models::softstring;
use crate::models::string_solve::{whirl_warning, BUCKLED_START_WARNING};

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
    /// Correct the march by the tendency assimilated from the hole behind the start, with
    /// bounds ([`crate::predict::tracking::project`], the case's `[tracking]` settings).
    pub assimilate: bool,
}

/// A prediction and what its outputs show, SI.
pub struct Forecast {
    /// The march (the coarse one when extrapolated, with the fine one's bit forces).
    pub prediction: Prediction,
    /// The step error estimated by the extrapolation, when asked for.
    pub step_error: Option<StepError>,
    /// One row per step and per measured station in the interval (assimilated when asked).
    pub rows: Vec<TrajectoryRow>,
    /// The projection of the rows, when assimilating (in the order of `rows`).
    pub projection: Option<Projection>,
    /// The model against the naive projections at the survey stations drilled ahead (None
    /// when there are none).
    pub skill: Option<Skill>,
    /// Build and walk rates and mean bit values over the interval.
    pub rates: IntervalRates,
    /// Errors at the survey stations drilled ahead (None when there are none).
    pub tracking: Option<TrackingErrors>,
    /// The bit-rock law's parameters at the start.
    pub law: LawParams,
    /// The settings the march ran with.
    pub settings: MarchSettings,
    /// What the user must know about the prediction's inputs (e.g. a WOB the string cannot
    /// deliver).
    pub warnings: Vec<String>,
}

impl Forecast {
    /// The plain march's inclination and azimuth (rad) at each row's MD.
    pub fn prediction_rows(&self) -> Vec<(f64, f64)> {
        self.rows
            .iter()
            .map(|r| {
                let p = self.prediction.path.point_at(r.md_m);
                (p.inc_rad, p.azi_rad)
            })
            .collect()
    }
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

/// The model against the references at each measured station below `from` (m) in `rows`
/// (the plain march `plain` and the frozen assimilation of `projection` beside an assimilated
/// model).
fn tracking_skill(
    case: &Case,
    from: f64,
    rows: &[TrajectoryRow],
    plain: &[TrajectoryRow],
    projection: Option<&Projection>,
) -> Option<Skill> {
    let dir = |r: &TrajectoryRow| Direction {
        inc_rad: r.inc_rad,
        azi_rad: r.azi_rad,
    };
    let ends: Vec<EndDirections> = rows
        .iter()
        .enumerate()
        .filter(|(_, r)| r.md_m > from + 1e-6)
        .filter_map(|(k, r)| {
            let (inc_rad, azi_rad) = r.measured?;
            Some(EndDirections {
                length_m: r.md_m - from,
                measured: Direction { inc_rad, azi_rad },
                model: dir(r),
                references: Reference::all().map(|q| project_reference(&case.well.path, from, r.md_m, q)),
                plain: projection.map(|_| dir(&plain[k])),
                frozen: projection.map(|p| p.rows[k].frozen),
            })
        })
        .collect();
    skill(&ends)
}

/// The warning of a prediction whose WOB the string cannot put on the bit at `from_md_m` (the
/// soft string's hook load below zero with the string refitted to that depth: lock-up).
pub fn wob_warning(case: &Case, from_md_m: f64) -> Option<String> {
    let c = case.at_bit_depth(from_md_m);
    let soft = softstring::from_case(&c, softstring::segment_length_m(&c.solver));
    let l = lock_up(&c, Some(soft.hook_load_n), c.operation.wob_n)?;
    Some(format!(
        "with the bit at {from_md_m:.2} m MD, {}; the march used the WOB asked for",
        l.warning(c.operation.mode.name())
    ))
}

/// The warning of a prediction whose string, in the case's operation at its WOB, locks up
/// along the predicted hole after the start and before the end: the lock-up depth there
/// ([`lock_up_depth_m`], the string refitted to the end on the predicted path, by the soft string
/// with the helix's drag: the plain one wherever nothing is helically buckled, and the more
/// restrictive of the two). A string locked up at the start has [`wob_warning`] instead.
pub fn lock_up_ahead_warning(case: &Case, prediction: &Prediction) -> Option<String> {
    let to = prediction.to_md_m;
    let mut c = case.at_bit_depth(to);
    c.well.path = prediction.path.clone();
    let wob = c.operation.wob_n;
    let depth = lock_up_depth_m(&c, wob, Drag::WithHelix).filter(|d| *d > prediction.from_md_m + 1e-6)?;
    Some(format!(
        "along the predicted hole the string locks up once the bit is deeper than {depth:.1} m MD at {:.0} kN WOB while {} (by the {}, the string refitted to each bit depth): the hole predicted beyond it cannot be drilled this way without the surface pushing",
        wob / 1e3,
        c.operation.mode.name(),
        Drag::WithHelix.name()
    ))
}

/// The warnings of a whole-string prediction as `solve` gives them: where its rotating string
/// whirls at the start ([`whirl_warning`]), and from which bit depth on its solves came from the
/// re-solve from the buckled shape ([`BUCKLED_START_WARNING`]).
pub fn whole_string_warnings(prediction: &Prediction) -> Vec<String> {
    let mut w = Vec::new();
    if !prediction.whirl_md_m.is_empty() {
        w.push(format!(
            "with the bit at the start, {}",
            whirl_warning(&prediction.whirl_md_m)
        ));
    }
    if let Some(md) = prediction.buckled_start_md_m {
        w.push(format!(
            "with the bit at {md:.2} m MD {BUCKLED_START_WARNING}; the march went on from that shape"
        ));
    }
    w
}

/// Predict `case` as `req` asks; `on_step` hears the bit MD after each step (of both marches
/// when extrapolating, the coarse one first).
pub fn forecast(case: &Case, req: &ForecastRequest, on_step: &mut dyn FnMut(f64)) -> Result<Forecast, PredictError> {
    let (from, to, settings) = (req.from_md_m, req.to_md_m, &req.settings);
    let mut warnings: Vec<String> = wob_warning(case, from).into_iter().collect();
    let (prediction, step_error) = if req.extrapolate {
        predict_extrapolated(case, from, to, settings, on_step).map(|(p, e)| (p, Some(e)))?
    } else {
        (predict(case, from, to, settings, on_step)?, None)
    };
    warnings.extend(lock_up_ahead_warning(case, &prediction));
    warnings.extend(whole_string_warnings(&prediction));
    let mut rows = trajectory_rows(&prediction, Some(&case.well.path));
    let plain: Vec<TrajectoryRow> = rows.clone();
    let projection = req.assimilate.then(|| {
        let mds: Vec<f64> = rows.iter().map(|r| r.md_m).collect();
        project(case, &prediction, &mds, &case.tracking)
    });
    if let Some(p) = &projection {
        for (r, q) in rows.iter_mut().zip(&p.rows) {
            r.inc_rad = q.direction.inc_rad;
            r.azi_rad = q.direction.azi_rad;
            r.position = q.position;
        }
    }
    let rates = interval_rates(&prediction);
    let tracking = tracking_errors(&rows, from);
    let skill = tracking_skill(case, from, &rows, &plain, projection.as_ref());
    Ok(Forecast {
        step_error,
        rows,
        projection,
        skill,
        rates,
        tracking,
        law: LawParams::at(&case.bit_rock, from),
        settings: *settings,
        warnings,
        prediction,
    })
}
