//! Decoding and printing literal values.
//!
//! The parser decodes every literal token here and reports a problem with the
//! code the function returns. The canonical printers (durations, dates) are
//! the forms spec/cli.md fixes for reports, and the forms the AST printer
//! writes, so a value printed and read back is the same value.

use stc_diagnostics::Code;

/// A literal problem: the code to report and the message.
#[derive(Clone, PartialEq, Eq, Debug)]
pub struct LitError {
    pub code: Code,
    pub message: String,
}

fn err<T>(code: Code, message: impl Into<String>) -> Result<T, LitError> {
    Err(LitError {
        code,
        message: message.into(),
    })
}

/// Digits with single `_` separators (`1_000`) in the given base.
fn digits_value(text: &str, base: u32, what: &str) -> Result<u64, LitError> {
    if text.is_empty() {
        return err(Code::E0006, format!("{what}: missing digits"));
    }
    if text.starts_with('_') || text.ends_with('_') || text.contains("__") {
        return err(
            Code::E0006,
            format!("{what}: `_` may only separate two digits"),
        );
    }
    let mut value: u64 = 0;
    let mut overflow = false;
    for c in text.chars() {
        if c == '_' {
            continue;
        }
        let Some(d) = c.to_digit(base) else {
            return err(
                Code::E0006,
                format!("{what}: `{c}` is not a digit in base {base}"),
            );
        };
        match value
            .checked_mul(base as u64)
            .and_then(|v| v.checked_add(d as u64))
        {
            Some(v) => value = v,
            None => overflow = true,
        }
    }
    if overflow {
        return err(Code::E0007, format!("{what} does not fit in 64 bits"));
    }
    Ok(value)
}

/// A decimal integer literal `123`, `1_000`.
pub fn parse_int(text: &str) -> Result<u64, LitError> {
    if let Some(i) = text.find(|c: char| !(c.is_ascii_digit() || c == '_')) {
        return err(
            Code::E0006,
            format!(
                "malformed integer literal `{text}`: unexpected `{}`",
                &text[i..]
            ),
        );
    }
    digits_value(text, 10, "integer literal")
}

/// A based integer literal `2#1010`, `8#17`, `16#FF`.
pub fn parse_based_int(text: &str) -> Result<u64, LitError> {
    let (base, digits) = text.split_once('#').unwrap_or((text, ""));
    let base: u32 = match base.replace('_', "").parse() {
        Ok(b @ (2 | 8 | 16)) => b,
        _ => {
            return err(
                Code::E0006,
                format!("unsupported base `{base}#`: integer literals use 2#, 8# or 16#"),
            )
        }
    };
    digits_value(digits, base, "integer literal")
}

/// A real literal `1.5`, `2.5E-3`.
pub fn parse_real(text: &str) -> Result<f64, LitError> {
    let ok_shape = text
        .chars()
        .all(|c| c.is_ascii_digit() || matches!(c, '_' | '.' | 'e' | 'E' | '+' | '-'));
    if !ok_shape || text.contains("__") || text.contains("_.") || text.contains("._") {
        return err(Code::E0006, format!("malformed real literal `{text}`"));
    }
    let cleaned: String = text.chars().filter(|&c| c != '_').collect();
    match cleaned.parse::<f64>() {
        Ok(v) if v.is_finite() => Ok(v),
        Ok(_) => err(
            Code::E0007,
            format!("real literal `{text}` is out of range"),
        ),
        Err(_) => err(Code::E0006, format!("malformed real literal `{text}`")),
    }
}

pub const NS_PER_US: i128 = 1_000;
pub const NS_PER_MS: i128 = 1_000_000;
pub const NS_PER_S: i128 = 1_000_000_000;
pub const NS_PER_M: i128 = 60 * NS_PER_S;
pub const NS_PER_H: i128 = 60 * NS_PER_M;
pub const NS_PER_D: i128 = 24 * NS_PER_H;

/// Splits `T#...` (or `DATE#...`) into its prefix and body.
fn body(text: &str) -> (&str, &str) {
    text.split_once('#').unwrap_or((text, ""))
}

/// Whether a time-literal prefix is the long variant (`LTIME`, `LT`, `LDATE`,
/// `LD`, `LTOD`, `LTIME_OF_DAY`, `LDT`, `LDATE_AND_TIME`).
pub fn is_long_prefix(text: &str) -> bool {
    let p = body(text).0;
    p.len() >= 2 && p.as_bytes()[0].eq_ignore_ascii_case(&b'L')
}

