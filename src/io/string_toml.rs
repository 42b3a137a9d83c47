//! The `[[string]]` tables of a case file: components from the bit upward
//! ([`crate::string::DrillString`]), every value checked and named on error, the topmost
//! length filled to the surface, and the fit of each component in its hole.

use super::rss_toml::RSS_KEYS;
use super::toml_reader::Section;
use crate::case::fit::first_misfit;
use crate::case::{Mud, Operation};
use crate::error::InputResult;
use crate::geometry::HoleSize;
use crate::string::component::{default_blade_length_m, Component, ComponentKind};
use crate::string::material::{material_by_name, steel, MATERIAL_NAMES};
use crate::string::DrillString;
use crate::units::{Dimension as D, G};

/// Default joint spacing of pipe with tool joints, m (30 ft).
pub const DEFAULT_JOINT_LENGTH_M: f64 = 9.144;

/// Keys accepted in a `[[string]]` component besides the rotary steerable system's
/// ([`RSS_KEYS`], [`component_keys`]).
pub(crate) const COMPONENT_KEYS: &[&str] = &[
    "type",
    "name",
    "od",
    "body_od",
    "id",
    "length",
    "weight",
    "tool_joint_od",
    "joint_length",
    "material",
    "youngs_modulus",
    "shear_modulus",
    "material_density",
    "grade",
    "yield_strength",
    "sensor_to_bit",
    "blade_od",
    "blade_length",
    "gauge_length",
    "bend_angle",
    "bend_to_bit",
];

/// Every key accepted in a `[[string]]` component: [`COMPONENT_KEYS`] and [`RSS_KEYS`].
pub(crate) fn component_keys() -> Vec<&'static str> {
    [COMPONENT_KEYS, RSS_KEYS].concat()
}

/// The string of the `[[string]]` tables `secs` (`top`: the case's top table, for errors about
/// the whole string), checked against the hole `hole` with the bit at `op`'s bit MD in mud `mud`.
pub fn read_string(
    secs: &[Section],
    top: &Section,
    op: &Operation,
    hole: &HoleSize,
    mud: &Mud,
) -> InputResult<DrillString> {
    if secs.is_empty() {
        return Err(top.error("string", "the string has no components"));
    }
    let mut comps: Vec<Component> = Vec::new();
    let mut missing_length: Option<usize> = None;
    let mut contact_lengths = Vec::new();
    for (k, c) in secs.iter().enumerate() {
        let bottom = comps.last().map(|p: &Component| p.top_m()).unwrap_or(0.0);
        let (component, has_length) = read_component(c, k, k + 1 == secs.len(), mud, bottom)?;
        if component.bend.is_some() && comps.iter().any(|p| p.bend.is_some()) {
            return Err(c.error("bend_angle", "a string may have one bent housing"));
        }
        let steers = |p: &Component| p.bend.is_some() || p.rss.is_some();
        if steers(&component) && comps.iter().any(steers) {
            let key = if component.rss.is_some() {
                "rss_type"
            } else {
                "bend_angle"
            };
            return Err(c.error(
                key,
                "a string may have one steering tool (a bent housing or a rotary steerable system)",
            ));
        }
        if !has_length {
            missing_length = Some(k);
        }
        contact_lengths.push(read_contact_length(c, component.kind)?);
        comps.push(component);
    }
    let bit_md = op.bit_md_m;
    fill_to_surface(&mut comps, missing_length, secs, top, bit_md)?;
    for ((c, given), sec) in comps.iter_mut().zip(contact_lengths).zip(secs) {
        c.contact_length_m = match given {
            Some((key, l)) if l > c.length_m + 1e-9 => {
                return Err(sec.error(
                    key,
                    format!(
                        "{key} {l:.3} m is longer than the {} ({:.3} m)",
                        c.kind.name(),
                        c.length_m
                    ),
                ))
            }
            Some((_, l)) => l,
            None if c.kind == ComponentKind::Stabilizer => default_blade_length_m(c.length_m),
            None => 0.0,
        };
    }
    // OD against the hole where each component sits (bit and stabilizers may be exactly gauge)
    let string = DrillString { components: comps };
    if let Some(m) = first_misfit(&string, hole, bit_md) {
        return Err(secs[m.component].error(m.key, m.describe(&string)));
    }
    Ok(string)
}

