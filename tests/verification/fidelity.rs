//! Fidelity levels (issue 5) against independent references: the whole-string FEM (bit
//! forces, hook load, torque), the exact hanging-weight hook load (docs/theory.md 10.5 (a)).
//!
//! Run with `cargo test --release --test verification fidelity:: -- --nocapture` to see the numbers.

use drillpath::case::{choose, Case, Fidelity, Level, Mode, Purpose};
use drillpath::io::case_toml::{load_case, CaseOverrides};
use drillpath::models::fem::solve::SolveControls;
use drillpath::models::levels::{run, upper_part, LevelResult};

use crate::common::{example, example_dir};

fn at(case: &Case, level: Fidelity) -> LevelResult {
    let r = run(
        case,
        choose(level, Purpose::Solve),
        &SolveControls::from_settings(&case.solver),
    )
    .unwrap();
    assert!(r.converged, "{level:?} did not converge");
    r
}

const EXAMPLES: [&str; 5] = ["j-shape", "s-shape", "horizontal", "seed-daqing", "forge-16a"];

#[test]
fn fidelity_bha_and_hybrid_bit_forces_match_whole() {
    // Reference: the whole-string FEM on the example wells. Tolerance: 1% of the bit's lateral
    // force magnitude on build and walk force, 1% of the tilt magnitude (the bit-force
    // target); measured: below 0.02%.
    for name in EXAMPLES {
        let case = example(name);
        let whole = at(&case, Fidelity::Level(Level::Whole));
        let wb = whole.bit.unwrap();
        let lateral = wb.build_force_n.hypot(wb.walk_force_n);
        let tilt = wb.tilt_inc_rad.hypot(wb.tilt_azi_rad);
        for level in [Fidelity::Level(Level::Bha), Fidelity::Level(Level::Hybrid)] {
            let r = at(&case, level);
            let b = r.bit.unwrap();
            let (eb, ew) = (
                (b.build_force_n - wb.build_force_n) / lateral,
                (b.walk_force_n - wb.walk_force_n) / lateral,
            );
            let (ti, ta) = (
                (b.tilt_inc_rad - wb.tilt_inc_rad) / tilt,
                (b.tilt_azi_rad - wb.tilt_azi_rad) / tilt,
            );
            println!(
                "{name:<12} {:<6} {:.4} s (whole {:.4} s): build {:+.3} kN ({:+.4}%), walk {:+.3} kN ({:+.4}%), tilt errors {:+.4}% / {:+.4}%",
                r.choice.level.name(),
                r.seconds,
                whole.seconds,
                b.build_force_n / 1e3,
                100.0 * eb,
                b.walk_force_n / 1e3,
                100.0 * ew,
                100.0 * ti,
                100.0 * ta
            );
            for e in [eb, ew, ti, ta] {
                assert!(
                    e.abs() < 0.01,
                    "{name} {level:?}: bit error {:.3}% of the lateral force/tilt",
                    100.0 * e
                );
            }
        }
    }
}

