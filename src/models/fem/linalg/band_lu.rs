//! General (unsymmetric) band matrix and its LU factorization without pivoting.
//!
//! Friction makes the consistent tangent unsymmetric (the friction force is proportional to
//! the normal force and follows the contact normal), so the contact solver factors it with
//! this LU when friction acts on a moving string; the symmetric [`super::band::BandLdlt`] is
//! used otherwise. Storage: row-major band, row `i` holds columns `i - b ..= i + b` at offsets
//! `0 ..= 2b`. No pivoting: the stiffness is dominated by its symmetric part (elastic, penalty
//! springs), and a zero or non-finite pivot is reported, never divided by.

use super::band::FactorError;

/// Square band matrix with half-bandwidth `b` (entries with `|i - j| <= b`).
#[derive(Debug, Clone)]
pub struct GeneralBand {
    n: usize,
    b: usize,
    w: usize,
    data: Vec<f64>,
    constraint_scale: Option<f64>,
}

impl GeneralBand {
    /// Zero matrix of order `n`, half-bandwidth `b`.
    pub fn zeros(n: usize, b: usize) -> Self {
        let w = 2 * b + 1;
        GeneralBand {
            n,
            b,
            w,
            data: super::buffers::zeroed(n * w),
            constraint_scale: None,
        }
    }
    /// Matrix of order `n`, half-bandwidth `b`, with unspecified entries: storage
    /// that is completely written before it is read (the LU factor).
    fn for_overwrite(n: usize, b: usize) -> Self {
        let w = 2 * b + 1;
        GeneralBand {
            n,
            b,
            w,
            data: super::buffers::for_overwrite(n * w),
            constraint_scale: None,
        }
    }
    /// Order.
    pub fn n(&self) -> usize {
        self.n
    }
    #[inline]
    fn idx(&self, i: usize, j: usize) -> usize {
        debug_assert!(i.abs_diff(j) <= self.b);
        i * self.w + (j + self.b - i)
    }
    /// Entry (i, j), 0 outside the band.
    pub fn get(&self, i: usize, j: usize) -> f64 {
        if i.abs_diff(j) > self.b {
            0.0
        } else {
            self.data[self.idx(i, j)]
        }
    }
    /// Add `v` to entry (i, j) (must be inside the band).
    pub fn add(&mut self, i: usize, j: usize, v: f64) {
        assert!(
            i.abs_diff(j) <= self.b && i < self.n && j < self.n,
            "GeneralBand::add outside the band"
        );
        let k = self.idx(i, j);
        self.data[k] += v;
    }
    /// Set all entries to zero (keeps the constraint scale).
    pub fn fill_zero(&mut self) {
        self.data.fill(0.0);
    }
    /// Scatter a dense block (row-major, leading dimension `ld`): `A[dofs[r], dofs[c]] += k[r*ld + c]`.
    ///
    /// # Panics
    /// If the DOFs span more than the band or reach past the matrix (checked once per block),
    /// or `k` is too short.
    pub fn add_block(&mut self, dofs: &[usize], k: &[f64], ld: usize) {
        let m = dofs.len();
        if m == 0 {
            return;
        }
        assert!(
            m <= ld && k.len() >= (m - 1) * ld + m,
            "GeneralBand::add_block: k too short"
        );
        let (lo, hi) = dofs.iter().fold((usize::MAX, 0), |(lo, hi), &d| (lo.min(d), hi.max(d)));
        assert!(
            hi < self.n && hi - lo <= self.b,
            "GeneralBand::add_block: dofs span {lo}..={hi} outside n = {} or half-bandwidth = {}",
            self.n,
            self.b
        );
        let consecutive = dofs.windows(2).all(|p| p[1] == p[0] + 1);
        for (r, &gr) in dofs.iter().enumerate() {
            // row gr, column gc at gr * w + gc + b - gr
            let base = gr * self.w + self.b - gr;
            let krow = &k[r * ld..r * ld + m];
            if consecutive {
                let dst = &mut self.data[base + lo..base + lo + m];
                for (x, &v) in dst.iter_mut().zip(krow) {
                    *x += v;
                }
            } else {
                for (&gc, &v) in dofs.iter().zip(krow) {
                    self.data[base + gc] += v;
                }
            }
        }
    }

