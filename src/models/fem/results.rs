//! Post-processing: bit forces and tilt, top reactions, and per-node results along the string
//! (docs/guide.md `summary.json` and `string.csv`), all SI.

use super::model::Model;
use super::solve::Solution;
use crate::geometry::Vec3;
use crate::units::G;

/// Bit results (physics.md 5).
#[derive(Debug, Clone, Copy)]
pub struct BitResult {
    /// Bit MD, m.
    pub md_m: f64,
    /// Weight on bit (bit on rock along t), N.
    pub wob_n: f64,
    /// Build force (bit on rock along h), N.
    pub build_force_n: f64,
    /// Walk force (bit on rock along r), N.
    pub walk_force_n: f64,
    /// Tilt toward higher inclination, rad.
    pub tilt_inc_rad: f64,
    /// Tilt to the right, rad.
    pub tilt_azi_rad: f64,
    /// Bit torque, N.m.
    pub torque_nm: f64,
    /// Sag angle at the survey sensor of the string's first `mwd` component with one
    /// (`sensor_to_bit`), rad ([`SensorResult::sag_rad`]); None without a sensor in the model.
    pub sensor_sag_rad: Option<f64>,
}

/// The survey sensor of an `mwd` component in a solved model: where it is and the sag angle
/// it reads.
#[derive(Debug, Clone, PartialEq)]
pub struct SensorResult {
    /// Name of the component carrying the sensor.
    pub component: String,
    /// Distance from the bit face to the sensor, m.
    pub sensor_to_bit_m: f64,
    /// MD of the sensor, m.
    pub md_m: f64,
    /// Sag angle: tilt of the string's axis at the sensor from the hole axis toward the high
    /// side, rad (the sensor reads the hole's inclination plus this; the correction is minus
    /// it).
    pub sag_rad: f64,
    /// Tilt of the axis at the sensor toward the right side, rad.
    pub tilt_right_rad: f64,
}

/// The sensors of `string` that lie on the solved `nodes` of `model` (from the bit up; a
/// sensor above a cut model's reported nodes is left out): each read at its node (the mesh
/// has a node at every sensor).
pub fn sensor_results(string: &crate::string::DrillString, model: &Model, nodes: &[NodeResult]) -> Vec<SensorResult> {
    string
        .components
        .iter()
        .filter_map(|c| {
            let x = c.sensor_to_bit_m?;
            let i = sensor_node(model, nodes.len(), x)?;
            Some(SensorResult {
                component: c.name.clone(),
                sensor_to_bit_m: x,
                md_m: nodes[i].md_m,
                sag_rad: nodes[i].tilt_high_rad,
                tilt_right_rad: nodes[i].tilt_right_rad,
            })
        })
        .collect()
}

/// The node of `model` among its first `n` (from the bit) at the sensor `sensor_to_bit_m`
/// (m) from the bit face, if one is there.
fn sensor_node(model: &Model, n: usize, sensor_to_bit_m: f64) -> Option<usize> {
    model.mesh.nodes[..n.min(model.mesh.nodes.len())]
        .iter()
        .position(|m| (m.s_m - sensor_to_bit_m).abs() < 1e-6)
}

/// The bit results of `sol` with the sag at the first sensor of `string` on `model`'s nodes
/// ([`BitResult::sensor_sag_rad`]): the bit of [`extract`] and the sag of [`sensor_results`],
/// without the other nodes' results.
pub fn bit_with_sensor(
    string: &crate::string::DrillString,
    model: &Model,
    sol: &Solution,
    mud_density_kg_m3: f64,
) -> BitResult {
    let mut bit = bit_result(model, sol);
    bit.sensor_sag_rad = string
        .components
        .iter()
        .find_map(|c| sensor_node(model, model.nodes(), c.sensor_to_bit_m?))
        .map(|i| node_result(model, sol, i, mud_density_kg_m3).tilt_high_rad);
    bit
}

