//! Conversions (`stc_values::convert`, `trunc`, `bcd_to_int`,
//! `int_to_bcd`): casts where C's are the rule (integers keep their
//! low-order bits, integers to reals round once), the runtime for the
//! rest (reals to integers with ties to even and range faults, times and
//! dates, texts).

use super::arith::int_like;
use super::c::{
    bits64, call_checked, elem_arg, int_cast, lit, misuse, range, set, set_checked, signed_flag,
    Rep, Val,
};
use super::Emit;
use stc_syntax::token::ElemType;
use stc_values::{conversion_allowed, is_bit_string, is_integer, is_real};

use ElemType as E;

#[derive(Clone, Copy, PartialEq, Eq, Debug)]
enum Cat {
    Bool,
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
        _ if int_like(t) => Cat::Int,
        E::Real | E::Lreal => Cat::Real,
        E::Time | E::Ltime => Cat::Dur,
        E::Date | E::Ldate => Cat::Date,
        E::Tod | E::Ltod => Cat::Tod,
        E::Dt | E::Ldt => Cat::Dt,
        E::String | E::Wstring => Cat::Str,
        E::Char | E::Wchar => Cat::Char,
        _ => Cat::Int,
    }
}

/// `dst := FROM_TO_TO(a)`.
pub(crate) fn convert(e: &mut dyn Emit, a: &Val, dst: &Val, cap: u32) {
    let (Some(from), Some(to)) = (a.elem, dst.elem) else {
        // Aggregates of one type: a copy (MOVE-like), nothing else.
        if a.ty == dst.ty {
            return set(e, dst, &a.x);
        }
        return misuse(e, dst);
    };
    if !conversion_allowed(from, to) {
        return misuse(e, dst);
    }
    let site = e.site();
    match (cat(from), cat(to)) {
        (_, Cat::Str) => to_string(e, from, to, a, dst, cap, site),
        (Cat::Str, _) => from_string(e, from, to, a, dst, site),
        _ => scalar(e, from, to, a, dst, site),
    }
}

/// The representation of a non-string elementary type.
fn rep(t: ElemType) -> Rep {
    Rep::of(t).unwrap_or(Rep::I64)
}

