//! Progress bar on stderr for the long runs (`predict`, `backanalyze`, `loads --stiff`, `solve`
//! with several stages), drawn with indicatif. Shown only when stderr is a terminal and `-q` is
//! not given; silent otherwise, so pipes, files and tests see nothing of it.

use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use std::io::IsTerminal;

/// Whether a progress bar is drawn: stderr is a terminal and the run is not quiet (`-q`).
pub fn enabled(stderr_is_terminal: bool, quiet: bool) -> bool {
    stderr_is_terminal && !quiet
}

/// A progress bar over a number of steps, or nothing when progress is not shown. Cleared from
/// the terminal when finished or dropped (also on an error).
pub struct Progress {
    bar: Option<ProgressBar>,
}

impl Progress {
    /// A bar of `len` steps labelled `prefix` (e.g. the command and case), drawn only when
    /// [`enabled`] for this process's stderr and `quiet`.
    pub fn new(len: u64, prefix: &str, quiet: bool) -> Progress {
        if !enabled(std::io::stderr().is_terminal(), quiet) {
            return Progress { bar: None };
        }
        let bar = ProgressBar::with_draw_target(Some(len), ProgressDrawTarget::stderr());
        let style = ProgressStyle::with_template("{prefix} [{bar:30}] {pos}/{len} {elapsed} {msg}")
            .unwrap_or_else(|_| ProgressStyle::default_bar())
            .progress_chars("=> ");
        bar.set_style(style);
        bar.set_prefix(prefix.to_string());
        bar.tick();
        Progress { bar: Some(bar) }
    }

    /// A spinner labelled `prefix` for a run whose number of steps is not known ahead (its
    /// messages tell what it does), drawn only when [`enabled`].
    pub fn spinner(prefix: &str, quiet: bool) -> Progress {
        if !enabled(std::io::stderr().is_terminal(), quiet) {
            return Progress { bar: None };
        }
        let bar = ProgressBar::with_draw_target(None, ProgressDrawTarget::stderr());
        let style = ProgressStyle::with_template("{spinner} {prefix} {elapsed} {msg}")
            .unwrap_or_else(|_| ProgressStyle::default_spinner());
        bar.set_style(style);
        bar.set_prefix(prefix.to_string());
        bar.enable_steady_tick(std::time::Duration::from_millis(120));
        Progress { bar: Some(bar) }
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
        Progress { bar: None }
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
            b.finish_and_clear();
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Reference: the rule of the README (a bar only on a terminal, never with -q).
    #[test]
    fn shown_only_on_a_terminal_and_not_quiet() {
        assert!(enabled(true, false));
        assert!(!enabled(true, true));
        assert!(!enabled(false, false));
        assert!(!enabled(false, true));
        assert!(!Progress::hidden().is_shown());
    }
}
