//! The interpreter loop.
//!
//! One `match` over pre-decoded instructions; an operand's address is its
//! base (frame, instance or absolute) plus its offset, computed without a
//! branch. Every memory access is bounds-checked against the machine's byte
//! array, so no bytecode can reach outside it, verified or not; a failed
//! check is an "invalid bytecode" fault, never a crash. The step budget
//! counts every instruction (the watchdog of `--max-steps`).

use std::cmp::Ordering::{Equal, Less};

use stc_ir::FaultKind;
use stc_values::Value;

use crate::compile::fault_of_code;
use crate::image::{Image, StdCall, StdOp};
use crate::instr::{Instr, Op, OFFSET_MASK};
use crate::machine::{read_scalar, read_string, write_scalar, write_string, Machine, VmFault};
use crate::num::Num;

/// Why execution stopped early.
#[derive(Clone, Debug, PartialEq, Eq)]
enum Trap {
    Fault(FaultKind),
    /// A value outside its range (an index, a subrange): the kind, the
    /// value and the bounds (boxed: faults are rare, the trap stays small).
    Range(Box<(FaultKind, i128, i128, i128)>),
    /// Memory outside the machine, a bad jump or call: only corrupt bytecode.
    Invalid,
}

/// The deepest chain of calls (the verifier refuses deeper call graphs).
pub(crate) const MAX_CALL_DEPTH: usize = 1024;

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
    ) -> Result<u64, VmFault> {
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
            Ok(()) => Ok(max_steps - cpu.steps),
            Err(t) => {
                let (kind, range) = match t {
                    Trap::Fault(k) => (k, None),
                    Trap::Range(r) => (r.0, Some((r.1, r.2, r.3))),
                    Trap::Invalid => (FaultKind::InvalidCode, None),
                };
                let mut f = self.fault_at(kind, cpu.pc as u32);
                if let Some((v, lo, hi)) = range {
                    f = f.out_of_range(v, lo, hi);
                }
                f.instance_at = innermost_instance(&image, &cpu);
                Err(f)
            }
        }
    }
}

