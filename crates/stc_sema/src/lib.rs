//! Semantic analysis: from a syntax tree to a typed, checked program model.
//!
//! [`analyze`] resolves every name, gives every expression a type (with the
//! implicit conversions made explicit in [`Analysis::coercions`]), folds
//! constants with the exact run-time semantics of `stc_values`, and reports
//! every error and warning of `docs/diagnostics.md`. The result is data that
//! later phases (the IR, a language server) query; nothing here prints.
//!
//! One root cause gives one diagnostic: an expression whose error is already
//! reported gets the poisoned type [`TypeId::ERROR`], which is compatible with
//! everything, so no diagnostic ever follows from another.
//!
//! The standard function blocks (TON, CTU, ...) are written in ST in the
//! [`prelude`], which the driver parses together with the user's files, so
//! every back end gets their exact semantics from one source.

mod analyzer;
mod calls;
mod checkpoint;
mod classes;
mod config;
mod decls;
mod expr;
mod flow;
pub mod idx;
pub use pointers::byte_like;
mod il;
mod namespaces;
mod pointers;
pub mod prelude;
mod properties;
mod sfc;
mod split;
mod stmt;
#[cfg(test)]
mod tests;
pub mod types;

use rustc_hash::FxHashMap;
use stc_diagnostics::{Diagnostic, SourceMap, Span};
use stc_syntax::ast::{Ast, Edge, ExprId, PouKind};
use stc_syntax::literal::DirectAddress;
use stc_syntax::{Interner, Symbol};
use stc_values::{Intrinsic, Value};

pub use checkpoint::{analyze_split, resume, Checkpoint, Made, Split, SUGGESTS_GLOBALS};
pub use types::{Compat, InitValue, TypeId, TypeKind, TypeTable};

/// Index of a POU in [`Analysis::pous`].
#[derive(Clone, Copy, PartialEq, Eq, Hash, Debug, PartialOrd, Ord, Default)]
pub struct PouId(pub u32);

/// Index of a variable in its POU's [`PouDef::vars`].
#[derive(Clone, Copy, PartialEq, Eq, Hash, Debug, PartialOrd, Ord, Default)]
pub struct VarId(pub u32);

/// Index of a global variable in [`Analysis::globals`].
#[derive(Clone, Copy, PartialEq, Eq, Hash, Debug, PartialOrd, Ord, Default)]
pub struct GlobalId(pub u32);

/// An id is shown as its position (in generated names, `FB3_Pump`).
macro_rules! show_id {
    ($($t:ty),*) => {$(
        impl std::fmt::Display for $t {
            fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
                write!(f, "{}", self.0)
            }
        }
    )*};
}
show_id!(PouId, VarId, GlobalId);

#[derive(Clone, Copy, Debug, Default)]
pub struct Options {
    /// `--std iec2`: no implicit conversions.
    pub iec2: bool,
}

#[derive(Clone, Copy, PartialEq, Eq, Debug, Hash)]
pub enum Section {
    Input,
    Output,
    InOut,
    Var,
    Temp,
    External,
    /// VAR_GLOBAL declared inside a PROGRAM.
    Global,
    /// The result variable of a FUNCTION (named like the function).
    Result,
}

#[derive(Clone, Debug)]
pub struct VarDef {
    pub name: Symbol,
    pub span: Span,
    pub section: Section,
    pub ty: TypeId,
    /// The evaluated initial value (explicit, or from the declared type).
    pub init: Option<InitValue>,
    pub constant: bool,
    pub retain: bool,
    pub location: Option<DirectAddress>,
    pub edge: Option<Edge>,
    /// Declared by the language, not the user: the EN and ENO of a function
    /// or function block (ed2 2.5.1.2). Implicit variables come after every
    /// declared one, so a back end that drops them when nothing refers to
    /// them (see [`Analysis::implicit_used`]) keeps every other `VarId`.
    pub implicit: bool,
}

