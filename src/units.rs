//! Units at the edges: parse quantities such as `"8.5 in"`, `"25 klbf"` or `"3 deg/30m"` into SI.
//!
//! Inside the library every `f64` is SI (m, N, N.m, Pa, kg/m3, kg/m, m/s, rad, rad/m, Pa.s).
//! Conversion happens only here (input) and in `report` (output column names carry the unit).
//! A bare number means the field's documented default unit, which the caller passes in.

use std::fmt;

/// Standard gravity, m/s2 (docs/guide.md).
pub const G: f64 = 9.80665;
/// Density of fresh water used for specific gravity, kg/m3.
pub const WATER_DENSITY: f64 = 1000.0;

/// One metre in feet is 1/0.3048: the international foot, m.
pub const FOOT: f64 = 0.3048;
/// The inch, m.
pub const INCH: f64 = 0.0254;
/// The pound-force, N.
pub const POUND_FORCE: f64 = 4.448_221_615_260_5;
/// The pound mass, kg.
pub const POUND_MASS: f64 = 0.453_592_37;
/// The US gallon, m3.
pub const US_GALLON: f64 = 3.785_411_784e-3;
/// Pound per square inch, Pa.
pub const PSI: f64 = POUND_FORCE / (INCH * INCH);

/// Physical dimension of a quantity: decides which units are accepted.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Dimension {
    /// Length, m.
    Length,
    /// Force, N.
    Force,
    /// Moment or torque, N.m.
    Moment,
    /// Density, kg/m3.
    Density,
    /// Mass per length, kg/m.
    LinearMass,
    /// Speed, m/s.
    Speed,
    /// Angle, rad.
    Angle,
    /// Curvature or dogleg severity, rad/m.
    Curvature,
    /// Pressure, stress or modulus, Pa.
    Pressure,
    /// Rotary speed, rad/s.
    RotarySpeed,
    /// Dynamic viscosity, Pa.s.
    Viscosity,
    /// Time, s.
    Time,
    /// No unit.
    Dimensionless,
}

impl fmt::Display for Dimension {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let s = match self {
            Dimension::Length => "length",
            Dimension::Force => "force",
            Dimension::Moment => "moment",
            Dimension::Density => "density",
            Dimension::LinearMass => "mass per length",
            Dimension::Speed => "speed",
            Dimension::Angle => "angle",
            Dimension::Curvature => "dogleg severity",
            Dimension::Pressure => "pressure or modulus",
            Dimension::RotarySpeed => "rotary speed",
            Dimension::Viscosity => "viscosity",
            Dimension::Time => "time",
            Dimension::Dimensionless => "dimensionless number",
        };
        f.write_str(s)
    }
}

/// A unit: its dimension and the factor that converts one of it to SI.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Unit {
    /// Canonical spelling, e.g. `"klbf"`.
    pub name: &'static str,
    /// Dimension of the unit.
    pub dimension: Dimension,
    /// SI value of one unit.
    pub to_si: f64,
}

const DEG: f64 = std::f64::consts::PI / 180.0;

