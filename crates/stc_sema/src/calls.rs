//! Calls: user functions, function block instances and standard functions.
//!
//! Arguments are bound to parameters (formal `name := x`, `name => y`, or
//! positional), checked against the parameter types, and recorded in a
//! [`CallInfo`]. Standard functions are typed from the signature table of
//! `stc_values`: type variables (ANY_NUM, ANY_BIT...) are bound by the
//! arguments that have their own type, then given to the literals and enum
//! values, then to the result (from the context when no argument binds it,
//! as TRUNC's integer result).

use stc_diagnostics::{Code, Diagnostic, Span};
use stc_syntax::ast::{Arg, ArgKind, BinaryOp, ExprId, ExprKind, PouKind};
use stc_syntax::token::{ElemType, GenericType};
use stc_values::{Intrinsic, StdFunction, TyPat, Value};

use crate::analyzer::{GlobalName, Scope, Sema};
use crate::expr::Ctx;
use crate::types::{TypeId, TypeKind};
use crate::{BoundArg, BoundArgKind, CallInfo, CallTarget, PouId, Res, Section};

/// How an lvalue is being written, which decides the code of a non-variable.
#[derive(Clone, Copy, PartialEq, Eq)]
pub(crate) enum Write {
    Assign,
    Output,
    InOut,
}

fn arg_value(a: &Arg) -> ExprId {
    match &a.kind {
        ArgKind::Positional(v) | ArgKind::Input { value: v, .. } => *v,
        ArgKind::Output { target, .. } => *target,
    }
}

impl<'a> Sema<'a> {
    /// Checks the arguments of a call whose callee is not known, for their
    /// own errors only.
    /// The one positional argument of an operator-like call (`REF`,
    /// `ADR`, `SIZEOF`); otherwise `code` at `span` with `msg` and
    /// `label`, and the arguments checked loose.
    pub(crate) fn one_argument(
        &mut self,
        args: &[Arg],
        scope: Scope,
        (code, span): (Code, Span),
        msg: &str,
        label: &str,
    ) -> Option<ExprId> {
        if let [Arg {
            kind: ArgKind::Positional(x),
            ..
        }] = args
        {
            return Some(*x);
        }
        self.emit(Diagnostic::new(code, span, msg).with_label(label));
        self.loose_args(args, scope);
        None
    }

    /// Reports a call that mixes formal (`name := value`) and positional
    /// arguments (E0404), checking its arguments alone; whether it did.
    pub(crate) fn mixed_args(&mut self, args: &[Arg], scope: Scope) -> bool {
        let formal = |a: &Arg| !matches!(a.kind, ArgKind::Positional(_));
        let Some(first) = args.first() else {
            return false;
        };
        let Some(odd) = args.iter().find(|a| formal(a) != formal(first)) else {
            return false;
        };
        self.emit(
            Diagnostic::new(
                Code::E0404,
                odd.span,
                "formal (`name := value`) and positional arguments cannot be mixed in one call",
            )
            .with_help("name every argument, or none"),
        );
        self.loose_args(args, scope);
        true
    }

    pub(crate) fn loose_args(&mut self, args: &[Arg], scope: Scope) {
        for a in args {
            self.check_expr(arg_value(a), Some(TypeId::ERROR), scope);
        }
    }

