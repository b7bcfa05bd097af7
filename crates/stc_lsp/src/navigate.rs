//! What a name written at a place means, and every place a declaration is
//! named: go to definition and hover (through [`Project::resolve_token`]),
//! find references, rename, semantic tokens and signature help.
//!
//! Names are resolved on the tokens of the text as the editor has it (so a
//! half-typed file still answers): a name is a variable of the POU (or
//! METHOD) around it, else a global declaration (POU, type, enumeration
//! value, global variable); after `base.` it is a member of the type of
//! `base`; before `:=` or `=>` inside a call's parentheses it is a formal
//! parameter of the callee.

use std::collections::HashMap;

use lsp_types::{
    Location, ParameterInformation, ParameterLabel, Position, Range, SemanticToken,
    SemanticTokenModifier, SemanticTokenType, SemanticTokensLegend, SignatureHelp,
    SignatureInformation, TextEdit, Uri, WorkspaceEdit,
};
use stc_diagnostics::Span;
use stc_syntax::ast::{Item, Pou, PouKind, TypeSpecKind, VarBlock, VarBlockItems, VarKind};
use stc_syntax::lexer::{lex, TriviaKind};
use stc_syntax::token::{Token, TokenKind};
use stc_syntax::Symbol;

use crate::analysis::{lsp_position, Decl, Project};

/// The global declarations by name (the first of each name, as the
/// analyser sees duplicates) and the POUs by position.
pub(crate) struct Index<'a> {
    globals: HashMap<Symbol, (Span, Decl<'a>)>,
    /// (start, end, POU), sorted by start.
    pous: Vec<(u32, u32, &'a Pou)>,
}

impl<'a> Index<'a> {
    fn pou_at(&self, at: u32) -> Option<&'a Pou> {
        let i = self.pous.partition_point(|(lo, _, _)| *lo <= at);
        let (lo, hi, p) = self.pous.get(i.checked_sub(1)?)?;
        (*lo <= at && at <= *hi).then_some(*p)
    }
}

/// The variable `sym` declared in `blocks`, if any.
fn var_in<'a>(blocks: &'a [VarBlock], sym: Symbol) -> Option<(Span, Decl<'a>)> {
    for b in blocks {
        if let VarBlockItems::Vars(vs) = &b.items {
            for v in vs {
                for n in &v.names {
                    if n.sym == sym {
                        return Some((n.span, Decl::Var(v, b.kind)));
                    }
                }
            }
        }
    }
    None
}

/// The index of the token a position is in (an identifier), or that ends
/// at it.
pub(crate) fn token_at(toks: &[Token], at: u32) -> Option<usize> {
    let i = toks.partition_point(|t| t.hi <= at);
    if let Some(t) = toks.get(i) {
        if t.lo <= at && at < t.hi && t.kind != TokenKind::Eof {
            return Some(i);
        }
    }
    let prev = i.checked_sub(1)?;
    (toks.get(prev)?.hi == at).then_some(prev)
}

/// Semantic token types, in the legend's order.
const TYPES: &[SemanticTokenType] = &[
    SemanticTokenType::NAMESPACE,
    SemanticTokenType::TYPE,
    SemanticTokenType::CLASS,
    SemanticTokenType::ENUM,
    SemanticTokenType::ENUM_MEMBER,
    SemanticTokenType::STRUCT,
    SemanticTokenType::FUNCTION,
    SemanticTokenType::METHOD,
    SemanticTokenType::VARIABLE,
    SemanticTokenType::PARAMETER,
    SemanticTokenType::PROPERTY,
    SemanticTokenType::KEYWORD,
    SemanticTokenType::NUMBER,
    SemanticTokenType::STRING,
    SemanticTokenType::COMMENT,
];

const MODIFIERS: &[SemanticTokenModifier] = &[
    SemanticTokenModifier::DECLARATION,
    SemanticTokenModifier::READONLY,
    SemanticTokenModifier::DEFAULT_LIBRARY,
];

fn ty(t: SemanticTokenType) -> u32 {
    TYPES.iter().position(|x| *x == t).unwrap_or(0) as u32
}

const DECLARATION: u32 = 1;
const READONLY: u32 = 2;
const DEFAULT_LIBRARY: u32 = 4;

/// The legend the server announces.
pub fn legend() -> SemanticTokensLegend {
    SemanticTokensLegend {
        token_types: TYPES.to_vec(),
        token_modifiers: MODIFIERS.to_vec(),
    }
}

