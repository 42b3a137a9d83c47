//! Measured hook loads (and torques) against bit depth for friction calibration
//! (`drillpath loads CASE --measured FILE.csv`).
//!
//! Header row required; columns found by name (case-insensitive, ignoring spaces, `_` and `-`):
//! - bit depth: `bit_md`, `bit depth`, `md`, `depth`, `measured depth` (default m);
//! - load case: `mode`, `load case`, `case`, `operation` (values as in case files:
//!   `trip_in`, `trip_out`, `rotating_off_bottom`, `drilling`, `sliding`; also `rih`,
//!   `slack_off` = trip_in, `pooh`, `pick_up` = trip_out, `rotating` = rotating_off_bottom);
//! - hook load: `hook_load`, `hookload`, `hkld` (default kN);
//! - optional surface torque: `torque`, `surface_torque` (default kN.m);
//! - optional weight on bit: `wob`, `weight on bit` (default kN), for on-bottom rows.
//!
//! Units come from a bracket or parenthesis (`Hook load [klbf]`) or a suffix after the last
//! underscore (`hook_load_kN`, `md_ft`, `torque_kNm`). Lines starting with `#` and blank lines
//! are skipped; other columns are ignored. Every error names the file, line and column.

use crate::case::Mode;
use crate::error::{InputError, InputResult};
use crate::loads::calibrate::MeasuredPoint;
use crate::units::{lookup_dim, Dimension, Unit};
use std::path::Path;

#[derive(Clone, Copy, PartialEq)]
enum Role {
    Md,
    Mode,
    Hook,
    Torque,
    Wob,
}

const ROLES: [(Role, &[&str], Dimension, &str); 5] = [
    (
        Role::Md,
        &["bitmd", "bitdepth", "md", "depth", "measureddepth", "bitmeasureddepth"],
        Dimension::Length,
        "m",
    ),
    (
        Role::Mode,
        &["mode", "loadcase", "case", "operation"],
        Dimension::Dimensionless,
        "-",
    ),
    (Role::Hook, &["hookload", "hkld", "hook"], Dimension::Force, "kN"),
    (
        Role::Torque,
        &["torque", "surfacetorque", "tq", "rotarytorque"],
        Dimension::Moment,
        "kN.m",
    ),
    (Role::Wob, &["wob", "weightonbit"], Dimension::Force, "kN"),
];

fn normalize(name: &str) -> String {
    name.chars()
        .filter(|c| !c.is_whitespace() && *c != '_' && *c != '-')
        .flat_map(char::to_lowercase)
        .collect()
}

/// Split a header into its name and unit text (bracket, parenthesis or `_unit` suffix).
fn split_header(h: &str) -> (String, Option<String>) {
    let t = h.trim();
    for (open, close) in [('[', ']'), ('(', ')')] {
        if let Some(inner) = t.strip_suffix(close) {
            if let Some(p) = inner.rfind(open) {
                return (inner[..p].trim().to_string(), Some(inner[p + 1..].trim().to_string()));
            }
        }
    }
    if let Some(p) = t.rfind('_') {
        let (name, unit) = (&t[..p], &t[p + 1..]);
        if !name.is_empty() && crate::units::lookup(unit).is_some() {
            return (name.to_string(), Some(unit.to_string()));
        }
    }
    (t.to_string(), None)
}

/// Parse a load-case name (see the module documentation for the aliases).
pub fn parse_mode(text: &str) -> Option<Mode> {
    let k: String = text
        .trim()
        .to_ascii_lowercase()
        .chars()
        .map(|c| if c == ' ' || c == '-' { '_' } else { c })
        .collect();
    Mode::parse(&k).or(match k.as_str() {
        "rih" | "run_in" | "running_in" | "slack_off" | "slackoff" | "tripping_in" => Some(Mode::TripIn),
        "pooh" | "pull_out" | "pulling_out" | "pick_up" | "pickup" | "tripping_out" => Some(Mode::TripOut),
        "rotating" | "rotate_off_bottom" | "free_rotating" | "rotating_off" => Some(Mode::RotatingOffBottom),
        _ => None,
    })
}

/// Read and validate the measured file at `path` (see the module documentation). Depths must
/// lie in `(md_min, md_max]` (the surveyed hole).
pub fn read_measured_csv(path: &Path, md_min: f64, md_max: f64) -> InputResult<Vec<MeasuredPoint>> {
    let bytes =
        std::fs::read(path).map_err(|e| InputError::file(path, format!("cannot read the measured file: {e}")))?;
    let text = String::from_utf8_lossy(&bytes);
    parse_measured_csv(text.trim_start_matches('\u{feff}'), path, md_min, md_max)
}

