//! The interpreter loop.
//!
//! One `match` over pre-decoded instructions; an operand's address is its
//! base (frame, instance or absolute) plus its offset, computed without a
//! branch. Every memory access is bounds-checked against the machine's byte
//! array, so no bytecode can reach outside it, verified or not; a failed
//! check is an "invalid bytecode" fault, never a crash. The step budget
//! counts every instruction (the watchdog of `--max-steps`).

use stc_ir::FaultKind;
use stc_values::Value;

use crate::compile::fault_of_code;
use crate::image::{Image, StdCall, StdOp};
use crate::instr::{Instr, Op, OFFSET_MASK};
use crate::machine::{read_scalar, read_string, write_scalar, write_string, Machine, VmFault};
use crate::num::Num;

/// Why execution stopped early.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Trap {
    Fault(FaultKind),
    /// Memory outside the machine, a bad jump or call: only corrupt bytecode.
    Invalid,
}

const MAX_CALL_DEPTH: usize = 1024;

trait Scalar: Sized + Copy {
    const N: usize;
    fn from_bytes(b: &[u8]) -> Self;
    fn to_bytes(self, out: &mut [u8]);
}

macro_rules! scalar {
    ($($t:ty),*) => {$(
        impl Scalar for $t {
            const N: usize = std::mem::size_of::<$t>();
            #[inline(always)]
            fn from_bytes(b: &[u8]) -> $t {
                let mut a = [0u8; std::mem::size_of::<$t>()];
                a.copy_from_slice(b);
                <$t>::from_le_bytes(a)
            }
            #[inline(always)]
            fn to_bytes(self, out: &mut [u8]) {
                out.copy_from_slice(&self.to_le_bytes());
            }
        }
    )*};
}
scalar!(i8, i16, i32, i64, u8, u16, u32, u64, f32, f64);

#[inline(always)]
fn ld<T: Scalar>(m: &[u8], a: usize) -> Result<T, Trap> {
    match m.get(a..a.wrapping_add(T::N)) {
        Some(b) => Ok(T::from_bytes(b)),
        None => Err(Trap::Invalid),
    }
}

#[inline(always)]
fn st<T: Scalar>(m: &mut [u8], a: usize, v: T) -> Result<(), Trap> {
    match m.get_mut(a..a.wrapping_add(T::N)) {
        Some(b) => {
            v.to_bytes(b);
            Ok(())
        }
        None => Err(Trap::Invalid),
    }
}

#[inline(always)]
fn st_bool(m: &mut [u8], a: usize, v: bool) -> Result<(), Trap> {
    st::<u8>(m, a, v as u8)
}

fn copy(m: &mut [u8], d: usize, s: usize, len: usize) -> Result<(), Trap> {
    if s.checked_add(len).is_none_or(|e| e > m.len())
        || d.checked_add(len).is_none_or(|e| e > m.len())
    {
        return Err(Trap::Invalid);
    }
    m.copy_within(s..s + len, d);
    Ok(())
}

/// Reads an operand of a scalar kind as an integer (floats truncated) or float.
fn read_num(m: &[u8], a: usize, n: Num) -> Result<(i128, f64), Trap> {
    Ok(match n {
        Num::I8 => (ld::<i8>(m, a)? as i128, 0.0),
        Num::I16 => (ld::<i16>(m, a)? as i128, 0.0),
        Num::I32 => (ld::<i32>(m, a)? as i128, 0.0),
        Num::I64 => (ld::<i64>(m, a)? as i128, 0.0),
        Num::U8 | Num::B => (ld::<u8>(m, a)? as i128, 0.0),
        Num::U16 => (ld::<u16>(m, a)? as i128, 0.0),
        Num::U32 => (ld::<u32>(m, a)? as i128, 0.0),
        Num::U64 => (ld::<u64>(m, a)? as i128, 0.0),
        Num::F32 => (0, ld::<f32>(m, a)? as f64),
        Num::F64 => (0, ld::<f64>(m, a)?),
    })
}

fn write_int(m: &mut [u8], a: usize, n: Num, v: i128) -> Result<(), Trap> {
    match n {
        Num::I8 | Num::U8 => st::<u8>(m, a, v as u8),
        Num::I16 | Num::U16 => st::<u16>(m, a, v as u16),
        Num::I32 | Num::U32 => st::<u32>(m, a, v as u32),
        Num::I64 | Num::U64 => st::<u64>(m, a, v as u64),
        Num::B => st_bool(m, a, v != 0),
        Num::F32 => st::<f32>(m, a, v as f32),
        Num::F64 => st::<f64>(m, a, v as f64),
    }
}

