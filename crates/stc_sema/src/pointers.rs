//! CODESYS pointers: `POINTER TO T`, `ADR(x)`, `SIZEOF(x)`, `p^`, pointer
//! arithmetic and comparison (docs/oop.md, "Pointers").
//!
//! A pointer is checked, never a bare address: it points into one *object*
//! (the variable `ADR` was given, an array as a whole when `ADR` was given
//! one of its elements) and knows the object's element type, its number of
//! elements and a byte offset. What the analyser decides here:
//!
//! - which *views* are allowed: a `POINTER TO T` (or `TO ARRAY[..] OF T`)
//!   may point at objects whose element type is `T`, and a pointer to a
//!   1-byte type (BYTE, USINT, SINT, CHAR) also at a STRING's bytes (E1402);
//! - which pointer values may be stored where, so that no pointer outlives
//!   its object (E1404): a pointer into a function's variables (a
//!   *short-lived* pointer) may only be kept in that function's own
//!   variables and passed to calls;
//! - the object element types `ADR` makes, in order (`Analysis::ptr_kinds`):
//!   the lowering tags each pointer with the index of its object's kind.

use stc_diagnostics::{Code, Diagnostic, Span};
use stc_syntax::ast::{Arg, BinaryOp, ExprId, ExprKind, PouKind};
use stc_syntax::token::ElemType;

use crate::analyzer::{Scope, Sema};
use crate::{BoundArg, BoundArgKind, CallInfo, CallTarget, Res, Section, TypeId, TypeKind};
use rustc_hash::FxHashMap;
use stc_values::Value;

/// The 1-byte types through which a STRING's bytes are seen (a STRING's
/// characters are bytes; SINT is not, its values stop at 127).
pub fn byte_like(types: &crate::TypeTable, t: TypeId) -> bool {
    matches!(
        types.kind(t),
        TypeKind::Elem(ElemType::Byte | ElemType::Usint | ElemType::Char)
    )
}

