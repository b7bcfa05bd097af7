//! The operators of ST on elementary values (spec/semantics.md
//! "Arithmetic"): integer arithmetic wraps in two's complement and reports
//! the wrap; REAL is IEEE binary32 (every result rounded to f32), LREAL
//! binary64; comparisons work on every elementary type; the time operators
//! are those of the standard's table of time functions.

use crate::convert::{f64_to_ns, int, real, round_to};
use crate::types::{is_date, is_dt, is_duration, is_int_like, is_real, is_time_like, is_tod, wrap};
use crate::{misuse, BinOp, Fault, Outcome, UnOp, Value};
use stc_syntax::literal::{NS_PER_D, NS_PER_S};
use stc_syntax::token::ElemType;
use std::cmp::Ordering;

/// `lhs op rhs`.
///
/// `lhs_ty` and `rhs_ty` are the operand types: the same type (the analyser
/// has inserted the implicit conversions) except for the time operators and
/// for `**`, whose exponent may be any number. `result` is the result type.
///
/// - `+ - * / MOD` on integer types wrap into `result` (`overflow` tells
///   whether they did); `/` truncates toward zero; `MOD` has the sign of the
///   dividend; a zero divisor is [`Fault::DivisionByZero`].
/// - `+ - * /` on REAL/LREAL follow IEEE 754 (a zero divisor gives ±INF or
///   NaN, never a fault); REAL results are rounded to f32.
/// - `**` takes a REAL/LREAL base and any numeric exponent, is computed by
///   `f64::powf` (the platform's `pow`) and rounded to `result`.
/// - `AND OR XOR` on BOOL and bit strings.
/// - `= <> < <= > >=` on every elementary type: numbers by value, BOOL with
///   FALSE < TRUE, strings lexicographically by byte / code unit, time-like
///   types by their count; a comparison with a REAL NaN is false except `<>`.
/// - Time: TIME±TIME, TOD±TIME (modulo 24 h), DT±TIME, DATE-DATE, TOD-TOD,
///   DT-DT (all giving TIME), TIME*ANY_NUM, ANY_NUM*TIME, TIME/ANY_NUM, and
///   the L variants. An integer factor wraps, an integer divisor truncates
///   (zero faults); a real factor or divisor is applied in LREAL and the
///   result rounded to the nearest nanosecond, ties to even (NaN or out of
///   range is [`Fault::Conversion`]).
pub fn binary(
    op: BinOp,
    lhs_ty: ElemType,
    lhs: &Value,
    rhs_ty: ElemType,
    rhs: &Value,
    result: ElemType,
) -> Result<Outcome, Fault> {
    use BinOp::*;
    match op {
        Eq | Ne | Lt | Le | Gt | Ge => {
            let ord = compare(lhs, rhs)?;
            let b = match op {
                Eq => ord == Some(Ordering::Equal),
                Ne => ord != Some(Ordering::Equal),
                Lt => ord == Some(Ordering::Less),
                Le => matches!(ord, Some(Ordering::Less | Ordering::Equal)),
                Gt => ord == Some(Ordering::Greater),
                _ => matches!(ord, Some(Ordering::Greater | Ordering::Equal)),
            };
            Ok(Outcome::exact(Value::Bool(b)))
        }
        And | Or | Xor => logic(op, lhs, rhs, result),
        Add | Sub | Mul | Div | Mod | Pow => {
            if is_time_like(lhs_ty) || is_time_like(rhs_ty) {
                time_arith(op, lhs_ty, lhs, rhs_ty, rhs, result)
            } else if is_real(lhs_ty) || is_real(rhs_ty) || op == Pow {
                real_arith(op, lhs, rhs, result)
            } else if is_int_like(result) {
                int_arith(op, result, int(lhs)?, int(rhs)?)
            } else {
                misuse()
            }
        }
    }
}

