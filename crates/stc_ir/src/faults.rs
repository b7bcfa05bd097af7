//! Which POUs may raise a run-time fault: [`may_fault`], computed on the IR
//! before any back end emits code, so a back end can leave out the fault
//! check after a call of a POU that cannot fault (the C back end does).
//!
//! A body *faults directly* when it holds a check of the IR that some value
//! can fail: an array index that is neither a constant (the analyser checked
//! those) nor the control variable of an enclosing FOR whose constant bounds
//! lie inside the array's ([`for_range`]); an integer or time division (or
//! MOD) by anything but a non-zero constant; a subrange check
//! ([`ExprKind::Check`]) whose bounds do not cover the value's type; a
//! conversion that can fail (reals to integers or durations, from strings,
//! WCHAR to CHAR, DATE to DT, BCD, TRUNC...); MUX with a selector that can
//! be out of range; date concatenations; a [`StmtKind::Fault`]; and every
//! operation `stc_values` answers with a fault whatever the values (an
//! ill-typed request). Whatever is not known to be total counts as a fault,
//! so the analysis errs only towards a check. A POU then may fault when it
//! faults directly or calls a POU that may fault: a fixpoint over the call
//! graph, which terminates on any graph (recursion, which IEC 61131-3
//! forbids, included).
//!
//! The watchdog is not a fault here: it can stop any loop or call, and the
//! back ends check it on their own (the C back end at loop back-edges, POU
//! entries and after calls).

use stc_sema::{PouId, TypeTable, VarId};
use stc_syntax::token::ElemType;
use stc_values::{is_real, is_time_like, BinOp, Intrinsic, UnOp, Value};

use crate::{Expr, ExprKind, Module, Output, Place, Pou, Proj, Root, Stmt, StmtKind};

/// For each POU of the module (by index), whether running its body may
/// raise a run-time fault, directly or in a POU it calls.
pub fn may_fault(m: &Module) -> Vec<bool> {
    let n = m.pous.len();
    let mut faults: Vec<bool> = m.pous.iter().map(|p| faults_directly(m, p)).collect();
    let callees: Vec<Vec<usize>> = m
        .pous
        .iter()
        .map(|p| {
            let mut out = Vec::new();
            crate::visit::calls(&p.body, &mut |c| out.push(c.0 as usize));
            out.sort_unstable();
            out.dedup();
            out
        })
        .collect();
    // Each round turns at least one `false` into `true`, or stops: at most
    // `n` rounds, whatever the call graph.
    loop {
        let mut changed = false;
        for p in 0..n {
            // (A call of a POU outside the module cannot be known.)
            if !faults[p]
                && callees[p]
                    .iter()
                    .any(|&q| faults.get(q).copied().unwrap_or(true))
            {
                faults[p] = true;
                changed = true;
            }
        }
        if !changed {
            return faults;
        }
    }
}

/// Whether the body of `pou` holds a check that can fail, not counting the
/// POUs it calls.
pub fn faults_directly(m: &Module, pou: &Pou) -> bool {
    Direct {
        m,
        pou,
        ranges: Vec::new(),
    }
    .block(&pou.body)
}

/// When `s` is the loop of a FOR with constant bounds (the IR sets the
/// control variable and the hidden end just before it, and the body starts
/// with the exit test), the control variable and the range it stays in
/// inside the loop's body (not its latch): the body cannot assign it
/// (E0306). `before` are the statements of the block before `s`.
pub fn for_range(before: &[Stmt], s: &Stmt, pou: &Pou) -> Option<(VarId, i128, i128)> {
    let StmtKind::Loop { body, .. } = &s.kind else {
        return None;
    };
    let StmtKind::If { cond, .. } = &body.first()?.kind else {
        return None;
    };
    let ExprKind::Binary(op, a, b) = &cond.kind else {
        return None;
    };
    let (ExprKind::Load(pv), ExprKind::Load(pe)) = (&a.kind, &b.kind) else {
        return None;
    };
    let (Root::Var(v), Root::Var(end)) = (&pv.root, &pe.root) else {
        return None;
    };
    if pou.var(*end).hidden != Some("end") {
        return None;
    }
    let konst = |target: VarId| {
        before
            .iter()
            .rev()
            .find_map(|st| match &st.kind {
                StmtKind::Assign { place, value }
                    if matches!(place.root, Root::Var(x) if x == target)
                        && place.proj.is_empty() =>
                {
                    match &value.kind {
                        ExprKind::Const(Value::Int(c)) => Some(Some(*c)),
                        _ => Some(None),
                    }
                }
                _ => None,
            })
            .flatten()
    };
    let (start, stop) = (konst(*v)?, konst(*end)?);
    match op {
        BinOp::Gt => Some((*v, start, stop)),
        BinOp::Lt => Some((*v, stop, start)),
        _ => None,
    }
}

