//! Long lines in a snippet: a line longer than [`LONG_LINE`] bytes is
//! shown only around the fault, with `...` where text is left out. A file
//! with no line ends (a binary file given by mistake, a 10 MB line of one
//! letter) was otherwise echoed whole, with a caret run as long, for each
//! diagnostic: megabytes on the terminal, in JSON too.

use super::SourceFile;
use codespan_reporting::files::{self, Files};
use std::ops::Range;

/// A line of up to this many bytes (its line end left out) is shown whole,
/// as every line of an ordinary program is.
pub const LONG_LINE: usize = 240;

/// Of a longer line, the window shown: this many bytes before the fault,
/// and this many in all.
const BEFORE: usize = 40;
const WINDOW: usize = 120;

/// What stands for the text left out of a long line (ASCII, as the rest
/// of a snippet: one byte is one column).
pub const CLIPPED: &str = "...";

/// The most characters of source text a message quotes (`malformed number
/// `1.2.3``): a word of ten million characters is not echoed whole.
pub const QUOTED: usize = 60;

/// Source text as a message quotes it: at most [`QUOTED`] characters, and
/// [`CLIPPED`] after them when more follow.
pub fn quote(chars: impl IntoIterator<Item = char>) -> String {
    let mut chars = chars.into_iter();
    let mut out: String = chars.by_ref().take(QUOTED).collect();
    if chars.next().is_some() {
        out.push_str(CLIPPED);
    }
    out
}

/// The part of a line a snippet shows.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct LineWindow {
    /// The bytes of the file shown (the line end never is).
    pub shown: Range<usize>,
    /// Text of the line is left out before / after them.
    pub before: bool,
    pub after: bool,
}

impl LineWindow {
    /// Where byte `at` of the file stands in the window's text, 0-based,
    /// the marker counted; a byte outside the window stands at its edge.
    pub fn offset(&self, at: usize) -> usize {
        let marker = if self.before { CLIPPED.len() } else { 0 };
        marker + at.clamp(self.shown.start, self.shown.end) - self.shown.start
    }

    /// Whether the line is shown whole.
    pub fn whole(&self) -> bool {
        !self.before && !self.after
    }
}

impl SourceFile {
    /// The bytes of line index `i` without its line end.
    fn content(&self, i: usize) -> Option<Range<usize>> {
        let range = self.line_range(i)?;
        let bytes = self.text().as_bytes().get(range.clone())?;
        // One line end (LF, CR LF, or a lone CR made LF); blanks before it
        // are text.
        let len = bytes
            .iter()
            .rposition(|b| !matches!(b, b'\n' | b'\r'))
            .map_or(0, |p| p + 1);
        Some(range.start..range.start + len)
    }

    /// The part of line index `i` a snippet shows so that byte `focus` is
    /// seen: the whole line up to [`LONG_LINE`] bytes, else a window of
    /// `WINDOW` bytes that starts a little before it.
    pub fn line_window(&self, i: usize, focus: usize) -> Option<LineWindow> {
        let line = self.content(i)?;
        if line.len() <= LONG_LINE {
            return Some(LineWindow {
                shown: line,
                before: false,
                after: false,
            });
        }
        let focus = focus.clamp(line.start, line.end);
        // Near the line's end the window keeps its width, reaching back.
        let start = focus
            .saturating_sub(BEFORE)
            .max(line.start)
            .min(line.end - WINDOW);
        let end = start + WINDOW;
        Some(LineWindow {
            shown: start..end,
            before: start > line.start,
            after: end < line.end,
        })
    }

    /// The text of a window, with the markers where text is left out.
    pub fn window_text(&self, w: &LineWindow) -> String {
        let mut out = String::new();
        if w.before {
            out.push_str(CLIPPED);
        }
        out.push_str(self.text().get(w.shown.clone()).unwrap_or(""));
        if w.after {
            out.push_str(CLIPPED);
        }
        out
    }
}

