//! Outputs of `predict` and `backanalyze`: `trajectory.csv` (docs/guide.md columns) and the
//! JSON summaries.

use super::tracking_output::{
    assimilation_cells, reference_cells, AssimilationJson, BaselinesJson, TrackingSkillJson, ASSIMILATION_COLUMNS,
    REFERENCE_COLUMNS,
};
use super::{num, Finite};
use crate::case::{Case, Choice};
use crate::models::fem::results::BitResult;
use crate::predict::backanalysis::{Backanalysis, BackanalysisPlan, ErrorStats};
use crate::predict::calibrate::{Calibration, FitParameter};
use crate::predict::forecast::Forecast;
use crate::predict::law::LawParams;
use crate::predict::track::{IntervalRates, TrackingErrors, TrajectoryRow};
use crate::predict::tracking::skill::Skill;
use serde::Serialize;
use std::path::Path;

/// Header of `trajectory.csv` (docs/guide.md).
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
        num(crate::geometry::survey::degrees_in_turn(azi.to_degrees(), 4), 4)?,
        num(pos.z, 3)?,
        num(pos.x, 3)?,
        num(pos.y, 3)?,
        opt(meas.map(|m| m.0.to_degrees()), 4)?,
        opt(
            meas.map(|m| crate::geometry::survey::degrees_in_turn(m.1.to_degrees(), 4)),
            4
        )?,
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

/// `trajectory.csv` of a forecast: [`trajectory_csv`], with an assimilation its bounds and the
/// plain march ([`PROJECTION_COLUMNS`]), when the string has a survey sensor the sag angle
/// there (`sensor_sag_deg`), and with a bent housing how each step was drilled
/// ([`STEERING_COLUMNS`], the last columns).
pub fn forecast_csv(f: &Forecast) -> Result<String, String> {
    let text = with_sensor_column(f)?;
    if f.rows.iter().all(|r| r.steer.is_none()) {
        return Ok(text);
    }
    let mut out = String::with_capacity(text.len() + 16 * f.rows.len());
    let mut lines = text.lines();
    let reactive = f.rows.iter().any(|r| r.reactive_turn_rad.is_some());
    out.push_str(lines.next().unwrap_or_default());
    out.push(',');
    out.push_str(STEERING_COLUMNS);
    if reactive {
        out.push(',');
        out.push_str(REACTIVE_COLUMN);
    }
    out.push('\n');
    for (line, r) in lines.zip(&f.rows) {
        let mut cells = match r.steer {
            Some(st) => format!("{},{}", st.mode_name(), num(st.toolface_rad.to_degrees(), 2)?),
            None => ",".to_string(),
        };
        if reactive {
            cells.push(',');
            if let Some(t) = r.reactive_turn_rad {
                cells.push_str(&num(t.to_degrees(), 3)?);
            }
        }
        out.push_str(line);
        out.push(',');
        out.push_str(&cells);
        out.push('\n');
    }
    Ok(out)
}

/// The column `trajectory.csv` ends with when `[operation] reactive_torque` is on and a step
/// slides: the turn to the left of the toolface by the motor's reactive torque in the step's
/// solve, deg (the toolface drilled is `toolface_deg` less it; empty for rotating steps).
pub const REACTIVE_COLUMN: &str = "reactive_toolface_turn_deg";

/// Columns `trajectory.csv` of `predict` ends with for a string with a bent housing: how the
/// step ending at the row (or next) was drilled, `slide` or `rotate`, and the toolface set, deg
/// (gravity, or magnetic near vertical; the first of the revolution when rotating).
pub const STEERING_COLUMNS: &str = "mode,toolface_deg";

/// [`forecast_columns`] with `sensor_sag_deg` after them when the string has a survey sensor.
fn with_sensor_column(f: &Forecast) -> Result<String, String> {
    let text = forecast_columns(f)?;
    if f.rows.iter().all(|r| r.bit.sensor_sag_rad.is_none()) {
        return Ok(text);
    }
    let mut out = String::with_capacity(text.len() + 12 * f.rows.len());
    let mut lines = text.lines();
    out.push_str(lines.next().unwrap_or_default());
    out.push_str(",sensor_sag_deg\n");
    for (line, r) in lines.zip(&f.rows) {
        let cell = r.bit.sensor_sag_rad.map(|s| num(s.to_degrees(), 5)).transpose()?;
        out.push_str(line);
        out.push(',');
        out.push_str(&cell.unwrap_or_default());
        out.push('\n');
    }
    Ok(out)
}

