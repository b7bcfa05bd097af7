//! The program: C types, data, POU bodies, initialisers and the descriptor
//! tables of `stc_meta.h`, from the IR (see the crate documentation for the
//! design). This module writes the types and the bodies of POUs
//! (statements, places, expressions, calls); `init` the initial values and
//! init functions; `tables` the data objects, `stc_init_all` and the
//! descriptor tables.

mod init;
mod tables;

use std::fmt::Write as _;

use rustc_hash::{FxHashMap, FxHashSet};
use stc_ir::{
    Expr, ExprKind, FaultKind, Module, Output, Place, Proj, Root, Stmt, StmtKind, Storage,
};
use stc_sema::idx::{IdVec, Idx};
use stc_sema::{DataRef, GlobalId, InitValue, PouId, Section, TypeId, TypeKind, VarId};
use stc_syntax::ast::PouKind;
use stc_syntax::literal::{AddrSize, DirectAddress};
use stc_syntax::token::ElemType;
use stc_values::{UnOp, Value};

use crate::names::{self, elem_c, elem_code, literal};
use crate::ops::{self, Emit, Operation};
use crate::Error;

/// The generated program: `program.h` and `program.c`.
pub struct Program {
    pub header: String,
    pub source: String,
}

/// What the statement generator knows about the function being written.
#[derive(Default)]
struct Func {
    pou: PouId,
    function: bool,
    /// Declarations at the top of the function.
    decls: Vec<String>,
    /// Its statements.
    body: Vec<String>,
    depth: usize,
    next_temp: u32,
    site: u32,
    /// Per enclosing loop: the label of its latch (when CONTINUE needs it).
    loops: Vec<Option<String>>,
    /// Control variables of enclosing FOR loops with constant bounds, and
    /// the range they stay in inside the loop body.
    ranges: Vec<(VarId, i128, i128)>,
    /// The indices range analysis proves inside their bounds.
    proven: stc_ir::ranges::Proven,
    /// The loops emitted twice behind a guard (`stc_ir::ranges::Versions`),
    /// and inside the check-free copy of one, its version.
    versions: stc_ir::ranges::Versions,
    fast: Option<stc_ir::ranges::Version>,
    /// By variable: the C local holding it inside the body, when it is
    /// held in one (`stc_ir::visit::register_vars`), and whether the body
    /// assigns it (then it is stored back before calls and at exits).
    locals: Vec<Option<String>>,
    written: Vec<bool>,
    next_label: u32,
}

/// Finds the file, line and column of a span.
pub type Locate<'a> = &'a dyn Fn(stc_diagnostics::Span) -> Option<(String, u32, u32)>;

struct Gen<'a> {
    m: &'a Module,
    locate: Locate<'a>,
    /// Type definitions (program.h), in dependency order.
    typedefs: String,
    forward: String,
    defined: FxHashSet<TypeId>,
    defined_pous: FxHashSet<PouId>,
    array_names: FxHashSet<String>,
    /// The `static const` tables of CONSTANT arrays (see `const_table`).
    const_tables: FxHashSet<String>,
    strings: FxHashSet<(bool, u32)>,
    /// File-scope data of program.c.
    data: String,
    /// Statements of `stc_init_all` that set constants.
    const_init: Vec<String>,
    consts: FxHashMap<(bool, Vec<u16>), String>,
    protos: String,
    bodies: String,
    /// Per POU: whether running it may raise a fault (`stc_ir::faults`).
    may_fault: Vec<bool>,
    sites: Vec<(String, String, u32, u32)>,
    site_map: FxHashMap<(PouId, u32, u32), u32>,
    /// The program model (`stc_ir::model`): the numbering of the
    /// descriptor tables, the process image slots.
    model: stc_ir::model::Data,
    meta_extra: String,
    f: Func,
    /// The (configuration, resource) contexts, for binding VAR_EXTERNAL.
    contexts: Vec<(usize, usize)>,
    /// The POUs the program uses (others, such as unused standard FBs, are
    /// not generated).
    used: IdVec<PouId, bool>,
    /// The POUs whose body is generated (`called_pous`).
    called: IdVec<PouId, bool>,
    /// The POUs that have instances (and so an initialiser).
    instantiated: IdVec<PouId, bool>,
    /// The type of each process-image slot: of the first variable located
    /// there, else of its address.
    io_types: FxHashMap<DirectAddress, TypeId>,
    /// The declarations of the process image arrays (program.h).
    image_header: String,
    /// The private variables of unbound VAR_EXTERNALs (`private_external`).
    private_cells: FxHashSet<String>,
}

/// Generates the program of a module.
pub fn program(m: &Module, locate: Locate<'_>) -> Result<Program, Error> {
    let layouts = stc_ir::layout::Layouts::compute(m).map_err(Error::Diagnostics)?;
    let model = stc_ir::model::build(m, &layouts).map_err(|e| match e {
        stc_ir::model::ModelError::Diagnostics(d) => Error::Diagnostics(d),
        stc_ir::model::ModelError::Internal(what) => {
            Error::Unsupported(format!("internal error: {what}"))
        }
    })?;
    // The type of each process-image slot, as the model decided it.
    let mut io_types = FxHashMap::default();
    for slot in &model.model.io {
        if let Some(Some(t)) = model.type_ids.get(slot.ty as usize) {
            io_types.insert(slot.address.clone(), *t);
        }
    }
    let mut contexts = Vec::new();
    for (c, conf) in m.configs.iter().enumerate() {
        for r in 0..conf.resources.len() {
            contexts.push((c, r));
        }
    }
    let mut g = Gen {
        m,
        locate,
        typedefs: String::new(),
        forward: String::new(),
        defined: FxHashSet::default(),
        defined_pous: FxHashSet::default(),
        array_names: FxHashSet::default(),
        const_tables: FxHashSet::default(),
        strings: FxHashSet::default(),
        data: String::new(),
        const_init: Vec::new(),
        consts: FxHashMap::default(),
        protos: String::new(),
        bodies: String::new(),
        may_fault: stc_ir::faults::may_fault(m),
        sites: Vec::new(),
        site_map: FxHashMap::default(),
        model,
        meta_extra: String::new(),
        f: Func::default(),
        contexts,
        used: used_pous(m),
        called: IdVec::new(),
        instantiated: IdVec::new(),
        io_types,
        image_header: String::new(),
        private_cells: FxHashSet::default(),
    };
    g.called = called_pous(m, &g.used);
    g.instantiated = instantiated_pous(m, &g.used);
    g.run()
}

impl<'a> Gen<'a> {
    /// The program, or the first construct not translated, with where it is.
    fn run(&mut self) -> Result<Program, Error> {
        self.program().map_err(|e| match e {
            Error::Unsupported(what) => match self.sites.get(self.f.site as usize) {
                Some((_, file, line, col)) => Error::At(file.clone(), *line, *col, what),
                None => Error::Unsupported(what),
            },
            e => e,
        })
    }

