//! Memory layout of every type and POU, for back ends that work with bytes
//! (the VM and the process image). Decided once, here.
//!
//! Scalars have their natural size and alignment; BOOL takes one byte;
//! TIME, LTIME and all date types are 8-byte integers (nanoseconds, or
//! seconds for DATE); a STRING[n] is a 2-byte length followed by n bytes
//! (WSTRING: n 2-byte units); references (VAR_IN_OUT, VAR_EXTERNAL) are
//! 4-byte addresses. Structs and instances lay their members out in order,
//! each aligned to its own alignment.

use stc_diagnostics::{Code, Diagnostic, Span};
use stc_sema::idx::IdVec;
use stc_sema::{PouId, TypeId, TypeKind, TypeTable, VarId};
use stc_syntax::ast::PouKind;
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

fn align_up(x: u64, a: u32) -> Option<u64> {
    let a = u64::from(a.max(1));
    x.checked_next_multiple_of(a)
}

/// The memory model's limit, in bytes, on every type, every POU instance,
/// every frame and the data area (globals and program instances): 1 GiB.
/// The VM addresses its whole memory (data area, constants, stack) with
/// 30-bit operand offsets, so nothing larger can be placed; a declaration
/// over the limit is error E0901 (docs/runtime.md, "Memory").
pub const MAX_SIZE: u64 = 1 << 30;

/// A layout that could not be given: what needs more than [`MAX_SIZE`].
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
struct TooLarge {
    /// The size needed, when it fits in a `u64`.
    size: Option<u64>,
    /// Whether a diagnostic has been reported for it (at a named type or a
    /// declaration inside it), so users of the type report nothing more.
    reported: bool,
}

type Lay = Result<Layout, TooLarge>;

/// A size as a layout, if it is within the limit.
fn checked(size: Option<u64>, align: u32) -> Lay {
    match size {
        Some(s) if s <= MAX_SIZE => Ok(Layout {
            size: s as u32,
            align,
        }),
        _ => Err(TooLarge {
            size,
            reported: false,
        }),
    }
}

/// "needs 5248000328 bytes" or "needs more than ... bytes".
fn needs(size: Option<u64>) -> String {
    match size {
        Some(s) => format!("needs {s} bytes"),
        None => format!("needs more than {} bytes", u64::MAX),
    }
}

/// Layouts of all types and POUs of a module.
#[derive(Debug)]
pub struct Layouts {
    /// By type: not computed yet (`None`), or its layout.
    types: Vec<Option<Lay>>,
    /// Offset of each struct field, by type.
    fields: Vec<Vec<u32>>,
    pub pous: IdVec<PouId, PouLayout>,
    /// By POU: whether its instance and frame fit (`Err`: too large).
    pou_ok: IdVec<PouId, Result<(), TooLarge>>,
    /// By type: whether its being too large is reported at a declaration
    /// of it, or is part of an enclosing array's (reported with it).
    covered: Vec<bool>,
    diagnostics: Vec<Diagnostic>,
}

/// Where the variables of a POU live: in the instance (function blocks and
/// programs) or in the frame of a call.
#[derive(Clone, Debug, Default)]
pub struct PouLayout {
    pub instance: Layout,
    pub frame: Layout,
    /// Offset of each variable in the instance or in the frame (by storage).
    pub offsets: IdVec<VarId, u32>,
    /// Whether each variable lives in the frame.
    pub in_frame: IdVec<VarId, bool>,
}

impl Default for Layout {
    fn default() -> Self {
        Layout { size: 0, align: 1 }
    }
}

/// One area (an instance or a frame) being laid out, in bytes.
struct Area {
    size: Option<u64>,
    align: u32,
}

impl Area {
    fn new() -> Area {
        Area {
            size: Some(0),
            align: 1,
        }
    }

    /// Places a member of layout `l`; its offset, while the area fits.
    fn place(&mut self, l: Layout) -> Option<u32> {
        let off = self.size.and_then(|s| align_up(s, l.align));
        self.size = off.and_then(|o| o.checked_add(u64::from(l.size)));
        self.align = self.align.max(l.align);
        off.filter(|&o| o <= MAX_SIZE).map(|o| o as u32)
    }

