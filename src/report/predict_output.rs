//! Outputs of `predict` and `backanalyze`: `trajectory.csv` (interface.md columns) and the
//! JSON summaries.

use super::{finite, num};
use crate::models::fem::results::BitResult;
use crate::predict::backanalysis::{ErrorStats, IntervalResult};
use crate::predict::calibrate::{Calibration, FitParameter};
use crate::predict::law::LawParams;
use crate::predict::track::{IntervalRates, TrackingErrors, TrajectoryRow};
use serde_json::{json, Value};

/// Header of `trajectory.csv` (interface.md).
pub const TRAJECTORY_HEADER: &str = "md_m,inc_deg,azi_deg,tvd_m,north_m,east_m,inc_meas_deg,azi_meas_deg,inc_err_deg,azi_err_deg,build_force_kN,walk_force_kN,tilt_inc_deg,tilt_azi_deg,wob_kN";

fn opt(x: Option<f64>, decimals: usize) -> Result<String, String> {
    x.map(|v| num(v, decimals)).transpose().map(|s| s.unwrap_or_default())
}

fn row_line(
    md: f64,
    inc: f64,
    azi: f64,
    pos: &crate::geometry::Vec3,
    meas: Option<(f64, f64)>,
    err: Option<(f64, f64)>,
    bit: &BitResult,
) -> Result<String, String> {
    Ok(format!(
        "{},{},{},{},{},{},{},{},{},{},{},{},{},{},{}\n",
        num(md, 3)?,
        num(inc.to_degrees(), 4)?,
        num(azi.to_degrees().rem_euclid(360.0), 4)?,
        num(pos.z, 3)?,
        num(pos.x, 3)?,
        num(pos.y, 3)?,
        opt(meas.map(|m| m.0.to_degrees()), 4)?,
        opt(meas.map(|m| m.1.to_degrees().rem_euclid(360.0)), 4)?,
        opt(err.map(|e| e.0.to_degrees()), 4)?,
        opt(err.map(|e| e.1.to_degrees()), 4)?,
        num(bit.build_force_n / 1e3, 4)?,
        num(bit.walk_force_n / 1e3, 4)?,
        num(bit.tilt_inc_rad.to_degrees(), 5)?,
        num(bit.tilt_azi_rad.to_degrees(), 5)?,
        num(bit.wob_n / 1e3, 3)?,
    ))
}

/// `trajectory.csv` of `predict`.
pub fn trajectory_csv(rows: &[TrajectoryRow]) -> Result<String, String> {
    let mut out = format!("{TRAJECTORY_HEADER}\n");
    for r in rows {
        out.push_str(&row_line(
            r.md_m,
            r.inc_rad,
            r.azi_rad,
            &r.position,
            r.measured,
            r.errors(),
            &r.bit,
        )?);
    }
    Ok(out)
}

/// `trajectory.csv` of `backanalyze`: one row per interval end, bit values at the end.
pub fn backanalysis_csv(results: &[IntervalResult]) -> Result<String, String> {
    let mut out = format!("{TRAJECTORY_HEADER}\n");
    for r in results {
        out.push_str(&row_line(
            r.interval.to_md_m,
            r.inc_rad,
            r.azi_rad,
            &r.position,
            Some(r.interval.measured),
            Some((r.inc_err_rad(), r.azi_err_rad())),
            &r.bit_end,
        )?);
    }
    Ok(out)
}

/// The law's parameters as JSON (angles in degrees).
pub fn law_json(law: &str, p: &LawParams, formations: usize) -> Result<Value, String> {
    Ok(json!({
        "law": law,
        "lateral_drillability": finite(p.lateral_drillability)?,
        "walk_angle_deg": finite(p.walk_angle_rad.to_degrees())?,
        "rock_anisotropy": finite(p.rock_anisotropy)?,
        "dip_deg": finite(p.dip_rad.to_degrees())?,
        "dip_direction_deg": finite(p.dip_direction_rad.to_degrees())?,
        "formation_intervals": formations,
    }))
}

