//! The translation of one PROGRAM of the IR into a circuit.
//!
//! Every variable of the program (and of every function block instance in
//! it, and every global it reaches) is split into *cells*, one per
//! elementary leaf (array elements, struct members and FB variables are
//! separate cells, named by their run-time path: `Main.tmr.ET`,
//! `Main.a[2]`). A cell that keeps its value across cycles is a register;
//! the program's VAR_INPUT and `%I` cells are input modules; VAR_TEMP and
//! function frames are temporaries that start from their initial value at
//! each call.
//!
//! The body is translated by symbolic execution into static single
//! assignment form: the current value of each cell is a net, and each
//! assignment gives the cell a new net (so a variable may be assigned any
//! number of times, on any path). The two branches of an IF (a CASE is a
//! chain of them) are translated from the same values, and where they join
//! every cell either branch changed becomes a two-way selector on the
//! condition between the branches' values. RETURN, EXIT and CONTINUE
//! are *jumps*: each records its condition and the values of the cells
//! changed since the start of its POU, loop or iteration, and where the
//! jump lands those values are selected back for the paths that jumped (so
//! what the rest of the body computes on a path that left is never
//! seen). `alive`, the exact condition that execution reaches the
//! statement (the branch conditions less the paths that jumped or
//! faulted), enables
//! the fault modules and decides which code is dead. Loops are unrolled for
//! as long as `alive` at the start of an iteration is not the constant
//! FALSE, which the FOR of the IR (with its folded constant bounds)
//! decides; a loop whose end depends on run-time values is refused. Functions and function block bodies (user FBs and the
//! standard ones, which are ST in the prelude) are inlined at each call,
//! with the FB's variables being the cells of its instance.
//!
//! Run-time faults: every component that may fault has a fault output
//! (F1); an `IC_FAULT` module per fault site reads it with the `alive` of
//! its statement, so the circuit says exactly when and where the program
//! would fault (the first fault module that fires, in order, is the fault
//! the program raises first), and a faulting component gives a defined
//! value (docs/netlist.md).

use rustc_hash::FxHashMap;
use stc_diagnostics::{Code, Diagnostic, SourceMap, Span};
use stc_ir::{
    Expr, ExprKind, FaultKind, Module, Output, Place, Pou, Proj, Root, Stmt, StmtKind, Storage,
};
use stc_sema::{InitValue, PouId, Section, TypeId, TypeKind, VarId};
use stc_syntax::literal::{AddrArea, DirectAddress};
use stc_values::{BinOp, ElemType, Value};

use crate::build::Builder;
use crate::circuit::{Circuit, Kind, NetId};

/// Limits of the translation (docs/netlist.md).
pub mod limits {
    /// Iterations of one loop that are unrolled before the loop is refused
    /// as one whose number of iterations is not known.
    pub const LOOP_ITERATIONS: usize = 4096;
    /// Elements of an array that one run-time index may select among.
    pub const INDEXED_ELEMENTS: usize = 1024;
    /// Function block instances among which one call chosen at run time
    /// (`fbs[i](...)`) is inlined.
    pub const INDEXED_INSTANCES: usize = 64;
    /// Components of a whole circuit.
    pub const COMPONENTS: usize = 1_000_000;
}

/// Why a program cannot become a circuit: a diagnostic whose position is
/// given as the IR has it (a POU's file, a statement's line and column).
#[derive(Clone, Debug)]
pub struct Refusal {
    pub code: Code,
    pub message: String,
    /// Where the POU is (its file), and the statement's line and column
    /// (1-based; 0 for the POU itself).
    pub pou_span: Span,
    pub line: u32,
    pub col: u32,
}

impl Refusal {
    /// The diagnostic, located in `sources`.
    pub fn to_diagnostic(&self, sources: &SourceMap) -> Diagnostic {
        let span = self.span(sources).unwrap_or(self.pou_span);
        Diagnostic::new(self.code, span, self.message.clone())
            .with_label("a circuit cannot express this")
            .with_help(
                "the netlist back end translates what a circuit can compute in one cycle (docs/netlist.md)",
            )
    }

    fn span(&self, sources: &SourceMap) -> Option<Span> {
        if self.line == 0 {
            return None;
        }
        let fid = sources.file_of(self.pou_span.lo)?;
        let file = sources.file(fid);
        let start = *file.line_starts().get(self.line as usize - 1)?;
        let text = file.line_text(self.line);
        let skip: usize = text
            .chars()
            .take(self.col.saturating_sub(1) as usize)
            .map(char::len_utf8)
            .sum();
        let lo = file.span().lo + start + skip as u32;
        Some(Span::new(lo, lo + 1))
    }
}

type R<T> = Result<T, Box<Refusal>>;

/// The value of an index expression and its position (line, column).
type IndexVal = (NetId, Option<(u32, u32)>);

/// Translates the PROGRAM `program` of `m`.
pub fn translate(m: &Module, program: PouId) -> Result<Circuit, Box<Refusal>> {
    let pou = m.pou(program);
    let name = m.spelled(pou.name, pou.name_span).to_string();
    let mut t = Tr::new(m, name.clone());
    t.program(program, &name, None)?;
    t.commit();
    Ok(t.b.finish())
}

/// The name of the enable input of a program instance of a configuration
/// (`Fast$EN`): TRUE in the step that runs that instance. (A `$` name is
/// no run-time path, as a hidden variable's.)
pub fn enable_name(instance: &str) -> String {
    format!("{instance}$EN")
}

/// Translates the configuration `config` (an index into `m.configs`): every
/// program instance of every resource, in declaration order, each under its
/// enable input ([`enable_name`]); the configuration's globals (its
/// located ones are its I/O modules) and the instances' connections
/// (docs/netlist.md, "Configurations").
pub fn translate_config(m: &Module, config: usize) -> Result<Circuit, Box<Refusal>> {
    let Some(conf) = m.configs.get(config) else {
        return Err(Box::new(Refusal {
            code: Code::E1105,
            message: format!("no configuration number {config}"),
            pou_span: Span::new(0, 0),
            line: 0,
            col: 0,
        }));
    };
    let name = m.spelled(conf.name, conf.span).to_string();
    let mut t = Tr::new(m, name);
    for g in &conf.globals {
        t.global(*g);
    }
    for (r, res) in conf.resources.iter().enumerate() {
        for g in &res.globals {
            t.global(*g);
        }
        for inst in &res.programs {
            let iname = m.spelled(inst.name, inst.name_span).to_string();
            let en = t.b.add(
                Kind::Input {
                    name: enable_name(&iname),
                    init: Value::Bool(false),
                    aliases: Vec::new(),
                },
                &[],
                Some(ElemType::Bool),
            );
            let run = Run {
                enable: en,
                ctx: (config, r),
                inputs: &inst.inputs,
                outputs: &inst.outputs,
            };
            t.program(inst.pou, &iname, Some(run))?;
        }
    }
    t.commit();
    Ok(t.b.finish())
}

/// How a program instance of a configuration runs: under its enable, with
/// the configuration's globals and its connections.
struct Run<'a> {
    enable: NetId,
    /// (configuration, resource), to bind its externals.
    ctx: (usize, usize),
    inputs: &'a [(VarId, stc_sema::DataRef)],
    outputs: &'a [(VarId, stc_sema::DataRef)],
}

/// A value: a net, or the values of an aggregate's leaves.
#[derive(Clone, Debug)]
enum Val {
    S(NetId),
    A(Vec<Val>),
}

#[derive(Clone, Copy, PartialEq, Eq, Debug)]
struct SlotId(u32);

#[derive(Clone, Debug)]
enum Slot {
    Leaf(usize),
    /// A STRING or WSTRING leaf: refused when used.
    Text,
    /// (Shared, so reading a slot does not copy its children.)
    Agg(std::rc::Rc<[SlotId]>),
    /// A variable an instance does not hold (a frame variable).
    Absent,
    /// A reference (`REF_TO`, VAR_IN_OUT, the base of a pointer): refused
    /// when used.
    Address,
}

#[derive(Clone, Copy, PartialEq, Eq, Debug)]
enum CellKind {
    /// Keeps its value across cycles: a register (component index).
    Reg(usize),
    /// An input module.
    Input,
    /// A frame variable.
    Temp,
}

