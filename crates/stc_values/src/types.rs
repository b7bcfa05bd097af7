//! Facts about elementary types: widths, ranges, generic families, initial
//! values, wrap-around, and the implicit widenings of spec/semantics.md
//! ("Types", "Implicit conversions").

use crate::Value;
use stc_syntax::literal::NS_PER_D;
use stc_syntax::token::{ElemType, GenericType};

use ElemType as E;

/// Storage width in bits (BOOL 1, STRING and WSTRING 0; every time and date
/// type 64).
pub fn bits(t: ElemType) -> u32 {
    match t {
        E::Bool => 1,
        E::Sint | E::Usint | E::Byte | E::Char => 8,
        E::Int | E::Uint | E::Word | E::Wchar => 16,
        E::Dint | E::Udint | E::Dword | E::Real => 32,
        E::Lint | E::Ulint | E::Lword | E::Lreal => 64,
        E::Time | E::Ltime | E::Date | E::Ldate | E::Tod | E::Ltod | E::Dt | E::Ldt => 64,
        E::String | E::Wstring => 0,
    }
}

/// The signed integer types (ANY_SIGNED).
pub fn is_signed(t: ElemType) -> bool {
    matches!(t, E::Sint | E::Int | E::Dint | E::Lint)
}

/// The integer types (ANY_INT).
pub fn is_integer(t: ElemType) -> bool {
    matches!(
        t,
        E::Sint | E::Int | E::Dint | E::Lint | E::Usint | E::Uint | E::Udint | E::Ulint
    )
}

/// BOOL and BYTE..LWORD (ANY_BIT).
pub fn is_bit_string(t: ElemType) -> bool {
    matches!(t, E::Bool | E::Byte | E::Word | E::Dword | E::Lword)
}

/// REAL and LREAL (ANY_REAL).
pub fn is_real(t: ElemType) -> bool {
    matches!(t, E::Real | E::Lreal)
}

/// TIME, LTIME, DATE, LDATE, TOD, LTOD, DT, LDT.
pub fn is_time_like(t: ElemType) -> bool {
    matches!(
        t,
        E::Time | E::Ltime | E::Date | E::Ldate | E::Tod | E::Ltod | E::Dt | E::Ldt
    )
}

pub(crate) fn is_duration(t: ElemType) -> bool {
    matches!(t, E::Time | E::Ltime)
}

pub(crate) fn is_date(t: ElemType) -> bool {
    matches!(t, E::Date | E::Ldate)
}

pub(crate) fn is_tod(t: ElemType) -> bool {
    matches!(t, E::Tod | E::Ltod)
}

pub(crate) fn is_dt(t: ElemType) -> bool {
    matches!(t, E::Dt | E::Ldt)
}

pub(crate) fn is_string(t: ElemType) -> bool {
    matches!(t, E::String | E::Wstring)
}

pub(crate) fn is_char(t: ElemType) -> bool {
    matches!(t, E::Char | E::Wchar)
}

/// ANY_INT and BYTE..LWORD: the types whose values are plain integers that
/// wrap like C's fixed-width integers.
pub(crate) fn is_int_like(t: ElemType) -> bool {
    is_integer(t) || matches!(t, E::Byte | E::Word | E::Dword | E::Lword)
}

/// The range of the `Int` representation of integer, bit-string, CHAR/WCHAR
/// and time-like types (BOOL is 0..=1; TOD counts nanoseconds below 24 h).
pub fn int_range(t: ElemType) -> Option<(i128, i128)> {
    Some(match t {
        E::Bool => (0, 1),
        E::Sint => (i8::MIN.into(), i8::MAX.into()),
        E::Int => (i16::MIN.into(), i16::MAX.into()),
        E::Dint => (i32::MIN.into(), i32::MAX.into()),
        E::Lint => (i64::MIN.into(), i64::MAX.into()),
        E::Usint | E::Byte | E::Char => (0, u8::MAX.into()),
        E::Uint | E::Word | E::Wchar => (0, u16::MAX.into()),
        E::Udint | E::Dword => (0, u32::MAX.into()),
        E::Ulint | E::Lword => (0, u64::MAX.into()),
        E::Time | E::Ltime | E::Date | E::Ldate | E::Dt | E::Ldt => {
            (i64::MIN.into(), i64::MAX.into())
        }
        E::Tod | E::Ltod => (0, NS_PER_D - 1),
        E::Real | E::Lreal | E::String | E::Wstring => return None,
    })
}

