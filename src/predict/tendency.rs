//! Tendency sweeps for pre-drill design (`drillpath tendency`, docs/guide.md "Tendency
//! charts"): the steady dogleg of 9.9 ([`steady_turn`]) of a steerable assembly over a grid of
//! settings, each point an independent solve run in parallel (rayon).
//!
//! Two sweeps: the **capability**, the dogleg the tool gives against its setting (a bent
//! housing's bend angle, sliding at the operation's toolface; an RSS's steering ratio, rotating)
//! for several WOBs (and a bent housing's pad stabilizer ODs) at the case's hole; and the **rotary** tendency, the assembly rotating
//! without steering (a bent housing turning with the string, an RSS neutral) against the
//! inclination of a straight hole, for the same WOBs.

use super::steer::{steady_turn, SteadyTurn};
use crate::case::Case;
use crate::geometry::{Station, Survey, Vec3, WellPath};
use crate::models::fem::solve::SolveControls;
use crate::string::MotorBend;
use rayon::prelude::*;

/// Which sweep a point belongs to.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Sweep {
    /// The tool's setting against the dogleg, at the case's hole.
    Capability,
    /// The assembly rotating without steering, against the inclination.
    Rotary,
}

impl Sweep {
    /// `capability` or `rotary`.
    pub fn name(self) -> &'static str {
        match self {
            Sweep::Capability => "capability",
            Sweep::Rotary => "rotary",
        }
    }
}

/// The grid of a tendency sweep, SI.
#[derive(Debug, Clone, PartialEq)]
pub struct TendencyGrid {
    /// The settings of the capability sweep: bend angles (rad) of a bent housing, or steering
    /// ratios (0-1) of an RSS.
    pub settings: Vec<f64>,
    /// Weights on bit, N (both sweeps).
    pub wobs_n: Vec<f64>,
    /// Blade ODs of the bent housing's pad stabilizer in the capability sweep, m (empty: the
    /// case's pad, or none).
    pub pad_ods_m: Vec<f64>,
    /// Inclinations of the rotary sweep, rad.
    pub incs_rad: Vec<f64>,
}

/// One point of a sweep and its steady dogleg.
#[derive(Debug, Clone)]
pub struct TendencyPoint {
    /// The sweep.
    pub sweep: Sweep,
    /// The bend angle of the bent housing, rad (None for an RSS).
    pub bend_rad: Option<f64>,
    /// The RSS's steering ratio (None for a bent housing).
    pub ratio: Option<f64>,
    /// Weight on bit, N.
    pub wob_n: f64,
    /// Blade OD of the bent housing's pad stabilizer, m (None without one).
    pub pad_od_m: Option<f64>,
    /// Diametral under-gauge of the pad: the hole's diameter at the pad less its blade OD, m
    /// (None without a pad).
    pub pad_under_gauge_m: Option<f64>,
    /// Inclination of the hole at the bit, rad.
    pub inc_rad: f64,
    /// The string rotates (else it slides).
    pub rotating: bool,
    /// The toolface, rad.
    pub toolface_rad: f64,
    /// The steady dogleg, or why it was not found.
    pub turn: Result<SteadyTurn, String>,
}

/// The tool a sweep varies: `Some(bend)` for a bent housing, None for an RSS; an error when the
/// string has neither.
fn tool(case: &Case) -> Result<Option<MotorBend>, String> {
    match (case.string.bend(), case.string.rss()) {
        (Some(b), _) => Ok(Some(b)),
        (None, Some(_)) => Ok(None),
        (None, None) => Err("the string has no bent housing (`bend_angle` on a motor) or rotary steerable system (`rss` component): nothing to sweep".into()),
    }
}

/// `case` with the bent housing's angle set to `angle_rad` (0: a straight housing).
fn with_bend(case: &Case, angle_rad: f64) -> Case {
    let mut c = case.clone();
    for comp in &mut c.string.components {
        if let Some(b) = comp.bend {
            comp.bend = (angle_rad > 0.0).then_some(MotorBend { angle_rad, ..b });
        }
    }
    c
}

/// The hole's diameter at the middle of the bent housing's pad stabilizer, m (None without a
/// pad: [`crate::string::DrillString::pad_index`]).
pub fn pad_hole_diameter_m(case: &Case) -> Option<f64> {
    let c = &case.string.components[case.string.pad_index()?];
    let md = case.operation.bit_md_m - (c.bottom_m + c.length_m / 2.0);
    Some(case.well.hole.diameter_at(md))
}

