//! Why a stiff solve may not have converged: what the soft string (docs/theory.md 10.5, cheap and
//! always convergent) says about the same operation. Two physical causes are recognised:
//!
//! - **lock-up**: the soft-string hook load is negative, i.e. the top would have to be pushed
//!   down to put the requested WOB on the bit (typical when sliding a long lateral); the
//!   compressed pipe above then buckles, and the stiff model has no static state near the start;
//! - **helical buckling**: compression above the helical onset ([`crate::models::buckling`], with the
//!   hole curvature) over part of the string; the stiff model must find a post-buckled shape.
//!
//! Neither proves the stiff solve impossible, but both tell the user the case is at the edge
//! of what the string can do, not only of what the solver can do.

use crate::case::{Case, Mode};
use crate::models::buckling::{soft_marks, zones, BuckleState};
use crate::models::helical_drag::helical_lock_up;
use crate::models::levels::FemPart;
use crate::models::lock_up_depth::{hook_load_at_wob_n, lock_up_depths, Drag};
use crate::models::softstring;

/// One-sentence hints on `case` for a non-converged stiff solve (empty when the soft string
/// shows neither lock-up nor helical buckling). Forces in kN, depths in m.
pub fn nonconvergence_hints(case: &Case) -> Vec<String> {
    if case.string.components.is_empty() {
        return Vec::new();
    }
    let soft = softstring::from_case(case, softstring::segment_length_m(&case.solver));
    let mut hints = Vec::new();
    let wob = -soft.points[0].tension_n;
    if soft.hook_load_n < 0.0 && case.operation.hook_load_n.is_none() {
        hints.push(format!(
            "soft-string estimate: hook load {:.0} kN, i.e. the top would have to be pushed down to put {:.0} kN on the bit while {} (lock-up): less WOB or friction, rotation, or heavier pipe above the compressed part",
            soft.hook_load_n / 1e3,
            wob / 1e3,
            case.operation.mode.name()
        ));
    }
    let helical = helical_lock_up(case);
    if let Some(l) = &helical {
        hints.push(format!(
            "helical lock-up: the soft string with the helix's drag (Mitchell's r F^2/(4 EI) added to the wall force beyond the helical onset) has a hook load of {:.0} kN at {:.0} kN WOB while {}: it delivers at most about {:.0} kN WOB; the whole string's drag lies at or above that soft string's in the buckled sliding cases measured (docs/performance.md), so the WOB asked for is most likely beyond the string's reach",
            l.hook_load_n / 1e3,
            l.wob_n / 1e3,
            case.operation.mode.name(),
            l.max_wob_n / 1e3
        ));
    }
    if helical.is_none() && soft.hook_load_n >= 0.0 {
        hints.extend(near_helical_lock_up_hint(case));
    }
    let locked = soft.hook_load_n < 0.0 || helical.is_some();
    if locked && case.operation.hook_load_n.is_none() {
        hints.extend(lock_up_depth_hint(case, wob));
    }
    let m = soft_marks(case, &soft, 0);
    let helical: Vec<_> = zones(&m)
        .into_iter()
        .filter(|z| z.state == BuckleState::Helical)
        .collect();
    if !helical.is_empty() {
        let list: Vec<String> = helical
            .iter()
            .take(3)
            .map(|z| format!("{:.0}-{:.0} m", z.top_md_m, z.bottom_md_m))
            .collect();
        let compression = m.iter().map(|k| k.compression_n).fold(0.0, f64::max);
        hints.push(format!(
            "soft-string estimate: helically buckled at MD {}{} (max compression {:.0} kN): the stiff model has to find a post-buckled shape there",
            list.join(", "),
            if helical.len() > 3 { ", ..." } else { "" },
            compression / 1e3
        ));
    }
    hints
}

/// Hook load of the soft string with the helix's drag (N) below which a string that it does not
/// lock up is named near its helical lock-up: where both were solved, the whole string's hook
/// load lay 1.4-7.0 kN below that soft string's sliding on bottom (15 of 16 grid cases) and
/// 4.8-7.8 kN below it running in (docs/theory.md 7.7).
pub const NEAR_HELICAL_LOCK_UP_N: f64 = 10e3;

