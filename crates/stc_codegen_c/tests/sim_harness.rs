//! The simulation harness (`runtime/stc_sim*.c`) against `stc run`.
//!
//! The harness is compiled (C99, `-pedantic -Wall -Wextra -Wconversion
//! -Wshadow -Werror`, with the address and undefined-behaviour sanitizers)
//! with hand-written fixtures that stand for the `program.c` the generator
//! makes of `tests/sim_fixture/fixture.st` and `fixture2.st`. Each case
//! runs the harness with some options and `stc run` on the ST source with
//! the same options, and compares stdout, stderr and the exit status byte
//! for byte. The value formats (REAL digits, durations, dates) are also
//! compared directly with stc_runtime's on many generated values.

use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::OnceLock;

use stc_syntax::token::ElemType;
use stc_values::Value;

const CFLAGS: &[&str] = &[
    "-std=c99",
    "-pedantic",
    "-Wall",
    "-Wextra",
    "-Wconversion",
    "-Wshadow",
    "-Werror",
    "-g",
    "-fsanitize=undefined,address",
    "-fno-sanitize-recover=all",
];

const FIXTURE: &str = "tests/sim_fixture/fixture.st";
const FIXTURE2: &str = "tests/sim_fixture/fixture2.st";

fn crate_dir() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

fn work_dir() -> PathBuf {
    let d = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("sim_harness");
    std::fs::create_dir_all(&d).expect("a work directory");
    d
}

/// The harness sources: every `runtime/stc_sim*.c`.
fn harness_sources() -> Vec<PathBuf> {
    let mut v: Vec<PathBuf> = std::fs::read_dir(crate_dir().join("runtime"))
        .expect("the runtime directory")
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| {
            let name = p.file_name().and_then(|n| n.to_str()).unwrap_or("");
            name.starts_with("stc_sim") && name.ends_with(".c")
        })
        .collect();
    v.sort();
    v
}

fn gcc(sources: &[PathBuf], out: &Path) -> Result<(), String> {
    let o = Command::new("gcc")
        .args(CFLAGS)
        .arg("-I")
        .arg(crate_dir().join("runtime"))
        .args(sources)
        .arg("-lm")
        .arg("-o")
        .arg(out)
        .output()
        .map_err(|e| format!("cannot run gcc: {e}"))?;
    if o.status.success() {
        Ok(())
    } else {
        Err(String::from_utf8_lossy(&o.stderr).into_owned())
    }
}

/// Builds the harness with a fixture and the runtime `runtime/stc_rt.c`;
/// panics (the test fails) when they do not compile.
fn build(fixture: &str) -> PathBuf {
    let out = work_dir().join(format!("sim_{fixture}"));
    let mut sources = harness_sources();
    sources.push(crate_dir().join(format!("tests/sim_fixture/{fixture}.c")));
    sources.push(crate_dir().join("runtime/stc_rt.c"));
    if let Err(e) = gcc(&sources, &out) {
        panic!("the harness, the fixture or runtime/stc_rt.c does not compile:\n{e}");
    }
    out
}

fn sim(fixture: &str) -> &'static Path {
    static ONE: OnceLock<PathBuf> = OnceLock::new();
    static TWO: OnceLock<PathBuf> = OnceLock::new();
    let cell = if fixture == "fixture" { &ONE } else { &TWO };
    cell.get_or_init(|| build(fixture))
}

#[derive(Debug, PartialEq, Eq)]
struct Outcome {
    stdout: String,
    stderr: String,
    status: i32,
}

fn run_sim(fixture: &str, args: &[String]) -> Outcome {
    let o = Command::new(sim(fixture))
        .args(args)
        .current_dir(crate_dir())
        .output()
        .expect("the harness runs");
    Outcome {
        stdout: String::from_utf8_lossy(&o.stdout).into_owned(),
        stderr: String::from_utf8_lossy(&o.stderr).into_owned(),
        status: o.status.code().unwrap_or(-1),
    }
}

fn run_stc(source: &str, args: &[String]) -> Outcome {
    static CWD: OnceLock<()> = OnceLock::new();
    CWD.get_or_init(|| std::env::set_current_dir(crate_dir()).expect("the crate directory"));
    let mut argv: Vec<&str> = vec!["stc", "run", source];
    argv.extend(args.iter().map(|s| s.as_str()));
    let o = stc::cli::run_args(&argv);
    Outcome {
        stdout: o.stdout,
        stderr: o.stderr,
        status: i32::from(o.status),
    }
}

fn split(case: &str) -> Vec<String> {
    shlex::split(case).unwrap_or_else(|| panic!("a shell-quoted case: {case}"))
}

/// Runs every case on the harness and on `stc run`; panics listing every
/// case whose outcomes differ.
fn compare_all(fixture: &str, source: &str, cases: &[&str]) {
    let mut failures = Vec::new();
    for case in cases {
        let args = split(case);
        let got = run_sim(fixture, &args);
        let want = run_stc(source, &args);
        if got != want {
            failures.push(format!(
                "case `{case}`:\n--- harness ---\n{}{}status {}\n--- stc run ---\n{}{}status {}\n",
                got.stdout, got.stderr, got.status, want.stdout, want.stderr, want.status
            ));
        }
    }
    assert!(
        failures.is_empty(),
        "{} of {} cases differ:\n{}",
        failures.len(),
        cases.len(),
        failures.join("\n")
    );
}

