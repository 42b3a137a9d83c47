//! WITSML 1.4.1.1 `trajectory`: the survey stations of one trajectory object, with its
//! azimuth reference, declination and grid convergence, tie-in position, station types and
//! toolfaces, as a [`SurveyFile`].
//!
//! Rules (docs/guide.md, "WITSML trajectory"):
//! - `md`, `incl` and `azi` of every `trajectoryStation` are required, each with a `uom`
//!   (`m`, `ft`, `ftUS`, ...; `dega`, `rad`); a station without `incl` or `azi` is an error that
//!   names it (all such stations are counted and the first ones listed): never azimuth 0;
//! - `aziRef` (`grid north`, `true north`, `magnetic north`) sets the survey's azimuth
//!   reference; `magDeclUsed` and `gridCorUsed` are kept;
//! - the first station's `dispNs`, `dispEw` and `tvd` (the tie-in point's) are the position the
//!   minimum-curvature path starts from;
//! - stations whose `typeTrajStation` is not a measurement (projections, planned sections,
//!   interpolated, marker, formation and casing points) are kept apart, not in the survey;
//! - `gtf` and `mtf` are kept per station.

use std::path::Path;

use roxmltree::Node;

use super::{child_text, choose, line, measure, parse, root, LineIndex};
use crate::case::{AzimuthReference, StationInfo, SurveyFile};
use crate::error::{InputError, InputResult};
use crate::geometry::{Station, Survey};
use crate::units::Dimension;

/// Station types that are measurements (compared case-insensitively): the survey tools
/// (`gyro ...`, `magnetic ...`), the tie-in point, an MWD/gyro station given as `MD INCL and
/// AZI`, and `unknown` (a type nobody set: read as a measurement, with a note).
fn is_measurement(kind: &str) -> bool {
    let k = kind.trim().to_ascii_lowercase();
    k.starts_with("gyro")
        || k.starts_with("magnetic")
        || matches!(
            k.as_str(),
            "tie in point" | "unknown" | "md incl and azi" | "md and incl"
        )
}

/// One station as read.
struct Read<'a> {
    uid: &'a str,
    line: usize,
    md: super::Measure<'a>,
    incl: Option<super::Measure<'a>>,
    azi: Option<super::Measure<'a>>,
    info: StationInfo,
    /// `[dispNs, dispEw, tvd]`, SI, when all three are given.
    position: Option<[f64; 3]>,
}

