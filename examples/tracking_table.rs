//! The tracking table of docs/tracking.md: on the real wells and seed-daqing, at 30 m and 90 m
//! intervals, the mean direction error per 100 m of the plain model, the assimilated model,
//! the frozen assimilation, the statistic and every naive projection, with the skill, the
//! physics share, the coverage of the one-standard-deviation bounds and the cost.
//!
//! Run: `cargo run --release --example tracking_table -- docs/tracking` (a few minutes). Writes
//! `table.csv` and `table.md` into the folder. The same settings on every well: the case's
//! `[tracking]` table is not set in any of them, so the defaults apply.
//! `WELLS=forge-16b,volve-f5` and `HORIZONS=90` restrict the run (a study, not the table).

use drillpath::case::fidelity::{choose, Fidelity, Purpose};
use drillpath::io::case_toml::{load_case, CaseOverrides};
use drillpath::predict::backanalysis::{plan, run, Backanalysis, BackanalysisRequest};
use drillpath::predict::forecast::settings_at_level;
use drillpath::predict::tracking::references::Reference;
use std::fmt::Write as _;
use std::path::Path;
use std::time::Instant;

const WELLS: [&str; 5] = ["forge-16a", "forge-16b", "volve-f10", "volve-f5", "seed-daqing"];

fn wells() -> Vec<&'static str> {
    match std::env::var("WELLS") {
        Ok(w) => WELLS
            .iter()
            .copied()
            .filter(|x| w.split(',').any(|y| y == *x))
            .collect(),
        Err(_) => WELLS.to_vec(),
    }
}
const HORIZONS_M: [f64; 2] = [30.0, 90.0];

/// The horizons, or those of `HORIZONS` (e.g. `HORIZONS=90`).
fn horizons() -> Vec<f64> {
    match std::env::var("HORIZONS") {
        Ok(h) => h.split(',').map(|x| x.parse().expect("a horizon, m")).collect(),
        Err(_) => HORIZONS_M.to_vec(),
    }
}

struct Row {
    well: &'static str,
    horizon: f64,
    intervals: usize,
    plain: f64,
    assimilated: f64,
    frozen: f64,
    statistic: f64,
    naive: [f64; 4],
    best: String,
    skill: f64,
    physics: f64,
    coverage: [f64; 3],
    cost: f64,
}

fn back(well: &str, horizon: f64, assimilate: bool) -> (Backanalysis, f64) {
    let path = Path::new("wells").join(well).join("case.toml");
    let mut case = load_case(&path, &CaseOverrides::default()).expect("example case");
    // study overrides of the tracking defaults (the same on every well), e.g.
    // TRACKING="forgetting_length=90,correlation_length=60,tendency_sd=1,fluctuation_sd=1"
    // (lengths m, standard deviations deg/30 m)
    if let Ok(o) = std::env::var("TRACKING") {
        for kv in o.split(',').filter(|s| !s.is_empty()) {
            let (k, v) = kv.split_once('=').expect("key=value");
            let v: f64 = v.parse().expect("a number");
            let t = &mut case.tracking;
            match k {
                "forgetting_length" => t.forgetting_length_m = v,
                "correlation_length" => t.correlation_length_m = v,
                "tendency_sd" => t.tendency_sd_rad_per_m = v.to_radians() / 30.0,
                "fluctuation_sd" => t.fluctuation_sd_rad_per_m = v.to_radians() / 30.0,
                "window" => t.window_m = v.min(case.well.path.md_end() - case.well.path.md_start()),
                "interval" => t.interval_m = v,
                _ => panic!("unknown key {k}"),
            }
        }
    }
    let choice = choose(Fidelity::Auto, Purpose::Predict);
    let settings = settings_at_level(&case, choice.level, None, None).expect("a stiff level");
    let req = BackanalysisRequest {
        from_md_m: None,
        to_md_m: None,
        horizon_m: horizon,
        calibration: None,
        assimilate,
    };
    let p = plan(&case, &req).expect("plan");
    let t0 = Instant::now();
    let b = run(std::slice::from_ref(&case), &p, &[settings], &mut |_| {}).expect("back-analysis");
    (b, t0.elapsed().as_secs_f64())
}