    fn program(&mut self) -> Result<Program, Error> {
        let m = self.m;
        let used: Vec<PouId> = m.pous.ids().filter(|&p| self.used[p]).collect();
        for &p in &used {
            self.define_pou(p);
        }
        for &p in &used {
            self.prototype(p);
        }
        for &p in &used {
            if self.called[p] {
                self.pou_body(p)?;
            }
        }
        for &p in &used {
            if m.pous[p].kind != PouKind::Function && self.instantiated[p] {
                self.init_fn(p)?;
            }
        }
        let init_all = self.data_and_tables()?;
        let mut header = String::new();
        header.push_str(
            "/* Generated by stc from IEC 61131-3 sources: types of the program. */\n\
             #ifndef STC_PROGRAM_H\n#define STC_PROGRAM_H\n\n#include <stdint.h>\n\n",
        );
        let mut strings: Vec<&(bool, u32)> = self.strings.iter().collect();
        strings.sort();
        for &&(wide, len) in &strings {
            if wide {
                let _ = writeln!(
                    header,
                    "typedef struct {{ uint16_t s[{}]; }} stc_wstr_{len};",
                    len + 1
                );
            } else {
                let _ = writeln!(
                    header,
                    "typedef struct {{ uint8_t s[{}]; }} stc_str_{len};",
                    len + 2
                );
            }
        }
        header.push('\n');
        // A reference (REF_TO T): the address of its variable, NULL for
        // none; a dereference casts it to the target's type after checking
        // it is not NULL. Declared only where the generated code uses it
        // (MISRA C 2.3): a program may have a reference type that no
        // variable or expression has (a method's instance, for one).
        let uses_refs = [
            &self.forward,
            &self.typedefs,
            &self.data,
            &self.protos,
            &self.bodies,
            &self.meta_extra,
            &init_all,
        ]
        .iter()
        .any(|text| text.contains("stc_ref"));
        if uses_refs {
            header.push_str("typedef void *stc_ref;\n");
        }
        header.push_str(&self.forward);
        header.push('\n');
        header.push_str(&self.typedefs);
        header.push_str("\n/* ---- process image (stc_io.h) ---- */\n");
        header.push_str(&self.image_header);
        header.push_str("\n#endif\n");
        let mut source = String::new();
        source.push_str(
            "/* Generated by stc from IEC 61131-3 sources: the program, its data and\n   \
             its descriptor tables (stc_meta.h). */\n\
             #include <math.h>\n#include <stddef.h>\n#include <stdint.h>\n#include <string.h>\n\n\
             #include \"stc_rt.h\"\n#include \"stc_gen.h\"\n#include \"stc_meta.h\"\n#include \"program.h\"\n\n",
        );
        source.push_str("/* ---- data ---- */\n");
        source.push_str(&self.data);
        source.push_str("\n/* ---- POUs ---- */\n");
        source.push_str(&self.protos);
        source.push('\n');
        source.push_str(&self.bodies);
        source.push_str("\n/* ---- descriptor tables ---- */\n");
        source.push_str(&self.meta_extra);
        source.push_str(&init_all);
        Ok(Program { header, source })
    }

    // ----- types ------------------------------------------------------------

    /// Makes sure a C type exists for `t` (typedefs in dependency order).
    fn define(&mut self, t: TypeId) {
        let m = self.m;
        match m.types.kind(t).clone() {
            TypeKind::String { wide, len } => {
                self.strings.insert((wide, len));
            }
            TypeKind::Array { dims, elem } => {
                if !self.defined.insert(t) {
                    return;
                }
                self.define(elem);
                let n = array_count(&dims);
                let name = names::type_name(m, t);
                if !self.array_names.insert(name.clone()) {
                    return;
                }
                let _ = writeln!(
                    self.typedefs,
                    "typedef struct {{ {} a[{n}]; }} {name};",
                    names::type_name(m, elem)
                );
            }
            TypeKind::Struct { fields } => {
                if !self.defined.insert(t) {
                    return;
                }
                for f in &fields {
                    self.define(f.ty);
                }
                let name = names::type_name(m, t);
                let mut body = String::new();
                for f in &fields {
                    let _ = writeln!(
                        body,
                        "    {} m_{};",
                        names::type_name(m, f.ty),
                        names::ident(m.spelled(f.name, f.span))
                    );
                }
                if fields.is_empty() {
                    body.push_str("    uint8_t stc_empty;\n");
                }
                let _ = writeln!(self.forward, "typedef struct {name}_s {name};");
                let _ = writeln!(self.typedefs, "struct {name}_s {{\n{body}}};");
            }
            TypeKind::Fb(p) | TypeKind::Program(p) => self.define_pou(p),
            _ => {}
        }
    }

    /// The instance struct of an FB or program, or the frame struct of a function.
    fn define_pou(&mut self, p: PouId) {
        if !self.defined_pous.insert(p) {
            return;
        }
        let m = self.m;
        let pou = &m.pous[p];
        let function = pou.kind == PouKind::Function;
        let name = if function {
            names::frame_type_name(m, p)
        } else {
            names::pou_type_name(m, p)
        };
        // (A reference to it may have declared it already.)
        let line = format!("typedef struct {name}_s {name};\n");
        if !self.forward.contains(&line) {
            self.forward.push_str(&line);
        }
        let mut body = String::new();
        for (i, v) in pou.vars.iter_enumerated() {
            let in_struct = function || v.storage != Storage::Frame;
            if !in_struct {
                continue;
            }
            if v.storage == Storage::Ref {
                self.define_pointee(v.ty);
                let _ = writeln!(
                    body,
                    "    {} *{};",
                    names::type_name(m, v.ty),
                    names::var_name(m, i, v)
                );
            } else {
                self.define(v.ty);
                let _ = writeln!(
                    body,
                    "    {} {};",
                    names::type_name(m, v.ty),
                    names::var_name(m, i, v)
                );
            }
        }
        if body.is_empty() {
            body.push_str("    uint8_t stc_empty;\n");
        }
        let _ = writeln!(self.typedefs, "struct {name}_s {{\n{body}}};");
    }

    /// A type used behind a pointer: declared (structs forward, the rest whole).
    fn define_pointee(&mut self, t: TypeId) {
        match self.m.types.kind(t) {
            TypeKind::Fb(p) | TypeKind::Program(p) => {
                let p = *p;
                if !self.defined_pous.contains(&p) {
                    // A forward declaration is enough; the definition comes
                    // when the POU is defined.
                    let name = names::pou_type_name(self.m, p);
                    let line = format!("typedef struct {name}_s {name};\n");
                    if !self.forward.contains(&line) {
                        self.forward.push_str(&line);
                    }
                    self.define_pou(p);
                }
            }
            _ => self.define(t),
        }
    }

    fn scalar(&self, t: TypeId) -> Option<ElemType> {
        self.m.types.scalar(t)
    }

    fn is_string(&self, t: TypeId) -> Option<(bool, u32)> {
        match self.m.types.kind(t) {
            TypeKind::String { wide, len } => Some((*wide, *len)),
            _ => None,
        }
    }

    // ----- the process image ---------------------------------------------------

    fn io_type(&self, a: &DirectAddress) -> TypeId {
        self.io_types
            .get(a)
            .copied()
            .unwrap_or_else(|| self.m.addr_type(a))
    }

    /// The slot of an address as an lvalue of type `want`: itself, or seen
    /// as the other signedness of the same integer size (C allows that
    /// access); other views of one address are not translated.
    fn io_access(&self, a: &DirectAddress, want: TypeId) -> Result<String, Error> {
        let m = self.m;
        let slot = self.io_type(a);
        let (sc, wc) = (names::type_name(m, slot), names::type_name(m, want));
        let name = names::io_name(a);
        if sc == wc {
            return Ok(name);
        }
        let int = |c: &str| c.starts_with("int") || c.starts_with("uint");
        let same_size = sc.trim_start_matches('u') == wc.trim_start_matches('u');
        if int(&sc) && int(&wc) && same_size {
            Ok(format!("(*({wc} *)&{name})"))
        } else {
            Err(Error::Unsupported(format!(
                "variables of different types ({sc} and {wc}) at the address {a}"
            )))
        }
    }

    /// The variable a VAR_EXTERNAL gets when no global of its name and
    /// type exists where it runs (a program run on its own whose globals
    /// are in a configuration): a static of its own, set to the type's
    /// default by the POU's init function, as the VM gives it.
    fn private_external(&mut self, p: PouId, v: VarId, t: TypeId) -> Result<String, Error> {
        let cell = format!("ext_{p}_{v}");
        self.define(t);
        if self.private_cells.insert(cell.clone()) {
            let _ = writeln!(self.data, "static {} {cell};", names::type_name(self.m, t));
        }
        self.init_value(&cell, t, None, Some("0U"), 0)?;
        Ok(cell)
    }

    // ----- sites ------------------------------------------------------------

    fn site_of(&mut self, line: u32, col: u32) -> u32 {
        let key = (self.f.pou, line, col);
        if let Some(&s) = self.site_map.get(&key) {
            return s;
        }
        let pou = &self.m.pous[self.f.pou];
        let s = self.sites.len() as u32;
        self.sites.push((
            self.m.spelled(pou.name, pou.name_span).to_string(),
            pou.file.clone(),
            line,
            col,
        ));
        self.site_map.insert(key, s);
        s
    }

    // ----- bodies -----------------------------------------------------------

