//! Sequential Function Chart bodies (IEC 61131-3 2nd edition 2.6, the
//! textual form; docs/sfc.md).
//!
//! A POU body is a chart when, after the variable sections, its first
//! element is a step (`INITIAL_STEP name :`, `STEP name :`), a transition
//! (`TRANSITION FROM`, `TRANSITION name FROM`, `TRANSITION [name]
//! (PRIORITY`) or an action (`ACTION name :`) followed somewhere by a
//! step. The words are not reserved: they are recognised here only. The
//! chart's meaning in ST is made by [`crate::sfc::lower`] once the body is
//! read.

use stc_diagnostics::{Code, Diagnostic, Span};

use super::{is_item_end, is_item_start, Parser};
use crate::ast::{
    ActionAssoc, Ident, IlBody, PouKind, Qualifier, SfcAction, SfcBody, SfcElement, SfcStep,
    SfcTransition, Stmt, TransitionCond, VarBlock,
};
use crate::token::{Keyword, TokenKind};

/// Words that end a statement list inside a chart.
const SFC_WORDS: [&str; 7] = [
    "END_STEP",
    "END_TRANSITION",
    "END_ACTION",
    "STEP",
    "INITIAL_STEP",
    "TRANSITION",
    "ACTION",
];

impl Parser<'_> {
    /// Whether a step starts here.
    fn at_step(&self) -> bool {
        (self.at_word("INITIAL_STEP") || self.at_word("STEP"))
            && self.nth_kind(1) == TokenKind::Ident
            && self.nth_kind(2) == TokenKind::Colon
    }

    /// Whether a transition starts here.
    fn at_transition(&self) -> bool {
        self.at_word("TRANSITION")
            && (self.nth_is_word(1, "FROM")
                || self.nth_kind(1) == TokenKind::LParen && self.nth_is_word(2, "PRIORITY")
                || self.nth_kind(1) == TokenKind::Ident
                    && (self.nth_is_word(2, "FROM") || self.nth_kind(2) == TokenKind::LParen))
    }

    /// Whether an action of a chart starts here.
    fn at_sfc_action(&self) -> bool {
        self.at_word("ACTION")
            && self.nth_kind(1) == TokenKind::Ident
            && self.nth_kind(2) == TokenKind::Colon
    }

    /// Whether the body that starts here is a chart: a step or a
    /// transition, or actions followed by a step before the POU ends.
    pub(crate) fn at_sfc_body(&self) -> bool {
        if self.at_step() || self.at_transition() {
            return true;
        }
        if !self.at_sfc_action() {
            return false;
        }
        let mut n = 0;
        loop {
            let k = self.nth_kind(n);
            if k == TokenKind::Eof || is_item_end(k) || is_item_start(k) {
                return false;
            }
            if (self.nth_is_word(n, "STEP") || self.nth_is_word(n, "INITIAL_STEP"))
                && self.nth_kind(n + 1) == TokenKind::Ident
                && self.nth_kind(n + 2) == TokenKind::Colon
            {
                return true;
            }
            n += 1;
        }
    }

    fn at_sfc_word(&self) -> bool {
        SFC_WORDS.iter().any(|w| self.at_word(w))
    }

    /// Whether an IL body of a chart ends here: at an END word of the
    /// chart or where the next element starts (the words are not reserved,
    /// so an IL operand may be named `STEP`: only the full forms count).
    pub(super) fn at_sfc_end(&self) -> bool {
        ["END_STEP", "END_TRANSITION", "END_ACTION"]
            .iter()
            .any(|w| self.at_word(w))
            || self.at_step()
            || self.at_transition()
            || self.at_sfc_action()
    }

    /// An IL body inside a chart, up to the element's END.
    fn sfc_il(&mut self) -> IlBody {
        let outer = std::mem::replace(&mut self.in_chart_il, true);
        let il = self.il_body();
        self.in_chart_il = outer;
        il
    }

    /// The chart, up to the END of the POU; its ST meaning is `body` and
    /// the state it needs is appended to `var_blocks`.
    pub(crate) fn sfc_body(
        &mut self,
        kind: PouKind,
        var_blocks: &mut Vec<VarBlock>,
    ) -> (SfcBody, Vec<Stmt>) {
        let start = self.tok().span();
        let errors = self.diags.len();
        let mut elements = Vec::new();
        while !self.aborted {
            if self.at_step() {
                if let Some(s) = self.sfc_step() {
                    elements.push(SfcElement::Step(s));
                }
            } else if self.at_word("TRANSITION") {
                if let Some(t) = self.sfc_transition() {
                    elements.push(SfcElement::Transition(t));
                }
            } else if self.at_sfc_action() {
                let a = self.sfc_action();
                elements.push(SfcElement::Action(a));
            } else if self.at(TokenKind::Semi) {
                self.bump();
            } else {
                break;
            }
        }
        if self.diags.len() > errors {
            // What uses what is not known: no warnings that depend on it.
            self.pou_partial = true;
        }
        let span = start.to(self.prev().span());
        let mut sfc = SfcBody {
            elements,
            span,
            generated_blocks: 0,
        };
        let (blocks, body) = crate::sfc::lower(self.ast, self.interner, kind, var_blocks, &sfc);
        sfc.generated_blocks = blocks.len();
        var_blocks.extend(blocks);
        // The generated expressions are shallow: keep the depth table
        // aligned with the arena.
        let len = self.ast.exprs.len() - self.first_expr;
        self.expr_depth.resize(len, 1);
        (sfc, body)
    }

    /// Skips to `end` (included) after an error in an element.
    fn skip_element(&mut self, end: &str) {
        while !self.at(TokenKind::Eof) && !is_item_end(self.kind()) && !is_item_start(self.kind()) {
            if self.at_word(end) {
                self.bump();
                self.eat(TokenKind::Semi);
                return;
            }
            if self.at_step() || self.at_transition() || self.at_sfc_action() {
                return;
            }
            self.bump();
        }
    }

    /// `END_x [;]`, or an error.
    fn sfc_end(&mut self, end: &str, opener: Span, what: &str) -> bool {
        if self.at_word(end) {
            self.bump();
            self.eat(TokenKind::Semi);
            return true;
        }
        let d = Diagnostic::new(
            Code::E0021,
            self.tok().span(),
            format!("expected `{end}`, found {}", self.describe_current()),
        )
        .with_label(format!("expected `{end}`"))
        .with_secondary(opener, format!("this {what} is not closed"));
        self.report(d);
        self.skip_element(end);
        false
    }

    fn sfc_step(&mut self) -> Option<SfcStep> {
        let opener = self.bump();
        let initial = self.text_of(opener).eq_ignore_ascii_case("INITIAL_STEP");
        let name = self.name("a step name")?;
        self.expect(TokenKind::Colon);
        let mut assocs = Vec::new();
        while !self.aborted && self.at(TokenKind::Ident) && !self.at_sfc_word() {
            match self.action_assoc() {
                Some(a) => assocs.push(a),
                None => {
                    self.skip_element("END_STEP");
                    return Some(SfcStep {
                        initial,
                        name,
                        assocs,
                        span: opener.span().to(self.prev().span()),
                    });
                }
            }
        }
        self.sfc_end("END_STEP", opener.span(), "step");
        Some(SfcStep {
            initial,
            name,
            assocs,
            span: opener.span().to(self.prev().span()),
        })
    }

    /// `action(qualifier [, duration] {, indicator});`
    fn action_assoc(&mut self) -> Option<ActionAssoc> {
        let first = self.tok();
        let action = self.name("an action name")?;
        if !self.expect(TokenKind::LParen) {
            return None;
        }
        let mut qualifier = None;
        let mut duration = None;
        let mut indicators = Vec::new();
        if !self.at(TokenKind::RParen) {
            let t = self.tok();
            let q = match t.kind {
                TokenKind::Ident => Qualifier::from_word(self.text_of(t)),
                _ => None,
            };
            let Some(q) = q else {
                self.expected("an action qualifier (N, R, S, L, D, P, P0, P1, SD, DS or SL)");
                return None;
            };
            self.bump();
            qualifier = Some((q, t.span()));
            if q.timed() {
                if !self.eat(TokenKind::Comma) {
                    self.expected(&format!(
                        "`,` and the duration of the qualifier {}",
                        q.name()
                    ));
                    return None;
                }
                duration = Some(self.expr());
            }
            while self.eat(TokenKind::Comma) {
                indicators.push(self.name("an indicator variable")?);
            }
        }
        if !self.expect(TokenKind::RParen) {
            return None;
        }
        let span = first.span().to(self.prev().span());
        if !self.expect(TokenKind::Semi) {
            return None;
        }
        Some(ActionAssoc {
            action,
            qualifier,
            duration,
            indicators,
            span,
        })
    }

    /// One step name, or a parenthesised list of them.
    fn step_list(&mut self) -> Option<(Vec<Ident>, bool)> {
        if self.eat(TokenKind::LParen) {
            let mut names = vec![self.name("a step name")?];
            while self.eat(TokenKind::Comma) {
                names.push(self.name("a step name")?);
            }
            if !self.expect(TokenKind::RParen) {
                return None;
            }
            Some((names, true))
        } else {
            Some((vec![self.name("a step name")?], false))
        }
    }

    fn sfc_transition(&mut self) -> Option<SfcTransition> {
        let opener = self.bump().span();
        let mut name = None;
        if self.at(TokenKind::Ident) && !self.at_word("FROM") {
            name = self.name("a transition name");
        }
        let mut priority = None;
        if self.at(TokenKind::LParen) && self.nth_is_word(1, "PRIORITY") {
            self.bump();
            self.bump();
            if !self.expect(TokenKind::Assign) {
                self.skip_element("END_TRANSITION");
                return None;
            }
            priority = Some(self.expr());
            if !self.expect(TokenKind::RParen) {
                self.skip_element("END_TRANSITION");
                return None;
            }
        }
        if !self.at_word("FROM") {
            self.expected("`FROM`");
            self.skip_element("END_TRANSITION");
            return None;
        }
        self.bump();
        let Some((from, from_parens)) = self.step_list() else {
            self.skip_element("END_TRANSITION");
            return None;
        };
        if !self.expect_kw(Keyword::To) {
            self.skip_element("END_TRANSITION");
            return None;
        }
        let Some((to, to_parens)) = self.step_list() else {
            self.skip_element("END_TRANSITION");
            return None;
        };
        let cond = if self.eat(TokenKind::Assign) {
            let e = self.expr();
            if !self.expect(TokenKind::Semi) {
                self.skip_element("END_TRANSITION");
                return None;
            }
            TransitionCond::Expr(e)
        } else if self.eat(TokenKind::Colon) {
            if !self.at_sfc_end() && self.at_il_body() {
                TransitionCond::Il(self.sfc_il())
            } else {
                TransitionCond::Body(self.sfc_stmts())
            }
        } else {
            self.expected("`:=` and the condition, or `:` and statements");
            self.skip_element("END_TRANSITION");
            return None;
        };
        self.sfc_end("END_TRANSITION", opener, "transition");
        Some(SfcTransition {
            name,
            priority,
            from,
            from_parens,
            to,
            to_parens,
            cond,
            span: opener.to(self.prev().span()),
        })
    }

    fn sfc_action(&mut self) -> SfcAction {
        let opener = self.bump().span();
        let t = self.bump();
        let name = self.intern_token(t);
        self.bump(); // `:`
        let (body, il) = if !self.at_sfc_end() && self.at_il_body() {
            (Vec::new(), Some(self.sfc_il()))
        } else {
            (self.sfc_stmts(), None)
        };
        self.sfc_end("END_ACTION", opener, "action");
        SfcAction {
            name,
            body,
            il,
            span: opener.to(self.prev().span()),
        }
    }

    /// Statements up to an END word of the chart (or anything that ends a
    /// statement list).
    fn sfc_stmts(&mut self) -> Vec<Stmt> {
        let mut out = Vec::new();
        while !self.aborted && !super::stmt::ends_stmt_list(self.kind()) && !self.at_sfc_word() {
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
}
