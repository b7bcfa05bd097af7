//! The standard functions (`stc_values::call`): numeric, bit shifts,
//! selection, strings, time and date.

use super::arith::{binary, chain, fold, int_like, int_or_bool, int_valued, unary};
use super::c::{int_cast, lit, misuse, paren, sat_i64, set, set_checked, Rep, Val};
use super::conv;
use super::Emit;
use stc_syntax::token::ElemType;
use stc_values::{is_bit_string, is_real, BinOp, Intrinsic, UnOp};

use ElemType as E;
use Intrinsic as I;

pub(crate) fn intrinsic(e: &mut dyn Emit, f: Intrinsic, args: &[Val], dst: &Val, cap: u32) {
    if args.is_empty() {
        return misuse(e, dst);
    }
    let a0 = &args[0];
    match f {
        I::Abs => abs(e, a0, dst),
        I::Sqrt => math(e, "sqrt", args, dst),
        I::Ln => math(e, "log", args, dst),
        I::Log => math(e, "log10", args, dst),
        I::Exp => math(e, "exp", args, dst),
        I::Sin => math(e, "sin", args, dst),
        I::Cos => math(e, "cos", args, dst),
        I::Tan => math(e, "tan", args, dst),
        I::Asin => math(e, "asin", args, dst),
        I::Acos => math(e, "acos", args, dst),
        I::Atan => math(e, "atan", args, dst),
        I::Atan2 => math(e, "atan2", args, dst),
        I::Expt => match args {
            [b, x] => binary(e, BinOp::Pow, b, x, dst),
            _ => misuse(e, dst),
        },
        I::Shl | I::Shr | I::Rol | I::Ror => shift(e, f, args, dst),
        I::Sel => sel(e, args, dst, cap),
        I::Max | I::Min => max_min(e, f == I::Max, args, dst, cap),
        I::Limit => limit(e, args, dst, cap),
        I::Mux => mux(e, args, dst, cap),
        I::Move => copy(e, a0, dst, cap),
        I::Len => match (args, a0.elem) {
            ([s], Some(E::String)) => store_count(e, &format!("stc_str_len({})", s.x), dst),
            ([s], Some(E::Wstring)) => store_count(e, &format!("stc_wstr_len({})", s.x), dst),
            _ => misuse(e, dst),
        },
        I::Left | I::Right | I::Mid | I::Insert | I::Delete | I::Replace => {
            strfn(e, f, args, dst, cap)
        }
        I::Concat => concat(e, args, dst, cap),
        I::Find => match args {
            [a, b] => match (a.elem, b.elem) {
                (Some(E::String), Some(E::String)) => {
                    store_count(e, &format!("stc_str_find({}, {})", a.x, b.x), dst)
                }
                (Some(E::Wstring), Some(E::Wstring)) => {
                    store_count(e, &format!("stc_wstr_find({}, {})", a.x, b.x), dst)
                }
                _ => misuse(e, dst),
            },
            _ => misuse(e, dst),
        },
        I::AddTime | I::AddTodTime | I::AddDtTime => two(e, BinOp::Add, args, dst),
        I::SubTime | I::SubTodTime | I::SubDtTime | I::SubDateDate | I::SubTodTod | I::SubDtDt => {
            two(e, BinOp::Sub, args, dst)
        }
        I::MulTime => two(e, BinOp::Mul, args, dst),
        I::DivTime => two(e, BinOp::Div, args, dst),
        I::ConcatDateTod => dates(e, "stc_concat_date_tod", args, 2, dst),
        I::ConcatDate => dates(e, "stc_concat_date", args, 3, dst),
        I::ConcatTod => dates(e, "stc_concat_tod", args, 4, dst),
        I::ConcatDt => dates(e, "stc_concat_dt", args, 7, dst),
        I::DayOfWeek => match (args, a0.elem) {
            ([d], Some(t)) if int_or_bool(t) => {
                store_count(e, &format!("stc_day_of_week({})", sat_i64(d)), dst)
            }
            _ => misuse(e, dst),
        },
        // One field of SPLIT_*: the value and the field's index, a LINT
        // (the lowering's form of a SPLIT call, stc_ir::lower::split).
        I::SplitDate | I::SplitTod | I::SplitDt => match args {
            [v, k] if v.rep() == Some(Rep::I64) && dst.rep() == Some(Rep::I64) => {
                let kind = match f {
                    I::SplitDate => 0,
                    I::SplitTod => 1,
                    _ => 2,
                };
                set(
                    e,
                    dst,
                    &format!("stc_split_field({kind}U, {}, {})", v.x, sat_i64(k)),
                )
            }
            _ => misuse(e, dst),
        },
        I::Convert { .. } => match args {
            [a] => conv::convert(e, a, dst, cap),
            _ => misuse(e, dst),
        },
        I::Trunc { .. } => match args {
            [a] => conv::trunc(e, a, dst),
            _ => misuse(e, dst),
        },
        I::BcdToInt { .. } => match args {
            [a] => conv::bcd_to_int(e, a, dst),
            _ => misuse(e, dst),
        },
        I::IntToBcd { .. } => match args {
            [a] => conv::int_to_bcd(e, a, dst),
            _ => misuse(e, dst),
        },
        I::Add => fold(e, BinOp::Add, args, dst),
        I::Mul => fold(e, BinOp::Mul, args, dst),
        I::And => fold(e, BinOp::And, args, dst),
        I::Or => fold(e, BinOp::Or, args, dst),
        I::Xor => fold(e, BinOp::Xor, args, dst),
        I::Sub => two(e, BinOp::Sub, args, dst),
        I::Div => two(e, BinOp::Div, args, dst),
        I::Mod => two(e, BinOp::Mod, args, dst),
        I::Not => match args {
            [a] => unary(e, UnOp::Not, a, dst),
            _ => misuse(e, dst),
        },
        I::Gt => chain(e, BinOp::Gt, args, dst),
        I::Ge => chain(e, BinOp::Ge, args, dst),
        I::Eq => chain(e, BinOp::Eq, args, dst),
        I::Le => chain(e, BinOp::Le, args, dst),
        I::Lt => chain(e, BinOp::Lt, args, dst),
        I::Ne => two(e, BinOp::Ne, args, dst),
    }
}

