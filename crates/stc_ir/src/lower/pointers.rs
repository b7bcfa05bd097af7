//! CODESYS pointers (docs/oop.md, "Pointers"), lowered to what every back
//! end already has: a pointer is the structure `{OBJECT, BASE, OFFSET}`
//! of [`stc_sema::PtrInfo`] (the object kind, 0 for NULL; a reference to
//! the whole object; the byte offset into it), so nothing here needs a
//! back end.
//!
//! - `ADR(x)` fills a temporary: the kind of `x`'s object (the array for
//!   an element), the reference to it, and the element's byte offset.
//! - `p + n`, `p - n` copy `p` and move the offset; `p - q` and the
//!   comparisons check that both point into one object (else the fault
//!   `pointer out of bounds`) and compare offsets.
//! - `p^` (and `p^[i]`, which is `(p + i * SIZEOF(element))^`) calls a
//!   helper FUNCTION, one per element type (`Helpers`, built after every
//!   POU by `ptr_helper`): a `SWITCH` on the object kind over the kinds
//!   that type can see, each arm checking the offset against its object
//!   (whole elements, inside it) and giving a reference to the element,
//!   through which the statement reads or writes. A kind that is a STRING
//!   seen through a pointer to BYTE (USINT, CHAR) reads its characters and
//!   a NUL (the GET helper), and a write changes the string (the SET
//!   helper, after the statement: a NUL inside it ends it there). A helper
//!   never faults: it returns a status (1 NULL, 2 outside the object) and
//!   the caller raises `NULL dereference` or `pointer out of bounds` at the
//!   `^`. Each dereference is checked before the statement's other
//!   operations.

use stc_diagnostics::Span;
use stc_sema::{BoundArgKind, PtrInfo, TypeId, TypeKind};
use stc_syntax::ast::{ExprId, ExprKind as AK};
use stc_syntax::token::ElemType;
use stc_values::{BinOp, Intrinsic, UnOp, Value};

use super::Lowerer;
use crate::{Expr, ExprKind, FaultKind, Place, Proj, Root, Stmt, StmtKind, Storage, SwitchArm};

/// Which helper function (see [`Lowerer::ptr_helper`]).
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
pub(super) enum Helper {
    Ref,
    Get,
    Set,
}

impl Helper {
    pub(super) fn word(self) -> &'static str {
        match self {
            Helper::Ref => "REF",
            Helper::Get => "GET",
            Helper::Set => "SET",
        }
    }
}

/// The helper functions the lowered POUs call, by kind and element type:
/// each becomes one FUNCTION after the analysis's POUs.
#[derive(Default)]
pub(super) struct Helpers {
    list: Vec<(Helper, TypeId)>,
}

impl Helpers {
    pub(super) fn list(&self) -> &[(Helper, TypeId)] {
        &self.list
    }

    /// The PouId of a helper (`first`: the number of the analysis's POUs).
    fn get(&mut self, h: Helper, v: TypeId, first: usize) -> crate::PouId {
        let i = match self.list.iter().position(|x| *x == (h, v)) {
            Some(i) => i,
            None => {
                self.list.push((h, v));
                self.list.len() - 1
            }
        };
        crate::PouId((first + i) as u32)
    }
}

const OBJECT: u32 = 0;
const BASE: u32 = 1;
const OFFSET: u32 = 2;

