//! clap argument definitions (the raw layer; validated before any computation).

use clap::{Args, Parser, Subcommand};
use std::path::PathBuf;

/// drillpath: drillstring mechanics and well-trajectory prediction.
#[derive(Debug, Parser)]
#[command(name = "drillpath", version, about, long_about = None)]
pub struct Cli {
    /// More log output on stderr (-v info, -vv debug).
    #[arg(short, long, action = clap::ArgAction::Count, global = true)]
    pub verbose: u8,
    /// Only errors on stderr.
    #[arg(short, long, global = true)]
    pub quiet: bool,
    /// The command.
    #[command(subcommand)]
    pub command: Command,
}

/// Subcommands.
#[derive(Debug, Subcommand)]
pub enum Command {
    /// Positions by minimum curvature from a case file or a survey CSV.
    ///
    /// Example: drillpath survey wells/j-shape/case.toml --out positions.csv
    Survey(SurveyArgs),
}

/// Arguments of `drillpath survey`.
#[derive(Debug, Args)]
pub struct SurveyArgs {
    /// Case file (.toml) or survey CSV.
    pub input: PathBuf,
    /// Write the positions CSV here (default: print it to stdout after the summary... no: only the summary is printed; use --out for the table).
    #[arg(long)]
    pub out: Option<PathBuf>,
    /// Unit of a survey MD column whose header has none, e.g. ft [default: m, or the case file's survey_md_unit].
    #[arg(long, value_name = "UNIT")]
    pub md_unit: Option<String>,
    /// Print the positions CSV on stdout instead of the summary.
    #[arg(long)]
    pub csv: bool,
}
