//! The string above the refined runs condensed onto a node, for the refined solve of the
//! assembly's mesh ([`super::refine`]; docs/theory.md 5.2, "The refined solve of the lower
//! part").
//!
//! The refinement splits elements near the bit only, so the string above them is the same in
//! the plain and the refined model, and, the DOFs being numbered from the surface down, its
//! DOFs lead both. The plain solve's last Newton step factored `K + N diag(R/s) N^T` by an LU
//! without pivoting, whose leading rows are the LU of that block: the part above a cut node
//! condenses onto it ([`CondensedTop`]: the Schur complement of its block, its force at the
//! plain solution and the hook load's column) at the cost of a few substitutions. The lower
//! part is solved with that top ([`Model::lower_part`]), the part above follows linearly
//! (`Upper::follow`: its increments and the contact forces of its contacts in the plain
//! step's contact stiffness), and the whole refined model is checked from there with the
//! solver's own convergence test.

use super::condensed_top::CondensedTop;
use super::element::corotational::Mat12;
use super::model::{Model, State};
use super::model_top::state_part;
use super::solve::interior_point_newton::steps_until_likely;
use super::solve::solution::{LastLinearization, Solution};
use super::solve::{solve_interior_point_from, SolveControls};
use crate::geometry::Vec3;
use nalgebra::{Matrix6, Vector6};

/// The refined solve of `fine` (the refinement of `plain` whose highest split element is
/// `highest_split`) from the `carried` state of the plain solution `sol`, by its lower part:
/// the part of `plain` above a cut node [`CUT_MARGIN_NODES`] above the split condensed onto it
/// ([`Upper::condense`]), the lower part of `fine` solved with that top up to its step likely
/// the last ([`steps_until_likely`]: the check below evaluates it), the part above moved by its
/// linear response ([`Upper::follow`]) and the whole of `fine` solved from there (its first
/// evaluation without the tangent: converged there, that is the whole cost). None, with the
/// reason in the debug log, where it does not apply (a kink, pads above the cut, no last
/// linearization, no cut node) or does not converge: the caller solves `fine` whole.
pub(crate) fn solve_refined_lower(
    plain: &Model,
    sol: &Solution,
    fine: &Model,
    highest_split: usize,
    carried: &State,
    ctl: &SolveControls,
) -> Option<Solution> {
    let declined = |why: &str| {
        tracing::debug!(why, "refined solve by the lower part declined");
        None
    };
    // a bent housing's toolface is held by turning its kink between solves
    // (`solve_holding_toolface`), which the whole refined solve does
    if plain.kink.is_some() || plain.toolface_hold_rad.is_some() {
        return declined("a bent housing");
    }
    let Some(cut) = cut_node(plain, highest_split + 1 + CUT_MARGIN_NODES) else {
        return declined("no cut node above the split");
    };
    if plain.mesh.pad.is_some_and(|p| p.node >= cut) {
        return declined("pads above the cut");
    }
    let Some(upper) = Upper::condense(plain, sol, cut) else {
        return declined("no last linearization of the plain solve");
    };
    let c = cut + fine.nodes() - plain.nodes();
    let lower = fine.lower_part(c, upper.top.clone());
    let (low_state, low, ok) = steps_until_likely(&lower, state_part(carried, c), ctl).ok()?;
    if !ok {
        return declined("the lower part did not converge");
    }
    let mut state = carried.clone();
    put_part(&mut state, &low_state);
    if !upper.follow(plain, fine, &mut state) {
        return declined("the part above does not solve");
    }
    let check = SolveControls {
        likely_converged_start: true,
        ..*ctl
    };
    let Some(mut whole) = solve_interior_point_from(fine, state, &check)
        .ok()
        .filter(|s| s.converged)
    else {
        return declined("the whole refined model did not converge from the parts");
    };
    tracing::debug!(
        cut_s_m = plain.mesh.nodes[cut].s_m,
        lower_iterations = low.iterations,
        check_iterations = whole.stats.iterations,
        "refined solve by the lower part"
    );
    whole.stats.add_work(&low);
    whole.stats.lower_part_refined = true;
    Some(whole)
}

/// `part` (the state of the first nodes of `state`'s model, and a hook load) put into `state`.
fn put_part(state: &mut State, part: &State) {
    let n = part.x.len();
    state.x[..n].copy_from_slice(&part.x);
    state.triads[..n].copy_from_slice(&part.triads);
    state.md[..n].copy_from_slice(&part.md);
    state.multipliers[..n].copy_from_slice(&part.multipliers);
    state.normal[..n].copy_from_slice(&part.normal);
    state.pin_multipliers[..n].copy_from_slice(&part.pin_multipliers);
    state.hook_load_n = part.hook_load_n;
}

