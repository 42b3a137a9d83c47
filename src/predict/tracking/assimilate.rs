//! Survey assimilation over consecutive intervals: each interval is predicted from the
//! measured hole behind it with the tendency filter's correction, then its measured end station
//! updates the filter (no station below an interval's start is used for its prediction).
//! The frozen assimilation runs the same filter on the model's tendency held at its value on
//! the first interval: pure statistics through the filter.

use super::bank::{FilterBank, Situation, REVERSION_M};
use super::experts::{Naive, MEMBERS};
use super::references::{self, Direction};
use crate::case::bit_rock::LawParameter;
use crate::case::{BitRock, Case, TrackingSettings};
use crate::geometry::frame::{inc_azi, tangent};
use crate::geometry::{Frame, Vec3, WellPath};
use crate::predict::intervals::{
    predict_interval_path, result_of, Interval, IntervalResult, LastEnd, RunModel, DEFAULT_MIN_INCLINATION_DEG,
};
use crate::predict::law::deviation;
use crate::predict::march::{PredictError, WarmStart};
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
    pub filter: FilterBank,
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

/// The naive members' corrections (toward the high side, toward the right, rad, in the order of
/// [`MEMBERS`]) of the prediction `base` at `to_md`, the members projecting from the measured
/// `path` at and behind `from_md` (m) only.
pub fn naive_corrections(path: &WellPath, from_md: f64, to_md: f64, base: &Direction) -> Vec<[f64; 2]> {
    MEMBERS
        .iter()
        .map(|m| match m {
            Naive::NoCorrection => [0.0; 2],
            Naive::Reference(r) => turn_between(base, &references::project(path, from_md, to_md, *r)),
        })
        .collect()
}

/// Survey noise covariance of one station's direction at inclination `inc_rad` (toward the
/// high side, toward the right), rad^2.
pub fn survey_covariance(settings: &TrackingSettings, inc_rad: f64) -> Matrix2<f64> {
    let si = settings.inc_noise_rad;
    let sr = settings.azi_noise_rad * inc_rad.sin();
    Matrix2::new(si * si, 0.0, 0.0, si * si + sr * sr)
}

/// The case's law with the law parameters `parameters` at the unbounded values `u`.
fn law_of(case: &Case, parameters: &[LawParameter], u: &[f64]) -> BitRock {
    law_stepped(case, parameters, u, None)
}

/// As [`law_of`], with parameter `k` stepped by [`PARAMETER_STEP`] when `step` is `Some(k)`.
fn law_stepped(case: &Case, parameters: &[LawParameter], u: &[f64], step: Option<usize>) -> BitRock {
    let mut br = case.bit_rock.clone();
    for (k, (p, u)) in parameters.iter().zip(u).enumerate() {
        let du = if step == Some(k) { PARAMETER_STEP } else { 0.0 };
        p.set(&mut br, p.natural(u + du));
    }
    br
}

/// The runs `runs` predicting with the laws `laws` (one per run).
fn with_laws<'a>(runs: &[RunModel<'a>], laws: &'a [BitRock]) -> Vec<RunModel<'a>> {
    runs.iter()
        .zip(laws)
        .map(|(r, law)| RunModel { bit_rock: law, ..*r })
        .collect()
}

/// The direction of `path` at `md_m`.
fn direction_at(path: &WellPath, md_m: f64) -> Direction {
    let p = path.point_at(md_m);
    Direction {
        inc_rad: p.inc_rad,
        azi_rad: p.azi_rad,
    }
}

/// The marches of `iv` by `runs` with the law `parameters` at `u` (unbounded), each stepped in
/// turn by [`PARAMETER_STEP`], started from `warm`.
fn stepped_marches(
    runs: &[RunModel],
    (parameters, u): (&[LawParameter], &[f64]),
    iv: &Interval,
    warm: &WarmStart,
) -> Result<Vec<WellPath>, PredictError> {
    (0..parameters.len())
        .map(|k| {
            let laws: Vec<BitRock> = runs
                .iter()
                .map(|r| law_stepped(r.case, parameters, u, Some(k)))
                .collect();
            let mut w = warm.clone();
            Ok(predict_interval_path(&with_laws(runs, &laws), iv, &mut w)?.path)
        })
        .collect()
}

