//! Verification of the library against independent references: closed forms, published and
//! real-well data, and consistency checks. One test binary; one module per topic. Each test
//! states its reference and tolerance.
//!
//! Run one topic with `cargo test --release --test verification solver::`; add
//! `-- --nocapture` to see the measured numbers.

#[path = "../common/mod.rs"]
mod common;

mod acceptance_grid;
mod architecture;
mod blade;
mod buckling;
mod condense;
mod extremes;
mod fidelity;
mod fine_mesh;
mod fuzz_input;
mod geometry;
mod helical_drag;
mod hybrid;
mod known_truth;
mod loads;
mod lock_up_depth;
mod mwd_sag;
mod paper;
mod predict;
mod reactive_torque;
mod rss;
mod slack_off;
mod sliding;
mod softstring;
mod solver;
mod spreadsheet;
mod steering;
mod steering_pads;
mod toolface_hold;
mod tracking;
mod witsml;
