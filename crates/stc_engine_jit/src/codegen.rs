//! IR to native code with Cranelift: one function per POU body,
//! `(ctx, base, this, fp) -> status`.
//!
//! Addresses are model addresses (offsets into the engine's memory array)
//! as `i64` values; a native pointer is `base + address`. A scalar
//! expression is a Cranelift value of its elementary type's width (BOOL a
//! byte 0/1, REAL `f32`, LREAL `f64`); any other value (strings,
//! structures, arrays) is a native pointer to its bytes: in memory, or in
//! a slot of the native stack for a temporary. A POU's frame (its
//! function variables or VAR_TEMP, at the layout's offsets) is at `fp` in
//! the stack area of the memory; a callee's frame starts right after it.
//! A function's caller writes the whole frame (the template of initial
//! values from the constant pool, then the inputs given); an FB or
//! program initialises its own VAR_TEMP from its template on entry.

use cranelift_codegen::ir::condcodes::{FloatCC, IntCC};
use cranelift_codegen::ir::types::{F32, F64, I16, I32, I64, I8};
use cranelift_codegen::ir::{
    AbiParam, Block, FuncRef, InstBuilder, InstructionData, MemFlags, Opcode, Signature,
    StackSlotData, StackSlotKind, TrapCode, Type, Value as CVal, ValueDef,
};
use cranelift_codegen::isa::TargetFrontendConfig;
use cranelift_codegen::settings::{self, Configurable};
use cranelift_frontend::{FunctionBuilder, FunctionBuilderContext, Variable};
use cranelift_jit::{ArenaMemoryProvider, JITBuilder, JITModule};
use cranelift_module::{FuncId, Linkage, Module as _};
use rustc_hash::FxHashMap;
use stc_diagnostics::Diagnostic;
use stc_ir::layout::{elem_size, Layouts};
use stc_ir::model::{Builder, Model, ModelError};
use stc_ir::{Expr, ExprKind, FaultKind, Module, Place, Proj, Root, Stmt, StmtKind, Storage};
use stc_sema::idx::Idx;
use stc_sema::{PouId, Section, TypeId, TypeKind, VarId};
use stc_syntax::ast::PouKind;
use stc_syntax::literal::AddrSize;
use stc_syntax::token::ElemType;
use stc_values::{BinOp, UnOp, Value};

use crate::{
    Body, CTX_INST, CTX_INST_POU, CTX_KIND, CTX_NOW, CTX_RANGE, CTX_RANGE_FLAGS, CTX_SITE,
    CTX_STEPS, NO_POU, RANGE_BOUNDS_UNSIGNED, RANGE_KNOWN, RANGE_VALUE_UNSIGNED,
};

/// The address space reserved for one engine's code (never committed
/// beyond what the code uses): PC-relative calls reach 2 GiB.
const JIT_CODE_RESERVE: usize = 1 << 30;

/// Why a module was not compiled.
#[derive(Debug)]
pub enum Error {
    /// Cranelift has no back end for this host, or the program uses what
    /// the JIT does not translate: the caller runs the VM instead.
    Unsupported(String),
    /// The program is too large for the memory model (E0901).
    Diagnostics(Vec<Diagnostic>),
    /// A bug: a broken invariant of the IR or of this translation.
    Internal(String),
}

impl std::fmt::Display for Error {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Error::Unsupported(s) => write!(f, "{s}"),
            Error::Diagnostics(d) => write!(
                f,
                "{}",
                d.first()
                    .map_or("the program is too large", |d| d.message.as_str())
            ),
            Error::Internal(s) => write!(f, "internal error: {s}"),
        }
    }
}

impl std::error::Error for Error {}

fn internal(s: impl Into<String>) -> Error {
    Error::Internal(s.into())
}

fn model_error(e: ModelError) -> Error {
    match e {
        ModelError::Diagnostics(d) => Error::Diagnostics(d),
        ModelError::Internal(s) => Error::Internal(s),
    }
}

/// What the generic helper computes (the VM's `StdOp`).
#[derive(Clone, Copy, Debug)]
enum StdOp {
    Call(stc_values::Intrinsic),
    Binary(BinOp),
    Unary(UnOp),
    Convert,
    Trunc,
}

/// One operation through `stc_values`: the operands' elementary types
/// and string capacities, and the result's.
struct StdDesc {
    op: StdOp,
    args: Vec<(ElemType, u32)>,
    result: (ElemType, u32),
}

/// The compiled code and what it points to.
pub(crate) struct Code {
    /// Owns the machine code (freed when the engine is dropped).
    module: Option<JITModule>,
    /// Descriptors of generic operations, pointed to by the code (boxed:
    /// their addresses must not move when the vector grows).
    #[allow(clippy::vec_box)]
    _stds: Vec<Box<StdDesc>>,
}

pub(crate) struct Output {
    pub model: Model,
    pub memory: Vec<u8>,
    pub stack_base: u32,
    pub bodies: Vec<Option<Body>>,
    pub sites: Vec<(String, String, u32, u32)>,
    pub code: Code,
}

impl Drop for Code {
    fn drop(&mut self) {
        if let Some(m) = self.module.take() {
            // SAFETY: the code is dropped with its engine (the last field
            // of `JitEngine`), and nothing keeps a pointer to a compiled
            // function beyond the engine's `bodies`.
            unsafe { m.free_memory() };
        }
    }
}

/// The size of a byte slice a value of `(e, cap)` occupies.
fn value_len(e: ElemType, cap: u32) -> usize {
    match e {
        ElemType::String => 2 + cap as usize,
        ElemType::Wstring => 2 + 2 * cap as usize,
        e => elem_size(e) as usize,
    }
}

/// The generic operation: reads the operands through their pointers as
/// values, computes with `stc_values`, writes the result; returns the
/// fault code (0: none).
///
/// # Safety
/// `desc` is a descriptor of this module and `argv` holds one pointer per
/// operand and one for the result, each to as many bytes as its type
/// occupies ([`value_len`]).
unsafe extern "C" fn jit_std(desc: *const StdDesc, argv: *const *mut u8) -> u32 {
    // SAFETY: see the function's contract.
    let desc = unsafe { &*desc };
    let read = |i: usize, (e, cap): (ElemType, u32)| -> Option<Value> {
        // SAFETY: see the function's contract.
        let bytes = unsafe { std::slice::from_raw_parts(*argv.add(i), value_len(e, cap)) };
        match e {
            ElemType::String => stc_ir::model::repr::read_string(bytes, 0, false, cap),
            ElemType::Wstring => stc_ir::model::repr::read_string(bytes, 0, true, cap),
            _ => stc_ir::model::repr::read_scalar(bytes, 0, e),
        }
    };
    let invalid = u32::from(FaultKind::InvalidCode.code());
    let mut args = Vec::with_capacity(desc.args.len());
    let mut types = Vec::with_capacity(desc.args.len());
    for (i, &a) in desc.args.iter().enumerate() {
        let Some(v) = read(i, a) else {
            return invalid;
        };
        args.push(v);
        types.push(a.0);
    }
    let rt = desc.result.0;
    let r = match desc.op {
        StdOp::Call(f) => stc_values::call(f, &types, &args, rt).map(|o| o.value),
        StdOp::Binary(op) => match (args.first(), args.get(1)) {
            (Some(x), Some(y)) => {
                stc_values::binary(op, types[0], x, types[1], y, rt).map(|o| o.value)
            }
            _ => return invalid,
        },
        StdOp::Unary(op) => match args.first() {
            Some(x) => stc_values::unary(op, types[0], x).map(|o| o.value),
            None => return invalid,
        },
        StdOp::Convert => match args.first() {
            Some(x) => stc_values::convert(types[0], rt, x),
            None => return invalid,
        },
        StdOp::Trunc => match args.first() {
            Some(x) => stc_values::trunc(types[0], rt, x),
            None => return invalid,
        },
    };
    let v = match r {
        Ok(v) => v,
        Err(f) => return u32::from(FaultKind::from_value_fault(f).code()),
    };
    let (e, cap) = desc.result;
    // SAFETY: see the function's contract.
    let out =
        unsafe { std::slice::from_raw_parts_mut(*argv.add(desc.args.len()), value_len(e, cap)) };
    let ok = match e {
        ElemType::String => stc_ir::model::repr::write_string(out, 0, false, cap, &v),
        ElemType::Wstring => stc_ir::model::repr::write_string(out, 0, true, cap, &v),
        _ => stc_ir::model::repr::write_scalar(out, 0, e, &v),
    };
    if ok {
        0
    } else {
        invalid
    }
}

/// Copies a string of `unit`-byte characters into one of capacity `cap`
/// (the VM's `strcopy`: truncated to the capacity).
///
/// # Safety
/// `src` points to a string (its 2-byte length, then at least that many
/// characters or `cap`, whichever is less) and `dst` to `2 + cap * unit`
/// bytes.
unsafe extern "C" fn jit_strcopy(dst: *mut u8, src: *const u8, cap: u32, unit: u32) {
    // SAFETY: see the function's contract.
    unsafe {
        let len = u32::from(u16::from_le_bytes([*src, *src.add(1)])).min(cap);
        std::ptr::copy(src.add(2), dst.add(2), (len * unit) as usize);
        let l = (len as u16).to_le_bytes();
        *dst = l[0];
        *dst.add(1) = l[1];
    }
}

fn align8(x: u64) -> u64 {
    x.div_ceil(8) * 8
}

