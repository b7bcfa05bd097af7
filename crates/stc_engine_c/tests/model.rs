//! The program model the C engine reads back from the generated library's
//! `stc_meta.h` tables is the model `stc_ir::model` built for the VM, in
//! the same numbering: only the addresses and sizes of C objects differ
//! (C's `offsetof` and pointers against the model's data area).

use stc_engine_c::{CEngine, Toolchain};
use stc_ir::model::{Model, ProgramInst, Source, TypeDesc};
use stc_runtime::Engine;

/// The model with every address, offset and size set to 0.
fn shape(m: &Model) -> Model {
    let mut m = m.clone();
    for t in &mut m.types {
        match t {
            TypeDesc::Struct { fields, .. } => fields.iter_mut().for_each(|f| f.offset = 0),
            TypeDesc::Array { stride, .. } => *stride = 0,
            _ => {}
        }
    }
    for p in &mut m.pous {
        p.instance_size = 0;
        p.vars.iter_mut().for_each(|v| v.offset = 0);
    }
    m.globals.iter_mut().for_each(|g| g.offset = 0);
    m.io.iter_mut().for_each(|s| s.offset = 0);
    let clear = |p: &mut ProgramInst| {
        p.offset = 0;
        for (off, _, Source::Addr { offset, .. }) in p.inputs.iter_mut().chain(p.outputs.iter_mut())
        {
            *off = 0;
            *offset = 0;
        }
    };
    m.programs.iter_mut().for_each(clear);
    for c in &mut m.configs {
        for r in &mut c.resources {
            r.programs.iter_mut().for_each(clear);
            for t in &mut r.tasks {
                if let Some(Source::Addr { offset, .. }) = &mut t.single {
                    *offset = 0;
                }
            }
        }
    }
    m
}

fn check(name: &str, text: &str) {
    let compiled = stc_pipeline::compile_text(name, text, &stc_pipeline::Options::default());
    let Some(module) = compiled.module else {
        panic!("{name} does not compile: {:?}", compiled.diagnostics);
    };
    let image = stc_vm::compile(&module).expect("the VM compiles it");
    let sources = compiled.sources;
    let locate = |sp: stc_diagnostics::Span| {
        sources
            .locate(sp.lo)
            .map(|(f, lc)| (f.name.clone(), lc.line, lc.col))
    };
    let engine = CEngine::build(&module, &locate, &Toolchain::default())
        .unwrap_or_else(|e| panic!("{name}: the C engine does not build it: {e}"));
    let vm = shape(&image.model);
    let c = shape(engine.model());
    assert_eq!(vm.types, c.types, "{name}: types");
    assert_eq!(vm.pous.len(), c.pous.len(), "{name}: POUs");
    for (a, b) in vm.pous.iter().zip(&c.pous) {
        assert_eq!(a, b, "{name}: POU {}", a.name);
    }
    assert_eq!(vm.globals, c.globals, "{name}: globals");
    assert_eq!(vm.io, c.io, "{name}: process image");
    assert_eq!(vm.programs, c.programs, "{name}: programs");
    assert_eq!(vm.configs, c.configs, "{name}: configurations");
}

const PLANT: &str = r#"
TYPE
    Mode : (Off, Manual, Auto) := Manual;
    Level : INT (0..100);
    Reading : STRUCT
        value : REAL;
        ok : BOOL;
        tag : STRING[8];
        hist : ARRAY[1..4] OF Level;
    END_STRUCT;
END_TYPE

VAR_GLOBAL
    shared : DINT := 7;
    lamp AT %QX0.1 : BOOL;
END_VAR

FUNCTION Scale : REAL
    VAR_INPUT x : INT; k : REAL; END_VAR
    VAR tmp : REAL; END_VAR
    tmp := INT_TO_REAL(x) * k;
    Scale := tmp;
END_FUNCTION

FUNCTION_BLOCK Counter
    VAR_INPUT step : INT := 1; END_VAR
    VAR_IN_OUT total : DINT; END_VAR
    VAR_OUTPUT n : INT; END_VAR
    VAR_EXTERNAL shared : DINT; END_VAR
    VAR_TEMP t : INT; END_VAR
    VAR last : REF_TO DINT; refs : ARRAY[1..2] OF REF_TO INT; END_VAR
    METHOD Reset : INT
        VAR_INPUT v : INT; END_VAR
        n := v;
        Reset := n;
    END_METHOD
    t := step;
    n := n + t;
    total := total + shared;
    last := REF(shared);
    refs[1] := NULL;
END_FUNCTION_BLOCK

PROGRAM Main
    VAR_INPUT go : BOOL; END_VAR
    VAR_OUTPUT out : REAL; END_VAR
    VAR
        c : Counter;
        sum : DINT;
        r : Reading;
        m : Mode;
        w : WSTRING[4] := "ab";
        sensor AT %IW2 : INT;
        tm : TON;
    END_VAR
    VAR_EXTERNAL shared : DINT; lamp : BOOL; END_VAR
    c(step := 2, total := sum);
    c.Reset(v := 1);
    out := Scale(c.n, 0.5);
    r.hist[2] := 3;
    lamp := go AND sensor > 0;
    tm(IN := go, PT := T#1s);
END_PROGRAM

CONFIGURATION Plant
    VAR_GLOBAL trig : BOOL; level : INT := 3; END_VAR
    RESOURCE Cpu ON PLC
        TASK fast (INTERVAL := T#10ms, PRIORITY := 1);
        TASK ev (SINGLE := trig, PRIORITY := 2);
        PROGRAM main1 WITH fast : Main (go := trig);
        PROGRAM main2 WITH ev : Main;
    END_RESOURCE
END_CONFIGURATION
"#;

#[test]
fn a_plant_with_every_kind_of_table_entry_has_one_model() {
    check("plant.st", PLANT);
}

#[test]
fn the_examples_have_one_model() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples");
    let mut n = 0;
    for e in std::fs::read_dir(&dir).expect("examples") {
        let path = e.expect("entry").path();
        if path.extension().is_some_and(|x| x == "st") {
            let text = std::fs::read_to_string(&path).expect("readable");
            check(&path.display().to_string(), &text);
            n += 1;
        }
    }
    assert!(n >= 4, "only {n} examples");
}
