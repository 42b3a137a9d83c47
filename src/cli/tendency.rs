//! `drillpath tendency`: the tendency sweeps of a steerable assembly
//! ([`crate::predict::tendency::run_sweep`]), written as `tendency.csv` and `tendency.svg`
//! ([`crate::report::tendency_output`]), with a progress bar over the points.

use super::args::TendencyArgs;
use super::outputs::{names, Outputs};
use super::progress::Progress;
use crate::case::Case;
use crate::error::InputError;
use crate::io::case_toml::{load_case, CaseOverrides};
use crate::models::fem::solve::SolveControls;
use crate::predict::tendency::{pad_hole_diameter_m, run_sweep, TendencyGrid};
use crate::report::tendency_output::{tendency_csv, tendency_svg, tendency_text};
use crate::string::MAX_BEND_ANGLE_RAD;
use crate::units::{parse_quantity, Dimension};
use anyhow::anyhow;
use std::io::Write;
use std::sync::atomic::{AtomicU64, Ordering};

/// The comma-separated values of option `name` in SI (`dim`, bare numbers in `unit`), each in
/// `[lo, hi]` (SI); `default` when the option is not given. Errors name the option.
fn list(
    name: &str,
    text: Option<&str>,
    dim: Dimension,
    unit: &str,
    (lo, hi): (f64, f64),
    default: Vec<f64>,
) -> Result<Vec<f64>, InputError> {
    let Some(text) = text else {
        return Ok(default);
    };
    let mut out = Vec::new();
    for item in text.split(',').map(str::trim) {
        if item.is_empty() {
            return Err(InputError::option(name, format!("an empty value in `{text}`")));
        }
        let v = if dim == Dimension::Dimensionless {
            item.parse::<f64>().map_err(|_| format!("`{item}` is not a number"))
        } else {
            parse_quantity(item, dim, unit)
        }
        .map_err(|m| InputError::option(name, m))?;
        if !(v.is_finite() && (lo..=hi).contains(&v)) {
            return Err(InputError::option(
                name,
                format!("`{item}` outside [{}, {}] {unit}", show(lo, dim), show(hi, dim)),
            ));
        }
        if !out.contains(&v) {
            out.push(v);
        }
    }
    Ok(out)
}

/// A limit of [`list`] in the unit of its message.
fn show(x: f64, dim: Dimension) -> String {
    let v = match dim {
        Dimension::Angle => x.to_degrees(),
        Dimension::Force => x / 1e3,
        Dimension::Length => x / 0.0254,
        _ => x,
    };
    crate::units::message_number(v)
}

/// Default diametral under-gauges of the pad stabilizer swept, m: full gauge, 1/16, 1/8 and
/// 1/4 in.
const DEFAULT_PAD_UNDER_GAUGES_M: [f64; 4] = [0.0, 0.0625 * 0.0254, 0.125 * 0.0254, 0.25 * 0.0254];

/// The pad stabilizer's blade ODs of the capability sweep, m, from `--pads` (diametral
/// under-gauges, bare numbers in inches, each from 0 to the hole less the pad's body OD); by
/// default full gauge, 1/16, 1/8 and 1/4 in under gauge and the case's own, in increasing
/// under-gauge; empty without a pad. `--pads` on an RSS or a motor without a pad is an error.
fn pads(case: &Case, text: Option<&str>, rss: bool) -> Result<Vec<f64>, InputError> {
    let (Some(hole), Some(k)) = (pad_hole_diameter_m(case), case.string.pad_index()) else {
        return match (text, rss) {
            (None, _) => Ok(Vec::new()),
            (Some(_), true) => Err(InputError::option(
                "--pads",
                "the string's steering tool is an RSS: pads are a bent motor's",
            )),
            (Some(_), false) => Err(InputError::option(
                "--pads",
                "the motor has no pad stabilizer (a `stabilizer` component below the bend)",
            )),
        };
    };
    let pad = &case.string.components[k];
    let mut default = DEFAULT_PAD_UNDER_GAUGES_M.to_vec();
    let own = hole - pad.contact_od_m;
    if !default.iter().any(|u| (u - own).abs() < 1e-9) && own >= 0.0 {
        default.push(own);
        default.sort_by(f64::total_cmp);
    }
    let hi = hole - pad.body_od_m;
    let unders = list("--pads", text, Dimension::Length, "in", (0.0, hi), default)?;
    Ok(unders.iter().map(|u| hole - u).collect())
}

