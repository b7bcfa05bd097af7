//! Instruction List bodies: the type of the current result along the body.
//!
//! The parser gives every instruction its meaning in ST terms over the
//! current-result leaf (`ExprKind::IlCr`); here the instructions are walked
//! in order with the current result's state, each meaning is checked with
//! the ST rules while the leaf has the current result's type, and the state
//! moves on. The rules (docs/il.md):
//!
//! - at the start of the body the current result is undefined;
//! - an instruction that loads or combines gives it the type of its value;
//!   ST, STN, S, R, the FB input operators, conditional jumps and returns
//!   leave it as it is; CAL leaves it undefined;
//! - at a label it is the join of what reaches it from the instruction
//!   before (if that one continues) and from the jumps written before the
//!   label: the same type, else undefined;
//! - a jump written after its label must bring that label's type when the
//!   instruction at the label reads the current result.
//!
//! Reading an undefined current result is E1001; S, R and the conditional
//! operators need a BOOL one (E1002). After an error the current result has
//! the poisoned type, so nothing that follows from it is reported again.

use rustc_hash::FxHashMap;
use stc_diagnostics::{Code, Diagnostic, Span};
use stc_syntax::ast::{
    ArgKind, BinaryOp, ExprId, ExprKind, IlBody, IlCond, IlInstr, IlOp, IlOperator, IlSem, Stmt,
    StmtKind,
};
use stc_syntax::Symbol;

use crate::analyzer::{Scope, Sema};
use crate::types::{TypeId, TypeKind};
use crate::PouId;

/// The state of the current result.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
enum Cr {
    Ty(TypeId),
    Undefined(Why),
}

/// Why the current result is undefined, for the diagnostic's note.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
enum Why {
    Start,
    AfterCal(Span),
    /// At this label, reached with different types.
    Merge(Span),
    /// At this label, reached only by jumps written after it.
    OnlyLater(Span),
}