/// Writes a file into the work directory and returns its path.
fn write_file(name: &str, bytes: &[u8]) -> String {
    let p = work_dir().join(name);
    std::fs::write(&p, bytes).expect("a test file");
    p.to_str().expect("a UTF-8 path").to_string()
}

#[test]
fn default_runs_and_reports() {
    compare_all(
        "fixture",
        FIXTURE,
        &[
            "",
            "--cycles 0",
            "--cycles 0 --trace",
            "--cycles 3",
            "--cycles 3 --format json",
            "--cycles 5 --trace",
            "--cycles 5 --trace --format json",
            "--cycles 3 --format text",
            "--format=json --cycles=2",
            "--program Main --cycles 2",
            "--program aux --cycles 2 --trace",
            "--program MAIN --format json --cycles 3 --watch Main",
            "--config Plant --cycles 4 --trace",
            "--config plant --cycles 2 --format json",
            "--tick 5ms --cycles 4 --trace",
            "--tick T#7ms --cycles 4 --trace --format json",
            "--tick ' 20ms ' --cycles 2 --trace",
            "--tick 30ms --cycles 3 --trace --watch p3.inp,p3.n,Main.count --set g_sint=-4",
            "--cycles 12 --trace --format json --set trig=TRUE --set g_sint=-5 --set Main.start=TRUE",
            "--cycles 12 --trace --watch Main.tmr,Main.lamp,lamp_g,%QX1.0 --set Main.start=TRUE",
            "-W error --std iec3 --message-format json --cycles 2",
            "--max-steps 100000 --cycles 2",
            "--cycles 922337203685 --tick 10ms --cycles 1",
        ],
    );
}

#[test]
fn watched_paths() {
    compare_all(
        "fixture",
        FIXTURE,
        &[
            "--cycles 3 --watch Main",
            "--cycles 3 --watch Main --format json",
            "--cycles 4 --watch Main.m,Main.m[2],Main.m[2][1],Main.m[2,1],Main.pts[1].x",
            "--cycles 4 --watch 'Main.m[1,0],Main.m[1][0],Main.arr[2],Main.arr[16#2]' --format json",
            "--cycles 2 --watch Main.adder,Main.tmr,Main.tmr.Q,Main.pts,Main.pt --format json",
            "--cycles 2 --watch 'MAIN.COUNT,main.TMR.q,Main.pts[1].Y,Main.arr[ 2 ],Main.arr[+2]'",
            "--cycles 2 --watch 'Main.arr[2#10],Main.arr[1_0],Main.m[2][0],Main.m[2], Main.count '",
            "--cycles 2 --watch top,G,k,Main.g,Main.lamp,Main.sensor,p2.inp,Main.adder.step",
            "--cycles 2 --watch Main,,,Main.count --watch Main.count,main.count",
            "--cycles 2 --watch %ix0.0,%Q0.0,%QX1.0,%IW2,w_in,lamp_g,%QX0.0 --format json",
            "--cycles 2 --watch Main.name,Main.wname,Main.ch,Main.wch,Main.big,Main.t,Main.d",
            "--cycles 2 --watch Main.tod1,Main.dt1,Main.pct,Main.b,Main.u,Main.colour --format json",
            "--watch ''",
            "--watch ,",
            "--watch Main.",
            "--watch Main..x",
            "--watch 'Main.a[1'",
            "--watch 'Main.a[i]'",
            "--watch 'Main.arr[]'",
            "--watch 1abc",
            "--watch 'Main x'",
            "--watch Main.ä",
            "--watch %Z1",
            "--watch '%I*'",
            "--watch %QW7",
            "--watch %IX",
            "--watch %I",
            "--watch %",
            "--watch %QX1..0",
            "--watch %QX99999999999",
            "--watch %QX1.0.x",
            "--watch %IXé",
            "--watch nobody.x",
            "--watch Main.nope",
            "--watch Main._hidden",
            "--watch Main.tmr.edge",
            "--watch Main.j",
            "--watch Main.count.x",
            "--watch 'Main.count[1]'",
            "--watch 'Main.arr[4]'",
            "--watch 'Main.arr[0]'",
            "--watch 'Main.m[0,1]'",
            "--watch 'Main.m[1].x'",
            "--watch 'Main.m[1,2,3]'",
            "--watch 'Main.arr[1,1]'",
            "--watch 'Main.arr[-1]'",
            "--watch 'Main.arr[99999999999999999999]'",
            "--watch 'Main.arr[-9223372036854775808]'",
            "--watch 'Main.arr[3#1]'",
            "--watch 'Main.name[1]'",
            "--watch 'Main.tmr[1]'",
            "--watch 'Main.pt[0]'",
            "--watch 'Main.m[1,0].x'",
            "--watch trig.x",
            "--program Aux --watch Aux,top,g,K,trig,lamp_g,%QX0.0,%Q1.0,%IX0.0,%IW2,w_in",
            "--program Aux --watch Main.count",
        ],
    );
}

