//! Operations: the C code for every IR operation on values (unary and
//! binary operators, conversions, standard functions, subrange checks),
//! with exactly the semantics of `stc_values` (which the VM and the constant
//! folder use), over the value representation of `runtime/stc_meta.h`.
//!
//! The generator of program structure (`lib.rs`) evaluates every operand
//! into a C expression first (a variable, a temporary or a literal), then
//! calls [`emit_op`] to compute the result into a destination. What is a
//! plain C operator and what calls a function of `runtime/stc_rt.c` is
//! decided here; every function called is declared in `runtime/stc_rt.h`.
//!
//! The split: the operations of one type on scalars (wrap-around `+ - *`,
//! `/` and `MOD` with their zero check, comparisons, bit logic, shifts,
//! negation) are `static inline` functions of `stc_rt.h`, so `gcc -O2`
//! compiles `s := s + i * 3` to the instructions of hand-written C
//! (`tests/ops_vs_values.rs` checks it); conversions that C's casts get
//! right (integers keeping their low-order bits, integers to reals, reals
//! between precisions) and SEL, MAX, MIN, LIMIT, MUX, MOVE on scalars are
//! plain C; everything else (reals to integers, times and dates, texts,
//! strings, BCD) calls `stc_rt.c`. Submodules: `c` (representations,
//! literals, statement patterns), `arith` (operators), `conv`
//! (conversions), `funcs` (standard functions).
//!
//! `tests/ops_vs_values.rs` compares the emitted code, compiled with gcc
//! and the sanitizers, with `stc_values` on random and edge operands of
//! every type, operation, conversion and function.

use stc_ir::Module;
use stc_sema::TypeId;
use stc_values::{BinOp, Intrinsic, UnOp};

mod arith;
mod c;
mod conv;
mod funcs;

/// An operation of the IR on values.
#[derive(Clone, Copy, Debug)]
pub enum Operation {
    Unary(UnOp),
    /// Operands have one type, except time arithmetic (`TOD + TIME`) and
    /// `**` (any numeric exponent), as in the IR.
    Binary(BinOp),
    /// A conversion from `args[0]`'s type to the result type.
    Convert,
    /// A standard function resolved at the argument types given.
    Intrinsic(Intrinsic),
    /// A store into a subrange: the value must lie in `lo..=hi`, else a
    /// subrange fault; the result is the value.
    Check {
        lo: i128,
        hi: i128,
    },
}

/// What [`emit_op`] may ask of the code generator.
pub trait Emit {
    fn module(&self) -> &Module;
    /// A new temporary of IR type `ty`, declared at the start of the
    /// current C function; returns its name.
    fn temp(&mut self, ty: TypeId) -> String;
    /// Appends a complete C statement (with its `;`) to the current block.
    fn stmt(&mut self, s: String);
    /// Appends the check that ends the current POU when a fault is
    /// pending (after a call of a function that can fault).
    fn fault_check(&mut self);
    /// Appends: when `cond` holds, the fault `kind` (a C expression) and
    /// the end of the POU. The default records the fault and checks.
    fn fail_if(&mut self, cond: &str, kind: &str) {
        let site = self.site();
        self.stmt(format!("if ({cond}) {{ stc_fault({kind}, {site}U); }}"));
        self.fault_check();
    }
    /// The index in `stc_sites` of the statement being generated (the
    /// second argument of `stc_fault`).
    fn site(&self) -> u32;
    /// The C type of a scalar IR type (`int16_t`, `float`, `uint8_t`...).
    fn c_type(&self, ty: TypeId) -> String;
}

