//! gcc's warning switches for the dialect's warnings (dialect.md §8.5):
//! `-Wall`, `-Wextra`, `-WW113`, `-Wno-W113`, `-Werror`, `-Werror=W101`,
//! `-Wno-error=W101`, and `-w`. docs/diagnostics.md says what each means.

use grammar::{Diagnostic, Severity};

/// The warnings of the language reference, W101…W117, and gbc's own
/// W118 (a thread without the room to reach or leave its speed), W119
/// (an arc of a program with macros that cannot be drawn), W120 (the
/// dry run stopped, its budget of repeated blocks spent), W121 (calls
/// that always nest too deep), W122 (a run longer than the block
/// budget), W123 (an `M99 P n` whose caller has no block Nn), W124
/// (the alarm a run stops with, known at compile time), W125 (a feed
/// per minute below 1: a feed per revolution in G98), W126 (a thread
/// too fast for an axis's maximum cutting feed) and W127 (a loop that
/// never ends once it goes round).
pub const FIRST: u16 = 101;
pub const LAST: u16 = 127;

/// What becomes of a warning.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Verdict {
    /// Not reported.
    Silent,
    /// Reported as a warning.
    Warn,
    /// Reported as an error that fails the build (`-Werror`).
    Error,
}

/// The warning switches of one command line, applied in order.
#[derive(Debug, Clone)]
pub struct Policy {
    /// Index `code - FIRST`: the warning is reported.
    enabled: [bool; (LAST - FIRST + 1) as usize],
    /// `-Werror=CODE` / `-Wno-error=CODE`: an explicit choice per code.
    error: [Option<bool>; (LAST - FIRST + 1) as usize],
    /// `-Werror`.
    error_all: bool,
    /// `-w`: nothing is reported, whatever else was asked.
    silent: bool,
}

impl Default for Policy {
    /// Every warning on, none an error (what `-Wall` asks for too).
    fn default() -> Policy {
        Policy {
            enabled: [true; (LAST - FIRST + 1) as usize],
            error: [None; (LAST - FIRST + 1) as usize],
            error_all: false,
            silent: false,
        }
    }
}

/// The index of a warning code such as `W113` (any case).
fn index(code: &str) -> Option<usize> {
    let n: u16 = code.strip_prefix(['W', 'w'])?.parse().ok()?;
    (FIRST..=LAST).contains(&n).then(|| usize::from(n - FIRST))
}

impl Policy {
    /// `-w`.
    pub fn silence(&mut self) {
        self.silent = true;
    }

    /// One `-W…` switch, without its `-W`; unknown ones are refused with a
    /// message that says what exists.
    pub fn apply(&mut self, switch: &str) -> Result<(), String> {
        let unknown = || {
            format!(
                "unknown warning option '-W{switch}' (known: -Wall, -Wextra, -Werror, \
                 -Werror=CODE, -Wno-error=CODE, -WCODE, -Wno-CODE with CODE W{FIRST}…W{LAST}; \
                 gbcc --explain CODE)"
            )
        };
        match switch {
            // Every warning exists to point at a probable mistake, so both
            // mean "all of them" (docs/diagnostics.md).
            "all" | "extra" => self.enabled = [true; (LAST - FIRST + 1) as usize],
            "error" => self.error_all = true,
            "no-error" => self.error_all = false,
            _ => {
                if let Some(code) = switch.strip_prefix("error=") {
                    let i = index(code).ok_or_else(unknown)?;
                    self.error[i] = Some(true);
                    self.enabled[i] = true;
                } else if let Some(code) = switch.strip_prefix("no-error=") {
                    self.error[index(code).ok_or_else(unknown)?] = Some(false);
                } else if let Some(code) = switch.strip_prefix("no-") {
                    self.enabled[index(code).ok_or_else(unknown)?] = false;
                } else {
                    self.enabled[index(switch).ok_or_else(unknown)?] = true;
                }
            }
        }
        Ok(())
    }

    /// Whether warning `code` is reported at all (not `-Wno-CODE`, not
    /// `-w`): a check whose only finding is that warning need not run.
    pub fn reports(&self, code: &str) -> bool {
        !self.silent && index(code).is_none_or(|i| self.enabled[i])
    }

    /// What becomes of `d`: errors stay errors; a warning is judged by its
    /// code (an unknown warning code follows `-w` and `-Werror` only).
    pub fn judge(&self, d: &Diagnostic) -> Verdict {
        if d.severity == Severity::Error {
            return Verdict::Error;
        }
        let i = index(d.code);
        if self.silent || i.is_some_and(|i| !self.enabled[i]) {
            return Verdict::Silent;
        }
        let error = i.and_then(|i| self.error[i]).unwrap_or(self.error_all);
        if error {
            Verdict::Error
        } else {
            Verdict::Warn
        }
    }
}

#[cfg(test)]
mod tests {
    use super::{Policy, Verdict};
    use grammar::{Diagnostic, Span};

    fn w(code: &'static str) -> Diagnostic {
        Diagnostic::warning(code, Span::default(), "x")
    }

    #[test]
    fn a_warning_turned_off_is_not_reported() {
        let mut p = Policy::default();
        assert!(p.reports("W124"));
        p.apply("no-W124").unwrap();
        assert!(!p.reports("W124"));
        assert!(p.reports("W113"));
        p.apply("W124").unwrap();
        assert!(p.reports("W124"));
        p.silence();
        assert!(!p.reports("W113"));
    }

    #[test]
    fn switches_apply_in_order() {
        let mut p = Policy::default();
        assert_eq!(p.judge(&w("W113")), Verdict::Warn);
        p.apply("no-W113").unwrap();
        assert_eq!(p.judge(&w("W113")), Verdict::Silent);
        p.apply("all").unwrap();
        assert_eq!(p.judge(&w("W113")), Verdict::Warn);
        p.apply("error=W101").unwrap();
        assert_eq!(p.judge(&w("W101")), Verdict::Error);
        assert_eq!(p.judge(&w("W104")), Verdict::Warn);
        p.apply("error").unwrap();
        p.apply("no-error=W104").unwrap();
        assert_eq!(p.judge(&w("W104")), Verdict::Warn);
        assert_eq!(p.judge(&w("W117")), Verdict::Error);
        p.silence();
        assert_eq!(p.judge(&w("W101")), Verdict::Silent);
        let e = Diagnostic::error("E1001", Span::default(), "x");
        assert_eq!(p.judge(&e), Verdict::Error);
    }

    #[test]
    fn unknown_switches_are_refused() {
        let mut p = Policy::default();
        for bad in ["foo", "no-W100", "W128", "error=E1001", "no-error=", "W"] {
            let e = p.apply(bad).unwrap_err();
            assert!(e.contains(&format!("'-W{bad}'")), "{e}");
        }
    }
}
