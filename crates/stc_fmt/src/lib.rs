//! `stc fmt`: the canonical layout of Structured Text and Instruction
//! List, checked safe.
//!
//! [`format`] lays a file out again (indentation, one statement per line,
//! spacing around operators, reserved words in one case) from its tokens and
//! trivia ([`layout`]), keeping every token's and every comment's and
//! pragma's own text in source order. Then, on every run, it proves the
//! result: the output parses without error to the same syntax tree (compared
//! through the position-free AST dump), has the same comments and pragmas in
//! the same order, and formats to itself (idempotence). A file that fails any
//! of these is not touched: the caller gets an error instead of text.
//!
//! No I/O: text in, text or an error out. The parser recurses, so callers run
//! [`format`] on a big stack (`stc_pipeline::with_big_stack`) as for any phase.

mod layout;

use stc_diagnostics::Diagnostic;
use stc_syntax::ast::Ast;
use stc_syntax::lexer::Trivia;
use stc_syntax::{dump, Interner};

/// How reserved words (keywords and elementary type names) are spelled.
#[derive(Clone, Copy, PartialEq, Eq, Debug, Default)]
pub enum KeywordCase {
    #[default]
    Upper,
    Lower,
    /// As written.
    Preserve,
}

#[derive(Clone, Copy, Debug)]
pub struct Options {
    pub keyword_case: KeywordCase,
    /// Spaces per indentation level.
    pub indent_width: usize,
    /// 2nd-edition source (`--std iec2`): the words only the 3rd edition
    /// reserved are names, and keep their case.
    pub iec2: bool,
}

impl Default for Options {
    fn default() -> Self {
        Options {
            keyword_case: KeywordCase::Upper,
            indent_width: 4,
            iec2: false,
        }
    }
}

/// Why a file was left alone.
#[derive(Debug)]
pub enum FormatError {
    /// The file has syntax errors (its diagnostics, positioned from `base`).
    Syntax(Vec<Diagnostic>),
    /// The layout would have changed the program or lost a comment: a bug
    /// in the formatter, caught before anything was written.
    Unsafe(String),
}

impl std::fmt::Display for FormatError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            FormatError::Syntax(d) => write!(
                f,
                "the file has {} syntax error{} ({}...); fix {} first",
                d.len(),
                if d.len() == 1 { "" } else { "s" },
                d.first().map_or("", |d| d.message.as_str()),
                if d.len() == 1 { "it" } else { "them" }
            ),
            FormatError::Unsafe(why) => write!(f, "cannot format this file safely: {why}"),
        }
    }
}

/// A file's tree (as its position-free dump) and its comments and pragmas.
struct Parsed {
    tree: String,
    il: layout::IlRegions,
    trivia_text: Vec<String>,
    trivia: Vec<Trivia>,
    tokens: Vec<stc_syntax::token::Token>,
    errors: Vec<Diagnostic>,
}

fn parse(text: &str, base: u32, iec2: bool) -> Parsed {
    let mut ast = Ast::default();
    let mut interner = Interner::new();
    let r = stc_syntax::parse_file_in(text, base, &mut ast, &mut interner, iec2);
    let mut lexed = stc_syntax::lexer::lex(text, base);
    if iec2 {
        for t in lexed.tokens.iter_mut() {
            if stc_syntax::parser::third_edition_word(t.kind) {
                t.kind = stc_syntax::token::TokenKind::Ident;
            }
        }
    }
    let slice = |s: stc_diagnostics::Span| {
        text.get((s.lo - base) as usize..(s.hi - base) as usize)
            .unwrap_or("")
            .trim_end_matches(['\r', '\n'])
            .to_string()
    };
    Parsed {
        il: layout::IlRegions::of(&ast, base),
        tree: dump::dump(&ast, &interner, None),
        trivia_text: r.trivia.iter().map(|t| slice(t.span)).collect(),
        trivia: r.trivia,
        tokens: lexed.tokens,
        errors: r.diagnostics.into_iter().filter(|d| d.is_error()).collect(),
    }
}

/// Formats one file whose first byte is at `base` (for the positions of
/// syntax errors). Returns the new text, or why the file must be left alone.
pub fn format(text: &str, base: u32, opts: &Options) -> Result<String, FormatError> {
    let before = parse(text, base, opts.iec2);
    if !before.errors.is_empty() {
        return Err(FormatError::Syntax(before.errors));
    }
    let out = layout::layout(text, base, &before.tokens, &before.trivia, &before.il, opts);
    let after = parse(&out, 0, opts.iec2);
    if !after.errors.is_empty() {
        return Err(FormatError::Unsafe(format!(
            "the formatted text would not parse ({})",
            after.errors[0].message
        )));
    }
    if after.tree != before.tree {
        return Err(FormatError::Unsafe(
            "the formatted text would parse to a different syntax tree".into(),
        ));
    }
    if after.trivia_text != before.trivia_text {
        return Err(FormatError::Unsafe(
            "a comment or pragma would be lost or changed".into(),
        ));
    }
    let again = layout::layout(&out, 0, &after.tokens, &after.trivia, &after.il, opts);
    if again != out {
        return Err(FormatError::Unsafe(
            "formatting the result again would change it (not idempotent)".into(),
        ));
    }
    Ok(out)
}

#[cfg(test)]
mod tests;
