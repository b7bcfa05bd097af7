//! Type conversions: every `*_TO_*` of the standard, TRUNC, and the BCD
//! conversions (spec/semantics.md "Arithmetic"; the decisions the spec leaves
//! open are in docs/semantics-notes.md, "Conversions").
//!
//! The rules in one place:
//! - integers, bit strings and characters between themselves keep the
//!   low-order bits, as a C cast does; to BOOL is `<> 0`, from BOOL 0/1;
//! - integer and bit-string types to REAL/LREAL round to nearest (ties to
//!   even), a bit string read as an unsigned integer; REAL/LREAL to an
//!   integer or bit-string type rounds to nearest, ties to even, and faults
//!   on NaN or out of range; TRUNC truncates toward zero with the same
//!   faults;
//! - TIME counts milliseconds, LTIME nanoseconds; DATE and DT count seconds,
//!   TOD milliseconds; LDATE, LTOD and LDT nanoseconds;
//! - to STRING/WSTRING is [`to_text`]; from them is [`parse_value`]; a
//!   STRING's bytes are Windows-1252 characters.

use crate::text::{parse_value, string_text, to_text};
use crate::types::{
    bits, int_range, is_bit_string, is_char, is_date, is_dt, is_duration, is_int_like, is_integer,
    is_real, is_string, is_tod, wrap,
};
use crate::{misuse, Fault, Value};
use stc_syntax::literal::{cp1252_decode, cp1252_encode};
use stc_syntax::literal::{NS_PER_D, NS_PER_MS, NS_PER_S};
use stc_syntax::token::ElemType;

use ElemType as E;

const SECS_PER_DAY: i128 = 86_400;

/// The categories conversions are defined between.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
enum Cat {
    Bool,
    /// ANY_INT and BYTE..LWORD.
    Int,
    Real,
    Dur,
    Date,
    Tod,
    Dt,
    Str,
    Char,
}

fn cat(t: ElemType) -> Cat {
    match t {
        E::Bool => Cat::Bool,
        _ if is_int_like(t) => Cat::Int,
        _ if is_real(t) => Cat::Real,
        _ if is_duration(t) => Cat::Dur,
        _ if is_date(t) => Cat::Date,
        _ if is_tod(t) => Cat::Tod,
        _ if is_dt(t) => Cat::Dt,
        _ if is_string(t) => Cat::Str,
        _ => Cat::Char,
    }
}

/// Whether [`convert`] from `from` to `to` can fault for some value (a
/// refused pair counts as faulting): what a back end needs to know to leave
/// out a check. Sound by test: every conversion that faults on a value has
/// this true (`conversion_may_fault_is_sound`).
pub fn conversion_may_fault(from: ElemType, to: ElemType) -> bool {
    if from == to {
        return false;
    }
    if !conversion_allowed(from, to) {
        return true;
    }
    let (cf, ct) = (cat(from), cat(to));
    match (cf, ct) {
        // To a string: a WSTRING or a WCHAR may have no STRING character.
        (_, Cat::Str) => matches!(from, E::Wstring | E::Wchar),
        // From a string: parsed (CHAR and WCHAR take the first character).
        (Cat::Str, _) => !(from == E::String && matches!(to, E::Char | E::Wchar)),
        (Cat::Real, Cat::Int | Cat::Dur) => true,
        (Cat::Char, Cat::Char) => to == E::Char,
        (Cat::Date, Cat::Dt) => true,
        (Cat::Real, Cat::Real) | (Cat::Int | Cat::Bool, Cat::Real) => false,
        (Cat::Real, Cat::Bool) => false,
        (Cat::Bool | Cat::Int, Cat::Bool) => false,
        (Cat::Bool | Cat::Int | Cat::Char, Cat::Int | Cat::Char) => false,
        (Cat::Dur, Cat::Dur | Cat::Int | Cat::Real | Cat::Tod) => false,
        (Cat::Int, Cat::Dur) => false,
        (Cat::Tod, Cat::Dur) => false,
        (Cat::Date | Cat::Tod | Cat::Dt, Cat::Int) | (Cat::Int, Cat::Date | Cat::Tod | Cat::Dt) => {
            false
        }
        (Cat::Date, Cat::Date) | (Cat::Tod, Cat::Tod) | (Cat::Dt, Cat::Dt) => false,
        (Cat::Dt, Cat::Date | Cat::Tod) => false,
        _ => true,
    }
}

/// Whether `FROM_TO_TO` is a conversion this implementation provides (and
/// so whether the generic `TO_*` accepts an argument of type `from`).
/// Identity (`from == to`) is allowed.
pub fn conversion_allowed(from: ElemType, to: ElemType) -> bool {
    use Cat::*;
    if from == to {
        return true;
    }
    match (cat(from), cat(to)) {
        (Str, _) | (_, Str) => true,
        (Bool | Int, Bool | Int) => true,
        // Bit strings convert to and from reals numerically, as integers
        // (ed2 table 22 defines every pair; real code relies on it).
        (Int, Real) | (Real, Int) | (Real, Real) => true,
        (Dur, Int | Real | Dur | Tod) | (Int | Real, Dur) => true,
        (Date | Tod | Dt, Int) | (Int, Date | Tod | Dt) => true,
        (Date, Date) | (Tod, Tod) | (Dt, Dt) => true,
        (Dt, Date | Tod) | (Date, Dt) | (Tod, Dur) => true,
        (Char, Int | Char) | (Int, Char) => true,
        // Not in the standard, but in MatIEC, Beremiz and CODESYS
        // ([`conversion_is_extension`]).
        (Bool, Real) | (Real, Bool) => true,
        _ => false,
    }
}

