//! The program model: what a compiled program is made of, as every engine
//! and tool outside the compiler sees it: its types, its POUs with their
//! variables, its globals with the configuration that owns each, its
//! configurations with resources, tasks and program instances and their
//! connections, and the process image slots, with one numbering for all of
//! them (types by [`TypeRef`], POUs by their `PouId`, globals by their
//! index in the module).
//!
//! [`build`] computes it once from a [`Module`] and its [`Layouts`], with
//! the canonical addresses of one flat data area: the process image slots,
//! then the globals, the configurations' program instances and one
//! standalone instance of every PROGRAM, each at its layout's offset, with
//! their initial bytes and the references bound in them. The VM runs that
//! data area as it is and writes the model into `.stbc` files; the C back
//! end writes the same tables into `stc_meta.h` with C addresses, and
//! `stc run --backend c` reads them back into a `Model` of the same shape
//! with the addresses of the loaded library. The runtime (`stc_runtime`)
//! reads nothing but a `Model` and the engine's memory.
//!
//! Values are stored as [`repr`] says (little-endian, two's complement,
//! IEC 60559), in every engine.

use stc_syntax::literal::DirectAddress;
use stc_syntax::token::ElemType;

mod build;
pub mod repr;

pub use build::{build, Builder, Data, ModelError};