/// Sensitivity (2 x n, rad per unbounded unit) of the turn from `from_md` to `to_md` to the law
/// parameters: the turns of the stepped marches `stepped` against the march `path`'s.
fn turn_sensitivity(path: &WellPath, stepped: &[WellPath], from_md: f64, to_md: f64) -> DMatrix<f64> {
    let base = turn_between(&direction_at(path, from_md), &direction_at(path, to_md));
    let mut j = DMatrix::zeros(2, stepped.len());
    for (k, sp) in stepped.iter().enumerate() {
        let t = turn_between(&direction_at(sp, from_md), &direction_at(sp, to_md));
        for c in 0..2 {
            j[(c, k)] = (t[c] - base[c]) / PARAMETER_STEP;
        }
    }
    j
}

/// The model's side of the steps taken in: its turn (none where the model could not predict the
/// hole: the assimilated bank then takes the stations in without observing a turn) and its
/// sensitivity to the law parameters between two MDs, and its tendency held (rad/m) for the
/// frozen bank.
struct ModelSide<'a> {
    turn: Option<&'a dyn Fn(f64, f64) -> [f64; 2]>,
    sensitivity: &'a dyn Fn(f64, f64) -> DMatrix<f64>,
    kappa: [f64; 2],
}

/// The model's turn with its tendency `kappa` (rad/m) held.
fn held_turn(kappa: [f64; 2]) -> impl Fn(f64, f64) -> [f64; 2] {
    move |a: f64, b: f64| [kappa[0] * (b - a), kappa[1] * (b - a)]
}

/// No sensitivity to the `np` law parameters.
fn no_sensitivity(np: usize) -> impl Fn(f64, f64) -> DMatrix<f64> {
    move |_: f64, _: f64| DMatrix::zeros(2, np)
}

/// The filters of an assimilation and the frozen model tendency, carried over the intervals.
struct Filters {
    filter: FilterBank,
    frozen: FilterBank,
    /// The model's tendency held by the frozen assimilation (rad/m): the model's on the first
    /// interval (of the first BHA run: pure statistics from there on, which know nothing of a
    /// change of assembly).
    frozen_tendency: Option<[f64; 2]>,
}

/// How the filters are scored while they take in the hole behind the first interval: at each
/// station, on their prediction over the `horizon_m` of hole that follows it, when that hole
/// ends at or above `limit_md` (no station below the first interval's start).
#[derive(Clone, Copy)]
struct WarmUpScoring {
    horizon_m: f64,
    limit_md: f64,
}

/// The steps between the measured stations from `from_md` to `to_md` (both stations, or the
/// first station after `from_md`): consecutive, each at least the tracking interval long but
/// the last, which ends at `to_md` (a remainder shorter than half an interval joins the step
/// before it).
fn steps(case: &Case, from_md: f64, to_md: f64, tracking: &TrackingSettings) -> Vec<Interval> {
    let mds: Vec<f64> = case
        .well
        .path
        .stations()
        .iter()
        .map(|s| s.md_m)
        .filter(|&m| m >= from_md - 1e-9 && m <= to_md + 1e-9)
        .collect();
    let mut ends: Vec<usize> = Vec::new();
    let mut last = 0;
    for (k, &m) in mds.iter().enumerate().skip(1) {
        if m - mds[last] >= tracking.interval_m - 1e-9 {
            ends.push(k);
            last = k;
        }
    }
    let n = mds.len();
    if n >= 2 && last != n - 1 {
        let rest = mds[n - 1] - mds[last];
        match ends.last_mut() {
            Some(e) if rest < 0.5 * tracking.interval_m => *e = n - 1,
            _ => ends.push(n - 1),
        }
    }
    let mut out = Vec::with_capacity(ends.len());
    let mut a = 0;
    for e in ends {
        out.push(Interval {
            from_md_m: mds[a],
            to_md_m: mds[e],
            measured: (0.0, 0.0),
        });
        a = e;
    }
    out
}