struct Cell {
    kind: CellKind,
    /// Its input module or register (component index).
    comp: Option<usize>,
    /// Also shown by an output module.
    output: bool,
}

/// Where a place is.
#[derive(Clone, Debug)]
enum Loc {
    Fixed(SlotId),
    /// One of `elems`, chosen by the zero-based LINT net `idx`.
    Dyn {
        idx: NetId,
        elems: Vec<SlotId>,
    },
    /// A part of the bit string at `word`: `bits` bits from `pos · bits`,
    /// of type `ty`.
    Part {
        word: Box<Loc>,
        bits: u32,
        pos: u32,
        ty: ElemType,
    },
}

#[derive(Clone, Debug)]
enum Bind {
    Slot(SlotId),
    Loc(Loc),
    None,
}

/// A jump (RETURN, EXIT, CONTINUE): the paths that took it, and where the
/// journal was then (the values of the cells there are found from it when
/// the jump lands).
struct Jump {
    cond: NetId,
    pos: usize,
}

struct LoopCtx {
    /// The journal position at the loop's start and at its iteration's.
    start: usize,
    iter_start: usize,
    breaks: Vec<Jump>,
    continues: Vec<Jump>,
}

struct Frame {
    pou: PouId,
    binds: Vec<Bind>,
    /// The journal position at the call's start, and the RETURNs.
    start: usize,
    ret: Vec<Jump>,
    loops: Vec<LoopCtx>,
    instance: String,
}

#[derive(Clone, Copy, PartialEq, Eq, Hash, Debug)]
enum Kind2 {
    Input,
    Reg,
    Temp,
}

struct Tr<'m> {
    m: &'m Module,
    b: Builder,
    cells: Vec<Cell>,
    /// The current value of each cell.
    env: Vec<NetId>,
    slots: Vec<Slot>,
    alive: NetId,
    /// Every change of a cell's value: the cell and its value before.
    journal: Vec<(usize, NetId)>,
    /// Per cell, the last mark it got (sets of cells without hashing).
    mark: Vec<u32>,
    generation: u32,
    fals: NetId,
    globals: FxHashMap<stc_sema::GlobalId, SlotId>,
    directs: FxHashMap<String, SlotId>,
    privates: FxHashMap<(u32, u32), SlotId>,
    /// The path of each function block instance, by its slot.
    inst_names: FxHashMap<u32, String>,
    /// The statement being translated (line, column).
    at: (u32, u32),
    depth: usize,
    /// The configuration and resource of the program instance being
    /// translated (`None`: a PROGRAM on its own).
    ctx: Option<(usize, usize)>,
}

