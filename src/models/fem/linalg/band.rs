//! Symmetric band storage and a band LDLᵀ factorization without pivoting.
//!
//! The global stiffness of a drill string is a chain of 6-DOF nodes, so it is banded with
//! half-bandwidth 11. Nodes are numbered from the surface down, so the bit-end contacts
//! (the ones that change most often inside the contact loop) sit at the END of the band and
//! only the tail of the factor has to be recomputed ([`BandLdlt::refactor_from`]).
//!
//! The factorization is a left-looking column LDLᵀ: column `j` of `L` is built from column `j`
//! of `A` and the (final) columns `j - b .. j` of `L`. Every inner loop is a contiguous axpy
//! over a stored column. No pivoting is done; the matrix may be indefinite (compressed string
//! past buckling) as long as no pivot vanishes, and the number of negative pivots gives the
//! inertia (Sylvester's law): the number of negative eigenvalues.

/// Relative size below which a pivot counts as zero: `|d_j| <= PIVOT_TOL * |a_jj|` (its own column).
pub const PIVOT_TOL: f64 = 1e-14;

/// Symmetric matrix in lower band storage: entry (i, j), i >= j, i - j <= half_bandwidth.
///
/// Storage is column-major with leading dimension `half_bandwidth + 1`: column `j` stores rows
/// `j..=j + half_bandwidth` (entries past row `n - 1` exist in storage and are kept at zero).
/// Each symmetric pair is stored once; [`get`](Self::get), [`add`](Self::add) and
/// [`set`](Self::set) accept either triangle.
#[derive(Clone, Debug, PartialEq)]
pub struct BandMatrix {
    n: usize,
    hb: usize,
    ld: usize,
    data: Vec<f64>,
    constraint_scale: Option<f64>,
}

impl BandMatrix {
    /// An `n x n` zero matrix with the given half-bandwidth.
    pub fn zeros(n: usize, half_bandwidth: usize) -> Self {
        let ld = half_bandwidth + 1;
        Self {
            n,
            hb: half_bandwidth,
            ld,
            data: vec![0.0; n * ld],
            constraint_scale: None,
        }
    }

    /// Matrix dimension.
    #[inline]
    pub fn n(&self) -> usize {
        self.n
    }

    /// Half-bandwidth `b`: entries with `|i - j| > b` are zero.
    #[inline]
    pub fn half_bandwidth(&self) -> usize {
        self.hb
    }

    /// Raw column-major lower band storage (`n * (half_bandwidth + 1)` values).
    #[inline]
    pub fn data(&self) -> &[f64] {
        &self.data
    }

    #[inline]
    fn idx(&self, i: usize, j: usize) -> usize {
        let (r, c) = if i >= j { (i, j) } else { (j, i) };
        assert!(
            r < self.n && r - c <= self.hb,
            "band entry ({i}, {j}) outside n = {}, half-bandwidth = {}",
            self.n,
            self.hb
        );
        c * self.ld + (r - c)
    }

    /// Entry `(i, j)` (either triangle); zero outside the band.
    ///
    /// # Panics
    /// If `i` or `j` is `>= n`.
    #[inline]
    pub fn get(&self, i: usize, j: usize) -> f64 {
        let (r, c) = if i >= j { (i, j) } else { (j, i) };
        assert!(r < self.n, "band entry ({i}, {j}) outside n = {}", self.n);
        if r - c > self.hb {
            0.0
        } else {
            self.data[c * self.ld + (r - c)]
        }
    }

    /// Adds `v` to entry `(i, j)` (either triangle; the symmetric pair is stored once, so this
    /// also changes `(j, i)`).
    ///
    /// # Panics
    /// If the entry is outside the matrix or the band (a cheap check, kept in release builds
    /// because an out-of-band write would silently corrupt the next column).
    #[inline]
    pub fn add(&mut self, i: usize, j: usize, v: f64) {
        let k = self.idx(i, j);
        self.data[k] += v;
    }

    /// Sets entry `(i, j)` (and therefore `(j, i)`) to `v`.
    ///
    /// # Panics
    /// If the entry is outside the matrix or the band.
    #[inline]
    pub fn set(&mut self, i: usize, j: usize, v: f64) {
        let k = self.idx(i, j);
        self.data[k] = v;
    }

    /// Sets every entry to zero. The stored constraint scale (see
    /// [`constrain_dof`](Self::constrain_dof)) is kept.
    pub fn fill_zero(&mut self) {
        self.data.fill(0.0);
    }

    /// Zero the stored entries of columns `cols` (the lower triangle: rows `c ..= c + hb`).
    pub fn clear_columns(&mut self, cols: std::ops::Range<usize>) {
        self.data[cols.start * self.ld..cols.end * self.ld].fill(0.0);
    }

    /// Copies values and constraint scale from `other` (same `n` and half-bandwidth) without
    /// reallocating.
    ///
    /// # Panics
    /// If the shapes differ.
    pub fn copy_from(&mut self, other: &BandMatrix) {
        assert!(
            self.n == other.n && self.hb == other.hb,
            "copy_from: shape mismatch ({}, hb {}) vs ({}, hb {})",
            self.n,
            self.hb,
            other.n,
            other.hb
        );
        self.data.copy_from_slice(&other.data);
        self.constraint_scale = other.constraint_scale;
    }

