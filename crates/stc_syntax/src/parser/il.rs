//! Instruction List bodies (IEC 61131-3 2nd edition 3.2, seed 003 3.2).
//!
//! IL is line-oriented: an instruction is `[label:] operator [operand]` on
//! one line; only a parenthesised sequence (`AND(` ... `)`) and the
//! parameter list of a call span lines. The lexer drops line breaks, so the
//! parser asks the text whether one separates two tokens.
//!
//! Each instruction is kept as written ([`IlOp`], for the printer and the
//! dump) and with its meaning over the current result ([`IlSem`]), built
//! here from ordinary ST expressions and statements around
//! [`ExprKind::IlCr`]: the analyser and the IR then treat IL with the ST
//! rules. A parenthesised sequence, and a sequence given as a parameter, is
//! composed into one expression (`AND( LD b OR c )` is `CR AND (b OR c)`),
//! which is why only loads, operators and function calls may stand in one.
//!
//! The operator names are not reserved: they are recognised by their place
//! at the start of an instruction, so `LD LD` loads a variable named `LD`.

use stc_diagnostics::{Code, Diagnostic, Span};

use super::{is_item_end, is_item_start, Parser};
use crate::ast::{
    Arg, ArgKind, CondBranch, ExprId, ExprKind, Ident, IlArg, IlArgKind, IlArgValue, IlBody,
    IlCallArgs, IlCond, IlInstr, IlOp, IlOperator, IlSem, LitValue, Literal, Stmt, StmtKind,
    UnaryOp,
};
use crate::token::{Keyword, TokenKind};

/// The words of the jump, call and return operators with their modifier.
fn control_word(w: &str) -> Option<(&'static str, IlCond)> {
    let all = [
        ("JMP", IlCond::Always),
        ("JMPC", IlCond::IfTrue),
        ("JMPCN", IlCond::IfFalse),
        ("CAL", IlCond::Always),
        ("CALC", IlCond::IfTrue),
        ("CALCN", IlCond::IfFalse),
        ("RET", IlCond::Always),
        ("RETC", IlCond::IfTrue),
        ("RETCN", IlCond::IfFalse),
    ];
    all.into_iter()
        .find(|(n, _)| n.eq_ignore_ascii_case(w))
        .map(|(n, c)| (&n[..3], c))
}

