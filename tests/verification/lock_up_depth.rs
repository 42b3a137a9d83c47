//! The lock-up depth (`models::lock_up_depth`): the bit depth from which a string locks up in
//! its operation, against the closed form of a string that drags only in its lateral.
//!
//! Reference: with no wall friction in the vertical section and the build, a soft string's axial
//! force changes there by its buoyed weight times the change of true vertical depth, whatever the
//! path; in a horizontal lateral with friction `f`, below the sinusoidal onset, a string slid
//! down gains compression `f w` per metre. So with the bit in the lateral the hook load is
//! `w (V + R) - W - f w L - f (w_bit - w) L_bit` (`V` the vertical section, `R` the build's radius
//! and its true vertical depth, `L` the lateral's length with friction, `W` the WOB), zero at
//! `L* = (w (V + R) - W - f (w_bit - w) L_bit) / (f w)`.

use drillpath::case::Case;
use drillpath::models::lock_up_depth::{
    hook_load_at_depth_n, lock_up_depth_m, lock_up_depths, Drag, DEPTH_TOLERANCE_M,
};

use crate::common::{load_temp_case, slid_bit_on_pipe, solve_whole};

/// Vertical to 300 m, a 90 deg build of radius 100 m (a circular arc by minimum curvature, to
/// 457.08 m), a horizontal lateral to 1,500 m (bit there); 8.5 in hole without friction down to
/// 460 m, with friction `friction` below; 5 in pipe without tool joints below a 0.3 m bit; 1.2 sg;
/// sliding with `wob_kn`.
fn lateral_case(wob_kn: f64, friction: f64) -> Case {
    let build_end = 300.0 + 100.0 * std::f64::consts::FRAC_PI_2;
    let survey = format!("md_m,inc_deg,azi_deg\n0,0,0\n300,0,0\n{build_end},90,0\n1500,90,0\n");
    let text = format!(
        r#"
[well]
survey = "survey.csv"
hole = [{{ to_md = "460 m", diameter = "8.5 in", friction = 0 }}, {{ to_md = "1500 m", diameter = "8.5 in" }}]
{}"#,
        slid_bit_on_pipe(1500.0, wob_kn, friction)
    );
    load_temp_case(&survey, &text)
}

/// The closed-form lock-up depth of [`lateral_case`] (module docs), m.
fn closed_form_depth_m(case: &Case, wob_n: f64, friction: f64) -> f64 {
    let rho = case.mud.density_kg_m3;
    let bit = &case.string.components[0];
    let pipe = &case.string.components[1];
    let (w, w_bit) = (pipe.buoyed_weight_n_per_m(rho), bit.buoyed_weight_n_per_m(rho));
    let drag_free_tvd = 400.0;
    let lateral = (w * drag_free_tvd - wob_n - friction * (w_bit - w) * bit.length_m) / (friction * w);
    460.0 + lateral
}

/// At 30 kN and friction 0.3 the string locks up 919 m into the lateral's dragging part (1,379 m
/// MD, below the case's bit at 1,500 m); at zero WOB not before 1,794 m, so it reaches the bit
/// depth. Tolerance: the bisection's 0.1 m and 0.05 m for the soft string's 1 m elements.
#[test]
fn lock_up_depth_matches_the_closed_form() {
    let friction = 0.3;
    let case = lateral_case(30.0, friction);
    let expected = closed_form_depth_m(&case, 30e3, friction);
    let zero = closed_form_depth_m(&case, 0.0, friction);
    assert!(zero > 1500.0, "the reference reaches the bit at zero WOB: {zero}");
    assert_eq!(Drag::of(&case, 30e3), Drag::Plain);
    // no helix anywhere (no friction above the lateral, the lateral below its onsets): both
    // models give the closed form
    for drag in [Drag::Plain, Drag::WithHelix] {
        let found = lock_up_depth_m(&case, 30e3, drag).expect("locked up at 1,500 m");
        println!("{drag:?}: lock-up depth at 30 kN: {found:.2} m MD, closed form {expected:.2} m");
        assert!(
            (found - expected).abs() <= DEPTH_TOLERANCE_M + 0.05,
            "{found} vs {expected}"
        );
        let depths = lock_up_depths(&case, 30e3, drag);
        assert_eq!(depths.at_wob_md_m, Some(found));
        assert_eq!(depths.at_zero_wob_md_m, None);
    }
}

