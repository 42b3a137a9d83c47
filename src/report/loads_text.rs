//! The readable summary of `drillpath loads` on stdout: the level, the calibration, the soft
//! string's table and limits, and the stiff columns' table.

use super::display_units::{fixed, UnitSystem};
use crate::case::{Case, Level, Mode};
use crate::loads::calibrate::Calibration;
use crate::loads::row::{LoadRow, RowLoads, Start, StiffOutcome};
use crate::loads::run::{Chart, ChartPlan};
use crate::loads::MODES;
use crate::models::helical_drag::diverged;
use std::io::Write;
use std::path::Path;

/// The whole summary of `chart` (computed by `plan` on `case`, read from `case_file`) in `units`.
pub fn write_loads(
    out: &mut impl Write,
    case: &Case,
    case_file: &Path,
    plan: &ChartPlan,
    chart: &Chart,
    units: UnitSystem,
) -> std::io::Result<()> {
    write_header(out, case, case_file, plan)?;
    if let Some(cal) = &chart.calibration {
        write_calibration(out, cal, plan.measured.len(), units)?;
    }
    print_summary(&chart.rows, &plan.depths, chart.soft_seconds, units, out)?;
    warn_helical_lock_up(&chart.rows, units, out)?;
    warn_helical_drag_diverges(&chart.rows, units, out)?;
    print_lock_up_depths(chart, units, out)?;
    if plan.choice.level != Level::Soft {
        print_stiff_summary(
            &chart.rows,
            &plan.depths,
            plan.choice.level,
            chart.stiff_seconds,
            units,
            out,
        )?;
    }
    Ok(())
}

/// The case, the level and why, what the columns hold, and the operation's notes.
fn write_header(out: &mut impl Write, case: &Case, case_file: &Path, plan: &ChartPlan) -> std::io::Result<()> {
    let level = plan.choice.level;
    writeln!(out, "loads: {} ({})", case.name, case_file.display())?;
    writeln!(out, "  fidelity {}: {}", level.name(), plan.choice.reason)?;
    if level != Level::Soft {
        writeln!(
            out,
            "  loads.csv: hook_load_kN, surface_torque_kNm, max_contact_force_kN and the buckling and yield columns are the soft string's (computed for every row); the {} results are the stiff_* columns (stiff_model = {})",
            level.name(),
            level.name()
        )?;
    }
    if case.operation.rpm <= 0.0 {
        writeln!(
            out,
            "  note: the case gives no rpm; rotating rows use {} rpm",
            fixed(plan.op.rpm, 0)
        )?;
    }
    if plan.op.wob_n == 0.0 {
        writeln!(
            out,
            "  note: WOB 0 for the drilling and sliding rows (give wob in the case or --wob)"
        )?;
    }
    Ok(())
}

