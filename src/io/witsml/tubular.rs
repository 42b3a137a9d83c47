//! WITSML 1.4.1.1 `tubular`: a drill string's components as the `[[string]]` tables of a case
//! (`string_from = "FILE.xml"`), read then by the case's own string reader
//! ([`crate::io::string_toml`]) with all its checks.
//!
//! Rules (docs/guide.md, "WITSML tubular"):
//! - components are ordered by `sequence` from the bit (1 = at the bit), whatever their order
//!   in the file; two components with one `sequence`, or none, are an error naming them;
//! - `typeTubularComp` maps to drillpath's types ([`kind_of`]); a type with no mechanical
//!   meaning to drillpath is an error naming its uid and type, or, with
//!   `string_other_as_tube = true`, a plain tube (`sub`) with a note;
//! - `od`, `id`, `len`, `wtPerLen`, `lenJointAv`, `connection/od` (tool-joint OD), `grade`,
//!   and for stabilizers the `stabilizer` sub-element's `odBladeMx` (blade diameter) and
//!   `lenBlade` (blade length) map to the component keys; the blades are centred on the
//!   stabilizer in drillpath, so a `distBladeBot` is noted, not used;
//! - a `bend` sub-element with a non-zero `angle` becomes the motor's `bend_angle` and
//!   `bend_to_bit` (the components below plus `distBendBot`, from the bit face);
//! - the topmost component fills the string to the surface (its `len`, if any, is replaced;
//!   [`Tubular::top_len_m`] keeps it for a note when it differs).

use std::path::Path;

use roxmltree::Node;
use toml::{Table, Value};

use super::{child, child_text, choose, measure, parse, root, LineIndex};
use crate::error::{InputError, InputResult};
use crate::units::Dimension;

/// One component as read: its uid, its type as written and its `[[string]]` table.
#[derive(Debug, Clone)]
pub struct TubularComponent {
    /// The component's `uid` in the file.
    pub uid: String,
    /// `typeTubularComp` as written.
    pub kind: String,
    /// 1-based line of the `tubularComponent` element.
    pub line: usize,
    /// The `[[string]]` table (quantities as SI strings with units, e.g. `"0.2159 m"`).
    pub table: Table,
}

/// The components of a tubular, from the bit up, with notes for the user.
#[derive(Debug, Clone)]
pub struct Tubular {
    /// The tubular's name.
    pub name: String,
    /// The components, ordered by `sequence` (the bit first).
    pub components: Vec<TubularComponent>,
    /// What was assumed or left out.
    pub notes: Vec<String>,
    /// The `len` of the topmost component as the file gives it, m (the string fills to the
    /// surface instead: see [`parse_tubular`]).
    pub top_len_m: Option<f64>,
}

/// The drillpath component type of WITSML `typeTubularComp` `t` (case-insensitive), with the
/// material when it is not steel; `None` for types with no mechanical meaning to drillpath.
pub fn kind_of(t: &str) -> Option<(&'static str, Option<&'static str>)> {
    let t = t.trim().to_ascii_lowercase();
    Some(match t.as_str() {
        "bit"
        | "bit core diamond"
        | "bit core pdc"
        | "bit diamond fixed cut"
        | "bit insert roller cone"
        | "bit mill tooth roller cone"
        | "bit pdc fixed cutter"
        | "coring bit" => ("bit", None),
        "stabilizer"
        | "near bit stabilizer"
        | "stabilizer inline"
        | "stabilizer near bit roller reamer"
        | "stabilizer non-rotating"
        | "stabilizer steerable"
        | "stabilizer string" => ("stabilizer", None),
        "non-magnetic stabilizer" => ("stabilizer", Some("nonmagnetic")),
        "drill collar" | "spiral drill collar" | "short drill collar" => ("collar", None),
        "non-magnetic collar" | "non-magnetic drill collar" => ("collar", Some("nonmagnetic")),
        "heavy weight drill pipe" => ("hwdp", None),
        "drill pipe" | "drill pipe compressive" => ("pipe", None),
        "mud motor" | "turbine" => ("motor", None),
        "mwd tool" | "lwd tool" | "mwd hang off sub" | "mwd pulser" => ("mwd", None),
        "jar" | "accelerator" => ("jar", None),
        "rotary steerable tool" => ("sub", None),
        t if t.starts_with("sub") || t.contains("crossover") || t == "float sub" || t == "bypass sub" => ("sub", None),
        _ => return None,
    })
}

/// A quantity as a TOML string in SI with its unit (exact: Rust's round-trip form).
fn si(value: f64, unit: &str) -> Value {
    Value::String(format!("{value} {unit}"))
}

