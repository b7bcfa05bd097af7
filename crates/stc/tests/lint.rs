//! The lint suite: every case of `tests/lint` gives exactly its annotated
//! diagnostics (`//~ L0003`...) through the path of `stc check`, with the
//! lints its `// lints:` line names at `warn` (every lint when it has
//! none) and the others off; a `// lints: default` line keeps every lint
//! at its default level.

mod common;

use std::path::Path;

use stc_lint::{Level, Levels};

fn levels(case: &Path) -> Levels {
    for f in common::case_files(case) {
        let text = std::fs::read_to_string(&f).unwrap_or_default();
        for line in text.lines() {
            let Some(names) = line.trim().strip_prefix("// lints:") else {
                continue;
            };
            if names.trim() == "default" {
                return Levels::default();
            }
            let mut l = Levels::all(Level::Allow);
            for n in names.split_whitespace() {
                let lint = stc_lint::find(n).unwrap_or_else(|| panic!("unknown lint {n}"));
                l.set(lint.code, Level::Warn);
            }
            return l;
        }
    }
    Levels::all(Level::Warn)
}

fn lint_case(case: &Path) -> Result<(), String> {
    let (sm, diags) = stc::sources::load(&common::case_files(case)).map_err(|e| e.to_string())?;
    let levels = levels(case);
    let analysed = stc_pipeline::with_big_stack(move || {
        stc_pipeline::analyse_linted(sm, diags, &stc_pipeline::Options::default(), Some(&levels))
    });
    common::compare(&analysed.all_diagnostics(), &analysed.parsed.sources)
}

#[test]
fn lint_cases_give_exactly_their_annotated_diagnostics() {
    common::run_all(&common::data_dir().join("lint"), lint_case);
}

/// `stc check` shows the lints at the levels of the command line: `-W`
/// turns one on, `-D` makes it an error (exit 1), `-A` turns it off; an
/// unknown name is a usage error.
#[test]
fn levels_from_the_command_line() {
    let case = common::data_dir().join("lint/L0006_case_without_else.st");
    let case = case.to_str().unwrap();
    let o = stc::cli::run_args(&["stc", "check", case]);
    assert_eq!(o.status, 0, "{}", o.stderr);
    assert!(!o.stderr.contains("L0006"), "off by default: {}", o.stderr);
    let o = stc::cli::run_args(&["stc", "check", "-W", "case-without-else", case]);
    assert_eq!(o.status, 0, "{}", o.stderr);
    assert!(o.stderr.contains("warning[L0006]"), "{}", o.stderr);
    let o = stc::cli::run_args(&["stc", "check", "-D", "L0006", case]);
    assert_eq!(o.status, 1, "{}", o.stderr);
    assert!(o.stderr.contains("error[L0006]"), "{}", o.stderr);
    let o = stc::cli::run_args(&[
        "stc",
        "check",
        "-W",
        "case-without-else",
        "-A",
        "case_without_else",
        "--message-format",
        "json",
        case,
    ]);
    assert_eq!(o.status, 0, "{}", o.stderr);
    let o = stc::cli::run_args(&["stc", "check", "-W", "no-such-lint", case]);
    assert_eq!(o.status, 2, "{}", o.stderr);
    assert!(
        o.stderr.contains("unknown lint `no-such-lint`"),
        "{}",
        o.stderr
    );
    // JSON and SARIF carry the lint's code like any other.
    let o = stc::cli::run_args(&[
        "stc",
        "check",
        "-W",
        "L0006",
        "--message-format",
        "json",
        case,
    ]);
    assert!(o.stderr.contains("\"code\":\"L0006\""), "{}", o.stderr);
    let o = stc::cli::run_args(&[
        "stc",
        "check",
        "-W",
        "L0006",
        "--message-format",
        "sarif",
        case,
    ]);
    let all = format!("{}{}", o.stdout, o.stderr);
    assert!(
        all.contains("\"ruleId\": \"L0006\"") || all.contains("\"ruleId\":\"L0006\""),
        "{all}"
    );
}
