//! The command's view of the pipeline: its options (the language options
//! of [`stc_pipeline`] plus how diagnostics are shown) and the rendering of
//! diagnostics. The phases themselves are [`stc_pipeline`]'s.

use stc_diagnostics::{render_human, render_json, Code, Diagnostic, Severity, SourceMap};

#[derive(Clone, Copy, PartialEq, Eq, Debug, Default)]
pub enum MessageFormat {
    #[default]
    Human,
    Json,
    /// One SARIF 2.1.0 document for the whole run.
    Sarif,
}

/// Options shared by every subcommand that analyses sources.
#[derive(Clone, Copy, Debug, Default)]
pub struct Options {
    pub format: MessageFormat,
    pub warnings_as_errors: bool,
    /// What the program means (`--std iec2`...).
    pub language: stc_pipeline::Options,
    /// Warnings not reported (`allow` in stc.toml).
    pub allowed: CodeSet,
    /// Warnings reported as errors (`deny` in stc.toml).
    pub denied: CodeSet,
    /// The level of each lint (`[lints]` in stc.toml, `-W`/`-A`/`-D`);
    /// only `stc check` runs the lints.
    pub lints: stc_lint::Levels,
}

/// A set of diagnostic codes.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct CodeSet([u64; 4]);

impl CodeSet {
    pub fn insert(&mut self, c: Code) {
        let i = c as usize;
        if let Some(w) = self.0.get_mut(i / 64) {
            *w |= 1 << (i % 64);
        }
    }

    pub fn contains(&self, c: Code) -> bool {
        let i = c as usize;
        self.0.get(i / 64).is_some_and(|w| w & (1 << (i % 64)) != 0)
    }
}

/// A diagnostic as the options show it: `None` when it is an allowed
/// warning, else with its severity raised where warnings are denied.
pub fn shown(d: &Diagnostic, opts: &Options) -> Option<Diagnostic> {
    if d.is_error() {
        return Some(d.clone());
    }
    if opts.allowed.contains(d.code) {
        return None;
    }
    let mut d = d.clone();
    if opts.warnings_as_errors || opts.denied.contains(d.code) {
        d.severity = Severity::Error;
    }
    Some(d)
}

/// Whether the diagnostics make the run fail (exit status 1).
pub fn failed(diags: &[Diagnostic], opts: &Options) -> bool {
    diags
        .iter()
        .any(|d| shown(d, opts).is_some_and(|d| d.is_error()))
}

/// At most this many errors are printed per file in the human format (a
/// file that is not ST at all, say a VMASM listing given to `stc run`,
/// would otherwise print one per line); the others are counted.
pub const MAX_ERRORS_PER_FILE: usize = 50;

/// The diagnostics as the command prints them: in source order, in the
/// requested format; the human format shows at most
/// [`MAX_ERRORS_PER_FILE`] errors of each file (saying how many more there
/// are) and ends with the summary line (`2 errors, 1 warning`).
pub fn render(diags: &[Diagnostic], sources: &SourceMap, opts: &Options) -> String {
    if opts.format != MessageFormat::Human {
        return render_each(diags, sources, opts);
    }
    // What the options show (allowed warnings left out, denied ones
    // errors): the cap and the summary count these.
    let diags: Vec<Diagnostic> = diags.iter().filter_map(|d| shown(d, opts)).collect();
    let diags = diags.as_slice();
    if diags.is_empty() {
        return String::new();
    }
    let severe = |d: &Diagnostic| d.is_error();
    let file_of = |d: &Diagnostic| {
        sources
            .file_of(d.span.lo)
            .map(|f| sources.file(f).name.clone())
    };
    let mut shown: Vec<Diagnostic> = Vec::new();
    let mut hidden: Vec<(Option<String>, usize)> = Vec::new();
    let mut per_file: std::collections::HashMap<Option<String>, usize> = Default::default();
    let mut sorted: Vec<&Diagnostic> = diags.iter().collect();
    sorted.sort_by_key(|d| d.span.lo);
    for d in sorted {
        if severe(d) {
            let f = file_of(d);
            let n = per_file.entry(f.clone()).or_default();
            *n += 1;
            if *n > MAX_ERRORS_PER_FILE {
                match hidden.iter_mut().find(|(g, _)| *g == f) {
                    Some((_, k)) => *k += 1,
                    None => hidden.push((f, 1)),
                }
                continue;
            }
        }
        shown.push(d.clone());
    }
    let mut out = render_each(&shown, sources, opts);
    for (f, k) in &hidden {
        let what = if *k == 1 { "error" } else { "errors" };
        match f {
            Some(f) => out.push_str(&format!("... and {k} more {what} in {f} not shown\n")),
            None => out.push_str(&format!("... and {k} more {what} not shown\n")),
        }
    }
    out.push_str(&summary(diags, opts));
    out.push('\n');
    out
}

/// The summary line of the human format: `2 errors, 1 warning`.
pub fn summary(diags: &[Diagnostic], opts: &Options) -> String {
    let errors = diags
        .iter()
        .filter(|d| shown(d, opts).is_some_and(|d| d.is_error()))
        .count();
    let warnings = diags.len() - errors;
    let count = |n: usize, one: &str| {
        if n == 1 {
            format!("1 {one}")
        } else {
            format!("{n} {one}s")
        }
    };
    match (errors, warnings) {
        (0, w) => count(w, "warning"),
        (e, 0) => count(e, "error"),
        (e, w) => format!("{}, {}", count(e, "error"), count(w, "warning")),
    }
}

/// Each diagnostic as text, in source order, in the requested format (no
/// summary and no cap: the snapshot tests show every diagnostic).
pub fn render_each(diags: &[Diagnostic], sources: &SourceMap, opts: &Options) -> String {
    let mut sorted: Vec<&Diagnostic> = diags.iter().collect();
    sorted.sort_by_key(|d| d.span.lo);
    if opts.format == MessageFormat::Sarif {
        let shown: Vec<Diagnostic> = sorted.iter().filter_map(|d| shown(d, opts)).collect();
        return stc_diagnostics::render_sarif(&shown, sources, env!("CARGO_PKG_VERSION"));
    }
    let mut out = String::new();
    for d in sorted {
        let Some(d) = shown(d, opts) else {
            continue;
        };
        match opts.format {
            MessageFormat::Human => {
                out.push_str(&render_human(&d, sources));
                out.push('\n');
            }
            MessageFormat::Json => {
                out.push_str(&render_json(&d, sources));
                out.push('\n');
            }
            MessageFormat::Sarif => {}
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_code_fits_a_code_set() {
        assert!(Code::ALL.len() <= 256);
        let mut s = CodeSet::default();
        for &c in Code::ALL {
            assert!(!s.contains(c));
            s.insert(c);
            assert!(s.contains(c));
        }
    }
}