/// Parse the WITSML text `text` (file `path`) and read its tubular named or with uid `wanted`
/// (the only one when `None`); `other_as_tube` reads unknown component types as plain tubes.
/// A non-zero `bend` becomes the motor keys `bend_angle` and `bend_to_bit` (the distance from
/// the bit face).
pub fn parse_tubular(text: &str, path: &Path, wanted: Option<&str>, other_as_tube: bool) -> InputResult<Tubular> {
    let doc = parse(text, path)?;
    let lines = LineIndex::new(text);
    let root = root(&doc, "tubulars", path)?;
    let tub = choose(root, "tubular", wanted, "`string_from_tubular`", path)?;
    let name = child_text(tub, "name").unwrap_or("(no name)").to_string();
    let mut notes = Vec::new();
    let mut comps: Vec<(i64, TubularComponent)> = Vec::new();
    for c in tub
        .children()
        .filter(|c| c.is_element() && c.tag_name().name() == "tubularComponent")
    {
        let (seq, comp) = component(c, path, &lines, other_as_tube, &mut notes)?;
        if let Some((_, prev)) = comps.iter().find(|(s, _)| *s == seq) {
            return Err(InputError::element(
                path,
                comp.line,
                format!("element `sequence` of component `{}`", comp.uid),
                format!("sequence {seq} is also that of component `{}` (line {}): each component needs its own place from the bit", prev.uid, prev.line),
            ));
        }
        comps.push((seq, comp));
    }
    if comps.is_empty() {
        return Err(InputError::element(
            path,
            lines.line(tub),
            format!("tubular `{name}`"),
            "has no `tubularComponent`",
        ));
    }
    let listed: Vec<i64> = comps.iter().map(|(s, _)| *s).collect();
    comps.sort_by_key(|(s, _)| *s);
    if listed.windows(2).any(|w| w[0] > w[1]) {
        notes.push(
            "the components are listed out of `sequence` order in the file: ordered by `sequence` from the bit".into(),
        );
    }
    let mut components: Vec<TubularComponent> = comps.into_iter().map(|(_, c)| c).collect();
    // a bend's distance from the component's bottom, made a distance from the bit face
    let mut below = 0.0;
    for c in &mut components {
        if let Some(Value::String(d)) = c.table.remove("bend_from_bottom") {
            let d: f64 = d.trim_end_matches(" m").parse().unwrap_or(0.0);
            c.table.insert("bend_to_bit".into(), si(below + d, "m"));
        }
        below += c
            .table
            .get("length")
            .and_then(Value::as_str)
            .and_then(|l| l.trim_end_matches(" m").parse::<f64>().ok())
            .unwrap_or(0.0);
    }
    let top_len_m = components.last_mut().and_then(|top| match top.table.remove("length") {
        Some(Value::String(len)) => len.trim_end_matches(" m").parse().ok(),
        _ => None,
    });
    Ok(Tubular {
        name,
        components,
        notes,
        top_len_m,
    })
}

