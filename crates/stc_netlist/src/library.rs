//! The component library of the `NOB_FLAT` dialect (docs/netlist.md): the
//! name each component kind is written with, the names of pin types, and
//! the text of constant values. One table each way, used by the writer and
//! the reader alike.

use stc_ir::FaultKind;
use stc_values::{BinOp, ElemType, Intrinsic, UnOp, Value};

use crate::circuit::Kind;

pub const INPUT: &str = "IC_MODULE-IN-U1";
pub const OUTPUT: &str = "IC_MODULE-OUT";
pub const CLOCK: &str = "IC_CLOCK";
pub const CONST: &str = "C__CONST";
pub const REGISTER: &str = "DL_UNIT-DELAY";
pub const FAULT: &str = "IC_FAULT";
pub const SWITCH: &str = "GF_SWITCH";
pub const INDEX: &str = "GF_INDEX";
pub const RANGE: &str = "LC_RANGE";
pub const CONVERT: &str = "CV_CONVERT";
pub const CALL: &str = "FN_CALL";
pub const PART_GET: &str = "BS_PART-GET";
pub const PART_SET: &str = "BS_PART-SET";

/// The binary operators and their component names.
pub const BINARY: &[(BinOp, &str)] = &[
    (BinOp::Add, "AF_ADD"),
    (BinOp::Sub, "AF_SUB"),
    (BinOp::Mul, "AF_MUL"),
    (BinOp::Div, "AF_DIV"),
    (BinOp::Mod, "AF_MOD"),
    (BinOp::Pow, "AF_EXPT"),
    (BinOp::And, "LG_AND2"),
    (BinOp::Or, "LG_OR2"),
    (BinOp::Xor, "LG_XOR2"),
    (BinOp::Eq, "LC_COMPARE-E"),
    (BinOp::Ne, "LC_COMPARE-NE"),
    (BinOp::Lt, "LC_COMPARE-L"),
    (BinOp::Le, "LC_COMPARE-LE"),
    (BinOp::Gt, "LC_COMPARE-G"),
    (BinOp::Ge, "LC_COMPARE-GE"),
];

pub const UNARY: &[(UnOp, &str)] = &[(UnOp::Neg, "AF_NEG"), (UnOp::Not, "LG_NOT")];

/// The standard functions a `FN_CALL` may name (its `FUNC` attribute);
/// the conversions take their types from their pins.
pub const FUNCTIONS: &[(Intrinsic, &str)] = {
    use Intrinsic as I;
    &[
        (I::Abs, "ABS"),
        (I::Sqrt, "SQRT"),
        (I::Ln, "LN"),
        (I::Log, "LOG"),
        (I::Exp, "EXP"),
        (I::Sin, "SIN"),
        (I::Cos, "COS"),
        (I::Tan, "TAN"),
        (I::Asin, "ASIN"),
        (I::Acos, "ACOS"),
        (I::Atan, "ATAN"),
        (I::Atan2, "ATAN2"),
        (I::Expt, "EXPT"),
        (I::Shl, "SHL"),
        (I::Shr, "SHR"),
        (I::Rol, "ROL"),
        (I::Ror, "ROR"),
        (I::Sel, "SEL"),
        (I::Max, "MAX"),
        (I::Min, "MIN"),
        (I::Limit, "LIMIT"),
        (I::Mux, "MUX"),
        (I::Move, "MOVE"),
        (I::AddTime, "ADD_TIME"),
        (I::SubTime, "SUB_TIME"),
        (I::MulTime, "MUL_TIME"),
        (I::DivTime, "DIV_TIME"),
        (I::AddTodTime, "ADD_TOD_TIME"),
        (I::AddDtTime, "ADD_DT_TIME"),
        (I::SubTodTime, "SUB_TOD_TIME"),
        (I::SubDtTime, "SUB_DT_TIME"),
        (I::SubDateDate, "SUB_DATE_DATE"),
        (I::SubTodTod, "SUB_TOD_TOD"),
        (I::SubDtDt, "SUB_DT_DT"),
        (I::ConcatDateTod, "CONCAT_DATE_TOD"),
        (I::ConcatDate, "CONCAT_DATE"),
        (I::ConcatTod, "CONCAT_TOD"),
        (I::ConcatDt, "CONCAT_DT"),
        (I::DayOfWeek, "DAY_OF_WEEK"),
        // One field of the date or time on A1: A2 is the field's index
        // (the lowering gives each output of a SPLIT call its own call).
        (I::SplitDate, "SPLIT_DATE"),
        (I::SplitTod, "SPLIT_TOD"),
        (I::SplitDt, "SPLIT_DT"),
        (I::Add, "ADD"),
        (I::Sub, "SUB"),
        (I::Mul, "MUL"),
        (I::Div, "DIV"),
        (I::Mod, "MOD"),
        (I::And, "AND"),
        (I::Or, "OR"),
        (I::Xor, "XOR"),
        (I::Not, "NOT"),
        (I::Gt, "GT"),
        (I::Ge, "GE"),
        (I::Eq, "EQ"),
        (I::Le, "LE"),
        (I::Lt, "LT"),
        (I::Ne, "NE"),
    ]
};