    /// Scatters a dense symmetric element block into the matrix: `A[dofs[r], dofs[c]] += k[r * ld + c]`.
    ///
    /// `k` is row-major with leading dimension `ld` and `dofs.len() <= ld` rows/columns are used.
    /// Only pairs that land in the global lower triangle (`dofs[r] >= dofs[c]`) are read, so
    /// only one triangle of `k` needs to be valid in each symmetric pair; `dofs` need not be
    /// sorted. Each global entry receives the full sum of the element contributions.
    ///
    /// # Panics
    /// If `dofs.len() > ld`, `k` is too short, or a pair falls outside the matrix or band.
    pub fn add_block(&mut self, dofs: &[usize], k: &[f64], ld: usize) {
        let m = dofs.len();
        assert!(m <= ld, "add_block: {m} dofs but ld = {ld}");
        assert!(m == 0 || k.len() >= (m - 1) * ld + m, "add_block: k too short");
        if m == 0 {
            return;
        }
        let (lo, hi) = dofs.iter().fold((usize::MAX, 0), |(lo, hi), &d| (lo.min(d), hi.max(d)));
        assert!(
            hi < self.n && hi - lo <= self.hb,
            "add_block: dofs span {lo}..={hi} outside n = {} or half-bandwidth = {}",
            self.n,
            self.hb
        );
        let ldb = self.ld;
        for (r, &gr) in dofs.iter().enumerate() {
            let krow = &k[r * ld..r * ld + m];
            for (&gc, &v) in dofs.iter().zip(krow) {
                if gr >= gc {
                    self.data[gc * ldb + (gr - gc)] += v;
                }
            }
        }
    }

    /// The diagonal value used by [`constrain_dof`](Self::constrain_dof), if already fixed.
    pub fn constraint_scale(&self) -> Option<f64> {
        self.constraint_scale
    }

    /// Fixes (or with `None`, resets) the diagonal value used by
    /// [`constrain_dof`](Self::constrain_dof).
    pub fn set_constraint_scale(&mut self, scale: Option<f64>) {
        self.constraint_scale = scale;
    }

    /// Mean `|a_jj|` over the non-zero diagonal entries (1.0 if all are zero).
    pub fn mean_abs_diag(&self) -> f64 {
        let (sum, cnt) = self
            .data
            .iter()
            .step_by(self.ld)
            .take(self.n)
            .filter(|v| **v != 0.0)
            .fold((0.0, 0usize), |(s, c), v| (s + v.abs(), c + 1));
        if cnt == 0 || !sum.is_finite() || sum <= 0.0 {
            1.0
        } else {
            sum / cnt as f64
        }
    }

    /// Imposes a homogeneous Dirichlet condition on DOF `i`: zeroes row and column `i` and sets
    /// the diagonal to the stored constraint scale `s`.
    ///
    /// `s` is fixed on the first call (unless set with
    /// [`set_constraint_scale`](Self::set_constraint_scale)) as the mean `|a_jj|` of the matrix
    /// at that moment, and then reused for every later constrained DOF (it survives
    /// [`fill_zero`](Self::fill_zero) and is copied by [`copy_from`](Self::copy_from)). Using a
    /// diagonal of the same size as the rest keeps the condition number and the relative
    /// zero-pivot test meaningful, where a plain `1.0` next to stiffnesses of order 1e9 would not.
    ///
    /// The constrained equation reads `s * x_i = f_i`: set `f_i = 0` (or `s * prescribed`) in the
    /// right-hand side.
    pub fn constrain_dof(&mut self, i: usize) {
        assert!(i < self.n, "constrain_dof: {i} >= n = {}", self.n);
        let s = match self.constraint_scale {
            Some(s) => s,
            None => {
                let s = self.mean_abs_diag();
                self.constraint_scale = Some(s);
                s
            }
        };
        let ld = self.ld;
        for j in i.saturating_sub(self.hb)..i {
            self.data[j * ld + (i - j)] = 0.0;
        }
        let col = &mut self.data[i * ld..(i + 1) * ld];
        col.fill(0.0);
        col[0] = s;
    }

    /// `y = A x`.
    ///
    /// # Panics
    /// If `x` or `y` does not have length `n`.
    pub fn mul_vec(&self, x: &[f64], y: &mut [f64]) {
        let n = self.n;
        assert!(x.len() == n && y.len() == n, "mul_vec: length mismatch");
        y.fill(0.0);
        for j in 0..n {
            let m = self.hb.min(n - 1 - j);
            let col = &self.data[j * self.ld..j * self.ld + 1 + m];
            let xj = x[j];
            let mut acc = col[0] * xj;
            let xs = &x[j + 1..j + 1 + m];
            let ys = &mut y[j + 1..j + 1 + m];
            for ((yi, &xi), &a) in ys.iter_mut().zip(xs).zip(&col[1..]) {
                *yi += a * xj;
                acc += a * xi;
            }
            y[j] += acc;
        }
    }

    /// `max_j |a_jj|` (0 for an empty matrix).
    pub fn diag_abs_max(&self) -> f64 {
        self.data
            .iter()
            .step_by(self.ld)
            .take(self.n)
            .fold(0.0, |m: f64, v| m.max(v.abs()))
    }
}