/// Parse measured points from `text` (errors name `path`).
pub fn parse_measured_csv(text: &str, path: &Path, md_min: f64, md_max: f64) -> InputResult<Vec<MeasuredPoint>> {
    let mut lines = text
        .lines()
        .enumerate()
        .map(|(i, l)| (i + 1, l.trim()))
        .filter(|(_, l)| !l.is_empty() && !l.starts_with('#'));
    let (hline, header) = lines
        .next()
        .ok_or_else(|| InputError::file(path, "the measured file is empty (expected a header row)"))?;
    let delim = if header.contains(',') {
        ','
    } else if header.contains(';') {
        ';'
    } else {
        '\t'
    };
    let heads: Vec<&str> = header.split(delim).map(str::trim).collect();
    // column index, header text, unit
    let mut cols: Vec<Option<(usize, String, Unit)>> = vec![None; ROLES.len()];
    for (i, h) in heads.iter().enumerate() {
        let (name, unit) = split_header(h);
        let norm = normalize(&name);
        for (r, (_, names, dim, default)) in ROLES.iter().enumerate() {
            if names.contains(&norm.as_str()) {
                if let Some((_, prev, _)) = &cols[r] {
                    return Err(InputError::line(
                        path,
                        hline,
                        Some(h),
                        format!("two columns for the same quantity: `{prev}` and `{h}`"),
                    ));
                }
                let unit = if *dim == Dimension::Dimensionless {
                    lookup_dim("-", *dim).expect("dimensionless unit")
                } else {
                    lookup_dim(unit.as_deref().unwrap_or(default), *dim)
                        .map_err(|m| InputError::line(path, hline, Some(h), m))?
                };
                cols[r] = Some((i, h.to_string(), unit));
            }
        }
    }
    for (r, what) in [
        (0, "bit depth (bit_md)"),
        (1, "load case (mode)"),
        (2, "hook load (hook_load_kN)"),
    ] {
        if cols[r].is_none() {
            return Err(InputError::line(
                path,
                hline,
                None,
                format!("no {what} column; found columns: {}", heads.join(", ")),
            ));
        }
    }
    let mut out = Vec::new();
    for (line, l) in lines {
        let fields: Vec<&str> = l.split(delim).map(|f| f.trim().trim_matches('"')).collect();
        let get = |r: usize, required: bool| -> InputResult<Option<f64>> {
            let Some((i, h, unit)) = &cols[r] else { return Ok(None) };
            let t = fields.get(*i).copied().unwrap_or("");
            if t.is_empty() {
                return if required {
                    Err(InputError::line(path, line, Some(h), "missing value"))
                } else {
                    Ok(None)
                };
            }
            let v: f64 = t
                .parse()
                .map_err(|_| InputError::line(path, line, Some(h), format!("`{t}` is not a number")))?;
            if !v.is_finite() {
                return Err(InputError::line(
                    path,
                    line,
                    Some(h),
                    format!("`{t}` is not a finite number"),
                ));
            }
            Ok(Some(v * unit.to_si))
        };
        let md = get(0, true)?.expect("required");
        let (_, md_head, _) = cols[0].as_ref().expect("checked");
        if md <= md_min || md > md_max + 1e-6 {
            return Err(InputError::line(
                path,
                line,
                Some(md_head),
                format!("bit depth {md:.2} m is outside the surveyed hole ({md_min:.2} m to {md_max:.2} m)"),
            ));
        }
        let (mi, mode_head, _) = cols[1].as_ref().expect("checked");
        let mode_text = fields.get(*mi).copied().unwrap_or("");
        let mode = parse_mode(mode_text).ok_or_else(|| {
            InputError::line(
                path,
                line,
                Some(mode_head),
                format!("unknown load case `{mode_text}` (expected {})", Mode::NAMES),
            )
        })?;
        let hook = get(2, true)?.expect("required");
        let (_, hook_head, _) = cols[2].as_ref().expect("checked");
        if hook <= 0.0 {
            return Err(InputError::line(
                path,
                line,
                Some(hook_head),
                "hook load must be positive",
            ));
        }
        let torque = get(3, false)?;
        if let (Some(t), Some((_, h, _))) = (torque, &cols[3]) {
            if t < 0.0 {
                return Err(InputError::line(path, line, Some(h), "torque must not be negative"));
            }
        }
        let wob = get(4, false)?;
        if let (Some(w), Some((_, h, _))) = (wob, &cols[4]) {
            if w < 0.0 {
                return Err(InputError::line(path, line, Some(h), "WOB must not be negative"));
            }
        }
        out.push(MeasuredPoint {
            line,
            bit_md_m: md,
            mode,
            hook_load_n: hook,
            torque_nm: torque,
            wob_n: wob,
        });
    }
    if out.is_empty() {
        return Err(InputError::file(
            path,
            "the measured file has a header but no data rows",
        ));
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse(t: &str) -> InputResult<Vec<MeasuredPoint>> {
        parse_measured_csv(t, Path::new("m.csv"), 0.0, 3000.0)
    }

    #[test]
    fn units_from_headers_and_aliases() {
        let p =
            parse("# rig data\nBit depth [ft],Mode,Hook load [klbf],torque_kNm\n1000,POOH,100,\n2000,rotating,90,5\n")
                .unwrap();
        assert_eq!(p.len(), 2);
        assert!((p[0].bit_md_m - 304.8).abs() < 1e-9);
        assert_eq!(p[0].mode, Mode::TripOut);
        assert!((p[0].hook_load_n - 444_822.16152605).abs() < 1e-3);
        assert_eq!(p[0].torque_nm, None);
        assert_eq!(p[1].mode, Mode::RotatingOffBottom);
        assert_eq!(p[1].torque_nm, Some(5000.0));
        assert_eq!(p[1].line, 4);
    }

    #[test]
    fn errors_name_line_and_column() {
        let e = parse("bit_md_m,mode,hook_load_kN\n100,trip_in,50\n200,dancing,60\n").unwrap_err();
        assert!(e.to_string().contains("line 3, column `mode`"), "{e}");
        let e = parse("bit_md_m,mode,hook_load_kN\n100,trip_in,abc\n").unwrap_err();
        assert!(e.to_string().contains("line 2, column `hook_load_kN`"), "{e}");
        let e = parse("bit_md_m,mode,hook_load_kN\n4000,trip_in,50\n").unwrap_err();
        assert!(e.to_string().contains("outside the surveyed hole"), "{e}");
        let e = parse("bit_md_m,mode\n100,trip_in\n").unwrap_err();
        assert!(e.to_string().contains("no hook load"), "{e}");
        let e = parse("bit_md_m,mode,hook_load_furlongs\n100,trip_in,5\n").unwrap_err();
        assert!(e.to_string().contains("line 1"), "{e}");
        assert!(parse("bit_md_m,mode,hook_load_kN\n").is_err());
    }
}
