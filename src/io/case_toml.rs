//! TOML case files -> validated [`Case`] (docs/guide.md "Case file").
//!
//! Default units of bare numbers (documented in docs/guide.md, "Case-file reference"): measured depths and lengths m,
//! diameters (`od`, `id`, `body_od`, `tool_joint_od`, `diameter`) in, forces kN, torques kN.m,
//! mud density sg, weight per length kg/m, ROP m/h, trip speed m/s, angles deg, moduli GPa,
//! material density kg/m3, viscosity cP.

use super::solver_toml::{check_mesh_size, read_solver};
use super::string_toml::read_string;
use super::survey::{convert_reference, parse_reference, read_survey, survey_format, SurveyFormat, SurveyUnits};
use super::toml_reader::Section;
use super::tracking_toml::read_tracking;
use super::witsml::geometry::{hole_sections, parse_geometry};
use super::witsml::tubular::parse_tubular;
use crate::case::SurveyFile;
use crate::case::*;
use crate::error::{InputError, InputResult};
use crate::geometry::{HoleSection, HoleSize, Vec3, WellPath};
use crate::string::DrillString;
use crate::units::{lookup_dim, Dimension as D, Unit};
use std::path::{Path, PathBuf};

/// Values from the command line that override or complete the case file.
#[derive(Debug, Clone, Default)]
pub struct CaseOverrides {
    /// Unit of a survey MD column whose header has none (`--md-unit`).
    pub survey_md_unit: Option<Unit>,
    /// Bit measured depth (`--bit-md`), m.
    pub bit_md_m: Option<f64>,
}

/// Read and validate a case file.
pub fn load_case(path: &Path, overrides: &CaseOverrides) -> InputResult<Case> {
    let bytes = std::fs::read(path).map_err(|e| InputError::file(path, format!("cannot read case file: {e}")))?;
    parse_case(&bytes, path, overrides)
}

