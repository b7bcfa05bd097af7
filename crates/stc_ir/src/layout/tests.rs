//! Properties of the layout over random nested types (structs of arrays of
//! structs, strings, scalars of every size, function block instances, in
//! instances, frames and globals), against an independent model of the
//! sizes computed without any limit: members never overlap and lie inside
//! their parent, aligned; an array is its count times its stride; every
//! size is the model's; and whatever the model finds over the limit gives
//! E0901 diagnostics (one per declaration) instead of a layout.

use proptest::prelude::*;
use stc_diagnostics::{Code, Span};
use stc_sema::idx::Idx;
use stc_sema::types::Field;
use stc_sema::{PouId, Section, TypeId, TypeKind, TypeTable, VarId};
use stc_syntax::ast::PouKind;
use stc_syntax::token::ElemType;
use stc_syntax::Symbol;

use super::{Layouts, MAX_SIZE};
use crate::{Global, Module, Pou, Storage, Var};

const SCALARS: &[ElemType] = &[
    ElemType::Bool,
    ElemType::Sint,
    ElemType::Byte,
    ElemType::Int,
    ElemType::Word,
    ElemType::Dint,
    ElemType::Real,
    ElemType::Lint,
    ElemType::Lreal,
    ElemType::Time,
    ElemType::Dt,
];

/// A type to build.
#[derive(Clone, Debug)]
enum Spec {
    Scalar(usize),
    Str {
        wide: bool,
        len: u32,
    },
    /// Dimensions as (low bound, count).
    Array(Vec<(i64, u64)>, Box<Spec>),
    Struct {
        named: bool,
        fields: Vec<Spec>,
    },
    /// A function block with variables (and how each is stored).
    Fb(Vec<(Spec, Kind)>),
}

#[derive(Clone, Copy, Debug, PartialEq)]
enum Kind {
    Instance,
    Frame,
    Ref,
}

fn count() -> impl Strategy<Value = u64> {
    prop_oneof![6 => 1u64..5, 1 => 1u64..20_000_000]
}

fn kind() -> impl Strategy<Value = Kind> {
    prop_oneof![4 => Just(Kind::Instance), 1 => Just(Kind::Frame), 1 => Just(Kind::Ref)]
}

fn spec() -> impl Strategy<Value = Spec> {
    let leaf = prop_oneof![
        (0..SCALARS.len()).prop_map(Spec::Scalar),
        (any::<bool>(), 1u32..300).prop_map(|(wide, len)| Spec::Str { wide, len }),
    ];
    leaf.prop_recursive(4, 24, 4, |inner| {
        prop_oneof![
            (
                prop::collection::vec((-3i64..3, count()), 1..3),
                inner.clone()
            )
                .prop_map(|(d, e)| Spec::Array(d, Box::new(e))),
            (any::<bool>(), prop::collection::vec(inner.clone(), 1..4))
                .prop_map(|(named, fields)| Spec::Struct { named, fields }),
            prop::collection::vec((inner, kind()), 1..4).prop_map(Spec::Fb),
        ]
    })
}

/// The model: size and alignment without any limit (`None`: beyond u128).
fn model(s: &Spec) -> (Option<u128>, u128) {
    fn up(x: Option<u128>, a: u128) -> Option<u128> {
        x.and_then(|x| x.checked_next_multiple_of(a))
    }
    fn area(members: impl Iterator<Item = (Option<u128>, u128)>) -> (Option<u128>, u128) {
        let mut size = Some(0u128);
        let mut align = 1;
        for (s, a) in members {
            size = up(size, a).zip(s).and_then(|(o, s)| o.checked_add(s));
            align = align.max(a);
        }
        (up(size, align), align)
    }
    match s {
        Spec::Scalar(i) => {
            let n = u128::from(super::elem_size(SCALARS[*i]));
            (Some(n), n)
        }
        Spec::Str { wide, len } => (Some(2 + u128::from(*len) * if *wide { 2 } else { 1 }), 2),
        Spec::Array(dims, e) => {
            let (es, ea) = model(e);
            let n = dims
                .iter()
                .try_fold(1u128, |n, (_, c)| n.checked_mul(u128::from(*c)));
            (up(es, ea).zip(n).and_then(|(s, n)| s.checked_mul(n)), ea)
        }
        Spec::Struct { fields, .. } => area(fields.iter().map(model)),
        Spec::Fb(vars) => area(
            vars.iter()
                .filter(|(_, k)| *k != Kind::Frame)
                .map(|(s, k)| {
                    if *k == Kind::Ref {
                        (Some(4), 4)
                    } else {
                        model(s)
                    }
                }),
        ),
    }
}