    /// The area's layout, padded to its alignment.
    fn finish(&self) -> Lay {
        checked(self.size.and_then(|s| align_up(s, self.align)), self.align)
    }
}

impl Layouts {
    /// The layout of every type and POU of a module, or the diagnostics
    /// (E0901) of the declarations too large for the memory model: no
    /// layout is ever given with a size or offset that overflowed.
    pub fn compute(m: &Module) -> Result<Layouts, Vec<Diagnostic>> {
        let mut l = Layouts {
            types: vec![None; m.types.len()],
            fields: vec![Vec::new(); m.types.len()],
            pous: m.pous.iter().map(|_| PouLayout::default()).collect(),
            pou_ok: m.pous.iter().map(|_| Ok(())).collect(),
            covered: vec![false; m.types.len()],
            diagnostics: Vec::new(),
        };
        let mut state: IdVec<PouId, u8> = m.pous.iter().map(|_| 0).collect();
        for p in m.pous.ids() {
            l.pou(m, p, &mut state);
        }
        for g in &m.globals {
            let what = format!("global `{}`", m.spelled(g.name, g.span));
            let _ = l.decl(m, g.ty, g.span, what, &mut state);
        }
        // The types of references too, once every instance is laid out (a
        // VAR_EXTERNAL no global binds gets a variable of its own).
        for pou in &m.pous {
            for v in pou.vars.iter().filter(|v| v.storage == Storage::Ref) {
                let what = format!("variable `{}`", m.spelled(v.name, v.span));
                let _ = l.decl(m, v.ty, v.span, what, &mut state);
            }
        }
        for t in 0..m.types.len() {
            let t = TypeId(t as u32);
            // An anonymous type too large is reported where it is declared
            // (variable, member, global); one used nowhere, at its own
            // span: no type is left without a layout and without an error.
            if let Err(e) = l.ty(m, t, &mut state) {
                if !e.reported && !l.covered[t.0 as usize] {
                    let span = m.types.get(t).span.unwrap_or_default();
                    l.report(span, "the type".into(), e.size);
                    l.types[t.0 as usize] = Some(Err(TooLarge {
                        reported: true,
                        ..e
                    }));
                }
            }
        }
        l.data_area(m);
        if l.diagnostics.is_empty() {
            Ok(l)
        } else {
            Err(l.diagnostics)
        }
    }

    /// The diagnostics of [`Layouts::compute`] alone.
    pub fn check(m: &Module) -> Vec<Diagnostic> {
        Layouts::compute(m).err().unwrap_or_default()
    }

    fn report(&mut self, span: Span, what: String, size: Option<u64>) {
        self.diagnostics.push(
            Diagnostic::new(
                Code::E0901,
                span,
                format!(
                    "{what} {}; the limit is {MAX_SIZE} bytes (1 GiB)",
                    needs(size)
                ),
            )
            .with_label("too large for the memory model"),
        );
    }

    /// The layout of a declaration of type `t` named `what` at `span`,
    /// reporting it when its (anonymous) type is too large.
    fn decl(
        &mut self,
        m: &Module,
        t: TypeId,
        span: Span,
        what: String,
        state: &mut IdVec<PouId, u8>,
    ) -> Lay {
        let l = self.ty(m, t, state);
        match l {
            Err(e) if !e.reported => {
                self.report(span, what, e.size);
                if let Some(c) = self.covered.get_mut(t.0 as usize) {
                    *c = true;
                }
                Err(TooLarge {
                    reported: true,
                    ..e
                })
            }
            l => l,
        }
    }