fn two(e: &mut dyn Emit, op: BinOp, args: &[Val], dst: &Val) {
    match args {
        [a, b] => binary(e, op, a, b, dst),
        _ => misuse(e, dst),
    }
}

/// A count (LEN, FIND, DAY_OF_WEEK: `uint16_t`/`uint8_t`, never negative)
/// wrapped into the integer result type.
fn store_count(e: &mut dyn Emit, x: &str, dst: &Val) {
    match (dst.elem, dst.rep()) {
        (Some(t), Some(r)) if int_like(t) => set(e, dst, &int_cast(Rep::U16, r, x)),
        _ => misuse(e, dst),
    }
}

fn abs(e: &mut dyn Emit, a: &Val, dst: &Val) {
    let (Some(t), Some(r), Some(res), Some(rr)) = (a.elem, a.rep(), dst.elem, dst.rep()) else {
        return misuse(e, dst);
    };
    if int_like(t) {
        let x = if r.signed() {
            format!("stc_abs_{}({})", r.sfx(), a.x)
        } else {
            a.x.clone()
        };
        if r == rr {
            set(e, dst, &x)
        } else {
            match super::c::wrap_bits(res, &format!("(uint64_t){}", paren(&x))) {
                Some(w) => set(e, dst, &w),
                None => misuse(e, dst),
            }
        }
    } else if is_real(t) && is_real(res) {
        let x = format!("fabs((double){})", a.p());
        set(e, dst, &round_to(res, &x))
    } else {
        misuse(e, dst)
    }
}

/// A double result rounded to the result type.
fn round_to(res: ElemType, x: &str) -> String {
    if res == E::Real {
        format!("(float){}", paren(x))
    } else {
        x.to_string()
    }
}

/// SQRT..ATAN2: computed in double by the C library (as Rust's f64
/// methods, which call the same libm), rounded to the result type.
fn math(e: &mut dyn Emit, f: &str, args: &[Val], dst: &Val) {
    let Some(res) = dst.elem else {
        return misuse(e, dst);
    };
    let reals = args.iter().all(|a| a.elem.is_some_and(is_real));
    let n = if f == "atan2" { 2 } else { 1 };
    if !is_real(res) || !reals || args.len() != n {
        return misuse(e, dst);
    }
    let list: Vec<String> = args.iter().map(|a| format!("(double){}", a.p())).collect();
    set(e, dst, &round_to(res, &format!("{f}({})", list.join(", "))))
}