/// Component `k` of the string from its table `c` (`last`: the topmost, which may leave out
/// its length to fill to the surface), its bottom `bottom_m` above the bit; with whether the
/// length was given (0 when not).
fn read_component(c: &Section, k: usize, last: bool, mud: &Mud, bottom_m: f64) -> InputResult<(Component, bool)> {
    c.check_known(&component_keys())?;
    let kind = read_kind(c, k)?;
    let name = c.string("name")?.unwrap_or_else(|| kind.name().to_string());
    let (od, body, id) = read_diameters(c, kind)?;
    let length = c.positive("length", D::Length, "m", false)?;
    if length.is_none() && !last {
        return Err(c.error(
            "length",
            "missing length (only the topmost component may leave it out to fill to surface)",
        ));
    }
    let tj = c.positive("tool_joint_od", D::Length, "in", false)?;
    if let Some(t) = tj {
        if t < body {
            return Err(c.error("tool_joint_od", "tool_joint_od is smaller than the body od"));
        }
    }
    let joint_length = c
        .positive("joint_length", D::Length, "m", false)?
        .unwrap_or(DEFAULT_JOINT_LENGTH_M);
    let material = read_material(c, mud)?;
    let area = std::f64::consts::PI / 4.0 * (body * body - id * id);
    let weight = match c.positive("weight", D::LinearMass, "kg/m", false)? {
        Some(m) => m * G,
        None => area * material.density_kg_m3 * G,
    };
    let contact = match kind {
        ComponentKind::Bit | ComponentKind::Stabilizer => od,
        _ => body,
    };
    let component = Component {
        kind,
        name,
        length_m: length.unwrap_or(0.0),
        bottom_m,
        body_od_m: body,
        contact_od_m: contact,
        contact_length_m: 0.0,
        id_m: id,
        tool_joint_od_m: tj,
        joint_length_m: joint_length,
        material,
        weight_air_n_per_m: weight,
        sensor_to_bit_m: read_sensor(c, kind, bottom_m, length)?,
        bend: super::motor_toml::read_bend(c, kind, bottom_m, length)?,
        rss: super::rss_toml::read_rss(c, kind, bottom_m, length)?,
    };
    Ok((component, length.is_some()))
}

/// The given length along which the contact OD of table `c` (a component of kind `kind`)
/// touches the wall, with its key: `blade_length` of a stabilizer, `gauge_length` of a bit
/// (0 allowed: a point at the stabilizer's middle, the bit's face only); None when not given.
/// The keys are refused on the other kinds.
fn read_contact_length(c: &Section, kind: ComponentKind) -> InputResult<Option<(&'static str, f64)>> {
    let key = match kind {
        ComponentKind::Stabilizer => "blade_length",
        ComponentKind::Bit => "gauge_length",
        _ => "",
    };
    for other in ["blade_length", "gauge_length", "blade_od"] {
        let allowed = other == key || (other == "blade_od" && kind == ComponentKind::Stabilizer);
        if !allowed && c.quantity(other, D::Length, "m")?.is_some() {
            let owner = if other == "gauge_length" {
                "a bit"
            } else {
                "a stabilizer"
            };
            return Err(c.error(
                other,
                format!("only {owner} has `{other}` (this component is a {})", kind.name()),
            ));
        }
    }
    if key.is_empty() {
        return Ok(None);
    }
    Ok(c.positive(key, D::Length, "m", true)?.map(|l| (key, l)))
}

/// The survey sensor's distance from the bit face (`sensor_to_bit`, m) of an `mwd` component
/// `c` starting `bottom_m` above the bit, `length` long: it must lie on the component.
fn read_sensor(c: &Section, kind: ComponentKind, bottom_m: f64, length: Option<f64>) -> InputResult<Option<f64>> {
    let Some(x) = c.positive("sensor_to_bit", D::Length, "m", false)? else {
        return Ok(None);
    };
    if kind != ComponentKind::Mwd {
        return Err(c.error("sensor_to_bit", "only an `mwd` component has a survey sensor"));
    }
    let top = bottom_m + length.unwrap_or(f64::INFINITY);
    if x < bottom_m - 1e-9 || x > top + 1e-9 {
        return Err(c.error(
            "sensor_to_bit",
            format!("{x:.3} m from the bit is not on this component ({bottom_m:.3} to {top:.3} m from the bit)"),
        ));
    }
    Ok(Some(x))
}

/// The component type of table `c`, the `k`-th from the bit (only the first may be the bit).
fn read_kind(c: &Section, k: usize) -> InputResult<ComponentKind> {
    let kind_name = c
        .string("type")?
        .ok_or_else(|| c.error("type", format!("missing component type ({})", ComponentKind::NAMES)))?;
    let kind = ComponentKind::parse(&kind_name).ok_or_else(|| {
        c.error(
            "type",
            format!(
                "unknown component type `{kind_name}` (expected {})",
                ComponentKind::NAMES
            ),
        )
    })?;
    if kind == ComponentKind::Bit && k != 0 {
        return Err(c.error(
            "type",
            "the bit must be the first component (components are listed from the bit upward)",
        ));
    }
    Ok(kind)
}