/// The `FUNC` name of a standard function with typed pins (conversions).
pub fn function_name(f: Intrinsic) -> Option<&'static str> {
    use Intrinsic as I;
    match f {
        I::Convert { .. } => Some("CONVERT"),
        I::Trunc { .. } => Some("TRUNC"),
        I::BcdToInt { .. } => Some("BCD_TO_INT"),
        I::IntToBcd { .. } => Some("INT_TO_BCD"),
        _ => FUNCTIONS.iter().find(|(g, _)| *g == f).map(|(_, n)| *n),
    }
}

/// The standard function named `name`, its conversion types taken from the
/// pins (`from`: A1's type, `to`: X1's).
pub fn function_of(name: &str, from: ElemType, to: ElemType) -> Option<Intrinsic> {
    use Intrinsic as I;
    match name {
        "CONVERT" => Some(I::Convert { from, to }),
        "TRUNC" => Some(I::Trunc { from, to: Some(to) }),
        "BCD_TO_INT" => Some(I::BcdToInt { from, to }),
        "INT_TO_BCD" => Some(I::IntToBcd { from, to }),
        _ => FUNCTIONS.iter().find(|(_, n)| *n == name).map(|(f, _)| *f),
    }
}

/// The library name of a component kind.
pub fn name_of(k: &Kind) -> &'static str {
    match k {
        Kind::Input { .. } => INPUT,
        Kind::Clock => CLOCK,
        Kind::Const(_) => CONST,
        Kind::Register { .. } => REGISTER,
        Kind::Output { .. } => OUTPUT,
        Kind::Fault { .. } => FAULT,
        Kind::Switch => SWITCH,
        Kind::Index { .. } => INDEX,
        Kind::Range { .. } => RANGE,
        Kind::Binary(op) => BINARY
            .iter()
            .find(|(o, _)| o == op)
            .map(|(_, n)| *n)
            .unwrap_or("AF_?"),
        Kind::Unary(op) => UNARY
            .iter()
            .find(|(o, _)| o == op)
            .map(|(_, n)| *n)
            .unwrap_or("AF_?"),
        Kind::Convert => CONVERT,
        Kind::Call(_) => CALL,
        Kind::PartGet { .. } => PART_GET,
        Kind::PartSet { .. } => PART_SET,
    }
}

/// The `PINTYPE` of nets of an elementary type: the seed's names for
/// numbers (`S16` is INT, `U32` UDINT, `F32` REAL), `B8`..`B64` for bit
/// strings, the IEC name for the others.
pub fn pin_type(t: ElemType) -> &'static str {
    use ElemType as E;
    match t {
        E::Bool => "BOOL",
        E::Sint => "S8",
        E::Int => "S16",
        E::Dint => "S32",
        E::Lint => "S64",
        E::Usint => "U8",
        E::Uint => "U16",
        E::Udint => "U32",
        E::Ulint => "U64",
        E::Real => "F32",
        E::Lreal => "F64",
        E::Byte => "B8",
        E::Word => "B16",
        E::Dword => "B32",
        E::Lword => "B64",
        other => other.name(),
    }
}

/// The elementary type of a `PINTYPE` (not STRING/WSTRING: no net has them).
pub fn type_of_pin(s: &str) -> Option<ElemType> {
    ElemType::ALL
        .iter()
        .copied()
        .filter(|t| !matches!(t, ElemType::String | ElemType::Wstring))
        .find(|t| pin_type(*t) == s)
}

/// The text of a value in the `V1`/`INIT` attributes: BOOL `1`/`0`,
/// integers and times in decimal (nanoseconds, days in seconds, as
/// `stc_values` holds them), reals in Rust's shortest round-trip form
/// (`NaN`, `inf`, `-inf`).
pub fn value_text(v: &Value) -> String {
    match v {
        Value::Bool(b) => if *b { "1" } else { "0" }.to_string(),
        Value::Int(i) => i.to_string(),
        Value::Real(x) => format!("{x:?}"),
        // (No net carries a string; kept readable all the same.)
        Value::Str(s) => String::from_utf8_lossy(s).into_owned(),
        Value::WStr(w) => String::from_utf16_lossy(w),
    }
}

/// The value of a text written by [`value_text`] for a net of type `t`.
pub fn parse_value(t: ElemType, s: &str) -> Option<Value> {
    match t {
        ElemType::Bool => match s {
            "1" => Some(Value::Bool(true)),
            "0" => Some(Value::Bool(false)),
            _ => None,
        },
        ElemType::Real | ElemType::Lreal => s.parse::<f64>().ok().map(Value::Real),
        ElemType::String | ElemType::Wstring => None,
        _ => s.parse::<i128>().ok().map(Value::Int),
    }
}

/// The name of a fault kind in an `IC_FAULT` (its code, as in the VM).
pub fn fault_code(k: FaultKind) -> u8 {
    k.code()
}