    pub(crate) fn call(
        &mut self,
        e: ExprId,
        callee: ExprId,
        args: &'a [Arg],
        expected: Option<TypeId>,
        scope: Scope,
        as_stmt: bool,
    ) -> TypeId {
        let span = self.ast.expr(e).span;
        let callee_span = self.ast.expr(callee).span;
        let named = match &self.ast.expr(callee).kind {
            ExprKind::Name(id) => Some(*id),
            ExprKind::Member { .. } => self.qualified_callee(callee, scope),
            _ => None,
        };
        if let Some(id) = named.as_ref() {
            // In call position a function block instance is called; any other
            // variable (a function's own result, `max : INT`) does not hide
            // the function of the same name.
            let is_var = match scope {
                Scope::Pou(p) => match self.pous[p.0 as usize].lookup(id.sym) {
                    Some(v) => {
                        self.ensure_var(p, v);
                        let var = self.pous[p.0 as usize].var(v);
                        let callable_elsewhere = self.is_global_name(*id)
                            || stc_values::lookup(self.interner.key(id.sym)).is_some();
                        let fb = matches!(self.types.kind(var.ty), TypeKind::Fb(_));
                        fb || var.ty == TypeId::ERROR || !callable_elsewhere
                    }
                    // In a METHOD: an instance of its function block.
                    None => self.pous[p.0 as usize]
                        .method_of
                        .is_some_and(|(fb, _)| self.pous[fb.0 as usize].lookup(id.sym).is_some()),
                },
                _ => false,
            };
            if !is_var {
                // A METHOD of the running instance's function block.
                if let Scope::Pou(p) = scope {
                    if let Some(m) = self
                        .own_instance(p)
                        .and_then(|fb| self.find_method(fb, id.sym))
                    {
                        return self.method_call(e, m, None, args, scope, span, id.span);
                    }
                }
                let shown = self.spelled(id.sym, id.span);
                match self.global_name(*id) {
                    Some(GlobalName::Pou(q)) => match self.pous[q.0 as usize].kind {
                        PouKind::Function => return self.function_call(e, q, args, scope, span),
                        PouKind::FunctionBlock => {
                            self.emit(
                                Diagnostic::new(Code::E0409, id.span, format!("`{shown}` is a function block type, not an instance"))
                                    .with_help(format!("declare an instance (`inst : {shown};`) and call it: `inst(...)`")),
                            );
                            self.loose_args(args, scope);
                            return TypeId::ERROR;
                        }
                        PouKind::Program => {
                            self.error(
                                Code::E0405,
                                id.span,
                                format!("`{shown}` is a program and cannot be called"),
                            );
                            self.loose_args(args, scope);
                            return TypeId::ERROR;
                        }
                    },
                    Some(GlobalName::Type(_)) | Some(GlobalName::Config(_)) => {
                        self.error(Code::E0405, id.span, format!("`{shown}` is not a function"));
                        self.loose_args(args, scope);
                        return TypeId::ERROR;
                    }
                    None => {}
                }
                let key = self.interner.key(id.sym).to_string();
                if key == "CUR_TIME" && args.is_empty() {
                    self.calls.insert(
                        e,
                        CallInfo {
                            target: CallTarget::CurTime,
                            args: Vec::new(),
                            en: None,
                            eno: None,
                        },
                    );
                    return self.types.elem(ElemType::Time);
                }
                if let Some(f) = stc_values::lookup(&key) {
                    return self.std_call(e, &f, args, expected, scope, span);
                }
                if let Some(split) = stc_values::split_lookup(&key) {
                    return self.split_call(e, &shown, split, args, scope, span, as_stmt);
                }
                if matches!(key.as_str(), "LOWER_BOUND" | "UPPER_BOUND") {
                    let upper = key == "UPPER_BOUND";
                    return self.bound_call(e, upper, &shown, args, scope, span);
                }
                if self.reserved_name(*id, "a function") {
                    self.loose_args(args, scope);
                    return TypeId::ERROR;
                }
                if key == "ADR" {
                    return self.adr_call(e, args, span, scope);
                }
                if key == "SIZEOF" {
                    return self.sizeof_call(e, args, expected, span, scope);
                }
                if key == "REF" {
                    // The 3rd-edition reference operator.
                    let Some(x) = self.one_argument(
                        args,
                        scope,
                        (Code::E1302, span),
                        "REF takes one argument: the variable it refers to",
                        "`REF(x)`",
                    ) else {
                        return TypeId::ERROR;
                    };
                    let x = &x;
                    let t = self.ref_of(*x, scope);
                    if t != TypeId::ERROR {
                        self.calls.insert(
                            e,
                            CallInfo {
                                target: CallTarget::Ref,
                                args: vec![BoundArg {
                                    param: 0,
                                    kind: BoundArgKind::Input(*x),
                                }],
                                en: None,
                                eno: None,
                            },
                        );
                    }
                    return t;
                }
                if self.unsupported_names.contains(&id.sym) {
                    // A POU reported as not supported (a generic function):
                    // its calls are not reported again.
                    self.loose_args(args, scope);
                    return TypeId::ERROR;
                }
                if let Scope::Pou(p) = scope {
                    if self.member_may_be_unsupported(p, id.sym) {
                        // An ACTION or METHOD of this POU (`Reset();`), or one
                        // it may inherit: reported at its declaration.
                        self.loose_args(args, scope);
                        return TypeId::ERROR;
                    }
                }
                let mut d =
                    Diagnostic::new(Code::E0103, id.span, format!("unknown function `{shown}`"))
                        .with_label("not a function or function block");
                let mut candidates: Vec<String> = self
                    .pous
                    .iter()
                    .filter(|p| p.kind != PouKind::Program)
                    .map(|p| self.sym_name(p.name))
                    .collect();
                candidates.extend(stc_values::all().iter().map(|f| f.name.to_string()));
                if let Some(s) = self.did_you_mean(&shown, candidates.iter().map(|s| s.as_str())) {
                    d = d.with_help(format!("did you mean `{s}`?"));
                }
                self.emit(d);
                self.loose_args(args, scope);
                return TypeId::ERROR;
            }
        }
        // `inst.m(...)`: a METHOD of the instance's function block.
        if let ExprKind::Member { base, member } = &self.ast.expr(callee).kind {
            let bt = self.check_expr(*base, None, scope);
            if bt == TypeId::ERROR {
                self.loose_args(args, scope);
                return TypeId::ERROR;
            }
            // (An interface value: its instance's method.)
            let receiver = self
                .interface_of(bt)
                .map(|i| self.pou_type(i))
                .unwrap_or(bt);
            if let TypeKind::Fb(fb) = *self.types.kind(receiver) {
                if let Some(m) = self.find_method(fb, member.sym) {
                    return self.method_call(e, m, Some(*base), args, scope, span, member.span);
                }
                let skipped = self.member_may_be_unsupported(fb, member.sym);
                if self.pous[fb.0 as usize].lookup(member.sym).is_none() && !skipped {
                    let shown = self.spelled(member.sym, member.span);
                    let fb_name = self.sym_name(self.pous[fb.0 as usize].name);
                    let mut d = Diagnostic::new(
                        Code::E1310,
                        member.span,
                        format!("`{fb_name}` has no method `{shown}`"),
                    )
                    .with_label("unknown method");
                    let names: Vec<String> = self.pous[fb.0 as usize]
                        .methods
                        .iter()
                        .map(|q| self.sym_name(self.pous[q.0 as usize].name))
                        .collect();
                    if let Some(s) = self.did_you_mean(&shown, names.iter().map(|s| s.as_str())) {
                        d = d.with_help(format!("did you mean `{s}`?"));
                    }
                    self.emit(d);
                    self.loose_args(args, scope);
                    return TypeId::ERROR;
                }
            }
        }
        // A variable (or member, element): it must be a function block instance.
        let t = self.check_expr(callee, None, scope);
        if t == TypeId::ERROR {
            self.loose_args(args, scope);
            return TypeId::ERROR;
        }
        let TypeKind::Fb(fb) = *self.types.kind(t) else {
            let msg = format!("a value of type {} cannot be called", self.tname(t));
            self.emit(
                Diagnostic::new(Code::E0405, callee_span, msg)
                    .with_label("not a function block instance"),
            );
            self.loose_args(args, scope);
            return TypeId::ERROR;
        };
        if self.pous[fb.0 as usize].class.is_some() {
            let msg = format!(
                "an instance of the CLASS `{}` has no body to call",
                self.tname(t)
            );
            self.emit(
                Diagnostic::new(Code::E0405, callee_span, msg)
                    .with_label("a CLASS instance")
                    .with_help("call one of its methods: `inst.m()`"),
            );
            self.loose_args(args, scope);
            return TypeId::ERROR;
        }
        if let Scope::Pou(p) = scope {
            if self.pous[p.0 as usize].kind == PouKind::Function {
                // A local instance is already E0501 at its declaration.
                let local_instance = self.root_var(callee).is_some_and(|v| {
                    !matches!(
                        self.pous[p.0 as usize].var(v).section,
                        Section::InOut | Section::External
                    )
                });
                // (A METHOD calls the instances of its function block.)
                let method = self.pous[p.0 as usize].method_of.is_some();
                if !local_instance && !method {
                    self.error(
                        Code::E0502,
                        callee_span,
                        "a FUNCTION cannot call a function block instance",
                    );
                }
            }
            self.call_edges.push((p, fb, callee_span));
        }
        let (bound, en, eno) = self.bind_args(fb, args, scope, callee_span);
        self.calls.insert(
            e,
            CallInfo {
                target: CallTarget::FbInstance(fb),
                args: bound,
                en,
                eno,
            },
        );
        if !as_stmt {
            self.emit(
                Diagnostic::new(Code::E0409, span, "a function block call has no value")
                    .with_help("call the instance as a statement and read its outputs (`inst.Q`)"),
            );
            return TypeId::ERROR;
        }
        TypeId::VOID
    }

    /// A call of METHOD `m` on the instance `this` (the running one for
    /// `None`).
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn method_call(
        &mut self,
        e: ExprId,
        m: PouId,
        this: Option<ExprId>,
        args: &'a [Arg],
        scope: Scope,
        span: Span,
        name_span: Span,
    ) -> TypeId {
        let (fb, _) = self.pous[m.0 as usize].method_of.unwrap_or((m, 0));
        let access = self.pous[m.0 as usize].access;
        let private = matches!(
            access,
            Some(stc_syntax::ast::Access::Private | stc_syntax::ast::Access::Protected)
        );
        // PROTECTED: also from the blocks derived from it.
        let protected = access == Some(stc_syntax::ast::Access::Protected);
        let inside = matches!(scope, Scope::Pou(p) if self.own_instance(p).is_some_and(|o| o == fb || protected && self.types.is_subtype(o, fb)));
        if access == Some(stc_syntax::ast::Access::Internal) && !self.in_namespace_of(fb, name_span)
        {
            let shown = self.sym_name(self.pous[m.0 as usize].name);
            let home = self.namespace_of(fb).unwrap_or_default();
            self.emit(
                Diagnostic::new(
                    Code::E1331,
                    name_span,
                    format!("the method `{shown}` is INTERNAL to namespace `{home}`"),
                )
                .with_secondary(self.pous[m.0 as usize].name_span, "declared here")
                .with_help("call it from inside the namespace, or declare it PUBLIC"),
            );
            self.loose_args(args, scope);
            return TypeId::ERROR;
        }
        if private && !inside {
            let shown = self.sym_name(self.pous[m.0 as usize].name);
            let decl = self.pous[m.0 as usize].name_span;
            self.emit(
                Diagnostic::new(
                    Code::E1311,
                    name_span,
                    format!("the method `{shown}` is private to its function block"),
                )
                .with_secondary(decl, "declared here")
                .with_help(
                    "call it from the function block's body or methods, or declare it PUBLIC",
                ),
            );
            self.loose_args(args, scope);
            return TypeId::ERROR;
        }
        let t = self.function_call(e, m, args, scope, span);
        if let Some(info) = self.calls.get_mut(&e) {
            info.target = CallTarget::Method { method: m, this };
        }
        // A call may run any override of the method (not one through
        // SUPER^, which is static): for the recursion check.
        let through_super = this.is_some_and(|x| self.is_super_deref(x));
        if let (Scope::Pou(p), false) = (scope, through_super) {
            let name = self.pous[m.0 as usize].name;
            for d in 0..self.pous.len() {
                let d = PouId(d as u32);
                if d != fb
                    && self.pous[d.0 as usize].method_of.is_none()
                    && self.types.is_subtype(d, fb)
                {
                    if let Some(o) = self.find_method(d, name).filter(|&o| o != m) {
                        self.call_edges.push((p, o, name_span));
                    }
                }
            }
        }
        t
    }

