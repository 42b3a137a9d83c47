//! Header names of survey files: which column is the measured depth, the inclination and the
//! azimuth, the unit each one is in, and the azimuth reference a qualified azimuth column
//! states (`Azimuth Grid`, `Azi (true)`).

use std::f64::consts::PI;
use std::path::Path;

use super::SurveyUnits;
use crate::case::AzimuthReference;
use crate::error::{InputError, InputResult};
use crate::units::{lookup_dim, Dimension, Unit};

/// The three columns the reader needs.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Role {
    Md,
    Inc,
    Azi,
}

impl Role {
    pub(super) const ALL: [Role; 3] = [Role::Md, Role::Inc, Role::Azi];

    /// Short name, as in [`crate::geometry::survey::SurveyProblem::field`].
    pub(super) fn key(self) -> &'static str {
        match self {
            Role::Md => "md",
            Role::Inc => "inc",
            Role::Azi => "azi",
        }
    }

    pub(super) fn what(self) -> &'static str {
        match self {
            Role::Md => "measured depth",
            Role::Inc => "inclination",
            Role::Azi => "azimuth",
        }
    }

    /// Accepted md and inc header names after [`normalize_name`] (azimuths: [`azimuth_name`]).
    fn names(self) -> &'static [&'static str] {
        match self {
            Role::Md => &["md", "measureddepth", "measdepth", "depth"],
            Role::Inc => &["inc", "incl", "inclination"],
            Role::Azi => &[],
        }
    }

    /// The accepted names as written in messages.
    fn spellings(self) -> &'static str {
        match self {
            Role::Md => "`md`, `measured depth`, `meas. depth` or `depth`",
            Role::Inc => "`inc`, `incl` or `inclination`",
            Role::Azi => {
                "`azi`, `az`, `azim` or `azimuth`, optionally qualified `grid`, `true` or `magnetic` (`Azimuth Grid`, `True Azimuth`, `Azi (true)`)"
            }
        }
    }

    fn dimension(self) -> Dimension {
        match self {
            Role::Md => Dimension::Length,
            Role::Inc | Role::Azi => Dimension::Angle,
        }
    }

    fn default_unit(self) -> Unit {
        match self {
            Role::Md => Unit {
                name: "m",
                dimension: Dimension::Length,
                to_si: 1.0,
            },
            Role::Inc | Role::Azi => Unit {
                name: "deg",
                dimension: Dimension::Angle,
                to_si: PI / 180.0,
            },
        }
    }

    fn override_unit(self, units: &SurveyUnits) -> Option<Unit> {
        match self {
            Role::Md => units.md,
            Role::Inc | Role::Azi => units.angle,
        }
    }
}

/// A column found in the header.
#[derive(Debug, Clone)]
pub(super) struct Column {
    pub(super) role: Role,
    /// 0-based field index.
    pub(super) index: usize,
    /// Header text as written (quotes removed, trimmed).
    pub(super) header: String,
    /// Unit written in the header or the units line, if any.
    pub(super) unit: Option<String>,
    /// Line where that unit is written (the header line when there is none).
    pub(super) unit_line: usize,
    /// The north a qualified azimuth column names (unspecified for the others).
    pub(super) reference: AzimuthReference,
}

/// Split a header into (name, unit text): `MD [ft]`, `md ( ft )`, `md_ft`, `inc_deg`, `azi_rad`.
pub(crate) fn split_header_unit(header: &str) -> (&str, Option<&str>) {
    let t = header.trim();
    for (open, close) in [('[', ']'), ('(', ')')] {
        if let Some(inner) = t.strip_suffix(close) {
            if let Some(p) = inner.rfind(open) {
                return (&inner[..p], Some(inner[p + open.len_utf8()..].trim()));
            }
        }
    }
    for suffix in ["_ft", "_m", "_deg", "_rad"] {
        if t.len() > suffix.len() && t.is_char_boundary(t.len() - suffix.len()) {
            let (name, tail) = t.split_at(t.len() - suffix.len());
            if tail.eq_ignore_ascii_case(suffix) {
                return (name, Some(&tail[1..]));
            }
        }
    }
    (t, None)
}