/// The trajectory columns of `f`, with the projection's when assimilating.
fn forecast_columns(f: &Forecast) -> Result<String, String> {
    let plain = trajectory_csv(&f.rows)?;
    let Some(p) = &f.projection else {
        return Ok(plain);
    };
    let mut out = String::with_capacity(plain.len() * 2);
    let mut lines = plain.lines();
    out.push_str(lines.next().unwrap_or_default());
    out.push(',');
    out.push_str(PROJECTION_COLUMNS);
    out.push('\n');
    for ((line, q), r) in lines.zip(&p.rows).zip(&f.prediction_rows()) {
        let cells = [
            num(q.inc_sd_rad.to_degrees(), 4)?,
            num(q.azi_sd_rad.to_degrees(), 4)?,
            num(q.lateral_sd_m, 3)?,
            num(q.vertical_sd_m, 3)?,
            num(r.0.to_degrees(), 4)?,
            num(crate::geometry::survey::degrees_in_turn(r.1.to_degrees(), 4), 4)?,
        ];
        out.push_str(line);
        out.push(',');
        out.push_str(&cells.join(","));
        out.push('\n');
    }
    Ok(out)
}

/// Header of the columns an assimilating prediction adds to `trajectory.csv`: one standard
/// deviation of the inclination and azimuth (deg) against a survey station at the row, of the
/// position sideways and toward the high side (m, an upper bound), and the plain march's
/// inclination and azimuth (deg).
pub const PROJECTION_COLUMNS: &str = "inc_sd_deg,azi_sd_deg,lateral_sd_m,vertical_sd_m,plain_inc_deg,plain_azi_deg";

/// `trajectory.csv` of `backanalyze`: one row per interval end, bit values at the end, then the
/// direction errors of the model and the references ([`REFERENCE_COLUMNS`]) and, assimilating,
/// the plain and frozen predictions and the bounds ([`ASSIMILATION_COLUMNS`]).
pub fn backanalysis_csv(b: &Backanalysis) -> Result<String, String> {
    let mut out = format!("{TRAJECTORY_HEADER},{REFERENCE_COLUMNS}");
    if b.assimilation.is_some() {
        out.push(',');
        out.push_str(ASSIMILATION_COLUMNS);
    }
    out.push('\n');
    for (k, (r, e)) in b.results.iter().zip(&b.ends).enumerate() {
        let line = row_line(
            r.interval.to_md_m,
            r.inc_rad,
            r.azi_rad,
            &r.position,
            Some(r.interval.measured),
            Some((r.inc_err_rad(), r.azi_err_rad())),
            &r.bit_end,
        )?;
        let mut cells = reference_cells(e)?;
        if let Some(a) = &b.assimilation {
            cells.extend(assimilation_cells(a, k, e)?);
        }
        out.push_str(line.trim_end());
        out.push(',');
        out.push_str(&cells.join(","));
        out.push('\n');
    }
    Ok(out)
}

/// The law's parameters (`bit_rock` key; angles in degrees).
#[derive(Serialize)]
pub struct LawJson {
    law: String,
    lateral_drillability: Finite,
    walk_angle_deg: Finite,
    rock_anisotropy: Finite,
    dip_deg: Finite,
    dip_direction_deg: Finite,
    formation_intervals: usize,
}

impl LawJson {
    /// The law named `law` with parameters `p` and `formations` formation intervals.
    pub fn new(law: &str, p: &LawParams, formations: usize) -> LawJson {
        LawJson {
            law: law.to_string(),
            lateral_drillability: Finite(p.lateral_drillability),
            walk_angle_deg: Finite(p.walk_angle_rad.to_degrees()),
            rock_anisotropy: Finite(p.rock_anisotropy),
            dip_deg: Finite(p.dip_rad.to_degrees()),
            dip_direction_deg: Finite(p.dip_direction_rad.to_degrees()),
            formation_intervals: formations,
        }
    }
}

