//! The JIT engine through the runtime's engine interface, in-process: the
//! memory is the model's data area (read back through `Memory`), faults
//! carry their site, the watchdog stops a runaway loop, and a reset
//! restores the initial state. The whole run suite is compared with the
//! VM in `crates/stc/tests/jit_backend.rs`.

use stc_engine_jit::JitEngine;
use stc_ir::FaultKind;
use stc_runtime::engine::read_value;
use stc_runtime::Engine;
use stc_values::Value;

fn engine(src: &str) -> JitEngine {
    let c = stc_pipeline::compile_text("t.st", src, &stc_pipeline::Options::default());
    let m = c.module.expect("the program compiles");
    JitEngine::build(&m).expect("the JIT compiles it")
}

/// The value of variable `name` of the first standalone program instance.
fn var(e: &JitEngine, name: &str) -> Option<Value> {
    let model = e.model().clone();
    let inst = model.programs.first()?;
    let pou = &model.pous[inst.pou as usize];
    let v = pou
        .vars
        .iter()
        .find(|v| v.name.eq_ignore_ascii_case(name))?;
    read_value(e, &model, inst.offset + v.offset, v.ty)
}

fn run(e: &mut JitEngine, steps: u64) -> Result<u64, stc_vm::VmFault> {
    let inst = e.model().programs[0].clone();
    e.run_program(&inst, 0, steps)
}

const SRC: &str = "
FUNCTION Sq : DINT
VAR_INPUT x : DINT; END_VAR
Sq := x * x;
END_FUNCTION
PROGRAM Main
VAR_OUTPUT n : DINT; s : STRING[10]; END_VAR
VAR a : ARRAY[1..4] OF DINT; i : INT; d : DINT := 1; END_VAR
FOR i := 1 TO 4 DO a[i] := Sq(i); END_FOR;
n := n + a[4];
s := CONCAT('ab', INT_TO_STRING(i));
n := n + 10 / (d - 1) * 0;
END_PROGRAM
";

#[test]
fn runs_through_the_engine_interface_and_faults_at_the_statement() {
    let mut e = engine(SRC);
    assert_eq!(e.name(), "jit");
    let f = run(&mut e, 1000).expect_err("division by zero");
    assert_eq!(f.kind, FaultKind::DivisionByZero);
    assert_eq!(
        (f.pou.as_str(), f.file.as_str(), f.line),
        ("Main", "t.st", 12)
    );
    // What ran before the fault stays written.
    assert_eq!(var(&e, "n"), Some(Value::Int(16)));
    assert_eq!(var(&e, "s"), Some(Value::Str(b"ab5".to_vec())));
    e.reset();
    assert_eq!(var(&e, "n"), Some(Value::Int(0)));
}

#[test]
fn the_watchdog_counts_loop_iterations_and_calls() {
    let mut e = engine(SRC.replace("d : DINT := 1", "d : DINT := 2").as_str());
    // Four iterations, four calls.
    assert_eq!(run(&mut e, 1000), Ok(8));
    let f = run(&mut e, 5).expect_err("watchdog");
    assert_eq!(f.kind, FaultKind::Watchdog);
}
