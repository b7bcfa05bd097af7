//! Building the program model and its canonical data area from a module.

use rustc_hash::FxHashMap;
use stc_diagnostics::{Code, Diagnostic, Span};
use stc_sema::{GlobalId, InitValue, PouId, Section, TypeId, TypeKind, VarId};
use stc_syntax::ast::PouKind as AstPouKind;
use stc_syntax::literal::{AddrSize, DirectAddress};
use stc_syntax::token::ElemType;
use stc_values::Value;

use super::repr::{write_scalar, write_string};
use super::*;
use crate::layout::{Layouts, MAX_SIZE};
use crate::{Module, Place, Root, Storage};
use stc_sema::idx::Idx;

/// The bytes at address 0 left unused in the data area of a program that
/// has references, so that 0 is the address of no variable: NULL.
pub const NULL_GUARD: u32 = 8;

/// Why no model was built.
#[derive(Clone, Debug, PartialEq)]
pub enum ModelError {
    /// Errors in the program (E0901: the data area is too large for the
    /// memory model), at their declarations.
    Diagnostics(Vec<Diagnostic>),
    /// A bug: the module broke an invariant of the IR.
    Internal(String),
}

impl std::fmt::Display for ModelError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            ModelError::Diagnostics(d) => match d.first() {
                Some(first) => write!(f, "{}", first.message),
                None => write!(f, "the program does not fit the memory model"),
            },
            ModelError::Internal(what) => write!(f, "internal error: {what}"),
        }
    }
}

fn internal(what: impl Into<String>) -> ModelError {
    ModelError::Internal(what.into())
}

/// E0901 at `span`: `what` needs `size` bytes.
pub(crate) fn too_large(span: Span, what: String, size: u64) -> ModelError {
    ModelError::Diagnostics(vec![Diagnostic::new(
        Code::E0901,
        span,
        format!("{what} needs {size} bytes; the limit is {MAX_SIZE} bytes (1 GiB)"),
    )
    .with_label("too large for the memory model")])
}

/// The model with its canonical data area: the initial bytes of the
/// process image slots, globals and program instances, every reference
/// bound (a reference is the 4-byte little-endian address of its target).
#[derive(Clone, Debug, PartialEq)]
pub struct Data {
    pub model: Model,
    pub init: Vec<u8>,
    /// The model's reference of every type of the module it has (every
    /// type of a variable, field, global or connection; a function block
    /// or program type is its POU's instance type).
    pub type_refs: FxHashMap<TypeId, TypeRef>,
    /// For each model type, the type of the module it stands for (`None`
    /// for an instance type, which stands for its POU).
    pub type_ids: Vec<Option<TypeId>>,
}

/// The model and its data area of a module (see the module documentation).
pub fn build(m: &Module, l: &Layouts) -> Result<Data, ModelError> {
    Ok(Builder::new(m, l)?.finish())
}

/// The model being built, kept by a back end that needs more of the data
/// area's machinery while it compiles bodies (initial bytes of frames,
/// constants in memory representation, the addresses of globals).
pub struct Builder<'a> {
    m: &'a Module,
    l: &'a Layouts,
    model: Model,
    type_map: FxHashMap<TypeId, TypeRef>,
    data: Vec<u8>,
    io_map: FxHashMap<DirectAddress, u32>,
    /// The private variables of unbound VAR_EXTERNALs, by (POU, variable).
    private_externals: FxHashMap<(PouId, VarId), u32>,
    global_off: Vec<u32>,
    /// The first error met where it could not be returned at once (data
    /// allocated while initialising): no model is given after one.
    failed: Option<ModelError>,
}