    /// `A[first + r, first + c] += k[c * 12 + r]` (a column-major 12x12 on 12 consecutive
    /// DOFs: a beam element of the node chain). Reads the block as it is stored instead of
    /// through a transposed copy (the copy cost more than the additions).
    ///
    /// # Panics
    /// If the block reaches past the matrix or the half-bandwidth is below 11.
    pub fn add_block_12(&mut self, first: usize, k: &[f64]) {
        assert!(
            first + 12 <= self.n && self.b >= 11 && k.len() >= 144,
            "GeneralBand::add_block_12: block at {first} outside n = {} or half-bandwidth {} < 11",
            self.n,
            self.b
        );
        for r in 0..12 {
            let gr = first + r;
            let start = gr * self.w + self.b - gr + first;
            let dst = &mut self.data[start..start + 12];
            for (c, x) in dst.iter_mut().enumerate() {
                *x += k[c * 12 + r];
            }
        }
    }

    /// Zero rows `rows` (all their stored entries).
    pub fn clear_rows(&mut self, rows: std::ops::Range<usize>) {
        self.data[rows.start * self.w..rows.end * self.w].fill(0.0);
    }

    /// Copy values and constraint scale from `other` (same shape) without reallocating.
    ///
    /// # Panics
    /// If the shapes differ.
    pub fn copy_from(&mut self, other: &GeneralBand) {
        assert!(
            self.n == other.n && self.b == other.b,
            "GeneralBand::copy_from: shape mismatch"
        );
        self.data.copy_from_slice(&other.data);
        self.constraint_scale = other.constraint_scale;
    }
    /// Homogeneous Dirichlet condition on DOF `i`: zero row and column, diagonal = a fixed
    /// scale (mean |diagonal| at the first call), as [`super::band::BandMatrix::constrain_dof`].
    pub fn constrain_dof(&mut self, i: usize) {
        let s = match self.constraint_scale {
            Some(s) => s,
            None => {
                let (sum, cnt) = (0..self.n)
                    .map(|j| self.get(j, j).abs())
                    .filter(|v| *v > 0.0)
                    .fold((0.0, 0usize), |(s, c), v| (s + v, c + 1));
                let s = if cnt > 0 && sum.is_finite() {
                    sum / cnt as f64
                } else {
                    1.0
                };
                self.constraint_scale = Some(s);
                s
            }
        };
        let lo = i.saturating_sub(self.b);
        let hi = (i + self.b).min(self.n - 1);
        for j in lo..=hi {
            let a = self.idx(i, j);
            self.data[a] = 0.0;
            let a = self.idx(j, i);
            self.data[a] = 0.0;
        }
        let d = self.idx(i, i);
        self.data[d] = s;
    }
    /// `y = A x`.
    pub fn mul_vec(&self, x: &[f64], y: &mut [f64]) {
        let (n, b, w) = (self.n, self.b, self.w);
        for (i, yi) in y.iter_mut().enumerate().take(n) {
            if b == CHAIN_HALF_BANDWIDTH && i >= b && i + b < n {
                // interior row of the node chain: fixed-length dot with independent partial sums
                const W: usize = 2 * CHAIN_HALF_BANDWIDTH + 1;
                let row: &[f64; W] = self.data[i * w..(i + 1) * w].try_into().expect("row length");
                let v: &[f64; W] = x[i - b..=i + b].try_into().expect("window length");
                *yi = tree_dot::<W>(row, v, 0, W);
                continue;
            }
            let lo = i.saturating_sub(b);
            let hi = (i + b).min(n - 1);
            let row = &self.data[self.idx(i, lo)..=self.idx(i, hi)];
            *yi = row.iter().zip(&x[lo..=hi]).map(|(a, v)| a * v).sum();
        }
    }
}

impl Drop for GeneralBand {
    fn drop(&mut self) {
        super::buffers::give_back(std::mem::take(&mut self.data));
    }
}

/// Half-bandwidth of the 6-DOF node chain, for which [`BandLu::factor`] has an unrolled kernel.
const CHAIN_HALF_BANDWIDTH: usize = 11;

/// Eliminate column `k` below the pivot in rows `k+1 ..= k+B` (all inside the matrix), width
/// `2B + 1` row-major storage: `row_i -= (a_ik / pivot) row_k` on columns `k+1 ..= k+B`.
#[inline(always)]
fn eliminate_fixed<const B: usize>(data: &mut [f64], k: usize, pivot: f64) {
    let w = 2 * B + 1;
    let (head, tail) = data.split_at_mut((k + 1) * w);
    let mut row_k = [0.0; B];
    row_k.copy_from_slice(&head[k * w + B + 1..k * w + 2 * B + 1]);
    for d in 1..=B {
        // row i = k + d: column k sits at offset B - d
        let row_i = &mut tail[(d - 1) * w..d * w];
        let off = B - d;
        let lik = row_i[off] / pivot;
        row_i[off] = lik;
        let dst = &mut row_i[off + 1..off + 1 + B];
        for (x, &u) in dst.iter_mut().zip(row_k.iter()) {
            *x -= lik * u;
        }
    }
}