/// The fitted friction per section and the residuals.
fn write_calibration(out: &mut impl Write, cal: &Calibration, points: usize, units: UnitSystem) -> std::io::Result<()> {
    let (depth_unit, small_unit, force_unit, torque_unit) =
        (units.depth(), units.small_length(), units.force(), units.torque());
    writeln!(
        out,
        "  calibration: {} points ({} residuals), {} iterations{}",
        points,
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
            depth_unit.num(p.from_md_m, 0),
            depth_unit.fmt(p.to_md_m, 0),
            small_unit.fmt(p.diameter_m, 1),
            what
        )?;
    }
    write!(
        out,
        "    residual RMS: hook load {}",
        force_unit.fmt(cal.rms_hook_load_n, 2)
    )?;
    match cal.rms_torque_nm {
        Some(t) => writeln!(out, ", torque {}", torque_unit.fmt(t, 3))?,
        None => writeln!(out)?,
    }
    writeln!(out, "  the chart below uses the fitted friction factors")
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
        let buckled = count(Start::BuckledShape);
        if buckled > 0 {
            writeln!(
                out,
                "  solved again from the buckled shape after the cold start found no equilibrium: {buckled} rows (stiff_buckled_start; buckled equilibria with friction are not unique, docs/theory.md 7.5)"
            )?;
        }
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
        .filter(|r| {
            !matches!(
                r.stiff,
                Some(StiffOutcome::Converged { .. } | StiffOutcome::LockedAtZeroWob { .. })
            )
        })
        .map(|r| format!("{} {}", units.depth().fmt(r.bit_md_m, 0), r.mode.name()))
        .collect();
    warn_rows(out, &bad, |n| {
        format!("stiff solve not converged for {n} rows (no stiff numbers written for them)")
    })?;
    let at_zero: Vec<String> = rows
        .iter()
        .filter(|r| matches!(r.stiff, Some(StiffOutcome::LockedAtZeroWob { .. })))
        .map(|r| format!("{} {}", units.depth().fmt(r.bit_md_m, 0), r.mode.name()))
        .collect();
    warn_rows(out, &at_zero, |n| {
        format!("lock-up at zero WOB: in {n} rows the string cannot be put on bottom at any WOB, or run in (trip_in), by the soft string of the lock-up (plain, or with the helix's drag), so no whole-string equilibrium exists there: stiff_status locked_up, no stiff numbers; the soft string's numbers and the lock-up depths are the answer")
    })?;
    let locked = |by_helix: bool| -> Vec<String> {
        rows.iter()
            .filter(|r| helically_locked(r) == by_helix)
            .filter_map(|r| {
                let wob = r.stiff.as_ref()?.lock_up_wob_n()?;
                let depth = units.depth().fmt(r.bit_md_m, 0);
                Some(format!("{depth} {} at {}", r.mode.name(), units.force().fmt(wob, 1)))
            })
            .collect()
    };
    warn_rows(out, &locked(false), |n| {
        format!("lock-up: {n} stiff rows find no equilibrium at their WOB; their stiff numbers are at the largest WOB the string delivers, hook load zero (stiff_lock_up_wob_kN)")
    })?;
    warn_rows(out, &locked(true), |n| {
        format!("helical lock-up: {n} stiff rows find no equilibrium at their WOB, locked up by the helix's drag (helical_drag_hook_load_kN below zero); their stiff numbers are at a WOB below the lock-up, solved from the buckled shape (stiff_lock_up_wob_kN; the largest WOB lies between it and that soft string's, docs/guide.md)")
    })?;
    let unbuckled = rows_over(rows, units, StiffOutcome::unbuckled_helical_m);
    warn_rows(out, &unbuckled, |n| {
        format!("{n} stiff rows find the pipe unbuckled where it is compressed beyond the helical onset (stiff_unbuckled_helical_m): their stiff hook load and torque miss the helix's wall force and drag there; treat them with caution")
    })?;
    let coarse = rows_over(rows, units, StiffOutcome::coarse_for_pitch_m);
    warn_rows(out, &coarse, |n| {
        format!("{n} stiff rows mesh helically buckled pipe with elements longer than an eighth of the helix's pitch (stiff_coarse_for_pitch_m): their wall force and drag there are a coarse mesh's; `solve` at that bit depth refines it, or set [solver] element_length shorter (docs/guide.md)")
    })?;
    let whirling = rows_over(rows, units, StiffOutcome::whirl_m);
    warn_rows(out, &whirling, |n| {
        format!("{n} stiff rows rotate with pipe helically buckled (stiff_whirl_m): a real string whirls there, and their wall friction there keeps its torque and drag but not its lateral push (docs/theory.md 7.5)")
    })?;
    Ok(())
}

/// Whether the row `r` is locked up by the helix's drag only: the soft string's hook load not
/// below zero, that of the soft string with the helix's drag below it.
fn helically_locked(r: &LoadRow) -> bool {
    r.soft.hook_load_n >= 0.0 && r.helical_drag_hook_load_n < 0.0
}

/// A `WARNING:` line listing the rows the helix locks up: the soft string's hook load not below
/// zero, that of the soft string with the helix's drag below it (`helical_drag_hook_load_kN`).
fn warn_helical_lock_up(rows: &[LoadRow], units: UnitSystem, out: &mut impl Write) -> std::io::Result<()> {
    let locked: Vec<String> = rows
        .iter()
        .filter(|r| helically_locked(r))
        .map(|r| format!("{} {}", units.depth().fmt(r.bit_md_m, 0), r.mode.name()))
        .collect();
    warn_rows(out, &locked, |n| {
        format!("helical lock-up: in {n} rows the soft string with the helix's drag (Mitchell's r F^2/(4 EI), helical_drag_hook_load_kN) needs the surface to push, while the soft string's hook load is not below zero: the helically buckled pipe's drag outgrows its weight (docs/theory.md 7.7)")
    })
}

/// A `WARNING:` line listing the rows whose soft string with the helix's drag diverged
/// (`helical_drag_diverges`): their `helical_drag_hook_load_kN` is a flag, not a load.
fn warn_helical_drag_diverges(rows: &[LoadRow], units: UnitSystem, out: &mut impl Write) -> std::io::Result<()> {
    let diverging: Vec<String> = rows
        .iter()
        .filter(|r| diverged(r.helical_drag_hook_load_n))
        .map(|r| format!("{} {}", units.depth().fmt(r.bit_md_m, 0), r.mode.name()))
        .collect();
    warn_rows(out, &diverging, |n| {
        format!("the helix's drag diverges: in {n} rows the compression of the soft string with the helix's drag grows without bound up the helix (helical_drag_diverges true): their helical_drag_hook_load_kN, below -10,000 kN, flags the lock-up and is not a load (docs/theory.md 7.7)")
    })
}