#[test]
fn fidelity_surface_values_against_whole() {
    // Reference: the whole-string FEM. Tolerances: hook load 0.2% (soft string and FEM agree
    // on the weight; friction differs by the contact pattern; measured < 0.03%). Surface torque:
    // soft 10% (Johancsik's soft string overstates the torque of rotating pipe lying in straight
    // sections by sqrt(1 + f^2), docs/theory.md 4, 3% at f = 0.25, and differs in curved ones;
    // measured -2.3% to +2.2%). Hybrid 3% (its stiff part holds the whole bottom-hole assembly,
    // its soft part balances the lateral load with the normal force and the circumferential
    // friction together, as the stiff model does; measured -0.2% to +1.1%), except forge-16a,
    // 8% (measured +6.3%): its real survey has short doglegs in the near-vertical upper hole
    // that the stiff pipe bridges, so the whole model's torque gain above 1,474 m is 0.81 of
    // the soft string's there. Sharp builds: tests/verification/hybrid.rs.
    for name in EXAMPLES {
        let case = example(name);
        let whole = at(&case, Fidelity::Level(Level::Whole));
        let (h, t) = (whole.hook_load_n.unwrap(), whole.surface_torque_nm.unwrap());
        for level in [Fidelity::Level(Level::Soft), Fidelity::Level(Level::Hybrid)] {
            let r = at(&case, level);
            let eh = r.hook_load_n.unwrap() / h - 1.0;
            let et = r.surface_torque_nm.unwrap() / t - 1.0;
            println!(
                "{name:<12} {:<6} hook load {:.2} kN ({:+.3}%), surface torque {:.3} kN.m ({:+.2}%)",
                r.choice.level.name(),
                r.hook_load_n.unwrap() / 1e3,
                100.0 * eh,
                r.surface_torque_nm.unwrap() / 1e3,
                100.0 * et
            );
            assert!(
                eh.abs() < 0.002,
                "{name} {level:?}: hook load off by {:.3}%",
                100.0 * eh
            );
            let tol = match (level, name) {
                (Fidelity::Level(Level::Hybrid), "forge-16a") => 0.08,
                (Fidelity::Level(Level::Hybrid), _) => 0.03,
                _ => 0.10,
            };
            assert!(
                et.abs() < tol,
                "{name} {level:?}: surface torque off by {:.2}%",
                100.0 * et
            );
        }
    }
}

/// Bending energy per length `M^2/2 (1/EI_up - 1/EI_lo)` released at the stiffness changes of
/// the stiff part of `r` up to its coupling node (its top for a whole-string model), summed, N
/// (docs/theory.md 8.3: `F + M^2/(2 EI)` follows the soft string's balance within a section,
/// `F` and `M` are continuous across a change).
fn stiffness_change_energy_n(r: &LevelResult) -> f64 {
    let Some(part) = r.fem.as_ref() else {
        return 0.0;
    };
    let m = &part.model;
    let last = part.coupling.unwrap_or(m.nodes() - 1);
    (1..last)
        .map(|i| {
            let (lo, up) = (m.mesh.elements[i - 1].ei, m.mesh.elements[i].ei);
            part.results.nodes[i].bending_moment_nm.powi(2) / 2.0 * (1.0 / up - 1.0 / lo)
        })
        .sum()
}

#[test]
fn fidelity_hybrid_hook_load_is_hanging_weight_without_axial_motion() {
    // Reference: docs/theory.md 10.5 exact check (a): rotating with no axial motion, the hook load
    // is sum(w_b dTVD) over the string, exact for the soft string (tolerance 1e-6). A stiff part
    // adds the bending energy released at its stiffness changes (docs/theory.md 8.3; here
    // 1.27 N at the bit-stabilizer and the collar-HWDP changes of hybrid's stiff part, which
    // holds the whole assembly): hybrid against sum(w_b dTVD) plus those terms, tolerance 2e-6
    // (measured +8.9e-7, +2.7e-6 without them; the FEM part's residual tolerance is 1e-7 of the
    // load scale). The whole FEM is printed for comparison and held to 2e-4 against the same
    // reference (measured +8.0e-5 on this well: an open point, the energy terms explain 1.4 N of
    // its 59 N).
    let mut case = example("j-shape");
    case.operation.mode = Mode::RotatingOffBottom;
    case.operation.wob_n = 0.0;
    let bit = case.operation.bit_md_m;
    let rho = case.mud.density_kg_m3;
    let hanging: f64 = case
        .string
        .components
        .iter()
        .map(|c| {
            let tvd = |s: f64| case.well.path.point_at(bit - s).position.z;
            c.buoyed_weight_n_per_m(rho) * (tvd(c.bottom_m) - tvd(c.top_m()))
        })
        .sum();
    for level in [
        Fidelity::Level(Level::Hybrid),
        Fidelity::Level(Level::Soft),
        Fidelity::Level(Level::Whole),
    ] {
        let r = at(&case, level);
        let energy = stiffness_change_energy_n(&r);
        let e = r.hook_load_n.unwrap() / (hanging + energy) - 1.0;
        println!(
            "{:<6} hook load {:.4} kN, sum w_b dTVD {:.4} kN, stiffness-change energy {:.3} N ({e:+.2e}; {:+.2e} without it)",
            r.choice.level.name(),
            r.hook_load_n.unwrap() / 1e3,
            hanging / 1e3,
            energy,
            r.hook_load_n.unwrap() / hanging - 1.0
        );
        let tol = match level {
            Fidelity::Level(Level::Whole) => 2e-4,
            Fidelity::Level(Level::Hybrid) => 2e-6,
            _ => 1e-6,
        };
        assert!(e.abs() < tol, "{level:?}: {e:e}");
    }
}

