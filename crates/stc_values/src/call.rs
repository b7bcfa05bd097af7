//! Evaluation of the standard functions that are not operators: numeric,
//! bit shift, selection, string, time and date functions, conversions and
//! the operator functions (`ADD`, `GT`, ...), dispatched by [`Intrinsic`].
//!
//! Every edge the standard leaves open (string positions out of range,
//! negative shift counts, NaN in MAX) is decided in docs/semantics-notes.md
//! and tested in tests/functions.rs; none of them faults or panics.

use crate::convert::{bcd_to_int, convert, int, int_to_bcd, real, round_to, trunc};
use crate::ops::{binary, compare, unary};
use crate::types::{bits, is_bit_string, is_int_like, is_real, wrap};
use crate::{misuse, BinOp, Fault, Intrinsic, Outcome, UnOp, Value};
use stc_syntax::literal::{
    civil_from_days, days_from_civil, NS_PER_D, NS_PER_H, NS_PER_M, NS_PER_MS, NS_PER_S,
};
use stc_syntax::token::ElemType;
use std::cmp::Ordering;

use ElemType as E;

const SECS_PER_DAY: i128 = 86_400;

/// Calls the standard function `f` on `args`, whose types are `arg_types`
/// (one per argument, in the order of the signature's inputs), giving a
/// value of type `result`. The types must be the concrete ones of the call;
/// the `from`/`to` carried by conversion intrinsics are not consulted.
///
/// SPLIT_DATE, SPLIT_TOD and SPLIT_DT have outputs instead of a result:
/// [`split`] gives them all; here, called with the value and a field's
/// index `k` (a LINT), they give field `k` (as a LINT), which is how a
/// program computes them (`stc_ir`'s lowering of a SPLIT call).
pub fn call(
    f: Intrinsic,
    arg_types: &[ElemType],
    args: &[Value],
    result: ElemType,
) -> Result<Outcome, Fault> {
    use Intrinsic as I;
    if arg_types.len() != args.len() || args.is_empty() {
        return misuse();
    }
    let t0 = arg_types[0];
    let a0 = &args[0];
    let exact = |v: Value| Ok(Outcome::exact(v));
    match f {
        // Numeric functions.
        I::Abs => match a0 {
            Value::Int(a) if is_int_like(t0) => {
                Ok(wrapped(result, a.checked_abs(), a.wrapping_abs()))
            }
            Value::Real(x) if is_real(result) => exact(Value::Real(round_to(result, x.abs()))),
            _ => misuse(),
        },
        I::Sqrt => math(result, a0, f64::sqrt),
        I::Ln => math(result, a0, f64::ln),
        I::Log => math(result, a0, f64::log10),
        I::Exp => math(result, a0, f64::exp),
        I::Sin => math(result, a0, f64::sin),
        I::Cos => math(result, a0, f64::cos),
        I::Tan => math(result, a0, f64::tan),
        I::Asin => math(result, a0, f64::asin),
        I::Acos => math(result, a0, f64::acos),
        I::Atan => math(result, a0, f64::atan),
        I::Atan2 => {
            let [y, x] = two(args)?;
            if !is_real(result) {
                return misuse();
            }
            exact(Value::Real(round_to(result, real(y)?.atan2(real(x)?))))
        }
        I::Expt => {
            let [b, e] = two(args)?;
            binary(BinOp::Pow, t0, b, arg_types[1], e, result)
        }

        // Bit shifts.
        I::Shl | I::Shr | I::Rol | I::Ror => {
            let [v, n] = two(args)?;
            shift(f, t0, int(v)?, int(n)?)
        }

        // Selection.
        I::Sel => {
            let [g, in0, in1] = three(args)?;
            let g = g.as_bool().ok_or(Fault::Conversion)?;
            exact(if g { in1.clone() } else { in0.clone() })
        }
        I::Max | I::Min => {
            let want = if f == I::Max {
                Ordering::Greater
            } else {
                Ordering::Less
            };
            let mut best = a0;
            for v in &args[1..] {
                best = pick(best, v, want)?;
            }
            exact(best.clone())
        }
        I::Limit => {
            let [mn, x, mx] = three(args)?;
            let low = pick(x, mn, Ordering::Greater)?;
            exact(pick(low, mx, Ordering::Less)?.clone())
        }
        I::Mux => {
            let k = int(a0)?;
            let inputs = &args[1..];
            usize::try_from(k)
                .ok()
                .and_then(|k| inputs.get(k))
                .map(|v| Outcome::exact(v.clone()))
                .ok_or(Fault::MuxRange)
        }
        I::Move => exact(a0.clone()),

        // Strings.
        I::Len => {
            let n = str_len(a0)?;
            Ok(wrapped(result, Some(n), n))
        }
        I::Left => {
            let [s, l] = two(args)?;
            let l = int(l)?;
            exact(slice_str(s, |len| (0, clamp(l, len)))?)
        }
        I::Right => {
            let [s, l] = two(args)?;
            let l = int(l)?;
            exact(slice_str(s, |len| (len - clamp(l, len), len))?)
        }
        I::Mid => {
            let [s, l, p] = three(args)?;
            let (l, p) = (int(l)?, int(p)?);
            exact(slice_str(s, |len| mid_range(len, l, p))?)
        }
        I::Concat => concat(args).map(Outcome::exact),
        I::Insert => {
            let [a, b, p] = three(args)?;
            let p = int(p)?;
            exact(replace_str(a, b, |len| {
                let at = clamp(p, len);
                (at, at)
            })?)
        }
        I::Delete => {
            let [s, l, p] = three(args)?;
            let (l, p) = (int(l)?, int(p)?);
            let nothing = match s {
                Value::WStr(_) => Value::WStr(Vec::new()),
                _ => Value::Str(Vec::new()),
            };
            exact(replace_str(s, &nothing, |len| delete_range(len, l, p))?)
        }
        I::Replace => {
            let [a, b, l, p] = four(args)?;
            let (l, p) = (int(l)?, int(p)?);
            exact(replace_str(a, b, |len| replace_range(len, l, p))?)
        }
        I::Find => {
            let [a, b] = two(args)?;
            let n = find(a, b)?;
            Ok(wrapped(result, Some(n), n))
        }

        // Time and date.
        I::AddTime | I::AddTodTime | I::AddDtTime => {
            let [a, b] = two(args)?;
            binary(BinOp::Add, t0, a, arg_types[1], b, result)
        }
        I::SubTime | I::SubTodTime | I::SubDtTime | I::SubDateDate | I::SubTodTod | I::SubDtDt => {
            let [a, b] = two(args)?;
            binary(BinOp::Sub, t0, a, arg_types[1], b, result)
        }
        I::MulTime => {
            let [a, b] = two(args)?;
            binary(BinOp::Mul, t0, a, arg_types[1], b, result)
        }
        I::DivTime => {
            let [a, b] = two(args)?;
            binary(BinOp::Div, t0, a, arg_types[1], b, result)
        }
        I::ConcatDateTod => {
            let [d, t] = two(args)?;
            let tod = int(t)?;
            let ns = int(d)?
                .checked_mul(NS_PER_S)
                .and_then(|x| x.checked_add(tod))
                .ok_or(Fault::Conversion)?;
            exact(Value::Int(in_i64(ns)?))
        }
        I::ConcatDate => {
            let [y, m, d] = three(args)?;
            let days = civil_days(int(y)?, int(m)?, int(d)?)?;
            exact(Value::Int(days * SECS_PER_DAY))
        }
        I::ConcatTod => {
            let [h, m, s, ms] = four(args)?;
            exact(Value::Int(tod_ns(int(h)?, int(m)?, int(s)?, int(ms)?)?))
        }
        I::ConcatDt => {
            let [y, mo, d, h, mi, s, ms] = seven(args)?;
            let days = civil_days(int(y)?, int(mo)?, int(d)?)?;
            let tod = tod_ns(int(h)?, int(mi)?, int(s)?, int(ms)?)?;
            exact(Value::Int(in_i64(days * NS_PER_D + tod)?))
        }
        I::DayOfWeek => {
            // 1970-01-01 was a Thursday (4); 0 is Sunday.
            let days = int(a0)?.div_euclid(SECS_PER_DAY);
            let dow = (days.rem_euclid(7) + 4) % 7;
            Ok(wrapped(result, Some(dow), dow))
        }
        // One field of [`split`]: the value and the field's index.
        I::SplitDate | I::SplitTod | I::SplitDt => match args {
            [v, k] => {
                let fields = split(f, t0, v)?;
                let k = usize::try_from(int(k)?).map_err(|_| Fault::Conversion)?;
                let field = *fields.get(k).ok_or(Fault::Conversion)?;
                exact(Value::Int(field))
            }
            _ => misuse(),
        },

        // Conversions.
        I::Convert { .. } => convert(t0, result, a0).map(Outcome::exact),
        I::Trunc { .. } => trunc(t0, result, a0).map(Outcome::exact),
        I::BcdToInt { .. } => bcd_to_int(t0, result, a0).map(Outcome::exact),
        I::IntToBcd { .. } => int_to_bcd(t0, result, a0).map(Outcome::exact),

        // Operator functions.
        I::Add | I::Mul | I::And | I::Or | I::Xor => {
            let op = match f {
                I::Add => BinOp::Add,
                I::Mul => BinOp::Mul,
                I::And => BinOp::And,
                I::Or => BinOp::Or,
                _ => BinOp::Xor,
            };
            if args.len() < 2 {
                return misuse();
            }
            let mut acc = Outcome::exact(a0.clone());
            let mut acc_ty = t0;
            for (t, v) in arg_types.iter().zip(args).skip(1) {
                let next = binary(op, acc_ty, &acc.value, *t, v, result)?;
                acc = Outcome {
                    value: next.value,
                    overflow: acc.overflow || next.overflow,
                };
                acc_ty = result;
            }
            Ok(acc)
        }
        I::Sub | I::Div | I::Mod => {
            let [a, b] = two(args)?;
            let op = match f {
                I::Sub => BinOp::Sub,
                I::Div => BinOp::Div,
                _ => BinOp::Mod,
            };
            binary(op, t0, a, arg_types[1], b, result)
        }
        I::Not => unary(UnOp::Not, t0, a0),
        I::Gt | I::Ge | I::Eq | I::Le | I::Lt => {
            let op = match f {
                I::Gt => BinOp::Gt,
                I::Ge => BinOp::Ge,
                I::Eq => BinOp::Eq,
                I::Le => BinOp::Le,
                _ => BinOp::Lt,
            };
            if args.len() < 2 {
                return misuse();
            }
            // GT(a, b, c) is a > b AND b > c: a monotonic chain.
            let mut all = true;
            for i in 1..args.len() {
                let o = binary(
                    op,
                    arg_types[i - 1],
                    &args[i - 1],
                    arg_types[i],
                    &args[i],
                    E::Bool,
                )?;
                all &= o.value == Value::Bool(true);
            }
            exact(Value::Bool(all))
        }
        I::Ne => {
            let [a, b] = two(args)?;
            binary(BinOp::Ne, t0, a, arg_types[1], b, E::Bool)
        }
    }
}

