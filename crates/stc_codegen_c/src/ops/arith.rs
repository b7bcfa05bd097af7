//! The operators: `stc_values::unary` and `stc_values::binary` in C.
//!
//! The common case (operands and result of one type) is one call of an
//! inline function of `stc_rt.h` (`stc_add_i32`), which gcc compiles to
//! the plain instruction; mixed types (which the analyser does not
//! produce, but `stc_values` defines) go through 64-bit patterns.

use super::c::{
    bits64, int_cast, misuse, paren, set, set_checked, signed_flag, wrap_bits, zero, Rep, Val,
};
use super::Emit;
use stc_syntax::token::ElemType;
use stc_values::{is_integer, is_real, is_time_like, BinOp, UnOp};

use ElemType as E;

/// ANY_INT and BYTE..LWORD.
pub(crate) fn int_like(t: ElemType) -> bool {
    is_integer(t) || matches!(t, E::Byte | E::Word | E::Dword | E::Lword)
}

fn is_dur(t: ElemType) -> bool {
    matches!(t, E::Time | E::Ltime)
}

fn is_tod(t: ElemType) -> bool {
    matches!(t, E::Tod | E::Ltod)
}

fn is_dt(t: ElemType) -> bool {
    matches!(t, E::Dt | E::Ldt)
}

fn is_date(t: ElemType) -> bool {
    matches!(t, E::Date | E::Ldate)
}

/// Whether values of the type are `Value::Int` (every scalar but BOOL,
/// the reals and the strings).
pub(crate) fn int_valued(t: ElemType) -> bool {
    !matches!(t, E::Bool | E::Real | E::Lreal | E::String | E::Wstring)
}

/// Whether values of the type are `Value::Int` or `Value::Bool` (what
/// `stc_values`'s `int()` accepts).
pub(crate) fn int_or_bool(t: ElemType) -> bool {
    int_valued(t) || t == E::Bool
}

pub(crate) fn unary(e: &mut dyn Emit, op: UnOp, a: &Val, dst: &Val) {
    let (Some(t), Some(r)) = (a.elem, a.rep()) else {
        return misuse(e, dst);
    };
    let x = match op {
        UnOp::Neg if r.float() => format!("stc_neg_{}({})", r.sfx(), a.x),
        UnOp::Neg if int_like(t) || is_dur(t) => format!("stc_neg_{}({})", r.sfx(), a.x),
        UnOp::Not if t == E::Bool => format!("stc_not_b({})", a.x),
        UnOp::Not if int_like(t) => format!("stc_not_{}({})", r.sfx(), a.x),
        _ => return misuse(e, dst),
    };
    store_same(e, r, &x, dst);
}

/// Stores a value computed in representation `r` into the destination
/// (a plain assignment when the destination has that representation).
fn store_same(e: &mut dyn Emit, r: Rep, x: &str, dst: &Val) {
    match dst.rep() {
        Some(d) if d == r => set(e, dst, x),
        Some(d) if !d.float() && !r.float() => set(e, dst, &int_cast(r, d, x)),
        Some(d) if d.float() && r.float() => set(e, dst, &format!("({}){}", d.ctype(), paren(x))),
        _ => misuse(e, dst),
    }
}

pub(crate) fn binary(e: &mut dyn Emit, op: BinOp, a: &Val, b: &Val, dst: &Val) {
    let (Some(lt), Some(rt), Some(res)) = (a.elem, b.elem, dst.elem) else {
        return misuse(e, dst);
    };
    match op {
        BinOp::Eq | BinOp::Ne | BinOp::Lt | BinOp::Le | BinOp::Gt | BinOp::Ge => {
            compare(e, op, a, b, dst)
        }
        BinOp::And | BinOp::Or | BinOp::Xor => logic(e, op, a, b, dst),
        _ => {
            if is_time_like(lt) || is_time_like(rt) {
                time_arith(e, op, a, b, dst)
            } else if is_real(lt) || is_real(rt) || op == BinOp::Pow {
                real_arith(e, op, a, b, dst)
            } else if int_like(res) && int_or_bool(lt) && int_or_bool(rt) {
                int_arith(e, op, a, b, dst)
            } else {
                misuse(e, dst)
            }
        }
    }
}

fn cmp_sym(op: BinOp) -> &'static str {
    match op {
        BinOp::Eq => "==",
        BinOp::Ne => "!=",
        BinOp::Lt => "<",
        BinOp::Le => "<=",
        BinOp::Gt => ">",
        _ => ">=",
    }
}

fn cmp_name(op: BinOp) -> &'static str {
    match op {
        BinOp::Eq => "eq",
        BinOp::Ne => "ne",
        BinOp::Lt => "lt",
        BinOp::Le => "le",
        BinOp::Gt => "gt",
        _ => "ge",
    }
}