impl<'a> Sema<'a> {
    /// Checks the body; returns the type of the current result at its end
    /// (`None` if undefined there, `ERROR` if the end is not reached or
    /// after an error).
    pub(crate) fn il_body(&mut self, p: PouId, il: &'a IlBody) -> Option<TypeId> {
        let instrs = &il.instrs;
        // Labels: where each is, whether the code at it reads the current
        // result, and which are jumped to.
        let mut labels: FxHashMap<Symbol, usize> = FxHashMap::default();
        for (i, ins) in instrs.iter().enumerate() {
            let Some(l) = ins.label else { continue };
            if let Some(&first) = labels.get(&l.sym) {
                let name = self.spelled(l.sym, l.span);
                let first_span = instrs[first].label.map(|f| f.span).unwrap_or(l.span);
                self.emit(
                    Diagnostic::new(
                        Code::E1004,
                        l.span,
                        format!("label `{name}` is defined twice"),
                    )
                    .with_label("second definition")
                    .with_secondary(first_span, "first defined here"),
                );
            } else {
                labels.insert(l.sym, i);
            }
        }
        let reads_at = |i: usize| {
            instrs[i..]
                .iter()
                .find(|x| x.op != IlOp::None)
                .is_some_and(|x| self.il_reads_cr(x))
        };
        let label_reads: FxHashMap<Symbol, bool> =
            labels.iter().map(|(s, &i)| (*s, reads_at(i))).collect();
        let jumped: Vec<Symbol> = instrs
            .iter()
            .filter_map(|x| match &x.sem {
                IlSem::Jump { target, .. } => Some(target.sym),
                _ => None,
            })
            .collect();
        // A jump to a label that does not exist (E1003) may have meant any
        // label: none is then said to be unreachable.
        let lost_jump = jumped.iter().any(|s| !labels.contains_key(s));

        let scope = Scope::Pou(p);
        let mut forward: FxHashMap<Symbol, Vec<Cr>> = FxHashMap::default();
        let mut at_label: FxHashMap<Symbol, Cr> = FxHashMap::default();
        let mut cr = Cr::Undefined(Why::Start);
        let mut reachable = true;
        let mut unreachable_reported = false;
        for (i, ins) in instrs.iter().enumerate() {
            if let Some(l) = ins.label.filter(|l| labels.get(&l.sym) == Some(&i)) {
                let mut incoming = forward.remove(&l.sym).unwrap_or_default();
                if reachable {
                    incoming.push(cr);
                }
                cr = join(&incoming, l.span);
                at_label.insert(l.sym, cr);
                reachable = reachable || lost_jump || jumped.contains(&l.sym);
                unreachable_reported = false;
                // Values known before the label may not hold when a jump
                // arrives.
                self.body.known.clear();
            } else if !reachable && ins.op != IlOp::None && !unreachable_reported {
                unreachable_reported = true;
                let after = match instrs[..i].iter().rev().find(|x| x.op != IlOp::None) {
                    Some(IlInstr {
                        op: IlOp::Ret { .. },
                        ..
                    }) => "RET",
                    _ => "JMP",
                };
                self.emit(
                    Diagnostic::new(Code::W0105, ins.span, "unreachable instruction")
                        .with_label(format!("this can never run: it comes after {after}"))
                        .with_help("give it a label that a jump names, or remove it"),
                );
            }
            let mut ty = match cr {
                Cr::Ty(t) => t,
                Cr::Undefined(why) => {
                    if self.il_reads_cr(ins) {
                        self.il_undefined(ins, why);
                    }
                    TypeId::ERROR
                }
            };
            if il_needs_bool(ins) && ty != TypeId::ERROR && !self.types.is_bool(ty) {
                let shown = self.tname(ty);
                let what = self.il_op_name(ins);
                self.emit(
                    Diagnostic::new(
                        Code::E1002,
                        ins.span,
                        format!("`{what}` needs a BOOL current result, but it is {shown}"),
                    )
                    .with_label(format!("the current result is {shown}"))
                    .with_help("compare first (`GT 0`, `EQ x`) to get a BOOL"),
                );
                ty = TypeId::ERROR;
            }
            self.body.il_cr = Some(ty);
            match &ins.sem {
                IlSem::Nothing => {}
                IlSem::Load(v) => {
                    // `LD 0` then `ST i`: an untyped literal takes the type
                    // the next instruction gives the current result.
                    let expected = if self.is_flexible(*v, scope) {
                        self.il_expected_after(&instrs[i + 1..], scope)
                    } else {
                        None
                    };
                    let t = self.check_expr(*v, expected, scope);
                    if matches!(self.types.kind(t), TypeKind::Fb(_)) {
                        let span = self.ast.expr(*v).span;
                        self.emit(
                            Diagnostic::new(
                                Code::E0409,
                                span,
                                "a function block instance cannot be loaded: it is not a value",
                            )
                            .with_label("a function block instance")
                            .with_help(
                                "load one of its outputs (`LD inst.Q`), or call it with CAL",
                            ),
                        );
                        cr = Cr::Ty(TypeId::ERROR);
                    } else {
                        cr = Cr::Ty(t);
                    }
                }
                IlSem::Effect {
                    stmts,
                    undefined_after,
                } => {
                    self.stmts_pub(stmts, p);
                    if *undefined_after {
                        cr = Cr::Undefined(Why::AfterCal(ins.span));
                    }
                }
                IlSem::SetReset {
                    operand,
                    bool_form,
                    fb_form,
                } => {
                    // Which form: typed quietly first (the form checked
                    // next reports what is wrong with the operand).
                    let mark = self.diags.len();
                    let t = self.check_expr(*operand, None, scope);
                    self.diags.truncate(mark);
                    if matches!(self.types.kind(t), TypeKind::Fb(_)) {
                        self.il_fb_inputs.insert(*operand);
                        self.stmts_pub(fb_form, p);
                    } else {
                        self.stmts_pub(bool_form, p);
                    }
                }
                IlSem::Jump { cond, target } => {
                    if let Some(c) = cond {
                        self.check_expr(*c, None, scope);
                    }
                    match labels.get(&target.sym) {
                        None => {
                            let name = self.spelled(target.sym, target.span);
                            let names: Vec<String> =
                                labels.keys().map(|s| self.sym_name(*s)).collect();
                            let mut d = Diagnostic::new(
                                Code::E1003,
                                target.span,
                                format!("no label `{name}` in this body"),
                            )
                            .with_label("undefined label");
                            if let Some(s) =
                                self.did_you_mean(&name, names.iter().map(|s| s.as_str()))
                            {
                                d = d.with_help(format!("did you mean `{s}`?"));
                            }
                            self.emit(d);
                        }
                        Some(&at) if at > i => forward.entry(target.sym).or_default().push(cr),
                        Some(_) => {
                            let there = at_label.get(&target.sym).copied();
                            let reads = label_reads.get(&target.sym).copied().unwrap_or(false);
                            if reads {
                                self.il_backward(ins, target.sym, target.span, cr, there);
                            }
                        }
                    }
                    if cond.is_none() {
                        reachable = false;
                    }
                }
            }
            if matches!(
                ins.op,
                IlOp::Ret {
                    op: IlCond::Always,
                    ..
                }
            ) {
                reachable = false;
            }
        }
        self.body.il_cr = None;
        match cr {
            _ if !reachable => Some(TypeId::ERROR),
            Cr::Ty(t) => Some(t),
            Cr::Undefined(_) => None,
        }
    }