#[derive(Clone, Debug)]
pub struct PouDef {
    pub kind: PouKind,
    pub name: Symbol,
    pub span: Span,
    pub name_span: Span,
    /// Index of the POU in [`Ast::items`].
    pub item: usize,
    pub vars: Vec<VarDef>,
    /// The function result type (`None` for function blocks, programs and
    /// functions without a result).
    pub return_type: Option<TypeId>,
    /// Part of the standard library prelude.
    pub is_std: bool,
    pub var_index: FxHashMap<Symbol, VarId>,
    /// The execution control input EN of a function or function block
    /// (implicit unless the user declared a VAR_INPUT named EN): a call
    /// that gives `EN := FALSE` does nothing (see [`CallInfo::en`]).
    pub en: Option<VarId>,
    /// The execution control output ENO (implicit unless declared as a
    /// VAR_OUTPUT): TRUE at the start of every call, assignable in the body.
    pub eno: Option<VarId>,
    /// For a METHOD: the FUNCTION_BLOCK it belongs to and its position in
    /// the block's [`stc_syntax::ast::Pou::methods`]. A method is a
    /// FUNCTION whose last variable, [`PouDef::this`], is the instance.
    pub method_of: Option<(PouId, usize)>,
    /// For a METHOD: the hidden VAR_IN_OUT bound to the instance the
    /// method is called on (`THIS^`); not a positional parameter, not named
    /// in [`PouDef::var_index`].
    pub this: Option<VarId>,
    /// For a METHOD: its access specifier (PUBLIC when none is written).
    pub access: Option<stc_syntax::ast::Access>,
    /// For a FUNCTION_BLOCK: its methods, in declaration order.
    pub methods: Vec<PouId>,
    /// What the POU was declared as when not FUNCTION_BLOCK (a CLASS, an
    /// INTERFACE: docs/oop.md).
    pub class: Option<stc_syntax::ast::ClassKind>,
    /// The function block or class it EXTENDS.
    pub base: Option<PouId>,
    /// The interfaces it IMPLEMENTS (of an INTERFACE: those it EXTENDS).
    pub interfaces: Vec<PouId>,
    /// The first `inherited` variables are its base's, in the base's order
    /// (so a base instance is a prefix of a derived one): the base's hidden
    /// ones too (its tag, its EN and ENO), which are named by no name here.
    pub inherited: u32,
    /// The hidden type tag (variable 0, a UDINT set at initialisation to
    /// [`PouDef::tag_value`]) of a block, class or interface that takes part
    /// in inheritance or implements an interface: what dynamic dispatch
    /// reads.
    pub tag: Option<VarId>,
}

impl PouDef {
    /// The value of the type tag of the POU `p`'s instances.
    pub fn tag_value(p: PouId) -> u32 {
        p.0 + 1
    }

    /// Whether variable `v` is one the user cannot name: an inherited copy
    /// of a base's hidden variable, or the tag.
    pub fn hidden_var(&self, v: VarId) -> bool {
        Some(v) == self.tag || (v.0 < self.inherited && !self.var_index.values().any(|&x| x == v))
    }
}

impl PouDef {
    pub fn var(&self, v: VarId) -> &VarDef {
        &self.vars[v.0 as usize]
    }

    pub fn lookup(&self, name: Symbol) -> Option<VarId> {
        self.var_index.get(&name).copied()
    }

    /// The order of positional arguments (ed2 2.5.1.1): the inputs and
    /// in-outs in declaration order, then the outputs in declaration order;
    /// EN and ENO are never positional.
    pub fn positional_params(&self) -> Vec<VarId> {
        let control = |i: usize| {
            let v = Some(VarId(i as u32));
            v == self.en || v == self.eno || v == self.this
        };
        let of = |sections: &[Section]| {
            self.vars
                .iter()
                .enumerate()
                .filter(|(i, v)| sections.contains(&v.section) && !control(*i))
                .map(|(i, _)| VarId(i as u32))
                .collect::<Vec<_>>()
        };
        let mut out = of(&[Section::Input, Section::InOut]);
        out.extend(of(&[Section::Output]));
        out
    }
}

/// Where a global variable is declared.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
pub enum GlobalOwner {
    /// A VAR_GLOBAL block outside any configuration.
    TopLevel,
    Config(usize),
    Resource(usize, usize),
}

#[derive(Clone, Debug)]
pub struct GlobalDef {
    pub var: VarDef,
    pub owner: GlobalOwner,
}

#[derive(Clone, Debug)]
pub struct TaskDef {
    pub name: Symbol,
    /// Where its name is declared (its spelling).
    pub name_span: Span,
    pub span: Span,
    /// The event input of an event task.
    pub single: Option<DataRef>,
    /// Period in nanoseconds.
    pub interval: Option<i64>,
    pub priority: u32,
}

/// A value source or sink in a configuration: a global or a direct variable.
#[derive(Clone, Debug)]
pub enum DataRef {
    Global(GlobalId),
    Direct(DirectAddress),
    Const(Value),
}

