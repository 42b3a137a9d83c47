//! The one way the tests run the `drillpath` binary, and the checks of a user error.

use std::path::{Path, PathBuf};
use std::process::{Command, ExitStatus};

/// The package root (`CARGO_MANIFEST_DIR`): the directory `wells/...` and `docs/...` are
/// relative to, and the working directory cargo gives the tests.
pub fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// The built `drillpath` binary as a command with a clean logging environment: no
/// `DRILLPATH_LOG` or `RUST_LOG` from the caller's shell (log lines would add to stderr), and
/// `RUST_BACKTRACE=1` so that a panic prints a backtrace the error checks see. For the few
/// tests that need the child's pipes; the others use [`run_in`].
pub fn drillpath() -> Command {
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_drillpath"));
    cmd.env_remove("DRILLPATH_LOG")
        .env_remove("RUST_LOG")
        .env("RUST_BACKTRACE", "1");
    cmd
}

/// What one run of the binary gave: its exit status and what it wrote (UTF-8, as drillpath
/// always writes).
pub struct Run {
    pub status: ExitStatus,
    pub stdout: String,
    pub stderr: String,
}

impl Run {
    /// The exit code (`None` if a signal ended the process).
    pub fn code(&self) -> Option<i32> {
        self.status.code()
    }

    /// Exit status 0.
    pub fn success(&self) -> bool {
        self.status.success()
    }

    /// Exit code and both streams, for assertion messages.
    pub fn describe(&self) -> String {
        format!(
            "exit code {:?}\n--- stdout ---\n{}\n--- stderr ---\n{}",
            self.code(),
            self.stdout,
            self.stderr
        )
    }
}

/// Run `drillpath args` in `dir` (see [`drillpath`] for the environment) and wait for it.
pub fn run_in(dir: impl AsRef<Path>, args: &[&str]) -> Run {
    let out = drillpath()
        .args(args)
        .current_dir(dir)
        .output()
        .expect("cannot start the drillpath binary");
    Run {
        status: out.status,
        stdout: String::from_utf8(out.stdout).expect("drillpath wrote UTF-8 on stdout"),
        stderr: String::from_utf8(out.stderr).expect("drillpath wrote UTF-8 on stderr"),
    }
}

/// [`run_in`] that must succeed: fails the test with the arguments and stderr otherwise.
pub fn run_ok(dir: impl AsRef<Path>, args: &[&str]) -> Run {
    let r = run_in(dir, args);
    assert!(r.success(), "drillpath {args:?} failed: {}", r.stderr);
    r
}

/// A user error as the command line reports one: a normal exit (not a signal) with a non-zero
/// code, exactly one line on stderr, starting `error: ` and naming every item of `must_name`
/// (the file, the line, the dotted case-file key, the option, what is wrong), and no panic or
/// backtrace. Returns that line.
pub fn assert_error_names<'a>(r: &'a Run, must_name: &[&str]) -> &'a str {
    let ctx = r.describe();
    assert!(r.code().is_some(), "killed by a signal\n{ctx}");
    assert_ne!(r.code(), Some(0), "bad input accepted\n{ctx}");
    for bad in ["panicked", "RUST_BACKTRACE", "stack backtrace"] {
        assert!(!r.stderr.contains(bad), "`{bad}` on stderr\n{ctx}");
    }
    let lines: Vec<&str> = r.stderr.lines().collect();
    assert_eq!(lines.len(), 1, "expected exactly one line on stderr\n{ctx}");
    assert!(
        lines[0].starts_with("error: "),
        "stderr must start with `error: `\n{ctx}"
    );
    for s in must_name {
        assert!(lines[0].contains(s), "the message does not name `{s}`\n{ctx}");
    }
    lines[0]
}
