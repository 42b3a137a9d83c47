//! The soft string with the helix's drag (`models::helical_drag`, docs/theory.md 7.6) and the
//! helical lock-up it predicts.
//!
//! References: in a vertical hole the axial balance of a sliding, helically buckled soft string
//! is `dF/ds = -w + k F^2` (`F` the effective compression, `s` upward, `k = f r / (4 EI)`, Mitchell
//! 1986), solved in closed form: `F = a tanh(atanh(F_0 / a) - a k s)` below the lock-up force
//! `a = sqrt(w / k)` and `F = a coth(acoth(F_0 / a) - a k s)` above it (diverging at
//! `s = acoth(F_0 / a) / (a k)`: the helical lock-up); below the helical onset `dF/ds = -w`. And the
//! whole string (the stiff FEM, which forms the helix itself) as the independent reference of the
//! helix's drag in an inclined well.

use drillpath::case::Case;
use drillpath::models::diagnose::nonconvergence_hints;
use drillpath::models::helical_drag::{
    diverged, helical_lock_up, helical_soft_string, lock_up_wob_n, DIVERGED_HOOK_LOAD_N,
};
use drillpath::models::lock_up_depth::{hook_load_at_depth_n, Drag};
use drillpath::models::softstring;

use crate::acceptance_grid::{well_case, GridCase};
use crate::buckling::straight_hole_case;
use crate::common::{load_temp_case, solve_whole};

/// A vertical hole of `length_m` with 5 in pipe (no tool joints) below a short bit, 8.5 in
/// hole, 1.2 sg, sliding with `wob_kn` and wall friction `friction`
/// (`buckling::straight_hole_case` at 0 deg).
fn vertical_case(length_m: f64, wob_kn: f64, friction: f64) -> Case {
    straight_hole_case(0.0, length_m, wob_kn, friction, None)
}

/// The closed-form compression (N) at `s_m` above the bit of the vertical string of
/// [`vertical_case`] (module docs): from `f0_n` at the bit, `w` (N/m) the buoyed weight, `k`
/// (1/(N m)) the helix's drag coefficient, `onset_n` the helical onset; None once locked up.
fn closed_form_compression(f0_n: f64, s_m: f64, w: f64, k: f64, onset_n: f64) -> Option<f64> {
    let a = (w / k).sqrt();
    // length over which the helix holds, and the compression at its top
    let (helix_len, top) = if f0_n <= onset_n {
        (0.0, f0_n)
    } else if f0_n < a {
        let u0 = (f0_n / a).atanh();
        let u1 = (onset_n / a).atanh();
        ((u0 - u1) / (a * k), onset_n)
    } else {
        let u0 = (a / f0_n).atanh();
        let at = u0 - a * k * s_m;
        return (at > 0.0).then(|| a / at.tanh());
    };
    if s_m <= helix_len {
        let u0 = (f0_n / a).atanh();
        return Some(a * (u0 - a * k * s_m).tanh());
    }
    Some(top - w * (s_m - helix_len))
}

