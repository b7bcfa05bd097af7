//! Parsing and analysing again only the file that changed (for a
//! language server).
//!
//! A project's files share one position space and one expression arena,
//! both filled in file order, so the trees of the files before a given one
//! never depend on it: they are a prefix of the arena, of the items and of
//! the source map. A caller that keeps the file being edited last in its
//! order parses every other file, then the prelude, then that file
//! ([`parse_all`], which records where the last file starts: a [`Mark`]);
//! after an edit it cuts the project back to the mark and parses only the
//! new text ([`reparse_last`]). The result is the parse a full
//! [`parse_all`] of the same files in the same order gives (the same
//! trees, spans and expression ids; only the interner keeps the names of
//! the texts it saw before).
//!
//! [`check`] then analyses the project in the same two parts: the
//! analyser's state after the first (every file but the last, and the
//! prelude) and the lints' findings there are [`Kept`] and reused while
//! only the last file changes ([`stc_sema::Checkpoint`] says when that
//! gives exactly the whole analysis, and makes the whole analysis when
//! not). The prelude sits before the last file so that it is part of what
//! is kept; the analyser declares the prelude's items after the user's
//! wherever they sit, so the diagnostics are those of [`crate::analyse`].
//!
//! Call these inside [`crate::with_big_stack`].

use stc_diagnostics::{SourceMap, Span};
use stc_syntax::ast::Ast;
use stc_syntax::Interner;

use crate::{Options, Parsed};

pub use stc_sema::Made;

/// Where the trees of every file but the last, and the prelude's, end.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Mark {
    files: usize,
    items: usize,
    exprs: usize,
    unsupported: usize,
    diagnostics: usize,
    /// The prelude's span.
    prelude: Span,
    /// The spellings the last file had not given yet.
    spelling: stc_syntax::intern::SpellingMark,
}

impl Mark {
    /// Where the prelude is.
    pub fn prelude(&self) -> Span {
        self.prelude
    }

    fn split(&self) -> stc_sema::Split {
        stc_sema::Split {
            files: self.files,
            items: self.items,
            exprs: self.exprs,
            unsupported: self.unsupported,
        }
    }
}

fn parse_one(parsed: &mut Parsed, name: String, text: String, opts: &Options) -> Option<Span> {
    let id = parsed.sources.add(name, text)?;
    let f = parsed.sources.file(id);
    let r = stc_syntax::parse_source_in(f, &mut parsed.ast, &mut parsed.interner, opts.iec2);
    parsed.diagnostics.extend(r.diagnostics);
    Some(f.span())
}

fn mark(parsed: &Parsed, prelude: Span) -> Mark {
    Mark {
        files: parsed.sources.len(),
        items: parsed.ast.items.len(),
        exprs: parsed.ast.exprs.len(),
        unsupported: parsed.ast.unsupported_names.len(),
        diagnostics: parsed.diagnostics.len(),
        prelude,
        spelling: parsed.interner.spelling_mark(),
    }
}

fn prelude(parsed: &mut Parsed, opts: &Options) -> Span {
    parse_one(
        parsed,
        stc_sema::prelude::PRELUDE_NAME.into(),
        stc_sema::prelude::source(),
        opts,
    )
    .expect("the prelude fits in the position space")
}

/// Parses the files (name, text) in order, the prelude before the last.
/// Returns the parse and the mark before the last file (where the
/// prelude's span is). A file that does not fit in the 32-bit position
/// space is left out.
pub fn parse_all(mut files: Vec<(String, String)>, opts: &Options) -> (Parsed, Mark) {
    let mut parsed = Parsed {
        sources: SourceMap::new(),
        interner: Interner::new(),
        ast: Ast::default(),
        diagnostics: Vec::new(),
    };
    let last = files.pop();
    for (name, text) in files {
        let _ = parse_one(&mut parsed, name, text, opts);
    }
    let p = prelude(&mut parsed, opts);
    let m = mark(&parsed, p);
    if let Some((name, text)) = last {
        let _ = parse_one(&mut parsed, name, text, opts);
    }
    (parsed, m)
}

/// Drops the last file of a project [`parse_all`] (or this function)
/// parsed, and parses its new text (`name`, `text`).
pub fn reparse_last(
    mut parsed: Parsed,
    mark: Mark,
    name: String,
    text: String,
    opts: &Options,
) -> Parsed {
    parsed.sources.truncate(mark.files);
    parsed.ast.items.truncate(mark.items);
    parsed.ast.exprs.truncate(mark.exprs);
    parsed.ast.unsupported_names.truncate(mark.unsupported);
    parsed.diagnostics.truncate(mark.diagnostics);
    parsed.interner.rewind_spellings(mark.spelling);
    let _ = parse_one(&mut parsed, name, text, opts);
    parsed
}

