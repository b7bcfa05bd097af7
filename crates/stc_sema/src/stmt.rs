//! Statements and POU bodies.

use stc_diagnostics::{Code, Diagnostic, Span};
use stc_syntax::ast::{CaseLabel, ExprKind, Pou, Stmt, StmtKind};
use stc_syntax::token::ElemType;
use stc_values::Value;

use crate::analyzer::{Body, Scope, Sema};

use crate::calls::Write;
use crate::expr::Ctx;
use crate::types::{TypeId, TypeKind};
use crate::{PouId, Res};

impl<'a> Sema<'a> {
    pub(crate) fn check_body(&mut self, p: PouId, pou: &'a Pou) {
        self.resolve_pou(p);
        self.body = Body {
            current: Some(p),
            ..Body::default()
        };
        self.stmts(&pou.body, p);
        if let Some(il) = &pou.il {
            self.il_body(p, il);
        }
        if let Some(sfc) = &pou.sfc {
            self.check_sfc(p, pou, sfc);
        }
        self.pou_warnings(p, pou);
    }

    /// The statements an Instruction List instruction means.
    pub(crate) fn stmts_pub(&mut self, list: &'a [Stmt], p: PouId) {
        self.stmts(list, p);
    }

    fn stmts(&mut self, list: &'a [Stmt], p: PouId) {
        let mut ended: Option<&'static str> = None;
        let mut reported = false;
        for s in list {
            if let Some(after) = ended {
                if !reported && !matches!(s.kind, StmtKind::Empty) {
                    reported = true;
                    self.emit(
                        Diagnostic::new(Code::W0105, s.span, "unreachable statement")
                            .with_label(format!("this can never run: it comes after {after}")),
                    );
                }
            }
            self.stmt(s, p);
            if ended.is_none() {
                ended = match s.kind {
                    StmtKind::Return => Some("RETURN"),
                    StmtKind::Exit => Some("EXIT"),
                    StmtKind::Continue => Some("CONTINUE"),
                    _ => None,
                };
            }
        }
    }