#[test]
fn bit_torque_is_the_same_in_every_model() {
    // Reference: one bit-torque law for every model (Pessier & Fear `mu_b W D_b / 3` when
    // drilling; the given `bit_torque`, the motor's reactive torque, when sliding), and the
    // moment balance about the string axis: sliding, no wall friction acts around the axis (the
    // friction of axial motion is axial), so the surface torque equals the bit torque in every
    // model. Tolerances: 1e-9 relative between the levels' bit torques and on the soft
    // string's surface torque (both exact); 0.5% on the stiff models' surface torque
    // (discretization of a curved string; measured 0.05% for the whole string).
    let mut case = example("j-shape");
    let expect = case.bit_rock.bit_friction * case.operation.wob_n * case.string.bit_diameter_m().unwrap() / 3.0;
    for level in [Level::Soft, Level::Bha, Level::Hybrid, Level::Whole] {
        let r = at(&case, Fidelity::Level(level));
        println!(
            "drilling {:<6} bit torque {:.4} kN.m (law {:.4})",
            level.name(),
            r.bit_torque_nm / 1e3,
            expect / 1e3
        );
        assert!(
            (r.bit_torque_nm / expect - 1.0).abs() < 1e-9,
            "{level:?} drilling: {}",
            r.bit_torque_nm
        );
    }
    case.operation.mode = Mode::Sliding;
    case.operation.rop_m_s = 10.0 / 3600.0;
    case.operation.bit_torque_nm = Some(3.0e3);
    for level in [Level::Soft, Level::Bha, Level::Hybrid, Level::Whole] {
        let r = at(&case, Fidelity::Level(level));
        assert!(
            (r.bit_torque_nm / 3.0e3 - 1.0).abs() < 1e-9,
            "{level:?} sliding: bit torque {}",
            r.bit_torque_nm
        );
        if let Some(t) = r.surface_torque_nm {
            println!(
                "sliding  {:<6} surface torque {:.4} kN.m (bit 3 kN.m)",
                level.name(),
                t / 1e3
            );
            let tol = if level == Level::Soft { 1e-9 } else { 5e-3 };
            assert!((t / 3.0e3 - 1.0).abs() < tol, "{level:?} sliding: surface torque {t}");
        }
    }
}

#[test]
fn soft_string_is_the_same_in_every_model() {
    // Reference: one soft-string pass and one segment rule (models::softstring::segment_length_m,
    // min(element length, 1 m)) for the soft level, the torque-and-drag chart's row at the
    // case's depth and the non-convergence diagnosis. With 6 m pipe elements the three must give
    // the same hook load and torque to round-off (1e-12 relative), and differ from a pass at the
    // element length itself (the rule is in force).
    use drillpath::loads::chart::soft_row;
    use drillpath::loads::{set_row_operation, ChartOperation};
    use drillpath::models::softstring::{from_case, segment_length_m};
    let mut case = example("j-shape");
    case.solver.element_length_m = 6.0;
    let seg = segment_length_m(&case.solver);
    assert_eq!(seg, 1.0);
    let level = at(&case, Fidelity::Level(Level::Soft));
    let direct = from_case(&case, seg);
    let mut row_case = case.at_bit_depth(case.operation.bit_md_m);
    set_row_operation(
        &mut row_case,
        case.operation.bit_md_m,
        Mode::Drilling,
        &ChartOperation::from_case(&case),
    );
    let row = soft_row(&row_case, seg);
    let rel = |a: f64, b: f64| (a - b).abs() / b.abs();
    for (what, h, t) in [
        ("level", level.hook_load_n.unwrap(), level.surface_torque_nm.unwrap()),
        ("chart", row.soft.hook_load_n, row.soft.surface_torque_nm),
    ] {
        assert!(
            rel(h, direct.hook_load_n) < 1e-12,
            "{what}: hook load {h} vs {}",
            direct.hook_load_n
        );
        assert!(
            rel(t, direct.surface_torque_nm) < 1e-12,
            "{what}: torque {t} vs {}",
            direct.surface_torque_nm
        );
    }
    let coarse = from_case(&case, case.solver.element_length_m);
    assert!(rel(coarse.surface_torque_nm, direct.surface_torque_nm) > 1e-6);
}

