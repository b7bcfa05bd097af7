//! The bytecode compiler: IR to [`Image`].
//!
//! Data first: every process-image slot, global and program instance gets
//! its place in the data area with its initial value (references bound to
//! what they refer to). Then code, one POU at a time, callees first so each
//! call knows the size of the frame it reserves for its callee. Expression
//! trees become three-address code over frame temporaries; a place whose
//! address is static is used directly as an operand, a computed one (an
//! element with a run-time index, anything behind a reference) through a
//! pointer temporary and `load`/`store`.
//!
//! `data` holds the program model's side (type descriptors, the data area
//! and its initial bytes, variable descriptors and frames); this module
//! the assembly of the image and the code of bodies.

mod data;

use rustc_hash::FxHashMap;
use stc_diagnostics::{Code, Diagnostic, Span};
use stc_ir::layout::{elem_size, Layouts, MAX_SIZE};
use stc_ir::{Expr, ExprKind, FaultKind, Module, Place, Proj, Root, Stmt, StmtKind, Storage};
use stc_sema::{PouId, Section, TypeId, TypeKind, VarId};
use stc_syntax::ast::PouKind as AstPouKind;
use stc_syntax::literal::AddrSize;
use stc_syntax::token::ElemType;
use stc_values::{BinOp, UnOp, Value};

use crate::image::*;
use crate::instr::{Instr, Op, Tgt};
use crate::num::Num;
use stc_ir::model::{Builder, ModelError};
use stc_sema::idx::{IdVec, Idx};
use std::sync::Arc;

#[derive(Debug, thiserror::Error)]
pub enum CompileError {
    /// Errors in the program found by the back end (E0901: too large for
    /// the memory model), at their declarations.
    #[error("{}", .0.first().map_or("the program cannot be compiled", |d| d.message.as_str()))]
    Diagnostics(Vec<Diagnostic>),
    #[error("{0} is not supported by the bytecode compiler yet")]
    Unsupported(String),
    /// A bug: the IR or the compiler's own tables broke an invariant.
    #[error("internal error: {0}")]
    Internal(String),
}

fn internal(what: impl Into<String>) -> CompileError {
    CompileError::Internal(what.into())
}

/// Rounds up to a multiple of `a`; every value rounded here is at most
/// [`MAX_SIZE`] (checked where it grows), so this cannot overflow.
fn align_up(x: u32, a: u32) -> u32 {
    x.div_ceil(a.max(1)) * a.max(1)
}

/// E0901 at `span`: `what` needs `size` bytes.
fn too_large(span: Span, what: String, size: u64) -> CompileError {
    CompileError::Diagnostics(vec![Diagnostic::new(
        Code::E0901,
        span,
        format!("{what} needs {size} bytes; the limit is {MAX_SIZE} bytes (1 GiB)"),
    )
    .with_label("too large for the memory model")])
}

/// A fault kind's code in `fault` instructions ([`FaultKind::code`]).
pub fn fault_code(k: FaultKind) -> u32 {
    u32::from(k.code())
}

/// The kind of a `fault` instruction's code (an unknown code, which the
/// verifier rejects, is invalid code).
pub fn fault_of_code(c: u32) -> FaultKind {
    FaultKind::from_code(c).unwrap_or(FaultKind::InvalidCode)
}

/// Where a value is: at an operand, behind a pointer held in a temporary,
/// or in an element of an array at a fixed place (`base` is the array
/// moved by the offset inside the element), not yet computed: a scalar
/// there is read and written by one `ldelem`/`stelem`.
#[derive(Clone, Copy, Debug)]
enum Loc {
    At(Op),
    Ptr {
        ptr: Op,
        off: u32,
    },
    /// `at`: the index's own position, which its check reports.
    Elem {
        base: Op,
        idx: Op,
        desc: u32,
        at: Option<(u32, u32)>,
    },
}

/// A place: its location, and for `x.%X3` the part selected.
#[derive(Clone, Copy, Debug)]
struct PlaceLoc {
    loc: Loc,
    part: Option<(u32, AddrSize, u32)>,
}

/// The frame of the POU being compiled.
#[derive(Default)]
struct Frame {
    /// Offset of each frame variable.
    var_off: FxHashMap<VarId, u32>,
    /// Top of the temporaries.
    top: u32,
    max: u32,
    /// The end of the largest temporary that did not fit in [`MAX_SIZE`]
    /// (the POU is then reported, and its code thrown away).
    overflow: Option<u64>,
}

struct LoopCtx {
    breaks: Vec<usize>,
    continues: Vec<usize>,
}

pub struct Compiler<'a> {
    m: &'a Module,
    l: &'a Layouts,
    /// The program model with its data area (`stc_ir::model`).
    d: Builder<'a>,
    code: Vec<Instr>,
    lines: Vec<LineEntry>,
    files: Vec<String>,
    consts: Vec<u8>,
    const_map: FxHashMap<Vec<u8>, u32>,
    calls: Vec<StdCall>,
    elems: Vec<ElemDesc>,
    elem_map: FxHashMap<ElemDesc, u32>,
    pous: Vec<PouCode>,
    /// Per POU: the frame layout (set when the POU is compiled).
    frames: IdVec<PouId, Option<FrameInfo>>,
    // State of the POU being compiled.
    cur: PouId,
    /// The source position the code being emitted reports.
    pos: (u32, u32),
    frame: Frame,
    loops: Vec<LoopCtx>,
    /// The first error met where it could not be returned at once (the
    /// constant pool growing too large): no image is built after one.
    failed: Option<CompileError>,
}

#[derive(Clone)]
struct FrameInfo {
    var_off: FxHashMap<VarId, u32>,
    size: u32,
}

/// Compiles a module (without errors) to an image.
pub fn compile(m: &Module) -> Result<Image, CompileError> {
    let l = Layouts::compute(m).map_err(CompileError::Diagnostics)?;
    let d = Builder::new(m, &l).map_err(model_error)?;
    let c = Compiler {
        m,
        l: &l,
        pous: (0..m.pous.len())
            .map(|_| PouCode {
                entry: 0,
                frame_size: 0,
                frame_init_at: 0,
                frame_template: (0, 0),
            })
            .collect(),
        d,
        code: Vec::new(),
        lines: Vec::new(),
        files: Vec::new(),
        consts: Vec::new(),
        const_map: FxHashMap::default(),
        calls: Vec::new(),
        elems: Vec::new(),
        elem_map: FxHashMap::default(),
        frames: m.pous.iter().map(|_| None).collect(),
        cur: PouId(0),
        pos: (0, 0),
        frame: Frame::default(),
        loops: Vec::new(),
        failed: None,
    };
    c.run()
}

/// A model that could not be built, as the compiler's error.
fn model_error(e: ModelError) -> CompileError {
    match e {
        ModelError::Diagnostics(d) => CompileError::Diagnostics(d),
        ModelError::Internal(s) => CompileError::Internal(s),
    }
}

impl<'a> Compiler<'a> {
    fn run(mut self) -> Result<Image, CompileError> {
        // Code, callees first.
        for p in self.callee_order() {
            self.compile_pou(p)?;
        }
        if let Some(e) = self.failed.take() {
            return Err(e);
        }
        let stack_size = self.stack_need();
        let data_size = self.d.data_size();
        // The whole memory: data, constants, stack.
        let memory = u64::from(data_size) + self.consts.len() as u64 + u64::from(stack_size);
        if memory > MAX_SIZE {
            let deepest = self
                .m
                .pous
                .iter()
                .zip(&self.pous)
                .max_by_key(|(_, c)| c.frame_size)
                .map_or(Span::default(), |(p, _)| p.name_span);
            return Err(too_large(
                deepest,
                format!(
                    "the program's memory (data area {data_size} bytes, constants {} bytes, \
                     stack {stack_size} bytes for the deepest frame, this POU's)",
                    self.consts.len()
                ),
                memory,
            ));
        }
        let data = self.d.finish();
        Ok(Image {
            code: self.code,
            consts: self.consts,
            data_size,
            init: data.init,
            stack_size,
            model: Arc::new(data.model),
            pous: self.pous,
            calls: self.calls,
            elems: self.elems,
            lines: self.lines,
            files: self.files,
        })
    }

    /// Keeps the first error met where it cannot be returned at once.
    fn defer(&mut self, e: CompileError) {
        self.failed.get_or_insert(e);
    }

    // ----- constants and temporaries -------------------------------------------

    /// The offset of constant bytes in the pool. The pool grows past
    /// [`MAX_SIZE`] only for a program whose memory check fails at the end
    /// (no image is built then), so offsets are taken modulo nothing.
    fn const_bytes(&mut self, bytes: &[u8], align: u32) -> u32 {
        if let Some(&off) = self.const_map.get(bytes) {
            return off;
        }
        if self.consts.len() as u64 + bytes.len() as u64 > MAX_SIZE {
            let at = self.m.pous[self.cur].name_span;
            let size = self.consts.len() as u64 + bytes.len() as u64;
            self.defer(too_large(at, "the constant pool".into(), size));
            return 0;
        }
        let off = align_up(self.consts.len() as u32, align.max(1));
        self.consts.resize(off as usize, 0);
        self.consts.extend_from_slice(bytes);
        self.const_map.insert(bytes.to_vec(), off);
        off
    }

