//! What the command says around the diagnostics and reports: the summary
//! line, the cap on errors per file, and the warnings of `stc run` about
//! its options.

use std::path::PathBuf;

fn write(name: &str, text: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("stc-messages-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    let path = dir.join(name);
    std::fs::write(&path, text).expect("written");
    path
}

fn run(args: &[&str]) -> stc::cli::Outcome {
    let mut all = vec!["stc"];
    all.extend_from_slice(args);
    stc::cli::run_args(&all)
}

#[test]
fn the_human_format_ends_with_a_summary_line() {
    let p = write(
        "two.st",
        "PROGRAM P\n VAR x : INT; b : BOOL; u : INT; END_VAR\n x := b;\n x := TRUE;\nEND_PROGRAM\n",
    );
    let out = run(&["check", p.to_str().unwrap()]);
    let last = out.stderr.lines().last().unwrap_or_default();
    assert!(
        last.ends_with(" errors") || last.contains("errors, "),
        "{}",
        out.stderr
    );
    let json = run(&["check", "--message-format", "json", p.to_str().unwrap()]);
    assert!(
        json.stderr.lines().all(|l| l.starts_with('{')),
        "JSON has no summary line: {}",
        json.stderr
    );
}

#[test]
fn a_file_that_is_not_st_shows_at_most_fifty_errors() {
    let text: String = (0..400)
        .map(|i| format!("  mov8 @{i}, #{i} ; §\n"))
        .collect();
    let p = write("listing.vmasm.st", &text);
    let out = run(&["check", p.to_str().unwrap()]);
    let shown = out.stderr.matches(": error[").count();
    assert!(shown <= 50, "{shown} errors shown");
    let more = out
        .stderr
        .lines()
        .find(|l| l.starts_with("... and "))
        .unwrap_or_else(|| panic!("no count of the errors not shown:\n{}", out.stderr));
    assert!(more.ends_with("not shown"), "{more}");
    let hidden: usize = more
        .trim_start_matches("... and ")
        .split(' ')
        .next()
        .and_then(|n| n.parse().ok())
        .expect("a count");
    let total: usize = out
        .stderr
        .lines()
        .last()
        .and_then(|l| l.split(' ').next())
        .and_then(|n| n.parse().ok())
        .expect("the summary's count");
    assert_eq!(shown + hidden, total, "{}", out.stderr);
}

#[test]
fn a_tick_that_does_not_divide_a_task_interval_is_a_warning() {
    let p = write(
        "tasks.st",
        "PROGRAM Main VAR n : INT; END_VAR n := n + 1; END_PROGRAM\n\
         CONFIGURATION C RESOURCE R ON PLC\n\
         TASK t (INTERVAL := T#15ms, PRIORITY := 1);\n\
         PROGRAM m WITH t : Main;\n\
         END_RESOURCE END_CONFIGURATION\n",
    );
    let out = run(&[
        "run",
        p.to_str().unwrap(),
        "--tick",
        "10ms",
        "--cycles",
        "4",
    ]);
    assert_eq!(out.status, 0, "{}", out.stderr);
    assert!(
        out.stderr.contains(
            "warning: task `t` has INTERVAL T#15ms, which the tick T#10ms does not divide: it runs every T#30ms"
        ),
        "{}",
        out.stderr
    );
    let fine = run(&["run", p.to_str().unwrap(), "--tick", "5ms"]);
    assert!(!fine.stderr.contains("warning"), "{}", fine.stderr);
}

#[test]
fn help_is_given_where_a_person_needs_it() {
    let p = write(
        "help.st",
        "PROGRAM P\nVAR r : REAL; c : CTU; t : TON; END_VAR\n\
         r := LIMIT(0.0, r);\n\
         c(CU := TRUE, RESET := FALSE, PV := 3);\n\
         t(IN := TRUE, PT := 1000);\n\
         t(IN := TRUE, PT := 250);\nEND_PROGRAM\n",
    );
    let out = run(&["check", p.to_str().unwrap()]);
    for want in [
        "error[E0410]: `LIMIT` needs the input(s) MX",
        "= note: the parameters of `CTU` are CU, R, PV, Q, CV, EN, ENO",
        "= help: did you mean `R`?",
        "= help: a duration is written as a time literal: `T#1s` if 1000 means milliseconds",
        "= help: a duration is written as a time literal: `T#250ms` if 250 means milliseconds",
    ] {
        assert!(out.stderr.contains(want), "no `{want}` in:\n{}", out.stderr);
    }
}

#[test]
fn reports_as_csv_and_stimulus_rows_by_time() {
    let p = write(
        "csv.st",
        "PROGRAM Main VAR_INPUT k : INT; END_VAR VAR_OUTPUT n : INT; s : STRING := 'a,\"b'; END_VAR n := n + k; END_PROGRAM\n",
    );
    let st = write("csv_stim.csv", "time,Main.k\nT#0s,1\nT#20ms,10\n");
    let out = run(&[
        "run",
        p.to_str().unwrap(),
        "--cycles",
        "4",
        "--tick",
        "10ms",
        "--trace",
        "--format",
        "csv",
        "--stimulus",
        st.to_str().unwrap(),
    ]);
    assert_eq!(out.status, 0, "{}", out.stderr);
    assert_eq!(
        out.stdout,
        "cycle,time,Main.n,Main.s\n\
         1,T#0s,1,\"a,\"\"b\"\n\
         2,T#10ms,2,\"a,\"\"b\"\n\
         3,T#20ms,12,\"a,\"\"b\"\n\
         4,T#30ms,22,\"a,\"\"b\"\n"
    );
    let off = run(&[
        "run",
        p.to_str().unwrap(),
        "--tick",
        "15ms",
        "--stimulus",
        st.to_str().unwrap(),
    ]);
    assert_eq!(off.status, 2, "{}", off.stderr);
    assert!(
        off.stderr
            .contains("T#20ms is not the time of a cycle with a tick of T#15ms"),
        "{}",
        off.stderr
    );
}

#[test]
fn vmasm_text_runs_as_its_program_does() {
    let root = std::path::Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../.."));
    let src = root.join("examples/traffic_light.st");
    let asm = std::env::temp_dir().join(format!("stc-messages-{}.vmasm", std::process::id()));
    let built = run(&[
        "build",
        "--emit",
        "vmasm",
        src.to_str().unwrap(),
        "-o",
        asm.to_str().unwrap(),
    ]);
    assert_eq!(built.status, 0, "{}", built.stderr);
    let direct = run(&["run", src.to_str().unwrap(), "--cycles", "40", "--trace"]);
    let assembled = run(&["run", asm.to_str().unwrap(), "--cycles", "40", "--trace"]);
    assert_eq!(assembled.status, 0, "{}", assembled.stderr);
    assert_eq!(assembled.stdout, direct.stdout);
    let broken = write(
        "broken.vmasm",
        "  mov8 @1, #2\n  bogus 1 2 3\n.tables\nnot a table\n",
    );
    let out = run(&["run", broken.to_str().unwrap()]);
    assert_eq!(out.status, 2, "{}", out.stderr);
    assert!(
        out.stderr.starts_with("error: cannot load "),
        "{}",
        out.stderr
    );
}
