//! Values as text and back: what `*_TO_STRING` produces (and reports print),
//! what `STRING_TO_*` accepts, and truncation to declared string lengths.
//!
//! The texts are the literals of ST without a type prefix, printed by the
//! canonical printers of `stc_syntax::literal` so that a value printed here
//! and read back by the parser (or by [`parse_value`]) is the same value.
//! Time and date values keep their `T#` / `D#` / `TOD#` / `DT#` prefix: it
//! is part of their literal form, not a type prefix.

use crate::types::{int_range, is_date, is_dt, is_duration, is_int_like, is_real, is_tod};
use crate::{misuse, Fault, Value};
use stc_syntax::literal::{
    cp1252_decode, cp1252_encode, format_date, format_dt, format_duration, format_tod,
    parse_based_int, parse_date, parse_dt, parse_duration, parse_int, parse_tod,
};
use stc_syntax::token::{ElemType, TokenKind};

use ElemType as E;

/// Text of a value as `*_TO_STRING` produces it and as reports print it:
/// `TRUE`, `-42`, `1.5`, `3.4028235E38`, `INF`, `NaN`, `T#1s500ms`,
/// `LTIME#5ns`, `D#2024-01-31`, `TOD#12:30:00.5`, `DT#2024-01-31-12:30:00`;
/// strings and characters as their characters, without quotes.
pub fn to_text(t: ElemType, v: &Value) -> String {
    match (t, v) {
        (E::Real, Value::Real(x)) => real_text(*x, true),
        (_, Value::Real(x)) => real_text(*x, false),
        (E::Time | E::Ltime, Value::Int(ns)) => format_duration(clamp_i64(*ns), t == E::Ltime),
        (E::Date | E::Ldate, Value::Int(s)) => format_date(clamp_i64(*s), t == E::Ldate),
        (E::Tod | E::Ltod, Value::Int(ns)) => format_tod(
            u64::try_from(ns.rem_euclid(stc_syntax::literal::NS_PER_D)).unwrap_or(0),
            t == E::Ltod,
        ),
        (E::Dt | E::Ldt, Value::Int(ns)) => format_dt(clamp_i64(*ns), t == E::Ldt),
        (E::Char, Value::Int(c)) => match u8::try_from(*c) {
            Ok(b) => cp1252_decode(b).to_string(),
            Err(_) => char::REPLACEMENT_CHARACTER.to_string(),
        },
        (E::Wchar, Value::Int(c)) => char_text(*c).to_string(),
        (E::Bool, Value::Int(i)) => bool_text(*i != 0).to_string(),
        (_, Value::Bool(b)) => bool_text(*b).to_string(),
        (_, Value::Int(i)) => i.to_string(),
        (_, Value::Str(s)) => string_text(s),
        (_, Value::WStr(w)) => String::from_utf16_lossy(w),
    }
}

fn bool_text(b: bool) -> &'static str {
    if b {
        "TRUE"
    } else {
        "FALSE"
    }
}

fn clamp_i64(v: i128) -> i64 {
    i64::try_from(v).unwrap_or(if v < 0 { i64::MIN } else { i64::MAX })
}

fn char_text(c: i128) -> char {
    u32::try_from(c)
        .ok()
        .and_then(char::from_u32)
        .unwrap_or(char::REPLACEMENT_CHARACTER)
}

/// The text of a STRING's bytes, read as Windows-1252 (spec/semantics.md:
/// single-byte text is Windows-1252, a superset of Latin-1's printable
/// characters).
pub fn string_text(s: &[u8]) -> String {
    s.iter().map(|&b| cp1252_decode(b)).collect()
}

/// REAL values print as the shortest text that reads back to the same f32,
/// LREAL values as the shortest that reads back to the same f64; both in
/// the literal form of `format_real` (always a `.`, exponent as `E`).
fn real_text(x: f64, single: bool) -> String {
    if x.is_nan() {
        return "NaN".into();
    }
    if x.is_infinite() {
        return if x > 0.0 { "INF" } else { "-INF" }.into();
    }
    stc_syntax::real::text(x, single)
}

/// Truncates a string value to at most `len` characters (bytes of a
/// STRING, code units of a WSTRING), as assignment to `STRING[len]` does.
/// Other values are returned unchanged.
pub fn truncate(v: &Value, len: u32) -> Value {
    let n = usize::try_from(len).unwrap_or(usize::MAX);
    match v {
        Value::Str(s) => Value::Str(s.iter().copied().take(n).collect()),
        Value::WStr(s) => Value::WStr(s.iter().copied().take(n).collect()),
        other => other.clone(),
    }
}