/// A non-string conversion.
fn scalar(e: &mut dyn Emit, from: ElemType, to: ElemType, a: &Val, dst: &Val, site: u32) {
    use Cat as C;
    let (rf, rt) = (rep(from), rep(to));
    let ax = a.x.as_str();
    let pa = a.p();
    if from == to {
        return set(e, dst, ax);
    }
    match (cat(from), cat(to)) {
        (C::Real, C::Real) => set(e, dst, &format!("({}){pa}", rt.ctype())),
        (C::Real, C::Int) => real_to_int(e, a, to, dst, false),
        (C::Int | C::Bool, C::Real) => set(e, dst, &format!("({}){pa}", rt.ctype())),
        (C::Bool | C::Int | C::Real, C::Bool) => {
            let z = super::c::zero(rf);
            set(e, dst, &format!("({pa} != {z}) ? 1U : 0U"))
        }
        (C::Char, C::Char) => {
            if to == E::Char {
                set_checked(e, dst, &format!("stc_wchar_to_char({ax}, {site}U)"))
            } else {
                set(e, dst, &format!("(uint16_t){pa}"))
            }
        }
        (C::Bool | C::Int | C::Char, C::Int | C::Char) => set(e, dst, &int_cast(rf, rt, ax)),
        // Durations.
        (C::Dur, C::Dur) => set(e, dst, ax),
        (C::Dur, C::Int) => {
            let n = if from == E::Time {
                format!("({pa} / INT64_C(1000000))")
            } else {
                ax.to_string()
            };
            set(e, dst, &int_cast(Rep::I64, rt, &n))
        }
        (C::Int, C::Dur) => {
            if to == E::Time {
                set(e, dst, &format!("stc_time_of_ms({})", bits64(a)))
            } else {
                set(e, dst, &int_cast(rf, Rep::I64, ax))
            }
        }
        (C::Dur, C::Real) => {
            let x = if from == E::Time {
                if to == E::Real {
                    format!("(float)((double){pa} / 1000000.0)")
                } else {
                    format!("(double){pa} / 1000000.0")
                }
            } else {
                format!("({}){pa}", rt.ctype())
            };
            set(e, dst, &x)
        }
        (C::Real, C::Dur) => {
            let x = if to == E::Time {
                format!("stc_real_to_ns((double){pa} * 1000000.0, {site}U)")
            } else {
                format!("stc_real_to_ns((double){pa}, {site}U)")
            };
            set_checked(e, dst, &x)
        }
        (C::Dur, C::Tod) => set(e, dst, &format!("stc_tod_of_time({ax})")),
        (C::Tod, C::Dur) => set(e, dst, ax),
        // Dates and times of day against integers.
        (C::Date, C::Int) => {
            if from == E::Date {
                set(e, dst, &int_cast(Rep::I64, rt, ax))
            } else {
                set(
                    e,
                    dst,
                    &int_cast(Rep::U64, rt, &format!("stc_date_to_ns({ax})")),
                )
            }
        }
        (C::Int, C::Date) => {
            let unit_ns = if to == E::Ldate { "1U" } else { "0U" };
            let x = format!(
                "stc_date_of_int({}, {}, {unit_ns})",
                bits64(a),
                signed_flag(a)
            );
            set(e, dst, &x)
        }
        (C::Tod, C::Int) => {
            let n = if from == E::Tod {
                format!("({pa} / INT64_C(1000000))")
            } else {
                ax.to_string()
            };
            set(e, dst, &int_cast(Rep::I64, rt, &n))
        }
        (C::Int, C::Tod) => {
            let unit_ms = if to == E::Tod { "1U" } else { "0U" };
            let x = format!(
                "stc_tod_of_int({}, {}, {unit_ms})",
                bits64(a),
                signed_flag(a)
            );
            set(e, dst, &x)
        }
        (C::Dt, C::Int) => {
            let n = if from == E::Dt {
                format!("stc_floordiv_i64({ax}, INT64_C(1000000000))")
            } else {
                ax.to_string()
            };
            set(e, dst, &int_cast(Rep::I64, rt, &n))
        }
        (C::Int, C::Dt) => {
            if to == E::Dt {
                set(e, dst, &format!("stc_dt_of_secs({})", bits64(a)))
            } else {
                set(e, dst, &int_cast(rf, Rep::I64, ax))
            }
        }
        (C::Date, C::Date) | (C::Tod, C::Tod) | (C::Dt, C::Dt) => set(e, dst, ax),
        (C::Dt, C::Date) => set(e, dst, &format!("stc_dt_to_date({ax})")),
        (C::Dt, C::Tod) => set(e, dst, &format!("stc_dt_to_tod({ax})")),
        (C::Date, C::Dt) => set_checked(e, dst, &format!("stc_date_to_dt({ax}, {site}U)")),
        _ => misuse(e, dst),
    }
}

/// REAL/LREAL to an integer or bit string: rounded (ties to even) or
/// truncated (TRUNC); NaN or out of range faults.
fn real_to_int(e: &mut dyn Emit, a: &Val, to: ElemType, dst: &Val, truncate: bool) {
    let site = e.site();
    let (Some((lo, hi)), Some(rt)) = (range(to), Rep::of(to)) else {
        return misuse(e, dst);
    };
    let t = if truncate { "1U" } else { "0U" };
    let x = if rt.signed() {
        format!(
            "({})stc_real_to_int((double){}, {}, {}, {t}, {site}U)",
            rt.ctype(),
            a.p(),
            lit(Rep::I64, lo),
            lit(Rep::I64, hi)
        )
    } else {
        format!(
            "({})stc_real_to_uint((double){}, {}, {t}, {site}U)",
            rt.ctype(),
            a.p(),
            lit(Rep::U64, hi)
        )
    };
    set_checked(e, dst, &x)
}

/// TRUNC: REAL/LREAL to an integer, toward zero.
pub(crate) fn trunc(e: &mut dyn Emit, a: &Val, dst: &Val) {
    match (a.elem, dst.elem) {
        (Some(from), Some(to)) if is_real(from) && int_like(to) => real_to_int(e, a, to, dst, true),
        _ => misuse(e, dst),
    }
}

/// `*_BCD_TO_*`: the number a BCD bit string holds.
pub(crate) fn bcd_to_int(e: &mut dyn Emit, a: &Val, dst: &Val) {
    let site = e.site();
    match (a.elem, dst.elem) {
        (Some(from), Some(to)) if is_bit_string(from) && is_integer(to) => {
            let (Some((_, hi)), Some(rt)) = (range(to), Rep::of(to)) else {
                return misuse(e, dst);
            };
            let x = format!(
                "stc_bcd_to_int({}, {}, {site}U)",
                bits64(a),
                lit(Rep::U64, hi)
            );
            set_checked(e, dst, &format!("({}){x}", rt.ctype()))
        }
        _ => misuse(e, dst),
    }
}

