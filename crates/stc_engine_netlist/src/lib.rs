//! The netlist as an engine (`stc run --backend netlist`): the XML document
//! that `stc build --emit netlist` writes is read back (the document itself
//! is what runs, not an in-memory shortcut) and simulated one cycle per run
//! of the program instance, behind the runtime's engine interface.
//!
//! The program model and the memory are `stc_ir::model`'s: the model's
//! canonical data area holds every variable the runtime reads and writes
//! (`--set`, stimuli, reports, connections), at the model's addresses. Each circuit input and register
//! whose name is a run-time path is mapped to its place in that memory:
//! before a cycle the circuit takes their values from memory (what the
//! runtime wrote), after it the registers' new values go back. Cells no
//! path names (the compiler's hidden variables, such as an edge memory)
//! live in the simulator only. No bytecode runs.

use std::sync::Arc;

use stc_ir::model::repr::{read_scalar, write_scalar};
use stc_ir::model::{Model, ProgramInst};
use stc_netlist::{Simulator, StepError};
use stc_runtime::engine::{Engine, Memory};
use stc_runtime::path::{Scope, View};
use stc_values::ElemType;
use stc_vm::VmFault;

/// Why a program cannot run on the netlist engine.
#[derive(Debug)]
pub enum Error {
    /// The program cannot be a circuit (a diagnostic: exit status 1).
    Refused(Box<stc_netlist::Refusal>),
    /// The program model could not be made (a bug: the pipeline lays the
    /// module out before any back end runs).
    Model(String),
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
    /// The program model, its initial data area, and the memory.
    model: Arc<Model>,
    init: Vec<u8>,
    mem: Vec<u8>,
    /// The document, for `reset`.
    doc: String,
    sim: Simulator,
    /// The program the circuit is of (a configuration's circuit: its name).
    program: String,
    /// A configuration's circuit: its index in the model and the names of
    /// its program instances (each has an enable input).
    config: Option<(u32, Vec<String>)>,
    /// Resolved at the first run (the program instance is known then).
    map: Option<Vec<Mapped>>,
}

impl NetlistEngine {
    /// Translates `program` (by name; the only PROGRAM when `None`) of
    /// `module`, writes the document, reads it back and loads it.
    pub fn build(module: &stc_ir::Module, program: Option<&str>) -> Result<NetlistEngine, Error> {
        NetlistEngine::build_unit(module, None, program)
    }

    /// Translates what `stc run` would run: the configuration `config`, the
    /// program `program`, else the only configuration or the only program
    /// (`stc_netlist::choose`).
    pub fn build_unit(
        module: &stc_ir::Module,
        config: Option<&str>,
        program: Option<&str>,
    ) -> Result<NetlistEngine, Error> {
        let unit = stc_netlist::choose(module, config, program).map_err(Error::Choose)?;
        let circuit = stc_netlist::translate_unit(module, unit).map_err(Error::Refused)?;
        let doc = stc_netlist::xml::write(&circuit);
        let layouts = stc_ir::layout::Layouts::compute(module)
            .map_err(|d| Error::Model(format!("{} layout errors", d.len())))?;
        let data =
            stc_ir::model::build(module, &layouts).map_err(|e| Error::Model(e.to_string()))?;
        let mut engine = NetlistEngine::load(Arc::new(data.model), data.init, doc)?;
        if let stc_netlist::Unit::Config(c) = unit {
            let names = engine
                .model
                .configs
                .get(c)
                .map(|conf| {
                    conf.resources
                        .iter()
                        .flat_map(|r| r.programs.iter().map(|p| p.name.clone()))
                        .collect()
                })
                .unwrap_or_default();
            engine.config = Some((c as u32, names));
        }
        Ok(engine)
    }

    /// The engine of a document over `model` and its initial data area.
    pub fn load(model: Arc<Model>, init: Vec<u8>, doc: String) -> Result<NetlistEngine, Error> {
        let circuit = stc_netlist::xml::read(&doc).map_err(Error::Read)?;
        let program = circuit.name.clone();
        Ok(NetlistEngine {
            model,
            mem: init.clone(),
            init,
            doc,
            sim: Simulator::new(circuit),
            program,
            config: None,
            map: None,
        })
    }

