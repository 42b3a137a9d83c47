//! The soft string with the helix's drag: Mitchell's helical contact force added to the wall
//! force wherever the soft string's compression exceeds the helical onset.
//!
//! A soft string lies on the hole axis and cannot buckle, so beyond the helical onset it misses
//! the wall force the helix adds, `w_c = r F^2 / (4 EI)` (Mitchell 1986, 1988; `r` the radial
//! body clearance, `F` the effective compression, `EI` the pipe's bending stiffness). Added to
//! the element's wall force (its lateral load from weight and curvature, Johancsik) and
//! dragging with the same friction, it makes the axial balance of a sliding string in a
//! vertical section `dF/ds = -w + f r F^2 / (4 EI)` (compression `F`, `s` upward): compression
//! beyond `sqrt(4 EI w / (f r))` grows upward instead of falling, the classic helical lock-up
//! (Mitchell 1986; docs/theory.md 7.7). Adding the helix's force to the lateral load's is the
//! common torque-and-drag practice **\[uncertain: in an inclined hole the two loads are not
//! parallel and their magnitudes do not add exactly; the stiff string is the reference]**.
//!
//! Used beside the whole string: in the soft-string comparison of `solve`, in the hints of a
//! whole-string solve that found no equilibrium ([`helical_lock_up`], the largest WOB by
//! [`lock_up_wob_n`]), and to skip the re-solve from the buckled shape where the helix locks the
//! string up (`models::buckled_start`).

use crate::case::{Case, Mode};
use crate::models::buckling::{mitchell_wall_force, onset_at, soft_marks, support_span_m, BuckleState};
use crate::models::softstring::{from_case_with_extra_contact, segment_length_m, SoftStringResult};

/// Compression above which the added helical force is held constant, N: keeps a string
/// locked up far beyond its lock-up finite (the hook load then falls steeply, not to infinity).
pub const COMPRESSION_CAP_N: f64 = 1e8;

/// Hook load below which the soft string with the helix's drag has diverged, N: its compression
/// grew without bound up the helix (Mitchell's drag grows with the square of the compression,
/// and the compression of the closed form, a `coth`, diverges over a finite length:
/// tests/verification/helical_drag.rs), the added force was held at [`COMPRESSION_CAP_N`], and
/// the hook load is a flag, not a load (-10,000 kN: far beyond what any drill string can be
/// pushed with).
pub const DIVERGED_HOOK_LOAD_N: f64 = -1e7;

/// Whether the hook load `hook_load_n` (N) of a soft string with the helix's drag says its
/// compression diverged up the helix ([`DIVERGED_HOOK_LOAD_N`]).
pub fn diverged(hook_load_n: f64) -> bool {
    hook_load_n < DIVERGED_HOOK_LOAD_N
}

/// Mitchell's helical wall force per length (N/m) of `case`'s string at `md_m` (`s_m` from the
/// bit face, m) under the effective compression `compression_n` (N): zero below the helical
/// onset ([`onset_at`]) or where the pipe cannot buckle.
pub fn helical_contact_n_per_m(case: &Case, md_m: f64, s_m: f64, compression_n: f64) -> f64 {
    if compression_n <= 0.0 {
        return 0.0;
    }
    let string = &case.string;
    let c = string.component_at(s_m.max(0.0));
    let hole_d = case.well.hole.diameter_at(md_m);
    let span = support_span_m(string, s_m);
    let Some((_, helical)) = onset_at(c, &case.well.path, md_m, hole_d, case.mud.density_kg_m3, span) else {
        return 0.0;
    };
    if compression_n <= helical {
        return 0.0;
    }
    mitchell_wall_force(c, hole_d, compression_n.min(COMPRESSION_CAP_N))
}

/// The soft string of `case` ([`crate::models::softstring::from_case`], the case's segment
/// length) with Mitchell's helical contact force where it is helically buckled.
pub fn helical_soft_string(case: &Case) -> SoftStringResult {
    helical_soft_string_with(case, segment_length_m(&case.solver))
}

/// [`helical_soft_string`] with elements of at most `max_element_m` (m).
pub fn helical_soft_string_with(case: &Case, max_element_m: f64) -> SoftStringResult {
    let extra = |md: f64, s: f64, compression: f64| helical_contact_n_per_m(case, md, s, compression);
    from_case_with_extra_contact(case, max_element_m, &extra)
}

/// Bisection steps of [`lock_up_wob_n`]: the WOB to 1e-6 of the case's.
const BISECTIONS: usize = 20;

/// The largest WOB (N) at which [`helical_soft_string`] keeps a non-negative hook load, when it
/// is below `case`'s WOB (None when the helical soft string delivers the case's WOB, or the
/// string is locked up even at zero WOB): bisected on the WOB to 1e-6 of the case's.
pub fn lock_up_wob_n(case: &Case) -> Option<f64> {
    lock_up_wob_from(case, helical_hook_load_at(case, case.operation.wob_n))
}

