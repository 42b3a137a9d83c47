//! HTML reports of `drillpath predict` and `drillpath backanalyze`: inclination and azimuth
//! against MD (predicted vs measured), plan view and vertical section, bit build/walk force and
//! tilt against MD, and the errors against the measured stations.

use super::display_units::UnitSystem;
use super::html::{check_finite_text, Page};
use super::inputs::echo_inputs;
use super::plots::{render, Chart, Series, Style};
use crate::case::Case;
use crate::geometry::{Vec3, WellPath};
use crate::predict::backanalysis::Backanalysis;
use crate::predict::forecast::Forecast;
use crate::predict::intervals::IntervalResult;
use crate::predict::march::StepRecord;
use crate::predict::tracking::project::{ProjectedRow, Projection};
use crate::predict::tracking::references::{Direction, Reference};
use crate::predict::tracking::skill::EndDirections;

/// Ids of the figures of a predict report (the tests look for each).
pub const PREDICT_FIGURES: &[&str] = &[
    "inclination",
    "azimuth",
    "plan-view",
    "vertical-section",
    "bit-forces",
    "bit-tilt",
    "errors",
];

/// Ids of the figures of a backanalyze report.
pub const BACKANALYZE_FIGURES: &[&str] = PREDICT_FIGURES;

/// Measured stations of `path` between `from` and `to` MD: (md, inc rad, azi rad, position).
fn measured(path: &WellPath, from: f64, to: f64) -> Vec<(f64, f64, f64, Vec3)> {
    path.stations()
        .iter()
        .enumerate()
        .filter(|(_, s)| s.md_m >= from - 1e-6 && s.md_m <= to + 1e-6)
        .map(|(k, s)| (s.md_m, s.inc_rad, s.azi_rad, path.station_position(k)))
        .collect()
}

/// The "Trajectory" section of a report: the inclination and azimuth charts (both captioned
/// `angles_caption`), the plan view and the vertical section along the azimuth at
/// `section_azimuth_at` (e.g. "the start").
fn trajectory_figures(
    page: &mut Page,
    [inc, azi, plan, sec]: [&Chart; 4],
    angles_caption: &str,
    section_azimuth_at: &str,
) -> Result<(), String> {
    page.heading("Trajectory");
    page.figure("inclination", &render(inc)?, angles_caption);
    page.figure("azimuth", &render(azi)?, angles_caption);
    page.figure(
        "plan-view",
        &render(plan)?,
        "north against east, same scale on both axes",
    );
    page.figure(
        "vertical-section",
        &render(sec)?,
        &format!(
            "TVD against the horizontal distance along the azimuth at {section_azimuth_at}, same scale on both axes"
        ),
    );
    Ok(())
}

/// Azimuth in degrees kept continuous near `reference` (no jump at 0/360 within a plot).
fn azi_deg(azi_rad: f64, reference_rad: f64) -> f64 {
    let d = crate::geometry::survey::wrap_pi(azi_rad - reference_rad);
    (reference_rad + d).to_degrees()
}

struct Trajectories<'a> {
    units: UnitSystem,
    /// Section azimuth, rad.
    section_azi: f64,
    /// Reference azimuth for continuous azimuth plots, rad.
    azi_ref: f64,
    measured: &'a [(f64, f64, f64, Vec3)],
}