/// Whether `FROM_TO_TO` is one of the conversions stc provides beyond the
/// standard's (BOOL_TO_REAL, BOOL_TO_LREAL, REAL_TO_BOOL, LREAL_TO_BOOL):
/// the analyser warns about them (W0112).
pub fn conversion_is_extension(from: ElemType, to: ElemType) -> bool {
    matches!(
        (cat(from), cat(to)),
        (Cat::Bool, Cat::Real) | (Cat::Real, Cat::Bool)
    )
}

/// Explicit or implicit conversion of `v` from type `from` to type `to`
/// (every `*_TO_*` of the standard). A pair [`conversion_allowed`] rejects
/// answers `Err(Fault::Conversion)`.
pub fn convert(from: ElemType, to: ElemType, v: &Value) -> Result<Value, Fault> {
    use Cat::*;
    if !conversion_allowed(from, to) {
        return misuse();
    }
    match (cat(from), cat(to)) {
        (_, Str) => to_string_value(from, to, v),
        (Str, _) => from_string_value(from, to, v),
        (Real, Real) => {
            let x = real(v)?;
            Ok(Value::Real(round_to(to, x)))
        }
        (Real, Int) => real_to_int(to, real(v)?, f64::round_ties_even),
        (Int, Real) => Ok(Value::Real(int_to_real(to, int(v)?))),
        // BOOL is 0 or 1; a real is TRUE when it is not zero (NaN too).
        (Bool, Real) => Ok(Value::Real(if int(v)? != 0 { 1.0 } else { 0.0 })),
        (Real, Bool) => Ok(Value::Bool(real(v)? != 0.0)),
        (Bool | Int, Bool) => Ok(Value::Bool(int(v)? != 0)),
        (Char, Char) => {
            let c = int(v)?;
            match int_range(to) {
                Some((lo, hi)) if (lo..=hi).contains(&c) => Ok(Value::Int(c)),
                _ => Err(Fault::Conversion),
            }
        }
        (Bool | Int | Char, Int | Char) => Ok(Value::Int(wrap(to, int(v)?))),
        // Durations.
        (Dur, Dur) => Ok(Value::Int(wrap(to, int(v)?))),
        (Dur, Int) => {
            let ns = int(v)?;
            let n = if from == E::Time { ns / NS_PER_MS } else { ns };
            Ok(Value::Int(wrap(to, n)))
        }
        (Int, Dur) => {
            let n = int(v)?;
            let ns = if to == E::Time {
                n.wrapping_mul(NS_PER_MS)
            } else {
                n
            };
            Ok(Value::Int(wrap(to, ns)))
        }
        (Dur, Real) => {
            let ns = int(v)?;
            Ok(Value::Real(if from == E::Time {
                round_to(to, ns as f64 / NS_PER_MS as f64)
            } else {
                int_to_real(to, ns)
            }))
        }
        (Real, Dur) => {
            let x = real(v)?;
            let ns = if to == E::Time {
                x * NS_PER_MS as f64
            } else {
                x
            };
            f64_to_ns(ns).map(Value::Int)
        }
        (Dur, Tod) => Ok(Value::Int(int(v)?.rem_euclid(NS_PER_D))),
        (Tod, Dur) => Ok(Value::Int(int(v)?)),
        // Dates and times of day against integers.
        (Date, Int) => {
            let secs = int(v)?;
            let n = if from == E::Date {
                secs
            } else {
                secs.wrapping_mul(NS_PER_S)
            };
            Ok(Value::Int(wrap(to, n)))
        }
        (Int, Date) => {
            let n = int(v)?;
            let secs = if to == E::Date {
                n
            } else {
                n.div_euclid(NS_PER_S)
            };
            Ok(Value::Int(date_from_secs(secs)))
        }
        (Tod, Int) => {
            let ns = int(v)?;
            let n = if from == E::Tod { ns / NS_PER_MS } else { ns };
            Ok(Value::Int(wrap(to, n)))
        }
        (Int, Tod) => {
            let n = int(v)?;
            let ns = if to == E::Tod {
                n.wrapping_mul(NS_PER_MS)
            } else {
                n
            };
            Ok(Value::Int(ns.rem_euclid(NS_PER_D)))
        }
        (Dt, Int) => {
            let ns = int(v)?;
            let n = if from == E::Dt {
                ns.div_euclid(NS_PER_S)
            } else {
                ns
            };
            Ok(Value::Int(wrap(to, n)))
        }
        (Int, Dt) => {
            let n = int(v)?;
            let ns = if to == E::Dt {
                n.wrapping_mul(NS_PER_S)
            } else {
                n
            };
            Ok(Value::Int(wrap(to, ns)))
        }
        // Between time-like types.
        (Date, Date) | (Tod, Tod) | (Dt, Dt) => Ok(Value::Int(int(v)?)),
        (Dt, Date) => Ok(Value::Int(int(v)?.div_euclid(NS_PER_D) * SECS_PER_DAY)),
        (Dt, Tod) => Ok(Value::Int(int(v)?.rem_euclid(NS_PER_D))),
        (Date, Dt) => {
            let ns = int(v)?.checked_mul(NS_PER_S).ok_or(Fault::Conversion)?;
            in_i64(ns).map(Value::Int)
        }
        _ => misuse(),
    }
}

