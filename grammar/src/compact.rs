//! Cutting a line into blocks, and removing blanks and comments from them.
//!
//! Spaces and tabs mean nothing outside comments, not even inside numbers
//! and keywords (`X 3 0 . 5` = `X30.5`, dialect.md §1.1), so they are
//! removed before tokenizing; comments are taken out in the same pass (their
//! text goes to the syntax tree). Spans must still point into the original
//! bytes, so the compacted text comes with an [`OffsetMap`]. A block without
//! blanks or comments — most blocks of most files — is lexed in place,
//! without a copy.

use crate::ast::Comment;
use crate::diag::Diagnostic;
use crate::span::Span;

/// Maps positions in a block's compacted text back to source offsets.
///
/// It holds one `(compact position, source offset)` pair for the block
/// start and one for every place where text resumes after a removed gap, so
/// a block without gaps costs a single entry.
#[derive(Debug, Default)]
pub struct OffsetMap {
    breaks: Vec<(u32, u32)>,
}

impl OffsetMap {
    /// A cursor for lookups in increasing order (tokens come in order).
    pub fn cursor(&self) -> Cursor<'_> {
        Cursor {
            breaks: &self.breaks,
            i: 0,
        }
    }
}

pub struct Cursor<'a> {
    breaks: &'a [(u32, u32)],
    i: usize,
}

impl Cursor<'_> {
    /// The source offset of compacted byte `c`.
    pub fn start(&mut self, c: usize) -> usize {
        while self.i + 1 < self.breaks.len() && self.breaks[self.i + 1].0 as usize <= c {
            self.i += 1;
        }
        match self.breaks.get(self.i) {
            Some(&(at, src)) => src as usize + (c - at as usize),
            None => c,
        }
    }

    /// The source end of a compacted range ending at `c`: just after its last
    /// byte, so a span never takes in the blanks that follow it.
    pub fn end(&mut self, c: usize) -> usize {
        match c.checked_sub(1) {
            Some(last) => self.start(last) + 1,
            None => self.start(0),
        }
    }
}

/// What ended a block.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Terminator {
    Semicolon,
    /// LF, CR LF or a lone CR: the next block starts a new line.
    LineEnd,
    /// The end of the input.
    Eof,
}

/// One block, ready for the lexer.
pub struct Scanned<'a> {
    /// The block without blanks and comments.
    pub text: &'a [u8],
    pub map: &'a OffsetMap,
    pub comments: Vec<Comment>,
    /// From the first to the last byte that is not a blank (comments
    /// included); `None` for an empty block.
    pub span: Option<Span>,
    /// Offset of the terminator (or of the end of the input).
    pub end: usize,
    pub terminator: Terminator,
    /// A character or comment fault: the block is not parsed.
    pub error: Option<Diagnostic>,
}

/// Reusable buffers, so that compacting allocates nothing once warm.
#[derive(Default)]
pub struct Compactor {
    buf: Vec<u8>,
    map: OffsetMap,
}

/// Bytes that can be copied as they are (and lexed in place).
fn is_plain(b: u8) -> bool {
    (0x21..=0x7E).contains(&b) && b != b'(' && b != b')' && b != b';'
}

fn is_terminator(b: u8) -> bool {
    b == b';' || b == b'\n' || b == b'\r'
}

impl Compactor {
    /// Scans the block starting at `start`; `limit` is the end of the input
    /// (a final Ctrl-Z excluded).
    pub fn scan<'a>(&'a mut self, src: &'a [u8], start: usize, limit: usize) -> Scanned<'a> {
        self.map.breaks.clear();
        self.map.breaks.push((0, start as u32));
        let mut i = start;
        while i < limit && is_plain(src[i]) {
            i += 1;
        }
        let mut first = (i > start).then_some(start);
        let mut last = i;
        if i >= limit || is_terminator(src[i]) {
            return Scanned {
                text: &src[start..i],
                map: &self.map,
                comments: Vec::new(),
                span: first.map(|f| Span::new(f, last)),
                end: i,
                terminator: terminator_at(src, i, limit),
                error: None,
            };
        }

        // Slow path: copy what is significant.
        self.buf.clear();
        self.buf.extend_from_slice(&src[start..i]);
        let mut comments = Vec::new();
        let mut gap = false;
        let mut error = None;
        while i < limit {
            let b = src[i];
            match b {
                b';' | b'\n' | b'\r' => break,
                b' ' | b'\t' => {
                    gap = true;
                    i += 1;
                }
                b'(' => match comment_end(src, i, limit) {
                    Ok(close) => {
                        comments.push(Comment {
                            text: comment_text(&src[i + 1..close]),
                            span: Span::new(i, close + 1),
                        });
                        first.get_or_insert(i);
                        last = close + 1;
                        gap = true;
                        i = close + 1;
                    }
                    Err(d) => {
                        error = Some(d);
                        break;
                    }
                },
                b')' => {
                    error = Some(
                        Diagnostic::error("E1002", Span::new(i, i + 1), "`)` without `(`")
                            .with_label("no comment is open here"),
                    );
                    i += 1;
                    break;
                }
                0x21..=0x7E => {
                    if gap {
                        self.map.breaks.push((self.buf.len() as u32, i as u32));
                        gap = false;
                    }
                    self.buf.push(b);
                    first.get_or_insert(i);
                    last = i + 1;
                    i += 1;
                }
                _ => {
                    error = Some(bad_byte(b, i));
                    break;
                }
            }
        }
        if error.is_some() {
            i = skip_rest(src, i, limit);
            // The faulty block reaches to its end, whatever it holds.
            last = last.max(i);
        }
        Scanned {
            text: &self.buf,
            map: &self.map,
            comments,
            span: first.map(|f| Span::new(f, last)),
            end: i,
            terminator: terminator_at(src, i, limit),
            error,
        }
    }
}