fn wrapped(t: ElemType, exact: Option<i128>, raw: i128) -> Outcome {
    let v = wrap(t, raw);
    Outcome {
        value: Value::Int(v),
        overflow: exact != Some(v),
    }
}

fn two(args: &[Value]) -> Result<[&Value; 2], Fault> {
    match args {
        [a, b] => Ok([a, b]),
        _ => misuse(),
    }
}

fn three(args: &[Value]) -> Result<[&Value; 3], Fault> {
    match args {
        [a, b, c] => Ok([a, b, c]),
        _ => misuse(),
    }
}

fn four(args: &[Value]) -> Result<[&Value; 4], Fault> {
    match args {
        [a, b, c, d] => Ok([a, b, c, d]),
        _ => misuse(),
    }
}

fn seven(args: &[Value]) -> Result<[&Value; 7], Fault> {
    match args {
        [a, b, c, d, e, f, g] => Ok([a, b, c, d, e, f, g]),
        _ => misuse(),
    }
}

/// A REAL/LREAL function computed in f64 (the platform's libm, as the C back
/// end's `<math.h>`) and rounded to the result type.
fn math(result: ElemType, v: &Value, f: fn(f64) -> f64) -> Result<Outcome, Fault> {
    if !is_real(result) {
        return misuse();
    }
    Ok(Outcome::exact(Value::Real(round_to(result, f(real(v)?)))))
}