/// Rates over an interval (`rates` key).
#[derive(Serialize)]
#[allow(non_snake_case)]
pub struct RatesJson {
    length_m: Finite,
    build_rate_deg_per_30m: Finite,
    walk_rate_deg_per_30m: Finite,
    mean_build_force_kN: Finite,
    mean_walk_force_kN: Finite,
    mean_tilt_inc_deg: Finite,
    mean_tilt_azi_deg: Finite,
}

impl From<&IntervalRates> for RatesJson {
    fn from(r: &IntervalRates) -> RatesJson {
        RatesJson {
            length_m: Finite(r.length_m),
            build_rate_deg_per_30m: Finite(r.build_rate_rad_per_30m.to_degrees()),
            walk_rate_deg_per_30m: Finite(r.walk_rate_rad_per_30m.to_degrees()),
            mean_build_force_kN: Finite(r.mean_build_force_n / 1e3),
            mean_walk_force_kN: Finite(r.mean_walk_force_n / 1e3),
            mean_tilt_inc_deg: Finite(r.mean_tilt_inc_rad.to_degrees()),
            mean_tilt_azi_deg: Finite(r.mean_tilt_azi_rad.to_degrees()),
        }
    }
}

/// Tracking errors (`tracking` key).
#[derive(Serialize)]
pub struct TrackingJson {
    stations_compared: usize,
    end_md_m: Finite,
    end_inc_err_deg: Finite,
    end_azi_err_deg: Finite,
    inc_err_per_100m_deg: Finite,
    azi_err_per_100m_deg: Finite,
    max_abs_inc_err_deg: Finite,
    max_abs_azi_err_deg: Finite,
    /// The model against the naive projections at the same stations.
    #[serde(flatten)]
    skill: Option<TrackingSkillJson>,
}

impl TrackingJson {
    /// The tracking errors `e` with the skill `s` at the same stations.
    fn new(e: &TrackingErrors, s: Option<&Skill>) -> TrackingJson {
        TrackingJson {
            skill: s.map(TrackingSkillJson::new),
            ..TrackingJson::from(e)
        }
    }
}

impl From<&TrackingErrors> for TrackingJson {
    fn from(e: &TrackingErrors) -> TrackingJson {
        TrackingJson {
            skill: None,
            stations_compared: e.stations,
            end_md_m: Finite(e.end_md_m),
            end_inc_err_deg: Finite(e.end_inc_err_rad.to_degrees()),
            end_azi_err_deg: Finite(e.end_azi_err_rad.to_degrees()),
            inc_err_per_100m_deg: Finite(e.inc_err_per_100m_rad.to_degrees()),
            azi_err_per_100m_deg: Finite(e.azi_err_per_100m_rad.to_degrees()),
            max_abs_inc_err_deg: Finite(e.max_abs_inc_err_rad.to_degrees()),
            max_abs_azi_err_deg: Finite(e.max_abs_azi_err_rad.to_degrees()),
        }
    }
}

/// Back-analysis error statistics (interface keys `inc_err_per_100m_deg` and
/// `azi_err_per_100m_deg` are the mean absolute errors per 100 m).
#[derive(Serialize)]
pub struct ErrorStatsJson {
    intervals: usize,
    inc_err_per_100m_deg: Finite,
    azi_err_per_100m_deg: Finite,
    inc_rms_per_100m_deg: Finite,
    azi_rms_per_100m_deg: Finite,
}

impl From<&ErrorStats> for ErrorStatsJson {
    fn from(e: &ErrorStats) -> ErrorStatsJson {
        ErrorStatsJson {
            intervals: e.intervals,
            inc_err_per_100m_deg: Finite(e.inc_mean_abs_per_100m_rad.to_degrees()),
            azi_err_per_100m_deg: Finite(e.azi_mean_abs_per_100m_rad.to_degrees()),
            inc_rms_per_100m_deg: Finite(e.inc_rms_per_100m_rad.to_degrees()),
            azi_rms_per_100m_deg: Finite(e.azi_rms_per_100m_rad.to_degrees()),
        }
    }
}

