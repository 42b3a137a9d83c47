//! The assembled whole-string model: mesh on the hole, loads, boundary conditions, and the
//! evaluation of residual and tangent for a given state.
//!
//! DOFs: 6 per node (3 displacements, 3 spins) in the node's fixed basis `Q = [t, b1, b2]`
//! (hole tangent and Bishop normals at the node's reference MD). Nodes are numbered from the
//! bit (node 0) upward, but DOFs are ordered from the surface down so that the bottom-hole
//! assembly, where contacts change most, sits at the end of the band (tail refactoring).

use super::element::beam::BeamSection;
use super::element::corotational::{element_forces, element_response_into, ElementForces, ElementState, Mat12};
use super::kink::Kink;
use super::mesh::{build_mesh, Mesh};
use crate::case::{Case, Motion};
use crate::geometry::{HoleSize, Vec3, WellPath};
use crate::models::fem::contact::gap::{evaluate, GapInput, GapResponse};
use crate::string::DrillString;
use nalgebra::Matrix3;

/// Half bandwidth of the node-chain stiffness (6 DOF per node, neighbours only).
pub const HALF_BANDWIDTH: usize = 11;

/// Penalty stiffness of a gap element as a multiple of EI/l^3 of its element; the
/// augmented-Lagrangian updates remove the penetration it leaves.
pub const PENALTY_FACTOR: f64 = 10.0;

pub use super::stiffness_sink::StiffnessSink;

/// Loads and kinematics of the operation, SI.
#[derive(Debug, Clone, Copy)]
pub struct Loads {
    /// Weight on bit, N (the solver finds the hook load that gives it).
    pub wob_n: f64,
    /// Hook load given instead (N): then the bit reaction is the output.
    pub hook_load_n: Option<f64>,
    /// Bit torque, N.m (applied about -t at the bit).
    pub bit_torque_nm: f64,
    /// String spin, rad/s ([`crate::case::Operation::motion`]).
    pub omega_rad_s: f64,
    /// Axial speed, m/s, positive down ([`crate::case::Operation::motion`]).
    pub axial_speed_m_s: f64,
    /// Mud plastic viscosity for the drag torque, Pa.s (0: off).
    pub mud_viscosity_pa_s: f64,
    /// Toolface of the bent housing, rad ([`crate::case::Operation::toolface_rad`]; no effect
    /// on a straight string).
    pub toolface_rad: f64,
}

/// How the model's top node is held.
#[derive(Debug, Clone, PartialEq)]
pub enum TopCondition {
    /// The whole string: the top is the rotary table, held on the hole axis laterally and in
    /// twist, free to tilt; the hook load acts along the axis.
    Surface,
    /// A bottom part of the string cut where it lies steadily on the wall (physics.md 3.7, the
    /// `bha` fidelity): the cut node is held at `offset_m` (global, m) from the hole axis, its
    /// axis clamped parallel to the hole and its twist held; the axial force there plays the
    /// hook load's role.
    Cut {
        /// Lateral position of the cut node relative to the hole axis (global), m.
        offset_m: Vec3,
    },
    /// A lower part of a model whose top node carries the part above condensed onto it
    /// ([`super::condensed_top::CondensedTop`]): nothing held there; the hook load acts through
    /// the condensed part.
    Condensed(std::sync::Arc<super::condensed_top::CondensedTop>),
}

impl Loads {
    /// The string's motion, whose [`Motion::friction_split`] at each contact sets the
    /// direction of wall friction.
    pub fn motion(&self) -> Motion {
        Motion {
            axial_speed_m_s: self.axial_speed_m_s,
            omega_rad_s: self.omega_rad_s,
        }
    }
}

/// Loads and kinematics of `case`'s operation: WOB or hook load, bit torque
/// ([`crate::models::bit::bit_torque_nm`] at the case's WOB), spin and axial speed
/// ([`crate::case::Operation::motion`]), mud drag.
pub fn loads_from_case(case: &Case) -> Loads {
    let op = &case.operation;
    let motion = op.motion();
    let bit_torque = crate::models::bit::bit_torque_nm(case, op.wob_n);
    Loads {
        wob_n: op.wob_n,
        hook_load_n: op.hook_load_n,
        bit_torque_nm: bit_torque,
        omega_rad_s: motion.omega_rad_s,
        axial_speed_m_s: motion.axial_speed_m_s,
        mud_viscosity_pa_s: if op.viscous_torque {
            case.mud.plastic_viscosity_pa_s
        } else {
            0.0
        },
        toolface_rad: op.toolface_rad,
    }
}