    /// An IL body inside a chart (an action's, or a transition's whose
    /// condition is the current result at the end, stored in `result`).
    pub(crate) fn il_in_chart(&mut self, p: PouId, il: &'a IlBody, result: Option<ExprId>) {
        for ins in &il.instrs {
            if let IlOp::Ret { op_span, .. } = &ins.op {
                self.emit(
                    Diagnostic::new(
                        Code::E1213,
                        *op_span,
                        "RET cannot stand in an action or a transition of a chart",
                    )
                    .with_label("would leave the whole POU, not only this body")
                    .with_help("jump to a label at the end of the body instead"),
                );
            }
        }
        let end = self.il_body(p, il);
        let Some(result) = result else { return };
        let at = il
            .instrs
            .iter()
            .rev()
            .find(|x| x.op != IlOp::None)
            .map_or(il.span, |x| x.span);
        let bool_ty = self.types.elem(stc_syntax::token::ElemType::Bool);
        let ty = match end {
            Some(t) if t == TypeId::ERROR || self.types.is_bool(t) => t,
            other => {
                let shown = match other {
                    Some(t) => self.tname(t),
                    None => "undefined".to_string(),
                };
                self.emit(
                    Diagnostic::new(
                        Code::E1210,
                        at,
                        format!(
                            "the condition of a transition in IL is the current result at its end, which must be BOOL, but it is {shown}"
                        ),
                    )
                    .with_label(format!("the current result here is {shown}"))
                    .with_help("end the body with a BOOL value: a comparison (`GT 0`) or a BOOL load"),
                );
                TypeId::ERROR
            }
        };
        self.check_lvalue(result, Scope::Pou(p), crate::calls::Write::Assign);
        self.il_results
            .insert(result, if ty == TypeId::ERROR { bool_ty } else { ty });
    }

    /// The type the next instruction wants the current result to have,
    /// if it reads it (without a label between): the target of ST, the
    /// operand of a combining operator, BOOL for the tests.
    fn il_expected_after(&mut self, rest: &'a [IlInstr], scope: Scope) -> Option<TypeId> {
        let next = rest.iter().find(|x| x.op != IlOp::None)?;
        if rest
            .iter()
            .take_while(|x| !std::ptr::eq(*x, next))
            .any(|x| x.label.is_some())
            || next.label.is_some()
        {
            return None;
        }
        let bool_ty = self.types.elem(stc_syntax::token::ElemType::Bool);
        let other = match &next.sem {
            IlSem::SetReset { .. } | IlSem::Jump { cond: Some(_), .. } => return Some(bool_ty),
            IlSem::Effect { stmts, .. } => match stmts.first().map(|s| &s.kind) {
                Some(StmtKind::Assign { target, value }) if self.has_cr(*value) => *target,
                Some(StmtKind::If { .. }) if il_needs_bool(next) => return Some(bool_ty),
                _ => return None,
            },
            IlSem::Load(w) => match &self.ast.expr(*w).kind {
                // NOT keeps the type: ask the instruction after it.
                ExprKind::Unary { operand, .. } if self.has_cr(*operand) => {
                    let at = rest.iter().position(|x| std::ptr::eq(x, next))?;
                    return self.il_expected_after(&rest[at + 1..], scope);
                }
                ExprKind::Binary { op, lhs, rhs } if self.has_cr(*lhs) => {
                    let rhs = match &self.ast.expr(*rhs).kind {
                        ExprKind::Unary { operand, .. } => *operand,
                        _ => *rhs,
                    };
                    let keeps_type = !matches!(
                        op,
                        BinaryOp::Eq
                            | BinaryOp::Ne
                            | BinaryOp::Lt
                            | BinaryOp::Le
                            | BinaryOp::Gt
                            | BinaryOp::Ge
                    );
                    // `LD 5.0` `DIV 4.0` `ST r`: the type comes after.
                    if keeps_type && self.is_flexible(rhs, scope) {
                        let at = rest.iter().position(|x| std::ptr::eq(x, next))?;
                        return self.il_expected_after(&rest[at + 1..], scope);
                    }
                    rhs
                }
                ExprKind::Call { callee, args } => {
                    // A user function: the type of its first input.
                    if let ExprKind::Name(f) = &self.ast.expr(*callee).kind {
                        if let Some(crate::analyzer::GlobalName::Pou(q)) =
                            self.find_global(*f).hit.map(|(g, _)| g)
                        {
                            self.resolve_pou(q);
                            let def = &self.pous[q.0 as usize];
                            if def.kind == stc_syntax::ast::PouKind::Function {
                                return def.positional_params().first().map(|v| def.var(*v).ty);
                            }
                        }
                    }
                    // A standard function: its other operands, else (ABS,
                    // MAX of literals...) what comes after; a conversion
                    // names its input type itself.
                    let conversion = match &self.ast.expr(*callee).kind {
                        ExprKind::Name(f) => {
                            let n = self.interner.key(f.sym).to_ascii_uppercase();
                            n.contains("_TO_") || n == "TRUNC"
                        }
                        _ => true,
                    };
                    if conversion {
                        return None;
                    }
                    match args.get(1).map(|a| &a.kind) {
                        Some(ArgKind::Positional(x)) if !self.is_flexible(*x, scope) => *x,
                        _ => {
                            let at = rest.iter().position(|x| std::ptr::eq(x, next))?;
                            return self.il_expected_after(&rest[at + 1..], scope);
                        }
                    }
                }
                _ => return None,
            },
            _ => return None,
        };
        if self.is_flexible(other, scope) {
            return None;
        }
        let mark = self.diags.len();
        let t = self.check_expr(other, None, scope);
        self.diags.truncate(mark);
        (t != TypeId::ERROR && self.types.scalar(t).is_some()).then_some(t)
    }