/// One fitted parameter of a calibration (walk angle in degrees).
#[derive(Serialize)]
pub struct FittedJson {
    name: &'static str,
    value: Finite,
    std_dev: Option<Finite>,
    identifiable: bool,
}

/// A calibration's result (`calibration.parameters` key).
#[derive(Serialize)]
pub struct CalibrationJson {
    fitted: Vec<FittedJson>,
    ssr_start: Finite,
    ssr_end: Finite,
    iterations: usize,
}

/// A fitted parameter as shown: its name in the outputs, its value and standard deviation in
/// output units (the walk angle in degrees; None when not finite) and whether the data
/// identify it (standard deviation below [`FitParameter::identifiable_below`]).
pub fn fitted_shown(p: FitParameter, value: f64, std_dev: f64) -> (&'static str, f64, Option<f64>, bool) {
    let walk = p == FitParameter::WalkAngle;
    let (v, sd, limit) = if walk {
        (
            value.to_degrees(),
            std_dev.to_degrees(),
            p.identifiable_below().to_degrees(),
        )
    } else {
        (value, std_dev, p.identifiable_below())
    };
    let name = if walk { "walk_angle_deg" } else { p.name() };
    (name, v, sd.is_finite().then_some(sd), sd.is_finite() && sd < limit)
}

impl From<&Calibration> for CalibrationJson {
    fn from(c: &Calibration) -> CalibrationJson {
        let fitted = c
            .fitted
            .iter()
            .map(|&(p, v, sd)| {
                let (name, value, std_dev, identifiable) = fitted_shown(p, v, sd);
                FittedJson {
                    name,
                    value: Finite(value),
                    std_dev: std_dev.map(Finite),
                    identifiable,
                }
            })
            .collect();
        CalibrationJson {
            fitted,
            ssr_start: Finite(c.ssr_start),
            ssr_end: Finite(c.ssr_end),
            iterations: c.iterations,
        }
    }
}