    fn prototype(&mut self, p: PouId) {
        let m = self.m;
        if self.called[p] {
            let sig = self.signature(p);
            let _ = writeln!(self.protos, "{sig};");
        }
        if m.pous[p].kind != PouKind::Function && self.instantiated[p] {
            let _ = writeln!(
                self.protos,
                "static void {}({} *const self, uint32_t ctx);",
                names::init_name(m, p),
                names::pou_type_name(m, p)
            );
        }
    }

    fn signature(&self, p: PouId) -> String {
        let m = self.m;
        if m.pous[p].kind == PouKind::Function {
            format!(
                "static void {}({} *const f)",
                names::body_name(m, p),
                names::frame_type_name(m, p)
            )
        } else {
            format!(
                "static void {}({} *const self)",
                names::body_name(m, p),
                names::pou_type_name(m, p)
            )
        }
    }

    fn pou_body(&mut self, p: PouId) -> Result<(), Error> {
        let m = self.m;
        let pou = &m.pous[p];
        let function = pou.kind == PouKind::Function;
        let proven = stc_ir::ranges::Proven::of(m, pou);
        let versions = stc_ir::ranges::Versions::of(m, pou, &proven);
        self.f = Func {
            pou: p,
            function,
            depth: 1,
            proven,
            versions,
            ..Func::default()
        };
        let line = pou.body.first().map_or(1, |s| s.line);
        let col = pou.body.first().map_or(1, |s| s.col);
        self.f.site = self.site_of(line, col);
        let entry_site = self.f.site;
        // A function's locals, outputs and result start at their initial
        // values at each call (its inputs and in-outs are set by the caller);
        // an FB's or program's VAR_TEMP likewise.
        for (i, v) in pou.vars.iter_enumerated() {
            if !in_frame(function, v) {
                continue;
            }
            let name = names::var_name(m, i, v);
            if !function {
                self.define(v.ty);
                self.f
                    .decls
                    .push(format!("{} {name};", names::type_name(m, v.ty)));
            }
            let lv = if function { format!("f->{name}") } else { name };
            self.init_value(&lv, v.ty, v.init.as_ref(), None, 0)?;
            if !function {
                // A VAR_TEMP only written (an output target) is still used.
                self.line(format!("(void){lv};"));
            }
        }
        self.declare_locals(p);
        // The watchdog's step after the initial values: a function stopped
        // here still hands back an initialised frame (no uninitialised read
        // in the caller, which leaves at once anyway).
        let bail = self.bail();
        self.line(format!("if (stc_step({entry_site}U) != 0U) {{ {bail} }}"));
        self.block(&pou.body)?;
        for l in self.flush_lines() {
            self.line(l);
        }
        let sig = self.signature(p);
        let mut out = format!("{sig}\n{{\n");
        for d in &self.f.decls {
            let _ = writeln!(out, "    {d}");
        }
        // An empty body (or one that touches no variable) still takes its
        // instance or frame: say it is unused on purpose (-Wunused-parameter).
        let param = if function { "f" } else { "self" };
        if !self.body_uses_param(p) {
            let _ = writeln!(out, "    (void){param};");
        }
        self.finish_function(out);
        Ok(())
    }

    /// Holds the scalars of the body in C locals (as a C programmer keeps
    /// `i`, `j`, `tmp` in registers: gcc cannot, for a struct member that
    /// a store into an array of the same struct may alias), loaded here.
    fn declare_locals(&mut self, p: PouId) {
        let m = self.m;
        let pou = &m.pous[p];
        let scalar = |t: TypeId| {
            matches!(
                m.types.kind(t),
                TypeKind::Elem(_) | TypeKind::Subrange { .. } | TypeKind::Enum { .. }
            ) && !matches!(
                m.types.scalar(t),
                None | Some(ElemType::String | ElemType::Wstring)
            )
        };
        let (ok, written) = stc_ir::visit::register_vars(m, p, &scalar, &|_, _| true);
        self.f.locals = vec![None; ok.len()];
        self.f.written = written;
        for (i, v) in pou.vars.iter_enumerated() {
            // An FB's or program's VAR_TEMP is a C local already.
            if !ok[i.index()] || (!self.f.function && v.storage == Storage::Frame) {
                continue;
            }
            let name = format!("l_{}", names::var_name(m, i, v));
            self.f
                .decls
                .push(format!("{} {name};", names::type_name(m, v.ty)));
            let mem = self.mem_lvalue(i);
            self.line(format!("{name} = {mem};"));
            self.f.locals[i.index()] = Some(name);
        }
    }

    /// Stores the locals the body assigns back to their variables.
    fn flush_lines(&self) -> Vec<String> {
        let mut out = Vec::new();
        for (i, l) in self.f.locals.iter().enumerate() {
            if let (Some(l), true) = (l, self.f.written.get(i).copied().unwrap_or(true)) {
                out.push(format!("{} = {l};", self.mem_lvalue(VarId::new(i))));
            }
        }
        out
    }

    /// Reloads every local from its variable (after a call).
    fn reload_lines(&self) -> Vec<String> {
        let mut out = Vec::new();
        for (i, l) in self.f.locals.iter().enumerate() {
            if let Some(l) = l {
                out.push(format!("{l} = {};", self.mem_lvalue(VarId::new(i))));
            }
        }
        out
    }

    /// A call of a body at `call` (a C statement), the locals stored
    /// before it and reloaded after it: the callee may reach them through
    /// a reference.
    fn call_line(&mut self, call: String) {
        for l in self.flush_lines() {
            self.line(l);
        }
        self.line(call);
        for l in self.reload_lines() {
            self.line(l);
        }
    }

    /// The check after a call of POU `p`: the full fault check when it may
    /// fault (directly, or through its own calls), else only the
    /// watchdog's (which costs nothing without STC_WATCHDOG).
    fn call_check(&mut self, p: PouId) {
        if self.may_fault.get(p.index()).copied().unwrap_or(true) {
            self.fault_return();
        } else {
            let bail = self.bail();
            self.line(format!("if (stc_watchdog_tripped() != 0U) {{ {bail} }}"));
        }
    }

    /// Ends a function whose head is `out`: its body lines, the closing
    /// brace, appended to the bodies of the program.
    fn finish_function(&mut self, mut out: String) {
        for l in &self.f.body {
            out.push_str(l);
            out.push('\n');
        }
        out.push_str("}\n\n");
        self.bodies.push_str(&out);
    }

    fn line(&mut self, s: String) {
        let pad = "    ".repeat(self.f.depth);
        self.f.body.push(format!("{pad}{s}"));
    }

    fn open(&mut self, s: String) {
        self.line(s);
        self.f.depth += 1;
    }

    fn close(&mut self, s: &str) {
        self.f.depth = self.f.depth.saturating_sub(1);
        self.line(s.to_string());
    }

    fn new_temp(&mut self, c_type: String) -> String {
        let n = format!("t{}", self.f.next_temp);
        self.f.next_temp += 1;
        self.f.decls.push(format!("{c_type} {n};"));
        n
    }

    /// How a body ends because of a fault: a function block or program
    /// body first says the fault happened in its instance (unless a
    /// deeper one said so).
    fn bail(&self) -> String {
        let mut out = self.flush_lines().join(" ");
        if !out.is_empty() {
            out.push(' ');
        }
        if self.f.function {
            out.push_str("return;");
        } else {
            let _ = write!(out, "stc_fault_in(self, {}U); return;", self.f.pou.0);
        }
        out
    }

    fn fault_return(&mut self) {
        let bail = self.bail();
        self.line(format!("if (stc_fault_kind != 0U) {{ {bail} }}"));
    }

    fn block(&mut self, stmts: &[Stmt]) -> Result<(), Error> {
        for (k, s) in stmts.iter().enumerate() {
            let range = stc_ir::faults::for_range(&stmts[..k], s, &self.m.pous[self.f.pou]);
            if let Some(r) = range {
                self.f.ranges.push(r);
            }
            self.stmt(s)?;
            if range.is_some() {
                self.f.ranges.pop();
            }
        }
        Ok(())
    }

