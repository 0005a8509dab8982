//! Diagnostics: one type for every phase (lexer, parser, compiler, VM
//! alarms), rendered gcc-style with a codespan-reporting snippet below.

use crate::span::Span;
use codespan_reporting::diagnostic as cs;
use codespan_reporting::files::{self, Files};
use codespan_reporting::term;
use std::ops::Range;
use std::sync::{Arc, OnceLock};

mod clip;

pub use clip::{quote, LineWindow, CLIPPED, LONG_LINE, QUOTED};

#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Severity {
    Warning,
    Error,
}

/// A finding about the program at a place in its source.
#[derive(Debug, Clone, PartialEq)]
pub struct Diagnostic {
    pub severity: Severity,
    /// The dialect's code: `E1001`, `W102` (dialect.md §8).
    pub code: &'static str,
    pub message: String,
    /// The exact place; the header's line and column come from its start.
    pub span: Span,
    /// The label under the snippet (defaults to nothing).
    pub label: String,
    /// Extra lines such as "expected one of …".
    pub notes: Vec<String>,
    /// A likely fix.
    pub help: Option<String>,
    /// A second place the finding is about, and its label: the profile
    /// block a cycle block's error points to.
    pub related: Option<(Span, String)>,
}

impl Diagnostic {
    pub fn error(code: &'static str, span: Span, message: impl Into<String>) -> Diagnostic {
        Diagnostic {
            severity: Severity::Error,
            code,
            message: message.into(),
            span,
            label: String::new(),
            notes: Vec::new(),
            help: None,
            related: None,
        }
    }

    pub fn warning(code: &'static str, span: Span, message: impl Into<String>) -> Diagnostic {
        Diagnostic {
            severity: Severity::Warning,
            ..Diagnostic::error(code, span, message)
        }
    }

    pub fn with_label(mut self, label: impl Into<String>) -> Diagnostic {
        self.label = label.into();
        self
    }

    pub fn with_note(mut self, note: impl Into<String>) -> Diagnostic {
        self.notes.push(note.into());
        self
    }

    pub fn with_related(mut self, span: Span, label: impl Into<String>) -> Diagnostic {
        self.related = Some((span, label.into()));
        self
    }

    pub fn with_help(mut self, help: impl Into<String>) -> Diagnostic {
        self.help = Some(help.into());
        self
    }

    pub fn is_error(&self) -> bool {
        self.severity == Severity::Error
    }
}

/// The line of the last [`SourceFile::line_col_near`] answer: its index and
/// its byte range (the last line runs on). The default matches no offset.
#[derive(Debug, Clone, Copy, Default)]
pub struct LineHint {
    line: usize,
    start: usize,
    end: usize,
}

/// A source file as the renderer needs it: its name, and its bytes made
/// printable one byte for one character, so byte offsets stay valid.
pub struct SourceFile {
    pub name: String,
    /// Shared with whoever else holds the source (the compiler's unit):
    /// a large program is not copied again.
    bytes: Arc<[u8]>,
    /// The printable text, made when first rendered: most compilations
    /// render nothing, and only need line numbers.
    text: OnceLock<String>,
    /// (`u32`: spans are; half the table of a long program.)
    line_starts: Vec<u32>,
}

impl SourceFile {
    pub fn new(name: impl Into<String>, bytes: impl Into<Arc<[u8]>>) -> SourceFile {
        let bytes = bytes.into();
        SourceFile {
            name: name.into(),
            line_starts: line_starts(&bytes),
            bytes,
            text: OnceLock::new(),
        }
    }

    /// 1-based line and column (in bytes) of a byte offset.
    pub fn line_col(&self, offset: u32) -> (usize, usize) {
        let line = match self.line_starts.binary_search(&offset) {
            Ok(i) => i,
            Err(i) => i - 1,
        };
        (line + 1, (offset - self.line_starts[line]) as usize + 1)
    }

    /// [`SourceFile::line_col`] for offsets asked for in source order:
    /// `hint` holds the line of the previous answer, and the offset is
    /// nearly always on that line (one comparison) or the next, which needs
    /// no search. (Inline: the compiler asks for every word.) A hint
    /// belongs to one file.
    #[inline]
    pub fn line_col_near(&self, offset: u32, hint: &mut LineHint) -> (usize, usize) {
        let at = offset as usize;
        if hint.start <= at && at < hint.end {
            return (hint.line + 1, at - hint.start + 1);
        }
        let line = [hint.line, hint.line + 1]
            .into_iter()
            .find(|&i| self.on_line(at, i))
            .unwrap_or_else(|| match self.line_starts.binary_search(&offset) {
                Ok(i) => i,
                Err(i) => i - 1,
            });
        let start = self.line_starts[line] as usize;
        *hint = LineHint {
            line,
            start,
            end: (self.line_starts.get(line + 1)).map_or(usize::MAX, |&e| e as usize),
        };
        (line + 1, at - start + 1)
    }

