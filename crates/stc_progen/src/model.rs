//! What the generator knows about the program it is writing: the types it
//! declared, the POUs and their variables, and the ways a body can reach a
//! value (variables, members, elements, FB outputs).

use stc_values::ElemType as E;

/// The elementary types the generator uses, with how often it picks each.
pub const ELEMS: &[(E, u64)] = &[
    (E::Bool, 14),
    (E::Sint, 4),
    (E::Int, 9),
    (E::Dint, 9),
    (E::Lint, 4),
    (E::Usint, 4),
    (E::Uint, 4),
    (E::Udint, 4),
    (E::Ulint, 3),
    (E::Byte, 3),
    (E::Word, 4),
    (E::Dword, 3),
    (E::Lword, 3),
    (E::Real, 6),
    (E::Lreal, 6),
    (E::Time, 6),
    (E::Ltime, 2),
    (E::Date, 2),
    (E::Tod, 2),
    (E::Dt, 2),
    (E::Ldate, 1),
    (E::Ltod, 1),
    (E::Ldt, 1),
    (E::String, 5),
    (E::Wstring, 2),
    (E::Char, 2),
    (E::Wchar, 1),
];

pub const INTS: &[E] = &[
    E::Sint,
    E::Int,
    E::Dint,
    E::Lint,
    E::Usint,
    E::Uint,
    E::Udint,
    E::Ulint,
];

pub const BITS: &[E] = &[E::Byte, E::Word, E::Dword, E::Lword];

/// The kinds of elementary type, as expressions are generated.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Class {
    Bool,
    Int,
    Bits,
    Real,
    Dur,
    Date,
    Tod,
    Dt,
    Str,
    Char,
}

pub fn class(t: E) -> Class {
    match t {
        E::Bool => Class::Bool,
        E::Sint | E::Int | E::Dint | E::Lint | E::Usint | E::Uint | E::Udint | E::Ulint => {
            Class::Int
        }
        E::Byte | E::Word | E::Dword | E::Lword => Class::Bits,
        E::Real | E::Lreal => Class::Real,
        E::Time | E::Ltime => Class::Dur,
        E::Date | E::Ldate => Class::Date,
        E::Tod | E::Ltod => Class::Tod,
        E::Dt | E::Ldt => Class::Dt,
        E::String | E::Wstring => Class::Str,
        E::Char | E::Wchar => Class::Char,
    }
}

pub fn is_signed(t: E) -> bool {
    matches!(t, E::Sint | E::Int | E::Dint | E::Lint)
}

/// The range of an integer or bit-string type.
pub fn range(t: E) -> (i128, i128) {
    stc_values::int_range(t).unwrap_or((0, 0))
}

/// A short lower-case tag of a type for variable names.
pub fn tag(t: E) -> &'static str {
    match t {
        E::Bool => "bool",
        E::Sint => "sint",
        E::Int => "int",
        E::Dint => "dint",
        E::Lint => "lint",
        E::Usint => "usint",
        E::Uint => "uint",
        E::Udint => "udint",
        E::Ulint => "ulint",
        E::Byte => "byte",
        E::Word => "word",
        E::Dword => "dword",
        E::Lword => "lword",
        E::Real => "real",
        E::Lreal => "lreal",
        E::Time => "time",
        E::Ltime => "ltime",
        E::Date => "date",
        E::Ldate => "ldate",
        E::Tod => "tod",
        E::Ltod => "ltod",
        E::Dt => "dt",
        E::Ldt => "ldt",
        E::String => "str",
        E::Wstring => "wstr",
        E::Char => "char",
        E::Wchar => "wchar",
    }
}

/// A standard function block type.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum StdFb {
    /// TON, TOF, TP over TIME or LTIME.
    Ton(E),
    Tof(E),
    Tp(E),
    /// CTU, CTD, CTUD over the counter type (INT, DINT, LINT, UDINT, ULINT).
    Ctu(E),
    Ctd(E),
    Ctud(E),
    RTrig,
    FTrig,
    Sr,
    Rs,
}

impl StdFb {
    pub fn name(self) -> String {
        let timer = |base: &str, t: E| {
            if t == E::Ltime {
                format!("{base}_LTIME")
            } else {
                base.to_string()
            }
        };
        let counter = |base: &str, t: E| {
            if t == E::Int {
                base.to_string()
            } else {
                format!("{base}_{}", t.name())
            }
        };
        match self {
            StdFb::Ton(t) => timer("TON", t),
            StdFb::Tof(t) => timer("TOF", t),
            StdFb::Tp(t) => timer("TP", t),
            StdFb::Ctu(t) => counter("CTU", t),
            StdFb::Ctd(t) => counter("CTD", t),
            StdFb::Ctud(t) => counter("CTUD", t),
            StdFb::RTrig => "R_TRIG".into(),
            StdFb::FTrig => "F_TRIG".into(),
            StdFb::Sr => "SR".into(),
            StdFb::Rs => "RS".into(),
        }
    }

