//! Small numerical routines shared by the models and the calibrations (no mechanics here).

pub mod least_squares;