/// `STRING_TO_*`: the value of `text` read as an ST literal of type `to`.
///
/// Surrounding blanks (space, tab, CR, LF) are ignored. Accepted forms:
/// BOOL `TRUE`/`FALSE`/`1`/`0`; integers and bit strings in decimal or
/// `2#`/`8#`/`16#`, with an optional sign and `_` separators; REAL/LREAL
/// decimal integers or reals with optional exponent, and `INF`, `-INF`,
/// `NaN` (what [`to_text`] prints); durations, dates, times of day and
/// dates-and-times with or without their prefix (`T#1s`, `1s`, `D#2024-01-31`,
/// `2024-01-31`). Every form may carry its type prefix (`INT#-5`,
/// `BOOL#TRUE`, `LREAL#1.5`); it must name `to` (for time and date types
/// the long and short prefixes are both accepted). A STRING or WSTRING
/// target takes the text itself (for STRING in Windows-1252: a character
/// it cannot encode faults); a CHAR or WCHAR target takes its first
/// character (NUL for an empty text). Anything else, and any value outside
/// `to`'s range, is a conversion fault.
pub fn parse_value(to: ElemType, text: &str) -> Result<Value, Fault> {
    match to {
        E::String => {
            return text
                .chars()
                .map(|c| cp1252_encode(c).ok_or(Fault::Conversion))
                .collect::<Result<Vec<u8>, Fault>>()
                .map(Value::Str)
        }
        E::Wstring => return Ok(Value::wstring(text)),
        E::Char => {
            let c = text.chars().next().unwrap_or('\0');
            return cp1252_encode(c)
                .map(|b| Value::Int(b.into()))
                .ok_or(Fault::Conversion);
        }
        E::Wchar => {
            let c = text.chars().next().map_or(0, u32::from);
            if c > 0xFFFF {
                return Err(Fault::Conversion);
            }
            return Ok(Value::Int(c.into()));
        }
        _ => {}
    }
    let s = text.trim_matches([' ', '\t', '\r', '\n']);
    if s.is_empty() {
        return Err(Fault::Conversion);
    }
    match to {
        E::Bool => parse_bool(s),
        _ if is_int_like(to) => parse_integer(to, s),
        _ if is_real(to) => parse_real(to, s),
        _ if is_duration(to) => time_literal(s, TokenKind::Duration, "T#", |t| {
            parse_duration(t).ok().map(i128::from)
        }),
        _ if is_date(to) => time_literal(s, TokenKind::Date, "D#", |t| {
            parse_date(t).ok().map(i128::from)
        }),
        _ if is_tod(to) => time_literal(s, TokenKind::Tod, "TOD#", |t| {
            parse_tod(t).ok().map(i128::from)
        }),
        _ if is_dt(to) => time_literal(s, TokenKind::Dt, "DT#", |t| {
            parse_dt(t).ok().map(i128::from)
        }),
        _ => misuse(),
    }
}

/// Splits off a `NAME#` type prefix when the text before the first `#`
/// is a word (a based number's base is digits). The prefix must name `to`.
fn strip_type_prefix(to: ElemType, s: &str) -> Result<&str, Fault> {
    match s.split_once('#') {
        Some((p, rest)) if p.starts_with(|c: char| c.is_ascii_alphabetic()) => {
            if ElemType::from_name(p) == Some(to) {
                Ok(rest)
            } else {
                Err(Fault::Conversion)
            }
        }
        _ => Ok(s),
    }
}

fn parse_bool(s: &str) -> Result<Value, Fault> {
    let body = strip_type_prefix(E::Bool, s)?;
    if body.eq_ignore_ascii_case("TRUE") || body == "1" {
        Ok(Value::Bool(true))
    } else if body.eq_ignore_ascii_case("FALSE") || body == "0" {
        Ok(Value::Bool(false))
    } else {
        Err(Fault::Conversion)
    }
}

fn split_sign(s: &str) -> (bool, &str) {
    if let Some(r) = s.strip_prefix('-') {
        (true, r)
    } else if let Some(r) = s.strip_prefix('+') {
        (false, r)
    } else {
        (false, s)
    }
}

fn parse_integer(to: ElemType, s: &str) -> Result<Value, Fault> {
    let body = strip_type_prefix(to, s)?;
    let (negative, digits) = split_sign(body);
    let magnitude = if digits.contains('#') {
        parse_based_int(digits)
    } else {
        parse_int(digits)
    }
    .map_err(|_| Fault::Conversion)?;
    let v = if negative {
        -i128::from(magnitude)
    } else {
        i128::from(magnitude)
    };
    match int_range(to) {
        Some((lo, hi)) if (lo..=hi).contains(&v) => Ok(Value::Int(v)),
        _ => Err(Fault::Conversion),
    }
}