impl Trajectories<'_> {
    fn vs(&self, p: &Vec3) -> f64 {
        p.x * self.section_azi.cos() + p.y * self.section_azi.sin()
    }
    /// Inclination, azimuth, plan and section charts with the measured series added.
    fn charts(&self) -> [Chart; 4] {
        let depth_unit = self.units.depth();
        let md = format!("MD [{}]", depth_unit.label);
        let m = self.measured;
        let inc = Chart::new("Inclination", &md, "inclination [deg]").with(Series::new(
            "measured",
            m.iter().map(|s| (depth_unit.show(s.0), s.1.to_degrees())).collect(),
            Style::Points,
            6,
        ));
        let azi = Chart::new("Azimuth", &md, "azimuth [deg]").with(Series::new(
            "measured",
            m.iter()
                .map(|s| (depth_unit.show(s.0), azi_deg(s.2, self.azi_ref)))
                .collect(),
            Style::Points,
            6,
        ));
        let mut plan = Chart::new(
            "Plan view",
            &format!("east [{}]", depth_unit.label),
            &format!("north [{}]", depth_unit.label),
        )
        .with(Series::new(
            "measured",
            m.iter()
                .map(|s| (depth_unit.show(s.3.y), depth_unit.show(s.3.x)))
                .collect(),
            Style::LinePoints,
            6,
        ));
        plan.equal_aspect = true;
        plan.size = (860, 520);
        let mut sec = Chart::new(
            &format!(
                "Vertical section along azimuth {:.1} deg",
                crate::geometry::survey::degrees_in_turn(self.section_azi.to_degrees(), 1)
            ),
            &format!("vertical section [{}]", depth_unit.label),
            &format!("TVD [{}]", depth_unit.label),
        )
        .with(Series::new(
            "measured",
            m.iter()
                .map(|s| (depth_unit.show(self.vs(&s.3)), depth_unit.show(s.3.z)))
                .collect(),
            Style::LinePoints,
            6,
        ));
        sec.equal_aspect = true;
        sec.y_down = true;
        sec.size = (860, 520);
        [inc, azi, plan, sec]
    }
}

/// The predict report's HTML text for one or several cases predicted over the same interval.
pub fn predict_report(runs: &[(&Case, &Forecast)], units: UnitSystem) -> Result<String, String> {
    let (first_case, _) = *runs.first().ok_or("no prediction to report")?;
    let title = if runs.len() == 1 {
        format!("drillpath predict: {}", first_case.name)
    } else {
        format!("drillpath predict: {} cases compared", runs.len())
    };
    let mut page = Page::new(&title);
    predict_key_results(&mut page, runs, units)?;
    predict_figures(&mut page, runs, units)?;
    for (case, forecast) in runs {
        echo_inputs(&mut page, case, forecast.prediction.from_md_m, units)?;
    }
    let html = page.finish();
    check_finite_text(&html)?;
    Ok(html)
}

/// The key results of a predict report: per case the interval, rates, end direction, mean bit
/// forces and end errors.
fn predict_key_results(page: &mut Page, runs: &[(&Case, &Forecast)], units: UnitSystem) -> Result<(), String> {
    let (depth_unit, force_unit) = (units.depth(), units.force());
    page.heading("Key results");
    let mut rows = Vec::new();
    for (case, forecast) in runs {
        let (pred, rt, tr) = (&forecast.prediction, &forecast.rates, &forecast.tracking);
        let end = pred.steps.last().ok_or("empty prediction")?;
        rows.push(vec![
            case.name.clone(),
            format!(
                "{} - {}",
                depth_unit.fmt(pred.from_md_m, 1),
                depth_unit.fmt(pred.to_md_m, 1)
            ),
            units.dogleg().fmt(rt.build_rate_rad_per_30m / 30.0, 3),
            units.dogleg().fmt(rt.walk_rate_rad_per_30m / 30.0, 3),
            format!(
                "{:.3} / {:.3} deg",
                end.inc_rad.to_degrees(),
                crate::geometry::survey::degrees_in_turn(end.azi_rad.to_degrees(), 3)
            ),
            force_unit.fmt(rt.mean_build_force_n, 3),
            force_unit.fmt(rt.mean_walk_force_n, 3),
            tr.map(|t| {
                format!(
                    "{:+.3} / {:+.3} deg ({} stations)",
                    t.end_inc_err_rad.to_degrees(),
                    t.end_azi_err_rad.to_degrees(),
                    t.stations
                )
            })
            .unwrap_or_else(|| "no measured stations".into()),
        ]);
    }
    page.table(
        &[
            "case".into(),
            "interval".into(),
            "build rate".into(),
            "walk rate".into(),
            "end inc / azi".into(),
            "mean build force".into(),
            "mean walk force".into(),
            "end error inc / azi".into(),
        ],
        &rows,
    );
    page.note("build force + = toward the high side, walk force + = to the right; errors are predicted - measured.");

    Ok(())
}