/// Whether `t` belongs to the generic family `g` (IEC 61131-3 3rd edition
/// hierarchy). No elementary type is ANY_DERIVED.
pub fn in_family(g: GenericType, t: ElemType) -> bool {
    use GenericType as G;
    match g {
        G::Any | G::AnyElementary => true,
        G::AnyDerived => false,
        G::AnyMagnitude => in_family(G::AnyNum, t) || in_family(G::AnyDuration, t),
        G::AnyNum => is_real(t) || is_integer(t),
        G::AnyReal => is_real(t),
        G::AnyInt => is_integer(t),
        G::AnySigned => is_signed(t),
        G::AnyUnsigned => matches!(t, E::Usint | E::Uint | E::Udint | E::Ulint),
        G::AnyBit => is_bit_string(t),
        G::AnyString => is_string(t),
        G::AnyChars => is_string(t) || is_char(t),
        G::AnyChar => is_char(t),
        G::AnyDate => is_date(t) || is_tod(t) || is_dt(t),
        G::AnyDuration => is_duration(t),
    }
}

/// The initial value of a variable of type `t` with no initialiser.
pub fn default_value(t: ElemType) -> Value {
    match t {
        E::Bool => Value::Bool(false),
        E::Real | E::Lreal => Value::Real(0.0),
        E::String => Value::Str(Vec::new()),
        E::Wstring => Value::WStr(Vec::new()),
        // Integers, bit strings, characters (NUL), T#0s, D#1970-01-01,
        // TOD#00:00:00 and DT#1970-01-01-00:00:00 are all zero.
        _ => Value::Int(0),
    }
}

/// Two's-complement wrap-around of `v` into `t`'s range: modulo 2^n for
/// unsigned and bit-string types (BOOL modulo 2), into the signed n-bit
/// range for signed ones, modulo 24 h for TOD/LTOD. Types without an integer
/// representation (REAL, strings) return `v` unchanged.
pub fn wrap(t: ElemType, v: i128) -> i128 {
    match t {
        E::Tod | E::Ltod => v.rem_euclid(NS_PER_D),
        E::Real | E::Lreal | E::String | E::Wstring => v,
        _ => {
            let n = bits(t);
            let signed = is_signed(t)
                || matches!(t, E::Time | E::Ltime | E::Date | E::Ldate | E::Dt | E::Ldt);
            let low = v & ((1i128 << n) - 1);
            if signed && low >= 1i128 << (n - 1) {
                low - (1i128 << n)
            } else {
                low
            }
        }
    }
}

/// The direct implicit widenings of spec/semantics.md (Types): the closure
/// of these edges is the relation [`implicit_widening`].
const WIDENING_EDGES: &[(ElemType, ElemType)] = &[
    (E::Sint, E::Int),
    (E::Int, E::Dint),
    (E::Dint, E::Lint),
    (E::Usint, E::Uint),
    (E::Uint, E::Udint),
    (E::Udint, E::Ulint),
    (E::Usint, E::Int),
    (E::Uint, E::Dint),
    (E::Udint, E::Lint),
    (E::Byte, E::Word),
    (E::Word, E::Dword),
    (E::Dword, E::Lword),
    (E::Real, E::Lreal),
    (E::Sint, E::Real),
    (E::Int, E::Real),
    (E::Usint, E::Real),
    (E::Uint, E::Real),
    (E::Dint, E::Lreal),
    (E::Udint, E::Lreal),
    (E::Bool, E::Byte),
];

/// Whether a value of type `from` converts implicitly to `to`: exactly the
/// table of spec/semantics.md, transitively closed; never reflexive.
pub fn implicit_widening(from: ElemType, to: ElemType) -> bool {
    if from == to {
        return false;
    }
    // Depth-first search over at most 27 types.
    let mut seen = [false; 32];
    let mut stack = vec![from];
    while let Some(t) = stack.pop() {
        for &(a, b) in WIDENING_EDGES {
            if a == t {
                if b == to {
                    return true;
                }
                let i = b as usize;
                if i < seen.len() && !seen[i] {
                    seen[i] = true;
                    stack.push(b);
                }
            }
        }
    }
    false
}

fn reaches(from: ElemType, to: ElemType) -> bool {
    from == to || implicit_widening(from, to)
}

