//! The instruction set.
//!
//! Memory-to-memory, as CPDev's: every operand is an address, so `x := x + 1`
//! on a variable of an instance is one instruction, not a load, an add and a
//! store. Opcodes are typed (`add.i32`, `lt.f64`), so the interpreter never
//! inspects a value's type, and operands are pre-decoded: an operand is a
//! `u32` whose top two bits say which base it is relative to (the current
//! frame, the current instance, or absolute: globals and constants), so the
//! interpreter computes an address with one table lookup and one add.
//!
//! Every instruction is defined once, in the table at the bottom: the enum,
//! the binary encoding, the assembler mnemonics and the field kinds the
//! verifier checks all come from it.

use std::fmt;

/// An operand: an address relative to a base.
#[derive(Clone, Copy, PartialEq, Eq, Hash, Default)]
pub struct Op(pub u32);

pub const MODE_FRAME: u32 = 0;
pub const MODE_THIS: u32 = 1;
pub const MODE_ABS: u32 = 2;
pub const OFFSET_MASK: u32 = (1 << 30) - 1;

impl Op {
    pub fn frame(off: u32) -> Op {
        Op(off & OFFSET_MASK)
    }
    pub fn this(off: u32) -> Op {
        Op((MODE_THIS << 30) | (off & OFFSET_MASK))
    }
    pub fn abs(addr: u32) -> Op {
        Op((MODE_ABS << 30) | (addr & OFFSET_MASK))
    }
    pub fn mode(self) -> u32 {
        self.0 >> 30
    }
    pub fn offset(self) -> u32 {
        self.0 & OFFSET_MASK
    }
    /// The same operand moved by `delta` bytes.
    pub fn plus(self, delta: u32) -> Op {
        Op((self.0 & !OFFSET_MASK) | ((self.offset() + delta) & OFFSET_MASK))
    }
}

impl fmt::Debug for Op {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.mode() {
            MODE_FRAME => write!(f, "f{}", self.offset()),
            MODE_THIS => write!(f, "t{}", self.offset()),
            MODE_ABS => write!(f, "@{}", self.offset()),
            _ => write!(f, "?{}", self.offset()),
        }
    }
}

/// A jump target: an instruction index.
#[derive(Clone, Copy, PartialEq, Eq, Hash, Debug, Default)]
pub struct Tgt(pub u32);

/// What a field of an instruction is, for the text form and the verifier.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
pub enum FieldKind {
    /// An operand read or written with the given number of bytes (0: a size
    /// given by another field).
    Op(u32),
    Target,
    Imm,
}

pub trait Field: Copy {
    fn to_u32(self) -> u32;
    fn from_u32(v: u32) -> Self;
}

impl Field for Op {
    fn to_u32(self) -> u32 {
        self.0
    }
    fn from_u32(v: u32) -> Op {
        Op(v)
    }
}
impl Field for Tgt {
    fn to_u32(self) -> u32 {
        self.0
    }
    fn from_u32(v: u32) -> Tgt {
        Tgt(v)
    }
}
impl Field for u32 {
    fn to_u32(self) -> u32 {
        self
    }
    fn from_u32(v: u32) -> u32 {
        v
    }
}

macro_rules! field_kind {
    (Op, $size:expr) => {
        FieldKind::Op($size)
    };
    (Tgt, $size:expr) => {
        FieldKind::Target
    };
    (u32, $size:expr) => {
        FieldKind::Imm
    };
}