fn terminator_at(src: &[u8], i: usize, limit: usize) -> Terminator {
    if i >= limit {
        Terminator::Eof
    } else if src[i] == b';' {
        Terminator::Semicolon
    } else {
        Terminator::LineEnd
    }
}

/// The `)` closing the comment opened at `open`, on the same line.
fn comment_end(src: &[u8], open: usize, limit: usize) -> Result<usize, Diagnostic> {
    let mut j = open + 1;
    loop {
        if j >= limit || src[j] == b'\n' || src[j] == b'\r' {
            return Err(
                Diagnostic::error("E1002", Span::new(open, j), "comment not closed on its line")
                    .with_label("this `(` has no `)`")
                    .with_help("close the comment with `)` before the end of the line"),
            );
        }
        match src[j] {
            b')' => return Ok(j),
            b'(' => {
                return Err(
                    Diagnostic::error("E1002", Span::new(j, j + 1), "nested comment")
                        .with_label("`(` inside a comment")
                        .with_note("comments do not nest: a comment ends at the first `)`"),
                )
            }
            _ => j += 1,
        }
    }
}

/// Finds the end of a faulty block: the next `;` outside a comment, or the
/// end of the line (a comment that is not closed takes the line with it).
fn skip_rest(src: &[u8], mut i: usize, limit: usize) -> usize {
    let mut in_comment = false;
    while i < limit {
        match src[i] {
            b'\n' | b'\r' => break,
            b';' if !in_comment => break,
            b'(' => in_comment = true,
            b')' => in_comment = false,
            _ => {}
        }
        i += 1;
    }
    i
}

fn bad_byte(b: u8, at: usize) -> Diagnostic {
    let what = if b == 0x1A {
        "Ctrl-Z (0x1A) before the end of the file".to_string()
    } else {
        format!("byte 0x{b:02X} not allowed outside a comment")
    };
    Diagnostic::error("E1001", Span::new(at, at + 1), what)
        .with_label("only printable ASCII, space and tab may stand outside ( )")
}

/// The comment text as the canon prints it: printable ASCII kept, every
/// other byte (and `"`) replaced by `?`.
pub fn comment_text(bytes: &[u8]) -> String {
    bytes
        .iter()
        .map(|&b| {
            if (0x20..=0x7E).contains(&b) && b != b'"' {
                b as char
            } else {
                '?'
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scan(src: impl AsRef<[u8]>) -> (Vec<u8>, Vec<usize>, Vec<String>, Option<&'static str>) {
        let src = src.as_ref();
        let mut c = Compactor::default();
        let s = c.scan(src, 0, src.len());
        let mut cur = s.map.cursor();
        let offsets = (0..s.text.len()).map(|i| cur.start(i)).collect();
        (
            s.text.to_vec(),
            offsets,
            s.comments.iter().map(|c| c.text.clone()).collect(),
            s.error.map(|d| d.code),
        )
    }

    #[test]
    fn in_place_without_blanks() {
        let (text, offsets, _, err) = scan("G01X10;G00");
        assert_eq!(text, b"G01X10");
        assert_eq!(offsets, vec![0, 1, 2, 3, 4, 5]);
        assert_eq!(err, None);
    }

    #[test]
    fn blanks_removed_offsets_kept() {
        let (text, offsets, _, _) = scan("X 3 0 .\t5");
        assert_eq!(text, b"X30.5");
        assert_eq!(offsets, vec![0, 2, 4, 6, 8]);
    }

    #[test]
    fn comments_taken_out() {
        let (text, offsets, comments, _) = scan(b"N30 G01(CUT; \xe9)X45");
        assert_eq!(text, b"N30G01X45");
        assert_eq!(offsets[6], 15);
        assert_eq!(comments, vec!["CUT; ?".to_string()]);
    }

    #[test]
    fn comment_faults() {
        assert_eq!(scan("G01 (A(B))").3, Some("E1002"));
        assert_eq!(scan("G01 (OPEN").3, Some("E1002"));
        assert_eq!(scan("G01 X1)").3, Some("E1002"));
        assert_eq!(scan(b"G01 X\x01").3, Some("E1001"));
        assert_eq!(scan("G01 \"").3, None, "printable ASCII is the lexer's business");
    }
}
