//! The start of the contact Newton: a frictionless soft string sets the stretch, the contact
//! sides and the first multipliers of the stiff string, smoothed and wound up. Only the start
//! changes, not the solution.
//!
//! [`cold_start`] is the interior-point Newton's sequence: [`stretch_start`],
//! [`soft_string_start`], [`smooth_start`], [`align_start`], [`wind_up_start`] on
//! [`Model::initial_state`].

use crate::geometry::min_curvature::AxisGeometry;
use crate::geometry::Vec3;
use crate::models::fem::model::{Model, State};
use crate::models::softstring;

/// Nodes closer than this to the bit start on the hole axis (not on the wall), m.
pub const START_OFF_WALL_M: f64 = 5.0;

/// The interior-point Newton's start of `model`: its initial state stretched, put on the
/// soft-string contact sides, smoothed, its triads turned along the smoothed centreline and
/// wound up.
pub fn cold_start(model: &Model) -> State {
    let mut state = model.initial_state();
    stretch_start(model, &mut state);
    soft_string_start(model, &mut state);
    smooth_start(model, &mut state);
    align_start(model, &mut state);
    wind_up_start(model, &mut state);
    state
}

/// A frictionless soft string on the hole axis at the nodes' MDs (physics.md 6.5 without
/// friction, [`softstring::element_balance`] per element), integrated from `-WOB` at the bit
/// upward with the axial weight `W tbar.e_D` of each element.
struct SoftStringPass {
    /// Axis point at each node's MD.
    axis: Vec<AxisGeometry>,
    /// Axial force at each element's centre, N (tension positive).
    mid_tension: Vec<f64>,
    /// Lateral load at each node, N (global): half of each adjacent element's.
    nodal_load: Vec<Vec3>,
    /// Axial force at the top, N.
    top_tension: f64,
}

impl SoftStringPass {
    /// The pass along the nodes' MDs `md` (bit first), m.
    fn along(model: &Model, md: &[f64]) -> SoftStringPass {
        let nn = model.nodes();
        let mut tension = -model.loads.wob_n;
        let mut nodal_load = vec![Vec3::zeros(); nn];
        let mut mid_tension = Vec::with_capacity(nn - 1);
        let axis: Vec<AxisGeometry> = md.iter().map(|&md| model.path.axis_at(md)).collect();
        for e in 0..nn - 1 {
            let w = model.mesh.elements[e].buoyed_weight_n_per_m * model.sections[e].l0;
            let b = softstring::element_balance(axis[e].tangent, axis[e + 1].tangent, tension, w);
            mid_tension.push(tension + 0.5 * w * b.tbar.z);
            nodal_load[e] += b.lateral * 0.5;
            nodal_load[e + 1] += b.lateral * 0.5;
            tension += w * b.tbar.z;
        }
        SoftStringPass {
            axis,
            mid_tension,
            nodal_load,
            top_tension: tension,
        }
    }
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
    let tension = SoftStringPass::along(model, &state.md).mid_tension;
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
        state.triads[i] = nalgebra::Matrix3::from_columns(&[t, b1, b2]);
        state.normal[i] = -model.path.frame_at(md).h;
    }
}

/// Soft-string start: axial force by integrating weight from the bit, contact side from the
/// lateral load of each element; nodes put on that side of the wall with the soft-string
/// normal force as their first multiplier (physics.md 4.5). Axis points at the nodes' MDs in
/// `state.md` (the reference MDs, or the stretched ones of [`stretch_start`]).
pub fn soft_string_start(model: &Model, state: &mut State) {
    let SoftStringPass {
        axis,
        nodal_load,
        top_tension,
        ..
    } = SoftStringPass::along(model, &state.md);
    if model.loads.hook_load_n.is_none() {
        state.hook_load_n = top_tension.max(0.0);
    }
    for (i, li) in nodal_load.iter().enumerate() {
        // near the bit the stiff assembly lifts off the wall: leave those nodes on the axis
        if !model.mesh.nodes[i].has_gap || li.norm() < 1e-6 || model.mesh.nodes[i].s_m < START_OFF_WALL_M {
            continue;
        }
        let n = li.normalize();
        let eo = model.clearance(i, state.md[i]);
        state.x[i] = axis[i].position + n * eo;
        state.multipliers[i] = li.norm();
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
            let share = model.loads.motion().friction_split(rc).tangential;
            torque += model.friction[i] * state.multipliers[i] * rc * share;
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
        let t = state.triads[i].column(0).into_owned();
        state.triads[i] = crate::models::fem::element::rotation::exp_so3(&(t * phi)) * state.triads[i];
    }
}

