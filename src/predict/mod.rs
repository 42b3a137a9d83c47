//! Trajectory prediction: the bit-rock law, the forward-marching loop on the stiff
//! bottom-hole-assembly model, tracking against a survey, back-analysis and calibration
//! (docs/theory.md 9).

pub mod backanalysis;
pub mod calibrate;
pub mod extrapolate;
pub mod forecast;
pub mod intervals;
pub mod law;
pub mod march;
pub mod revolution;
pub mod steer;
pub mod tendency;
pub mod track;
pub mod tracking;