/// `op v`: `-` on integers (wrapping: `-MIN` is `MIN` with `overflow`),
/// REAL/LREAL and TIME/LTIME; `NOT` on BOOL and bit strings (bitwise within
/// the width; on a signed integer type, the two's-complement complement).
pub fn unary(op: UnOp, ty: ElemType, v: &Value) -> Result<Outcome, Fault> {
    match (op, v) {
        (UnOp::Neg, Value::Real(x)) => Ok(Outcome::exact(Value::Real(-x))),
        (UnOp::Neg, Value::Int(a)) if is_int_like(ty) || is_duration(ty) => {
            let exact = a.checked_neg();
            Ok(wrapped(ty, exact, a.wrapping_neg()))
        }
        (UnOp::Not, Value::Bool(b)) => Ok(Outcome::exact(Value::Bool(!b))),
        (UnOp::Not, Value::Int(a)) if is_int_like(ty) => {
            Ok(Outcome::exact(Value::Int(wrap(ty, !a))))
        }
        _ => misuse(),
    }
}

/// The outcome of an integer computation: `raw` wrapped into `t`, with
/// `overflow` unless the exact result (`None` when even i128 overflowed)
/// already was in range.
fn wrapped(t: ElemType, exact: Option<i128>, raw: i128) -> Outcome {
    let v = wrap(t, raw);
    Outcome {
        value: Value::Int(v),
        overflow: exact != Some(v),
    }
}

fn int_arith(op: BinOp, t: ElemType, a: i128, b: i128) -> Result<Outcome, Fault> {
    let (exact, raw) = match op {
        BinOp::Add => (a.checked_add(b), a.wrapping_add(b)),
        BinOp::Sub => (a.checked_sub(b), a.wrapping_sub(b)),
        BinOp::Mul => (a.checked_mul(b), a.wrapping_mul(b)),
        BinOp::Div | BinOp::Mod if b == 0 => return Err(Fault::DivisionByZero),
        // Rust's `/` truncates toward zero and `%` has the dividend's sign.
        BinOp::Div => (a.checked_div(b), a.wrapping_div(b)),
        BinOp::Mod => (a.checked_rem(b), a.wrapping_rem(b)),
        _ => return misuse(),
    };
    Ok(wrapped(t, exact, raw))
}

fn real_arith(op: BinOp, lhs: &Value, rhs: &Value, result: ElemType) -> Result<Outcome, Fault> {
    if !is_real(result) {
        return misuse();
    }
    let a = real(lhs)?;
    let x = match op {
        BinOp::Pow => {
            let e = match rhs {
                Value::Real(e) => *e,
                Value::Int(e) => *e as f64,
                _ => return misuse(),
            };
            a.powf(e)
        }
        BinOp::Add => a + real(rhs)?,
        BinOp::Sub => a - real(rhs)?,
        BinOp::Mul => a * real(rhs)?,
        BinOp::Div => a / real(rhs)?,
        _ => return misuse(),
    };
    Ok(Outcome::exact(Value::Real(round_to(result, x))))
}

fn logic(op: BinOp, lhs: &Value, rhs: &Value, result: ElemType) -> Result<Outcome, Fault> {
    match (lhs, rhs) {
        (Value::Bool(a), Value::Bool(b)) => Ok(Outcome::exact(Value::Bool(match op {
            BinOp::And => a & b,
            BinOp::Or => a | b,
            _ => a ^ b,
        }))),
        (Value::Int(a), Value::Int(b)) if is_int_like(result) => {
            let v = match op {
                BinOp::And => a & b,
                BinOp::Or => a | b,
                _ => a ^ b,
            };
            Ok(Outcome::exact(Value::Int(wrap(result, v))))
        }
        _ => misuse(),
    }
}

/// The order of two values of the same type; `None` when a REAL is NaN.
pub(crate) fn compare(lhs: &Value, rhs: &Value) -> Result<Option<Ordering>, Fault> {
    Ok(match (lhs, rhs) {
        (Value::Bool(a), Value::Bool(b)) => Some(a.cmp(b)),
        (Value::Int(a), Value::Int(b)) => Some(a.cmp(b)),
        (Value::Real(a), Value::Real(b)) => a.partial_cmp(b),
        (Value::Str(a), Value::Str(b)) => Some(a.cmp(b)),
        (Value::WStr(a), Value::WStr(b)) => Some(a.cmp(b)),
        _ => return misuse(),
    })
}

