//! WITSML 1.4.1.1 `wbGeometry`: the hole sections of a wellbore as the case's hole
//! (`[well] hole_from = "FILE.xml"`).
//!
//! Rules (docs/guide.md, "WITSML hole geometry"): each `wbGeometrySection` needs `mdTop`,
//! `mdBottom` and `idSection` (the inner diameter: a casing's, a riser's or liner's bore, the
//! open hole's diameter); the sections, in any order in the file, are sorted by `mdTop` and
//! must follow one another without gap or overlap; cased sections (every type but `open
//! hole`) take the case's cased-hole friction when it gives one.

use std::path::Path;

use super::{child_text, choose, measure, parse, root, LineIndex};
use crate::error::{InputError, InputResult};
use crate::geometry::HoleSection;
use crate::units::Dimension;

/// One section as read.
#[derive(Debug, Clone)]
pub struct GeometrySection {
    /// The section's `uid`.
    pub uid: String,
    /// `typeHoleCasing` as written (`casing`, `riser`, `open hole`, ...).
    pub kind: String,
    /// Top MD, m.
    pub md_top_m: f64,
    /// Bottom MD, m.
    pub md_bottom_m: f64,
    /// Inner diameter, m.
    pub id_m: f64,
    /// 1-based line of the element.
    pub line: usize,
}

impl GeometrySection {
    /// True for an open-hole section (`typeHoleCasing` `open hole`), false for casing, liner,
    /// riser and the others.
    pub fn is_open_hole(&self) -> bool {
        self.kind.eq_ignore_ascii_case("open hole")
    }
}

/// Parse the WITSML text `text` (file `path`) and read the sections of its wbGeometry named or
/// with uid `wanted` (the only one when `None`), sorted by MD and checked to follow one another.
pub fn parse_geometry(text: &str, path: &Path, wanted: Option<&str>) -> InputResult<Vec<GeometrySection>> {
    let doc = parse(text, path)?;
    let lines = LineIndex::new(text);
    let root = root(&doc, "wbGeometrys", path)?;
    let geo = choose(root, "wbGeometry", wanted, "`[well] hole_from_geometry`", path)?;
    let mut sections = Vec::new();
    for s in geo
        .children()
        .filter(|c| c.is_element() && c.tag_name().name() == "wbGeometrySection")
    {
        let uid = s.attribute("uid").unwrap_or("(no uid)").to_string();
        let kind = child_text(s, "typeHoleCasing").unwrap_or("unknown").to_string();
        let what = format!("section `{uid}` ({kind})");
        let line = lines.line(s);
        let need = |name: &str| -> InputResult<f64> {
            measure(s, name, Dimension::Length, &what, path, &lines)?
                .map(|m| m.si)
                .ok_or_else(|| InputError::element(path, line, what.clone(), format!("has no `{name}` element")))
        };
        let (md_top_m, md_bottom_m, id_m) = (need("mdTop")?, need("mdBottom")?, need("idSection")?);
        if md_bottom_m <= md_top_m {
            return Err(InputError::element(
                path,
                line,
                what,
                format!("mdBottom {md_bottom_m} m is not below mdTop {md_top_m} m"),
            ));
        }
        if !(id_m > 0.0 && id_m <= 2.0) {
            return Err(InputError::element(
                path,
                line,
                format!("element `idSection` of {what}"),
                format!("{id_m} m is not a plausible hole or casing diameter"),
            ));
        }
        sections.push(GeometrySection {
            uid,
            kind,
            md_top_m,
            md_bottom_m,
            id_m,
            line,
        });
    }
    if sections.is_empty() {
        return Err(InputError::element(
            path,
            lines.line(geo),
            "the wbGeometry",
            "has no `wbGeometrySection`",
        ));
    }
    sections.sort_by(|a, b| a.md_top_m.total_cmp(&b.md_top_m));
    for w in sections.windows(2) {
        let (a, b) = (&w[0], &w[1]);
        if (b.md_top_m - a.md_bottom_m).abs() > 0.01 {
            let what = if b.md_top_m > a.md_bottom_m {
                "a gap"
            } else {
                "an overlap"
            };
            return Err(InputError::element(
                path,
                b.line,
                format!("section `{}` ({})", b.uid, b.kind),
                format!(
                    "{what} between it (mdTop {} m) and section `{}` ({}, mdBottom {} m, line {}): the sections must follow one another; drillpath takes one diameter at each MD (the innermost: give only the casing the string runs in)",
                    b.md_top_m, a.uid, a.kind, a.md_bottom_m, a.line
                ),
            ));
        }
    }
    Ok(sections)
}

/// The case's hole sections from `sections`: each to its `mdBottom` with its `idSection`, the
/// cased ones with `cased_friction` when given.
pub fn hole_sections(sections: &[GeometrySection], cased_friction: Option<f64>) -> Vec<HoleSection> {
    sections
        .iter()
        .map(|s| HoleSection {
            to_md_m: s.md_bottom_m,
            diameter_m: s.id_m,
            friction: if s.is_open_hole() { None } else { cased_friction },
        })
        .collect()
}