/// Static description of the discretized problem.
#[derive(Debug, Clone)]
pub struct Model {
    /// Hole axis, in the model frame (see [`Model::origin_m`]).
    pub path: WellPath,
    /// Well-frame position (north, east, TVD) of the model frame's origin, m: the hole axis
    /// at the bit. Positions in [`Model::path`], [`Model::axis_ref`] and [`State::x`] are
    /// relative to it, so that they stay small where the stiffness is (the bottom-hole
    /// assembly): with well-frame coordinates, a bit 10 km from the first station or a
    /// map-grid `[well] origin` rounds positions to ~1e-12 to 1e-9 m, and the axial forces of
    /// short stiff elements computed from them carry noise above the residual tolerance.
    /// Outputs add it back ([`super::results`]).
    pub origin_m: Vec3,
    /// Hole diameter along the well.
    pub hole: HoleSize,
    /// Mesh.
    pub mesh: Mesh,
    /// Bit MD, m.
    pub bit_md_m: f64,
    /// Reference MD of each node, m.
    pub md_ref: Vec<f64>,
    /// Hole-axis position at each node's reference MD (`path.axis_at(md_ref[i]).position`), m.
    pub axis_ref: Vec<Vec3>,
    /// DOF basis per node.
    pub basis: Vec<Matrix3<f64>>,
    /// Element sections (with stress-free chord length).
    pub sections: Vec<BeamSection>,
    /// Friction coefficient per node.
    pub friction: Vec<f64>,
    /// Penalty stiffness per node, N/m.
    pub k_n: Vec<f64>,
    /// Loads.
    pub loads: Loads,
    /// Whether the axial-force/bending coupling is on (off only to demonstrate its effect).
    pub geometric_stiffness: bool,
    /// Full consistent element tangent (needed under torque; slower), see
    /// [`super::element::corotational::element_response`].
    pub consistent_tangent: bool,
    /// How the top node is held.
    pub top: TopCondition,
    /// The bent housing's kink in the unloaded axis (None: a straight string).
    pub kink: Option<Kink>,
    /// The motor's reactive torque turning a sliding bent housing's toolface (None: off,
    /// [`super::reactive`]).
    pub reactive: Option<super::reactive::ReactiveTorque>,
    /// MD intervals `(top, bottom)`, m, where a rotating string whirls
    /// ([`crate::models::whirl`]): wall friction there keeps its torque and its axial drag but
    /// not its lateral push round the wall. Empty: the full friction law everywhere.
    pub whirl_md_m: Vec<(f64, f64)>,
    /// The housing toolface (rad) the interior-point Newton holds the bent housing at by
    /// turning its kink as it iterates, the turn in the solution's statistics
    /// ([`super::solve::SolveStats::kink_turned_to_rad`]); None (the default): the kink stays
    /// as set. The predictor sets it for each state's solve;
    /// [`super::solve::toolface::solve_holding_toolface`] takes the turned kink and clears it.
    pub toolface_hold_rad: Option<f64>,
}

/// Mechanical state of the string: what a solve finds, what a warm start carries.
#[derive(Debug, Clone)]
pub struct State {
    /// Node positions (model frame), m.
    pub x: Vec<Vec3>,
    /// Node material triads (columns: the section's axis and its two principal directions,
    /// global).
    pub triads: Vec<Matrix3<f64>>,
    /// MD of each node's nearest axis point, m.
    pub md: Vec<f64>,
    /// Wall normal force multiplier of each gap node, N (the contact force of a closed gap,
    /// regularized by the penalty unless [`GapTreatment::exact_multipliers`]).
    pub multipliers: Vec<f64>,
    /// Last contact normal per node (outward, global).
    pub normal: Vec<Vec3>,
    /// Hook load (top axial force), N.
    pub hook_load_n: f64,
    /// Vector multipliers of the zero-clearance gaps (pins), N: the wall force of a pin.
    pub pin_multipliers: Vec<Vec3>,
}