/// Whether `e`, read where the FOR control variables `ranges` (innermost
/// last) hold, is a variable whose range lies in `lo..=hi`.
pub fn index_in_range(e: &Expr, ranges: &[(VarId, i128, i128)], lo: i128, hi: i128) -> bool {
    let ExprKind::Load(p) = &e.unlocated().kind else {
        return false;
    };
    let Root::Var(v) = p.root else {
        return false;
    };
    p.proj.is_empty()
        && ranges
            .iter()
            .rev()
            .find(|(x, _, _)| *x == v)
            .is_some_and(|&(_, l, h)| lo <= l && h <= hi)
}

/// The direct-fault walk over one body, with the FOR ranges in force.
struct Direct<'a> {
    m: &'a Module,
    pou: &'a Pou,
    ranges: Vec<(VarId, i128, i128)>,
}

impl Direct<'_> {
    fn block(&mut self, stmts: &[Stmt]) -> bool {
        for (k, s) in stmts.iter().enumerate() {
            let range = for_range(&stmts[..k], s, self.pou);
            if let Some(r) = range {
                self.ranges.push(r);
            }
            let faults = self.stmt(s);
            if range.is_some() {
                self.ranges.pop();
            }
            if faults {
                return true;
            }
        }
        false
    }

    fn stmt(&mut self, s: &Stmt) -> bool {
        match &s.kind {
            StmtKind::Assign { place, value } => self.place(place) || self.expr(value),
            StmtKind::CallFb {
                instance,
                fb,
                inputs,
                inouts,
                outputs,
            } => {
                self.place(instance)
                    || inputs.iter().any(|(_, e)| self.expr(e))
                    || inouts.iter().any(|(_, p)| self.place(p))
                    || outputs.iter().any(|o| self.output(*fb, o))
            }
            StmtKind::Eval(e) => self.expr(e),
            StmtKind::If {
                cond,
                then_body,
                else_body,
            } => self.expr(cond) || self.block(then_body) || self.block(else_body),
            StmtKind::Switch {
                selector,
                arms,
                default,
            } => {
                self.expr(selector)
                    || arms.iter().any(|a| self.block(&a.body))
                    || self.block(default)
            }
            StmtKind::Loop { body, latch } => {
                if self.block(body) {
                    return true;
                }
                // The control variable leaves its range in the latch.
                let saved = std::mem::take(&mut self.ranges);
                let faults = self.block(latch);
                self.ranges = saved;
                faults
            }
            StmtKind::Break | StmtKind::Continue | StmtKind::Return => false,
            StmtKind::Fault(_) => true,
        }
    }

    fn place(&mut self, p: &Place) -> bool {
        // A dereference faults on NULL.
        if let Root::Deref(_) = p.root {
            return true;
        }
        p.proj.iter().any(|pr| match pr {
            Proj::Index(idx) => idx.iter().any(|(e, lo, hi)| {
                let checked = !matches!(e.unlocated().kind, ExprKind::Const(Value::Int(_)))
                    && !index_in_range(e, &self.ranges, *lo, *hi);
                checked || self.expr(e)
            }),
            _ => false,
        })
    }

    /// An output of `callee` copied to its target: negated (BOOL), then
    /// converted to the target's type.
    fn output(&mut self, callee: PouId, o: &Output) -> bool {
        let from = self
            .m
            .pous
            .get_id(callee)
            .and_then(|p| p.vars.get_id(o.var))
            .map(|v| self.m.types.scalar(v.ty));
        let to = self.m.types.scalar(o.target.ty);
        let converts = match (from, to) {
            (Some(Some(f)), Some(t)) => stc_values::conversion_may_fault(f, t),
            (None, _) => true,
            _ => false,
        };
        converts || self.place(&o.target)
    }

    fn expr(&mut self, e: &Expr) -> bool {
        if node_may_fault(&self.m.types, e) {
            return true;
        }
        match &e.kind {
            ExprKind::Const(_) | ExprKind::CurTime | ExprKind::Null => false,
            ExprKind::Load(p) | ExprKind::Ref(p) => self.place(p),
            ExprKind::Unary(_, x) | ExprKind::Convert(x) => self.expr(x),
            ExprKind::Binary(_, x, y) => self.expr(x) || self.expr(y),
            ExprKind::Check { value, .. } => self.expr(value),
            ExprKind::Located { expr, .. } => self.expr(expr),
            ExprKind::CallFn {
                func,
                inputs,
                inouts,
                outputs,
            } => {
                inputs.iter().any(|(_, x)| self.expr(x))
                    || inouts.iter().any(|(_, p)| self.place(p))
                    || outputs.iter().any(|o| self.output(*func, o))
            }
            ExprKind::Intrinsic { args, .. } => args.iter().any(|a| self.expr(a)),
        }
    }
}