/// The unit table: (spellings, dimension, SI factor). Spellings are compared after removing
/// spaces and lower-casing; the first spelling is the canonical one.
#[rustfmt::skip]
const TABLE: &[(&[&str], Dimension, f64)] = &[
    (&["m", "meter", "meters", "metre", "metres"], Dimension::Length, 1.0),
    (&["ft", "feet", "foot", "'"], Dimension::Length, FOOT),
    (&["usft", "ftus", "us survey ft", "us survey foot", "us survey feet"], Dimension::Length, 1200.0 / 3937.0),
    (&["in", "inch", "inches", "\""], Dimension::Length, INCH),
    (&["mm"], Dimension::Length, 1e-3),
    (&["cm"], Dimension::Length, 1e-2),
    (&["km"], Dimension::Length, 1e3),
    (&["N"], Dimension::Force, 1.0),
    (&["kN"], Dimension::Force, 1e3),
    (&["daN"], Dimension::Force, 10.0),
    (&["lbf"], Dimension::Force, POUND_FORCE),
    (&["klbf", "kip", "kips"], Dimension::Force, 1e3 * POUND_FORCE),
    (&["tf", "tonf"], Dimension::Force, 1e3 * G),
    (&["N.m", "Nm", "N*m", "N-m"], Dimension::Moment, 1.0),
    (&["kN.m", "kNm", "kN*m", "kN-m"], Dimension::Moment, 1e3),
    (&["ft.lbf", "ftlbf", "ft*lbf", "ft-lbf", "lbf.ft", "lbf-ft"], Dimension::Moment, FOOT * POUND_FORCE),
    (&["kft.lbf", "ft.klbf", "kft-lbf", "ft-klbf", "klbf.ft"], Dimension::Moment, 1e3 * FOOT * POUND_FORCE),
    (&["kg/m3", "kg/m^3", "kg/m³"], Dimension::Density, 1.0),
    (&["g/cm3", "g/cc", "g/cm^3"], Dimension::Density, 1000.0),
    (&["sg", "s.g."], Dimension::Density, WATER_DENSITY),
    (&["ppg", "lb/gal", "lbm/gal"], Dimension::Density, POUND_MASS / US_GALLON),
    (&["kg/m"], Dimension::LinearMass, 1.0),
    (&["lb/ft", "lbm/ft", "ppf"], Dimension::LinearMass, POUND_MASS / FOOT),
    (&["m/s"], Dimension::Speed, 1.0),
    (&["m/h", "m/hr"], Dimension::Speed, 1.0 / 3600.0),
    (&["ft/h", "ft/hr"], Dimension::Speed, FOOT / 3600.0),
    (&["m/min"], Dimension::Speed, 1.0 / 60.0),
    (&["ft/min"], Dimension::Speed, FOOT / 60.0),
    (&["ft/s"], Dimension::Speed, FOOT),
    (&["deg", "degree", "degrees", "°"], Dimension::Angle, DEG),
    (&["rad", "radian", "radians"], Dimension::Angle, 1.0),
    (&["deg/30m", "°/30m"], Dimension::Curvature, DEG / 30.0),
    (&["deg/100ft", "°/100ft"], Dimension::Curvature, DEG / (100.0 * FOOT)),
    (&["deg/100m", "°/100m"], Dimension::Curvature, DEG / 100.0),
    (&["deg/m", "°/m"], Dimension::Curvature, DEG),
    (&["deg/10m"], Dimension::Curvature, DEG / 10.0),
    (&["rad/m"], Dimension::Curvature, 1.0),
    (&["Pa"], Dimension::Pressure, 1.0),
    (&["kPa"], Dimension::Pressure, 1e3),
    (&["MPa"], Dimension::Pressure, 1e6),
    (&["GPa"], Dimension::Pressure, 1e9),
    (&["bar"], Dimension::Pressure, 1e5),
    (&["psi"], Dimension::Pressure, PSI),
    (&["ksi"], Dimension::Pressure, 1e3 * PSI),
    (&["Mpsi"], Dimension::Pressure, 1e6 * PSI),
    (&["rpm", "rev/min"], Dimension::RotarySpeed, 2.0 * std::f64::consts::PI / 60.0),
    (&["rad/s"], Dimension::RotarySpeed, 1.0),
    (&["Pa.s", "Pas", "Pa*s"], Dimension::Viscosity, 1.0),
    (&["mPa.s", "mPas", "cP", "cp"], Dimension::Viscosity, 1e-3),
    (&["s", "sec", "second", "seconds"], Dimension::Time, 1.0),
    (&["min", "minute", "minutes"], Dimension::Time, 60.0),
    (&["h", "hr", "hour", "hours"], Dimension::Time, 3600.0),
    (&["-", "1"], Dimension::Dimensionless, 1.0),
];

fn normalize(s: &str) -> String {
    s.chars()
        .filter(|c| !c.is_whitespace())
        .collect::<String>()
        .to_lowercase()
}

/// Look up a unit by any of its spellings (case-insensitive, spaces ignored).
pub fn lookup(name: &str) -> Option<Unit> {
    let key = normalize(name);
    for (names, dim, factor) in TABLE {
        if names.iter().any(|n| normalize(n) == key) {
            return Some(Unit {
                name: names[0],
                dimension: *dim,
                to_si: *factor,
            });
        }
    }
    None
}