    fn stmt(&mut self, s: &'a Stmt, p: PouId) {
        let scope = Scope::Pou(p);
        match &s.kind {
            StmtKind::Empty | StmtKind::Error => {}
            StmtKind::Il { body, result } => self.il_in_chart(p, body, *result),
            StmtKind::Unsupported(exprs) => {
                // Reported by the parser; its names still resolve.
                for &e in exprs {
                    self.check_expr(e, Some(TypeId::ERROR), scope);
                }
            }
            StmtKind::AssignAttempt { target, value } => {
                self.assign_attempt(*target, *value, p);
            }
            StmtKind::Assign { target, value }
                if self.property_write(*target, *value, scope).is_some() =>
            {
                // `inst.p := v`: a call of the property's SET.
                self.forget_writes_in(*target, p);
                self.forget_writes_in(*value, p);
            }
            StmtKind::Assign { target, value } => {
                let tt = self.check_lvalue(*target, scope, Write::Assign);
                let vt = self.check_expr(*value, Some(tt), scope);
                let mut known = None;
                if tt != TypeId::ERROR && vt != TypeId::ERROR {
                    let what = self.target_name(*target);
                    if self.coerce(*value, vt, tt, Ctx::Assign, &what) {
                        let span = self.ast.expr(*value).span;
                        self.check_ptr_store(Some(*target), *value, tt, span);
                        let c = self
                            .prop_value(*value)
                            .and_then(|c| self.convert_const(&c, vt, tt));
                        if self.check_subrange(&c, tt, self.ast.expr(*value).span) {
                            known = c;
                        }
                    }
                }
                self.forget_writes_in(*value, p);
                if let Some(v) = self.root_var(*target) {
                    let plain = matches!(self.ast.expr(*target).kind, ExprKind::Name(_));
                    // References (in-outs, externals) may change behind a call.
                    let tracked = plain
                        && self.types.scalar(tt).is_some()
                        && !self
                            .ref_taken
                            .contains(&self.pous[p.0 as usize].var(v).name)
                        && !matches!(
                            self.pous[p.0 as usize].var(v).section,
                            crate::Section::InOut | crate::Section::External
                        );
                    match known {
                        Some(c) if tracked => {
                            self.body.known.insert(v, c);
                        }
                        _ => {
                            self.body.known.remove(&v);
                        }
                    }
                }
            }
            StmtKind::Call(e) => {
                match &self.ast.expr(*e).kind {
                    ExprKind::Call { callee, args } => {
                        let t = self.call(*e, *callee, args, None, scope, true);
                        self.set_type(*e, t);
                    }
                    _ => {
                        self.check_expr(*e, None, scope);
                    }
                }
                self.forget_writes_in(*e, p);
            }
            StmtKind::If {
                branches,
                else_body,
            } => {
                let mut ends = Vec::new();
                for b in branches {
                    self.condition(b.cond, scope, "IF", false);
                    self.forget_writes_in(b.cond, p);
                    let at_branch = self.body.known.clone();
                    self.stmts(&b.body, p);
                    ends.push(std::mem::replace(&mut self.body.known, at_branch));
                }
                if let Some(e) = else_body {
                    self.stmts(e, p);
                }
                ends.push(std::mem::take(&mut self.body.known));
                self.body.known = meet(ends);
            }
            StmtKind::Case {
                selector,
                arms,
                else_body,
            } => {
                let st = self.check_expr(*selector, None, scope);
                let sel_ok = st == TypeId::ERROR
                    || self.types.is_integer(st)
                    || matches!(self.types.kind(st), TypeKind::Enum { .. })
                    || self
                        .types
                        .numeric(st)
                        .is_some_and(|t| stc_values::is_bit_string(t) && t != ElemType::Bool);
                if !sel_ok {
                    let span = self.ast.expr(*selector).span;
                    let msg = format!(
                        "a CASE selector must be an integer or an enumeration, not {}",
                        self.tname(st)
                    );
                    self.emit(Diagnostic::new(Code::E0203, span, msg));
                }
                let expected = if sel_ok { st } else { TypeId::ERROR };
                self.forget_writes_in(*selector, p);
                let at_case = self.body.known.clone();
                let mut ends = Vec::new();
                let mut seen: Vec<(i128, i128, Span)> = Vec::new();
                for arm in arms {
                    for label in &arm.labels {
                        let (lo, hi) = match label {
                            CaseLabel::Value(v) => (*v, *v),
                            CaseLabel::Range(a, b) => (*a, *b),
                        };
                        let mut vals = [None, None];
                        for (k, e) in [lo, hi].into_iter().enumerate() {
                            if k == 1 && lo == hi {
                                vals[1] = vals[0];
                                break;
                            }
                            vals[k] = self.case_label(e, expected, scope);
                        }
                        if let [Some(a), Some(b)] = vals {
                            let span = self.ast.expr(lo).span.to(self.ast.expr(hi).span);
                            // A label the selector's subrange cannot reach
                            // is an error, as one outside an elementary
                            // selector's range is.
                            if let TypeKind::Subrange {
                                lo: min, hi: max, ..
                            } = self.types.kind(expected).clone()
                            {
                                if a.min(b) < min || a.max(b) > max {
                                    let shown = if a == b {
                                        format!("{a}")
                                    } else {
                                        format!("{a}..{b}")
                                    };
                                    let msg = format!(
                                        "the CASE label {shown} is outside the subrange {min}..{max} of the selector's type {}",
                                        self.tname(expected)
                                    );
                                    self.emit(
                                        Diagnostic::new(Code::E0702, span, msg)
                                            .with_label("the selector never has this value"),
                                    );
                                    continue;
                                }
                            }
                            if let Some(&(_, _, prev)) =
                                seen.iter().find(|(x, y, _)| a <= *y && *x <= b)
                            {
                                self.emit(
                                    Diagnostic::new(
                                        Code::E0602,
                                        span,
                                        "this CASE label overlaps an earlier one",
                                    )
                                    .with_label("selects a value already selected")
                                    .with_secondary(prev, "earlier label"),
                                );
                            } else {
                                seen.push((a.min(b), a.max(b), span));
                            }
                        }
                    }
                    self.body.known = at_case.clone();
                    self.stmts(&arm.body, p);
                    ends.push(std::mem::take(&mut self.body.known));
                }
                self.body.known = at_case;
                if let Some(e) = else_body {
                    self.stmts(e, p);
                }
                ends.push(std::mem::take(&mut self.body.known));
                self.body.known = meet(ends);
            }
            StmtKind::For {
                var,
                from,
                to,
                by,
                body,
            } => {
                let var_ty = match self.pous[p.0 as usize].lookup(var.sym) {
                    Some(v) => {
                        self.used.insert((p, v));
                        let vd = self.pous[p.0 as usize].var(v).clone();
                        let shown = self.sym_name(vd.name);
                        if !self.types.is_integer(vd.ty) && vd.ty != TypeId::ERROR {
                            let msg = format!(
                                "the FOR control variable `{shown}` must be an integer, not {}",
                                self.tname(vd.ty)
                            );
                            self.emit(Diagnostic::new(Code::E0204, var.span, msg));
                            TypeId::ERROR
                        } else if vd.constant {
                            self.error(
                                Code::E0304,
                                var.span,
                                format!(
                                    "`{shown}` is a constant and cannot be a FOR control variable"
                                ),
                            );
                            TypeId::ERROR
                        } else if self.body.for_vars.contains(&v) {
                            self.error(Code::E0306, var.span, format!("`{shown}` is already the control variable of an enclosing FOR loop"));
                            TypeId::ERROR
                        } else {
                            vd.ty
                        }
                    }
                    None => {
                        let shown = self.spelled(var.sym, var.span);
                        self.error(
                            Code::E0101,
                            var.span,
                            format!("undeclared variable `{shown}`"),
                        );
                        TypeId::ERROR
                    }
                };
                for (e, what) in [(Some(*from), "start"), (Some(*to), "end"), (*by, "step")] {
                    let Some(e) = e else { continue };
                    let t = self.check_expr(e, Some(var_ty), scope);
                    if t == TypeId::ERROR || var_ty == TypeId::ERROR {
                        continue;
                    }
                    let ok = matches!(
                        self.types.compat(t, var_ty, self.opts.iec2),
                        crate::Compat::Same | crate::Compat::Widen
                    );
                    if !ok {
                        let span = self.ast.expr(e).span;
                        let msg = format!(
                            "the FOR {what} is {}, but the control variable is {}",
                            self.tname(t),
                            self.tname(var_ty)
                        );
                        self.emit(Diagnostic::new(Code::E0204, span, msg));
                    } else if t != var_ty {
                        self.coercions.insert(e, var_ty);
                    }
                }
                if let Some(b) = by {
                    if matches!(self.consts.get(b), Some(Value::Int(0))) {
                        let span = self.ast.expr(*b).span;
                        self.emit(
                            Diagnostic::new(
                                Code::E0604,
                                span,
                                "a FOR loop with a step of zero never ends",
                            )
                            .with_label("zero step"),
                        );
                    }
                }
                let control = self.pous[p.0 as usize].lookup(var.sym);
                self.forget_assigned_in(body, p);
                if let Some(v) = control {
                    self.body.known.remove(&v);
                }
                self.body.loop_depth += 1;
                if let Some(v) = control {
                    self.body.for_vars.push(v);
                }
                let at_loop = self.body.known.clone();
                self.stmts(body, p);
                self.body.known = at_loop;
                if control.is_some() {
                    self.body.for_vars.pop();
                }
                self.body.loop_depth -= 1;
            }
            StmtKind::While { cond, body } => {
                self.forget_assigned_in(body, p);
                let mid_exit = is_literal_bool(self.ast, *cond, true) && leaves_loop(body);
                self.condition(*cond, scope, "WHILE", mid_exit);
                self.forget_writes_in(*cond, p);
                let at_loop = self.body.known.clone();
                self.body.loop_depth += 1;
                self.stmts(body, p);
                self.body.loop_depth -= 1;
                self.body.known = at_loop;
            }
            StmtKind::Repeat { body, until } => {
                self.forget_assigned_in(body, p);
                self.body.loop_depth += 1;
                self.stmts(body, p);
                self.body.loop_depth -= 1;
                let mid_exit = is_literal_bool(self.ast, *until, false) && leaves_loop(body);
                self.condition(*until, scope, "UNTIL", mid_exit);
                self.forget_writes_in(*until, p);
            }
            StmtKind::Exit | StmtKind::Continue => {
                if self.body.loop_depth == 0 {
                    let word = if matches!(s.kind, StmtKind::Exit) {
                        "EXIT"
                    } else {
                        "CONTINUE"
                    };
                    self.emit(
                        Diagnostic::new(Code::E0601, s.span, format!("{word} outside a loop"))
                            .with_help("EXIT and CONTINUE work in FOR, WHILE and REPEAT loops; use RETURN to leave the POU"),
                    );
                }
            }
            StmtKind::Return => {}
        }
    }

