//! `drillpath import`: an editable, commented case from WITSML 1.4.1.1 files (a trajectory,
//! a wbGeometry, a tubular), written through [`Outputs`] (checked against the inputs, all or
//! nothing).

use std::io::Write;
use std::path::{Path, PathBuf};

use anyhow::bail;

use super::args::ImportArgs;
use super::outputs::Outputs;
use crate::error::InputError;
use crate::io::survey::{read_survey, SurveyUnits};
use crate::io::witsml::geometry::parse_geometry;
use crate::io::witsml::tubular::parse_tubular;
use crate::io::witsml::{read_text, root_name};
use crate::report::case_writer::{import_case, ImportParts};

/// How the case names `file`: its name when it sits in the case's folder `dir`, else its
/// absolute path.
fn as_named(file: &Path, dir: &Path) -> String {
    let abs = |p: &Path| std::fs::canonicalize(p).unwrap_or_else(|_| p.to_path_buf());
    let f = abs(file);
    match f.parent() {
        Some(parent) if parent == abs(dir) => f
            .file_name()
            .map_or_else(|| f.display().to_string(), |n| n.to_string_lossy().into_owned()),
        _ => f.display().to_string(),
    }
}

/// Run the command.
pub fn run(a: ImportArgs) -> anyhow::Result<()> {
    let dir: PathBuf = a
        .out
        .parent()
        .filter(|p| !p.as_os_str().is_empty())
        .unwrap_or(Path::new("."))
        .to_path_buf();
    let mut outputs = Outputs::new();
    for f in &a.files {
        outputs.input(f);
    }
    if a.out.exists() && !a.force {
        bail!(
            "option `--out`: {} exists; not overwritten (use --force)",
            a.out.display()
        );
    }
    outputs.file("--out", &a.out)?;
    let mut parts = ImportParts::default();
    let mut sources = Vec::new();
    let mut seen: Vec<(&str, &Path)> = Vec::new();
    for f in &a.files {
        let text = read_text(f)?;
        let root = root_name(&text, f)?;
        let kind = match root.as_str() {
            "trajectorys" => "trajectory",
            "wbGeometrys" => "wbGeometry",
            "tubulars" => "tubular",
            other => {
                return Err(InputError::file(
                    f,
                    format!("root element `{other}`: `drillpath import` reads WITSML 1.4.1.1 `trajectorys`, `wbGeometrys` and `tubulars` files"),
                )
                .into())
            }
        };
        if let Some((_, prev)) = seen.iter().find(|(k, _)| *k == kind) {
            bail!(
                "{}: a second {kind} file (the first is {}); import one of each",
                f.display(),
                prev.display()
            );
        }
        seen.push((kind, f));
        sources.push(format!("{kind}: {}", f.display()));
        match kind {
            "trajectory" => {
                let units = SurveyUnits {
                    trajectory: a.trajectory.clone(),
                    ..Default::default()
                };
                let sf = read_survey(f, &units)?;
                let last = sf.survey.stations().last().map_or(0.0, |s| s.md_m);
                parts.survey = Some((as_named(f, &dir), a.trajectory.clone(), last));
            }
            "wbGeometry" => {
                parts.hole = Some((
                    parse_geometry(&text, f, a.geometry.as_deref())?,
                    f.display().to_string(),
                ));
            }
            _ => {
                let tub = parse_tubular(&text, f, a.tubular.as_deref(), a.other_as_tube)?;
                parts.string = Some((tub, f.display().to_string()));
            }
        }
    }
    let case = import_case(&parts, &sources);
    outputs.stage(a.out.clone(), case.as_bytes());
    outputs.commit()?;
    let mut out = std::io::stdout().lock();
    writeln!(out, "wrote {} from {}", a.out.display(), sources.join(", "))?;
    writeln!(
        out,
        "next: edit the ASSUMED values, then drillpath survey {}",
        a.out.display()
    )?;
    Ok(())
}