/// Compiles a module to native code with its memory.
pub(crate) fn compile(m: &Module) -> Result<Output, Error> {
    let l = Layouts::compute(m).map_err(Error::Diagnostics)?;
    let mut d = Builder::new(m, &l).map_err(model_error)?;
    let data_size = u64::from(d.data_size());
    let const_base = align8(data_size);

    // Frame templates, in the constant pool.
    let mut consts: Vec<u8> = Vec::new();
    let mut templates: Vec<Option<(u32, u32)>> = Vec::with_capacity(m.pous.len());
    for p in m.pous.ids() {
        let pou = &m.pous[p];
        let lay = &l.pous[p];
        let size = lay.frame.size as usize;
        if size == 0 || !pou.vars.ids().any(|v| lay.in_frame[v]) {
            templates.push(None);
            continue;
        }
        let mut t = vec![0u8; size];
        for v in pou.vars.ids() {
            let var = &pou.vars[v];
            if !lay.in_frame[v] || var.storage == Storage::Ref {
                continue;
            }
            let bytes = d
                .init_bytes(var.ty, var.init.as_ref())
                .map_err(model_error)?;
            let off = lay.offsets[v] as usize;
            let dst = t
                .get_mut(off..off + bytes.len())
                .ok_or_else(|| internal("a frame variable outside its frame"))?;
            dst.copy_from_slice(&bytes);
        }
        while !consts.len().is_multiple_of(8) {
            consts.push(0);
        }
        let at = const_base + consts.len() as u64;
        consts.extend_from_slice(&t);
        templates.push(Some((at as u32, size as u32)));
    }
    // The model's frame offsets are this engine's (the layout's).
    for p in m.pous.ids() {
        if let Some(desc) = d.model_mut().pous.get_mut(p.index()) {
            for (i, vd) in desc.vars.iter_mut().enumerate() {
                if vd.in_frame {
                    vd.offset = l.pous[p].offsets[VarId::new(i)];
                }
            }
        }
    }

    // The Cranelift module.
    let mut flags = settings::builder();
    let set = |f: &mut settings::Builder, k: &str, v: &str| {
        f.set(k, v)
            .map_err(|e| internal(format!("cranelift flag {k}: {e}")))
    };
    // The IR verifier is for Cranelift's own development: its cost grows
    // with every function, and the translation here is tested instead.
    set(&mut flags, "enable_verifier", "false")?;
    set(&mut flags, "opt_level", "speed")?;
    set(&mut flags, "use_colocated_libcalls", "false")?;
    set(&mut flags, "is_pic", "false")?;
    let isa_builder = cranelift_native::builder()
        .map_err(|e| Error::Unsupported(format!("no JIT for this host: {e}")))?;
    let isa = isa_builder
        .finish(settings::Flags::new(flags))
        .map_err(|e| Error::Unsupported(format!("no JIT for this host: {e}")))?;
    let mut jb = JITBuilder::with_isa(isa, cranelift_module::default_libcall_names());
    // All the code of one engine in one reserved region (address space
    // only, committed as it is used): calls between the program's functions
    // are 32-bit PC-relative, and with the default provider two functions
    // of a large program could land more than 2 GiB apart (found by the
    // random differential: a panic in cranelift-jit's relocation).
    let arena = ArenaMemoryProvider::new_with_size(JIT_CODE_RESERVE)
        .map_err(|e| Error::Unsupported(format!("no memory for JIT code: {e}")))?;
    jb.memory_provider(Box::new(arena));
    jb.symbol("stc_jit_std", jit_std as *const u8);
    jb.symbol("stc_jit_strcopy", jit_strcopy as *const u8);
    let mut module = JITModule::new(jb);
    let ptr = module.target_config().pointer_type();
    if ptr != I64 {
        return Err(Error::Unsupported(
            "no JIT for a host without 64-bit pointers".into(),
        ));
    }
    let mut body_sig = module.make_signature();
    body_sig.params.extend([AbiParam::new(I64); 4]);
    body_sig.returns.push(AbiParam::new(I32));
    let mut std_sig = module.make_signature();
    std_sig.params.extend([AbiParam::new(I64); 2]);
    std_sig.returns.push(AbiParam::new(I32));
    let mut copy_sig = module.make_signature();
    copy_sig.params.extend([
        AbiParam::new(I64),
        AbiParam::new(I64),
        AbiParam::new(I32),
        AbiParam::new(I32),
    ]);
    let decl = |module: &mut JITModule, name: &str, l: Linkage, s: &Signature| {
        module
            .declare_function(name, l, s)
            .map_err(|e| internal(format!("declare {name}: {e}")))
    };
    let std_fn = decl(&mut module, "stc_jit_std", Linkage::Import, &std_sig)?;
    let copy_fn = decl(&mut module, "stc_jit_strcopy", Linkage::Import, &copy_sig)?;
    // Only what can run is compiled: the programs and what they call (a
    // project's library of function blocks nobody instantiates costs no
    // compile time).
    let reachable = reachable(m);
    let mut ids = Vec::with_capacity(m.pous.len());
    for p in m.pous.ids() {
        ids.push(if reachable[p.index()] {
            Some(decl(
                &mut module,
                &format!("pou{}", p.index()),
                Linkage::Local,
                &body_sig,
            )?)
        } else {
            None
        });
    }

    // The stack each POU needs: its frame, then its deepest callee's.
    let frame_size: Vec<u64> = m
        .pous
        .ids()
        .map(|p| align8(u64::from(l.pous[p].frame.size)))
        .collect();
    let stack_need = stack_need(m, &frame_size)?;

    let mut g = Globals {
        m,
        l: &l,
        d: &mut d,
        consts,
        const_base,
        stds: Vec::new(),
        sites: Vec::new(),
        site_map: FxHashMap::default(),
        ids,
        std_fn,
        copy_fn,
        frame_size,
        templates,
        config: module.target_config(),
    };
    let mut fctx = FunctionBuilderContext::new();
    let mut ctx = module.make_context();
    // A debugging aid: `STC_JIT_DUMP=FILE` appends each function's CLIF as
    // translated and the machine code Cranelift made of it to FILE.
    let mut dump = std::env::var_os("STC_JIT_DUMP").and_then(|f| {
        std::fs::OpenOptions::new()
            .create(true)
            .append(true)
            .open(f)
            .ok()
    });
    for p in m.pous.ids() {
        let Some(id) = g.ids[p.index()] else {
            continue;
        };
        ctx.func.signature = body_sig.clone();
        {
            let b = FunctionBuilder::new(&mut ctx.func, &mut fctx);
            Fx::new(&mut g, &mut module, b, p).body()?;
        }
        if let Some(f) = dump.as_mut() {
            use std::io::Write;
            ctx.set_disasm(true);
            let _ = writeln!(
                f,
                "; POU {}\n{}",
                m.name(m.pous[p].name),
                ctx.func.display()
            );
        }
        module
            .define_function(id, &mut ctx)
            .map_err(|e| internal(format!("cranelift: {e:?}")))?;
        if let Some(f) = dump.as_mut() {
            use std::io::Write;
            let _ = writeln!(f, "; optimised\n{}", ctx.func.display());
            if let Some(vcode) = ctx.compiled_code().and_then(|c| c.vcode.as_ref()) {
                let _ = writeln!(f, "; machine code of {}\n{vcode}", m.name(m.pous[p].name));
            }
        }
        module.clear_context(&mut ctx);
    }
    module
        .finalize_definitions()
        .map_err(|e| internal(format!("cranelift: {e}")))?;
    let bodies = g
        .ids
        .iter()
        .map(|id| {
            let f = module.get_finalized_function((*id)?);
            // SAFETY: the function was defined with `body_sig`, which is
            // the C ABI signature of `Body`.
            Some(unsafe { std::mem::transmute::<*const u8, Body>(f) })
        })
        .collect();
    let Globals {
        consts,
        stds,
        sites,
        ..
    } = g;
    let stack_base = align8(const_base + consts.len() as u64);
    let total = stack_base + stack_need + 64;
    if total > stc_ir::layout::MAX_SIZE {
        return Err(Error::Unsupported(format!(
            "the JIT's memory would need {total} bytes, over the limit"
        )));
    }
    let data = d.finish();
    let mut memory = vec![0u8; total as usize];
    let n = data.init.len().min(data_size as usize);
    memory[..n].copy_from_slice(&data.init[..n]);
    memory[const_base as usize..const_base as usize + consts.len()].copy_from_slice(&consts);
    Ok(Output {
        model: data.model,
        memory,
        stack_base: stack_base as u32,
        bodies,
        sites,
        code: Code {
            module: Some(module),
            _stds: stds,
        },
    })
}

/// Which POUs can run: the programs, and every POU they call, directly or
/// not.
fn reachable(m: &Module) -> Vec<bool> {
    let mut seen = vec![false; m.pous.len()];
    let mut work: Vec<usize> = m
        .pous
        .iter()
        .enumerate()
        .filter(|(_, p)| p.kind == PouKind::Program)
        .map(|(i, _)| i)
        .collect();
    for &i in &work {
        seen[i] = true;
    }
    while let Some(i) = work.pop() {
        stc_ir::visit::calls(&m.pous[PouId::new(i)].body, &mut |c| {
            if let Some(s) = seen.get_mut(c.index()) {
                if !*s {
                    *s = true;
                    work.push(c.index());
                }
            }
        });
    }
    seen
}

/// The stack of frames every POU needs with its calls (calls are acyclic:
/// the analyser rejects recursion).
fn stack_need(m: &Module, frame: &[u64]) -> Result<u64, Error> {
    let n = m.pous.len();
    let mut callees: Vec<Vec<usize>> = vec![Vec::new(); n];
    for (i, p) in m.pous.iter().enumerate() {
        stc_ir::visit::calls(&p.body, &mut |c| callees[i].push(c.index()));
    }
    let mut need: Vec<Option<u64>> = vec![None; n];
    let mut state = vec![0u8; n];
    for start in 0..n {
        if need[start].is_some() {
            continue;
        }
        let mut stack = vec![(start, 0usize)];
        state[start] = 1;
        while let Some(&mut (v, ref mut i)) = stack.last_mut() {
            if let Some(&w) = callees[v].get(*i) {
                *i += 1;
                match state[w] {
                    0 => {
                        state[w] = 1;
                        stack.push((w, 0));
                    }
                    1 => return Err(internal("a recursive call")),
                    _ => {}
                }
            } else {
                let deepest = callees[v]
                    .iter()
                    .filter_map(|&c| need[c])
                    .max()
                    .unwrap_or(0);
                need[v] = Some(frame[v] + deepest);
                state[v] = 2;
                stack.pop();
            }
        }
    }
    Ok(need.into_iter().flatten().max().unwrap_or(0))
}

/// What every POU's translation shares.
struct Globals<'a, 'm> {
    m: &'m Module,
    l: &'m Layouts,
    d: &'a mut Builder<'m>,
    consts: Vec<u8>,
    const_base: u64,
    /// (Boxed: the code points to them.)
    #[allow(clippy::vec_box)]
    stds: Vec<Box<StdDesc>>,
    sites: Vec<(String, String, u32, u32)>,
    site_map: FxHashMap<(u32, u32, u32), u32>,
    /// By POU: its function, when it can run.
    ids: Vec<Option<FuncId>>,
    std_fn: FuncId,
    copy_fn: FuncId,
    frame_size: Vec<u64>,
    templates: Vec<Option<(u32, u32)>>,
    config: TargetFrontendConfig,
}

/// A value: a scalar in a register, or a native pointer to its bytes.
#[derive(Clone, Copy)]
enum V {
    S(CVal),
    M(CVal),
}

/// A place: its model address, and the bit part selected (`x.%X3`):
/// (width of the word in bits, part size, index).
struct PlaceAt {
    addr: CVal,
    part: Option<(u32, AddrSize, u32)>,
    /// The native pointer of `addr`, when [`Fx::place_lazy`] built it in
    /// the form Cranelift hoists and folds into an addressing mode:
    /// `(base + root + constant offset) + index terms`.
    ptr: Option<CVal>,
}

