//! The editable, commented case that `drillpath import` writes from WITSML objects: the
//! survey naming the trajectory file, the hole list from a wbGeometry, the `[[string]]` tables
//! from a tubular, and what WITSML does not say (mud, operation, bit-rock law) as commented,
//! ASSUMED defaults.

use std::fmt::Write;

use crate::io::witsml::geometry::GeometrySection;
use crate::io::witsml::tubular::Tubular;
use crate::units::{from_si, INCH};

/// What an import gathered: each part optional.
#[derive(Debug, Clone, Default)]
pub struct ImportParts {
    /// The trajectory file as the case should name it (relative to the case, or absolute),
    /// with the chosen trajectory's name or uid when the file holds several, and the last
    /// station's MD (m).
    pub survey: Option<(String, Option<String>, f64)>,
    /// The hole sections and the file they came from.
    pub hole: Option<(Vec<GeometrySection>, String)>,
    /// The tubular and the file it came from.
    pub string: Option<(Tubular, String)>,
}

/// `v` with at most `decimals` decimals, trailing zeros dropped (`8.5`, `27.6`, `0.3`).
fn short(v: f64, decimals: usize) -> String {
    let s = format!("{v:.decimals$}");
    let s = if s.contains('.') {
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        s
    };
    if s == "-0" {
        "0".into()
    } else {
        s
    }
}

/// A TOML string literal.
fn quoted(s: &str) -> String {
    toml::Value::String(s.to_string()).to_string()
}

/// The SI value of a `[[string]]` table's quantity (written as `"<SI> <unit>"` by the tubular
/// reader).
fn si_of(v: &toml::Value) -> Option<f64> {
    v.as_str()?.split_whitespace().next()?.parse().ok()
}

/// The case text (see the module documentation).
pub fn import_case(parts: &ImportParts, sources: &[String]) -> String {
    let mut t = String::new();
    let _ = writeln!(
        t,
        "# drillpath case written by `drillpath import` from WITSML 1.4.1.1 objects:"
    );
    for s in sources {
        let _ = writeln!(t, "#   {s}");
    }
    let _ = writeln!(
        t,
        "# What WITSML does not say (mud, operation, bit-rock law) is written below as ASSUMED"
    );
    let _ = writeln!(
        t,
        "# defaults, commented out: edit them for your well. Run:  drillpath survey <this file>\n"
    );
    let _ = writeln!(t, "name = \"Imported case\"\n");
    write_well(&mut t, parts);
    write_assumed(&mut t, parts);
    if let Some((tub, file)) = &parts.string {
        write_string(&mut t, tub, file);
    } else {
        let _ = writeln!(t, "# No tubular was imported: add the string as [[string]] tables (docs/guide.md), or\n# string_from = \"bha.xml\" at the top of this file.\n");
    }
    t
}

fn write_well(t: &mut String, parts: &ImportParts) {
    let _ = writeln!(t, "[well]");
    match &parts.survey {
        Some((file, chosen, _)) => {
            let _ = writeln!(
                t,
                "survey = {}   # WITSML trajectory (tie-in position, north and units from the file)",
                quoted(file)
            );
            if let Some(c) = chosen {
                let _ = writeln!(t, "survey_trajectory = {}", quoted(c));
            }
        }
        None => {
            let _ = writeln!(
                t,
                "survey = \"survey.csv\"   # no trajectory was imported: name the survey file here"
            );
        }
    }
    match &parts.hole {
        Some((sections, file)) => {
            let _ = writeln!(
                t,
                "# the hole from {file}: each section to its mdBottom at its idSection"
            );
            let _ = writeln!(t, "hole = [");
            for s in sections {
                let cased = if s.is_open_hole() { "" } else { ", friction = 0.2" };
                let _ = writeln!(
                    t,
                    "  {{ to_md = \"{} m\", diameter = \"{} in\"{cased} }},   # {} {}-{} m (uid {}){}",
                    short(s.md_bottom_m, 3),
                    short(s.id_m / INCH, 4),
                    s.kind,
                    short(s.md_top_m, 3),
                    short(s.md_bottom_m, 3),
                    s.uid,
                    if cased.is_empty() {
                        ": open hole, [operation] friction"
                    } else {
                        ": ASSUMED cased-hole friction"
                    }
                );
            }
            let _ = writeln!(t, "]\n");
        }
        None => {
            let _ = writeln!(
                t,
                "hole = [ {{ to_md = \"3000 m\", diameter = \"8.5 in\" }} ]   # ASSUMED: no wbGeometry was imported\n"
            );
        }
    }
}