/// A duration literal `T#1h2m3.5s` to signed nanoseconds.
pub fn parse_duration(text: &str) -> Result<i64, LitError> {
    let mut s = body(text).1;
    let bad = |why: &str| err(Code::E0008, format!("malformed duration `{text}`: {why}"));
    let negative = match s.as_bytes().first() {
        Some(b'-') => {
            s = &s[1..];
            true
        }
        Some(b'+') => {
            s = &s[1..];
            false
        }
        _ => false,
    };
    if s.is_empty() {
        return bad("expected a number and a unit such as `T#1s`");
    }
    let units: [(&str, i128, i128); 7] = [
        ("D", NS_PER_D, i128::MAX),
        ("H", NS_PER_H, 24),
        ("M", NS_PER_M, 60),
        ("S", NS_PER_S, 60),
        ("MS", NS_PER_MS, 1000),
        ("US", NS_PER_US, 1000),
        ("NS", 1, 1000),
    ];
    let mut total: i128 = 0;
    let mut last_unit: Option<usize> = None;
    let mut had_fraction = false;
    let mut rest = s;
    while !rest.is_empty() {
        if had_fraction {
            return bad("only the last unit may have a fraction");
        }
        let num_end = rest
            .find(|c: char| !(c.is_ascii_digit() || c == '_' || c == '.'))
            .unwrap_or(rest.len());
        let (num, after) = rest.split_at(num_end);
        let unit_end = after
            .find(|c: char| !c.is_ascii_alphabetic())
            .unwrap_or(after.len());
        let (unit, after) = after.split_at(unit_end);
        if num.is_empty() {
            return bad("expected a number before each unit");
        }
        let unit_upper = unit.to_ascii_uppercase();
        let Some(ui) = units.iter().position(|u| u.0 == unit_upper) else {
            return if unit.is_empty() {
                bad("a unit (d, h, m, s, ms, us, ns) must follow the number")
            } else {
                bad(&format!(
                    "unknown unit `{unit}` (units are d, h, m, s, ms, us, ns)"
                ))
            };
        };
        if let Some(prev) = last_unit {
            if ui <= prev {
                return bad("units must be given from the largest to the smallest, each once");
            }
        }
        let (int_part, frac_part) = match num.split_once('.') {
            Some((i, f)) => {
                had_fraction = true;
                (i, Some(f))
            }
            None => (num, None),
        };
        let int_val = digits_value(int_part, 10, "duration").map_err(|e| LitError {
            code: if e.code == Code::E0007 {
                Code::E0007
            } else {
                Code::E0008
            },
            message: format!("malformed duration `{text}`: {}", e.message),
        })? as i128;
        let (unit_ns, unit_limit) = (units[ui].1, units[ui].2);
        // The most significant unit may overflow (T#25h); the others may not.
        if last_unit.is_some() && int_val >= unit_limit {
            return bad(&format!(
                "`{num}{unit}` is out of range after a larger unit"
            ));
        }
        let mut part = int_val * unit_ns;
        if let Some(f) = frac_part {
            if f.is_empty() || !f.bytes().all(|b| b.is_ascii_digit()) {
                return bad("malformed fraction");
            }
            // The decimal fraction of the unit, truncated below 1 ns. Its
            // first 20 digits are used (below 1e-6 ns even for days), so
            // the product stays far inside i128.
            let digits = &f[..f.len().min(20)];
            let scale = 10i128.pow(digits.len() as u32);
            let frac: i128 = digits.parse().unwrap_or(0);
            part += frac * unit_ns / scale;
        }
        total = total.saturating_add(part);
        if total > i64::MAX as i128 {
            return err(
                Code::E0007,
                format!("duration `{text}` is out of range (at most about 106751 days)"),
            );
        }
        last_unit = Some(ui);
        rest = after.strip_prefix('_').unwrap_or(after);
        if !after.is_empty() && rest.is_empty() {
            return bad("`_` must be followed by another number and unit");
        }
    }
    Ok(if negative {
        -(total as i64)
    } else {
        total as i64
    })
}

fn days_in_month(year: i64, month: u32) -> u32 {
    match month {
        1 | 3 | 5 | 7 | 8 | 10 | 12 => 31,
        4 | 6 | 9 | 11 => 30,
        _ if (year % 4 == 0 && year % 100 != 0) || year % 400 == 0 => 29,
        _ => 28,
    }
}

