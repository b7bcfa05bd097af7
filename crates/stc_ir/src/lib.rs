//! The typed intermediate representation shared by every back end.
//!
//! Design: the IR keeps the program *structured* (IF, SWITCH, LOOP with a
//! latch, BREAK, CONTINUE, RETURN) with *expression trees*, because its three
//! consumers want different things from it: the C back end prints structured
//! C almost one-to-one, the netlist back end turns expression trees into
//! dataflow, and the bytecode compiler linearises trees into three-address
//! code itself. Everything a back end would otherwise have to re-derive from
//! the source is decided here, once:
//!
//! - every expression is typed, and every implicit conversion is an explicit
//!   [`ExprKind::Convert`];
//! - every name is resolved to a [`Place`]: a variable of the current POU, a
//!   global, a direct address, with projections (member, element, bit);
//! - constants are folded ([`ExprKind::Const`]);
//! - FOR is lowered to [`StmtKind::Loop`] with the exact semantics of
//!   spec/semantics.md (bounds evaluated once, no overflow of the control
//!   variable, its final value), REPEAT/WHILE likewise, ELSIF to nested IFs,
//!   CASE to [`StmtKind::Switch`] over integer ranges;
//! - every run-time check is explicit where it happens: array indices carry
//!   their bounds, integer division is marked, subrange stores are wrapped in
//!   [`ExprKind::Check`], FOR's zero step is a [`StmtKind::Fault`];
//! - R_EDGE/F_EDGE inputs and VAR_TEMP re-initialisation are lowered into
//!   ordinary statements of the body's prologue;
//! - standard function blocks are ordinary POUs (from the prelude); standard
//!   functions are [`Intrinsic`] calls with their resolved types.
//!
//! Types are the analyser's [`TypeTable`], so reports can print enumeration
//! names and struct members; [`layout`] decides the memory layout of every
//! type for back ends that need bytes (the VM, the process image).
//!
//! What back ends would otherwise each compute from a body is computed here
//! once, on the IR: [`visit`] walks bodies (calls, places, the variables
//! used, whether an expression calls), and [`faults`] decides which POUs
//! may raise a run-time fault (so a back end can leave out the check after
//! a call that cannot fault).

pub mod dump;
pub mod faults;
pub mod layout;
mod lower;
pub mod model;
pub mod ranges;
pub mod visit;

use stc_diagnostics::Span;
use stc_sema::idx::IdVec;
use stc_sema::{GlobalId, PouId, TypeId, TypeTable, VarId};
use stc_syntax::ast::PouKind;
use stc_syntax::literal::{AddrSize, DirectAddress};
use stc_syntax::Symbol;
use stc_values::{BinOp, Intrinsic, UnOp, Value};

pub use lower::lower;

/// The module of a program without errors (no prelude), for unit tests.
#[cfg(test)]
pub(crate) fn test_module(src: &str) -> Module {
    let mut sm = stc_diagnostics::SourceMap::new();
    sm.add("t.st", src.to_string()).expect("small source");
    let mut interner = stc_syntax::Interner::new();
    let (ast, diags) = stc_syntax::parse_project(&sm, &mut interner);
    assert!(diags.is_empty(), "{diags:?}");
    let a = stc_sema::analyze(&ast, &mut interner, &sm, None, Default::default());
    let errors = a
        .diagnostics
        .iter()
        .any(|d| d.severity == stc_diagnostics::Severity::Error);
    assert!(!errors, "{:?}", a.diagnostics);
    lower(&ast, a, &interner, &sm)
}

/// A whole program ready for a back end.
pub struct Module {
    pub types: TypeTable,
    pub pous: IdVec<PouId, Pou>,
    pub globals: IdVec<GlobalId, Global>,
    pub configs: Vec<stc_sema::ConfigDef>,
    /// Names as spelled at their declaration, by symbol (the last
    /// declaration of the symbol wins: see [`Module::spelled`]).
    pub names: Vec<String>,
    /// The spelling at each declaration, by the position where its name
    /// starts: a type `Valve` and a variable `valve` keep their own.
    pub spellings: rustc_hash::FxHashMap<u32, Box<str>>,
}

