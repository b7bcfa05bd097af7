//! The run conformance suite (docs/testing.md): every case of
//! `tests/conformance/run`, and every example with `// run:` directives, is
//! run through `stc run` in-process (`stc::cli::run_args`, the same path as
//! the command) with `--format json`, and the values of its `// expect:`
//! lines are compared with the reports, as JSON values (numbers by value).
//! A case with `// expect-fault: KIND @ LINE[:COL] [in INSTANCE (POU)]`
//! must stop with exit status 3 and that fault (on stderr, and as the JSON
//! object of the last stdout line), its `expect:` lines then being checked
//! against the report of the last completed cycle.

mod common;

use std::path::{Path, PathBuf};

use serde_json::Value;

/// A fault: expected, or as `stc run` reported it.
#[derive(Debug, PartialEq, Eq)]
struct Fault {
    kind: String,
    line: u32,
    /// Not checked when the expectation leaves it out.
    col: Option<u32>,
    /// `INSTANCE (POU)`; not checked when the expectation leaves it out.
    place: Option<String>,
}

impl Fault {
    /// Whether the reported fault `got` is this expected one.
    fn matches(&self, got: &Fault) -> bool {
        self.kind == got.kind
            && self.line == got.line
            && self.col.is_none_or(|c| got.col == Some(c))
            && self
                .place
                .as_ref()
                .is_none_or(|p| got.place.as_ref() == Some(p))
    }
}

impl std::fmt::Display for Fault {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "`{}` at line {}", self.kind, self.line)?;
        if let Some(c) = self.col {
            write!(f, ":{c}")?;
        }
        if let Some(p) = &self.place {
            write!(f, " in {p}")?;
        }
        Ok(())
    }
}

/// `KIND @ LINE[:COL] [in INSTANCE (POU)]`.
fn parse_expected_fault(text: &str) -> Option<Fault> {
    let (kind, rest) = text.split_once('@')?;
    let rest = rest.trim();
    let (at, place) = match rest.split_once(" in ") {
        Some((a, p)) => (a.trim(), Some(p.trim().to_string())),
        None => (rest, None),
    };
    let (line, col) = match at.split_once(':') {
        Some((l, c)) => (l.trim().parse().ok()?, Some(c.trim().parse().ok()?)),
        None => (at.parse().ok()?, None),
    };
    Some(Fault {
        kind: kind.trim().to_string(),
        line,
        col,
        place,
    })
}

/// One `// expect:` or `// expect @K:` line.
struct Expect {
    /// `None`: after the last cycle.
    cycle: Option<u64>,
    path: String,
    value: Value,
    /// Where it is written, for messages.
    line: String,
}

/// What a case's directives ask for.
struct Directives {
    /// The `// run:` options, split as a shell would.
    options: Vec<String>,
    expects: Vec<Expect>,
    /// `// expect-fault: KIND @ LINE[:COL] [in INSTANCE (POU)]`.
    fault: Option<Fault>,
    /// `// expect-fault-details: {JSON}`: the fault object's `details`.
    fault_details: Option<Value>,
    has_run_line: bool,
}

