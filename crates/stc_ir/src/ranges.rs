//! Range analysis of array indices: which index expressions of a body are
//! proven to lie inside their bounds, so that a back end may leave out
//! their check (the JIT and the C back end do).
//!
//! A forward walk over the structured body keeps, for the integer
//! variables of the POU, an interval each holds at the current point (a
//! variable without one is anywhere in its type). Facts come from
//! assignments (the interval of the value), from the conditions of IF and
//! of loop exits (`IF NOT (j > 0) THEN BREAK` leaves `j >= 1` after it),
//! and for loops from monotonic induction: a variable the loop changes only
//! by `v := v + d` with `d >= 0` (never wrapping, checked at each such
//! assignment) keeps its lower bound from the loop's entry everywhere in
//! the loop, and symmetrically for `v := v - d`. That covers FOR control
//! variables (whatever their bounds' expressions) and the induction
//! variables of WHILE loops guarded by their own condition (`WHILE j > 0
//! DO ... a[j - 1] ... j := j - 1`). An index is proven when the interval
//! of its expression (exact integer arithmetic, falling back to the whole
//! type where the operation could wrap) lies inside the dimension.
//!
//! It is sound before it is clever: anything that could change a variable
//! behind the walk's back (a call, a write through a reference or `THIS`,
//! an in-out) forgets every fact, a loop containing one starts from
//! nothing, facts are never kept for variables reached through a reference,
//! and a statement that calls proves none of its indices. A body too large
//! to analyse within a fixed budget proves nothing.

use rustc_hash::{FxHashMap, FxHashSet};
use stc_sema::{TypeId, VarId};
use stc_syntax::token::ElemType;
use stc_values::{BinOp, UnOp, Value};

use crate::layout::elem_size;
use crate::visit::{has_call, place_has_call};
use crate::{Expr, ExprKind, Module, Place, Pou, Proj, Root, Stmt, StmtKind, Storage};

/// The index expressions of one body proven inside their bounds.
#[derive(Default, Debug)]
pub struct Proven {
    /// Addresses of the index expressions (as they stand in
    /// [`Proj::Index`]), valid while the module is borrowed.
    at: FxHashSet<usize>,
}

impl Proven {
    /// The proven indices of `pou`'s body.
    pub fn of(m: &Module, pou: &Pou) -> Proven {
        let mut a = Walk {
            m,
            pou,
            budget: BUDGET,
            continues: Vec::new(),
        };
        let mut env = Env::default();
        let mut at = FxHashSet::default();
        a.block(&pou.body, &mut env, &mut at);
        if a.budget == 0 {
            return Proven::default();
        }
        Proven { at }
    }

    /// Whether the index expression `e` (the one in its [`Proj::Index`])
    /// can never be outside its bounds.
    pub fn contains(&self, e: &Expr) -> bool {
        self.at.contains(&(e as *const Expr as usize))
    }

    /// How many indices are proven.
    pub fn len(&self) -> usize {
        self.at.len()
    }

    pub fn is_empty(&self) -> bool {
        self.at.is_empty()
    }
}

/// Loop versioning of the index checks range analysis cannot remove.
///
/// An innermost FOR loop whose body indexes arrays with `v + c`, `c + v`,
/// `v - c` or `v` (`v` its control variable, `c` a constant) gets a guard:
/// a condition on the control variable and the hidden end at the loop's
/// entry under which every value `v` takes in the body (the loop runs `v`
/// monotonically from its value at entry to the end, never past it: the
/// exit test opens the body, the latch's overflow test leaves before a
/// wrap) puts each of those indices inside its dimension, without
/// wrapping in its type. A back end emits the loop twice, behind the
/// guard: a copy without those checks, and the checked loop where the
/// guard fails. Faults stay exact: the check-free copy runs only where no
/// guarded index of any iteration can be out of bounds, so it is the
/// checked loop whenever one would fault (same iteration, same report).
///
/// Only loops whose body (not counting the latch) has no nested loop (one
/// copy each: no growth with depth), no call of a POU (a callee could
/// change the control variable through a reference), no dereference, no
/// `THIS`, no `REF()`, and no assignment of the control variable or the
/// end (the analyser refuses those, E0306: checked again here) are
/// versioned; the indices range analysis already proves are left out of
/// the guard.
#[derive(Default, Debug)]
pub struct Versions {
    /// By address of the loop statement.
    loops: FxHashMap<usize, Version>,
}

/// The guard of one versioned loop and the indices it makes safe.
#[derive(Clone, Debug)]
pub struct Version {
    /// A BOOL expression, evaluated just before the loop.
    pub guard: Expr,
    /// Addresses of the index expressions (as in [`Proj::Index`]).
    indices: FxHashSet<usize>,
}

impl Version {
    /// Whether the index expression `e` needs no check in the loop's
    /// check-free copy.
    pub fn covers(&self, e: &Expr) -> bool {
        self.indices.contains(&(e as *const Expr as usize))
    }
}