/// `*_TO_BCD_*`: a number as BCD.
pub(crate) fn int_to_bcd(e: &mut dyn Emit, a: &Val, dst: &Val) {
    let site = e.site();
    match (a.elem, dst.elem) {
        (Some(from), Some(to)) if is_integer(from) && is_bit_string(to) => {
            let (Some((_, hi)), Some(rt)) = (range(to), Rep::of(to)) else {
                return misuse(e, dst);
            };
            let nibbles = stc_values::bits(to).div_ceil(4);
            let x = format!(
                "stc_int_to_bcd({}, {}, {nibbles}U, {}, {site}U)",
                bits64(a),
                signed_flag(a),
                lit(Rep::U64, hi)
            );
            set_checked(e, dst, &format!("({}){x}", rt.ctype()))
        }
        _ => misuse(e, dst),
    }
}

/// `*_TO_STRING`, `*_TO_WSTRING`.
#[allow(clippy::too_many_arguments)]
fn to_string(
    e: &mut dyn Emit,
    from: ElemType,
    to: ElemType,
    a: &Val,
    dst: &Val,
    cap: u32,
    site: u32,
) {
    let w = if to == E::Wstring { "wstr" } else { "str" };
    let d = &dst.x;
    let ax = &a.x;
    let pa = a.p();
    let call = match (from, to) {
        (E::String, E::String) => format!("stc_str_copy({d}, {cap}U, {ax})"),
        (E::String, E::Wstring) => format!("stc_str_to_wstr({d}, {cap}U, {ax})"),
        (E::Wstring, E::Wstring) => format!("stc_wstr_copy({d}, {cap}U, {ax})"),
        (E::Wstring, E::String) => {
            return call_checked(e, &format!("stc_wstr_to_str({d}, {cap}U, {ax}, {site}U)"))
        }
        (E::Char, _) => format!("stc_char_to_{w}({d}, {cap}U, {ax})"),
        (E::Wchar, _) => {
            return call_checked(e, &format!("stc_wchar_to_{w}({d}, {cap}U, {ax}, {site}U)"))
        }
        (E::Bool, _) => format!("stc_bool_to_{w}({d}, {cap}U, {ax})"),
        (E::Real, _) => format!("stc_real_to_{w}({d}, {cap}U, {ax})"),
        (E::Lreal, _) => format!("stc_lreal_to_{w}({d}, {cap}U, {ax})"),
        _ if stc_values::is_time_like(from) => {
            format!("stc_time_to_{w}({d}, {cap}U, {ax}, {})", elem_arg(from))
        }
        _ => match Rep::of(from) {
            Some(r) if r.signed() => format!("stc_int_to_{w}({d}, {cap}U, (int64_t){pa})"),
            Some(Rep::U64) => format!("stc_uint_to_{w}({d}, {cap}U, {ax})"),
            Some(_) => format!("stc_uint_to_{w}({d}, {cap}U, (uint64_t){pa})"),
            None => return misuse(e, dst),
        },
    };
    e.stmt(format!("{call};"));
}

/// `STRING_TO_*`, `WSTRING_TO_*` (not to a string type).
fn from_string(e: &mut dyn Emit, from: ElemType, to: ElemType, a: &Val, dst: &Val, site: u32) {
    let w = if from == E::Wstring { "wstr" } else { "str" };
    let ax = &a.x;
    let Some(rt) = Rep::of(to) else {
        return misuse(e, dst);
    };
    let x = match to {
        E::Char if from == E::String => return set(e, dst, &format!("stc_str_to_char({ax})")),
        E::Wchar if from == E::String => return set(e, dst, &format!("stc_str_to_wchar({ax})")),
        E::Char | E::Wchar => format!(
            "stc_{w}_to_{}({ax}, {site}U)",
            if to == E::Char { "char" } else { "wchar" }
        ),
        E::Bool => format!("stc_{w}_to_bool({ax}, {site}U)"),
        E::Real => format!("stc_{w}_to_real({ax}, {site}U)"),
        E::Lreal => format!("stc_{w}_to_lreal({ax}, {site}U)"),
        // The parsed value is in the type's range: a plain cast.
        _ if rt.signed() => format!(
            "({})stc_{w}_to_i64({ax}, {}, {site}U)",
            rt.ctype(),
            elem_arg(to)
        ),
        _ => format!(
            "({})stc_{w}_to_u64({ax}, {}, {site}U)",
            rt.ctype(),
            elem_arg(to)
        ),
    };
    set_checked(e, dst, &x)
}