fn directives(case: &Path) -> Result<Directives, String> {
    let mut d = Directives {
        options: Vec::new(),
        expects: Vec::new(),
        fault: None,
        fault_details: None,
        has_run_line: false,
    };
    for file in common::case_files(case) {
        let text = std::fs::read_to_string(&file)
            .map_err(|e| format!("cannot read {}: {e}", file.display()))?;
        let dir = file.parent().unwrap_or(Path::new(".")).to_path_buf();
        let name = file
            .file_name()
            .unwrap_or_default()
            .to_string_lossy()
            .into_owned();
        for (i, raw) in text.lines().enumerate() {
            let line = raw.trim();
            let at = format!("{name}:{}", i + 1);
            if let Some(rest) = line.strip_prefix("// run:") {
                if d.has_run_line {
                    return Err(format!("{at}: a second `// run:` line"));
                }
                d.has_run_line = true;
                let words = shlex::split(rest)
                    .ok_or_else(|| format!("{at}: unbalanced quotes in `// run:`"))?;
                d.options = common::with_stimulus_beside(words, &dir);
            } else if let Some(rest) = line.strip_prefix("// expect-fault-details:") {
                d.fault_details = Some(serde_json::from_str(rest.trim()).map_err(|e| {
                    format!("{at}: `// expect-fault-details:` takes a JSON object ({e})")
                })?);
            } else if let Some(rest) = line.strip_prefix("// expect-fault:") {
                d.fault = Some(parse_expected_fault(rest).ok_or_else(|| {
                    format!(
                        "{at}: expected `// expect-fault: KIND @ LINE[:COL] [in INSTANCE (POU)]`"
                    )
                })?);
            } else if let Some(rest) = line.strip_prefix("// expect") {
                let (cycle, rest) = match rest.trim_start().strip_prefix('@') {
                    Some(r) => {
                        let (k, r) = r.split_once(':').ok_or_else(|| {
                            format!("{at}: expected `// expect @K: PATH = VALUE`")
                        })?;
                        let k = k
                            .trim()
                            .parse()
                            .map_err(|_| format!("{at}: `{}` is not a cycle number", k.trim()))?;
                        (Some(k), r)
                    }
                    None => match rest.strip_prefix(':') {
                        Some(r) => (None, r),
                        // Another word, such as a comment "// expected ...".
                        None => continue,
                    },
                };
                let (path, value) = rest
                    .split_once('=')
                    .ok_or_else(|| format!("{at}: expected `PATH = VALUE`"))?;
                let value = serde_json::from_str(value.trim())
                    .map_err(|e| format!("{at}: the value `{}` is not JSON: {e}", value.trim()))?;
                d.expects.push(Expect {
                    cycle,
                    path: path.trim().to_string(),
                    value,
                    line: format!("{at}: {line}"),
                });
            }
        }
    }
    Ok(d)
}

/// JSON equality with numbers compared by value (`1.0` equals `1`).
fn same(a: &Value, b: &Value) -> bool {
    match (a, b) {
        (Value::Number(x), Value::Number(y)) => match (x.as_i128(), y.as_i128()) {
            (Some(i), Some(j)) => i == j,
            _ => x.as_f64() == y.as_f64(),
        },
        (Value::Array(x), Value::Array(y)) => {
            x.len() == y.len() && x.iter().zip(y).all(|(a, b)| same(a, b))
        }
        (Value::Object(x), Value::Object(y)) => {
            x.len() == y.len() && x.iter().all(|(k, v)| y.get(k).is_some_and(|w| same(v, w)))
        }
        _ => a == b,
    }
}

/// The value of a path in a report's `values`, matched case-insensitively.
fn lookup<'r>(report: &'r Value, path: &str) -> Option<&'r Value> {
    let wanted: String = path.chars().filter(|c| !c.is_whitespace()).collect();
    report
        .get("values")?
        .as_object()?
        .iter()
        .find(|(k, _)| k.eq_ignore_ascii_case(&wanted))
        .map(|(_, v)| v)
}

/// `fault: KIND in INSTANCE (POU) at FILE:LINE:COL`.
fn fault_line(stderr: &str) -> Option<Fault> {
    let l = stderr.lines().find_map(|l| l.strip_prefix("fault: "))?;
    let (kind, rest) = l.split_once(" in ")?;
    let (place, at) = rest.rsplit_once(" at ")?;
    let mut parts = at.rsplitn(3, ':');
    let col = parts.next()?.parse().ok()?;
    let line = parts.next()?.parse().ok()?;
    Some(Fault {
        kind: kind.to_string(),
        line,
        col: Some(col),
        place: Some(place.to_string()),
    })
}

/// The JSON fault object (`{"fault":{...}}`) as a [`Fault`].
fn fault_object(v: &Value) -> Option<Fault> {
    let f = v.get("fault")?;
    Some(Fault {
        kind: f.get("kind")?.as_str()?.to_string(),
        line: u32::try_from(f.get("line")?.as_u64()?).ok()?,
        col: Some(u32::try_from(f.get("column")?.as_u64()?).ok()?),
        place: Some(format!(
            "{} ({})",
            f.get("instance")?.as_str()?,
            f.get("pou")?.as_str()?
        )),
    })
    .filter(|_| f.get("details").is_some_and(Value::is_object))
}

