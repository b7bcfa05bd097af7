//! The parser: tokens to [`Ast`], by hand-written recursive descent with
//! precedence climbing for expressions.
//!
//! Error recovery is the design driver. Each construct that fails reports one
//! diagnostic and resynchronises at a point the grammar makes safe (the next
//! `;` of a statement or declaration, the END keyword of a block, the next
//! POU), so a file with three independent mistakes gets three diagnostics. A
//! second error at the same token is never reported. Block ends are matched
//! against a stack of the blocks that are open, so a missing `END_IF` is
//! reported once at the construct that needed it, not again at every outer
//! block.
//!
//! Deep nesting is bounded ([`MAX_NESTING`] for recursion, [`MAX_EXPR_DEPTH`]
//! for the depth of an expression tree, including long left-associative
//! chains) so that no input can overflow the stack of the parser or of any
//! later phase walking the tree.

mod decl;
mod expr;
mod il;
mod sfc;
mod stmt;

use stc_diagnostics::{Code, Diagnostic, Span};

use crate::ast::{Ast, ExprId, ExprKind, Ident, Item, Method, NamespaceDecl, PouKind, UsingDecl};
use crate::intern::Interner;
use crate::lexer::{lex, Trivia, TriviaKind};
use crate::token::{ElemType, Keyword, Token, TokenKind};

/// Deepest recursion of nested statements, parentheses and types.
pub const MAX_NESTING: u32 = 256;
/// Deepest expression tree.
pub const MAX_EXPR_DEPTH: u32 = 4096;

/// What parsing one file produced besides the items added to the [`Ast`].
pub struct FileParse {
    pub trivia: Vec<Trivia>,
    pub diagnostics: Vec<Diagnostic>,
}

/// Lexes and parses one file (whose first byte is at `base` in the source
/// map), appending its items to `ast`.
pub fn parse_file(text: &str, base: u32, ast: &mut Ast, interner: &mut Interner) -> FileParse {
    parse_file_in(text, base, ast, interner, false)
}

/// The words the 3rd edition made keywords: in 2nd-edition code (`--std
/// iec2`) they are ordinary names (`char : BYTE;`, a member `LDT`).
pub fn third_edition_word(k: TokenKind) -> bool {
    matches!(
        k,
        TokenKind::Elem(
            ElemType::Char
                | ElemType::Wchar
                | ElemType::Ltime
                | ElemType::Ldate
                | ElemType::Ltod
                | ElemType::Ldt
        ) | TokenKind::Kw(Keyword::Continue)
    )
}

/// Reserved words that 2nd-edition code uses as names and whose use as a
/// name is unambiguous: the 3rd edition's new words, and the edge
/// qualifiers, which only mean something after a declaration's type.
fn soft_reserved_word(k: TokenKind) -> bool {
    third_edition_word(k) || matches!(k, TokenKind::Kw(Keyword::REdge | Keyword::FEdge))
}

/// [`parse_file`] for an edition: with `iec2`, the words the 3rd edition
/// reserved are names.
pub fn parse_file_in(
    text: &str,
    base: u32,
    ast: &mut Ast,
    interner: &mut Interner,
    iec2: bool,
) -> FileParse {
    let mut lexed = lex(text, base);
    if iec2 {
        for t in lexed.tokens.iter_mut() {
            if third_edition_word(t.kind) {
                t.kind = TokenKind::Ident;
            }
        }
    }
    let mut diagnostics = lexed.diagnostics;
    let pragmas: Vec<Span> = lexed
        .trivia
        .iter()
        .filter(|t| t.kind == TriviaKind::Pragma)
        .map(|t| t.span)
        .collect();
    let first_expr = ast.exprs.len();
    // A comment or pragma left open runs to the end of the file, which
    // already has its error: "found end of file" would say it again.
    let runs_to_eof = diagnostics
        .iter()
        .any(|d| matches!(d.code, Code::E0002 | Code::E0004));
    let eof_index = lexed.tokens.len() - 1;
    let mut p = Parser {
        text,
        base,
        toks: lexed.tokens,
        pos: 0,
        ast,
        interner,
        diags: Vec::new(),
        pragmas,
        next_pragma: 0,
        nesting: 0,
        first_expr,
        expr_depth: Vec::new(),
        last_error_pos: if runs_to_eof { eof_index } else { usize::MAX },
        aborted: false,
        open: Vec::new(),
        superseded: Vec::new(),
        pou_partial: false,
        pou_skipped: Vec::new(),
        pou_kind: None,
        in_property: false,
        late_methods: Vec::new(),
        in_method: false,
        in_action: false,
        in_chart_il: false,
        reserved_names: Vec::new(),
        unit: UnitPart::Outside,
        namespaces: Vec::new(),
    };
    p.file();
    // A `__` operator reported as not supported is not also an invalid
    // identifier: one diagnostic for the one construct.
    let superseded = std::mem::take(&mut p.superseded);
    diagnostics.retain(|d| {
        !matches!(d.code, Code::E0005 | Code::W0008)
            || !superseded
                .iter()
                .any(|s| s.lo <= d.span.lo && d.span.hi <= s.hi)
    });
    diagnostics.append(&mut p.diags);
    for span in p
        .pragmas
        .iter()
        .filter(|s| text.as_bytes()[(s.hi - base) as usize - 1] == b'}')
    {
        diagnostics.extend(pragma_diagnostic(
            *span,
            &text[(span.lo - base) as usize..(span.hi - base) as usize],
        ));
    }
    diagnostics.sort_by_key(|d| d.span.lo);
    FileParse {
        trivia: lexed.trivia,
        diagnostics,
    }
}