    /// A loop: `for (;;)` with the watchdog step, the body and the latch.
    fn emit_loop(&mut self, body: &[Stmt], latch: &[Stmt]) -> Result<(), Error> {
        let label = if !latch.is_empty() && uses_continue(body) {
            let l = format!("L{}", self.f.next_label);
            self.f.next_label += 1;
            Some(l)
        } else {
            None
        };
        let site = self.f.site;
        self.open("for (;;) {".into());
        let bail = self.bail();
        self.line(format!("if (stc_step({site}U) != 0U) {{ {bail} }}"));
        self.f.loops.push(label.clone());
        self.block(body)?;
        self.f.loops.pop();
        if let Some(l) = &label {
            self.line(format!("{l}: ;"));
        }
        // The control variable leaves its range in the latch.
        let saved = std::mem::take(&mut self.f.ranges);
        self.block(latch)?;
        self.f.ranges = saved;
        self.close("}");
        Ok(())
    }

    fn stmt(&mut self, s: &Stmt) -> Result<(), Error> {
        self.f.site = self.site_of(s.line, s.col);
        match &s.kind {
            StmtKind::Assign { place, value } => self.assign(place, value),
            StmtKind::CallFb {
                instance,
                fb,
                inputs,
                inouts,
                outputs,
            } => self.call_fb(instance, *fb, inputs, inouts, outputs),
            StmtKind::Eval(e) => {
                self.expr(e)?;
                Ok(())
            }
            StmtKind::If {
                cond,
                then_body,
                else_body,
            } => {
                let c = self.expr(cond)?;
                if then_body.is_empty() && !else_body.is_empty() {
                    // IF c THEN ELSE ... (WHILE's test): the negated test.
                    self.open(format!("if ({c} == 0U) {{"));
                    self.block(else_body)?;
                    self.close("}");
                    return Ok(());
                }
                self.open(format!("if ({c} != 0U) {{"));
                self.block(then_body)?;
                if else_body.is_empty() {
                    self.close("}");
                } else {
                    self.f.depth = self.f.depth.saturating_sub(1);
                    self.open("} else {".into());
                    self.block(else_body)?;
                    self.close("}");
                }
                Ok(())
            }
            StmtKind::Switch {
                selector,
                arms,
                default,
            } => {
                let sel = self.expr(selector)?;
                let e = self.scalar(selector.ty).unwrap_or(ElemType::Lint);
                let (tmin, tmax) = stc_values::int_range(e).unwrap_or((i128::MIN, i128::MAX));
                let mut first = true;
                let mut any = false;
                for arm in arms {
                    let mut conds = Vec::new();
                    for &(lo, hi) in &arm.ranges {
                        let l = literal(e, &Value::Int(lo));
                        let h = literal(e, &Value::Int(hi));
                        conds.push(if lo == hi {
                            format!("({sel} == {l})")
                        } else if lo <= tmin && hi >= tmax {
                            "(1 == 1)".to_string()
                        } else if lo <= tmin {
                            format!("({sel} <= {h})")
                        } else if hi >= tmax {
                            format!("({sel} >= {l})")
                        } else {
                            format!("(({sel} >= {l}) && ({sel} <= {h}))")
                        });
                    }
                    if conds.is_empty() {
                        continue;
                    }
                    let c = conds.join(" || ");
                    if first {
                        self.open(format!("if ({c}) {{"));
                        first = false;
                    } else {
                        self.f.depth = self.f.depth.saturating_sub(1);
                        self.open(format!("}} else if ({c}) {{"));
                    }
                    any = true;
                    self.block(&arm.body)?;
                }
                if any {
                    self.f.depth = self.f.depth.saturating_sub(1);
                    self.open("} else {".into());
                    if default.is_empty() {
                        self.line("/* no arm selected */".into());
                    }
                    self.block(default)?;
                    self.close("}");
                } else {
                    self.block(default)?;
                }
                Ok(())
            }
            StmtKind::Loop { body, latch } => match self.f.versions.get(s).cloned() {
                // Loop versioning: the check-free copy where the guard
                // holds, the checked loop where it does not.
                Some(v) if self.f.fast.is_none() => {
                    let c = self.expr(&v.guard)?;
                    self.open(format!("if ({c} != 0U) {{"));
                    self.f.fast = Some(v);
                    let r = self.emit_loop(body, latch);
                    self.f.fast = None;
                    r?;
                    self.f.depth = self.f.depth.saturating_sub(1);
                    self.open("} else {".into());
                    self.emit_loop(body, latch)?;
                    self.close("}");
                    Ok(())
                }
                _ => self.emit_loop(body, latch),
            },
            StmtKind::Break => {
                self.line("break;".into());
                Ok(())
            }
            StmtKind::Continue => {
                match self.f.loops.last().cloned().flatten() {
                    Some(l) => self.line(format!("goto {l};")),
                    None => self.line("continue;".into()),
                }
                Ok(())
            }
            StmtKind::Return => {
                for l in self.flush_lines() {
                    self.line(l);
                }
                self.line("return;".into());
                Ok(())
            }
            StmtKind::Fault(k) => {
                let site = self.f.site;
                self.line(format!("stc_fault({}U, {site}U);", fault_code(*k)));
                let bail = self.bail();
                self.line(bail);
                Ok(())
            }
        }
    }

    // ----- places -----------------------------------------------------------

    /// The C lvalue of a variable of the current POU: its local, when
    /// the body holds it in one.
    fn var_lvalue(&self, v: VarId) -> String {
        if let Some(Some(l)) = self.f.locals.get(v.index()) {
            return l.clone();
        }
        self.mem_lvalue(v)
    }

    /// The C lvalue of a variable of the current POU in memory.
    fn mem_lvalue(&self, v: VarId) -> String {
        let m = self.m;
        let pou = &m.pous[self.f.pou];
        let var = pou.var(v);
        let name = names::var_name(m, v, var);
        let base = if self.f.function {
            format!("f->{name}")
        } else if var.storage == Storage::Frame {
            name
        } else {
            format!("self->{name}")
        };
        if var.storage == Storage::Ref {
            format!("(*{base})")
        } else {
            base
        }
    }

    /// A CONSTANT array of elementary values of the current POU as a
    /// `static const` table (its reads can then be folded by the C
    /// compiler); the variable itself still holds the same values for the
    /// harness.
    fn const_table(&mut self, v: VarId) -> Option<String> {
        let m = self.m;
        if !self.is_const_table(self.f.pou, v) {
            return None;
        }
        let var = m.pous[self.f.pou].var(v);
        let TypeKind::Array { dims, elem } = m.types.kind(var.ty) else {
            return None;
        };
        let e = self.scalar(*elem)?;
        let name = format!("KC{}_{}", self.f.pou, v.0);
        if !self.const_tables.contains(&name) {
            let n = array_count(dims) as usize;
            let list = match &var.init {
                Some(InitValue::Array(l)) => l.clone(),
                _ => Vec::new(),
            };
            let default = match m.types.kind(*elem) {
                TypeKind::Subrange { lo, .. } => Value::Int(*lo),
                TypeKind::Enum { values, .. } => Value::Int(values.first().map_or(0, |x| x.value)),
                _ => stc_values::default_value(e),
            };
            let mut items = Vec::with_capacity(n);
            for i in 0..n {
                let val = match list.get(i) {
                    Some(Some(InitValue::Scalar(x))) => x.clone(),
                    Some(Some(_)) => return None,
                    _ => default.clone(),
                };
                items.push(literal(e, &val));
            }
            self.define(var.ty);
            let _ = writeln!(
                self.data,
                "static const {} {name} = {{ {{ {} }} }};",
                names::type_name(m, var.ty),
                items.join(", ")
            );
            self.const_tables.insert(name.clone());
        }
        Some(name)
    }

    /// Whether variable `v` of POU `p` is read from a `static const` table
    /// ([`Gen::const_table`]): a CONSTANT array of elementary values (not
    /// strings) held directly, every initial value given a scalar.
    fn is_const_table(&self, p: PouId, v: VarId) -> bool {
        let m = self.m;
        let var = m.pous[p].var(v);
        if !var.constant || var.storage == Storage::Ref {
            return false;
        }
        let TypeKind::Array { elem, .. } = m.types.kind(var.ty) else {
            return false;
        };
        let elementary = self
            .scalar(*elem)
            .is_some_and(|e| !matches!(e, ElemType::String | ElemType::Wstring));
        let scalars = match &var.init {
            Some(InitValue::Array(l)) => l
                .iter()
                .all(|x| matches!(x, None | Some(InitValue::Scalar(_)))),
            _ => true,
        };
        elementary && scalars
    }

