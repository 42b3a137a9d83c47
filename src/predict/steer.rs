//! Steerable assemblies in the predictor (docs/theory.md, "Bent motors"): the toolfaces a bent
//! housing is solved at (the operation's when the string slides, [`ROTATING_TOOLFACES`] over a
//! revolution when it rotates), the mean drilling direction over them, and the steady dogleg
//! rate of the assembly: the curvature of a circular hole in which the bit drills along the
//! hole (the motor yield when sliding, the rotating tendency when rotating).

use super::law::deviation;
use super::march::{hole_for_prediction, solve_bit, PredictError, WarmStart};
use crate::case::{BitRock, Case};
use crate::geometry::frame::{inc_azi, MAGNETIC_TOOLFACE_BELOW_RAD};
use crate::geometry::{Station, Survey, Vec3, WellPath};
use crate::models::fem::bha::default_cut_m;
use crate::models::fem::solve::SolveControls;
use crate::string::{MotorBend, RssTool};

pub use super::revolution::{mean_bit, mean_direction, toolfaces, toolfaces_n, SteerState, ROTATING_TOOLFACES};

/// A steady dogleg rate in the hole frame at the bit, rad/m.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SteadyTurn {
    /// Curvature toward the high side (build), rad/m.
    pub build_rad_per_m: f64,
    /// Curvature toward the right side, rad/m (the azimuth rate is this over sin I).
    pub right_rad_per_m: f64,
    /// Newton iterations on the curvature.
    pub iterations: usize,
    /// String solves done.
    pub solves: usize,
}

impl SteadyTurn {
    /// The dogleg rate, rad/m.
    pub fn dogleg_rad_per_m(&self) -> f64 {
        self.build_rad_per_m.hypot(self.right_rad_per_m)
    }
    /// The toolface of the curvature (gravity: from the high side toward the right), rad in
    /// (-pi, pi].
    pub fn toolface_rad(&self) -> f64 {
        self.right_rad_per_m.atan2(self.build_rad_per_m)
    }
}

/// Length of the circular hole behind the bit beyond the string model's cut, m.
const ARC_MARGIN_M: f64 = 30.0;
/// Straight hole above the circular hole, m.
const ARC_LEAD_M: f64 = 100.0;
/// Finite-difference step of the curvature for the Jacobian, rad/m (0.017 deg/30 m).
const CURVATURE_PERTURBATION: f64 = 1e-5;
/// The Newton iteration on the curvature stops when its update is below this, rad/m
/// (0.0006 deg/30 m).
const CURVATURE_TOLERANCE: f64 = 3e-7;
/// Halvings of a Newton update of the curvature whose deviation grows.
const MAX_HALVINGS: usize = 8;
/// Newton iterations allowed on the curvature.
const MAX_CURVATURE_ITERATIONS: usize = 30;
/// Largest change of the curvature per Newton iteration, rad/m (10 deg/30 m).
const MAX_CURVATURE_CHANGE: f64 = 10.0 / 30.0 * std::f64::consts::PI / 180.0;

/// The hole ending at `bit_md_m` with the tangent `t_bit` there, a circle of curvature
/// `curvature` (global, rad/m, perpendicular to `t_bit`: the way the hole turns going down)
/// over the `arc_m` above the bit and straight above that (from MD 0 at most).
pub fn arc_hole(bit_md_m: f64, t_bit: &Vec3, curvature: &Vec3, arc_m: f64) -> Result<WellPath, PredictError> {
    let k = curvature.norm();
    let arc = arc_m.min(bit_md_m);
    // the tangent a distance s above the bit: the bit's turned back by k s
    let t_at = |s: f64| -> Vec3 {
        if k == 0.0 {
            *t_bit
        } else {
            let u = curvature / k;
            (t_bit * (k * s).cos() - u * (k * s).sin()).normalize()
        }
    };
    let station = |md: f64, t: Vec3| -> Station {
        let (inc, azi) = inc_azi(&t, 0.0);
        Station {
            md_m: md,
            inc_rad: inc,
            azi_rad: azi,
        }
    };
    let mut st = Vec::new();
    let top = (bit_md_m - arc - ARC_LEAD_M).max(0.0);
    if top < bit_md_m - arc - 1e-6 {
        st.push(station(top, t_at(arc)));
    }
    if arc < bit_md_m - 1e-9 || st.is_empty() {
        st.push(station(bit_md_m - arc, t_at(arc)));
    }
    st.push(station(bit_md_m, *t_bit));
    let survey = Survey::new(st).map_err(|p| PredictError::Geometry(p.message))?;
    WellPath::new(&survey, Vec3::zeros()).map_err(|p| PredictError::Geometry(p.message))
}