fn shift(e: &mut dyn Emit, f: Intrinsic, args: &[Val], dst: &Val) {
    let [v, n] = args else {
        return misuse(e, dst);
    };
    let (Some(t), Some(r), Some(nt), Some(nr)) = (v.elem, v.rep(), n.elem, n.rep()) else {
        return misuse(e, dst);
    };
    if !(is_bit_string(t) || int_like(t)) || !int_or_bool(nt) {
        return misuse(e, dst);
    }
    let rotate = matches!(f, I::Rol | I::Ror);
    // The count as int64_t: a ULINT count is saturated for a shift (any
    // count at or above the width is the same) and reduced modulo 64 for
    // a rotation (the width divides 64).
    let count = match nr {
        Rep::U64 if rotate => format!("(int64_t)({} & 63U)", n.x),
        _ => sat_i64(n),
    };
    let name = match f {
        I::Shl => "shl",
        I::Shr => "shr",
        I::Rol => "rol",
        _ => "ror",
    };
    let x = if t == E::Bool {
        if rotate {
            v.x.clone()
        } else {
            // One bit: any non-zero count shifts it out, either way.
            format!("stc_shl_b({}, {count})", v.x)
        }
    } else if r.signed() {
        let u = r.unsigned();
        let inner = format!("stc_{name}_{}(({}){}, {count})", u.sfx(), u.ctype(), v.p());
        int_cast(u, r, &inner)
    } else {
        format!("stc_{name}_{}({}, {count})", r.sfx(), v.x)
    };
    match dst.rep() {
        Some(d) if d == r => set(e, dst, &x),
        Some(d) if !d.float() => set(e, dst, &int_cast(r, d, &x)),
        _ => misuse(e, dst),
    }
}

/// Whether a value of `v`'s type can be stored in the destination as is
/// (the same representation, or the same aggregate type).
fn same_kind(v: &Val, dst: &Val) -> bool {
    match (v.elem, dst.elem) {
        (Some(a), Some(b)) => {
            a == b
                || (Rep::of(a).is_some()
                    && Rep::of(a) == Rep::of(b)
                    && int_valued(a) == int_valued(b))
        }
        (None, None) => v.ty == dst.ty,
        _ => false,
    }
}

/// The statement copying `v` into the destination.
fn copy_stmt(v: &Val, dst: &Val, cap: u32) -> String {
    match dst.elem {
        Some(E::String) => format!("stc_str_copy({}, {cap}U, {});", dst.x, v.x),
        Some(E::Wstring) => format!("stc_wstr_copy({}, {cap}U, {});", dst.x, v.x),
        _ => format!("{} = {};", dst.x, v.x),
    }
}

fn copy(e: &mut dyn Emit, v: &Val, dst: &Val, cap: u32) {
    if !same_kind(v, dst) {
        return misuse(e, dst);
    }
    e.stmt(copy_stmt(v, dst, cap));
}

fn sel(e: &mut dyn Emit, args: &[Val], dst: &Val, cap: u32) {
    let [g, in0, in1] = args else {
        return misuse(e, dst);
    };
    if g.elem != Some(E::Bool) || !same_kind(in0, dst) || !same_kind(in1, dst) {
        return misuse(e, dst);
    }
    match dst.elem {
        Some(E::String) => e.stmt(format!(
            "stc_str_copy({}, {cap}U, ({} != 0U) ? {} : {});",
            dst.x,
            g.p(),
            in1.x,
            in0.x
        )),
        Some(E::Wstring) => e.stmt(format!(
            "stc_wstr_copy({}, {cap}U, ({} != 0U) ? {} : {});",
            dst.x,
            g.p(),
            in1.x,
            in0.x
        )),
        _ => e.stmt(format!(
            "if ({} != 0U) {{ {} }} else {{ {} }}",
            g.p(),
            copy_stmt(in1, dst, cap),
            copy_stmt(in0, dst, cap)
        )),
    }
}

/// The comparison `a > b` (or `<`) of two scalars of one type, as a C
/// condition (strings through the runtime).
fn greater(a: &Val, b: &Val, max: bool) -> Option<String> {
    let sym = if max { ">" } else { "<" };
    // An unsigned zero is never greater than anything: no test (gcc's
    // -Wtype-limits, MISRA's invariant condition), no statement.
    let unsigned = a
        .elem
        .is_some_and(|t| crate::names::elem_c(t).starts_with('u') && t != E::Bool);
    if max && unsigned && is_zero_literal(&a.x) {
        return None;
    }
    match a.elem? {
        E::String => Some(format!("stc_str_cmp({}, {}) {sym} 0", a.x, b.x)),
        E::Wstring => Some(format!("stc_wstr_cmp({}, {}) {sym} 0", a.x, b.x)),
        _ => Some(format!("{} {sym} {}", a.p(), b.p())),
    }
}

