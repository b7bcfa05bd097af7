//! The incremental analysis of a language server gives exactly the
//! diagnostics of `stc check`, on every conformance case.
//!
//! For each `.st` file of `tests/conformance` (check and run cases), the
//! diagnostics (with their spans as file and offset, so that the prelude's
//! place in the position space does not matter) of:
//! - `stc_pipeline::analyse`, what `stc check` does (the prelude last);
//! - the case as the last file of an incremental parse (the prelude before
//!   it), analysed in two parts (the prelude, then the case), then again
//!   after an edit resuming from what the first analysis kept;
//! - the case as the first file, with a small second file edited after it,
//!   resumed from the case's checkpoint, the edit given each time.
//!
//! must be equal (with the lints at their default levels).

use std::path::{Path, PathBuf};

use stc_diagnostics::{Diagnostic, SourceMap, Span};
use stc_pipeline::incremental::{self, Made};
use stc_pipeline::Options;

fn cases(dir: &Path, out: &mut Vec<PathBuf>) {
    let Ok(rd) = std::fs::read_dir(dir) else {
        return;
    };
    let mut entries: Vec<PathBuf> = rd.filter_map(|e| e.ok().map(|e| e.path())).collect();
    entries.sort();
    for p in entries {
        if p.is_dir() {
            cases(&p, out);
        } else if p.extension().is_some_and(|e| e == "st") {
            out.push(p);
        }
    }
}

/// A span as (file name, offset in it, length).
fn place(sources: &SourceMap, s: Span) -> String {
    match sources.file_of(s.lo) {
        Some(f) => {
            let f = sources.file(f);
            format!("{}@{}+{}", f.name, s.lo - f.base, s.hi - s.lo)
        }
        None => format!("?{}+{}", s.lo, s.hi - s.lo),
    }
}

fn shown(sources: &SourceMap, ds: &[Diagnostic]) -> Vec<String> {
    let mut out: Vec<String> = ds
        .iter()
        .map(|d| {
            let secondary: Vec<String> = d
                .secondary
                .iter()
                .map(|l| format!("{} {}", place(sources, l.span), l.message))
                .collect();
            format!(
                "{} {:?} {} [{}] {:?} {:?} {:?} {:?}",
                d.code.as_str(),
                d.severity,
                place(sources, d.span),
                d.message,
                d.label,
                secondary,
                d.notes,
                d.help
            )
        })
        .collect();
    out.sort();
    out
}

fn options(text: &str) -> Options {
    Options {
        iec2: text.lines().take(3).any(|l| l.contains("--std iec2")),
    }
}

/// What `stc check` says of the files (the prelude appended).
fn whole(files: &[(String, String)], opts: &Options) -> Vec<String> {
    let files = files.to_vec();
    let opts = *opts;
    stc_pipeline::with_big_stack(move || {
        let mut sources = SourceMap::new();
        for (name, text) in files {
            let _ = sources.add(name, text);
        }
        let levels = stc_lint::Levels::default();
        let a = stc_pipeline::analyse_linted(sources, Vec::new(), &opts, Some(&levels));
        shown(&a.parsed.sources, &a.all_diagnostics())
    })
}

/// The incremental analyses of the files, the last one taking each text
/// of `edits` in turn: what each says, and how each was made.
fn incremental(
    files: &[(String, String)],
    edits: &[String],
    opts: &Options,
) -> Vec<(Vec<String>, Made)> {
    let files = files.to_vec();
    let edits = edits.to_vec();
    let opts = *opts;
    stc_pipeline::with_big_stack(move || {
        let levels = stc_lint::Levels::default();
        let last = files.last().map(|(n, _)| n.clone()).unwrap_or_default();
        let (parsed, mark) = incremental::parse_all(files, &opts);
        let (mut a, pending, mut kept, made) =
            incremental::check(parsed, mark, &opts, Some(&levels), None);
        stc_pipeline::lay_out(&mut a, pending);
        let mut out = vec![(shown(&a.parsed.sources, &a.all_diagnostics()), made)];
        let mut parsed = a.parsed;
        for text in edits {
            let p = incremental::reparse_last(parsed, mark, last.clone(), text, &opts);
            let (mut a, pending, k, made) = incremental::check(p, mark, &opts, Some(&levels), kept);
            stc_pipeline::lay_out(&mut a, pending);
            kept = k;
            out.push((shown(&a.parsed.sources, &a.all_diagnostics()), made));
            parsed = a.parsed;
        }
        out
    })
}

