//! clap argument definitions (the raw layer; validated before any computation).

pub use crate::report::display_units::UnitSystem;
use clap::{Args, Parser, Subcommand};
use std::path::PathBuf;

/// drillpath: drillstring mechanics and well-trajectory prediction.
#[derive(Debug, Parser)]
#[command(name = "drillpath", version, about, long_about = None)]
pub struct Cli {
    /// More log output on stderr (-v info, -vv debug).
    #[arg(short, long, action = clap::ArgAction::Count, global = true)]
    pub verbose: u8,
    /// Only errors on stderr (no progress bar).
    #[arg(short, long, global = true)]
    pub quiet: bool,
    /// The command.
    #[command(subcommand)]
    pub command: Command,
}

/// Subcommands.
#[derive(Debug, Subcommand)]
pub enum Command {
    /// Positions by minimum curvature from a case file or a survey file (CSV, text report, spreadsheet, WITSML).
    ///
    /// Example: drillpath survey wells/j-shape/case.toml --out positions.csv
    Survey(SurveyArgs),
    /// Static whole-string solve at the bit depth: bit forces and tilt, contacts, hook load, torque.
    ///
    /// Example: drillpath solve wells/j-shape/case.toml --out results/ --report solve.html
    Solve(SolveArgs),
    /// Forward-marching trajectory prediction (pre-drill design or tracking against the survey).
    ///
    /// Example: drillpath predict wells/seed-daqing/case.toml --from 292 --to 413 --out pred/
    ///
    /// Several cases (e.g. candidate BHAs) give one comparison table of build and walk rates.
    Predict(PredictArgs),
    /// Post-drill back-analysis: predict each survey interval from the measured hole behind it.
    ///
    /// Example: drillpath backanalyze wells/seed-daqing/case.toml --calibrate --out back/
    Backanalyze(BackanalyzeArgs),
    /// Torque-and-drag chart: hook load and surface torque against bit depth for every load case,
    /// buckling and yield limits; friction calibration from measured hook loads.
    ///
    /// Example: drillpath loads wells/j-shape/case.toml --every "30 m" --out results/
    Loads(LoadsArgs),
    /// Tendency charts for pre-drill design: the dogleg a bent motor (or RSS) gives against its
    /// bend angle (or steering ratio) for several WOBs, and the rotary tendency against
    /// inclination; independent solves in parallel.
    ///
    /// Example: drillpath tendency wells/horizontal/steered.toml --out tendency/
    Tendency(TendencyArgs),
    /// Write an editable, commented case from WITSML 1.4.1.1 trajectory, wbGeometry and tubular files.
    ///
    /// Example: drillpath import traj.xml geometry.xml bha.xml --out case.toml
    Import(ImportArgs),
    /// Write a commented starter case (well, BHA, mud, operation) and its survey CSV to edit.
    ///
    /// Example: drillpath init mywell/case.toml && drillpath solve mywell/case.toml
    Init(InitArgs),
}

/// Arguments of `drillpath tendency`.
#[derive(Debug, Args)]
pub struct TendencyArgs {
    /// Case file (.toml) with a bent motor (`bend_angle`) or an `rss` component.
    pub case: PathBuf,
    /// Bend angles of the motor's capability sweep, comma-separated (e.g. "0,0.5,1,1.5"; bare
    /// numbers in deg) [default: 0 to 3 deg by 0.5].
    #[arg(long, value_name = "LIST", allow_hyphen_values = true)]
    pub bends: Option<String>,
    /// Steering ratios of an RSS's capability sweep, comma-separated, each in [0, 1]
    /// [default: 0 to 1 by 0.25].
    #[arg(long, value_name = "LIST", allow_hyphen_values = true)]
    pub ratios: Option<String>,
    /// Weights on bit, comma-separated (e.g. "40 kN,60 kN"; bare numbers in kN) [default: the
    /// case's WOB x 0.5, 1, 1.5].
    #[arg(long, value_name = "LIST", allow_hyphen_values = true)]
    pub wobs: Option<String>,
    /// Diametral under-gauges of a bent motor's pad stabilizer (below the bend) for the
    /// capability sweep, comma-separated (bare numbers in inches, e.g. "0,0.125"), each from 0
    /// (full gauge) to the hole less the pad's body OD [default: 0, 1/16, 1/8, 1/4 in and the
    /// case's own; none without a pad].
    #[arg(long, value_name = "LIST", allow_hyphen_values = true)]
    pub pads: Option<String>,
    /// Inclinations of the rotary sweep, comma-separated (bare numbers in deg), each in [0, 120]
    /// [default: 0 to 90 deg by 15].
    #[arg(long, value_name = "LIST", allow_hyphen_values = true)]
    pub incs: Option<String>,
    /// Directory for tendency.csv and tendency.svg.
    #[arg(long, value_name = "DIR", default_value = "tendency")]
    pub out: PathBuf,
    /// Worker threads [default: all cores].
    #[arg(long, value_name = "N")]
    pub threads: Option<usize>,
}

