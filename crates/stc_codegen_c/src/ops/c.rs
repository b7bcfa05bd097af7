//! How values look in C: the representation of each elementary type
//! (`runtime/stc_meta.h`), literals, casts and the small statement
//! patterns every operation uses.

use super::Emit;
use stc_sema::{TypeId, TypeKind};
use stc_syntax::token::ElemType;

use ElemType as E;

/// The C representation of a scalar.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
pub(crate) enum Rep {
    I8,
    I16,
    I32,
    I64,
    U8,
    U16,
    U32,
    U64,
    F32,
    F64,
}

impl Rep {
    pub(crate) fn of(e: ElemType) -> Option<Rep> {
        Some(match e {
            E::Sint => Rep::I8,
            E::Int => Rep::I16,
            E::Dint => Rep::I32,
            E::Lint
            | E::Time
            | E::Ltime
            | E::Date
            | E::Ldate
            | E::Tod
            | E::Ltod
            | E::Dt
            | E::Ldt => Rep::I64,
            E::Bool | E::Usint | E::Byte | E::Char => Rep::U8,
            E::Uint | E::Word | E::Wchar => Rep::U16,
            E::Udint | E::Dword => Rep::U32,
            E::Ulint | E::Lword => Rep::U64,
            E::Real => Rep::F32,
            E::Lreal => Rep::F64,
            E::String | E::Wstring => return None,
        })
    }

    /// The suffix of the runtime's functions (`stc_add_i32`).
    pub(crate) fn sfx(self) -> &'static str {
        match self {
            Rep::I8 => "i8",
            Rep::I16 => "i16",
            Rep::I32 => "i32",
            Rep::I64 => "i64",
            Rep::U8 => "u8",
            Rep::U16 => "u16",
            Rep::U32 => "u32",
            Rep::U64 => "u64",
            Rep::F32 => "f32",
            Rep::F64 => "f64",
        }
    }

    pub(crate) fn ctype(self) -> &'static str {
        match self {
            Rep::I8 => "int8_t",
            Rep::I16 => "int16_t",
            Rep::I32 => "int32_t",
            Rep::I64 => "int64_t",
            Rep::U8 => "uint8_t",
            Rep::U16 => "uint16_t",
            Rep::U32 => "uint32_t",
            Rep::U64 => "uint64_t",
            Rep::F32 => "float",
            Rep::F64 => "double",
        }
    }

    pub(crate) fn bits(self) -> u32 {
        match self {
            Rep::I8 | Rep::U8 => 8,
            Rep::I16 | Rep::U16 => 16,
            Rep::I32 | Rep::U32 | Rep::F32 => 32,
            Rep::I64 | Rep::U64 | Rep::F64 => 64,
        }
    }

    pub(crate) fn signed(self) -> bool {
        matches!(self, Rep::I8 | Rep::I16 | Rep::I32 | Rep::I64)
    }

    pub(crate) fn float(self) -> bool {
        matches!(self, Rep::F32 | Rep::F64)
    }

    /// The unsigned representation of the same width.
    pub(crate) fn unsigned(self) -> Rep {
        match self {
            Rep::I8 | Rep::U8 => Rep::U8,
            Rep::I16 | Rep::U16 => Rep::U16,
            Rep::I32 | Rep::U32 | Rep::F32 => Rep::U32,
            Rep::I64 | Rep::U64 | Rep::F64 => Rep::U64,
        }
    }
}

