//! Reports: the watched values after a cycle, in the two formats of
//! `stc run` (spec/cli.md for JSON; the text format is documented in the
//! README and docs/runtime.md).
//!
//! JSON is written by hand, key by key, because the contract fixes the key
//! order (the watch order) and the number forms: REAL values are printed
//! from the `f32` itself and LREAL from the `f64`, each in the shortest
//! form that reads back to the same number (serde_json's own float
//! printing), so a value never gains the digits of a wider type.

use stc_syntax::literal::{cp1252_decode, format_duration, format_string};
use stc_syntax::token::ElemType;
use stc_values::{to_text, Value};

use stc_vm::VmFault;

use crate::value::Shown;

/// The output format of reports.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Format {
    #[default]
    Text,
    Json,
    /// A header `cycle,time,PATH,...`, then one row per report (values as
    /// in JSON; strings, and arrays and structures as their JSON text,
    /// quoted per RFC 4180 where they need it).
    Csv,
}

/// Renders the reports of one run in order: the CSV header comes before
/// the first row.
#[derive(Clone, Debug)]
pub struct Renderer {
    format: Format,
    started: bool,
}

impl Renderer {
    pub fn new(format: Format) -> Renderer {
        Renderer {
            format,
            started: false,
        }
    }

    pub fn render(&mut self, r: &Report) -> String {
        let mut out = String::new();
        if self.format == Format::Csv && !self.started {
            out.push_str(&r.csv_header());
        }
        self.started = true;
        out.push_str(&r.render(self.format));
        out
    }

    /// What stdout gets after the last report when the run stops at a
    /// fault: in JSON one more line, `{"fault":{...}}` (spec/cli.md); in
    /// the other formats nothing (the fault's text goes to stderr).
    pub fn fault(&self, f: &VmFault) -> String {
        if self.format != Format::Json {
            return String::new();
        }
        let details: Vec<String> = f
            .details
            .iter()
            .map(|(k, v)| format!("{}:{v}", json_string(k)))
            .collect();
        let details = details.join(",");
        format!(
            "{{\"fault\":{{\"kind\":{},\"instance\":{},\"pou\":{},\"file\":{},\"line\":{},\"column\":{},\"details\":{{{details}}}}}}}\n",
            json_string(f.kind.text()),
            json_string(f.instance.as_deref().unwrap_or(&f.pou)),
            json_string(&f.pou),
            json_string(&f.file),
            f.line,
            f.col
        )
    }
}

/// The watched values at the end of a cycle.
#[derive(Clone, Debug, PartialEq)]
pub struct Report {
    /// The cycle (1-based); 0 is the state before the first cycle.
    pub cycle: u64,
    /// The cycle's time in nanoseconds: (cycle - 1) * tick, 0 for cycle 0.
    pub time_ns: i64,
    /// Watched paths (declared spelling) and their values, in watch order.
    pub values: Vec<(String, Shown)>,
}

impl Report {
    pub fn render(&self, format: Format) -> String {
        match format {
            Format::Text => self.to_text(),
            Format::Json => self.to_json(),
            Format::Csv => self.to_csv(),
        }
    }

    /// The CSV header `cycle,time,PATH,...` and a newline.
    pub fn csv_header(&self) -> String {
        let mut out = String::from("cycle,time");
        for (name, _) in &self.values {
            out.push(',');
            out.push_str(&csv_cell(name));
        }
        out.push('\n');
        out
    }

    /// One CSV row: the cycle, its time and each value as in JSON (a JSON
    /// string as its text), quoted per RFC 4180 where needed.
    pub fn to_csv(&self) -> String {
        let mut out = format!(
            "{},{}",
            self.cycle,
            csv_cell(&format_duration(self.time_ns, false))
        );
        for (_, v) in &self.values {
            let mut json = String::new();
            json_value(&mut json, v);
            let text = match serde_json::from_str::<serde_json::Value>(&json) {
                Ok(serde_json::Value::String(s)) => s,
                _ => json,
            };
            out.push(',');
            out.push_str(&csv_cell(&text));
        }
        out.push('\n');
        out
    }

    /// One line: `{"cycle":3,"time":"T#20ms","values":{"Main.count":3}}`
    /// and a newline.
    pub fn to_json(&self) -> String {
        let mut out = format!(
            "{{\"cycle\":{},\"time\":{},\"values\":{{",
            self.cycle,
            json_string(&format_duration(self.time_ns, false))
        );
        for (i, (name, v)) in self.values.iter().enumerate() {
            if i > 0 {
                out.push(',');
            }
            out.push_str(&json_string(name));
            out.push(':');
            json_value(&mut out, v);
        }
        out.push_str("}}\n");
        out
    }

