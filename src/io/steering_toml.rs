//! Steering plans of a case (docs/guide.md, "Steering plans"): the `[[steering]]` intervals of
//! the case file and the slide sheet CSV it names (`slide_sheet`), merged into one
//! [`SteeringPlan`] whose intervals run forward and do not overlap.

use super::survey::{detect_delimiter, normalize_name, split_fields, split_header_unit};
use super::toml_reader::Section;
use crate::case::{SteeringInterval, SteeringPlan};
use crate::error::{InputError, InputResult};
use crate::units::{lookup_dim, parse_quantity, Dimension as D};
use std::path::Path;

/// Keys accepted in a `[[steering]]` interval.
pub const STEERING_KEYS: &[&str] = &["from_md", "to_md", "mode", "toolface", "ratio"];

/// Where an interval came from, for messages.
enum Origin {
    /// `[[steering]]` number k (0-based).
    Table(usize),
    /// Line of the slide sheet (1-based).
    Line(usize),
}

/// The steering plan of the case file `top` (its `[[steering]]` tables and the `slide_sheet`
/// it names, relative to `dir`); `default_toolface_rad` is the toolface of an interval that
/// gives none (the operation's); `has_rss`: the string has a rotary steerable system (a
/// `ratio` is refused without one).
pub fn read_steering(top: &Section, dir: &Path, default_toolface_rad: f64, has_rss: bool) -> InputResult<SteeringPlan> {
    let mut all: Vec<(SteeringInterval, Origin)> = Vec::new();
    let tables = top.tables("steering")?.unwrap_or_default();
    for (k, t) in tables.iter().enumerate() {
        t.check_known(STEERING_KEYS)?;
        let from = t.req_quantity("from_md", D::Length, "m")?;
        let to = t.req_quantity("to_md", D::Length, "m")?;
        if to <= from {
            return Err(t.error(
                "to_md",
                "to_md must be deeper than from_md (intervals run down the hole)",
            ));
        }
        let mode = t
            .string("mode")?
            .ok_or_else(|| t.error("mode", "missing mode (slide or rotate)"))?;
        let rotating = parse_mode(&mode).ok_or_else(|| t.error("mode", unknown_mode(&mode)))?;
        let tf = t.quantity("toolface", D::Angle, "deg")?.unwrap_or(default_toolface_rad);
        let ratio = super::rss_toml::read_ratio(t, "ratio")?;
        if ratio.is_some() && !has_rss {
            return Err(t.error(
                "ratio",
                "a steering ratio needs a rotary steerable system (an `rss` component) in the string",
            ));
        }
        let mut iv = interval(from, to, rotating, tf);
        iv.ratio = ratio;
        all.push((iv, Origin::Table(k)));
    }
    let sheet_path = top.string("slide_sheet")?.map(|rel| dir.join(rel));
    if let Some(path) = &sheet_path {
        if !path.is_file() {
            return Err(top.error("slide_sheet", format!("slide sheet `{}` not found", path.display())));
        }
        let text = std::fs::read_to_string(path)
            .map_err(|e| InputError::file(path, format!("cannot read the slide sheet: {e}")))?;
        all.extend(read_sheet(&text, path, default_toolface_rad, has_rss)?);
    }
    all.sort_by(|a, b| a.0.from_md_m.total_cmp(&b.0.from_md_m));
    for w in all.windows(2) {
        let (prev, next) = (&w[0].0, &w[1]);
        if next.0.from_md_m < prev.to_md_m - 1e-9 {
            let msg = format!(
                "this interval ({:.2} to {:.2} m) overlaps the one from {:.2} to {:.2} m",
                next.0.from_md_m, next.0.to_md_m, prev.from_md_m, prev.to_md_m
            );
            return Err(match (&next.1, &sheet_path) {
                (Origin::Table(k), _) => top.error(&format!("steering[{k}].from_md"), msg),
                (Origin::Line(l), Some(p)) => InputError::line(p, *l, Some("md_from"), msg),
                (Origin::Line(_), None) => unreachable!("a sheet line without a sheet"),
            });
        }
    }
    Ok(SteeringPlan {
        intervals: all.into_iter().map(|(iv, _)| iv).collect(),
        sheet_path,
    })
}

fn interval(from: f64, to: f64, rotating: bool, toolface_rad: f64) -> SteeringInterval {
    SteeringInterval {
        from_md_m: from,
        to_md_m: to,
        rotating,
        toolface_rad: toolface_rad.rem_euclid(std::f64::consts::TAU),
        ratio: None,
    }
}

/// `slide`/`sliding` (false) or `rotate`/`rotating` (true), case-insensitive.
fn parse_mode(s: &str) -> Option<bool> {
    match s.trim().to_ascii_lowercase().as_str() {
        "slide" | "sliding" => Some(false),
        "rotate" | "rotating" => Some(true),
        _ => None,
    }
}

fn unknown_mode(s: &str) -> String {
    format!("unknown mode `{s}` (expected slide or rotate)")
}

