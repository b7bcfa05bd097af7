//! The syntax tree.
//!
//! Expressions live in one arena per project ([`Ast::exprs`]) and are named by
//! [`ExprId`]; later phases attach facts to them with side tables indexed by
//! the id (the type of every expression, its constant value) instead of
//! mutating the tree. Statements, declarations and POUs are plain owned
//! values. Every node carries its [`Span`]. Names are interned [`Symbol`]s
//! with the span of their spelling.

use stc_diagnostics::Span;

use crate::intern::Symbol;
use crate::literal::{AddrSize, DirectAddress};
use crate::token::{ElemType, GenericType};

/// Index of an expression in [`Ast::exprs`].
#[derive(Clone, Copy, PartialEq, Eq, Hash, Debug, PartialOrd, Ord)]
pub struct ExprId(pub u32);

impl ExprId {
    pub fn index(self) -> usize {
        self.0 as usize
    }
}

/// A name as written: its symbol and where.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
pub struct Ident {
    pub sym: Symbol,
    pub span: Span,
}

/// A whole project: every file's items in one tree.
#[derive(Default)]
pub struct Ast {
    pub items: Vec<Item>,
    pub exprs: Vec<Expr>,
    /// Names declared by top-level constructs that were reported as not
    /// supported (E0030) and skipped: an INTERFACE, a NAMESPACE... A use of
    /// such a name (a variable of an interface type) is then not reported
    /// again.
    pub unsupported_names: Vec<Ident>,
}

impl Ast {
    pub fn expr(&self, id: ExprId) -> &Expr {
        &self.exprs[id.index()]
    }

    pub fn alloc(&mut self, kind: ExprKind, span: Span) -> ExprId {
        let id = ExprId(self.exprs.len() as u32);
        self.exprs.push(Expr { kind, span });
        id
    }
}

#[derive(Clone, PartialEq, Debug)]
pub struct Expr {
    pub kind: ExprKind,
    pub span: Span,
}

#[derive(Clone, PartialEq, Debug)]
pub enum ExprKind {
    /// Something that could not be parsed; already reported.
    Error,
    Literal(Literal),
    /// A variable, an unqualified enumeration value, a constant...
    Name(Ident),
    /// `Type#value`.
    EnumValue {
        ty: Ident,
        value: Ident,
    },
    /// `%IX0.1` used as a variable.
    Address(Box<DirectAddress>),
    /// `base.member`.
    Member {
        base: ExprId,
        member: Ident,
    },
    /// `base.3` or `base.%X3`: one bit (byte, word...) of a bit string.
    PartialAccess {
        base: ExprId,
        size: AddrSize,
        index: u32,
    },
    /// `base[i, j]`.
    Index {
        base: ExprId,
        indices: Box<[ExprId]>,
    },
    /// `callee(args)`: a function or a function block instance call.
    Call {
        callee: ExprId,
        args: Box<[Arg]>,
    },
    Unary {
        op: UnaryOp,
        operand: ExprId,
    },
    Binary {
        op: BinaryOp,
        lhs: ExprId,
        rhs: ExprId,
    },
    /// `( inner )`, kept so the printer can reproduce the source.
    Paren(ExprId),
    /// `base^`: the dereference of a 3rd-edition reference (`REF_TO`).
    Deref(ExprId),
    /// The current result of an Instruction List body (see [`IlInstr`]):
    /// never written by users, made by the parser where an IL instruction
    /// reads the accumulator; its type is the one the analyser tracks.
    IlCr,
}

#[derive(Clone, Copy, PartialEq, Eq, Debug, Hash)]
pub enum UnaryOp {
    Neg,
    Plus,
    Not,
}

#[derive(Clone, Copy, PartialEq, Eq, Debug, Hash)]
pub enum BinaryOp {
    Or,
    Xor,
    And,
    Eq,
    Ne,
    Lt,
    Le,
    Gt,
    Ge,
    Add,
    Sub,
    Mul,
    Div,
    Mod,
    Pow,
}

impl BinaryOp {
    /// Binding strength: higher binds tighter. Unary operators bind at 8,
    /// between `*` (7) and `**` (9).
    pub fn precedence(self) -> u8 {
        match self {
            BinaryOp::Or => 1,
            BinaryOp::Xor => 2,
            BinaryOp::And => 3,
            BinaryOp::Eq | BinaryOp::Ne => 4,
            BinaryOp::Lt | BinaryOp::Le | BinaryOp::Gt | BinaryOp::Ge => 5,
            BinaryOp::Add | BinaryOp::Sub => 6,
            BinaryOp::Mul | BinaryOp::Div | BinaryOp::Mod => 7,
            BinaryOp::Pow => 9,
        }
    }

    pub fn symbol(self) -> &'static str {
        match self {
            BinaryOp::Or => "OR",
            BinaryOp::Xor => "XOR",
            BinaryOp::And => "AND",
            BinaryOp::Eq => "=",
            BinaryOp::Ne => "<>",
            BinaryOp::Lt => "<",
            BinaryOp::Le => "<=",
            BinaryOp::Gt => ">",
            BinaryOp::Ge => ">=",
            BinaryOp::Add => "+",
            BinaryOp::Sub => "-",
            BinaryOp::Mul => "*",
            BinaryOp::Div => "/",
            BinaryOp::Mod => "MOD",
            BinaryOp::Pow => "**",
        }
    }
}

