//! Memory layout of every type and POU, for back ends that work with bytes
//! (the VM and the process image). Decided once, here.
//!
//! Scalars have their natural size and alignment; BOOL takes one byte;
//! TIME, LTIME and all date types are 8-byte integers (nanoseconds, or
//! seconds for DATE); a STRING[n] is a 2-byte length followed by n bytes
//! (WSTRING: n 2-byte units); references (VAR_IN_OUT, VAR_EXTERNAL) are
//! 4-byte addresses. Structs and instances lay their members out in order,
//! each aligned to its own alignment.

use stc_sema::{TypeId, TypeKind, TypeTable, VarId};
use stc_syntax::token::ElemType;

use crate::{Module, Pou, Storage};

/// Size in bytes of a reference.
pub const REF_SIZE: u32 = 4;

#[derive(Clone, Copy, PartialEq, Eq, Debug)]
pub struct Layout {
    pub size: u32,
    pub align: u32,
}

pub fn elem_size(e: ElemType) -> u32 {
    use ElemType as E;
    match e {
        E::Bool | E::Sint | E::Usint | E::Byte | E::Char => 1,
        E::Int | E::Uint | E::Word | E::Wchar => 2,
        E::Dint | E::Udint | E::Dword | E::Real => 4,
        E::Lint
        | E::Ulint
        | E::Lword
        | E::Lreal
        | E::Time
        | E::Ltime
        | E::Date
        | E::Ldate
        | E::Tod
        | E::Ltod
        | E::Dt
        | E::Ldt => 8,
        E::String | E::Wstring => 2,
    }
}

fn align_up(x: u32, a: u32) -> u32 {
    x.div_ceil(a.max(1)) * a.max(1)
}

/// Layouts of all types and POUs of a module.
pub struct Layouts {
    types: Vec<Option<Layout>>,
    /// Offset of each struct field, by type.
    fields: Vec<Vec<u32>>,
    pub pous: Vec<PouLayout>,
}

/// Where the variables of a POU live: in the instance (function blocks and
/// programs) or in the frame of a call.
#[derive(Clone, Debug, Default)]
pub struct PouLayout {
    pub instance: Layout,
    pub frame: Layout,
    /// Offset of each variable in the instance or in the frame (by storage).
    pub offsets: Vec<u32>,
    /// Whether each variable lives in the frame.
    pub in_frame: Vec<bool>,
}

impl Default for Layout {
    fn default() -> Self {
        Layout { size: 0, align: 1 }
    }
}

impl Layouts {
    pub fn compute(m: &Module) -> Layouts {
        let mut l = Layouts {
            types: vec![None; m.types.len()],
            fields: vec![Vec::new(); m.types.len()],
            pous: vec![PouLayout::default(); m.pous.len()],
        };
        let mut state = vec![0u8; m.pous.len()];
        for p in 0..m.pous.len() {
            l.pou(m, p, &mut state);
        }
        for t in 0..m.types.len() {
            l.ty(m, TypeId(t as u32), &mut state);
        }
        l
    }

    fn pou(&mut self, m: &Module, p: usize, state: &mut [u8]) {
        if state[p] != 0 {
            // 1: in progress (an instance containing itself is reported by
            // the analyser as recursion; give it no size).
            return;
        }
        state[p] = 1;
        let pou: &Pou = &m.pous[p];
        let function = pou.kind == stc_syntax::ast::PouKind::Function;
        let mut inst = Layout::default();
        let mut frame = Layout::default();
        let mut offsets = Vec::with_capacity(pou.vars.len());
        let mut in_frame = Vec::with_capacity(pou.vars.len());
        for v in &pou.vars {
            let vl = match v.storage {
                Storage::Ref => Layout {
                    size: REF_SIZE,
                    align: REF_SIZE,
                },
                _ => self.ty(m, v.ty, state),
            };
            let frame_var = v.storage == Storage::Frame || (function && v.storage == Storage::Ref);
            let area = if frame_var { &mut frame } else { &mut inst };
            let off = align_up(area.size, vl.align);
            area.size = off + vl.size;
            area.align = area.align.max(vl.align);
            offsets.push(off);
            in_frame.push(frame_var);
        }
        inst.size = align_up(inst.size, inst.align);
        frame.size = align_up(frame.size, frame.align);
        self.pous[p] = PouLayout {
            instance: inst,
            frame,
            offsets,
            in_frame,
        };
        state[p] = 2;
    }

    fn ty(&mut self, m: &Module, t: TypeId, state: &mut [u8]) -> Layout {
        if let Some(l) = self.types.get(t.0 as usize).copied().flatten() {
            return l;
        }
        let l = match m.types.kind(t).clone() {
            TypeKind::Error | TypeKind::Void => Layout { size: 0, align: 1 },
            TypeKind::Elem(e) => Layout {
                size: elem_size(e),
                align: elem_size(e),
            },
            TypeKind::Subrange { base, .. } | TypeKind::Enum { base, .. } => Layout {
                size: elem_size(base),
                align: elem_size(base),
            },
            TypeKind::String { wide, len } => Layout {
                size: 2 + len * if wide { 2 } else { 1 },
                align: 2,
            },
            TypeKind::Array { dims, elem } => {
                let el = self.ty(m, elem, state);
                let stride = align_up(el.size, el.align);
                let count: i128 = dims.iter().map(|(lo, hi)| hi - lo + 1).product();
                Layout {
                    size: (stride as i128 * count).min(u32::MAX as i128) as u32,
                    align: el.align,
                }
            }
            TypeKind::Struct { fields } => {
                let mut size = 0;
                let mut align = 1;
                let mut offs = Vec::with_capacity(fields.len());
                for f in &fields {
                    let fl = self.ty(m, f.ty, state);
                    let off = align_up(size, fl.align);
                    offs.push(off);
                    size = off + fl.size;
                    align = align.max(fl.align);
                }
                if let Some(slot) = self.fields.get_mut(t.0 as usize) {
                    *slot = offs;
                }
                Layout {
                    size: align_up(size, align),
                    align,
                }
            }
            TypeKind::Fb(p) | TypeKind::Program(p) => {
                self.pou(m, p.0 as usize, state);
                self.pous[p.0 as usize].instance
            }
        };
        if let Some(slot) = self.types.get_mut(t.0 as usize) {
            *slot = Some(l);
        }
        l
    }

    pub fn of(&self, t: TypeId) -> Layout {
        self.types
            .get(t.0 as usize)
            .copied()
            .flatten()
            .unwrap_or_default()
    }

    /// Offset of a struct member.
    pub fn field_offset(&self, t: TypeId, field: u32) -> u32 {
        self.fields
            .get(t.0 as usize)
            .and_then(|f| f.get(field as usize))
            .copied()
            .unwrap_or(0)
    }

    /// Size of one element of an array type, including alignment padding.
    pub fn stride(&self, types: &TypeTable, t: TypeId) -> u32 {
        match types.kind(t) {
            TypeKind::Array { elem, .. } => {
                let l = self.of(*elem);
                align_up(l.size, l.align)
            }
            _ => 0,
        }
    }

    pub fn var_offset(&self, p: stc_sema::PouId, v: VarId) -> u32 {
        self.pous[p.0 as usize]
            .offsets
            .get(v.0 as usize)
            .copied()
            .unwrap_or(0)
    }
}
