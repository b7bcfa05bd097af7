//! The generated C as an engine of the runtime (`stc run --backend c`).
//!
//! [`CEngine::build`] writes the C back end's output for a module into a
//! fresh temporary directory, compiles it with the system C compiler (`$CC`,
//! else `cc`) into a shared library, and loads it. From then on the runtime
//! (`stc_runtime`: scheduling, stimulus, `--set`, `--watch`, reports,
//! faults) drives it through [`stc_runtime::Engine`] exactly as it drives the
//! VM: nothing of the runtime is written again in C.
//!
//! The program model comes from the library's own descriptor tables
//! (`stc_meta.h`: types with their `offsetof` offsets, POU variables,
//! globals, configurations, program instances, process-image slots; see
//! [`tables`]): the engine reads them into the runtime's model
//! ([`stc_vm::image::Image`]'s tables) with addresses of its own. The C
//! program's objects (globals, program instances, process-image slots, the
//! constants a configuration connects) are not one array, so each object
//! is given a range of a virtual `u32` address space ([`memory`]); a model
//! address is translated to the object's bytes, and a reference slot (a C
//! pointer) back to a model address.
//!
//! Why a shared library and not the simulation harness the C back end also
//! ships: the harness re-implemented the runtime in C, and every runtime
//! change had to be made twice. Loading the compiled program keeps one
//! runtime, and it is what a JIT engine will look like too.
//!
//! Each engine loads its own copy of the library (its own file), so two
//! engines never share the C program's state.

mod compile;
mod memory;
mod tables;

use std::ffi::c_void;
use std::path::Path;
use std::sync::Arc;

use stc_ir::model::{Model, ProgramInst};
use stc_ir::FaultKind;
use stc_runtime::{Engine, Memory};
use stc_vm::VmFault;

pub use compile::Toolchain;
use memory::Regions;

/// Why the C engine could not be set up.
#[derive(Debug)]
pub enum Error {
    /// The C back end does not translate the program (exit 1: a program
    /// the back end cannot express).
    Generate(stc_codegen_c::Error),
    /// No C compiler, or it failed, or the library did not load (exit 2).
    Build(String),
}

impl std::fmt::Display for Error {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Error::Generate(e) => write!(f, "{e}"),
            Error::Build(m) => write!(f, "error: --backend c: {m}"),
        }
    }
}

impl std::error::Error for Error {}

/// The run-time state the generated code shares with its runner
/// (`stc_rt.h`).
struct Globals {
    fault_kind: *mut u32,
    fault_site: *mut u32,
    /// `stc_fault_inst`, `stc_fault_pou`: the innermost instance the
    /// fault happened in.
    fault_inst: *mut *const c_void,
    fault_pou: *mut u32,
    /// `stc_fault_range_*`: the value outside its range and the range.
    range: [*mut u64; 3],
    range_flags: *mut u32,
    clock: *mut i64,
    steps: *mut u64,
    init_all: unsafe extern "C" fn(),
}

/// A program compiled from C and loaded: see the module documentation.
pub struct CEngine {
    model: Arc<Model>,
    regions: Regions,
    /// By the model address of a program instance: its body and data.
    bodies: Vec<(u32, unsafe extern "C" fn(*mut c_void), *mut c_void)>,
    /// `stc_sites`: where each fault site is (POU, file, line, column).
    sites: Vec<(String, String, u32, u32)>,
    globals: Globals,
    /// Kept last: the library stays loaded while the pointers above live.
    _lib: libloading::Library,
}

impl CEngine {
    /// Generates, compiles and loads the C of a module. `locate` turns
    /// spans into positions for the C back end's messages.
    pub fn build(
        m: &stc_ir::Module,
        locate: stc_codegen_c::Locate<'_>,
        tc: &Toolchain,
    ) -> Result<CEngine, Error> {
        let files = stc_codegen_c::generate(m, locate).map_err(Error::Generate)?;
        let dir = compile::TempDir::new()?;
        let lib = tc.shared_library(dir.path(), &files)?;
        let engine = CEngine::load(&lib);
        drop(dir);
        engine
    }

