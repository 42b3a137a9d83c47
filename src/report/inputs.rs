//! Report sections echoing the inputs: well, string (with the BHA schematic), mud, operation.

use super::display_units::UnitSystem;
use super::html::Page;
use super::schematic::{bha_svg, shown_length_m};
use crate::case::Case;
use crate::string::ComponentKind;

/// Add the well, BHA, mud and operation sections for `case` with the bit at `bit_md_m`.
pub fn echo_inputs(page: &mut Page, case: &Case, bit_md_m: f64, units: UnitSystem) -> Result<(), String> {
    let (depth_unit, small_unit) = (units.depth(), units.small_length());
    let path = &case.well.path;
    let st = path.stations();
    let (dls, dls_md) = path.max_dls();
    let max_inc = st.iter().map(|s| s.inc_rad).fold(0.0, f64::max);
    page.heading("Well");
    if !case.description.is_empty() {
        page.para(&case.description);
    }
    page.key_values(&[
        ("case file".into(), case.path.display().to_string()),
        ("survey".into(), case.well.survey_path.display().to_string()),
        (
            "azimuth reference".into(),
            match case.well.survey.azimuth_reference_source.as_str() {
                "" => case.well.survey.azimuth_reference.describe().to_string(),
                source => format!("{} (from {source})", case.well.survey.azimuth_reference.describe()),
            },
        ),
        ("stations".into(), st.len().to_string()),
        (
            "survey MD range".into(),
            format!(
                "{} to {}",
                depth_unit.fmt(path.md_start(), 1),
                depth_unit.fmt(path.md_end(), 1)
            ),
        ),
        ("max inclination".into(), format!("{:.2} deg", max_inc.to_degrees())),
        (
            "max dogleg severity".into(),
            format!("{} at {}", units.dogleg().fmt(dls, 2), depth_unit.fmt(dls_md, 1)),
        ),
        (
            "TVD at the bit".into(),
            depth_unit.fmt(path.point_at(bit_md_m).position.z, 1),
        ),
    ]);
    let rows: Vec<Vec<String>> = case
        .well
        .hole
        .sections()
        .iter()
        .map(|s| {
            vec![
                depth_unit.fmt(s.to_md_m, 1),
                small_unit.fmt(s.diameter_m, 1),
                s.friction
                    .map(|f| format!("{f:.3}"))
                    .unwrap_or_else(|| format!("{:.3} (operation)", case.operation.friction)),
            ]
        })
        .collect();
    page.table(
        &["hole section to MD".into(), "diameter".into(), "friction".into()],
        &rows,
    );
    if !case.well.hole.caliper().is_empty() {
        page.note(&format!(
            "caliper log: {} points override the sections inside its range",
            case.well.hole.caliper().len()
        ));
    }

    page.heading("String (from the bit up)");
    let rows: Vec<Vec<String>> = case
        .string
        .components
        .iter()
        .map(|c| {
            vec![
                c.kind.name().to_string(),
                c.name.clone(),
                depth_unit.fmt(c.bottom_m, 2),
                depth_unit.fmt(c.length_m, 2),
                small_unit.fmt(c.body_od_m, 1),
                small_unit.fmt(c.contact_od_m, 1),
                match c.kind {
                    ComponentKind::Stabilizer | ComponentKind::Bit => depth_unit.fmt(c.contact_length_m, 2),
                    _ => String::new(),
                },
                small_unit.fmt(c.id_m, 1),
            ]
        })
        .collect();
    page.table(
        &[
            "type".into(),
            "name".into(),
            "from bit".into(),
            "length".into(),
            "body OD".into(),
            "contact OD".into(),
            "blade / gauge length".into(),
            "ID".into(),
        ],
        &rows,
    );
    if !case.string.components.is_empty() {
        let hole = case.well.hole.diameter_at(bit_md_m);
        let svg = bha_svg(&case.string, hole, units)?;
        page.figure(
            "bha-schematic",
            &svg,
            &format!(
                "bottom {} of the string; hole {} at the bit",
                depth_unit.fmt(shown_length_m(&case.string), 1),
                small_unit.fmt(hole, 1)
            ),
        );
    }

    page.heading("Mud and operation");
    let op = &case.operation;
    let mut kv = vec![
        (
            "mud density".to_string(),
            units.density().fmt(case.mud.density_kg_m3, 1),
        ),
        (
            "plastic viscosity".into(),
            format!("{:.1} cP", case.mud.plastic_viscosity_pa_s * 1e3),
        ),
        ("mode".into(), op.mode.name().to_string()),
        ("bit MD".into(), depth_unit.fmt(bit_md_m, 2)),
    ];
    match op.hook_load_n {
        Some(h) => kv.push(("hook load (given)".into(), units.force().fmt(h, 1))),
        None => kv.push(("weight on bit".into(), units.force().fmt(op.wob_n, 1))),
    }
    kv.push(("rotary speed".into(), format!("{:.0} rpm", op.rpm)));
    kv.push(("rate of penetration".into(), units.rop().fmt(op.rop_m_s, 1)));
    kv.push(("friction (open hole)".into(), format!("{:.3}", op.friction)));
    page.key_values(&kv);
    Ok(())
}