fn int_range(n: Num) -> (i128, i128) {
    match n {
        Num::I8 => (i8::MIN as i128, i8::MAX as i128),
        Num::I16 => (i16::MIN as i128, i16::MAX as i128),
        Num::I32 => (i32::MIN as i128, i32::MAX as i128),
        Num::I64 => (i64::MIN as i128, i64::MAX as i128),
        Num::U8 => (0, u8::MAX as i128),
        Num::U16 => (0, u16::MAX as i128),
        Num::U32 => (0, u32::MAX as i128),
        Num::U64 => (0, u64::MAX as i128),
        Num::B => (0, 1),
        Num::F32 | Num::F64 => (i128::MIN, i128::MAX),
    }
}

/// Numeric conversion with the semantics of `stc_values::convert`.
fn convert(m: &mut [u8], d: usize, a: usize, from: Num, to: Num) -> Result<(), Trap> {
    let (i, f) = read_num(m, a, from)?;
    if from.is_float() {
        match to {
            Num::F32 => st::<f32>(m, d, f as f32),
            Num::F64 => st::<f64>(m, d, f),
            Num::B => st_bool(m, d, f != 0.0),
            _ => {
                let r = f.round_ties_even();
                let (lo, hi) = int_range(to);
                if r.is_nan() || r < lo as f64 || r > hi as f64 {
                    return Err(Trap::Fault(FaultKind::Conversion));
                }
                let v = r as i128;
                if v < lo || v > hi {
                    return Err(Trap::Fault(FaultKind::Conversion));
                }
                write_int(m, d, to, v)
            }
        }
    } else {
        match to {
            Num::F32 => st::<f32>(m, d, i as f32),
            Num::F64 => st::<f64>(m, d, i as f64),
            Num::B => st_bool(m, d, i != 0),
            _ => write_int(m, d, to, i),
        }
    }
}

/// The state of one run of a program body.
struct Cpu {
    pc: usize,
    bases: [u32; 4],
    steps: u64,
    calls: Vec<(usize, u32, u32)>,
    now: i64,
}

impl Machine {
    pub(crate) fn execute(
        &mut self,
        entry: u32,
        this: u32,
        pou: u32,
        now: i64,
        max_steps: u64,
    ) -> Result<(), VmFault> {
        let image = self.image.clone();
        let fp = image.stack_base();
        let mut cpu = Cpu {
            pc: entry as usize,
            bases: [fp, this, 0, 0],
            steps: max_steps,
            calls: Vec::new(),
            now,
        };
        let r = enter_frame(&image, &mut self.mem, pou, fp)
            .and_then(|_| run(&image, &mut self.mem, &mut cpu));
        match r {
            Ok(()) => Ok(()),
            Err(t) => {
                let kind = match t {
                    Trap::Fault(k) => k,
                    Trap::Invalid => FaultKind::InvalidCode,
                };
                Err(self.fault_at(kind, cpu.pc as u32))
            }
        }
    }
}

/// Copies a POU's frame template into a new frame at `fp`.
fn enter_frame(image: &Image, m: &mut [u8], pou: u32, fp: u32) -> Result<(), Trap> {
    let p = image.pous.get(pou as usize).ok_or(Trap::Invalid)?;
    let (src, len) = p.frame_template;
    if len > 0 {
        let s = image.const_base() as usize + src as usize;
        copy(m, fp as usize + p.frame_init_at as usize, s, len as usize)?;
    }
    Ok(())
}

macro_rules! bin {
    ($m:ident, $cpu:ident, $t:ty, $d:ident, $a:ident, $b:ident, |$x:ident, $y:ident| $e:expr) => {{
        let $x: $t = ld($m, addr(&$cpu.bases, $a))?;
        let $y: $t = ld($m, addr(&$cpu.bases, $b))?;
        st($m, addr(&$cpu.bases, $d), $e)?;
    }};
}

macro_rules! cmp {
    ($m:ident, $cpu:ident, $t:ty, $d:ident, $a:ident, $b:ident, |$x:ident, $y:ident| $e:expr) => {{
        let $x: $t = ld($m, addr(&$cpu.bases, $a))?;
        let $y: $t = ld($m, addr(&$cpu.bases, $b))?;
        st_bool($m, addr(&$cpu.bases, $d), $e)?;
    }};
}