const EDITED_OK: &str = "PROGRAM EditedByTheTest\nVAR x : INT; END_VAR\nx := x + 1;\nEND_PROGRAM\n";
const EDITED_BAD: &str =
    "PROGRAM EditedByTheTest\nVAR x : INT; END_VAR\nx := 'text';\nEND_PROGRAM\n";

#[test]
fn the_incremental_analysis_is_stc_check_on_every_case() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../tests/conformance");
    let mut files = Vec::new();
    cases(&root, &mut files);
    assert!(
        files.len() > 100,
        "{} cases under {}",
        files.len(),
        root.display()
    );
    let mut resumed = 0;
    let mut total = 0;
    let mut wrong: Vec<String> = Vec::new();
    let mut check = |got: &Vec<String>, expected: &Vec<String>, what: String| {
        if got != expected {
            let only_got: Vec<&String> = got.iter().filter(|d| !expected.contains(d)).collect();
            let only_expected: Vec<&String> =
                expected.iter().filter(|d| !got.contains(d)).collect();
            wrong.push(format!(
                "{what}:\n  incremental only: {only_got:?}\n  stc check only: {only_expected:?}"
            ));
        }
    };
    for path in &files {
        // (A case that is not UTF-8 tests the loader, not the analysis.)
        let Ok(text) = std::fs::read_to_string(path) else {
            continue;
        };
        let name = path.display().to_string();
        let opts = options(&text);
        // The case as the edited file.
        let one = vec![(name.clone(), text.clone())];
        let expected = whole(&one, &opts);
        for (i, (got, made)) in incremental(&one, std::slice::from_ref(&text), &opts)
            .iter()
            .enumerate()
        {
            check(
                got,
                &expected,
                format!("{name}, the case last, analysis {i} ({made:?})"),
            );
            total += 1;
            resumed += usize::from(*made == Made::Resumed);
        }
        // The case first, another file edited after it.
        let two = |edited: &str| {
            vec![
                (name.clone(), text.clone()),
                ("edited.st".to_string(), edited.to_string()),
            ]
        };
        let edits = [EDITED_BAD.to_string(), EDITED_OK.to_string()];
        let runs = incremental(&two(EDITED_OK), &edits, &opts);
        for (i, (got, made)) in runs.iter().enumerate() {
            let edited = if i == 1 { EDITED_BAD } else { EDITED_OK };
            let expected = whole(&two(edited), &opts);
            check(
                got,
                &expected,
                format!("{name}, then an edited file, analysis {i} ({made:?})"),
            );
            total += 1;
            resumed += usize::from(*made == Made::Resumed);
        }
    }
    assert!(
        wrong.is_empty(),
        "{} differences:\n{}",
        wrong.len(),
        wrong.join("\n")
    );
    // Most analyses are resumed (the others are cases with errors whose
    // suggestions draw on every name, or that use namespaces).
    assert!(resumed * 10 >= total * 7, "{resumed} of {total} resumed");
    eprintln!("{resumed} of {total} analyses resumed");
}