/// The steady dogleg of `case`'s assembly with the bit at the case's bit MD, in the case's
/// mode (sliding at the operation's toolface, or rotating: the mean drilling direction over
/// [`toolfaces`]): the curvature `(k_h, k_r)` of a circular hole ending at the bit with the
/// hole's tangent there, in which the bit-rock law of `bit_rock` drills along the hole
/// (deviation zero), found by Newton's method with a finite-difference Jacobian. The string
/// model is the predictor's (the stiff bottom-hole assembly cut where it lies on the wall).
/// This is the rate the predictor settles to in a hole of constant curvature.
pub fn steady_turn(case: &Case, bit_rock: &BitRock, ctl: &SolveControls) -> Result<SteadyTurn, PredictError> {
    steady_turn_at(case, bit_rock, ctl, &toolfaces(case))
}

/// [`steady_turn`] with the drilling direction averaged over the states `faces`.
pub fn steady_turn_at(
    case: &Case,
    bit_rock: &BitRock,
    ctl: &SolveControls,
    faces: &[SteerState],
) -> Result<SteadyTurn, PredictError> {
    let md = case.operation.bit_md_m;
    let frame = case.well.path.frame_at(md);
    let hole = hole_for_prediction(case, md);
    let p = case.well.path.point_at(md);
    let cut = default_cut_m(&case.string, hole.diameter_at(md), p.inc_rad, case.mud.density_kg_m3);
    let mut solves = 0;
    let mut warm: WarmStart = None;
    let mut eval = |k: [f64; 2], warm: &mut WarmStart| -> Result<[f64; 2], PredictError> {
        let curvature = frame.h * k[0] + frame.r * k[1];
        let path = arc_hole(md, &frame.t, &curvature, cut + ARC_MARGIN_M)?;
        let sol = solve_bit(case, bit_rock, &path, &hole, md, cut, (warm, &None), ctl, faces)?;
        solves += faces.len();
        let (dh, dr) = deviation(&path.frame_at(md), &sol.direction);
        *warm = Some(sol.into_warm());
        Ok([dh, dr])
    };
    let mut k = [0.0f64; 2];
    let mut res = eval(k, &mut warm)?;
    let norm = |r: &[f64; 2]| r[0].abs().max(r[1].abs());
    let mut iterations = 0;
    let mut converged = false;
    while iterations < MAX_CURVATURE_ITERATIONS {
        iterations += 1;
        let mut j = nalgebra::Matrix2::zeros();
        for c in 0..2 {
            let mut kp = k;
            kp[c] += CURVATURE_PERTURBATION;
            let rp = eval(kp, &mut warm.clone())?;
            for r in 0..2 {
                j[(r, c)] = (rp[r] - res[r]) / CURVATURE_PERTURBATION;
            }
        }
        let Some(jinv) = j.try_inverse() else {
            break;
        };
        let mut dk = -(jinv * nalgebra::Vector2::new(res[0], res[1]));
        let big = dk.amax();
        if big > MAX_CURVATURE_CHANGE {
            dk *= MAX_CURVATURE_CHANGE / big;
        }
        // backtracking: halve the update while the deviation grows (contacts that open or
        // close make it steep in places)
        let mut trial_warm = warm.clone();
        let mut r_trial = eval([k[0] + dk[0], k[1] + dk[1]], &mut trial_warm)?;
        for _ in 0..MAX_HALVINGS {
            if norm(&r_trial) <= norm(&res) {
                break;
            }
            dk *= 0.5;
            trial_warm = warm.clone();
            r_trial = eval([k[0] + dk[0], k[1] + dk[1]], &mut trial_warm)?;
        }
        k = [k[0] + dk[0], k[1] + dk[1]];
        (res, warm) = (r_trial, trial_warm);
        if dk.amax() < CURVATURE_TOLERANCE {
            converged = true;
            break;
        }
    }
    if !converged {
        return Err(PredictError::NoDirection {
            md_m: md,
            residual_rad: res[0].abs().max(res[1].abs()),
            step_m: 0.0,
            hint: "; no steady curvature of a circular hole found for this assembly".into(),
        });
    }
    Ok(SteadyTurn {
        build_rad_per_m: k[0],
        right_rad_per_m: k[1],
        iterations,
        solves,
    })
}

