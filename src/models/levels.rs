//! Running a static string solve at a fidelity level ([`crate::case::fidelity`]): the soft
//! string, the stiff bottom-hole assembly cut where it lies on the wall, the two coupled
//! (`hybrid`), or the whole stiff string.
//!
//! The coupling of `hybrid` ([`stiff_extent`], [`soft_above`]): the stiff model holds the whole
//! bottom-hole assembly and the pipe three tangency lengths above it; the soft-string
//! integration starts at the coupling node there with `F = F_c + M_c^2/(2 EI)` (the FEM's
//! effective axial force, tension positive, plus the bending energy per length of the pipe
//! there) and `M = T_c` (the FEM's torque), and runs up the string above it with the same
//! friction, speeds and mud. Without axial motion and rotation the hook load is then
//! `sum w_b dTVD - WOB` up to the bending-energy terms of the stiff part (docs/theory.md 8.3,
//! 10.5 exact check (a)). The soft part is [`softstring::soft_string_stiff_contact`]: its wall
//! carries the lateral load with the normal force and the circumferential friction together,
//! as in the stiff model (docs/theory.md 4), so the torque above the cut is consistent with
//! the stiff part below. Against `whole`: tests/verification/fidelity.rs and
//! tests/verification/hybrid.rs (the example wells, and packed assemblies at the bottom of
//! 10-30 deg/30 m builds; docs/theory.md 8.3 has the measured table).

use crate::case::fidelity::{Choice, Level};
use crate::case::Case;
use crate::models::buckled_start;
use crate::models::buckling::{helical_runs, stiff_marks, unbuckled_helical_runs, Mark};
use crate::models::checks::locked_at_zero_wob;
use crate::models::fem::bha::{bha_model, default_cut_m, tangency_length_m};
use crate::models::fem::model::{Model, TopCondition};
use crate::models::fem::refine;
use crate::models::fem::results::{extract, BitResult, NodeResult, SolveResults};
use crate::models::fem::solve::helix;
use crate::models::fem::solve::toolface::solve_holding_toolface;
use crate::models::fem::solve::{solve_interior_point_from, Solution, SolveControls, SolveError, SolveStats};
use crate::models::softstring::{self, SoftStringInput, SoftStringResult};
use crate::models::whirl::whirl_intervals;
use crate::string::DrillString;
use std::time::Instant;

/// The part of `string` above `cut_m` from the bit, with positions measured from the cut
/// (the component crossing the cut shortened); empty if the string is not longer.
pub fn upper_part(string: &DrillString, cut_m: f64) -> DrillString {
    let mut components = Vec::new();
    for c in &string.components {
        if c.top_m() <= cut_m + 1e-9 {
            continue;
        }
        let mut c = c.clone();
        let bottom = c.bottom_m.max(cut_m);
        c.length_m = c.top_m() - bottom;
        c.bottom_m = bottom - cut_m;
        components.push(c);
    }
    DrillString { components }
}

/// The stiff part of a level's result.
pub struct FemPart {
    /// The model solved (whole string, or cut at the top).
    pub model: Model,
    /// Whether the solve converged.
    pub converged: bool,
    /// Solver statistics.
    pub stats: SolveStats,
    /// Post-processed results (for a cut model `hook_load_n` and `surface_torque_nm` are the
    /// axial force and torque at the cut).
    pub results: SolveResults,
    /// Index of the coupling node of a cut model ([`StiffExtent::coupling_m`]): the soft
    /// string of `hybrid` takes over there and the stiff results are reported up to it. None
    /// for a model of the whole string.
    pub coupling: Option<usize>,
}

/// The result of one solve at a fidelity level, SI. Values a level does not compute are None.
pub struct LevelResult {
    /// The level and why.
    pub choice: Choice,
    /// Stiff part (bha, hybrid, whole).
    pub fem: Option<FemPart>,
    /// Soft-string part: the whole string (soft) or from the cut up (hybrid).
    pub soft: Option<SoftStringResult>,
    /// Cut distance above the bit of the stiff part, m (bha, hybrid; None when the string is
    /// not longer than the cut and the stiff part is the whole string).
    pub cut_m: Option<f64>,
    /// Bit forces and tilt (not with soft).
    pub bit: Option<BitResult>,
    /// Weight on bit, N (always known: the input, or the soft string's with a hook-load input).
    pub wob_n: f64,
    /// Bit torque, N.m.
    pub bit_torque_nm: f64,
    /// Hook load, N (not with bha).
    pub hook_load_n: Option<f64>,
    /// Surface torque, N.m (not with bha).
    pub surface_torque_nm: Option<f64>,
    /// Whether every part converged (the soft string always does).
    pub converged: bool,
    /// Wall-clock time of the whole computation, s.
    pub seconds: f64,
}