/// [`eliminate_fixed`] for a pivot row of the 6-DOF node chain whose last `L` rows below and
/// columns right of the pivot hold the chain's structural nonzeros (`L = 11 - k` for local
/// DOF `k` of the pivot's node): the rows and columns past them are exact zeros in the
/// matrix and stay zero in the factor (fill-in stays inside each row's profile), so skipping
/// them gives the same factor bit for bit with `(11 - k)^2` instead of 121 updates (38% of
/// the work on average).
#[inline(always)]
fn eliminate_chain<const L: usize>(data: &mut [f64], k: usize, pivot: f64) {
    const B: usize = CHAIN_HALF_BANDWIDTH;
    const W: usize = 2 * B + 1;
    let (head, tail) = data.split_at_mut((k + 1) * W);
    let row_k: [f64; L] = head[k * W + B + 1..k * W + B + 1 + L].try_into().expect("row length L");
    // rows k + 1 ..= k + L as fixed-width arrays (constant offsets once unrolled)
    let rows = &mut tail.as_chunks_mut::<W>().0[..L];
    for (d, row_i) in rows.iter_mut().enumerate() {
        // row i = k + 1 + d: column k sits at offset B - 1 - d
        let off = B - 1 - d;
        let lik = row_i[off] / pivot;
        row_i[off] = lik;
        for (j, &u) in row_k.iter().enumerate() {
            row_i[off + 1 + j] -= lik * u;
        }
    }
}

/// DOFs per node of the node chain (the block size behind [`CHAIN_HALF_BANDWIDTH`]).
const CHAIN_NODE_DOFS: usize = 6;

/// Whether row `i` of a half-bandwidth-11 band (storage `row`) is inside the node-chain
/// profile: zero left of the previous node's first column and right of the next node's
/// last column (the `5 - k` leftmost and `k` rightmost stored entries, `k = i mod 6`).
#[inline(always)]
fn in_chain_profile(i: usize, row: &[f64]) -> bool {
    let k = i % CHAIN_NODE_DOFS;
    let w = row.len();
    row[..CHAIN_NODE_DOFS - 1 - k].iter().all(|&v| v == 0.0) && row[w - k..].iter().all(|&v| v == 0.0)
}

/// The elimination of [`BandLu::eliminate`] on the band storage `data` of order `n`,
/// half-bandwidth `b`, row width `w` (`[n, b, w]`), `diag` receiving each row's diagonal as
/// loaded. Compiled also for AVX2 and selected at run time where the processor has it (the
/// same operations in the same order: the same factor bit for bit).
#[multiversion::multiversion(targets("x86_64+avx2+fma"))]
fn eliminate_band(
    data: &mut [f64],
    diag: &mut [f64],
    [n, b, w]: [usize; 3],
    mut load: impl FnMut(usize, &mut [f64]),
) -> Result<(), FactorError> {
    // the node-chain kernel skips the chain's structural zeros while every row loaded so
    // far lies inside the chain profile (checked as each row is loaded; a row outside it
    // switches to the full kernel from there on, before any pivot that the row affects)
    let mut chain = b == CHAIN_HALF_BANDWIDTH;
    for i in 0..b.min(n) {
        load(i, &mut data[i * w..(i + 1) * w]);
        diag[i] = data[i * w + b];
        chain = chain && in_chain_profile(i, &data[i * w..(i + 1) * w]);
    }
    // columns whose whole band lies inside the matrix: a kernel with the node-chain
    // half-bandwidth fixed at compile time (fully unrolled), the rest generic
    let fixed_end = if b == CHAIN_HALF_BANDWIDTH {
        n.saturating_sub(b)
    } else {
        0
    };
    for k in 0..n {
        if k + b < n {
            let i = k + b;
            load(i, &mut data[i * w..(i + 1) * w]);
            diag[i] = data[i * w + b];
            chain = chain && in_chain_profile(i, &data[i * w..(i + 1) * w]);
        }
        let pivot = data[k * w + b];
        if !pivot.is_finite() || pivot.abs() <= 1e-14 * diag[k].abs().max(f64::MIN_POSITIVE) {
            return Err(FactorError::ZeroPivot {
                column: k,
                pivot,
                diagonal: diag[k].abs(),
            });
        }
        if k < fixed_end {
            const B: usize = CHAIN_HALF_BANDWIDTH;
            if chain {
                match k % CHAIN_NODE_DOFS {
                    0 => eliminate_chain::<11>(data, k, pivot),
                    1 => eliminate_chain::<10>(data, k, pivot),
                    2 => eliminate_chain::<9>(data, k, pivot),
                    3 => eliminate_chain::<8>(data, k, pivot),
                    4 => eliminate_chain::<7>(data, k, pivot),
                    _ => eliminate_chain::<6>(data, k, pivot),
                }
            } else {
                eliminate_fixed::<B>(data, k, pivot);
            }
            continue;
        }
        let hi = (k + b).min(n - 1);
        let len = hi - k; // columns k+1 ..= hi
        let (head, tail) = data.split_at_mut((k + 1) * w);
        let row_k = &head[k * w + b + 1..k * w + b + 1 + len];
        for i in k + 1..=hi {
            let row_i = &mut tail[(i - k - 1) * w..(i - k) * w];
            let off = k + b - i; // column k in row i
            let lik = row_i[off] / pivot;
            row_i[off] = lik;
            if lik != 0.0 {
                for (x, &u) in row_i[off + 1..off + 1 + len].iter_mut().zip(row_k) {
                    *x -= lik * u;
                }
            }
        }
    }
    Ok(())
}

