//! Survey assimilation over consecutive intervals: each interval is predicted from the
//! measured hole behind it with the tendency filter's correction, then its measured end station
//! updates the filter (no station below an interval's start is used for its prediction).
//! The frozen assimilation runs the same filter on the model's tendency held at its value on
//! the first interval: pure statistics through the filter.

use super::estimator::TendencyFilter;
use super::references::Direction;
use crate::case::bit_rock::LawParameter;
use crate::case::{BitRock, Case, TrackingSettings};
use crate::geometry::frame::{inc_azi, tangent};
use crate::geometry::{Frame, Vec3};
use crate::predict::intervals::{
    intervals as cut_intervals, predict_interval_path, result_of, Interval, IntervalPlan, IntervalResult,
};
use crate::predict::law::deviation;
use crate::predict::march::{MarchSettings, PredictError, WarmStart};
use nalgebra::{DMatrix, Matrix2};

/// Step of the unbounded law parameters in the sensitivity marches.
pub const PARAMETER_STEP: f64 = 0.05;

/// Prior standard deviation of a law parameter in the tracking filter, in the calibration's
/// unbounded variable (beta_b: logistic, about 0.25 in beta near 0.5; walk angle: 10 deg;
/// rock anisotropy: 0.2 in `atanh(2 I_r)`, about 0.1 in I_r).
pub fn prior_sd(p: LawParameter) -> f64 {
    match p {
        LawParameter::LateralDrillability => 1.0,
        LawParameter::WalkAngle => 10f64.to_radians(),
        LawParameter::RockAnisotropy => 0.2,
    }
}

/// One interval of an assimilation.
#[derive(Debug, Clone, Copy)]
pub struct AssimilatedInterval {
    /// The march (with the law as estimated at the interval's start).
    pub plain: IntervalResult,
    /// The assimilated prediction at the end.
    pub assimilated: Direction,
    /// The assimilated position at the end (north, east, TVD), m.
    pub position: Vec3,
    /// The frozen assimilation's prediction at the end.
    pub frozen: Direction,
    /// One standard deviation of the assimilated prediction against the measured end station
    /// (survey noise of both ends included): inclination, rad.
    pub inc_sd_rad: f64,
    /// Same for the azimuth, rad.
    pub azi_sd_rad: f64,
    /// The turn added to the march over the interval (toward the high side, toward the
    /// right), rad.
    pub correction_rad: [f64; 2],
}

/// An assimilation over intervals.
#[derive(Debug)]
pub struct Assimilation {
    /// The intervals predicted.
    pub intervals: Vec<AssimilatedInterval>,
    /// The intervals that could not be predicted, with why.
    pub skipped: Vec<(Interval, PredictError)>,
    /// The filter after the last station.
    pub filter: TendencyFilter,
    /// The model's tendency held by the frozen assimilation (toward the high side, toward the
    /// right), rad/m.
    pub frozen_model_tendency: [f64; 2],
}

impl AssimilatedInterval {
    /// The interval's result with the assimilated direction and position at the end.
    pub fn result(&self) -> IntervalResult {
        IntervalResult {
            inc_rad: self.assimilated.inc_rad,
            azi_rad: self.assimilated.azi_rad,
            position: self.position,
            ..self.plain
        }
    }
}

impl Assimilation {
    /// Share of the measured end inclinations, azimuths and both together that lie within
    /// one standard deviation of the assimilated prediction.
    pub fn coverage(&self) -> [f64; 3] {
        let n = self.intervals.len().max(1) as f64;
        let inside = |f: &dyn Fn(&AssimilatedInterval) -> bool| self.intervals.iter().filter(|i| f(i)).count() as f64;
        let inc = inside(&|i| (i.assimilated.inc_rad - i.plain.interval.measured.0).abs() <= i.inc_sd_rad);
        let azi = inside(&|i| {
            crate::geometry::survey::wrap_pi(i.assimilated.azi_rad - i.plain.interval.measured.1).abs() <= i.azi_sd_rad
        });
        [inc / n, azi / n, (inc + azi) / (2.0 * n)]
    }
}

