//! The C back end against the VM: every case of the run conformance suite
//! (and every example with `// run:` directives) is compiled both ways and
//! run in simulation with the same options plus `--format json --trace`.
//! The reports (stdout), the exit status and the fault line must be
//! identical. The generated C is compiled with `gcc -std=c99 -pedantic
//! -Wall -Wextra -Wconversion -Wshadow -Werror` and runs under
//! `-fsanitize=undefined,address`, so it must also be free of warnings and
//! of undefined behaviour on the whole suite.

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
    "-O0",
    "-fsanitize=undefined,address",
    "-fno-sanitize-recover=all",
    "-DSTC_WATCHDOG",
];

fn runtime_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../stc_codegen_c/runtime")
}

fn gcc(args: &[&str], cwd: &Path) -> Result<(), String> {
    let out = Command::new("gcc")
        .args(CFLAGS)
        .args(args)
        .current_dir(cwd)
        .output()
        .map_err(|e| format!("cannot run gcc: {e}"))?;
    if out.status.success() {
        Ok(())
    } else {
        Err(String::from_utf8_lossy(&out.stderr).into_owned())
    }
}

/// Compiles the runtime and the simulation harness once.
fn runtime_objects(dir: &Path) -> Vec<PathBuf> {
    std::fs::create_dir_all(dir).unwrap();
    let mut objs = Vec::new();
    let mut sources: Vec<PathBuf> = std::fs::read_dir(runtime_dir())
        .unwrap()
        .flatten()
        .map(|e| e.path())
        .filter(|p| {
            let n = p
                .file_name()
                .unwrap_or_default()
                .to_string_lossy()
                .into_owned();
            n == "stc_rt.c" || (n.starts_with("stc_sim") && n.ends_with(".c"))
        })
        .collect();
    sources.sort();
    for src in sources {
        let obj = dir.join(src.file_name().unwrap()).with_extension("o");
        let inc = format!("-I{}", runtime_dir().display());
        gcc(
            &[
                &inc,
                "-c",
                &src.display().to_string(),
                "-o",
                &obj.display().to_string(),
            ],
            dir,
        )
        .unwrap_or_else(|e| panic!("the runtime does not compile: {e}"));
        objs.push(obj);
    }
    objs
}

/// The fault lines of a run's stderr (warnings of the analyser are the
/// VM's alone). A watchdog fault is compared without its position: the VM
/// counts instructions, the C program loop iterations and calls, so they
/// run out at different points of the same loop (docs/c-backend.md).
fn faults(stderr: &str) -> Vec<String> {
    stderr
        .lines()
        .filter(|l| l.starts_with("fault:"))
        .map(|l| match l.split_once(" at ") {
            Some((head, _)) if l.starts_with("fault: watchdog") => head.to_string(),
            _ => l.to_string(),
        })
        .collect()
}

fn check_case(case: &Path, work: &Path, objs: &[PathBuf]) -> Result<bool, String> {
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
    gcc(&["-I.", "-c", "program.c", "-o", "program.o"], &dir)
        .map_err(|e| format!("the generated C does not compile cleanly:\n{e}"))?;
    let mut link = vec!["-o".to_string(), "sim".into(), "program.o".into()];
    link.extend(objs.iter().map(|o| o.display().to_string()));
    link.push("-lm".into());
    let link: Vec<&str> = link.iter().map(|s| s.as_str()).collect();
    gcc(&link, &dir).map_err(|e| format!("the generated C does not link:\n{e}"))?;

    let mut vm_args = vec!["stc", "run"];
    vm_args.extend(files.iter().map(|s| s.as_str()));
    vm_args.extend(options.iter().map(|s| s.as_str()));
    let vm = stc::cli::run_args(&vm_args);
    let c = Command::new(dir.join("sim"))
        .args(&options)
        .output()
        .map_err(|e| format!("cannot run the C program: {e}"))?;
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
    if c_out != vm.stdout {
        problems.push(format!(
            "reports differ:\n--- VM\n{}--- C\n{c_out}",
            vm.stdout
        ));
    }
    if faults(&vm.stderr) != faults(&c_err) {
        problems.push(format!(
            "faults differ:\n--- VM\n{}--- C\n{c_err}",
            vm.stderr
        ));
    }
    let _ = std::fs::remove_dir_all(&dir);
    if problems.is_empty() {
        Ok(true)
    } else {
        Err(format!("options {options:?}\n{}", problems.join("\n")))
    }
}

#[test]
fn c_and_vm_agree_on_every_run_case() {
    if Command::new("gcc").arg("--version").output().is_err() {
        panic!("gcc is needed to test the C back end");
    }
    let work = std::env::temp_dir().join(format!("stc-c-backend-{}", std::process::id()));
    let objs = runtime_objects(&work.join("runtime"));
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
                match check_case(&case, &work, &objs) {
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