fn row(well: &'static str, horizon: f64) -> Row {
    let t_plain = if std::env::var("NO_COST").is_ok() {
        1.0
    } else {
        back(well, horizon, false).1
    };
    let (b, t_assim) = back(well, horizon, true);
    let s = b.skill.as_ref().expect("skill");
    let d = |e: &drillpath::predict::tracking::skill::ErrorSummary| e.dir_err_per_100m_rad.to_degrees();
    let r = |q: Reference| d(s.reference(q).expect("reference"));
    let a = b.assimilation.as_ref().expect("assimilation");
    Row {
        well,
        horizon,
        intervals: b.results.len(),
        plain: d(s.plain.as_ref().expect("plain")),
        assimilated: d(&s.model),
        frozen: d(s.frozen.as_ref().expect("frozen")),
        statistic: r(Reference::Statistic),
        naive: [
            r(Reference::Hold),
            r(Reference::Rates { window_m: 30.0 }),
            r(Reference::Rates { window_m: 60.0 }),
            r(Reference::Rates { window_m: 90.0 }),
        ],
        best: s.best_naive.name(),
        skill: s.skill.unwrap_or(f64::NAN),
        physics: s.physics_share.unwrap_or(f64::NAN),
        coverage: a.coverage(),
        cost: t_assim / t_plain,
    }
}

fn main() {
    let dir = std::env::args().nth(1).unwrap_or_else(|| "docs/tracking".into());
    std::fs::create_dir_all(&dir).expect("output folder");
    let mut rows = Vec::new();
    for h in horizons() {
        for w in wells() {
            let r = row(w, h);
            eprintln!(
                "{:<12} {:>3.0} m: assim {:.3} plain {:.3} frozen {:.3} stat {:.3} best {} {:.3}; skill {:+.3} physics {:+.3}; coverage {:.2}; cost x{:.2}",
                r.well,
                r.horizon,
                r.assimilated,
                r.plain,
                r.frozen,
                r.statistic,
                r.best,
                r.naive.iter().copied().fold(f64::INFINITY, f64::min),
                r.skill,
                r.physics,
                r.coverage[2],
                r.cost
            );
            rows.push(r);
        }
    }
    let mut csv = String::from("well,interval_m,intervals,plain,assimilated,frozen,statistic,hold,rates_30m,rates_60m,rates_90m,best_naive,assimilated_over_best_naive,assimilated_over_statistic,skill,physics_share,coverage_inc,coverage_azi,coverage_both,cost_ratio\n");
    let mut md = String::from("| well | interval | n | plain | assimilated | frozen | statistic | hold | rates 30 / 60 / 90 m | assimilated / best naive | assimilated / statistic | physics share | within 1 sd | cost |\n|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
    for r in &rows {
        let best = r.naive.iter().copied().fold(f64::INFINITY, f64::min);
        writeln!(
            csv,
            "{},{},{},{:.4},{:.4},{:.4},{:.4},{:.4},{:.4},{:.4},{:.4},{},{:.4},{:.4},{:.4},{:.4},{:.3},{:.3},{:.3},{:.2}",
            r.well, r.horizon, r.intervals, r.plain, r.assimilated, r.frozen, r.statistic, r.naive[0], r.naive[1],
            r.naive[2], r.naive[3], r.best, r.assimilated / best, r.assimilated / r.statistic, r.skill, r.physics,
            r.coverage[0], r.coverage[1], r.coverage[2], r.cost
        )
        .unwrap();
        writeln!(
            md,
            "| {} | {:.0} m | {} | {:.2} | **{:.2}** | {:.2} | {:.2} | {:.2} | {:.2} / {:.2} / {:.2} | {:.2} ({}) | {:.2} | {:+.2} | {:.0}% | x{:.2} |",
            r.well, r.horizon, r.intervals, r.plain, r.assimilated, r.frozen, r.statistic, r.naive[0], r.naive[1],
            r.naive[2], r.naive[3], r.assimilated / best, r.best, r.assimilated / r.statistic, r.physics,
            100.0 * r.coverage[2], r.cost
        )
        .unwrap();
    }
    for h in horizons() {
        let sel: Vec<&Row> = rows
            .iter()
            .filter(|r| r.horizon == h && r.well != "seed-daqing")
            .collect();
        let mean = |f: &dyn Fn(&Row) -> f64| sel.iter().map(|r| f(r)).sum::<f64>() / sel.len() as f64;
        let best = |r: &Row| r.naive.iter().copied().fold(f64::INFINITY, f64::min);
        writeln!(
            md,
            "| **mean of the four real wells** | {:.0} m | | | | | | | | mean ratio {:.3}, worst {:.3} | mean ratio {:.3} | {:+.2} | {:.0}% | |",
            h,
            mean(&|r| r.assimilated / best(r)),
            sel.iter().map(|r| r.assimilated / best(r)).fold(0.0, f64::max),
            mean(&|r| r.assimilated / r.statistic),
            mean(&|r| r.physics),
            100.0 * mean(&|r| r.coverage[2]),
        )
        .unwrap();
    }
    std::fs::write(Path::new(&dir).join("table.csv"), csv).expect("write table.csv");
    std::fs::write(Path::new(&dir).join("table.md"), &md).expect("write table.md");
    print!("{md}");
}
