//! Rendering diagnostics as text, in the two formats of spec/cli.md.
//!
//! The human format is the contract's own (a `file:line:col: severity[code]:`
//! header, then the source lines with carets, then `= note:`/`= help:`
//! lines), which no rendering crate produces exactly, so it is written here.
//! Both renderers are pure functions returning strings; the caller prints.

use std::fmt::Write;

use crate::{Diagnostic, SourceFile, SourceMap, Span};

/// Renders one diagnostic in the human format (ends with a newline).
pub fn render_human(d: &Diagnostic, sm: &SourceMap) -> String {
    let mut out = String::new();
    let Some((file, lc)) = sm.locate(d.span.lo) else {
        let _ = writeln!(out, "{}[{}]: {}", d.severity.as_str(), d.code, d.message);
        for n in &d.notes {
            let _ = writeln!(out, "  = note: {n}");
        }
        for h in &d.help {
            let _ = writeln!(out, "  = help: {h}");
        }
        return out;
    };
    let _ = writeln!(
        out,
        "{}:{}:{}: {}[{}]: {}",
        file.name,
        lc.line,
        lc.col,
        d.severity.as_str(),
        d.code,
        d.message
    );

    // Marks to draw: (line, start col, end col, primary?, message).
    let file_id = sm.file_of(d.span.lo);
    let mut marks = vec![mark(file, d.span, true, &d.label)];
    let mut elsewhere = Vec::new();
    for l in &d.secondary {
        if sm.file_of(l.span.lo) == file_id {
            marks.push(mark(file, l.span, false, &l.message));
        } else if let Some((f, lc)) = sm.locate(l.span.lo) {
            elsewhere.push(format!("{}:{}:{}: {}", f.name, lc.line, lc.col, l.message));
        }
    }
    marks.sort_by_key(|m| (m.line, m.start));
    let width = marks
        .iter()
        .map(|m| m.line)
        .max()
        .unwrap_or(1)
        .to_string()
        .len();
    let pad = " ".repeat(width);
    let _ = writeln!(out, "{pad} |");
    let mut prev_line: Option<u32> = None;
    let mut i = 0;
    while i < marks.len() {
        let line = marks[i].line;
        if let Some(p) = prev_line {
            if line > p + 1 {
                let _ = writeln!(out, "{pad} ...");
            }
        }
        let text = file.line_text(line);
        // A long line is shown as a window around its marks.
        let on_line = marks[i..].iter().take_while(|m| m.line == line);
        let (lo, hi) = on_line.fold((usize::MAX, 0), |(lo, hi), m| {
            (
                lo.min(display_width(text, m.start)),
                hi.max(display_width(text, m.end)),
            )
        });
        let win = window(display_width(text, text.len()), lo, hi);
        let shown: String = expand_tabs(text)
            .chars()
            .skip(win.start)
            .take(win.end - win.start)
            .collect();
        let (before, after) = (
            if win.start > 0 { ELLIPSIS } else { "" },
            if win.cut_end { ELLIPSIS } else { "" },
        );
        let _ = writeln!(out, "{line:>width$} | {before}{shown}{after}");
        while i < marks.len() && marks[i].line == line {
            let m = &marks[i];
            let start = display_width(text, m.start).clamp(win.start, win.end);
            let end = display_width(text, m.end).clamp(start, win.end);
            let lead = start - win.start + before.len();
            let len = (end - start).max(1);
            let ch = if m.primary { "^" } else { "-" };
            let underline = format!("{}{}", " ".repeat(lead), ch.repeat(len));
            if m.message.is_empty() {
                let _ = writeln!(out, "{pad} | {underline}");
            } else {
                let _ = writeln!(out, "{pad} | {underline} {}", m.message);
            }
            i += 1;
        }
        prev_line = Some(line);
    }
    for n in d.notes.iter().chain(elsewhere.iter()) {
        let _ = writeln!(out, "{pad} = note: {n}");
    }
    for h in &d.help {
        let _ = writeln!(out, "{pad} = help: {h}");
    }
    out
}

struct Mark<'a> {
    line: u32,
    /// Byte offsets into the line's text.
    start: usize,
    end: usize,
    primary: bool,
    message: &'a str,
}

fn mark<'a>(file: &SourceFile, span: Span, primary: bool, message: &'a str) -> Mark<'a> {
    let lo = file.line_col(span.lo);
    let text = file.line_text(lo.line);
    let line_start = file.line_starts()[lo.line as usize - 1] + file.base;
    let start = (span.lo.saturating_sub(line_start) as usize).min(text.len());
    // A span running past its first line is underlined to the line's end.
    let end = (span.hi.saturating_sub(line_start) as usize).clamp(start, text.len());
    Mark {
        line: lo.line,
        start,
        end,
        primary,
        message,
    }
}

const TAB: &str = "    ";

/// Display columns of a source line shown at most; a longer line is cut
/// to a window around its marks, as rustc does.
const MAX_SHOWN: usize = 160;
/// Columns kept before the first mark of a cut line.
const MARGIN: usize = 40;
const ELLIPSIS: &str = "...";

/// The display columns `start..end` shown of a line `full` columns wide
/// whose marks cover `lo..hi`; `cut_end` when the line goes on after it.
struct Window {
    start: usize,
    end: usize,
    cut_end: bool,
}

fn window(full: usize, lo: usize, hi: usize) -> Window {
    if full <= MAX_SHOWN {
        return Window {
            start: 0,
            end: full,
            cut_end: false,
        };
    }
    let start = lo.min(full).saturating_sub(MARGIN);
    let _ = hi; // marks past the window are cut with it
    let end = (start + MAX_SHOWN).min(full);
    Window {
        start,
        end,
        cut_end: end < full,
    }
}