/// Why a level could not run.
#[derive(Debug, thiserror::Error)]
pub enum FidelityError {
    /// The stiff solve failed.
    #[error(transparent)]
    Solve(#[from] SolveError),
    /// The combination is not supported.
    #[error("{0}")]
    Unsupported(String),
}

/// Cut distance above the bit for `case` (the rule of [`crate::models::fem::bha`]).
pub fn cut_for(case: &Case) -> f64 {
    let md = case.operation.bit_md_m;
    default_cut_m(
        &case.string,
        case.well.hole.diameter_at(md),
        case.well.path.point_at(md).inc_rad,
        case.mud.density_kg_m3,
    )
}

/// Tangency lengths of the pipe above the bottom-hole assembly kept between the assembly's top
/// and the coupling point of `hybrid`, and again between the coupling point and its cut.
pub const HYBRID_TANGENCY_LENGTHS: f64 = 3.0;

/// Where the stiff part of a cut level ends, m from the bit.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StiffExtent {
    /// The cut (the stiff model's top), m from the bit.
    pub cut_m: f64,
    /// The coupling point, m from the bit: the soft string of `hybrid` starts there, and the
    /// stiff results are reported up to it (the cut's clamp disturbs them above).
    pub coupling_m: f64,
}

/// The stiff part of `level` for `case` (docs/theory.md 8.2, 8.3).
///
/// `bha` (and any level but `hybrid`): the cut of [`cut_for`], the coupling point half way
/// between the highest stabilizer and the cut; the cut's clamp disturbs the string within
/// about a tangency length below it, the bit forces depend on the string within a few above
/// the stabilizers.
///
/// `hybrid`: the same, but the coupling point at least [`HYBRID_TANGENCY_LENGTHS`] tangency
/// lengths `L_t` of the pipe above the bottom-hole assembly ([`DrillString::bha_length_m`])
/// above the assembly's top, and the cut at least as many above the coupling point (`L_t` at
/// the inclination and hole size there). A stiff assembly lying in a curved hole is bent: it
/// presses on the wall where it straightens and at its top, where the pipe above cannot carry
/// its bending moment, and its axial force changes by the bending energy it releases
/// (docs/theory.md 8.3); the soft string knows neither, so the stiff model holds the whole
/// assembly and hands over in the pipe above it. A string without pipe above its assembly
/// keeps the `bha` extent.
pub fn stiff_extent(case: &Case, level: Level) -> StiffExtent {
    let cut = cut_for(case);
    let s_stab = case
        .string
        .stabilizer_contacts_m()
        .into_iter()
        .fold(0.0, f64::max)
        .min(cut);
    let bha = StiffExtent {
        cut_m: cut,
        coupling_m: s_stab + 0.5 * (cut - s_stab),
    };
    if level != Level::Hybrid {
        return bha;
    }
    let top = case.string.bha_length_m();
    if top >= case.string.length_m() - 1e-9 {
        // no pipe above the assembly to hand over in
        return bha;
    }
    let md = case.operation.bit_md_m - top;
    let lt = tangency_length_m(
        case.string.component_at(top + 1e-6),
        case.well.hole.diameter_at(md),
        case.well.path.point_at(md).inc_rad,
        case.mud.density_kg_m3,
    );
    let coupling = top + HYBRID_TANGENCY_LENGTHS * lt;
    if coupling <= bha.coupling_m {
        return bha;
    }
    StiffExtent {
        cut_m: cut
            .max(coupling + HYBRID_TANGENCY_LENGTHS * lt)
            .min(case.string.length_m()),
        coupling_m: coupling,
    }
}

/// Index of the node of `model` nearest to `s_m` from the bit.
fn nearest_node(model: &Model, s_m: f64) -> usize {
    (0..model.nodes())
        .min_by(|&a, &b| {
            let da = (model.mesh.nodes[a].s_m - s_m).abs();
            let db = (model.mesh.nodes[b].s_m - s_m).abs();
            da.total_cmp(&db)
        })
        .unwrap_or(model.nodes() - 1)
}