/// Days since 1970-01-01 of a proleptic Gregorian date.
pub fn days_from_civil(y: i64, m: u32, d: u32) -> i64 {
    let y = if m <= 2 { y - 1 } else { y };
    let era = y.div_euclid(400);
    let yoe = y - era * 400;
    let mp = (m as i64 + 9) % 12;
    let doy = (153 * mp + 2) / 5 + d as i64 - 1;
    let doe = yoe * 365 + yoe / 4 - yoe / 100 + doy;
    era * 146_097 + doe - 719_468
}

/// The date of a day count since 1970-01-01: (year, month, day).
pub fn civil_from_days(z: i64) -> (i64, u32, u32) {
    let z = z + 719_468;
    let era = z.div_euclid(146_097);
    let doe = z - era * 146_097;
    let yoe = (doe - doe / 1460 + doe / 36_524 - doe / 146_096) / 365;
    let y = yoe + era * 400;
    let doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    let mp = (5 * doy + 2) / 153;
    let d = (doy - (153 * mp + 2) / 5 + 1) as u32;
    let m = if mp < 10 { mp + 3 } else { mp - 9 } as u32;
    (if m <= 2 { y + 1 } else { y }, m, d)
}

fn number(s: &str, what: &str, text: &str) -> Result<u64, LitError> {
    if s.is_empty() || !s.bytes().all(|b| b.is_ascii_digit() || b == b'_') {
        return err(Code::E0008, format!("malformed {what} in `{text}`"));
    }
    digits_value(s, 10, what).map_err(|e| LitError {
        code: Code::E0008,
        message: format!("malformed {what} in `{text}`: {}", e.message),
    })
}

fn parse_date_part(s: &str, text: &str) -> Result<i64, LitError> {
    let mut it = s.splitn(3, '-');
    let (Some(y), Some(m), Some(d)) = (it.next(), it.next(), it.next()) else {
        return err(
            Code::E0008,
            format!("malformed date `{text}`: expected YYYY-MM-DD"),
        );
    };
    let y = number(y, "year", text)?;
    let m = number(m, "month", text)?;
    let d = number(d, "day", text)?;
    if y > 9999 {
        return err(Code::E0008, format!("year {y} in `{text}` is out of range"));
    }
    if !(1..=12).contains(&m) {
        return err(
            Code::E0008,
            format!("month {m} in `{text}` is not in 1..12"),
        );
    }
    let dim = days_in_month(y as i64, m as u32);
    if d < 1 || d > dim as u64 {
        return err(
            Code::E0008,
            format!("day {d} in `{text}` is not in 1..{dim}"),
        );
    }
    Ok(days_from_civil(y as i64, m as u32, d as u32))
}

fn parse_tod_part(s: &str, text: &str) -> Result<u64, LitError> {
    let mut it = s.splitn(3, ':');
    let (Some(h), Some(m), Some(sec)) = (it.next(), it.next(), it.next()) else {
        return err(
            Code::E0008,
            format!("malformed time of day `{text}`: expected HH:MM:SS"),
        );
    };
    let h = number(h, "hour", text)?;
    let m = number(m, "minute", text)?;
    let (sec, frac) = match sec.split_once('.') {
        Some((s, f)) => (s, Some(f)),
        None => (sec, None),
    };
    let sec = number(sec, "second", text)?;
    if h > 23 || m > 59 || sec > 59 {
        return err(Code::E0008, format!("time of day `{text}` is out of range"));
    }
    let mut ns = (h as i128 * NS_PER_H + m as i128 * NS_PER_M + sec as i128 * NS_PER_S) as u64;
    if let Some(f) = frac {
        if f.is_empty() || !f.bytes().all(|b| b.is_ascii_digit()) {
            return err(Code::E0008, format!("malformed fraction in `{text}`"));
        }
        let digits: String = f.chars().take(9).collect();
        let scale = 10u64.pow(digits.len() as u32);
        ns += digits.parse::<u64>().unwrap_or(0) * 1_000_000_000 / scale;
    }
    Ok(ns)
}

/// Whether a TOD or DT literal leaves out the seconds (`TOD#09:00`,
/// `DT#2024-01-31-09:00`): the parser reads such a literal in source text
/// as zero seconds, with a warning (W0007), by parsing
/// [`with_zero_seconds`]. Text read at run time (STRING_TO_TOD) stays
/// strict.
pub fn lacks_seconds(text: &str) -> bool {
    let b = body(text).1;
    let tod = match b.match_indices('-').nth(2) {
        Some((i, _)) => &b[i + 1..],
        None => b,
    };
    tod.matches(':').count() == 1
}