    pub fn inputs(self) -> Vec<(&'static str, Ty)> {
        let b = Ty::E(E::Bool);
        match self {
            StdFb::Ton(t) | StdFb::Tof(t) | StdFb::Tp(t) => vec![("IN", b), ("PT", Ty::E(t))],
            StdFb::Ctu(t) => vec![("CU", b.clone()), ("R", b), ("PV", Ty::E(t))],
            StdFb::Ctd(t) => vec![("CD", b.clone()), ("LD", b), ("PV", Ty::E(t))],
            StdFb::Ctud(t) => vec![
                ("CU", b.clone()),
                ("CD", b.clone()),
                ("R", b.clone()),
                ("LD", b),
                ("PV", Ty::E(t)),
            ],
            StdFb::RTrig | StdFb::FTrig => vec![("CLK", b)],
            StdFb::Sr => vec![("S1", b.clone()), ("R", b)],
            StdFb::Rs => vec![("S", b.clone()), ("R1", b)],
        }
    }

    pub fn outputs(self) -> Vec<(&'static str, Ty)> {
        let b = Ty::E(E::Bool);
        match self {
            StdFb::Ton(t) | StdFb::Tof(t) | StdFb::Tp(t) => vec![("Q", b), ("ET", Ty::E(t))],
            StdFb::Ctu(t) | StdFb::Ctd(t) => vec![("Q", b), ("CV", Ty::E(t))],
            StdFb::Ctud(t) => vec![("QU", b.clone()), ("QD", b), ("CV", Ty::E(t))],
            StdFb::RTrig | StdFb::FTrig => vec![("Q", b)],
            StdFb::Sr | StdFb::Rs => vec![("Q1", b)],
        }
    }
}

/// A function block type: standard or one of the generated ones.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Fb {
    Std(StdFb),
    User(usize),
}

/// A data type of a variable, member or element.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Ty {
    /// An elementary type (STRING and WSTRING of the default length).
    E(E),
    /// STRING[len] or WSTRING[len].
    Str {
        wide: bool,
        len: u32,
    },
    /// Indices into [`Types`].
    Enum(usize),
    Struct(usize),
    Array(usize),
    Sub(usize),
    Fb(Fb),
}

impl Ty {
    /// The elementary type a read of this type gives, if any.
    pub fn scalar(&self, types: &Types) -> Option<E> {
        match self {
            Ty::E(e) => Some(*e),
            Ty::Str { wide: false, .. } => Some(E::String),
            Ty::Str { wide: true, .. } => Some(E::Wstring),
            Ty::Sub(i) => Some(types.subs[*i].base),
            _ => None,
        }
    }

    pub fn is_fb(&self, types: &Types) -> bool {
        match self {
            Ty::Fb(_) => true,
            Ty::Array(i) => types.arrays[*i].elem.is_fb(types),
            _ => false,
        }
    }
}

pub struct EnumDef {
    pub name: String,
    pub values: Vec<String>,
}

pub struct StructDef {
    pub name: String,
    pub fields: Vec<(String, Ty)>,
    /// The declaration text of each field (type and initial value).
    pub field_text: Vec<String>,
}

pub struct ArrayDef {
    /// `None`: written in the variable declaration (anonymous).
    pub name: Option<String>,
    pub dims: Vec<(i128, i128)>,
    /// How each bound pair is written (`1..4`, `0..N_MAX`).
    pub dims_text: Vec<String>,
    pub elem: Ty,
}

impl ArrayDef {
    pub fn len(&self) -> i128 {
        self.dims.iter().map(|(lo, hi)| hi - lo + 1).product()
    }
}

pub struct SubDef {
    /// `None`: written in the variable declaration (anonymous).
    pub name: Option<String>,
    pub base: E,
    pub lo: i128,
    pub hi: i128,
}

/// The types of the project.
#[derive(Default)]
pub struct Types {
    pub enums: Vec<EnumDef>,
    pub structs: Vec<StructDef>,
    pub arrays: Vec<ArrayDef>,
    pub subs: Vec<SubDef>,
    /// Generated FUNCTION_BLOCK types (their interfaces).
    pub fbs: Vec<PouSig>,
}

impl Types {
    /// How a type is written in a declaration.
    pub fn text(&self, t: &Ty) -> String {
        match t {
            Ty::E(e) => e.name().to_string(),
            Ty::Str { wide, len } => {
                format!("{}[{len}]", if *wide { "WSTRING" } else { "STRING" })
            }
            Ty::Enum(i) => self.enums[*i].name.clone(),
            Ty::Struct(i) => self.structs[*i].name.clone(),
            Ty::Array(i) => {
                let a = &self.arrays[*i];
                match &a.name {
                    Some(n) => n.clone(),
                    None => format!(
                        "ARRAY[{}] OF {}",
                        a.dims_text.join(", "),
                        self.text(&a.elem)
                    ),
                }
            }
            Ty::Sub(i) => {
                let s = &self.subs[*i];
                match &s.name {
                    Some(n) => n.clone(),
                    None => format!("{}({}..{})", s.base.name(), s.lo, s.hi),
                }
            }
            Ty::Fb(Fb::Std(f)) => f.name(),
            Ty::Fb(Fb::User(i)) => self.fbs[*i].name.clone(),
        }
    }