    /// The value an expression certainly has here: its folded constant, or
    /// one computed from the propagated values of local variables.
    pub(crate) fn prop_value(&self, e: stc_syntax::ast::ExprId) -> Option<Value> {
        if let Some(v) = self.consts.get(&e) {
            return Some(v.clone());
        }
        let ty = self.expr_types.get(e.index()).copied()?;
        let v = match &self.ast.expr(e).kind {
            ExprKind::Name(_) => match self.resolutions.get(&e) {
                Some(Res::Var(v)) => self.body.known.get(v).cloned(),
                _ => None,
            },
            ExprKind::Paren(i) => self.prop_value(*i),
            ExprKind::Unary { op, operand } => {
                let x = self.prop_value(*operand)?;
                let s = self.types.scalar(ty)?;
                let op = match op {
                    stc_syntax::ast::UnaryOp::Neg => stc_values::UnOp::Neg,
                    stc_syntax::ast::UnaryOp::Not => stc_values::UnOp::Not,
                    stc_syntax::ast::UnaryOp::Plus => return Some(x),
                };
                stc_values::unary(op, s, &x).ok().map(|o| o.value)
            }
            ExprKind::Binary { op, lhs, rhs } => {
                let (a, b) = (self.prop_value(*lhs)?, self.prop_value(*rhs)?);
                let lt = self
                    .coercions
                    .get(lhs)
                    .copied()
                    .unwrap_or(*self.expr_types.get(lhs.index())?);
                let rt = self
                    .coercions
                    .get(rhs)
                    .copied()
                    .unwrap_or(*self.expr_types.get(rhs.index())?);
                let (ls, rs, res) = (
                    self.types.scalar(lt)?,
                    self.types.scalar(rt)?,
                    self.types.scalar(ty)?,
                );
                stc_values::binary(crate::expr::bin_op(*op), ls, &a, rs, &b, res)
                    .ok()
                    .map(|o| o.value)
            }
            _ => None,
        }?;
        // The value after the expression's own implicit conversion.
        match (self.coercions.get(&e), self.types.scalar(ty)) {
            (Some(&to), Some(from)) => stc_values::convert(from, self.types.scalar(to)?, &v).ok(),
            _ => Some(v),
        }
    }