impl<'a> Lowerer<'a> {
    fn ptrs(&self) -> &'a PtrInfo {
        self.a
            .ptrs
            .as_ref()
            .expect("pointer lowering only runs in a program with pointer types")
    }

    /// Whether values of type `t` are pointers.
    pub(super) fn is_ptr(&self, t: TypeId) -> bool {
        self.a.ptrs.as_ref().is_some_and(|p| p.ptr == t)
    }

    /// A standard function of the lowering's own (no operator forms).
    fn std_fn(&self, f: Intrinsic, mut args: Vec<Expr>, ty: TypeId) -> Expr {
        match f {
            Intrinsic::Convert { .. } if args.len() == 1 => Expr {
                kind: ExprKind::Convert(Box::new(args.remove(0))),
                ty,
            },
            _ => Expr {
                kind: ExprKind::Intrinsic { func: f, args },
                ty,
            },
        }
    }

    fn konst(&self, ty: TypeId, v: i128) -> Expr {
        Expr {
            kind: ExprKind::Const(Value::Int(v)),
            ty,
        }
    }

    fn bin(&self, op: BinOp, l: Expr, r: Expr, ty: TypeId) -> Expr {
        Expr {
            kind: ExprKind::Binary(op, Box::new(l), Box::new(r)),
            ty,
        }
    }

    /// `x` as a DINT (byte offsets and indices are DINTs).
    fn to_dint(&self, x: Expr) -> Expr {
        let dint = self.ptrs().dint;
        if x.ty == dint {
            return x;
        }
        if let ExprKind::Const(Value::Int(v)) = x.kind {
            return self.konst(dint, v);
        }
        Expr {
            kind: ExprKind::Convert(Box::new(x)),
            ty: dint,
        }
    }

    /// A new temporary of type `ty` (in the frame of the running call).
    fn ptr_temp(&mut self, role: &'static str, ty: TypeId) -> crate::VarId {
        let name = self.a.pou(self.pou).name;
        let span = self.a.pou(self.pou).span;
        self.hidden(name, role, ty, Storage::Frame, span)
    }

    fn field(&self, v: crate::VarId, f: u32) -> Place {
        let info = self.ptrs();
        let ty = match self.a.types.kind(info.ptr) {
            TypeKind::Struct { fields } => fields[f as usize].ty,
            _ => info.dint,
        };
        Place {
            root: Root::Var(v),
            proj: vec![Proj::Field(f)],
            ty,
        }
    }

    fn load(&self, p: Place) -> Expr {
        let ty = p.ty;
        Expr {
            kind: ExprKind::Load(p),
            ty,
        }
    }

    fn assign(&self, at: (u32, u32), place: Place, value: Expr) -> Stmt {
        Stmt {
            kind: StmtKind::Assign { place, value },
            line: at.0,
            col: at.1,
        }
    }

    fn fault(&self, at: (u32, u32), k: FaultKind) -> Stmt {
        Stmt {
            kind: StmtKind::Fault(k),
            line: at.0,
            col: at.1,
        }
    }

    /// A pointer value in a temporary (its own, unless it is one already).
    fn ptr_in_temp(&mut self, x: Expr, at: (u32, u32)) -> crate::VarId {
        if let ExprKind::Load(Place {
            root: Root::Var(v),
            proj,
            ..
        }) = &x.kind
        {
            if proj.is_empty()
                && self
                    .vars
                    .get(v.0 as usize)
                    .is_some_and(|v| v.hidden.is_some())
            {
                return *v;
            }
        }
        let t = self.ptr_temp("pointer", self.ptrs().ptr);
        let s = self.assign(at, self.var_place(t, x.ty), x);
        self.pending.push(s);
        t
    }

    /// `ADR(x)`.
    pub(super) fn adr(&mut self, e: ExprId, x: ExprId) -> Expr {
        let info = self.ptrs();
        let at = self.line_col(self.ast.expr(e).span);
        // The object and the byte offset of `x` in it.
        let mut obj = x;
        let mut levels = Vec::new();
        loop {
            match &self.ast.expr(obj).kind {
                AK::Paren(b) => obj = *b,
                AK::Index { base, indices } => {
                    levels.push((*base, indices.clone()));
                    obj = *base;
                }
                _ => break,
            }
        }
        let obj_ty = self.a.expr_type(obj);
        let kind = info
            .kinds
            .iter()
            .position(|k| k.obj == obj_ty)
            .map_or(0, |i| i + 1);
        let dint = info.dint;
        let mut off = self.konst(dint, 0);
        for (base, indices) in levels.iter().rev() {
            let bt = self.a.expr_type(*base);
            let TypeKind::Array { dims, elem } = self.a.types.kind(bt) else {
                continue;
            };
            let esize = self.a.types.byte_size(*elem).unwrap_or(1) as i128;
            let values = self.seq(indices);
            let mut stride: i128 = 1;
            for ((lo, hi), v) in dims.iter().zip(values).rev() {
                let i = self.to_dint(v);
                let rel = self.bin(BinOp::Sub, i, self.konst(dint, *lo), dint);
                let term = self.bin(BinOp::Mul, rel, self.konst(dint, stride * esize), dint);
                off = self.bin(BinOp::Add, off, term, dint);
                stride *= hi - lo + 1;
            }
        }
        let obj_place = self.place(obj);
        let t = self.ptr_temp("adr", info.ptr);
        let base_ty = self.field(t, BASE).ty;
        let base = Expr {
            kind: ExprKind::Convert(Box::new(Expr {
                kind: ExprKind::Ref(obj_place),
                ty: info
                    .kinds
                    .get(kind.wrapping_sub(1))
                    .map_or(base_ty, |k| k.obj_ref),
            })),
            ty: base_ty,
        };
        let stmts = [
            self.assign(
                at,
                self.field(t, OBJECT),
                self.konst(info.udint, kind as i128),
            ),
            self.assign(at, self.field(t, BASE), base),
            self.assign(at, self.field(t, OFFSET), off),
        ];
        self.pending.extend(stmts);
        self.load(self.var_place(t, info.ptr))
    }

    /// The null pointer (a temporary left at its initial value).
    pub(super) fn null_ptr(&mut self) -> Expr {
        let info = self.ptrs();
        let t = self.ptr_temp("null", info.ptr);
        let at = (0, 0);
        let s = self.assign(at, self.field(t, OBJECT), self.konst(info.udint, 0));
        self.pending.push(s);
        self.load(self.var_place(t, info.ptr))
    }

    /// `l op r` with a pointer operand (`e` its node).
    pub(super) fn ptr_binary(
        &mut self,
        e: ExprId,
        op: stc_syntax::ast::BinaryOp,
        l: ExprId,
        r: ExprId,
    ) -> Expr {
        use stc_syntax::ast::BinaryOp as B;
        let info = self.ptrs();
        let (dint, bool_ty) = (info.dint, self.bool_ty());
        let at = self.op_position(e);
        let lp = self.is_ptr(self.a.expr_type(l));
        let rp = self.is_ptr(self.a.expr_type(r));
        if lp && rp {
            let a = self.expr(l);
            let ta = self.ptr_in_temp(a, at);
            let b = self.expr(r);
            let tb = self.ptr_in_temp(b, at);
            let same_obj = |s: &Self| {
                let k = s.bin(
                    BinOp::Eq,
                    s.load(s.field(ta, OBJECT)),
                    s.load(s.field(tb, OBJECT)),
                    bool_ty,
                );
                let base = s.bin(
                    BinOp::Eq,
                    s.load(s.field(ta, BASE)),
                    s.load(s.field(tb, BASE)),
                    bool_ty,
                );
                s.bin(BinOp::And, k, base, bool_ty)
            };
            let (oa, ob) = (
                self.load(self.field(ta, OFFSET)),
                self.load(self.field(tb, OFFSET)),
            );
            if matches!(op, B::Eq | B::Ne) {
                let eq = self.bin(
                    BinOp::And,
                    same_obj(self),
                    self.bin(BinOp::Eq, oa, ob, bool_ty),
                    bool_ty,
                );
                return if op == B::Eq {
                    eq
                } else {
                    Expr {
                        kind: ExprKind::Unary(UnOp::Not, Box::new(eq)),
                        ty: bool_ty,
                    }
                };
            }
            // Order and distance: only within one object.
            let check = Stmt {
                kind: StmtKind::If {
                    cond: same_obj(self),
                    then_body: Vec::new(),
                    else_body: vec![self.fault(at, FaultKind::PointerBounds)],
                },
                line: at.0,
                col: at.1,
            };
            self.pending.push(check);
            let bop = match op {
                B::Sub => return self.bin(BinOp::Sub, oa, ob, dint),
                B::Lt => BinOp::Lt,
                B::Le => BinOp::Le,
                B::Gt => BinOp::Gt,
                _ => BinOp::Ge,
            };
            return self.bin(bop, oa, ob, bool_ty);
        }
        let (p, n) = if lp { (l, r) } else { (r, l) };
        if self.a.null_ptrs.contains(&n) {
            // `p = 0`, `p <> 0`.
            let x = self.expr(p);
            let t = self.ptr_in_temp(x, at);
            let op2 = if op == B::Eq { BinOp::Eq } else { BinOp::Ne };
            return self.bin(
                op2,
                self.load(self.field(t, OBJECT)),
                self.konst(info.udint, 0),
                bool_ty,
            );
        }
        // `p + n`, `n + p`, `p - n`: a copy moved by n bytes.
        let (x, k) = if lp {
            let x = self.expr(p);
            let t = self.ptr_in_temp(x, at);
            (t, self.expr(n))
        } else {
            let k = self.expr(n);
            let mut done = [k];
            let x = self.expr(p);
            let mark = self.pending.len();
            let t = self.ptr_in_temp(x, at);
            if self.pending.len() > mark {
                self.spill(&mut done, mark);
            }
            let [k] = done;
            (t, k)
        };
        let t = self.ptr_temp("pointer", info.ptr);
        let copy = self.assign(
            at,
            self.var_place(t, info.ptr),
            self.load(self.var_place(x, info.ptr)),
        );
        let k = self.to_dint(k);
        let off = self.bin(
            if op == B::Sub { BinOp::Sub } else { BinOp::Add },
            self.load(self.field(t, OFFSET)),
            k,
            dint,
        );
        let moved = self.assign(at, self.field(t, OFFSET), off);
        self.pending.extend([copy, moved]);
        self.load(self.var_place(t, info.ptr))
    }

    /// Whether `e` (a `p^` or `p^[i..]` node) dereferences a pointer: the
    /// pointer expression and the indices.
    pub(super) fn ptr_deref_parts(&self, e: ExprId) -> Option<(ExprId, Option<Vec<ExprId>>)> {
        self.a.ptrs.as_ref()?;
        match &self.ast.expr(e).kind {
            AK::Deref(p) if self.is_ptr(self.a.expr_type(*p)) => Some((*p, None)),
            AK::Index { base, indices } => {
                let mut b = *base;
                while let AK::Paren(i) = &self.ast.expr(b).kind {
                    b = *i;
                }
                match &self.ast.expr(b).kind {
                    AK::Deref(p) if self.is_ptr(self.a.expr_type(*p)) => {
                        let dims = match self.a.types.kind(self.a.expr_type(b)) {
                            TypeKind::Array { dims, .. } => dims.len(),
                            _ => 0,
                        };
                        // (Only every dimension at once.)
                        (dims == indices.len()).then(|| (*p, Some(indices.to_vec())))
                    }
                    _ => None,
                }
            }
            _ => None,
        }
    }

    /// The place of `p^` or `p^[i..]` (node `e`, of type `ty`): the call
    /// of the helper that checks the pointer and gives the reference to
    /// the element, faulting here on its status; for a byte that may be a
    /// STRING's, the helper's value in a temporary (written back through
    /// the SET helper after the statement when it is written).
    pub(super) fn ptr_deref(
        &mut self,
        e: ExprId,
        p: ExprId,
        indices: Option<Vec<ExprId>>,
        ty: TypeId,
    ) -> Place {
        let write = std::mem::replace(&mut self.writing, false);
        let info = self.ptrs();
        let dint = info.dint;
        let span = self.ast.expr(e).span;
        // The fault names the `^` (of `p^`, or of `p^[i]`'s base).
        let hat = match &self.ast.expr(e).kind {
            AK::Index { base, .. } => self.ast.expr(*base).span.hi,
            _ => span.hi,
        };
        let at = self.line_col(Span::new(hat.saturating_sub(1), hat));
        let x = self.expr(p);
        let mut t = self.ptr_in_temp(x, at);
        if let Some(indices) = indices {
            // `p^[i, j]`: `p` moved by the element's offset in the array.
            let target = self.a.expr_type(match &self.ast.expr(e).kind {
                AK::Index { base, .. } => *base,
                _ => e,
            });
            let dims = match self.a.types.kind(target) {
                TypeKind::Array { dims, .. } => dims.clone(),
                _ => Vec::new(),
            };
            let esize = self.a.types.byte_size(ty).unwrap_or(1) as i128;
            let values = self.seq(&indices);
            let mut off = self.konst(dint, 0);
            let mut stride: i128 = 1;
            for ((lo, hi), i) in dims.iter().zip(values).rev() {
                let i = self.to_dint(i);
                let rel = self.bin(BinOp::Sub, i, self.konst(dint, *lo), dint);
                let term = self.bin(BinOp::Mul, rel, self.konst(dint, stride * esize), dint);
                off = self.bin(BinOp::Add, off, term, dint);
                stride *= hi - lo + 1;
            }
            let moved = self.ptr_temp("pointer", info.ptr);
            let copy = self.assign(
                at,
                self.var_place(moved, info.ptr),
                self.load(self.var_place(t, info.ptr)),
            );
            let sum = self.bin(BinOp::Add, self.load(self.field(moved, OFFSET)), off, dint);
            let set = self.assign(at, self.field(moved, OFFSET), sum);
            self.pending.extend([copy, set]);
            t = moved;
        }
        let elem = self.a.types.ptr_elem(ty);
        let strings =
            stc_sema::byte_like(&self.a.types, elem) && info.kinds.iter().any(|k| k.string);
        let status = self.ptr_temp("status", dint);
        let ptr = self.load(self.var_place(t, info.ptr));
        if strings {
            let get = self.helpers.get(Helper::Get, elem, self.a.pous.len());
            let val = self.ptr_temp("byte", elem);
            let call = self.helper_call(get, vec![ptr], status, elem);
            let s = self.assign(at, self.var_place(val, elem), call);
            self.pending.push(s);
            let check = self.status_check(status, at);
            self.pending.push(check);
            if write {
                // The byte written, after the statement.
                let set = self.helpers.get(Helper::Set, elem, self.a.pous.len());
                let args = vec![
                    self.load(self.var_place(t, info.ptr)),
                    self.load(self.var_place(val, elem)),
                ];
                let call = self.helper_call(set, args, status, TypeId::VOID);
                let s = Stmt {
                    kind: StmtKind::Eval(call),
                    line: at.0,
                    col: at.1,
                };
                let check = self.status_check(status, at);
                self.post.extend([s, check]);
            }
            return self.var_place(val, elem);
        }
        let Some(&rt) = info.elem_refs.get(&elem) else {
            // (No pointer type sees this element: nothing points here.)
            let v = self.ptr_temp("byte", ty);
            return self.var_place(v, ty);
        };
        let get = self.helpers.get(Helper::Ref, elem, self.a.pous.len());
        let r = self.ptr_temp("element", rt);
        let call = self.helper_call(get, vec![ptr], status, rt);
        let s = self.assign(at, self.var_place(r, rt), call);
        self.pending.push(s);
        let check = self.status_check(status, at);
        self.pending.push(check);
        Place {
            root: Root::Deref(Box::new(self.load(self.var_place(r, rt)))),
            proj: vec![],
            ty,
        }
    }

    /// A call of helper `f` with its inputs in order, its status output
    /// into `status`.
    fn helper_call(
        &self,
        f: crate::PouId,
        args: Vec<Expr>,
        status: crate::VarId,
        ty: TypeId,
    ) -> Expr {
        let dint = self.ptrs().dint;
        // (The helper's variables: its result (when it has one), the
        // inputs, then the status.)
        let first = u32::from(ty != TypeId::VOID);
        let n = args.len() as u32;
        Expr {
            kind: ExprKind::CallFn {
                func: f,
                inputs: args
                    .into_iter()
                    .enumerate()
                    .map(|(i, a)| (crate::VarId(first + i as u32), a))
                    .collect(),
                inouts: Vec::new(),
                outputs: vec![crate::Output {
                    var: crate::VarId(first + n),
                    target: self.var_place(status, dint),
                    negated: false,
                }],
            },
            ty,
        }
    }

    /// The fault a helper's status stands for, raised at `at`.
    fn status_check(&self, status: crate::VarId, at: (u32, u32)) -> Stmt {
        let dint = self.ptrs().dint;
        Stmt {
            kind: StmtKind::Switch {
                selector: self.load(self.var_place(status, dint)),
                arms: vec![
                    SwitchArm {
                        ranges: vec![(1, 1)],
                        body: vec![self.fault(at, FaultKind::NullReference)],
                    },
                    SwitchArm {
                        ranges: vec![(2, 2)],
                        body: vec![self.fault(at, FaultKind::PointerBounds)],
                    },
                ],
                default: Vec::new(),
            },
            line: at.0,
            col: at.1,
        }
    }

    /// The body of a pointer helper function for element type `v`:
    /// `Ref` returns the reference to the element `p` points at, `Get`
    /// its value (a STRING's byte too), `Set` writes `value` there; each
    /// sets `status` to 0, 1 (NULL) or 2 (out of bounds) and never
    /// faults itself (the caller faults, at the dereference).
    pub(super) fn ptr_helper(
        &mut self,
        h: Helper,
        v: TypeId,
        name: stc_syntax::Symbol,
    ) -> crate::Pou {
        use stc_sema::Section;
        let info = self.ptrs();
        let dint = info.dint;
        let bool_ty = self.bool_ty();
        let rt = info.elem_refs.get(&v).copied().unwrap_or(TypeId::ERROR);
        let var = |l: &mut Self, role: &'static str, ty: TypeId, section: Section| {
            let id = crate::VarId(l.vars.len() as u32);
            l.vars.push(crate::Var {
                name,
                ty,
                section,
                storage: Storage::Frame,
                init: None,
                constant: false,
                retain: false,
                location: None,
                hidden: Some(role),
                span: Span::default(),
            });
            id
        };
        let result = match h {
            Helper::Ref => Some(var(self, "result", rt, Section::Result)),
            Helper::Get => Some(var(self, "result", v, Section::Result)),
            Helper::Set => None,
        };
        let t = var(self, "pointer", info.ptr, Section::Input);
        let value = (h == Helper::Set).then(|| var(self, "value", v, Section::Input));
        let status = var(self, "status", dint, Section::Output);
        let at = (0, 0);
        let set_status =
            |l: &Self, n: i128| l.assign(at, l.var_place(status, dint), l.konst(dint, n));
        let off = |l: &Self| l.load(l.field(t, OFFSET));
        let if_ = |cond: Expr, then_body: Vec<Stmt>, else_body: Vec<Stmt>| Stmt {
            kind: StmtKind::If {
                cond,
                then_body,
                else_body,
            },
            line: 0,
            col: 0,
        };
        let mut arms = Vec::new();
        for (i, k) in info.kinds.iter().enumerate() {
            let obj = Expr {
                kind: ExprKind::Convert(Box::new(self.load(self.field(t, BASE)))),
                ty: k.obj_ref,
            };
            let obj_place = Place {
                root: Root::Deref(Box::new(obj)),
                proj: vec![],
                ty: k.obj,
            };
            let same = k.elem == v
                || self.a.types.compat(k.elem, v, false) == stc_sema::Compat::Same
                    && self.a.types.compat(v, k.elem, false) == stc_sema::Compat::Same
                    && self.a.types.scalar(k.elem) == self.a.types.scalar(v);
            let body = if same {
                // Whole elements inside the object.
                let size = k.elem_size as i128;
                let inside = self.bin(
                    BinOp::And,
                    self.bin(
                        BinOp::And,
                        self.bin(BinOp::Ge, off(self), self.konst(dint, 0), bool_ty),
                        self.bin(
                            BinOp::Lt,
                            off(self),
                            self.konst(dint, k.count as i128 * size),
                            bool_ty,
                        ),
                        bool_ty,
                    ),
                    self.bin(
                        BinOp::Eq,
                        self.bin(BinOp::Mod, off(self), self.konst(dint, size), dint),
                        self.konst(dint, 0),
                        bool_ty,
                    ),
                    bool_ty,
                );
                let index = self.bin(BinOp::Div, off(self), self.konst(dint, size), dint);
                let elem_place = self.element_of(obj_place, k.obj, index);
                let action = match h {
                    Helper::Ref => self.assign(
                        at,
                        self.var_place(result.unwrap_or(status), rt),
                        Expr {
                            kind: ExprKind::Ref(elem_place),
                            ty: rt,
                        },
                    ),
                    Helper::Get => self.assign(
                        at,
                        self.var_place(result.unwrap_or(status), v),
                        self.load(elem_place),
                    ),
                    Helper::Set => self.assign(
                        at,
                        elem_place,
                        self.load(self.var_place(value.unwrap_or(status), v)),
                    ),
                };
                vec![if_(inside, vec![action], vec![set_status(self, 2)])]
            } else if k.string && h != Helper::Ref && stc_sema::byte_like(&self.a.types, v) {
                self.string_byte(
                    h,
                    k,
                    obj_place,
                    t,
                    result.or(value).unwrap_or(status),
                    v,
                    status,
                )
            } else {
                continue;
            };
            arms.push(SwitchArm {
                ranges: vec![(i as i128 + 1, i as i128 + 1)],
                body,
            });
        }
        arms.push(SwitchArm {
            ranges: vec![(0, 0)],
            body: vec![set_status(self, 1)],
        });
        let body = vec![
            set_status(self, 0),
            Stmt {
                kind: StmtKind::Switch {
                    selector: self.load(self.field(t, OBJECT)),
                    arms,
                    default: vec![set_status(self, 2)],
                },
                line: 0,
                col: 0,
            },
        ];
        crate::Pou {
            kind: stc_syntax::ast::PouKind::Function,
            name,
            vars: std::mem::take(&mut self.vars),
            result,
            body,
            is_std: false,
            span: Span::default(),
            name_span: Span::default(),
            file: String::new(),
        }
    }

    /// A STRING's byte at the pointer's offset: read into `val` (Get), or
    /// `val` written (Set: a NUL inside the string ends it there, another
    /// byte inside replaces its character, at its end appends one while
    /// there is room, after its end is status 2).
    #[allow(clippy::too_many_arguments)]
    fn string_byte(
        &self,
        h: Helper,
        k: &stc_sema::PtrKind,
        obj_place: Place,
        t: crate::VarId,
        val: crate::VarId,
        elem: TypeId,
        status: crate::VarId,
    ) -> Vec<Stmt> {
        let info = self.ptrs();
        let dint = info.dint;
        let bool_ty = self.bool_ty();
        let at = (0, 0);
        let off = || self.load(self.field(t, OFFSET));
        let s = || self.load(obj_place.clone());
        let len = || self.std_fn(Intrinsic::Len, vec![s()], dint);
        let b = || self.load(self.var_place(val, elem));
        let if_ = |cond: Expr, then_body: Vec<Stmt>, else_body: Vec<Stmt>| Stmt {
            kind: StmtKind::If {
                cond,
                then_body,
                else_body,
            },
            line: 0,
            col: 0,
        };
        let bounds = self.a.types.byte_size(k.obj).unwrap_or(1) as i128;
        let fail = self.assign(at, self.var_place(status, dint), self.konst(dint, 2));
        let inside = self.bin(
            BinOp::And,
            self.bin(BinOp::Ge, off(), self.konst(dint, 0), bool_ty),
            self.bin(BinOp::Lt, off(), self.konst(dint, bounds), bool_ty),
            bool_ty,
        );
        let char_scalar = self.a.types.scalar(elem) == Some(ElemType::Char);
        let work = if h == Helper::Get {
            // Its characters, then 0 for every byte after its end.
            let pos = self.bin(BinOp::Add, off(), self.konst(dint, 1), dint);
            let one = self.std_fn(Intrinsic::Mid, vec![s(), self.konst(dint, 1), pos], k.obj);
            let ch = self.std_fn(
                Intrinsic::Convert {
                    from: ElemType::String,
                    to: ElemType::Char,
                },
                vec![one],
                info.char_ty,
            );
            let byte = if char_scalar {
                ch
            } else {
                let to = self.a.types.scalar(elem).unwrap_or(ElemType::Byte);
                self.std_fn(
                    Intrinsic::Convert {
                        from: ElemType::Char,
                        to,
                    },
                    vec![ch],
                    elem,
                )
            };
            vec![if_(
                self.bin(BinOp::Lt, off(), len(), bool_ty),
                vec![self.assign(at, self.var_place(val, elem), byte)],
                vec![self.assign(at, self.var_place(val, elem), self.konst(elem, 0))],
            )]
        } else {
            let code = if char_scalar {
                b()
            } else {
                let from = self.a.types.scalar(elem).unwrap_or(ElemType::Byte);
                self.std_fn(
                    Intrinsic::Convert {
                        from,
                        to: ElemType::Char,
                    },
                    vec![b()],
                    info.char_ty,
                )
            };
            let one = self.std_fn(
                Intrinsic::Convert {
                    from: ElemType::Char,
                    to: ElemType::String,
                },
                vec![code],
                info.string,
            );
            let zero = self.bin(BinOp::Eq, b(), self.konst(elem, 0), bool_ty);
            let cut = self.std_fn(Intrinsic::Left, vec![s(), off()], k.obj);
            let pos = self.bin(BinOp::Add, off(), self.konst(dint, 1), dint);
            let replaced = self.std_fn(
                Intrinsic::Replace,
                vec![s(), one.clone(), self.konst(dint, 1), pos],
                k.obj,
            );
            let appended = self.std_fn(Intrinsic::Concat, vec![s(), one], k.obj);
            let st = |x: Expr| self.assign(at, obj_place.clone(), x);
            let at_end = self.bin(
                BinOp::And,
                self.bin(BinOp::Eq, off(), len(), bool_ty),
                self.bin(BinOp::Lt, off(), self.konst(dint, bounds - 1), bool_ty),
                bool_ty,
            );
            vec![if_(
                zero,
                vec![if_(
                    self.bin(BinOp::Lt, off(), len(), bool_ty),
                    vec![st(cut)],
                    vec![],
                )],
                vec![if_(
                    self.bin(BinOp::Lt, off(), len(), bool_ty),
                    vec![st(replaced)],
                    vec![if_(at_end, vec![st(appended)], vec![fail.clone()])],
                )],
            )]
        };
        vec![if_(inside, work, vec![fail])]
    }

    /// The element `index` (0-based, row-major over every dimension) of
    /// the object at `obj` of type `obj_ty` (itself when not an array).
    fn element_of(&self, obj: Place, obj_ty: TypeId, index: Expr) -> Place {
        let dint = self.ptrs().dint;
        let mut place = obj;
        let mut t = obj_ty;
        let mut rest = index;
        // Nested arrays: each level's dimensions, outermost first.
        let mut levels = Vec::new();
        while let TypeKind::Array { dims, elem } = self.a.types.kind(t) {
            levels.push((dims.clone(), *elem));
            t = *elem;
        }
        // Elements below each dimension.
        let mut sizes = Vec::new();
        let mut below: i128 = 1;
        for (dims, _) in levels.iter().rev() {
            let mut ds = Vec::new();
            for (lo, hi) in dims.iter().rev() {
                ds.push(below);
                below *= hi - lo + 1;
            }
            ds.reverse();
            sizes.push(ds);
        }
        sizes.reverse();
        for ((dims, elem), ds) in levels.into_iter().zip(sizes) {
            let mut idx = Vec::new();
            for ((lo, hi), per) in dims.iter().zip(ds) {
                let q = self.bin(BinOp::Div, rest.clone(), self.konst(dint, per), dint);
                rest = self.bin(BinOp::Mod, rest, self.konst(dint, per), dint);
                let i = self.bin(BinOp::Add, q, self.konst(dint, *lo), dint);
                idx.push((i, *lo, *hi));
            }
            place.proj.push(Proj::Index(idx));
            place.ty = elem;
        }
        place
    }

    /// `ADR`'s argument, when `e` is an `ADR` call.
    pub(super) fn adr_arg(&self, info: &stc_sema::CallInfo) -> Option<ExprId> {
        match info.args.first().map(|a| &a.kind) {
            Some(BoundArgKind::Input(x)) => Some(*x),
            _ => None,
        }
    }
}
