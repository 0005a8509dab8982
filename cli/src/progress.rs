//! The progress display of a long compile or run: nothing for the first
//! second, then a bar (or a spinner, when the amount of work is not known)
//! on standard error. Off when standard error is not a terminal (a script,
//! a pipe, a CI log) or with `--quiet`, so it never ends up in a log.

use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use std::io::IsTerminal;
use std::sync::mpsc::{self, RecvTimeoutError, Sender};
use std::thread::JoinHandle;
use std::time::{Duration, Instant};

/// How long work runs before any progress shows.
const DELAY: Duration = Duration::from_secs(1);
/// `Progress::set` reads the clock on one call in this many: it is called
/// once per interpolation period.
const CLOCK_EVERY: u32 = 1024;

/// Whether progress may be drawn at all.
pub fn wanted(quiet: bool, stderr_is_terminal: bool) -> bool {
    !quiet && stderr_is_terminal
}

fn wanted_here(quiet: bool) -> bool {
    wanted(quiet, std::io::stderr().is_terminal())
}

/// A bar over a known amount of work (e.g. the lines of a program).
pub struct Progress {
    bar: ProgressBar,
    enabled: bool,
    start: Instant,
    calls: u32,
}

impl Progress {
    /// A bar of `len` steps labelled `what`.
    pub fn bar(len: u64, what: &str, quiet: bool) -> Progress {
        let bar = ProgressBar::with_draw_target(Some(len.max(1)), ProgressDrawTarget::hidden());
        let style = ProgressStyle::with_template("{prefix} [{bar:30}] {msg} ({elapsed})")
            .unwrap_or_else(|_| ProgressStyle::default_bar())
            .progress_chars("=> ");
        bar.set_style(style);
        bar.set_prefix(what.to_string());
        Progress {
            bar,
            enabled: wanted_here(quiet),
            start: Instant::now(),
            calls: 0,
        }
    }

    /// Moves the bar to `pos`; `msg` is asked for only when the bar is
    /// drawn. Cheap enough to call every period.
    pub fn set(&mut self, pos: u64, msg: impl FnOnce() -> String) {
        self.set_from(|| (pos, msg()));
    }

    /// [`Progress::set`] with the position asked for too only when the
    /// bar is drawn (`gbvm run` looks the source line up for it).
    pub fn set_from(&mut self, at: impl FnOnce() -> (u64, String)) {
        if !self.enabled {
            return;
        }
        self.calls = self.calls.wrapping_add(1);
        if !self.calls.is_multiple_of(CLOCK_EVERY) {
            return;
        }
        if self.bar.is_hidden() {
            if self.start.elapsed() < DELAY {
                return;
            }
            self.bar.set_draw_target(ProgressDrawTarget::stderr());
        }
        let (pos, msg) = at();
        self.bar.set_position(pos);
        self.bar.set_message(msg);
    }

    /// Takes the bar off the screen (before the tool prints its results).
    pub fn finish(&self) {
        self.bar.finish_and_clear();
    }
}

/// A spinner for work whose amount is not known (a compile): a thread
/// waits a second, then spins until the spinner is dropped.
pub struct Spinner {
    done: Option<Sender<()>>,
    thread: Option<JoinHandle<()>>,
}

impl Spinner {
    pub fn start(msg: String, quiet: bool) -> Spinner {
        if !wanted_here(quiet) {
            return Spinner {
                done: None,
                thread: None,
            };
        }
        let (tx, rx) = mpsc::channel::<()>();
        let thread = std::thread::spawn(move || {
            if rx.recv_timeout(DELAY) != Err(RecvTimeoutError::Timeout) {
                return;
            }
            let spin = ProgressBar::new_spinner();
            spin.set_message(msg);
            while rx.recv_timeout(Duration::from_millis(100)) == Err(RecvTimeoutError::Timeout) {
                spin.tick();
            }
            spin.finish_and_clear();
        });
        Spinner {
            done: Some(tx),
            thread: Some(thread),
        }
    }
}

impl Drop for Spinner {
    fn drop(&mut self) {
        // Dropping the sender wakes the thread; joining it makes sure the
        // spinner is off the screen before anything else is printed.
        self.done.take();
        if let Some(t) = self.thread.take() {
            let _ = t.join();
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn progress_shows_only_on_a_terminal_and_not_when_quiet() {
        assert!(wanted(false, true));
        assert!(!wanted(true, true));
        assert!(!wanted(false, false));
        assert!(!wanted(true, false));
    }

    #[test]
    fn a_short_piece_of_work_draws_nothing() {
        // Under the test harness stderr may or may not be a terminal; a
        // bar used for less than a second stays hidden either way.
        let mut p = Progress::bar(100, "run", false);
        for i in 0..5000 {
            p.set(i % 100, || String::from("x"));
        }
        assert!(p.bar.is_hidden() || p.start.elapsed() >= DELAY);
        p.finish();
        drop(Spinner::start("compiling".into(), false));
    }
}
