//! Acceptance tests of the torque-and-drag chart (`drillpath::loads`, issue 6). Each test names
//! its reference and tolerance.

use drillpath::case::{Case, Mode};
use drillpath::loads::calibrate::calibrate;
use drillpath::loads::calibrate::MeasuredPoint;
use drillpath::loads::chart::{soft_chart, ChartSettings};
use drillpath::loads::row::{LoadRow, StiffOutcome};
use drillpath::loads::stiff::stiff_row;
use drillpath::loads::{set_row_operation, ChartOperation, MODES};

use crate::common::{collar, example, load_temp_case as temp_case, pipe_properties, DRILL_PIPE, DRILL_PIPE_BODY};

/// Survey rows every 10 m from (md, inc, azi) knots with inclination and azimuth linear in MD
/// between knots (constant build/turn rate).
fn survey(knots: &[(f64, f64, f64)]) -> String {
    let mut rows = vec!["md_m,inc_deg,azi_deg".to_string()];
    for w in knots.windows(2) {
        let ((m0, i0, a0), (m1, i1, a1)) = (w[0], w[1]);
        let n = ((m1 - m0) / 10.0).round() as usize;
        for k in 0..n {
            let s = k as f64 / n as f64;
            rows.push(format!(
                "{},{},{}",
                m0 + s * (m1 - m0),
                i0 + s * (i1 - i0),
                a0 + s * (a1 - a0)
            ));
        }
    }
    let (m, i, a) = knots[knots.len() - 1];
    rows.push(format!("{m},{i},{a}"));
    rows.join("\n") + "\n"
}

/// A case of plain 5 in pipe (29 kg/m, optional 6-5/8 in joints) in 8.5 in hole, 1.2 sg mud.
fn pipe_case(survey_csv: &str, td: f64, friction: f64, joints: bool, element: f64) -> Case {
    let pipe = if joints { DRILL_PIPE } else { DRILL_PIPE_BODY };
    temp_case(
        survey_csv,
        &format!(
            r#"
[well]
survey = "survey.csv"
hole = [{{ to_md = "{td} m", diameter = "8.5 in" }}]
[mud]
density = "1.2 sg"
[operation]
mode = "trip_out"
rpm = 60
friction = {friction}
viscous_torque = false
{pipe}[solver]
element_length = "{element} m"
bha_element_length = "{element} m"
max_iterations = 500
"#
        ),
    )
}

/// Buoyed weight of the 5 in pipe, N/m.
fn w_b() -> f64 {
    pipe_properties().1
}

fn row(rows: &[LoadRow], depth_index: usize, mode: Mode) -> &LoadRow {
    &rows[depth_index * MODES.len() + MODES.iter().position(|m| *m == mode).unwrap()]
}

fn stiff(case: &Case, bit_md: f64, mode: Mode) -> drillpath::loads::row::RowLoads {
    let mut c = case.at_bit_depth(bit_md);
    set_row_operation(&mut c, bit_md, mode, &ChartOperation::from_case(case));
    match stiff_row(&c, None).0 {
        StiffOutcome::Converged { loads, .. } => loads,
        other => panic!("stiff {} at {bit_md} m: {other:?}", mode.name()),
    }
}