/// An index check: the index, its bounds, and the fault site it reports.
/// (whether the index is an unsigned 64-bit value).
type IndexCheck = (CVal, i64, i64, u32, bool);

/// Whether a conversion between scalars of this type is the VM's plain
/// numeric `cvt`.
fn plain_numeric(t: Option<ElemType>) -> bool {
    t.is_some_and(|t| {
        !matches!(
            t,
            ElemType::String | ElemType::Wstring | ElemType::Char | ElemType::Wchar
        ) && !stc_values::is_time_like(t)
    })
}

fn is_signed(e: ElemType) -> bool {
    use ElemType as E;
    matches!(
        e,
        E::Sint
            | E::Int
            | E::Dint
            | E::Lint
            | E::Time
            | E::Ltime
            | E::Date
            | E::Ldate
            | E::Tod
            | E::Ltod
            | E::Dt
            | E::Ldt
    )
}

fn is_float(e: ElemType) -> bool {
    matches!(e, ElemType::Real | ElemType::Lreal)
}

fn cl_type(e: ElemType) -> Type {
    match e {
        ElemType::Real => F32,
        ElemType::Lreal => F64,
        e => match elem_size(e) {
            1 => I8,
            2 => I16,
            4 => I32,
            _ => I64,
        },
    }
}

fn int_of_bytes(n: u32) -> Type {
    match n {
        1 => I8,
        2 => I16,
        4 => I32,
        _ => I64,
    }
}

/// The range of an integer type (bit strings unsigned).
fn int_range(e: ElemType) -> (i128, i128) {
    let bits = elem_size(e) * 8;
    if e == ElemType::Bool {
        (0, 1)
    } else if is_signed(e) {
        (-(1i128 << (bits - 1)), (1i128 << (bits - 1)) - 1)
    } else {
        (0, (1i128 << bits) - 1)
    }
}

struct Fx<'g, 'a, 'm, 'f> {
    g: &'g mut Globals<'a, 'm>,
    module: &'g mut JITModule,
    b: FunctionBuilder<'f>,
    p: PouId,
    ctx: CVal,
    base: CVal,
    this: CVal,
    fp: CVal,
    site: u32,
    fault_block: Block,
    prop_block: Block,
    ret_block: Block,
    loops: Vec<(Block, Block)>,
    funcs: FxHashMap<FuncId, FuncRef>,
    /// By variable of this POU: the SSA variable holding it, when it is
    /// held in a register inside the body (see [`promotable`]).
    regs: Vec<Option<(Variable, Type)>>,
    /// By variable: whether the body assigns it (what is stored back).
    written: Vec<bool>,
    /// The watchdog steps left, held in a register inside the body.
    steps: Option<Variable>,
    /// The indices range analysis proves inside their bounds (unchecked).
    proven: stc_ir::ranges::Proven,
    /// The loops emitted twice behind a guard (`stc_ir::ranges::Versions`).
    versions: stc_ir::ranges::Versions,
    /// Inside the check-free copy of a versioned loop: its version.
    fast: Option<stc_ir::ranges::Version>,
}

impl<'g, 'a, 'm, 'f> Fx<'g, 'a, 'm, 'f> {
    fn new(
        g: &'g mut Globals<'a, 'm>,
        module: &'g mut JITModule,
        mut b: FunctionBuilder<'f>,
        p: PouId,
    ) -> Self {
        let entry = b.create_block();
        b.append_block_params_for_function_params(entry);
        b.switch_to_block(entry);
        let params = b.block_params(entry).to_vec();
        let fault_block = b.create_block();
        b.append_block_param(fault_block, I32);
        b.append_block_param(fault_block, I32);
        let prop_block = b.create_block();
        let ret_block = b.create_block();
        let m: &'m Module = g.m;
        let proven = stc_ir::ranges::Proven::of(m, &m.pous[p]);
        let versions = stc_ir::ranges::Versions::of(m, &m.pous[p], &proven);
        Fx {
            g,
            module,
            b,
            p,
            ctx: params[0],
            base: params[1],
            this: params[2],
            fp: params[3],
            site: 0,
            fault_block,
            prop_block,
            ret_block,
            loops: Vec::new(),
            funcs: FxHashMap::default(),
            regs: Vec::new(),
            written: Vec::new(),
            steps: None,
            proven,
            versions,
            fast: None,
        }
    }

    /// Gives the promotable scalars of this POU their SSA variables,
    /// loaded from memory, and the watchdog count its register.
    fn promote(&mut self) {
        let pou = &self.g.m.pous[self.p];
        let (ok, written) = promotable(self.g.m, self.p, |t| self.scalar(t));
        self.regs = vec![None; ok.len()];
        self.written = written;
        for v in pou.vars.ids() {
            if !ok[v.index()] {
                continue;
            }
            let Some(e) = self.scalar(pou.vars[v].ty) else {
                continue;
            };
            let var = self.b.declare_var(cl_type(e));
            self.regs[v.index()] = Some((var, cl_type(e)));
        }
        let st = self.b.declare_var(I64);
        self.steps = Some(st);
        self.reload();
    }

    /// Stores the registers the body assigns (and the watchdog count)
    /// back to memory: before a call, at every exit.
    fn flush(&mut self) {
        for i in 0..self.regs.len() {
            let Some((var, _)) = self.regs[i] else {
                continue;
            };
            if !self.written[i] {
                continue;
            }
            let x = self.b.use_var(var);
            let a = self.var_addr(VarId::new(i));
            let ptr = self.native(a);
            self.b.ins().store(MemFlags::new(), x, ptr, 0);
        }
        if let Some(st) = self.steps {
            let x = self.b.use_var(st);
            self.b
                .ins()
                .store(MemFlags::trusted(), x, self.ctx, CTX_STEPS);
        }
    }

    /// Loads every register from memory: at entry, after a call.
    fn reload(&mut self) {
        for i in 0..self.regs.len() {
            let Some((var, t)) = self.regs[i] else {
                continue;
            };
            let a = self.var_addr(VarId::new(i));
            let ptr = self.native(a);
            let x = self.b.ins().load(t, MemFlags::new(), ptr, 0);
            self.b.def_var(var, x);
        }
        if let Some(st) = self.steps {
            let x = self
                .b
                .ins()
                .load(I64, MemFlags::trusted(), self.ctx, CTX_STEPS);
            self.b.def_var(st, x);
        }
    }

    /// The register of a place that is a whole promoted variable.
    fn reg_of(&self, p: &Place) -> Option<(Variable, Type)> {
        match (&p.root, p.proj.is_empty()) {
            (Root::Var(v), true) => self.regs.get(v.index()).copied().flatten(),
            _ => None,
        }
    }

    fn body(mut self) -> Result<(), Error> {
        let m = self.g.m;
        let pou = &m.pous[self.p];
        self.site = self.site_of(pou.span_line_col());
        if pou.kind != PouKind::Function {
            if let Some((src, len)) = self.g.templates[self.p.index()] {
                let s = self.native_const(u64::from(src));
                let d = self.native(self.fp);
                self.copy(d, s, len);
            }
        }
        self.promote();
        self.block(&pou.body)?;
        self.goto(self.ret_block);
        // Exits.
        self.b.switch_to_block(self.ret_block);
        self.flush();
        let z = self.b.ins().iconst(I32, 0);
        self.b.ins().return_(&[z]);
        // A fault from a callee: the innermost function block or program
        // instance on the way out is where it happened (the first to see
        // it records itself; a function has no instance of its own).
        self.b.switch_to_block(self.prop_block);
        let is_instance = pou.kind != PouKind::Function;
        if is_instance {
            let recorded = self
                .b
                .ins()
                .load(I32, MemFlags::trusted(), self.ctx, CTX_INST_POU);
            let none = self.b.ins().icmp_imm(IntCC::Equal, recorded, NO_POU);
            let record = self.b.create_block();
            let done = self.b.create_block();
            self.b.ins().brif(none, record, &[], done, &[]);
            self.b.switch_to_block(record);
            self.record_instance();
            self.b.ins().jump(done, &[]);
            self.b.switch_to_block(done);
        }
        let one = self.b.ins().iconst(I32, 1);
        self.b.ins().return_(&[one]);
        self.b.switch_to_block(self.fault_block);
        // The report after a fault shows every assignment made before it.
        self.flush();
        let kp = self.b.block_params(self.fault_block).to_vec();
        self.b
            .ins()
            .store(MemFlags::trusted(), kp[0], self.ctx, CTX_KIND);
        self.b
            .ins()
            .store(MemFlags::trusted(), kp[1], self.ctx, CTX_SITE);
        if is_instance {
            self.record_instance();
        } else {
            let none = self.b.ins().iconst(I32, NO_POU);
            self.b
                .ins()
                .store(MemFlags::trusted(), none, self.ctx, CTX_INST_POU);
        }
        let one = self.b.ins().iconst(I32, 1);
        self.b.ins().return_(&[one]);
        self.b.seal_all_blocks();
        self.b.finalize();
        Ok(())
    }

    // ----- helpers ------------------------------------------------------------------

    /// Stores this body's instance and POU as where the pending fault
    /// happened.
    fn record_instance(&mut self) {
        let at = self.b.ins().ireduce(I32, self.this);
        self.b
            .ins()
            .store(MemFlags::trusted(), at, self.ctx, CTX_INST);
        let p = self.b.ins().iconst(I32, i64::from(self.p.0));
        self.b
            .ins()
            .store(MemFlags::trusted(), p, self.ctx, CTX_INST_POU);
    }

    fn site_of(&mut self, (line, col): (u32, u32)) -> u32 {
        let key = (self.p.0, line, col);
        if let Some(&s) = self.g.site_map.get(&key) {
            return s;
        }
        let pou = &self.g.m.pous[self.p];
        let name = self
            .g
            .d
            .model()
            .pous
            .get(self.p.index())
            .map(|d| d.name.clone())
            .unwrap_or_default();
        let s = self.g.sites.len() as u32;
        self.g.sites.push((name, pou.file.clone(), line, col));
        self.g.site_map.insert(key, s);
        s
    }

    fn func(&mut self, id: FuncId) -> FuncRef {
        if let Some(&f) = self.funcs.get(&id) {
            return f;
        }
        let f = self.module.declare_func_in_func(id, self.b.func);
        self.funcs.insert(id, f);
        f
    }

    /// Starts a new block (after a jump: code that follows is unreachable).
    /// It is sealed at once (nothing jumps to it), so the builder knows it
    /// unreachable and [`Self::goto`] leaves it without an edge.
    fn fresh(&mut self) {
        let blk = self.b.create_block();
        self.b.switch_to_block(blk);
        self.b.seal_block(blk);
    }