/// The figures of a predict report: trajectory, bit forces and tilt, errors.
fn predict_figures(page: &mut Page, runs: &[(&Case, &Forecast)], units: UnitSystem) -> Result<(), String> {
    let (depth_unit, force_unit) = (units.depth(), units.force());
    let (first_case, first) = *runs.first().ok_or("no prediction to report")?;
    let first = &first.prediction;
    let from = first.from_md_m;
    let to = runs
        .iter()
        .map(|r| r.1.prediction.to_md_m)
        .fold(first.to_md_m, f64::max);
    let context = (to - from).max(30.0);
    let meas = measured(&first_case.well.path, from - context, to);
    let start = first.path.point_at(from);
    let tj = Trajectories {
        units,
        section_azi: start.azi_rad,
        azi_ref: start.azi_rad,
        measured: &meas,
    };
    let [mut inc, mut azi, mut plan, mut sec] = tj.charts();
    let md = format!("MD [{}]", depth_unit.label);
    let mut forces = Chart::new("Bit side forces", &md, &format!("force [{}]", force_unit.label));
    forces.zero_line = true;
    let mut tilt = Chart::new("Bit tilt", &md, "tilt [deg]");
    tilt.zero_line = true;
    let mut errors = Chart::new(
        "Errors at the measured stations (predicted - measured)",
        &md,
        "error [deg]",
    );
    errors.zero_line = true;
    let mut any_error = false;
    for (k, (case, forecast)) in runs.iter().enumerate() {
        let pred = &forecast.prediction;
        let label = |what: &str| {
            if runs.len() == 1 {
                what.to_string()
            } else {
                format!("{what}: {}", case.name)
            }
        };
        let c = if k == 0 { 0 } else { k + 1 };
        let n = 200usize;
        let pts: Vec<_> = (0..=n)
            .map(|i| {
                pred.path
                    .point_at(pred.from_md_m + (pred.to_md_m - pred.from_md_m) * i as f64 / n as f64)
            })
            .collect();
        inc = inc.with(Series::new(
            &label("predicted"),
            pts.iter()
                .map(|p| (depth_unit.show(p.md_m), p.inc_rad.to_degrees()))
                .collect(),
            Style::Line,
            c,
        ));
        azi = azi.with(Series::new(
            &label("predicted"),
            pts.iter()
                .map(|p| (depth_unit.show(p.md_m), azi_deg(p.azi_rad, tj.azi_ref)))
                .collect(),
            Style::Line,
            c,
        ));
        plan = plan.with(Series::new(
            &label("predicted"),
            pts.iter()
                .map(|p| (depth_unit.show(p.position.y), depth_unit.show(p.position.x)))
                .collect(),
            Style::Line,
            c,
        ));
        sec = sec.with(Series::new(
            &label("predicted"),
            pts.iter()
                .map(|p| (depth_unit.show(tj.vs(&p.position)), depth_unit.show(p.position.z)))
                .collect(),
            Style::Line,
            c,
        ));
        if let Some(pr) = &forecast.projection {
            (inc, azi) = assimilated_series(inc, azi, pr, &label, c, tj.azi_ref, units);
        }
        (forces, tilt) = bit_series(forces, tilt, &pred.steps, &label, k, units);
        let errs: Vec<(f64, (f64, f64))> = forecast
            .rows
            .iter()
            .filter(|r| r.md_m > pred.from_md_m + 1e-6)
            .filter_map(|r| r.errors().map(|e| (r.md_m, e)))
            .collect();
        any_error |= !errs.is_empty();
        errors = errors
            .with(Series::new(
                &label("inclination error"),
                errs.iter()
                    .map(|(m, e)| (depth_unit.show(*m), e.0.to_degrees()))
                    .collect(),
                Style::LinePoints,
                2 * k,
            ))
            .with(Series::new(
                &label("azimuth error"),
                errs.iter()
                    .map(|(m, e)| (depth_unit.show(*m), e.1.to_degrees()))
                    .collect(),
                Style::LinePoints,
                2 * k + 1,
            ));
    }
    trajectory_figures(
        page,
        [&inc, &azi, &plan, &sec],
        "predicted (line) and measured survey stations (points)",
        "the start",
    )?;
    page.heading("Bit");
    page.figure("bit-forces", &render(&forces)?, "bit side forces at each solved step");
    page.figure(
        "bit-tilt",
        &render(&tilt)?,
        "bit tilt against the hole axis at each solved step",
    );
    errors_figure(page, errors, any_error, (from, to), units)
}