macro_rules! un {
    ($m:ident, $cpu:ident, $t:ty, $d:ident, $a:ident, |$x:ident| $e:expr) => {{
        let $x: $t = ld($m, addr(&$cpu.bases, $a))?;
        st($m, addr(&$cpu.bases, $d), $e)?;
    }};
}

macro_rules! div {
    ($m:ident, $cpu:ident, $t:ty, $d:ident, $a:ident, $b:ident, $op:ident) => {{
        let x: $t = ld($m, addr(&$cpu.bases, $a))?;
        let y: $t = ld($m, addr(&$cpu.bases, $b))?;
        if y == 0 {
            return Err(Trap::Fault(FaultKind::DivisionByZero));
        }
        st($m, addr(&$cpu.bases, $d), x.$op(y))?;
    }};
}

#[inline(always)]
fn addr(bases: &[u32; 4], op: Op) -> usize {
    bases[(op.0 >> 30) as usize].wrapping_add(op.0 & OFFSET_MASK) as usize
}

fn run(image: &Image, m: &mut [u8], cpu: &mut Cpu) -> Result<(), Trap> {
    let code = &image.code[..];
    loop {
        if cpu.steps == 0 {
            return Err(Trap::Fault(FaultKind::Watchdog));
        }
        cpu.steps -= 1;
        let Some(&ins) = code.get(cpu.pc) else {
            return Err(Trap::Invalid);
        };
        cpu.pc += 1;
        use Instr as I;
        match ins {
            I::Nop {} => {}
            I::Mov1 { d, a } => un!(m, cpu, u8, d, a, |x| x),
            I::Mov2 { d, a } => un!(m, cpu, u16, d, a, |x| x),
            I::Mov4 { d, a } => un!(m, cpu, u32, d, a, |x| x),
            I::Mov8 { d, a } => un!(m, cpu, u64, d, a, |x| x),
            I::Copy { d, a, len } => {
                copy(m, addr(&cpu.bases, d), addr(&cpu.bases, a), len as usize)?
            }
            I::StrCopy { d, a, cap, unit } => {
                let (da, sa) = (addr(&cpu.bases, d), addr(&cpu.bases, a));
                let len = (ld::<u16>(m, sa)? as u32).min(cap);
                copy(m, da + 2, sa + 2, (len * unit) as usize)?;
                st::<u16>(m, da, len as u16)?;
            }
            I::Add8 { d, a, b } => bin!(m, cpu, u8, d, a, b, |x, y| x.wrapping_add(y)),
            I::Add16 { d, a, b } => bin!(m, cpu, u16, d, a, b, |x, y| x.wrapping_add(y)),
            I::Add32 { d, a, b } => bin!(m, cpu, u32, d, a, b, |x, y| x.wrapping_add(y)),
            I::Add64 { d, a, b } => bin!(m, cpu, u64, d, a, b, |x, y| x.wrapping_add(y)),
            I::Sub8 { d, a, b } => bin!(m, cpu, u8, d, a, b, |x, y| x.wrapping_sub(y)),
            I::Sub16 { d, a, b } => bin!(m, cpu, u16, d, a, b, |x, y| x.wrapping_sub(y)),
            I::Sub32 { d, a, b } => bin!(m, cpu, u32, d, a, b, |x, y| x.wrapping_sub(y)),
            I::Sub64 { d, a, b } => bin!(m, cpu, u64, d, a, b, |x, y| x.wrapping_sub(y)),
            I::Mul8 { d, a, b } => bin!(m, cpu, u8, d, a, b, |x, y| x.wrapping_mul(y)),
            I::Mul16 { d, a, b } => bin!(m, cpu, u16, d, a, b, |x, y| x.wrapping_mul(y)),
            I::Mul32 { d, a, b } => bin!(m, cpu, u32, d, a, b, |x, y| x.wrapping_mul(y)),
            I::Mul64 { d, a, b } => bin!(m, cpu, u64, d, a, b, |x, y| x.wrapping_mul(y)),
            I::Neg8 { d, a } => un!(m, cpu, u8, d, a, |x| x.wrapping_neg()),
            I::Neg16 { d, a } => un!(m, cpu, u16, d, a, |x| x.wrapping_neg()),
            I::Neg32 { d, a } => un!(m, cpu, u32, d, a, |x| x.wrapping_neg()),
            I::Neg64 { d, a } => un!(m, cpu, u64, d, a, |x| x.wrapping_neg()),
            I::DivI8 { d, a, b } => div!(m, cpu, i8, d, a, b, wrapping_div),
            I::DivI16 { d, a, b } => div!(m, cpu, i16, d, a, b, wrapping_div),
            I::DivI32 { d, a, b } => div!(m, cpu, i32, d, a, b, wrapping_div),
            I::DivI64 { d, a, b } => div!(m, cpu, i64, d, a, b, wrapping_div),
            I::DivU8 { d, a, b } => div!(m, cpu, u8, d, a, b, wrapping_div),
            I::DivU16 { d, a, b } => div!(m, cpu, u16, d, a, b, wrapping_div),
            I::DivU32 { d, a, b } => div!(m, cpu, u32, d, a, b, wrapping_div),
            I::DivU64 { d, a, b } => div!(m, cpu, u64, d, a, b, wrapping_div),
            I::ModI8 { d, a, b } => div!(m, cpu, i8, d, a, b, wrapping_rem),
            I::ModI16 { d, a, b } => div!(m, cpu, i16, d, a, b, wrapping_rem),
            I::ModI32 { d, a, b } => div!(m, cpu, i32, d, a, b, wrapping_rem),
            I::ModI64 { d, a, b } => div!(m, cpu, i64, d, a, b, wrapping_rem),
            I::ModU8 { d, a, b } => div!(m, cpu, u8, d, a, b, wrapping_rem),
            I::ModU16 { d, a, b } => div!(m, cpu, u16, d, a, b, wrapping_rem),
            I::ModU32 { d, a, b } => div!(m, cpu, u32, d, a, b, wrapping_rem),
            I::ModU64 { d, a, b } => div!(m, cpu, u64, d, a, b, wrapping_rem),
            I::AddF32 { d, a, b } => bin!(m, cpu, f32, d, a, b, |x, y| x + y),
            I::AddF64 { d, a, b } => bin!(m, cpu, f64, d, a, b, |x, y| x + y),
            I::SubF32 { d, a, b } => bin!(m, cpu, f32, d, a, b, |x, y| x - y),
            I::SubF64 { d, a, b } => bin!(m, cpu, f64, d, a, b, |x, y| x - y),
            I::MulF32 { d, a, b } => bin!(m, cpu, f32, d, a, b, |x, y| x * y),
            I::MulF64 { d, a, b } => bin!(m, cpu, f64, d, a, b, |x, y| x * y),
            I::DivF32 { d, a, b } => bin!(m, cpu, f32, d, a, b, |x, y| x / y),
            I::DivF64 { d, a, b } => bin!(m, cpu, f64, d, a, b, |x, y| x / y),
            I::NegF32 { d, a } => un!(m, cpu, f32, d, a, |x| -x),
            I::NegF64 { d, a } => un!(m, cpu, f64, d, a, |x| -x),
            I::Eq8 { d, a, b } => cmp!(m, cpu, u8, d, a, b, |x, y| x == y),
            I::Eq16 { d, a, b } => cmp!(m, cpu, u16, d, a, b, |x, y| x == y),
            I::Eq32 { d, a, b } => cmp!(m, cpu, u32, d, a, b, |x, y| x == y),
            I::Eq64 { d, a, b } => cmp!(m, cpu, u64, d, a, b, |x, y| x == y),
            I::EqF32 { d, a, b } => cmp!(m, cpu, f32, d, a, b, |x, y| x == y),
            I::EqF64 { d, a, b } => cmp!(m, cpu, f64, d, a, b, |x, y| x == y),
            I::Ne8 { d, a, b } => cmp!(m, cpu, u8, d, a, b, |x, y| x != y),
            I::Ne16 { d, a, b } => cmp!(m, cpu, u16, d, a, b, |x, y| x != y),
            I::Ne32 { d, a, b } => cmp!(m, cpu, u32, d, a, b, |x, y| x != y),
            I::Ne64 { d, a, b } => cmp!(m, cpu, u64, d, a, b, |x, y| x != y),
            I::NeF32 { d, a, b } => cmp!(m, cpu, f32, d, a, b, |x, y| x != y),
            I::NeF64 { d, a, b } => cmp!(m, cpu, f64, d, a, b, |x, y| x != y),
            I::LtI8 { d, a, b } => cmp!(m, cpu, i8, d, a, b, |x, y| x < y),
            I::LtI16 { d, a, b } => cmp!(m, cpu, i16, d, a, b, |x, y| x < y),
            I::LtI32 { d, a, b } => cmp!(m, cpu, i32, d, a, b, |x, y| x < y),
            I::LtI64 { d, a, b } => cmp!(m, cpu, i64, d, a, b, |x, y| x < y),
            I::LtU8 { d, a, b } => cmp!(m, cpu, u8, d, a, b, |x, y| x < y),
            I::LtU16 { d, a, b } => cmp!(m, cpu, u16, d, a, b, |x, y| x < y),
            I::LtU32 { d, a, b } => cmp!(m, cpu, u32, d, a, b, |x, y| x < y),
            I::LtU64 { d, a, b } => cmp!(m, cpu, u64, d, a, b, |x, y| x < y),
            I::LtF32 { d, a, b } => cmp!(m, cpu, f32, d, a, b, |x, y| x < y),
            I::LtF64 { d, a, b } => cmp!(m, cpu, f64, d, a, b, |x, y| x < y),
            I::LeI8 { d, a, b } => cmp!(m, cpu, i8, d, a, b, |x, y| x <= y),
            I::LeI16 { d, a, b } => cmp!(m, cpu, i16, d, a, b, |x, y| x <= y),
            I::LeI32 { d, a, b } => cmp!(m, cpu, i32, d, a, b, |x, y| x <= y),
            I::LeI64 { d, a, b } => cmp!(m, cpu, i64, d, a, b, |x, y| x <= y),
            I::LeU8 { d, a, b } => cmp!(m, cpu, u8, d, a, b, |x, y| x <= y),
            I::LeU16 { d, a, b } => cmp!(m, cpu, u16, d, a, b, |x, y| x <= y),
            I::LeU32 { d, a, b } => cmp!(m, cpu, u32, d, a, b, |x, y| x <= y),
            I::LeU64 { d, a, b } => cmp!(m, cpu, u64, d, a, b, |x, y| x <= y),
            I::LeF32 { d, a, b } => cmp!(m, cpu, f32, d, a, b, |x, y| x <= y),
            I::LeF64 { d, a, b } => cmp!(m, cpu, f64, d, a, b, |x, y| x <= y),
            I::And8 { d, a, b } => bin!(m, cpu, u8, d, a, b, |x, y| x & y),
            I::And16 { d, a, b } => bin!(m, cpu, u16, d, a, b, |x, y| x & y),
            I::And32 { d, a, b } => bin!(m, cpu, u32, d, a, b, |x, y| x & y),
            I::And64 { d, a, b } => bin!(m, cpu, u64, d, a, b, |x, y| x & y),
            I::Or8 { d, a, b } => bin!(m, cpu, u8, d, a, b, |x, y| x | y),
            I::Or16 { d, a, b } => bin!(m, cpu, u16, d, a, b, |x, y| x | y),
            I::Or32 { d, a, b } => bin!(m, cpu, u32, d, a, b, |x, y| x | y),
            I::Or64 { d, a, b } => bin!(m, cpu, u64, d, a, b, |x, y| x | y),
            I::Xor8 { d, a, b } => bin!(m, cpu, u8, d, a, b, |x, y| x ^ y),
            I::Xor16 { d, a, b } => bin!(m, cpu, u16, d, a, b, |x, y| x ^ y),
            I::Xor32 { d, a, b } => bin!(m, cpu, u32, d, a, b, |x, y| x ^ y),
            I::Xor64 { d, a, b } => bin!(m, cpu, u64, d, a, b, |x, y| x ^ y),
            I::Not8 { d, a } => un!(m, cpu, u8, d, a, |x| !x),
            I::Not16 { d, a } => un!(m, cpu, u16, d, a, |x| !x),
            I::Not32 { d, a } => un!(m, cpu, u32, d, a, |x| !x),
            I::Not64 { d, a } => un!(m, cpu, u64, d, a, |x| !x),
            I::NotB { d, a } => un!(m, cpu, u8, d, a, |x| (x == 0) as u8),
            I::Cvt { d, a, from, to } => {
                let (Some(f), Some(t)) = (Num::from_code(from), Num::from_code(to)) else {
                    return Err(Trap::Invalid);
                };
                convert(m, addr(&cpu.bases, d), addr(&cpu.bases, a), f, t)?;
            }
            I::Check { a, lo, hi, num } => {
                let n = Num::from_code(num).ok_or(Trap::Invalid)?;
                let (v, _) = read_num(m, addr(&cpu.bases, a), n)?;
                let (l, _) = read_num(m, addr(&cpu.bases, lo), n)?;
                let (h, _) = read_num(m, addr(&cpu.bases, hi), n)?;
                if v < l || v > h {
                    return Err(Trap::Fault(FaultKind::SubrangeViolation));
                }
            }
            I::GetPart {
                d,
                a,
                width,
                part,
                index,
            } => {
                let w = read_width(m, addr(&cpu.bases, a), width)?;
                let mask = if part >= 64 {
                    u64::MAX
                } else {
                    (1u64 << part) - 1
                };
                let shift = index.saturating_mul(part);
                let v = if shift >= 64 { 0 } else { (w >> shift) & mask };
                write_width(m, addr(&cpu.bases, d), part.max(8), v)?;
            }
            I::SetPart {
                d,
                a,
                width,
                part,
                index,
            } => {
                let da = addr(&cpu.bases, d);
                let w = read_width(m, da, width)?;
                let v = read_width(m, addr(&cpu.bases, a), part.max(8))?;
                let mask = if part >= 64 {
                    u64::MAX
                } else {
                    (1u64 << part) - 1
                };
                let shift = index.saturating_mul(part);
                if shift < 64 {
                    let nw = (w & !(mask << shift)) | ((v & mask) << shift);
                    write_width(m, da, width, nw)?;
                }
            }
            I::Lea { d, a } => st::<u32>(m, addr(&cpu.bases, d), addr(&cpu.bases, a) as u32)?,
            I::Index {
                d,
                a,
                idx,
                lo,
                count,
                stride,
            } => {
                let base = ld::<u32>(m, addr(&cpu.bases, a))? as u64;
                let i = ld::<i64>(m, addr(&cpu.bases, idx))? as i128;
                let l = ld::<i64>(m, addr(&cpu.bases, lo))? as i128;
                let k = i - l;
                if k < 0 || k >= count as i128 {
                    return Err(Trap::Fault(FaultKind::IndexOutOfBounds));
                }
                let p = base + k as u64 * stride as u64;
                st::<u32>(
                    m,
                    addr(&cpu.bases, d),
                    u32::try_from(p).map_err(|_| Trap::Invalid)?,
                )?;
            }
            I::Load { d, p, off, len } => {
                let src = ld::<u32>(m, addr(&cpu.bases, p))? as usize + off as usize;
                copy(m, addr(&cpu.bases, d), src, len as usize)?;
            }
            I::Store { p, a, off, len } => {
                let dst = ld::<u32>(m, addr(&cpu.bases, p))? as usize + off as usize;
                copy(m, dst, addr(&cpu.bases, a), len as usize)?;
            }
            I::Jmp { t } => cpu.pc = t.0 as usize,
            I::Jz { c, t } => {
                if ld::<u8>(m, addr(&cpu.bases, c))? == 0 {
                    cpu.pc = t.0 as usize;
                }
            }
            I::Jnz { c, t } => {
                if ld::<u8>(m, addr(&cpu.bases, c))? != 0 {
                    cpu.pc = t.0 as usize;
                }
            }
            I::JltI32 { a, b, t } => {
                let x: i32 = ld(m, addr(&cpu.bases, a))?;
                let y: i32 = ld(m, addr(&cpu.bases, b))?;
                if x < y {
                    cpu.pc = t.0 as usize;
                }
            }
            I::CallFn { pou, frame } => {
                let fp = cpu.bases[0].checked_add(frame).ok_or(Trap::Invalid)?;
                call(image, m, cpu, pou, fp, cpu.bases[1])?;
            }
            I::CallFb { pou, inst, frame } => {
                let fp = cpu.bases[0].checked_add(frame).ok_or(Trap::Invalid)?;
                let this = addr(&cpu.bases, inst) as u32;
                call(image, m, cpu, pou, fp, this)?;
            }
            I::CallFbInd { pou, inst, frame } => {
                let fp = cpu.bases[0].checked_add(frame).ok_or(Trap::Invalid)?;
                let this = ld::<u32>(m, addr(&cpu.bases, inst))?;
                call(image, m, cpu, pou, fp, this)?;
            }
            I::Ret {} => match cpu.calls.pop() {
                Some((pc, fp, this)) => {
                    cpu.pc = pc;
                    cpu.bases[0] = fp;
                    cpu.bases[1] = this;
                }
                None => return Ok(()),
            },
            I::Std { call } => {
                let c = image.calls.get(call as usize).ok_or(Trap::Invalid)?;
                std_call(m, &cpu.bases, c)?;
            }
            I::CurTime { d } => st::<i64>(m, addr(&cpu.bases, d), cpu.now)?,
            I::Fault { kind } => return Err(Trap::Fault(fault_of_code(kind))),
        }
    }
}

