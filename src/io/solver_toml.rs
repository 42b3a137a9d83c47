//! The `[solver]` table of a case file ([`crate::case::SolverSettings`]), every value checked
//! and named on error, and the bound on the size of the string model it asks for.

use super::toml_reader::Section;
use crate::case::solver::MAX_ELEMENTS;
use crate::case::*;
use crate::error::InputResult;
use crate::string::DrillString;
use crate::units::Dimension as D;

/// Smallest contact `tolerance` accepted (relative to the clearance).
pub const MIN_TOLERANCE: f64 = 1e-8;

/// Refuse element lengths that would give the string model more than [`MAX_ELEMENTS`]
/// elements, naming the key and the remedy (before any mesh is built).
pub fn check_mesh_size(s: &Section, solver: &SolverSettings, string: &DrillString) -> InputResult<()> {
    let bha = string.bha_length_m().min(string.length_m());
    let pipe = string.length_m() - bha;
    let in_bha = bha / solver.bha_element_length_m.min(solver.element_length_m);
    let in_pipe = pipe / solver.element_length_m;
    if in_bha + in_pipe <= MAX_ELEMENTS {
        return Ok(());
    }
    let (key, length, count) = if in_pipe >= in_bha {
        ("element_length", solver.element_length_m, in_pipe)
    } else {
        ("bha_element_length", solver.bha_element_length_m, in_bha)
    };
    Err(s.error(
        key,
        format!(
            "{} m elements give the string model about {:.0} elements ({count:.0} from this key), more than the {MAX_ELEMENTS} a model may have: take longer elements (the accuracy presets in docs/guide.md give the measured trade)",
            crate::units::message_number(length),
            in_bha + in_pipe
        ),
    ))
}

/// Keys accepted in the solver table (checked before any is read, so a typo is named).
pub const SOLVER_KEYS: &[&str] = &[
    "accuracy",
    "element_length",
    "bha_element_length",
    "time_limit",
    "tolerance",
    "fidelity",
    "method",
    "max_iterations",
    "alpha",
    "stabilizer_contact",
    "refine_contacts",
    "refine_runs",
];

/// The `[solver]` table `s`, every value checked and named on error.
pub fn read_solver(s: &Section) -> InputResult<SolverSettings> {
    s.check_known(SOLVER_KEYS)?;
    let mut d = SolverSettings::default();
    let mut accuracy = None;
    if let Some(name) = s.string("accuracy")? {
        let preset = crate::case::accuracy::Accuracy::parse(&name).ok_or_else(|| {
            s.error(
                "accuracy",
                format!("unknown accuracy `{name}` (expected {})", crate::case::accuracy::NAMES),
            )
        })?;
        d.apply_preset(preset);
        accuracy = Some(preset);
    }
    let el = s
        .positive("element_length", D::Length, "m", false)?
        .unwrap_or(d.element_length_m);
    let bha = s
        .positive("bha_element_length", D::Length, "m", false)?
        .unwrap_or(d.bha_element_length_m.min(el));
    let tol = s.number("tolerance")?.unwrap_or(d.tolerance);
    if !(MIN_TOLERANCE..=0.1).contains(&tol) {
        return Err(s.error(
            "tolerance",
            format!("{} outside [{MIN_TOLERANCE:e}, 0.1]: below {MIN_TOLERANCE:e} of the clearance a penetration is as small as the rounding of the positions in double precision, which no solve can reach", crate::units::message_number(tol)),
        ));
    }
    let fidelity = match s.string("fidelity")? {
        None => Fidelity::Auto,
        Some(name) => Fidelity::parse(&name).ok_or_else(|| {
            s.error(
                "fidelity",
                format!("unknown fidelity `{name}` (expected {})", crate::case::fidelity::NAMES),
            )
        })?,
    };
    let method = match s.string("method")?.as_deref() {
        None | Some("newton") => Method::Newton,
        Some("paper") => Method::Paper,
        Some(other) => return Err(s.error("method", format!("unknown method `{other}` (expected newton, paper)"))),
    };
    let max_it = s.number("max_iterations")?.unwrap_or(d.max_iterations as f64);
    if !(1.0..=100_000.0).contains(&max_it) {
        return Err(s.error("max_iterations", "must be between 1 and 100000"));
    }
    let alpha = s.number("alpha")?.unwrap_or(d.alpha);
    if !(alpha > 0.0 && alpha < 1.0) {
        return Err(s.error("alpha", format!("{alpha} outside (0, 1)")));
    }
    let time_limit = s.positive("time_limit", D::Time, "s", false)?.unwrap_or(d.time_limit_s);
    let stabilizer_contact = match s.string("stabilizer_contact")? {
        None => d.stabilizer_contact,
        Some(name) => StabilizerContact::parse(&name).ok_or_else(|| {
            s.error(
                "stabilizer_contact",
                format!(
                    "unknown stabilizer contact `{name}` (expected {})",
                    StabilizerContact::NAMES
                ),
            )
        })?,
    };
    let refine_contacts = s.boolean("refine_contacts")?.unwrap_or(d.refine_contacts);
    let refine_runs = s.number("refine_runs")?.unwrap_or(d.refine_runs as f64);
    if !(1.0..=100_000.0).contains(&refine_runs) || refine_runs.fract() != 0.0 {
        return Err(s.error("refine_runs", "must be a whole number between 1 and 100000"));
    }
    Ok(SolverSettings {
        element_length_m: el,
        bha_element_length_m: bha,
        tolerance: tol,
        fidelity,
        method,
        max_iterations: max_it as usize,
        stabilizer_contact,
        refine_contacts,
        refine_runs: refine_runs as usize,
        alpha,
        time_limit_s: time_limit,
        accuracy,
    })
}
