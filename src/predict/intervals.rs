//! The intervals of a back-analysis: the survey cut into consecutive intervals, each predicted
//! from the measured hole behind it to its end station and compared with the measured station
//! there. Errors per 100 m are the seed paper's metric (end-of-interval error divided by the
//! interval length).

use crate::case::{BitRock, Case};
use crate::geometry::survey::wrap_pi;
use crate::geometry::{Vec3, WellPath};
use crate::models::fem::results::BitResult;
use crate::predict::march::{hole_to, predict_from, MarchSettings, PredictError, Prediction, WarmStart};

/// By default back-analysis starts at the first station this inclined, deg: in a vertical
/// hole the bit forces have no direction to predict (a kick-off is steered, not predicted).
pub const DEFAULT_MIN_INCLINATION_DEG: f64 = 3.0;

/// How the survey is cut into intervals.
#[derive(Debug, Clone, Copy)]
pub struct IntervalPlan {
    /// First interval starts at the first station at or below this MD, m.
    pub from_md_m: f64,
    /// No interval ends below this MD, m.
    pub to_md_m: f64,
    /// Shortest interval, m: an interval ends at the first station at least this far below
    /// its start (0: the next station). Intervals are consecutive (each starts where the last
    /// ended).
    pub horizon_m: f64,
}

/// One interval: predicted from its start station to its end station.
#[derive(Debug, Clone, Copy)]
pub struct Interval {
    /// Start MD (a measured station), m.
    pub from_md_m: f64,
    /// End MD (a measured station), m.
    pub to_md_m: f64,
    /// Measured inclination and azimuth at the end, rad.
    pub measured: (f64, f64),
}

/// Result of one interval.
#[derive(Debug, Clone, Copy)]
pub struct IntervalResult {
    /// The interval.
    pub interval: Interval,
    /// Predicted inclination at the end, rad.
    pub inc_rad: f64,
    /// Predicted azimuth at the end, rad.
    pub azi_rad: f64,
    /// Predicted position at the end (north, east, tvd), m.
    pub position: Vec3,
    /// Bit results at the interval's start (on the measured hole).
    pub bit_start: BitResult,
    /// Bit results at the interval's end (on the predicted hole).
    pub bit_end: BitResult,
}

impl IntervalResult {
    /// Interval length, m.
    pub fn length_m(&self) -> f64 {
        self.interval.to_md_m - self.interval.from_md_m
    }
    /// Inclination error at the end (predicted - measured), rad.
    pub fn inc_err_rad(&self) -> f64 {
        self.inc_rad - self.interval.measured.0
    }
    /// Azimuth error at the end, wrapped, rad.
    pub fn azi_err_rad(&self) -> f64 {
        wrap_pi(self.azi_rad - self.interval.measured.1)
    }
    /// Inclination error per 100 m of interval (the seed paper's metric), rad.
    pub fn inc_err_per_100m_rad(&self) -> f64 {
        self.inc_err_rad() * 100.0 / self.length_m()
    }
    /// Azimuth error per 100 m of interval, rad.
    pub fn azi_err_per_100m_rad(&self) -> f64 {
        self.azi_err_rad() * 100.0 / self.length_m()
    }
}

/// Consecutive intervals of `path` per `plan`.
pub fn intervals(path: &WellPath, plan: &IntervalPlan) -> Vec<Interval> {
    let st = path.stations();
    let mut out = Vec::new();
    let Some(mut k) = st.iter().position(|s| s.md_m >= plan.from_md_m - 1e-9) else {
        return out;
    };
    while k + 1 < st.len() {
        let mut e = k + 1;
        while e + 1 < st.len() && st[e].md_m - st[k].md_m < plan.horizon_m - 1e-9 {
            e += 1;
        }
        if st[e].md_m > plan.to_md_m + 1e-9 {
            break;
        }
        out.push(Interval {
            from_md_m: st[k].md_m,
            to_md_m: st[e].md_m,
            measured: (st[e].inc_rad, st[e].azi_rad),
        });
        k = e;
    }
    out
}

/// One BHA run as the predictor sees it: its case (the assembly, the operation, the bit depth
/// where the run ended), the bit-rock law to predict with and the march settings.
#[derive(Clone, Copy)]
pub struct RunModel<'a> {
    /// The run's case.
    pub case: &'a Case,
    /// The bit-rock law to predict with.
    pub bit_rock: &'a BitRock,
    /// The march settings.
    pub settings: &'a MarchSettings,
}

