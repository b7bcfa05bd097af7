//! Parsing again only the file that changed (for a language server).
//!
//! A project's files share one position space and one expression arena,
//! both filled in file order, so the trees of the files before a given one
//! never depend on it: they are a prefix of the arena, of the items and of
//! the source map. A caller that keeps the file being edited last in its
//! order ([`parse_all`] records where the others end, a [`Mark`]) can
//! therefore cut the project back to the mark after an edit and parse only
//! the new text of that file, and the prelude after it
//! ([`reparse_last`]); the result is the parse a full [`crate::parse`] of
//! the same files in the same order gives (the same trees, spans and
//! expression ids; only the interner keeps the names of the texts it saw
//! before).
//!
//! Call these inside [`crate::with_big_stack`].

use stc_diagnostics::{SourceMap, Span};
use stc_syntax::ast::Ast;
use stc_syntax::Interner;

use crate::{Options, Parsed};

/// Where the trees of every file but the last end.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Mark {
    files: usize,
    items: usize,
    exprs: usize,
    unsupported: usize,
    diagnostics: usize,
}

fn parse_one(parsed: &mut Parsed, name: String, text: String, opts: &Options) -> Option<Span> {
    let id = parsed.sources.add(name, text)?;
    let f = parsed.sources.file(id);
    // The standard library (`<stdlib>`) is written in the 3rd edition.
    let iec2 = opts.iec2 && !f.name.starts_with('<');
    let r = stc_syntax::parse_file_in(&f.text, f.base, &mut parsed.ast, &mut parsed.interner, iec2);
    parsed.diagnostics.extend(r.diagnostics);
    Some(f.span())
}

fn mark(parsed: &Parsed) -> Mark {
    Mark {
        files: parsed.sources.len(),
        items: parsed.ast.items.len(),
        exprs: parsed.ast.exprs.len(),
        unsupported: parsed.ast.unsupported_names.len(),
        diagnostics: parsed.diagnostics.len(),
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

/// Parses the files (name, text) in order, then the prelude. Returns the
/// parse, the mark after every file but the last, and the prelude's span.
/// A file that does not fit in the 32-bit position space is left out.
pub fn parse_all(files: Vec<(String, String)>, opts: &Options) -> (Parsed, Mark, Span) {
    let mut parsed = Parsed {
        sources: SourceMap::new(),
        interner: Interner::new(),
        ast: Ast::default(),
        diagnostics: Vec::new(),
    };
    let n = files.len();
    let mut m = mark(&parsed);
    for (i, (name, text)) in files.into_iter().enumerate() {
        if i + 1 == n {
            m = mark(&parsed);
        }
        let _ = parse_one(&mut parsed, name, text, opts);
    }
    let p = prelude(&mut parsed, opts);
    (parsed, m, p)
}

/// Drops the last file and the prelude of a project [`parse_all`] (or this
/// function) parsed, and parses the last file's new text (`name`, `text`)
/// and the prelude again. Returns the parse and the prelude's span.
pub fn reparse_last(
    mut parsed: Parsed,
    mark: Mark,
    name: String,
    text: String,
    opts: &Options,
) -> (Parsed, Span) {
    parsed.sources.truncate(mark.files);
    parsed.ast.items.truncate(mark.items);
    parsed.ast.exprs.truncate(mark.exprs);
    parsed.ast.unsupported_names.truncate(mark.unsupported);
    parsed.diagnostics.truncate(mark.diagnostics);
    let _ = parse_one(&mut parsed, name, text, opts);
    let p = prelude(&mut parsed, opts);
    (parsed, p)
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
            let (p, m, _) = parse_all(vec![("a.st".into(), a.clone()), ("b.st".into(), b1)], &opts);
            let (p, prelude) = reparse_last(p, m, "b.st".into(), b2.clone(), &opts);
            let (full, _, full_prelude) =
                parse_all(vec![("a.st".into(), a), ("b.st".into(), b2)], &opts);
            assert_eq!(prelude, full_prelude);
            assert_eq!(dump(&p), dump(&full));
            assert_eq!(p.sources.len(), full.sources.len());
            assert!(!p.diagnostics.is_empty());
        });
    }
}