pub const UNARY_PRECEDENCE: u8 = 8;

/// One argument of a call.
#[derive(Clone, PartialEq, Debug)]
pub struct Arg {
    pub kind: ArgKind,
    pub span: Span,
}

#[derive(Clone, PartialEq, Debug)]
pub enum ArgKind {
    /// A positional (non-formal) argument.
    Positional(ExprId),
    /// `name := value`.
    Input { name: Ident, value: ExprId },
    /// `name => target` or `NOT name => target`.
    Output {
        name: Ident,
        negated: bool,
        target: ExprId,
    },
}

/// The prefix of a typed literal: `INT#`, `MyType#`.
#[derive(Clone, Copy, PartialEq, Debug)]
pub enum TypePrefix {
    Elem(ElemType, Span),
    Named(Ident),
}

#[derive(Clone, PartialEq, Debug)]
pub struct Literal {
    pub value: LitValue,
    /// `INT#` in `INT#5`; time literals carry their kind in the value.
    pub prefix: Option<TypePrefix>,
}

#[derive(Clone, PartialEq, Debug)]
pub enum LitValue {
    /// An integer; `negative` only for a signed typed literal (`INT#-5`).
    /// Untyped negative numbers are `Unary(Neg, Int)`.
    Int {
        value: u64,
        negative: bool,
    },
    Real(f64),
    Bool(bool),
    String {
        value: Box<str>,
        wide: bool,
    },
    /// Nanoseconds; `long` for LTIME.
    Duration {
        ns: i64,
        long: bool,
    },
    /// Seconds since 1970-01-01 (a whole day); `long` for LDATE.
    Date {
        secs: i64,
        long: bool,
    },
    /// Nanoseconds since midnight; `long` for LTOD.
    Tod {
        ns: u64,
        long: bool,
    },
    /// Nanoseconds since 1970-01-01T00:00; `long` for LDT.
    Dt {
        ns: i64,
        long: bool,
    },
}

// ---------------------------------------------------------------------------
// Statements

#[derive(Clone, PartialEq, Debug)]
pub struct Stmt {
    pub kind: StmtKind,
    pub span: Span,
}

#[derive(Clone, PartialEq, Debug)]
pub enum StmtKind {
    /// `;` alone.
    Empty,
    /// A statement that could not be parsed; already reported.
    Error,
    Assign {
        target: ExprId,
        value: ExprId,
    },
    /// `target ?= value` (assignment attempt, 3rd edition): the reference
    /// or interface value `value` when the instance it refers to fits
    /// `target`'s type, else NULL.
    AssignAttempt {
        target: ExprId,
        value: ExprId,
    },
    /// A call used as a statement (a function block or function call).
    Call(ExprId),
    If {
        /// `IF`/`ELSIF` conditions with their bodies, in order.
        branches: Vec<CondBranch>,
        else_body: Option<Vec<Stmt>>,
    },
    Case {
        selector: ExprId,
        arms: Vec<CaseArm>,
        else_body: Option<Vec<Stmt>>,
    },
    For {
        var: Ident,
        from: ExprId,
        to: ExprId,
        by: Option<ExprId>,
        body: Vec<Stmt>,
    },
    While {
        cond: ExprId,
        body: Vec<Stmt>,
    },
    Repeat {
        body: Vec<Stmt>,
        until: ExprId,
    },
    Exit,
    Continue,
    Return,
    /// An Instruction List body inside a statement list: the meaning of an
    /// IL action or transition of a chart (`stc_syntax::sfc`). With
    /// `result`, the current result at the end of the body is assigned to
    /// that place (a transition's condition, which must be BOOL).
    Il {
        body: Box<IlBody>,
        result: Option<ExprId>,
    },
    /// A statement of a dialect form that stc does not support (`r REF= v`,
    /// `x ?= y`), already reported (E0030). Its expressions are kept so the
    /// names in them are still resolved (and count as used).
    Unsupported(Vec<ExprId>),
}

#[derive(Clone, PartialEq, Debug)]
pub struct CondBranch {
    pub cond: ExprId,
    pub body: Vec<Stmt>,
}

#[derive(Clone, PartialEq, Debug)]
pub struct CaseArm {
    pub labels: Vec<CaseLabel>,
    pub body: Vec<Stmt>,
    pub span: Span,
}

#[derive(Clone, PartialEq, Debug)]
pub enum CaseLabel {
    Value(ExprId),
    Range(ExprId, ExprId),
}

// ---------------------------------------------------------------------------
// Types and declarations

#[derive(Clone, PartialEq, Debug)]
pub struct TypeSpec {
    pub kind: TypeSpecKind,
    pub span: Span,
}

