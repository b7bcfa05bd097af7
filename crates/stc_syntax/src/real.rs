//! The text of REAL and LREAL values (docs/semantics-notes.md, "Text of
//! REAL and LREAL values"): the shortest decimal digits that read back to
//! the same value, laid out in one of two forms.
//!
//! - [`text`]: ST literal form, used by the text report, `TO_STRING`-like
//!   conversions and diagnostics: fixed notation for `1e-4 <= |x| < 1e16`
//!   (`0.001`, `100.0`, always a `.` and at least one digit after it),
//!   otherwise `d.dddE±n` (`1.0E-7`, `1.5E16`, a `-` sign only).
//! - [`json`]: the JSON report's number form: fixed notation for decimal
//!   exponents -5..=15 (LREAL) or -6..=12 (REAL), otherwise `d.ddde+n` /
//!   `de-n` (no `.0` on a one-digit mantissa, an explicit `+`).
//!
//! The digits come from Rust's `{:e}` formatting, which the standard library
//! guarantees to be the shortest that reads back to the same value, and,
//! among the shortest, the closest (an exact tie takes the upper one). The
//! JSON form breaks exact ties to the even digit instead.

/// The shortest decimal digits of a finite value: `x = ±d1.d2d3... *
/// 10^exp`, with no trailing zero (`"0"`, exponent 0, for zero).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Digits {
    pub negative: bool,
    /// ASCII digits, the first non-zero (except for zero).
    pub digits: String,
    pub exp: i32,
}

/// How a tie between two shortest candidates is broken.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Ties {
    /// The one above (Rust's `{:e}` and `{:?}`).
    Up,
    /// The one whose last digit is even.
    Even,
}

/// The shortest digits of a finite `x`, as an f32 (`single`) or an f64.
pub fn shortest(x: f64, single: bool, ties: Ties) -> Digits {
    let s = if single {
        format!("{:e}", x as f32)
    } else {
        format!("{x:e}")
    };
    let (negative, s) = match s.strip_prefix('-') {
        Some(rest) => (true, rest),
        None => (false, s.as_str()),
    };
    let (mantissa, exp) = s.split_once('e').unwrap_or((s, "0"));
    let mut d = Digits {
        negative,
        digits: mantissa.chars().filter(char::is_ascii_digit).collect(),
        exp: exp.parse().unwrap_or(0),
    };
    if ties == Ties::Even {
        to_even(&mut d, x, single);
    }
    d
}

/// At an exact tie between the digits (the upper candidate) and the ones
/// below, takes the even one.
fn to_even(d: &mut Digits, x: f64, single: bool) {
    let Some(last) = d.digits.bytes().last() else {
        return;
    };
    if last % 2 == 0 {
        return;
    }
    let mut below = d.digits.clone();
    below.pop();
    below.push(char::from(last - 1));
    // A tie is x exactly halfway: its expansion to one more digit ends in 5
    // (a cheap test first), and it has no other digit after.
    let one_more = format!("{:.*e}", d.digits.len(), x.abs());
    if one_more
        .split_once('e')
        .is_none_or(|(m, _)| !m.ends_with('5'))
    {
        return;
    }
    // The exact decimal expansion of |x| (finite: x is a dyadic rational).
    let exact = format!("{:.1100e}", x.abs());
    let (m, e) = exact.split_once('e').unwrap_or((&exact, "0"));
    if e.parse::<i32>().ok() != Some(d.exp) {
        return;
    }
    let exact_digits: String = m.chars().filter(char::is_ascii_digit).collect();
    let mid = format!("{below}5");
    let tie =
        exact_digits.starts_with(&mid) && exact_digits[mid.len()..].bytes().all(|b| b == b'0');
    if !tie {
        return;
    }
    let text = format!("{below}e{}", d.exp + 1 - below.len() as i32);
    let reads_back = if single {
        text.parse::<f32>().is_ok_and(|y| y == x.abs() as f32)
    } else {
        text.parse::<f64>().is_ok_and(|y| y == x.abs())
    };
    if reads_back {
        d.digits = below;
    }
}

/// Fixed notation of `d1.d2... * 10^exp` (always a `.` and a digit after it).
fn fixed(out: &mut String, digits: &str, exp: i32) {
    if exp >= 0 {
        let int_digits = exp as usize + 1;
        for i in 0..int_digits {
            out.push(char::from(*digits.as_bytes().get(i).unwrap_or(&b'0')));
        }
        out.push('.');
        match digits.get(int_digits..) {
            Some(rest) if !rest.is_empty() => out.push_str(rest),
            _ => out.push('0'),
        }
    } else {
        out.push_str("0.");
        for _ in 1..-exp {
            out.push('0');
        }
        out.push_str(digits);
    }
}

/// The ST literal form (see the module documentation). NaN is `NaN`, the
/// infinities `inf` and `-inf` (as Rust prints them; reports print `INF`).
pub fn text(x: f64, single: bool) -> String {
    if x.is_nan() {
        return "NaN".into();
    }
    if x.is_infinite() {
        return if x > 0.0 { "inf" } else { "-inf" }.into();
    }
    let d = shortest(x, single, Ties::Up);
    let mut out = String::new();
    if d.negative {
        out.push('-');
    }
    if x == 0.0 {
        out.push_str("0.0");
    } else if (-4..=15).contains(&d.exp) {
        fixed(&mut out, &d.digits, d.exp);
    } else {
        out.push_str(&d.digits[..1]);
        out.push('.');
        match &d.digits[1..] {
            "" => out.push('0'),
            rest => out.push_str(rest),
        }
        out.push('E');
        out.push_str(&d.exp.to_string());
    }
    out
}

/// The JSON report's form (see the module documentation): a JSON number,
/// or the strings `"NaN"`, `"INF"`, `"-INF"`.
pub fn json(x: f64, single: bool) -> String {
    if x.is_nan() {
        return "\"NaN\"".into();
    }
    if x.is_infinite() {
        return if x > 0.0 { "\"INF\"" } else { "\"-INF\"" }.into();
    }
    let d = shortest(x, single, Ties::Even);
    let mut out = String::new();
    if d.negative {
        out.push('-');
    }
    let (lo, hi) = if single { (-6, 12) } else { (-5, 15) };
    if x == 0.0 {
        out.push_str("0.0");
    } else if (lo..=hi).contains(&d.exp) {
        fixed(&mut out, &d.digits, d.exp);
    } else {
        out.push_str(&d.digits[..1]);
        if d.digits.len() > 1 {
            out.push('.');
            out.push_str(&d.digits[1..]);
        }
        out.push('e');
        out.push(if d.exp < 0 { '-' } else { '+' });
        out.push_str(&d.exp.unsigned_abs().to_string());
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn forms() {
        assert_eq!(text(1.0, false), "1.0");
        assert_eq!(text(100.0, false), "100.0");
        assert_eq!(text(0.001, false), "0.001");
        assert_eq!(text(1e-7, false), "1.0E-7");
        assert_eq!(text(1.5e16, false), "1.5E16");
        assert_eq!(text(-0.0, false), "-0.0");
        assert_eq!(text(0.1f32 as f64, true), "0.1");
        assert_eq!(text(0.1f32 as f64, false), "0.10000000149011612");
        assert_eq!(json(1e-7, false), "1e-7");
        assert_eq!(json(1.5e16, false), "1.5e+16");
        assert_eq!(json(1e15, false), "1000000000000000.0");
        assert_eq!(json(0.00001, false), "0.00001");
        assert_eq!(json(-0.0, false), "-0.0");
        assert_eq!(json(f64::NEG_INFINITY, true), "\"-INF\"");
    }
}