/// Arguments of `drillpath import`.
#[derive(Debug, Args)]
pub struct ImportArgs {
    /// WITSML 1.4.1.1 files: at most one each of trajectory, wbGeometry and tubular.
    #[arg(required = true, num_args = 1..)]
    pub files: Vec<PathBuf>,
    /// The case file to write.
    #[arg(long, value_name = "FILE", default_value = "case.toml")]
    pub out: PathBuf,
    /// Overwrite an existing case file.
    #[arg(long)]
    pub force: bool,
    /// The trajectory to use, by name or uid, when the file holds several [default: the only one].
    #[arg(long, value_name = "NAME_OR_UID")]
    pub trajectory: Option<String>,
    /// The wbGeometry to use, by name or uid [default: the only one].
    #[arg(long, value_name = "NAME_OR_UID")]
    pub geometry: Option<String>,
    /// The tubular to use, by name or uid [default: the only one].
    #[arg(long, value_name = "NAME_OR_UID")]
    pub tubular: Option<String>,
    /// Read tubular components of no mechanical meaning to drillpath as plain tubes (`sub`).
    #[arg(long)]
    pub other_as_tube: bool,
}

/// Arguments of `drillpath init`.
#[derive(Debug, Args)]
pub struct InitArgs {
    /// Case file to write; survey.csv is written next to it.
    #[arg(default_value = "case.toml")]
    pub file: PathBuf,
    /// Overwrite existing files.
    #[arg(long)]
    pub force: bool,
}

/// Arguments of `drillpath predict`.
#[derive(Debug, Args)]
pub struct PredictArgs {
    /// Case file(s) (.toml); several cases are compared over the same interval.
    #[arg(required = true, num_args = 1..)]
    pub cases: Vec<PathBuf>,
    /// Start MD: the hole is the survey up to here [default: the case's bit_md, where solve puts the bit].
    #[arg(long, value_name = "MD", allow_hyphen_values = true)]
    pub from: Option<String>,
    /// End MD of the prediction (e.g. "413 m", 1500ft) [default: none; give --to or --ahead].
    #[arg(
        long,
        value_name = "MD",
        conflicts_with = "ahead",
        required_unless_present = "ahead",
        allow_hyphen_values = true
    )]
    pub to: Option<String>,
    /// Length to drill ahead of --from instead of --to (e.g. "60 m") [default: none].
    #[arg(long, value_name = "LENGTH", allow_hyphen_values = true)]
    pub ahead: Option<String>,
    /// Step length [default: the case's `[bit_rock]` step, 1 m].
    #[arg(long, value_name = "LENGTH", allow_hyphen_values = true)]
    pub step: Option<String>,
    /// Distance from the bit where the stiff model is cut [default: automatic, see docs/guide.md, "The stiff BHA model"].
    #[arg(long, value_name = "LENGTH", allow_hyphen_values = true)]
    pub cut: Option<String>,
    /// Richardson extrapolation in the step: march at --step and at half of it, combine the two
    /// (error ~ step^2 cancels; about 3x the time of one march) and report the step-error
    /// estimate [default: off].
    #[arg(long)]
    pub extrapolate: bool,
    /// Correct the prediction by the tendency assimilated from the measured hole behind --from
    /// (settings in the case's `[tracking]` table) and give one-standard-deviation bounds
    /// (trajectory.csv: inc_sd_deg, azi_sd_deg, lateral_sd_m, vertical_sd_m).
    #[arg(long)]
    pub assimilate: bool,
    /// Write trajectory.csv and summary.json (several cases: comparison.csv and one folder per case)
    /// [default: no files].
    #[arg(long, value_name = "DIR")]
    pub out: Option<PathBuf>,
    /// Write the predicted path as a WITSML 1.4.1.1 trajectory (one per case; stations typed
    /// as computed, not measured) [default: no file].
    #[arg(long, value_name = "FILE.xml")]
    pub witsml: Option<PathBuf>,
    /// --json, --report, --units.
    #[command(flatten)]
    pub view: ViewArgs,
    /// Model fidelity and accuracy preset.
    #[command(flatten)]
    pub model: PredictionModelArgs,
}