/// Why a rename is refused.
pub enum RenameError {
    /// The request is malformed (a position outside the document...).
    Invalid(String),
    /// The position is not a name the project declares, or the new name
    /// is not one.
    Refused(String),
}

impl Project {
    pub(crate) fn index(&self) -> Index<'_> {
        let mut globals: HashMap<Symbol, (Span, Decl<'_>)> = HashMap::new();
        let mut pous = Vec::new();
        // In `visible`'s order: POUs, types and their values, global
        // variables, in item order; the first of a name wins.
        let mut tmp: Vec<(Symbol, Span, Decl<'_>)> = Vec::new();
        for it in self.items() {
            match it {
                Item::Pou(p) => {
                    pous.push((p.span.lo, p.span.hi, p));
                    tmp.push((p.name.sym, p.name.span, Decl::Pou(p)));
                }
                Item::Types(ts, _) => {
                    for t in ts {
                        tmp.push((t.name.sym, t.name.span, Decl::Type(t)));
                        if let TypeSpecKind::Enum { values, .. } = &t.spec.kind {
                            for v in values {
                                tmp.push((v.name.sym, v.name.span, Decl::EnumValue(t)));
                            }
                        }
                    }
                }
                Item::GlobalVars(b) => crate::analysis::vars_of(std::slice::from_ref(b), &mut tmp),
                Item::Configuration(c) => {
                    crate::analysis::vars_of(&c.var_blocks, &mut tmp);
                    for r in &c.resources {
                        crate::analysis::vars_of(&r.var_blocks, &mut tmp);
                    }
                }
                // Their elements are listed by their own names (an
                // approximation: the language server does not scope them).
                Item::Namespace(_) | Item::EndNamespace(_) | Item::Using(_) => {}
            }
        }
        for (s, span, d) in tmp {
            globals.entry(s).or_insert((span, d));
        }
        pous.sort_by_key(|(lo, _, _)| *lo);
        Index { globals, pous }
    }

    /// What `sym` written at `at` (not after a dot) declares. A
    /// VAR_EXTERNAL stands for the global it binds: they are one name (a
    /// rename renames both).
    pub(crate) fn resolve<'a>(
        &'a self,
        index: &Index<'a>,
        sym: Symbol,
        at: u32,
    ) -> Option<(Span, Decl<'a>)> {
        let found = self.resolve_local(index, sym, at);
        if let Some((_, Decl::Var(_, VarKind::External))) = found {
            if let Some(g @ (_, Decl::Var(..))) = index.globals.get(&sym) {
                return Some(*g);
            }
        }
        found
    }

