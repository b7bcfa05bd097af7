//! The command's view of the pipeline: its options (the language options
//! of [`stc_pipeline`] plus how diagnostics are shown) and the rendering of
//! diagnostics. The phases themselves are [`stc_pipeline`]'s.

use stc_diagnostics::{render_human, render_json, Diagnostic, SourceMap};

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
    /// What the program means (`--std iec2`...).
    pub language: stc_pipeline::Options,
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