#[derive(Clone, Debug)]
pub struct ProgramInstDef {
    pub name: Symbol,
    pub span: Span,
    /// Where the instance name is written (its spelling).
    pub name_span: Span,
    pub pou: PouId,
    /// Index into the resource's tasks.
    pub task: Option<usize>,
    pub inputs: Vec<(VarId, DataRef)>,
    pub outputs: Vec<(VarId, DataRef)>,
}

#[derive(Clone, Debug)]
pub struct ResourceDef {
    pub name: Option<Symbol>,
    pub span: Span,
    pub globals: Vec<GlobalId>,
    pub tasks: Vec<TaskDef>,
    pub programs: Vec<ProgramInstDef>,
}

#[derive(Clone, Debug)]
pub struct ConfigDef {
    pub name: Symbol,
    pub span: Span,
    pub globals: Vec<GlobalId>,
    pub resources: Vec<ResourceDef>,
}

/// What a name or member expression refers to.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
pub enum Res {
    /// A variable of the POU whose body is being analysed.
    Var(VarId),
    /// An enumeration value: its type and its index in the type's values.
    EnumValue(TypeId, u32),
    /// A member of a struct (field index) or of an FB instance (variable).
    Field(u32),
    FbMember(PouId, VarId),
    /// A global of a configuration (only in configuration scope).
    Global(GlobalId),
    /// `THIS`: the reference to the function block instance whose body
    /// or method runs.
    This,
    /// `SUPER`: `THIS` as a reference to the base of its block.
    Super,
}

/// A resolved call.
#[derive(Clone, Debug)]
pub struct CallInfo {
    pub target: CallTarget,
    pub args: Vec<BoundArg>,
    /// `EN := cond` (ed2 2.5.1.2): when `cond` is FALSE the call does
    /// nothing: no input is assigned, the body does not run, no output is
    /// copied, a function's value is its result type's default, and ENO is
    /// FALSE. Not among `args`.
    pub en: Option<ExprId>,
    /// `ENO => target` (`negated` for `NOT ENO => target`): receives the
    /// callee's ENO after the call (TRUE for a standard function), FALSE
    /// when EN was FALSE. Not among `args`.
    pub eno: Option<(ExprId, bool)>,
}

#[derive(Clone, Debug)]
pub enum CallTarget {
    /// A user (or prelude) FUNCTION.
    Function(PouId),
    /// A call of the function block instance that the callee expression denotes.
    FbInstance(PouId),
    /// A standard function with the concrete types it was resolved at: one
    /// per argument (after implicit conversion) and the result.
    Std {
        intrinsic: Intrinsic,
        arg_types: Vec<TypeId>,
        ret: TypeId,
    },
    /// The task clock (`CUR_TIME()`).
    CurTime,
    /// `REF(x)`: the reference to its one argument, a variable.
    Ref,
    /// `ADR(x)`: a pointer to its one argument, a variable.
    Adr,
    /// A METHOD (a function with the hidden in-out [`PouDef::this`]),
    /// called on the instance `this` denotes (`inst.m()`), or on the
    /// running instance (`m()` in the block's body or methods) for `None`.
    Method { method: PouId, this: Option<ExprId> },
}

#[derive(Clone, Debug)]
pub struct BoundArg {
    /// The parameter: a variable of the callee POU, or the position of a
    /// standard function's input.
    pub param: u32,
    pub kind: BoundArgKind,
}

#[derive(Clone, Debug)]
pub enum BoundArgKind {
    Input(ExprId),
    InOut(ExprId),
    Output { target: ExprId, negated: bool },
}

/// Pointers after the analysis (docs/oop.md, "Pointers"): every pointer
/// type is then a structure `{OBJECT : UDINT; BASE : REF_TO BYTE; OFFSET :
/// DINT}`: the object kind (0 for NULL, else the index in `kinds` plus 1),
/// the reference to the whole object, and the byte offset into it.
#[derive(Clone, Debug)]
pub struct PtrInfo {
    /// The one structure type of every pointer value.
    pub ptr: TypeId,
    /// The target type of each pointer type (VOID for `ADR(x)`'s).
    pub targets: rustc_hash::FxHashMap<TypeId, TypeId>,
    pub kinds: Vec<PtrKind>,
    /// `REF_TO V` for the element type `V` of every pointer type's target.
    pub elem_refs: rustc_hash::FxHashMap<TypeId, TypeId>,
    pub string: TypeId,
    pub char_ty: TypeId,
    pub byte: TypeId,
    pub dint: TypeId,
    pub udint: TypeId,
}

