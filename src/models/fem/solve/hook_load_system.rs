//! The bordered hook-load system. The bit is held on the hole axis at the bit MD; when the WOB
//! is given, the hook load `H` at the top is an extra unknown found with the equation "axial
//! reaction at the bit = -WOB": the tangent bordered by the hook-load column (the top axial
//! DOF, or a condensed top's column) and the bit's axial row, solved with two
//! back-substitutions of the same factor.

use super::matrix_and_factor::MatrixAndFactor;
use crate::models::fem::model::{Evaluation, Model};

/// Newton step of the bordered system with the factored tangent in `lin`: `K du = -r` (`du`
/// the displacement increment, DOF order, node bases) with the hook-load column `hook` (DOF,
/// entry; [`Model::hook_column`]) when `bordered` (the WOB equation `kb . du = -c` fixes the hook-load
/// change `dh`, N; two back-substitutions of the same factor), else `K du = -r` alone with
/// `dh = 0`. Returns `(du, dh)`.
pub(crate) fn bordered_step(
    lin: &MatrixAndFactor,
    r: &[f64],
    kb: &[(usize, f64)],
    c: f64,
    hook: &[(usize, f64)],
    bordered: bool,
) -> (Vec<f64>, f64) {
    let mut a: Vec<f64> = r.iter().map(|v| -v).collect();
    lin.solve(&mut a);
    if !bordered {
        return (a, 0.0);
    }
    let mut b = vec![0.0; r.len()];
    for &(d, v) in hook {
        b[d] = v;
    }
    lin.solve(&mut b);
    let kba: f64 = kb.iter().map(|&(d, v)| v * a[d]).sum();
    let kbb: f64 = kb.iter().map(|&(d, v)| v * b[d]).sum();
    let dh = if kbb.abs() > 1e-30 { (c + kba) / kbb } else { 0.0 };
    (a.iter().zip(&b).map(|(x, y)| x - dh * y).collect(), dh)
}

/// Row of the bit's axial DOF of the assembled tangent over the free columns (DOF, entry):
/// the WOB equation's linearization.
pub(crate) fn bit_row(model: &Model, lin: &MatrixAndFactor, constrained: &[usize]) -> Vec<(usize, f64)> {
    let bit_ax = model.dof(0, 0);
    (0..6)
        .map(|c| model.dof(0, c))
        .chain((0..6).map(|c| model.dof(1, c)))
        .filter(|d| !constrained.contains(d))
        .map(|d| (d, lin.get(bit_ax, d)))
        .collect()
}

/// The WOB equation's residual `c` (N; 0 when the hook load is given) and the residual of
/// `ev` with the entries of the DOFs `constrained` zeroed.
pub(crate) fn free_residual(model: &Model, ev: &Evaluation, constrained: &[usize]) -> (f64, Vec<f64>) {
    let c = if model.loads.hook_load_n.is_none() {
        ev.residual[model.dof(0, 0)] + model.loads.wob_n
    } else {
        0.0
    };
    let mut r = ev.residual.clone();
    for &d in constrained {
        r[d] = 0.0;
    }
    (c, r)
}
