//! `solve` outputs at every fidelity level: `summary.json` and `string.csv` with the
//! interface's names (kN, kN.m, mm, deg, MPa). Values a level does not compute are `null` in
//! JSON and empty cells in CSV.

use super::{in_unit, num, Finite};
use crate::case::{Case, Level};
use crate::models::buckling::{summarize, Mark};
use crate::models::fem::results::NodeResult;
use crate::models::levels::LevelResult;
use crate::models::soft_comparison::SoftComparison;
use crate::models::softstring::SoftStringResult;
use crate::models::string_solve::StringSolve;
use crate::predict::steer::{RssSteering, SteadyTurn, Steering};
use crate::string::RssSteer;
use serde::Serialize;

/// Header of `string.csv`: the interface's columns.
pub const STRING_HEADER: &str = "md_m,north_m,east_m,tvd_m,disp_high_mm,disp_right_mm,clearance_mm,contact_force_kN,contact_angle_deg,axial_force_kN,torque_kNm,bending_moment_kNm,von_mises_MPa";

/// Columns appended to `string.csv` after the interface's (kN; empty where the component
/// cannot buckle).
pub const BUCKLING_COLUMNS: &str = "sinusoidal_onset_kN,helical_onset_kN,buckling";

/// Columns appended to `string.csv` after the buckling columns: the tilt of the string's axis
/// from the hole axis toward the high side and the right, deg (what a survey sensor at the
/// node reads above the hole's inclination and azimuth direction: the sag angle; empty for
/// soft-string rows).
pub const TILT_COLUMNS: &str = "tilt_high_deg,tilt_right_deg";

/// Columns appended to `string.csv` after the tilt columns: Mitchell's helical contact force
/// per length `r F^2 / (4 EI)` where the compression exceeds the helical onset (0 below it,
/// empty where the component cannot buckle), N/m: the wall force a helix adds
/// ([`crate::models::buckling::Mark::helical_wall_force_n_per_m`]).
pub const HELIX_COLUMNS: &str = "helical_wall_force_N_per_m";

/// Contacts reported in the summary: nodes with a normal force above this, N.
pub const CONTACT_THRESHOLD_N: f64 = 1.0;

/// How the buckling onsets are computed (the `buckling.onsets` text of `summary.json`).
pub const ONSETS_TEXT: &str = "Dawson-Paslay / Chen-Lin-Cheatham with the curved-hole wall load, vertical-hole floor 2.55 / 5.55 (EI w_b^2)^(1/3)";

/// The `bit` key.
#[derive(Serialize)]
#[allow(non_snake_case)]
struct BitJson {
    md_m: Finite,
    wob_kN: Finite,
    build_force_kN: Option<Finite>,
    walk_force_kN: Option<Finite>,
    tilt_inc_deg: Option<Finite>,
    tilt_azi_deg: Option<Finite>,
    torque_kNm: Finite,
}

/// The `surface` key.
#[derive(Serialize)]
#[allow(non_snake_case)]
struct SurfaceJson {
    hook_load_kN: Option<Finite>,
    torque_kNm: Option<Finite>,
}

/// One entry of the `contacts` key.
#[derive(Serialize)]
#[allow(non_snake_case)]
struct ContactJson {
    md_m: Finite,
    force_kN: Finite,
    angle_deg: Finite,
}

/// The `equilibrium` key of a stiff solve.
#[derive(Serialize)]
#[allow(non_snake_case)]
struct EquilibriumJson {
    force_imbalance_kN: Finite,
    moment_imbalance_kNm: Finite,
    largest_force_kN: Finite,
}