/// Largest lateral slope of the smoothed start between neighbouring nodes (m of lateral offset
/// per m along the string), see [`smooth_start`].
pub const START_MAX_SLOPE: f64 = 0.005;

/// Element length below which [`smooth_start`] allows less than [`START_MAX_SLOPE`]: across an
/// element of length `l` the offset may change by `START_MAX_SLOPE l min(1, l / this)`, m. A
/// change of slope `d` at a node is a kink of curvature `d / l`, whose nodal forces grow as
/// `EI d / l^2`: at [`START_MAX_SLOPE`] they were 600-1,200 load scales on 0.05 m elements
/// and 1e4-3e4 on 0.01 m ones, which stalled the interior point of the first Newton steps
/// (docs/performance.md, Fine BHA meshes). Below this length the slope allowed shrinks with
/// `l`, keeping the kinks' curvature at most `START_MAX_SLOPE / this`: fine meshes start
/// nearer the hole axis. The default meshes (0.5 m BHA elements, component ends and blade
/// centres seldom closer) are not affected.
pub const START_KINK_LENGTH_M: f64 = 0.25;

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
    // the lateral step allowed across each element
    let rise: Vec<f64> = (0..nn - 1)
        .map(|e| {
            let l = model.sections[e].l0;
            START_MAX_SLOPE * l * (l / START_KINK_LENGTH_M).min(1.0)
        })
        .collect();
    // a side change: both nodes leave the wall (the passes below ramp their neighbours)
    for (e, &step) in rise.iter().enumerate() {
        let (i, j) = (e, e + 1);
        if a[i] > 0.0 && a[j] > 0.0 {
            let jump = (dir[i] * a[i] - dir[j] * a[j]).norm() - (a[i] - a[j]).abs();
            if jump > step {
                a[i] = 0.0;
                a[j] = 0.0;
            }
        }
    }
    for (e, &step) in rise.iter().enumerate() {
        a[e + 1] = a[e + 1].min(a[e] + step);
    }
    for e in (0..nn - 1).rev() {
        a[e] = a[e].min(a[e + 1] + rise[e]);
    }
    for i in 0..nn {
        state.x[i] = axis[i] + dir[i] * a[i];
    }
}

/// Aligned start: turn the triad of each node between the bit and the top by the smallest
/// rotation that takes its section axis onto the tangent of the start's centreline there (the
/// three-point tangent of the node and its neighbours, `(l_a u_b + l_b u_a) / (l_a + l_b)` with
/// `u_b`, `u_a` the unit chords of the elements below and above and `l_b`, `l_a` their
/// lengths, exact for a parabola through the three nodes). [`smooth_start`] moves the nodes
/// off the hole axis (lateral slopes up to [`START_MAX_SLOPE`]) but the triads stay on the
/// axis frame: an element on such a ramp then has both end rotations off its chord by the
/// slope, a bending moment `~6 EI slope / l` and end shears `~12 EI slope / l^2`. On 0.5 m
/// elements that is a residual of 6-30 load scales; on 0.05 m elements of 600-1,200, and the
/// first interior-point solve stalls (steps of 1e-4 to the boundary) and so does every Newton
/// step after it (docs/performance.md, Fine BHA meshes). Turned along the centreline, the
/// start's residual is what its curvature carries. Only nodes next to an element shorter than
/// [`START_KINK_LENGTH_M`] are turned: on longer elements the first Newton step removes the
/// misalignment as it is (the default meshes' starts, and so their iteration counts, are
/// unchanged; turned everywhere, the horizontal example's whole-string solve took 17
/// iterations instead of 7). The bit's and the top node's triads are left as they are (the
/// bit is on the axis; the top's bending rotations may be held). Only the start changes, not
/// the solution.
pub fn align_start(model: &Model, state: &mut State) {
    let nn = model.nodes();
    for i in 1..nn.saturating_sub(1) {
        // chords point down the hole, like the triads' section axes
        let below = state.x[i - 1] - state.x[i];
        let above = state.x[i] - state.x[i + 1];
        let (lb, la) = (below.norm(), above.norm());
        if lb <= 0.0 || la <= 0.0 || lb.min(la) >= START_KINK_LENGTH_M {
            continue;
        }
        let tangent = (below * (la / lb) + above * (lb / la)).normalize();
        let t = state.triads[i].column(0).into_owned();
        let axis = t.cross(&tangent);
        let sin = axis.norm();
        if sin > 1e-15 {
            let angle = sin.atan2(t.dot(&tangent));
            state.triads[i] = crate::models::fem::element::rotation::exp_so3(&(axis * (angle / sin))) * state.triads[i];
        }
    }
}
