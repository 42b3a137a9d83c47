//! The contact subproblem of one Newton step, solved by a primal-dual interior-point method on
//! the band system: `K du + N R = -r0`, `N^T du + s = -g`, `R, s >= 0`, `R s = 0` (`du` the
//! displacement increment, `R` the contact forces, `s` the slacks of the linearized gaps `g`),
//! bordered by the hook-load equation. Each iteration factors `K + N diag(R/s) N^T`, which
//! keeps the band structure (a rank-one 3x3 block per contact), and makes two solves with it
//! (Mehrotra predictor-corrector: the affine direction sets the centering, the corrector adds
//! the second-order complementarity term). The iteration is warm-started from the previous
//! step's multipliers, shifted off the boundary in proportion to the outer residual
//! ([`IP_START_SHIFT`]), and stopped at a tolerance tied to the outer residual
//! (`ip_tolerance`: inexact Newton, exact near convergence). Near convergence it first tries
//! the active-set step of the last contact set ([`ACTIVE_SET_RESIDUAL`]).

use super::contacts::ContactColumns;
use super::convergence::MIN_REFERENCE_CLEARANCE_M;
use super::errors::{singular, SolveError};
use super::matrix_and_factor::MatrixAndFactor;
use super::solution::SolveStats;
use crate::models::fem::model::{Evaluation, Model, StiffnessSink, HALF_BANDWIDTH};

/// Shift of the interior-point warm start off the boundary, per unit of outer residual:
/// multipliers get `+ shift * load_scale / contacts`, slacks `+ shift * clearance`, with
/// `shift = clamp(IP_START_SHIFT * rn, 1e-6, 0.1)`.
pub const IP_START_SHIFT: f64 = 0.1;

/// Factor of the warm-start shift ([`IP_START_SHIFT`]) for a start carried onto a refined mesh
/// ([`super::SolveControls::carried_start`]), its floor lowered by the same factor: the start
/// is a converged solution and its contact forces spread along the refined runs, so the pairs
/// start near their values (docs/performance.md, "Contact-aware refinement": with the spread
/// forces and no active-set step, 1-6 fewer factorizations of the refined solve on the example
/// wells).
pub const CARRIED_START_SHIFT_FACTOR: f64 = 0.1;

/// Consecutive stalled interior-point steps (shorter than 1e-2, or cycling beyond
/// [`IP_CYCLE_STEPS`]) after which the contact subproblem of a linearization far from the
/// solution (inner tolerance above 1e-8) is left as it is, and one near it restarted
/// ([`IP_RESTARTS`]).
pub const IP_STALL_STEPS: usize = 5;

/// An interior-point step whose iterate is feasible to the tolerance (the dual residual below
/// it, the primal below ten times it) and whose mean complementarity is above this share of
/// the smallest before is cycling: with friction the linearized contact problem may have no
/// complementary solution, and the iterates then cycle at a constant complementarity
/// (docs/performance.md, "Interior-point cycles").
pub const IP_CYCLE_MU_RATIO: f64 = 0.9;

/// Cycling interior-point steps ([`IP_CYCLE_MU_RATIO`]) in a row after which each further one
/// counts as stalled ([`IP_STALL_STEPS`] stalled steps stop or restart the solve); with five
/// instead of ten, the loads row beyond lock-up of `tests/verification/slack_off.rs` did not
/// converge.
pub const IP_CYCLE_STEPS: usize = 10;

/// Recentrings of an interior-point solve stalled far from the solution (inner tolerance
/// above 1e-8) before it takes the step found so far: the pairs that limited the stalled
/// steps ([`IP_STALL_STEPS`] steps shorter than 1e-2) are moved off the boundary onto the
/// central path (`R s` the mean complementarity, `R / s` the pair's own ratio `|dR / ds|` in
/// the step that it limited), the rest of the warm start kept. A pair with force and gap
/// both near zero whose direction asks kilonewtons and metres (a contact on a nearly
/// singular mode of a post-buckled string, held only by the pseudo-transient damping)
/// otherwise limits every step to 1e-5, and the outer Newton crawls (docs/performance.md,
/// "Interior-point pairs recentred").
pub const IP_RECENTRES: usize = 3;

/// An interior-point step shorter than this is stalled ([`IP_STALL_STEPS`]).
const STALLED_STEP: f64 = 1e-2;

/// Restarts of an interior-point solve stalled near the solution (inner tolerance at most 1e-8),
/// each from its warm start shifted [`IP_RESTART_SHIFT_FACTOR`] times farther off the
/// boundary. Far from the solution it does not restart: a restart there discards the warm
/// start's contact set and makes the outer iteration wander on the horizontal WOB case of
/// tests/verification/extremes.rs (thousands of factorizations).
pub const IP_RESTARTS: usize = 2;