/// The lock-up depth is what its definition says, checked by other means: the hook load is
/// negative from it down to the bit on a 1 m grid and not negative 0.1 m above it, and the case
/// refitted to it delivers the WOB asked for as its largest (the soft string solved with a zero
/// hook load, `checks::lock_up`: another computation), to the WOB that 0.1 m of lateral drags. A
/// higher WOB or friction locks up shallower.
#[test]
fn lock_up_depth_is_where_the_largest_wob_is_the_one_asked_for() {
    let case = lateral_case(30.0, 0.3);
    let d = lock_up_depth_m(&case, 30e3, Drag::Plain).unwrap();
    assert!(hook_load_at_depth_n(&case, d - DEPTH_TOLERANCE_M, 30e3, Drag::Plain) >= 0.0);
    let mut md = d;
    while md <= 1500.0 {
        assert!(
            hook_load_at_depth_n(&case, md, 30e3, Drag::Plain) < 0.0,
            "free at {md} m"
        );
        md += 1.0;
    }
    let at = case.at_bit_depth(d);
    let largest = drillpath::models::checks::lock_up(&at, Some(-1.0), 30e3)
        .expect("locked up")
        .max_wob_n;
    let per_tolerance = 0.3 * 241.0 * DEPTH_TOLERANCE_M;
    assert!(
        (largest - 30e3).abs() <= per_tolerance + 1.0,
        "largest WOB there {largest} N"
    );
    assert!(lock_up_depth_m(&case, 40e3, Drag::Plain).unwrap() < d);
    assert!(lock_up_depth_m(&lateral_case(30.0, 0.35), 30e3, Drag::Plain).unwrap() < d);
    assert_eq!(lock_up_depth_m(&lateral_case(30.0, 0.1), 30e3, Drag::Plain), None);
}

/// `loads` names the lock-up depth of each on-bottom load case locked up at its deepest bit
/// depth: the small grid well (kick-off at 500 m, 300 m lateral at 90 deg, friction 0.35) slid
/// at 55 kN, helically locked up at 1,250 m. The depth printed is the library's, at the chart's
/// WOB; the drilling rows, rotating, are not locked up and get no line.
#[test]
fn loads_prints_the_lock_up_depth() {
    let case = crate::helical_drag::small_grid_case(55.0);
    let text = loads_text(&case);
    let d = lock_up_depth_m(&case, 55e3, Drag::WithHelix).expect("slid at 55 kN it is locked up");
    let line = format!("lock-up depth, sliding: at the chart's WOB the string locks up once the bit is deeper than {d:.0} m MD, at zero WOB it reaches the deepest depth (soft string with the helix's drag, to 0.1 m)");
    assert!(text.contains(&line), "{text}");
    assert!(!text.contains("lock-up depth, drilling"), "{text}");
}

/// The hints of a whole solve that finds no equilibrium name the lock-up depth where the soft
/// string with the helix's drag is locked up, and none where it is not (the small grid well slid
/// at 55 kN, locked up; at 20 kN, not).
#[test]
fn failure_hints_name_the_lock_up_depth() {
    use drillpath::models::diagnose::nonconvergence_hints;
    let case = crate::helical_drag::small_grid_case(55.0);
    let d = lock_up_depth_m(&case, 55e3, Drag::WithHelix).unwrap();
    let hints = nonconvergence_hints(&case);
    let expected = format!("locks up once the bit is deeper than {d:.0} m MD, while at zero WOB it reaches this depth");
    assert!(hints.iter().any(|h| h.contains(&expected)), "{hints:?}");
    let free = nonconvergence_hints(&crate::helical_drag::small_grid_case(20.0));
    assert!(!free.iter().any(|h| h.contains("lock-up depth")), "{free:?}");
}

