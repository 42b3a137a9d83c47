//! The crate's shape, checked on its source text: the layers of `src/` import only downward,
//! no module imports itself back through others (no circle, at file granularity), and no
//! function or file outgrows the limits of `docs/architecture.md` unless that document names
//! it with the reason.
//!
//! Reference: the layer table below, which `docs/architecture.md` and the crate documentation
//! (`src/lib.rs`) state in words. A `use` of a higher layer, a new circle or a new long
//! function fails the test with the file and the line.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

/// Top-level modules from the bottom layer up; a module may import its own layer's other
/// modules only where listed in [`SAME_LAYER`], and any lower layer.
const LAYERS: &[&[&str]] = &[
    &["units", "error", "numerics"],
    &["geometry", "string"],
    &["case"],
    &["models"],
    &["predict", "loads"],
    &["io"],
    &["analytical"],
    &["report"],
    &["cli"],
];

/// Imports allowed within one layer (importer, imported).
const SAME_LAYER: &[(&str, &str)] = &[("geometry", "units"), ("string", "units")];

/// Longest function body allowed, lines (signature to closing brace).
const MAX_FUNCTION_LINES: usize = 150;

/// Longest source file allowed, lines before its `#[cfg(test)]` module.
const MAX_FILE_LINES: usize = 800;

fn src_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("src")
}

fn rust_files(dir: &Path, out: &mut Vec<PathBuf>) {
    let mut entries: Vec<_> = std::fs::read_dir(dir)
        .expect("read src")
        .flatten()
        .map(|e| e.path())
        .collect();
    entries.sort();
    for p in entries {
        if p.is_dir() {
            rust_files(&p, out);
        } else if p.extension().is_some_and(|e| e == "rs") {
            out.push(p);
        }
    }
}

/// Module path of a source file (`src/models/fem/mod.rs` -> `models::fem`).
fn module_of(file: &Path) -> Vec<String> {
    let rel = file.strip_prefix(src_dir()).expect("under src");
    let mut parts: Vec<String> = rel.iter().map(|s| s.to_string_lossy().into_owned()).collect();
    let last = parts.pop().expect("file name");
    let stem = last.trim_end_matches(".rs").to_string();
    if !matches!(stem.as_str(), "mod" | "lib" | "main") {
        parts.push(stem);
    }
    parts
}

/// The code of a file without its test module, comments and string literals (each line kept,
/// so that line numbers stay right).
fn code_lines(text: &str) -> Vec<String> {
    let mut lines = Vec::new();
    let mut in_string = false;
    for line in text.lines() {
        if line.trim_start().starts_with("#[cfg(test)]") {
            break;
        }
        let mut out = String::with_capacity(line.len());
        let chars: Vec<char> = line.chars().collect();
        let mut i = 0;
        while i < chars.len() {
            let c = chars[i];
            if in_string {
                if c == '\\' {
                    i += 2;
                    continue;
                }
                if c == '"' {
                    in_string = false;
                }
                i += 1;
                continue;
            }
            if c == '/' && chars.get(i + 1) == Some(&'/') {
                break;
            }
            if c == '"' {
                in_string = true;
                out.push_str("\"\"");
                i += 1;
                continue;
            }
            if c == '\'' && chars.get(i + 2) == Some(&'\'') {
                // a char literal such as '{'
                i += 3;
                continue;
            }
            out.push(c);
            i += 1;
        }
        lines.push(out);
    }
    lines
}

/// Paths named by `crate::...` and `super::...` in a line, with `{a, b::c}` groups expanded one
/// level, resolved to absolute module paths (`super` relative to `module`).
fn referenced_paths(line: &str, module: &[String]) -> Vec<Vec<String>> {
    let mut out = Vec::new();
    for (key, base) in [("crate::", Vec::new()), ("super::", parent_of(module))] {
        let mut rest = line;
        while let Some(pos) = rest.find(key) {
            let before = &rest[..pos];
            if before.ends_with(|c: char| c.is_alphanumeric() || c == '_' || c == ':') {
                rest = &rest[pos + key.len()..];
                continue;
            }
            rest = &rest[pos + key.len()..];
            let mut prefix = base.clone();
            let mut tail = rest;
            // further `super::` steps
            while key == "super::" && tail.starts_with("super::") {
                prefix.pop();
                tail = &tail["super::".len()..];
            }
            collect_path(tail, prefix, &mut out);
        }
    }
    out
}

/// The module `super` names: the parent of `module` (for `a/b.rs` and `a/mod.rs` alike, since
/// `module` is already the file's module path).
fn parent_of(module: &[String]) -> Vec<String> {
    module[..module.len().saturating_sub(1)].to_vec()
}