impl<'m> Tr<'m> {
    fn new(m: &'m Module, name: String) -> Tr<'m> {
        let mut b = Builder::new(name);
        let tru = b.bool(true);
        let fals = b.bool(false);
        Tr {
            m,
            b,
            cells: Vec::new(),
            env: Vec::new(),
            slots: Vec::new(),
            alive: tru,
            journal: Vec::new(),
            mark: Vec::new(),
            generation: 0,
            fals,
            globals: FxHashMap::default(),
            directs: FxHashMap::default(),
            privates: FxHashMap::default(),
            inst_names: FxHashMap::default(),
            at: (0, 0),
            depth: 0,
            ctx: None,
        }
    }

    fn refuse(&self, fr: &Frame, code: Code, message: impl Into<String>) -> Box<Refusal> {
        let pou = self.m.pou(fr.pou);
        Box::new(Refusal {
            code,
            message: message.into(),
            pou_span: pou.span,
            line: self.at.0,
            col: self.at.1,
        })
    }

    fn slot(&mut self, s: Slot) -> SlotId {
        self.slots.push(s);
        SlotId(self.slots.len() as u32 - 1)
    }

    fn scalar(&self, t: TypeId) -> Option<ElemType> {
        self.m.types.scalar(t)
    }

    // ---- storage ----------------------------------------------------------

    /// The cells of a variable of type `t` named `name`, with its initial
    /// value.
    fn build(&mut self, t: TypeId, name: &str, init: Option<&InitValue>, kind: Kind2) -> SlotId {
        let m = self.m;
        match m.types.kind(t) {
            // (A reference has no cells; using one is refused.)
            TypeKind::Ref(_) | TypeKind::Ptr(_) => self.slot(Slot::Address),
            TypeKind::Elem(_)
            | TypeKind::Subrange { .. }
            | TypeKind::Enum { .. }
            | TypeKind::String { .. } => {
                let Some(e) = self.scalar(t) else {
                    return self.slot(Slot::Absent);
                };
                if matches!(e, ElemType::String | ElemType::Wstring) {
                    return self.slot(Slot::Text);
                }
                let v = match init {
                    Some(InitValue::Scalar(v)) => v.clone(),
                    _ => match m.types.kind(t) {
                        TypeKind::Subrange { lo, .. } => Value::Int(*lo),
                        TypeKind::Enum { values, .. } => values
                            .first()
                            .map(|v| Value::Int(v.value))
                            .unwrap_or(Value::Int(0)),
                        _ => stc_values::default_value(e),
                    },
                };
                let cell = self.cells.len();
                let (ck, net) = match kind {
                    Kind2::Input => {
                        let n = self.b.add(
                            Kind::Input {
                                name: name.to_string(),
                                init: v,
                                aliases: Vec::new(),
                            },
                            &[],
                            Some(e),
                        );
                        (CellKind::Input, n)
                    }
                    Kind2::Reg => {
                        let n = self.b.add(
                            Kind::Register {
                                name: name.to_string(),
                                init: v,
                                aliases: Vec::new(),
                            },
                            &[],
                            Some(e),
                        );
                        (CellKind::Reg(self.b.components() - 1), n)
                    }
                    Kind2::Temp => (CellKind::Temp, self.b.konst(e, v)),
                };
                let comp = (kind != Kind2::Temp).then(|| self.b.components() - 1);
                self.cells.push(Cell {
                    kind: ck,
                    comp,
                    output: false,
                });
                self.env.push(net);
                self.slot(Slot::Leaf(cell))
            }
            TypeKind::Array { dims, elem } => {
                let count: i128 = dims.iter().map(|(lo, hi)| hi - lo + 1).product();
                let list: &[Option<InitValue>] = match init {
                    Some(InitValue::Array(l)) => l,
                    _ => &[],
                };
                let (dims, elem) = (dims.clone(), *elem);
                let mut kids = Vec::with_capacity(count.max(0) as usize);
                for i in 0..count.max(0) {
                    // Row-major: the last index varies fastest.
                    let mut rest = i;
                    let mut idx = Vec::with_capacity(dims.len());
                    for (lo, hi) in dims.iter().rev() {
                        let n = hi - lo + 1;
                        idx.push(lo + rest % n);
                        rest /= n;
                    }
                    idx.reverse();
                    // (A frame variable needs no name.)
                    let ename = if kind == Kind2::Temp {
                        String::new()
                    } else {
                        let text: Vec<String> = idx.iter().map(|i| i.to_string()).collect();
                        format!("{name}[{}]", text.join(","))
                    };
                    let v = list.get(i as usize).and_then(|v| v.as_ref());
                    kids.push(self.build(elem, &ename, v, kind));
                }
                self.slot(Slot::Agg(kids.into()))
            }
            TypeKind::Struct { fields } => {
                let mut kids = Vec::with_capacity(fields.len());
                for f in fields.clone() {
                    let given = match init {
                        Some(InitValue::Struct(l)) => {
                            l.iter().find(|(n, _)| *n == f.name).map(|(_, v)| v.clone())
                        }
                        _ => None,
                    };
                    let v = given.or(f.init.clone());
                    let fname = if kind == Kind2::Temp {
                        String::new()
                    } else {
                        format!("{name}.{}", m.spelled(f.name, f.span))
                    };
                    kids.push(self.build(f.ty, &fname, v.as_ref(), kind));
                }
                self.slot(Slot::Agg(kids.into()))
            }
            TypeKind::Fb(p) | TypeKind::Program(p) => {
                let overrides: Vec<(stc_syntax::Symbol, InitValue)> = match init {
                    Some(InitValue::Struct(l)) => l.clone(),
                    _ => Vec::new(),
                };
                self.instance(*p, name, &overrides, kind)
            }
            TypeKind::Error | TypeKind::Void => self.slot(Slot::Absent),
        }
    }

    /// The cells of an instance of a function block: its instance
    /// variables, by VarId (frame variables and references are absent).
    fn instance(
        &mut self,
        p: PouId,
        name: &str,
        overrides: &[(stc_syntax::Symbol, InitValue)],
        kind: Kind2,
    ) -> SlotId {
        let pou = self.m.pou(p);
        let mut kids = Vec::with_capacity(pou.vars.len());
        for v in &pou.vars {
            if v.storage != Storage::Instance {
                kids.push(self.slot(Slot::Absent));
                continue;
            }
            let init = overrides
                .iter()
                .find(|(n, _)| *n == v.name)
                .map(|(_, v)| v.clone())
                .or_else(|| v.init.clone());
            let vname = var_name(self.m, pou, v);
            kids.push(self.build(v.ty, &format!("{name}.{vname}"), init.as_ref(), kind));
        }
        let s = self.slot(Slot::Agg(kids.into()));
        self.inst_names.insert(s.0, name.to_string());
        s
    }

    fn child(&self, s: SlotId, i: usize) -> Option<SlotId> {
        match &self.slots[s.0 as usize] {
            Slot::Agg(k) => k.get(i).copied(),
            _ => None,
        }
    }

    fn leaves(&self, s: SlotId, out: &mut Vec<usize>) {
        match &self.slots[s.0 as usize] {
            Slot::Leaf(c) => out.push(*c),
            Slot::Agg(k) => {
                for k in k.iter() {
                    self.leaves(*k, out);
                }
            }
            Slot::Text | Slot::Absent | Slot::Address => {}
        }
    }

    /// Gives the cell of `s` (an elementary variable) another name.
    fn alias(&mut self, s: SlotId, alias: String) {
        let Slot::Leaf(c) = self.slots[s.0 as usize] else {
            return;
        };
        let Some(comp) = self.cells[c].comp else {
            return;
        };
        if let Kind::Input { aliases, .. } | Kind::Register { aliases, .. } =
            &mut self.b.c.components[comp].kind
        {
            if !aliases.contains(&alias) {
                aliases.push(alias);
            }
        }
    }

    fn global(&mut self, gi: stc_sema::GlobalId) -> SlotId {
        if let Some(s) = self.globals.get(&gi) {
            return *s;
        }
        let g = &self.m.globals[gi];
        let s = match g.location.as_ref().filter(|a| !a.is_incomplete()) {
            Some(a) => {
                let s = self.direct(a, g.ty, g.init.as_ref());
                let name = self.m.spelled(g.name, g.span).to_string();
                self.alias(s, name);
                s
            }
            None => {
                let name = self.m.spelled(g.name, g.span).to_string();
                self.build(g.ty, &name, g.init.as_ref(), Kind2::Reg)
            }
        };
        self.globals.insert(gi, s);
        s
    }

    /// The process-image slot of a direct address: an input module for
    /// `%I`, a register (also shown by an output module for `%Q`) else.
    fn direct(&mut self, a: &DirectAddress, ty: TypeId, init: Option<&InitValue>) -> SlotId {
        let key = a.to_string();
        if let Some(s) = self.directs.get(&key) {
            return *s;
        }
        let init = init.or_else(|| {
            self.m
                .located_inits()
                .into_iter()
                .find(|(b, _, _)| b == a)
                .and_then(|(_, _, i)| i)
        });
        let init = init.cloned();
        let kind = if a.area == AddrArea::Input {
            Kind2::Input
        } else {
            Kind2::Reg
        };
        let s = self.build(ty, &key, init.as_ref(), kind);
        if a.area == AddrArea::Output {
            let mut cells = Vec::new();
            self.leaves(s, &mut cells);
            for c in cells {
                self.cells[c].output = true;
            }
        }
        self.directs.insert(key, s);
        s
    }

    /// How a POU's variable is reached when it runs as `inst`.
    fn bind_var(&mut self, p: PouId, v: VarId, inst: Option<SlotId>, frame_name: &str) -> Bind {
        let m = self.m;
        let pou = m.pou(p);
        let var = pou.var(v);
        if let Some(a) = var.location.as_ref().filter(|a| !a.is_incomplete()) {
            let s = self.direct(a, var.ty, var.init.as_ref());
            if inst.is_some() {
                // The variable is also known by its path in the instance.
                let alias = format!("{frame_name}.{}", var_name(m, pou, var));
                self.alias(s, alias);
            }
            return Bind::Slot(s);
        }
        match var.storage {
            Storage::Instance => match inst.and_then(|i| self.child(i, v.0 as usize)) {
                Some(s) => Bind::Slot(s),
                None => Bind::None,
            },
            Storage::Frame => Bind::Slot(self.build(var.ty, "", var.init.as_ref(), Kind2::Temp)),
            Storage::Ref if var.section == Section::External => {
                match m.bind_global(var.name, var.ty, self.ctx) {
                    Some(g) => Bind::Slot(self.global(g)),
                    None => {
                        let key = (p.0, v.0);
                        if let Some(s) = self.privates.get(&key) {
                            return Bind::Slot(*s);
                        }
                        let name = format!(
                            "{}.{}",
                            m.spelled(pou.name, pou.name_span),
                            var_name(m, pou, var)
                        );
                        let s = self.build(var.ty, &name, None, Kind2::Reg);
                        self.privates.insert(key, s);
                        Bind::Slot(s)
                    }
                }
            }
            Storage::Ref => Bind::None,
        }
    }

    // ---- the program ------------------------------------------------------

    fn program(&mut self, p: PouId, name: &str, run: Option<Run>) -> R<()> {
        let m = self.m;
        let pou = m.pou(p);
        self.ctx = run.as_ref().map(|r| r.ctx);
        let mut fr = Frame {
            pou: p,
            binds: Vec::new(),
            start: 0,
            ret: Vec::new(),
            loops: Vec::new(),
            instance: name.to_string(),
        };
        if pou.kind != stc_syntax::ast::PouKind::Program {
            return Err(self.refuse(&fr, Code::E1105, "only a PROGRAM can be a circuit"));
        }
        // The program's own variables: inputs are input modules, the rest
        // registers (outputs also shown by output modules).
        let mut kids = Vec::with_capacity(pou.vars.len());
        let mut outputs = Vec::new();
        for v in &pou.vars {
            if v.storage != Storage::Instance {
                kids.push(self.slot(Slot::Absent));
                continue;
            }
            let i = VarId(kids.len() as u32);
            let connected = run
                .as_ref()
                .is_some_and(|r| r.inputs.iter().any(|(w, _)| *w == i));
            let kind = if v.section == Section::Input && !connected {
                Kind2::Input
            } else {
                Kind2::Reg
            };
            let vname = format!("{name}.{}", var_name(m, pou, v));
            let s = self.build(v.ty, &vname, v.init.as_ref(), kind);
            if v.section == Section::Output && v.hidden.is_none() {
                outputs.push((s, v));
            }
            kids.push(s);
        }
        let inst = self.slot(Slot::Agg(kids.into()));
        for (s, v) in outputs {
            if self.has_text(s) {
                self.at = (0, 0);
                let vn = m.spelled(v.name, v.span);
                let mut r = self.refuse(
                    &fr,
                    Code::E1102,
                    format!("the output `{vn}` is a STRING: a circuit has no strings"),
                );
                r.pou_span = v.span;
                return Err(r);
            }
            let mut cells = Vec::new();
            self.leaves(s, &mut cells);
            for c in cells {
                self.cells[c].output = true;
            }
        }
        for (i, var) in pou.vars.iter().enumerate() {
            if var.storage == Storage::Ref
                && var.section == Section::InOut
                && var.location.is_none()
            {
                let mut r = self.refuse(
                    &fr,
                    Code::E1105,
                    "a program's VAR_IN_OUT has nothing to refer to in a circuit",
                );
                r.pou_span = var.span;
                return Err(r);
            }
            let b = self.bind_var(p, VarId(i as u32), Some(inst), name);
            fr.binds.push(b);
        }
        let Some(run) = run else {
            self.block(&mut fr, &pou.body)?;
            let ret = std::mem::take(&mut fr.ret);
            self.land(0, ret);
            return Ok(());
        };
        // An instance of a configuration runs when its enable is TRUE: its
        // connections are copied in, its body runs, its outputs are copied
        // out; otherwise every cell keeps its value.
        let mut body = |t: &mut Self, fr: &mut Frame| -> R<()> {
            let start = t.journal.len();
            for (v, src) in run.inputs {
                let val = t.data_ref(fr, src, m.pou(p).var(*v).ty)?;
                let Some(slot) = t.child(inst, v.0 as usize) else {
                    return Err(t.refuse(fr, Code::E1105, "a connected input without storage"));
                };
                t.write_slot(fr, slot, val, None)?;
            }
            t.block(fr, &pou.body)?;
            let ret = std::mem::take(&mut fr.ret);
            t.land(start, ret);
            for (v, sink) in run.outputs {
                let Some(slot) = t.child(inst, v.0 as usize) else {
                    return Err(t.refuse(fr, Code::E1105, "a connected output without storage"));
                };
                let val = t.read_slot(fr, slot)?;
                let target = match sink {
                    stc_sema::DataRef::Global(g) => t.global(*g),
                    stc_sema::DataRef::Direct(a) => t.direct(a, m.addr_type(a), None),
                    stc_sema::DataRef::Const(_) => continue,
                };
                t.write_slot(fr, target, val, None)?;
            }
            Ok(())
        };
        self.branch(&mut fr, run.enable, &mut body, &mut |_, _| Ok(()))
    }

    /// The value of a configuration's data reference (a connection's
    /// source).
    fn data_ref(&mut self, fr: &Frame, d: &stc_sema::DataRef, ty: TypeId) -> R<Val> {
        match d {
            stc_sema::DataRef::Global(g) => {
                let s = self.global(*g);
                self.read_slot(fr, s)
            }
            stc_sema::DataRef::Direct(a) => {
                let s = self.direct(a, self.m.addr_type(a), None);
                self.read_slot(fr, s)
            }
            stc_sema::DataRef::Const(v) => {
                let t = self.elem(fr, ty)?;
                Ok(Val::S(self.b.konst(t, v.clone())))
            }
        }
    }

    /// Registers take the values at the end of the cycle; output modules
    /// show them.
    fn commit(&mut self) {
        for c in 0..self.cells.len() {
            let v = self.env[c];
            if let CellKind::Reg(comp) = self.cells[c].kind {
                self.b.c.components[comp].inputs = crate::circuit::Pins::from_slice(&[v]);
            }
        }
        let mut shown = Vec::new();
        for c in 0..self.cells.len() {
            if self.cells[c].output {
                let comp = match self.cells[c].kind {
                    CellKind::Reg(comp) => comp,
                    _ => continue,
                };
                if let Kind::Register { name, .. } = &self.b.c.components[comp].kind {
                    shown.push((name.clone(), self.env[c]));
                }
            }
        }
        for (name, v) in shown {
            self.b.add(Kind::Output { name }, &[v], None);
        }
    }

    fn has_text(&self, s: SlotId) -> bool {
        match &self.slots[s.0 as usize] {
            Slot::Text => true,
            Slot::Agg(k) => k.iter().any(|k| self.has_text(*k)),
            _ => false,
        }
    }

    // ---- statements -------------------------------------------------------

    fn budget(&self, fr: &Frame) -> R<()> {
        if self.b.components() > limits::COMPONENTS {
            return Err(self.refuse(
                fr,
                Code::E1106,
                format!(
                    "the circuit would have more than {} components",
                    limits::COMPONENTS
                ),
            ));
        }
        Ok(())
    }

    fn block(&mut self, fr: &mut Frame, stmts: &[Stmt]) -> R<()> {
        for s in stmts {
            if self.alive == self.fals {
                // Dead code: no path reaches it.
                break;
            }
            self.stmt(fr, s)?;
        }
        Ok(())
    }

    fn stmt(&mut self, fr: &mut Frame, s: &Stmt) -> R<()> {
        self.at = (s.line, s.col);
        match &s.kind {
            StmtKind::Assign { place, value } => {
                // As the VM: the index expressions first; the element is
                // checked after the value only when the value calls
                // nothing and the place has a single index.
                let pre = self.place_indices(fr, place)?;
                let (loc, v) = if !stc_ir::visit::has_call(value) && single_index(place) {
                    let v = self.expr(fr, value)?;
                    (self.place_at(fr, place, &pre)?, v)
                } else {
                    let loc = self.place_at(fr, place, &pre)?;
                    (loc, self.expr(fr, value)?)
                };
                self.store(fr, &loc, v)?;
            }
            StmtKind::CallFb {
                instance,
                fb,
                inputs,
                inouts,
                outputs,
            } => {
                let loc = self.place(fr, instance)?;
                let inst = match loc {
                    Loc::Fixed(inst) => inst,
                    Loc::Dyn { idx, elems } => {
                        return self
                            .call_fb_chosen(fr, s, *fb, idx, &elems, inputs, inouts, outputs)
                    }
                    Loc::Part { .. } => {
                        return Err(self.refuse(
                            fr,
                            Code::E1105,
                            "a call of a part of a bit string",
                        ))
                    }
                };
                self.call_fb(fr, *fb, inst, inputs, inouts)?;
                self.at = (s.line, s.col);
                for o in outputs {
                    let v = match self.child(inst, o.var.0 as usize) {
                        Some(slot) => self.read(fr, &Loc::Fixed(slot))?,
                        None => {
                            return Err(self.refuse(fr, Code::E1105, "an output without storage"))
                        }
                    };
                    self.output(fr, o, v)?;
                }
            }
            StmtKind::Eval(e) => {
                self.expr(fr, e)?;
            }
            StmtKind::If {
                cond,
                then_body,
                else_body,
            } => {
                let c = self.bool_net(fr, cond)?;
                self.branch(fr, c, &mut |t, fr| t.block(fr, then_body), &mut |t, fr| {
                    t.block(fr, else_body)
                })?;
            }
            StmtKind::Switch {
                selector,
                arms,
                default,
            } => {
                let sel = self.scalar_net(fr, selector)?;
                self.arms(fr, sel, arms, default)?;
            }
            StmtKind::Loop { body, latch } => {
                fr.loops.push(LoopCtx {
                    start: self.journal.len(),
                    iter_start: self.journal.len(),
                    breaks: Vec::new(),
                    continues: Vec::new(),
                });
                let mut n = 0usize;
                while self.alive != self.fals {
                    n += 1;
                    if n > limits::LOOP_ITERATIONS {
                        self.at = (s.line, s.col);
                        return Err(self.refuse(
                            fr,
                            Code::E1101,
                            format!(
                                "a loop whose number of iterations is not known when compiling (WHILE, REPEAT, or FOR with run-time bounds), or above {}",
                                limits::LOOP_ITERATIONS
                            ),
                        ));
                    }
                    self.at = (s.line, s.col);
                    self.budget(fr)?;
                    let here = self.journal.len();
                    if let Some(l) = fr.loops.last_mut() {
                        l.iter_start = here;
                    }
                    self.block(fr, body)?;
                    let cont = fr
                        .loops
                        .last_mut()
                        .map(|l| std::mem::take(&mut l.continues))
                        .unwrap_or_default();
                    self.land(here, cont);
                    self.block(fr, latch)?;
                }
                if let Some(l) = fr.loops.pop() {
                    self.land(l.start, l.breaks);
                }
            }
            StmtKind::Break => {
                let j = self.jump();
                if let Some(l) = fr.loops.last_mut() {
                    l.breaks.push(j);
                }
                self.alive = self.fals;
            }
            StmtKind::Continue => {
                let j = self.jump();
                if let Some(l) = fr.loops.last_mut() {
                    l.continues.push(j);
                }
                self.alive = self.fals;
            }
            StmtKind::Return => {
                let j = self.jump();
                fr.ret.push(j);
                self.alive = self.fals;
            }
            StmtKind::Fault(kind) => {
                let code = self
                    .b
                    .konst(ElemType::Usint, Value::Int(kind.code() as i128));
                self.fault_site(fr, code);
                self.alive = self.fals;
            }
        }
        Ok(())
    }

    /// IF `c` THEN `then` ELSE `els`: each branch is translated from the
    /// values before the IF, and every cell either changes becomes a
    /// selector on `c` between the two branches' values.
    #[allow(clippy::type_complexity)]
    fn branch(
        &mut self,
        fr: &mut Frame,
        c: NetId,
        then: &mut dyn FnMut(&mut Self, &mut Frame) -> R<()>,
        els: &mut dyn FnMut(&mut Self, &mut Frame) -> R<()>,
    ) -> R<()> {
        let a0 = self.alive;
        let start = self.journal.len();
        let then_entry = self.b.and(a0, c);
        self.alive = then_entry;
        if self.alive != self.fals {
            then(self, fr)?;
        }
        let at = self.alive;
        // The THEN values, and the cells back to their values before.
        let then_changed = self.changed_since(start);
        let then_vals: Vec<NetId> = then_changed.iter().map(|(c, _)| self.env[*c]).collect();
        for &(cell, old) in &then_changed {
            self.set_cell(cell, old);
        }
        let mid = self.journal.len();
        let nc = self.b.not(c);
        let else_alive = self.b.and(a0, nc);
        self.alive = else_alive;
        if self.alive != self.fals {
            els(self, fr)?;
        }
        let ae = self.alive;
        let else_changed = self.changed_since(mid);
        let g = self.next_mark();
        for &(cell, _) in &then_changed {
            self.mark[cell] = g;
        }
        let mut cells: Vec<(usize, NetId)> = then_changed
            .iter()
            .map(|(c, _)| *c)
            .zip(then_vals)
            .collect();
        for (cell, old) in else_changed {
            if self.mark[cell] != g {
                cells.push((cell, old));
            }
        }
        for (cell, vt) in cells {
            let ve = self.env[cell];
            let v = if at == self.fals {
                ve
            } else if ae == self.fals {
                vt
            } else {
                self.b.switch(c, vt, ve)
            };
            self.set_cell(cell, v);
        }
        // (When neither branch jumped or faulted, every path that came in
        // goes on: no gate needed.)
        self.alive = if at == then_entry && ae == else_alive {
            a0
        } else {
            self.b.or(at, ae)
        };
        Ok(())
    }

    /// The cells changed since journal position `start`, in order, with
    /// their values then.
    fn changed_since(&mut self, start: usize) -> Vec<(usize, NetId)> {
        let g = self.next_mark();
        let mut out = Vec::new();
        for &(c, old) in &self.journal[start..] {
            if self.mark[c] != g {
                self.mark[c] = g;
                out.push((c, old));
            }
        }
        out
    }

    /// A fresh mark for [`Self::mark`] (every cell has an older one).
    fn next_mark(&mut self) -> u32 {
        self.mark.resize(self.cells.len(), 0);
        self.generation += 1;
        self.generation
    }

    /// CASE: the first arm whose ranges hold the selector, as a chain of
    /// branches.
    fn arms(
        &mut self,
        fr: &mut Frame,
        sel: NetId,
        arms: &[stc_ir::SwitchArm],
        default: &[Stmt],
    ) -> R<()> {
        let Some((arm, rest)) = arms.split_first() else {
            return self.block(fr, default);
        };
        let t = self.b.ty(sel);
        let mut c = self.fals;
        for &(lo, hi) in &arm.ranges {
            let r = if lo == hi {
                let k = self.b.konst(t, Value::Int(lo));
                self.b
                    .op(Kind::Binary(BinOp::Eq), &[sel, k], ElemType::Bool)
                    .0
            } else {
                let kl = self.b.konst(t, Value::Int(lo));
                let kh = self.b.konst(t, Value::Int(hi));
                let ge = self
                    .b
                    .op(Kind::Binary(BinOp::Ge), &[sel, kl], ElemType::Bool)
                    .0;
                let le = self
                    .b
                    .op(Kind::Binary(BinOp::Le), &[sel, kh], ElemType::Bool)
                    .0;
                self.b.and(ge, le)
            };
            c = self.b.or(c, r);
        }
        self.branch(fr, c, &mut |t, fr| t.block(fr, &arm.body), &mut |t, fr| {
            t.arms(fr, sel, rest, default)
        })
    }

    /// A jump from here: the paths alive now.
    fn jump(&mut self) -> Jump {
        Jump {
            cond: self.alive,
            pos: self.journal.len(),
        }
    }

    /// Where jumps land (their region began at journal position `start`):
    /// for the paths that took one, each cell changed since then gets the
    /// value it had at the jump; those paths are alive again.
    fn land(&mut self, start: usize, jumps: Vec<Jump>) {
        if jumps.is_empty() {
            return;
        }
        // Each changed cell's changes: (position, value before), in order.
        let mut changes: FxHashMap<usize, Vec<(usize, NetId)>> = FxHashMap::default();
        let mut order = Vec::new();
        for (i, &(c, old)) in self.journal[start..].iter().enumerate() {
            let e = changes.entry(c).or_insert_with(|| {
                order.push(c);
                Vec::new()
            });
            e.push((start + i, old));
        }
        let before: Vec<NetId> = order.iter().map(|c| self.env[*c]).collect();
        for j in jumps {
            for (&c, &now) in order.iter().zip(&before) {
                let list = &changes[&c];
                // The value at the jump: the one the first change after it
                // replaced, or the value now.
                let k = list.partition_point(|(p, _)| *p < j.pos);
                let v = list.get(k).map(|(_, old)| *old).unwrap_or(now);
                let cur = self.env[c];
                if v != now {
                    let n = self.b.switch(j.cond, v, cur);
                    self.env[c] = n;
                }
            }
            self.alive = self.b.or(self.alive, j.cond);
        }
        // The merged values are changes like any other.
        for (&c, &b) in order.iter().zip(&before) {
            if self.env[c] != b {
                self.journal.push((c, b));
            }
        }
    }

    fn set_cell(&mut self, c: usize, n: NetId) {
        let old = self.env[c];
        if old != n {
            self.journal.push((c, old));
            self.env[c] = n;
        }
    }

    fn output(&mut self, fr: &mut Frame, o: &Output, v: Val) -> R<()> {
        let v = if o.negated {
            match v {
                Val::S(n) => {
                    let t = self.b.ty(n);
                    Val::S(self.b.op(Kind::Unary(stc_values::UnOp::Not), &[n], t).0)
                }
                Val::A(_) => {
                    return Err(self.refuse(fr, Code::E1105, "a negated structured output"))
                }
            }
        } else {
            v
        };
        let loc = self.place(fr, &o.target)?;
        self.store(fr, &loc, v)
    }

    fn fault_site(&mut self, fr: &Frame, code: NetId) {
        let pou = self.m.pou(fr.pou);
        let alive = self.alive;
        self.b.add(
            Kind::Fault {
                instance: fr.instance.clone(),
                pou: self.m.spelled(pou.name, pou.name_span).to_string(),
                file: pou.file.clone(),
                line: self.at.0,
                col: self.at.1,
            },
            &[code, alive],
            None,
        );
    }

    fn check(&mut self, fr: &Frame, f: Option<NetId>) {
        if let Some(f) = f {
            if self.alive != self.fals {
                self.fault_site(fr, f);
            }
        }
    }

    fn op(&mut self, fr: &Frame, kind: Kind, ins: &[NetId], out: ElemType) -> NetId {
        let (x, f) = self.b.op(kind, ins, out);
        self.check(fr, f);
        x
    }

    // ---- calls ------------------------------------------------------------

    fn enter(&mut self, fr: &Frame) -> R<()> {
        self.depth += 1;
        if self.depth > 64 {
            return Err(self.refuse(fr, Code::E1105, "calls nested more than 64 deep"));
        }
        self.budget(fr)
    }

    fn call_fb(
        &mut self,
        fr: &mut Frame,
        fb: PouId,
        inst: SlotId,
        inputs: &[(VarId, Expr)],
        inouts: &[(VarId, Place)],
    ) -> R<()> {
        self.enter(fr)?;
        let at = self.at;
        for (v, e) in inputs {
            let val = self.expr(fr, e)?;
            let Some(slot) = self.child(inst, v.0 as usize) else {
                return Err(self.refuse(fr, Code::E1105, "an input without storage"));
            };
            self.store(fr, &Loc::Fixed(slot), val)?;
        }
        let mut bound = Vec::new();
        for (v, p) in inouts {
            bound.push((*v, self.place(fr, p)?));
        }
        let m = self.m;
        let pou = m.pou(fb);
        let iname = self.slot_name(inst).unwrap_or_else(|| fr.instance.clone());
        let mut callee = Frame {
            pou: fb,
            binds: Vec::with_capacity(pou.vars.len()),
            start: self.journal.len(),
            ret: Vec::new(),
            loops: Vec::new(),
            instance: iname.clone(),
        };
        for i in 0..pou.vars.len() {
            let v = VarId(i as u32);
            let b = match bound.iter().find(|(w, _)| *w == v) {
                Some((_, loc)) => Bind::Loc(loc.clone()),
                None => self.bind_var(fb, v, Some(inst), &iname),
            };
            callee.binds.push(b);
        }
        self.block(&mut callee, &pou.body)?;
        let ret = std::mem::take(&mut callee.ret);
        self.land(callee.start, ret);
        self.at = at;
        self.depth -= 1;
        Ok(())
    }

    /// A call of the instance `elems[idx]` chosen at run time
    /// (`fbs[i](...)`): the body of each candidate inlined under
    /// `idx = k`, like the arms of a CASE, and the outputs selected from
    /// the chosen one.
    #[allow(clippy::too_many_arguments)]
    fn call_fb_chosen(
        &mut self,
        fr: &mut Frame,
        s: &Stmt,
        fb: PouId,
        idx: NetId,
        elems: &[SlotId],
        inputs: &[(VarId, Expr)],
        inouts: &[(VarId, Place)],
        outputs: &[Output],
    ) -> R<()> {
        if elems.len() > limits::INDEXED_INSTANCES {
            return Err(self.refuse(
                fr,
                Code::E1103,
                format!(
                    "a call of a function block instance chosen at run time among {} (a circuit inlines at most {} candidates)",
                    elems.len(),
                    limits::INDEXED_INSTANCES
                ),
            ));
        }
        for (k, &inst) in elems.iter().enumerate() {
            let kn = self.b.konst(ElemType::Lint, Value::Int(k as i128));
            let eq = self
                .b
                .op(Kind::Binary(BinOp::Eq), &[idx, kn], ElemType::Bool)
                .0;
            self.branch(
                fr,
                eq,
                &mut |t, fr| t.call_fb(fr, fb, inst, inputs, inouts),
                &mut |_, _| Ok(()),
            )?;
            self.at = (s.line, s.col);
        }
        for o in outputs {
            let mut picks = Vec::with_capacity(elems.len());
            for &e in elems {
                match self.child(e, o.var.0 as usize) {
                    Some(c) => picks.push(c),
                    None => return Err(self.refuse(fr, Code::E1105, "an output without storage")),
                }
            }
            let v = self.read(fr, &Loc::Dyn { idx, elems: picks })?;
            self.output(fr, o, v)?;
        }
        Ok(())
    }

    /// The run-time path of an instance (`Main.tmr`).
    fn slot_name(&self, s: SlotId) -> Option<String> {
        self.inst_names.get(&s.0).cloned()
    }

    fn call_fn(
        &mut self,
        fr: &mut Frame,
        func: PouId,
        inputs: &[(VarId, Expr)],
        inouts: &[(VarId, Place)],
        outputs: &[Output],
    ) -> R<Val> {
        self.enter(fr)?;
        let at = self.at;
        let mut vals = Vec::with_capacity(inputs.len());
        for (v, e) in inputs {
            vals.push((*v, self.expr(fr, e)?));
        }
        let mut bound = Vec::new();
        for (v, p) in inouts {
            bound.push((*v, self.place(fr, p)?));
        }
        let m = self.m;
        let pou = m.pou(func);
        let mut callee = Frame {
            pou: func,
            binds: Vec::with_capacity(pou.vars.len()),
            start: self.journal.len(),
            ret: Vec::new(),
            loops: Vec::new(),
            instance: fr.instance.clone(),
        };
        for i in 0..pou.vars.len() {
            let v = VarId(i as u32);
            let b = match bound.iter().find(|(w, _)| *w == v) {
                Some((_, loc)) => Bind::Loc(loc.clone()),
                None => self.bind_var(func, v, None, ""),
            };
            callee.binds.push(b);
        }
        // Parameters are set unconditionally: the frame is new.
        for (v, val) in vals {
            if let Bind::Slot(s) = callee.binds[v.0 as usize].clone() {
                self.write_slot(&callee, s, val, None)?;
            }
        }
        self.block(&mut callee, &pou.body)?;
        let ret = std::mem::take(&mut callee.ret);
        self.land(callee.start, ret);
        let result = match pou.result {
            Some(r) => match callee.binds[r.0 as usize].clone() {
                Bind::Slot(s) => self.read(&callee, &Loc::Fixed(s))?,
                _ => Val::A(vec![]),
            },
            None => Val::A(vec![]),
        };
        self.at = at;
        for o in outputs {
            let v = match callee.binds[o.var.0 as usize].clone() {
                Bind::Slot(s) => self.read(&callee, &Loc::Fixed(s))?,
                _ => return Err(self.refuse(fr, Code::E1105, "an output without storage")),
            };
            self.output(fr, o, v)?;
        }
        self.depth -= 1;
        Ok(result)
    }

    // ---- places -----------------------------------------------------------

    fn place(&mut self, fr: &mut Frame, p: &Place) -> R<Loc> {
        let pre = self.place_indices(fr, p)?;
        self.place_at(fr, p, &pre)
    }

    /// The values of all the index expressions of a place, in order: they
    /// are all computed before any of them is checked against its bounds
    /// (as on every back end).
    fn place_indices(&mut self, fr: &mut Frame, p: &Place) -> R<Vec<IndexVal>> {
        let mut out = Vec::new();
        for proj in &p.proj {
            if let Proj::Index(list) = proj {
                for (e, _, _) in list {
                    // A checked index reports its own position.
                    let (at, e) = e.located();
                    out.push((self.scalar_net(fr, e)?, at));
                }
            }
        }
        Ok(out)
    }

    /// The place `p` whose index values are `pre` (see
    /// [`Self::place_indices`]): the indices checked in order.
    fn place_at(&mut self, fr: &mut Frame, p: &Place, pre: &[IndexVal]) -> R<Loc> {
        let mut next = 0usize;
        let mut loc = match &p.root {
            Root::Var(v) => match fr.binds.get(v.0 as usize).cloned() {
                Some(Bind::Slot(s)) => Loc::Fixed(s),
                Some(Bind::Loc(l)) => l,
                _ => {
                    return Err(self.refuse(
                        fr,
                        Code::E1105,
                        "a variable without storage in a circuit",
                    ))
                }
            },
            Root::Deref(_) => {
                return Err(self.refuse(
                    fr,
                    Code::E1105,
                    "a dereference (`p^` of a pointer or a reference): a circuit has no memory addresses",
                ));
            }
            Root::This => {
                return Err(self.refuse(fr, Code::E1105, "`THIS` (a method call)"));
            }
            Root::Global(g) => Loc::Fixed(self.global(*g)),
            Root::Direct(a) => Loc::Fixed(self.direct(a, p.ty, None)),
        };
        for proj in &p.proj {
            loc = match proj {
                Proj::Field(i) => self.project(fr, loc, *i as usize)?,
                Proj::FbVar(_, v) => self.project(fr, loc, v.0 as usize)?,
                Proj::Index(list) => {
                    let vals = pre.get(next..next + list.len()).unwrap_or(&[]);
                    next += list.len();
                    self.index(fr, loc, list, vals)?
                }
                Proj::Part(size, pos) => Loc::Part {
                    word: Box::new(loc),
                    bits: size.bits(),
                    pos: *pos,
                    ty: self.elem(fr, p.ty)?,
                },
            };
        }
        Ok(loc)
    }

    fn project(&mut self, fr: &Frame, loc: Loc, i: usize) -> R<Loc> {
        let bad = || "a member without storage".to_string();
        Ok(match loc {
            Loc::Part { .. } => return Err(self.refuse(fr, Code::E1105, bad())),
            Loc::Fixed(s) => match self.child(s, i) {
                Some(c) => Loc::Fixed(c),
                None => return Err(self.refuse(fr, Code::E1105, bad())),
            },
            Loc::Dyn { idx, elems } => {
                let mut out = Vec::with_capacity(elems.len());
                for e in elems {
                    match self.child(e, i) {
                        Some(c) => out.push(c),
                        None => return Err(self.refuse(fr, Code::E1105, bad())),
                    }
                }
                Loc::Dyn { idx, elems: out }
            }
        })
    }

    fn index(
        &mut self,
        fr: &mut Frame,
        loc: Loc,
        list: &[(Expr, i128, i128)],
        vals: &[IndexVal],
    ) -> R<Loc> {
        if vals.len() != list.len() {
            return Err(self.refuse(fr, Code::E1105, "an index without its value"));
        }
        let mut nets = Vec::with_capacity(list.len());
        for ((_, lo, hi), &(n, at)) in list.iter().zip(vals) {
            // A run-time index is checked against its bounds (a fault
            // site), and so is a constant one outside them (folded from an
            // expression the analyser does not evaluate, `a[LIMIT(...)]`:
            // the cycle faults there when the statement is reached).
            let n = match self.b.known(n).and_then(Value::as_int) {
                Some(i) if (*lo..=*hi).contains(&i) => n,
                _ => {
                    let t = self.b.ty(n);
                    let outer = self.at;
                    self.at = at.unwrap_or(outer);
                    let n = self.op(
                        fr,
                        Kind::Range {
                            lo: *lo,
                            hi: *hi,
                            fault: FaultKind::IndexOutOfBounds,
                        },
                        &[n],
                        t,
                    );
                    self.at = outer;
                    n
                }
            };
            nets.push(n);
        }
        let consts: Option<Vec<i128>> = nets
            .iter()
            .map(|n| self.b.known(*n).and_then(Value::as_int))
            .collect();
        // The arrays the index applies to: one, or one per element of an
        // outer array chosen at run time (`a[i][j]`, `a[i].b[j]`).
        let (outer, arrays) = match loc {
            Loc::Fixed(arr) => (None, vec![arr]),
            Loc::Dyn { idx, elems } => (Some(idx), elems),
            Loc::Part { .. } => {
                return Err(self.refuse(fr, Code::E1105, "an index into a part of a bit string"))
            }
        };
        let count = match arrays.first().map(|a| &self.slots[a.0 as usize]) {
            Some(Slot::Agg(k)) => k.len(),
            _ => 0,
        };
        if let Some(cs) = consts {
            let mut off: i128 = 0;
            for ((_, lo, hi), i) in list.iter().zip(cs) {
                off = off * (hi - lo + 1) + (i - lo);
            }
            let mut picked = Vec::with_capacity(arrays.len());
            for arr in &arrays {
                match usize::try_from(off).ok().and_then(|o| self.child(*arr, o)) {
                    Some(c) => picked.push(c),
                    None => {
                        return Err(self.refuse(
                            fr,
                            Code::E1105,
                            "a constant index outside its array",
                        ))
                    }
                }
            }
            return Ok(match outer {
                None => Loc::Fixed(picked[0]),
                Some(idx) => Loc::Dyn { idx, elems: picked },
            });
        }
        let total = count.saturating_mul(arrays.len());
        if total > limits::INDEXED_ELEMENTS {
            return Err(self.refuse(
                fr,
                Code::E1103,
                if outer.is_some() {
                    format!(
                        "array elements chosen at run time inside others chosen at run time: {total} elements to select among (a circuit selects among at most {})",
                        limits::INDEXED_ELEMENTS
                    )
                } else {
                    format!(
                        "an array of {count} elements indexed at run time (a circuit selects among at most {})",
                        limits::INDEXED_ELEMENTS
                    )
                },
            ));
        }
        // The zero-based offset, in LINT (after the outer one's: the
        // elements of every inner array in order).
        let lint = ElemType::Lint;
        let mut off = match outer {
            Some(idx) => idx,
            None => self.b.konst(lint, Value::Int(0)),
        };
        let mut first = outer.is_none();
        for ((_, lo, hi), n) in list.iter().zip(nets) {
            let w = self.b.konst(lint, Value::Int(hi - lo + 1));
            if !first {
                off = self.b.op(Kind::Binary(BinOp::Mul), &[off, w], lint).0;
            }
            first = false;
            let t = self.b.ty(n);
            let n = if t == lint {
                n
            } else {
                self.b.op(Kind::Convert, &[n], lint).0
            };
            let l = self.b.konst(lint, Value::Int(*lo));
            let d = self.b.op(Kind::Binary(BinOp::Sub), &[n, l], lint).0;
            off = self.b.op(Kind::Binary(BinOp::Add), &[off, d], lint).0;
        }
        let mut elems = Vec::with_capacity(total);
        for arr in &arrays {
            match &self.slots[arr.0 as usize] {
                Slot::Agg(k) if k.len() == count => elems.extend(k.iter().copied()),
                _ => {
                    return Err(self.refuse(
                        fr,
                        Code::E1105,
                        "arrays of different shapes chosen at run time",
                    ))
                }
            }
        }
        Ok(Loc::Dyn { idx: off, elems })
    }

    fn read_slot(&mut self, fr: &Frame, s: SlotId) -> R<Val> {
        match self.slots[s.0 as usize].clone() {
            Slot::Leaf(c) => Ok(Val::S(self.env[c])),
            Slot::Agg(k) => {
                let mut out = Vec::with_capacity(k.len());
                for &k in k.iter() {
                    out.push(self.read_slot(fr, k)?);
                }
                Ok(Val::A(out))
            }
            Slot::Text => Err(self.refuse(
                fr,
                Code::E1102,
                "a STRING or WSTRING variable: a circuit has no strings",
            )),
            Slot::Absent => {
                Err(self.refuse(fr, Code::E1105, "a variable without storage in a circuit"))
            }
            Slot::Address => Err(self.refuse(fr, Code::E1105, NO_ADDRESSES)),
        }
    }

    fn read(&mut self, fr: &Frame, loc: &Loc) -> R<Val> {
        match loc {
            Loc::Part {
                word,
                bits,
                pos,
                ty,
            } => {
                let w = self.read(fr, word)?;
                let Val::S(w) = w else {
                    return Err(self.refuse(fr, Code::E1105, "a part of a structured value"));
                };
                let kind = Kind::PartGet {
                    bits: *bits,
                    pos: *pos,
                };
                Ok(Val::S(self.b.op(kind, &[w], *ty).0))
            }
            Loc::Fixed(s) => self.read_slot(fr, *s),
            Loc::Dyn { idx, elems } => {
                let mut vals = Vec::with_capacity(elems.len());
                for e in elems {
                    vals.push(self.read_slot(fr, *e)?);
                }
                Ok(self.select(*idx, &vals))
            }
        }
    }

    /// The element `idx` of `vals` (all of one shape), leaf by leaf.
    fn select(&mut self, idx: NetId, vals: &[Val]) -> Val {
        match vals.first() {
            Some(Val::A(first)) => {
                let n = first.len();
                let mut out = Vec::with_capacity(n);
                for i in 0..n {
                    let col: Vec<Val> = vals
                        .iter()
                        .map(|v| match v {
                            Val::A(k) => k[i].clone(),
                            s => s.clone(),
                        })
                        .collect();
                    out.push(self.select(idx, &col));
                }
                Val::A(out)
            }
            Some(Val::S(first)) => {
                let t = self.b.ty(*first);
                let mut ins = vec![idx];
                for v in vals {
                    if let Val::S(n) = v {
                        ins.push(*n);
                    }
                }
                Val::S(self.b.op(Kind::Index { lo: 0 }, &ins, t).0)
            }
            None => Val::A(vec![]),
        }
    }

    fn store(&mut self, fr: &Frame, loc: &Loc, v: Val) -> R<()> {
        match loc {
            Loc::Part {
                word,
                bits,
                pos,
                ty,
            } => {
                let (Val::S(w), Val::S(v)) = (self.read(fr, word)?, v) else {
                    return Err(self.refuse(fr, Code::E1105, "a part of a structured value"));
                };
                let v = self.fit(v, *ty);
                let t = self.b.ty(w);
                let kind = Kind::PartSet {
                    bits: *bits,
                    pos: *pos,
                };
                let n = self.b.op(kind, &[w, v], t).0;
                self.store(fr, word, Val::S(n))
            }
            Loc::Fixed(s) => self.write_slot(fr, *s, v, None),
            Loc::Dyn { idx, elems } => {
                for (k, e) in elems.iter().enumerate() {
                    let kn = self.b.konst(ElemType::Lint, Value::Int(k as i128));
                    let eq = self
                        .b
                        .op(Kind::Binary(BinOp::Eq), &[*idx, kn], ElemType::Bool)
                        .0;
                    self.write_slot(fr, *e, v.clone(), Some(eq))?;
                }
                Ok(())
            }
        }
    }

    /// Writes `v` into the cells of `s`, under `guard` (`None`: always).
    fn write_slot(&mut self, fr: &Frame, s: SlotId, v: Val, guard: Option<NetId>) -> R<()> {
        match (self.slots[s.0 as usize].clone(), v) {
            (Slot::Leaf(c), Val::S(n)) => {
                if self.cells[c].kind == CellKind::Input {
                    return Err(self.refuse(
                        fr,
                        Code::E1104,
                        "an assignment to an input of the circuit (a program VAR_INPUT or a %I variable), which the circuit only reads",
                    ));
                }
                let old = self.env[c];
                let n = self.fit(n, self.b.ty(old));
                let n = match guard {
                    None => n,
                    Some(g) => self.b.switch(g, n, old),
                };
                self.set_cell(c, n);
                Ok(())
            }
            (Slot::Agg(k), Val::A(vs)) if k.len() == vs.len() => {
                for (k, v) in k.iter().copied().zip(vs) {
                    self.write_slot(fr, k, v, guard)?;
                }
                Ok(())
            }
            (Slot::Text, _) => Err(self.refuse(
                fr,
                Code::E1102,
                "a STRING or WSTRING variable: a circuit has no strings",
            )),
            (Slot::Address, _) => Err(self.refuse(fr, Code::E1105, NO_ADDRESSES)),
            _ => Err(self.refuse(
                fr,
                Code::E1105,
                "an assignment whose value does not match its target's shape",
            )),
        }
    }

    /// A net of type `t` for `n` (a subrange or enumeration stored in its
    /// base type has the same representation).
    fn fit(&mut self, n: NetId, t: ElemType) -> NetId {
        if self.b.ty(n) == t {
            n
        } else {
            self.b.op(Kind::Convert, &[n], t).0
        }
    }

    // ---- expressions ------------------------------------------------------

    fn scalar_net(&mut self, fr: &mut Frame, e: &Expr) -> R<NetId> {
        match self.expr(fr, e)? {
            Val::S(n) => Ok(n),
            Val::A(_) => Err(self.refuse(
                fr,
                Code::E1105,
                "a structured value where a single value is needed",
            )),
        }
    }

    fn bool_net(&mut self, fr: &mut Frame, e: &Expr) -> R<NetId> {
        self.scalar_net(fr, e)
    }

    fn elem(&self, fr: &Frame, t: TypeId) -> R<ElemType> {
        if let Some(why) = self.is_address(t) {
            return Err(self.refuse(fr, Code::E1105, why));
        }
        match self.scalar(t) {
            Some(ElemType::String | ElemType::Wstring) => Err(self.refuse(
                fr,
                Code::E1102,
                "a STRING or WSTRING operation: a circuit has no strings",
            )),
            Some(e) => Ok(e),
            None => Err(self.refuse(
                fr,
                Code::E1105,
                "a structured value where a single value is needed",
            )),
        }
    }

    fn expr(&mut self, fr: &mut Frame, e: &Expr) -> R<Val> {
        Ok(match &e.kind {
            ExprKind::Ref(_) | ExprKind::Null => {
                return Err(self.refuse(
                    fr,
                    Code::E1105,
                    "an address (`ADR(x)`, `REF(x)`, `NULL`): a circuit has no memory addresses",
                ));
            }
            ExprKind::Const(v) => {
                let t = self.elem(fr, e.ty)?;
                Val::S(self.b.konst(t, v.clone()))
            }
            ExprKind::Load(p) => {
                let loc = self.place(fr, p)?;
                self.read(fr, &loc)?
            }
            ExprKind::Unary(op, a) => {
                let t = self.elem(fr, e.ty)?;
                let a = self.scalar_net(fr, a)?;
                Val::S(self.op(fr, Kind::Unary(*op), &[a], t))
            }
            ExprKind::Binary(op, a, b) => {
                let t = self.elem(fr, e.ty)?;
                self.elem(fr, a.ty)?;
                self.elem(fr, b.ty)?;
                let a = self.scalar_net(fr, a)?;
                let b = self.scalar_net(fr, b)?;
                Val::S(self.op(fr, Kind::Binary(*op), &[a, b], t))
            }
            ExprKind::Convert(a) => {
                let t = self.elem(fr, e.ty)?;
                self.elem(fr, a.ty)?;
                let a = self.scalar_net(fr, a)?;
                if self.b.ty(a) == t {
                    Val::S(a)
                } else {
                    Val::S(self.op(fr, Kind::Convert, &[a], t))
                }
            }
            ExprKind::Check { value, lo, hi } => {
                let t = self.elem(fr, e.ty)?;
                let a = self.scalar_net(fr, value)?;
                let a = self.fit(a, t);
                Val::S(self.op(
                    fr,
                    Kind::Range {
                        lo: *lo,
                        hi: *hi,
                        fault: FaultKind::SubrangeViolation,
                    },
                    &[a],
                    t,
                ))
            }
            ExprKind::CallFn {
                func,
                inputs,
                inouts,
                outputs,
            } => self.call_fn(fr, *func, inputs, inouts, outputs)?,
            ExprKind::Intrinsic { func, args } => {
                let t = self.elem(fr, e.ty)?;
                let mut ins = Vec::with_capacity(args.len());
                for a in args {
                    self.elem(fr, a.ty)?;
                    ins.push(self.scalar_net(fr, a)?);
                }
                Val::S(self.op(fr, Kind::Call(*func), &ins, t))
            }
            ExprKind::CurTime => {
                let t = self.elem(fr, e.ty)?;
                Val::S(self.b.op(Kind::Clock, &[], t).0)
            }
            ExprKind::Located { line, col, expr } => {
                let outer = std::mem::replace(&mut self.at, (*line, *col));
                let v = self.expr(fr, expr);
                self.at = outer;
                v?
            }
        })
    }
}

/// The refusals of pointers and references.
/// (After the analysis a pointer is a structure holding a reference, so
/// both are refused where the first reference is met: the column says
/// which construct it is.)
const NO_ADDRESSES: &str = "a pointer or a reference (`POINTER TO`, `ADR(x)`, `REF_TO`, `REF(x)`, `p^`): a circuit has no memory addresses";

impl Tr<'_> {
    /// Whether values of type `t` are addresses: a reference, or a pointer
    /// (after the analysis the structure `{OBJECT, BASE, OFFSET}` whose
    /// BASE is a reference, docs/oop.md).
    fn is_address(&self, t: TypeId) -> Option<&'static str> {
        match self.m.types.kind(t) {
            TypeKind::Ref(_) => Some(NO_ADDRESSES),
            TypeKind::Ptr(_) => Some(NO_ADDRESSES),
            TypeKind::Struct { fields } => fields
                .iter()
                .any(|f| matches!(self.m.types.kind(f.ty), TypeKind::Ref(_)))
                .then_some(NO_ADDRESSES),
            _ => None,
        }
    }
}

/// Whether a place has exactly one index (`a[i]`, not `a[i, j]` or
/// `a[i][j]`) from a variable: the one case where the VM checks the index
/// after computing the value assigned.
fn single_index(p: &Place) -> bool {
    let mut indexes = p.proj.iter().filter_map(|pr| match pr {
        Proj::Index(i) => Some(i),
        _ => None,
    });
    let one = matches!((indexes.next(), indexes.next()), (Some(i), None) if i.len() == 1);
    one && !matches!(p.root, Root::Deref(_))
}

/// A variable's name in paths (a hidden variable gets its role after `$`).
fn var_name(m: &Module, pou: &Pou, v: &stc_ir::Var) -> String {
    let _ = pou;
    let base = m.spelled(v.name, v.span);
    match v.hidden {
        Some(role) => format!("{base}${role}"),
        None => base.to_string(),
    }
}