/// How an evaluation treats the gap elements: the contact scheme's settings, owned by the
/// solver and passed to [`Model::evaluate`] beside the mechanical [`State`]. The default
/// puts every gap under the unilateral law `R = max(0, multiplier + k_n (s - EO))` and the pins
/// as penalty springs about their vector multipliers.
#[derive(Debug, Clone, Default)]
pub struct GapTreatment {
    /// Contact status per node imposed by the solver: `true` closed (bilateral: the force
    /// `multiplier + k_n (s - EO)` may turn negative), `false` open (no force). `None`: the
    /// unilateral law everywhere.
    pub closed: Option<Vec<bool>>,
    /// Nodes under the unilateral law whatever `closed` says (the modified Newton's open and
    /// frozen gaps).
    pub unilateral: Option<Vec<bool>>,
    /// Gaps whose normal and friction forces the solver applies itself (the interior-point
    /// contact step, friction in proportion to the unknown normal force): the evaluation
    /// leaves both out of the residual and assembles only the stiffness of the friction's
    /// direction at the node's multiplier.
    pub solver_contacts: Option<Vec<bool>>,
    /// Closed gaps carry exactly their multiplier (no penalty term): the final evaluation of a
    /// solution whose contact forces came from the interior-point step.
    pub exact_multipliers: bool,
    /// Zero-clearance gaps (pins) are exact constraints: the node is held on the hole axis (its
    /// lateral DOFs are held by the solver) and its wall force is the reaction that balances
    /// the lateral residual of everything else, friction included ([`Model::pin_reaction`]);
    /// the pin's multiplier in [`State::pin_multipliers`] is set to it at each evaluation,
    /// and the force is that reaction alone (no penalty on an offset from the axis, which the
    /// solver removes by prescribed lateral increments). `false`: penalty springs about the
    /// multiplier.
    pub exact_pins: bool,
}

/// Everything evaluated at a state.
pub struct Evaluation {
    /// Residual `f_int - f_ext`, DOF order (surface first), node bases.
    pub residual: Vec<f64>,
    /// Element responses, bit upward (`elements[e]` joins nodes e+1 = end A and e = end B).
    pub elements: Vec<ElementForces>,
    /// Gap responses per node (None: no gap or open far from the wall).
    pub gaps: Vec<Option<GapResponse>>,
    /// Radial clearance per node, m.
    pub clearance: Vec<f64>,
    /// Nearest axis point of each gap node (position m, unit tangent) at `state.md`, as the
    /// gaps were evaluated (zeros for nodes without a gap).
    pub axis: Vec<(Vec3, Vec3)>,
}

impl Model {
    /// Build the whole-string model of `case` with the bit at `case.operation.bit_md_m`.
    pub fn from_case(case: &Case) -> Model {
        Model::for_string(
            case,
            &case.string,
            &case.well.path,
            &case.well.hole,
            case.operation.bit_md_m,
        )
    }

    /// The model of `string` (the case's or a part of it, bit first) with the bit at
    /// `bit_md_m` in the hole `path`/`hole`, with `case`'s mud, operation and mesh settings;
    /// the top is held as [`TopCondition::Surface`].
    pub fn for_string(case: &Case, string: &DrillString, path: &WellPath, hole: &HoleSize, bit_md_m: f64) -> Model {
        let mesh = build_mesh(string, &case.solver, case.mud.density_kg_m3, &|s| {
            hole.diameter_at(bit_md_m - s)
        });
        let mut model = Model::new(
            path.clone(),
            hole.clone(),
            mesh,
            bit_md_m,
            loads_from_case(case),
            |md| hole.friction_at(md).unwrap_or(case.operation.friction),
        );
        model.reactive = super::reactive::reactive_torque(case, string, bit_md_m);
        model
    }

    /// Build from parts; `friction_at(md)` gives the wall friction coefficient. `path` is in
    /// the well frame; the model keeps it moved to its own frame ([`Model::origin_m`]).
    pub fn new(
        path: WellPath,
        hole: HoleSize,
        mesh: Mesh,
        bit_md_m: f64,
        loads: Loads,
        friction_at: impl Fn(f64) -> f64,
    ) -> Model {
        Model::with_known_frames(path, hole, mesh, bit_md_m, loads, friction_at, |_| None)
    }

