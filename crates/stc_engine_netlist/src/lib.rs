//! The netlist as an engine (`stc run --backend netlist`): the XML document
//! that `stc build --emit netlist` writes is read back (the document itself
//! is what runs, not an in-memory shortcut) and simulated one cycle per run
//! of the program instance, behind the runtime's engine interface.
//!
//! The program model and the memory are the VM's: the module is compiled
//! to bytecode only for its tables and its initial data area, which hold
//! every variable the runtime reads and writes (`--set`, stimuli, reports,
//! connections), at the VM's addresses. Each circuit input and register
//! whose name is a run-time path is mapped to its place in that memory:
//! before a cycle the circuit takes their values from memory (what the
//! runtime wrote), after it the registers' new values go back. Cells no
//! path names (the compiler's hidden variables, such as an edge memory)
//! live in the simulator only. No bytecode runs.

use std::sync::Arc;

use stc_netlist::{Simulator, StepError};
use stc_runtime::engine::{Engine, Memory};
use stc_runtime::path::{Scope, View};
use stc_values::ElemType;
use stc_vm::image::{Image, ProgramInst};
use stc_vm::machine::{read_scalar, write_scalar};
use stc_vm::{Machine, VmFault};

/// Why a program cannot run on the netlist engine.
#[derive(Debug)]
pub enum Error {
    /// The program cannot be a circuit (a diagnostic: exit status 1).
    Refused(Box<stc_netlist::Refusal>),
    /// The bytecode compiler's tables could not be made.
    Model(stc_vm::CompileError),
    /// The document does not read back (a bug in stc).
    Read(stc_netlist::xml::ReadError),
    /// No PROGRAM to run, or several.
    Choose(String),
}

impl std::fmt::Display for Error {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Error::Refused(r) => write!(f, "{}", r.message),
            Error::Model(e) => write!(f, "{e}"),
            Error::Read(e) => write!(f, "the netlist does not read back: {e} (a bug in stc)"),
            Error::Choose(e) => write!(f, "{e}"),
        }
    }
}

/// A variable of the circuit with a place in memory.
struct Mapped {
    name: String,
    loc: stc_runtime::path::Loc,
    elem: ElemType,
}

pub struct NetlistEngine {
    /// The model and the memory (never run).
    vm: Machine,
    /// The document, for `reset`.
    doc: String,
    sim: Simulator,
    /// The program the circuit is of.
    program: String,
    /// Resolved at the first run (the program instance is known then).
    map: Option<Vec<Mapped>>,
}

impl NetlistEngine {
    /// Translates `program` (by name; the only PROGRAM when `None`) of
    /// `module`, writes the document, reads it back and loads it.
    pub fn build(module: &stc_ir::Module, program: Option<&str>) -> Result<NetlistEngine, Error> {
        let p = stc_netlist::choose_program(module, program).map_err(Error::Choose)?;
        let circuit = stc_netlist::translate(module, p).map_err(Error::Refused)?;
        let doc = stc_netlist::xml::write(&circuit);
        let image = stc_vm::compile(module).map_err(Error::Model)?;
        NetlistEngine::load(Arc::new(image), doc)
    }

    /// The engine of a document over the model `image`.
    pub fn load(image: Arc<Image>, doc: String) -> Result<NetlistEngine, Error> {
        let circuit = stc_netlist::xml::read(&doc).map_err(Error::Read)?;
        let program = circuit.name.clone();
        Ok(NetlistEngine {
            vm: Machine::new(image),
            doc,
            sim: Simulator::new(circuit),
            program,
            map: None,
        })
    }

    /// The cells of the circuit that a path names, against the program
    /// instance `inst`.
    fn resolve(&self, inst: &ProgramInst) -> Vec<Mapped> {
        let image = self.vm.image_arc().clone();
        let instances = std::slice::from_ref(inst);
        let scope = Scope {
            image: &image,
            instances,
            config: None,
        };
        let mut out = Vec::new();
        for name in self.sim.names() {
            let Some(elem) = self.sim.type_of(name) else {
                continue;
            };
            let Ok(place) = scope.resolve(name) else {
                continue;
            };
            let View::Type(t) = place.view else { continue };
            // (An elementary value, an enumeration or a subrange.)
            if image.scalar_of(t).is_none() {
                continue;
            }
            out.push(Mapped {
                name: name.to_string(),
                loc: place.loc,
                elem,
            });
        }
        out
    }
}

impl Memory for NetlistEngine {
    fn bytes(&self, addr: u32, len: u32) -> Option<&[u8]> {
        self.vm.memory().bytes(addr, len)
    }
    fn bytes_mut(&mut self, addr: u32, len: u32) -> Option<&mut [u8]> {
        self.vm.memory_mut().bytes_mut(addr, len)
    }
    fn deref(&self, slot: u32) -> Option<u32> {
        self.vm.memory().deref(slot)
    }
}

impl Engine for NetlistEngine {
    fn image(&self) -> &Arc<Image> {
        self.vm.image_arc()
    }

    fn run_program(
        &mut self,
        inst: &ProgramInst,
        now_ns: i64,
        _max_steps: u64,
    ) -> Result<u64, VmFault> {
        let pou = self
            .vm
            .image_arc()
            .pous
            .get(inst.pou as usize)
            .map(|p| p.name.clone())
            .unwrap_or_default();
        if !pou.eq_ignore_ascii_case(&self.program) {
            // (The command only builds this engine for one PROGRAM.)
            return Err(VmFault::unlocated(stc_ir::FaultKind::InvalidCode, &pou));
        }
        if self.map.is_none() {
            self.map = Some(self.resolve(inst));
        }
        let map = self.map.take().unwrap_or_default();
        // What the runtime wrote goes in.
        for m in &map {
            let v = m
                .loc
                .address(self.vm.memory())
                .and_then(|a| read_scalar(self.vm.memory(), a, m.elem));
            if let Some(v) = v {
                self.sim.set(&m.name, v);
            }
        }
        let result = self.sim.step(&[], i128::from(now_ns));
        if result.is_ok() {
            for m in &map {
                let Some(v) = self.sim.get(&m.name).cloned() else {
                    continue;
                };
                if let Some(a) = m.loc.address(self.vm.memory()) {
                    write_scalar(self.vm.memory_mut(), a, m.elem, &v);
                }
            }
        }
        self.map = Some(map);
        match result {
            Ok(_) => Ok(1),
            Err(StepError::Fault(f)) => Err(VmFault {
                kind: f.kind,
                pou: f.pou,
                file: f.file,
                line: f.line,
                col: f.col,
            }),
            Err(StepError::Unchecked(i)) => Err(VmFault::unlocated(
                stc_ir::FaultKind::InvalidCode,
                &format!("{} (component U{})", self.program, i + 1),
            )),
        }
    }

    fn reset(&mut self) {
        self.vm.reset();
        if let Ok(c) = stc_netlist::xml::read(&self.doc) {
            self.sim = Simulator::new(c);
        }
    }

    fn name(&self) -> &'static str {
        "netlist"
    }
}