/// The assimilated inclination and azimuth with their one-standard-deviation bounds added to
/// the `inc` and `azi` charts (colour `c`, azimuths kept continuous near `azi_ref`).
fn assimilated_series(
    inc: Chart,
    azi: Chart,
    p: &Projection,
    label: &dyn Fn(&str) -> String,
    c: usize,
    azi_ref: f64,
    units: UnitSystem,
) -> (Chart, Chart) {
    let depth_unit = units.depth();
    let md = |r: &ProjectedRow| depth_unit.show(r.md_m);
    let line = |f: &dyn Fn(&ProjectedRow) -> f64| p.rows.iter().map(|r| (md(r), f(r))).collect::<Vec<_>>();
    let deg = |x: f64| x.to_degrees();
    let inc = inc
        .with(Series::new(
            &label("assimilated"),
            line(&|r| deg(r.direction.inc_rad)),
            Style::Line,
            3,
        ))
        .with(Series::new(
            &label("assimilated + 1 sd"),
            line(&|r| deg(r.direction.inc_rad + r.inc_sd_rad)),
            Style::Thin,
            c,
        ))
        .with(Series::new(
            &label("assimilated - 1 sd"),
            line(&|r| deg(r.direction.inc_rad - r.inc_sd_rad)),
            Style::Thin,
            c,
        ));
    let a = |r: &ProjectedRow| azi_deg(r.direction.azi_rad, azi_ref);
    let azi = azi
        .with(Series::new(&label("assimilated"), line(&|r| a(r)), Style::Line, 3))
        .with(Series::new(
            &label("assimilated + 1 sd"),
            line(&|r| a(r) + deg(r.azi_sd_rad)),
            Style::Thin,
            c,
        ))
        .with(Series::new(
            &label("assimilated - 1 sd"),
            line(&|r| a(r) - deg(r.azi_sd_rad)),
            Style::Thin,
            c,
        ));
    (inc, azi)
}

/// The bit's build and walk forces and its tilts at each solved step added to `forces` and
/// `tilt` for the `k`-th case (`label` names a series).
fn bit_series(
    mut forces: Chart,
    mut tilt: Chart,
    steps: &[StepRecord],
    label: &dyn Fn(&str) -> String,
    k: usize,
    units: UnitSystem,
) -> (Chart, Chart) {
    let (depth_unit, force_unit) = (units.depth(), units.force());
    forces = forces
        .with(Series::new(
            &label("build force"),
            steps
                .iter()
                .map(|s| (depth_unit.show(s.md_m), force_unit.show(s.bit.build_force_n)))
                .collect(),
            Style::LinePoints,
            2 * k,
        ))
        .with(Series::new(
            &label("walk force"),
            steps
                .iter()
                .map(|s| (depth_unit.show(s.md_m), force_unit.show(s.bit.walk_force_n)))
                .collect(),
            Style::LinePoints,
            2 * k + 1,
        ));
    tilt = tilt
        .with(Series::new(
            &label("tilt inclination"),
            steps
                .iter()
                .map(|s| (depth_unit.show(s.md_m), s.bit.tilt_inc_rad.to_degrees()))
                .collect(),
            Style::LinePoints,
            2 * k,
        ))
        .with(Series::new(
            &label("tilt azimuth"),
            steps
                .iter()
                .map(|s| (depth_unit.show(s.md_m), s.bit.tilt_azi_rad.to_degrees()))
                .collect(),
            Style::LinePoints,
            2 * k + 1,
        ));
    (forces, tilt)
}