/// The helical soft string of a vertical string against the closed form (module docs): with
/// 150 kN on the bit and friction 0.35 (below the lock-up force `a`, about 275 kN) the
/// compression falls along the `tanh` until the helical onset, then by the weight; with 300 kN
/// (above `a`) it grows upward along the `coth`, from the top of the bit (a solid bar that does
/// not buckle). Tolerance: 0.01% of the larger of the local compression and the one at the bit's
/// top (the soft string's trapezoidal 1 m steps against the exact solution; with explicit steps
/// the error reached 0.5%).
#[test]
fn vertical_helix_drag_follows_mitchells_closed_form() {
    for (wob_kn, length_m) in [(150.0, 1200.0), (300.0, 1000.0)] {
        let case = vertical_case(length_m, wob_kn, 0.35);
        let pipe = case.string.component_at(10.0);
        let ei = pipe.ei_nm2();
        let w = pipe.buoyed_weight_n_per_m(case.mud.density_kg_m3);
        let r = (8.5 * 0.0254 - pipe.body_od_m) / 2.0;
        let k = 0.35 * r / (4.0 * ei);
        let onset = 5.55 * (ei * w * w).cbrt();
        let soft = helical_soft_string(&case);
        let plain = softstring::from_case(&case, softstring::segment_length_m(&case.solver));
        // from the top of the 0.3 m bit (a solid bar that does not buckle)
        let top = soft.points.iter().find(|p| p.md_m < length_m - 0.3 + 1e-9).unwrap();
        let f0 = -top.tension_n;
        let mut checked = 0;
        for p in soft.points.iter().filter(|p| p.md_m <= top.md_m).step_by(50) {
            let s = top.md_m - p.md_m;
            let Some(exact) = closed_form_compression(f0, s, w, k, onset) else {
                continue;
            };
            let err = (-p.tension_n - exact).abs();
            assert!(
                err < 1e-4 * exact.max(wob_kn * 1e3),
                "{wob_kn} kN at {s:.0} m: {} vs {exact}",
                -p.tension_n
            );
            checked += 1;
        }
        assert!(checked > 10, "{checked} points checked");
        // the helix drags: the hook load falls below the plain soft string's
        assert!(soft.hook_load_n < plain.hook_load_n - 1e3);
        println!(
            "{wob_kn} kN: hook load {:.1} kN (plain soft string {:.1} kN)",
            soft.hook_load_n / 1e3,
            plain.hook_load_n / 1e3
        );
    }
    // above `a` the compression grows upward: locked up, the surface would have to push
    let locked = helical_soft_string(&vertical_case(1000.0, 300.0, 0.35));
    assert!(locked.hook_load_n < -300e3, "{}", locked.hook_load_n);
}

/// Divergence of the soft string with the helix's drag where the closed form diverges (module
/// docs): with 300 kN on the bit at friction 0.35 (above the lock-up force `a`) the compression
/// grows without bound `acoth(F_0 / a) / (a k)` above the bit's top (about 1,800 m). A vertical
/// string 30% shorter than that keeps a finite hook load, minus the compression at its top,
/// within 1% of the closed form's, and is not flagged; one 30% longer is flagged as diverged
/// (`helical_drag::diverged`, its hook load below -10,000 kN), and so is the lock-up `solve`
/// reports for it.
#[test]
fn the_helix_drag_diverges_where_the_closed_form_does() {
    let probe = vertical_case(1000.0, 300.0, 0.35);
    let pipe = probe.string.component_at(10.0);
    let (ei, w) = (pipe.ei_nm2(), pipe.buoyed_weight_n_per_m(probe.mud.density_kg_m3));
    let r = (8.5 * 0.0254 - pipe.body_od_m) / 2.0;
    let k = 0.35 * r / (4.0 * ei);
    let a = (w / k).sqrt();
    let f0 = 300e3;
    let diverges_at = (a / f0).atanh() / (a * k);
    assert!((1500.0..2200.0).contains(&diverges_at), "{diverges_at}");
    let short = (0.7 * diverges_at).round();
    let finite = helical_soft_string(&vertical_case(short + 0.3, 300.0, 0.35));
    let exact = a / ((a / f0).atanh() - a * k * short).tanh();
    assert!(!diverged(finite.hook_load_n), "{}", finite.hook_load_n);
    assert!(
        (-finite.hook_load_n - exact).abs() < 1e-2 * exact,
        "top compression {} vs closed form {exact}",
        -finite.hook_load_n
    );
    let long = (1.3 * diverges_at).round();
    let case = vertical_case(long, 300.0, 0.35);
    let runaway = helical_soft_string(&case);
    assert!(diverged(runaway.hook_load_n), "{}", runaway.hook_load_n);
    assert!(runaway.hook_load_n < DIVERGED_HOOK_LOAD_N);
    let lock = helical_lock_up(&case).expect("a helical lock-up: the plain soft string delivers 300 kN");
    assert!(drillpath::models::checks::LockUp::by_helix(&lock).helical_drag_diverged());
}

