//! Leaving the straight branch (issue 16): a converged stiff solve can be the straight string
//! lying on one side of the hole in a run compressed beyond the helical onset, an equilibrium
//! past its stability limit (`models::buckling::unbuckled_helical_runs` finds such runs). The
//! Newton solve has no reason to leave it: the straight shape is an exact equilibrium, and the
//! tangent's negative directions do not stop a Newton step.
//!
//! [`helical_start`] moves the string of each run onto a helix along the wall: lateral offset
//! `a r (cos theta, sin theta)` in the plane normal to the hole axis (`r` the radial clearance,
//! `a` = [`HELIX_AMPLITUDE`]), phase `theta' = sqrt(F / (2 EI))` (the helix of pitch
//! `2 pi sqrt(2 EI / F)` under the local compression `F`, Lubinski / Mitchell, docs/theory.md 7),
//! tapered to the converged shape over half a pitch at each end of the run, the node rotations
//! turned with the change of slope. [`solve_from_helix`] re-solves from there with the
//! interior-point contact Newton under a pseudo-transient lateral damping
//! ([`SolveControls::lateral_damping_n_per_m`], [`instability_stiffness`]) that vanishes with
//! the residual, with the model's friction at once or along a friction path ([`ATTEMPTS`]);
//! the caller accepts the result only if it converged and is buckled. [`coarse_for_pitch`]
//! names the elements too long for the helix's pitch.

use super::continuation::{follow_path, with_friction, PathSteps};
use super::{solve_interior_point_from, Solution, SolveControls, SolveStats};
use crate::geometry::Vec3;
use crate::models::fem::model::{Model, State};
use std::f64::consts::{FRAC_PI_2, PI};
use std::time::Instant;

/// Radius of the start helix as a fraction of the radial clearance: just off the wall, so that
/// no node starts in penetration.
pub const HELIX_AMPLITUDE: f64 = 0.95;

/// The lateral shape a start moves a run onto.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Shape {
    /// A helix along the wall: the contact angle turns by the phase `theta`.
    Helix,
    /// A sinusoid along the wall: the contact angle swings `swing_rad sin(theta)` (rad) about
    /// where the run's lower end lies. Not among [`ATTEMPTS`]: tried on the horizontal pipe at
    /// 350 kN with friction 0.2 (swing 90 deg, friction path in steps of 0.25) it converged at
    /// 0.25 of the friction and failed at 0.5, as the helix's path stops (at 0.39; docs/theory.md
    /// 7.5).
    Snake {
        /// Largest swing of the contact angle, rad.
        swing_rad: f64,
    },
}

/// One way from the straight string to the buckled one: the start's shape, the
/// pseudo-transient damping (a multiple of [`instability_stiffness`]) and whether friction is
/// put on along a path (the buckled string solved without friction, then with fractions of it
/// rising to the model's, [`FRICTION_STEPS`]) or at once.
#[derive(Debug, Clone, Copy)]
pub struct Attempt {
    /// The start's shape.
    pub shape: Shape,
    /// The damping as a multiple of [`instability_stiffness`].
    pub damping: f64,
    /// Friction put on along a path (made only where the model has friction).
    pub friction_path: bool,
}

/// The attempts [`solve_from_helix`] makes, in order.
pub const ATTEMPTS: [Attempt; 2] = [
    Attempt {
        shape: Shape::Helix,
        damping: 1.0,
        friction_path: false,
    },
    Attempt {
        shape: Shape::Helix,
        damping: 1.0,
        friction_path: true,
    },
];

/// The friction path's steps (in fractions of the model's friction): a quarter first, at least
/// a sixteenth, 40 iterations a step, doubled after a converged step.
pub const FRICTION_STEPS: PathSteps = PathSteps {
    first: 0.25,
    smallest: 1.0 / 16.0,
    step_iterations: 40,
    growth: 2.0,
};

/// Iteration limit of the attempt that puts the friction on at once.
pub const DIRECT_ITERATIONS: usize = 100;

/// Elements per helix pitch the mesh of a buckled run must have at least.
pub const ELEMENTS_PER_PITCH: f64 = 8.0;

/// The elements of `model` in `runs` (node index ranges from the bit) longer than the shortest
/// helix pitch there over [`ELEMENTS_PER_PITCH`], with that length (m): the pitch
/// `2 pi sqrt(2 EI / F)` at each node's compression of `axial_n` (N, tension positive). None
/// when every element there is short enough.
pub fn coarse_for_pitch(model: &Model, axial_n: &[f64], runs: &[(usize, usize)]) -> Option<(Vec<usize>, f64)> {
    let nn = model.nodes();
    let elements: Vec<usize> = runs.iter().flat_map(|&(lo, hi)| lo..hi.min(nn - 1)).collect();
    let h = elements
        .iter()
        .map(|&e| {
            let f = (-axial_n.get(e).copied().unwrap_or(0.0)).max(0.0);
            2.0 * PI * (2.0 * model.mesh.elements[e].ei / f).sqrt() / ELEMENTS_PER_PITCH
        })
        .fold(f64::INFINITY, f64::min);
    let long: Vec<usize> = elements
        .into_iter()
        .filter(|&e| model.mesh.nodes[e + 1].s_m - model.mesh.nodes[e].s_m > h * (1.0 + 1e-6))
        .collect();
    (!long.is_empty() && h.is_finite()).then_some((long, h))
}