/// Run `drillpath tendency`.
pub fn run(a: TendencyArgs, quiet: bool) -> anyhow::Result<()> {
    let case = load_case(&a.case, &CaseOverrides::default())?;
    let rss = case.string.bend().is_none() && case.string.rss().is_some();
    if case.string.bend().is_none() && !rss {
        return Err(InputError::file(
            &a.case,
            "the string has no bent housing (`bend_angle` on a motor) or rotary steerable system (`rss` component): nothing to sweep",
        )
        .into());
    }
    if rss && a.bends.is_some() {
        return Err(InputError::option("--bends", "the string's steering tool is an RSS: sweep its --ratios").into());
    }
    if !rss && a.ratios.is_some() {
        return Err(InputError::option(
            "--ratios",
            "the string's steering tool is a bent motor: sweep its --bends",
        )
        .into());
    }
    let deg = |d: f64| d.to_radians();
    let settings = if rss {
        list(
            "--ratios",
            a.ratios.as_deref(),
            Dimension::Dimensionless,
            "",
            (0.0, 1.0),
            vec![0.0, 0.25, 0.5, 0.75, 1.0],
        )?
    } else {
        let d = (0..=6).map(|k| deg(0.5 * k as f64)).collect();
        list(
            "--bends",
            a.bends.as_deref(),
            Dimension::Angle,
            "deg",
            (0.0, MAX_BEND_ANGLE_RAD),
            d,
        )?
    };
    let w = case.operation.wob_n;
    if a.wobs.is_none() && (w.is_nan() || w <= 0.0) {
        return Err(InputError::option("--wobs", "the case gives no WOB: give the weights on bit to sweep").into());
    }
    let wobs_n = list(
        "--wobs",
        a.wobs.as_deref(),
        Dimension::Force,
        "kN",
        (1.0, 1e7),
        vec![0.5 * w, w, 1.5 * w],
    )?;
    let incs_rad = list(
        "--incs",
        a.incs.as_deref(),
        Dimension::Angle,
        "deg",
        (0.0, deg(120.0)),
        (0..=6).map(|k| deg(15.0 * k as f64)).collect(),
    )?;
    let pad_ods_m = pads(&case, a.pads.as_deref(), rss)?;
    if a.threads == Some(0) {
        return Err(InputError::option("--threads", "at least one thread").into());
    }
    let mut outputs = Outputs::new();
    outputs.case_inputs(&case);
    outputs.dir("--out", &a.out, &names(&["tendency.csv", "tendency.svg"]))?;
    let grid = TendencyGrid {
        settings,
        wobs_n,
        pad_ods_m,
        incs_rad,
    };
    let n =
        grid.settings.len() * grid.wobs_n.len() * grid.pad_ods_m.len().max(1) + grid.incs_rad.len() * grid.wobs_n.len();
    let progress = Progress::new(n as u64, &format!("tendency {}", a.case.display()), quiet);
    let done = AtomicU64::new(0);
    let tick = || {
        let k = done.fetch_add(1, Ordering::Relaxed) + 1;
        progress.set(k, "");
    };
    let ctl = SolveControls::from_settings(&case.solver);
    let mut pool = rayon::ThreadPoolBuilder::new();
    if let Some(t) = a.threads {
        pool = pool.num_threads(t);
    }
    let pool = pool
        .build()
        .map_err(|e| anyhow!("cannot start the worker threads: {e}"))?;
    let t0 = std::time::Instant::now();
    let points = pool
        .install(|| run_sweep(&case, &grid, &ctl, &tick))
        .map_err(|m| InputError::file(&a.case, m))?;
    let secs = t0.elapsed().as_secs_f64();
    progress.finish();
    let internal = |e: String| anyhow!("internal error: {e}");
    outputs.stage(a.out.join("tendency.csv"), tendency_csv(&points).map_err(internal)?);
    outputs.stage(
        a.out.join("tendency.svg"),
        tendency_svg(&points, rss).map_err(internal)?,
    );
    outputs.commit()?;
    let mut out = std::io::stdout().lock();
    writeln!(out, "tendency: {} ({})", case.name, a.case.display())?;
    write!(out, "{}", tendency_text(&points, rss))?;
    writeln!(
        out,
        "  {} points on {} threads in {secs:.2} s; wrote {}/tendency.csv and {}/tendency.svg",
        points.len(),
        pool.current_num_threads(),
        a.out.display(),
        a.out.display()
    )?;
    Ok(())
}