    /// Whether [`Gen::init_value`] writes anything for a value of type `t`
    /// (not for an empty struct or an erroneous type).
    fn init_writes(&self, t: TypeId) -> bool {
        match self.m.types.kind(t) {
            TypeKind::Array { elem, .. } => self.init_writes(*elem),
            TypeKind::Struct { fields } => fields.iter().any(|f| self.init_writes(f.ty)),
            TypeKind::Error | TypeKind::Void => false,
            TypeKind::Ref(_)
            | TypeKind::Ptr(_)
            | TypeKind::Elem(_)
            | TypeKind::String { .. }
            | TypeKind::Subrange { .. }
            | TypeKind::Enum { .. }
            | TypeKind::Fb(_)
            | TypeKind::Program(_) => true,
        }
    }

    /// Whether the body function of POU `p` refers to its parameter (`f`,
    /// a function's frame; `self`, an FB's or program's instance): a
    /// function sets its locals, outputs and result in the frame on entry,
    /// and a body names its variables there, except VAR_TEMPs of an FB or
    /// program (locals of the C function) and CONSTANT arrays read from
    /// their tables. Decided on the IR (`stc_ir::visit::used_vars`).
    fn body_uses_param(&self, p: PouId) -> bool {
        let pou = &self.m.pous[p];
        let function = pou.kind == PouKind::Function;
        let used = stc_ir::visit::used_vars(&pou.body, pou.vars.len());
        pou.vars.iter().enumerate().any(|(i, v)| {
            let set_on_entry = function && in_frame(function, v) && self.init_writes(v.ty);
            let named = used[i]
                && (function || v.storage != Storage::Frame)
                && !self.is_const_table(p, VarId(i as u32));
            set_on_entry || named
        })
    }

    /// Whether the initialiser of FB or program `p` refers to its instance:
    /// when it has a variable of the instance to set or bind.
    fn init_uses_self(&self, p: PouId) -> bool {
        self.m.pous[p].vars.iter().any(|v| match v.storage {
            Storage::Frame => false,
            Storage::Ref => true,
            Storage::Instance => self.init_writes(v.ty),
        })
    }

    /// The C lvalue of a place, with its index checks emitted (or, with
    /// `defer`, returned to be emitted later). A bit part is not applied
    /// here (see [`Gen::load_place`] and [`Gen::store_place`]).
    fn place(&mut self, p: &Place, defer: Option<&mut Vec<String>>) -> Result<String, Error> {
        let m = self.m;
        let (mut lv, mut ty) = match &p.root {
            Root::Var(v) => (
                match self.const_table(*v) {
                    Some(k) => k,
                    None => self.var_lvalue(*v),
                },
                m.pous[self.f.pou].var(*v).ty,
            ),
            Root::Global(g) => (global_lvalue(m, *g), m.globals[*g].ty),
            Root::Direct(a) => (self.io_access(a, m.addr_type(a))?, m.addr_type(a)),
            // The running function block's instance (only in its body).
            Root::This => ("(*self)".to_string(), p.ty),
            Root::Deref(r) => {
                // The address, checked not to be NULL, as the target type.
                let target = m.types.ref_target(r.ty).unwrap_or(TypeId::ERROR);
                self.define_pointee(target);
                // A fault at the `^`, said to be in this body's instance.
                let (at, r) = r.located();
                let v = self.expr(r)?;
                let t = self.new_temp("stc_ref".into());
                self.line(format!("{t} = {v};"));
                let site = match at {
                    Some((line, col)) => self.site_of(line, col),
                    None => self.f.site,
                };
                let code = fault_code(FaultKind::NullReference);
                let bail = self.bail();
                self.line(format!(
                    "if ({t} == NULL) {{ stc_fault({code}U, {site}U); {bail} }}"
                ));
                (format!("(*({} *){t})", names::type_name(m, target)), target)
            }
        };
        let mut deferred = defer;
        // The bound checks of every index of the place come after all its
        // index expressions, as on the VM (`a[k][MUX(k, ...)]` faults in
        // the MUX before `k` is checked).
        let mut own_checks: Vec<String> = Vec::new();
        for proj in &p.proj {
            match proj {
                Proj::Field(i) => {
                    let TypeKind::Struct { fields } = m.types.kind(ty) else {
                        return Err(Error::Unsupported("a member of a non-struct".into()));
                    };
                    let Some(f) = fields.get(*i as usize) else {
                        return Err(Error::Unsupported("an unknown struct member".into()));
                    };
                    lv = format!("{lv}.m_{}", names::ident(m.spelled(f.name, f.span)));
                    ty = f.ty;
                }
                Proj::FbVar(fb, v) => {
                    let var = m.pous[*fb].var(*v);
                    let name = names::var_name(m, *v, var);
                    lv = if var.storage == Storage::Ref {
                        if var.section == Section::InOut {
                            // NULL until a call of the instance binds it.
                            let t = self.new_temp("const void *".into());
                            self.line(format!("{t} = (const void *){lv}.{name};"));
                            let code = fault_code(FaultKind::NullReference);
                            let site = self.f.site;
                            let bail = self.bail();
                            self.line(format!(
                                "if ({t} == NULL) {{ stc_fault({code}U, {site}U); {bail} }}"
                            ));
                        }
                        format!("(*{lv}.{name})")
                    } else {
                        format!("{lv}.{name}")
                    };
                    ty = var.ty;
                }
                Proj::Index(idx) => {
                    let TypeKind::Array { dims, elem } = m.types.kind(ty).clone() else {
                        return Err(Error::Unsupported("indexing a non-array".into()));
                    };
                    if idx.len() != dims.len() {
                        return Err(Error::Unsupported(
                            "a partial index of a multi-dimensional array".into(),
                        ));
                    }
                    let counts: Vec<i128> = dims.iter().map(|(l, h)| h - l + 1).collect();
                    // Indices no check can fail (constants; FOR control
                    // variables whose bounds are inside the array's) are
                    // signed offsets when every index of the access is such:
                    // gcc then walks the array with a pointer, as it does
                    // for hand-written C (an unsigned conversion hides the
                    // induction).
                    let unchecked = |g: &Self, e: &stc_ir::Expr, lo: i128, hi: i128| {
                        matches!(e.kind, ExprKind::Const(Value::Int(_)))
                            || stc_ir::faults::index_in_range(e, &g.f.ranges, lo, hi)
                            || g.f.proven.contains(e)
                            || g.f.fast.as_ref().is_some_and(|v| v.covers(e))
                    };
                    let signed = idx.iter().all(|(e, lo, hi)| unchecked(self, e, *lo, *hi));
                    let mut flat = Vec::new();
                    let mut checks = Vec::new();
                    for (k, (e, lo, hi)) in idx.iter().enumerate() {
                        let mult: i128 = counts[k + 1..].iter().product();
                        let proven = self.f.proven.contains(e)
                            || self.f.fast.as_ref().is_some_and(|v| v.covers(e));
                        // A checked index reports its own position.
                        let (at, e) = e.located();
                        if let ExprKind::Const(Value::Int(i)) = &e.kind {
                            // Checked by the analyser.
                            let pos = (i - lo) * mult;
                            flat.push(if signed {
                                format!("INT64_C({})", pos.max(0))
                            } else {
                                format!("{}U", pos.max(0))
                            });
                            continue;
                        }
                        let known =
                            proven || stc_ir::faults::index_in_range(e, &self.f.ranges, *lo, *hi);
                        let i = self.expr(e)?;
                        if known && signed {
                            let k_t = self.new_temp("int64_t".into());
                            checks.push(format!("{k_t} = (int64_t){i} - INT64_C({lo});"));
                            flat.push(if mult == 1 {
                                k_t
                            } else {
                                format!("({k_t} * INT64_C({mult}))")
                            });
                            continue;
                        }
                        let k_t = self.new_temp("uint32_t".into());
                        let site = match at {
                            Some((line, col)) => self.site_of(line, col),
                            None => self.f.site,
                        };
                        if known {
                            checks
                                .push(format!("{k_t} = (uint32_t)((int64_t){i} - INT64_C({lo}));"));
                            flat.push(if mult == 1 {
                                k_t
                            } else {
                                format!("({k_t} * {mult}U)")
                            });
                            continue;
                        }
                        let unsigned64 =
                            matches!(self.scalar(e.ty), Some(ElemType::Ulint | ElemType::Lword));
                        let call = if unsigned64 {
                            format!(
                                "{k_t} = stc_ix_u64({i}, INT64_C({lo}), INT64_C({hi}), {site}U);"
                            )
                        } else {
                            format!(
                                "{k_t} = stc_ix_i64((int64_t){i}, INT64_C({lo}), INT64_C({hi}), {site}U);"
                            )
                        };
                        checks.push(call);
                        checks.push(format!("if (stc_fault_kind != 0U) {{ {} }}", self.bail()));
                        flat.push(if mult == 1 {
                            k_t
                        } else {
                            format!("({k_t} * {mult}U)")
                        });
                    }
                    match deferred.as_deref_mut() {
                        Some(d) => d.extend(checks),
                        None => own_checks.extend(checks),
                    }
                    lv = format!("{lv}.a[{}]", flat.join(" + "));
                    ty = elem;
                }
                Proj::Part(..) => {}
            }
        }
        for c in own_checks {
            self.line(c);
        }
        Ok(lv)
    }