fn call(
    image: &Image,
    m: &mut [u8],
    cpu: &mut Cpu,
    pou: u32,
    fp: u32,
    this: u32,
) -> Result<(), Trap> {
    if cpu.calls.len() >= MAX_CALL_DEPTH {
        return Err(Trap::Invalid);
    }
    let entry = image.pous.get(pou as usize).ok_or(Trap::Invalid)?.entry;
    enter_frame(image, m, pou, fp)?;
    cpu.calls.push((cpu.pc, cpu.bases[0], cpu.bases[1]));
    cpu.bases[0] = fp;
    cpu.bases[1] = this;
    cpu.pc = entry as usize;
    Ok(())
}

fn read_width(m: &[u8], a: usize, bits: u32) -> Result<u64, Trap> {
    Ok(match bits {
        0..=8 => ld::<u8>(m, a)? as u64,
        9..=16 => ld::<u16>(m, a)? as u64,
        17..=32 => ld::<u32>(m, a)? as u64,
        _ => ld::<u64>(m, a)?,
    })
}

fn write_width(m: &mut [u8], a: usize, bits: u32, v: u64) -> Result<(), Trap> {
    match bits {
        0..=8 => st::<u8>(m, a, v as u8),
        9..=16 => st::<u16>(m, a, v as u16),
        17..=32 => st::<u32>(m, a, v as u32),
        _ => st::<u64>(m, a, v),
    }
}