#[test]
fn set_values_of_every_kind() {
    let mut cases: Vec<String> = Vec::new();
    let mut add = |path: &str, values: &[&str]| {
        for v in values {
            for fmt in ["text", "json"] {
                cases.push(format!(
                    "--cycles 0 --watch {path} --format {fmt} --set {}",
                    shlex::try_quote(&format!("{path}={v}")).expect("quotable")
                ));
            }
        }
    };
    add(
        "Main.start",
        &["TRUE", "false", "1", "0", "BOOL#TRUE", "yes", "2", " TRUE "],
    );
    add(
        "Main.divisor",
        &[
            "42", " -7 ", "16#FF", "INT#-3", "-32768", "32768", "1.5", "abc", "SINT#1",
        ],
    );
    add(
        "Main.b",
        &[
            "255", "256", "16#FF", "2#1010", "8#17", "BYTE#7", "-1", "+5", "1_0", "_1", "16#_F",
        ],
    );
    add(
        "Main.u",
        &[
            "18446744073709551615",
            "18446744073709551616",
            "ULINT#5",
            "INT#5",
        ],
    );
    add(
        "Main.level",
        &[
            "0.1",
            "-3.5",
            "2",
            "1e20",
            "1.5E-7",
            "3.4028235E38",
            "3.5e38",
            "INF",
            "-inf",
            "NaN",
            "-NaN",
            "REAL#1.5",
            "LREAL#1.5",
            "1_000.5",
            "16777216",
            "1e-45",
            "1.4e-45",
            "0.0001",
            "0.00001",
            "1e15",
            "1e16",
            "-0.0",
            "1.",
            ".5",
            "1e",
            "0x10",
        ],
    );
    add(
        "Main.big",
        &[
            "0.1",
            "1e-7",
            "1e300",
            "1e-300",
            "4.9e-324",
            "1.7976931348623157e308",
            "123456789012345678",
            "0.30000000000000004",
            "1e16",
            "9999999999999998",
            "1e-5",
            "1e-4",
            "2.5e-5",
            "123.456e2",
        ],
    );
    add(
        "Main.t",
        &[
            "T#1s",
            "1s",
            "T#-2s",
            "t#1h2m3.5s",
            "T#25h",
            "T#1d2h",
            "LTIME#5ns",
            "T#1.5s",
            "10",
            "T#1s500ms",
            "T#0s",
            "T#106751d23h47m16s854ms775us807ns",
            "T#-106751d23h47m16s854ms775us808ns",
            "T#1m61s",
            "T#1s_500ms",
            "TIME#90m",
            "D#2024-01-01",
        ],
    );
    add(
        "Main.d",
        &[
            "D#2024-01-31",
            "2024-02-29",
            "D#2023-02-29",
            "D#1900-01-01",
            "D#0001-01-01",
            "D#9999-12-31",
            "DATE#1970-01-01",
            "LDATE#2000-01-01",
            "D#10000-01-01",
        ],
    );
    add(
        "Main.tod1",
        &[
            "TOD#12:30:00",
            "TOD#12:30:00.5",
            "TOD#23:59:59.999999999",
            "12:00:00.123",
            "TOD#24:00:00",
            "TIME_OF_DAY#01:02:03",
            "TOD#1:2:3",
        ],
    );
    add(
        "Main.dt1",
        &[
            "DT#2024-01-31-12:30:00",
            "DT#1970-01-01-00:00:00.5",
            "DT#1600-01-01-00:00:00",
            "DT#2262-04-11-23:47:16",
            "DT#1677-09-21-00:12:44",
            "DT#1677-09-21-00:12:43",
            "DT#2262-04-11-23:47:17",
            "DATE_AND_TIME#2000-01-01-00:00:00",
        ],
    );
    add(
        "Main.name",
        &[
            "'it$'s'",
            "abc def",
            "'$41$42$N$T$$$R$P$L'",
            "'$Q'",
            "'abc",
            "STRING#'x'",
            "'café'",
            "'☺'",
            "'a=b'",
            "''",
            "'$'",
            "'0123456789abc'",
            "\"dq\"",
            "'$C3$A9'",
            "'$1'",
            "'$7F$01'",
            "'it$",
        ],
    );
    add(
        "Main.wname",
        &[
            "\"☺x$0041\"",
            "\"$D800\"",
            "😀abcdefg",
            "WSTRING#\"w\"",
            "'single'",
            "\"$00E9\"",
            "\"$12\"",
        ],
    );
    add(
        "Main.ch",
        &["'$$'", "''", "€", "☺", "'AB'", "A", "\"Z\"", "'$0A'"],
    );
    add("Main.wch", &["\"☺\"", "$", "'x'", "😀", "\"$263A\""]);
    add(
        "Main.colour",
        &[
            "Color#Blue",
            "blue",
            "Purple",
            "Shade#Red",
            " COLOR# green ",
            "1",
        ],
    );
    add("Main.pct", &["101", "-1", "50", "abc", "100"]);
    add("Main.arr", &["1"]);
    add("'Main.m[1]'", &["1"]);
    add("Main.pt", &["1"]);
    add("Main.tmr", &["1"]);
    add("Main", &["1"]);
    add("K", &["1"]);
    add("g", &["abc", "7"]);
    add("nope", &["1"]);
    add("%IX0.0", &["TRUE"]);
    add("%IW2", &["16#BEEF"]);
    add("w_in", &["65535", "65536"]);
    add("Main.sensor", &["TRUE"]);
    add("Main.g", &["9"]);
    add("'Main.m[2,1]'", &["-4"]);
    add("Main.tmr.PT", &["T#2s"]);
    add("Main.j", &["1"]);
    let mut more: Vec<String> = vec![
        "--set g".into(),
        "--set =1".into(),
        "--set ' = 1'".into(),
        "--set Main.count=5 --set Main.count=6 --watch Main.count --cycles 0".into(),
        "--set %IX0.0=TRUE --cycles 3 --watch Main.tmr,Main.lamp --trace".into(),
        "--set Main.sensor=TRUE --set Main.divisor=0 --cycles 2".into(),
    ];
    cases.append(&mut more);
    let refs: Vec<&str> = cases.iter().map(|s| s.as_str()).collect();
    compare_all("fixture", FIXTURE, &refs);
}