fn fem_part(model: Model, case: &Case, ctl: &SolveControls, coupling_m: Option<f64>) -> Result<FemPart, SolveError> {
    // a whole string that finds no equilibrium is solved again from its buckled shape, unless
    // it cannot be put on bottom at any WOB (its answer is the lock-up, models::string_solve)
    let first = |m: &Model| {
        let locked = || whole_locked_at_zero_wob(case, m);
        let (sol, gave_up) = buckled_start::solve_damped_before_paths(case, m, ctl, locked)?;
        Ok(match gave_up {
            true => sol,
            false => buckled_start::solve_from_buckled_start(case, m, sol, ctl),
        })
    };
    let mut part = fem_part_by(model, case, ctl, coupling_m, first)?;
    for _ in 0..PITCH_REFINEMENTS {
        let Some(fine) = finer_for_pitch(case, &part) else {
            break;
        };
        let left = SolveControls {
            time_limit_s: ctl.time_limit_s - part.stats.seconds,
            ..*ctl
        };
        match fem_part_by(fine, case, &left, coupling_m, first) {
            Ok(mut again) if again.converged && again.results.equilibrium_error() <= HELIX_EQUILIBRIUM => {
                tracing::info!(
                    nodes = again.model.nodes(),
                    "solved again on a mesh that resolves the helix's pitch"
                );
                again.stats.add_work(&part.stats);
                part = again;
            }
            Ok(again) => {
                tracing::info!("no equilibrium on the mesh that resolves the helix's pitch: the coarser answer kept");
                part.stats.add_work(&again.stats);
                break;
            }
            Err(_) => break,
        }
    }
    Ok(part)
}

/// Whole-string solves afresh on meshes refined for the helix's pitch after the first
/// ([`finer_for_pitch`]): a refined answer's helix can reach pipe the coarser answer's did not,
/// and is refined once more there.
const PITCH_REFINEMENTS: usize = 2;

/// The whole-string model of the converged `part` (of `case`) with the elements of its
/// helically buckled pipe split to an eighth of the helix's pitch there
/// ([`helix::coarse_for_pitch`] at the solve's axial forces, [`refine::refined_model`]), where
/// any is longer; None where the mesh resolves the pitch, or for a cut model. An answer solved
/// on the coarse mesh keeps that mesh's equilibrium even when re-solved from its state on the
/// refined one (docs/performance.md, "Pipe mesh"), so the caller solves the refined model
/// afresh.
fn finer_for_pitch(case: &Case, part: &FemPart) -> Option<Model> {
    if !part.converged || matches!(part.model.top, TopCondition::Cut { .. }) {
        return None;
    }
    let nodes = &part.results.nodes;
    let marks = stiff_marks(case, &part.model, nodes);
    let (split, h) = coarse_for_helix_pitch(&part.model, nodes, &marks)?;
    Some(refine::refined_model(&part.model, &split, h))
}

/// The elements of a stiff model `model` in its helically buckled pipe (the runs of `marks`
/// beyond the helical onset, at the node results `nodes` from the bit) longer than an eighth of
/// the helix's pitch there, with that length (m): [`helix::coarse_for_pitch`] at the nodes'
/// axial forces. None where the mesh resolves the pitch.
pub fn coarse_for_helix_pitch(model: &Model, nodes: &[NodeResult], marks: &[Mark]) -> Option<(Vec<usize>, f64)> {
    let axial: Vec<f64> = nodes.iter().map(|n| n.axial_force_n).collect();
    helix::coarse_for_pitch(model, &axial, &helical_runs(marks))
}

/// Whether `model` is the whole string of `case` and the string cannot be put on bottom at any
/// WOB ([`locked_at_zero_wob`]): no whole-string equilibrium on bottom exists, and the WOB and
/// friction paths and the re-solves from the buckled shape could only end with the surface
/// pushing.
pub fn whole_locked_at_zero_wob(case: &Case, model: &Model) -> bool {
    !matches!(model.top, TopCondition::Cut { .. }) && locked_at_zero_wob(case)
}