/// Whether the operation of `e` itself (not its operands, not the indices
/// of a place it reads, not a function it calls) can fault: what lowering
/// gives its own position ([`ExprKind::Located`]).
pub fn node_may_fault(types: &TypeTable, e: &Expr) -> bool {
    let elem = |t| types.scalar(t);
    match &e.kind {
        ExprKind::Const(_)
        | ExprKind::CurTime
        | ExprKind::Load(_)
        | ExprKind::CallFn { .. }
        | ExprKind::Null
        | ExprKind::Ref(_)
        | ExprKind::Located { .. } => false,
        ExprKind::Unary(op, x) => unary_faults(*op, elem(x.ty)),
        ExprKind::Binary(op, x, y) => binary_faults(*op, elem(x.ty), elem(y.ty), elem(e.ty), y),
        ExprKind::Convert(x) => {
            let same = types.kind(x.ty) == types.kind(e.ty);
            match (elem(x.ty), elem(e.ty)) {
                _ if same => false,
                (Some(f), Some(t)) => stc_values::conversion_may_fault(f, t),
                // Aggregates: only a copy of one type is total.
                _ => x.ty != e.ty,
            }
        }
        ExprKind::Check { value, lo, hi } => {
            let value = value.unlocated();
            let covered = match (&value.kind, elem(value.ty)) {
                (ExprKind::Const(Value::Int(v)), _) => lo <= v && v <= hi,
                (_, Some(t)) if !is_real(t) => {
                    stc_values::int_range(t).is_some_and(|(tmin, tmax)| *lo <= tmin && tmax <= *hi)
                }
                _ => false,
            };
            !covered
        }
        ExprKind::Intrinsic { func, args } => {
            let arg_types: Vec<Option<ElemType>> = args.iter().map(|a| elem(a.ty)).collect();
            intrinsic_faults(*func, &arg_types, elem(e.ty), args)
        }
    }
}

/// Whether a unary operator on an operand of type `t` can fault.
fn unary_faults(op: UnOp, t: Option<ElemType>) -> bool {
    let Some(t) = t else {
        return true;
    };
    match op {
        UnOp::Neg => !(int_like(t) || is_real(t) || matches!(t, ElemType::Time | ElemType::Ltime)),
        UnOp::Not => !(int_like(t) || t == ElemType::Bool),
    }
}

