//! Post-drill back-analysis (`drillpath backanalyze`): the survey cut into intervals
//! ([`crate::predict::intervals`]), each predicted from the measured hole behind it and compared with the
//! measured station at its end; optionally the bit-rock law calibrated on the first part of
//! the intervals and scored on the rest ([`crate::predict::calibrate`]).
//!
//! [`plan`] decides where the analysis starts (by default the first station inclined
//! [`DEFAULT_MIN_INCLINATION_DEG`] or more, below the wider hole drilled by an earlier bit) and
//! cuts the intervals; [`run`] predicts them, calibrates and scores.

pub use super::intervals::{
    error_stats, intervals as cut_intervals, run_intervals, run_intervals_skipping, ErrorStats, Interval, IntervalPlan,
    IntervalResult, RunModel, DEFAULT_MIN_INCLINATION_DEG,
};

use super::calibrate::{calibrate, Calibration, FitParameter};
use super::law::LawParams;
use super::march::{MarchSettings, PredictError, WarmStart, MIN_MODEL_LENGTH_M};
use super::tracking::assimilate::{assimilate, Assimilation};
use super::tracking::references::{project, Direction, Reference};
use super::tracking::skill::{skill, EndDirections, Skill};
use crate::case::Case;
use std::time::Instant;

/// Hole above the first interval's start by default, m.
pub const DEFAULT_START_DEPTH_M: f64 = 30.0;

/// Intervals a calibration needs: at least 2 to fit on and 2 to score on.
pub const MIN_CALIBRATION_INTERVALS: usize = 4;

/// A calibration asked of a back-analysis.
#[derive(Debug, Clone, PartialEq)]
pub struct CalibrationRequest {
    /// The law's parameters to fit.
    pub parameters: Vec<FitParameter>,
    /// Share of the intervals (from the top) to fit on, in (0, 1); the rest is scored.
    pub split: f64,
}

/// What a back-analysis is asked, SI.
#[derive(Debug, Clone, PartialEq)]
pub struct BackanalysisRequest {
    /// First interval starts at the first station at or below this MD, m (None: the default
    /// start, see the module documentation).
    pub from_md_m: Option<f64>,
    /// No interval ends below this MD, m (None: the last station).
    pub to_md_m: Option<f64>,
    /// Shortest interval, m (0: station to station).
    pub horizon_m: f64,
    /// The calibration, if asked.
    pub calibration: Option<CalibrationRequest>,
    /// Assimilate the survey ([`crate::predict::tracking::assimilate`], with the case's
    /// `[tracking]` settings).
    pub assimilate: bool,
}

/// Where a back-analysis runs and on which intervals.
#[derive(Debug, Clone)]
pub struct BackanalysisPlan {
    /// Start MD asked or decided, m.
    pub from_md_m: f64,
    /// End MD, m.
    pub to_md_m: f64,
    /// Shortest interval, m.
    pub horizon_m: f64,
    /// When the default start was used and wider hole lies above: the bottom of that hole,
    /// m MD (the start is below it).
    pub below_previous_hole_md_m: Option<f64>,
    /// The intervals.
    pub intervals: Vec<Interval>,
    /// The calibration, if asked.
    pub calibration: Option<CalibrationRequest>,
    /// Whether the survey is assimilated.
    pub assimilate: bool,
}

/// Most march steps one back-analysis may take over all its intervals (each calibration
/// evaluation repeats them); a larger one is refused before any solve, with the remedy.
pub const MAX_BACKANALYSIS_STEPS: f64 = 200_000.0;

impl BackanalysisPlan {
    /// March steps over all intervals at `step_m` (m), once.
    pub fn march_steps(&self, step_m: f64) -> f64 {
        self.intervals
            .iter()
            .map(|i| ((i.to_md_m - i.from_md_m) / step_m).ceil())
            .sum()
    }

    /// Refuse a plan whose intervals take more than [`MAX_BACKANALYSIS_STEPS`] steps at
    /// `step_m` (m), with the remedy.
    pub fn check_size(&self, step_m: f64) -> Result<(), String> {
        let steps = self.march_steps(step_m);
        if steps <= MAX_BACKANALYSIS_STEPS {
            return Ok(());
        }
        Err(format!(
            "{} intervals from {:.2} to {:.2} m MD take {steps:.0} march steps of {step_m} m, more than the {MAX_BACKANALYSIS_STEPS} a back-analysis may take: a shorter --horizon, a shorter range (--from, --to) or a longer --step",
            self.intervals.len(),
            self.from_md_m,
            self.to_md_m
        ))
    }
}

