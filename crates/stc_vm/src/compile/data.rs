//! The program model's side of compilation: the image's type descriptors,
//! the data area (process-image slots, globals, program instances and
//! their initial bytes, the references bound in them) and the variable
//! descriptors and frames of each POU.

use super::*;

impl Compiler<'_> {
    // ----- types -------------------------------------------------------------

    pub(super) fn ty_ref(&mut self, t: TypeId) -> TypeRef {
        if let Some(&r) = self.type_map.get(&t) {
            return r;
        }
        let desc = match self.m.types.kind(t).clone() {
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
                let r = self.pous[p.0 as usize].instance_type;
                self.type_map.insert(t, r);
                return r;
            }
            TypeKind::Error | TypeKind::Void => TypeDesc::Scalar(ElemType::Bool),
        };
        let r = self.types.len() as u32;
        self.types.push(desc);
        self.type_map.insert(t, r);
        r
    }

    pub(super) fn scalar(&self, t: TypeId) -> Option<ElemType> {
        self.m.types.scalar(t)
    }

    pub(super) fn num(&self, t: TypeId) -> Option<Num> {
        self.scalar(t).and_then(Num::of)
    }

    pub(super) fn size_of(&self, t: TypeId) -> u32 {
        self.l.of(t).size
    }

    // ----- data area -----------------------------------------------------------

    /// Places `size` bytes in the data area for `what`, declared at `span`
    /// (reported with E0901 when the data area would pass [`MAX_SIZE`]).
    pub(super) fn alloc_data(
        &mut self,
        size: u32,
        align: u32,
        span: Span,
        what: &str,
    ) -> Result<u32, CompileError> {
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
    pub(super) fn defer(&mut self, e: CompileError) {
        self.failed.get_or_insert(e);
    }

    pub(super) fn collect_io(&mut self) {
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
            stc_ir::visit::places(&p.body, &mut |pl: &Place| {
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
    pub(super) fn io_slot(&mut self, a: &DirectAddress, t: TypeId, span: Span) -> u32 {
        if let Some(&off) = self.io_map.get(a) {
            return off;
        }
        let size = match a.size {
            AddrSize::Bit => 1,
            s => s.bits() / 8,
        };
        let what = format!("the process image slot {a}");
        let off = match self.alloc_data(size.max(self.size_of(t)), size, span, &what) {
            Ok(off) => off,
            Err(e) => {
                self.defer(e);
                0
            }
        };
        let ty = self.ty_ref(t);
        self.io.push(IoSlot {
            address: a.clone(),
            offset: off,
            ty,
        });
        self.io_map.insert(a.clone(), off);
        off
    }

    /// Writes the initial value of a variable of type `t` at data offset `off`.
    pub(super) fn write_init(
        &mut self,
        t: TypeId,
        off: u32,
        init: Option<&InitValue>,
        ctx: Option<(usize, usize)>,
    ) {
        match self.m.types.kind(t).clone() {
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
                } else if let Some(e) = self.scalar(t) {
                    if Num::of(e).is_some() {
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
                let count = self.size_of(t).checked_div(stride).unwrap_or(0);
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
    pub(super) fn init_instance(
        &mut self,
        p: PouId,
        off: u32,
        ctx: Option<(usize, usize)>,
        overrides: &[(stc_syntax::Symbol, InitValue)],
    ) {
        let m = self.m;
        let pou = &m.pous[p.0 as usize];
        for (i, v) in pou.vars.iter().enumerate() {
            if self.l.pous[p.0 as usize].in_frame[i] {
                continue;
            }
            let voff = off + self.l.pous[p.0 as usize].offsets[i];
            if v.storage == Storage::Ref {
                let target = if let Some(a) = v.location.as_ref().filter(|a| !a.is_incomplete()) {
                    Some(self.io_slot(a, v.ty, v.span))
                } else if v.section == Section::External {
                    let bound = m.bind_global(v.name, v.ty, ctx);
                    Some(match bound.and_then(|g| self.global_off.get(g).copied()) {
                        Some(t) => t,
                        None => self.private_external(p, i, v.ty),
                    })
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
    pub(super) fn private_external(&mut self, p: PouId, v: usize, t: TypeId) -> u32 {
        if let Some(&off) = self.private_externals.get(&(p.0, v)) {
            return off;
        }
        let lay = self.l.of(t);
        let var = &self.m.pous[p.0 as usize].vars[v];
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
        self.private_externals.insert((p.0, v), off);
        off
    }

    pub(super) fn instance(
        &mut self,
        p: PouId,
        ctx: Option<(usize, usize)>,
        span: Span,
    ) -> Result<u32, CompileError> {
        let lay = self.l.pous[p.0 as usize].instance;
        let pou = &self.m.pous[p.0 as usize];
        let what = format!(
            "the instance of program `{}`",
            self.m.spelled(pou.name, pou.name_span)
        );
        let off = self.alloc_data(lay.size, lay.align, span, &what)?;
        self.init_instance(p, off, ctx, &[]);
        Ok(off)
    }

    pub(super) fn program_instance(
        &mut self,
        name: String,
        p: PouId,
        task: Option<u32>,
        ctx: Option<(usize, usize)>,
        def: &stc_sema::ProgramInstDef,
    ) -> Result<ProgramInst, CompileError> {
        let off = self.instance(p, ctx, def.name_span)?;
        let mut inputs = Vec::new();
        let mut outputs = Vec::new();
        for (v, src) in &def.inputs {
            let var = self.m.pous[p.0 as usize].var(*v);
            let ty = self.ty_ref(var.ty);
            if let Some(s) = self.source(src, var.ty, def.name_span) {
                inputs.push((self.l.var_offset(p, *v), ty, s));
            }
        }
        for (v, dst) in &def.outputs {
            let var = self.m.pous[p.0 as usize].var(*v);
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
    /// `None` only after an error kept with [`Compiler::defer`].
    pub(super) fn source(
        &mut self,
        r: &stc_sema::DataRef,
        ty: TypeId,
        span: Span,
    ) -> Option<Source> {
        match r {
            stc_sema::DataRef::Global(g) => {
                let t = self.m.globals[g.0 as usize].ty;
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
    pub(super) fn value_bytes(&self, t: TypeId, v: &Value) -> Vec<u8> {
        let size = self.size_of(t).max(1);
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
                if let Some(e) = self.scalar(t) {
                    write_scalar(&mut buf, 0, e, v);
                }
            }
        }
        buf
    }

    // ----- POU variables and frames -------------------------------------------

    pub(super) fn pou_vars(&mut self, p: PouId) {
        let m = self.m;
        let pou = &m.pous[p.0 as usize];
        let mut vars = Vec::new();
        for (i, v) in pou.vars.iter().enumerate() {
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
            let in_frame = self.l.pous[p.0 as usize].in_frame[i];
            vars.push(VarDesc {
                name: self.m.spelled(v.name, v.span).to_string(),
                ty,
                kind,
                offset: if in_frame {
                    0
                } else {
                    self.l.pous[p.0 as usize].offsets[i]
                },
                in_frame,
                is_ref: v.storage == Storage::Ref,
                location: v.location.clone(),
                constant: v.constant,
            });
        }
        self.pous[p.0 as usize].vars = vars;
    }

    /// POUs in an order where every callee comes before its callers.
    pub(super) fn callee_order(&self) -> Vec<PouId> {
        let n = self.m.pous.len();
        let mut deps: Vec<Vec<usize>> = vec![Vec::new(); n];
        for (i, p) in self.m.pous.iter().enumerate() {
            stc_ir::visit::calls(&p.body, &mut |c| deps[i].push(c.0 as usize));
        }
        let mut order = Vec::with_capacity(n);
        let mut state = vec![0u8; n];
        for start in 0..n {
            if state[start] != 0 {
                continue;
            }
            let mut stack = vec![(start, 0usize)];
            state[start] = 1;
            while let Some(&mut (v, ref mut i)) = stack.last_mut() {
                if *i < deps[v].len() {
                    let w = deps[v][*i];
                    *i += 1;
                    if state[w] == 0 {
                        state[w] = 1;
                        stack.push((w, 0));
                    }
                } else {
                    state[v] = 2;
                    order.push(PouId(v as u32));
                    stack.pop();
                }
            }
        }
        order
    }

    /// The deepest chain of frames any program can build.
    pub(super) fn stack_need(&self) -> u32 {
        // Frames nest inside their caller's frame (a call reserves its
        // callee's frame among its temporaries), so a program's own frame
        // size already covers its whole call tree.
        self.pous.iter().map(|p| p.frame_size).max().unwrap_or(0) + 64
    }

    pub(super) fn compile_pou(&mut self, p: PouId) -> Result<(), CompileError> {
        let m = self.m;
        let pou = &m.pous[p.0 as usize];
        self.cur = p;
        self.frame = Frame::default();
        let function = pou.kind == AstPouKind::Function;
        // Frame variables: a function's inputs and in-outs first (the caller
        // writes them, the frame template starts after them), then the rest;
        // then temporaries.
        let by_caller =
            |v: &stc_ir::Var| function && matches!(v.section, Section::Input | Section::InOut);
        let mut order: Vec<usize> = (0..pou.vars.len())
            .filter(|&i| self.l.pous[p.0 as usize].in_frame[i])
            .collect();
        order.sort_by_key(|&i| if by_caller(&pou.vars[i]) { 0 } else { 1 });
        let mut init_at = 0;
        let frame_of = || format!("the frame of `{}`", m.spelled(pou.name, pou.name_span));
        let mut top: u64 = 0;
        for &i in &order {
            let v = &pou.vars[i];
            let lay = if v.storage == Storage::Ref {
                stc_ir::layout::Layout { size: 4, align: 4 }
            } else {
                self.l.of(v.ty)
            };
            let a = u64::from(lay.align.max(1));
            let off = top.div_ceil(a) * a;
            top = off + u64::from(lay.size);
            if top > MAX_SIZE {
                return Err(too_large(pou.name_span, frame_of(), top));
            }
            self.frame.var_off.insert(i as u32, off as u32);
            if by_caller(v) {
                init_at = top as u32;
            }
        }
        self.frame.top = align_up(top as u32, 8);
        let vars_end = self.frame.top;
        self.frame.max = vars_end;
        // The template: initial values of the frame variables after `init_at`.
        let mut template = vec![0u8; (vars_end - init_at) as usize];
        for &i in &order {
            let v = &pou.vars[i];
            let off = self.frame.var_off[&(i as u32)];
            if off < init_at || v.storage == Storage::Ref {
                continue;
            }
            let mut scratch = std::mem::take(&mut self.data);
            let base = scratch.len() as u32;
            scratch.resize((base + self.size_of(v.ty)) as usize, 0);
            self.data = scratch;
            self.write_init(v.ty, base, v.init.as_ref(), None);
            let bytes = self.data[base as usize..].to_vec();
            self.data.truncate(base as usize);
            let s = (off - init_at) as usize;
            template[s..s + bytes.len()].copy_from_slice(&bytes);
        }
        let template = self.const_bytes(&template, 8);
        let entry = self.code.len() as u32;
        let file = {
            let f = &pou.file;
            match self.files.iter().position(|x| x == f) {
                Some(i) => i as u32,
                None => {
                    self.files.push(f.clone());
                    (self.files.len() - 1) as u32
                }
            }
        };
        let _ = file;
        self.block(&pou.body)?;
        self.emit(Instr::Ret {});
        let size = align_up(self.frame.max, 8);
        let need = self.frame.overflow.unwrap_or(0).max(u64::from(size));
        if need > MAX_SIZE {
            return Err(too_large(
                pou.name_span,
                format!(
                    "{} with its temporaries and the frames of its calls",
                    frame_of()
                ),
                need,
            ));
        }
        self.frames[p.0 as usize] = Some(FrameInfo {
            var_off: self.frame.var_off.clone(),
            size,
        });
        let code = &mut self.pous[p.0 as usize];
        code.entry = entry;
        code.frame_size = size;
        code.frame_init_at = init_at;
        code.frame_template = (template, vars_end - init_at);
        for (i, d) in code.vars.iter_mut().enumerate() {
            if d.in_frame {
                d.offset = *self
                    .frame
                    .var_off
                    .get(&(i as u32))
                    .ok_or_else(|| internal("a frame variable without a place"))?;
            }
        }
        Ok(())
    }
}