/// Contact (blade for a stabilizer), body and inner diameters of table `c`, m. A stabilizer's
/// blade diameter is `blade_od`, its body `body_od` or else `od`; without `blade_od`, `od` is
/// the blade and `body_od` is required.
fn read_diameters(c: &Section, kind: ComponentKind) -> InputResult<(f64, f64, f64)> {
    let od = c
        .positive("od", D::Length, "in", false)?
        .ok_or_else(|| c.error("od", "missing outer diameter"))?;
    let body_od = c.positive("body_od", D::Length, "in", false)?;
    let blade_od = match kind {
        ComponentKind::Stabilizer => c.positive("blade_od", D::Length, "in", false)?,
        _ => None,
    };
    let (od, body) = match (kind, blade_od, body_od) {
        (ComponentKind::Stabilizer, None, None) => {
            return Err(c.error(
                "body_od",
                "a stabilizer needs body_od (od is the blade diameter), or blade_od (od is then the body diameter)",
            ))
        }
        (ComponentKind::Stabilizer, Some(blade), Some(b)) if !same(od, b) && !same(od, blade) => {
            return Err(c.error(
                "od",
                "with both blade_od and body_od, od must equal one of them (or give od as the body diameter with blade_od and leave body_od out)",
            ))
        }
        (ComponentKind::Stabilizer, Some(blade), b) => (blade, b.unwrap_or(od)),
        (_, _, Some(b)) => (od, b),
        (_, _, None) => (od, od),
    };
    if kind == ComponentKind::Stabilizer && body > od {
        let key = if blade_od.is_some() { "blade_od" } else { "body_od" };
        return Err(c.error(key, "the body diameter is larger than the blade diameter"));
    }
    let id = match c.positive("id", D::Length, "in", true)? {
        Some(id) => id,
        None if kind == ComponentKind::Bit => 0.0,
        None => return Err(c.error("id", "missing inner diameter (bore)")),
    };
    if id >= body {
        return Err(c.error(
            "id",
            format!(
                "inner diameter {:.4} in is not smaller than the outer diameter {:.4} in",
                id / 0.0254,
                body / 0.0254
            ),
        ));
    }
    Ok((od, body, id))
}

/// Two diameters equal to rounding, m.
fn same(a: f64, b: f64) -> bool {
    (a - b).abs() < 1e-9
}

/// The material of table `c` (named, with any property overridden), heavier than the mud.
fn read_material(c: &Section, mud: &Mud) -> InputResult<crate::string::material::Material> {
    let mut material = match c.string("material")? {
        Some(m) => material_by_name(&m).ok_or_else(|| {
            c.error(
                "material",
                format!("unknown material `{m}` (expected {})", MATERIAL_NAMES.join(", ")),
            )
        })?,
        None => steel(),
    };
    if let Some(e) = c.positive("youngs_modulus", D::Pressure, "GPa", false)? {
        material.youngs_modulus_pa = e;
    }
    if let Some(g) = c.positive("shear_modulus", D::Pressure, "GPa", false)? {
        material.shear_modulus_pa = g;
    }
    if let Some(r) = c.positive("material_density", D::Density, "kg/m3", false)? {
        material.density_kg_m3 = r;
    }
    material.yield_strength_pa = read_yield_strength(c)?;
    if mud.density_kg_m3 >= material.density_kg_m3 {
        return Err(c.error(
            "material_density",
            "material density must exceed the mud density (the string would float)",
        ));
    }
    Ok(material)
}

/// Give the component `missing_length` (when one left out its length) the length that brings
/// the string from the bit at `bit_md` (m) to the surface; else check that the lengths do.
fn fill_to_surface(
    comps: &mut [Component],
    missing_length: Option<usize>,
    secs: &[Section],
    top: &Section,
    bit_md: f64,
) -> InputResult<()> {
    let total: f64 = comps.iter().map(|c| c.length_m).sum();
    if let Some(k) = missing_length {
        let fill = bit_md - total;
        if fill <= 0.0 {
            return Err(secs[k].error(
                "length",
                format!("the components below already measure {total:.2} m, more than the bit MD {bit_md:.2} m: the string is longer than the hole"),
            ));
        }
        comps[k].length_m = fill;
    } else if total > bit_md + 0.01 {
        return Err(top.error(
            "string",
            format!("the string ({total:.2} m) is longer than the hole to the bit ({bit_md:.2} m MD)"),
        ));
    } else if total < bit_md - 0.01 {
        return Err(top.error(
            "string",
            format!("the string ({total:.2} m) does not reach the surface from the bit at {bit_md:.2} m MD; leave out the topmost length to fill"),
        ));
    }
    Ok(())
}

/// Pipe-body yield strength from `grade` (API name) or `yield_strength` (pressure), if given.
fn read_yield_strength(c: &Section) -> InputResult<Option<f64>> {
    let grade = c.string("grade")?;
    let given = c.positive("yield_strength", D::Pressure, "MPa", false)?;
    match (grade, given) {
        (Some(_), Some(_)) => Err(c.error("yield_strength", "give either grade or yield_strength, not both")),
        (Some(g), None) => crate::string::material::grade_yield_strength_pa(&g)
            .map(Some)
            .ok_or_else(|| {
                let names: Vec<&str> = crate::string::material::GRADES.iter().map(|(n, _)| *n).collect();
                c.error(
                    "grade",
                    format!(
                        "unknown grade `{g}` (expected {}, or give yield_strength)",
                        names.join(", ")
                    ),
                )
            }),
        (None, y) => Ok(y),
    }
}