/// Arguments of `drillpath backanalyze`.
#[derive(Debug, Args)]
pub struct BackanalyzeArgs {
    /// Case file (.toml) whose survey is the measured well; several for a well drilled in BHA
    /// runs (the same survey, in the order of their bit depths: each predicts the hole from the
    /// previous one's bit depth to its own).
    #[arg(required = true, num_args = 1..)]
    pub cases: Vec<PathBuf>,
    /// Fit the bit-rock law's parameters on the first part of the intervals (see --split) and
    /// score them on the rest.
    #[arg(long)]
    pub calibrate: bool,
    /// Assimilate the survey: correct each interval's prediction by the tendency learned from
    /// the stations behind its start (settings in the case's `[tracking]` table), and report
    /// the frozen assimilation and one-standard-deviation bounds.
    #[arg(long, conflicts_with = "calibrate")]
    pub assimilate: bool,
    /// Parameters to fit, comma-separated: lateral_drillability, walk_angle, rock_anisotropy.
    #[arg(long, value_name = "LIST", default_value = "lateral_drillability,walk_angle")]
    pub fit: String,
    /// Fraction of the intervals (from the top) used for calibration.
    #[arg(long, value_name = "FRACTION", default_value_t = 0.5, allow_hyphen_values = true)]
    pub split: f64,
    /// Shortest interval: each interval ends at the first station at least this far below its
    /// start [default: the next station].
    #[arg(long, value_name = "LENGTH", allow_hyphen_values = true)]
    pub horizon: Option<String>,
    /// First interval starts at the first station at or below this MD [default: the first
    /// station inclined 3 deg or more, with at least 30 m of hole above it, below the hole
    /// sections wider than the bit (drilled by another BHA)].
    #[arg(long, value_name = "MD", allow_hyphen_values = true)]
    pub from: Option<String>,
    /// No interval ends below this MD [default: the last station].
    #[arg(long, value_name = "MD", allow_hyphen_values = true)]
    pub to: Option<String>,
    /// Step length [default: the case's `[bit_rock]` step, 1 m].
    #[arg(long, value_name = "LENGTH", allow_hyphen_values = true)]
    pub step: Option<String>,
    /// Write trajectory.csv, summary.json (and bit_rock_fitted.toml, case_fitted.toml with --calibrate) [default: no files].
    #[arg(long, value_name = "DIR")]
    pub out: Option<PathBuf>,
    /// Write the predicted interval ends as a WITSML 1.4.1.1 trajectory (tied in at the first
    /// interval's start; stations typed as computed, not measured) [default: no file].
    #[arg(long, value_name = "FILE.xml")]
    pub witsml: Option<PathBuf>,
    /// --json, --report, --units.
    #[command(flatten)]
    pub view: ViewArgs,
    /// Model fidelity and accuracy preset.
    #[command(flatten)]
    pub model: PredictionModelArgs,
}

/// Arguments of `drillpath solve`.
#[derive(Debug, Args)]
pub struct SolveArgs {
    /// Case file (.toml).
    pub case: PathBuf,
    /// Bit measured depth (e.g. "2500 m", 8200ft; bare number = m) [default: the case's bit_md].
    #[arg(long, value_name = "MD", allow_hyphen_values = true)]
    pub bit_md: Option<String>,
    /// Write summary.json and string.csv into this directory [default: no files].
    #[arg(long, value_name = "DIR")]
    pub out: Option<PathBuf>,
    /// Write results of a non-converged solve, flagged `converged: false`, instead of failing.
    #[arg(long)]
    pub allow_unconverged: bool,
    /// --json, --report, --units.
    #[command(flatten)]
    pub view: ViewArgs,
    /// Model fidelity: auto, soft, bha, hybrid, whole [default: the case's `[solver]` fidelity, auto].
    #[arg(long, value_name = "LEVEL")]
    pub fidelity: Option<String>,
    /// Accuracy preset: fast, default, precise (sets element lengths and contact tolerance,
    /// overriding the case file) [default: the case's `[solver]` accuracy, or its own settings].
    #[arg(long, value_name = "PRESET")]
    pub accuracy: Option<String>,
}