/// What an ignored pragma is worth saying: nothing for the CODESYS/TwinCAT
/// `{attribute '...'}` pragmas (they tune the vendor's IDE, compiler or HMI
/// and never change what a program computes), W0002 for anything else.
fn pragma_diagnostic(span: Span, text: &str) -> Option<Diagnostic> {
    let inner = text.trim_start_matches('{').trim_end_matches('}').trim();
    let word: String = inner
        .chars()
        .take_while(|c| c.is_ascii_alphanumeric() || *c == '_')
        .collect();
    if word.eq_ignore_ascii_case("attribute") {
        None
    } else {
        // The first line, shortened: a message is one line.
        let first = text.lines().next().unwrap_or("");
        let words: Vec<&str> = first.split_whitespace().collect();
        let first = words.join(" ");
        let mut shown: String = first.chars().take(40).collect();
        if shown.len() < first.len() || text.trim_end().contains('\n') {
            shown.push_str(" …");
        }
        Some(Diagnostic::new(
            Code::W0002,
            span,
            format!("pragma `{shown}` is not understood and is ignored"),
        ))
    }
}

/// Blocks that can be open while statements are parsed, for END matching.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
pub(crate) enum Open {
    If,
    Case,
    For,
    While,
    Repeat,
}

impl Open {
    fn end(self) -> Keyword {
        match self {
            Open::If => Keyword::EndIf,
            Open::Case => Keyword::EndCase,
            Open::For => Keyword::EndFor,
            Open::While => Keyword::EndWhile,
            Open::Repeat => Keyword::EndRepeat,
        }
    }
}

/// Where the parser is in a logi.CAD `UNIT` file (reported once as not
/// supported; its declarations are still read).
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
pub(crate) enum UnitPart {
    Outside,
    /// After `UNIT name;`.
    Body,
    /// Inside its INTERFACE section: forward declarations are skipped.
    Interface,
}

