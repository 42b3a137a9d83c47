//! Progress bar on stderr for the long runs (`predict`, `backanalyze`, `loads --stiff`, `solve`
//! with several stages), drawn with indicatif. Shown only when stderr is a terminal and `-q` is
//! not given; silent otherwise, so pipes, files and tests see nothing of it. Log lines (`-v`)
//! go through [`LogWriter`], which hides the bar while a line is written so the two do not tear.

use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use std::io::{IsTerminal, Write};
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::Mutex;

/// The bar on the terminal now (with the id of its [`Progress`]), for [`LogWriter`].
static ACTIVE: Mutex<Option<(u64, ProgressBar)>> = Mutex::new(None);
/// Ids of the drawn bars.
static NEXT_ID: AtomicU64 = AtomicU64::new(0);

/// stderr for log lines: a line is written with the active progress bar hidden and redrawn
/// after it. Give `|| LogWriter` to the tracing subscriber as its writer.
pub struct LogWriter;

impl Write for LogWriter {
    fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
        self.write_all(buf).map(|()| buf.len())
    }

    fn write_all(&mut self, buf: &[u8]) -> std::io::Result<()> {
        let bar = ACTIVE.lock().ok().and_then(|a| a.as_ref().map(|(_, b)| b.clone()));
        match bar {
            Some(b) => b.suspend(|| std::io::stderr().write_all(buf)),
            None => std::io::stderr().write_all(buf),
        }
    }

    fn flush(&mut self) -> std::io::Result<()> {
        std::io::stderr().flush()
    }
}

/// Whether a progress bar is drawn: stderr is a terminal and the run is not quiet (`-q`).
pub fn enabled(stderr_is_terminal: bool, quiet: bool) -> bool {
    stderr_is_terminal && !quiet
}

/// A progress bar over a number of steps, or nothing when progress is not shown. Cleared from
/// the terminal when finished or dropped (also on an error).
pub struct Progress {
    bar: Option<ProgressBar>,
    /// Id in [`ACTIVE`] while drawn.
    id: u64,
}

impl Progress {
    /// A bar of `len` steps labelled `prefix` (e.g. the command and case), drawn only when
    /// [`enabled`] for this process's stderr and `quiet`.
    pub fn new(len: u64, prefix: &str, quiet: bool) -> Progress {
        if !enabled(std::io::stderr().is_terminal(), quiet) {
            return Progress::hidden();
        }
        let bar = ProgressBar::with_draw_target(Some(len), ProgressDrawTarget::stderr());
        let style = ProgressStyle::with_template("{prefix} [{bar:30}] {pos}/{len} {elapsed} {msg}")
            .unwrap_or_else(|_| ProgressStyle::default_bar())
            .progress_chars("=> ");
        bar.set_style(style);
        bar.set_prefix(prefix.to_string());
        bar.tick();
        Progress::activate(bar)
    }

    /// A spinner labelled `prefix` for a run whose number of steps is not known ahead (its
    /// messages tell what it does), drawn only when [`enabled`].
    pub fn spinner(prefix: &str, quiet: bool) -> Progress {
        if !enabled(std::io::stderr().is_terminal(), quiet) {
            return Progress::hidden();
        }
        let bar = ProgressBar::with_draw_target(None, ProgressDrawTarget::stderr());
        let style = ProgressStyle::with_template("{spinner} {prefix} {elapsed} {msg}")
            .unwrap_or_else(|_| ProgressStyle::default_spinner());
        bar.set_style(style);
        bar.set_prefix(prefix.to_string());
        bar.enable_steady_tick(std::time::Duration::from_millis(120));
        Progress::activate(bar)
    }

    /// Run `f` with the bar hidden (e.g. to write a log line without tearing the bar).
    pub fn suspend<R>(&self, f: impl FnOnce() -> R) -> R {
        match &self.bar {
            Some(b) => b.suspend(f),
            None => f(),
        }
    }

    /// A progress that shows nothing.
    pub fn hidden() -> Progress {
        Progress { bar: None, id: 0 }
    }

    /// `bar` as the drawn progress, registered for [`LogWriter`].
    fn activate(bar: ProgressBar) -> Progress {
        let id = NEXT_ID.fetch_add(1, Ordering::Relaxed) + 1;
        if let Ok(mut a) = ACTIVE.lock() {
            *a = Some((id, bar.clone()));
        }
        Progress { bar: Some(bar), id }
    }

    /// Whether anything is drawn.
    pub fn is_shown(&self) -> bool {
        self.bar.is_some()
    }

    /// Move to step `pos` (of the length) with message `msg`.
    pub fn set(&self, pos: u64, msg: &str) {
        if let Some(b) = &self.bar {
            b.set_position(pos);
            b.set_message(msg.to_string());
        }
    }

    /// Change the number of steps (when it becomes known).
    pub fn set_length(&self, len: u64) {
        if let Some(b) = &self.bar {
            b.set_length(len);
        }
    }

    /// Change the message only.
    pub fn message(&self, msg: &str) {
        if let Some(b) = &self.bar {
            b.set_message(msg.to_string());
        }
    }

    /// Remove the bar from the terminal.
    pub fn finish(self) {
        drop(self);
    }
}

impl Drop for Progress {
    fn drop(&mut self) {
        if let Some(b) = self.bar.take() {
            if let Ok(mut a) = ACTIVE.lock() {
                if a.as_ref().is_some_and(|(id, _)| *id == self.id) {
                    *a = None;
                }
            }
            b.finish_and_clear();
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Reference: the rule of docs/guide.md, "Running drillpath" (a bar only on a terminal, never with -q).
    #[test]
    fn shown_only_on_a_terminal_and_not_quiet() {
        assert!(enabled(true, false));
        assert!(!enabled(true, true));
        assert!(!enabled(false, false));
        assert!(!enabled(false, true));
        assert!(!Progress::hidden().is_shown());
    }
}