/// One `tubularComponent`: its `sequence` and its table.
fn component(
    c: Node,
    path: &Path,
    lines: &LineIndex,
    other_as_tube: bool,
    notes: &mut Vec<String>,
) -> InputResult<(i64, TubularComponent)> {
    let line = lines.line(c);
    let uid = c.attribute("uid").unwrap_or("(no uid)").to_string();
    let kind = child_text(c, "typeTubularComp").unwrap_or("").to_string();
    let what = format!(
        "component `{uid}` ({})",
        if kind.is_empty() { "no type" } else { &kind }
    );
    let at = |el: &str, m: String| InputError::element(path, line, format!("element `{el}` of {what}"), m);
    let seq: i64 = child_text(c, "sequence")
        .ok_or_else(|| {
            at(
                "sequence",
                "missing: the component's place from the bit (1 = at the bit) is needed".into(),
            )
        })?
        .parse()
        .map_err(|_| at("sequence", "not a whole number".into()))?;
    let (dp_kind, material) = match kind_of(&kind) {
        Some(k) => k,
        None if other_as_tube => {
            notes.push(format!("{what} has no mechanical meaning to drillpath: read as a plain tube (`sub`) of its od and id (`string_other_as_tube`)"));
            ("sub", None)
        }
        None => {
            return Err(at(
                "typeTubularComp",
                format!("`{kind}` has no mechanical meaning to drillpath (it reads bits, stabilizers, collars, HWDP, drill pipe, motors, MWD/LWD tools, jars, subs and crossovers, rotary steerable tools); remove it, or set `string_other_as_tube = true` to read it as a plain tube"),
            ))
        }
    };
    let len = |el: &str, node: Node| measure(node, el, Dimension::Length, &what, path, lines).map(|m| m.map(|m| m.si));
    let mut t = Table::new();
    t.insert("type".into(), Value::String(dp_kind.into()));
    t.insert("name".into(), Value::String(format!("{uid} ({kind})")));
    if let Some(m) = material {
        t.insert("material".into(), Value::String(m.into()));
    }
    let od = len("od", c)?.ok_or_else(|| at("od", "missing: every component needs its outer diameter".into()))?;
    t.insert("od".into(), si(od, "m"));
    match len("id", c)? {
        Some(id) => {
            t.insert("id".into(), si(id, "m"));
        }
        None if dp_kind == "bit" => {}
        None => return Err(at("id", "missing: the inner diameter (bore) is needed".into())),
    }
    if let Some(l) = len("len", c)? {
        t.insert("length".into(), si(l, "m"));
    }
    if let Some(w) = measure(c, "wtPerLen", Dimension::LinearMass, &what, path, lines)? {
        t.insert("weight".into(), si(w.si, "kg/m"));
    }
    if let Some(j) = len("lenJointAv", c)? {
        if matches!(dp_kind, "pipe" | "hwdp") {
            t.insert("joint_length".into(), si(j, "m"));
        }
    }
    if let Some(conn) = child(c, "connection") {
        if let Some(tj) = len("od", conn)? {
            if matches!(dp_kind, "pipe" | "hwdp") && tj > od {
                t.insert("tool_joint_od".into(), si(tj, "m"));
            }
        }
    }
    if let Some(g) = child_text(c, "grade") {
        if crate::string::material::grade_yield_strength_pa(g).is_some() {
            t.insert("grade".into(), Value::String(g.into()));
        } else {
            notes.push(format!(
                "{what}: grade `{g}` is not an API drill-pipe grade drillpath knows: not used"
            ));
        }
    }
    stabilizer(c, dp_kind, &mut t, &what, path, lines, notes)?;
    if let Some((angle, from_bottom)) = bend(c, &what, path, lines)? {
        t.insert("bend_angle".into(), si(angle, "rad"));
        t.insert("bend_from_bottom".into(), si(from_bottom, "m"));
    }
    Ok((
        seq,
        TubularComponent {
            uid,
            kind,
            line,
            table: t,
        },
    ))
}

/// The `stabilizer` sub-element of a stabilizer component: blade diameter and length.
fn stabilizer(
    c: Node,
    dp_kind: &str,
    t: &mut Table,
    what: &str,
    path: &Path,
    lines: &LineIndex,
    notes: &mut Vec<String>,
) -> InputResult<()> {
    let Some(s) = child(c, "stabilizer") else {
        if dp_kind == "stabilizer" {
            return Err(InputError::element(
                path,
                lines.line(c),
                what.to_string(),
                "has no `stabilizer` sub-element: its blade diameter `odBladeMx` is needed (the component's `od` is the body's)",
            ));
        }
        return Ok(());
    };
    if dp_kind != "stabilizer" {
        notes.push(format!(
            "{what}: its `stabilizer` sub-element is not used (drillpath has blades on stabilizers only)"
        ));
        return Ok(());
    }
    let len = |el: &str| measure(s, el, Dimension::Length, what, path, lines);
    let blade = len("odBladeMx")?.ok_or_else(|| {
        InputError::element(
            path,
            lines.line(s),
            format!("element `stabilizer` of {what}"),
            "has no `odBladeMx`: the blade diameter is needed",
        )
    })?;
    t.insert("blade_od".into(), si(blade.si, "m"));
    if let Some(l) = len("lenBlade")? {
        t.insert("blade_length".into(), si(l.si, "m"));
    }
    if let Some(d) = len("distBladeBot")? {
        notes.push(format!(
            "{what}: `distBladeBot` {} {} not used: drillpath centres the blades on the stabilizer",
            d.raw, d.unit.name
        ));
    }
    Ok(())
}

/// A `bend` with a non-zero `angle`: its angle (rad) and distance from the component's bottom
/// (`distBendBot`, m, then required).
fn bend(c: Node, what: &str, path: &Path, lines: &LineIndex) -> InputResult<Option<(f64, f64)>> {
    let Some(b) = child(c, "bend") else {
        return Ok(None);
    };
    let Some(a) = measure(b, "angle", Dimension::Angle, what, path, lines)? else {
        return Ok(None);
    };
    if a.si == 0.0 {
        return Ok(None);
    }
    let d = measure(b, "distBendBot", Dimension::Length, what, path, lines)?.ok_or_else(|| {
        InputError::element(
            path,
            lines.line(b),
            format!("element `bend` of {what}"),
            "has no `distBendBot`: the bend's distance from the component's bottom is needed",
        )
    })?;
    Ok(Some((a.si, d.si)))
}