fn collect_path(text: &str, mut prefix: Vec<String>, out: &mut Vec<Vec<String>>) {
    let mut t = text;
    loop {
        if let Some(inner) = t.strip_prefix('{') {
            let end = inner.find('}').unwrap_or(inner.len());
            for item in inner[..end].split(',') {
                let item = item.trim();
                if !item.is_empty() {
                    collect_path(item, prefix.clone(), out);
                }
            }
            return;
        }
        let ident: String = t.chars().take_while(|c| c.is_alphanumeric() || *c == '_').collect();
        if ident.is_empty() {
            break;
        }
        prefix.push(ident.clone());
        t = &t[ident.len()..];
        match t.strip_prefix("::") {
            Some(r) => t = r,
            None => break,
        }
    }
    out.push(prefix);
}

struct Source {
    module: Vec<String>,
    file: PathBuf,
    lines: Vec<String>,
    total_lines: usize,
}

fn sources() -> Vec<Source> {
    let mut files = Vec::new();
    rust_files(&src_dir(), &mut files);
    files
        .into_iter()
        .filter(|f| !f.to_string_lossy().ends_with("tests.rs"))
        .map(|f| {
            let text = std::fs::read_to_string(&f).expect("read source");
            Source {
                module: module_of(&f),
                lines: code_lines(&text),
                total_lines: text.lines().count(),
                file: f,
            }
        })
        .collect()
}

fn layer_of(top: &str) -> Option<usize> {
    LAYERS.iter().position(|l| l.contains(&top))
}

/// The longest module of `modules` that `path` starts with.
fn resolve(path: &[String], modules: &BTreeSet<Vec<String>>) -> Option<Vec<String>> {
    (1..=path.len())
        .rev()
        .map(|n| path[..n].to_vec())
        .find(|p| modules.contains(p))
}

fn display(file: &Path) -> String {
    file.strip_prefix(Path::new(env!("CARGO_MANIFEST_DIR")))
        .unwrap_or(file)
        .display()
        .to_string()
}

/// Module-level imports: (importer, imported) -> first (file, line) where it happens.
fn import_edges(srcs: &[Source]) -> BTreeMap<(Vec<String>, Vec<String>), (String, usize)> {
    let modules: BTreeSet<Vec<String>> = srcs.iter().map(|s| s.module.clone()).collect();
    let mut edges = BTreeMap::new();
    for s in srcs {
        if s.module.is_empty() {
            continue;
        }
        for (n, line) in s.lines.iter().enumerate() {
            for p in referenced_paths(line, &s.module) {
                let Some(target) = resolve(&p, &modules) else {
                    continue;
                };
                // a module using its own descendants is its job (declaring and re-exporting)
                if target.starts_with(&s.module) || s.module.starts_with(&target) {
                    continue;
                }
                edges
                    .entry((s.module.clone(), target))
                    .or_insert((display(&s.file), n + 1));
            }
        }
    }
    edges
}

#[test]
fn layers_import_only_downward() {
    let srcs = sources();
    let mut bad = Vec::new();
    for ((from, to), (file, line)) in import_edges(&srcs) {
        let (a, b) = (from[0].as_str(), to[0].as_str());
        if a == b {
            continue;
        }
        let (Some(la), Some(lb)) = (layer_of(a), layer_of(b)) else {
            bad.push(format!(
                "{file}:{line}: `{a}` or `{b}` is in no layer of tests/verification/architecture.rs"
            ));
            continue;
        };
        if lb > la || (lb == la && !SAME_LAYER.contains(&(a, b))) {
            bad.push(format!(
                "{file}:{line}: `{}` imports `{}` from a layer above or beside it",
                from.join("::"),
                to.join("::")
            ));
        }
    }
    assert!(bad.is_empty(), "upward imports:\n{}", bad.join("\n"));
}

#[test]
fn no_import_circles() {
    let srcs = sources();
    let edges = import_edges(&srcs);
    let mut circles = BTreeSet::new();
    // at every granularity: files, and folders collapsed to their first `depth` names
    for depth in [1, 2, 3, usize::MAX] {
        let cut = |m: &Vec<String>| m[..m.len().min(depth)].to_vec();
        let mut graph: BTreeMap<Vec<String>, BTreeSet<Vec<String>>> = BTreeMap::new();
        for (from, to) in edges.keys() {
            let (a, b) = (cut(from), cut(to));
            if a != b {
                graph.entry(a).or_default().insert(b);
            }
        }
        for ((from, to), (file, line)) in &edges {
            let (a, b) = (cut(from), cut(to));
            if a == b {
                continue;
            }
            // is `a` reachable from `b`?
            let mut seen = BTreeSet::new();
            let mut stack = vec![b.clone()];
            while let Some(m) = stack.pop() {
                if m == a {
                    circles.insert(format!(
                        "{file}:{line}: `{}` -> `{}` closes a circle",
                        a.join("::"),
                        b.join("::")
                    ));
                    break;
                }
                if seen.insert(m.clone()) {
                    stack.extend(graph.get(&m).into_iter().flatten().cloned());
                }
            }
        }
    }
    assert!(
        circles.is_empty(),
        "import circles:\n{}",
        circles.into_iter().collect::<Vec<_>>().join("\n")
    );
}