#[derive(Clone, PartialEq, Debug)]
pub enum TypeSpecKind {
    /// A type that could not be parsed or is not supported; already reported.
    Error,
    Elementary(ElemType),
    Generic(GenericType),
    /// A derived type, function block type or program type by name.
    Named(Ident),
    /// `STRING`, `STRING[10]`, `WSTRING(20)`.
    String {
        wide: bool,
        len: Option<ExprId>,
    },
    /// `INT (0..100)`.
    Subrange {
        base: Box<TypeSpec>,
        lo: ExprId,
        hi: ExprId,
    },
    /// `(red, green := 5, blue)`, optionally with a base type after it.
    Enum {
        values: Vec<EnumMember>,
        base: Option<Box<TypeSpec>>,
    },
    /// `ARRAY [1..10, 0..N] OF T`.
    Array {
        dims: Vec<ArrayDim>,
        elem: Box<TypeSpec>,
    },
    /// `STRUCT ... END_STRUCT`.
    Struct {
        members: Vec<VarDecl>,
    },
    /// `REF_TO T`: a reference to a variable of type `T` (3rd edition).
    Ref(Box<TypeSpec>),
    /// `POINTER TO T`: a CODESYS pointer (docs/oop.md, "Pointers").
    Pointer(Box<TypeSpec>),
}

#[derive(Clone, PartialEq, Debug)]
pub struct EnumMember {
    pub name: Ident,
    pub value: Option<ExprId>,
}

#[derive(Clone, PartialEq, Debug)]
pub enum ArrayDim {
    Range {
        lo: ExprId,
        hi: ExprId,
    },
    /// `*`: a variable-length dimension (3rd edition, VAR_IN_OUT only).
    Star(Span),
}

/// An initial value.
#[derive(Clone, PartialEq, Debug)]
pub struct Init {
    pub kind: InitKind,
    pub span: Span,
}

#[derive(Clone, PartialEq, Debug)]
pub enum InitKind {
    Expr(ExprId),
    /// `[1, 2, 3(0)]`.
    Array(Vec<ArrayInitElem>),
    /// `(x := 1, y := 2)`.
    Struct(Vec<StructInitElem>),
}

#[derive(Clone, PartialEq, Debug)]
pub struct ArrayInitElem {
    /// `3` in `3(0)`.
    pub repeat: Option<ExprId>,
    /// The value, or the values repeated: `[2(1, 2)]` is `[1, 2, 1, 2]`;
    /// empty for `3()`, three default values.
    pub values: Vec<Init>,
    pub span: Span,
}

#[derive(Clone, PartialEq, Debug)]
pub struct StructInitElem {
    pub name: Ident,
    pub value: Init,
}

#[derive(Clone, Copy, PartialEq, Eq, Debug, Hash)]
pub enum Edge {
    Rising,
    Falling,
}

/// One declaration line: `a, b AT %IX0.0 : T := init;`.
#[derive(Clone, PartialEq, Debug)]
pub struct VarDecl {
    /// Empty for an unnamed located variable (`AT %IX0.0 : BOOL;`).
    pub names: Vec<Ident>,
    pub location: Option<Located>,
    pub ty: TypeSpec,
    pub edge: Option<Edge>,
    pub init: Option<Init>,
    pub span: Span,
    /// Pragmas written just before the declaration.
    pub pragmas: Vec<Span>,
}

#[derive(Clone, PartialEq, Debug)]
pub struct Located {
    pub address: DirectAddress,
    pub span: Span,
}

#[derive(Clone, Copy, PartialEq, Eq, Debug, Hash)]
pub enum VarKind {
    Var,
    Input,
    Output,
    InOut,
    External,
    Global,
    Temp,
    Access,
    Config,
    /// `VAR_STAT` (CODESYS): one variable for every call and instance.
    Stat,
    /// `VAR_INST` of a METHOD (CODESYS): kept in the instance.
    Inst,
}

impl VarKind {
    pub fn keyword(self) -> &'static str {
        match self {
            VarKind::Var => "VAR",
            VarKind::Input => "VAR_INPUT",
            VarKind::Output => "VAR_OUTPUT",
            VarKind::InOut => "VAR_IN_OUT",
            VarKind::External => "VAR_EXTERNAL",
            VarKind::Global => "VAR_GLOBAL",
            VarKind::Temp => "VAR_TEMP",
            VarKind::Access => "VAR_ACCESS",
            VarKind::Config => "VAR_CONFIG",
            VarKind::Stat => "VAR_STAT",
            VarKind::Inst => "VAR_INST",
        }
    }
}

#[derive(Clone, Copy, PartialEq, Eq, Debug, Hash)]
pub enum Retention {
    Retain,
    NonRetain,
}

#[derive(Clone, PartialEq, Debug)]
pub struct VarBlock {
    pub kind: VarKind,
    /// An access specifier after the keyword (`VAR PUBLIC`, 3rd edition):
    /// a PUBLIC or INTERNAL VAR of a block or class is visible outside it.
    pub access: Option<Access>,
    pub constant: bool,
    pub retention: Option<Retention>,
    pub items: VarBlockItems,
    pub span: Span,
}

#[derive(Clone, PartialEq, Debug)]
pub enum VarBlockItems {
    Vars(Vec<VarDecl>),
    Access(Vec<AccessDecl>),
    Config(Vec<ConfigInit>),
}

#[derive(Clone, Copy, PartialEq, Eq, Debug, Hash)]
pub enum AccessDirection {
    ReadOnly,
    ReadWrite,
}

/// `name : path : TYPE [READ_ONLY|READ_WRITE];` in VAR_ACCESS.
#[derive(Clone, PartialEq, Debug)]
pub struct AccessDecl {
    pub name: Ident,
    /// `CPU` in `CPU.%IW4` (a direct variable of a named resource).
    pub resource: Option<Ident>,
    pub path: ExprId,
    pub ty: TypeSpec,
    pub direction: Option<AccessDirection>,
    pub span: Span,
}

