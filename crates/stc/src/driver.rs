//! The phases, run in order over one project, and the rendering of their
//! diagnostics.

use stc_diagnostics::{render_human, render_json, Diagnostic, SourceMap, Span};
use stc_syntax::ast::Ast;
use stc_syntax::Interner;

#[derive(Clone, Copy, PartialEq, Eq, Debug, Default)]
pub enum MessageFormat {
    #[default]
    Human,
    Json,
}

/// Options shared by every subcommand that analyses sources.
#[derive(Clone, Copy, Debug, Default)]
pub struct Options {
    pub format: MessageFormat,
    pub warnings_as_errors: bool,
    /// `--std iec2`: 2nd edition strictness.
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
    /// The project in the IR; `None` when the analysis found errors.
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
}

/// Parses the project with the standard library prelude appended, then
/// analyses it; without errors, lowers it to the IR and lays its memory out
/// (so `stc check` reports a declaration too large for the memory model,
/// E0901, as every back end would: the layout is computed once, in stc_ir).
pub fn analyse(mut sources: SourceMap, diagnostics: Vec<Diagnostic>, opts: &Options) -> Analysed {
    let prelude_id = sources
        .add(stc_sema::prelude::PRELUDE_NAME, stc_sema::prelude::source())
        .expect("the prelude fits in the position space");
    let prelude = sources.file(prelude_id).span();
    let mut parsed = parse(sources, diagnostics, opts.iec2);
    let mut analysis = stc_sema::analyze(
        &parsed.ast,
        &mut parsed.interner,
        &parsed.sources,
        Some(prelude),
        stc_sema::Options { iec2: opts.iec2 },
    );
    let mut diagnostics = std::mem::take(&mut analysis.diagnostics);
    let clean = !parsed
        .diagnostics
        .iter()
        .chain(diagnostics.iter())
        .any(|d| d.is_error());
    let module = clean.then(|| {
        let m = stc_ir::lower(&parsed.ast, analysis, &parsed.interner, &parsed.sources);
        diagnostics.extend(stc_ir::layout::Layouts::check(&m));
        m
    });
    Analysed {
        parsed,
        diagnostics,
        module,
        prelude,
    }
}

/// The IR of an analysed project without errors.
///
/// # Panics
/// When the project has errors (callers check [`failed`] first).
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

/// Parses every file of the source map as one project.
/// Parses a project; with `iec2`, the words the 3rd edition reserved
/// (CHAR, LTIME, LDT, CONTINUE...) are names.
pub fn parse(sources: SourceMap, mut diagnostics: Vec<Diagnostic>, iec2: bool) -> Parsed {
    let mut interner = Interner::new();
    let (ast, mut diags) = stc_syntax::parse_project_in(&sources, &mut interner, iec2);
    diagnostics.append(&mut diags);
    Parsed {
        sources,
        interner,
        ast,
        diagnostics,
    }
}

/// Whether the diagnostics make the run fail (exit status 1).
pub fn failed(diags: &[Diagnostic], opts: &Options) -> bool {
    diags
        .iter()
        .any(|d| d.is_error() || opts.warnings_as_errors)
}

/// The diagnostics as text, in source order, in the requested format.
pub fn render(diags: &[Diagnostic], sources: &SourceMap, opts: &Options) -> String {
    let mut sorted: Vec<&Diagnostic> = diags.iter().collect();
    sorted.sort_by_key(|d| d.span.lo);
    let mut out = String::new();
    for d in sorted {
        let mut d = d.clone();
        if opts.warnings_as_errors {
            d.severity = stc_diagnostics::Severity::Error;
        }
        match opts.format {
            MessageFormat::Human => {
                out.push_str(&render_human(&d, sources));
                out.push('\n');
            }
            MessageFormat::Json => {
                out.push_str(&render_json(&d, sources));
                out.push('\n');
            }
        }
    }
    out
}

/// Runs `f` on a thread with a large stack. The phases are recursive over
/// trees whose depth the parser bounds; the bound is chosen so this stack is
/// always enough, whatever the input.
pub fn with_big_stack<T: Send>(f: impl FnOnce() -> T + Send) -> T {
    const STACK: usize = 256 << 20;
    std::thread::scope(|s| {
        std::thread::Builder::new()
            .stack_size(STACK)
            .spawn_scoped(s, f)
            .expect("cannot start the compiler thread")
            .join()
            .unwrap_or_else(|e| std::panic::resume_unwind(e))
    })
}
