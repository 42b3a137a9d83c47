//! Warm starts of the stiff string model: carry a solved [`State`] of one [`Model`] onto
//! another model of the same string in a (possibly) different place.
//!
//! Each node of the new model takes its state from a point of the previous model (a
//! [`Source`]: a node, or a point between two adjacent nodes). What is carried is what the
//! node holds *relative to the hole*: its lateral and axial offset from its axis point and its
//! triad, both in its node basis (the hole frame at its reference MD), its contact multipliers (scalar, and the vector one of a pin)
//! and normal, and the offset of its nearest axis point from its reference MD; the hook load is
//! kept. Between two source nodes the local values are interpolated linearly (the triad then
//! re-orthonormalized: adjacent nodes' triads differ by small rotations).
//!
//! Users: the predictor moves the bit along the hole with an unchanged mesh
//! ([`transport_state`], node `i` to node `i`); the torque-and-drag chart moves the bit to the
//! next bit depth, where the string is longer ([`crate::loads::stiff`] maps nodes by their
//! distance from the bit).

use crate::geometry::Vec3;
use crate::models::fem::element::rotation::orthonormalize;
use crate::models::fem::model::{Model, State};
use nalgebra::Matrix3;

/// Where a node of the new model takes its state: between node `node` and node `node + 1` of
/// the previous model, `weight` (in [0, 1)) being the share of node `node + 1` (0: node `node`
/// itself).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Source {
    /// Lower node of the previous model.
    pub node: usize,
    /// Share of node `node + 1`, in [0, 1).
    pub weight: f64,
    /// Scale the lateral offset by the ratio of the node's radial clearance to the source
    /// node's, so that a node lying on the wall stays on the wall when the hole or the contact
    /// diameter changes (for a node that moves along the hole with its source).
    pub scale_to_clearance: bool,
}

impl Source {
    /// Node `node` itself, offsets unscaled.
    pub fn node(node: usize) -> Source {
        Source {
            node,
            weight: 0.0,
            scale_to_clearance: false,
        }
    }
}

/// One node's state carried to node `i` of `model` (the predictor's rule, kept bit for bit).
struct Carried {
    x: Vec3,
    triad: Matrix3<f64>,
    md: f64,
    multiplier: f64,
    normal: Vec3,
    /// Vector multiplier of a pin (zero-clearance gap), N.
    pin_multiplier: Vec3,
}

fn carry(prev_model: &Model, prev: &State, j: usize, model: &Model, i: usize, lateral_scale: f64) -> Carried {
    let qp = &prev_model.basis[j];
    let qn = &model.basis[i];
    let rel = qn * qp.transpose();
    let p_prev = prev_model.axis_ref[j];
    let p_new = model.axis_ref[i];
    let mut d = prev.x[j] - p_prev;
    if lateral_scale != 1.0 {
        // scale the part across the hole axis (node basis columns 1 and 2)
        let t = qp.column(0).into_owned();
        let along = t * t.dot(&d);
        d = along + (d - along) * lateral_scale;
    }
    Carried {
        x: p_new + rel * d,
        triad: orthonormalize(&(rel * prev.triads[j])),
        md: model.md_ref[i] + (prev.md[j] - prev_model.md_ref[j]),
        multiplier: prev.multipliers[j],
        normal: rel * prev.normal[j],
        pin_multiplier: rel * prev.pin_multipliers[j],
    }
}

/// The state of `model` whose node `i` takes its state from `source(i)` in `prev_model` /
/// `prev` (see the module documentation); `None` leaves node `i` at its initial state (on
/// the hole axis, triad = node basis, no contact).
pub fn transport_mapped(
    prev_model: &Model,
    prev: &State,
    model: &Model,
    source: impl Fn(usize) -> Option<Source>,
) -> State {
    let mut st = model.initial_state();
    let last = prev_model.nodes() - 1;
    for i in 0..model.nodes() {
        let Some(src) = source(i) else { continue };
        let j = src.node.min(last);
        let scale = |j: usize| -> f64 {
            if !src.scale_to_clearance {
                return 1.0;
            }
            let c_prev = prev_model.clearance(j, prev.md[j]);
            let c_new = model.clearance(i, model.md_ref[i]);
            if c_prev > 1e-9 {
                c_new / c_prev
            } else {
                1.0
            }
        };
        let a = carry(prev_model, prev, j, model, i, scale(j));
        let w = src.weight;
        let c = if w > 0.0 && j < last {
            let b = carry(prev_model, prev, j + 1, model, i, scale(j + 1));
            let n = a.normal * (1.0 - w) + b.normal * w;
            Carried {
                x: a.x * (1.0 - w) + b.x * w,
                triad: orthonormalize(&(a.triad * (1.0 - w) + b.triad * w)),
                md: a.md * (1.0 - w) + b.md * w,
                multiplier: a.multiplier * (1.0 - w) + b.multiplier * w,
                normal: if n.norm() > 1e-12 { n.normalize() } else { a.normal },
                pin_multiplier: a.pin_multiplier * (1.0 - w) + b.pin_multiplier * w,
            }
        } else {
            a
        };
        st.x[i] = c.x;
        st.triads[i] = c.triad;
        st.md[i] = c.md;
        st.multipliers[i] = c.multiplier;
        st.normal[i] = c.normal;
        st.pin_multipliers[i] = c.pin_multiplier;
    }
    st.hook_load_n = prev.hook_load_n;
    st
}

/// Carry a solved state to the model with the bit moved and the same mesh (the predictor's
/// step): node `i` takes node `i`'s state relative to its node basis (position, triad,
/// contact force and normal, pin multiplier); the hook load is kept.
pub fn transport_state(prev_model: &Model, prev: &State, model: &Model) -> State {
    let n = prev_model.nodes();
    transport_mapped(prev_model, prev, model, |i| (i < n).then_some(Source::node(i)))
}

/// The [`Source`] of a point at distance `s_m` from the bit (m) among the nodes of `model`:
/// the bracketing nodes by their distance from the bit (`None` above the top node), offsets
/// unscaled.
pub fn source_by_distance(model: &Model, s_m: f64) -> Option<Source> {
    let nodes = &model.mesh.nodes;
    let top = nodes.last()?.s_m;
    if s_m > top + 1e-9 {
        return None;
    }
    // first node at or above s
    let k = nodes.partition_point(|n| n.s_m < s_m - 1e-9);
    if k == 0 {
        return Some(Source::node(0));
    }
    if k >= nodes.len() {
        return Some(Source::node(nodes.len() - 1));
    }
    if (nodes[k].s_m - s_m).abs() <= 1e-9 {
        return Some(Source::node(k));
    }
    let (a, b) = (nodes[k - 1].s_m, nodes[k].s_m);
    Some(Source {
        node: k - 1,
        weight: ((s_m - a) / (b - a)).clamp(0.0, 1.0 - 1e-12),
        scale_to_clearance: false,
    })
}