/// LU factor (Doolittle, no pivoting) of a [`GeneralBand`], stored in place of a copy.
#[derive(Debug, Clone)]
pub struct BandLu {
    f: GeneralBand,
    ok: bool,
    /// Diagonal of the matrix being factored (reference for the zero-pivot test).
    diag: Vec<f64>,
    /// `1 / U_kk` (the substitutions multiply instead of dividing on their dependency chain).
    inv_pivot: Vec<f64>,
}

impl BandLu {
    /// Allocate for order `n`, half-bandwidth `b`.
    pub fn new(n: usize, b: usize) -> Self {
        BandLu {
            // every row is written (copied from the matrix) before the elimination reads it
            f: GeneralBand::for_overwrite(n, b),
            ok: false,
            diag: vec![0.0; n],
            inv_pivot: vec![0.0; n],
        }
    }

    /// Factor `a` = L U (unit lower L).
    pub fn factor(&mut self, a: &GeneralBand) -> Result<(), FactorError> {
        self.factor_with(a, |_| {})
    }

    /// Factor `a` changed by `modify` (e.g. extra blocks and boundary conditions) without
    /// changing `a`: the copy into the factor's storage is the only copy made.
    pub fn factor_with(&mut self, a: &GeneralBand, modify: impl FnOnce(&mut GeneralBand)) -> Result<(), FactorError> {
        self.f.copy_from(a);
        modify(&mut self.f);
        self.eliminate(|_, _| {})
    }

    /// Factor `a` with each row finished by `finish_row(i, row)` just before the elimination
    /// first touches it, in one streaming pass (the row is copied, changed and eliminated
    /// while in cache). `row` is row `i` of the band storage: column `c` at offset
    /// `c + b - i`, `b` the half-bandwidth. `a` is not changed.
    pub fn factor_rows(
        &mut self,
        a: &GeneralBand,
        mut finish_row: impl FnMut(usize, &mut [f64]),
    ) -> Result<(), FactorError> {
        assert!(
            a.n == self.f.n && a.b == self.f.b,
            "BandLu::factor_rows: shape mismatch"
        );
        let w = self.f.w;
        if self.f.b == CHAIN_HALF_BANDWIDTH {
            // fixed-length row copy in pieces of at most 64 bytes: inlined moves instead of a
            // memcpy call per row (a 184-byte copy is left to the library)
            const W: usize = 2 * CHAIN_HALF_BANDWIDTH + 1;
            return self.eliminate(|i, row| {
                let dst: &mut [f64; W] = row.try_into().expect("row length");
                let src: &[f64; W] = a.data[i * W..(i + 1) * W].try_into().expect("row length");
                for (d, s) in dst.chunks_mut(8).zip(src.chunks(8)) {
                    d.copy_from_slice(s);
                }
                finish_row(i, row);
            });
        }
        self.eliminate(|i, row| {
            row.copy_from_slice(&a.data[i * w..(i + 1) * w]);
            finish_row(i, row);
        })
    }

    /// The elimination; `load(i, row)` is called for every row before the first column
    /// that updates it (rows `0..b` first, then row `k + b` before column `k`).
    fn eliminate(&mut self, load: impl FnMut(usize, &mut [f64])) -> Result<(), FactorError> {
        self.ok = false;
        let (n, b, w) = (self.f.n, self.f.b, self.f.w);
        self.diag.resize(n, 0.0);
        eliminate_band(&mut self.f.data, &mut self.diag, [n, b, w], load)?;
        let data = &self.f.data;
        self.inv_pivot.resize(n, 0.0);
        for (k, inv) in self.inv_pivot.iter_mut().enumerate() {
            *inv = 1.0 / data[k * w + b];
        }
        self.ok = true;
        Ok(())
    }

