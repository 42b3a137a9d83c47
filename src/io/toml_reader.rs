//! A small reader over a TOML table that rejects unknown keys up front, converts quantities
//! with units, and reports unknown keys by their full dotted path (typos must not pass).

use crate::error::{InputError, InputResult};
use crate::units::{parse_quantity, Dimension};
use std::path::Path;
use toml::{Table, Value};

/// One TOML table being read; call [`Section::check_known`] first to reject unknown keys.
pub struct Section<'a> {
    file: &'a Path,
    prefix: String,
    table: &'a Table,
}

fn type_name(v: &Value) -> &'static str {
    match v {
        Value::String(_) => "a string",
        Value::Integer(_) => "an integer",
        Value::Float(_) => "a number",
        Value::Boolean(_) => "a boolean",
        Value::Datetime(_) => "a date",
        Value::Array(_) => "an array",
        Value::Table(_) => "a table",
    }
}

impl<'a> Section<'a> {
    /// Reader over `table`, whose keys are reported as `prefix.key` (no prefix at top level).
    pub fn new(file: &'a Path, prefix: impl Into<String>, table: &'a Table) -> Self {
        Section {
            file,
            prefix: prefix.into(),
            table,
        }
    }

    /// Full dotted path of `key`.
    pub fn path(&self, key: &str) -> String {
        if self.prefix.is_empty() {
            key.to_string()
        } else {
            format!("{}.{}", self.prefix, key)
        }
    }

    /// Error at `key` of this table.
    pub fn error(&self, key: &str, message: impl Into<String>) -> InputError {
        InputError::key(self.file, self.path(key), message)
    }

    fn get(&self, key: &str) -> Option<&'a Value> {
        self.table.get(key)
    }

    /// True if the key is present.
    pub fn has(&self, key: &str) -> bool {
        self.get(key).is_some()
    }

    /// Optional quantity in SI: a number (read in `default_unit`) or a string with units.
    pub fn quantity(&self, key: &str, dim: Dimension, default_unit: &str) -> InputResult<Option<f64>> {
        let v = match self.get(key) {
            None => return Ok(None),
            Some(v) => v,
        };
        let parsed = match v {
            Value::Integer(i) => parse_quantity(&i.to_string(), dim, default_unit),
            Value::Float(f) => {
                if f.is_finite() {
                    parse_quantity(&format!("{f:e}"), dim, default_unit)
                } else {
                    Err(format!("`{f}` is not a finite number"))
                }
            }
            Value::String(s) => parse_quantity(s, dim, default_unit),
            other => Err(format!(
                "expected a number or a string with units (e.g. \"8.5 in\"), found {}",
                type_name(other)
            )),
        };
        parsed.map(Some).map_err(|m| self.error(key, m))
    }

    /// Required quantity in SI.
    pub fn req_quantity(&self, key: &str, dim: Dimension, default_unit: &str) -> InputResult<f64> {
        self.quantity(key, dim, default_unit)?
            .ok_or_else(|| self.error(key, format!("missing required {dim} (e.g. a number in {default_unit})")))
    }

    /// Optional quantity that must be > 0 (or >= 0 when `allow_zero`).
    pub fn positive(&self, key: &str, dim: Dimension, unit: &str, allow_zero: bool) -> InputResult<Option<f64>> {
        let v = self.quantity(key, dim, unit)?;
        if let Some(x) = v {
            if x < 0.0 || (!allow_zero && x == 0.0) {
                let what = if allow_zero {
                    "must not be negative"
                } else {
                    "must be positive"
                };
                return Err(self.error(key, format!("{what} (got {})", self.raw(key))));
            }
        }
        Ok(v)
    }

    /// The value as written, for messages.
    pub fn raw(&self, key: &str) -> String {
        self.table.get(key).map(|v| v.to_string()).unwrap_or_default()
    }

    /// Optional plain number (no units).
    pub fn number(&self, key: &str) -> InputResult<Option<f64>> {
        self.quantity(key, Dimension::Dimensionless, "-")
    }

    /// Optional string.
    pub fn string(&self, key: &str) -> InputResult<Option<String>> {
        match self.get(key) {
            None => Ok(None),
            Some(Value::String(s)) => Ok(Some(s.clone())),
            Some(other) => Err(self.error(key, format!("expected a string, found {}", type_name(other)))),
        }
    }

    /// Optional boolean.
    pub fn boolean(&self, key: &str) -> InputResult<Option<bool>> {
        match self.get(key) {
            None => Ok(None),
            Some(Value::Boolean(b)) => Ok(Some(*b)),
            Some(other) => Err(self.error(key, format!("expected true or false, found {}", type_name(other)))),
        }
    }

    /// Optional array of strings (a single string is accepted as a list of one); each bad
    /// item is reported as `key[i]`.
    pub fn strings(&self, key: &str) -> InputResult<Option<Vec<String>>> {
        match self.get(key) {
            None => Ok(None),
            Some(Value::String(s)) => Ok(Some(vec![s.clone()])),
            Some(Value::Array(items)) => items
                .iter()
                .enumerate()
                .map(|(i, item)| match item {
                    Value::String(s) => Ok(s.clone()),
                    other => Err(self.error(
                        &format!("{key}[{i}]"),
                        format!("expected a string, found {}", type_name(other)),
                    )),
                })
                .collect::<InputResult<Vec<String>>>()
                .map(Some),
            Some(other) => Err(self.error(key, format!("expected an array of strings, found {}", type_name(other)))),
        }
    }

    /// Optional sub-table.
    pub fn table(&self, key: &str) -> InputResult<Option<Section<'a>>> {
        match self.get(key) {
            None => Ok(None),
            Some(Value::Table(t)) => Ok(Some(Section::new(self.file, self.path(key), t))),
            Some(other) => Err(self.error(key, format!("expected a table, found {}", type_name(other)))),
        }
    }

    /// Optional array of tables; each is reported as `key[i]`.
    pub fn tables(&self, key: &str) -> InputResult<Option<Vec<Section<'a>>>> {
        match self.get(key) {
            None => Ok(None),
            Some(Value::Array(items)) => {
                let mut out = Vec::new();
                for (i, item) in items.iter().enumerate() {
                    match item {
                        Value::Table(t) => out.push(Section::new(self.file, format!("{}[{}]", self.path(key), i), t)),
                        other => {
                            return Err(self.error(
                                &format!("{key}[{i}]"),
                                format!("expected a table, found {}", type_name(other)),
                            ))
                        }
                    }
                }
                Ok(Some(out))
            }
            Some(other) => Err(self.error(key, format!("expected an array of tables, found {}", type_name(other)))),
        }
    }

    /// Reject, before anything is read, keys that are not in `known` (so a misspelt required
    /// key is named as unknown rather than reported as missing).
    pub fn check_known(&self, known: &[&str]) -> InputResult<()> {
        for key in self.table.keys() {
            if !known.contains(&key.as_str()) {
                let hint = closest(key, known)
                    .map(|k| format!(" (did you mean `{k}`?)"))
                    .unwrap_or_default();
                return Err(self.error(
                    &as_written(key),
                    format!("unknown key{hint}; accepted keys here: {}", known.join(", ")),
                ));
            }
        }
        Ok(())
    }

    /// Optional array of exactly three lengths in m (numbers or strings with units).
    pub fn length_triple(&self, key: &str) -> InputResult<Option<[f64; 3]>> {
        match self.get(key) {
            None => Ok(None),
            Some(Value::Array(items)) if items.len() == 3 => {
                let mut out = [0.0; 3];
                for (i, v) in items.iter().enumerate() {
                    let parsed = match v {
                        Value::Integer(x) => parse_quantity(&x.to_string(), Dimension::Length, "m"),
                        Value::Float(x) if x.is_finite() => parse_quantity(&format!("{x:e}"), Dimension::Length, "m"),
                        Value::String(t) => parse_quantity(t, Dimension::Length, "m"),
                        other => Err(format!("expected a length, found {}", type_name(other))),
                    };
                    out[i] = parsed.map_err(|m| self.error(&format!("{key}[{i}]"), m))?;
                }
                Ok(Some(out))
            }
            Some(_) => Err(self.error(key, "expected [north, east, tvd] in m")),
        }
    }
}