/// The `solver` key (the stiff solve's statistics; the soft string's have fewer keys).
#[derive(Serialize)]
struct SolverJson {
    converged: bool,
    iterations: usize,
    #[serde(skip_serializing_if = "Option::is_none")]
    factorizations: Option<usize>,
    dofs: usize,
    elements: usize,
    seconds: Finite,
    #[serde(skip_serializing_if = "Option::is_none")]
    final_residual: Option<Finite>,
    #[serde(skip_serializing_if = "Option::is_none")]
    max_penetration_rel: Option<Finite>,
    /// `blade` or `point` (`[solver] stabilizer_contact`); absent for the soft string.
    #[serde(skip_serializing_if = "Option::is_none")]
    stabilizer_contact: Option<&'static str>,
    /// Whether the solution came from the friction continuation; absent for the soft string.
    #[serde(skip_serializing_if = "Option::is_none")]
    friction_continuation: Option<bool>,
    /// True when the answer came from the re-solve from the buckled shape; absent otherwise.
    #[serde(skip_serializing_if = "Option::is_none")]
    buckled_start: Option<bool>,
    /// MD intervals `[top, bottom]` (m) where the rotating string whirls and its wall friction
    /// has no lateral push (`models::whirl`); absent when there are none.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    whirl_md_m: Vec<[Finite; 2]>,
}

/// The `fidelity` key: the level asked for and run, and what it does not compute.
#[derive(Serialize)]
struct FidelityJson {
    requested: &'static str,
    used: &'static str,
    reason: String,
    cut_m: Option<Finite>,
    coupling_m: Option<Finite>,
    surface_values_from: &'static str,
    not_computed: Vec<&'static str>,
    seconds: Finite,
}

/// One entry of `buckling.zones`.
#[derive(Serialize)]
struct ZoneJson {
    top_md_m: Finite,
    bottom_md_m: Finite,
    state: &'static str,
    max_compression_over_sinusoidal_onset: Finite,
}

/// The `buckling` key: model compared, buckled lengths, zones.
#[derive(Serialize)]
#[allow(non_snake_case)]
struct BucklingJson {
    axial_force_from: &'static str,
    onsets: &'static str,
    sinusoidal_length_m: Finite,
    helical_length_m: Finite,
    max_compression_kN: Finite,
    zones: Vec<ZoneJson>,
}

/// The `yield` key: the highest von Mises stress of the stiff part against the yield strength.
#[derive(Serialize)]
#[allow(non_snake_case)]
struct YieldJson {
    max_von_mises_MPa: Finite,
    at_md_m: Finite,
    yield_strength_MPa: Finite,
    yield_strength_assumed: bool,
    ratio: Finite,
    exceeded: bool,
}

/// The `lock_up` key: a hook load below zero on bottom.
#[derive(Serialize)]
#[allow(non_snake_case)]
struct LockUpJson {
    hook_load_kN: Finite,
    wob_kN: Finite,
    max_wob_kN: Finite,
    results_at_wob_kN: Option<Finite>,
    by_helical_drag: bool,
    helical_drag_diverges: bool,
    helical_top_md_m: Option<Finite>,
    helical_bottom_md_m: Option<Finite>,
    results_at_largest_wob: bool,
    lock_up_depth_m: Option<Finite>,
    lock_up_depth_zero_wob_m: Option<Finite>,
    results_without_helical_drag: bool,
    results_without_hook_load: bool,
    running_in: bool,
    results_from_soft_string: bool,
}

/// The `soft_string_comparison` key: the soft string at the same WOB beside a `whole` or
/// `hybrid` solve (stiff minus soft: negative hook load difference = more drag in the stiff
/// string).
#[derive(Serialize)]
#[allow(non_snake_case)]
struct SoftComparisonJson {
    wob_kN: Finite,
    hook_load_kN: Finite,
    surface_torque_kNm: Finite,
    helical_length_m: Finite,
    helical_wall_force_kN: Finite,
    helical_drag_hook_load_kN: Finite,
    helical_drag_surface_torque_kNm: Finite,
    helical_drag_diverges: bool,
    hook_load_difference_kN: Finite,
    surface_torque_difference_kNm: Finite,
}

