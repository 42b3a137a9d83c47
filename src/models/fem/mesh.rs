//! Mesh of the string along the hole axis, from the bit (node 0) to the surface.
//!
//! Nodes sit at component boundaries, along stabilizer blades and bit gauges, at tool
//! joints, survey sensors and the bend of a bent motor housing; elements are at most `bha_element_length` in the bottom-hole assembly and
//! `element_length` above (docs/theory.md 5.2). Each node knows its contact diameter: blade OD
//! along a stabilizer's blades, bit OD along the bit's gauge, tool-joint OD at a joint, body
//! OD elsewhere; the bit node has no gap (it is centred). With `[solver] stabilizer_contact =
//! "point"` a stabilizer touches at its middle only and the bit at its face only.

use super::contact::gap::ZERO_CLEARANCE_M;
use crate::case::{SolverSettings, StabilizerContact};
use crate::string::{ComponentKind, DrillString};

/// Contact points per BHA element length along a blade or gauge with a clearance: they are at
/// most `bha_element_length / BLADE_POINTS_PER_ELEMENT` apart (0.1 m by default), so that the
/// blade's contact moment and a contact inside the blade are resolved (docs/theory.md 3.4).
pub const BLADE_POINTS_PER_ELEMENT: f64 = 5.0;
/// Fewest intervals between contact points along a blade or gauge with a clearance (five
/// points on a blade: ends, quarters, middle).
pub const MIN_BLADE_INTERVALS: f64 = 4.0;
/// Bending stiffness of a full-gauge blade (and of a bit's gauge in a hole of its size)
/// relative to its body. With no clearance the blade cannot tilt in the hole: it is a stiff
/// segment held on the axis at its two ends, which carries the clamping moment as a couple of
/// forces at its ends (as a rigid blade bears on its edges). Contact points all along it
/// would clamp it too, but through forces alternating in sign that grow as the points close
/// up (a chain of rigid supports), and their friction with them (docs/theory.md 3.4). 100
/// leaves the blade a rotation of `M b / (600 EI)` under the moment `M` of the span above it;
/// 1000 stalled the solve of wells/volve-f10.
pub const RIGID_BLADE_FACTOR: f64 = 100.0;

/// How a stabilizer's blades or a bit's gauge touch the wall.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Touch {
    /// At one point (a stabilizer's middle).
    Point(f64),
    /// At points along `lo..hi` (from the bit face, m), each with the contact OD (a blade or
    /// gauge with a clearance).
    Along(f64, f64),
    /// A full-gauge blade or gauge (no clearance along `lo..hi`): a stiff segment held on the
    /// axis at its ends (the bit's face holds a gauge's lower end).
    Rigid(f64, f64),
}

/// Where component `k` of `string` touches the wall along its blade or gauge, with the
/// contact OD; `hole_at(s)` is the hole diameter `s` m above the bit, m. None for components
/// that touch with their whole body (and a bit without gauge).
fn touch_of(string: &DrillString, k: usize, settings: &SolverSettings, hole_at: &dyn Fn(f64) -> f64) -> Option<Touch> {
    let c = &string.components[k];
    let blade = settings.stabilizer_contact == StabilizerContact::Blade;
    let zone = c.contact_zone_m().filter(|_| blade);
    let full_gauge = |lo: f64, hi: f64| {
        [lo, 0.5 * (lo + hi), hi]
            .iter()
            .all(|&s| hole_at(s) - c.contact_od_m <= 2.0 * ZERO_CLEARANCE_M)
    };
    match (c.kind, zone) {
        (ComponentKind::Stabilizer, Some((lo, hi))) if hi - lo > 1e-3 => Some(if full_gauge(lo, hi) {
            Touch::Rigid(lo, hi)
        } else {
            Touch::Along(lo, hi)
        }),
        (ComponentKind::Stabilizer, _) => Some(Touch::Point(c.bottom_m + c.length_m / 2.0)),
        (ComponentKind::Bit, Some((lo, hi))) if hi - lo > 1e-3 => Some(if full_gauge(lo, hi) {
            Touch::Rigid(lo, hi)
        } else {
            Touch::Along(lo, hi)
        }),
        _ => None,
    }
}

