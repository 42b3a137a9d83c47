//! The lock-up depth: how deep the string can be drilled (or slid) in the case's operation
//! before the surface would have to push, by the soft string that finds the lock-up ([`Drag`]):
//! the plain soft string where it is locked up itself, else the soft string with the helix's
//! drag ([`crate::models::helical_drag`]), so that the depths agree with the lock-up's largest
//! WOB.
//!
//! The string is refitted to each bit depth (the pipe shortened at the surface, as `loads` does)
//! and its hook load computed at a fixed WOB; the lock-up depth is the bit depth from which that
//! hook load stays negative down to the case's bit depth, found by scanning up from there
//! ([`scan_step_m`]: steps of 10-200 m, half the distance to the hook load's zero that its local
//! slope predicts) and bisecting to [`DEPTH_TOLERANCE_M`]: how far the hole could have
//! been drilled in this operation. The scan stops at the first depth that delivers the WOB, so a
//! locked window higher up the hole (possible in an S-shaped well) is not reported.

use crate::case::{Case, Mode};
use crate::models::helical_drag::helical_hook_load_at;
use crate::models::softstring;

/// The soft string whose hook load decides the lock-up depth.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Drag {
    /// The plain soft string ([`softstring::from_case`]).
    Plain,
    /// The soft string with the helix's drag ([`crate::models::helical_drag::helical_soft_string`]).
    WithHelix,
}

impl Drag {
    /// The model of a lock-up of `case` at the WOB `wob_n` (N): the plain soft string where it is
    /// locked up itself (its largest WOB is the lock-up's, `models::checks::lock_up`), else the
    /// one with the helix's drag.
    pub fn of(case: &Case, wob_n: f64) -> Drag {
        if hook_load_at_wob_n(case, wob_n, Drag::Plain) < 0.0 {
            Drag::Plain
        } else {
            Drag::WithHelix
        }
    }

    /// How the outputs name the model.
    pub fn name(self) -> &'static str {
        match self {
            Drag::Plain => "soft string",
            Drag::WithHelix => "soft string with the helix's drag",
        }
    }
}

/// The hook load (N) of `case` by the model `drag` at the WOB `wob_n` (N), the case's hook-load
/// input dropped.
pub fn hook_load_at_wob_n(case: &Case, wob_n: f64, drag: Drag) -> f64 {
    match drag {
        Drag::Plain => {
            let mut c = case.clone();
            c.operation.wob_n = wob_n;
            c.operation.hook_load_n = None;
            softstring::from_case(&c, softstring::segment_length_m(&c.solver)).hook_load_n
        }
        Drag::WithHelix => helical_hook_load_at(case, wob_n),
    }
}

/// Shortest step of the scan up the hole, m.
pub const SCAN_STEP_M: f64 = 10.0;

/// Longest step of the scan up the hole, m.
pub const MAX_SCAN_STEP_M: f64 = 200.0;

/// The next step (m) of the scan up the hole from a depth with the (negative) hook load
/// `hook_n` (N), the hook load rising upward by `slope_n_per_m` (N/m, from the last step): half
/// the distance to the zero the slope predicts, within [`SCAN_STEP_M`] and [`MAX_SCAN_STEP_M`];
/// the shortest where the hook load does not rise upward.
pub fn scan_step_m(hook_n: f64, slope_n_per_m: f64) -> f64 {
    if slope_n_per_m.is_nan() || slope_n_per_m <= 0.0 {
        return SCAN_STEP_M;
    }
    (0.5 * -hook_n / slope_n_per_m).clamp(SCAN_STEP_M, MAX_SCAN_STEP_M)
}

/// The lock-up depth is bisected to this, m.
pub const DEPTH_TOLERANCE_M: f64 = 0.1;

/// The hook load (N) by the model `drag` with `case`'s string refitted to the bit depth
/// `bit_md_m` (m) and the WOB `wob_n` (N); the case's hook-load input dropped.
pub fn hook_load_at_depth_n(case: &Case, bit_md_m: f64, wob_n: f64, drag: Drag) -> f64 {
    hook_load_at_wob_n(&case.at_bit_depth(bit_md_m), wob_n, drag)
}

/// The bit depth (MD, m) from which the string of `case`, in its operation at the WOB `wob_n`
/// (N), has a negative hook load by the model `drag` all the way down to the case's bit depth,
/// to within [`DEPTH_TOLERANCE_M`]: scanned up from the case's bit depth in steps of
/// [`scan_step_m`] to the first depth with a non-negative hook load, then bisected.
/// None when the hook load at the case's bit depth is not negative (or the case is off bottom
/// other than running in at zero WOB, or gives the hook load instead of the WOB); the top of the
/// survey when no bit depth of the surveyed hole has a non-negative hook load. Running in
/// (`trip_in`, zero WOB), it is the depth the string cannot be run in beyond.
pub fn lock_up_depth_m(case: &Case, wob_n: f64, drag: Drag) -> Option<f64> {
    let op = &case.operation;
    let runs_down = op.mode.on_bottom() || (op.mode == Mode::TripIn && wob_n == 0.0);
    if !runs_down || op.hook_load_n.is_some() || !wob_n.is_finite() {
        return None;
    }
    let hook = |md: f64| hook_load_at_depth_n(case, md, wob_n, drag);
    let locked = |md: f64| hook(md) < 0.0;
    let top = survey_top_md_m(case);
    let mut below = op.bit_md_m;
    let mut hook_below = hook(below);
    if hook_below.is_nan() || hook_below >= 0.0 {
        return None;
    }
    let mut step = SCAN_STEP_M;
    loop {
        let above = below - step;
        if above <= top {
            return Some(top);
        }
        let hook_above = hook(above);
        if hook_above.is_nan() || hook_above >= 0.0 {
            return Some(bisect(above, below, &locked));
        }
        step = scan_step_m(hook_above, (hook_above - hook_below) / step);
        (below, hook_below) = (above, hook_above);
    }
}