/// MAX/MIN step: `candidate` replaces `best` only when it compares strictly
/// `want` (so a NaN never replaces, and never is replaced: like C's
/// `b > a ? b : a`).
fn pick<'a>(best: &'a Value, candidate: &'a Value, want: Ordering) -> Result<&'a Value, Fault> {
    Ok(if compare(candidate, best)? == Some(want) {
        candidate
    } else {
        best
    })
}

/// SHL/SHR/ROL/ROR on the bit pattern of `t`'s width. A count at or above
/// the width shifts everything out; rotations go modulo the width; a
/// negative count shifts or rotates the other way.
fn shift(f: Intrinsic, t: ElemType, v: i128, n: i128) -> Result<Outcome, Fault> {
    if !(is_bit_string(t) || is_int_like(t)) {
        return misuse();
    }
    let w = bits(t);
    let mask: u128 = (1u128 << w) - 1;
    let u = (v as u128) & mask;
    let left = matches!(f, Intrinsic::Shl | Intrinsic::Rol) == (n >= 0);
    let out = match f {
        Intrinsic::Shl | Intrinsic::Shr => {
            let count = n.unsigned_abs();
            if count >= u128::from(w) {
                0
            } else if left {
                (u << count) & mask
            } else {
                u >> count
            }
        }
        _ => {
            // Rotating left by k is rotating right by w - k.
            let k = n.rem_euclid(i128::from(w)) as u32;
            let k = if matches!(f, Intrinsic::Rol) {
                k
            } else {
                (w - k) % w
            };
            if k == 0 {
                u
            } else {
                ((u << k) | (u >> (w - k))) & mask
            }
        }
    };
    let value = if t == E::Bool {
        Value::Bool(out != 0)
    } else {
        Value::Int(wrap(t, out as i128))
    };
    Ok(Outcome::exact(value))
}

