//! The C back end against the VM: every case of the run conformance suite
//! (and every example with `// run:` directives) runs with `stc run` and
//! with `stc run --backend c` (the generated C built as a shared library
//! and driven by the same runtime), with the same options plus `--format
//! json --trace`. The reports (stdout), the exit status and the fault line
//! must be identical. The generated C is compiled with `gcc -std=c99
//! -pedantic -Wall -Wextra -Wconversion -Wshadow -Werror` and runs under
//! `-fsanitize=undefined` (`STC_CFLAGS`), so it must also be free of
//! warnings and of undefined behaviour on the whole suite (AddressSanitizer
//! cannot run in a library loaded into a process: `make rt` below is built
//! with it). Each `program.c` is also
//! checked with `cppcheck --addon=misra`: only the advisory rules listed in
//! docs/misra-deviations.md may be reported.

mod common;

use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::Mutex;

const CFLAGS: &[&str] = &[
    "-std=c99",
    "-pedantic",
    "-Wall",
    "-Wextra",
    "-Wconversion",
    "-Wshadow",
    "-Werror",
    "-O1",
    "-fsanitize=undefined",
    "-fno-sanitize-recover=all",
];

/// The MISRA C:2012 rules generated code deviates from, all advisory
/// (docs/misra-deviations.md gives each reason).
const MISRA_DEVIATIONS: &[&str] = &["2.4", "8.7", "8.9", "8.11", "11.5", "15.1", "15.4", "15.5"];

/// The MISRA rules cppcheck reports on a generated program, beyond the
/// deviations.
fn misra(dir: &Path) -> Result<(), String> {
    let out = Command::new("cppcheck")
        .args([
            "--addon=misra",
            "--enable=style",
            "-q",
            "--std=c99",
            "program.c",
        ])
        .current_dir(dir)
        .output()
        .map_err(|e| format!("cannot run cppcheck (./test.sh installs it): {e}"))?;
    let text = String::from_utf8_lossy(&out.stderr);
    let bad: Vec<&str> = text
        .lines()
        .filter(|l| {
            l.split("[misra-c2012-")
                .nth(1)
                .and_then(|r| r.split(']').next())
                .is_some_and(|rule| !MISRA_DEVIATIONS.contains(&rule))
        })
        .collect();
    if bad.is_empty() {
        Ok(())
    } else {
        Err(format!(
            "MISRA findings beyond the deviations:\n{}",
            bad.join("\n")
        ))
    }
}

fn check_case(case: &Path, work: &Path) -> Result<bool, String> {
    let Some(mut options) = common::run_options(case)? else {
        return Ok(false);
    };
    options.extend(["--format".to_string(), "json".into(), "--trace".into()]);
    let files: Vec<String> = common::case_files(case)
        .iter()
        .map(|f| f.display().to_string())
        .collect();
    let name = case
        .file_name()
        .unwrap_or_default()
        .to_string_lossy()
        .replace('.', "_");
    let dir = work.join(&name);
    let dir_s = dir.display().to_string();
    let mut build = vec!["stc", "build"];
    build.extend(files.iter().map(|s| s.as_str()));
    build.extend(["--emit", "c", "-o", &dir_s]);
    let built = stc::cli::run_args(&build);
    if built.status != 0 {
        return Err(format!("stc build --emit c failed:\n{}", built.stderr));
    }
    misra(&dir)?;
    let _ = std::fs::remove_dir_all(&dir);

    let mut vm_args = vec!["stc", "run"];
    vm_args.extend(files.iter().map(|s| s.as_str()));
    vm_args.extend(options.iter().map(|s| s.as_str()));
    let vm = stc::cli::run_args(&vm_args);
    // The C engine in its own process: a sanitizer's report ends it.
    let c = Command::new(env!("CARGO_BIN_EXE_stc"))
        .arg("run")
        .args(&files)
        .args(&options)
        .args(["--backend", "c"])
        .env("CC", "gcc")
        .env("STC_CFLAGS", CFLAGS.join(" "))
        .output()
        .map_err(|e| format!("cannot run stc: {e}"))?;
    let c_out = String::from_utf8_lossy(&c.stdout);
    let c_err = String::from_utf8_lossy(&c.stderr);
    let c_status = c.status.code().unwrap_or(-1);
    let mut problems = Vec::new();
    if c_status != vm.status as i32 {
        problems.push(format!(
            "exit status: VM {}, C {c_status}\nC stderr: {c_err}",
            vm.status
        ));
    }
    if common::comparable_reports(&c_out) != common::comparable_reports(&vm.stdout) {
        problems.push(format!(
            "reports differ:\n--- VM\n{}--- C\n{c_out}",
            vm.stdout
        ));
    }
    if common::fault_lines(&vm.stderr) != common::fault_lines(&c_err)
        || c_err.contains("runtime error")
    {
        problems.push(format!(
            "faults differ:\n--- VM\n{}--- C\n{c_err}",
            vm.stderr
        ));
    }
    if problems.is_empty() {
        Ok(true)
    } else {
        Err(format!("options {options:?}\n{}", problems.join("\n")))
    }
}

