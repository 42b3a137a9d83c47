//! Projection to the bit and ahead with survey assimilation (`predict --assimilate`): the march
//! from the last station, corrected by the tendency banks warmed up on the measured hole behind
//! it, with one-standard-deviation bounds on the direction and the position.

use super::assimilate::{
    banks_behind, deviation_from_recent, naive_corrections, survey_covariance, turn_between, turned,
};
use super::bank::{FilterBank, Situation};
use super::references::Direction;
use crate::case::{Case, TrackingSettings};
use crate::geometry::{Frame, Vec3};
use crate::predict::march::Prediction;
use nalgebra::DMatrix;

/// One projected point.
#[derive(Debug, Clone, Copy)]
pub struct ProjectedRow {
    /// MD, m.
    pub md_m: f64,
    /// The assimilated direction.
    pub direction: Direction,
    /// The assimilated position (north, east, TVD), m.
    pub position: Vec3,
    /// The frozen assimilation's direction.
    pub frozen: Direction,
    /// One standard deviation of the inclination against a survey station here, rad.
    pub inc_sd_rad: f64,
    /// Same for the azimuth, rad.
    pub azi_sd_rad: f64,
    /// One standard deviation of the position sideways (toward the right of the hole at the
    /// start), m: an upper bound (the direction errors along the way taken as fully correlated).
    pub lateral_sd_m: f64,
    /// Same toward the high side (vertical in the plane of the hole), m.
    pub vertical_sd_m: f64,
}

/// A projection.
#[derive(Debug, Clone)]
pub struct Projection {
    /// One row per MD asked, from the start.
    pub rows: Vec<ProjectedRow>,
    /// The assimilated bank at the start.
    pub bank: FilterBank,
    /// The model's tendency at the start, held for the hole behind and by the frozen
    /// assimilation (toward the high side, toward the right), rad/m.
    pub model_tendency: [f64; 2],
}

/// The model's tendency at the start of `pred`: its turn over the first tracking interval (or
/// the whole prediction when shorter) per metre, rad/m.
fn model_tendency(pred: &Prediction, tracking: &TrackingSettings) -> [f64; 2] {
    let from = pred.from_md_m;
    let len = tracking.interval_m.min(pred.to_md_m - from);
    if len <= 0.0 {
        return [0.0; 2];
    }
    let d = |md: f64| {
        let p = pred.path.point_at(md);
        Direction {
            inc_rad: p.inc_rad,
            azi_rad: p.azi_rad,
        }
    };
    turn_between(&d(from), &d(from + len)).map(|t| t / len)
}

/// Project `pred` (of `case`, from its start) at `mds` (ascending, within the prediction).
pub fn project(case: &Case, pred: &Prediction, mds: &[f64], tracking: &TrackingSettings) -> Projection {
    let from = pred.from_md_m;
    let kappa = model_tendency(pred, tracking);
    let horizon = (pred.to_md_m - from).clamp(tracking.interval_m, (tracking.window_m / 2.0).max(tracking.interval_m));
    let (bank, frozen) = banks_behind(case, from, kappa, horizon, tracking);
    let dev = deviation_from_recent(case, from);
    let s = pred.path.point_at(from);
    let start = Direction {
        inc_rad: s.inc_rad,
        azi_rad: s.azi_rad,
    };
    let sf = Frame::from_tangent(&s.tangent, s.azi_rad);
    let none = DMatrix::zeros(2, 0);
    let mut rows: Vec<ProjectedRow> = Vec::with_capacity(mds.len());
    let (mut lat, mut vert, mut last) = (0.0, 0.0, (from, [0.0; 2]));
    for &md in mds {
        let u = md - from;
        let p = pred.path.point_at(md);
        let march = Direction {
            inc_rad: p.inc_rad,
            azi_rad: p.azi_rad,
        };
        let mt = turn_between(&start, &march);
        let excess = [mt[0] - kappa[0] * u, mt[1] - kappa[1] * u];
        let naive = naive_corrections(&case.well.path, from, md, &march);
        let at = Situation {
            from_md_m: from,
            deviation: dev,
            excess,
            naive: &naive,
        };
        let c = bank.predicted_turn(u.max(1e-6), &at);
        let direction = turned(&march, c);
        let off = bank.predicted_offset(u, &at);
        let position = p.position + sf.h * off[0] + sf.r * off[1];
        let held = turned(&start, [kappa[0] * u, kappa[1] * u]);
        let frozen_naive = naive_corrections(&case.well.path, from, md, &held);
        let frozen_at = Situation {
            from_md_m: from,
            deviation: dev,
            excess: [0.0; 2],
            naive: &frozen_naive,
        };
        let frozen_dir = turned(&held, frozen.predicted_turn(u.max(1e-6), &frozen_at));
        let cov = bank.calibrated(
            &(bank.turn_covariance(u.max(1e-6), &none, &at) + survey_covariance(tracking, direction.inc_rad)),
        );
        let sd = [cov[(0, 0)].sqrt(), cov[(1, 1)].sqrt()];
        // the position's bound: the direction's standard deviation integrated along the way
        let du = md - last.0;
        vert += 0.5 * (sd[0] + last.1[0]) * du;
        lat += 0.5 * (sd[1] + last.1[1]) * du;
        last = (md, sd);
        rows.push(ProjectedRow {
            md_m: md,
            direction,
            position,
            frozen: frozen_dir,
            inc_sd_rad: sd[0],
            azi_sd_rad: (sd[1] / direction.inc_rad.sin().max(1e-6)).min(std::f64::consts::PI),
            lateral_sd_m: lat,
            vertical_sd_m: vert,
        });
    }
    Projection {
        rows,
        bank,
        model_tendency: kappa,
    }
}