/// Parse and validate the case file contents `bytes`, as [`load_case`] does the file at `path`
/// (used in messages, and to find the survey file relative to it).
pub fn parse_case(bytes: &[u8], path: &Path, overrides: &CaseOverrides) -> InputResult<Case> {
    let text = std::str::from_utf8(bytes).map_err(|e| {
        let line = line_of(bytes, e.valid_up_to());
        InputError::line(
            path,
            line,
            None,
            format!(
                "the case file is not valid UTF-8 text (byte 0x{:02X}); save it as UTF-8",
                bytes.get(e.valid_up_to()).copied().unwrap_or(0)
            ),
        )
    })?;
    if text.trim().is_empty() {
        return Err(InputError::file(path, "the case file is empty"));
    }
    let table: toml::Table = text.parse().map_err(|e: toml::de::Error| {
        let msg = e.message().to_string();
        match e.span() {
            Some(span) => InputError::line(
                path,
                line_of(bytes, span.start),
                None,
                format!("TOML syntax error: {msg}"),
            ),
            None => InputError::file(path, format!("TOML syntax error: {msg}")),
        }
    })?;
    let top = Section::new(path, "", &table);
    top.check_known(TOP_KEYS)?;
    let name = top.string("name")?.unwrap_or_else(|| {
        path.file_stem()
            .map(|s| s.to_string_lossy().into_owned())
            .unwrap_or_default()
    });
    let description = top.string("description")?.unwrap_or_default();
    let dir = path.parent().map(Path::to_path_buf).unwrap_or_default();

    let well_sec = top
        .table("well")?
        .ok_or_else(|| top.error("well", "missing the [well] table (survey and hole sizes)"))?;
    let (survey_file, survey_path, origin, hole, hole_from) = read_well(&well_sec, &dir, overrides)?;
    let caliper_path = well_sec.string("caliper")?.map(|rel| dir.join(rel));
    let wellpath = WellPath::new(&survey_file.survey, origin).map_err(|p| {
        let line = survey_file.station_lines.get(p.index).copied().unwrap_or(0);
        InputError::line(&survey_path, line, Some("inc/azi"), p.message)
    })?;

    let mud = match top.table("mud")? {
        Some(s) => {
            s.check_known(MUD_KEYS)?;
            let density = s.positive("density", D::Density, "sg", false)?.unwrap_or(1000.0);
            if density > 3000.0 {
                return Err(s.error("density", "mud density above 3 sg is not plausible"));
            }
            let pv = s
                .positive("plastic_viscosity", D::Viscosity, "cP", true)?
                .unwrap_or(0.02);
            Mud {
                density_kg_m3: density,
                plastic_viscosity_pa_s: pv,
            }
        }
        None => Mud {
            density_kg_m3: 1000.0,
            plastic_viscosity_pa_s: 0.02,
        },
    };

    let empty = toml::Table::new();
    let op_sec = top
        .table("operation")?
        .unwrap_or_else(|| Section::new(path, "operation", &empty));
    let operation = read_operation(&op_sec, &wellpath, &hole, overrides)?;

    let (string, string_from, string_notes) = read_case_string(&top, &dir, &operation, &hole, &mud)?;

    let sol_sec = top
        .table("solver")?
        .unwrap_or_else(|| Section::new(path, "solver", &empty));
    let solver = read_solver(&sol_sec)?;
    check_mesh_size(&sol_sec, &solver, &string)?;
    let br_sec = top
        .table("bit_rock")?
        .unwrap_or_else(|| Section::new(path, "bit_rock", &empty));
    let default_step_m = solver.accuracy.map(|p| p.knobs().step_m).unwrap_or(DEFAULT_STEP_M);
    let bit_rock = read_bit_rock(&br_sec, default_step_m)?;
    let tr_sec = top
        .table("tracking")?
        .unwrap_or_else(|| Section::new(path, "tracking", &empty));
    let tracking = read_tracking(&tr_sec, wellpath.md_end() - wellpath.md_start())?;
    let steering = super::steering_toml::read_steering(&top, &dir, operation.toolface_rad, string.rss().is_some())?;

    let case = Case {
        name,
        description,
        path: path.to_path_buf(),
        well: Well {
            survey: survey_file,
            survey_path,
            caliper_path,
            hole_from,
            path: wellpath,
            hole,
        },
        mud,
        operation,
        string,
        string_from,
        bit_rock,
        solver,
        tracking,
        steering,
    };
    if let Some(note) = case.string_above_survey_note() {
        tracing::warn!("{}: {note}", path.display());
    }
    for note in string_notes {
        tracing::warn!("{note}");
    }
    Ok(case)
}

/// The string of the case: its `[[string]]` tables, or the WITSML tubular `string_from` names
/// (with that file's path and the notes of its reading, to show once the case is read), or none.
fn read_case_string(
    top: &Section,
    dir: &Path,
    operation: &Operation,
    hole: &HoleSize,
    mud: &Mud,
) -> InputResult<(DrillString, Option<PathBuf>, Vec<String>)> {
    let from = top.string("string_from")?;
    let chosen = top.string("string_from_tubular")?;
    let other_as_tube = top.boolean("string_other_as_tube")?.unwrap_or(false);
    match (top.tables("string")?, from) {
        (Some(_), Some(_)) => Err(top.error(
            "string_from",
            "the case has both `[[string]]` tables and `string_from`: give one of them",
        )),
        (Some(secs), None) => Ok((read_string(&secs, top, operation, hole, mud)?, None, vec![])),
        (None, Some(rel)) => {
            let xml = dir.join(&rel);
            if !xml.is_file() {
                return Err(top.error(
                    "string_from",
                    format!("WITSML tubular file `{}` not found", xml.display()),
                ));
            }
            let text = crate::io::witsml::read_text(&xml)?;
            let tub = parse_tubular(&text, &xml, chosen.as_deref(), other_as_tube)?;
            let secs: Vec<Section> = tub
                .components
                .iter()
                .map(|c| Section::new(&xml, format!("tubularComponent[{}]", c.uid), &c.table))
                .collect();
            let string = read_string(&secs, top, operation, hole, mud)?;
            let mut notes: Vec<String> = tub.notes.iter().map(|n| format!("{}: {n}", xml.display())).collect();
            if let (Some(len), Some(c), Some(t)) = (tub.top_len_m, string.components.last(), tub.components.last()) {
                if (len - c.length_m).abs() > 0.01 {
                    notes.push(format!(
                        "{}: the topmost component `{}` ({}) fills the string to the surface: {:.2} m long, not its `len` {len} m",
                        xml.display(),
                        t.uid,
                        t.kind,
                        c.length_m
                    ));
                }
            }
            Ok((string, Some(xml), notes))
        }
        (None, None) if chosen.is_some() || other_as_tube => Err(top.error(
            if chosen.is_some() {
                "string_from_tubular"
            } else {
                "string_other_as_tube"
            },
            "applies only with `string_from`",
        )),
        (None, None) => Ok((DrillString { components: vec![] }, None, vec![])),
    }
}

