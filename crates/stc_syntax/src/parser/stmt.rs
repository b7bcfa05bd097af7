//! Statements and statement lists.
//!
//! A statement list ends at any token that closes a block (END_x, ELSE,
//! ELSIF, UNTIL), at the start of a declaration, or, inside a CASE, at the
//! start of the next case label. Which block a closing keyword belongs to is
//! decided with the stack of open blocks: a keyword that closes an outer
//! block is left for it, one that closes nothing open is reported and
//! skipped.
//!
//! CASE labels and statements are told apart without restricting the grammar
//! (seed 000 section III.G): `MAX:` is a label and `MAX := E;` an assignment,
//! decided by looking ahead to the first `:` or `:=`.

use stc_diagnostics::{Code, Diagnostic, Span};

use super::{is_item_end, is_item_start, is_var_block_start, Open, Parser};
use crate::ast::{CaseArm, CaseLabel, CondBranch, ExprKind, PouKind, Stmt, StmtKind};
use crate::token::{Keyword, TokenKind};

/// Tokens at which a statement list stops.
pub(crate) fn ends_stmt_list(k: TokenKind) -> bool {
    matches!(
        k,
        TokenKind::Eof
            | TokenKind::Kw(
                Keyword::EndIf
                    | Keyword::EndCase
                    | Keyword::EndFor
                    | Keyword::EndWhile
                    | Keyword::EndRepeat
                    | Keyword::Else
                    | Keyword::Elsif
                    | Keyword::Until
            )
    ) || is_item_end(k)
        || is_item_start(k)
        || is_var_block_start(k)
        || matches!(k, TokenKind::Kw(Keyword::EndVar | Keyword::EndStruct))
}

/// Tokens where skipping after a bad statement stops (without consuming).
fn stmt_sync(k: TokenKind) -> bool {
    ends_stmt_list(k)
        || matches!(
            k,
            TokenKind::Kw(
                Keyword::If
                    | Keyword::Case
                    | Keyword::For
                    | Keyword::While
                    | Keyword::Repeat
                    | Keyword::Exit
                    | Keyword::Return
                    | Keyword::Continue
            )
        )
}

