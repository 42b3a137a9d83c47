//! Tracking: a prediction compared with measured stations, rates over the interval, and the
//! output rows of `trajectory.csv` (docs/guide.md).

use super::march::{Prediction, StepRecord, StepSteer};
use crate::geometry::survey::wrap_pi;
use crate::geometry::{Vec3, WellPath};
use crate::models::fem::results::BitResult;

/// One output station.
#[derive(Debug, Clone, Copy)]
pub struct TrajectoryRow {
    /// MD, m.
    pub md_m: f64,
    /// Predicted inclination, rad.
    pub inc_rad: f64,
    /// Predicted azimuth, rad.
    pub azi_rad: f64,
    /// Predicted position (north, east, tvd), m.
    pub position: Vec3,
    /// Measured inclination and azimuth, rad, where a station is measured here.
    pub measured: Option<(f64, f64)>,
    /// Bit forces and tilt with the bit here (linear between solved steps).
    pub bit: BitResult,
    /// How a bent housing drilled the step ending here or next (None: a straight string).
    pub steer: Option<StepSteer>,
    /// The reactive torque's turn of the toolface in that step, rad
    /// ([`StepRecord::reactive_turn_rad`]).
    pub reactive_turn_rad: Option<f64>,
}

impl TrajectoryRow {
    /// Inclination and azimuth errors (predicted - measured, azimuth wrapped to (-pi, pi]), rad.
    pub fn errors(&self) -> Option<(f64, f64)> {
        self.measured
            .map(|(i, a)| (self.inc_rad - i, wrap_pi(self.azi_rad - a)))
    }
}

/// Bit results at `md_m`, linear between the solved steps around it.
pub fn bit_at(steps: &[StepRecord], md_m: f64) -> BitResult {
    let k = steps.partition_point(|r| r.md_m <= md_m);
    if k == 0 {
        return steps[0].bit;
    }
    if k >= steps.len() {
        return steps[steps.len() - 1].bit;
    }
    let (a, b) = (&steps[k - 1], &steps[k]);
    let lam = if b.md_m > a.md_m {
        (md_m - a.md_m) / (b.md_m - a.md_m)
    } else {
        0.0
    };
    let mix = |x: f64, y: f64| x + lam * (y - x);
    BitResult {
        md_m,
        wob_n: mix(a.bit.wob_n, b.bit.wob_n),
        build_force_n: mix(a.bit.build_force_n, b.bit.build_force_n),
        walk_force_n: mix(a.bit.walk_force_n, b.bit.walk_force_n),
        tilt_inc_rad: mix(a.bit.tilt_inc_rad, b.bit.tilt_inc_rad),
        tilt_azi_rad: mix(a.bit.tilt_azi_rad, b.bit.tilt_azi_rad),
        torque_nm: mix(a.bit.torque_nm, b.bit.torque_nm),
        sensor_sag_rad: a.bit.sensor_sag_rad.zip(b.bit.sensor_sag_rad).map(|(x, y)| mix(x, y)),
    }
}

/// How the step ending at or next after `md_m` was drilled (the last step's beyond the end).
pub fn steer_at(steps: &[StepRecord], md_m: f64) -> Option<StepSteer> {
    step_at(steps, md_m).and_then(|r| r.steer)
}

/// The step ending at or next after `md_m` (the last step beyond the end).
fn step_at(steps: &[StepRecord], md_m: f64) -> Option<&StepRecord> {
    let k = steps.partition_point(|r| r.md_m < md_m - 1e-9);
    steps.get(k).or(steps.last())
}

/// Output rows: every solved step, plus every measured station of `measured` within the
/// prediction's interval (predicted values interpolated on the predicted hole), sorted by MD.
pub fn trajectory_rows(pred: &Prediction, measured: Option<&WellPath>) -> Vec<TrajectoryRow> {
    let mut mds: Vec<f64> = pred.steps.iter().map(|r| r.md_m).collect();
    let stations: Vec<(f64, f64, f64)> = measured
        .map(|m| {
            m.stations()
                .iter()
                .filter(|s| s.md_m >= pred.from_md_m - 1e-6 && s.md_m <= pred.to_md_m + 1e-6)
                .map(|s| (s.md_m, s.inc_rad, s.azi_rad))
                .collect()
        })
        .unwrap_or_default();
    mds.extend(stations.iter().map(|s| s.0));
    mds.sort_by(f64::total_cmp);
    mds.dedup_by(|a, b| (*a - *b).abs() < 1e-6);
    mds.into_iter()
        .map(|md| {
            let p = pred.path.point_at(md);
            let meas = stations.iter().find(|s| (s.0 - md).abs() < 1e-6).map(|s| (s.1, s.2));
            TrajectoryRow {
                md_m: md,
                inc_rad: p.inc_rad,
                azi_rad: p.azi_rad,
                position: p.position,
                measured: meas,
                bit: bit_at(&pred.steps, md),
                steer: steer_at(&pred.steps, md),
                reactive_turn_rad: step_at(&pred.steps, md).and_then(|r| r.reactive_turn_rad),
            }
        })
        .collect()
}