/// Growth of the warm-start shift at each interior-point restart.
pub const IP_RESTART_SHIFT_FACTOR: f64 = 100.0;

/// Interior-point iterations allowed per Newton step.
pub const MAX_IP_ITERATIONS: usize = 60;

/// Outer residual (relative to the load scale) below which an interior-point solve first
/// tries the active-set step of the last contact set (one factorization; [`ACTIVE_SET_TRIES`]
/// with the pairs that left the set switched), the interior point taking over when the set
/// does not hold.
pub const ACTIVE_SET_RESIDUAL: f64 = 1e-3;

/// Distance from the boundary of the active-set step's start, and how far past it a pair may
/// end and still count as in its set: relative to the clearance (slacks) and to the load scale
/// per contact (multipliers).
pub const ACTIVE_SET_EPS: f64 = 1e-9;

/// Active-set steps tried per Newton step before the interior point takes over, unless the
/// set is settling ([`ACTIVE_SET_MAX_TRIES`]).
pub const ACTIVE_SET_TRIES: usize = 2;

/// Active-set steps tried at most per Newton step: beyond [`ACTIVE_SET_TRIES`], one more while
/// the last try switched fewer pairs than the one before (the set settling, not cycling). On the
/// example wells' `bha` solves 2-3 factorizations fewer on two of six (one pair, then none, to
/// switch), the others unchanged (docs/performance.md, "A third active-set try while the set
/// settles").
pub const ACTIVE_SET_MAX_TRIES: usize = 3;

/// Smallest force of a pair in the active set's start, per contact's share of the load scale:
/// a pair with less force (one just touching, at the end of a contact run) starts outside the
/// set.
pub const ACTIVE_SET_MIN_FORCE: f64 = 1e-3;

/// Relative tolerance of the interior-point solve of one linearization whose outer residual
/// (relative to the load scale) is `rn`: `min(1e-2 rn, rn^2)`, never below 1e-10 (the exact
/// tolerance used at convergence).
pub(crate) fn ip_tolerance(rn: f64) -> f64 {
    (1e-2 * rn).min(rn * rn).max(1e-10)
}

/// The pair that limits the step to the boundary of `r + a dr`, `s + a ds` (contact index) and
/// its ratio `|dr / ds|` (N/m); None if no pair limits it or its ratio is not finite and
/// positive. The same ratios as [`step_to_boundary`], whose loop stays free of the index
/// bookkeeping: it runs twice per interior-point iteration, this one only after a stalled step.
fn blocking_pair(r: &[f64], dr: &[f64], s: &[f64], ds: &[f64]) -> Option<(usize, f64)> {
    let mut worst = (f64::INFINITY, None);
    for j in 0..r.len() {
        for (x, dx) in [(r[j], dr[j]), (s[j], ds[j])] {
            if dx < 0.0 && -x / dx < worst.0 {
                worst = (-x / dx, Some(j));
            }
        }
    }
    let j = worst.1?;
    let k = (dr[j] / ds[j]).abs();
    (k.is_finite() && k > 0.0).then_some((j, k))
}

/// Move the pairs `blockers` (contact index, ratio `|dR / ds|` N/m) of `it` onto the central
/// path at its mean complementarity `mu`: `R = sqrt(mu k)`, `s = sqrt(mu / k)`, neither
/// lowered ([`IP_RECENTRES`]).
fn recentre(it: &mut IpIterate, blockers: &[(usize, f64)]) {
    let mt = it.r.len();
    let mu = (0..mt).map(|j| it.r[j] * it.s[j]).sum::<f64>() / mt.max(1) as f64;
    for &(j, k) in blockers {
        it.r[j] = it.r[j].max((mu * k).sqrt());
        it.s[j] = it.s[j].max((mu / k).sqrt());
    }
}

/// Largest step in (0, 1] keeping `r + a dr` and `s + a ds` positive, times `tau`
/// (fraction to the boundary).
fn step_to_boundary(r: &[f64], dr: &[f64], s: &[f64], ds: &[f64], tau: f64) -> f64 {
    let mut a: f64 = 1.0;
    for j in 0..r.len() {
        if dr[j] < 0.0 {
            a = a.min(-tau * r[j] / dr[j]);
        }
        if ds[j] < 0.0 {
            a = a.min(-tau * s[j] / ds[j]);
        }
    }
    a
}