/// `res.prog.fb.var [AT %Q..] : TYPE [:= init];` in VAR_CONFIG.
#[derive(Clone, PartialEq, Debug)]
pub struct ConfigInit {
    pub path: Vec<Ident>,
    pub location: Option<Located>,
    pub ty: TypeSpec,
    pub init: Option<Init>,
    pub span: Span,
}

/// `name : spec [:= init];` in a TYPE block.
#[derive(Clone, PartialEq, Debug)]
pub struct TypeDecl {
    pub name: Ident,
    pub spec: TypeSpec,
    pub init: Option<Init>,
    pub span: Span,
    pub pragmas: Vec<Span>,
}

// ---------------------------------------------------------------------------
// Program organisation units and configurations

#[derive(Clone, Copy, PartialEq, Eq, Debug, Hash)]
pub enum PouKind {
    Function,
    FunctionBlock,
    Program,
}

impl PouKind {
    pub fn keyword(self) -> &'static str {
        match self {
            PouKind::Function => "FUNCTION",
            PouKind::FunctionBlock => "FUNCTION_BLOCK",
            PouKind::Program => "PROGRAM",
        }
    }

    pub fn end_keyword(self) -> &'static str {
        match self {
            PouKind::Function => "END_FUNCTION",
            PouKind::FunctionBlock => "END_FUNCTION_BLOCK",
            PouKind::Program => "END_PROGRAM",
        }
    }
}

#[derive(Clone, PartialEq, Debug)]
pub struct Pou {
    pub kind: PouKind,
    pub name: Ident,
    /// The result type of a FUNCTION (`None` for a function without result).
    pub return_type: Option<TypeSpec>,
    pub var_blocks: Vec<VarBlock>,
    pub body: Vec<Stmt>,
    /// The body in Instruction List (then `body` is empty).
    pub il: Option<IlBody>,
    /// The body as a Sequential Function Chart, as written (docs/sfc.md).
    /// Then `body` holds its meaning in ST (the evolution rules over the
    /// step flags and the action controls, made by the parser) and the last
    /// [`SfcBody::generated_blocks`] blocks of `var_blocks` declare the
    /// state it needs; the printer and the dump show the chart instead.
    pub sfc: Option<SfcBody>,
    pub span: Span,
    pub pragmas: Vec<Span>,
    /// The base named by `EXTENDS` of a FUNCTION_BLOCK or CLASS (for an
    /// INTERFACE, its bases are in `implements`).
    pub extends: Option<Ident>,
    /// The interfaces named by `IMPLEMENTS` (of an INTERFACE: those it
    /// `EXTENDS`).
    pub implements: Vec<Ident>,
    /// A CLASS or an INTERFACE (3rd edition), kept as a POU of kind
    /// FUNCTION_BLOCK (docs/oop.md): `None` for an ordinary POU.
    pub class: Option<ClassKind>,
    /// ACTIONs, METHODs and PROPERTYs declared inside the POU, skipped after
    /// their E0030: a use of one of them (`inst.Reset()`) is not reported
    /// again.
    pub skipped_members: Vec<Ident>,
    /// Some part of the POU (its body as IL or SFC, a method, a `__TRY`
    /// block...) was skipped after an E0030, so which variables are used and
    /// whether the result is assigned is not known: the warnings that
    /// depend on it (W0104, W0106) are not given.
    pub partial: bool,
    /// The METHODs of a FUNCTION_BLOCK (3rd edition), in source order.
    pub methods: Vec<Method>,
    /// `FUNCTION_BLOCK ABSTRACT`: never instantiated.
    pub is_abstract: bool,
    /// `FUNCTION_BLOCK FINAL`.
    pub is_final: bool,
    /// `FUNCTION_BLOCK INTERNAL`: inside a namespace, visible only within
    /// it.
    pub internal: bool,
    /// The POU's `USING` directives (after its name, or a FUNCTION's
    /// result type), each namespace as written.
    pub usings: Vec<Ident>,
}

/// What a POU of kind FUNCTION_BLOCK was declared as, when not
/// `FUNCTION_BLOCK`.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
pub enum ClassKind {
    /// `CLASS ... END_CLASS`: variables and methods, no body, no inputs or
    /// outputs.
    Class,
    /// `INTERFACE ... END_INTERFACE`: method prototypes only.
    Interface,
}

impl Pou {
    /// The word that opens the POU (`FUNCTION_BLOCK`, `CLASS`...).
    pub fn keyword(&self) -> &'static str {
        match self.class {
            Some(ClassKind::Class) => "CLASS",
            Some(ClassKind::Interface) => "INTERFACE",
            None => self.kind.keyword(),
        }
    }

    /// The word that closes the POU.
    pub fn end_keyword(&self) -> &'static str {
        match self.class {
            Some(ClassKind::Class) => "END_CLASS",
            Some(ClassKind::Interface) => "END_INTERFACE",
            None => self.kind.end_keyword(),
        }
    }

    pub fn is_interface(&self) -> bool {
        self.class == Some(ClassKind::Interface)
    }
}