/// The `enum stc_elem` constant of an elementary type (stc_meta.h).
pub(crate) fn elem_code(e: ElemType) -> &'static str {
    match e {
        E::Bool => "STC_E_BOOL",
        E::Sint => "STC_E_SINT",
        E::Int => "STC_E_INT",
        E::Dint => "STC_E_DINT",
        E::Lint => "STC_E_LINT",
        E::Usint => "STC_E_USINT",
        E::Uint => "STC_E_UINT",
        E::Udint => "STC_E_UDINT",
        E::Ulint => "STC_E_ULINT",
        E::Real => "STC_E_REAL",
        E::Lreal => "STC_E_LREAL",
        E::Byte => "STC_E_BYTE",
        E::Word => "STC_E_WORD",
        E::Dword => "STC_E_DWORD",
        E::Lword => "STC_E_LWORD",
        E::Time => "STC_E_TIME",
        E::Ltime => "STC_E_LTIME",
        E::Date => "STC_E_DATE",
        E::Ldate => "STC_E_LDATE",
        E::Tod => "STC_E_TOD",
        E::Ltod => "STC_E_LTOD",
        E::Dt => "STC_E_DT",
        E::Ldt => "STC_E_LDT",
        E::String => "STC_E_STRING",
        E::Wstring => "STC_E_WSTRING",
        E::Char => "STC_E_CHAR",
        E::Wchar => "STC_E_WCHAR",
    }
}

/// `(uint8_t)STC_E_INT`: the argument form of a type code.
pub(crate) fn elem_arg(e: ElemType) -> String {
    format!("(uint8_t){}", elem_code(e))
}

/// A C literal of `v` for a variable of representation `r` (in range).
pub(crate) fn lit(r: Rep, v: i128) -> String {
    match r {
        Rep::I8 | Rep::I16 | Rep::I32 => {
            if v == i128::from(i32::MIN) {
                "INT32_MIN".into()
            } else {
                format!("{v}")
            }
        }
        // Plain suffixed literals rather than INT64_C/UINT64_C, whose
        // expansion hides the `U` from MISRA checkers (rule 7.2).
        Rep::I64 => {
            if v == i128::from(i64::MIN) {
                "(-9223372036854775807LL - 1LL)".into()
            } else {
                format!("{v}LL")
            }
        }
        Rep::U8 | Rep::U16 | Rep::U32 => format!("{v}U"),
        Rep::U64 => format!("{v}ULL"),
        Rep::F32 => format!("{v}.0f"),
        Rep::F64 => format!("{v}.0"),
    }
}

/// A zero of representation `r`.
pub(crate) fn zero(r: Rep) -> &'static str {
    if r.signed() {
        "0"
    } else if r.float() {
        "0.0"
    } else {
        "0U"
    }
}

/// The value range of an integer-like elementary type.
pub(crate) fn range(e: ElemType) -> Option<(i128, i128)> {
    stc_values::int_range(e)
}

/// An operand or the destination: its C expression and types.
#[derive(Clone, Debug)]
pub(crate) struct Val {
    pub x: String,
    pub ty: TypeId,
    /// The elementary type of the representation (an enumeration's or a
    /// subrange's base; STRING/WSTRING for strings); `None` for aggregates.
    pub elem: Option<ElemType>,
}

impl Val {
    pub(crate) fn rep(&self) -> Option<Rep> {
        self.elem.and_then(Rep::of)
    }

    /// The expression in parentheses (safe to cast or index).
    pub(crate) fn p(&self) -> String {
        paren(&self.x)
    }
}

pub(crate) fn paren(x: &str) -> String {
    let simple = x
        .bytes()
        .all(|b| b.is_ascii_alphanumeric() || b == b'_' || b == b'.');
    if simple {
        x.to_string()
    } else {
        format!("({x})")
    }
}

/// The capacity of a string type (0 when not a string).
pub(crate) fn cap_of(e: &dyn Emit, t: TypeId) -> u32 {
    match e.module().types.kind(t) {
        TypeKind::String { len, .. } => *len,
        _ => 0,
    }
}

pub(crate) fn elem_of(e: &dyn Emit, t: TypeId) -> Option<ElemType> {
    e.module().types.scalar(t)
}