pub(crate) struct Parser<'a> {
    text: &'a str,
    base: u32,
    toks: Vec<Token>,
    pos: usize,
    ast: &'a mut Ast,
    interner: &'a mut Interner,
    diags: Vec<Diagnostic>,
    /// Pragma spans not yet attached to an item.
    pragmas: Vec<Span>,
    next_pragma: usize,
    nesting: u32,
    /// Id of the first expression of this file; `expr_depth` is indexed from it.
    first_expr: usize,
    expr_depth: Vec<u32>,
    /// Token index of the last error, to report at most one per token.
    last_error_pos: usize,
    /// Set when nesting limits are hit: the rest of the file is skipped.
    aborted: bool,
    /// Blocks open around the statement being parsed.
    open: Vec<Open>,
    /// Regions reported as unsupported and skipped (and `__` words reported
    /// as unsupported operators): an E0005 from the lexer inside them is
    /// dropped.
    superseded: Vec<Span>,
    /// Whether part of the POU being parsed was skipped (see `Pou::partial`).
    pou_partial: bool,
    /// Members of the POU being parsed that were skipped.
    pou_skipped: Vec<Ident>,
    /// Inside the body of a METHOD: END_METHOD ends its statement list.
    in_method: bool,
    /// Inside the body of an ACTION: END_ACTION ends its statement list.
    in_action: bool,
    /// Inside an accessor of a PROPERTY: END_GET, END_SET and END_PROPERTY
    /// end its statement list.
    in_property: bool,
    /// Inside an IL body of a chart's transition or action: the chart's
    /// END words and its next element end the body.
    in_chart_il: bool,
    /// The kind of the POU whose body is being parsed.
    pou_kind: Option<PouKind>,
    /// METHODs written after the statements of a function block's body (a
    /// CODESYS and TwinCAT export shape): added to its methods.
    late_methods: Vec<Method>,
    /// Reserved words declared as names (after their E0022): their uses
    /// (`struct(x := 1);`, `a := struct.q;`) are read as names, so the one
    /// mistake gets one diagnostic, not one more per use.
    reserved_names: Vec<TokenKind>,
    unit: UnitPart,
    /// The `NAMESPACE` words of the namespaces open at this point of the
    /// file (innermost last).
    namespaces: Vec<Span>,
}

/// Reserved words that open or close a section, which are never taken for a
/// misused name: reading them as names would derail the parse.
fn starts_construct(k: TokenKind) -> bool {
    is_item_start(k)
        || is_item_end(k)
        || is_var_block_start(k)
        || matches!(k, TokenKind::Kw(kw) if kw.name().starts_with("END_"))
        || matches!(
            k,
            TokenKind::Kw(
                Keyword::Then
                    | Keyword::Do
                    | Keyword::Of
                    | Keyword::To
                    | Keyword::By
                    | Keyword::Else
                    | Keyword::Elsif
                    | Keyword::Until
                    | Keyword::Struct
                    | Keyword::Array
                    | Keyword::Resource
                    | Keyword::Task
                    | Keyword::Constant
                    | Keyword::Retain
                    | Keyword::NonRetain
                    | Keyword::At
                    | Keyword::With
            )
        )
}

/// Keywords that begin a top-level declaration.
fn is_item_start(k: TokenKind) -> bool {
    matches!(
        k,
        TokenKind::Kw(
            Keyword::Function
                | Keyword::FunctionBlock
                | Keyword::Program
                | Keyword::Configuration
                | Keyword::Type
        )
    )
}

/// Keywords that end a POU or another top-level construct.
fn is_item_end(k: TokenKind) -> bool {
    matches!(
        k,
        TokenKind::Kw(
            Keyword::EndFunction
                | Keyword::EndFunctionBlock
                | Keyword::EndProgram
                | Keyword::EndConfiguration
                | Keyword::EndResource
                | Keyword::EndType
        )
    )
}

fn is_var_block_start(k: TokenKind) -> bool {
    matches!(
        k,
        TokenKind::Kw(
            Keyword::Var
                | Keyword::VarInput
                | Keyword::VarOutput
                | Keyword::VarInOut
                | Keyword::VarExternal
                | Keyword::VarGlobal
                | Keyword::VarTemp
                | Keyword::VarAccess
                | Keyword::VarConfig
        )
    )
}

impl<'a> Parser<'a> {
    // ----- token access -------------------------------------------------

    fn tok(&self) -> Token {
        self.toks[self.pos]
    }

    fn kind(&self) -> TokenKind {
        self.toks[self.pos].kind
    }

    fn nth(&self, n: usize) -> Token {
        self.toks[(self.pos + n).min(self.toks.len() - 1)]
    }

    fn nth_kind(&self, n: usize) -> TokenKind {
        self.nth(n).kind
    }

    fn at(&self, k: TokenKind) -> bool {
        self.kind() == k
    }

    fn at_kw(&self, k: Keyword) -> bool {
        self.kind() == TokenKind::Kw(k)
    }

    fn bump(&mut self) -> Token {
        let t = self.toks[self.pos];
        if t.kind != TokenKind::Eof {
            self.pos += 1;
        }
        t
    }

    fn eat(&mut self, k: TokenKind) -> bool {
        if self.at(k) {
            self.bump();
            true
        } else {
            false
        }
    }