/// `solve` at `soft` and `hybrid`, whose soft strings have no helix's drag, flags the helical
/// lock-up their hook load misses: the small grid well slid at 55 kN has a plain soft hook load
/// above zero and one below zero with the helix's drag; both levels report the lock-up by the
/// helix with the lock-up depth, and where their own hook load is not below zero, the results
/// flagged as without its drag (the hybrid's stiff-contact soft string may find the hook load
/// below zero itself). At 20 kN nothing is flagged.
#[test]
fn soft_and_hybrid_flag_the_helical_lock_up_they_miss() {
    use drillpath::case::{choose, Fidelity, Level, Purpose};
    use drillpath::models::fem::solve::SolveControls;
    use drillpath::models::string_solve::solve_string;
    for (wob, locked) in [(55.0, true), (20.0, false)] {
        let case = crate::helical_drag::small_grid_case(wob);
        let ctl = SolveControls::from_settings(&case.solver);
        for level in [Level::Soft, Level::Hybrid] {
            let choice = choose(Fidelity::Level(level), Purpose::Solve);
            let s = solve_string(&case, choice, &ctl, &mut |_, _, _| {}).unwrap();
            let hook = s.level.hook_load_n.unwrap();
            println!("{level:?} at {wob} kN: hook load {:.1} kN", hook / 1e3);
            let Some(l) = s.lock_up else {
                assert!(!locked, "{level:?} at {wob} kN: no lock-up");
                continue;
            };
            assert!(locked, "{level:?} at {wob} kN: {l:?}");
            // a hook load below zero is the level's own lock-up, named as the helix's
            assert!(l.by_helix && l.results_without_helical_drag == (hook >= 0.0), "{l:?}");
            let d = l.depths.and_then(|d| d.at_wob_md_m).unwrap();
            // the hybrid's lock-up is at its solved WOB, within rounding of the case's
            assert!((d - lock_up_depth_m(&case, 55e3, Drag::WithHelix).unwrap()).abs() < 1e-6);
            let w = s.warnings(&case);
            let flagged = w
                .iter()
                .any(|w| w.contains("from a soft string without the helix's drag"));
            assert_eq!(flagged, hook >= 0.0, "{w:?}");
            // the depth is named once, with the model that found it
            let warning = w.iter().find(|w| w.starts_with("helical lock-up")).unwrap();
            assert_eq!(warning.matches("lock-up depth").count(), 1, "{warning}");
            assert!(
                warning.contains("lock-up depth (by the soft string with the helix's drag"),
                "{warning}"
            );
        }
    }
}

/// Running in (`trip_in`, zero WOB) locks up where the closed form puts a zero WOB (friction 0.45:
/// 889 m into the lateral's dragging part, 1,349 m MD), the same depth as sliding at zero WOB (the
/// same downward motion without rotation); tolerance as above. `loads` names it, and `solve`
/// running in to the bit depth flags the lock-up with it.
#[test]
fn running_in_locks_up_where_sliding_does_at_zero_wob() {
    use drillpath::case::Mode;
    let friction = 0.45;
    let sliding = lateral_case(30.0, friction);
    let mut trip_in = sliding.clone();
    trip_in.operation.mode = Mode::TripIn;
    trip_in.operation.wob_n = 0.0;
    let expected = closed_form_depth_m(&sliding, 0.0, friction);
    let found = lock_up_depth_m(&trip_in, 0.0, Drag::Plain).expect("locked up running in");
    println!("running in: {found:.2} m MD, closed form {expected:.2} m");
    assert!(
        (found - expected).abs() <= DEPTH_TOLERANCE_M + 0.05,
        "{found} vs {expected}"
    );
    let at_zero = lock_up_depths(&sliding, 30e3, Drag::Plain).at_zero_wob_md_m.unwrap();
    assert!((found - at_zero).abs() < 1e-9, "{found} {at_zero}");
    // off bottom, a WOB is not a case of running in
    assert_eq!(lock_up_depth_m(&trip_in, 10e3, Drag::Plain), None);
    let text = loads_text(&sliding);
    let line = format!("lock-up depth, trip_in: it cannot be run in deeper than {found:.0} m MD");
    assert!(text.contains(&line), "{text}");
    // `solve` running in at the bit depth flags the lock-up with its depth
    use drillpath::case::{choose, Fidelity, Level, Purpose};
    use drillpath::models::fem::solve::SolveControls;
    use drillpath::models::string_solve::solve_string;
    let ctl = SolveControls::from_settings(&trip_in.solver);
    let choice = choose(Fidelity::Level(Level::Soft), Purpose::Solve);
    let s = solve_string(&trip_in, choice, &ctl, &mut |_, _, _| {}).unwrap();
    let l = s.lock_up.expect("no lock-up running in");
    assert!(l.running_in && l.hook_load_n < 0.0 && l.wob_n == 0.0, "{l:?}");
    assert_eq!(l.depths.and_then(|d| d.at_wob_md_m), Some(found));
    let w = s.warnings(&trip_in);
    let expected = format!("it cannot be run in deeper than {found:.0} m MD");
    assert!(
        w.iter()
            .any(|w| w.starts_with("lock-up running in") && w.contains(&expected)),
        "{w:?}"
    );
}