/// TRUNC: REAL/LREAL to an integer type, toward zero. NaN or a value
/// outside `to`'s range is a conversion fault.
pub fn trunc(from: ElemType, to: ElemType, v: &Value) -> Result<Value, Fault> {
    if !is_real(from) || !is_int_like(to) {
        return misuse();
    }
    real_to_int(to, real(v)?, f64::trunc)
}

/// `*_BCD_TO_*`: the decimal number a bit string holds in BCD
/// (`WORD#16#1234` is 1234). A nibble above 9, or a number outside `to`'s
/// range, is a conversion fault.
pub fn bcd_to_int(from: ElemType, to: ElemType, v: &Value) -> Result<Value, Fault> {
    if !is_bit_string(from) || !is_integer(to) {
        return misuse();
    }
    let mut pattern = int(v)?;
    if pattern < 0 {
        return misuse();
    }
    let mut value: i128 = 0;
    let mut scale: i128 = 1;
    while pattern > 0 {
        let digit = pattern & 0xF;
        if digit > 9 {
            return Err(Fault::Conversion);
        }
        value += digit * scale;
        scale = scale.saturating_mul(10);
        pattern >>= 4;
    }
    match int_range(to) {
        Some((lo, hi)) if (lo..=hi).contains(&value) => Ok(Value::Int(value)),
        _ => Err(Fault::Conversion),
    }
}

/// `*_TO_BCD_*`: an unsigned number as BCD in a bit string (25 becomes
/// `2#0010_0101`). A negative number, or one with more decimal digits than
/// `to` has nibbles, is a conversion fault.
pub fn int_to_bcd(from: ElemType, to: ElemType, v: &Value) -> Result<Value, Fault> {
    if !is_integer(from) || !is_bit_string(to) {
        return misuse();
    }
    let mut n = int(v)?;
    if n < 0 {
        return Err(Fault::Conversion);
    }
    let nibbles = bits(to).div_ceil(4);
    let mut pattern: i128 = 0;
    let mut shift = 0u32;
    while n > 0 {
        if shift / 4 >= nibbles {
            return Err(Fault::Conversion);
        }
        pattern |= (n % 10) << shift;
        n /= 10;
        shift += 4;
    }
    match int_range(to) {
        Some((_, hi)) if pattern <= hi => Ok(Value::Int(pattern)),
        _ => Err(Fault::Conversion),
    }
}

pub(crate) fn int(v: &Value) -> Result<i128, Fault> {
    v.as_int().ok_or(Fault::Conversion)
}

pub(crate) fn real(v: &Value) -> Result<f64, Fault> {
    v.as_real().ok_or(Fault::Conversion)
}

/// Rounds an f64 to the precision of a real type (REAL: nearest f32).
pub(crate) fn round_to(t: ElemType, x: f64) -> f64 {
    if t == E::Real {
        x as f32 as f64
    } else {
        x
    }
}

/// An integer to REAL (rounded once, to nearest f32) or LREAL.
fn int_to_real(t: ElemType, n: i128) -> f64 {
    if t == E::Real {
        n as f32 as f64
    } else {
        n as f64
    }
}

fn real_to_int(to: ElemType, x: f64, round: fn(f64) -> f64) -> Result<Value, Fault> {
    if x.is_nan() {
        return Err(Fault::Conversion);
    }
    // Saturates far outside every range, so the check below rejects it.
    let n = round(x) as i128;
    match int_range(to) {
        Some((lo, hi)) if (lo..=hi).contains(&n) => Ok(Value::Int(n)),
        _ => Err(Fault::Conversion),
    }
}

/// A real number of nanoseconds, rounded to nearest (ties to even), as a
/// TIME; NaN or outside the i64 range is a conversion fault.
pub(crate) fn f64_to_ns(x: f64) -> Result<i128, Fault> {
    if x.is_nan() {
        return Err(Fault::Conversion);
    }
    in_i64(x.round_ties_even() as i128)
}

fn in_i64(n: i128) -> Result<i128, Fault> {
    if (i64::MIN as i128..=i64::MAX as i128).contains(&n) {
        Ok(n)
    } else {
        Err(Fault::Conversion)
    }
}

