//! Contact-aware refinement of the bottom-hole assembly's mesh.
//!
//! The wall is touched only at nodes, so where a collar's body comes onto the wall (a
//! tangency point) or leaves it, the contact snaps to the nearest node: on a 0.5 m mesh the
//! pendulum's bit force and tilt move by up to 0.3% with where the nodes fall
//! (docs/performance.md, "Fine BHA meshes"). After a solve, each end of a run of body contacts
//! in the assembly (a contact node next to a free one) marks the element between them; those
//! elements are split into pieces of at most [`REFINED_FRACTION`] of the BHA element length,
//! the solved state is carried onto the new nodes (on the cubic of each split element), and the
//! model is solved again from there: two more Newton iterations, usually. Stabilizer and
//! tool-joint contacts (a node wider than the bodies beside it) and pins are where the string
//! really touches and are left as they are. Only the runs up to the third run of contacts
//! above the bit, or above the highest survey sensor, are refined ([`Scope`], `[solver]
//! refine_runs`): a run further up moves the bit's answers through the spans between by about
//! 0.27 per span. `[solver] refine_contacts = false` turns it off.

use super::element::rotation::skew;
use super::mesh::{Mesh, MeshBend, MeshNode, MeshPad};
use super::model::{Model, State};
use super::solve::toolface::solve_holding_toolface;
use super::solve::{solve, solve_interior_point_from, Solution, SolveControls, SolveError};
use super::warm::{source_by_distance, transport_mapped};
use crate::case::Method;
use crate::geometry::Vec3;
use nalgebra::Matrix3;

/// Refined element length as a fraction of the BHA element length.
pub const REFINED_FRACTION: f64 = 0.2;

/// Normal force above which a node counts as touching the wall, N (as in the reported
/// contacts).
pub const CONTACT_FORCE_N: f64 = 1.0;

/// What the refinement is for: the assembly's top and the highest point whose answer it serves.
#[derive(Debug, Clone, Copy)]
pub struct Scope {
    /// Distance of the assembly's top from the bit, m: no node above it is refined.
    pub bha_top_m: f64,
    /// Distance from the bit of the highest survey sensor, m (0 without one): every contact
    /// run below it is refined, and `runs_above` runs above it.
    pub watch_m: f64,
    /// Contact runs refined above `watch_m` (at least 1; `usize::MAX`: every run).
    pub runs_above: usize,
}

impl Scope {
    /// The scope of `string` refining `runs_above` runs above its highest sensor: its
    /// assembly's top and that sensor.
    pub fn of(string: &crate::string::DrillString, runs_above: usize) -> Scope {
        let watch_m = string
            .components
            .iter()
            .filter_map(|c| c.sensor_to_bit_m)
            .fold(0.0, f64::max);
        Scope {
            bha_top_m: string.bha_length_m(),
            watch_m,
            runs_above,
        }
    }
}

/// Distance from the bit (m) of the top node of the `runs`-th run of touching gap nodes (of
/// any kind with a clearance: stabilizers, tool joints and bodies) of `state` whose lowest node
/// lies above `watch_m` (m from the bit); infinite if there are fewer runs. Pins (full-gauge
/// stabilizers, held on the axis, their force in [`State::pin_multipliers`]) are not counted:
/// counted, three runs end at a packed BHA's third stabilizer and leave its bit force 0.27% off
/// at a 1 m mesh (docs/performance.md, "The near-bit scope").
pub fn reach_m(model: &Model, state: &State, watch_m: f64, runs: usize) -> f64 {
    let nodes = &model.mesh.nodes;
    let touching = |i: usize| nodes[i].has_gap && state.multipliers[i] > CONTACT_FORCE_N;
    let mut count = 0;
    let mut lowest = 0;
    for i in 1..nodes.len() {
        if !touching(i) {
            continue;
        }
        if !touching(i - 1) {
            lowest = i;
        }
        let top_of_run = i + 1 == nodes.len() || !touching(i + 1);
        if top_of_run && nodes[lowest].s_m > watch_m + 1e-9 {
            count += 1;
            if count >= runs {
                return nodes[i].s_m;
            }
        }
    }
    f64::INFINITY
}

/// The elements of `model` that the refinement of `scope` splits into pieces of at most `h_m`:
/// those of [`tangency_elements`] up to the top of the run [`reach_m`] finds.
pub fn near_bit_elements(model: &Model, state: &State, scope: &Scope, h_m: f64) -> Vec<usize> {
    let top = scope
        .bha_top_m
        .min(reach_m(model, state, scope.watch_m, scope.runs_above.max(1)));
    tangency_elements(model, state, top, h_m)
}

