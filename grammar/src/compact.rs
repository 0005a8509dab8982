//! Cutting a line into blocks, and removing blanks and comments from them.
//!
//! Spaces and tabs mean nothing outside comments, not even inside numbers
//! and keywords (`X 3 0 . 5` = `X30.5`, dialect.md §1.1), so they are
//! removed before tokenizing; comments are taken out in the same pass (their
//! text goes to the syntax tree). Spans must still point into the original
//! bytes, so the compacted text comes with an [`OffsetMap`].
//!
//! Most blocks need no copy: when every blank only separates two tokens
//! (`G01 X10 Z-5`, not `X 1 0`) and there is no comment, the block is lexed
//! in place and the lexer skips the blanks.

use crate::ast::Comment;
use crate::diag::Diagnostic;
use crate::span::Span;

/// Maps positions in a block's compacted text back to source offsets.
///
/// A block lexed in place needs only its start; a copied block keeps the
/// source offset of every byte it copied (one table lookup per position,
/// no search).
#[derive(Debug, Clone, Copy)]
pub enum OffsetMap<'a> {
    InPlace(usize),
    Copied(&'a [u32]),
}

impl OffsetMap<'_> {
    /// The source offset of compacted byte `c`.
    pub fn start(&self, c: usize) -> usize {
        match self {
            OffsetMap::InPlace(base) => base + c,
            OffsetMap::Copied(table) => table.get(c).map_or(c, |&o| o as usize),
        }
    }

    /// The source end of a compacted range ending at `c`: just after its last
    /// byte, so a span never takes in the blanks that follow it.
    pub fn end(&self, c: usize) -> usize {
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
    pub map: OffsetMap<'a>,
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
    offsets: Vec<u32>,
}

/// Byte classes for the scanner, looked up once per byte.
const PLAIN: u8 = 0;
const BLANK: u8 = 1;
const OPEN: u8 = 2;
const CLOSE: u8 = 3;
const END: u8 = 4;
const BAD: u8 = 5;

static CLASS: [u8; 256] = {
    let mut t = [BAD; 256];
    let mut b = 0x21;
    while b <= 0x7E {
        t[b] = PLAIN;
        b += 1;
    }
    t[b' ' as usize] = BLANK;
    t[b'\t' as usize] = BLANK;
    t[b'(' as usize] = OPEN;
    t[b')' as usize] = CLOSE;
    t[b';' as usize] = END;
    t[b'\n' as usize] = END;
    t[b'\r' as usize] = END;
    t
};

fn class(b: u8) -> u8 {
    CLASS[b as usize]
}

/// The end of the run of plain bytes starting at `i`.
fn plain_run(src: &[u8], mut i: usize, limit: usize) -> usize {
    while i < limit && class(src[i]) == PLAIN {
        i += 1;
    }
    i
}

/// Can `a` and `b` be neighbours inside one token? A blank between such
/// bytes (`X 10`, `F 0.25`, `GO TO`) must be removed before lexing; any
/// other blank only separates tokens, and the lexer can skip it in place.
fn joins(a: u8, b: u8) -> bool {
    let letter = |c: u8| c.is_ascii_alphabetic();
    let digit = |c: u8| c.is_ascii_digit() || c == b'.';
    let sign = |c: u8| c == b'+' || c == b'-';
    (letter(a) && (letter(b) || digit(b) || sign(b)))
        || (digit(a) && digit(b))
        || (sign(a) && digit(b))
}

impl Compactor {
    /// Scans the block starting at `start`; `limit` is the end of the input
    /// (a final Ctrl-Z excluded).
    pub fn scan<'a>(&'a mut self, src: &'a [u8], start: usize, limit: usize) -> Scanned<'a> {
        match in_place(src, start, limit) {
            Ok(scanned) => scanned,
            Err(stop) => self.copied(src, start, stop, limit),
        }
    }

    /// The slow path: copies the block's significant bytes (those before
    /// `stop`, then the rest, its comments taken out).
    fn copied<'a>(
        &'a mut self,
        src: &'a [u8],
        start: usize,
        stop: Stop,
        limit: usize,
    ) -> Scanned<'a> {
        let Stop {
            at: mut i,
            mut first,
            mut last,
        } = stop;
        self.buf.clear();
        self.offsets.clear();
        for (k, &b) in src[start..i].iter().enumerate() {
            if class(b) != BLANK {
                self.buf.push(b);
                self.offsets.push((start + k) as u32);
            }
        }
        let mut comments = Vec::new();
        let mut error = None;
        while i < limit {
            match class(src[i]) {
                PLAIN => {
                    let run = i;
                    i = plain_run(src, i, limit);
                    self.buf.extend_from_slice(&src[run..i]);
                    self.offsets.extend(run as u32..i as u32);
                    first.get_or_insert(run);
                    last = i;
                }
                BLANK => i += 1,
                END => break,
                OPEN => match comment_end(src, i, limit) {
                    Ok(close) => {
                        comments.push(Comment {
                            text: comment_text(&src[i + 1..close]),
                            span: Span::new(i, close + 1),
                        });
                        first.get_or_insert(i);
                        last = close + 1;
                        i = close + 1;
                    }
                    Err(d) => {
                        error = Some(*d);
                        break;
                    }
                },
                CLOSE => {
                    error = Some(unopened(i));
                    i += 1;
                    break;
                }
                _ => {
                    error = Some(bad_byte(src[i], i));
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
            map: OffsetMap::Copied(&self.offsets),
            comments,
            span: first.map(|f| Span::new(f, last)),
            end: i,
            terminator: terminator_at(src, i, limit),
            error,
        }
    }
}