/// The least type both `a` and `b` widen to (or are): the operand type of a
/// binary operator on mixed operands. When an integer and a real type are
/// both minimal (INT and UINT reach DINT and REAL), the integer one wins,
/// since it is exact. `None` when the types have no common widening
/// (LINT and ULINT, DINT and REAL have LREAL).
pub fn common_type(a: ElemType, b: ElemType) -> Option<ElemType> {
    if a == b {
        return Some(a);
    }
    let candidates: Vec<ElemType> = ElemType::ALL
        .iter()
        .copied()
        .filter(|&c| reaches(a, c) && reaches(b, c))
        .collect();
    let minimal: Vec<ElemType> = candidates
        .iter()
        .copied()
        .filter(|&c| {
            !candidates
                .iter()
                .any(|&d| d != c && implicit_widening(d, c))
        })
        .collect();
    match minimal.as_slice() {
        [] => None,
        [one] => Some(*one),
        several => {
            let exact: Vec<ElemType> = several.iter().copied().filter(|&t| !is_real(t)).collect();
            match exact.as_slice() {
                [one] => Some(*one),
                _ => None,
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn widths() {
        let cases = [
            (E::Bool, 1),
            (E::Sint, 8),
            (E::Usint, 8),
            (E::Byte, 8),
            (E::Char, 8),
            (E::Int, 16),
            (E::Wchar, 16),
            (E::Dint, 32),
            (E::Real, 32),
            (E::Lint, 64),
            (E::Lreal, 64),
            (E::Time, 64),
            (E::Dt, 64),
            (E::String, 0),
            (E::Wstring, 0),
        ];
        for (t, n) in cases {
            assert_eq!(bits(t), n, "{t:?}");
        }
    }

    #[test]
    fn ranges() {
        assert_eq!(int_range(E::Sint), Some((-128, 127)));
        assert_eq!(int_range(E::Ulint), Some((0, u64::MAX as i128)));
        assert_eq!(int_range(E::Bool), Some((0, 1)));
        assert_eq!(int_range(E::Wchar), Some((0, 65535)));
        assert_eq!(int_range(E::Tod), Some((0, 86_399_999_999_999)));
        assert_eq!(int_range(E::Real), None);
        assert_eq!(int_range(E::String), None);
    }

    #[test]
    fn wrap_every_width() {
        assert_eq!(wrap(E::Sint, 128), -128);
        assert_eq!(wrap(E::Sint, -129), 127);
        assert_eq!(wrap(E::Usint, 256), 0);
        assert_eq!(wrap(E::Usint, -1), 255);
        assert_eq!(wrap(E::Byte, 300), 44);
        assert_eq!(wrap(E::Int, 32768), -32768);
        assert_eq!(wrap(E::Uint, -1), 65535);
        assert_eq!(wrap(E::Word, 65536 + 7), 7);
        assert_eq!(wrap(E::Dint, 1 << 31), -(1 << 31));
        assert_eq!(wrap(E::Udint, -1), u32::MAX as i128);
        assert_eq!(wrap(E::Lint, 1 << 63), i64::MIN as i128);
        assert_eq!(wrap(E::Ulint, -1), u64::MAX as i128);
        assert_eq!(wrap(E::Lword, 1 << 64), 0);
        assert_eq!(wrap(E::Bool, 3), 1);
        assert_eq!(wrap(E::Time, i64::MAX as i128 + 1), i64::MIN as i128);
        assert_eq!(wrap(E::Tod, -1), NS_PER_D - 1);
        assert_eq!(wrap(E::Tod, NS_PER_D), 0);
        assert_eq!(wrap(E::Char, 256 + 65), 65);
        assert_eq!(wrap(E::Lreal, 1 << 100), 1 << 100);
        assert_eq!(wrap(E::Ulint, i128::MIN), 0);
        assert_eq!(wrap(E::Lint, i128::MAX), -1);
    }

    #[test]
    fn families() {
        use GenericType as G;
        assert!(in_family(G::AnyNum, E::Lreal));
        assert!(in_family(G::AnyNum, E::Usint));
        assert!(!in_family(G::AnyNum, E::Byte));
        assert!(!in_family(G::AnyNum, E::Time));
        assert!(in_family(G::AnyMagnitude, E::Ltime));
        assert!(in_family(G::AnyMagnitude, E::Int));
        assert!(!in_family(G::AnyMagnitude, E::Tod));
        assert!(in_family(G::AnyBit, E::Bool));
        assert!(in_family(G::AnyBit, E::Lword));
        assert!(!in_family(G::AnyBit, E::Int));
        assert!(in_family(G::AnyDate, E::Ldt));
        assert!(in_family(G::AnyDate, E::Tod));
        assert!(!in_family(G::AnyDate, E::Time));
        assert!(in_family(G::AnyDuration, E::Time));
        assert!(in_family(G::AnyString, E::Wstring));
        assert!(!in_family(G::AnyString, E::Char));
        assert!(in_family(G::AnyChars, E::Char));
        assert!(in_family(G::AnyChars, E::String));
        assert!(in_family(G::AnyChar, E::Wchar));
        assert!(!in_family(G::AnyChar, E::String));
        assert!(in_family(G::AnySigned, E::Lint));
        assert!(!in_family(G::AnySigned, E::Real));
        assert!(in_family(G::AnyUnsigned, E::Ulint));
        for &t in ElemType::ALL {
            assert!(in_family(G::AnyElementary, t));
            assert!(in_family(G::Any, t));
            assert!(!in_family(G::AnyDerived, t));
        }
    }

    #[test]
    fn defaults() {
        assert_eq!(default_value(E::Bool), Value::Bool(false));
        assert_eq!(default_value(E::Real), Value::Real(0.0));
        assert_eq!(default_value(E::Date), Value::Int(0));
        assert_eq!(default_value(E::String), Value::Str(vec![]));
        assert_eq!(default_value(E::Wstring), Value::WStr(vec![]));
        assert_eq!(default_value(E::Dint), Value::Int(0));
    }

    #[test]
    fn widening_is_the_spec_table_closed() {
        let yes = [
            (E::Sint, E::Int),
            (E::Sint, E::Lint),
            (E::Sint, E::Lreal),
            (E::Usint, E::Ulint),
            (E::Usint, E::Int),
            (E::Usint, E::Lint),
            (E::Uint, E::Dint),
            (E::Uint, E::Lreal),
            (E::Udint, E::Lint),
            (E::Udint, E::Lreal),
            (E::Dint, E::Lreal),
            (E::Real, E::Lreal),
            (E::Int, E::Real),
            (E::Byte, E::Lword),
            (E::Bool, E::Byte),
            (E::Bool, E::Lword),
        ];
        for (a, b) in yes {
            assert!(implicit_widening(a, b), "{a:?} -> {b:?}");
        }
        let no = [
            (E::Int, E::Int),
            (E::Int, E::Sint),
            (E::Int, E::Uint),
            (E::Uint, E::Int),
            (E::Dint, E::Real),
            (E::Lint, E::Lreal),
            (E::Ulint, E::Lreal),
            (E::Ulint, E::Lint),
            (E::Byte, E::Usint),
            (E::Usint, E::Byte),
            (E::Bool, E::Int),
            (E::Time, E::Ltime),
            (E::String, E::Wstring),
            (E::Char, E::String),
            (E::Lreal, E::Real),
        ];
        for (a, b) in no {
            assert!(!implicit_widening(a, b), "{a:?} -> {b:?}");
        }
    }

    #[test]
    fn common_types() {
        let cases = [
            (E::Int, E::Int, Some(E::Int)),
            (E::Int, E::Uint, Some(E::Dint)),
            (E::Sint, E::Usint, Some(E::Int)),
            (E::Dint, E::Udint, Some(E::Lint)),
            (E::Dint, E::Real, Some(E::Lreal)),
            (E::Int, E::Real, Some(E::Real)),
            (E::Sint, E::Dint, Some(E::Dint)),
            (E::Lint, E::Ulint, None),
            (E::Lint, E::Real, None),
            (E::Bool, E::Word, Some(E::Word)),
            (E::Bool, E::Int, None),
            (E::Byte, E::Usint, None),
            (E::Time, E::Ltime, None),
            (E::Udint, E::Sint, Some(E::Lint)),
        ];
        for (a, b, want) in cases {
            assert_eq!(common_type(a, b), want, "{a:?} {b:?}");
            assert_eq!(common_type(b, a), want, "{b:?} {a:?}");
        }
    }

    #[test]
    fn common_type_is_reachable_from_both() {
        for &a in ElemType::ALL {
            for &b in ElemType::ALL {
                if let Some(c) = common_type(a, b) {
                    assert!(reaches(a, c) && reaches(b, c), "{a:?} {b:?} {c:?}");
                }
            }
        }
    }
}