    /// Jumps to `to`; from an unreachable block (code after `EXIT`,
    /// `CONTINUE`, `RETURN`) ends it with a trap instead: an edge from it
    /// would give the target a predecessor where every variable is
    /// undefined, and every variable a block parameter at the target,
    /// which hides loop invariants from Cranelift's code motion.
    fn goto(&mut self, to: Block) {
        if self.b.is_unreachable() {
            self.b.ins().trap(TrapCode::unwrap_user(1));
        } else {
            self.b.ins().jump(to, &[]);
        }
    }

    /// A constant of an integer type (Cranelift wants the immediate of a
    /// narrow type zero-extended: the low bits of `v`).
    fn iconst(&mut self, t: Type, v: i64) -> CVal {
        let bits = t.bits();
        let v = if bits < 64 {
            v & ((1i64 << bits) - 1)
        } else {
            v
        };
        self.b.ins().iconst(t, v)
    }

    /// The value of `v` when it is an integer constant (`iconst`).
    fn const_of(&self, v: CVal) -> Option<i64> {
        let dfg = &self.b.func.dfg;
        match dfg.value_def(dfg.resolve_aliases(v)) {
            ValueDef::Result(inst, _) => match dfg.insts[inst] {
                InstructionData::UnaryImm {
                    opcode: Opcode::Iconst,
                    imm,
                } => Some(imm.bits()),
                _ => None,
            },
            _ => None,
        }
    }

    /// The native pointer of a model address.
    fn native(&mut self, addr: CVal) -> CVal {
        self.b.ins().iadd(self.base, addr)
    }

    fn native_const(&mut self, addr: u64) -> CVal {
        let a = self.iconst(I64, addr as i64);
        self.native(a)
    }

    fn copy(&mut self, dst: CVal, src: CVal, len: u32) {
        if len == 0 {
            return;
        }
        let cfg = self.g.config;
        self.b
            .emit_small_memory_copy(cfg, dst, src, u64::from(len), 1, 1, false, MemFlags::new());
    }

    /// Jumps to the fault exit when `cond` (an i8 truth value) holds.
    /// (Through a cold block of its own that sets the fault exit's
    /// arguments: set before the branch, the constants would be
    /// materialised on the hot path, in every iteration of a loop.)
    fn fault_if(&mut self, cond: CVal, kind: FaultKind) {
        let fail = self.b.create_block();
        let cont = self.b.create_block();
        self.b.set_cold_block(fail);
        self.b.ins().brif(cond, fail, &[], cont, &[]);
        self.b.seal_block(fail);
        self.b.seal_block(cont);
        self.b.switch_to_block(fail);
        let k = self.iconst(I32, i64::from(kind.code()));
        let s = self.iconst(I32, i64::from(self.site));
        self.b.ins().jump(self.fault_block, &[k.into(), s.into()]);
        self.b.switch_to_block(cont);
    }

    /// Jumps to the fault exit with a dynamic code when `code` is not 0.
    fn fault_code(&mut self, code: CVal) {
        let fail = self.b.create_block();
        let cont = self.b.create_block();
        self.b.set_cold_block(fail);
        self.b.ins().brif(code, fail, &[], cont, &[]);
        self.b.seal_block(fail);
        self.b.seal_block(cont);
        self.b.switch_to_block(fail);
        let s = self.iconst(I32, i64::from(self.site));
        self.b
            .ins()
            .jump(self.fault_block, &[code.into(), s.into()]);
        self.b.switch_to_block(cont);
    }

    /// One watchdog step: a decrement of the register holding the count
    /// (stored to the context before calls and at the exits).
    fn step(&mut self) {
        let Some(st) = self.steps else {
            return;
        };
        let s = self.b.use_var(st);
        let out = self.b.ins().icmp_imm(IntCC::Equal, s, 0);
        self.fault_if(out, FaultKind::Watchdog);
        let s1 = self.b.ins().iadd_imm(s, -1);
        self.b.def_var(st, s1);
    }

    fn stack_slot(&mut self, size: u32) -> CVal {
        let ss = self.b.create_sized_stack_slot(StackSlotData::new(
            StackSlotKind::ExplicitSlot,
            size.max(8).div_ceil(8) * 8,
            3,
        ));
        self.b.ins().stack_addr(I64, ss, 0)
    }

    /// The elementary type a value is handled as natively; a reference is
    /// its 4-byte model address, handled as a UDINT (NULL is 0), as on
    /// the VM.
    fn scalar(&self, t: TypeId) -> Option<ElemType> {
        if let TypeKind::Ref(_) = self.g.m.types.kind(t) {
            return Some(ElemType::Udint);
        }
        self.g
            .m
            .types
            .scalar(t)
            .filter(|e| !matches!(e, ElemType::String | ElemType::Wstring))
    }

    fn size_of(&self, t: TypeId) -> u32 {
        self.g.l.of(t).size
    }

    /// The elementary type and capacity a value of `t` is passed to
    /// `stc_values` as.
    fn std_arg(&self, t: TypeId) -> (ElemType, u32) {
        match self.g.m.types.kind(t) {
            TypeKind::String { wide, len } => (
                if *wide {
                    ElemType::Wstring
                } else {
                    ElemType::String
                },
                *len,
            ),
            _ => (self.g.m.types.scalar(t).unwrap_or(ElemType::Lint), 0),
        }
    }

    fn load_scalar(&mut self, e: ElemType, ptr: CVal) -> CVal {
        self.b.ins().load(cl_type(e), MemFlags::new(), ptr, 0)
    }

    /// A value as a native pointer (a scalar spilled to a stack slot).
    fn spill(&mut self, v: V) -> CVal {
        match v {
            V::M(p) => p,
            V::S(x) => {
                let p = self.stack_slot(8);
                self.b.ins().store(MemFlags::new(), x, p, 0);
                p
            }
        }
    }

    /// A generic operation through `stc_values`.
    fn generic(&mut self, op: StdOp, args: &[(V, TypeId)], result: TypeId) -> Result<V, Error> {
        let desc = Box::new(StdDesc {
            op,
            args: args.iter().map(|&(_, t)| self.std_arg(t)).collect(),
            result: self.std_arg(result),
        });
        let dp = &*desc as *const StdDesc as i64;
        self.g.stds.push(desc);
        let argv = self.stack_slot(8 * (args.len() as u32 + 1));
        for (i, &(v, _)) in args.iter().enumerate() {
            let p = self.spill(v);
            self.b.ins().store(MemFlags::new(), p, argv, 8 * i as i32);
        }
        let (re, cap) = self.std_arg(result);
        let rp = self.stack_slot(value_len(re, cap) as u32);
        self.b
            .ins()
            .store(MemFlags::new(), rp, argv, 8 * args.len() as i32);
        let f = self.func(self.g.std_fn);
        let dv = self.iconst(I64, dp);
        let call = self.b.ins().call(f, &[dv, argv]);
        let code = self.b.inst_results(call)[0];
        self.fault_code(code);
        Ok(match self.scalar(result) {
            Some(e) => V::S(self.load_scalar(e, rp)),
            None => V::M(rp),
        })
    }

    // ----- statements ---------------------------------------------------------------

    /// Branches on `c` to the code `then` emits and the code `other`
    /// emits, both going on after them. Each block is sealed as soon as
    /// its predecessors are all known (see `emit_loop`).
    fn two_way(
        &mut self,
        c: cranelift_codegen::ir::Value,
        then: impl FnOnce(&mut Self) -> Result<(), Error>,
        other: impl FnOnce(&mut Self) -> Result<(), Error>,
    ) -> Result<(), Error> {
        let (t, e, end) = (
            self.b.create_block(),
            self.b.create_block(),
            self.b.create_block(),
        );
        self.b.ins().brif(c, t, &[], e, &[]);
        self.b.seal_block(t);
        self.b.seal_block(e);
        self.b.switch_to_block(t);
        then(self)?;
        self.goto(end);
        self.b.switch_to_block(e);
        other(self)?;
        self.goto(end);
        self.b.seal_block(end);
        self.b.switch_to_block(end);
        Ok(())
    }

    fn block(&mut self, stmts: &[Stmt]) -> Result<(), Error> {
        for s in stmts {
            self.stmt(s)?;
        }
        Ok(())
    }

    fn stmt(&mut self, s: &Stmt) -> Result<(), Error> {
        let saved = self.site;
        self.site = self.site_of((s.line, s.col));
        match &s.kind {
            StmtKind::Assign { place, value } => {
                if let Some(var) = self.reg_of(place) {
                    let v = self.expr(value)?;
                    self.def_reg(var, place, v)?;
                } else if stc_ir::visit::has_call(value) {
                    let pl = self.place(place)?;
                    let v = self.expr(value)?;
                    self.store(&pl, v, value.ty, place.ty)?;
                } else {
                    let (pl, pending) = self.place_lazy(place)?;
                    let v = self.expr(value)?;
                    if let Some(c) = pending {
                        self.index_check(c);
                    }
                    self.store(&pl, v, value.ty, place.ty)?;
                }
            }
            StmtKind::CallFb {
                instance,
                fb,
                inputs,
                inouts,
                outputs,
            } => self.call_fb(instance, *fb, inputs, inouts, outputs)?,
            StmtKind::Eval(e) => {
                self.expr(e)?;
            }
            StmtKind::If {
                cond,
                then_body,
                else_body,
            } => {
                let c = self.expr_s(cond)?;
                self.two_way(
                    c,
                    |g: &mut Self| g.block(then_body),
                    |g: &mut Self| g.block(else_body),
                )?;
            }
            StmtKind::Switch {
                selector,
                arms,
                default,
            } => self.switch(selector, arms, default)?,
            StmtKind::Loop { body, latch } => match self.versions.get(s).cloned() {
                // Loop versioning: the check-free copy where the guard
                // holds, the checked loop where it does not.
                Some(v) if self.fast.is_none() => {
                    let c = self.expr_s(&v.guard)?;
                    self.two_way(
                        c,
                        |g: &mut Self| {
                            g.fast = Some(v);
                            let r = g.emit_loop(s, body, latch);
                            g.fast = None;
                            r
                        },
                        |g: &mut Self| g.emit_loop(s, body, latch),
                    )?;
                }
                _ => self.emit_loop(s, body, latch)?,
            },
            StmtKind::Break => {
                let (_, exit) = *self
                    .loops
                    .last()
                    .ok_or_else(|| internal("BREAK outside a loop"))?;
                self.goto(exit);
                self.fresh();
            }
            StmtKind::Continue => {
                let (lat, _) = *self
                    .loops
                    .last()
                    .ok_or_else(|| internal("CONTINUE outside a loop"))?;
                self.goto(lat);
                self.fresh();
            }
            StmtKind::Return => {
                self.goto(self.ret_block);
                self.fresh();
            }
            StmtKind::Fault(k) => {
                if !self.b.is_unreachable() {
                    let k = self.iconst(I32, i64::from(k.code()));
                    let s = self.iconst(I32, i64::from(self.site));
                    self.b.ins().jump(self.fault_block, &[k.into(), s.into()]);
                    self.fresh();
                }
            }
        }
        self.site = saved;
        Ok(())
    }