#[test]
fn stimulus_files() {
    let basic = "tests/sim_fixture/stim_basic.csv";
    let crlf = "tests/sim_fixture/stim_crlf.csv";
    let mut cases: Vec<String> = vec![
        format!("--stimulus {basic} --cycles 6 --trace --watch p2.inp,p3.inp,trig,Main.name,Main.sensor,Main.tmr,p2.n,top"),
        format!("--stimulus {basic} --cycles 6 --trace --format json --watch p2.inp,p3.inp,trig,Main.name,Main.sensor,top"),
        format!("--stimulus {basic} --cycles 3"),
        format!("--stimulus {crlf} --cycles 4 --trace --watch Main.start,Main.tmr"),
        format!("--stimulus {basic} --set g=100 --cycles 1 --watch g,p2.inp"),
    ];
    let bad: &[&[u8]] = &[
        b"",
        b"\n\ntime,x\n",
        b"cycle,x,,y\n",
        b"Cycle,g\n1,2,3\n",
        b"cycle,g\n0,1\n",
        b"cycle,g\n-1,1\n",
        b"cycle,g\n,1\n",
        b"cycle,g\n1,'a\n",
        b"cycle,g\n1,\"a\n",
        b"cycle,g\n1,\"a\"b\n",
        b"cycle,Main.zz\n1,2\n",
        b"cycle,g\n1,2\n2,x\n",
        b"cycle,K\n",
        b"cycle,g\n+2,5\n1_0,6\n",
        b"cycle,g\n99999999999999999999,1\n",
        b"cycle,Main.name\n1,'$Q'\n",
        b"cycle,g,Main.arr\n1,2,3\n",
        b"cycle,g\n1,\"a\"\r",
        b"cycle ,g\n 1 , 7 \n",
        b"cycle,g\n1,'a'x,2\n",
        b"cycle,g\n1,\"x\"\xc3\xa9\n",
        b"\xff\xfe",
        b"cycle,g\n3,1\n1,2\n3,3\n2,4\n",
        b"  \n\t\ncycle,\"g\"\n1, 5\n",
        b"cycle,Main.name\n1,'a,b' , x\n",
        b"cycle,g,g\n1,1,2\n",
        b"cycle,g\n1,2\n1,3\n",
        b"cycle\n1\n",
        b"cycle,%IX0.0\n2,TRUE\n",
        b"cycle,g\n1,\"\"\n",
    ];
    for (i, text) in bad.iter().enumerate() {
        let path = write_file(&format!("stim_{i}.csv"), text);
        cases.push(format!(
            "--stimulus {path} --watch g,Main.sensor --cycles 3 --trace"
        ));
    }
    cases.push(format!(
        "--stimulus {} --watch g",
        work_dir().to_str().expect("a UTF-8 path")
    ));
    cases.push("--stimulus no_such_file.csv".into());
    let refs: Vec<&str> = cases.iter().map(|s| s.as_str()).collect();
    compare_all("fixture", FIXTURE, &refs);
}