/// The innermost function block or program instance running when the
/// run stopped: (data address, POU). A function runs with its caller's
/// instance register, so the address is the current one; its POU is the
/// first one that is not a function, from the current code outwards
/// through the return addresses.
fn innermost_instance(image: &Image, cpu: &Cpu) -> Option<(u32, u32)> {
    let pcs = std::iter::once(cpu.pc).chain(cpu.calls.iter().rev().map(|c| c.0));
    for pc in pcs {
        let pou = image.pou_at(u32::try_from(pc).ok()?)?;
        if image.model.pous.get(pou as usize)?.kind != stc_ir::model::PouKind::Function {
            return Some((cpu.bases[1], pou));
        }
    }
    None
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

/// `?` for the interpreter loop: leaves the loop with the error, so the
/// loop's state (kept in locals) is written back once.
macro_rules! tr {
    ($e:expr) => {
        match $e {
            Ok(v) => v,
            Err(e) => break Err(e),
        }
    };
}

macro_rules! bin {
    ($m:ident, $b:ident, $t:ty, $d:ident, $a:ident, $bb:ident, |$x:ident, $y:ident| $e:expr) => {{
        let $x: $t = tr!(ld($m, addr(&$b, $a)));
        let $y: $t = tr!(ld($m, addr(&$b, $bb)));
        tr!(st($m, addr(&$b, $d), $e));
    }};
}

macro_rules! cmp {
    ($m:ident, $b:ident, $t:ty, $d:ident, $a:ident, $bb:ident, |$x:ident, $y:ident| $e:expr) => {{
        let $x: $t = tr!(ld($m, addr(&$b, $a)));
        let $y: $t = tr!(ld($m, addr(&$b, $bb)));
        tr!(st_bool($m, addr(&$b, $d), $e));
    }};
}

macro_rules! un {
    ($m:ident, $b:ident, $t:ty, $d:ident, $a:ident, |$x:ident| $e:expr) => {{
        let $x: $t = tr!(ld($m, addr(&$b, $a)));
        tr!(st($m, addr(&$b, $d), $e));
    }};
}

macro_rules! div {
    ($m:ident, $b:ident, $t:ty, $d:ident, $a:ident, $bb:ident, $op:ident) => {{
        let x: $t = tr!(ld($m, addr(&$b, $a)));
        let y: $t = tr!(ld($m, addr(&$b, $bb)));
        if y == 0 {
            break Err(Trap::Fault(FaultKind::DivisionByZero));
        }
        tr!(st($m, addr(&$b, $d), x.$op(y)));
    }};
}

/// Compare and branch.
macro_rules! jcmp {
    ($m:ident, $b:ident, $pc:ident, $t:ty, $a:ident, $bb:ident, $tg:ident, |$x:ident, $y:ident| $e:expr) => {{
        let $x: $t = tr!(ld($m, addr(&$b, $a)));
        let $y: $t = tr!(ld($m, addr(&$b, $bb)));
        if $e {
            $pc = $tg.0 as usize;
        }
    }};
}

/// The FOR latch: step without overflow, then compare with the end and
/// branch; an overflowing step ends the loop.
macro_rules! forstep {
    ($m:ident, $b:ident, $pc:ident, $t:ty, $v:ident, $s:ident, $e:ident, $tg:ident, $up:expr) => {{
        let va = addr(&$b, $v);
        let x: $t = tr!(ld($m, va));
        let s: $t = tr!(ld($m, addr(&$b, $s)));
        let e: $t = tr!(ld($m, addr(&$b, $e)));
        let next = if $up { x.checked_add(s) } else { x.checked_sub(s) };
        if let Some(n) = next {
            tr!(st($m, va, n));
            if if $up { n <= e } else { n >= e } {
                $pc = $tg.0 as usize;
            }
        }
    }};
}

/// Load or store a scalar through a pointer.
macro_rules! ldp {
    ($m:ident, $b:ident, $t:ty, $d:ident, $p:ident, $off:ident) => {{
        let src = (tr!(ld::<u32>($m, addr(&$b, $p))) as usize).wrapping_add($off as usize);
        let v: $t = tr!(ld($m, src));
        tr!(st($m, addr(&$b, $d), v));
    }};
}
macro_rules! stp {
    ($m:ident, $b:ident, $t:ty, $p:ident, $a:ident, $off:ident) => {{
        let dst = (tr!(ld::<u32>($m, addr(&$b, $p))) as usize).wrapping_add($off as usize);
        let v: $t = tr!(ld($m, addr(&$b, $a)));
        tr!(st($m, dst, v));
    }};
}

/// Load or store an array element.
macro_rules! ldelem {
    ($m:ident, $b:ident, $img:ident, $t:ty, $d:ident, $a:ident, $idx:ident, $desc:ident) => {{
        let at = tr!(elem_addr($m, $img, addr(&$b, $a), addr(&$b, $idx), $desc));
        let v: $t = tr!(ld($m, at));
        tr!(st($m, addr(&$b, $d), v));
    }};
}
macro_rules! stelem {
    ($m:ident, $b:ident, $img:ident, $t:ty, $a:ident, $idx:ident, $v:ident, $desc:ident) => {{
        let at = tr!(elem_addr($m, $img, addr(&$b, $a), addr(&$b, $idx), $desc));
        let v: $t = tr!(ld($m, addr(&$b, $v)));
        tr!(st($m, at, v));
    }};
}

#[inline(always)]
fn addr(bases: &[u32; 4], op: Op) -> usize {
    bases[(op.0 >> 30) as usize].wrapping_add(op.0 & OFFSET_MASK) as usize
}

/// Reads an array index of scalar kind `n` as an `i64` (`None`: a 64-bit
/// unsigned value beyond `i64`, out of every range).
#[inline(always)]
fn read_index(m: &[u8], a: usize, n: Num) -> Result<Option<i64>, Trap> {
    Ok(Some(match n {
        Num::I16 => ld::<i16>(m, a)? as i64,
        Num::I32 => ld::<i32>(m, a)? as i64,
        Num::I64 => ld::<i64>(m, a)?,
        Num::I8 => ld::<i8>(m, a)? as i64,
        Num::U8 | Num::B => ld::<u8>(m, a)? as i64,
        Num::U16 => ld::<u16>(m, a)? as i64,
        Num::U32 => ld::<u32>(m, a)? as i64,
        Num::U64 => match i64::try_from(ld::<u64>(m, a)?) {
            Ok(v) => v,
            Err(_) => return Ok(None),
        },
        Num::F32 | Num::F64 => return Err(Trap::Invalid),
    }))
}

/// The address of element `idx` of the array at `base`, bounds-checked.
#[inline(always)]
fn elem_addr(m: &[u8], img: &Image, base: usize, idx: usize, desc: u32) -> Result<usize, Trap> {
    let d = img.elems.get(desc as usize).ok_or(Trap::Invalid)?;
    let k = read_index(m, idx, d.num)?
        .and_then(|i| i.checked_sub(d.lo))
        .filter(|k| (*k as u64) < d.count as u64);
    match k {
        Some(k) => Ok(base.wrapping_add(k as usize * d.stride as usize)),
        None => Err(index_fault(m, idx, d)),
    }
}

/// The fault of an index outside its array's bounds, with its value.
#[cold]
fn index_fault(m: &[u8], idx: usize, d: &crate::image::ElemDesc) -> Trap {
    let value = match d.num {
        Num::U64 => ld::<u64>(m, idx).map(i128::from),
        n => read_num(m, idx, n).map(|(v, _)| v),
    };
    match value {
        Ok(v) => {
            let lo = i128::from(d.lo);
            Trap::Range(Box::new((
                FaultKind::IndexOutOfBounds,
                v,
                lo,
                lo + i128::from(d.count) - 1,
            )))
        }
        Err(t) => t,
    }
}

/// MIN or MAX of two scalars of kind `n`: `b` when it compares `want`
/// against `a` (so a NaN keeps `a`), as `stc_values` picks.
fn min_max(m: &mut [u8], d: usize, a: usize, b: usize, n: Num, max: bool) -> Result<(), Trap> {
    macro_rules! pick {
        ($t:ty) => {{
            let x: $t = ld(m, a)?;
            let y: $t = ld(m, b)?;
            st(
                m,
                d,
                if (max && y > x) || (!max && y < x) {
                    y
                } else {
                    x
                },
            )
        }};
    }
    match n {
        Num::I8 => pick!(i8),
        Num::I16 => pick!(i16),
        Num::I32 => pick!(i32),
        Num::I64 => pick!(i64),
        Num::U8 | Num::B => pick!(u8),
        Num::U16 => pick!(u16),
        Num::U32 => pick!(u32),
        Num::U64 => pick!(u64),
        Num::F32 => pick!(f32),
        Num::F64 => pick!(f64),
    }
}

/// LIMIT(lo, x, hi) as `stc_values` computes it: `max(x, lo)`, then `min` with `hi`.
fn limit(m: &mut [u8], d: usize, lo: usize, a: usize, hi: usize, n: Num) -> Result<(), Trap> {
    macro_rules! lim {
        ($t:ty) => {{
            let l: $t = ld(m, lo)?;
            let x: $t = ld(m, a)?;
            let h: $t = ld(m, hi)?;
            let low = if l > x { l } else { x };
            st(m, d, if h < low { h } else { low })
        }};
    }
    match n {
        Num::I8 => lim!(i8),
        Num::I16 => lim!(i16),
        Num::I32 => lim!(i32),
        Num::I64 => lim!(i64),
        Num::U8 | Num::B => lim!(u8),
        Num::U16 => lim!(u16),
        Num::U32 => lim!(u32),
        Num::U64 => lim!(u64),
        Num::F32 => lim!(f32),
        Num::F64 => lim!(f64),
    }
}

/// ABS: integers wrap (`ABS(INT#-32768)` is -32768), reals clear the sign.
fn abs(m: &mut [u8], d: usize, a: usize, n: Num) -> Result<(), Trap> {
    match n {
        Num::I8 => st(m, d, ld::<i8>(m, a)?.wrapping_abs()),
        Num::I16 => st(m, d, ld::<i16>(m, a)?.wrapping_abs()),
        Num::I32 => st(m, d, ld::<i32>(m, a)?.wrapping_abs()),
        Num::I64 => st(m, d, ld::<i64>(m, a)?.wrapping_abs()),
        Num::F32 => st(m, d, ld::<f32>(m, a)?.abs()),
        Num::F64 => st(m, d, ld::<f64>(m, a)?.abs()),
        Num::U8 | Num::B => st(m, d, ld::<u8>(m, a)?),
        Num::U16 => st(m, d, ld::<u16>(m, a)?),
        Num::U32 => st(m, d, ld::<u32>(m, a)?),
        Num::U64 => st(m, d, ld::<u64>(m, a)?),
    }
}

/// SHL, SHR, ROL, ROR on the bit pattern of the value's width; a count at
/// or above the width shifts everything out, rotations go modulo the width,
/// a negative count goes the other way (as `stc_values`).
fn shift(
    m: &mut [u8],
    d: usize,
    a: usize,
    n: usize,
    op: u32,
    num: Num,
    nnum: Num,
) -> Result<(), Trap> {
    let w = match num {
        Num::B => 1u32,
        Num::F32 | Num::F64 => return Err(Trap::Invalid),
        k => k.size() * 8,
    };
    let (v, _) = read_num(m, a, num)?;
    let (count, _) = read_num(m, n, nnum)?;
    if nnum.is_float() || op > 3 {
        return Err(Trap::Invalid);
    }
    let mask: u64 = if w == 64 { u64::MAX } else { (1u64 << w) - 1 };
    let u = (v as u64) & mask;
    let left = (op == 0 || op == 2) == (count >= 0);
    let out = if op < 2 {
        let c = count.unsigned_abs();
        if c >= w as u128 {
            0
        } else if left {
            (u << c) & mask
        } else {
            u >> c
        }
    } else {
        let k = count.rem_euclid(w as i128) as u32;
        let k = if op == 2 { k } else { (w - k) % w };
        if k == 0 {
            u
        } else {
            ((u << k) | (u >> (w - k))) & mask
        }
    };
    write_width(m, d, w.max(8), out)
}

fn run(image: &Image, m: &mut [u8], cpu: &mut Cpu) -> Result<(), Trap> {
    let code = &image.code[..];
    let mut pc = cpu.pc;
    let mut steps = cpu.steps;
    let mut b = cpu.bases;
    // The instruction being executed (where a fault is reported).
    let mut cur;
    let r = loop {
        cur = pc;
        if steps == 0 {
            break Err(Trap::Fault(FaultKind::Watchdog));
        }
        steps -= 1;
        let Some(&ins) = code.get(pc) else {
            break Err(Trap::Invalid);
        };
        pc += 1;
        use Instr as I;
        match ins {
            I::Nop {} => {}
            I::Mov1 { d, a } => un!(m, b, u8, d, a, |x| x),
            I::Mov2 { d, a } => un!(m, b, u16, d, a, |x| x),
            I::Mov4 { d, a } => un!(m, b, u32, d, a, |x| x),
            I::Mov8 { d, a } => un!(m, b, u64, d, a, |x| x),
            I::Copy { d, a, len } => tr!(copy(m, addr(&b, d), addr(&b, a), len as usize)),
            I::StrCopy { d, a, cap, unit } => {
                let (da, sa) = (addr(&b, d), addr(&b, a));
                let len = (tr!(ld::<u16>(m, sa)) as u32).min(cap);
                tr!(copy(m, da + 2, sa + 2, (len * unit) as usize));
                tr!(st::<u16>(m, da, len as u16));
            }
            I::Add8 { d, a, b: c } => bin!(m, b, u8, d, a, c, |x, y| x.wrapping_add(y)),
            I::Add16 { d, a, b: c } => bin!(m, b, u16, d, a, c, |x, y| x.wrapping_add(y)),
            I::Add32 { d, a, b: c } => bin!(m, b, u32, d, a, c, |x, y| x.wrapping_add(y)),
            I::Add64 { d, a, b: c } => bin!(m, b, u64, d, a, c, |x, y| x.wrapping_add(y)),
            I::Sub8 { d, a, b: c } => bin!(m, b, u8, d, a, c, |x, y| x.wrapping_sub(y)),
            I::Sub16 { d, a, b: c } => bin!(m, b, u16, d, a, c, |x, y| x.wrapping_sub(y)),
            I::Sub32 { d, a, b: c } => bin!(m, b, u32, d, a, c, |x, y| x.wrapping_sub(y)),
            I::Sub64 { d, a, b: c } => bin!(m, b, u64, d, a, c, |x, y| x.wrapping_sub(y)),
            I::Mul8 { d, a, b: c } => bin!(m, b, u8, d, a, c, |x, y| x.wrapping_mul(y)),
            I::Mul16 { d, a, b: c } => bin!(m, b, u16, d, a, c, |x, y| x.wrapping_mul(y)),
            I::Mul32 { d, a, b: c } => bin!(m, b, u32, d, a, c, |x, y| x.wrapping_mul(y)),
            I::Mul64 { d, a, b: c } => bin!(m, b, u64, d, a, c, |x, y| x.wrapping_mul(y)),
            I::Neg8 { d, a } => un!(m, b, u8, d, a, |x| x.wrapping_neg()),
            I::Neg16 { d, a } => un!(m, b, u16, d, a, |x| x.wrapping_neg()),
            I::Neg32 { d, a } => un!(m, b, u32, d, a, |x| x.wrapping_neg()),
            I::Neg64 { d, a } => un!(m, b, u64, d, a, |x| x.wrapping_neg()),
            I::DivI8 { d, a, b: c } => div!(m, b, i8, d, a, c, wrapping_div),
            I::DivI16 { d, a, b: c } => div!(m, b, i16, d, a, c, wrapping_div),
            I::DivI32 { d, a, b: c } => div!(m, b, i32, d, a, c, wrapping_div),
            I::DivI64 { d, a, b: c } => div!(m, b, i64, d, a, c, wrapping_div),
            I::DivU8 { d, a, b: c } => div!(m, b, u8, d, a, c, wrapping_div),
            I::DivU16 { d, a, b: c } => div!(m, b, u16, d, a, c, wrapping_div),
            I::DivU32 { d, a, b: c } => div!(m, b, u32, d, a, c, wrapping_div),
            I::DivU64 { d, a, b: c } => div!(m, b, u64, d, a, c, wrapping_div),
            I::ModI8 { d, a, b: c } => div!(m, b, i8, d, a, c, wrapping_rem),
            I::ModI16 { d, a, b: c } => div!(m, b, i16, d, a, c, wrapping_rem),
            I::ModI32 { d, a, b: c } => div!(m, b, i32, d, a, c, wrapping_rem),
            I::ModI64 { d, a, b: c } => div!(m, b, i64, d, a, c, wrapping_rem),
            I::ModU8 { d, a, b: c } => div!(m, b, u8, d, a, c, wrapping_rem),
            I::ModU16 { d, a, b: c } => div!(m, b, u16, d, a, c, wrapping_rem),
            I::ModU32 { d, a, b: c } => div!(m, b, u32, d, a, c, wrapping_rem),
            I::ModU64 { d, a, b: c } => div!(m, b, u64, d, a, c, wrapping_rem),
            I::AddF32 { d, a, b: c } => bin!(m, b, f32, d, a, c, |x, y| x + y),
            I::AddF64 { d, a, b: c } => bin!(m, b, f64, d, a, c, |x, y| x + y),
            I::SubF32 { d, a, b: c } => bin!(m, b, f32, d, a, c, |x, y| x - y),
            I::SubF64 { d, a, b: c } => bin!(m, b, f64, d, a, c, |x, y| x - y),
            I::MulF32 { d, a, b: c } => bin!(m, b, f32, d, a, c, |x, y| x * y),
            I::MulF64 { d, a, b: c } => bin!(m, b, f64, d, a, c, |x, y| x * y),
            I::DivF32 { d, a, b: c } => bin!(m, b, f32, d, a, c, |x, y| x / y),
            I::DivF64 { d, a, b: c } => bin!(m, b, f64, d, a, c, |x, y| x / y),
            I::NegF32 { d, a } => un!(m, b, f32, d, a, |x| -x),
            I::NegF64 { d, a } => un!(m, b, f64, d, a, |x| -x),
            I::Eq8 { d, a, b: c } => cmp!(m, b, u8, d, a, c, |x, y| x == y),
            I::Eq16 { d, a, b: c } => cmp!(m, b, u16, d, a, c, |x, y| x == y),
            I::Eq32 { d, a, b: c } => cmp!(m, b, u32, d, a, c, |x, y| x == y),
            I::Eq64 { d, a, b: c } => cmp!(m, b, u64, d, a, c, |x, y| x == y),
            I::EqF32 { d, a, b: c } => cmp!(m, b, f32, d, a, c, |x, y| x == y),
            I::EqF64 { d, a, b: c } => cmp!(m, b, f64, d, a, c, |x, y| x == y),
            I::Ne8 { d, a, b: c } => cmp!(m, b, u8, d, a, c, |x, y| x != y),
            I::Ne16 { d, a, b: c } => cmp!(m, b, u16, d, a, c, |x, y| x != y),
            I::Ne32 { d, a, b: c } => cmp!(m, b, u32, d, a, c, |x, y| x != y),
            I::Ne64 { d, a, b: c } => cmp!(m, b, u64, d, a, c, |x, y| x != y),
            I::NeF32 { d, a, b: c } => cmp!(m, b, f32, d, a, c, |x, y| x != y),
            I::NeF64 { d, a, b: c } => cmp!(m, b, f64, d, a, c, |x, y| x != y),
            I::LtI8 { d, a, b: c } => cmp!(m, b, i8, d, a, c, |x, y| x < y),
            I::LtI16 { d, a, b: c } => cmp!(m, b, i16, d, a, c, |x, y| x < y),
            I::LtI32 { d, a, b: c } => cmp!(m, b, i32, d, a, c, |x, y| x < y),
            I::LtI64 { d, a, b: c } => cmp!(m, b, i64, d, a, c, |x, y| x < y),
            I::LtU8 { d, a, b: c } => cmp!(m, b, u8, d, a, c, |x, y| x < y),
            I::LtU16 { d, a, b: c } => cmp!(m, b, u16, d, a, c, |x, y| x < y),
            I::LtU32 { d, a, b: c } => cmp!(m, b, u32, d, a, c, |x, y| x < y),
            I::LtU64 { d, a, b: c } => cmp!(m, b, u64, d, a, c, |x, y| x < y),
            I::LtF32 { d, a, b: c } => cmp!(m, b, f32, d, a, c, |x, y| x < y),
            I::LtF64 { d, a, b: c } => cmp!(m, b, f64, d, a, c, |x, y| x < y),
            I::LeI8 { d, a, b: c } => cmp!(m, b, i8, d, a, c, |x, y| x <= y),
            I::LeI16 { d, a, b: c } => cmp!(m, b, i16, d, a, c, |x, y| x <= y),
            I::LeI32 { d, a, b: c } => cmp!(m, b, i32, d, a, c, |x, y| x <= y),
            I::LeI64 { d, a, b: c } => cmp!(m, b, i64, d, a, c, |x, y| x <= y),
            I::LeU8 { d, a, b: c } => cmp!(m, b, u8, d, a, c, |x, y| x <= y),
            I::LeU16 { d, a, b: c } => cmp!(m, b, u16, d, a, c, |x, y| x <= y),
            I::LeU32 { d, a, b: c } => cmp!(m, b, u32, d, a, c, |x, y| x <= y),
            I::LeU64 { d, a, b: c } => cmp!(m, b, u64, d, a, c, |x, y| x <= y),
            I::LeF32 { d, a, b: c } => cmp!(m, b, f32, d, a, c, |x, y| x <= y),
            I::LeF64 { d, a, b: c } => cmp!(m, b, f64, d, a, c, |x, y| x <= y),
            I::And8 { d, a, b: c } => bin!(m, b, u8, d, a, c, |x, y| x & y),
            I::And16 { d, a, b: c } => bin!(m, b, u16, d, a, c, |x, y| x & y),
            I::And32 { d, a, b: c } => bin!(m, b, u32, d, a, c, |x, y| x & y),
            I::And64 { d, a, b: c } => bin!(m, b, u64, d, a, c, |x, y| x & y),
            I::Or8 { d, a, b: c } => bin!(m, b, u8, d, a, c, |x, y| x | y),
            I::Or16 { d, a, b: c } => bin!(m, b, u16, d, a, c, |x, y| x | y),
            I::Or32 { d, a, b: c } => bin!(m, b, u32, d, a, c, |x, y| x | y),
            I::Or64 { d, a, b: c } => bin!(m, b, u64, d, a, c, |x, y| x | y),
            I::Xor8 { d, a, b: c } => bin!(m, b, u8, d, a, c, |x, y| x ^ y),
            I::Xor16 { d, a, b: c } => bin!(m, b, u16, d, a, c, |x, y| x ^ y),
            I::Xor32 { d, a, b: c } => bin!(m, b, u32, d, a, c, |x, y| x ^ y),
            I::Xor64 { d, a, b: c } => bin!(m, b, u64, d, a, c, |x, y| x ^ y),
            I::Not8 { d, a } => un!(m, b, u8, d, a, |x| !x),
            I::Not16 { d, a } => un!(m, b, u16, d, a, |x| !x),
            I::Not32 { d, a } => un!(m, b, u32, d, a, |x| !x),
            I::Not64 { d, a } => un!(m, b, u64, d, a, |x| !x),
            I::NotB { d, a } => un!(m, b, u8, d, a, |x| (x == 0) as u8),
            I::Cvt { d, a, from, to } => {
                let (Some(f), Some(t)) = (Num::from_code(from), Num::from_code(to)) else {
                    break Err(Trap::Invalid);
                };
                tr!(convert(m, addr(&b, d), addr(&b, a), f, t));
            }
            I::Check { a, lo, hi, num } => {
                let n = tr!(Num::from_code(num).ok_or(Trap::Invalid));
                let (v, _) = tr!(read_num(m, addr(&b, a), n));
                let (l, _) = tr!(read_num(m, addr(&b, lo), n));
                let (h, _) = tr!(read_num(m, addr(&b, hi), n));
                if v < l || v > h {
                    break Err(Trap::Range(Box::new((
                        FaultKind::SubrangeViolation,
                        v,
                        l,
                        h,
                    ))));
                }
            }
            I::GetPart {
                d,
                a,
                width,
                part,
                index,
            } => {
                let w = tr!(read_width(m, addr(&b, a), width));
                let mask = if part >= 64 {
                    u64::MAX
                } else {
                    (1u64 << part) - 1
                };
                let shift = index.saturating_mul(part);
                let v = if shift >= 64 { 0 } else { (w >> shift) & mask };
                tr!(write_width(m, addr(&b, d), part.max(8), v));
            }
            I::SetPart {
                d,
                a,
                width,
                part,
                index,
            } => {
                let da = addr(&b, d);
                let w = tr!(read_width(m, da, width));
                let v = tr!(read_width(m, addr(&b, a), part.max(8)));
                let mask = if part >= 64 {
                    u64::MAX
                } else {
                    (1u64 << part) - 1
                };
                let shift = index.saturating_mul(part);
                if shift < 64 {
                    let nw = (w & !(mask << shift)) | ((v & mask) << shift);
                    tr!(write_width(m, da, width, nw));
                }
            }
            I::Lea { d, a } => tr!(st::<u32>(m, addr(&b, d), addr(&b, a) as u32)),
            I::Load { d, p, off, len } => {
                let src = tr!(ld::<u32>(m, addr(&b, p))) as usize + off as usize;
                tr!(copy(m, addr(&b, d), src, len as usize));
            }
            I::Store { p, a, off, len } => {
                let dst = tr!(ld::<u32>(m, addr(&b, p))) as usize + off as usize;
                tr!(copy(m, dst, addr(&b, a), len as usize));
            }
            I::Jmp { t } => pc = t.0 as usize,
            I::Jz { c, t } => {
                if tr!(ld::<u8>(m, addr(&b, c))) == 0 {
                    pc = t.0 as usize;
                }
            }
            I::Jnz { c, t } => {
                if tr!(ld::<u8>(m, addr(&b, c))) != 0 {
                    pc = t.0 as usize;
                }
            }
            I::JltI8 { a, b: c, t } => jcmp!(m, b, pc, i8, a, c, t, |x, y| x < y),
            I::JltI16 { a, b: c, t } => jcmp!(m, b, pc, i16, a, c, t, |x, y| x < y),
            I::JltI32 { a, b: c, t } => jcmp!(m, b, pc, i32, a, c, t, |x, y| x < y),
            I::JltI64 { a, b: c, t } => jcmp!(m, b, pc, i64, a, c, t, |x, y| x < y),
            I::JltU8 { a, b: c, t } => jcmp!(m, b, pc, u8, a, c, t, |x, y| x < y),
            I::JltU16 { a, b: c, t } => jcmp!(m, b, pc, u16, a, c, t, |x, y| x < y),
            I::JltU32 { a, b: c, t } => jcmp!(m, b, pc, u32, a, c, t, |x, y| x < y),
            I::JltU64 { a, b: c, t } => jcmp!(m, b, pc, u64, a, c, t, |x, y| x < y),
            I::JltF32 { a, b: c, t } => jcmp!(m, b, pc, f32, a, c, t, |x, y| x < y),
            I::JltF64 { a, b: c, t } => jcmp!(m, b, pc, f64, a, c, t, |x, y| x < y),
            I::JleI8 { a, b: c, t } => jcmp!(m, b, pc, i8, a, c, t, |x, y| x <= y),
            I::JleI16 { a, b: c, t } => jcmp!(m, b, pc, i16, a, c, t, |x, y| x <= y),
            I::JleI32 { a, b: c, t } => jcmp!(m, b, pc, i32, a, c, t, |x, y| x <= y),
            I::JleI64 { a, b: c, t } => jcmp!(m, b, pc, i64, a, c, t, |x, y| x <= y),
            I::JleU8 { a, b: c, t } => jcmp!(m, b, pc, u8, a, c, t, |x, y| x <= y),
            I::JleU16 { a, b: c, t } => jcmp!(m, b, pc, u16, a, c, t, |x, y| x <= y),
            I::JleU32 { a, b: c, t } => jcmp!(m, b, pc, u32, a, c, t, |x, y| x <= y),
            I::JleU64 { a, b: c, t } => jcmp!(m, b, pc, u64, a, c, t, |x, y| x <= y),
            I::JleF32 { a, b: c, t } => jcmp!(m, b, pc, f32, a, c, t, |x, y| x <= y),
            I::JleF64 { a, b: c, t } => jcmp!(m, b, pc, f64, a, c, t, |x, y| x <= y),
            I::Jeq8 { a, b: c, t } => jcmp!(m, b, pc, u8, a, c, t, |x, y| x == y),
            I::Jeq16 { a, b: c, t } => jcmp!(m, b, pc, u16, a, c, t, |x, y| x == y),
            I::Jeq32 { a, b: c, t } => jcmp!(m, b, pc, u32, a, c, t, |x, y| x == y),
            I::Jeq64 { a, b: c, t } => jcmp!(m, b, pc, u64, a, c, t, |x, y| x == y),
            I::JeqF32 { a, b: c, t } => jcmp!(m, b, pc, f32, a, c, t, |x, y| x == y),
            I::JeqF64 { a, b: c, t } => jcmp!(m, b, pc, f64, a, c, t, |x, y| x == y),
            I::Jne8 { a, b: c, t } => jcmp!(m, b, pc, u8, a, c, t, |x, y| x != y),
            I::Jne16 { a, b: c, t } => jcmp!(m, b, pc, u16, a, c, t, |x, y| x != y),
            I::Jne32 { a, b: c, t } => jcmp!(m, b, pc, u32, a, c, t, |x, y| x != y),
            I::Jne64 { a, b: c, t } => jcmp!(m, b, pc, u64, a, c, t, |x, y| x != y),
            I::JneF32 { a, b: c, t } => jcmp!(m, b, pc, f32, a, c, t, |x, y| x != y),
            I::JneF64 { a, b: c, t } => jcmp!(m, b, pc, f64, a, c, t, |x, y| x != y),
            I::JnltF32 { a, b: c, t } => jcmp!(m, b, pc, f32, a, c, t, |x, y| x.partial_cmp(&y)
                != Some(Less)),
            I::JnltF64 { a, b: c, t } => jcmp!(m, b, pc, f64, a, c, t, |x, y| x.partial_cmp(&y)
                != Some(Less)),
            I::JnleF32 { a, b: c, t } => jcmp!(m, b, pc, f32, a, c, t, |x, y| !matches!(
                x.partial_cmp(&y),
                Some(Less | Equal)
            )),
            I::JnleF64 { a, b: c, t } => jcmp!(m, b, pc, f64, a, c, t, |x, y| !matches!(
                x.partial_cmp(&y),
                Some(Less | Equal)
            )),
            I::ForUpI8 { v, s, e, t } => forstep!(m, b, pc, i8, v, s, e, t, true),
            I::ForUpI16 { v, s, e, t } => forstep!(m, b, pc, i16, v, s, e, t, true),
            I::ForUpI32 { v, s, e, t } => forstep!(m, b, pc, i32, v, s, e, t, true),
            I::ForUpI64 { v, s, e, t } => forstep!(m, b, pc, i64, v, s, e, t, true),
            I::ForUpU8 { v, s, e, t } => forstep!(m, b, pc, u8, v, s, e, t, true),
            I::ForUpU16 { v, s, e, t } => forstep!(m, b, pc, u16, v, s, e, t, true),
            I::ForUpU32 { v, s, e, t } => forstep!(m, b, pc, u32, v, s, e, t, true),
            I::ForUpU64 { v, s, e, t } => forstep!(m, b, pc, u64, v, s, e, t, true),
            I::ForDnI8 { v, s, e, t } => forstep!(m, b, pc, i8, v, s, e, t, false),
            I::ForDnI16 { v, s, e, t } => forstep!(m, b, pc, i16, v, s, e, t, false),
            I::ForDnI32 { v, s, e, t } => forstep!(m, b, pc, i32, v, s, e, t, false),
            I::ForDnI64 { v, s, e, t } => forstep!(m, b, pc, i64, v, s, e, t, false),
            I::ForDnU8 { v, s, e, t } => forstep!(m, b, pc, u8, v, s, e, t, false),
            I::ForDnU16 { v, s, e, t } => forstep!(m, b, pc, u16, v, s, e, t, false),
            I::ForDnU32 { v, s, e, t } => forstep!(m, b, pc, u32, v, s, e, t, false),
            I::ForDnU64 { v, s, e, t } => forstep!(m, b, pc, u64, v, s, e, t, false),
            I::Elem { d, a, idx, desc } => {
                let at = tr!(elem_addr(m, image, addr(&b, a), addr(&b, idx), desc));
                tr!(st::<u32>(m, addr(&b, d), at as u32));
            }
            I::ElemP { d, p, idx, desc } => {
                let base = tr!(ld::<u32>(m, addr(&b, p))) as usize;
                let at = tr!(elem_addr(m, image, base, addr(&b, idx), desc));
                let at = tr!(u32::try_from(at).map_err(|_| Trap::Invalid));
                tr!(st::<u32>(m, addr(&b, d), at));
            }
            I::LdElem1 { d, a, idx, desc } => ldelem!(m, b, image, u8, d, a, idx, desc),
            I::LdElem2 { d, a, idx, desc } => ldelem!(m, b, image, u16, d, a, idx, desc),
            I::LdElem4 { d, a, idx, desc } => ldelem!(m, b, image, u32, d, a, idx, desc),
            I::LdElem8 { d, a, idx, desc } => ldelem!(m, b, image, u64, d, a, idx, desc),
            I::StElem1 { a, idx, v, desc } => stelem!(m, b, image, u8, a, idx, v, desc),
            I::StElem2 { a, idx, v, desc } => stelem!(m, b, image, u16, a, idx, v, desc),
            I::StElem4 { a, idx, v, desc } => stelem!(m, b, image, u32, a, idx, v, desc),
            I::StElem8 { a, idx, v, desc } => stelem!(m, b, image, u64, a, idx, v, desc),
            I::Ld1 { d, p, off } => ldp!(m, b, u8, d, p, off),
            I::Ld2 { d, p, off } => ldp!(m, b, u16, d, p, off),
            I::Ld4 { d, p, off } => ldp!(m, b, u32, d, p, off),
            I::Ld8 { d, p, off } => ldp!(m, b, u64, d, p, off),
            I::St1 { p, a, off } => stp!(m, b, u8, p, a, off),
            I::St2 { p, a, off } => stp!(m, b, u16, p, a, off),
            I::St4 { p, a, off } => stp!(m, b, u32, p, a, off),
            I::St8 { p, a, off } => stp!(m, b, u64, p, a, off),
            I::Min { d, a, b: c, num } => {
                let n = tr!(Num::from_code(num).ok_or(Trap::Invalid));
                tr!(min_max(m, addr(&b, d), addr(&b, a), addr(&b, c), n, false));
            }
            I::Max { d, a, b: c, num } => {
                let n = tr!(Num::from_code(num).ok_or(Trap::Invalid));
                tr!(min_max(m, addr(&b, d), addr(&b, a), addr(&b, c), n, true));
            }
            I::Limit { d, lo, a, hi, num } => {
                let n = tr!(Num::from_code(num).ok_or(Trap::Invalid));
                tr!(limit(
                    m,
                    addr(&b, d),
                    addr(&b, lo),
                    addr(&b, a),
                    addr(&b, hi),
                    n
                ));
            }
            I::Abs { d, a, num } => {
                let n = tr!(Num::from_code(num).ok_or(Trap::Invalid));
                tr!(abs(m, addr(&b, d), addr(&b, a), n));
            }
            I::Shift {
                d,
                a,
                n,
                op,
                num,
                nnum,
            } => {
                let (Some(k), Some(nk)) = (Num::from_code(num), Num::from_code(nnum)) else {
                    break Err(Trap::Invalid);
                };
                tr!(shift(m, addr(&b, d), addr(&b, a), addr(&b, n), op, k, nk));
            }
            I::Sel { d, g, a, b: c, len } => {
                let src = if tr!(ld::<u8>(m, addr(&b, g))) != 0 {
                    c
                } else {
                    a
                };
                tr!(copy(m, addr(&b, d), addr(&b, src), len as usize));
            }
            I::CallFn { pou, frame } => {
                let fp = tr!(b[0].checked_add(frame).ok_or(Trap::Invalid));
                let this = b[1];
                tr!(call(
                    image,
                    m,
                    &mut cpu.calls,
                    &mut pc,
                    &mut b,
                    pou,
                    fp,
                    this
                ));
            }
            I::CallFb { pou, inst, frame } => {
                let fp = tr!(b[0].checked_add(frame).ok_or(Trap::Invalid));
                let this = addr(&b, inst) as u32;
                tr!(call(
                    image,
                    m,
                    &mut cpu.calls,
                    &mut pc,
                    &mut b,
                    pou,
                    fp,
                    this
                ));
            }
            I::CallFbInd { pou, inst, frame } => {
                let fp = tr!(b[0].checked_add(frame).ok_or(Trap::Invalid));
                let this = tr!(ld::<u32>(m, addr(&b, inst)));
                tr!(call(
                    image,
                    m,
                    &mut cpu.calls,
                    &mut pc,
                    &mut b,
                    pou,
                    fp,
                    this
                ));
            }
            I::Ret {} => match cpu.calls.pop() {
                Some((rpc, fp, this)) => {
                    pc = rpc;
                    b[0] = fp;
                    b[1] = this;
                }
                None => break Ok(()),
            },
            I::Std { call } => {
                let c = tr!(image.calls.get(call as usize).ok_or(Trap::Invalid));
                tr!(std_call(m, &b, c));
            }
            I::CurTime { d } => tr!(st::<i64>(m, addr(&b, d), cpu.now)),
            I::Fault { kind } => break Err(Trap::Fault(fault_of_code(kind))),
        }
    };
    cpu.pc = if r.is_err() { cur } else { pc };
    cpu.steps = steps;
    cpu.bases = b;
    r
}

#[allow(clippy::too_many_arguments)]
#[inline(always)]
fn call(
    image: &Image,
    m: &mut [u8],
    calls: &mut Vec<(usize, u32, u32)>,
    pc: &mut usize,
    bases: &mut [u32; 4],
    pou: u32,
    fp: u32,
    this: u32,
) -> Result<(), Trap> {
    if calls.len() >= MAX_CALL_DEPTH {
        return Err(Trap::Invalid);
    }
    let entry = image.pous.get(pou as usize).ok_or(Trap::Invalid)?.entry;
    enter_frame(image, m, pou, fp)?;
    calls.push((*pc, bases[0], bases[1]));
    bases[0] = fp;
    bases[1] = this;
    *pc = entry as usize;
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