/// 1-based line of byte `offset` of `bytes`; the end of a file that ends with a line end is on
/// its last line (not on the empty line after it).
fn line_of(bytes: &[u8], offset: usize) -> usize {
    let newlines = |b: &[u8]| b.iter().filter(|&&c| c == b'\n').count();
    let lines = newlines(bytes) + usize::from(!bytes.ends_with(b"\n"));
    (newlines(&bytes[..offset.min(bytes.len())]) + 1).min(lines.max(1))
}

/// What `[well]` gives: the survey as read and its path, the origin, the hole and the WITSML
/// file it was read from (`hole_from`), if any.
type WellParts = (SurveyFile, PathBuf, Vec3, HoleSize, Option<PathBuf>);

/// The hole sections of the `hole` list of `[well]` (`s`).
fn read_hole_list(s: &Section) -> InputResult<Vec<HoleSection>> {
    let secs = s.tables("hole")?.ok_or_else(|| {
        s.error(
            "hole",
            "missing the hole sections, e.g. hole = [{ to_md = \"3000 m\", diameter = \"8.5 in\" }] (or hole_from = \"geometry.xml\", a WITSML wbGeometry)",
        )
    })?;
    if secs.is_empty() {
        return Err(s.error("hole", "needs at least one section"));
    }
    let mut sections = Vec::new();
    for h in &secs {
        h.check_known(HOLE_KEYS)?;
        let to_md = h.req_quantity("to_md", D::Length, "m")?;
        let diameter = h
            .positive("diameter", D::Length, "in", false)?
            .ok_or_else(|| h.error("diameter", "missing hole diameter"))?;
        if diameter > 2.0 {
            return Err(h.error(
                "diameter",
                format!("hole diameter {diameter:.3} m is not plausible (bare numbers are inches)"),
            ));
        }
        let friction = h.number("friction")?;
        if let Some(f) = friction {
            if !(0.0..=1.5).contains(&f) {
                return Err(h.error("friction", format!("friction coefficient {f} outside [0, 1.5]")));
            }
        }
        if let Some(prev) = sections.last() {
            let prev: &HoleSection = prev;
            if to_md <= prev.to_md_m {
                return Err(h.error("to_md", "hole sections must be listed top down with increasing to_md"));
            }
        }
        sections.push(HoleSection {
            to_md_m: to_md,
            diameter_m: diameter,
            friction,
        });
    }
    Ok(sections)
}

/// The hole sections of the WITSML wbGeometry `rel` (relative to `dir`) that `[well]
/// hole_from` (`s`) names, with the file's path; `cased_friction` applies to cased sections.
fn read_hole_from(s: &Section, dir: &Path, rel: &str) -> InputResult<(Vec<HoleSection>, PathBuf)> {
    let file = dir.join(rel);
    if !file.is_file() {
        return Err(s.error(
            "hole_from",
            format!("WITSML wbGeometry file `{}` not found", file.display()),
        ));
    }
    let cased = s.number("cased_friction")?;
    if let Some(f) = cased {
        if !(0.0..=1.5).contains(&f) {
            return Err(s.error("cased_friction", format!("friction coefficient {f} outside [0, 1.5]")));
        }
    }
    let text = crate::io::witsml::read_text(&file)?;
    let chosen = s.string("hole_from_geometry")?;
    let sections = parse_geometry(&text, &file, chosen.as_deref())?;
    Ok((hole_sections(&sections, cased), file))
}