    /// An operand holding a constant.
    fn konst(&mut self, t: TypeId, v: &Value) -> Op {
        let bytes = self.d.value_bytes(t, v);
        let off = self.const_bytes(&bytes, 8);
        Op::abs(self.d.data_size() + off)
    }

    fn elem_desc(&mut self, d: ElemDesc) -> u32 {
        if let Some(&i) = self.elem_map.get(&d) {
            return i;
        }
        let i = self.elems.len() as u32;
        self.elems.push(d);
        self.elem_map.insert(d, i);
        i
    }

    fn const_u32(&mut self, v: u32) -> Op {
        let off = self.const_bytes(&v.to_le_bytes(), 4);
        Op::abs(self.d.data_size() + off)
    }

    /// A temporary of `size` bytes in the frame. One that does not fit in
    /// [`MAX_SIZE`] marks the frame as overflowed (the POU is reported, its
    /// code is never used) and gets offset 0.
    fn temp(&mut self, size: u32) -> Op {
        let off = align_up(self.frame.top, 8);
        let end = u64::from(off) + u64::from(size.max(1));
        if end > MAX_SIZE {
            self.frame.overflow = Some(self.frame.overflow.unwrap_or(0).max(end));
            return Op::frame(0);
        }
        self.frame.top = end as u32;
        self.frame.max = self.frame.max.max(self.frame.top);
        Op::frame(off)
    }

    fn temp_of(&mut self, t: TypeId) -> Op {
        let s = self.size_of(t);
        self.temp(s)
    }

    fn emit(&mut self, i: Instr) -> usize {
        self.code.push(i);
        self.code.len() - 1
    }

    fn here(&self) -> u32 {
        self.code.len() as u32
    }

    fn patch(&mut self, at: usize, target: u32) {
        if let Some(i) = self.code.get(at) {
            self.code[at] = i.with_target(target);
        }
    }

    fn patch_all(&mut self, jumps: &[usize], target: u32) {
        for &j in jumps {
            self.patch(j, target);
        }
    }

    /// Records that the code from here on is statement `s`'s.
    fn mark_line(&mut self, s: &Stmt) {
        self.pos = (s.line, s.col);
        self.mark_pos(self.pos);
    }

    /// Runs `f` with its code at position `at` (when given: an operation's
    /// own, [`ExprKind::Located`]), then goes back to the position before.
    fn at_pos<T>(&mut self, at: Option<(u32, u32)>, f: impl FnOnce(&mut Self) -> T) -> T {
        let Some(at) = at else {
            return f(self);
        };
        let outer = std::mem::replace(&mut self.pos, at);
        self.mark_pos(at);
        let r = f(self);
        self.pos = outer;
        self.mark_pos(outer);
        r
    }

    /// Records that the code from here on is at source position `(line, col)`.
    fn mark_pos(&mut self, (line, col): (u32, u32)) {
        let file = self
            .files
            .iter()
            .position(|f| *f == self.m.pous[self.cur].file)
            .unwrap_or(0) as u32;
        let entry = LineEntry {
            pc: self.here(),
            pou: self.cur.0,
            file,
            line,
            col,
        };
        match self.lines.last_mut() {
            Some(l) if l.pc == entry.pc => *l = entry,
            _ => self.lines.push(entry),
        }
    }

    // ----- conditions ----------------------------------------------------------------

    /// Emits jumps taken when `e` (a BOOL) is `when`; returns them for
    /// patching. Comparisons become one compare-and-branch; NOT flips the
    /// sense; AND and OR short-circuit when skipping the right operand
    /// changes nothing (it reads variables and calls, divides, converts
    /// or indexes nothing).
    fn branch(&mut self, e: &Expr, when: bool) -> Result<Vec<usize>, CompileError> {
        let mark = self.frame.top;
        let is_bool = self.num(e.ty) == Some(Num::B);
        let r = match &e.kind {
            ExprKind::Const(Value::Bool(b)) => {
                if *b == when {
                    vec![self.emit(Instr::Jmp { t: Tgt(0) })]
                } else {
                    Vec::new()
                }
            }
            ExprKind::Unary(UnOp::Not, x) if is_bool => self.branch(x, !when)?,
            ExprKind::Binary(op @ (BinOp::And | BinOp::Or), x, y)
                if is_bool
                    && self.num(x.ty) == Some(Num::B)
                    && self.num(y.ty) == Some(Num::B)
                    && quiet(y) =>
            {
                // AND jumping on false, OR jumping on true: either operand decides.
                let either = (*op == BinOp::And) != when;
                if either {
                    let mut j = self.branch(x, when)?;
                    j.extend(self.branch(y, when)?);
                    j
                } else {
                    let skip = self.branch(x, !when)?;
                    let j = self.branch(y, when)?;
                    let here = self.here();
                    self.patch_all(&skip, here);
                    j
                }
            }
            ExprKind::Binary(
                op @ (BinOp::Eq | BinOp::Ne | BinOp::Lt | BinOp::Le | BinOp::Gt | BinOp::Ge),
                x,
                y,
            ) if self.fused_cmp_ok(x.ty, y.ty) => {
                let n = self.num(x.ty).unwrap_or(Num::I64);
                let a = self.expr(x)?;
                let b = self.expr(y)?;
                let i = cmp_branch(*op, n, a, b, when);
                vec![self.emit(i)]
            }
            _ => {
                let c = self.expr(e)?;
                vec![self.emit(if when {
                    Instr::Jnz { c, t: Tgt(0) }
                } else {
                    Instr::Jz { c, t: Tgt(0) }
                })]
            }
        };
        self.frame.top = mark;
        Ok(r)
    }

    /// Whether a comparison of these operand types is one native branch.
    fn fused_cmp_ok(&self, lt: TypeId, rt: TypeId) -> bool {
        match (self.scalar(lt), self.scalar(rt)) {
            (Some(a), Some(b)) => a == b && Num::of(a).is_some(),
            _ => false,
        }
    }

    // ----- statements ------------------------------------------------------------

    fn block(&mut self, stmts: &[Stmt]) -> Result<(), CompileError> {
        for s in stmts {
            self.stmt(s)?;
        }
        Ok(())
    }

