//! The layout pass: tokens and trivia in, canonical text out.
//!
//! The formatter rewrites only what lies *between* tokens (white space) and
//! the case of reserved words; every token and every comment and pragma is
//! written with its source text, in source order. So the output can differ
//! from the input only in the ways [`crate::format`] then checks (the tree
//! and the trivia are compared after every run).
//!
//! Structure comes from a stack of open blocks (POU, VAR block, IF, CASE...)
//! kept from the keywords themselves, which is all layout needs: where a
//! line must end (after `;`, THEN, DO, a CASE label...), how deep the next
//! line is indented, and where a user's own line break is a continuation of
//! the same statement (indented one level more). Line breaks the user wrote
//! inside a statement are kept; blank lines are kept, at most one in a row.
//!
//! Instruction List is line-oriented, so tokens alone cannot tell where an
//! IL body is: the parser finds the bodies ([`IlRegions`]) and, inside
//! them, the layout keeps each line break the user wrote (one instruction
//! per line, a label alone or before its instruction), indents every line
//! at the body's level plus the nesting of parenthesised sequences and
//! parameter lists, spaces tokens canonically, and writes the operators in
//! the case of reserved words.

use stc_syntax::ast::{
    Ast, IlArg, IlArgKind, IlArgValue, IlBody, IlCallArgs, IlInstr, IlOp, Item, SfcElement,
    TransitionCond,
};
use stc_syntax::lexer::{Trivia, TriviaKind};
use stc_syntax::token::{ElemType, Keyword, Token, TokenKind};

use crate::{KeywordCase, Options};

/// Where the Instruction List bodies of a file are (byte ranges from the
/// file's start, in order), and the operators in them.
#[derive(Default, Debug)]
pub(crate) struct IlRegions {
    bodies: Vec<(usize, usize)>,
    /// The byte ranges of the operator words (`LD`, `JMPC`, `&N`...).
    ops: Vec<(usize, usize)>,
}

impl IlRegions {
    /// The IL bodies of POUs and of charts' actions and transitions.
    pub(crate) fn of(ast: &Ast, base: u32) -> IlRegions {
        let mut r = IlRegions::default();
        for item in &ast.items {
            let Item::Pou(pou) = item else { continue };
            if let Some(il) = &pou.il {
                r.body(il, base);
            }
            for e in pou.sfc.iter().flat_map(|s| &s.elements) {
                match e {
                    SfcElement::Action(a) => {
                        if let Some(il) = &a.il {
                            r.body(il, base);
                        }
                    }
                    SfcElement::Transition(t) => {
                        if let TransitionCond::Il(il) = &t.cond {
                            r.body(il, base);
                        }
                    }
                    SfcElement::Step(_) => {}
                }
            }
        }
        r.bodies.sort_unstable();
        r.ops.sort_unstable();
        r
    }

    fn body(&mut self, il: &IlBody, base: u32) {
        if il.instrs.is_empty() {
            return;
        }
        let at = |p: u32| p.saturating_sub(base) as usize;
        self.bodies.push((at(il.span.lo), at(il.span.hi)));
        self.instrs(&il.instrs, base);
    }

    fn instrs(&mut self, list: &[IlInstr], base: u32) {
        let at = |p: u32| p.saturating_sub(base) as usize;
        for ins in list {
            match &ins.op {
                IlOp::None => {}
                IlOp::Simple { op_span, .. }
                | IlOp::Jump { op_span, .. }
                | IlOp::Ret { op_span, .. } => self.ops.push((at(op_span.lo), at(op_span.hi))),
                IlOp::Paren { op_span, body, .. } => {
                    self.ops.push((at(op_span.lo), at(op_span.hi)));
                    self.instrs(body, base);
                }
                IlOp::Call { .. } => {}
                IlOp::FormalCall { args, .. } => self.args(args, base),
                IlOp::Cal { op_span, args, .. } => {
                    self.ops.push((at(op_span.lo), at(op_span.hi)));
                    if let Some(IlCallArgs::Formal(args)) = args {
                        self.args(args, base);
                    }
                }
            }
        }
    }

    fn args(&mut self, args: &[IlArg], base: u32) {
        for a in args {
            if let IlArgKind::Input {
                value: IlArgValue::List { body, .. },
                ..
            } = &a.kind
            {
                self.instrs(body, base);
            }
        }
    }

    /// The IL body the byte at `lo` is in.
    fn body_at(&self, lo: usize) -> Option<usize> {
        let k = self.bodies.partition_point(|&(b, _)| b <= lo);
        k.checked_sub(1).filter(|&k| lo < self.bodies[k].1)
    }

    fn is_op(&self, lo: usize) -> bool {
        let k = self.ops.partition_point(|&(b, _)| b <= lo);
        k.checked_sub(1).is_some_and(|k| lo < self.ops[k].1)
    }
}