/// The previous multiplier of each contact of `cols` (N; the far-wall planes: 0), from the
/// multipliers per node `multipliers` of the managed gaps `qidx`.
pub(crate) fn previous_multipliers(cols: &ContactColumns, qidx: &[usize], multipliers: &[f64]) -> Vec<f64> {
    let m = qidx.len();
    (0..cols.len())
        .map(|j| if j < m { multipliers[qidx[j]] } else { 0.0 })
        .collect()
}

/// Clearance of each contact's node at the evaluation `ev`, at least
/// [`MIN_REFERENCE_CLEARANCE_M`], m.
pub(crate) fn contact_clearances(cols: &ContactColumns, ev: &Evaluation) -> Vec<f64> {
    cols.node
        .iter()
        .map(|&i| ev.clearance[i].max(MIN_REFERENCE_CLEARANCE_M))
        .collect()
}

/// The six DOFs of each contact's node.
pub(crate) fn contact_dofs(model: &Model, cols: &ContactColumns) -> Vec<[usize; 6]> {
    cols.node
        .iter()
        .map(|&i| std::array::from_fn(|k| model.dof(i, k)))
        .collect()
}

/// Diagonal given to the held DOFs of `lin`'s matrix (any positive value: they are
/// decoupled): the mean magnitude of its positive finite diagonal entries (1 if none).
pub(crate) fn constraint_scale(lin: &MatrixAndFactor, n: usize) -> f64 {
    let (sum, cnt) = (0..n)
        .map(|d| lin.get(d, d).abs())
        .filter(|v| *v > 0.0 && v.is_finite())
        .fold((0.0, 0usize), |(s, c), v| (s + v, c + 1));
    if cnt > 0 {
        sum / cnt as f64
    } else {
        1.0
    }
}

/// The contact subproblem of one linearization, with the tangent `K` assembled (and kept in
/// `base` when the factorization overwrites it).
pub(crate) struct ContactSubproblem<'a> {
    /// The model.
    pub(crate) model: &'a Model,
    /// The linearized contacts.
    pub(crate) cols: &'a ContactColumns,
    /// Managed-gap contact index of each node (`usize::MAX`: none).
    pub(crate) contact_at: &'a [usize],
    /// Residual with the constrained entries zeroed, N and N.m (DOF order).
    pub(crate) r0: &'a [f64],
    /// The WOB equation's residual, N.
    pub(crate) c: f64,
    /// The bit's axial row of `K` over the free columns.
    pub(crate) kb: &'a [(usize, f64)],
    /// The hook-load column: the residual's change per newton of hook load, by DOF
    /// ([`Model::hook_column`]).
    pub(crate) hook: &'a [(usize, f64)],
    /// Whether the hook load is unknown (the system is bordered).
    pub(crate) bordered: bool,
    /// Held DOFs.
    pub(crate) constrained: &'a [usize],
    /// Prescribed increments of held DOFs (DOF, m): the switching pins' lateral moves.
    pub(crate) pin_move: &'a [(usize, f64)],
    /// The assembled `K` kept for the factorizations (`None`: in the factored object itself).
    pub(crate) base: Option<&'a MatrixAndFactor>,
    /// Diagonal of the held DOFs.
    pub(crate) constraint_scale: f64,
    /// Load scale, N.
    pub(crate) scale: f64,
    /// Relative tolerance of this solve ([`ip_tolerance`]).
    pub(crate) eta: f64,
    /// Previous multiplier per contact, N ([`previous_multipliers`]).
    pub(crate) lam_prev: Vec<f64>,
    /// Reference clearance per contact, m ([`contact_clearances`]).
    pub(crate) clr: Vec<f64>,
    /// DOFs of each contact's node ([`contact_dofs`]).
    pub(crate) dofs6: Vec<[usize; 6]>,
    /// The start was carried onto a refined mesh ([`CARRIED_START_SHIFT_FACTOR`]).
    pub(crate) carried_start: bool,
    /// Recentre the pairs that block a stalled solve far from the solution ([`IP_RECENTRES`]):
    /// for a pseudo-transient damped solve ([`super::SolveControls::lateral_damping_n_per_m`]).
    pub(crate) recentre_blockers: bool,
}

/// An iterate of the interior point.
pub(crate) struct IpIterate {
    /// Displacement increment of the linearization (DOF order, node bases).
    pub(crate) du: Vec<f64>,
    /// Hook-load change, N.
    pub(crate) dh: f64,
    /// Contact forces, N.
    pub(crate) r: Vec<f64>,
    /// Slacks of the linearized gaps, m.
    pub(crate) s: Vec<f64>,
}

