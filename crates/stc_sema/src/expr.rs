//! Expressions: names, literals, operators, members, indexing.
//!
//! Typing is bidirectional. An expression is checked with the type its
//! context expects (the assignment target, the parameter, the other operand);
//! untyped literals and unqualified enumeration values ("flexible"
//! expressions) take that type, everything else has its own type and is then
//! converted implicitly where spec/semantics.md allows it. Every constant
//! subexpression is folded with `stc_values`, the same code the VM runs.

use stc_diagnostics::{Code, Diagnostic, Span};
use stc_syntax::ast::{BinaryOp, ExprId, ExprKind, Ident, LitValue, Literal, TypePrefix, UnaryOp};
use stc_syntax::literal::AddrSize;
use stc_syntax::token::ElemType;
use stc_values::{BinOp, UnOp, Value};

use crate::analyzer::{GlobalName, Scope, Sema};
use crate::types::{Compat, InitValue, TypeId, TypeKind};
use crate::{GlobalId, GlobalOwner, PouId, Res, Section};

/// The context of a conversion, which decides the diagnostic code.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
pub(crate) enum Ctx {
    Assign,
    Init,
    Arg,
}

impl<'a> Sema<'a> {
    pub(crate) fn check_expr(
        &mut self,
        e: ExprId,
        expected: Option<TypeId>,
        scope: Scope,
    ) -> TypeId {
        let t = self.expr_kind(e, expected, scope);
        self.set_type(e, t);
        t
    }

    fn expr_kind(&mut self, e: ExprId, expected: Option<TypeId>, scope: Scope) -> TypeId {
        let expr = &self.ast.exprs[e.index()];
        let span = expr.span;
        match &expr.kind {
            ExprKind::Error => TypeId::ERROR,
            ExprKind::Literal(l) => self.literal(e, l, expected, span, false),
            ExprKind::Name(id) => self.name_expr(e, *id, expected, scope),
            ExprKind::EnumValue { ty, value } => self.qualified_enum(e, *ty, *value),
            ExprKind::Address(a) => {
                if a.is_incomplete() {
                    self.error(
                        Code::E0010,
                        span,
                        format!("the incomplete address {a} can only be used in an AT clause"),
                    );
                    return TypeId::ERROR;
                }
                let e = match a.size {
                    AddrSize::Bit => ElemType::Bool,
                    AddrSize::Byte => ElemType::Byte,
                    AddrSize::Word => ElemType::Word,
                    AddrSize::Dword => ElemType::Dword,
                    AddrSize::Lword => ElemType::Lword,
                };
                self.types.elem(e)
            }
            ExprKind::Member { base, member } => self.member(e, *base, *member, scope),
            ExprKind::PartialAccess { base, size, index } => {
                let bt = self.check_expr(*base, None, scope);
                if bt == TypeId::ERROR {
                    return TypeId::ERROR;
                }
                let part = match size {
                    AddrSize::Bit => ElemType::Bool,
                    AddrSize::Byte => ElemType::Byte,
                    AddrSize::Word => ElemType::Word,
                    AddrSize::Dword => ElemType::Dword,
                    AddrSize::Lword => ElemType::Lword,
                };
                let width = self
                    .types
                    .numeric(bt)
                    .filter(|t| stc_values::is_integer(*t) || stc_values::is_bit_string(*t))
                    .map(stc_values::bits);
                match width {
                    Some(w) if w > size.bits() => {
                        let parts = w / size.bits();
                        if *index >= parts {
                            let msg = format!(
                                "{} has parts 0..{} of this size, not {index}",
                                self.tname(bt),
                                parts - 1
                            );
                            self.error(Code::E0701, span, msg);
                        }
                        self.types.elem(part)
                    }
                    _ => {
                        let msg =
                            format!("a value of type {} has no bits to select", self.tname(bt));
                        self.error(Code::E0201, span, msg);
                        TypeId::ERROR
                    }
                }
            }
            ExprKind::Index { base, indices } => self.index(e, *base, indices, scope),
            ExprKind::Call { callee, args } => {
                let t = self.call(e, *callee, args, expected, scope, false);
                if t == TypeId::VOID {
                    // A FUNCTION declared without a result type, used as a
                    // value: said once here, not as "no value" further up.
                    let name = match &self.ast.expr(*callee).kind {
                        ExprKind::Name(id) => self.spelled(id.sym, id.span),
                        _ => "this function".to_string(),
                    };
                    self.emit(
                        Diagnostic::new(
                            Code::E0301,
                            self.ast.expr(e).span,
                            format!("`{name}` has no result: it is declared without a result type"),
                        )
                        .with_label("used as a value here")
                        .with_help("declare its result type (`FUNCTION f : INT`), or call it as a statement"),
                    );
                    return TypeId::ERROR;
                }
                t
            }
            ExprKind::Unary { op, operand } => self.unary(e, *op, *operand, expected, scope),
            ExprKind::Binary { op, lhs, rhs } => self.binary(e, *op, *lhs, *rhs, expected, scope),
            ExprKind::IlCr => self.body.il_cr.unwrap_or(TypeId::ERROR),
            ExprKind::Deref(base) => self.deref(*base, span, scope),
            ExprKind::Paren(inner) => {
                let t = self.check_expr(*inner, expected, scope);
                if let Some(v) = self.consts.get(inner).cloned() {
                    self.consts.insert(e, v);
                }
                if let Some(r) = self.resolutions.get(inner).copied() {
                    if matches!(r, Res::EnumValue(..)) {
                        self.resolutions.insert(e, r);
                    }
                }
                t
            }
        }
    }

    // ----- instances and methods --------------------------------------------

    /// The function block whose instance runs a POU's code: the block
    /// itself, or the block a METHOD belongs to.
    pub(crate) fn own_fb(&self, p: PouId) -> Option<PouId> {
        self.own_instance(p)
            .filter(|&q| self.pous[q.0 as usize].kind == stc_syntax::ast::PouKind::FunctionBlock)
    }

    /// The function block or program whose instance POU `p` runs on: `p`
    /// itself, or the POU a METHOD or ACTION belongs to (a PROGRAM has
    /// ACTIONs, not methods: no `THIS`).
    pub(crate) fn own_instance(&self, p: PouId) -> Option<PouId> {
        let def = &self.pous[p.0 as usize];
        match def.method_of {
            Some((fb, _)) => Some(fb),
            None if matches!(
                def.kind,
                stc_syntax::ast::PouKind::FunctionBlock | stc_syntax::ast::PouKind::Program
            ) =>
            {
                Some(p)
            }
            None => None,
        }
    }

    /// The METHOD `name` of function block `fb`.
    /// (Its own, else its base's, else its interfaces': the
    /// implementation an instance of exactly `fb` runs.)
    pub(crate) fn find_method(&self, fb: PouId, name: stc_syntax::Symbol) -> Option<PouId> {
        let mut stack = vec![fb];
        let mut seen = Vec::new();
        while let Some(p) = stack.pop() {
            if seen.contains(&p) {
                continue;
            }
            seen.push(p);
            let def = &self.pous[p.0 as usize];
            if let Some(m) = def
                .methods
                .iter()
                .copied()
                .find(|m| self.pous[m.0 as usize].name == name)
            {
                return Some(m);
            }
            // (Last pushed, first searched: the base before the interfaces.)
            stack.extend(def.interfaces.iter().rev().copied());
            stack.extend(def.base);
        }
        None
    }

    /// Whether variable `v` of block `p` is declared in a `VAR PUBLIC` or
    /// `VAR INTERNAL` section (3rd edition): visible outside its instance
    /// (INTERNAL: from inside the block's namespace, `at` the use).
    fn public_var(&self, p: PouId, v: crate::VarId, at: Span) -> bool {
        let Some(Some(src)) = self
            .pou_var_src
            .get(p.0 as usize)
            .and_then(|s| s.get(v.0 as usize))
        else {
            return false;
        };
        src.block.kind == stc_syntax::ast::VarKind::Var
            && match src.block.access {
                Some(stc_syntax::ast::Access::Public) => true,
                Some(stc_syntax::ast::Access::Internal) => self.in_namespace_of(p, at),
                _ => false,
            }
    }

    /// A name in POU `p` that is not one of its own variables: `THIS`,
    /// `SUPER`, or in a METHOD a variable of its function block (the
    /// instance's, through `THIS`).
    fn instance_name(&mut self, e: ExprId, id: Ident, p: PouId) -> Option<TypeId> {
        let key = self.interner.key(id.sym);
        if key == "THIS" {
            let Some(fb) = self.own_fb(p) else {
                self.emit(
                    Diagnostic::new(
                        Code::E1312,
                        id.span,
                        "`THIS` is only defined in a FUNCTION_BLOCK and its methods",
                    )
                    .with_label("no instance here"),
                );
                return Some(TypeId::ERROR);
            };
            self.resolutions.insert(e, Res::This);
            let t = self.pou_type(fb);
            return Some(self.types.ref_to(t));
        }
        if key == "SUPER" {
            let base = self.own_fb(p).and_then(|fb| self.pous[fb.0 as usize].base);
            if let Some(b) = base {
                // `SUPER^`: this instance as its base (its methods called
                // statically, its body by `SUPER^()`).
                self.resolutions.insert(e, Res::Super);
                let t = self.pou_type(b);
                return Some(self.types.ref_to(t));
            }
            self.emit(
                Diagnostic::new(
                    Code::E1313,
                    id.span,
                    "`SUPER` refers to the base of a function block, and this one extends none",
                )
                .with_help("call the method of this block: `THIS^.m()`"),
            );
            return Some(TypeId::ERROR);
        }
        let (fb, _) = self.pous[p.0 as usize].method_of?;
        let v = self.pous[fb.0 as usize].lookup(id.sym)?;
        self.ensure_var(fb, v);
        self.resolutions.insert(e, Res::FbMember(fb, v));
        self.used.insert((fb, v));
        Some(self.pous[fb.0 as usize].var(v).ty)
    }

    // ----- references -------------------------------------------------------