/// Why a back-analysis cannot run.
#[derive(Debug, thiserror::Error)]
pub enum BackanalysisError {
    /// Too few intervals in the range.
    #[error("only {found} survey interval(s) between {from_md_m:.1} m and {to_md_m:.1} m; back-analysis needs {needed}{}", if *.calibrate { " to calibrate on half and score on the other half" } else { "" })]
    TooFewIntervals {
        /// Intervals found.
        found: usize,
        /// Intervals needed.
        needed: usize,
        /// Start MD, m.
        from_md_m: f64,
        /// End MD, m.
        to_md_m: f64,
        /// Whether a calibration was asked.
        calibrate: bool,
    },
    /// No interval could be predicted.
    #[error("no interval could be predicted; the first ({from_md_m:.1}-{to_md_m:.1} m): {error}")]
    NothingPredicted {
        /// Start of the first interval, m.
        from_md_m: f64,
        /// End of the first interval, m.
        to_md_m: f64,
        /// Why it failed.
        error: PredictError,
    },
    /// Too few intervals could be predicted to calibrate.
    #[error("only {found} interval(s) could be predicted; calibration needs {needed}")]
    TooFewPredicted {
        /// Intervals predicted.
        found: usize,
        /// Intervals needed.
        needed: usize,
    },
    /// The calibration or the scoring failed.
    #[error(transparent)]
    Predict(#[from] PredictError),
    /// Calibration asked of a well drilled in several runs.
    #[error("calibration runs on one case: give one BHA run, or leave out --calibrate")]
    CalibrationWithRuns,
    /// The runs do not share one survey or are not in the order of their bit depths.
    #[error("{0}")]
    Runs(String),
    /// Calibration and assimilation asked together.
    #[error("calibration and assimilation cannot run together: the assimilation estimates the law's parameters itself (`estimate` in [tracking])")]
    CalibrationAndAssimilation,
}

/// The plan of a back-analysis of `case`'s survey as `req` asks (see the module documentation).
pub fn plan(case: &Case, req: &BackanalysisRequest) -> Result<BackanalysisPlan, BackanalysisError> {
    let survey = &case.well.path;
    // by default, only the hole this bit drilled: below the earlier (wider) hole sections (a
    // string without a bit: the hole at the bottom of the survey gives the bit size)
    let bit_diameter_m = case
        .string
        .bit_diameter_m()
        .unwrap_or_else(|| case.well.hole.diameter_at(survey.md_end()));
    let previous_hole = case.well.hole.previous_hole_bottom_md(bit_diameter_m);
    let from = match req.from_md_m {
        Some(md) => md,
        None => survey
            .stations()
            .iter()
            .find(|s| s.inc_rad >= DEFAULT_MIN_INCLINATION_DEG.to_radians() && s.md_m >= previous_hole.unwrap_or(0.0))
            .map(|s| s.md_m)
            .unwrap_or(survey.md_end())
            .max(survey.md_start() + DEFAULT_START_DEPTH_M),
    }
    .max(survey.md_start() + MIN_MODEL_LENGTH_M);
    let to = req.to_md_m.unwrap_or(survey.md_end());
    let list = cut_intervals(
        survey,
        &IntervalPlan {
            from_md_m: from,
            to_md_m: to,
            horizon_m: req.horizon_m,
        },
    );
    let calibrate = req.calibration.is_some();
    if calibrate && req.assimilate {
        return Err(BackanalysisError::CalibrationAndAssimilation);
    }
    let needed = if calibrate { MIN_CALIBRATION_INTERVALS } else { 1 };
    if list.len() < needed {
        return Err(BackanalysisError::TooFewIntervals {
            found: list.len(),
            needed,
            from_md_m: from,
            to_md_m: to,
            calibrate,
        });
    }
    Ok(BackanalysisPlan {
        from_md_m: from,
        to_md_m: to,
        horizon_m: req.horizon_m,
        below_previous_hole_md_m: previous_hole.filter(|_| req.from_md_m.is_none()),
        intervals: list,
        calibration: req.calibration.clone(),
        assimilate: req.assimilate,
    })
}

/// The calibration of a back-analysis and its scores.
pub struct CalibrationOutcome {
    /// The fit.
    pub calibration: Calibration,
    /// MD where the scored part starts (the calibrated part ends), m.
    pub split_md_m: f64,
    /// Errors of the calibration intervals with the case's law.
    pub in_sample_default: ErrorStats,
    /// Errors of the calibration intervals with the fitted law.
    pub in_sample_fitted: ErrorStats,
    /// Errors of the scored intervals with the case's law.
    pub out_of_sample_default: ErrorStats,
    /// Errors of the scored intervals with the fitted law.
    pub out_of_sample_fitted: ErrorStats,
}

/// A back-analysis, SI.
pub struct Backanalysis {
    /// The intervals predicted with the case's law.
    pub base: Vec<IntervalResult>,
    /// The intervals that could not be predicted, with why.
    pub skipped: Vec<(Interval, PredictError)>,
    /// Errors of `base` (of the assimilated predictions when assimilating).
    pub stats: ErrorStats,
    /// Errors of `results` (with a calibration: the calibration intervals with the fitted
    /// law and the scored ones; else `stats`).
    pub results_stats: ErrorStats,
    /// The law's parameters at the start.
    pub law: LawParams,
    /// The calibration, if asked.
    pub calibration: Option<CalibrationOutcome>,
    /// The intervals reported: `base`, or with a calibration the calibration intervals with
    /// the fitted law followed by the scored ones, or with an assimilation the assimilated
    /// predictions.
    pub results: Vec<IntervalResult>,
    /// The end directions of the reported intervals with the references' (and, assimilating,
    /// the plain and frozen predictions).
    pub ends: Vec<EndDirections>,
    /// The model against the references on `ends`.
    pub skill: Option<Skill>,
    /// The assimilation, when asked.
    pub assimilation: Option<Assimilation>,
    /// Wall-clock time, s.
    pub seconds: f64,
}

impl Backanalysis {
    /// First and last MD of the predicted intervals, m.
    pub fn range_md_m(&self) -> (f64, f64) {
        let first = self.base.first().map(|r| r.interval.from_md_m).unwrap_or(0.0);
        let last = self.base.last().map(|r| r.interval.to_md_m).unwrap_or(0.0);
        (first, last)
    }
}

/// What a back-analysis reports while it runs.
pub enum Progress<'a> {
    /// `done` of `of` intervals predicted with the case's law.
    Interval {
        /// Intervals done.
        done: usize,
        /// Intervals in all.
        of: usize,
    },
    /// The calibration started.
    CalibrationStarted,
    /// A message of the calibration.
    Calibration(&'a str),
}

/// Run the back-analysis `plan` of the well drilled by the BHA runs `cases` (one case, or several
/// sharing one survey in the order of their bit depths, each having drilled the hole from the
/// previous one's bit depth to its own; the plan and the `[tracking]` settings are the first
/// case's) with the march settings `settings` (one per case); `progress` hears how it goes.
pub fn run(
    cases: &[Case],
    plan: &BackanalysisPlan,
    settings: &[MarchSettings],
    progress: &mut dyn FnMut(Progress),
) -> Result<Backanalysis, BackanalysisError> {
    let t0 = Instant::now();
    check_runs(cases, plan)?;
    if settings.len() != cases.len() {
        return Err(BackanalysisError::Runs(format!(
            "{} march settings for {} BHA runs",
            settings.len(),
            cases.len()
        )));
    }
    let case = &cases[0];
    let runs: Vec<RunModel> = cases.iter().zip(settings).map(|(c, s)| RunModel::of(c, s)).collect();
    let mut out = if plan.assimilate {
        run_assimilated(&runs, plan, progress)?
    } else {
        run_plain(&runs, plan, progress)?
    };
    out.ends = out
        .results
        .iter()
        .enumerate()
        .map(|(k, r)| {
            let a = out.assimilation.as_ref().map(|a| &a.intervals[k]);
            end_directions(case, r, a.map(|a| a.plain), a.map(|a| a.frozen))
        })
        .collect();
    out.skill = skill(&out.ends);
    out.seconds = t0.elapsed().as_secs_f64();
    Ok(out)
}

/// The runs must share the first one's survey and come in the order of their bit depths; a
/// calibration needs a single run.
fn check_runs(cases: &[Case], plan: &BackanalysisPlan) -> Result<(), BackanalysisError> {
    let first = cases
        .first()
        .ok_or_else(|| BackanalysisError::Runs("no case given".into()))?;
    if cases.len() > 1 && plan.calibration.is_some() {
        return Err(BackanalysisError::CalibrationWithRuns);
    }
    for w in cases.windows(2) {
        if w[1].operation.bit_md_m <= w[0].operation.bit_md_m {
            return Err(BackanalysisError::Runs(format!(
                "the BHA runs must come in the order of their bit depths: {} (bit at {:.1} m) after {} (bit at {:.1} m)",
                w[1].path.display(),
                w[1].operation.bit_md_m,
                w[0].path.display(),
                w[0].operation.bit_md_m
            )));
        }
    }
    for c in &cases[1..] {
        if c.well.path.stations() != first.well.path.stations() {
            return Err(BackanalysisError::Runs(format!(
                "the BHA runs must share one survey: {} and {} differ",
                first.path.display(),
                c.path.display()
            )));
        }
    }
    Ok(())
}

/// The predicted end of `r` with the references', and the plain and frozen predictions of an
/// assimilation.
fn end_directions(
    case: &Case,
    r: &IntervalResult,
    plain: Option<IntervalResult>,
    frozen: Option<Direction>,
) -> EndDirections {
    let iv = &r.interval;
    let dir = |r: &IntervalResult| Direction {
        inc_rad: r.inc_rad,
        azi_rad: r.azi_rad,
    };
    EndDirections {
        length_m: r.length_m(),
        measured: Direction {
            inc_rad: iv.measured.0,
            azi_rad: iv.measured.1,
        },
        model: dir(r),
        references: Reference::all().map(|q| project(&case.well.path, iv.from_md_m, iv.to_md_m, q)),
        plain: plain.as_ref().map(dir),
        frozen,
    }
}

/// The back-analysis with the runs' laws (and a calibration when asked, of a single run).
fn run_plain(
    runs: &[RunModel],
    plan: &BackanalysisPlan,
    progress: &mut dyn FnMut(Progress),
) -> Result<Backanalysis, BackanalysisError> {
    let case = runs[0].case;
    let mut warm = Vec::new();
    let (base, skipped) = run_intervals_skipping(
        runs,
        &plan.intervals,
        &mut warm,
        |done, of| progress(Progress::Interval { done, of }),
        false,
    );
    let skipped = check_predicted(&base, skipped)?;
    // calibration and scoring use the intervals that could be predicted with the case's law
    let predicted = |iv: &Interval| !skipped.iter().any(|(s, _)| s.from_md_m == iv.from_md_m);
    let warm: Vec<_> = plan
        .intervals
        .iter()
        .zip(warm)
        .filter(|(iv, _)| predicted(iv))
        .map(|(_, w)| w)
        .collect();
    let stats = error_stats(&base);
    let mut out = Backanalysis {
        results: base.clone(),
        results_stats: stats,
        stats,
        law: LawParams::at(&case.bit_rock, plan.from_md_m),
        calibration: None,
        skipped,
        base,
        ends: Vec::new(),
        skill: None,
        assimilation: None,
        seconds: 0.0,
    };
    if let Some(req) = &plan.calibration {
        let (outcome, scored) = calibrate_and_score(&runs[0], req, &out.base, warm, progress)?;
        out.results = outcome.calibration.results.clone();
        out.results.extend(scored);
        out.results_stats = error_stats(&out.results);
        out.calibration = Some(outcome);
    }
    Ok(out)
}

/// The back-analysis with the survey assimilated (over the runs `runs`).
fn run_assimilated(
    runs: &[RunModel],
    plan: &BackanalysisPlan,
    progress: &mut dyn FnMut(Progress),
) -> Result<Backanalysis, BackanalysisError> {
    let case = runs[0].case;
    let mut a = assimilate(runs, &plan.intervals, &case.tracking, &mut |done, of| {
        progress(Progress::Interval { done, of })
    });
    let base: Vec<IntervalResult> = a.intervals.iter().map(|i| i.plain).collect();
    let skipped = check_predicted(&base, std::mem::take(&mut a.skipped))?;
    let results: Vec<IntervalResult> = a.intervals.iter().map(|i| i.result()).collect();
    let stats = error_stats(&results);
    Ok(Backanalysis {
        results,
        results_stats: stats,
        stats,
        law: LawParams::at(&case.bit_rock, plan.from_md_m),
        calibration: None,
        skipped,
        base,
        ends: Vec::new(),
        skill: None,
        assimilation: Some(a),
        seconds: 0.0,
    })
}

/// The skipped intervals back when some interval was predicted; else the error of the first.
fn check_predicted(
    base: &[IntervalResult],
    skipped: Vec<(Interval, PredictError)>,
) -> Result<Vec<(Interval, PredictError)>, BackanalysisError> {
    if !base.is_empty() {
        return Ok(skipped);
    }
    let (iv, error) = skipped.into_iter().next().expect("an interval failed");
    Err(BackanalysisError::NothingPredicted {
        from_md_m: iv.from_md_m,
        to_md_m: iv.to_md_m,
        error,
    })
}

/// Fit `req`'s parameters on the first part of the predicted intervals `base` (with their warm
/// starts `warm`) and score the fitted law on the rest; returns the outcome and the scored
/// intervals' results.
fn calibrate_and_score(
    run: &RunModel,
    req: &CalibrationRequest,
    base: &[IntervalResult],
    mut warm: Vec<WarmStart>,
    progress: &mut dyn FnMut(Progress),
) -> Result<(CalibrationOutcome, Vec<IntervalResult>), BackanalysisError> {
    let (case, settings) = (run.case, run.settings);
    let list: Vec<Interval> = base.iter().map(|r| r.interval).collect();
    if list.len() < MIN_CALIBRATION_INTERVALS {
        return Err(BackanalysisError::TooFewPredicted {
            found: list.len(),
            needed: MIN_CALIBRATION_INTERVALS,
        });
    }
    // at least 2 intervals to fit on and 2 to score on
    let ncal = ((list.len() as f64 * req.split).round() as usize).clamp(2, list.len() - 2);
    let (cal_list, score_list) = list.split_at(ncal);
    progress(Progress::CalibrationStarted);
    let calibration = calibrate(case, &req.parameters, cal_list, settings, |m| {
        progress(Progress::Calibration(m))
    })?;
    let mut warm_scored = warm.split_off(ncal.min(warm.len()));
    let fitted = RunModel {
        bit_rock: &calibration.bit_rock,
        ..*run
    };
    let scored = run_intervals(&[fitted], score_list, &mut warm_scored, |_, _| {})?;
    let outcome = CalibrationOutcome {
        split_md_m: list[ncal].from_md_m,
        in_sample_default: error_stats(&base[..ncal]),
        in_sample_fitted: error_stats(&calibration.results),
        out_of_sample_default: error_stats(&base[ncal..]),
        out_of_sample_fitted: error_stats(&scored),
        calibration,
    };
    Ok((outcome, scored))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The plan's size: consecutive intervals of 10 m from 1,000 m to 11,000 m are 1,000
    /// intervals; at a 1 m step 10,000 steps (accepted), at a 0.04 m step 250,000 (refused,
    /// the message names the remedy).
    #[test]
    fn a_plan_beyond_the_step_bound_is_refused() {
        let intervals: Vec<Interval> = (0..1000)
            .map(|k| Interval {
                from_md_m: 1000.0 + 10.0 * k as f64,
                to_md_m: 1010.0 + 10.0 * k as f64,
                measured: (0.1, 0.2),
            })
            .collect();
        let plan = BackanalysisPlan {
            from_md_m: 1000.0,
            to_md_m: 11_000.0,
            horizon_m: 0.0,
            below_previous_hole_md_m: None,
            intervals,
            calibration: None,
            assimilate: false,
        };
        assert_eq!(plan.march_steps(1.0), 10_000.0);
        assert!(plan.check_size(1.0).is_ok());
        let e = plan.check_size(0.04).unwrap_err();
        assert!(e.contains("250000") && e.contains("--horizon"), "{e}");
    }
}