    /// [`Model::new`] with the DOF basis and the axis position (model frame) of node `i` taken
    /// from `known(i)` where it gives them (a refinement of a model keeps its old nodes'),
    /// computed from the path elsewhere.
    pub fn with_known_frames(
        path: WellPath,
        hole: HoleSize,
        mesh: Mesh,
        bit_md_m: f64,
        loads: Loads,
        friction_at: impl Fn(f64) -> f64,
        known: impl Fn(usize) -> Option<(Matrix3<f64>, Vec3)>,
    ) -> Model {
        let origin_m = path.axis_at(bit_md_m).position;
        let path = path.translated(-origin_m);
        let md_ref: Vec<f64> = mesh.nodes.iter().map(|n| bit_md_m - n.s_m).collect();
        // the DOF bases and the axis positions of the nodes (each shared by the two elements
        // that meet there)
        let (basis, axis_ref): (Vec<Matrix3<f64>>, Vec<Vec3>) = md_ref
            .iter()
            .enumerate()
            .map(|(i, &md)| {
                known(i).unwrap_or_else(|| {
                    let (t, b1, b2) = path.bishop_at(md);
                    (Matrix3::from_columns(&[t, b1, b2]), path.axis_at(md).position)
                })
            })
            .unzip();
        let sections = mesh
            .elements
            .iter()
            .enumerate()
            .map(|(e, el)| {
                let l0 = (axis_ref[e + 1] - axis_ref[e]).norm();
                BeamSection {
                    l0,
                    ea: el.ea,
                    ei: el.ei,
                    gj: el.gj,
                }
            })
            .collect::<Vec<_>>();
        let nn = mesh.nodes.len();
        let k_n = (0..nn)
            .map(|i| {
                let e = if i == 0 { 0 } else { i - 1 };
                let s = &sections[e.min(sections.len() - 1)];
                PENALTY_FACTOR * s.ei / s.l0.powi(3)
            })
            .collect();
        let friction = md_ref.iter().map(|&m| friction_at(m)).collect();
        let kink = Kink::of_mesh(&mesh, &basis, loads.toolface_rad);
        Model {
            path,
            origin_m,
            hole,
            mesh,
            bit_md_m,
            md_ref,
            axis_ref,
            basis,
            sections,
            friction,
            k_n,
            loads,
            geometric_stiffness: true,
            consistent_tangent: false,
            top: TopCondition::Surface,
            kink,
            reactive: None,
            whirl_md_m: Vec::new(),
            toolface_hold_rad: None,
        }
    }

    /// Whether node `i` lies in a whirling interval ([`Model::whirl_md_m`]).
    pub fn whirls(&self, i: usize) -> bool {
        let md = self.md_ref[i];
        self.whirl_md_m.iter().any(|&(top, bottom)| md >= top && md <= bottom)
    }

    /// True when friction acts on a moving string: the consistent tangent is then unsymmetric.
    pub fn needs_unsymmetric(&self) -> bool {
        self.friction.iter().any(|&f| f > 0.0) && self.loads.motion().is_moving()
    }

    /// Number of nodes.
    pub fn nodes(&self) -> usize {
        self.mesh.nodes.len()
    }

    /// Number of DOFs.
    pub fn dofs(&self) -> usize {
        6 * self.nodes()
    }

    /// Global DOF index of local DOF `k` (0..6) of node `i` (bit = 0): surface first.
    pub fn dof(&self, i: usize, k: usize) -> usize {
        6 * (self.nodes() - 1 - i) + k
    }

    /// DOFs held fixed: the bit's three translations (the axial one through the hook-load
    /// equation); at a surface top its two lateral translations and its twist, at a cut top
    /// all but its axial translation, at a condensed top none.
    pub fn constrained_dofs(&self) -> Vec<usize> {
        let top = self.nodes() - 1;
        let mut c = vec![self.dof(0, 0), self.dof(0, 1), self.dof(0, 2)];
        match self.top {
            TopCondition::Surface => c.extend([self.dof(top, 1), self.dof(top, 2), self.dof(top, 3)]),
            TopCondition::Cut { .. } => c.extend((1..6).map(|k| self.dof(top, k))),
            TopCondition::Condensed(_) => {}
        }
        c
    }

    /// Initial state: nodes on the hole axis (a cut top at its offset), triads = node bases.
    pub fn initial_state(&self) -> State {
        let nn = self.nodes();
        let mut x = self.axis_ref.clone();
        if let TopCondition::Cut { offset_m } = self.top {
            x[nn - 1] += offset_m;
        }
        State {
            x,
            triads: self.basis.clone(),
            md: self.md_ref.clone(),
            multipliers: vec![0.0; nn],
            normal: self.md_ref.iter().map(|&m| -self.path.frame_at(m).h).collect(),
            hook_load_n: self.loads.hook_load_n.unwrap_or(0.0),
            pin_multipliers: vec![Vec3::zeros(); nn],
        }
    }