/// Nodes between the top of the highest split element and the cut node.
pub const CUT_MARGIN_NODES: usize = 2;

/// The part of a plain model above a cut node, condensed from the plain solve's last
/// linearization.
pub(crate) struct Upper<'a> {
    /// The plain solve's last linear system.
    last: &'a LastLinearization,
    /// Leading DOFs (the part above the cut), the same in the plain and the refined model.
    m: usize,
    /// The cut node in the plain model.
    cut: usize,
    /// The plain solution's residual over the leading DOFs (held DOFs zeroed), N and N.m.
    r_u: Vec<f64>,
    /// The coupling `A_Uc` of the cut's six DOFs with the node above it (its rows: the last six
    /// leading DOFs; the rest of `A_Uc` is zero).
    a_uc: Matrix6<f64>,
    /// The hook-load column over the leading DOFs.
    hook_u: Vec<f64>,
    /// The condensed top of the lower part.
    pub(crate) top: CondensedTop,
}

/// The first node at or above `lowest` (plain model) where neither it nor the node above is a
/// pin (a zero-clearance gap: held on the axis, its force coupled to its neighbours), with at
/// least two nodes above it; None if there is none.
fn cut_node(plain: &Model, lowest: usize) -> Option<usize> {
    let pin = |i: usize| {
        plain.mesh.nodes[i].has_gap && plain.clearance(i, plain.md_ref[i]) <= super::contact::gap::ZERO_CLEARANCE_M
    };
    (lowest..plain.nodes().saturating_sub(2)).find(|&c| !pin(c) && !pin(c + 1))
}