/// The contact marks of a touch (`(distance from the bit face, contact OD)`) of component
/// kind `kind` with contact OD `od`: evenly along a blade or gauge with a clearance (a gauge's
/// above the face), the ends of a full-gauge blade (a full gauge's top), a point.
fn touch_marks(touch: Touch, kind: ComponentKind, od: f64, settings: &SolverSettings) -> Vec<(f64, Option<f64>)> {
    let od = Some(od);
    match touch {
        Touch::Point(s) => vec![(s, od)],
        Touch::Along(lo, hi) => {
            let spacing = settings.bha_element_length_m / BLADE_POINTS_PER_ELEMENT;
            let n = ((hi - lo) / spacing - 1e-9).ceil().max(MIN_BLADE_INTERVALS) as usize;
            let first = usize::from(kind == ComponentKind::Bit);
            (first..=n)
                .map(|k| (lo + (hi - lo) * k as f64 / n as f64, od))
                .collect()
        }
        Touch::Rigid(_, hi) if kind == ComponentKind::Bit => vec![(hi, od)],
        Touch::Rigid(lo, hi) => vec![(lo, od), (hi, od)],
    }
}

/// A node of the mesh.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MeshNode {
    /// Distance from the bit face along the unstressed string, m.
    pub s_m: f64,
    /// Contact diameter where this node may touch the wall, m.
    pub contact_od_m: f64,
    /// Whether the node carries a gap element (all but the bit and the top node).
    pub has_gap: bool,
    /// Whether the node is on the bit's gauge (its wall force is part of the bit's force on
    /// the rock).
    pub on_bit_gauge: bool,
    /// Index of the component this node belongs to (the lower one at a boundary).
    pub component: usize,
}

/// An element between nodes `e` and `e + 1`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MeshElement {
    /// Index of the component holding the element.
    pub component: usize,
    /// Buoyed weight per length, N/m.
    pub buoyed_weight_n_per_m: f64,
    /// Axial stiffness EA, N.
    pub ea: f64,
    /// Bending stiffness EI, N.m2.
    pub ei: f64,
    /// Torsional stiffness GJ, N.m2.
    pub gj: f64,
    /// Body OD (for stress and mud torque), m.
    pub od_m: f64,
    /// Bore, m.
    pub id_m: f64,
}

/// Nodes from the bit upward and the elements between consecutive nodes.
#[derive(Debug, Clone)]
pub struct Mesh {
    /// Nodes, bit first.
    pub nodes: Vec<MeshNode>,
    /// Elements, `elements[e]` joins nodes e and e+1.
    pub elements: Vec<MeshElement>,
    /// The kink's node and angle: a bent housing's bend or a point-the-bit hinge (None: a
    /// straight string).
    pub bend: Option<MeshBend>,
    /// A push-the-bit tool's pads (None: none).
    pub pad: Option<MeshPad>,
}

/// Where a push-the-bit tool's pads push, on the mesh.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MeshPad {
    /// Index of the node at the pads.
    pub node: usize,
    /// Pad force, N (applied toward the toolface).
    pub force_n: f64,
}

/// The node of `nodes` nearest `s_m` (m above the bit).
fn nearest_node(nodes: &[MeshNode], s_m: f64) -> Option<usize> {
    nodes
        .iter()
        .enumerate()
        .min_by(|a, c| (a.1.s_m - s_m).abs().total_cmp(&(c.1.s_m - s_m).abs()))
        .map(|(k, _)| k)
}

/// The pads of `string`'s push-the-bit tool on `nodes` (None without one).
fn pad_node(string: &DrillString, nodes: &[MeshNode]) -> Option<MeshPad> {
    let crate::string::RssSteer::PushTheBit {
        pad_force_n,
        pad_to_bit_m,
    } = string.rss()?.steer
    else {
        return None;
    };
    let node = nearest_node(nodes, pad_to_bit_m)?;
    Some(MeshPad {
        node,
        force_n: pad_force_n,
    })
}

