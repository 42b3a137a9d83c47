//! Static solution with contact by Newton iterations on the co-rotational model, the contact
//! forces of each step from an interior-point complementarity solve (`method = "newton"`).
//!
//! The bit is held on the hole axis at the bit MD; the hook load `H` at the top is an extra
//! unknown found with the equation "axial reaction at the bit = -WOB" (a bordered system solved
//! with two back-substitutions of the same factor). Friction enters the residual exactly and
//! is lagged in the tangent.

use crate::case::{Method, SolverSettings};
use crate::geometry::Vec3;
use crate::models::fem::linalg::band::{BandLdlt, BandMatrix, FactorError};
use crate::models::fem::linalg::band_lu::{BandLu, GeneralBand};
use crate::models::fem::model::StiffnessSink;
use crate::models::fem::model::{Evaluation, Model, State, HALF_BANDWIDTH};
use std::time::Instant;

/// Solver controls.
#[derive(Debug, Clone, Copy)]
pub struct SolveControls {
    /// Iteration limit.
    pub max_iterations: usize,
    /// Allowed penetration relative to the clearance (interface `tolerance`).
    pub gap_tolerance: f64,
    /// Residual tolerance relative to the load scale.
    pub residual_tolerance: f64,
    /// Contact scheme.
    pub method: Method,
    /// Paper scheme's alpha.
    pub alpha: f64,
}

impl SolveControls {
    /// Controls from a case's `[solver]` table (iteration limit, gap tolerance, scheme, alpha).
    pub fn from_settings(s: &SolverSettings) -> SolveControls {
        SolveControls {
            max_iterations: s.max_iterations,
            gap_tolerance: s.tolerance,
            method: s.method,
            alpha: s.alpha,
            ..SolveControls::default()
        }
    }
}

impl Default for SolveControls {
    fn default() -> Self {
        SolveControls {
            max_iterations: 300,
            gap_tolerance: 1e-4,
            residual_tolerance: 1e-7,
            method: Method::Newton,
            alpha: 0.7,
        }
    }
}

/// Globalization choices of one solve attempt (see [`solve_newton`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Strategy {
    /// Iterates remembered by the non-monotone line search (1: monotone).
    pub nonmonotone_memory: usize,
    /// Start the bottom-hole assembly off the wall instead of on the soft-string contact side.
    pub bha_open_start: bool,
}

/// Attempts made by [`solve_newton`], in order, each from a fresh start: the active-set iteration is
/// sensitive to its start and line search, and no single choice converges on every case.
pub const STRATEGIES: [Strategy; 4] = [
    Strategy {
        nonmonotone_memory: 1,
        bha_open_start: false,
    },
    Strategy {
        nonmonotone_memory: 8,
        bha_open_start: true,
    },
    Strategy {
        nonmonotone_memory: 8,
        bha_open_start: false,
    },
    Strategy {
        nonmonotone_memory: 1,
        bha_open_start: true,
    },
];

/// Statistics of a solve.
#[derive(Debug, Clone, Default)]
pub struct SolveStats {
    /// Iterations done.
    pub iterations: usize,
    /// Factorizations done.
    pub factorizations: usize,
    /// Residual norm (relative to the load scale) per iteration.
    pub residual_history: Vec<f64>,
    /// Largest penetration relative to the clearance at the end.
    pub max_penetration: f64,
    /// Wall-clock time, s.
    pub seconds: f64,
    /// Negative pivots in the last factor (unstable directions).
    pub negative_pivots: usize,
    /// Nodes whose contact state changed in the last iterations.
    pub chattering_nodes: Vec<usize>,
    /// Strategies tried (the last one is the one whose result is returned).
    pub attempts: usize,
}

/// A converged (or flagged unconverged) solution.
pub struct Solution {
    /// Final state.
    pub state: State,
    /// Evaluation at the final state.
    pub eval: Evaluation,
    /// Whether all convergence criteria were met.
    pub converged: bool,
    /// Statistics.
    pub stats: SolveStats,
}

