//! Shared pieces of the data-driven test harnesses: locating the test data
//! and comparing the diagnostics a case produces with its `//~` annotations
//! (docs/testing.md).

#![allow(dead_code)]

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use stc::driver::{self, Options};
use stc_diagnostics::{Diagnostic, SourceMap};

/// The repository's `tests/` folder.
pub fn data_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../tests")
}

/// Every test case below `dir`: `.st` files, and `.project` folders as one
/// case each. Sorted, so failures are reported in a stable order.
pub fn cases(dir: &Path) -> Vec<PathBuf> {
    let mut out = Vec::new();
    collect(dir, &mut out);
    out.sort();
    out
}

fn collect(dir: &Path, out: &mut Vec<PathBuf>) {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return;
    };
    for e in entries.flatten() {
        let p = e.path();
        if p.is_dir() {
            if p.extension().is_some_and(|x| x == "project") {
                out.push(p);
            } else if p.file_name().is_some_and(|n| n != "snapshots") {
                collect(&p, out);
            }
        } else if p.extension().is_some_and(|x| x == "st" || x == "il") {
            out.push(p);
        }
    }
}

/// The source files of a case.
pub fn case_files(case: &Path) -> Vec<PathBuf> {
    if case.is_dir() {
        let mut files: Vec<PathBuf> = std::fs::read_dir(case)
            .unwrap()
            .flatten()
            .map(|e| e.path())
            .filter(|p| p.extension().is_some_and(|x| x == "st" || x == "il"))
            .collect();
        files.sort();
        files
    } else {
        vec![case.to_path_buf()]
    }
}

/// (file name, line, code) of each annotation; `file name` is the file's
/// path as loaded.
pub type Key = (String, u32, String);

/// The `//~ CODE` annotations of one file's text.
pub fn annotations(file: &str, text: &str) -> Vec<Key> {
    let mut out = Vec::new();
    for (i, line) in text.lines().enumerate() {
        let mut rest = line;
        while let Some(p) = rest.find("//~") {
            let after = &rest[p + 3..];
            let up = after.chars().take_while(|&c| c == '^').count();
            for word in after[up..].split_whitespace() {
                let is_code = word.len() == 5
                    && (word.starts_with('E') || word.starts_with('W') || word.starts_with('L'))
                    && word[1..].bytes().all(|b| b.is_ascii_digit());
                if !is_code {
                    break;
                }
                let line_no = (i + 1).saturating_sub(up) as u32;
                out.push((file.to_string(), line_no, word.to_string()));
            }
            rest = after;
        }
    }
    out
}

/// The (file, line, code) of each diagnostic.
pub fn diagnostic_keys(diags: &[Diagnostic], sm: &SourceMap) -> Vec<Key> {
    diags
        .iter()
        .map(|d| {
            let (file, line) = match sm.locate(d.span.lo) {
                Some((f, lc)) => (f.name.clone(), lc.line),
                None => (String::new(), 0),
            };
            (file, line, d.code.as_str().to_string())
        })
        .collect()
}

fn count(keys: Vec<Key>) -> BTreeMap<Key, i32> {
    let mut m = BTreeMap::new();
    for k in keys {
        *m.entry(k).or_insert(0) += 1;
    }
    m
}

/// Compares diagnostics with annotations; `Err` describes the differences.
pub fn compare(diags: &[Diagnostic], sm: &SourceMap) -> Result<(), String> {
    let mut expected = Vec::new();
    for (_, f) in sm.files() {
        expected.extend(annotations(&f.name, &f.text));
    }
    let expected = count(expected);
    let actual = count(diagnostic_keys(diags, sm));
    if expected == actual {
        return Ok(());
    }
    let mut msg = String::new();
    for (k, n) in &expected {
        let got = actual.get(k).copied().unwrap_or(0);
        if got < *n {
            msg.push_str(&format!(
                "  missing: {} at {}:{} ({}x)\n",
                k.2,
                k.0,
                k.1,
                n - got
            ));
        }
    }
    for (k, n) in &actual {
        let want = expected.get(k).copied().unwrap_or(0);
        if *n > want {
            msg.push_str(&format!(
                "  unexpected: {} at {}:{} ({}x)\n",
                k.2,
                k.0,
                k.1,
                n - want
            ));
        }
    }
    msg.push_str("  diagnostics produced:\n");
    let rendered = driver::render(diags, sm, &Options::default());
    for l in rendered.lines() {
        msg.push_str("    ");
        msg.push_str(l);
        msg.push('\n');
    }
    Err(msg)
}