    /// A header line `cycle 3 (T#20ms)`, then one indented line per value
    /// with the `=` signs aligned; values are written as ST literals.
    pub fn to_text(&self) -> String {
        let mut out = format!(
            "cycle {} ({})\n",
            self.cycle,
            format_duration(self.time_ns, false)
        );
        let width = self
            .values
            .iter()
            .map(|(n, _)| n.chars().count())
            .max()
            .unwrap_or(0);
        for (name, v) in &self.values {
            out.push_str("  ");
            out.push_str(name);
            for _ in name.chars().count()..width {
                out.push(' ');
            }
            out.push_str(" = ");
            text_value(&mut out, v);
            out.push('\n');
        }
        out
    }
}

/// A CSV cell: as it is, or in double quotes (with `""` for a quote) when
/// it holds a comma, a quote or a line break (RFC 4180).
fn csv_cell(s: &str) -> String {
    if s.contains([',', '"', '\n', '\r']) {
        format!("\"{}\"", s.replace('"', "\"\""))
    } else {
        s.to_string()
    }
}

/// A JSON string literal.
pub fn json_string(s: &str) -> String {
    serde_json::to_string(s).unwrap_or_else(|_| "\"\"".into())
}

/// A STRING's bytes as text: STRING is Windows-1252 (semantics.md).
fn cp1252(s: &[u8]) -> String {
    s.iter().map(|&b| cp1252_decode(b)).collect()
}

fn string_text(v: &Value) -> (String, bool) {
    match v {
        Value::Str(s) => (cp1252(s), false),
        Value::WStr(w) => (String::from_utf16_lossy(w), true),
        other => (format!("{other:?}"), false),
    }
}

/// The character of a CHAR (a Windows-1252 byte) or WCHAR (UTF-16 unit).
fn char_of(code: &Value, wide: bool) -> String {
    let c = code.as_int().and_then(|c| u32::try_from(c).ok());
    match c {
        Some(b) if !wide && b <= 0xFF => cp1252_decode(b as u8),
        Some(u) => char::from_u32(u).unwrap_or(char::REPLACEMENT_CHARACTER),
        None => char::REPLACEMENT_CHARACTER,
    }
    .to_string()
}

fn is_number_type(e: ElemType) -> bool {
    use ElemType as E;
    matches!(
        e,
        E::Sint
            | E::Int
            | E::Dint
            | E::Lint
            | E::Usint
            | E::Uint
            | E::Udint
            | E::Ulint
            | E::Byte
            | E::Word
            | E::Dword
            | E::Lword
    )
}

/// A REAL (`single`) or LREAL as JSON: the shortest round-trip number, or
/// the strings "NaN", "INF", "-INF" ([`stc_syntax::real::json`]).
pub fn json_real(x: f64, single: bool) -> String {
    stc_syntax::real::json(x, single)
}

/// Appends the JSON form of a value (spec/cli.md).
pub fn json_value(out: &mut String, v: &Shown) {
    match v {
        Shown::Scalar(e, val) => match (e, val) {
            (ElemType::Bool, _) => {
                let b = val.as_int().is_some_and(|i| i != 0);
                out.push_str(if b { "true" } else { "false" });
            }
            (ElemType::Real | ElemType::Lreal, Value::Real(x)) => {
                out.push_str(&json_real(*x, *e == ElemType::Real))
            }
            (ElemType::Char | ElemType::Wchar, _) => {
                out.push_str(&json_string(&char_of(val, *e == ElemType::Wchar)))
            }
            (e, Value::Int(i)) if is_number_type(*e) => out.push_str(&i.to_string()),
            (e, val) => out.push_str(&json_string(&to_text(*e, val))),
        },
        Shown::Str(s) => out.push_str(&json_string(&string_text(s).0)),
        Shown::Enum { ty, name, value } => match name {
            Some(n) => out.push_str(&json_string(&format!("{ty}#{n}"))),
            None => out.push_str(&value.to_string()),
        },
        Shown::List(items) => {
            out.push('[');
            for (i, item) in items.iter().enumerate() {
                if i > 0 {
                    out.push(',');
                }
                json_value(out, item);
            }
            out.push(']');
        }
        Shown::Record(members) => {
            out.push('{');
            for (i, (name, item)) in members.iter().enumerate() {
                if i > 0 {
                    out.push(',');
                }
                out.push_str(&json_string(name));
                out.push(':');
                json_value(out, item);
            }
            out.push('}');
        }
        Shown::Unreadable => out.push_str("null"),
    }
}