/// The stiff part of `case` on `model` with its first solve by `first`: a bent housing held at
/// its toolface against the string's twist (a straight string is solved once), the contact
/// runs near the bit refined, a whole string taken off the straight branch where it is
/// compressed beyond the helical onset, and the results extracted.
pub(crate) fn fem_part_by(
    mut model: Model,
    case: &Case,
    ctl: &SolveControls,
    coupling_m: Option<f64>,
    first: impl FnOnce(&Model) -> Result<Solution, SolveError>,
) -> Result<FemPart, SolveError> {
    model.whirl_md_m = whirl_intervals(case, &model);
    let (model, sol) = if case.solver.refine_contacts {
        let h = refine::REFINED_FRACTION * case.solver.bha_element_length_m;
        refine::solve_refined_by(
            model,
            ctl,
            &refine::Scope::of(&case.string, case.solver.refine_runs),
            h,
            first,
        )?
    } else {
        let sol = solve_holding_toolface(&mut model, ctl, first)?;
        (model, sol)
    };
    let (model, sol) = if matches!(model.top, TopCondition::Cut { .. }) {
        (model, sol)
    } else {
        off_the_straight_branch(case, model, sol, ctl)
    };
    let results = extract(&model, &sol, case.mud.density_kg_m3);
    let coupling = coupling_m.map(|s| nearest_node(&model, s));
    Ok(FemPart {
        model,
        converged: sol.converged,
        stats: sol.stats,
        results,
        coupling,
    })
}

/// Relative equilibrium (force imbalance over the largest force) a buckled re-solve must meet.
pub const HELIX_EQUILIBRIUM: f64 = buckled_start::EQUILIBRIUM;

/// The converged solve `sol` of the whole-string model `model` of `case`, or, where it lies
/// straight in runs compressed beyond the helical onset
/// ([`crate::models::buckling::unbuckled_helical_runs`]), the re-solve from a helix along the
/// wall there ([`helix::solve_from_helix`]) if that converges with global equilibrium within
/// [`HELIX_EQUILIBRIUM`] of the largest force and penetration within the gap tolerance, and
/// leaves a shorter length of such runs (the buckled equilibrium). Before the re-solve, the
/// elements of the runs longer than an eighth of the helix pitch are split
/// ([`helix::coarse_for_pitch`], [`refine::refined_model`]) and the straight string solved
/// again on that mesh; the model returned is the one solved. The statistics add the first
/// solves' work and say whether the helix was tried and kept ([`SolveStats::helix_restart`]).
fn off_the_straight_branch(case: &Case, model: Model, sol: Solution, ctl: &SolveControls) -> (Model, Solution) {
    if !sol.converged {
        return (model, sol);
    }
    let results = extract(&model, &sol, case.mud.density_kg_m3);
    let straight = node_runs(case, &model, &results);
    if straight.is_empty() {
        return (model, sol);
    }
    let axial: Vec<f64> = results.nodes.iter().map(|n| n.axial_force_n).collect();
    let Some((split, h)) = helix::coarse_for_pitch(&model, &axial, &straight) else {
        let sol = buckled_or_straight(case, &model, sol, &straight, &axial, ctl);
        return (model, sol);
    };
    let fine = refine::refined_model(&model, &split, h);
    let start = refine::carried_state(&model, &sol.state, &fine);
    let mut consistent = fine.clone();
    consistent.consistent_tangent = true;
    let again = solve_interior_point_from(&consistent, start, ctl)
        .ok()
        .filter(|s| s.converged);
    let Some(mut again) = again else {
        let sol = buckled_or_straight(case, &model, sol, &straight, &axial, ctl);
        return (model, sol);
    };
    again.stats.continue_from(&sol.stats);
    let results = extract(&fine, &again, case.mud.density_kg_m3);
    let straight = node_runs(case, &fine, &results);
    let axial: Vec<f64> = results.nodes.iter().map(|n| n.axial_force_n).collect();
    let sol = if straight.is_empty() {
        again
    } else {
        buckled_or_straight(case, &fine, again, &straight, &axial, ctl)
    };
    (fine, sol)
}