#[test]
fn faults_report_the_last_completed_cycle() {
    let stim = write_file("stim_fault.csv", b"cycle,Main.divisor\n3,0\n");
    let cases = [
        "--set Main.divisor=0".to_string(),
        "--set Main.divisor=0 --trace --cycles 4".into(),
        "--set Main.divisor=0 --cycles 0".into(),
        format!("--stimulus {stim} --cycles 5"),
        format!("--stimulus {stim} --cycles 5 --trace --format json"),
        format!("--stimulus {stim} --cycles 2"),
        format!("--stimulus {stim} --cycles 5 --watch Main,g,top --set trig=TRUE"),
        "--max-steps 0".into(),
        "--max-steps 0 --program Main --format json".into(),
        "--max-steps 0 --cycles 0".into(),
        // INT overflow makes an index fault in cycle 32768: the report of
        // cycle 32767 comes from replaying 32767 cycles on a fresh machine.
        "--cycles 32770 --watch Main.count,Main.arr,Main.m,Main.level,Main.big,Main.t,Main.u,Main.dt1,Main.tod1,Main.adder".into(),
    ];
    let refs: Vec<&str> = cases.iter().map(|s| s.as_str()).collect();
    compare_all("fixture", FIXTURE, &refs);
}

#[test]
fn usage_errors_read_as_clap_writes_them() {
    compare_all(
        "fixture",
        FIXTURE,
        &[
            "--cycles abc",
            "--cycles -1",
            "--cycles",
            "--bogus",
            "--format xml",
            "--max-steps 1e5",
            "--config A --program B",
            "--trace --trace",
            "--format",
            "--cycles 99999999999999999999",
            "-x",
            "--tick=",
            "--tick 0ms",
            "--tick abc",
            "--tick -5ms",
            "--tick=-5ms",
            "--set x",
            "--cycles 3 --cycles 4",
            "--help",
            "-h",
            "--cycle 3",
            "--cycles 3 --bogus",
            "--trac",
            "--traces",
            "--form json",
            "--format=",
            "--format=JSON",
            "--format Json",
            "--format jsn",
            "--trace=yes",
            "--realtime=1",
            "-W warn",
            "--cycles ''",
            "--cycles +3",
            "--cycles ' 3'",
            "--cycles +",
            "--cycles -",
            "--max-steps 18446744073709551616",
            "--cycles 0x10",
            "--program",
            "--set",
            "--watch",
            "--stimulus",
            "--version",
            "-V",
            "--config X --config Y",
            "--set a=1 --set",
            "--format text --format json",
            "--format json --cycles 3 --bogus",
            "--trace --cycles 3 --bogus",
            "--set a=1 --watch x --bogus",
            "--cycles --trace",
            "--cycles=-1",
            "--set -x",
            "-Werror",
            "-W=error",
            "-Wwarn",
            "-W",
            "-W ''",
            "-W=",
            "-Wx",
            "-Wh",
            "-hW",
            "-hx",
            "-xh",
            "--cycles 3 -x",
            "--trace -x",
            "--set=a=1 --set=b",
            "--std iec2 --bogus",
            "--std iec4",
            "--std",
            "--message-format xml",
            "-W error --bogus",
            "--message-format json --bogus",
            "--realtime --bogus",
            "--max-steps 5 --bogus",
            "--watch a --watch b --bogus",
            "--config A --program B --bogus",
            "--bogus --config A --program B",
            "--program B --config A",
            "--cycles 3 --watch x --format json --trace --bogus",
            "--cycles 3 --help",
            "--bogus --help",
            "--help --bogus",
            "--cycles 3 --cycles 4 --help",
            "--config A --program B --help",
            "--cycles abc --help",
            "--c",
            "--con",
            "--s",
            "--st",
            "--wat",
            "--sets",
            "--maxsteps",
            "--max_steps",
            "--ticks",
            "--trace --cycle 3",
            "--cycles 3 --cycle 3",
            "--confi",
            "--progra",
            "--real",
            "--stim",
            "--forma",
            "--message",
            "--messageformat",
            "--x",
            "--cyclesx",
            "--Cycles 3",
            "--CYCLES",
            "--help=1",
            "--cycles 3 -W",
            "-W error -W error --cycles 1",
            "--std iec2 --std iec3",
            "--realtime --realtime",
            "--cycles 3 --config A --program B",
            "--cycles=3 --cycles=3",
            "--format=text --bogus",
            "--cycles -0",
            "--watch -a",
            "--set 'a=-1'",
            "--cycles abc --bogus",
            "--cycles abc --trace",
            "--cycles --bogus",
            "--cycles 3 --trace --trace=1",
            "--cycles --trace=1",
            "--format ''",
            "--=x",
            "--cycles 3 --cycles",
            "--cycles abc --cycles 3",
            "--trace --cycles abc --config a --program b",
            "--set=x --help",
            "-h=1",
            "-W error -h",
            "--cycles 1 --program Main --config Plant",
            "--format json --format=xx",
            "--trace=1",
            "-W error --trace=1",
            "--std iec3 --cycles 3 --trace=1",
            "--std iec3 --help=1",
            "--realtime=x",
            "--std iec3 --cycles 3 --config a --program b",
            "--watch a --trace --realtime=x",
            "--config Line",
            "--program Pump",
            "--cycles 922337203687 --tick 10ms",
            "--cycles -- 3",
            "--tick 4611686018427387904ns --cycles 3",
            "--tick 4611686018427387903ns --cycles 3 --trace",
            "--cycles 18446744073709551615",
            "--tick 1ns --cycles 18446744073709551615",
        ],
    );
}

