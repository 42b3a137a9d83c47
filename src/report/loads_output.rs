//! Outputs of `drillpath loads`: `loads.csv` (docs/guide.md columns first, then extensions),
//! the calibration overlay `calibration.csv` and `calibration.json`.

use super::{num, Finite};
use crate::loads::calibrate::Calibration;
use crate::loads::row::{LoadRow, Start, StiffOutcome};
use crate::models::helical_drag::diverged;

/// Header of `loads.csv`: the six interface columns, then buckling, yield and stiff columns
/// (`stiff_model`: `whole` or `hybrid`, the level of the `stiff_*` values).
pub const LOADS_HEADER: &str = "bit_md_m,mode,hook_load_kN,surface_torque_kNm,max_contact_force_kN,buckled_length_m,\
wob_kN,helical_buckled_length_m,max_compression_kN,max_sinusoidal_ratio,max_side_force_kN_per_m,\
tension_limit_kN,torque_limit_kNm,combined_torque_limit_kNm,max_stress_ratio,\
stiff_status,stiff_hook_load_kN,stiff_surface_torque_kNm,stiff_max_contact_force_kN,stiff_model,\
stiff_lock_up_wob_kN,stiff_unbuckled_helical_m,stiff_whirl_m,helical_drag_hook_load_kN,stiff_buckled_start,\
helical_drag_diverges,stiff_coarse_for_pitch_m";

fn opt(x: Option<f64>, scale: f64, decimals: usize) -> Result<String, String> {
    x.map(|v| num(v * scale, decimals))
        .transpose()
        .map(Option::unwrap_or_default)
}

/// `loads.csv` text (one row per bit depth and load case; empty cells where a value does not
/// apply: limits without a yield strength, stiff columns when the stiff model was not run or
/// did not converge).
pub fn loads_csv(rows: &[LoadRow]) -> Result<String, String> {
    let mut out = String::with_capacity(200 * (rows.len() + 1));
    out.push_str(LOADS_HEADER);
    out.push('\n');
    for r in rows {
        let s = &r.soft;
        let b = &r.buckling;
        let y = &r.yield_;
        let stiff = r.stiff.as_ref();
        let sl = stiff.and_then(|o| o.loads());
        let fields = [
            num(r.bit_md_m, 2)?,
            r.mode.name().to_string(),
            num(s.hook_load_n / 1e3, 3)?,
            num(s.surface_torque_nm / 1e3, 4)?,
            num(s.max_contact_force_n / 1e3, 3)?,
            num(b.sinusoidal_length_m, 2)?,
            num(r.wob_n / 1e3, 3)?,
            num(b.helical_length_m, 2)?,
            num(b.max_compression_n / 1e3, 3)?,
            num(b.max_sinusoidal_ratio, 4)?,
            num(s.max_side_force_n_per_m / 1e3, 4)?,
            opt(y.tension_limit_n, 1e-3, 1)?,
            opt(y.torque_limit_nm, 1e-3, 2)?,
            opt(y.combined_torque_limit_nm, 1e-3, 2)?,
            opt(y.max_stress_ratio, 1.0, 4)?,
            stiff.map(|o| o.status().to_string()).unwrap_or_default(),
            opt(sl.map(|l| l.hook_load_n), 1e-3, 3)?,
            opt(sl.map(|l| l.surface_torque_nm), 1e-3, 4)?,
            opt(sl.map(|l| l.max_contact_force_n), 1e-3, 3)?,
            r.stiff_level.map(|l| l.name().to_string()).unwrap_or_default(),
            opt(stiff.and_then(StiffOutcome::lock_up_wob_n), 1e-3, 3)?,
            opt(stiff.and_then(StiffOutcome::unbuckled_helical_m), 1.0, 1)?,
            opt(stiff.and_then(StiffOutcome::whirl_m), 1.0, 1)?,
            num(r.helical_drag_hook_load_n / 1e3, 3)?,
            stiff
                .and_then(StiffOutcome::start)
                .map(|s| (s == Start::BuckledShape).to_string())
                .unwrap_or_default(),
            diverged(r.helical_drag_hook_load_n).to_string(),
            opt(stiff.and_then(StiffOutcome::coarse_for_pitch_m), 1.0, 1)?,
        ];
        out.push_str(&fields.join(","));
        out.push('\n');
    }
    Ok(out)
}

/// Header of the calibration overlay `calibration.csv`.
pub const OVERLAY_HEADER: &str = "line,bit_md_m,mode,measured_hook_load_kN,initial_hook_load_kN,fitted_hook_load_kN,\
hook_load_residual_kN,measured_torque_kNm,initial_torque_kNm,fitted_torque_kNm,torque_residual_kNm";

/// The overlay of measured and modelled values (residual = fitted - measured).
pub fn overlay_csv(cal: &Calibration) -> Result<String, String> {
    let mut out = String::from(OVERLAY_HEADER);
    out.push('\n');
    for p in &cal.points {
        let m = &p.measured;
        let fields = [
            m.line.to_string(),
            num(m.bit_md_m, 2)?,
            m.mode.name().to_string(),
            num(m.hook_load_n / 1e3, 3)?,
            num(p.initial_hook_load_n / 1e3, 3)?,
            num(p.fitted_hook_load_n / 1e3, 3)?,
            num((p.fitted_hook_load_n - m.hook_load_n) / 1e3, 3)?,
            opt(m.torque_nm, 1e-3, 4)?,
            num(p.initial_torque_nm / 1e3, 4)?,
            num(p.fitted_torque_nm / 1e3, 4)?,
            opt(m.torque_nm.map(|t| p.fitted_torque_nm - t), 1e-3, 4)?,
        ];
        out.push_str(&fields.join(","));
        out.push('\n');
    }
    Ok(out)
}

/// One hole section of `calibration.json`.
#[derive(Debug, serde::Serialize)]
struct SectionFit {
    section: usize,
    from_md_m: Finite,
    to_md_m: Finite,
    diameter_in: Finite,
    initial_friction: Finite,
    friction: Finite,
    std_error: Option<Finite>,
    fitted: bool,
}

/// `calibration.json`: fitted friction per hole section with standard errors, residual RMS.
#[allow(non_snake_case)]
#[derive(Debug, serde::Serialize)]
pub struct CalibrationSummary {
    sections: Vec<SectionFit>,
    points: usize,
    residuals: usize,
    rms_hook_load_kN: Finite,
    rms_torque_kNm: Option<Finite>,
    iterations: usize,
    converged: bool,
}

impl CalibrationSummary {
    /// The summary of `cal`.
    pub fn new(cal: &Calibration) -> CalibrationSummary {
        let sections = cal
            .parameters
            .iter()
            .map(|p| SectionFit {
                section: p.section,
                from_md_m: Finite(p.from_md_m),
                to_md_m: Finite(p.to_md_m),
                diameter_in: Finite(p.diameter_m / 0.0254),
                initial_friction: Finite(p.initial),
                friction: Finite(p.value),
                std_error: p.std_error.map(Finite),
                fitted: p.fitted,
            })
            .collect();
        CalibrationSummary {
            sections,
            points: cal.points.len(),
            residuals: cal.residuals,
            rms_hook_load_kN: Finite(cal.rms_hook_load_n / 1e3),
            rms_torque_kNm: cal.rms_torque_nm.map(|t| Finite(t / 1e3)),
            iterations: cal.iterations,
            converged: cal.converged,
        }
    }
}