fn run_case(case: &Path) -> Result<(), String> {
    let d = directives(case)?;
    let files: Vec<PathBuf> = common::case_files(case);
    let mut args: Vec<String> = vec!["stc".into(), "run".into()];
    args.extend(files.iter().map(|f| f.display().to_string()));
    if d.has_run_line {
        args.extend(d.options.iter().cloned());
    } else {
        args.extend(["--cycles".to_string(), "1".to_string()]);
    }
    args.extend(["--format".to_string(), "json".to_string()]);
    if !d.expects.is_empty() {
        let paths: Vec<&str> = d.expects.iter().map(|e| e.path.as_str()).collect();
        args.push("--watch".into());
        args.push(paths.join(","));
    }
    if d.expects.iter().any(|e| e.cycle.is_some()) {
        args.push("--trace".into());
    }
    let argv: Vec<&str> = args.iter().map(|s| s.as_str()).collect();
    let out = stc::cli::run_args(&argv);

    let mut problems = Vec::new();
    let mut stdout_lines: Vec<&str> = out.stdout.lines().collect();
    match &d.fault {
        Some(want) => {
            if out.status != 3 {
                problems.push(format!(
                    "expected a fault ({want}), got exit status {}",
                    out.status
                ));
            } else {
                let text = fault_line(&out.stderr);
                match &text {
                    Some(got) if want.matches(got) => {}
                    Some(got) => problems.push(format!("expected the fault {want}, got {got}")),
                    None => problems.push("exit status 3 but no `fault:` line".into()),
                }
                // The JSON object, last on stdout, says the same.
                let last = stdout_lines
                    .pop()
                    .and_then(|l| serde_json::from_str::<Value>(l).ok());
                if let Some(want) = &d.fault_details {
                    let got = last.as_ref().and_then(|v| v.get("fault")?.get("details"));
                    if got != Some(want) {
                        problems.push(format!("expected the fault's details {want}, got {got:?}"));
                    }
                }
                let object = last.as_ref().and_then(fault_object);
                if object.is_none() || object != text {
                    problems.push(format!(
                        "the last stdout line is not the fault's JSON object ({object:?} vs {text:?})"
                    ));
                }
            }
        }
        None if out.status != 0 => {
            problems.push(format!("exit status {}", out.status));
        }
        None => {}
    }

    let mut reports = Vec::new();
    for l in stdout_lines {
        match serde_json::from_str::<Value>(l) {
            Ok(v) => reports.push(v),
            Err(e) => problems.push(format!("a report line is not JSON ({e}): {l}")),
        }
    }
    for e in &d.expects {
        let report = match e.cycle {
            None => reports.last(),
            Some(k) => reports
                .iter()
                .find(|r| r.get("cycle").and_then(Value::as_u64) == Some(k)),
        };
        let Some(report) = report else {
            problems.push(format!("{}\n      no report for that cycle", e.line));
            continue;
        };
        match lookup(report, &e.path) {
            Some(v) if same(v, &e.value) => {}
            Some(v) => problems.push(format!("{}\n      got {v}", e.line)),
            None => problems.push(format!(
                "{}\n      `{}` is not in the report",
                e.line, e.path
            )),
        }
    }
    if problems.is_empty() {
        return Ok(());
    }
    let mut msg = String::new();
    for p in &problems {
        msg.push_str(&format!("  {p}\n"));
    }
    msg.push_str(&format!("  command: {}\n", args[1..].join(" ")));
    for l in out.stderr.lines().take(20) {
        msg.push_str(&format!("  stderr: {l}\n"));
    }
    Err(msg)
}

#[test]
fn run_cases_give_their_expected_values() {
    common::run_all(&common::data_dir().join("conformance/run"), run_case);
}