/// Per-node results.
#[derive(Debug, Clone, Copy)]
pub struct NodeResult {
    /// Current MD (nearest axis point), m.
    pub md_m: f64,
    /// Position (north, east, tvd), m.
    pub position: Vec3,
    /// Lateral displacement from the axis toward the high side, m.
    pub disp_high_m: f64,
    /// Lateral displacement toward the right side, m.
    pub disp_right_m: f64,
    /// Radial clearance of the node's gap element, m (None where the node has no gap element:
    /// the bit face, the bit body, the top node).
    pub clearance_m: Option<f64>,
    /// Wall normal force, N.
    pub contact_force_n: f64,
    /// Contact angle in the gap plane, deg (0 high side, 90 right), 0 when not in contact.
    pub contact_angle_deg: f64,
    /// Effective axial force, N (tension positive).
    pub axial_force_n: f64,
    /// Torque, N.m.
    pub torque_nm: f64,
    /// Bending moment magnitude, N.m.
    pub bending_moment_nm: f64,
    /// Von Mises stress at the outer fibre, Pa.
    pub von_mises_pa: f64,
    /// Tilt of the string's axis from the hole axis toward the high side, rad: what a survey
    /// sensor here reads above the hole's inclination (the sag angle; at the bit, the bit
    /// tilt).
    pub tilt_high_rad: f64,
    /// Tilt of the string's axis from the hole axis toward the right, rad.
    pub tilt_right_rad: f64,
}

/// Summary of a solve.
#[derive(Debug, Clone)]
pub struct SolveResults {
    /// Bit.
    pub bit: BitResult,
    /// Hook load (top reaction), N.
    pub hook_load_n: f64,
    /// Surface torque (top reaction), N.m.
    pub surface_torque_nm: f64,
    /// Nodes from the bit upward.
    pub nodes: Vec<NodeResult>,
    /// Net external force on the whole string (should vanish), N.
    pub force_imbalance_n: Vec3,
    /// Net external moment about the bit (should vanish), N.m.
    pub moment_imbalance_nm: Vec3,
    /// Largest single external force term, N (for relative equilibrium checks).
    pub largest_force_n: f64,
}

impl SolveResults {
    /// The global equilibrium error: the net external force's magnitude over the largest single
    /// external force term (dimensionless).
    pub fn equilibrium_error(&self) -> f64 {
        self.force_imbalance_n.norm() / self.largest_force_n
    }
}

/// Extract results from a solution (`mud_density_kg_m3` for the hydrostatic pressure of the
/// stresses, kg/m3).
pub fn extract(model: &Model, sol: &Solution, mud_density_kg_m3: f64) -> SolveResults {
    let st = &sol.state;
    let r = &sol.eval.residual;
    let nn = model.nodes();
    let surface_torque = r[model.dof(nn - 1, 3)];
    let nodes = (0..nn).map(|i| node_result(model, sol, i, mud_density_kg_m3)).collect();
    let (force_imbalance_n, moment_imbalance_nm, largest_force_n) = imbalance(model, sol);
    SolveResults {
        bit: bit_result(model, sol),
        hook_load_n: st.hook_load_n,
        surface_torque_nm: surface_torque,
        nodes,
        force_imbalance_n,
        moment_imbalance_nm,
        largest_force_n,
    }
}

