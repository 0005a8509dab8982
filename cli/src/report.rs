//! How `gbcc` reports diagnostics: gcc-style text (coloured or not), one
//! JSON object per diagnostic in rustc's shape, or one SARIF 2.1.0 log;
//! with the warning policy, the `-fmax-errors` cap and the summary line.

use crate::warnings::{Policy, Verdict};
use grammar::{Diagnostic, Severity, SourceFile};
use std::io::Write;

pub mod json;
pub mod sarif;

/// `-fdiagnostics-format=`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Format {
    Text,
    Json,
    Sarif,
}

/// The default of `-fmax-errors`: a screenful. A binary file given by
/// mistake makes thousands of errors, and the first ones say it all.
pub const DEFAULT_MAX_ERRORS: usize = 20;

/// A diagnostic as reported: the policy may have made a warning an error.
pub struct Reported<'a> {
    pub file: &'a SourceFile,
    pub diag: &'a Diagnostic,
    pub severity: Severity,
    /// `-Werror` turned this warning into an error.
    pub promoted: bool,
}

impl Reported<'_> {
    /// The message, with the switch that made a warning an error (gcc's
    /// `[-Werror=…]`).
    pub fn message(&self) -> String {
        if self.promoted {
            format!("{} [-Werror={}]", self.diag.message, self.diag.code)
        } else {
            self.diag.message.clone()
        }
    }

    /// The diagnostic as the text form prints it.
    pub fn rendered(&self, color: bool) -> String {
        if self.promoted {
            let d = Diagnostic {
                severity: self.severity,
                message: self.message(),
                ..self.diag.clone()
            };
            self.file.render_styled(&d, color)
        } else {
            self.file.render_styled(self.diag, color)
        }
    }
}

/// Writes the diagnostics of a whole `gbcc` run to standard error.
pub struct Reporter<W: Write> {
    out: W,
    pub format: Format,
    pub color: bool,
    pub policy: Policy,
    /// Errors shown before the rest are only counted; 0: no limit.
    pub max_errors: usize,
    pub errors: usize,
    pub warnings: usize,
    /// Diagnostics past the cap: counted, not shown.
    hidden: usize,
    /// The cap is reached.
    stopped: bool,
    /// A warning was made an error.
    pub promoted: usize,
    sarif: sarif::Log,
    /// Standard error could not be written.
    pub broken: bool,
}

impl<W: Write> Reporter<W> {
    pub fn new(out: W, format: Format, color: bool, policy: Policy) -> Reporter<W> {
        Reporter {
            out,
            format,
            color,
            policy,
            max_errors: DEFAULT_MAX_ERRORS,
            errors: 0,
            warnings: 0,
            hidden: 0,
            stopped: false,
            promoted: 0,
            sarif: sarif::Log::default(),
            broken: false,
        }
    }

    /// Reports one diagnostic; true when it counts as an error.
    pub fn report(&mut self, file: &SourceFile, d: &Diagnostic) -> bool {
        let severity = match self.policy.judge(d) {
            Verdict::Silent => return false,
            Verdict::Warn => Severity::Warning,
            Verdict::Error => Severity::Error,
        };
        let promoted = severity == Severity::Error && d.severity == Severity::Warning;
        match severity {
            Severity::Error => self.errors += 1,
            Severity::Warning => self.warnings += 1,
        }
        self.promoted += usize::from(promoted);
        if self.stopped {
            self.hidden += 1;
            return severity == Severity::Error;
        }
        // Once the cap's errors are shown, the rest is only counted.
        self.stopped =
            severity == Severity::Error && self.max_errors != 0 && self.errors >= self.max_errors;
        let r = Reported {
            file,
            diag: d,
            severity,
            promoted,
        };
        match self.format {
            Format::Text => {
                let text = r.rendered(self.color);
                self.write(&text);
            }
            Format::Json => {
                let line = json::diagnostic(&r);
                self.write(&line);
            }
            Format::Sarif => self.sarif.add(&r),
        }
        severity == Severity::Error
    }

    /// A line of the driver's own (`gbcc: error: …`) in the text form; in
    /// JSON a diagnostic without spans; in SARIF a tool notification.
    pub fn driver_error(&mut self, msg: &str) {
        self.errors += 1;
        match self.format {
            Format::Text => self.write(&format!("gbcc: error: {msg}")),
            Format::Json => self.write(&json::driver_error(msg)),
            Format::Sarif => self.sarif.notify(msg),
        }
    }

    /// A run-time alarm of `-E` (its header names the block), as is.
    pub fn alarm(&mut self, header: &str) {
        self.errors += 1;
        match self.format {
            Format::Text => self.write(header),
            Format::Json => self.write(&json::driver_error(header)),
            Format::Sarif => self.sarif.notify(header),
        }
    }

    fn write(&mut self, text: &str) {
        if !self.broken && writeln!(self.out, "{text}").is_err() {
            self.broken = true;
        }
    }

    /// Ends the run: the SARIF log, or the count of hidden diagnostics
    /// and the summary line (`2 errors, 1 warning`) of the text form.
    /// False when standard error could not be written.
    pub fn finish(mut self) -> bool {
        match self.format {
            Format::Sarif => {
                let log = self.sarif.to_json();
                self.write(&log);
            }
            Format::Json => {}
            Format::Text => {
                if self.hidden > 0 {
                    let note = format!(
                        "gbcc: note: {} more {} not shown (-fmax-errors={}; 0 shows all)",
                        self.hidden,
                        plural(self.hidden, "diagnostic"),
                        self.max_errors
                    );
                    self.write(&note);
                }
                if self.errors + self.warnings > 0 {
                    let mut line = format!(
                        "gbcc: {} {}, {} {}",
                        self.errors,
                        plural(self.errors, "error"),
                        self.warnings,
                        plural(self.warnings, "warning")
                    );
                    if self.promoted > 0 {
                        line.push_str(&format!(
                            " ({} {} treated as {} by -Werror)",
                            self.promoted,
                            plural(self.promoted, "warning"),
                            plural(self.promoted, "error")
                        ));
                    }
                    self.write(&line);
                }
            }
        }
        if self.out.flush().is_err() {
            self.broken = true;
        }
        !self.broken
    }
}

fn plural(n: usize, word: &str) -> String {
    if n == 1 {
        word.to_string()
    } else {
        format!("{word}s")
    }
}