/// Emits code computing `op` over `args` into `dst`.
///
/// `args` are C expressions for the operand values, each with its IR
/// type: a scalar by value; a STRING as a `const uint8_t *` to its
/// length-prefixed array, a WSTRING as a `const uint16_t *` (stc_meta.h).
/// `dst` is a C lvalue of the result type: a scalar variable, or for a
/// string result the array itself, whose capacity is the result type's.
/// `dst` never appears in `args` unless the operation allows it (the
/// generator passes a fresh temporary otherwise).
///
/// Aliasing: every operation with a scalar result allows `dst` among the
/// `args` (the operands are read before `dst` is written, or the
/// operation is a copy); an operation with a string result needs a `dst`
/// distinct from its arguments.
///
/// Faults: every operation that can fault is followed by
/// [`Emit::fault_check`], and writes `dst` only after the check (as on the
/// VM, a faulting operation leaves its destination unchanged). A request
/// `stc_values` answers with a conversion failure whatever the values (an
/// operation on types the analyser never combines, SPLIT_* which have
/// outputs) emits that fault.
pub fn emit_op(
    e: &mut dyn Emit,
    op: Operation,
    args: &[(String, TypeId)],
    result: TypeId,
    dst: &str,
) {
    let vals: Vec<c::Val> = args
        .iter()
        .map(|(x, t)| c::Val {
            x: x.clone(),
            ty: *t,
            elem: c::elem_of(e, *t),
        })
        .collect();
    let d = c::Val {
        x: dst.to_string(),
        ty: result,
        elem: c::elem_of(e, result),
    };
    let cap = c::cap_of(e, result);
    match op {
        Operation::Unary(u) => match vals.as_slice() {
            [a] => arith::unary(e, u, a, &d),
            _ => c::misuse(e, &d),
        },
        Operation::Binary(b) => match vals.as_slice() {
            [x, y] => arith::binary(e, b, x, y, &d),
            _ => c::misuse(e, &d),
        },
        Operation::Convert => match vals.as_slice() {
            [a] => conv::convert(e, a, &d, cap),
            _ => c::misuse(e, &d),
        },
        Operation::Intrinsic(f) => funcs::intrinsic(e, f, &vals, &d, cap),
        Operation::Check { lo, hi } => match vals.as_slice() {
            [a] => check(e, a, lo, hi, &d),
            _ => c::misuse(e, &d),
        },
    }
}

/// A subrange store: `lo <= v <= hi`, else the subrange fault.
fn check(e: &mut dyn Emit, a: &c::Val, lo: i128, hi: i128, dst: &c::Val) {
    let (Some(t), Some(r)) = (a.elem, a.rep()) else {
        return c::misuse(e, dst);
    };
    let Some((tmin, tmax)) = c::range(t).filter(|_| !r.float()) else {
        return c::misuse(e, dst);
    };
    let site = e.site();
    let v = a.p();
    // Bounds outside the type's range are either always met (left out, so
    // the C compiler sees no comparison that is always true) or never.
    let never = lo > tmax || hi < tmin || lo > hi;
    let mut conds = Vec::new();
    if lo > tmin && lo <= tmax {
        conds.push(format!("({v} < {})", c::lit(r, lo)));
    }
    if hi < tmax && hi >= tmin {
        conds.push(format!("({v} > {})", c::lit(r, hi)));
    }
    // The value and the bounds go with the fault, as 64-bit patterns.
    let unsigned = tmin >= 0;
    let bits = |x: i128| {
        if unsigned {
            format!("UINT64_C({})", x.clamp(0, i128::from(u64::MAX)))
        } else {
            format!(
                "(uint64_t)INT64_C({})",
                x.clamp(i128::from(i64::MIN + 1), i128::from(i64::MAX))
            )
        }
    };
    // stc_fault_range's flags (stc_rt.h): value and bounds unsigned.
    let flags = if unsigned { "3U" } else { "0U" };
    let fault = format!(
        "stc_fault_range((uint32_t)STC_FAULT_SUBRANGE, {site}U, (uint64_t){v}, {}, {}, {flags});",
        bits(lo),
        bits(hi)
    );
    if never {
        e.stmt(fault);
        e.fault_check();
    } else if !conds.is_empty() {
        e.stmt(format!("if ({}) {{ {fault} }}", conds.join(" || ")));
        e.fault_check();
    }
    match dst.rep() {
        Some(d) if d == r => c::set(e, dst, &a.x),
        Some(d) if !d.float() => c::set(e, dst, &c::int_cast(r, d, &a.x)),
        _ => c::misuse(e, dst),
    }
}