/// The grid's well with its kick-off at 500 m, a 300 m lateral at 90 deg, sliding with wall
/// friction 0.35 (the case of `acceptance_grid::buckled_start_rescues_the_helix_above_the_kick_off`).
pub(crate) fn small_grid_case(wob_kn: f64) -> Case {
    let g = GridCase {
        inc_deg: 90.0,
        lateral_m: 300.0,
        mode: "sliding",
        wob_kn,
        friction: 0.35,
    };
    let (csv, toml) = well_case(&g, 500.0);
    load_temp_case(&csv, &toml)
}

/// Helical lock-up of a slid string: the plain soft string delivers the WOB (hook load >= 0)
/// while the soft string with the helix's drag does not. Its largest WOB is where that soft
/// string's hook load crosses zero (checked on both sides, 1 kN apart), below the WOB asked
/// for, and a failed stiff solve's hints name the helical lock-up. At 30 kN (where the whole
/// string converges, hook load 33.6 kN) it is not locked up.
#[test]
fn helical_lock_up_where_the_plain_soft_string_delivers() {
    let delivers = small_grid_case(30.0);
    assert!(helical_lock_up(&delivers).is_none());
    let wob_kn = 50.0;
    let case = small_grid_case(wob_kn);
    let plain = softstring::from_case(&case, softstring::segment_length_m(&case.solver));
    assert!(
        plain.hook_load_n > 0.0,
        "plain soft string locked up: {}",
        plain.hook_load_n
    );
    let l = helical_lock_up(&case).expect("not locked up by the helix");
    assert!(l.hook_load_n < 0.0 && l.wob_n == wob_kn * 1e3);
    let max = lock_up_wob_n(&case).unwrap();
    assert_eq!(l.max_wob_n, max);
    let hook_at = |wob_n: f64| {
        let mut c = case.clone();
        c.operation.wob_n = wob_n;
        helical_soft_string(&c).hook_load_n
    };
    assert!(max > 30e3 && max < wob_kn * 1e3, "{max}");
    assert!(hook_at(max - 500.0) >= 0.0 && hook_at(max + 500.0) < 0.0);
    let hints = nonconvergence_hints(&case);
    assert!(hints.iter().any(|h| h.starts_with("helical lock-up")), "{hints:?}");
    println!(
        "plain soft hook load {:.1} kN, helical {:.1} kN, largest WOB {:.1} kN",
        plain.hook_load_n / 1e3,
        l.hook_load_n / 1e3,
        max / 1e3
    );
}

/// `loads.csv`'s `helical_drag_hook_load_kN`: the sliding row of the small grid well at 30 kN
/// (helically buckled above the kick-off) gives the soft string with the helix's drag at the
/// row's WOB (1e-9), below the row's plain hook load; a row that is nowhere helically buckled
/// (tripping out, in tension) gives its plain hook load.
#[test]
fn loads_rows_carry_the_helix_drag() {
    use drillpath::case::Mode;
    use drillpath::loads::chart::{soft_chart, ChartSettings};
    use drillpath::loads::ChartOperation;
    let case = small_grid_case(30.0);
    let settings = ChartSettings {
        op: ChartOperation::from_case(&case),
        max_element_m: softstring::segment_length_m(&case.solver),
    };
    let rows = soft_chart(&case, &[case.operation.bit_md_m], &settings);
    let sliding = rows.iter().find(|r| r.mode == Mode::Sliding).unwrap();
    assert!(sliding.buckling.helical_length_m > 0.0);
    let expected = helical_soft_string(&case).hook_load_n;
    assert!((sliding.helical_drag_hook_load_n - expected).abs() < 1e-9 * expected.abs());
    assert!(sliding.helical_drag_hook_load_n < sliding.soft.hook_load_n - 1e3);
    let out = rows.iter().find(|r| r.mode == Mode::TripOut).unwrap();
    assert_eq!(out.buckling.helical_length_m, 0.0);
    assert_eq!(out.helical_drag_hook_load_n, out.soft.hook_load_n);
}

