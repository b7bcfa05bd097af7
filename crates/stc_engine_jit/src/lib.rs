//! A Cranelift JIT of the typed IR as an engine of the runtime
//! (`stc run --backend jit`).
//!
//! [`JitEngine::build`] lays out the program model and its canonical data
//! area (`stc_ir::model::build`), then translates every POU body of the
//! `Module` into one native function with Cranelift ([`codegen`]). From
//! then on the runtime (`stc_runtime`: scheduling, stimulus, `--set`,
//! `--watch`, reports, faults) drives it through [`stc_runtime::Engine`]
//! exactly as it drives the VM.
//!
//! **Memory** is one byte array, as the VM's: the data area exactly as the
//! model lays it out (process-image slots, globals, program instances;
//! references are 4-byte little-endian model addresses), then the constant
//! pool (string constants), then the stack of frames (a function's
//! variables and an FB's VAR_TEMP). So [`Memory`] is the VM's `[u8]`
//! implementation, and a model address is an offset into the array.
//! Temporaries of expressions live on the native stack.
//!
//! **Semantics** are the VM's: integer and real arithmetic, comparisons,
//! plain numeric conversions, bit parts, array indexing with its bounds
//! checks, subrange checks and the watchdog are native code with the
//! VM's exact rules (wrapping integer arithmetic, `wrapping_div`, a
//! conversion from a real rounding half to even and faulting out of
//! range); everything else (strings, time and date arithmetic, other
//! conversions, every standard function) calls back into Rust, which
//! calls `stc_values`, the one definition of every operator, as the VM's
//! generic `std` instruction does.
//!
//! **Faults** stop the body where the VM stops it: the generated code
//! stores the fault kind and the index of its site (POU, file, line and
//! column of the statement) in the [`Ctx`] and returns 1; every caller
//! returns at once.
//!
//! **The watchdog** spends one step per loop iteration (at the back edge)
//! and per call of a POU, as the C engine does (docs/runtime.md).

mod codegen;

use std::sync::Arc;

use stc_ir::model::{Model, ProgramInst};
use stc_ir::FaultKind;
use stc_runtime::{Engine, Memory};
use stc_vm::VmFault;

pub use codegen::Error;

/// The state the generated code shares with the engine, by pointer (its
/// field offsets are used by the generated code: `#[repr(C)]`).
#[repr(C)]
pub(crate) struct Ctx {
    /// Watchdog steps left.
    pub steps: u64,
    /// The task clock (TIME, ns).
    pub now: i64,
    /// The fault raised ([`FaultKind::code`]; 0: none).
    pub fault_kind: u32,
    /// The site of the fault (index into the sites table).
    pub fault_site: u32,
    /// The innermost function block or program instance the fault
    /// happened in: its data address and its POU (`NO_POU` while only
    /// functions have seen the fault).
    pub fault_inst: u32,
    pub fault_inst_pou: u32,
    /// The value outside its range (an index, a subrange) and the range,
    /// as 64-bit patterns; `range_flags` says which are unsigned
    /// (`RANGE_*`), 0: no value.
    pub range: [u64; 3],
    pub range_flags: u32,
}

pub(crate) const CTX_STEPS: i32 = 0;
pub(crate) const CTX_NOW: i32 = 8;
pub(crate) const CTX_KIND: i32 = 16;
pub(crate) const CTX_SITE: i32 = 20;
pub(crate) const CTX_INST: i32 = 24;
pub(crate) const CTX_INST_POU: i32 = 28;
pub(crate) const CTX_RANGE: i32 = 32;
pub(crate) const CTX_RANGE_FLAGS: i32 = 56;
/// `Ctx::range_flags` (`stc_vm::range_flags`).
pub(crate) const RANGE_VALUE_UNSIGNED: i64 = stc_vm::range_flags::VALUE_UNSIGNED as i64;
pub(crate) const RANGE_BOUNDS_UNSIGNED: i64 = stc_vm::range_flags::BOUNDS_UNSIGNED as i64;
pub(crate) const RANGE_KNOWN: i64 = stc_vm::range_flags::KNOWN as i64;
/// `Ctx::fault_inst_pou` before an instance has seen the fault.
pub(crate) const NO_POU: i64 = u32::MAX as i64;

/// The body of a POU: `(ctx, memory base, this, frame) -> status` (0, or 1
/// after a fault recorded in the context).
type Body = unsafe extern "C" fn(*mut Ctx, *mut u8, u64, u64) -> u32;

/// A program compiled to native code: see the module documentation.
pub struct JitEngine {
    model: Arc<Model>,
    mem: Vec<u8>,
    /// The memory as after loading: data area and constants.
    init: Vec<u8>,
    /// Where the stack of frames starts.
    stack_base: u32,
    /// The body of each POU, by `PouId`.
    bodies: Vec<Option<Body>>,
    /// Fault sites: POU, file, line, column.
    sites: Vec<(String, String, u32, u32)>,
    ctx: Box<Ctx>,
    /// Kept last: owns the code and the tables it points to.
    _code: codegen::Code,
}