    fn stmt(&mut self, s: &Stmt) -> Result<(), CompileError> {
        self.mark_line(s);
        let mark = self.frame.top;
        match &s.kind {
            StmtKind::Assign { place, value } => self.assign(place, value)?,
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
                // `IF c THEN EXIT` (or CONTINUE; or the ELSE form of
                // WHILE) is one conditional jump.
                fn jump_only(b: &[Stmt]) -> Option<&StmtKind> {
                    match b {
                        [Stmt {
                            kind: k @ (StmtKind::Break | StmtKind::Continue),
                            ..
                        }] => Some(k),
                        _ => None,
                    }
                }
                let shortcut = match (jump_only(then_body), jump_only(else_body)) {
                    (Some(k), None) if else_body.is_empty() => Some((k, true)),
                    (None, Some(k)) if then_body.is_empty() => Some((k, false)),
                    _ => None,
                };
                if self.loops.last().is_some() {
                    if let Some((k, when)) = shortcut {
                        let j = self.branch(cond, when)?;
                        if let Some(l) = self.loops.last_mut() {
                            if matches!(k, StmtKind::Break) {
                                l.breaks.extend(j);
                            } else {
                                l.continues.extend(j);
                            }
                        }
                        self.frame.top = mark;
                        return Ok(());
                    }
                }
                let jf = self.branch(cond, false)?;
                self.frame.top = mark;
                self.block(then_body)?;
                if else_body.is_empty() {
                    let end = self.here();
                    self.patch_all(&jf, end);
                } else {
                    let jmp = self.emit(Instr::Jmp { t: Tgt(0) });
                    let el = self.here();
                    self.patch_all(&jf, el);
                    self.block(else_body)?;
                    let end = self.here();
                    self.patch(jmp, end);
                }
            }
            StmtKind::Switch {
                selector,
                arms,
                default,
            } => self.switch(selector, arms, default)?,
            StmtKind::Loop { body, latch } => self.loop_stmt(body, latch)?,
            StmtKind::Break => {
                let j = self.emit(Instr::Jmp { t: Tgt(0) });
                if let Some(l) = self.loops.last_mut() {
                    l.breaks.push(j);
                }
            }
            StmtKind::Continue => {
                let j = self.emit(Instr::Jmp { t: Tgt(0) });
                if let Some(l) = self.loops.last_mut() {
                    l.continues.push(j);
                }
            }
            StmtKind::Return => {
                self.emit(Instr::Ret {});
            }
            StmtKind::Fault(k) => {
                self.emit(Instr::Fault {
                    kind: fault_code(*k),
                });
            }
        }
        self.frame.top = mark;
        Ok(())
    }

    /// A loop. One whose body starts with `IF c THEN EXIT` (WHILE, FOR)
    /// is rotated: the test runs before the first iteration and again at
    /// the bottom, so each iteration costs one branch; at the bottom of a
    /// FOR, the increment and the test fuse into one `forup`/`fordn`.
    fn loop_stmt(&mut self, body: &[Stmt], latch: &[Stmt]) -> Result<(), CompileError> {
        self.loops.push(LoopCtx {
            breaks: Vec::new(),
            continues: Vec::new(),
        });
        let exit_test = body.first().and_then(exit_test);
        let latch_at;
        match exit_test {
            Some((cond, exit_when)) => {
                // Small tests are repeated at the top; big ones jumped to.
                let small = expr_size(cond) <= 16;
                let entry = if small {
                    if let Some(test) = body.first() {
                        self.mark_line(test);
                    }
                    let j = self.branch(cond, exit_when)?;
                    if let Some(l) = self.loops.last_mut() {
                        l.breaks.extend(j);
                    }
                    None
                } else {
                    Some(self.emit(Instr::Jmp { t: Tgt(0) }))
                };
                let top = self.here();
                self.block(&body[1..])?;
                latch_at = self.here();
                let step = if exit_when {
                    self.for_step(cond, latch, top)?
                } else {
                    None
                };
                if let Some(step) = step {
                    self.emit(step);
                    let end = self.here();
                    let ctx = self.loops.pop().unwrap_or(LoopCtx {
                        breaks: Vec::new(),
                        continues: Vec::new(),
                    });
                    self.patch_all(&ctx.breaks, end);
                    self.patch_all(&ctx.continues, latch_at);
                    return Ok(());
                }
                self.block(latch)?;
                let test_at = self.here();
                if let Some(j) = entry {
                    self.patch(j, test_at);
                }
                if let Some(test) = body.first() {
                    self.mark_line(test);
                }
                let back = self.branch(cond, !exit_when)?;
                self.patch_all(&back, top);
            }
            None => {
                let top = self.here();
                self.block(body)?;
                latch_at = self.here();
                self.block(latch)?;
                self.emit(Instr::Jmp { t: Tgt(top) });
            }
        }
        let end = self.here();
        let ctx = self.loops.pop().unwrap_or(LoopCtx {
            breaks: Vec::new(),
            continues: Vec::new(),
        });
        self.patch_all(&ctx.breaks, end);
        self.patch_all(&ctx.continues, latch_at);
        Ok(())
    }

    /// The latch of a FOR loop with a constant step, as the IR lowers it
    /// (`IF v > max - step THEN EXIT; v := v + step`, with the loop test
    /// `v > end`), is one `forup` (`fordn`): the add, checked against
    /// overflow (which ends the loop, as the test did), and the branch back
    /// while `v <= end`. `None` when the loop has another shape.
    fn for_step(
        &mut self,
        test: &Expr,
        latch: &[Stmt],
        top: u32,
    ) -> Result<Option<Instr>, CompileError> {
        // The latch: the overflow test (left out by the IR when it cannot
        // fire), then the step.
        let (ovf, inc) = match latch {
            [Stmt {
                kind:
                    StmtKind::If {
                        cond,
                        then_body,
                        else_body,
                    },
                ..
            }, inc]
                if else_body.is_empty()
                    && matches!(
                        then_body.as_slice(),
                        [Stmt {
                            kind: StmtKind::Break,
                            ..
                        }]
                    ) =>
            {
                (Some(cond), inc)
            }
            [inc] => (None, inc),
            _ => return Ok(None),
        };
        let StmtKind::Assign { place, value } = &inc.kind else {
            return Ok(None);
        };
        let simple = |p: &Place| matches!(p.root, Root::Var(_)) && p.proj.is_empty();
        let same = |a: &Place, b: &Place| match (&a.root, &b.root) {
            (Root::Var(x), Root::Var(y)) => x == y && simple(a) && simple(b),
            _ => false,
        };
        let ExprKind::Binary(BinOp::Add, x, st) = &value.kind else {
            return Ok(None);
        };
        let (ExprKind::Load(px), ExprKind::Const(Value::Int(step))) = (&x.kind, &st.kind) else {
            return Ok(None);
        };
        let ExprKind::Binary(top_op, tv, tend) = &test.kind else {
            return Ok(None);
        };
        let ExprKind::Load(pt) = &tv.kind else {
            return Ok(None);
        };
        if !(same(place, px) && same(place, pt)) {
            return Ok(None);
        }
        let ty = place.ty;
        let Some((n, (min, max))) = self
            .scalar(ty)
            .and_then(|e| Some((Num::of(e)?, stc_values::int_range(e)?)))
        else {
            return Ok(None);
        };
        let up = match top_op {
            BinOp::Gt if *step > 0 => true,
            BinOp::Lt if *step < 0 => false,
            _ => return Ok(None),
        };
        if let Some(ovf) = ovf {
            let ExprKind::Binary(oop, ov, ok) = &ovf.kind else {
                return Ok(None);
            };
            let (ExprKind::Load(po), ExprKind::Const(Value::Int(k))) = (&ov.kind, &ok.kind) else {
                return Ok(None);
            };
            let fits = if up {
                *oop == BinOp::Gt && *k == max - step
            } else {
                *oop == BinOp::Lt && *k == min - step
            };
            if !fits || !same(place, po) {
                return Ok(None);
            }
        }
        if n.is_float() || n == Num::B || self.scalar(tend.ty) != self.scalar(ty) {
            return Ok(None);
        }
        self.mark_line(inc);
        let v = match self.var_loc_of(place)? {
            Some(v) => v,
            None => return Ok(None),
        };
        let e = self.expr(tend)?;
        let s = self.konst(ty, &Value::Int(step.abs()));
        let t = Tgt(top);
        use Instr as I;
        Ok(Some(match (up, n) {
            (true, Num::I8) => I::ForUpI8 { v, s, e, t },
            (true, Num::I16) => I::ForUpI16 { v, s, e, t },
            (true, Num::I32) => I::ForUpI32 { v, s, e, t },
            (true, Num::I64) => I::ForUpI64 { v, s, e, t },
            (true, Num::U8) => I::ForUpU8 { v, s, e, t },
            (true, Num::U16) => I::ForUpU16 { v, s, e, t },
            (true, Num::U32) => I::ForUpU32 { v, s, e, t },
            (true, _) => I::ForUpU64 { v, s, e, t },
            (false, Num::I8) => I::ForDnI8 { v, s, e, t },
            (false, Num::I16) => I::ForDnI16 { v, s, e, t },
            (false, Num::I32) => I::ForDnI32 { v, s, e, t },
            (false, Num::I64) => I::ForDnI64 { v, s, e, t },
            (false, Num::U8) => I::ForDnU8 { v, s, e, t },
            (false, Num::U16) => I::ForDnU16 { v, s, e, t },
            (false, Num::U32) => I::ForDnU32 { v, s, e, t },
            (false, _) => I::ForDnU64 { v, s, e, t },
        }))
    }

    /// The operand of a variable place held directly (not by reference).
    fn var_loc_of(&mut self, p: &Place) -> Result<Option<Op>, CompileError> {
        Ok(match p.root {
            Root::Var(v) if p.proj.is_empty() => match self.var_loc(v)? {
                Loc::At(a) => Some(a),
                _ => None,
            },
            _ => None,
        })
    }

    fn switch(
        &mut self,
        selector: &Expr,
        arms: &[stc_ir::SwitchArm],
        default: &[Stmt],
    ) -> Result<(), CompileError> {
        let sel = self.expr(selector)?;
        let t = selector.ty;
        let num = self.num(t).unwrap_or(Num::I64);
        let mut to_body = Vec::new();
        for (ai, arm) in arms.iter().enumerate() {
            for &(lo, hi) in &arm.ranges {
                let lo_op = self.konst(t, &Value::Int(lo));
                if lo == hi {
                    let j = self.emit(cmp_branch(BinOp::Eq, num, sel, lo_op, true));
                    to_body.push((j, ai));
                } else {
                    let hi_op = self.konst(t, &Value::Int(hi));
                    let below = self.emit(cmp_branch(BinOp::Lt, num, sel, lo_op, true));
                    let j = self.emit(cmp_branch(BinOp::Le, num, sel, hi_op, true));
                    to_body.push((j, ai));
                    let next = self.here();
                    self.patch(below, next);
                }
            }
        }
        let to_default = self.emit(Instr::Jmp { t: Tgt(0) });
        let mut ends = Vec::new();
        for (ai, arm) in arms.iter().enumerate() {
            let at = self.here();
            for (j, a) in &to_body {
                if *a == ai {
                    self.patch(*j, at);
                }
            }
            self.block(&arm.body)?;
            ends.push(self.emit(Instr::Jmp { t: Tgt(0) }));
        }
        let d = self.here();
        self.patch(to_default, d);
        self.block(default)?;
        let end = self.here();
        for j in ends {
            self.patch(j, end);
        }
        Ok(())
    }

    fn assign(&mut self, place: &Place, value: &Expr) -> Result<(), CompileError> {
        // The element address may be computed after the value only when
        // the value cannot change the index (it calls nothing).
        let pl = if stc_ir::visit::has_call(value) {
            self.place(place)?
        } else {
            self.place_lazy(place)?
        };
        match (pl.loc, pl.part) {
            (Loc::At(d), None)
                if self.is_scalar(place.ty) && !matches!(value.kind, ExprKind::Check { .. }) =>
            {
                self.expr_into(value, d)?;
            }
            _ => {
                let v = self.expr(value)?;
                self.store(pl, v, value.ty, place.ty)?;
            }
        }
        Ok(())
    }

    fn is_scalar(&self, t: TypeId) -> bool {
        self.num(t).is_some()
    }

    /// Stores the value at `v` (of type `vt`) into a place of type `pt`.
    fn store(&mut self, pl: PlaceLoc, v: Op, vt: TypeId, pt: TypeId) -> Result<(), CompileError> {
        if let Some((width, size, index)) = pl.part {
            // Read-modify-write of the whole bit string.
            let word = self.load_loc(pl.loc, width / 8)?;
            self.emit(Instr::SetPart {
                d: word,
                a: v,
                width,
                part: size.bits(),
                index,
            });
            return self.store_loc(pl.loc, word, width / 8);
        }
        match self.m.types.kind(pt) {
            TypeKind::String { wide, len } => {
                let unit = if *wide { 2 } else { 1 };
                match pl.loc {
                    Loc::At(d) => {
                        self.emit(Instr::StrCopy {
                            d,
                            a: v,
                            cap: *len,
                            unit,
                        });
                    }
                    _ => {
                        let size = self.size_of(pt);
                        let t = self.temp(size);
                        self.emit(Instr::StrCopy {
                            d: t,
                            a: v,
                            cap: *len,
                            unit,
                        });
                        self.store_loc(pl.loc, t, size)?;
                    }
                }
                let _ = vt;
                Ok(())
            }
            _ => {
                let size = self.size_of(pt);
                self.store_loc(pl.loc, v, size)
            }
        }
    }

    fn store_loc(&mut self, loc: Loc, v: Op, size: u32) -> Result<(), CompileError> {
        match loc {
            Loc::At(d) => {
                self.mov(d, v, size);
            }
            Loc::Elem {
                base: a,
                idx,
                desc,
                at,
            } if matches!(size, 1 | 2 | 4 | 8) => {
                self.at_pos(at, |c| {
                    c.emit(width_instr(
                        size,
                        [
                            Instr::StElem1 { a, idx, v, desc },
                            Instr::StElem2 { a, idx, v, desc },
                            Instr::StElem4 { a, idx, v, desc },
                            Instr::StElem8 { a, idx, v, desc },
                        ],
                    ))
                });
            }
            Loc::Elem { .. } => {
                let l = self.materialize(loc);
                return self.store_loc(l, v, size);
            }
            Loc::Ptr { ptr: p, off } => {
                let a = v;
                self.emit(match size {
                    1 => Instr::St1 { p, a, off },
                    2 => Instr::St2 { p, a, off },
                    4 => Instr::St4 { p, a, off },
                    8 => Instr::St8 { p, a, off },
                    len => Instr::Store { p, a, off, len },
                });
            }
        }
        Ok(())
    }

    /// A location computed: an array element becomes a pointer.
    fn materialize(&mut self, loc: Loc) -> Loc {
        match loc {
            Loc::Elem {
                base,
                idx,
                desc,
                at,
            } => {
                let d = self.temp(4);
                self.at_pos(at, |c| {
                    c.emit(Instr::Elem {
                        d,
                        a: base,
                        idx,
                        desc,
                    })
                });
                Loc::Ptr { ptr: d, off: 0 }
            }
            l => l,
        }
    }

    fn load_loc(&mut self, loc: Loc, size: u32) -> Result<Op, CompileError> {
        Ok(match loc {
            Loc::At(a) => {
                let t = self.temp(size);
                self.mov(t, a, size);
                t
            }
            Loc::Ptr { ptr: p, off } => {
                let d = self.temp(size);
                self.emit(match size {
                    1 => Instr::Ld1 { d, p, off },
                    2 => Instr::Ld2 { d, p, off },
                    4 => Instr::Ld4 { d, p, off },
                    8 => Instr::Ld8 { d, p, off },
                    len => Instr::Load { d, p, off, len },
                });
                d
            }
            Loc::Elem {
                base: a,
                idx,
                desc,
                at,
            } if matches!(size, 1 | 2 | 4 | 8) => {
                let d = self.temp(size);
                self.at_pos(at, |c| {
                    c.emit(width_instr(
                        size,
                        [
                            Instr::LdElem1 { d, a, idx, desc },
                            Instr::LdElem2 { d, a, idx, desc },
                            Instr::LdElem4 { d, a, idx, desc },
                            Instr::LdElem8 { d, a, idx, desc },
                        ],
                    ))
                });
                d
            }
            Loc::Elem { .. } => {
                let l = self.materialize(loc);
                return self.load_loc(l, size);
            }
        })
    }

    fn mov(&mut self, d: Op, a: Op, size: u32) {
        if d == a {
            return;
        }
        match size {
            1 => self.emit(Instr::Mov1 { d, a }),
            2 => self.emit(Instr::Mov2 { d, a }),
            4 => self.emit(Instr::Mov4 { d, a }),
            8 => self.emit(Instr::Mov8 { d, a }),
            0 => 0,
            n => self.emit(Instr::Copy { d, a, len: n }),
        };
    }

    // ----- places ------------------------------------------------------------------

    fn var_loc(&mut self, v: VarId) -> Result<Loc, CompileError> {
        let pou = &self.m.pous[self.cur];
        let var = pou.var(v);
        let in_frame = self.l.pous[self.cur].in_frame[v];
        let slot = if in_frame {
            Op::frame(
                *self
                    .frame
                    .var_off
                    .get(&v)
                    .ok_or_else(|| internal("a frame variable without a place"))?,
            )
        } else {
            Op::this(self.l.pous[self.cur].offsets[v])
        };
        Ok(if var.storage == Storage::Ref {
            Loc::Ptr { ptr: slot, off: 0 }
        } else {
            Loc::At(slot)
        })
    }

    /// A place, with every address computed.
    fn place(&mut self, p: &Place) -> Result<PlaceLoc, CompileError> {
        let pl = self.place_lazy(p)?;
        Ok(PlaceLoc {
            loc: self.materialize(pl.loc),
            part: pl.part,
        })
    }

    /// A place; an element of an array at a fixed place may stay a
    /// [`Loc::Elem`] for the caller to read or write in one instruction.
    fn place_lazy(&mut self, p: &Place) -> Result<PlaceLoc, CompileError> {
        let mut loc = match &p.root {
            Root::Var(v) => self.var_loc(*v)?,
            Root::Global(g) => Loc::At(Op::abs(
                self.d
                    .global_offset(*g)
                    .ok_or_else(|| internal("a global without a place"))?,
            )),
            Root::Direct(a) => {
                Loc::At(Op::abs(self.d.io_offset(a).ok_or_else(|| {
                    internal(format!("{a} without a process image slot"))
                })?))
            }
            // The running function block's instance.
            Root::This => Loc::At(Op::this(0)),
            Root::Deref(r) => {
                // The address, checked not to be NULL (a fault at the `^`).
                let (at, r) = r.located();
                let ptr = self.expr(r)?;
                let zero = self.const_u32(0);
                let ok = self.emit(cmp_branch(BinOp::Ne, Num::U32, ptr, zero, true));
                self.at_pos(at, |c| {
                    c.emit(Instr::Fault {
                        kind: fault_code(FaultKind::NullReference),
                    })
                });
                let here = self.here();
                self.patch(ok, here);
                Loc::Ptr { ptr, off: 0 }
            }
        };
        // The type of the value reached so far, to find offsets.
        let mut ty = match &p.root {
            Root::Var(v) => self.m.pous[self.cur].var(*v).ty,
            Root::Global(g) => self.m.globals[*g].ty,
            Root::Direct(a) => self.m.addr_type(a),
            Root::Deref(r) => self.m.types.ref_target(r.ty).unwrap_or(TypeId::ERROR),
            // (Only a variable of the instance follows it: its type.)
            Root::This => p.ty,
        };
        let mut part = None;
        for proj in &p.proj {
            match proj {
                Proj::Field(i) => {
                    let off = self.l.field_offset(ty, *i);
                    loc = offset_loc(loc, off);
                    ty = match self.m.types.kind(ty) {
                        TypeKind::Struct { fields } => fields
                            .get(*i as usize)
                            .map(|f| f.ty)
                            .unwrap_or(TypeId::ERROR),
                        _ => TypeId::ERROR,
                    };
                }
                Proj::FbVar(fb, v) => {
                    let off = self.l.var_offset(*fb, *v);
                    loc = offset_loc(loc, off);
                    let var = self.m.pous[*fb].var(*v);
                    ty = var.ty;
                    if var.storage == Storage::Ref {
                        // Through the slot: an in-out's address is the one
                        // the last call of the instance bound (NULL before
                        // the first call, a fault), an external's its
                        // global's.
                        let in_out = var.section == Section::InOut;
                        let slot = self.materialize(loc);
                        let ptr = self.load_loc(slot, 4)?;
                        if in_out {
                            let zero = self.const_u32(0);
                            let ok = self.emit(cmp_branch(BinOp::Ne, Num::U32, ptr, zero, true));
                            self.emit(Instr::Fault {
                                kind: fault_code(FaultKind::NullReference),
                            });
                            let here = self.here();
                            self.patch(ok, here);
                        }
                        loc = Loc::Ptr { ptr, off: 0 };
                    }
                }
                Proj::Index(idx) => {
                    let (dims, elem) = match self.m.types.kind(ty).clone() {
                        TypeKind::Array { dims, elem } => (dims, elem),
                        _ => return Err(internal("indexing a non-array")),
                    };
                    let stride = self.l.stride(&self.m.types, ty);
                    // Strides per dimension: the element stride times the
                    // counts of the dimensions after it.
                    let counts: Vec<i128> = dims.iter().map(|(l, h)| h - l + 1).collect();
                    let mut mults = vec![stride as i128; dims.len()];
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
                        loc = offset_loc(loc, off.max(0) as u32);
                    } else {
                        // One checked step per index: the first from the
                        // array's place (left lazy when it is the only one),
                        // the others from the pointer so far.
                        for (k, (e, lo, hi)) in idx.iter().enumerate() {
                            let (at, e) = e.located();
                            let i = self.expr(e)?;
                            let (i, num) = match self.num(e.ty) {
                                Some(n) if !n.is_float() => (i, n),
                                _ => (self.widen_to_i64(i, e.ty), Num::I64),
                            };
                            let count = (hi - lo + 1).clamp(0, u32::MAX as i128) as u32;
                            let desc = self.elem_desc(ElemDesc {
                                lo: (*lo).clamp(i64::MIN as i128, i64::MAX as i128) as i64,
                                count,
                                stride: mults[k].clamp(0, u32::MAX as i128) as u32,
                                num,
                            });
                            loc = match loc {
                                Loc::At(base) => Loc::Elem {
                                    base,
                                    idx: i,
                                    desc,
                                    at,
                                },
                                l => {
                                    let p = self.ptr_of(l);
                                    let d = self.temp(4);
                                    self.at_pos(at, |c| {
                                        c.emit(Instr::ElemP { d, p, idx: i, desc })
                                    });
                                    Loc::Ptr { ptr: d, off: 0 }
                                }
                            };
                        }
                    }
                    // A partial index (`a[i]` of `a[i][j]`) leaves the rest.
                    ty = if idx.len() < dims.len() { p.ty } else { elem };
                }
                Proj::Part(size, index) => {
                    let width = self.scalar(ty).map(elem_size).unwrap_or(8) * 8;
                    part = Some((width, *size, *index));
                }
            }
        }
        Ok(PlaceLoc { loc, part })
    }

    /// An 8-byte signed copy of an integer operand (for indexing).
    fn widen_to_i64(&mut self, a: Op, t: TypeId) -> Op {
        match self.num(t) {
            Some(Num::I64) => a,
            Some(n) => {
                let d = self.temp(8);
                self.emit(Instr::Cvt {
                    d,
                    a,
                    from: n.code(),
                    to: Num::I64.code(),
                });
                d
            }
            None => a,
        }
    }

    // ----- expressions ---------------------------------------------------------------

    /// Evaluates an expression; returns the operand holding its value.
    fn expr(&mut self, e: &Expr) -> Result<Op, CompileError> {
        match &e.kind {
            ExprKind::Const(v) => Ok(self.konst(e.ty, v)),
            ExprKind::Null => Ok(self.const_u32(0)),
            ExprKind::Ref(p) => self.address_of(p),
            ExprKind::Load(p) => {
                let pl = self.place_lazy(p)?;
                match (pl.loc, pl.part) {
                    (Loc::At(a), None) => Ok(a),
                    (loc, None) => {
                        let size = self.size_of(e.ty);
                        self.load_loc(loc, size)
                    }
                    (loc, Some((width, size, index))) => {
                        let word = match loc {
                            Loc::At(a) => a,
                            l => self.load_loc(l, width / 8)?,
                        };
                        let d = self.temp(8);
                        self.emit(Instr::GetPart {
                            d,
                            a: word,
                            width,
                            part: size.bits(),
                            index,
                        });
                        Ok(d)
                    }
                }
            }
            _ => {
                let d = self.temp_of(e.ty);
                self.expr_into(e, d)?;
                Ok(d)
            }
        }
    }

    /// Evaluates an expression into `d` (which its subexpressions never use).
    fn expr_into(&mut self, e: &Expr, d: Op) -> Result<(), CompileError> {
        match &e.kind {
            ExprKind::Const(_) | ExprKind::Load(_) | ExprKind::Null | ExprKind::Ref(_) => {
                let a = self.expr(e)?;
                let size = self.size_of(e.ty);
                if let TypeKind::String { wide, len } = self.m.types.kind(e.ty) {
                    let unit = if *wide { 2 } else { 1 };
                    self.emit(Instr::StrCopy {
                        d,
                        a,
                        cap: *len,
                        unit,
                    });
                } else {
                    self.mov(d, a, size);
                }
            }
            ExprKind::Unary(op, x) => {
                let a = self.expr(x)?;
                let num = self.num(x.ty);
                let i = match (op, num) {
                    (UnOp::Not, Some(Num::B)) => Some(Instr::NotB { d, a }),
                    (UnOp::Not, Some(n)) if !n.is_float() => Some(match n.size() {
                        1 => Instr::Not8 { d, a },
                        2 => Instr::Not16 { d, a },
                        4 => Instr::Not32 { d, a },
                        _ => Instr::Not64 { d, a },
                    }),
                    (UnOp::Neg, Some(Num::F32)) => Some(Instr::NegF32 { d, a }),
                    (UnOp::Neg, Some(Num::F64)) => Some(Instr::NegF64 { d, a }),
                    (UnOp::Neg, Some(n)) if n != Num::B => Some(match n.size() {
                        1 => Instr::Neg8 { d, a },
                        2 => Instr::Neg16 { d, a },
                        4 => Instr::Neg32 { d, a },
                        _ => Instr::Neg64 { d, a },
                    }),
                    _ => None,
                };
                match i {
                    Some(i) => {
                        self.emit(i);
                    }
                    None => {
                        self.generic(StdOp::Unary(*op), &[(a, x.ty)], (d, e.ty));
                    }
                }
            }
            ExprKind::Binary(op, x, y) => {
                let a = self.expr(x)?;
                let b = self.expr(y)?;
                match self.native_binary(*op, x.ty, y.ty, e.ty, d, a, b) {
                    Some(i) => {
                        self.emit(i);
                    }
                    None => {
                        self.generic(StdOp::Binary(*op), &[(a, x.ty), (b, y.ty)], (d, e.ty));
                    }
                }
            }
            ExprKind::Convert(x)
                if matches!(self.m.types.kind(x.ty), TypeKind::Ref(_))
                    && matches!(self.m.types.kind(e.ty), TypeKind::Ref(_)) =>
            {
                // A reference seen as another (pointers): the same address.
                let a = self.expr(x)?;
                let size = self.size_of(e.ty);
                self.mov(d, a, size);
            }
            ExprKind::Convert(x) => {
                let a = self.expr(x)?;
                let (from, to) = (self.scalar(x.ty), self.scalar(e.ty));
                let plain = plain_numeric;
                match (from, to) {
                    (Some(f), Some(t)) if f == t => {
                        let size = self.size_of(e.ty);
                        if let TypeKind::String { wide, len } = self.m.types.kind(e.ty) {
                            let unit = if *wide { 2 } else { 1 };
                            self.emit(Instr::StrCopy {
                                d,
                                a,
                                cap: *len,
                                unit,
                            });
                        } else {
                            self.mov(d, a, size);
                        }
                    }
                    (Some(f), Some(t)) if plain(from) && plain(to) => {
                        let (nf, nt) = (
                            Num::of(f).unwrap_or(Num::I64),
                            Num::of(t).unwrap_or(Num::I64),
                        );
                        self.emit(Instr::Cvt {
                            d,
                            a,
                            from: nf.code(),
                            to: nt.code(),
                        });
                    }
                    _ => {
                        self.generic(StdOp::Convert, &[(a, x.ty)], (d, e.ty));
                    }
                }
            }
            ExprKind::Check { value, lo, hi } => {
                let v = self.expr(value)?;
                let num = self.num(e.ty).unwrap_or(Num::I64);
                let lo_op = self.konst(e.ty, &Value::Int(*lo));
                let hi_op = self.konst(e.ty, &Value::Int(*hi));
                self.emit(Instr::Check {
                    a: v,
                    lo: lo_op,
                    hi: hi_op,
                    num: num.code(),
                });
                let size = self.size_of(e.ty);
                self.mov(d, v, size);
            }
            ExprKind::CallFn {
                func,
                inputs,
                inouts,
                outputs,
            } => {
                let res = self.call_fn(*func, inputs, inouts, outputs)?;
                if let Some(r) = res {
                    let size = self.size_of(e.ty);
                    if let TypeKind::String { wide, len } = self.m.types.kind(e.ty) {
                        let unit = if *wide { 2 } else { 1 };
                        self.emit(Instr::StrCopy {
                            d,
                            a: r,
                            cap: *len,
                            unit,
                        });
                    } else {
                        self.mov(d, r, size);
                    }
                }
            }
            ExprKind::Intrinsic { func, args } => {
                if self.native_intrinsic(*func, args, e.ty, d)? {
                    return Ok(());
                }
                let mut ops = Vec::with_capacity(args.len());
                for a in args {
                    let o = self.expr(a)?;
                    ops.push((o, a.ty));
                }
                let op = match func {
                    stc_values::Intrinsic::Trunc { .. } => StdOp::Trunc,
                    f => StdOp::Call(*f),
                };
                self.generic(op, &ops, (d, e.ty));
            }
            ExprKind::CurTime => {
                self.emit(Instr::CurTime { d });
            }
            ExprKind::Located { line, col, expr } => {
                return self.at_pos(Some((*line, *col)), |c| c.expr_into(expr, d));
            }
        }
        Ok(())
    }

    /// MIN, MAX, LIMIT, ABS, the shifts, SEL and MOVE on scalars of one
    /// type as single instructions; `false` when the call is not one of those.
    fn native_intrinsic(
        &mut self,
        f: stc_values::Intrinsic,
        args: &[Expr],
        ty: TypeId,
        d: Op,
    ) -> Result<bool, CompileError> {
        use stc_values::Intrinsic as F;
        let Some(n) = self.num(ty) else {
            return Ok(false);
        };
        let same = |c: &Self, es: &[Expr]| es.iter().all(|a| c.scalar(a.ty) == c.scalar(ty));
        let num = n.code();
        match f {
            F::Min | F::Max if args.len() >= 2 && same(self, args) => {
                let ops = args
                    .iter()
                    .map(|a| self.expr(a))
                    .collect::<Result<Vec<_>, _>>()?;
                let acc = if ops.len() == 2 {
                    d
                } else {
                    self.temp(n.size())
                };
                let mut a = ops[0];
                for &b in &ops[1..] {
                    self.emit(if f == F::Min {
                        Instr::Min { d: acc, a, b, num }
                    } else {
                        Instr::Max { d: acc, a, b, num }
                    });
                    a = acc;
                }
                self.mov(d, acc, n.size());
            }
            F::Limit if args.len() == 3 && same(self, args) => {
                let lo = self.expr(&args[0])?;
                let a = self.expr(&args[1])?;
                let hi = self.expr(&args[2])?;
                self.emit(Instr::Limit { d, lo, a, hi, num });
            }
            F::Abs if args.len() == 1 && same(self, args) => {
                let a = self.expr(&args[0])?;
                self.emit(Instr::Abs { d, a, num });
            }
            F::Shl | F::Shr | F::Rol | F::Ror
                if args.len() == 2 && same(self, &args[..1]) && !n.is_float() =>
            {
                let Some(nn) = self.num(args[1].ty).filter(|k| !k.is_float()) else {
                    return Ok(false);
                };
                let a = self.expr(&args[0])?;
                let c = self.expr(&args[1])?;
                let op = match f {
                    F::Shl => 0,
                    F::Shr => 1,
                    F::Rol => 2,
                    _ => 3,
                };
                self.emit(Instr::Shift {
                    d,
                    a,
                    n: c,
                    op,
                    num,
                    nnum: nn.code(),
                });
            }
            F::Sel
                if args.len() == 3
                    && same(self, &args[1..])
                    && self.num(args[0].ty) == Some(Num::B) =>
            {
                let g = self.expr(&args[0])?;
                let a = self.expr(&args[1])?;
                let b = self.expr(&args[2])?;
                self.emit(Instr::Sel {
                    d,
                    g,
                    a,
                    b,
                    len: n.size(),
                });
            }
            F::Move if args.len() == 1 && same(self, args) => {
                let a = self.expr(&args[0])?;
                self.mov(d, a, n.size());
            }
            _ => return Ok(false),
        }
        Ok(true)
    }

    /// A typed instruction for `a op b`, if the operation is native.
    #[allow(clippy::too_many_arguments)]
    fn native_binary(
        &self,
        op: BinOp,
        lt: TypeId,
        rt: TypeId,
        res: TypeId,
        d: Op,
        a: Op,
        b: Op,
    ) -> Option<Instr> {
        let (ls, rs) = (self.scalar(lt)?, self.scalar(rt)?);
        if ls != rs {
            return None;
        }
        let n = Num::of(ls)?;
        let cmp = matches!(
            op,
            BinOp::Eq | BinOp::Ne | BinOp::Lt | BinOp::Le | BinOp::Gt | BinOp::Ge
        );
        if !cmp {
            // Arithmetic natively only where the result has the operands'
            // type and no calendar wraps (TOD, DATE, DT go through stc_values).
            if self.scalar(res) != Some(ls)
                || matches!(
                    ls,
                    ElemType::Tod
                        | ElemType::Ltod
                        | ElemType::Date
                        | ElemType::Ldate
                        | ElemType::Dt
                        | ElemType::Ldt
                )
            {
                return None;
            }
        }
        Some(match op {
            BinOp::Eq | BinOp::Ne | BinOp::Lt | BinOp::Le | BinOp::Gt | BinOp::Ge => {
                return Some(self.cmp_instr(op, n, d, a, b))
            }
            BinOp::Add => match n {
                Num::F32 => Instr::AddF32 { d, a, b },
                Num::F64 => Instr::AddF64 { d, a, b },
                Num::B => return None,
                _ => width_instr(
                    n.size(),
                    [
                        Instr::Add8 { d, a, b },
                        Instr::Add16 { d, a, b },
                        Instr::Add32 { d, a, b },
                        Instr::Add64 { d, a, b },
                    ],
                ),
            },
            BinOp::Sub => match n {
                Num::F32 => Instr::SubF32 { d, a, b },
                Num::F64 => Instr::SubF64 { d, a, b },
                Num::B => return None,
                _ => width_instr(
                    n.size(),
                    [
                        Instr::Sub8 { d, a, b },
                        Instr::Sub16 { d, a, b },
                        Instr::Sub32 { d, a, b },
                        Instr::Sub64 { d, a, b },
                    ],
                ),
            },
            BinOp::Mul => match n {
                Num::F32 => Instr::MulF32 { d, a, b },
                Num::F64 => Instr::MulF64 { d, a, b },
                Num::B => return None,
                _ => width_instr(
                    n.size(),
                    [
                        Instr::Mul8 { d, a, b },
                        Instr::Mul16 { d, a, b },
                        Instr::Mul32 { d, a, b },
                        Instr::Mul64 { d, a, b },
                    ],
                ),
            },
            BinOp::Div => match n {
                Num::F32 => Instr::DivF32 { d, a, b },
                Num::F64 => Instr::DivF64 { d, a, b },
                Num::I8 => Instr::DivI8 { d, a, b },
                Num::I16 => Instr::DivI16 { d, a, b },
                Num::I32 => Instr::DivI32 { d, a, b },
                Num::I64 => Instr::DivI64 { d, a, b },
                Num::U8 => Instr::DivU8 { d, a, b },
                Num::U16 => Instr::DivU16 { d, a, b },
                Num::U32 => Instr::DivU32 { d, a, b },
                Num::U64 => Instr::DivU64 { d, a, b },
                Num::B => return None,
            },
            BinOp::Mod => match n {
                Num::I8 => Instr::ModI8 { d, a, b },
                Num::I16 => Instr::ModI16 { d, a, b },
                Num::I32 => Instr::ModI32 { d, a, b },
                Num::I64 => Instr::ModI64 { d, a, b },
                Num::U8 => Instr::ModU8 { d, a, b },
                Num::U16 => Instr::ModU16 { d, a, b },
                Num::U32 => Instr::ModU32 { d, a, b },
                Num::U64 => Instr::ModU64 { d, a, b },
                _ => return None,
            },
            BinOp::And | BinOp::Or | BinOp::Xor if !n.is_float() => {
                let i = match op {
                    BinOp::And => [
                        Instr::And8 { d, a, b },
                        Instr::And16 { d, a, b },
                        Instr::And32 { d, a, b },
                        Instr::And64 { d, a, b },
                    ],
                    BinOp::Or => [
                        Instr::Or8 { d, a, b },
                        Instr::Or16 { d, a, b },
                        Instr::Or32 { d, a, b },
                        Instr::Or64 { d, a, b },
                    ],
                    _ => [
                        Instr::Xor8 { d, a, b },
                        Instr::Xor16 { d, a, b },
                        Instr::Xor32 { d, a, b },
                        Instr::Xor64 { d, a, b },
                    ],
                };
                width_instr(n.size(), i)
            }
            _ => return None,
        })
    }

    /// A comparison (`>` and `>=` by swapping to `<` and `<=`).
    fn cmp_instr(&self, op: BinOp, n: Num, d: Op, a: Op, b: Op) -> Instr {
        let (op, a, b) = match op {
            BinOp::Gt => (BinOp::Lt, b, a),
            BinOp::Ge => (BinOp::Le, b, a),
            o => (o, a, b),
        };
        match (op, n) {
            (BinOp::Eq, Num::F32) => Instr::EqF32 { d, a, b },
            (BinOp::Eq, Num::F64) => Instr::EqF64 { d, a, b },
            (BinOp::Eq, n) => width_instr(
                n.size(),
                [
                    Instr::Eq8 { d, a, b },
                    Instr::Eq16 { d, a, b },
                    Instr::Eq32 { d, a, b },
                    Instr::Eq64 { d, a, b },
                ],
            ),
            (BinOp::Ne, Num::F32) => Instr::NeF32 { d, a, b },
            (BinOp::Ne, Num::F64) => Instr::NeF64 { d, a, b },
            (BinOp::Ne, n) => width_instr(
                n.size(),
                [
                    Instr::Ne8 { d, a, b },
                    Instr::Ne16 { d, a, b },
                    Instr::Ne32 { d, a, b },
                    Instr::Ne64 { d, a, b },
                ],
            ),
            (BinOp::Lt, n) => match n {
                Num::I8 => Instr::LtI8 { d, a, b },
                Num::I16 => Instr::LtI16 { d, a, b },
                Num::I32 => Instr::LtI32 { d, a, b },
                Num::I64 => Instr::LtI64 { d, a, b },
                Num::U8 | Num::B => Instr::LtU8 { d, a, b },
                Num::U16 => Instr::LtU16 { d, a, b },
                Num::U32 => Instr::LtU32 { d, a, b },
                Num::U64 => Instr::LtU64 { d, a, b },
                Num::F32 => Instr::LtF32 { d, a, b },
                Num::F64 => Instr::LtF64 { d, a, b },
            },
            (_, n) => match n {
                Num::I8 => Instr::LeI8 { d, a, b },
                Num::I16 => Instr::LeI16 { d, a, b },
                Num::I32 => Instr::LeI32 { d, a, b },
                Num::I64 => Instr::LeI64 { d, a, b },
                Num::U8 | Num::B => Instr::LeU8 { d, a, b },
                Num::U16 => Instr::LeU16 { d, a, b },
                Num::U32 => Instr::LeU32 { d, a, b },
                Num::U64 => Instr::LeU64 { d, a, b },
                Num::F32 => Instr::LeF32 { d, a, b },
                Num::F64 => Instr::LeF64 { d, a, b },
            },
        }
    }

    /// An operation through `stc_values`.
    fn generic(&mut self, op: StdOp, args: &[(Op, TypeId)], result: (Op, TypeId)) {
        let arg = |c: &Self, (o, t): (Op, TypeId)| {
            (o, c.scalar(t).unwrap_or(ElemType::Lint), c.cap_of(t))
        };
        let call = StdCall {
            op,
            args: args.iter().map(|&a| arg(self, a)).collect(),
            result: arg(self, result),
        };
        let idx = self.calls.len() as u32;
        self.calls.push(call);
        self.emit(Instr::Std { call: idx });
    }

    fn cap_of(&self, t: TypeId) -> u32 {
        match self.m.types.kind(t) {
            TypeKind::String { len, .. } => *len,
            _ => 0,
        }
    }

    // ----- calls --------------------------------------------------------------------

    /// Calls a function; returns the operand of its result.
    fn call_fn(
        &mut self,
        func: PouId,
        inputs: &[(VarId, Expr)],
        inouts: &[(VarId, Place)],
        outputs: &[stc_ir::Output],
    ) -> Result<Option<Op>, CompileError> {
        let info = self.frames[func]
            .clone()
            .ok_or_else(|| internal("a call before its callee"))?;
        let callee = &self.m.pous[func];
        if callee.vars.ids().any(|i| !info.var_off.contains_key(&i)) {
            return Err(internal(
                "a variable of a function without a place in its frame",
            ));
        }
        let region = self.temp(info.size).offset();
        let slot = |v: VarId| Op::frame(region + info.var_off[&v]);
        // Every input: given, or its initial value.
        for (i, v) in callee.vars.iter().enumerate() {
            if v.section != Section::Input {
                continue;
            }
            let var = VarId(i as u32);
            match inputs.iter().find(|(p, _)| *p == var) {
                Some((_, e)) => {
                    let d = slot(var);
                    if self.is_scalar(v.ty) {
                        self.expr_into(e, d)?;
                    } else {
                        let a = self.expr(e)?;
                        self.store(
                            PlaceLoc {
                                loc: Loc::At(d),
                                part: None,
                            },
                            a,
                            e.ty,
                            v.ty,
                        )?;
                    }
                }
                None => {
                    let size = self.size_of(v.ty);
                    let bytes = self
                        .d
                        .init_bytes(v.ty, v.init.as_ref())
                        .map_err(model_error)?;
                    let c = Op::abs(self.d.data_size() + self.const_bytes(&bytes, 8));
                    let d = slot(var);
                    self.mov(d, c, size);
                }
            }
        }
        for (v, p) in inouts {
            let addr = self.address_of(p)?;
            self.mov(slot(*v), addr, 4);
        }
        self.emit(Instr::CallFn {
            pou: func.0,
            frame: region,
        });
        for o in outputs {
            let var = &callee.vars[o.var];
            let src = slot(o.var);
            self.copy_out(src, var.ty, o)?;
        }
        Ok(callee
            .vars
            .iter()
            .position(|v| v.section == Section::Result)
            .map(|i| slot(VarId(i as u32))))
    }

    /// Copies an output parameter into its `=>` target (converting, negating).
    fn copy_out(
        &mut self,
        src: Op,
        src_ty: TypeId,
        o: &stc_ir::Output,
    ) -> Result<(), CompileError> {
        let mut v = src;
        if o.negated {
            let t = self.temp(1);
            self.emit(Instr::NotB { d: t, a: src });
            v = t;
        }
        let tt = o.target.ty;
        let (f, t) = (self.scalar(src_ty), self.scalar(tt));
        if f != t
            && f.is_some()
            && t.is_some()
            && !matches!(self.m.types.kind(tt), TypeKind::String { .. })
        {
            let d = self.temp_of(tt);
            let plain = plain_numeric;
            if plain(f) && plain(t) {
                self.emit(Instr::Cvt {
                    d,
                    a: v,
                    from: Num::of(f.unwrap_or(ElemType::Lint))
                        .unwrap_or(Num::I64)
                        .code(),
                    to: Num::of(t.unwrap_or(ElemType::Lint))
                        .unwrap_or(Num::I64)
                        .code(),
                });
            } else {
                self.generic(StdOp::Convert, &[(v, src_ty)], (d, tt));
            }
            v = d;
        }
        let pl = self.place(&o.target)?;
        self.store(pl, v, src_ty, tt)
    }

    /// An operand holding the address of a place.
    fn address_of(&mut self, p: &Place) -> Result<Op, CompileError> {
        let pl = self.place_lazy(p)?;
        Ok(self.ptr_of(pl.loc))
    }

    /// An operand holding the address of a location.
    fn ptr_of(&mut self, loc: Loc) -> Op {
        match loc {
            Loc::At(a) => {
                let d = self.temp(4);
                self.emit(Instr::Lea { d, a });
                d
            }
            Loc::Ptr { ptr, off: 0 } => ptr,
            Loc::Ptr { ptr, off } => {
                let d = self.temp(4);
                let c = self.const_u32(off);
                self.emit(Instr::Add32 { d, a: ptr, b: c });
                d
            }
            Loc::Elem {
                base,
                idx,
                desc,
                at,
            } => {
                let d = self.temp(4);
                self.at_pos(at, |c| {
                    c.emit(Instr::Elem {
                        d,
                        a: base,
                        idx,
                        desc,
                    })
                });
                d
            }
        }
    }

    fn call_fb(
        &mut self,
        instance: &Place,
        fb: PouId,
        inputs: &[(VarId, Expr)],
        inouts: &[(VarId, Place)],
        outputs: &[stc_ir::Output],
    ) -> Result<(), CompileError> {
        let info = self.frames[fb]
            .clone()
            .ok_or_else(|| internal("a call before its callee"))?;
        let pl = self.place(instance)?;
        let lay = self.l.pous[fb].clone();
        let m = self.m;
        let fbp = &m.pous[fb];
        // Inputs, in order, into the instance.
        for (v, e) in inputs {
            let var = fbp.var(*v);
            let off = lay.offsets[*v];
            let dst = PlaceLoc {
                loc: offset_loc(pl.loc, off),
                part: None,
            };
            match dst.loc {
                Loc::At(d) if self.is_scalar(var.ty) => self.expr_into(e, d)?,
                _ => {
                    let a = self.expr(e)?;
                    self.store(dst, a, e.ty, var.ty)?;
                }
            }
        }
        for (v, p) in inouts {
            let addr = self.address_of(p)?;
            let off = lay.offsets[*v];
            self.store_loc(offset_loc(pl.loc, off), addr, 4)?;
        }
        let region = self.temp(info.size).offset();
        match pl.loc {
            Loc::At(inst) => {
                self.emit(Instr::CallFb {
                    pou: fb.0,
                    inst,
                    frame: region,
                });
            }
            l => {
                let p = self.ptr_of(l);
                self.emit(Instr::CallFbInd {
                    pou: fb.0,
                    inst: p,
                    frame: region,
                });
            }
        }
        for o in outputs {
            let var = fbp.var(o.var);
            let off = lay.offsets[o.var];
            let src = match offset_loc(pl.loc, off) {
                Loc::At(a) => a,
                l => {
                    let size = self.size_of(var.ty);
                    self.load_loc(l, size)?
                }
            };
            self.copy_out(src, var.ty, o)?;
        }
        Ok(())
    }
}

