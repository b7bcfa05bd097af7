//! The compile pipeline: the phases of stc, run in order over one project.
//!
//! [`compile`] is the whole front half in one call: it appends the standard
//! library prelude ([`stc_sema::prelude`]) to the sources, parses, analyses
//! and lowers to the IR, and returns the [`stc_ir::Module`] (when there is no
//! error), every diagnostic, and the [`SourceMap`] the diagnostics' spans
//! point into. The finer steps are for callers that stop early or look at an
//! intermediate result: [`parse`] (no prelude: `stc build --emit ast` shows
//! the user's files only), [`analyse`] (with the prelude), [`lower`] and
//! [`lower_keeping_sources`].
//!
//! The analyser is only correct with the prelude in the project (TON, CTU,
//! R_TRIG... are ST source there), which is why it is added here and
//! nowhere else: every tool (the command, the tests, the benchmarks, the
//! program generator, a language server) goes through this crate.
//!
//! No I/O and no printing: sources come in as a [`SourceMap`], results go out
//! as data. Rendering the diagnostics is the caller's business
//! ([`stc_diagnostics::render_human`] / [`stc_diagnostics::render_json`]).
//!
//! # Stack
//!
//! The phases recurse over trees whose depth the parser bounds (256 levels
//! of nesting, expression trees 4096 deep); [`STACK_SIZE`] is chosen so that
//! bound always fits. [`compile`] runs on a thread of that size by itself.
//! The finer steps run on the caller's thread: call them inside
//! [`with_big_stack`] (the command line runs each whole command in it; a
//! language server must do the same for each request, a default 2 MiB
//! thread is not enough for the deepest inputs the parser accepts).

pub mod incremental;

pub use stc_ir::Module;

use stc_diagnostics::{Diagnostic, SourceMap, Span};
use stc_syntax::ast::Ast;
use stc_syntax::Interner;

/// The options that change what a program means (not how diagnostics are
/// shown: that is the caller's).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Options {
    /// `--std iec2`: 2nd edition strictness; the words only the 3rd edition
    /// reserved (CHAR, LTIME, LDT, CONTINUE...) are names.
    pub iec2: bool,
}

/// A parsed project.
pub struct Parsed {
    pub sources: SourceMap,
    pub interner: Interner,
    pub ast: Ast,
    pub diagnostics: Vec<Diagnostic>,
}

/// A parsed and analysed project, lowered to the IR when it has no error.
pub struct Analysed {
    pub parsed: Parsed,
    /// The analyser's diagnostics, then the memory layout's (E0901).
    pub diagnostics: Vec<Diagnostic>,
    /// The project in the IR; `None` when the analysis found errors or a
    /// declaration is too large for the memory model.
    pub module: Option<stc_ir::Module>,
    /// Where the standard library prelude sits in the source map.
    pub prelude: Span,
}

impl Analysed {
    /// Every diagnostic: the parser's, the analyser's and the layout's.
    pub fn diagnostics(&self) -> impl Iterator<Item = &Diagnostic> {
        self.parsed
            .diagnostics
            .iter()
            .chain(self.diagnostics.iter())
    }

    pub fn all_diagnostics(&self) -> Vec<Diagnostic> {
        self.diagnostics().cloned().collect()
    }

    /// Whether a diagnostic is an error (then the project cannot be lowered).
    pub fn has_errors(&self) -> bool {
        self.diagnostics().any(Diagnostic::is_error)
    }
}

/// The result of [`compile`].
pub struct Compiled {
    /// The IR, when no diagnostic is an error.
    pub module: Option<stc_ir::Module>,
    /// Every diagnostic (the ones given to [`compile`] first), in the order
    /// the phases found them.
    pub diagnostics: Vec<Diagnostic>,
    /// The sources with the prelude appended: the position space of the
    /// diagnostics' spans and of the IR's spans.
    pub sources: SourceMap,
}

/// Parses, analyses and lowers a project (on a thread with a big stack).
/// `diagnostics` are the ones found while loading the sources (kept first).
pub fn compile(sources: SourceMap, diagnostics: Vec<Diagnostic>, opts: &Options) -> Compiled {
    let opts = *opts;
    with_big_stack(move || {
        let a = analyse(sources, diagnostics, &opts);
        let diagnostics = a.all_diagnostics();
        if a.has_errors() {
            return Compiled {
                module: None,
                diagnostics,
                sources: a.parsed.sources,
            };
        }
        let (module, sources) = lower_keeping_sources(a);
        Compiled {
            module: Some(module),
            diagnostics,
            sources,
        }
    })
}

/// [`compile`] of one source text named `name`.
pub fn compile_text(name: &str, text: &str, opts: &Options) -> Compiled {
    let mut sources = SourceMap::new();
    let _ = sources.add(name, text.to_string());
    compile(sources, Vec::new(), opts)
}