/// The "Errors" section: the `errors` chart, or when no case had a measured station in the
/// interval `(from, to)` (m), an empty chart saying so.
fn errors_figure(
    page: &mut Page,
    errors: Chart,
    any_error: bool,
    (from, to): (f64, f64),
    units: UnitSystem,
) -> Result<(), String> {
    let depth_unit = units.depth();
    let md = format!("MD [{}]", depth_unit.label);
    page.heading("Errors");
    if any_error {
        page.figure(
            "errors",
            &render(&errors)?,
            "predicted minus measured at the survey stations drilled ahead",
        );
    } else {
        // keep the figure (tests and readers expect it), with the zero line only
        let mut empty = Chart::new(
            "Errors: no measured stations in the predicted interval",
            &md,
            "error [deg]",
        )
        .with(Series::new(
            "no measured stations",
            vec![(depth_unit.show(from), 0.0), (depth_unit.show(to), 0.0)],
            Style::Thin,
            7,
        ));
        empty.zero_line = true;
        page.figure(
            "errors",
            &render(&empty)?,
            "a pre-drill prediction has nothing to compare with",
        );
    }
    Ok(())
}

/// The backanalyze report's HTML text (with a calibration, where it ends is marked).
pub fn backanalyze_report(case: &Case, back: &Backanalysis, units: UnitSystem) -> Result<String, String> {
    let results = &back.results;
    let f = results.first().ok_or("no interval to report")?;
    let mut page = Page::new(&format!("drillpath backanalyze: {}", case.name));
    backanalyze_key_results(&mut page, back, units);
    interval_figures(&mut page, case, results, units)?;
    direction_error_figure(&mut page, back, units)?;
    interval_table(&mut page, results, units);
    echo_inputs(&mut page, case, f.interval.from_md_m, units)?;
    let html = page.finish();
    check_finite_text(&html)?;
    Ok(html)
}

/// "100 m" or "100 ft": the length the errors are given per in `units`.
fn hundred(units: UnitSystem) -> &'static str {
    match units {
        UnitSystem::Si => "100 m",
        UnitSystem::Oilfield => "100 ft",
    }
}

/// The direction error per 100 m at each interval's end of the model and of every reference
/// (and, assimilating, of the plain model and the frozen assimilation), on one chart.
fn direction_error_figure(page: &mut Page, back: &Backanalysis, units: UnitSystem) -> Result<(), String> {
    let depth_unit = units.depth();
    let md = format!("MD [{}]", depth_unit.label);
    let x = |k: usize| depth_unit.show(back.results[k].interval.to_md_m);
    let error_unit = units.per_100();
    let per100 = |d: &Direction, e: &EndDirections| error_unit.show(d.angle_to(&e.measured) / e.length_m);
    let series = |name: &str, pick: &dyn Fn(&EndDirections) -> Option<Direction>, style: Style, colour: usize| {
        let pts: Vec<(f64, f64)> = back
            .ends
            .iter()
            .enumerate()
            .filter_map(|(k, e)| pick(e).map(|d| (x(k), per100(&d, e))))
            .collect();
        (!pts.is_empty()).then(|| Series::new(name, pts, style, colour))
    };
    let mut chart = Chart::new(
        &format!("Direction error at each interval's end, per {}", hundred(units)),
        &md,
        &format!("error [{}]", error_unit.label),
    );
    let mut all = vec![series("model", &|e| Some(e.model), Style::LinePoints, 0)];
    for (k, r) in Reference::all().into_iter().enumerate() {
        all.push(series(&r.name(), &move |e| Some(e.references[k]), Style::Thin, k + 1));
    }
    all.push(series("plain model", &|e| e.plain, Style::Points, 6));
    all.push(series("frozen assimilation", &|e| e.frozen, Style::Points, 7));
    for s in all.into_iter().flatten() {
        chart = chart.with(s);
    }
    page.figure(
        "direction-errors",
        &render(&chart)?,
        "angle between the predicted and the measured direction at each interval's end, divided by the interval length: the model against holding the direction, extrapolating the build and turn rates of the last 30, 60 and 90 m, and the statistic",
    );
    Ok(())
}