    /// Forgets the propagated values of variables written by calls inside an
    /// expression (outputs and in-outs).
    fn forget_writes_in(&mut self, e: stc_syntax::ast::ExprId, p: PouId) {
        let _ = p;
        match &self.ast.expr(e).kind {
            ExprKind::Call { args, callee } => {
                self.forget_writes_in(*callee, p);
                if let Some(call) = self.calls.get(&e) {
                    let written: Vec<stc_syntax::ast::ExprId> = call
                        .args
                        .iter()
                        .filter_map(|a| match a.kind {
                            crate::BoundArgKind::Output { target, .. }
                            | crate::BoundArgKind::InOut(target) => Some(target),
                            _ => None,
                        })
                        .collect();
                    let eno = call.eno.map(|(t, _)| t);
                    for t in written.into_iter().chain(eno) {
                        if let Some(v) = self.root_var(t) {
                            self.body.known.remove(&v);
                        }
                    }
                }
                for a in args.iter() {
                    if let stc_syntax::ast::ArgKind::Positional(v)
                    | stc_syntax::ast::ArgKind::Input { value: v, .. } = &a.kind
                    {
                        self.forget_writes_in(*v, p);
                    }
                }
            }
            ExprKind::Unary { operand, .. } => self.forget_writes_in(*operand, p),
            ExprKind::Binary { lhs, rhs, .. } => {
                self.forget_writes_in(*lhs, p);
                self.forget_writes_in(*rhs, p);
            }
            ExprKind::Paren(i)
            | ExprKind::Member { base: i, .. }
            | ExprKind::PartialAccess { base: i, .. } => self.forget_writes_in(*i, p),
            ExprKind::Index { base, indices } => {
                self.forget_writes_in(*base, p);
                for i in indices.iter() {
                    self.forget_writes_in(*i, p);
                }
            }
            _ => {}
        }
    }