/// Where the in-place scan of a block gave up: the byte `at`, and the
/// block's first and last significant bytes so far.
struct Stop {
    at: usize,
    first: Option<usize>,
    last: usize,
}

/// The block at `start` lexed in place, while it holds only plain bytes
/// and blanks that separate tokens (the lexer skips those); where it
/// holds more, where the copy must start.
#[inline]
fn in_place(src: &[u8], start: usize, limit: usize) -> Result<Scanned<'_>, Stop> {
    let mut i = start;
    let mut first = None;
    let mut last = start;
    loop {
        let run = i;
        i = plain_run(src, i, limit);
        if i > run {
            first.get_or_insert(run);
            last = i;
        }
        if i >= limit || class(src[i]) == END {
            return Ok(Scanned {
                text: &src[start..i],
                map: OffsetMap::InPlace(start),
                comments: Vec::new(),
                span: first.map(|f| Span::new(f, last)),
                end: i,
                terminator: terminator_at(src, i, limit),
                error: None,
            });
        }
        if class(src[i]) != BLANK {
            break;
        }
        let mut j = i + 1;
        while j < limit && class(src[j]) == BLANK {
            j += 1;
        }
        if i > start && last == i && j < limit && joins(src[i - 1], src[j]) {
            break;
        }
        i = j;
    }
    Err(Stop { at: i, first, last })
}

/// E1002: a `)` outside a comment.
fn unopened(at: usize) -> Diagnostic {
    Diagnostic::error("E1002", Span::new(at, at + 1), "`)` without `(`")
        .with_label("no comment is open here")
}

pub(crate) fn terminator_at(src: &[u8], i: usize, limit: usize) -> Terminator {
    if i >= limit {
        Terminator::Eof
    } else if src[i] == b';' {
        Terminator::Semicolon
    } else {
        Terminator::LineEnd
    }
}

/// The `)` closing the comment opened at `open`, on the same line.
fn comment_end(src: &[u8], open: usize, limit: usize) -> Result<usize, Box<Diagnostic>> {
    let mut j = open + 1;
    loop {
        if j >= limit || src[j] == b'\n' || src[j] == b'\r' {
            return Err(Box::new(
                Diagnostic::error(
                    "E1002",
                    Span::new(open, j),
                    "comment not closed on its line",
                )
                .with_label("this `(` has no `)`")
                .with_help("close the comment with `)` before the end of the line"),
            ));
        }
        match src[j] {
            b')' => return Ok(j),
            b'(' => {
                return Err(Box::new(
                    Diagnostic::error("E1002", Span::new(j, j + 1), "nested comment")
                        .with_label("`(` inside a comment")
                        .with_note("comments do not nest: a comment ends at the first `)`"),
                ))
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

/// The comment's text as the program wrote it, when its bytes are UTF-8:
/// a host shows it (a message, an alarm's text), and the canon prints
/// `?` for each byte outside printable ASCII itself. A comment that is
/// not UTF-8 (Latin-1 or GBK, dialect.md §1.1: which, cannot be told)
/// comes as the canon prints it, printable ASCII kept and every other
/// byte (and `"`) a `?`: text the canon prints as it did the bytes.
pub fn comment_text(bytes: &[u8]) -> String {
    if let Ok(text) = core::str::from_utf8(bytes) {
        return text.to_string();
    }
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
        let offsets = (0..s.text.len()).map(|i| s.map.start(i)).collect();
        (
            s.text.to_vec(),
            offsets,
            s.comments.iter().map(|c| c.text.clone()).collect(),
            s.error.map(|d| d.code),
        )
    }

    #[test]
    fn in_place_when_blanks_separate_tokens() {
        let mut c = Compactor::default();
        let s = c.scan(b"G01 X10 Z-5 ;", 0, 13);
        assert!(matches!(s.map, OffsetMap::InPlace(0)));
        assert_eq!(s.text, b"G01 X10 Z-5 ");
        assert_eq!(s.span, Some(Span::new(0, 11)));
        for joined in ["X 10", "F 0.25", "GO TO", "X- 5", "X1 .5", "1 2"] {
            let s = c.scan(joined.as_bytes(), 0, joined.len());
            assert!(matches!(s.map, OffsetMap::Copied(_)), "{joined}");
        }
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
    fn a_utf8_comment_keeps_its_text() {
        let (_, _, comments, _) = scan("#3006=1(CHECK \"INSERT\" \u{e9}\t.)");
        assert_eq!(comments, ["CHECK \"INSERT\" \u{e9}\t."]);
        // One byte that is no UTF-8 makes the comment Latin-1 or GBK:
        // the canon's form, byte by byte.
        let (_, _, comments, _) = scan(b"(\xc3\xa9 \"\xe9\")");
        assert_eq!(comments, ["?? ???"]);
    }

    #[test]
    fn comment_faults() {
        assert_eq!(scan("G01 (A(B))").3, Some("E1002"));
        assert_eq!(scan("G01 (OPEN").3, Some("E1002"));
        assert_eq!(scan("G01 X1)").3, Some("E1002"));
        assert_eq!(scan(b"G01 X\x01").3, Some("E1001"));
        assert_eq!(
            scan("G01 \"").3,
            None,
            "printable ASCII is the lexer's business"
        );
    }
}