/// Seconds to a DATE: the midnight starting that day, kept in the i64 range.
fn date_from_secs(secs: i128) -> i128 {
    let secs = wrap(E::Date, secs);
    let day = secs - secs.rem_euclid(SECS_PER_DAY);
    if day < i64::MIN as i128 {
        day + SECS_PER_DAY
    } else {
        day
    }
}

fn to_string_value(from: ElemType, to: ElemType, v: &Value) -> Result<Value, Fault> {
    let wide = to == E::Wstring;
    match (v, wide) {
        (Value::Str(s), false) => Ok(Value::Str(s.clone())),
        (Value::Str(s), true) => Ok(Value::wstring(&string_text(s))),
        (Value::WStr(w), true) => Ok(Value::WStr(w.clone())),
        (Value::WStr(w), false) => {
            let text = String::from_utf16(w).map_err(|_| Fault::Conversion)?;
            encode_string(&text)
        }
        (Value::Int(c), _) if is_char(from) => {
            let code = u32::try_from(*c).map_err(|_| Fault::Conversion)?;
            let ch = match from {
                E::Char => cp1252_decode(u8::try_from(code).map_err(|_| Fault::Conversion)?),
                _ => char::from_u32(code).ok_or(Fault::Conversion)?,
            };
            if wide {
                u16::try_from(u32::from(ch))
                    .map(|u| Value::WStr(vec![u]))
                    .map_err(|_| Fault::Conversion)
            } else {
                encode_string(&ch.to_string())
            }
        }
        _ => {
            let mut text = to_text(from, v);
            if crate::is_time_like(from) {
                // *_TO_STRING gives the literal without its type prefix
                // (spec/semantics.md): `1s500ms`, not `T#1s500ms`.
                if let Some((_, body)) = text.split_once('#') {
                    text = body.to_string();
                }
            }
            Ok(if wide {
                Value::wstring(&text)
            } else {
                Value::string(&text)
            })
        }
    }
}

/// Text as a STRING: its Windows-1252 bytes; a character Windows-1252 has
/// no byte for is a conversion fault.
fn encode_string(text: &str) -> Result<Value, Fault> {
    text.chars()
        .map(|c| cp1252_encode(c).ok_or(Fault::Conversion))
        .collect::<Result<Vec<u8>, Fault>>()
        .map(Value::Str)
}