    /// Before a loop: forget every variable the loop may assign, since its
    /// body may run any number of times.
    fn forget_assigned_in(&mut self, list: &'a [Stmt], p: PouId) {
        for s in list {
            match &s.kind {
                StmtKind::Assign { target, .. } => self.forget_named(*target, p),
                StmtKind::Call(e) => self.forget_call_targets(*e, p),
                StmtKind::If {
                    branches,
                    else_body,
                } => {
                    for b in branches {
                        self.forget_assigned_in(&b.body, p);
                    }
                    if let Some(e) = else_body {
                        self.forget_assigned_in(e, p);
                    }
                }
                StmtKind::Case {
                    arms, else_body, ..
                } => {
                    for a in arms {
                        self.forget_assigned_in(&a.body, p);
                    }
                    if let Some(e) = else_body {
                        self.forget_assigned_in(e, p);
                    }
                }
                StmtKind::For { var, body, .. } => {
                    if let Some(v) = self.pous[p.0 as usize].lookup(var.sym) {
                        self.body.known.remove(&v);
                    }
                    self.forget_assigned_in(body, p);
                }
                StmtKind::While { body, .. } | StmtKind::Repeat { body, .. } => {
                    self.forget_assigned_in(body, p)
                }
                _ => {}
            }
        }
    }

    /// Forgets the variable at the root of an assignment target, by name
    /// (the target may not be resolved yet).
    fn forget_named(&mut self, mut e: stc_syntax::ast::ExprId, p: PouId) {
        loop {
            match &self.ast.expr(e).kind {
                ExprKind::Member { base, .. }
                | ExprKind::Index { base, .. }
                | ExprKind::PartialAccess { base, .. } => e = *base,
                ExprKind::Paren(i) => e = *i,
                ExprKind::Name(id) => {
                    if let Some(v) = self.pous[p.0 as usize].lookup(id.sym) {
                        self.body.known.remove(&v);
                    }
                    return;
                }
                _ => return,
            }
        }
    }

    /// Forgets every plain variable passed to a call (it may be an output or
    /// an in-out, which is not known before the call is resolved).
    fn forget_call_targets(&mut self, e: stc_syntax::ast::ExprId, p: PouId) {
        if let ExprKind::Call { args, .. } = &self.ast.expr(e).kind {
            for a in args.iter() {
                match &a.kind {
                    stc_syntax::ast::ArgKind::Output { target, .. } => {
                        self.forget_named(*target, p)
                    }
                    stc_syntax::ast::ArgKind::Positional(v)
                    | stc_syntax::ast::ArgKind::Input { value: v, .. } => {
                        self.forget_named(*v, p);
                        self.forget_call_targets(*v, p);
                    }
                }
            }
        }
    }

    /// A CASE label: a constant of the selector's type.
    fn case_label(
        &mut self,
        e: stc_syntax::ast::ExprId,
        sel: TypeId,
        scope: Scope,
    ) -> Option<i128> {
        let t = self.check_expr(e, Some(sel), scope);
        if t == TypeId::ERROR || sel == TypeId::ERROR {
            return None;
        }
        let span = self.ast.expr(e).span;
        let ok = matches!(
            self.types.compat(t, sel, false),
            crate::Compat::Same | crate::Compat::Widen
        );
        if !ok {
            let msg = format!(
                "this CASE label is {}, but the selector is {}",
                self.tname(t),
                self.tname(sel)
            );
            self.emit(Diagnostic::new(Code::E0203, span, msg));
            return None;
        }
        match self.consts.get(&e) {
            Some(Value::Int(v)) => Some(*v),
            Some(_) => None,
            None => {
                self.emit(
                    Diagnostic::new(Code::E0603, span, "a CASE label must be a constant")
                        .with_help("use literals, enumeration values or VAR CONSTANT names"),
                );
                None
            }
        }
    }