#[test]
fn straight_inclined_hole_trip_loads_match_closed_form() {
    // Reference: docs/theory.md 10.5 exact check (b), a straight section of length L from zero
    // tension: F = w_b L (cos i -/+ f sin i) (trip in -, trip out +). Tolerance 0.5% (soft and
    // stiff; the soft string is exact to round-off, asserted to 1e-9). The stiff string is held
    // on the hole axis at the bit and at the top and lifts off the low side over about
    // (72 EI r / q)^(1/4) ~ 12 m at each end, which removes a fixed ~0.6 kN of friction: 0.45%
    // on trip in at 1000 m, 0.28% at 2000 m (measured), hence the 2000 m string.
    let (inc, f, len) = (45.0_f64, 0.25, 2000.0);
    let case = pipe_case(&survey(&[(0.0, inc, 30.0), (len, inc, 30.0)]), len, f, false, 2.0);
    let i = inc.to_radians();
    let exact_in = w_b() * len * (i.cos() - f * i.sin());
    let exact_out = w_b() * len * (i.cos() + f * i.sin());
    let settings = ChartSettings {
        op: ChartOperation::from_case(&case),
        max_element_m: 1.0,
    };
    let rows = soft_chart(&case, &[len], &settings);
    let soft_in = row(&rows, 0, Mode::TripIn).soft.hook_load_n;
    let soft_out = row(&rows, 0, Mode::TripOut).soft.hook_load_n;
    assert!(
        (soft_in / exact_in - 1.0).abs() < 1e-9,
        "soft trip in {soft_in} vs {exact_in}"
    );
    assert!(
        (soft_out / exact_out - 1.0).abs() < 1e-9,
        "soft trip out {soft_out} vs {exact_out}"
    );
    for (mode, exact) in [(Mode::TripIn, exact_in), (Mode::TripOut, exact_out)] {
        let s = stiff(&case, len, mode);
        let e = s.hook_load_n / exact - 1.0;
        println!(
            "{}: stiff {:.3} kN, closed form {:.3} kN ({:+.3}%)",
            mode.name(),
            s.hook_load_n / 1e3,
            exact / 1e3,
            100.0 * e
        );
        assert!(e.abs() < 0.005, "stiff {} off by {:.3}%", mode.name(), 100.0 * e);
    }
}

/// An on-bottom row where even a zero WOB leaves the hook load below zero: a straight 85 deg hole
/// at friction 0.25 (`cos i < f sin i`), where the pipe cannot be slid down at all. Reference:
/// the closed form of docs/theory.md 10.5 (b), `F = w_b L (cos i - f sin i)`, negative here. The
/// sliding row asked for 50 kN has a zero WOB and that hook load (to 1e-9, as trip in), not a
/// hook load of zero.
#[test]
fn a_string_that_cannot_be_put_on_bottom_keeps_its_negative_hook_load() {
    let (inc, f, len) = (85.0_f64, 0.25, 1000.0);
    let case = pipe_case(&survey(&[(0.0, inc, 30.0), (len, inc, 30.0)]), len, f, false, 2.0);
    let i = inc.to_radians();
    let exact = w_b() * len * (i.cos() - f * i.sin());
    assert!(exact < -10e3, "{exact}");
    let mut op = ChartOperation::from_case(&case);
    op.wob_n = 50e3;
    let settings = ChartSettings { op, max_element_m: 1.0 };
    let rows = soft_chart(&case, &[len], &settings);
    for mode in [Mode::Sliding, Mode::TripIn] {
        let r = row(&rows, 0, mode);
        assert_eq!(r.wob_n, 0.0, "{}", mode.name());
        let hook = r.soft.hook_load_n;
        assert!((hook / exact - 1.0).abs() < 1e-9, "{}: {hook} vs {exact}", mode.name());
    }
}

/// Independent Johancsik computation (scalar form, docs/theory.md 10.5 with the sign of the lower -
/// upper differences): inclination and azimuth linear in MD between `knots` (exact for these
/// constant-rate sections up to the minimum-curvature interpolation), TVD by the midpoint rule,
/// 0.5 m elements, from the bit up. Returns (hook load N, torque N.m) for axial direction `dir`
/// (+1 running in, -1 pulling out, 0 rotating) with contact radius `rc`.
fn johancsik(knots: &[(f64, f64, f64)], bit_md: f64, f: f64, dir: f64, rc: f64) -> (f64, f64) {
    let at = |md: f64| -> (f64, f64) {
        let k = knots.windows(2).position(|w| md <= w[1].0).unwrap_or(knots.len() - 2);
        let ((m0, i0, a0), (m1, i1, a1)) = (knots[k], knots[k + 1]);
        let s = ((md - m0) / (m1 - m0)).clamp(0.0, 1.0);
        ((i0 + s * (i1 - i0)).to_radians(), (a0 + s * (a1 - a0)).to_radians())
    };
    let w = w_b();
    let n = (bit_md / 0.5).round() as usize;
    let dl = bit_md / n as f64;
    let (mut t, mut m) = (0.0_f64, 0.0_f64);
    for k in 0..n {
        let lo = bit_md - k as f64 * dl;
        let up = lo - dl;
        let (i_lo, a_lo) = at(lo);
        let (i_up, a_up) = at(up);
        let ib = 0.5 * (i_lo + i_up);
        let wt = w * dl;
        let nf = ((t * (a_lo - a_up) * ib.sin()).powi(2) + (t * (i_lo - i_up) - wt * ib.sin()).powi(2)).sqrt();
        let (im, _) = at(0.5 * (lo + up));
        t += wt * im.cos() - dir * f * nf;
        if dir == 0.0 {
            m += f * nf * rc;
        }
    }
    (t, m)
}