    /// The bit part of a place, if it ends with one: (word bits, part bits, index).
    fn part_of(&self, p: &Place) -> Option<(u32, u32, u32)> {
        let Some(Proj::Part(size, index)) = p.proj.last() else {
            return None;
        };
        let word = self.place_base_type(p)?;
        let bits = self
            .scalar(word)
            .map(stc_ir::layout::elem_size)
            .unwrap_or(8)
            * 8;
        let part = match size {
            AddrSize::Bit => 1,
            s => s.bits(),
        };
        Some((bits, part, *index))
    }

    /// The type of a place before its final bit part.
    fn place_base_type(&self, p: &Place) -> Option<TypeId> {
        let m = self.m;
        let mut ty = match &p.root {
            Root::Var(v) => m.pous[self.f.pou].var(*v).ty,
            Root::Global(g) => m.globals[*g].ty,
            Root::Direct(a) => m.addr_type(a),
            Root::Deref(r) => m.types.ref_target(r.ty)?,
            Root::This => p.ty,
        };
        for proj in &p.proj {
            ty = match proj {
                Proj::Field(i) => match m.types.kind(ty) {
                    TypeKind::Struct { fields } => fields.get(*i as usize)?.ty,
                    _ => return None,
                },
                Proj::FbVar(fb, v) => m.pous[*fb].var(*v).ty,
                Proj::Index(_) => match m.types.kind(ty) {
                    TypeKind::Array { elem, .. } => *elem,
                    _ => return None,
                },
                Proj::Part(..) => return Some(ty),
            };
        }
        Some(ty)
    }

    /// The value of a place as an operand.
    fn load_place(&mut self, p: &Place) -> Result<String, Error> {
        let lv = self.place(p, None)?;
        if let Some((_, part, index)) = self.part_of(p) {
            let t = self.new_temp(names::type_name(self.m, p.ty));
            let c = names::type_name(self.m, p.ty);
            let read = format!("stc_getpart((uint64_t){lv}, {part}U, {index}U)");
            if part == 1 {
                // (Not a cast of the comparison: MISRA C 10.5.)
                self.line(format!("{t} = ({read} != 0U) ? 1U : 0U;"));
            } else {
                self.line(format!("{t} = ({c}){read};"));
            }
            return Ok(t);
        }
        Ok(match self.is_string(p.ty) {
            Some(_) => format!("{lv}.s"),
            None => lv,
        })
    }

    /// Stores operand `v` (of type `vt`) into the place.
    fn store_place(&mut self, p: &Place, lv: &str, v: &str, vt: TypeId) -> Result<(), Error> {
        let m = self.m;
        if let Some((bits, part, index)) = self.part_of(p) {
            let word_t = self
                .place_base_type(p)
                .map(|t| names::type_name(m, t))
                .unwrap_or_else(|| "uint64_t".into());
            let _ = bits;
            self.line(format!(
                "{lv} = ({word_t})stc_setpart((uint64_t){lv}, {part}U, {index}U, (uint64_t){v});"
            ));
            return Ok(());
        }
        match self.is_string(p.ty) {
            Some((false, cap)) => self.line(format!("stc_str_copy({lv}.s, {cap}U, {v});")),
            Some((true, cap)) => self.line(format!("stc_wstr_copy({lv}.s, {cap}U, {v});")),
            None => {
                let _ = vt;
                self.line(format!("{lv} = {v};"));
            }
        }
        Ok(())
    }

    fn assign(&mut self, place: &Place, value: &Expr) -> Result<(), Error> {
        // As the VM: with a value that calls nothing, the element of a
        // one-dimensional array is checked after the value is computed.
        let lazy = !stc_ir::visit::has_call(value) && single_index(place);
        if lazy {
            let mut checks = Vec::new();
            let lv = self.place(place, Some(&mut checks))?;
            let v = self.expr(value)?;
            for c in checks {
                self.line(c);
            }
            self.store_place(place, &lv, &v, value.ty)
        } else {
            let lv = self.place(place, None)?;
            let v = self.expr(value)?;
            self.store_place(place, &lv, &v, value.ty)
        }
    }

    // ----- expressions ------------------------------------------------------

    /// The operand of an expression: a C expression of its value (for a
    /// string, the length-prefixed array).
    fn expr(&mut self, e: &Expr) -> Result<String, Error> {
        let m = self.m;
        match &e.kind {
            ExprKind::Const(v) => self.constant(e.ty, v),
            ExprKind::Load(p) => self.load_place(p),
            ExprKind::CurTime => Ok("stc_clock".into()),
            ExprKind::Null => Ok("((stc_ref)NULL)".into()),
            ExprKind::Ref(p) => {
                let lv = self.place(p, None)?;
                let t = self.new_temp("stc_ref".into());
                self.line(format!("{t} = (stc_ref)&{lv};"));
                Ok(t)
            }
            ExprKind::Binary(op @ (stc_values::BinOp::Eq | stc_values::BinOp::Ne), x, y)
                if m.types.ref_target(x.ty).is_some() =>
            {
                let a = self.expr(x)?;
                let b = self.expr(y)?;
                let c = if *op == stc_values::BinOp::Eq {
                    "=="
                } else {
                    "!="
                };
                let t = self.new_temp("uint8_t".into());
                self.line(format!("{t} = ({a} {c} {b}) ? 1U : 0U;"));
                Ok(t)
            }
            ExprKind::Unary(op, x) => {
                let a = self.expr(x)?;
                self.op(Operation::Unary(*op), vec![(a, x.ty)], e.ty)
            }
            ExprKind::Binary(op, x, y) => {
                let a = self.expr(x)?;
                let b = self.expr(y)?;
                self.op(Operation::Binary(*op), vec![(a, x.ty), (b, y.ty)], e.ty)
            }
            ExprKind::Convert(x) => {
                let a = self.expr(x)?;
                if m.types.kind(x.ty) == m.types.kind(e.ty) {
                    return Ok(a);
                }
                // A reference seen as another (pointers, docs/oop.md): the
                // same address.
                if matches!(m.types.kind(x.ty), TypeKind::Ref(_))
                    && matches!(m.types.kind(e.ty), TypeKind::Ref(_))
                {
                    return Ok(a);
                }
                if let (Some((fw, _)), Some((tw, cap))) =
                    (self.is_string(x.ty), self.is_string(e.ty))
                {
                    if fw == tw {
                        // The same string kind: truncated to the new capacity.
                        self.define(e.ty);
                        let t = self.new_temp(names::type_name(m, e.ty));
                        let f = if tw { "stc_wstr_copy" } else { "stc_str_copy" };
                        self.line(format!("{f}({t}.s, {cap}U, {a});"));
                        return Ok(format!("{t}.s"));
                    }
                }
                self.op(Operation::Convert, vec![(a, x.ty)], e.ty)
            }
            ExprKind::Check { value, lo, hi } => {
                let a = self.expr(value)?;
                self.op(
                    Operation::Check { lo: *lo, hi: *hi },
                    vec![(a, value.ty)],
                    e.ty,
                )
            }
            ExprKind::Intrinsic { func, args } => {
                let mut ops = Vec::with_capacity(args.len());
                for a in args {
                    let o = self.expr(a)?;
                    ops.push((o, a.ty));
                }
                self.op(Operation::Intrinsic(*func), ops, e.ty)
            }
            ExprKind::CallFn {
                func,
                inputs,
                inouts,
                outputs,
            } => self.call_fn(*func, inputs, inouts, outputs, e.ty),
            ExprKind::Located { line, col, expr } => {
                let outer = self.f.site;
                self.f.site = self.site_of(*line, *col);
                let r = self.expr(expr);
                self.f.site = outer;
                r
            }
        }
    }