#[test]
fn examples_run_as_their_directives_say() {
    common::run_all(
        &common::data_dir().join("../examples"),
        |case| match directives(case)?.has_run_line {
            true => run_case(case),
            false => Ok(()),
        },
    );
}

#[test]
fn directives_are_read_like_a_shell_would() {
    let dir = std::env::temp_dir().join(format!("stc-run-directives-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("case.st");
    std::fs::write(
        &file,
        "// run: --cycles 3 --set \"Main.s='a b'\" --stimulus in.csv\n\
         // expect: Main.x = 1.5\n\
         // expect @2: Main.s = \"a=b\"\n\
         // expected values above\n\
         // expect-fault: division by zero @ 12\n",
    )
    .unwrap();
    let d = directives(&file).unwrap();
    std::fs::remove_dir_all(&dir).unwrap();
    assert_eq!(
        d.options,
        [
            "--cycles".to_string(),
            "3".into(),
            "--set".into(),
            "Main.s='a b'".into(),
            "--stimulus".into(),
            dir.join("in.csv").display().to_string(),
        ]
    );
    let e: Vec<(Option<u64>, &str, String)> = d
        .expects
        .iter()
        .map(|e| (e.cycle, e.path.as_str(), e.value.to_string()))
        .collect();
    assert_eq!(
        e,
        [
            (None, "Main.x", "1.5".to_string()),
            (Some(2), "Main.s", "\"a=b\"".to_string())
        ]
    );
    assert_eq!(
        d.fault,
        Some(Fault {
            kind: "division by zero".into(),
            line: 12,
            col: None,
            place: None
        })
    );
    assert_eq!(
        parse_expected_fault(" subrange violation @ 7:12 in Main.fbs[2] (Scale)"),
        Some(Fault {
            kind: "subrange violation".into(),
            line: 7,
            col: Some(12),
            place: Some("Main.fbs[2] (Scale)".into())
        })
    );
    assert!(same(&serde_json::json!(1.0), &serde_json::json!(1)));
    assert!(same(
        &serde_json::json!({"a": [1, 2.5]}),
        &serde_json::json!({"a": [1.0, 2.5]})
    ));
    assert!(!same(&serde_json::json!("1"), &serde_json::json!(1)));
    assert_eq!(
        fault_line("fault: MUX selector out of range in Main (Main) at dir/a b.st:13:5\n"),
        Some(Fault {
            kind: "MUX selector out of range".into(),
            line: 13,
            col: Some(5),
            place: Some("Main (Main)".into())
        })
    );
}

/// A scratch folder with the given files, removed when dropped.
struct Scratch(PathBuf);

impl Scratch {
    fn new(name: &str, files: &[(&str, &str)]) -> Scratch {
        let dir = std::env::temp_dir().join(format!("stc-run-{name}-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        for (f, text) in files {
            std::fs::write(dir.join(f), text).unwrap();
        }
        Scratch(dir)
    }

    fn path(&self, f: &str) -> String {
        self.0.join(f).display().to_string()
    }
}

impl Drop for Scratch {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

const COUNTER: &str = "\
PROGRAM Main
VAR_INPUT
  step : INT := 1;
END_VAR
VAR_OUTPUT
  count : INT;
  ratio : INT;
END_VAR
VAR
  name : STRING[8] := 'abc';
  lights : ARRAY[1..2] OF BOOL;
END_VAR
lights[2] := name = 'x';
count := count + step;
ratio := 100 / (3 - count);
END_PROGRAM
";

fn stc(args: &[&str]) -> stc::cli::Outcome {
    let mut all = vec!["stc", "run"];
    all.extend_from_slice(args);
    stc::cli::run_args(&all)
}

#[test]
fn reports_in_text_and_json() {
    let s = Scratch::new("formats", &[("main.st", COUNTER)]);
    let f = s.path("main.st");
    let out = stc(&[
        &f,
        "--cycles",
        "2",
        "--trace",
        "--watch",
        "Main.count,MAIN.NAME",
        "--watch",
        "main.lights",
    ]);
    assert_eq!(out.status, 0, "{}", out.stderr);
    assert_eq!(
        out.stdout,
        "cycle 1 (T#0s)\n  Main.count  = 1\n  Main.name   = 'abc'\n  Main.lights = [FALSE, FALSE]\n\
         cycle 2 (T#10ms)\n  Main.count  = 2\n  Main.name   = 'abc'\n  Main.lights = [FALSE, FALSE]\n"
    );
    let out = stc(&[
        &f,
        "--format",
        "json",
        "--set",
        "Main.step=-1",
        "--set",
        "Main.name='x y'",
    ]);
    assert_eq!(out.status, 0, "{}", out.stderr);
    assert_eq!(
        out.stdout,
        "{\"cycle\":1,\"time\":\"T#0s\",\"values\":{\"Main.count\":-1,\"Main.ratio\":25}}\n"
    );
}

#[test]
fn a_fault_exits_3_with_the_last_completed_cycle() {
    let s = Scratch::new("fault", &[("main.st", COUNTER)]);
    let f = s.path("main.st");
    let out = stc(&[
        &f,
        "--cycles",
        "5",
        "--format",
        "json",
        "--watch",
        "Main.count",
    ]);
    assert_eq!(out.status, 3);
    assert_eq!(
        out.stdout,
        format!(
            "{{\"cycle\":2,\"time\":\"T#10ms\",\"values\":{{\"Main.count\":2}}}}\n\
             {{\"fault\":{{\"kind\":\"division by zero\",\"instance\":\"Main\",\"pou\":\"Main\",\
             \"file\":\"{f}\",\"line\":15,\"column\":14,\"details\":{{\"divisor\":0}}}}}}\n"
        )
    );
    assert_eq!(
        out.stderr,
        format!("fault: division by zero in Main (Main) at {f}:15:14\nnote: the divisor is 0\n")
    );
}

#[test]
fn usage_errors_exit_2_with_a_message() {
    let s = Scratch::new(
        "usage",
        &[
            ("main.st", COUNTER),
            ("bad.csv", "cycle,Main.count\n1,abc\n"),
            (
                "bad.st",
                "PROGRAM P\nVAR x : INT; END_VAR\nx := TRUE;\nEND_PROGRAM\n",
            ),
        ],
    );
    let f = s.path("main.st");
    let err = |args: &[&str]| {
        let out = stc(args);
        (out.status, out.stderr)
    };
    assert_eq!(
        err(&[&f, "--watch", "Main.nothing"]),
        (
            2,
            "error: unknown variable `Main.nothing`: `Main` has no member `nothing`\n".into()
        )
    );
    assert_eq!(
        err(&[&f, "--stimulus", &s.path("bad.csv")]),
        (
            2,
            format!(
                "error: {}:2: Main.count: `abc` cannot be read as INT (expected an ST literal within the type's range)\n",
                s.path("bad.csv")
            )
        )
    );
    assert_eq!(
        err(&[&f, "--tick", "fast"]),
        (
            2,
            "error: --tick fast: expected a duration such as 10ms or T#10ms\n".into()
        )
    );
    assert_eq!(
        err(&[&f, "--program", "Pump"]),
        (
            2,
            "error: no program type `Pump`: the programs are Main\n".into()
        )
    );
    assert_eq!(err(&[&f, "--cycles", "-1"]).0, 2);
    assert_eq!(err(&[&s.path("bad.st")]).0, 1);
    let (status, stderr) = err(&[&s.path("bad.st"), &f]);
    assert_eq!(status, 1, "{stderr}");
}

#[test]
fn the_same_inputs_give_byte_identical_output() {
    for example in ["two_tasks.st", "tank_control.st"] {
        let case = common::data_dir().join("../examples").join(example);
        let d = directives(&case).unwrap();
        let mut args = vec!["stc".to_string(), "run".into(), case.display().to_string()];
        args.extend(d.options);
        args.push("--trace".into());
        let argv: Vec<&str> = args.iter().map(|s| s.as_str()).collect();
        let a = stc::cli::run_args(&argv);
        let b = stc::cli::run_args(&argv);
        assert_eq!(a.status, 0, "{}", a.stderr);
        assert!(a.stdout.lines().count() > 20);
        assert_eq!(a.stdout, b.stdout);
    }
}

const GUARDED: &str = "TYPE Pct : INT (0..100); END_TYPE
PROGRAM Main
VAR CONSTANT
  limit : INT := 10;
END_VAR
VAR_INPUT
  level : Pct;
END_VAR
VAR_OUTPUT
  out : INT;
END_VAR
out := level + limit;
END_PROGRAM
";

#[test]
fn constants_and_subranges_are_guarded_from_set() {
    let s = Scratch::new("guarded", &[("main.st", GUARDED)]);
    let f = s.path("main.st");
    let out = stc(&[&f, "--set", "Main.level=40", "--watch", "Main.out"]);
    assert_eq!(out.status, 0, "{}", out.stderr);
    assert_eq!(out.stdout, "cycle 1 (T#0s)\n  Main.out = 50\n");
    let out = stc(&[&f, "--set", "Main.level=101"]);
    assert_eq!(out.status, 2);
    assert!(
        out.stderr.contains("outside the subrange 0..100"),
        "{}",
        out.stderr
    );
    let out = stc(&[&f, "--set", "Main.limit=5"]);
    assert_eq!(out.status, 2);
    assert!(out.stderr.contains("CONSTANT"), "{}", out.stderr);
}

const TWO_IN_ONE_TASK: &str = "PROGRAM Busy
VAR_OUTPUT n : DINT; END_VAR
VAR i : DINT; END_VAR
FOR i := 1 TO 300 DO n := n + 1; END_FOR;
END_PROGRAM
CONFIGURATION C
  RESOURCE R ON PLC
    TASK t (INTERVAL := T#10ms, PRIORITY := 1);
    PROGRAM a WITH t : Busy;
    PROGRAM b WITH t : Busy;
  END_RESOURCE
END_CONFIGURATION
";

#[test]
fn the_watchdog_budget_is_shared_by_the_programs_of_a_task() {
    let s = Scratch::new("watchdog", &[("main.st", TWO_IN_ONE_TASK)]);
    let f = s.path("main.st");
    // Each program needs about 600 instructions: one fits in 1000, two do not.
    let one = stc(&[&f, "--max-steps", "100000", "--watch", "a.n,b.n"]);
    assert_eq!(one.status, 0, "{}", one.stderr);
    assert_eq!(one.stdout, "cycle 1 (T#0s)\n  a.n = 300\n  b.n = 300\n");
    let out = stc(&[&f, "--max-steps", "1000"]);
    assert_eq!(out.status, 3, "{}", out.stdout);
    assert!(out.stderr.starts_with("fault: watchdog"), "{}", out.stderr);
}

#[test]
fn a_bytecode_file_runs_like_its_sources_and_a_damaged_one_is_refused() {
    let s = Scratch::new("stbc", &[("main.st", COUNTER)]);
    let (src, bin) = (s.path("main.st"), s.path("main.stbc"));
    let built = stc::cli::run_args(&["stc", "build", &src, "--emit", "bytecode", "-o", &bin]);
    assert_eq!(built.status, 0, "{}", built.stderr);
    let from_source = stc(&[&src, "--cycles", "2", "--trace", "--format", "json"]);
    let from_file = stc(&[&bin, "--cycles", "2", "--trace", "--format", "json"]);
    assert_eq!(from_file.status, 0, "{}", from_file.stderr);
    assert_eq!(from_file.stdout, from_source.stdout);
    // One flipped byte: the checksum no longer matches.
    let mut bytes = std::fs::read(&bin).unwrap();
    let mid = bytes.len() / 2;
    bytes[mid] ^= 0x40;
    std::fs::write(&bin, &bytes).unwrap();
    let out = stc(&[&bin]);
    assert_eq!(out.status, 2, "{}", out.stderr);
    assert!(out.stderr.contains("checksum"), "{}", out.stderr);
    assert!(out.stdout.is_empty());
}