/// A line per load case locked up at the deepest bit depth (on bottom, or running in): its
/// lock-up depths ([`Chart::lock_up_depths`]).
fn print_lock_up_depths(chart: &Chart, units: UnitSystem, out: &mut impl Write) -> std::io::Result<()> {
    let depth = units.depth();
    let md = |m: f64| depth.fmt(m, 0);
    for (mode, d) in &chart.lock_up_depths {
        if *mode == Mode::TripIn {
            let Some(first) = d.running_in_clause(md) else {
                continue;
            };
            writeln!(
                out,
                "  lock-up depth, {}: {first} (the hook load below zero from there; {}, to 0.1 m)",
                mode.name(),
                d.drag.name()
            )?;
            continue;
        }
        let Some(first) = d.at_wob_clause(md) else {
            continue;
        };
        let zero = match d.at_zero_wob_md_m {
            Some(z) => format!("even at zero WOB from {}", md(z)),
            None => "at zero WOB it reaches the deepest depth".to_string(),
        };
        writeln!(
            out,
            "  lock-up depth, {}: at the chart's WOB {first}, {zero} ({}, to 0.1 m)",
            mode.name(),
            d.drag.name()
        )?;
    }
    Ok(())
}

/// The rows whose stiff outcome gives a positive `length` (m), each as "depth mode over length"
/// (a warning's list of rows).
fn rows_over(rows: &[LoadRow], units: UnitSystem, length: impl Fn(&StiffOutcome) -> Option<f64>) -> Vec<String> {
    rows.iter()
        .filter_map(|r| {
            let l = r.stiff.as_ref().and_then(&length).filter(|l| *l > 0.0)?;
            let depth = units.depth().fmt(r.bit_md_m, 0);
            Some(format!("{depth} {} over {}", r.mode.name(), units.depth().fmt(l, 0)))
        })
        .collect()
}

/// A `WARNING:` line about the listed `rows` (none without rows): `text` of their count, then
/// the first ten of them, joined by commas.
fn warn_rows(out: &mut impl Write, rows: &[String], text: impl Fn(usize) -> String) -> std::io::Result<()> {
    if rows.is_empty() {
        return Ok(());
    }
    let first_ten = rows.iter().take(10).cloned().collect::<Vec<_>>().join(", ");
    writeln!(out, "  WARNING: {}: {first_ten}", text(rows.len()))
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
    let (depth_unit, force_unit, torque_unit) = (units.depth(), units.force(), units.torque());
    write!(
        out,
        "  bit MD {} | hook load {}: trip_in  trip_out  rot_off  drilling  sliding | torque {}: rot_off  drilling",
        depth_unit.label, force_unit.label, torque_unit.label
    )?;
    if buckled_column {
        write!(out, " | buckled {} (sliding)", depth_unit.label)?;
    }
    writeln!(out)?;
    let stride = depths.len().div_ceil(40).max(1);
    for (k, d) in depths.iter().enumerate() {
        if k % stride != 0 && k + 1 != depths.len() {
            continue;
        }
        let value = |m, f: &dyn Fn(&RowLoads) -> String| loads(row(rows, k, m)).map_or("-".to_string(), f);
        let h = |m| value(m, &|l| force_unit.num(l.hook_load_n, 1));
        let t = |m| value(m, &|l| torque_unit.num(l.surface_torque_nm, 2));
        write!(
            out,
            "  {:>9} | {:>9} {:>9} {:>8} {:>9} {:>8} | {:>8} {:>9}",
            depth_unit.num(*d, 1),
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
                depth_unit.num(row(rows, k, Mode::Sliding).buckling.sinusoidal_length_m, 1)
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
    let (depth_unit, force_unit, torque_unit) = (units.depth(), units.force(), units.torque());
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
            depth_unit.fmt(r.bit_md_m, 0),
            force_unit.fmt(r.yield_.tension_limit_n.unwrap_or(0.0), 0),
            torque_unit.fmt(r.yield_.torque_limit_nm.unwrap_or(0.0), 1)
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
            depth_unit.fmt(first.bit_md_m, 0),
            rows.iter().filter(|r| r.buckling.helical_length_m > 0.0).count()
        )
    } else {
        writeln!(
            out,
            "  buckling: none (compression below the sinusoidal onset everywhere)"
        )
    }
}
