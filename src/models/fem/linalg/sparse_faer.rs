//! General sparse LDLᵀ through faer: the fallback for structures that are not a node chain
//! (branches, distant couplings) and the test oracle for [`crate::models::fem::linalg::band`].
//!
//! The symbolic analysis is done once from the full band pattern of a [`BandMatrix`]
//! (natural ordering, simplicial), then every [`FaerLdlt::factor`] is a numeric refactor into
//! preallocated buffers.
//!
//! faer 0.24.4 pitfall: with `SymmetricOrdering::Identity`, `factorize_symbolic_cholesky`
//! ignores `side` and reads the pattern as upper-triangular. We therefore always pass the
//! UPPER triangle with `Side::Upper` (passing the lower triangle gives a wrong structure and a
//! panic in the numeric phase).
//!
//! The LDLᵀ runs without pivoting and without regularization, so it works for symmetric
//! indefinite matrices as long as no pivot vanishes (same contract as
//! [`BandLdlt`](crate::models::fem::linalg::band::BandLdlt)); zero pivots are detected with the same relative
//! threshold and reported as [`FactorError::ZeroPivot`].

use faer::dyn_stack::{MemBuffer, MemStack, StackReq};
use faer::linalg::cholesky::ldlt::factor::{LdltError, LdltRegularization};
use faer::sparse::linalg::cholesky::{
    factorize_symbolic_cholesky, CholeskySymbolicParams, LdltRef, SymbolicCholesky, SymbolicCholeskyRaw,
    SymmetricOrdering,
};
use faer::sparse::linalg::SupernodalThreshold;
use faer::sparse::{SparseColMatRef, SymbolicSparseColMat};
use faer::{Conj, MatMut, Par, Side};

use crate::models::fem::linalg::band::{is_zero_pivot, BandMatrix, FactorError, PIVOT_TOL};

/// Sparse LDLᵀ (faer, simplicial, natural ordering) with the pattern of a [`BandMatrix`].
pub struct FaerLdlt {
    n: usize,
    hb: usize,
    /// Upper-triangle CSC pattern of the full band.
    pattern: SymbolicSparseColMat<usize>,
    /// For each CSC entry, its index in the band storage of [`BandMatrix::data`].
    slots: Vec<usize>,
    values: Vec<f64>,
    symbolic: SymbolicCholesky<usize>,
    /// Position of `d_j` in `l_values`.
    diag_pos: Vec<usize>,
    l_values: Vec<f64>,
    mem: MemBuffer,
    factored: bool,
    negative: usize,
    min_abs: f64,
}

impl FaerLdlt {
    /// Symbolic analysis (once) for matrices with the size and half-bandwidth of `a`.
    /// Only the shape of `a` is used; the pattern is the full band.
    ///
    /// # Panics
    /// If faer's symbolic analysis fails (out of memory / index overflow).
    pub fn new(a: &BandMatrix) -> Self {
        let n = a.n();
        let hb = a.half_bandwidth();
        let ld = hb + 1;
        let mut col_ptr = Vec::with_capacity(n + 1);
        let mut row_idx = Vec::new();
        let mut slots = Vec::new();
        col_ptr.push(0usize);
        for j in 0..n {
            for i in j.saturating_sub(hb)..=j {
                row_idx.push(i);
                // Upper entry (i, j), i <= j, is the lower band entry (j, i).
                slots.push(i * ld + (j - i));
            }
            col_ptr.push(row_idx.len());
        }
        let pattern = SymbolicSparseColMat::new_checked(n, n, col_ptr, None, row_idx);
        let params = CholeskySymbolicParams {
            supernodal_flop_ratio_threshold: SupernodalThreshold::FORCE_SIMPLICIAL,
            ..Default::default()
        };
        let symbolic = factorize_symbolic_cholesky(pattern.as_ref(), Side::Upper, SymmetricOrdering::Identity, params)
            .expect("faer symbolic Cholesky analysis failed");
        let diag_pos = match symbolic.raw() {
            SymbolicCholeskyRaw::Simplicial(s) => s.col_ptr()[..n].to_vec(),
            SymbolicCholeskyRaw::Supernodal(_) => unreachable!("simplicial was forced"),
        };
        let req = StackReq::or(
            symbolic.factorize_numeric_ldlt_scratch::<f64>(Par::Seq, Default::default()),
            symbolic.solve_in_place_scratch::<f64>(1, Par::Seq),
        );
        let l_values = vec![0.0; symbolic.len_val()];
        Self {
            n,
            hb,
            values: vec![0.0; slots.len()],
            pattern,
            slots,
            symbolic,
            diag_pos,
            l_values,
            mem: MemBuffer::new(req),
            factored: false,
            negative: 0,
            min_abs: f64::INFINITY,
        }
    }

    /// Matrix dimension.
    pub fn n(&self) -> usize {
        self.n
    }