/// Take in the measured hole between `from_md` and `to_md` step by step: the assimilated
/// filter against the model's turns `model_turn(a, b)` and sensitivities `sensitivity(a, b)`,
/// the frozen one against the frozen model tendency `kappa` (rad/m).
fn take_in(
    case: &Case,
    (from_md, to_md): (f64, f64),
    model: &ModelSide,
    tracking: &TrackingSettings,
    f: &mut Filters,
    scoring: Option<WarmUpScoring>,
) {
    let (model_turn, sensitivity, kappa) = (model.turn, model.sensitivity, model.kappa);
    let path = &case.well.path;
    for st in steps(case, from_md, to_md, tracking) {
        if let Some(w) = scoring {
            score_behind(case, st.from_md_m, kappa, w, tracking, f);
        }
        let d = st.to_md_m - st.from_md_m;
        let (a, b) = (direction_at(path, st.from_md_m), direction_at(path, st.to_md_m));
        let measured = turn_between(&a, &b);
        let r = survey_covariance(tracking, b.inc_rad);
        let dev = deviation_from_recent(case, st.from_md_m);
        f.filter.advance(d);
        match model_turn {
            Some(turn) => {
                let m = turn(st.from_md_m, st.to_md_m);
                let excess = [m[0] - kappa[0] * d, m[1] - kappa[1] * d];
                f.filter.observe(
                    [measured[0] - m[0], measured[1] - m[1]],
                    d,
                    &sensitivity(st.from_md_m, st.to_md_m),
                    &r,
                    dev,
                    excess,
                );
            }
            None => f.filter.pass_station(&r),
        }
        f.frozen.advance(d);
        f.frozen.observe(
            [measured[0] - kappa[0] * d, measured[1] - kappa[1] * d],
            d,
            &DMatrix::zeros(2, 0),
            &r,
            dev,
            [0.0; 2],
        );
    }
}

/// The deviation (rad, toward the high side and the right) of the measured hole's direction at
/// `md` from its mean direction over the [`REVERSION_M`] of hole behind (or what there is).
pub fn deviation_from_recent(case: &Case, md: f64) -> [f64; 2] {
    let path = &case.well.path;
    let from = (md - REVERSION_M).max(path.md_start());
    if md - from < 1e-6 {
        return [0.0; 2];
    }
    let n = 12;
    let mean = (0..n).fold(Vec3::zeros(), |acc, i| {
        acc + path.point_at(from + (md - from) * (i as f64 + 0.5) / n as f64).tangent
    });
    let (inc_rad, azi_rad) = inc_azi(&mean, path.point_at(md).azi_rad);
    turn_between(&Direction { inc_rad, azi_rad }, &direction_at(path, md))
}

/// Where the hole taken in behind the first interval (starting at `start_md`) begins: the
/// tracking window above it, but not above the survey's first station inclined
/// [`DEFAULT_MIN_INCLINATION_DEG`] or more (in near-vertical hole build and turn have no
/// direction to follow; the kick-off is steered) unless the interval starts above that.
pub fn warm_up_start_md(case: &Case, start_md: f64, tracking: &TrackingSettings) -> f64 {
    let path = &case.well.path;
    let inclined = path
        .stations()
        .iter()
        .find(|s| s.inc_rad >= DEFAULT_MIN_INCLINATION_DEG.to_radians())
        .map_or(path.md_start(), |s| s.md_m);
    (start_md - tracking.window_m)
        .max(inclined.min(start_md))
        .max(path.md_start())
}

/// Score both banks at `md` on the measured hole behind the first interval (see
/// [`WarmUpScoring`]): the model's turn taken as `kappa` (rad/m).
fn score_behind(case: &Case, md: f64, kappa: [f64; 2], w: WarmUpScoring, tracking: &TrackingSettings, f: &mut Filters) {
    let end = md + w.horizon_m;
    if end > w.limit_md + 1e-9 {
        return;
    }
    let path = &case.well.path;
    let (a, b) = (direction_at(path, md), direction_at(path, end));
    let t = turn_between(&a, &b);
    let z = [t[0] - kappa[0] * w.horizon_m, t[1] - kappa[1] * w.horizon_m];
    let r = survey_covariance(tracking, b.inc_rad);
    let np = f.filter.parameter_count();
    let held = turned(&a, [kappa[0] * w.horizon_m, kappa[1] * w.horizon_m]);
    let naive = naive_corrections(path, md, end, &held);
    let at = Situation {
        from_md_m: md,
        deviation: deviation_from_recent(case, md),
        excess: [0.0; 2],
        naive: &naive,
    };
    f.filter.score(z, w.horizon_m, &DMatrix::zeros(2, np), &r, &at);
    f.frozen.score(z, w.horizon_m, &DMatrix::zeros(2, 0), &r, &at);
}

