//! WITSML 1.4.1.1 files (the industry's data standard for the rig's data store): the XML
//! document read safely, its root checked, one object chosen, and `uom`-tagged measures
//! converted to SI through [`crate::units::witsml_uom`].
//!
//! Safety rules (docs/guide.md, "WITSML files"):
//! - a file larger than [`MAX_XML_BYTES`] is refused before it is read;
//! - the text must be UTF-8 (a BOM is stripped);
//! - a document type declaration (`<!DOCTYPE ...>`, a DTD) is refused: no entity is ever
//!   expanded or fetched (so neither external entities nor "billion laughs" can do harm);
//! - malformed or truncated XML is refused with the line and column the parser stopped at;
//! - the root element must be the plural container of the object read (`trajectorys`), in the
//!   WITSML 1.x namespace (or none), with a `version` of 1.4.x when it has one.
//!
//! The XML parser is `roxmltree`; no XML is parsed by hand.

pub mod example;
pub mod geometry;
pub mod trajectory;
pub mod tubular;

use std::io::Read;
use std::path::Path;

use roxmltree::{Document, Node, ParsingOptions};

use crate::error::{InputError, InputResult};
use crate::units::{witsml_uom, Dimension, Unit};

/// Largest WITSML file read, bytes (16 MiB): far above the largest real trajectory we know of
/// (the 225 kB Volve F-4 file; a 1.2 MB trajectory of 480 stations with raw sensor data) and
/// small enough that the document tree stays well under a gigabyte.
pub const MAX_XML_BYTES: u64 = 16 * 1024 * 1024;

/// The WITSML 1.x data-object namespace.
pub const WITSML_1_NAMESPACE: &str = "http://www.witsml.org/schemas/1series";

/// Read the file at `path` as text for [`parse`]: refused beyond [`MAX_XML_BYTES`] or when
/// it is not UTF-8.
pub fn read_text(path: &Path) -> InputResult<String> {
    let cannot = |e: std::io::Error| InputError::file(path, format!("cannot read the WITSML file: {e}"));
    let file = std::fs::File::open(path).map_err(cannot)?;
    let mut bytes = Vec::new();
    file.take(MAX_XML_BYTES + 1).read_to_end(&mut bytes).map_err(cannot)?;
    text_of(bytes, path)
}

/// The text of the file contents `bytes` (see [`read_text`]); `path` only names it in messages.
pub fn text_of(bytes: Vec<u8>, path: &Path) -> InputResult<String> {
    if bytes.len() as u64 > MAX_XML_BYTES {
        return Err(InputError::file(
            path,
            format!(
                "the file is larger than {} MiB, the limit of a WITSML file drillpath reads (real trajectories are well under 2 MB); split the object or remove the raw sensor data",
                MAX_XML_BYTES / (1024 * 1024)
            ),
        ));
    }
    match String::from_utf8(bytes) {
        Ok(t) => Ok(t.strip_prefix('\u{feff}').map(str::to_string).unwrap_or(t)),
        Err(e) => {
            let at = e.utf8_error().valid_up_to();
            let line = e.as_bytes()[..at].iter().filter(|&&b| b == b'\n').count() + 1;
            Err(InputError::line(
                path,
                line,
                None,
                "the WITSML file is not UTF-8 text (the only encoding drillpath reads in XML); save it as UTF-8",
            ))
        }
    }
}

/// Parse `text` as XML with no DTD (see the module documentation).
pub fn parse<'a>(text: &'a str, path: &Path) -> InputResult<Document<'a>> {
    let options = ParsingOptions {
        allow_dtd: false,
        ..ParsingOptions::default()
    };
    Document::parse_with_options(text, options).map_err(|e| {
        let pos = e.pos();
        match e {
            roxmltree::Error::DtdDetected => {
                // the parser stops before saying where: the line of the declaration
                let at = text.find("<!DOCTYPE").unwrap_or(0);
                let line = text[..at].matches('\n').count() + 1;
                InputError::line(
                    path,
                    line,
                    None,
                    "the file has a document type declaration (`<!DOCTYPE`); WITSML files have none, and drillpath reads no DTD (entities are never expanded or fetched): remove it",
                )
            }
            roxmltree::Error::UnexpectedEndOfStream | roxmltree::Error::UnclosedRootNode | roxmltree::Error::NoRootNode => {
                InputError::line(
                path,
                text.trim_end().matches('\n').count() + 1,
                None,
                "the XML ends before its elements are closed: the file is truncated or empty",
                )
            }
            // the parser may place an error just past the last line end: name the last line
            e => InputError::line(
                path,
                (pos.row as usize).clamp(1, text.lines().count().max(1)),
                None,
                format!("not well-formed XML: {e} (line:column)"),
            ),
        }
    })
}