    /// `base^`: the variable a reference refers to.
    fn deref(&mut self, base: ExprId, span: Span, scope: Scope) -> TypeId {
        let t = self.check_expr(base, None, scope);
        if t == TypeId::ERROR {
            return TypeId::ERROR;
        }
        if let Some(target) = self.types.ptr_target(t) {
            if matches!(self.types.kind(target), TypeKind::Array { .. }) {
                // Only its elements: `p^[i]` (see `index`).
                self.whole_ptr_arrays.push(span);
            }
            if target == TypeId::VOID {
                self.emit(
                    Diagnostic::new(
                        Code::E1403,
                        span,
                        "`ADR(x)` cannot be dereferenced: it has no pointer type of its own",
                    )
                    .with_help("assign it to a POINTER TO variable and dereference that"),
                );
                return TypeId::ERROR;
            }
            return target;
        }
        match self.types.ref_target(t) {
            Some(TypeId::VOID) => {
                self.emit(
                    Diagnostic::new(Code::E1301, span, "`NULL` cannot be dereferenced")
                        .with_label("refers to no variable"),
                );
                TypeId::ERROR
            }
            Some(target) => target,
            None => {
                let shown = self.tname(t);
                self.emit(
                    Diagnostic::new(
                        Code::E1301,
                        span,
                        format!("`^` dereferences a reference, not a value of type {shown}"),
                    )
                    .with_label(format!("this is {shown}"))
                    .with_help("declare the variable `REF_TO T` and set it with `REF(x)`"),
                );
                TypeId::ERROR
            }
        }
    }

    /// `REF(x)`: a reference to the variable `x`. Only memory that lives as
    /// long as the program may be referred to (globals, the variables of
    /// program and function block instances, and what a reference refers
    /// to), so a reference can never outlive its target (docs/oop.md).
    pub(crate) fn ref_of(&mut self, arg: ExprId, scope: Scope) -> TypeId {
        let t = self.check_expr(arg, None, scope);
        if t == TypeId::ERROR {
            return TypeId::ERROR;
        }
        self.ref_of_checked(arg, t, scope)
    }

    /// [`Sema::ref_of`] of an expression already checked, of type `t`.
    pub(crate) fn ref_of_checked(&mut self, arg: ExprId, t: TypeId, scope: Scope) -> TypeId {
        let aspan = self.ast.expr(arg).span;
        let not_var = |s: &mut Self, why: &str| {
            s.emit(
                Diagnostic::new(
                    Code::E1302,
                    aspan,
                    format!("REF needs a variable, not {why}"),
                )
                .with_label("has no address"),
            );
            TypeId::ERROR
        };
        let mut root = arg;
        loop {
            match &self.ast.expr(root).kind {
                ExprKind::Paren(b) | ExprKind::Member { base: b, .. } => root = *b,
                ExprKind::Index { base, .. } => root = *base,
                ExprKind::Deref(_) => {
                    // What a reference refers to lives long enough.
                    return self.types.ref_to(t);
                }
                ExprKind::PartialAccess { .. } => return not_var(self, "a part of a bit string"),
                ExprKind::Name(_) => break,
                ExprKind::Address(_) => return not_var(self, "a direct address"),
                _ => return not_var(self, "the value of an expression"),
            }
        }
        if matches!(self.resolutions.get(&root), Some(Res::EnumValue(..))) {
            return not_var(self, "an enumeration value");
        }
        match self.resolutions.get(&root).copied() {
            Some(Res::Var(v)) => {
                let Scope::Pou(p) = scope else {
                    return not_var(self, "this");
                };
                let pou = &self.pous[p.0 as usize];
                let var = pou.var(v).clone();
                let function = pou.kind == stc_syntax::ast::PouKind::Function;
                let shown = self.sym_name(var.name);
                let why = if function {
                    Some("a variable of a function, which lives only during its call")
                } else {
                    match var.section {
                        Section::Temp => Some("a VAR_TEMP, which lives only during one call"),
                        Section::InOut => Some(
                            "a VAR_IN_OUT, which may stand for a variable that lives only during the call",
                        ),
                        _ => None,
                    }
                };
                if let Some(why) = why {
                    self.emit(
                        Diagnostic::new(
                            Code::E1303,
                            aspan,
                            format!("REF of `{shown}`: {why}"),
                        )
                        .with_secondary(var.span, "declared here")
                        .with_help(
                            "refer to a global or to a variable of a PROGRAM or FUNCTION_BLOCK instance",
                        ),
                    );
                    return TypeId::ERROR;
                }
                if var.constant {
                    return self.ref_of_constant(&shown, aspan, var.span);
                }
            }
            Some(Res::Global(g)) => {
                let gv = self.globals[g.0 as usize].var.clone();
                if gv.constant {
                    let shown = self.sym_name(gv.name);
                    return self.ref_of_constant(&shown, aspan, gv.span);
                }
            }
            _ => return not_var(self, "this"),
        }
        self.types.ref_to(t)
    }

    /// `a = b` and `a <> b` on references (the only operators they have).
    fn ref_binary(&mut self, op: BinaryOp, lt: TypeId, rt: TypeId, span: Span) -> TypeId {
        let bool_ty = self.types.elem(ElemType::Bool);
        if !matches!(op, BinaryOp::Eq | BinaryOp::Ne) {
            self.emit(
                Diagnostic::new(
                    Code::E1307,
                    span,
                    "references have no operator but `=` and `<>`",
                )
                .with_help("dereference them (`r^`) to work on what they refer to"),
            );
            let cmp = matches!(
                op,
                BinaryOp::Eq
                    | BinaryOp::Ne
                    | BinaryOp::Lt
                    | BinaryOp::Le
                    | BinaryOp::Gt
                    | BinaryOp::Ge
            );
            return if cmp { bool_ty } else { TypeId::ERROR };
        }
        let fits = self.types.compat(lt, rt, false) == Compat::Same
            || self.types.compat(rt, lt, false) == Compat::Same;
        if !fits {
            let (a, b) = (self.tname(lt), self.tname(rt));
            self.emit(
                Diagnostic::new(
                    Code::E1304,
                    span,
                    format!("cannot compare a value of type {a} with one of type {b}"),
                )
                .with_help("references compare with references of the same target type, or NULL"),
            );
        }
        bool_ty
    }

    fn ref_of_constant(&mut self, shown: &str, span: Span, decl: Span) -> TypeId {
        self.emit(
            Diagnostic::new(
                Code::E1305,
                span,
                format!("REF of the constant `{shown}`: it could be changed through the reference"),
            )
            .with_secondary(decl, "declared CONSTANT here"),
        );
        TypeId::ERROR
    }

    // ----- literals ---------------------------------------------------------

    /// The type a literal takes, from its prefix or its context.
    pub(crate) fn literal(
        &mut self,
        e: ExprId,
        l: &Literal,
        expected: Option<TypeId>,
        span: Span,
        negated: bool,
    ) -> TypeId {
        let prefix_ty = match l.prefix {
            Some(TypePrefix::Elem(t, _)) => Some(self.types.elem(t)),
            Some(TypePrefix::Named(id)) => match self.global_name(id) {
                Some(GlobalName::Type(i)) => Some(self.resolve_type_decl(i).0),
                _ => {
                    let shown = self.spelled(id.sym, id.span);
                    self.error(Code::E0102, id.span, format!("unknown type `{shown}`"));
                    return TypeId::ERROR;
                }
            },
            None => None,
        };
        if prefix_ty == Some(TypeId::ERROR) {
            return TypeId::ERROR;
        }
        let target = prefix_ty.or(expected.filter(|t| *t != TypeId::ERROR));
        let target_scalar = target.and_then(|t| self.types.numeric(t));
        match &l.value {
            LitValue::Int { value, negative } => {
                let mut v = *value as i128;
                if *negative != negated {
                    v = -v;
                }
                match target_scalar {
                    Some(ElemType::Bool) => {
                        if v == 0 || v == 1 {
                            self.consts.insert(e, Value::Bool(v == 1));
                            return self.types.elem(ElemType::Bool);
                        }
                        if prefix_ty.is_some() {
                            self.error(
                                Code::E0303,
                                span,
                                format!("`{v}` is not a BOOL: only 0 and 1 are"),
                            );
                            return TypeId::ERROR;
                        }
                    }
                    Some(t) if stc_values::is_real(t) => {
                        let value = if t == ElemType::Real {
                            (v as f32) as f64
                        } else {
                            v as f64
                        };
                        self.consts.insert(e, Value::Real(value));
                        return self.types.elem(t);
                    }
                    Some(t) if stc_values::is_integer(t) || stc_values::is_bit_string(t) => {
                        let (min, max) = stc_values::int_range(t).unwrap_or((0, 0));
                        if v < min || v > max {
                            let shown = target.map(|t| self.tname(t)).unwrap_or_default();
                            self.emit(
                                Diagnostic::new(
                                    Code::E0303,
                                    span,
                                    format!("`{v}` is out of the range of {shown} ({min}..{max})"),
                                )
                                .with_label(format!("does not fit in {shown}")),
                            );
                            return TypeId::ERROR;
                        }
                        self.consts.insert(e, Value::Int(v));
                        return self.types.elem(t);
                    }
                    _ => {}
                }
                if let Some(pt) = prefix_ty {
                    let msg = format!("an integer literal cannot have type {}", self.tname(pt));
                    self.error(Code::E0303, span, msg);
                    return TypeId::ERROR;
                }
                self.consts.insert(e, Value::Int(v));
                let t = if i32::try_from(v).is_ok() {
                    ElemType::Dint
                } else if i64::try_from(v).is_ok() {
                    ElemType::Lint
                } else if u64::try_from(v).is_ok() {
                    ElemType::Ulint
                } else {
                    self.error(
                        Code::E0303,
                        span,
                        format!("`{v}` is out of the range of every integer type"),
                    );
                    return TypeId::ERROR;
                };
                self.types.elem(t)
            }
            LitValue::Real(r) => {
                let r = if negated { -*r } else { *r };
                let t = match target_scalar {
                    Some(ElemType::Real) => ElemType::Real,
                    _ => ElemType::Lreal,
                };
                if let Some(pt) = prefix_ty {
                    if !self.types.numeric(pt).is_some_and(stc_values::is_real) {
                        let msg = format!("a real literal cannot have type {}", self.tname(pt));
                        self.error(Code::E0303, span, msg);
                        return TypeId::ERROR;
                    }
                }
                let value = if t == ElemType::Real {
                    let f = r as f32;
                    if f.is_infinite() {
                        self.error(
                            Code::E0303,
                            span,
                            format!("`{r}` is out of the range of REAL"),
                        );
                        return TypeId::ERROR;
                    }
                    f as f64
                } else {
                    r
                };
                self.consts.insert(e, Value::Real(value));
                self.types.elem(t)
            }
            LitValue::Bool(b) => {
                if let Some(pt) = prefix_ty {
                    if !self.types.is_bool(pt) {
                        let msg = format!("TRUE and FALSE cannot have type {}", self.tname(pt));
                        self.error(Code::E0303, span, msg);
                        return TypeId::ERROR;
                    }
                }
                self.consts.insert(e, Value::Bool(*b));
                self.types.elem(ElemType::Bool)
            }
            LitValue::String { value, wide } => {
                let chars = value.chars().count() as u32;
                let char_prefix = matches!(
                    l.prefix,
                    Some(TypePrefix::Elem(ElemType::Char | ElemType::Wchar, _))
                );
                if let Some(TypePrefix::Elem(p, _)) = l.prefix {
                    let ok = match p {
                        ElemType::String | ElemType::Char => !wide,
                        ElemType::Wstring | ElemType::Wchar => *wide,
                        _ => false,
                    };
                    if !ok || (char_prefix && chars != 1) {
                        self.error(
                            Code::E0303,
                            span,
                            format!("this string literal cannot have type {}", p.name()),
                        );
                        return TypeId::ERROR;
                    }
                }
                let v = if *wide {
                    Value::WStr(value.encode_utf16().collect())
                } else {
                    // Single-byte text is Windows-1252 (spec/semantics.md).
                    let mut bytes = Vec::with_capacity(value.len());
                    for c in value.chars() {
                        match stc_syntax::literal::cp1252_encode(c) {
                            Some(b) => bytes.push(b),
                            None => {
                                self.emit(
                                    Diagnostic::new(
                                        Code::E0303,
                                        span,
                                        format!(
                                            "`{}` (U+{:04X}) cannot be stored in a single-byte STRING",
                                            c.escape_debug(),
                                            c as u32
                                        ),
                                    )
                                    .with_note("a STRING holds Windows-1252 characters")
                                    .with_help("use a WSTRING (\"...\") for other characters"),
                                );
                                return TypeId::ERROR;
                            }
                        }
                    }
                    Value::Str(bytes)
                };
                if char_prefix {
                    let code = match &v {
                        Value::Str(b) => b.first().copied().unwrap_or(0) as i128,
                        Value::WStr(u) => u.first().copied().unwrap_or(0) as i128,
                        _ => 0,
                    };
                    self.consts.insert(e, Value::Int(code));
                    return self.types.elem(if *wide {
                        ElemType::Wchar
                    } else {
                        ElemType::Char
                    });
                }
                self.consts.insert(e, v);
                self.types.string(*wide, chars.max(1))
            }
            LitValue::Duration { ns, long } => {
                self.consts.insert(e, Value::Int(*ns as i128));
                self.types.elem(if *long {
                    ElemType::Ltime
                } else {
                    ElemType::Time
                })
            }
            LitValue::Date { secs, long } => {
                self.consts.insert(e, Value::Int(*secs as i128));
                self.types.elem(if *long {
                    ElemType::Ldate
                } else {
                    ElemType::Date
                })
            }
            LitValue::Tod { ns, long } => {
                self.consts.insert(e, Value::Int(*ns as i128));
                self.types
                    .elem(if *long { ElemType::Ltod } else { ElemType::Tod })
            }
            LitValue::Dt { ns, long } => {
                self.consts.insert(e, Value::Int(*ns as i128));
                self.types
                    .elem(if *long { ElemType::Ldt } else { ElemType::Dt })
            }
        }
    }