/// The edits that could change what the other files mean: each gives the
/// whole analysis's diagnostics, and the analyses that must not resume do
/// not.
#[test]
fn edits_that_reach_the_other_files_give_the_whole_analysis() {
    const LIB: &str = "TYPE Mode : (Off, Auto); END_TYPE\n\
        VAR_GLOBAL g : INT; END_VAR\n\
        FUNCTION_BLOCK Base\nVAR_INPUT pulse : BOOL; END_VAR\nVAR_OUTPUT count : INT; END_VAR\n\
        VAR spare : INT; END_VAR\n\
        IF pulse THEN count := count + 1; END_IF;\nEND_FUNCTION_BLOCK\n\
        INTERFACE IRun\nMETHOD Run : INT\nEND_METHOD\nEND_INTERFACE\n\
        FUNCTION_BLOCK User\nVAR_INPUT r : IRun; END_VAR\nVAR_OUTPUT n : INT; END_VAR\n\
        n := r.Run();\nEND_FUNCTION_BLOCK\n\
        PROGRAM Lib\nVAR level : INT; m : Mode; b : Base; END_VAR\n\
        b(pulse := TRUE);\nlevel := b.count;\nm := Auto;\nlevel := level + 1;\nEND_PROGRAM\n";
    let program =
        |body: &str| format!("PROGRAM Edited\nVAR x : INT; END_VAR\n{body}\nEND_PROGRAM\n");
    // (the last file's text, whether it may resume)
    let edits: Vec<(String, bool)> = vec![
        (program("x := x + 1;"), true),
        // Uses of the library: resumed.
        (program("x := Lib.level;"), true),
        (
            "PROGRAM Edited\nVAR b : Base; y : INT; END_VAR\nb(pulse := FALSE);\ny := b.count;\nEND_PROGRAM\n"
                .into(),
            true,
        ),
        // An error in the last file only: resumed.
        (program("x := 'text';"), true),
        (program("x := undeclared;"), true),
        // A block extending the library's: its unused VAR is no more.
        (
            "FUNCTION_BLOCK Derived EXTENDS Base\nVAR_OUTPUT twice : INT; END_VAR\n\
             twice := count * 2 + spare;\nEND_FUNCTION_BLOCK\n"
                .into(),
            false,
        ),
        // A class implementing the library's interface: a call may reach it.
        (
            "FUNCTION_BLOCK Runner IMPLEMENTS IRun\nMETHOD Run : INT\nRun := 1;\nEND_METHOD\n\
             END_FUNCTION_BLOCK\n"
                .into(),
            false,
        ),
        // Names the library uses, declared again.
        ("TYPE Mode : (Manual, Auto); END_TYPE\n".into(), false),
        ("TYPE Other : (Auto, Off); END_TYPE\n".into(), false),
        ("VAR_GLOBAL level : INT; END_VAR\n".into(), false),
        ("FUNCTION_BLOCK Base\nEND_FUNCTION_BLOCK\n".into(), false),
        // A name the prelude declares.
        ("FUNCTION_BLOCK TON\nEND_FUNCTION_BLOCK\n".into(), false),
        // A reference to a name the library's bodies use.
        (
            "PROGRAM Edited\nVAR level : INT; r : REF_TO INT; END_VAR\nr := REF(level);\nEND_PROGRAM\n"
                .into(),
            false,
        ),
        // Back to a plain edit: resumed again.
        (program("x := x + 2;"), true),
        // Spelled otherwise than before.
        (program("X := X + 2;"), true),
    ];
    let opts = Options::default();
    let first = vec![
        ("lib.st".to_string(), LIB.to_string()),
        ("edited.st".to_string(), edits[0].0.clone()),
    ];
    let texts: Vec<String> = edits.iter().map(|(t, _)| t.clone()).collect();
    let runs = incremental(&first, &texts, &opts);
    for (i, (got, made)) in runs.iter().enumerate().skip(1) {
        let (text, may_resume) = &edits[i - 1];
        let files = vec![
            ("lib.st".to_string(), LIB.to_string()),
            ("edited.st".to_string(), text.clone()),
        ];
        assert_eq!(got, &whole(&files, &opts), "edit {}: {text}", i - 1);
        assert_eq!(
            *made == Made::Resumed,
            *may_resume,
            "edit {}: {text}",
            i - 1
        );
    }
}

/// A first part whose errors draw their suggestions from every global
/// name keeps no checkpoint: the last file could declare a better one.
#[test]
fn errors_suggesting_global_names_keep_nothing() {
    let lib = "PROGRAM Lib\nVAR t : Motr; END_VAR\nEND_PROGRAM\n".to_string();
    let opts = Options::default();
    for edited in [
        "FUNCTION_BLOCK Motor\nEND_FUNCTION_BLOCK\n",
        "FUNCTION_BLOCK Motors\nEND_FUNCTION_BLOCK\n",
    ] {
        let files = vec![
            ("lib.st".to_string(), lib.clone()),
            ("edited.st".to_string(), edited.to_string()),
        ];
        let runs = incremental(&files, &[edited.to_string()], &opts);
        for (got, made) in &runs {
            assert_eq!(got, &whole(&files, &opts), "{edited}");
            assert_eq!(*made, Made::Whole);
        }
    }
}