/// Parses the project with the standard library prelude appended, then
/// analyses it; without errors, lowers it to the IR and lays its memory out
/// (so `stc check` reports a declaration too large for the memory model,
/// E0901, as every back end would: the layout is computed once, in stc_ir).
/// `diagnostics` are kept first.
pub fn analyse(sources: SourceMap, diagnostics: Vec<Diagnostic>, opts: &Options) -> Analysed {
    analyse_linted(sources, diagnostics, opts, None)
}

/// [`analyse`], then the lints at `lints` on the analysed program
/// (`stc check` and the language server; the other commands do not lint,
/// so their output never changes with a lint). The lints' findings come
/// after the analyser's and do not decide whether the project is lowered.
pub fn analyse_linted(
    mut sources: SourceMap,
    diagnostics: Vec<Diagnostic>,
    opts: &Options,
    lints: Option<&stc_lint::Levels>,
) -> Analysed {
    let prelude_id = sources
        .add(stc_sema::prelude::PRELUDE_NAME, stc_sema::prelude::source())
        .expect("the prelude fits in the position space");
    let prelude = sources.file(prelude_id).span();
    let parsed = parse(sources, diagnostics, opts);
    analyse_parsed(parsed, prelude, opts, lints)
}

/// Analyses a project parsed with the prelude (at `prelude`) and lints it
/// with `lints`: the second half of [`analyse_linted`], for a caller that
/// parsed the files itself ([`incremental`]).
pub fn analyse_parsed(
    parsed: Parsed,
    prelude: Span,
    opts: &Options,
    lints: Option<&stc_lint::Levels>,
) -> Analysed {
    let (mut a, pending) = check_parsed(parsed, prelude, opts, lints);
    lay_out(&mut a, pending);
    a
}

/// The analysis of a project, waiting to be lowered and laid out when it
/// has no error ([`lay_out`]).
pub struct Pending {
    analysis: stc_sema::Analysis,
    clean: bool,
}

/// [`analyse_parsed`] up to the lints: the analyser's diagnostics, then the
/// lints', and what [`lay_out`] needs to lower the project and check its
/// memory layout (E0901) when the analysis found no error. A language
/// server publishes the diagnostics of this step first.
pub fn check_parsed(
    parsed: Parsed,
    prelude: Span,
    opts: &Options,
    lints: Option<&stc_lint::Levels>,
) -> (Analysed, Pending) {
    let sema_opts = stc_sema::Options { iec2: opts.iec2 };
    check_with(
        parsed,
        prelude,
        lints,
        |p| {
            stc_sema::analyze(
                &p.ast,
                &mut p.interner,
                &p.sources,
                Some(prelude),
                sema_opts,
            )
        },
        stc_lint::check,
    )
}