    /// The globals and the program instances (of every configuration, and
    /// one of every PROGRAM run on its own) together: the data area.
    fn data_area(&mut self, m: &Module) {
        if !self.diagnostics.is_empty() {
            return;
        }
        let mut area = Area::new();
        let mut objects: Vec<(Layout, Span, String)> = Vec::new();
        // The user's globals first, then the library's, wherever the
        // library's file sits among the user's.
        let user_first = m.globals.iter().filter(|g| !g.library);
        for g in user_first.chain(m.globals.iter().filter(|g| g.library)) {
            if g.location.as_ref().is_some_and(|a| !a.is_incomplete()) {
                continue;
            }
            let what = format!("global `{}`", m.spelled(g.name, g.span));
            objects.push((self.of(g.ty), g.span, what));
        }
        for c in &m.configs {
            for r in &c.resources {
                for i in &r.programs {
                    let what = format!("program instance `{}`", m.spelled(i.name, i.name_span));
                    let lay = self.pous[i.pou].instance;
                    objects.push((lay, i.name_span, what));
                }
            }
        }
        for (p, pou) in m.pous.iter_enumerated() {
            if pou.kind == PouKind::Program {
                let what = format!("program `{}`", m.spelled(pou.name, pou.name_span));
                objects.push((self.pous[p].instance, pou.name_span, what));
            }
        }
        for (lay, span, what) in objects {
            area.place(lay);
            if area.size.is_none_or(|s| s > MAX_SIZE) {
                self.report(
                    span,
                    format!("the data area (globals and program instances) up to {what}"),
                    area.size,
                );
                return;
            }
        }
    }

    fn pou(&mut self, m: &Module, p: PouId, state: &mut IdVec<PouId, u8>) {
        if state[p] != 0 {
            // 1: in progress (an instance containing itself is reported by
            // the analyser as recursion), 2: done.
            return;
        }
        state[p] = 1;
        let pou: &Pou = &m.pous[p];
        let function = pou.kind == PouKind::Function;
        let mut inst = Area::new();
        let mut frame = Area::new();
        let mut offsets = Vec::with_capacity(pou.vars.len());
        let mut in_frame = Vec::with_capacity(pou.vars.len());
        let mut ok: Result<(), TooLarge> = Ok(());
        for v in &pou.vars {
            let vl = match v.storage {
                Storage::Ref => Ok(Layout {
                    size: REF_SIZE,
                    align: REF_SIZE,
                }),
                _ => {
                    let what = format!("variable `{}`", m.spelled(v.name, v.span));
                    self.decl(m, v.ty, v.span, what, state)
                }
            };
            let frame_var = v.storage == Storage::Frame || (function && v.storage == Storage::Ref);
            let area = if frame_var { &mut frame } else { &mut inst };
            let off = match vl {
                Ok(vl) => area.place(vl),
                Err(e) => {
                    ok = Err(e);
                    area.size = None;
                    None
                }
            };
            offsets.push(off.unwrap_or(0));
            in_frame.push(frame_var);
        }
        let name = m.spelled(pou.name, pou.name_span).to_string();
        let mut finish = |area: &Area, what: &str, l: &mut Layouts| -> Layout {
            match area.finish() {
                Ok(lay) => lay,
                Err(e) => {
                    if ok.is_ok() {
                        l.report(pou.name_span, format!("the {what} of `{name}`"), e.size);
                        ok = Err(TooLarge {
                            reported: true,
                            ..e
                        });
                    }
                    Layout::default()
                }
            }
        };
        let instance = finish(&inst, "instance", self);
        let frame = finish(&frame, "frame", self);
        self.pous[p] = PouLayout {
            instance,
            frame,
            offsets: offsets.into(),
            in_frame: in_frame.into(),
        };
        self.pou_ok[p] = ok;
        state[p] = 2;
    }

