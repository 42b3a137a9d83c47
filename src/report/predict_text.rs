//! The readable summaries of `drillpath predict` and `drillpath backanalyze` on stdout, in the
//! user's units.

use super::display_units::{fixed, signed, UnitSystem};
use super::predict_output::{fitted_shown, BackanalysisRun};
use crate::case::{Case, Choice, Level};
use crate::predict::forecast::Forecast;
use crate::predict::march::{RIPPLE_WARN_DEG, RIPPLE_WINDOW_M};
use crate::predict::tracking::project::Projection;
use crate::predict::tracking::references::Reference;
use crate::predict::tracking::skill::{ErrorSummary, Skill};
use std::io::Write;

/// Write the summary of the forecast `f` of `case` (model `choice`) to `out`.
pub fn write_forecast(
    out: &mut impl Write,
    case: &Case,
    choice: &Choice,
    f: &Forecast,
    units: UnitSystem,
) -> std::io::Result<()> {
    let (depth_unit, force_unit, ru, error_unit) = (units.depth(), units.force(), units.dogleg(), units.per_100());
    let p = &f.prediction;
    let rt = &f.rates;
    let first = &p.steps[0];
    let end = f.rows.last().expect("start row");
    writeln!(out, "predict: {} ({})", case.name, case.path.display())?;
    writeln!(out, "  fidelity {}: {}", choice.level.name(), choice.reason)?;
    for w in &f.warnings {
        writeln!(out, "  WARNING: {w}")?;
    }
    writeln!(
        out,
        "  from {} (I {} deg, A {} deg) to {}: I {} deg, A {} deg, TVD {}, N {}, E {}",
        depth_unit.fmt(p.from_md_m, 2),
        fixed(first.inc_rad.to_degrees(), 3),
        fixed(
            crate::geometry::survey::degrees_in_turn(first.azi_rad.to_degrees(), 3),
            3
        ),
        depth_unit.fmt(p.to_md_m, 2),
        fixed(end.inc_rad.to_degrees(), 3),
        fixed(crate::geometry::survey::degrees_in_turn(end.azi_rad.to_degrees(), 3), 3),
        depth_unit.fmt(end.position.z, 2),
        depth_unit.fmt(end.position.x, 2),
        depth_unit.fmt(end.position.y, 2)
    )?;
    writeln!(
        out,
        "  build rate {}, walk rate {}; bit at start: build force {}, walk force {}, tilt {}/{} deg; mean over the steps: {}, {}",
        ru.fmt_signed(rt.build_rate_rad_per_30m / 30.0, 3),
        ru.fmt_signed(rt.walk_rate_rad_per_30m / 30.0, 3),
        force_unit.fmt_signed(first.bit.build_force_n, 3),
        force_unit.fmt_signed(first.bit.walk_force_n, 3),
        signed(first.bit.tilt_inc_rad.to_degrees(), 4),
        signed(first.bit.tilt_azi_rad.to_degrees(), 4),
        force_unit.fmt_signed(rt.mean_build_force_n, 3),
        force_unit.fmt_signed(rt.mean_walk_force_n, 3)
    )?;
    if let Some(t) = &f.tracking {
        writeln!(
            out,
            "  tracking: {} measured stations; at {} error inc {} deg, azi {} deg = {} and {} (seed paper metric)",
            t.stations,
            depth_unit.fmt(t.end_md_m, 1),
            signed(t.end_inc_err_rad.to_degrees(), 3),
            signed(t.end_azi_err_rad.to_degrees(), 3),
            error_unit.fmt(t.inc_err_per_100m_rad / 100.0, 3),
            error_unit.fmt(t.azi_err_per_100m_rad / 100.0, 3)
        )?;
    }
    if let Some(sk) = &f.skill {
        write_skill(
            out,
            sk,
            "at the stations drilled ahead (per length from the start)",
            units,
        )?;
    }
    if let Some(pr) = &f.projection {
        write_projection(out, pr, units)?;
    }
    if let Some(e) = &f.step_error {
        writeln!(
            out,
            "  step extrapolation: marches at {} and {} combined (Richardson); step error left in the finer one, estimated: inc {} deg, azi {} deg",
            depth_unit.fmt(e.coarse_step_m, 2),
            depth_unit.fmt(e.fine_step_m, 2),
            fixed(e.max_inc_rad.to_degrees(), 3),
            fixed(e.max_azi_rad.to_degrees(), 3)
        )?;
    }
    if p.ripple_deg >= RIPPLE_WARN_DEG {
        writeln!(
            out,
            "  warning: the predicted hole ripples around its trend by {} deg at the end (over the last {}): the end inclination and azimuth move by up to that much with the ripple's phase; a longer step damps it (docs/performance.md, \"Step convergence\")",
            fixed(p.ripple_deg, 2),
            depth_unit.fmt(RIPPLE_WINDOW_M, 0)
        )?;
    }
    let model = if choice.level == Level::Whole {
        "stiff whole string".to_string()
    } else {
        format!("stiff BHA cut {} above the bit", depth_unit.fmt(p.cut_m, 1))
    };
    writeln!(
        out,
        "  model: {model}, {} DOF; {} steps, {} solver iterations, {:.2} s",
        p.dofs,
        p.steps.len() - 1,
        p.iterations,
        p.seconds
    )
}

