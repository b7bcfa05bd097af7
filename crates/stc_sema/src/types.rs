//! The type table: every type of a project, named by [`TypeId`].
//!
//! Equivalence follows spec/semantics.md (seed 001 section 3.1): a plain
//! rename of a named type is that type (it resolves to the same `TypeId`);
//! every STRUCT, ARRAY, enumeration or subrange declared by name is a new,
//! distinct type; an anonymous ARRAY written in a declaration is compatible
//! with any array of the same bounds and element type; STRING[n] of any
//! lengths are compatible with each other.

use std::fmt::Write;

use stc_diagnostics::Span;
use stc_syntax::token::ElemType;
use stc_syntax::{Interner, Symbol};
use stc_values::Value;

use crate::PouId;

#[derive(Clone, Copy, PartialEq, Eq, Hash, Debug, PartialOrd, Ord)]
pub struct TypeId(pub u32);

impl TypeId {
    /// The poisoned type of an expression whose error is already reported:
    /// compatible with everything, so one mistake gives one diagnostic.
    pub const ERROR: TypeId = TypeId(0);
    /// The "result" of a function without a return type.
    pub const VOID: TypeId = TypeId(1);
    /// The first elementary type: every type table holds the elementary
    /// types at `FIRST_ELEM + ElemType::code()` (see [`TypeTable::new`]).
    pub const FIRST_ELEM: u32 = 2;

    /// The pre-allocated entry of an elementary type in every table (for
    /// STRING and WSTRING, the entry without a length; sized strings have
    /// their own, see [`TypeTable::elem`]).
    pub const fn of_elem(e: ElemType) -> TypeId {
        TypeId(Self::FIRST_ELEM + e.code() as u32)
    }
}

pub const DEFAULT_STRING_LEN: u32 = 80;

#[derive(Clone, PartialEq, Debug)]
pub struct EnumValue {
    pub name: Symbol,
    pub value: i128,
    pub span: Span,
}

#[derive(Clone, PartialEq, Debug)]
pub struct Field {
    pub name: Symbol,
    pub ty: TypeId,
    pub init: Option<InitValue>,
    pub span: Span,
}

#[derive(Clone, PartialEq, Debug)]
pub enum TypeKind {
    Error,
    Void,
    Elem(ElemType),
    String {
        wide: bool,
        len: u32,
    },
    Subrange {
        base: ElemType,
        lo: i128,
        hi: i128,
    },
    Enum {
        values: Vec<EnumValue>,
        base: ElemType,
    },
    Array {
        dims: Vec<(i128, i128)>,
        elem: TypeId,
    },
    Struct {
        fields: Vec<Field>,
    },
    /// An instance of a function block.
    Fb(PouId),
    /// A program type (only instantiated by configurations).
    Program(PouId),
    /// `REF_TO T`: a reference to a variable of type `T`. One type per
    /// target type ([`TypeTable::ref_to`]); `Ref(VOID)` is the type of
    /// `NULL`, which every reference type accepts.
    Ref(TypeId),
    /// `POINTER TO T` (CODESYS): a checked pointer into one object of the
    /// program's memory (docs/oop.md, "Pointers"). One type per target
    /// type ([`TypeTable::ptr_to`]); `Ptr(VOID)` is the type of `ADR(x)`,
    /// which every pointer type accepts when the view is allowed. The
    /// lowering replaces it by a structure ([`TypeTable::pointer_fields`]).
    Ptr(TypeId),
}

#[derive(Clone, PartialEq, Debug)]
pub struct TypeInfo {
    pub kind: TypeKind,
    /// The declared name of a named type.
    pub name: Option<Symbol>,
    pub span: Option<Span>,
    /// Where the name of a named type is declared (its spelling).
    pub name_span: Option<Span>,
}

/// An evaluated initial value.
#[derive(Clone, PartialEq, Debug)]
pub enum InitValue {
    Scalar(Value),
    /// Every element of an array in order (row-major), after expanding
    /// repetitions; elements not given keep their type's default (`None`).
    Array(Vec<Option<InitValue>>),
    /// Members given by name; the others keep their declared default.
    Struct(Vec<(Symbol, InitValue)>),
}