fn read_well(s: &Section, dir: &Path, ov: &CaseOverrides) -> InputResult<WellParts> {
    s.check_known(WELL_KEYS)?;
    let rel = s
        .string("survey")?
        .ok_or_else(|| s.error("survey", "missing the survey CSV path"))?;
    let survey_path = dir.join(&rel);
    if !survey_path.exists() {
        return Err(s.error("survey", format!("survey file `{}` not found", survey_path.display())));
    }
    if !survey_path.is_file() {
        return Err(s.error("survey", format!("`{}` is not a file", survey_path.display())));
    }
    let case_unit = match s.string("survey_md_unit")? {
        Some(u) => Some(lookup_dim(&u, D::Length).map_err(|m| s.error("survey_md_unit", m))?),
        None => None,
    };
    let units = SurveyUnits {
        md: ov.survey_md_unit.or(case_unit),
        angle: None,
        trajectory: s.string("survey_trajectory")?,
        sheet: s.string("survey_sheet")?,
    };
    let format = survey_format(&survey_path);
    if units.trajectory.is_some() && format != SurveyFormat::Witsml {
        return Err(s.error(
            "survey_trajectory",
            "the survey file is not a WITSML file: only a WITSML file has trajectories to choose from",
        ));
    }
    if units.sheet.is_some() && format != SurveyFormat::Spreadsheet {
        return Err(s.error(
            "survey_sheet",
            "the survey file is not a spreadsheet (.xlsx, .xls, .ods): it has no sheets to choose from",
        ));
    }
    let mut survey = read_survey(&survey_path, &units)?;
    if let Some(text) = s.string("azimuth_reference")? {
        let to = parse_reference(&text).ok_or_else(|| {
            s.error(
                "azimuth_reference",
                format!("`{text}` is not a north: expected `true`, `grid` or `magnetic`"),
            )
        })?;
        convert_reference(&mut survey, to).map_err(|m| s.error("azimuth_reference", m))?;
    }
    // the case's origin, else the position the survey file gives its first station (WITSML)
    let origin = s
        .length_triple("origin")?
        .or(survey.origin)
        .map(|o| Vec3::new(o[0], o[1], o[2]))
        .unwrap_or_else(Vec3::zeros);
    let (sections, hole_from) = match (s.string("hole_from")?, s.has("hole")) {
        (Some(_), true) => {
            return Err(s.error(
                "hole_from",
                "the case has both `hole` and `hole_from`: give one of them",
            ));
        }
        (Some(rel), false) => {
            let (sections, file) = read_hole_from(s, dir, &rel)?;
            (sections, Some(file))
        }
        (None, _) => {
            for key in ["hole_from_geometry", "cased_friction"] {
                if s.has(key) {
                    return Err(s.error(key, "applies only with `hole_from`"));
                }
            }
            (read_hole_list(s)?, None)
        }
    };
    let caliper = match s.string("caliper")? {
        Some(rel) => read_caliper(&dir.join(rel), s)?,
        None => vec![],
    };
    Ok((survey, survey_path, origin, HoleSize::new(sections, caliper), hole_from))
}