/// A field-less enumeration whose values are a file format and an ABI:
/// stored as a byte in `.stbc` files and written as a code in the
/// generated C (`stc_codes.h`). Each variant has an explicit value; never
/// renumber one. `from_code` rejects values no variant has.
macro_rules! coded_enum {
    ($(#[$m:meta])* $name:ident { $($(#[$vm:meta])* $variant:ident = $code:literal,)* }) => {
        $(#[$m])*
        #[derive(Clone, Copy, Debug, PartialEq, Eq)]
        #[repr(u8)]
        pub enum $name { $($(#[$vm])* $variant = $code,)* }

        impl $name {
            /// Every variant, in the order of their codes.
            pub const ALL: &'static [$name] = &[$($name::$variant,)*];

            /// The variant's stable code.
            pub const fn code(self) -> u8 {
                self as u8
            }

            /// The variant of a code; `None` for a value no variant has.
            pub fn from_code(code: u8) -> Option<$name> {
                match code {
                    $($code => Some($name::$variant),)*
                    _ => None,
                }
            }
        }
    };
}

/// Index of a type in [`Model::types`].
pub type TypeRef = u32;

/// The program model: see the module documentation.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Model {
    pub types: Vec<TypeDesc>,
    /// By `PouId`.
    pub pous: Vec<PouDesc>,
    /// Global variables, by plain name (all configurations and top-level
    /// lists), in the module's order.
    pub globals: Vec<GlobalDesc>,
    pub configs: Vec<ConfigDesc>,
    /// A standalone instance of every PROGRAM type (for `--program`).
    pub programs: Vec<ProgramInst>,
    /// Process image slots: one per direct address used.
    pub io: Vec<IoSlot>,
}

impl Model {
    /// The elementary type a value of type `t` is stored as (scalars,
    /// enumerations, subranges), if it is one.
    pub fn scalar_of(&self, t: TypeRef) -> Option<ElemType> {
        match self.types.get(t as usize)? {
            TypeDesc::Scalar(e)
            | TypeDesc::Subrange { base: e, .. }
            | TypeDesc::Enum { base: e, .. } => Some(*e),
            _ => None,
        }
    }

    /// The size in bytes of a value of type `t` (a structure without its
    /// trailing padding); 0 for an unknown type. `u64::MAX` where
    /// [`Model::checked_type_size`] has none: no memory holds such a
    /// value, so every range check against it fails.
    pub fn type_size(&self, t: TypeRef) -> u64 {
        self.checked_type_size(t).unwrap_or(u64::MAX)
    }

    /// The size in bytes of a value of type `t`, computed without
    /// overflow; `None` past `u64` or for types nested deeper than 256
    /// (only a hostile table has either).
    pub fn checked_type_size(&self, t: TypeRef) -> Option<u64> {
        self.type_size_at(t, 0)
    }

    fn type_size_at(&self, t: TypeRef, depth: u32) -> Option<u64> {
        if depth > 256 {
            return None;
        }
        Some(match self.types.get(t as usize) {
            Some(TypeDesc::Scalar(e))
            | Some(TypeDesc::Enum { base: e, .. })
            | Some(TypeDesc::Subrange { base: e, .. }) => crate::layout::elem_size(*e) as u64,
            Some(TypeDesc::String { wide, cap }) => 2 + *cap as u64 * if *wide { 2 } else { 1 },
            Some(TypeDesc::Array { dims, stride, .. }) => {
                let n = dims.iter().try_fold(1u64, |a, (l, h)| {
                    let n = (i128::from(*h) - i128::from(*l) + 1).max(0);
                    a.checked_mul(u64::try_from(n).ok()?)
                })?;
                n.checked_mul(u64::from(*stride))?
            }
            Some(TypeDesc::Struct { fields, .. }) => {
                let mut end = 0;
                for f in fields {
                    let e = u64::from(f.offset).checked_add(self.type_size_at(f.ty, depth + 1)?)?;
                    end = end.max(e);
                }
                end
            }
            Some(TypeDesc::Instance { pou }) => self
                .pous
                .get(*pou as usize)
                .map_or(0, |p| p.instance_size as u64),
            None => 0,
        })
    }
}

#[derive(Clone, Debug, PartialEq)]
pub enum TypeDesc {
    Scalar(ElemType),
    String {
        wide: bool,
        cap: u32,
    },
    Enum {
        name: String,
        base: ElemType,
        values: Vec<(String, i128)>,
    },
    /// `stride` is the size of one element; dims are (low, high) bounds.
    Array {
        elem: TypeRef,
        dims: Vec<(i64, i64)>,
        stride: u32,
    },
    Struct {
        name: Option<String>,
        fields: Vec<FieldDesc>,
    },
    /// An instance of a function block or program: the POU's variables.
    Instance {
        pou: u32,
    },
    /// An integer type restricted to `lo..=hi` (stored as `base`).
    Subrange {
        base: ElemType,
        lo: i128,
        hi: i128,
    },
}

coded_enum! {
    /// The kind of a [`TypeDesc`] (`STC_TK_*` in C).
    TypeDescKind {
        Scalar = 0,
        String = 1,
        Enum = 2,
        Array = 3,
        Struct = 4,
        Instance = 5,
        Subrange = 6,
    }
}

impl TypeDesc {
    pub fn kind(&self) -> TypeDescKind {
        match self {
            TypeDesc::Scalar(_) => TypeDescKind::Scalar,
            TypeDesc::String { .. } => TypeDescKind::String,
            TypeDesc::Enum { .. } => TypeDescKind::Enum,
            TypeDesc::Array { .. } => TypeDescKind::Array,
            TypeDesc::Struct { .. } => TypeDescKind::Struct,
            TypeDesc::Instance { .. } => TypeDescKind::Instance,
            TypeDesc::Subrange { .. } => TypeDescKind::Subrange,
        }
    }
}

#[derive(Clone, Debug, PartialEq)]
pub struct FieldDesc {
    pub name: String,
    pub ty: TypeRef,
    pub offset: u32,
}

coded_enum! {
    /// The section a variable is declared in (`STC_VK_*` in C).
    VarKind {
        Input = 0,
        Output = 1,
        InOut = 2,
        Var = 3,
        Temp = 4,
        External = 5,
        Global = 6,
        Result = 7,
        Hidden = 8,
    }
}

#[derive(Clone, Debug, PartialEq)]
pub struct VarDesc {
    pub name: String,
    pub ty: TypeRef,
    pub kind: VarKind,
    /// Offset in the instance (function blocks, programs), or in the
    /// frame of a call: an engine's own calling convention, 0 in the model
    /// [`build`] gives and filled in by the engine that has frames (the VM).
    pub offset: u32,
    /// Whether the variable lives in the frame (functions, VAR_TEMP).
    pub in_frame: bool,
    /// A reference (VAR_IN_OUT, VAR_EXTERNAL, a located variable): the slot
    /// holds an address.
    pub is_ref: bool,
    /// The direct address of a located variable (`AT %IX0.0`).
    pub location: Option<DirectAddress>,
    /// Declared CONSTANT: not to be changed from outside.
    pub constant: bool,
    /// Declared in a RETAIN block: kept across a warm restart
    /// (`stc run --realtime --retain`).
    pub retain: bool,
}

/// A POU: its variables, and the type of its instances.
#[derive(Clone, Debug, PartialEq)]
pub struct PouDesc {
    pub name: String,
    pub kind: PouKind,
    /// Size of an instance (function blocks and programs).
    pub instance_size: u32,
    pub vars: Vec<VarDesc>,
    /// The type describing an instance of this POU.
    pub instance_type: TypeRef,
}

coded_enum! {
    PouKind {
        Function = 0,
        FunctionBlock = 1,
        Program = 2,
    }
}

#[derive(Clone, Debug, PartialEq)]
pub struct GlobalDesc {
    pub name: String,
    pub ty: TypeRef,
    pub offset: u32,
    /// The configuration the global belongs to (`None`: a top-level list).
    pub config: Option<u32>,
    pub location: Option<DirectAddress>,
    pub constant: bool,
    /// Declared in a VAR_GLOBAL RETAIN block.
    pub retain: bool,
}

#[derive(Clone, Debug, PartialEq)]
pub struct ConfigDesc {
    pub name: String,
    pub resources: Vec<ResourceDesc>,
}

#[derive(Clone, Debug, PartialEq)]
pub struct ResourceDesc {
    pub name: Option<String>,
    pub tasks: Vec<TaskDesc>,
    pub programs: Vec<ProgramInst>,
}

#[derive(Clone, Debug, PartialEq)]
pub struct TaskDesc {
    pub name: String,
    pub interval_ns: Option<i64>,
    pub priority: u32,
    /// The BOOL that triggers an event task.
    pub single: Option<Source>,
}

/// A program instance: where its data is and what is connected to it.
#[derive(Clone, Debug, PartialEq)]
pub struct ProgramInst {
    pub name: String,
    pub pou: u32,
    /// Address of the instance in the data area.
    pub offset: u32,
    /// Index of its task in its resource.
    pub task: Option<u32>,
    /// Inputs copied in before each run: (offset in the instance, type, source).
    pub inputs: Vec<(u32, TypeRef, Source)>,
    /// Outputs copied out after each run: (offset in the instance, type, sink).
    pub outputs: Vec<(u32, TypeRef, Source)>,
}

/// A value in the data area (or a constant in the pool) with its type.
#[derive(Clone, Debug, PartialEq)]
pub enum Source {
    /// An absolute address (a global, a process image slot, a constant).
    Addr { offset: u32, ty: TypeRef },
}

#[derive(Clone, Debug, PartialEq)]
pub struct IoSlot {
    pub address: DirectAddress,
    pub offset: u32,
    pub ty: TypeRef,
}