#[derive(Clone)]
pub struct TypeTable {
    types: Vec<TypeInfo>,
    strings: rustc_hash::FxHashMap<(bool, u32), TypeId>,
    refs: rustc_hash::FxHashMap<TypeId, TypeId>,
    ptrs: rustc_hash::FxHashMap<TypeId, TypeId>,
    /// Per function block, class or interface: the POUs it extends or
    /// implements directly (docs/oop.md); an instance of it is one of
    /// theirs.
    supers: rustc_hash::FxHashMap<crate::PouId, Vec<crate::PouId>>,
    /// The INTERFACEs (whose references are interface values).
    interfaces: rustc_hash::FxHashSet<crate::PouId>,
}

/// How a value of one type can be stored in another.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
pub enum Compat {
    /// Same type (or compatible without any conversion).
    Same,
    /// An implicit widening conversion (3rd edition).
    Widen,
    /// Numeric or bit-string types whose conversion may lose information.
    Narrow,
    Incompatible,
}

impl Default for TypeTable {
    fn default() -> Self {
        TypeTable::new()
    }
}

impl TypeTable {
    pub fn new() -> TypeTable {
        let mut t = TypeTable {
            types: Vec::new(),
            strings: Default::default(),
            refs: Default::default(),
            ptrs: Default::default(),
            supers: Default::default(),
            interfaces: Default::default(),
        };
        t.add(TypeKind::Error, None, None);
        t.add(TypeKind::Void, None, None);
        for &e in ElemType::ALL {
            let id = t.add(TypeKind::Elem(e), None, None);
            assert_eq!(id, TypeId::of_elem(e), "ElemType codes are dense");
        }
        t
    }

    pub fn add(&mut self, kind: TypeKind, name: Option<Symbol>, span: Option<Span>) -> TypeId {
        let id = TypeId(self.types.len() as u32);
        self.types.push(TypeInfo {
            kind,
            name,
            span,
            name_span: None,
        });
        id
    }

    /// Records where a type's name is declared (the first declaration wins).
    pub fn set_name_span(&mut self, t: TypeId, span: Span) {
        if let Some(info) = self.types.get_mut(t.0 as usize) {
            info.name_span.get_or_insert(span);
        }
    }

    /// The type of an elementary type name (STRING/WSTRING: the default length).
    pub fn elem(&mut self, e: ElemType) -> TypeId {
        match e {
            ElemType::String => self.string(false, DEFAULT_STRING_LEN),
            ElemType::Wstring => self.string(true, DEFAULT_STRING_LEN),
            _ => TypeId::of_elem(e),
        }
    }

    pub fn string(&mut self, wide: bool, len: u32) -> TypeId {
        if let Some(&t) = self.strings.get(&(wide, len)) {
            return t;
        }
        let t = self.add(TypeKind::String { wide, len }, None, None);
        self.strings.insert((wide, len), t);
        t
    }

    /// The type `REF_TO t` (one per target type); `ref_to(VOID)` is the
    /// type of `NULL`.
    pub fn ref_to(&mut self, t: TypeId) -> TypeId {
        if let Some(&r) = self.refs.get(&t) {
            return r;
        }
        let r = self.add(TypeKind::Ref(t), None, None);
        self.refs.insert(t, r);
        r
    }

    /// The type `POINTER TO t` (one per target type); `ptr_to(VOID)` is
    /// the type of `ADR(x)`.
    pub fn ptr_to(&mut self, t: TypeId) -> TypeId {
        if let Some(&r) = self.ptrs.get(&t) {
            return r;
        }
        let r = self.add(TypeKind::Ptr(t), None, None);
        self.ptrs.insert(t, r);
        r
    }

    /// The target type of a pointer type (VOID for `ADR(x)`'s type).
    pub fn ptr_target(&self, t: TypeId) -> Option<TypeId> {
        match self.kind(t) {
            TypeKind::Ptr(x) => Some(*x),
            _ => None,
        }
    }