/// The comparison of several cases' forecasts as a readable table in `units` (the CSV stays SI).
pub fn comparison_table(runs: &[(&Case, &Forecast)], units: UnitSystem) -> String {
    let (depth_unit, force_unit, ru) = (units.depth(), units.force(), units.dogleg());
    let mut out = format!(
        "case | from {d} | to {d} | build {r} | walk {r} | mean build force {f} | mean walk force {f} | end inc deg | end azi deg\n",
        d = depth_unit.label,
        r = ru.label,
        f = force_unit.label
    );
    for (case, f) in runs {
        let (p, rt) = (&f.prediction, &f.rates);
        let end = p.steps.last().expect("start record");
        out.push_str(&format!(
            "{} | {} | {} | {} | {} | {} | {} | {} | {}\n",
            case.name,
            depth_unit.num(p.from_md_m, 2),
            depth_unit.num(p.to_md_m, 2),
            signed(ru.show(rt.build_rate_rad_per_30m / 30.0), ru.decimals(3)),
            signed(ru.show(rt.walk_rate_rad_per_30m / 30.0), ru.decimals(3)),
            signed(force_unit.show(rt.mean_build_force_n), force_unit.decimals(3)),
            signed(force_unit.show(rt.mean_walk_force_n), force_unit.decimals(3)),
            fixed(end.inc_rad.to_degrees(), 3),
            fixed(crate::geometry::survey::degrees_in_turn(end.azi_rad.to_degrees(), 3), 3),
        ));
    }
    out
}

/// Write the summary of the back-analysis `run` to `out`.
pub fn write_backanalysis(out: &mut impl Write, run: &BackanalysisRun, units: UnitSystem) -> std::io::Result<()> {
    let BackanalysisRun {
        case,
        case_file,
        plan,
        step_m,
        choice,
        result: b,
        later_runs,
    } = *run;
    let (depth_unit, error_unit) = (units.depth(), units.per_100());
    writeln!(out, "backanalyze: {} ({})", case.name, case_file.display())?;
    if !later_runs.is_empty() {
        writeln!(out, "  BHA run 1 to {}", depth_unit.fmt(case.operation.bit_md_m, 1))?;
        for (k, (c, f)) in later_runs.iter().enumerate() {
            writeln!(
                out,
                "  BHA run {} to {}: {} ({})",
                k + 2,
                depth_unit.fmt(c.operation.bit_md_m, 1),
                c.name,
                f.display()
            )?;
        }
    }
    writeln!(out, "  fidelity {}: {}", choice.level.name(), choice.reason)?;
    if let Some(shoe) = plan.below_previous_hole_md_m {
        writeln!(
            out,
            "  from: the hole below {} (the wider hole above was drilled by another bit; give --from to include it)",
            depth_unit.fmt(shoe, 1)
        )?;
    }
    for (iv, e) in &b.skipped {
        writeln!(
            out,
            "  WARNING: interval {}-{} skipped (not in the errors): {e}",
            depth_unit.num(iv.from_md_m, 1),
            depth_unit.fmt(iv.to_md_m, 1)
        )?;
    }
    let (first, last) = b.range_md_m();
    let s = &b.stats;
    writeln!(
        out,
        "  {} intervals from {} to {} (step {}): mean |error|: inclination {}, azimuth {} (RMS {} and {})",
        b.base.len(),
        depth_unit.fmt(first, 1),
        depth_unit.fmt(last, 1),
        depth_unit.fmt(step_m, 2),
        error_unit.fmt(s.inc_mean_abs_per_100m_rad / 100.0, 3),
        error_unit.fmt(s.azi_mean_abs_per_100m_rad / 100.0, 3),
        error_unit.fmt(s.inc_rms_per_100m_rad / 100.0, 3),
        error_unit.fmt(s.azi_rms_per_100m_rad / 100.0, 3)
    )?;
    if let Some(c) = &b.calibration {
        for &(p, v, sd) in &c.calibration.fitted {
            let (name, value, std_dev, identifiable) = fitted_shown(p, v, sd);
            writeln!(
                out,
                "  fitted {name} = {} +/- {}{}",
                fixed(value, 5),
                std_dev.map(|v| fixed(v, 5)).unwrap_or_else(|| "n/a".into()),
                if identifiable {
                    ""
                } else {
                    "  (NOT identifiable from these intervals: the predictions barely depend on it)"
                }
            )?;
        }
        writeln!(
            out,
            "  calibrated on {}-{}, scored on {}-{}:",
            depth_unit.num(first, 1),
            depth_unit.fmt(c.split_md_m, 1),
            depth_unit.num(c.split_md_m, 1),
            depth_unit.fmt(last, 1)
        )?;
        for (stats, label) in [
            (&c.in_sample_default, "  calibration part, case law "),
            (&c.in_sample_fitted, "  calibration part, fitted law"),
            (&c.out_of_sample_default, "  scoring part, case law     "),
            (&c.out_of_sample_fitted, "  scoring part, fitted law   "),
        ] {
            writeln!(
                out,
                "  {label}: inclination {}, azimuth {}",
                error_unit.fmt(stats.inc_mean_abs_per_100m_rad / 100.0, 3),
                error_unit.fmt(stats.azi_mean_abs_per_100m_rad / 100.0, 3)
            )?;
        }
    }
    if let Some(sk) = &b.skill {
        write_skill(out, sk, "at the interval ends (per length of interval)", units)?;
    }
    if let Some(a) = &b.assimilation {
        let [inc, azi, _] = a.coverage();
        writeln!(
            out,
            "  assimilation: model trust {}% (the likelihood's share on the variants following the model's changing tendency); naive members {}; measured end stations within one standard deviation: {}% of inclinations, {}% of azimuths",
            fixed(100.0 * a.filter.model_trust(), 0),
            naive_shares(&a.filter),
            fixed(100.0 * inc, 0),
            fixed(100.0 * azi, 0)
        )?;
    }
    writeln!(out, "  {:.2} s", b.seconds)
}