#[test]
fn fidelity_levels_report_only_what_they_compute() {
    // Reference: the level table of src/case/fidelity.rs: soft has no bit side forces, bha no
    // surface values; auto picks per command.
    let case = example("seed-daqing");
    let soft = at(&case, Fidelity::Level(Level::Soft));
    assert!(soft.bit.is_none() && soft.fem.is_none() && soft.hook_load_n.is_some());
    let bha = at(&case, Fidelity::Level(Level::Bha));
    assert!(bha.bit.is_some() && bha.hook_load_n.is_none() && bha.surface_torque_nm.is_none());
    assert!(bha.cut_m.unwrap() < case.string.length_m());
    assert_eq!(choose(Fidelity::Auto, Purpose::Solve).level, Level::Whole);
    assert_eq!(choose(Fidelity::Auto, Purpose::Predict).level, Level::Bha);
    assert_eq!(choose(Fidelity::Auto, Purpose::Loads).level, Level::Soft);
    // prediction needs bit forces only: hybrid's soft upper part would not change them
    assert_eq!(
        choose(Fidelity::Level(Level::Hybrid), Purpose::Predict).level,
        Level::Bha
    );
    assert_eq!(
        choose(Fidelity::Level(Level::Hybrid), Purpose::Solve).level,
        Level::Hybrid
    );
}

#[test]
fn fidelity_upper_part_complements_truncated() {
    // Reference: the string's own components: bottom part + upper part = whole string in
    // length and weight, upper part contiguous from 0. Tolerance 1e-9 m / 1e-9 relative.
    let case = example("j-shape");
    let s = &case.string;
    for cut in [0.0, 1.0, 30.0, 57.3, 200.0, s.length_m()] {
        let lo = s.truncated(cut);
        let up = upper_part(s, cut);
        assert!((lo.length_m() + up.length_m() - s.length_m()).abs() < 1e-9);
        let w = |d: &drillpath::string::DrillString| {
            d.components
                .iter()
                .map(|c| c.weight_air_n_per_m * c.length_m)
                .sum::<f64>()
        };
        assert!(((w(&lo) + w(&up)) / w(s) - 1.0).abs() < 1e-9, "cut {cut}");
        let mut x = 0.0;
        for c in &up.components {
            assert!((c.bottom_m - x).abs() < 1e-9 && c.length_m > 0.0);
            x = c.top_m();
        }
    }
}

/// `case` with its wellhead placed at a map-grid position (UTM-like, m): the same well
/// translated by `origin` (the `[well] origin` key, read as users give it).
fn at_map_grid(name: &str, origin: [f64; 3]) -> Case {
    let dir = tempfile::tempdir().unwrap();
    let src = example_dir(name);
    for entry in std::fs::read_dir(&src).unwrap() {
        let p = entry.unwrap().path();
        if p.is_file() {
            std::fs::copy(&p, dir.path().join(p.file_name().unwrap())).unwrap();
        }
    }
    let toml = std::fs::read_to_string(src.join("case.toml")).unwrap();
    let line = format!(
        "origin = [\"{} m\", \"{} m\", \"{} m\"]\n",
        origin[0], origin[1], origin[2]
    );
    let toml = toml.replacen("[well]\n", &format!("[well]\n{line}"), 1);
    assert!(toml.contains(&line), "{name}: no [well] table to put the origin in");
    std::fs::write(dir.path().join("case.toml"), toml).unwrap();
    load_case(&dir.path().join("case.toml"), &CaseOverrides::default()).unwrap()
}

