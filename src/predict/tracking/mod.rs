//! Tracking: a prediction judged against the naive projections a directional driller makes by
//! hand, and corrected by what the measured hole behind the bit shows (survey assimilation).
//!
//! - [`references`]: hold, the build and turn rates of the hole behind extrapolated, a damped
//!   statistic; the direction error;
//! - [`estimator`]: the tendency filter (a Kalman filter on the turn the model does not
//!   explain);
//! - [`bank`]: filters that differ in how the unexplained turn behaves, and naive projections,
//!   weighted by how well each predicted the hole so far;
//! - [`experts`]: the naive members of that mixture (no correction, the statistic, hold);
//! - [`calibration`]: the stated covariance scaled by the mixture's past errors;
//! - [`assimilate`]: the filter run over consecutive intervals, with the frozen assimilation;
//! - [`project`]: the projection to the bit and ahead, with its bounds;
//! - [`skill`]: mean errors per predictor over the same intervals, the best naive projection,
//!   the skill and the physics' share.

pub mod assimilate;
pub mod bank;
pub mod calibration;
pub mod estimator;
pub mod experts;
pub mod project;
pub mod references;
pub mod skill;