#[test]
fn curved_well_soft_chart_matches_independent_johancsik() {
    // Reference: an independent scalar Johancsik (1984) computation written above (not the
    // library's vector form). Tolerance 1% on hook loads and rotating torque.
    let knots = [
        (0.0, 0.0, 20.0),
        (400.0, 0.0, 20.0),
        (900.0, 40.0, 20.0),
        (1300.0, 40.0, 20.0),
        (1600.0, 55.0, 50.0),
        (2000.0, 55.0, 50.0),
    ];
    let f = 0.25;
    let case = pipe_case(&survey(&knots), 2000.0, f, true, 1.0);
    let settings = ChartSettings {
        op: ChartOperation::from_case(&case),
        max_element_m: 1.0,
    };
    let depths = [700.0, 1450.0, 2000.0];
    let rows = soft_chart(&case, &depths, &settings);
    let rc = 6.625 * 0.0254 / 2.0;
    for (k, &d) in depths.iter().enumerate() {
        for (mode, dir) in [
            (Mode::TripIn, 1.0),
            (Mode::TripOut, -1.0),
            (Mode::RotatingOffBottom, 0.0),
        ] {
            let (h, t) = johancsik(&knots, d, f, dir, rc);
            let r = row(&rows, k, mode);
            let eh = r.soft.hook_load_n / h - 1.0;
            println!(
                "{d} m {}: chart {:.2} kN, reference {:.2} kN ({:+.3}%); torque {:.3} / {:.3} kN.m",
                mode.name(),
                r.soft.hook_load_n / 1e3,
                h / 1e3,
                100.0 * eh,
                r.soft.surface_torque_nm / 1e3,
                t / 1e3
            );
            assert!(
                eh.abs() < 0.01,
                "{d} m {}: hook load off by {:.3}%",
                mode.name(),
                100.0 * eh
            );
            if dir == 0.0 && t > 0.0 {
                let et = r.soft.surface_torque_nm / t - 1.0;
                assert!(et.abs() < 0.01, "{d} m: torque off by {:.3}%", 100.0 * et);
            }
        }
    }
}