/// Runs `check` over every case of a folder and reports all failures at once.
pub fn run_all(dir: &Path, mut check: impl FnMut(&Path) -> Result<(), String>) {
    let cases = cases(dir);
    assert!(!cases.is_empty(), "no test cases in {}", dir.display());
    let mut failures = Vec::new();
    for case in &cases {
        let result = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| check(case)));
        match result {
            Ok(Ok(())) => {}
            Ok(Err(msg)) => failures.push(format!("{}:\n{msg}", case.display())),
            Err(_) => failures.push(format!("{}: PANIC", case.display())),
        }
    }
    if !failures.is_empty() {
        panic!(
            "{} of {} cases failed:\n\n{}",
            failures.len(),
            cases.len(),
            failures.join("\n")
        );
    }
}

/// `--stimulus FILE` names a file beside the test file.
pub fn with_stimulus_beside(words: Vec<String>, dir: &Path) -> Vec<String> {
    let mut out = Vec::with_capacity(words.len());
    let mut it = words.into_iter();
    while let Some(w) = it.next() {
        if w == "--stimulus" {
            out.push(w);
            if let Some(f) = it.next() {
                out.push(dir.join(f).display().to_string());
            }
        } else if let Some(f) = w.strip_prefix("--stimulus=") {
            out.push(format!("--stimulus={}", dir.join(f).display()));
        } else {
            out.push(w);
        }
    }
    out
}

/// The options of a case's `// run:` line, split as a shell would, with
/// stimulus files made absolute; `None` when it has no such line.
pub fn run_options(case: &Path) -> Result<Option<Vec<String>>, String> {
    for file in case_files(case) {
        let text = std::fs::read_to_string(&file)
            .map_err(|e| format!("cannot read {}: {e}", file.display()))?;
        let dir = file.parent().unwrap_or(Path::new(".")).to_path_buf();
        for line in text.lines() {
            if let Some(rest) = line.trim().strip_prefix("// run:") {
                let words = shlex::split(rest)
                    .ok_or_else(|| format!("{}: unbalanced quotes in `// run:`", file.display()))?;
                return Ok(Some(with_stimulus_beside(words, &dir)));
            }
        }
    }
    Ok(None)
}

/// The fault lines of a run's stderr (with the note of their values) as
/// two back ends must agree on them. A watchdog fault is compared without
/// its position: the VM counts instructions, the JIT and C loop iterations
/// and calls, so they run out at different points of the same loop
/// (docs/runtime.md).
pub fn fault_lines(stderr: &str) -> Vec<String> {
    stderr
        .lines()
        .filter(|l| l.starts_with("fault:") || l.starts_with("note:"))
        .map(|l| match l.split_once(" at ") {
            Some((head, _)) if l.starts_with("fault: watchdog") => head.to_string(),
            _ => l.to_string(),
        })
        .collect()
}

/// A run's stdout as two back ends must agree on it: the same, but for
/// the position in a watchdog fault's JSON object (see [`fault_lines`]).
pub fn comparable_reports(stdout: &str) -> String {
    let mut out = String::with_capacity(stdout.len());
    for l in stdout.lines() {
        match l.strip_prefix("{\"fault\":{\"kind\":\"watchdog\"") {
            Some(rest) => {
                let cut = rest.find(",\"line\":").unwrap_or(rest.len());
                out.push_str("{\"fault\":{\"kind\":\"watchdog\"");
                out.push_str(&rest[..cut]);
            }
            None => out.push_str(l),
        }
        out.push('\n');
    }
    out
}