/// Digits with single `_` separators between digits.
fn is_digit_run(s: &str) -> bool {
    !s.is_empty()
        && s.starts_with(|c: char| c.is_ascii_digit())
        && s.ends_with(|c: char| c.is_ascii_digit())
        && !s.contains("__")
        && s.bytes().all(|b| b.is_ascii_digit() || b == b'_')
}

fn parse_real(to: ElemType, s: &str) -> Result<Value, Fault> {
    let body = strip_type_prefix(to, s)?;
    let (negative, unsigned) = split_sign(body);
    let special = if unsigned.eq_ignore_ascii_case("INF") {
        Some(f64::INFINITY)
    } else if unsigned.eq_ignore_ascii_case("NAN") && unsigned.len() == body.len() {
        Some(f64::NAN)
    } else {
        None
    };
    if let Some(x) = special {
        return Ok(Value::Real(if negative { -x } else { x }));
    }
    let (mantissa, exponent) = match unsigned.find(['e', 'E']) {
        Some(i) => (&unsigned[..i], Some(&unsigned[i + 1..])),
        None => (unsigned, None),
    };
    let (int_part, frac_part) = match mantissa.split_once('.') {
        Some((i, f)) => (i, Some(f)),
        None => (mantissa, None),
    };
    let shape_ok = is_digit_run(int_part)
        && frac_part.is_none_or(is_digit_run)
        && exponent.is_none_or(|e| is_digit_run(split_sign(e).1));
    if !shape_ok {
        return Err(Fault::Conversion);
    }
    let cleaned: String = body.chars().filter(|&c| c != '_').collect();
    let x = if to == E::Real {
        cleaned.parse::<f32>().map(f64::from)
    } else {
        cleaned.parse::<f64>()
    }
    .map_err(|_| Fault::Conversion)?;
    if x.is_finite() {
        Ok(Value::Real(x))
    } else {
        Err(Fault::Conversion)
    }
}