/// The re-solve of the converged `sol` of `model` (of `case`) from a helix in the runs
/// `straight` ([`helix::solve_from_helix`], `axial` the effective axial forces there, N) if it
/// meets the acceptance of [`off_the_straight_branch`]; `sol` otherwise.
fn buckled_or_straight(
    case: &Case,
    model: &Model,
    mut sol: Solution,
    straight: &[(usize, usize)],
    axial: &[f64],
    ctl: &SolveControls,
) -> Solution {
    let left = SolveControls {
        time_limit_s: ctl.time_limit_s - sol.stats.seconds,
        ..*ctl
    };
    let length = |runs: &[(usize, usize)]| -> f64 {
        runs.iter()
            .map(|&(a, b)| model.mesh.nodes[b].s_m - model.mesh.nodes[a].s_m)
            .sum()
    };
    let accept = |h: &Solution| {
        if !h.converged || h.stats.max_penetration > ctl.gap_tolerance {
            return false;
        }
        let r = extract(model, h, case.mud.density_kg_m3);
        let eq = r.equilibrium_error();
        let rest = length(&node_runs(case, model, &r));
        tracing::info!(equilibrium = eq, straight_m = rest, "buckled re-solve converged");
        eq <= HELIX_EQUILIBRIUM && rest < length(straight)
    };
    let (kept, work) = helix::solve_from_helix(model, &sol.state, axial, straight, &left, accept);
    match kept {
        Some(mut h) => {
            // the kept solve's own work is in `work`
            h.stats = SolveStats {
                iterations: 0,
                factorizations: 0,
                seconds: 0.0,
                helix_restart: Some(true),
                wob_continuation_n: sol.stats.wob_continuation_n,
                friction_continuation: sol.stats.friction_continuation,
                reactive_turn: sol.stats.reactive_turn,
                buckled_start: sol.stats.buckled_start,
                ..h.stats
            };
            h.stats.add_work(&sol.stats);
            h.stats.add_work(&work);
            h
        }
        None => {
            sol.stats.add_work(&work);
            sol.stats.helix_restart = Some(false);
            sol
        }
    }
}

/// The runs of `results` (of `model`, the whole string of `case`) beyond the helical onset
/// where the string lies straight, as node index ranges (from the bit, inclusive).
fn node_runs(case: &Case, model: &Model, results: &SolveResults) -> Vec<(usize, usize)> {
    let marks = stiff_marks(case, model, &results.nodes);
    unbuckled_helical_runs(&marks, &results.nodes)
        .into_iter()
        .filter_map(|(top, bottom)| {
            let inside: Vec<usize> = (0..results.nodes.len())
                .filter(|&i| results.nodes[i].md_m >= top - 1e-9 && results.nodes[i].md_m <= bottom + 1e-9)
                .collect();
            Some((*inside.first()?, *inside.last()?))
        })
        .collect()
}

/// Run `case` at the level of `choice` with solver controls `ctl`.
pub fn run(case: &Case, choice: Choice, ctl: &SolveControls) -> Result<LevelResult, FidelityError> {
    run_with_progress(case, choice, ctl, &mut |_, _, _| {})
}

/// Number of stages [`run_with_progress`] reports for `level` (hybrid: the stiff bottom-hole
/// assembly, then the soft string above it).
pub fn stages(level: Level) -> usize {
    match level {
        Level::Hybrid => 2,
        _ => 1,
    }
}