#[derive(Clone, Copy, PartialEq, Eq, Debug)]
enum Block {
    Pou,
    /// A METHOD of a function block (its words are identifiers).
    Method,
    /// A PROPERTY of a function block, and its GET or SET (identifiers).
    Property,
    Accessor,
    Type,
    Struct,
    Var,
    Config,
    Resource,
    If,
    Case,
    For,
    While,
    Repeat,
    /// `NAMESPACE ... END_NAMESPACE` (3rd edition; identifiers): its items
    /// one level in.
    Namespace,
    /// The elements of a Sequential Function Chart (their words are not
    /// reserved: recognised at the start of a statement of a POU body).
    Step,
    Transition,
    Action,
}

#[derive(Clone, Copy, Debug)]
struct Frame {
    block: Block,
    /// Indentation level of the line that opened the block.
    indent: usize,
    /// Still in the block's head (`IF cond` before THEN, a POU's name line).
    header: bool,
    /// In a CASE: inside an arm (after its label), whose body is one level
    /// deeper than the labels.
    arm: bool,
}

#[derive(Clone, Copy, PartialEq, Eq, Debug)]
enum Pending {
    None,
    /// The next token starts a new line.
    Break,
    /// The next token starts a new line unless it is a `;` (after END_IF...).
    BreakUnlessSemi,
}

/// One element of the source in order: a token (index into the tokens) or
/// a comment/pragma.
#[derive(Clone, Copy)]
enum Elem {
    Tok(usize),
    Triv(Trivia),
}

struct Layout<'a> {
    text: &'a str,
    base: u32,
    toks: &'a [Token],
    opts: &'a Options,
    out: String,
    /// Whether the current output line has content.
    line_has_content: bool,
    stack: Vec<Frame>,
    depth: usize,
    pending: Pending,
    at_stmt_start: bool,
    /// After VAR (and its qualifiers) until the first declaration.
    var_header: bool,
    /// The tokens from a CASE label's first token to its `:`.
    in_label: bool,
    prev_tok: Option<TokenKind>,
    /// The previous token was a unary `+`/`-`.
    prev_unary: bool,
    prev_was_line_comment: bool,
    prev_was_trivia: bool,
    /// On the head line of a NAMESPACE: its first item follows without a
    /// blank line.
    in_ns_head: bool,
    /// Indentation of the current output line.
    line_indent: usize,
    il: &'a IlRegions,
    /// The IL body the last token was in, and the nesting of parentheses
    /// in it.
    il_body: Option<usize>,
    il_depth: usize,
    /// The last token was the `(` of a sequence (`AND(`, `IN := (`).
    il_paren_op: bool,
    prev_i: usize,
}

/// Lays out `text` (whose first byte is at `base`) from its tokens and
/// trivia. Never fails: the caller checks the result.
pub(crate) fn layout(
    text: &str,
    base: u32,
    toks: &[Token],
    trivia: &[Trivia],
    il: &IlRegions,
    opts: &Options,
) -> String {
    let mut elems = Vec::with_capacity(toks.len() + trivia.len());
    let (mut i, mut j) = (0, 0);
    let ntoks = toks
        .iter()
        .position(|t| t.kind == TokenKind::Eof)
        .unwrap_or(toks.len());
    while i < ntoks || j < trivia.len() {
        if j < trivia.len() && (i >= ntoks || trivia[j].span.lo < toks[i].lo) {
            elems.push(Elem::Triv(trivia[j]));
            j += 1;
        } else {
            elems.push(Elem::Tok(i));
            i += 1;
        }
    }
    let mut l = Layout {
        text,
        base,
        toks: &toks[..ntoks],
        opts,
        out: String::with_capacity(text.len() + text.len() / 8),
        line_has_content: false,
        stack: Vec::new(),
        depth: 0,
        pending: Pending::None,
        at_stmt_start: true,
        var_header: false,
        in_label: false,
        prev_tok: None,
        prev_unary: false,
        prev_was_line_comment: false,
        prev_was_trivia: false,
        in_ns_head: false,
        line_indent: 0,
        il,
        il_body: None,
        il_depth: 0,
        il_paren_op: false,
        prev_i: 0,
    };
    let start = if text.starts_with('\u{FEFF}') { 3 } else { 0 };
    let mut prev_end = start;
    for e in elems {
        let (lo, hi) = match e {
            Elem::Tok(i) => (toks[i].lo, toks[i].hi),
            Elem::Triv(t) => (t.span.lo, t.span.hi),
        };
        let (lo, hi) = ((lo - base) as usize, (hi - base) as usize);
        let newlines = text
            .get(prev_end..lo)
            .map_or(0, |gap| gap.bytes().filter(|&b| b == b'\n').count());
        match e {
            Elem::Tok(i) => l.token(i, newlines),
            Elem::Triv(t) => l.trivia(t, newlines),
        }
        prev_end = hi;
    }
    if l.line_has_content {
        l.out.push('\n');
    }
    l.out
}