    /// Radial clearance at node `i` when its nearest axis point is at `md`, m (>= 0).
    pub fn clearance(&self, i: usize, md: f64) -> f64 {
        ((self.hole.diameter_at(md) - self.mesh.nodes[i].contact_od_m) / 2.0).max(0.0)
    }

    /// Mud drag torque per length on element `e`, N.m/m (laminar Couette, physics.md 2.4).
    pub fn mud_torque(&self, e: usize, md: f64) -> f64 {
        let mu = self.loads.mud_viscosity_pa_s;
        let w = self.loads.omega_rad_s;
        if mu <= 0.0 || w <= 0.0 {
            return 0.0;
        }
        let r1 = self.mesh.elements[e].od_m / 2.0;
        let r2 = self.hole.diameter_at(md) / 2.0;
        if r2 <= r1 * 1.0001 {
            return 0.0;
        }
        4.0 * std::f64::consts::PI * mu * w * r1 * r1 * r2 * r2 / (r2 * r2 - r1 * r1)
    }

    /// Evaluate residual (and, if `k` is given, assemble the tangent into it) at `state`, the
    /// gaps treated as `gaps` says. Updates each gap node's nearest-axis MD in `state.md` and
    /// contact normal in `state.normal` (and, with exact pins, the pins' multipliers).
    pub fn evaluate(&self, state: &mut State, gaps: &GapTreatment, k: Option<&mut dyn StiffnessSink>) -> Evaluation {
        self.evaluate_with(state, gaps, k, None)
    }

    /// [`Model::evaluate`] without the tangent, taking the element responses from `elements`
    /// (the [`Evaluation::elements`] of an evaluation at the same node positions and triads)
    /// instead of computing them again: for a second evaluation of the same configuration with
    /// other contact settings (the solver's final evaluation with exact multipliers). The
    /// result is the same as `evaluate(state, gaps, None)` bit for bit.
    ///
    /// # Panics
    /// If `elements` does not hold one response per element.
    pub fn evaluate_reusing_elements(
        &self,
        state: &mut State,
        gaps: &GapTreatment,
        elements: Vec<ElementForces>,
    ) -> Evaluation {
        assert_eq!(
            elements.len(),
            self.nodes().saturating_sub(1),
            "Model::evaluate_reusing_elements: one response per element"
        );
        self.evaluate_with(state, gaps, None, Some(elements))
    }

    /// The push-the-bit pads' force on the string (global, N) and its node: the pad force along
    /// the toolface direction ([`crate::geometry::frame::toolface_direction`] at the node's
    /// unloaded axis, the model's toolface), fixed in space (the tool holds its toolface
    /// whatever the string does). None without pads or with a zero force.
    pub fn pad_force(&self) -> Option<(usize, Vec3)> {
        let p = self.mesh.pad.filter(|p| p.force_n != 0.0)?;
        let t = self.basis[p.node].column(0).into_owned();
        let d = crate::geometry::frame::toolface_direction(&t, self.loads.toolface_rad);
        Some((p.node, d * p.force_n))
    }

    fn evaluate_with(
        &self,
        state: &mut State,
        gaps: &GapTreatment,
        k: Option<&mut dyn StiffnessSink>,
        reuse: Option<Vec<ElementForces>>,
    ) -> Evaluation {
        let nn = self.nodes();
        let mut r = vec![0.0; self.dofs()];
        let mut kmat = k;
        if let Some(km) = kmat.as_deref_mut() {
            if nn < 2 {
                km.clear();
            }
        }
        let elements = self.assemble_elements(state, &mut r, kmat.as_deref_mut(), reuse);
        // bit torque: moment -T_b t at the bit node
        let tb = self.basis[0].column(0).into_owned() * (-self.loads.bit_torque_nm);
        let tb_loc = self.basis[0].transpose() * tb;
        for k in 0..3 {
            r[self.dof(0, 3 + k)] -= tb_loc[k];
        }
        // push-the-bit pads: a force of set magnitude toward the toolface at the pad node
        if let Some((node, f)) = self.pad_force() {
            let f_loc = self.basis[node].transpose() * f;
            for k in 0..3 {
                r[self.dof(node, k)] -= f_loc[k];
            }
        }
        self.add_top_force(state, &mut r, kmat.as_deref_mut());
        let mut ev = Evaluation {
            residual: r,
            elements,
            gaps: vec![None; nn],
            clearance: vec![0.0; nn],
            axis: vec![(Vec3::zeros(), Vec3::zeros()); nn],
        };
        let pins = self.assemble_gaps(state, gaps, &mut ev, kmat);
        self.apply_exact_pins(state, gaps, &pins, &mut ev);
        ev
    }