#[test]
fn tasks_events_and_connections() {
    compare_all(
        "fixture2",
        FIXTURE2,
        &[
            "",
            "--cycles 2",
            "--config A --cycles 9 --trace",
            "--config A --cycles 9 --trace --set trig=TRUE --format json",
            "--config a --tick 10ms --cycles 5 --trace",
            "--config A --tick 3ms --cycles 25 --watch a1.x,a3.x,b1.y,b2.x",
            "--config A --cycles 4 --trace --set ga=-3 --watch a2,b1,out_a,%QD4",
            "--config B --cycles 3 --trace",
            "--config B --watch c1 --cycles 2",
            "--config C",
            "--program P1 --cycles 3",
            "--program p2 --cycles 2 --set P2.i=5 --trace",
            "--program P3",
            "--config A --max-steps 1",
            "--config A --max-steps 0 --trace --cycles 3",
            "--config A --watch a1,trig --stimulus tests/sim_fixture/stim_trig.csv --cycles 8 --trace",
        ],
    );
}

/// Behaviours `stc run` cannot show: a connection whose conversion fails
/// (the analyser never lets one through) and the options the harness does
/// not take.
#[test]
fn harness_only_behaviours() {
    let cases: &[(&str, &str, &str, &str, i32)] = &[
        (
            "fixture2",
            "--config B --set gb=5000000000 --cycles 2 --trace",
            "cycle 0 (T#0s)\n  c1.y = 0\n",
            "fault: conversion failure in P2 at <configuration>:0:0\n",
            3,
        ),
        (
            "fixture2",
            "--config B --set gb=-2147483648.4 --cycles 2 --watch c1",
            "cycle 2 (T#10ms)\n  c1 = (i := -2147483648, y := 0)\n",
            "",
            0,
        ),
        (
            "fixture",
            "--realtime",
            "",
            "error: --realtime is not available in the simulation harness: build the real-time program with `make rt`\n",
            2,
        ),
        (
            "fixture",
            "--cycles 2 extra.st",
            "",
            "error: unexpected argument 'extra.st' found\n\n  tip: the simulation harness runs the program it was built from; it takes no FILES\n\nUsage: stc run [OPTIONS] <FILES>...\n\nFor more information, try '--help'.\n",
            2,
        ),
        (
            // The budget is per task: a1 and a3 share `both`'s 2 steps,
            // a2, b1 and b2 have their own.
            "fixture2",
            "--config A --max-steps 2 --cycles 9 --format json",
            "{\"cycle\":9,\"time\":\"T#40ms\",\"values\":{\"a1.x\":3,\"a2.y\":18,\"a3.x\":3,\"b1.y\":18,\"b2.x\":9,\"out_a\":18}}\n",
            "",
            0,
        ),
    ];
    for (fixture, args, stdout, stderr, status) in cases {
        let got = run_sim(fixture, &split(args));
        let want = Outcome {
            stdout: stdout.to_string(),
            stderr: stderr.to_string(),
            status: *status,
        };
        assert_eq!(got, want, "case `{args}` on {fixture}");
    }
}

/// Arguments that are not UTF-8 (the expected texts are what `stc run`
/// prints; the in-process entry point only takes `&str`).
#[cfg(unix)]
#[test]
fn arguments_that_are_not_utf8() {
    use std::ffi::OsString;
    use std::os::unix::ffi::OsStringExt;
    let bad_utf8 = "error: invalid UTF-8 was detected in one or more arguments\n\nUsage: stc run [OPTIONS] <FILES>...\n\nFor more information, try '--help'.\n";
    let cases: &[(&[&[u8]], &str)] = &[
        (&[b"--config", b"\xff"], bad_utf8),
        (&[b"--cycles", b"\xff"], bad_utf8),
        (&[b"--set", b"a=\xff"], bad_utf8),
        (&[b"--watch", b"Main.\xff"], bad_utf8),
        (
            &[b"--format", b"\xff"],
            "error: invalid value '\u{fffd}' for '--format <FORMAT>'\n  [possible values: text, json]\n\nFor more information, try '--help'.\n",
        ),
        (
            &[b"--\xffx"],
            "error: unexpected argument '--\u{fffd}x' found\n\n  tip: to pass '--\u{fffd}x' as a value, use '-- --\u{fffd}x'\n\nUsage: stc run <FILES>...\n\nFor more information, try '--help'.\n",
        ),
        (
            &[b"-\xff"],
            "error: unexpected argument '-\u{fffd}' found\n\n  tip: to pass '-\u{fffd}' as a value, use '-- -\u{fffd}'\n\nUsage: stc run [OPTIONS] <FILES>...\n\nFor more information, try '--help'.\n",
        ),
        (
            &[b"--trace=\xff"],
            "error: unexpected value '\u{fffd}' for '--trace' found; no more were expected\n\nUsage: stc run --trace <FILES>...\n\nFor more information, try '--help'.\n",
        ),
        (
            &[b"--stimulus", b"/nonexist\xff.csv"],
            "error: cannot read /nonexist\u{fffd}.csv: No such file or directory (os error 2)\n",
        ),
    ];
    for (args, stderr) in cases {
        let argv: Vec<OsString> = args
            .iter()
            .map(|a| OsString::from_vec(a.to_vec()))
            .collect();
        let o = Command::new(sim("fixture"))
            .args(&argv)
            .current_dir(crate_dir())
            .output()
            .expect("the harness runs");
        assert_eq!(
            (
                String::from_utf8_lossy(&o.stderr).as_ref(),
                o.stdout.is_empty(),
                o.status.code()
            ),
            (*stderr, true, Some(2)),
            "{argv:?}"
        );
    }
}