    /// A loop: its header, body, latch (with the watchdog step) and exit.
    fn emit_loop(&mut self, s: &Stmt, body: &[Stmt], latch: &[Stmt]) -> Result<(), Error> {
        let (head, lat, exit) = (
            self.b.create_block(),
            self.b.create_block(),
            self.b.create_block(),
        );
        self.goto(head);
        self.b.switch_to_block(head);
        self.loops.push((lat, exit));
        self.block(body)?;
        self.goto(lat);
        self.b.seal_block(lat);
        self.b.switch_to_block(lat);
        self.block(latch)?;
        self.loops.pop();
        self.site = self.site_of((s.line, s.col));
        self.step();
        self.goto(head);
        // The loop's blocks are sealed as soon as their
        // predecessors are all known, the header after its back
        // edge: inner loops first, so that the SSA builder's
        // removal of redundant block parameters sees a variable
        // the loop does not assign as the value it enters with, a
        // loop invariant for Cranelift's code motion (sealed all at
        // the end, an outer header keeps a parameter whose inputs
        // are its own value and the value entering it).
        self.b.seal_block(head);
        self.b.seal_block(exit);
        self.b.switch_to_block(exit);
        Ok(())
    }

    fn switch(
        &mut self,
        selector: &Expr,
        arms: &[stc_ir::SwitchArm],
        default: &[Stmt],
    ) -> Result<(), Error> {
        let e = self
            .scalar(selector.ty)
            .ok_or_else(|| internal("a CASE selector that is not a scalar"))?;
        let sel = self.expr_s(selector)?;
        let t = cl_type(e);
        let (tmin, tmax) = int_range(e);
        let signed = is_signed(e);
        let end = self.b.create_block();
        let bodies: Vec<Block> = arms.iter().map(|_| self.b.create_block()).collect();
        for (ai, arm) in arms.iter().enumerate() {
            for &(lo, hi) in &arm.ranges {
                let (lo, hi) = (lo.max(tmin), hi.min(tmax));
                if lo > hi {
                    continue;
                }
                let next = self.b.create_block();
                if lo == hi {
                    let lo_v = self.iconst(t, lo as i64);
                    let c = self.b.ins().icmp(IntCC::Equal, sel, lo_v);
                    self.b.ins().brif(c, bodies[ai], &[], next, &[]);
                } else {
                    let lo_v = self.iconst(t, lo as i64);
                    let hi_v = self.iconst(t, hi as i64);
                    let (ge, le) = if signed {
                        (
                            IntCC::SignedGreaterThanOrEqual,
                            IntCC::SignedLessThanOrEqual,
                        )
                    } else {
                        (
                            IntCC::UnsignedGreaterThanOrEqual,
                            IntCC::UnsignedLessThanOrEqual,
                        )
                    };
                    let a = self.b.ins().icmp(ge, sel, lo_v);
                    let b = self.b.ins().icmp(le, sel, hi_v);
                    let c = self.b.ins().band(a, b);
                    self.b.ins().brif(c, bodies[ai], &[], next, &[]);
                }
                self.b.seal_block(next);
                self.b.switch_to_block(next);
            }
        }
        self.block(default)?;
        self.goto(end);
        for (ai, arm) in arms.iter().enumerate() {
            self.b.seal_block(bodies[ai]);
            self.b.switch_to_block(bodies[ai]);
            self.block(&arm.body)?;
            self.goto(end);
        }
        self.b.seal_block(end);
        self.b.switch_to_block(end);
        Ok(())
    }

    /// Assigns a promoted variable (through memory if the value's width
    /// is not the register's: what a store would do).
    fn def_reg(&mut self, (var, want): (Variable, Type), place: &Place, v: V) -> Result<(), Error> {
        let V::S(x) = v else {
            return Err(internal("a promoted variable given a non-scalar"));
        };
        if self.b.func.dfg.value_type(x) == want {
            self.b.def_var(var, x);
        } else {
            let pl = self.place(place)?;
            let ptr = self.native(pl.addr);
            self.b.ins().store(MemFlags::new(), x, ptr, 0);
            let y = self.b.ins().load(want, MemFlags::new(), ptr, 0);
            self.b.def_var(var, y);
        }
        Ok(())
    }

    // ----- places -------------------------------------------------------------------

    fn var_addr(&mut self, v: VarId) -> CVal {
        let lay = &self.g.l.pous[self.p];
        let off = lay.offsets[v];
        let base = if lay.in_frame[v] { self.fp } else { self.this };
        let slot = self.b.ins().iadd_imm(base, i64::from(off));
        if self.g.m.pous[self.p].vars[v].storage == Storage::Ref {
            let p = self.native(slot);
            let a = self.b.ins().load(I32, MemFlags::new(), p, 0);
            self.b.ins().uextend(I64, a)
        } else {
            slot
        }
    }

    /// A place with every bounds check done.
    fn place(&mut self, p: &Place) -> Result<PlaceAt, Error> {
        let (pl, pending) = self.place_lazy(p)?;
        if let Some(c) = pending {
            self.index_check(c);
        }
        Ok(pl)
    }

    fn index_check(&mut self, (i, lo, hi, site, unsigned): IndexCheck) {
        let below = self.b.ins().icmp_imm(IntCC::SignedLessThan, i, lo);
        let above = self.b.ins().icmp_imm(IntCC::SignedGreaterThan, i, hi);
        let out = self.b.ins().bor(below, above);
        let outer = std::mem::replace(&mut self.site, site);
        let lo = self.iconst(I64, lo);
        let hi = self.iconst(I64, hi);
        let flags = if unsigned { RANGE_VALUE_UNSIGNED } else { 0 };
        self.range_fault_if(out, FaultKind::IndexOutOfBounds, [i, lo, hi], flags);
        self.site = outer;
    }

    /// [`Self::fault_if`] for a value outside its range: on the way to
    /// the fault exit the value and the bounds (64-bit patterns) and
    /// `flags` (`RANGE_*`) are stored in the context.
    fn range_fault_if(&mut self, cond: CVal, kind: FaultKind, values: [CVal; 3], flags: i64) {
        let fail = self.b.create_block();
        let cont = self.b.create_block();
        self.b.set_cold_block(fail);
        self.b.ins().brif(cond, fail, &[], cont, &[]);
        self.b.seal_block(fail);
        self.b.seal_block(cont);
        self.b.switch_to_block(fail);
        for (k, v) in values.into_iter().enumerate() {
            self.b
                .ins()
                .store(MemFlags::trusted(), v, self.ctx, CTX_RANGE + 8 * k as i32);
        }
        let f = self.iconst(I32, flags | RANGE_KNOWN);
        self.b
            .ins()
            .store(MemFlags::trusted(), f, self.ctx, CTX_RANGE_FLAGS);
        let k = self.iconst(I32, i64::from(kind.code()));
        let s = self.iconst(I32, i64::from(self.site));
        self.b.ins().jump(self.fault_block, &[k.into(), s.into()]);
        self.b.switch_to_block(cont);
    }