/// Lock-up by the helix's drag as an answer (`models::string_solve`): the small grid well slid at
/// 55 kN is helically locked up (as at 50 kN, the test above; at 50 kN the whole string
/// converges with the surface pushing, a plain lock-up), and `solve --fidelity whole` answers with the
/// whole string below its lock-up instead of a failure: converged, global equilibrium within
/// 1e-6 of the largest force, a hook load not below zero, at a WOB between the lowest of
/// `HELICAL_LOCK_UP_FRACTIONS` of the largest WOB of the soft string with the helix's drag and
/// that largest WOB (the bit's WOB that one to 1e-6), and a lock-up flagged by the helix with
/// the helical interval inside the string. Where the results are at the whole string's largest
/// WOB, its hook load is within the climb's tolerance of zero. Reference: the whole string's
/// own hook load lies below that soft string's at the same WOB where both answer
/// (docs/performance.md), checked here to 1 kN.
#[test]
fn helical_lock_up_is_an_answer() {
    use drillpath::models::fem::solve::continuation::lock_up_hook_tolerance_n;
    use drillpath::models::helical_lock_up::HELICAL_LOCK_UP_FRACTIONS;
    let case = small_grid_case(55.0);
    let s = solve_whole(&case);
    let l = s.lock_up.expect("no lock-up reported");
    assert!(l.by_helix && l.wob_n == 55e3 && l.hook_load_n < 0.0, "{l:?}");
    let at = l.results_at_wob_n.expect("no results below the lock-up");
    let lowest = HELICAL_LOCK_UP_FRACTIONS.iter().copied().fold(1.0, f64::min);
    assert!(
        at >= lowest * l.max_wob_n * (1.0 - 1e-9) && at <= l.max_wob_n,
        "{at} against {}",
        l.max_wob_n
    );
    let (top, bottom) = l.helical_md_m.expect("no helical interval");
    assert!(top < bottom && bottom <= case.operation.bit_md_m, "{top} {bottom}");
    assert!(s.level.converged);
    let fem = s.level.fem.as_ref().unwrap();
    let r = &fem.results;
    assert!(r.force_imbalance_n.norm() / r.largest_force_n < 1e-6);
    assert!((r.bit.wob_n - at).abs() < 1e-6 * at, "{} {at}", r.bit.wob_n);
    let hook = s.level.hook_load_n.unwrap();
    let mut c = case.clone();
    c.operation.wob_n = at;
    let helical_soft = helical_soft_string(&c).hook_load_n;
    assert!(hook >= 0.0 && hook < helical_soft + 1e3, "{hook} {helical_soft}");
    if l.results_at_largest_wob {
        let tolerance = lock_up_hook_tolerance_n(l.max_wob_n);
        assert!(hook < tolerance, "{hook} {tolerance}");
    }
    assert!(s
        .warnings(&case)
        .iter()
        .any(|w| w.starts_with("helical lock-up") && w.contains("lock-up depth")));
    // the lock-up depth: locked below it, the WOB delivered just above it; reaching the bit at
    // zero WOB (the largest WOB is above zero)
    let depths = l.depths.expect("no lock-up depths");
    assert_eq!(depths.drag, Drag::WithHelix);
    let d = depths.at_wob_md_m.expect("no lock-up depth");
    assert!(d > 500.0 && d < case.operation.bit_md_m, "{d}");
    assert!(
        hook_load_at_depth_n(&case, d, 55e3, Drag::WithHelix) < 0.0
            && hook_load_at_depth_n(&case, d - 0.1, 55e3, Drag::WithHelix) >= 0.0
    );
    assert_eq!(depths.at_zero_wob_md_m, None);
    println!(
        "results at {:.1} kN (the largest: {}) of a largest {:.1} kN: hook load {:.1} kN (soft string with the helix's drag {:.1} kN), {:.1} s",
        at / 1e3,
        l.results_at_largest_wob,
        l.max_wob_n / 1e3,
        hook / 1e3,
        helical_soft / 1e3,
        s.level.seconds
    );
}