/// Random paths, values and stimulus files: the harness and `stc run`
/// agree on every one (and nothing makes the harness misbehave: the
/// sanitizers abort on undefined behaviour).
#[test]
fn random_inputs_match_stc() {
    let mut rng = Rng(0x5EED_1234_ABCD_0001);
    let mut pick = |items: &[&'static str]| -> &'static str {
        items[(rng.next() % items.len() as u64) as usize]
    };
    let roots = [
        "Main", "main", "p2", "top", "g", "K", "trig", "%IX0.0", "%QX1.0", "%IW2", "nobody",
        "%Q0.0", "Aux", "lamp_g", "w_in", "%", "", " ", "1", "_x",
    ];
    let segments = [
        ".count",
        ".tmr",
        ".tmr.Q",
        ".tmr.PT",
        ".arr",
        "[1]",
        "[2,1]",
        "[0]",
        "[16#1]",
        ".m",
        "[1][2]",
        ".pts",
        ".x",
        ".name",
        ".nope",
        ".j",
        "[",
        "]",
        ".",
        "[ 2 ]",
        "[-1]",
        "[1,]",
        ".pct",
        ".colour",
        ".adder",
        ".step",
        ".b",
        ".u",
        ".big",
        ".level",
        ".t",
        ".d",
        ".tod1",
        ".dt1",
        ".ch",
        ".wch",
        ".wname",
        ".g",
        ".lamp",
        ".sensor",
        ".inp",
        ".n",
        "é",
        "[2#1]",
        "[99999999999999999999]",
    ];
    let values = [
        "1",
        "0",
        "-1",
        "TRUE",
        "FALSE",
        "16#FF",
        "2#101",
        "'x'",
        "\"y\"",
        "''",
        "'$'",
        "'$N$41'",
        "T#1s",
        "1.5",
        "-0.0",
        "1e40",
        "NaN",
        "INF",
        "D#2024-01-31",
        "TOD#12:00:00",
        "DT#2024-01-31-12:00:00",
        "Color#Red",
        "Blue",
        "abc",
        "",
        " ",
        "99999999999999999999",
        "-32769",
        "32767",
        "255",
        "256",
        "LREAL#1.5",
        "REAL#-2",
        "STRING#'s'",
        "'☺'",
        "\"☺\"",
        "T#-5ms",
        "Color#",
        "#",
        "=",
        "'a''b'",
    ];
    let mut cases: Vec<Vec<String>> = Vec::new();
    for i in 0..300 {
        let mut path = pick(&roots).to_string();
        for _ in 0..(i % 4) {
            path.push_str(pick(&segments));
        }
        let mut args = vec![
            "--watch".to_string(),
            path.clone(),
            "--cycles".into(),
            "1".into(),
        ];
        if i % 2 == 0 {
            args.push("--format".into());
            args.push("json".into());
        }
        if i % 3 != 0 {
            args.push("--set".into());
            args.push(format!("{path}={}", pick(&values)));
        }
        cases.push(args);
    }
    let alphabet: &[u8] = b"cycle,g'\"$ \n\r.#=-19TRUEMain.ame\t_";
    for i in 0..120 {
        let mut text = if i % 2 == 0 {
            b"cycle,g,Main.name\n".to_vec()
        } else {
            Vec::new()
        };
        let len = (rng.next() % 40) as usize;
        for _ in 0..len {
            text.push(alphabet[(rng.next() % alphabet.len() as u64) as usize]);
        }
        let path = write_file(&format!("rand_{i}.csv"), &text);
        cases.push(vec![
            "--stimulus".into(),
            path,
            "--watch".into(),
            "g,Main.name".into(),
            "--cycles".into(),
            "3".into(),
            "--trace".into(),
        ]);
    }
    let mut failures = Vec::new();
    for args in &cases {
        let got = run_sim("fixture", args);
        let want = run_stc(FIXTURE, args);
        if got != want {
            failures.push(format!("{args:?}:\n  harness {got:?}\n  stc     {want:?}"));
        }
    }
    assert!(
        failures.is_empty(),
        "{} differ:\n{}",
        failures.len(),
        failures.join("\n")
    );
}

/// A small deterministic generator (xorshift64*).
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_F491_4F6C_DD1D)
    }
}

