//! HTML report of `drillpath solve`: inputs, key results and plots along the string.

use super::display_units::{signed, DisplayUnit, UnitSystem};
use super::html::{check_finite_text, Page};
use super::inputs::echo_inputs;
use super::plots::{render, Band, Chart, Series, Style};
use super::schematic::shown_length_m;
use super::solve_output::CONTACT_THRESHOLD_N;
use super::solve_text::{helical_drag_hook_load_text, rss_line, steering_line};
use crate::case::{Case, Level};
use crate::models::buckling::{spans, tributary, BuckleState, Mark};
use crate::models::fem::results::{NodeResult, SolveResults};
use crate::models::fem::solve::SolveStats;
use crate::models::soft_comparison::SoftComparison;
use crate::models::string_solve::StringSolve;
use crate::predict::steer::{RssSteering, Steering};

/// Ids of the solve report's figures (the tests look for each).
pub const SOLVE_FIGURES: &[&str] = &[
    "bha-schematic",
    "contact-force",
    "deflection-high",
    "deflection-right",
    "axial-force",
    "torque",
    "bending-stress",
];

/// Contact nodes closer than this along the string form one contact zone, m.
pub const ZONE_GAP_M: f64 = 1.5;

/// Legend names of the buckling marks on the axial-force plot (the tests look for them).
pub const BUCKLING_SERIES: [&str; 4] = [
    "sinusoidal buckling",
    "helical buckling",
    "sinusoidal onset",
    "helical onset",
];

/// Onset curves are drawn up to this multiple of the largest compression.
pub const ONSET_SHOWN_UP_TO: f64 = 2.0;

/// Legend names of the helix marks on the contact-force plot (shown only where the string is
/// helically buckled).
pub const HELIX_SERIES: [&str; 2] = ["helical buckling", "helix wall force (Mitchell)"];

/// Legend name of the whirling intervals on the contact-force plot (shown only where a rotating
/// string whirls, [`ReportOptions::whirl_md_m`]).
pub const WHIRL_SERIES: &str = "whirling (rotary friction without its push round the wall)";

/// The wall contact force chart: the normal force at each node of `res` along MD (display
/// units `du`, `fu`) and, where `marks` (at the nodes of `res`, or empty) put the string beyond
/// the helical onset, those intervals shaded and Mitchell's helical wall force per length
/// times each node's tributary length: the force per node a helix along the wall would give.
pub fn contact_force_chart(res: &SolveResults, marks: &[Mark], du: DisplayUnit, fu: DisplayUnit) -> Chart {
    let along: Vec<(f64, f64)> = res
        .nodes
        .iter()
        .map(|n| (du.show(n.md_m), fu.show(n.contact_force_n)))
        .collect();
    let c = Chart::new(
        "Wall contact force",
        &format!("MD [{}]", du.label),
        &format!("contact force [{}]", fu.label),
    )
    .with(Series::new("contact force", along, Style::Line, 1))
    .with_band(Band {
        name: HELIX_SERIES[0].into(),
        spans: spans(marks, BuckleState::Helical)
            .into_iter()
            .map(|(a, b)| (du.show(a), du.show(b)))
            .collect(),
        color: 1,
    });
    let helix: Vec<(f64, f64)> = marks
        .iter()
        .zip(tributary(marks))
        .filter(|(m, _)| m.state == BuckleState::Helical)
        .filter_map(|(m, l)| Some((du.show(m.md_m), fu.show(m.helical_wall_force_n_per_m? * l))))
        .collect();
    if helix.is_empty() {
        c
    } else {
        c.with(Series::new(HELIX_SERIES[1], helix, Style::Points, 3))
    }
}