/// Lower case, without spaces, underscores, hyphens, dots and brackets.
pub(crate) fn normalize_name(name: &str) -> String {
    name.chars()
        .filter(|c| !c.is_whitespace() && !matches!(c, '_' | '-' | '.' | '(' | ')' | '[' | ']'))
        .flat_map(char::to_lowercase)
        .collect()
}

/// Qualifiers of an azimuth name, after [`normalize_name`].
const QUALIFIERS: &[(&str, AzimuthReference)] = &[
    ("grid", AzimuthReference::Grid),
    ("gridnorth", AzimuthReference::Grid),
    ("gn", AzimuthReference::Grid),
    ("true", AzimuthReference::True),
    ("truenorth", AzimuthReference::True),
    ("tn", AzimuthReference::True),
    ("magnetic", AzimuthReference::Magnetic),
    ("magneticnorth", AzimuthReference::Magnetic),
    ("mag", AzimuthReference::Magnetic),
    ("mn", AzimuthReference::Magnetic),
];

/// The reference named by a qualifier word (`Grid`, `true north`, `MAG`), if it is one.
pub(super) fn reference_word(text: &str) -> Option<AzimuthReference> {
    let norm = normalize_name(text);
    QUALIFIERS.iter().find(|(q, _)| *q == norm).map(|(_, r)| *r)
}

/// The reference of a normalized azimuth name: `azimuth`, `azi`, `azim`, `az`, alone or with a
/// qualifier before or after (`azimuthgrid`, `trueazimuth`); `None` if it is not one.
fn azimuth_name(norm: &str) -> Option<AzimuthReference> {
    let qualifier = |rest: &str| {
        if rest.is_empty() {
            Some(AzimuthReference::Unspecified)
        } else {
            QUALIFIERS.iter().find(|(q, _)| *q == rest).map(|(_, r)| *r)
        }
    };
    for base in ["azimuth", "azim", "azi", "az"] {
        if let Some(r) = norm.strip_prefix(base).and_then(qualifier) {
            return Some(r);
        }
        if let Some(rest) = norm.strip_suffix(base) {
            if !rest.is_empty() {
                if let Some(r) = qualifier(rest) {
                    return Some(r);
                }
            }
        }
    }
    None
}

/// The role, unit text and azimuth reference of one header field, if it names a needed column.
fn classify(header: &str) -> Option<(Role, Option<&str>, AzimuthReference)> {
    let (name, unit) = split_header_unit(header);
    let norm = normalize_name(name);
    if let Some(role) = [Role::Md, Role::Inc]
        .into_iter()
        .find(|r| r.names().contains(&norm.as_str()))
    {
        return Some((role, unit, AzimuthReference::Unspecified));
    }
    let named = azimuth_name(&norm)?;
    // `Azi (grid)`: the bracket holds the qualifier, not a unit
    match unit.and_then(reference_word) {
        Some(r) if named == AzimuthReference::Unspecified || named == r => Some((Role::Azi, None, r)),
        Some(_) => None,
        None => Some((Role::Azi, unit, named)),
    }
}

/// True if `fields` name the three needed columns (a header, perhaps with problems
/// [`find_columns`] reports).
pub(super) fn names_all_roles<S: AsRef<str>>(fields: &[S]) -> bool {
    let roles: Vec<Role> = fields
        .iter()
        .filter_map(|f| classify(f.as_ref()).map(|c| c.0))
        .collect();
    Role::ALL.iter().all(|r| roles.contains(r))
}