/// The columns of a slide sheet: their names after [`normalize_name`].
const COLUMNS: [(&str, &[&str]); 5] = [
    ("md_from", &["mdfrom", "from", "frommd", "top", "mdtop"]),
    ("md_to", &["mdto", "to", "tomd", "bottom", "mdbottom"]),
    ("mode", &["mode", "slideorrotate"]),
    ("toolface_deg", &["toolface", "tf", "toolfaceangle"]),
    ("ratio", &["ratio", "steeringratio", "dutycycle"]),
];

/// The intervals of the slide sheet `text` (file `path`): a header naming the columns
/// `md_from,md_to,mode,toolface_deg` (found by name, in any order, units in brackets or as a
/// suffix: `_m`, `_ft`, `[ft]`, `_deg`), then one interval per line; blank and `#` lines
/// skipped. The toolface cell may be empty (then `default_toolface_rad`). An optional `ratio`
/// column sets a rotary steerable system's steering ratio (in [0, 1]; refused when `has_rss` is
/// false); an empty cell keeps the tool's.
fn read_sheet(
    text: &str,
    path: &Path,
    default_toolface_rad: f64,
    has_rss: bool,
) -> InputResult<Vec<(SteeringInterval, Origin)>> {
    let mut lines = text
        .lines()
        .enumerate()
        .map(|(i, l)| (i + 1, l.trim().trim_start_matches('\u{feff}')))
        .filter(|(_, l)| !l.is_empty() && !l.starts_with('#'));
    let Some((hl, header)) = lines.next() else {
        return Err(InputError::file(
            path,
            "the slide sheet is empty (a header md_from,md_to,mode,toolface_deg and one line per interval)",
        ));
    };
    let delim = detect_delimiter(header);
    let fields = split_fields(header, delim);
    let mut index = [usize::MAX; 5];
    let mut units: [Option<String>; 5] = Default::default();
    for (i, f) in fields.iter().enumerate() {
        let (name, unit) = split_header_unit(f);
        let norm = normalize_name(name);
        if let Some(c) = COLUMNS.iter().position(|(_, names)| names.contains(&norm.as_str())) {
            if index[c] != usize::MAX {
                return Err(InputError::line(
                    path,
                    hl,
                    Some(COLUMNS[c].0),
                    "two columns name this role",
                ));
            }
            index[c] = i;
            units[c] = unit.map(str::to_string);
        }
    }
    for (c, (name, _)) in COLUMNS.iter().enumerate().take(3) {
        if index[c] == usize::MAX {
            return Err(InputError::line(
                path,
                hl,
                Some(name),
                format!("the header has no `{name}` column (md_from,md_to,mode,toolface_deg)"),
            ));
        }
    }
    let md_unit = |c: usize| -> InputResult<String> {
        match &units[c] {
            Some(u) => lookup_dim(u, D::Length)
                .map(|_| u.clone())
                .map_err(|m| InputError::line(path, hl, Some(COLUMNS[c].0), m)),
            None => Ok("m".into()),
        }
    };
    let (from_unit, to_unit) = (md_unit(0)?, md_unit(1)?);
    let tf_unit = units[3].clone().unwrap_or_else(|| "deg".into());
    let mut out = Vec::new();
    for (line, l) in lines {
        let cells = split_fields(l, delim);
        let cell = |c: usize| cells.get(index[c]).map(String::as_str).unwrap_or("").trim();
        let number = |c: usize, dim: D, unit: &str| -> InputResult<f64> {
            parse_quantity(cell(c), dim, unit).map_err(|m| InputError::line(path, line, Some(COLUMNS[c].0), m))
        };
        let from = number(0, D::Length, &from_unit)?;
        let to = number(1, D::Length, &to_unit)?;
        if to <= from {
            return Err(InputError::line(
                path,
                line,
                Some("md_to"),
                "md_to must be deeper than md_from (intervals run down the hole)",
            ));
        }
        let rotating =
            parse_mode(cell(2)).ok_or_else(|| InputError::line(path, line, Some("mode"), unknown_mode(cell(2))))?;
        let tf = if index[3] == usize::MAX || cell(3).is_empty() {
            default_toolface_rad
        } else {
            number(3, D::Angle, &tf_unit)?
        };
        let mut iv = interval(from, to, rotating, tf);
        if index[4] != usize::MAX && !cell(4).is_empty() {
            let err = |m: &str| InputError::line(path, line, Some("ratio"), m);
            let r: f64 = cell(4)
                .parse()
                .map_err(|_| err(&format!("`{}` is not a number", cell(4))))?;
            if !(0.0..=1.0).contains(&r) {
                return Err(err(&format!("steering ratio {} outside [0, 1]", cell(4))));
            }
            if !has_rss {
                return Err(err(
                    "a steering ratio needs a rotary steerable system (an `rss` component) in the string",
                ));
            }
            iv.ratio = Some(r);
        }
        out.push((iv, Origin::Line(line)));
    }
    Ok(out)
}