    /// Whether `e` is `SUPER^` (in parentheses or not).
    fn is_super_deref(&self, mut e: ExprId) -> bool {
        while let ExprKind::Paren(i) = &self.ast.expr(e).kind {
            e = *i;
        }
        let ExprKind::Deref(mut r) = self.ast.expr(e).kind else {
            return false;
        };
        while let ExprKind::Paren(i) = &self.ast.expr(r).kind {
            r = *i;
        }
        matches!(self.resolutions.get(&r), Some(crate::Res::Super))
    }

    fn function_call(
        &mut self,
        e: ExprId,
        q: PouId,
        args: &'a [Arg],
        scope: Scope,
        span: Span,
    ) -> TypeId {
        self.resolve_pou(q);
        if let Scope::Pou(p) = scope {
            self.call_edges.push((p, q, span));
        }
        let (bound, en, eno) = self.bind_args(q, args, scope, span);
        self.calls.insert(
            e,
            CallInfo {
                target: CallTarget::Function(q),
                args: bound,
                en,
                eno,
            },
        );
        self.pous[q.0 as usize].return_type.unwrap_or(TypeId::VOID)
    }

    /// Binds the arguments of a call to a POU's parameters and checks them;
    /// EN and ENO are returned apart (see [`CallInfo::en`]).
    #[allow(clippy::type_complexity)]
    fn bind_args(
        &mut self,
        q: PouId,
        args: &'a [Arg],
        scope: Scope,
        call_span: Span,
    ) -> (Vec<BoundArg>, Option<ExprId>, Option<(ExprId, bool)>) {
        self.resolve_pou(q);
        let callee_name = self.sym_name(self.pous[q.0 as usize].name);
        let mut bound: Vec<BoundArg> = Vec::new();
        let (mut en, mut eno) = (None, None);
        if self.mixed_args(args, scope) {
            return (bound, en, eno);
        }
        let positional: Vec<crate::VarId> = self.pous[q.0 as usize].positional_params();
        let (en_var, eno_var) = (self.pous[q.0 as usize].en, self.pous[q.0 as usize].eno);
        let mut given = rustc_hash::FxHashSet::default();
        for (i, a) in args.iter().enumerate() {
            let (v, value, output) = match &a.kind {
                ArgKind::Positional(value) => {
                    let Some(&v) = positional.get(i) else {
                        let pou = &self.pous[q.0 as usize];
                        let outs = positional
                            .iter()
                            .filter(|v| pou.var(**v).section == Section::Output)
                            .count();
                        let ins = positional.len() - outs;
                        let msg = format!(
                            "too many arguments: `{callee_name}` takes {ins} input(s) and {outs} output(s)"
                        );
                        self.emit(
                            Diagnostic::new(Code::E0403, a.span, msg).with_label("extra argument"),
                        );
                        self.loose_args(&args[i..], scope);
                        break;
                    };
                    // A positional argument after the inputs and in-outs is an
                    // output (ed2 2.5.1.1), exactly like `name => value`.
                    let out = (self.pous[q.0 as usize].var(v).section == Section::Output)
                        .then_some(false);
                    (v, *value, out)
                }
                ArgKind::Input { name, value }
                | ArgKind::Output {
                    name,
                    target: value,
                    ..
                } => {
                    let is_out = matches!(a.kind, ArgKind::Output { .. });
                    let negated = matches!(a.kind, ArgKind::Output { negated: true, .. });
                    let shown = self.spelled(name.sym, name.span);
                    let pou = &self.pous[q.0 as usize];
                    let found = pou.lookup(name.sym).map(|v| (v, pou.var(v).section));
                    let ok = match found {
                        Some((_, Section::Input | Section::InOut)) => !is_out,
                        Some((_, Section::Output)) => is_out,
                        _ => false,
                    };
                    if !ok {
                        if found.is_none() && self.member_may_be_unsupported(q, name.sym) {
                            // May be inherited through an EXTENDS already
                            // reported.
                            self.check_expr(*value, Some(TypeId::ERROR), scope);
                            continue;
                        }
                        let msg = match found {
                            Some((_, Section::Output)) => format!("`{shown}` is an output of `{callee_name}`: write `{shown} => variable`"),
                            Some((_, Section::Input)) if is_out => format!("`{shown}` is an input of `{callee_name}`: write `{shown} := value`"),
                            _ => format!("`{callee_name}` has no parameter `{shown}`"),
                        };
                        let names: Vec<String> = pou
                            .vars
                            .iter()
                            .filter(|v| {
                                matches!(
                                    v.section,
                                    Section::Input | Section::InOut | Section::Output
                                )
                            })
                            .map(|v| self.spelled(v.name, v.span))
                            .collect();
                        let mut d = Diagnostic::new(Code::E0401, name.span, msg)
                            .with_label("unknown parameter");
                        if found.is_none() {
                            if let Some(s) =
                                self.did_you_mean(&shown, names.iter().map(|s| s.as_str()))
                            {
                                d = d.with_help(format!("did you mean `{s}`?"));
                            }
                            d = d.with_note(format!(
                                "the parameters of `{callee_name}` are {}",
                                names.join(", ")
                            ));
                        }
                        self.emit(d);
                        self.check_expr(*value, Some(TypeId::ERROR), scope);
                        continue;
                    }
                    let v = found.map(|f| f.0).unwrap_or(crate::VarId(0));
                    if !given.insert(v) {
                        self.error(Code::E0408, name.span, format!("`{shown}` is given twice"));
                        self.check_expr(*value, Some(TypeId::ERROR), scope);
                        continue;
                    }
                    if Some(v) == en_var {
                        en = self.en_arg(*value, scope);
                        continue;
                    }
                    if Some(v) == eno_var {
                        eno = self.eno_arg(*value, negated, scope);
                        continue;
                    }
                    (v, *value, if is_out { Some(negated) } else { None })
                }
            };
            given.insert(v);
            let param = self.pous[q.0 as usize].var(v).clone();
            let pname = format!("parameter `{}`", self.sym_name(param.name));
            let kind = match (output, param.section) {
                (Some(negated), _) => {
                    let tt = self.check_lvalue(value, scope, Write::Output);
                    if tt != TypeId::ERROR && param.ty != TypeId::ERROR {
                        if negated && !self.types.is_bool(param.ty) {
                            self.error(Code::E0407, a.span, "`NOT name =>` needs a BOOL output");
                        } else {
                            self.check_output_type(value, param.ty, tt, &pname);
                        }
                    }
                    BoundArgKind::Output {
                        target: value,
                        negated,
                    }
                }
                (None, Section::InOut) => {
                    let tt = self.check_lvalue(value, scope, Write::InOut);
                    if tt != TypeId::ERROR
                        && param.ty != TypeId::ERROR
                        && self.types.compat(tt, param.ty, false) != crate::Compat::Same
                    {
                        let msg = format!(
                            "{pname} is passed by reference and needs {}, not {}",
                            self.tname(param.ty),
                            self.tname(tt)
                        );
                        self.emit(Diagnostic::new(Code::E0407, self.ast.expr(value).span, msg));
                    }
                    BoundArgKind::InOut(value)
                }
                _ => {
                    let vt = self.check_expr(value, Some(param.ty), scope);
                    if vt != TypeId::ERROR
                        && param.ty != TypeId::ERROR
                        && self.coerce(value, vt, param.ty, Ctx::Arg, &pname)
                    {
                        if self.pous[q.0 as usize].kind != PouKind::Function {
                            // An instance's input outlives the call.
                            let span = self.ast.expr(value).span;
                            self.check_ptr_store(None, value, param.ty, span);
                        }
                        let c = self
                            .consts
                            .get(&value)
                            .cloned()
                            .and_then(|c| self.convert_const(&c, vt, param.ty));
                        self.check_subrange(&c, param.ty, self.ast.expr(value).span);
                    }
                    BoundArgKind::Input(value)
                }
            };
            bound.push(BoundArg { param: v.0, kind });
        }
        let missing: Vec<String> = self.pous[q.0 as usize]
            .vars
            .iter()
            .enumerate()
            .filter(|(i, v)| {
                v.section == Section::InOut
                    && !given.contains(&crate::VarId(*i as u32))
                    && self.pous[q.0 as usize].this != Some(crate::VarId(*i as u32))
            })
            .map(|(_, v)| self.sym_name(v.name))
            .collect();
        if !missing.is_empty() {
            let list = missing
                .iter()
                .map(|m| format!("`{m}`"))
                .collect::<Vec<_>>()
                .join(", ");
            self.emit(
                Diagnostic::new(
                    Code::E0402,
                    call_span,
                    format!("the VAR_IN_OUT parameter(s) {list} of `{callee_name}` must be given"),
                )
                .with_label("missing VAR_IN_OUT argument"),
            );
        }
        self.check_eval_order(args, scope, call_span);
        (bound, en, eno)
    }