/// Find the md, inc and azi columns (in that order) in the header `fields` of line `line`.
pub(super) fn find_columns<S: AsRef<str>>(fields: &[S], path: &Path, line: usize) -> InputResult<[Column; 3]> {
    let mut found: [Option<Column>; 3] = [None, None, None];
    for (index, h) in fields.iter().map(AsRef::as_ref).enumerate() {
        let Some((role, unit, reference)) = classify(h) else {
            continue;
        };
        let k = Role::ALL.iter().position(|r| *r == role).unwrap_or(0);
        if let Some(prev) = &found[k] {
            let message = if role == Role::Azi {
                format!(
                    "two azimuth columns: `{}` (field {}, {}) and `{h}` (field {}, {}); drillpath reads one: delete the column you do not want, or rename its header to a name that is not an azimuth (e.g. `unused`)",
                    prev.header,
                    prev.index + 1,
                    prev.reference.describe(),
                    index + 1,
                    reference.describe()
                )
            } else {
                format!(
                    "two columns look like the {} column: `{}` (field {}) and `{h}` (field {}); rename or remove one of them",
                    role.what(),
                    prev.header,
                    prev.index + 1,
                    index + 1
                )
            };
            return Err(InputError::line(path, line, Some(h), message));
        }
        found[k] = Some(Column {
            role,
            index,
            header: h.to_string(),
            unit: unit.map(str::to_string),
            unit_line: line,
            reference,
        });
    }
    match found {
        [Some(md), Some(inc), Some(azi)] => Ok([md, inc, azi]),
        _ => {
            let k = found.iter().position(Option::is_none).unwrap_or(0);
            let role = Role::ALL[k];
            let listed = listed_columns(fields.iter().map(|h| h.as_ref()));
            Err(InputError::line(
                path,
                line,
                None,
                format!(
                    "the header has no {} column (named {}, optionally with a unit such as `{} [{}]`); the header's columns are: {listed}",
                    role.what(),
                    role.spellings(),
                    role.key(),
                    role.default_unit().name,
                ),
            ))
        }
    }
}

/// The unit text of a units-line field: `(ft)`, `[ deg ]`; `None` if it is not bracketed.
fn bracketed(field: &str) -> Option<&str> {
    let t = field.trim();
    let inner = t
        .strip_prefix('(')
        .and_then(|r| r.strip_suffix(')'))
        .or_else(|| t.strip_prefix('[').and_then(|r| r.strip_suffix(']')))?;
    Some(inner.trim())
}

/// True if `fields` are a units line: at least one field, each non-empty field a unit in
/// brackets (`(ft)  (deg)  (deg)`).
pub(super) fn is_units_line<S: AsRef<str>>(fields: &[S]) -> bool {
    let mut any = false;
    for f in fields.iter().map(AsRef::as_ref) {
        if f.trim().is_empty() {
            continue;
        }
        if bracketed(f).is_none() {
            return false;
        }
        any = true;
    }
    any
}

/// Take the units of the needed columns from the units line `fields` (line `line`); a unit
/// also written in a column's header must be the same.
pub(super) fn apply_units_line<S: AsRef<str>>(
    columns: &mut [Column; 3],
    fields: &[S],
    path: &Path,
    line: usize,
) -> InputResult<()> {
    for col in columns.iter_mut() {
        let Some(unit) = fields.get(col.index).and_then(|f| bracketed(f.as_ref())) else {
            continue;
        };
        if unit.is_empty() {
            continue;
        }
        let dim = col.role.dimension();
        let from_line = lookup_dim(unit, dim).map_err(|m| {
            InputError::line(
                path,
                line,
                Some(&col.header),
                format!("{m} in the units line, under the {} column", col.role.what()),
            )
        })?;
        if let Some(written) = &col.unit {
            let same = lookup_dim(written, dim).is_ok_and(|u| u.name == from_line.name);
            if !same {
                return Err(InputError::line(
                    path,
                    line,
                    Some(&col.header),
                    format!(
                        "the units line says the {} is in `{unit}` but its header says `{written}`; make them agree",
                        col.role.what()
                    ),
                ));
            }
        }
        col.unit = Some(unit.to_string());
        col.unit_line = line;
    }
    Ok(())
}