    /// Whether byte `at` lies on line index `i` (the last line runs on).
    #[inline]
    fn on_line(&self, at: usize, i: usize) -> bool {
        let starts = &self.line_starts;
        starts.get(i).is_some_and(|&s| s as usize <= at)
            && starts.get(i + 1).is_none_or(|&e| at < e as usize)
    }

    pub fn text(&self) -> &str {
        self.text.get_or_init(|| printable(&self.bytes))
    }

    /// The one-line gcc-style header of a diagnostic.
    pub fn header(&self, d: &Diagnostic) -> String {
        let (line, col) = self.line_col(d.span.start);
        let kind = match d.severity {
            Severity::Error => "error",
            Severity::Warning => "warning",
        };
        format!(
            "{}:{}:{}: {}[{}]: {}",
            self.name, line, col, kind, d.code, d.message
        )
    }

    /// Header, then the snippet with the label, notes and help; no colour.
    pub fn render(&self, d: &Diagnostic) -> String {
        self.render_styled(d, false)
    }

    /// [`SourceFile::render`], with ANSI colours when `color` is set (the
    /// header as gcc colours it, the snippet as codespan does).
    pub fn render_styled(&self, d: &Diagnostic, color: bool) -> String {
        let mut out = if color {
            self.header_colored(d)
        } else {
            self.header(d)
        };
        out.push('\n');
        out.push_str(&self.snippet(d, color));
        out
    }

    fn header_colored(&self, d: &Diagnostic) -> String {
        let (line, col) = self.line_col(d.span.start);
        // Bold place, red error / magenta warning as gcc, bold message.
        let (kind, colour) = match d.severity {
            Severity::Error => ("error", "31"),
            Severity::Warning => ("warning", "35"),
        };
        format!(
            "\x1b[1m{}:{}:{}: \x1b[1;{colour}m{kind}[{}]:\x1b[0m \x1b[1m{}\x1b[0m",
            self.name, line, col, d.code, d.message
        )
    }

    /// The snippet under the header: the file's lines as they are, or,
    /// when one is long, a view of them clipped around the fault.
    fn snippet(&self, d: &Diagnostic, color: bool) -> String {
        let len = self.text().len();
        let range = |s: Span| {
            let start = (s.start as usize).min(len);
            start..(s.end as usize).clamp(start, len)
        };
        let mut spans = vec![range(d.span)];
        spans.extend(d.related.iter().map(|(span, _)| range(*span)));
        match clip::Clipped::new(self, &spans) {
            None => emit(self, &labelled(d, &spans), color),
            Some(view) => {
                let spans: Vec<Range<usize>> = spans
                    .iter()
                    .map(|r| view.offset(r.start)..view.offset(r.end))
                    .collect();
                emit(&view, &labelled(d, &spans), color)
            }
        }
    }

    /// The byte range of line index `i`, its line end included.
    pub fn line_range(&self, i: usize) -> Option<Range<usize>> {
        let start = *self.line_starts.get(i)? as usize;
        let end = (self.line_starts.get(i + 1)).map_or(self.bytes.len(), |&e| e as usize);
        Some(start..end)
    }

    /// The source's bytes as read.
    pub fn bytes(&self) -> &[u8] {
        &self.bytes
    }
}

/// The file is its own codespan database of one file.
impl<'a> Files<'a> for SourceFile {
    type FileId = ();
    type Name = &'a str;
    type Source = &'a str;