    /// Numeric LDLᵀ factorization of `a` (same shape as at construction).
    ///
    /// # Errors
    /// [`FactorError::ZeroPivot`] at the first pivot with `|d| <= 1e-14 * max|a_jj|` (or an
    /// exactly zero / non-finite pivot reported by faer).
    ///
    /// # Panics
    /// If `a` has a different size or half-bandwidth than at construction.
    pub fn factor(&mut self, a: &BandMatrix) -> Result<(), FactorError> {
        assert!(
            a.n() == self.n && a.half_bandwidth() == self.hb,
            "FaerLdlt: shape mismatch"
        );
        self.factored = false;
        let src = a.data();
        for (v, &s) in self.values.iter_mut().zip(&self.slots) {
            *v = src[s];
        }
        let mat = SparseColMatRef::new(self.pattern.as_ref(), &self.values);
        let res = self.symbolic.factorize_numeric_ldlt(
            &mut self.l_values,
            mat,
            Side::Upper,
            LdltRegularization::default(),
            Par::Seq,
            MemStack::new(&mut self.mem),
            Default::default(),
        );
        if let Err(LdltError::ZeroPivot { index }) = res {
            // faer's simplicial kernel reports the pivot 1-based (LAPACK-style `info`) and
            // does not store it; it only fails for an exactly zero or non-finite pivot.
            return Err(FactorError::ZeroPivot {
                column: index.saturating_sub(1),
                pivot: 0.0,
                diagonal: a.diag_abs_max(),
            });
        }
        let tol = PIVOT_TOL * a.diag_abs_max();
        let mut negative = 0;
        let mut min_abs = f64::INFINITY;
        for (j, &p) in self.diag_pos.iter().enumerate() {
            let d = self.l_values[p];
            if is_zero_pivot(d, tol) {
                return Err(FactorError::ZeroPivot {
                    column: j,
                    pivot: d,
                    diagonal: a.diag_abs_max(),
                });
            }
            negative += (d < 0.0) as usize;
            min_abs = min_abs.min(d.abs());
        }
        self.negative = negative;
        self.min_abs = min_abs;
        self.factored = true;
        Ok(())
    }

    /// Solves `A x = b` in place with the last successful factorization (`&mut self` for the
    /// preallocated workspace).
    ///
    /// # Panics
    /// If `b.len() != n` or there is no valid factorization.
    pub fn solve_in_place(&mut self, b: &mut [f64]) {
        assert!(b.len() == self.n, "FaerLdlt::solve_in_place: length mismatch");
        assert!(self.factored, "FaerLdlt::solve_in_place: no valid factorization");
        let n = self.n;
        let rhs = MatMut::from_column_major_slice_mut(b, n, 1);
        LdltRef::new(&self.symbolic, &self.l_values).solve_in_place_with_conj(
            Conj::No,
            rhs,
            Par::Seq,
            MemStack::new(&mut self.mem),
        );
    }

    /// Number of negative pivots (= negative eigenvalues) of the last successful factorization.
    pub fn negative_pivots(&self) -> usize {
        self.negative
    }

    /// `min_j |d_j|` of the last successful factorization.
    pub fn min_abs_pivot(&self) -> f64 {
        self.min_abs
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::models::fem::linalg::band::{chain_test_matrix, BandLdlt};

    fn rel_diff(x: &[f64], y: &[f64]) -> f64 {
        let num = x.iter().zip(y).map(|(p, q)| (p - q).abs()).fold(0.0, f64::max);
        let den = y.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        num / den
    }

    #[test]
    fn faer_matches_band_on_chain() {
        let a = chain_test_matrix(60);
        let n = a.n();
        let b: Vec<f64> = (0..n)
            .map(|i| if i < 6 { 0.0 } else { (i as f64).sin() * 1e3 })
            .collect();
        let mut f = FaerLdlt::new(&a);
        f.factor(&a).unwrap();
        let mut x = b.clone();
        f.solve_in_place(&mut x);
        let mut g = BandLdlt::new(n, 11);
        g.factor(&a).unwrap();
        let mut y = b.clone();
        g.solve_in_place(&mut y);
        // cond(K) ~ 1e10 (1e3 N/m springs next to EA/L ~ 2e9 N/m): agreement ~ cond * eps.
        assert!(rel_diff(&x, &y) < 1e-9, "{}", rel_diff(&x, &y));
        assert_eq!(f.negative_pivots(), 0);
        assert!((f.min_abs_pivot() - g.min_abs_pivot()).abs() <= 1e-10 * g.min_abs_pivot());
        // refactor with changed values reuses the symbolic analysis
        let mut a2 = a.clone();
        a2.add(n - 3, n - 3, 1e6);
        f.factor(&a2).unwrap();
        g.factor(&a2).unwrap();
        let (mut x2, mut y2) = (b.clone(), b.clone());
        f.solve_in_place(&mut x2);
        g.solve_in_place(&mut y2);
        assert!(rel_diff(&x2, &y2) < 1e-9);
    }

    #[test]
    fn faer_indefinite_and_singular() {
        let n = 40;
        let mut a = BandMatrix::zeros(n, 3);
        for j in 0..n {
            a.set(j, j, if j % 3 == 0 { -4.0 } else { 5.0 + j as f64 * 0.1 });
            for i in j + 1..(j + 4).min(n) {
                a.set(i, j, ((i * 31 + j * 17) % 13) as f64 / 13.0 - 0.5);
            }
        }
        let mut f = FaerLdlt::new(&a);
        f.factor(&a).unwrap();
        let mut g = BandLdlt::new(n, 3);
        g.factor(&a).unwrap();
        assert!(g.negative_pivots() > 0);
        assert_eq!(f.negative_pivots(), g.negative_pivots());
        let b: Vec<f64> = (0..n).map(|i| i as f64).collect();
        let (mut x, mut y) = (b.clone(), b.clone());
        f.solve_in_place(&mut x);
        g.solve_in_place(&mut y);
        assert!(rel_diff(&x, &y) < 1e-12);

        let mut s = BandMatrix::zeros(6, 1);
        for i in 0..6 {
            s.set(i, i, 2.0);
        }
        s.set(2, 2, 1.0);
        s.set(3, 3, 1.0);
        s.set(3, 2, 1.0);
        let mut f = FaerLdlt::new(&s);
        let r = f.factor(&s);
        assert!(matches!(r, Err(FactorError::ZeroPivot { column: 3, .. })), "{r:?}");
    }
}