/// The hook load (N) of [`helical_soft_string`] of `case` at the WOB `wob_n` (N), the hook-load
/// input dropped.
pub fn helical_hook_load_at(case: &Case, wob_n: f64) -> f64 {
    let mut c = case.clone();
    c.operation.wob_n = wob_n;
    c.operation.hook_load_n = None;
    helical_soft_string(&c).hook_load_n
}

/// [`lock_up_wob_n`] with the hook load at the case's WOB, `hook_at_wob_n` (N), already known.
fn lock_up_wob_from(case: &Case, hook_at_wob_n: f64) -> Option<f64> {
    let hook_at = |wob: f64| helical_hook_load_at(case, wob);
    let target = case.operation.wob_n;
    if target.is_nan() || target <= 0.0 || hook_at_wob_n >= 0.0 || hook_at(0.0) < 0.0 {
        return None;
    }
    let (mut lo, mut hi) = (0.0, target);
    for _ in 0..BISECTIONS {
        let mid = 0.5 * (lo + hi);
        if hook_at(mid) >= 0.0 {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    Some(lo)
}

/// The plain soft string's hook load of `case` at its WOB (the hook-load input dropped), N.
fn plain_hook_load_n(case: &Case) -> f64 {
    let mut c = case.clone();
    c.operation.hook_load_n = None;
    crate::models::softstring::from_case(&c, segment_length_m(&c.solver)).hook_load_n
}

/// A helical lock-up: the soft string with the helix's drag locked up at the WOB asked for
/// while the plain soft string is not.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HelicalLockUp {
    /// The hook load of the soft string with the helix's drag at the WOB asked for, N
    /// (negative).
    pub hook_load_n: f64,
    /// The WOB asked for, N.
    pub wob_n: f64,
    /// The largest WOB with a non-negative hook load of that soft string, N (0 when even a zero
    /// WOB needs the surface to push).
    pub max_wob_n: f64,
    /// Where that soft string is helically buckled at its largest WOB: MD of the highest and
    /// the lowest helical point, m (None without a helix there).
    pub helical_md_m: Option<(f64, f64)>,
}

/// The helical lock-up of `case` at its WOB ([`HelicalLockUp`]); None when the soft string with
/// the helix's drag delivers the WOB, when the plain soft string is locked up too (the plain
/// lock-up, `models::checks`), off bottom, or with a hook-load input.
pub fn helical_lock_up(case: &Case) -> Option<HelicalLockUp> {
    let op = &case.operation;
    if !op.mode.on_bottom() || op.hook_load_n.is_some() || plain_hook_load_n(case) < 0.0 {
        return None;
    }
    let hook = helical_hook_load_at(case, op.wob_n);
    if hook >= 0.0 {
        return None;
    }
    let max_wob_n = lock_up_wob_from(case, hook).unwrap_or(0.0);
    Some(HelicalLockUp {
        hook_load_n: hook,
        wob_n: op.wob_n,
        max_wob_n,
        helical_md_m: helical_interval_md_m(case, max_wob_n),
    })
}

/// The helical lock-up of `case` running in (`trip_in`, no WOB): the plain soft string can be
/// run in to the bit depth (hook load not below zero) and the soft string with the helix's drag
/// cannot. `wob_n` and `max_wob_n` are 0, `helical_md_m` where that soft string is helically
/// buckled. None otherwise, or with a hook-load input.
pub fn helical_running_in_lock_up(case: &Case) -> Option<HelicalLockUp> {
    let op = &case.operation;
    if op.mode != Mode::TripIn || op.hook_load_n.is_some() || plain_hook_load_n(case) < 0.0 {
        return None;
    }
    let hook = helical_hook_load_at(case, 0.0);
    (hook < 0.0).then(|| HelicalLockUp {
        hook_load_n: hook,
        wob_n: 0.0,
        max_wob_n: 0.0,
        helical_md_m: helical_interval_md_m(case, 0.0),
    })
}

/// MD of the highest and the lowest point (m) where [`helical_soft_string`] of `case` at the
/// WOB `wob_n` (N) is beyond the helical onset; None where it is nowhere.
pub fn helical_interval_md_m(case: &Case, wob_n: f64) -> Option<(f64, f64)> {
    let mut c = case.clone();
    c.operation.wob_n = wob_n;
    let soft = helical_soft_string(&c);
    let helical = soft_marks(&c, &soft, 0)
        .into_iter()
        .filter(|m| m.state == BuckleState::Helical)
        .map(|m| m.md_m);
    helical.fold(None, |acc, md| match acc {
        None => Some((md, md)),
        Some((top, bottom)) => Some((f64::min(top, md), f64::max(bottom, md))),
    })
}