impl Module {
    /// The global a VAR_EXTERNAL named `name` of type `ty` binds when its
    /// POU runs in `ctx` (configuration, resource): the resource's, else
    /// the configuration's, else one outside configurations; run on its own
    /// (`None`), or where none of those has it, a global of that name and
    /// type outside configurations, else in any configuration. `None`: the
    /// external has no global (back ends give it a private variable). One
    /// rule for every back end.
    pub fn bind_global(
        &self,
        name: Symbol,
        ty: TypeId,
        ctx: Option<(usize, usize)>,
    ) -> Option<GlobalId> {
        let named = |g: &&GlobalId| self.globals[**g].name == name;
        if let Some(conf) = ctx.and_then(|(c, _)| self.configs.get(c)) {
            let res = ctx.and_then(|(_, r)| conf.resources.get(r));
            if let Some(g) = res.and_then(|res| res.globals.iter().find(named)) {
                return Some(*g);
            }
            if let Some(g) = conf.globals.iter().find(named) {
                return Some(*g);
            }
        }
        let in_config = |g: GlobalId| self.config_of_global(g).is_some();
        // (Outside the configurations that sema checked: only a global of
        // the external's type.)
        let fits =
            |g: GlobalId| self.globals[g].name == name && self.same_type(self.globals[g].ty, ty);
        let top = self.globals.ids().find(|&g| fits(g) && !in_config(g));
        top.or_else(|| self.globals.ids().find(|&g| fits(g)))
    }

    /// The configuration a global belongs to (declared in it or in one of
    /// its resources); `None` for a global outside every configuration.
    pub fn config_of_global(&self, g: GlobalId) -> Option<usize> {
        self.configs.iter().position(|c| {
            c.globals.contains(&g) || c.resources.iter().any(|r| r.globals.contains(&g))
        })
    }

    /// Whether two types are the same type (assignable both ways without
    /// conversion), as a VAR_EXTERNAL and its VAR_GLOBAL must be.
    pub fn same_type(&self, a: TypeId, b: TypeId) -> bool {
        use stc_sema::Compat;
        self.types.compat(a, b, false) == Compat::Same
            && self.types.compat(b, a, false) == Compat::Same
    }

    /// The initial value of every process-image slot that a located
    /// variable declares: the last explicit initial value among the
    /// declarations at that address (globals in order, then the variables
    /// of each POU in order), else the type default of the first
    /// declaration (`None`). Both back ends write it once, at start, so a
    /// located variable's initial value does not depend on which instance
    /// is initialised first.
    pub fn located_inits(&self) -> Vec<(DirectAddress, TypeId, Option<&stc_sema::InitValue>)> {
        let mut out: Vec<(DirectAddress, TypeId, Option<&stc_sema::InitValue>)> = Vec::new();
        let decls = self
            .globals
            .iter()
            .map(|g| (&g.location, g.ty, g.init.as_ref()))
            .chain(
                self.pous
                    .iter()
                    .flat_map(|p| p.vars.iter().map(|v| (&v.location, v.ty, v.init.as_ref()))),
            );
        for (loc, ty, init) in decls {
            let Some(a) = loc.as_ref().filter(|a| !a.is_incomplete()) else {
                continue;
            };
            match out.iter_mut().find(|(b, _, _)| b == a) {
                Some(slot) if init.is_some() => *slot = (a.clone(), ty, init),
                Some(_) => {}
                None => out.push((a.clone(), ty, init)),
            }
        }
        out
    }

    /// The type of an elementary type name (not STRING/WSTRING).
    pub fn types_elem(&self, e: stc_syntax::token::ElemType) -> TypeId {
        TypeId::of_elem(e)
    }

