//! `drillpath loads`: torque-and-drag chart, limits, optional stiff rows and friction
//! calibration (the computation is in [`crate::loads`]).

use super::args::LoadsArgs;
use super::progress::Progress;
use super::{apply_accuracy_option, fidelity_option, length_opt};
use crate::case::fidelity::{choose, Choice, Level, Purpose};
use crate::case::{Case, Fidelity, Mode};
use crate::error::InputError;
use crate::io::case_toml::{load_case, CaseOverrides};
use crate::io::measured_csv::read_measured_csv;
use crate::loads::calibrate::{calibrate, calibrated_case};
use crate::loads::chart::{case_at_depth, soft_chart, ChartSettings};
use crate::loads::row::{LoadRow, RowLoads, Start, StiffOutcome};
use crate::loads::stiff::{hybrid_depth, stiff_depth, Solved};
use crate::loads::{check_fits, depth_list, string_at_depth, ChartOperation, MODES};
use crate::report::display_units::{fixed, UnitSystem};
use crate::report::loads_output::{calibration_json, loads_csv, overlay_csv};
use crate::report::write_atomic;
use crate::units::{parse_quantity, Dimension};
use anyhow::{bail, Context};
use std::io::Write;

/// Default bit-depth step, m.
pub const DEFAULT_EVERY_M: f64 = 30.0;