/// The key results of a backanalyze report: intervals, range, errors per 100 m, calibration.
fn backanalyze_key_results(page: &mut Page, back: &Backanalysis, units: UnitSystem) {
    let (results, stats) = (&back.results, &back.results_stats);
    let split_md_m = back.calibration.as_ref().map(|c| c.split_md_m);
    let (depth_unit, e) = (units.depth(), units.per_100());
    let per = hundred(units);
    let (f, l) = (&results[0], &results[results.len() - 1]);
    page.heading("Key results");
    let mut kv = vec![
        ("intervals".to_string(), results.len().to_string()),
        (
            "range".into(),
            format!(
                "{} - {}",
                depth_unit.fmt(f.interval.from_md_m, 1),
                depth_unit.fmt(l.interval.to_md_m, 1)
            ),
        ),
        (
            format!("mean |inclination error| per {per}"),
            e.fmt(stats.inc_mean_abs_per_100m_rad / 100.0, 3),
        ),
        (
            format!("mean |azimuth error| per {per}"),
            e.fmt(stats.azi_mean_abs_per_100m_rad / 100.0, 3),
        ),
        (
            format!("RMS error per {per}, inclination / azimuth"),
            format!(
                "{} / {}",
                e.fmt(stats.inc_rms_per_100m_rad / 100.0, 3),
                e.fmt(stats.azi_rms_per_100m_rad / 100.0, 3)
            ),
        ),
    ];
    if let Some(s) = split_md_m {
        kv.push((
            "calibration".into(),
            format!("fitted on the intervals above {}, scored below", depth_unit.fmt(s, 1)),
        ));
    }
    page.key_values(&kv);
}

/// The figures of a backanalyze report: trajectory at the interval ends, bit forces and tilt at
/// their starts, errors per 100 m.
fn interval_figures(page: &mut Page, case: &Case, results: &[IntervalResult], units: UnitSystem) -> Result<(), String> {
    let (depth_unit, force_unit) = (units.depth(), units.force());
    let (f, l) = (&results[0], &results[results.len() - 1]);
    let meas = measured(&case.well.path, f.interval.from_md_m, l.interval.to_md_m);
    let azi_ref = f.interval.measured.1;
    let tj = Trajectories {
        units,
        section_azi: case.well.path.point_at(l.interval.to_md_m).azi_rad,
        azi_ref,
        measured: &meas,
    };
    let [mut inc, mut azi, mut plan, mut sec] = tj.charts();
    let end = |r: &IntervalResult| depth_unit.show(r.interval.to_md_m);
    inc = inc.with(Series::new(
        "predicted (interval ends)",
        results.iter().map(|r| (end(r), r.inc_rad.to_degrees())).collect(),
        Style::Points,
        1,
    ));
    azi = azi.with(Series::new(
        "predicted (interval ends)",
        results.iter().map(|r| (end(r), azi_deg(r.azi_rad, azi_ref))).collect(),
        Style::Points,
        1,
    ));
    plan = plan.with(Series::new(
        "predicted (interval ends)",
        results
            .iter()
            .map(|r| (depth_unit.show(r.position.y), depth_unit.show(r.position.x)))
            .collect(),
        Style::Points,
        1,
    ));
    sec = sec.with(Series::new(
        "predicted (interval ends)",
        results
            .iter()
            .map(|r| (depth_unit.show(tj.vs(&r.position)), depth_unit.show(r.position.z)))
            .collect(),
        Style::Points,
        1,
    ));
    let md = format!("MD [{}]", depth_unit.label);
    let start = |r: &IntervalResult| depth_unit.show(r.interval.from_md_m);
    let mut forces = Chart::new(
        "Bit side forces at the interval starts",
        &md,
        &format!("force [{}]", force_unit.label),
    )
    .with(Series::new(
        "build force",
        results
            .iter()
            .map(|r| (start(r), force_unit.show(r.bit_start.build_force_n)))
            .collect(),
        Style::LinePoints,
        0,
    ))
    .with(Series::new(
        "walk force",
        results
            .iter()
            .map(|r| (start(r), force_unit.show(r.bit_start.walk_force_n)))
            .collect(),
        Style::LinePoints,
        1,
    ));
    forces.zero_line = true;
    let mut tilt = Chart::new("Bit tilt at the interval starts", &md, "tilt [deg]")
        .with(Series::new(
            "tilt inclination",
            results
                .iter()
                .map(|r| (start(r), r.bit_start.tilt_inc_rad.to_degrees()))
                .collect(),
            Style::LinePoints,
            0,
        ))
        .with(Series::new(
            "tilt azimuth",
            results
                .iter()
                .map(|r| (start(r), r.bit_start.tilt_azi_rad.to_degrees()))
                .collect(),
            Style::LinePoints,
            1,
        ));
    tilt.zero_line = true;
    let e = units.per_100();
    let mut errors = Chart::new(
        &format!("Per-interval errors (predicted - measured) per {}", hundred(units)),
        &md,
        &format!("error [{}]", e.label),
    )
    .with(Series::new(
        "inclination error",
        results
            .iter()
            .map(|r| (end(r), e.show(r.inc_err_per_100m_rad() / 100.0)))
            .collect(),
        Style::LinePoints,
        0,
    ))
    .with(Series::new(
        "azimuth error",
        results
            .iter()
            .map(|r| (end(r), e.show(r.azi_err_per_100m_rad() / 100.0)))
            .collect(),
        Style::LinePoints,
        1,
    ));
    errors.zero_line = true;
    trajectory_figures(
        page,
        [&inc, &azi, &plan, &sec],
        "measured stations and the predicted value at each interval's end",
        "the last station",
    )?;
    page.heading("Bit");
    page.figure(
        "bit-forces",
        &render(&forces)?,
        "bit side forces on the measured hole at each interval's start",
    );
    page.figure("bit-tilt", &render(&tilt)?, "bit tilt at each interval's start");
    page.heading("Errors");
    page.figure(
        "errors",
        &render(&errors)?,
        "error at each interval's end divided by its length",
    );
    Ok(())
}