/// [`run`], calling `on_stage(k, n, what)` when stage `k` (0-based) of `n` starts.
pub fn run_with_progress(
    case: &Case,
    choice: Choice,
    ctl: &SolveControls,
    on_stage: &mut dyn FnMut(usize, usize, &str),
) -> Result<LevelResult, FidelityError> {
    let t0 = Instant::now();
    let n = stages(choice.level);
    let op = &case.operation;
    let mut out = LevelResult::empty(choice, op.wob_n);
    match out.choice.level {
        Level::Soft => {
            on_stage(0, n, "soft string");
            let s = softstring::from_case(case, softstring::segment_length_m(&case.solver));
            out.wob_n = -s.points[0].tension_n;
            out.bit_torque_nm = s.points[0].torque_nm;
            out.hook_load_n = Some(s.hook_load_n);
            out.surface_torque_nm = Some(s.surface_torque_nm);
            out.soft = Some(s);
        }
        Level::Whole => {
            on_stage(0, n, "stiff whole string");
            out.fill_from_whole(fem_part(Model::from_case(case), case, ctl, None)?);
        }
        Level::Bha | Level::Hybrid => {
            if op.hook_load_n.is_some() {
                return Err(FidelityError::Unsupported(format!(
                    "fidelity `{}` needs the WOB as input (the hook load is given): use soft or whole",
                    out.choice.level.name()
                )));
            }
            let extent = stiff_extent(case, out.choice.level);
            on_stage(0, n, "stiff bottom-hole assembly");
            let model = bha_model(case, &case.well.path, &case.well.hole, op.bit_md_m, extent.cut_m);
            let is_cut = matches!(model.top, TopCondition::Cut { .. });
            let part = fem_part(model, case, ctl, is_cut.then_some(extent.coupling_m))?;
            out.fill_from_fem(&part);
            out.cut_m = is_cut.then_some(extent.cut_m);
            if let (Level::Hybrid, Some(k)) = (out.choice.level, part.coupling) {
                on_stage(1, n, "soft string above the coupling point");
                let s = soft_above(case, &part, k);
                out.hook_load_n = Some(s.hook_load_n);
                out.surface_torque_nm = Some(s.surface_torque_nm);
                out.soft = Some(s);
            } else if !is_cut {
                // the string is not longer than the cut: the stiff part is the whole string
                out.hook_load_n = Some(part.results.hook_load_n);
                out.surface_torque_nm = Some(part.results.surface_torque_nm);
            }
            out.fem = Some(part);
        }
    }
    out.seconds = t0.elapsed().as_secs_f64();
    Ok(out)
}

impl LevelResult {
    /// A result of `choice` at the WOB `wob_n` (N) with nothing computed yet.
    pub(crate) fn empty(choice: Choice, wob_n: f64) -> Self {
        LevelResult {
            choice,
            fem: None,
            soft: None,
            cut_m: None,
            bit: None,
            wob_n,
            bit_torque_nm: 0.0,
            hook_load_n: None,
            surface_torque_nm: None,
            converged: true,
            seconds: 0.0,
        }
    }

    fn fill_from_fem(&mut self, part: &FemPart) {
        self.bit = Some(part.results.bit);
        self.wob_n = part.results.bit.wob_n;
        self.bit_torque_nm = part.results.bit.torque_nm;
        self.converged = part.converged;
    }

    /// Fill from `part`, the stiff model of the whole string.
    pub(crate) fn fill_from_whole(&mut self, part: FemPart) {
        self.fill_from_fem(&part);
        self.hook_load_n = Some(part.results.hook_load_n);
        self.surface_torque_nm = Some(part.results.surface_torque_nm);
        self.fem = Some(part);
    }
}

/// Bending strain energy per length of the stiff part `part` at its node `k`, `M^2 / (2 EI)`
/// with the node's bending moment and the flexural rigidity of the element above it, N (J/m).
pub fn bending_energy_n(part: &FemPart, k: usize) -> f64 {
    let m = &part.model;
    let ei = m.mesh.elements[k.min(m.nodes() - 2)].ei;
    part.results.nodes[k].bending_moment_nm.powi(2) / (2.0 * ei)
}

/// The soft string from node `k` of the stiff part `part` (its coupling node) to the surface.
/// It starts with the torque there and, as its axial force, the FEM's effective axial force
/// plus the bending energy per length there ([`bending_energy_n`]): along a beam
/// `d/ds (F + M^2/(2 EI)) = -q.t`, the equation of the soft string's tension, so the bent
/// pipe's axial force rises by that energy where it straightens (docs/theory.md 8.3).
pub fn soft_above(case: &Case, part: &FemPart, k: usize) -> SoftStringResult {
    let m = &part.model;
    let upper = upper_part(&case.string, m.mesh.nodes[k].s_m);
    let op = &case.operation;
    let node = &part.results.nodes[k];
    softstring::soft_string_stiff_contact(&SoftStringInput {
        path: &case.well.path,
        hole: &case.well.hole,
        string: &upper,
        mud_density_kg_m3: case.mud.density_kg_m3,
        bit_md_m: m.md_ref[k],
        wob_n: -(node.axial_force_n + bending_energy_n(part, k)),
        bit_torque_nm: node.torque_nm,
        axial_speed_m_s: op.motion().axial_speed_m_s,
        omega_rad_s: op.motion().omega_rad_s,
        friction: op.friction,
        max_element_m: softstring::segment_length_m(&case.solver),
    })
}