#[test]
fn stiff_agrees_with_soft_in_smooth_well_and_exceeds_it_in_sharp_dogleg() {
    // References: (a) the soft string (Johancsik) in a smooth well (3 deg/30 m): stiff hook
    // loads within 5% (issue 6); rotating torque within 5% too (docs/theory.md 4 predicts -3% at
    // f = 0.25). (b) A 10 deg/30 m dogleg: the stiff string must bend, so its largest contact
    // force exceeds the soft string's per-joint force (asserted: at least 10% higher).
    let f = 0.25;
    let smooth = [
        (0.0, 0.0, 0.0),
        (100.0, 0.0, 0.0),
        (400.0, 30.0, 0.0),
        (600.0, 30.0, 0.0),
    ];
    let case = pipe_case(&survey(&smooth), 600.0, f, true, 2.0);
    let settings = ChartSettings {
        op: ChartOperation::from_case(&case),
        max_element_m: 1.0,
    };
    let rows = soft_chart(&case, &[600.0], &settings);
    for mode in [Mode::TripIn, Mode::TripOut, Mode::RotatingOffBottom] {
        let soft = row(&rows, 0, mode).soft;
        let s = stiff(&case, 600.0, mode);
        let eh = s.hook_load_n / soft.hook_load_n - 1.0;
        println!(
            "smooth {}: hook stiff {:.2} soft {:.2} kN ({:+.2}%), torque stiff {:.3} soft {:.3} kN.m",
            mode.name(),
            s.hook_load_n / 1e3,
            soft.hook_load_n / 1e3,
            100.0 * eh,
            s.surface_torque_nm / 1e3,
            soft.surface_torque_nm / 1e3
        );
        assert!(eh.abs() < 0.05, "{}: hook load off by {:.2}%", mode.name(), 100.0 * eh);
        if mode == Mode::RotatingOffBottom {
            let et = s.surface_torque_nm / soft.surface_torque_nm - 1.0;
            assert!(et.abs() < 0.05, "torque off by {:.2}%", 100.0 * et);
        }
    }
    let sharp = [
        (0.0, 0.0, 0.0),
        (100.0, 0.0, 0.0),
        (190.0, 30.0, 0.0),
        (400.0, 30.0, 0.0),
    ];
    let case = pipe_case(&survey(&sharp), 400.0, f, true, 1.0);
    let rows = soft_chart(&case, &[400.0], &settings);
    let soft = row(&rows, 0, Mode::TripOut).soft;
    let s = stiff(&case, 400.0, Mode::TripOut);
    println!(
        "10 deg/30 m dogleg, trip out: max contact stiff {:.2} kN, soft {:.2} kN per joint; hook {:.2} / {:.2} kN",
        s.max_contact_force_n / 1e3,
        soft.max_contact_force_n / 1e3,
        s.hook_load_n / 1e3,
        soft.hook_load_n / 1e3
    );
    assert!(
        s.max_contact_force_n > 1.1 * soft.max_contact_force_n,
        "stiff {} N vs soft {} N",
        s.max_contact_force_n,
        soft.max_contact_force_n
    );
}

#[test]
fn friction_calibration_round_trip() {
    // Reference: synthetic measurements from the soft string with friction 0.18 in the cased
    // section (0-1200 m) and 0.28 in open hole, multiplied by (1 + 2% noise) from a fixed-seed
    // generator (uniform with standard deviation 2%). Tolerance: both factors back within 0.02.
    let knots = [
        (0.0, 0.0, 0.0),
        (500.0, 0.0, 0.0),
        (1000.0, 40.0, 0.0),
        (2500.0, 40.0, 0.0),
    ];
    let make = |cased: f64, open: f64| {
        temp_case(
            &survey(&knots),
            &format!(
                r#"
[well]
survey = "survey.csv"
hole = [
  {{ to_md = "1200 m", diameter = "12.25 in", friction = {cased} }},
  {{ to_md = "2500 m", diameter = "8.5 in", friction = {open} }},
]
[mud]
density = "1.2 sg"
[operation]
mode = "trip_out"
rpm = 60
friction = 0.3
{}{DRILL_PIPE}"#,
                collar("60 m")
            ),
        )
    };
    let truth = make(0.18, 0.28);
    let op = ChartOperation::from_case(&truth);
    let settings = ChartSettings { op, max_element_m: 2.0 };
    let depths: Vec<f64> = (0..20).map(|k| 600.0 + 100.0 * k as f64).collect();
    let rows = soft_chart(&truth, &depths, &settings);
    // fixed-seed LCG, uniform in [-sqrt(3), sqrt(3)] (unit variance)
    let mut seed: u64 = 0x5eed_1234;
    let mut noise = || {
        seed = seed.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
        let u = (seed >> 11) as f64 / (1u64 << 53) as f64;
        1.0 + 0.02 * 3f64.sqrt() * (2.0 * u - 1.0)
    };
    let mut data = Vec::new();
    for (k, &d) in depths.iter().enumerate() {
        for mode in [Mode::TripIn, Mode::TripOut, Mode::RotatingOffBottom] {
            let r = row(&rows, k, mode);
            data.push(MeasuredPoint {
                line: data.len() + 2,
                bit_md_m: d,
                mode,
                hook_load_n: r.soft.hook_load_n * noise(),
                torque_nm: (mode == Mode::RotatingOffBottom).then(|| r.soft.surface_torque_nm * noise()),
                wob_n: None,
            });
        }
    }
    // start from the operation's 0.3 everywhere
    let start = make(0.3, 0.3);
    let cal = calibrate(&start, &data, &op, 2.0).unwrap();
    for p in &cal.parameters {
        println!(
            "section {}: {:.4} +/- {:?} (fitted {})",
            p.section, p.value, p.std_error, p.fitted
        );
    }
    assert!(cal.converged);
    let (c, o) = (&cal.parameters[0], &cal.parameters[1]);
    assert!(c.fitted && o.fitted);
    assert!((c.value - 0.18).abs() < 0.02, "cased {}", c.value);
    assert!((o.value - 0.28).abs() < 0.02, "open {}", o.value);
    // the standard errors are of the size of the actual errors (not zero, not huge)
    for (p, truth) in [(c, 0.18), (o, 0.28)] {
        let s = p.std_error.unwrap();
        assert!(s > 0.0 && s < 0.02, "std error {s}");
        assert!(
            (p.value - truth).abs() < 5.0 * s,
            "error {} vs std {s}",
            p.value - truth
        );
    }
}

