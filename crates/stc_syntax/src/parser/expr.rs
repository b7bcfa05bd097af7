//! Expressions, by precedence climbing over the IEC levels (lowest first):
//! OR, XOR, AND/&, = <>, < > <= >=, + -, * / MOD, unary - + NOT, **, then
//! calls, indexing and member access, then primaries. `**` binds tighter
//! than unary minus (`-2**2` is `-(2**2)`) but its right operand may itself
//! be negated (`2 ** -1`). All binary operators are left-associative.

use stc_diagnostics::{Code, Diagnostic, Span};

use super::Parser;
use crate::ast::{
    Arg, ArgKind, BinaryOp, ExprId, ExprKind, Ident, LitValue, Literal, TypePrefix, UnaryOp,
};
use crate::literal::{self, AddrSize, LitError};
use crate::token::{ElemType, Keyword, TokenKind};

impl Parser<'_> {
    pub(crate) fn expr(&mut self) -> ExprId {
        self.binary(1)
    }

    fn binary_op(&self) -> Option<BinaryOp> {
        Some(match self.kind() {
            TokenKind::Kw(Keyword::Or) => BinaryOp::Or,
            TokenKind::Kw(Keyword::Xor) => BinaryOp::Xor,
            TokenKind::Kw(Keyword::And) | TokenKind::Amp => BinaryOp::And,
            TokenKind::Eq => BinaryOp::Eq,
            TokenKind::Ne => BinaryOp::Ne,
            TokenKind::Lt => BinaryOp::Lt,
            TokenKind::Le => BinaryOp::Le,
            TokenKind::Gt => BinaryOp::Gt,
            TokenKind::Ge => BinaryOp::Ge,
            TokenKind::Plus => BinaryOp::Add,
            TokenKind::Minus => BinaryOp::Sub,
            TokenKind::Star => BinaryOp::Mul,
            TokenKind::Slash => BinaryOp::Div,
            TokenKind::Kw(Keyword::Mod) => BinaryOp::Mod,
            _ => return None,
        })
    }

    fn binary(&mut self, min_prec: u8) -> ExprId {
        let mut lhs = self.unary();
        while !self.aborted {
            let Some(op) = self.binary_op() else { break };
            let prec = op.precedence();
            if prec < min_prec {
                break;
            }
            self.bump();
            let rhs = self.binary(prec + 1);
            let span = self.expr_span(lhs).to(self.expr_span(rhs));
            let depth = self.depth_of(lhs).max(self.depth_of(rhs));
            lhs = self.mk(ExprKind::Binary { op, lhs, rhs }, span, depth);
        }
        lhs
    }

    fn unary_op(&self) -> Option<UnaryOp> {
        match self.kind() {
            TokenKind::Minus => Some(UnaryOp::Neg),
            TokenKind::Plus => Some(UnaryOp::Plus),
            TokenKind::Kw(Keyword::Not) => Some(UnaryOp::Not),
            _ => None,
        }
    }

    fn unary(&mut self) -> ExprId {
        self.prefixed(Self::power)
    }

    /// A unary operator applied to `next`, or just `next`.
    fn prefixed(&mut self, next: fn(&mut Self) -> ExprId) -> ExprId {
        let Some(op) = self.unary_op() else {
            return next(self);
        };
        if !self.enter() {
            return self.error_expr(self.tok().span());
        }
        let start = self.bump().span();
        let operand = self.prefixed(next);
        self.leave();
        let span = start.to(self.expr_span(operand));
        let depth = self.depth_of(operand);
        self.mk(ExprKind::Unary { op, operand }, span, depth)
    }

    fn power(&mut self) -> ExprId {
        let mut lhs = self.postfix();
        while self.at(TokenKind::StarStar) && !self.aborted {
            self.bump();
            let rhs = self.prefixed(Self::postfix);
            let span = self.expr_span(lhs).to(self.expr_span(rhs));
            let depth = self.depth_of(lhs).max(self.depth_of(rhs));
            lhs = self.mk(
                ExprKind::Binary {
                    op: BinaryOp::Pow,
                    lhs,
                    rhs,
                },
                span,
                depth,
            );
        }
        lhs
    }

    /// A primary followed by `.member`, `[indices]`, `(arguments)`.
    pub(crate) fn postfix(&mut self) -> ExprId {
        let mut e = self.primary();
        while !self.aborted {
            match self.kind() {
                TokenKind::Dot => {
                    self.bump();
                    let t = self.tok();
                    let base_span = self.expr_span(e);
                    let depth = self.depth_of(e);
                    match t.kind {
                        TokenKind::Ident => {
                            self.bump();
                            let member = self.intern_token(t);
                            e = self.mk(
                                ExprKind::Member { base: e, member },
                                base_span.to(t.span()),
                                depth,
                            );
                        }
                        TokenKind::Int => {
                            self.bump();
                            let index = self
                                .text_of(t)
                                .replace('_', "")
                                .parse::<u32>()
                                .unwrap_or(u32::MAX);
                            e = self.mk(
                                ExprKind::PartialAccess {
                                    base: e,
                                    size: AddrSize::Bit,
                                    index,
                                },
                                base_span.to(t.span()),
                                depth,
                            );
                        }
                        TokenKind::PartialAccess => {
                            self.bump();
                            match literal::parse_partial_access(self.text_of(t)) {
                                Ok((size, index)) => {
                                    e = self.mk(
                                        ExprKind::PartialAccess {
                                            base: e,
                                            size,
                                            index,
                                        },
                                        base_span.to(t.span()),
                                        depth,
                                    );
                                }
                                Err(err) => {
                                    self.lit_error(t.span(), err);
                                    e = self.error_expr(base_span.to(t.span()));
                                }
                            }
                        }
                        k if k.is_reserved_word() && !super::starts_construct(k) => {
                            // A member named like a reserved word (`c.LDT`):
                            // its declaration had the E0022.
                            self.bump();
                            let member = self.intern_token(t);
                            e = self.mk(
                                ExprKind::Member { base: e, member },
                                base_span.to(t.span()),
                                depth,
                            );
                        }
                        _ => {
                            self.expected("a member name after `.`");
                            return self.error_expr(base_span);
                        }
                    }
                }
                TokenKind::LBracket => {
                    self.bump();
                    if !self.enter() {
                        return self.error_expr(self.tok().span());
                    }
                    let mut indices = Vec::new();
                    let mut depth = self.depth_of(e);
                    loop {
                        let i = self.expr();
                        depth = depth.max(self.depth_of(i));
                        indices.push(i);
                        if !self.eat(TokenKind::Comma) {
                            break;
                        }
                    }
                    self.leave();
                    let end = self.tok().span();
                    if !self.expect(TokenKind::RBracket) {
                        return self.error_expr(self.expr_span(e).to(end));
                    }
                    let span = self.expr_span(e).to(end);
                    e = self.mk(
                        ExprKind::Index {
                            base: e,
                            indices: indices.into_boxed_slice(),
                        },
                        span,
                        depth,
                    );
                }
                TokenKind::LParen => {
                    e = self.call(e);
                }
                TokenKind::Caret => {
                    let span = self.bump().span();
                    let depth = self.depth_of(e);
                    e = self.mk(ExprKind::Deref(e), self.expr_span(e).to(span), depth);
                }
                _ => break,
            }
        }
        e
    }

    fn call(&mut self, callee: ExprId) -> ExprId {
        self.bump(); // (
        if !self.enter() {
            return self.error_expr(self.tok().span());
        }
        let mut args = Vec::new();
        let mut depth = self.depth_of(callee);
        if !self.at(TokenKind::RParen) {
            loop {
                let arg = self.arg();
                match &arg.kind {
                    ArgKind::Positional(v) | ArgKind::Input { value: v, .. } => {
                        depth = depth.max(self.depth_of(*v))
                    }
                    ArgKind::Output { target, .. } => depth = depth.max(self.depth_of(*target)),
                }
                args.push(arg);
                if !self.eat(TokenKind::Comma) || self.aborted {
                    break;
                }
            }
        }
        self.leave();
        let end = self.tok().span();
        let span = self.expr_span(callee).to(end);
        if !self.expect(TokenKind::RParen) {
            return self.error_expr(span);
        }
        self.mk(
            ExprKind::Call {
                callee,
                args: args.into_boxed_slice(),
            },
            span,
            depth,
        )
    }

    fn arg(&mut self) -> Arg {
        let start = self.tok().span();
        let named = self.kind() == TokenKind::Ident
            || (self.kind().is_reserved_word()
                && matches!(self.nth_kind(1), TokenKind::Assign | TokenKind::Arrow));
        if named && self.nth_kind(1) == TokenKind::Assign {
            let name = self.name_use("a parameter name");
            self.bump();
            let value = self.expr();
            if let Some(name) = name {
                return Arg {
                    kind: ArgKind::Input { name, value },
                    span: start.to(self.expr_span(value)),
                };
            }
            return Arg {
                kind: ArgKind::Positional(value),
                span: start.to(self.expr_span(value)),
            };
        }
        let negated = self.at_kw(Keyword::Not)
            && self.nth_kind(1) == TokenKind::Ident
            && self.nth_kind(2) == TokenKind::Arrow;
        if (named && self.nth_kind(1) == TokenKind::Arrow) || negated {
            if negated {
                self.bump();
            }
            let name = self.name_use("a parameter name");
            self.bump(); // =>
            let target = self.expr();
            if let Some(name) = name {
                return Arg {
                    kind: ArgKind::Output {
                        name,
                        negated,
                        target,
                    },
                    span: start.to(self.expr_span(target)),
                };
            }
        }
        let value = self.expr();
        Arg {
            kind: ArgKind::Positional(value),
            span: start.to(self.expr_span(value)),
        }
    }

    fn lit_error(&mut self, span: Span, e: LitError) {
        let d = Diagnostic::new(e.code, span, e.message);
        self.report_always(d);
    }

    fn literal_expr(&mut self, value: LitValue, prefix: Option<TypePrefix>, span: Span) -> ExprId {
        self.mk(ExprKind::Literal(Literal { value, prefix }), span, 0)
    }

    /// Decodes the current literal token (after an optional sign).
    fn literal_value(&mut self, negative: bool) -> Result<LitValue, LitError> {
        let t = self.bump();
        let source = self.text_of(t);
        let completed;
        let text =
            if matches!(t.kind, TokenKind::Tod | TokenKind::Dt) && literal::lacks_seconds(source) {
                let d = Diagnostic::new(
                    Code::W0007,
                    t.span(),
                    format!("`{source}` has no seconds; read as zero seconds"),
                )
                .with_help("write the seconds: IEC 61131-3 requires HH:MM:SS");
                self.report_always(d);
                completed = literal::with_zero_seconds(source);
                completed.as_str()
            } else {
                source
            };
        Ok(match t.kind {
            TokenKind::Int => LitValue::Int {
                value: literal::parse_int(text)?,
                negative,
            },
            TokenKind::BasedInt => LitValue::Int {
                value: literal::parse_based_int(text)?,
                negative,
            },
            TokenKind::Real => {
                let v = literal::parse_real(text)?;
                LitValue::Real(if negative { -v } else { v })
            }
            TokenKind::Kw(Keyword::True) => LitValue::Bool(true),
            TokenKind::Kw(Keyword::False) => LitValue::Bool(false),
            TokenKind::SString | TokenKind::WString => {
                let wide = t.kind == TokenKind::WString;
                let (value, errors) = literal::decode_string(text, wide);
                for (lo, hi, msg) in errors {
                    let span = Span::new(t.lo + lo as u32, t.lo + hi as u32);
                    self.report_always(Diagnostic::new(Code::E0009, span, msg));
                }
                LitValue::String {
                    value: value.into_boxed_str(),
                    wide,
                }
            }
            TokenKind::Duration => LitValue::Duration {
                ns: literal::parse_duration(text)?,
                long: literal::is_long_prefix(text),
            },
            TokenKind::Date => LitValue::Date {
                secs: literal::parse_date(text)?,
                long: literal::is_long_prefix(text),
            },
            TokenKind::Tod => LitValue::Tod {
                ns: literal::parse_tod(text)?,
                long: literal::is_long_prefix(text),
            },
            TokenKind::Dt => LitValue::Dt {
                ns: literal::parse_dt(text)?,
                long: literal::is_long_prefix(text),
            },
            _ => unreachable!("literal_value called on a non-literal token"),
        })
    }

    fn is_literal_start(k: TokenKind) -> bool {
        matches!(
            k,
            TokenKind::Int
                | TokenKind::BasedInt
                | TokenKind::Real
                | TokenKind::SString
                | TokenKind::WString
                | TokenKind::Duration
                | TokenKind::Date
                | TokenKind::Tod
                | TokenKind::Dt
                | TokenKind::Kw(Keyword::True)
                | TokenKind::Kw(Keyword::False)
        )
    }

    fn primary(&mut self) -> ExprId {
        let t = self.tok();
        match t.kind {
            k if Self::is_literal_start(k) => match self.literal_value(false) {
                Ok(v) => self.literal_expr(v, None, t.span()),
                Err(e) => {
                    self.lit_error(t.span(), e);
                    self.error_expr(t.span())
                }
            },
            TokenKind::Address => {
                self.bump();
                match literal::parse_address(self.text_of(t)) {
                    Ok(a) => self.mk(ExprKind::Address(Box::new(a)), t.span(), 0),
                    Err(e) => {
                        self.lit_error(t.span(), e);
                        self.error_expr(t.span())
                    }
                }
            }
            TokenKind::LParen => {
                self.bump();
                if !self.enter() {
                    return self.error_expr(t.span());
                }
                let inner = self.expr();
                self.leave();
                let end = self.tok().span();
                if !self.expect(TokenKind::RParen) {
                    return inner;
                }
                let depth = self.depth_of(inner);
                self.mk(ExprKind::Paren(inner), t.span().to(end), depth)
            }
            // `Drives.Direction#FORWARD`: a typed literal whose type is
            // named with its namespace.
            TokenKind::Ident if self.qualified_hash_ahead() => {
                match self.qualified_name("a type name") {
                    Some(prefix) => self.typed_literal(TypePrefix::Named(prefix)),
                    None => self.error_expr(t.span()),
                }
            }
            TokenKind::Ident if self.nth_kind(1) == TokenKind::Hash => {
                self.bump();
                let prefix = self.intern_token(t);
                self.typed_literal(TypePrefix::Named(prefix))
            }
            TokenKind::Ident if self.at_dunder() && self.nth_kind(1) == TokenKind::LParen => {
                // `__NEW(INT)`, `__TRUNC(x)`: an operator of the CODESYS and
                // TwinCAT dialects, reported once (not also as an invalid
                // identifier) and skipped with its arguments.
                self.bump();
                let what = format!("the dialect operator `{}` is", self.text_of(t));
                self.unsupported(t.span(), &what);
                self.pou_partial = true;
                self.skip_parens();
                let span = t.span().to(self.prev().span());
                self.superseded.push(span);
                self.error_expr(span)
            }
            TokenKind::Ident => {
                self.bump();
                let name = self.intern_token(t);
                self.mk(ExprKind::Name(name), t.span(), 0)
            }
            TokenKind::Elem(ty) if self.nth_kind(1) == TokenKind::Hash => {
                self.bump();
                self.typed_literal(TypePrefix::Elem(ty, t.span()))
            }
            // A reserved word used as a name (`TIME(...)`, `r_edge`): its
            // declaration had the E0022; an undeclared one is reported when
            // names are resolved.
            TokenKind::Elem(_)
            | TokenKind::Generic(_)
            | TokenKind::Kw(Keyword::REdge | Keyword::FEdge) => {
                self.bump();
                let name = self.intern_token(t);
                self.mk(ExprKind::Name(name), t.span(), 0)
            }
            // Operators in functional form: AND(a, b), MOD(7, 2), OR(...).
            TokenKind::Kw(
                Keyword::And | Keyword::Or | Keyword::Xor | Keyword::Mod | Keyword::Not,
            ) if self.nth_kind(1) == TokenKind::LParen => {
                self.bump();
                let name = self.intern_token(t);
                self.mk(ExprKind::Name(name), t.span(), 0)
            }
            // A reserved word this file declared as a name (its E0022).
            k if self.reserved_names.contains(&k) => {
                self.bump();
                let name = self.intern_token(t);
                self.mk(ExprKind::Name(name), t.span(), 0)
            }
            _ => {
                self.expected("an expression");
                self.error_expr(t.span())
            }
        }
    }

    /// At `A.B#`, `A.B.C#`: a dotted type name before a typed literal's `#`.
    fn qualified_hash_ahead(&self) -> bool {
        let mut i = 1;
        while self.nth_kind(i) == TokenKind::Dot && self.nth_kind(i + 1) == TokenKind::Ident {
            i += 2;
        }
        i > 1 && self.nth_kind(i) == TokenKind::Hash
    }

    /// After `INT#`, `MyEnum#`: the value.
    fn typed_literal(&mut self, prefix: TypePrefix) -> ExprId {
        let start = match prefix {
            TypePrefix::Elem(_, s) => s,
            TypePrefix::Named(i) => i.span,
        };
        self.bump(); // #
        let t = self.tok();
        let negative = matches!(t.kind, TokenKind::Minus | TokenKind::Plus)
            && matches!(
                self.nth_kind(1),
                TokenKind::Int | TokenKind::BasedInt | TokenKind::Real
            );
        if negative {
            let sign = self.bump();
            let value_tok = self.tok();
            let neg = sign.kind == TokenKind::Minus;
            return match self.literal_value(neg) {
                Ok(v) => self.literal_expr(v, Some(prefix), start.to(value_tok.span())),
                Err(e) => {
                    self.lit_error(value_tok.span(), e);
                    self.error_expr(start.to(value_tok.span()))
                }
            };
        }
        if Self::is_literal_start(t.kind) {
            return match self.literal_value(false) {
                Ok(v) => self.literal_expr(v, Some(prefix), start.to(t.span())),
                Err(e) => {
                    self.lit_error(t.span(), e);
                    self.error_expr(start.to(t.span()))
                }
            };
        }
        if let (TypePrefix::Named(ty), TokenKind::Ident) = (prefix, t.kind) {
            self.bump();
            let value: Ident = self.intern_token(t);
            return self.mk(ExprKind::EnumValue { ty, value }, start.to(t.span()), 0);
        }
        let what = match prefix {
            TypePrefix::Elem(ElemType::Bool, _) => "TRUE, FALSE, 0 or 1 after `BOOL#`",
            TypePrefix::Elem(..) => "a literal after the type prefix",
            TypePrefix::Named(_) => "an enumeration value or literal after `#`",
        };
        self.expected(what);
        self.error_expr(start)
    }
}