    // ----- names ------------------------------------------------------------

    /// Whether an expression takes its type from its context: untyped numeric
    /// literals and unqualified enumeration values, and operators over them.
    pub(crate) fn is_flexible(&self, e: ExprId, scope: Scope) -> bool {
        match &self.ast.expr(e).kind {
            ExprKind::Literal(l) => {
                l.prefix.is_none() && matches!(l.value, LitValue::Int { .. } | LitValue::Real(_))
            }
            ExprKind::Unary {
                op: UnaryOp::Neg | UnaryOp::Plus,
                operand,
            } => self.is_flexible(*operand, scope),
            ExprKind::Paren(i) => self.is_flexible(*i, scope),
            ExprKind::Binary { op, lhs, rhs } => {
                !matches!(
                    op,
                    BinaryOp::Eq
                        | BinaryOp::Ne
                        | BinaryOp::Lt
                        | BinaryOp::Le
                        | BinaryOp::Gt
                        | BinaryOp::Ge
                ) && self.is_flexible(*lhs, scope)
                    && self.is_flexible(*rhs, scope)
            }
            ExprKind::Name(id) => {
                !self.is_variable_name(id.sym, scope)
                    && self.enum_candidates(id.sym, scope).next().is_some()
            }
            // A standard function whose result type is fixed by nothing but
            // its context (LEN, FIND, TRUNC: ANY_INT out): `LEN(s) < pos`
            // compares INTs when `pos` is an INT, as with a literal.
            ExprKind::Call { callee, .. } => match &self.ast.expr(*callee).kind {
                ExprKind::Name(id) if !self.is_global_name(*id) => {
                    let f = stc_values::lookup(self.interner.key(id.sym));
                    f.is_some_and(|f| match f.ret {
                        stc_values::TyPat::Var(k, _) => !f
                            .params
                            .iter()
                            .any(|p| matches!(p.ty, stc_values::TyPat::Var(j, _) if j == k)),
                        stc_values::TyPat::Elem(_) => false,
                    })
                }
                _ => false,
            },
            _ => false,
        }
    }

    fn is_variable_name(&self, sym: stc_syntax::Symbol, scope: Scope) -> bool {
        match scope {
            Scope::Pou(p) => self.pous[p.0 as usize].lookup(sym).is_some(),
            Scope::Config(c, r) => self.config_global(sym, c, r).is_some(),
            Scope::Global => self.global_constant(sym).is_some(),
        }
    }