    /// Solve `A x = rhs` in place.
    pub fn solve_in_place(&self, x: &mut [f64]) {
        assert!(self.ok, "BandLu::solve_in_place without a valid factor");
        let n = self.f.n;
        assert!(
            x.len() == n,
            "BandLu::solve_in_place: rhs length {} != n = {n}",
            x.len()
        );
        if self.f.b == CHAIN_HALF_BANDWIDTH {
            self.substitute_fixed::<CHAIN_HALF_BANDWIDTH, 1>([x]);
        } else {
            self.substitute_generic([x]);
        }
    }

    /// Solve `A x = x0` and `A y = y0` in place with one pass over the factor for both (the
    /// solves are memory bound).
    pub fn solve2_in_place(&self, x: &mut [f64], y: &mut [f64]) {
        assert!(self.ok, "BandLu::solve2_in_place without a valid factor");
        let n = self.f.n;
        assert!(
            x.len() == n && y.len() == n,
            "BandLu::solve2_in_place: rhs length != n = {n}"
        );
        if self.f.b == CHAIN_HALF_BANDWIDTH {
            self.substitute_fixed::<CHAIN_HALF_BANDWIDTH, 2>([x, y]);
        } else {
            self.substitute_generic([x, y]);
        }
    }

    /// Forward and backward substitution of `R` right-hand sides, any half-bandwidth.
    /// Solve in place with the leading `m x m` block of the factored matrix, `m = x.len()`
    /// (at most the order): without pivoting the LU of a leading principal block is the leading
    /// part of the LU, so the factor of the whole matrix serves every leading block.
    ///
    /// # Panics
    /// Without a valid factor, or if `x` is longer than the order.
    pub fn solve_leading_in_place(&self, x: &mut [f64]) {
        self.solve_leading_from(x, 0);
    }

    /// [`BandLu::solve_leading_in_place`] for the rows `from..` of the solution only (those
    /// above `from` are left unspecified): the backward substitution stops there, and the
    /// forward one starts at the first nonzero entry of `x`. A right-hand side that lives in
    /// the last rows and is wanted there costs a few rows, not the whole block.
    ///
    /// # Panics
    /// Without a valid factor, or if `x` is longer than the order.
    pub fn solve_leading_from(&self, x: &mut [f64], from: usize) {
        assert!(self.ok, "BandLu::solve_leading_from without a valid factor");
        let m = x.len();
        assert!(m <= self.f.n, "BandLu::solve_leading_from: {m} rows of {}", self.f.n);
        let (b, w) = (self.f.b, self.f.w);
        let data = &self.f.data;
        let first = x.iter().position(|&v| v != 0.0).unwrap_or(m);
        for i in first..m {
            let lo = i.saturating_sub(b).max(first);
            let row = &data[i * w + (lo + b - i)..i * w + b];
            let acc: f64 = row.iter().zip(&x[lo..i]).map(|(l, v)| l * v).sum();
            x[i] -= acc;
        }
        for i in (from.min(m)..m).rev() {
            let hi = (i + b).min(m - 1);
            let row = &data[i * w + b + 1..i * w + b + 1 + (hi - i)];
            let acc: f64 = row.iter().zip(&x[i + 1..=hi]).map(|(u, v)| u * v).sum();
            x[i] = (x[i] - acc) / data[i * w + b];
        }
    }

    fn substitute_generic<const R: usize>(&self, mut xs: [&mut [f64]; R]) {
        let (n, b, w) = (self.f.n, self.f.b, self.f.w);
        let data = &self.f.data;
        // forward: x_i -= L[i, lo..i] . x[lo..i] (row i stores column j at j + b - i)
        for i in 0..n {
            let lo = i.saturating_sub(b);
            let row = &data[i * w + (lo + b - i)..i * w + b];
            for x in xs.iter_mut() {
                let acc: f64 = row.iter().zip(&x[lo..i]).map(|(l, v)| l * v).sum();
                x[i] -= acc;
            }
        }
        // backward: x_i = (x_i - U[i, i+1..=hi] . x[i+1..=hi]) / U_ii
        for i in (0..n).rev() {
            let hi = (i + b).min(n - 1);
            let row = &data[i * w + b + 1..i * w + b + 1 + (hi - i)];
            let d = data[i * w + b];
            for x in xs.iter_mut() {
                let acc: f64 = row.iter().zip(&x[i + 1..=hi]).map(|(u, v)| u * v).sum();
                x[i] = (x[i] - acc) / d;
            }
        }
    }