/// `case` with its pad stabilizer's blade OD `pad_od_m` (m; None: as it is).
fn with_pad(case: &Case, pad_od_m: Option<f64>) -> Case {
    let mut c = case.clone();
    if let Some(d) = pad_od_m {
        c.string = c.string.with_pad_od(d);
    }
    c
}

/// `case` with its hole straight at inclination `inc_rad` and the azimuth of the hole at the
/// bit, from the surface to the bit (the hole sizes and friction kept).
pub fn at_inclination(case: &Case, inc_rad: f64) -> Result<Case, String> {
    let md = case.operation.bit_md_m;
    let azi = case.well.path.point_at(md).azi_rad;
    let st = |md_m: f64| Station {
        md_m,
        inc_rad,
        azi_rad: azi,
    };
    let survey = Survey::new(vec![st(0.0), st(md)]).map_err(|p| p.message)?;
    let mut c = case.clone();
    c.well.path = WellPath::new(&survey, Vec3::zeros()).map_err(|p| p.message)?;
    Ok(c)
}

/// `case` on bottom at `wob_n`, rotating (drilling at its rpm, 60 when it gives none) or sliding.
fn operated(case: &Case, wob_n: f64, rotating: bool) -> Case {
    let mut c = case.on_bottom(rotating);
    c.operation.wob_n = wob_n;
    c.operation.hook_load_n = None;
    c
}

/// The points of `grid` for `case` (capability first, by WOB, pad OD and setting; then rotary,
/// by WOB and inclination, at the case's pad), each with the case to solve; an error when the
/// string has no steering tool.
pub fn sweep_cases(case: &Case, grid: &TendencyGrid) -> Result<Vec<(TendencyPoint, Case)>, String> {
    let bend = tool(case)?;
    let here = case.well.path.point_at(case.operation.bit_md_m).inc_rad;
    let tf = case.operation.toolface_rad;
    let hole = pad_hole_diameter_m(case);
    let point = |sweep, bend_rad, ratio, (wob_n, pad): (f64, Option<f64>), inc_rad, rotating| TendencyPoint {
        sweep,
        bend_rad,
        ratio,
        wob_n,
        pad_od_m: pad,
        pad_under_gauge_m: pad.zip(hole).map(|(p, h)| h - p),
        inc_rad,
        rotating,
        toolface_rad: tf,
        turn: Err(String::new()),
    };
    let own = case.string.pad_od_m();
    let pads: Vec<Option<f64>> = match (bend, grid.pad_ods_m.is_empty() || own.is_none()) {
        (Some(_), false) => grid.pad_ods_m.iter().map(|&d| Some(d)).collect(),
        _ => vec![own],
    };
    let mut out = Vec::new();
    for &w in &grid.wobs_n {
        for &pad in &pads {
            for &s in &grid.settings {
                out.push(match bend {
                    Some(_) => (
                        point(Sweep::Capability, Some(s), None, (w, pad), here, false),
                        operated(&with_bend(&with_pad(case, pad), s), w, false),
                    ),
                    None => {
                        let mut c = operated(case, w, true);
                        c.string = c.string.with_rss_ratio(s);
                        (point(Sweep::Capability, None, Some(s), (w, pad), here, true), c)
                    }
                });
            }
        }
    }
    for &w in &grid.wobs_n {
        for &inc in &grid.incs_rad {
            let mut c = operated(&at_inclination(case, inc)?, w, true);
            let (b, r) = match bend {
                Some(b) => (Some(b.angle_rad), None),
                None => {
                    c.string = c.string.with_rss_ratio(0.0);
                    (None, Some(0.0))
                }
            };
            out.push((point(Sweep::Rotary, b, r, (w, own), inc, true), c));
        }
    }
    Ok(out)
}

/// Run the sweep of `grid` over `case`: every point's [`steady_turn`] with `ctl`, independent
/// solves in parallel on rayon's pool (the caller's, e.g. built with a thread count);
/// `done()` is called after each point (from the worker threads). Points keep the order of
/// [`sweep_cases`]; a point whose steady dogleg is not found carries the reason.
pub fn run_sweep(
    case: &Case,
    grid: &TendencyGrid,
    ctl: &SolveControls,
    done: &(dyn Fn() + Sync),
) -> Result<Vec<TendencyPoint>, String> {
    let cases = sweep_cases(case, grid)?;
    Ok(cases
        .into_par_iter()
        .map(|(mut p, c)| {
            p.turn = steady_turn(&c, &c.bit_rock, ctl).map_err(|e| e.to_string());
            done();
            p
        })
        .collect())
}
