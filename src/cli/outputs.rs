//! The files a run writes: every output path checked against the run's inputs before any work
//! (through links and relative paths), then all outputs written together at the end, or none.

use crate::io::paths::{resolve, write_temp};
use anyhow::bail;
use std::path::{Path, PathBuf};

/// The inputs a run read and the outputs it will write.
#[derive(Debug, Default)]
pub struct Outputs {
    /// Each input as given, with its identity on disk.
    inputs: Vec<(PathBuf, FileId)>,
    /// Each declared output: the option that named it and its resolved path.
    claimed: Vec<(String, PathBuf)>,
    /// Contents to write at [`Outputs::commit`], by path as given.
    staged: Vec<(PathBuf, Vec<u8>)>,
}

/// What makes two paths the same file: the device and inode where the file exists (hard links
/// and symbolic links included), else the resolved path.
#[derive(Debug, Clone, PartialEq, Eq)]
enum FileId {
    Inode(u64, u64),
    Path(PathBuf),
}

impl FileId {
    fn of(path: &Path) -> FileId {
        #[cfg(unix)]
        if let Ok(m) = std::fs::metadata(path) {
            use std::os::unix::fs::MetadataExt;
            return FileId::Inode(m.dev(), m.ino());
        }
        FileId::Path(resolve(path))
    }
}

impl Outputs {
    /// No inputs, no outputs yet.
    pub fn new() -> Outputs {
        Outputs::default()
    }

    /// Record a file the run reads (case, survey, caliper, measured CSV ...).
    pub fn input(&mut self, path: &Path) {
        self.inputs.push((path.to_path_buf(), FileId::of(path)));
    }

    /// Record every file a case was read from.
    pub fn case_inputs(&mut self, case: &crate::case::Case) {
        for p in case.input_files() {
            self.input(&p);
        }
    }

    /// Declare the output file `path` named by `option`: refused when it is an input of the
    /// run, an existing directory, inside an existing non-directory, or already claimed.
    pub fn file(&mut self, option: &str, path: &Path) -> anyhow::Result<()> {
        if path.as_os_str().is_empty() {
            bail!("option `{option}`: an empty path");
        }
        if path.is_dir() {
            bail!(
                "option `{option}`: {} is an existing directory, not a file; nothing was computed or written",
                path.display()
            );
        }
        self.check_parent(option, path)?;
        let id = FileId::of(path);
        if let Some((input, _)) = self.inputs.iter().find(|(_, i)| *i == id) {
            bail!(
                "option `{option}`: {} is an input of this run ({}); refused so as not to overwrite it; nothing was computed or written",
                path.display(),
                input.display()
            );
        }
        let resolved = resolve(path);
        if let Some((other, _)) = self.claimed.iter().find(|(_, p)| *p == resolved) {
            bail!(
                "option `{option}`: {} is also written by `{other}`; give different paths",
                path.display()
            );
        }
        self.claimed.push((option.to_string(), resolved));
        Ok(())
    }

    /// Declare the output directory `dir` named by `option` and the files the run writes in it
    /// (relative names, possibly in subfolders): each is checked like [`Outputs::file`].
    pub fn dir(&mut self, option: &str, dir: &Path, names: &[String]) -> anyhow::Result<()> {
        if dir.exists() && !dir.is_dir() {
            bail!(
                "option `{option}`: {} exists and is not a directory; nothing was computed or written",
                dir.display()
            );
        }
        self.check_parent(option, dir)?;
        for name in names {
            self.file(option, &dir.join(name))?;
        }
        Ok(())
    }

    /// Refuse a path below an existing file that is not a directory.
    fn check_parent(&self, option: &str, path: &Path) -> anyhow::Result<()> {
        let mut p = path.parent();
        while let Some(dir) = p.filter(|d| !d.as_os_str().is_empty()) {
            if dir.exists() {
                if !dir.is_dir() {
                    bail!(
                        "option `{option}`: {} cannot be written: {} is not a directory; nothing was computed or written",
                        path.display(),
                        dir.display()
                    );
                }
                return Ok(());
            }
            p = dir.parent();
        }
        Ok(())
    }