impl<'a> Builder<'a> {
    /// Lays out the whole data area and builds the model.
    pub fn new(m: &'a Module, l: &'a Layouts) -> Result<Builder<'a>, ModelError> {
        let mut b = Builder {
            m,
            l,
            model: Model::default(),
            type_map: FxHashMap::default(),
            data: Vec::new(),
            io_map: FxHashMap::default(),
            private_externals: FxHashMap::default(),
            global_off: Vec::new(),
            failed: None,
        };
        b.run()?;
        Ok(b)
    }

    fn run(&mut self) -> Result<(), ModelError> {
        // POU descriptors first (instances refer to them by index).
        if self.l.pous.len() != self.m.pous.len() {
            return Err(internal("a layout for another module"));
        }
        for (i, p) in self.m.pous.iter_enumerated() {
            let kind = match p.kind {
                AstPouKind::Function => PouKind::Function,
                AstPouKind::FunctionBlock => PouKind::FunctionBlock,
                AstPouKind::Program => PouKind::Program,
            };
            self.model.pous.push(PouDesc {
                name: self.m.spelled(p.name, p.name_span).to_string(),
                kind,
                instance_size: self.l.pous[i].instance.size,
                vars: Vec::new(),
                instance_type: 0,
            });
        }
        for i in 0..self.m.pous.len() {
            let t = self.model.types.len() as u32;
            self.model.types.push(TypeDesc::Instance { pou: i as u32 });
            self.model.pous[i].instance_type = t;
        }
        // Data: process image, globals, program instances. A program with
        // references keeps address 0 free, so no variable has the address
        // of NULL (the first 8 bytes of its data area are never used).
        let m = self.m;
        let has_refs =
            (0..m.types.len() as u32).any(|t| matches!(m.types.kind(TypeId(t)), TypeKind::Ref(_)));
        if has_refs {
            self.data.resize(NULL_GUARD as usize, 0);
        }
        self.collect_io();
        // Located variables' initial values, once per slot.
        let m = self.m;
        for (a, t, init) in m.located_inits() {
            let off = self.io_slot(&a, t, Span::default());
            self.write_init(t, off, init, None);
        }
        for (gi, g) in m.globals.iter_enumerated() {
            let lay = self.l.of(g.ty);
            let off = match g.location.as_ref().filter(|a| !a.is_incomplete()) {
                Some(a) => self.io_slot(a, g.ty, g.span),
                None => {
                    let what = format!("global `{}`", m.spelled(g.name, g.span));
                    let off = self.alloc_data(lay.size, lay.align, g.span, &what)?;
                    self.write_init(g.ty, off, g.init.as_ref(), None);
                    off
                }
            };
            self.global_off.push(off);
            let ty = self.ty_ref(g.ty);
            let config = m.config_of_global(gi).map(|c| c as u32);
            self.model.globals.push(GlobalDesc {
                name: m.spelled(g.name, g.span).to_string(),
                ty,
                offset: off,
                config,
                location: g.location.clone(),
                constant: g.constant,
                retain: g.retain,
            });
        }
        for (ci, c) in m.configs.iter().enumerate() {
            let mut resources = Vec::new();
            for (ri, r) in c.resources.iter().enumerate() {
                let tasks = r
                    .tasks
                    .iter()
                    .map(|t| TaskDesc {
                        name: m.spelled(t.name, t.name_span).to_string(),
                        interval_ns: t.interval,
                        priority: t.priority,
                        single: t
                            .single
                            .as_ref()
                            .and_then(|s| self.source(s, m.types_bool(), t.span)),
                    })
                    .collect();
                let mut programs = Vec::new();
                for inst in &r.programs {
                    programs.push(self.program_instance(
                        m.spelled(inst.name, inst.name_span).to_string(),
                        inst.pou,
                        inst.task.map(|t| t as u32),
                        Some((ci, ri)),
                        inst,
                    )?);
                }
                resources.push(ResourceDesc {
                    name: r.name.map(|n| m.name(n).to_string()),
                    tasks,
                    programs,
                });
            }
            self.model.configs.push(ConfigDesc {
                name: m.name(c.name).to_string(),
                resources,
            });
        }
        for (i, p) in m.pous.iter().enumerate() {
            if p.kind == AstPouKind::Program {
                let off = self.instance(PouId(i as u32), None, p.name_span)?;
                self.model.programs.push(ProgramInst {
                    name: m.name(p.name).to_string(),
                    pou: i as u32,
                    offset: off,
                    task: None,
                    inputs: Vec::new(),
                    outputs: Vec::new(),
                });
            }
        }
        // Variable descriptors.
        for i in 0..m.pous.len() {
            self.pou_vars(PouId(i as u32));
        }
        match self.failed.take() {
            Some(e) => Err(e),
            None => Ok(()),
        }
    }

    /// The model built so far (all of it once [`Builder::new`] returned).
    pub fn model(&self) -> &Model {
        &self.model
    }

    /// The model, for an engine to fill in its own part (the frame
    /// offsets of variables that live in a call's frame).
    pub fn model_mut(&mut self) -> &mut Model {
        &mut self.model
    }

    /// The size of the data area.
    pub fn data_size(&self) -> u32 {
        self.data.len() as u32
    }

    /// The address of global `g`.
    pub fn global_offset(&self, g: GlobalId) -> Option<u32> {
        self.global_off.get(g.index()).copied()
    }

    /// The address of the process image slot of a direct address.
    pub fn io_offset(&self, a: &DirectAddress) -> Option<u32> {
        self.io_map.get(a).copied()
    }

    /// The model's reference of a type of the module, if the model has it
    /// (every type of a variable, field or connection does).
    pub fn type_ref(&self, t: TypeId) -> Option<TypeRef> {
        self.type_map.get(&t).copied()
    }

    /// The initial bytes of a value of type `t` with initial value `init`
    /// (its default without one), for a variable outside the data area
    /// (in a frame). An error where initialising it would need data the
    /// area does not have yet (a bug: the model has it all).
    pub fn init_bytes(
        &mut self,
        t: TypeId,
        init: Option<&InitValue>,
    ) -> Result<Vec<u8>, ModelError> {
        let base = self.data.len();
        let size = self.l.of(t).size as usize;
        self.data.resize(base + size, 0);
        self.write_init(t, base as u32, init, None);
        if self.data.len() != base + size {
            return Err(internal("data allocated while initialising a frame"));
        }
        let bytes = self.data[base..].to_vec();
        self.data.truncate(base);
        match self.failed.take() {
            Some(e) => Err(e),
            None => Ok(bytes),
        }
    }

    /// The model and its data area.
    pub fn finish(self) -> Data {
        let mut type_ids = vec![None; self.model.types.len()];
        for (&t, &r) in &self.type_map {
            if !matches!(
                self.model.types.get(r as usize),
                Some(TypeDesc::Instance { .. })
            ) {
                if let Some(slot) = type_ids.get_mut(r as usize) {
                    *slot = Some(t);
                }
            }
        }
        Data {
            model: self.model,
            init: self.data,
            type_refs: self.type_map,
            type_ids,
        }
    }

    fn ty_ref(&mut self, t: TypeId) -> TypeRef {
        if let Some(&r) = self.type_map.get(&t) {
            return r;
        }
        let desc = match self.m.types.kind(t).clone() {
            // A reference's address is an engine's own: the model shows it
            // as an opaque value with no member (`{}` in reports), the same
            // on every engine.
            TypeKind::Ref(_) | TypeKind::Ptr(_) => TypeDesc::Struct {
                name: Some(ref_name(self.m, t)),
                fields: Vec::new(),
            },
            TypeKind::Elem(e) => TypeDesc::Scalar(e),
            TypeKind::Subrange { base, lo, hi } => TypeDesc::Subrange { base, lo, hi },
            TypeKind::String { wide, len } => TypeDesc::String { wide, cap: len },
            TypeKind::Enum { values, base } => TypeDesc::Enum {
                name: self.m.type_name(t).unwrap_or_default().to_string(),
                base,
                values: values
                    .iter()
                    .map(|v| (self.m.spelled(v.name, v.span).to_string(), v.value))
                    .collect(),
            },
            TypeKind::Array { dims, elem } => {
                let e = self.ty_ref(elem);
                TypeDesc::Array {
                    elem: e,
                    dims: dims.iter().map(|(l, h)| (*l as i64, *h as i64)).collect(),
                    stride: self.l.stride(&self.m.types, t),
                }
            }
            TypeKind::Struct { fields } => {
                let mut fs = Vec::new();
                for (i, f) in fields.iter().enumerate() {
                    let ft = self.ty_ref(f.ty);
                    fs.push(FieldDesc {
                        name: self.m.spelled(f.name, f.span).to_string(),
                        ty: ft,
                        offset: self.l.field_offset(t, i as u32),
                    });
                }
                TypeDesc::Struct {
                    name: self.m.type_name(t).map(str::to_string),
                    fields: fs,
                }
            }
            TypeKind::Fb(p) | TypeKind::Program(p) => {
                let r = self.model.pous[p.index()].instance_type;
                self.type_map.insert(t, r);
                return r;
            }
            TypeKind::Error | TypeKind::Void => TypeDesc::Scalar(ElemType::Bool),
        };
        let r = self.model.types.len() as u32;
        self.model.types.push(desc);
        self.type_map.insert(t, r);
        r
    }

    // ----- data area -----------------------------------------------------------

    /// Places `size` bytes in the data area for `what`, declared at `span`
    /// (reported with E0901 when the data area would pass [`MAX_SIZE`]).
    fn alloc_data(
        &mut self,
        size: u32,
        align: u32,
        span: Span,
        what: &str,
    ) -> Result<u32, ModelError> {
        let a = u64::from(align.max(1));
        let off = (self.data.len() as u64).div_ceil(a) * a;
        let end = off + u64::from(size);
        if end > MAX_SIZE {
            return Err(too_large(
                span,
                format!("the data area (globals, program instances, process image) up to {what}"),
                end,
            ));
        }
        self.data.resize(end as usize, 0);
        Ok(off as u32)
    }

    /// Keeps the first error met where it cannot be returned at once.
    fn defer(&mut self, e: ModelError) {
        self.failed.get_or_insert(e);
    }

    fn collect_io(&mut self) {
        let m = self.m;
        let mut found: Vec<(DirectAddress, TypeId, Span)> = Vec::new();
        for g in &m.globals {
            if let Some(a) = g.location.as_ref().filter(|a| !a.is_incomplete()) {
                found.push((a.clone(), g.ty, g.span));
            }
        }
        for p in &m.pous {
            for v in &p.vars {
                if let Some(a) = v.location.as_ref().filter(|a| !a.is_incomplete()) {
                    found.push((a.clone(), v.ty, v.span));
                }
            }
            crate::visit::places(&p.body, &mut |pl: &Place| {
                if let Root::Direct(a) = &pl.root {
                    found.push((a.clone(), m.addr_type(a), p.name_span));
                }
            });
        }
        for (a, t, span) in found {
            self.io_slot(&a, t, span);
        }
    }

    /// The data offset of a direct address's slot (allocated on first use,
    /// by a declaration or use at `span`).
    fn io_slot(&mut self, a: &DirectAddress, t: TypeId, span: Span) -> u32 {
        if let Some(&off) = self.io_map.get(a) {
            return off;
        }
        let size = match a.size {
            AddrSize::Bit => 1,
            s => s.bits() / 8,
        };
        let what = format!("the process image slot {a}");
        let off = match self.alloc_data(size.max(self.l.of(t).size), size, span, &what) {
            Ok(off) => off,
            Err(e) => {
                self.defer(e);
                0
            }
        };
        let ty = self.ty_ref(t);
        self.model.io.push(IoSlot {
            address: a.clone(),
            offset: off,
            ty,
        });
        self.io_map.insert(a.clone(), off);
        off
    }

    /// Writes the initial value of a variable of type `t` at data offset `off`.
    fn write_init(
        &mut self,
        t: TypeId,
        off: u32,
        init: Option<&InitValue>,
        ctx: Option<(usize, usize)>,
    ) {
        match self.m.types.kind(t).clone() {
            // A reference starts as NULL: the zero bytes already there.
            TypeKind::Ref(_) | TypeKind::Ptr(_) => {}
            TypeKind::Elem(_)
            | TypeKind::Subrange { .. }
            | TypeKind::Enum { .. }
            | TypeKind::String { .. } => {
                let v = match init {
                    Some(InitValue::Scalar(v)) => Some(v.clone()),
                    _ => match self.m.types.kind(t) {
                        TypeKind::Subrange { lo, .. } => Some(Value::Int(*lo)),
                        TypeKind::Enum { values, .. } => {
                            values.first().map(|v| Value::Int(v.value))
                        }
                        _ => None,
                    },
                };
                if let Some(v) = v {
                    let bytes = self.value_bytes(t, &v);
                    let o = off as usize;
                    if let Some(dst) = self.data.get_mut(o..o + bytes.len()) {
                        dst.copy_from_slice(&bytes);
                    }
                } else if let Some(e) = self.m.types.scalar(t) {
                    if !matches!(e, ElemType::String | ElemType::Wstring) {
                        let v = stc_values::default_value(e);
                        let bytes = self.value_bytes(t, &v);
                        let o = off as usize;
                        if let Some(dst) = self.data.get_mut(o..o + bytes.len()) {
                            dst.copy_from_slice(&bytes);
                        }
                    }
                }
            }
            TypeKind::Array { elem, .. } => {
                let stride = self.l.stride(&self.m.types, t);
                let count = self.l.of(t).size.checked_div(stride).unwrap_or(0);
                let list = match init {
                    Some(InitValue::Array(l)) => l.as_slice(),
                    _ => &[],
                };
                for i in 0..count {
                    let v = list.get(i as usize).and_then(|v| v.as_ref());
                    self.write_init(elem, off + i * stride, v, ctx);
                }
            }
            TypeKind::Struct { fields } => {
                for (i, f) in fields.iter().enumerate() {
                    let given = match init {
                        Some(InitValue::Struct(l)) => {
                            l.iter().find(|(n, _)| *n == f.name).map(|(_, v)| v)
                        }
                        _ => None,
                    };
                    let v = given.or(f.init.as_ref()).cloned();
                    let fo = off + self.l.field_offset(t, i as u32);
                    self.write_init(f.ty, fo, v.as_ref(), ctx);
                }
            }
            TypeKind::Fb(p) | TypeKind::Program(p) => {
                let overrides = match init {
                    Some(InitValue::Struct(l)) => l.clone(),
                    _ => Vec::new(),
                };
                self.init_instance(p, off, ctx, &overrides);
            }
            TypeKind::Error | TypeKind::Void => {}
        }
    }

    /// Initialises an instance of a POU at `off`: variables, nested
    /// instances, and references bound to globals and process-image slots.
    fn init_instance(
        &mut self,
        p: PouId,
        off: u32,
        ctx: Option<(usize, usize)>,
        overrides: &[(stc_syntax::Symbol, InitValue)],
    ) {
        let m = self.m;
        let pou = &m.pous[p];
        for (i, v) in pou.vars.iter_enumerated() {
            if self.l.pous[p].in_frame[i] {
                continue;
            }
            let voff = off + self.l.pous[p].offsets[i];
            if v.storage == Storage::Ref {
                let target = if let Some(a) = v.location.as_ref().filter(|a| !a.is_incomplete()) {
                    Some(self.io_slot(a, v.ty, v.span))
                } else if v.section == Section::External {
                    let bound = m.bind_global(v.name, v.ty, ctx);
                    Some(
                        match bound.and_then(|g| self.global_off.get(g.index()).copied()) {
                            Some(t) => t,
                            None => self.private_external(p, i, v.ty),
                        },
                    )
                } else {
                    None
                };
                if let Some(t) = target {
                    let o = voff as usize;
                    if let Some(dst) = self.data.get_mut(o..o + 4) {
                        dst.copy_from_slice(&t.to_le_bytes());
                    }
                }
                continue;
            }
            let init = overrides
                .iter()
                .find(|(n, _)| *n == v.name)
                .map(|(_, v)| v.clone())
                .or_else(|| v.init.clone());
            self.write_init(v.ty, voff, init.as_ref(), ctx);
        }
    }

    /// The global a VAR_EXTERNAL named `name` refers to, in a configuration
    /// (and resource) or among the top-level globals.
    /// The variable a VAR_EXTERNAL gets when no global of its name and type
    /// exists where it runs (a program run on its own, `--program`, whose
    /// globals are in a configuration): its own, at the type's default, one
    /// per POU and variable, never another variable's memory.
    fn private_external(&mut self, p: PouId, v: VarId, t: TypeId) -> u32 {
        if let Some(&off) = self.private_externals.get(&(p, v)) {
            return off;
        }
        let lay = self.l.of(t);
        let var = &self.m.pous[p].vars[v];
        let what = format!(
            "the variable of VAR_EXTERNAL `{}` (no global binds it)",
            self.m.spelled(var.name, var.span)
        );
        let off = match self.alloc_data(lay.size, lay.align, var.span, &what) {
            Ok(off) => off,
            Err(e) => {
                self.defer(e);
                return 0;
            }
        };
        self.write_init(t, off, None, None);
        self.private_externals.insert((p, v), off);
        off
    }

    fn instance(
        &mut self,
        p: PouId,
        ctx: Option<(usize, usize)>,
        span: Span,
    ) -> Result<u32, ModelError> {
        let lay = self.l.pous[p].instance;
        let pou = &self.m.pous[p];
        let what = format!(
            "the instance of program `{}`",
            self.m.spelled(pou.name, pou.name_span)
        );
        let off = self.alloc_data(lay.size, lay.align, span, &what)?;
        self.init_instance(p, off, ctx, &[]);
        Ok(off)
    }

    fn program_instance(
        &mut self,
        name: String,
        p: PouId,
        task: Option<u32>,
        ctx: Option<(usize, usize)>,
        def: &stc_sema::ProgramInstDef,
    ) -> Result<ProgramInst, ModelError> {
        let off = self.instance(p, ctx, def.name_span)?;
        let mut inputs = Vec::new();
        let mut outputs = Vec::new();
        for (v, src) in &def.inputs {
            let var = self.m.pous[p].var(*v);
            let ty = self.ty_ref(var.ty);
            if let Some(s) = self.source(src, var.ty, def.name_span) {
                inputs.push((self.l.var_offset(p, *v), ty, s));
            }
        }
        for (v, dst) in &def.outputs {
            let var = self.m.pous[p].var(*v);
            let ty = self.ty_ref(var.ty);
            if let Some(s) = self.source(dst, var.ty, def.name_span) {
                outputs.push((self.l.var_offset(p, *v), ty, s));
            }
        }
        Ok(ProgramInst {
            name,
            pou: p.0,
            offset: off,
            task,
            inputs,
            outputs,
        })
    }

    /// A configuration data reference (written at `span`) as an address;
    /// `None` only after an error kept with [`Builder::defer`].
    fn source(&mut self, r: &stc_sema::DataRef, ty: TypeId, span: Span) -> Option<Source> {
        match r {
            stc_sema::DataRef::Global(g) => {
                let t = self.m.globals[*g].ty;
                let ty = self.ty_ref(t);
                let Some(&offset) = self.global_off.get(g.0 as usize) else {
                    self.defer(internal("a connection to a global not placed yet"));
                    return None;
                };
                Some(Source::Addr { offset, ty })
            }
            stc_sema::DataRef::Direct(a) => {
                let off = self.io_slot(a, self.m.addr_type(a), span);
                let t = self.m.addr_type(a);
                Some(Source::Addr {
                    offset: off,
                    ty: self.ty_ref(t),
                })
            }
            stc_sema::DataRef::Const(v) => {
                let bytes = self.value_bytes(ty, v);
                let off = match self.alloc_data(
                    bytes.len() as u32,
                    8,
                    span,
                    "a constant connected to a program",
                ) {
                    Ok(off) => off,
                    Err(e) => {
                        self.defer(e);
                        return None;
                    }
                };
                self.data[off as usize..off as usize + bytes.len()].copy_from_slice(&bytes);
                Some(Source::Addr {
                    offset: off,
                    ty: self.ty_ref(ty),
                })
            }
        }
    }

    /// The bytes of a value of type `t`, as stored in memory.
    pub fn value_bytes(&self, t: TypeId, v: &Value) -> Vec<u8> {
        let size = self.l.of(t).size.max(1);
        let mut buf = vec![0u8; size as usize];
        match self.m.types.kind(t) {
            TypeKind::String { wide, len } => {
                let v = match (wide, v) {
                    (false, Value::WStr(_)) | (true, Value::Str(_)) => stc_values::convert(
                        if *wide {
                            ElemType::String
                        } else {
                            ElemType::Wstring
                        },
                        if *wide {
                            ElemType::Wstring
                        } else {
                            ElemType::String
                        },
                        v,
                    )
                    .unwrap_or_else(|_| v.clone()),
                    _ => v.clone(),
                };
                write_string(&mut buf, 0, *wide, *len, &v);
            }
            _ => {
                if let Some(e) = self.m.types.scalar(t) {
                    write_scalar(&mut buf, 0, e, v);
                }
            }
        }
        buf
    }

    fn pou_vars(&mut self, p: PouId) {
        let m = self.m;
        let pou = &m.pous[p];
        let mut vars = Vec::new();
        for (i, v) in pou.vars.iter_enumerated() {
            let ty = self.ty_ref(v.ty);
            let kind = match (v.hidden, v.section) {
                (Some(_), _) => VarKind::Hidden,
                (_, Section::Input) => VarKind::Input,
                (_, Section::Output) => VarKind::Output,
                (_, Section::InOut) => VarKind::InOut,
                (_, Section::Var) => VarKind::Var,
                (_, Section::Temp) => VarKind::Temp,
                (_, Section::External) => VarKind::External,
                (_, Section::Global) => VarKind::Global,
                (_, Section::Result) => VarKind::Result,
            };
            let in_frame = self.l.pous[p].in_frame[i];
            vars.push(VarDesc {
                name: self.m.spelled(v.name, v.span).to_string(),
                ty,
                kind,
                offset: if in_frame {
                    0
                } else {
                    self.l.pous[p].offsets[i]
                },
                in_frame,
                is_ref: v.storage == Storage::Ref,
                location: v.location.clone(),
                constant: v.constant,
                retain: v.retain,
            });
        }
        self.model.pous[p.index()].vars = vars;
    }
}

/// The name a reference type is shown with in the model (`REF_TO INT`).
fn ref_name(m: &Module, t: TypeId) -> String {
    match m.types.kind(t) {
        TypeKind::Ref(x) if *x == TypeId::VOID => "NULL".into(),
        TypeKind::Ref(x) => {
            let inner = match m.type_name(*x) {
                Some(n) => n.to_string(),
                None => match m.types.kind(*x) {
                    TypeKind::Elem(e) => e.name().to_string(),
                    TypeKind::Ref(_) => ref_name(m, *x),
                    TypeKind::String { wide: false, .. } => "STRING".into(),
                    TypeKind::String { wide: true, .. } => "WSTRING".into(),
                    _ => "?".into(),
                },
            };
            format!("REF_TO {inner}")
        }
        _ => String::new(),
    }
}