/// A TOD or DT literal that [`lacks_seconds`] completed with `:00`.
pub fn with_zero_seconds(text: &str) -> String {
    format!("{text}:00")
}

/// `D#2024-01-31` to seconds since 1970-01-01.
pub fn parse_date(text: &str) -> Result<i64, LitError> {
    Ok(parse_date_part(body(text).1, text)? * 86_400)
}

/// `TOD#12:30:00.5` to nanoseconds since midnight.
pub fn parse_tod(text: &str) -> Result<u64, LitError> {
    parse_tod_part(body(text).1, text)
}

/// `DT#2024-01-31-12:30:00` to nanoseconds since 1970-01-01T00:00:00.
pub fn parse_dt(text: &str) -> Result<i64, LitError> {
    let b = body(text).1;
    // The date has two dashes; the third separates the time of day.
    let split = b.match_indices('-').nth(2).map(|(i, _)| i);
    let Some(i) = split else {
        return err(
            Code::E0008,
            format!("malformed date and time `{text}`: expected YYYY-MM-DD-HH:MM:SS"),
        );
    };
    let days = parse_date_part(&b[..i], text)? as i128;
    let tod = parse_tod_part(&b[i + 1..], text)? as i128;
    let ns = days * NS_PER_D + tod;
    i64::try_from(ns).map_err(|_| LitError {
        code: Code::E0007,
        message: format!("date and time `{text}` is out of range (years 1678..2262)"),
    })
}

/// A string literal's value. Escapes are decoded; problems come back with
/// their byte range inside `text` (which includes the quotes).
/// The characters of Windows-1252 bytes 0x80..=0x9F, as the WHATWG encoding
/// standard (and so every browser and `encoding_rs`) decodes them: the five
/// bytes Windows-1252 leaves undefined stand for the C1 control of the same
/// code. Every other byte is the Latin-1 character of the same code.
const CP1252_HIGH: [char; 32] = [
    '\u{20AC}', '\u{81}', '\u{201A}', '\u{192}', '\u{201E}', '\u{2026}', '\u{2020}', '\u{2021}',
    '\u{2C6}', '\u{2030}', '\u{160}', '\u{2039}', '\u{152}', '\u{8D}', '\u{17D}', '\u{8F}',
    '\u{90}', '\u{2018}', '\u{2019}', '\u{201C}', '\u{201D}', '\u{2022}', '\u{2013}', '\u{2014}',
    '\u{2DC}', '\u{2122}', '\u{161}', '\u{203A}', '\u{153}', '\u{9D}', '\u{17E}', '\u{178}',
];

/// The character a byte of single-byte text stands for: STRING values and
/// files that are not UTF-8 are Windows-1252 (spec/semantics.md).
pub fn cp1252_decode(b: u8) -> char {
    match b {
        0x80..=0x9F => CP1252_HIGH[(b - 0x80) as usize],
        _ => char::from(b),
    }
}

/// The Windows-1252 byte of a character, `None` for a character that has
/// none (`Ω`, and the C1 controls that Windows-1252 uses for other
/// characters, such as U+0080).
pub fn cp1252_encode(c: char) -> Option<u8> {
    match u32::from(c) {
        n @ (0..=0x7F | 0xA0..=0xFF) => Some(n as u8),
        _ => CP1252_HIGH
            .iter()
            .position(|&h| h == c)
            .map(|i| 0x80 + i as u8),
    }
}