/// Whether node `i` of `model` is a body contact candidate: a gap node no wider than the
/// bodies of the elements beside it (not a stabilizer, blade or tool joint), within the first
/// `bha_top_m` above the bit.
fn body_node(model: &Model, i: usize, bha_top_m: f64) -> bool {
    let nodes = &model.mesh.nodes;
    let n = &nodes[i];
    if !n.has_gap || n.s_m > bha_top_m + 1e-9 || i == 0 || i + 1 >= nodes.len() {
        return false;
    }
    let widest = model.mesh.elements[i - 1].od_m.max(model.mesh.elements[i].od_m);
    n.contact_od_m <= widest + 1e-9
}

/// The elements (by index) beside the ends of the runs of body contacts of `state` in the first
/// `bha_top_m` of `model` whose length exceeds `h_m`: both elements of a touching body node
/// with a free gap node beside it (a short run, a collar touching at a point between two
/// nodes, has its point inside the run; a long one lifts off at either side of its end node).
pub fn tangency_elements(model: &Model, state: &State, bha_top_m: f64, h_m: f64) -> Vec<usize> {
    let nodes = &model.mesh.nodes;
    let touching = |i: usize| state.multipliers[i] > CONTACT_FORCE_N;
    let free = |i: usize| nodes[i].has_gap && !touching(i);
    let mut out = Vec::new();
    for i in 1..nodes.len().saturating_sub(1) {
        let run_end = body_node(model, i, bha_top_m) && touching(i) && (free(i - 1) || free(i + 1));
        if !run_end {
            continue;
        }
        for e in [i - 1, i] {
            let len = nodes[e + 1].s_m - nodes[e].s_m;
            if len > h_m * (1.0 + 1e-6) && !out.contains(&e) {
                out.push(e);
            }
        }
    }
    out.sort_unstable();
    out
}

/// The mesh of `model` with each element of `split` divided evenly into pieces of at most
/// `h_m`; the new nodes carry the element's body as their contact diameter, and a gap where
/// both end nodes have one.
fn split_mesh(mesh: &Mesh, split: &[usize], h_m: f64) -> Mesh {
    let mut nodes: Vec<MeshNode> = vec![mesh.nodes[0]];
    let mut elements = Vec::new();
    let mut bend = None;
    let mut pad = mesh.pad.filter(|mp| mp.node == 0);
    for (e, el) in mesh.elements.iter().enumerate() {
        let (a, b) = (mesh.nodes[e], mesh.nodes[e + 1]);
        let pieces = if split.contains(&e) {
            (((b.s_m - a.s_m) / h_m) - 1e-9).ceil().max(1.0) as usize
        } else {
            1
        };
        for k in 1..pieces {
            nodes.push(MeshNode {
                s_m: a.s_m + (b.s_m - a.s_m) * k as f64 / pieces as f64,
                contact_od_m: el.od_m,
                has_gap: a.has_gap && b.has_gap,
                on_bit_gauge: false,
                component: el.component,
            });
            elements.push(*el);
        }
        nodes.push(b);
        elements.push(*el);
        // the bent housing's node keeps its kink at its new index
        if let Some(mb) = mesh.bend.filter(|mb| mb.node == e + 1) {
            bend = Some(MeshBend {
                node: nodes.len() - 1,
                ..mb
            });
        }
        // and the pads their force
        if let Some(mp) = mesh.pad.filter(|mp| mp.node == e + 1) {
            pad = Some(MeshPad {
                node: nodes.len() - 1,
                ..mp
            });
        }
    }
    Mesh {
        nodes,
        elements,
        bend,
        pad,
    }
}