/// The 64-bit two's complement pattern of an integer-valued operand
/// (`uint64_t`; a signed value is sign-extended).
pub(crate) fn bits64(v: &Val) -> String {
    match v.rep() {
        Some(Rep::U64) => v.x.clone(),
        _ => format!("(uint64_t){}", v.p()),
    }
}

/// `1U` when the operand's representation is signed.
pub(crate) fn signed_flag(v: &Val) -> &'static str {
    if v.rep().is_some_and(Rep::signed) {
        "1U"
    } else {
        "0U"
    }
}

/// An integer-valued operand as `int64_t` (an unsigned 64-bit value
/// saturated at INT64_MAX: for positions, counts and date fields, where
/// every such value means the same).
pub(crate) fn sat_i64(v: &Val) -> String {
    match v.rep() {
        Some(Rep::I64) => v.x.clone(),
        Some(Rep::U64) => format!("stc_sat_i64({})", v.x),
        _ => format!("(int64_t){}", v.p()),
    }
}

/// The value of an integer-valued expression of representation `from`
/// in representation `to`, keeping the low-order bits (a C cast where it
/// is exact or unsigned, the runtime's portable reinterpretation where a
/// signed result would be implementation-defined).
pub(crate) fn int_cast(from: Rep, to: Rep, x: &str) -> String {
    if from == to {
        return x.to_string();
    }
    let px = paren(x);
    if !to.signed() {
        return format!("({}){px}", to.ctype());
    }
    let exact = if from.signed() {
        from.bits() <= to.bits()
    } else {
        from.bits() < to.bits()
    };
    if exact {
        format!("({}){px}", to.ctype())
    } else if from == to.unsigned() {
        format!("stc_{}_of({x})", to.sfx())
    } else {
        format!("stc_{}_of(({}){px})", to.sfx(), to.unsigned().ctype())
    }
}

/// A 64-bit pattern (`uint64_t` expression) wrapped into an integer-like
/// elementary type, as `stc_values::wrap` does; `None` for the types whose
/// wrap is not the low-order bits (BOOL, TOD) and for non-integers.
pub(crate) fn wrap_bits(to: ElemType, x: &str) -> Option<String> {
    if matches!(to, E::Bool | E::Tod | E::Ltod) {
        return None;
    }
    let r = Rep::of(to)?;
    if r.float() {
        return None;
    }
    Some(int_cast(Rep::U64, r, x))
}

/// `dst = x;`
pub(crate) fn set(e: &mut dyn Emit, dst: &Val, x: &str) {
    e.stmt(format!("{} = {x};", dst.x));
}

/// A value of a call that can fault: computed into a temporary, the POU
/// ends on a fault, and only then is the destination written (as on the
/// VM, a faulting operation leaves its destination unchanged).
pub(crate) fn set_checked(e: &mut dyn Emit, dst: &Val, x: &str) {
    let t = e.temp(dst.ty);
    e.stmt(format!("{t} = {x};"));
    e.fault_check();
    e.stmt(format!("{} = {t};", dst.x));
}

/// A statement that can fault, then the check.
pub(crate) fn call_checked(e: &mut dyn Emit, call: &str) {
    e.stmt(format!("{call};"));
    e.fault_check();
}

/// The conversion fault raised for a request `stc_values` answers with
/// "conversion failure" whatever the values (an ill-typed operation the
/// analyser never produces). The destination gets a neutral value so the
/// C compiler sees it written on every path.
pub(crate) fn misuse(e: &mut dyn Emit, dst: &Val) {
    let site = e.site();
    e.stmt(format!(
        "stc_fault((uint32_t)STC_FAULT_CONVERSION, {site}U);"
    ));
    match (dst.elem, dst.rep()) {
        (Some(E::String | E::Wstring), _) => {
            e.stmt(format!("(void)memset({}, 0, 2U);", dst.x));
        }
        (_, Some(r)) => e.stmt(format!("{} = {};", dst.x, zero(r))),
        _ => {}
    }
    e.fault_check();
}
