//! The model's top node: the force there (the hook load along the top's axis, or a condensed
//! part above, [`CondensedTop`]), the hook load's column of the residual, and the part of a
//! model from the bit to a node ([`Model::lower_part`]) with its state ([`state_part`]).

use super::condensed_top::CondensedTop;
use super::model::{Model, State, StiffnessSink, TopCondition};
use std::sync::Arc;

impl Model {
    /// Add the top node's force to the residual `r`: the hook load `H` along the top's axis
    /// (`-H t`), or the condensed part above ([`CondensedTop::residual`], its stiffness added to
    /// the tangent `k` when given).
    pub(crate) fn add_top_force(&self, state: &State, r: &mut [f64], k: Option<&mut (dyn StiffnessSink + '_)>) {
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
            let blk: [f64; 36] = std::array::from_fn(|i| c.stiffness[(i / 6, i % 6)]);
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
    /// are a state of the part ([`state_part`]); its top is `condensed`.
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

/// The nodes from the bit to `top` (inclusive) of `state`, the hook load kept: a state of
/// [`Model::lower_part`] of the same `top`.
pub fn state_part(state: &State, top: usize) -> State {
    let r = ..top + 1;
    State {
        x: state.x[r].to_vec(),
        triads: state.triads[r].to_vec(),
        md: state.md[r].to_vec(),
        multipliers: state.multipliers[r].to_vec(),
        normal: state.normal[r].to_vec(),
        hook_load_n: state.hook_load_n,
        pin_multipliers: state.pin_multipliers[r].to_vec(),
    }
}