    /// The type a direct address has when no declared variable gives it
    /// one: BOOL for a bit, BYTE..LWORD by its size.
    pub fn addr_type(&self, a: &DirectAddress) -> TypeId {
        use stc_syntax::token::ElemType;
        self.types_elem(match a.size {
            AddrSize::Bit => ElemType::Bool,
            AddrSize::Byte => ElemType::Byte,
            AddrSize::Word => ElemType::Word,
            AddrSize::Dword => ElemType::Dword,
            AddrSize::Lword => ElemType::Lword,
        })
    }

    pub fn types_bool(&self) -> TypeId {
        self.types_elem(stc_syntax::token::ElemType::Bool)
    }

    pub fn pou(&self, p: PouId) -> &Pou {
        &self.pous[p]
    }

    /// The name declared at `span` as spelled there (else as [`Module::name`]).
    pub fn spelled(&self, s: Symbol, span: Span) -> &str {
        let name = self.name(s);
        match self.spellings.get(&span.lo) {
            // (A compiler-made variable may carry another name's span.)
            Some(t) if t.eq_ignore_ascii_case(name) => t,
            _ => name,
        }
    }

    /// The spelling of a named type's declaration.
    pub fn type_name(&self, t: TypeId) -> Option<&str> {
        let info = self.types.get(t);
        let n = info.name?;
        Some(match info.name_span {
            Some(sp) => self.spelled(n, sp),
            None => self.name(n),
        })
    }

    pub fn name(&self, s: Symbol) -> &str {
        self.names
            .get(s.0 as usize)
            .map(|s| s.as_str())
            .unwrap_or("?")
    }
}

pub struct Global {
    pub name: Symbol,
    pub ty: TypeId,
    pub init: Option<stc_sema::InitValue>,
    pub constant: bool,
    pub retain: bool,
    pub location: Option<DirectAddress>,
    pub span: Span,
    /// Declared by the standard library (the prelude), not the user.
    pub library: bool,
}

/// Where a variable lives.
#[derive(Clone, Copy, PartialEq, Eq, Debug, Hash)]
pub enum Storage {
    /// In the instance (function blocks and programs: inputs, outputs,
    /// VAR, hidden edge memories).
    Instance,
    /// In the frame of one call (functions: everything; FB/programs:
    /// VAR_TEMP).
    Frame,
    /// A reference (VAR_IN_OUT, VAR_EXTERNAL, a located variable), stored in
    /// the instance or the frame as the address of the real variable (for a
    /// located variable: its slot of the process image).
    Ref,
}

pub struct Var {
    pub name: Symbol,
    pub ty: TypeId,
    pub section: stc_sema::Section,
    pub storage: Storage,
    pub init: Option<stc_sema::InitValue>,
    pub constant: bool,
    pub retain: bool,
    pub location: Option<DirectAddress>,
    /// Variables the compiler added (edge memories, FOR bounds), with the
    /// role they play (`prev`, `end`...); not visible to users.
    pub hidden: Option<&'static str>,
    pub span: Span,
}

pub struct Pou {
    pub kind: PouKind,
    pub name: Symbol,
    pub vars: IdVec<VarId, Var>,
    /// The function's result variable.
    pub result: Option<VarId>,
    pub body: Vec<Stmt>,
    pub is_std: bool,
    pub span: Span,
    /// Where its name is declared (its spelling).
    pub name_span: Span,
    /// The source file the POU comes from (for fault reports).
    pub file: String,
}

impl Pou {
    pub fn var(&self, v: VarId) -> &Var {
        &self.vars[v]
    }
}

#[derive(Clone, Debug)]
pub struct Stmt {
    pub kind: StmtKind,
    /// 1-based source line and column, for fault reports.
    pub line: u32,
    pub col: u32,
}