    /// E1001 at an instruction that reads an undefined current result.
    fn il_undefined(&mut self, ins: &IlInstr, why: Why) {
        let what = self.il_op_name(ins);
        let mut d = Diagnostic::new(
            Code::E1001,
            ins.span,
            format!("`{what}` reads the current result, which is undefined here"),
        )
        .with_label("the current result has no value here");
        d = match why {
            Why::Start => d.with_note("the body starts with no current result"),
            Why::AfterCal(s) => d.with_secondary(s, "a function block call leaves it undefined"),
            Why::Merge(s) => d.with_secondary(s, "this label is reached with different types"),
            Why::OnlyLater(s) => {
                d.with_secondary(s, "this label is reached only by jumps written after it")
            }
        };
        self.emit(d.with_help("load a value first (`LD x`)"));
    }

    /// A jump written after its label, whose instruction reads the current
    /// result: it must bring the type the label has.
    fn il_backward(&mut self, ins: &IlInstr, label: Symbol, span: Span, cr: Cr, there: Option<Cr>) {
        let poisoned = |c: Option<Cr>| c == Some(Cr::Ty(TypeId::ERROR));
        // (An undefined one was reported where the label's code reads it.)
        let undefined = matches!(there, None | Some(Cr::Undefined(_)));
        if poisoned(Some(cr)) || poisoned(there) || undefined || there == Some(cr) {
            return;
        }
        let text = |s: &Self, c: Cr| match c {
            Cr::Ty(t) => s.tname(t),
            Cr::Undefined(_) => "undefined".to_string(),
        };
        let here = text(self, cr);
        let at = there
            .map(|c| text(self, c))
            .unwrap_or_else(|| "undefined".into());
        let name = self.spelled(label, span);
        self.emit(
            Diagnostic::new(
                Code::E1001,
                ins.span,
                format!(
                    "this jump brings a current result of type {here} to `{name}`, where it is {at}"
                ),
            )
            .with_label(format!("the current result is {here} here"))
            .with_help(format!(
                "the instruction at `{name}` reads the current result: load it there, or jump with the same type"
            )),
        );
    }

    /// The operator of an instruction as written in messages.
    fn il_op_name(&self, ins: &IlInstr) -> String {
        match &ins.op {
            IlOp::None => String::new(),
            IlOp::Simple { op, .. } => op.name().to_string(),
            IlOp::Paren { op, .. } => format!("{}(", op.name()),
            IlOp::Call { name, .. } | IlOp::FormalCall { name, .. } => {
                self.spelled(name.sym, name.span)
            }
            IlOp::Cal { op, .. } => format!("CAL{}", op.suffix()),
            IlOp::Jump { op, .. } => format!("JMP{}", op.suffix()),
            IlOp::Ret { op, .. } => format!("RET{}", op.suffix()),
        }
    }