/// Whether a binary operator with operands of types `a`, `b` and a result
/// of type `res` can fault (`stc_values::binary`); `divisor` is the right
/// operand.
fn binary_faults(
    op: BinOp,
    a: Option<ElemType>,
    b: Option<ElemType>,
    res: Option<ElemType>,
    divisor: &Expr,
) -> bool {
    let dur = |t| matches!(t, ElemType::Time | ElemType::Ltime);
    let is_date = |t| matches!(t, ElemType::Date | ElemType::Ldate);
    let is_tod = |t| matches!(t, ElemType::Tod | ElemType::Ltod);
    let is_dt = |t| matches!(t, ElemType::Dt | ElemType::Ldt);
    let (Some(a), Some(b), Some(res)) = (a, b, res) else {
        return true;
    };
    let nonzero = matches!(divisor.unlocated().kind, ExprKind::Const(Value::Int(v)) if v != 0);
    // A plain integer value (`Value::Int`; not BOOL, a real or a string).
    let string = |t: ElemType| matches!(t, ElemType::String | ElemType::Wstring);
    let int_valued = |t: ElemType| !matches!(t, ElemType::Bool) && !is_real(t) && !string(t);
    match op {
        BinOp::Eq | BinOp::Ne | BinOp::Lt | BinOp::Le | BinOp::Gt | BinOp::Ge => false,
        BinOp::And | BinOp::Or | BinOp::Xor => false,
        _ if is_time_like(a) || is_time_like(b) => match op {
            BinOp::Add | BinOp::Sub if (dur(a) || is_tod(a) || is_dt(a)) && dur(b) => false,
            BinOp::Sub if (is_date(a) && is_date(b)) || (is_tod(a) && is_tod(b)) => false,
            BinOp::Sub if is_dt(a) && is_dt(b) => false,
            // A duration scaled by a real can leave the range of TIME.
            BinOp::Mul if dur(a) && !is_time_like(b) => !int_valued(b),
            BinOp::Mul if dur(b) && !is_time_like(a) => !int_valued(a),
            BinOp::Div if dur(a) && !is_time_like(b) => !(int_valued(b) && nonzero),
            _ => true,
        },
        _ if is_real(a) || is_real(b) || op == BinOp::Pow => {
            let rhs = is_real(b) || (op == BinOp::Pow && int_valued(b));
            op == BinOp::Mod || !is_real(a) || !rhs || !is_real(res)
        }
        // Integer arithmetic (operands `Value::Int` or `Value::Bool`).
        _ if !int_like(res) || string(a) || string(b) => true,
        BinOp::Div | BinOp::Mod => !nonzero,
        BinOp::Add | BinOp::Sub | BinOp::Mul | BinOp::Pow => false,
    }
}

/// Whether a standard function at these argument types can fault.
fn intrinsic_faults(
    f: Intrinsic,
    types: &[Option<ElemType>],
    res: Option<ElemType>,
    args: &[Expr],
) -> bool {
    use Intrinsic as I;
    let two = |op| match (types, args) {
        ([a, b], [_, y]) => binary_faults(op, *a, *b, res, y),
        _ => true,
    };
    match f {
        I::Abs | I::Sqrt | I::Ln | I::Log | I::Exp | I::Sin | I::Cos | I::Tan => false,
        I::Asin | I::Acos | I::Atan | I::Atan2 | I::Expt => false,
        I::Shl | I::Shr | I::Rol | I::Ror => false,
        I::Sel | I::Max | I::Min | I::Limit | I::Move => false,
        I::Len | I::Left | I::Right | I::Mid | I::Insert | I::Delete | I::Replace => false,
        I::Concat | I::Find | I::DayOfWeek | I::Not => false,
        I::Gt | I::Ge | I::Eq | I::Le | I::Lt | I::Ne => false,
        // The selector must name one of the inputs.
        I::Mux => {
            let inputs = args.len() as i128 - 1;
            match (types.first(), args.first().map(|k| &k.unlocated().kind)) {
                (_, Some(ExprKind::Const(Value::Int(k)))) => !(0..inputs).contains(k),
                (Some(Some(t)), _) => {
                    stc_values::int_range(*t).is_none_or(|(lo, hi)| lo < 0 || hi > inputs - 1)
                }
                _ => true,
            }
        }
        I::AddTime | I::AddTodTime | I::AddDtTime => two(BinOp::Add),
        I::SubTime | I::SubTodTime | I::SubDtTime | I::SubDateDate | I::SubTodTod | I::SubDtDt => {
            two(BinOp::Sub)
        }
        I::MulTime => two(BinOp::Mul),
        I::DivTime => two(BinOp::Div),
        I::Sub => two(BinOp::Sub),
        I::Div => two(BinOp::Div),
        I::Mod => two(BinOp::Mod),
        // Folds: only a duration times a real can fault.
        I::Add | I::And | I::Or | I::Xor => false,
        I::Mul => {
            types.iter().any(|t| t.is_some_and(is_time_like))
                && types.iter().any(|t| t.is_some_and(is_real))
        }
        I::Convert { from, to } => stc_values::conversion_may_fault(from, to),
        I::ConcatDateTod | I::ConcatDate | I::ConcatTod | I::ConcatDt => true,
        I::SplitDate | I::SplitTod | I::SplitDt => true,
        I::Trunc { .. } | I::BcdToInt { .. } | I::IntToBcd { .. } => true,
    }
}