/// A METHOD of a FUNCTION_BLOCK: a function of its instance, which reads
/// and writes the instance's variables (and `THIS`).
#[derive(Clone, PartialEq, Debug)]
pub struct Method {
    /// The method as a POU of kind FUNCTION: its name, result type,
    /// variables and body (`methods` is empty).
    pub pou: Pou,
    /// The access specifier as written (`None`: PUBLIC by default).
    pub access: Option<Access>,
    pub is_abstract: bool,
    pub is_final: bool,
    pub is_override: bool,
    /// An ACTION of the function block (`ACTION name: statements
    /// END_ACTION`): a method with no variables, no result and no
    /// modifiers, written after the body.
    pub is_action: bool,
    /// A part of a PROPERTY (`PROPERTY name : T GET ... END_GET SET ...
    /// END_SET END_PROPERTY`, docs/oop.md): the getter is a method named
    /// like the property returning `T`; the setter a method named
    /// `name.SET` (a name no one can write) whose first variable block is
    /// the VAR_INPUT `name : T` the parser adds. `property` is the
    /// property's name as written.
    pub property: Option<(PropertyPart, Ident)>,
}

/// Which accessor of a PROPERTY a [`Method`] is.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
pub enum PropertyPart {
    Get,
    Set,
}

impl Method {
    /// The words between `METHOD` and the name, as written in canonical
    /// form: the access specifier, then ABSTRACT, FINAL, OVERRIDE (each
    /// with a leading space; empty when there are none).
    pub fn modifiers(&self) -> String {
        let mut out = String::new();
        if let Some(a) = self.access {
            out.push(' ');
            out.push_str(a.keyword());
        }
        for (on, word) in [
            (self.is_abstract, "ABSTRACT"),
            (self.is_final, "FINAL"),
            (self.is_override, "OVERRIDE"),
        ] {
            if on {
                out.push(' ');
                out.push_str(word);
            }
        }
        out
    }
}

/// An access specifier of a METHOD.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
pub enum Access {
    Public,
    Private,
    Protected,
    Internal,
}

impl Access {
    pub fn keyword(self) -> &'static str {
        match self {
            Access::Public => "PUBLIC",
            Access::Private => "PRIVATE",
            Access::Protected => "PROTECTED",
            Access::Internal => "INTERNAL",
        }
    }
}

#[derive(Clone, PartialEq, Debug)]
pub struct Configuration {
    pub name: Ident,
    /// VAR_GLOBAL, VAR_ACCESS and VAR_CONFIG blocks, in source order.
    pub var_blocks: Vec<VarBlock>,
    pub resources: Vec<Resource>,
    pub span: Span,
}

/// A RESOURCE, or the implicit single resource of a configuration written
/// without one (then `name` is `None`).
#[derive(Clone, PartialEq, Debug)]
pub struct Resource {
    pub name: Option<Ident>,
    /// The resource type after ON.
    pub on: Option<Ident>,
    pub var_blocks: Vec<VarBlock>,
    pub tasks: Vec<TaskDecl>,
    pub programs: Vec<ProgramConfig>,
    pub span: Span,
}

#[derive(Clone, PartialEq, Debug)]
pub struct TaskDecl {
    pub name: Ident,
    pub single: Option<ExprId>,
    pub interval: Option<ExprId>,
    pub priority: Option<ExprId>,
    pub span: Span,
}

#[derive(Clone, PartialEq, Debug)]
pub struct ProgramConfig {
    pub name: Ident,
    pub retention: Option<Retention>,
    pub task: Option<Ident>,
    pub type_name: Ident,
    pub conns: Vec<ProgramConn>,
    pub span: Span,
}

#[derive(Clone, PartialEq, Debug)]
pub enum ProgramConn {
    /// `input := source`.
    Input { name: ExprId, value: ExprId },
    /// `output => sink`.
    Output { name: ExprId, target: ExprId },
    /// `fb_instance WITH task`.
    FbTask { fb: ExprId, task: Ident },
}

#[derive(Clone, PartialEq, Debug)]
// A file has a handful of items, each built once and never moved in a
// loop: boxing the POU would buy nothing.
#[allow(clippy::large_enum_variant)]
pub enum Item {
    Types(Vec<TypeDecl>, Span),
    Pou(Pou),
    Configuration(Configuration),
    /// A VAR_GLOBAL block outside any configuration (a global variable list
    /// as CODESYS-style projects write them).
    GlobalVars(VarBlock),
    /// `NAMESPACE [INTERNAL] A.B`: the items up to the matching
    /// [`Item::EndNamespace`] belong to the namespace (3rd edition; items
    /// stay flat so every pass that walks them needs no recursion, and the
    /// analyser gives each item its scope, see `stc_sema::namespaces`).
    Namespace(NamespaceDecl),
    /// `END_NAMESPACE` closing the innermost open namespace.
    EndNamespace(Span),
    /// `USING A.B, C;` between items: the namespaces named are searched for
    /// the names the following items of the same namespace (or, at the top
    /// level, of the same file) use.
    Using(UsingDecl),
}

impl Item {
    /// Where the item is written (for a namespace, its opening line).
    pub fn span(&self) -> Span {
        match self {
            Item::Types(_, span) | Item::EndNamespace(span) => *span,
            Item::Pou(p) => p.span,
            Item::Configuration(c) => c.span,
            Item::GlobalVars(b) => b.span,
            Item::Namespace(n) => n.span,
            Item::Using(u) => u.span,
        }
    }
}