/// Bit forces (the reaction of the held bit DOFs, bit on rock, plus the lateral wall forces
/// of the bit's gauge) and tilt of a solution.
fn bit_result(model: &Model, sol: &Solution) -> BitResult {
    let r = &sol.eval.residual;
    // bit reaction (rock on bit) in global, bit on rock = minus that
    let qb = &model.basis[0];
    let react = qb * Vec3::new(r[model.dof(0, 0)], r[model.dof(0, 1)], r[model.dof(0, 2)]);
    let f_bit = -react;
    // the gauge's wall forces are the bit's too (their lateral part: the WOB is the face's)
    let gauge: Vec3 = (0..model.nodes())
        .filter(|&i| model.mesh.nodes[i].on_bit_gauge)
        .filter_map(|i| sol.eval.gaps[i].as_ref())
        .filter(|g| g.normal_force > 0.0)
        .map(|g| -g.force)
        .sum();
    let frame = model.path.frame_at(model.bit_md_m);
    let eb = sol.state.triads[0].column(0).into_owned();
    BitResult {
        md_m: model.bit_md_m,
        wob_n: f_bit.dot(&frame.t),
        build_force_n: (f_bit + gauge).dot(&frame.h),
        walk_force_n: (f_bit + gauge).dot(&frame.r),
        tilt_inc_rad: axis_tilt(&eb, &frame).0,
        tilt_azi_rad: axis_tilt(&eb, &frame).1,
        torque_nm: model.loads.bit_torque_nm,
        sensor_sag_rad: None,
    }
}

/// Results at node `i`: axial force, torque and bending moment averaged over the adjacent
/// element ends (element e: A = node e+1 upper, B = node e lower), position, contact and the
/// von Mises stress (`mud_density_kg_m3`, kg/m3, for the hydrostatic pressure).
fn node_result(model: &Model, sol: &Solution, i: usize, mud_density_kg_m3: f64) -> NodeResult {
    let (st, ev) = (&sol.state, &sol.eval);
    let nn = model.nodes();
    let mut ax = Vec::new();
    let mut tq = Vec::new();
    let mut bm = Vec::new();
    let mut sec: Option<usize> = None;
    if i > 0 {
        // element i-1, node i is its upper end A
        let e = i - 1;
        let resp = &ev.elements[e];
        let q = Vec3::new(0.0, 0.0, model.mesh.elements[e].buoyed_weight_n_per_m);
        let qa = q.dot(&resp.frame.column(0).into_owned());
        ax.push(resp.axial_force + qa * model.sections[e].l0 / 2.0);
        tq.push(resp.local_moments[0]);
        bm.push(resp.local_moments[1].hypot(resp.local_moments[2]));
        sec = Some(e);
    }
    if i < nn - 1 {
        let e = i;
        let resp = &ev.elements[e];
        let q = Vec3::new(0.0, 0.0, model.mesh.elements[e].buoyed_weight_n_per_m);
        let qa = q.dot(&resp.frame.column(0).into_owned());
        ax.push(resp.axial_force - qa * model.sections[e].l0 / 2.0);
        tq.push(-resp.local_moments[3]);
        bm.push(resp.local_moments[4].hypot(resp.local_moments[5]));
        sec = sec.or(Some(e));
    }
    let mean = |v: &[f64]| v.iter().sum::<f64>() / v.len() as f64;
    let (axial, torque, bend) = (mean(&ax), mean(&tq), mean(&bm));
    let md = if model.mesh.nodes[i].has_gap {
        st.md[i]
    } else {
        model.path.nearest_md(&st.x[i], st.md[i])
    };
    let p = model.path.point_at(md);
    let f = model.path.frame_at(md);
    let d = st.x[i] - p.position;
    let (dh, dr) = (d.dot(&f.h), d.dot(&f.r));
    let (cf, ang) = match &ev.gaps[i] {
        Some(g) if g.normal_force > 0.0 => {
            let a = g.normal.dot(&f.r).atan2(g.normal.dot(&f.h)).to_degrees();
            let a = crate::geometry::survey::degrees_in_turn(a, crate::geometry::survey::FULL_PRECISION_DECIMALS);
            (g.normal_force, a)
        }
        _ => (0.0, 0.0),
    };
    let el = &model.mesh.elements[sec.unwrap_or(0)];
    let (od, id) = (el.od_m, el.id_m);
    let area = std::f64::consts::PI / 4.0 * (od * od - id * id);
    let inertia = std::f64::consts::PI / 64.0 * (od.powi(4) - id.powi(4));
    // hydrostatic pressure at the well-frame TVD (the model frame's origin is at the bit)
    let pressure = mud_density_kg_m3 * G * (p.position.z + model.origin_m.z).max(0.0);
    let f_true = axial - pressure * area;
    let sa = f_true / area;
    let sb = bend * od / (2.0 * inertia);
    let tau = torque * od / (4.0 * inertia);
    let vm = ((sa.abs() + sb).powi(2) + 3.0 * tau * tau).sqrt();
    let (tilt_high_rad, tilt_right_rad) = axis_tilt(&st.triads[i].column(0).into_owned(), &f);
    NodeResult {
        md_m: md,
        position: st.x[i] + model.origin_m,
        disp_high_m: dh,
        disp_right_m: dr,
        clearance_m: model.mesh.nodes[i].has_gap.then_some(ev.clearance[i]),
        contact_force_n: cf,
        contact_angle_deg: ang,
        axial_force_n: axial,
        torque_nm: torque,
        bending_moment_nm: bend,
        von_mises_pa: vm,
        tilt_high_rad,
        tilt_right_rad,
    }
}