    /// Enumeration values named `sym` visible in the scope: (type, index, local?).
    pub(crate) fn enum_candidates(
        &self,
        sym: stc_syntax::Symbol,
        scope: Scope,
    ) -> impl Iterator<Item = (TypeId, u32, bool)> + '_ {
        let pou = match scope {
            Scope::Pou(p) => Some(p),
            _ => None,
        };
        self.enum_index
            .get(&sym)
            .into_iter()
            .flatten()
            .filter(move |(_, _, owner)| owner.is_none() || *owner == pou)
            .map(|(t, i, owner)| (*t, *i, owner.is_some()))
    }

    pub(crate) fn global_constant(&self, sym: stc_syntax::Symbol) -> Option<GlobalId> {
        self.globals
            .iter()
            .position(|g| g.var.name == sym && g.var.constant)
            .map(|i| GlobalId(i as u32))
    }

    /// A global visible in a configuration (or one of its resources).
    pub(crate) fn config_global(
        &self,
        sym: stc_syntax::Symbol,
        c: usize,
        r: Option<usize>,
    ) -> Option<GlobalId> {
        let find = |owner: GlobalOwner| {
            self.globals
                .iter()
                .position(|g| g.owner == owner && g.var.name == sym)
                .map(|i| GlobalId(i as u32))
        };
        r.and_then(|r| find(GlobalOwner::Resource(c, r)))
            .or_else(|| find(GlobalOwner::Config(c)))
            .or_else(|| find(GlobalOwner::TopLevel))
    }

    fn name_expr(
        &mut self,
        e: ExprId,
        id: Ident,
        expected: Option<TypeId>,
        scope: Scope,
    ) -> TypeId {
        match scope {
            Scope::Pou(p) => {
                if let Some(v) = self.pous[p.0 as usize].lookup(id.sym) {
                    self.ensure_var(p, v);
                    self.resolutions.insert(e, Res::Var(v));
                    self.used.insert((p, v));
                    let var = &self.pous[p.0 as usize].vars[v.0 as usize];
                    // A CONSTANT input, output or in-out gets its value from
                    // the caller: it is never folded.
                    let from_caller = matches!(
                        var.section,
                        Section::Input | Section::Output | Section::InOut
                    );
                    if var.constant && var.section == Section::External {
                        // A VAR_EXTERNAL CONSTANT has its global's value when
                        // only one global has its name (so it is a constant
                        // whatever configuration runs the POU).
                        let named: Vec<usize> = (0..self.globals.len())
                            .filter(|&i| self.globals[i].var.name == id.sym)
                            .collect();
                        if let [g] = named[..] {
                            self.resolve_global(GlobalId(g as u32));
                            let gv = &self.globals[g].var;
                            if let (true, Some(InitValue::Scalar(val))) = (gv.constant, &gv.init) {
                                self.consts.insert(e, val.clone());
                            }
                        }
                        return self.pous[p.0 as usize].vars[v.0 as usize].ty;
                    }
                    if var.constant && !from_caller {
                        if let Some(InitValue::Scalar(val)) = &var.init {
                            self.consts.insert(e, val.clone());
                        } else if var.init.is_none() && var.section != Section::External {
                            if let Some(s) = self.types.scalar(var.ty) {
                                self.consts.insert(e, stc_values::default_value(s));
                            }
                        }
                    }
                    return var.ty;
                }
                // A VAR_STAT variable (a global of its own), or in a METHOD
                // a VAR_INST variable (one of its block's).
                if let Some(&g) = self.statics.get(&(p, id.sym)) {
                    return self.global_ref(e, g);
                }
                if let Some((fb, k)) = self.pous[p.0 as usize].method_of {
                    let m = self
                        .pou_ast(fb)
                        .and_then(|a| a.methods.get(k))
                        .map(|m| m.pou.name.sym);
                    if let Some(&v) = m.and_then(|m| self.inst_vars.get(&(fb, m, id.sym))) {
                        self.ensure_var(fb, v);
                        self.resolutions.insert(e, Res::FbMember(fb, v));
                        self.used.insert((fb, v));
                        return self.pous[fb.0 as usize].var(v).ty;
                    }
                }
                if let Some(t) = self.instance_name(e, id, p) {
                    return t;
                }
                // A property of the running instance, by its bare name.
                if let Some(fb) = self.own_instance(p) {
                    if let Some(t) = self.property_read(e, fb, None, id, scope) {
                        return t;
                    }
                }
                if self.in_type_constant {
                    let top = self.globals.iter().position(|g| {
                        g.var.name == id.sym
                            && g.var.constant
                            && g.owner == crate::GlobalOwner::TopLevel
                    });
                    if let Some(g) = top {
                        return self.global_ref(e, GlobalId(g as u32));
                    }
                }
            }
            Scope::Config(c, r) => {
                if let Some(g) = self.config_global(id.sym, c, r) {
                    return self.global_ref(e, g);
                }
            }
            Scope::Global => {
                if let Some(g) = self.global_constant(id.sym) {
                    return self.global_ref(e, g);
                }
            }
        }
        if let Some(t) = self.unqualified_enum(e, id, expected, scope) {
            return t;
        }
        let shown = self.spelled(id.sym, id.span);
        if let Some(g) = self.global_name(id) {
            let what = match g {
                GlobalName::Type(_) => "a data type",
                GlobalName::Config(_) => "a configuration",
                GlobalName::Pou(p) => match self.pous[p.0 as usize].kind {
                    stc_syntax::ast::PouKind::Function => "a function",
                    stc_syntax::ast::PouKind::FunctionBlock => "a function block type",
                    stc_syntax::ast::PouKind::Program => "a program",
                },
            };
            self.emit(
                Diagnostic::new(
                    Code::E0110,
                    id.span,
                    format!("`{shown}` is {what}, not a variable"),
                )
                .with_label("not a variable"),
            );
            return TypeId::ERROR;
        }
        if let Scope::Pou(p) = scope {
            if self.member_may_be_unsupported(p, id.sym) {
                // May be inherited through an EXTENDS, or a PROPERTY of this
                // POU: reported already.
                return TypeId::ERROR;
            }
        }
        if self.reserved_name(id, "a variable") {
            return TypeId::ERROR;
        }
        if self.interner.key(id.sym) == "NULL" {
            // The null reference of the 3rd edition: its type is accepted
            // by every reference type.
            return self.types.ref_to(TypeId::VOID);
        }
        if let Some(t) = self.implicit_global(e, id, scope) {
            return t;
        }
        let mut d = Diagnostic::new(
            Code::E0101,
            id.span,
            format!("undeclared variable `{shown}`"),
        )
        .with_label("not declared");
        let candidates: Vec<String> = match scope {
            Scope::Pou(p) => self.pous[p.0 as usize]
                .vars
                .iter()
                .map(|v| self.sym_name(v.name))
                .collect(),
            _ => self
                .globals
                .iter()
                .map(|g| self.sym_name(g.var.name))
                .collect(),
        };
        if let Some(s) = self.did_you_mean(&shown, candidates.iter().map(|s| s.as_str())) {
            d = d.with_help(format!("did you mean `{s}`?"));
        } else if let Scope::Pou(p) = scope {
            if let Some(g) = self.globals.iter().find(|g| g.var.name == id.sym) {
                let function = self.pous[p.0 as usize].kind == stc_syntax::ast::PouKind::Function;
                d = d.with_help(if self.in_type_constant && !g.var.constant {
                    format!("`{shown}` is a global variable, not a constant")
                } else if self.in_type_constant {
                    format!(
                        "`{shown}` is a constant of a configuration; only a VAR_GLOBAL CONSTANT \
                         outside configurations can size a type here"
                    )
                } else if function {
                    format!(
                        "`{shown}` is a global variable, and a FUNCTION cannot use globals: \
                         pass it as an input"
                    )
                } else {
                    format!(
                        "`{shown}` is a global variable: declare it in VAR_EXTERNAL to use it here"
                    )
                });
            }
        }
        self.emit(d);
        TypeId::ERROR
    }

    /// E0022 for a reserved word used as a name that nothing declares (a
    /// declared one had its E0022 at the declaration and then works as a
    /// name). Returns whether it reported.
    pub(crate) fn reserved_name(&mut self, id: Ident, what: &str) -> bool {
        let key = self.interner.key(id.sym);
        if !stc_syntax::token::classify_word(key.as_bytes()).is_reserved_word() {
            return false;
        }
        let shown = self.spelled(id.sym, id.span);
        self.emit(
            Diagnostic::new(
                Code::E0022,
                id.span,
                format!("`{shown}` is a reserved word and cannot be used as a name"),
            )
            .with_label(format!("not {what}")),
        );
        true
    }

    /// A name no declaration of the POU binds that is a global declared
    /// outside every configuration: read as if a VAR_EXTERNAL declared it,
    /// as CODESYS and TwinCAT do for their global variable lists (W0114,
    /// once per POU and name; an error under `--std iec2`, which keeps
    /// E0101).
    fn implicit_global(&mut self, e: ExprId, id: Ident, scope: Scope) -> Option<TypeId> {
        let Scope::Pou(p) = scope else {
            return None;
        };
        if self.opts.iec2 || self.in_type_constant {
            return None;
        }
        let g = self
            .globals
            .iter()
            .position(|g| g.var.name == id.sym && g.owner == GlobalOwner::TopLevel)?;
        let gspan = self.globals[g].var.span;
        if !self.in_prelude(gspan) && self.implicit_globals.insert((p, id.sym)) {
            let shown = self.spelled(id.sym, id.span);
            let pou = self.sym_name(self.pous[p.0 as usize].name);
            let constant = if self.globals[g].var.constant {
                " CONSTANT"
            } else {
                ""
            };
            self.emit(
                Diagnostic::new(
                    Code::W0114,
                    id.span,
                    format!("global variable `{shown}` used without VAR_EXTERNAL"),
                )
                .with_label("a global, not declared in this POU")
                .with_secondary(gspan, "declared here")
                .with_help(format!(
                    "declare it in `{pou}`: VAR_EXTERNAL{constant} {shown} : ...; END_VAR"
                )),
            );
        }
        Some(self.global_ref(e, GlobalId(g as u32)))
    }

    fn global_ref(&mut self, e: ExprId, g: GlobalId) -> TypeId {
        self.resolve_global(g);
        self.resolutions.insert(e, Res::Global(g));
        let var = &self.globals[g.0 as usize].var;
        if var.constant {
            if let Some(InitValue::Scalar(v)) = &var.init {
                self.consts.insert(e, v.clone());
            }
        }
        var.ty
    }

    /// An enumeration value named without its type, resolved from context.
    fn unqualified_enum(
        &mut self,
        e: ExprId,
        id: Ident,
        expected: Option<TypeId>,
        scope: Scope,
    ) -> Option<TypeId> {
        if let Some(t) = expected {
            if let TypeKind::Enum { values, .. } = self.types.kind(t) {
                if let Some(i) = values.iter().position(|v| v.name == id.sym) {
                    let value = values[i].value;
                    self.resolutions.insert(e, Res::EnumValue(t, i as u32));
                    self.consts.insert(e, Value::Int(value));
                    self.warn_hidden_enum_value(id, t, scope);
                    return Some(t);
                }
            }
        }
        let cands: Vec<(TypeId, u32, bool)> = self.enum_candidates(id.sym, scope).collect();
        if cands.is_empty() {
            return None;
        }
        let local: Vec<&(TypeId, u32, bool)> = cands.iter().filter(|c| c.2).collect();
        let pick = if local.len() == 1 {
            Some(*local[0])
        } else if cands.len() == 1 {
            Some(cands[0])
        } else {
            None
        };
        match pick {
            Some((t, i, _)) => {
                if let TypeKind::Enum { values, .. } = self.types.kind(t) {
                    let value = values[i as usize].value;
                    self.consts.insert(e, Value::Int(value));
                }
                self.resolutions.insert(e, Res::EnumValue(t, i));
                self.warn_hidden_enum_value(id, t, scope);
                Some(t)
            }
            None if expected == Some(TypeId::ERROR) => Some(TypeId::ERROR),
            None => {
                let shown = self.spelled(id.sym, id.span);
                let types: Vec<String> = cands
                    .iter()
                    .map(|c| format!("`{}#{shown}`", self.tname(c.0)))
                    .collect();
                self.emit(
                    Diagnostic::new(
                        Code::E0108,
                        id.span,
                        format!("`{shown}` is a value of several enumeration types"),
                    )
                    .with_label("ambiguous")
                    .with_help(format!("write one of {}", types.join(", "))),
                );
                Some(TypeId::ERROR)
            }
        }
    }

    /// W0102 at a use of an unqualified enumeration value that resolved to
    /// a value of a POU's own anonymous enumeration (type `t`) while a
    /// global enumeration has a value of that name, as MatIEC reports it.
    fn warn_hidden_enum_value(&mut self, id: Ident, t: TypeId, scope: Scope) {
        let Scope::Pou(p) = scope else { return };
        let Some(entry) = self.enum_index.get(&id.sym) else {
            return;
        };
        let local = entry.iter().any(|(ty, _, o)| *ty == t && *o == Some(p));
        let global = entry.iter().any(|(_, _, o)| o.is_none());
        if local && global {
            let shown = self.spelled(id.sym, id.span);
            self.emit(
                Diagnostic::new(
                    Code::W0102,
                    id.span,
                    format!("`{shown}` is the local enumeration value, which hides a global one"),
                )
                .with_label("the local value")
                .with_note(
                    "inside this POU the unqualified name means the local value; other tools may report it as ambiguous",
                ),
            );
        }
    }

    fn qualified_enum(&mut self, e: ExprId, ty: Ident, value: Ident) -> TypeId {
        let t = match self.global_name(ty) {
            Some(GlobalName::Type(i)) => self.resolve_type_decl(i).0,
            _ => {
                let shown = self.spelled(ty.sym, ty.span);
                self.error(Code::E0102, ty.span, format!("unknown type `{shown}`"));
                return TypeId::ERROR;
            }
        };
        if t == TypeId::ERROR {
            return t;
        }
        let TypeKind::Enum { values, .. } = self.types.kind(t) else {
            let msg = format!("`{}` is not an enumeration type", self.tname(t));
            self.error(Code::E0109, ty.span, msg);
            return TypeId::ERROR;
        };
        match values.iter().position(|v| v.name == value.sym) {
            Some(i) => {
                let v = values[i].value;
                self.consts.insert(e, Value::Int(v));
                self.resolutions.insert(e, Res::EnumValue(t, i as u32));
                t
            }
            None => {
                let names: Vec<String> = values.iter().map(|v| self.sym_name(v.name)).collect();
                let shown = self.spelled(value.sym, value.span);
                let mut d = Diagnostic::new(
                    Code::E0109,
                    value.span,
                    format!("`{}` has no value `{shown}`", self.tname(t)),
                )
                .with_label("not a value of this type");
                if let Some(s) = self.did_you_mean(&shown, names.iter().map(|s| s.as_str())) {
                    d = d.with_help(format!("did you mean `{s}`?"));
                } else {
                    d = d.with_note(format!("its values are {}", names.join(", ")));
                }
                self.emit(d);
                TypeId::ERROR
            }
        }
    }

    // ----- members and indexing ---------------------------------------------

    fn member(&mut self, e: ExprId, base: ExprId, member: Ident, scope: Scope) -> TypeId {
        let bt = self.check_expr(base, None, scope);
        if bt == TypeId::ERROR {
            return TypeId::ERROR;
        }
        let shown = self.spelled(member.sym, member.span);
        match self.types.kind(bt).clone() {
            TypeKind::Struct { fields } => match fields.iter().position(|f| f.name == member.sym) {
                Some(i) => {
                    self.resolutions.insert(e, Res::Field(i as u32));
                    fields[i].ty
                }
                None => {
                    let names: Vec<String> = fields.iter().map(|f| self.sym_name(f.name)).collect();
                    let mut d = Diagnostic::new(
                        Code::E0104,
                        member.span,
                        format!("{} has no member `{shown}`", self.tname(bt)),
                    )
                    .with_label("unknown member");
                    if let Some(s) = self.did_you_mean(&shown, names.iter().map(|s| s.as_str())) {
                        d = d.with_help(format!("did you mean `{s}`?"));
                    }
                    self.emit(d);
                    TypeId::ERROR
                }
            },
            TypeKind::Fb(p) | TypeKind::Program(p) => {
                self.resolve_pou(p);
                if self.pous[p.0 as usize].lookup(member.sym).is_none() {
                    if let Some(t) = self.property_read(e, p, Some(base), member, scope) {
                        return t;
                    }
                }
                let public = self.pous[p.0 as usize]
                    .lookup(member.sym)
                    .is_some_and(|v| self.public_var(p, v, member.span));
                let pou = &self.pous[p.0 as usize];
                match pou.lookup(member.sym) {
                    Some(v)
                        if matches!(pou.var(v).section, Section::Input | Section::Output)
                            || public =>
                    {
                        let ty = pou.var(v).ty;
                        if pou.var(v).implicit {
                            // `inst.ENO`: the variable needs storage.
                            self.used.insert((p, v));
                        }
                        self.resolutions.insert(e, Res::FbMember(p, v));
                        ty
                    }
                    found
                        if self.is_skipped_member(p, member.sym)
                            || found.is_none() && self.member_may_be_unsupported(p, member.sym) =>
                    {
                        // An ACTION or METHOD, or a member inherited through
                        // an EXTENDS: already reported at its declaration.
                        TypeId::ERROR
                    }
                    Some(v) if pou.var(v).section == Section::InOut && !self.opts.iec2 => {
                        // Read through the address the last call bound, as
                        // MatIEC allows (W0115); NULL before the first call,
                        // a run-time fault. Writes are refused (E0104, in
                        // `check_lvalue`).
                        let ty = pou.var(v).ty;
                        let msg = format!(
                            "`{shown}` is an in-out of `{}`, read from outside the instance",
                            self.tname(bt)
                        );
                        self.emit(
                            Diagnostic::new(Code::W0115, member.span, msg)
                                .with_label("VAR_IN_OUT")
                                .with_note("it is the variable the last call of the instance passed; before the first call, reading it is the fault `NULL dereference`"),
                        );
                        // The slot is an address: keep address 0 free.
                        self.types.ref_to(ty);
                        self.resolutions.insert(e, Res::FbMember(p, v));
                        ty
                    }
                    Some(v) if pou.var(v).section == Section::InOut => {
                        let msg = format!(
                            "`{shown}` is an in-out of `{}`, which is not visible from outside",
                            self.tname(bt)
                        );
                        self.emit(
                            Diagnostic::new(Code::E0104, member.span, msg)
                                .with_label("VAR_IN_OUT")
                                .with_note("a VAR_IN_OUT refers to the caller's variable during a call only: use that variable instead (`--std iec2` refuses reading it from outside)"),
                        );
                        TypeId::ERROR
                    }
                    found => {
                        let names: Vec<String> = pou
                            .vars
                            .iter()
                            .filter(|v| matches!(v.section, Section::Input | Section::Output))
                            .map(|v| self.sym_name(v.name))
                            .collect();
                        let what = if found.is_some() {
                            "an input or output of"
                        } else {
                            "a member of"
                        };
                        let mut d = Diagnostic::new(
                            Code::E0104,
                            member.span,
                            format!("`{shown}` is not {what} `{}`", self.tname(bt)),
                        )
                        .with_label("unknown member");
                        if found.is_none() {
                            if let Some(s) =
                                self.did_you_mean(&shown, names.iter().map(|s| s.as_str()))
                            {
                                d = d.with_help(format!("did you mean `{s}`?"));
                            }
                        } else {
                            d = d.with_note(
                                "only the inputs, the outputs and the `VAR PUBLIC` variables of an instance are visible outside it",
                            );
                        }
                        self.emit(d);
                        TypeId::ERROR
                    }
                }
            }
            _ => {
                let msg = format!("a value of type {} has no members", self.tname(bt));
                self.emit(
                    Diagnostic::new(Code::E0207, member.span, msg).with_label("no member here"),
                );
                TypeId::ERROR
            }
        }
    }

    fn index(&mut self, e: ExprId, base: ExprId, indices: &[ExprId], scope: Scope) -> TypeId {
        let partial_ok = std::mem::take(&mut self.partial_index_ok) == Some(e);
        if let ExprKind::Index { .. } = self.ast.expr(base).kind {
            // `a[i][j]` on a two-dimensional array: the inner index may be partial.
            self.partial_index_ok = Some(base);
        }
        let bt = self.check_expr(base, None, scope);
        let mut b = base;
        while let ExprKind::Paren(i) = &self.ast.expr(b).kind {
            b = *i;
        }
        if let ExprKind::Deref(_) = self.ast.expr(b).kind {
            let bspan = self.ast.expr(b).span;
            let all = matches!(self.types.kind(bt), TypeKind::Array { dims, .. } if dims.len() == indices.len());
            if all {
                self.whole_ptr_arrays.retain(|s| *s != bspan);
            }
        }
        let (dims, elem) = match self.types.kind(bt).clone() {
            TypeKind::Array { dims, elem } => (dims, elem),
            _ => {
                for &i in indices {
                    self.check_expr(i, None, scope);
                }
                if bt != TypeId::ERROR {
                    let span = self.ast.expr(base).span;
                    let msg = format!("a value of type {} cannot be indexed", self.tname(bt));
                    self.emit(Diagnostic::new(Code::E0206, span, msg).with_label("not an array"));
                }
                return TypeId::ERROR;
            }
        };
        let mut ok = true;
        for (k, &i) in indices.iter().enumerate() {
            let it = self.check_expr(i, None, scope);
            if it == TypeId::ERROR {
                ok = false;
                continue;
            }
            let bit_index = self
                .types
                .scalar(it)
                .filter(|t| stc_values::is_bit_string(*t) && *t != ElemType::Bool);
            if let (Some(b), false) = (bit_index, self.opts.iec2) {
                // A BYTE or WORD index, as CODESYS allows: its unsigned
                // value (W0113), converted to ULINT.
                let span = self.ast.expr(i).span;
                self.emit(
                    Diagnostic::new(
                        Code::W0113,
                        span,
                        format!(
                            "a bit string used as an array index: its value as an unsigned {}",
                            unsigned_of(b).name()
                        ),
                    )
                    .with_label(format!("this is {}", b.name()))
                    .with_help(format!(
                        "the standard wants an integer index: convert with {}_TO_{}(...)",
                        b.name(),
                        unsigned_of(b).name()
                    )),
                );
                let to = self.types.elem(unsigned_of(b));
                self.coercions.insert(i, to);
            } else if !self.types.is_integer(it) {
                let span = self.ast.expr(i).span;
                let msg = format!("an array index must be an integer, not {}", self.tname(it));
                self.emit(Diagnostic::new(Code::E0205, span, msg).with_label("not an integer"));
                ok = false;
                continue;
            }
            if let (Some((lo, hi)), Some(Value::Int(v))) =
                (dims.get(k), self.prop_value(i).as_ref())
            {
                if v < lo || v > hi {
                    let span = self.ast.expr(i).span;
                    let msg = format!("index {v} is out of the bounds {lo}..{hi}");
                    self.emit(Diagnostic::new(Code::E0701, span, msg).with_label("out of bounds"));
                    ok = false;
                }
            }
        }
        if indices.len() > dims.len() {
            let span = self.ast.expr(indices[dims.len()]).span;
            let msg = format!(
                "too many indices: the array has {} dimension(s)",
                dims.len()
            );
            self.emit(Diagnostic::new(Code::E0206, span, msg));
            return TypeId::ERROR;
        }
        if !ok {
            return TypeId::ERROR;
        }
        if indices.len() < dims.len() {
            if !partial_ok {
                let span = self.ast.expr(e).span;
                let msg = format!("too few indices: the array has {} dimensions", dims.len());
                self.emit(
                    Diagnostic::new(Code::E0206, span, msg)
                        .with_help("give one index per dimension: `a[i, j]`"),
                );
                return TypeId::ERROR;
            }
            // `a[i]` of `a[i][j]`: the rest of the dimensions.
            let rest = dims[indices.len()..].to_vec();
            return self
                .types
                .add(TypeKind::Array { dims: rest, elem }, None, None);
        }
        elem
    }

    // ----- operators ----------------------------------------------------------

    fn unary(
        &mut self,
        e: ExprId,
        op: UnaryOp,
        operand: ExprId,
        expected: Option<TypeId>,
        scope: Scope,
    ) -> TypeId {
        let span = self.ast.expr(e).span;
        if op == UnaryOp::Neg {
            if let ExprKind::Literal(l) = &self.ast.expr(operand).kind {
                if l.prefix.is_none() && matches!(l.value, LitValue::Int { .. } | LitValue::Real(_))
                {
                    // A negative literal is one literal, range-checked as a whole.
                    let t = self.literal(e, l, expected, span, true);
                    self.set_type(operand, t);
                    return t;
                }
            }
        }
        let hint = expected.filter(|t| self.types.numeric(*t).is_some());
        let t = self.check_expr(operand, hint, scope);
        if t == TypeId::ERROR {
            return t;
        }
        let Some(s) = self.types.numeric(t) else {
            return self.bad_unary(op, t, span);
        };
        let ok = match op {
            UnaryOp::Neg | UnaryOp::Plus => {
                stc_values::in_family(stc_syntax::token::GenericType::AnyNum, s)
                    || matches!(s, ElemType::Time | ElemType::Ltime)
            }
            UnaryOp::Not => stc_values::is_bit_string(s),
        };
        if !ok {
            return self.bad_unary(op, t, span);
        }
        let t = self.types.elem(s);
        if let Some(v) = self.consts.get(&operand).cloned() {
            let folded = match op {
                UnaryOp::Plus => Ok(stc_values::Outcome {
                    value: v,
                    overflow: false,
                }),
                UnaryOp::Neg => stc_values::unary(UnOp::Neg, s, &v),
                UnaryOp::Not => stc_values::unary(UnOp::Not, s, &v),
            };
            self.record_fold(e, folded, span, None);
        }
        t
    }

    fn bad_unary(&mut self, op: UnaryOp, t: TypeId, span: Span) -> TypeId {
        let (sym, need) = match op {
            UnaryOp::Neg => ("-", "a number or a duration"),
            UnaryOp::Plus => ("+", "a number or a duration"),
            UnaryOp::Not => ("NOT", "BOOL or a bit string"),
        };
        let msg = format!("`{sym}` needs {need}, not {}", self.tname(t));
        self.emit(Diagnostic::new(Code::E0201, span, msg));
        TypeId::ERROR
    }

    /// Records a folded constant (or the fold's problem).
    pub(crate) fn record_fold(
        &mut self,
        e: ExprId,
        r: Result<stc_values::Outcome, stc_values::Fault>,
        span: Span,
        divisor: Option<Span>,
    ) {
        match r {
            Ok(o) => {
                if o.overflow {
                    let msg = "integer overflow in a constant expression: the value wraps around"
                        .to_string();
                    self.emit(
                        Diagnostic::new(Code::W0107, span, msg)
                            .with_label(format!("this wraps around to {}", show_value(&o.value))),
                    );
                }
                self.consts.insert(e, o.value);
            }
            Err(stc_values::Fault::DivisionByZero) => {
                let at = divisor.unwrap_or(span);
                self.emit(
                    Diagnostic::new(Code::E0703, at, "division by zero").with_label("this is zero"),
                );
            }
            Err(_) => {}
        }
    }

    pub(crate) fn binary(
        &mut self,
        e: ExprId,
        op: BinaryOp,
        l: ExprId,
        r: ExprId,
        expected: Option<TypeId>,
        scope: Scope,
    ) -> TypeId {
        let span = self.ast.expr(e).span;
        let cmp = matches!(
            op,
            BinaryOp::Eq | BinaryOp::Ne | BinaryOp::Lt | BinaryOp::Le | BinaryOp::Gt | BinaryOp::Ge
        );
        // What the operands are told to expect.
        let outer = if cmp {
            None
        } else {
            expected.filter(|t| self.types.scalar(*t).is_some())
        };
        let lf = self.is_flexible(l, scope);
        let rf = self.is_flexible(r, scope);
        let (lt, rt) = if op == BinaryOp::Pow {
            let base_hint = match outer.and_then(|t| self.types.numeric(t)) {
                Some(ElemType::Real) => Some(self.types.elem(ElemType::Real)),
                _ => Some(self.types.elem(ElemType::Lreal)),
            };
            let lt = self.check_expr(l, if lf { base_hint } else { None }, scope);
            let rt = self.check_expr(r, None, scope);
            (lt, rt)
        } else if !lf || rf {
            let lt = self.check_expr(l, outer, scope);
            let mut hint = self.operand_hint(op, lt).or(outer);
            if !lf {
                hint = self.fitting_hint(r, hint);
            }
            let rt = self.check_expr(r, hint, scope);
            (lt, rt)
        } else {
            let rt = self.check_expr(r, outer, scope);
            let hint = self.operand_hint(op, rt).or(outer);
            let hint = self.fitting_hint(l, hint);
            let lt = self.check_expr(l, hint, scope);
            (lt, rt)
        };
        if lt == TypeId::ERROR || rt == TypeId::ERROR {
            return if cmp {
                self.types.elem(ElemType::Bool)
            } else {
                TypeId::ERROR
            };
        }
        // `itf = inst`: whether the interface value refers to the instance.
        if matches!(op, BinaryOp::Eq | BinaryOp::Ne) {
            for (itf_t, e, et) in [(lt, r, rt), (rt, l, lt)] {
                if self.interface_of(itf_t).is_some()
                    && matches!(self.types.kind(et), TypeKind::Fb(_))
                {
                    if self
                        .instance_as_interface(e, et, itf_t, "an interface value")
                        .is_none()
                    {
                        self.instance_as_value(e, et);
                    }
                    return self.types.elem(ElemType::Bool);
                }
            }
        }
        if self.instance_as_value(l, lt) || self.instance_as_value(r, rt) {
            return if cmp {
                self.types.elem(ElemType::Bool)
            } else {
                TypeId::ERROR
            };
        }
        let lptr = matches!(self.types.kind(lt), TypeKind::Ptr(_));
        let rptr = matches!(self.types.kind(rt), TypeKind::Ptr(_));
        if lptr || rptr {
            return self.ptr_binary(op, (l, lt), (r, rt), span);
        }
        let lref = matches!(self.types.kind(lt), TypeKind::Ref(_));
        let rref = matches!(self.types.kind(rt), TypeKind::Ref(_));
        if lref || rref {
            return self.ref_binary(op, lt, rt, span);
        }
        let Some((result, operand)) = self.binary_types(e, op, l, lt, r, rt, span) else {
            // Reported: not even a comparison's BOOL result is known, so a
            // chain `a >= b <= c` gives one diagnostic.
            return TypeId::ERROR;
        };
        // Folding, and the static division-by-zero check.
        let (ls, rs) = (self.types.scalar(lt), self.types.scalar(rt));
        let rspan = self.ast.expr(r).span;
        if matches!(op, BinaryOp::Div | BinaryOp::Mod) {
            if let Some(Value::Int(0)) = self.prop_value(r) {
                if rs.is_some_and(|t| !stc_values::is_real(t)) {
                    self.emit(
                        Diagnostic::new(Code::E0703, rspan, "division by zero")
                            .with_label("this is zero"),
                    );
                    return TypeId::ERROR;
                }
            }
        }
        if let (Some(lv), Some(rv), Some(ls), Some(rs), Some(res)) = (
            self.consts.get(&l).cloned(),
            self.consts.get(&r).cloned(),
            ls,
            rs,
            self.types.scalar(result),
        ) {
            let (lv, lty) = match operand {
                Some(o) if o != ls => (stc_values::convert(ls, o, &lv).ok(), o),
                _ => (Some(lv), ls),
            };
            let (rv, rty) = match operand {
                Some(o) if o != rs && op != BinaryOp::Pow => {
                    (stc_values::convert(rs, o, &rv).ok(), o)
                }
                _ => (Some(rv), rs),
            };
            if let (Some(lv), Some(rv)) = (lv, rv) {
                let r = stc_values::binary(bin_op(op), lty, &lv, rty, &rv, res);
                self.record_fold(e, r, span, Some(rspan));
            }
        }
        result
    }

    /// The hint a flexible operand takes from the other operand's type, or
    /// none when the literal does not fit that type: `a * 60000` with `a`
    /// an INT is then a DINT multiplication (the literal's own type, and
    /// the usual implicit widening), not an out-of-range INT literal.
    pub(crate) fn fitting_hint(&self, e: ExprId, hint: Option<TypeId>) -> Option<TypeId> {
        let t = hint?;
        let Some(s) = self.types.numeric(t) else {
            return hint;
        };
        // The literal's own type, when it does not fit the hint and a common
        // type with it exists (BYTE and DINT have none: then the hint stays
        // and the literal is out of its range, E0303).
        let own = match flexible_value(self.ast, e) {
            Some(FlexValue::Int(v))
                if stc_values::is_integer(s) || stc_values::is_bit_string(s) =>
            {
                let (min, max) = stc_values::int_range(s).unwrap_or((0, 0));
                if s == ElemType::Bool || (min..=max).contains(&v) {
                    return hint;
                }
                if i32::try_from(v).is_ok() {
                    ElemType::Dint
                } else if i64::try_from(v).is_ok() {
                    ElemType::Lint
                } else {
                    ElemType::Ulint
                }
            }
            Some(FlexValue::Real(x)) if s == ElemType::Real && (x as f32).is_infinite() => {
                ElemType::Lreal
            }
            _ => return hint,
        };
        match stc_values::common_type(s, own) {
            Some(_) => None,
            None => hint,
        }
    }

    /// The type the other operand should take when one operand has type `t`.
    fn operand_hint(&self, op: BinaryOp, t: TypeId) -> Option<TypeId> {
        if t == TypeId::ERROR {
            return Some(TypeId::ERROR);
        }
        let s = self.types.scalar(t)?;
        if stc_values::is_time_like(s) {
            return match op {
                BinaryOp::Mul | BinaryOp::Div => None,
                BinaryOp::Add | BinaryOp::Sub if matches!(s, ElemType::Tod | ElemType::Dt) => None,
                BinaryOp::Add | BinaryOp::Sub if matches!(s, ElemType::Ltod | ElemType::Ldt) => {
                    None
                }
                _ => Some(t),
            };
        }
        Some(t)
    }

    /// The result type of `lt op rt`, and the common operand type (with the
    /// implicit conversions recorded), or `None` after reporting E0201.
    #[allow(clippy::too_many_arguments)]
    fn binary_types(
        &mut self,
        e: ExprId,
        op: BinaryOp,
        l: ExprId,
        lt: TypeId,
        r: ExprId,
        rt: TypeId,
        span: Span,
    ) -> Option<(TypeId, Option<ElemType>)> {
        use ElemType as E;
        let bool_ty = self.types.elem(E::Bool);
        let ls = self.types.scalar(lt);
        let enums = matches!(self.types.kind(lt), TypeKind::Enum { .. })
            || matches!(self.types.kind(rt), TypeKind::Enum { .. });
        let fail = |s: &mut Self| {
            let msg = format!(
                "`{}` cannot be applied to {} and {}",
                op.symbol(),
                s.tname(lt),
                s.tname(rt)
            );
            s.emit(Diagnostic::new(Code::E0201, span, msg).with_label(format!(
                "{} {} {}",
                s.tname(lt),
                op.symbol(),
                s.tname(rt)
            )));
            None
        };
        match op {
            BinaryOp::Eq
            | BinaryOp::Ne
            | BinaryOp::Lt
            | BinaryOp::Le
            | BinaryOp::Gt
            | BinaryOp::Ge => {
                if enums {
                    if lt == rt && matches!(op, BinaryOp::Eq | BinaryOp::Ne) {
                        return Some((bool_ty, ls));
                    }
                    return fail(self);
                }
                match (self.types.kind(lt).clone(), self.types.kind(rt).clone()) {
                    (TypeKind::String { wide: a, .. }, TypeKind::String { wide: b, .. })
                        if a == b =>
                    {
                        return Some((bool_ty, ls));
                    }
                    _ => {}
                }
                let (Some(a), Some(b)) = (self.types.numeric(lt), self.types.numeric(rt)) else {
                    return fail(self);
                };
                let Some(c) = self.unify(l, a, r, b) else {
                    return fail(self);
                };
                Some((bool_ty, Some(c)))
            }
            _ if enums => fail(self),
            BinaryOp::And | BinaryOp::Or | BinaryOp::Xor => {
                let (Some(a), Some(b)) = (self.types.numeric(lt), self.types.numeric(rt)) else {
                    return fail(self);
                };
                if !stc_values::is_bit_string(a) || !stc_values::is_bit_string(b) {
                    return fail(self);
                }
                let Some(c) = self.unify(l, a, r, b) else {
                    return fail(self);
                };
                Some((self.types.elem(c), Some(c)))
            }
            BinaryOp::Pow => {
                let (Some(a), Some(b)) = (self.types.numeric(lt), self.types.numeric(rt)) else {
                    return fail(self);
                };
                if !stc_values::is_real(a) {
                    let lspan = self.ast.expr(l).span;
                    let msg = format!(
                        "the base of `**` must be REAL or LREAL, not {}",
                        self.tname(lt)
                    );
                    self.emit(Diagnostic::new(Code::E0201, lspan, msg).with_help(format!(
                        "convert it, for example with {}_TO_LREAL(...)",
                        a.name()
                    )));
                    return None;
                }
                if !stc_values::in_family(stc_syntax::token::GenericType::AnyNum, b) {
                    return fail(self);
                }
                Some((self.types.elem(a), Some(a)))
            }
            _ => {
                let (Some(a), Some(b)) = (self.types.numeric(lt), self.types.numeric(rt)) else {
                    return fail(self);
                };
                let num = |t: E| stc_values::in_family(stc_syntax::token::GenericType::AnyNum, t);
                if num(a) && num(b) {
                    if op == BinaryOp::Mod
                        && (!stc_values::is_integer(a) || !stc_values::is_integer(b))
                    {
                        return fail(self);
                    }
                    let Some(c) = self.unify(l, a, r, b) else {
                        return fail(self);
                    };
                    return Some((self.types.elem(c), Some(c)));
                }
                if let Some(c) = self.bit_arith(e, l, a, r, b, span) {
                    return Some((self.types.elem(c), Some(c)));
                }
                // Time arithmetic.
                let res = match (op, a, b) {
                    (BinaryOp::Add | BinaryOp::Sub, E::Time, E::Time) => E::Time,
                    (BinaryOp::Add | BinaryOp::Sub, E::Ltime, E::Ltime) => E::Ltime,
                    (BinaryOp::Add | BinaryOp::Sub, E::Tod, E::Time) => E::Tod,
                    (BinaryOp::Add | BinaryOp::Sub, E::Ltod, E::Ltime) => E::Ltod,
                    (BinaryOp::Add | BinaryOp::Sub, E::Dt, E::Time) => E::Dt,
                    (BinaryOp::Add | BinaryOp::Sub, E::Ldt, E::Ltime) => E::Ldt,
                    (BinaryOp::Sub, E::Date, E::Date)
                    | (BinaryOp::Sub, E::Tod, E::Tod)
                    | (BinaryOp::Sub, E::Dt, E::Dt) => E::Time,
                    (BinaryOp::Sub, E::Ldate, E::Ldate)
                    | (BinaryOp::Sub, E::Ltod, E::Ltod)
                    | (BinaryOp::Sub, E::Ldt, E::Ldt) => E::Ltime,
                    (BinaryOp::Mul | BinaryOp::Div, E::Time | E::Ltime, n) if num(n) => a,
                    (BinaryOp::Mul, n, E::Time | E::Ltime) if num(n) => b,
                    _ => return fail(self),
                };
                Some((self.types.elem(res), None))
            }
        }
    }

    /// Arithmetic with a bit string operand (BYTE, WORD, DWORD, LWORD), as
    /// CODESYS allows it: accepted with W0113 (an error under `--std
    /// iec2`), computed unsigned in the bit string of the wider operand's
    /// width, the other operand converted to it. `None` when the operands
    /// are not a bit string and a bit string or integer.
    fn bit_arith(
        &mut self,
        e: ExprId,
        l: ExprId,
        a: ElemType,
        r: ExprId,
        b: ElemType,
        span: Span,
    ) -> Option<ElemType> {
        use ElemType as E;
        let bits = |t: ElemType| stc_values::is_bit_string(t) && t != E::Bool;
        let operand = |t: ElemType| bits(t) || stc_values::is_integer(t) || stc_values::is_real(t);
        if !(bits(a) || bits(b)) || !operand(a) || !operand(b) || self.opts.iec2 {
            return None;
        }
        let c = if stc_values::is_real(a) || stc_values::is_real(b) {
            // With a REAL or LREAL: the bit string's unsigned value in it.
            if op_is_mod(self.ast, e) {
                return None;
            }
            if stc_values::is_real(a) {
                a
            } else {
                b
            }
        } else {
            match stc_values::bits(a).max(stc_values::bits(b)) {
                8 => E::Byte,
                16 => E::Word,
                32 => E::Dword,
                _ => E::Lword,
            }
        };
        for (e, t) in [(l, a), (r, b)] {
            if t != c {
                let ct = self.types.elem(c);
                self.coercions.insert(e, ct);
            }
        }
        for o in [l, r] {
            let mut o = o;
            while let ExprKind::Paren(inner) = self.ast.expr(o).kind {
                o = inner;
            }
            if let Some(&i) = self.bit_arith.get(&o) {
                self.dropped.insert(i);
            }
        }
        self.bit_arith.insert(e, self.diags.len());
        self.emit(
            Diagnostic::new(
                Code::W0113,
                span,
                if stc_values::is_real(c) {
                    format!(
                        "arithmetic on a bit string: its unsigned value as a {}",
                        c.name()
                    )
                } else {
                    format!(
                        "arithmetic on a bit string: computed as an unsigned {}",
                        c.name()
                    )
                },
            )
            .with_label(format!("{} and {}", a.name(), b.name()))
            .with_help(if stc_values::is_real(c) {
                let b = if bits(a) { a } else { b };
                format!(
                    "the standard allows arithmetic only on numbers: convert with {}_TO_{}(...)",
                    b.name(),
                    c.name()
                )
            } else {
                format!(
                    "the standard allows arithmetic only on numbers: convert with {}_TO_{}(...)",
                    c.name(),
                    unsigned_of(c).name()
                )
            }),
        );
        Some(c)
    }

    /// The common type of two operands, recording the implicit conversions;
    /// under `--std iec2` mixing types is an error (E0302, once).
    fn unify(&mut self, l: ExprId, a: ElemType, r: ExprId, b: ElemType) -> Option<ElemType> {
        if a == b {
            return Some(a);
        }
        let c = stc_values::common_type(a, b)?;
        for (e, t) in [(l, a), (r, b)] {
            if t != c {
                if self.opts.iec2 {
                    let span = self.ast.expr(e).span;
                    let msg = format!(
                        "implicit conversion from {} to {} is not allowed with --std iec2",
                        t.name(),
                        c.name()
                    );
                    self.emit(Diagnostic::new(Code::E0302, span, msg).with_help(format!(
                        "use {}_TO_{}(...)",
                        t.name(),
                        c.name()
                    )));
                    // Reported: the operation itself is typed as if the
                    // conversion were there, so nothing more is said.
                    return Some(c);
                }
                let ct = self.types.elem(c);
                self.coercions.insert(e, ct);
            }
        }
        Some(c)
    }

    // ----- conversions ----------------------------------------------------------

    /// Checks that a value of type `from` may be stored where `to` is
    /// expected, recording an implicit conversion. `what` describes the
    /// target for messages.
    pub(crate) fn coerce(
        &mut self,
        e: ExprId,
        from: TypeId,
        to: TypeId,
        ctx: Ctx,
        what: &str,
    ) -> bool {
        let span = self.ast.expr(e).span;
        if let Some(ok) = self.instance_as_interface(e, from, to, what) {
            return ok;
        }
        if from != to && self.instance_as_value(e, from) {
            return false;
        }
        if let Some(ok) = self.coerce_ptr(e, from, to, what) {
            return ok;
        }
        let refs = matches!(self.types.kind(from), TypeKind::Ref(_))
            || matches!(self.types.kind(to), TypeKind::Ref(_));
        match self.types.compat(from, to, self.opts.iec2) {
            Compat::Same => true,
            Compat::Incompatible if refs => {
                let (f, t) = (self.tname(from), self.tname(to));
                let d = Diagnostic::new(
                    Code::E1304,
                    span,
                    format!("{what} of type {t} cannot take a value of type {f}"),
                )
                .with_label(format!("this is {f}"))
                .with_help(
                    "a reference holds `NULL` or `REF(x)` of a variable `x` of exactly its target type",
                );
                self.emit(d);
                false
            }
            Compat::Widen => {
                self.coercions.insert(e, to);
                true
            }
            Compat::Narrow if self.dialect_int_conversion(from, to) => {
                self.dialect_conversion_warning(span, from, to);
                self.coercions.insert(e, to);
                true
            }
            Compat::Narrow => {
                let (f, t) = (self.tname(from), self.tname(to));
                let code = if ctx == Ctx::Init {
                    Code::E0208
                } else {
                    Code::E0302
                };
                let msg = match self.narrowing(from, to) {
                    Narrowing::Iec2 => format!(
                        "implicit conversion from {f} to {t} is not allowed with --std iec2"
                    ),
                    Narrowing::Family => format!(
                        "no implicit conversion from {f} to {t}: bit strings and numbers convert only explicitly"
                    ),
                    Narrowing::Loses => {
                        format!("implicit conversion from {f} to {t} may lose information")
                    }
                };
                let mut d = Diagnostic::new(code, span, msg).with_label(format!("this is {f}"));
                if let (Some(a), Some(b)) = (self.types.numeric(from), self.types.numeric(to)) {
                    d = d.with_help(format!(
                        "convert explicitly with {}_TO_{}(...)",
                        a.name(),
                        b.name()
                    ));
                }
                self.emit(d);
                false
            }
            Compat::Incompatible => {
                let (f, t) = (self.tname(from), self.tname(to));
                let (code, msg) = match ctx {
                    Ctx::Assign => (
                        Code::E0301,
                        format!("cannot assign a value of type {f} to {what} of type {t}"),
                    ),
                    Ctx::Init => (
                        Code::E0208,
                        format!("a value of type {f} cannot initialise {what} of type {t}"),
                    ),
                    Ctx::Arg => (Code::E0407, format!("{what} expects {t}, not {f}")),
                };
                let mut d = Diagnostic::new(code, span, msg).with_label(format!("this is {f}"));
                let literal = match &self.ast.expr(e).kind {
                    ExprKind::Literal(Literal {
                        value: LitValue::Int { value, negative },
                        prefix: None,
                    }) => Some((*value, *negative)),
                    _ => None,
                };
                let to_elem = self.types.scalar(to);
                match (literal, to_elem) {
                    // `PT := 1000`: a duration is written as a TIME literal.
                    (Some((n, false)), Some(ElemType::Time | ElemType::Ltime)) => {
                        let prefix = if to_elem == Some(ElemType::Ltime) {
                            "LTIME"
                        } else {
                            "T"
                        };
                        let text = if n != 0 && n % 1000 == 0 {
                            format!("{prefix}#{}s", n / 1000)
                        } else {
                            format!("{prefix}#{n}ms")
                        };
                        d = d.with_help(format!(
                            "a duration is written as a time literal: `{text}` if {n} means milliseconds"
                        ));
                    }
                    _ => {
                        if let (Some(a), Some(b)) = (self.types.scalar(from), to_elem) {
                            let name = format!("{}_TO_{}", a.name(), b.name());
                            if stc_values::lookup(&name).is_some() {
                                d = d.with_help(format!("use {name}(...) to convert explicitly"));
                            }
                        }
                    }
                }
                self.emit(d);
                false
            }
        }
    }

    /// Whether a narrowing conversion is one CODESYS makes implicitly and
    /// stc accepts with W0118: between integers and bit strings (not BOOL),
    /// outside `--std iec2`.
    pub(crate) fn dialect_int_conversion(&self, from: TypeId, to: TypeId) -> bool {
        let int_or_bits = |t: TypeId| {
            self.types.numeric(t).is_some_and(|e| {
                e != ElemType::Bool && (stc_values::is_integer(e) || stc_values::is_bit_string(e))
            })
        };
        !self.opts.iec2 && int_or_bits(from) && int_or_bits(to)
    }

    /// W0118 for the conversion from `from` to `to` at `span`.
    pub(crate) fn dialect_conversion_warning(&mut self, span: Span, from: TypeId, to: TypeId) {
        let (f, t) = (self.tname(from), self.tname(to));
        let mut d = Diagnostic::new(
            Code::W0118,
            span,
            format!("implicit conversion from {f} to {t}, as CODESYS converts"),
        )
        .with_label(format!("this is {f}"));
        if let (Some(a), Some(b)) = (self.types.numeric(from), self.types.numeric(to)) {
            d = d.with_help(format!(
                "write {}_TO_{}(...) if the conversion is meant",
                a.name(),
                b.name()
            ));
        }
        self.emit(d);
    }

    /// Why a conversion that [`crate::types::TypeTable::compat`] calls
    /// narrowing is not implicit.
    pub(crate) fn narrowing(&self, from: TypeId, to: TypeId) -> Narrowing {
        let (Some(a), Some(b)) = (self.types.numeric(from), self.types.numeric(to)) else {
            return Narrowing::Loses;
        };
        if stc_values::implicit_widening(a, b) {
            return Narrowing::Iec2;
        }
        if lossless(a, b) {
            Narrowing::Family
        } else {
            Narrowing::Loses
        }
    }

    pub(crate) fn coerce_init(&mut self, e: ExprId, from: TypeId, to: TypeId) -> bool {
        self.coerce(e, from, to, Ctx::Init, "a variable")
    }

    /// E0409: a function block instance where a value is needed.
    /// Whether `to` is an interface type (a reference to an INTERFACE),
    /// and which interface.
    pub(crate) fn interface_of(&self, to: TypeId) -> Option<PouId> {
        let target = self.types.ref_target(to)?;
        match *self.types.kind(target) {
            TypeKind::Fb(i)
                if self.pous[i.0 as usize].class == Some(stc_syntax::ast::ClassKind::Interface) =>
            {
                Some(i)
            }
            _ => None,
        }
    }

    /// An instance where an interface value is expected (`itf := inst`):
    /// the reference to it, when its type implements the interface (E1326)
    /// and it lives as long as the program (E1303). `None`: not that case.
    fn instance_as_interface(
        &mut self,
        e: ExprId,
        from: TypeId,
        to: TypeId,
        what: &str,
    ) -> Option<bool> {
        let i = self.interface_of(to)?;
        let TypeKind::Fb(d) = *self.types.kind(from) else {
            return None;
        };
        if !self.types.is_subtype(d, i) {
            let it = self.pou_type(i);
            let (f, t) = (self.tname(from), self.tname(it));
            let decl = self.pous[d.0 as usize].name_span;
            self.emit(
                Diagnostic::new(
                    Code::E1326,
                    self.ast.expr(e).span,
                    format!("{what} of interface {t} cannot refer to an instance of {f}"),
                )
                .with_label(format!("{f} does not implement {t}"))
                .with_secondary(decl, format!("{f} declared here")),
            );
            return Some(false);
        }
        let p = self.body.current?;
        if self.ref_of_checked(e, from, Scope::Pou(p)) == TypeId::ERROR {
            return Some(false);
        }
        self.coercions.insert(e, to);
        Some(true)
    }

    pub(crate) fn instance_as_value(&mut self, e: ExprId, t: TypeId) -> bool {
        if !matches!(self.types.kind(t), TypeKind::Fb(_)) {
            return false;
        }
        let span = self.ast.expr(e).span;
        self.emit(
            Diagnostic::new(
                Code::E0409,
                span,
                "a function block instance is not a value",
            )
            .with_label("function block instance")
            .with_help("read one of its outputs, for example `inst.Q`"),
        );
        true
    }

    /// A constant of type `from` as a value of type `to` (after an implicit
    /// conversion).
    pub(crate) fn convert_const(&self, v: &Value, from: TypeId, to: TypeId) -> Option<Value> {
        match (self.types.scalar(from), self.types.scalar(to)) {
            (Some(a), Some(b))
                if a != b && !matches!(self.types.kind(to), TypeKind::Enum { .. }) =>
            {
                stc_values::convert(a, b, v).ok()
            }
            _ => Some(v.clone()),
        }
    }

    /// E0702: a constant outside the subrange it is stored in.
    pub(crate) fn check_subrange(&mut self, v: &Option<Value>, ty: TypeId, span: Span) -> bool {
        if let (TypeKind::Subrange { lo, hi, .. }, Some(Value::Int(x))) = (self.types.kind(ty), v) {
            if x < lo || x > hi {
                let msg = format!(
                    "{x} is outside the subrange {lo}..{hi} of {}",
                    self.tname(ty)
                );
                self.emit(
                    Diagnostic::new(Code::E0702, span, msg).with_label("out of the subrange"),
                );
                return false;
            }
        }
        true
    }
}