/// The opening of a namespace.
#[derive(Clone, PartialEq, Debug)]
pub struct NamespaceDecl {
    /// As written: one name or a dotted path (`NAMESPACE A.B` opens B
    /// inside A).
    pub name: Ident,
    /// `NAMESPACE INTERNAL`.
    pub internal: bool,
    /// From `NAMESPACE` to the name.
    pub span: Span,
    pub pragmas: Vec<Span>,
}

/// A `USING` directive: the namespaces it names, each one name or a
/// dotted path as written.
#[derive(Clone, PartialEq, Debug)]
pub struct UsingDecl {
    pub names: Vec<Ident>,
    pub span: Span,
}

// ---------------------------------------------------------------------------
// Sequential Function Chart

/// A body written as a Sequential Function Chart (IEC 61131-3 2nd edition
/// 2.6, textual form): its steps, transitions and actions in source order.
#[derive(Clone, PartialEq, Debug)]
pub struct SfcBody {
    pub elements: Vec<SfcElement>,
    pub span: Span,
    /// How many of the POU's last variable blocks the parser made for the
    /// chart's state (never printed).
    pub generated_blocks: usize,
}

#[derive(Clone, PartialEq, Debug)]
pub enum SfcElement {
    Step(SfcStep),
    Transition(SfcTransition),
    Action(SfcAction),
}

/// `[INITIAL_]STEP name : associations END_STEP`.
#[derive(Clone, PartialEq, Debug)]
pub struct SfcStep {
    pub initial: bool,
    pub name: Ident,
    pub assocs: Vec<ActionAssoc>,
    pub span: Span,
}

/// `action(qualifier [, duration] [, indicator...]);` in a step.
#[derive(Clone, PartialEq, Debug)]
pub struct ActionAssoc {
    pub action: Ident,
    /// The qualifier as written (`None`: N).
    pub qualifier: Option<(Qualifier, Span)>,
    /// The duration of a timed qualifier (L, D, SD, DS, SL).
    pub duration: Option<ExprId>,
    pub indicators: Vec<Ident>,
    pub span: Span,
}

/// An action qualifier (2nd edition Table 45, with the 3rd edition's P0
/// and P1).
#[derive(Clone, Copy, PartialEq, Eq, Debug, Hash)]
pub enum Qualifier {
    N,
    R,
    S,
    L,
    D,
    P,
    P0,
    P1,
    SD,
    DS,
    SL,
}

impl Qualifier {
    pub const ALL: [Qualifier; 11] = [
        Qualifier::N,
        Qualifier::R,
        Qualifier::S,
        Qualifier::L,
        Qualifier::D,
        Qualifier::P,
        Qualifier::P0,
        Qualifier::P1,
        Qualifier::SD,
        Qualifier::DS,
        Qualifier::SL,
    ];

    pub fn name(self) -> &'static str {
        match self {
            Qualifier::N => "N",
            Qualifier::R => "R",
            Qualifier::S => "S",
            Qualifier::L => "L",
            Qualifier::D => "D",
            Qualifier::P => "P",
            Qualifier::P0 => "P0",
            Qualifier::P1 => "P1",
            Qualifier::SD => "SD",
            Qualifier::DS => "DS",
            Qualifier::SL => "SL",
        }
    }

    /// The qualifier spelled `word` (case-insensitive).
    pub fn from_word(word: &str) -> Option<Qualifier> {
        Qualifier::ALL
            .into_iter()
            .find(|q| q.name().eq_ignore_ascii_case(word))
    }

    /// The input of ACTION_CONTROL the qualifier drives (`S0` for S, as
    /// the standard names it).
    pub fn input(self) -> &'static str {
        match self {
            Qualifier::S => "S0",
            q => q.name(),
        }
    }

    /// Whether the qualifier takes a duration.
    pub fn timed(self) -> bool {
        matches!(
            self,
            Qualifier::L | Qualifier::D | Qualifier::SD | Qualifier::DS | Qualifier::SL
        )
    }
}

/// `TRANSITION [name] [(PRIORITY := n)] FROM steps TO steps condition
/// END_TRANSITION`.
#[derive(Clone, PartialEq, Debug)]
pub struct SfcTransition {
    pub name: Option<Ident>,
    pub priority: Option<ExprId>,
    pub from: Vec<Ident>,
    /// Whether FROM was written with parentheses (`FROM (a, b)`).
    pub from_parens: bool,
    pub to: Vec<Ident>,
    pub to_parens: bool,
    pub cond: TransitionCond,
    pub span: Span,
}

#[derive(Clone, PartialEq, Debug)]
pub enum TransitionCond {
    /// `:= expression;`
    Expr(ExprId),
    /// `: statements` that assign the condition to the transition's name.
    Body(Vec<Stmt>),
    /// `: IL instructions`: the current result at the end is the condition.
    Il(IlBody),
}

/// `ACTION name : statements END_ACTION`.
#[derive(Clone, PartialEq, Debug)]
pub struct SfcAction {
    pub name: Ident,
    pub body: Vec<Stmt>,
    /// The body in Instruction List (then `body` is empty).
    pub il: Option<IlBody>,
    pub span: Span,
}