impl Sema<'_> {
    /// `ADR(x)`: a pointer to the variable `x`, of the type `Ptr(VOID)`
    /// that every pointer type takes when its view of `x` is allowed.
    pub(crate) fn adr_call(&mut self, e: ExprId, args: &[Arg], span: Span, scope: Scope) -> TypeId {
        let Some(x) = self.one_argument(
            args,
            scope,
            (Code::E1401, span),
            "ADR takes one argument: the variable it points at",
            "`ADR(x)`",
        ) else {
            return TypeId::ERROR;
        };
        let t = self.check_expr(x, None, scope);
        if t == TypeId::ERROR {
            return TypeId::ERROR;
        }
        let Some(short) = self.addressable(x, "ADR", Code::E1401, scope) else {
            return TypeId::ERROR;
        };
        // The object: `a[i]` points into the whole array `a`.
        let mut obj = x;
        while let ExprKind::Index { base, .. } | ExprKind::Paren(base) = &self.ast.expr(obj).kind {
            obj = *base;
        }
        let obj_ty = self.expr_type_of(obj);
        let elem = self.types.ptr_elem(obj_ty);
        let viewable = match self.types.kind(elem) {
            TypeKind::Ref(_) | TypeKind::Program(_) | TypeKind::Error | TypeKind::Void => false,
            TypeKind::Fb(p) => !self.types.is_interface(*p),
            _ => true,
        };
        if !viewable {
            let shown = self.tname(elem);
            self.emit(
                Diagnostic::new(
                    Code::E1401,
                    self.ast.expr(x).span,
                    format!("ADR of a value of type {shown}: a pointer cannot point at it"),
                )
                .with_help("take the address of a variable of an elementary, string, array, structure or function block type"),
            );
            return TypeId::ERROR;
        }
        if !self.ptr_kinds.contains(&obj_ty) {
            self.ptr_kinds.push(obj_ty);
        }
        if short {
            self.short_adrs.insert(e);
        }
        self.calls.insert(
            e,
            CallInfo {
                target: CallTarget::Adr,
                args: vec![BoundArg {
                    param: 0,
                    kind: BoundArgKind::Input(x),
                }],
                en: None,
                eno: None,
            },
        );
        self.types.ptr_to(TypeId::VOID)
    }

    /// Whether `x` is a variable whose address can be taken, and if so
    /// whether it lives only during a call (`Some(true)`); reported (with
    /// `what` and `code`) and `None` when it is not a variable.
    fn addressable(&mut self, x: ExprId, what: &str, code: Code, scope: Scope) -> Option<bool> {
        let span = self.ast.expr(x).span;
        let not_var = |s: &mut Self, why: &str| {
            s.emit(
                Diagnostic::new(code, span, format!("{what} needs a variable, not {why}"))
                    .with_label("has no address"),
            );
            None
        };
        let mut root = x;
        let mut through_instance = false;
        loop {
            match &self.ast.expr(root).kind {
                ExprKind::Paren(b) | ExprKind::Index { base: b, .. } => root = *b,
                ExprKind::Member { base, .. } => {
                    if matches!(self.resolutions.get(&root), Some(Res::FbMember(..))) {
                        through_instance = true;
                    }
                    root = *base;
                }
                ExprKind::Deref(p) => {
                    // What a reference refers to lives long enough; what a
                    // pointer points at lives as long as the pointer may.
                    let pt = self.expr_type_of(*p);
                    return Some(
                        matches!(self.types.kind(pt), TypeKind::Ptr(_)) && self.ptr_short(*p),
                    );
                }
                ExprKind::PartialAccess { .. } => return not_var(self, "a part of a bit string"),
                ExprKind::Name(_) => break,
                ExprKind::Address(_) => return not_var(self, "a direct address"),
                _ => return not_var(self, "the value of an expression"),
            }
        }
        let _ = through_instance;
        match self.resolutions.get(&root).copied() {
            Some(Res::Var(v)) => {
                let Scope::Pou(p) = scope else {
                    return not_var(self, "this");
                };
                let var = self.pous[p.0 as usize].var(v).clone();
                if var.constant {
                    let shown = self.sym_name(var.name);
                    self.emit(
                        Diagnostic::new(
                            code,
                            span,
                            format!("{what} of the constant `{shown}`: it could be changed through the pointer"),
                        )
                        .with_secondary(var.span, "declared CONSTANT here"),
                    );
                    return None;
                }
                Some(self.frame_var(p, v))
            }
            Some(Res::FbMember(..)) | Some(Res::This) => Some(false),
            Some(Res::Global(g)) => {
                let gv = self.globals[g.0 as usize].var.clone();
                if gv.constant {
                    let shown = self.sym_name(gv.name);
                    self.emit(
                        Diagnostic::new(
                            code,
                            span,
                            format!("{what} of the constant `{shown}`: it could be changed through the pointer"),
                        )
                        .with_secondary(gv.span, "declared CONSTANT here"),
                    );
                    return None;
                }
                Some(false)
            }
            Some(Res::EnumValue(..)) => not_var(self, "an enumeration value"),
            _ => not_var(self, "this"),
        }
    }

    /// Whether variable `v` of POU `p` lives only during a call of `p`: a
    /// variable of a FUNCTION or METHOD, a VAR_TEMP, or a VAR_IN_OUT (which
    /// may stand for such a variable of the caller).
    fn frame_var(&self, p: crate::PouId, v: crate::VarId) -> bool {
        let pou = &self.pous[p.0 as usize];
        let var = pou.var(v);
        pou.kind == PouKind::Function || matches!(var.section, Section::Temp | Section::InOut)
    }

    /// `SIZEOF(x)`: the size of `x` (a variable or a type name) in the
    /// byte view of pointers, a constant of an integer type taken from the
    /// context (UDINT without one).
    pub(crate) fn sizeof_call(
        &mut self,
        e: ExprId,
        args: &[Arg],
        expected: Option<TypeId>,
        span: Span,
        scope: Scope,
    ) -> TypeId {
        let Some(x) = self.one_argument(
            args,
            scope,
            (Code::E1405, span),
            "SIZEOF takes one argument: a variable or a type",
            "`SIZEOF(x)`",
        ) else {
            return TypeId::ERROR;
        };
        let t = match &self.ast.expr(x).kind {
            ExprKind::Name(id) if self.type_named(*id, scope).is_some() => {
                self.type_named(*id, scope).unwrap_or(TypeId::ERROR)
            }
            _ => self.check_expr(x, None, scope),
        };
        if t == TypeId::ERROR {
            return TypeId::ERROR;
        }
        let Some(n) = self.types.byte_size(t) else {
            let shown = self.tname(t);
            self.emit(
                Diagnostic::new(
                    Code::E1405,
                    self.ast.expr(x).span,
                    format!("SIZEOF of a value of type {shown}: it has no size in bytes"),
                )
                .with_help(
                    "SIZEOF measures elementary, string, array, structure and pointer values",
                ),
            );
            return TypeId::ERROR;
        };
        let ty = expected
            .filter(|t| self.types.is_integer(*t))
            .unwrap_or_else(|| self.types.elem(ElemType::Udint));
        let fits = self
            .types
            .numeric(ty)
            .and_then(stc_values::int_range)
            .is_some_and(|(lo, hi)| (lo..=hi).contains(&i128::from(n)));
        let ty = if fits {
            ty
        } else {
            self.types.elem(ElemType::Udint)
        };
        self.consts.insert(e, Value::Int(i128::from(n)));
        ty
    }

    /// `ADR` of an object whose element type `obj` is viewed through a
    /// pointer whose target is `to`: whether the view is allowed.
    pub(crate) fn ptr_view_ok(&self, whole: TypeId, to: TypeId) -> bool {
        let obj = self.types.ptr_elem(whole);
        let v = self.types.ptr_elem(to);
        if v == TypeId::ERROR || obj == TypeId::ERROR {
            return true;
        }
        let same = v == obj
            || self.types.compat(v, obj, false) == crate::Compat::Same
                && self.types.compat(obj, v, false) == crate::Compat::Same
                && self.types.scalar(v) == self.types.scalar(obj);
        same || (self.byte_like(v)
            && matches!(self.types.kind(whole), TypeKind::String { wide: false, .. }))
    }

    /// The 1-byte types through which a STRING's bytes are seen.
    pub(crate) fn byte_like(&self, t: TypeId) -> bool {
        byte_like(&self.types, t)
    }

    /// After the analysis: the types and names the lowering of pointers
    /// needs ([`crate::PtrInfo`]), and every pointer type replaced by the
    /// structure that represents it on every engine.
    pub(crate) fn finish_pointers(&mut self) -> Option<crate::PtrInfo> {
        let mut whole = std::mem::take(&mut self.whole_ptr_arrays);
        whole.sort_by_key(|s| (s.lo, s.hi));
        whole.dedup();
        for span in whole {
            self.emit(
                Diagnostic::new(
                    Code::E1403,
                    span,
                    "a pointer to an array is used through its elements, not as a whole array",
                )
                .with_label("index it with every dimension: `p^[i]`")
                .with_help("copy the elements one by one, or point at the element type"),
            );
        }
        let ptr_types: Vec<(TypeId, TypeId)> = (0..self.types.len())
            .map(|i| TypeId(i as u32))
            .filter_map(|t| self.types.ptr_target(t).map(|x| (t, x)))
            .collect();
        if ptr_types.is_empty() {
            return None;
        }
        let udint = self.types.elem(ElemType::Udint);
        let dint = self.types.elem(ElemType::Dint);
        let byte = self.types.elem(ElemType::Byte);
        let base_ref = self.types.ref_to(byte);
        let field = |s: &mut Self, name: &str, ty: TypeId| crate::types::Field {
            name: s.interner.intern(name),
            ty,
            init: None,
            span: Span::default(),
        };
        let fields = vec![
            field(self, "OBJECT", udint),
            field(self, "BASE", base_ref),
            field(self, "OFFSET", dint),
        ];
        let mut kinds = Vec::new();
        for &obj in &self.ptr_kinds.clone() {
            let elem = self.types.ptr_elem(obj);
            kinds.push(crate::PtrKind {
                obj,
                elem,
                count: self.types.elem_count(obj),
                elem_size: self.types.byte_size(elem).unwrap_or(1).max(1),
                obj_ref: self.types.ref_to(obj),
                elem_ref: self.types.ref_to(elem),
                string: matches!(self.types.kind(obj), TypeKind::String { wide: false, .. }),
            });
        }
        let mut elem_refs = FxHashMap::default();
        let mut targets = FxHashMap::default();
        for &(t, x) in &ptr_types {
            targets.insert(t, x);
            let v = self.types.ptr_elem(x);
            if v != TypeId::VOID && v != TypeId::ERROR {
                let r = self.types.ref_to(v);
                elem_refs.insert(v, r);
            }
        }
        // One structure type for every pointer type, so that pointers of
        // any target type are values of one type on every engine: the
        // first pointer type becomes it, and every use of another pointer
        // type (variables, members, elements, expressions) is renamed.
        let canon = ptr_types[0].0;
        for &(t, _) in &ptr_types {
            *self.types.kind_mut(t) = TypeKind::Struct {
                fields: fields.clone(),
            };
        }
        let map = |t: TypeId| if targets.contains_key(&t) { canon } else { t };
        for i in 0..self.types.len() {
            let t = TypeId(i as u32);
            match self.types.kind_mut(t) {
                TypeKind::Array { elem, .. } => *elem = map(*elem),
                TypeKind::Struct { fields } => {
                    for f in fields.iter_mut() {
                        f.ty = map(f.ty);
                    }
                }
                TypeKind::Ref(x) => *x = map(*x),
                _ => {}
            }
        }
        for pou in &mut self.pous {
            for v in &mut pou.vars {
                v.ty = map(v.ty);
            }
            pou.return_type = pou.return_type.map(map);
        }
        for g in &mut self.globals {
            g.var.ty = map(g.var.ty);
        }
        for t in &mut self.expr_types {
            *t = map(*t);
        }
        for t in self.coercions.values_mut() {
            *t = map(*t);
        }
        for c in self.calls.values_mut() {
            if let CallTarget::Std { arg_types, ret, .. } = &mut c.target {
                for t in arg_types.iter_mut() {
                    *t = map(*t);
                }
                *ret = map(*ret);
            }
        }
        Some(crate::PtrInfo {
            ptr: canon,
            targets,
            kinds,
            elem_refs,
            string: self.types.elem(ElemType::String),
            char_ty: self.types.elem(ElemType::Char),
            byte,
            dint,
            udint,
        })
    }

    /// The conversion of a pointer value (`ADR(x)`, another pointer, `0`,
    /// `NULL`) to the pointer type `to`, called by `coerce`: `Some(ok)`
    /// when `to` or `from` is a pointer type.
    pub(crate) fn coerce_ptr(
        &mut self,
        e: ExprId,
        from: TypeId,
        to: TypeId,
        what: &str,
    ) -> Option<bool> {
        let to_ptr = matches!(self.types.kind(to), TypeKind::Ptr(_));
        let from_ptr = matches!(self.types.kind(from), TypeKind::Ptr(_));
        if !to_ptr && !from_ptr {
            return None;
        }
        let span = self.ast.expr(e).span;
        if to_ptr && !from_ptr {
            // `0` and `NULL` are the null pointer.
            let null = matches!(self.types.kind(from), TypeKind::Ref(TypeId::VOID))
                || matches!(self.consts.get(&e), Some(Value::Int(0))) && self.is_literal(e);
            if null {
                self.null_ptrs.insert(e);
                return Some(true);
            }
        }
        if to_ptr && from_ptr {
            let target = self.types.ptr_target(to).unwrap_or(TypeId::ERROR);
            if self.types.ptr_target(from) == Some(TypeId::VOID) {
                // `ADR(x)`: is this view of x's object allowed?
                let mut a = e;
                loop {
                    match &self.ast.expr(a).kind {
                        ExprKind::Paren(b) => a = *b,
                        ExprKind::Binary { lhs, rhs, .. } => {
                            let lp = matches!(
                                self.types.kind(self.expr_type_of(*lhs)),
                                TypeKind::Ptr(_)
                            );
                            a = if lp { *lhs } else { *rhs };
                        }
                        _ => break,
                    }
                }
                let obj = self.adr_object(a);
                if self.ptr_view_ok(obj, target) {
                    return Some(true);
                }
                let (o, t) = (self.tname(obj), self.tname(to));
                self.emit(
                    Diagnostic::new(
                        Code::E1402,
                        span,
                        format!("{what} of type {t} cannot point at a value of type {o}"),
                    )
                    .with_label(format!("points at {o}"))
                    .with_help("a POINTER TO T points at variables of type T (or arrays of T); a pointer to BYTE, USINT, SINT or CHAR also at the bytes of a STRING"),
                );
                return Some(false);
            }
            if self.types.compat(from, to, false) == crate::Compat::Same {
                return Some(true);
            }
        }
        let (f, t) = (self.tname(from), self.tname(to));
        self.emit(
            Diagnostic::new(
                Code::E1402,
                span,
                format!("{what} of type {t} cannot take a value of type {f}"),
            )
            .with_label(format!("this is {f}"))
            .with_help("a pointer holds `ADR(x)` of a variable, another pointer to the same element type, or `0`; no number converts to a pointer or back"),
        );
        Some(false)
    }

    /// The type of the object of an `ADR` call (ERROR if `e` is not one).
    fn adr_object(&self, e: ExprId) -> TypeId {
        let Some(info) = self.calls.get(&e) else {
            return TypeId::ERROR;
        };
        if !matches!(info.target, CallTarget::Adr) {
            return TypeId::ERROR;
        }
        let Some(BoundArg {
            kind: BoundArgKind::Input(x),
            ..
        }) = info.args.first()
        else {
            return TypeId::ERROR;
        };
        let mut obj = *x;
        while let ExprKind::Index { base, .. } | ExprKind::Paren(base) = &self.ast.expr(obj).kind {
            obj = *base;
        }
        self.expr_type_of(obj)
    }

    fn is_literal(&self, e: ExprId) -> bool {
        let mut a = e;
        while let ExprKind::Paren(b) = &self.ast.expr(a).kind {
            a = *b;
        }
        matches!(self.ast.expr(a).kind, ExprKind::Literal(_))
    }

    /// `l op r` where one operand is a pointer: `p + n`, `n + p`, `p - n`
    /// (a pointer moved by `n` bytes), `p - q` (the distance in bytes, a
    /// DINT), and comparisons of two pointers or of a pointer with `0`.
    pub(crate) fn ptr_binary(
        &mut self,
        op: BinaryOp,
        (l, lt): (ExprId, TypeId),
        (r, rt): (ExprId, TypeId),
        span: Span,
    ) -> TypeId {
        let bool_ty = self.types.elem(ElemType::Bool);
        let lp = matches!(self.types.kind(lt), TypeKind::Ptr(_));
        let rp = matches!(self.types.kind(rt), TypeKind::Ptr(_));
        let cmp = matches!(
            op,
            BinaryOp::Eq | BinaryOp::Ne | BinaryOp::Lt | BinaryOp::Le | BinaryOp::Gt | BinaryOp::Ge
        );
        let void = |s: &Self, t: TypeId| s.types.ptr_target(t) == Some(TypeId::VOID);
        if lp && rp {
            if void(self, lt) || void(self, rt) {
                // (`ADR(x) = p`: compare `p` with a pointer variable.)
                self.emit(
                    Diagnostic::new(
                        Code::E1403,
                        span,
                        "`ADR(x)` has no pointer type of its own here",
                    )
                    .with_help("assign it to a POINTER TO variable first"),
                );
                return if cmp { bool_ty } else { TypeId::ERROR };
            }
            let same = self.types.compat(lt, rt, false) == crate::Compat::Same;
            if !same {
                let (a, b) = (self.tname(lt), self.tname(rt));
                self.emit(Diagnostic::new(
                    Code::E1403,
                    span,
                    format!("pointers of types {a} and {b} point at different types"),
                ));
                return if cmp { bool_ty } else { TypeId::ERROR };
            }
            if cmp {
                return bool_ty;
            }
            if op == BinaryOp::Sub {
                return self.types.elem(ElemType::Dint);
            }
        } else {
            let (p, pt, n, nt) = if lp { (l, lt, r, rt) } else { (r, rt, l, lt) };
            let moves = op == BinaryOp::Add || op == BinaryOp::Sub && lp;
            // The offset: an integer, or a bit string read as its unsigned
            // value (CODESYS adds DWORDs to pointers).
            let offset = self.types.is_integer(nt)
                || self
                    .types
                    .numeric(nt)
                    .is_some_and(|e| e != ElemType::Bool && stc_values::is_bit_string(e));
            if void(self, pt) && moves && offset {
                // `ADR(x) + n`: still an address of x's object.
                return pt;
            }
            if void(self, pt) {
                self.emit(
                    Diagnostic::new(
                        Code::E1403,
                        span,
                        "`ADR(x)` has no pointer type of its own here",
                    )
                    .with_help("assign it to a POINTER TO variable first, then move it"),
                );
                return if cmp { bool_ty } else { TypeId::ERROR };
            }
            let _ = p;
            let zero = matches!(self.consts.get(&n), Some(Value::Int(0))) && self.is_literal(n)
                || matches!(self.types.kind(nt), TypeKind::Ref(TypeId::VOID));
            if matches!(op, BinaryOp::Eq | BinaryOp::Ne) && zero {
                self.null_ptrs.insert(n);
                return bool_ty;
            }
            let moves = op == BinaryOp::Add || op == BinaryOp::Sub && lp;
            if moves && offset {
                return pt;
            }
        }
        let what = match op {
            BinaryOp::Add | BinaryOp::Sub => "pointers move by a whole number of bytes: `p + n`, `p - n`; `p - q` is their distance",
            _ if cmp => "pointers compare with pointers of the same type, or with 0",
            _ => "pointers have no operator but `+`, `-` and comparisons",
        };
        self.emit(
            Diagnostic::new(
                Code::E1403,
                span,
                "operator not defined on these pointer operands",
            )
            .with_help(what),
        );
        if cmp {
            bool_ty
        } else {
            TypeId::ERROR
        }
    }

    /// Whether the pointer value of `e` may point into a variable that
    /// lives only during a call (of this POU or a caller's), see the
    /// module documentation.
    pub(crate) fn ptr_short(&self, e: ExprId) -> bool {
        match &self.ast.expr(e).kind {
            ExprKind::Paren(b) => self.ptr_short(*b),
            ExprKind::Binary { lhs, rhs, .. } => {
                let pl = matches!(self.types.kind(self.expr_type_of(*lhs)), TypeKind::Ptr(_));
                let pr = matches!(self.types.kind(self.expr_type_of(*rhs)), TypeKind::Ptr(_));
                (pl && self.ptr_short(*lhs)) || (pr && self.ptr_short(*rhs))
            }
            ExprKind::Literal(_) => false,
            ExprKind::Call { .. } => match self.calls.get(&e).map(|c| &c.target) {
                Some(CallTarget::Adr) => self.short_adrs.contains(&e),
                // A function's result and outputs only hold long-lived pointers.
                Some(CallTarget::Function(_)) | Some(CallTarget::Method { .. }) => false,
                _ => true,
            },
            ExprKind::Name(_)
            | ExprKind::Member { .. }
            | ExprKind::Index { .. }
            | ExprKind::Deref(_) => self.place_local(e) != Some(false),
            _ => !matches!(
                self.types.kind(self.expr_type_of(e)),
                TypeKind::Ref(TypeId::VOID)
            ),
        }
    }

    /// Where a place lives: `Some(true)` in the frame of the running call
    /// (a variable of this FUNCTION or METHOD other than its result and
    /// outputs, a VAR_TEMP), `Some(false)` in memory that outlives calls,
    /// `None` when unknown (a VAR_IN_OUT, what a pointer points at).
    fn place_local(&self, e: ExprId) -> Option<bool> {
        let mut root = e;
        let mut instance = false;
        loop {
            match &self.ast.expr(root).kind {
                ExprKind::Paren(b) | ExprKind::Index { base: b, .. } => root = *b,
                ExprKind::Member { base, .. } => {
                    if matches!(self.types.kind(self.expr_type_of(*base)), TypeKind::Fb(_)) {
                        instance = true;
                    }
                    root = *base;
                }
                ExprKind::Deref(p) => {
                    // Memory that outlives calls holds only pointers that
                    // do (what a reference refers to always does).
                    let pt = self.expr_type_of(*p);
                    let long = matches!(self.types.kind(pt), TypeKind::Ref(_))
                        || matches!(self.types.kind(pt), TypeKind::Ptr(_)) && !self.ptr_short(*p);
                    return if long { Some(false) } else { None };
                }
                ExprKind::Name(_) => break,
                _ => return None,
            }
        }
        match self.resolutions.get(&root).copied() {
            Some(Res::Var(v)) => {
                let p = self.body.current?;
                let pou = &self.pous[p.0 as usize];
                let var = pou.var(v);
                if var.section == Section::InOut {
                    return None;
                }
                let function = pou.kind == PouKind::Function;
                let local_section =
                    matches!(var.section, Section::Var | Section::Input | Section::Temp);
                let result = var.name == pou.name;
                Some(
                    !instance
                        && (var.section == Section::Temp || function && local_section && !result),
                )
            }
            _ => Some(false),
        }
    }

    /// A value of type `ty` (`value`) stored into the place `target`: a
    /// pointer that may point into a call's variables (or a value holding
    /// one) cannot be kept where it outlives that call (E1404).
    pub(crate) fn check_ptr_store(
        &mut self,
        target: Option<ExprId>,
        value: ExprId,
        ty: TypeId,
        span: Span,
    ) {
        if !self.types_holds_ptr(ty) {
            return;
        }
        let dest_local = target.and_then(|t| self.place_local(t)) == Some(true);
        if dest_local {
            return;
        }
        let short = if matches!(self.types.kind(ty), TypeKind::Ptr(_)) {
            self.ptr_short(value)
        } else {
            // A structure or array holding pointers: where it comes from.
            !matches!(self.place_local(value), Some(false))
                && !matches!(
                    self.calls.get(&value).map(|c| &c.target),
                    Some(CallTarget::Function(_))
                )
        };
        if short {
            self.emit(
                Diagnostic::new(
                    Code::E1404,
                    span,
                    "a pointer that may point into a function's variables is kept where it outlives the call",
                )
                .with_label("may point into memory that lives only during a call")
                .with_help("keep pointers to a FUNCTION's or METHOD's variables (or a VAR_TEMP or VAR_IN_OUT) in that call's own variables; store only pointers to globals or instance variables"),
            );
        }
    }

    /// The type a name in `SIZEOF(name)` denotes, when it is a type's and
    /// not a variable's: a declared type or a function block.
    fn type_named(&mut self, id: stc_syntax::ast::Ident, scope: Scope) -> Option<TypeId> {
        let sym = id.sym;
        if let Scope::Pou(p) = scope {
            if self.pous[p.0 as usize].lookup(sym).is_some() {
                return None;
            }
        }
        if let Some(e) = ElemType::from_name(self.interner.key(sym)) {
            return Some(self.types.elem(e));
        }
        match self.global_name(id) {
            Some(crate::analyzer::GlobalName::Type(i)) => Some(self.resolve_type_decl(i).0),
            Some(crate::analyzer::GlobalName::Pou(p))
                if self.pous[p.0 as usize].kind == PouKind::FunctionBlock =>
            {
                Some(self.pou_type(p))
            }
            _ => None,
        }
    }

    fn expr_type_of(&self, e: ExprId) -> TypeId {
        self.expr_types
            .get(e.index())
            .copied()
            .unwrap_or(TypeId::ERROR)
    }

    /// Whether a value of type `t` is or contains a pointer.
    pub(crate) fn types_holds_ptr(&self, t: TypeId) -> bool {
        let mut seen = Vec::new();
        self.holds_ptr_at(t, &mut seen)
    }

    fn holds_ptr_at(&self, t: TypeId, seen: &mut Vec<TypeId>) -> bool {
        if seen.contains(&t) || seen.len() > 64 {
            return false;
        }
        seen.push(t);
        match self.types.kind(t) {
            TypeKind::Ptr(_) => true,
            TypeKind::Array { elem, .. } => self.holds_ptr_at(*elem, seen),
            TypeKind::Struct { fields } => fields.iter().any(|f| self.holds_ptr_at(f.ty, seen)),
            _ => false,
        }
    }
}