/// Look up a unit that must have `dimension`; the error lists the accepted units.
pub fn lookup_dim(name: &str, dimension: Dimension) -> Result<Unit, String> {
    match lookup(name) {
        Some(u) if u.dimension == dimension => Ok(u),
        Some(u) => Err(format!(
            "unit `{name}` is a {} unit, expected a {dimension} unit ({})",
            u.dimension,
            accepted_units(dimension)
        )),
        None => Err(format!(
            "unknown unit `{name}` (expected one of {})",
            accepted_units(dimension)
        )),
    }
}

/// The canonical spellings accepted for `dimension`, comma separated.
pub fn accepted_units(dimension: Dimension) -> String {
    TABLE
        .iter()
        .filter(|(_, d, _)| *d == dimension)
        .map(|(n, _, _)| n[0])
        .collect::<Vec<_>>()
        .join(", ")
}

/// Parse `"<number> [unit]"` into SI. A bare number is read in `default_unit`.
///
/// Errors (as text, the caller adds the location): not a number, non-finite, unknown unit,
/// unit of the wrong dimension.
pub fn parse_quantity(text: &str, dimension: Dimension, default_unit: &str) -> Result<f64, String> {
    let t = text.trim();
    if t.is_empty() {
        return Err("empty value, expected a number with optional unit".into());
    }
    // Split the numeric prefix from the unit suffix.
    let bytes = t.as_bytes();
    let mut end = 0;
    let mut seen_digit = false;
    while end < bytes.len() {
        let c = bytes[end] as char;
        let ok = c.is_ascii_digit()
            || c == '.'
            || ((c == '+' || c == '-') && (end == 0 || matches!(bytes[end - 1] as char, 'e' | 'E')))
            || ((c == 'e' || c == 'E')
                && seen_digit
                && end + 1 < bytes.len()
                && (bytes[end + 1].is_ascii_digit() || bytes[end + 1] == b'+' || bytes[end + 1] == b'-'));
        if !ok {
            break;
        }
        if c.is_ascii_digit() {
            seen_digit = true;
        }
        end += 1;
    }
    let (num, unit) = t.split_at(end);
    if !seen_digit {
        return Err(format!("`{t}` is not a number (expected e.g. `8.5 in`)"));
    }
    let value: f64 = num.parse().map_err(|_| format!("`{t}` is not a number"))?;
    if !value.is_finite() {
        return Err(format!("`{t}` is not a finite number"));
    }
    let unit = unit.trim();
    let unit = if unit.is_empty() { default_unit } else { unit };
    let u = lookup_dim(unit, dimension)?;
    let si = value * u.to_si;
    if !si.is_finite() || si.abs() > MAX_ABS_SI {
        return Err(format!(
            "`{t}` is too large: beyond any physical value (more than {MAX_ABS_SI:e} in SI units, where products of a few such values overflow)"
        ));
    }
    Ok(si)
}

/// Largest magnitude of a quantity accepted in SI units: far beyond any physical value of a
/// drilling case, and small enough that products of a few of them stay finite.
pub const MAX_ABS_SI: f64 = 1e100;

/// Convert an SI value into `unit` (for output and messages).
pub fn from_si(value_si: f64, unit: &str) -> f64 {
    let u = lookup(unit).unwrap_or_else(|| panic!("internal: unit `{unit}` missing from the table"));
    value_si / u.to_si
}

/// WITSML 1.4.1.1 unit symbols (`uom` attributes) that drillpath reads, by dimension: the
/// symbol as the standard spells it (case-sensitive, as the standard's unit dictionary) and the
/// unit of this module's table it is. Lengths: `m`, `ft`, `ftUS` (US survey foot), `in`, `cm`,
/// `mm`, `km`; angles: `dega` (degree), `rad`; mass per length `kg/m`, `lbm/ft`; curvature
/// `dega/m`, `dega/30m`, `dega/100ft`, `rad/m`.
#[rustfmt::skip]
const WITSML_UOMS: &[(&str, &str)] = &[
    ("m", "m"), ("ft", "ft"), ("ftUS", "usft"), ("in", "in"), ("cm", "cm"), ("mm", "mm"), ("km", "km"),
    ("dega", "deg"), ("rad", "rad"),
    ("kg/m", "kg/m"), ("lbm/ft", "lb/ft"),
    ("dega/m", "deg/m"), ("dega/30m", "deg/30m"), ("dega/100ft", "deg/100ft"), ("rad/m", "rad/m"),
];