    /// The element a pointer to `t` steps over: the innermost element of
    /// an array type, else `t` itself. `POINTER TO ARRAY[0..99] OF BYTE`
    /// and `POINTER TO BYTE` are one kind of pointer.
    pub fn ptr_elem(&self, mut t: TypeId) -> TypeId {
        while let TypeKind::Array { elem, .. } = self.kind(t) {
            t = *elem;
        }
        t
    }

    /// The number of elements of [`TypeTable::ptr_elem`] in a value of
    /// type `t` (1 for anything but an array).
    pub fn elem_count(&self, mut t: TypeId) -> u64 {
        let mut n: u64 = 1;
        while let TypeKind::Array { dims, elem } = self.kind(t) {
            for (lo, hi) in dims {
                let k = u64::try_from((hi - lo + 1).max(0)).unwrap_or(u64::MAX);
                n = n.saturating_mul(k);
            }
            t = *elem;
        }
        n
    }

    /// `SIZEOF` of a value of type `t`, in the byte view of memory that
    /// pointers use, the same on every engine (docs/oop.md, "Pointers"):
    /// scalars their natural size (TIME, DATE, TOD, DT 8 bytes), a
    /// STRING(n) n + 1 bytes (its characters and the terminating NUL), a
    /// WSTRING(n) 2(n + 1), an array its elements', a structure the sum
    /// of its members' (no padding), a pointer 8. `None` for function
    /// block instances, references and erroneous types (no byte view).
    pub fn byte_size(&self, t: TypeId) -> Option<u64> {
        self.byte_size_at(t, 0)
    }

    fn byte_size_at(&self, t: TypeId, depth: u32) -> Option<u64> {
        if depth > 64 {
            return None;
        }
        Some(match self.kind(t) {
            TypeKind::String { wide, len } => (u64::from(*len) + 1) * if *wide { 2 } else { 1 },
            TypeKind::Elem(_) | TypeKind::Subrange { .. } | TypeKind::Enum { .. } => {
                elem_byte_size(self.scalar(t)?)
            }
            TypeKind::Array { elem, .. } => self
                .elem_count(t)
                .checked_mul(self.byte_size_at(self.ptr_elem(*elem), depth + 1)?)?,
            TypeKind::Struct { fields } => {
                let mut n: u64 = 0;
                for f in fields {
                    n = n.checked_add(self.byte_size_at(f.ty, depth + 1)?)?;
                }
                n
            }
            TypeKind::Ptr(_) => 8,
            _ => return None,
        })
    }

    /// The reference type to `t`, if the table has it.
    pub fn find_ref(&self, t: TypeId) -> Option<TypeId> {
        self.refs.get(&t).copied()
    }

    /// The target type of a reference type (VOID for `NULL`'s type).
    pub fn ref_target(&self, t: TypeId) -> Option<TypeId> {
        match self.kind(t) {
            TypeKind::Ref(x) => Some(*x),
            _ => None,
        }
    }

    pub fn get(&self, t: TypeId) -> &TypeInfo {
        &self.types[t.0 as usize]
    }

    pub fn kind(&self, t: TypeId) -> &TypeKind {
        &self.types[t.0 as usize].kind
    }

    pub fn kind_mut(&mut self, t: TypeId) -> &mut TypeKind {
        &mut self.types[t.0 as usize].kind
    }

    pub fn len(&self) -> usize {
        self.types.len()
    }

    pub fn is_empty(&self) -> bool {
        self.types.is_empty()
    }

    pub fn is_error(&self, t: TypeId) -> bool {
        t == TypeId::ERROR
    }

    /// The elementary type a value of `t` is represented as: the type itself,
    /// a subrange's base, an enumeration's base, STRING/WSTRING for strings.
    pub fn scalar(&self, t: TypeId) -> Option<ElemType> {
        match self.kind(t) {
            TypeKind::Elem(e) => Some(*e),
            TypeKind::Subrange { base, .. } => Some(*base),
            TypeKind::Enum { base, .. } => Some(*base),
            TypeKind::String { wide: false, .. } => Some(ElemType::String),
            TypeKind::String { wide: true, .. } => Some(ElemType::Wstring),
            _ => None,
        }
    }