/// The lines one snippet shows, long ones clipped: a codespan file
/// database of those lines alone, whose line numbers and columns are the
/// file's.
pub(super) struct Clipped<'a> {
    file: &'a SourceFile,
    text: String,
    /// The lines shown, by line index.
    lines: Vec<Shown>,
}

/// A line of the view.
struct Shown {
    /// Its index in the file.
    line: usize,
    window: LineWindow,
    /// Where its text starts in the view, and ends (before its LF).
    start: usize,
    end: usize,
}

impl<'a> Clipped<'a> {
    /// The view of the lines `spans` touch, when one of them is long;
    /// `None` when all are shown whole (the file itself is the database
    /// then). A line is seen from the primary span's start when that is on
    /// it, else from the first span byte on it.
    pub(super) fn new(file: &'a SourceFile, spans: &[Range<usize>]) -> Option<Clipped<'a>> {
        let focus = |i: usize| {
            let on_line = |at: usize| file.line_col(at as u32).0 - 1 == i;
            let points = spans.iter().flat_map(|r| [r.start, r.end]);
            match spans.first().filter(|p| on_line(p.start)) {
                Some(p) => p.start,
                None => points.filter(|&at| on_line(at)).min().unwrap_or(0),
            }
        };
        let windows: Vec<(usize, LineWindow)> = touched_lines(file, spans)
            .into_iter()
            .filter_map(|i| Some((i, file.line_window(i, focus(i))?)))
            .collect();
        if windows.iter().all(|(_, w)| w.whole()) {
            return None;
        }
        let mut view = Clipped {
            file,
            text: String::new(),
            lines: Vec::new(),
        };
        for (line, window) in windows {
            let start = view.text.len();
            view.text.push_str(&file.window_text(&window));
            let end = view.text.len();
            view.text.push('\n');
            view.lines.push(Shown {
                line,
                window,
                start,
                end,
            });
        }
        Some(view)
    }

    /// Where byte `at` of the file stands in the view.
    pub(super) fn offset(&self, at: usize) -> usize {
        let line = self.file.line_col(at as u32).0 - 1;
        self.shown(line)
            .map_or(0, |s| s.start + s.window.offset(at))
    }

    fn shown(&self, line: usize) -> Option<&Shown> {
        let k = self.lines.binary_search_by_key(&line, |s| s.line).ok()?;
        self.lines.get(k)
    }

    fn missing(&self, line: usize) -> files::Error {
        files::Error::LineTooLarge {
            given: line,
            max: self.lines.last().map_or(0, |s| s.line),
        }
    }
}

/// The lines codespan reads for labels on `spans`: each span's lines,
/// and the one line between two of them that it shows rather than a gap.
fn touched_lines(file: &SourceFile, spans: &[Range<usize>]) -> Vec<usize> {
    let line = |at: usize| file.line_col(at as u32).0 - 1;
    let mut lines: Vec<usize> = spans
        .iter()
        .flat_map(|r| line(r.start)..=line(r.end))
        .collect();
    lines.sort_unstable();
    lines.dedup();
    let gaps: Vec<usize> = lines
        .windows(2)
        .filter(|w| w[1] == w[0] + 2)
        .map(|w| w[0] + 1)
        .collect();
    lines.extend(gaps);
    lines.sort_unstable();
    lines
}

impl<'a> Files<'a> for Clipped<'_> {
    type FileId = ();
    type Name = &'a str;
    type Source = &'a str;