/// Rates over an interval as JSON.
pub fn rates_json(r: &IntervalRates) -> Result<Value, String> {
    Ok(json!({
        "length_m": finite(r.length_m)?,
        "build_rate_deg_per_30m": finite(r.build_rate_rad_per_30m.to_degrees())?,
        "walk_rate_deg_per_30m": finite(r.walk_rate_rad_per_30m.to_degrees())?,
        "mean_build_force_kN": finite(r.mean_build_force_n / 1e3)?,
        "mean_walk_force_kN": finite(r.mean_walk_force_n / 1e3)?,
        "mean_tilt_inc_deg": finite(r.mean_tilt_inc_rad.to_degrees())?,
        "mean_tilt_azi_deg": finite(r.mean_tilt_azi_rad.to_degrees())?,
    }))
}

/// Tracking errors as JSON.
pub fn tracking_json(e: &TrackingErrors) -> Result<Value, String> {
    Ok(json!({
        "stations_compared": e.stations,
        "end_md_m": finite(e.end_md_m)?,
        "end_inc_err_deg": finite(e.end_inc_err_rad.to_degrees())?,
        "end_azi_err_deg": finite(e.end_azi_err_rad.to_degrees())?,
        "inc_err_per_100m_deg": finite(e.inc_err_per_100m_rad.to_degrees())?,
        "azi_err_per_100m_deg": finite(e.azi_err_per_100m_rad.to_degrees())?,
        "max_abs_inc_err_deg": finite(e.max_abs_inc_err_rad.to_degrees())?,
        "max_abs_azi_err_deg": finite(e.max_abs_azi_err_rad.to_degrees())?,
    }))
}

/// Back-analysis error statistics as JSON (interface keys `inc_err_per_100m_deg` and
/// `azi_err_per_100m_deg` are the mean absolute errors per 100 m).
pub fn error_stats_json(e: &ErrorStats) -> Result<Value, String> {
    Ok(json!({
        "intervals": e.intervals,
        "inc_err_per_100m_deg": finite(e.inc_mean_abs_per_100m_rad.to_degrees())?,
        "azi_err_per_100m_deg": finite(e.azi_mean_abs_per_100m_rad.to_degrees())?,
        "inc_rms_per_100m_deg": finite(e.inc_rms_per_100m_rad.to_degrees())?,
        "azi_rms_per_100m_deg": finite(e.azi_rms_per_100m_rad.to_degrees())?,
    }))
}

/// Calibration result as JSON (walk angle in degrees).
pub fn calibration_json(c: &Calibration) -> Result<Value, String> {
    let fitted: Vec<Value> = c
        .fitted
        .iter()
        .map(|&(p, v, sd)| {
            let (v, sd) = if p == FitParameter::WalkAngle {
                (v.to_degrees(), sd.to_degrees())
            } else {
                (v, sd)
            };
            Ok(json!({
                "name": if p == FitParameter::WalkAngle { "walk_angle_deg" } else { p.name() },
                "value": finite(v)?,
                "std_dev": if sd.is_finite() { json!(sd) } else { Value::Null },
                "identifiable": sd.is_finite() && sd < if p == FitParameter::WalkAngle { p.identifiable_below().to_degrees() } else { p.identifiable_below() },
            }))
        })
        .collect::<Result<_, String>>()?;
    Ok(json!({
        "fitted": fitted,
        "ssr_start": finite(c.ssr_start)?,
        "ssr_end": finite(c.ssr_end)?,
        "iterations": c.iterations,
    }))
}

/// The fitted `[bit_rock]` keys as TOML lines to paste into a case file.
pub fn fitted_toml(c: &Calibration) -> String {
    let mut s = String::from("# fitted by drillpath backanalyze --calibrate\n[bit_rock]\n");
    for &(p, v, sd) in &c.fitted {
        match p {
            FitParameter::WalkAngle => s.push_str(&format!(
                "walk_angle = \"{:.4} deg\"   # +/- {:.4} deg\n",
                v.to_degrees(),
                sd.to_degrees()
            )),
            _ => s.push_str(&format!("{} = {:.6}   # +/- {:.6}\n", p.name(), v, sd)),
        }
    }
    s
}