impl SoftComparisonJson {
    fn of(c: &SoftComparison) -> SoftComparisonJson {
        SoftComparisonJson {
            wob_kN: Finite(c.wob_n / 1e3),
            hook_load_kN: Finite(c.hook_load_n / 1e3),
            surface_torque_kNm: Finite(c.surface_torque_nm / 1e3),
            helical_length_m: Finite(c.helical_length_m),
            helical_wall_force_kN: Finite(c.helical_wall_force_n / 1e3),
            helical_drag_hook_load_kN: Finite(c.helical_drag_hook_load_n / 1e3),
            helical_drag_surface_torque_kNm: Finite(c.helical_drag_surface_torque_nm / 1e3),
            helical_drag_diverges: c.helical_drag_diverged(),
            hook_load_difference_kN: Finite(c.hook_load_difference_n() / 1e3),
            surface_torque_difference_kNm: Finite(c.surface_torque_difference_nm() / 1e3),
        }
    }
}

/// One entry of the `sensors` key: a survey sensor's sag angle.
#[derive(Serialize)]
struct SensorJson {
    component: String,
    sensor_to_bit_m: Finite,
    md_m: Finite,
    sag_deg: Finite,
    tilt_right_deg: Finite,
}

/// `summary.json` of `drillpath solve`.
#[derive(Serialize)]
pub struct SolveSummary {
    bit: BitJson,
    surface: SurfaceJson,
    contacts: Vec<ContactJson>,
    equilibrium: Option<EquilibriumJson>,
    solver: SolverJson,
    fidelity: FidelityJson,
    buckling: BucklingJson,
    notes: Vec<String>,
    #[serde(rename = "yield")]
    yield_check: Option<YieldJson>,
    lock_up: Option<LockUpJson>,
    warnings: Vec<String>,
    sensors: Vec<SensorJson>,
    motor_yield_deg_per_30m: Option<Finite>,
    rotating_tendency_deg_per_30m: Option<TurnRateJson>,
    steering: Option<SteeringJson>,
    rss_dogleg_deg_per_30m: Option<Finite>,
    rss: Option<RssJson>,
    soft_string_comparison: Option<SoftComparisonJson>,
}

/// A dogleg rate split into build and right turn, deg/30 m.
#[derive(Serialize)]
struct TurnRateJson {
    build: Finite,
    right: Finite,
}

impl TurnRateJson {
    fn of(t: &SteadyTurn) -> TurnRateJson {
        TurnRateJson {
            build: Finite(t.build_rad_per_m.to_degrees() * 30.0),
            right: Finite(t.right_rad_per_m.to_degrees() * 30.0),
        }
    }
}

/// The `steering` key: the bent housing and how its tendencies were computed.
#[derive(Serialize)]
#[allow(non_snake_case)]
struct SteeringJson {
    bend_angle_deg: Finite,
    bend_to_bit_m: Finite,
    toolface_deg: Finite,
    toolface_reference: &'static str,
    motor_yield_toolface_deg: Option<Finite>,
    motor_yield_rate_deg_per_30m: Option<TurnRateJson>,
    rotating_toolfaces: usize,
    not_computed: Option<String>,
    reactive_torque_kNm: Option<Finite>,
    reactive_toolface_turn_deg: Option<Finite>,
    effective_toolface_deg: Option<Finite>,
    reactive_torque_held_m: Option<Finite>,
}

/// The `rss` key: the rotary steerable system and its steering tendency.
#[derive(Serialize)]
#[allow(non_snake_case)]
struct RssJson {
    rss_type: &'static str,
    pad_force_kN: Option<Finite>,
    pad_position_m: Option<Finite>,
    deflection_angle_deg: Option<Finite>,
    hinge_position_m: Option<Finite>,
    ratio: Finite,
    toolface_deg: Finite,
    toolface_reference: &'static str,
    rate_deg_per_30m: Option<TurnRateJson>,
    dogleg_toolface_deg: Option<Finite>,
    not_computed: Option<String>,
}