fn time_arith(
    op: BinOp,
    lt: ElemType,
    lhs: &Value,
    rt: ElemType,
    rhs: &Value,
    result: ElemType,
) -> Result<Outcome, Fault> {
    use BinOp::*;
    let dur = is_duration;
    match op {
        Add | Sub if dur(lt) && dur(rt) => {
            let (a, b) = (int(lhs)?, int(rhs)?);
            Ok(plus_minus(op, result, a, b))
        }
        Add | Sub if (is_tod(lt) && dur(rt)) => {
            let (a, b) = (int(lhs)?, int(rhs)?);
            let v = if op == Add {
                a.wrapping_add(b)
            } else {
                a.wrapping_sub(b)
            };
            Ok(Outcome::exact(Value::Int(v.rem_euclid(NS_PER_D))))
        }
        Add | Sub if (is_dt(lt) && dur(rt)) => {
            let (a, b) = (int(lhs)?, int(rhs)?);
            Ok(plus_minus(op, result, a, b))
        }
        Sub if is_date(lt) && is_date(rt) => {
            let secs = int(lhs)?.wrapping_sub(int(rhs)?);
            let ns = secs.checked_mul(NS_PER_S);
            Ok(wrapped(result, ns, secs.wrapping_mul(NS_PER_S)))
        }
        Sub if (is_tod(lt) && is_tod(rt)) || (is_dt(lt) && is_dt(rt)) => {
            let (a, b) = (int(lhs)?, int(rhs)?);
            Ok(plus_minus(Sub, result, a, b))
        }
        Mul if dur(lt) && !is_time_like(rt) => scale(Mul, int(lhs)?, rhs, result),
        Mul if dur(rt) && !is_time_like(lt) => scale(Mul, int(rhs)?, lhs, result),
        Div if dur(lt) && !is_time_like(rt) => scale(Div, int(lhs)?, rhs, result),
        _ => misuse(),
    }
}

fn plus_minus(op: BinOp, t: ElemType, a: i128, b: i128) -> Outcome {
    if op == BinOp::Add {
        wrapped(t, a.checked_add(b), a.wrapping_add(b))
    } else {
        wrapped(t, a.checked_sub(b), a.wrapping_sub(b))
    }
}