/// The lateral stiffness (N/m per node) the straight string lacks in `runs` at its worst: the
/// negative stiffness per length of its most unstable lateral mode, `F^2 / (4 EI)` (the
/// wavenumber `sqrt(F / (2 EI))`), times the element length, at the largest compression of
/// `axial_n` (N, tension positive) in the runs.
pub fn instability_stiffness(model: &Model, axial_n: &[f64], runs: &[(usize, usize)]) -> f64 {
    let nn = model.nodes();
    runs.iter()
        .flat_map(|&(lo, hi)| lo..=hi.min(nn - 1))
        .map(|i| {
            let e = &model.mesh.elements[i.min(nn - 2)];
            let f = (-axial_n.get(i).copied().unwrap_or(0.0)).max(0.0);
            let h = (model.mesh.nodes[i.min(nn - 2) + 1].s_m - model.mesh.nodes[i.min(nn - 2)].s_m).abs();
            h * f * f / (4.0 * e.ei)
        })
        .fold(0.0, f64::max)
}

/// The state `state` of `model` with the nodes of each run of `runs` (node indices from the bit,
/// inclusive, lower index first) moved onto a helix along the wall (module docs), for the
/// effective axial forces `axial_n` at the nodes (N, tension positive, from the bit).
pub fn helical_start(model: &Model, state: &State, axial_n: &[f64], runs: &[(usize, usize)], shape: Shape) -> State {
    let nn = model.nodes();
    let s = |i: usize| model.mesh.nodes[i].s_m;
    let ei = |i: usize| model.mesh.elements[i.min(nn - 2)].ei;
    let compression = |i: usize| (-axial_n.get(i).copied().unwrap_or(0.0)).max(0.0);
    let mut dx = vec![Vec3::zeros(); nn];
    for &(lo, hi) in runs {
        let hi = hi.min(nn - 1);
        if hi <= lo {
            continue;
        }
        let f_mean = (lo..=hi).map(compression).sum::<f64>() / (hi - lo + 1) as f64;
        if f_mean <= 0.0 {
            continue;
        }
        let pitch = 2.0 * PI * (2.0 * ei(lo) / f_mean).sqrt();
        let taper = (0.5 * pitch).min(0.5 * (s(hi) - s(lo))).max(1e-9);
        let theta0 = {
            let (d, t, b1) = lateral(model, state, lo);
            let b2 = t.cross(&b1);
            d.dot(&b2).atan2(d.dot(&b1))
        };
        let mut theta = theta0;
        for (i, dxi) in dx.iter_mut().enumerate().take(hi + 1).skip(lo) {
            if i > lo {
                let f = 0.5 * (compression(i - 1) + compression(i));
                theta += (s(i) - s(i - 1)) * (f / (2.0 * ei(i - 1))).sqrt();
            }
            let to_end = (s(i) - s(lo)).min(s(hi) - s(i));
            let ramp = (FRAC_PI_2 * (to_end / taper).min(1.0)).sin().powi(2);
            let (d, t, b1) = lateral(model, state, i);
            let b2 = t.cross(&b1);
            let a = HELIX_AMPLITUDE * model.clearance(i, state.md[i]);
            let angle = match shape {
                Shape::Helix => theta,
                Shape::Snake { swing_rad } => theta0 + swing_rad * (theta - theta0).sin(),
            };
            let target = (b1 * angle.cos() + b2 * angle.sin()) * a;
            *dxi = (target - d) * ramp;
        }
    }
    let mut du = vec![0.0; model.dofs()];
    for i in 0..nn {
        let q = &model.basis[i];
        let w = if i > 0 && i + 1 < nn && (dx[i - 1].norm() + dx[i + 1].norm()) > 0.0 {
            let t = model.path.axis_at(state.md[i]).tangent;
            // MD falls as the distance from the bit grows
            let slope = -(dx[i + 1] - dx[i - 1]) / (s(i + 1) - s(i - 1));
            t.cross(&slope)
        } else {
            Vec3::zeros()
        };
        let (dl, wl) = (q.transpose() * dx[i], q.transpose() * w);
        for k in 0..3 {
            du[model.dof(i, k)] = dl[k];
            du[model.dof(i, k + 3)] = wl[k];
        }
    }
    for d in model.constrained_dofs() {
        du[d] = 0.0;
    }
    let mut out = state.clone();
    model.update(&mut out, &du, 1.0);
    for (i, dxi) in dx.iter().enumerate() {
        let (d, _, _) = lateral(model, &out, i);
        if dxi.norm() > 0.0 && d.norm() > 0.5 * model.clearance(i, out.md[i]) {
            out.normal[i] = d.normalize();
        }
    }
    out
}

