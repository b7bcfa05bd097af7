//! `stc_codes.h`: the numeric codes the generated C shares with the Rust
//! side of stc, written from the Rust enumerations that define them
//! (elementary types, type descriptor kinds, variable kinds, POU kinds,
//! fault kinds),
//! so C and Rust cannot drift apart. Every output directory gets this
//! text; `runtime/stc_codes.h` is a copy for the hand-written runtime's own
//! tests, kept equal to it by a test (`STC_BLESS=1` rewrites it).

use std::fmt::Write;

use stc_ir::model::{PouKind, TypeDescKind, VarKind};
use stc_ir::FaultKind;
use stc_syntax::token::ElemType;

/// `STC_VK_FIELD`: the kind of a member of a STRUCT, which exists only in
/// the C tables (the VM describes struct members as fields, not variables).
pub const VK_FIELD: u8 = 9;

/// The C name of a fault kind (`STC_FAULT_` + this).
pub fn fault_name(k: FaultKind) -> &'static str {
    match k {
        FaultKind::DivisionByZero => "DIVISION_BY_ZERO",
        FaultKind::IndexOutOfBounds => "INDEX",
        FaultKind::SubrangeViolation => "SUBRANGE",
        FaultKind::Conversion => "CONVERSION",
        FaultKind::MuxRange => "MUX",
        FaultKind::ForStepZero => "FOR_STEP_ZERO",
        FaultKind::Watchdog => "WATCHDOG",
        FaultKind::InvalidCode => "INVALID_CODE",
        FaultKind::NullReference => "NULL_REFERENCE",
        FaultKind::PointerBounds => "POINTER_BOUNDS",
    }
}

fn var_kind_name(k: VarKind) -> &'static str {
    match k {
        VarKind::Input => "INPUT",
        VarKind::Output => "OUTPUT",
        VarKind::InOut => "INOUT",
        VarKind::Var => "VAR",
        VarKind::Temp => "TEMP",
        VarKind::External => "EXTERNAL",
        VarKind::Global => "GLOBAL",
        VarKind::Result => "RESULT",
        VarKind::Hidden => "HIDDEN",
    }
}

fn pou_kind_name(k: PouKind) -> &'static str {
    match k {
        PouKind::Function => "FUNCTION",
        PouKind::FunctionBlock => "FUNCTION_BLOCK",
        PouKind::Program => "PROGRAM",
    }
}

fn type_kind_name(k: TypeDescKind) -> &'static str {
    match k {
        TypeDescKind::Scalar => "SCALAR",
        TypeDescKind::String => "STRING",
        TypeDescKind::Enum => "ENUM",
        TypeDescKind::Array => "ARRAY",
        TypeDescKind::Struct => "STRUCT",
        TypeDescKind::Instance => "INSTANCE",
        TypeDescKind::Subrange => "SUBRANGE",
    }
}

fn enumeration(out: &mut String, comment: &str, items: &[(String, u32)]) {
    let _ = writeln!(out, "\n/* {comment} */\nenum {{");
    for (i, (name, value)) in items.iter().enumerate() {
        let sep = if i + 1 < items.len() { "," } else { "" };
        let _ = writeln!(out, "    {name} = {value}{sep}");
    }
    out.push_str("};\n");
}

/// The text of `stc_codes.h`.
pub fn header() -> String {
    let mut out = String::from(
        "/*\n * stc_codes.h - the numeric codes shared by the generated C, its runtime\n \
         * and the Rust side of stc. Written by stc (stc_codegen_c::codes) from\n \
         * the Rust enumerations that define them; do not edit.\n */\n\
         #ifndef STC_CODES_H\n#define STC_CODES_H\n",
    );
    let elems: Vec<(String, u32)> = ElemType::ALL
        .iter()
        .map(|e| (format!("STC_E_{}", e.name()), u32::from(e.code())))
        .collect();
    enumeration(
        &mut out,
        "Elementary types (stc_syntax::token::ElemType).",
        &elems,
    );
    let kinds: Vec<(String, u32)> = TypeDescKind::ALL
        .iter()
        .map(|&k| (format!("STC_TK_{}", type_kind_name(k)), u32::from(k.code())))
        .collect();
    enumeration(
        &mut out,
        "Kinds of type descriptors (stc_ir::model::TypeDescKind).",
        &kinds,
    );
    let mut vars: Vec<(String, u32)> = VarKind::ALL
        .iter()
        .map(|&k| (format!("STC_VK_{}", var_kind_name(k)), u32::from(k.code())))
        .collect();
    vars.push(("STC_VK_FIELD".into(), u32::from(VK_FIELD)));
    enumeration(
        &mut out,
        "Kinds of variables (stc_ir::model::VarKind); STC_VK_FIELD: a member of a STRUCT.",
        &vars,
    );
    let pous: Vec<(String, u32)> = PouKind::ALL
        .iter()
        .map(|&k| (format!("STC_PK_{}", pou_kind_name(k)), u32::from(k.code())))
        .collect();
    enumeration(
        &mut out,
        "Kinds of POUs (stc_ir::model::PouKind), in the elem of an INSTANCE type.",
        &pous,
    );
    let mut faults = vec![("STC_FAULT_NONE".to_string(), 0)];
    faults.extend(
        FaultKind::ALL
            .iter()
            .map(|&k| (format!("STC_FAULT_{}", fault_name(k)), u32::from(k.code()))),
    );
    let n = FaultKind::ALL.iter().map(|k| k.code()).max().unwrap_or(0) + 1;
    faults.push(("STC_N_FAULT_KINDS".into(), u32::from(n)));
    enumeration(
        &mut out,
        "Fault kinds (stc_ir::FaultKind); the texts are in stc_fault_text().\n   STC_N_FAULT_KINDS: the number of codes, STC_FAULT_NONE included.",
        &faults,
    );
    out.push_str("\n#endif\n");
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_runtime_copy_is_the_generated_text() {
        let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("runtime/stc_codes.h");
        let want = header();
        if std::env::var_os("STC_BLESS").is_some() {
            std::fs::write(&path, &want).expect("runtime/stc_codes.h is writable");
        }
        let got = std::fs::read_to_string(&path).unwrap_or_default();
        assert!(
            got == want,
            "runtime/stc_codes.h differs from stc_codegen_c::codes::header(); \
             rerun with STC_BLESS=1 to rewrite it:\n{want}"
        );
    }

    #[test]
    fn the_c_only_field_kind_is_free() {
        assert!(VarKind::ALL.iter().all(|k| k.code() != VK_FIELD));
    }
}