/// Whether a type or anything inside it is over the limit in the model.
fn too_large(s: &Spec) -> bool {
    let over = |s: &Spec| model(s).0.is_none_or(|n| n > u128::from(MAX_SIZE));
    over(s)
        || match s {
            Spec::Array(_, e) => too_large(e),
            Spec::Struct { fields, .. } => fields.iter().any(too_large),
            Spec::Fb(vars) => {
                vars.iter().any(|(s, _)| too_large(s))
                    || area_over(vars.iter().filter(|(_, k)| *k == Kind::Frame))
            }
            _ => false,
        }
}

/// Whether the frame of these variables is over the limit in the model.
fn area_over<'a>(vars: impl Iterator<Item = &'a (Spec, Kind)>) -> bool {
    let st = Spec::Struct {
        named: false,
        fields: vars.map(|(s, _)| s.clone()).collect(),
    };
    model(&st).0.is_none_or(|n| n > u128::from(MAX_SIZE))
}

/// Builds a module from specs: every built type and POU, with unique
/// declaration spans.
struct Builder {
    types: TypeTable,
    pous: Vec<Pou>,
    next_span: u32,
}

impl Builder {
    fn span(&mut self) -> Span {
        self.next_span += 2;
        Span {
            lo: self.next_span,
            hi: self.next_span + 1,
        }
    }

    fn var(&mut self, ty: TypeId, k: Kind) -> Var {
        Var {
            name: Symbol(0),
            ty,
            section: match k {
                Kind::Instance => Section::Var,
                Kind::Frame => Section::Temp,
                Kind::Ref => Section::InOut,
            },
            storage: match k {
                Kind::Instance => Storage::Instance,
                Kind::Frame => Storage::Frame,
                Kind::Ref => Storage::Ref,
            },
            init: None,
            constant: false,
            retain: false,
            location: None,
            hidden: None,
            span: self.span(),
        }
    }

    fn pou(&mut self, kind: PouKind, vars: Vec<Var>) -> PouId {
        let name_span = self.span();
        self.pous.push(Pou {
            kind,
            name: Symbol(0),
            vars: vars.into(),
            result: None,
            body: Vec::new(),
            is_std: false,
            span: name_span,
            name_span,
            file: String::new(),
        });
        PouId(self.pous.len() as u32 - 1)
    }

    fn ty(&mut self, s: &Spec) -> TypeId {
        match s {
            Spec::Scalar(i) => self.types.elem(SCALARS[*i]),
            Spec::Str { wide, len } => self.types.string(*wide, *len),
            Spec::Array(dims, e) => {
                let elem = self.ty(e);
                let dims = dims
                    .iter()
                    .map(|&(lo, c)| (i128::from(lo), i128::from(lo) + i128::from(c) - 1))
                    .collect();
                let span = self.span();
                self.types
                    .add(TypeKind::Array { dims, elem }, None, Some(span))
            }
            Spec::Struct { named, fields } => {
                let fields = fields
                    .iter()
                    .map(|f| Field {
                        name: Symbol(0),
                        ty: self.ty(f),
                        init: None,
                        span: self.span(),
                    })
                    .collect();
                let span = self.span();
                let t = self.types.add(
                    TypeKind::Struct { fields },
                    named.then_some(Symbol(0)),
                    Some(span),
                );
                if *named {
                    self.types.set_name_span(t, span);
                }
                t
            }
            Spec::Fb(vars) => {
                let vars = vars
                    .iter()
                    .map(|(s, k)| {
                        let t = self.ty(s);
                        self.var(t, *k)
                    })
                    .collect();
                let p = self.pou(PouKind::FunctionBlock, vars);
                let span = self.span();
                let t = self.types.add(TypeKind::Fb(p), Some(Symbol(0)), Some(span));
                self.types.set_name_span(t, span);
                t
            }
        }
    }
}

