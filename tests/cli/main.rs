//! The command line, through the built `drillpath` binary: input errors, the output of each
//! command, reports. One test binary; one module per topic.
//!
//! Run one topic with `cargo test --release --test cli input::`.

#[path = "../common/mod.rs"]
mod common;

mod drag;
mod input;
mod loads;
mod output;
mod predict;
mod refusals;
mod report;
mod solve;
mod tendency;
mod tubular;
mod witsml;