impl Versions {
    /// The versioned loops of `pou`'s body (`proven`: its proven indices).
    pub fn of(m: &Module, pou: &Pou, proven: &Proven) -> Versions {
        let mut loops = FxHashMap::default();
        version_block(m, pou, proven, &pou.body, &mut loops);
        Versions { loops }
    }

    /// The version of a loop statement, when it has one.
    pub fn get(&self, s: &Stmt) -> Option<&Version> {
        self.loops.get(&(s as *const Stmt as usize))
    }

    pub fn len(&self) -> usize {
        self.loops.len()
    }

    pub fn is_empty(&self) -> bool {
        self.loops.is_empty()
    }
}

fn version_block(
    m: &Module,
    pou: &Pou,
    proven: &Proven,
    stmts: &[Stmt],
    out: &mut FxHashMap<usize, Version>,
) {
    for s in stmts {
        match &s.kind {
            StmtKind::If {
                then_body,
                else_body,
                ..
            } => {
                version_block(m, pou, proven, then_body, out);
                version_block(m, pou, proven, else_body, out);
            }
            StmtKind::Switch { arms, default, .. } => {
                for a in arms {
                    version_block(m, pou, proven, &a.body, out);
                }
                version_block(m, pou, proven, default, out);
            }
            StmtKind::Loop { body, latch } => {
                version_block(m, pou, proven, body, out);
                version_block(m, pou, proven, latch, out);
                if let Some(v) = version_of(m, pou, proven, body) {
                    out.insert(s as *const Stmt as usize, v);
                }
            }
            _ => {}
        }
    }
}

/// Whether a body may change `vars` other than by its latch, or holds what
/// versioning leaves alone (a nested loop, a call, a reference).
fn disqualified(stmts: &[Stmt], vars: &[VarId]) -> bool {
    let mut bad = false;
    for s in stmts {
        match &s.kind {
            StmtKind::Assign { place, .. } => {
                if matches!(place.root, Root::Var(v) if vars.contains(&v)) {
                    return true;
                }
            }
            StmtKind::CallFb { .. } | StmtKind::Loop { .. } => return true,
            StmtKind::If {
                then_body,
                else_body,
                ..
            } => bad |= disqualified(then_body, vars) || disqualified(else_body, vars),
            StmtKind::Switch { arms, default, .. } => {
                bad |=
                    arms.iter().any(|a| disqualified(&a.body, vars)) || disqualified(default, vars)
            }
            _ => {}
        }
    }
    if bad {
        return true;
    }
    let (mut calls, mut refs) = (false, false);
    crate::visit::walk(
        stmts,
        &mut |e| calls |= matches!(e.kind, ExprKind::CallFn { .. } | ExprKind::Ref(_)),
        &mut |p| refs |= matches!(p.root, Root::Deref(_) | Root::This),
    );
    calls || refs
}

/// `v + c` as `c` (`v`, `c + v`, `v - c` too), where `v` is `var` read
/// whole.
fn offset_of(e: &Expr, var: VarId) -> Option<i128> {
    let is_var = |x: &Expr| {
        matches!(&x.unlocated().kind, ExprKind::Load(p)
            if p.proj.is_empty() && matches!(p.root, Root::Var(v) if v == var))
    };
    let konst = |x: &Expr| match &x.unlocated().kind {
        ExprKind::Const(Value::Int(c)) => Some(*c),
        _ => None,
    };
    let e = e.unlocated();
    if is_var(e) {
        return Some(0);
    }
    match &e.kind {
        ExprKind::Binary(BinOp::Add, x, y) if is_var(x) => konst(y),
        ExprKind::Binary(BinOp::Add, x, y) if is_var(y) => konst(x),
        ExprKind::Binary(BinOp::Sub, x, y) if is_var(x) => konst(y)?.checked_neg(),
        _ => None,
    }
}