/// One row per interval: measured and predicted end direction, error, bit forces at the start.
fn interval_table(page: &mut Page, results: &[IntervalResult], units: UnitSystem) {
    let (depth_unit, force_unit) = (units.depth(), units.force());
    let rows: Vec<Vec<String>> = results
        .iter()
        .map(|r| {
            vec![
                format!(
                    "{} - {}",
                    depth_unit.fmt(r.interval.from_md_m, 1),
                    depth_unit.fmt(r.interval.to_md_m, 1)
                ),
                format!(
                    "{:.3} / {:.3}",
                    r.interval.measured.0.to_degrees(),
                    r.interval.measured.1.to_degrees()
                ),
                format!(
                    "{:.3} / {:.3}",
                    r.inc_rad.to_degrees(),
                    crate::geometry::survey::degrees_in_turn(r.azi_rad.to_degrees(), 3)
                ),
                format!(
                    "{:+.3} / {:+.3}",
                    r.inc_err_rad().to_degrees(),
                    r.azi_err_rad().to_degrees()
                ),
                force_unit.fmt(r.bit_start.build_force_n, 3),
                force_unit.fmt(r.bit_start.walk_force_n, 3),
            ]
        })
        .collect();
    page.table(
        &[
            "interval".into(),
            "measured inc / azi [deg]".into(),
            "predicted inc / azi [deg]".into(),
            "error inc / azi [deg]".into(),
            "build force".into(),
            "walk force".into(),
        ],
        &rows,
    );
}

/// The HTML report of a prediction (one or several cases), in `units`.
pub fn predict_html(runs: &[(&Case, &Forecast)], units: UnitSystem) -> anyhow::Result<String> {
    predict_report(runs, units).map_err(|e| anyhow::anyhow!("internal error in the report: {e}"))
}

/// The HTML report of a back-analysis, in `units`.
pub fn backanalyze_html(case: &Case, back: &Backanalysis, units: UnitSystem) -> anyhow::Result<String> {
    backanalyze_report(case, back, units).map_err(|e| anyhow::anyhow!("internal error in the report: {e}"))
}