/// The stiff rows of `loads` where the cold start finds no equilibrium: the small grid well slid
/// at 30 kN (the case of `acceptance_grid::buckled_start_rescues_the_helix_above_the_kick_off`)
/// is solved again from its buckled shape (`Start::BuckledShape`, at the row's WOB); at 55 kN,
/// helically locked up, the row answers below its lock-up (`lock_up_wob_n` between the lowest of
/// `HELICAL_LOCK_UP_FRACTIONS` of the largest WOB of the soft string with the helix's drag and
/// that WOB, a hook load not below zero), as `solve` does (the test above, its WOB to 1e-6).
#[test]
fn loads_rows_answer_from_the_buckled_shape() {
    use drillpath::loads::row::{Start, StiffOutcome};
    use drillpath::loads::stiff::stiff_row;
    use drillpath::models::helical_lock_up::HELICAL_LOCK_UP_FRACTIONS;
    let (rescued, _) = stiff_row(&small_grid_case(30.0), None);
    let StiffOutcome::Converged {
        start,
        lock_up_wob_n: at,
        ..
    } = &rescued
    else {
        panic!("{rescued:?}");
    };
    assert_eq!((*start, *at), (Start::BuckledShape, None));
    let case = small_grid_case(55.0);
    let max = lock_up_wob_n(&case).unwrap();
    let (locked, _) = stiff_row(&case, None);
    let StiffOutcome::Converged {
        start,
        lock_up_wob_n: Some(at),
        loads,
        ..
    } = &locked
    else {
        panic!("{locked:?}");
    };
    let lowest = HELICAL_LOCK_UP_FRACTIONS.iter().copied().fold(1.0, f64::min);
    assert_eq!(*start, Start::BuckledShape);
    assert!(*at >= lowest * max * (1.0 - 1e-9) && *at <= max, "{at} {max}");
    assert!(loads.hook_load_n >= 0.0, "{}", loads.hook_load_n);
    println!(
        "30 kN: {:?}; 55 kN: loads at {:.1} kN of a largest {:.1} kN, hook load {:.1} kN",
        rescued.loads().map(|l| l.hook_load_n / 1e3),
        at / 1e3,
        max / 1e3,
        loads.hook_load_n / 1e3
    );
}

/// The whole string of the small grid well slid at 50 kN converges at that WOB with a hook load
/// below zero (the surface pushing): its lock-up is named as the helix's (the plain soft
/// string, which delivers 50 kN, would give a largest WOB above the WOB asked for), with the
/// largest WOB of the soft string with the helix's drag (below 50 kN) and the results at the WOB
/// asked for.
#[test]
fn a_converged_lock_up_is_named_by_the_helix() {
    let case = small_grid_case(50.0);
    let s = solve_whole(&case);
    assert!(s.level.converged && s.level.hook_load_n.unwrap() < 0.0);
    let l = s.lock_up.expect("no lock-up reported");
    assert!(l.by_helix && l.results_at_wob_n.is_none(), "{l:?}");
    assert_eq!(l.max_wob_n, lock_up_wob_n(&case).unwrap());
    assert!(l.max_wob_n < 50e3 && l.hook_load_n < 0.0, "{l:?}");
}

/// The small grid well slid at 45 kN (not helically locked) answers from the buckled shape:
/// the damped re-solve's contact subproblems stalled on pairs with force and gap both near zero
/// (every stage failed, 1,900 iterations) until those pairs are recentred
/// (`interior_point::IP_RECENTRES`). References: global equilibrium within 1e-6 of the largest
/// force, and the hook load between zero and that of the soft string with the helix's drag at
/// 45 kN (3.5 against 7.1 kN measured; the whole string lies below it wherever both answer,
/// docs/performance.md).
#[test]
fn recentred_pairs_let_the_damped_buckled_start_answer() {
    let case = small_grid_case(45.0);
    assert!(helical_lock_up(&case).is_none());
    let s = solve_whole(&case);
    assert!(s.level.converged);
    let fem = s.level.fem.as_ref().unwrap();
    assert_eq!(fem.stats.buckled_start, Some(true));
    let r = &fem.results;
    assert!(r.force_imbalance_n.norm() < 1e-6 * r.largest_force_n);
    let hook = s.level.hook_load_n.unwrap();
    let helical = helical_soft_string(&case).hook_load_n;
    assert!(hook >= 0.0 && hook < helical, "{hook} {helical}");
}