fn expand_tabs(s: &str) -> String {
    s.replace('\t', TAB)
}

/// Display columns taken by the first `byte` bytes of `line`.
fn display_width(line: &str, byte: usize) -> usize {
    let mut b = byte.min(line.len());
    while !line.is_char_boundary(b) {
        b -= 1;
    }
    line[..b]
        .chars()
        .map(|c| if c == '\t' { TAB.len() } else { 1 })
        .sum()
}

/// Renders one diagnostic as one JSON object on one line (no newline).
pub fn render_json(d: &Diagnostic, sm: &SourceMap) -> String {
    use serde_json::{json, Map, Value};
    let mut obj = Map::new();
    obj.insert("severity".into(), json!(d.severity.as_str()));
    obj.insert("code".into(), json!(d.code.as_str()));
    obj.insert("message".into(), json!(d.message));
    let location = |span: Span, obj: &mut Map<String, Value>| {
        if let (Some((f, lo)), Some((_, hi))) = (sm.locate(span.lo), sm.locate(span.hi)) {
            obj.insert("file".into(), json!(f.name));
            obj.insert("line".into(), json!(lo.line));
            obj.insert("column".into(), json!(lo.col));
            obj.insert("end_line".into(), json!(hi.line));
            obj.insert("end_column".into(), json!(hi.col));
        }
    };
    location(d.span, &mut obj);
    let notes: Vec<String> = d
        .notes
        .iter()
        .cloned()
        .chain(d.help.iter().map(|h| format!("help: {h}")))
        .collect();
    obj.insert("notes".into(), json!(notes));
    if !d.label.is_empty() {
        obj.insert("label".into(), json!(d.label));
    }
    if !d.secondary.is_empty() {
        let labels: Vec<Value> = d
            .secondary
            .iter()
            .map(|l| {
                let mut o = Map::new();
                location(l.span, &mut o);
                o.insert("message".into(), json!(l.message));
                Value::Object(o)
            })
            .collect();
        obj.insert("labels".into(), Value::Array(labels));
    }
    Value::Object(obj).to_string()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Code;

    fn sample() -> (SourceMap, Diagnostic) {
        let mut sm = SourceMap::new();
        let text = "PROGRAM p\n".repeat(11) + "    level := valve_open;\n";
        let f = sm.add("tank.st", text).unwrap();
        let base = sm.file(f).base;
        let line12 = base + 110;
        let d = Diagnostic::new(
            Code::E0301,
            Span::new(line12 + 13, line12 + 23),
            "cannot assign a value of type BOOL to `level` of type INT",
        )
        .with_label("this is BOOL")
        .with_help("use BOOL_TO_INT(...) to convert explicitly");
        (sm, d)
    }

    #[test]
    fn a_long_line_is_shown_as_a_window_around_the_mark() {
        let mut sm = SourceMap::new();
        let head = "x := x + 1; ".repeat(1000);
        let text = format!("{head}bad!;{head}\n");
        let f = sm.add("long.st", text).unwrap();
        let base = sm.file(f).base;
        let at = base + head.len() as u32;
        let d = Diagnostic::new(Code::E0301, Span::new(at, at + 3), "here").with_label("this");
        let out = render_human(&d, &sm);
        let lines: Vec<&str> = out.lines().collect();
        let src = lines[2];
        let marks = lines[3];
        assert!(src.len() < 200, "{src}");
        assert!(src.starts_with("1 | ...") && src.ends_with("..."), "{src}");
        let col = src.find("bad!").expect("the mark's text is shown");
        assert_eq!(marks.find('^'), Some(col), "{out}");
        assert!(marks.contains("^^^ this"), "{out}");
    }

    #[test]
    fn human_format_matches_the_cli_contract() {
        let (sm, d) = sample();
        let expected = "\
tank.st:12:14: error[E0301]: cannot assign a value of type BOOL to `level` of type INT
   |
12 |     level := valve_open;
   |              ^^^^^^^^^^ this is BOOL
   = help: use BOOL_TO_INT(...) to convert explicitly
";
        assert_eq!(render_human(&d, &sm), expected);
    }

    #[test]
    fn json_format_has_the_contract_fields() {
        let (sm, d) = sample();
        let v: serde_json::Value = serde_json::from_str(&render_json(&d, &sm)).unwrap();
        assert_eq!(v["severity"], "error");
        assert_eq!(v["code"], "E0301");
        assert_eq!(v["file"], "tank.st");
        assert_eq!(v["line"], 12);
        assert_eq!(v["column"], 14);
        assert_eq!(v["end_line"], 12);
        assert_eq!(v["end_column"], 24);
        assert_eq!(
            v["notes"][0],
            "help: use BOOL_TO_INT(...) to convert explicitly"
        );
    }

    #[test]
    fn secondary_labels_on_other_lines_are_shown_in_order() {
        let mut sm = SourceMap::new();
        let f = sm
            .add("a.st", "IF x THEN\n  y := 1;\n\n\nEND_WHILE;\n".to_string())
            .unwrap();
        let b = sm.file(f).base;
        let d = Diagnostic::new(Code::E0021, Span::new(b + 22, b + 31), "expected END_IF")
            .with_label("expected END_IF")
            .with_secondary(Span::new(b, b + 2), "this IF is not closed");
        let s = render_human(&d, &sm);
        assert!(s.contains("1 | IF x THEN\n  | -- this IF is not closed\n  ...\n5 | END_WHILE;\n  | ^^^^^^^^^ expected END_IF\n"), "{s}");
    }
}
