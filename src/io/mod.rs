//! Input files: survey files (CSV, text report, spreadsheet or WITSML trajectory) and TOML case files, turned into validated
//! library types.

pub mod case_toml;
pub mod measured_csv;
pub mod motor_toml;
pub mod paths;
pub mod rss_toml;
pub mod solver_toml;
pub mod steering_toml;
pub mod string_toml;
pub mod survey;
pub mod toml_reader;
pub mod tracking_toml;
pub mod witsml;