/// Appends the text form of a value: ST literal syntax (`TRUE`, `-42`,
/// `1.5`, `T#1s500ms`, `'text'`, `Color#Red`), arrays as `[1, 2, 3]`,
/// structures and instances as `(x := 1, y := 2)`.
pub fn text_value(out: &mut String, v: &Shown) {
    match v {
        Shown::Scalar(e @ (ElemType::Char | ElemType::Wchar), val) => out.push_str(&format_string(
            &char_of(val, *e == ElemType::Wchar),
            *e == ElemType::Wchar,
        )),
        Shown::Scalar(e, val) => out.push_str(&to_text(*e, val)),
        Shown::Str(s) => {
            let (text, wide) = string_text(s);
            out.push_str(&format_string(&text, wide));
        }
        Shown::Enum { ty, name, value } => match name {
            Some(n) => {
                out.push_str(ty);
                out.push('#');
                out.push_str(n);
            }
            None => out.push_str(&value.to_string()),
        },
        Shown::List(items) => {
            out.push('[');
            for (i, item) in items.iter().enumerate() {
                if i > 0 {
                    out.push_str(", ");
                }
                text_value(out, item);
            }
            out.push(']');
        }
        Shown::Record(members) => {
            out.push('(');
            for (i, (name, item)) in members.iter().enumerate() {
                if i > 0 {
                    out.push_str(", ");
                }
                out.push_str(name);
                out.push_str(" := ");
                text_value(out, item);
            }
            out.push(')');
        }
        Shown::Unreadable => out.push('?'),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use ElemType as E;

    fn s(e: ElemType, v: Value) -> Shown {
        Shown::Scalar(e, v)
    }

    fn i(e: ElemType, v: i128) -> Shown {
        s(e, Value::Int(v))
    }

    fn json(v: Shown) -> String {
        let mut out = String::new();
        json_value(&mut out, &v);
        out
    }

    fn text(v: Shown) -> String {
        let mut out = String::new();
        text_value(&mut out, &v);
        out
    }

    #[test]
    fn elementary_values_in_json() {
        assert_eq!(json(s(E::Bool, Value::Bool(true))), "true");
        assert_eq!(json(s(E::Bool, Value::Bool(false))), "false");
        assert_eq!(json(i(E::Int, -5)), "-5");
        assert_eq!(json(i(E::Ulint, u64::MAX as i128)), "18446744073709551615");
        assert_eq!(json(i(E::Byte, 255)), "255");
        assert_eq!(json(i(E::Char, 65)), "\"A\"");
        assert_eq!(json(i(E::Time, 90_500_000_000)), "\"T#1m30s500ms\"");
        assert_eq!(json(i(E::Time, 0)), "\"T#0s\"");
        assert_eq!(json(i(E::Time, -2_000_000_000)), "\"T#-2s\"");
        assert_eq!(json(i(E::Ltime, 5)), "\"LTIME#5ns\"");
        assert_eq!(json(i(E::Date, 1_706_659_200)), "\"D#2024-01-31\"");
        assert_eq!(json(i(E::Tod, 45_000_500_000_000)), "\"TOD#12:30:00.5\"");
        assert_eq!(json(i(E::Tod, 45_000_000_000_000)), "\"TOD#12:30:00\"");
        assert_eq!(
            json(i(E::Dt, 1_706_704_200_000_000_000)),
            "\"DT#2024-01-31-12:30:00\""
        );
        assert_eq!(
            json(Shown::Str(Value::Str(b"a\"b\xe9".to_vec()))),
            "\"a\\\"b\u{e9}\""
        );
        assert_eq!(json(Shown::Str(Value::wstring("\u{263a}"))), "\"\u{263a}\"");
        assert_eq!(
            json(Shown::Enum {
                ty: "Color".into(),
                name: Some("Red".into()),
                value: 0
            }),
            "\"Color#Red\""
        );
        assert_eq!(
            json(Shown::Enum {
                ty: "Color".into(),
                name: None,
                value: 7
            }),
            "7"
        );
        assert_eq!(json(Shown::Unreadable), "null");
    }

    #[test]
    fn reals_print_the_shortest_form_of_their_own_width() {
        let r = |x: f32| json(s(E::Real, Value::Real(x as f64)));
        let l = |x: f64| json(s(E::Lreal, Value::Real(x)));
        assert_eq!(r(0.1), "0.1");
        assert_eq!(l(0.1), "0.1");
        assert_eq!(l(0.1f32 as f64), "0.10000000149011612");
        assert_eq!(r(100.0 / 3.0), "33.333332");
        assert_eq!(r(1.0), "1.0");
        assert_eq!(r(-2.5), "-2.5");
        assert_eq!(r(1e20), "1e+20");
        assert_eq!(l(1e-7), "1e-7");
        assert_eq!(r(16777216.0), "16777216.0");
        assert_eq!(r(f32::NAN), "\"NaN\"");
        assert_eq!(l(f64::INFINITY), "\"INF\"");
        assert_eq!(l(f64::NEG_INFINITY), "\"-INF\"");
    }

    #[test]
    fn aggregates_in_json() {
        let grid = Shown::List(vec![
            Shown::List(vec![i(E::Int, 1), i(E::Int, 2)]),
            Shown::List(vec![i(E::Int, 3), i(E::Int, 4)]),
        ]);
        assert_eq!(json(grid), "[[1,2],[3,4]]");
        let rec = Shown::Record(vec![
            ("x".into(), i(E::Int, 1)),
            ("tags".into(), Shown::List(vec![])),
        ]);
        assert_eq!(json(rec), "{\"x\":1,\"tags\":[]}");
    }

    fn sample_report() -> Report {
        Report {
            cycle: 3,
            time_ns: 20_000_000,
            values: vec![
                ("Main.count".into(), i(E::Int, 3)),
                ("Main.tmr.Q".into(), s(E::Bool, Value::Bool(true))),
                ("Main.tmr.ET".into(), i(E::Time, 1_500_000_000)),
                ("Main.name".into(), Shown::Str(Value::Str(b"it's".to_vec()))),
                ("Main.x".into(), s(E::Real, Value::Real(0.5))),
                (
                    "Main.pt".into(),
                    Shown::Record(vec![("x".into(), i(E::Int, 1)), ("y".into(), i(E::Int, 2))]),
                ),
                (
                    "Main.arr".into(),
                    Shown::List(vec![i(E::Int, 1), i(E::Int, 2), i(E::Int, 3)]),
                ),
                (
                    "c".into(),
                    Shown::Enum {
                        ty: "Color".into(),
                        name: Some("Green".into()),
                        value: 1,
                    },
                ),
            ],
        }
    }

    #[test]
    fn a_json_report_is_one_line_in_watch_order() {
        assert_eq!(
            sample_report().render(Format::Json),
            "{\"cycle\":3,\"time\":\"T#20ms\",\"values\":{\"Main.count\":3,\"Main.tmr.Q\":true,\
             \"Main.tmr.ET\":\"T#1s500ms\",\"Main.name\":\"it's\",\"Main.x\":0.5,\
             \"Main.pt\":{\"x\":1,\"y\":2},\"Main.arr\":[1,2,3],\"c\":\"Color#Green\"}}\n"
        );
        let empty = Report {
            cycle: 0,
            time_ns: 0,
            values: vec![],
        };
        assert_eq!(
            empty.to_json(),
            "{\"cycle\":0,\"time\":\"T#0s\",\"values\":{}}\n"
        );
    }

    #[test]
    fn a_text_report_aligns_st_literals() {
        assert_eq!(
            sample_report().render(Format::Text),
            "cycle 3 (T#20ms)\n\
             \x20 Main.count  = 3\n\
             \x20 Main.tmr.Q  = TRUE\n\
             \x20 Main.tmr.ET = T#1s500ms\n\
             \x20 Main.name   = 'it$'s'\n\
             \x20 Main.x      = 0.5\n\
             \x20 Main.pt     = (x := 1, y := 2)\n\
             \x20 Main.arr    = [1, 2, 3]\n\
             \x20 c           = Color#Green\n"
        );
        assert_eq!(text(s(E::Real, Value::Real(f64::NAN))), "NaN");
        assert_eq!(text(s(E::Real, Value::Real((0.1f32) as f64))), "0.1");
        assert_eq!(text(i(E::Char, 36)), "'$$'");
        assert_eq!(text(i(E::Wchar, 0x263a)), "\"\u{263a}\"");
        assert_eq!(text(Shown::Str(Value::wstring("a\"b"))), "\"a$\"b\"");
        assert_eq!(text(Shown::Unreadable), "?");
    }
}