    fn eat_kw(&mut self, k: Keyword) -> bool {
        self.eat(TokenKind::Kw(k))
    }

    fn text_of(&self, t: Token) -> &'a str {
        let lo = (t.lo - self.base) as usize;
        let hi = (t.hi - self.base) as usize;
        &self.text[lo..hi]
    }

    /// The current token is an identifier spelled `word` (case-insensitive):
    /// how contextual keywords (PRIORITY, ON, STEP...) are recognised.
    fn at_word(&self, word: &str) -> bool {
        self.nth_is_word(0, word)
    }

    fn nth_is_word(&self, n: usize, word: &str) -> bool {
        let t = self.nth(n);
        t.kind == TokenKind::Ident && self.text_of(t).eq_ignore_ascii_case(word)
    }

    /// Whether a line break separates the start of `a` from the start of `b`.
    fn newline_between(&self, a: Token, b: Token) -> bool {
        let lo = (a.lo.min(b.lo) - self.base) as usize;
        let hi = (a.lo.max(b.lo) - self.base) as usize;
        self.text.as_bytes()[lo..hi].contains(&b'\n')
    }

    /// Whether the previous token is a string literal its line ended
    /// (E0003 from the lexer): the `;` it swallowed is not a second error.
    fn after_unterminated_string(&self) -> bool {
        let t = self.prev();
        if !matches!(t.kind, TokenKind::SString | TokenKind::WString) {
            return false;
        }
        let text = self.text_of(t);
        let quote = if t.kind == TokenKind::SString {
            '\''
        } else {
            '"'
        };
        text.len() < 2 || !text.ends_with(quote)
    }

    fn prev(&self) -> Token {
        self.toks[self.pos.saturating_sub(1)]
    }

    // ----- diagnostics --------------------------------------------------

    /// Reports at the current token unless an error was already reported
    /// there.
    fn report(&mut self, d: Diagnostic) {
        if self.last_error_pos == self.pos || self.aborted {
            return;
        }
        self.last_error_pos = self.pos;
        self.diags.push(d);
    }

    /// Reports wherever `d` points, without the one-per-token rule.
    fn report_always(&mut self, d: Diagnostic) {
        if !self.aborted {
            self.diags.push(d);
        }
    }

    fn describe_current(&self) -> String {
        let t = self.tok();
        match t.kind {
            TokenKind::Ident => format!("`{}`", self.text_of(t)),
            TokenKind::Kw(_) | TokenKind::Elem(_) | TokenKind::Generic(_) => {
                format!("`{}`", self.text_of(t))
            }
            TokenKind::Int
            | TokenKind::BasedInt
            | TokenKind::Real
            | TokenKind::SString
            | TokenKind::WString
            | TokenKind::Duration
            | TokenKind::Date
            | TokenKind::Tod
            | TokenKind::Dt
            | TokenKind::Address => {
                let text: String = self.text_of(t).chars().take(30).collect();
                format!("{} `{}`", t.kind.describe(), text)
            }
            k => k.describe(),
        }
    }

    /// "expected X, found Y" at the current token.
    fn expected(&mut self, what: &str) {
        let found = self.describe_current();
        let d = Diagnostic::new(
            Code::E0020,
            self.tok().span(),
            format!("expected {what}, found {found}"),
        )
        .with_label(format!("expected {what}"));
        self.report(d);
    }

    fn expect(&mut self, k: TokenKind) -> bool {
        if self.eat(k) {
            true
        } else {
            self.expected(&k.describe());
            false
        }
    }

    fn expect_kw(&mut self, k: Keyword) -> bool {
        self.expect(TokenKind::Kw(k))
    }

    /// Enters one level of nesting; false (after reporting E0023 once and
    /// aborting the file) when the limit is reached.
    fn enter(&mut self) -> bool {
        if self.aborted {
            return false;
        }
        if self.nesting >= MAX_NESTING {
            let d = Diagnostic::new(
                Code::E0023,
                self.tok().span(),
                format!("nesting too deep: more than {MAX_NESTING} levels"),
            )
            .with_help("split the construct with intermediate variables or POUs");
            self.report(d);
            self.aborted = true;
            return false;
        }
        self.nesting += 1;
        true
    }

    fn leave(&mut self) {
        self.nesting = self.nesting.saturating_sub(1);
    }

    // ----- names --------------------------------------------------------

    fn intern_token(&mut self, t: Token) -> Ident {
        let sym = self.interner.intern(self.text_of(t));
        Ident {
            sym,
            span: t.span(),
        }
    }

    /// A name being declared or referenced. A reserved word in its place is
    /// reported (E0022) and then accepted, so parsing goes on normally.
    fn name(&mut self, what: &str) -> Option<Ident> {
        let t = self.tok();
        match t.kind {
            TokenKind::Ident => {
                self.bump();
                Some(self.intern_token(t))
            }
            k if k.is_reserved_word()
                && (self.reserved_name_plausible() || !starts_construct(k)) =>
            {
                let d = if third_edition_word(k) {
                    // Reserved only by the 3rd edition: a name in older code.
                    Diagnostic::new(
                        Code::W0009,
                        t.span(),
                        format!(
                            "`{}` is reserved in IEC 61131-3 3rd edition; accepted as a name",
                            self.text_of(t)
                        ),
                    )
                    .with_label("3rd-edition word")
                    .with_help("this looks like 2nd-edition code: use --std iec2")
                } else if soft_reserved_word(k) {
                    // An edge qualifier only means something after a
                    // declaration's type: as a name it is unambiguous.
                    Diagnostic::new(
                        Code::W0009,
                        t.span(),
                        format!(
                            "`{}` is an edge qualifier; accepted as a name",
                            self.text_of(t)
                        ),
                    )
                    .with_label("reserved word")
                } else {
                    Diagnostic::new(
                        Code::E0022,
                        t.span(),
                        format!(
                            "`{}` is a reserved word and cannot be used as a name",
                            self.text_of(t)
                        ),
                    )
                    .with_label("reserved word")
                };
                self.report(d);
                if !self.reserved_names.contains(&k) {
                    self.reserved_names.push(k);
                }
                self.bump();
                Some(self.intern_token(t))
            }
            _ => {
                self.expected(what);
                None
            }
        }
    }

    /// A name being used, not declared (a parameter or member name): a
    /// reserved word is accepted silently, since its declaration already
    /// had the E0022 (or a later phase reports the unknown name).
    fn name_use(&mut self, what: &str) -> Option<Ident> {
        let t = self.tok();
        if t.kind.is_reserved_word() && !starts_construct(t.kind) {
            self.bump();
            return Some(self.intern_token(t));
        }
        self.name(what)
    }

    /// After a reserved word where a name is expected: does the next token
    /// suggest the word was meant as a name (`if : INT;`, `int,`)?
    fn reserved_name_plausible(&self) -> bool {
        matches!(
            self.nth_kind(1),
            TokenKind::Colon
                | TokenKind::Comma
                | TokenKind::Assign
                | TokenKind::Semi
                | TokenKind::RParen
        ) || matches!(self.nth(1).kind, TokenKind::Kw(Keyword::At))
    }

    // ----- expressions arena --------------------------------------------

    fn depth_of(&self, id: ExprId) -> u32 {
        self.expr_depth
            .get(id.index().wrapping_sub(self.first_expr))
            .copied()
            .unwrap_or(0)
    }

    /// Allocates an expression whose children have the given greatest depth.
    fn mk(&mut self, kind: ExprKind, span: Span, child_depth: u32) -> ExprId {
        let depth = child_depth + 1;
        if depth > MAX_EXPR_DEPTH && !self.aborted {
            let d = Diagnostic::new(
                Code::E0023,
                span,
                format!("expression nested too deeply: more than {MAX_EXPR_DEPTH} levels"),
            )
            .with_help("split the expression with intermediate variables");
            self.report_always(d);
            self.aborted = true;
        }
        let id = self.ast.alloc(kind, span);
        self.expr_depth.push(depth);
        id
    }

    fn error_expr(&mut self, span: Span) -> ExprId {
        self.mk(ExprKind::Error, span, 0)
    }

    fn expr_span(&self, id: ExprId) -> Span {
        self.ast.expr(id).span
    }

    // ----- pragmas --------------------------------------------------------

    /// Pragmas written before position `pos` and not yet attached.
    fn take_pragmas(&mut self, pos: u32) -> Vec<Span> {
        let start = self.next_pragma;
        while self.next_pragma < self.pragmas.len() && self.pragmas[self.next_pragma].hi <= pos {
            self.next_pragma += 1;
        }
        self.pragmas[start..self.next_pragma].to_vec()
    }

    // ----- recovery -------------------------------------------------------

    /// Skips to the start of the next top-level declaration.
    fn skip_to_item(&mut self) {
        while !(self.at(TokenKind::Eof)
            || is_item_start(self.kind())
            || self.at_kw(Keyword::VarGlobal)
            || self.at_word("END_NAMESPACE")
            || (self.at_word("NAMESPACE") && self.nth_kind(1) == TokenKind::Ident))
        {
            self.bump();
        }
    }

    /// Skips a construct that stc does not support, up to and including the
    /// identifier `end_word` (END_METHOD, END_INTERFACE...), or up to a token
    /// that cannot be inside it.
    fn skip_unsupported(&mut self, end_word: &str, stop: fn(TokenKind) -> bool) {
        while !self.at(TokenKind::Eof) {
            if self.at_word(end_word) {
                self.bump();
                self.eat(TokenKind::Semi);
                return;
            }
            if stop(self.kind()) {
                return;
            }
            self.bump();
        }
    }

    fn unsupported(&mut self, span: Span, what: &str) {
        let d = Diagnostic::new(Code::E0030, span, format!("{what} not supported yet"))
            .with_label("not supported yet");
        self.report(d);
    }

    /// Skips a parenthesised group starting at `(` (nested groups too).
    fn skip_parens(&mut self) {
        let mut depth = 0u32;
        while !self.at(TokenKind::Eof) {
            match self.bump().kind {
                TokenKind::LParen => depth += 1,
                TokenKind::RParen => {
                    depth = depth.saturating_sub(1);
                    if depth == 0 {
                        return;
                    }
                }
                _ => {}
            }
            if depth == 0 {
                return;
            }
        }
    }

    /// Whether the current token is a word starting with `__`: the
    /// operators CODESYS and TwinCAT reserve (`__NEW`, `__TRY`, `__TRUNC`).
    fn at_dunder(&self) -> bool {
        self.at(TokenKind::Ident) && self.text_of(self.tok()).starts_with("__")
    }

    // ----- top level ------------------------------------------------------

    fn file(&mut self) {
        while !self.at(TokenKind::Eof) && !self.aborted {
            let before = self.pos;
            if let Some(item) = self.item() {
                self.ast.items.push(item);
            }
            if self.pos == before && !self.at(TokenKind::Eof) {
                self.bump();
            }
        }
        // A namespace left open ends with its file (after the error), so
        // the next file's items are not read as inside it.
        while let Some(open) = self.namespaces.pop() {
            let end = self.tok().span();
            if !self.aborted {
                let d = Diagnostic::new(
                    Code::E0020,
                    end,
                    "expected `END_NAMESPACE`, found end of file",
                )
                .with_label("expected `END_NAMESPACE`")
                .with_secondary(open, "this namespace is not closed");
                self.report(d);
            }
            self.ast
                .items
                .push(Item::EndNamespace(Span::new(end.lo, end.lo)));
        }
    }

    /// A name or a dotted path (`Drives.Motor`, a namespace's element) as
    /// one identifier: the parts as written, joined by dots.
    pub(crate) fn qualified_name(&mut self, what: &str) -> Option<Ident> {
        let first_tok = self.tok();
        let first = self.name(what)?;
        if !(self.at(TokenKind::Dot) && self.nth_kind(1) == TokenKind::Ident) {
            return Some(first);
        }
        let mut text = self.text_of(first_tok).to_string();
        let mut span = first.span;
        while self.at(TokenKind::Dot) && self.nth_kind(1) == TokenKind::Ident {
            self.bump();
            let t = self.bump();
            text.push('.');
            text.push_str(self.text_of(t));
            span = span.to(t.span());
        }
        Some(Ident {
            sym: self.interner.intern(&text),
            span,
        })
    }

    /// `USING A, B.C;` directives: their namespaces are added to `out`.
    pub(crate) fn usings_into(&mut self, out: &mut Vec<Ident>) {
        while self.at_word("USING") && self.nth_kind(1) == TokenKind::Ident {
            self.bump();
            while let Some(n) = self.qualified_name("a namespace name") {
                out.push(n);
                if !self.eat(TokenKind::Comma) {
                    break;
                }
            }
            self.expect(TokenKind::Semi);
        }
    }

    /// NAMESPACE, END_NAMESPACE and USING between items.
    fn namespace_item(&mut self, pragmas: Vec<Span>) -> Option<Item> {
        if self.at_word("NAMESPACE") && self.nth_kind(1) == TokenKind::Ident {
            let start = self.bump().span();
            let internal = self.at_word("INTERNAL") && self.nth_kind(1) == TokenKind::Ident;
            if internal {
                self.bump();
            }
            let name = self.qualified_name("a namespace name")?;
            self.namespaces.push(start);
            return Some(Item::Namespace(NamespaceDecl {
                name,
                internal,
                span: start.to(name.span),
                pragmas,
            }));
        }
        if self.at_word("END_NAMESPACE") {
            let span = self.bump().span();
            self.eat(TokenKind::Semi);
            if self.namespaces.pop().is_none() {
                let d = Diagnostic::new(Code::E0020, span, "`END_NAMESPACE` without a `NAMESPACE`")
                    .with_label("no namespace is open here");
                self.report(d);
                return None;
            }
            return Some(Item::EndNamespace(span));
        }
        let start = self.tok().span();
        let mut names = Vec::new();
        self.usings_into(&mut names);
        Some(Item::Using(UsingDecl {
            names,
            span: start.to(self.prev().span()),
        }))
    }

    fn item(&mut self) -> Option<Item> {
        let t = self.tok();
        let pragmas = self.take_pragmas(t.lo);
        match t.kind {
            TokenKind::Kw(Keyword::Function | Keyword::FunctionBlock | Keyword::Program)
                if self.unit == UnitPart::Interface =>
            {
                // A forward declaration `FUNCTION name;` of a UNIT's
                // INTERFACE: the POU itself follows in IMPLEMENTATION.
                while !self.at(TokenKind::Eof) && !self.eat(TokenKind::Semi) {
                    self.bump();
                }
                None
            }
            TokenKind::Kw(Keyword::Function | Keyword::FunctionBlock)
                if self.nth_kind(1) == TokenKind::Ident && self.nth_kind(2) == TokenKind::Lt =>
            {
                // RuSTy's generic POUs, `FUNCTION f <T: ANY_NUM> : T`: one
                // E0030, the POU skipped whole, its calls not reported.
                let span = t.span().to(self.nth(2).span());
                self.unsupported(span, "generic functions (`<T: ...>`) are");
                let name = self.nth(1);
                let name = self.intern_token(name);
                self.ast.unsupported_names.push(name);
                let end = if t.kind == TokenKind::Kw(Keyword::Function) {
                    Keyword::EndFunction
                } else {
                    Keyword::EndFunctionBlock
                };
                while !self.at(TokenKind::Eof) && !self.eat_kw(end) {
                    self.bump();
                }
                self.superseded.push(span.to(self.prev().span()));
                None
            }
            TokenKind::Kw(Keyword::Type) => self.type_block(pragmas),
            TokenKind::Kw(Keyword::Function) => self
                .pou(crate::ast::PouKind::Function, pragmas)
                .map(Item::Pou),
            TokenKind::Kw(Keyword::FunctionBlock) => self
                .pou(crate::ast::PouKind::FunctionBlock, pragmas)
                .map(Item::Pou),
            TokenKind::Kw(Keyword::Program) => self
                .pou(crate::ast::PouKind::Program, pragmas)
                .map(Item::Pou),
            TokenKind::Kw(Keyword::Configuration) => self.configuration().map(Item::Configuration),
            TokenKind::Kw(Keyword::VarGlobal) => self.var_block().map(Item::GlobalVars),
            TokenKind::Semi => {
                // A stray `;` after END_FUNCTION and the like is harmless.
                self.bump();
                None
            }
            TokenKind::Ident if self.at_unit_part() => None,
            TokenKind::Ident
                if (self.at_word("CLASS") || self.at_word("INTERFACE"))
                    && self.nth_kind(1) == TokenKind::Ident =>
            {
                let class = if self.at_word("CLASS") {
                    crate::ast::ClassKind::Class
                } else {
                    crate::ast::ClassKind::Interface
                };
                self.pou_of(crate::ast::PouKind::FunctionBlock, Some(class), pragmas)
                    .map(Item::Pou)
            }
            TokenKind::Ident
                if (self.at_word("NAMESPACE") && self.nth_kind(1) == TokenKind::Ident)
                    || self.at_word("END_NAMESPACE")
                    || (self.at_word("USING") && self.nth_kind(1) == TokenKind::Ident) =>
            {
                self.namespace_item(pragmas)
            }
            TokenKind::Ident if self.at_unsupported_item() => None,
            _ => {
                self.expected(
                    "a declaration (TYPE, FUNCTION, FUNCTION_BLOCK, PROGRAM or CONFIGURATION)",
                );
                self.bump();
                self.skip_to_item();
                None
            }
        }
    }

    /// A stand-alone METHOD, PROPERTY or ACTION: reported once and skipped
    /// whole.
    fn at_unsupported_item(&mut self) -> bool {
        for (word, end, what) in [
            ("ACTIONS", "END_ACTIONS", "ACTIONS blocks are"),
            ("METHOD", "END_METHOD", "methods are"),
            ("PROPERTY", "END_PROPERTY", "properties are"),
            ("ACTION", "END_ACTION", "actions are"),
        ] {
            if self.at_word(word) && self.nth_kind(1) == TokenKind::Ident {
                let span = self.tok().span();
                self.unsupported(span, what);
                let name = self.nth(1);
                let name = self.intern_token(name);
                self.ast.unsupported_names.push(name);
                self.skip_unsupported(end, is_item_start);
                self.superseded.push(span.to(self.prev().span()));
                return true;
            }
        }
        false
    }

    /// The parts of a logi.CAD `UNIT` file: `UNIT name;` is reported once;
    /// `USES ...;`, INTERFACE, IMPLEMENTATION and their ends are then
    /// skipped without a word, and the declarations inside are read as
    /// usual (forward declarations excepted, see `item`).
    fn at_unit_part(&mut self) -> bool {
        if self.at_word("UNIT") && self.nth_kind(1) == TokenKind::Ident {
            let span = self.tok().span();
            self.unsupported(span, "logi.CAD UNIT files are");
            self.bump();
            self.bump();
            self.eat(TokenKind::Semi);
            self.unit = UnitPart::Body;
            return true;
        }
        if self.unit == UnitPart::Outside {
            return false;
        }
        if self.at_word("USES") {
            while !self.at(TokenKind::Eof) && !self.eat(TokenKind::Semi) {
                self.bump();
            }
            return true;
        }
        for (word, next) in [
            ("INTERFACE", UnitPart::Interface),
            ("END_INTERFACE", UnitPart::Body),
            ("IMPLEMENTATION", UnitPart::Body),
            ("END_IMPLEMENTATION", UnitPart::Body),
        ] {
            if self.at_word(word) {
                self.bump();
                self.eat(TokenKind::Semi);
                self.unit = next;
                return true;
            }
        }
        false
    }
}

