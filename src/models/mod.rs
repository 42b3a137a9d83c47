//! The mechanical models of the string in the hole, and the pieces of mechanics they share.
//!
//! - [`bit`]: the bit's loads (bit torque), the same for every model;
//! - [`softstring`]: the soft string (torque and drag along the hole axis, no bending);
//! - [`fem`]: the stiff string (co-rotational beams and contact-friction gap elements);
//! - [`levels`]: one static solve at a fidelity level (soft, bha, hybrid, whole);
//! - [`string_solve`]: a solve as `drillpath solve` reports it, and the answers of a whole string
//!   that found no equilibrium at its WOB;
//! - [`buckling`]: sinusoidal and helical buckling onsets and the buckled intervals;
//! - [`soft_comparison`]: the soft string beside a stiff solve's surface values;
//! - [`helical_drag`]: the soft string with the helix's drag, and its helical lock-up;
//! - [`helical_lock_up`]: the whole string below a helical lock-up, the answer where it locks up;
//! - [`lock_up_depth`]: the bit depth from which the string locks up in its operation;
//! - [`diagnose`]: why a stiff solve may not converge (lock-up, helical buckling).

pub mod bit;
pub mod buckled_start;
pub mod buckling;
pub mod checks;
pub mod diagnose;
pub mod fem;
pub mod helical_drag;
pub mod helical_lock_up;
pub mod levels;
pub mod lock_up_depth;
pub mod soft_comparison;
pub mod softstring;
pub mod string_solve;
pub mod whirl;
