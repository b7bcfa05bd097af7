//! Scalar kinds: how the interpreter sees an elementary type.

use stc_syntax::token::ElemType;

/// The machine representation of a scalar, as used by `cvt` and `check`.
/// The explicit values are instruction operands and bytes of `.stbc`
/// files: never renumber one.
#[derive(Clone, Copy, PartialEq, Eq, Debug, Hash)]
#[repr(u8)]
pub enum Num {
    I8 = 0,
    I16 = 1,
    I32 = 2,
    I64 = 3,
    U8 = 4,
    U16 = 5,
    U32 = 6,
    U64 = 7,
    F32 = 8,
    F64 = 9,
    /// BOOL: one byte, 0 or 1.
    B = 10,
}

impl Num {
    pub const ALL: [Num; 11] = [
        Num::I8,
        Num::I16,
        Num::I32,
        Num::I64,
        Num::U8,
        Num::U16,
        Num::U32,
        Num::U64,
        Num::F32,
        Num::F64,
        Num::B,
    ];

    pub fn of(e: ElemType) -> Option<Num> {
        use ElemType as E;
        Some(match e {
            E::Bool => Num::B,
            E::Sint => Num::I8,
            E::Int => Num::I16,
            E::Dint => Num::I32,
            E::Lint
            | E::Time
            | E::Ltime
            | E::Date
            | E::Ldate
            | E::Tod
            | E::Ltod
            | E::Dt
            | E::Ldt => Num::I64,
            E::Usint | E::Byte | E::Char => Num::U8,
            E::Uint | E::Word | E::Wchar => Num::U16,
            E::Udint | E::Dword => Num::U32,
            E::Ulint | E::Lword => Num::U64,
            E::Real => Num::F32,
            E::Lreal => Num::F64,
            E::String | E::Wstring => return None,
        })
    }

    pub fn from_code(c: u32) -> Option<Num> {
        Num::ALL.into_iter().find(|n| n.code() == c)
    }

    pub fn code(self) -> u32 {
        self as u32
    }

    pub fn size(self) -> u32 {
        match self {
            Num::I8 | Num::U8 | Num::B => 1,
            Num::I16 | Num::U16 => 2,
            Num::I32 | Num::U32 | Num::F32 => 4,
            Num::I64 | Num::U64 | Num::F64 => 8,
        }
    }

    pub fn is_float(self) -> bool {
        matches!(self, Num::F32 | Num::F64)
    }

    pub fn is_signed(self) -> bool {
        matches!(self, Num::I8 | Num::I16 | Num::I32 | Num::I64)
    }
}
