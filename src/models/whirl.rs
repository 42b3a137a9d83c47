//! Where a rotating string whirls: the helically buckled pipe of a rotating string, where the
//! quasi-static model leaves out the lateral push of rotary friction (issue 16; docs/theory.md
//! 7.5, "The rotating helix").
//!
//! Rotary friction at a wall contact opposes the contact's sliding velocity, whose
//! circumferential part `Omega R_c (t x n)` pushes the pipe round the wall. On pipe lying on
//! the low side that push is held by the pipe's weight (it climbs the wall until the weight's
//! share balances it), but on a helix every contact is pushed the same way round and the
//! pushes' moment about the hole axis, `r f w_c` per length, has nothing to hold it over more
//! than a few tens of metres: a real string there whirls, and the static problem has no
//! equilibrium (the acceptance grid's rotating failures). In the soft string's helically
//! buckled runs above the bottom-hole assembly, [`whirl_intervals`] marks the pipe as
//! whirling: its wall friction keeps its torque (`f R R_c`) and its axial drag, the soft
//! string's friction, and loses its lateral push.

use crate::case::Case;
use crate::models::buckled_start::soft_helical_runs;
use crate::models::fem::model::{Model, TopCondition};

/// The MD intervals `(top, bottom)`, m, of `model` (of `case`) where the string whirls: none
/// unless the string rotates and `model` is the whole string (a cut model ends where the string
/// lies on the wall, below any helix that matters to it); else the soft string's runs beyond the helical onset
/// ([`soft_helical_runs`]) above the bottom-hole assembly.
pub fn whirl_intervals(case: &Case, model: &Model) -> Vec<(f64, f64)> {
    if model.loads.omega_rad_s <= 0.0 || matches!(model.top, TopCondition::Cut { .. }) {
        return Vec::new();
    }
    let (_, runs) = soft_helical_runs(case, model);
    let bha_top_md = model.bit_md_m - case.string.bha_length_m();
    runs.iter()
        .filter_map(|&(a, b)| {
            let bottom = model.md_ref[a].min(bha_top_md);
            let top = model.md_ref[b];
            (top < bottom).then_some((top, bottom))
        })
        .collect()
}