/// One kind of object a pointer can point into: the type of a variable
/// `ADR` was given (an array as a whole for an element of it).
#[derive(Clone, Debug)]
pub struct PtrKind {
    pub obj: TypeId,
    /// The innermost element type and how many of them the object has.
    pub elem: TypeId,
    pub count: u64,
    /// `SIZEOF` of one element.
    pub elem_size: u64,
    /// `REF_TO obj` and `REF_TO elem`.
    pub obj_ref: TypeId,
    pub elem_ref: TypeId,
    /// A STRING, whose bytes a pointer to BYTE, USINT or CHAR can see.
    pub string: bool,
}

/// The result of analysis.
pub struct Analysis {
    pub types: TypeTable,
    pub pous: Vec<PouDef>,
    pub globals: Vec<GlobalDef>,
    pub configs: Vec<ConfigDef>,
    /// The type of every expression, before any implicit conversion.
    pub expr_types: Vec<TypeId>,
    /// Expressions converted implicitly, with the type they convert to.
    pub coercions: FxHashMap<ExprId, TypeId>,
    pub resolutions: FxHashMap<ExprId, Res>,
    /// Folded constant values (of the expression's type, before coercion).
    pub consts: FxHashMap<ExprId, Value>,
    pub calls: FxHashMap<ExprId, CallInfo>,
    /// The implicit variables (EN, ENO) that some code refers to: the POU's
    /// own body, or `inst.ENO` outside it. The others need no storage.
    pub implicit_used: rustc_hash::FxHashSet<(PouId, VarId)>,
    /// Operands of Instruction List `S`/`R` instructions that name function
    /// block instances: the instruction sets the instance's input (the
    /// `fb_form` of `IlSem::SetReset`), not the operand itself.
    pub il_fb_inputs: rustc_hash::FxHashSet<ExprId>,
    /// The element types of the objects `ADR` points into: a pointer's
    /// object kind is the index here plus 1 (0 is NULL).
    pub ptr_kinds: Vec<TypeId>,
    /// `0` and `NULL` standing for the null pointer.
    pub null_ptrs: rustc_hash::FxHashSet<ExprId>,
    /// What the lowering of pointers needs; `None` in a program without
    /// pointer types.
    pub ptrs: Option<PtrInfo>,
    /// The type of the current result at the end of the IL body of a
    /// chart's transition (`StmtKind::Il` with a result), by the place it
    /// is stored in (the transition's condition variable).
    pub il_results: rustc_hash::FxHashMap<ExprId, TypeId>,
    pub diagnostics: Vec<Diagnostic>,
}

impl Analysis {
    pub fn pou(&self, p: PouId) -> &PouDef {
        &self.pous[p.0 as usize]
    }

    pub fn global(&self, g: GlobalId) -> &GlobalDef {
        &self.globals[g.0 as usize]
    }

    pub fn expr_type(&self, e: ExprId) -> TypeId {
        self.expr_types
            .get(e.index())
            .copied()
            .unwrap_or(TypeId::ERROR)
    }

    /// The type an expression has after its implicit conversion.
    pub fn final_type(&self, e: ExprId) -> TypeId {
        self.coercions
            .get(&e)
            .copied()
            .unwrap_or_else(|| self.expr_type(e))
    }

    pub fn pou_by_name(&self, name: Symbol) -> Option<PouId> {
        self.pous
            .iter()
            .position(|p| p.name == name)
            .map(|i| PouId(i as u32))
    }

    /// The syntax of a POU (of a METHOD: inside its function block).
    pub fn pou_syntax<'a>(&self, ast: &'a Ast, p: PouId) -> Option<&'a stc_syntax::ast::Pou> {
        let def = self.pous.get(p.0 as usize)?;
        if let Some((owner, k)) = def.method_of {
            return self.pou_syntax(ast, owner)?.methods.get(k).map(|m| &m.pou);
        }
        match ast.items.get(def.item)? {
            stc_syntax::ast::Item::Pou(pou) => Some(pou),
            _ => None,
        }
    }

    pub fn has_errors(&self) -> bool {
        self.diagnostics.iter().any(|d| d.is_error())
    }
}

/// Analyses a parsed project. `prelude` is the span of the prelude file in
/// the source map, if it was added: its POUs are the standard library.
pub fn analyze(
    ast: &Ast,
    interner: &mut Interner,
    sources: &SourceMap,
    prelude: Option<Span>,
    opts: Options,
) -> Analysis {
    analyzer::Sema::new(ast, interner, sources, prelude, opts).run()
}