fn real_cases() -> (Vec<f32>, Vec<f64>) {
    let mut rng = Rng(0x9E37_79B9_7F4A_7C15);
    let mut singles: Vec<f32> = vec![
        0.0,
        -0.0,
        0.1,
        1.0,
        -2.5,
        1e20,
        16_777_216.0,
        100.0 / 3.0,
        f32::MAX,
        f32::MIN_POSITIVE,
        f32::from_bits(1),
        f32::NAN,
        f32::INFINITY,
        f32::NEG_INFINITY,
    ];
    let mut doubles: Vec<f64> = vec![
        0.0,
        -0.0,
        0.1,
        0.1f32 as f64,
        1e-7,
        1e16,
        9_999_999_999_999_998.0,
        f64::MAX,
        f64::MIN_POSITIVE,
        f64::from_bits(1),
        f64::NAN,
        f64::INFINITY,
        f64::NEG_INFINITY,
    ];
    for e in -330i32..=310 {
        for m in [
            1.0f64,
            1.5,
            2.0,
            5.0,
            9.99,
            9.999_999_999_999_999,
            1.000_000_000_000_001,
        ] {
            let x = m * 10f64.powi(e);
            doubles.push(x);
            doubles.push(-x);
            singles.push(x as f32);
        }
    }
    for e in -1075i32..=1024 {
        let x = 2f64.powi(e);
        doubles.push(x);
        doubles.push(f64::from_bits(x.to_bits().wrapping_sub(1)));
        doubles.push(f64::from_bits(x.to_bits() + 1));
        let s = x as f32;
        singles.push(s);
        singles.push(f32::from_bits(s.to_bits().wrapping_sub(1)));
        singles.push(f32::from_bits(s.to_bits() + 1));
    }
    for _ in 0..40_000 {
        let bits = rng.next();
        doubles.push(f64::from_bits(bits));
        singles.push(f32::from_bits((bits >> 32) as u32));
        // short decimals: what programs usually hold
        let digits = (rng.next() % 100_000) as f64;
        let exp = (rng.next() % 40) as i32 - 20;
        doubles.push(digits * 10f64.powi(exp));
        singles.push((digits * 10f64.powi(exp)) as f32);
    }
    (singles, doubles)
}

#[test]
fn value_formats_match_stc_runtime() {
    let driver = work_dir().join("fmt_driver");
    gcc(
        &[
            crate_dir().join("runtime/stc_sim_text.c"),
            crate_dir().join("tests/sim_fixture/fmt_driver.c"),
        ],
        &driver,
    )
    .unwrap_or_else(|e| panic!("fmt_driver does not compile:\n{e}"));
    let (singles, doubles) = real_cases();
    let mut input = String::new();
    let mut want = String::new();
    for x in &singles {
        input.push_str(&format!("r {:08x}\n", x.to_bits()));
        want.push_str(&format!(
            "{}\t{}\n",
            stc_values::to_text(ElemType::Real, &Value::Real(f64::from(*x))),
            stc_runtime::report::json_real(f64::from(*x), true)
        ));
    }
    for x in &doubles {
        input.push_str(&format!("l {:016x}\n", x.to_bits()));
        want.push_str(&format!(
            "{}\t{}\n",
            stc_values::to_text(ElemType::Lreal, &Value::Real(*x)),
            stc_runtime::report::json_real(*x, false)
        ));
    }
    let mut rng = Rng(42);
    let mut ints: Vec<i64> = vec![
        0,
        1,
        -1,
        i64::MAX,
        i64::MIN,
        86_400_000_000_000,
        -86_400_000_000_000,
        1_706_659_200,
        45_000_500_000_000,
        1_706_704_200_000_000_000,
        -62_135_596_800,
        253_402_300_799,
    ];
    for _ in 0..20_000 {
        let v = rng.next() as i64;
        ints.push(v);
        ints.push(v >> (rng.next() % 64));
    }
    for v in &ints {
        for (k, e) in [
            ('t', ElemType::Time),
            ('d', ElemType::Date),
            ('o', ElemType::Tod),
            ('a', ElemType::Dt),
        ] {
            input.push_str(&format!("{k} {v}\n"));
            want.push_str(&stc_values::to_text(e, &Value::Int(i128::from(*v))));
            want.push('\n');
        }
    }
    let path = work_dir().join("fmt_input.txt");
    std::fs::write(&path, &input).expect("the input file");
    let o = Command::new(&driver)
        .stdin(std::fs::File::open(&path).expect("the input file"))
        .output()
        .expect("the driver runs");
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let got = String::from_utf8(o.stdout).expect("UTF-8 output");
    let inputs: Vec<&str> = input.lines().collect();
    let mismatches: Vec<String> = got
        .lines()
        .zip(want.lines())
        .enumerate()
        .filter(|(_, (g, w))| g != w)
        .take(20)
        .map(|(i, (g, w))| format!("{}: harness `{g}`, stc `{w}`", inputs[i]))
        .collect();
    assert!(mismatches.is_empty(), "{}", mismatches.join("\n"));
    assert_eq!(got.lines().count(), want.lines().count());
}