/// `x` clamped into `0..=max`.
fn clamp(x: i128, max: usize) -> usize {
    if x <= 0 {
        0
    } else {
        usize::try_from(x).map_or(max, |x| x.min(max))
    }
}

/// MID: `l` characters from position `p` (1-based; `p < 1` counts as 1),
/// cut at the end; empty when `l <= 0` or `p` is past the end.
fn mid_range(len: usize, l: i128, p: i128) -> (usize, usize) {
    let start = clamp(p.max(1) - 1, len);
    (start, start + clamp(l, len - start))
}

/// DELETE: the 0-based half-open range of characters removed: `l` from
/// position `p` (`p < 1` counts as 1), cut at the end; empty when `l <= 0`
/// or `p` is past the end.
fn delete_range(len: usize, l: i128, p: i128) -> (usize, usize) {
    let start = clamp(p.max(1) - 1, len);
    let end = start + clamp(l, len - start);
    (start, end)
}

/// REPLACE: like DELETE, and IN2 goes where the deleted characters were
/// (at the end when `p` is past it).
fn replace_range(len: usize, l: i128, p: i128) -> (usize, usize) {
    delete_range(len, l, p)
}

fn str_len(v: &Value) -> Result<i128, Fault> {
    match v {
        Value::Str(s) => Ok(s.len() as i128),
        Value::WStr(s) => Ok(s.len() as i128),
        _ => misuse(),
    }
}