    /// Keep `contents` to write at `path` when the run succeeds.
    pub fn stage(&mut self, path: PathBuf, contents: impl Into<Vec<u8>>) {
        self.staged.push((path, contents.into()));
    }

    /// Write every staged output: all to temporary files first, then each renamed to its name.
    /// When any cannot be written, the temporary files and the directories this call created
    /// are removed and no output is touched.
    pub fn commit(self) -> anyhow::Result<()> {
        let mut created: Vec<PathBuf> = Vec::new();
        let mut temps: Vec<(PathBuf, &Path)> = Vec::new();
        let result = (|| -> anyhow::Result<()> {
            for (path, contents) in &self.staged {
                create_dirs(path, &mut created)?;
                let tmp =
                    write_temp(path, contents).map_err(|e| anyhow::anyhow!("cannot write {}: {e}", path.display()))?;
                temps.push((tmp, path));
            }
            Ok(())
        })();
        if let Err(e) = result {
            for (tmp, _) in &temps {
                let _ = std::fs::remove_file(tmp);
            }
            for dir in created.iter().rev() {
                let _ = std::fs::remove_dir(dir);
            }
            return Err(e.context("no output was written"));
        }
        for (tmp, path) in &temps {
            std::fs::rename(tmp, path).map_err(|e| anyhow::anyhow!("cannot write {}: {e}", path.display()))?;
        }
        Ok(())
    }
}

/// Create the missing directories above `path`, recording each created (top first).
fn create_dirs(path: &Path, created: &mut Vec<PathBuf>) -> anyhow::Result<()> {
    let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty()) else {
        return Ok(());
    };
    let mut missing = Vec::new();
    let mut p = Some(dir);
    while let Some(d) = p.filter(|d| !d.as_os_str().is_empty() && !d.exists()) {
        missing.push(d.to_path_buf());
        p = d.parent();
    }
    for d in missing.into_iter().rev() {
        std::fs::create_dir(&d).map_err(|e| anyhow::anyhow!("cannot create directory {}: {e}", d.display()))?;
        created.push(d);
    }
    Ok(())
}

/// File names as owned strings, for [`Outputs::dir`].
pub fn names(list: &[&str]) -> Vec<String> {
    list.iter().map(|s| s.to_string()).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_input_reached_through_a_relative_path_or_a_link_is_refused() {
        let dir = tempfile::tempdir().unwrap();
        let input = dir.path().join("survey.csv");
        std::fs::write(&input, "md,inc,azi\n").unwrap();
        let sub = dir.path().join("sub");
        std::fs::create_dir(&sub).unwrap();
        let mut o = Outputs::new();
        o.input(&input);
        let dotted = sub.join("..").join("survey.csv");
        assert!(o.file("--out", &dotted).is_err());
        #[cfg(unix)]
        {
            let link = dir.path().join("link.csv");
            std::os::unix::fs::symlink(&input, &link).unwrap();
            assert!(o.file("--out", &link).is_err());
            let dir_link = dir.path().join("dirlink");
            std::os::unix::fs::symlink(dir.path(), &dir_link).unwrap();
            assert!(o.dir("--out", &dir_link, &["survey.csv".into()]).is_err());
        }
        assert!(o.file("--out", &sub.join("positions.csv")).is_ok());
        assert!(o.file("--report", &sub.join("positions.csv")).is_err(), "claimed twice");
    }

    #[test]
    fn a_failed_commit_leaves_nothing() {
        let dir = tempfile::tempdir().unwrap();
        let blocker = dir.path().join("file");
        std::fs::write(&blocker, "x").unwrap();
        let mut o = Outputs::new();
        o.stage(dir.path().join("new/a.csv"), "a");
        o.stage(blocker.join("b.csv"), "b");
        assert!(o.commit().is_err());
        let left: Vec<_> = std::fs::read_dir(dir.path())
            .unwrap()
            .map(|e| e.unwrap().file_name())
            .collect();
        assert_eq!(left, vec![std::ffi::OsString::from("file")]);
    }
}