    /// Forward and backward substitution of `R` right-hand sides for half-bandwidth `B`.
    /// Hand-optimized because the substitutions are a chain: `x_i` needs `x_{i-1}` (forward)
    /// or `x_{i+1}` (backward), so their speed is set by the latency of the operations on
    /// that chain, not by the arithmetic. A plain left-to-right dot product puts all `B`
    /// additions (and the back substitution's division) on the chain; here the `B - 1` terms
    /// that do not involve the neighbour are summed first in a tree and subtracted (they
    /// overlap with the previous row), only the neighbour's term is subtracted on the chain,
    /// and the division is a multiplication by the stored reciprocal pivot. Rows within `B`
    /// of either end use the generic loops.
    fn substitute_fixed<const B: usize, const R: usize>(&self, mut xs: [&mut [f64]; R]) {
        let (n, w) = (self.f.n, self.f.w);
        let data = &self.f.data;
        let edge = B.min(n);
        for i in 0..edge {
            let row = &data[i * w + (B - i)..i * w + B];
            for x in xs.iter_mut() {
                let acc: f64 = row.iter().zip(&x[..i]).map(|(l, v)| l * v).sum();
                x[i] -= acc;
            }
        }
        for i in edge..n {
            // columns i - B ..= i - 1; the last one (i - 1) is the neighbour on the chain
            let row: &[f64; B] = data[i * w..i * w + B].try_into().expect("row length B");
            for x in xs.iter_mut() {
                let v: &[f64; B] = x[i - B..i].try_into().expect("window length B");
                let far = tree_dot::<B>(row, v, 0, B - 1);
                // on the chain: one multiplication and one subtraction
                x[i] = (x[i] - far) - row[B - 1] * v[B - 1];
            }
        }
        let back_start = n.saturating_sub(B);
        for i in (back_start..n).rev() {
            let hi = n - 1;
            let row = &data[i * w + B + 1..i * w + B + 1 + (hi - i)];
            let d = data[i * w + B];
            for x in xs.iter_mut() {
                let acc: f64 = row.iter().zip(&x[i + 1..=hi]).map(|(u, v)| u * v).sum();
                x[i] = (x[i] - acc) / d;
            }
        }
        for i in (0..back_start).rev() {
            // columns i + 1 ..= i + B; the first one (i + 1) is the neighbour on the chain
            let row: &[f64; B] = data[i * w + B + 1..i * w + 2 * B + 1].try_into().expect("row length B");
            let inv = self.inv_pivot[i];
            for x in xs.iter_mut() {
                let v: &[f64; B] = x[i + 1..i + 1 + B].try_into().expect("window length B");
                let far = tree_dot::<B>(row, v, 1, B);
                // on the chain: multiplication, subtraction, multiplication by 1 / U_ii (a
                // division would add ~13 cycles per row)
                x[i] = ((x[i] - far) - row[0] * v[0]) * inv;
            }
        }
    }
}