/// The characters `start..end` of a STRING or WSTRING, where
/// `(start, end) = range(LEN(v))` (clamped to the string, never panicking).
fn slice_str(v: &Value, range: impl Fn(usize) -> (usize, usize)) -> Result<Value, Fault> {
    fn cut<T: Copy>(s: &[T], (start, end): (usize, usize)) -> Vec<T> {
        s.iter().copied().take(end).skip(start).collect()
    }
    match v {
        Value::Str(s) => Ok(Value::Str(cut(s, range(s.len())))),
        Value::WStr(s) => Ok(Value::WStr(cut(s, range(s.len())))),
        _ => misuse(),
    }
}

/// `a[..start] & b & a[end..]` where `(start, end) = range(LEN(a))`.
fn replace_str(
    a: &Value,
    b: &Value,
    range: impl Fn(usize) -> (usize, usize),
) -> Result<Value, Fault> {
    fn join<T: Copy>(a: &[T], b: &[T], (start, end): (usize, usize)) -> Vec<T> {
        let mut out = Vec::with_capacity(a.len() + b.len());
        out.extend(a.iter().copied().take(start));
        out.extend_from_slice(b);
        out.extend(a.iter().copied().skip(end));
        out
    }
    match (a, b) {
        (Value::Str(a), Value::Str(b)) => Ok(Value::Str(join(a, b, range(a.len())))),
        (Value::WStr(a), Value::WStr(b)) => Ok(Value::WStr(join(a, b, range(a.len())))),
        _ => misuse(),
    }
}

fn concat(args: &[Value]) -> Result<Value, Fault> {
    match args.first() {
        Some(Value::Str(_)) => {
            let mut out = Vec::new();
            for a in args {
                match a {
                    Value::Str(s) => out.extend_from_slice(s),
                    _ => return misuse(),
                }
            }
            Ok(Value::Str(out))
        }
        Some(Value::WStr(_)) => {
            let mut out = Vec::new();
            for a in args {
                match a {
                    Value::WStr(s) => out.extend_from_slice(s),
                    _ => return misuse(),
                }
            }
            Ok(Value::WStr(out))
        }
        _ => misuse(),
    }
}

/// FIND: the 1-based position of the first occurrence of `b` in `a`; 0 when
/// there is none or `b` is empty.
fn find(a: &Value, b: &Value) -> Result<i128, Fault> {
    fn first<T: PartialEq>(a: &[T], b: &[T]) -> i128 {
        if b.is_empty() {
            return 0;
        }
        a.windows(b.len())
            .position(|w| w == b)
            .map_or(0, |i| i as i128 + 1)
    }
    match (a, b) {
        (Value::Str(a), Value::Str(b)) => Ok(first(a, b)),
        (Value::WStr(a), Value::WStr(b)) => Ok(first(a, b)),
        _ => misuse(),
    }
}

fn in_i64(n: i128) -> Result<i128, Fault> {
    if (i64::MIN as i128..=i64::MAX as i128).contains(&n) {
        Ok(n)
    } else {
        Err(Fault::Conversion)
    }
}

fn days_in_month(y: i128, m: i128) -> i128 {
    match m {
        1 | 3 | 5 | 7 | 8 | 10 | 12 => 31,
        4 | 6 | 9 | 11 => 30,
        _ if (y % 4 == 0 && y % 100 != 0) || y % 400 == 0 => 29,
        _ => 28,
    }
}