    /// A place, and the bounds check the VM leaves to the load or store
    /// of the element (`ldelem`/`stelem`): the one index of an array at a
    /// fixed place. The other checks are made where the VM makes them (an
    /// index is checked when the next one has been evaluated, or at once
    /// behind a reference), so faults come in the VM's order.
    fn place_lazy(&mut self, p: &Place) -> Result<(PlaceAt, Option<IndexCheck>), Error> {
        let m = self.g.m;
        let mut pending: Option<IndexCheck> = None;
        // Whether the address so far is a fixed place (not behind a
        // reference or a checked index).
        let mut fixed = match &p.root {
            Root::Var(v) => m.pous[self.p].vars[*v].storage != Storage::Ref,
            _ => true,
        };
        let mut addr = match &p.root {
            Root::Var(v) => self.var_addr(*v),
            Root::Global(g) => {
                let a = self
                    .g
                    .d
                    .global_offset(*g)
                    .ok_or_else(|| internal("a global without a place"))?;
                self.iconst(I64, i64::from(a))
            }
            Root::Direct(a) => {
                let o = self
                    .g
                    .d
                    .io_offset(a)
                    .ok_or_else(|| internal(format!("{a} without a process image slot")))?;
                self.iconst(I64, i64::from(o))
            }
            // The running function block's instance.
            Root::This => self.this,
            Root::Deref(r) => {
                // The address, checked not to be NULL (as the VM does).
                let (at, r) = r.located();
                let v = self.expr_s(r)?;
                let null = self.b.ins().icmp_imm(IntCC::Equal, v, 0);
                // A fault at the `^`.
                let outer = self.site;
                if let Some(at) = at {
                    self.site = self.site_of(at);
                }
                self.fault_if(null, FaultKind::NullReference);
                self.site = outer;
                fixed = false;
                self.b.ins().uextend(I64, v)
            }
        };
        // The native pointer, built beside the model address as the
        // native address of the root (a function parameter plus the
        // memory base: invariant, hoisted out of loops), a constant offset
        // (fields, constant indices and every `-lo * stride` folded
        // together) and the index terms (`i * stride`): a form the x86
        // back end makes one addressing mode of.
        let (mut n_root, mut n_k) = match &p.root {
            Root::Var(v) if fixed => {
                let lay = &self.g.l.pous[self.p];
                let (off, in_frame) = (lay.offsets[*v], lay.in_frame[*v]);
                let r = if in_frame { self.fp } else { self.this };
                (self.b.ins().iadd(self.base, r), i64::from(off))
            }
            Root::This => (self.b.ins().iadd(self.base, self.this), 0),
            Root::Global(g) => match self.g.d.global_offset(*g) {
                Some(a) => (self.base, i64::from(a)),
                None => (self.native(addr), 0),
            },
            Root::Direct(a) => match self.g.d.io_offset(a) {
                Some(o) => (self.base, i64::from(o)),
                None => (self.native(addr), 0),
            },
            _ => (self.native(addr), 0),
        };
        let mut n_terms: Vec<CVal> = Vec::new();
        let mut ty = match &p.root {
            Root::Var(v) => m.pous[self.p].var(*v).ty,
            Root::Global(g) => m.globals[*g].ty,
            Root::Direct(a) => m.addr_type(a),
            Root::Deref(r) => m.types.ref_target(r.ty).unwrap_or(TypeId::ERROR),
            Root::This => p.ty,
        };
        let mut part = None;
        for proj in &p.proj {
            match proj {
                Proj::Field(i) => {
                    let off = self.g.l.field_offset(ty, *i);
                    addr = self.b.ins().iadd_imm(addr, i64::from(off));
                    n_k = n_k.wrapping_add(i64::from(off));
                    ty = match m.types.kind(ty) {
                        TypeKind::Struct { fields } => fields
                            .get(*i as usize)
                            .map(|f| f.ty)
                            .ok_or_else(|| internal("a field out of its struct"))?,
                        _ => return Err(internal("a field of a non-struct")),
                    };
                }
                Proj::FbVar(fb, v) => {
                    let off = self.g.l.var_offset(*fb, *v);
                    addr = self.b.ins().iadd_imm(addr, i64::from(off));
                    n_k = n_k.wrapping_add(i64::from(off));
                    let var = m.pous[*fb].var(*v);
                    ty = var.ty;
                    if var.storage == Storage::Ref {
                        // Through the slot (as the VM does): an in-out's is
                        // NULL until a call of the instance binds it.
                        let p = self.native(addr);
                        let a = self.b.ins().load(I32, MemFlags::new(), p, 0);
                        if var.section == Section::InOut {
                            let null = self.b.ins().icmp_imm(IntCC::Equal, a, 0);
                            self.fault_if(null, FaultKind::NullReference);
                        }
                        addr = self.b.ins().uextend(I64, a);
                        fixed = false;
                        n_root = self.native(addr);
                        n_k = 0;
                        n_terms.clear();
                    }
                }
                Proj::Index(idx) => {
                    let (dims, elem) = match m.types.kind(ty) {
                        TypeKind::Array { dims, elem } => (dims.clone(), *elem),
                        _ => return Err(internal("indexing a non-array")),
                    };
                    let stride = self.g.l.stride(&m.types, ty);
                    let counts: Vec<i128> = dims.iter().map(|(l, h)| h - l + 1).collect();
                    let mut mults = vec![i128::from(stride); dims.len()];
                    for k in (0..dims.len().saturating_sub(1)).rev() {
                        mults[k] = mults[k + 1] * counts[k + 1];
                    }
                    let all_const = idx
                        .iter()
                        .all(|(e, _, _)| matches!(e.unlocated().kind, ExprKind::Const(_)));
                    if all_const {
                        let mut off: i128 = 0;
                        for (k, (e, lo, _)) in idx.iter().enumerate() {
                            if let ExprKind::Const(Value::Int(i)) = &e.unlocated().kind {
                                off += (i - lo) * mults[k];
                            }
                        }
                        addr = self.b.ins().iadd_imm(addr, off.max(0) as i64);
                        n_k = n_k.wrapping_add(off.max(0) as i64);
                    } else {
                        for (k, (e, lo, hi)) in idx.iter().enumerate() {
                            // An index range analysis proves needs no check.
                            let proven = self.proven.contains(e)
                                || self.fast.as_ref().is_some_and(|v| v.covers(e));
                            // A checked index reports its own position.
                            let (at, e) = e.located();
                            let site = match at {
                                Some(at) => self.site_of(at),
                                None => self.site,
                            };
                            let unsigned = matches!(
                                self.scalar(e.ty),
                                Some(ElemType::Ulint | ElemType::Lword)
                            );
                            let i = self.index_value(e)?;
                            let lo = (*lo).clamp(i64::MIN as i128, i64::MAX as i128) as i64;
                            let hi = (*hi).clamp(i64::MIN as i128, i64::MAX as i128) as i64;
                            if proven {
                                // A check that cannot fail: leaving it out
                                // changes no fault's order.
                                fixed = false;
                            } else if fixed {
                                pending = Some((i, lo, hi, site, unsigned));
                                fixed = false;
                            } else {
                                if let Some(c) = pending.take() {
                                    self.index_check(c);
                                }
                                self.index_check((i, lo, hi, site, unsigned));
                            }
                            let rel = self.b.ins().iadd_imm(i, lo.wrapping_neg());
                            let mult = mults[k].clamp(0, i64::MAX as i128) as i64;
                            let off = self.b.ins().imul_imm(rel, mult);
                            addr = self.b.ins().iadd(addr, off);
                            // (i - lo) * mult = i * mult - lo * mult, in
                            // wrapping 64-bit arithmetic as the address.
                            n_k = n_k.wrapping_sub(lo.wrapping_mul(mult));
                            let term = if mult == 1 {
                                i
                            } else if mult > 0 && (mult as u64).is_power_of_two() {
                                self.b.ins().ishl_imm(i, i64::from(mult.trailing_zeros()))
                            } else {
                                self.b.ins().imul_imm(i, mult)
                            };
                            n_terms.push(term);
                        }
                    }
                    ty = if idx.len() < dims.len() { p.ty } else { elem };
                }
                Proj::Part(size, index) => {
                    let width = self.scalar(ty).map(elem_size).unwrap_or(8) * 8;
                    part = Some((width, *size, *index));
                }
            }
        }
        let mut ptr = self.b.ins().iadd_imm(n_root, n_k);
        for t in n_terms {
            ptr = self.b.ins().iadd(ptr, t);
        }
        Ok((
            PlaceAt {
                addr,
                part,
                ptr: Some(ptr),
            },
            pending,
        ))
    }

    /// An integer index as a signed 64-bit value.
    fn index_value(&mut self, e: &Expr) -> Result<CVal, Error> {
        let t = self
            .scalar(e.ty)
            .ok_or_else(|| internal("an index that is not an integer"))?;
        let v = self.expr_s(e)?;
        Ok(self.widen_i64(v, t))
    }

    fn widen_i64(&mut self, v: CVal, t: ElemType) -> CVal {
        match elem_size(t) {
            8 => v,
            _ if is_signed(t) => self.b.ins().sextend(I64, v),
            _ => self.b.ins().uextend(I64, v),
        }
    }

    fn load_place(&mut self, pl: &PlaceAt, ty: TypeId) -> Result<V, Error> {
        let ptr = match pl.ptr {
            Some(p) => p,
            None => self.native(pl.addr),
        };
        if let Some((width, size, index)) = pl.part {
            let w = self
                .b
                .ins()
                .load(int_of_bytes(width / 8), MemFlags::new(), ptr, 0);
            let w = if width / 8 == 8 {
                w
            } else {
                self.b.ins().uextend(I64, w)
            };
            let bits = size.bits();
            let shift = index.saturating_mul(bits);
            let v = if shift >= 64 {
                self.iconst(I64, 0)
            } else {
                let mask = if bits >= 64 {
                    u64::MAX
                } else {
                    (1u64 << bits) - 1
                };
                let s = self.b.ins().ushr_imm(w, i64::from(shift));
                self.b.ins().band_imm(s, mask as i64)
            };
            let rt = self
                .scalar(ty)
                .map(cl_type)
                .unwrap_or(int_of_bytes(bits.max(8) / 8));
            return Ok(V::S(if rt == I64 {
                v
            } else {
                self.b.ins().ireduce(rt, v)
            }));
        }
        Ok(match self.scalar(ty) {
            Some(e) => V::S(self.load_scalar(e, ptr)),
            None => V::M(ptr),
        })
    }

    /// Stores a value of type `vt` into a place of type `pt`.
    fn store(&mut self, pl: &PlaceAt, v: V, vt: TypeId, pt: TypeId) -> Result<(), Error> {
        let ptr = match pl.ptr {
            Some(p) => p,
            None => self.native(pl.addr),
        };
        if let Some((width, size, index)) = pl.part {
            let V::S(x) = v else {
                return Err(internal("a bit part of a non-scalar"));
            };
            let bits = size.bits();
            let shift = index.saturating_mul(bits);
            if shift >= 64 {
                return Ok(());
            }
            let wt = int_of_bytes(width / 8);
            let w = self.b.ins().load(wt, MemFlags::new(), ptr, 0);
            let w = if wt == I64 {
                w
            } else {
                self.b.ins().uextend(I64, w)
            };
            let xt = self.b.func.dfg.value_type(x);
            let x = if xt == I64 {
                x
            } else if xt.is_int() {
                self.b.ins().uextend(I64, x)
            } else {
                return Err(internal("a bit part of a real"));
            };
            let mask = if bits >= 64 {
                u64::MAX
            } else {
                (1u64 << bits) - 1
            };
            let keep = self.b.ins().band_imm(w, !(mask << shift) as i64);
            let xm = self.b.ins().band_imm(x, mask as i64);
            let xs = self.b.ins().ishl_imm(xm, i64::from(shift));
            let nw = self.b.ins().bor(keep, xs);
            let nw = if wt == I64 {
                nw
            } else {
                self.b.ins().ireduce(wt, nw)
            };
            self.b.ins().store(MemFlags::new(), nw, ptr, 0);
            return Ok(());
        }
        let _ = vt;
        match self.g.m.types.kind(pt) {
            TypeKind::String { wide, len } => {
                let (wide, len) = (*wide, *len);
                let src = self.spill(v);
                let f = self.func(self.g.copy_fn);
                let cap = self.iconst(I32, i64::from(len));
                let unit = self.iconst(I32, if wide { 2 } else { 1 });
                self.b.ins().call(f, &[ptr, src, cap, unit]);
            }
            _ => match v {
                V::S(x) => {
                    self.b.ins().store(MemFlags::new(), x, ptr, 0);
                }
                V::M(src) => {
                    let size = self.size_of(pt);
                    self.copy(ptr, src, size);
                }
            },
        }
        Ok(())
    }

    // ----- expressions --------------------------------------------------------------

    fn expr_s(&mut self, e: &Expr) -> Result<CVal, Error> {
        match self.expr(e)? {
            V::S(v) => Ok(v),
            V::M(_) => Err(internal("a scalar expected")),
        }
    }

