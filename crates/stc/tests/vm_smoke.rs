//! End-to-end smoke tests of compile → VM, independent of the runtime's
//! command line: a program runs for some cycles and its outputs are read.

use std::sync::Arc;

use stc::driver;
use stc_pipeline::Options;
use stc_values::Value;

/// Compiles `src`, runs program `prog` for `cycles` cycles of 10 ms and
/// returns the named output variables.
fn run(src: &str, prog: &str, cycles: u32, outputs: &[&str]) -> Vec<Value> {
    let mut sm = stc_diagnostics::SourceMap::new();
    sm.add("t.st", src.to_string());
    let a = stc_pipeline::analyse(sm, Vec::new(), &Options::default());
    let diags = a.all_diagnostics();
    assert!(
        diags.iter().all(|d| !d.is_error()),
        "{}",
        driver::render(&diags, &a.parsed.sources, &driver::Options::default())
    );
    let module = stc_pipeline::lower(a);
    let image = Arc::new(stc_vm::compile(&module).expect("compiles"));
    let mut m = stc_vm::Machine::new(image.clone());
    let inst = image
        .model
        .programs
        .iter()
        .find(|p| p.name.eq_ignore_ascii_case(prog))
        .expect("program")
        .clone();
    for k in 0..cycles {
        if let Err(f) = m.run_program(&inst, k as i64 * 10_000_000, 1_000_000) {
            panic!("{f}");
        }
    }
    let pou = &image.model.pous[inst.pou as usize];
    outputs
        .iter()
        .map(|name| {
            let v = pou
                .vars
                .iter()
                .find(|v| v.name.eq_ignore_ascii_case(name))
                .expect("variable");
            m.read_value(inst.offset + v.offset, v.ty)
                .expect("readable")
        })
        .collect()
}

#[test]
fn arithmetic_loops_and_calls() {
    let src = r#"
FUNCTION Sq : DINT
VAR_INPUT x : DINT; END_VAR
    Sq := x * x;
END_FUNCTION
PROGRAM Main
VAR_OUTPUT total : DINT; count : INT; r : REAL; s : STRING[20]; END_VAR
VAR i : INT; END_VAR
    total := 0;
    FOR i := 1 TO 10 DO
        total := total + Sq(i);
    END_FOR;
    count := count + 1;
    r := INT_TO_REAL(i) / 4.0;
    s := CONCAT('ab', INT_TO_STRING(count));
END_PROGRAM
"#;
    let v = run(src, "Main", 3, &["total", "count", "r", "s"]);
    assert_eq!(v[0], Value::Int(385));
    assert_eq!(v[1], Value::Int(3));
    assert_eq!(v[2], Value::Real(2.75));
    assert_eq!(v[3], Value::Str(b"ab3".to_vec()));
}

#[test]
fn timers_and_counters_from_the_prelude() {
    let src = r#"
PROGRAM Main
VAR_OUTPUT q : BOOL; et : TIME; cv : INT; END_VAR
VAR t : TON; c : CTU; tick : BOOL; END_VAR
    t(IN := TRUE, PT := T#50ms);
    q := t.Q;
    et := t.ET;
    tick := NOT tick;
    c(CU := tick, PV := 3);
    cv := c.CV;
END_PROGRAM
"#;
    // Cycle k runs at (k-1)*10ms: after 5 cycles the time is 40 ms.
    let v = run(src, "Main", 5, &["q", "et", "cv"]);
    assert_eq!(
        v,
        vec![Value::Bool(false), Value::Int(40_000_000), Value::Int(3)]
    );
    let v = run(src, "Main", 6, &["q", "et"]);
    assert_eq!(v, vec![Value::Bool(true), Value::Int(50_000_000)]);
}

#[test]
fn arrays_structs_case_and_faults() {
    let src = r#"
TYPE P : STRUCT x : INT := 1; y : INT := 2; END_STRUCT; END_TYPE
PROGRAM Main
VAR_OUTPUT sum : INT; sel : INT; p : P; END_VAR
VAR a : ARRAY[1..5] OF INT := [1, 2, 3(7)]; i : INT; END_VAR
    sum := 0;
    FOR i := 1 TO 5 DO
        sum := sum + a[i];
    END_FOR;
    CASE sum OF
        1..10: sel := 1;
        20, 21: sel := 2;
    ELSE
        sel := 3;
    END_CASE;
    p.y := p.x + sum;
END_PROGRAM
"#;
    let v = run(src, "Main", 1, &["sum", "sel"]);
    assert_eq!(v, vec![Value::Int(24), Value::Int(3)]);
}