/// Parse the WITSML text `text` (file `path`) and read its trajectory named or with uid
/// `wanted` (the only one when `None`).
pub fn parse_trajectory(text: &str, path: &Path, wanted: Option<&str>) -> InputResult<SurveyFile> {
    let doc = parse(text, path)?;
    let lines = LineIndex::new(text);
    let root = root(&doc, "trajectorys", path)?;
    let traj = choose(
        root,
        "trajectory",
        wanted,
        "`[well] survey_trajectory` (or `--trajectory`)",
        path,
    )?;
    let name = child_text(traj, "name").unwrap_or("(no name)").to_string();
    let uid = traj.attribute("uid").unwrap_or("");
    let what_traj = format!("trajectory `{name}`");
    let mut read = Vec::new();
    for (k, st) in traj
        .children()
        .filter(|c| c.is_element() && c.tag_name().name() == "trajectoryStation")
        .enumerate()
    {
        read.push(station(st, k, path, &lines)?);
    }
    if read.is_empty() {
        return Err(InputError::element(
            path,
            line(traj),
            what_traj,
            "has no `trajectoryStation`: the survey needs at least one station",
        ));
    }
    missing(&read, "incl", |r| r.incl.is_none(), path)?;
    missing(&read, "azi", |r| r.azi.is_none(), path)?;
    let (measured, projected): (Vec<Read>, Vec<Read>) = read.into_iter().partition(|r| is_measurement(&r.info.kind));
    let mut notes = vec![format!(
        "read as WITSML trajectory `{name}`{} of wellbore `{}`: {} stations{}",
        if uid.is_empty() {
            String::new()
        } else {
            format!(" (uid `{uid}`)")
        },
        child_text(traj, "nameWellbore").unwrap_or("(not named)"),
        measured.len() + projected.len(),
        type_counts(measured.iter().chain(projected.iter()))
    )];
    let Some(first) = measured.first() else {
        return Err(InputError::element(
            path,
            line(traj),
            what_traj,
            "has no measured station: every station is a projection or a planned point",
        ));
    };
    if !projected.is_empty() {
        notes.push(format!(
            "{} station(s) are not measurements and are left out of the survey: {}",
            projected.len(),
            listed(&projected)
        ));
    }
    let unknown = measured
        .iter()
        .filter(|r| r.info.kind.eq_ignore_ascii_case("unknown"))
        .count();
    if unknown > 0 {
        notes.push(format!(
            "{unknown} station(s) have the type `unknown` (or none): read as measurements"
        ));
    }
    let toolfaces = measured
        .iter()
        .filter(|r| r.info.gtf_rad.is_some() || r.info.mtf_rad.is_some())
        .count();
    if toolfaces > 0 {
        notes.push(format!(
            "toolfaces (gtf, mtf) kept on {toolfaces} of {} stations",
            measured.len()
        ));
    }
    let origin = first.position;
    if let Some([n, e, t]) = origin {
        notes.push(format!(
            "positions start from the first station's dispNs {n} m, dispEw {e} m, tvd {t} m (station `{}`, {})",
            first.uid, first.info.kind
        ));
    }
    let (reference, source, decl, conv) = reference(traj, &what_traj, path, &lines)?;
    let units = [
        first.md.unit.name,
        first.incl.map_or("deg", |m| m.unit.name),
        first.azi.map_or("deg", |m| m.unit.name),
    ];
    let stations: Vec<Station> = measured.iter().map(to_station).collect();
    let survey = Survey::new(stations).map_err(|p| {
        let r = &measured[p.index.min(measured.len() - 1)];
        let prev = p.index.checked_sub(1).and_then(|i| measured.get(i));
        let message = match (p.field, prev) {
            ("md", Some(prev)) if r.md.si <= prev.md.si => format!(
                "measured depth {} {} is not greater than {} {} of the station before it (`{}`, line {}); stations must be listed with MD strictly increasing",
                r.md.raw, r.md.unit.name, prev.md.raw, prev.md.unit.name, prev.uid, prev.line
            ),
            _ => p.message.clone(),
        };
        InputError::element(path, r.line, station_words(r), message)
    })?;
    Ok(SurveyFile {
        survey,
        md_unit: units[0].to_string(),
        inc_unit: units[1].to_string(),
        azi_unit: units[2].to_string(),
        notes,
        station_lines: measured.iter().map(|r| r.line).collect(),
        azimuth_reference: reference,
        azimuth_reference_source: source,
        magnetic_declination_rad: decl,
        grid_convergence_rad: conv,
        origin,
        station_info: measured.iter().map(|r| r.info.clone()).collect(),
        projected: projected.iter().map(|r| (to_station(r), r.info.clone())).collect(),
    })
}

fn to_station(r: &Read) -> Station {
    Station {
        md_m: r.md.si,
        inc_rad: r.incl.map_or(f64::NAN, |m| m.si),
        azi_rad: r.azi.map_or(f64::NAN, |m| m.si),
    }
}

/// ``station `uid` (MD 150.66 m)`` for messages.
fn station_words(r: &Read) -> String {
    format!("station `{}` (MD {} {})", r.uid, r.md.raw, r.md.unit.name)
}

/// Read one `trajectoryStation` (the `k`-th, 0-based).
fn station<'a>(st: Node<'a, '_>, k: usize, path: &Path, lines: &LineIndex) -> InputResult<Read<'a>> {
    let uid = st.attribute("uid").unwrap_or("");
    let line = lines.line(st);
    let what = if uid.is_empty() {
        format!("station {} (no uid, line {line})", k + 1)
    } else {
        format!("station `{uid}`")
    };
    let md = measure(st, "md", Dimension::Length, &what, path, lines)?.ok_or_else(|| {
        InputError::element(
            path,
            line,
            what.clone(),
            "has no `md` element: every station needs its measured depth",
        )
    })?;
    let what = format!("{what} (MD {} {})", md.raw, md.unit.name);
    let angle = |name: &str| measure(st, name, Dimension::Angle, &what, path, lines);
    let length = |name: &str| measure(st, name, Dimension::Length, &what, path, lines);
    let (incl, azi, gtf, mtf) = (angle("incl")?, angle("azi")?, angle("gtf")?, angle("mtf")?);
    // the position is used for the first station only (the start of the path)
    let position = if k == 0 {
        match (length("dispNs")?, length("dispEw")?, length("tvd")?) {
            (Some(n), Some(e), Some(t)) => Some([n.si, e.si, t.si]),
            _ => None,
        }
    } else {
        None
    };
    Ok(Read {
        uid: if uid.is_empty() { "(no uid)" } else { uid },
        line,
        md,
        incl,
        azi,
        info: StationInfo {
            uid: uid.to_string(),
            kind: child_text(st, "typeTrajStation").unwrap_or("unknown").to_string(),
            gtf_rad: gtf.map(|m| m.si),
            mtf_rad: mtf.map(|m| m.si),
        },
        position,
    })
}