    fn resolve_local<'a>(
        &'a self,
        index: &Index<'a>,
        sym: Symbol,
        at: u32,
    ) -> Option<(Span, Decl<'a>)> {
        if let Some(p) = index.pou_at(at) {
            for m in &p.methods {
                if m.pou.span.lo <= at && at <= m.pou.span.hi {
                    if let Some(x) = var_in(&m.pou.var_blocks, sym) {
                        return Some(x);
                    }
                }
            }
            if let Some(x) = var_in(&p.var_blocks, sym) {
                return Some(x);
            }
            for m in &p.methods {
                if m.pou.name.sym == sym {
                    return Some((m.pou.name.span, Decl::Pou(&m.pou)));
                }
            }
        }
        index.globals.get(&sym).copied()
    }

    /// The POU (or structure type) of the variable `base` seen at `at`.
    fn type_of<'a>(&'a self, index: &Index<'a>, base: Symbol, at: u32) -> Option<Decl<'a>> {
        let (_, d) = self.resolve(index, base, at)?;
        let Decl::Var(v, _) = d else {
            return None;
        };
        let TypeSpecKind::Named(n) = &v.ty.kind else {
            return None;
        };
        index.globals.get(&n.sym).map(|(_, d)| *d)
    }

    /// The member `sym` of a POU or structure.
    fn member_in<'a>(&'a self, owner: Decl<'a>, sym: Symbol) -> Option<(Span, Decl<'a>)> {
        match owner {
            Decl::Pou(p) => {
                for b in p.var_blocks.iter().filter(|b| {
                    matches!(
                        b.kind,
                        VarKind::Input | VarKind::Output | VarKind::InOut | VarKind::Var
                    )
                }) {
                    if let Some(x) = var_in(std::slice::from_ref(b), sym) {
                        return Some(x);
                    }
                }
                p.methods
                    .iter()
                    .find(|m| m.pou.name.sym == sym)
                    .map(|m| (m.pou.name.span, Decl::Pou(&m.pou)))
            }
            Decl::Type(t) => match &t.spec.kind {
                TypeSpecKind::Struct { members } => members.iter().find_map(|m| {
                    m.names
                        .iter()
                        .find(|n| n.sym == sym)
                        .map(|n| (n.span, Decl::Var(m, VarKind::Var)))
                }),
                _ => None,
            },
            _ => None,
        }
    }

    /// The callee of the call whose parentheses enclose token `i` (the
    /// token index of its `(`), as the POU it calls.
    fn callee<'a>(
        &'a self,
        index: &Index<'a>,
        text: &str,
        base: u32,
        toks: &[Token],
        i: usize,
    ) -> Option<(Decl<'a>, usize)> {
        let mut depth = 0i32;
        let mut j = i;
        let mut steps = 0;
        while j > 0 && steps < 4096 {
            j -= 1;
            steps += 1;
            match toks.get(j)?.kind {
                TokenKind::RParen => depth += 1,
                TokenKind::LParen if depth > 0 => depth -= 1,
                TokenKind::LParen => {
                    let c = j.checked_sub(1)?;
                    if toks.get(c)?.kind != TokenKind::Ident {
                        return None;
                    }
                    let pou = self.callee_pou(index, text, base, toks, c)?;
                    return Some((pou, j));
                }
                TokenKind::Semi => return None,
                _ => {}
            }
        }
        None
    }

    /// The POU a callee identifier (token `c`) calls: a function, a
    /// program, the type of an instance, a method after `inst.`.
    fn callee_pou<'a>(
        &'a self,
        index: &Index<'a>,
        text: &str,
        base: u32,
        toks: &[Token],
        c: usize,
    ) -> Option<Decl<'a>> {
        let word = |k: usize| -> Option<Symbol> {
            let t = toks.get(k)?;
            self.sym(text.get((t.lo - base) as usize..(t.hi - base) as usize)?)
        };
        let at = toks.get(c)?.lo;
        let sym = word(c)?;
        let d = if c >= 2
            && toks.get(c - 1)?.kind == TokenKind::Dot
            && toks.get(c - 2)?.kind == TokenKind::Ident
        {
            let owner = self.type_of(index, word(c - 2)?, at)?;
            self.member_in(owner, sym)?.1
        } else {
            self.resolve(index, sym, at)?.1
        };
        match d {
            Decl::Pou(_) => Some(d),
            Decl::Var(v, _) => match &v.ty.kind {
                TypeSpecKind::Named(n) => match index.globals.get(&n.sym) {
                    Some((_, p @ Decl::Pou(_))) => Some(*p),
                    _ => None,
                },
                _ => None,
            },
            _ => None,
        }
    }

    /// What the identifier token `i` of a file names.
    pub(crate) fn resolve_token<'a>(
        &'a self,
        index: &Index<'a>,
        text: &str,
        base: u32,
        toks: &[Token],
        i: usize,
    ) -> Option<(Span, Decl<'a>)> {
        let t = toks.get(i)?;
        if t.kind != TokenKind::Ident {
            return None;
        }
        let word = |k: usize| -> Option<Symbol> {
            let t = toks.get(k)?;
            self.sym(text.get((t.lo - base) as usize..(t.hi - base) as usize)?)
        };
        let sym = word(i)?;
        let at = t.lo;
        if i >= 2
            && toks.get(i - 1)?.kind == TokenKind::Dot
            && toks.get(i - 2)?.kind == TokenKind::Ident
        {
            let owner = self.type_of(index, word(i - 2)?, at)?;
            return self.member_in(owner, sym);
        }
        // `name :=` / `name =>` inside a call's parentheses: a formal
        // parameter of the callee.
        let next = toks.get(i + 1).map(|t| t.kind);
        let prev = i.checked_sub(1).and_then(|p| toks.get(p)).map(|t| t.kind);
        if matches!(next, Some(TokenKind::Assign | TokenKind::Arrow))
            && matches!(
                prev,
                Some(TokenKind::LParen | TokenKind::Comma)
                    | Some(TokenKind::Kw(stc_syntax::token::Keyword::Not))
            )
        {
            if let Some((Decl::Pou(p), _)) = self.callee(index, text, base, toks, i) {
                return var_in(&p.var_blocks, sym);
            }
        }
        self.resolve(index, sym, at)
    }

    /// What the name at a position declares.
    pub(crate) fn lookup_at(
        &self,
        uri: &str,
        pos: Position,
    ) -> Result<Option<(Span, Decl<'_>)>, String> {
        let (at, text, base) = self.locate(uri, pos)?;
        let lexed = lex(text, base);
        let Some(i) = token_at(&lexed.tokens, at) else {
            return Ok(None);
        };
        let index = self.index();
        Ok(self.resolve_token(&index, text, base, &lexed.tokens, i))
    }

    /// Every place (file, span) that names the declaration at `decl`,
    /// outside the prelude.
    fn places(&self, decl: Span, name: &str) -> Vec<Span> {
        let index = self.index();
        let prelude = self.prelude();
        let mut out = Vec::new();
        for (_, f) in self.sources().files() {
            if f.base == prelude.lo {
                continue;
            }
            // Only files that spell the name are lexed.
            if !contains_ignore_case(&f.text, name) {
                continue;
            }
            let lexed = lex(&f.text, f.base);
            for (i, t) in lexed.tokens.iter().enumerate() {
                if t.kind != TokenKind::Ident {
                    continue;
                }
                let w = f
                    .text
                    .get((t.lo - f.base) as usize..(t.hi - f.base) as usize)
                    .unwrap_or("");
                if !w.eq_ignore_ascii_case(name) {
                    continue;
                }
                if let Some((span, _)) =
                    self.resolve_token(&index, &f.text, f.base, &lexed.tokens, i)
                {
                    if span == decl {
                        out.push(Span::new(t.lo, t.hi));
                    }
                }
            }
        }
        out
    }

    fn location(&self, span: Span) -> Option<Location> {
        let (u, r) = self.range(span)?;
        Some(Location::new(u.parse::<Uri>().ok()?, r))
    }

    pub fn references(
        &self,
        uri: &str,
        pos: Position,
        include_declaration: bool,
    ) -> Result<Vec<Location>, String> {
        let Some((decl, _)) = self.lookup_at(uri, pos)? else {
            return Ok(Vec::new());
        };
        let name = self.sources().slice(decl).to_string();
        let mut spans = self.places(decl, &name);
        if !include_declaration {
            spans.retain(|s| *s != decl);
        } else if !spans.contains(&decl) {
            spans.insert(0, decl);
        }
        Ok(spans.into_iter().filter_map(|s| self.location(s)).collect())
    }

    /// The declaration a rename at `pos` renames, if it may be renamed.
    fn renamable(&self, uri: &str, pos: Position) -> Result<(Span, Span), RenameError> {
        let (at, text, base) = self.locate(uri, pos).map_err(RenameError::Invalid)?;
        let lexed = lex(text, base);
        let refuse =
            || RenameError::Refused("there is no name declared in this project here".to_string());
        let i = token_at(&lexed.tokens, at).ok_or_else(refuse)?;
        let t = lexed.tokens.get(i).ok_or_else(refuse)?;
        if t.kind != TokenKind::Ident {
            let word = text
                .get((t.lo - base) as usize..(t.hi - base) as usize)
                .unwrap_or("");
            return Err(RenameError::Refused(format!(
                "`{word}` is not a name: it cannot be renamed"
            )));
        }
        let index = self.index();
        let Some((decl, _)) = self.resolve_token(&index, text, base, &lexed.tokens, i) else {
            let word = text
                .get((t.lo - base) as usize..(t.hi - base) as usize)
                .unwrap_or("");
            return Err(RenameError::Refused(format!(
                "`{word}` is not declared in this project (a standard function, or unknown): it cannot be renamed"
            )));
        };
        let prelude = self.prelude();
        if prelude.lo <= decl.lo && decl.lo <= prelude.hi {
            return Err(RenameError::Refused(format!(
                "`{}` is part of the standard library: it cannot be renamed",
                self.sources().slice(decl)
            )));
        }
        Ok((decl, Span::new(t.lo, t.hi)))
    }

    /// The range of the name a rename at `pos` would rename.
    pub fn prepare_rename(&self, uri: &str, pos: Position) -> Result<Range, RenameError> {
        let (_, at) = self.renamable(uri, pos)?;
        self.range(at)
            .map(|(_, r)| r)
            .ok_or_else(|| RenameError::Invalid("no such position".into()))
    }

    /// The edits that rename the declaration at `pos` and every use of it.
    pub fn rename(
        &self,
        uri: &str,
        pos: Position,
        new_name: &str,
    ) -> Result<WorkspaceEdit, RenameError> {
        let (decl, _) = self.renamable(uri, pos)?;
        let lexed = lex(new_name, 0);
        let one_ident = lexed.tokens.len() == 2
            && lexed.tokens[0].kind == TokenKind::Ident
            && lexed.tokens[0].lo == 0
            && lexed.tokens[0].hi as usize == new_name.len()
            && lexed.trivia.is_empty();
        if !one_ident {
            return Err(RenameError::Refused(format!(
                "`{new_name}` is not a valid name (a letter or `_`, then letters, digits and `_`; not a keyword)"
            )));
        }
        // A name the declaration's scope already sees would change what
        // other code means.
        if let Some(sym) = self.sym(new_name) {
            let index = self.index();
            if let Some((other, _)) = self.resolve(&index, sym, decl.lo) {
                if other != decl {
                    return Err(RenameError::Refused(format!(
                        "`{new_name}` is already declared where `{}` is visible",
                        self.sources().slice(decl)
                    )));
                }
            }
        }
        let name = self.sources().slice(decl).to_string();
        let mut by_uri: std::collections::BTreeMap<String, Vec<TextEdit>> = Default::default();
        let mut spans = self.places(decl, &name);
        if !spans.contains(&decl) {
            spans.push(decl);
        }
        for s in spans {
            if let Some((u, r)) = self.range(s) {
                by_uri.entry(u).or_default().push(TextEdit {
                    range: r,
                    new_text: new_name.to_string(),
                });
            }
        }
        Ok(WorkspaceEdit {
            changes: Some(
                by_uri
                    .into_iter()
                    .filter_map(|(u, edits)| Some((u.parse::<Uri>().ok()?, edits)))
                    .collect(),
            ),
            ..WorkspaceEdit::default()
        })
    }

    /// The semantic tokens of a document (LSP's relative encoding).
    pub fn semantic_tokens(&self, uri: &str) -> Result<Vec<SemanticToken>, String> {
        let sm = self.sources();
        let f = sm
            .files()
            .map(|(_, f)| f)
            .find(|f| f.name == uri)
            .ok_or_else(|| format!("unknown document {uri}"))?;
        let index = self.index();
        let lexed = lex(&f.text, f.base);
        // (start, end, type, modifiers) in source order.
        let mut marks: Vec<(u32, u32, u32, u32)> = Vec::new();
        for t in &lexed.trivia {
            if t.kind == TriviaKind::Comment {
                marks.push((t.span.lo, t.span.hi, ty(SemanticTokenType::COMMENT), 0));
            }
        }
        let prelude = self.prelude();
        for (i, t) in lexed.tokens.iter().enumerate() {
            let kind = match t.kind {
                TokenKind::Kw(_) => Some((ty(SemanticTokenType::KEYWORD), 0)),
                TokenKind::Elem(_) | TokenKind::Generic(_) => {
                    Some((ty(SemanticTokenType::TYPE), DEFAULT_LIBRARY))
                }
                TokenKind::Int
                | TokenKind::BasedInt
                | TokenKind::Real
                | TokenKind::Duration
                | TokenKind::Date
                | TokenKind::Tod
                | TokenKind::Dt => Some((ty(SemanticTokenType::NUMBER), 0)),
                TokenKind::SString | TokenKind::WString => Some((ty(SemanticTokenType::STRING), 0)),
                TokenKind::Address => Some((ty(SemanticTokenType::VARIABLE), 0)),
                TokenKind::Ident => self
                    .resolve_token(&index, &f.text, f.base, &lexed.tokens, i)
                    .map(|(span, d)| {
                        let member = i >= 1
                            && lexed.tokens.get(i - 1).map(|p| p.kind) == Some(TokenKind::Dot);
                        let mut m = 0;
                        if span == Span::new(t.lo, t.hi) {
                            m |= DECLARATION;
                        }
                        if prelude.lo <= span.lo && span.lo <= prelude.hi {
                            m |= DEFAULT_LIBRARY;
                        }
                        (token_type(d, member), m | readonly(d))
                    }),
                _ => None,
            };
            if let Some((k, m)) = kind {
                marks.push((t.lo, t.hi, k, m));
            }
        }
        marks.sort_by_key(|m| m.0);
        let mut out = Vec::new();
        let (mut line, mut col) = (0u32, 0u32);
        for (lo, hi, k, m) in marks {
            // A token over several lines (a comment) is one token per line.
            let mut start = lo;
            while start < hi {
                let p = lsp_position(f, start);
                let rest = f
                    .text
                    .get((start - f.base) as usize..(hi - f.base) as usize)
                    .unwrap_or("");
                let piece = rest.split('\n').next().unwrap_or("");
                let piece_trim = piece.strip_suffix('\r').unwrap_or(piece);
                let len: u32 = piece_trim.chars().map(|c| c.len_utf16() as u32).sum();
                if len > 0 {
                    let delta_line = p.line.saturating_sub(line);
                    let delta_start = if delta_line == 0 {
                        p.character.saturating_sub(col)
                    } else {
                        p.character
                    };
                    out.push(SemanticToken {
                        delta_line,
                        delta_start,
                        length: len,
                        token_type: k,
                        token_modifiers_bitset: m,
                    });
                    line = p.line;
                    col = p.character;
                }
                start += piece.len() as u32 + 1;
            }
        }
        Ok(out)
    }

    /// Signature help inside the parentheses of a call.
    pub fn signature_help(
        &self,
        uri: &str,
        pos: Position,
    ) -> Result<Option<SignatureHelp>, String> {
        let (at, text, base) = self.locate(uri, pos)?;
        let lexed = lex(text, base);
        let toks = &lexed.tokens;
        // The first token at or after the cursor.
        let i = toks.partition_point(|t| t.hi <= at && t.kind != TokenKind::Eof);
        let i = if toks.get(i).is_some_and(|t| t.lo < at) {
            i + 1
        } else {
            i
        };
        let index = self.index();
        let Some((Decl::Pou(p), lparen)) = self.callee(&index, text, base, toks, i) else {
            return Ok(None);
        };
        // The argument the cursor is in: commas at depth 0 since `(`, or
        // the formal name it starts with.
        let mut depth = 0;
        let mut arg = 0u32;
        let mut arg_start = lparen + 1;
        for (k, t) in toks.iter().enumerate().take(i).skip(lparen + 1) {
            match t.kind {
                TokenKind::LParen | TokenKind::LBracket => depth += 1,
                TokenKind::RParen | TokenKind::RBracket => depth -= 1,
                TokenKind::Comma if depth == 0 => {
                    arg += 1;
                    arg_start = k + 1;
                }
                _ => {}
            }
        }
        let params = parameters(p);
        let formal = {
            let mut k = arg_start;
            if toks.get(k).map(|t| t.kind) == Some(TokenKind::Kw(stc_syntax::token::Keyword::Not)) {
                k += 1;
            }
            match (toks.get(k), toks.get(k + 1)) {
                (Some(n), Some(op))
                    if n.kind == TokenKind::Ident
                        && matches!(op.kind, TokenKind::Assign | TokenKind::Arrow)
                        && k + 1 < i =>
                {
                    self.sym(
                        text.get((n.lo - base) as usize..(n.hi - base) as usize)
                            .unwrap_or(""),
                    )
                }
                _ => None,
            }
        };
        let active = match formal {
            Some(s) => params
                .iter()
                .position(|(sym, ..)| *sym == s)
                .map(|x| x as u32),
            None => Some(arg),
        };
        let sm = self.sources();
        let mut label = format!("{}(", self.spelling(p.name.sym));
        let mut infos = Vec::new();
        for (k, (sym, kind, ty_span)) in params.iter().enumerate() {
            if k > 0 {
                label.push_str(", ");
            }
            let start = label.encode_utf16().count() as u32;
            let arrow = if *kind == VarKind::Output {
                " =>"
            } else {
                " :="
            };
            label.push_str(&format!(
                "{}{arrow} {}",
                self.spelling(*sym),
                sm.slice(*ty_span)
            ));
            let end = label.encode_utf16().count() as u32;
            infos.push(ParameterInformation {
                label: ParameterLabel::LabelOffsets([start, end]),
                documentation: Some(lsp_types::Documentation::String(kind.keyword().to_string())),
            });
        }
        label.push(')');
        if let Some(r) = &p.return_type {
            label.push_str(&format!(" : {}", sm.slice(r.span)));
        }
        let doc = self
            .doc_comment(Span::new(p.span.lo, p.name.span.hi))
            .map(lsp_types::Documentation::String);
        Ok(Some(SignatureHelp {
            signatures: vec![SignatureInformation {
                label,
                documentation: doc,
                parameters: Some(infos),
                active_parameter: active,
            }],
            active_signature: Some(0),
            active_parameter: active,
        }))
    }
}