/// The direction `d` turned by `turn` (toward its high side, toward its right), rad.
pub fn turned(d: &Direction, turn: [f64; 2]) -> Direction {
    let f = Frame::from_tangent(&tangent(d.inc_rad, d.azi_rad), d.azi_rad);
    let t = f.t + f.h * turn[0].tan() + f.r * turn[1].tan();
    let (inc_rad, azi_rad) = inc_azi(&t, d.azi_rad);
    Direction { inc_rad, azi_rad }
}

/// The angles (toward the high side, toward the right) of `d` in the frame of `from`, rad.
pub fn turn_between(from: &Direction, d: &Direction) -> [f64; 2] {
    let f = Frame::from_tangent(&tangent(from.inc_rad, from.azi_rad), from.azi_rad);
    let (h, r) = deviation(&f, &tangent(d.inc_rad, d.azi_rad));
    [h, r]
}

/// Survey noise covariance of one station's direction at inclination `inc_rad` (toward the
/// high side, toward the right), rad^2.
pub fn survey_covariance(settings: &TrackingSettings, inc_rad: f64) -> Matrix2<f64> {
    let si = settings.inc_noise_rad;
    let sr = settings.azi_noise_rad * inc_rad.sin();
    Matrix2::new(si * si, 0.0, 0.0, si * si + sr * sr)
}

/// The case's law with the filter's parameter estimates.
fn law_of(case: &Case, filter: &TendencyFilter) -> BitRock {
    let mut br = case.bit_rock.clone();
    for (p, u, _, _) in filter.parameters() {
        p.set(&mut br, p.natural(u));
    }
    br
}

/// Sensitivity (2 x n) of the end direction of `iv` to the filter's law parameters, by
/// differences of marches started from `warm`, in the frame of the march's end `end`.
fn sensitivity(
    case: &Case,
    filter: &TendencyFilter,
    iv: &Interval,
    settings: &MarchSettings,
    warm: &WarmStart,
    end: &Direction,
) -> Result<DMatrix<f64>, PredictError> {
    let params = filter.parameters();
    let mut j = DMatrix::zeros(2, params.len());
    for (k, &(p, u, _, _)) in params.iter().enumerate() {
        let mut law = law_of(case, filter);
        p.set(&mut law, p.natural(u + PARAMETER_STEP));
        let mut w = warm.clone();
        let pred = predict_interval_path(case, &law, iv, settings, &mut w)?;
        let r = result_of(iv, &pred);
        let t = turn_between(
            end,
            &Direction {
                inc_rad: r.inc_rad,
                azi_rad: r.azi_rad,
            },
        );
        j[(0, k)] = t[0] / PARAMETER_STEP;
        j[(1, k)] = t[1] / PARAMETER_STEP;
    }
    Ok(j)
}

/// The filters of an assimilation and the frozen model tendency, carried over the intervals.
struct Filters {
    filter: TendencyFilter,
    frozen: TendencyFilter,
    frozen_tendency: Option<[f64; 2]>,
}

/// Assimilate the survey of `case` over the consecutive intervals `list`, predicting each with
/// `settings`; `progress` hears (intervals done, intervals).
pub fn assimilate(
    case: &Case,
    list: &[Interval],
    settings: &MarchSettings,
    tracking: &TrackingSettings,
    progress: &mut dyn FnMut(usize, usize),
) -> Assimilation {
    let priors: Vec<(LawParameter, f64, f64)> = tracking
        .parameters
        .iter()
        .map(|&p| (p, p.unbounded(p.value(&case.bit_rock)), prior_sd(p)))
        .collect();
    let mut f = Filters {
        filter: TendencyFilter::new(tracking, &priors),
        frozen: TendencyFilter::new(tracking, &[]),
        frozen_tendency: None,
    };
    let mut out = Vec::with_capacity(list.len());
    let mut skipped = Vec::new();
    let mut warm: WarmStart = None;
    for (k, iv) in list.iter().enumerate() {
        let len = iv.to_md_m - iv.from_md_m;
        match assimilate_interval(case, iv, settings, tracking, &mut f, &mut warm) {
            Ok(a) => out.push(a),
            Err(e) => {
                tracing::warn!(from = iv.from_md_m, to = iv.to_md_m, error = %e, "interval skipped");
                skipped.push((*iv, e));
                f.filter.propagate(len);
                f.frozen.propagate(len);
            }
        }
        progress(k + 1, list.len());
    }
    Assimilation {
        intervals: out,
        skipped,
        frozen_model_tendency: f.frozen_tendency.unwrap_or([0.0; 2]),
        filter: f.filter,
    }
}