    /// Loads a library built from the C back end's output.
    pub fn load(path: &Path) -> Result<CEngine, Error> {
        // SAFETY: the library is one the C back end generated and the
        // system compiler built; loading it runs no code of ours but the
        // C runtime's constructors (it has none).
        let lib = unsafe { libloading::Library::new(path) }
            .map_err(|e| Error::Build(format!("cannot load {}: {e}", path.display())))?;
        // SAFETY: every symbol is read with the type stc_meta.h and
        // stc_rt.h declare for it, and the library outlives them (`_lib`).
        unsafe {
            let sym = |name: &str| -> Result<*mut c_void, Error> {
                let s: libloading::Symbol<*mut c_void> = lib.get(name.as_bytes()).map_err(|e| {
                    Error::Build(format!("{}: no symbol {name}: {e}", path.display()))
                })?;
                Ok(*s)
            };
            let init: libloading::Symbol<unsafe extern "C" fn()> = lib
                .get(b"stc_init_all")
                .map_err(|e| Error::Build(format!("{}: {e}", path.display())))?;
            let globals = Globals {
                fault_kind: sym("stc_fault_kind")?.cast(),
                fault_site: sym("stc_fault_site")?.cast(),
                fault_inst: sym("stc_fault_inst")?.cast(),
                fault_pou: sym("stc_fault_pou")?.cast(),
                range: [
                    sym("stc_fault_range_value")?.cast(),
                    sym("stc_fault_range_lo")?.cast(),
                    sym("stc_fault_range_hi")?.cast(),
                ],
                range_flags: sym("stc_fault_range_flags")?.cast(),
                clock: sym("stc_clock")?.cast(),
                steps: sym("stc_steps")?.cast(),
                init_all: *init,
            };
            let t = tables::Tables::read(&sym)?;
            let loaded = t.model()?;
            (globals.init_all)();
            Ok(CEngine {
                model: Arc::new(loaded.model),
                regions: loaded.regions,
                bodies: loaded.bodies,
                sites: t.sites(),
                globals,
                _lib: lib,
            })
        }
    }

    fn fault(&self, code: u32, site: u32) -> VmFault {
        let kind = fault_kind(code);
        let mut f = match self.sites.get(site as usize) {
            Some((pou, file, line, col)) => VmFault::at(kind, pou, file, *line, *col),
            None => VmFault::unlocated(kind, "?"),
        };
        // SAFETY: the library's own variables (stc_rt.h), read after the
        // body returned; no other thread runs the library.
        let (inst, pou) = unsafe { (*self.globals.fault_inst, *self.globals.fault_pou) };
        // SAFETY: as above.
        let (range, flags) = unsafe { (self.globals.range.map(|p| *p), *self.globals.range_flags) };
        f = f.out_of_range_bits(range, flags);
        if pou != u32::MAX {
            f.instance_at = self.regions.model_addr(inst as usize).map(|at| (at, pou));
        }
        f
    }
}

/// A fault code of `stc_codes.h` (`STC_FAULT_*`: [`FaultKind::code`]).
fn fault_kind(code: u32) -> FaultKind {
    FaultKind::from_code(code).unwrap_or(FaultKind::InvalidCode)
}

impl Memory for CEngine {
    fn bytes(&self, addr: u32, len: u32) -> Option<&[u8]> {
        self.regions.bytes(addr, len)
    }

    fn bytes_mut(&mut self, addr: u32, len: u32) -> Option<&mut [u8]> {
        self.regions.bytes_mut(addr, len)
    }

    fn deref(&self, slot: u32) -> Option<u32> {
        self.regions.deref(slot)
    }
}

impl Engine for CEngine {
    fn model(&self) -> &Arc<Model> {
        &self.model
    }

    fn run_program(
        &mut self,
        inst: &ProgramInst,
        now_ns: i64,
        max_steps: u64,
    ) -> Result<u64, VmFault> {
        let Some(&(_, body, data)) = self.bodies.iter().find(|b| b.0 == inst.offset) else {
            return Err(VmFault::unlocated(FaultKind::InvalidCode, &inst.name));
        };
        // SAFETY: the pointers are the library's own variables (stc_rt.h),
        // the body and instance are an entry of its stc_programs or
        // stc_configs tables, and no other thread runs the library.
        unsafe {
            *self.globals.fault_kind = 0;
            *self.globals.clock = now_ns;
            *self.globals.steps = max_steps;
            body(data);
            let left = *self.globals.steps;
            let used = max_steps.saturating_sub(left);
            match *self.globals.fault_kind {
                0 => Ok(used),
                code => Err(self.fault(code, *self.globals.fault_site)),
            }
        }
    }

    fn reset(&mut self) {
        // SAFETY: stc_init_all sets every object of the program to its
        // initial value; no reference into the memory is alive (&mut self).
        unsafe { (self.globals.init_all)() }
    }

    fn name(&self) -> &'static str {
        "c"
    }
}
