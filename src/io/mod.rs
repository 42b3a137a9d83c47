//! Input files: survey CSV and TOML case files, turned into validated library types.

pub mod case_toml;
pub mod measured_csv;
pub mod paths;
pub mod survey_csv;
pub mod toml_reader;
pub mod tracking_toml;
