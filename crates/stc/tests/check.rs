//! The check conformance suite (docs/testing.md): every case of
//! `tests/conformance/check` (and every run case and example, which must be
//! valid) gives exactly its annotated diagnostics, through the same path as
//! `stc check`.

mod common;

use std::path::Path;

use stc_pipeline::Options;

/// The options of a case from its `// flags:` lines.
fn options(case: &Path) -> Options {
    let mut opts = Options::default();
    for f in common::case_files(case) {
        let text = std::fs::read_to_string(&f).unwrap_or_default();
        for line in text.lines() {
            if let Some(flags) = line.trim().strip_prefix("// flags:") {
                let words: Vec<&str> = flags.split_whitespace().collect();
                for w in words.windows(2) {
                    if w == ["--std", "iec2"] {
                        opts.iec2 = true;
                    }
                }
                if words.contains(&"--std=iec2") {
                    opts.iec2 = true;
                }
            }
        }
    }
    opts
}

fn check_case(case: &Path) -> Result<(), String> {
    let (sm, diags) = stc::sources::load(&common::case_files(case)).map_err(|e| e.to_string())?;
    let opts = options(case);
    let analysed = stc_pipeline::with_big_stack(move || stc_pipeline::analyse(sm, diags, &opts));
    common::compare(&analysed.all_diagnostics(), &analysed.parsed.sources)
}

#[test]
fn check_cases_give_exactly_their_annotated_diagnostics() {
    common::run_all(&common::data_dir().join("conformance/check"), check_case);
}

#[test]
fn run_cases_check_cleanly_except_for_their_annotations() {
    common::run_all(&common::data_dir().join("conformance/run"), check_case);
}

#[test]
fn examples_check_without_any_diagnostic() {
    common::run_all(&common::data_dir().join("../examples"), check_case);
}

/// Every diagnostic code of the catalogue is triggered by at least one test
/// case (an annotation in the corpus), and has an explanation.
#[test]
fn every_diagnostic_code_has_a_test_case() {
    let mut seen = std::collections::BTreeSet::new();
    let mut stack = vec![common::data_dir()];
    while let Some(d) = stack.pop() {
        for e in std::fs::read_dir(&d).unwrap().flatten() {
            let p = e.path();
            if p.is_dir() {
                stack.push(p);
            } else if p.extension().is_some_and(|x| x == "st" || x == "il") {
                let text = std::fs::read_to_string(&p).unwrap_or_else(|_| {
                    String::from_utf8_lossy(&std::fs::read(&p).unwrap()).into_owned()
                });
                for (_, _, code) in common::annotations("", &text) {
                    seen.insert(code);
                }
            }
        }
    }
    let missing: Vec<&str> = stc_diagnostics::Code::ALL
        .iter()
        .map(|c| c.as_str())
        .filter(|c| !seen.contains(*c))
        .collect();
    assert!(missing.is_empty(), "codes without a test case: {missing:?}");
}
