//! `stc test`: unit tests written in plain ST, run on the VM.
//!
//! A test is a PROGRAM whose name starts with `TEST_` (any case), in the
//! project's sources or its test sources (stc.toml `[test] sources`). Each
//! runs alone, as `stc run --program TEST_x` would run it, on a fresh VM:
//! one cycle, or as many as it asks for with `TEST_CYCLES(n)` (ended early
//! by `TEST_DONE()`); cycle k runs at time (k-1) * tick, so timers (TON, TOF,
//! TP) and everything counted in cycles behave deterministically. A test
//! stops at the end of the first cycle in which an assertion failed, or at
//! a run-time fault.
//!
//! The assertions are ST functions of a small library shipped with stc
//! (`test_lib/assert.st`), compiled with the project only here. To say
//! where an assertion failed, the test programs' text is instrumented
//! before compiling, without moving any line: each test program gets a
//! hidden log variable (`STC_LOG`, declared on its PROGRAM line) and each
//! call of a library function inside it gets the call's line and that log
//! as two more arguments. After each cycle the runner reads the log through
//! the runtime's variable paths.

use std::fmt::Write;
use std::path::PathBuf;
use std::sync::Arc;

use stc_diagnostics::SourceMap;
use stc_runtime::value::Shown;
use stc_syntax::lexer::lex;
use stc_syntax::token::{Keyword, TokenKind};
use stc_values::Value;

use crate::cli::{Outcome, EXIT_ERRORS, EXIT_OK, EXIT_USAGE};
use crate::driver::{self, Options};
use crate::sources;

/// The library, as a file of the project.
pub const LIBRARY: &str = include_str!("test_lib/assert.st");
const LIBRARY_NAME: &str = "<stc-test>";

/// The library functions whose calls get the line and the log.
const LIBRARY_FUNCTIONS: &[&str] = &[
    "ASSERT_TRUE",
    "ASSERT_FALSE",
    "ASSERT_EQ_INT",
    "ASSERT_EQ_UINT",
    "ASSERT_EQ_BOOL",
    "ASSERT_EQ_REAL",
    "ASSERT_NEAR",
    "ASSERT_EQ_STRING",
    "ASSERT_EQ_TIME",
    "TEST_CYCLES",
    "TEST_DONE",
];

/// A test's cycles are capped: a test that asks for more is cut there.
const MAX_CYCLES: i128 = 10_000_000;

pub struct TestArgs {
    pub files: Vec<PathBuf>,
    pub filter: Option<String>,
    pub junit: Option<PathBuf>,
    pub tick: Option<String>,
    pub max_steps: u64,
}

/// A test program found in a file.
#[derive(Debug, Clone)]
pub struct TestDecl {
    pub name: String,
    pub file: String,
}

/// Instruments one file's text (see the module comment); returns the new
/// text and the test programs it declares. Lines do not move.
pub fn instrument(text: &str) -> (String, Vec<String>) {
    let lexed = lex(text, 0);
    let toks = &lexed.tokens;
    let src = |i: usize| &text[toks[i].lo as usize..toks[i].hi as usize];
    let line_of = |pos: u32| text[..pos as usize].bytes().filter(|&b| b == b'\n').count() + 1;
    let mut inserts: Vec<(usize, String)> = Vec::new();
    let mut tests = Vec::new();
    let mut in_config = false;
    let mut in_test = false;
    let mut i = 0;
    while i < toks.len() {
        match toks[i].kind {
            TokenKind::Kw(Keyword::Configuration) => in_config = true,
            TokenKind::Kw(Keyword::EndConfiguration) => in_config = false,
            TokenKind::Kw(Keyword::EndProgram) => in_test = false,
            TokenKind::Kw(Keyword::Program)
                if !in_config
                    && toks.get(i + 1).is_some_and(|t| t.kind == TokenKind::Ident)
                    && src(i + 1)
                        .get(..5)
                        .is_some_and(|p| p.eq_ignore_ascii_case("TEST_")) =>
            {
                in_test = true;
                tests.push(src(i + 1).to_string());
                inserts.push((
                    toks[i + 1].hi as usize,
                    " VAR STC_LOG : STC_TestLog; END_VAR".into(),
                ));
                i += 1;
            }
            TokenKind::Ident
                if in_test
                    && toks.get(i + 1).is_some_and(|t| t.kind == TokenKind::LParen)
                    && LIBRARY_FUNCTIONS
                        .iter()
                        .any(|f| f.eq_ignore_ascii_case(src(i))) =>
            {
                let line = line_of(toks[i].lo);
                let mut depth = 0usize;
                let mut close = None;
                for (j, t) in toks.iter().enumerate().skip(i + 1) {
                    match t.kind {
                        TokenKind::LParen => depth += 1,
                        TokenKind::RParen => {
                            depth -= 1;
                            if depth == 0 {
                                close = Some(j);
                                break;
                            }
                        }
                        TokenKind::Semi | TokenKind::Eof => break,
                        _ => {}
                    }
                }
                if let Some(close) = close {
                    let first = toks[i + 2].kind;
                    let formal = first == TokenKind::Ident
                        && toks.get(i + 3).is_some_and(|t| {
                            matches!(t.kind, TokenKind::Assign | TokenKind::Arrow)
                        });
                    let extra = if close == i + 2 {
                        format!("{line}, STC_LOG")
                    } else if formal {
                        format!(", line := {line}, log := STC_LOG")
                    } else {
                        format!(", {line}, STC_LOG")
                    };
                    inserts.push((toks[close].lo as usize, extra));
                }
            }
            _ => {}
        }
        i += 1;
    }
    let mut out = text.to_string();
    inserts.sort_by_key(|(at, _)| std::cmp::Reverse(*at));
    for (at, s) in inserts {
        out.insert_str(at, &s);
    }
    (out, tests)
}