    fn name(&'a self, (): ()) -> Result<&'a str, files::Error> {
        Ok(&self.file.name)
    }

    fn source(&'a self, (): ()) -> Result<&'a str, files::Error> {
        Ok(&self.text)
    }

    fn line_index(&'a self, (): (), byte_index: usize) -> Result<usize, files::Error> {
        let k = self.lines.partition_point(|s| s.start <= byte_index);
        Ok(self.lines.get(k.saturating_sub(1)).map_or(0, |s| s.line))
    }

    fn line_range(&'a self, (): (), line_index: usize) -> Result<Range<usize>, files::Error> {
        let s = self.shown(line_index).ok_or(self.missing(line_index))?;
        // The text and its LF.
        Ok(s.start..s.end + 1)
    }

    /// The file's column (in bytes, as the header's), not the view's.
    fn column_number(
        &'a self,
        (): (),
        line_index: usize,
        byte_index: usize,
    ) -> Result<usize, files::Error> {
        let s = self.shown(line_index).ok_or(self.missing(line_index))?;
        let w = &s.window;
        let marker = if w.before { CLIPPED.len() } else { 0 };
        let into = byte_index
            .saturating_sub(s.start + marker)
            .min(w.shown.len());
        let line_start =
            (self.file.line_starts.get(line_index)).map_or(w.shown.start, |&l| l as usize);
        Ok(w.shown.start + into - line_start + 1)
    }
}

#[cfg(test)]
mod tests {
    use crate::{Diagnostic, SourceFile, Span};

    /// The line of the snippet that shows source line `n`.
    fn source_line(text: &str, n: usize) -> &str {
        let gutter = format!("{n} │ ");
        text.lines()
            .find_map(|l| l.trim_start().strip_prefix(&gutter))
            .unwrap_or_default()
    }

    /// The caret line under the source line `n`: its offset in the line's
    /// text and its length.
    fn carets(text: &str, n: usize) -> (usize, usize) {
        let lines: Vec<&str> = text.lines().collect();
        let gutter = format!("{n} │ ");
        let at = lines
            .iter()
            .position(|l| l.trim_start().starts_with(&gutter))
            .unwrap_or_default();
        let src = lines[at];
        let under = lines.get(at + 1).copied().unwrap_or_default();
        let from = src.find(" │ ").unwrap_or_default() + " │ ".len();
        let under: String = under.chars().skip(src[..from].chars().count()).collect();
        let start = under.find('^').unwrap_or(usize::MAX);
        (start, under.matches('^').count())
    }

    #[test]
    fn a_fault_in_a_long_line_is_shown_in_a_window_around_it() {
        let mut src = "G01".to_string();
        src.push_str(&" X1".repeat(100_000));
        let fault = src.len() + 1;
        src.push_str(" X1.2.3");
        src.push_str(&" Z2".repeat(1000));
        src.push_str("\nM30\n");
        let f = SourceFile::new("long.nc", src.as_bytes());
        let d = Diagnostic::error("E1007", Span::new(fault, fault + 6), "bad").with_label("here");
        let text = f.render(&d);
        assert!(text.len() < 1000, "{} bytes", text.len());
        let col = fault + 1;
        assert!(
            text.starts_with(&format!("long.nc:1:{col}: error[E1007]")),
            "{text}"
        );
        assert!(text.contains(&format!("┌─ long.nc:1:{col}\n")), "{text}");
        let shown = source_line(&text, 1);
        assert!(
            shown.starts_with("... X1 X1") && shown.ends_with("..."),
            "{shown}"
        );
        assert!(shown.contains(" X1 X1.2.3 Z2 Z2 "), "{shown}");
        assert_eq!(shown.len(), 3 + 120 + 3);
        // The carets stand under `X1.2.3` and the label follows them.
        let (at, len) = carets(&text, 1);
        assert_eq!((&shown[at..at + len], len), ("X1.2.3", 6), "{text}");
        assert!(text.contains("^^^^^^ here"), "{text}");
    }

    /// A line of ten million bytes without a line end (a binary file): a
    /// few hundred bytes, in whichever form; a span as long is cut at the
    /// window's edge.
    #[test]
    fn one_enormous_line_gives_a_short_snippet() {
        let src = vec![b'X'; 10_000_000];
        let f = SourceFile::new("bin.nc", src);
        let d = Diagnostic::error("E1008", Span::new(0, 10_000_000), "unknown");
        for color in [false, true] {
            let text = f.render_styled(&d, color);
            assert!(text.len() < 1000, "{} bytes: {text}", text.len());
            assert!(
                text.contains(&"X".repeat(120)) && text.contains("..."),
                "{text}"
            );
        }
        // At the line's end: the window reaches back its full width.
        let d = Diagnostic::error("E1008", Span::new(9_999_999, 10_000_000), "unknown");
        let text = f.render(&d);
        let shown = source_line(&text, 1);
        assert_eq!(shown, format!("...{}", "X".repeat(120)), "{text}");
        assert_eq!(carets(&text, 1), (122, 1), "{text}");
        assert!(text.contains("┌─ bin.nc:1:10000000\n"), "{text}");
    }

    /// Lines of an ordinary length beside a long one are shown whole, and
    /// one between two labelled lines is still shown.
    #[test]
    fn short_lines_beside_a_long_one_stay_whole() {
        let long = "X".repeat(5000);
        let src = format!("G00 X1\nG01 Z2\n{long}\nM30\n");
        let f = SourceFile::new("mix.nc", src.as_bytes());
        let at = src.find("XXX").unwrap() + 2500;
        let d = Diagnostic::error("E1008", Span::new(at, at + 1), "unknown")
            .with_related(Span::new(0, 3), "set here");
        let text = f.render(&d);
        assert_eq!(source_line(&text, 1), "G00 X1", "{text}");
        assert_eq!(source_line(&text, 2), "G01 Z2", "{text}");
        assert!(source_line(&text, 3).starts_with("...XXX"), "{text}");
        assert!(text.contains("┌─ mix.nc:3:2501\n"), "{text}");
        assert!(text.contains("set here") && text.len() < 1000, "{text}");
    }

    /// A span over several lines, one of them long: every line codespan
    /// draws is there, the long one clipped.
    #[test]
    fn a_span_over_a_long_line_is_drawn_whole() {
        let src = format!("G00 X1\n{}\nG01 Z2\nM30\n", "Y".repeat(3000));
        let f = SourceFile::new("multi.nc", src.as_bytes());
        let end = src.find("Z2").unwrap();
        let d = Diagnostic::error("E2014", Span::new(4, end), "crossed").with_label("this");
        let text = f.render(&d);
        assert!(text.contains("┌─ multi.nc:1:5\n"), "{text}");
        assert!(source_line(&text, 1).ends_with("G00 X1"), "{text}");
        assert!(
            source_line(&text, 2).contains(&format!("{}...", "Y".repeat(120))),
            "{text}"
        );
        assert!(source_line(&text, 3).ends_with("G01 Z2"), "{text}");
        assert!(text.contains("this") && text.len() < 1000, "{text}");
    }

    /// Quoted source text is clipped after QUOTED characters.
    #[test]
    fn quotes_are_clipped() {
        assert_eq!(super::quote("1.2.3".chars()), "1.2.3");
        let long = super::quote("9".repeat(1000).chars());
        assert_eq!(long, format!("{}...", "9".repeat(super::QUOTED)));
    }

    /// The window of a line at most LONG_LINE bytes long is the line.
    #[test]
    fn lines_up_to_the_limit_are_whole() {
        let src = format!("{}\n{}\r\n", "A".repeat(240), "B".repeat(241));
        let f = SourceFile::new("edge.nc", src.as_bytes());
        let w = f.line_window(0, 100).unwrap();
        assert!(w.whole() && w.shown == (0..240), "{w:?}");
        // (Bytes of the file: line 2 starts at 241.)
        let w = f.line_window(1, 241 + 241).unwrap();
        assert_eq!(
            (w.shown.clone(), w.before, w.after),
            (362..482, true, false)
        );
        assert_eq!(f.window_text(&w), format!("...{}", "B".repeat(120)));
    }
}