fn offset_loc(l: Loc, off: u32) -> Loc {
    match l {
        Loc::At(a) => Loc::At(a.plus(off)),
        Loc::Ptr { ptr, off: o } => Loc::Ptr { ptr, off: o + off },
        Loc::Elem {
            base,
            idx,
            desc,
            at,
        } => Loc::Elem {
            base: base.plus(off),
            idx,
            desc,
            at,
        },
    }
}

fn width_instr(size: u32, options: [Instr; 4]) -> Instr {
    let [a, b, c, d] = options;
    match size {
        1 => a,
        2 => b,
        4 => c,
        _ => d,
    }
}

/// The compare-and-branch jumping when `a op b` is `when`. Integers negate
/// by swapping operands (`!(a < b)` is `b <= a`); floats cannot (NaN), so
/// they have their own negated branches.
fn cmp_branch(op: BinOp, n: Num, a: Op, b: Op, when: bool) -> Instr {
    let t = Tgt(0);
    // Normalise to <, <=, =, <> (swapping for > and >=).
    let (op, a, b) = match op {
        BinOp::Gt => (BinOp::Lt, b, a),
        BinOp::Ge => (BinOp::Le, b, a),
        o => (o, a, b),
    };
    // The sense to test: for integers, a false `<` is a swapped `<=`.
    let (op, a, b, negate) = match (op, when, n.is_float()) {
        (o, true, _) => (o, a, b, false),
        (BinOp::Eq, false, _) => (BinOp::Ne, a, b, false),
        (BinOp::Ne, false, _) => (BinOp::Eq, a, b, false),
        (BinOp::Lt, false, false) => (BinOp::Le, b, a, false),
        (_, false, false) => (BinOp::Lt, b, a, false),
        (o, false, true) => (o, a, b, true),
    };
    match (op, n, negate) {
        (BinOp::Lt, Num::F32, true) => Instr::JnltF32 { a, b, t },
        (BinOp::Lt, Num::F64, true) => Instr::JnltF64 { a, b, t },
        (_, Num::F32, true) => Instr::JnleF32 { a, b, t },
        (_, Num::F64, true) => Instr::JnleF64 { a, b, t },
        (BinOp::Eq, Num::F32, _) => Instr::JeqF32 { a, b, t },
        (BinOp::Eq, Num::F64, _) => Instr::JeqF64 { a, b, t },
        (BinOp::Ne, Num::F32, _) => Instr::JneF32 { a, b, t },
        (BinOp::Ne, Num::F64, _) => Instr::JneF64 { a, b, t },
        (BinOp::Eq, n, _) => width_instr(
            n.size(),
            [
                Instr::Jeq8 { a, b, t },
                Instr::Jeq16 { a, b, t },
                Instr::Jeq32 { a, b, t },
                Instr::Jeq64 { a, b, t },
            ],
        ),
        (BinOp::Ne, n, _) => width_instr(
            n.size(),
            [
                Instr::Jne8 { a, b, t },
                Instr::Jne16 { a, b, t },
                Instr::Jne32 { a, b, t },
                Instr::Jne64 { a, b, t },
            ],
        ),
        (BinOp::Lt, n, _) => match n {
            Num::I8 => Instr::JltI8 { a, b, t },
            Num::I16 => Instr::JltI16 { a, b, t },
            Num::I32 => Instr::JltI32 { a, b, t },
            Num::I64 => Instr::JltI64 { a, b, t },
            Num::U8 | Num::B => Instr::JltU8 { a, b, t },
            Num::U16 => Instr::JltU16 { a, b, t },
            Num::U32 => Instr::JltU32 { a, b, t },
            Num::U64 => Instr::JltU64 { a, b, t },
            Num::F32 => Instr::JltF32 { a, b, t },
            Num::F64 => Instr::JltF64 { a, b, t },
        },
        (_, n, _) => match n {
            Num::I8 => Instr::JleI8 { a, b, t },
            Num::I16 => Instr::JleI16 { a, b, t },
            Num::I32 => Instr::JleI32 { a, b, t },
            Num::I64 => Instr::JleI64 { a, b, t },
            Num::U8 | Num::B => Instr::JleU8 { a, b, t },
            Num::U16 => Instr::JleU16 { a, b, t },
            Num::U32 => Instr::JleU32 { a, b, t },
            Num::U64 => Instr::JleU64 { a, b, t },
            Num::F32 => Instr::JleF32 { a, b, t },
            Num::F64 => Instr::JleF64 { a, b, t },
        },
    }
}