/// Whether C text is an integer literal zero as `names::literal` writes
/// it (`0U`, `((uint32_t)0U)`, `UINT64_C(0)`).
fn is_zero_literal(x: &str) -> bool {
    let core = x.trim_matches(|c| c == '(' || c == ')' || c == ' ');
    let core = core
        .rsplit(')')
        .next()
        .unwrap_or(core)
        .trim_start_matches("UINT64_C(");
    matches!(core, "0U" | "0" | "0ULL" | "0UL")
}

/// Where MAX, MIN and LIMIT keep their running result: the destination,
/// or a temporary when the destination is also one of the inputs.
fn accumulator(e: &mut dyn Emit, args: &[Val], dst: &Val) -> Val {
    if args.iter().any(|a| a.x == dst.x) {
        Val {
            x: e.temp(dst.ty),
            ty: dst.ty,
            elem: dst.elem,
        }
    } else {
        dst.clone()
    }
}

fn max_min(e: &mut dyn Emit, max: bool, args: &[Val], dst: &Val, cap: u32) {
    if args.is_empty() || !args.iter().all(|a| a.elem.is_some() && same_kind(a, dst)) {
        return misuse(e, dst);
    }
    match dst.elem {
        Some(t @ (E::String | E::Wstring)) => {
            let (w, ct) = if t == E::String {
                ("str", "uint8_t")
            } else {
                ("wstr", "uint16_t")
            };
            let list: Vec<&str> = args.iter().map(|a| a.x.as_str()).collect();
            let name = if max { "max" } else { "min" };
            e.stmt(format!(
                "stc_{w}_{name}({}, {cap}U, (const {ct} *const[]){{ {} }}, {}U);",
                dst.x,
                list.join(", "),
                args.len()
            ));
        }
        _ => {
            // A later input replaces the running result only when it is
            // strictly greater (smaller): a NaN first stays, later is skipped.
            let acc = accumulator(e, args, dst);
            set(e, &acc, &args[0].x);
            for a in &args[1..] {
                if let Some(c) = greater(a, &acc, max) {
                    e.stmt(format!("if ({c}) {{ {} = {}; }}", acc.x, a.x));
                }
            }
            if acc.x != dst.x {
                set(e, dst, &acc.x);
            }
        }
    }
}

fn limit(e: &mut dyn Emit, args: &[Val], dst: &Val, cap: u32) {
    let [mn, x, mx] = args else {
        return misuse(e, dst);
    };
    if !args.iter().all(|a| same_kind(a, dst)) {
        return misuse(e, dst);
    }
    match dst.elem {
        Some(E::String) => e.stmt(format!(
            "stc_str_limit({}, {cap}U, {}, {}, {});",
            dst.x, mn.x, x.x, mx.x
        )),
        Some(E::Wstring) => e.stmt(format!(
            "stc_wstr_limit({}, {cap}U, {}, {}, {});",
            dst.x, mn.x, x.x, mx.x
        )),
        Some(_) => {
            let acc = accumulator(e, args, dst);
            set(e, &acc, &x.x);
            if let Some(lo) = greater(mn, &acc, true) {
                e.stmt(format!("if ({lo}) {{ {} = {}; }}", acc.x, mn.x));
            }
            if let Some(hi) = greater(mx, &acc, false) {
                e.stmt(format!("if ({hi}) {{ {} = {}; }}", acc.x, mx.x));
            }
            if acc.x != dst.x {
                set(e, dst, &acc.x);
            }
        }
        None => misuse(e, dst),
    }
}