/// The fitted `[bit_rock]` keys as TOML lines to paste into a case file.
pub fn fitted_toml(c: &Calibration) -> String {
    let mut s = String::from(
        "# fitted by drillpath backanalyze --calibrate: set these keys in a case's [bit_rock] table\n# (replacing the same keys there), or run case_fitted.toml next to this file\n[bit_rock]\n",
    );
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

/// The fidelity asked for and run (`model.fidelity_choice` of `predict`, `fidelity` of
/// `backanalyze`).
#[derive(Serialize)]
pub struct ChoiceJson {
    requested: &'static str,
    used: &'static str,
    reason: String,
}

impl From<&Choice> for ChoiceJson {
    fn from(c: &Choice) -> ChoiceJson {
        ChoiceJson {
            requested: c.requested.name(),
            used: c.level.name(),
            reason: c.reason.clone(),
        }
    }
}

/// The end of a prediction (`end` key).
#[derive(Serialize)]
struct EndJson {
    md_m: Finite,
    inc_deg: Finite,
    azi_deg: Finite,
    tvd_m: Finite,
    north_m: Finite,
    east_m: Finite,
}

/// The step error estimated by Richardson extrapolation (`step_extrapolation` key).
#[derive(Serialize)]
struct StepErrorJson {
    coarse_step_m: Finite,
    fine_step_m: Finite,
    est_inc_err_deg: Finite,
    est_azi_err_deg: Finite,
}

/// The model of a prediction (`model` key).
#[derive(Serialize)]
struct ModelJson {
    fidelity: &'static str,
    fidelity_choice: ChoiceJson,
    cut_m: Finite,
    dofs: usize,
    steps: usize,
    solver_iterations: usize,
    seconds: Finite,
}

/// The survey's north beyond its name: `azimuth_reference_source` (where the survey file states
/// it, or the case's conversion; empty when not stated), `magnetic_declination_deg` and
/// `grid_convergence_deg` (deg, as the file gives them, e.g. WITSML `magDeclUsed`,
/// `gridCorUsed`; null when it does not).
#[derive(Serialize)]
pub struct NorthJson {
    azimuth_reference_source: String,
    magnetic_declination_deg: Option<Finite>,
    grid_convergence_deg: Option<Finite>,
}

impl NorthJson {
    /// From the survey file of `case`.
    pub fn of(case: &Case) -> NorthJson {
        let f = &case.well.survey;
        NorthJson {
            azimuth_reference_source: f.azimuth_reference_source.clone(),
            magnetic_declination_deg: f.magnetic_declination_rad.map(|d| Finite(d.to_degrees())),
            grid_convergence_deg: f.grid_convergence_rad.map(|c| Finite(c.to_degrees())),
        }
    }
}

/// `summary.json` of one case of `drillpath predict`.
#[derive(Serialize)]
pub struct PredictSummary {
    case: String,
    case_file: String,
    /// The north the survey's (and so the predicted) azimuths are measured from, as the survey
    /// file states it: `unspecified`, `true`, `grid` or `magnetic`.
    azimuth_reference: &'static str,
    /// Where the reference and the declination / convergence come from, and the conversion.
    #[serde(flatten)]
    north: NorthJson,
    from_md_m: Finite,
    to_md_m: Finite,
    step_m: Finite,
    ripple_deg: Finite,
    end: EndJson,
    rates: RatesJson,
    tracking: Option<TrackingJson>,
    bit_rock: LawJson,
    step_extrapolation: Option<StepErrorJson>,
    model: ModelJson,
    #[serde(skip_serializing_if = "Option::is_none")]
    assimilation: Option<AssimilationJson>,
    warnings: Vec<String>,
}

impl PredictSummary {
    /// The summary of the forecast `f` of `case` (file `case_file`) with the model `choice`.
    pub fn new(case: &Case, case_file: &Path, choice: &Choice, f: &Forecast) -> PredictSummary {
        let p = &f.prediction;
        let end = f.rows.last().expect("a prediction has a start row");
        PredictSummary {
            case: case.name.clone(),
            case_file: case_file.display().to_string(),
            azimuth_reference: case.well.survey.azimuth_reference.name(),
            north: NorthJson::of(case),
            from_md_m: Finite(p.from_md_m),
            to_md_m: Finite(p.to_md_m),
            step_m: Finite(f.settings.step_m),
            ripple_deg: Finite(p.ripple_deg),
            end: EndJson {
                md_m: Finite(end.md_m),
                inc_deg: Finite(end.inc_rad.to_degrees()),
                azi_deg: Finite(crate::geometry::survey::degrees_in_turn(
                    end.azi_rad.to_degrees(),
                    crate::geometry::survey::FULL_PRECISION_DECIMALS,
                )),
                tvd_m: Finite(end.position.z),
                north_m: Finite(end.position.x),
                east_m: Finite(end.position.y),
            },
            rates: RatesJson::from(&f.rates),
            warnings: f.warnings.clone(),
            tracking: f.tracking.as_ref().map(|t| TrackingJson::new(t, f.skill.as_ref())),
            assimilation: f
                .projection
                .as_ref()
                .map(|pr| AssimilationJson::of_bank(&pr.bank, pr.model_tendency, &[])),
            bit_rock: LawJson::new(&case.bit_rock.law, &f.law, case.bit_rock.formations.len()),
            step_extrapolation: f.step_error.as_ref().map(|e| StepErrorJson {
                coarse_step_m: Finite(e.coarse_step_m),
                fine_step_m: Finite(e.fine_step_m),
                est_inc_err_deg: Finite(e.max_inc_rad.to_degrees()),
                est_azi_err_deg: Finite(e.max_azi_rad.to_degrees()),
            }),
            model: ModelJson {
                fidelity: choice.level.name(),
                fidelity_choice: ChoiceJson::from(choice),
                cut_m: Finite(p.cut_m),
                dofs: p.dofs,
                steps: p.steps.len() - 1,
                solver_iterations: p.iterations,
                seconds: Finite(p.seconds),
            },
        }
    }
}

/// `summary.json` of several cases of `drillpath predict` (`cases` key).
#[derive(Serialize)]
pub struct ComparisonSummary<'a> {
    /// One summary per case, in the order given.
    pub cases: &'a [PredictSummary],
}