fn read_caliper(path: &Path, s: &Section) -> InputResult<Vec<(f64, f64)>> {
    let text = std::fs::read_to_string(path)
        .map_err(|e| s.error("caliper", format!("cannot read `{}`: {e}", path.display())))?;
    let mut rows = Vec::new();
    let mut header_seen = false;
    for (i, line) in text.lines().enumerate() {
        let l = line.trim().trim_start_matches('\u{feff}');
        if l.is_empty() || l.starts_with('#') {
            continue;
        }
        if !header_seen {
            header_seen = true;
            continue;
        }
        let f: Vec<&str> = l.split(',').collect();
        let parse = |k: usize, dim: D, unit: &str, col: &str| -> InputResult<f64> {
            let t = f
                .get(k)
                .ok_or_else(|| InputError::line(path, i + 1, Some(col), "missing value"))?;
            crate::units::parse_quantity(t, dim, unit).map_err(|m| InputError::line(path, i + 1, Some(col), m))
        };
        let md = parse(0, D::Length, "m", "md")?;
        let d = parse(1, D::Length, "in", "diameter")?;
        if d <= 0.0 {
            return Err(InputError::line(
                path,
                i + 1,
                Some("diameter"),
                "diameter must be positive",
            ));
        }
        if let Some(&(m0, _)) = rows.last() {
            if md <= m0 {
                return Err(InputError::line(path, i + 1, Some("md"), "MD must strictly increase"));
            }
        }
        rows.push((md, d));
    }
    if rows.len() < 2 {
        return Err(InputError::file(
            path,
            "a caliper file needs a header (md_m, diameter_in) and at least two rows",
        ));
    }
    Ok(rows)
}

fn read_operation(s: &Section, path: &WellPath, hole: &HoleSize, ov: &CaseOverrides) -> InputResult<Operation> {
    s.check_known(OPERATION_KEYS)?;
    let mode = match s.string("mode")? {
        Some(m) => {
            Mode::parse(&m).ok_or_else(|| s.error("mode", format!("unknown mode `{m}` (expected {})", Mode::NAMES)))?
        }
        None => Mode::Drilling,
    };
    let bit_md_case = s.quantity("bit_md", D::Length, "m")?;
    let bit_md = ov.bit_md_m.or(bit_md_case).unwrap_or_else(|| path.md_end());
    let (lo, hi) = (path.md_start(), path.md_end());
    if bit_md <= lo || bit_md > hi + 1e-6 {
        let msg = format!("bit MD {bit_md:.2} m is outside the surveyed hole ({lo:.2} m to {hi:.2} m)");
        return Err(if ov.bit_md_m.is_some() {
            InputError::option("--bit-md", msg)
        } else {
            s.error("bit_md", msg)
        });
    }
    if bit_md > hole.deepest_md() + 1e-6 {
        return Err(s.error(
            "bit_md",
            format!(
                "bit MD {bit_md:.2} m is below the deepest hole section ({:.2} m)",
                hole.deepest_md()
            ),
        ));
    }
    let wob = s.positive("wob", D::Force, "kN", true)?;
    let hook = s.positive("hook_load", D::Force, "kN", true)?;
    if wob.is_some() && hook.is_some() {
        return Err(s.error("hook_load", "give either wob or hook_load, not both"));
    }
    let wob = if mode.on_bottom() { wob.unwrap_or(0.0) } else { 0.0 };
    let rpm = s
        .quantity("rpm", D::RotarySpeed, "rpm")?
        .map(|w| w * 60.0 / std::f64::consts::TAU)
        .unwrap_or(0.0);
    if !(0.0..=400.0).contains(&rpm) {
        return Err(s.error("rpm", format!("rotary speed {rpm:.1} rpm outside [0, 400]")));
    }
    let rop = s.positive("rop", D::Speed, "m/h", true)?.unwrap_or(0.0);
    let trip = s.positive("trip_speed", D::Speed, "m/s", false)?.unwrap_or(0.3);
    let friction = s.number("friction")?.unwrap_or(0.25);
    if !(0.0..=1.5).contains(&friction) {
        return Err(s.error("friction", format!("friction coefficient {friction} outside [0, 1.5]")));
    }
    let bit_torque = s.quantity("bit_torque", D::Moment, "kN.m")?;
    let viscous = s.boolean("viscous_torque")?.unwrap_or(true);
    Ok(Operation {
        mode,
        bit_md_m: bit_md,
        wob_n: wob,
        hook_load_n: hook,
        rpm,
        rop_m_s: rop,
        trip_speed_m_s: trip,
        friction,
        bit_torque_nm: bit_torque,
        viscous_torque: viscous,
        toolface_rad: super::motor_toml::read_toolface(s)?,
        reactive_torque: s.boolean("reactive_torque")?.unwrap_or(false),
    })
}

