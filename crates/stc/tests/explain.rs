//! `stc explain`: every code's example is compiled through the real
//! pipeline. The wrong text gives exactly its code, once, on the line marked
//! `// CODE`; the right text gives no diagnostic at all. A code without an
//! example must be listed in `NO_EXAMPLE` with the reason, so a new code
//! needs an example or a reason.

use stc_diagnostics::{Code, Diagnostic, SourceMap};

/// Codes that cannot be shown in one short, self-contained source text.
const NO_EXAMPLE: &[(Code, &str)] = &[
    (
        Code::E0023,
        "needs nesting hundreds of levels deep, not a short example",
    ),
    (
        Code::W0001,
        "needs a file that is not valid UTF-8; an example is text",
    ),
    (Code::E1101, NETLIST),
    (Code::E1102, NETLIST),
    (Code::E1103, NETLIST),
    (Code::E1104, NETLIST),
    (Code::E1105, NETLIST),
    (Code::E1106, NETLIST),
];

/// Why the netlist back end's codes have no example here: they are given
/// by `stc build --emit netlist` (tests/netlist/refuse has a case for
/// each), not by the analysis this test runs.
const NETLIST: &str = "reported by the netlist back end, not by `stc check`";

/// (line, code) of each diagnostic.
fn keys(diags: &[Diagnostic], sm: &SourceMap) -> Vec<(u32, String)> {
    diags
        .iter()
        .map(|d| {
            let line = sm.locate(d.span.lo).map_or(0, |(_, lc)| lc.line);
            (line, d.code.as_str().to_string())
        })
        .collect()
}

fn compile(name: &str, text: &str) -> Vec<(u32, String)> {
    let c = stc_pipeline::compile_text(name, text, &stc_pipeline::Options::default());
    keys(&c.diagnostics, &c.sources)
}

/// A lint's example is checked with that lint on and every other off.
fn compile_linted(name: &str, text: &str, lint: Code) -> Vec<(u32, String)> {
    let mut sm = SourceMap::new();
    let _ = sm.add(name, text.to_string());
    let mut levels = stc_lint::Levels::all(stc_lint::Level::Allow);
    levels.set(lint, stc_lint::Level::Warn);
    let a = stc_pipeline::with_big_stack(move || {
        stc_pipeline::analyse_linted(
            sm,
            Vec::new(),
            &stc_pipeline::Options::default(),
            Some(&levels),
        )
    });
    keys(&a.all_diagnostics(), &a.parsed.sources)
}

/// The line of `text` marked `// CODE` (1-based).
fn marked_line(text: &str, code: Code) -> Option<u32> {
    let marker = format!("// {code}");
    text.lines()
        .position(|l| l.contains(&marker))
        .map(|i| i as u32 + 1)
}

fn check_example(code: Code) -> Result<(), String> {
    let Some(ex) = stc_diagnostics::example(code) else {
        return Err("no example, and not listed in NO_EXAMPLE".into());
    };
    let line = marked_line(ex.wrong, code).ok_or("the wrong text marks no line")?;
    let run = |name: &str, text: &str| match stc_lint::of_code(code) {
        Some(_) => compile_linted(name, text, code),
        None => compile(name, text),
    };
    let wrong = run("wrong.st", ex.wrong);
    if wrong != [(line, code.to_string())] {
        return Err(format!(
            "the wrong text gives {wrong:?}, expected [({line}, {code:?})]"
        ));
    }
    let right = run("right.st", ex.right);
    if !right.is_empty() {
        return Err(format!("the right text gives {right:?}"));
    }
    Ok(())
}

#[test]
fn every_example_gives_its_code_and_its_correction_nothing() {
    let mut failures = String::new();
    for &code in Code::ALL {
        if let Some((_, why)) = NO_EXAMPLE.iter().find(|(c, _)| *c == code) {
            assert!(
                stc_diagnostics::example(code).is_none(),
                "{code} has an example but is listed in NO_EXAMPLE ({why})"
            );
            continue;
        }
        if let Err(e) = check_example(code) {
            failures.push_str(&format!("{code}: {e}\n"));
        }
    }
    assert!(failures.is_empty(), "examples that fail:\n{failures}");
}

#[test]
fn explain_prints_the_explanation_then_the_example() {
    let out = stc::cli::run_args(&["stc", "explain", "e0301"]);
    assert_eq!(out.status, 0);
    let ex = stc_diagnostics::example(Code::E0301).unwrap();
    let text = &out.stdout;
    assert!(text.starts_with("E0301: incompatible types in assignment\n\n"));
    let explanation = text.find(Code::E0301.explanation()).unwrap();
    let wrong = text.find("For example, this is wrong:\n\n").unwrap();
    let right = text.find("\nand this is right:\n\n").unwrap();
    assert!(explanation < wrong && wrong < right);
    let indented = |s: &str| -> String {
        s.lines()
            .map(|l| {
                if l.is_empty() {
                    "\n".to_string()
                } else {
                    format!("    {l}\n")
                }
            })
            .collect()
    };
    assert!(text[wrong..right].contains(&indented(ex.wrong)));
    assert!(text[right..].ends_with(&indented(ex.right)));
}

#[test]
fn explain_without_an_example_prints_the_explanation_only() {
    let out = stc::cli::run_args(&["stc", "explain", "W0001"]);
    assert_eq!(out.status, 0);
    assert!(out
        .stdout
        .ends_with(&format!("{}\n", Code::W0001.explanation())));
    assert!(!out.stdout.contains("For example"));
}