/// A program with `vars` (the last POU), a function with `locals`, and
/// `globals`.
fn module(vars: &[(Spec, Kind)], locals: &[Spec], globals: &[Spec]) -> Module {
    let mut b = Builder {
        types: TypeTable::new(),
        pous: Vec::new(),
        next_span: 0,
    };
    let pvars = vars
        .iter()
        .map(|(s, k)| {
            let t = b.ty(s);
            b.var(t, *k)
        })
        .collect();
    let fvars = locals
        .iter()
        .map(|s| {
            let t = b.ty(s);
            b.var(t, Kind::Frame)
        })
        .collect();
    b.pou(PouKind::Function, fvars);
    let globals = globals
        .iter()
        .map(|s| Global {
            name: Symbol(0),
            ty: b.ty(s),
            init: None,
            constant: false,
            retain: false,
            location: None,
            span: b.span(),
            library: false,
        })
        .collect();
    b.pou(PouKind::Program, pvars);
    Module {
        types: b.types,
        pous: b.pous.into(),
        globals,
        configs: Vec::new(),
        names: vec!["x".into()],
        spellings: Default::default(),
    }
}

/// Members (offset, size, align) lie inside `size`, aligned, apart.
fn members_ok(what: &str, size: u32, members: &[(u32, u32, u32)]) -> Result<(), TestCaseError> {
    let mut spans: Vec<(u64, u64)> = Vec::new();
    for &(off, sz, al) in members {
        prop_assert_eq!(
            off % al.max(1),
            0,
            "{}: member at {} misaligned ({})",
            what,
            off,
            al
        );
        let end = u64::from(off) + u64::from(sz);
        prop_assert!(
            end <= u64::from(size),
            "{}: member ends at {} past {}",
            what,
            end,
            size
        );
        if sz > 0 {
            spans.push((u64::from(off), end));
        }
    }
    spans.sort();
    for w in spans.windows(2) {
        prop_assert!(w[0].1 <= w[1].0, "{}: members overlap: {:?}", what, w);
    }
    Ok(())
}

fn check_layouts(m: &Module, l: &Layouts) -> Result<(), TestCaseError> {
    for t in 0..m.types.len() {
        let t = TypeId(t as u32);
        let lay = l.of(t);
        prop_assert!(u64::from(lay.size) <= MAX_SIZE);
        match m.types.kind(t) {
            TypeKind::Struct { fields } => {
                let members: Vec<(u32, u32, u32)> = (0..fields.len())
                    .map(|i| {
                        let f = l.of(fields[i].ty);
                        (l.field_offset(t, i as u32), f.size, f.align)
                    })
                    .collect();
                members_ok(&format!("struct {}", t.0), lay.size, &members)?;
                // (A string's size need not be a multiple of its alignment;
                // a struct's is: an array of it needs no other padding.)
                prop_assert_eq!(lay.size % lay.align, 0, "struct {} {:?}", t.0, lay);
                let most = fields.iter().map(|f| l.of(f.ty).align).max().unwrap_or(1);
                prop_assert_eq!(lay.align, most);
            }
            TypeKind::Array { dims, elem } => {
                let e = l.of(*elem);
                let stride = l.stride(&m.types, t);
                prop_assert!(stride >= e.size && stride.is_multiple_of(e.align.max(1)));
                let n: i128 = dims.iter().map(|(lo, hi)| hi - lo + 1).product();
                prop_assert_eq!(i128::from(lay.size), i128::from(stride) * n);
                prop_assert_eq!(lay.align, e.align);
            }
            _ => {}
        }
    }
    for (p, pou) in m.pous.iter_enumerated() {
        let pl = &l.pous[p];
        for frame in [false, true] {
            let area = if frame { pl.frame } else { pl.instance };
            let members: Vec<(u32, u32, u32)> = pou
                .vars
                .iter_enumerated()
                .filter(|(i, _)| pl.in_frame[*i] == frame)
                .map(|(i, v)| {
                    let vl = if v.storage == Storage::Ref {
                        super::Layout { size: 4, align: 4 }
                    } else {
                        l.of(v.ty)
                    };
                    (pl.offsets[i], vl.size, vl.align)
                })
                .collect();
            members_ok(&format!("POU {p} frame={frame}"), area.size, &members)?;
            prop_assert!(u64::from(area.size) <= MAX_SIZE);
        }
    }
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(400))]

    #[test]
    fn layouts_are_sound_or_too_large_is_reported(
        vars in prop::collection::vec((spec(), kind()), 0..4),
        locals in prop::collection::vec(spec(), 0..3),
        globals in prop::collection::vec(spec(), 0..3),
    ) {
        let m = module(&vars, &locals, &globals);
        // The model: anything over the limit, or an area (the program's
        // instance and frame, the function's frame, the data area).
        let prog_instance: Vec<(Spec, Kind)> =
            vars.iter().filter(|(_, k)| *k != Kind::Frame).cloned().collect();
        let prog = Spec::Fb(prog_instance);
        let data: Vec<Spec> = globals.iter().cloned().chain([prog.clone()]).collect();
        let over = vars.iter().any(|(s, _)| too_large(s))
            || locals.iter().any(too_large)
            || globals.iter().any(too_large)
            || too_large(&prog)
            || area_over(vars.iter().filter(|(_, k)| *k == Kind::Frame))
            || area_over(locals.iter().map(|s| (s.clone(), Kind::Frame)).collect::<Vec<_>>().iter())
            || area_over(data.iter().map(|s| (s.clone(), Kind::Instance)).collect::<Vec<_>>().iter());
        match Layouts::compute(&m) {
            Ok(l) => {
                prop_assert!(!over, "the model finds something over the limit");
                check_layouts(&m, &l)?;
                // Sizes are the model's.
                let main = m.pous.ids().last().expect("a program");
                for (i, (s, k)) in vars.iter().enumerate() {
                    if *k != Kind::Ref {
                        let got = u128::from(l.of(m.pous[main].vars[VarId::new(i)].ty).size);
                        prop_assert_eq!(Some(got), model(s).0);
                    }
                }
                prop_assert_eq!(Some(u128::from(l.pous[main].instance.size)), model(&prog).0);
            }
            Err(diags) => {
                prop_assert!(over, "reported but the model fits: {:?}", diags);
                prop_assert!(!diags.is_empty());
                let mut spans: Vec<Span> = diags.iter().map(|d| d.span).collect();
                prop_assert!(diags.iter().all(|d| d.code == Code::E0901));
                // Every type here is declared somewhere: none is reported
                // on its own, and an array of a type too large is reported
                // with it, not again.
                prop_assert!(
                    diags.iter().all(|d| !d.message.starts_with("the type")),
                    "{:?}",
                    diags
                );
                spans.sort();
                spans.dedup();
                prop_assert_eq!(spans.len(), diags.len(), "reported twice: {:?}", diags);
            }
        }
    }
}