impl Parser<'_> {
    /// Statements up to a token that ends the list.
    pub(crate) fn stmt_list(&mut self, in_case: bool) -> Vec<Stmt> {
        let mut out = Vec::new();
        // Inside a CASE, a label ends the statements of a block nested in
        // an arm too: that block was left unclosed (one error, where its
        // END is missing, then the CASE reads on at the label).
        let in_arm = in_case || self.open.contains(&Open::Case);
        while !self.aborted && !ends_stmt_list(self.kind()) {
            if in_arm && self.at_case_label() {
                break;
            }
            if self.in_method && self.at_word("END_METHOD") {
                break;
            }
            if self.in_action && self.at_word("END_ACTION") {
                break;
            }
            if self.in_property
                && (self.at_word("END_GET")
                    || self.at_word("END_SET")
                    || self.at_word("END_PROPERTY"))
            {
                break;
            }
            let before = self.pos;
            if let Some(s) = self.statement() {
                out.push(s);
            }
            if self.pos == before {
                self.bump();
            }
        }
        out
    }

    /// Skips what is left of a bad statement: up to and including its `;`,
    /// or up to a token that begins or ends a statement.
    fn skip_stmt(&mut self) {
        while !stmt_sync(self.kind()) {
            if self.bump().kind == TokenKind::Semi {
                return;
            }
        }
    }

    fn expect_semi(&mut self) {
        if self.eat(TokenKind::Semi) {
            return;
        }
        if ends_stmt_list(self.kind()) && self.kind() != TokenKind::Eof {
            // `x := 1 END_IF`: CODESYS and TwinCAT accept the last `;` of a
            // list left out; nothing is ambiguous, so read on with a warning
            // (none when the keyword closes the wrong block, or this
            // statement already has its error: that is the one to fix).
            if self.closes_innermost(self.kind()) && self.last_error_pos != self.pos {
                self.missing_semi_before_end();
            }
            return;
        }
        if self.newline_between(self.prev(), self.tok()) {
            if self.after_unterminated_string() {
                return;
            }
            let prev = self.prev().span().shrink_to_hi();
            let d = Diagnostic::new(
                Code::E0020,
                self.tok().span(),
                format!("expected `;`, found {}", self.describe_current()),
            )
            .with_label("expected `;`")
            .with_secondary(prev, "the statement before needs a `;` here");
            self.report(d);
            // Read on as if the `;` were there: the next line is a statement
            // of its own (skipping it would lose it, and what depends on it).
            return;
        }
        self.expected("`;`");
        self.skip_stmt();
    }

    pub(crate) fn statement(&mut self) -> Option<Stmt> {
        let t = self.tok();
        let simple = |p: &mut Self, kind| {
            p.bump();
            let span = t.span();
            p.expect_semi();
            Some(Stmt { kind, span })
        };
        // A statement word this file declared as a name (E0022 there):
        // `exit := 1;` assigns it.
        if self.reserved_names.contains(&t.kind)
            && matches!(
                self.nth_kind(1),
                TokenKind::Assign | TokenKind::Dot | TokenKind::LBracket | TokenKind::LParen
            )
        {
            return self.expr_statement();
        }
        match t.kind {
            TokenKind::Semi => {
                self.bump();
                Some(Stmt {
                    kind: StmtKind::Empty,
                    span: t.span(),
                })
            }
            TokenKind::Kw(Keyword::If) => self.compound(Self::if_stmt),
            TokenKind::Kw(Keyword::Case) => self.compound(Self::case_stmt),
            TokenKind::Kw(Keyword::For) => self.compound(Self::for_stmt),
            TokenKind::Kw(Keyword::While) => self.compound(Self::while_stmt),
            TokenKind::Kw(Keyword::Repeat) => self.compound(Self::repeat_stmt),
            TokenKind::Kw(Keyword::Exit) => simple(self, StmtKind::Exit),
            TokenKind::Kw(Keyword::Continue) => simple(self, StmtKind::Continue),
            TokenKind::Kw(Keyword::Return) => simple(self, StmtKind::Return),
            TokenKind::Ident if self.at_unsupported_in_body() => None,
            TokenKind::Ident if self.at_word("__TRY") => {
                // TwinCAT/CODESYS exception handling: one E0030, the block
                // up to `__ENDTRY` skipped.
                let start = self.tok().span();
                self.unsupported(start, "`__TRY` blocks are");
                self.pou_partial = true;
                while !self.at(TokenKind::Eof)
                    && !is_item_end(self.kind())
                    && !is_item_start(self.kind())
                {
                    let end = self.at_word("__ENDTRY");
                    self.bump();
                    if end {
                        break;
                    }
                }
                self.superseded.push(start.to(self.prev().span()));
                self.eat(TokenKind::Semi);
                None
            }
            _ => self.expr_statement(),
        }
    }

    /// A compound statement: bounded nesting, then its closing `;`.
    fn compound(&mut self, f: fn(&mut Self) -> StmtKind) -> Option<Stmt> {
        let start = self.tok().span();
        if !self.enter() {
            return None;
        }
        let kind = f(self);
        self.leave();
        let span = start.to(self.prev().span());
        let closed = matches!(
            self.prev().kind,
            TokenKind::Kw(
                Keyword::EndIf
                    | Keyword::EndCase
                    | Keyword::EndFor
                    | Keyword::EndWhile
                    | Keyword::EndRepeat
            )
        );
        if closed && !self.at(TokenKind::Semi) && !self.at(TokenKind::Eof) {
            // `END_IF` without its `;`, as CODESYS, TwinCAT and RuSTy
            // accept: the block is complete, so the next token starts the
            // next statement (or closes the list) whatever it is.
            let end = self.prev();
            let d = Diagnostic::new(
                Code::W0004,
                end.span(),
                format!("missing `;` after `{}`", self.text_of(end)),
            )
            .with_label("`;` expected after this")
            .with_help("add `;`: IEC 61131-3 ends every statement with it");
            self.report_always(d);
        } else {
            self.expect_semi();
        }
        Some(Stmt { kind, span })
    }

    /// Whether `k` closes (or continues) the innermost open block, or the
    /// POU when no block is open.
    fn closes_innermost(&self, k: TokenKind) -> bool {
        let TokenKind::Kw(kw) = k else {
            return false;
        };
        match self.open.last() {
            Some(Open::If) => matches!(kw, Keyword::EndIf | Keyword::Else | Keyword::Elsif),
            Some(Open::Case) => matches!(kw, Keyword::EndCase | Keyword::Else),
            Some(Open::For) => kw == Keyword::EndFor,
            Some(Open::While) => kw == Keyword::EndWhile,
            Some(Open::Repeat) => kw == Keyword::Until,
            None => is_item_end(k),
        }
    }

    /// The `;` after the last statement or declaration before a closing
    /// keyword is missing (W0005), reported at the end of what lacks it.
    pub(crate) fn missing_semi_before_end(&mut self) {
        let at = self.prev().span().shrink_to_hi();
        let d = Diagnostic::new(
            Code::W0005,
            at,
            format!("missing `;` before {}", self.describe_current()),
        )
        .with_label("`;` expected here")
        .with_help("add `;`: IEC 61131-3 ends every statement and declaration with it");
        self.report_always(d);
    }

    fn expr_statement(&mut self) -> Option<Stmt> {
        let start = self.tok();
        if !Self::can_start_expr(start.kind) && !self.reserved_names.contains(&start.kind) {
            self.expected("a statement");
            self.bump();
            self.skip_stmt();
            return None;
        }
        let target = self.postfix();
        let kind = match self.kind() {
            TokenKind::Assign => {
                self.bump();
                let value = self.expr();
                StmtKind::Assign { target, value }
            }
            TokenKind::QuestionAssign => {
                self.bump();
                let value = self.expr();
                StmtKind::AssignAttempt { target, value }
            }
            TokenKind::Ident if self.at_word("REF") && self.nth_kind(1) == TokenKind::Eq => {
                // `r REF= x` is `r := REF(x)`.
                let word = self.bump();
                self.bump();
                let x = self.expr();
                let callee = ExprKind::Name(self.intern_token(word));
                let callee = self.ast.alloc(callee, word.span());
                let xspan = self.ast.expr(x).span;
                let args = vec![crate::ast::Arg {
                    kind: crate::ast::ArgKind::Positional(x),
                    span: xspan,
                }];
                let call = ExprKind::Call {
                    callee,
                    args: args.into_boxed_slice(),
                };
                let value = self.ast.alloc(call, word.span().to(xspan));
                StmtKind::Assign { target, value }
            }
            _ if matches!(self.ast.expr(target).kind, ExprKind::Call { .. }) => {
                StmtKind::Call(target)
            }
            _ if matches!(self.ast.expr(target).kind, ExprKind::Error) => {
                self.skip_stmt();
                return None;
            }
            TokenKind::Eq => {
                let d = Diagnostic::new(Code::E0020, self.tok().span(), "expected `:=`, found `=`")
                    .with_label("`=` compares; it does not assign")
                    .with_help("use `:=` to assign a value");
                self.report(d);
                self.skip_stmt();
                return None;
            }
            _ => {
                self.expected("`:=` or a call");
                self.skip_stmt();
                return None;
            }
        };
        let span = start.span().to(self.prev().span());
        self.expect_semi();
        Some(Stmt { kind, span })
    }

    pub(crate) fn can_start_expr(k: TokenKind) -> bool {
        matches!(
            k,
            TokenKind::Ident
                | TokenKind::Address
                | TokenKind::LParen
                | TokenKind::Minus
                | TokenKind::Plus
                | TokenKind::Int
                | TokenKind::BasedInt
                | TokenKind::Real
                | TokenKind::SString
                | TokenKind::WString
                | TokenKind::Duration
                | TokenKind::Date
                | TokenKind::Tod
                | TokenKind::Dt
                | TokenKind::Elem(_)
                | TokenKind::Generic(_)
                | TokenKind::Kw(
                    Keyword::True
                        | Keyword::False
                        | Keyword::REdge
                        | Keyword::FEdge
                        | Keyword::Not
                        | Keyword::And
                        | Keyword::Or
                        | Keyword::Xor
                        | Keyword::Mod
                )
        )
    }

    /// SFC elements and object-oriented members inside a POU body are
    /// reported once and skipped up to their END.
    fn at_unsupported_in_body(&mut self) -> bool {
        let sfc = (self.at_word("INITIAL_STEP") || self.at_word("STEP"))
            && self.nth_kind(1) == TokenKind::Ident
            && self.nth_kind(2) == TokenKind::Colon
            || self.at_word("TRANSITION")
                && (self.nth_kind(1) == TokenKind::Ident)
                && (self.nth_is_word(1, "FROM")
                    || matches!(
                        self.nth_kind(2),
                        TokenKind::Ident | TokenKind::Colon | TokenKind::Assign
                    ));
        if sfc {
            let span = self.tok().span();
            self.unsupported(
                span,
                "Sequential Function Chart elements after Structured Text statements are",
            );
            self.pou_partial = true;
            while !self.at(TokenKind::Eof)
                && !is_item_end(self.kind())
                && !is_item_start(self.kind())
            {
                self.bump();
            }
            self.superseded.push(span.to(self.prev().span()));
            return true;
        }
        if self.at_word("METHOD")
            && self.nth_kind(1) == TokenKind::Ident
            && self.pou_kind == Some(PouKind::FunctionBlock)
            && !self.in_method
        {
            // A METHOD after the statements of its block's body, as CODESYS
            // and TwinCAT exports place them: one of its methods.
            if let Some(m) = self.method() {
                self.late_methods.push(m);
            }
            while self.eat(TokenKind::Semi) {}
            return true;
        }
        if self.at_word("PROPERTY")
            && self.nth_kind(1) == TokenKind::Ident
            && self.pou_kind == Some(PouKind::FunctionBlock)
            && !self.in_method
        {
            // A PROPERTY after the statements of its block's body.
            let mut parts = self.property();
            self.late_methods.append(&mut parts);
            while self.eat(TokenKind::Semi) {}
            return true;
        }
        if self.at_word("ACTION")
            && matches!(self.nth_kind(1), TokenKind::Ident)
            && matches!(
                self.pou_kind,
                Some(PouKind::FunctionBlock | PouKind::Program)
            )
            && !self.in_method
            && !self.in_action
        {
            // An ACTION of the function block, after its body.
            if let Some(m) = self.action() {
                self.late_methods.push(m);
            }
            while self.eat(TokenKind::Semi) {}
            return true;
        }
        for (word, end, what) in [
            (
                "METHOD",
                "END_METHOD",
                "methods outside a function block are",
            ),
            (
                "PROPERTY",
                "END_PROPERTY",
                "properties outside a function block are",
            ),
            ("ACTION", "END_ACTION", "actions of a FUNCTION are"),
        ] {
            if self.at_word(word) && self.nth_kind(1) == TokenKind::Ident {
                let span = self.tok().span();
                self.unsupported(span, what);
                let name = self.nth(1);
                let name = self.intern_token(name);
                self.pou_skipped.push(name);
                self.pou_partial = true;
                self.skip_unsupported(end, |k| is_item_end(k) || is_item_start(k));
                self.superseded.push(span.to(self.prev().span()));
                return true;
            }
        }
        false
    }

    /// After a block's statements: the keyword `end` must follow. Anything
    /// else is reported; a token that closes an outer block is left for it,
    /// a stray one is skipped and parsing of the body resumes.
    fn close_block(&mut self, end: Keyword, opener: Span, opener_kw: &str, body: &mut Vec<Stmt>) {
        self.close_block_with(end, opener, opener_kw, body, None)
    }

    /// [`Self::close_block`], with a help for the missing END keyword.
    fn close_block_with(
        &mut self,
        end: Keyword,
        opener: Span,
        opener_kw: &str,
        body: &mut Vec<Stmt>,
        help: Option<&str>,
    ) {
        loop {
            if self.eat_kw(end) {
                return;
            }
            let k = self.kind();
            let found = self.describe_current();
            let code = match k {
                TokenKind::Kw(kw) if kw.name().starts_with("END_") => Code::E0021,
                _ if is_item_end(k) => Code::E0021,
                _ => Code::E0020,
            };
            let d = Diagnostic::new(
                code,
                self.tok().span(),
                format!("expected `{}`, found {found}", end.name()),
            )
            .with_label(format!("expected `{}`", end.name()))
            .with_secondary(opener, format!("this {opener_kw} is not closed"));
            let d = match help {
                Some(h) => d.with_help(h),
                None => d,
            };
            self.report(d);
            if self.belongs_to_outer(k) || self.aborted {
                return;
            }
            if code == Code::E0021 {
                // The wrong END keyword, meant for this block: it closes it.
                self.bump();
                return;
            }
            self.bump();
            if self.at(TokenKind::Semi) {
                self.bump();
            }
            body.extend(self.stmt_list(false));
        }
    }

    /// Whether a block-closing token is meant for a block around the current
    /// one (or for the POU), so the current block was left unclosed.
    fn belongs_to_outer(&self, k: TokenKind) -> bool {
        if k == TokenKind::Eof || is_item_end(k) || is_item_start(k) || is_var_block_start(k) {
            return true;
        }
        let outer = &self.open[..self.open.len().saturating_sub(1)];
        if outer.contains(&Open::Case) && self.at_case_label() {
            return true;
        }
        match k {
            TokenKind::Kw(Keyword::Else) => {
                outer.iter().any(|o| matches!(o, Open::If | Open::Case))
            }
            TokenKind::Kw(Keyword::Elsif) => outer.contains(&Open::If),
            TokenKind::Kw(Keyword::Until) => outer.contains(&Open::Repeat),
            TokenKind::Kw(kw) => outer.iter().any(|o| o.end() == kw),
            _ => false,
        }
    }

    fn if_stmt(&mut self) -> StmtKind {
        let opener = self.bump().span();
        self.open.push(Open::If);
        let mut branches = Vec::new();
        let mut else_body = None;
        let cond = self.expr();
        self.then_kw();
        let body = self.stmt_list(false);
        branches.push(CondBranch { cond, body });
        loop {
            if self.eat_kw(Keyword::Elsif) {
                let cond = self.expr();
                self.then_kw();
                let body = self.stmt_list(false);
                branches.push(CondBranch { cond, body });
            } else if self.eat_kw(Keyword::Else) {
                // `ELSE IF` opens a second IF inside the ELSE branch, which
                // takes the one END_IF: when this IF then misses its own,
                // the person meant ELSIF.
                let else_if = self.at_kw(Keyword::If);
                let help = else_if.then_some(
                    "`ELSE IF` opens a new IF inside the ELSE branch, which needs its own `END_IF`; did you mean `ELSIF`?",
                );
                let mut body = self.stmt_list(false);
                // ELSIF or a second ELSE after ELSE: reported, then parsed
                // as if it were allowed, so its statements are still checked.
                while self.at_kw(Keyword::Elsif) || self.at_kw(Keyword::Else) {
                    self.expected("`END_IF`");
                    if self.bump().kind == TokenKind::Kw(Keyword::Elsif) {
                        let cond = self.expr();
                        self.then_kw();
                        let _ = cond;
                    }
                    body.extend(self.stmt_list(false));
                }
                self.close_block_with(Keyword::EndIf, opener, "IF", &mut body, help);
                else_body = Some(body);
                break;
            } else {
                let mut extra = Vec::new();
                self.close_block(Keyword::EndIf, opener, "IF", &mut extra);
                if let Some(last) = branches.last_mut() {
                    last.body.extend(extra);
                }
                break;
            }
        }
        self.open.pop();
        StmtKind::If {
            branches,
            else_body,
        }
    }

    /// `THEN` after a condition; when missing, the body is parsed anyway.
    fn then_kw(&mut self) {
        if !self.eat_kw(Keyword::Then) {
            self.expected("`THEN`");
            // Skip a garbled rest of the condition up to THEN on this line.
            let cond_line_tok = self.tok();
            let mut i = 0;
            while !ends_stmt_list(self.nth_kind(i)) && self.nth_kind(i) != TokenKind::Semi {
                if self.nth_kind(i) == TokenKind::Kw(Keyword::Then) {
                    for _ in 0..=i {
                        self.bump();
                    }
                    return;
                }
                if self.newline_between(cond_line_tok, self.nth(i)) {
                    break;
                }
                i += 1;
            }
        }
    }

    fn case_stmt(&mut self) -> StmtKind {
        let opener = self.bump().span();
        self.open.push(Open::Case);
        let selector = self.expr();
        self.expect_kw(Keyword::Of);
        if self.at_kw(Keyword::EndCase) || self.at_kw(Keyword::Else) {
            self.expected("a CASE label");
        }
        let mut arms = Vec::new();
        while !self.aborted && !ends_stmt_list(self.kind()) {
            let before = self.pos;
            if let Some(arm) = self.case_arm() {
                arms.push(arm);
            }
            if self.pos == before {
                self.bump();
            }
        }
        let mut else_body = None;
        if self.eat_kw(Keyword::Else) {
            let mut body = self.stmt_list(false);
            self.close_block(Keyword::EndCase, opener, "CASE", &mut body);
            else_body = Some(body);
        } else {
            let mut extra = Vec::new();
            self.close_block(Keyword::EndCase, opener, "CASE", &mut extra);
            if let Some(last) = arms.last_mut() {
                last.body.extend(extra);
            }
        }
        self.open.pop();
        StmtKind::Case {
            selector,
            arms,
            else_body,
        }
    }

    fn case_arm(&mut self) -> Option<CaseArm> {
        let start = self.tok().span();
        if !self.at_case_label() {
            self.expected("a CASE label");
            self.skip_stmt();
            return None;
        }
        let mut labels = Vec::new();
        loop {
            let lo = self.expr();
            if self.eat(TokenKind::DotDot) {
                let hi = self.expr();
                labels.push(CaseLabel::Range(lo, hi));
            } else {
                labels.push(CaseLabel::Value(lo));
            }
            if !self.eat(TokenKind::Comma) {
                break;
            }
        }
        if !self.expect(TokenKind::Colon) {
            self.skip_stmt();
        }
        let body = self.stmt_list(true);
        Some(CaseArm {
            labels,
            body,
            span: start.to(self.prev().span()),
        })
    }

    /// Whether a case label (`1:`, `1..5, 7:`, `Red:`, `Color#Red:`, `MAX:`)
    /// starts here, rather than a statement (`MAX := 1;`, `f(x := 1);`).
    fn at_case_label(&self) -> bool {
        match self.kind() {
            TokenKind::Elem(_) if self.nth_kind(1) == TokenKind::Hash => true,
            TokenKind::Int
            | TokenKind::BasedInt
            | TokenKind::Real
            | TokenKind::Minus
            | TokenKind::Plus
            | TokenKind::LParen
            | TokenKind::SString
            | TokenKind::WString
            | TokenKind::Duration
            | TokenKind::Kw(Keyword::True | Keyword::False) => true,
            // A name (reserved words too: a variable may be named like one).
            TokenKind::Ident
            | TokenKind::Elem(_)
            | TokenKind::Generic(_)
            | TokenKind::Kw(Keyword::REdge | Keyword::FEdge) => {
                // Look for the first `:` (a label) or `:=`/`;`/keyword (a
                // statement) outside brackets.
                let mut depth = 0i32;
                let mut i = 0;
                loop {
                    match self.nth_kind(i) {
                        TokenKind::LParen | TokenKind::LBracket => depth += 1,
                        TokenKind::RParen | TokenKind::RBracket => depth -= 1,
                        TokenKind::Colon if depth <= 0 => return true,
                        TokenKind::Assign | TokenKind::Arrow | TokenKind::Semi if depth <= 0 => {
                            return false
                        }
                        TokenKind::Eof => return false,
                        TokenKind::Kw(k)
                            if !matches!(
                                k,
                                Keyword::Mod
                                    | Keyword::And
                                    | Keyword::Or
                                    | Keyword::Xor
                                    | Keyword::Not
                                    | Keyword::True
                                    | Keyword::False
                            ) =>
                        {
                            return false
                        }
                        _ => {}
                    }
                    i += 1;
                }
            }
            _ => false,
        }
    }

    fn for_stmt(&mut self) -> StmtKind {
        let opener = self.bump().span();
        self.open.push(Open::For);
        let var = self.name("the control variable");
        if self.at(TokenKind::Eq) {
            // `FOR i = 1`: reported, then read as `:=`.
            self.expected("`:=`");
            self.bump();
        } else if !self.expect(TokenKind::Assign) {
            // Recover at DO if it is on this statement.
            while !ends_stmt_list(self.kind())
                && !self.at_kw(Keyword::Do)
                && !self.at(TokenKind::Semi)
            {
                self.bump();
            }
        }
        let from = self.expr();
        self.expect_kw(Keyword::To);
        let to = self.expr();
        let by = if self.eat_kw(Keyword::By) {
            Some(self.expr())
        } else {
            None
        };
        self.expect_kw(Keyword::Do);
        let mut body = self.stmt_list(false);
        self.close_block(Keyword::EndFor, opener, "FOR", &mut body);
        self.open.pop();
        match var {
            Some(var) => StmtKind::For {
                var,
                from,
                to,
                by,
                body,
            },
            None => StmtKind::Error,
        }
    }

    fn while_stmt(&mut self) -> StmtKind {
        let opener = self.bump().span();
        self.open.push(Open::While);
        let cond = self.expr();
        self.expect_kw(Keyword::Do);
        let mut body = self.stmt_list(false);
        self.close_block(Keyword::EndWhile, opener, "WHILE", &mut body);
        self.open.pop();
        StmtKind::While { cond, body }
    }

    fn repeat_stmt(&mut self) -> StmtKind {
        let opener = self.bump().span();
        self.open.push(Open::Repeat);
        let mut body = self.stmt_list(false);
        let until = if self.eat_kw(Keyword::Until) {
            self.expr()
        } else {
            let d = Diagnostic::new(
                Code::E0020,
                self.tok().span(),
                format!("expected `UNTIL`, found {}", self.describe_current()),
            )
            .with_label("expected `UNTIL`")
            .with_secondary(opener, "this REPEAT needs `UNTIL condition`");
            self.report(d);
            self.error_expr(self.tok().span())
        };
        self.close_block(Keyword::EndRepeat, opener, "REPEAT", &mut body);
        self.open.pop();
        StmtKind::Repeat { body, until }
    }
}