/// Why an implicit conversion is refused (E0302), which decides its words.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
pub(crate) enum Narrowing {
    /// A widening, refused only because `--std iec2` has none.
    Iec2,
    /// Nothing can be lost, but bit strings and numbers never convert
    /// implicitly (BYTE to INT, UINT to WORD).
    Family,
    /// Some values of the source type do not exist in the target.
    Loses,
}

/// Whether every value of `a` is exactly a value of `b` (integers and bit
/// strings by range, and into a real type if its mantissa holds them).
fn lossless(a: ElemType, b: ElemType) -> bool {
    let Some((lo, hi)) = stc_values::int_range(a).filter(|_| a != ElemType::Bool) else {
        return a == ElemType::Real && b == ElemType::Lreal;
    };
    if let Some((l2, h2)) = stc_values::int_range(b) {
        return b != ElemType::Bool && l2 <= lo && hi <= h2;
    }
    let mantissa: u32 = match b {
        ElemType::Real => 24,
        ElemType::Lreal => 53,
        _ => return false,
    };
    let limit = 1i128 << mantissa;
    -limit <= lo && hi <= limit
}

/// The value of a flexible numeric literal, possibly negated or in
/// parentheses, without checking it.
enum FlexValue {
    Int(i128),
    Real(f64),
}