    pub fn fb_inputs(&self, fb: Fb) -> Vec<(String, Ty)> {
        match fb {
            Fb::Std(f) => f
                .inputs()
                .into_iter()
                .map(|(n, t)| (n.to_string(), t))
                .collect(),
            Fb::User(i) => self.fbs[i].inputs.clone(),
        }
    }

    pub fn fb_outputs(&self, fb: Fb) -> Vec<(String, Ty)> {
        match fb {
            Fb::Std(f) => f
                .outputs()
                .into_iter()
                .map(|(n, t)| (n.to_string(), t))
                .collect(),
            Fb::User(i) => self.fbs[i].outputs.clone(),
        }
    }
}

/// The interface of a generated FUNCTION or FUNCTION_BLOCK.
#[derive(Clone, Debug)]
pub struct PouSig {
    pub name: String,
    /// The result type of a FUNCTION.
    pub ret: Option<Ty>,
    pub inputs: Vec<(String, Ty)>,
    pub outputs: Vec<(String, Ty)>,
    pub inouts: Vec<(String, Ty)>,
}

/// The section a variable is declared in.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Sect {
    Input,
    Output,
    InOut,
    Local,
    Temp,
    External,
    Constant,
}

/// A variable of a POU.
#[derive(Clone, Debug)]
pub struct Var {
    pub name: String,
    pub ty: Ty,
    pub sect: Sect,
    /// The initial value as written, if any.
    pub init: Option<String>,
    /// The direct address it is located at (`%QW7`), if any.
    pub location: Option<String>,
}

/// One step of a path from a variable to a value.
#[derive(Clone, Debug)]
pub enum Step {
    Name(String),
    Field(String),
    /// `[i, j]` with the bounds of each index.
    Index(Vec<(i128, i128)>),
}

/// A way to reach a value from the body of a POU.
#[derive(Clone, Debug)]
pub struct Access {
    pub steps: Vec<Step>,
    pub ty: Ty,
    pub writable: bool,
    /// Whether the analyser cannot know its value by propagation (a member,
    /// an element, an FB output, an input, an in-out or an external): the
    /// only reads used unguarded as divisors or indices, since a divisor or
    /// index the analyser can prove wrong is a compile-time error.
    pub opaque: bool,
}

/// The ways to reach values and FB instances from a body.
#[derive(Default)]
pub struct Reach {
    pub values: Vec<Access>,
    /// FB instances (and elements of arrays of them) that can be called.
    pub instances: Vec<(Access, Fb)>,
}

impl Reach {
    pub fn of(vars: &[Var], types: &Types) -> Reach {
        let mut r = Reach::default();
        for v in vars {
            if v.sect == Sect::Constant && v.ty.scalar(types).is_none() {
                continue;
            }
            let writable = !matches!(v.sect, Sect::Input | Sect::Constant);
            let opaque = matches!(v.sect, Sect::Input | Sect::InOut | Sect::External);
            r.walk(
                types,
                vec![Step::Name(v.name.clone())],
                &v.ty,
                writable,
                opaque,
                0,
            );
        }
        r
    }

    fn walk(
        &mut self,
        types: &Types,
        steps: Vec<Step>,
        ty: &Ty,
        writable: bool,
        opaque: bool,
        depth: u32,
    ) {
        if depth > 4 {
            return;
        }
        match ty {
            Ty::Fb(fb) => {
                for (name, t) in types.fb_outputs(*fb) {
                    let mut s = steps.clone();
                    s.push(Step::Field(name));
                    self.walk(types, s, &t, false, true, depth + 1);
                }
                self.instances.push((
                    Access {
                        steps,
                        ty: ty.clone(),
                        writable: false,
                        opaque: true,
                    },
                    *fb,
                ));
            }
            Ty::Struct(i) => {
                for (name, t) in &types.structs[*i].fields {
                    let mut s = steps.clone();
                    s.push(Step::Field(name.clone()));
                    self.walk(types, s, t, writable, true, depth + 1);
                }
                self.values.push(Access {
                    steps,
                    ty: ty.clone(),
                    writable,
                    opaque,
                });
            }
            Ty::Array(i) => {
                let a = &types.arrays[*i];
                let mut s = steps.clone();
                s.push(Step::Index(a.dims.clone()));
                self.walk(types, s, &a.elem, writable, true, depth + 1);
                if !a.elem.is_fb(types) {
                    self.values.push(Access {
                        steps,
                        ty: ty.clone(),
                        writable,
                        opaque,
                    });
                }
            }
            _ => self.values.push(Access {
                steps,
                ty: ty.clone(),
                writable,
                opaque,
            }),
        }
    }
}