/// The `buckling` key of `marks`, whose axial force comes from `model`.
fn buckling_json(marks: &[Mark], model: &'static str) -> BucklingJson {
    let b = summarize(marks);
    BucklingJson {
        axial_force_from: model,
        onsets: ONSETS_TEXT,
        sinusoidal_length_m: Finite(b.sinusoidal_length_m),
        helical_length_m: Finite(b.helical_length_m),
        max_compression_kN: Finite(b.max_compression_n / 1e3),
        zones: b
            .zones
            .iter()
            .map(|z| ZoneJson {
                top_md_m: Finite(z.top_md_m),
                bottom_md_m: Finite(z.bottom_md_m),
                state: z.state.name(),
                max_compression_over_sinusoidal_onset: Finite(z.max_ratio),
            })
            .collect(),
    }
}

/// Where the surface values of `lr` come from, and what its level does not compute.
fn scope(lr: &LevelResult) -> (&'static str, Vec<&'static str>) {
    let whole_stiff = matches!(lr.choice.level, Level::Bha | Level::Hybrid) && lr.cut_m.is_none();
    match lr.choice.level {
        _ if whole_stiff => ("stiff whole string (not longer than the cut)", vec![]),
        Level::Soft => (
            "soft string",
            vec![
                "bit build and walk force",
                "bit tilt",
                "contacts",
                "bending moment",
                "von Mises stress",
            ],
        ),
        Level::Bha => (
            "not computed (the stiff model ends at the cut)",
            vec!["hook load", "surface torque", "string above the coupling point"],
        ),
        Level::Hybrid => (
            "soft string from the coupling point up, started from the stiff model's axial force (plus the bending energy of the pipe there) and torque",
            vec!["bending, contacts and stresses above the coupling point"],
        ),
        Level::Whole => ("stiff whole string", vec![]),
    }
}

fn fidelity_json(s: &StringSolve) -> FidelityJson {
    let lr = &s.level;
    let (surface, missing) = scope(lr);
    FidelityJson {
        requested: lr.choice.requested.name(),
        used: lr.choice.level.name(),
        reason: lr.choice.reason.clone(),
        cut_m: in_unit(lr.cut_m, 1.0),
        coupling_m: in_unit(s.coupling_m, 1.0),
        surface_values_from: surface,
        not_computed: missing,
        seconds: Finite(lr.seconds),
    }
}

fn solver_json(case: &Case, lr: &LevelResult) -> SolverJson {
    match &lr.fem {
        Some(p) => SolverJson {
            converged: p.converged,
            iterations: p.stats.iterations,
            factorizations: Some(p.stats.factorizations),
            dofs: p.model.dofs(),
            elements: p.model.nodes() - 1,
            seconds: Finite(lr.seconds),
            final_residual: Some(Finite(*p.stats.residual_history.last().unwrap_or(&0.0))),
            max_penetration_rel: Some(Finite(p.stats.max_penetration)),
            stabilizer_contact: Some(case.solver.stabilizer_contact.name()),
            friction_continuation: Some(p.converged && p.stats.friction_continuation.is_some()),
            buckled_start: (p.converged && p.stats.buckled_start == Some(true)).then_some(true),
            whirl_md_m: p
                .model
                .whirl_md_m
                .iter()
                .map(|&(a, b)| [Finite(a), Finite(b)])
                .collect(),
        },
        None => SolverJson {
            converged: true,
            iterations: 0,
            factorizations: None,
            dofs: 0,
            elements: lr.soft.as_ref().map(|s| s.points.len().saturating_sub(1)).unwrap_or(0),
            seconds: Finite(lr.seconds),
            final_residual: None,
            max_penetration_rel: None,
            stabilizer_contact: None,
            friction_continuation: None,
            buckled_start: None,
            whirl_md_m: Vec::new(),
        },
    }
}

/// Name of the model whose axial force the buckling marks of `level` compare.
fn axial_force_model(level: Level) -> &'static str {
    match level {
        Level::Soft => "soft string",
        Level::Bha => "stiff FEM below the coupling point",
        Level::Hybrid => "stiff FEM below the coupling point, soft string above",
        Level::Whole => "stiff FEM",
    }
}