/// The comparison `a op b` as a C expression of value 0 or 1 (`uint8_t`),
/// or `None` when `stc_values::compare` refuses the operands.
pub(crate) fn compare_expr(op: BinOp, a: &Val, b: &Val) -> Option<String> {
    let (lt, rt) = (a.elem?, b.elem?);
    let three_way = |f: &str| Some(format!("(({f}) {} 0) ? 1U : 0U", cmp_sym(op)));
    match (lt, rt) {
        (E::String, E::String) => three_way(&format!("stc_str_cmp({}, {})", a.x, b.x)),
        (E::Wstring, E::Wstring) => three_way(&format!("stc_wstr_cmp({}, {})", a.x, b.x)),
        (E::Bool, E::Bool) => Some(format!("stc_{}_u8({}, {})", cmp_name(op), a.x, b.x)),
        _ if is_real(lt) && is_real(rt) => {
            if lt == rt {
                let r = Rep::of(lt)?;
                Some(format!(
                    "stc_{}_{}({}, {})",
                    cmp_name(op),
                    r.sfx(),
                    a.x,
                    b.x
                ))
            } else {
                Some(format!(
                    "stc_{}_f64((double){}, (double){})",
                    cmp_name(op),
                    a.p(),
                    b.p()
                ))
            }
        }
        _ if int_valued(lt) && int_valued(rt) => {
            let (ra, rb) = (Rep::of(lt)?, Rep::of(rt)?);
            if ra == rb {
                Some(format!(
                    "stc_{}_{}({}, {})",
                    cmp_name(op),
                    ra.sfx(),
                    a.x,
                    b.x
                ))
            } else {
                three_way(&format!(
                    "stc_cmp_any({}, {}, {}, {})",
                    bits64(a),
                    signed_flag(a),
                    bits64(b),
                    signed_flag(b)
                ))
            }
        }
        _ => None,
    }
}

fn compare(e: &mut dyn Emit, op: BinOp, a: &Val, b: &Val, dst: &Val) {
    match compare_expr(op, a, b) {
        Some(x) => store_bool(e, &x, dst),
        None => misuse(e, dst),
    }
}

/// Stores a BOOL value (0/1 of type `uint8_t`).
pub(crate) fn store_bool(e: &mut dyn Emit, x: &str, dst: &Val) {
    match dst.rep() {
        Some(Rep::U8) => set(e, dst, x),
        Some(r) if !r.float() => set(e, dst, &format!("({}){}", r.ctype(), paren(x))),
        _ => misuse(e, dst),
    }
}

fn logic(e: &mut dyn Emit, op: BinOp, a: &Val, b: &Val, dst: &Val) {
    let name = match op {
        BinOp::And => "and",
        BinOp::Or => "or",
        _ => "xor",
    };
    let (Some(lt), Some(rt), Some(res)) = (a.elem, b.elem, dst.elem) else {
        return misuse(e, dst);
    };
    if lt == E::Bool && rt == E::Bool {
        let x = format!("stc_{name}_u8({}, {})", a.x, b.x);
        return store_bool(e, &x, dst);
    }
    if !(int_valued(lt) && int_valued(rt) && int_like(res)) {
        return misuse(e, dst);
    }
    let (Some(ra), Some(rb), Some(rr)) = (a.rep(), b.rep(), dst.rep()) else {
        return misuse(e, dst);
    };
    if ra == rb && ra == rr {
        return set(
            e,
            dst,
            &format!("stc_{name}_{}({}, {})", rr.sfx(), a.x, b.x),
        );
    }
    let x = format!("stc_{name}_u64({}, {})", bits64(a), bits64(b));
    match wrap_bits(res, &x) {
        Some(w) => set(e, dst, &w),
        None => misuse(e, dst),
    }
}

