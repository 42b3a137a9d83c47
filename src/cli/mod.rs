//! Command-line layer: clap arguments, one module per subcommand, errors to exit codes.

pub mod args;
pub mod backanalyze;
pub mod init;
pub mod loads;
pub mod predict;
pub mod progress;
pub mod solve;
pub mod solve_levels;
pub mod survey;

use crate::error::InputError;
use crate::units::{lookup_dim, parse_quantity, Dimension};
use args::{Cli, Command};

/// Run a parsed command line; errors carry a message for stderr.
pub fn run(cli: Cli) -> anyhow::Result<()> {
    match cli.command {
        Command::Survey(a) => survey::run(a),
        Command::Solve(a) => solve::run(a, cli.quiet),
        Command::Predict(a) => predict::run(a, cli.quiet),
        Command::Backanalyze(a) => backanalyze::run(a, cli.quiet),
        Command::Loads(a) => loads::run(a, cli.quiet),
        Command::Init(a) => init::run(a.file, a.force),
    }
}

/// Parse a command-line length (`"30 m"`, `9000ft`; bare number = m) for option `name`.
pub fn parse_length_option(name: &str, text: &str) -> Result<f64, InputError> {
    parse_quantity(text, Dimension::Length, "m").map_err(|m| InputError::option(name, m))
}

/// Parse a command-line length unit (`ft`, `m`) for option `name`.
pub fn parse_length_unit(name: &str, text: &str) -> Result<crate::units::Unit, InputError> {
    lookup_dim(text, Dimension::Length).map_err(|m| InputError::option(name, m))
}

/// Apply the command line's `--accuracy` preset to `case` (element lengths, contact tolerance
/// and, for prediction, the step) and choose the model level for `purpose`: `--fidelity` over
/// the case's `[solver] fidelity`.
pub fn model_choice(
    fidelity: Option<&str>,
    accuracy: Option<&str>,
    case: &mut crate::case::Case,
    purpose: crate::fidelity::Purpose,
) -> Result<crate::fidelity::Choice, InputError> {
    if let Some(t) = accuracy {
        let preset = crate::accuracy::Accuracy::parse(t.trim()).ok_or_else(|| {
            InputError::option(
                "--accuracy",
                format!("unknown accuracy `{t}` (expected {})", crate::accuracy::NAMES),
            )
        })?;
        preset.apply(&mut case.solver);
        case.bit_rock.step_m = preset.knobs().step_m;
    }
    let requested = match fidelity {
        None => case.solver.fidelity,
        Some(t) => crate::fidelity::parse(t.trim()).ok_or_else(|| {
            InputError::option(
                "--fidelity",
                format!("unknown fidelity `{t}` (expected {})", crate::fidelity::NAMES),
            )
        })?,
    };
    Ok(crate::fidelity::choose(requested, purpose))
}