/// Run the command (`quiet`: no progress bar).
pub fn run(a: LoadsArgs, quiet: bool) -> anyhow::Result<()> {
    let from = length_opt("--from", &a.from, 0.0)?.unwrap_or(0.0);
    let to = length_opt("--to", &a.to, f64::NEG_INFINITY)?;
    let every = length_opt("--every", &a.every, f64::NEG_INFINITY)?.unwrap_or(DEFAULT_EVERY_M);
    let wob = a
        .wob
        .as_deref()
        .map(|t| parse_quantity(t, Dimension::Force, "kN").map_err(|m| InputError::option("--wob", m)))
        .transpose()?;
    if every <= 0.0 {
        return Err(InputError::option("--every", "the bit-depth step must be positive").into());
    }
    if wob.is_some_and(|w| w < 0.0) {
        return Err(InputError::option("--wob", "the weight on bit must not be negative").into());
    }
    let mut case = load_case(&a.case, &CaseOverrides::default())?;
    if case.string.components.is_empty() {
        bail!("{}: the case has no [[string]] components", a.case.display());
    }
    apply_accuracy_option(a.accuracy.as_deref(), &mut case.solver)?;
    let choice = chart_fidelity(&a, &case)?;
    let path = &case.well.path;
    let deepest = path.md_end().min(case.well.hole.deepest_md());
    let to = to.unwrap_or(case.operation.bit_md_m);
    if to > deepest + 1e-6 {
        return Err(InputError::option(
            "--to",
            format!("bit depth {to:.2} m is below the surveyed hole and its sections (deepest {deepest:.2} m)"),
        )
        .into());
    }
    if to < from {
        return Err(InputError::option("--to", format!("--to ({to:.2} m) is above --from ({from:.2} m)")).into());
    }
    let depths = depth_list(from, to, every, path.md_start());
    if depths.is_empty() {
        return Err(InputError::option("--to", "no bit depth below the top of the survey in the range").into());
    }
    if depths.len() > 100_000 {
        return Err(InputError::option("--every", format!("{} bit depths: use a longer step", depths.len())).into());
    }
    for &d in &depths {
        check_fits(&string_at_depth(&case.string, d), &case.well.hole, d).map_err(|m| InputError::option("--to", m))?;
    }
    let mut op = ChartOperation::from_case(&case);
    if let Some(w) = wob {
        op.wob_n = w;
    }
    let settings = ChartSettings {
        op,
        max_element_m: crate::models::softstring::segment_length_m(&case.solver),
    };
    let (du, su, fu, tu) = (
        a.units.depth(),
        a.units.small_length(),
        a.units.force(),
        a.units.torque(),
    );
    let mut out = std::io::stdout().lock();
    writeln!(out, "loads: {} ({})", case.name, a.case.display())?;
    writeln!(out, "  fidelity {}: {}", choice.level.name(), choice.reason)?;
    if choice.level != Level::Soft {
        writeln!(
            out,
            "  loads.csv: hook_load_kN, surface_torque_kNm, max_contact_force_kN and the buckling and yield columns are the soft string's (computed for every row); the {} results are the stiff_* columns (stiff_model = {})",
            choice.level.name(),
            choice.level.name()
        )?;
    }
    if case.operation.rpm <= 0.0 {
        writeln!(
            out,
            "  note: the case gives no rpm; rotating rows use {} rpm",
            fixed(op.rpm, 0)
        )?;
    }
    if op.wob_n == 0.0 {
        writeln!(
            out,
            "  note: WOB 0 for the drilling and sliding rows (give wob in the case or --wob)"
        )?;
    }

    // friction calibration first: the chart then uses the fitted factors
    let mut chart_case = case.clone();
    if let Some(mpath) = &a.measured {
        let data = read_measured_csv(mpath, path.md_start(), deepest)?;
        for p in &data {
            check_fits(&string_at_depth(&case.string, p.bit_md_m), &case.well.hole, p.bit_md_m)
                .map_err(|m| InputError::line(mpath, p.line, None, m))?;
        }
        let cal = calibrate(&case, &data, &op, settings.max_element_m)
            .with_context(|| format!("{}: friction calibration", mpath.display()))?;
        writeln!(
            out,
            "  calibration: {} points ({} residuals), {} iterations{}",
            data.len(),
            cal.residuals,
            cal.iterations,
            if cal.converged { "" } else { " (NOT CONVERGED)" }
        )?;
        for p in &cal.parameters {
            let what = match (p.fitted, p.std_error) {
                (true, Some(s)) => format!("{:.3} +/- {:.3} (was {:.3})", p.value, s, p.initial),
                (true, None) => format!(
                    "{:.3} (was {:.3}; no redundancy for an error estimate)",
                    p.value, p.initial
                ),
                (false, _) => format!("{:.3} kept (the data do not constrain this section)", p.value),
            };
            writeln!(
                out,
                "    section {} ({}-{}, {}): friction {}",
                p.section + 1,
                du.num(p.from_md_m, 0),
                du.fmt(p.to_md_m, 0),
                su.fmt(p.diameter_m, 1),
                what
            )?;
        }
        write!(out, "    residual RMS: hook load {}", fu.fmt(cal.rms_hook_load_n, 2))?;
        match cal.rms_torque_nm {
            Some(t) => writeln!(out, ", torque {}", tu.fmt(t, 3))?,
            None => writeln!(out)?,
        }
        if let Some(dir) = &a.out {
            let overlay = overlay_csv(&cal).map_err(|e| anyhow::anyhow!("internal error: {e}"))?;
            let json = calibration_json(&cal).map_err(|e| anyhow::anyhow!("internal error: {e}"))?;
            write_atomic(&dir.join("calibration.csv"), overlay.as_bytes())
                .with_context(|| format!("cannot write {}", dir.display()))?;
            write_atomic(
                &dir.join("calibration.json"),
                serde_json::to_string_pretty(&json)?.as_bytes(),
            )
            .with_context(|| format!("cannot write {}", dir.display()))?;
        }
        chart_case = calibrated_case(&case, &cal);
        writeln!(out, "  the chart below uses the fitted friction factors")?;
    }

    let t0 = std::time::Instant::now();
    let mut rows = soft_chart(&chart_case, &depths, &settings);
    let soft_s = t0.elapsed().as_secs_f64();
    let stiff = choice.level != Level::Soft;
    let t1 = std::time::Instant::now();
    if stiff {
        let progress = Progress::new(
            depths.len() as u64,
            &format!("loads {}: {}", a.case.display(), choice.level.name()),
            quiet,
        );
        run_stiff(&chart_case, &depths, &op, choice.level, &mut rows, &|k, d| {
            progress.set(k as u64, &format!("bit at {}", du.fmt(d, 1)))
        });
        progress.finish();
    }
    let csv = loads_csv(&rows).map_err(|e| anyhow::anyhow!("internal error: {e}"))?;
    if let Some(dir) = &a.out {
        write_atomic(&dir.join("loads.csv"), csv.as_bytes())
            .with_context(|| format!("cannot write {}", dir.display()))?;
    }
    print_summary(&rows, &depths, soft_s, a.units, &mut out)?;
    if stiff {
        print_stiff_summary(
            &rows,
            &depths,
            choice.level,
            t1.elapsed().as_secs_f64(),
            a.units,
            &mut out,
        )?;
    }
    match &a.out {
        Some(dir) => writeln!(out, "  wrote {}/loads.csv", dir.display())?,
        None => writeln!(out, "  (use --out DIR to write loads.csv)")?,
    }
    Ok(())
}

