//! The engine interface: what the runtime needs of a back end that runs
//! programs, so the scheduler, stimulus, `--set`, `--watch`, reports and
//! faults are written once, here, for every back end.
//!
//! An engine holds a loaded program and its state. It gives the runtime:
//! - the program model ([`Engine::image`]): types, POUs with their
//!   variables, globals, configurations, program instances and process
//!   image slots, with the addresses and offsets of *this* engine (the VM's
//!   byte offsets, or the places of the generated C's objects);
//! - its memory, addressed by those `u32` addresses ([`Memory`]): bytes of
//!   one object at a time, and the target of a reference slot (a VM
//!   reference is a 4-byte offset, a C one a pointer: the engine knows);
//! - one run of a program instance's body at a task time with a watchdog
//!   budget ([`Engine::run_program`]), which reports a fault with its
//!   source position;
//! - a reset to the initial state ([`Engine::reset`]).
//!
//! The VM ([`stc_vm::Machine`]) implements it below; the generated C,
//! compiled and loaded as a shared library, implements it in `stc_engine_c`.
//! Values are stored as `stc_ir::model::repr` says
//! read them in every engine (little-endian, two's complement, IEC 60559):
//! the C back end's memory representation is the same (see stc_meta.h).

use std::sync::Arc;

use stc_ir::model::repr::{read_scalar, read_string, write_scalar, write_string};
use stc_ir::model::{Model, ProgramInst, TypeDesc, TypeRef};
use stc_values::Value;
use stc_vm::{Machine, VmFault};

/// Memory addressed as the model's addresses.
pub trait Memory {
    /// The `len` bytes at `addr`, when they all lie in one object of the
    /// memory (`None` otherwise: nothing outside it is ever read).
    fn bytes(&self, addr: u32, len: u32) -> Option<&[u8]>;
    /// The same, to write.
    fn bytes_mut(&mut self, addr: u32, len: u32) -> Option<&mut [u8]>;
    /// The address held by the reference slot at `slot` (a VAR_IN_OUT,
    /// VAR_EXTERNAL or located variable), when it points into the memory.
    fn deref(&self, slot: u32) -> Option<u32>;
}

/// A flat byte array whose references are 4-byte little-endian offsets:
/// the VM's memory.
impl Memory for [u8] {
    fn bytes(&self, addr: u32, len: u32) -> Option<&[u8]> {
        let a = addr as usize;
        self.get(a..a.checked_add(len as usize)?)
    }

    fn bytes_mut(&mut self, addr: u32, len: u32) -> Option<&mut [u8]> {
        let a = addr as usize;
        self.get_mut(a..a.checked_add(len as usize)?)
    }

    fn deref(&self, slot: u32) -> Option<u32> {
        let b = self.bytes(slot, 4)?;
        Some(u32::from_le_bytes([b[0], b[1], b[2], b[3]]))
    }
}

/// A loaded program that runs: see the module documentation.
pub trait Engine: Memory {
    /// The program model, with this engine's addresses.
    fn model(&self) -> &Arc<Model>;

    /// Runs the body of a program instance once at task time `now_ns`
    /// with at most `max_steps` steps of the watchdog; returns the steps
    /// used. What a step is belongs to the engine (a VM instruction; a loop
    /// iteration or call of generated C).
    fn run_program(
        &mut self,
        inst: &ProgramInst,
        now_ns: i64,
        max_steps: u64,
    ) -> Result<u64, VmFault>;

    /// Every variable back to its initial value, as just after loading.
    fn reset(&mut self);

    /// A short name for messages (`vm`, `c`).
    fn name(&self) -> &'static str;
}

impl Memory for Machine {
    fn bytes(&self, addr: u32, len: u32) -> Option<&[u8]> {
        self.memory().bytes(addr, len)
    }

    fn bytes_mut(&mut self, addr: u32, len: u32) -> Option<&mut [u8]> {
        self.memory_mut().bytes_mut(addr, len)
    }

    fn deref(&self, slot: u32) -> Option<u32> {
        self.memory().deref(slot)
    }
}

impl Engine for Machine {
    fn model(&self) -> &Arc<Model> {
        &Machine::image(self).model
    }

    fn run_program(
        &mut self,
        inst: &ProgramInst,
        now_ns: i64,
        max_steps: u64,
    ) -> Result<u64, VmFault> {
        Machine::run_program(self, inst, now_ns, max_steps)
    }

    fn reset(&mut self) {
        Machine::reset(self)
    }

    fn name(&self) -> &'static str {
        "vm"
    }
}

/// The size in bytes of a scalar or string value of type `ty`.
fn value_size(model: &Model, ty: TypeRef) -> Option<u32> {
    if let Some(e) = model.scalar_of(ty) {
        return Some(stc_ir::layout::elem_size(e));
    }
    match model.types.get(ty as usize)? {
        TypeDesc::String { wide, cap } => {
            Some(2u32.checked_add(cap.checked_mul(if *wide { 2 } else { 1 })?)?)
        }
        _ => None,
    }
}

/// Reads a scalar or string value (enumerations read as their integer).
pub fn read_value(mem: &dyn Memory, model: &Model, addr: u32, ty: TypeRef) -> Option<Value> {
    let bytes = mem.bytes(addr, value_size(model, ty)?)?;
    if let Some(e) = model.scalar_of(ty) {
        return read_scalar(bytes, 0, e);
    }
    match model.types.get(ty as usize)? {
        TypeDesc::String { wide, cap } => read_string(bytes, 0, *wide, *cap),
        _ => None,
    }
}

/// Writes a scalar or string value (strings truncated to their capacity;
/// integers keep their low bits: the caller has converted the value).
pub fn write_value(mem: &mut dyn Memory, model: &Model, addr: u32, ty: TypeRef, v: &Value) -> bool {
    let Some(size) = value_size(model, ty) else {
        return false;
    };
    let Some(bytes) = mem.bytes_mut(addr, size) else {
        return false;
    };
    if let Some(e) = model.scalar_of(ty) {
        return write_scalar(bytes, 0, e, v);
    }
    match model.types.get(ty as usize) {
        Some(TypeDesc::String { wide, cap }) => write_string(bytes, 0, *wide, *cap, v),
        _ => false,
    }
}

impl Memory for Vec<u8> {
    fn bytes(&self, addr: u32, len: u32) -> Option<&[u8]> {
        self.as_slice().bytes(addr, len)
    }

    fn bytes_mut(&mut self, addr: u32, len: u32) -> Option<&mut [u8]> {
        self.as_mut_slice().bytes_mut(addr, len)
    }

    fn deref(&self, slot: u32) -> Option<u32> {
        self.as_slice().deref(slot)
    }
}