    /// Element responses from the bit upward (taken from `reuse` when given), their internal
    /// forces minus their gravity and mud-drag loads added to the residual `r`, and with `k`
    /// their tangents assembled into it (each node's lines zeroed just before the first
    /// element that touches them).
    fn assemble_elements(
        &self,
        state: &State,
        r: &mut [f64],
        mut k: Option<&mut (dyn StiffnessSink + '_)>,
        reuse: Option<Vec<ElementForces>>,
    ) -> Vec<ElementForces> {
        let nn = self.nodes();
        let mut reuse = reuse.map(|v| v.into_iter());
        let mut elements = Vec::with_capacity(nn - 1);
        let mut tangent = Mat12::zeros();
        for e in 0..nn - 1 {
            let (a, b) = (e + 1, e);
            let given = reuse.as_mut().map(|v| v.next().expect("one response per element"));
            let want = k.is_some() && given.is_none();
            let (resp, terms) =
                self.element_terms(state, e, given, want.then_some(&mut tangent), self.consistent_tangent);
            let first = self.dof(a, 0);
            for (j, t) in terms.iter().enumerate() {
                r[first + j] += t;
            }
            if let Some(km) = k.as_deref_mut() {
                // each node's lines are zeroed just before the first element that touches
                // them (element e is the first for node e + 1, element 0 also for node 0):
                // the matrix is built in one pass while its rows are in cache
                if e == 0 {
                    km.clear_dofs(self.dof(b, 0)..self.dof(b, 0) + 6);
                }
                km.clear_dofs(first..first + 6);
                km.add_element(first, &tangent);
            }
            elements.push(resp);
        }
        elements
    }

    /// Element `e` at `state`: its response (`given`, or computed) and its 12 residual terms
    /// (internal force less its gravity and mud-drag loads, upper node's DOFs first, node
    /// bases); with `tangent`, its tangent stiffness written there (`consistent`: the full
    /// consistent tangent with the end moments' load stiffness where the tangent is
    /// unsymmetric; `given` must then be None).
    #[inline(always)]
    pub(crate) fn element_terms(
        &self,
        state: &State,
        e: usize,
        given: Option<ElementForces>,
        tangent: Option<&mut Mat12>,
        consistent: bool,
    ) -> (ElementForces, [f64; 12]) {
        // Node A is the upper node (e + 1), B the lower (e): the chord points down the hole
        // like the triads' first axis.
        let (a, b) = (e + 1, e);
        // the section below a bent housing is turned by the kink (the same spin: the offset
        // is constant in the node's material frame)
        let kinked;
        let lam_a = match self.kink {
            Some(k) if k.element == e => {
                kinked = state.triads[a] * k.offset;
                &kinked
            }
            _ => &state.triads[a],
        };
        let st = ElementState {
            x_a: &state.x[a],
            x_b: &state.x[b],
            lam_a,
            lam_b: &state.triads[b],
            q_a: &self.basis[a],
            q_b: &self.basis[b],
        };
        let mut tangent = tangent;
        let resp = match (given, tangent.as_deref_mut()) {
            (Some(r), _) => r,
            (None, Some(t)) => element_response_into(&st, &self.sections[e], self.geometric_stiffness, consistent, t),
            (None, None) => element_forces(&st, &self.sections[e], self.geometric_stiffness),
        };
        // gravity: consistent nodal loads of q = w_b e_D on the current chord
        let l = self.sections[e].l0;
        let q = Vec3::new(0.0, 0.0, 1.0) * self.mesh.elements[e].buoyed_weight_n_per_m;
        let e1 = resp.frame.column(0).into_owned();
        let fa = q * (l / 2.0);
        let ma = e1.cross(&q) * (l * l / 12.0);
        // mud drag torque about -t, lumped
        let c = self.mud_torque(e, 0.5 * (state.md[e] + state.md[e + 1])) * l / 2.0;
        let mt = -e1 * c;
        let (qa, qb) = (&self.basis[a], &self.basis[b]);
        let ext = [
            qa.transpose() * fa,
            qa.transpose() * (ma + mt),
            qb.transpose() * fa,
            qb.transpose() * (-ma + mt),
        ];
        let terms = std::array::from_fn(|j| resp.force[j] - ext[j / 3][j % 3]);
        if let Some(t) = tangent {
            if consistent && self.needs_unsymmetric() {
                self.add_end_moment_load_stiffness(state, e, &e1, &q, c, t);
            }
        }
        (resp, terms)
    }

    /// Add to the element tangent `tangent` of element `e` (chord direction `e1`, weight per
    /// length `q`, N/m, global; `c` its mud torque lumped at each end, N.m) the load stiffness
    /// of the end moments that follow the chord `r1` (gravity's consistent moments and the mud
    /// torque):
    /// `dr1/dx_B = -dr1/dx_A = (I - r1 r1^T)/L`. Unsymmetric, so only in the unsymmetric (LU)
    /// tangent: a symmetric band store keeps one triangle.
    fn add_end_moment_load_stiffness(&self, state: &State, e: usize, e1: &Vec3, q: &Vec3, c: f64, tangent: &mut Mat12) {
        let (a, b) = (e + 1, e);
        let l = self.sections[e].l0;
        let chord = state.x[b] - state.x[a];
        let dr1 = (Matrix3::identity() - e1 * e1.transpose()) / chord.norm();
        let qx = q.cross_matrix() * (l * l / 12.0);
        // d(ext moment)/dr1 at A (ma + mt) and at B (-ma + mt)
        let dm = [-qx - Matrix3::identity() * c, qx - Matrix3::identity() * c];
        let bases = [&self.basis[a], &self.basis[b]];
        for (end, dme) in dm.iter().enumerate() {
            for (col, sign) in [(0usize, -1.0), (6usize, 1.0)] {
                // residual = internal - external: minus the load's derivative
                let blk = bases[end].transpose() * dme * dr1 * bases[col / 6] * (-sign);
                for rr in 0..3 {
                    for cc in 0..3 {
                        tangent[(6 * end + 3 + rr, col + cc)] += blk[(rr, cc)];
                    }
                }
            }
        }
    }

    /// Gap forces of every gap node but the exact pins, subtracted from `ev.residual` (and
    /// their stiffness assembled into `k`); fills `ev.gaps`, `ev.clearance` and `ev.axis`, and
    /// updates each gap node's nearest-axis MD and contact normal in `state`. Returns the
    /// exact pins, whose force needs the lateral residual of everything else
    /// ([`Model::apply_exact_pins`]).
    fn assemble_gaps(
        &self,
        state: &mut State,
        gaps: &GapTreatment,
        ev: &mut Evaluation,
        mut kmat: Option<&mut (dyn StiffnessSink + '_)>,
    ) -> Vec<usize> {
        let r = &mut ev.residual;
        let mut pins = Vec::new();
        for i in 0..self.nodes() {
            if !self.mesh.nodes[i].has_gap {
                continue;
            }
            let (md, p) = self.path.nearest_axis(&state.x[i], state.md[i]);
            state.md[i] = md;
            ev.axis[i] = (p.position, p.tangent);
            let eo = self.clearance(i, md);
            ev.clearance[i] = eo;
            if gaps.exact_pins && eo <= crate::models::fem::contact::gap::ZERO_CLEARANCE_M {
                // applied below, once the lateral residual of everything else is known
                pins.push(i);
                continue;
            }
            let g = evaluate(&self.gap_input(state, gaps, i, state.x[i] - p.position, p.tangent, eo));
            // the solver's contacts: the solver adds their forces itself (friction
            // proportional to the unknown normal force); only the friction's geometric
            // stiffness comes from here
            let force_here = !gaps.solver_contacts.as_ref().is_some_and(|q| q[i]);
            if g.normal_force != 0.0 || g.active || g.force != Vec3::zeros() {
                let qb = &self.basis[i];
                if force_here {
                    let f = qb.transpose() * g.force;
                    let m = qb.transpose() * g.moment;
                    for k in 0..3 {
                        r[self.dof(i, k)] -= f[k];
                        r[self.dof(i, 3 + k)] -= m[k];
                    }
                }
                if let Some(km) = kmat.as_deref_mut() {
                    // 6x6 block of the node: translations <- translations (wall force) and
                    // rotations <- translations (friction moment); row-major
                    let kt = qb.transpose() * g.stiffness * qb;
                    let kr = qb.transpose() * g.moment_stiffness * qb;
                    let mut blk = [0.0; 36];
                    for r in 0..3 {
                        for c in 0..3 {
                            blk[r * 6 + c] = kt[(r, c)];
                            blk[(r + 3) * 6 + c] = kr[(r, c)];
                        }
                    }
                    let d: [usize; 6] = std::array::from_fn(|k| self.dof(i, k));
                    km.add_block(&d, &blk, 6);
                }
                state.normal[i] = g.normal;
            }
            ev.gaps[i] = Some(g);
        }
        pins
    }

    /// Wall forces of the exact `pins` ([`GapTreatment::exact_pins`]): each pin's multiplier
    /// becomes the reaction to the lateral residual of everything else
    /// ([`Model::pin_reaction`]), and its force (that reaction, no penalty on its offset) with
    /// its friction is subtracted from `ev.residual`.
    fn apply_exact_pins(&self, state: &mut State, gaps: &GapTreatment, pins: &[usize], ev: &mut Evaluation) {
        let r = &mut ev.residual;
        for &i in pins {
            let q = &self.basis[i];
            // lateral residual of everything but the pin (basis DOFs 1 and 2), global
            let e_lat = q.column(1) * r[self.dof(i, 1)] + q.column(2) * r[self.dof(i, 2)];
            let (p, t) = ev.axis[i];
            let offset = state.x[i] - p;
            state.pin_multipliers[i] = self.pin_reaction(i, &t, &(-e_lat));
            // the exact pin's force is the reaction alone: no penalty on its offset (which the
            // solver removes by the pin's prescribed lateral increment)
            let mut input = self.gap_input(state, gaps, i, offset, t, ev.clearance[i]);
            input.k_n = 0.0;
            let g = evaluate(&input);
            let f = q.transpose() * g.force;
            let m = q.transpose() * g.moment;
            for k in 0..3 {
                r[self.dof(i, k)] -= f[k];
                r[self.dof(i, 3 + k)] -= m[k];
            }
            state.normal[i] = g.normal;
            ev.gaps[i] = Some(g);
        }
    }

    /// Gap input of node `i` at `state` with lateral `offset` (m) from the axis point of tangent
    /// `t` and clearance `eo` (m), treated as `gaps` says.
    fn gap_input(&self, state: &State, gaps: &GapTreatment, i: usize, offset: Vec3, t: Vec3, eo: f64) -> GapInput {
        let solver_contact = gaps.solver_contacts.as_ref().is_some_and(|q| q[i]);
        GapInput {
            offset,
            t,
            clearance: eo,
            contact_radius: self.mesh.nodes[i].contact_od_m / 2.0,
            lambda: state.multipliers[i],
            k_n: if gaps.exact_multipliers && eo > crate::models::fem::contact::gap::ZERO_CLEARANCE_M {
                0.0
            } else {
                self.k_n[i]
            },
            friction: self.friction[i],
            axial_speed: self.loads.axial_speed_m_s,
            omega: self.loads.omega_rad_s,
            fallback_normal: state.normal[i],
            status: match (&gaps.closed, &gaps.unilateral) {
                _ if solver_contact => Some(false),
                (_, Some(f)) if f[i] => None,
                (Some(c), _) => Some(c[i]),
                (None, _) => None,
            },
            lambda_vec: state.pin_multipliers[i],
            friction_load: solver_contact.then_some(state.multipliers[i]),
            whirl: self.whirls(i),
        }
    }

    /// Apply the increment `du` (DOF order, node bases) to `state`, scaled by `alpha`.
    pub fn update(&self, state: &mut State, du: &[f64], alpha: f64) {
        for i in 0..self.nodes() {
            let q = &self.basis[i];
            let dx = Vec3::new(du[self.dof(i, 0)], du[self.dof(i, 1)], du[self.dof(i, 2)]) * alpha;
            let dw = Vec3::new(du[self.dof(i, 3)], du[self.dof(i, 4)], du[self.dof(i, 5)]) * alpha;
            state.x[i] += q * dx;
            let w = q * dw;
            state.triads[i] =
                super::element::rotation::orthonormalize(&(super::element::rotation::exp_so3(&w) * state.triads[i]));
        }
    }
}