/// `loads`' stdout for `case` at the soft level, bit depths every 250 m to the case's.
fn loads_text(case: &Case) -> String {
    use drillpath::case::{choose, Fidelity, Level, Purpose};
    use drillpath::loads::run::{plan, run, ChartRequest};
    use drillpath::report::display_units::UnitSystem;
    use drillpath::report::loads_text::write_loads;
    let req = ChartRequest {
        from_md_m: 0.0,
        to_md_m: None,
        every_m: 250.0,
        wob_n: None,
        choice: choose(Fidelity::Level(Level::Soft), Purpose::Loads),
        measured: Vec::new(),
    };
    let p = plan(case, &req).unwrap();
    let chart = run(case, &p, &mut |_, _| {}).unwrap();
    let mut out = Vec::new();
    write_loads(
        &mut out,
        case,
        std::path::Path::new("case.toml"),
        &p,
        &chart,
        UnitSystem::Si,
    )
    .unwrap();
    String::from_utf8(out).unwrap()
}

/// `predict` warns where the string locks up along the predicted hole: the small grid well slid
/// at 55 kN, predicted from 1,100 to 1,220 m; the depth the warning names is [`lock_up_depth_m`]'s
/// on the predicted path (the soft string with the helix's drag), between the start and the end.
/// A prediction that ends above it gets no warning.
#[test]
fn predict_warns_where_the_predicted_hole_locks_up() {
    use drillpath::predict::forecast::lock_up_ahead_warning;
    use drillpath::predict::march::{predict, MarchSettings};
    let case = crate::helical_drag::small_grid_case(55.0);
    let settings = MarchSettings::from_case(&case);
    let p = predict(&case, 1100.0, 1220.0, &settings, &mut |_| {}).unwrap();
    let w = lock_up_ahead_warning(&case, &p).expect("no lock-up along the predicted hole");
    let mut along = case.at_bit_depth(1220.0);
    along.well.path = p.path.clone();
    let d = lock_up_depth_m(&along, 55e3, Drag::WithHelix).unwrap();
    assert!(w.contains(&format!("deeper than {d:.1} m MD")), "{w}");
    let surveyed = lock_up_depth_m(&case, 55e3, Drag::WithHelix).unwrap();
    println!("along the prediction {d:.1} m, along the survey {surveyed:.1} m");
    assert!(d > 1100.0 && d < 1220.0, "{d}");
    let short = predict(&case, 1100.0, d - 5.0, &settings, &mut |_| {}).unwrap();
    assert_eq!(lock_up_ahead_warning(&case, &short), None);
}

/// `solve` at `bha`, a cut model without a hook load, flags a WOB the string cannot deliver by
/// the soft string: the small grid well slid at 55 kN (locked up by the helix's drag) reports the
/// lock-up with its results flagged as the assembly's (`results_without_hook_load`) and its
/// lock-up depth; at 20 kN nothing.
#[test]
fn bha_flags_a_wob_the_string_cannot_deliver() {
    use drillpath::case::{choose, Fidelity, Level, Purpose};
    use drillpath::models::fem::solve::SolveControls;
    use drillpath::models::string_solve::solve_string;
    for (wob, locked) in [(55.0, true), (20.0, false)] {
        let case = crate::helical_drag::small_grid_case(wob);
        let ctl = SolveControls::from_settings(&case.solver);
        let choice = choose(Fidelity::Level(Level::Bha), Purpose::Solve);
        let s = solve_string(&case, choice, &ctl, &mut |_, _, _| {}).unwrap();
        assert!(s.level.converged && s.level.hook_load_n.is_none());
        assert_eq!(s.lock_up.is_some(), locked, "{wob} kN: {:?}", s.lock_up);
        let Some(l) = s.lock_up else {
            continue;
        };
        assert!(
            l.by_helix && l.results_without_hook_load && !l.results_without_helical_drag,
            "{l:?}"
        );
        let d = l.depths.and_then(|d| d.at_wob_md_m).unwrap();
        assert!((d - lock_up_depth_m(&case, 55e3, Drag::WithHelix).unwrap()).abs() < 1e-9);
        let w = s.warnings(&case);
        assert!(
            w.iter().any(|w| w.ends_with("a WOB the string cannot deliver")),
            "{w:?}"
        );
    }
}

