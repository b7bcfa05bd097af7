//! The JIT against the VM: every case of the run conformance suite (and
//! every example with `// run:` directives) runs with `stc run` and with
//! `stc run --backend jit`, in-process, with the same options plus
//! `--format json --trace`. The reports (stdout), the exit status and the
//! fault line must be identical, and the JIT must really have run (no
//! note of a fallback to the VM).

mod common;

use std::path::Path;
use std::sync::Mutex;

/// The fault lines of a run's stderr. A watchdog fault is compared without
/// its position: the VM counts instructions, the JIT loop iterations and
/// calls (docs/runtime.md).
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

fn check_case(case: &Path) -> Result<bool, String> {
    let Some(mut options) = common::run_options(case)? else {
        return Ok(false);
    };
    options.extend(["--format".to_string(), "json".into(), "--trace".into()]);
    let files: Vec<String> = common::case_files(case)
        .iter()
        .map(|f| f.display().to_string())
        .collect();
    let mut vm_args = vec!["stc", "run"];
    vm_args.extend(files.iter().map(|s| s.as_str()));
    vm_args.extend(options.iter().map(|s| s.as_str()));
    let vm = stc::cli::run_args(&vm_args);
    let mut jit_args = vm_args.clone();
    jit_args.extend(["--backend", "jit"]);
    let jit = stc::cli::run_args(&jit_args);
    let mut problems = Vec::new();
    if jit.stderr.contains("--backend jit:") {
        problems.push(format!("the JIT did not run:\n{}", jit.stderr));
    }
    if jit.status != vm.status {
        problems.push(format!(
            "exit status: VM {}, JIT {}\nJIT stderr: {}",
            vm.status, jit.status, jit.stderr
        ));
    }
    if jit.stdout != vm.stdout {
        problems.push(format!(
            "reports differ:\n--- VM\n{}--- JIT\n{}",
            vm.stdout, jit.stdout
        ));
    }
    if faults(&vm.stderr) != faults(&jit.stderr) {
        problems.push(format!(
            "faults differ:\n--- VM\n{}--- JIT\n{}",
            vm.stderr, jit.stderr
        ));
    }
    if problems.is_empty() {
        Ok(true)
    } else {
        Err(format!("options {options:?}\n{}", problems.join("\n")))
    }
}

#[test]
fn jit_and_vm_agree_on_every_run_case() {
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
                match check_case(&case) {
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
    let failures = failures.into_inner().unwrap();
    let compared = compared.into_inner().unwrap();
    eprintln!("{compared} cases compared, {} differ", failures.len());
    assert!(
        failures.is_empty(),
        "{} of {} cases differ:\n\n{}",
        failures.len(),
        compared + failures.len(),
        failures.join("\n\n")
    );
    assert!(compared > 250, "only {compared} cases compared");
}