#[test]
fn map_grid_origin_leaves_every_answer_unchanged() {
    // Reference: translation invariance. Moving the wellhead to a map-grid position (here
    // north 6,478,566 m, east 435,050 m: Volve's UTM zone 31 coordinates) moves every
    // position by that vector and changes no force. With the solver working in well-frame
    // coordinates this failed: positions rounded to ~1e-9 m put noise above the residual
    // tolerance into the axial forces of short stiff elements, and neither the whole string
    // nor the stiff BHA of volve-f10 converged. The two wells are not identical to the last
    // bit: the survey's station positions, summed from the map-grid origin, are themselves
    // rounded to ~1e-9 m. Tolerances: bit forces 1e-6 of the lateral bit force (measured
    // 1.2e-7), tilts 1e-5 of the tilt magnitude (measured 1.4e-6 on a 1.3e-4 rad tilt), hook
    // load and surface torque 1e-9 relative, node positions shifted by the origin to 1e-6 m.
    let origin = [6_478_566.0, 435_050.0, 0.0];
    let shift = drillpath::geometry::Vec3::new(origin[0], origin[1], origin[2]);
    for name in ["volve-f10", "j-shape"] {
        let (local, grid) = (example(name), at_map_grid(name, origin));
        for level in [Fidelity::Level(Level::Whole), Fidelity::Level(Level::Bha)] {
            let (a, b) = (at(&local, level), at(&grid, level));
            let (ba, bb) = (a.bit.unwrap(), b.bit.unwrap());
            let lateral = ba.build_force_n.hypot(ba.walk_force_n);
            let tilt = ba.tilt_inc_rad.hypot(ba.tilt_azi_rad);
            println!(
                "{name} {level:?}: build {:.6} / {:.6} N, walk {:.6} / {:.6} N, tilt {:.4e} / {:.4e} rad",
                ba.build_force_n,
                bb.build_force_n,
                ba.walk_force_n,
                bb.walk_force_n,
                tilt,
                bb.tilt_inc_rad.hypot(bb.tilt_azi_rad)
            );
            assert!(
                (ba.build_force_n - bb.build_force_n).abs() < 1e-6 * lateral,
                "{name} {level:?}"
            );
            assert!(
                (ba.walk_force_n - bb.walk_force_n).abs() < 1e-6 * lateral,
                "{name} {level:?}"
            );
            assert!(
                (ba.tilt_inc_rad - bb.tilt_inc_rad).abs() < 1e-5 * tilt,
                "{name} {level:?}"
            );
            assert!(
                (ba.tilt_azi_rad - bb.tilt_azi_rad).abs() < 1e-5 * tilt,
                "{name} {level:?}"
            );
            if let (Some(ha), Some(hb)) = (a.hook_load_n, b.hook_load_n) {
                assert!((ha - hb).abs() < 1e-9 * ha.abs(), "{name}: hook load {ha} vs {hb}");
            }
            if let (Some(ta), Some(tb)) = (a.surface_torque_nm, b.surface_torque_nm) {
                assert!(
                    (ta - tb).abs() < 1e-9 * ta.abs().max(1.0),
                    "{name}: torque {ta} vs {tb}"
                );
            }
            let (na, nb) = (
                &a.fem.as_ref().unwrap().results.nodes,
                &b.fem.as_ref().unwrap().results.nodes,
            );
            assert_eq!(na.len(), nb.len());
            for (p, q) in na.iter().zip(nb) {
                let moved = (q.position - p.position - shift).norm();
                assert!(
                    moved < 1e-6,
                    "{name} {level:?}: node at {} m moved {moved} m off the shift",
                    p.md_m
                );
            }
        }
    }
}