/// Reference: the cold-started solve of the same row (the solver's own start).
/// Warm starts between bit depths (the same load case one depth up, carried onto the longer
/// string's mesh) must converge to the same solution: hook load and torque within 1e-6
/// relative (of the row's hook load for the torque of a non-rotating row, whose value is 0),
/// and the largest contact force within 1e-4 relative (a contact multiplier, converged to the
/// gap tolerance). Also checks that the warm starts are used (the rows at the second and
/// third depth start from the previous depth) and take fewer Newton iterations.
#[test]
fn warm_started_rows_equal_cold_started_rows() {
    use drillpath::loads::row::Start;
    use drillpath::loads::stiff::stiff_depth;
    let case = example("seed-daqing");
    let op = ChartOperation::from_case(&case);
    let wobs: Vec<f64> = MODES
        .iter()
        .map(|m| if m.on_bottom() { op.wob_n } else { 0.0 })
        .collect();
    let mut previous = Vec::new();
    let (mut it_warm, mut it_cold) = (0, 0);
    for (k, d) in [677.0, 702.0, 727.0].into_iter().enumerate() {
        let c = case.at_bit_depth(d);
        let (warm, solved) = stiff_depth(&c, d, &op, &wobs, &previous);
        previous = solved;
        for (j, mode) in MODES.into_iter().enumerate() {
            let mut cc = c.clone();
            set_row_operation(&mut cc, d, mode, &op);
            let cold = stiff_row(&cc, None).0;
            let (
                StiffOutcome::Converged {
                    loads: w,
                    start,
                    iterations,
                    ..
                },
                StiffOutcome::Converged {
                    loads: r,
                    iterations: ic,
                    ..
                },
            ) = (&warm[j], &cold)
            else {
                panic!("{d} m {}: {:?} / {:?}", mode.name(), warm[j], cold);
            };
            if k > 0 {
                assert_eq!(*start, Start::PreviousDepth, "{d} m {}", mode.name());
                it_warm += iterations;
                it_cold += ic;
            }
            let rel = |a: f64, b: f64, scale: f64| (a - b).abs() / scale;
            assert!(
                rel(w.hook_load_n, r.hook_load_n, r.hook_load_n) < 1e-6,
                "{d} {}: {w:?} {r:?}",
                mode.name()
            );
            let t_scale = r.surface_torque_nm.abs().max(1e-6 * r.hook_load_n);
            assert!(
                rel(w.surface_torque_nm, r.surface_torque_nm, t_scale) < 1e-6,
                "{d} {}: {w:?} {r:?}",
                mode.name()
            );
            let f_scale = r.max_contact_force_n.max(1.0);
            assert!(
                rel(w.max_contact_force_n, r.max_contact_force_n, f_scale) < 1e-4,
                "{d} {}: {w:?} {r:?}",
                mode.name()
            );
            if !matches!(mode, Mode::Drilling | Mode::RotatingOffBottom) {
                assert_eq!(w.surface_torque_nm, 0.0, "non-rotating torque cleaned to 0");
            }
        }
    }
    println!("Newton iterations of the last two depths: warm {it_warm}, cold {it_cold}");
    assert!(it_warm < it_cold, "warm {it_warm} vs cold {it_cold}");
}