/// `sum_{j in lo..hi} a_j b_j` with four independent partial sums (a short dependency chain;
/// the order of the additions differs from a left-to-right sum only by rounding).
#[inline(always)]
fn tree_dot<const B: usize>(a: &[f64; B], b: &[f64; B], lo: usize, hi: usize) -> f64 {
    let mut acc = [0.0; 4];
    for j in lo..hi {
        acc[(j - lo) % 4] += a[j] * b[j];
    }
    (acc[0] + acc[1]) + (acc[2] + acc[3])
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::{DMatrix, DVector};

    #[test]
    fn lu_matches_dense_solve_on_unsymmetric_band() {
        let (n, b) = (40, 5);
        let mut a = GeneralBand::zeros(n, b);
        let mut dense = DMatrix::<f64>::zeros(n, n);
        for i in 0..n {
            for j in i.saturating_sub(b)..=(i + b).min(n - 1) {
                let v = if i == j {
                    20.0 + i as f64
                } else {
                    ((i * 7 + j * 3) % 11) as f64 / 11.0 - 0.4
                };
                a.add(i, j, v);
                dense[(i, j)] = v;
            }
        }
        let rhs: Vec<f64> = (0..n).map(|i| (i as f64).sin()).collect();
        let mut x = rhs.clone();
        let mut lu = BandLu::new(n, b);
        lu.factor(&a).unwrap();
        lu.solve_in_place(&mut x);
        let xd = dense.lu().solve(&DVector::from_vec(rhs)).unwrap();
        for i in 0..n {
            assert!((x[i] - xd[i]).abs() < 1e-12, "{i}");
        }
        // A x reproduces the right-hand side (checks mul_vec)
        let mut y = vec![0.0; n];
        a.mul_vec(&x, &mut y);
        for (i, yi) in y.iter().enumerate() {
            assert!((yi - (i as f64).sin()).abs() < 1e-12, "A x at {i}");
        }
    }

    /// The factor of the whole matrix solves its leading blocks, and their last rows alone:
    /// against nalgebra's dense LU of
    /// the leading 17 x 17 block of an unsymmetric band (tolerance 1e-12).
    #[test]
    fn the_factor_solves_a_leading_block() {
        let (n, b, m) = (40, 5, 17);
        let mut a = GeneralBand::zeros(n, b);
        let mut dense = DMatrix::<f64>::zeros(m, m);
        for i in 0..n {
            for j in i.saturating_sub(b)..=(i + b).min(n - 1) {
                let v = if i == j {
                    20.0 + i as f64
                } else {
                    ((i * 5 + j * 3) % 13) as f64 / 13.0 - 0.45
                };
                a.add(i, j, v);
                if i < m && j < m {
                    dense[(i, j)] = v;
                }
            }
        }
        let rhs: Vec<f64> = (0..m).map(|i| (i as f64 * 0.7).cos()).collect();
        let mut lu = BandLu::new(n, b);
        lu.factor(&a).unwrap();
        let mut x = rhs.clone();
        lu.solve_leading_in_place(&mut x);
        let xd = dense.clone().lu().solve(&DVector::from_vec(rhs)).unwrap();
        for i in 0..m {
            assert!((x[i] - xd[i]).abs() < 1e-12, "{i}: {} vs {}", x[i], xd[i]);
        }
        // a right-hand side in the last rows, the solution wanted in the last six rows
        let mut tail = vec![0.0; m];
        tail[m - 2] = 1.0;
        let mut x = tail.clone();
        lu.solve_leading_from(&mut x, m - 6);
        let xd = dense.lu().solve(&DVector::from_vec(tail)).unwrap();
        for i in m - 6..m {
            assert!((x[i] - xd[i]).abs() < 1e-12, "{i}: {} vs {}", x[i], xd[i]);
        }
    }

    #[test]
    fn add_block_consecutive_and_scattered_dofs_agree_with_dense() {
        // Reference: the same blocks added entry by entry into a dense matrix.
        let (n, b) = (20, 11);
        let mut a = GeneralBand::zeros(n, b);
        let mut dense = DMatrix::<f64>::zeros(n, n);
        let k: Vec<f64> = (0..144).map(|i| (i as f64 * 0.37).sin()).collect();
        for dofs in [vec![3usize, 4, 5, 6, 7, 8], vec![9, 2, 12, 5]] {
            a.add_block(&dofs, &k, 12);
            for (r, &gr) in dofs.iter().enumerate() {
                for (c, &gc) in dofs.iter().enumerate() {
                    dense[(gr, gc)] += k[r * 12 + c];
                }
            }
        }
        for i in 0..n {
            for j in 0..n {
                assert_eq!(a.get(i, j), dense[(i, j)], "({i}, {j})");
            }
        }
    }

    #[test]
    fn unrolled_chain_kernel_matches_dense_solve() {
        // The half-bandwidth-11 kernel (all but the last 11 columns) against nalgebra's dense
        // LU (partial pivoting) on a diagonally dominant unsymmetric band; tolerance 1e-11.
        let (n, b) = (90, CHAIN_HALF_BANDWIDTH);
        let mut a = GeneralBand::zeros(n, b);
        let mut dense = DMatrix::<f64>::zeros(n, n);
        for i in 0..n {
            for j in i.saturating_sub(b)..=(i + b).min(n - 1) {
                let v = if i == j {
                    30.0 + (i % 7) as f64
                } else {
                    ((i * 13 + j * 5) % 17) as f64 / 17.0 - 0.45
                };
                a.add(i, j, v);
                dense[(i, j)] = v;
            }
        }
        let rhs: Vec<f64> = (0..n).map(|i| (0.3 * i as f64).cos()).collect();
        let mut x = rhs.clone();
        let mut lu = BandLu::new(n, b);
        lu.factor(&a).unwrap();
        lu.solve_in_place(&mut x);
        let xd = dense.lu().solve(&DVector::from_vec(rhs.clone())).unwrap();
        for i in 0..n {
            assert!((x[i] - xd[i]).abs() < 1e-11, "{i}: {} vs {}", x[i], xd[i]);
        }
        // two right-hand sides in one pass: identical to two single solves
        let other: Vec<f64> = (0..n).map(|i| (1.7 * i as f64).sin()).collect();
        let (mut x2, mut y2) = (rhs.clone(), other.clone());
        lu.solve2_in_place(&mut x2, &mut y2);
        let mut y1 = other;
        lu.solve_in_place(&mut y1);
        assert_eq!(x2, x);
        assert_eq!(y2, y1);
    }

    #[test]
    fn node_chain_kernel_matches_dense_solve() {
        // A block-tridiagonal matrix of 6x6 blocks (the node chain: 15 nodes, unsymmetric,
        // diagonally dominant) takes the structure-skipping kernel; reference: nalgebra's
        // dense LU, tolerance 1e-11. Then one entry outside the chain profile (row 40,
        // column 51) makes the factor fall back to the full kernel: again against dense LU.
        let (n, b) = (90, CHAIN_HALF_BANDWIDTH);
        for outside in [false, true] {
            let mut a = GeneralBand::zeros(n, b);
            let mut dense = DMatrix::<f64>::zeros(n, n);
            for i in 0..n {
                let lo = (i / 6).saturating_sub(1) * 6;
                let hi = ((i / 6 + 1) * 6 + 5).min(n - 1);
                for j in lo..=hi {
                    let v = if i == j {
                        40.0 + (i % 5) as f64
                    } else {
                        ((i * 11 + j * 7) % 19) as f64 / 19.0 - 0.5
                    };
                    a.add(i, j, v);
                    dense[(i, j)] = v;
                }
            }
            assert!((0..n).all(|i| in_chain_profile(i, &a.data[i * a.w..(i + 1) * a.w])));
            if outside {
                a.add(40, 51, 0.3);
                dense[(40, 51)] += 0.3;
                assert!(!in_chain_profile(40, &a.data[40 * a.w..41 * a.w]));
            }
            let rhs: Vec<f64> = (0..n).map(|i| (0.7 * i as f64).sin()).collect();
            let mut x = rhs.clone();
            let mut lu = BandLu::new(n, b);
            lu.factor(&a).unwrap();
            lu.solve_in_place(&mut x);
            let xd = dense.lu().solve(&DVector::from_vec(rhs)).unwrap();
            for i in 0..n {
                assert!(
                    (x[i] - xd[i]).abs() < 1e-11,
                    "outside {outside}, {i}: {} vs {}",
                    x[i],
                    xd[i]
                );
            }
            // A x reproduces the right-hand side (the fixed-width rows of mul_vec)
            let mut y = vec![0.0; n];
            a.mul_vec(&x, &mut y);
            for (i, yi) in y.iter().enumerate() {
                assert!((yi - (0.7 * i as f64).sin()).abs() < 1e-12, "A x at {i}");
            }
        }
    }

    #[test]
    fn streaming_factor_equals_modify_then_factor() {
        // factor_rows (each row changed just before its elimination) against factor_with
        // (the whole matrix changed first): identical factors, bit for bit.
        let (n, b) = (60, CHAIN_HALF_BANDWIDTH);
        let mut a = GeneralBand::zeros(n, b);
        for i in 0..n {
            for j in i.saturating_sub(b)..=(i + b).min(n - 1) {
                let v = if i == j {
                    25.0
                } else {
                    ((i * 7 + j * 11) % 13) as f64 / 13.0 - 0.5
                };
                a.add(i, j, v);
            }
        }
        // change: row i gets 0.1 (i % 5) at columns i-2..=i (within the band)
        let extra = |i: usize, j: usize| 0.1 * (i % 5) as f64 * (j + 2 >= i && j <= i) as u8 as f64;
        let mut f1 = BandLu::new(n, b);
        f1.factor_with(&a, |m| {
            for i in 0..n {
                for j in i.saturating_sub(2)..=i {
                    m.add(i, j, extra(i, j));
                }
            }
        })
        .unwrap();
        let mut f2 = BandLu::new(n, b);
        f2.factor_rows(&a, |i, row| {
            for j in i.saturating_sub(2)..=i {
                row[j + b - i] += extra(i, j);
            }
        })
        .unwrap();
        assert_eq!(f1.f.data, f2.f.data);
    }

    #[test]
    fn zero_pivot_is_reported() {
        let mut a = GeneralBand::zeros(3, 1);
        a.add(0, 0, 1.0);
        a.add(1, 1, 0.0);
        a.add(2, 2, 1.0);
        assert!(BandLu::new(3, 1).factor(&a).is_err());
    }
}