    fn name(&'a self, (): ()) -> Result<&'a str, files::Error> {
        Ok(&self.name)
    }

    fn source(&'a self, (): ()) -> Result<&'a str, files::Error> {
        Ok(self.text())
    }

    fn line_index(&'a self, (): (), byte_index: usize) -> Result<usize, files::Error> {
        Ok(self.line_col(byte_index as u32).0 - 1)
    }

    fn line_range(&'a self, (): (), line_index: usize) -> Result<Range<usize>, files::Error> {
        let max = self.line_starts.len() - 1;
        match SourceFile::line_range(self, line_index) {
            Some(r) => Ok(r),
            // codespan asks for the line after the last one.
            None if line_index == max + 1 => Ok(self.bytes.len()..self.bytes.len()),
            None => Err(files::Error::LineTooLarge {
                given: line_index,
                max,
            }),
        }
    }
}

/// The codespan diagnostic of `d`, its label on `spans[0]` and the related
/// one's on `spans[1]`, with the notes and the help.
fn labelled(d: &Diagnostic, spans: &[Range<usize>]) -> cs::Diagnostic<()> {
    let mut labels = Vec::new();
    if let Some(r) = spans.first() {
        labels.push(cs::Label::primary((), r.clone()).with_message(d.label.clone()));
    }
    if let (Some((_, label)), Some(r)) = (&d.related, spans.get(1)) {
        labels.push(cs::Label::secondary((), r.clone()).with_message(label.clone()));
    }
    let mut notes = d.notes.clone();
    if let Some(help) = &d.help {
        notes.push(format!("help: {help}"));
    }
    match d.severity {
        Severity::Error => cs::Diagnostic::error(),
        Severity::Warning => cs::Diagnostic::warning(),
    }
    .with_code(d.code)
    .with_message(d.message.clone())
    .with_labels(labels)
    .with_notes(notes)
}

/// Renders the snippet of `diag` from the file database `files`, without
/// codespan's own first line (the header replaces it). Rendering into
/// memory cannot fail for in-range spans; the header stands alone if it
/// ever does. (The database is the file itself, or its clipped view: its
/// line starts are made once, not per message, as a `SimpleFile` per
/// message made rendering quadratic, and they are the ones the header
/// counts with, lone CR included.)
fn emit<'f, F: Files<'f, FileId = ()>>(
    files: &'f F,
    diag: &cs::Diagnostic<()>,
    color: bool,
) -> String {
    let config = term::Config {
        display_style: term::DisplayStyle::Rich,
        ..term::Config::default()
    };
    let buffer = if color {
        let mut ansi = term::termcolor::Ansi::new(Vec::new());
        let _ = term::emit_to_write_style(&mut ansi, &config, files, diag);
        String::from_utf8_lossy(&ansi.into_inner()).into_owned()
    } else {
        let mut s = String::new();
        let _ = term::emit_to_string(&mut s, &config, files, diag);
        s
    };
    match buffer.split_once('\n') {
        Some((_, rest)) => rest.to_string(),
        None => String::new(),
    }
}

/// The bytes made printable one for one: every byte is ASCII afterwards,
/// so the text is valid UTF-8. A lone CR becomes LF, so the snippet breaks
/// its lines where the header counts them.
fn printable(bytes: &[u8]) -> String {
    let ascii: Vec<u8> = bytes
        .iter()
        .enumerate()
        .map(|(i, &b)| match b {
            b'\r' if bytes.get(i + 1) != Some(&b'\n') => b'\n',
            b'\n' | b'\r' | b'\t' | b' '..=b'~' => b,
            _ => b'?',
        })
        .collect();
    String::from_utf8(ascii).unwrap_or_else(|e| String::from_utf8_lossy(e.as_bytes()).into_owned())
}

/// The offset of every line start: 0, and after each LF, CR LF or lone CR
/// (a lone CR ends a line too, dialect.md §1.3).
fn line_starts(bytes: &[u8]) -> Vec<u32> {
    let mut starts = vec![0];
    for end in memchr::memchr2_iter(b'\n', b'\r', bytes) {
        // The CR of a CR LF is no line end of its own: its LF is.
        if bytes[end] == b'\n' || bytes.get(end + 1) != Some(&b'\n') {
            // (Past 4 GiB no span can point anyway.)
            starts.push(u32::try_from(end + 1).unwrap_or(u32::MAX));
        }
    }
    starts
}

#[cfg(test)]
mod tests {
    use super::SourceFile;

    /// The hinted lookup gives what the search gives, in order, backwards
    /// and jumping about, over every kind of line end.
    #[test]
    fn line_col_near_equals_line_col() {
        let src = b"G01 X1\r\nX2\rX3\n\nX4 (a)\r\r\nX5";
        let f = SourceFile::new("t.nc", &src[..]);
        let offsets: Vec<u32> = (0..=src.len() as u32 + 2)
            .chain((0..=src.len() as u32).rev())
            .chain([3, 20, 1, 27, 9, 0])
            .collect();
        let mut hint = super::LineHint::default();
        for at in offsets {
            assert_eq!(f.line_col_near(at, &mut hint), f.line_col(at), "at {at}");
        }
    }

    /// A file with lone-CR line ends: the snippet shows the line the
    /// header names (codespan alone counts LF only and showed line 1).
    #[test]
    fn lone_cr_lines_agree_in_header_and_snippet() {
        let src = b"G00 X1\rG01 X1.2.3\rM30\r";
        let f = SourceFile::new("cr.nc", &src[..]);
        // "G01 X1.2.3" starts at byte 7; "1.2.3" at 12, column 6.
        let d = super::Diagnostic::error("E1007", crate::Span::new(12, 17), "malformed number");
        let text = f.render(&d);
        let mut lines = text.lines();
        assert_eq!(
            lines.next(),
            Some("cr.nc:2:6: error[E1007]: malformed number")
        );
        assert!(text.contains("┌─ cr.nc:2:6"), "{text}");
        assert!(text.contains("2 │ G01 X1.2.3\n"), "{text}");
        assert!(!text.contains('\r'), "{text:?}");
    }
}