impl JitEngine {
    /// Compiles a module (without errors) to native code. `Err` with
    /// [`Error::Unsupported`] where Cranelift has no back end for the host
    /// (the caller falls back to the VM).
    pub fn build(m: &stc_ir::Module) -> Result<JitEngine, Error> {
        let out = codegen::compile(m)?;
        let mut model = out.model;
        let _ = &mut model;
        Ok(JitEngine {
            model: Arc::new(model),
            mem: out.memory.clone(),
            init: out.memory,
            stack_base: out.stack_base,
            bodies: out.bodies,
            sites: out.sites,
            ctx: Box::new(Ctx {
                steps: 0,
                now: 0,
                fault_kind: 0,
                fault_site: 0,
                fault_inst: 0,
                fault_inst_pou: NO_POU as u32,
                range: [0; 3],
                range_flags: 0,
            }),
            _code: out.code,
        })
    }

    fn fault(&self) -> VmFault {
        let kind = FaultKind::from_code(self.ctx.fault_kind).unwrap_or(FaultKind::InvalidCode);
        let mut f = match self.sites.get(self.ctx.fault_site as usize) {
            Some((pou, file, line, col)) => VmFault::at(kind, pou, file, *line, *col),
            None => VmFault::unlocated(kind, "?"),
        };
        if i64::from(self.ctx.fault_inst_pou) != NO_POU {
            f.instance_at = Some((self.ctx.fault_inst, self.ctx.fault_inst_pou));
        }
        f.out_of_range_bits(self.ctx.range, self.ctx.range_flags)
    }
}

impl Memory for JitEngine {
    fn bytes(&self, addr: u32, len: u32) -> Option<&[u8]> {
        self.mem.bytes(addr, len)
    }

    fn bytes_mut(&mut self, addr: u32, len: u32) -> Option<&mut [u8]> {
        self.mem.bytes_mut(addr, len)
    }

    fn deref(&self, slot: u32) -> Option<u32> {
        self.mem.deref(slot)
    }
}

impl Engine for JitEngine {
    fn model(&self) -> &Arc<Model> {
        &self.model
    }

    fn run_program(
        &mut self,
        inst: &ProgramInst,
        now_ns: i64,
        max_steps: u64,
    ) -> Result<u64, VmFault> {
        let Some(Some(body)) = self.bodies.get(inst.pou as usize).copied() else {
            return Err(VmFault::unlocated(FaultKind::InvalidCode, &inst.name));
        };
        let this = u64::from(inst.offset);
        let size = self.model.pous[inst.pou as usize].instance_size;
        if u64::from(inst.offset) + u64::from(size) > self.mem.len() as u64 {
            return Err(VmFault::unlocated(FaultKind::InvalidCode, &inst.name));
        }
        self.ctx.steps = max_steps;
        self.ctx.now = now_ns;
        self.ctx.fault_kind = 0;
        self.ctx.fault_site = 0;
        self.ctx.range_flags = 0;
        // SAFETY: `body` was compiled from this module for this memory
        // layout: it reads and writes only the memory array (whose length
        // the code was compiled for: `mem` is never resized), at the
        // instance of its POU (checked above to lie in it), its frame on
        // the stack area (sized for the deepest chain of calls) and the
        // addresses the model and its own code bound references to.
        let status = unsafe {
            body(
                &mut *self.ctx,
                self.mem.as_mut_ptr(),
                this,
                u64::from(self.stack_base),
            )
        };
        let used = max_steps.saturating_sub(self.ctx.steps);
        if status == 0 {
            Ok(used)
        } else {
            Err(self.fault())
        }
    }

    fn reset(&mut self) {
        self.mem.copy_from_slice(&self.init);
    }

    fn name(&self) -> &'static str {
        "jit"
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The generated code addresses the context by these offsets.
    #[test]
    fn the_context_offsets_are_the_struct_fields() {
        use std::mem::offset_of;
        assert_eq!(offset_of!(Ctx, steps) as i32, CTX_STEPS);
        assert_eq!(offset_of!(Ctx, now) as i32, CTX_NOW);
        assert_eq!(offset_of!(Ctx, fault_kind) as i32, CTX_KIND);
        assert_eq!(offset_of!(Ctx, fault_site) as i32, CTX_SITE);
        assert_eq!(offset_of!(Ctx, fault_inst) as i32, CTX_INST);
        assert_eq!(offset_of!(Ctx, fault_inst_pou) as i32, CTX_INST_POU);
        assert_eq!(offset_of!(Ctx, range) as i32, CTX_RANGE);
        assert_eq!(offset_of!(Ctx, range_flags) as i32, CTX_RANGE_FLAGS);
    }
}