/// Rates and mean bit quantities of a prediction over its interval.
#[derive(Debug, Clone, Copy)]
pub struct IntervalRates {
    /// Predicted length, m.
    pub length_m: f64,
    /// Inclination change over the interval per 30 m, rad.
    pub build_rate_rad_per_30m: f64,
    /// Azimuth change (wrapped) over the interval per 30 m, rad.
    pub walk_rate_rad_per_30m: f64,
    /// Mean build force over the solved steps, N.
    pub mean_build_force_n: f64,
    /// Mean walk force, N.
    pub mean_walk_force_n: f64,
    /// Mean tilt toward higher inclination, rad.
    pub mean_tilt_inc_rad: f64,
    /// Mean tilt to the right, rad.
    pub mean_tilt_azi_rad: f64,
}

/// Build and walk rates of `pred` over its whole interval, and the mean bit values.
pub fn interval_rates(pred: &Prediction) -> IntervalRates {
    let a = pred.path.point_at(pred.from_md_m);
    let b = pred.path.point_at(pred.to_md_m);
    let len = pred.to_md_m - pred.from_md_m;
    let per30 = if len > 0.0 { 30.0 / len } else { 0.0 };
    let n = pred.steps.len() as f64;
    let mean = |f: &dyn Fn(&StepRecord) -> f64| pred.steps.iter().map(f).sum::<f64>() / n;
    IntervalRates {
        length_m: len,
        build_rate_rad_per_30m: (b.inc_rad - a.inc_rad) * per30,
        walk_rate_rad_per_30m: wrap_pi(b.azi_rad - a.azi_rad) * per30,
        mean_build_force_n: mean(&|r| r.bit.build_force_n),
        mean_walk_force_n: mean(&|r| r.bit.walk_force_n),
        mean_tilt_inc_rad: mean(&|r| r.bit.tilt_inc_rad),
        mean_tilt_azi_rad: mean(&|r| r.bit.tilt_azi_rad),
    }
}

/// Tracking errors against the measured stations of a prediction's rows.
#[derive(Debug, Clone, Copy)]
pub struct TrackingErrors {
    /// Measured stations compared (the start station excluded).
    pub stations: usize,
    /// MD of the last compared station, m.
    pub end_md_m: f64,
    /// Inclination error at the last compared station (predicted - measured), rad.
    pub end_inc_err_rad: f64,
    /// Azimuth error at the last compared station, rad.
    pub end_azi_err_rad: f64,
    /// The seed paper's metric: |end inclination error| per 100 m tracked, rad.
    pub inc_err_per_100m_rad: f64,
    /// |end azimuth error| per 100 m tracked, rad.
    pub azi_err_per_100m_rad: f64,
    /// Largest |inclination error| over the compared stations, rad.
    pub max_abs_inc_err_rad: f64,
    /// Largest |azimuth error|, rad.
    pub max_abs_azi_err_rad: f64,
}

/// Errors of `rows` against their measured stations after `from_md_m` (None if none).
pub fn tracking_errors(rows: &[TrajectoryRow], from_md_m: f64) -> Option<TrackingErrors> {
    let cmp: Vec<(f64, (f64, f64))> = rows
        .iter()
        .filter(|r| r.md_m > from_md_m + 1e-6)
        .filter_map(|r| r.errors().map(|e| (r.md_m, e)))
        .collect();
    let &(end_md, (ei, ea)) = cmp.last()?;
    let tracked = end_md - from_md_m;
    Some(TrackingErrors {
        stations: cmp.len(),
        end_md_m: end_md,
        end_inc_err_rad: ei,
        end_azi_err_rad: ea,
        inc_err_per_100m_rad: ei.abs() * 100.0 / tracked,
        azi_err_per_100m_rad: ea.abs() * 100.0 / tracked,
        max_abs_inc_err_rad: cmp.iter().map(|c| c.1 .0.abs()).fold(0.0, f64::max),
        max_abs_azi_err_rad: cmp.iter().map(|c| c.1 .1.abs()).fold(0.0, f64::max),
    })
}