/// ANY_INT and BYTE..LWORD.
fn int_like(t: ElemType) -> bool {
    stc_values::is_integer(t)
        || matches!(
            t,
            ElemType::Byte | ElemType::Word | ElemType::Dword | ElemType::Lword
        )
}

#[cfg(test)]
mod tests {
    /// Whether each POU of a valid program (no prelude) may fault, by name.
    fn faults(src: &str) -> Vec<(String, bool)> {
        let m = crate::test_module(src);
        let f = super::may_fault(&m);
        m.pous
            .iter()
            .zip(f)
            .map(|(p, f)| (m.name(p.name).to_ascii_uppercase(), f))
            .collect()
    }

    fn of(all: &[(String, bool)], name: &str) -> bool {
        all.iter()
            .find(|(n, _)| n == name)
            .unwrap_or_else(|| panic!("no POU {name} in {all:?}"))
            .1
    }

    const HALF: &str = "FUNCTION Half : INT
VAR_INPUT x : INT; END_VAR
  Half := x / 2;
END_FUNCTION
FUNCTION Ratio : INT
VAR_INPUT x, y : INT; END_VAR
  Ratio := x / y;
END_FUNCTION
FUNCTION Sum : INT
VAR_INPUT x, y : INT; END_VAR
VAR r : REAL; END_VAR
  Sum := x + y * 3 - Half(x := y);
  IF x > y AND NOT (y = 0) THEN Sum := -Sum MOD 7; END_IF;
  r := INT_TO_REAL(x) / INT_TO_REAL(y);
END_FUNCTION
";

    #[test]
    fn a_division_by_a_variable_may_fault_and_so_may_its_callers() {
        let f = faults(&format!(
            "{HALF}FUNCTION Calls : INT
VAR_INPUT x : INT; END_VAR
  Calls := Ratio(x := x, y := 3) + 1;
END_FUNCTION
PROGRAM P VAR r : INT; END_VAR r := Calls(x := 4); END_PROGRAM"
        ));
        assert!(of(&f, "RATIO"), "{f:?}");
        assert!(of(&f, "CALLS"), "{f:?}");
        assert!(of(&f, "P"), "{f:?}");
    }

    #[test]
    fn arithmetic_that_cannot_fail_does_not_fault() {
        let f = faults(&format!(
            "{HALF}PROGRAM P VAR r : INT; END_VAR r := Sum(x := 4, y := 5); END_PROGRAM"
        ));
        assert!(!of(&f, "HALF"), "{f:?}");
        assert!(!of(&f, "SUM"), "{f:?}");
        assert!(!of(&f, "P"), "{f:?}");
        assert!(of(&f, "RATIO"), "{f:?}");
    }