#[derive(Clone, Debug)]
pub enum StmtKind {
    Assign {
        place: Place,
        value: Expr,
    },
    /// A call of a function block instance: inputs are assigned to the
    /// instance in order, references bound, the body runs, then outputs
    /// are copied to their targets.
    CallFb {
        instance: Place,
        fb: PouId,
        inputs: Vec<(VarId, Expr)>,
        inouts: Vec<(VarId, Place)>,
        outputs: Vec<Output>,
    },
    /// An expression evaluated for its effects (a function call).
    Eval(Expr),
    If {
        cond: Expr,
        then_body: Vec<Stmt>,
        else_body: Vec<Stmt>,
    },
    /// CASE: the first arm with a range containing the selector runs.
    Switch {
        selector: Expr,
        arms: Vec<SwitchArm>,
        default: Vec<Stmt>,
    },
    /// Runs `body` then `latch` forever; `Continue` runs the latch and starts
    /// the next iteration, `Break` leaves the loop.
    Loop {
        body: Vec<Stmt>,
        latch: Vec<Stmt>,
    },
    Break,
    Continue,
    Return,
    /// A run-time fault, raised when reached.
    Fault(FaultKind),
}

/// One arm of a [`StmtKind::Switch`]: inclusive value ranges and a body.
#[derive(Clone, Debug)]
pub struct SwitchArm {
    pub ranges: Vec<(i128, i128)>,
    pub body: Vec<Stmt>,
}

/// A run-time fault.
///
/// The explicit values are the one numbering of faults: the operand of the
/// VM's `fault` instruction (so a byte of `.stbc` files) and the
/// `STC_FAULT_*` codes of the generated C (`stc_codes.h`), where 0 is
/// `STC_FAULT_NONE`. Never renumber a kind.
#[derive(Clone, Copy, PartialEq, Eq, Debug, Hash)]
#[repr(u8)]
pub enum FaultKind {
    DivisionByZero = 1,
    IndexOutOfBounds = 2,
    SubrangeViolation = 3,
    Conversion = 4,
    MuxRange = 5,
    ForStepZero = 6,
    Watchdog = 7,
    /// Bytecode that tried to leave its memory (only a corrupt or hostile
    /// program file can; the verifier rejects them before they run).
    InvalidCode = 8,
    /// A dereference of NULL.
    NullReference = 9,
    /// A pointer dereferenced outside its object (or not at a whole
    /// element of it), or two pointers into different objects ordered or
    /// subtracted.
    PointerBounds = 10,
}

impl FaultKind {
    /// Every kind, in the order of their codes.
    pub const ALL: [FaultKind; 10] = [
        FaultKind::DivisionByZero,
        FaultKind::IndexOutOfBounds,
        FaultKind::SubrangeViolation,
        FaultKind::Conversion,
        FaultKind::MuxRange,
        FaultKind::ForStepZero,
        FaultKind::Watchdog,
        FaultKind::InvalidCode,
        FaultKind::NullReference,
        FaultKind::PointerBounds,
    ];

    /// The kind's stable code (see the type's documentation).
    pub const fn code(self) -> u8 {
        self as u8
    }

    /// The kind of a code; `None` for 0 (no fault) and unknown values.
    pub fn from_code(code: u32) -> Option<FaultKind> {
        Self::ALL.into_iter().find(|k| u32::from(k.code()) == code)
    }

    /// The fault's name in `fault: KIND in POU at FILE:LINE:COL`.
    pub fn text(self) -> &'static str {
        match self {
            FaultKind::DivisionByZero => "division by zero",
            FaultKind::IndexOutOfBounds => "array index out of bounds",
            FaultKind::SubrangeViolation => "subrange violation",
            FaultKind::Conversion => "conversion failure",
            FaultKind::MuxRange => "MUX selector out of range",
            FaultKind::ForStepZero => "FOR step of zero",
            FaultKind::Watchdog => "watchdog",
            FaultKind::InvalidCode => "invalid bytecode",
            FaultKind::NullReference => "NULL dereference",
            FaultKind::PointerBounds => "pointer out of bounds",
        }
    }

    pub fn from_value_fault(f: stc_values::Fault) -> FaultKind {
        match f {
            stc_values::Fault::DivisionByZero => FaultKind::DivisionByZero,
            stc_values::Fault::Conversion => FaultKind::Conversion,
            stc_values::Fault::MuxRange => FaultKind::MuxRange,
        }
    }
}