    /// Whether the meaning of an instruction reads the current result.
    pub(crate) fn il_reads_cr(&self, ins: &IlInstr) -> bool {
        match &ins.sem {
            IlSem::Nothing => false,
            IlSem::Load(v) => self.has_cr(*v),
            IlSem::Effect { stmts, .. }
            | IlSem::SetReset {
                bool_form: stmts, ..
            } => stmts.iter().any(|s| self.stmt_has_cr(s)),
            IlSem::Jump { cond, .. } => cond.is_some(),
        }
    }

    fn stmt_has_cr(&self, s: &Stmt) -> bool {
        match &s.kind {
            StmtKind::Assign { target, value } => self.has_cr(*target) || self.has_cr(*value),
            StmtKind::Call(e) => self.has_cr(*e),
            StmtKind::If {
                branches,
                else_body,
            } => {
                branches
                    .iter()
                    .any(|b| self.has_cr(b.cond) || b.body.iter().any(|s| self.stmt_has_cr(s)))
                    || else_body
                        .as_ref()
                        .is_some_and(|b| b.iter().any(|s| self.stmt_has_cr(s)))
            }
            _ => false,
        }
    }

    fn has_cr(&self, e: ExprId) -> bool {
        match &self.ast.expr(e).kind {
            ExprKind::IlCr => true,
            ExprKind::Unary { operand, .. } => self.has_cr(*operand),
            ExprKind::Binary { lhs, rhs, .. } => self.has_cr(*lhs) || self.has_cr(*rhs),
            ExprKind::Paren(i) => self.has_cr(*i),
            ExprKind::Call { args, .. } => args.iter().any(|a| match &a.kind {
                ArgKind::Positional(v) | ArgKind::Input { value: v, .. } => self.has_cr(*v),
                ArgKind::Output { .. } => false,
            }),
            _ => false,
        }
    }

    /// Whether some instruction of an IL body writes the function result
    /// (for W0106: with jumps, paths are not followed).
    pub(crate) fn il_assigns_result(&self, p: PouId, il: &IlBody) -> bool {
        fn walk(s: &Sema<'_>, p: PouId, list: &[Stmt]) -> bool {
            list.iter().any(|st| match &st.kind {
                StmtKind::Assign { target, .. } => s.is_result_pub(p, *target),
                StmtKind::If {
                    branches,
                    else_body,
                } => {
                    branches.iter().any(|b| walk(s, p, &b.body))
                        || else_body.as_ref().is_some_and(|b| walk(s, p, b))
                }
                StmtKind::Call(e) => s.calls.get(e).is_some_and(|c| {
                    c.args.iter().any(|a| match a.kind {
                        crate::BoundArgKind::Output { target, .. }
                        | crate::BoundArgKind::InOut(target) => s.is_result_pub(p, target),
                        _ => false,
                    })
                }),
                _ => false,
            })
        }
        il.instrs.iter().any(|i| match &i.sem {
            IlSem::Effect { stmts, .. } => walk(self, p, stmts),
            IlSem::SetReset {
                operand, bool_form, ..
            } => !self.il_fb_inputs.contains(operand) && walk(self, p, bool_form),
            _ => false,
        })
    }
}

/// The join of the current results reaching a label.
fn join(incoming: &[Cr], label: Span) -> Cr {
    if incoming.contains(&Cr::Ty(TypeId::ERROR)) {
        return Cr::Ty(TypeId::ERROR);
    }
    match incoming.first() {
        None => Cr::Undefined(Why::OnlyLater(label)),
        Some(&first) if incoming.iter().all(|c| *c == first) => first,
        Some(_) => Cr::Undefined(Why::Merge(label)),
    }
}

/// Whether the operator tests the current result as a BOOL.
fn il_needs_bool(ins: &IlInstr) -> bool {
    match &ins.op {
        IlOp::Simple { op, .. } => matches!(op, IlOperator::S | IlOperator::R),
        IlOp::Jump { op, .. } | IlOp::Cal { op, .. } | IlOp::Ret { op, .. } => {
            *op != IlCond::Always
        }
        _ => false,
    }
}