fn from_string_value(from: ElemType, to: ElemType, v: &Value) -> Result<Value, Fault> {
    let text = match (from, v) {
        (E::String, Value::Str(s)) => string_text(s),
        (E::Wstring, Value::WStr(w)) => String::from_utf16(w).map_err(|_| Fault::Conversion)?,
        _ => return misuse(),
    };
    parse_value(to, &text)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn conv(from: ElemType, to: ElemType, v: Value) -> Result<Value, Fault> {
        convert(from, to, &v)
    }

    fn i(n: i128) -> Value {
        Value::Int(n)
    }

    fn r(x: f64) -> Value {
        Value::Real(x)
    }

    const MS: i128 = 1_000_000;

    #[test]
    fn integers_keep_low_order_bits() {
        let cases = [
            (E::Int, E::Byte, 300, 44),
            (E::Dint, E::Word, -1, 65535),
            (E::Word, E::Int, 65535, -1),
            (E::Int, E::Sint, 200, -56),
            (E::Sint, E::Usint, -1, 255),
            (E::Lint, E::Dint, 1 << 32, 0),
            (E::Ulint, E::Lint, u64::MAX as i128, -1),
            (E::Lint, E::Ulint, -1, u64::MAX as i128),
            (E::Byte, E::Lword, 255, 255),
            (E::Sint, E::Lword, -1, u64::MAX as i128),
            (E::Udint, E::Dint, 1 << 31, -(1 << 31)),
            (E::Int, E::Char, 321, 65),
            (E::Char, E::Int, 255, 255),
            (E::Wchar, E::Byte, 0x20ac, 0xac),
            (E::Dword, E::Wchar, 0x1_0041, 0x41),
        ];
        for (from, to, a, b) in cases {
            assert_eq!(conv(from, to, i(a)), Ok(i(b)), "{from:?}_TO_{to:?}({a})");
        }
    }

    #[test]
    fn bools() {
        assert_eq!(conv(E::Bool, E::Int, Value::Bool(true)), Ok(i(1)));
        assert_eq!(conv(E::Bool, E::Lword, Value::Bool(false)), Ok(i(0)));
        assert_eq!(conv(E::Int, E::Bool, i(-5)), Ok(Value::Bool(true)));
        assert_eq!(conv(E::Word, E::Bool, i(0)), Ok(Value::Bool(false)));
        assert_eq!(conv(E::Byte, E::Bool, i(256)), Ok(Value::Bool(true)));
        // BOOL to REAL/LREAL and back: not in the standard, accepted as the
        // other tools do (W0112): FALSE/TRUE are 0.0/1.0, a REAL is TRUE
        // when it is not zero.
        assert!(conversion_allowed(E::Bool, E::Real));
        assert!(conversion_allowed(E::Real, E::Bool));
        assert_eq!(
            conv(E::Bool, E::Lreal, Value::Bool(true)),
            Ok(Value::Real(1.0))
        );
        assert!(!conversion_allowed(E::Bool, E::Time));
        assert!(!conversion_allowed(E::Bool, E::Char));
    }

    #[test]
    fn reals_to_integers_round_half_even() {
        let cases = [
            (2.5, Some(2)),
            (3.5, Some(4)),
            (-1.5, Some(-2)),
            (-2.5, Some(-2)),
            (1.6, Some(2)),
            (-1.6, Some(-2)),
            (1.4, Some(1)),
            (-1.4, Some(-1)),
            (0.5, Some(0)),
            (32767.4, Some(32767)),
            (32767.5, None),
            (-32768.5, Some(-32768)),
            (-32768.51, None),
            (f64::NAN, None),
            (f64::INFINITY, None),
            (f64::NEG_INFINITY, None),
            (1e30, None),
        ];
        for (x, want) in cases {
            let got = conv(E::Lreal, E::Int, r(x));
            assert_eq!(
                got,
                want.map(i).ok_or(Fault::Conversion),
                "LREAL_TO_INT({x})"
            );
        }
        assert_eq!(conv(E::Real, E::Usint, r(-0.4)), Ok(i(0)));
        assert_eq!(conv(E::Real, E::Usint, r(-0.6)), Err(Fault::Conversion));
        // 2^63 is just outside LINT although it equals i64::MAX as f64.
        assert_eq!(
            conv(E::Lreal, E::Lint, r(i64::MAX as f64)),
            Err(Fault::Conversion)
        );
        assert_eq!(
            conv(E::Lreal, E::Lint, r(i64::MIN as f64)),
            Ok(i(i64::MIN as i128))
        );
        assert_eq!(
            conv(E::Lreal, E::Ulint, r(18_446_744_073_709_549_568.0)),
            Ok(i(18446744073709549568))
        );
        assert_eq!(
            conv(E::Lreal, E::Ulint, r(u64::MAX as f64)),
            Err(Fault::Conversion)
        );
    }

    #[test]
    fn truncation_toward_zero() {
        let cases = [
            (1.6, Some(1)),
            (-1.6, Some(-1)),
            (1.4, Some(1)),
            (-1.4, Some(-1)),
            (-0.9, Some(0)),
            (127.9, Some(127)),
            (128.0, None),
            (-128.9, Some(-128)),
            (f64::NAN, None),
        ];
        for (x, want) in cases {
            assert_eq!(
                trunc(E::Lreal, E::Sint, &r(x)),
                want.map(i).ok_or(Fault::Conversion),
                "TRUNC({x})"
            );
        }
        assert_eq!(trunc(E::Int, E::Sint, &i(1)), Err(Fault::Conversion));
    }

    #[test]
    fn integers_to_reals_round_once() {
        assert_eq!(conv(E::Dint, E::Real, i(16_777_217)), Ok(r(16_777_216.0)));
        assert_eq!(conv(E::Dint, E::Real, i(16_777_219)), Ok(r(16_777_220.0)));
        assert_eq!(
            conv(E::Lint, E::Lreal, i(9_007_199_254_740_993)),
            Ok(r(9_007_199_254_740_992.0))
        );
        // Directly to f32, not through f64 (which would round twice).
        let n: i128 = (1 << 53) + (1 << 29) + 1;
        assert_eq!(
            conv(E::Lint, E::Real, i(n)),
            Ok(r(((1u64 << 53) + (1 << 30)) as f64))
        );
        assert_eq!(
            conv(E::Ulint, E::Lreal, i(u64::MAX as i128)),
            Ok(r(18446744073709551616.0))
        );
        assert_eq!(conv(E::Int, E::Lreal, i(-3)), Ok(r(-3.0)));
    }

    #[test]
    fn reals_between_precisions() {
        assert_eq!(conv(E::Lreal, E::Real, r(0.1)), Ok(r(0.1f32 as f64)));
        assert_eq!(conv(E::Lreal, E::Real, r(1e300)), Ok(r(f64::INFINITY)));
        assert_eq!(conv(E::Real, E::Lreal, r(0.5)), Ok(r(0.5)));
    }

    #[test]
    fn bit_strings_and_reals_convert_numerically() {
        for (a, b) in [
            (E::Byte, E::Real),
            (E::Word, E::Lreal),
            (E::Dword, E::Real),
            (E::Lword, E::Lreal),
            (E::Real, E::Byte),
            (E::Lreal, E::Lword),
        ] {
            assert!(conversion_allowed(a, b), "{a:?} {b:?}");
        }
        // The bit string read as an unsigned integer.
        assert_eq!(conv(E::Byte, E::Real, i(255)), Ok(r(255.0)));
        assert_eq!(conv(E::Word, E::Real, i(0xFFFF)), Ok(r(65535.0)));
        assert_eq!(
            conv(E::Dword, E::Real, i(0x3F80_0000)),
            Ok(r(1_065_353_216.0))
        );
        assert_eq!(
            conv(E::Dword, E::Real, i(0xFFFF_FFFF)),
            Ok(r(4_294_967_296.0))
        );
        assert_eq!(
            conv(E::Lword, E::Lreal, i(u64::MAX as i128)),
            Ok(r(18_446_744_073_709_551_616.0))
        );
        // Rounded to nearest, ties to even; out of the unsigned range faults.
        assert_eq!(conv(E::Real, E::Word, r(1.0)), Ok(i(1)));
        assert_eq!(conv(E::Real, E::Byte, r(2.5)), Ok(i(2)));
        assert_eq!(conv(E::Lreal, E::Byte, r(3.5)), Ok(i(4)));
        assert_eq!(conv(E::Lreal, E::Byte, r(255.4)), Ok(i(255)));
        assert_eq!(conv(E::Lreal, E::Byte, r(255.5)), Err(Fault::Conversion));
        assert_eq!(conv(E::Real, E::Dword, r(-1.0)), Err(Fault::Conversion));
        assert_eq!(conv(E::Lreal, E::Lword, r(-0.4)), Ok(i(0)));
        assert_eq!(conv(E::Real, E::Word, r(f64::NAN)), Err(Fault::Conversion));
        assert_eq!(conv(E::Real, E::Dword, r(1.0)), Ok(i(1)));
    }

    #[test]
    fn durations() {
        assert_eq!(conv(E::Time, E::Dint, i(1500 * MS)), Ok(i(1500)));
        assert_eq!(conv(E::Time, E::Dint, i(1_999_999)), Ok(i(1)));
        assert_eq!(conv(E::Time, E::Dint, i(-1_999_999)), Ok(i(-1)));
        assert_eq!(conv(E::Dint, E::Time, i(1500)), Ok(i(1500 * MS)));
        assert_eq!(conv(E::Ltime, E::Lint, i(7)), Ok(i(7)));
        assert_eq!(conv(E::Lint, E::Ltime, i(7)), Ok(i(7)));
        assert_eq!(conv(E::Time, E::Udint, i(-MS)), Ok(i(u32::MAX as i128)));
        // 30 days in ms does not fit a DINT: low-order bits.
        let thirty_days_ms: i128 = 30 * 86_400_000;
        assert_eq!(
            conv(E::Time, E::Dint, i(thirty_days_ms * MS)),
            Ok(i(wrap(E::Dint, thirty_days_ms)))
        );
        assert_eq!(
            conv(E::Lint, E::Time, i(i64::MAX as i128)),
            Ok(i(wrap(E::Time, i64::MAX as i128 * MS)))
        );
        assert_eq!(conv(E::Time, E::Dword, i(MS)), Ok(i(1)));
        assert_eq!(conv(E::Time, E::Lreal, i(1500 * MS)), Ok(r(1500.0)));
        assert_eq!(conv(E::Time, E::Real, i(1)), Ok(r((1e-6f64) as f32 as f64)));
        assert_eq!(conv(E::Lreal, E::Time, r(1.5)), Ok(i(1_500_000)));
        assert_eq!(conv(E::Lreal, E::Time, r(0.0000005)), Ok(i(0)));
        assert_eq!(conv(E::Lreal, E::Time, r(0.0000015)), Ok(i(2)));
        assert_eq!(conv(E::Lreal, E::Time, r(-0.0000025)), Ok(i(-2)));
        assert_eq!(conv(E::Lreal, E::Time, r(1e20)), Err(Fault::Conversion));
        assert_eq!(conv(E::Lreal, E::Time, r(f64::NAN)), Err(Fault::Conversion));
        assert_eq!(conv(E::Lreal, E::Ltime, r(2.5)), Ok(i(2)));
        assert_eq!(conv(E::Ltime, E::Lreal, i(3)), Ok(r(3.0)));
        assert_eq!(conv(E::Time, E::Ltime, i(5)), Ok(i(5)));
        assert_eq!(conv(E::Ltime, E::Time, i(5)), Ok(i(5)));
    }

    #[test]
    fn dates_and_times() {
        let day_ns = NS_PER_D;
        assert_eq!(conv(E::Date, E::Udint, i(86_400)), Ok(i(86_400)));
        assert_eq!(conv(E::Udint, E::Date, i(86_400 + 3_599)), Ok(i(86_400)));
        assert_eq!(conv(E::Dint, E::Date, i(-1)), Ok(i(-86_400)));
        assert_eq!(conv(E::Ldate, E::Lint, i(86_400)), Ok(i(day_ns)));
        assert_eq!(conv(E::Lint, E::Ldate, i(day_ns + 5)), Ok(i(86_400)));
        assert_eq!(conv(E::Tod, E::Udint, i(1500 * MS)), Ok(i(1500)));
        assert_eq!(conv(E::Udint, E::Tod, i(1500)), Ok(i(1500 * MS)));
        assert_eq!(conv(E::Udint, E::Tod, i(86_400_000 + 1)), Ok(i(MS)));
        assert_eq!(conv(E::Dint, E::Tod, i(-1)), Ok(i(day_ns - MS)));
        assert_eq!(conv(E::Ltod, E::Ulint, i(5)), Ok(i(5)));
        assert_eq!(conv(E::Dt, E::Lint, i(1_500_000_000)), Ok(i(1)));
        assert_eq!(conv(E::Dt, E::Lint, i(-500_000_000)), Ok(i(-1)));
        assert_eq!(conv(E::Lint, E::Dt, i(2)), Ok(i(2_000_000_000)));
        assert_eq!(conv(E::Ldt, E::Lint, i(7)), Ok(i(7)));
        // DT_TO_DATE, DT_TO_TOD, DATE_TO_DT, TOD_TO_TIME, TIME_TO_TOD.
        let dt = 3 * day_ns + 5 * MS;
        assert_eq!(conv(E::Dt, E::Date, i(dt)), Ok(i(3 * 86_400)));
        assert_eq!(conv(E::Dt, E::Tod, i(dt)), Ok(i(5 * MS)));
        assert_eq!(conv(E::Dt, E::Date, i(-1)), Ok(i(-86_400)));
        assert_eq!(conv(E::Dt, E::Tod, i(-1)), Ok(i(day_ns - 1)));
        assert_eq!(conv(E::Date, E::Dt, i(86_400)), Ok(i(day_ns)));
        assert_eq!(
            conv(E::Date, E::Dt, i(200_000 * 86_400)),
            Err(Fault::Conversion)
        );
        assert_eq!(conv(E::Ldt, E::Ldate, i(day_ns)), Ok(i(86_400)));
        assert_eq!(conv(E::Tod, E::Time, i(5)), Ok(i(5)));
        assert_eq!(conv(E::Time, E::Tod, i(-MS)), Ok(i(day_ns - MS)));
        assert_eq!(conv(E::Time, E::Tod, i(day_ns + 1)), Ok(i(1)));
        assert_eq!(conv(E::Dt, E::Ldt, i(5)), Ok(i(5)));
        assert!(!conversion_allowed(E::Date, E::Tod));
        assert!(!conversion_allowed(E::Tod, E::Dt));
        assert!(!conversion_allowed(E::Date, E::Real));
        assert!(!conversion_allowed(E::Time, E::Date));
    }

    #[test]
    fn strings() {
        let s = |x: &str| Value::string(x);
        assert_eq!(conv(E::Int, E::String, i(-42)), Ok(s("-42")));
        assert_eq!(conv(E::Bool, E::String, Value::Bool(true)), Ok(s("TRUE")));
        assert_eq!(conv(E::Real, E::String, r(0.1f32 as f64)), Ok(s("0.1")));
        assert_eq!(conv(E::Time, E::String, i(1500 * MS)), Ok(s("1s500ms")));
        assert_eq!(
            conv(E::Bool, E::Real, Value::Bool(true)),
            Ok(Value::Real(1.0))
        );
        assert_eq!(
            conv(E::Bool, E::Lreal, Value::Bool(false)),
            Ok(Value::Real(0.0))
        );
        assert_eq!(
            conv(E::Real, E::Bool, Value::Real(-0.5)),
            Ok(Value::Bool(true))
        );
        assert_eq!(
            conv(E::Lreal, E::Bool, Value::Real(0.0)),
            Ok(Value::Bool(false))
        );
        assert_eq!(
            conv(E::Lreal, E::Bool, Value::Real(f64::NAN)),
            Ok(Value::Bool(true))
        );
        assert_eq!(conv(E::Time, E::String, i(-2000 * MS)), Ok(s("-2s")));
        assert_eq!(conv(E::Date, E::String, i(86_400)), Ok(s("1970-01-02")));
        assert_eq!(conv(E::Tod, E::String, i(1500 * MS)), Ok(s("00:00:01.5")));
        assert_eq!(conv(E::Dt, E::String, i(0)), Ok(s("1970-01-01-00:00:00")));
        assert_eq!(conv(E::Time, E::Wstring, i(0)), Ok(Value::wstring("0s")));
        assert_eq!(conv(E::String, E::Int, s(" 42 ")), Ok(i(42)));
        assert_eq!(conv(E::String, E::Int, s("x")), Err(Fault::Conversion));
        assert_eq!(
            conv(E::Wstring, E::Dint, Value::wstring("16#10")),
            Ok(i(16))
        );
        assert_eq!(
            conv(E::Wstring, E::Dint, Value::WStr(vec![0xD800])),
            Err(Fault::Conversion)
        );
        assert_eq!(
            conv(E::String, E::Wstring, Value::Str(vec![0xE9])),
            Ok(Value::WStr(vec![0xE9]))
        );
        assert_eq!(
            conv(E::Wstring, E::String, Value::WStr(vec![0xE9, 65])),
            Ok(Value::Str(vec![0xE9, 65]))
        );
        // STRING is Windows-1252: byte 0x80 is the euro sign.
        assert_eq!(
            conv(E::String, E::Wstring, Value::Str(vec![0x80, 0x9F])),
            Ok(Value::WStr(vec![0x20AC, 0x178]))
        );
        assert_eq!(
            conv(E::Wstring, E::String, Value::WStr(vec![0x20AC])),
            Ok(Value::Str(vec![0x80]))
        );
        assert_eq!(
            conv(E::Wstring, E::String, Value::WStr(vec![0x3A9])),
            Err(Fault::Conversion)
        );
        assert_eq!(
            conv(E::Wstring, E::String, Value::WStr(vec![0x80])),
            Err(Fault::Conversion)
        );
        assert_eq!(conv(E::Char, E::String, i(65)), Ok(s("A")));
        assert_eq!(conv(E::Char, E::Wstring, i(0x80)), Ok(Value::wstring("€")));
        assert_eq!(
            conv(E::Wchar, E::String, i(0x20AC)),
            Ok(Value::Str(vec![0x80]))
        );
        assert_eq!(conv(E::Wchar, E::String, i(0x3A9)), Err(Fault::Conversion));
        assert_eq!(
            conv(E::String, E::Wchar, Value::Str(vec![0x80])),
            Ok(i(0x20AC))
        );
        assert_eq!(
            conv(E::Wchar, E::Wstring, i(0x20AC)),
            Ok(Value::WStr(vec![0x20AC]))
        );
        assert_eq!(conv(E::String, E::Char, s("xyz")), Ok(i(120)));
        assert_eq!(conv(E::String, E::Char, s("")), Ok(i(0)));
        assert_eq!(
            conv(E::Wstring, E::Char, Value::WStr(vec![0x20AC])),
            Ok(i(0x80))
        );
        assert_eq!(
            conv(E::Wstring, E::Char, Value::WStr(vec![0x3A9])),
            Err(Fault::Conversion)
        );
        assert_eq!(conv(E::String, E::String, s("x")), Ok(s("x")));
        assert_eq!(conv(E::String, E::Time, s("T#2s")), Ok(i(2000 * MS)));
        assert_eq!(conv(E::String, E::Real, s("1E39")), Err(Fault::Conversion));
    }

    #[test]
    fn characters() {
        assert_eq!(conv(E::Char, E::Wchar, i(0xE9)), Ok(i(0xE9)));
        assert_eq!(conv(E::Wchar, E::Char, i(0xE9)), Ok(i(0xE9)));
        assert_eq!(conv(E::Wchar, E::Char, i(0x100)), Err(Fault::Conversion));
        assert!(!conversion_allowed(E::Char, E::Bool));
        assert!(!conversion_allowed(E::Char, E::Real));
        assert!(!conversion_allowed(E::Char, E::Time));
    }

    #[test]
    fn bcd() {
        assert_eq!(bcd_to_int(E::Word, E::Int, &i(0x1234)), Ok(i(1234)));
        assert_eq!(bcd_to_int(E::Word, E::Uint, &i(0x0369)), Ok(i(369)));
        assert_eq!(bcd_to_int(E::Byte, E::Usint, &i(0x25)), Ok(i(25)));
        assert_eq!(
            bcd_to_int(E::Lword, E::Ulint, &i(0x9999_9999_9999_9999)),
            Ok(i(9_999_999_999_999_999))
        );
        assert_eq!(
            bcd_to_int(E::Word, E::Int, &i(0x12A4)),
            Err(Fault::Conversion)
        );
        assert_eq!(
            bcd_to_int(E::Word, E::Sint, &i(0x0128)),
            Err(Fault::Conversion)
        );
        assert_eq!(bcd_to_int(E::Word, E::Int, &i(0)), Ok(i(0)));
        assert_eq!(int_to_bcd(E::Usint, E::Byte, &i(25)), Ok(i(0x25)));
        assert_eq!(int_to_bcd(E::Int, E::Word, &i(1234)), Ok(i(0x1234)));
        assert_eq!(int_to_bcd(E::Uint, E::Word, &i(9999)), Ok(i(0x9999)));
        assert_eq!(
            int_to_bcd(E::Uint, E::Word, &i(10000)),
            Err(Fault::Conversion)
        );
        assert_eq!(int_to_bcd(E::Int, E::Word, &i(-1)), Err(Fault::Conversion));
        assert_eq!(
            int_to_bcd(E::Ulint, E::Lword, &i(9_999_999_999_999_999)),
            Ok(i(0x9999_9999_9999_9999))
        );
        assert_eq!(
            int_to_bcd(E::Ulint, E::Lword, &i(10_000_000_000_000_000)),
            Err(Fault::Conversion)
        );
        assert_eq!(int_to_bcd(E::Int, E::Word, &i(0)), Ok(i(0)));
        assert_eq!(
            int_to_bcd(E::Real, E::Word, &r(1.0)),
            Err(Fault::Conversion)
        );
    }

    #[test]
    fn identity_and_misuse() {
        for &t in ElemType::ALL {
            assert!(conversion_allowed(t, t));
            let d = crate::default_value(t);
            assert_eq!(convert(t, t, &d), Ok(d.clone()), "{t:?}");
        }
        assert_eq!(conv(E::Int, E::Dint, r(1.0)), Err(Fault::Conversion));
        assert_eq!(conv(E::Real, E::Int, i(1)), Err(Fault::Conversion));
    }
}