/// One assertion that failed.
#[derive(Debug, Clone, PartialEq)]
pub struct Failure {
    pub file: String,
    pub line: i128,
    pub msg: String,
    pub expected: String,
    pub actual: String,
}

#[derive(Debug, Clone, PartialEq)]
pub enum Verdict {
    Passed,
    Failed(Vec<Failure>),
    /// A run-time fault (its text) stopped the test.
    Fault(String),
}

#[derive(Debug, Clone)]
pub struct TestResult {
    pub test: TestDecl,
    pub verdict: Verdict,
    pub cycles: u64,
    pub checks: i128,
    /// Simulated time of the last cycle run.
    pub time_ns: i64,
}

fn field<'a>(fields: &'a [(String, Shown)], name: &str) -> Option<&'a Shown> {
    fields.iter().find(|(n, _)| n == name).map(|(_, v)| v)
}

fn int(v: Option<&Shown>) -> i128 {
    match v {
        Some(Shown::Scalar(_, v)) => v.as_int().unwrap_or(0),
        _ => 0,
    }
}

fn text(v: Option<&Shown>) -> String {
    match v {
        Some(Shown::Str(Value::Str(b))) => String::from_utf8_lossy(b).into_owned(),
        _ => String::new(),
    }
}

/// What the log says after a cycle: (checks, done, cycles asked, failures).
fn read_log(report: &stc_runtime::Report, file: &str) -> (i128, bool, i128, Vec<Failure>) {
    let Some((_, Shown::Record(fields))) = report.values.first() else {
        return (0, false, 1, Vec::new());
    };
    let fails = int(field(fields, "fails"));
    let mut failures = Vec::new();
    if let Some(Shown::List(items)) = field(fields, "failures") {
        for item in items.iter().take(fails.clamp(0, 16) as usize) {
            if let Shown::Record(f) = item {
                failures.push(Failure {
                    file: file.to_string(),
                    line: int(field(f, "line")),
                    msg: text(field(f, "msg")),
                    expected: text(field(f, "expected")),
                    actual: text(field(f, "actual")),
                });
            }
        }
    }
    let done = int(field(fields, "done")) != 0;
    (
        int(field(fields, "checks")),
        done,
        int(field(fields, "cycles")),
        failures,
    )
}

fn run_one(
    image: &Arc<stc_vm::Image>,
    test: &TestDecl,
    tick_ns: Option<i64>,
    max_steps: u64,
) -> Result<TestResult, String> {
    let options = stc_runtime::Options {
        program: Some(test.name.clone()),
        tick_ns,
        watch: Some(vec![format!("{}.STC_LOG", test.name)]),
        max_steps,
        ..stc_runtime::Options::default()
    };
    let mut sim = stc_runtime::Simulation::new(Arc::clone(image), &options, None)
        .map_err(|e| format!("{}: {e}", test.name))?;
    let mut result = TestResult {
        test: test.clone(),
        verdict: Verdict::Passed,
        cycles: 0,
        checks: 0,
        time_ns: 0,
    };
    loop {
        let fault = sim.run_cycle().err();
        let report = sim.report();
        result.cycles = sim.completed().max(report.cycle);
        result.time_ns = report.time_ns;
        let (checks, done, wanted, failures) = read_log(&report, &test.file);
        result.checks = checks;
        if let Some(f) = fault {
            result.cycles += 1;
            result.verdict = Verdict::Fault(f.to_string());
            return Ok(result);
        }
        if !failures.is_empty() {
            result.verdict = Verdict::Failed(failures);
            return Ok(result);
        }
        let wanted = wanted.clamp(1, MAX_CYCLES) as u64;
        if done || sim.completed() >= wanted.min(sim.last_cycle()) {
            return Ok(result);
        }
    }
}