/// `model` with the elements `split` divided into pieces of at most `h_m` (same hole, loads,
/// friction by node, top condition and tangent options).
pub fn refined_model(model: &Model, split: &[usize], h_m: f64) -> Model {
    let mesh = split_mesh(&model.mesh, split, h_m);
    let friction_of = |md: f64| -> f64 {
        // the friction of the nearest old node (the friction changes only at hole sections,
        // which carry no refined element); the reference MDs fall from the bit upward
        let md_ref = &model.md_ref;
        let k = md_ref.partition_point(|&m| m > md).min(md_ref.len() - 1);
        let k = if k > 0 && (md_ref[k - 1] - md).abs() <= (md_ref[k] - md).abs() {
            k - 1
        } else {
            k
        };
        model.friction[k]
    };
    // the old nodes keep their bases and axis positions (the new ones are computed)
    let old_of: Vec<Option<usize>> = {
        let old = &model.mesh.nodes;
        let mut j = 0;
        mesh.nodes
            .iter()
            .map(|n| {
                while j < old.len() && old[j].s_m < n.s_m {
                    j += 1;
                }
                (j < old.len() && old[j].s_m == n.s_m).then_some(j)
            })
            .collect()
    };
    let mut out = Model::with_known_frames(
        model.path.translated(model.origin_m),
        model.hole.clone(),
        mesh,
        model.bit_md_m,
        model.loads,
        friction_of,
        |i| old_of[i].map(|j| (model.basis[j], model.axis_ref[j])),
    );
    out.top = model.top.clone();
    out.reactive = model.reactive.clone();
    out.whirl_md_m = model.whirl_md_m.clone();
    if let Some(k) = model.kink {
        // the bent housing turned as in `model` (its toolface held against the twist)
        out.turn_kink(k.orientation_rad);
    }
    out.geometric_stiffness = model.geometric_stiffness;
    out.consistent_tangent = model.consistent_tangent;
    out
}

/// The state of `prev` on `model` (a refinement of `prev_model`): an old node keeps its state;
/// a new node lies on the cubic (Hermite) curve of its element through the end nodes'
/// positions and section axes, its triad interpolated and turned onto that curve. The contact
/// forces are spread along the runs, the total wall force unchanged: a new node between two
/// touching nodes takes its share of the run's line load, a new node beside a free node none.
pub fn carried_state(prev_model: &Model, prev: &State, model: &Model) -> State {
    let mut st = transport_mapped(prev_model, prev, model, |i| {
        source_by_distance(prev_model, model.mesh.nodes[i].s_m)
    });
    for i in 0..model.nodes() {
        let Some(src) = source_by_distance(prev_model, model.mesh.nodes[i].s_m) else {
            continue;
        };
        if src.weight <= 0.0 {
            continue;
        }
        let (x, tangent) = hermite_point(prev, src.node, src.weight);
        if !(x.iter().chain(tangent.iter()).all(|v| v.is_finite())) {
            continue;
        }
        st.x[i] = x;
        st.triads[i] = turned_onto(&st.triads[i], &tangent);
        st.multipliers[i] = 0.0;
    }
    spread_run_forces(prev_model, prev, model, &mut st);
    st
}

/// Half the length of the elements beside node `i` of `model` (its tributary length), m.
fn tributary_m(model: &Model, i: usize) -> f64 {
    let n = &model.mesh.nodes;
    let below = if i > 0 { n[i - 1].s_m } else { n[i].s_m };
    let above = if i + 1 < n.len() { n[i + 1].s_m } else { n[i].s_m };
    0.5 * (above - below)
}

/// Spread the contact forces of `prev` (on `prev_model`) over the new nodes of `model` (a
/// refinement) in `st`: a new node of an element whose end nodes both touch the wall (a collar
/// lying on it) takes the smaller of the end nodes' line loads (force over tributary length)
/// times its own tributary length, taken from the nearer end node, which keeps the rest (the
/// concentrated part at a run's end). A start whose new nodes carry no force has the
/// interior point build each refined run's forces from zero.
fn spread_run_forces(prev_model: &Model, prev: &State, model: &Model, st: &mut State) {
    let touching = |j: usize| prev.multipliers[j] > CONTACT_FORCE_N;
    let line_load = |j: usize| prev.multipliers[j] / tributary_m(prev_model, j);
    // the force given to new nodes, per old node
    let mut given = vec![0.0; prev_model.nodes()];
    // the new model's node of each old node that gave force
    let mut old_at = Vec::new();
    for i in 0..model.nodes() {
        let Some(src) = source_by_distance(prev_model, model.mesh.nodes[i].s_m) else {
            continue;
        };
        let (a, b) = (src.node, src.node + 1);
        if src.weight <= 0.0 {
            old_at.push((i, a));
            continue;
        }
        if !(touching(a) && touching(b)) {
            continue;
        }
        let f = line_load(a).min(line_load(b)) * tributary_m(model, i);
        st.multipliers[i] = f;
        given[if src.weight < 0.5 { a } else { b }] += f;
    }
    for (i, j) in old_at {
        if given[j] > 0.0 {
            st.multipliers[i] = (prev.multipliers[j] - given[j]).max(0.0);
        }
    }
}