    /// `EN := value`: a BOOL.
    fn en_arg(&mut self, value: ExprId, scope: Scope) -> Option<ExprId> {
        let bool_ty = self.types.elem(ElemType::Bool);
        let t = self.check_expr(value, Some(bool_ty), scope);
        if t != TypeId::ERROR {
            self.coerce(value, t, bool_ty, Ctx::Arg, "`EN`");
        }
        Some(value)
    }

    /// `ENO => target`: a BOOL variable.
    fn eno_arg(&mut self, target: ExprId, negated: bool, scope: Scope) -> Option<(ExprId, bool)> {
        let bool_ty = self.types.elem(ElemType::Bool);
        let tt = self.check_lvalue(target, scope, Write::Output);
        if tt != TypeId::ERROR {
            self.check_output_type(target, bool_ty, tt, "`ENO`");
        }
        Some((target, negated))
    }

    /// The type of a `=>` target against the output it receives.
    fn check_output_type(&mut self, target: ExprId, from: TypeId, to: TypeId, what: &str) {
        let span = self.ast.expr(target).span;
        match self.types.compat(from, to, self.opts.iec2) {
            crate::Compat::Same | crate::Compat::Widen => {}
            crate::Compat::Narrow if self.dialect_int_conversion(from, to) => {
                self.dialect_conversion_warning(span, from, to);
            }
            crate::Compat::Narrow => {
                let (f, t) = (self.tname(from), self.tname(to));
                let msg = match self.narrowing(from, to) {
                    crate::expr::Narrowing::Iec2 => format!(
                        "{what} is {f}, which is not converted implicitly to {t} with --std iec2"
                    ),
                    crate::expr::Narrowing::Family => format!(
                        "{what} is {f}, which does not convert implicitly to {t}: bit strings and numbers convert only explicitly"
                    ),
                    crate::expr::Narrowing::Loses => {
                        format!("{what} is {f} and would be narrowed into {t}")
                    }
                };
                self.emit(Diagnostic::new(Code::E0302, span, msg));
            }
            crate::Compat::Incompatible => {
                let msg = format!(
                    "{what} gives {}, which cannot be stored in {}",
                    self.tname(from),
                    self.tname(to)
                );
                self.emit(Diagnostic::new(Code::E0407, span, msg));
            }
        }
    }

    // ----- standard functions -------------------------------------------------

