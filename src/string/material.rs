//! Materials of string components: elastic moduli and density (SI).

/// Elastic and mass properties of a component's material.
#[derive(Debug, Clone, PartialEq)]
pub struct Material {
    /// Name as accepted in the case file.
    pub name: String,
    /// Young's modulus E, Pa.
    pub youngs_modulus_pa: f64,
    /// Shear modulus G, Pa.
    pub shear_modulus_pa: f64,
    /// Density, kg/m3.
    pub density_kg_m3: f64,
    /// Minimum yield strength of the pipe body, Pa, if given (`grade` or `yield_strength` in
    /// the case file); used only for the yield limit curves of `drillpath loads`.
    pub yield_strength_pa: Option<f64>,
}

/// Names accepted for `material`.
pub const MATERIAL_NAMES: &[&str] = &["steel", "aluminium", "titanium", "nonmagnetic"];

/// Built-in material by name (`steel` default: E 207 GPa, G 79.6 GPa, 7850 kg/m3; docs/guide.md).
/// Aluminium: drill-pipe alloy 2014-T6 (E 72.4 GPa, G 27.6 GPa, 2800 kg/m3); titanium:
/// Ti-6Al-4V (113.8 GPa, 44 GPa, 4430 kg/m3); nonmagnetic: austenitic stainless steel for
/// non-magnetic collars (196 GPa, 75.8 GPa, 7900 kg/m3). Typical handbook values.
pub fn material_by_name(name: &str) -> Option<Material> {
    let (e, g, rho) = match name.to_ascii_lowercase().as_str() {
        "steel" => (207e9, 79.6e9, 7850.0),
        "aluminium" | "aluminum" => (72.4e9, 27.6e9, 2800.0),
        "titanium" => (113.8e9, 44.0e9, 4430.0),
        "nonmagnetic" | "non-magnetic" | "nonmag" => (196e9, 75.8e9, 7900.0),
        _ => return None,
    };
    Some(Material {
        name: name.to_ascii_lowercase(),
        youngs_modulus_pa: e,
        shear_modulus_pa: g,
        density_kg_m3: rho,
        yield_strength_pa: None,
    })
}

/// Default material: steel.
pub fn steel() -> Material {
    material_by_name("steel").expect("steel is built in")
}

/// API drill-pipe grades (API Spec 5DP / RP 7G) and their minimum yield strengths, ksi.
pub const GRADES: &[(&str, f64)] = &[("E-75", 75.0), ("X-95", 95.0), ("G-105", 105.0), ("S-135", 135.0)];

/// Minimum yield strength of an API drill-pipe grade, Pa (`"S-135"`, `"s135"`, `"S 135"`).
pub fn grade_yield_strength_pa(grade: &str) -> Option<f64> {
    let key: String = grade
        .chars()
        .filter(|c| c.is_ascii_alphanumeric())
        .collect::<String>()
        .to_ascii_uppercase();
    GRADES
        .iter()
        .find(|(name, _)| name.replace('-', "") == key)
        .map(|(_, ksi)| ksi * 1e3 * crate::units::lookup("psi").expect("psi is a unit").to_si)
}