/// Failure of a band factorization.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum FactorError {
    /// Pivot `d_column` is zero (or not finite) relative to its column: `|d| <= 1e-14 * |a_jj|`.
    /// The matrix is singular or nearly so at that DOF (unconstrained rigid-body mode, lost
    /// contact, exactly critical buckling load).
    #[error(
        "zero pivot at DOF column {column} (node {node}, local DOF {local} for 6 DOF/node): \
         d = {pivot:e} against the diagonal entry |a_jj| = {diagonal:e} it was reduced from \
         (zero means |d| <= 1e-14 |a_jj|); the stiffness matrix is singular there \
         (missing constraint or support?)",
        node = column / 6,
        local = column % 6
    )]
    ZeroPivot {
        /// Global DOF (column) index of the failed pivot.
        column: usize,
        /// Value of the pivot.
        pivot: f64,
        /// The magnitude the pivot is compared with (the column's diagonal entry, or the
        /// largest diagonal entry for the sparse factor).
        diagonal: f64,
    },
}

/// LDLᵀ factor of a [`BandMatrix`], without pivoting; keeps its own copy of the factor so a
/// tail refactor is possible.
///
/// Storage mirrors [`BandMatrix`]: column `j` holds `d_j` at offset 0 and `L[j+1.., j]` below.
/// After a failed factorization only the columns before the failing one are valid; a later
/// [`refactor_from`](Self::refactor_from) restarts from there automatically.
#[derive(Clone, Debug)]
pub struct BandLdlt {
    n: usize,
    hb: usize,
    ld: usize,
    data: Vec<f64>,
    /// `diag_max[j]` = max |a_ii| over i < j (of the matrix last factored).
    diag_max: Vec<f64>,
    /// `neg[j]` = number of negative pivots among columns < j.
    neg: Vec<usize>,
    /// `min_abs[j]` = min |d_i| over i < j.
    min_abs: Vec<f64>,
    /// Number of leading columns that hold a valid, final factor.
    valid: usize,
}

impl BandLdlt {
    /// Allocates a factor for `n x n` matrices of the given half-bandwidth (allocate once,
    /// refactor many times).
    pub fn new(n: usize, half_bandwidth: usize) -> Self {
        let ld = half_bandwidth + 1;
        let mut diag_max = vec![0.0; n + 1];
        diag_max[0] = 0.0;
        let mut min_abs = vec![f64::INFINITY; n + 1];
        min_abs[0] = f64::INFINITY;
        Self {
            n,
            hb: half_bandwidth,
            ld,
            data: vec![0.0; n * ld],
            diag_max,
            neg: vec![0; n + 1],
            min_abs,
            valid: 0,
        }
    }

    /// Matrix dimension.
    pub fn n(&self) -> usize {
        self.n
    }

    /// Half-bandwidth.
    pub fn half_bandwidth(&self) -> usize {
        self.hb
    }

    /// Whether the last (re)factorization succeeded, i.e. all `n` columns are valid.
    pub fn is_factored(&self) -> bool {
        self.valid == self.n
    }

    /// Pivot `d_j` of the last factorization.
    pub fn pivot(&self, j: usize) -> f64 {
        self.data[j * self.ld]
    }

    /// Raw factor storage (see the type documentation).
    pub fn data(&self) -> &[f64] {
        &self.data
    }

    /// Factors `a = L D Lᵀ` from scratch.
    ///
    /// # Errors
    /// [`FactorError::ZeroPivot`] at the first column whose pivot is zero (never divided by).
    ///
    /// # Panics
    /// If `a` has a different size or half-bandwidth.
    pub fn factor(&mut self, a: &BandMatrix) -> Result<(), FactorError> {
        self.valid = 0;
        self.factor_from(a, 0)
    }

    /// Refactors only columns `>= first_changed`. Valid when the entries `(i, j)` of `a` with
    /// `j < first_changed` (lower triangle) are unchanged since the last factorization; the
    /// result is bit-identical to [`factor`](Self::factor).
    ///
    /// Why this is exact: in the left-looking LDLᵀ, column `j` of `L` and `d_j` are computed
    /// only from column `j` of `A` (rows `>= j`) and the already final columns `k < j` of `L`
    /// and `D`. By induction, columns `0..first_changed` of the factor depend only on the
    /// lower-triangle columns `0..first_changed` of `A`, which did not change, so they are
    /// still the exact factor columns. (Band structure is what makes "the column of `A`" a
    /// finite, fixed set of entries; no pivoting means the order never changes.) Recomputing
    /// columns `first_changed..n` runs the identical floating-point operations in the identical
    /// order as a full factorization, so the factors agree bit for bit. The zero-pivot threshold
    /// uses `max |a_jj|` of the whole matrix, assembled from a cached prefix maximum of the
    /// unchanged columns and the current tail; inertia and minimum pivot are cached the same way.
    ///
    /// `first_changed` is clamped to the number of valid columns, so after a failed or missing
    /// factorization this falls back to (part of) a full one. Cost: O((n - first_changed) b²).
    ///
    /// # Errors
    /// As [`factor`](Self::factor).
    pub fn refactor_from(&mut self, a: &BandMatrix, first_changed: usize) -> Result<(), FactorError> {
        self.factor_from(a, first_changed)
    }