/// The interior point's result: its last iterate and the iterations made.
pub(crate) struct IpSolution {
    /// The last iterate.
    pub(crate) iterate: IpIterate,
    /// Interior-point iterations (factorizations) made.
    pub(crate) iterations: usize,
    /// `R / s` per contact of the iterate the last factorization was made at, N/m (empty
    /// without one): the contact stiffness of the last matrix factored (`K + N diag(R/s) N^T`).
    pub(crate) factored_ratio: Vec<f64>,
}

/// Residuals of an iterate and the work vectors of one interior-point iteration.
struct Work {
    /// Dual residual `K du + N R + r0` (hook-load column included), DOF order.
    rd: Vec<f64>,
    /// Primal residual `N^T du + s + g` per contact, m.
    rp: Vec<f64>,
    /// Right-hand side, then the solved `du` direction.
    rhs: Vec<f64>,
    /// `K^-1 e_top` (the hook-load column solved).
    b_top: Vec<f64>,
    /// Complementarity target per contact.
    rc: Vec<f64>,
    /// Corrector slack and force directions.
    ds: Vec<f64>,
    dr: Vec<f64>,
    /// Affine (predictor) slack and force directions.
    ds_aff: Vec<f64>,
    dr_aff: Vec<f64>,
    /// The WOB equation's residual at the iterate, N.
    cb: f64,
    /// `kb . K^-1 e_top`.
    kbb: f64,
    /// Scratch of the matrix product.
    mul: Vec<f64>,
    /// The pairs that limited the stalled steps since the last step that was not: contact
    /// index and the pair's ratio `|dR / ds|` in that step, N/m.
    blockers: Vec<(usize, f64)>,
}

/// The active-set steps left to an interior-point solve ([`ACTIVE_SET_TRIES`],
/// [`ACTIVE_SET_MAX_TRIES`]).
struct ActiveSetTries {
    /// Tries left.
    left: usize,
    /// Tries made.
    made: usize,
    /// Pairs switched by the last try.
    last_switched: usize,
}

impl ActiveSetTries {
    /// [`ACTIVE_SET_TRIES`] tries, or none.
    fn new(try_active_set: bool) -> ActiveSetTries {
        ActiveSetTries {
            left: if try_active_set { ACTIVE_SET_TRIES } else { 0 },
            made: 0,
            last_switched: usize::MAX,
        }
    }

    /// Count a try that switched `switched` pairs; whether another is made: while tries are
    /// left, or, up to [`ACTIVE_SET_MAX_TRIES`], when this one switched fewer than the last.
    fn another_after(&mut self, switched: usize) -> bool {
        self.left -= 1;
        self.made += 1;
        if self.left == 0 && switched < self.last_switched && self.made < ACTIVE_SET_MAX_TRIES {
            self.left = 1;
        }
        self.last_switched = switched;
        self.left > 0
    }
}

/// Sizes of an iterate's residuals.
struct Residuals {
    /// Mean complementarity `R s`, N.m.
    mu: f64,
    /// Largest dual residual relative to the load scale.
    rd_n: f64,
    /// Largest primal residual relative to the clearance.
    rp_n: f64,
}