/// Warm both filters up on the measured hole behind `start_md` (at most the tracking window,
/// in steps of at least its interval between stations), the model's tendency there taken as
/// `kappa` (rad/m, toward the high side and the right): its value on the first interval, so
/// no march is run for it.
fn warm_up(case: &Case, start_md: f64, kappa: [f64; 2], tracking: &TrackingSettings, f: &mut Filters) {
    let path = &case.well.path;
    let plan = IntervalPlan {
        from_md_m: (start_md - tracking.window_m).max(path.md_start()),
        to_md_m: start_md,
        horizon_m: tracking.interval_m,
    };
    let dir = |md: f64| {
        let p = path.point_at(md);
        Direction {
            inc_rad: p.inc_rad,
            azi_rad: p.azi_rad,
        }
    };
    for iv in cut_intervals(path, &plan) {
        let len = iv.to_md_m - iv.from_md_m;
        let (a, b) = (dir(iv.from_md_m), dir(iv.to_md_m));
        let r = survey_covariance(tracking, a.inc_rad) + survey_covariance(tracking, b.inc_rad);
        for filter in [&mut f.filter, &mut f.frozen] {
            let t = filter.predicted_turn(len);
            let predicted = turned(&a, [kappa[0] * len + t[0], kappa[1] * len + t[1]]);
            let h = filter.observation(len, &DMatrix::zeros(2, filter.parameters().len()));
            filter.update(turn_between(&predicted, &b), len, &h, &r);
            filter.propagate(len);
        }
    }
}

/// Predict one interval with the filters' corrections, then take in its measured end.
fn assimilate_interval(
    case: &Case,
    iv: &Interval,
    settings: &MarchSettings,
    tracking: &TrackingSettings,
    f: &mut Filters,
    warm: &mut WarmStart,
) -> Result<AssimilatedInterval, PredictError> {
    let len = iv.to_md_m - iv.from_md_m;
    let start_warm = warm.clone();
    let pred = predict_interval_path(case, &law_of(case, &f.filter), iv, settings, warm)?;
    let plain = result_of(iv, &pred);
    let march_end = Direction {
        inc_rad: plain.inc_rad,
        azi_rad: plain.azi_rad,
    };
    let j = sensitivity(case, &f.filter, iv, settings, &start_warm, &march_end)?;
    let h = f.filter.observation(len, &j);
    let s = case.well.path.point_at(iv.from_md_m);
    let start = Direction {
        inc_rad: s.inc_rad,
        azi_rad: s.azi_rad,
    };
    let kappa = match f.frozen_tendency {
        Some(k) => k,
        None => {
            let k = turn_between(&start, &march_end).map(|t| t / len);
            f.frozen_tendency = Some(k);
            warm_up(case, iv.from_md_m, k, tracking, f);
            k
        }
    };
    let correction = f.filter.predicted_turn(len);
    let assimilated = turned(&march_end, correction);
    let offset = f.filter.predicted_offset(len);
    let sf = Frame::from_tangent(&s.tangent, s.azi_rad);
    let position = plain.position + sf.h * offset[0] + sf.r * offset[1];
    let ft = f.frozen.predicted_turn(len);
    let frozen = turned(&start, [kappa[0] * len + ft[0], kappa[1] * len + ft[1]]);
    let r = survey_covariance(tracking, start.inc_rad) + survey_covariance(tracking, assimilated.inc_rad);
    let cov = f.filter.turn_covariance(len, &h) + r;
    let measured = Direction {
        inc_rad: iv.measured.0,
        azi_rad: iv.measured.1,
    };
    let out = AssimilatedInterval {
        plain,
        assimilated,
        position,
        frozen,
        inc_sd_rad: cov[(0, 0)].sqrt(),
        azi_sd_rad: (cov[(1, 1)].sqrt() / assimilated.inc_rad.sin().max(1e-6)).min(std::f64::consts::PI),
        correction_rad: correction,
    };
    f.filter.update(turn_between(&assimilated, &measured), len, &h, &r);
    f.filter.propagate(len);
    let hf = f.frozen.observation(len, &DMatrix::zeros(2, 0));
    f.frozen.update(turn_between(&frozen, &measured), len, &hf, &r);
    f.frozen.propagate(len);
    Ok(out)
}