/// The unit of a column: from its header or the units line, else from the override, else the
/// default; notes say which was assumed and why.
pub(super) fn column_unit(
    col: &Column,
    units: &SurveyUnits,
    path: &Path,
    notes: &mut Vec<String>,
) -> InputResult<Unit> {
    let dim = col.role.dimension();
    let over = col.role.override_unit(units);
    if let Some(o) = over {
        if o.dimension != dim {
            return Err(InputError::file(
                path,
                format!(
                    "the {} unit given by the case file or command line, `{}`, is a {} unit, expected a {dim} unit",
                    col.role.what(),
                    o.name,
                    o.dimension
                ),
            ));
        }
    }
    let line = col.unit_line;
    match (&col.unit, over) {
        (Some(text), over) => {
            let u = lookup_dim(text, dim).map_err(|m| {
                InputError::line(
                    path,
                    line,
                    Some(&col.header),
                    format!("{m} in the header of the {} column", col.role.what()),
                )
            })?;
            if let Some(o) = over {
                if o.name != u.name {
                    return Err(InputError::line(
                        path,
                        line,
                        Some(&col.header),
                        format!(
                            "the header says the {} is in {} but the case file or command line says {}; remove one of them or make them agree",
                            col.role.what(),
                            u.name,
                            o.name
                        ),
                    ));
                }
            }
            Ok(u)
        }
        (None, Some(o)) => {
            notes.push(format!(
                "{} column `{}` has no unit in its header: assumed {} (from the case file or command line)",
                col.role.key(),
                col.header,
                o.name
            ));
            Ok(o)
        }
        (None, None) => {
            let d = col.role.default_unit();
            notes.push(format!(
                "{} column `{}` has no unit in its header: assumed {} (the default; write e.g. `{} [{}]` in the header or give the unit in the case file to change it)",
                col.role.key(),
                col.header,
                d.name,
                col.role.key(),
                if col.role == Role::Md { "ft" } else { "rad" }
            ));
            Ok(d)
        }
    }
}

/// The units of the three columns ([`column_unit`]).
pub(super) fn column_units(
    columns: &[Column; 3],
    units: &SurveyUnits,
    path: &Path,
    notes: &mut Vec<String>,
) -> InputResult<[Unit; 3]> {
    Ok([
        column_unit(&columns[0], units, path, notes)?,
        column_unit(&columns[1], units, path, notes)?,
        column_unit(&columns[2], units, path, notes)?,
    ])
}

#[cfg(test)]
mod tests {
    use super::*;
    use AzimuthReference as R;

    fn role(h: &str) -> Option<(Role, Option<&str>, AzimuthReference)> {
        classify(h)
    }

    #[test]
    fn names_of_exported_reports() {
        // (header, role, unit, reference): the variants of issue 18 (9) and the old ones
        let cases: &[(&str, Role, Option<&str>, AzimuthReference)] = &[
            ("Measured Depth ( ft )", Role::Md, Some("ft"), R::Unspecified),
            ("MD", Role::Md, None, R::Unspecified),
            ("Meas. Depth [m]", Role::Md, Some("m"), R::Unspecified),
            ("md_ft", Role::Md, Some("ft"), R::Unspecified),
            ("Incl.", Role::Inc, None, R::Unspecified),
            ("Inc", Role::Inc, None, R::Unspecified),
            ("Inclination (deg)", Role::Inc, Some("deg"), R::Unspecified),
            ("INC [ ° ]", Role::Inc, Some("°"), R::Unspecified),
            ("Azi.", Role::Azi, None, R::Unspecified),
            ("Azim", Role::Azi, None, R::Unspecified),
            ("Azimuth Grid ( deg )", Role::Azi, Some("deg"), R::Grid),
            ("Azimuth True", Role::Azi, None, R::True),
            ("True Azimuth [deg]", Role::Azi, Some("deg"), R::True),
            ("Azi (grid)", Role::Azi, None, R::Grid),
            ("Azimuth (True) (deg)", Role::Azi, Some("deg"), R::True),
            ("azi_mag_deg", Role::Azi, Some("deg"), R::Magnetic),
            ("Azimuth Magnetic North", Role::Azi, None, R::Magnetic),
            ("AZ-GN", Role::Azi, None, R::Grid),
        ];
        for &(h, r, u, reference) in cases {
            assert_eq!(role(h), Some((r, u, reference)), "{h}");
        }
        for h in [
            "At Azim",
            "Closure Azimuth",
            "VS Azimuth",
            "TVD",
            "Azimuth Grid (true)",
            "dls [deg/100ft]",
            "Incl Azim",
        ] {
            assert_eq!(role(h), None, "{h}");
        }
    }