/// Every key a case file accepts, in any table (for tools that generate or check case files,
/// such as the readers' fuzz test).
pub fn known_keys() -> Vec<&'static str> {
    [
        TOP_KEYS,
        WELL_KEYS,
        HOLE_KEYS,
        MUD_KEYS,
        OPERATION_KEYS,
        FORMATION_KEYS,
        BIT_ROCK_KEYS,
        super::string_toml::COMPONENT_KEYS,
        super::rss_toml::RSS_KEYS,
        super::solver_toml::SOLVER_KEYS,
        super::tracking_toml::TRACKING_KEYS,
        super::steering_toml::STEERING_KEYS,
    ]
    .concat()
}

/// Keys accepted in the top table (checked before any is read, so a typo is named).
const TOP_KEYS: &[&str] = &[
    "name",
    "description",
    "well",
    "mud",
    "operation",
    "string",
    "string_from",
    "string_from_tubular",
    "string_other_as_tube",
    "bit_rock",
    "solver",
    "tracking",
    "steering",
    "slide_sheet",
];
/// Keys accepted in the well table (checked before any is read, so a typo is named).
const WELL_KEYS: &[&str] = &[
    "survey",
    "survey_md_unit",
    "survey_trajectory",
    "survey_sheet",
    "azimuth_reference",
    "origin",
    "hole",
    "hole_from",
    "hole_from_geometry",
    "cased_friction",
    "caliper",
];
/// Keys accepted in the hole table (checked before any is read, so a typo is named).
const HOLE_KEYS: &[&str] = &["to_md", "diameter", "friction"];
/// Keys accepted in the mud table (checked before any is read, so a typo is named).
const MUD_KEYS: &[&str] = &["density", "plastic_viscosity"];
/// Keys accepted in the operation table (checked before any is read, so a typo is named).
const OPERATION_KEYS: &[&str] = &[
    "mode",
    "bit_md",
    "wob",
    "hook_load",
    "rpm",
    "rop",
    "trip_speed",
    "friction",
    "bit_torque",
    "viscous_torque",
    "toolface",
    "reactive_torque",
];
/// Keys accepted in the formation table (checked before any is read, so a typo is named).
const FORMATION_KEYS: &[&str] = &["from_md", "to_md", "rock_anisotropy", "dip", "dip_direction"];
/// Keys accepted in the bit rock table (checked before any is read, so a typo is named).
const BIT_ROCK_KEYS: &[&str] = &[
    "law",
    "lateral_drillability",
    "walk_angle",
    "rock_anisotropy",
    "dip",
    "dip_direction",
    "step",
    "bit_friction",
    "formations",
];
/// Prediction step when neither `[bit_rock] step` nor `[solver] accuracy` gives one, m.
pub const DEFAULT_STEP_M: f64 = 1.0;

