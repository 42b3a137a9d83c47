//! The global tangent band matrix together with its factorization: symmetric band with
//! LDL^T, or general band with LU when friction makes the consistent tangent unsymmetric; and
//! the interior point's factorizations of the tangent with its contact terms added.

use super::errors::{singular, SolveError};
use crate::models::fem::linalg::band::{BandLdlt, BandMatrix, FactorError};
use crate::models::fem::linalg::band_lu::{BandLu, GeneralBand};
use crate::models::fem::model::{Model, StiffnessSink, HALF_BANDWIDTH};

/// The global tangent band matrix (half-bandwidth [`HALF_BANDWIDTH`], DOF order) and its
/// factorization.
pub(crate) enum MatrixAndFactor {
    /// Symmetric band (lower triangle) and its LDL^T.
    Symmetric(BandMatrix, BandLdlt),
    /// General band and its LU.
    General(GeneralBand, BandLu),
}

impl MatrixAndFactor {
    /// For `model`'s DOFs: LU when friction makes the consistent tangent unsymmetric, LDL^T
    /// otherwise.
    pub(crate) fn for_model(model: &Model) -> MatrixAndFactor {
        if model.needs_unsymmetric() {
            MatrixAndFactor::general(model.dofs())
        } else {
            let n = model.dofs();
            MatrixAndFactor::Symmetric(BandMatrix::zeros(n, HALF_BANDWIDTH), BandLdlt::new(n, HALF_BANDWIDTH))
        }
    }
    /// General band and LU for `n` DOFs.
    pub(crate) fn general(n: usize) -> MatrixAndFactor {
        MatrixAndFactor::General(GeneralBand::zeros(n, HALF_BANDWIDTH), BandLu::new(n, HALF_BANDWIDTH))
    }
    /// The matrix, to assemble into.
    pub(crate) fn sink(&mut self) -> &mut dyn StiffnessSink {
        match self {
            MatrixAndFactor::Symmetric(k, _) => k,
            MatrixAndFactor::General(k, _) => k,
        }
    }
    /// Entry `(i, j)` of the matrix.
    pub(crate) fn get(&self, i: usize, j: usize) -> f64 {
        match self {
            MatrixAndFactor::Symmetric(k, _) => k.get(i, j),
            MatrixAndFactor::General(k, _) => k.get(i, j),
        }
    }
    /// Hold DOF `d`: its row and column zeroed, its diagonal kept.
    fn constrain(&mut self, d: usize) {
        match self {
            MatrixAndFactor::Symmetric(k, _) => k.constrain_dof(d),
            MatrixAndFactor::General(k, _) => k.constrain_dof(d),
        }
    }
    /// Factor the matrix.
    fn factor(&mut self) -> Result<(), FactorError> {
        match self {
            MatrixAndFactor::Symmetric(k, f) => f.factor(k),
            MatrixAndFactor::General(k, f) => f.factor(k),
        }
    }
    /// Solve with the factor in place: `x <- A^-1 x`.
    pub(crate) fn solve(&self, x: &mut [f64]) {
        match self {
            MatrixAndFactor::Symmetric(_, f) => f.solve_in_place(x),
            MatrixAndFactor::General(_, f) => f.solve_in_place(x),
        }
    }
    /// Solve in place with the leading `x.len()` rows and columns of the factored matrix (the
    /// DOFs nearest the surface): true for the LU ([`BandLu::solve_leading_in_place`]); false,
    /// `x` unchanged, for the LDL^T.
    pub(crate) fn solve_leading(&self, x: &mut [f64]) -> bool {
        self.solve_leading_from(x, 0)
    }
    /// [`MatrixAndFactor::solve_leading`] for the rows `from..` only
    /// ([`BandLu::solve_leading_from`]).
    pub(crate) fn solve_leading_from(&self, x: &mut [f64], from: usize) -> bool {
        match self {
            MatrixAndFactor::Symmetric(..) => false,
            MatrixAndFactor::General(_, f) => {
                f.solve_leading_from(x, from);
                true
            }
        }
    }
    /// What the interior point keeps of the assembled matrix (before constraints) while it
    /// factors modified copies: LU factors straight from this object's matrix in one
    /// streaming pass and needs no copy (`None`); LDL^T factors in place and needs one.
    pub(crate) fn keep_base(&self) -> Option<MatrixAndFactor> {
        match self {
            MatrixAndFactor::Symmetric(k, _) => Some(MatrixAndFactor::Symmetric(k.clone(), BandLdlt::new(1, 1))),
            MatrixAndFactor::General(..) => None,
        }
    }
    /// Replace the matrix with a stored copy.
    fn set_matrix(&mut self, from: &MatrixAndFactor) {
        match (self, from) {
            (MatrixAndFactor::Symmetric(k, _), MatrixAndFactor::Symmetric(f, _)) => k.copy_from(f),
            (MatrixAndFactor::General(k, _), MatrixAndFactor::General(f, _)) => k.copy_from(f),
            _ => unreachable!("matrix kinds match"),
        }
    }
    /// Factor the assembled matrix (the stored copy `base` from [`MatrixAndFactor::keep_base`], or this
    /// object's own when that is `None`) plus the same additions given two ways:
    /// `add_row(i, row)` adds to row `i` of the general band storage (column `c` at offset
    /// `c + hb - i`, `hb` the half-bandwidth), `add` assembles them as blocks; the DOFs
    /// `constrained` are held (row and column zeroed, diagonal `constraint_scale`). LU: one
    /// streaming pass, each row copied, changed and eliminated while in cache (the matrix is
    /// not changed); LDL^T: copy, assemble, factor (the matrix is left unspecified).
    pub(crate) fn factor_modified(
        &mut self,
        base: Option<&MatrixAndFactor>,
        constrained: &[usize],
        constraint_scale: f64,
        mut add_row: impl FnMut(usize, &mut [f64]),
        mut add: impl FnMut(&mut dyn StiffnessSink),
    ) -> Result<(), FactorError> {
        if let MatrixAndFactor::General(k, f) = &mut *self {
            let hb = HALF_BANDWIDTH;
            let k: &GeneralBand = match base {
                Some(MatrixAndFactor::General(b, _)) => b,
                _ => k,
            };
            // rows within the half-bandwidth of a constrained DOF (their column is zeroed), as
            // merged ranges (the constrained DOFs sit at the two ends of the chain: testing
            // one span from the first to the last would visit every row)
            let mut sorted = constrained.to_vec();
            sorted.sort_unstable();
            let mut near_rows: Vec<(usize, usize)> = Vec::new();
            for c in sorted {
                let (a, b) = (c.saturating_sub(hb), c + hb);
                match near_rows.last_mut() {
                    Some(last) if a <= last.1 + 1 => last.1 = last.1.max(b),
                    _ => near_rows.push((a, b)),
                }
            }
            return f.factor_rows(k, |i, row| {
                let near = near_rows.iter().any(|&(a, b)| a <= i && i <= b);
                if near && constrained.contains(&i) {
                    row.fill(0.0);
                    row[hb] = constraint_scale;
                    return;
                }
                add_row(i, row);
                if near {
                    for &c in constrained {
                        if c.abs_diff(i) <= hb {
                            row[c + hb - i] = 0.0;
                        }
                    }
                }
            });
        }
        self.set_matrix(base.expect("LDL^T keeps a copy of the matrix"));
        add(self.sink());
        for &d in constrained {
            self.constrain(d);
        }
        self.factor()
    }
    /// `y += A x` with the assembled matrix (`base`, or this object's own when `None`).
    pub(crate) fn matrix_mul_add(&self, base: Option<&MatrixAndFactor>, x: &[f64], y: &mut [f64], work: &mut Vec<f64>) {
        work.resize(x.len(), 0.0);
        match base.unwrap_or(self) {
            MatrixAndFactor::Symmetric(k, _) => k.mul_vec(x, work),
            MatrixAndFactor::General(k, _) => k.mul_vec(x, work),
        }
        for (yi, ti) in y.iter_mut().zip(work.iter()) {
            *yi += ti;
        }
    }
    /// Solve for two right-hand sides at once (LU: one pass over the factor).
    pub(crate) fn solve2(&self, x: &mut [f64], y: &mut [f64]) {
        match self {
            MatrixAndFactor::Symmetric(_, f) => {
                f.solve_in_place(x);
                f.solve_in_place(y);
            }
            MatrixAndFactor::General(_, f) => f.solve2_in_place(x, y),
        }
    }
    /// Hold the DOFs `constrained` and factor; a zero pivot becomes a
    /// [`SolveError::Singular`] naming the node of `model`.
    pub(crate) fn constrain_and_factor(&mut self, model: &Model, constrained: &[usize]) -> Result<(), SolveError> {
        for &d in constrained {
            self.constrain(d);
        }
        self.factor().map_err(|e| singular(model, e))
    }
}
