//! `-fdiagnostics-format=sarif`: one SARIF 2.1.0 log for the whole run
//! (OASIS SARIF 2.1.0, the subset gcc writes and code-scanning tools
//! read): the tool and its rules, then a result per diagnostic.

use super::Reported;
use serde_json::{json, Value};

/// The schema the log names.
pub const SCHEMA: &str =
    "https://docs.oasis-open.org/sarif/sarif/v2.1.0/errata01/os/schemas/sarif-schema-2.1.0.json";

/// The log as it grows.
#[derive(Default)]
pub struct Log {
    /// The codes seen, in order: a result's `ruleIndex` points here.
    rules: Vec<&'static str>,
    results: Vec<Value>,
    /// Failures of the driver itself (toolExecutionNotifications).
    notifications: Vec<Value>,
}

/// A file name as a relative URI reference: `%`, spaces and the other
/// characters that cannot stand in a URI are percent-encoded.
fn uri(name: &str) -> String {
    let mut out = String::new();
    for b in name.replace('\\', "/").bytes() {
        if b.is_ascii_alphanumeric() || b"-._~/:@!$&'()*+,;=".contains(&b) {
            out.push(b as char);
        } else {
            out.push_str(&format!("%{b:02X}"));
        }
    }
    out
}

/// A place in the diagnostic's file as a SARIF location, with its label.
fn location(r: &Reported<'_>, at: grammar::Span, label: &str) -> Value {
    let f = r.file;
    let len = f.bytes().len() as u32;
    let start = at.start.min(len);
    let end = at.end.clamp(start, len);
    let (start_line, start_column) = f.line_col(start);
    let (end_line, end_column) = f.line_col(end);
    let mut location = json!({
        "physicalLocation": {
            "artifactLocation": { "uri": uri(&f.name) },
            "region": {
                "startLine": start_line,
                "startColumn": start_column,
                "endLine": end_line,
                "endColumn": end_column,
                "byteOffset": start,
                "byteLength": end - start,
            }
        }
    });
    if !label.is_empty() {
        location["message"] = json!({ "text": label });
    }
    location
}

impl Log {
    pub fn add(&mut self, r: &Reported<'_>) {
        let d = r.diag;
        let index = match self.rules.iter().position(|c| *c == d.code) {
            Some(i) => i,
            None => {
                self.rules.push(d.code);
                self.rules.len() - 1
            }
        };
        // The text form's notes and help follow the message, as there.
        let mut text = r.message();
        for n in &d.notes {
            text.push_str(&format!("\nnote: {n}"));
        }
        if let Some(h) = &d.help {
            text.push_str(&format!("\nhelp: {h}"));
        }
        let mut result = json!({
            "ruleId": d.code,
            "ruleIndex": index,
            "level": match r.severity {
                grammar::Severity::Error => "error",
                grammar::Severity::Warning => "warning",
            },
            "message": { "text": text },
            "locations": [location(r, d.span, &d.label)],
        });
        if let Some((at, label)) = &d.related {
            let mut related = location(r, *at, label);
            related["id"] = json!(0);
            result["relatedLocations"] = json!([related]);
        }
        self.results.push(result);
    }

    pub fn notify(&mut self, msg: &str) {
        self.notifications.push(json!({
            "level": "error",
            "message": { "text": msg },
        }));
    }

    /// The whole log.
    pub fn to_json(&self) -> String {
        let rules: Vec<Value> = self
            .rules
            .iter()
            .map(|code| {
                let entry = crate::explain::find(code);
                let mut rule = json!({ "id": code });
                if let Some(e) = entry {
                    rule["shortDescription"] = json!({ "text": e.title });
                    rule["fullDescription"] = json!({ "text": e.body });
                }
                rule
            })
            .collect();
        let log = json!({
            "$schema": SCHEMA,
            "version": "2.1.0",
            "runs": [{
                "tool": {
                    "driver": {
                        "name": "gbcc",
                        "version": env!("CARGO_PKG_VERSION"),
                        "rules": rules,
                    }
                },
                "invocations": [{
                    "executionSuccessful": self.notifications.is_empty(),
                    "toolExecutionNotifications": self.notifications,
                }],
                "results": self.results,
            }]
        });
        serde_json::to_string_pretty(&log).unwrap_or_default()
    }
}

#[cfg(test)]
mod tests {
    #[test]
    fn uris_are_encoded() {
        assert_eq!(super::uri("lib dir/O1%.nc"), "lib%20dir/O1%25.nc");
        assert_eq!(super::uri("a\\b.nc"), "a/b.nc");
    }
}