#[derive(Clone, Debug)]
pub struct Output {
    pub var: VarId,
    pub target: Place,
    pub negated: bool,
}

#[derive(Clone, Debug)]
pub struct Expr {
    pub kind: ExprKind,
    pub ty: TypeId,
}

#[derive(Clone, Debug)]
pub enum ExprKind {
    Const(Value),
    Load(Place),
    Unary(UnOp, Box<Expr>),
    /// Operands have one type, except time arithmetic (`TOD + TIME`) and
    /// `**` (any numeric exponent).
    Binary(BinOp, Box<Expr>, Box<Expr>),
    /// A conversion from the operand's type to this expression's type.
    Convert(Box<Expr>),
    /// A subrange store: the value must lie in `lo..=hi`.
    Check {
        value: Box<Expr>,
        lo: i128,
        hi: i128,
    },
    CallFn {
        func: PouId,
        inputs: Vec<(VarId, Expr)>,
        inouts: Vec<(VarId, Place)>,
        outputs: Vec<Output>,
    },
    /// A standard function with arguments of the types it was resolved at.
    Intrinsic {
        func: Intrinsic,
        args: Vec<Expr>,
    },
    /// The task clock (TIME).
    CurTime,
    /// `expr`, whose own check (a division, a conversion, a subrange
    /// check, an array index...) reports this source position (1-based
    /// line and column: the operator, the call, the index) when it faults,
    /// rather than its statement's. Lowering puts it around each
    /// expression that may fault at its own node and around each checked
    /// array index; for everything but fault reports it is `expr` itself
    /// (see [`Expr::located`]).
    Located {
        line: u32,
        col: u32,
        expr: Box<Expr>,
    },
    /// `REF(x)`: the reference to a place (of instance or global memory,
    /// never of a frame: the analyser refuses those, docs/oop.md). Its type
    /// is a [`stc_sema::TypeKind::Ref`].
    Ref(Place),
    /// The null reference (of any reference type). Back ends store a
    /// reference as an address (4 bytes on the VM and the JIT, a pointer in
    /// C) and `NULL` as 0; `=` and `<>` compare references.
    Null,
}

impl Expr {
    /// The position a [`ExprKind::Located`] gives, and the expression
    /// inside it (`self` and `None` for any other expression).
    pub fn located(&self) -> (Option<(u32, u32)>, &Expr) {
        match &self.kind {
            ExprKind::Located { line, col, expr } => (Some((*line, *col)), expr),
            _ => (None, self),
        }
    }

    /// The expression without its [`ExprKind::Located`] wrapper.
    pub fn unlocated(&self) -> &Expr {
        self.located().1
    }
}

#[derive(Clone, Debug)]
pub struct Place {
    pub root: Root,
    pub proj: Vec<Proj>,
    pub ty: TypeId,
}

#[derive(Clone, Debug)]
pub enum Root {
    /// A variable of the current POU (through its reference for VAR_IN_OUT
    /// and VAR_EXTERNAL).
    Var(VarId),
    Global(GlobalId),
    Direct(DirectAddress),
    /// The instance of the FUNCTION_BLOCK whose body runs (`THIS^` in its
    /// body; a METHOD reaches its instance through its hidden in-out
    /// variable instead). Only in the body of a function block.
    This,
    /// What a reference refers to (`r^`): the expression, of a reference
    /// type, is evaluated, and a NULL reference is the fault
    /// [`FaultKind::NullReference`].
    Deref(Box<Expr>),
}

#[derive(Clone, Debug)]
pub enum Proj {
    /// A member of a struct (by index).
    Field(u32),
    /// A variable of a function block or program instance.
    FbVar(PouId, VarId),
    /// Array elements: one index per dimension, with the dimension's bounds.
    Index(Vec<(Expr, i128, i128)>),
    /// A part of a bit string: bit `index` (size X), byte, word...
    Part(AddrSize, u32),
}