#[test]
fn the_misra_deviations_are_documented() {
    let doc = std::fs::read_to_string(common::data_dir().join("../docs/misra-deviations.md"))
        .expect("docs/misra-deviations.md");
    for rule in MISRA_DEVIATIONS {
        assert!(
            doc.contains(&format!("Rule {rule} (Advisory)")),
            "rule {rule} is deviated but not documented"
        );
    }
}

#[test]
fn c_and_vm_agree_on_every_run_case() {
    if Command::new("gcc").arg("--version").output().is_err() {
        panic!("gcc is needed to test the C back end");
    }
    let work = std::env::temp_dir().join(format!("stc-c-backend-{}", std::process::id()));
    let mut cases = common::cases(&common::data_dir().join("conformance/run"));
    cases.extend(common::cases(&common::data_dir().join("../examples")));
    let next = Mutex::new(cases.into_iter());
    let failures = Mutex::new(Vec::new());
    let compared = Mutex::new(0usize);
    std::thread::scope(|s| {
        for _ in 0..2 {
            s.spawn(|| loop {
                let Some(case) = next.lock().unwrap().next() else {
                    break;
                };
                match check_case(&case, &work) {
                    Ok(true) => *compared.lock().unwrap() += 1,
                    Ok(false) => {}
                    Err(e) => failures
                        .lock()
                        .unwrap()
                        .push(format!("{}:\n{e}", case.display())),
                }
            });
        }
    });
    let _ = std::fs::remove_dir_all(&work);
    let failures = failures.into_inner().unwrap();
    let compared = compared.into_inner().unwrap();
    assert!(
        failures.is_empty(),
        "{} of {} cases differ:\n\n{}",
        failures.len(),
        compared + failures.len(),
        failures.join("\n\n")
    );
    assert!(compared > 250, "only {compared} cases compared");
}