    fn factor_from(&mut self, a: &BandMatrix, first: usize) -> Result<(), FactorError> {
        assert!(
            a.n == self.n && a.hb == self.hb,
            "BandLdlt: matrix is {} (hb {}), factor was allocated for {} (hb {})",
            a.n,
            a.hb,
            self.n,
            self.hb
        );
        let n = self.n;
        let ld = self.ld;
        let hb = self.hb;
        let start = first.min(self.valid).min(n);
        self.valid = start;

        // Zero-pivot threshold from max |a_jj| over the whole matrix (prefix is cached).
        let mut dmax = self.diag_max[start];
        for (j, v) in a.data[start * ld..].iter().step_by(ld).enumerate() {
            let v = v.abs();
            if v > dmax {
                dmax = v;
            }
            self.diag_max[start + j + 1] = dmax;
        }

        let mut neg = self.neg[start];
        let mut min_abs = self.min_abs[start];
        let adata = &a.data[..n * ld];
        // Columns with a full window of `hb` previous columns use a kernel specialized for the
        // drill-string half-bandwidth; the choice depends only on `j`, never on `start`, so a
        // tail refactor repeats exactly the operations of a full factorization.
        let fixed_from = if hb == CHAIN_HB { hb.min(n) } else { n };
        for j in start..n {
            let (head, tail) = self.data.split_at_mut(j * ld);
            let col = &mut tail[..ld];
            col.copy_from_slice(&adata[j * ld..(j + 1) * ld]);
            if j >= fixed_from {
                update_col_fixed::<CHAIN_HB, { CHAIN_HB + 1 }>(&head[(j - hb) * ld..], col);
            } else {
                update_col_dyn(&head[j.saturating_sub(hb) * ld..], col, j.min(hb));
            }
            let d = col[0];
            // zero relative to this column's own diagonal: contact barrier or penalty terms
            // make the diagonal span many decades, so a global scale would flag sound pivots
            let tol = PIVOT_TOL * adata[j * ld].abs().max(f64::MIN_POSITIVE);
            if is_zero_pivot(d, tol) {
                return Err(FactorError::ZeroPivot {
                    column: j,
                    pivot: d,
                    diagonal: adata[j * ld].abs(),
                });
            }
            for c in col[1..].iter_mut() {
                *c /= d;
            }
            neg += (d < 0.0) as usize;
            min_abs = min_abs.min(d.abs());
            self.neg[j + 1] = neg;
            self.min_abs[j + 1] = min_abs;
            self.valid = j + 1;
        }
        Ok(())
    }

    /// Solves `A x = b` in place (`b` becomes `x`) with the last successful factorization.
    ///
    /// # Panics
    /// If `b.len() != n` or the factorization is not valid (failed or never done).
    pub fn solve_in_place(&self, b: &mut [f64]) {
        let n = self.n;
        let ld = self.ld;
        assert!(b.len() == n, "solve_in_place: rhs length {} != n = {n}", b.len());
        assert!(
            self.valid == n,
            "solve_in_place: no valid factorization (last one failed or none was done)"
        );
        let data = &self.data[..n * ld];
        // Forward: L y = b, then z = D^-1 y.
        for (k, col) in data.chunks_exact(ld).enumerate() {
            let m = (n - 1 - k).min(self.hb);
            let (bk, rest) = b[k..].split_first_mut().unwrap();
            let yk = *bk;
            for (bi, &l) in rest[..m].iter_mut().zip(&col[1..1 + m]) {
                *bi -= yk * l;
            }
            *bk = yk / col[0];
        }
        // Backward: Lᵀ x = z; farthest term first so the newest x_{j+1} enters last.
        for (j, col) in data.chunks_exact(ld).enumerate().rev() {
            let m = (n - 1 - j).min(self.hb);
            let (bj, rest) = b[j..].split_first_mut().unwrap();
            let mut acc = *bj;
            for (&xi, &l) in rest[..m].iter().zip(&col[1..1 + m]).rev() {
                acc -= l * xi;
            }
            *bj = acc;
        }
    }

    /// Number of negative pivots of the last factorization = number of negative eigenvalues of
    /// `A` (Sylvester's law of inertia). Counts only the valid columns after a failure.
    pub fn negative_pivots(&self) -> usize {
        self.neg[self.valid]
    }

    /// `min_j |d_j|` of the last factorization (`inf` if no column is valid).
    pub fn min_abs_pivot(&self) -> f64 {
        self.min_abs[self.valid]
    }
}

/// `|d| <= tol`, or `d` is NaN (never divided by).
#[inline]
pub(crate) fn is_zero_pivot(d: f64, tol: f64) -> bool {
    d.is_nan() || d.abs() <= tol
}

/// Half-bandwidth of a 6-DOF node chain (two nodes per element), for which the factor kernel
/// is specialized at compile time.
const CHAIN_HB: usize = 11;

/// Subtracts from `col` (column `j` of A, `ld` values) the contributions of the `w` previous
/// factor columns stored in `win` (`w * ld` values, oldest first): `col[i] -= L[j,k] d_k L[j+i,k]`.
/// The newest column, on the critical path, is applied last.
#[inline]
fn update_col_dyn(win: &[f64], col: &mut [f64], w: usize) {
    let ld = col.len();
    for (kk, lk) in win.chunks_exact(ld).take(w).enumerate() {
        let off = w - kk;
        let t = lk[off] * lk[0];
        let dst = &mut col[..ld - off];
        for (c, &l) in dst.iter_mut().zip(&lk[off..]) {
            *c -= t * l;
        }
    }
}

