//! A study tool for the tracking mixture: runs `backanalyze --assimilate` once per well and
//! interval length and writes every prediction the assimilated bank scored (the warm-up's and
//! the intervals'), as each member made it (see
//! `drillpath::predict::tracking::bank::ScoredPrediction`), with the measured hole's direction
//! behind and at the end of each, so that rules mixing the members can be compared offline in
//! seconds instead of re-running the tracking table (`examples/tracking_mix.py` does, see
//! docs/tracking.md).
//!
//! Run: `cargo run --release --example tracking_members -- target/members` (about 2 minutes).
//! Writes `<well>_<interval>m.json` into the folder. `WELLS` and `HORIZONS` restrict the run as
//! in `tracking_table`. Directions in rad, corrections toward the high side and the right of
//! the prediction they correct.

use drillpath::case::fidelity::{choose, Fidelity, Purpose};
use drillpath::io::case_toml::{load_case, CaseOverrides};
use drillpath::predict::backanalysis::{plan, run, BackanalysisRequest};
use drillpath::predict::forecast::settings_at_level;
use serde_json::json;
use std::path::Path;

const WELLS: [&str; 5] = ["forge-16a", "forge-16b", "volve-f10", "volve-f5", "seed-daqing"];

/// Spacing (m) and count of the directions recorded behind each prediction's start.
const BEHIND_STEP_M: f64 = 10.0;
const BEHIND_COUNT: usize = 31;

fn list(var: &str, all: &[&'static str]) -> Vec<&'static str> {
    match std::env::var(var) {
        Ok(w) => all.iter().copied().filter(|x| w.split(',').any(|y| y == *x)).collect(),
        Err(_) => all.to_vec(),
    }
}

fn main() {
    let dir = std::env::args().nth(1).unwrap_or_else(|| "target/members".into());
    std::fs::create_dir_all(&dir).expect("output folder");
    let horizons: Vec<f64> = match std::env::var("HORIZONS") {
        Ok(h) => h.split(',').map(|x| x.parse().expect("a horizon, m")).collect(),
        Err(_) => vec![30.0, 90.0],
    };
    for h in horizons {
        for well in list("WELLS", &WELLS) {
            let path = Path::new("wells").join(well).join("case.toml");
            let case = load_case(&path, &CaseOverrides::default()).expect("example case");
            let choice = choose(Fidelity::Auto, Purpose::Predict);
            let settings = settings_at_level(&case, choice.level, None, None).expect("a stiff level");
            let req = BackanalysisRequest {
                from_md_m: None,
                to_md_m: None,
                horizon_m: h,
                calibration: None,
                assimilate: true,
            };
            let p = plan(&case, &req).expect("plan");
            let b = run(std::slice::from_ref(&case), &p, &[settings], &mut |_| {}).expect("back-analysis");
            let a = b.assimilation.as_ref().expect("assimilation");
            let wp = &case.well.path;
            let dir_at = |md: f64| {
                let q = wp.point_at(md.clamp(wp.md_start(), wp.md_end()));
                [q.inc_rad, q.azi_rad]
            };
            let m2 = |c: &nalgebra::Matrix2<f64>| [c[(0, 0)], c[(0, 1)], c[(1, 1)]];
            let events: Vec<_> = a
                .filter
                .history()
                .iter()
                .map(|s| {
                    let behind: Vec<[f64; 2]> = (0..BEHIND_COUNT)
                        .map(|k| dir_at(s.from_md_m - BEHIND_STEP_M * k as f64))
                        .collect();
                    json!({
                        "from_md": s.from_md_m,
                        "len": s.len_m,
                        "z": s.z,
                        "end_station": m2(&s.end_station),
                        "filters": s.filters.iter().map(|(t, c)| json!([t, m2(c)])).collect::<Vec<_>>(),
                        "filter_weights": s.filter_weights,
                        "naive": s.naive.iter().map(|(t, c)| json!([t, m2(c)])).collect::<Vec<_>>(),
                        "member_weights": s.member_weights,
                        "behind": behind,
                        "end": dir_at(s.from_md_m + s.len_m),
                    })
                })
                .collect();
            let intervals: Vec<_> = a
                .intervals
                .iter()
                .map(|i| {
                    json!({
                        "from_md": i.plain.interval.from_md_m,
                        "to_md": i.plain.interval.to_md_m,
                        "correction": i.correction_rad,
                        "assimilated": [i.assimilated.inc_rad, i.assimilated.azi_rad],
                        "measured": [i.plain.interval.measured.0, i.plain.interval.measured.1],
                        "inc_sd": i.inc_sd_rad,
                        "azi_sd": i.azi_sd_rad,
                    })
                })
                .collect();
            let sections: Vec<f64> = case.well.hole.sections().iter().map(|s| s.to_md_m).collect();
            let ends: Vec<_> = b
                .ends
                .iter()
                .map(|e| {
                    json!({
                        "len": e.length_m,
                        "measured": [e.measured.inc_rad, e.measured.azi_rad],
                        "model": [e.model.inc_rad, e.model.azi_rad],
                        "references": e.references.iter().map(|r| [r.inc_rad, r.azi_rad]).collect::<Vec<_>>(),
                    })
                })
                .collect();
            let out = json!({
                "well": well,
                "horizon": h,
                "md_start": wp.md_start(),
                "section_ends": sections,
                "events": events,
                "intervals": intervals,
                "ends": ends,
            });
            let file = Path::new(&dir).join(format!("{well}_{h:.0}m.json"));
            std::fs::write(&file, serde_json::to_string(&out).expect("json")).expect("write");
            eprintln!(
                "{well} {h:.0} m: {} scored, {} intervals",
                events.len(),
                intervals.len()
            );
        }
    }
}