fn flexible_value(ast: &stc_syntax::ast::Ast, e: ExprId) -> Option<FlexValue> {
    match &ast.expr(e).kind {
        ExprKind::Literal(Literal {
            value: LitValue::Int { value, negative },
            prefix: None,
        }) => {
            let v = *value as i128;
            Some(FlexValue::Int(if *negative { -v } else { v }))
        }
        ExprKind::Literal(Literal {
            value: LitValue::Real(x),
            prefix: None,
        }) => Some(FlexValue::Real(*x)),
        ExprKind::Paren(i)
        | ExprKind::Unary {
            op: UnaryOp::Plus,
            operand: i,
        } => flexible_value(ast, *i),
        ExprKind::Unary {
            op: UnaryOp::Neg,
            operand,
        } => match flexible_value(ast, *operand)? {
            FlexValue::Int(v) => Some(FlexValue::Int(-v)),
            FlexValue::Real(x) => Some(FlexValue::Real(-x)),
        },
        _ => None,
    }
}

pub(crate) fn bin_op(op: BinaryOp) -> BinOp {
    match op {
        BinaryOp::Or => BinOp::Or,
        BinaryOp::Xor => BinOp::Xor,
        BinaryOp::And => BinOp::And,
        BinaryOp::Eq => BinOp::Eq,
        BinaryOp::Ne => BinOp::Ne,
        BinaryOp::Lt => BinOp::Lt,
        BinaryOp::Le => BinOp::Le,
        BinaryOp::Gt => BinOp::Gt,
        BinaryOp::Ge => BinOp::Ge,
        BinaryOp::Add => BinOp::Add,
        BinaryOp::Sub => BinOp::Sub,
        BinaryOp::Mul => BinOp::Mul,
        BinaryOp::Div => BinOp::Div,
        BinaryOp::Mod => BinOp::Mod,
        BinaryOp::Pow => BinOp::Pow,
    }
}

pub(crate) fn show_value(v: &Value) -> String {
    match v {
        Value::Bool(b) => if *b { "TRUE" } else { "FALSE" }.into(),
        Value::Int(i) => i.to_string(),
        Value::Real(r) => stc_syntax::literal::format_real(*r),
        Value::Str(s) => format!("'{}'", stc_values::string_text(s)),
        Value::WStr(s) => format!("\"{}\"", String::from_utf16_lossy(s)),
    }
}

/// The unsigned integer type of a bit string's width (BYTE: USINT...).
fn unsigned_of(b: ElemType) -> ElemType {
    match stc_values::bits(b) {
        8 => ElemType::Usint,
        16 => ElemType::Uint,
        32 => ElemType::Udint,
        _ => ElemType::Ulint,
    }
}

/// Whether expression `e` is a `MOD`.
fn op_is_mod(ast: &stc_syntax::ast::Ast, e: ExprId) -> bool {
    matches!(
        ast.expr(e).kind,
        ExprKind::Binary {
            op: BinaryOp::Mod,
            ..
        }
    )
}