fn int_arith(e: &mut dyn Emit, op: BinOp, a: &Val, b: &Val, dst: &Val) {
    let (Some(ra), Some(rb), Some(rr), Some(res)) = (a.rep(), b.rep(), dst.rep(), dst.elem) else {
        return misuse(e, dst);
    };
    let site = e.site();
    let name = match op {
        BinOp::Add => "add",
        BinOp::Sub => "sub",
        BinOp::Mul => "mul",
        BinOp::Div => "div",
        BinOp::Mod => "mod",
        _ => return misuse(e, dst),
    };
    let divides = matches!(op, BinOp::Div | BinOp::Mod);
    if ra == rb && ra == rr {
        // The hot path: one inline function of stc_rt.h.
        if divides {
            let x = format!("stc_{name}_{}({}, {}, {site}U)", rr.sfx(), a.x, b.x);
            // By a literal other than zero nothing can fault: no check,
            // so the C compiler is free to optimise the loop around it.
            if literal_int(&b.x).is_some_and(|v| v != 0) {
                return set(e, dst, &x);
            }
            // The divisor is tested where it is (in a register), not the
            // fault flag after the fact: the POU ends at once on zero.
            e.fail_if(
                &format!("{} == {}", b.x, zero(rb)),
                "(uint32_t)STC_FAULT_DIVISION_BY_ZERO",
            );
            return set(e, dst, &x);
        }
        return set(
            e,
            dst,
            &format!("stc_{name}_{}({}, {})", rr.sfx(), a.x, b.x),
        );
    }
    // Mixed types: the exact result's low 64 bits, then wrapped.
    let x = if divides {
        format!(
            "stc_{name}_any({}, {}, {}, {}, {site}U)",
            bits64(a),
            signed_flag(a),
            bits64(b),
            signed_flag(b)
        )
    } else {
        format!("stc_{name}_u64({}, {})", bits64(a), bits64(b))
    };
    match wrap_bits(res, &x) {
        Some(w) if divides => set_checked(e, dst, &w),
        Some(w) => set(e, dst, &w),
        None => misuse(e, dst),
    }
}

/// A real operand as `double`.
fn dbl(v: &Val) -> String {
    match v.rep() {
        Some(Rep::F64) => v.x.clone(),
        _ => format!("(double){}", v.p()),
    }
}

fn real_arith(e: &mut dyn Emit, op: BinOp, a: &Val, b: &Val, dst: &Val) {
    let (Some(lt), Some(rt), Some(res)) = (a.elem, b.elem, dst.elem) else {
        return misuse(e, dst);
    };
    if !is_real(res) || !is_real(lt) {
        return misuse(e, dst);
    }
    let rhs_ok = if op == BinOp::Pow {
        is_real(rt) || int_valued(rt)
    } else {
        is_real(rt)
    };
    if !rhs_ok {
        return misuse(e, dst);
    }
    let sym = match op {
        BinOp::Add => "+",
        BinOp::Sub => "-",
        BinOp::Mul => "*",
        BinOp::Div => "/",
        BinOp::Pow => "",
        _ => return misuse(e, dst),
    };
    let name = match op {
        BinOp::Add => "add",
        BinOp::Sub => "sub",
        BinOp::Mul => "mul",
        _ => "div",
    };
    if op != BinOp::Pow && lt == rt && lt == res {
        let r = if res == E::Real { "f32" } else { "f64" };
        return set(e, dst, &format!("stc_{name}_{r}({}, {})", a.x, b.x));
    }
    let x = if op == BinOp::Pow {
        format!("pow({}, {})", dbl(a), dbl(b))
    } else {
        format!("{} {sym} {}", dbl(a), dbl(b))
    };
    if res == E::Real {
        set(e, dst, &format!("(float)({x})"));
    } else {
        set(e, dst, &x);
    }
}

fn time_arith(e: &mut dyn Emit, op: BinOp, a: &Val, b: &Val, dst: &Val) {
    let (Some(lt), Some(rt), Some(res)) = (a.elem, b.elem, dst.elem) else {
        return misuse(e, dst);
    };
    let site = e.site();
    // A result that stc_values wraps into the result type.
    let wrapped =
        |e: &mut dyn Emit, x: &str| match wrap_bits(res, &format!("(uint64_t){}", paren(x))) {
            Some(w) => set(e, dst, &w),
            None => misuse(e, dst),
        };
    match op {
        BinOp::Add | BinOp::Sub if (is_dur(lt) || is_dt(lt)) && is_dur(rt) => {
            let name = if op == BinOp::Add { "add" } else { "sub" };
            let x = format!("stc_{name}_i64({}, {})", a.x, b.x);
            if res == lt {
                set(e, dst, &x)
            } else {
                wrapped(e, &x)
            }
        }
        BinOp::Add | BinOp::Sub if is_tod(lt) && is_dur(rt) => {
            let name = if op == BinOp::Add { "add" } else { "sub" };
            let x = format!("stc_tod_{name}({}, {})", a.x, b.x);
            store_i64(e, &x, dst)
        }
        BinOp::Sub if is_date(lt) && is_date(rt) => {
            let x = format!("stc_date_sub({}, {})", a.x, b.x);
            if is_dur(res) {
                set(e, dst, &x)
            } else {
                wrapped(e, &x)
            }
        }
        BinOp::Sub if (is_tod(lt) && is_tod(rt)) || (is_dt(lt) && is_dt(rt)) => {
            let x = format!("stc_sub_i64({}, {})", a.x, b.x);
            if is_dur(res) {
                set(e, dst, &x)
            } else {
                wrapped(e, &x)
            }
        }
        BinOp::Mul if is_dur(lt) && !is_time_like(rt) => scale(e, op, a, b, dst, site),
        BinOp::Mul if is_dur(rt) && !is_time_like(lt) => scale(e, op, b, a, dst, site),
        BinOp::Div if is_dur(lt) && !is_time_like(rt) => scale(e, op, a, b, dst, site),
        _ => misuse(e, dst),
    }
}