    fn ty(&mut self, m: &Module, t: TypeId, state: &mut IdVec<PouId, u8>) -> Lay {
        if let Some(l) = self.types.get(t.0 as usize).copied().flatten() {
            return l;
        }
        let l = match m.types.kind(t).clone() {
            TypeKind::Error | TypeKind::Void => Ok(Layout { size: 0, align: 1 }),
            TypeKind::Ref(_) | TypeKind::Ptr(_) => Ok(Layout {
                size: REF_SIZE,
                align: REF_SIZE,
            }),
            TypeKind::Elem(e) => Ok(Layout {
                size: elem_size(e),
                align: elem_size(e),
            }),
            TypeKind::Subrange { base, .. } | TypeKind::Enum { base, .. } => Ok(Layout {
                size: elem_size(base),
                align: elem_size(base),
            }),
            TypeKind::String { wide, len } => checked(
                u64::from(len)
                    .checked_mul(if wide { 2 } else { 1 })
                    .and_then(|n| n.checked_add(2)),
                2,
            ),
            TypeKind::Array { dims, elem } => {
                let count = dims.iter().try_fold(1u64, |n, (lo, hi)| {
                    // (Bounds are checked by the analyser: lo <= hi.)
                    let c = u64::try_from(hi.checked_sub(*lo)?.checked_add(1)?.max(0)).ok()?;
                    n.checked_mul(c)
                });
                match self.ty(m, elem, state) {
                    Ok(el) => {
                        let stride = align_up(u64::from(el.size), el.align);
                        checked(
                            stride.zip(count).and_then(|(s, n)| s.checked_mul(n)),
                            el.align,
                        )
                    }
                    // An element too large: the array needs `count` times
                    // its size (for the message where it is reported).
                    Err(e) if !e.reported => {
                        if let Some(c) = self.covered.get_mut(elem.0 as usize) {
                            *c = true;
                        }
                        Err(TooLarge {
                            size: e.size.zip(count).and_then(|(s, n)| s.checked_mul(n)),
                            reported: false,
                        })
                    }
                    Err(e) => Err(e),
                }
            }
            TypeKind::Struct { fields } => {
                let mut area = Area::new();
                let mut offs = Vec::with_capacity(fields.len());
                let mut bad = None;
                for f in &fields {
                    let what = format!("member `{}`", m.spelled(f.name, f.span));
                    match self.decl(m, f.ty, f.span, what, state) {
                        Ok(fl) => offs.push(area.place(fl).unwrap_or(0)),
                        Err(e) => {
                            bad = Some(e);
                            offs.push(0);
                        }
                    }
                }
                if let Some(slot) = self.fields.get_mut(t.0 as usize) {
                    *slot = offs;
                }
                match bad {
                    Some(e) => Err(e),
                    None => area.finish(),
                }
            }
            TypeKind::Fb(p) | TypeKind::Program(p) => {
                self.pou(m, p, state);
                if state[p] != 2 {
                    // An instance containing itself (the analyser reports
                    // the recursion): no size, and nothing cached.
                    return Ok(Layout::default());
                }
                self.pou_ok[p].map(|()| self.pous[p].instance)
            }
        };
        // A named type too large is reported at its name, once.
        let l = match (l, m.types.get(t).name_span) {
            (Err(e), Some(span)) if !e.reported => {
                let what = match m.type_name(t) {
                    Some(n) => format!("type `{n}`"),
                    None => "the type".to_string(),
                };
                self.report(span, what, e.size);
                Err(TooLarge {
                    reported: true,
                    ..e
                })
            }
            (l, _) => l,
        };
        if let Some(slot) = self.types.get_mut(t.0 as usize) {
            *slot = Some(l);
        }
        l
    }

    /// The layout of a type (of the module the layouts were computed
    /// for: every type has one).
    ///
    /// # Panics
    /// For a type of another module: [`Layouts::compute`] succeeds only
    /// when every type of its module has a layout.
    pub fn of(&self, t: TypeId) -> Layout {
        match self.types.get(t.0 as usize) {
            Some(Some(Ok(l))) => *l,
            _ => panic!("no layout for type {}", t.0),
        }
    }

    /// Offset of a struct member (of a struct type of the module).
    pub fn field_offset(&self, t: TypeId, field: u32) -> u32 {
        self.fields[t.0 as usize][field as usize]
    }

    /// Size of one element of an array type, including alignment padding.
    pub fn stride(&self, types: &TypeTable, t: TypeId) -> u32 {
        match types.kind(t) {
            TypeKind::Array { elem, .. } => {
                let l = self.of(*elem);
                // (Within the limit: the array's size is a multiple of it.)
                align_up(u64::from(l.size), l.align).map_or(0, |s| s as u32)
            }
            _ => 0,
        }
    }

    /// Offset of a variable of a POU of the module, in its instance or
    /// frame.
    pub fn var_offset(&self, p: stc_sema::PouId, v: VarId) -> u32 {
        self.pous[p].offsets[v]
    }
}

#[cfg(test)]
mod tests;