/// Lateral offset of node `i` of `state` from the hole axis at its MD (m, global), the axis
/// tangent there and the node basis' first lateral direction made normal to it.
fn lateral(model: &Model, state: &State, i: usize) -> (Vec3, Vec3, Vec3) {
    let ax = model.path.axis_at(state.md[i]);
    let t = ax.tangent;
    let rel = state.x[i] - ax.position;
    let d = rel - t * t.dot(&rel);
    let b1 = model.basis[i].column(1).into_owned();
    let b1 = (b1 - t * t.dot(&b1)).normalize();
    (d, t, b1)
}

/// Re-solve `model` from its converged state `state` moved onto a buckled shape in `runs`
/// ([`helical_start`]; `axial_n` the effective axial forces of the converged solve, N, from the
/// bit) with the damped interior-point contact Newton (consistent tangent) under `ctl`, each of
/// [`ATTEMPTS`] in turn until `accept` takes a solution; returns that solution, or None, with
/// the work of every solve made.
pub fn solve_from_helix(
    model: &Model,
    state: &State,
    axial_n: &[f64],
    runs: &[(usize, usize)],
    ctl: &SolveControls,
    accept: impl Fn(&Solution) -> bool,
) -> (Option<Solution>, SolveStats) {
    let t0 = Instant::now();
    let frictional = model.friction.iter().any(|&f| f > 0.0);
    let damping = instability_stiffness(model, axial_n, runs);
    let mut work = SolveStats::default();
    for attempt in ATTEMPTS {
        if attempt.friction_path && !frictional {
            continue;
        }
        let ctl = SolveControls {
            lateral_damping_n_per_m: attempt.damping * damping,
            ..ctl.with_time_left(t0)
        };
        if ctl.time_limit_s <= 0.0 {
            break;
        }
        let start = helical_start(model, state, axial_n, runs, attempt.shape);
        let sol = if attempt.friction_path {
            friction_path(model, start, &ctl, &mut work)
        } else {
            let direct = SolveControls {
                max_iterations: ctl.max_iterations.min(DIRECT_ITERATIONS),
                ..ctl
            };
            solve_at_once(model, start, &direct, &mut work)
        };
        if let Some(sol) = sol.filter(|s| s.converged && accept(s)) {
            return (Some(sol), work);
        }
    }
    (None, work)
}

/// Solve `model` with its friction from `start` under `ctl` (consistent tangent), adding the
/// work to `work`; None if the solve fails.
fn solve_at_once(model: &Model, start: State, ctl: &SolveControls, work: &mut SolveStats) -> Option<Solution> {
    let mut m = model.clone();
    m.consistent_tangent = true;
    let sol = solve_interior_point_from(&m, start, ctl).ok()?;
    work.add_work(&sol.stats);
    tracing::info!(
        converged = sol.converged,
        iterations = sol.stats.iterations,
        "re-solve from a buckled start"
    );
    Some(sol)
}

/// The friction path of [`Attempt::friction_path`] from `start` ([`FRICTION_STEPS`], the
/// continuation's path follower): the converged solution with the model's friction, or None;
/// the work of every solve added to `work`.
fn friction_path(model: &Model, start: State, ctl: &SolveControls, work: &mut SolveStats) -> Option<Solution> {
    let t0 = Instant::now();
    let mut consistent = model.clone();
    consistent.consistent_tangent = true;
    let first = solve_interior_point_from(&with_friction(&consistent, 0.0), start, ctl).ok()?;
    if !first.converged {
        work.add_work(&first.stats);
        return None;
    }
    // the steps bound the path (each at most `FRICTION_STEPS.step_iterations`, halved down to
    // the smallest step) together with the time limit, not the solve's iteration limit
    let path_ctl = SolveControls {
        max_iterations: usize::MAX,
        ..*ctl
    };
    let (sol, reached) = follow_path(
        |t| with_friction(&consistent, t),
        first,
        0.0,
        &path_ctl,
        FRICTION_STEPS,
        t0,
    );
    work.add_work(&sol.stats);
    tracing::info!(
        friction_fraction = reached,
        iterations = sol.stats.iterations,
        "friction path from a buckled start"
    );
    Some(sol).filter(|s| s.converged)
}