fn is_operand_end(k: TokenKind) -> bool {
    matches!(
        k,
        TokenKind::Ident
            | TokenKind::Int
            | TokenKind::BasedInt
            | TokenKind::Real
            | TokenKind::SString
            | TokenKind::WString
            | TokenKind::Duration
            | TokenKind::Date
            | TokenKind::Tod
            | TokenKind::Dt
            | TokenKind::Address
            | TokenKind::PartialAccess
            | TokenKind::RParen
            | TokenKind::RBracket
            | TokenKind::Caret
            | TokenKind::Kw(Keyword::True | Keyword::False)
    )
}

/// The block an END keyword closes.
fn closes(k: Keyword) -> Option<Block> {
    Some(match k {
        Keyword::EndIf => Block::If,
        Keyword::EndCase => Block::Case,
        Keyword::EndFor => Block::For,
        Keyword::EndWhile => Block::While,
        Keyword::EndRepeat => Block::Repeat,
        Keyword::EndVar => Block::Var,
        Keyword::EndType => Block::Type,
        Keyword::EndStruct => Block::Struct,
        Keyword::EndProgram | Keyword::EndFunction | Keyword::EndFunctionBlock => Block::Pou,
        Keyword::EndConfiguration => Block::Config,
        Keyword::EndResource => Block::Resource,
        _ => return None,
    })
}

fn is_var_keyword(k: Keyword) -> bool {
    matches!(
        k,
        Keyword::Var
            | Keyword::VarAccess
            | Keyword::VarConfig
            | Keyword::VarExternal
            | Keyword::VarGlobal
            | Keyword::VarInOut
            | Keyword::VarInput
            | Keyword::VarOutput
            | Keyword::VarTemp
    )
}