/// The WOB climb from the buckled shape (`models::helical_lock_up::climb_from_buckled_shape`):
/// on the small grid well slid at 47 kN (not helically locked: the largest WOB of the soft string
/// with the helix's drag is about 48 kN) every stage fails; the climb toward 47 kN from its
/// buckled start at half of it stops at a limit of the path between 23.5 and 47 kN, and the
/// failure's statistics and message say where. The climb run alone ends at the same WOB (to
/// 1e-9) with an equilibrium there: global equilibrium within 1e-6 of the largest force, the hook
/// load not below zero and below that of the soft string with the helix's drag at that WOB plus
/// 1 kN (the whole string's hook load lies below it where both answer, docs/performance.md).
/// The climbs that reach their WOB are measured on the acceptance grid (docs/performance.md).
#[test]
fn the_climb_from_the_buckled_shape() {
    use drillpath::models::diagnose::stop_phrase;
    use drillpath::models::fem::results::extract;
    use drillpath::models::fem::solve::continuation::ClimbEnd;
    use drillpath::models::fem::solve::SolveControls;
    use drillpath::models::helical_lock_up::climb_from_buckled_shape;
    let case = small_grid_case(47.0);
    assert!(helical_lock_up(&case).is_none());
    let ctl = SolveControls::from_settings(&case.solver);
    let s = solve_whole(&case);
    assert!(!s.level.converged, "converged: the case no longer needs the climb");
    let stats = &s.level.fem.as_ref().unwrap().stats;
    let (reached, target) = stats.buckled_climb_n.expect("no climb recorded");
    assert!(
        target == 47e3 && (23.5e3..47e3).contains(&reached),
        "{reached} {target}"
    );
    assert!(stop_phrase(stats, &ctl).contains("a WOB climb from the buckled shape that reached"));
    let c = climb_from_buckled_shape(&case, 47e3, 0.0, &ctl, &mut Default::default()).expect("no start converged");
    assert_eq!(c.climb_end, ClimbEnd::Stalled);
    assert!((c.wob_n - reached).abs() < 1e-9 * reached, "{} {reached}", c.wob_n);
    assert_eq!(c.model.loads.wob_n, c.wob_n);
    let r = extract(&c.model, &c.solution, case.mud.density_kg_m3);
    assert!(r.force_imbalance_n.norm() < 1e-6 * r.largest_force_n);
    let mut at = case.clone();
    at.operation.wob_n = c.wob_n;
    let helical = helical_soft_string(&at).hook_load_n;
    assert!(
        r.hook_load_n >= 0.0 && r.hook_load_n < helical + 1e3,
        "{} {helical}",
        r.hook_load_n
    );
    println!(
        "climb to 47 kN stopped at {:.1} kN, hook load {:.1} kN (soft string with the helix's drag {:.1} kN)",
        reached / 1e3,
        r.hook_load_n / 1e3,
        helical / 1e3
    );
}

/// The grid's 95 deg, 1,000 m lateral (wall friction 0.35) run in (`trip_in`, no WOB) with the
/// bit at `bit_md_m`.
fn running_in_case(bit_md_m: f64) -> Case {
    let g = GridCase {
        inc_deg: 95.0,
        lateral_m: 1000.0,
        mode: "sliding",
        wob_kn: 20.0,
        friction: 0.35,
    };
    let (csv, toml) = well_case(&g, 1000.0);
    let toml = toml
        .replace("mode = \"sliding\"", "mode = \"trip_in\"")
        .replace("wob = \"20 kN\"\n", "")
        .replace("bit_md = \"2475 m\"", &format!("bit_md = \"{bit_md_m} m\""));
    load_temp_case(&csv, &toml)
}