/// Whether evaluating `e` or not is indistinguishable: it reads variables
/// and constants and computes without calls, division, conversion, range
/// checks or computed indexes (all of which may fault or have effects).
fn quiet(e: &Expr) -> bool {
    match &e.kind {
        ExprKind::Const(_) | ExprKind::Null => true,
        // A dereference may fault on NULL.
        ExprKind::Load(p) if matches!(p.root, Root::Deref(_)) => false,
        ExprKind::Load(p) => p.proj.iter().all(|pr| match pr {
            Proj::Index(idx) => idx
                .iter()
                .all(|(e, _, _)| matches!(e.unlocated().kind, ExprKind::Const(_))),
            _ => true,
        }),
        ExprKind::Unary(_, x) => quiet(x),
        ExprKind::Binary(op, x, y) => {
            matches!(
                op,
                BinOp::Eq
                    | BinOp::Ne
                    | BinOp::Lt
                    | BinOp::Le
                    | BinOp::Gt
                    | BinOp::Ge
                    | BinOp::And
                    | BinOp::Or
                    | BinOp::Xor
            ) && quiet(x)
                && quiet(y)
        }
        _ => false,
    }
}

/// `IF c THEN EXIT` (exit when `c` is TRUE) or `IF c THEN ELSE EXIT` (when
/// FALSE): the loop test at the top of a FOR or WHILE body.
fn exit_test(s: &Stmt) -> Option<(&Expr, bool)> {
    let StmtKind::If {
        cond,
        then_body,
        else_body,
    } = &s.kind
    else {
        return None;
    };
    let is_break = |b: &[Stmt]| {
        matches!(
            b,
            [Stmt {
                kind: StmtKind::Break,
                ..
            }]
        )
    };
    if else_body.is_empty() && is_break(then_body) {
        Some((cond, true))
    } else if then_body.is_empty() && is_break(else_body) {
        Some((cond, false))
    } else {
        None
    }
}