    /// A BOOL condition; a constant one is a warning, except the loop with
    /// its exit in the middle (`mid_exit`): `WHILE TRUE DO ... EXIT ...` or
    /// `REPEAT ... UNTIL FALSE` whose body has an EXIT or RETURN.
    fn condition(&mut self, e: stc_syntax::ast::ExprId, scope: Scope, what: &str, mid_exit: bool) {
        let bool_ty = self.types.elem(ElemType::Bool);
        let t = self.check_expr(e, Some(bool_ty), scope);
        let span = self.ast.expr(e).span;
        if t != TypeId::ERROR && !self.types.is_bool(t) {
            let msg = format!(
                "the condition of {what} must be BOOL, not {}",
                self.tname(t)
            );
            self.emit(
                Diagnostic::new(Code::E0202, span, msg)
                    .with_label(format!("this is {}", self.tname(t))),
            );
            return;
        }
        if mid_exit {
            return;
        }
        if let Some(Value::Bool(b)) = self.consts.get(&e) {
            let v = if *b { "TRUE" } else { "FALSE" };
            self.emit(
                Diagnostic::new(Code::W0108, span, format!("this condition is always {v}"))
                    .with_label(format!("always {v}")),
            );
        }
    }

    /// How the target of an assignment is named in messages.
    fn target_name(&self, e: stc_syntax::ast::ExprId) -> String {
        let text = self.sources.slice(self.ast.expr(e).span);
        if text.len() <= 40 {
            format!("`{text}`")
        } else {
            "the target".into()
        }
    }

    pub(crate) fn root_var(&self, mut e: stc_syntax::ast::ExprId) -> Option<crate::VarId> {
        loop {
            match &self.ast.expr(e).kind {
                ExprKind::Member { base, .. }
                | ExprKind::Index { base, .. }
                | ExprKind::PartialAccess { base, .. } => e = *base,
                ExprKind::Paren(i) => e = *i,
                _ => break,
            }
        }
        match self.resolutions.get(&e) {
            Some(Res::Var(v)) => Some(*v),
            _ => None,
        }
    }
}

/// Whether an expression is the literal TRUE (or FALSE), in parentheses or
/// not.
fn is_literal_bool(ast: &stc_syntax::ast::Ast, e: stc_syntax::ast::ExprId, b: bool) -> bool {
    match &ast.expr(e).kind {
        ExprKind::Literal(stc_syntax::ast::Literal {
            value: stc_syntax::ast::LitValue::Bool(v),
            prefix: None,
        }) => *v == b,
        ExprKind::Paren(i) => is_literal_bool(ast, *i, b),
        _ => false,
    }
}

/// Whether a loop body can leave the loop: a RETURN anywhere, or an EXIT
/// that is not inside a nested loop.
fn leaves_loop(body: &[Stmt]) -> bool {
    fn walk(list: &[Stmt], nested: bool) -> bool {
        list.iter().any(|s| match &s.kind {
            StmtKind::Return => true,
            StmtKind::Exit => !nested,
            StmtKind::If {
                branches,
                else_body,
            } => {
                branches.iter().any(|b| walk(&b.body, nested))
                    || else_body.as_deref().is_some_and(|e| walk(e, nested))
            }
            StmtKind::Case {
                arms, else_body, ..
            } => {
                arms.iter().any(|a| walk(&a.body, nested))
                    || else_body.as_deref().is_some_and(|e| walk(e, nested))
            }
            StmtKind::For { body, .. }
            | StmtKind::While { body, .. }
            | StmtKind::Repeat { body, .. } => walk(body, true),
            _ => false,
        })
    }
    walk(body, false)
}

/// The values known on every one of several paths that join.
fn meet(
    mut ends: Vec<rustc_hash::FxHashMap<crate::VarId, Value>>,
) -> rustc_hash::FxHashMap<crate::VarId, Value> {
    let Some(mut acc) = ends.pop() else {
        return Default::default();
    };
    for e in ends {
        acc.retain(|k, v| e.get(k) == Some(v));
    }
    acc
}