/// The axial-force chart: the effective axial force along MD (display units `du`, `fu`), the
/// buckled MD intervals of `marks` shaded (sinusoidal, helical; only where there are any) and
/// the onset loads drawn as compressive axial forces where the string is in compression and can
/// buckle, up to [`ONSET_SHOWN_UP_TO`] times the largest compression.
pub fn axial_force_chart(
    res: &SolveResults,
    marks: &[Mark],
    depth_unit: DisplayUnit,
    force_unit: DisplayUnit,
) -> Chart {
    let mut c = Chart::new(
        "Effective axial force (tension +) and buckling",
        &format!("MD [{}]", depth_unit.label),
        &format!("axial force [{}]", force_unit.label),
    );
    for (k, state) in [BuckleState::Sinusoidal, BuckleState::Helical].into_iter().enumerate() {
        c = c.with_band(Band {
            name: BUCKLING_SERIES[k].into(),
            spans: spans(marks, state)
                .into_iter()
                .map(|(a, b)| (depth_unit.show(a), depth_unit.show(b)))
                .collect(),
            color: if k == 0 { 4 } else { 1 },
        });
    }
    // onset curves where the string is in compression, up to ONSET_SHOWN_UP_TO times the largest
    // compression (the stiff collars' onsets would squash the axial force); broken where the
    // component cannot buckle (bit, stabilizers) or the onset is off the scale
    let max_c = marks.iter().map(|m| m.compression_n).fold(0.0, f64::max);
    for (k, onset) in [(|m: &Mark| m.sinusoidal_n) as fn(&Mark) -> Option<f64>, |m: &Mark| {
        m.helical_n
    }]
    .into_iter()
    .enumerate()
    {
        let mut run: Vec<(f64, f64)> = Vec::new();
        for m in marks.iter().map(Some).chain([None]) {
            let shown = m
                .filter(|m| m.compression_n > 0.0)
                .and_then(|m| onset(m).map(|f| (m.md_m, f)))
                .filter(|&(_, f)| f <= ONSET_SHOWN_UP_TO * max_c);
            match shown {
                Some((md, f)) => run.push((depth_unit.show(md), -force_unit.show(f))),
                None if !run.is_empty() => {
                    c.series.push(Series::new(
                        BUCKLING_SERIES[2 + k],
                        std::mem::take(&mut run),
                        Style::Thin,
                        if k == 0 { 4 } else { 1 },
                    ));
                }
                None => {}
            }
        }
    }
    c = c.with(Series::new(
        "axial force",
        res.nodes
            .iter()
            .map(|n| (depth_unit.show(n.md_m), force_unit.show(n.axial_force_n)))
            .collect(),
        Style::Line,
        0,
    ));
    c.zero_line = true;
    c
}

/// How a solve report is shown: units, and what part of the string it covers.
#[derive(Debug, Clone, Default)]
pub struct ReportOptions {
    /// Units shown.
    pub units: UnitSystem,
    /// A sentence shown at the top when the report does not cover the whole stiff string
    /// (the fidelity level and what it leaves out); None for the whole string.
    pub note: Option<String>,
    /// False when the model gives no hook load or surface torque (`bha`): the key results
    /// say "not computed" instead of showing `res`'s values (the axial force at the cut).
    pub no_surface_values: bool,
    /// The soft string at the same WOB, shown beside the hook load and surface torque.
    pub soft: Option<SoftComparison>,
    /// MD intervals `(top, bottom)`, m, where the rotating string whirls
    /// (`crate::models::whirl`), shaded on the contact-force plot; empty: none.
    pub whirl_md_m: Vec<(f64, f64)>,
}

/// The report's HTML text (`marks`: buckling marks at the nodes of `res`, may be empty;
/// `scope`: units and what the results cover).
pub fn solve_report(
    case: &Case,
    res: &SolveResults,
    marks: &[Mark],
    stats: &SolveStats,
    converged: bool,
    scope: &ReportOptions,
) -> Result<String, String> {
    let units = scope.units;
    let b = &res.bit;
    let mut page = Page::new(&format!("drillpath solve: {}", case.name));
    if !converged {
        page.warning("NOT CONVERGED: the results below are flagged and not valid.");
    }
    if let Some(note) = &scope.note {
        page.note(note);
    }
    let contacts: Vec<&NodeResult> = res
        .nodes
        .iter()
        .filter(|n| n.contact_force_n > CONTACT_THRESHOLD_N)
        .collect();
    key_results(&mut page, res, &contacts, stats, converged, scope);
    contact_zones(&mut page, case, b.md_m, &contacts, units);
    echo_inputs(&mut page, case, b.md_m, units)?;
    page.heading("Along the string");
    string_figures(&mut page, case, res, marks, scope)?;
    let html = page.finish();
    check_finite_text(&html)?;
    Ok(html)
}