// ---------------------------------------------------------------------------
// Instruction List

/// An Instruction List body (IEC 61131-3 2nd edition 3.2).
///
/// Every instruction keeps its surface form (for the printer and the dump)
/// and its meaning in terms of ST ([`IlSem`]), built by the parser over
/// [`ExprKind::IlCr`], the current result: `ADD x` means "CR := CR + x",
/// `ST x` "x := CR", `S x` "IF CR THEN x := TRUE". The analyser checks those
/// expressions and statements with the ST rules while it tracks the type of
/// the current result; the IR lowers them like ST, with the current result
/// in hidden temporaries. Only jumps are IL's own.
#[derive(Clone, PartialEq, Debug)]
pub struct IlBody {
    pub instrs: Vec<IlInstr>,
    pub span: Span,
}

#[derive(Clone, PartialEq, Debug)]
pub struct IlInstr {
    pub label: Option<Ident>,
    pub op: IlOp,
    pub span: Span,
    /// What the instruction does (unused inside a parenthesised sequence
    /// or a parameter's sequence, which are composed into one expression).
    pub sem: IlSem,
}

/// The surface form of one instruction.
#[derive(Clone, PartialEq, Debug)]
pub enum IlOp {
    /// A label alone on its line (or an empty instruction).
    None,
    /// `LD x`, `ADD 1`, `NOT`, `S1 inst`.
    Simple {
        op: IlOperator,
        op_span: Span,
        operand: Option<ExprId>,
    },
    /// `AND( x` ... `)`: the operator applied to the result of a nested
    /// sequence, which starts with the operand when there is one.
    Paren {
        op: IlOperator,
        op_span: Span,
        operand: Option<ExprId>,
        body: Vec<IlInstr>,
    },
    /// `MAX b, c`: a function called with the current result as its first
    /// argument.
    Call { name: Ident, operands: Vec<ExprId> },
    /// `F(a := 1, b := 2)`: a function called with formal parameters only.
    FormalCall { name: Ident, args: Vec<IlArg> },
    /// `CAL inst(...)`, `CALC inst`, `CALCN inst(x, y)`.
    Cal {
        op: IlCond,
        op_span: Span,
        callee: ExprId,
        args: Option<IlCallArgs>,
    },
    /// `JMP label`, `JMPC label`, `JMPCN label`.
    Jump {
        op: IlCond,
        op_span: Span,
        target: Ident,
    },
    /// `RET`, `RETC`, `RETCN`.
    Ret { op: IlCond, op_span: Span },
}

/// The modifier of JMP, CAL and RET: always, if the current result is
/// TRUE (`C`), if it is FALSE (`CN`).
#[derive(Clone, Copy, PartialEq, Eq, Debug, Hash)]
pub enum IlCond {
    Always,
    IfTrue,
    IfFalse,
}

impl IlCond {
    pub fn suffix(self) -> &'static str {
        match self {
            IlCond::Always => "",
            IlCond::IfTrue => "C",
            IlCond::IfFalse => "CN",
        }
    }
}

#[derive(Clone, PartialEq, Debug)]
pub enum IlCallArgs {
    /// `(IN := x, Q => y)`, each value an operand or a nested sequence.
    Formal(Vec<IlArg>),
    /// `(x, y)`: the inputs in order.
    Positional(Vec<ExprId>),
}

#[derive(Clone, PartialEq, Debug)]
pub struct IlArg {
    pub kind: IlArgKind,
    pub span: Span,
}

#[derive(Clone, PartialEq, Debug)]
pub enum IlArgKind {
    /// `name := operand` or `name := ( sequence )`.
    Input { name: Ident, value: IlArgValue },
    /// `name => target`, `NOT name => target`.
    Output {
        name: Ident,
        negated: bool,
        target: ExprId,
    },
}

#[derive(Clone, PartialEq, Debug)]
pub enum IlArgValue {
    Operand(ExprId),
    /// A nested sequence; `value` is its result composed into one expression.
    List {
        body: Vec<IlInstr>,
        value: ExprId,
    },
}

/// The IL operators that take at most one operand (Tables 51-53).
#[derive(Clone, Copy, PartialEq, Eq, Debug, Hash)]
pub enum IlOperator {
    Ld,
    Ldn,
    St,
    Stn,
    Not,
    S,
    R,
    And,
    Andn,
    Or,
    Orn,
    Xor,
    Xorn,
    Add,
    Sub,
    Mul,
    Div,
    Mod,
    Gt,
    Ge,
    Eq,
    Ne,
    Le,
    Lt,
    /// The input operators of the standard function blocks: set that
    /// input of the instance named by the operand to the current result.
    FbInput(IlFbInput),
}

#[derive(Clone, Copy, PartialEq, Eq, Debug, Hash)]
pub enum IlFbInput {
    S1,
    R1,
    Clk,
    Cu,
    Cd,
    Pv,
    In,
    Pt,
}

impl IlFbInput {
    pub const ALL: [IlFbInput; 8] = [
        IlFbInput::S1,
        IlFbInput::R1,
        IlFbInput::Clk,
        IlFbInput::Cu,
        IlFbInput::Cd,
        IlFbInput::Pv,
        IlFbInput::In,
        IlFbInput::Pt,
    ];