impl<'a> Upper<'a> {
    /// The part of `plain` above node `cut` condensed onto it at the converged `sol` (its last
    /// linearization); None without one or with a singular leading block.
    pub(crate) fn condense(plain: &Model, sol: &'a Solution, cut: usize) -> Option<Upper<'a>> {
        let last = sol.last_linearization.as_deref()?;
        let m = plain.dof(cut, 0);
        let mut is_held = vec![false; m + 6];
        for &d in &last.constrained {
            if d < is_held.len() {
                is_held[d] = true;
            }
        }
        let held = |d: usize| is_held[d];
        // the element above the cut where the factored matrix was assembled (it alone couples
        // the cut to the part above), its terms at the solution
        let (k, r_c) = element_at_cut(plain, &last.state, &sol.state, cut);
        let above = m - 6;
        let a_uc = Matrix6::from_fn(|r, l| if held(above + r) { 0.0 } else { k[(r, 6 + l)] });
        let a_cu = |kk: usize, j: usize| if held(j) { 0.0 } else { k[(6 + kk, j - above)] };
        // A_cU A_UU^-1 v, over the cut's six DOFs: A_cU reaches the node above the cut only, so
        // only its rows of the solution are computed
        let through = |v: &[f64]| -> Option<Vector6<f64>> {
            let mut x: Vec<f64> = v
                .iter()
                .enumerate()
                .map(|(i, &e)| if held(i) { 0.0 } else { e })
                .collect();
            let solved = last.lin.solve_leading_from(&mut x, above) && x[above..].iter().all(|v| v.is_finite());
            solved.then(|| Vector6::from_fn(|kk, _| (above..m).map(|j| a_cu(kk, j) * x[j]).sum()))
        };
        let mut stiffness = Matrix6::from_fn(|r, c| k[(6 + r, 6 + c)]);
        for l in 0..6 {
            let mut col = vec![0.0; m];
            for r in 0..6 {
                col[above + r] = a_uc[(r, l)];
            }
            let t = through(&col)?;
            for kk in 0..6 {
                stiffness[(kk, l)] -= t[kk];
            }
        }
        let mut hook_u = vec![0.0; m];
        for (d, v) in plain.hook_column() {
            if d < m {
                hook_u[d] = v;
            }
        }
        let r_u: Vec<f64> = (0..m)
            .map(|i| if held(i) { 0.0 } else { sol.eval.residual[i] })
            .collect();
        let st = &sol.state;
        let top = CondensedTop {
            force: r_c - through(&r_u)?,
            stiffness,
            hook_column: -through(&hook_u)?,
            x0: st.x[cut],
            triad0: st.triads[cut],
            hook_load0_n: st.hook_load_n,
        };
        Some(Upper {
            last,
            m,
            cut,
            r_u,
            a_uc,
            hook_u,
            top,
        })
    }

    /// Move the part above the cut of `state` (a state of `fine`, the refined model, whose
    /// nodes up to the cut hold the lower part's solution and whose hook load is the lower
    /// part's) by its linear response to the cut's increment and the hook load's change: the
    /// leading rows `r_U + A_UU du_U + A_Uc du_c + h_U dH = 0` solved for `du_U`, and each
    /// contact's force changed by its stiffness `R/s` times its normal motion (the linearized
    /// complementarity of the plain step). Returns false if the leading block does not solve.
    pub(crate) fn follow(&self, plain: &Model, fine: &Model, state: &mut State) -> bool {
        let shift = fine.nodes() - plain.nodes();
        let c = self.cut + shift;
        let du_c = self.top.increment(&fine.basis[c], &state.x[c], &state.triads[c]);
        let dh = state.hook_load_n - self.top.hook_load0_n;
        let coupled = self.a_uc * du_c;
        let above = self.m - 6;
        let mut x: Vec<f64> = (0..self.m)
            .map(|i| {
                let a = if i >= above { coupled[i - above] } else { 0.0 };
                -(self.r_u[i] + a + self.hook_u[i] * dh)
            })
            .collect();
        for &d in &self.last.constrained {
            if d < self.m {
                x[d] = 0.0;
            }
        }
        if !self.last.lin.solve_leading(&mut x) || x.iter().any(|v| !v.is_finite()) {
            return false;
        }
        for (j, &i) in self.last.node.iter().enumerate() {
            if i <= self.cut {
                continue;
            }
            let d = plain.dof(i, 0);
            let du = Vec3::new(x[d], x[d + 1], x[d + 2]);
            let dr = self.last.ratio[j] * self.last.normals[j].dot(&du);
            let f = &mut state.multipliers[i + shift];
            *f = (*f + dr).max(0.0);
        }
        let corrections = self.stretch_corrections(plain, fine, state, &x);
        let mut du = vec![0.0; fine.dofs()];
        du[..self.m].copy_from_slice(&x);
        fine.update(state, &du, 1.0);
        for (i, v) in corrections {
            state.x[i] += v;
        }
        true
    }

    /// Shifts (global, m) of the nodes of `fine` above the cut that take out the second-order
    /// stretch of the linear increments `x` (the leading DOFs) of the part above: added
    /// translations lengthen an element that turns by `theta` by `L theta^2 / 2`, and a stiff
    /// collar's axial force by `EA theta^2 / 2` (0.4 N at the cut of wells/s-shape, beyond
    /// the residual tolerance). Each element's chord is put back to its length to first order
    /// (`|b - a| + t . (db - da)`) by shifting its upper node, and every node above it, along
    /// the chord.
    fn stretch_corrections(&self, plain: &Model, fine: &Model, state: &State, x: &[f64]) -> Vec<(usize, Vec3)> {
        let shift = fine.nodes() - plain.nodes();
        let c = self.cut + shift;
        let moved = |i: usize| -> Vec3 {
            let d = plain.dof(i - shift, 0);
            fine.basis[i] * Vec3::new(x[d], x[d + 1], x[d + 2])
        };
        let (mut a, mut da) = (self.top.x0, state.x[c] - self.top.x0);
        let mut total = Vec3::zeros();
        let mut out = Vec::with_capacity(fine.nodes() - c - 1);
        for i in c + 1..fine.nodes() {
            let (b, db) = (state.x[i], moved(i));
            let chord = b - a;
            let t = chord / chord.norm();
            let stretch = (chord + db - da).norm() - (chord.norm() + t.dot(&(db - da)));
            total -= t * stretch;
            out.push((i, total));
            (a, da) = (b, db);
        }
        out
    }
}

/// The tangent (consistent, both nodes, the upper node's DOFs first) at `state_k` and the
/// residual terms at node `cut` at `state_r` of the element above node `cut` of `model` (DOF
/// bases): the part above's own terms at the cut.
fn element_at_cut(model: &Model, state_k: &State, state_r: &State, cut: usize) -> (Mat12, Vector6<f64>) {
    let mut k = Mat12::zeros();
    model.element_terms(state_k, cut, None, Some(&mut k), true);
    let (_, terms) = model.element_terms(state_r, cut, None, None, true);
    (k, Vector6::from_fn(|r, _| terms[6 + r]))
}