/// Assimilate the survey of the well drilled by the BHA runs `runs` (see
/// [`crate::predict::intervals::run_intervals`]; one run, or several sharing one survey) over
/// the consecutive intervals `list`, each part of an interval predicted by the run that drilled
/// it with the law the filter estimates; `progress` hears (intervals done, intervals).
pub fn assimilate(
    runs: &[RunModel],
    list: &[Interval],
    tracking: &TrackingSettings,
    progress: &mut dyn FnMut(usize, usize),
) -> Assimilation {
    let case = runs[0].case;
    let priors: Vec<(LawParameter, f64, f64)> = tracking
        .parameters
        .iter()
        .map(|&p| (p, p.unbounded(p.value(&case.bit_rock)), prior_sd(p)))
        .collect();
    let first_md = list
        .first()
        .map(|iv| warm_up_start_md(case, iv.from_md_m, tracking))
        .unwrap_or(case.well.path.md_start());
    let first = survey_covariance(tracking, case.well.path.point_at(first_md).inc_rad);
    let mut f = Filters {
        filter: FilterBank::new(tracking, &priors, &first, true),
        frozen: FilterBank::new(tracking, &[], &first, false),
        frozen_tendency: None,
    };
    let mut out = Vec::with_capacity(list.len());
    let mut skipped = Vec::new();
    let mut last_end = LastEnd::default();
    for (k, iv) in list.iter().enumerate() {
        let mut warm = last_end.take_for(runs, iv);
        match assimilate_interval(runs, iv, tracking, &mut f, &mut warm) {
            Ok(a) => {
                out.push(a);
                last_end = LastEnd::of(runs, iv, warm);
            }
            Err(e) => {
                tracing::warn!(from = iv.from_md_m, to = iv.to_md_m, error = %e, "interval skipped");
                skipped.push((*iv, e));
                // the interval's stations still come in: into the frozen bank against its held
                // tendency; the assimilated bank, with no model turn to compare, only passes
                // them (before the first prediction, the next interval's warm-up takes them in)
                if let Some(kappa) = f.frozen_tendency {
                    let sensitivity = no_sensitivity(f.filter.parameter_count());
                    let model = ModelSide {
                        turn: None,
                        sensitivity: &sensitivity,
                        kappa,
                    };
                    take_in(case, (iv.from_md_m, iv.to_md_m), &model, tracking, &mut f, None);
                }
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

/// The assimilated and the frozen banks after taking in the measured hole behind `start_md`
/// (the tracking window), the model's tendency there held at `kappa` (rad/m), each scored on
/// its predictions over `horizon_m` within that hole.
pub fn banks_behind(
    case: &Case,
    start_md: f64,
    kappa: [f64; 2],
    horizon_m: f64,
    tracking: &TrackingSettings,
) -> (FilterBank, FilterBank) {
    let from = warm_up_start_md(case, start_md, tracking);
    let first = survey_covariance(tracking, case.well.path.point_at(from).inc_rad);
    let mut f = Filters {
        filter: FilterBank::new(tracking, &[], &first, true),
        frozen: FilterBank::new(tracking, &[], &first, false),
        frozen_tendency: Some(kappa),
    };
    let (turn, sensitivity) = (held_turn(kappa), no_sensitivity(0));
    let model = ModelSide {
        turn: Some(&turn),
        sensitivity: &sensitivity,
        kappa,
    };
    let scoring = WarmUpScoring {
        horizon_m,
        limit_md: start_md,
    };
    take_in(case, (from, start_md), &model, tracking, &mut f, Some(scoring));
    (f.filter, f.frozen)
}

/// Predict one interval with the filters' corrections (the first one after warming them up on
/// the hole behind it), then take in its measured stations.
fn assimilate_interval(
    runs: &[RunModel],
    iv: &Interval,
    tracking: &TrackingSettings,
    f: &mut Filters,
    warm: &mut WarmStart,
) -> Result<AssimilatedInterval, PredictError> {
    let case = runs[0].case;
    let len = iv.to_md_m - iv.from_md_m;
    let start_warm = warm.clone();
    let parameters: Vec<LawParameter> = f.filter.parameters().iter().map(|p| p.0).collect();
    let u = f.filter.linearize();
    let laws: Vec<BitRock> = runs.iter().map(|r| law_of(r.case, &parameters, &u)).collect();
    let pred = predict_interval_path(&with_laws(runs, &laws), iv, warm)?;
    let plain = result_of(iv, &pred);
    let stepped = stepped_marches(runs, (&parameters, &u), iv, &start_warm)?;
    let start = direction_at(&case.well.path, iv.from_md_m);
    let march_end = direction_at(&pred.path, iv.to_md_m);
    let kappa = match f.frozen_tendency {
        Some(k) => k,
        None => {
            // the model's tendency on the first interval, also taken for the hole behind it
            let k = turn_between(&start, &march_end).map(|t| t / len);
            f.frozen_tendency = Some(k);
            let behind = (warm_up_start_md(case, iv.from_md_m, tracking), iv.from_md_m);
            let scoring = WarmUpScoring {
                horizon_m: len,
                limit_md: iv.from_md_m,
            };
            let (turn, sensitivity) = (held_turn(k), no_sensitivity(f.filter.parameter_count()));
            let model = ModelSide {
                turn: Some(&turn),
                sensitivity: &sensitivity,
                kappa: k,
            };
            take_in(case, behind, &model, tracking, f, Some(scoring));
            k
        }
    };
    let dev = deviation_from_recent(case, iv.from_md_m);
    let march_turn = turn_between(&start, &march_end);
    let excess = [march_turn[0] - kappa[0] * len, march_turn[1] - kappa[1] * len];
    let naive = naive_corrections(&case.well.path, iv.from_md_m, iv.to_md_m, &march_end);
    let at = Situation {
        from_md_m: iv.from_md_m,
        deviation: dev,
        excess,
        naive: &naive,
    };
    let correction = f.filter.predicted_turn(len, &at);
    tracing::debug!(
        from = iv.from_md_m,
        correction_deg = ?correction.map(f64::to_degrees),
        offset = ?f.filter.offset().0.map(|x| (x * 30.0).to_degrees()),
        fluctuation = ?f.filter.fluctuation().map(|x| (x * 30.0).to_degrees()),
        fluctuation_sd = ?f.filter.fluctuation_sd().map(|x| (x * 30.0).to_degrees()),
        offset_sd = ?f.filter.offset().1.map(|x| (x * 30.0).to_degrees()),
        weights = ?f.filter.weights().iter().map(|w| (w * 100.0).round() / 100.0).collect::<Vec<_>>(),
        naive = ?f.filter.naive_weights().iter().map(|(m, w)| (m.name(), (w * 100.0).round() / 100.0)).collect::<Vec<_>>(),
        parameters = ?f.filter.parameters().iter().map(|&(p, u, sd, _)| (p.natural(u), sd * p.slope(u).abs())).collect::<Vec<_>>(),
        "assimilated interval"
    );
    let assimilated = turned(&march_end, correction);
    let offset = f.filter.predicted_offset(len, &at);
    let s = case.well.path.point_at(iv.from_md_m);
    let sf = Frame::from_tangent(&s.tangent, s.azi_rad);
    let position = plain.position + sf.h * offset[0] + sf.r * offset[1];
    let frozen_model = turned(&start, [kappa[0] * len, kappa[1] * len]);
    let frozen_naive = naive_corrections(&case.well.path, iv.from_md_m, iv.to_md_m, &frozen_model);
    let frozen_at = Situation {
        from_md_m: iv.from_md_m,
        deviation: dev,
        excess: [0.0; 2],
        naive: &frozen_naive,
    };
    let frozen = turned(&frozen_model, f.frozen.predicted_turn(len, &frozen_at));
    let j_end = turn_sensitivity(&pred.path, &stepped, iv.from_md_m, iv.to_md_m);
    let cov = f
        .filter
        .calibrated(&(f.filter.turn_covariance(len, &j_end, &at) + survey_covariance(tracking, assimilated.inc_rad)));
    let out = AssimilatedInterval {
        plain,
        assimilated,
        position,
        frozen,
        inc_sd_rad: cov[(0, 0)].sqrt(),
        azi_sd_rad: (cov[(1, 1)].sqrt() / assimilated.inc_rad.sin().max(1e-6)).min(std::f64::consts::PI),
        correction_rad: correction,
    };
    // each filter is scored on its prediction of this interval, then takes in its stations
    let measured = Direction {
        inc_rad: iv.measured.0,
        azi_rad: iv.measured.1,
    };
    let r_end = survey_covariance(tracking, iv.measured.0);
    f.filter
        .score(turn_between(&march_end, &measured), len, &j_end, &r_end, &at);
    f.frozen.score(
        turn_between(&frozen_model, &measured),
        len,
        &DMatrix::zeros(2, 0),
        &r_end,
        &frozen_at,
    );
    let model_path = &pred.path;
    let turn = |a: f64, b: f64| turn_between(&direction_at(model_path, a), &direction_at(model_path, b));
    let sensitivity = |a: f64, b: f64| turn_sensitivity(model_path, &stepped, a, b);
    let model = ModelSide {
        turn: Some(&turn),
        sensitivity: &sensitivity,
        kappa,
    };
    take_in(case, (iv.from_md_m, iv.to_md_m), &model, tracking, f, None);
    Ok(out)
}