/// The unit of the WITSML `uom` symbol `uom` (`m`, `ft`, `ftUS`, `in`, `cm`, `mm`, `km`, `dega`,
/// `rad`, `kg/m`, `lbm/ft`, `dega/m`, `dega/30m`, `dega/100ft`, `rad/m`), which must have `dimension`;
/// the error lists the accepted symbols of that dimension.
pub fn witsml_uom(uom: &str, dimension: Dimension) -> Result<Unit, String> {
    let accepted = || {
        WITSML_UOMS
            .iter()
            .filter(|(_, n)| lookup(n).is_some_and(|u| u.dimension == dimension))
            .map(|(w, _)| format!("`{w}`"))
            .collect::<Vec<_>>()
            .join(", ")
    };
    match WITSML_UOMS
        .iter()
        .find(|(w, _)| *w == uom.trim())
        .and_then(|(_, n)| lookup(n))
    {
        Some(u) if u.dimension == dimension => Ok(u),
        Some(u) => Err(format!(
            "uom `{uom}` is a {} unit, expected a {dimension} unit ({})",
            u.dimension,
            accepted()
        )),
        None => Err(format!(
            "unknown uom `{uom}` (drillpath reads the WITSML {dimension} units {})",
            accepted()
        )),
    }
}

/// `x` for an error message as a user would write it: six significant digits at most
/// (rounding noise such as `0.06096000000000001` dropped), plain when short, else in
/// scientific notation (`1e-300`).
pub fn message_number(x: f64) -> String {
    let rounded = format!("{x:.5e}").parse::<f64>().unwrap_or(x);
    let plain = rounded.to_string();
    if plain.len() <= 10 {
        plain
    } else {
        format!("{rounded:e}")
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    #[test]
    fn witsml_uoms() {
        assert_eq!(witsml_uom("dega", Dimension::Angle).unwrap().name, "deg");
        assert_eq!(witsml_uom("ftUS", Dimension::Length).unwrap().to_si, 1200.0 / 3937.0);
        assert_eq!(witsml_uom("rad", Dimension::Angle).unwrap().to_si, 1.0);
        let e = witsml_uom("deg", Dimension::Angle).unwrap_err();
        assert!(e.contains("unknown uom `deg`") && e.contains("`dega`, `rad`"), "{e}");
        let e = witsml_uom("m", Dimension::Angle).unwrap_err();
        assert!(e.contains("is a length unit"), "{e}");
    }

    #[test]
    fn factor_table_matches_definitions() {
        // Reference: NIST SP 811 (exact definitions of the inch, foot, pound).
        assert_relative_eq!(lookup("in").unwrap().to_si, 0.0254, max_relative = 1e-15);
        assert_relative_eq!(lookup("ft").unwrap().to_si, 0.3048, max_relative = 1e-15);
        assert_relative_eq!(lookup("lbf").unwrap().to_si, 4.4482216, max_relative = 1e-8);
        assert_relative_eq!(lookup("psi").unwrap().to_si, 6894.757, max_relative = 1e-6);
        assert_relative_eq!(lookup("ppg").unwrap().to_si, 119.826_427, max_relative = 1e-7);
        assert_relative_eq!(lookup("lb/ft").unwrap().to_si, 1.488_163_9, max_relative = 1e-7);
        assert_relative_eq!(lookup("ft.lbf").unwrap().to_si, 1.355_817_9, max_relative = 1e-7);
        // 1 deg/30 m = 1.016 deg/100 ft (docs/theory.md 2.1).
        let r = lookup("deg/30m").unwrap().to_si / lookup("deg/100ft").unwrap().to_si;
        assert_relative_eq!(r, 1.016, max_relative = 1e-12);
    }

    #[test]
    fn parses_interface_examples() {
        let cases = [
            ("8.5 in", Dimension::Length, 0.2159),
            ("30 ft", Dimension::Length, 9.144),
            ("120 kN", Dimension::Force, 120e3),
            ("25 klbf", Dimension::Force, 111_205.54),
            ("1.2 sg", Dimension::Density, 1200.0),
            ("10 ppg", Dimension::Density, 1198.264),
            ("1250 kg/m3", Dimension::Density, 1250.0),
            ("29 kg/m", Dimension::LinearMass, 29.0),
            ("19.5 lb/ft", Dimension::LinearMass, 29.019_196),
            ("12 m/h", Dimension::Speed, 12.0 / 3600.0),
            ("40 ft/h", Dimension::Speed, 40.0 * 0.3048 / 3600.0),
            ("5 kN.m", Dimension::Moment, 5000.0),
            ("207 GPa", Dimension::Pressure, 207e9),
            ("9000ft", Dimension::Length, 2743.2),
            ("1e3 m", Dimension::Length, 1000.0),
            ("-2.5e-1 m", Dimension::Length, -0.25),
        ];
        for (text, dim, want) in cases {
            let got = parse_quantity(text, dim, "m").unwrap();
            assert_relative_eq!(got, want, max_relative = 1e-6);
        }
        let dls = parse_quantity("3.5 deg/30m", Dimension::Curvature, "deg/30m").unwrap();
        assert_relative_eq!(dls, 3.5_f64.to_radians() / 30.0, max_relative = 1e-12);
    }

    #[test]
    fn bare_number_uses_default_unit() {
        assert_relative_eq!(
            parse_quantity("8.5", Dimension::Length, "in").unwrap(),
            0.2159,
            max_relative = 1e-12
        );
        assert_relative_eq!(
            parse_quantity("60", Dimension::RotarySpeed, "rpm").unwrap(),
            2.0 * std::f64::consts::PI
        );
    }

    #[test]
    fn a_value_that_overflows_in_si_units_is_refused() {
        // 1e308 kN is 1e311 N: beyond f64; 1e308 lb/ft is finite in kg/m, but its weight per
        // length in N/m is not
        let e = parse_quantity("1e308 kN", Dimension::Force, "kN").unwrap_err();
        assert!(e.contains("too large"), "{e}");
        assert!(parse_quantity("1e300 kN", Dimension::Force, "kN").is_err());
        assert!(parse_quantity("1e90 kN", Dimension::Force, "kN").unwrap().is_finite());
    }

    #[test]
    fn rejects_bad_values() {
        assert!(parse_quantity("", Dimension::Length, "m")
            .unwrap_err()
            .contains("empty"));
        assert!(parse_quantity("abc", Dimension::Length, "m")
            .unwrap_err()
            .contains("not a number"));
        assert!(parse_quantity("12 furlong", Dimension::Length, "m")
            .unwrap_err()
            .contains("unknown unit"));
        assert!(parse_quantity("12 kN", Dimension::Length, "m")
            .unwrap_err()
            .contains("force unit"));
        assert!(parse_quantity("NaN m", Dimension::Length, "m").is_err());
        assert!(parse_quantity("inf", Dimension::Length, "m").is_err());
        assert!(parse_quantity("1e999 m", Dimension::Length, "m").is_err());
    }

    /// The US survey foot is exactly 1200/3937 m (NIST), 2 ppm longer than the foot: 0.6 m
    /// over a 10,000 ft well. Common in US survey exports as `usft`.
    #[test]
    fn us_survey_foot_is_1200_over_3937_m() {
        let u = lookup_dim("usft", Dimension::Length).unwrap();
        assert_eq!(u.to_si, 1200.0 / 3937.0);
        assert!((u.to_si - 0.304_800_609_6).abs() < 1e-10);
        assert_eq!(lookup("US Survey Feet").unwrap().to_si, u.to_si);
    }

    #[test]
    fn message_numbers_read_as_written() {
        assert_eq!(message_number(1e-6), "0.000001");
        assert_eq!(message_number(1e-300), "1e-300");
        assert_eq!(message_number(-0.2 * 0.3048), "-0.06096");
        assert_eq!(message_number(0.01), "0.01");
        assert_eq!(message_number(-1.0), "-1");
    }
}