impl<'a> RunModel<'a> {
    /// The run `case` with its own law and `settings`.
    pub fn of(case: &'a Case, settings: &'a MarchSettings) -> RunModel<'a> {
        RunModel {
            case,
            bit_rock: &case.bit_rock,
            settings,
        }
    }
}

/// Which of the BHA runs with the bit depths `bit_mds` (m, increasing; each run drilled the hole
/// from the previous one's bit depth to its own) drilled the hole just below `md_m`: the first
/// whose bit depth is below it, else the last.
pub fn run_at(bit_mds: &[f64], md_m: f64) -> usize {
    bit_mds
        .iter()
        .position(|&b| b > md_m + 1e-6)
        .unwrap_or(bit_mds.len().saturating_sub(1))
}

/// The bit depths of `runs`, m.
pub fn bit_mds(runs: &[RunModel]) -> Vec<f64> {
    runs.iter().map(|r| r.case.operation.bit_md_m).collect()
}

/// The parts of the hole from `from_md` to `to_md` drilled by each of the runs with the bit
/// depths `bit_mds`: (run, from, to), in order.
pub fn run_parts(bit_mds: &[f64], from_md: f64, to_md: f64) -> Vec<(usize, f64, f64)> {
    let mut out = Vec::new();
    let mut a = from_md;
    loop {
        let j = run_at(bit_mds, a);
        let b = if j + 1 < bit_mds.len() {
            bit_mds[j].min(to_md)
        } else {
            to_md
        };
        out.push((j, a, b));
        if b >= to_md - 1e-6 {
            return out;
        }
        a = b;
    }
}

/// Predict each interval with the runs `runs` (one, or the BHA runs that drilled the well in
/// the order of their bit depths: each part of an interval with the run that drilled it);
/// `warm` holds one warm start per interval: the solved state at its start, kept between calls
/// with other parameters (as calibration makes); on the first call each interval starts from
/// the previous one's end when the same run drills on. The first interval that cannot be
/// predicted stops the run with its error.
pub fn run_intervals(
    runs: &[RunModel],
    list: &[Interval],
    warm: &mut Vec<WarmStart>,
    progress: impl FnMut(usize, usize),
) -> Result<Vec<IntervalResult>, PredictError> {
    let (done, mut failed) = run_intervals_skipping(runs, list, warm, progress, true);
    match failed.pop() {
        Some((_, e)) => Err(e),
        None => Ok(done),
    }
}

/// As [`run_intervals`], but an interval that cannot be predicted (a string solve that does not
/// converge, an implicit step that finds no direction) is set aside with its error and the run
/// goes on (unless `stop_at_first`). Returns the predicted intervals and the failed ones.
#[allow(clippy::type_complexity)]
pub fn run_intervals_skipping(
    runs: &[RunModel],
    list: &[Interval],
    warm: &mut Vec<WarmStart>,
    mut progress: impl FnMut(usize, usize),
    stop_at_first: bool,
) -> (Vec<IntervalResult>, Vec<(Interval, PredictError)>) {
    warm.resize_with(list.len(), || None);
    let mut out = Vec::with_capacity(list.len());
    let mut failed = Vec::new();
    let mut last_end = LastEnd::default();
    for (k, iv) in list.iter().enumerate() {
        let mut w = match &warm[k] {
            Some(_) => warm[k].clone(),
            None => last_end.take_for(runs, iv),
        };
        match predict_interval(runs, iv, &mut w) {
            Ok((result, start_warm)) => {
                warm[k] = start_warm;
                last_end = LastEnd::of(runs, iv, w);
                out.push(result);
            }
            Err(e) => {
                tracing::warn!(from = iv.from_md_m, to = iv.to_md_m, error = %e, "interval skipped");
                failed.push((*iv, e));
                if stop_at_first {
                    break;
                }
            }
        }
        progress(k + 1, list.len());
    }
    (out, failed)
}

/// The solved state at the end of the last interval predicted, with the run that drilled there.
#[derive(Default)]
pub struct LastEnd {
    run: usize,
    warm: WarmStart,
}

impl LastEnd {
    /// The end state `warm` of interval `iv` predicted with `runs`.
    pub fn of(runs: &[RunModel], iv: &Interval, warm: WarmStart) -> LastEnd {
        let parts = run_parts(&bit_mds(runs), iv.from_md_m, iv.to_md_m);
        LastEnd {
            run: parts.last().map_or(0, |p| p.0),
            warm,
        }
    }