fn mux(e: &mut dyn Emit, args: &[Val], dst: &Val, cap: u32) {
    let Some((k, inputs)) = args.split_first() else {
        return misuse(e, dst);
    };
    let (Some(kt), Some(kr)) = (k.elem, k.rep()) else {
        return misuse(e, dst);
    };
    if inputs.is_empty() || !int_or_bool(kt) || !inputs.iter().all(|v| same_kind(v, dst)) {
        return misuse(e, dst);
    }
    let site = e.site();
    let n = inputs.len() as i128;
    let kx = k.p();
    // The selector first: out of range is the MUX fault.
    let mut bad = Vec::new();
    if kr.signed() {
        bad.push(format!("({kx} < 0)"));
    }
    let max = super::c::range(kt).map_or(i128::MAX, |r| r.1);
    if n - 1 < max {
        bad.push(format!("({kx} > {})", lit(kr, n - 1)));
    }
    if !bad.is_empty() {
        e.stmt(format!(
            "if ({}) {{ stc_fault((uint32_t)STC_FAULT_MUX, {site}U); }}",
            bad.join(" || ")
        ));
        e.fault_check();
    }
    let mut s = format!("switch ({kx}) {{");
    for (i, v) in inputs.iter().enumerate().skip(1) {
        s.push_str(&format!(
            " case {}: {} break;",
            lit(kr, i as i128),
            copy_stmt(v, dst, cap)
        ));
    }
    s.push_str(&format!(
        " default: {} break; }}",
        copy_stmt(&inputs[0], dst, cap)
    ));
    e.stmt(s);
}

fn strfn(e: &mut dyn Emit, f: Intrinsic, args: &[Val], dst: &Val, cap: u32) {
    let w = match (dst.elem, args.first().and_then(|a| a.elem)) {
        (Some(E::String), Some(E::String)) => "str",
        (Some(E::Wstring), Some(E::Wstring)) => "wstr",
        _ => return misuse(e, dst),
    };
    let skind = dst.elem;
    let is_str = |v: &Val| v.elem == skind;
    let is_int = |v: &Val| v.elem.is_some_and(int_or_bool);
    let d = &dst.x;
    let call = match (f, args) {
        (I::Left, [s, l]) if is_int(l) => {
            format!("stc_{w}_left({d}, {cap}U, {}, {})", s.x, sat_i64(l))
        }
        (I::Right, [s, l]) if is_int(l) => {
            format!("stc_{w}_right({d}, {cap}U, {}, {})", s.x, sat_i64(l))
        }
        (I::Mid, [s, l, p]) if is_int(l) && is_int(p) => format!(
            "stc_{w}_mid({d}, {cap}U, {}, {}, {})",
            s.x,
            sat_i64(l),
            sat_i64(p)
        ),
        (I::Insert, [a, b, p]) if is_str(b) && is_int(p) => format!(
            "stc_{w}_insert({d}, {cap}U, {}, {}, {})",
            a.x,
            b.x,
            sat_i64(p)
        ),
        (I::Delete, [s, l, p]) if is_int(l) && is_int(p) => format!(
            "stc_{w}_delete({d}, {cap}U, {}, {}, {})",
            s.x,
            sat_i64(l),
            sat_i64(p)
        ),
        (I::Replace, [a, b, l, p]) if is_str(b) && is_int(l) && is_int(p) => format!(
            "stc_{w}_replace({d}, {cap}U, {}, {}, {}, {})",
            a.x,
            b.x,
            sat_i64(l),
            sat_i64(p)
        ),
        _ => return misuse(e, dst),
    };
    e.stmt(format!("{call};"));
}

fn concat(e: &mut dyn Emit, args: &[Val], dst: &Val, cap: u32) {
    let (w, ct) = match dst.elem {
        Some(E::String) => ("str", "uint8_t"),
        Some(E::Wstring) => ("wstr", "uint16_t"),
        _ => return misuse(e, dst),
    };
    if !args.iter().all(|a| a.elem == dst.elem) {
        return misuse(e, dst);
    }
    let list: Vec<&str> = args.iter().map(|a| a.x.as_str()).collect();
    e.stmt(format!(
        "stc_{w}_concat({}, {cap}U, (const {ct} *const[]){{ {} }}, {}U);",
        dst.x,
        list.join(", "),
        args.len()
    ));
}

/// CONCAT_DATE_TOD, CONCAT_DATE, CONCAT_TOD, CONCAT_DT: integer fields
/// (saturated into int64_t), a result checked by the runtime.
fn dates(e: &mut dyn Emit, f: &str, args: &[Val], n: usize, dst: &Val) {
    if args.len() != n || !args.iter().all(|a| a.elem.is_some_and(int_or_bool)) {
        return misuse(e, dst);
    }
    if dst.rep() != Some(Rep::I64) {
        return misuse(e, dst);
    }
    let site = e.site();
    let list: Vec<String> = args.iter().map(sat_i64).collect();
    set_checked(e, dst, &format!("{f}({}, {site}U)", list.join(", ")));
}