/// `[bit_rock]`; `default_step_m` applies when the table has no `step` (the accuracy preset's).
fn read_bit_rock(s: &Section, default_step_m: f64) -> InputResult<BitRock> {
    s.check_known(BIT_ROCK_KEYS)?;
    let law = s.string("law")?.unwrap_or_else(|| "ho".into());
    if law != "ho" {
        return Err(s.error("law", format!("unknown bit-rock law `{law}` (expected ho)")));
    }
    let beta = s.number("lateral_drillability")?.unwrap_or(1.0);
    if !(beta > 0.0 && beta <= 1.0) {
        return Err(s.error("lateral_drillability", format!("{beta} outside (0, 1]")));
    }
    let walk = s.quantity("walk_angle", D::Angle, "deg")?.unwrap_or(0.0);
    let ir = s.number("rock_anisotropy")?.unwrap_or(0.0);
    if !(-0.5..=0.5).contains(&ir) {
        return Err(s.error("rock_anisotropy", format!("{ir} outside [-0.5, 0.5]")));
    }
    let dip = s.quantity("dip", D::Angle, "deg")?.unwrap_or(0.0);
    let dipdir = s.quantity("dip_direction", D::Angle, "deg")?.unwrap_or(0.0);
    let step = s.positive("step", D::Length, "m", false)?.unwrap_or(default_step_m);
    if step < crate::case::bit_rock::MIN_STEP_M - 1e-9 {
        return Err(s.error(
            "step",
            format!(
                "{step} m is shorter than the shortest prediction step accepted, {} m",
                crate::case::bit_rock::MIN_STEP_M
            ),
        ));
    }
    let bit_friction = s.number("bit_friction")?.unwrap_or(0.25);
    let mut formations = Vec::new();
    if let Some(fs) = s.tables("formations")? {
        for f in fs {
            f.check_known(FORMATION_KEYS)?;
            let from = f.req_quantity("from_md", D::Length, "m")?;
            let to = f.req_quantity("to_md", D::Length, "m")?;
            if to <= from {
                return Err(f.error("to_md", "to_md must exceed from_md"));
            }
            let fi = f.number("rock_anisotropy")?.unwrap_or(ir);
            let fd = f.quantity("dip", D::Angle, "deg")?.unwrap_or(dip);
            let fdd = f.quantity("dip_direction", D::Angle, "deg")?.unwrap_or(dipdir);
            formations.push(Formation {
                from_md_m: from,
                to_md_m: to,
                rock_anisotropy: fi,
                dip_rad: fd,
                dip_direction_rad: fdd,
            });
        }
    }
    Ok(BitRock {
        law,
        lateral_drillability: beta,
        walk_angle_rad: walk,
        rock_anisotropy: ir,
        dip_rad: dip,
        dip_direction_rad: dipdir,
        formations,
        step_m: step,
        bit_friction,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A case file in `wells/j-shape` (so that its `survey.csv` is found).
    fn j_shape() -> PathBuf {
        Path::new(env!("CARGO_MANIFEST_DIR")).join("wells/j-shape/case.toml")
    }

    fn err(text: &[u8]) -> String {
        match parse_case(text, &j_shape(), &CaseOverrides::default()) {
            Ok(_) => panic!("expected an error"),
            Err(e) => e.to_string(),
        }
    }

    #[test]
    fn syntax_error_at_the_end_is_on_the_last_line() {
        // Found by tests/verification/fuzz_input.rs: an unterminated string at the end of a
        // file ending with a line end was reported on the line after the last one.
        let e = err(b"[well]\nsurvey = \"survey.csv\"\nname = \"\"\"x\n");
        assert!(e.contains("case.toml: line 3: TOML syntax error"), "{e}");
        assert_eq!(line_of(b"a\nb\n", 4), 2);
        assert_eq!(line_of(b"a\nb", 3), 2);
        assert_eq!(line_of(b"a\nb\n", 2), 2);
        assert_eq!(line_of(b"", 0), 1);
    }

    #[test]
    fn not_utf8_names_the_line() {
        let e = err(b"name = \"x\"\n\n[well]\nsurvey = \"\xB0.csv\"\n");
        assert!(
            e.contains("case.toml: line 4: the case file is not valid UTF-8 text (byte 0xB0)"),
            "{e}"
        );
    }

    #[test]
    fn survey_that_is_a_directory_is_named_by_its_key() {
        // Found while writing the fuzz test (by reading, before it ran): `survey = ""` named the
        // directory in a file-level error ("cannot read the survey file: Is a directory").
        let e = err(b"[well]\nsurvey = \"\"\nhole = [{ to_md = \"2600 m\", diameter = \"8.5 in\" }]\n");
        assert!(
            e.contains("case.toml: key `well.survey`: ") && e.contains("is not a file"),
            "{e}"
        );
    }
}