/// The hint on `case` (on bottom with a WOB, or running in) whose soft string with the helix's
/// drag keeps a hook load not below zero but below [`NEAR_HELICAL_LOCK_UP_N`], and below the
/// plain soft string's (a helix there): the whole string is most likely locked up.
fn near_helical_lock_up_hint(case: &Case) -> Option<String> {
    let op = &case.operation;
    let wob_n = match op.mode {
        Mode::TripIn => 0.0,
        _ if op.mode.on_bottom() => op.wob_n,
        _ => return None,
    };
    if op.hook_load_n.is_some() {
        return None;
    }
    let helical = hook_load_at_wob_n(case, wob_n, Drag::WithHelix);
    let plain = hook_load_at_wob_n(case, wob_n, Drag::Plain);
    if !(0.0..NEAR_HELICAL_LOCK_UP_N).contains(&helical) || helical >= plain {
        return None;
    }
    Some(format!(
        "near a helical lock-up: the soft string with the helix's drag (Mitchell's r F^2/(4 EI)) keeps a hook load of only {:.1} kN while {} (the plain soft string {:.0} kN); where both were solved the whole string's hook load lay 1.4-8 kN below that soft string's (docs/theory.md 7.7), so the whole string most likely cannot be {} with the surface holding it",
        helical / 1e3,
        op.mode.name(),
        plain / 1e3,
        if op.mode == Mode::TripIn { "run in to this depth" } else { "put on bottom at this WOB" }
    ))
}

/// The hint naming the lock-up depths of `case` at the WOB `wob_n` (N) and at zero WOB
/// ([`lock_up_depths`], by the model of [`Drag::of`]); None when that soft string is not locked
/// up at the case's bit depth.
fn lock_up_depth_hint(case: &Case, wob_n: f64) -> Option<String> {
    lock_up_depths(case, wob_n, Drag::of(case, wob_n)).sentence(wob_n)
}

/// "stopped at the time limit of one solve, T s (`[solver] time_limit`)", for the messages of
/// a solve that ran out of time.
pub fn time_limit_phrase(ctl: &crate::models::fem::solve::SolveControls) -> String {
    format!(
        "stopped at the time limit of one solve, {} s (`[solver] time_limit`)",
        ctl.time_limit_s
    )
}

/// Where a stiff solve that did not converge stopped, in one phrase: "in N iterations (the
/// limit, `[solver] max_iterations`)" or "at the time limit of T s ...".
pub fn stop_phrase(
    stats: &crate::models::fem::solve::SolveStats,
    ctl: &crate::models::fem::solve::SolveControls,
) -> String {
    let n = stats.iterations;
    let its = if n == 1 { "iteration" } else { "iterations" };
    let wob_path = stats.wob_continuation_n.map(|(reached, target)| {
        format!(
            "a WOB continuation from {:.0}% of the WOB that reached {:.1} of {:.1} kN",
            100.0 * crate::models::fem::solve::continuation::START_FRACTION,
            reached / 1e3,
            target / 1e3
        )
    });
    let friction_path = stats.friction_continuation.map(|share| {
        format!(
            "a friction continuation from zero that reached {:.0}% of the wall friction",
            100.0 * share
        )
    });
    let buckled = (stats.buckled_start == Some(false))
        .then(|| "a re-solve from the buckled shape (damped; a helix along the wall)".to_string());
    let climb = stats.buckled_climb_n.map(|(reached, target)| {
        format!(
            "a WOB climb from the buckled shape that reached {:.1} of {:.1} kN",
            reached / 1e3,
            target / 1e3
        )
    });
    let others = stats.unanswered_stages.iter().map(|s| s.to_string());
    let paths: Vec<String> = wob_path
        .into_iter()
        .chain(friction_path)
        .chain(buckled)
        .chain(others)
        .chain(climb)
        .collect();
    let path = if paths.is_empty() {
        format!(" (the limit, `[solver] max_iterations` = {})", ctl.max_iterations)
    } else {
        format!(
            ", with {} (each stage limited by `[solver] max_iterations` = {})",
            paths.join(", then "),
            ctl.max_iterations
        )
    };
    if stats.timed_out {
        format!("in {n} {its}{path}: it {}", time_limit_phrase(ctl))
    } else {
        format!("in {n} {its}{path}")
    }
}

/// The case's geometry where the whole-string solve has known limits (docs/guide.md, Limits):
/// a hole beyond 90 deg over the string, a dogleg over 30 deg/30 m while rotating.
pub fn known_limit_hints(case: &Case) -> Vec<String> {
    let path = &case.well.path;
    let bit = case.operation.bit_md_m;
    let mut hints = Vec::new();
    let steepest = path
        .stations()
        .iter()
        .filter(|s| s.md_m <= bit + 1e-6)
        .max_by(|a, b| a.inc_rad.total_cmp(&b.inc_rad));
    if let Some(s) = steepest.filter(|s| s.inc_rad > 91f64.to_radians()) {
        hints.push(format!(
            "the hole reaches {:.1} deg inclination at {:.0} m MD: a hole beyond 90 deg is a known limit of the stiff solve (docs/guide.md, Limits)",
            s.inc_rad.to_degrees(),
            s.md_m
        ));
    }
    let (dls, at) = path.max_dls();
    if case.operation.rpm > 0.0 && dls * 30.0 > 30f64.to_radians() {
        hints.push(format!(
            "a dogleg of {:.1} deg/30 m at {at:.0} m MD while rotating: above 30 deg/30 m is a known limit of the stiff solve (docs/guide.md, Limits)",
            dls.to_degrees() * 30.0
        ));
    }
    hints
}

