//! The bytecode file and VMASM text round-trip exactly, for every program of
//! the run conformance suite; and corrupted files are rejected cleanly.

mod common;

use stc_pipeline::Options;

fn compile(case: &std::path::Path) -> Option<stc_vm::Image> {
    let (sm, diags) = stc::sources::load(&common::case_files(case)).ok()?;
    let a =
        stc_pipeline::with_big_stack(move || stc_pipeline::analyse(sm, diags, &Options::default()));
    if a.all_diagnostics().iter().any(|d| d.is_error()) {
        return None;
    }
    let m = stc_pipeline::lower(a);
    Some(stc_vm::compile(&m).expect("compiles"))
}

#[test]
fn binary_and_vmasm_round_trip_every_run_case() {
    common::run_all(&common::data_dir().join("conformance/run"), |case| {
        let Some(img) = compile(case) else {
            return Ok(());
        };
        let bytes = stc_vm::format::encode(&img);
        let back = stc_vm::format::decode(&bytes).map_err(|e| format!("decode: {e}"))?;
        if back != img {
            return Err("binary round trip changed the image".into());
        }
        let text = stc_vm::asm::disassemble(&img);
        let again = stc_vm::asm::assemble(&text).map_err(|e| format!("assemble: {e}"))?;
        if again != img {
            return Err("VMASM round trip changed the image".into());
        }
        Ok(())
    });
}

#[test]
fn corrupted_files_are_rejected_not_run() {
    let case = common::data_dir().join("ir/calls.st");
    let img = compile(&case).expect("the sample compiles");
    let good = stc_vm::format::encode(&img);
    assert!(matches!(
        stc_vm::format::decode(&good[..10]),
        Err(stc_vm::format::LoadError::Magic)
    ));
    let mut bad = good.clone();
    bad[4] = 9;
    assert!(matches!(
        stc_vm::format::decode(&bad),
        Err(stc_vm::format::LoadError::Version(_))
    ));
    let mut bad = good.clone();
    let last = bad.len() - 1;
    bad[last] ^= 0x55;
    assert_eq!(
        stc_vm::format::decode(&bad),
        Err(stc_vm::format::LoadError::Checksum)
    );
    // A jump out of its POU, with a valid checksum: the verifier refuses it.
    let mut img2 = img.clone();
    let pc = img2
        .code
        .iter()
        .position(|i| matches!(i, stc_vm::instr::Instr::Jz { .. }))
        .expect("a jump");
    if let stc_vm::instr::Instr::Jz { t, .. } = &mut img2.code[pc] {
        t.0 = 1_000_000;
    }
    let err = stc_vm::format::decode(&stc_vm::format::encode(&img2)).unwrap_err();
    assert!(
        matches!(err, stc_vm::format::LoadError::Invalid(_)),
        "{err}"
    );
    // An operand outside its frame.
    let mut img3 = img.clone();
    img3.code[0] = stc_vm::instr::Instr::Mov8 {
        d: stc_vm::instr::Op::frame(1 << 20),
        a: stc_vm::instr::Op::frame(0),
    };
    assert!(matches!(
        stc_vm::format::decode(&stc_vm::format::encode(&img3)),
        Err(stc_vm::format::LoadError::Invalid(_))
    ));
}

#[test]
fn call_chains_deeper_than_the_interpreter_allows_are_refused() {
    let chain = |n: usize| {
        let mut src = String::new();
        for i in 0..n {
            let body = if i + 1 < n {
                format!("F{i} := F{}(x + 1);", i + 1)
            } else {
                format!("F{i} := x;")
            };
            src.push_str(&format!(
                "FUNCTION F{i} : INT\nVAR_INPUT x : INT; END_VAR\n{body}\nEND_FUNCTION\n"
            ));
        }
        src.push_str("PROGRAM Main\nVAR_OUTPUT r : INT; END_VAR\nr := F0(0);\nEND_PROGRAM\n");
        let mut sm = stc_diagnostics::SourceMap::new();
        sm.add("deep.st", src);
        let a = stc_pipeline::with_big_stack(move || {
            stc_pipeline::analyse(sm, Vec::new(), &Options::default())
        });
        assert!(!a.all_diagnostics().iter().any(|d| d.is_error()));
        let img = stc_vm::compile(&stc_pipeline::lower(a)).expect("compiles");
        stc_vm::format::decode(&stc_vm::format::encode(&img))
    };
    // Main plus 1 023 nested calls fits; one more level does not.
    assert!(chain(1023).is_ok());
    let err = chain(1024).unwrap_err();
    assert!(err.to_string().contains("nest deeper"), "{err}");
}
