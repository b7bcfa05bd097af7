//! A running program: its memory and the interpreter state around it.
//!
//! The runtime (scheduling, process image, reports) drives a [`Machine`]:
//! it writes inputs with [`Machine::write_value`], runs program instances
//! with [`Machine::run_program`], and reads variables back. Nothing a
//! program does can touch memory outside this machine's byte array.

use std::sync::Arc;

use stc_ir::FaultKind;
use stc_values::Value;

use crate::image::{Image, ProgramInst, TypeDesc, TypeRef};
pub use stc_ir::model::repr::{read_scalar, read_string, write_scalar, write_string};

/// A run-time fault, located in the source.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct VmFault {
    pub kind: FaultKind,
    /// The POU whose body was running (a function's own name).
    pub pou: String,
    pub file: String,
    pub line: u32,
    pub col: u32,
    /// The innermost function block or program instance whose body was
    /// running (for a fault in a function, the instance that called it),
    /// as the engine knows it: its data-area address and its POU (by
    /// index; an instance can share its address with its first member).
    pub instance_at: Option<(u32, u32)>,
    /// The path of that instance (`Main.scale_b`): given by an engine that
    /// knows it, else resolved from `instance_at` by the runtime.
    pub instance: Option<String>,
    /// The values involved, by name, in order: an index and its array's
    /// bounds (`index`, `lower`, `upper`), a value and the subrange it
    /// left (`value`, `lower`, `upper`), the divisor (`divisor`).
    pub details: Vec<(&'static str, i128)>,
}

impl VmFault {
    /// A fault at a source position in `pou`, its instance not yet known.
    pub fn at(kind: FaultKind, pou: &str, file: &str, line: u32, col: u32) -> VmFault {
        VmFault {
            kind,
            pou: pou.into(),
            file: file.into(),
            line,
            col,
            instance_at: None,
            instance: None,
            // The divisor of a division by zero is known without asking.
            details: match kind {
                FaultKind::DivisionByZero => vec![("divisor", 0)],
                _ => Vec::new(),
            },
        }
    }

    /// The same fault, of a value outside `lo..=hi` (an index, a
    /// subrange): its details.
    pub fn out_of_range(mut self, value: i128, lo: i128, hi: i128) -> VmFault {
        let name = match self.kind {
            FaultKind::IndexOutOfBounds => "index",
            _ => "value",
        };
        self.details = vec![(name, value), ("lower", lo), ("upper", hi)];
        self
    }

    /// [`VmFault::out_of_range`] from the 64-bit patterns a native engine
    /// hands over (C's `stc_fault_range_*`, the JIT's context): the value
    /// and the bounds, and `flags` of [`range_flags`] (nothing when its
    /// `KNOWN` bit is clear).
    pub fn out_of_range_bits(self, [value, lo, hi]: [u64; 3], flags: u32) -> VmFault {
        if flags & range_flags::KNOWN == 0 {
            return self;
        }
        let wide = |bits: u64, unsigned: bool| {
            if unsigned {
                i128::from(bits)
            } else {
                i128::from(bits as i64)
            }
        };
        let bounds = flags & range_flags::BOUNDS_UNSIGNED != 0;
        self.out_of_range(
            wide(value, flags & range_flags::VALUE_UNSIGNED != 0),
            wide(lo, bounds),
            wide(hi, bounds),
        )
    }

    /// The line after the fault's that says what the values were (empty
    /// when there are none): `note: index 11 is outside 1..10`.
    pub fn note(&self) -> String {
        let get = |k: &str| self.details.iter().find(|d| d.0 == k).map(|d| d.1);
        match (self.details.first(), get("lower"), get("upper")) {
            (Some(&(name, v)), Some(lo), Some(hi)) => {
                format!("note: {name} {v} is outside {lo}..{hi}")
            }
            (Some(&("divisor", v)), _, _) => format!("note: the divisor is {v}"),
            (Some(_), _, _) => {
                let parts: Vec<String> = self
                    .details
                    .iter()
                    .map(|(k, v)| format!("{k} = {v}"))
                    .collect();
                format!("note: {}", parts.join(", "))
            }
            (None, _, _) => String::new(),
        }
    }

    /// A fault with no known source position (`?:0:0`) in `pou`.
    pub fn unlocated(kind: FaultKind, pou: &str) -> VmFault {
        VmFault::at(kind, pou, "?", 0, 0)
    }
}

/// The flags of [`VmFault::out_of_range_bits`], as the native engines
/// write them (the C runtime's `stc_fault_range_flags`, stc_rt.h, uses
/// the same bits as literals).
pub mod range_flags {
    /// The value is an unsigned 64-bit pattern.
    pub const VALUE_UNSIGNED: u32 = 1;
    /// The bounds are.
    pub const BOUNDS_UNSIGNED: u32 = 2;
    /// There is a value at all.
    pub const KNOWN: u32 = 4;
}