fn usage(msg: impl std::fmt::Display) -> Outcome {
    Outcome {
        stderr: format!("error: {msg}\n"),
        status: EXIT_USAGE,
        ..Outcome::default()
    }
}

/// Runs `stc test`.
pub fn run(args: &TestArgs, opts: &Options) -> Outcome {
    let files = match sources::expand(&args.files) {
        Ok(f) => f,
        Err(e) => return usage(e),
    };
    let mut sm = SourceMap::new();
    let diags = Vec::new();
    let mut tests = Vec::new();
    for path in &files {
        let bytes = match std::fs::read(path) {
            Ok(b) => b,
            Err(e) => return usage(format!("cannot read {}: {e}", path.display())),
        };
        let (text, _) = sources::decode(bytes);
        let (text, names) = instrument(&text);
        let name = path.display().to_string();
        tests.extend(names.into_iter().map(|n| TestDecl {
            name: n,
            file: name.clone(),
        }));
        if sm.add(name, text).is_none() {
            return usage("the project is larger than 4 GiB");
        }
    }
    sm.add(LIBRARY_NAME, LIBRARY.to_string());
    let mut compiled = stc_pipeline::compile(sm, diags, &opts.language);
    // A test that asserts nothing leaves its hidden log unused: not the
    // user's variable, so not the user's warning.
    let sources = &compiled.sources;
    compiled.diagnostics.retain(|d| {
        !(d.code == stc_diagnostics::Code::W0104 && sources.slice(d.span) == "STC_LOG")
    });
    let mut o = Outcome {
        stderr: driver::render(&compiled.diagnostics, &compiled.sources, opts),
        ..Outcome::default()
    };
    let module = match compiled.module {
        Some(m) if !driver::failed(&compiled.diagnostics, opts) => m,
        _ => {
            o.status = EXIT_ERRORS;
            return o;
        }
    };
    let image = match stc_vm::compile(&module) {
        Ok(i) => Arc::new(i),
        Err(e) => {
            let (text, status) = crate::cli::vm_compile_error(&e, &compiled.sources, opts);
            o.stderr.push_str(&text);
            o.status = status;
            return o;
        }
    };
    let tick_ns = match args
        .tick
        .as_deref()
        .map(stc_runtime::parse_tick)
        .transpose()
    {
        Ok(t) => t,
        Err(e) => return usage(e),
    };
    let selected: Vec<&TestDecl> = tests
        .iter()
        .filter(|t| {
            args.filter.as_ref().is_none_or(|f| {
                t.name
                    .to_ascii_lowercase()
                    .contains(&f.to_ascii_lowercase())
            })
        })
        .collect();
    let mut results = Vec::new();
    let _ = writeln!(
        o.stdout,
        "running {} test{}",
        selected.len(),
        if selected.len() == 1 { "" } else { "s" }
    );
    for t in selected {
        match run_one(&image, t, tick_ns, args.max_steps) {
            Ok(r) => {
                o.stdout.push_str(&render_result(&r));
                results.push(r);
            }
            Err(e) => return usage(e),
        }
    }
    let failed = results
        .iter()
        .filter(|r| r.verdict != Verdict::Passed)
        .count();
    let passed = results.len() - failed;
    let _ = writeln!(
        o.stdout,
        "\ntest result: {}. {passed} passed, {failed} failed",
        if failed == 0 { "ok" } else { "FAILED" }
    );
    if let Some(path) = &args.junit {
        o.file = Some((path.clone(), junit(&results).into_bytes()));
    }
    o.status = if failed == 0 { EXIT_OK } else { EXIT_ERRORS };
    o
}

fn plural(n: impl Into<i128>, word: &str) -> String {
    let n = n.into();
    format!("{n} {word}{}", if n == 1 { "" } else { "s" })
}

fn render_failure(f: &Failure) -> String {
    let what = if f.msg.is_empty() {
        String::new()
    } else {
        format!("{}: ", f.msg)
    };
    format!(
        "{}:{}: {what}expected {}, actual {}",
        f.file, f.line, f.expected, f.actual
    )
}

