//! A model's top node carrying the string above it condensed: the linearized force of the
//! part above on that node ([`CondensedTop`], [`super::model::TopCondition::Condensed`]), and
//! the part of a model from the bit to a node ([`Model::lower_part`]). The refined solve of the
//! assembly's mesh solves such a lower part (`models::fem::condense`, docs/theory.md 5.2).

use super::element::rotation::log_so3;
use super::model::{Model, State, TopCondition};
use crate::geometry::Vec3;
use nalgebra::{Matrix3, Matrix6, Vector6};
use std::sync::Arc;

/// The string above a model's top node, condensed onto it at a reference state: its force on
/// the node linearized in the node's DOF increments from the reference and in the hook load.
/// All in the node's DOF basis (three translations, three rotations; N and N.m per m and rad).
#[derive(Debug, Clone, PartialEq)]
pub struct CondensedTop {
    /// Residual of the part above at the node at the reference (its internal force less its
    /// loads, the part above itself in equilibrium to first order), N and N.m.
    pub force: Vector6<f64>,
    /// Condensed tangent stiffness of the part above at the node (the Schur complement of its
    /// tangent with the contact stiffness of its last linear solve).
    pub stiffness: Matrix6<f64>,
    /// Change of the residual at the node per newton of hook load (the hook load acting at the
    /// top of the part above, transmitted through it), 1.
    pub hook_column: Vector6<f64>,
    /// Reference position of the node (model frame), m.
    pub x0: Vec3,
    /// Reference triad of the node.
    pub triad0: Matrix3<f64>,
    /// Reference hook load, N.
    pub hook_load0_n: f64,
}

impl CondensedTop {
    /// DOF increment (node basis `q`) of a node at `x` (m) with `triad` from the reference:
    /// `q^T (x - x0)` and `q^T log(triad triad0^T)` (the spin the solver's updates apply).
    pub fn increment(&self, q: &Matrix3<f64>, x: &Vec3, triad: &Matrix3<f64>) -> Vector6<f64> {
        let dx = q.transpose() * (x - self.x0);
        let dw = q.transpose() * log_so3(&(triad * self.triad0.transpose()));
        Vector6::new(dx[0], dx[1], dx[2], dw[0], dw[1], dw[2])
    }

    /// The residual of the part above at the node (DOF basis `q`) at `x`, `triad` and the hook
    /// load `hook_load_n`: `force + stiffness du + hook_column (H - H0)`.
    pub fn residual(&self, q: &Matrix3<f64>, x: &Vec3, triad: &Matrix3<f64>, hook_load_n: f64) -> Vector6<f64> {
        self.force + self.stiffness * self.increment(q, x, triad) + self.hook_column * (hook_load_n - self.hook_load0_n)
    }
}

impl Model {
    /// Add the top node's force to the residual `r`: the hook load `H` along the top's axis
    /// (`-H t`), or the condensed part above ([`CondensedTop::residual`], its stiffness added to
    /// the tangent `k` when given).
    pub(crate) fn add_top_force(
        &self,
        state: &State,
        r: &mut [f64],
        k: Option<&mut (dyn super::model::StiffnessSink + '_)>,
    ) {
        let top = self.nodes() - 1;
        let TopCondition::Condensed(c) = &self.top else {
            r[self.dof(top, 0)] += state.hook_load_n;
            return;
        };
        let q = &self.basis[top];
        let f = c.residual(q, &state.x[top], &state.triads[top], state.hook_load_n);
        let dofs: [usize; 6] = std::array::from_fn(|k| self.dof(top, k));
        for (k, &d) in dofs.iter().enumerate() {
            r[d] += f[k];
        }
        if let Some(sink) = k {
            let blk: Vec<f64> = (0..36).map(|i| c.stiffness[(i / 6, i % 6)]).collect();
            sink.add_block(&dofs, &blk, 6);
        }
    }

    /// The residual's change per newton of hook load, by DOF: 1 at the top's axial DOF, or the
    /// condensed part's [`CondensedTop::hook_column`] at the top node.
    pub fn hook_column(&self) -> Vec<(usize, f64)> {
        let top = self.nodes() - 1;
        match &self.top {
            TopCondition::Condensed(c) => (0..6).map(|k| (self.dof(top, k), c.hook_column[k])).collect(),
            _ => vec![(self.dof(top, 0), 1.0)],
        }
    }

    /// The part of this model from the bit to node `top` (inclusive): the same nodes, elements,
    /// sections, bases and frame, so that the first `top + 1` nodes of a [`State`] of this model
    /// are a state of the part ([`lower_state`]); its top is `condensed`.
    ///
    /// # Panics
    /// If `top` is not a node above the bit.
    pub fn lower_part(&self, top: usize, condensed: CondensedTop) -> Model {
        assert!(top > 0 && top < self.nodes(), "Model::lower_part: a node above the bit");
        let mut m = self.clone();
        m.mesh.nodes.truncate(top + 1);
        m.mesh.elements.truncate(top);
        m.md_ref.truncate(top + 1);
        m.axis_ref.truncate(top + 1);
        m.basis.truncate(top + 1);
        m.sections.truncate(top);
        m.friction.truncate(top + 1);
        m.k_n.truncate(top + 1);
        m.top = TopCondition::Condensed(Arc::new(condensed));
        m
    }
}

/// The nodes `lo..=hi` of `state` (the hook load kept).
pub fn state_part(state: &State, lo: usize, hi: usize) -> State {
    let r = lo..hi + 1;
    State {
        x: state.x[r.clone()].to_vec(),
        triads: state.triads[r.clone()].to_vec(),
        md: state.md[r.clone()].to_vec(),
        multipliers: state.multipliers[r.clone()].to_vec(),
        normal: state.normal[r.clone()].to_vec(),
        hook_load_n: state.hook_load_n,
        pin_multipliers: state.pin_multipliers[r].to_vec(),
    }
}
