//! `gbcc --explain CODE`: the long explanation of a diagnostic code. The
//! texts live in one place, the diagnostics reference `docs/diagnostics.md`,
//! which is compiled in: the manual and the tool cannot disagree.

use std::sync::OnceLock;

/// The diagnostics reference as written.
pub const REFERENCE: &str = include_str!("../../docs/diagnostics.md");

/// One code's section of the reference.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Entry {
    /// `E4009`, `W113`, or a range of user alarms such as `3000–3999`.
    pub code: &'static str,
    /// The one-line condition after the code.
    pub title: &'static str,
    /// The explanation with its wrong and right examples (markdown).
    pub body: &'static str,
}

/// Every entry of the reference, in its order (read once: JSON output
/// looks one up per diagnostic).
pub fn entries() -> &'static [Entry] {
    static ENTRIES: OnceLock<Vec<Entry>> = OnceLock::new();
    ENTRIES.get_or_init(|| read(REFERENCE).collect())
}

/// A section per code, opened by a `### CODE: title` line and closed by
/// the next heading.
fn read(reference: &'static str) -> impl Iterator<Item = Entry> {
    reference.split("\n### ").skip(1).filter_map(|section| {
        let (head, rest) = section.split_once('\n')?;
        let (code, title) = head.split_once(": ")?;
        // A level-2 heading after the last code of a group ends the body.
        let body = rest.split("\n## ").next().unwrap_or(rest);
        Some(Entry {
            code: code.trim(),
            title: title.trim(),
            body: body.trim(),
        })
    })
}

/// The entry of `code`: `E4009`, `e4009` and `4009` all find E4009; a user
/// alarm number (`3005`, `505`) finds its range.
pub fn find(code: &str) -> Option<Entry> {
    let code = code.trim().to_ascii_uppercase();
    if code.chars().all(|c| c.is_ascii_digit()) {
        if let Some(e) = entries().iter().find(|e| e.code[1..] == code) {
            return Some(*e);
        }
        // A user alarm: 500–599 or 3000–3999.
        let n: u32 = code.parse().ok()?;
        return entries()
            .iter()
            .find(|e| range(e.code).is_some_and(|(lo, hi)| (lo..=hi).contains(&n)))
            .copied();
    }
    if (code.len() == 5 && code.starts_with('E')) || (code.len() == 4 && code.starts_with('W')) {
        return entries().iter().find(|e| e.code == code).copied();
    }
    None
}

/// `3000–3999` as numbers.
fn range(code: &str) -> Option<(u32, u32)> {
    let (lo, hi) = code.split_once('–')?;
    Some((lo.parse().ok()?, hi.parse().ok()?))
}

/// What `gbcc --explain` prints: the code and its title, then the body.
pub fn render(e: &Entry) -> String {
    format!("{}: {}\n\n{}\n", e.code, e.title, e.body)
}

#[cfg(test)]
mod tests {
    use super::find;

    #[test]
    fn codes_are_found_in_every_spelling() {
        assert_eq!(find("E4009").map(|e| e.code), Some("E4009"));
        assert_eq!(find("e4009").map(|e| e.code), Some("E4009"));
        assert_eq!(find("4009").map(|e| e.code), Some("E4009"));
        assert_eq!(find("w113").map(|e| e.code), Some("W113"));
        assert_eq!(find("3005").map(|e| e.code), Some("3000–3999"));
        assert_eq!(find("505").map(|e| e.code), Some("500–599"));
        assert_eq!(find("E9999"), None);
        assert_eq!(find("W3005"), None);
    }
}