/// Stores an `int64_t` value that `stc_values` does not wrap (it is
/// already the result type's): TOD arithmetic, time scaled by a real.
fn store_i64(e: &mut dyn Emit, x: &str, dst: &Val) {
    match dst.rep() {
        Some(Rep::I64) => set(e, dst, x),
        _ => misuse(e, dst),
    }
}

/// A duration `ns` times or divided by a number `k`.
fn scale(e: &mut dyn Emit, op: BinOp, ns: &Val, k: &Val, dst: &Val, site: u32) {
    let (Some(kt), Some(res)) = (k.elem, dst.elem) else {
        return misuse(e, dst);
    };
    if is_real(kt) {
        if dst.rep() != Some(Rep::I64) {
            return misuse(e, dst);
        }
        let name = if op == BinOp::Mul { "mul" } else { "div" };
        let x = format!("stc_time_{name}_real({}, {}, {site}U)", ns.x, dbl(k));
        return set_checked(e, dst, &x);
    }
    if !int_valued(kt) {
        return misuse(e, dst);
    }
    if op == BinOp::Mul {
        let x = format!("stc_mul_u64((uint64_t){}, {})", ns.p(), bits64(k));
        match wrap_bits(res, &x) {
            Some(w) => set(e, dst, &w),
            None => misuse(e, dst),
        }
    } else {
        let x = format!(
            "stc_div_any((uint64_t){}, 1U, {}, {}, {site}U)",
            ns.p(),
            bits64(k),
            signed_flag(k)
        );
        match wrap_bits(res, &x) {
            Some(w) => set_checked(e, dst, &w),
            None => misuse(e, dst),
        }
    }
}

/// The n-ary operator functions (ADD, MUL, AND, OR, XOR): a left fold,
/// the accumulator taking the result type after the first step.
pub(crate) fn fold(e: &mut dyn Emit, op: BinOp, args: &[Val], dst: &Val) {
    match args {
        [] | [_] => misuse(e, dst),
        [a, b] => binary(e, op, a, b, dst),
        [first, rest @ ..] => {
            let mut acc = first.clone();
            for (i, v) in rest.iter().enumerate() {
                let last = i + 1 == rest.len();
                let step = if last {
                    dst.clone()
                } else {
                    Val {
                        x: e.temp(dst.ty),
                        ty: dst.ty,
                        elem: dst.elem,
                    }
                };
                binary(e, op, &acc, v, &step);
                acc = step;
            }
        }
    }
}

/// GT, GE, EQ, LE, LT over several inputs: a monotonic chain.
pub(crate) fn chain(e: &mut dyn Emit, op: BinOp, args: &[Val], dst: &Val) {
    if args.len() < 2 {
        return misuse(e, dst);
    }
    let mut parts = Vec::new();
    for w in args.windows(2) {
        match compare_expr(op, &w[0], &w[1]) {
            Some(x) => parts.push(format!("({x})")),
            None => return misuse(e, dst),
        }
    }
    let x = if parts.len() == 1 {
        parts.remove(0)
    } else {
        format!("(uint8_t)({})", parts.join(" & "))
    };
    store_bool(e, &x, dst);
}

/// The value of an integer literal as the generator writes them
/// (`((int32_t)7)`, `((uint16_t)7U)`, `((int64_t)-7LL)`).
fn literal_int(x: &str) -> Option<i128> {
    let inner = x.strip_prefix("((")?.strip_suffix(')')?;
    let (_, num) = inner.split_once(')')?;
    let num = num.trim_end_matches(['U', 'L']);
    num.parse().ok()
}

#[cfg(test)]
mod literal_tests {
    use super::literal_int;

    #[test]
    fn literals_are_recognised_and_nothing_else() {
        assert_eq!(literal_int("((int32_t)7)"), Some(7));
        assert_eq!(literal_int("((uint16_t)7U)"), Some(7));
        assert_eq!(literal_int("((int64_t)-7LL)"), Some(-7));
        assert_eq!(literal_int("((uint64_t)0ULL)"), Some(0));
        assert_eq!(literal_int("self->v_x"), None);
        assert_eq!(literal_int("((int32_t)a)"), None);
    }
}
