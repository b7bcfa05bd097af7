//! The JIT against the VM: every case of the run conformance suite (and
//! every example with `// run:` directives) runs with `stc run` and with
//! `stc run --backend jit`, in-process, with the same options plus
//! `--format json --trace`. The reports (stdout), the exit status and the
//! fault line must be identical, and the JIT must really have run (no
//! note of a fallback to the VM).

mod common;

use std::path::Path;
use std::sync::Mutex;

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
    if common::comparable_reports(&jit.stdout) != common::comparable_reports(&vm.stdout) {
        problems.push(format!(
            "reports differ:\n--- VM\n{}--- JIT\n{}",
            vm.stdout, jit.stdout
        ));
    }
    if common::fault_lines(&vm.stderr) != common::fault_lines(&jit.stderr) {
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

/// Programs of the shapes that stress a code generator: deep nesting, a
/// huge CASE, long expressions, a deep loop nest. Same reports as the VM.
#[test]
fn pathological_shapes_agree_with_the_vm() {
    let mut progs = Vec::new();
    let mut s = String::from("PROGRAM Main\nVAR_OUTPUT x : DINT; END_VAR\n");
    for k in 0..200 {
        s += &format!("IF x >= {} THEN x := x + 1;\n", k - 1);
    }
    s += "x := x + 1000;\n";
    s += &"END_IF;\n".repeat(200);
    progs.push(("deep_if", s + "END_PROGRAM\n"));
    let mut s = String::from(
        "PROGRAM Main\nVAR_OUTPUT x : DINT; c : DINT; END_VAR\nc := c + 7;\nCASE c MOD 3000 OF\n",
    );
    for k in 0..3000 {
        s += &format!("{k}: x := x + {};\n", k * 3);
    }
    progs.push(("huge_case", s + "ELSE x := -1;\nEND_CASE;\nEND_PROGRAM\n"));
    let terms: Vec<String> = (0..2000)
        .map(|k| format!("{k}.5 * DINT_TO_LREAL(a)"))
        .collect();
    let ints: Vec<String> = (0..2000).map(|k| format!("a * {k}")).collect();
    progs.push((
        "long_expr",
        format!(
            "PROGRAM Main\nVAR_OUTPUT x : LREAL; y : DINT; z : DINT; END_VAR\nVAR a : DINT := 3; END_VAR\nx := {};\ny := {}a{};\nz := {};\nEND_PROGRAM\n",
            terms.join(" + "),
            "(".repeat(250),
            " + 1)".repeat(250),
            ints.join(" + ")
        ),
    ));
    let vars: Vec<String> = (0..60).map(|k| format!("i{k}")).collect();
    let mut s = format!(
        "PROGRAM Main\nVAR_OUTPUT x : DINT; END_VAR\nVAR {} : DINT; END_VAR\n",
        vars.join(", ")
    );
    for k in 0..60 {
        s += &format!("FOR i{k} := 1 TO {} DO\n", if k >= 55 { 2 } else { 1 });
    }
    s += "x := x + 1;\n";
    s += &"END_FOR;\n".repeat(60);
    progs.push(("deep_for", s + "END_PROGRAM\n"));

    let dir = std::env::temp_dir().join(format!("stc-jit-shapes-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    for (name, src) in progs {
        let f = dir.join(format!("{name}.st"));
        std::fs::write(&f, src).unwrap();
        let f = f.display().to_string();
        let args = [
            "stc", "run", &f, "--cycles", "3", "--format", "json", "--trace",
        ];
        let vm = stc::cli::run_args(&args);
        let mut jit_args = args.to_vec();
        jit_args.extend(["--backend", "jit"]);
        let jit = stc::cli::run_args(&jit_args);
        assert_eq!(vm.status, 0, "{name}: {}", vm.stderr);
        assert_eq!(
            (jit.status, &jit.stdout, &jit.stderr),
            (vm.status, &vm.stdout, &vm.stderr),
            "{name}"
        );
    }
    let _ = std::fs::remove_dir_all(&dir);
}