/// A time or date literal with or without its prefix; a prefix must start
/// a literal of the right kind.
fn time_literal(
    s: &str,
    kind: TokenKind,
    default_prefix: &str,
    parse: impl Fn(&str) -> Option<i128>,
) -> Result<Value, Fault> {
    let owned;
    let text = match s.split_once('#') {
        Some((p, _)) => {
            if ElemType::time_literal_prefix(p.to_ascii_uppercase().as_bytes()) != Some(kind) {
                return Err(Fault::Conversion);
            }
            s
        }
        None => {
            owned = format!("{default_prefix}{s}");
            &owned
        }
    };
    parse(text).map(Value::Int).ok_or(Fault::Conversion)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn text(t: ElemType, v: Value) -> String {
        to_text(t, &v)
    }

    #[test]
    fn texts_of_every_kind() {
        let ns = 1_000_000_000i128;
        let cases = [
            (E::Bool, Value::Bool(true), "TRUE"),
            (E::Bool, Value::Bool(false), "FALSE"),
            (E::Int, Value::Int(-42), "-42"),
            (
                E::Ulint,
                Value::Int(u64::MAX as i128),
                "18446744073709551615",
            ),
            (E::Byte, Value::Int(255), "255"),
            (E::Real, Value::Real(0.1f32 as f64), "0.1"),
            (E::Real, Value::Real(1.0), "1.0"),
            (E::Real, Value::Real(f32::MAX as f64), "3.4028235E38"),
            (E::Real, Value::Real(1e-10f32 as f64), "1.0E-10"),
            (E::Lreal, Value::Real(0.1), "0.1"),
            (E::Lreal, Value::Real(0.1f32 as f64), "0.10000000149011612"),
            (E::Lreal, Value::Real(-2.5), "-2.5"),
            (E::Real, Value::Real(f64::NAN), "NaN"),
            (E::Lreal, Value::Real(f64::INFINITY), "INF"),
            (E::Lreal, Value::Real(f64::NEG_INFINITY), "-INF"),
            (E::Time, Value::Int(1_500_000_000), "T#1s500ms"),
            (E::Time, Value::Int(0), "T#0s"),
            (E::Time, Value::Int(-2 * ns), "T#-2s"),
            (E::Ltime, Value::Int(5), "LTIME#5ns"),
            (E::Date, Value::Int(86_400), "D#1970-01-02"),
            (E::Ldate, Value::Int(0), "LDATE#1970-01-01"),
            (
                E::Tod,
                Value::Int(12 * 3600 * ns + ns / 2),
                "TOD#12:00:00.5",
            ),
            (E::Ltod, Value::Int(0), "LTOD#00:00:00"),
            (E::Dt, Value::Int(-ns), "DT#1969-12-31-23:59:59"),
            (E::Ldt, Value::Int(0), "LDT#1970-01-01-00:00:00"),
            (E::String, Value::Str(b"a\xE9".to_vec()), "a\u{e9}"),
            (E::Wstring, Value::wstring("\u{20ac}"), "\u{20ac}"),
            (E::Char, Value::Int(65), "A"),
            (E::Wchar, Value::Int(0x20ac), "\u{20ac}"),
        ];
        for (t, v, want) in cases {
            assert_eq!(text(t, v.clone()), want, "{t:?} {v:?}");
        }
    }

    #[test]
    fn mismatched_values_still_print() {
        assert_eq!(text(E::Int, Value::Real(1.5)), "1.5");
        assert_eq!(text(E::Real, Value::Int(3)), "3");
        assert_eq!(
            text(E::Time, Value::Int(i128::MAX)),
            format_duration(i64::MAX, false)
        );
    }

    #[test]
    fn truncation() {
        assert_eq!(truncate(&Value::string("abcdef"), 3), Value::string("abc"));
        assert_eq!(truncate(&Value::string("ab"), 3), Value::string("ab"));
        assert_eq!(truncate(&Value::string("ab"), 0), Value::string(""));
        assert_eq!(truncate(&Value::wstring("abcd"), 2), Value::wstring("ab"));
        assert_eq!(truncate(&Value::Int(5), 1), Value::Int(5));
    }

    fn ok(t: ElemType, s: &str) -> Value {
        parse_value(t, s).unwrap_or_else(|e| panic!("{t:?} {s:?}: {e:?}"))
    }

    fn bad(t: ElemType, s: &str) {
        assert_eq!(parse_value(t, s), Err(Fault::Conversion), "{t:?} {s:?}");
    }

    #[test]
    fn parse_integers() {
        assert_eq!(ok(E::Int, "42"), Value::Int(42));
        assert_eq!(ok(E::Int, "  -42 "), Value::Int(-42));
        assert_eq!(ok(E::Int, "+7"), Value::Int(7));
        assert_eq!(ok(E::Int, "1_000"), Value::Int(1000));
        assert_eq!(ok(E::Int, "INT#-5"), Value::Int(-5));
        assert_eq!(ok(E::Int, "int#5"), Value::Int(5));
        assert_eq!(ok(E::Byte, "16#FF"), Value::Int(255));
        assert_eq!(ok(E::Word, "WORD#16#FFFF"), Value::Int(65535));
        assert_eq!(ok(E::Sint, "-2#1000_0000"), Value::Int(-128));
        assert_eq!(ok(E::Usint, "8#377"), Value::Int(255));
        assert_eq!(
            ok(E::Ulint, "18446744073709551615"),
            Value::Int(u64::MAX as i128)
        );
        assert_eq!(
            ok(E::Lint, "-9223372036854775808"),
            Value::Int(i64::MIN as i128)
        );
        assert_eq!(ok(E::Uint, "-0"), Value::Int(0));
        bad(E::Int, "32768");
        bad(E::Sint, "-129");
        bad(E::Uint, "-1");
        bad(E::Byte, "256");
        bad(E::Byte, "16#100");
        bad(E::Int, "DINT#5");
        bad(E::Int, "1.5");
        bad(E::Int, "");
        bad(E::Int, "   ");
        bad(E::Int, "12abc");
        bad(E::Int, "- 5");
        bad(E::Int, "1__0");
        bad(E::Int, "_1");
        bad(E::Int, "16#");
        bad(E::Int, "3#12");
        bad(E::Ulint, "18446744073709551616");
        bad(E::Int, "--5");
    }

    #[test]
    fn parse_bools() {
        assert_eq!(ok(E::Bool, "TRUE"), Value::Bool(true));
        assert_eq!(ok(E::Bool, "false"), Value::Bool(false));
        assert_eq!(ok(E::Bool, "1"), Value::Bool(true));
        assert_eq!(ok(E::Bool, " BOOL#0 "), Value::Bool(false));
        bad(E::Bool, "2");
        bad(E::Bool, "yes");
        bad(E::Bool, "INT#1");
    }

    #[test]
    fn parse_reals() {
        assert_eq!(ok(E::Real, "0.1"), Value::Real(0.1f32 as f64));
        assert_eq!(ok(E::Lreal, "0.1"), Value::Real(0.1));
        assert_eq!(ok(E::Lreal, "-1.5E3"), Value::Real(-1500.0));
        assert_eq!(ok(E::Lreal, "2.5e-4"), Value::Real(0.00025));
        assert_eq!(ok(E::Lreal, "1_000.5"), Value::Real(1000.5));
        assert_eq!(ok(E::Lreal, "5"), Value::Real(5.0));
        assert_eq!(ok(E::Lreal, "1E3"), Value::Real(1000.0));
        assert_eq!(ok(E::Real, "REAL#1.5"), Value::Real(1.5));
        assert_eq!(ok(E::Lreal, "INF"), Value::Real(f64::INFINITY));
        assert_eq!(ok(E::Lreal, "-inf"), Value::Real(f64::NEG_INFINITY));
        assert!(ok(E::Real, "NaN").as_real().is_some_and(f64::is_nan));
        // Rounded once, directly to f32 (not through f64).
        assert_eq!(ok(E::Real, "16777217"), Value::Real(16777216.0));
        assert_eq!(ok(E::Real, "3.4028235E38"), Value::Real(f32::MAX as f64));
        bad(E::Real, "1E39");
        bad(E::Lreal, "1E400");
        bad(E::Real, "LREAL#1.0");
        bad(E::Lreal, "1.");
        bad(E::Lreal, ".5");
        bad(E::Lreal, "1.5E");
        bad(E::Lreal, "16#FF");
        bad(E::Lreal, "infinity");
        bad(E::Lreal, "-NaN");
        bad(E::Lreal, "1.5x");
        bad(E::Lreal, "1,5");
    }

    #[test]
    fn parse_times_and_dates() {
        let ms = 1_000_000i128;
        assert_eq!(ok(E::Time, "T#1s500ms"), Value::Int(1500 * ms));
        assert_eq!(ok(E::Time, "1s500ms"), Value::Int(1500 * ms));
        assert_eq!(ok(E::Time, "time#-2s"), Value::Int(-2000 * ms));
        assert_eq!(ok(E::Time, "LTIME#1ms"), Value::Int(ms));
        assert_eq!(ok(E::Ltime, "T#1ms"), Value::Int(ms));
        assert_eq!(ok(E::Date, "D#1970-01-02"), Value::Int(86_400));
        assert_eq!(ok(E::Date, "1970-01-02"), Value::Int(86_400));
        assert_eq!(ok(E::Ldate, "LDATE#1970-01-02"), Value::Int(86_400));
        assert_eq!(ok(E::Tod, "TOD#00:00:01.5"), Value::Int(1500 * ms));
        assert_eq!(ok(E::Tod, "TIME_OF_DAY#00:00:01"), Value::Int(1000 * ms));
        assert_eq!(ok(E::Tod, "00:00:01"), Value::Int(1000 * ms));
        assert_eq!(ok(E::Dt, "DT#1970-01-01-00:00:01"), Value::Int(1000 * ms));
        assert_eq!(ok(E::Dt, "1970-01-01-00:00:01"), Value::Int(1000 * ms));
        bad(E::Time, "D#1970-01-01");
        bad(E::Time, "5");
        bad(E::Time, "T#5x");
        bad(E::Date, "T#1s");
        bad(E::Date, "D#2023-02-29");
        bad(E::Tod, "TOD#24:00:00");
        bad(E::Dt, "DT#1970-01-01");
        bad(E::Dt, "DT#9999-01-01-00:00:00");
    }

    #[test]
    fn parse_strings_and_chars() {
        assert_eq!(ok(E::String, " a b "), Value::string(" a b "));
        assert_eq!(ok(E::Wstring, "x"), Value::wstring("x"));
        assert_eq!(ok(E::String, ""), Value::string(""));
        assert_eq!(ok(E::String, "\u{20ac}"), Value::Str(vec![0x80]));
        bad(E::String, "\u{3a9}");
        assert_eq!(ok(E::Char, "AB"), Value::Int(65));
        assert_eq!(ok(E::Char, ""), Value::Int(0));
        assert_eq!(ok(E::Wchar, "\u{20ac}"), Value::Int(0x20ac));
        assert_eq!(ok(E::Char, "\u{20ac}"), Value::Int(0x80));
        bad(E::Char, "\u{3a9}");
        assert_eq!(text(E::Char, Value::Int(0x80)), "€");
        assert_eq!(text(E::String, Value::Str(vec![0x80, 0xE9])), "€é");
    }
}