    #[test]
    fn two_azimuth_columns_are_named_with_the_way_out() {
        let e = find_columns(&["MD", "Inc", "Azimuth Grid", "Azimuth True"], Path::new("s.csv"), 4)
            .unwrap_err()
            .to_string();
        assert!(e.starts_with("s.csv: line 4, column `Azimuth True`"), "{e}");
        assert!(
            e.contains("`Azimuth Grid` (field 3, grid north)") && e.contains("`Azimuth True` (field 4, true north)"),
            "{e}"
        );
        assert!(e.contains("delete the column you do not want"), "{e}");
    }

    #[test]
    fn units_line_fields() {
        assert!(is_units_line(&["(ft)", "(deg)", "", "[ deg ]"]));
        assert!(!is_units_line(&["", " "]));
        assert!(!is_units_line(&["(ft)", "0"]));
        let mut cols = find_columns(&["MD", "INC", "AZI [deg]"], Path::new("r.txt"), 3).unwrap();
        apply_units_line(&mut cols, &["(ft)", "(deg)", "( deg )"], Path::new("r.txt"), 4).unwrap();
        assert_eq!(cols[0].unit.as_deref(), Some("ft"));
        assert_eq!(cols[0].unit_line, 4);
        let e = apply_units_line(&mut cols, &["(ft)", "(deg)", "(rad)"], Path::new("r.txt"), 4)
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("r.txt: line 4, column `AZI [deg]`") && e.contains("agree"),
            "{e}"
        );
        let e = apply_units_line(&mut cols, &["(furlong)"], Path::new("r.txt"), 4)
            .unwrap_err()
            .to_string();
        assert!(e.contains("r.txt: line 4, column `MD`") && e.contains("furlong"), "{e}");
    }
}

/// Longest column name quoted whole in a message, characters.
pub const MAX_LISTED_NAME_CHARS: usize = 40;

/// Most columns listed in a message.
pub const MAX_LISTED_COLUMNS: usize = 12;

/// The header's column names for a message, each quoted: long names cut after
/// [`MAX_LISTED_NAME_CHARS`] characters and the list after [`MAX_LISTED_COLUMNS`] names (a file
/// that is not a survey table, such as a one-line XML export, would otherwise be echoed whole).
fn listed_columns<'a>(names: impl Iterator<Item = &'a str>) -> String {
    let names: Vec<&str> = names.collect();
    let mut out: Vec<String> = names
        .iter()
        .take(MAX_LISTED_COLUMNS)
        .map(|h| {
            let cut: String = h.chars().take(MAX_LISTED_NAME_CHARS).collect();
            if cut.len() < h.len() {
                format!("`{cut}...` ({} characters)", h.chars().count())
            } else {
                format!("`{h}`")
            }
        })
        .collect();
    if names.len() > MAX_LISTED_COLUMNS {
        out.push(format!("and {} more", names.len() - MAX_LISTED_COLUMNS));
    }
    out.join(", ")
}

#[cfg(test)]
mod listed_tests {
    use super::*;

    #[test]
    fn long_headers_are_cut_in_messages() {
        let long = "x".repeat(500);
        let s = listed_columns([long.as_str(), "md"].into_iter());
        assert!(
            s.contains("(500 characters)") && s.contains("`md`") && s.len() < 120,
            "{s}"
        );
        let many: Vec<String> = (0..20).map(|k| format!("c{k}")).collect();
        let s = listed_columns(many.iter().map(|x| x.as_str()));
        assert!(s.ends_with("and 8 more"), "{s}");
    }
}