    /// The elementary type for arithmetic: like [`Self::scalar`] but not for
    /// enumerations (which have no arithmetic).
    pub fn numeric(&self, t: TypeId) -> Option<ElemType> {
        match self.kind(t) {
            TypeKind::Elem(e) => Some(*e),
            TypeKind::Subrange { base, .. } => Some(*base),
            _ => None,
        }
    }

    pub fn is_bool(&self, t: TypeId) -> bool {
        matches!(self.kind(t), TypeKind::Elem(ElemType::Bool))
    }

    pub fn is_integer(&self, t: TypeId) -> bool {
        self.numeric(t).is_some_and(stc_values::is_integer)
    }

    /// Can a value of type `from` be stored in `to`?
    /// Records that `p` extends or implements `sup` directly.
    pub fn add_super(&mut self, p: crate::PouId, sup: crate::PouId) {
        self.supers.entry(p).or_default().push(sup);
    }

    /// Records that `p` is an INTERFACE.
    pub fn add_interface(&mut self, p: crate::PouId) {
        self.interfaces.insert(p);
    }

    /// Whether `p` is an INTERFACE.
    pub fn is_interface(&self, p: crate::PouId) -> bool {
        self.interfaces.contains(&p)
    }

    /// The POUs `p` extends or implements directly.
    pub fn supers(&self, p: crate::PouId) -> &[crate::PouId] {
        self.supers.get(&p).map_or(&[], |v| v.as_slice())
    }

    /// Whether an instance of `a` is an instance of `b`: `a` is `b`, or
    /// extends or implements it, directly or not.
    pub fn is_subtype(&self, a: crate::PouId, b: crate::PouId) -> bool {
        let mut stack = vec![a];
        let mut seen = rustc_hash::FxHashSet::default();
        while let Some(p) = stack.pop() {
            if p == b {
                return true;
            }
            if seen.insert(p) {
                stack.extend_from_slice(self.supers(p));
            }
        }
        false
    }

    /// Whether the function block type `from` is a proper subtype of `to`.
    fn fb_subtype(&self, from: TypeId, to: TypeId) -> bool {
        match (self.kind(from), self.kind(to)) {
            (TypeKind::Fb(a), TypeKind::Fb(b)) => a != b && self.is_subtype(*a, *b),
            _ => false,
        }
    }

    pub fn compat(&self, from: TypeId, to: TypeId, iec2: bool) -> Compat {
        if from == to || from == TypeId::ERROR || to == TypeId::ERROR {
            return Compat::Same;
        }
        if self.fb_subtype(from, to) {
            // A derived instance where its base is expected (a VAR_IN_OUT).
            return Compat::Same;
        }
        match (self.kind(from), self.kind(to)) {
            (TypeKind::String { wide: a, .. }, TypeKind::String { wide: b, .. }) if a == b => {
                Compat::Same
            }
            (TypeKind::Array { .. }, TypeKind::Array { .. }) => {
                let anonymous = self.get(from).name.is_none() || self.get(to).name.is_none();
                if anonymous && self.same_array_shape(from, to) {
                    Compat::Same
                } else {
                    Compat::Incompatible
                }
            }
            (TypeKind::Enum { .. }, _) | (_, TypeKind::Enum { .. }) => Compat::Incompatible,
            (TypeKind::Ref(a), TypeKind::Ref(b)) => {
                let same = *a == TypeId::VOID
                    || *a == *b
                    || *a == TypeId::ERROR
                    || *b == TypeId::ERROR
                    || self.fb_subtype(*a, *b)
                    || self.compat(*a, *b, false) == Compat::Same
                        && self.compat(*b, *a, false) == Compat::Same;
                if same {
                    Compat::Same
                } else {
                    Compat::Incompatible
                }
            }
            (TypeKind::Ref(_), _) | (_, TypeKind::Ref(_)) => Compat::Incompatible,
            (TypeKind::Ptr(a), TypeKind::Ptr(b)) => {
                // (`ADR(x)`, of `Ptr(VOID)`, is checked where it is stored.)
                let (ea, eb) = (self.ptr_elem(*a), self.ptr_elem(*b));
                let same = *a == TypeId::VOID
                    || ea == eb
                    || ea == TypeId::ERROR
                    || eb == TypeId::ERROR
                    || self.compat(ea, eb, false) == Compat::Same
                        && self.compat(eb, ea, false) == Compat::Same;
                if same {
                    Compat::Same
                } else {
                    Compat::Incompatible
                }
            }
            (TypeKind::Ptr(_), _) | (_, TypeKind::Ptr(_)) => Compat::Incompatible,
            _ => match (self.numeric(from), self.numeric(to)) {
                (Some(a), Some(b)) if a == b => Compat::Same,
                (Some(a), Some(b)) if stc_values::implicit_widening(a, b) => {
                    if iec2 {
                        Compat::Narrow
                    } else {
                        Compat::Widen
                    }
                }
                (Some(a), Some(b)) if convertible_family(a) && convertible_family(b) => {
                    Compat::Narrow
                }
                _ => Compat::Incompatible,
            },
        }
    }