/// The key results: bit, surface, contacts, solver.
fn key_results(
    page: &mut Page,
    res: &SolveResults,
    contacts: &[&NodeResult],
    stats: &SolveStats,
    converged: bool,
    scope: &ReportOptions,
) {
    let units = scope.units;
    let (depth_unit, force_unit, torque_unit) = (units.depth(), units.force(), units.torque());
    let b = &res.bit;
    page.heading("Key results");
    let max_contact = contacts.iter().map(|n| n.contact_force_n).fold(0.0, f64::max);
    let mut kv = vec![
        ("bit MD".to_string(), depth_unit.fmt(b.md_m, 2)),
        ("weight on bit".into(), force_unit.fmt(b.wob_n, 2)),
        ("bit build force (+ = up)".into(), force_unit.fmt(b.build_force_n, 3)),
        ("bit walk force (+ = right)".into(), force_unit.fmt(b.walk_force_n, 3)),
        (
            "bit tilt, inclination".into(),
            format!("{} deg", signed(b.tilt_inc_rad.to_degrees(), 4)),
        ),
        (
            "bit tilt, azimuth".into(),
            format!("{} deg", signed(b.tilt_azi_rad.to_degrees(), 4)),
        ),
        ("bit torque".into(), torque_unit.fmt(b.torque_nm, 2)),
        (
            "hook load".into(),
            if scope.no_surface_values {
                "not computed (bha)".into()
            } else {
                force_unit.fmt(res.hook_load_n, 1)
            },
        ),
        (
            "surface torque".into(),
            if scope.no_surface_values {
                "not computed (bha)".into()
            } else {
                torque_unit.fmt(res.surface_torque_nm, 2)
            },
        ),
    ];
    if let Some(c) = &scope.soft {
        kv.extend(soft_rows(c, units));
    }
    kv.extend([
        ("contact nodes".into(), contacts.len().to_string()),
        ("largest contact force".into(), force_unit.fmt(max_contact, 2)),
    ]);
    kv.push((
        "solver".into(),
        format!(
            "{} ({} iterations, {} factorizations, {:.3} s)",
            if converged { "converged" } else { "NOT converged" },
            stats.iterations,
            stats.factorizations,
            stats.seconds
        ),
    ));
    kv.push((
        "equilibrium error".into(),
        format!(
            "{:.1e} of the largest force",
            res.force_imbalance_n.norm() / res.largest_force_n.max(1.0)
        ),
    ));
    page.key_values(&kv);
}

/// The key-result rows of the soft string beside the stiff solve `c`.
fn soft_rows(c: &SoftComparison, units: UnitSystem) -> [(String, String); 4] {
    let (depth_unit, force_unit, torque_unit) = (units.depth(), units.force(), units.torque());
    [
        (
            "soft-string hook load at this WOB (stiff - soft)".into(),
            format!(
                "{} ({})",
                force_unit.fmt(c.hook_load_n, 1),
                force_unit.fmt(c.hook_load_difference_n(), 1)
            ),
        ),
        (
            "soft-string surface torque (stiff - soft)".into(),
            format!(
                "{} ({})",
                torque_unit.fmt(c.surface_torque_nm, 2),
                torque_unit.fmt(c.surface_torque_difference_nm(), 2)
            ),
        ),
        (
            "soft string: helically buckled length, Mitchell's helical wall force".into(),
            format!(
                "{}, {}",
                depth_unit.fmt(c.helical_length_m, 1),
                force_unit.fmt(c.helical_wall_force_n, 2)
            ),
        ),
        (
            "soft string with the helix's drag (Mitchell): hook load, surface torque".into(),
            format!(
                "{}, {}",
                helical_drag_hook_load_text(c, force_unit),
                torque_unit.fmt(c.helical_drag_surface_torque_nm, 2)
            ),
        ),
    ]
}

/// The contact zones in the shown bottom of the string (bit at `bit_md_m`): runs of
/// neighbouring contact nodes, with their total and largest force.
fn contact_zones(page: &mut Page, case: &Case, bit_md_m: f64, contacts: &[&NodeResult], units: UnitSystem) {
    let (depth_unit, force_unit) = (units.depth(), units.force());
    let b_md = bit_md_m;
    let shown = shown_length_m(&case.string);
    let mut zones: Vec<Vec<&NodeResult>> = Vec::new();
    for n in contacts.iter().filter(|n| b_md - n.md_m < shown) {
        match zones.last_mut() {
            Some(z) if z.last().is_some_and(|p| (p.md_m - n.md_m).abs() < ZONE_GAP_M) => z.push(n),
            _ => zones.push(vec![n]),
        }
    }
    let near: Vec<Vec<String>> = zones
        .iter()
        .map(|z| {
            let (lo, hi) = (b_md - z[0].md_m, b_md - z[z.len() - 1].md_m);
            let total: f64 = z.iter().map(|n| n.contact_force_n).sum();
            let peak = z
                .iter()
                .copied()
                .fold(z[0], |a, n| if n.contact_force_n > a.contact_force_n { n } else { a });
            vec![
                if z.len() == 1 {
                    depth_unit.fmt(lo, 2)
                } else {
                    format!("{} - {}", depth_unit.fmt(lo, 2), depth_unit.fmt(hi, 2))
                },
                z.len().to_string(),
                force_unit.fmt(total, 2),
                force_unit.fmt(peak.contact_force_n, 2),
                format!(
                    "{:.0} deg",
                    crate::geometry::survey::degrees_in_turn(peak.contact_angle_deg, 0)
                ),
            ]
        })
        .collect();
    if !near.is_empty() {
        page.note("contact zones in the BHA (angle of the largest force: 0 = high side, 90 = right):");
        page.table(
            &[
                "above the bit".into(),
                "nodes".into(),
                "total normal force".into(),
                "largest".into(),
                "angle".into(),
            ],
            &near,
        );
    }
}