pub fn decode_string(text: &str, wide: bool) -> (String, Vec<(usize, usize, String)>) {
    let mut out = String::with_capacity(text.len());
    let mut errors = Vec::new();
    let inner_end = if text.len() >= 2 && text.ends_with(&text[..1]) {
        text.len() - 1
    } else {
        text.len()
    };
    let bytes = text.as_bytes();
    let mut i = 1;
    while i < inner_end {
        let c = text[i..].chars().next().unwrap_or('\0');
        if c != '$' {
            out.push(c);
            i += c.len_utf8();
            continue;
        }
        let e = bytes.get(i + 1).copied().unwrap_or(0);
        let simple = match e.to_ascii_uppercase() {
            b'$' => Some('$'),
            b'\'' => Some('\''),
            b'"' => Some('"'),
            b'L' | b'N' => Some('\n'),
            b'P' => Some('\u{0C}'),
            b'R' => Some('\r'),
            b'T' => Some('\t'),
            _ => None,
        };
        if let Some(ch) = simple {
            out.push(ch);
            i += 2;
            continue;
        }
        let n = if wide { 4 } else { 2 };
        let hex = text.get(i + 1..(i + 1 + n).min(inner_end)).unwrap_or("");
        if hex.len() == n && hex.bytes().all(|b| b.is_ascii_hexdigit()) {
            let v = u32::from_str_radix(hex, 16).unwrap_or(0);
            // In a STRING `$hh` is a byte, so the character it stands for is
            // the byte's Windows-1252 character (`$80` is `€`).
            let ch = if wide {
                char::from_u32(v)
            } else {
                Some(cp1252_decode(v as u8))
            };
            match ch {
                Some(ch) => out.push(ch),
                None => errors.push((i, i + 1 + n, format!("`${hex}` is not a character"))),
            }
            i += 1 + n;
        } else {
            let shown: String = text[i + 1..inner_end.max(i + 1)].chars().take(1).collect();
            let len = 1 + shown.len();
            let expect = if wide { "four" } else { "two" };
            errors.push((
                i,
                i + len,
                format!(
                    "invalid escape `${shown}`: use $$, $', $\", $L, $N, $P, $R, $T or $ and {expect} hex digits"
                ),
            ));
            i += len;
        }
    }
    (out, errors)
}

/// Where a direct address lives.
#[derive(Clone, Copy, PartialEq, Eq, Debug, Hash)]
pub enum AddrArea {
    Input,
    Output,
    Memory,
}

/// The size prefix of a direct address.
#[derive(Clone, Copy, PartialEq, Eq, Debug, Hash, PartialOrd, Ord)]
pub enum AddrSize {
    /// `X`, or no size prefix.
    Bit,
    Byte,
    Word,
    Dword,
    Lword,
}

impl AddrSize {
    pub fn bits(self) -> u32 {
        match self {
            AddrSize::Bit => 1,
            AddrSize::Byte => 8,
            AddrSize::Word => 16,
            AddrSize::Dword => 32,
            AddrSize::Lword => 64,
        }
    }

    pub fn letter(self) -> char {
        match self {
            AddrSize::Bit => 'X',
            AddrSize::Byte => 'B',
            AddrSize::Word => 'W',
            AddrSize::Dword => 'D',
            AddrSize::Lword => 'L',
        }
    }

    fn from_letter(c: u8) -> Option<AddrSize> {
        Some(match c.to_ascii_uppercase() {
            b'X' => AddrSize::Bit,
            b'B' => AddrSize::Byte,
            b'W' => AddrSize::Word,
            b'D' => AddrSize::Dword,
            b'L' => AddrSize::Lword,
            _ => return None,
        })
    }
}

/// A decoded direct address such as `%IX1.2` (or `%I*`).
#[derive(Clone, PartialEq, Eq, Debug, Hash)]
pub struct DirectAddress {
    pub area: AddrArea,
    pub size: AddrSize,
    /// Whether the size letter was written (`%IX0` vs `%I0`).
    pub explicit_size: bool,
    /// The numbers of a hierarchical address; empty for `%I*`.
    pub path: Vec<u32>,
}

impl DirectAddress {
    pub fn is_incomplete(&self) -> bool {
        self.path.is_empty()
    }
}

impl std::fmt::Display for DirectAddress {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let area = match self.area {
            AddrArea::Input => 'I',
            AddrArea::Output => 'Q',
            AddrArea::Memory => 'M',
        };
        write!(f, "%{area}")?;
        if self.explicit_size {
            write!(f, "{}", self.size.letter())?;
        }
        if self.path.is_empty() {
            return write!(f, "*");
        }
        for (i, n) in self.path.iter().enumerate() {
            if i > 0 {
                write!(f, ".")?;
            }
            write!(f, "{n}")?;
        }
        Ok(())
    }
}

fn address_path(s: &str, text: &str) -> Result<Vec<u32>, LitError> {
    let bad = || LitError {
        code: Code::E0010,
        message: format!(
            "invalid direct address `{text}`: expected numbers separated by dots, as in %IX0.1"
        ),
    };
    if s.is_empty() {
        return Err(bad());
    }
    s.split('.')
        .map(|n| {
            if n.is_empty() || !n.bytes().all(|b| b.is_ascii_digit()) {
                return Err(bad());
            }
            n.parse::<u32>().map_err(|_| bad())
        })
        .collect()
}