fn version_of(m: &Module, pou: &Pou, proven: &Proven, body: &[Stmt]) -> Option<Version> {
    // The FOR's exit test opens the body: `IF v > end THEN BREAK` (a
    // positive step), `IF v < end THEN BREAK` (a negative one).
    let StmtKind::If { cond, .. } = &body.first()?.kind else {
        return None;
    };
    let ExprKind::Binary(op, a, b) = &cond.kind else {
        return None;
    };
    let up = match op {
        BinOp::Gt => true,
        BinOp::Lt => false,
        _ => return None,
    };
    let (ExprKind::Load(pv), ExprKind::Load(pe)) = (&a.kind, &b.kind) else {
        return None;
    };
    let (Root::Var(v), Root::Var(end)) = (&pv.root, &pe.root) else {
        return None;
    };
    let (v, end) = (*v, *end);
    if !pv.proj.is_empty()
        || !pe.proj.is_empty()
        || pou.var(end).hidden != Some("end")
        || pou.var(v).storage == Storage::Ref
    {
        return None;
    }
    let vt = pou.var(v).ty;
    let (tmin, tmax) = m.types.scalar(vt).and_then(int_range)?;
    // Values compared as 64-bit integers by the back ends.
    if tmin < i128::from(i64::MIN) || tmax > i128::from(i64::MAX) {
        return None;
    }
    if disqualified(body, &[v, end]) {
        return None;
    }
    // Every value of `v` in the body must lie in lo..=hi.
    let (mut lo, mut hi) = (tmin, tmax);
    let mut indices = FxHashSet::default();
    crate::visit::places(body, &mut |p| {
        for proj in &p.proj {
            let Proj::Index(idx) = proj else { continue };
            for (e, dlo, dhi) in idx {
                if proven.contains(e) {
                    continue;
                }
                let Some(c) = offset_of(e, v) else { continue };
                let Some((emin, emax)) = m.types.scalar(e.ty).and_then(int_range) else {
                    continue;
                };
                // v + c inside the dimension and inside its own type (no
                // wrap): v in (max(dlo, emin) - c)..=(min(dhi, emax) - c).
                lo = lo.max((*dlo).max(emin) - c);
                hi = hi.min((*dhi).min(emax) - c);
                indices.insert(e as *const Expr as usize);
            }
        }
    });
    if indices.is_empty() || lo > hi {
        return None;
    }
    let bool_ty = cond.ty;
    let load = |x: VarId| Expr {
        kind: ExprKind::Load(Place {
            root: Root::Var(x),
            proj: Vec::new(),
            ty: vt,
        }),
        ty: vt,
    };
    let konst = |c: i128| Expr {
        kind: ExprKind::Const(Value::Int(c)),
        ty: vt,
    };
    let cmp = |op: BinOp, x: Expr, y: Expr| Expr {
        kind: ExprKind::Binary(op, Box::new(x), Box::new(y)),
        ty: bool_ty,
    };
    // The first value is `v` at entry, the last at most `end` (counting
    // up) or the reverse.
    let (first, last) = if up { (v, end) } else { (end, v) };
    let guard = cmp(
        BinOp::And,
        cmp(BinOp::Ge, load(first), konst(lo)),
        cmp(BinOp::Le, load(last), konst(hi)),
    );
    Some(Version { guard, indices })
}

/// Statements visited at most (loops are walked again when an induction
/// assumption fails): past it, nothing is proven.
const BUDGET: u32 = 200_000;

type Range = (i128, i128);

/// Intervals of variables at a point of the body.
#[derive(Clone, Default, Debug)]
struct Env {
    facts: FxHashMap<VarId, Range>,
}

impl Env {
    fn join(a: Option<Env>, b: Option<Env>) -> Option<Env> {
        match (a, b) {
            (Some(a), Some(b)) => Some(Env {
                facts: a
                    .facts
                    .iter()
                    .filter_map(|(v, &(l1, h1))| {
                        b.facts
                            .get(v)
                            .map(|&(l2, h2)| (*v, (l1.min(l2), h1.max(h2))))
                    })
                    .collect(),
            }),
            (a, None) => a,
            (None, b) => b,
        }
    }
}

/// The direction a loop moves an induction variable in.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
enum Dir {
    Up,
    Down,
}

struct Walk<'a> {
    m: &'a Module,
    pou: &'a Pou,
    budget: u32,
    /// Per enclosing loop: the environments at its CONTINUEs.
    continues: Vec<Vec<Env>>,
}

/// The range of an integer type (BOOL 0..1); `None` for anything else.
fn int_range(e: ElemType) -> Option<Range> {
    use ElemType as E;
    let signed = match e {
        E::Bool => return Some((0, 1)),
        E::Sint | E::Int | E::Dint | E::Lint => true,
        E::Usint | E::Uint | E::Udint | E::Ulint | E::Byte | E::Word | E::Dword | E::Lword => false,
        _ => return None,
    };
    let bits = elem_size(e) * 8;
    Some(if signed {
        (-(1i128 << (bits - 1)), (1i128 << (bits - 1)) - 1)
    } else {
        (0, (1i128 << bits) - 1)
    })
}