/// A whole-string solve that finds no equilibrium where the string cannot be put on bottom at any
/// WOB (the lateral case slid at friction 0.5: locked up at zero WOB from 1,260 m by the closed
/// form, the bit at 1,500 m) answers with the soft string, exit 0: `fidelity.used` soft, the
/// lock-up flagged `results_from_soft_string`, the results the soft string's at the WOB asked for
/// (its hook load against `softstring::from_case`, another call, to 1e-9 N). The whole solve is
/// made to fail by an iteration limit of 2. With a WOB the string delivers (friction 0.3), the
/// same failure gives no answer.
#[test]
fn whole_locked_at_zero_wob_answers_with_the_soft_string() {
    use drillpath::case::{Fidelity, Level};
    use drillpath::models::softstring;
    for (friction, zero_locked) in [(0.5, true), (0.3, false)] {
        let mut case = lateral_case(30.0, friction);
        assert_eq!(closed_form_depth_m(&case, 0.0, friction) < 1500.0, zero_locked);
        case.solver.max_iterations = 2;
        let s = solve_whole(&case);
        assert_eq!(s.level.converged, zero_locked, "friction {friction}");
        if !zero_locked {
            assert_eq!(s.level.choice.level, Level::Whole);
            continue;
        }
        assert_eq!(
            (s.level.choice.requested, s.level.choice.level),
            (Fidelity::Level(Level::Whole), Level::Soft)
        );
        let l = s.lock_up.expect("a lock-up");
        assert!(l.results_from_soft_string && !l.by_helix && l.max_wob_n == 0.0, "{l:?}");
        let soft = softstring::from_case(&case, softstring::segment_length_m(&case.solver)).hook_load_n;
        assert!(
            (s.level.hook_load_n.unwrap() - soft).abs() < 1e-9 && soft < 0.0,
            "{soft}"
        );
        let zero = l.depths.and_then(|d| d.at_zero_wob_md_m).unwrap();
        let expected = closed_form_depth_m(&case, 0.0, friction);
        assert!(
            (zero - expected).abs() <= DEPTH_TOLERANCE_M + 0.05,
            "{zero} vs {expected}"
        );
        let w = s.warnings(&case).join("\n");
        assert!(
            w.contains("the results are the soft string's at the WOB asked for"),
            "{w}"
        );
    }
}

/// A `loads` whole-string row that finds no equilibrium where the string cannot be put on bottom
/// at any WOB (the lateral case slid at friction 0.5), or run in (the same running in), is a
/// lock-up, `stiff_status` `locked_up`, with no stiff numbers; at friction 0.3 (a WOB delivered
/// at zero WOB) the same failure is not. The solves are made to fail by an iteration limit of 2.
#[test]
fn loads_row_locked_at_zero_wob_is_a_lock_up() {
    use drillpath::case::Mode;
    use drillpath::loads::stiff::stiff_row;
    for (friction, mode, locked) in [
        (0.5, Mode::Sliding, true),
        (0.5, Mode::TripIn, true),
        (0.3, Mode::Sliding, false),
    ] {
        let mut case = lateral_case(30.0, friction);
        case.solver.max_iterations = 2;
        case.operation.mode = mode;
        if mode == Mode::TripIn {
            case.operation.wob_n = 0.0;
        }
        let (out, _) = stiff_row(&case, None);
        assert_eq!(out.status() == "locked_up", locked, "{friction} {mode:?}: {out:?}");
        if locked {
            assert!(out.loads().is_none() && out.iterations() > 0);
        }
    }
}