macro_rules! instructions {
    ($( $(#[$meta:meta])* $name:ident $mn:literal [$size:expr] { $($f:ident : $t:ident),* } )*) => {
        /// One instruction. Fields are operands (`Op`), jump targets (`Tgt`)
        /// or immediates (`u32`).
        #[derive(Clone, Copy, PartialEq, Eq, Debug)]
        pub enum Instr { $( $(#[$meta])* $name { $($f: $t),* }, )* }

        /// Every opcode's mnemonic, in opcode order.
        pub const MNEMONICS: &[&str] = &[$($mn,)*];

        impl Instr {
            pub fn opcode(&self) -> u8 {
                #[allow(unused_assignments)]
                let mut n: u8 = 0;
                $(
                    if let Instr::$name { .. } = self { return n; }
                    n += 1;
                )*
                n
            }

            pub fn mnemonic(&self) -> &'static str {
                MNEMONICS.get(self.opcode() as usize).copied().unwrap_or("?")
            }

            /// The fields, as stored in the binary form.
            pub fn fields(&self) -> Vec<u32> {
                match *self { $( Instr::$name { $($f),* } => vec![$($f.to_u32()),*], )* }
            }

            /// The kind of each field of an opcode.
            pub fn field_kinds(opcode: u8) -> Option<&'static [FieldKind]> {
                let table: &[&[FieldKind]] = &[$( &[$(field_kind!($t, $size)),*], )*];
                table.get(opcode as usize).copied()
            }

            /// The jump target of a branch, if it has one.
            pub fn target(&self) -> Option<u32> {
                let kinds = Instr::field_kinds(self.opcode())?;
                let i = kinds.iter().position(|k| *k == FieldKind::Target)?;
                self.fields().get(i).copied()
            }

            /// The same branch to another target (other instructions unchanged).
            pub fn with_target(&self, t: u32) -> Instr {
                let Some(kinds) = Instr::field_kinds(self.opcode()) else { return *self };
                let Some(i) = kinds.iter().position(|k| *k == FieldKind::Target) else { return *self };
                let mut f = self.fields();
                f[i] = t;
                Instr::from_parts(self.opcode(), &f).unwrap_or(*self)
            }

            /// Builds an instruction from its opcode and fields (the inverse
            /// of `opcode` and `fields`); `None` for an unknown opcode or the
            /// wrong number of fields.
            pub fn from_parts(opcode: u8, fields: &[u32]) -> Option<Instr> {
                #[allow(unused_assignments, unused_mut, unused_variables)]
                let mut n: u8 = 0;
                $(
                    if opcode == n {
                        let mut it = fields.iter().copied();
                        let i = Instr::$name { $($f: <$t as Field>::from_u32(it.next()?)),* };
                        return if it.next().is_none() { Some(i) } else { None };
                    }
                    n += 1;
                )*
                None
            }
        }
    };
}

// The table. `[N]` is the byte size of the values the operand fields access
// (0: given by a field, or several sizes).
instructions! {
    Nop "nop" [0] {}
    // Moves by size, and block copies.
    Mov1 "mov.1" [1] { d: Op, a: Op }
    Mov2 "mov.2" [2] { d: Op, a: Op }
    Mov4 "mov.4" [4] { d: Op, a: Op }
    Mov8 "mov.8" [8] { d: Op, a: Op }
    Copy "copy" [0] { d: Op, a: Op, len: u32 }
    /// String assignment: `d` has capacity `cap` characters of `unit` bytes.
    StrCopy "strcopy" [0] { d: Op, a: Op, cap: u32, unit: u32 }
    // Integer arithmetic, wrapping, by width.
    Add8 "add.8" [1] { d: Op, a: Op, b: Op }
    Add16 "add.16" [2] { d: Op, a: Op, b: Op }
    Add32 "add.32" [4] { d: Op, a: Op, b: Op }
    Add64 "add.64" [8] { d: Op, a: Op, b: Op }
    Sub8 "sub.8" [1] { d: Op, a: Op, b: Op }
    Sub16 "sub.16" [2] { d: Op, a: Op, b: Op }
    Sub32 "sub.32" [4] { d: Op, a: Op, b: Op }
    Sub64 "sub.64" [8] { d: Op, a: Op, b: Op }
    Mul8 "mul.8" [1] { d: Op, a: Op, b: Op }
    Mul16 "mul.16" [2] { d: Op, a: Op, b: Op }
    Mul32 "mul.32" [4] { d: Op, a: Op, b: Op }
    Mul64 "mul.64" [8] { d: Op, a: Op, b: Op }
    Neg8 "neg.8" [1] { d: Op, a: Op }
    Neg16 "neg.16" [2] { d: Op, a: Op }
    Neg32 "neg.32" [4] { d: Op, a: Op }
    Neg64 "neg.64" [8] { d: Op, a: Op }
    // Division and remainder, by signedness and width (zero divisor: fault).
    DivI8 "div.i8" [1] { d: Op, a: Op, b: Op }
    DivI16 "div.i16" [2] { d: Op, a: Op, b: Op }
    DivI32 "div.i32" [4] { d: Op, a: Op, b: Op }
    DivI64 "div.i64" [8] { d: Op, a: Op, b: Op }
    DivU8 "div.u8" [1] { d: Op, a: Op, b: Op }
    DivU16 "div.u16" [2] { d: Op, a: Op, b: Op }
    DivU32 "div.u32" [4] { d: Op, a: Op, b: Op }
    DivU64 "div.u64" [8] { d: Op, a: Op, b: Op }
    ModI8 "mod.i8" [1] { d: Op, a: Op, b: Op }
    ModI16 "mod.i16" [2] { d: Op, a: Op, b: Op }
    ModI32 "mod.i32" [4] { d: Op, a: Op, b: Op }
    ModI64 "mod.i64" [8] { d: Op, a: Op, b: Op }
    ModU8 "mod.u8" [1] { d: Op, a: Op, b: Op }
    ModU16 "mod.u16" [2] { d: Op, a: Op, b: Op }
    ModU32 "mod.u32" [4] { d: Op, a: Op, b: Op }
    ModU64 "mod.u64" [8] { d: Op, a: Op, b: Op }
    // Floating point (REAL results rounded to binary32).
    AddF32 "add.f32" [4] { d: Op, a: Op, b: Op }
    AddF64 "add.f64" [8] { d: Op, a: Op, b: Op }
    SubF32 "sub.f32" [4] { d: Op, a: Op, b: Op }
    SubF64 "sub.f64" [8] { d: Op, a: Op, b: Op }
    MulF32 "mul.f32" [4] { d: Op, a: Op, b: Op }
    MulF64 "mul.f64" [8] { d: Op, a: Op, b: Op }
    DivF32 "div.f32" [4] { d: Op, a: Op, b: Op }
    DivF64 "div.f64" [8] { d: Op, a: Op, b: Op }
    NegF32 "neg.f32" [4] { d: Op, a: Op }
    NegF64 "neg.f64" [8] { d: Op, a: Op }
    // Equality by width (floats by value); the result is a BOOL byte.
    Eq8 "eq.8" [1] { d: Op, a: Op, b: Op }
    Eq16 "eq.16" [2] { d: Op, a: Op, b: Op }
    Eq32 "eq.32" [4] { d: Op, a: Op, b: Op }
    Eq64 "eq.64" [8] { d: Op, a: Op, b: Op }
    EqF32 "eq.f32" [4] { d: Op, a: Op, b: Op }
    EqF64 "eq.f64" [8] { d: Op, a: Op, b: Op }
    Ne8 "ne.8" [1] { d: Op, a: Op, b: Op }
    Ne16 "ne.16" [2] { d: Op, a: Op, b: Op }
    Ne32 "ne.32" [4] { d: Op, a: Op, b: Op }
    Ne64 "ne.64" [8] { d: Op, a: Op, b: Op }
    NeF32 "ne.f32" [4] { d: Op, a: Op, b: Op }
    NeF64 "ne.f64" [8] { d: Op, a: Op, b: Op }
    // Ordering: `lt` and `le` only (the compiler swaps operands for > and >=).
    LtI8 "lt.i8" [1] { d: Op, a: Op, b: Op }
    LtI16 "lt.i16" [2] { d: Op, a: Op, b: Op }
    LtI32 "lt.i32" [4] { d: Op, a: Op, b: Op }
    LtI64 "lt.i64" [8] { d: Op, a: Op, b: Op }
    LtU8 "lt.u8" [1] { d: Op, a: Op, b: Op }
    LtU16 "lt.u16" [2] { d: Op, a: Op, b: Op }
    LtU32 "lt.u32" [4] { d: Op, a: Op, b: Op }
    LtU64 "lt.u64" [8] { d: Op, a: Op, b: Op }
    LtF32 "lt.f32" [4] { d: Op, a: Op, b: Op }
    LtF64 "lt.f64" [8] { d: Op, a: Op, b: Op }
    LeI8 "le.i8" [1] { d: Op, a: Op, b: Op }
    LeI16 "le.i16" [2] { d: Op, a: Op, b: Op }
    LeI32 "le.i32" [4] { d: Op, a: Op, b: Op }
    LeI64 "le.i64" [8] { d: Op, a: Op, b: Op }
    LeU8 "le.u8" [1] { d: Op, a: Op, b: Op }
    LeU16 "le.u16" [2] { d: Op, a: Op, b: Op }
    LeU32 "le.u32" [4] { d: Op, a: Op, b: Op }
    LeU64 "le.u64" [8] { d: Op, a: Op, b: Op }
    LeF32 "le.f32" [4] { d: Op, a: Op, b: Op }
    LeF64 "le.f64" [8] { d: Op, a: Op, b: Op }
    // Bit strings and BOOL (BOOL is a byte holding 0 or 1).
    And8 "and.8" [1] { d: Op, a: Op, b: Op }
    And16 "and.16" [2] { d: Op, a: Op, b: Op }
    And32 "and.32" [4] { d: Op, a: Op, b: Op }
    And64 "and.64" [8] { d: Op, a: Op, b: Op }
    Or8 "or.8" [1] { d: Op, a: Op, b: Op }
    Or16 "or.16" [2] { d: Op, a: Op, b: Op }
    Or32 "or.32" [4] { d: Op, a: Op, b: Op }
    Or64 "or.64" [8] { d: Op, a: Op, b: Op }
    Xor8 "xor.8" [1] { d: Op, a: Op, b: Op }
    Xor16 "xor.16" [2] { d: Op, a: Op, b: Op }
    Xor32 "xor.32" [4] { d: Op, a: Op, b: Op }
    Xor64 "xor.64" [8] { d: Op, a: Op, b: Op }
    Not8 "not.8" [1] { d: Op, a: Op }
    Not16 "not.16" [2] { d: Op, a: Op }
    Not32 "not.32" [4] { d: Op, a: Op }
    Not64 "not.64" [8] { d: Op, a: Op }
    NotB "not.b" [1] { d: Op, a: Op }
    /// Numeric conversion: `from` and `to` are scalar codes (see `vm::Num`).
    Cvt "cvt" [0] { d: Op, a: Op, from: u32, to: u32 }
    /// Fault unless `lo <= a <= hi` for the scalar code `num`; `lo`, `hi`
    /// are constant-pool operands of that scalar's width.
    Check "check" [0] { a: Op, lo: Op, hi: Op, num: u32 }
    /// A bit (or byte, word...) of a bit string: `d := a.part`.
    GetPart "getpart" [0] { d: Op, a: Op, width: u32, part: u32, index: u32 }
    SetPart "setpart" [0] { d: Op, a: Op, width: u32, part: u32, index: u32 }
    // References and indexing. Addresses are 4-byte values.
    Lea "lea" [4] { d: Op, a: Op }
    /// `d := mem[*p + off .. + len]`, `mem[*p + off .. + len] := a`.
    Load "load" [0] { d: Op, p: Op, off: u32, len: u32 }
    Store "store" [0] { p: Op, a: Op, off: u32, len: u32 }
    // Control flow.
    Jmp "jmp" [0] { t: Tgt }
    Jz "jz" [1] { c: Op, t: Tgt }
    Jnz "jnz" [1] { c: Op, t: Tgt }
    // Compare and branch: jump to `t` if the comparison holds.
    JltI8 "jlt.i8" [1] { a: Op, b: Op, t: Tgt }
    JltI16 "jlt.i16" [2] { a: Op, b: Op, t: Tgt }
    JltI32 "jlt.i32" [4] { a: Op, b: Op, t: Tgt }
    JltI64 "jlt.i64" [8] { a: Op, b: Op, t: Tgt }
    JltU8 "jlt.u8" [1] { a: Op, b: Op, t: Tgt }
    JltU16 "jlt.u16" [2] { a: Op, b: Op, t: Tgt }
    JltU32 "jlt.u32" [4] { a: Op, b: Op, t: Tgt }
    JltU64 "jlt.u64" [8] { a: Op, b: Op, t: Tgt }
    JltF32 "jlt.f32" [4] { a: Op, b: Op, t: Tgt }
    JltF64 "jlt.f64" [8] { a: Op, b: Op, t: Tgt }
    JleI8 "jle.i8" [1] { a: Op, b: Op, t: Tgt }
    JleI16 "jle.i16" [2] { a: Op, b: Op, t: Tgt }
    JleI32 "jle.i32" [4] { a: Op, b: Op, t: Tgt }
    JleI64 "jle.i64" [8] { a: Op, b: Op, t: Tgt }
    JleU8 "jle.u8" [1] { a: Op, b: Op, t: Tgt }
    JleU16 "jle.u16" [2] { a: Op, b: Op, t: Tgt }
    JleU32 "jle.u32" [4] { a: Op, b: Op, t: Tgt }
    JleU64 "jle.u64" [8] { a: Op, b: Op, t: Tgt }
    JleF32 "jle.f32" [4] { a: Op, b: Op, t: Tgt }
    JleF64 "jle.f64" [8] { a: Op, b: Op, t: Tgt }
    Jeq8 "jeq.8" [1] { a: Op, b: Op, t: Tgt }
    Jeq16 "jeq.16" [2] { a: Op, b: Op, t: Tgt }
    Jeq32 "jeq.32" [4] { a: Op, b: Op, t: Tgt }
    Jeq64 "jeq.64" [8] { a: Op, b: Op, t: Tgt }
    JeqF32 "jeq.f32" [4] { a: Op, b: Op, t: Tgt }
    JeqF64 "jeq.f64" [8] { a: Op, b: Op, t: Tgt }
    Jne8 "jne.8" [1] { a: Op, b: Op, t: Tgt }
    Jne16 "jne.16" [2] { a: Op, b: Op, t: Tgt }
    Jne32 "jne.32" [4] { a: Op, b: Op, t: Tgt }
    Jne64 "jne.64" [8] { a: Op, b: Op, t: Tgt }
    JneF32 "jne.f32" [4] { a: Op, b: Op, t: Tgt }
    JneF64 "jne.f64" [8] { a: Op, b: Op, t: Tgt }
    // Float branches on a false comparison (true when an operand is NaN).
    JnltF32 "jnlt.f32" [4] { a: Op, b: Op, t: Tgt }
    JnltF64 "jnlt.f64" [8] { a: Op, b: Op, t: Tgt }
    JnleF32 "jnle.f32" [4] { a: Op, b: Op, t: Tgt }
    JnleF64 "jnle.f64" [8] { a: Op, b: Op, t: Tgt }
    // The latch of a FOR loop with a constant step: `v := v + s` (up) or
    // `v := v - s` (down), then jump to `t` while `v <= e` (`v >= e`); when
    // the new value would overflow, `v` keeps its value and the loop ends.
    ForUpI8 "forup.i8" [1] { v: Op, s: Op, e: Op, t: Tgt }
    ForUpI16 "forup.i16" [2] { v: Op, s: Op, e: Op, t: Tgt }
    ForUpI32 "forup.i32" [4] { v: Op, s: Op, e: Op, t: Tgt }
    ForUpI64 "forup.i64" [8] { v: Op, s: Op, e: Op, t: Tgt }
    ForUpU8 "forup.u8" [1] { v: Op, s: Op, e: Op, t: Tgt }
    ForUpU16 "forup.u16" [2] { v: Op, s: Op, e: Op, t: Tgt }
    ForUpU32 "forup.u32" [4] { v: Op, s: Op, e: Op, t: Tgt }
    ForUpU64 "forup.u64" [8] { v: Op, s: Op, e: Op, t: Tgt }
    ForDnI8 "fordn.i8" [1] { v: Op, s: Op, e: Op, t: Tgt }
    ForDnI16 "fordn.i16" [2] { v: Op, s: Op, e: Op, t: Tgt }
    ForDnI32 "fordn.i32" [4] { v: Op, s: Op, e: Op, t: Tgt }
    ForDnI64 "fordn.i64" [8] { v: Op, s: Op, e: Op, t: Tgt }
    ForDnU8 "fordn.u8" [1] { v: Op, s: Op, e: Op, t: Tgt }
    ForDnU16 "fordn.u16" [2] { v: Op, s: Op, e: Op, t: Tgt }
    ForDnU32 "fordn.u32" [4] { v: Op, s: Op, e: Op, t: Tgt }
    ForDnU64 "fordn.u64" [8] { v: Op, s: Op, e: Op, t: Tgt }
    /// The address of an array element: `d := &a + (idx - lo) * stride`
    /// after checking `lo <= idx < lo + count` (`desc` indexes
    /// `Image::elems`: lo, count, stride and the scalar kind of `idx`).
    Elem "elem" [0] { d: Op, a: Op, idx: Op, desc: u32 }
    /// The same from the address held in `p`.
    ElemP "elem.p" [0] { d: Op, p: Op, idx: Op, desc: u32 }
    LdElem1 "ldelem.1" [0] { d: Op, a: Op, idx: Op, desc: u32 }
    LdElem2 "ldelem.2" [0] { d: Op, a: Op, idx: Op, desc: u32 }
    LdElem4 "ldelem.4" [0] { d: Op, a: Op, idx: Op, desc: u32 }
    LdElem8 "ldelem.8" [0] { d: Op, a: Op, idx: Op, desc: u32 }
    StElem1 "stelem.1" [0] { a: Op, idx: Op, v: Op, desc: u32 }
    StElem2 "stelem.2" [0] { a: Op, idx: Op, v: Op, desc: u32 }
    StElem4 "stelem.4" [0] { a: Op, idx: Op, v: Op, desc: u32 }
    StElem8 "stelem.8" [0] { a: Op, idx: Op, v: Op, desc: u32 }
    // Scalars through a pointer: `d := mem[*p + off]`, `mem[*p + off] := a`.
    Ld1 "ld.1" [0] { d: Op, p: Op, off: u32 }
    Ld2 "ld.2" [0] { d: Op, p: Op, off: u32 }
    Ld4 "ld.4" [0] { d: Op, p: Op, off: u32 }
    Ld8 "ld.8" [0] { d: Op, p: Op, off: u32 }
    St1 "st.1" [0] { p: Op, a: Op, off: u32 }
    St2 "st.2" [0] { p: Op, a: Op, off: u32 }
    St4 "st.4" [0] { p: Op, a: Op, off: u32 }
    St8 "st.8" [0] { p: Op, a: Op, off: u32 }
    /// Calls: the callee's frame starts at `frame` bytes into the caller's.
    CallFn "callfn" [0] { pou: u32, frame: u32 }
    /// `inst` is the instance (its address is the operand's address).
    CallFb "callfb" [0] { pou: u32, inst: Op, frame: u32 }
    /// `inst` holds the address of the instance.
    CallFbInd "callfb.ind" [4] { pou: u32, inst: Op, frame: u32 }
    Ret "ret" [0] {}
    // Standard functions on one scalar kind (`num`, see `vm::Num`).
    Min "min" [0] { d: Op, a: Op, b: Op, num: u32 }
    Max "max" [0] { d: Op, a: Op, b: Op, num: u32 }
    Limit "limit" [0] { d: Op, lo: Op, a: Op, hi: Op, num: u32 }
    Abs "abs" [0] { d: Op, a: Op, num: u32 }
    /// SHL, SHR, ROL, ROR (`op` 0..3) of `a` (scalar kind `num`) by `n`
    /// (scalar kind `nnum`).
    Shift "shift" [0] { d: Op, a: Op, n: Op, op: u32, num: u32, nnum: u32 }
    /// `d := if g { b } else { a }`, `len` bytes.
    Sel "sel" [0] { d: Op, g: Op, a: Op, b: Op, len: u32 }
    /// A standard function or generic operation through its descriptor.
    Std "std" [0] { call: u32 }
    /// `d := ` the task clock (TIME, 8 bytes).
    CurTime "curtime" [8] { d: Op }
    /// A run-time fault (the kind is a `FaultKind` code).
    Fault "fault" [0] { kind: u32 }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn instructions_rebuild_from_their_parts() {
        let samples = [
            Instr::Add32 {
                d: Op::frame(8),
                a: Op::this(4),
                b: Op::abs(100),
            },
            Instr::Jz {
                c: Op::frame(1),
                t: Tgt(7),
            },
            Instr::CallFb {
                pou: 3,
                inst: Op::this(16),
                frame: 24,
            },
            Instr::Ret {},
            Instr::Elem {
                d: Op::frame(0),
                a: Op::frame(4),
                idx: Op::frame(8),
                desc: 9,
            },
        ];
        for i in samples {
            let back = Instr::from_parts(i.opcode(), &i.fields());
            assert_eq!(back, Some(i));
            assert_eq!(
                Instr::field_kinds(i.opcode()).map(|k| k.len()),
                Some(i.fields().len())
            );
        }
        assert_eq!(
            MNEMONICS.len(),
            MNEMONICS
                .iter()
                .collect::<std::collections::HashSet<_>>()
                .len()
        );
    }
}

#[cfg(test)]
mod opcodes {
    /// An opcode is its position in the table above, and a byte of `.stbc`
    /// files: `opcodes.txt` pins the numbering. New instructions go at the
    /// end (the test then asks to append them to the file, `STC_BLESS=1`);
    /// moving or removing one fails here, and then needs a new
    /// `format::VERSION` besides the new file.
    #[test]
    fn opcodes_keep_their_numbers() {
        let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("src/opcodes.txt");
        let now: String = super::MNEMONICS
            .iter()
            .enumerate()
            .map(|(i, m)| format!("{i} {m}\n"))
            .collect();
        if std::env::var_os("STC_BLESS").is_some() {
            std::fs::write(&path, &now).expect("src/opcodes.txt is writable");
        }
        let pinned = std::fs::read_to_string(&path).unwrap_or_default();
        assert!(
            now.starts_with(&pinned),
            "the opcode numbering changed (see src/opcodes.txt)"
        );
        assert!(
            now == pinned,
            "new instructions: rerun with STC_BLESS=1 to add them to src/opcodes.txt"
        );
    }
}

#[cfg(test)]
mod size {
    #[test]
    fn instructions_stay_small() {
        // A tag and at most six 4-byte fields: the interpreter's working
        // set stays in cache.
        assert!(
            std::mem::size_of::<super::Instr>() <= 28,
            "{}",
            std::mem::size_of::<super::Instr>()
        );
    }
}
