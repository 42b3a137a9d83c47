//! Mesh of the string along the hole axis, from the bit (node 0) to the surface.
//!
//! Nodes sit at component boundaries, stabilizer blade centres, tool joints, survey sensors
//! and the bend of a bent motor housing; elements are
//! at most `bha_element_length` in the bottom-hole assembly and `element_length` above
//! (docs/theory.md 5.2). Each node knows its contact diameter: blade OD at a stabilizer centre,
//! tool-joint OD at a joint, body OD elsewhere; the bit node has no gap (it is centred).

use crate::case::SolverSettings;
use crate::string::{ComponentKind, DrillString};

/// A node of the mesh.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MeshNode {
    /// Distance from the bit face along the unstressed string, m.
    pub s_m: f64,
    /// Contact diameter where this node may touch the wall, m.
    pub contact_od_m: f64,
    /// Whether the node carries a gap element (all but the bit and the top node).
    pub has_gap: bool,
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
    /// The bent housing's node and angle (None: a straight string).
    pub bend: Option<MeshBend>,
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

/// Build the mesh of `string` with `settings`' element lengths and mud density (kg/m3).
pub fn build_mesh(string: &DrillString, settings: &SolverSettings, mud_density_kg_m3: f64) -> Mesh {
    let total = string.length_m();
    let bha_top = string.bha_length_m();
    let mut marks: Vec<(f64, Option<f64>)> = vec![(0.0, None), (total, None)];
    for c in &string.components {
        marks.push((c.bottom_m, None));
        marks.push((c.top_m(), None));
        if let Some(b) = c.bend {
            // a node at the bent housing, where the unloaded axis kinks
            marks.push((b.to_bit_m, None));
        }
        if let Some(x) = c.sensor_to_bit_m {
            // a node at the survey sensor, where its sag angle is read
            marks.push((x, None));
        }
        if c.kind == ComponentKind::Stabilizer {
            marks.push((c.bottom_m + c.length_m / 2.0, Some(c.contact_od_m)));
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
    // merge marks closer than 1 mm, keeping the largest contact OD
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
    let mut nodes: Vec<MeshNode> = Vec::new();
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
            component: comp,
        }
    };
    for w in merged.windows(2) {
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
    let last = nodes.len() - 1;
    nodes[0].has_gap = false;
    nodes[last].has_gap = false;
    // the bit's own body above the face does not touch the wall
    for node in nodes.iter_mut() {
        if string.components[node.component].kind == ComponentKind::Bit
            && node.s_m < string.components[0].top_m() - 1e-6
        {
            node.has_gap = false;
        }
    }
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
            MeshElement {
                component: ci,
                buoyed_weight_n_per_m: c.buoyed_weight_n_per_m(mud_density_kg_m3),
                ea: c.ea_n(),
                ei: c.ei_nm2(),
                gj: c.gj_nm2(),
                od_m: c.body_od_m,
                id_m: c.id_m,
            }
        })
        .collect();
    let bend = string.bend().and_then(|b| {
        let node = nodes
            .iter()
            .enumerate()
            .min_by(|a, c| (a.1.s_m - b.to_bit_m).abs().total_cmp(&(c.1.s_m - b.to_bit_m).abs()))
            .map(|(k, _)| k)?;
        // a bend at the bit face or at the top of the string has no element on one side
        (node > 0 && node < nodes.len() - 1).then_some(MeshBend {
            node,
            angle_rad: b.angle_rad,
        })
    });
    Mesh { nodes, elements, bend }
}