/// The parameters of a POU in positional order: inputs and in-outs, then
/// outputs (EN and ENO, and a chart's hidden state, left out).
fn parameters(p: &Pou) -> Vec<(Symbol, VarKind, Span)> {
    let mut first = Vec::new();
    let mut outputs = Vec::new();
    for b in &p.var_blocks {
        let VarBlockItems::Vars(vs) = &b.items else {
            continue;
        };
        for v in vs {
            for n in &v.names {
                match b.kind {
                    VarKind::Input | VarKind::InOut => first.push((n.sym, b.kind, v.ty.span)),
                    VarKind::Output => outputs.push((n.sym, b.kind, v.ty.span)),
                    _ => {}
                }
            }
        }
    }
    first.extend(outputs);
    first
}

fn token_type(d: Decl<'_>, member: bool) -> u32 {
    ty(match d {
        Decl::Var(_, VarKind::Input | VarKind::Output | VarKind::InOut) if !member => {
            SemanticTokenType::PARAMETER
        }
        Decl::Var(..) if member => SemanticTokenType::PROPERTY,
        Decl::Var(..) => SemanticTokenType::VARIABLE,
        Decl::Pou(p) => match p.kind {
            PouKind::Function if member => SemanticTokenType::METHOD,
            PouKind::Function => SemanticTokenType::FUNCTION,
            PouKind::FunctionBlock => SemanticTokenType::CLASS,
            PouKind::Program => SemanticTokenType::NAMESPACE,
        },
        Decl::Type(t) => match t.spec.kind {
            TypeSpecKind::Enum { .. } => SemanticTokenType::ENUM,
            TypeSpecKind::Struct { .. } => SemanticTokenType::STRUCT,
            _ => SemanticTokenType::TYPE,
        },
        Decl::EnumValue(_) => SemanticTokenType::ENUM_MEMBER,
    })
}