    fn std_call(
        &mut self,
        e: ExprId,
        f: &StdFunction,
        args: &'a [Arg],
        expected: Option<TypeId>,
        scope: Scope,
        span: Span,
    ) -> TypeId {
        // Bind arguments to positions.
        if self.mixed_args(args, scope) {
            return TypeId::ERROR;
        }
        let mut slots: Vec<Option<ExprId>> = Vec::new();
        // EN and ENO, which every standard function has too (ed2 2.5.1.2).
        let (mut en, mut eno) = (None, None);
        for a in args {
            let (name, slot) = match &a.kind {
                ArgKind::Input { name, value } if self.interner.key(name.sym) == "EN" => {
                    (name, Some(*value))
                }
                ArgKind::Output {
                    name,
                    target,
                    negated,
                } if self.interner.key(name.sym) == "ENO" => {
                    if eno.replace((*target, *negated)).is_none() {
                        continue;
                    }
                    (name, None)
                }
                _ => continue,
            };
            if slot.is_some() && en.replace(slot).is_none() {
                continue;
            }
            let shown = self.spelled(name.sym, name.span);
            self.error(Code::E0408, name.span, format!("`{shown}` is given twice"));
            self.loose_args(args, scope);
            return TypeId::ERROR;
        }
        let en = en.flatten();
        for (i, a) in args.iter().enumerate() {
            let pos = match &a.kind {
                ArgKind::Input { name, .. } | ArgKind::Output { name, .. }
                    if matches!(self.interner.key(name.sym), "EN" | "ENO") =>
                {
                    if matches!(
                        (&a.kind, self.interner.key(name.sym)),
                        (ArgKind::Input { .. }, "EN") | (ArgKind::Output { .. }, "ENO")
                    ) {
                        continue;
                    }
                    let shown = self.spelled(name.sym, name.span);
                    let msg = if matches!(a.kind, ArgKind::Input { .. }) {
                        format!(
                            "`{shown}` is an output of `{}`: write `{shown} => variable`",
                            f.name
                        )
                    } else {
                        format!(
                            "`{shown}` is an input of `{}`: write `{shown} := value`",
                            f.name
                        )
                    };
                    self.error(Code::E0401, name.span, msg);
                    self.loose_args(args, scope);
                    return TypeId::ERROR;
                }
                ArgKind::Positional(_) => {
                    if i >= f.params.len() && !f.extensible {
                        let msg =
                            format!("too many arguments: `{}` takes {}", f.name, f.params.len());
                        self.emit(
                            Diagnostic::new(Code::E0403, a.span, msg).with_label("extra argument"),
                        );
                        self.loose_args(&args[i..], scope);
                        return TypeId::ERROR;
                    }
                    i
                }
                ArgKind::Input { name, .. } => {
                    let key = self.interner.key(name.sym).to_string();
                    match param_position(f, &key) {
                        Some(p) => p,
                        None => {
                            let shown = self.spelled(name.sym, name.span);
                            let names: Vec<String> =
                                (0..f.params.len()).map(|i| param_name(f, i)).collect();
                            let mut d = Diagnostic::new(
                                Code::E0401,
                                name.span,
                                format!("`{}` has no parameter `{shown}`", f.name),
                            );
                            d = d.with_note(format!("its parameters are {}", names.join(", ")));
                            self.emit(d);
                            self.loose_args(args, scope);
                            return TypeId::ERROR;
                        }
                    }
                }
                ArgKind::Output { name, .. } => {
                    let shown = self.spelled(name.sym, name.span);
                    self.error(
                        Code::E0401,
                        name.span,
                        format!("`{}` has no output `{shown}`", f.name),
                    );
                    self.loose_args(args, scope);
                    return TypeId::ERROR;
                }
            };
            if slots.len() <= pos {
                slots.resize(pos + 1, None);
            }
            if slots[pos].is_some() {
                self.error(
                    Code::E0408,
                    a.span,
                    format!("parameter `{}` is given twice", param_name(f, pos)),
                );
                self.loose_args(args, scope);
                return TypeId::ERROR;
            }
            slots[pos] = Some(arg_value(a));
        }
        let needed = f.params.len();
        if slots.len() < needed || slots.iter().any(|s| s.is_none()) {
            let missing: Vec<String> = (0..needed.max(slots.len()))
                .filter(|&i| slots.get(i).copied().flatten().is_none())
                .map(|i| param_name(f, i))
                .collect();
            let msg = format!("`{}` needs the input(s) {}", f.name, missing.join(", "));
            self.emit(Diagnostic::new(Code::E0410, span, msg).with_label("missing argument"));
            self.loose_args(args, scope);
            return TypeId::ERROR;
        }
        let values: Vec<ExprId> = slots.into_iter().flatten().collect();
        let typed_form = matches!(f.params.first().map(|p| p.ty), Some(TyPat::Elem(_)));
        let binary_op = match f.intrinsic {
            Intrinsic::Add => Some(BinaryOp::Add),
            Intrinsic::Sub => Some(BinaryOp::Sub),
            Intrinsic::Mul => Some(BinaryOp::Mul),
            Intrinsic::Div => Some(BinaryOp::Div),
            _ => None,
        };
        let result = match (binary_op, f.intrinsic) {
            // ADD(a, b) is `a + b` with everything the operator allows
            // (TIME, TOD, DT and DATE operands: the 2nd edition's Table 30
            // overloads), checked, converted and folded the same way; the
            // IR lowers both to the same operation.
            (Some(op), _) if values.len() == 2 && !typed_form => {
                let ret = self.binary(e, op, values[0], values[1], expected, scope);
                if ret != TypeId::ERROR {
                    let arg_types = values
                        .iter()
                        .map(|v| {
                            self.coercions
                                .get(v)
                                .copied()
                                .unwrap_or(self.expr_types[v.index()])
                        })
                        .collect();
                    let args = (0u32..)
                        .zip(&values)
                        .map(|(param, &v)| BoundArg {
                            param,
                            kind: crate::BoundArgKind::Input(v),
                        })
                        .collect();
                    self.calls.insert(
                        e,
                        CallInfo {
                            target: CallTarget::Std {
                                intrinsic: f.intrinsic,
                                arg_types,
                                ret,
                            },
                            args,
                            en: None,
                            eno: None,
                        },
                    );
                }
                ret
            }
            (
                _,
                Intrinsic::Add
                | Intrinsic::Sub
                | Intrinsic::Mul
                | Intrinsic::Div
                | Intrinsic::Mod
                | Intrinsic::And
                | Intrinsic::Or
                | Intrinsic::Xor
                | Intrinsic::Gt
                | Intrinsic::Ge
                | Intrinsic::Eq
                | Intrinsic::Le
                | Intrinsic::Lt
                | Intrinsic::Ne
                | Intrinsic::Not,
            ) => self.operator_call(e, f, &values, expected, scope, span),
            _ => self.generic_call(e, f, &values, expected, scope, span),
        };
        // The overloaded TO_<T> converts what the typed S_TO_T would: a pair
        // with no S_TO_T (BOOL to REAL, DATE to TOD...) is an error here,
        // not a fault at run time.
        if let (Intrinsic::Convert { to, .. }, Some(&v)) = (f.intrinsic, values.first()) {
            let from = self.types.scalar(self.expr_types[v.index()]);
            if let Some(from) = from.filter(|&s| result != TypeId::ERROR && s != to) {
                if f.name.starts_with("TO_") && !stc_values::conversion_allowed(from, to) {
                    let msg = format!(
                        "`{}` cannot convert {}: there is no {}_TO_{}",
                        f.name,
                        from.name(),
                        from.name(),
                        to.name()
                    );
                    self.emit(
                        Diagnostic::new(Code::E0407, self.ast.expr(v).span, msg)
                            .with_label(format!("this is {}", from.name())),
                    );
                    self.calls.remove(&e);
                    self.consts.remove(&e);
                    return TypeId::ERROR;
                }
                if stc_values::conversion_is_extension(from, to) {
                    let msg = format!(
                        "{}_TO_{} is not a conversion of IEC 61131-3",
                        from.name(),
                        to.name()
                    );
                    let help = if to == ElemType::Bool {
                        "compare instead: `x <> 0.0`".to_string()
                    } else {
                        format!("portable: BOOL_TO_INT, then INT_TO_{}", to.name())
                    };
                    self.emit(
                        Diagnostic::new(Code::W0112, span, msg)
                            .with_label("accepted: MatIEC, Beremiz and CODESYS have it")
                            .with_help(help),
                    );
                }
            }
        }
        if en.is_some() || eno.is_some() {
            let en = en.and_then(|v| self.en_arg(v, scope));
            let eno = eno.and_then(|(t, n)| self.eno_arg(t, n, scope));
            if let Some(c) = self.calls.get_mut(&e) {
                c.en = en;
                c.eno = eno;
            }
            if en.is_some() {
                // Its value depends on EN: not a constant.
                self.consts.remove(&e);
            }
        }
        self.check_eval_order(args, scope, span);
        result
    }

    /// LOWER_BOUND(ARR, DIM) and UPPER_BOUND(ARR, DIM) (3rd edition): a
    /// bound of an array, a DINT constant since every array stc supports
    /// has fixed bounds. Of a variable-length array (already reported as
    /// not supported) nothing more is said.
    fn bound_call(
        &mut self,
        e: ExprId,
        upper: bool,
        name: &str,
        args: &'a [Arg],
        scope: Scope,
        span: Span,
    ) -> TypeId {
        let mut slots: [Option<ExprId>; 2] = [None, None];
        for (i, a) in args.iter().enumerate() {
            let pos = match &a.kind {
                ArgKind::Positional(_) if i < 2 => Some(i),
                ArgKind::Input { name, .. } => match self.interner.key(name.sym) {
                    "ARR" => Some(0),
                    "DIM" => Some(1),
                    _ => None,
                },
                _ => None,
            };
            match pos {
                Some(p) if slots[p].is_none() => slots[p] = Some(arg_value(a)),
                _ => {
                    let msg = format!("`{name}` takes the inputs ARR (an array) and DIM");
                    self.emit(Diagnostic::new(Code::E0401, a.span, msg));
                    self.loose_args(args, scope);
                    return TypeId::ERROR;
                }
            }
        }
        let [Some(arr), Some(dim)] = slots else {
            let msg = format!("`{name}` needs the inputs ARR and DIM");
            self.emit(Diagnostic::new(Code::E0410, span, msg).with_label("missing argument"));
            self.loose_args(args, scope);
            return TypeId::ERROR;
        };
        let at = self.check_expr(arr, None, scope);
        let dint = self.types.elem(ElemType::Dint);
        let dt = self.check_expr(dim, Some(dint), scope);
        if at == TypeId::ERROR || dt == TypeId::ERROR {
            return TypeId::ERROR;
        }
        let TypeKind::Array { dims, .. } = self.types.kind(at).clone() else {
            let msg = format!("`{name}` needs an array, not {}", self.tname(at));
            self.emit(Diagnostic::new(Code::E0407, self.ast.expr(arr).span, msg));
            return TypeId::ERROR;
        };
        let k = match self.consts.get(&dim) {
            Some(Value::Int(k)) if self.types.is_integer(dt) => *k,
            _ => {
                let msg = format!("the DIM of `{name}` must be an integer constant");
                self.emit(Diagnostic::new(Code::E0407, self.ast.expr(dim).span, msg));
                return TypeId::ERROR;
            }
        };
        let Some(&(lo, hi)) = usize::try_from(k - 1).ok().and_then(|i| dims.get(i)) else {
            let msg = format!("the array has dimensions 1..{}, not {k}", dims.len());
            self.emit(Diagnostic::new(Code::E0701, self.ast.expr(dim).span, msg));
            return TypeId::ERROR;
        };
        self.consts
            .insert(e, Value::Int(if upper { hi } else { lo }));
        dint
    }