/// What an analysis by [`check`] keeps for the next one of the same
/// parse's first part: the analyser's checkpoint, and the lints' findings
/// in the first part (once a resumed analysis found them).
pub struct Kept {
    sema: stc_sema::Checkpoint,
    lints: Option<Vec<stc_diagnostics::Diagnostic>>,
}

/// [`crate::check_parsed`] of a project parsed by [`parse_all`] or
/// [`reparse_last`] with `mark`, made from `kept` (what the last analysis
/// of the same first part kept) when it can be. Returns the analysis, what
/// to keep for the next, and how the analysis was made.
pub fn check(
    parsed: Parsed,
    mark: Mark,
    opts: &Options,
    lints: Option<&stc_lint::Levels>,
    kept: Option<Kept>,
) -> (
    crate::Analysed,
    crate::Pending,
    Option<Kept>,
    stc_sema::Made,
) {
    let sema_opts = stc_sema::Options { iec2: opts.iec2 };
    let prelude = mark.prelude;
    let split = mark.split();
    let (mut sema_cp, mut prefix_lints) = match kept {
        Some(k) => (Some(k.sema), k.lints),
        None => (None, None),
    };
    let made = std::cell::Cell::new(stc_sema::Made::Whole);
    let (analysed, pending) = crate::check_with(
        parsed,
        prelude,
        lints,
        |p| {
            let (a, m) = match &sema_cp {
                Some(cp) => stc_sema::resume(
                    cp,
                    &p.ast,
                    &mut p.interner,
                    &p.sources,
                    Some(prelude),
                    sema_opts,
                ),
                None => {
                    let (a, cp, m) = stc_sema::analyze_split(
                        &p.ast,
                        &mut p.interner,
                        &p.sources,
                        Some(prelude),
                        sema_opts,
                        split,
                    );
                    sema_cp = cp;
                    (a, m)
                }
            };
            made.set(m);
            a
        },
        |input, levels| {
            let whole = || stc_lint::check(input, levels);
            let end = input
                .sources
                .files()
                .nth(split.files.saturating_sub(1))
                .map_or(0, |(_, f)| f.span().hi);
            if made.get() != stc_sema::Made::Resumed || end == 0 {
                return whole();
            }
            // The first part's findings are the same for every resumed
            // analysis (no name of the last file reaches it).
            let first = prefix_lints
                .get_or_insert_with(|| stc_lint::check_within(input, levels, 0..end))
                .clone();
            let mut found = first;
            found.extend(stc_lint::check_within(input, levels, end..u32::MAX));
            found
        },
    );
    let kept = sema_cp.map(|sema| Kept {
        sema,
        lints: prefix_lints,
    });
    (analysed, pending, kept, made.get())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn dump(p: &Parsed) -> String {
        format!(
            "{}\n{:?}\n{:?}",
            stc_syntax::dump::dump(&p.ast, &p.interner, Some(&|s: Span| format!("{s:?}"))),
            p.ast.exprs.iter().map(|e| e.span).collect::<Vec<_>>(),
            p.diagnostics
                .iter()
                .map(|d| (d.code, d.span))
                .collect::<Vec<_>>()
        )
    }

    #[test]
    fn a_reparse_is_the_full_parse() {
        let a = "PROGRAM A\nVAR x : INT; END_VAR\n    x := x + 1;\nEND_PROGRAM\n".to_string();
        let b1 = "PROGRAM B\nVAR y : INT; END_VAR\n    y := 2 * y\nEND_PROGRAM\n".to_string();
        let b2 = "PROGRAM B\nVAR y, z : INT; END_VAR\n    y := z;\n    z := (y;\nEND_PROGRAM\n"
            .to_string();
        let opts = Options::default();
        crate::with_big_stack(move || {
            let (p, m) = parse_all(vec![("a.st".into(), a.clone()), ("b.st".into(), b1)], &opts);
            let p = reparse_last(p, m, "b.st".into(), b2.clone(), &opts);
            let (full, full_mark) = parse_all(vec![("a.st".into(), a), ("b.st".into(), b2)], &opts);
            assert_eq!(m.prelude(), full_mark.prelude());
            assert_eq!(dump(&p), dump(&full));
            assert_eq!(p.sources.len(), full.sources.len());
            assert!(!p.diagnostics.is_empty());
        });
    }
}