fn readonly(d: Decl<'_>) -> u32 {
    match d {
        Decl::EnumValue(_) => READONLY,
        _ => 0,
    }
}

fn contains_ignore_case(text: &str, name: &str) -> bool {
    let n = name.as_bytes();
    if n.is_empty() {
        return false;
    }
    text.as_bytes()
        .windows(n.len())
        .any(|w| w.eq_ignore_ascii_case(n))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_global_and_its_externals_are_one_name() {
        let text = "VAR_GLOBAL\n    g : INT;\nEND_VAR\nPROGRAM P\nVAR_EXTERNAL\n    g : INT;\nEND_VAR\n    g := g + 1;\nEND_PROGRAM\n";
        let uri = "file:///g.st".to_string();
        let p = Project::analyse(vec![(uri.clone(), text.into())], Default::default());
        let refs = p
            .references(&uri, Position::new(7, 4), true)
            .expect("references");
        let lines: Vec<u32> = refs.iter().map(|l| l.range.start.line).collect();
        assert_eq!(lines, [1, 5, 7, 7], "{refs:?}");
        let Ok(edit) = p.rename(&uri, Position::new(5, 4), "level") else {
            panic!("renamed");
        };
        let n: usize = edit.changes.iter().flatten().map(|(_, e)| e.len()).sum();
        assert_eq!(n, 4);
    }

    #[test]
    fn standard_functions_and_blocks_are_not_renamed() {
        let text = "PROGRAM P\nVAR\n    t : TON;\n    x : INT;\nEND_VAR\n    x := MAX(x, 2);\n    t(IN := TRUE, PT := T#1s);\nEND_PROGRAM\n";
        let uri = "file:///p.st".to_string();
        let p = Project::analyse(vec![(uri.clone(), text.into())], Default::default());
        for (line, ch, what) in [(5, 10, "MAX"), (2, 9, "TON"), (6, 7, "IN")] {
            match p.rename(&uri, Position::new(line, ch), "other") {
                Err(RenameError::Refused(m)) => assert!(m.contains(what), "{m}"),
                Err(RenameError::Invalid(m)) => panic!("{what}: {m}"),
                Ok(e) => panic!("{what} renamed: {e:?}"),
            }
        }
        assert!(p.rename(&uri, Position::new(3, 4), "y").is_ok());
    }
}