impl ContactSubproblem<'_> {
    /// Number of contacts.
    fn mt(&self) -> usize {
        self.cols.len()
    }

    /// The warm start of the contact forces, shifted `shift` off the boundary.
    fn start_r(&self, shift: f64) -> Vec<f64> {
        let mt = self.mt();
        (0..mt)
            .map(|j| self.lam_prev[j].max(0.0) + shift * self.scale / mt.max(1) as f64)
            .collect()
    }

    /// The warm start of the slacks, shifted `shift` off the boundary.
    fn start_s(&self, shift: f64) -> Vec<f64> {
        (0..self.mt())
            .map(|j| (-self.cols.gaps0[j]).max(1e-6 * self.clr[j]) + shift * self.clr[j])
            .collect()
    }

    /// The warm start: the step at the prescribed increments (the switching pins'), zero
    /// elsewhere, and the shifted multipliers and slacks.
    fn start(&self, shift: f64) -> IpIterate {
        let mut du = vec![0.0; self.model.dofs()];
        for &(d, v) in self.pin_move {
            du[d] = v;
        }
        IpIterate {
            du,
            dh: 0.0,
            r: self.start_r(shift),
            s: self.start_s(shift),
        }
    }

    /// Each contact's share of the load scale, N.
    fn per_contact(&self) -> f64 {
        self.scale / self.mt().max(1) as f64
    }

    /// The last step's contact set: a pair is in it when its force (per contact's share of
    /// the load scale) is the larger side of the complementarity pair, the open gap (per
    /// clearance) the other.
    fn initial_set(&self) -> Vec<bool> {
        let per_contact = self.per_contact();
        (0..self.mt())
            .map(|j| {
                self.lam_prev[j] / per_contact
                    > ((-self.cols.gaps0[j]).max(0.0) / self.clr[j]).max(ACTIVE_SET_MIN_FORCE)
            })
            .collect()
    }

    /// Start of the active-set step of the set `in_set`: pairs in the set on the boundary
    /// (slack [`ACTIVE_SET_EPS`] clearances: the linearized gap held closed), the others with
    /// zero force (their force held at zero).
    fn active_set_start(&self, in_set: &[bool], it: &mut IpIterate) {
        let per_contact = self.per_contact();
        for (j, &inside) in in_set.iter().enumerate() {
            if inside {
                // at least the contact's share of the load scale: the pair's compliance in
                // the step's matrix is its slack over this force, and it ends the step
                // `slack * dR / R` past the wall
                it.r[j] = self.lam_prev[j].max(per_contact);
                it.s[j] = ACTIVE_SET_EPS * self.clr[j];
            } else {
                it.r[j] = 0.0;
                it.s[j] = (-self.cols.gaps0[j]).max(self.clr[j]);
            }
        }
    }

    /// Motion of contact `j`'s node along its normal in the increment `u`, m.
    fn radial(&self, j: usize, u: &[f64]) -> f64 {
        (0..3).map(|k| self.cols.normals[j][k] * u[self.dofs6[j][k]]).sum()
    }

    /// Residuals of the iterate `it` (the `ip`-th) into `w` (`K du` vanishes before the first
    /// step when `du` starts at zero).
    fn residuals(&self, lin: &MatrixAndFactor, ip: usize, it: &IpIterate, w: &mut Work) -> Residuals {
        let (mt, eq_cols) = (self.mt(), &self.cols.eq_cols);
        w.rd.copy_from_slice(self.r0);
        if ip > 0 || !self.pin_move.is_empty() {
            lin.matrix_mul_add(self.base, &it.du, &mut w.rd, &mut w.mul);
        }
        for (j, col) in eq_cols.iter().enumerate() {
            for (k, e) in col.iter().enumerate() {
                w.rd[self.dofs6[j][k]] += it.r[j] * e;
            }
        }
        for &(d, v) in self.hook {
            w.rd[d] += v * it.dh;
        }
        for &d in self.constrained {
            w.rd[d] = 0.0;
        }
        for j in 0..mt {
            w.rp[j] = self.radial(j, &it.du) + it.s[j] + self.cols.gaps0[j];
        }
        w.cb = if self.bordered {
            self.c + self.kb.iter().map(|&(d, v)| v * it.du[d]).sum::<f64>()
        } else {
            0.0
        };
        Residuals {
            mu: (0..mt).map(|j| it.r[j] * it.s[j]).sum::<f64>() / mt.max(1) as f64,
            rd_n: w.rd.iter().fold(0.0f64, |a, v| a.max(v.abs())) / self.scale,
            rp_n: (0..mt).map(|j| w.rp[j].abs() / self.clr[j]).fold(0.0, f64::max),
        }
    }

    /// Whether the residuals `res` (and the WOB equation's `cb`, N) are within the tolerance.
    fn solved(&self, res: &Residuals, cb: f64) -> bool {
        let (eta, scale) = (self.eta, self.scale);
        res.rd_n < eta && res.rp_n < 10.0 * eta && res.mu < 1e-2 * eta * scale * 1e-3 && cb.abs() < eta * scale
    }

    /// Factor the reduced matrix `K + N diag(R/s) N^T` of the iterate `it`. Row form: row `i`
    /// (DOF `k` of a contact node) gets `D e_k g^T` on the node's translation columns.
    fn factor(&self, lin: &mut MatrixAndFactor, it: &IpIterate) -> Result<(), SolveError> {
        let (cols, nn) = (self.cols, self.model.nodes());
        let (r_f, s_v) = (&it.r, &it.s);
        let add_row = |i: usize, row: &mut [f64]| {
            let node = nn - 1 - i / 6;
            for j in cols.of_node(self.contact_at, node) {
                let k = i % 6;
                let e = r_f[j] / s_v[j] * cols.eq_cols[j][k];
                // the node's first DOF i - k sits at offset HALF_BANDWIDTH - k
                let off = HALF_BANDWIDTH - k;
                for cc in 0..3 {
                    row[off + cc] += e * cols.normals[j][cc];
                }
            }
        };
        let add = |sink: &mut dyn StiffnessSink| {
            for j in 0..self.mt() {
                let dj = r_f[j] / s_v[j];
                let nv = cols.normals[j];
                // D e_j g_j^T: rows = equilibrium column (6), columns = gap normal (3)
                let mut blk = [0.0; 36];
                for r in 0..6 {
                    for cc in 0..3 {
                        blk[r * 6 + cc] = dj * cols.eq_cols[j][r] * nv[cc];
                    }
                }
                sink.add_block(&self.dofs6[j], &blk, 6);
            }
        };
        lin.factor_modified(self.base, self.constrained, self.constraint_scale, add_row, add)
            .map_err(|e| singular(self.model, e))
    }

    /// Right-hand side of one Newton solve of the (du, R, s) system for the complementarity
    /// target `w.rc` (of `R ds + s dR`), into `w.rhs`: `-rd - E S^-1 (rc + R rp)`.
    fn build_rhs(&self, it: &IpIterate, w: &mut Work) {
        for (x, v) in w.rhs.iter_mut().zip(&w.rd) {
            *x = -v;
        }
        for j in 0..self.mt() {
            let wj = (w.rc[j] + it.r[j] * w.rp[j]) / it.s[j];
            for k in 0..6 {
                w.rhs[self.dofs6[j][k]] -= wj * self.cols.eq_cols[j][k];
            }
        }
        for &d in self.constrained {
            w.rhs[d] = 0.0;
        }
    }

    /// Solve the predictor's right-hand side together with the hook-load column (`K^-1 e_top`)
    /// (one pass over the factor for both); sets `w.kbb`.
    fn solve_predictor(&self, lin: &MatrixAndFactor, w: &mut Work) {
        w.kbb = if self.bordered {
            w.b_top.fill(0.0);
            for &(d, v) in self.hook {
                w.b_top[d] = v;
            }
            lin.solve2(&mut w.b_top, &mut w.rhs);
            self.kb.iter().map(|&(d, v)| v * w.b_top[d]).sum::<f64>()
        } else {
            lin.solve(&mut w.rhs);
            0.0
        };
    }

    /// With the solved `w.rhs`: the hook-load step (returned, N), the `du` direction (in
    /// `w.rhs`), and the slack and force directions (the affine ones when `affine`).
    fn finish(&self, it: &IpIterate, w: &mut Work, affine: bool) -> f64 {
        let Work {
            rhs,
            b_top,
            rc,
            rp,
            ds,
            dr,
            ds_aff,
            dr_aff,
            cb,
            kbb,
            ..
        } = w;
        let (ds, dr) = if affine { (ds_aff, dr_aff) } else { (ds, dr) };
        let dh = if self.bordered {
            let kba: f64 = self.kb.iter().map(|&(d, v)| v * rhs[d]).sum();
            let dh = if kbb.abs() > 1e-30 { (*cb + kba) / *kbb } else { 0.0 };
            for (x, bt) in rhs.iter_mut().zip(b_top.iter()) {
                *x -= dh * bt;
            }
            dh
        } else {
            0.0
        };
        for j in 0..self.mt() {
            ds[j] = -rp[j] - self.radial(j, rhs);
            dr[j] = (rc[j] - it.r[j] * ds[j]) / it.s[j];
        }
        dh
    }

    /// The active-set step: the affine direction is taken in full when no pair leaves its set
    /// `in_set` (the equality-constrained Newton step of that set; returns 0); otherwise
    /// the pairs that left it switch sides (returns how many switched).
    fn try_active_set(&self, in_set: &mut [bool], it: &mut IpIterate, w: &Work, dh_aff: f64) -> usize {
        let eps_r = ACTIVE_SET_EPS * self.per_contact();
        let mut switched = 0usize;
        for (j, inside) in in_set.iter_mut().enumerate() {
            if *inside && it.r[j] + w.dr_aff[j] < -eps_r {
                *inside = false;
                switched += 1;
            } else if !*inside && it.s[j] + w.ds_aff[j] < -ACTIVE_SET_EPS * self.clr[j] {
                *inside = true;
                switched += 1;
            }
        }
        tracing::trace!(switched, "active-set step");
        if switched > 0 {
            return switched;
        }
        for (x, d) in it.du.iter_mut().zip(&w.rhs) {
            *x += d;
        }
        it.dh += dh_aff;
        for j in 0..self.mt() {
            it.r[j] = (it.r[j] + w.dr_aff[j]).max(0.0);
            it.s[j] = (it.s[j] + w.ds_aff[j]).max(0.0);
        }
        0
    }

    /// Mehrotra's corrector after the affine direction in `w`: the centering
    /// `sigma = (mu_aff / mu)^3` and the second-order term of the complementarity, solved and
    /// taken to 0.995 of the boundary. Returns the step length.
    fn corrector(&self, lin: &MatrixAndFactor, it: &mut IpIterate, w: &mut Work, res: &Residuals) -> f64 {
        let mt = self.mt();
        let mu = res.mu;
        let a_aff = step_to_boundary(&it.r, &w.dr_aff, &it.s, &w.ds_aff, 1.0);
        let mu_aff = (0..mt)
            .map(|j| (it.r[j] + a_aff * w.dr_aff[j]) * (it.s[j] + a_aff * w.ds_aff[j]))
            .sum::<f64>()
            / mt.max(1) as f64;
        let sigma = if mu > 0.0 {
            (mu_aff / mu).clamp(0.0, 1.0).powi(3)
        } else {
            0.0
        };
        for j in 0..mt {
            w.rc[j] = -it.r[j] * it.s[j] + sigma * mu - w.dr_aff[j] * w.ds_aff[j];
        }
        self.build_rhs(it, w);
        lin.solve(&mut w.rhs);
        let ddh = self.finish(it, w, false);
        let alpha = step_to_boundary(&it.r, &w.dr, &it.s, &w.ds, 0.995);
        if alpha < STALLED_STEP {
            w.blockers.extend(blocking_pair(&it.r, &w.dr, &it.s, &w.ds));
        } else {
            w.blockers.clear();
        }
        let (rd_n, rp_n) = (res.rd_n, res.rp_n);
        tracing::trace!(rd_n, rp_n, mu_rel = mu / (self.scale * 1e-3), a_aff, sigma, alpha, "ip");
        for (x, d) in it.du.iter_mut().zip(&w.rhs) {
            *x += alpha * d;
        }
        it.dh += alpha * ddh;
        for j in 0..mt {
            it.r[j] += alpha * w.dr[j];
            it.s[j] += alpha * w.ds[j];
        }
        alpha
    }

    /// Solve the subproblem from the outer residual `rn`, first by the active-set step when
    /// `try_active_set` ([`ACTIVE_SET_TRIES`] with the pairs that left the set switched), the
    /// interior point taking over when the set does not hold. Counts the factorizations in
    /// `stats`.
    pub(crate) fn solve(
        &self,
        lin: &mut MatrixAndFactor,
        stats: &mut SolveStats,
        rn: f64,
        try_active_set: bool,
    ) -> Result<IpSolution, SolveError> {
        let (n, mt) = (self.model.dofs(), self.mt());
        // warm start from the previous multipliers, pushed off the boundary by a shift that
        // grows with the outer residual (far from the solution the old contact set is a poor
        // guess, and pairs pinned at the boundary would block the interior-point steps)
        let mut shift = if self.carried_start {
            CARRIED_START_SHIFT_FACTOR * (IP_START_SHIFT * rn).clamp(1e-6, 1e-1)
        } else {
            (IP_START_SHIFT * rn).clamp(1e-6, 1e-1)
        };
        let mut it = self.start(shift);
        let mut in_set = self.initial_set();
        let mut tries = ActiveSetTries::new(try_active_set);
        if tries.left > 0 {
            self.active_set_start(&in_set, &mut it);
        }
        let mut w = Work {
            rd: vec![0.0; n],
            rp: vec![0.0; mt],
            rhs: vec![0.0; n],
            b_top: vec![0.0; n],
            rc: vec![0.0; mt],
            ds: vec![0.0; mt],
            dr: vec![0.0; mt],
            ds_aff: vec![0.0; mt],
            dr_aff: vec![0.0; mt],
            cb: 0.0,
            kbb: 0.0,
            mul: Vec::new(),
            blockers: Vec::new(),
        };
        let (mut iterations, mut stalled, mut restarts, mut recentres) = (0usize, 0usize, 0usize, 0usize);
        let mut factored_ratio = Vec::new();
        let (mut mu_min, mut cycles) = (f64::INFINITY, 0usize);
        for ip in 0..MAX_IP_ITERATIONS {
            let res = self.residuals(lin, ip, &it, &mut w);
            if self.solved(&res, w.cb) {
                break;
            }
            iterations += 1;
            self.factor(lin, &it)?;
            stats.factorizations += 1;
            factored_ratio.clear();
            factored_ratio.extend(it.r.iter().zip(&it.s).map(|(r, s)| r / s));
            // Mehrotra predictor: the affine-scaling direction (no centering)
            for j in 0..mt {
                w.rc[j] = -it.r[j] * it.s[j];
            }
            self.build_rhs(&it, &mut w);
            self.solve_predictor(lin, &mut w);
            let dh_aff = self.finish(&it, &mut w, true);
            if tries.left > 0 {
                let switched = self.try_active_set(&mut in_set, &mut it, &w, dh_aff);
                if switched == 0 {
                    break;
                }
                if tries.another_after(switched) {
                    self.active_set_start(&in_set, &mut it);
                } else {
                    it.r = self.start_r(shift);
                    it.s = self.start_s(shift);
                }
                continue;
            }
            let alpha = self.corrector(lin, &mut it, &mut w, &res);
            let feasible = res.rd_n < self.eta && res.rp_n < 10.0 * self.eta;
            let cycling = feasible && res.mu > IP_CYCLE_MU_RATIO * mu_min;
            mu_min = mu_min.min(res.mu);
            cycles = if cycling { cycles + 1 } else { 0 };
            stalled = if alpha < STALLED_STEP || cycles >= IP_CYCLE_STEPS {
                stalled + 1
            } else {
                0
            };
            // a stalled interior point (friction makes the contact problem non-monotone: its
            // steps short, or its iterates cycling at a constant complementarity) far from the
            // solution: the pairs that blocked its short steps recentred, else the step found
            // so far taken
            if stalled >= IP_STALL_STEPS && self.eta > 1e-8 {
                if self.recentre_blockers && recentres < IP_RECENTRES && !w.blockers.is_empty() {
                    recentres += 1;
                    recentre(&mut it, &w.blockers);
                    w.blockers.clear();
                    stalled = 0;
                    (mu_min, cycles) = (f64::INFINITY, 0);
                    tracing::debug!(recentres, "interior point: blocking pairs recentred");
                    continue;
                }
                break;
            }
            // stalled near the solution (where the exact tolerance is asked): the warm start sat
            // too close to the boundary for a pair that has to change (a contact switching while
            // its force and gap are both near zero), and the remaining iterations would creep
            // at steps of 1e-3; start again from a more central point
            if stalled >= IP_STALL_STEPS && restarts < IP_RESTARTS {
                restarts += 1;
                shift = (shift * IP_RESTART_SHIFT_FACTOR).min(1e-1);
                it = self.start(shift);
                stalled = 0;
                (mu_min, cycles) = (f64::INFINITY, 0);
                tracing::debug!(restarts, shift, "interior point restarted");
            }
        }
        Ok(IpSolution {
            iterate: it,
            iterations,
            factored_ratio,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Two tries whatever they switch; a third only after a try that switched fewer pairs than
    /// the one before; never a fourth.
    #[test]
    fn active_set_tries_go_on_only_while_the_set_settles() {
        let tries = |switched: &[usize]| {
            let mut t = ActiveSetTries::new(true);
            switched.iter().take_while(|&&s| t.another_after(s)).count() + 1
        };
        assert_eq!(tries(&[4, 5, 1, 0]), 2);
        assert_eq!(tries(&[6, 6, 1, 0]), 2);
        assert_eq!(tries(&[2, 1, 1, 0]), 3);
        assert_eq!(tries(&[3, 2, 1, 0]), 3);
        assert_eq!(ActiveSetTries::new(false).left, 0);
    }

    /// The pair that limits the step is found by its own ratio to the boundary (here the second
    /// pair's force, 0.1 / 10 = 0.01, before the first pair's 1 / 0.5 = 2), with its `|dR/ds|`.
    #[test]
    fn blocking_pair_is_the_one_at_the_boundary_first() {
        let (r, dr) = ([1.0, 0.1], [-0.5, -10.0]);
        let (s, ds) = ([1.0, 1e-6], [0.0, 1e-3]);
        assert_eq!(blocking_pair(&r, &dr, &s, &ds), Some((1, 1e4)));
        // nothing moves toward the boundary: no pair limits the step
        assert_eq!(blocking_pair(&r, &[1.0, 1.0], &s, &[0.0, 0.0]), None);
    }

    /// A recentred pair lies on the central path at the iterate's mean complementarity with its
    /// own ratio (`R s = mu`, `R / s = k`, to rounding), its values never lowered, and the other
    /// pairs untouched.
    #[test]
    fn recentred_pair_lies_on_the_central_path() {
        let mut it = IpIterate {
            du: Vec::new(),
            dh: 0.0,
            r: vec![2.0, 1e-3, 4.0],
            s: vec![0.5, 1e-9, 0.25],
        };
        let mu = (1.0 + 1e-12 + 1.0) / 3.0;
        recentre(&mut it, &[(1, 4.0)]);
        assert!((it.r[1] * it.s[1] - mu).abs() < 1e-12 * mu);
        assert!((it.r[1] / it.s[1] - 4.0).abs() < 1e-12);
        assert_eq!((it.r[0], it.s[0], it.r[2], it.s[2]), (2.0, 0.5, 4.0, 0.25));
        // a force already above its central value is kept
        it.r[1] = 10.0;
        recentre(&mut it, &[(1, 4.0)]);
        assert_eq!(it.r[1], 10.0);
    }
}