/// 1-based line where `node` starts (a scan of the text before it: for the few nodes named in
/// messages; [`LineIndex`] for many).
pub fn line(node: Node) -> usize {
    node.document().text_pos_at(node.range().start).row as usize
}

/// The byte offsets where the lines of a text start, to find the line of many nodes fast.
#[derive(Debug, Clone)]
pub struct LineIndex(Vec<usize>);

impl LineIndex {
    /// The index of `text`.
    pub fn new(text: &str) -> LineIndex {
        let starts = std::iter::once(0)
            .chain(text.match_indices('\n').map(|(i, _)| i + 1))
            .collect();
        LineIndex(starts)
    }

    /// 1-based line where `node` starts.
    pub fn line(&self, node: Node) -> usize {
        let at = node.range().start;
        self.0.partition_point(|&s| s <= at).max(1)
    }
}

/// The root element, which must be `plural` (e.g. `trajectorys`) in the WITSML 1.x namespace
/// (or none) and of version 1.4.x when it says.
pub fn root<'a, 'input>(doc: &'a Document<'input>, plural: &str, path: &Path) -> InputResult<Node<'a, 'input>> {
    let root = doc.root_element();
    let name = root.tag_name().name();
    let at = |m: String| InputError::element(path, line(root), format!("root element `{name}`"), m);
    if name != plural {
        let hint = match name {
            "trajectorys" | "wbGeometrys" | "tubulars" => {
                format!("a WITSML file of `{name}`, expected `{plural}` here")
            }
            "trajectory" | "wbGeometry" | "tubular" => {
                format!("a bare `{name}` object; WITSML 1.4.1.1 files wrap objects in their plural, `{name}s`")
            }
            _ => format!("not a WITSML 1.4.1.1 `{plural}` file"),
        };
        return Err(at(hint));
    }
    if let Some(ns) = root.tag_name().namespace() {
        if ns != WITSML_1_NAMESPACE {
            return Err(at(format!(
                "namespace `{ns}` is not WITSML 1.x (`{WITSML_1_NAMESPACE}`); drillpath reads WITSML 1.4.1.1 (WITSML 2.x objects are not read)"
            )));
        }
    }
    if let Some(v) = root.attribute("version") {
        if !v.trim().starts_with("1.4") {
            return Err(at(format!("version `{v}`: drillpath reads WITSML 1.4.1.1 (1.4.x)")));
        }
    }
    Ok(root)
}

/// The first child element of `node` named `name` (any namespace).
pub fn child<'a, 'input>(node: Node<'a, 'input>, name: &str) -> Option<Node<'a, 'input>> {
    node.children().find(|c| c.is_element() && c.tag_name().name() == name)
}

/// The trimmed text of the child element `name` of `node`, if it has one with text.
pub fn child_text<'a>(node: Node<'a, '_>, name: &str) -> Option<&'a str> {
    child(node, name)
        .and_then(|c| c.text())
        .map(str::trim)
        .filter(|t| !t.is_empty())
}

/// A measure read from a `uom`-tagged element.
#[derive(Debug, Clone, Copy)]
pub struct Measure<'a> {
    /// The value, SI.
    pub si: f64,
    /// The value as written.
    pub raw: &'a str,
    /// The unit it was written in.
    pub unit: Unit,
    /// 1-based line of the element.
    pub line: usize,
}