/// [`update_col_dyn`] with a full window of `HB` columns and compile-time lengths (`LD = HB + 1`),
/// so every loop is fully unrolled.
#[inline]
fn update_col_fixed<const HB: usize, const LD: usize>(win: &[f64], col: &mut [f64]) {
    let win = &win[..HB * LD];
    let col: &mut [f64; LD] = col.try_into().unwrap();
    let mut c = *col;
    for kk in 0..HB {
        let lk: &[f64; LD] = win[kk * LD..kk * LD + LD].try_into().unwrap();
        let off = HB - kk;
        let t = lk[off] * lk[0];
        for i in 0..LD - off {
            c[i] -= t * lk[off + i];
        }
    }
    *col = c;
}

// ---------------------------------------------------------------------------------------------
// Test / benchmark matrix generator.

/// Local 12x12 stiffness of a 3D Euler-Bernoulli beam (row-major), DOFs per node
/// `[ux, uy, uz, rx, ry, rz]`, local x along the axis.
#[doc(hidden)]
#[allow(clippy::too_many_arguments)]
pub fn beam_local_stiffness(e: f64, g: f64, area: f64, iy: f64, iz: f64, j: f64, l: f64) -> [f64; 144] {
    let mut k = [0.0; 144];
    let mut s = |r: usize, c: usize, v: f64| {
        k[r * 12 + c] = v;
        k[c * 12 + r] = v;
    };
    let ea = e * area / l;
    let gj = g * j / l;
    let (l2, l3) = (l * l, l * l * l);
    s(0, 0, ea);
    s(0, 6, -ea);
    s(6, 6, ea);
    s(3, 3, gj);
    s(3, 9, -gj);
    s(9, 9, gj);
    // bending in x-y plane (uy, rz), uses Iz
    let z = e * iz;
    s(1, 1, 12.0 * z / l3);
    s(1, 5, 6.0 * z / l2);
    s(1, 7, -12.0 * z / l3);
    s(1, 11, 6.0 * z / l2);
    s(5, 5, 4.0 * z / l);
    s(5, 7, -6.0 * z / l2);
    s(5, 11, 2.0 * z / l);
    s(7, 7, 12.0 * z / l3);
    s(7, 11, -6.0 * z / l2);
    s(11, 11, 4.0 * z / l);
    // bending in x-z plane (uz, ry), uses Iy
    let y = e * iy;
    s(2, 2, 12.0 * y / l3);
    s(2, 4, -6.0 * y / l2);
    s(2, 8, -12.0 * y / l3);
    s(2, 10, -6.0 * y / l2);
    s(4, 4, 4.0 * y / l);
    s(4, 8, 6.0 * y / l2);
    s(4, 10, 2.0 * y / l);
    s(8, 8, 12.0 * y / l3);
    s(8, 10, 6.0 * y / l2);
    s(10, 10, 4.0 * y / l);
    k
}

/// `Tᵀ k T` for `T = blockdiag(R, R, R, R)`, `R` (3x3 row-major) mapping global to local axes.
#[doc(hidden)]
pub fn rotate_element(k: &[f64; 144], r: &[[f64; 3]; 3]) -> [f64; 144] {
    let mut t = [0.0; 144];
    for b in 0..4 {
        for i in 0..3 {
            for j in 0..3 {
                t[(3 * b + i) * 12 + 3 * b + j] = r[i][j];
            }
        }
    }
    // kt = k T
    let mut kt = [0.0; 144];
    for i in 0..12 {
        for j in 0..12 {
            let mut s = 0.0;
            for m in 0..12 {
                s += k[i * 12 + m] * t[m * 12 + j];
            }
            kt[i * 12 + j] = s;
        }
    }
    let mut out = [0.0; 144];
    for i in 0..12 {
        for j in 0..12 {
            let mut s = 0.0;
            for m in 0..12 {
                s += t[m * 12 + i] * kt[m * 12 + j];
            }
            out[i * 12 + j] = s;
        }
    }
    // symmetrize exactly
    for i in 0..12 {
        for j in 0..i {
            let v = 0.5 * (out[i * 12 + j] + out[j * 12 + i]);
            out[i * 12 + j] = v;
            out[j * 12 + i] = v;
        }
    }
    out
}

/// Drill-string-like chain test matrix: `nodes` nodes (6 DOF each, half-bandwidth 11),
/// 1 m 3D Euler-Bernoulli pipe elements (E 207 GPa, G 79.6 GPa, OD 0.127 m, ID 0.1086 m)
/// inclined 30 deg, azimuth 40 deg (each element rotated with TᵀkT), 1e3 N/m grounded springs
/// on every translational DOF, node 0 constrained with [`BandMatrix::constrain_dof`].
#[doc(hidden)]
pub fn chain_test_matrix(nodes: usize) -> BandMatrix {
    chain_test_matrix_with(nodes, 1.0, 1e3)
}

/// [`chain_test_matrix`] with a chosen element length and grounded spring stiffness.
#[doc(hidden)]
pub fn chain_test_matrix_with(nodes: usize, elem_len: f64, spring: f64) -> BandMatrix {
    chain_assemble(nodes, elem_len, spring, true)
}