fn scratch(name: &str, text: &str) -> (PathBuf, String) {
    let dir = std::env::temp_dir().join(format!("stc-c-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let f = dir.join("main.st");
    std::fs::write(&f, text).unwrap();
    (dir, f.display().to_string())
}

#[test]
fn a_program_with_errors_writes_nothing() {
    let (dir, f) = scratch(
        "errors",
        "PROGRAM P\nVAR x : INT; END_VAR\nx := nothing;\nEND_PROGRAM\n",
    );
    let out_dir = dir.join("out");
    let out = stc::cli::run_args(&[
        "stc",
        "build",
        &f,
        "--emit",
        "c",
        "-o",
        &out_dir.display().to_string(),
    ]);
    assert_eq!(out.status, 1, "{}", out.stderr);
    assert!(out.stderr.contains("E0101"), "{}", out.stderr);
    assert!(!out_dir.exists());
    // Without -o there is nowhere to write a tree.
    let out = stc::cli::run_args(&["stc", "build", &f, "--emit", "c"]);
    assert_eq!(out.status, 1);
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn an_untranslated_construct_is_named_with_its_place() {
    let (dir, f) = scratch(
        "unsupported",
        "PROGRAM P\nVAR r AT %MD4 : REAL;\n  d AT %MD4 : DWORD; END_VAR\nr := 1.5;\nd := d OR 1;\nEND_PROGRAM\n",
    );
    let out_dir = dir.join("out");
    let out = stc::cli::run_args(&[
        "stc",
        "build",
        &f,
        "--emit",
        "c",
        "-o",
        &out_dir.display().to_string(),
    ]);
    assert_eq!(out.status, 1, "{}", out.stderr);
    assert!(
        out.stderr.contains(&format!(
            "{f}:3:3: error: the C back end does not translate variables of different types"
        )),
        "{}",
        out.stderr
    );
    assert!(!out_dir.exists());
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn make_builds_the_real_time_program() {
    let example = common::data_dir().join("../examples/two_tasks.st");
    let dir = std::env::temp_dir().join(format!("stc-c-make-{}", std::process::id()));
    let d = dir.display().to_string();
    let out = stc::cli::run_args(&[
        "stc",
        "build",
        &example.display().to_string(),
        "--emit",
        "c",
        "-o",
        &d,
    ]);
    assert_eq!(out.status, 0, "{}", out.stderr);
    let made = Command::new("make")
        .args(["-s", "-C", &d, "rt"])
        .output()
        .unwrap();
    assert!(
        made.status.success(),
        "make rt: {}",
        String::from_utf8_lossy(&made.stderr)
    );
    // The real-time program runs its tasks on the wall clock and reports.
    let rt = Command::new(dir.join("rt"))
        .args(["--cycles", "3", "--quiet"])
        .output()
        .unwrap();
    let text = String::from_utf8_lossy(&rt.stdout);
    assert!(
        rt.status.success(),
        "{text}{}",
        String::from_utf8_lossy(&rt.stderr)
    );
    assert!(text.contains(": 3 cycles,"), "{text}");
    let _ = std::fs::remove_dir_all(&dir);
}

/// The field side of located variables (seed 000 Fig. 3): `make rt
/// IO=field_io.c` with a test's field I/O that writes raw bits into the
/// input image arrays and prints the output arrays after each cycle. A
/// field value outside a subrange or an enumeration is a fault at its
/// address and the programs do not run on it.
#[test]
fn process_image_arrays_reach_the_field() {
    let data = common::data_dir().join("c_image");
    let dir = std::env::temp_dir().join(format!("stc-c-image-{}", std::process::id()));
    let d = dir.display().to_string();
    let out = stc::cli::run_args(&[
        "stc",
        "build",
        &data.join("process_image.st").display().to_string(),
        "--emit",
        "c",
        "-o",
        &d,
    ]);
    assert_eq!(out.status, 0, "{}", out.stderr);
    let header = std::fs::read_to_string(dir.join("program.h")).unwrap();
    for decl in [
        "extern uint8_t stc_img_I_X[2U][5U];",
        "extern uint16_t stc_img_I_W[2U][10U];",
        "extern uint64_t stc_img_I_L[2U][1U][3U];",
        "extern uint8_t stc_img_Q_X[6U][3U];",
        "extern uint32_t stc_img_Q_D[1U];",
    ] {
        assert!(header.contains(decl), "{decl} missing:\n{header}");
    }
    assert!(!header.contains("stc_img_M"), "memory has no field image");
    misra(&dir).unwrap();
    let made = Command::new("make")
        .args(["-s", "-C", &d, "rt"])
        .arg(format!("IO={}", data.join("field_io.c").display()))
        .arg(format!("CFLAGS={} -fsanitize=address", CFLAGS.join(" ")))
        .output()
        .unwrap();
    assert!(
        made.status.success(),
        "make rt: {}",
        String::from_utf8_lossy(&made.stderr)
    );
    let rt = Command::new(dir.join("rt"))
        .args(["--cycles", "4", "--quiet"])
        .output()
        .unwrap();
    let stdout = String::from_utf8_lossy(&rt.stdout);
    let stderr = String::from_utf8_lossy(&rt.stderr);
    let full = "X=0 B=ff W=fffa K=fff9 D=40400000 L1=400c000000000000 L2=3000000000";
    let lines: Vec<&str> = stdout.lines().filter(|l| l.starts_with("out ")).collect();
    assert_eq!(
        lines,
        [
            format!("out {full}"),
            // Cycles 2 and 3: USINT(0..100) got 200, Mode got 5: the
            // programs do not run, the outputs stay.
            format!("out {full}"),
            format!("out {full}"),
            format!("out {}", full.replace("B=ff", "B=b2")),
        ],
        "{stdout}{stderr}"
    );
    assert!(
        stdout.contains("4 cycles, 0 overruns, 2 faults"),
        "{stdout}"
    );
    assert!(
        stderr.contains("fault: subrange violation in %IB3 at <process image>:0:0")
            && stderr.contains("fault: subrange violation in %IW1.1 at <process image>:0:0"),
        "{stderr}"
    );
    assert_eq!(rt.status.code(), Some(3), "{stderr}");
    let _ = std::fs::remove_dir_all(&dir);
}

/// `stc run --backend ...` outside the happy path: each mistake is one
/// message and an exit status of the contract, never a crash.
#[test]
fn backend_choices_and_failures_are_reported() {
    let (dir, f) = scratch(
        "backend",
        "PROGRAM P\nVAR_OUTPUT n : INT; END_VAR\nn := n + 1;\nEND_PROGRAM\n",
    );
    let stc = |args: &[&str], cc: &str| {
        Command::new(env!("CARGO_BIN_EXE_stc"))
            .args(args)
            .env("CC", cc)
            .env_remove("STC_CFLAGS")
            .output()
            .unwrap()
    };
    // The C engine runs and prints what the VM prints.
    let c = stc(&["run", &f, "--cycles", "3", "--backend", "c"], "gcc");
    let vm = stc(&["run", &f, "--cycles", "3"], "gcc");
    assert_eq!(c.status.code(), Some(0), "{c:?}");
    assert_eq!(c.stdout, vm.stdout);
    assert_eq!(
        String::from_utf8_lossy(&c.stdout),
        "cycle 3 (T#20ms)\n  P.n = 3\n"
    );
    // The netlist runs and prints what the VM prints.
    let nl = stc(&["run", &f, "--cycles", "3", "--backend", "netlist"], "gcc");
    assert_eq!(nl.status.code(), Some(0), "{nl:?}");
    assert_eq!(nl.stdout, vm.stdout);
    // The JIT prints the same bytes.
    let jit = stc(&["run", &f, "--cycles", "3", "--backend", "jit"], "gcc");
    assert_eq!(jit.status.code(), Some(0), "{jit:?}");
    assert_eq!(jit.stdout, vm.stdout);
    // No C compiler: a usage error that says what to do.
    let o = stc(&["run", &f, "--backend", "c"], "/nonexistent/cc");
    assert_eq!(o.status.code(), Some(2), "{o:?}");
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        err.contains("cannot run the C compiler `/nonexistent/cc`") && err.contains("set CC"),
        "{err}"
    );
    // A compiler that fails.
    let o = stc(&["run", &f, "--backend", "c"], "false");
    assert_eq!(o.status.code(), Some(2), "{o:?}");
    assert!(String::from_utf8_lossy(&o.stderr).contains("`false` failed on"));
    // Bytecode runs on the VM only.
    let stbc = dir.join("p.stbc");
    let b = stc(
        &[
            "build",
            &f,
            "--emit",
            "bytecode",
            "-o",
            &stbc.display().to_string(),
        ],
        "gcc",
    );
    assert_eq!(b.status.code(), Some(0));
    let o = stc(
        &["run", &stbc.display().to_string(), "--backend", "c"],
        "gcc",
    );
    assert_eq!(o.status.code(), Some(2), "{o:?}");
    assert!(String::from_utf8_lossy(&o.stderr).contains("runs on the VM"));
    // A program the C back end does not translate: exit 1, with its place.
    let (dir2, g) = scratch(
        "backend_unsupported",
        "PROGRAM P\nVAR r AT %MD4 : REAL;\n  d AT %MD4 : DWORD; END_VAR\nr := 1.5;\nd := d OR 1;\nEND_PROGRAM\n",
    );
    let o = stc(&["run", &g, "--backend", "c"], "gcc");
    assert_eq!(o.status.code(), Some(1), "{o:?}");
    assert!(String::from_utf8_lossy(&o.stderr)
        .contains(":3:3: error: the C back end does not translate variables of different types"));
    let _ = std::fs::remove_dir_all(&dir);
    let _ = std::fs::remove_dir_all(&dir2);
}