/// Where the unloaded string axis kinks: a bent motor housing on the mesh.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MeshBend {
    /// Index of the node at the bend (> 0): the element below it (`node - 1`) is the one whose
    /// unloaded axis is turned by the bend.
    pub node: usize,
    /// Bend angle, rad.
    pub angle_rad: f64,
}

/// The node of `nodes` at the kink of `string` (a bent housing's bend, a point-the-bit
/// hinge: [`DrillString::kink`]; None for a straight string, or a kink at the first or last
/// node, which has no element on one side).
fn bend_node(string: &DrillString, nodes: &[MeshNode]) -> Option<MeshBend> {
    let b = string.kink()?;
    let node = nearest_node(nodes, b.to_bit_m)?;
    (node > 0 && node < nodes.len() - 1).then_some(MeshBend {
        node,
        angle_rad: b.angle_rad,
    })
}

/// Build the mesh of `string` with `settings`' element lengths and contact model and mud
/// density `mud_density_kg_m3` (kg/m3); `hole_at(s)` is the hole diameter `s` m above the bit
/// (m), which tells a full-gauge blade from one with a clearance.
pub fn build_mesh(
    string: &DrillString,
    settings: &SolverSettings,
    mud_density_kg_m3: f64,
    hole_at: &dyn Fn(f64) -> f64,
) -> Mesh {
    let touches: Vec<Option<Touch>> = (0..string.components.len())
        .map(|k| touch_of(string, k, settings, hole_at))
        .collect();
    let marks = merged_marks(string, &touches, settings);
    let mut nodes = subdivided_nodes(string, &marks, settings);
    let last = nodes.len() - 1;
    nodes[0].has_gap = false;
    nodes[last].has_gap = false;
    // the bit's own body above the face does not touch the wall, except along its gauge (at
    // the top of a full gauge)
    let gauge = match touches.first().copied().flatten() {
        Some(Touch::Along(_, hi)) => Some((hi, false)),
        Some(Touch::Rigid(_, hi)) => Some((hi, true)),
        _ => None,
    };
    let bit_top = string.components[0].top_m();
    for node in nodes.iter_mut() {
        let s = node.s_m;
        let on_gauge = node.has_gap
            && gauge.is_some_and(|(top, rigid)| {
                if rigid {
                    (s - top).abs() < 1e-6
                } else {
                    s > 1e-6 && s <= top + 1e-6
                }
            });
        node.on_bit_gauge = on_gauge;
        if !on_gauge && string.components[node.component].kind == ComponentKind::Bit && s < bit_top - 1e-6 {
            node.has_gap = false;
        }
    }
    let rigid: Vec<(f64, f64)> = touches
        .iter()
        .filter_map(|t| match t {
            Some(Touch::Rigid(lo, hi)) => Some((*lo, *hi)),
            _ => None,
        })
        .collect();
    let elements = nodes
        .windows(2)
        .map(|w| {
            let mid = 0.5 * (w[0].s_m + w[1].s_m);
            let ci = string
                .components
                .iter()
                .position(|c| mid < c.top_m())
                .unwrap_or(string.components.len() - 1);
            let c = &string.components[ci];
            let stiff = rigid.iter().any(|&(lo, hi)| mid > lo && mid < hi);
            MeshElement {
                component: ci,
                buoyed_weight_n_per_m: c.buoyed_weight_n_per_m(mud_density_kg_m3),
                ea: c.ea_n(),
                ei: c.ei_nm2() * if stiff { RIGID_BLADE_FACTOR } else { 1.0 },
                gj: c.gj_nm2(),
                od_m: c.body_od_m,
                id_m: c.id_m,
            }
        })
        .collect();
    let bend = bend_node(string, &nodes);
    let pad = pad_node(string, &nodes);
    Mesh {
        nodes,
        elements,
        bend,
        pad,
    }
}

