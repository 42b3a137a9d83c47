//! One torque-and-drag chart as `drillpath loads` computes it: the bit depths, the friction
//! calibration on measured loads (when given; the chart then uses the fitted factors), the
//! soft-string rows and, at the `hybrid` or `whole` level, their stiff columns.

use super::calibrate::{calibrate, calibrated_case, Calibration, CalibrationError, MeasuredPoint};
use super::chart::{soft_chart, ChartSettings};
use super::row::LoadRow;
use super::stiff::{hybrid_depth, stiff_depth, Solved};
use super::{case_for_row, check_fits, depth_list, ChartOperation, MODES};
use crate::case::fidelity::Choice;
use crate::case::{Case, Level, Mode};
use crate::models::lock_up_depth::{lock_up_depths, Drag, LockUpDepths};
use crate::models::softstring::segment_length_m;
use std::time::Instant;

/// Most bit depths a chart computes.
pub const MAX_DEPTHS: usize = 100_000;

/// What chart to compute, SI.
#[derive(Debug, Clone, PartialEq)]
pub struct ChartRequest {
    /// Shallowest bit depth, m.
    pub from_md_m: f64,
    /// Deepest bit depth, m (None: the case's bit depth).
    pub to_md_m: Option<f64>,
    /// Bit-depth step, m (> 0).
    pub every_m: f64,
    /// WOB of the on-bottom rows, N (None: the case's).
    pub wob_n: Option<f64>,
    /// Model level of the stiff columns (`soft`: none) and why.
    pub choice: Choice,
    /// Measured hook loads and torques to fit the friction factors to (empty: no calibration).
    pub measured: Vec<MeasuredPoint>,
}