/// A duration times or divided by a number.
fn scale(op: BinOp, ns: i128, k: &Value, result: ElemType) -> Result<Outcome, Fault> {
    match k {
        Value::Int(k) => int_arith(op, result, ns, *k),
        Value::Real(f) => {
            let x = if op == BinOp::Mul {
                ns as f64 * f
            } else {
                ns as f64 / f
            };
            Ok(Outcome::exact(Value::Int(f64_to_ns(x)?)))
        }
        _ => misuse(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use ElemType as E;

    fn i(n: i128) -> Value {
        Value::Int(n)
    }

    fn r(x: f64) -> Value {
        Value::Real(x)
    }

    fn int_op(op: BinOp, t: ElemType, a: i128, b: i128) -> Result<(i128, bool), Fault> {
        binary(op, t, &i(a), t, &i(b), t)
            .map(|o| (o.value.as_int().unwrap_or(i128::MIN), o.overflow))
    }

    #[test]
    fn integer_arithmetic_wraps_and_reports() {
        use BinOp::*;
        let cases: &[(BinOp, ElemType, i128, i128, i128, bool)] = &[
            (Add, E::Int, 32767, 1, -32768, true),
            (Add, E::Int, 1, 2, 3, false),
            (Sub, E::Int, -32768, 1, 32767, true),
            (Mul, E::Int, 256, 256, 0, true),
            (Mul, E::Sint, -8, 16, -128, false),
            (Add, E::Usint, 255, 1, 0, true),
            (Sub, E::Usint, 0, 1, 255, true),
            (Sub, E::Udint, 0, 1, u32::MAX as i128, true),
            (Mul, E::Ulint, u64::MAX as i128, u64::MAX as i128, 1, true),
            (Mul, E::Lint, i64::MIN as i128, -1, i64::MIN as i128, true),
            (Add, E::Lint, i64::MAX as i128, 1, i64::MIN as i128, true),
            (Div, E::Int, 7, 2, 3, false),
            (Div, E::Int, -7, 2, -3, false),
            (Div, E::Int, 7, -2, -3, false),
            (Div, E::Int, -32768, -1, -32768, true),
            (Div, E::Lint, i64::MIN as i128, -1, i64::MIN as i128, true),
            (Mod, E::Int, -7, 2, -1, false),
            (Mod, E::Int, 7, -2, 1, false),
            (Mod, E::Int, -7, -2, -1, false),
            (Mod, E::Int, -32768, -1, 0, false),
            (Mod, E::Dint, 10, 3, 1, false),
            (Add, E::Word, 65535, 1, 0, true),
        ];
        for &(op, t, a, b, want, ov) in cases {
            assert_eq!(int_op(op, t, a, b), Ok((want, ov)), "{op:?} {t:?} {a} {b}");
        }
        assert_eq!(int_op(Div, E::Int, 1, 0), Err(Fault::DivisionByZero));
        assert_eq!(int_op(Mod, E::Usint, 1, 0), Err(Fault::DivisionByZero));
        // Wrap-around far outside i64: i128 overflow is still reported.
        let big = i128::MAX;
        assert_eq!(int_op(Add, E::Lint, big, 1).map(|x| x.1), Ok(true));
        assert_eq!(int_op(Mul, E::Lint, big, big).map(|x| x.1), Ok(true));
    }

    #[test]
    fn real_arithmetic_is_ieee() {
        let f = |op, t, a: f64, b: f64| binary(op, t, &r(a), t, &r(b), t).map(|o| o.value);
        let third = (1.0f32 / 3.0f32) as f64;
        assert_eq!(f(BinOp::Div, E::Real, 1.0, 3.0), Ok(r(third)));
        assert_eq!(f(BinOp::Div, E::Lreal, 1.0, 3.0), Ok(r(1.0 / 3.0)));
        assert_eq!(
            f(BinOp::Add, E::Real, 0.1f32 as f64, 0.2f32 as f64),
            Ok(r((0.1f32 + 0.2f32) as f64))
        );
        assert_eq!(f(BinOp::Div, E::Real, 1.0, 0.0), Ok(r(f64::INFINITY)));
        assert_eq!(f(BinOp::Div, E::Lreal, -1.0, 0.0), Ok(r(f64::NEG_INFINITY)));
        assert!(
            f(BinOp::Div, E::Lreal, 0.0, 0.0).is_ok_and(|v| v.as_real().is_some_and(f64::is_nan))
        );
        assert_eq!(f(BinOp::Mul, E::Real, 3e38, 10.0), Ok(r(f64::INFINITY)));
        assert_eq!(f(BinOp::Mod, E::Real, 3.0, 2.0), Err(Fault::Conversion));
        assert_eq!(
            binary(BinOp::Add, E::Real, &r(1.0), E::Real, &r(1.0), E::Int),
            Err(Fault::Conversion)
        );
    }

    #[test]
    fn power() {
        let p = |bt, b: Value, et, e: Value, rt| {
            binary(BinOp::Pow, bt, &b, et, &e, rt).map(|o| o.value)
        };
        assert_eq!(p(E::Lreal, r(2.0), E::Int, i(10), E::Lreal), Ok(r(1024.0)));
        assert_eq!(
            p(E::Lreal, r(2.0), E::Lreal, r(0.5), E::Lreal),
            Ok(r(2f64.sqrt()))
        );
        assert_eq!(
            p(E::Real, r(2.0), E::Real, r(0.5), E::Real),
            Ok(r(2f64.sqrt() as f32 as f64))
        );
        assert_eq!(
            p(E::Lreal, r(0.0), E::Int, i(-1), E::Lreal),
            Ok(r(f64::INFINITY))
        );
        assert!(p(E::Lreal, r(-8.0), E::Lreal, r(1.0 / 3.0), E::Lreal)
            .is_ok_and(|v| v.as_real().is_some_and(f64::is_nan)));
        assert_eq!(
            p(E::Real, r(10.0), E::Dint, i(39), E::Real),
            Ok(r(f64::INFINITY))
        );
    }

    #[test]
    fn logic_on_bools_and_bits() {
        let b = |op, x, y| {
            binary(
                op,
                E::Bool,
                &Value::Bool(x),
                E::Bool,
                &Value::Bool(y),
                E::Bool,
            )
            .map(|o| o.value)
        };
        assert_eq!(b(BinOp::And, true, false), Ok(Value::Bool(false)));
        assert_eq!(b(BinOp::Or, true, false), Ok(Value::Bool(true)));
        assert_eq!(b(BinOp::Xor, true, true), Ok(Value::Bool(false)));
        let w = |op, x, y| int_op(op, E::Word, x, y).map(|x| x.0);
        assert_eq!(w(BinOp::And, 0xFF0F, 0x0FF0), Ok(0x0F00));
        assert_eq!(w(BinOp::Or, 0xFF00, 0x000F), Ok(0xFF0F));
        assert_eq!(w(BinOp::Xor, 0xFFFF, 0x0F0F), Ok(0xF0F0));
        assert_eq!(
            binary(
                BinOp::And,
                E::Bool,
                &Value::Bool(true),
                E::Bool,
                &i(1),
                E::Bool
            ),
            Err(Fault::Conversion)
        );
    }

    #[test]
    fn comparisons_on_every_kind() {
        use BinOp::*;
        let c = |op, t, a: &Value, b: &Value| binary(op, t, a, t, b, E::Bool).map(|o| o.value);
        let t = Value::Bool(true);
        let f = Value::Bool(false);
        assert_eq!(c(Lt, E::Bool, &f, &t), Ok(t.clone()));
        assert_eq!(c(Gt, E::Int, &i(-1), &i(1)), Ok(f.clone()));
        assert_eq!(c(Le, E::Int, &i(1), &i(1)), Ok(t.clone()));
        assert_eq!(c(Ge, E::Ulint, &i(u64::MAX as i128), &i(0)), Ok(t.clone()));
        assert_eq!(c(Eq, E::Lreal, &r(0.0), &r(-0.0)), Ok(t.clone()));
        let nan = r(f64::NAN);
        for op in [Eq, Lt, Le, Gt, Ge] {
            assert_eq!(c(op, E::Lreal, &nan, &nan), Ok(f.clone()), "{op:?}");
            assert_eq!(c(op, E::Real, &nan, &r(1.0)), Ok(f.clone()), "{op:?}");
        }
        assert_eq!(c(Ne, E::Lreal, &nan, &nan), Ok(t.clone()));
        let s = Value::string;
        assert_eq!(c(Lt, E::String, &s("abc"), &s("abd")), Ok(t.clone()));
        assert_eq!(c(Lt, E::String, &s("ab"), &s("abc")), Ok(t.clone()));
        assert_eq!(c(Lt, E::String, &s(""), &s("a")), Ok(t.clone()));
        assert_eq!(c(Lt, E::String, &s("Z"), &s("a")), Ok(t.clone()));
        assert_eq!(
            c(Gt, E::String, &Value::Str(vec![0xE9]), &s("z")),
            Ok(t.clone())
        );
        assert_eq!(c(Eq, E::String, &s("a"), &s("a")), Ok(t.clone()));
        let w = Value::wstring;
        assert_eq!(c(Lt, E::Wstring, &w("a"), &w("\u{20ac}")), Ok(t.clone()));
        assert_eq!(c(Lt, E::Time, &i(-1), &i(0)), Ok(t.clone()));
        assert_eq!(c(Ne, E::Dt, &i(5), &i(5)), Ok(f.clone()));
        assert_eq!(c(Eq, E::Int, &i(1), &r(1.0)), Err(Fault::Conversion));
    }

    const MS: i128 = 1_000_000;
    const S: i128 = 1_000_000_000;

    fn t_op(
        op: BinOp,
        lt: ElemType,
        a: Value,
        rt: ElemType,
        b: Value,
        res: ElemType,
    ) -> Result<Value, Fault> {
        binary(op, lt, &a, rt, &b, res).map(|o| o.value)
    }

    #[test]
    fn time_arithmetic() {
        use BinOp::*;
        assert_eq!(
            t_op(Add, E::Time, i(S), E::Time, i(500 * MS), E::Time),
            Ok(i(1500 * MS))
        );
        assert_eq!(
            t_op(Sub, E::Time, i(S), E::Time, i(2 * S), E::Time),
            Ok(i(-S))
        );
        assert_eq!(
            t_op(Add, E::Ltime, i(1), E::Ltime, i(2), E::Ltime),
            Ok(i(3))
        );
        let o = binary(Add, E::Time, &i(i64::MAX as i128), E::Time, &i(1), E::Time);
        assert_eq!(
            o,
            Ok(Outcome {
                value: i(i64::MIN as i128),
                overflow: true
            })
        );
        // TOD wraps modulo 24 h, without an overflow report.
        let day = NS_PER_D;
        let o = binary(Add, E::Tod, &i(day - S), E::Time, &i(2 * S), E::Tod);
        assert_eq!(o, Ok(Outcome::exact(i(S))));
        assert_eq!(
            t_op(Sub, E::Tod, i(0), E::Time, i(S), E::Tod),
            Ok(i(day - S))
        );
        assert_eq!(
            t_op(Add, E::Tod, i(0), E::Time, i(-3 * day - S), E::Tod),
            Ok(i(day - S))
        );
        assert_eq!(t_op(Add, E::Dt, i(0), E::Time, i(S), E::Dt), Ok(i(S)));
        assert_eq!(t_op(Sub, E::Dt, i(0), E::Time, i(S), E::Dt), Ok(i(-S)));
        assert_eq!(
            t_op(Sub, E::Date, i(86_400), E::Date, i(0), E::Time),
            Ok(i(day))
        );
        assert_eq!(
            t_op(Sub, E::Date, i(0), E::Date, i(86_400), E::Time),
            Ok(i(-day))
        );
        let o = binary(Sub, E::Date, &i(200_000 * 86_400), E::Date, &i(0), E::Time);
        assert!(o.is_ok_and(|o| o.overflow));
        assert_eq!(
            t_op(Sub, E::Tod, i(S), E::Tod, i(3 * S), E::Time),
            Ok(i(-2 * S))
        );
        assert_eq!(
            t_op(Sub, E::Dt, i(5 * S), E::Dt, i(2 * S), E::Time),
            Ok(i(3 * S))
        );
        assert_eq!(t_op(Sub, E::Ldt, i(5), E::Ldt, i(2), E::Ltime), Ok(i(3)));
        assert_eq!(
            t_op(Add, E::Date, i(0), E::Time, i(S), E::Date),
            Err(Fault::Conversion)
        );
        assert_eq!(
            t_op(Add, E::Time, i(0), E::Tod, i(S), E::Tod),
            Err(Fault::Conversion)
        );
    }

    #[test]
    fn time_scaling() {
        use BinOp::*;
        assert_eq!(
            t_op(Mul, E::Time, i(S), E::Int, i(3), E::Time),
            Ok(i(3 * S))
        );
        assert_eq!(
            t_op(Mul, E::Dint, i(3), E::Time, i(S), E::Time),
            Ok(i(3 * S))
        );
        assert_eq!(
            t_op(Div, E::Time, i(S), E::Int, i(3), E::Time),
            Ok(i(333_333_333))
        );
        assert_eq!(
            t_op(Div, E::Time, i(-S), E::Int, i(3), E::Time),
            Ok(i(-333_333_333))
        );
        assert_eq!(
            t_op(Div, E::Time, i(S), E::Int, i(0), E::Time),
            Err(Fault::DivisionByZero)
        );
        let o = binary(Mul, E::Time, &i(i64::MAX as i128), E::Lint, &i(2), E::Time);
        assert_eq!(
            o,
            Ok(Outcome {
                value: i(-2),
                overflow: true
            })
        );
        let o = binary(Div, E::Time, &i(i64::MIN as i128), E::Lint, &i(-1), E::Time);
        assert_eq!(
            o,
            Ok(Outcome {
                value: i(i64::MIN as i128),
                overflow: true
            })
        );
        assert_eq!(
            t_op(Mul, E::Time, i(S), E::Lreal, r(1.5), E::Time),
            Ok(i(1500 * MS))
        );
        assert_eq!(
            t_op(Mul, E::Time, i(3), E::Lreal, r(0.5), E::Time),
            Ok(i(2))
        );
        assert_eq!(
            t_op(Mul, E::Time, i(5), E::Lreal, r(0.5), E::Time),
            Ok(i(2))
        );
        assert_eq!(
            t_op(Mul, E::Time, i(-3), E::Lreal, r(0.5), E::Time),
            Ok(i(-2))
        );
        assert_eq!(
            t_op(Mul, E::Time, i(S), E::Real, r(0.1f32 as f64), E::Time),
            Ok(i(100_000_001))
        );
        assert_eq!(
            t_op(Div, E::Time, i(S), E::Lreal, r(4.0), E::Time),
            Ok(i(250 * MS))
        );
        assert_eq!(
            t_op(Div, E::Time, i(S), E::Lreal, r(0.0), E::Time),
            Err(Fault::Conversion)
        );
        assert_eq!(
            t_op(Div, E::Time, i(0), E::Lreal, r(0.0), E::Time),
            Err(Fault::Conversion)
        );
        assert_eq!(
            t_op(Mul, E::Time, i(S), E::Lreal, r(1e19), E::Time),
            Err(Fault::Conversion)
        );
        assert_eq!(
            t_op(Mul, E::Ltime, i(10), E::Usint, i(3), E::Ltime),
            Ok(i(30))
        );
        assert_eq!(
            t_op(Div, E::Int, i(3), E::Time, i(S), E::Time),
            Err(Fault::Conversion)
        );
    }

    #[test]
    fn unary_operators() {
        let u = |op, t, v: Value| unary(op, t, &v);
        assert_eq!(u(UnOp::Neg, E::Int, i(5)), Ok(Outcome::exact(i(-5))));
        assert_eq!(
            u(UnOp::Neg, E::Int, i(-32768)),
            Ok(Outcome {
                value: i(-32768),
                overflow: true
            })
        );
        assert_eq!(
            u(UnOp::Neg, E::Lint, i(i64::MIN as i128)),
            Ok(Outcome {
                value: i(i64::MIN as i128),
                overflow: true
            })
        );
        assert_eq!(
            u(UnOp::Neg, E::Usint, i(1)),
            Ok(Outcome {
                value: i(255),
                overflow: true
            })
        );
        assert_eq!(u(UnOp::Neg, E::Usint, i(0)), Ok(Outcome::exact(i(0))));
        assert_eq!(u(UnOp::Neg, E::Real, r(1.5)), Ok(Outcome::exact(r(-1.5))));
        assert_eq!(u(UnOp::Neg, E::Time, i(S)), Ok(Outcome::exact(i(-S))));
        assert_eq!(
            u(UnOp::Not, E::Bool, Value::Bool(true)),
            Ok(Outcome::exact(Value::Bool(false)))
        );
        assert_eq!(u(UnOp::Not, E::Byte, i(0x0F)), Ok(Outcome::exact(i(0xF0))));
        assert_eq!(
            u(UnOp::Not, E::Lword, i(0)),
            Ok(Outcome::exact(i(u64::MAX as i128)))
        );
        assert_eq!(u(UnOp::Not, E::Int, i(0)), Ok(Outcome::exact(i(-1))));
        assert_eq!(
            u(UnOp::Neg, E::Bool, Value::Bool(true)),
            Err(Fault::Conversion)
        );
        assert_eq!(u(UnOp::Not, E::Real, r(1.0)), Err(Fault::Conversion));
        assert_eq!(u(UnOp::Neg, E::Date, i(0)), Err(Fault::Conversion));
        assert_eq!(
            u(UnOp::Neg, E::String, Value::string("a")),
            Err(Fault::Conversion)
        );
    }
}