/// Why a solve failed.
#[derive(Debug, thiserror::Error)]
pub enum SolveError {
    /// The requested contact scheme is not available yet.
    #[error("contact scheme `{0}` is not implemented yet; use method = \"newton\"")]
    NotImplemented(&'static str),
    /// The factorization met a zero pivot.
    #[error("singular stiffness at DOF {dof} (node {node} from the bit): {detail}")]
    Singular {
        /// DOF index.
        dof: usize,
        /// Node index from the bit.
        node: usize,
        /// Details.
        detail: String,
    },
}

/// Nodes closer than this to the bit start on the hole axis (not on the wall), m.
pub const START_OFF_WALL_M: f64 = 5.0;

/// A closed gap opens when its force is below minus this fraction of the load scale: a gap
/// that is just touching (force and gap both ~0) is accepted either way instead of cycling.
pub const RELEASE_FORCE_FRACTION: f64 = 1e-5;

/// Status changes after which a gap leaves the active-set logic for the unilateral law.
pub const MAX_STATUS_FLIPS: usize = 2;

/// Halvings tried by the line search.
pub const LINE_SEARCH_STEPS: usize = 8;

/// Largest lateral motion of a gap node per interior-point Newton step, in clearances.
pub const MAX_LATERAL_STEP_CLEARANCES: f64 = 2.0;

/// Largest bending rotation increment allowed per iteration, rad.
pub const MAX_BENDING_ROTATION_STEP: f64 = 0.02;

/// Load scale used for relative residuals: total buoyed weight plus WOB, N.
pub fn load_scale(model: &Model) -> f64 {
    let w: f64 = model
        .mesh
        .elements
        .iter()
        .zip(&model.sections)
        .map(|(e, s)| e.buoyed_weight_n_per_m.abs() * s.l0)
        .sum();
    w + model.loads.wob_n.abs() + model.loads.hook_load_n.unwrap_or(0.0).abs() + 1e3
}

/// Soft-string axial force of each element (tension positive), N: `-WOB` at the bit plus the
/// buoyed weight's axial part integrated upward on the hole axis between the nodes' MDs in
/// `state.md` (no friction).
fn soft_string_tension(model: &Model, state: &State) -> Vec<f64> {
    let mut tension = -model.loads.wob_n;
    let tangent: Vec<Vec3> = state.md.iter().map(|&md| model.path.axis_at(md).tangent).collect();
    (0..model.nodes() - 1)
        .map(|e| {
            let tbar = (tangent[e] + tangent[e + 1]).normalize();
            let w = model.mesh.elements[e].buoyed_weight_n_per_m * model.sections[e].l0;
            let mid = tension + 0.5 * w * tbar.z;
            tension += w * tbar.z;
            mid
        })
        .collect()
}

/// Stretched start: slide every node along the hole axis by the axial displacement of the
/// soft-string axial force (`u = sum N l0 / EA` from the bit, which stays put), with its triad
/// carried along the axis without twist (the parallel-transported frame at the new MD). A
/// string kilometres long stretches by metres (16 m on a 10 km string): started unstretched,
/// the Newton steps must slide it that far around the builds and across hole-size changes (a
/// node crossing a casing shoe meets a wall that jumps by centimetres), and their
/// bending-rotation and lateral caps make those steps short. The top node moves along its own
/// DOF basis axis only (its lateral DOFs are held). Only the start changes, not the solution.
/// Call it on a fresh [`Model::initial_state`] before [`soft_string_start`].
pub fn stretch_start(model: &Model, state: &mut State) {
    let nn = model.nodes();
    let tension = soft_string_tension(model, state);
    let mut u = 0.0;
    for i in 1..nn {
        let e = i - 1;
        let s = &model.sections[e];
        if s.ea > 0.0 {
            u += tension[e] * s.l0 / s.ea;
        }
        let md = model.md_ref[i] - u;
        let t0 = model.basis[i].column(0).into_owned();
        if i == nn - 1 {
            state.x[i] += t0 * (md - model.md_ref[i]);
            state.md[i] = model.path.nearest_md(&state.x[i], md);
            continue;
        }
        let (t, b1, b2) = model.path.bishop_at(md);
        state.x[i] = model.path.axis_at(md).position;
        state.md[i] = md;
        state.lam[i] = nalgebra::Matrix3::from_columns(&[t, b1, b2]);
        state.normal[i] = -model.path.frame_at(md).h;
    }
}

/// Soft-string start: axial force by integrating weight from the bit, contact side from the
/// lateral load of each element; nodes put on that side of the wall with the soft-string
/// normal force as their first multiplier (physics.md 4.5). Axis points at the nodes' MDs in
/// `state.md` (the reference MDs, or the stretched ones of [`stretch_start`]).
pub fn soft_string_start(model: &Model, state: &mut State, bha_open: bool) {
    let nn = model.nodes();
    let mut tension = -model.loads.wob_n;
    let mut load = vec![Vec3::zeros(); nn];
    let axis: Vec<_> = state.md.iter().map(|&md| model.path.axis_at(md)).collect();
    for e in 0..nn - 1 {
        let (p_lo, p_up) = (&axis[e], &axis[e + 1]);
        let w = model.mesh.elements[e].buoyed_weight_n_per_m * model.sections[e].l0;
        let tbar = (p_lo.tangent + p_up.tangent).normalize();
        let g = (p_lo.tangent - p_up.tangent) * tension + Vec3::new(0.0, 0.0, w);
        let gperp = g - tbar * g.dot(&tbar);
        load[e] += gperp * 0.5;
        load[e + 1] += gperp * 0.5;
        tension += w * tbar.z;
    }
    if model.loads.hook_load_n.is_none() {
        state.hook_load_n = tension.max(0.0);
    }
    for (i, li) in load.iter().enumerate() {
        // near the bit the stiff assembly lifts off the wall: leave those nodes on the axis
        // and the bottom-hole assembly starts off the wall (the active-set strategy closes
        // penetrating gaps many at a time, but opens them only a few at a time)
        let in_bha = model.mesh.nodes[i].s_m < model.bha_length_m;
        if !model.mesh.nodes[i].has_gap
            || li.norm() < 1e-6
            || model.mesh.nodes[i].s_m < START_OFF_WALL_M
            || (in_bha && bha_open)
        {
            continue;
        }
        let n = li.normalize();
        let eo = model.clearance(i, state.md[i]);
        state.x[i] = axis[i].position + n * eo;
        state.lambda[i] = li.norm();
        state.normal[i] = n;
    }
}

/// Torsional wind-up start: twist each node's triad about its hole tangent by the angle a
/// soft-string torque balance gives (bit torque, wall friction of the current multipliers,
/// mud drag), zero at the top where the twist is held. A rotating string several kilometres
/// long winds up by many radians; starting untwisted, the Newton steps must carry that rotation
/// and their bending-rotation cap makes them short. Only the start changes, not the solution.
pub fn wind_up_start(model: &Model, state: &mut State) {
    let nn = model.nodes();
    let omega = model.loads.omega_rad_s;
    // torque carried by element e (about -t), accumulated from the bit upward
    let mut torque = model.loads.bit_torque_nm;
    let mut twist_rate = vec![0.0; nn - 1];
    for (e, rate) in twist_rate.iter_mut().enumerate() {
        // node e is the lower end of element e
        let i = e;
        if omega > 0.0 && model.mesh.nodes[i].has_gap && model.friction[i] > 0.0 {
            let rc = model.mesh.nodes[i].contact_od_m / 2.0;
            let tangential = omega * rc;
            let speed = (tangential * tangential + model.loads.axial_speed_m_s.powi(2)).sqrt();
            if speed > 1e-12 {
                torque += model.friction[i] * state.lambda[i] * rc * tangential / speed;
            }
        }
        let l0 = model.sections[e].l0;
        let md = 0.5 * (model.md_ref[e] + model.md_ref[e + 1]);
        // half of the element's own drag counts at its centre
        let t_mid = torque + 0.5 * model.mud_torque(e, md) * l0;
        torque += model.mud_torque(e, md) * l0;
        let gj = model.sections[e].gj;
        *rate = if gj > 0.0 { t_mid / gj } else { 0.0 };
    }
    // twist about +t, zero at the top, decreasing toward the bit
    let mut phi = 0.0;
    for i in (0..nn - 1).rev() {
        phi -= twist_rate[i] * model.sections[i].l0;
        let t = state.lam[i].column(0).into_owned();
        state.lam[i] = crate::models::fem::element::rotation::exp_so3(&(t * phi)) * state.lam[i];
    }
}

/// Largest lateral slope of the smoothed start between neighbouring nodes (m of lateral offset
/// per m along the string), see [`smooth_start`].
pub const START_MAX_SLOPE: f64 = 0.005;

/// Smooth the soft-string start: the soft-string model puts each node on its own side of the
/// wall at its own clearance, so where the contact side flips (end of a build) or the
/// clearance jumps (a stabilizer between collars) neighbouring nodes sit centimetres apart
/// laterally on a 0.5-1 m element: the start then carries huge kinks (axial strains of 1%,
/// bending moments of MN.m) that the first Newton steps spend their time undoing. Here the
/// lateral offset of each node is limited to the offsets of its neighbours plus
/// [`START_MAX_SLOPE`] times their distance (and to zero where the side turns by more than
/// that allows), keeping each offset's direction. Multipliers are kept (they only seed
/// friction and the interior point). Only the start changes, not the solution.
pub fn smooth_start(model: &Model, state: &mut State) {
    let nn = model.nodes();
    let axis: Vec<_> = (0..nn).map(|i| model.path.axis_at(state.md[i]).position).collect();
    let mut a: Vec<f64> = (0..nn).map(|i| (state.x[i] - axis[i]).norm()).collect();
    let dir: Vec<Vec3> = (0..nn)
        .map(|i| {
            let d = state.x[i] - axis[i];
            if a[i] > 0.0 {
                d / a[i]
            } else {
                Vec3::zeros()
            }
        })
        .collect();
    let ds: Vec<f64> = (0..nn - 1).map(|e| model.sections[e].l0).collect();
    // a side change: both nodes leave the wall (the passes below ramp their neighbours)
    for (e, &l) in ds.iter().enumerate() {
        let (i, j) = (e, e + 1);
        if a[i] > 0.0 && a[j] > 0.0 {
            let jump = (dir[i] * a[i] - dir[j] * a[j]).norm() - (a[i] - a[j]).abs();
            if jump > START_MAX_SLOPE * l {
                a[i] = 0.0;
                a[j] = 0.0;
            }
        }
    }
    for (e, &l) in ds.iter().enumerate() {
        a[e + 1] = a[e + 1].min(a[e] + START_MAX_SLOPE * l);
    }
    for e in (0..nn - 1).rev() {
        a[e] = a[e].min(a[e + 1] + START_MAX_SLOPE * ds[e]);
    }
    for i in 0..nn {
        state.x[i] = axis[i] + dir[i] * a[i];
    }
}

/// Shift of the interior-point warm start off the boundary, per unit of outer residual:
/// multipliers get `+ shift * load_scale / contacts`, slacks `+ shift * clearance`, with
/// `shift = clamp(IP_START_SHIFT * rn, 1e-6, 0.1)`.
pub const IP_START_SHIFT: f64 = 0.1;

/// Consecutive interior-point steps shorter than 1e-2 after which the contact subproblem of a
/// linearization far from the solution (inner tolerance above 1e-8) is left as it is.
pub const IP_STALL_STEPS: usize = 5;

/// Restarts of an interior-point solve stalled near the solution (inner tolerance at most 1e-8),
/// each from its warm start shifted [`IP_RESTART_SHIFT_FACTOR`] times farther off the
/// boundary. Restarting far from the solution too was tried: it discards the warm start's
/// contact set and made the outer iteration wander on the horizontal WOB case of
/// tests/extremes.rs (thousands of factorizations).
pub const IP_RESTARTS: usize = 2;

/// Growth of the warm-start shift at each interior-point restart.
pub const IP_RESTART_SHIFT_FACTOR: f64 = 100.0;

/// Outer residual (relative to the load scale) below which a full Newton step of the
/// interior-point Newton is expected to converge: the next evaluation is then made without
/// the tangent first (the converged one needs none), and redone with it if the expectation
/// fails. Newton converges quadratically here (e.g. 8e-3, 8e-5, 3e-8 on a 3,000 m string).
pub const LIKELY_CONVERGED_RESIDUAL: f64 = 1e-3;

/// After two Newton iterations, a full step is expected to converge only if the next residual
/// predicted from the last contraction (`rn^2 / rn_prev`) is below this many residual
/// tolerances (the cold BHA's 0.05, 7.6e-4, 5e-6: the step from 7.6e-4 is not probed).
pub const LIKELY_CONVERGED_FACTOR: f64 = 10.0;

/// Gap nodes with a clearance below this (m) get the whole wall as constraints of the
/// linearized contact problem ([`WALL_PLANES`] supporting planes of the hole circle, the
/// current wall's among them): the linearized gap bounds only the motion toward the current
/// wall, and the lateral step cap (two clearances, but at least [`LATERAL_CAP_FLOOR_M`] of
/// clearance) would let a stabilizer with a clearance of a millimetre move around or across
/// its hole and out through the wall by more than a clearance in one step. Wider gaps stay
/// within about a clearance of the wall under the cap.
pub const FAR_WALL_CLEARANCE_M: f64 = LATERAL_CAP_FLOOR_M;

/// Supporting planes of the hole circle per tight gap (see [`FAR_WALL_CLEARANCE_M`]); the
/// square leaves at most `1 / cos(pi / WALL_PLANES) - 1` of the clearance (41%) of penetration
/// (8 planes, 8%, needed more Newton iterations on the example wells, not fewer).
pub const WALL_PLANES: usize = 4;

/// Smallest clearance the lateral step cap counts with, m (a tighter gap would hold the whole
/// step to a fraction of a millimetre).
pub const LATERAL_CAP_FLOOR_M: f64 = 2e-3;

/// Net force of the residual allowed at convergence, in units of the residual tolerance (both
/// relative to the load scale): every entry below the tolerance is not enough when thousands
/// of nodes' small imbalances add up in the global equilibrium check.
pub const NET_FORCE_TOLERANCE: f64 = 1.0;

/// Interior-point iterations allowed per Newton step.
pub const MAX_IP_ITERATIONS: usize = 60;

/// Relative tolerance of the interior-point solve of one linearization whose outer residual
/// (relative to the load scale) is `rn`: `min(1e-2 rn, rn^2)`, never below 1e-10 (the exact
/// tolerance used at convergence).
fn ip_tolerance(rn: f64) -> f64 {
    (1e-2 * rn).min(rn * rn).max(1e-10)
}

/// Outer residual (relative to the load scale) below which an interior-point solve first
/// tries the active-set step (see `solve_ip_from`).
pub const ACTIVE_SET_RESIDUAL: f64 = 1e-3;

/// Distance from the boundary of the active-set step's start, and how far past it a pair may
/// end and still count as in its set: relative to the clearance (slacks) and to the load scale
/// per contact (multipliers).
pub const ACTIVE_SET_EPS: f64 = 1e-9;

/// Active-set steps tried per Newton step before the interior point takes over.
pub const ACTIVE_SET_TRIES: usize = 2;

/// Smallest force of a pair in the active set's start, per contact's share of the load scale:
/// a pair with less force (one just touching, at the end of a contact run) starts outside the
/// set.
pub const ACTIVE_SET_MIN_FORCE: f64 = 1e-3;

/// Largest step in (0, 1] keeping `r + a dr` and `s + a ds` positive, times `tau`
/// (fraction to the boundary).
fn step_to_boundary(r: &[f64], dr: &[f64], s: &[f64], ds: &[f64], tau: f64) -> f64 {
    let mut a: f64 = 1.0;
    for j in 0..r.len() {
        if dr[j] < 0.0 {
            a = a.min(-tau * r[j] / dr[j]);
        }
        if ds[j] < 0.0 {
            a = a.min(-tau * s[j] / ds[j]);
        }
    }
    a
}

/// Part of node `i`'s translation (`k0` = 0) or rotation (`k0` = 3) increment in `du` (node
/// basis) normal to the hole axis at the node's nearest axis point (its DOF basis axis for a
/// node without a gap): the lateral motion (m) and the bending rotation (rad) that the step caps
/// limit. Not the basis components 1-2 or 4-5: where the string has slid along a curved hole
/// the hole tangent is off the basis tangent (by 1 deg after 12 m of stretch in a
/// 2.5 deg/30 m build), so axial sliding would count as lateral motion and a twist increment
/// of a rotating string (radians per step on a string kilometres long) as bending.
fn increment_across(model: &Model, ev: &Evaluation, du: &[f64], i: usize, k0: usize) -> f64 {
    let q = &model.basis[i];
    let v = q * Vec3::new(du[model.dof(i, k0)], du[model.dof(i, k0 + 1)], du[model.dof(i, k0 + 2)]);
    let t = if model.mesh.nodes[i].has_gap {
        ev.axis[i].1
    } else {
        q.column(0).into_owned()
    };
    (v - t * t.dot(&v)).norm()
}

/// Merit of a state: squared residual over free DOFs plus the WOB equation, forces in N and
/// moments in N.m (1 m length scale).
fn merit(r: &[f64], constrained: &[usize], c: f64, bordered: bool) -> f64 {
    let m: f64 = r
        .iter()
        .enumerate()
        .filter(|(d, _)| !constrained.contains(d))
        .map(|(_, v)| v * v)
        .sum();
    if bordered {
        m + c * c
    } else {
        m
    }
}

/// Index of the entry of `r` largest in magnitude (0 for an empty `r`).
fn largest_entry(r: &[f64]) -> usize {
    r.iter()
        .enumerate()
        .max_by(|a, b| a.1.abs().total_cmp(&b.1.abs()))
        .map(|(d, _)| d)
        .unwrap_or(0)
}

/// Largest residual entry relative to the load scale.
pub(crate) fn residual_norm(r: &[f64], scale: f64) -> f64 {
    r.iter().fold(0.0f64, |m, v| m.max(v.abs())) / scale
}

/// Where a gap node sits relative to the hole: outward unit normal (global; the previous one
/// when the node is on the axis), radial distance minus clearance, and the axis tangent.
pub(crate) struct GapGeometry {
    pub(crate) normal: Vec3,
    pub(crate) gap: f64,
    pub(crate) tangent: Vec3,
    pub(crate) radial: f64,
}

/// Gap geometry of node `i` from the axis point that the evaluation `ev` of `state` used
/// (its nearest axis point: no new search along the path).
fn gap_geometry(state: &State, ev: &Evaluation, i: usize) -> GapGeometry {
    let (position, tangent) = ev.axis[i];
    let d = state.x[i] - position;
    let d = d - tangent * tangent.dot(&d);
    let s = d.norm();
    let normal = if s > 1e-9 { d / s } else { state.normal[i] };
    GapGeometry {
        normal,
        gap: s - ev.clearance[i],
        tangent,
        radial: s,
    }
}

/// The global tangent and its factor: symmetric LDL^T, or LU when friction makes the
/// consistent tangent unsymmetric.
pub(crate) enum Linear {
    Symmetric(BandMatrix, BandLdlt),
    General(GeneralBand, BandLu),
}

impl Linear {
    /// LU when friction makes the consistent tangent unsymmetric, LDL^T otherwise.
    pub(crate) fn for_model(model: &Model) -> Linear {
        let n = model.dofs();
        if model.needs_unsymmetric() {
            Linear::General(GeneralBand::zeros(n, HALF_BANDWIDTH), BandLu::new(n, HALF_BANDWIDTH))
        } else {
            Linear::Symmetric(BandMatrix::zeros(n, HALF_BANDWIDTH), BandLdlt::new(n, HALF_BANDWIDTH))
        }
    }
    pub(crate) fn sink(&mut self) -> &mut dyn StiffnessSink {
        match self {
            Linear::Symmetric(k, _) => k,
            Linear::General(k, _) => k,
        }
    }
    pub(crate) fn get(&self, i: usize, j: usize) -> f64 {
        match self {
            Linear::Symmetric(k, _) => k.get(i, j),
            Linear::General(k, _) => k.get(i, j),
        }
    }
    fn constrain(&mut self, d: usize) {
        match self {
            Linear::Symmetric(k, _) => k.constrain_dof(d),
            Linear::General(k, _) => k.constrain_dof(d),
        }
    }
    fn factor(&mut self) -> Result<(), FactorError> {
        match self {
            Linear::Symmetric(k, f) => f.factor(k),
            Linear::General(k, f) => f.factor(k),
        }
    }
    pub(crate) fn solve(&self, x: &mut [f64]) {
        match self {
            Linear::Symmetric(_, f) => f.solve_in_place(x),
            Linear::General(_, f) => f.solve_in_place(x),
        }
    }
    /// What the interior point keeps of the assembled matrix (before constraints) while it
    /// factors modified copies: LU factors straight from this object's matrix in one
    /// streaming pass and needs no copy (`None`); LDL^T factors in place and needs one.
    fn keep_base(&self) -> Option<Linear> {
        match self {
            Linear::Symmetric(k, _) => Some(Linear::Symmetric(k.clone(), BandLdlt::new(1, 1))),
            Linear::General(..) => None,
        }
    }
    /// Replace the matrix with a stored copy.
    fn set_matrix(&mut self, from: &Linear) {
        match (self, from) {
            (Linear::Symmetric(k, _), Linear::Symmetric(f, _)) => k.copy_from(f),
            (Linear::General(k, _), Linear::General(f, _)) => k.copy_from(f),
            _ => unreachable!("matrix kinds match"),
        }
    }
    /// Factor the assembled matrix (the stored copy `base` from [`Linear::keep_base`], or this
    /// object's own when that is `None`) plus the same additions given two ways:
    /// `add_row(i, row)` adds to row `i` of the general band storage (column `c` at offset
    /// `c + hb - i`, `hb` the half-bandwidth), `add` assembles them as blocks; the DOFs
    /// `constrained` are held (row and column zeroed, diagonal `constraint_scale`). LU: one
    /// streaming pass, each row copied, changed and eliminated while in cache (the matrix is
    /// not changed); LDL^T: copy, assemble, factor (the matrix is left unspecified).
    fn factor_modified(
        &mut self,
        base: Option<&Linear>,
        constrained: &[usize],
        constraint_scale: f64,
        mut add_row: impl FnMut(usize, &mut [f64]),
        mut add: impl FnMut(&mut dyn StiffnessSink),
    ) -> Result<(), FactorError> {
        if let Linear::General(k, f) = &mut *self {
            let hb = HALF_BANDWIDTH;
            let k: &GeneralBand = match base {
                Some(Linear::General(b, _)) => b,
                _ => k,
            };
            // rows within the half-bandwidth of a constrained DOF (their column is zeroed), as
            // merged ranges (the constrained DOFs sit at the two ends of the chain: testing
            // one span from the first to the last would visit every row)
            let mut sorted = constrained.to_vec();
            sorted.sort_unstable();
            let mut near_rows: Vec<(usize, usize)> = Vec::new();
            for c in sorted {
                let (a, b) = (c.saturating_sub(hb), c + hb);
                match near_rows.last_mut() {
                    Some(last) if a <= last.1 + 1 => last.1 = last.1.max(b),
                    _ => near_rows.push((a, b)),
                }
            }
            return f.factor_rows(k, |i, row| {
                let near = near_rows.iter().any(|&(a, b)| a <= i && i <= b);
                if near && constrained.contains(&i) {
                    row.fill(0.0);
                    row[hb] = constraint_scale;
                    return;
                }
                add_row(i, row);
                if near {
                    for &c in constrained {
                        if c.abs_diff(i) <= hb {
                            row[c + hb - i] = 0.0;
                        }
                    }
                }
            });
        }
        self.set_matrix(base.expect("LDL^T keeps a copy of the matrix"));
        add(self.sink());
        for &d in constrained {
            self.constrain(d);
        }
        self.factor()
    }
    /// `y += A x` with the assembled matrix (`base`, or this object's own when `None`).
    fn matrix_mul_add(&self, base: Option<&Linear>, x: &[f64], y: &mut [f64], work: &mut Vec<f64>) {
        work.resize(x.len(), 0.0);
        match base.unwrap_or(self) {
            Linear::Symmetric(k, _) => k.mul_vec(x, work),
            Linear::General(k, _) => k.mul_vec(x, work),
        }
        for (yi, ti) in y.iter_mut().zip(work.iter()) {
            *yi += ti;
        }
    }
    /// Solve for two right-hand sides at once (LU: one pass over the factor).
    fn solve2(&self, x: &mut [f64], y: &mut [f64]) {
        match self {
            Linear::Symmetric(_, f) => {
                f.solve_in_place(x);
                f.solve_in_place(y);
            }
            Linear::General(_, f) => f.solve2_in_place(x, y),
        }
    }
    fn negative_pivots(&self) -> usize {
        match self {
            Linear::Symmetric(_, f) => f.negative_pivots(),
            Linear::General(..) => 0,
        }
    }
}

/// Row of the bit's axial DOF over the free columns (for the hook-load equation), the WOB
/// equation's residual `c`, and the residual with constrained entries zeroed.
pub(crate) fn bordered_parts(
    model: &Model,
    lin: &Linear,
    ev: &Evaluation,
    constrained: &[usize],
) -> (Vec<(usize, f64)>, f64, Vec<f64>) {
    let (c, r) = free_residual(model, ev, constrained);
    (bit_row(model, lin, constrained), c, r)
}

/// Newton step of the bordered system with the factored tangent in `lin`: `K du = -r` with
/// the hook-load column at the top axial DOF `top_ax` when `bordered` (the WOB equation
/// `kb . du = -c` fixes the hook-load change `dh`; two back-substitutions of the same factor),
/// else `K du = -r` alone with `dh = 0`. Returns `(du, dh)`.
pub(crate) fn bordered_step(
    lin: &Linear,
    r: &[f64],
    kb: &[(usize, f64)],
    c: f64,
    top_ax: usize,
    bordered: bool,
) -> (Vec<f64>, f64) {
    let mut a: Vec<f64> = r.iter().map(|v| -v).collect();
    lin.solve(&mut a);
    if !bordered {
        return (a, 0.0);
    }
    let mut b = vec![0.0; r.len()];
    b[top_ax] = 1.0;
    lin.solve(&mut b);
    let kba: f64 = kb.iter().map(|&(d, v)| v * a[d]).sum();
    let kbb: f64 = kb.iter().map(|&(d, v)| v * b[d]).sum();
    let dh = if kbb.abs() > 1e-30 { (c + kba) / kbb } else { 0.0 };
    (a.iter().zip(&b).map(|(x, y)| x - dh * y).collect(), dh)
}

/// Row of the bit's axial DOF of the assembled tangent over the free columns.
fn bit_row(model: &Model, lin: &Linear, constrained: &[usize]) -> Vec<(usize, f64)> {
    let bit_ax = model.dof(0, 0);
    (0..6)
        .map(|c| model.dof(0, c))
        .chain((0..6).map(|c| model.dof(1, c)))
        .filter(|d| !constrained.contains(d))
        .map(|d| (d, lin.get(bit_ax, d)))
        .collect()
}

/// The WOB equation's residual `c` (0 when the hook load is given) and the residual with
/// constrained entries zeroed.
fn free_residual(model: &Model, ev: &Evaluation, constrained: &[usize]) -> (f64, Vec<f64>) {
    let c = if model.loads.hook_load_n.is_none() {
        ev.residual[model.dof(0, 0)] + model.loads.wob_n
    } else {
        0.0
    };
    let mut r = ev.residual.clone();
    for &d in constrained {
        r[d] = 0.0;
    }
    (c, r)
}

/// Apply the boundary conditions to the tangent and factor it; a zero pivot becomes a
/// [`SolveError::Singular`] naming the node.
pub(crate) fn constrain_and_factor(model: &Model, lin: &mut Linear, constrained: &[usize]) -> Result<(), SolveError> {
    for &d in constrained {
        lin.constrain(d);
    }
    lin.factor().map_err(|e| singular(model, e))
}

/// A failed factorization as a [`SolveError::Singular`] naming the node.
fn singular(model: &Model, e: FactorError) -> SolveError {
    match e {
        FactorError::ZeroPivot { column: dof, pivot } => SolveError::Singular {
            dof,
            node: model.nodes() - 1 - dof / 6,
            detail: format!("zero pivot {pivot:e}"),
        },
    }
}

/// Solve the static problem from the model's initial state: first the interior-point contact
/// Newton ([`solve_ip_from`]) with the consistent tangent, then, if it fails, the active-set
/// [`STRATEGIES`] in turn and a load continuation; returns the last attempt (flagged
/// unconverged) if none converges.
pub fn solve_newton(model: &Model, ctl: &SolveControls) -> Result<Solution, SolveError> {
    let t0 = Instant::now();
    // 1. Newton with the fully consistent co-rotational tangent, each step solving the contact
    //    problem of all gaps by the interior-point method
    let mut consistent = model.clone();
    consistent.consistent_tangent = true;
    let mut state = model.initial_state();
    stretch_start(model, &mut state);
    soft_string_start(model, &mut state, false);
    smooth_start(model, &mut state);
    wind_up_start(model, &mut state);
    let mut sol = solve_ip_from(&consistent, state, ctl)?;
    sol.stats.attempts = 1;
    if sol.converged {
        sol.stats.seconds = t0.elapsed().as_secs_f64();
        return Ok(sol);
    }
    tracing::info!("interior-point contact Newton did not converge; trying the active-set strategies");
    // 2. fallbacks: active-set strategies, then load continuation, each with a shorter budget
    let ctl = &SolveControls {
        max_iterations: ctl.max_iterations.min(FALLBACK_MAX_ITERATIONS),
        ..*ctl
    };
    let mut total = sol.stats.iterations;
    let mut last = None;
    for (k, strategy) in STRATEGIES.iter().enumerate() {
        let mut state = model.initial_state();
        soft_string_start(model, &mut state, strategy.bha_open_start);
        let mut sol = solve_from(model, state, ctl, strategy)?;
        total += sol.stats.iterations;
        sol.stats.attempts = k + 2;
        let done = sol.converged;
        last = Some(sol);
        if done {
            break;
        }
        tracing::info!(attempt = k + 1, "solve did not converge; trying the next strategy");
    }
    let mut sol = last.expect("at least one strategy");
    if !sol.converged {
        // load continuation: WOB, bit torque and friction ramped from zero, each step warm
        // started from the last (contact states included)
        tracing::info!("trying load continuation");
        if let Some(mut cont) = solve_by_continuation(model, ctl)? {
            total += cont.stats.iterations;
            cont.stats.attempts = STRATEGIES.len() + 2;
            sol = cont;
        }
    }
    sol.stats.iterations = total;
    sol.stats.seconds = t0.elapsed().as_secs_f64();
    Ok(sol)
}

/// Iteration limit of each fallback attempt of [`solve_newton`] (active-set strategy, continuation
/// step) after the interior-point Newton failed. None of them has rescued a case since the
/// interior-point Newton became the default (the test suite, the example wells, the benchmark
/// wells and the failing extremes: inclination 120 and 180 deg, DLS 30 deg/30 m drilling,
/// WOB 1-3 x helical with friction), while with the full limit they made a failing solve take
/// a minute; the shorter budget keeps them as a last resort and fails in seconds.
pub const FALLBACK_MAX_ITERATIONS: usize = 100;

/// Load steps of the continuation fallback (fractions of WOB, bit torque and friction).
pub const CONTINUATION_STEPS: [f64; 6] = [0.0, 0.2, 0.4, 0.6, 0.8, 1.0];

/// Ramp WOB, bit torque and friction from zero, warm-starting each step (contact states
/// included). Returns the final solution if every step converged, `None` otherwise.
fn solve_by_continuation(model: &Model, ctl: &SolveControls) -> Result<Option<Solution>, SolveError> {
    let mut m = model.clone();
    let mut state = model.initial_state();
    soft_string_start(model, &mut state, false);
    let mut total = 0usize;
    let mut last = None;
    for &frac in &CONTINUATION_STEPS {
        m.loads.wob_n = model.loads.wob_n * frac;
        m.loads.bit_torque_nm = model.loads.bit_torque_nm * frac;
        m.friction = model.friction.iter().map(|f| f * frac).collect();
        let mut step = None;
        for strategy in [&STRATEGIES[0], &STRATEGIES[2]] {
            let sol = solve_from(&m, state.clone(), ctl, strategy)?;
            total += sol.stats.iterations;
            if sol.converged {
                step = Some(sol);
                break;
            }
        }
        tracing::info!(frac, converged = step.is_some(), "continuation step");
        match step {
            Some(sol) => {
                state = sol.state.clone();
                last = Some(sol);
            }
            None => return Ok(None),
        }
    }
    Ok(last.map(|mut s| {
        s.stats.iterations = total;
        s
    }))
}

/// Solve the static problem from `state` with one globalization `strategy`.
pub fn solve_from(
    model: &Model,
    mut state: State,
    ctl: &SolveControls,
    strategy: &Strategy,
) -> Result<Solution, SolveError> {
    let t0 = Instant::now();
    let mut lin = Linear::for_model(model);
    let constrained = model.constrained_dofs();
    let top = model.nodes() - 1;
    let bit_ax = model.dof(0, 0);
    let top_ax = model.dof(top, 0);
    let bordered = model.loads.hook_load_n.is_none();
    let scale = load_scale(model);
    let mut stats = SolveStats::default();
    let mut flips = vec![0usize; model.nodes()];
    let mut converged = false;
    let mut ev;
    // Active-set strategy: the contact status of every gap is held fixed while Newton solves
    // the (then smooth) problem, closed gaps acting as bilateral penalty springs; then gaps
    // whose force turned negative open and open gaps that penetrate close (primal-dual active
    // set, Hintermueller-Ito-Kunisch 2002), and the augmented-Lagrangian multipliers of closed
    // gaps are updated until the penetration is within tolerance.
    let mut newton_steps = 0usize;
    let mut merits: Vec<f64> = Vec::new();
    if state.closed.is_none() {
        let closed: Vec<bool> = (0..model.nodes())
            .map(|i| model.mesh.nodes[i].has_gap && state.lambda[i] > 0.0)
            .collect();
        state.closed = Some(closed);
    }
    loop {
        ev = model.evaluate(&mut state, Some(lin.sink()));
        // row of the bit axial DOF (free columns) before constraining
        let (kb, c, r) = bordered_parts(model, &lin, &ev, &constrained);
        let rn = residual_norm(&r, scale).max(c.abs() / scale);
        stats.residual_history.push(rn);
        let mut pen: f64 = 0.0;
        for (i, g) in ev.gaps.iter().enumerate() {
            if let Some(g) = g {
                let eo = ev.clearance[i].max(MIN_REFERENCE_CLEARANCE_M);
                let closed = state.closed.as_ref().is_some_and(|cl| cl[i]);
                let free = state.free_law.as_ref().is_some_and(|f| f[i]);
                if (closed && !free) || g.penetration > 0.0 {
                    pen = pen.max(g.penetration.abs() / eo);
                }
            }
        }
        stats.max_penetration = pen;
        if tracing::enabled!(tracing::Level::DEBUG) {
            // the largest residual entry: a scan over every DOF, made only for the log
            let worst = largest_entry(&r);
            tracing::debug!(
                worst_node = model.nodes() - 1 - worst / 6,
                worst_dof = worst % 6,
                iteration = stats.iterations,
                residual = rn,
                penetration = pen,
                hook_load = state.hook_load_n,
                "newton"
            );
        }
        if stats.iterations >= ctl.max_iterations {
            break;
        }
        if rn < ctl.residual_tolerance || (rn < 1e-2 && newton_steps >= 1) || newton_steps >= 6 {
            newton_steps = 0;
            // status update
            let mut changes = 0usize;
            let closed = state.closed.as_mut().expect("status set above");
            let free = state.free_law.get_or_insert_with(|| vec![false; model.nodes()]);
            for (i, g) in ev.gaps.iter().enumerate() {
                if let Some(g) = g {
                    if free[i] {
                        continue;
                    }
                    if flips[i] >= MAX_STATUS_FLIPS {
                        // a cycling gap: let Newton treat it with the unilateral law
                        free[i] = true;
                        changes += 1;
                        continue;
                    }
                    let eo = ev.clearance[i].max(MIN_REFERENCE_CLEARANCE_M);
                    if closed[i] && g.normal_force < -RELEASE_FORCE_FRACTION * scale {
                        tracing::trace!(s = model.mesh.nodes[i].s_m, force = g.normal_force, "open");
                        closed[i] = false;
                        changes += 1;
                        flips[i] += 1;
                    } else if !closed[i] && g.penetration > ctl.gap_tolerance * eo {
                        tracing::trace!(s = model.mesh.nodes[i].s_m, pen = g.penetration, "close");
                        closed[i] = true;
                        changes += 1;
                        flips[i] += 1;
                    }
                }
            }
            tracing::debug!(changes, "contact status update");
            if changes == 0 {
                if pen <= ctl.gap_tolerance && rn < ctl.residual_tolerance {
                    converged = true;
                    break;
                }
                // augmented-Lagrangian update of the closed (and freely switching) gaps
                for (i, g) in ev.gaps.iter().enumerate() {
                    if let Some(g) = g {
                        if ev.clearance[i] <= crate::models::fem::contact::gap::ZERO_CLEARANCE_M {
                            // pin: vector multiplier takes the whole current force
                            state.lambda_vec[i] = -g.force_normal();
                            continue;
                        }
                        if closed[i] || free[i] {
                            state.lambda[i] = g.normal_force.max(0.0);
                        }
                    }
                }
            }
            stats.iterations += 1;
            continue;
        }
        constrain_and_factor(model, &mut lin, &constrained)?;
        stats.factorizations += 1;
        stats.negative_pivots = lin.negative_pivots();
        let hook_before = state.hook_load_n;
        let (du, dh) = bordered_step(&lin, &r, &kb, c, top_ax, bordered);
        state.hook_load_n += dh;
        // cap lateral motion to one clearance per iteration (physics.md 4.5)
        let mut ratio: f64 = 0.0;
        for i in 0..model.nodes() {
            if model.mesh.nodes[i].has_gap {
                let lat = (du[model.dof(i, 1)].powi(2) + du[model.dof(i, 2)].powi(2)).sqrt();
                ratio = ratio.max(lat / ev.clearance[i].max(2e-3));
            }
        }
        // and bending rotations to a few hundredths of a radian (the string stays within the hole,
        // so large section rotations are never part of the solution)
        for i in 0..model.nodes() {
            let rot = (du[model.dof(i, 4)].powi(2) + du[model.dof(i, 5)].powi(2)).sqrt();
            ratio = ratio.max(rot / MAX_BENDING_ROTATION_STEP);
        }
        let mut alpha = if ratio > 1.0 { 1.0 / ratio } else { 1.0 };
        // backtracking line search on the residual norm (globalizes the semi-smooth Newton
        // step across contact switches)
        // non-monotone line search (Grippo et al. 1986): compare with the largest merit of
        // the last few iterates, so contact switches may raise the merit for a while
        let merit_now = merit(&ev.residual, &constrained, c, bordered);
        merits.push(merit_now);
        let merit0 = merits
            .iter()
            .rev()
            .take(strategy.nonmonotone_memory.max(1))
            .fold(0.0f64, |a, &b| a.max(b));
        let h0 = state.hook_load_n;
        let dh_total = state.hook_load_n - hook_before;
        let mut accepted = false;
        for _ in 0..LINE_SEARCH_STEPS {
            let mut trial = state.clone();
            trial.hook_load_n = hook_before + alpha * dh_total;
            model.update(&mut trial, &du, alpha);
            let tev = model.evaluate(&mut trial, None);
            let tc = if bordered {
                tev.residual[bit_ax] + model.loads.wob_n
            } else {
                0.0
            };
            let m1 = merit(&tev.residual, &constrained, tc, bordered);
            if m1 <= (1.0 - 1e-4 * alpha) * merit0 || merit0 < 1e-30 {
                state = trial;
                accepted = true;
                break;
            }
            alpha *= 0.5;
        }
        if !accepted {
            // take the (small) last step anyway so iterations can leave a stalled point
            state.hook_load_n = h0;
            state.hook_load_n = hook_before + alpha * dh_total;
            model.update(&mut state, &du, alpha);
        }
        tracing::debug!(alpha, cap = ratio, accepted, "step");
        newton_steps += 1;
        stats.iterations += 1;
    }
    stats.chattering_nodes = flips
        .iter()
        .enumerate()
        .filter(|(_, &f)| f > 3)
        .map(|(i, _)| i)
        .collect();
    stats.seconds = t0.elapsed().as_secs_f64();
    Ok(Solution {
        state,
        eval: ev,
        converged,
        stats,
    })
}

/// Smallest clearance the gap tolerance is measured against, m: a gap's penetration counts
/// relative to `max(clearance, this)`, and a pin's offset relative to this.
pub(crate) const MIN_REFERENCE_CLEARANCE_M: f64 = 1e-3;

/// Largest offset from the hole axis of the `pins` (zero-clearance gap nodes), m.
fn pin_offset_m(ev: &Evaluation, pins: &[usize]) -> f64 {
    pins.iter()
        .filter_map(|&i| ev.gaps[i].as_ref().map(|g| (g.penetration + ev.clearance[i]).max(0.0)))
        .fold(0.0, f64::max)
}

/// Outer residual (relative to the load scale) below which the interior-point Newton holds the
/// pins (zero-clearance gaps) exactly; above it they are penalty springs. Exact from the start,
/// a pin's force is the reaction to whatever lateral residual its neighbours carry, and its
/// friction (proportional to that force) made long rotating strings wander: the 10,000 m bench
/// string took 7-49 Newton iterations depending on its casing shoe depth (800-1,500 m),
/// against 10-12 with penalty pins and an augmented-Lagrangian phase, and 9-10 with this
/// switch. At the switch the Newton step prescribes the pins' lateral increments that take
/// them from the penalty's give (~15 um) onto the axis (moving the pins alone cost the cold BHA
/// solve an iteration: their neighbours' residual jumped); 0.3 brought the wandering back (17
/// iterations).
pub const PIN_EXACT_RESIDUAL: f64 = 0.1;

/// The model's held DOFs plus the lateral DOFs (basis 1 and 2) of the exact `pins`.
pub(crate) fn constrained_with_pins(model: &Model, pins: &[usize]) -> Vec<usize> {
    let mut constrained = model.constrained_dofs();
    for &i in pins {
        for k in 1..3 {
            if !constrained.contains(&model.dof(i, k)) {
                constrained.push(model.dof(i, k));
            }
        }
    }
    constrained
}

/// Linearization of the exact pins' friction (`State::exact_pins`): a pin's wall force `p`
/// is the reaction to the lateral residual `a = -(I - t t^T)(Q1 r1 + Q2 r2)` of everything
/// else (`p = M a`, [`Model::pin_reaction`]), and its friction force and moment depend on `p`
/// (`F = -p - (f/|v|)(v_a |p| t + Omega R_c t x p)`,
/// `M = -(f R_c/|v|)(v_a p x t + Omega R_c |p| t)`), so the pin node's rows of the residual get
/// `Q^T (dG/dp) M (Q1 K1 + Q2 K2)`, `K1, K2` the tangent's rows of the lateral DOFs. Only
/// with friction and motion (the unsymmetric tangent); the lateral rows themselves are held.
pub(crate) fn add_pin_coupling(model: &Model, lin: &mut Linear, ev: &Evaluation, state: &State, pins: &[usize]) {
    let Linear::General(k, _) = lin else {
        return;
    };
    let n = model.dofs();
    let (va, omega) = (model.loads.axial_speed_m_s, model.loads.omega_rad_s);
    for &i in pins {
        let f = model.friction[i];
        let rc = model.mesh.nodes[i].contact_od_m / 2.0;
        let spin = omega * rc;
        let speed = (va * va + spin * spin).sqrt();
        let p = state.lambda_vec[i];
        let pn = p.norm();
        if f <= 0.0 || speed <= 1e-12 || pn <= 1e-12 {
            continue;
        }
        let q = &model.basis[i];
        let t = ev.axis[i].1;
        let id = nalgebra::Matrix3::identity();
        let tx = t.cross_matrix();
        let fp = f * spin / speed;
        let mf = (id - t * t.transpose() - tx * fp) / (1.0 + fp * fp);
        let ph = p / pn;
        let dgf = -id - (t * ph.transpose() * va + tx * spin) * (f / speed);
        let dgm = -(t * ph.transpose() * spin - tx * va) * (f * rc / speed);
        let lat = nalgebra::Matrix3x2::from_columns(&[q.column(1).into_owned(), q.column(2).into_owned()]);
        let bf = q.transpose() * dgf * mf * lat;
        let bm = q.transpose() * dgm * mf * lat;
        let base = model.dof(i, 0);
        let rows = [(0, bf.row(0)), (3, bm.row(0)), (4, bm.row(1)), (5, bm.row(2))];
        for c in base.saturating_sub(6)..(base + 12).min(n) {
            let (k1, k2) = (k.get(base + 1, c), k.get(base + 2, c));
            for (r, b) in rows {
                k.add(base + r, c, b[0] * k1 + b[1] * k2);
            }
        }
    }
}

/// Put the `pins` (zero-clearance gap nodes) on the hole axis: each loses its lateral offset
/// from its nearest axis point (their lateral DOFs are held, so this only removes what sliding
/// along a curved axis leaves, and a warm start's offset; at the switch from penalty pins the
/// Newton step moves them instead).
fn hold_pins_on_axis(model: &Model, state: &mut State, pins: &[usize]) {
    for &i in pins {
        let (_, p) = model.path.nearest_axis(&state.x[i], state.md[i]);
        let d = state.x[i] - p.position;
        state.x[i] -= d - p.tangent * p.tangent.dot(&d);
    }
}

/// Node-basis normal and equilibrium column of a wall contact at node `i` with outward normal
/// `nrm` and hole tangent `tangent` (global): the force and moment on the node per newton of
/// normal force, `[n + f v^ ; f R_c n x v^]` (friction opposing the sliding velocity `v^` of the
/// contact point, proportional to the normal force).
fn wall_column(model: &Model, i: usize, nrm: Vec3, tangent: Vec3) -> (Vec3, [f64; 6]) {
    let q = &model.basis[i];
    let rc = model.mesh.nodes[i].contact_od_m / 2.0;
    let v = tangent * model.loads.axial_speed_m_s + tangent.cross(&nrm) * (model.loads.omega_rad_s * rc);
    let (fv, fm) = if model.friction[i] > 0.0 && v.norm() > 1e-12 {
        let vh = v / v.norm();
        (vh * model.friction[i], nrm.cross(&vh) * (model.friction[i] * rc))
    } else {
        (Vec3::zeros(), Vec3::zeros())
    };
    let et = q.transpose() * (nrm + fv);
    let em = q.transpose() * fm;
    (q.transpose() * nrm, [et.x, et.y, et.z, em.x, em.y, em.z])
}

/// The linearized contacts of the interior-point Newton's managed gaps at one evaluation.
pub(crate) struct ContactColumns {
    /// Node-basis outward normal per contact.
    pub(crate) normals: Vec<Vec3>,
    /// Equilibrium column per contact (see [`wall_column`]).
    pub(crate) eq_cols: Vec<[f64; 6]>,
    /// Radial distance minus clearance per contact, m.
    pub(crate) gaps0: Vec<f64>,
    /// Gap geometry per contact.
    pub(crate) geometry: Vec<GapGeometry>,
}

/// Contact normals, equilibrium columns and gaps of the managed gap nodes `qidx` at the
/// evaluation `ev` of `state` (whose contact normals it updates).
pub(crate) fn contact_columns(model: &Model, state: &mut State, ev: &Evaluation, qidx: &[usize]) -> ContactColumns {
    let m = qidx.len();
    let mut cc = ContactColumns {
        normals: Vec::with_capacity(m),
        eq_cols: Vec::with_capacity(m),
        gaps0: Vec::with_capacity(m),
        geometry: Vec::with_capacity(m),
    };
    for &i in qidx {
        let g = gap_geometry(state, ev, i);
        state.normal[i] = g.normal;
        let (nl, col) = wall_column(model, i, g.normal, g.tangent);
        cc.normals.push(nl);
        cc.eq_cols.push(col);
        cc.gaps0.push(g.gap);
        cc.geometry.push(g);
    }
    cc
}

/// Residual `r0` (constrained entries zeroed) plus the contact forces of the multipliers
/// `lambda` (N, per node) along the equilibrium columns of the managed gaps `qidx`.
pub(crate) fn contact_residual(
    model: &Model,
    r0: &[f64],
    qidx: &[usize],
    eq_cols: &[[f64; 6]],
    lambda: &[f64],
    constrained: &[usize],
) -> Vec<f64> {
    let mut rt = r0.to_vec();
    for (j, &i) in qidx.iter().enumerate() {
        for k in 0..6 {
            rt[model.dof(i, k)] += lambda[i] * eq_cols[j][k];
        }
    }
    for &d in constrained {
        rt[d] = 0.0;
    }
    rt
}

/// Add the circle stiffness of the managed gaps' contact forces `lambda` (N, per node): the
/// rotation of the normal `n` with the lateral motion, `(R / s)(I - t t^T - n n^T)`.
pub(crate) fn add_circle_stiffness(
    model: &Model,
    sink: &mut dyn StiffnessSink,
    qidx: &[usize],
    geometry: &[GapGeometry],
    lambda: &[f64],
) {
    for (j, &i) in qidx.iter().enumerate() {
        let (g, lam) = (&geometry[j], lambda[i]);
        if lam > 0.0 && g.radial > 1e-9 {
            let (t, nrm) = (g.tangent, g.normal);
            let kc = (nalgebra::Matrix3::identity() - t * t.transpose() - nrm * nrm.transpose()) * (lam / g.radial);
            let q = &model.basis[i];
            let kl = q.transpose() * kc * q;
            let dofs: [usize; 3] = std::array::from_fn(|k| model.dof(i, k));
            sink.add_block(&dofs, kl.transpose().as_slice(), 3);
        }
    }
}

/// Gap nodes whose contact the interior point manages (`true`): every gap but the
/// zero-clearance ones (pins, held by vector multipliers).
pub(crate) fn managed_gaps(model: &Model) -> Vec<bool> {
    (0..model.nodes())
        .map(|i| {
            model.mesh.nodes[i].has_gap
                && model.clearance(i, model.md_ref[i]) > crate::models::fem::contact::gap::ZERO_CLEARANCE_M
        })
        .collect()
}

/// Newton iteration on the geometry whose every step solves the linearized contact problem of
/// all (non-pin) gaps by a primal-dual interior-point method on the band system:
/// `K du + N R = -r0`, `N^T du + s = -g`, `R, s >= 0`, `R s = 0`. Each interior-point
/// iteration factors `K + N diag(R/s) N^T`, which keeps the band structure (a rank-one 3x3
/// block per gap), and makes two solves with it (Mehrotra predictor-corrector: the affine
/// direction sets the centering, the corrector adds the second-order complementarity term).
/// The iteration is warm-started from the previous step's multipliers, shifted off the
/// boundary in proportion to the outer residual ([`IP_START_SHIFT`]), and stopped at a
/// tolerance tied to the outer residual (inexact Newton; exact near convergence). Friction is
/// proportional to the unknown normal force (the equilibrium columns); the rotation of the
/// contact normal enters as the circle stiffness `(R/s)(I - t t^T - n n^T)` and the rotation of
/// the friction direction as the gaps' geometric stiffness at the previous multipliers. The
/// zero-clearance gaps (pins) are penalty springs until the outer residual falls below
/// [`PIN_EXACT_RESIDUAL`], then exact constraints: held on the hole axis by their lateral
/// DOFs (the step at the switch prescribes the lateral increments that take them from the
/// penalty's give onto the axis), their force the reaction (`State::exact_pins`) with its
/// friction linearized
/// (`add_pin_coupling`); no augmented-Lagrangian phase. Below [`ACTIVE_SET_RESIDUAL`] (not at
/// the pins' switch) each step first tries the equality-constrained Newton step of the last
/// contact set (one factorization; [`ACTIVE_SET_TRIES`] with the pairs that left the set
/// switched), the interior point taking over when the set does not hold. The linearization is checked against
/// central differences in `solve_tangent_tests.rs`.
pub fn solve_ip_from(model: &Model, mut state: State, ctl: &SolveControls) -> Result<Solution, SolveError> {
    let t0 = Instant::now();
    let n = model.dofs();
    let nn = model.nodes();
    let mut lin = Linear::for_model(model);
    let top_ax = model.dof(nn - 1, 0);
    let bordered = model.loads.hook_load_n.is_none();
    let scale = load_scale(model);
    let mut stats = SolveStats::default();
    let mut converged = false;
    let managed = managed_gaps(model);
    let qidx: Vec<usize> = (0..nn).filter(|&i| managed[i]).collect();
    // the zero-clearance gaps: pins, held by their vector multipliers outside the interior point
    let pins: Vec<usize> = (0..nn)
        .filter(|&i| model.mesh.nodes[i].has_gap && !managed[i])
        .collect();
    // contact index of each node (usize::MAX: none)
    let mut contact_at = vec![usize::MAX; nn];
    for (j, &i) in qidx.iter().enumerate() {
        contact_at[i] = j;
    }
    let m = qidx.len();
    // the pins become exact constraints once the outer residual is below
    // `PIN_EXACT_RESIDUAL` (held on the hole axis by their lateral DOFs, their wall force the
    // reaction, `Model::pin_reaction`, set by each evaluation); before that they are penalty
    // springs about their vector multipliers. A warm start that carries the pins' forces
    // starts exact.
    let pin_constrained = constrained_with_pins(model, &pins);
    state.exact_pins = pins.is_empty() || pins.iter().any(|&i| state.lambda_vec[i] != Vec3::zeros());
    let mut constrained = if state.exact_pins {
        pin_constrained.clone()
    } else {
        model.constrained_dofs()
    };
    state.closed = Some(vec![false; nn]);
    state.free_law = None;
    state.lcp_nodes = Some(managed.clone());
    state.implicit_friction = true;
    let mut ev;
    // the previous Newton step was full and its outer residual small: this evaluation is
    // likely the converged one, so it is first made without the tangent (then redone with it
    // if the solution is not converged after all)
    let mut likely_converged = false;
    let mut redo = false;
    loop {
        // linearize with the managed gaps carrying only their lagged friction
        let skip_tangent = likely_converged && !redo;
        redo = false;
        // at the switch to exact pins the pins are not moved onto the axis by themselves (their
        // neighbours would carry the jump into the residual): the Newton step prescribes their
        // lateral increment instead (`pin_move`)
        let switching = !state.exact_pins && stats.residual_history.last().is_some_and(|&r| r < PIN_EXACT_RESIDUAL);
        if switching {
            state.exact_pins = true;
            constrained.clone_from(&pin_constrained);
        } else if state.exact_pins {
            hold_pins_on_axis(model, &mut state, &pins);
        }
        ev = if skip_tangent {
            model.evaluate(&mut state, None)
        } else {
            model.evaluate(&mut state, Some(lin.sink()))
        };
        let (c, r0) = free_residual(model, &ev, &constrained);
        // prescribed increments of held DOFs: the switching pins' lateral DOFs take them to
        // the hole axis (non-homogeneous constraints; their coupling enters through `K du`)
        let pin_move: Vec<(usize, f64)> = if switching {
            pins.iter()
                .flat_map(|&i| {
                    let d = state.x[i] - ev.axis[i].0;
                    let q = &model.basis[i];
                    [
                        (model.dof(i, 1), -q.column(1).dot(&d)),
                        (model.dof(i, 2), -q.column(2).dot(&d)),
                    ]
                })
                .collect()
        } else {
            Vec::new()
        };
        // contact geometry of the managed gaps (node-basis normals, equilibrium columns, gaps)
        let ContactColumns {
            mut normals,
            mut eq_cols,
            mut gaps0,
            geometry,
        } = contact_columns(model, &mut state, &ev, &qidx);
        // the rest of the wall of tight gaps (see `FAR_WALL_CLEARANCE_M`): the supporting planes
        // of the hole circle with outward normals e = n cos(a) + b sin(a), b = t x n, at the
        // angles a = 2 pi k / WALL_PLANES from the current normal: e . (radial n + du) <= clearance
        let far: Vec<usize> = (0..m)
            .filter(|&j| ev.clearance[qidx[j]] < FAR_WALL_CLEARANCE_M)
            .collect();
        const EXTRA: usize = WALL_PLANES - 1;
        let mt = m + EXTRA * far.len();
        let mut far_at = vec![usize::MAX; nn];
        let mut cnode: Vec<usize> = qidx.clone();
        for (k, &j) in far.iter().enumerate() {
            let i = qidx[j];
            let g = &geometry[j];
            let b = g.tangent.cross(&g.normal);
            let eo = ev.clearance[i];
            for k in 1..WALL_PLANES {
                let a = std::f64::consts::TAU * k as f64 / WALL_PLANES as f64;
                let (nrm, gap) = (g.normal * a.cos() + b * a.sin(), g.radial * a.cos() - eo);
                let (nl, col) = wall_column(model, i, nrm, g.tangent);
                normals.push(nl);
                eq_cols.push(col);
                gaps0.push(gap);
                cnode.push(i);
            }
            far_at[i] = m + EXTRA * k;
        }
        // outer residual with the current multipliers as the contact forces
        let rt = contact_residual(model, &r0, &qidx, &eq_cols, &state.lambda, &constrained);
        let rn = residual_norm(&rt, scale).max(c.abs() / scale);
        let mut pen: f64 = 0.0;
        let mut compl: f64 = 0.0;
        let mut pen_s = 0.0;
        for (j, &i) in qidx.iter().enumerate() {
            let eo = ev.clearance[i].max(MIN_REFERENCE_CLEARANCE_M);
            if gaps0[j] / eo > pen {
                pen_s = model.mesh.nodes[i].s_m;
            }
            pen = pen.max(gaps0[j] / eo);
            compl = compl.max((state.lambda[i] * gaps0[j].min(0.0)).abs() / (scale * eo));
        }
        // net force of the residual (the global equilibrium error of physics.md 6.7): the entries
        // are each below the tolerance, but thousands of them may add up
        let net = (0..nn)
            .map(|i| model.basis[i] * Vec3::new(rt[model.dof(i, 0)], rt[model.dof(i, 1)], rt[model.dof(i, 2)]))
            .sum::<Vec3>()
            .norm()
            / scale;
        // zero-clearance gaps (full-gauge stabilizers) are pins: penalty springs about their
        // vector multiplier; their offset from the axis must fall below the tolerance of the
        // smallest clearance the managed gaps are measured against
        let pin_offset = pin_offset_m(&ev, &pins);
        let pins_held = pin_offset <= ctl.gap_tolerance * MIN_REFERENCE_CLEARANCE_M;
        let equilibrium = rn < ctl.residual_tolerance
            && net < NET_FORCE_TOLERANCE * ctl.residual_tolerance
            && pen <= ctl.gap_tolerance
            && compl < 1e-6;
        let done = equilibrium && pins_held && state.exact_pins;
        if skip_tangent && !done && stats.iterations < ctl.max_iterations {
            redo = true;
            continue;
        }
        stats.residual_history.push(rn);
        stats.max_penetration = pen.max(0.0);
        if tracing::enabled!(tracing::Level::DEBUG) {
            // the largest residual entry: a scan over every DOF, made only for the log
            let worst = largest_entry(&rt);
            tracing::debug!(
                iteration = stats.iterations,
                worst_s = model.mesh.nodes[nn - 1 - worst / 6].s_m,
                worst_dof = worst % 6,
                pen_s,
                residual = rn,
                net,
                penetration = pen,
                compl,
                "ip newton"
            );
        }
        if done {
            converged = true;
            break;
        }
        if stats.iterations >= ctl.max_iterations {
            break;
        }
        if equilibrium && !state.exact_pins {
            // in equilibrium about penalty pins (a step went straight from above
            // `PIN_EXACT_RESIDUAL` to the tolerance): the next evaluation holds them exactly
            stats.iterations += 1;
            likely_converged = false;
            continue;
        }
        // circle stiffness of the current contact forces
        add_circle_stiffness(model, lin.sink(), &qidx, &geometry, &state.lambda);
        if state.exact_pins {
            add_pin_coupling(model, &mut lin, &ev, &state, &pins);
        }
        let kb = bit_row(model, &lin, &constrained);
        // the base matrix K (before interior-point terms) is kept to rebuild each iteration
        let base = lin.keep_base();
        // diagonal given to the constrained DOFs (any positive value: they are decoupled)
        let constraint_scale = {
            let (sum, cnt) = (0..n)
                .map(|d| base.as_ref().unwrap_or(&lin).get(d, d).abs())
                .filter(|v| *v > 0.0 && v.is_finite())
                .fold((0.0, 0usize), |(s, c), v| (s + v, c + 1));
            if cnt > 0 {
                sum / cnt as f64
            } else {
                1.0
            }
        };
        // inexact Newton: the contact subproblem of an early, far-from-converged linearization
        // is solved only as accurately as that linearization deserves; near the solution the
        // tolerances tighten to the exact ones (see `ip_tolerance`)
        let eta = ip_tolerance(rn);
        // interior point on (du, R, s), du the step of this linearization
        // the step starts at the prescribed increments (the switching pins'), zero elsewhere
        let start_du = |du: &mut [f64]| {
            du.fill(0.0);
            for &(d, v) in &pin_move {
                du[d] = v;
            }
        };
        let mut du = vec![0.0; n];
        start_du(&mut du);
        let mut dh_total = 0.0;
        // warm start from the previous multipliers, pushed off the boundary by a shift that
        // grows with the outer residual (far from the solution the old contact set is a poor
        // guess, and pairs pinned at the boundary would block the interior-point steps)
        let mut shift = (IP_START_SHIFT * rn).clamp(1e-6, 1e-1);
        // the previous multiplier of each pair (the far-wall planes: none) and its clearance
        let lam_prev: Vec<f64> = (0..mt)
            .map(|j| if j < m { state.lambda[qidx[j]] } else { 0.0 })
            .collect();
        let clr: Vec<f64> = cnode
            .iter()
            .map(|&i| ev.clearance[i].max(MIN_REFERENCE_CLEARANCE_M))
            .collect();
        let start_r = |shift: f64| -> Vec<f64> {
            (0..mt)
                .map(|j| lam_prev[j].max(0.0) + shift * scale / mt.max(1) as f64)
                .collect()
        };
        let start_s = |shift: f64| -> Vec<f64> {
            (0..mt)
                .map(|j| (-gaps0[j]).max(1e-6 * clr[j]) + shift * clr[j])
                .collect()
        };
        let mut r_f = start_r(shift);
        let mut s_v = start_s(shift);
        let mut restarts = 0usize;
        // active-set finish (a primal-dual active-set step): near convergence the first
        // interior-point iterations start from the contact set of the last step, pairs in the
        // set on the boundary (slack `ACTIVE_SET_EPS` clearances: the linearized gap held
        // closed), the others with zero force (their force held at zero), and the affine
        // direction is taken in full when no pair leaves its set: the equality-constrained
        // Newton step of that set, one factorization. Pairs that leave it switch sides and the
        // step is tried again (`ACTIVE_SET_TRIES` in all); then the interior point goes on
        // from its usual warm start.
        let per_contact = scale / mt.max(1) as f64;
        let mut in_set: Vec<bool> = (0..mt)
            .map(|j| {
                // in the set when its force (per contact's share of the load scale) is the
                // larger side of the complementarity pair, the open gap (per clearance) the other
                lam_prev[j] / per_contact > ((-gaps0[j]).max(0.0) / clr[j]).max(ACTIVE_SET_MIN_FORCE)
            })
            .collect();
        // not at the pins' switch (their prescribed move changes the contact set)
        let mut active_set_tries = if stats.iterations > 0 && pin_move.is_empty() && rn < ACTIVE_SET_RESIDUAL {
            ACTIVE_SET_TRIES
        } else {
            0
        };
        let active_set_start = |in_set: &[bool], r_f: &mut [f64], s_v: &mut [f64]| {
            for j in 0..mt {
                if in_set[j] {
                    // at least the contact's share of the load scale: the pair's compliance in
                    // the step's matrix is its slack over this force, and it ends the step
                    // `slack * dR / R` past the wall
                    r_f[j] = lam_prev[j].max(per_contact);
                    s_v[j] = ACTIVE_SET_EPS * clr[j];
                } else {
                    r_f[j] = 0.0;
                    s_v[j] = (-gaps0[j]).max(clr[j]);
                }
            }
        };
        if active_set_tries > 0 {
            active_set_start(&in_set, &mut r_f, &mut s_v);
        }
        let dofs6: Vec<[usize; 6]> = cnode
            .iter()
            .map(|&i| std::array::from_fn(|k| model.dof(i, k)))
            .collect();
        let radial = |j: usize, u: &[f64]| -> f64 { (0..3).map(|k| normals[j][k] * u[dofs6[j][k]]).sum() };
        let mut rd = vec![0.0; n];
        let mut rp = vec![0.0; mt];
        let mut rhs = vec![0.0; n];
        let mut b_top = vec![0.0; n];
        let mut ds = vec![0.0; mt];
        let mut dr = vec![0.0; mt];
        let mut ds_aff = vec![0.0; mt];
        let mut dr_aff = vec![0.0; mt];
        let mut rc = vec![0.0; mt];
        let mut work = Vec::new();
        let mut ip_iters = 0usize;
        let mut stalled = 0usize;
        for ip in 0..MAX_IP_ITERATIONS {
            // residuals (K du vanishes before the first step: du starts at zero)
            rd.copy_from_slice(&r0);
            if ip > 0 || !pin_move.is_empty() {
                lin.matrix_mul_add(base.as_ref(), &du, &mut rd, &mut work);
            }
            for j in 0..mt {
                for k in 0..6 {
                    rd[dofs6[j][k]] += r_f[j] * eq_cols[j][k];
                }
            }
            rd[top_ax] += dh_total;
            for &d in &constrained {
                rd[d] = 0.0;
            }
            for j in 0..mt {
                rp[j] = radial(j, &du) + s_v[j] + gaps0[j];
            }
            let mu = (0..mt).map(|j| r_f[j] * s_v[j]).sum::<f64>() / mt.max(1) as f64;
            let rd_n = rd.iter().fold(0.0f64, |a, v| a.max(v.abs())) / scale;
            let rp_n = (0..mt).map(|j| rp[j].abs() / clr[j]).fold(0.0, f64::max);
            let cb = if bordered {
                c + kb.iter().map(|&(d, v)| v * du[d]).sum::<f64>()
            } else {
                0.0
            };
            if rd_n < eta && rp_n < 10.0 * eta && mu < 1e-2 * eta * scale * 1e-3 && cb.abs() < eta * scale {
                break;
            }
            ip_iters += 1;
            // reduced matrix K + N diag(R/s) N^T
            // row form: row i (DOF k of a contact node) gets D e_k g^T on the node's
            // translation columns
            let add_row = |i: usize, row: &mut [f64]| {
                let node = nn - 1 - i / 6;
                let first = far_at[node];
                let extra = if first == usize::MAX {
                    0..0
                } else {
                    first..first + EXTRA
                };
                for j in std::iter::once(contact_at[node]).chain(extra) {
                    if j == usize::MAX {
                        continue;
                    }
                    let k = i % 6;
                    let e = r_f[j] / s_v[j] * eq_cols[j][k];
                    // the node's first DOF i - k sits at offset HALF_BANDWIDTH - k
                    let off = HALF_BANDWIDTH - k;
                    for cc in 0..3 {
                        row[off + cc] += e * normals[j][cc];
                    }
                }
            };
            let factored = lin.factor_modified(base.as_ref(), &constrained, constraint_scale, add_row, |sink| {
                for j in 0..mt {
                    let dj = r_f[j] / s_v[j];
                    let nv = normals[j];
                    // D e_j g_j^T: rows = equilibrium column (6), columns = gap normal (3)
                    let mut blk = [0.0; 36];
                    for r in 0..6 {
                        for cc in 0..3 {
                            blk[r * 6 + cc] = dj * eq_cols[j][r] * nv[cc];
                        }
                    }
                    sink.add_block(&dofs6[j], &blk, 6);
                }
            });
            if let Err(e) = factored {
                return Err(singular(model, e));
            }
            stats.factorizations += 1;
            // right-hand side of one Newton solve of the (du, R, s) system for the
            // complementarity target `rc` (of R ds + s dR): -rd - E S^-1 (rc + R rp)
            let build_rhs = |rc: &[f64], rhs: &mut [f64]| {
                for (x, v) in rhs.iter_mut().zip(&rd) {
                    *x = -v;
                }
                for j in 0..mt {
                    let w = (rc[j] + r_f[j] * rp[j]) / s_v[j];
                    for k in 0..6 {
                        rhs[dofs6[j][k]] -= w * eq_cols[j][k];
                    }
                }
                for &d in &constrained {
                    rhs[d] = 0.0;
                }
            };
            // Mehrotra predictor: the affine-scaling direction (no centering), solved together
            // with the hook-load column K^-1 e_top (one pass over the factor for both)
            for j in 0..mt {
                rc[j] = -r_f[j] * s_v[j];
            }
            build_rhs(&rc, &mut rhs);
            let kbb = if bordered {
                b_top.fill(0.0);
                b_top[top_ax] = 1.0;
                lin.solve2(&mut b_top, &mut rhs);
                kb.iter().map(|&(d, v)| v * b_top[d]).sum::<f64>()
            } else {
                lin.solve(&mut rhs);
                0.0
            };
            // with the solved `rhs`: the hook-load step (returned), the du step (in `rhs`),
            // and the slack and multiplier steps
            let finish = |rc: &[f64], rhs: &mut [f64], ds: &mut [f64], dr: &mut [f64]| -> f64 {
                let dh = if bordered {
                    let kba: f64 = kb.iter().map(|&(d, v)| v * rhs[d]).sum();
                    let dh = if kbb.abs() > 1e-30 { (cb + kba) / kbb } else { 0.0 };
                    for (x, bt) in rhs.iter_mut().zip(&b_top) {
                        *x -= dh * bt;
                    }
                    dh
                } else {
                    0.0
                };
                for j in 0..mt {
                    ds[j] = -rp[j] - radial(j, rhs);
                    dr[j] = (rc[j] - r_f[j] * ds[j]) / s_v[j];
                }
                dh
            };
            let dh_aff = finish(&rc, &mut rhs, &mut ds_aff, &mut dr_aff);
            if active_set_tries > 0 {
                active_set_tries -= 1;
                let eps_r = ACTIVE_SET_EPS * per_contact;
                let mut switched = 0usize;
                for j in 0..mt {
                    if in_set[j] && r_f[j] + dr_aff[j] < -eps_r {
                        in_set[j] = false;
                        switched += 1;
                    } else if !in_set[j] && s_v[j] + ds_aff[j] < -ACTIVE_SET_EPS * clr[j] {
                        in_set[j] = true;
                        switched += 1;
                    }
                }
                tracing::trace!(switched, "active-set step");
                if switched == 0 {
                    for (x, d) in du.iter_mut().zip(&rhs) {
                        *x += d;
                    }
                    dh_total += dh_aff;
                    for j in 0..mt {
                        r_f[j] = (r_f[j] + dr_aff[j]).max(0.0);
                        s_v[j] = (s_v[j] + ds_aff[j]).max(0.0);
                    }
                    break;
                }
                if active_set_tries > 0 {
                    active_set_start(&in_set, &mut r_f, &mut s_v);
                } else {
                    r_f = start_r(shift);
                    s_v = start_s(shift);
                }
                continue;
            }
            let a_aff = step_to_boundary(&r_f, &dr_aff, &s_v, &ds_aff, 1.0);
            let mu_aff = (0..mt)
                .map(|j| (r_f[j] + a_aff * dr_aff[j]) * (s_v[j] + a_aff * ds_aff[j]))
                .sum::<f64>()
                / mt.max(1) as f64;
            // ... sets the centering sigma = (mu_aff / mu)^3; the corrector adds the
            // second-order term of the complementarity
            let sigma = if mu > 0.0 {
                (mu_aff / mu).clamp(0.0, 1.0).powi(3)
            } else {
                0.0
            };
            for j in 0..mt {
                rc[j] = -r_f[j] * s_v[j] + sigma * mu - dr_aff[j] * ds_aff[j];
            }
            build_rhs(&rc, &mut rhs);
            lin.solve(&mut rhs);
            let ddh = finish(&rc, &mut rhs, &mut ds, &mut dr);
            let alpha = step_to_boundary(&r_f, &dr, &s_v, &ds, 0.995);
            tracing::trace!(rd_n, rp_n, mu_rel = mu / (scale * 1e-3), a_aff, sigma, alpha, "ip");
            stalled = if alpha < 1e-2 { stalled + 1 } else { 0 };
            for (x, d) in du.iter_mut().zip(&rhs) {
                *x += alpha * d;
            }
            dh_total += alpha * ddh;
            for j in 0..mt {
                r_f[j] += alpha * dr[j];
                s_v[j] += alpha * ds[j];
            }
            // a stalled interior point (friction makes the contact problem non-monotone) far
            // from the solution: take the step found so far
            if stalled >= IP_STALL_STEPS && eta > 1e-8 {
                break;
            }
            // stalled near the solution (where the exact tolerance is asked): the warm start sat
            // too close to the boundary for a pair that has to change (a contact switching while
            // its force and gap are both near zero), and the remaining iterations would creep
            // at steps of 1e-3; start again from a more central point
            if stalled >= IP_STALL_STEPS && restarts < IP_RESTARTS {
                restarts += 1;
                shift = (shift * IP_RESTART_SHIFT_FACTOR).min(1e-1);
                r_f = start_r(shift);
                s_v = start_s(shift);
                start_du(&mut du);
                dh_total = 0.0;
                stalled = 0;
                tracing::debug!(restarts, shift, "interior point restarted");
            }
        }
        // geometric step with caps
        let (mut rot_ratio, mut rot_node): (f64, usize) = (0.0, 0);
        for i in 0..nn {
            let rot = increment_across(model, &ev, &du, i, 3);
            if rot / MAX_BENDING_ROTATION_STEP > rot_ratio {
                (rot_ratio, rot_node) = (rot / MAX_BENDING_ROTATION_STEP, i);
            }
        }
        // and lateral motion of the gap nodes to a few clearances: the linearized gaps bound
        // only the motion along each node's current normal, so a long step can carry nodes
        // around and through the wall
        let (mut lat_ratio, mut lat_node): (f64, usize) = (0.0, 0);
        for &i in &qidx {
            let lat = increment_across(model, &ev, &du, i, 0);
            let r = lat / (MAX_LATERAL_STEP_CLEARANCES * ev.clearance[i].max(LATERAL_CAP_FLOOR_M));
            if r > lat_ratio {
                (lat_ratio, lat_node) = (r, i);
            }
        }
        let ratio = rot_ratio.max(lat_ratio);
        let alpha = if ratio > 1.0 { 1.0 / ratio } else { 1.0 };
        tracing::debug!(
            ip_iters,
            alpha,
            rot_ratio,
            rot_s = model.mesh.nodes[rot_node].s_m,
            lat_ratio,
            lat_s = model.mesh.nodes[lat_node].s_m,
            "interior-point iterations and step cap (bending-rotation and lateral caps: ratio and \
             distance from the bit of the node that sets each)"
        );
        // ... and, after a previous iteration, its contraction (the next residual predicted as
        // rn^2 / rn_prev) says so too: a probe that fails costs a residual-only evaluation
        let h = &stats.residual_history;
        let predicted = match h.len() {
            0 | 1 => 0.0,
            k => rn * rn / h[k - 2],
        };
        likely_converged = alpha == 1.0
            && rn < LIKELY_CONVERGED_RESIDUAL
            && predicted < LIKELY_CONVERGED_FACTOR * ctl.residual_tolerance;
        state.hook_load_n += alpha * dh_total;
        model.update(&mut state, &du, alpha);
        for (j, &i) in qidx.iter().enumerate() {
            // a node that crossed to the far wall carries the far multiplier into the next
            // linearization (whose normal then points at that wall)
            let rj = match far_at[i] {
                usize::MAX => r_f[j],
                f => r_f[j] + r_f[f..f + EXTRA].iter().sum::<f64>(),
            };
            state.lambda[i] = if rj > 1e-9 * scale { rj } else { 0.0 };
        }
        stats.iterations += 1;
    }
    // final state: contacts with force are closed at their multipliers
    let closed: Vec<bool> = (0..nn).map(|i| managed[i] && state.lambda[i] > 0.0).collect();
    state.closed = Some(closed);
    state.lcp_nodes = None;
    state.implicit_friction = false;
    state.exact_pins = false;
    state.exact_multipliers = true;
    // same positions and triads as the last evaluation: its element responses are reused
    let ev_final = model.evaluate_reusing_elements(&mut state, ev.elements);
    state.exact_multipliers = false;
    stats.seconds = t0.elapsed().as_secs_f64();
    Ok(Solution {
        state,
        eval: ev_final,
        converged,
        stats,
    })
}

#[cfg(test)]
#[path = "newton_tangent_tests.rs"]
mod tangent_tests;