/// Reference: the identity. Carrying a solved state onto the model of the same string at the
/// same depth gives the state back (positions to 1e-12 m, triads to 1e-12, multipliers exactly);
/// carried two joints deeper, the pipe keeps its lateral offset from the hole axis at each MD
/// (to 1e-9 m; the nodes then sit at the previous nodes' MDs).
#[test]
fn transport_between_depths_keeps_the_state() {
    use drillpath::loads::stiff::transport_to_depth;
    let case = pipe_case(
        &survey(&[(0.0, 30.0, 10.0), (600.0, 30.0, 10.0)]),
        600.0,
        0.25,
        true,
        1.0,
    );
    let op = ChartOperation::from_case(&case);
    let mut c = case.at_bit_depth(500.0);
    set_row_operation(&mut c, 500.0, Mode::TripOut, &op);
    let (out, solved) = stiff_row(&c, None);
    assert!(matches!(out, StiffOutcome::Converged { .. }), "{out:?}");
    let (m, st) = solved.unwrap();
    let back = transport_to_depth(&(m.clone(), st.clone()), &m, &c.string);
    for i in 0..m.nodes() {
        assert!((back.x[i] - st.x[i]).norm() < 1e-12, "node {i}");
        assert!((back.triads[i] - st.triads[i]).norm() < 1e-12, "node {i}");
        assert_eq!(back.multipliers[i], st.multipliers[i]);
    }
    // two joints deeper: the new nodes sit at the MDs of the old ones
    let d2 = 500.0 + 2.0 * 9.144;
    let mut c2 = case.at_bit_depth(d2);
    set_row_operation(&mut c2, d2, Mode::TripOut, &op);
    let m2 = drillpath::models::fem::model::Model::from_case(&c2);
    let moved = transport_to_depth(&(m.clone(), st.clone()), &m2, &c2.string);
    // a single pipe component: the whole string follows the MD rule above its first two joints
    let mut checked = 0;
    for i in (0..m2.nodes()).step_by(37) {
        let md = m2.md_ref[i];
        let j = (0..m.nodes())
            .min_by(|&a, &b| (m.md_ref[a] - md).abs().total_cmp(&(m.md_ref[b] - md).abs()))
            .unwrap();
        if (m.md_ref[j] - md).abs() > 1e-9 || m2.mesh.nodes[i].s_m < d2 - 500.0 + 1e-9 {
            continue;
        }
        // same MD: same lateral offset from the axis (the stretch shift is along the axis)
        let lat = |x: drillpath::geometry::Vec3, q: &nalgebra::Matrix3<f64>| {
            let d = q.transpose() * x;
            (d[1], d[2])
        };
        // each model's positions are in its own frame (origin at its bit, `Model::origin_m`)
        let (p, p2) = (m.path.point_at(md).position, m2.path.point_at(md).position);
        let (a1, a2) = lat(st.x[j] - p, &m.basis[j]);
        let (b1, b2) = lat(moved.x[i] - p2, &m2.basis[i]);
        assert!((a1 - b1).abs() < 1e-9 && (a2 - b2).abs() < 1e-9, "node {i} at {md} m");
        checked += 1;
    }
    assert!(checked > 5, "{checked} nodes compared");
}