/// A key as TOML writes it: bare (`od`) when it can be, else quoted (`""`, `"a b"`), so that an
/// empty or spaced key is still visible in a message.
fn as_written(key: &str) -> String {
    let bare = !key.is_empty() && key.chars().all(|c| c.is_ascii_alphanumeric() || c == '_' || c == '-');
    if bare {
        key.to_string()
    } else {
        format!("{key:?}")
    }
}

/// Closest string by edit distance (at most 3 edits).
fn closest<'k>(key: &str, known: &[&'k str]) -> Option<&'k str> {
    known
        .iter()
        .map(|k| (edit_distance(key, k), *k))
        .filter(|(d, _)| *d <= 3)
        .min_by_key(|(d, _)| *d)
        .map(|(_, k)| k)
}

fn edit_distance(a: &str, b: &str) -> usize {
    let b: Vec<char> = b.chars().collect();
    let mut prev: Vec<usize> = (0..=b.len()).collect();
    for (i, ca) in a.chars().enumerate() {
        let mut cur = vec![i + 1; b.len() + 1];
        for j in 0..b.len() {
            cur[j + 1] = (prev[j] + usize::from(ca != b[j])).min(prev[j + 1] + 1).min(cur[j] + 1);
        }
        prev = cur;
    }
    prev[b.len()]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn unknown_empty_or_spaced_key_is_shown_quoted() {
        // Found by tests/verification/fuzz_input.rs: `"" = 1` was reported as key ``.
        for (text, shown) in [
            ("\"\" = 1", "key `\"\"`"),
            ("[mud]\n\"a b\" = 1", "key `mud.\"a b\"`"),
            ("odd = 1", "key `odd`"),
        ] {
            let table: Table = text.parse().unwrap();
            let top = Section::new(Path::new("c.toml"), "", &table);
            let e = match table.get("mud") {
                Some(Value::Table(t)) => Section::new(Path::new("c.toml"), "mud", t).check_known(&["density"]),
                _ => top.check_known(&["od"]),
            }
            .unwrap_err()
            .to_string();
            assert!(e.starts_with(&format!("c.toml: {shown}: unknown key")), "{e}");
        }
    }
}