/// The level the chart runs: `--fidelity` (or `--stiff` = whole) over the case's `[solver]
/// fidelity`, `auto` = soft; `bha` (no surface values) is refused.
fn chart_fidelity(a: &LoadsArgs, case: &Case) -> Result<Choice, InputError> {
    if a.stiff {
        if let Some(f) = a.fidelity.as_deref().filter(|f| f.trim() != "whole") {
            return Err(InputError::option(
                "--stiff",
                format!("--stiff is --fidelity whole; it cannot be combined with --fidelity {f}"),
            ));
        }
    }
    let requested = if a.stiff {
        Fidelity::Level(Level::Whole)
    } else {
        fidelity_option(a.fidelity.as_deref(), case.solver.fidelity)?
    };
    let choice = choose(requested, Purpose::Loads);
    if choice.level == Level::Bha {
        let msg = "fidelity bha has no hook load or surface torque (the stiff model ends at the cut above the bottom-hole assembly), which the chart is made of: use soft, hybrid or whole";
        return Err(if a.fidelity.is_some() {
            InputError::option("--fidelity", msg)
        } else {
            InputError::key(
                &case.path,
                "solver.fidelity",
                format!("{msg} (or override with --fidelity)"),
            )
        });
    }
    Ok(choice)
}

/// The stiff rows (`level` whole or hybrid) of the chart `rows` of `case` at `depths`.
/// The stiff rows of every depth at `level`; `progress` hears (depth index, bit MD) before each.
fn run_stiff(
    case: &Case,
    depths: &[f64],
    op: &ChartOperation,
    level: Level,
    rows: &mut [LoadRow],
    progress: &dyn Fn(usize, f64),
) {
    let t1 = std::time::Instant::now();
    let mut previous: Vec<Option<Solved>> = Vec::new();
    for (k, &d) in depths.iter().enumerate() {
        progress(k, d);
        let c = case_at_depth(case, d);
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

/// Time, iterations and starts of the stiff rows, their table, and the rows that did not converge.
fn print_stiff_summary(
    rows: &[LoadRow],
    depths: &[f64],
    level: Level,
    seconds: f64,
    units: UnitSystem,
    out: &mut impl Write,
) -> std::io::Result<()> {
    let count = |s: Start| {
        rows.iter()
            .filter(|r| matches!(r.stiff, Some(StiffOutcome::Converged { start, .. }) if start == s))
            .count()
    };
    let iterations: usize = rows
        .iter()
        .filter_map(|r| r.stiff.as_ref())
        .map(|o| o.iterations())
        .sum();
    let what = match level {
        Level::Hybrid => "hybrid (stiff BHA + soft string above)",
        _ => "whole-string FEM",
    };
    write!(
        out,
        "  {what}: {} rows in {seconds:.2} s, {iterations} Newton iterations",
        rows.len()
    )?;
    if level == Level::Whole {
        writeln!(
            out,
            "; started from the same load case one depth up {}, from the previous load case {}, cold {}",
            count(Start::PreviousDepth),
            count(Start::PreviousCase),
            count(Start::Cold),
        )?;
    } else {
        writeln!(out, " (each row cold-started)")?;
    }
    print_table(
        rows,
        depths,
        units,
        |r| r.stiff.as_ref().and_then(StiffOutcome::loads),
        false,
        out,
    )?;
    let bad: Vec<String> = rows
        .iter()
        .filter(|r| !matches!(r.stiff, Some(StiffOutcome::Converged { .. })))
        .map(|r| format!("{} {}", units.depth().fmt(r.bit_md_m, 0), r.mode.name()))
        .collect();
    if !bad.is_empty() {
        writeln!(
            out,
            "  WARNING: stiff solve not converged for {} rows (no stiff numbers written for them): {}",
            bad.len(),
            bad.iter().take(10).cloned().collect::<Vec<_>>().join(", ")
        )?;
    }
    Ok(())
}

/// The chart's table in `units`: per bit depth (at most about 40 lines) the hook loads of the
/// five load cases and the rotating torques taken from `loads` of each row ("-" where it gives
/// none, e.g. a stiff row that did not converge), with the sliding row's sinusoidally buckled
/// length when `buckled_column`.
fn print_table<'a>(
    rows: &'a [LoadRow],
    depths: &[f64],
    units: UnitSystem,
    loads: impl Fn(&'a LoadRow) -> Option<&'a RowLoads>,
    buckled_column: bool,
    out: &mut impl Write,
) -> std::io::Result<()> {
    let (du, fu, tu) = (units.depth(), units.force(), units.torque());
    write!(
        out,
        "  bit MD {} | hook load {}: trip_in  trip_out  rot_off  drilling  sliding | torque {}: rot_off  drilling",
        du.label, fu.label, tu.label
    )?;
    if buckled_column {
        write!(out, " | buckled {} (sliding)", du.label)?;
    }
    writeln!(out)?;
    let stride = depths.len().div_ceil(40).max(1);
    for (k, d) in depths.iter().enumerate() {
        if k % stride != 0 && k + 1 != depths.len() {
            continue;
        }
        let value = |m, f: &dyn Fn(&RowLoads) -> String| loads(row(rows, k, m)).map_or("-".to_string(), f);
        let h = |m| value(m, &|l| fu.num(l.hook_load_n, 1));
        let t = |m| value(m, &|l| tu.num(l.surface_torque_nm, 2));
        write!(
            out,
            "  {:>9} | {:>9} {:>9} {:>8} {:>9} {:>8} | {:>8} {:>9}",
            du.num(*d, 1),
            h(Mode::TripIn),
            h(Mode::TripOut),
            h(Mode::RotatingOffBottom),
            h(Mode::Drilling),
            h(Mode::Sliding),
            t(Mode::RotatingOffBottom),
            t(Mode::Drilling),
        )?;
        if buckled_column {
            write!(
                out,
                " | {:>7}",
                du.num(row(rows, k, Mode::Sliding).buckling.sinusoidal_length_m, 1)
            )?;
        }
        writeln!(out)?;
    }
    Ok(())
}

fn row(rows: &[LoadRow], k: usize, mode: Mode) -> &LoadRow {
    let j = MODES.iter().position(|m| *m == mode).expect("all modes");
    &rows[k * MODES.len() + j]
}

/// Readable table in `units`: hook loads of the five cases and the rotating torques per depth
/// (at most about 40 lines), then the limits.
fn print_summary(
    rows: &[LoadRow],
    depths: &[f64],
    seconds: f64,
    units: UnitSystem,
    out: &mut impl Write,
) -> std::io::Result<()> {
    let (du, fu, tu) = (units.depth(), units.force(), units.torque());
    writeln!(
        out,
        "  {} bit depths x {} load cases, soft string in {:.3} s",
        depths.len(),
        MODES.len(),
        seconds
    )?;
    print_table(rows, depths, units, |r| Some(&r.soft), true, out)?;
    let worst = rows
        .iter()
        .filter_map(|r| r.yield_.max_stress_ratio.map(|s| (s, r)))
        .max_by(|a, b| a.0.total_cmp(&b.0));
    match worst {
        Some((s, r)) => writeln!(
            out,
            "  yield: largest von Mises / yield {} ({} at {}); top pipe body: tension {}, torque {}",
            fixed(s, 3),
            r.mode.name(),
            du.fmt(r.bit_md_m, 0),
            fu.fmt(r.yield_.tension_limit_n.unwrap_or(0.0), 0),
            tu.fmt(r.yield_.torque_limit_nm.unwrap_or(0.0), 1)
        )?,
        None => writeln!(
            out,
            "  yield limits: not computed (give grade or yield_strength in the [[string]] components)"
        )?,
    }
    let buckled: Vec<&LoadRow> = rows.iter().filter(|r| r.buckling.sinusoidal_length_m > 0.0).collect();
    if let Some(first) = buckled.first() {
        writeln!(
            out,
            "  buckling: {} rows with sinusoidal buckling (first: {} at {}), {} with helical",
            buckled.len(),
            first.mode.name(),
            du.fmt(first.bit_md_m, 0),
            rows.iter().filter(|r| r.buckling.helical_length_m > 0.0).count()
        )
    } else {
        writeln!(
            out,
            "  buckling: none (compression below the sinusoidal onset everywhere)"
        )
    }
}