    /// An operation into a fresh temporary.
    fn op(
        &mut self,
        op: Operation,
        args: Vec<(String, TypeId)>,
        ty: TypeId,
    ) -> Result<String, Error> {
        self.define(ty);
        let t = self.new_temp(names::type_name(self.m, ty));
        let dst = if self.is_string(ty).is_some() {
            format!("{t}.s")
        } else {
            t
        };
        ops::emit_op(self, op, &args, ty, &dst);
        Ok(dst)
    }

    /// A constant operand.
    fn constant(&mut self, ty: TypeId, v: &Value) -> Result<String, Error> {
        match self.is_string(ty) {
            Some(_) => self.string_const(v),
            None => match self.scalar(ty) {
                Some(e) => Ok(literal(e, v)),
                None => Err(Error::Unsupported("a constant of an aggregate type".into())),
            },
        }
    }

    /// A string constant operand (a STRING or WSTRING of its own length).
    fn string_const(&mut self, v: &Value) -> Result<String, Error> {
        match v {
            Value::Str(bytes) => {
                let key = (false, bytes.iter().map(|&b| b as u16).collect::<Vec<u16>>());
                if let Some(n) = self.consts.get(&key) {
                    return Ok(format!("{n}.s"));
                }
                let n = format!("K{}", self.consts.len());
                self.strings.insert((false, bytes.len() as u32));
                let _ = writeln!(self.data, "static stc_str_{} {n};", bytes.len());
                if bytes.iter().all(|&b| (0x20..0x7f).contains(&b)) {
                    let lit = c_bytes(bytes);
                    self.const_init.push(format!(
                        "stc_sconst({n}.s, (const uint8_t *){lit}, {}U);",
                        bytes.len()
                    ));
                } else {
                    // Bytes outside printable ASCII as a table (no escape
                    // sequences in literals: MISRA rule 4.1).
                    let list: Vec<String> = bytes.iter().map(|b| format!("{b}U")).collect();
                    let _ = writeln!(
                        self.data,
                        "static const uint8_t {n}_bytes[{}] = {{ {} }};",
                        bytes.len().max(1),
                        if list.is_empty() {
                            "0U".to_string()
                        } else {
                            list.join(", ")
                        }
                    );
                    self.const_init
                        .push(format!("stc_sconst({n}.s, {n}_bytes, {}U);", bytes.len()));
                }
                self.consts.insert(key, n.clone());
                Ok(format!("{n}.s"))
            }
            Value::WStr(units) => {
                let key = (true, units.clone());
                if let Some(n) = self.consts.get(&key) {
                    return Ok(format!("{n}.s"));
                }
                let n = format!("K{}", self.consts.len());
                self.strings.insert((true, units.len() as u32));
                let _ = writeln!(self.data, "static stc_wstr_{} {n};", units.len());
                let list: Vec<String> = units.iter().map(|u| format!("{u}U")).collect();
                let arr = if list.is_empty() {
                    "0U".to_string()
                } else {
                    list.join(", ")
                };
                let _ = writeln!(
                    self.data,
                    "static const uint16_t {n}_units[{}] = {{ {arr} }};",
                    units.len().max(1)
                );
                self.const_init
                    .push(format!("stc_wsconst({n}.s, {n}_units, {}U);", units.len()));
                self.consts.insert(key, n.clone());
                Ok(format!("{n}.s"))
            }
            _ => Err(Error::Unsupported(
                "a string constant of another kind".into(),
            )),
        }
    }

    // ----- calls ------------------------------------------------------------

    fn call_fn(
        &mut self,
        func: PouId,
        inputs: &[(VarId, Expr)],
        inouts: &[(VarId, Place)],
        outputs: &[Output],
        ty: TypeId,
    ) -> Result<String, Error> {
        let m = self.m;
        let p = func;
        let callee = &m.pous[p];
        let fr = self.new_temp(names::frame_type_name(m, p));
        // Every input in declaration order: given, or its initial value.
        for (i, v) in callee.vars.iter_enumerated() {
            if v.section != Section::Input {
                continue;
            }
            let var = i;
            let dst = format!("{fr}.{}", names::var_name(m, i, v));
            match inputs.iter().find(|(p, _)| *p == var) {
                Some((_, e)) => {
                    let val = self.expr(e)?;
                    self.assign_value(&dst, v.ty, &val)?;
                }
                None => self.init_value(&dst, v.ty, v.init.as_ref(), None, 0)?,
            }
        }
        for (v, pl) in inouts {
            let var = callee.var(*v);
            let lv = self.place(pl, None)?;
            self.line(format!("{fr}.{} = &{lv};", names::var_name(m, *v, var)));
        }
        self.call_line(format!("{}(&{fr});", names::body_name(m, p)));
        self.call_check(p);
        for o in outputs {
            let var = callee.var(o.var);
            let src = format!("{fr}.{}", names::var_name(m, o.var, var));
            let src = if self.is_string(var.ty).is_some() {
                format!("{src}.s")
            } else {
                src
            };
            self.copy_out(&src, var.ty, o)?;
        }
        let res = callee
            .result
            .map(|r| (r, callee.var(r)))
            .map(|(r, v)| format!("{fr}.{}", names::var_name(m, r, v)));
        Ok(match res {
            Some(r) if self.is_string(ty).is_some() => format!("{r}.s"),
            Some(r) => r,
            None => "0U".to_string(),
        })
    }

    /// `dst := val` for a destination of type `ty` (strings truncated).
    fn assign_value(&mut self, dst: &str, ty: TypeId, val: &str) -> Result<(), Error> {
        match self.is_string(ty) {
            Some((false, cap)) => self.line(format!("stc_str_copy({dst}.s, {cap}U, {val});")),
            Some((true, cap)) => self.line(format!("stc_wstr_copy({dst}.s, {cap}U, {val});")),
            None => self.line(format!("{dst} = {val};")),
        }
        Ok(())
    }

    /// Copies an output parameter into its `=>` target (negated, converted).
    fn copy_out(&mut self, src: &str, src_ty: TypeId, o: &Output) -> Result<(), Error> {
        let m = self.m;
        let mut v = src.to_string();
        if o.negated {
            v = self.op(Operation::Unary(UnOp::Not), vec![(v, src_ty)], src_ty)?;
        }
        let tt = o.target.ty;
        let differ = self.scalar(src_ty) != self.scalar(tt);
        if differ && self.scalar(src_ty).is_some() && self.scalar(tt).is_some() {
            v = self.op(Operation::Convert, vec![(v, src_ty)], tt)?;
        }
        let _ = m;
        let lv = self.place(&o.target, None)?;
        self.store_place(&o.target, &lv, &v, tt)
    }

    fn call_fb(
        &mut self,
        instance: &Place,
        fb: PouId,
        inputs: &[(VarId, Expr)],
        inouts: &[(VarId, Place)],
        outputs: &[Output],
    ) -> Result<(), Error> {
        let m = self.m;
        let p = fb;
        let fbp = &m.pous[p];
        let lv = self.place(instance, None)?;
        let ptr = self.new_temp(format!("{} *", names::pou_type_name(m, p)));
        self.line(format!("{ptr} = &{lv};"));
        for (v, e) in inputs {
            let var = fbp.var(*v);
            let val = self.expr(e)?;
            let dst = format!("{ptr}->{}", names::var_name(m, *v, var));
            self.assign_value(&dst, var.ty, &val)?;
        }
        for (v, pl) in inouts {
            let var = fbp.var(*v);
            let target = self.place(pl, None)?;
            self.line(format!(
                "{ptr}->{} = &{target};",
                names::var_name(m, *v, var)
            ));
        }
        self.call_line(format!("{}({ptr});", names::body_name(m, p)));
        self.call_check(p);
        for o in outputs {
            let var = fbp.var(o.var);
            let name = names::var_name(m, o.var, var);
            let src = if var.storage == Storage::Ref {
                format!("(*{ptr}->{name})")
            } else {
                format!("{ptr}->{name}")
            };
            let src = if self.is_string(var.ty).is_some() {
                format!("{src}.s")
            } else {
                src
            };
            self.copy_out(&src, var.ty, o)?;
        }
        Ok(())
    }
}