    /// The cells of the circuit that a path names, against the program
    /// instance `inst`.
    fn resolve(&self, inst: &ProgramInst) -> Vec<Mapped> {
        let model = Arc::clone(&self.model);
        let all: Vec<ProgramInst> = match &self.config {
            Some((c, _)) => model
                .configs
                .get(*c as usize)
                .map(|conf| {
                    conf.resources
                        .iter()
                        .flat_map(|r| r.programs.iter().cloned())
                        .collect()
                })
                .unwrap_or_default(),
            None => vec![inst.clone()],
        };
        let scope = Scope {
            model: &model,
            instances: &all,
            config: self.config.as_ref().map(|(c, _)| *c),
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
            if model.scalar_of(t).is_none() {
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
        self.mem.as_slice().bytes(addr, len)
    }
    fn bytes_mut(&mut self, addr: u32, len: u32) -> Option<&mut [u8]> {
        self.mem.as_mut_slice().bytes_mut(addr, len)
    }
    fn deref(&self, slot: u32) -> Option<u32> {
        self.mem.as_slice().deref(slot)
    }
}

impl Engine for NetlistEngine {
    fn model(&self) -> &Arc<Model> {
        &self.model
    }

    fn run_program(
        &mut self,
        inst: &ProgramInst,
        now_ns: i64,
        _max_steps: u64,
    ) -> Result<u64, VmFault> {
        let pou = self
            .model
            .pous
            .get(inst.pou as usize)
            .map(|p| p.name.clone())
            .unwrap_or_default();
        match &self.config {
            // One step runs one instance: its enable alone is TRUE.
            Some((_, names)) => {
                if !names.iter().any(|n| n.eq_ignore_ascii_case(&inst.name)) {
                    return Err(VmFault::unlocated(
                        stc_ir::FaultKind::InvalidCode,
                        &inst.name,
                    ));
                }
                for n in names {
                    let on = n.eq_ignore_ascii_case(&inst.name);
                    self.sim
                        .set(&stc_netlist::enable_name(n), stc_values::Value::Bool(on));
                }
            }
            None => {
                if !pou.eq_ignore_ascii_case(&self.program) {
                    // (The command only builds this engine for one PROGRAM.)
                    return Err(VmFault::unlocated(stc_ir::FaultKind::InvalidCode, &pou));
                }
            }
        }
        if self.map.is_none() {
            self.map = Some(self.resolve(inst));
        }
        let map = self.map.take().unwrap_or_default();
        // What the runtime wrote goes in.
        for m in &map {
            let v = m
                .loc
                .address(self.mem.as_slice())
                .and_then(|a| read_scalar(&self.mem, a, m.elem));
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
                if let Some(a) = m.loc.address(self.mem.as_slice()) {
                    write_scalar(&mut self.mem, a, m.elem, &v);
                }
            }
        }
        self.map = Some(map);
        match result {
            Ok(_) => Ok(1),
            Err(StepError::Fault(f)) => {
                let mut fault = VmFault::at(f.kind, &f.pou, &f.file, f.line, f.col);
                if let Some(r) = f.range {
                    let (v, lo, hi) = *r;
                    fault = fault.out_of_range(v, lo, hi);
                }
                fault.instance = Some(f.instance);
                Err(fault)
            }
            Err(StepError::Unchecked(i)) => Err(VmFault::unlocated(
                stc_ir::FaultKind::InvalidCode,
                &format!("{} (component U{})", self.program, i + 1),
            )),
        }
    }

    fn reset(&mut self) {
        self.mem.clone_from(&self.init);
        if let Ok(c) = stc_netlist::xml::read(&self.doc) {
            self.sim = Simulator::new(c);
        }
    }

    fn name(&self) -> &'static str {
        "netlist"
    }
}