impl Parser<'_> {
    /// The body of a POU in IL, up to its END keyword.
    pub(crate) fn il_body(&mut self) -> IlBody {
        let start = self.tok().span();
        let mut instrs = Vec::new();
        while !self.il_body_end() && !self.aborted {
            let before = self.pos;
            if let Some(i) = self.il_instr(false) {
                instrs.push(i);
            }
            if self.pos == before {
                self.bump();
            }
        }
        IlBody {
            instrs,
            span: start.to(self.prev().span()),
        }
    }

    fn il_body_end(&self) -> bool {
        let k = self.kind();
        if self.in_chart_il && self.at_sfc_end() {
            return true;
        }
        k == TokenKind::Eof
            || is_item_end(k)
            || is_item_start(k)
            || matches!(k, TokenKind::Kw(kw) if kw.name().starts_with("END_"))
            || super::is_var_block_start(k)
    }

    /// Whether the current token starts a new line (or ends the body).
    fn il_line_end(&self) -> bool {
        self.il_body_end() || self.pos == 0 || self.newline_between(self.prev(), self.tok())
    }

    /// After an instruction: the line must end here (in a nested sequence,
    /// a `)` may close it on the same line).
    fn il_end_instr(&mut self, nested: bool) {
        if self.il_line_end() || (nested && self.at(TokenKind::RParen)) {
            return;
        }
        self.expected("the end of the line after an IL instruction");
        while !self.il_line_end() {
            self.bump();
        }
    }

    fn il_instr(&mut self, nested: bool) -> Option<IlInstr> {
        let first = self.tok();
        let mut label = None;
        if self.at(TokenKind::Ident) && self.nth_kind(1) == TokenKind::Colon && !nested {
            label = Some(self.intern_token(first));
            self.bump();
            self.bump();
            if self.il_line_end() {
                return Some(IlInstr {
                    label,
                    op: IlOp::None,
                    span: first.span().to(self.prev().span()),
                    sem: IlSem::Nothing,
                });
            }
        }
        let (op, sem) = self.il_operation(nested)?;
        let span = first.span().to(self.prev().span());
        self.il_end_instr(nested);
        Some(IlInstr {
            label,
            op,
            span,
            sem,
        })
    }

    /// The operation of an instruction and its meaning (over a fresh
    /// current-result leaf; nested sequences are composed by the caller).
    fn il_operation(&mut self, nested: bool) -> Option<(IlOp, IlSem)> {
        let t = self.tok();
        let start = t.span();
        let op = match t.kind {
            TokenKind::Amp => {
                self.bump();
                // `&N x`: the N written against the `&`.
                let n = self.tok();
                if n.kind == TokenKind::Ident
                    && n.lo == t.hi
                    && self.text_of(n).eq_ignore_ascii_case("N")
                {
                    self.bump();
                    IlOperator::Andn
                } else {
                    IlOperator::And
                }
            }
            TokenKind::Kw(Keyword::And) => {
                self.bump();
                IlOperator::And
            }
            TokenKind::Kw(Keyword::Or) => {
                self.bump();
                IlOperator::Or
            }
            TokenKind::Kw(Keyword::Xor) => {
                self.bump();
                IlOperator::Xor
            }
            TokenKind::Kw(Keyword::Not) => {
                self.bump();
                IlOperator::Not
            }
            TokenKind::Kw(Keyword::Mod) => {
                self.bump();
                IlOperator::Mod
            }
            TokenKind::Ident => {
                let word = self.text_of(t);
                if let Some((kind, cond)) = control_word(word) {
                    if nested {
                        self.il_not_in_sequence(t.span());
                        return None;
                    }
                    self.bump();
                    return Some(self.il_control(kind, cond, t.span()));
                }
                let formal_next = self.nth_kind(1) == TokenKind::LParen
                    && matches!(self.nth_kind(2), TokenKind::Ident | TokenKind::Kw(_))
                    && matches!(self.nth_kind(3), TokenKind::Assign | TokenKind::Arrow)
                    || self.nth_kind(1) == TokenKind::LParen
                        && self.nth_kind(2) == TokenKind::Kw(Keyword::Not)
                        && self.nth_kind(4) == TokenKind::Arrow
                    || self.nth_kind(1) == TokenKind::LParen
                        && self.nth_kind(2) == TokenKind::RParen;
                match IlOperator::from_word(word) {
                    Some(op) if !formal_next => {
                        self.bump();
                        op
                    }
                    _ => {
                        self.bump();
                        let name = self.intern_token(t);
                        return Some(self.il_function_call(name));
                    }
                }
            }
            _ => {
                self.expected("an IL instruction");
                while !(self.il_line_end() || nested && self.at(TokenKind::RParen)) {
                    self.bump();
                }
                return None;
            }
        };
        let op_span = start.to(self.prev().span());
        if self.at(TokenKind::LParen) && op.takes_paren() && !self.il_line_end() {
            return Some(self.il_paren(op, op_span));
        }
        let operand = if self.il_line_end() || (nested && self.at(TokenKind::RParen)) {
            None
        } else {
            Some(self.il_operand())
        };
        let needs_operand = !matches!(op, IlOperator::Not);
        if needs_operand && operand.is_none() {
            self.report_always(
                Diagnostic::new(
                    Code::E0020,
                    op_span,
                    format!("`{}` needs an operand on its line", op.name()),
                )
                .with_label("operand missing"),
            );
        }
        if !needs_operand && operand.is_some() {
            let span = operand.map(|o| self.expr_span(o)).unwrap_or(op_span);
            self.report_always(
                Diagnostic::new(Code::E0020, span, "`NOT` takes no operand")
                    .with_label("unexpected operand"),
            );
        }
        let span = start.to(self.prev().span());
        let surface = IlOp::Simple {
            op,
            op_span,
            operand,
        };
        if nested
            && !matches!(op, IlOperator::Ld | IlOperator::Ldn | IlOperator::Not)
            && op.binary().is_none()
        {
            self.il_not_in_sequence(op_span);
            return None;
        }
        let sem = self.il_simple_sem(op, op_span, operand, span);
        Some((surface, sem))
    }

    fn il_not_in_sequence(&mut self, span: Span) {
        let d = Diagnostic::new(
            Code::E0020,
            span,
            "only loads, operators and function calls can stand in a parenthesised sequence",
        )
        .with_label("not allowed here")
        .with_help("a sequence in `( )` computes one value: store or jump after the `)`");
        self.report_always(d);
    }

    /// An operand: a literal (possibly signed), an enumeration value, a
    /// variable with its members and indices, a direct address.
    fn il_operand(&mut self) -> ExprId {
        if matches!(self.kind(), TokenKind::Minus | TokenKind::Plus)
            && matches!(
                self.nth_kind(1),
                TokenKind::Int | TokenKind::Real | TokenKind::BasedInt
            )
        {
            let sign = self.bump();
            let inner = self.postfix();
            let op = if sign.kind == TokenKind::Minus {
                UnaryOp::Neg
            } else {
                UnaryOp::Plus
            };
            let span = sign.span().to(self.expr_span(inner));
            let depth = self.depth_of(inner);
            return self.mk(ExprKind::Unary { op, operand: inner }, span, depth);
        }
        self.postfix()
    }

    fn il_cr(&mut self, span: Span) -> ExprId {
        self.mk(ExprKind::IlCr, span, 0)
    }

    fn il_not(&mut self, e: ExprId, span: Span) -> ExprId {
        let depth = self.depth_of(e);
        self.mk(
            ExprKind::Unary {
                op: UnaryOp::Not,
                operand: e,
            },
            span,
            depth,
        )
    }

    /// The value a combining operator gives from `cr` and its operand.
    fn il_combine(&mut self, op: IlOperator, cr: ExprId, rhs: ExprId, span: Span) -> ExprId {
        let Some((bop, negate)) = op.binary() else {
            return cr;
        };
        let rhs = if negate { self.il_not(rhs, span) } else { rhs };
        let depth = self.depth_of(cr).max(self.depth_of(rhs));
        self.mk(
            ExprKind::Binary {
                op: bop,
                lhs: cr,
                rhs,
            },
            span,
            depth,
        )
    }

    fn il_bool(&mut self, b: bool, span: Span) -> ExprId {
        self.mk(
            ExprKind::Literal(Literal {
                value: LitValue::Bool(b),
                prefix: None,
            }),
            span,
            0,
        )
    }

    fn il_if(&mut self, cond: IlCond, span: Span, body: Vec<Stmt>) -> Vec<Stmt> {
        let leaf = self.il_cr(span);
        let cond = match cond {
            IlCond::Always => return body,
            IlCond::IfTrue => leaf,
            IlCond::IfFalse => self.il_not(leaf, span),
        };
        vec![Stmt {
            kind: StmtKind::If {
                branches: vec![CondBranch { cond, body }],
                else_body: None,
            },
            span,
        }]
    }

    /// The meaning of `op operand` at the top level of a body.
    fn il_simple_sem(
        &mut self,
        op: IlOperator,
        op_span: Span,
        operand: Option<ExprId>,
        span: Span,
    ) -> IlSem {
        let Some(x) = operand else {
            return match op {
                IlOperator::Not => {
                    let cr = self.il_cr(op_span);
                    IlSem::Load(self.il_not(cr, span))
                }
                _ => IlSem::Nothing,
            };
        };
        let stmt = |kind| Stmt { kind, span };
        match op {
            IlOperator::Ld => IlSem::Load(x),
            IlOperator::Ldn => IlSem::Load(self.il_not(x, span)),
            IlOperator::Not => IlSem::Nothing,
            IlOperator::St | IlOperator::Stn => {
                let cr = self.il_cr(op_span);
                let value = if op == IlOperator::Stn {
                    self.il_not(cr, span)
                } else {
                    cr
                };
                IlSem::Effect {
                    stmts: vec![stmt(StmtKind::Assign { target: x, value })],
                    undefined_after: false,
                }
            }
            IlOperator::S | IlOperator::R => {
                let set = op == IlOperator::S;
                let value = self.il_bool(set, op_span);
                let assign = stmt(StmtKind::Assign { target: x, value });
                let bool_form = self.il_if(IlCond::IfTrue, span, vec![assign]);
                let member = Ident {
                    sym: self.interner.intern(op.name()),
                    span: op_span,
                };
                let target = self.mk(ExprKind::Member { base: x, member }, span, 1);
                let value = self.il_cr(op_span);
                IlSem::SetReset {
                    operand: x,
                    bool_form,
                    fb_form: vec![stmt(StmtKind::Assign { target, value })],
                }
            }
            IlOperator::FbInput(input) => {
                let member = Ident {
                    sym: self.interner.intern(input.name()),
                    span: op_span,
                };
                let target = self.mk(ExprKind::Member { base: x, member }, span, 1);
                let value = self.il_cr(op_span);
                IlSem::Effect {
                    stmts: vec![stmt(StmtKind::Assign { target, value })],
                    undefined_after: false,
                }
            }
            _ => {
                let cr = self.il_cr(op_span);
                IlSem::Load(self.il_combine(op, cr, x, span))
            }
        }
    }

    /// `op( [operand]` EOL sequence `)`.
    fn il_paren(&mut self, op: IlOperator, op_span: Span) -> (IlOp, IlSem) {
        let open = self.bump().span();
        // `AND( LD b` with the first instruction on the `(`'s line (an
        // operand there is alone on it).
        let instr_here = self.at(TokenKind::Ident)
            && IlOperator::from_word(self.text_of(self.tok())).is_some()
            && !self.newline_between(self.tok(), self.nth(1))
            && !matches!(self.nth_kind(1), TokenKind::RParen | TokenKind::Eof);
        let operand = if self.il_line_end() || instr_here {
            None
        } else {
            Some(self.il_operand())
        };
        let (body, inner) = self.il_sequence(operand, open);
        let span = op_span.to(self.prev().span());
        let cr = self.il_cr(op_span);
        let sem = match inner {
            Some(v) => IlSem::Load(self.il_combine(op, cr, v, span)),
            None => IlSem::Nothing,
        };
        (
            IlOp::Paren {
                op,
                op_span,
                operand,
                body,
            },
            sem,
        )
    }

    /// The instructions of a nested sequence up to its `)` (consumed), and
    /// their result composed into one expression, starting from `start`.
    fn il_sequence(&mut self, start: Option<ExprId>, open: Span) -> (Vec<IlInstr>, Option<ExprId>) {
        if !self.enter() {
            return (Vec::new(), None);
        }
        let mut body = Vec::new();
        let mut cur = start;
        let mut ok = true;
        while !self.at(TokenKind::RParen) && !self.il_body_end() && !self.aborted {
            let before = self.pos;
            let first = self.tok();
            match self.il_instr(true) {
                Some(i) => {
                    match self.il_compose(&i, cur) {
                        Some(v) => cur = Some(v),
                        None => {
                            if ok {
                                let d = Diagnostic::new(
                                    Code::E1001,
                                    first.span(),
                                    "the current result is undefined here: \
                                     the sequence has no value yet",
                                )
                                .with_label("reads the current result")
                                .with_help(
                                    "start the sequence with an operand after `(` or with LD",
                                );
                                self.report_always(d);
                            }
                            ok = false;
                        }
                    }
                    body.push(i);
                }
                None => ok = false,
            }
            if self.pos == before {
                self.bump();
            }
        }
        self.leave();
        if !self.eat(TokenKind::RParen) {
            let d = Diagnostic::new(
                Code::E0020,
                self.tok().span(),
                format!("expected `)`, found {}", self.describe_current()),
            )
            .with_label("expected `)`")
            .with_secondary(open, "this `(` is not closed");
            self.report(d);
        }
        if cur.is_none() && ok {
            let d = Diagnostic::new(Code::E0020, open, "an empty parenthesised sequence")
                .with_label("this sequence computes no value");
            self.report_always(d);
        }
        (body, if ok { cur } else { None })
    }

    /// The value of a nested instruction applied to `cur` (`None` when it
    /// needs a current result and there is none).
    fn il_compose(&mut self, i: &IlInstr, cur: Option<ExprId>) -> Option<ExprId> {
        let span = i.span;
        match &i.op {
            IlOp::Simple {
                op: IlOperator::Ld,
                operand: Some(x),
                ..
            } => Some(*x),
            IlOp::Simple {
                op: IlOperator::Ldn,
                operand: Some(x),
                ..
            } => Some(self.il_not(*x, span)),
            IlOp::Simple {
                op: IlOperator::Not,
                ..
            } => Some(self.il_not(cur?, span)),
            IlOp::Simple {
                op,
                operand: Some(x),
                ..
            } => {
                let c = cur?;
                Some(self.il_combine(*op, c, *x, span))
            }
            IlOp::Paren { op, .. } => {
                let IlSem::Load(v) = &i.sem else { return cur };
                // Its sem combined a fresh leaf with the inner value: redo
                // it over `cur`.
                let inner = match &self.ast.expr(*v).kind {
                    ExprKind::Binary { rhs, .. } => *rhs,
                    _ => return None,
                };
                let inner = match (op.binary(), &self.ast.expr(inner).kind) {
                    (Some((_, true)), ExprKind::Unary { operand, .. }) => *operand,
                    _ => inner,
                };
                let c = cur?;
                Some(self.il_combine(*op, c, inner, span))
            }
            IlOp::Call { .. } | IlOp::FormalCall { .. } => {
                let IlSem::Load(v) = &i.sem else { return cur };
                let v = *v;
                // Replace the current-result leaf (the first argument).
                if let ExprKind::Call { args, .. } = &self.ast.expr(v).kind {
                    if let Some(ArgKind::Positional(first)) = args.first().map(|a| &a.kind) {
                        if self.ast.expr(*first).kind == ExprKind::IlCr {
                            let first = *first;
                            let c = cur?;
                            let cspan = self.ast.expr(c).span;
                            // The leaf becomes a parenthesis around `cur`.
                            self.ast.exprs[first.index()].kind = ExprKind::Paren(c);
                            self.ast.exprs[first.index()].span = cspan;
                        }
                    }
                }
                Some(v)
            }
            _ => cur,
        }
    }

    /// After an identifier that is no operator: a function call, `F a, b`
    /// with the current result as first argument, or `F(a := 1, ...)`.
    fn il_function_call(&mut self, name: Ident) -> (IlOp, IlSem) {
        let callee = self.mk(ExprKind::Name(name), name.span, 0);
        if self.at(TokenKind::LParen) && !self.il_line_end() {
            let open = self.bump().span();
            let args = self.il_formal_args(open);
            let st_args = self.il_st_args(&args);
            let span = name.span.to(self.prev().span());
            let call = self.mk(
                ExprKind::Call {
                    callee,
                    args: st_args.into_boxed_slice(),
                },
                span,
                2,
            );
            return (IlOp::FormalCall { name, args }, IlSem::Load(call));
        }
        let mut operands = Vec::new();
        if !self.il_line_end() && !self.at(TokenKind::RParen) {
            loop {
                operands.push(self.il_operand());
                if !self.eat(TokenKind::Comma) {
                    break;
                }
            }
        }
        let span = name.span.to(self.prev().span());
        let cr = self.il_cr(name.span);
        let mut args = vec![Arg {
            kind: ArgKind::Positional(cr),
            span: name.span,
        }];
        let mut depth = 1;
        for &o in &operands {
            depth = depth.max(self.depth_of(o) + 1);
            args.push(Arg {
                kind: ArgKind::Positional(o),
                span: self.expr_span(o),
            });
        }
        let call = self.mk(
            ExprKind::Call {
                callee,
                args: args.into_boxed_slice(),
            },
            span,
            depth,
        );
        (IlOp::Call { name, operands }, IlSem::Load(call))
    }

    /// `name := operand`, `name := ( sequence )`, `[NOT] name => target`,
    /// separated by commas, up to the `)` (consumed).
    fn il_formal_args(&mut self, open: Span) -> Vec<IlArg> {
        let mut args = Vec::new();
        if self.eat(TokenKind::RParen) {
            return args;
        }
        loop {
            let start = self.tok().span();
            let negated = self.at_kw(Keyword::Not) && self.nth_kind(2) == TokenKind::Arrow;
            if negated {
                self.bump();
            }
            let Some(name) = self.name_use("a parameter name") else {
                break;
            };
            if self.eat(TokenKind::Arrow) {
                let target = self.il_operand();
                args.push(IlArg {
                    kind: IlArgKind::Output {
                        name,
                        negated,
                        target,
                    },
                    span: start.to(self.prev().span()),
                });
            } else {
                if !self.expect(TokenKind::Assign) {
                    break;
                }
                let value = if self.at(TokenKind::LParen) {
                    // A parameter's sequence has no operand after its `(`
                    // (seed 003: `'(' EOL simple_instr_list ')'`); its
                    // first instruction may share the `(`'s line.
                    let inner_open = self.bump().span();
                    let (body, value) = self.il_sequence(None, inner_open);
                    let value = value.unwrap_or_else(|| self.error_expr(inner_open));
                    IlArgValue::List { body, value }
                } else {
                    IlArgValue::Operand(self.il_operand())
                };
                args.push(IlArg {
                    kind: IlArgKind::Input { name, value },
                    span: start.to(self.prev().span()),
                });
            }
            if !self.eat(TokenKind::Comma) {
                break;
            }
        }
        if !self.eat(TokenKind::RParen) {
            let d = Diagnostic::new(
                Code::E0020,
                self.tok().span(),
                format!("expected `,` or `)`, found {}", self.describe_current()),
            )
            .with_label("expected `)`")
            .with_secondary(open, "this `(` is not closed");
            self.report(d);
            while !self.il_body_end() && !self.at(TokenKind::RParen) {
                self.bump();
            }
            self.eat(TokenKind::RParen);
        }
        args
    }

    fn il_st_args(&mut self, args: &[IlArg]) -> Vec<Arg> {
        args.iter()
            .map(|a| Arg {
                kind: match &a.kind {
                    IlArgKind::Input { name, value } => ArgKind::Input {
                        name: *name,
                        value: match value {
                            IlArgValue::Operand(e) | IlArgValue::List { value: e, .. } => *e,
                        },
                    },
                    IlArgKind::Output {
                        name,
                        negated,
                        target,
                    } => ArgKind::Output {
                        name: *name,
                        negated: *negated,
                        target: *target,
                    },
                },
                span: a.span,
            })
            .collect()
    }

    /// JMP, CAL and RET with their modifiers (the word is consumed).
    fn il_control(&mut self, kind: &str, cond: IlCond, op_span: Span) -> (IlOp, IlSem) {
        match kind {
            "JMP" => {
                let target = match self.name("a label") {
                    Some(t) => t,
                    None => Ident {
                        sym: self.interner.intern("?"),
                        span: op_span,
                    },
                };
                let cond_expr = match cond {
                    IlCond::Always => None,
                    IlCond::IfTrue => Some(self.il_cr(op_span)),
                    IlCond::IfFalse => {
                        let leaf = self.il_cr(op_span);
                        Some(self.il_not(leaf, op_span))
                    }
                };
                (
                    IlOp::Jump {
                        op: cond,
                        op_span,
                        target,
                    },
                    IlSem::Jump {
                        cond: cond_expr,
                        target,
                    },
                )
            }
            "RET" => {
                let stmts = self.il_if(
                    cond,
                    op_span,
                    vec![Stmt {
                        kind: StmtKind::Return,
                        span: op_span,
                    }],
                );
                (
                    IlOp::Ret { op: cond, op_span },
                    IlSem::Effect {
                        stmts,
                        undefined_after: false,
                    },
                )
            }
            _ => {
                let callee = self.il_callee();
                let mut args = None;
                let mut st_args = Vec::new();
                if self.at(TokenKind::LParen) && !self.il_line_end() {
                    let open = self.bump().span();
                    let formal = matches!(
                        (self.nth_kind(0), self.nth_kind(1)),
                        (TokenKind::Ident, TokenKind::Assign | TokenKind::Arrow)
                            | (TokenKind::Kw(_), TokenKind::Assign | TokenKind::Arrow)
                            | (TokenKind::Kw(Keyword::Not), TokenKind::Ident)
                            | (TokenKind::RParen, _)
                    );
                    if formal {
                        let a = self.il_formal_args(open);
                        st_args = self.il_st_args(&a);
                        args = Some(IlCallArgs::Formal(a));
                    } else {
                        let mut list = Vec::new();
                        loop {
                            list.push(self.il_operand());
                            if !self.eat(TokenKind::Comma) {
                                break;
                            }
                        }
                        self.expect(TokenKind::RParen);
                        for &o in &list {
                            st_args.push(Arg {
                                kind: ArgKind::Positional(o),
                                span: self.expr_span(o),
                            });
                        }
                        args = Some(IlCallArgs::Positional(list));
                    }
                }
                let span = op_span.to(self.prev().span());
                let call = self.mk(
                    ExprKind::Call {
                        callee,
                        args: st_args.into_boxed_slice(),
                    },
                    span,
                    2,
                );
                let stmts = self.il_if(
                    cond,
                    span,
                    vec![Stmt {
                        kind: StmtKind::Call(call),
                        span,
                    }],
                );
                (
                    IlOp::Cal {
                        op: cond,
                        op_span,
                        callee,
                        args,
                    },
                    IlSem::Effect {
                        stmts,
                        undefined_after: true,
                    },
                )
            }
        }
    }

    /// The instance a CAL calls: a name with members and indices, without
    /// the parameter list.
    fn il_callee(&mut self) -> ExprId {
        let t = self.tok();
        let Some(name) = self.name_use("a function block instance") else {
            return self.error_expr(t.span());
        };
        let mut e = self.mk(ExprKind::Name(name), name.span, 0);
        loop {
            if self.at(TokenKind::Dot) && self.nth_kind(1) == TokenKind::Ident {
                self.bump();
                let m = self.bump();
                let member = self.intern_token(m);
                let span = self.expr_span(e).to(m.span());
                let depth = self.depth_of(e);
                e = self.mk(ExprKind::Member { base: e, member }, span, depth);
            } else if self.at(TokenKind::LBracket) {
                self.bump();
                let mut indices = Vec::new();
                loop {
                    indices.push(self.expr());
                    if !self.eat(TokenKind::Comma) {
                        break;
                    }
                }
                let end = self.tok().span();
                self.expect(TokenKind::RBracket);
                let span = self.expr_span(e).to(end);
                let depth = indices
                    .iter()
                    .map(|i| self.depth_of(*i))
                    .max()
                    .unwrap_or(0)
                    .max(self.depth_of(e));
                e = self.mk(
                    ExprKind::Index {
                        base: e,
                        indices: indices.into_boxed_slice(),
                    },
                    span,
                    depth,
                );
            } else {
                return e;
            }
        }
    }
}