impl<'a> Layout<'a> {
    fn src(&self, i: usize) -> &'a str {
        let t = &self.toks[i];
        &self.text[(t.lo - self.base) as usize..(t.hi - self.base) as usize]
    }

    /// Indentation of a line that starts a statement or declaration in the
    /// innermost open block.
    fn body_level(&self) -> usize {
        match self.stack.last() {
            None => 0,
            Some(f) if f.block == Block::Case && f.arm => f.indent + 2,
            Some(f) => f.indent + 1,
        }
    }

    fn newline(&mut self, indent: usize, blank: bool) {
        if self.line_has_content {
            self.out.push('\n');
        }
        if blank && !self.out.is_empty() && !self.out.ends_with("\n\n") {
            self.out.push('\n');
        }
        for _ in 0..indent * self.opts.indent_width {
            self.out.push(' ');
        }
        self.line_indent = indent;
        self.line_has_content = false;
    }

    fn trivia(&mut self, t: Trivia, newlines: usize) {
        let lo = (t.span.lo - self.base) as usize;
        let hi = (t.span.hi - self.base) as usize;
        let text = self.text[lo..hi].trim_end_matches(['\r', '\n']);
        if self.il.body_at(lo).is_some() && self.il_body.is_some() {
            if newlines > 0 || self.prev_was_line_comment {
                self.newline(self.body_level() + self.il_depth, newlines > 1);
            } else if self.line_has_content {
                self.out.push(' ');
            }
            self.out.push_str(text);
            self.line_has_content = true;
            self.prev_was_line_comment = t.kind == TriviaKind::Comment && text.starts_with("//");
            self.prev_was_trivia = true;
            return;
        }
        if newlines > 0 {
            self.end_head_line();
        }
        if self.line_has_content && newlines == 0 && !self.prev_was_line_comment {
            self.out.push(' ');
        } else if self.line_has_content || self.out.is_empty() || newlines > 0 {
            let level = if self.at_stmt_start || self.pending != Pending::None || self.var_header {
                self.body_level()
            } else {
                self.body_level() + 1
            };
            self.newline(level, newlines > 1);
        }
        self.out.push_str(text);
        self.line_has_content = true;
        self.prev_was_line_comment = t.kind == TriviaKind::Comment && text.starts_with("//");
        self.prev_was_trivia = true;
    }

    /// Whether the tokens from `i` up to a `:` at depth 0 are a CASE label
    /// (a statement reaches `:=`, `;` or a keyword first).
    fn is_case_label(&self, i: usize) -> bool {
        let mut depth = 0usize;
        for t in &self.toks[i..] {
            match t.kind {
                TokenKind::LParen | TokenKind::LBracket => depth += 1,
                TokenKind::RParen | TokenKind::RBracket => depth = depth.saturating_sub(1),
                TokenKind::Colon if depth == 0 => return true,
                TokenKind::Assign | TokenKind::Semi | TokenKind::Arrow => return false,
                TokenKind::Kw(k) if !matches!(k, Keyword::True | Keyword::False) => return false,
                _ => {}
            }
        }
        false
    }

    fn kind(&self, i: usize) -> TokenKind {
        let k = self.toks[i].kind;
        if self.opts.iec2 && stc_syntax::parser::third_edition_word(k) {
            TokenKind::Ident
        } else {
            k
        }
    }

    fn token(&mut self, i: usize, newlines: usize) {
        let lo = (self.toks[i].lo - self.base) as usize;
        if let Some(b) = self.il.body_at(lo) {
            self.il_token(i, newlines, b);
            return;
        }
        self.il_body = None;
        let kind = self.kind(i);
        let top = self.stack.last().copied();
        // Where this token's line must start, if it must start one.
        let mut forced: Option<usize> = None;
        let mut blank = newlines > 1;
        let after_ns_head = newlines > 0 && std::mem::take(&mut self.in_ns_head);
        let mut push: Option<Block> = None;

        if self.var_header {
            let qualifier = matches!(
                kind,
                TokenKind::Kw(Keyword::Constant | Keyword::Retain | Keyword::NonRetain)
            ) || (kind == TokenKind::Ident
                && ["PERSISTENT", "PUBLIC", "PRIVATE", "PROTECTED", "INTERNAL"]
                    .iter()
                    .any(|w| self.src(i).eq_ignore_ascii_case(w))
                && self
                    .toks
                    .get(i + 1)
                    .is_none_or(|t| !matches!(t.kind, TokenKind::Colon | TokenKind::Comma)));
            if !qualifier {
                self.var_header = false;
                self.at_stmt_start = true;
                forced = Some(self.body_level());
            }
        }
        if newlines > 0 {
            self.end_head_line();
        }
        // Between items: outside everything, or directly in namespaces.
        let top_level = self.stack.iter().all(|f| f.block == Block::Namespace);
        let in_config = matches!(top.map(|f| f.block), Some(Block::Config | Block::Resource));
        let sfc_open = self.sfc_opens(i, top);
        let sfc_close = self.sfc_closes(i);
        match kind {
            _ if sfc_open.is_some() => {
                forced = Some(self.body_level());
                push = sfc_open;
            }
            _ if sfc_close.is_some() => {
                if let Some(pos) = self.stack.iter().rposition(|f| Some(f.block) == sfc_close) {
                    let f = self.stack[pos];
                    self.stack.truncate(pos);
                    forced = Some(f.indent);
                } else {
                    forced = Some(self.body_level());
                }
            }
            TokenKind::Ident if top_level && self.opens_namespace(i) => {
                forced = Some(self.body_level());
                blank |= self.prev_tok.is_some() && !self.prev_was_trivia && !after_ns_head;
                push = Some(Block::Namespace);
                self.in_ns_head = true;
            }
            TokenKind::Ident
                if self.src(i).eq_ignore_ascii_case("END_NAMESPACE")
                    && self
                        .stack
                        .last()
                        .is_some_and(|f| f.block == Block::Namespace) =>
            {
                if let Some(f) = self.stack.pop() {
                    forced = Some(f.indent);
                }
            }
            TokenKind::Ident if top_level && self.opens_class(i) => {
                forced = Some(self.body_level());
                blank |= self.prev_tok.is_some() && !self.prev_was_trivia && !after_ns_head;
                push = Some(Block::Pou);
            }
            TokenKind::Ident if self.closes_class(i) => {
                if let Some(pos) = self.stack.iter().rposition(|f| f.block == Block::Pou) {
                    let f = self.stack[pos];
                    self.stack.truncate(pos);
                    forced = Some(f.indent);
                }
            }
            TokenKind::Kw(k) if closes(k).is_some() => {
                let b = closes(k);
                if let Some(pos) = self.stack.iter().rposition(|f| Some(f.block) == b) {
                    let f = self.stack[pos];
                    self.stack.truncate(pos);
                    forced = Some(f.indent);
                } else {
                    forced = Some(self.body_level());
                }
            }
            TokenKind::Kw(Keyword::Elsif) if top.map(|f| f.block) == Some(Block::If) => {
                forced = top.map(|f| f.indent);
                if let Some(f) = self.stack.last_mut() {
                    f.header = true;
                }
            }
            TokenKind::Kw(Keyword::Else) => match top.map(|f| f.block) {
                Some(Block::If) => forced = top.map(|f| f.indent),
                Some(Block::Case) => {
                    if let Some(f) = self.stack.last_mut() {
                        f.arm = false;
                        forced = Some(f.indent + 1);
                    }
                }
                _ => {}
            },
            TokenKind::Kw(Keyword::Until) if top.map(|f| f.block) == Some(Block::Repeat) => {
                forced = top.map(|f| f.indent);
            }
            TokenKind::Kw(k) if is_var_keyword(k) => {
                forced = Some(self.body_level());
                blank |=
                    top_level && self.prev_tok.is_some() && !self.prev_was_trivia && !after_ns_head;
                push = Some(Block::Var);
            }
            TokenKind::Kw(Keyword::Type) => {
                forced = Some(self.body_level());
                blank |=
                    top_level && self.prev_tok.is_some() && !self.prev_was_trivia && !after_ns_head;
                push = Some(Block::Type);
            }
            TokenKind::Kw(Keyword::Program | Keyword::Function | Keyword::FunctionBlock)
                if !in_config =>
            {
                forced = Some(self.body_level());
                blank |=
                    top_level && self.prev_tok.is_some() && !self.prev_was_trivia && !after_ns_head;
                push = Some(Block::Pou);
            }
            TokenKind::Kw(Keyword::Configuration) => {
                forced = Some(self.body_level());
                blank |=
                    top_level && self.prev_tok.is_some() && !self.prev_was_trivia && !after_ns_head;
                push = Some(Block::Config);
            }
            TokenKind::Kw(Keyword::Resource) => {
                forced = Some(self.body_level());
                push = Some(Block::Resource);
            }
            TokenKind::Kw(Keyword::Task | Keyword::Program) => {
                forced = Some(self.body_level());
            }
            TokenKind::Ident if self.opens_method(i) => {
                forced = Some(self.body_level());
                push = Some(Block::Method);
            }
            TokenKind::Ident if self.opens_property(i) => {
                forced = Some(self.body_level());
                push = Some(Block::Property);
            }
            TokenKind::Ident if self.opens_accessor(i) => {
                if let Some(f) = self.stack.last_mut() {
                    f.header = false;
                }
                forced = Some(self.body_level());
                push = Some(Block::Accessor);
            }
            TokenKind::Ident if self.closes_property_part(i).is_some() => {
                let b = self.closes_property_part(i);
                if let Some(pos) = self.stack.iter().rposition(|f| Some(f.block) == b) {
                    let f = self.stack[pos];
                    self.stack.truncate(pos);
                    forced = Some(f.indent);
                }
            }
            TokenKind::Ident if self.closes_method(i) => {
                if let Some(pos) = self.stack.iter().rposition(|f| f.block == Block::Method) {
                    let f = self.stack[pos];
                    self.stack.truncate(pos);
                    forced = Some(f.indent);
                }
            }
            TokenKind::Kw(Keyword::If) => push = Some(Block::If),
            TokenKind::Kw(Keyword::Case) => push = Some(Block::Case),
            TokenKind::Kw(Keyword::For) => push = Some(Block::For),
            TokenKind::Kw(Keyword::While) => push = Some(Block::While),
            TokenKind::Kw(Keyword::Repeat) => push = Some(Block::Repeat),
            TokenKind::Kw(Keyword::Struct) => push = Some(Block::Struct),
            _ => {}
        }
        // A CASE label starts a line one level inside the CASE.
        if let Some(f) = self.stack.last().copied() {
            if f.block == Block::Case
                && !f.header
                && self.at_stmt_start
                && self.depth == 0
                && !matches!(kind, TokenKind::Kw(Keyword::Else | Keyword::EndCase))
                && self.is_case_label(i)
            {
                if let Some(f) = self.stack.last_mut() {
                    f.arm = false;
                }
                forced = Some(f.indent + 1);
                self.in_label = true;
            }
        }

        let continuation_break = newlines > 0
            && !matches!(
                kind,
                TokenKind::Semi | TokenKind::Comma | TokenKind::RParen | TokenKind::RBracket
            );
        let must_break = forced.is_some()
            || self.prev_was_line_comment
            || self.pending == Pending::Break
            || (self.pending == Pending::BreakUnlessSemi && kind != TokenKind::Semi)
            || continuation_break;
        if must_break && (self.line_has_content || self.out.is_empty()) {
            let level = forced.unwrap_or_else(|| {
                if self.at_stmt_start || self.pending != Pending::None {
                    self.body_level()
                } else {
                    self.body_level() + 1
                }
            });
            self.newline(level, blank);
        } else if self.line_has_content && self.space_before(kind) {
            self.out.push(' ');
        }
        self.write_token(i, kind);
        self.line_has_content = true;
        self.pending = Pending::None;
        self.prev_was_line_comment = false;
        self.prev_was_trivia = false;
        self.prev_i = i;

        // What the token opens or ends.
        self.prev_unary = matches!(kind, TokenKind::Minus | TokenKind::Plus)
            && !self.prev_tok.is_some_and(is_operand_end);
        self.at_stmt_start = false;
        if let Some(b) = push {
            self.stack.push(Frame {
                block: b,
                indent: self.line_indent,
                header: !matches!(b, Block::Var | Block::Type | Block::Struct | Block::Repeat),
                arm: false,
            });
        }
        if sfc_close.is_some() {
            self.stmt_end(Pending::BreakUnlessSemi);
        }
        match kind {
            TokenKind::Colon
                if self.depth == 0
                    && top.is_some_and(|f| {
                        f.header
                            && matches!(f.block, Block::Step | Block::Transition | Block::Action)
                    }) =>
            {
                self.end_header();
            }
            TokenKind::LParen | TokenKind::LBracket => self.depth += 1,
            TokenKind::RParen | TokenKind::RBracket => self.depth = self.depth.saturating_sub(1),
            TokenKind::Semi if self.depth == 0 => self.stmt_end(Pending::Break),
            TokenKind::Colon if self.in_label => {
                self.in_label = false;
                if let Some(f) = self.stack.last_mut() {
                    f.arm = true;
                }
                self.stmt_end(Pending::Break);
            }
            TokenKind::Kw(Keyword::Then) if top.map(|f| f.block) == Some(Block::If) => {
                self.end_header();
            }
            TokenKind::Kw(Keyword::Do)
                if matches!(top.map(|f| f.block), Some(Block::For | Block::While)) =>
            {
                self.end_header();
            }
            TokenKind::Kw(Keyword::Of)
                if top.is_some_and(|f| f.block == Block::Case && f.header) =>
            {
                self.end_header();
            }
            TokenKind::Kw(Keyword::Else) => {
                if let Some(f) = self.stack.last_mut() {
                    if f.block == Block::Case {
                        f.arm = true;
                    }
                }
                self.stmt_end(Pending::Break);
            }
            TokenKind::Kw(Keyword::Repeat | Keyword::Type | Keyword::Struct) => {
                self.stmt_end(Pending::Break)
            }
            TokenKind::Kw(k) if is_var_keyword(k) => self.var_header = true,
            TokenKind::Kw(k) if closes(k).is_some() => self.stmt_end(Pending::BreakUnlessSemi),
            TokenKind::Ident if self.src(i).eq_ignore_ascii_case("END_METHOD") => {
                self.stmt_end(Pending::BreakUnlessSemi)
            }
            TokenKind::Ident
                if ["END_GET", "END_SET", "END_PROPERTY"]
                    .iter()
                    .any(|w| self.src(i).eq_ignore_ascii_case(w)) =>
            {
                self.stmt_end(Pending::BreakUnlessSemi)
            }
            TokenKind::Ident if push == Some(Block::Accessor) => {
                // `GET` / `SET`: the accessor's body starts on the next line.
                self.end_header();
            }
            TokenKind::Ident if self.closes_class(i) => self.stmt_end(Pending::BreakUnlessSemi),
            _ => {}
        }
        self.prev_tok = Some(kind);
    }

    /// The chart element the token at `i` opens: a step, transition or
    /// action word at the start of a statement directly in a POU body,
    /// followed by what only a chart puts there.
    fn sfc_opens(&self, i: usize, top: Option<Frame>) -> Option<Block> {
        if self.toks[i].kind != TokenKind::Ident
            || !self.at_stmt_start
            || self.depth != 0
            || !top.is_some_and(|f| f.block == Block::Pou)
        {
            return None;
        }
        let word = self.src(i);
        let next = |n: usize| self.toks.get(i + n).map(|t| t.kind);
        let next_is = |n: usize, w: &str| {
            next(n) == Some(TokenKind::Ident)
                && self.toks.get(i + n).is_some_and(|t| {
                    self.text[(t.lo - self.base) as usize..(t.hi - self.base) as usize]
                        .eq_ignore_ascii_case(w)
                })
        };
        let named_colon = next(1) == Some(TokenKind::Ident) && next(2) == Some(TokenKind::Colon);
        if (word.eq_ignore_ascii_case("STEP") || word.eq_ignore_ascii_case("INITIAL_STEP"))
            && named_colon
        {
            return Some(Block::Step);
        }
        if word.eq_ignore_ascii_case("ACTION") && named_colon {
            return Some(Block::Action);
        }
        if word.eq_ignore_ascii_case("TRANSITION")
            && (next_is(1, "FROM")
                || next(1) == Some(TokenKind::LParen)
                || next(1) == Some(TokenKind::Ident)
                    && (next_is(2, "FROM") || next(2) == Some(TokenKind::LParen)))
        {
            return Some(Block::Transition);
        }
        None
    }

    /// The chart element the token at `i` closes (END_STEP...).
    fn sfc_closes(&self, i: usize) -> Option<Block> {
        if self.toks[i].kind != TokenKind::Ident || self.depth != 0 {
            return None;
        }
        let word = self.src(i);
        [
            ("END_STEP", Block::Step),
            ("END_TRANSITION", Block::Transition),
            ("END_ACTION", Block::Action),
        ]
        .into_iter()
        .find(|(w, b)| word.eq_ignore_ascii_case(w) && self.stack.iter().any(|f| f.block == *b))
        .map(|(_, b)| b)
    }

    /// A line break the user wrote ends a POU's, configuration's or
    /// resource's head line: what follows is its body.
    /// `METHOD` starting a method of the function block being laid out
    /// (followed by its name or a modifier).
    fn opens_method(&self, i: usize) -> bool {
        self.src(i).eq_ignore_ascii_case("METHOD")
            && self.stack.last().is_some_and(|f| f.block == Block::Pou)
            && self.at_stmt_start
            && self
                .toks
                .get(i + 1)
                .is_some_and(|t| t.kind == TokenKind::Ident)
    }

    /// `NAMESPACE` opening a namespace (followed by its name, or INTERNAL
    /// and its name).
    fn opens_namespace(&self, i: usize) -> bool {
        self.src(i).eq_ignore_ascii_case("NAMESPACE")
            && self
                .toks
                .get(i + 1)
                .is_some_and(|t| t.kind == TokenKind::Ident)
    }

    /// `CLASS` or `INTERFACE` opening a POU (3rd edition; identifiers),
    /// followed by its name.
    fn opens_class(&self, i: usize) -> bool {
        (self.src(i).eq_ignore_ascii_case("CLASS") || self.src(i).eq_ignore_ascii_case("INTERFACE"))
            && self
                .toks
                .get(i + 1)
                .is_some_and(|t| t.kind == TokenKind::Ident)
            // (Not the INTERFACE part of a logi.CAD UNIT: `USES ...`.)
            && !self.src(i + 1).eq_ignore_ascii_case("USES")
    }

    /// `END_CLASS` or `END_INTERFACE` closing an open POU.
    fn closes_class(&self, i: usize) -> bool {
        (self.src(i).eq_ignore_ascii_case("END_CLASS")
            || self.src(i).eq_ignore_ascii_case("END_INTERFACE"))
            && self.stack.iter().any(|f| f.block == Block::Pou)
    }

    /// `PROPERTY` starting a property of the function block being laid
    /// out (followed by its name or a modifier).
    fn opens_property(&self, i: usize) -> bool {
        self.src(i).eq_ignore_ascii_case("PROPERTY")
            && self.stack.last().is_some_and(|f| f.block == Block::Pou)
            && self.at_stmt_start
            && self
                .toks
                .get(i + 1)
                .is_some_and(|t| t.kind == TokenKind::Ident)
    }

    /// `GET` or `SET` starting an accessor of the property being laid out.
    fn opens_accessor(&self, i: usize) -> bool {
        // (On the PROPERTY's own line too; a property named GET is
        // followed by its `:`.)
        (self.src(i).eq_ignore_ascii_case("GET") || self.src(i).eq_ignore_ascii_case("SET"))
            && self
                .stack
                .last()
                .is_some_and(|f| f.block == Block::Property && (f.header || self.at_stmt_start))
            && self
                .toks
                .get(i + 1)
                .is_none_or(|t| t.kind != TokenKind::Colon)
    }

    /// `END_GET`/`END_SET` (an accessor) or `END_PROPERTY` closing what is
    /// open.
    fn closes_property_part(&self, i: usize) -> Option<Block> {
        let word = self.src(i);
        let b = if word.eq_ignore_ascii_case("END_GET") || word.eq_ignore_ascii_case("END_SET") {
            Block::Accessor
        } else if word.eq_ignore_ascii_case("END_PROPERTY") {
            Block::Property
        } else {
            return None;
        };
        self.stack.iter().any(|f| f.block == b).then_some(b)
    }

    /// `END_METHOD` closing an open method.
    fn closes_method(&self, i: usize) -> bool {
        self.src(i).eq_ignore_ascii_case("END_METHOD")
            && self.stack.iter().any(|f| f.block == Block::Method)
    }

    fn end_head_line(&mut self) {
        if let Some(f) = self.stack.last_mut() {
            if f.header
                && matches!(
                    f.block,
                    Block::Pou
                        | Block::Method
                        | Block::Property
                        | Block::Config
                        | Block::Resource
                        | Block::Namespace
                )
            {
                f.header = false;
                self.at_stmt_start = true;
            }
        }
    }

    fn stmt_end(&mut self, p: Pending) {
        self.pending = p;
        self.at_stmt_start = true;
    }

    fn end_header(&mut self) {
        if let Some(f) = self.stack.last_mut() {
            f.header = false;
        }
        self.stmt_end(Pending::Break);
    }

    /// Whether a space separates the previous token from one of `kind` on
    /// the same line.
    fn space_before(&self, kind: TokenKind) -> bool {
        let Some(prev) = self.prev_tok else {
            return false;
        };
        if self.prev_was_trivia {
            return true;
        }
        match kind {
            TokenKind::RParen
            | TokenKind::RBracket
            | TokenKind::Comma
            | TokenKind::Semi
            | TokenKind::Dot
            | TokenKind::DotDot
            | TokenKind::Hash
            | TokenKind::Caret
            | TokenKind::PartialAccess => return false,
            TokenKind::Colon if self.in_label => return false,
            _ => {}
        }
        match prev {
            TokenKind::LParen | TokenKind::LBracket | TokenKind::Dot | TokenKind::DotDot => {
                return false
            }
            TokenKind::Hash => return false,
            TokenKind::Minus | TokenKind::Plus if self.prev_unary => {
                // `- -x` stays apart so it does not read as one operator.
                return matches!(kind, TokenKind::Minus | TokenKind::Plus);
            }
            _ => {}
        }
        let transition_head = self
            .stack
            .last()
            .is_some_and(|f| f.block == Block::Transition && f.header);
        match kind {
            // `TRANSITION t (PRIORITY := 1)`, `FROM (a, b)`, `TO (c, d)`.
            TokenKind::LParen if transition_head => true,
            TokenKind::LParen => !matches!(prev, TokenKind::Ident),
            TokenKind::LBracket => !matches!(
                prev,
                TokenKind::Ident
                    | TokenKind::RBracket
                    | TokenKind::RParen
                    | TokenKind::Kw(Keyword::Array)
                    | TokenKind::Elem(ElemType::String | ElemType::Wstring)
            ),
            _ => true,
        }
    }

    /// A token of an IL body: a line break where the user wrote one (IL is
    /// line-oriented), the body's indentation plus the open parentheses.
    fn il_token(&mut self, i: usize, newlines: usize, body: usize) {
        let kind = self.kind(i);
        let first = self.il_body != Some(body);
        if first {
            self.il_body = Some(body);
            self.il_depth = 0;
            self.end_head_line();
        }
        if first || newlines > 0 || self.prev_was_line_comment {
            let depth = if kind == TokenKind::RParen {
                self.il_depth.saturating_sub(1)
            } else {
                self.il_depth
            };
            self.newline(self.body_level() + depth, newlines > 1);
        } else if self.line_has_content && self.il_space_before(i, kind) {
            self.out.push(' ');
        }
        let lo = (self.toks[i].lo - self.base) as usize;
        let op = self.il.is_op(lo);
        // The operators are words of the language: written like reserved
        // words.
        self.write_word(i, op || kind.is_reserved_word());
        self.line_has_content = true;
        self.prev_was_line_comment = false;
        self.prev_was_trivia = false;
        // The `(` of a sequence (after an operator, or a parameter's `:=`)
        // is followed by an instruction: `AND( x`, `IN := ( LD a`.
        self.il_paren_op = kind == TokenKind::LParen
            && self.prev_tok.is_some_and(|p| {
                p == TokenKind::Assign || {
                    let at = (self.toks[self.prev_i].hi - self.base) as usize;
                    self.il.is_op(at.saturating_sub(1))
                }
            });
        match kind {
            TokenKind::LParen => self.il_depth += 1,
            TokenKind::RParen => self.il_depth = self.il_depth.saturating_sub(1),
            _ => {}
        }
        // What follows the body starts a line of its own.
        self.pending = Pending::Break;
        self.at_stmt_start = true;
        self.prev_unary = false;
        self.prev_tok = Some(kind);
        self.prev_i = i;
    }

    /// Whether a space separates two tokens of one IL line.
    fn il_space_before(&self, i: usize, kind: TokenKind) -> bool {
        let Some(prev) = self.prev_tok else {
            return false;
        };
        if self.prev_was_trivia {
            return true;
        }
        // `&N` and a signed literal (`-5`) keep the source's joining.
        if matches!(prev, TokenKind::Amp | TokenKind::Minus | TokenKind::Plus) {
            return self.toks[self.prev_i].hi != self.toks[i].lo;
        }
        match kind {
            TokenKind::RParen
            | TokenKind::Comma
            | TokenKind::Dot
            | TokenKind::Hash
            | TokenKind::Caret
            | TokenKind::PartialAccess
            | TokenKind::RBracket
            | TokenKind::Colon => return false,
            TokenKind::LParen => {
                return !matches!(prev, TokenKind::Ident | TokenKind::Kw(_) | TokenKind::Amp)
            }
            TokenKind::LBracket => return !matches!(prev, TokenKind::Ident | TokenKind::RBracket),
            _ => {}
        }
        match prev {
            TokenKind::LParen => self.il_paren_op,
            TokenKind::LBracket | TokenKind::Dot | TokenKind::Hash => false,
            _ => true,
        }
    }

    fn write_token(&mut self, i: usize, kind: TokenKind) {
        self.write_word(i, kind.is_reserved_word());
    }

    /// Writes the token's text, in the case of reserved words if `reserved`.
    fn write_word(&mut self, i: usize, reserved: bool) {
        let src = self.src(i);
        match self.opts.keyword_case {
            KeywordCase::Upper if reserved => self.out.push_str(&src.to_ascii_uppercase()),
            KeywordCase::Lower if reserved => self.out.push_str(&src.to_ascii_lowercase()),
            _ => self.out.push_str(src),
        }
    }
}