/// Why a chart cannot be computed. The variants name what was asked: the CLI maps them to
/// its options and files.
#[derive(Debug, thiserror::Error)]
pub enum ChartError {
    /// The case has no string.
    #[error("the case has no [[string]] components")]
    NoString,
    /// The deepest bit depth lies below the surveyed hole.
    #[error("bit depth {to_md_m:.2} m is below the surveyed hole and its sections (deepest {deepest_md_m:.2} m)")]
    BelowHole {
        /// Deepest bit depth asked, m.
        to_md_m: f64,
        /// Deepest hole, m.
        deepest_md_m: f64,
    },
    /// The range is upside down.
    #[error("--to ({to_md_m:.2} m) is above --from ({from_md_m:.2} m)")]
    Inverted {
        /// Shallowest bit depth, m.
        from_md_m: f64,
        /// Deepest bit depth, m.
        to_md_m: f64,
    },
    /// No bit depth lies below the top of the survey.
    #[error("no bit depth below the top of the survey in the range")]
    NoDepth,
    /// Too many bit depths.
    #[error("{0} bit depths, more than the {MAX_DEPTHS} a chart may have: use a longer step")]
    TooManyDepths(usize),
    /// The string does not fit the hole at a bit depth.
    #[error("{0}")]
    DoesNotFit(String),
    /// The string does not fit the hole at a measured point's bit depth.
    #[error("{message}")]
    MeasuredDoesNotFit {
        /// Line of the point in its file.
        line: usize,
        /// What does not fit.
        message: String,
    },
    /// The friction calibration failed.
    #[error(transparent)]
    Calibration(#[from] CalibrationError),
}

/// Where a chart runs: validated bit depths and operation.
#[derive(Debug, Clone)]
pub struct ChartPlan {
    /// Bit depths, m, shallowest first.
    pub depths: Vec<f64>,
    /// WOB, RPM and ROP of the rows.
    pub op: ChartOperation,
    /// Soft-string segment length, m.
    pub max_element_m: f64,
    /// Model level of the stiff columns and why.
    pub choice: Choice,
    /// Measured points to calibrate on (empty: none).
    pub measured: Vec<MeasuredPoint>,
}

/// A computed chart.
#[derive(Debug, Clone)]
pub struct Chart {
    /// One row per bit depth and load case ([`MODES`] order within a depth).
    pub rows: Vec<LoadRow>,
    /// The friction calibration, when measured points were given.
    pub calibration: Option<Calibration>,
    /// Time of the soft-string rows, s.
    pub soft_seconds: f64,
    /// Time of the stiff columns, s (0 at the `soft` level).
    pub stiff_seconds: f64,
    /// The lock-up depths of the on-bottom load cases and of running in that are locked up at the
    /// deepest bit depth (at the chart's WOB, running in at zero WOB; by the model of [`Drag::of`],
    /// [`crate::models::lock_up_depth`]), in [`MODES`] order.
    pub lock_up_depths: Vec<(Mode, LockUpDepths)>,
}

/// MDs between which a bit depth may lie, m: the top of the survey and the deepest hole (the
/// end of the survey or of the hole sections, whichever is shallower).
pub fn bit_depth_range(case: &Case) -> (f64, f64) {
    let path = &case.well.path;
    (path.md_start(), path.md_end().min(case.well.hole.deepest_md()))
}

/// Validate `req` against `case` and list the bit depths (see [`ChartError`]).
pub fn plan(case: &Case, req: &ChartRequest) -> Result<ChartPlan, ChartError> {
    if case.string.components.is_empty() {
        return Err(ChartError::NoString);
    }
    let (md_start, deepest) = bit_depth_range(case);
    let to = req.to_md_m.unwrap_or(case.operation.bit_md_m);
    if to > deepest + 1e-6 {
        return Err(ChartError::BelowHole {
            to_md_m: to,
            deepest_md_m: deepest,
        });
    }
    if to < req.from_md_m {
        return Err(ChartError::Inverted {
            from_md_m: req.from_md_m,
            to_md_m: to,
        });
    }
    // counted before the list is built: a tiny step must not exhaust the memory
    let count = (to - req.from_md_m.max(md_start)) / req.every_m + 1.0;
    if count > MAX_DEPTHS as f64 {
        return Err(ChartError::TooManyDepths(count.ceil() as usize));
    }
    let depths = depth_list(req.from_md_m, to, req.every_m, md_start);
    if depths.is_empty() {
        return Err(ChartError::NoDepth);
    }
    if depths.len() > MAX_DEPTHS {
        return Err(ChartError::TooManyDepths(depths.len()));
    }
    for &d in &depths {
        check_fits(&case.string.at_depth(d), &case.well.hole, d).map_err(ChartError::DoesNotFit)?;
    }
    for p in &req.measured {
        check_fits(&case.string.at_depth(p.bit_md_m), &case.well.hole, p.bit_md_m)
            .map_err(|message| ChartError::MeasuredDoesNotFit { line: p.line, message })?;
    }
    let mut op = ChartOperation::from_case(case);
    if let Some(w) = req.wob_n {
        op.wob_n = w;
    }
    Ok(ChartPlan {
        depths,
        op,
        max_element_m: segment_length_m(&case.solver),
        choice: req.choice.clone(),
        measured: req.measured.clone(),
    })
}

/// Compute the chart of `case` as `plan` says; `on_depth` hears (depth index, bit MD) before
/// each depth's stiff rows.
pub fn run(case: &Case, plan: &ChartPlan, on_depth: &mut dyn FnMut(usize, f64)) -> Result<Chart, ChartError> {
    let calibration = if plan.measured.is_empty() {
        None
    } else {
        Some(calibrate(case, &plan.measured, &plan.op, plan.max_element_m)?)
    };
    let chart_case = match &calibration {
        Some(c) => calibrated_case(case, c),
        None => case.clone(),
    };
    let settings = ChartSettings {
        op: plan.op,
        max_element_m: plan.max_element_m,
    };
    let t0 = Instant::now();
    let mut rows = soft_chart(&chart_case, &plan.depths, &settings);
    let soft_seconds = t0.elapsed().as_secs_f64();
    let t1 = Instant::now();
    let level = plan.choice.level;
    if level != Level::Soft {
        stiff_rows(&chart_case, &plan.depths, &plan.op, level, &mut rows, on_depth);
    }
    let lock_up_depths = chart_lock_up_depths(&chart_case, plan);
    Ok(Chart {
        rows,
        lock_up_depths,
        calibration,
        soft_seconds,
        stiff_seconds: if level == Level::Soft {
            0.0
        } else {
            t1.elapsed().as_secs_f64()
        },
    })
}

/// The lock-up depths ([`Chart::lock_up_depths`]) of the chart of `case` planned by `plan`.
fn chart_lock_up_depths(case: &Case, plan: &ChartPlan) -> Vec<(Mode, LockUpDepths)> {
    let Some(&deepest) = plan.depths.last() else {
        return Vec::new();
    };
    let string = case.string.at_depth(deepest);
    MODES
        .iter()
        .filter(|m| m.on_bottom() || **m == Mode::TripIn)
        .filter_map(|&mode| {
            let row_case = case_for_row(case, &string, deepest, mode, &plan.op);
            let wob = row_case.operation.wob_n;
            let depths = lock_up_depths(&row_case, wob, Drag::of(&row_case, wob));
            depths.at_wob_md_m.is_some().then_some((mode, depths))
        })
        .collect()
}

/// Fill the stiff columns of the chart `rows` of `case` at `depths` with the `level` (whole or
/// hybrid) model; whole-string rows are warm-started from the same load case one depth up.
/// `on_depth` hears (depth index, bit MD) before each depth.
pub fn stiff_rows(
    case: &Case,
    depths: &[f64],
    op: &ChartOperation,
    level: Level,
    rows: &mut [LoadRow],
    on_depth: &mut dyn FnMut(usize, f64),
) {
    let t1 = Instant::now();
    let mut previous: Vec<Option<Solved>> = Vec::new();
    for (k, &d) in depths.iter().enumerate() {
        on_depth(k, d);
        let c = case.at_bit_depth(d);
        let depth_rows = &mut rows[k * MODES.len()..(k + 1) * MODES.len()];
        let wobs: Vec<f64> = depth_rows.iter().map(|r| r.wob_n).collect();
        let outcomes = if level == Level::Hybrid {
            hybrid_depth(&c, d, op, &wobs)
        } else {
            let (outcomes, solved) = stiff_depth(&c, d, op, &wobs, &previous);
            previous = solved;
            outcomes
        };
        for (r, o) in depth_rows.iter_mut().zip(outcomes) {
            r.stiff = Some(o);
            r.stiff_level = Some(level);
        }
        tracing::info!(
            "{}: bit depth {d:.1} m done ({}/{}, {:.1} s)",
            level.name(),
            k + 1,
            depths.len(),
            t1.elapsed().as_secs_f64()
        );
    }
}