/// `%IX1.2`, `%QW4`, `%MD12`, `%I*`.
pub fn parse_address(text: &str) -> Result<DirectAddress, LitError> {
    let b = text.as_bytes();
    let area = match b.get(1).map(|c| c.to_ascii_uppercase()) {
        Some(b'I') => AddrArea::Input,
        Some(b'Q') => AddrArea::Output,
        Some(b'M') => AddrArea::Memory,
        _ => {
            return err(
                Code::E0010,
                format!("invalid direct address `{text}`: the location must be I, Q or M"),
            )
        }
    };
    let (size, explicit_size, rest) = match b.get(2).and_then(|&c| AddrSize::from_letter(c)) {
        Some(s) => (s, true, &text[3..]),
        None => (AddrSize::Bit, false, &text[2..]),
    };
    let path = if rest == "*" {
        Vec::new()
    } else {
        address_path(rest, text)?
    };
    Ok(DirectAddress {
        area,
        size,
        explicit_size,
        path,
    })
}

/// `%X3` (after a dot): the size and the index of the part.
pub fn parse_partial_access(text: &str) -> Result<(AddrSize, u32), LitError> {
    let bad = || LitError {
        code: Code::E0010,
        message: format!("invalid partial access `{text}`: expected %X, %B, %W or %D and a number"),
    };
    let size = text
        .as_bytes()
        .get(1)
        .and_then(|&c| AddrSize::from_letter(c))
        .ok_or_else(bad)?;
    let n = &text[2..];
    if n.is_empty() || !n.bytes().all(|b| b.is_ascii_digit()) {
        return Err(bad());
    }
    Ok((size, n.parse().map_err(|_| bad())?))
}

/// Canonical duration text: `T#1d2h3m4s5ms6us7ns`, largest units first, no
/// zero units, `T#0s` for zero, `T#-2s` when negative (spec/cli.md).
pub fn format_duration(ns: i64, long: bool) -> String {
    let mut out = String::from(if long { "LTIME#" } else { "T#" });
    let mut v = ns as i128;
    if v < 0 {
        out.push('-');
        v = -v;
    }
    if v == 0 {
        out.push_str("0s");
        return out;
    }
    for (unit, size) in [
        ("d", NS_PER_D),
        ("h", NS_PER_H),
        ("m", NS_PER_M),
        ("s", NS_PER_S),
        ("ms", NS_PER_MS),
        ("us", NS_PER_US),
        ("ns", 1),
    ] {
        let n = v / size;
        if n > 0 {
            out.push_str(&n.to_string());
            out.push_str(unit);
            v -= n * size;
        }
    }
    out
}

fn format_fraction(out: &mut String, ns: u64) {
    if ns > 0 {
        let s = format!("{ns:09}");
        out.push('.');
        out.push_str(s.trim_end_matches('0'));
    }
}

/// `D#2024-01-31` from seconds since the epoch (whole days).
pub fn format_date(secs: i64, long: bool) -> String {
    let (y, m, d) = civil_from_days(secs.div_euclid(86_400));
    format!("{}#{y:04}-{m:02}-{d:02}", if long { "LDATE" } else { "D" })
}

fn tod_text(ns: u64) -> String {
    let ns = ns % (NS_PER_D as u64);
    let h = ns / NS_PER_H as u64;
    let m = ns / NS_PER_M as u64 % 60;
    let s = ns / NS_PER_S as u64 % 60;
    let mut out = format!("{h:02}:{m:02}:{s:02}");
    format_fraction(&mut out, ns % NS_PER_S as u64);
    out
}

/// `TOD#12:30:00` (with `.fraction` when not zero).
pub fn format_tod(ns: u64, long: bool) -> String {
    format!("{}#{}", if long { "LTOD" } else { "TOD" }, tod_text(ns))
}

/// `DT#2024-01-31-12:30:00` from nanoseconds since the epoch.
pub fn format_dt(ns: i64, long: bool) -> String {
    let days = ns.div_euclid(NS_PER_D as i64);
    let rest = ns.rem_euclid(NS_PER_D as i64) as u64;
    let (y, m, d) = civil_from_days(days);
    format!(
        "{}#{y:04}-{m:02}-{d:02}-{}",
        if long { "LDT" } else { "DT" },
        tod_text(rest)
    )
}

/// A REAL/LREAL value as literal text that reads back to the same value
/// (always with a `.`; exponent in `E` form): [`crate::real::text`] of the
/// value as an f64.
pub fn format_real(v: f64) -> String {
    crate::real::text(v, false)
}