impl SolveSummary {
    /// The summary of the solve `s` of `case`.
    pub fn new(case: &Case, s: &StringSolve) -> SolveSummary {
        let lr = &s.level;
        let bit = lr.bit;
        SolveSummary {
            bit: BitJson {
                md_m: Finite(case.operation.bit_md_m),
                wob_kN: Finite(lr.wob_n / 1e3),
                build_force_kN: in_unit(bit.map(|b| b.build_force_n), 1e3),
                walk_force_kN: in_unit(bit.map(|b| b.walk_force_n), 1e3),
                tilt_inc_deg: bit.map(|b| Finite(b.tilt_inc_rad.to_degrees())),
                tilt_azi_deg: bit.map(|b| Finite(b.tilt_azi_rad.to_degrees())),
                torque_kNm: Finite(lr.bit_torque_nm / 1e3),
            },
            surface: SurfaceJson {
                hook_load_kN: in_unit(lr.hook_load_n, 1e3),
                torque_kNm: in_unit(lr.surface_torque_nm, 1e3),
            },
            contacts: s
                .reported_nodes()
                .iter()
                .filter(|n| n.contact_force_n > CONTACT_THRESHOLD_N)
                .map(|n| ContactJson {
                    md_m: Finite(n.md_m),
                    force_kN: Finite(n.contact_force_n / 1e3),
                    angle_deg: Finite(n.contact_angle_deg),
                })
                .collect(),
            equilibrium: lr.fem.as_ref().map(|p| EquilibriumJson {
                force_imbalance_kN: Finite(p.results.force_imbalance_n.norm() / 1e3),
                moment_imbalance_kNm: Finite(p.results.moment_imbalance_nm.norm() / 1e3),
                largest_force_kN: Finite(p.results.largest_force_n / 1e3),
            }),
            solver: solver_json(case, lr),
            fidelity: fidelity_json(s),
            buckling: buckling_json(&s.marks, axial_force_model(lr.choice.level)),
            notes: s.notes.clone(),
            yield_check: s.yield_check.map(|y| YieldJson {
                max_von_mises_MPa: Finite(y.von_mises_pa / 1e6),
                at_md_m: Finite(y.md_m),
                yield_strength_MPa: Finite(y.yield_strength_pa / 1e6),
                yield_strength_assumed: y.assumed,
                ratio: Finite(y.ratio()),
                exceeded: y.exceeded(),
            }),
            lock_up: s.lock_up.map(|l| LockUpJson {
                hook_load_kN: Finite(l.hook_load_n / 1e3),
                wob_kN: Finite(l.wob_n / 1e3),
                max_wob_kN: Finite(l.max_wob_n / 1e3),
                results_at_wob_kN: l.results_at_wob_n.map(|w| Finite(w / 1e3)),
                by_helical_drag: l.by_helix,
                helical_drag_diverges: l.helical_drag_diverged(),
                helical_top_md_m: l.helical_md_m.map(|(top, _)| Finite(top)),
                helical_bottom_md_m: l.helical_md_m.map(|(_, bottom)| Finite(bottom)),
                results_at_largest_wob: l.results_at_largest_wob,
                lock_up_depth_m: l.depths.and_then(|d| d.at_wob_md_m).map(Finite),
                lock_up_depth_zero_wob_m: l.depths.and_then(|d| d.at_zero_wob_md_m).map(Finite),
                results_without_helical_drag: l.results_without_helical_drag,
                results_without_hook_load: l.results_without_hook_load,
                results_from_soft_string: l.results_from_soft_string,
                running_in: l.running_in,
            }),
            warnings: s.warnings(case),
            motor_yield_deg_per_30m: None,
            rotating_tendency_deg_per_30m: None,
            steering: None,
            rss_dogleg_deg_per_30m: None,
            rss: None,
            soft_string_comparison: s.soft_comparison.as_ref().map(SoftComparisonJson::of),
            sensors: s
                .sensors
                .iter()
                .map(|x| SensorJson {
                    component: x.component.clone(),
                    sensor_to_bit_m: Finite(x.sensor_to_bit_m),
                    md_m: Finite(x.md_m),
                    sag_deg: Finite(x.sag_rad.to_degrees()),
                    tilt_right_deg: Finite(x.tilt_right_rad.to_degrees()),
                })
                .collect(),
        }
    }
}