    #[test]
    fn a_fault_reaches_a_program_through_a_function_block() {
        let src = "FUNCTION_BLOCK Inner
VAR_INPUT i : INT; END_VAR
VAR a : ARRAY[1..4] OF INT; END_VAR
  a[i] := 1;
END_FUNCTION_BLOCK
FUNCTION_BLOCK Outer
VAR_INPUT i : INT; END_VAR
VAR x : Inner; END_VAR
  x(i := i);
END_FUNCTION_BLOCK
FUNCTION_BLOCK Quiet
VAR a : ARRAY[1..4] OF INT; k : INT; END_VAR
  a[2] := 1;
  FOR k := 1 TO 4 DO a[k] := k; END_FOR;
END_FUNCTION_BLOCK
PROGRAM P
VAR o : Outer; END_VAR
  o(i := 5);
END_PROGRAM
PROGRAM Q
VAR qq : Quiet; END_VAR
  qq();
END_PROGRAM";
        let f = faults(src);
        assert!(of(&f, "INNER"), "{f:?}");
        assert!(of(&f, "OUTER"), "{f:?}");
        assert!(of(&f, "P"), "{f:?}");
        // Constant indices and a FOR's control variable inside the bounds.
        assert!(!of(&f, "QUIET"), "{f:?}");
        assert!(!of(&f, "Q"), "{f:?}");
    }

    #[test]
    fn subranges_conversions_and_mux() {
        let src = "TYPE Small : INT(0..10); END_TYPE
FUNCTION Store : INT
VAR_INPUT x : INT; END_VAR
VAR s : Small; END_VAR
  s := x;
  Store := s;
END_FUNCTION
FUNCTION Widen : DINT
VAR_INPUT x : Small; END_VAR
VAR s : Small; END_VAR
  s := 3;
  Widen := INT_TO_DINT(x) + MUX(1, 5, 6);
END_FUNCTION
FUNCTION Round : INT
VAR_INPUT r : REAL; END_VAR
  Round := REAL_TO_INT(r);
END_FUNCTION
FUNCTION Pick : INT
VAR_INPUT k : INT; END_VAR
  Pick := MUX(k, 1, 2, 3);
END_FUNCTION
PROGRAM P VAR r : DINT; END_VAR r := Widen(x := 1); END_PROGRAM";
        let f = faults(src);
        assert!(of(&f, "STORE"), "{f:?}");
        assert!(!of(&f, "WIDEN"), "{f:?}");
        assert!(of(&f, "ROUND"), "{f:?}");
        assert!(of(&f, "PICK"), "{f:?}");
    }

    #[test]
    fn the_fixpoint_ends_on_a_cycle() {
        use crate::{Pou, Stmt, StmtKind};
        // Recursion is rejected by the analyser; build it by hand.
        let src = "FUNCTION A : INT A := 1; END_FUNCTION
FUNCTION B : INT B := 2; END_FUNCTION
PROGRAM P VAR r : INT; END_VAR r := A(); END_PROGRAM";
        let mut m = crate::test_module(src);
        let find = |m: &crate::Module, n: &str| {
            m.pous
                .iter()
                .position(|p: &Pou| m.name(p.name).eq_ignore_ascii_case(n))
                .unwrap()
        };
        let (ia, ib) = (find(&m, "A"), find(&m, "B"));
        let call = |q: usize| Stmt {
            kind: StmtKind::Eval(crate::Expr {
                kind: crate::ExprKind::CallFn {
                    func: stc_sema::PouId(q as u32),
                    inputs: Vec::new(),
                    inouts: Vec::new(),
                    outputs: Vec::new(),
                },
                ty: m.types_bool(),
            }),
            line: 1,
            col: 1,
        };
        let (ca, cb) = (call(ib), call(ia));
        m.pous[stc_sema::PouId(ia as u32)].body.push(ca);
        m.pous[stc_sema::PouId(ib as u32)].body.push(cb);
        assert!(!super::may_fault(&m)[ia]);
        let fault = Stmt {
            kind: StmtKind::Fault(crate::FaultKind::DivisionByZero),
            line: 1,
            col: 1,
        };
        m.pous[stc_sema::PouId(ib as u32)].body.push(fault);
        let f = super::may_fault(&m);
        assert!(f[ia] && f[ib]);
        assert!(f[find(&m, "P")]);
    }
}