/// Parses a whole project: every file of the source map, in order.
pub fn parse_project(
    sources: &stc_diagnostics::SourceMap,
    interner: &mut Interner,
) -> (Ast, Vec<Diagnostic>) {
    parse_project_in(sources, interner, false)
}

/// [`parse_project`] for an edition (see [`parse_file_in`]); files named
/// `<...>` (the built-in standard library) are always 3rd edition.
pub fn parse_project_in(
    sources: &stc_diagnostics::SourceMap,
    interner: &mut Interner,
    iec2: bool,
) -> (Ast, Vec<Diagnostic>) {
    let mut ast = Ast::default();
    let mut diags = Vec::new();
    for (_, f) in sources.files() {
        diags.extend(parse_source_in(f, &mut ast, interner, iec2).diagnostics);
    }
    (ast, diags)
}

/// One file of a project into `ast` ([`parse_file_in`]): the standard
/// library's ([`stc_diagnostics::SourceFile::is_library`]) is written in
/// the 3rd edition whatever `iec2` says, and its spellings give way to
/// the user's (`Interner::library`).
pub fn parse_source_in(
    f: &stc_diagnostics::SourceFile,
    ast: &mut Ast,
    interner: &mut Interner,
    iec2: bool,
) -> FileParse {
    interner.library = f.is_library();
    let r = parse_file_in(&f.text, f.base, ast, interner, iec2 && !f.is_library());
    interner.library = false;
    r
}