/// The number of nodes of an expression (to decide whether to repeat it).
fn expr_size(e: &Expr) -> usize {
    1 + match &e.kind {
        ExprKind::Const(_) | ExprKind::CurTime | ExprKind::Null => 0,
        ExprKind::Load(p) | ExprKind::Ref(p) => {
            let root = match &p.root {
                Root::Deref(r) => expr_size(r) + 2,
                _ => 0,
            };
            root + p
                .proj
                .iter()
                .map(|pr| match pr {
                    Proj::Index(idx) => idx.iter().map(|(e, _, _)| expr_size(e)).sum(),
                    _ => 0,
                })
                .sum::<usize>()
        }
        ExprKind::Unary(_, x) | ExprKind::Convert(x) => expr_size(x),
        ExprKind::Check { value, .. } => expr_size(value),
        ExprKind::Located { expr, .. } => expr_size(expr),
        ExprKind::Binary(_, x, y) => expr_size(x) + expr_size(y),
        ExprKind::CallFn { .. } => 100,
        ExprKind::Intrinsic { args, .. } => args.iter().map(expr_size).sum(),
    }
}

/// Whether a conversion between scalars of this type is the plain numeric
/// `cvt` (time and date types and characters convert through `stc_values`:
/// calendars, and WCHAR to CHAR faults above 255).
fn plain_numeric(t: Option<ElemType>) -> bool {
    t.is_some_and(|t| {
        Num::of(t).is_some()
            && !stc_values::is_time_like(t)
            && !matches!(t, ElemType::Char | ElemType::Wchar)
    })
}