    /// W0116: SHL, SHR, ROL or ROR of an integer (`IN`), or by a bit
    /// string (`N`), as CODESYS allows: the integer's bits are shifted
    /// (SHR of a signed integer is arithmetic, its sign fills in; the
    /// lowering converts to the bit string of the same width and back).
    fn shift_of_integer(
        &mut self,
        f: &StdFunction,
        fam: GenericType,
        t: TypeId,
        v: ExprId,
    ) -> bool {
        use stc_values::Intrinsic as I;
        if self.opts.iec2 || !matches!(f.intrinsic, I::Shl | I::Shr | I::Rol | I::Ror) {
            return false;
        }
        let Some(s) = self.types.numeric(t) else {
            return false;
        };
        let (ok, what) = match fam {
            GenericType::AnyBit => (
                stc_values::is_integer(s),
                "an integer shifted as the bits of its type",
            ),
            GenericType::AnyInt => (
                stc_values::is_bit_string(s) && s != ElemType::Bool,
                "a bit string used as the number of bits",
            ),
            _ => (false, ""),
        };
        if ok {
            let shown = self.tname(t);
            self.emit(
                Diagnostic::new(
                    Code::W0116,
                    self.ast.expr(v).span,
                    format!("`{}` of {shown}: {what}, as CODESYS allows", f.name),
                )
                .with_label(format!("this is {shown}"))
                .with_help("the standard shifts bit strings by an integer: convert with INT_TO_WORD(...) and back"),
            );
        }
        ok
    }

    /// Binds the type variables of a signature and checks every argument.
    fn generic_call(
        &mut self,
        e: ExprId,
        f: &StdFunction,
        values: &[ExprId],
        expected: Option<TypeId>,
        scope: Scope,
        span: Span,
    ) -> TypeId {
        let pats: Vec<TyPat> = (0..values.len()).map(|i| param_pat(f, i)).collect();
        let mut bind: [Option<TypeId>; 8] = [None; 8];
        let mut types = vec![TypeId::ERROR; values.len()];
        let mut failed = false;
        // Arguments with their own type bind the variables first.
        for pass in 0..2 {
            for (i, &v) in values.iter().enumerate() {
                let flexible = self.is_flexible(v, scope);
                if (pass == 0) == flexible {
                    continue;
                }
                let hint = match pats[i] {
                    TyPat::Elem(t) => Some(self.types.elem(t)),
                    // A literal that does not fit the type the other inputs
                    // bound takes its own (`MAX(i, 70000)` is a DINT MAX).
                    TyPat::Var(k, _) if bind[k as usize].is_some() => {
                        self.fitting_hint(v, bind[k as usize])
                    }
                    TyPat::Var(k, fam) => {
                        expected.filter(|t| self.type_in_family(*t, fam) && ret_var(f) == Some(k))
                    }
                };
                let t = self.check_expr(v, hint, scope);
                types[i] = t;
                if t == TypeId::ERROR {
                    failed = true;
                    continue;
                }
                if let TyPat::Var(k, fam) = pats[i] {
                    if !self.type_in_family(t, fam) && !self.shift_of_integer(f, fam, t, v) {
                        let msg = format!(
                            "parameter {} of `{}` must be {}, not {}",
                            param_name(f, i),
                            f.name,
                            fam.name(),
                            self.tname(t)
                        );
                        self.emit(
                            Diagnostic::new(Code::E0407, self.ast.expr(v).span, msg)
                                .with_label(format!("this is {}", self.tname(t))),
                        );
                        failed = true;
                        continue;
                    }
                    match bind[k as usize] {
                        None => bind[k as usize] = Some(t),
                        Some(b) => match self.unify_types(b, t) {
                            Some(u) => bind[k as usize] = Some(u),
                            None => {
                                let msg = format!(
                                    "the inputs of `{}` must have one type, but this is {} and an earlier one {}",
                                    f.name,
                                    self.tname(t),
                                    self.tname(b)
                                );
                                self.emit(Diagnostic::new(Code::E0407, self.ast.expr(v).span, msg));
                                failed = true;
                            }
                        },
                    }
                }
            }
        }
        if failed {
            return TypeId::ERROR;
        }
        // Conversions of each argument to its parameter type.
        let mut arg_types = Vec::with_capacity(values.len());
        for (i, &v) in values.iter().enumerate() {
            let target = match pats[i] {
                TyPat::Elem(t) => self.types.elem(t),
                TyPat::Var(k, _) => bind[k as usize].unwrap_or(types[i]),
            };
            let pname = format!("parameter {} of `{}`", param_name(f, i), f.name);
            let strings = matches!(self.types.kind(target), TypeKind::String { .. });
            if !strings && !self.coerce(v, types[i], target, Ctx::Arg, &pname) {
                return TypeId::ERROR;
            }
            arg_types.push(if strings { types[i] } else { target });
        }
        let ret = match f.ret {
            TyPat::Elem(t) => self.types.elem(t),
            TyPat::Var(k, fam) => match bind[k as usize] {
                Some(t) => t,
                None => match expected.filter(|t| self.type_in_family(*t, fam)) {
                    Some(t) => t,
                    None => self.types.elem(default_of(fam)),
                },
            },
        };
        let ret = self.string_result(f.intrinsic, ret, &arg_types);
        let bound: Vec<BoundArg> = values
            .iter()
            .enumerate()
            .map(|(i, &v)| BoundArg {
                param: i as u32,
                kind: crate::BoundArgKind::Input(v),
            })
            .collect();
        self.calls.insert(
            e,
            CallInfo {
                target: CallTarget::Std {
                    intrinsic: f.intrinsic,
                    arg_types: arg_types.clone(),
                    ret,
                },
                args: bound,
                en: None,
                eno: None,
            },
        );
        self.fold_call(e, f.intrinsic, values, &arg_types, ret, span);
        ret
    }