/// The node marks of `string` (component ends, the contact marks of `touches`, tool joints),
/// sorted and merged when closer than 1 mm (keeping the largest contact OD).
fn merged_marks(string: &DrillString, touches: &[Option<Touch>], settings: &SolverSettings) -> Vec<(f64, Option<f64>)> {
    let mut marks: Vec<(f64, Option<f64>)> = vec![(0.0, None), (string.length_m(), None)];
    for (c, touch) in string.components.iter().zip(touches) {
        marks.push((c.bottom_m, None));
        marks.push((c.top_m(), None));
        if let Some(b) = c.bend {
            // a node at the bent housing, where the unloaded axis kinks
            marks.push((b.to_bit_m, None));
        }
        if let Some(r) = c.rss {
            // a node at the pads or the hinge of a rotary steerable system
            marks.push((r.position_to_bit_m(), None));
        }
        if let Some(x) = c.sensor_to_bit_m {
            // a node at the survey sensor, where its sag angle is read
            marks.push((x, None));
        }
        if let Some(t) = touch {
            marks.extend(touch_marks(*t, c.kind, c.contact_od_m, settings));
        }
        if let Some(tj) = c.tool_joint_od_m {
            let mut s = c.bottom_m;
            while s < c.top_m() - 1e-6 {
                marks.push((s, Some(tj)));
                s += c.joint_length_m;
            }
        }
    }
    marks.sort_by(|a, b| a.0.total_cmp(&b.0));
    let mut merged: Vec<(f64, Option<f64>)> = Vec::new();
    for (s, od) in marks {
        match merged.last_mut() {
            Some(last) if (s - last.0).abs() < 1e-3 => {
                last.1 = match (last.1, od) {
                    (Some(a), Some(b)) => Some(a.max(b)),
                    (a, b) => a.or(b),
                }
            }
            _ => merged.push((s, od)),
        }
    }
    merged
}

/// Nodes at `marks`, subdivided evenly so that no element exceeds the BHA or pipe element
/// length; each with its contact OD (a mark's, else its component's body, or the wider of two
/// bodies at a boundary) and a gap.
fn subdivided_nodes(string: &DrillString, marks: &[(f64, Option<f64>)], settings: &SolverSettings) -> Vec<MeshNode> {
    let bha_top = string.bha_length_m();
    let node_at = |s: f64, special: Option<f64>| -> MeshNode {
        let comp = string
            .components
            .iter()
            .position(|c| s < c.top_m() - 1e-9)
            .unwrap_or(string.components.len() - 1);
        let c = &string.components[comp];
        let mut od = match c.kind {
            ComponentKind::Stabilizer | ComponentKind::Bit => c.body_od_m,
            _ => c.contact_od_m,
        };
        // at a boundary the wider body of the two neighbours may touch
        if comp > 0 && (s - c.bottom_m).abs() < 1e-6 {
            let below = &string.components[comp - 1];
            if below.kind != ComponentKind::Bit {
                od = od.max(if below.kind == ComponentKind::Stabilizer {
                    below.body_od_m
                } else {
                    below.contact_od_m
                });
            }
        }
        if let Some(sp) = special {
            od = od.max(sp);
        }
        MeshNode {
            s_m: s,
            contact_od_m: od,
            has_gap: true,
            on_bit_gauge: false,
            component: comp,
        }
    };
    let mut nodes: Vec<MeshNode> = Vec::new();
    for w in marks.windows(2) {
        let (s0, od0) = w[0];
        let (s1, _) = w[1];
        if nodes.is_empty() {
            nodes.push(node_at(s0, od0));
        }
        let mid = 0.5 * (s0 + s1);
        let max_len = if mid <= bha_top + 1e-6 {
            settings.bha_element_length_m
        } else {
            settings.element_length_m
        };
        let n = ((s1 - s0) / max_len - 1e-9).ceil().max(1.0) as usize;
        for k in 1..=n {
            let s = s0 + (s1 - s0) * k as f64 / n as f64;
            let special = if k == n { w[1].1 } else { None };
            nodes.push(node_at(s, special));
        }
    }
    nodes
}