/// The naive members' shares of the mixture's weight, e.g. `no_correction 12%, statistic 30%,
/// hold 0%`.
fn naive_shares(bank: &crate::predict::tracking::bank::FilterBank) -> String {
    bank.naive_weights()
        .iter()
        .map(|(m, w)| format!("{} {}%", m.name(), fixed(100.0 * w, 0)))
        .collect::<Vec<_>>()
        .join(", ")
}

/// The model's mean direction error against the naive projections, the statistic and (when
/// assimilating) the plain model and the frozen assimilation, `where` they are compared.
fn write_skill(out: &mut impl Write, s: &Skill, place: &str, units: UnitSystem) -> std::io::Result<()> {
    let e = units.per_100();
    let d = |x: &ErrorSummary| e.fmt(x.dir_err_per_100m_rad / 100.0, 3);
    let r = |q: Reference| s.reference(q).map(d).unwrap_or_default();
    let bare = |q: Reference| {
        s.reference(q)
            .map(|x| e.num(x.dir_err_per_100m_rad / 100.0, 3))
            .unwrap_or_default()
    };
    let rates = |w: f64| Reference::Rates { window_m: w };
    writeln!(
        out,
        "  direction error {place}: model {}; hold {}, rates over the last {}/{}/{} {}/{}/{}, statistic {}; best naive {}: skill {}",
        d(&s.model),
        r(Reference::Hold),
        units.depth().num(30.0, 0),
        units.depth().num(60.0, 0),
        units.depth().fmt(90.0, 0),
        bare(rates(30.0)),
        bare(rates(60.0)),
        r(rates(90.0)),
        r(Reference::Statistic),
        s.best_naive.name(),
        s.skill
            .map(|k| signed(k, 3))
            .unwrap_or_else(|| "not defined (the naive projection is exact)".into())
    )?;
    if let (Some(plain), Some(frozen), Some(share)) = (&s.plain, &s.frozen, s.physics_share) {
        writeln!(
            out,
            "  assimilated model against the plain model {} and the frozen assimilation {}: physics share {}",
            d(plain),
            d(frozen),
            signed(share, 3)
        )?;
    }
    Ok(())
}

/// The projection's bounds at its end and the bank's trust in the model.
fn write_projection(out: &mut impl Write, p: &Projection, units: UnitSystem) -> std::io::Result<()> {
    let Some(end) = p.rows.last() else {
        return Ok(());
    };
    let depth_unit = units.depth();
    writeln!(
        out,
        "  assimilated at {}: I {} +/- {} deg, A {} +/- {} deg, position +/- {} sideways and {} up or down (one standard deviation); model trust {}%",
        depth_unit.fmt(end.md_m, 2),
        fixed(end.direction.inc_rad.to_degrees(), 3),
        fixed(end.inc_sd_rad.to_degrees(), 3),
        fixed(crate::geometry::survey::degrees_in_turn(end.direction.azi_rad.to_degrees(), 3), 3),
        fixed(end.azi_sd_rad.to_degrees(), 3),
        depth_unit.fmt(end.lateral_sd_m, 2),
        depth_unit.fmt(end.vertical_sd_m, 2),
        fixed(100.0 * p.bank.model_trust(), 0)
    )
}
