//! A loaded program: code, constants, the initial data image, and every
//! table the runtime needs (types, variables, configurations, the process
//! image, debug lines). This is what a `.stbc` file holds.
//!
//! Memory is one byte array, in this order: the data area (globals, program
//! instances with their nested function block instances, the process image
//! slots), the constant pool, then the stack of call frames. Addresses are
//! `u32` byte offsets into it.

use std::sync::Arc;

use stc_syntax::token::ElemType;

pub use stc_ir::model::{
    ConfigDesc, FieldDesc, GlobalDesc, IoSlot, Model, PouDesc, PouKind, ProgramInst, ResourceDesc,
    Source, TaskDesc, TypeDesc, TypeDescKind, TypeRef, VarDesc, VarKind,
};

use crate::instr::Instr;

#[derive(Clone, Debug, PartialEq)]
pub struct Image {
    pub code: Vec<Instr>,
    /// The constant pool, placed at [`Image::const_base`].
    pub consts: Vec<u8>,
    /// Size of the data area; its initial contents are `init`.
    pub data_size: u32,
    pub init: Vec<u8>,
    /// Size of the stack area (the deepest chain of frames).
    pub stack_size: u32,
    /// The program model (`stc_ir::model`) with the data area's addresses.
    pub model: Arc<Model>,
    /// By POU, as `model.pous`: the code and frame of each.
    pub pous: Vec<PouCode>,
    /// Calls of standard functions and generic operations (by descriptor).
    pub calls: Vec<StdCall>,
    /// Array dimensions indexed by the `elem` instructions.
    pub elems: Vec<ElemDesc>,
    /// Source positions: for each instruction index where a statement starts.
    pub lines: Vec<LineEntry>,
    pub files: Vec<String>,
}

impl Image {
    /// Where the constant pool starts.
    pub fn const_base(&self) -> u32 {
        self.data_size
    }

    /// Where the stack starts.
    pub fn stack_base(&self) -> u32 {
        self.data_size + self.consts.len() as u32
    }

    /// The elementary type a value of type `t` is stored as (see
    /// [`Model::scalar_of`]).
    pub fn scalar_of(&self, t: TypeRef) -> Option<ElemType> {
        self.model.scalar_of(t)
    }

    /// The size of a value of type `t` (see [`Model::type_size`]): the
    /// verifier rejects an image that places a value without one.
    pub fn type_size(&self, t: TypeRef) -> u64 {
        self.model.type_size(t)
    }

    /// See [`Model::checked_type_size`].
    pub fn checked_type_size(&self, t: TypeRef) -> Option<u64> {
        self.model.checked_type_size(t)
    }

    /// POU `i`: its model and its code together.
    pub fn pou(&self, i: usize) -> Option<PouView<'_>> {
        let d = self.model.pous.get(i)?;
        let c = self.pous.get(i)?;
        Some(PouView {
            name: &d.name,
            kind: d.kind,
            entry: c.entry,
            instance_size: d.instance_size,
            frame_size: c.frame_size,
            frame_init_at: c.frame_init_at,
            frame_template: c.frame_template,
            instance_type: d.instance_type,
            vars: &d.vars,
        })
    }

    /// The whole memory: data area, constants, stack (in `u64`: a loaded
    /// file may claim any sizes; the verifier bounds them).
    pub fn memory_size(&self) -> u64 {
        u64::from(self.data_size) + self.consts.len() as u64 + u64::from(self.stack_size)
    }

    /// The POU (by index) whose code holds the instruction at `pc`.
    pub fn pou_at(&self, pc: u32) -> Option<u32> {
        let i = match self.lines.binary_search_by_key(&pc, |l| l.pc) {
            Ok(i) => i,
            Err(0) => return None,
            Err(i) => i - 1,
        };
        Some(self.lines[i].pou)
    }

    /// The source position of an instruction: (POU, file, line, column).
    pub fn position(&self, pc: u32) -> Option<(&str, &str, u32, u32)> {
        let i = match self.lines.binary_search_by_key(&pc, |l| l.pc) {
            Ok(i) => i,
            Err(0) => return None,
            Err(i) => i - 1,
        };
        let l = &self.lines[i];
        let pou = self.model.pous.get(l.pou as usize)?;
        let file = self
            .files
            .get(l.file as usize)
            .map(|s| s.as_str())
            .unwrap_or("?");
        Some((pou.name.as_str(), file, l.line, l.col))
    }
}

/// A POU's model and code seen together ([`Image::pou`]).
#[derive(Clone, Copy, Debug)]
pub struct PouView<'a> {
    pub name: &'a str,
    pub kind: PouKind,
    pub entry: u32,
    pub instance_size: u32,
    pub frame_size: u32,
    pub frame_init_at: u32,
    pub frame_template: (u32, u32),
    pub instance_type: TypeRef,
    pub vars: &'a [VarDesc],
}

/// A POU's code and frame (its variables are in the model).
#[derive(Clone, Debug, PartialEq)]
pub struct PouCode {
    /// First instruction of the body.
    pub entry: u32,
    /// Size of one call frame, including temporaries and argument areas.
    pub frame_size: u32,
    /// The frame's initial bytes from `frame_init_at` on: a range of the
    /// constant pool copied at each call (VAR_TEMP, a function's locals).
    pub frame_init_at: u32,
    pub frame_template: (u32, u32),
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct LineEntry {
    pub pc: u32,
    pub pou: u32,
    pub file: u32,
    pub line: u32,
    pub col: u32,
}

/// A call of a standard function (or a generic operation) evaluated through
/// `stc_values`: the operation, operand addresses and their types.
#[derive(Clone, Debug, PartialEq)]
pub struct StdCall {
    pub op: StdOp,
    pub args: Vec<(crate::instr::Op, ElemType, u32)>,
    pub result: (crate::instr::Op, ElemType, u32),
}

#[derive(Clone, Copy, Debug, PartialEq)]
pub enum StdOp {
    Call(stc_values::Intrinsic),
    Binary(stc_values::BinOp),
    Unary(stc_values::UnOp),
    Convert,
    Trunc,
}

/// One dimension of an array as the `elem` instructions index it: element
/// `idx` (read as the scalar kind `num`) is at `(idx - lo) * stride` bytes
/// from the start, for `lo <= idx < lo + count`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct ElemDesc {
    pub lo: i64,
    pub count: u32,
    pub stride: u32,
    pub num: crate::num::Num,
}