    /// ADD, GT, AND...: typed like the operators over all their inputs.
    fn operator_call(
        &mut self,
        e: ExprId,
        f: &StdFunction,
        values: &[ExprId],
        expected: Option<TypeId>,
        scope: Scope,
        span: Span,
    ) -> TypeId {
        let cmp = matches!(
            f.intrinsic,
            Intrinsic::Gt
                | Intrinsic::Ge
                | Intrinsic::Eq
                | Intrinsic::Le
                | Intrinsic::Lt
                | Intrinsic::Ne
        );
        let outer = if cmp {
            None
        } else {
            expected.filter(|t| self.types.scalar(*t).is_some())
        };
        let mut types = vec![TypeId::ERROR; values.len()];
        let mut common: Option<TypeId> = None;
        // A typed form (`ADD_INT`, `EQ_STRING`): every input has that type.
        if let Some(TyPat::Elem(t)) = f.params.first().map(|p| p.ty) {
            let target = self.types.elem(t);
            for (i, &v) in values.iter().enumerate() {
                let vt = self.check_expr(v, Some(target), scope);
                types[i] = vt;
                let pname = format!("parameter {} of `{}`", param_name(f, i), f.name);
                if vt == TypeId::ERROR || !self.coerce(v, vt, target, Ctx::Arg, &pname) {
                    return TypeId::ERROR;
                }
            }
            common = Some(target);
        }
        for pass in 0..2 {
            for (i, &v) in values.iter().enumerate() {
                if common.is_some() && types[i] != TypeId::ERROR
                    || (pass == 0) == self.is_flexible(v, scope)
                {
                    continue;
                }
                let hint = match common {
                    Some(_) if pass == 1 => self.fitting_hint(v, common),
                    _ => common.or(outer),
                };
                let t = self.check_expr(v, hint, scope);
                types[i] = t;
                if t == TypeId::ERROR {
                    return if cmp {
                        self.types.elem(ElemType::Bool)
                    } else {
                        TypeId::ERROR
                    };
                }
                common = match common {
                    None => Some(t),
                    Some(c) => match self.unify_types(c, t) {
                        Some(u) => Some(u),
                        None => {
                            let msg = format!(
                                "`{}` cannot combine {} and {}",
                                f.name,
                                self.tname(c),
                                self.tname(t)
                            );
                            self.emit(Diagnostic::new(Code::E0201, span, msg));
                            return TypeId::ERROR;
                        }
                    },
                };
            }
        }
        let Some(c) = common else {
            return TypeId::ERROR;
        };
        let s = self.types.scalar(c);
        let ok = match f.intrinsic {
            Intrinsic::Add | Intrinsic::Sub | Intrinsic::Mul | Intrinsic::Div => {
                s.is_some_and(|s| stc_values::in_family(GenericType::AnyNum, s))
            }
            Intrinsic::Mod => s.is_some_and(stc_values::is_integer),
            Intrinsic::And | Intrinsic::Or | Intrinsic::Xor | Intrinsic::Not => {
                s.is_some_and(stc_values::is_bit_string)
            }
            _ => s.is_some(),
        };
        if !ok
            || matches!(self.types.kind(c), TypeKind::Enum { .. })
                && !matches!(f.intrinsic, Intrinsic::Eq | Intrinsic::Ne)
        {
            let msg = format!("`{}` cannot be applied to {}", f.name, self.tname(c));
            self.emit(Diagnostic::new(Code::E0201, span, msg));
            return TypeId::ERROR;
        }
        for (i, &v) in values.iter().enumerate() {
            if types[i] != c && !matches!(self.types.kind(c), TypeKind::String { .. }) {
                self.coercions.insert(v, c);
            }
        }
        if matches!(f.intrinsic, Intrinsic::Div | Intrinsic::Mod)
            && s.is_some_and(stc_values::is_integer)
        {
            for &v in &values[1..] {
                if matches!(self.consts.get(&v), Some(Value::Int(0))) {
                    let vspan = self.ast.expr(v).span;
                    self.emit(
                        Diagnostic::new(Code::E0703, vspan, "division by zero")
                            .with_label("this is zero"),
                    );
                    return TypeId::ERROR;
                }
            }
        }
        let ret = if cmp {
            self.types.elem(ElemType::Bool)
        } else {
            c
        };
        let arg_types = vec![c; values.len()];
        let bound = values
            .iter()
            .enumerate()
            .map(|(i, &v)| BoundArg {
                param: i as u32,
                kind: crate::BoundArgKind::Input(v),
            })
            .collect();
        self.calls.insert(
            e,
            CallInfo {
                target: CallTarget::Std {
                    intrinsic: f.intrinsic,
                    arg_types: arg_types.clone(),
                    ret,
                },
                args: bound,
                en: None,
                eno: None,
            },
        );
        self.fold_call(e, f.intrinsic, values, &arg_types, ret, span);
        ret
    }

    /// Folds a standard function call whose arguments are all constants.
    fn fold_call(
        &mut self,
        e: ExprId,
        f: Intrinsic,
        values: &[ExprId],
        arg_types: &[TypeId],
        ret: TypeId,
        span: Span,
    ) {
        let mut vals: Vec<Value> = Vec::with_capacity(values.len());
        let mut elems = Vec::with_capacity(values.len());
        for (i, &v) in values.iter().enumerate() {
            let (Some(c), Some(s)) = (
                self.consts.get(&v).cloned(),
                self.types.scalar(arg_types[i]),
            ) else {
                return;
            };
            let from = self.types.scalar(self.expr_types[v.index()]).unwrap_or(s);
            let Ok(c) = (if from != s {
                stc_values::convert(from, s, &c)
            } else {
                Ok(c)
            }) else {
                return;
            };
            vals.push(c);
            elems.push(s);
        }
        let Some(r) = self.types.scalar(ret) else {
            return;
        };
        let out = stc_values::call(f, &elems, &vals, r);
        match out {
            Ok(_) | Err(stc_values::Fault::DivisionByZero) => {
                self.record_fold(e, out, span, values.get(1).map(|v| self.ast.expr(*v).span))
            }
            Err(_) => {}
        }
    }

    /// Whether a type belongs to a generic family (strings by kind).
    fn type_in_family(&self, t: TypeId, fam: GenericType) -> bool {
        if matches!(fam, GenericType::Any) {
            return true;
        }
        match self.types.kind(t) {
            TypeKind::Enum { .. } => matches!(
                fam,
                GenericType::Any | GenericType::AnyDerived | GenericType::AnyElementary
            ),
            _ => self
                .types
                .scalar(t)
                .is_some_and(|s| stc_values::in_family(fam, s)),
        }
    }

    /// The common type of two argument types (strings: the longer one).
    fn unify_types(&mut self, a: TypeId, b: TypeId) -> Option<TypeId> {
        if a == b {
            return Some(a);
        }
        match (self.types.kind(a).clone(), self.types.kind(b).clone()) {
            (TypeKind::String { wide: wa, len: la }, TypeKind::String { wide: wb, len: lb })
                if wa == wb =>
            {
                Some(self.types.string(wa, la.max(lb)))
            }
            (TypeKind::Enum { .. }, _) | (_, TypeKind::Enum { .. }) => None,
            _ => {
                let (x, y) = (self.types.numeric(a)?, self.types.numeric(b)?);
                let c = stc_values::common_type(x, y)?;
                if self.opts.iec2 && x != y {
                    return None;
                }
                Some(self.types.elem(c))
            }
        }
    }

    /// String results: CONCAT, INSERT and REPLACE can be as long as all
    /// their inputs together; the other string functions as their input.
    fn string_result(&mut self, f: Intrinsic, ret: TypeId, args: &[TypeId]) -> TypeId {
        let TypeKind::String { wide, len } = *self.types.kind(ret) else {
            return ret;
        };
        let total: u32 = args
            .iter()
            .filter_map(|t| match self.types.kind(*t) {
                TypeKind::String { len, .. } => Some(*len),
                _ => None,
            })
            .sum();
        match f {
            Intrinsic::Concat | Intrinsic::Insert | Intrinsic::Replace => {
                self.types.string(wide, total.clamp(1, 65_535))
            }
            _ => self.types.string(wide, len),
        }
    }

    // ----- assignment targets ---------------------------------------------------

