//! The one definition of what every operator, conversion and standard
//! function computes on values of elementary types.
//!
//! Constant folding in the analyser, the bytecode VM (for everything that is
//! not a hot arithmetic path) and the differential tests of the C back end
//! all call this crate, so a program means the same thing everywhere. The
//! rules come from spec/semantics.md; where the spec is silent the decision
//! is written, with its reason, in docs/semantics-notes.md.
//!
//! A [`Value`] carries no type: the caller always passes the [`ElemType`]
//! alongside, as the typed IR knows it. Nothing here panics on any value:
//! integer arithmetic is checked or explicitly wrapping, and a request the
//! analyser would never make (a value of the wrong kind for its type, a
//! conversion the standard does not allow) answers
//! `Err(Fault::Conversion)` instead of crashing.
//!
//! [`types`] answers questions about types (widths, ranges, generic
//! families, implicit widening); [`ops`] evaluates the operators;
//! [`mod@convert`] the `*_TO_*` family, TRUNC and BCD; [`text`] prints values
//! and parses them back; [`stdfn`] is the table of standard functions
//! (signatures for the analyser, [`Intrinsic`] ids for the back ends) and
//! [`mod@call`] evaluates them.

pub mod call;
pub mod convert;
pub mod ops;
pub mod stdfn;
pub mod text;
pub mod types;

pub use stc_syntax::token::{ElemType, GenericType};

pub use call::{call, split, split_lookup};
pub use convert::{
    bcd_to_int, conversion_allowed, conversion_is_extension, conversion_may_fault, convert,
    int_to_bcd, trunc,
};
pub use ops::{binary, unary};
pub use stdfn::{all, lookup, Intrinsic, Param, StdFunction, TyPat};
pub use text::{parse_value, string_text, to_text, truncate};
pub use types::{
    bits, common_type, default_value, implicit_widening, in_family, int_range, is_bit_string,
    is_integer, is_real, is_signed, is_time_like, wrap,
};

/// A value of an elementary type. The [`ElemType`] is always supplied by the
/// caller alongside; the representation is:
///
/// | type | variant | meaning |
/// | --- | --- | --- |
/// | BOOL | `Bool` | |
/// | SINT..ULINT, BYTE..LWORD, CHAR, WCHAR, enumeration values | `Int` | always normalised into the type's range (BYTE 0..=255, SINT -128..=127, CHAR its code) |
/// | TIME, LTIME | `Int` | nanoseconds, i64 range |
/// | DATE, LDATE | `Int` | seconds since 1970-01-01, a multiple of 86400 |
/// | TOD, LTOD | `Int` | nanoseconds since midnight, `0..86_400e9` |
/// | DT, LDT | `Int` | nanoseconds since 1970-01-01T00:00:00, i64 range |
/// | REAL | `Real` | an f64 holding an exact f32 value |
/// | LREAL | `Real` | |
/// | STRING | `Str` | bytes, Windows-1252 |
/// | WSTRING | `WStr` | UTF-16 code units |
#[derive(Clone, Debug, PartialEq)]
pub enum Value {
    Bool(bool),
    Int(i128),
    Real(f64),
    Str(Vec<u8>),
    WStr(Vec<u16>),
}

impl Value {
    /// The integer of an `Int` (or 0/1 of a `Bool`).
    pub fn as_int(&self) -> Option<i128> {
        match *self {
            Value::Int(i) => Some(i),
            Value::Bool(b) => Some(b as i128),
            _ => None,
        }
    }

    /// The number of a `Real`.
    pub fn as_real(&self) -> Option<f64> {
        match *self {
            Value::Real(x) => Some(x),
            _ => None,
        }
    }

    /// The truth of a `Bool`.
    pub fn as_bool(&self) -> Option<bool> {
        match *self {
            Value::Bool(b) => Some(b),
            _ => None,
        }
    }

    /// A STRING value from Rust text, in Windows-1252 (characters it cannot
    /// encode become `?`, which cannot happen for the ASCII texts this crate
    /// produces).
    pub fn string(s: &str) -> Value {
        Value::Str(
            s.chars()
                .map(|c| stc_syntax::literal::cp1252_encode(c).unwrap_or(b'?'))
                .collect(),
        )
    }

    /// A WSTRING value from Rust text.
    pub fn wstring(s: &str) -> Value {
        Value::WStr(s.encode_utf16().collect())
    }
}

/// Run-time faults (spec/semantics.md "Run-time faults").
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Fault {
    DivisionByZero,
    Conversion,
    MuxRange,
}

impl Fault {
    /// The text `stc run` prints after `fault:` (spec/cli.md).
    pub fn kind(self) -> &'static str {
        match self {
            Fault::DivisionByZero => "division by zero",
            Fault::Conversion => "conversion failure",
            Fault::MuxRange => "MUX selector out of range",
        }
    }
}

impl std::fmt::Display for Fault {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.kind())
    }
}

impl std::error::Error for Fault {}

/// A computed value and whether integer wrap-around happened (for the
/// constant folder's overflow warning).
#[derive(Clone, Debug, PartialEq)]
pub struct Outcome {
    pub value: Value,
    pub overflow: bool,
}

impl Outcome {
    /// A result that involved no wrap-around.
    pub fn exact(value: Value) -> Outcome {
        Outcome {
            value,
            overflow: false,
        }
    }
}

/// Binary operators of ST (`**` is `Pow`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum BinOp {
    Add,
    Sub,
    Mul,
    Div,
    Mod,
    Pow,
    And,
    Or,
    Xor,
    Eq,
    Ne,
    Lt,
    Le,
    Gt,
    Ge,
}

/// Unary operators of ST.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum UnOp {
    Neg,
    Not,
}

/// What an ill-typed request answers: the analyser never makes one, and a
/// library must not panic, so it becomes a conversion failure.
pub(crate) fn misuse<T>() -> Result<T, Fault> {
    Err(Fault::Conversion)
}