impl Emit for Gen<'_> {
    fn module(&self) -> &Module {
        self.m
    }

    fn temp(&mut self, ty: TypeId) -> String {
        self.define(ty);
        let c = names::type_name(self.m, ty);
        self.new_temp(c)
    }

    fn stmt(&mut self, s: String) {
        self.line(s);
    }

    fn fault_check(&mut self) {
        self.fault_return();
    }

    fn fail_if(&mut self, cond: &str, kind: &str) {
        // The condition is tested where its operands are (in registers),
        // not the fault flag after the fact.
        let site = self.f.site;
        let bail = self.bail();
        self.line(format!(
            "if ({cond}) {{ stc_fault({kind}, {site}U); {bail} }}"
        ));
    }

    fn site(&self) -> u32 {
        self.f.site
    }

    fn c_type(&self, ty: TypeId) -> String {
        names::type_name(self.m, ty)
    }
}

/// Whether a variable of a POU lives in the frame of its body function
/// and is set to its initial value there on entry: a function's
/// variables but its inputs and references (set by the caller), an FB's or
/// program's VAR_TEMPs.
fn in_frame(function: bool, v: &stc_ir::Var) -> bool {
    if function {
        !matches!(v.section, Section::Input | Section::InOut) && v.storage != Storage::Ref
    } else {
        v.storage == Storage::Frame
    }
}

/// The number of elements of an array (at least 1 for C).
fn array_count(dims: &[(i128, i128)]) -> u64 {
    dims.iter()
        .map(|(l, h)| (h - l + 1).max(0))
        .product::<i128>()
        .clamp(1, u32::MAX as i128) as u64
}

/// The `STC_FAULT_*` code of a fault kind (one numbering with the VM).
fn fault_code(k: FaultKind) -> u32 {
    u32::from(k.code())
}

/// A C string literal of ST text (bytes outside ASCII as octal escapes).
pub(crate) fn c_str(s: &str) -> String {
    let mut out = String::from("\"");
    for b in s.bytes() {
        match b {
            b'"' => out.push_str("\\\""),
            b'\\' => out.push_str("\\\\"),
            0x20..=0x7e => out.push(b as char),
            _ => {
                // Each escape ends its own literal (MISRA rule 4.1).
                let _ = write!(out, "\" \"\\{b:03o}\" \"");
            }
        }
    }
    out.push('"');
    out
}

/// A C string literal of raw bytes.
fn c_bytes(b: &[u8]) -> String {
    let mut out = String::from("\"");
    for &c in b {
        match c {
            b'"' => out.push_str("\\\""),
            b'\\' => out.push_str("\\\\"),
            b'?' => out.push_str("\\?"),
            0x20..=0x7e => out.push(c as char),
            _ => {
                let _ = write!(out, "\\{c:03o}");
            }
        }
    }
    out.push('"');
    out
}

/// The C object of a global (a located global is its process-image slot).
fn global_lvalue(m: &Module, g: GlobalId) -> String {
    match m.globals[g]
        .location
        .as_ref()
        .filter(|a| !a.is_incomplete())
    {
        Some(a) => names::io_name(a),
        None => names::global_name(m, g),
    }
}

/// The POUs whose body runs: programs (the harness calls them) and every
/// POU a used POU calls. A function block used only as the type of an
/// instance that is never called needs its struct and init function, not
/// its body.
fn called_pous(m: &Module, used: &IdVec<PouId, bool>) -> IdVec<PouId, bool> {
    let mut called: IdVec<PouId, bool> =
        m.pous.iter().map(|p| p.kind == PouKind::Program).collect();
    for (p, pou) in m.pous.iter_enumerated() {
        if used[p] {
            stc_ir::visit::calls(&pou.body, &mut |c| {
                if c.index() < called.len() {
                    called[c] = true;
                }
            });
        }
    }
    called
}

/// The function blocks and programs whose instances a value of type `t`
/// holds (not behind a reference), added to `out`.
fn type_pous(m: &Module, t: TypeId, out: &mut Vec<PouId>, seen: &mut FxHashSet<TypeId>) {
    if !seen.insert(t) {
        return;
    }
    match m.types.kind(t) {
        TypeKind::Fb(p) | TypeKind::Program(p) => out.push(*p),
        TypeKind::Array { elem, .. } => type_pous(m, *elem, out, seen),
        TypeKind::Struct { fields } => {
            for f in fields {
                type_pous(m, f.ty, out, seen);
            }
        }
        _ => {}
    }
}

/// The used POUs with instances: programs, and the blocks a global or a
/// variable of a used POU holds by value. Only they get an initialiser (a
/// base class reached only through references and its derived blocks, whose
/// initialisers set the inherited variables themselves, has none: an unused
/// static function is an error under `-Werror`).
fn instantiated_pous(m: &Module, used: &IdVec<PouId, bool>) -> IdVec<PouId, bool> {
    let mut out: Vec<PouId> = m
        .pous
        .ids()
        .filter(|&p| m.pous[p].kind == PouKind::Program)
        .collect();
    let mut seen = FxHashSet::default();
    for g in &m.globals {
        type_pous(m, g.ty, &mut out, &mut seen);
    }
    for (p, pou) in m.pous.iter_enumerated() {
        if used[p] {
            // (An in-out or external refers to an instance held elsewhere.)
            for v in pou
                .vars
                .iter()
                .filter(|v| v.storage != stc_ir::Storage::Ref)
            {
                type_pous(m, v.ty, &mut out, &mut seen);
            }
        }
    }
    let mut inst: IdVec<PouId, bool> = m.pous.iter().map(|_| false).collect();
    for p in out {
        inst[p] = true;
    }
    inst
}

/// The POUs a program uses: every PROGRAM, and what their variables,
/// the globals and their bodies need (instances and calls), transitively.
fn used_pous(m: &Module) -> IdVec<PouId, bool> {
    let mut used: IdVec<PouId, bool> = m.pous.iter().map(|_| false).collect();
    let mut work: Vec<PouId> = m
        .pous
        .ids()
        .filter(|&p| m.pous[p].kind == PouKind::Program)
        .collect();
    let mut seen_types: FxHashSet<TypeId> = FxHashSet::default();
    for g in &m.globals {
        type_pous(m, g.ty, &mut work, &mut seen_types);
    }
    while let Some(p) = work.pop() {
        if used[p] {
            continue;
        }
        used[p] = true;
        let pou = &m.pous[p];
        for v in &pou.vars {
            type_pous(m, v.ty, &mut work, &mut seen_types);
        }
        stc_ir::visit::calls(&pou.body, &mut |c| work.push(c));
    }
    used
}

/// Whether the VM checks this place's element after the value: a variable
/// held directly (not by reference) with one one-dimensional index.
fn single_index(p: &Place) -> bool {
    let indexes: Vec<&Vec<(Expr, i128, i128)>> = p
        .proj
        .iter()
        .filter_map(|pr| match pr {
            Proj::Index(i) => Some(i),
            _ => None,
        })
        .collect();
    let direct = match &p.root {
        Root::Var(_) => true,
        Root::Global(_) | Root::Direct(_) | Root::This => true,
        Root::Deref(_) => false,
    };
    direct && indexes.len() == 1 && indexes[0].len() == 1
}

fn uses_continue(stmts: &[Stmt]) -> bool {
    stmts.iter().any(|s| match &s.kind {
        StmtKind::Continue => true,
        StmtKind::If {
            then_body,
            else_body,
            ..
        } => uses_continue(then_body) || uses_continue(else_body),
        StmtKind::Switch { arms, default, .. } => {
            arms.iter().any(|a| uses_continue(&a.body)) || uses_continue(default)
        }
        // A nested loop's CONTINUE is its own.
        _ => false,
    })
}