/// A string as an ST literal with escapes (`'it$'s'`).
pub fn format_string(s: &str, wide: bool) -> String {
    let quote = if wide { '"' } else { '\'' };
    let mut out = String::with_capacity(s.len() + 2);
    out.push(quote);
    for c in s.chars() {
        match c {
            '$' => out.push_str("$$"),
            '\n' => out.push_str("$N"),
            '\r' => out.push_str("$R"),
            '\t' => out.push_str("$T"),
            '\u{0C}' => out.push_str("$P"),
            c if c == quote => {
                out.push('$');
                out.push(c);
            }
            c if (c as u32) < 0x20 || c as u32 == 0x7F => {
                if wide {
                    out.push_str(&format!("${:04X}", c as u32));
                } else {
                    out.push_str(&format!("${:02X}", c as u32));
                }
            }
            c => out.push(c),
        }
    }
    out.push(quote);
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn windows_1252_round_trips_every_byte() {
        for b in 0..=255u8 {
            assert_eq!(cp1252_encode(cp1252_decode(b)), Some(b), "{b:#x}");
        }
        assert_eq!(cp1252_decode(0x80), '€');
        assert_eq!(cp1252_decode(0xE9), 'é');
        assert_eq!(cp1252_encode('€'), Some(0x80));
        assert_eq!(cp1252_encode('Ÿ'), Some(0x9F));
        assert_eq!(cp1252_encode('\u{80}'), None);
        assert_eq!(cp1252_encode('Ω'), None);
        // `$80` in a STRING is the byte 0x80, the euro sign.
        assert_eq!(decode_string("'$80$41'", false).0, "€A");
        assert_eq!(decode_string("\"$0080\"", true).0, "\u{80}");
    }

    #[test]
    fn integers_in_every_base() {
        assert_eq!(parse_int("1_000"), Ok(1000));
        assert_eq!(parse_based_int("16#FF"), Ok(255));
        assert_eq!(parse_based_int("2#1010_1010"), Ok(170));
        assert_eq!(parse_based_int("8#777"), Ok(511));
        assert_eq!(parse_int("18446744073709551615"), Ok(u64::MAX));
        assert_eq!(
            parse_int("18446744073709551616").unwrap_err().code,
            Code::E0007
        );
        assert_eq!(parse_int(&"9".repeat(400)).unwrap_err().code, Code::E0007);
        assert_eq!(parse_based_int("16#FG").unwrap_err().code, Code::E0006);
        assert_eq!(parse_based_int("2#102").unwrap_err().code, Code::E0006);
        assert_eq!(parse_based_int("3#1").unwrap_err().code, Code::E0006);
        assert_eq!(parse_based_int("16#").unwrap_err().code, Code::E0006);
        assert_eq!(parse_int("12abc").unwrap_err().code, Code::E0006);
        assert_eq!(parse_int("1__0").unwrap_err().code, Code::E0006);
    }

    #[test]
    fn reals() {
        assert_eq!(parse_real("1.5E3"), Ok(1500.0));
        assert_eq!(parse_real("2.5e-4"), Ok(0.00025));
        assert_eq!(parse_real("1_000.5"), Ok(1000.5));
        assert_eq!(parse_real("1.0E400").unwrap_err().code, Code::E0007);
    }

    #[test]
    fn durations() {
        assert_eq!(
            parse_duration("T#1h2m3s"),
            Ok((3600 + 120 + 3) * 1_000_000_000)
        );
        assert_eq!(parse_duration("t#1.5s"), Ok(1_500_000_000));
        assert_eq!(parse_duration("TIME#1d_2h"), Ok(26 * 3600 * 1_000_000_000));
        assert_eq!(parse_duration("T#-250ms"), Ok(-250_000_000));
        assert_eq!(parse_duration("T#25h"), Ok(25 * 3600 * 1_000_000_000));
        assert_eq!(parse_duration("LTIME#1us2ns"), Ok(1002));
        assert_eq!(parse_duration("T#0s"), Ok(0));
        assert_eq!(parse_duration("T#5x").unwrap_err().code, Code::E0008);
        assert_eq!(parse_duration("T#1s1h").unwrap_err().code, Code::E0008);
        assert_eq!(parse_duration("T#1.5s3ms").unwrap_err().code, Code::E0008);
        assert_eq!(parse_duration("T#1h75m").unwrap_err().code, Code::E0008);
        assert_eq!(
            parse_duration("T#99999999999d").unwrap_err().code,
            Code::E0007
        );
        assert_eq!(parse_duration("T#").unwrap_err().code, Code::E0008);
    }

    #[test]
    fn dates_and_times() {
        assert_eq!(parse_date("D#1970-01-02"), Ok(86_400));
        assert_eq!(
            parse_date("DATE#2024-02-29").map(|s| format_date(s, false)),
            Ok("D#2024-02-29".into())
        );
        assert_eq!(parse_date("D#2023-02-29").unwrap_err().code, Code::E0008);
        assert_eq!(parse_date("D#2024-13-01").unwrap_err().code, Code::E0008);
        assert_eq!(
            parse_tod("TOD#12:30:00.5"),
            Ok((12 * 3600 + 30 * 60) * 1_000_000_000 + 500_000_000)
        );
        assert_eq!(parse_tod("TOD#25:00:00").unwrap_err().code, Code::E0008);
        assert_eq!(parse_tod("TOD#09:30").unwrap_err().code, Code::E0008);
        assert_eq!(
            parse_tod(&with_zero_seconds("TOD#09:30")),
            parse_tod("TOD#09:30:00")
        );
        assert_eq!(
            parse_dt(&with_zero_seconds("DT#2024-01-31-9:30")),
            parse_dt("DT#2024-01-31-09:30:00")
        );
        assert!(lacks_seconds("TIME_OF_DAY#9:00") && lacks_seconds("DT#2024-01-31-09:00"));
        assert!(!lacks_seconds("TOD#09:00:00") && !lacks_seconds("DT#2024-01-31-09:00:00"));
        assert!(parse_tod("TOD#09").is_err() && parse_tod("TOD#09:00.5").is_err());
        let dt = parse_dt("DT#2024-01-31-12:30:00").unwrap();
        assert_eq!(format_dt(dt, false), "DT#2024-01-31-12:30:00");
        assert_eq!(
            format_tod(parse_tod("TOD#01:02:03.25").unwrap(), false),
            "TOD#01:02:03.25"
        );
        for days in [-800_000i64, -1, 0, 1, 59, 60, 11_016, 2_932_896] {
            let (y, m, d) = civil_from_days(days);
            assert_eq!(days_from_civil(y, m, d), days);
        }
    }

    #[test]
    fn canonical_duration_text() {
        assert_eq!(format_duration(0, false), "T#0s");
        assert_eq!(format_duration(90_500_000_000, false), "T#1m30s500ms");
        assert_eq!(format_duration(-2_000_000_000, false), "T#-2s");
        assert_eq!(
            format_duration(i64::MIN, true),
            "LTIME#-106751d23h47m16s854ms775us808ns"
        );
    }

    #[test]
    fn strings_and_escapes() {
        assert_eq!(
            decode_string("'a$'b$$c$N$t$41'", false),
            ("a'b$c\n\tA".into(), vec![])
        );
        assert_eq!(decode_string("\"$0041$\"\"", true).0, "A\"");
        let (_, errs) = decode_string("'abc$Q'", false);
        assert_eq!(errs.len(), 1);
        assert_eq!((errs[0].0, errs[0].1), (4, 6));
        assert_eq!(format_string("it's $5\n", false), "'it$'s $$5$N'");
        assert_eq!(
            decode_string(&format_string("x'y\"$\u{1}", false), false).0,
            "x'y\"$\u{1}"
        );
    }

    #[test]
    fn addresses() {
        let a = parse_address("%IX1.2.3").unwrap();
        assert_eq!(
            (a.area, a.size, a.path.clone()),
            (AddrArea::Input, AddrSize::Bit, vec![1, 2, 3])
        );
        assert_eq!(a.to_string(), "%IX1.2.3");
        assert_eq!(parse_address("%QW4").unwrap().size, AddrSize::Word);
        assert!(parse_address("%I*").unwrap().is_incomplete());
        assert_eq!(parse_address("%IX").unwrap_err().code, Code::E0010);
        assert_eq!(parse_address("%Z1").unwrap_err().code, Code::E0010);
        assert_eq!(parse_partial_access("%X3"), Ok((AddrSize::Bit, 3)));
    }

    #[test]
    fn reals_print_back_exactly() {
        for v in [1.0, 0.1, 1e-10, 1.5e20, -2.5, 123456.789] {
            let s = format_real(v);
            assert!(s.contains('.'), "{s}");
            assert_eq!(parse_real(&s), Ok(v));
        }
    }
}