/// The charts along the string: contact force, BHA deflection, axial force with the buckling
/// marks, torque and stresses.
fn string_figures(
    page: &mut Page,
    case: &Case,
    res: &SolveResults,
    marks: &[Mark],
    scope: &ReportOptions,
) -> Result<(), String> {
    let units = scope.units;
    let (depth_unit, small_unit, force_unit, torque_unit, stress_unit) = (
        units.depth(),
        units.small_length(),
        units.force(),
        units.torque(),
        units.stress(),
    );
    let b = &res.bit;
    let md_label = format!("MD [{}]", depth_unit.label);
    let along = |f: &dyn Fn(&NodeResult) -> f64| -> Vec<(f64, f64)> {
        res.nodes.iter().map(|n| (depth_unit.show(n.md_m), f(n))).collect()
    };
    let contact = contact_force_chart(res, marks, depth_unit, force_unit).with_band(Band {
        name: WHIRL_SERIES.into(),
        spans: scope
            .whirl_md_m
            .iter()
            .map(|&(a, b)| (depth_unit.show(a), depth_unit.show(b)))
            .collect(),
        color: 2,
    });
    page.figure(
        "contact-force",
        &render(&contact)?,
        "normal force of the wall on the string at each node; where the string is helically buckled (shaded), the helix's wall force by Mitchell (r F^2/(4 EI) times the node's share of the string) for comparison; where a rotating string whirls (shaded), its wall friction keeps its torque and drag but not its push round the wall (docs/theory.md 7.5)",
    );

    let bha_len = shown_length_m(&case.string);
    let bha: Vec<_> = res.nodes.iter().filter(|n| b.md_m - n.md_m <= bha_len + 1e-9).collect();
    let x = |n: &NodeResult| depth_unit.show(b.md_m - n.md_m);
    for (id, title, dir, f) in [
        (
            "deflection-high",
            "BHA deflection in the hole: high side",
            "toward the high side",
            (|n: &NodeResult| n.disp_high_m) as fn(&NodeResult) -> f64,
        ),
        (
            "deflection-right",
            "BHA deflection in the hole: right side",
            "toward the right side",
            |n: &NodeResult| n.disp_right_m,
        ),
    ] {
        let mut c = Chart::new(
            title,
            &format!("distance from the bit [{}]", depth_unit.label),
            &format!("displacement {dir} [{}]", small_unit.label),
        )
        .with(Series::new(
            "wall (+ radial clearance)",
            bha.iter()
                .filter_map(|n| n.clearance_m.map(|c| (x(n), small_unit.show(c))))
                .collect(),
            Style::Thin,
            6,
        ))
        .with(Series::new(
            "wall (- radial clearance)",
            bha.iter()
                .filter_map(|n| n.clearance_m.map(|c| (x(n), -small_unit.show(c))))
                .collect(),
            Style::Thin,
            7,
        ))
        .with(Series::new(
            "string axis",
            bha.iter().map(|n| (x(n), small_unit.show(f(n)))).collect(),
            Style::LinePoints,
            0,
        ));
        c.zero_line = true;
        page.figure(
            id,
            &render(&c)?,
            &format!(
                "displacement of the string axis from the hole axis, exaggerated: {} across against {} along",
                small_unit.label, depth_unit.label
            ),
        );
    }

    page.figure(
        "axial-force",
        &render(&axial_force_chart(res, marks, depth_unit, force_unit))?,
        "effective axial force, negative is compression; shaded: buckled intervals (sinusoidal, helical); thin lines: the sinusoidal and helical onsets (Dawson-Paslay / Chen-Lin-Cheatham with the curved-hole wall load) drawn as compressive axial forces where the string is in compression (up to twice the largest compression): the string is buckled where the axial force is below them",
    );
    let torque = Chart::new("Torque", &md_label, &format!("torque [{}]", torque_unit.label)).with(Series::new(
        "torque",
        along(&|n| torque_unit.show(n.torque_nm)),
        Style::Line,
        2,
    ));
    page.figure("torque", &render(&torque)?, "torque carried by the string");
    let stress = Chart::new(
        "Bending stress and von Mises stress",
        &md_label,
        &format!("stress [{}]", stress_unit.label),
    )
    .with(Series::new(
        "bending stress",
        along(&|n| {
            let c = case.string.component_at((b.md_m - n.md_m).max(0.0));
            stress_unit.show(c.bending_stress_pa(n.bending_moment_nm))
        }),
        Style::Line,
        3,
    ))
    .with(Series::new(
        "von Mises",
        along(&|n| stress_unit.show(n.von_mises_pa)),
        Style::Line,
        4,
    ));
    page.figure(
        "bending-stress",
        &render(&stress)?,
        "bending stress M (OD/2)/I of the body section; von Mises at the outer fibre",
    );
    Ok(())
}