fn write_assumed(t: &mut String, parts: &ImportParts) {
    let bit = parts
        .survey
        .as_ref()
        .map(|(_, _, md)| format!("\"{} m\"", short(*md, 3)))
        .unwrap_or_else(|| "\"3000 m\"".into());
    let _ = write!(
        t,
        "# [mud]                        # ASSUMED defaults: 1.0 sg, 20 cP\n\
         # density = \"1.2 sg\"\n\
         # plastic_viscosity = \"20 cP\"\n\n\
         [operation]\n\
         mode = \"drilling\"               # ASSUMED: drilling, sliding, rotating_off_bottom, trip_in, trip_out\n\
         bit_md = {bit}                # the last survey station: edit\n\
         # wob = \"100 kN\"              # ASSUMED values to set:\n\
         # rpm = 80\n\
         # rop = \"15 m/h\"\n\
         # friction = 0.25               # open-hole wall friction\n\n\
         # [bit_rock]                    # the prediction law's defaults (docs/guide.md)\n\
         # lateral_drillability = 1.0\n\n"
    );
}

fn write_string(t: &mut String, tub: &Tubular, file: &str) {
    let _ = writeln!(
        t,
        "# The string from the bit upward: tubular `{}` of {file}, by `sequence`.",
        tub.name
    );
    for note in &tub.notes {
        let _ = writeln!(t, "# note: {note}");
    }
    let n = tub.components.len();
    for (k, c) in tub.components.iter().enumerate() {
        let _ = writeln!(t, "\n[[string]]   # component `{}` ({})", c.uid, c.kind);
        const ORDER: &[&str] = &[
            "type",
            "name",
            "material",
            "od",
            "blade_od",
            "id",
            "length",
            "blade_length",
            "weight",
            "tool_joint_od",
            "joint_length",
            "grade",
            "bend_angle",
            "bend_to_bit",
        ];
        let mut keys: Vec<&String> = c.table.keys().collect();
        keys.sort_by_key(|k| ORDER.iter().position(|o| o == k).unwrap_or(ORDER.len()));
        if c.table.contains_key("bend_angle") {
            let _ = writeln!(
                t,
                "# the motor's bent housing: bend_to_bit is from the bit face (the components below + distBendBot)"
            );
        }
        for key in keys {
            let v = &c.table[key];
            let text = match key.as_str() {
                "od" | "id" | "blade_od" | "tool_joint_od" => {
                    si_of(v).map(|x| format!("\"{} in\"", short(x / INCH, 4)))
                }
                "length" | "blade_length" | "joint_length" | "bend_to_bit" => {
                    si_of(v).map(|x| format!("\"{} m\"", short(x, 4)))
                }
                "weight" => si_of(v).map(|x| format!("\"{} kg/m\"", short(from_si(x, "kg/m"), 3))),
                "bend_angle" => si_of(v).map(|x| format!("\"{} deg\"", short(x.to_degrees(), 4))),
                _ => None,
            };
            let text = text.unwrap_or_else(|| v.to_string());
            let _ = writeln!(t, "{key} = {text}");
        }
        if k + 1 == n {
            match tub.top_len_m {
                Some(l) => {
                    let _ = writeln!(
                        t,
                        "# no length: fills the string to the surface (the file's len is {} m)",
                        short(l, 3)
                    );
                }
                None => {
                    let _ = writeln!(t, "# no length: fills the string to the surface");
                }
            }
        }
    }
}