impl SolveSummary {
    /// The summary with the bent housing's tendencies `steering` (None: a straight string,
    /// whose `motor_yield_deg_per_30m`, `rotating_tendency_deg_per_30m` and `steering` are null).
    pub fn with_steering(mut self, steering: Option<&Steering>) -> SolveSummary {
        let Some(st) = steering else {
            return self;
        };
        let ok = st.tendencies.as_ref().ok();
        self.motor_yield_deg_per_30m = ok.map(|(y, _)| Finite(y.dogleg_rad_per_m().to_degrees() * 30.0));
        self.rotating_tendency_deg_per_30m = ok.map(|(_, r)| TurnRateJson::of(r));
        self.steering = Some(SteeringJson {
            bend_angle_deg: Finite(st.bend.angle_rad.to_degrees()),
            bend_to_bit_m: Finite(st.bend.to_bit_m),
            toolface_deg: Finite(st.toolface_rad.to_degrees()),
            toolface_reference: if st.magnetic { "magnetic" } else { "gravity" },
            motor_yield_toolface_deg: ok.map(|(y, _)| Finite(y.toolface_rad().to_degrees())),
            motor_yield_rate_deg_per_30m: ok.map(|(y, _)| TurnRateJson::of(y)),
            rotating_toolfaces: st.rotating_toolfaces,
            not_computed: st.tendencies.as_ref().err().cloned(),
            reactive_torque_kNm: st.reactive_turn.map(|t| Finite(t.torque_nm / 1e3)),
            reactive_toolface_turn_deg: st.reactive_turn.map(|t| Finite(t.turn_rad.to_degrees())),
            effective_toolface_deg: st.reactive_turn.map(|t| {
                Finite(crate::geometry::survey::degrees_in_turn(
                    (st.toolface_rad - t.turn_rad).to_degrees(),
                    crate::geometry::survey::FULL_PRECISION_DECIMALS,
                ))
            }),
            reactive_torque_held_m: st.reactive_turn.and_then(|t| t.held_m.map(Finite)),
        });
        self
    }
}

impl SolveSummary {
    /// The summary with the rotary steerable system's tendency `rss` (None: no RSS, whose
    /// `rss_dogleg_deg_per_30m` and `rss` are null).
    pub fn with_rss(mut self, rss: Option<&RssSteering>) -> SolveSummary {
        let Some(st) = rss else {
            return self;
        };
        let ok = st.tendency.as_ref().ok();
        self.rss_dogleg_deg_per_30m = ok.map(|t| Finite(t.dogleg_rad_per_m().to_degrees() * 30.0));
        let (force, pad, defl, hinge) = match st.tool.steer {
            RssSteer::PushTheBit {
                pad_force_n,
                pad_to_bit_m,
            } => (Some(Finite(pad_force_n / 1e3)), Some(Finite(pad_to_bit_m)), None, None),
            RssSteer::PointTheBit {
                deflection_rad,
                hinge_to_bit_m,
            } => (
                None,
                None,
                Some(Finite(deflection_rad.to_degrees())),
                Some(Finite(hinge_to_bit_m)),
            ),
        };
        self.rss = Some(RssJson {
            rss_type: st.tool.kind_name(),
            pad_force_kN: force,
            pad_position_m: pad,
            deflection_angle_deg: defl,
            hinge_position_m: hinge,
            ratio: Finite(st.tool.ratio),
            toolface_deg: Finite(st.toolface_rad.to_degrees()),
            toolface_reference: if st.magnetic { "magnetic" } else { "gravity" },
            rate_deg_per_30m: ok.map(TurnRateJson::of),
            dogleg_toolface_deg: ok.map(|t| Finite(t.toolface_rad().to_degrees())),
            not_computed: st.tendency.as_ref().err().cloned(),
        });
        self
    }
}