/// Build the report's HTML text.
fn html(
    case: &Case,
    res: &SolveResults,
    marks: &[Mark],
    stats: &SolveStats,
    converged: bool,
    scope: &ReportOptions,
) -> anyhow::Result<String> {
    solve_report(case, res, marks, stats, converged, scope)
        .map_err(|e| anyhow::anyhow!("internal error in the report: {e}"))
}

/// The HTML report of the solve `s` of `case`, in `units` (with a bent housing's tendencies
/// `steering`, or a rotary steerable system's `rss`, in the note at the top): the
/// whole string, or the stiff part of a `bha` or `hybrid` result from the bit to the coupling
/// point with the level's hook load and surface torque (hybrid) or none (bha). A `soft`
/// result has nothing stiff to draw: an error.
pub fn solve_html(
    case: &Case,
    s: &StringSolve,
    units: UnitSystem,
    steering: Option<&Steering>,
    rss: Option<&RssSteering>,
) -> anyhow::Result<String> {
    let lr = &s.level;
    let Some(part) = &lr.fem else {
        anyhow::bail!(
            "internal error: no stiff part to report for fidelity {}",
            lr.choice.level.name()
        );
    };
    // the bent housing's tendencies, as on stdout, then the warnings
    let mut warnings: String = steering
        .map(|st| {
            format!(
                " {}.",
                steering_line(st, units)
                    .trim()
                    .replacen("bent motor:", "Bent motor:", 1)
            )
        })
        .unwrap_or_default();
    if let Some(st) = rss {
        warnings.push_str(&format!(" {}.", rss_line(st, units).trim().replacen("rss", "RSS", 1)));
    }
    warnings.extend(s.warnings(case).iter().map(|w| format!(" WARNING: {w}.")));
    if lr.choice.level == Level::Whole {
        let options = ReportOptions {
            units,
            note: (!warnings.is_empty()).then(|| warnings.trim_start().to_string()),
            soft: s.soft_comparison,
            whirl_md_m: part.model.whirl_md_m.clone(),
            ..Default::default()
        };
        return html(case, &part.results, &s.marks, &part.stats, part.converged, &options);
    }
    let mut res = SolveResults {
        nodes: s.reported_nodes().to_vec(),
        ..part.results.clone()
    };
    let surface = match (lr.hook_load_n, lr.surface_torque_nm) {
        (Some(h), Some(t)) => {
            res.hook_load_n = h;
            res.surface_torque_nm = t;
            true
        }
        _ => false,
    };
    let shown = res
        .nodes
        .last()
        .map(|n| case.operation.bit_md_m - n.md_m)
        .unwrap_or(0.0);
    let note = format!(
        "Fidelity {}: stiff model of the bottom {} of the string only (cut {} above the bit, results shown up to the coupling point); {}",
        lr.choice.level.name(),
        units.depth().fmt(shown, 1),
        units.depth().fmt(lr.cut_m.unwrap_or(shown), 1),
        if surface {
            "hook load and surface torque from the soft string above the coupling point."
        } else {
            "no hook load or surface torque (use hybrid or whole)."
        }
    );
    let options = ReportOptions {
        units,
        note: Some(note + &warnings),
        no_surface_values: !surface,
        soft: s.soft_comparison,
        whirl_md_m: Vec::new(),
    };
    html(case, &res, s.stiff_marks(), &part.stats, lr.converged, &options)
}