/// Files and functions over the limits that `docs/architecture.md` names with its reason.
fn allowed_exceptions() -> String {
    std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("docs/architecture.md")).unwrap_or_default()
}

/// (file, first line, name, lines) of every function longer than [`MAX_FUNCTION_LINES`].
fn long_functions(s: &Source) -> Vec<(usize, String, usize)> {
    let mut out = Vec::new();
    for (start, line) in s.lines.iter().enumerate() {
        let t = line.trim_start();
        let Some(pos) = t.find("fn ").filter(|&p| {
            let head = &t[..p];
            head.split_whitespace().all(|w| {
                matches!(
                    w,
                    "pub" | "pub(crate)" | "pub(super)" | "const" | "async" | "unsafe" | "extern"
                )
            })
        }) else {
            continue;
        };
        let name: String = t[pos + 3..]
            .chars()
            .take_while(|c| c.is_alphanumeric() || *c == '_')
            .collect();
        // the body: from the first `{` after the signature to its matching `}`
        let mut depth = 0i64;
        let mut opened = false;
        let mut end = None;
        'scan: for (k, l) in s.lines.iter().enumerate().skip(start) {
            for c in l.chars() {
                match c {
                    '{' => {
                        depth += 1;
                        opened = true;
                    }
                    '}' => depth -= 1,
                    ';' if !opened => break 'scan,
                    _ => {}
                }
                if opened && depth == 0 {
                    end = Some(k);
                    break 'scan;
                }
            }
        }
        if let Some(e) = end {
            let n = e - start + 1;
            if n > MAX_FUNCTION_LINES {
                out.push((start + 1, name, n));
            }
        }
    }
    out
}

#[test]
fn functions_and_files_stay_short() {
    let doc = allowed_exceptions();
    let mut bad = Vec::new();
    for s in sources() {
        let file = display(&s.file);
        let rel = file.trim_start_matches("src/");
        let code = s.lines.len();
        if code > MAX_FILE_LINES && !doc.contains(&format!("`{rel}`")) {
            bad.push(format!(
                "{file}: {code} lines before its tests (limit {MAX_FILE_LINES}; total {})",
                s.total_lines
            ));
        }
        for (line, name, n) in long_functions(&s) {
            if !doc.contains(&format!("`{rel}` `{name}`")) {
                bad.push(format!(
                    "{file}:{line}: fn `{name}` has {n} lines (limit {MAX_FUNCTION_LINES})"
                ));
            }
        }
    }
    assert!(
        bad.is_empty(),
        "over the size limits (split them, or name them with the reason in docs/architecture.md):\n{}",
        bad.join("\n")
    );
}

/// The checks above must see real imports: a known downward import is found, and a made-up
/// upward one would be flagged.
#[test]
fn the_import_scanner_sees_imports() {
    let srcs = sources();
    let edges = import_edges(&srcs);
    assert!(
        edges.keys().any(|(a, b)| a[0] == "cli" && b[0] == "models"),
        "the scanner found no import of models by cli"
    );
    let m = vec!["models".to_string(), "fem".to_string(), "model".to_string()];
    let p = referenced_paths("use super::{element::beam::X, mesh};", &m);
    assert_eq!(
        p,
        vec![
            ["models", "fem", "element", "beam", "X"]
                .iter()
                .map(|s| s.to_string())
                .collect::<Vec<_>>(),
            ["models", "fem", "mesh"]
                .iter()
                .map(|s| s.to_string())
                .collect::<Vec<_>>(),
        ]
    );
    let f = Source {
        module: vec!["x".into()],
        file: src_dir().join("x.rs"),
        lines: std::iter::once("fn long() {".to_string())
            .chain((0..MAX_FUNCTION_LINES).map(|_| "    let a = 1;".to_string()))
            .chain(std::iter::once("}".to_string()))
            .collect(),
        total_lines: 0,
    };
    assert_eq!(long_functions(&f).len(), 1, "a function over the limit must be found");
}