/// Header of `comparison.csv`.
pub const COMPARISON_HEADER: &str = "case,from_md_m,to_md_m,build_rate_deg_per_30m,walk_rate_deg_per_30m,mean_build_force_kN,mean_walk_force_kN,mean_tilt_inc_deg,mean_tilt_azi_deg,end_inc_deg,end_azi_deg";

/// `comparison.csv` of several cases' forecasts: one row per case.
pub fn comparison_csv(runs: &[(&Case, &Forecast)]) -> Result<String, String> {
    let mut out = format!("{COMPARISON_HEADER}\n");
    for (case, f) in runs {
        let (p, rt) = (&f.prediction, &f.rates);
        let end = p.steps.last().expect("start record");
        let name = case.name.replace([',', '"', '\n'], " ");
        out.push_str(&format!(
            "{},{},{},{},{},{},{},{},{},{},{}\n",
            name,
            num(p.from_md_m, 2)?,
            num(p.to_md_m, 2)?,
            num(rt.build_rate_rad_per_30m.to_degrees(), 4)?,
            num(rt.walk_rate_rad_per_30m.to_degrees(), 4)?,
            num(rt.mean_build_force_n / 1e3, 4)?,
            num(rt.mean_walk_force_n / 1e3, 4)?,
            num(rt.mean_tilt_inc_rad.to_degrees(), 5)?,
            num(rt.mean_tilt_azi_rad.to_degrees(), 5)?,
            num(end.inc_rad.to_degrees(), 4)?,
            num(crate::geometry::survey::degrees_in_turn(end.azi_rad.to_degrees(), 4), 4)?,
        ));
    }
    Ok(out)
}

/// An MD range (`calibrated_on`, `scored_on`).
#[derive(Serialize)]
struct RangeJson {
    from_md_m: Finite,
    to_md_m: Finite,
}

/// An interval the back-analysis could not predict.
#[derive(Serialize)]
struct SkippedJson {
    from_md_m: Finite,
    to_md_m: Finite,
    reason: String,
}

/// The `calibration` key of a back-analysis.
#[derive(Serialize)]
struct BackCalibrationJson {
    parameters: CalibrationJson,
    calibrated_on: RangeJson,
    scored_on: RangeJson,
    in_sample_default: ErrorStatsJson,
    in_sample_fitted: ErrorStatsJson,
    out_of_sample_default: ErrorStatsJson,
    out_of_sample_fitted: ErrorStatsJson,
}

/// One BHA run of a back-analysis.
#[derive(Serialize)]
struct RunJson {
    case: String,
    case_file: String,
    /// Where the run ended (the case's bit depth), m.
    bit_md_m: Finite,
}

/// `summary.json` of `drillpath backanalyze`.
#[derive(Serialize)]
pub struct BackanalysisSummary {
    case: String,
    case_file: String,
    /// The north the survey's azimuths are measured from, as the survey file states it.
    azimuth_reference: &'static str,
    /// Where the reference and the declination / convergence come from, and the conversion.
    #[serde(flatten)]
    north: NorthJson,
    /// The BHA runs (each case's name, file and bit depth), the first case's first.
    runs: Vec<RunJson>,
    intervals: usize,
    from_md_m: Finite,
    to_md_m: Finite,
    horizon_m: Finite,
    step_m: Finite,
    fidelity: ChoiceJson,
    inc_err_per_100m_deg: Finite,
    azi_err_per_100m_deg: Finite,
    errors: ErrorStatsJson,
    skipped_intervals: Vec<SkippedJson>,
    bit_rock: LawJson,
    #[serde(skip_serializing_if = "Option::is_none")]
    calibration: Option<BackCalibrationJson>,
    /// The model's mean direction error per 100 m, deg.
    dir_err_per_100m_deg: Finite,
    baselines: BaselinesJson,
    /// `1 - model / best naive` on the mean direction error.
    skill: Option<Finite>,
    /// `1 - model / frozen assimilation` on the mean direction error (null without
    /// assimilation).
    physics_share: Option<Finite>,
    #[serde(skip_serializing_if = "Option::is_none")]
    assimilation: Option<AssimilationJson>,
    seconds: Finite,
}