    /// Checks an expression being written: by `:=`, by `=>`, or passed to a
    /// VAR_IN_OUT. Returns its type, or ERROR after reporting.
    pub(crate) fn check_lvalue(&mut self, target: ExprId, scope: Scope, how: Write) -> TypeId {
        let span = self.ast.expr(target).span;
        let not_var_code = if how == Write::Assign {
            Code::E0307
        } else {
            Code::E0406
        };
        let Scope::Pou(p) = scope else {
            return self.check_expr(target, None, scope);
        };
        // The variable at the root of `a.b[i].c`.
        let mut root = target;
        let mut through_fb_output = None;
        let mut through_fb_in_out = None;
        loop {
            match &self.ast.expr(root).kind {
                ExprKind::Member { base, .. } | ExprKind::PartialAccess { base, .. } => {
                    root = *base
                }
                ExprKind::Index { base, .. } => root = *base,
                // `r^ := v`: the variable a reference refers to (its
                // errors are the dereference's).
                ExprKind::Deref(_) => return self.check_expr(target, None, scope),
                // A target that did not parse: reported already; the names
                // in it are still resolved.
                ExprKind::Error | ExprKind::IlCr => {
                    self.check_expr(target, Some(TypeId::ERROR), scope);
                    return TypeId::ERROR;
                }
                _ => break,
            }
        }
        match &self.ast.expr(root).kind {
            ExprKind::Name(id) => {
                if self.pous[p.0 as usize].lookup(id.sym).is_none() {
                    let shown = self.spelled(id.sym, id.span);
                    let is_other = self.is_global_name(*id)
                        || self.enum_candidates(id.sym, scope).next().is_some();
                    if is_other {
                        let what = if how == Write::Assign {
                            "assigned"
                        } else {
                            "written"
                        };
                        self.emit(
                            Diagnostic::new(
                                not_var_code,
                                span,
                                format!("`{shown}` is not a variable and cannot be {what}"),
                            )
                            .with_label("not a variable"),
                        );
                        return TypeId::ERROR;
                    }
                }
            }
            ExprKind::Address(_) => {}
            _ => {
                let msg = match how {
                    Write::Assign => "the target of an assignment must be a variable".to_string(),
                    Write::Output => {
                        "the target of an output (`=>`) must be a variable".to_string()
                    }
                    Write::InOut => "a VAR_IN_OUT parameter must be given a variable".to_string(),
                };
                self.emit(Diagnostic::new(not_var_code, span, msg).with_label("not a variable"));
                return TypeId::ERROR;
            }
        }
        let t = self.check_expr(target, None, scope);
        if t == TypeId::ERROR {
            return t;
        }
        // An FB output written from outside (`fb.Q := ...`).
        let mut e = target;
        loop {
            match &self.ast.expr(e).kind {
                ExprKind::Member { base, .. } => {
                    if let Some(Res::FbMember(fb, v)) = self.resolutions.get(&e).copied() {
                        match self.pous[fb.0 as usize].var(v).section {
                            Section::Output => through_fb_output = Some(e),
                            Section::InOut => through_fb_in_out = Some(e),
                            _ => {}
                        }
                    }
                    e = *base;
                }
                ExprKind::PartialAccess { base, .. } | ExprKind::Index { base, .. } => e = *base,
                _ => break,
            }
        }
        if let Some(m) = through_fb_in_out {
            let mspan = self.ast.expr(m).span;
            // The W0115 of reading it says nothing more than this.
            let read = self.diags.iter().rposition(|d| {
                d.code == Code::W0115 && mspan.lo <= d.span.lo && d.span.hi <= mspan.hi
            });
            if let Some(i) = read {
                self.dropped.insert(i);
            }
            self.emit(
                Diagnostic::new(
                    Code::E0104,
                    mspan,
                    "the in-out of a function block instance cannot be written from outside",
                )
                .with_label("VAR_IN_OUT")
                .with_note(
                    "it refers to the variable the last call passed: write that variable instead",
                ),
            );
            return TypeId::ERROR;
        }
        if let Some(m) = through_fb_output {
            let mspan = self.ast.expr(m).span;
            self.emit(
                Diagnostic::new(
                    Code::E0305,
                    mspan,
                    "the output of a function block instance cannot be written from outside",
                )
                .with_help(
                    "outputs are set by the function block itself; use an input to pass a value in",
                ),
            );
            return TypeId::ERROR;
        }
        if let Some(Res::Var(v)) = self.resolutions.get(&root).copied() {
            let var = self.pous[p.0 as usize].var(v).clone();
            let shown = self.sym_name(var.name);
            if var.constant {
                self.emit(
                    Diagnostic::new(
                        Code::E0304,
                        span,
                        format!("`{shown}` is a constant and cannot be changed"),
                    )
                    .with_secondary(var.span, "declared CONSTANT here"),
                );
                return TypeId::ERROR;
            }
            if self.body.for_vars.contains(&v) {
                self.emit(
                    Diagnostic::new(Code::E0306, span, format!("`{shown}` is the control variable of an enclosing FOR loop"))
                        .with_label("changed inside the loop")
                        .with_help("the number of iterations is fixed when the loop starts; use WHILE to change it"),
                );
                return TypeId::ERROR;
            }
            if var.section == Section::Input && how == Write::Assign {
                self.emit(
                    Diagnostic::new(
                        Code::W0103,
                        span,
                        format!("assignment to the input `{shown}`"),
                    )
                    .with_help(
                        "inputs are set by the caller; copy the input to a local variable instead",
                    ),
                );
            }
        }
        t
    }
}

/// The name of a standard function's parameter at a position.
pub(crate) fn param_name(f: &StdFunction, i: usize) -> String {
    if let Some(p) = f.params.get(i) {
        return p.name.to_string();
    }
    let last = f.params.last().map(|p| p.name).unwrap_or("IN");
    let prefix = last.trim_end_matches(|c: char| c.is_ascii_digit());
    let n: usize = last[prefix.len()..].parse().unwrap_or(0);
    format!("{prefix}{}", n + 1 + (i - f.params.len()))
}

fn param_position(f: &StdFunction, upper: &str) -> Option<usize> {
    if let Some(i) = f
        .params
        .iter()
        .position(|p| p.name.eq_ignore_ascii_case(upper))
    {
        return Some(i);
    }
    if !f.extensible {
        return None;
    }
    let last = f.params.last()?.name;
    let prefix = last.trim_end_matches(|c: char| c.is_ascii_digit());
    let n: usize = last[prefix.len()..].parse().ok()?;
    let rest = upper.strip_prefix(&prefix.to_ascii_uppercase())?;
    let k: usize = rest.parse().ok()?;
    (k > n).then(|| f.params.len() - 1 + (k - n))
}

fn param_pat(f: &StdFunction, i: usize) -> TyPat {
    f.params
        .get(i)
        .or(f.params.last())
        .map(|p| p.ty)
        .unwrap_or(TyPat::Var(0, GenericType::Any))
}

fn ret_var(f: &StdFunction) -> Option<u8> {
    match f.ret {
        TyPat::Var(k, _) => Some(k),
        TyPat::Elem(_) => None,
    }
}

/// The type an unbound result variable takes without context.
fn default_of(fam: GenericType) -> ElemType {
    match fam {
        GenericType::AnyReal => ElemType::Lreal,
        GenericType::AnyBit => ElemType::Dword,
        GenericType::AnyString | GenericType::AnyChars => ElemType::String,
        GenericType::AnyDuration => ElemType::Time,
        GenericType::AnyDate => ElemType::Dt,
        _ => ElemType::Dint,
    }
}