/// The steering tendencies of a bent housing at the case's bit depth (what `solve` reports).
#[derive(Debug, Clone)]
pub struct Steering {
    /// The bent housing.
    pub bend: MotorBend,
    /// The operation's toolface, rad.
    pub toolface_rad: f64,
    /// Whether that toolface is magnetic (from north) at the bend, the hole being within
    /// [`MAGNETIC_TOOLFACE_BELOW_RAD`] of vertical there; else gravity (from the high side).
    pub magnetic: bool,
    /// Toolfaces over a revolution of the rotating tendency.
    pub rotating_toolfaces: usize,
    /// The motor yield (sliding at the operation's toolface) and the rotating tendency, or
    /// why they were not computed.
    pub tendencies: Result<(SteadyTurn, SteadyTurn), String>,
    /// The turn of the toolface by the motor's reactive torque in the case's own solve
    /// (`[operation] reactive_torque`, sliding; None otherwise): set by the caller that solved it.
    pub reactive_turn: Option<crate::models::fem::reactive::ReactiveTurn>,
}

/// Why `case`'s steady dogleg cannot be computed: off bottom (no WOB to drill with), or a hook
/// load given instead of the WOB; None when it can.
fn not_drillable(case: &Case) -> Option<String> {
    let op = &case.operation;
    if !op.mode.on_bottom() {
        Some(format!("off bottom (mode {}): no WOB to drill with", op.mode.name()))
    } else if op.hook_load_n.is_some() {
        Some("the hook load is given instead of the WOB".to_string())
    } else {
        None
    }
}

/// The motor yield and the rotating tendency of `case`'s bent housing (None for a straight
/// string): [`steady_turn`] with the string sliding at the operation's toolface, and rotating
/// at the case's rotary speed ([`crate::case::DEFAULT_ROTATING_RPM`] when it gives none). Not computed (the
/// reason given) off bottom, with a hook load given instead of the WOB, or when the steady
/// curvature is not found.
pub fn steering(case: &Case, ctl: &SolveControls) -> Option<Steering> {
    let bend = case.string.bend()?;
    let op = &case.operation;
    let md_bend = op.bit_md_m - bend.to_bit_m;
    let inc = case.well.path.point_at(md_bend.max(case.well.path.md_start())).inc_rad;
    let tendencies = match not_drillable(case) {
        Some(why) => Err(why),
        None => steady_turn(&case.on_bottom(false), &case.bit_rock, ctl)
            .and_then(|a| Ok((a, steady_turn(&case.on_bottom(true), &case.bit_rock, ctl)?)))
            .map_err(|e| e.to_string()),
    };
    Some(Steering {
        bend,
        toolface_rad: op.toolface_rad,
        magnetic: inc < MAGNETIC_TOOLFACE_BELOW_RAD,
        rotating_toolfaces: ROTATING_TOOLFACES,
        tendencies,
        reactive_turn: None,
    })
}

/// The steering tendency of a rotary steerable system at the case's bit depth (what `solve`
/// reports).
#[derive(Debug, Clone)]
pub struct RssSteering {
    /// The tool (with the ratio the tendency is computed at).
    pub tool: RssTool,
    /// The operation's toolface, rad.
    pub toolface_rad: f64,
    /// Whether that toolface is magnetic (from north) at the tool, the hole being within
    /// [`MAGNETIC_TOOLFACE_BELOW_RAD`] of vertical there; else gravity (from the high side).
    pub magnetic: bool,
    /// The dogleg the assembly drills rotating with the tool steering at the operation's
    /// toolface for the share `tool.ratio` of the time, or why it was not computed.
    pub tendency: Result<SteadyTurn, String>,
}

/// The steering tendency of `case`'s rotary steerable system (None without one):
/// [`steady_turn`] with the string rotating at the case's rotary speed
/// ([`crate::case::DEFAULT_ROTATING_RPM`] when it gives none) and the tool steering at the
/// operation's toolface for the share `ratio` of the time, neutral for the rest. Not computed
/// (the reason given) off bottom, with a hook load given instead of the WOB, or when the
/// steady curvature is not found.
pub fn rss_steering(case: &Case, ctl: &SolveControls) -> Option<RssSteering> {
    let tool = case.string.rss()?;
    let op = &case.operation;
    let md_tool = op.bit_md_m - tool.position_to_bit_m();
    let inc = case.well.path.point_at(md_tool.max(case.well.path.md_start())).inc_rad;
    let tendency = match not_drillable(case) {
        Some(why) => Err(why),
        None => steady_turn(&case.on_bottom(true), &case.bit_rock, ctl).map_err(|e| e.to_string()),
    };
    Some(RssSteering {
        tool,
        toolface_rad: op.toolface_rad,
        magnetic: inc < MAGNETIC_TOOLFACE_BELOW_RAD,
        tendency,
    })
}