fn chain_assemble(nodes: usize, elem_len: f64, spring: f64, constrain: bool) -> BandMatrix {
    use std::f64::consts::PI;
    let (e, g, od, id) = (207e9, 79.6e9, 0.127, 0.1086);
    let area = PI / 4.0 * (od * od - id * id);
    let i = PI / 64.0 * (od.powi(4) - id.powi(4));
    let kl = beam_local_stiffness(e, g, area, i, i, 2.0 * i, elem_len);
    let (inc, azi) = (30f64.to_radians(), 40f64.to_radians());
    // Global frame (north, east, down). Local x along the element, y = high side, z = x × y.
    let ex = [inc.sin() * azi.cos(), inc.sin() * azi.sin(), inc.cos()];
    let ey = [-inc.cos() * azi.cos(), -inc.cos() * azi.sin(), inc.sin()];
    let ez = [
        ex[1] * ey[2] - ex[2] * ey[1],
        ex[2] * ey[0] - ex[0] * ey[2],
        ex[0] * ey[1] - ex[1] * ey[0],
    ];
    let kg = rotate_element(&kl, &[ex, ey, ez]);
    let n = 6 * nodes;
    let mut a = BandMatrix::zeros(n, 11);
    let mut dofs = [0usize; 12];
    for el in 0..nodes.saturating_sub(1) {
        for (d, v) in dofs.iter_mut().enumerate() {
            *v = 6 * el + d;
        }
        a.add_block(&dofs, &kg, 12);
    }
    for node in 0..nodes {
        for d in 0..3 {
            a.add(6 * node + d, 6 * node + d, spring);
        }
    }
    if constrain {
        for d in 0..6.min(n) {
            a.constrain_dof(d);
        }
    }
    a
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::{DMatrix, DVector};
    use proptest::prelude::*;

    fn to_dense(a: &BandMatrix) -> DMatrix<f64> {
        DMatrix::from_fn(a.n(), a.n(), |i, j| a.get(i, j))
    }

    fn rel_residual(a: &BandMatrix, x: &[f64], b: &[f64]) -> f64 {
        let mut ax = vec![0.0; a.n()];
        a.mul_vec(x, &mut ax);
        let r = ax.iter().zip(b).map(|(p, q)| (p - q).abs()).fold(0.0, f64::max);
        let d = to_dense(a);
        let anorm = (0..a.n())
            .map(|i| d.row(i).iter().map(|v| v.abs()).sum::<f64>())
            .fold(0.0, f64::max);
        let xn = x.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        let bn = b.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        r / (anorm * xn + bn)
    }

    fn rel_diff(x: &[f64], y: &[f64]) -> f64 {
        let num = x.iter().zip(y).map(|(p, q)| (p - q).abs()).fold(0.0, f64::max);
        let den = y.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        num / den
    }

    fn random_band(n: usize, hb: usize, vals: &[f64], shift: f64) -> BandMatrix {
        let mut a = BandMatrix::zeros(n, hb);
        let mut it = vals.iter().cycle();
        for j in 0..n {
            for i in j + 1..(j + hb + 1).min(n) {
                a.set(i, j, *it.next().unwrap());
            }
        }
        // Diagonal dominance makes it SPD.
        for i in 0..n {
            let s: f64 = (i.saturating_sub(hb)..(i + hb + 1).min(n))
                .filter(|&j| j != i)
                .map(|j| a.get(i, j).abs())
                .sum();
            a.set(i, i, s + shift);
        }
        a
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(200))]
        #[test]
        fn band_ldlt_matches_dense_spd(
            n in 1usize..40,
            hb in 0usize..8,
            vals in prop::collection::vec(-1.0f64..1.0, 1..400),
            rhs in prop::collection::vec(-1.0f64..1.0, 40),
            shift in 0.01f64..10.0,
        ) {
            let a = random_band(n, hb, &vals, shift);
            let b: Vec<f64> = rhs[..n].to_vec();
            let mut f = BandLdlt::new(n, hb);
            f.factor(&a).unwrap();
            prop_assert_eq!(f.negative_pivots(), 0);
            let mut x = b.clone();
            f.solve_in_place(&mut x);
            prop_assert!(rel_residual(&a, &x, &b) < 1e-10);
            let xd = to_dense(&a).lu().solve(&DVector::from_vec(b.clone())).unwrap();
            prop_assert!(rel_diff(&x, xd.as_slice()) < 1e-10);
        }

        #[test]
        fn mul_vec_matches_dense(
            n in 1usize..30,
            hb in 0usize..6,
            vals in prop::collection::vec(-1.0f64..1.0, 1..200),
            x in prop::collection::vec(-1.0f64..1.0, 30),
        ) {
            let a = random_band(n, hb, &vals, 1.0);
            let mut y = vec![0.0; n];
            a.mul_vec(&x[..n], &mut y);
            let yd = to_dense(&a) * DVector::from_column_slice(&x[..n]);
            for (p, q) in y.iter().zip(yd.iter()) {
                prop_assert!((p - q).abs() <= 1e-12 * (1.0 + q.abs()));
            }
        }
    }

    fn chain_rhs(n: usize) -> Vec<f64> {
        // Weight-like load on the translations, zero on constrained node 0.
        (0..n)
            .map(|i| {
                if i < 6 {
                    0.0
                } else if i % 6 < 3 {
                    -500.0 + (i as f64).sin() * 100.0
                } else {
                    10.0
                }
            })
            .collect()
    }

    #[test]
    fn chain_matches_faer_and_dense() {
        let a = chain_test_matrix(100);
        let n = a.n();
        let b = chain_rhs(n);
        let mut f = BandLdlt::new(n, 11);
        f.factor(&a).unwrap();
        assert_eq!(f.negative_pivots(), 0);
        let mut x = b.clone();
        f.solve_in_place(&mut x);
        assert!(rel_residual(&a, &x, &b) < 1e-14, "{}", rel_residual(&a, &x, &b));

        let xd = to_dense(&a).cholesky().unwrap().solve(&DVector::from_vec(b.clone()));
        assert!(
            rel_diff(&x, xd.as_slice()) < 1e-9,
            "dense {}",
            rel_diff(&x, xd.as_slice())
        );

        let mut fl = crate::models::fem::linalg::sparse_faer::FaerLdlt::new(&a);
        fl.factor(&a).unwrap();
        let mut xf = b.clone();
        fl.solve_in_place(&mut xf);
        assert!(rel_diff(&x, &xf) < 1e-9, "faer {}", rel_diff(&x, &xf));
    }

    #[test]
    fn refactor_from_is_bit_identical() {
        let nodes = 100;
        let mut a = chain_test_matrix(nodes);
        let n = a.n();
        let mut tail = BandLdlt::new(n, 11);
        tail.factor(&a).unwrap();
        let first = 6 * (nodes - 10);
        for node in nodes - 10..nodes {
            for d in 0..3 {
                a.add(6 * node + d, 6 * node + d, 2.5e5 * (node % 3 + 1) as f64);
            }
        }
        // An off-diagonal change inside the tail as well.
        a.add(first + 7, first + 1, 3.0e4);
        tail.refactor_from(&a, first).unwrap();
        let mut full = BandLdlt::new(n, 11);
        full.factor(&a).unwrap();
        assert!(tail.data == full.data, "factors differ");
        assert_eq!(tail.negative_pivots(), full.negative_pivots());
        assert_eq!(tail.min_abs_pivot(), full.min_abs_pivot());
        let b = chain_rhs(n);
        let (mut x1, mut x2) = (b.clone(), b.clone());
        tail.solve_in_place(&mut x1);
        full.solve_in_place(&mut x2);
        assert_eq!(x1, x2);
        assert!(rel_residual(&a, &x1, &b) < 1e-14);
    }

    #[test]
    fn refactor_after_failure_restarts_correctly() {
        let mut a = chain_test_matrix(20);
        let n = a.n();
        let mut f = BandLdlt::new(n, 11);
        f.factor(&a).unwrap();
        let saved = a.clone();
        // Make column 60 singular: zero it completely.
        for j in 60usize.saturating_sub(11)..(60 + 12).min(n) {
            a.set(60, j, 0.0);
        }
        let err = f.refactor_from(&a, 60 - 11).unwrap_err();
        assert!(matches!(err, FactorError::ZeroPivot { column: 60, .. }), "{err:?}");
        assert!(!f.is_factored());
        // Change only column 100: the refactor must still restart at the failed column 60
        // (columns 60.. were never computed), and fail there again.
        a.add(100, 100, 1.0);
        let err = f.refactor_from(&a, 100).unwrap_err();
        assert!(matches!(err, FactorError::ZeroPivot { column: 60, .. }), "{err:?}");
        // Restore: entries of columns 49.. changed since the last call.
        a.copy_from(&saved);
        f.refactor_from(&a, 60 - 11).unwrap();
        assert!(f.is_factored());
        let mut full = BandLdlt::new(n, 11);
        full.factor(&a).unwrap();
        assert!(f.data == full.data);
    }

    #[test]
    fn indefinite_inertia_matches_eigen() {
        for (n, hb, seed) in [(30usize, 3usize, 1u64), (50, 11, 7), (17, 1, 3), (64, 5, 11)] {
            let mut s = seed.wrapping_mul(0x9E3779B97F4A7C15) | 1;
            let mut rnd = move || {
                s ^= s << 13;
                s ^= s >> 7;
                s ^= s << 17;
                (s >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
            };
            let mut a = BandMatrix::zeros(n, hb);
            for j in 0..n {
                let sign = if (j * 7 + seed as usize) % 5 < 2 { -1.0 } else { 1.0 };
                a.set(j, j, sign * (2.0 + 3.0 * rnd().abs()));
                for i in j + 1..(j + hb + 1).min(n) {
                    a.set(i, j, 0.4 * rnd());
                }
            }
            let mut f = BandLdlt::new(n, hb);
            match f.factor(&a) {
                Ok(()) => {
                    let eig = to_dense(&a).symmetric_eigenvalues();
                    let neg = eig.iter().filter(|v| **v < 0.0).count();
                    assert_eq!(f.negative_pivots(), neg, "n {n} hb {hb}");
                    assert!(neg > 0);
                    let b: Vec<f64> = (0..n).map(|i| (i as f64).cos()).collect();
                    let mut x = b.clone();
                    f.solve_in_place(&mut x);
                    assert!(rel_residual(&a, &x, &b) < 1e-12);
                }
                Err(e) => panic!("unexpected {e}"),
            }
        }
    }

    #[test]
    fn buckled_chain_counts_negative_pivots() {
        // Chain with a compressive geometric-stiffness-like negative shift on lateral DOFs.
        let mut a = chain_test_matrix(40);
        let n = a.n();
        for i in 6..n {
            if i % 6 == 1 || i % 6 == 2 {
                a.add(i, i, -3.0e5);
            }
        }
        let mut f = BandLdlt::new(n, 11);
        f.factor(&a).unwrap();
        let eig = to_dense(&a).symmetric_eigenvalues();
        let neg = eig.iter().filter(|v| **v < 0.0).count();
        assert!(neg > 0);
        assert_eq!(f.negative_pivots(), neg);
    }

    #[test]
    fn singular_reports_zero_pivot() {
        // Two identical rows: [[1,1],[1,1]] block at columns 3,4.
        let mut a = BandMatrix::zeros(8, 2);
        for i in 0..8 {
            a.set(i, i, 2.0);
        }
        a.set(3, 3, 1.0);
        a.set(4, 4, 1.0);
        a.set(4, 3, 1.0);
        let mut f = BandLdlt::new(8, 2);
        let err = f.factor(&a).unwrap_err();
        assert!(
            matches!(err, FactorError::ZeroPivot { column: 4, pivot, .. } if pivot == 0.0),
            "{err:?}"
        );
        assert!(err.to_string().contains("DOF column 4"));
        // the message says what the pivot is zero against
        assert!(err.to_string().contains("against the diagonal entry"), "{err}");
        assert_eq!(f.negative_pivots(), 0);

        // Unconstrained free-free chain without springs: rigid-body modes.
        let g = chain_assemble(10, 1.0, 0.0, false);
        let mut f = BandLdlt::new(g.n(), 11);
        let err = f.factor(&g).unwrap_err();
        assert!(
            matches!(err, FactorError::ZeroPivot { column, .. } if column >= 54),
            "{err}"
        );

        // All-zero matrix.
        let z = BandMatrix::zeros(5, 1);
        let mut f = BandLdlt::new(5, 1);
        assert!(matches!(f.factor(&z), Err(FactorError::ZeroPivot { column: 0, .. })));
    }

    #[test]
    fn band_matrix_basics() {
        let mut a = BandMatrix::zeros(5, 1);
        a.add(1, 0, 2.0);
        a.add(0, 1, 1.0);
        assert_eq!(a.get(0, 1), 3.0);
        assert_eq!(a.get(1, 0), 3.0);
        assert_eq!(a.get(4, 0), 0.0);
        a.set(2, 2, -7.0);
        assert_eq!(a.diag_abs_max(), 7.0);
        a.set(0, 0, 1.0);
        a.constrain_dof(1);
        assert_eq!(a.get(1, 0), 0.0);
        assert_eq!(a.get(1, 1), 4.0); // mean |diag| of {1, 7}
        assert_eq!(a.constraint_scale(), Some(4.0));
        let mut c = BandMatrix::zeros(5, 1);
        c.copy_from(&a);
        assert_eq!(c, a);
        // add_block with unsorted dofs and only one triangle valid.
        let mut m = BandMatrix::zeros(4, 2);
        let k = [1.0, 99.0, 2.0, 3.0]; // row-major 2x2, (0,1) is garbage: dofs[0] < dofs[1]
        m.add_block(&[1, 3], &k, 2);
        assert_eq!(m.get(1, 1), 1.0);
        assert_eq!(m.get(3, 1), 2.0);
        assert_eq!(m.get(3, 3), 3.0);
    }

    #[test]
    #[should_panic]
    fn out_of_band_add_panics() {
        let mut a = BandMatrix::zeros(5, 1);
        a.add(3, 0, 1.0);
    }

    /// Timing run: `cargo test --release --lib models::fem::linalg::band::tests::timings -- --ignored --nocapture`.
    #[test]
    #[ignore]
    fn timings() {
        use std::time::Instant;
        fn median(mut v: Vec<f64>) -> f64 {
            v.sort_by(|a, b| a.partial_cmp(b).unwrap());
            v[v.len() / 2]
        }
        for nodes in [1000usize, 3000, 16000] {
            let a = chain_test_matrix(nodes);
            let n = a.n();
            let reps = (2_000_000 / n).max(20);
            let mut f = BandLdlt::new(n, 11);
            let mut tf = Vec::new();
            for _ in 0..reps {
                let t = Instant::now();
                f.factor(&a).unwrap();
                tf.push(t.elapsed().as_secs_f64() * 1e3);
            }
            let mut tr = Vec::new();
            for _ in 0..reps {
                let t = Instant::now();
                f.refactor_from(&a, n - 600).unwrap();
                tr.push(t.elapsed().as_secs_f64() * 1e3);
            }
            let b = chain_rhs(n);
            let mut ts = Vec::new();
            let mut x = b.clone();
            for _ in 0..reps {
                x.copy_from_slice(&b);
                let t = Instant::now();
                f.solve_in_place(&mut x);
                ts.push(t.elapsed().as_secs_f64() * 1e3);
            }
            let mut fl = crate::models::fem::linalg::sparse_faer::FaerLdlt::new(&a);
            let mut tff = Vec::new();
            for _ in 0..reps {
                let t = Instant::now();
                fl.factor(&a).unwrap();
                tff.push(t.elapsed().as_secs_f64() * 1e3);
            }
            let mut tfs = Vec::new();
            let mut xf = b.clone();
            for _ in 0..reps {
                xf.copy_from_slice(&b);
                let t = Instant::now();
                fl.solve_in_place(&mut xf);
                tfs.push(t.elapsed().as_secs_f64() * 1e3);
            }
            println!(
                "n {n:6}: band factor {:.4} ms, tail600 {:.4} ms, solve {:.4} ms | faer factor {:.4} ms, solve {:.4} ms | diff {:.1e}",
                median(tf), median(tr), median(ts), median(tff), median(tfs), rel_diff(&x, &xf)
            );
        }
    }
}