    fn same_array_shape(&self, a: TypeId, b: TypeId) -> bool {
        match (self.kind(a), self.kind(b)) {
            (TypeKind::Array { dims: da, elem: ea }, TypeKind::Array { dims: db, elem: eb }) => {
                da == db
                    && (ea == eb
                        || self.compat(*ea, *eb, false) == Compat::Same
                            && self.compat(*eb, *ea, false) == Compat::Same)
            }
            _ => false,
        }
    }

    /// The type as the user would write it.
    pub fn display(&self, t: TypeId, interner: &Interner) -> String {
        let info = self.get(t);
        if let Some(n) = info.name {
            return interner.spelling(n).to_string();
        }
        match &info.kind {
            TypeKind::Error => "<error>".into(),
            TypeKind::Void => "no value".into(),
            TypeKind::Elem(e) => e.name().into(),
            TypeKind::String { wide, len } => {
                let kw = if *wide { "WSTRING" } else { "STRING" };
                if *len == DEFAULT_STRING_LEN {
                    kw.into()
                } else {
                    format!("{kw}[{len}]")
                }
            }
            TypeKind::Subrange { base, lo, hi } => format!("{} ({lo}..{hi})", base.name()),
            TypeKind::Enum { values, .. } => {
                let names: Vec<&str> = values.iter().map(|v| interner.spelling(v.name)).collect();
                format!("({})", names.join(", "))
            }
            TypeKind::Array { dims, elem } => {
                let mut s = String::from("ARRAY[");
                for (i, (lo, hi)) in dims.iter().enumerate() {
                    if i > 0 {
                        s.push_str(", ");
                    }
                    let _ = write!(s, "{lo}..{hi}");
                }
                let _ = write!(s, "] OF {}", self.display(*elem, interner));
                s
            }
            TypeKind::Struct { .. } => "STRUCT".into(),
            TypeKind::Fb(_) | TypeKind::Program(_) => "function block".into(),
            TypeKind::Ref(TypeId::VOID) => "NULL".into(),
            // (An interface value is written as its interface.)
            TypeKind::Ref(t) if matches!(self.kind(*t), TypeKind::Fb(p) if self.interfaces.contains(p)) => {
                self.display(*t, interner)
            }
            TypeKind::Ref(t) => format!("REF_TO {}", self.display(*t, interner)),
            TypeKind::Ptr(TypeId::VOID) => "an address".into(),
            TypeKind::Ptr(t) => format!("POINTER TO {}", self.display(*t, interner)),
        }
    }
}

/// The size of an elementary type in the byte view of pointers.
pub fn elem_byte_size(e: ElemType) -> u64 {
    use ElemType as E;
    match e {
        E::Bool | E::Sint | E::Usint | E::Byte | E::Char => 1,
        E::Int | E::Uint | E::Word | E::Wchar => 2,
        E::Dint | E::Udint | E::Dword | E::Real => 4,
        E::String => 1,
        E::Wstring => 2,
        _ => 8,
    }
}

/// Numeric and bit-string types, between which explicit conversions exist
/// (so a refused implicit one is "narrowing", E0302).
fn convertible_family(e: ElemType) -> bool {
    stc_values::is_integer(e)
        || stc_values::is_real(e)
        || (stc_values::is_bit_string(e) && e != ElemType::Bool)
}