    fn expr(&mut self, e: &Expr) -> Result<V, Error> {
        match &e.kind {
            ExprKind::Const(v) => self.konst(e.ty, v),
            ExprKind::Load(p) => {
                if let Some((var, _)) = self.reg_of(p) {
                    return Ok(V::S(self.b.use_var(var)));
                }
                let pl = self.place(p)?;
                self.load_place(&pl, e.ty)
            }
            ExprKind::Null => Ok(V::S(self.iconst(I32, 0))),
            ExprKind::Ref(p) => {
                let pl = self.place(p)?;
                Ok(V::S(self.b.ins().ireduce(I32, pl.addr)))
            }
            ExprKind::Unary(op, x) => {
                let a = self.expr(x)?;
                let n = self.scalar(x.ty);
                match (op, n, a) {
                    (UnOp::Not, Some(ElemType::Bool), V::S(a)) => {
                        Ok(V::S(self.b.ins().icmp_imm(IntCC::Equal, a, 0)))
                    }
                    (UnOp::Not, Some(t), V::S(a)) if !is_float(t) => Ok(V::S(self.b.ins().bnot(a))),
                    (UnOp::Neg, Some(t), V::S(a)) if is_float(t) => Ok(V::S(self.b.ins().fneg(a))),
                    (UnOp::Neg, Some(t), V::S(a)) if t != ElemType::Bool => {
                        Ok(V::S(self.b.ins().ineg(a)))
                    }
                    _ => self.generic(StdOp::Unary(*op), &[(a, x.ty)], e.ty),
                }
            }
            ExprKind::Binary(op, x, y) => {
                let a = self.expr(x)?;
                let b = self.expr(y)?;
                match self.native_binary(*op, x.ty, y.ty, e.ty, a, b)? {
                    Some(v) => Ok(V::S(v)),
                    None => self.generic(StdOp::Binary(*op), &[(a, x.ty), (b, y.ty)], e.ty),
                }
            }
            ExprKind::Convert(x) => {
                let a = self.expr(x)?;
                self.convert(a, x.ty, e.ty)
            }
            ExprKind::Check { value, lo, hi } => {
                let v = self.expr_s(value)?;
                let t = self
                    .scalar(e.ty)
                    .ok_or_else(|| internal("a subrange check of a non-scalar"))?;
                let signed = is_signed(t);
                let (lt, gt) = if signed {
                    (IntCC::SignedLessThan, IntCC::SignedGreaterThan)
                } else {
                    (IntCC::UnsignedLessThan, IntCC::UnsignedGreaterThan)
                };
                let ct = cl_type(t);
                let lo_v = self.iconst(ct, *lo as i64);
                let hi_v = self.iconst(ct, *hi as i64);
                let below = self.b.ins().icmp(lt, v, lo_v);
                let above = self.b.ins().icmp(gt, v, hi_v);
                let out = self.b.ins().bor(below, above);
                // The value and bounds as 64-bit patterns of their kind.
                let wide = |g: &mut Self, x: CVal| {
                    if ct == I64 {
                        x
                    } else if signed {
                        g.b.ins().sextend(I64, x)
                    } else {
                        g.b.ins().uextend(I64, x)
                    }
                };
                let (v64, lo64, hi64) = (wide(self, v), wide(self, lo_v), wide(self, hi_v));
                let flags = if signed {
                    0
                } else {
                    RANGE_VALUE_UNSIGNED | RANGE_BOUNDS_UNSIGNED
                };
                self.range_fault_if(out, FaultKind::SubrangeViolation, [v64, lo64, hi64], flags);
                Ok(V::S(v))
            }
            ExprKind::CallFn {
                func,
                inputs,
                inouts,
                outputs,
            } => self.call_fn(*func, inputs, inouts, outputs, e.ty),
            ExprKind::Intrinsic { func, args } => {
                let mut ops = Vec::with_capacity(args.len());
                for a in args {
                    // (A call's result is already a copy of its own.)
                    let v = self.expr(a)?;
                    ops.push((v, a.ty));
                }
                let op = match func {
                    stc_values::Intrinsic::Trunc { .. } => StdOp::Trunc,
                    f => StdOp::Call(*f),
                };
                self.generic(op, &ops, e.ty)
            }
            ExprKind::CurTime => Ok(V::S(self.b.ins().load(
                I64,
                MemFlags::trusted(),
                self.ctx,
                CTX_NOW,
            ))),
            ExprKind::Located { line, col, expr } => {
                let outer = self.site;
                self.site = self.site_of((*line, *col));
                let r = self.expr(expr);
                self.site = outer;
                r
            }
        }
    }

    fn konst(&mut self, t: TypeId, v: &Value) -> Result<V, Error> {
        if let Some(e) = self.scalar(t) {
            let ct = cl_type(e);
            return Ok(V::S(match (e, v) {
                (ElemType::Real, Value::Real(r)) => self.b.ins().f32const(*r as f32),
                (ElemType::Lreal, Value::Real(r)) => self.b.ins().f64const(*r),
                (ElemType::Real, Value::Int(i)) => self.b.ins().f32const(*i as f32),
                (ElemType::Lreal, Value::Int(i)) => self.b.ins().f64const(*i as f64),
                (_, Value::Int(i)) => self.iconst(ct, *i as i64),
                (_, Value::Bool(b)) => self.iconst(ct, i64::from(*b)),
                _ => return Err(Error::Unsupported(format!("the constant {v:?}"))),
            }));
        }
        // Anything else: its bytes in the constant pool.
        let size = self.size_of(t) as usize;
        let mut bytes = vec![0u8; size];
        let ok = match self.g.m.types.kind(t) {
            TypeKind::String { wide, len } => {
                stc_ir::model::repr::write_string(&mut bytes, 0, *wide, *len, v)
            }
            _ => false,
        };
        if !ok {
            return Err(Error::Unsupported(format!("the constant {v:?}")));
        }
        while !self.g.consts.len().is_multiple_of(8) {
            self.g.consts.push(0);
        }
        let at = self.g.const_base + self.g.consts.len() as u64;
        self.g.consts.extend_from_slice(&bytes);
        Ok(V::M(self.native_const(at)))
    }

    /// Converts a value between types: natively between plain numerics (the
    /// VM's `cvt`), else through `stc_values`.
    fn convert(&mut self, a: V, from_t: TypeId, to_t: TypeId) -> Result<V, Error> {
        if matches!(self.g.m.types.kind(from_t), TypeKind::Ref(_))
            && matches!(self.g.m.types.kind(to_t), TypeKind::Ref(_))
        {
            // A reference seen as another (pointers): the same address.
            return Ok(a);
        }
        let (from, to) = (self.g.m.types.scalar(from_t), self.g.m.types.scalar(to_t));
        match (from, to, a) {
            (Some(f), Some(t), _) if f == t => match (a, self.g.m.types.kind(to_t)) {
                (V::M(p), TypeKind::String { wide, len }) => {
                    // A copy truncated to the target's capacity.
                    let (wide, len) = (*wide, *len);
                    let unit = if wide { 2 } else { 1 };
                    let d = self.stack_slot(2 + len * unit);
                    let f = self.func(self.g.copy_fn);
                    let cap = self.iconst(I32, i64::from(len));
                    let u = self.iconst(I32, i64::from(unit));
                    self.b.ins().call(f, &[d, p, cap, u]);
                    Ok(V::M(d))
                }
                _ => Ok(a),
            },
            (Some(f), Some(t), V::S(x)) if plain_numeric(Some(f)) && plain_numeric(Some(t)) => {
                Ok(V::S(self.cvt(x, f, t)))
            }
            _ => self.generic(StdOp::Convert, &[(a, from_t)], to_t),
        }
    }

    /// The VM's `cvt` between plain numeric scalars.
    fn cvt(&mut self, x: CVal, f: ElemType, t: ElemType) -> CVal {
        if is_float(f) {
            let x64 = if f == ElemType::Real {
                self.b.ins().fpromote(F64, x)
            } else {
                x
            };
            match t {
                ElemType::Real => {
                    if f == ElemType::Real {
                        x
                    } else {
                        self.b.ins().fdemote(F32, x)
                    }
                }
                ElemType::Lreal => x64,
                ElemType::Bool => {
                    let z = self.b.ins().f64const(0.0);
                    self.b.ins().fcmp(FloatCC::NotEqual, x64, z)
                }
                _ => {
                    let r = self.b.ins().nearest(x64);
                    let (lo, hi) = int_range(t);
                    let lo_f = self.b.ins().f64const(lo as f64);
                    let hi_f = self.b.ins().f64const((hi + 1) as f64);
                    let ge = self.b.ins().fcmp(FloatCC::GreaterThanOrEqual, r, lo_f);
                    let lt = self.b.ins().fcmp(FloatCC::LessThan, r, hi_f);
                    let ok = self.b.ins().band(ge, lt);
                    let bad = self.b.ins().bxor_imm(ok, 1);
                    self.fault_if(bad, FaultKind::Conversion);
                    let i = if matches!(t, ElemType::Ulint | ElemType::Lword) {
                        self.b.ins().fcvt_to_uint(I64, r)
                    } else {
                        self.b.ins().fcvt_to_sint(I64, r)
                    };
                    let ct = cl_type(t);
                    if ct == I64 {
                        i
                    } else {
                        self.b.ins().ireduce(ct, i)
                    }
                }
            }
        } else {
            let i = self.widen_i64(x, f);
            let unsigned64 = !is_signed(f) && elem_size(f) == 8;
            match t {
                ElemType::Real | ElemType::Lreal => {
                    let ft = cl_type(t);
                    if unsigned64 {
                        self.b.ins().fcvt_from_uint(ft, i)
                    } else {
                        self.b.ins().fcvt_from_sint(ft, i)
                    }
                }
                ElemType::Bool => self.b.ins().icmp_imm(IntCC::NotEqual, i, 0),
                _ => {
                    let ct = cl_type(t);
                    if ct == I64 {
                        i
                    } else {
                        self.b.ins().ireduce(ct, i)
                    }
                }
            }
        }
    }