/// A back-analysis with what its outputs name: the case and its file, the plan, the march
/// step and the model choice.
#[derive(Clone, Copy)]
pub struct BackanalysisRun<'a> {
    /// The case.
    pub case: &'a Case,
    /// The case file as the user named it.
    pub case_file: &'a Path,
    /// The plan run.
    pub plan: &'a BackanalysisPlan,
    /// March step, m.
    pub step_m: f64,
    /// The model choice.
    pub choice: &'a Choice,
    /// The result.
    pub result: &'a Backanalysis,
    /// The BHA runs after the first, with their case files (empty for one case).
    pub later_runs: &'a [(&'a Case, &'a Path)],
}

impl BackanalysisSummary {
    /// The summary of the back-analysis `run`.
    pub fn new(run: &BackanalysisRun) -> BackanalysisSummary {
        let BackanalysisRun {
            case,
            case_file,
            plan,
            step_m,
            choice,
            result: b,
            later_runs,
        } = *run;
        let (first, last) = b.range_md_m();
        let skill = b
            .skill
            .as_ref()
            .expect("a back-analysis predicts at least one interval");
        BackanalysisSummary {
            case: case.name.clone(),
            case_file: case_file.display().to_string(),
            azimuth_reference: case.well.survey.azimuth_reference.name(),
            north: NorthJson::of(case),
            runs: std::iter::once((case, case_file))
                .chain(later_runs.iter().copied())
                .map(|(c, f)| RunJson {
                    case: c.name.clone(),
                    case_file: f.display().to_string(),
                    bit_md_m: Finite(c.operation.bit_md_m),
                })
                .collect(),
            intervals: b.base.len(),
            from_md_m: Finite(first),
            to_md_m: Finite(last),
            horizon_m: Finite(plan.horizon_m),
            step_m: Finite(step_m),
            fidelity: ChoiceJson::from(choice),
            inc_err_per_100m_deg: Finite(b.stats.inc_mean_abs_per_100m_rad.to_degrees()),
            azi_err_per_100m_deg: Finite(b.stats.azi_mean_abs_per_100m_rad.to_degrees()),
            errors: ErrorStatsJson::from(&b.stats),
            skipped_intervals: b
                .skipped
                .iter()
                .map(|(iv, e)| SkippedJson {
                    from_md_m: Finite(iv.from_md_m),
                    to_md_m: Finite(iv.to_md_m),
                    reason: e.to_string(),
                })
                .collect(),
            bit_rock: LawJson::new(&case.bit_rock.law, &b.law, case.bit_rock.formations.len()),
            calibration: b.calibration.as_ref().map(|c| BackCalibrationJson {
                parameters: CalibrationJson::from(&c.calibration),
                calibrated_on: RangeJson {
                    from_md_m: Finite(first),
                    to_md_m: Finite(c.split_md_m),
                },
                scored_on: RangeJson {
                    from_md_m: Finite(c.split_md_m),
                    to_md_m: Finite(last),
                },
                in_sample_default: ErrorStatsJson::from(&c.in_sample_default),
                in_sample_fitted: ErrorStatsJson::from(&c.in_sample_fitted),
                out_of_sample_default: ErrorStatsJson::from(&c.out_of_sample_default),
                out_of_sample_fitted: ErrorStatsJson::from(&c.out_of_sample_fitted),
            }),
            dir_err_per_100m_deg: Finite(skill.model.dir_err_per_100m_rad.to_degrees()),
            baselines: BaselinesJson::new(skill),
            skill: skill.skill.map(Finite),
            physics_share: skill.physics_share.map(Finite),
            assimilation: b.assimilation.as_ref().map(|a| {
                let start: Vec<f64> = case
                    .tracking
                    .parameters
                    .iter()
                    .map(|p| p.value(&case.bit_rock))
                    .collect();
                AssimilationJson::new(a, &start)
            }),
            seconds: Finite(b.seconds),
        }
    }
}
