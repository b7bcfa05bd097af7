//! SARIF 2.1.0 (`--message-format sarif`): the diagnostics of one run as one
//! JSON document, so code-scanning tools show stc's findings.
//!
//! One run, whose tool driver lists a rule per code that occurs (id, title,
//! the `stc explain` text, default level), and one result per diagnostic:
//! rule, level, message (with its notes and help), the primary location as
//! a region of 1-based lines and columns (columns count characters, as in
//! the human and JSON formats) and the secondary labels as related
//! locations. File names are written as relative URI references (`/`
//! separated, spaces and other reserved characters percent-encoded).

use serde_json::{json, Value};

use crate::{Code, CodeSeverity, Diagnostic, Severity, SourceMap, Span};

/// The SARIF document for `diags` (in the order given).
pub fn render_sarif(diags: &[Diagnostic], sm: &SourceMap, version: &str) -> String {
    let mut rules: Vec<Code> = Vec::new();
    for d in diags {
        if !rules.contains(&d.code) {
            rules.push(d.code);
        }
    }
    let rule_objects: Vec<Value> = rules
        .iter()
        .map(|c| {
            json!({
                "id": c.as_str(),
                "name": c.as_str(),
                "shortDescription": { "text": c.title() },
                "fullDescription": { "text": c.explanation() },
                "defaultConfiguration": {
                    "level": match c.severity() {
                        CodeSeverity::Error => "error",
                        CodeSeverity::Warning => "warning",
                    }
                },
            })
        })
        .collect();
    let results: Vec<Value> = diags
        .iter()
        .map(|d| {
            let mut text = d.message.clone();
            for n in &d.notes {
                text.push_str(&format!("\nnote: {n}"));
            }
            for h in &d.help {
                text.push_str(&format!("\nhelp: {h}"));
            }
            let mut r = json!({
                "ruleId": d.code.as_str(),
                "ruleIndex": rules.iter().position(|c| *c == d.code).unwrap_or(0),
                "level": match d.severity {
                    Severity::Error => "error",
                    Severity::Warning => "warning",
                },
                "message": { "text": text },
            });
            if let Some(loc) = location(d.span, sm, &d.label) {
                r["locations"] = json!([loc]);
            }
            let related: Vec<Value> = d
                .secondary
                .iter()
                .filter_map(|l| location(l.span, sm, &l.message))
                .enumerate()
                .map(|(i, mut l)| {
                    l["id"] = json!(i);
                    l
                })
                .collect();
            if !related.is_empty() {
                r["relatedLocations"] = Value::Array(related);
            }
            r
        })
        .collect();
    let doc = json!({
        "$schema": "https://json.schemastore.org/sarif-2.1.0.json",
        "version": "2.1.0",
        "runs": [{
            "tool": {
                "driver": {
                    "name": "stc",
                    "version": version,
                    "rules": rule_objects,
                }
            },
            "columnKind": "unicodeCodePoints",
            "results": results,
        }]
    });
    let mut s = serde_json::to_string_pretty(&doc).unwrap_or_default();
    s.push('\n');
    s
}

fn location(span: Span, sm: &SourceMap, message: &str) -> Option<Value> {
    let (f, lo) = sm.locate(span.lo)?;
    let (_, hi) = sm.locate(span.hi)?;
    let mut region = json!({
        "startLine": lo.line,
        "startColumn": lo.col,
        "endLine": hi.line,
        "endColumn": hi.col,
    });
    // An empty span (end of file, a missing token) still covers a column.
    if hi.line == lo.line && hi.col <= lo.col {
        region["endColumn"] = json!(lo.col + 1);
    }
    let mut loc = json!({
        "physicalLocation": {
            "artifactLocation": { "uri": uri(&f.name) },
            "region": region,
        }
    });
    if !message.is_empty() {
        loc["message"] = json!({ "text": message });
    }
    Some(loc)
}

/// A file name as a URI reference: `/` separators, reserved characters
/// percent-encoded; absolute paths become `file://` URIs.
fn uri(name: &str) -> String {
    let path = name.replace('\\', "/");
    let mut out = String::new();
    for b in path.bytes() {
        match b {
            b'A'..=b'Z' | b'a'..=b'z' | b'0'..=b'9' | b'-' | b'.' | b'_' | b'~' | b'/' => {
                out.push(b as char)
            }
            b':' if out.len() == 1 => out.push(':'),
            _ => out.push_str(&format!("%{b:02X}")),
        }
    }
    if path.starts_with('/') {
        format!("file://{out}")
    } else if out.as_bytes().get(1) == Some(&b':') {
        format!("file:///{out}")
    } else {
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn uris() {
        assert_eq!(uri("src/a b.st"), "src/a%20b.st");
        assert_eq!(uri("/abs/x.st"), "file:///abs/x.st");
        assert_eq!(uri("C:\\p\\x.st"), "file:///C:/p/x.st");
    }
}