/// Arguments of `drillpath survey`.
#[derive(Debug, Args)]
pub struct SurveyArgs {
    /// Case file (.toml) or survey file (CSV, whitespace-separated text report, spreadsheet
    /// .xlsx/.xls/.ods, or WITSML 1.4.1.1 trajectory .xml).
    pub input: PathBuf,
    /// Write the positions CSV to this file (stdout shows the summary) [default: no file].
    #[arg(long)]
    pub out: Option<PathBuf>,
    /// Unit of a survey MD column whose header has none, e.g. ft [default: m, or the case file's survey_md_unit].
    #[arg(long, value_name = "UNIT")]
    pub md_unit: Option<String>,
    /// Print the positions CSV on stdout instead of the summary.
    #[arg(long)]
    pub csv: bool,
    /// Trajectory of a WITSML file to read, by name or uid [default: the only one; the case's survey_trajectory].
    #[arg(long, value_name = "NAME_OR_UID")]
    pub trajectory: Option<String>,
    /// Sheet of a spreadsheet to read, by name [default: the first with a survey header; the case's survey_sheet].
    #[arg(long, value_name = "NAME")]
    pub sheet: Option<String>,
}

/// Arguments of `drillpath loads`.
#[derive(Debug, Args)]
pub struct LoadsArgs {
    /// Case file (.toml).
    pub case: PathBuf,
    /// Shallowest bit depth (e.g. "500 m", 1500ft; bare number = m) [default: 0; depths at the
    /// top of the survey are skipped].
    #[arg(long, value_name = "MD", allow_hyphen_values = true)]
    pub from: Option<String>,
    /// Deepest bit depth [default: the case's bit_md].
    #[arg(long, value_name = "MD", allow_hyphen_values = true)]
    pub to: Option<String>,
    /// Bit depth step [default: 30 m].
    #[arg(long, value_name = "LENGTH", allow_hyphen_values = true)]
    pub every: Option<String>,
    /// Write loads.csv (and calibration.csv, calibration.json with --measured) into this directory
    /// [default: no files].
    #[arg(long, value_name = "DIR")]
    pub out: Option<PathBuf>,
    /// Model of the chart: auto (= soft), soft (soft string only), hybrid (stiff BHA + soft
    /// string above, next to the soft chart), whole (stiff whole string, next to the soft chart)
    /// [default: the case's `[solver]` fidelity, auto]. bha has no hook load: refused.
    #[arg(long, value_name = "LEVEL")]
    pub fidelity: Option<String>,
    /// Accuracy preset: fast, default, precise (sets element lengths and contact tolerance,
    /// overriding the case file) [default: the case's `[solver]` accuracy, or its own settings].
    #[arg(long, value_name = "PRESET")]
    pub accuracy: Option<String>,
    /// Same as --fidelity whole: the stiff whole-string FEM for every row, next to the soft chart.
    #[arg(long)]
    pub stiff: bool,
    /// Measured hook loads (and torques) to fit the friction factor per hole section to [default: none].
    #[arg(long, value_name = "FILE")]
    pub measured: Option<PathBuf>,
    /// Weight on bit of the drilling and sliding rows (e.g. "100 kN", "20 klbf") [default: the case's wob].
    #[arg(long, value_name = "FORCE", allow_hyphen_values = true)]
    pub wob: Option<String>,
    /// Units shown on stdout: si or oilfield (loads.csv and the calibration files stay SI).
    #[arg(long, value_enum, default_value = "si")]
    pub units: UnitSystem,
}

/// How a result is shown: `--json`, `--report`, `--units` (solve, predict, backanalyze).
#[derive(Debug, Args)]
pub struct ViewArgs {
    /// Print summary.json on stdout instead of the readable summary.
    #[arg(long)]
    pub json: bool,
    /// Write a self-contained HTML report (inline SVG plots, opens offline), e.g. `--report r.html`
    /// [default: no report].
    #[arg(long, value_name = "FILE.html")]
    pub report: Option<PathBuf>,
    /// Units shown on stdout and in the report: si or oilfield (CSV and JSON files stay SI).
    #[arg(long, value_enum, default_value = "si")]
    pub units: UnitSystem,
}

/// The model of a prediction: `--fidelity`, `--accuracy` (predict, backanalyze).
#[derive(Debug, Args)]
pub struct PredictionModelArgs {
    /// Model fidelity: auto or bha (stiff bottom-hole assembly cut where it lies on the wall),
    /// hybrid (same bit forces as bha), whole (stiff whole string, slower); soft is refused (no bit
    /// forces) [default: the case's `[solver]` fidelity, auto].
    #[arg(long, value_name = "LEVEL")]
    pub fidelity: Option<String>,
    /// Accuracy preset: fast, default, precise (sets element lengths, contact tolerance and the
    /// step; --step wins) [default: the case's `[solver]` accuracy, or its own settings].
    #[arg(long, value_name = "PRESET")]
    pub accuracy: Option<String>,
}