/// Running in locked up by the helix's drag only (`helical_running_in_lock_up`): run in to
/// 2,475 m, the plain soft string's hook load is above zero (60.5 kN) and that of the soft string
/// with the helix's drag below it (-86.8 kN). `solve --fidelity whole` answers with that lock-up
/// after the direct solve's first iterations (`DIRECT_BEFORE_CONTINUATION`): the soft level's
/// results, flagged running in, by the helix, without its drag and from the soft string, with
/// the depth it cannot be run in beyond; `hybrid` flags it too. Reference for the answer: run in
/// to 2,300 m, where both soft strings are above zero, the whole string converges with a hook
/// load below that of the soft string with the helix's drag (39.1 against 45.6 kN measured;
/// checked strictly) and far below the plain one's (93.4 kN), so the helix's drag bounds it.
#[test]
fn running_in_helical_lock_up_is_an_answer() {
    use drillpath::case::{choose, Fidelity, Level, Purpose};
    use drillpath::models::fem::solve::{SolveControls, DIRECT_BEFORE_CONTINUATION};
    use drillpath::models::helical_drag::helical_running_in_lock_up;
    use drillpath::models::string_solve::solve_string;
    let case = running_in_case(2475.0);
    let plain = softstring::from_case(&case, softstring::segment_length_m(&case.solver)).hook_load_n;
    let h = helical_running_in_lock_up(&case).expect("not locked up by the helix running in");
    assert!(plain > 0.0 && h.hook_load_n < 0.0, "{plain} {h:?}");
    let ctl = SolveControls::from_settings(&case.solver);
    let solve = |c: &Case, level: Level| {
        let choice = choose(Fidelity::Level(level), Purpose::Solve);
        solve_string(c, choice, &ctl, &mut |_, _, _| {}).unwrap()
    };
    let s = solve(&case, Level::Whole);
    assert_eq!(s.level.choice.level, Level::Soft);
    assert_eq!(s.level.hook_load_n, Some(plain));
    let l = s.lock_up.expect("no lock-up");
    assert!(
        l.running_in && l.by_helix && l.results_from_soft_string && l.results_without_helical_drag,
        "{l:?}"
    );
    assert_eq!(l.hook_load_n, h.hook_load_n);
    let d = l.depths.and_then(|d| d.at_wob_md_m).expect("no lock-up depth");
    assert!(d > 1000.0 && d < 2475.0, "{d}");
    let warning = s.warnings(&case).join("\n");
    assert!(warning.contains("helical lock-up running in") && warning.contains("cannot be run in deeper than"));
    assert!(s
        .level
        .choice
        .reason
        .contains(&format!("({DIRECT_BEFORE_CONTINUATION} Newton iterations)")));
    let hybrid = solve(&case, Level::Hybrid).lock_up.expect("hybrid: no lock-up");
    assert!(hybrid.running_in && hybrid.by_helix && !hybrid.results_from_soft_string);

    let free = running_in_case(2300.0);
    assert!(helical_running_in_lock_up(&free).is_none());
    let s = solve(&free, Level::Whole);
    assert!(s.level.converged && s.lock_up.is_none());
    let whole = s.level.hook_load_n.unwrap();
    let helical = helical_soft_string(&free).hook_load_n;
    assert!(whole > 0.0 && whole < helical, "{whole} {helical}");
    println!(
        "2,300 m: whole {:.1} kN, with the helix's drag {:.1} kN; 2,475 m: lock-up depth {d:.0} m",
        whole / 1e3,
        helical / 1e3
    );
}

/// A failed solve near its helical lock-up says so (`diagnose::NEAR_HELICAL_LOCK_UP_N`): run in
/// to 2,375 m (7 m above the 2,382 m lock-up depth), the soft string with the helix's drag keeps
/// a hook load between zero and that margin (4.9 kN measured), and the hints name the near
/// lock-up; at 2,300 m (45.6 kN) they do not.
#[test]
fn a_string_near_its_helical_lock_up_is_named_so() {
    use drillpath::models::diagnose::NEAR_HELICAL_LOCK_UP_N;
    let near = running_in_case(2375.0);
    let h = helical_soft_string(&near).hook_load_n;
    assert!((0.0..NEAR_HELICAL_LOCK_UP_N).contains(&h), "{h}");
    let hints = nonconvergence_hints(&near);
    assert!(
        hints
            .iter()
            .any(|s| s.starts_with("near a helical lock-up") && s.contains("run in to this depth")),
        "{hints:?}"
    );
    let free = nonconvergence_hints(&running_in_case(2300.0));
    assert!(
        !free.iter().any(|s| s.starts_with("near a helical lock-up")),
        "{free:?}"
    );
}