impl Walk<'_> {
    fn type_range(&self, t: TypeId) -> Option<Range> {
        self.m.types.scalar(t).and_then(int_range)
    }

    /// The variable a place names whole, when facts may be kept for it.
    fn whole_var(&self, p: &Place) -> Option<VarId> {
        match (&p.root, p.proj.is_empty()) {
            (Root::Var(v), true)
                if self.pou.vars[*v].storage != Storage::Ref
                    && self.type_range(self.pou.vars[*v].ty).is_some() =>
            {
                Some(*v)
            }
            _ => None,
        }
    }

    /// Whether assigning this place may change a variable other than the
    /// one it names whole (through a reference, `THIS`, an in-out).
    fn writes_hidden(&self, p: &Place) -> bool {
        match &p.root {
            Root::Var(v) => self.pou.vars[*v].storage == Storage::Ref,
            Root::Deref(_) | Root::This => true,
            Root::Global(_) | Root::Direct(_) => false,
        }
    }

    /// The interval of an integer expression's value.
    fn range(&self, e: &Expr, env: &Env) -> Option<Range> {
        let full = self.type_range(e.ty);
        let fit = |r: Range| match full {
            Some((lo, hi)) if lo <= r.0 && r.1 <= hi => Some(r),
            _ => full,
        };
        match &e.kind {
            ExprKind::Located { expr, .. } => self.range(expr, env).or(full),
            ExprKind::Const(Value::Int(c)) => fit((*c, *c)),
            ExprKind::Load(p) => match self.whole_var(p) {
                Some(v) => env.facts.get(&v).copied().or(full),
                None => full,
            },
            ExprKind::Check { value, lo, hi } => {
                let (a, b) = self.range(value, env).or(full)?;
                let r = (a.max(*lo), b.min(*hi));
                if r.0 <= r.1 {
                    Some(r)
                } else {
                    full
                }
            }
            ExprKind::Convert(x) => match self.range(x, env) {
                Some(r) => fit(r),
                None => full,
            },
            ExprKind::Binary(op, x, y) if full.is_some() => {
                let (Some((a, b)), Some((c, d))) = (self.range(x, env), self.range(y, env)) else {
                    return full;
                };
                let r = match op {
                    BinOp::Add => (a.checked_add(c)?, b.checked_add(d)?),
                    BinOp::Sub => (a.checked_sub(d)?, b.checked_sub(c)?),
                    BinOp::Mul => {
                        let ps = [
                            a.checked_mul(c)?,
                            a.checked_mul(d)?,
                            b.checked_mul(c)?,
                            b.checked_mul(d)?,
                        ];
                        (*ps.iter().min()?, *ps.iter().max()?)
                    }
                    // A positive constant divisor (truncation toward 0 is
                    // monotonic); a zero divisor faults.
                    BinOp::Div if c == d && c > 0 => (a / c, b / c),
                    BinOp::Mod if c == d && c > 0 => {
                        if a >= 0 {
                            (0, b.min(c - 1))
                        } else {
                            (-(c - 1), c - 1)
                        }
                    }
                    _ => return full,
                };
                fit(r)
            }
            _ => full,
        }
    }

    /// `env` narrowed by `cond` being `truth`.
    fn refine(&self, cond: &Expr, truth: bool, env: &mut Env) {
        match &cond.kind {
            ExprKind::Located { expr, .. } => self.refine(expr, truth, env),
            ExprKind::Unary(UnOp::Not, x)
                if self.m.types.scalar(cond.ty) == Some(ElemType::Bool) =>
            {
                self.refine(x, !truth, env)
            }
            ExprKind::Binary(BinOp::And, x, y)
                if truth && self.m.types.scalar(cond.ty) == Some(ElemType::Bool) =>
            {
                self.refine(x, true, env);
                self.refine(y, true, env);
            }
            ExprKind::Binary(BinOp::Or, x, y)
                if !truth && self.m.types.scalar(cond.ty) == Some(ElemType::Bool) =>
            {
                self.refine(x, false, env);
                self.refine(y, false, env);
            }
            ExprKind::Binary(op, x, y) => {
                let Some(op) = (if truth { Some(*op) } else { negate(*op) }) else {
                    return;
                };
                // Both sides integers: the comparison is of their values.
                let (Some(rx), Some(ry)) = (self.range(x, env), self.range(y, env)) else {
                    return;
                };
                if let ExprKind::Load(p) = &x.unlocated().kind {
                    if let Some(v) = self.whole_var(p) {
                        narrow(env, v, rx, op, ry);
                    }
                }
                if let ExprKind::Load(p) = &y.unlocated().kind {
                    if let Some(v) = self.whole_var(p) {
                        if let Some(f) = flip(op) {
                            narrow(env, v, ry, f, rx);
                        }
                    }
                }
            }
            _ => {}
        }
    }

    /// Marks the indices of an expression proven under `env`.
    fn expr(&self, e: &Expr, env: &Env, at: &mut FxHashSet<usize>) {
        match &e.kind {
            ExprKind::Load(p) | ExprKind::Ref(p) => self.place(p, env, at),
            ExprKind::Unary(_, x) | ExprKind::Convert(x) => self.expr(x, env, at),
            ExprKind::Check { value, .. } => self.expr(value, env, at),
            ExprKind::Located { expr, .. } => self.expr(expr, env, at),
            ExprKind::Binary(_, x, y) => {
                self.expr(x, env, at);
                self.expr(y, env, at);
            }
            ExprKind::Intrinsic { args, .. } => args.iter().for_each(|a| self.expr(a, env, at)),
            // A statement with a call proves nothing (never reached).
            ExprKind::CallFn { .. } | ExprKind::Const(_) | ExprKind::CurTime | ExprKind::Null => {}
        }
    }

    fn place(&self, p: &Place, env: &Env, at: &mut FxHashSet<usize>) {
        if let Root::Deref(r) = &p.root {
            self.expr(r, env, at);
        }
        for pr in &p.proj {
            if let Proj::Index(idx) = pr {
                for (e, lo, hi) in idx {
                    self.expr(e, env, at);
                    if let Some((a, b)) = self.range(e, env) {
                        if *lo <= a && b <= *hi {
                            at.insert(e as *const Expr as usize);
                        }
                    }
                }
            }
        }
    }

    /// Walks a block from `env`; `env` becomes the facts after it when it
    /// falls through (`false` when it never does: BREAK, CONTINUE,
    /// RETURN, a fault).
    fn block(&mut self, stmts: &[Stmt], env: &mut Env, at: &mut FxHashSet<usize>) -> bool {
        for s in stmts {
            if self.budget == 0 {
                return false;
            }
            self.budget -= 1;
            if !self.stmt(s, env, at) {
                return false;
            }
        }
        true
    }

    fn stmt(&mut self, s: &Stmt, env: &mut Env, at: &mut FxHashSet<usize>) -> bool {
        match &s.kind {
            StmtKind::Assign { place, value } => {
                if has_call(value) || place_has_call(place) {
                    env.facts.clear();
                    return true;
                }
                self.place(place, env, at);
                self.expr(value, env, at);
                if self.writes_hidden(place) {
                    env.facts.clear();
                } else if let Some(v) = self.whole_var(place) {
                    match self.range(value, env) {
                        Some(r) => env.facts.insert(v, r),
                        None => env.facts.remove(&v),
                    };
                } else if let Root::Var(v) = place.root {
                    // A bit of it, or an element: what was known is gone.
                    env.facts.remove(&v);
                }
                true
            }
            StmtKind::CallFb { .. } => {
                env.facts.clear();
                true
            }
            StmtKind::Eval(e) => {
                if has_call(e) {
                    env.facts.clear();
                } else {
                    self.expr(e, env, at);
                }
                true
            }
            StmtKind::If {
                cond,
                then_body,
                else_body,
            } => {
                // A condition that calls says nothing: the call may change
                // a variable after the condition read it.
                let called = has_call(cond);
                if called {
                    env.facts.clear();
                } else {
                    self.expr(cond, env, at);
                }
                let mut t = env.clone();
                let mut e = env.clone();
                if !called {
                    self.refine(cond, true, &mut t);
                    self.refine(cond, false, &mut e);
                }
                let t = self.block(then_body, &mut t, at).then_some(t);
                let e = self.block(else_body, &mut e, at).then_some(e);
                match Env::join(t, e) {
                    Some(j) => {
                        *env = j;
                        true
                    }
                    None => false,
                }
            }
            StmtKind::Switch {
                selector,
                arms,
                default,
            } => {
                if has_call(selector) {
                    env.facts.clear();
                } else {
                    self.expr(selector, env, at);
                }
                let mut out: Option<Env> = None;
                let mut any = false;
                for body in arms.iter().map(|a| &a.body).chain(std::iter::once(default)) {
                    let mut b = env.clone();
                    if self.block(body, &mut b, at) {
                        out = Env::join(out, Some(b));
                        any = true;
                    }
                }
                match out {
                    Some(j) if any => {
                        *env = j;
                        true
                    }
                    _ => false,
                }
            }
            StmtKind::Loop { body, latch } => {
                self.loop_(body, latch, env, at);
                true
            }
            StmtKind::Continue => {
                if let Some(c) = self.continues.last_mut() {
                    c.push(env.clone());
                }
                false
            }
            StmtKind::Break | StmtKind::Return | StmtKind::Fault(_) => false,
        }
    }

    /// A loop: the facts at its head are those of `env` about variables it
    /// never assigns, and the kept bound of its monotonic induction
    /// variables; they hold everywhere in it and after it.
    fn loop_(&mut self, body: &[Stmt], latch: &[Stmt], env: &mut Env, at: &mut FxHashSet<usize>) {
        let mut assigned: FxHashMap<VarId, Option<Dir>> = FxHashMap::default();
        let mut hidden = false;
        for part in [body, latch] {
            self.assignments(part, env, &mut assigned, &mut hidden);
        }
        if hidden {
            env.facts.clear();
        }
        loop {
            let mut head = env.clone();
            head.facts.retain(|v, r| match assigned.get(v) {
                None => true,
                Some(None) => false,
                Some(Some(Dir::Up)) => {
                    r.1 = self.type_range(self.pou.vars[*v].ty).map_or(r.1, |t| t.1);
                    true
                }
                Some(Some(Dir::Down)) => {
                    r.0 = self.type_range(self.pou.vars[*v].ty).map_or(r.0, |t| t.0);
                    true
                }
            });
            let mut pass = FxHashSet::default();
            let mut broken: Option<VarId> = None;
            let mut b = head.clone();
            self.continues.push(Vec::new());
            let falls = self.block(body, &mut b, &mut pass);
            let conts = self.continues.pop().unwrap_or_default();
            let mut l = conts
                .into_iter()
                .map(Some)
                .fold(falls.then_some(b), Env::join);
            if let Some(l) = l.as_mut() {
                self.continues.push(Vec::new());
                self.block(latch, l, &mut pass);
                self.continues.pop();
            }
            // Check the induction assumptions on a walk that records them.
            for (v, dir) in &assigned {
                if let (Some(d), true) = (dir, head.facts.contains_key(v)) {
                    if !self.steps_ok(body, latch, &head, *v, *d) {
                        broken = Some(*v);
                        break;
                    }
                }
            }
            match broken {
                Some(v) if self.budget > 0 => {
                    assigned.insert(v, None);
                }
                _ => {
                    at.extend(pass);
                    *env = head;
                    return;
                }
            }
        }
    }

    /// The variables a loop assigns, with the direction when every
    /// assignment is `v := v + d` / `v := v - d` (the sign of `d` as seen
    /// at the loop's entry: verified later); `hidden` when it contains
    /// anything that may change variables unseen.
    fn assignments(
        &self,
        stmts: &[Stmt],
        env: &Env,
        out: &mut FxHashMap<VarId, Option<Dir>>,
        hidden: &mut bool,
    ) {
        for s in stmts {
            match &s.kind {
                StmtKind::Assign { place, value } => {
                    if has_call(value) || place_has_call(place) || self.writes_hidden(place) {
                        *hidden = true;
                    }
                    if let Root::Var(v) = place.root {
                        let d = if place.proj.is_empty() {
                            self.step_dir(v, value, env)
                        } else {
                            None
                        };
                        let e = out.entry(v).or_insert(d);
                        if *e != d {
                            *e = None;
                        }
                    }
                }
                StmtKind::CallFb { .. } => *hidden = true,
                StmtKind::Eval(e) if has_call(e) => *hidden = true,
                StmtKind::If {
                    cond,
                    then_body,
                    else_body,
                } => {
                    if has_call(cond) {
                        *hidden = true;
                    }
                    self.assignments(then_body, env, out, hidden);
                    self.assignments(else_body, env, out, hidden);
                }
                StmtKind::Switch {
                    selector,
                    arms,
                    default,
                } => {
                    if has_call(selector) {
                        *hidden = true;
                    }
                    for a in arms {
                        self.assignments(&a.body, env, out, hidden);
                    }
                    self.assignments(default, env, out, hidden);
                }
                StmtKind::Loop { body, latch } => {
                    self.assignments(body, env, out, hidden);
                    self.assignments(latch, env, out, hidden);
                }
                _ => {}
            }
        }
    }

    /// `v := v + d` or `v := v - d`: the step `d` (as an expression with
    /// its sign: `true` for a subtraction).
    fn step_of(v: VarId, value: &Expr) -> Option<(&Expr, bool)> {
        let is_v = |e: &Expr| {
            matches!(&e.unlocated().kind,
                ExprKind::Load(p) if matches!(p.root, Root::Var(x) if x == v) && p.proj.is_empty())
        };
        match &value.unlocated().kind {
            ExprKind::Binary(BinOp::Add, x, d) if is_v(x) => Some((d, false)),
            ExprKind::Binary(BinOp::Add, d, x) if is_v(x) => Some((d, false)),
            ExprKind::Binary(BinOp::Sub, x, d) if is_v(x) => Some((d, true)),
            _ => None,
        }
    }

    fn step_dir(&self, v: VarId, value: &Expr, env: &Env) -> Option<Dir> {
        let (d, neg) = Self::step_of(v, value)?;
        let (lo, hi) = self.range(d, env)?;
        match (lo >= 0, hi <= 0, neg) {
            (true, _, false) | (_, true, true) => Some(Dir::Up),
            (_, true, false) | (true, _, true) => Some(Dir::Down),
            _ => None,
        }
    }

    /// Whether every assignment of `v` in the loop, walked from `head`,
    /// moves it in direction `dir` without wrapping.
    fn steps_ok(&mut self, body: &[Stmt], latch: &[Stmt], head: &Env, v: VarId, dir: Dir) -> bool {
        let mut ok = true;
        let mut b = head.clone();
        self.continues.push(Vec::new());
        let falls = self.check_block(body, &mut b, v, dir, &mut ok);
        let conts = self.continues.pop().unwrap_or_default();
        let l = conts
            .into_iter()
            .map(Some)
            .fold(falls.then_some(b), Env::join);
        if let Some(mut l) = l {
            self.continues.push(Vec::new());
            self.check_block(latch, &mut l, v, dir, &mut ok);
            self.continues.pop();
        }
        ok
    }

    /// [`Self::block`] that also checks each assignment of `v` (nested
    /// loops are walked by the ordinary walk, which checks their own
    /// assumptions; an assignment of `v` inside one is checked there
    /// against the facts at its point as well).
    fn check_block(
        &mut self,
        stmts: &[Stmt],
        env: &mut Env,
        v: VarId,
        dir: Dir,
        ok: &mut bool,
    ) -> bool {
        let mut sink = FxHashSet::default();
        for s in stmts {
            if self.budget == 0 {
                *ok = false;
                return false;
            }
            self.budget -= 1;
            match &s.kind {
                StmtKind::Assign { place, value }
                    if matches!(place.root, Root::Var(x) if x == v) && place.proj.is_empty() =>
                {
                    let good = Self::step_of(v, value).is_some_and(|(d, neg)| {
                        let dr = self.range(d, env);
                        let vr = env
                            .facts
                            .get(&v)
                            .copied()
                            .or(self.type_range(self.pou.vars[v].ty));
                        let full = self.type_range(self.pou.vars[v].ty);
                        match (dr, vr, full) {
                            (Some((dl, dh)), Some((vl, vh)), Some((tl, th))) => {
                                let (sl, sh) = if neg { (-dh, -dl) } else { (dl, dh) };
                                let sign = match dir {
                                    Dir::Up => sl >= 0,
                                    Dir::Down => sh <= 0,
                                };
                                sign && vl + sl >= tl && vh + sh <= th
                            }
                            _ => false,
                        }
                    });
                    if !good {
                        *ok = false;
                    }
                    if !self.stmt(s, env, &mut sink) {
                        return false;
                    }
                }
                StmtKind::If {
                    cond,
                    then_body,
                    else_body,
                } if !has_call(cond) => {
                    let mut t = env.clone();
                    self.refine(cond, true, &mut t);
                    let mut e = env.clone();
                    self.refine(cond, false, &mut e);
                    let t = self.check_block(then_body, &mut t, v, dir, ok).then_some(t);
                    let e = self.check_block(else_body, &mut e, v, dir, ok).then_some(e);
                    match Env::join(t, e) {
                        Some(j) => *env = j,
                        None => return false,
                    }
                }
                StmtKind::Switch {
                    selector,
                    arms,
                    default,
                } if !has_call(selector) => {
                    let mut out: Option<Env> = None;
                    for body in arms.iter().map(|a| &a.body).chain(std::iter::once(default)) {
                        let mut b = env.clone();
                        if self.check_block(body, &mut b, v, dir, ok) {
                            out = Env::join(out, Some(b));
                        }
                    }
                    match out {
                        Some(j) => *env = j,
                        None => return false,
                    }
                }
                StmtKind::Loop { body, latch } => {
                    // An assignment of `v` in a nested loop is checked from
                    // that loop's head (which knows less: sound).
                    let mut inner = env.clone();
                    self.loop_(body, latch, &mut inner, &mut sink);
                    let mut h = inner.clone();
                    self.continues.push(Vec::new());
                    let _ = self.check_block(body, &mut h, v, dir, ok);
                    self.continues.pop();
                    let mut h2 = inner.clone();
                    self.continues.push(Vec::new());
                    let _ = self.check_block(latch, &mut h2, v, dir, ok);
                    self.continues.pop();
                    *env = inner;
                }
                _ => {
                    if !self.stmt(s, env, &mut sink) {
                        return false;
                    }
                }
            }
        }
        true
    }
}

