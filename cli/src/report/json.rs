//! `-fdiagnostics-format=json`: one object per line, in the shape rustc
//! gives with `--error-format=json`, so tools that read rustc's read these.

use super::Reported;
use serde::{Deserialize, Serialize};

/// A diagnostic (rustc's `Diagnostic`); notes and help are its children.
#[derive(Debug, Serialize, Deserialize, PartialEq)]
pub struct Diag {
    #[serde(rename = "$message_type")]
    pub message_type: String,
    pub message: String,
    pub code: Option<Code>,
    /// `error`, `warning`, `note`, `help`.
    pub level: String,
    pub spans: Vec<Span>,
    pub children: Vec<Diag>,
    /// The text form, header and snippet, as the text format prints it.
    pub rendered: Option<String>,
}

#[derive(Debug, Serialize, Deserialize, PartialEq)]
pub struct Code {
    pub code: String,
    /// The `--explain` text.
    pub explanation: Option<String>,
}

/// A place in a file: lines and columns 1-based, the end column and byte
/// exclusive, as rustc.
#[derive(Debug, Serialize, Deserialize, PartialEq)]
pub struct Span {
    pub file_name: String,
    pub byte_start: u32,
    pub byte_end: u32,
    pub line_start: usize,
    pub line_end: usize,
    pub column_start: usize,
    pub column_end: usize,
    pub is_primary: bool,
    pub text: Vec<SpanLine>,
    pub label: Option<String>,
    pub suggested_replacement: Option<String>,
    pub suggestion_applicability: Option<String>,
    pub expansion: Option<String>,
}

/// A source line of a span, with the highlighted columns.
#[derive(Debug, Serialize, Deserialize, PartialEq)]
pub struct SpanLine {
    pub text: String,
    pub highlight_start: usize,
    pub highlight_end: usize,
}

fn level(s: grammar::Severity) -> &'static str {
    match s {
        grammar::Severity::Error => "error",
        grammar::Severity::Warning => "warning",
    }
}

fn child(level: &str, message: &str) -> Diag {
    Diag {
        message_type: "diagnostic".into(),
        message: message.into(),
        code: None,
        level: level.into(),
        spans: Vec::new(),
        children: Vec::new(),
        rendered: None,
    }
}

/// A span of a diagnostic: its place (`primary`) or a related one, with
/// its label.
fn span(r: &Reported<'_>, at: grammar::Span, label: &str, primary: bool) -> Span {
    let f = r.file;
    let len = f.bytes().len() as u32;
    let start = at.start.min(len);
    let end = at.end.clamp(start, len);
    let (line_start, column_start) = f.line_col(start);
    let (line_end, column_end) = f.line_col(end);
    let lines = (line_start - 1..line_end)
        .filter_map(|i| {
            let from = (start as usize).max(f.line_range(i)?.start);
            // A long line is clipped around the span as the text form
            // clips it; the highlight counts in the text given.
            let window = f.line_window(i, from)?;
            let to = window.offset(end as usize) + 1;
            let from = window.offset(from) + 1;
            Some(SpanLine {
                text: f.window_text(&window),
                highlight_start: from,
                highlight_end: to.max(from),
            })
        })
        .collect();
    Span {
        file_name: f.name.clone(),
        byte_start: start,
        byte_end: end,
        line_start,
        line_end,
        column_start,
        column_end,
        is_primary: primary,
        text: lines,
        label: (!label.is_empty()).then(|| label.to_string()),
        suggested_replacement: None,
        suggestion_applicability: None,
        expansion: None,
    }
}

/// The object of one diagnostic.
pub fn build(r: &Reported<'_>) -> Diag {
    let d = r.diag;
    let mut children: Vec<Diag> = d.notes.iter().map(|n| child("note", n)).collect();
    children.extend(d.help.iter().map(|h| child("help", h)));
    let mut spans = vec![span(r, d.span, &d.label, true)];
    spans.extend(
        d.related
            .iter()
            .map(|(at, label)| span(r, *at, label, false)),
    );
    Diag {
        message_type: "diagnostic".into(),
        message: r.message(),
        code: Some(Code {
            code: d.code.into(),
            explanation: crate::explain::find(d.code).map(|e| crate::explain::render(&e)),
        }),
        level: level(r.severity).into(),
        spans,
        children,
        rendered: Some(r.rendered(false) + "\n"),
    }
}

/// One diagnostic as one line of JSON.
pub fn diagnostic(r: &Reported<'_>) -> String {
    // Plain strings and numbers: serialising cannot fail.
    serde_json::to_string(&build(r)).unwrap_or_default()
}

/// A failure of the driver itself (an unreadable file): no code, no span.
pub fn driver_error(msg: &str) -> String {
    let mut d = child("error", msg);
    d.rendered = Some(format!("gbcc: error: {msg}\n"));
    serde_json::to_string(&d).unwrap_or_default()
}
