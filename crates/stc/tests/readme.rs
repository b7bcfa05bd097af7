//! The README's claims about the command are true: its example diagnostic
//! is what `stc check` prints for the file it names, and every repository
//! path it mentions exists.

use std::path::Path;

fn root() -> &'static Path {
    Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../.."))
}

fn readme() -> String {
    std::fs::read_to_string(root().join("README.md")).expect("README.md")
}

#[test]
fn the_example_diagnostic_is_what_stc_prints() {
    let text = readme();
    let start = text
        .find("```text\ndocs/examples/")
        .expect("a diagnostic example")
        + 8;
    let end = start + text[start..].find("```").expect("its end");
    let shown = &text[start..end];
    let file = shown.split(':').next().expect("a file name");
    std::env::set_current_dir(root()).expect("the repository root");
    let out = stc::cli::run_args(&["stc", "check", file]);
    assert_eq!(
        out.stderr, shown,
        "README.md shows another output for {file}"
    );
}

#[test]
fn every_path_the_readme_names_exists() {
    let text = readme();
    let mut missing = Vec::new();
    for word in text.split(|c: char| c.is_whitespace() || "`()[],;".contains(c)) {
        let word = word
            .split(':')
            .next()
            .unwrap_or_default()
            .trim_end_matches('.');
        let is_path = ["examples/", "docs/", "crates/", "tests/", "bench/", "../"]
            .iter()
            .any(|p| word.starts_with(p))
            || word.ends_with(".md");
        // The files `stc init` writes into a new project are not the
        // repository's.
        let from_init = ["src/main.st", "tests/test_main.st", "stc.toml"].contains(&word);
        if is_path && !from_init && !word.contains(['*', '<', '>']) && !root().join(word).exists() {
            missing.push(word.to_string());
        }
        if word.starts_with("../") {
            missing.push(format!("{word} (outside the repository)"));
        }
    }
    assert!(
        missing.is_empty(),
        "README.md names paths that do not exist: {missing:?}"
    );
}