/// The miscompiled program of the issue: two members of 5 GB each.
#[test]
fn members_past_4_gib_are_reported_not_wrapped() {
    let s = Spec::Struct {
        named: true,
        fields: vec![Spec::Array(
            vec![(0, 16_000_001)],
            Box::new(Spec::Scalar(8)),
        )],
    };
    let arr = Spec::Array(vec![(0, 41)], Box::new(s));
    let t = Spec::Struct {
        named: true,
        fields: vec![arr.clone(), arr, Spec::Scalar(3)],
    };
    let m = module(&[(t, Kind::Instance)], &[], &[]);
    let diags = Layouts::compute(&m).expect_err("too large");
    assert_eq!(diags.len(), 2, "{diags:?}");
    assert!(
        diags[0].message.contains("needs 5248000328 bytes"),
        "{}",
        diags[0].message
    );
}

/// Arrays of arrays too large: one diagnostic, at the variable.
#[test]
fn nested_anonymous_arrays_are_reported_once() {
    let inner = Spec::Array(vec![(0, 16_000_000)], Box::new(Spec::Scalar(8)));
    let mid = Spec::Array(vec![(0, 16_000_000)], Box::new(inner));
    let outer = Spec::Array(vec![(0, 16_000_000)], Box::new(mid));
    let diags = Layouts::compute(&module(&[(outer, Kind::Instance)], &[], &[])).unwrap_err();
    assert_eq!(diags.len(), 1, "{diags:?}");
    assert!(
        diags[0].message.starts_with("variable"),
        "{}",
        diags[0].message
    );
}

/// Exactly the limit fits; one byte more does not.
#[test]
fn the_limit_is_inclusive() {
    let at = Spec::Array(vec![(0, MAX_SIZE)], Box::new(Spec::Scalar(0)));
    assert!(Layouts::compute(&module(&[(at, Kind::Instance)], &[], &[])).is_ok());
    let over = Spec::Array(vec![(0, MAX_SIZE + 1)], Box::new(Spec::Scalar(0)));
    let diags = Layouts::compute(&module(&[(over, Kind::Instance)], &[], &[])).unwrap_err();
    assert_eq!(diags.len(), 1);
}