/// The comparison that holds when `op` does not (`None`: not a
/// comparison, or `<>`, which says nothing about an interval).
fn negate(op: BinOp) -> Option<BinOp> {
    Some(match op {
        BinOp::Gt => BinOp::Le,
        BinOp::Ge => BinOp::Lt,
        BinOp::Lt => BinOp::Ge,
        BinOp::Le => BinOp::Gt,
        BinOp::Ne => BinOp::Eq,
        _ => return None,
    })
}

/// `y op x` for `x op y`.
fn flip(op: BinOp) -> Option<BinOp> {
    Some(match op {
        BinOp::Gt => BinOp::Lt,
        BinOp::Ge => BinOp::Le,
        BinOp::Lt => BinOp::Gt,
        BinOp::Le => BinOp::Ge,
        BinOp::Eq => BinOp::Eq,
        _ => return None,
    })
}

/// Narrows `v` (in `rv`) by `v op y` with `y` in `ry`.
fn narrow(env: &mut Env, v: VarId, rv: Range, op: BinOp, (yl, yh): Range) {
    let (mut lo, mut hi) = rv;
    match op {
        BinOp::Gt => lo = lo.max(yl + 1),
        BinOp::Ge => lo = lo.max(yl),
        BinOp::Lt => hi = hi.min(yh - 1),
        BinOp::Le => hi = hi.min(yh),
        BinOp::Eq => {
            lo = lo.max(yl);
            hi = hi.min(yh);
        }
        _ => return,
    }
    if lo <= hi {
        env.facts.insert(v, (lo, hi));
    }
    // An empty interval: the branch cannot run; keeping the old facts is
    // sound.
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The proven and the checked indices of the program's body, in
    /// source order (as `true`/`false`).
    fn indices(src: &str) -> Vec<bool> {
        let m = crate::test_module(src);
        let pou = m
            .pous
            .iter()
            .find(|p| !p.is_std && p.kind == stc_syntax::ast::PouKind::Program)
            .expect("a program");
        let proven = Proven::of(&m, pou);
        let mut out = Vec::new();
        crate::visit::places(&pou.body, &mut |p| {
            for pr in &p.proj {
                if let Proj::Index(idx) = pr {
                    for (e, _, _) in idx {
                        if !matches!(e.unlocated().kind, ExprKind::Const(_)) {
                            out.push(proven.contains(e));
                        }
                    }
                }
            }
        });
        out
    }

    /// For each loop of the program's body with a version: the guard's
    /// bounds and how many indices it covers.
    fn versions(src: &str) -> Vec<(i128, i128, usize)> {
        let m = crate::test_module(src);
        let pou = m
            .pous
            .iter()
            .find(|p| !p.is_std && p.kind == stc_syntax::ast::PouKind::Program)
            .expect("a program");
        let proven = Proven::of(&m, pou);
        let vs = Versions::of(&m, pou, &proven);
        let mut out = Vec::new();
        fn walk(stmts: &[Stmt], vs: &Versions, out: &mut Vec<(i128, i128, usize)>) {
            for s in stmts {
                match &s.kind {
                    StmtKind::Loop { body, .. } => {
                        if let Some(v) = vs.get(s) {
                            let konst = |e: &Expr| match &e.kind {
                                ExprKind::Binary(_, _, c) => match &c.kind {
                                    ExprKind::Const(Value::Int(x)) => *x,
                                    _ => i128::MIN,
                                },
                                _ => i128::MIN,
                            };
                            let ExprKind::Binary(BinOp::And, a, b) = &v.guard.kind else {
                                panic!("a guard is a conjunction");
                            };
                            out.push((konst(a), konst(b), v.indices.len()));
                        }
                        walk(body, vs, out);
                    }
                    StmtKind::If {
                        then_body,
                        else_body,
                        ..
                    } => {
                        walk(then_body, vs, out);
                        walk(else_body, vs, out);
                    }
                    _ => {}
                }
            }
        }
        walk(&pou.body, &vs, &mut out);
        out
    }

    #[test]
    fn for_loops_with_unproven_affine_indices_are_versioned() {
        // a[i + 1] and a[i - 1] of 0..9: i in 1..8; a[i + k] (k not
        // constant) is left checked; the outer loop (a nested loop)
        // and the loop with a call are not versioned; the constant FOR
        // is proven, nothing to version.
        let src = "FUNCTION F : DINT VAR_INPUT x : DINT; END_VAR F := x; END_FUNCTION
            PROGRAM P VAR a : ARRAY[0..9] OF DINT; i, j, k, n : DINT; END_VAR
            FOR j := 0 TO n DO
                FOR i := 1 TO n DO
                    a[i + 1] := a[i - 1] + a[i + k];
                END_FOR;
            END_FOR;
            FOR i := 0 TO n DO a[i] := F(i); END_FOR;
            FOR i := n TO 0 BY -1 DO a[i] := 0; END_FOR;
            FOR i := 0 TO 9 DO a[i] := 0; END_FOR;
        END_PROGRAM";
        assert_eq!(versions(src), vec![(1, 8, 2), (0, 9, 1)]);
    }

    #[test]
    fn for_and_guarded_while_indices_are_proven() {
        let src = "PROGRAM P VAR a : ARRAY[0..9] OF DINT; i, j, t : DINT; END_VAR
            FOR i := 1 TO 9 DO
                t := a[i]; j := i;
                WHILE j > 0 DO
                    IF a[j - 1] <= t THEN EXIT; END_IF;
                    a[j] := a[j - 1];
                    j := j - 1;
                END_WHILE;
                a[j] := t;
            END_FOR;
            END_PROGRAM";
        // a[i], a[j - 1], a[j], a[j - 1] proven; a[j] after the loop is not
        // (j >= 0 there is not derived).
        assert_eq!(indices(src), vec![true, true, true, true, false]);
    }

    #[test]
    fn linear_indices_of_nested_fors_are_proven() {
        let src = "PROGRAM P VAR x : ARRAY[0..99] OF DINT; n, k, s : DINT; END_VAR
            FOR n := 9 TO 99 DO
                FOR k := 0 TO 9 DO s := s + x[n - k]; END_FOR;
                FOR k := 0 TO 10 DO s := s + x[n - k]; END_FOR;
            END_FOR;
            END_PROGRAM";
        assert_eq!(indices(src), vec![true, false]);
    }

    #[test]
    fn boundary_and_unguarded_indices_keep_their_check() {
        let src = "PROGRAM P VAR a : ARRAY[0..9] OF DINT; i, j : DINT; b : BYTE; c : ARRAY[0..255] OF INT; END_VAR
            FOR i := 0 TO 10 DO a[i] := 1; END_FOR;
            j := 0;
            WHILE j <= 9 DO a[j] := 2; j := j + 2; END_WHILE;
            WHILE j < 10 DO a[j] := 2; j := j * 2; END_WHILE;
            j := 5;
            WHILE j > 0 DO a[j] := 3; j := j + 1; END_WHILE;
            c[b] := 1;
            END_PROGRAM";
        // FOR to 10: not proven; j += 2 from 0, guarded: proven; j * 2: not;
        // j grows under a lower guard only: not; a BYTE index of 0..255:
        // proven.
        assert_eq!(indices(src), vec![false, true, false, false, true]);
    }

    #[test]
    fn a_call_or_a_reference_forgets_the_facts() {
        let src = "FUNCTION F : DINT VAR_INPUT x : DINT; END_VAR F := x; END_FUNCTION
            PROGRAM P VAR a : ARRAY[0..9] OF DINT; i, j : DINT; r : REF_TO DINT; END_VAR
            j := 3;
            F(x := 1);
            a[j] := 1;
            j := 3;
            r := REF(j);
            r^ := 20;
            a[j] := 1;
            FOR i := 0 TO 9 DO a[i] := F(x := i); END_FOR;
            END_PROGRAM";
        assert_eq!(indices(src), vec![false, false, false]);
    }
}