/// Position and unit tangent at fraction `w` along the cubic through nodes `a` and `a + 1` of
/// `state` with their section axes as end tangents (oriented from `a` to `a + 1`).
fn hermite_point(state: &State, a: usize, w: f64) -> (Vec3, Vec3) {
    let (xa, xb) = (state.x[a], state.x[a + 1]);
    let d = xb - xa;
    let len = d.norm();
    let oriented = |t: Vec3| if t.dot(&d) < 0.0 { -t } else { t };
    let ta = oriented(state.triads[a].column(0).into_owned()) * len;
    let tb = oriented(state.triads[a + 1].column(0).into_owned()) * len;
    let (w2, w3) = (w * w, w * w * w);
    let x = xa * (2.0 * w3 - 3.0 * w2 + 1.0) + ta * (w3 - 2.0 * w2 + w) + xb * (-2.0 * w3 + 3.0 * w2) + tb * (w3 - w2);
    let dx = xa * (6.0 * w2 - 6.0 * w)
        + ta * (3.0 * w2 - 4.0 * w + 1.0)
        + xb * (-6.0 * w2 + 6.0 * w)
        + tb * (3.0 * w2 - 2.0 * w);
    let t = dx.normalize();
    let axis = state.triads[a].column(0).into_owned();
    (x, if axis.dot(&t) < 0.0 { -t } else { t })
}

/// `triad` turned by the smallest rotation that takes its first column (the section axis) onto
/// the unit vector `t`.
fn turned_onto(triad: &Matrix3<f64>, t: &Vec3) -> Matrix3<f64> {
    let a = triad.column(0).into_owned();
    let (v, c) = (a.cross(t), a.dot(t));
    if c <= -0.5 {
        // never for a section axis and a tangent of the same element; keep the triad
        return *triad;
    }
    // Rodrigues' formula for the rotation about a x t taking a onto t: I + [v] + [v]^2 / (1 + c)
    let k = skew(&v);
    (Matrix3::identity() + k + k * k / (1.0 + c)) * triad
}

/// Solve `model` cold with `ctl`, then, for the default contact scheme, refine its mesh at the
/// ends of the body contact runs of `scope` ([`near_bit_elements`]; `h_m`: the refined element
/// length) and solve again from the carried state. Returns the model solved last and its
/// solution (the statistics of both solves summed); if the refined solve does not converge, the
/// first model and solution (one pass is enough: docs/performance.md, "Fine BHA meshes").
pub fn solve_refined(
    model: Model,
    ctl: &SolveControls,
    scope: &Scope,
    h_m: f64,
) -> Result<(Model, Solution), SolveError> {
    solve_refined_by(model, ctl, scope, h_m, |m| solve(m, ctl))
}

/// [`solve_refined`] with the first (cold) solve made by `first`.
pub fn solve_refined_by(
    model: Model,
    ctl: &SolveControls,
    scope: &Scope,
    h_m: f64,
    first: impl FnOnce(&Model) -> Result<Solution, SolveError>,
) -> Result<(Model, Solution), SolveError> {
    let mut model = model;
    let sol = solve_holding_toolface(&mut model, ctl, first)?;
    if !sol.converged || ctl.method != Method::Newton {
        return Ok((model, sol));
    }
    let split = near_bit_elements(&model, &sol.state, scope, h_m);
    if split.is_empty() {
        return Ok((model, sol));
    }
    tracing::debug!(
        nodes = model.nodes(),
        highest_split = split.last().copied().unwrap_or(0),
        split = split.len(),
        "contact runs refined"
    );
    let mut fine = refined_model(&model, &split, h_m);
    let state = carried_state(&model, &sol.state, &fine);
    // a warm start near the solution converges with the full tangent (as the predictor's steps
    // and the loads rows do)
    fine.consistent_tangent = true;
    let rest = SolveControls {
        time_limit_s: ctl.time_limit_s - sol.stats.seconds,
        carried_start: true,
        ..*ctl
    };
    let highest = split.last().copied().unwrap_or(0);
    if let Some(mut again) = super::condense::solve_refined_lower(&model, &sol, &fine, highest, &state, &rest) {
        again.stats.continue_from(&sol.stats);
        return Ok((fine, again));
    }
    match solve_holding_toolface(&mut fine, &rest, |m| solve_interior_point_from(m, state, &rest)) {
        Ok(mut again) if again.converged => {
            again.stats.continue_from(&sol.stats);
            Ok((fine, again))
        }
        other => {
            let why = other.map_or_else(|e| e.to_string(), |_| "not converged".to_string());
            tracing::info!(%why, "refined solve failed; the unrefined solution stands");
            Ok((model, sol))
        }
    }
}