/// [`check_parsed`] with the analysis made by `analyse` and the lints
/// found by `lint` (given the analysis): the one sequence of both for the
/// whole analysis and the incremental one ([`incremental`]).
pub(crate) fn check_with(
    mut parsed: Parsed,
    prelude: Span,
    lints: Option<&stc_lint::Levels>,
    analyse: impl FnOnce(&mut Parsed) -> stc_sema::Analysis,
    lint: impl FnOnce(&stc_lint::Input<'_>, &stc_lint::Levels) -> Vec<Diagnostic>,
) -> (Analysed, Pending) {
    let mut analysis = analyse(&mut parsed);
    let mut diagnostics = std::mem::take(&mut analysis.diagnostics);
    let clean = !parsed
        .diagnostics
        .iter()
        .chain(diagnostics.iter())
        .any(|d| d.is_error());
    if let Some(levels) = lints {
        let said: Vec<Diagnostic> = parsed
            .diagnostics
            .iter()
            .chain(diagnostics.iter())
            .cloned()
            .collect();
        let found = lint(
            &stc_lint::Input {
                ast: &parsed.ast,
                analysis: &analysis,
                interner: &parsed.interner,
                sources: &parsed.sources,
                prelude,
                diagnostics: &said,
            },
            levels,
        );
        diagnostics.extend(found);
    }
    let a = Analysed {
        parsed,
        diagnostics,
        module: None,
        prelude,
    };
    (a, Pending { analysis, clean })
}

/// Lowers a project [`check_parsed`] found no error in and lays its memory
/// out: its diagnostics get E0901 where a declaration is too large for the
/// memory model, and it gets its module when nothing is. Returns whether
/// diagnostics were added. (A project with errors is left as it is.)
pub fn lay_out(a: &mut Analysed, pending: Pending) -> bool {
    if !pending.clean {
        return false;
    }
    let m = stc_ir::lower(
        &a.parsed.ast,
        pending.analysis,
        &a.parsed.interner,
        &a.parsed.sources,
    );
    let layout = stc_ir::layout::Layouts::check(&m);
    let fits = !layout.iter().any(|d| d.is_error());
    let added = !layout.is_empty();
    a.diagnostics.extend(layout);
    a.module = fits.then_some(m);
    added
}

/// The IR of an analysed project without errors.
///
/// # Panics
/// When the project has errors (callers check [`Analysed::has_errors`]
/// first).
pub fn lower(a: Analysed) -> stc_ir::Module {
    lower_keeping_sources(a).0
}

/// The same, keeping the sources (to turn spans of the IR into positions).
///
/// # Panics
/// When the project has errors.
pub fn lower_keeping_sources(a: Analysed) -> (stc_ir::Module, SourceMap) {
    let m = a
        .module
        .expect("a project is lowered only when its analysis found no error");
    (m, a.parsed.sources)
}

/// Parses every file of the source map as one project, without the
/// prelude. `diagnostics` are kept first.
pub fn parse(sources: SourceMap, mut diagnostics: Vec<Diagnostic>, opts: &Options) -> Parsed {
    let mut interner = Interner::new();
    let (ast, mut diags) = stc_syntax::parse_project_in(&sources, &mut interner, opts.iec2);
    diagnostics.append(&mut diags);
    Parsed {
        sources,
        interner,
        ast,
        diagnostics,
    }
}

/// The stack the phases need on the deepest input the parser accepts.
pub const STACK_SIZE: usize = 256 << 20;

/// Runs `f` on a thread of [`STACK_SIZE`] bytes and returns its result (a
/// panic in `f` is resumed on the caller's thread).
pub fn with_big_stack<T: Send>(f: impl FnOnce() -> T + Send) -> T {
    std::thread::scope(|s| {
        std::thread::Builder::new()
            .stack_size(STACK_SIZE)
            .spawn_scoped(s, f)
            .expect("cannot start the compiler thread")
            .join()
            .unwrap_or_else(|e| std::panic::resume_unwind(e))
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    const TIMER: &str = "PROGRAM Main
VAR t : TON; q : BOOL; END_VAR
    t(IN := TRUE, PT := T#1s);
    q := t.Q;
END_PROGRAM
";

    #[test]
    fn the_prelude_is_inside() {
        let c = compile_text("main.st", TIMER, &Options::default());
        assert!(c.diagnostics.is_empty(), "{:?}", c.diagnostics);
        let m = c.module.expect("a module");
        assert!(m
            .pous
            .iter()
            .any(|p| m.name(p.name).eq_ignore_ascii_case("TON")));
        assert!(c
            .sources
            .files()
            .any(|(_, f)| f.name == stc_sema::prelude::PRELUDE_NAME));
    }

    #[test]
    fn diagnostics_come_back_with_spans() {
        let text = "PROGRAM Main\nVAR x : INT; END_VAR\n    x := undeclared + 1;\nEND_PROGRAM\n";
        let c = compile_text("bad.st", text, &Options::default());
        assert!(c.module.is_none());
        let d = c
            .diagnostics
            .iter()
            .find(|d| d.is_error())
            .expect("an error");
        let at = text.find("undeclared").expect("the name") as u32;
        let (_, file) = c.sources.files().next().expect("the user's file");
        assert_eq!(file.name, "bad.st");
        assert_eq!(d.span.lo, file.base + at);
        let (f, lc) = c.sources.locate(d.span.lo).expect("a position");
        assert_eq!((f.name.as_str(), lc.line, lc.col), ("bad.st", 3, 10));
    }

    #[test]
    fn parse_only_has_no_prelude_and_no_analysis() {
        let mut sm = SourceMap::new();
        sm.add(
            "p.st",
            "PROGRAM P\nVAR x : INT; END_VAR\n    x := y;\nEND_PROGRAM\n".into(),
        );
        // An unknown name is the analyser's error, not the parser's.
        let p = with_big_stack(move || parse(sm, Vec::new(), &Options::default()));
        assert!(p.diagnostics.is_empty(), "{:?}", p.diagnostics);
        assert_eq!(p.sources.len(), 1);
        assert_eq!(p.ast.items.len(), 1);
    }

    #[test]
    fn iec2_makes_third_edition_words_names() {
        let text = "PROGRAM P\nVAR ltime : INT; END_VAR\n    ltime := 1;\nEND_PROGRAM\n";
        let strict = compile_text("p.st", text, &Options { iec2: true });
        assert!(strict.module.is_some(), "{:?}", strict.diagnostics);
        assert!(strict.diagnostics.is_empty(), "{:?}", strict.diagnostics);
        // In the 3rd edition the word is reserved: accepted as a name with
        // the dialect warning W0009.
        let third = compile_text("p.st", text, &Options::default());
        assert!(
            third
                .diagnostics
                .iter()
                .any(|d| d.code == stc_diagnostics::Code::W0009),
            "{:?}",
            third.diagnostics
        );
    }
}