/// One `string.csv` row of a stiff node (interface columns; the clearance empty where the node
/// has no gap element).
fn node_row(n: &NodeResult) -> Result<String, String> {
    Ok([
        num(n.md_m, 3)?,
        num(n.position.x, 4)?,
        num(n.position.y, 4)?,
        num(n.position.z, 4)?,
        num(n.disp_high_m * 1e3, 3)?,
        num(n.disp_right_m * 1e3, 3)?,
        n.clearance_m.map(|c| num(c * 1e3, 3)).transpose()?.unwrap_or_default(),
        num(n.contact_force_n / 1e3, 4)?,
        num(crate::geometry::survey::degrees_in_turn(n.contact_angle_deg, 2), 2)?,
        num(n.axial_force_n / 1e3, 3)?,
        num(n.torque_nm / 1e3, 4)?,
        num(n.bending_moment_nm / 1e3, 4)?,
        num(n.von_mises_pa / 1e6, 3)?,
    ]
    .join(","))
}

/// The tilt cells of a stiff node.
fn tilt_cells(n: &NodeResult) -> Result<String, String> {
    Ok(format!(
        "{},{}",
        num(n.tilt_high_rad.to_degrees(), 5)?,
        num(n.tilt_right_rad.to_degrees(), 5)?
    ))
}

/// One `string.csv` row of a soft-string point (columns the soft string does not compute
/// left empty; the contact force is the wall load per length times the point's share of the
/// string).
fn soft_row(case: &Case, soft: &SoftStringResult, i: usize) -> Result<String, String> {
    let p = &soft.points[i];
    let pos = case.well.path.point_at(p.md_m).position;
    let lo = if i > 0 {
        (soft.points[i - 1].md_m - p.md_m).abs()
    } else {
        0.0
    };
    let up = soft.points.get(i + 1).map(|q| (p.md_m - q.md_m).abs()).unwrap_or(0.0);
    let contact = p.normal_force_per_m * 0.5 * (lo + up);
    Ok([
        num(p.md_m, 3)?,
        num(pos.x, 4)?,
        num(pos.y, 4)?,
        num(pos.z, 4)?,
        String::new(),
        String::new(),
        String::new(),
        num(contact / 1e3, 4)?,
        String::new(),
        num(p.tension_n / 1e3, 3)?,
        num(p.torque_nm / 1e3, 4)?,
        String::new(),
        String::new(),
    ]
    .join(","))
}

/// The buckling cells of a mark.
fn mark_cells(m: &Mark) -> Result<String, String> {
    let f = |x: Option<f64>| x.map(|v| num(v / 1e3, 3)).transpose().map(|v| v.unwrap_or_default());
    Ok(format!("{},{},{}", f(m.sinusoidal_n)?, f(m.helical_n)?, m.state.name()))
}

/// `string.csv` of the solve `s` of `case`: the stiff part's reported nodes from the bit up,
/// then the soft string's points above them, each with its buckling columns.
pub fn string_csv(case: &Case, s: &StringSolve) -> Result<String, String> {
    let mut rows = Vec::with_capacity(s.marks.len());
    let mut tilts = Vec::with_capacity(s.marks.len());
    for n in s.reported_nodes() {
        rows.push(node_row(n)?);
        tilts.push(tilt_cells(n)?);
    }
    if let Some(soft) = &s.level.soft {
        for i in usize::from(s.level.fem.is_some())..soft.points.len() {
            rows.push(soft_row(case, soft, i)?);
            tilts.push(",".to_string());
        }
    }
    if rows.len() != s.marks.len() {
        return Err(format!("{} rows but {} buckling marks", rows.len(), s.marks.len()));
    }
    let mut out = format!("{STRING_HEADER},{BUCKLING_COLUMNS},{TILT_COLUMNS},{HELIX_COLUMNS}\n");
    for ((row, m), tilt) in rows.iter().zip(&s.marks).zip(&tilts) {
        out.push_str(row);
        out.push(',');
        out.push_str(&mark_cells(m)?);
        out.push(',');
        out.push_str(tilt);
        out.push(',');
        if let Some(w) = m.helical_wall_force_n_per_m {
            out.push_str(&num(w, 2)?);
        }
        out.push('\n');
    }
    Ok(out)
}