fn render_result(r: &TestResult) -> String {
    let at = format!(
        "{}, {}, at {}",
        plural(r.cycles as i128, "cycle"),
        plural(r.checks, "check"),
        stc_syntax::literal::format_duration(r.time_ns, false)
    );
    match &r.verdict {
        Verdict::Passed => format!("test {} ... ok ({at})\n", r.test.name),
        Verdict::Failed(fs) => {
            let mut s = format!("test {} ... FAILED ({at})\n", r.test.name);
            for f in fs {
                let _ = writeln!(s, "    {}", render_failure(f));
            }
            s
        }
        Verdict::Fault(f) => format!("test {} ... FAILED ({at})\n    {f}\n", r.test.name),
    }
}

fn xml_escape(s: &str) -> String {
    let mut out = String::with_capacity(s.len());
    for c in s.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            '\'' => out.push_str("&apos;"),
            c if (c as u32) < 0x20 && !matches!(c, '\n' | '\t' | '\r') => {}
            c => out.push(c),
        }
    }
    out
}

/// The results as JUnit XML (the format CI systems read: one testsuite,
/// one testcase per test, a failure element per failed test).
pub fn junit(results: &[TestResult]) -> String {
    let failures = results
        .iter()
        .filter(|r| r.verdict != Verdict::Passed)
        .count();
    let mut s = String::from("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n");
    let _ = writeln!(
        s,
        "<testsuites name=\"stc test\" tests=\"{}\" failures=\"{failures}\">",
        results.len()
    );
    let _ = writeln!(
        s,
        "  <testsuite name=\"stc test\" tests=\"{}\" failures=\"{failures}\" errors=\"0\">",
        results.len()
    );
    for r in results {
        let name = xml_escape(&r.test.name);
        let file = xml_escape(&r.test.file);
        let head = format!("    <testcase name=\"{name}\" classname=\"{file}\" file=\"{file}\"");
        match &r.verdict {
            Verdict::Passed => {
                let _ = writeln!(s, "{head}/>");
            }
            Verdict::Failed(fs) => {
                let _ = writeln!(s, "{head}>");
                let first = fs.first().map(render_failure).unwrap_or_default();
                let all: Vec<String> = fs.iter().map(render_failure).collect();
                let _ = writeln!(
                    s,
                    "      <failure message=\"{}\" type=\"assertion\">{}</failure>",
                    xml_escape(&first),
                    xml_escape(&all.join("\n"))
                );
                let _ = writeln!(s, "    </testcase>");
            }
            Verdict::Fault(f) => {
                let _ = writeln!(s, "{head}>");
                let _ = writeln!(
                    s,
                    "      <failure message=\"{}\" type=\"fault\">{}</failure>",
                    xml_escape(f),
                    xml_escape(f)
                );
                let _ = writeln!(s, "    </testcase>");
            }
        }
    }
    s.push_str("  </testsuite>\n</testsuites>\n");
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn instrumenting_keeps_lines_and_adds_line_and_log() {
        let src = "PROGRAM TEST_a\n  ASSERT_TRUE(x, 'm');\n  assert_eq_int(expected := 1, actual := f(2), msg := '');\n  TEST_DONE();\nEND_PROGRAM\nPROGRAM Other\n  ASSERT_TRUE(x, 'm');\nEND_PROGRAM\n";
        let (out, tests) = instrument(src);
        assert_eq!(tests, vec!["TEST_a".to_string()]);
        assert_eq!(out.lines().count(), src.lines().count());
        assert!(out.starts_with("PROGRAM TEST_a VAR STC_LOG : STC_TestLog; END_VAR\n"));
        assert!(out.contains("ASSERT_TRUE(x, 'm', 2, STC_LOG);"), "{out}");
        assert!(
            out.contains("assert_eq_int(expected := 1, actual := f(2), msg := '', line := 3, log := STC_LOG);"),
            "{out}"
        );
        assert!(out.contains("TEST_DONE(4, STC_LOG);"), "{out}");
        // Outside a test program nothing changes.
        assert!(out.ends_with("PROGRAM Other\n  ASSERT_TRUE(x, 'm');\nEND_PROGRAM\n"));
    }

    #[test]
    fn junit_escapes_and_counts() {
        let r = TestResult {
            test: TestDecl {
                name: "TEST_x".into(),
                file: "t.st".into(),
            },
            verdict: Verdict::Failed(vec![Failure {
                file: "t.st".into(),
                line: 3,
                msg: "a<b".into(),
                expected: "'x'".into(),
                actual: "&".into(),
            }]),
            cycles: 1,
            checks: 1,
            time_ns: 0,
        };
        let x = junit(&[r]);
        assert!(x.contains("tests=\"1\" failures=\"1\""), "{x}");
        assert!(
            x.contains("t.st:3: a&lt;b: expected &apos;x&apos;, actual &amp;"),
            "{x}"
        );
    }
}