    pub fn name(self) -> &'static str {
        match self {
            IlFbInput::S1 => "S1",
            IlFbInput::R1 => "R1",
            IlFbInput::Clk => "CLK",
            IlFbInput::Cu => "CU",
            IlFbInput::Cd => "CD",
            IlFbInput::Pv => "PV",
            IlFbInput::In => "IN",
            IlFbInput::Pt => "PT",
        }
    }
}

impl IlOperator {
    pub const PLAIN: [IlOperator; 24] = [
        IlOperator::Ld,
        IlOperator::Ldn,
        IlOperator::St,
        IlOperator::Stn,
        IlOperator::Not,
        IlOperator::S,
        IlOperator::R,
        IlOperator::And,
        IlOperator::Andn,
        IlOperator::Or,
        IlOperator::Orn,
        IlOperator::Xor,
        IlOperator::Xorn,
        IlOperator::Add,
        IlOperator::Sub,
        IlOperator::Mul,
        IlOperator::Div,
        IlOperator::Mod,
        IlOperator::Gt,
        IlOperator::Ge,
        IlOperator::Eq,
        IlOperator::Ne,
        IlOperator::Le,
        IlOperator::Lt,
    ];

    pub fn name(self) -> &'static str {
        match self {
            IlOperator::Ld => "LD",
            IlOperator::Ldn => "LDN",
            IlOperator::St => "ST",
            IlOperator::Stn => "STN",
            IlOperator::Not => "NOT",
            IlOperator::S => "S",
            IlOperator::R => "R",
            IlOperator::And => "AND",
            IlOperator::Andn => "ANDN",
            IlOperator::Or => "OR",
            IlOperator::Orn => "ORN",
            IlOperator::Xor => "XOR",
            IlOperator::Xorn => "XORN",
            IlOperator::Add => "ADD",
            IlOperator::Sub => "SUB",
            IlOperator::Mul => "MUL",
            IlOperator::Div => "DIV",
            IlOperator::Mod => "MOD",
            IlOperator::Gt => "GT",
            IlOperator::Ge => "GE",
            IlOperator::Eq => "EQ",
            IlOperator::Ne => "NE",
            IlOperator::Le => "LE",
            IlOperator::Lt => "LT",
            IlOperator::FbInput(i) => i.name(),
        }
    }

    /// The operator a word names (case-insensitive), if any.
    pub fn from_word(w: &str) -> Option<IlOperator> {
        let all = IlOperator::PLAIN
            .into_iter()
            .chain(IlFbInput::ALL.into_iter().map(IlOperator::FbInput));
        all.into_iter().find(|o| o.name().eq_ignore_ascii_case(w))
    }

    /// The operators that take the `(` modifier (Table 52: the ones that
    /// combine the current result with an operand).
    pub fn takes_paren(self) -> bool {
        self.binary().is_some()
    }

    /// The ST operator of a combining operator, and whether the operand is
    /// negated (`ANDN`).
    pub fn binary(self) -> Option<(BinaryOp, bool)> {
        Some(match self {
            IlOperator::And => (BinaryOp::And, false),
            IlOperator::Andn => (BinaryOp::And, true),
            IlOperator::Or => (BinaryOp::Or, false),
            IlOperator::Orn => (BinaryOp::Or, true),
            IlOperator::Xor => (BinaryOp::Xor, false),
            IlOperator::Xorn => (BinaryOp::Xor, true),
            IlOperator::Add => (BinaryOp::Add, false),
            IlOperator::Sub => (BinaryOp::Sub, false),
            IlOperator::Mul => (BinaryOp::Mul, false),
            IlOperator::Div => (BinaryOp::Div, false),
            IlOperator::Mod => (BinaryOp::Mod, false),
            IlOperator::Gt => (BinaryOp::Gt, false),
            IlOperator::Ge => (BinaryOp::Ge, false),
            IlOperator::Eq => (BinaryOp::Eq, false),
            IlOperator::Ne => (BinaryOp::Ne, false),
            IlOperator::Le => (BinaryOp::Le, false),
            IlOperator::Lt => (BinaryOp::Lt, false),
            _ => return None,
        })
    }
}

/// What an instruction means, over the current result.
#[derive(Clone, PartialEq, Debug)]
pub enum IlSem {
    /// Nothing (a label alone).
    Nothing,
    /// The current result becomes this value (`LD`, `ADD`, a function call).
    Load(ExprId),
    /// Statements run with the current result as it is (`ST`, `S`, `R`,
    /// the FB input operators, `CAL`, `RET`); after them the current
    /// result keeps its value, except after a call (`undefined_after`).
    Effect {
        stmts: Vec<Stmt>,
        undefined_after: bool,
    },
    /// `S x` / `R x`: set or reset the BOOL `x` if the current result is
    /// TRUE (`bool_form`), or, when `x` names a function block instance,
    /// its input `S` or `R` to the current result (`fb_form`, as the input
    /// operators do); the analyser decides which from the type of `x`.
    SetReset {
        operand: ExprId,
        bool_form: Vec<Stmt>,
        fb_form: Vec<Stmt>,
    },
    /// A jump, if `cond` (the current result, or its negation) holds.
    Jump { cond: Option<ExprId>, target: Ident },
}