/// An operation through `stc_values`: read the operands as values, compute,
/// write the result (strings truncated to their capacity).
fn std_call(m: &mut [u8], bases: &[u32; 4], c: &StdCall) -> Result<(), Trap> {
    let read =
        |m: &[u8], (op, e, cap): (Op, stc_syntax::token::ElemType, u32)| -> Result<Value, Trap> {
            let a = addr(bases, op) as u32;
            match e {
                stc_syntax::token::ElemType::String => read_string(m, a, false, cap),
                stc_syntax::token::ElemType::Wstring => read_string(m, a, true, cap),
                _ => read_scalar(m, a, e),
            }
            .ok_or(Trap::Invalid)
        };
    let mut args = Vec::with_capacity(c.args.len());
    let mut types = Vec::with_capacity(c.args.len());
    for &a in &c.args {
        args.push(read(m, a)?);
        types.push(a.1);
    }
    let (rop, rt, rcap) = c.result;
    let fault = |f: stc_values::Fault| Trap::Fault(stc_ir::FaultKind::from_value_fault(f));
    let v = match c.op {
        StdOp::Call(f) => stc_values::call(f, &types, &args, rt).map_err(fault)?.value,
        StdOp::Binary(op) => {
            let (Some(x), Some(y)) = (args.first(), args.get(1)) else {
                return Err(Trap::Invalid);
            };
            stc_values::binary(op, types[0], x, types[1], y, rt)
                .map_err(fault)?
                .value
        }
        StdOp::Unary(op) => {
            let x = args.first().ok_or(Trap::Invalid)?;
            stc_values::unary(op, types[0], x).map_err(fault)?.value
        }
        StdOp::Convert => {
            let x = args.first().ok_or(Trap::Invalid)?;
            stc_values::convert(types[0], rt, x).map_err(fault)?
        }
        StdOp::Trunc => {
            let x = args.first().ok_or(Trap::Invalid)?;
            stc_values::trunc(types[0], rt, x).map_err(fault)?
        }
    };
    let a = addr(bases, rop) as u32;
    let ok = match rt {
        stc_syntax::token::ElemType::String => write_string(m, a, false, rcap, &v),
        stc_syntax::token::ElemType::Wstring => write_string(m, a, true, rcap, &v),
        _ => write_scalar(m, a, rt, &v),
    };
    if ok {
        Ok(())
    } else {
        Err(Trap::Invalid)
    }
}
