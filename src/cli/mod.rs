//! Command-line layer: clap arguments, one module per subcommand, errors to exit codes.

pub mod args;
pub mod backanalyze;
pub mod import;
pub mod init;
pub mod loads;
pub mod outputs;
pub mod predict;
pub mod progress;
pub mod solve;
pub mod survey;
pub mod tendency;

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
        Command::Tendency(a) => tendency::run(a, cli.quiet),
        Command::Import(a) => import::run(a),
        Command::Init(a) => init::run(a.file, a.force),
    }
}

/// Parse a command-line length (`"30 m"`, `9000ft`) for option `name`; a bare number is in
/// `bare_unit` (the survey's measured-depth unit, see [`bare_unit`]), and a note says so when
/// that is not m.
pub fn parse_length_option(name: &str, text: &str, bare_unit: &str) -> Result<f64, InputError> {
    let value = parse_quantity(text, Dimension::Length, bare_unit).map_err(|m| InputError::option(name, m))?;
    if bare_unit != "m" && text.trim().parse::<f64>().is_ok() {
        tracing::warn!(
            "option `{name}`: the bare number {} is read in {bare_unit}, the unit of the survey's measured depths (give the unit, e.g. \"{} m\", for another)",
            text.trim(),
            text.trim()
        );
    }
    Ok(value)
}

/// The unit of bare numbers in the command line's depth and length options for `case`: the
/// unit its survey's measured depths were read in.
pub fn bare_unit(case: &crate::case::Case) -> &str {
    &case.well.survey.md_unit
}

/// Parse an optional length option (`None` when not given; bare numbers in `bare_unit`),
/// refusing values below `min` (m).
pub fn length_opt(name: &str, v: &Option<String>, min: f64, bare_unit: &str) -> anyhow::Result<Option<f64>> {
    let Some(t) = v else { return Ok(None) };
    let x = parse_length_option(name, t, bare_unit)?;
    if x.is_nan() || x < min {
        anyhow::bail!(
            "option `{name}`: {} m is below the smallest accepted value {min} m",
            crate::units::message_number(x)
        );
    }
    Ok(Some(x))
}

/// Apply `--accuracy PRESET` (when given) to the case's solver settings: element lengths and
/// contact tolerance of the preset, overriding the case file ([`crate::case::accuracy`]).
pub fn apply_accuracy_option(option: Option<&str>, solver: &mut crate::case::SolverSettings) -> Result<(), InputError> {
    let Some(t) = option else { return Ok(()) };
    let preset = crate::case::accuracy::Accuracy::parse(t.trim()).ok_or_else(|| {
        InputError::option(
            "--accuracy",
            format!("unknown accuracy `{t}` (expected {})", crate::case::accuracy::NAMES),
        )
    })?;
    solver.apply_preset(preset);
    Ok(())
}

/// The fidelity asked for: `--fidelity LEVEL` when given, else the case's `[solver] fidelity`.
pub fn fidelity_option(
    option: Option<&str>,
    case_value: crate::case::Fidelity,
) -> Result<crate::case::Fidelity, InputError> {
    match option {
        None => Ok(case_value),
        Some(t) => crate::case::Fidelity::parse(t.trim()).ok_or_else(|| {
            InputError::option(
                "--fidelity",
                format!("unknown fidelity `{t}` (expected {})", crate::case::fidelity::NAMES),
            )
        }),
    }
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
    purpose: crate::case::fidelity::Purpose,
) -> Result<crate::case::fidelity::Choice, InputError> {
    apply_accuracy_option(accuracy, &mut case.solver)?;
    if let Some(preset) = accuracy.and(case.solver.accuracy) {
        case.bit_rock.step_m = preset.knobs().step_m;
    }
    let requested = fidelity_option(fidelity, case.solver.fidelity)?;
    Ok(crate::case::fidelity::choose(requested, purpose))
}
