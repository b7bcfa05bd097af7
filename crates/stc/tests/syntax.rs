//! The syntax suite (docs/testing.md): every file of `tests/syntax/ok` parses
//! without a diagnostic, matches its AST snapshot and survives a round trip
//! through the printer; every file of `tests/syntax/err` gives exactly its
//! annotated diagnostics, whose rendering is snapshotted too.

mod common;

use std::path::Path;

use stc::driver;
use stc_syntax::{dump, print, Interner};

fn parse(path: &Path) -> stc_pipeline::Parsed {
    let (sm, diags) = stc::sources::load(&common::case_files(path)).expect("readable test file");
    stc_pipeline::with_big_stack(move || {
        stc_pipeline::parse(sm, diags, &stc_pipeline::Options::default())
    })
}

fn relative(path: &Path) -> String {
    let base = common::data_dir().join("syntax");
    path.strip_prefix(&base)
        .unwrap_or(path)
        .display()
        .to_string()
        .replace('/', "__")
}

/// The AST dump of a source text, without positions.
fn dump_of(text: &str) -> (String, Vec<stc_diagnostics::Diagnostic>) {
    let mut sm = stc_diagnostics::SourceMap::new();
    sm.add("roundtrip.st", text.to_string());
    let mut interner = Interner::new();
    let (ast, diags) = stc_syntax::parse_project(&sm, &mut interner);
    (dump::dump(&ast, &interner, None), diags)
}

#[test]
fn valid_files_parse_cleanly_match_snapshots_and_round_trip() {
    let dir = common::data_dir().join("syntax/ok");
    let mut snapshots = Vec::new();
    common::run_all(&dir, |case| {
        let parsed = parse(case);
        common::compare(&parsed.diagnostics, &parsed.sources)?;
        let sm = &parsed.sources;
        let pos = |s: stc_diagnostics::Span| match sm.locate(s.lo) {
            Some((_, lc)) => format!("{}:{}", lc.line, lc.col),
            None => "?".into(),
        };
        let with_pos = dump::dump(&parsed.ast, &parsed.interner, Some(&pos));
        snapshots.push((relative(case), with_pos));

        let original = dump::dump(&parsed.ast, &parsed.interner, None);
        let pragma_text = |s: stc_diagnostics::Span| sm.slice(s).to_string();
        let printed = print::print(&parsed.ast, &parsed.interner, &pragma_text);
        let (reparsed, diags) = stc_pipeline::with_big_stack(|| dump_of(&printed));
        let reparse_errors = diags.iter().any(|d| d.is_error());
        if reparse_errors || reparsed != original {
            return Err(format!(
                "round trip changed the tree\n--- printed:\n{printed}\n--- original tree:\n{original}\n--- reparsed tree:\n{reparsed}\n--- diagnostics: {diags:?}"
            ));
        }
        Ok(())
    });
    insta::with_settings!({snapshot_path => "../../../tests/syntax/snapshots", prepend_module_to_snapshot => false}, {
        for (name, text) in snapshots {
            insta::assert_snapshot!(name, text);
        }
    });
}

#[test]
fn error_files_give_exactly_their_annotated_diagnostics() {
    let dir = common::data_dir().join("syntax/err");
    let mut snapshots = Vec::new();
    common::run_all(&dir, |case| {
        let parsed = parse(case);
        common::compare(&parsed.diagnostics, &parsed.sources)?;
        let rendered = driver::render_each(
            &parsed.diagnostics,
            &parsed.sources,
            &driver::Options::default(),
        );
        let base = common::data_dir().display().to_string();
        snapshots.push((relative(case), rendered.replace(&base, "tests")));
        Ok(())
    });
    insta::with_settings!({snapshot_path => "../../../tests/syntax/snapshots", prepend_module_to_snapshot => false}, {
        for (name, text) in snapshots {
            insta::assert_snapshot!(name, text);
        }
    });
}

/// Every source in the repository (examples and all test data, valid or not)
/// parses without a panic; the examples parse without any diagnostic.
#[test]
fn corpus_of_every_source_file_parses() {
    let root = common::data_dir().join("..");
    let mut files = Vec::new();
    for dir in ["examples", "tests"] {
        let mut stack = vec![root.join(dir)];
        while let Some(d) = stack.pop() {
            for e in std::fs::read_dir(&d).unwrap().flatten() {
                let p = e.path();
                if p.is_dir() {
                    stack.push(p);
                } else if p.extension().is_some_and(|x| x == "st" || x == "il") {
                    files.push(p);
                }
            }
        }
    }
    assert!(files.len() > 100);
    for f in &files {
        let parsed = parse(f);
        if f.starts_with(root.join("examples")) {
            assert!(
                parsed.diagnostics.is_empty(),
                "{}: {}",
                f.display(),
                driver::render_each(
                    &parsed.diagnostics,
                    &parsed.sources,
                    &driver::Options::default()
                )
            );
        }
    }
}