/// `fault: <kind> in <instance path> (<POU>) at file:line:col`
/// (spec/cli.md), then on a line of its own the values involved
/// ([`VmFault::note`]); the POU's name stands for the path when it is
/// unknown.
impl std::fmt::Display for VmFault {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "fault: {} in {} ({}) at {}:{}:{}",
            self.kind.text(),
            self.instance.as_deref().unwrap_or(&self.pou),
            self.pou,
            self.file,
            self.line,
            self.col
        )?;
        let note = self.note();
        if !note.is_empty() {
            write!(f, "\n{note}")?;
        }
        Ok(())
    }
}

pub struct Machine {
    pub(crate) image: Arc<Image>,
    pub(crate) mem: Vec<u8>,
}

impl Machine {
    /// A machine with the image loaded: data initialised, constants in place.
    pub fn new(image: Arc<Image>) -> Machine {
        let size = image.memory_size().min(u32::MAX as u64) as usize;
        let mut mem = vec![0u8; size];
        let n = image.init.len().min(image.data_size as usize);
        mem[..n].copy_from_slice(&image.init[..n]);
        let cb = image.const_base() as usize;
        let ce = (cb + image.consts.len()).min(size);
        mem[cb..ce].copy_from_slice(&image.consts[..ce - cb]);
        Machine { image, mem }
    }

    pub fn image(&self) -> &Image {
        &self.image
    }

    /// The image, shared.
    pub fn image_arc(&self) -> &Arc<Image> {
        &self.image
    }

    /// The whole memory: data area, constants, stack.
    pub fn memory(&self) -> &[u8] {
        &self.mem
    }

    /// The whole memory, to write (the runtime's `--set` and stimuli).
    pub fn memory_mut(&mut self) -> &mut [u8] {
        &mut self.mem
    }

    /// Every variable back to its initial value, as [`Machine::new`] left it.
    pub fn reset(&mut self) {
        *self = Machine::new(Arc::clone(&self.image));
    }

    /// Runs the body of a program instance once, at task time `now_ns`,
    /// with at most `max_steps` instructions; returns the instructions used.
    pub fn run_program(
        &mut self,
        inst: &ProgramInst,
        now_ns: i64,
        max_steps: u64,
    ) -> Result<u64, VmFault> {
        let pou = self
            .image
            .pous
            .get(inst.pou as usize)
            .ok_or_else(|| self.fault_at(FaultKind::Watchdog, 0))?;
        let entry = pou.entry;
        self.execute(entry, inst.offset, inst.pou, now_ns, max_steps)
    }

    pub fn read_bytes(&self, off: u32, len: u32) -> Option<&[u8]> {
        self.mem.get(off as usize..off as usize + len as usize)
    }

    pub fn write_bytes(&mut self, off: u32, bytes: &[u8]) -> bool {
        match self.mem.get_mut(off as usize..off as usize + bytes.len()) {
            Some(dst) => {
                dst.copy_from_slice(bytes);
                true
            }
            None => false,
        }
    }

    /// The address stored in a reference slot.
    pub fn deref(&self, off: u32) -> Option<u32> {
        self.read_bytes(off, 4)
            .map(|b| u32::from_le_bytes([b[0], b[1], b[2], b[3]]))
    }

    /// A scalar or string value (enumerations read as their integer).
    pub fn read_value(&self, off: u32, ty: TypeRef) -> Option<Value> {
        if let Some(e) = self.image.scalar_of(ty) {
            return read_scalar(&self.mem, off, e);
        }
        match self.image.model.types.get(ty as usize)? {
            TypeDesc::String { wide, cap } => read_string(&self.mem, off, *wide, *cap),
            _ => None,
        }
    }

    /// Writes a scalar or string value (strings truncated to capacity).
    pub fn write_value(&mut self, off: u32, ty: TypeRef, v: &Value) -> bool {
        if let Some(e) = self.image.scalar_of(ty) {
            return write_scalar(&mut self.mem, off, e, v);
        }
        match self.image.model.types.get(ty as usize).cloned() {
            Some(TypeDesc::String { wide, cap }) => write_string(&mut self.mem, off, wide, cap, v),
            _ => false,
        }
    }

    pub(crate) fn fault_at(&self, kind: FaultKind, pc: u32) -> VmFault {
        match self.image.position(pc) {
            Some((pou, file, line, col)) => VmFault::at(kind, pou, file, line, col),
            None => VmFault::unlocated(kind, "?"),
        }
    }
}