    /// Arithmetic and comparisons the VM does natively; `None` for the
    /// others (through `stc_values`).
    fn native_binary(
        &mut self,
        op: BinOp,
        lt: TypeId,
        rt: TypeId,
        res: TypeId,
        a: V,
        b: V,
    ) -> Result<Option<CVal>, Error> {
        let (Some(ls), Some(rs), V::S(a), V::S(b)) = (self.scalar(lt), self.scalar(rt), a, b)
        else {
            return Ok(None);
        };
        if ls != rs {
            return Ok(None);
        }
        let cmp = matches!(
            op,
            BinOp::Eq | BinOp::Ne | BinOp::Lt | BinOp::Le | BinOp::Gt | BinOp::Ge
        );
        if !cmp
            && (self.scalar(res) != Some(ls)
                || matches!(
                    ls,
                    ElemType::Tod
                        | ElemType::Ltod
                        | ElemType::Date
                        | ElemType::Ldate
                        | ElemType::Dt
                        | ElemType::Ldt
                ))
        {
            return Ok(None);
        }
        let fl = is_float(ls);
        let signed = is_signed(ls);
        Ok(Some(match op {
            BinOp::Eq | BinOp::Ne | BinOp::Lt | BinOp::Le | BinOp::Gt | BinOp::Ge => {
                if fl {
                    let cc = match op {
                        BinOp::Eq => FloatCC::Equal,
                        BinOp::Ne => FloatCC::NotEqual,
                        BinOp::Lt => FloatCC::LessThan,
                        BinOp::Le => FloatCC::LessThanOrEqual,
                        BinOp::Gt => FloatCC::GreaterThan,
                        _ => FloatCC::GreaterThanOrEqual,
                    };
                    self.b.ins().fcmp(cc, a, b)
                } else {
                    let cc = match (op, signed) {
                        (BinOp::Eq, _) => IntCC::Equal,
                        (BinOp::Ne, _) => IntCC::NotEqual,
                        (BinOp::Lt, true) => IntCC::SignedLessThan,
                        (BinOp::Le, true) => IntCC::SignedLessThanOrEqual,
                        (BinOp::Gt, true) => IntCC::SignedGreaterThan,
                        (BinOp::Ge, true) => IntCC::SignedGreaterThanOrEqual,
                        (BinOp::Lt, false) => IntCC::UnsignedLessThan,
                        (BinOp::Le, false) => IntCC::UnsignedLessThanOrEqual,
                        (BinOp::Gt, false) => IntCC::UnsignedGreaterThan,
                        _ => IntCC::UnsignedGreaterThanOrEqual,
                    };
                    self.b.ins().icmp(cc, a, b)
                }
            }
            _ if ls == ElemType::Bool && !matches!(op, BinOp::And | BinOp::Or | BinOp::Xor) => {
                return Ok(None)
            }
            BinOp::Add if fl => self.b.ins().fadd(a, b),
            BinOp::Sub if fl => self.b.ins().fsub(a, b),
            BinOp::Mul if fl => self.b.ins().fmul(a, b),
            BinOp::Div if fl => self.b.ins().fdiv(a, b),
            BinOp::Add => self.b.ins().iadd(a, b),
            BinOp::Sub => self.b.ins().isub(a, b),
            BinOp::Mul => self.b.ins().imul(a, b),
            BinOp::Div | BinOp::Mod if !fl => {
                // A constant divisor other than 0 needs no test (Cranelift
                // folds the comparison, not the branch on it).
                if self.const_of(b).is_none_or(|d| d == 0) {
                    let z = self.b.ins().icmp_imm(IntCC::Equal, b, 0);
                    self.fault_if(z, FaultKind::DivisionByZero);
                }
                let div = op == BinOp::Div;
                if signed {
                    // wrapping_div/rem: MIN / -1 is MIN, MIN % -1 is 0 (a
                    // divisor of -1 never reaches the machine division).
                    let t = self.b.func.dfg.value_type(b);
                    let minus1 = self.iconst(t, -1);
                    let m1 = self.b.ins().icmp(IntCC::Equal, b, minus1);
                    let one = self.iconst(t, 1);
                    let safe_b = self.b.ins().select(m1, one, b);
                    let q = if div {
                        self.b.ins().sdiv(a, safe_b)
                    } else {
                        self.b.ins().srem(a, safe_b)
                    };
                    let alt = if div {
                        self.b.ins().ineg(a)
                    } else {
                        self.iconst(t, 0)
                    };
                    self.b.ins().select(m1, alt, q)
                } else if div {
                    self.b.ins().udiv(a, b)
                } else {
                    self.b.ins().urem(a, b)
                }
            }
            BinOp::And | BinOp::Or | BinOp::Xor if !fl => match op {
                BinOp::And => self.b.ins().band(a, b),
                BinOp::Or => self.b.ins().bor(a, b),
                _ => self.b.ins().bxor(a, b),
            },
            _ => return Ok(None),
        }))
    }

    // ----- calls --------------------------------------------------------------------

    /// A value kept safe across later evaluation: what points into a
    /// callee's frame (a call's result) is copied to the native stack.
    fn keep(&mut self, v: V, ty: TypeId, from_call: bool) -> V {
        if matches!(self.g.m.types.kind(ty), TypeKind::Void | TypeKind::Error) {
            return v;
        }
        match v {
            V::M(p) if from_call => {
                let size = self.size_of(ty);
                let d = self.stack_slot(size);
                self.copy(d, p, size);
                V::M(d)
            }
            v => v,
        }
    }

    fn callee_frame(&mut self) -> CVal {
        let own = self.g.frame_size[self.p.index()];
        self.b.ins().iadd_imm(self.fp, own as i64)
    }

    fn call_body(&mut self, callee: PouId, this: CVal, frame: CVal) -> Result<(), Error> {
        self.step();
        let id =
            self.g.ids[callee.index()].ok_or_else(|| internal("a call of a POU not compiled"))?;
        let f = self.func(id);
        // The callee may observe (through a reference) or change any
        // variable: memory is made exact before, registers reloaded after.
        self.flush();
        let call = self.b.ins().call(f, &[self.ctx, self.base, this, frame]);
        let st = self.b.inst_results(call)[0];
        let cont = self.b.create_block();
        self.b.ins().brif(st, self.prop_block, &[], cont, &[]);
        self.b.seal_block(cont);
        self.b.switch_to_block(cont);
        self.reload();
        Ok(())
    }

    fn call_fn(
        &mut self,
        func: PouId,
        inputs: &[(VarId, Expr)],
        inouts: &[(VarId, Place)],
        outputs: &[stc_ir::Output],
        ty: TypeId,
    ) -> Result<V, Error> {
        let m = self.g.m;
        let callee = &m.pous[func];
        let lay = &self.g.l.pous[func];
        // Every input given, in the callee's order, then the in-outs'
        // addresses; then the frame is written (a call in an argument uses
        // the same frame area).
        let mut given = Vec::new();
        for var in callee.vars.ids() {
            if callee.vars[var].section != Section::Input {
                continue;
            }
            if let Some((_, e)) = inputs.iter().find(|(p, _)| *p == var) {
                let v = self.expr(e)?;
                let v = self.keep(v, e.ty, stc_ir::visit::has_call(e));
                given.push((var, v, e.ty));
            }
        }
        let mut refs = Vec::new();
        for (v, p) in inouts {
            let pl = self.place(p)?;
            refs.push((*v, pl.addr));
        }
        let cf = self.callee_frame();
        if let Some((src, len)) = self.g.templates[func.index()] {
            let s = self.native_const(u64::from(src));
            let d = self.native(cf);
            self.copy(d, s, len);
        }
        for (var, v, vt) in given {
            let addr = self.b.ins().iadd_imm(cf, i64::from(lay.offsets[var]));
            let pl = PlaceAt {
                addr,
                part: None,
                ptr: None,
            };
            self.store(&pl, v, vt, callee.vars[var].ty)?;
        }
        for (var, a) in refs {
            let slot = self.b.ins().iadd_imm(cf, i64::from(lay.offsets[var]));
            let p = self.native(slot);
            let a32 = self.b.ins().ireduce(I32, a);
            self.b.ins().store(MemFlags::new(), a32, p, 0);
        }
        let this = self.iconst(I64, 0);
        self.call_body(func, this, cf)?;
        // The result is taken before the outputs are copied: a call in the
        // index of an output's target reuses this frame.
        let result = match callee.result {
            Some(r) => {
                let addr = self.b.ins().iadd_imm(cf, i64::from(lay.offsets[r]));
                let v = self.load_place(
                    &PlaceAt {
                        addr,
                        part: None,
                        ptr: None,
                    },
                    callee.vars[r].ty,
                )?;
                self.keep(v, ty, true)
            }
            None => V::S(self.iconst(I8, 0)),
        };
        for o in outputs {
            let var = &callee.vars[o.var];
            let addr = self.b.ins().iadd_imm(cf, i64::from(lay.offsets[o.var]));
            self.copy_out(addr, var.ty, o)?;
        }
        Ok(result)
    }

    /// Copies an output parameter at model address `src` into its `=>`
    /// target (negating, converting).
    fn copy_out(&mut self, src: CVal, src_ty: TypeId, o: &stc_ir::Output) -> Result<(), Error> {
        let mut v = self.load_place(
            &PlaceAt {
                addr: src,
                part: None,
                ptr: None,
            },
            src_ty,
        )?;
        if o.negated {
            if let V::S(x) = v {
                v = V::S(self.b.ins().icmp_imm(IntCC::Equal, x, 0));
            }
        }
        // A call in the target's index may reuse the frame the value is in.
        if stc_ir::visit::place_has_call(&o.target) {
            v = self.keep(v, src_ty, true);
        }
        let tt = o.target.ty;
        let (f, t) = (self.g.m.types.scalar(src_ty), self.g.m.types.scalar(tt));
        let mut vt = src_ty;
        if f != t
            && f.is_some()
            && t.is_some()
            && !matches!(self.g.m.types.kind(tt), TypeKind::String { .. })
        {
            v = self.convert(v, src_ty, tt)?;
            vt = tt;
        }
        let pl = self.place(&o.target)?;
        self.store(&pl, v, vt, tt)
    }

    fn call_fb(
        &mut self,
        instance: &Place,
        fb: PouId,
        inputs: &[(VarId, Expr)],
        inouts: &[(VarId, Place)],
        outputs: &[stc_ir::Output],
    ) -> Result<(), Error> {
        let m = self.g.m;
        let inst = self.place(instance)?.addr;
        let fbp = &m.pous[fb];
        let lay = &self.g.l.pous[fb];
        for (v, e) in inputs {
            let val = self.expr(e)?;
            let addr = self.b.ins().iadd_imm(inst, i64::from(lay.offsets[*v]));
            self.store(
                &PlaceAt {
                    addr,
                    part: None,
                    ptr: None,
                },
                val,
                e.ty,
                fbp.var(*v).ty,
            )?;
        }
        for (v, p) in inouts {
            let a = self.place(p)?.addr;
            let slot = self.b.ins().iadd_imm(inst, i64::from(lay.offsets[*v]));
            let sp = self.native(slot);
            let a32 = self.b.ins().ireduce(I32, a);
            self.b.ins().store(MemFlags::new(), a32, sp, 0);
        }
        let cf = self.callee_frame();
        self.call_body(fb, inst, cf)?;
        for o in outputs {
            let var = fbp.var(o.var);
            let addr = self.b.ins().iadd_imm(inst, i64::from(lay.offsets[o.var]));
            self.copy_out(addr, var.ty, o)?;
        }
        Ok(())
    }
}

/// The position of a POU's declaration, for faults outside statements.
trait SpanLineCol {
    fn span_line_col(&self) -> (u32, u32);
}

impl SpanLineCol for stc_ir::Pou {
    fn span_line_col(&self) -> (u32, u32) {
        (
            self.body.first().map_or(0, |s| s.line),
            self.body.first().map_or(0, |s| s.col),
        )
    }
}

/// Which variables of POU `p` the JIT holds in registers inside one
/// execution of its body ([`stc_ir::visit::register_vars`]): scalars
/// (a reference is a 4-byte address) assigned only values of their own
/// width.
fn promotable(
    m: &Module,
    p: PouId,
    scalar: impl Fn(TypeId) -> Option<ElemType>,
) -> (Vec<bool>, Vec<bool>) {
    stc_ir::visit::register_vars(m, p, &|t| scalar(t).is_some(), &|a, b| match (
        scalar(a),
        scalar(b),
    ) {
        (Some(a), Some(b)) => cl_type(a) == cl_type(b),
        _ => false,
    })
}