/// The last state of a stiff solve that did not converge, in one phrase: its last relative
/// residuals, the largest penetration relative to the clearance, and the MDs of the contacts
/// that kept switching (where the scheme tracks them: the paper's).
pub fn solve_state_summary(part: &FemPart) -> String {
    let stats = &part.stats;
    let hist = &stats.residual_history;
    let tail: Vec<String> = hist.iter().rev().take(5).rev().map(|r| format!("{r:.2e}")).collect();
    let chatter: Vec<String> = stats
        .chattering_nodes
        .iter()
        .take(10)
        .map(|&i| format!("{:.1} m", part.model.md_ref[i]))
        .collect();
    let switching = if chatter.is_empty() {
        String::new()
    } else {
        format!("; contacts switching at MD {}", chatter.join(", "))
    };
    format!(
        "last relative residuals {}; max penetration {:.2e} of clearance{switching}",
        tail.join(", "),
        stats.max_penetration,
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::io::case_toml::{load_case, CaseOverrides};

    fn case(wob_kn: f64, mode: &str) -> Case {
        let dir = tempfile::tempdir().unwrap();
        std::fs::write(
            dir.path().join("s.csv"),
            "md_m,inc_deg,azi_deg\n0,0,0\n300,0,0\n750,90,0\n1050,90,0\n",
        )
        .unwrap();
        let toml = format!(
            r#"[well]
survey = "s.csv"
hole = [{{ to_md = "1050 m", diameter = "8.5 in" }}]
[mud]
density = "1.2 sg"
[operation]
mode = "{mode}"
bit_md = "1050 m"
wob = "{wob_kn} kN"
rpm = 60
friction = 0.25
[[string]]
type = "pipe"
od = "5 in"
id = "4.276 in"
weight = "29 kg/m"
"#
        );
        std::fs::write(dir.path().join("c.toml"), toml).unwrap();
        load_case(&dir.path().join("c.toml"), &CaseOverrides::default()).unwrap()
    }

    /// Reference: the soft string of the same case (docs/theory.md 10.5). 300 m vertical, a 90 deg
    /// build of 450 m and a 300 m lateral of 5 in pipe (w_b = 241 N/m): the hanging weight is
    /// about 300 x 241 + 450 x 241 x 2/pi = 141 kN, so sliding with 20 kN on the bit keeps the
    /// top in tension and below the helical onset (no hint), while 250 kN needs the top pushed
    /// (lock-up) and buckles the pipe helically (both hints), and no bit depth delivers it (more
    /// than the whole string weighs: the lock-up depth's hint says so).
    #[test]
    fn lock_up_and_helical_buckling_are_named() {
        assert!(nonconvergence_hints(&case(20.0, "sliding")).is_empty());
        let h = nonconvergence_hints(&case(250.0, "sliding"));
        assert_eq!(h.len(), 3, "{h:?}");
        assert!(h[0].contains("lock-up") && h[0].contains("sliding"), "{h:?}");
        assert!(
            h[1].contains("at 250 kN WOB no bit depth of the surveyed hole"),
            "{h:?}"
        );
        assert!(h[2].contains("helically buckled"), "{h:?}");
    }

    #[test]
    fn the_stop_phrase_names_each_path_that_ran() {
        use crate::models::fem::solve::{SolveControls, SolveStats};
        let ctl = SolveControls::default();
        let mut stats = SolveStats {
            iterations: 420,
            ..SolveStats::default()
        };
        assert_eq!(
            stop_phrase(&stats, &ctl),
            "in 420 iterations (the limit, `[solver] max_iterations` = 300)"
        );
        stats.wob_continuation_n = Some((50e3, 60e3));
        stats.friction_continuation = Some(0.57);
        assert_eq!(
            stop_phrase(&stats, &ctl),
            "in 420 iterations, with a WOB continuation from 10% of the WOB that reached 50.0 of 60.0 kN, then a friction continuation from zero that reached 57% of the wall friction (each stage limited by `[solver] max_iterations` = 300)"
        );
        stats.buckled_start = Some(false);
        assert!(
            stop_phrase(&stats, &ctl).contains(
                "wall friction, then a re-solve from the buckled shape (damped; a helix along the wall) (each stage"
            ),
            "{}",
            stop_phrase(&stats, &ctl)
        );
    }
}