/// Tilt of the axis `e` (the node triad's first column) from the hole frame `f`'s tangent
/// toward its high side and its right side, rad.
fn axis_tilt(e: &Vec3, f: &crate::geometry::Frame) -> (f64, f64) {
    (e.dot(&f.h).atan2(e.dot(&f.t)), e.dot(&f.r).atan2(e.dot(&f.t)))
}

/// Global equilibrium of a solution: the net external force (N) and moment about the bit
/// (N.m) of the weight, mud drag, walls, bit and top reactions, hook load and bit torque, and
/// the largest single external force (N).
fn imbalance(model: &Model, sol: &Solution) -> (Vec3, Vec3, f64) {
    let (st, ev) = (&sol.state, &sol.eval);
    let r = &ev.residual;
    let nn = model.nodes();
    let mut fsum = Vec3::zeros();
    let mut msum = Vec3::zeros();
    let mut largest: f64 = 0.0;
    let origin = st.x[0];
    let mut add = |f: Vec3, m: Vec3, at: Vec3| {
        fsum += f;
        msum += m + (at - origin).cross(&f);
        largest = largest.max(f.norm());
    };
    for e in 0..nn - 1 {
        let w = model.mesh.elements[e].buoyed_weight_n_per_m * model.sections[e].l0;
        let mid = (st.x[e] + st.x[e + 1]) * 0.5;
        let e1 = ev.elements[e].frame.column(0).into_owned();
        let mud = -e1 * (model.mud_torque(e, 0.5 * (st.md[e] + st.md[e + 1])) * model.sections[e].l0);
        add(Vec3::new(0.0, 0.0, w), mud, mid);
    }
    for i in 0..nn {
        if let Some(g) = &ev.gaps[i] {
            if g.normal_force > 0.0 {
                add(g.force, g.moment, st.x[i]);
            }
        }
    }
    // reactions at constrained DOFs and the hook load (all equal the residual there)
    for i in [0, nn - 1] {
        let q = &model.basis[i];
        let mut fr = Vec3::zeros();
        let mut mr = Vec3::zeros();
        for c in 0..3 {
            // the top's axial DOF is free (loaded by the hook load, added below)
            if !(i == nn - 1 && c == 0) {
                fr += q.column(c) * r[model.dof(i, c)];
            }
            mr += q.column(c) * r[model.dof(i, 3 + c)];
        }
        // reactions act on the string as minus the residual's external counterpart:
        // f_int = f_ext + reaction, so the reaction force on the string is +residual there
        add(fr, mr, st.x[i]);
    }
    // a push-the-bit tool's pad force
    if let Some((node, f)) = model.pad_force() {
        add(f, Vec3::zeros(), st.x[node]);
    }
    // the applied hook load and bit torque
    add(
        -model.basis[nn - 1].column(0) * st.hook_load_n,
        Vec3::zeros(),
        st.x[nn - 1],
    );
    add(
        Vec3::zeros(),
        -model.basis[0].column(0) * model.loads.bit_torque_nm,
        st.x[0],
    );
    (fsum, msum, largest)
}