/// The shallowest bit depth scanned: the top of the survey (not above the surface), m MD.
fn survey_top_md_m(case: &Case) -> f64 {
    case.well.path.md_start().max(0.0)
}

/// The first locked depth between `free` (not locked) and `locked_md` (locked), m: bisected to
/// [`DEPTH_TOLERANCE_M`], the locked end returned.
fn bisect(mut free: f64, mut locked_md: f64, locked: &dyn Fn(f64) -> bool) -> f64 {
    while locked_md - free > DEPTH_TOLERANCE_M {
        let mid = 0.5 * (free + locked_md);
        if locked(mid) {
            locked_md = mid;
        } else {
            free = mid;
        }
    }
    locked_md
}

/// The lock-up depths of a string locked up on bottom.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LockUpDepths {
    /// Bit depth (MD, m) from which the WOB asked for can no longer be delivered
    /// ([`lock_up_depth_m`] at that WOB).
    pub at_wob_md_m: Option<f64>,
    /// Bit depth (MD, m) from which the string cannot be put on bottom even at zero WOB (None
    /// when it reaches the case's bit depth at zero WOB).
    pub at_zero_wob_md_m: Option<f64>,
    /// The top of the survey, m MD: a lock-up depth there means no bit depth of the surveyed
    /// hole delivers that WOB.
    pub top_md_m: f64,
    /// The model of both depths.
    pub drag: Drag,
}

impl LockUpDepths {
    /// Whether no bit depth of the surveyed hole delivers the WOB (the lock-up depth at the top
    /// of the survey).
    pub fn locked_everywhere(&self) -> bool {
        self.at_wob_md_m.is_some_and(|d| d <= self.top_md_m + DEPTH_TOLERANCE_M)
    }

    /// "the string locks up once the bit is deeper than X MD" (`depth` formats X, an MD in m), or
    /// that no bit depth of the surveyed hole delivers the WOB; None without a lock-up at it.
    pub fn at_wob_clause(&self, depth: impl Fn(f64) -> String) -> Option<String> {
        let at_wob = self.at_wob_md_m?;
        Some(if self.locked_everywhere() {
            "no bit depth of the surveyed hole has a hook load above zero".to_string()
        } else {
            format!("the string locks up once the bit is deeper than {} MD", depth(at_wob))
        })
    }

    /// For a string running in (zero WOB): "it cannot be run in deeper than X MD" (`depth`
    /// formats X, an MD in m), or at no bit depth of the surveyed hole; None without a lock-up.
    pub fn running_in_clause(&self, depth: impl Fn(f64) -> String) -> Option<String> {
        let at_wob = self.at_wob_md_m?;
        Some(if self.locked_everywhere() {
            "it cannot be run in at any bit depth of the surveyed hole".to_string()
        } else {
            format!("it cannot be run in deeper than {} MD", depth(at_wob))
        })
    }

    /// The sentence naming these depths at the WOB `wob_n` (N), depths in m MD: "lock-up depth
    /// (by the ...): at W kN WOB the string locks up once the bit is deeper than X m MD, ...";
    /// None without a lock-up at that WOB.
    pub fn sentence(&self, wob_n: f64) -> Option<String> {
        let first = format!("at {:.0} kN WOB {}", wob_n / 1e3, self.at_wob_clause(metres)?);
        let zero = match self.at_zero_wob_md_m {
            Some(z) => format!(
                "and even at zero WOB from {} MD: it cannot be put on bottom there at any WOB",
                metres(z)
            ),
            None => "while at zero WOB it reaches this depth".to_string(),
        };
        Some(format!(
            "lock-up depth (by the {}, the string refitted to each bit depth of the surveyed hole): {first}, {zero}",
            self.drag.name()
        ))
    }
}

/// An MD in m as the warnings print it: "1166 m".
pub fn metres(md_m: f64) -> String {
    format!("{md_m:.0} m")
}

/// The lock-up depths of `case` at the WOB `wob_n` (N) and at zero WOB by the model `drag` (one
/// search when the WOB is zero).
pub fn lock_up_depths(case: &Case, wob_n: f64, drag: Drag) -> LockUpDepths {
    let at_wob_md_m = lock_up_depth_m(case, wob_n, drag);
    LockUpDepths {
        at_wob_md_m,
        at_zero_wob_md_m: if wob_n == 0.0 {
            at_wob_md_m
        } else {
            lock_up_depth_m(case, 0.0, drag)
        },
        top_md_m: survey_top_md_m(case),
        drag,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The scan's step: half the distance to the zero the slope predicts (-50 kN rising by
    /// 500 N/m: 50 m), the shortest where the hook load does not rise upward, and within bounds.
    #[test]
    fn the_scan_step_is_half_the_predicted_distance_within_bounds() {
        assert_eq!(scan_step_m(-50e3, 500.0), 50.0);
        assert_eq!(scan_step_m(-50e3, 0.0), SCAN_STEP_M);
        assert_eq!(scan_step_m(-50e3, -10.0), SCAN_STEP_M);
        assert_eq!(scan_step_m(-50e3, f64::NAN), SCAN_STEP_M);
        assert_eq!(scan_step_m(-1e9, 1.0), MAX_SCAN_STEP_M);
        assert_eq!(scan_step_m(-1.0, 1e6), SCAN_STEP_M);
    }
}