/// The child measure `name` of `node` in a unit of `dim`, if present (`lines` of the document's
/// text for its line); `what` describes `node`
/// in messages (e.g. ``station `S-3` (line 40)``). A missing or unknown `uom`, an empty or
/// non-numeric or non-finite value is an error naming the element.
pub fn measure<'a>(
    node: Node<'a, '_>,
    name: &str,
    dim: Dimension,
    what: &str,
    path: &Path,
    lines: &LineIndex,
) -> InputResult<Option<Measure<'a>>> {
    let Some(el) = child(node, name) else {
        return Ok(None);
    };
    let line = lines.line(el);
    let at = |m: String| InputError::element(path, line, format!("element `{name}` of {what}"), m);
    let Some(uom) = el.attribute("uom") else {
        return Err(at(format!(
            "no `uom` attribute: the unit must be given (e.g. `<{name} uom=\"{}\">`)",
            if dim == Dimension::Length { "m" } else { "dega" }
        )));
    };
    let unit = witsml_uom(uom, dim).map_err(at)?;
    let raw = el.text().map(str::trim).unwrap_or("");
    if raw.is_empty() {
        return Err(at("empty: no value".into()));
    }
    let v: f64 = raw.parse().map_err(|_| at(format!("`{raw}` is not a number")))?;
    if !v.is_finite() || !(v * unit.to_si).is_finite() || (v * unit.to_si).abs() > crate::units::MAX_ABS_SI {
        return Err(at(format!(
            "`{raw}` is not a finite number of physical size (at most {:e} in SI units)",
            crate::units::MAX_ABS_SI
        )));
    }
    Ok(Some(Measure {
        si: v * unit.to_si,
        raw,
        unit,
        line,
    }))
}

/// Describe an object for lists and messages: `name` (uid `uid`).
fn describe(node: Node) -> String {
    let name = child_text(node, "name").unwrap_or("(no name)");
    match node.attribute("uid") {
        Some(uid) => format!("`{name}` (uid `{uid}`)"),
        None => format!("`{name}` (no uid)"),
    }
}

/// The object element `object` (e.g. `trajectory`) of `root` to read: the only one, or the one
/// whose `name` or `uid` is `wanted`; `key` names the setting that chooses it in messages.
pub fn choose<'a, 'input>(
    root: Node<'a, 'input>,
    object: &str,
    wanted: Option<&str>,
    key: &str,
    path: &Path,
) -> InputResult<Node<'a, 'input>> {
    let all: Vec<Node> = root
        .children()
        .filter(|c| c.is_element() && c.tag_name().name() == object)
        .collect();
    let list = || all.iter().map(|n| describe(*n)).collect::<Vec<_>>().join(", ");
    let at_root = |m: String| {
        InputError::element(
            path,
            line(root),
            format!("root element `{}`", root.tag_name().name()),
            m,
        )
    };
    match (wanted, all.as_slice()) {
        (_, []) => Err(at_root(format!("holds no `{object}` object"))),
        (None, [only]) => Ok(*only),
        (None, _) => Err(at_root(format!(
            "holds {} `{object}` objects: {}; choose one by name or uid with {key}",
            all.len(),
            list()
        ))),
        (Some(w), _) => {
            let w = w.trim();
            let hits: Vec<Node> = all
                .iter()
                .copied()
                .filter(|n| n.attribute("uid").map(str::trim) == Some(w) || child_text(*n, "name") == Some(w))
                .collect();
            match hits.as_slice() {
                [one] => Ok(*one),
                [] => Err(at_root(format!(
                    "no `{object}` named or with uid `{w}` ({key}); the file holds: {}",
                    list()
                ))),
                _ => Err(at_root(format!(
                    "{} `{object}` objects are named `{w}` ({key}); choose by uid: {}",
                    hits.len(),
                    list()
                ))),
            }
        }
    }
}

/// The name of the root element of the WITSML text `text` (file `path`), e.g. `trajectorys`.
pub fn root_name(text: &str, path: &Path) -> InputResult<String> {
    Ok(parse(text, path)?.root_element().tag_name().name().to_string())
}

/// True if `bytes` look like XML: after an optional BOM and white space, a `<`.
pub fn looks_like_xml(bytes: &[u8]) -> bool {
    let b = bytes.strip_prefix(b"\xef\xbb\xbf").unwrap_or(bytes);
    b.iter().find(|c| !c.is_ascii_whitespace()) == Some(&b'<')
}