/// Days since 1970-01-01 of a valid date: years 0..=9999 (those a date
/// literal can write), months 1..=12, days of that month.
fn civil_days(y: i128, m: i128, d: i128) -> Result<i128, Fault> {
    if !(0..=9999).contains(&y) || !(1..=12).contains(&m) || !(1..=days_in_month(y, m)).contains(&d)
    {
        return Err(Fault::Conversion);
    }
    // In range, so the narrowing cannot fail.
    let (y, m, d) = (y as i64, m as u32, d as u32);
    Ok(days_from_civil(y, m, d).into())
}

/// Nanoseconds since midnight of a valid time of day.
fn tod_ns(h: i128, m: i128, s: i128, ms: i128) -> Result<i128, Fault> {
    if !(0..24).contains(&h)
        || !(0..60).contains(&m)
        || !(0..60).contains(&s)
        || !(0..1000).contains(&ms)
    {
        return Err(Fault::Conversion);
    }
    Ok(h * NS_PER_H + m * NS_PER_M + s * NS_PER_S + ms * NS_PER_MS)
}

/// SPLIT_DATE, SPLIT_TOD, SPLIT_DT (and the L variants) by name: the
/// intrinsic, the type of the input `IN`, and the names of the outputs, in
/// order (each an ANY_INT output parameter).
pub fn split_lookup(name: &str) -> Option<(Intrinsic, ElemType, &'static [&'static str])> {
    const DATE: &[&str] = &["YEAR", "MONTH", "DAY"];
    const TOD: &[&str] = &["HOUR", "MINUTE", "SECOND", "MILLISECOND"];
    const DT: &[&str] = &[
        "YEAR",
        "MONTH",
        "DAY",
        "HOUR",
        "MINUTE",
        "SECOND",
        "MILLISECOND",
    ];
    Some(match name.to_ascii_uppercase().as_str() {
        "SPLIT_DATE" => (Intrinsic::SplitDate, E::Date, DATE),
        "SPLIT_TOD" => (Intrinsic::SplitTod, E::Tod, TOD),
        "SPLIT_LTOD" => (Intrinsic::SplitTod, E::Ltod, TOD),
        "SPLIT_DT" => (Intrinsic::SplitDt, E::Dt, DT),
        "SPLIT_LDT" => (Intrinsic::SplitDt, E::Ldt, DT),
        _ => return None,
    })
}

/// The output values of SPLIT_DATE (year, month, day), SPLIT_TOD (hour,
/// minute, second, millisecond) or SPLIT_DT (all seven) for a value of type
/// `t`; sub-millisecond parts are dropped.
pub fn split(f: Intrinsic, t: ElemType, v: &Value) -> Result<Vec<i128>, Fault> {
    let n = int(v)?;
    let date_fields = |days: i128| -> Result<Vec<i128>, Fault> {
        let days = i64::try_from(days).map_err(|_| Fault::Conversion)?;
        if days.unsigned_abs() > 1 << 50 {
            return Err(Fault::Conversion);
        }
        let (y, m, d) = civil_from_days(days);
        Ok(vec![y.into(), m.into(), d.into()])
    };
    let tod_fields = |ns: i128| {
        vec![
            ns / NS_PER_H,
            ns / NS_PER_M % 60,
            ns / NS_PER_S % 60,
            ns / NS_PER_MS % 1000,
        ]
    };
    match f {
        Intrinsic::SplitDate if matches!(t, E::Date | E::Ldate) => {
            date_fields(n.div_euclid(SECS_PER_DAY))
        }
        Intrinsic::SplitTod if matches!(t, E::Tod | E::Ltod) => {
            Ok(tod_fields(n.rem_euclid(NS_PER_D)))
        }
        Intrinsic::SplitDt if matches!(t, E::Dt | E::Ldt) => {
            let mut out = date_fields(n.div_euclid(NS_PER_D))?;
            out.extend(tod_fields(n.rem_euclid(NS_PER_D)));
            Ok(out)
        }
        _ => misuse(),
    }
}