/// An error naming the stations without the element `name` (`incl` or `azi`), if any.
fn missing(read: &[Read], name: &str, lacks: impl Fn(&Read) -> bool, path: &Path) -> InputResult<()> {
    let without: Vec<&Read> = read.iter().filter(|r| lacks(r)).collect();
    let Some(first) = without.first() else {
        return Ok(());
    };
    const SHOWN: usize = 5;
    let mut list: Vec<String> = without
        .iter()
        .take(SHOWN)
        .map(|r| format!("`{}` (MD {} {}, line {})", r.uid, r.md.raw, r.md.unit.name, r.line))
        .collect();
    if without.len() > SHOWN {
        list.push(format!("and {} more", without.len() - SHOWN));
    }
    let what = if name == "azi" { "azimuth" } else { "inclination" };
    Err(InputError::element(
        path,
        first.line,
        format!("element `{name}` of {}", station_words(first)),
        format!(
            "missing: {} of the {} stations have no `{name}` element ({what}): {}; drillpath never takes a missing {what} as 0: complete the survey or export it again",
            without.len(),
            read.len(),
            list.join(", ")
        ),
    ))
}

/// `(types: 1 tie in point, 32 magnetic MWD)`.
fn type_counts<'r, 'a: 'r>(reads: impl Iterator<Item = &'r Read<'a>>) -> String {
    let mut counts: Vec<(String, usize)> = Vec::new();
    for r in reads {
        match counts.iter_mut().find(|(k, _)| *k == r.info.kind) {
            Some((_, n)) => *n += 1,
            None => counts.push((r.info.kind.clone(), 1)),
        }
    }
    let parts: Vec<String> = counts.iter().map(|(k, n)| format!("{n} {k}")).collect();
    format!(" ({})", parts.join(", "))
}

/// The first stations of `reads` for a note.
fn listed(reads: &[Read]) -> String {
    let mut parts: Vec<String> = reads
        .iter()
        .take(5)
        .map(|r| format!("`{}` ({}, MD {} {})", r.uid, r.info.kind, r.md.raw, r.md.unit.name))
        .collect();
    if reads.len() > 5 {
        parts.push(format!("and {} more", reads.len() - 5));
    }
    parts.join(", ")
}

/// The azimuth reference (`aziRef`), where it is stated, and `magDeclUsed`, `gridCorUsed`.
fn reference(
    traj: Node,
    what: &str,
    path: &Path,
    lines: &LineIndex,
) -> InputResult<(AzimuthReference, String, Option<f64>, Option<f64>)> {
    let angle = |name: &str| -> InputResult<Option<f64>> {
        let Some(m) = measure(traj, name, Dimension::Angle, what, path, lines)? else {
            return Ok(None);
        };
        if m.si.abs() > std::f64::consts::PI {
            return Err(InputError::element(
                path,
                m.line,
                format!("element `{name}` of {what}"),
                format!("{} {} is not an angle between -180 and 180 deg", m.raw, m.unit.name),
            ));
        }
        Ok(Some(m.si))
    };
    let decl = angle("magDeclUsed")?;
    let conv = angle("gridCorUsed")?;
    let text = child_text(traj, "aziRef");
    let reference = match text.map(str::to_ascii_lowercase).as_deref() {
        Some("grid north") => AzimuthReference::Grid,
        Some("true north") => AzimuthReference::True,
        Some("magnetic north") => AzimuthReference::Magnetic,
        _ => AzimuthReference::Unspecified,
    };
    let mut source = match (text, reference) {
        (None, _) => String::new(),
        (Some(t), AzimuthReference::Unspecified) => {
            format!("element `aziRef` `{t}` (not a north drillpath knows: not used)")
        }
        (Some(t), _) => format!("element `aziRef` `{t}`"),
    };
    let mut extra = Vec::new();
    if let Some(d) = decl {
        extra.push(format!(
            "magDeclUsed {} deg",
            crate::units::message_number(d.to_degrees())
        ));
    }
    if let Some(c) = conv {
        extra.push(format!(
            "gridCorUsed {} deg",
            crate::units::message_number(c.to_degrees())
        ));
    }
    if !extra.is_empty() && !source.is_empty() {
        source = format!("{source}; {}", extra.join(", "));
    }
    Ok((reference, source, decl, conv))
}