    /// The warm start of interval `iv`: the state kept when the same run drills on, else none
    /// (another assembly: a cold start).
    pub fn take_for(&mut self, runs: &[RunModel], iv: &Interval) -> WarmStart {
        let w = self.warm.take();
        w.filter(|_| run_at(&bit_mds(runs), iv.from_md_m) == self.run)
    }
}

/// Predict interval `iv` from the measured hole behind it with `runs` (see [`run_intervals`]),
/// warm-started from `warm` (which then holds the solved state at the end); returns the result
/// and the solved state at the interval's start.
pub fn predict_interval(
    runs: &[RunModel],
    iv: &Interval,
    warm: &mut WarmStart,
) -> Result<(IntervalResult, WarmStart), PredictError> {
    let pred = predict_interval_path(runs, iv, warm)?;
    Ok((result_of(iv, &pred), pred.start_warm))
}

/// The prediction of interval `iv` (as [`predict_interval`], with the whole predicted hole):
/// where a run ended within the interval, the next run drills on from the predicted hole
/// (started cold).
pub fn predict_interval_path(
    runs: &[RunModel],
    iv: &Interval,
    warm: &mut WarmStart,
) -> Result<Prediction, PredictError> {
    let mut start = hole_to(&runs[0].case.well.path, iv.from_md_m)?;
    let mut whole: Option<Prediction> = None;
    for (j, _, to) in run_parts(&bit_mds(runs), iv.from_md_m, iv.to_md_m) {
        let r = &runs[j];
        if whole.is_some() {
            *warm = None;
        }
        let p = predict_from(r.case, r.bit_rock, &start, to, r.settings, warm, &mut |_| {})?;
        start = p.path.clone();
        whole = Some(match whole {
            None => p,
            Some(first) => joined(first, p),
        });
    }
    Ok(whole.expect("an interval has a part"))
}

/// The prediction `first` continued by `next` (which started from its hole).
fn joined(first: Prediction, next: Prediction) -> Prediction {
    let mut steps = first.steps;
    steps.extend(next.steps.into_iter().skip(1));
    Prediction {
        path: next.path,
        steps,
        from_md_m: first.from_md_m,
        to_md_m: next.to_md_m,
        cut_m: next.cut_m,
        dofs: next.dofs,
        iterations: first.iterations + next.iterations,
        seconds: first.seconds + next.seconds,
        start_warm: first.start_warm,
        ripple_deg: next.ripple_deg,
        whirl_md_m: first.whirl_md_m,
        buckled_start_md_m: first.buckled_start_md_m.or(next.buckled_start_md_m),
    }
}

/// The interval result of prediction `pred` of `iv`.
pub fn result_of(iv: &Interval, pred: &Prediction) -> IntervalResult {
    let end = pred.path.point_at(iv.to_md_m);
    IntervalResult {
        interval: *iv,
        inc_rad: end.inc_rad,
        azi_rad: end.azi_rad,
        position: end.position,
        bit_start: pred.steps[0].bit,
        bit_end: pred.steps[pred.steps.len() - 1].bit,
    }
}

/// Error statistics over intervals (all per 100 m of interval length).
#[derive(Debug, Clone, Copy, Default)]
pub struct ErrorStats {
    /// Intervals.
    pub intervals: usize,
    /// Mean |inclination error| per 100 m, rad.
    pub inc_mean_abs_per_100m_rad: f64,
    /// Mean |azimuth error| per 100 m, rad.
    pub azi_mean_abs_per_100m_rad: f64,
    /// RMS inclination error per 100 m, rad.
    pub inc_rms_per_100m_rad: f64,
    /// RMS azimuth error per 100 m, rad.
    pub azi_rms_per_100m_rad: f64,
}

/// Error statistics of `results`.
pub fn error_stats(results: &[IntervalResult]) -> ErrorStats {
    let n = results.len();
    if n == 0 {
        return ErrorStats::default();
    }
    let fi: Vec<f64> = results.iter().map(IntervalResult::inc_err_per_100m_rad).collect();
    let fa: Vec<f64> = results.iter().map(IntervalResult::azi_err_per_100m_rad).collect();
    let mean_abs = |v: &[f64]| v.iter().map(|x| x.abs()).sum::<f64>() / n as f64;
    let rms = |v: &[f64]| (v.iter().map(|x| x * x).sum::<f64>() / n as f64).sqrt();
    ErrorStats {
        intervals: n,
        inc_mean_abs_per_100m_rad: mean_abs(&fi),
        azi_mean_abs_per_100m_rad: mean_abs(&fa),
        inc_rms_per_100m_rad: rms(&fi),
        azi_rms_per_100m_rad: rms(&fa),
    }
}
