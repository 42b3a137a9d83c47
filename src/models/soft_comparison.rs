//! The soft string beside a stiff solve (issue 16's "whole vs soft side by side"): the same
//! case at the WOB the stiff solve ended at, solved by the soft string, with its hook load,
//! surface torque, helically buckled length and Mitchell's helical wall force. The difference
//! of the hook loads is what the stiff string's bending and (where it buckles into a helix)
//! the helix's wall contact add to the drag (docs/theory.md 7.4). Beside it, the soft string
//! with the helix's drag ([`crate::models::helical_drag`]), the torque-and-drag practice for
//! buckled pipe.

use super::buckling::{helical_wall_force_n, soft_marks, summarize};
use super::helical_drag::helical_soft_string;
use super::softstring;
use crate::case::Case;

/// The soft string of a case at a stiff solve's WOB, beside that solve's surface values.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SoftComparison {
    /// The WOB both are at, N.
    pub wob_n: f64,
    /// Soft-string hook load, N.
    pub hook_load_n: f64,
    /// Soft-string surface torque, N.m.
    pub surface_torque_nm: f64,
    /// Helically buckled length along the soft string, m.
    pub helical_length_m: f64,
    /// Mitchell's helical contact force summed over the soft string's helical intervals, N
    /// ([`helical_wall_force_n`]): the wall force a soft-string user adds for the helix.
    pub helical_wall_force_n: f64,
    /// Hook load of the soft string with the helix's drag ([`helical_soft_string`]: Mitchell's
    /// helical contact force added where it is helically buckled), N.
    pub helical_drag_hook_load_n: f64,
    /// Surface torque of the soft string with the helix's drag, N.m.
    pub helical_drag_surface_torque_nm: f64,
    /// The stiff solve's hook load, N.
    pub stiff_hook_load_n: f64,
    /// The stiff solve's surface torque, N.m.
    pub stiff_surface_torque_nm: f64,
}

impl SoftComparison {
    /// Stiff minus soft hook load, N (negative: the stiff string has more drag).
    pub fn hook_load_difference_n(&self) -> f64 {
        self.stiff_hook_load_n - self.hook_load_n
    }
    /// Whether the soft string with the helix's drag diverged (its compression unbounded up the
    /// helix): [`Self::helical_drag_hook_load_n`] is then a flag, not a load
    /// ([`crate::models::helical_drag::DIVERGED_HOOK_LOAD_N`]).
    pub fn helical_drag_diverged(&self) -> bool {
        crate::models::helical_drag::diverged(self.helical_drag_hook_load_n)
    }
    /// Stiff minus soft surface torque, N.m.
    pub fn surface_torque_difference_nm(&self) -> f64 {
        self.stiff_surface_torque_nm - self.surface_torque_nm
    }
}

/// The soft string of `case` at the WOB `wob_n` (N; the hook-load input, if any, dropped),
/// beside a stiff solve's hook load `stiff_hook_load_n` (N) and surface torque
/// `stiff_surface_torque_nm` (N.m) at that WOB.
pub fn soft_comparison(
    case: &Case,
    wob_n: f64,
    stiff_hook_load_n: f64,
    stiff_surface_torque_nm: f64,
) -> SoftComparison {
    let mut c = case.clone();
    c.operation.wob_n = wob_n;
    c.operation.hook_load_n = None;
    let soft = softstring::from_case(&c, softstring::segment_length_m(&c.solver));
    let marks = soft_marks(&c, &soft, 0);
    let helical = helical_soft_string(&c);
    SoftComparison {
        helical_drag_hook_load_n: helical.hook_load_n,
        helical_drag_surface_torque_nm: helical.surface_torque_nm,
        wob_n,
        hook_load_n: soft.hook_load_n,
        surface_torque_nm: soft.surface_torque_nm,
        helical_length_m: summarize(&marks).helical_length_m,
        helical_wall_force_n: helical_wall_force_n(&marks),
        stiff_hook_load_n,
        stiff_surface_torque_nm,
    }
}
