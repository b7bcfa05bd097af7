//! The analyser's state and the order of its passes.
//!
//! 1. `decls::collect` registers every global name (types, POUs,
//!    configurations) so declarations may appear in any order and file.
//! 2. Types, POU variables and globals are resolved lazily, on first need,
//!    with an in-progress mark that turns a cycle into one diagnostic.
//! 3. POU bodies are checked statement by statement (`stmt`, `expr`,
//!    `calls`), recording types, resolutions, coercions and constants.
//! 4. Configurations, externals, recursion and the flow warnings last.

use rustc_hash::{FxHashMap, FxHashSet};
use stc_diagnostics::{Code, Diagnostic, SourceMap, Span};
use stc_syntax::ast::{Ast, ExprId, Item, TypeDecl, VarBlock, VarDecl};
use stc_syntax::{Interner, Symbol};
use stc_values::Value;

use crate::types::{InitValue, TypeId, TypeTable};
use crate::{
    Analysis, CallInfo, ConfigDef, GlobalDef, GlobalId, Options, PouDef, PouId, Res, VarId,
};

/// Where names are looked up while checking an expression.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
pub(crate) enum Scope {
    /// Inside a POU: its variables.
    Pou(PouId),
    /// TYPE declarations: global constants only.
    Global,
    /// A configuration (and one of its resources): its globals.
    Config(usize, Option<usize>),
}

/// A global name.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
pub(crate) enum GlobalName {
    Type(usize),
    Pou(PouId),
    Config(usize),
}

#[derive(Clone, Copy, PartialEq, Eq, Debug)]
pub(crate) enum State {
    Todo,
    InProgress,
    Done,
}

pub(crate) struct TypeDeclEntry<'a> {
    pub decl: &'a TypeDecl,
    /// Its name with its namespace (`Drives.Speed`), the type's name.
    pub name: stc_syntax::Symbol,
    pub state: State,
    pub ty: TypeId,
    pub init: Option<InitValue>,
}

/// Where a variable was declared, for lazy resolution.
#[derive(Clone, Copy)]
pub(crate) struct VarSource<'a> {
    pub block: &'a VarBlock,
    pub decl: &'a VarDecl,
}

/// Per-body state while statements are checked.
#[derive(Default, Clone)]
pub(crate) struct Body {
    pub loop_depth: u32,
    /// FOR control variables of the loops around the current statement.
    pub for_vars: Vec<VarId>,
    /// Constant propagation: values that local variables certainly hold at
    /// the current statement (seed 001 section 3.3).
    pub known: FxHashMap<VarId, Value>,
    /// In an Instruction List body: the type of the current result for the
    /// instruction being checked (`ExprKind::IlCr` has it).
    pub il_cr: Option<TypeId>,
    /// A chart error left part of the body out of its meaning (an unknown
    /// step, an undefined action): which variables it uses is not known.
    pub partial: bool,
    /// The POU whose body is being checked.
    pub current: Option<PouId>,
}

/// Declares [`Sema`] with its borrowed context and the owned fields given,
/// and [`Owned`]: those same fields, what a [`crate::Checkpoint`] keeps of
/// an analysis (every field written once, so none can be forgotten).
macro_rules! sema_state {
    ($($(#[$doc:meta])* $name:ident : $ty:ty,)*) => {
        pub(crate) struct Sema<'a> {
            pub ast: &'a Ast,
            pub interner: &'a mut Interner,
            pub sources: &'a SourceMap,
            pub prelude: Option<Span>,
            pub opts: Options,
            pub type_decls: Vec<TypeDeclEntry<'a>>,
            /// Declaration sources of each POU's variables (parallel to `vars`).
            pub pou_var_src: Vec<Vec<Option<VarSource<'a>>>>,
            pub global_src: Vec<VarSource<'a>>,
            $($(#[$doc])* pub $name: $ty,)*
        }

        /// The state of [`Sema`] that borrows nothing from the syntax tree.
        #[derive(Clone, Default)]
        pub(crate) struct Owned {
            $(pub $name: $ty,)*
        }

        impl<'a> Sema<'a> {
            /// An analyser in the state `o`, over `ctx`'s tree.
            pub(crate) fn from_parts(ctx: Ctx<'a>, o: Owned, refs: Refs<'a>) -> Sema<'a> {
                Sema {
                    ast: ctx.ast,
                    interner: ctx.interner,
                    sources: ctx.sources,
                    prelude: ctx.prelude,
                    opts: ctx.opts,
                    type_decls: refs.type_decls,
                    pou_var_src: refs.pou_var_src,
                    global_src: refs.global_src,
                    $($name: o.$name,)*
                }
            }

            /// A copy of the owned state.
            pub(crate) fn owned(&self) -> Owned {
                Owned {
                    $($name: self.$name.clone(),)*
                }
            }
        }
    };
}

/// What an analysis reads: the project's tree and its names.
pub(crate) struct Ctx<'a> {
    pub ast: &'a Ast,
    pub interner: &'a mut Interner,
    pub sources: &'a SourceMap,
    pub prelude: Option<Span>,
    pub opts: Options,
}

/// The analyser's references into the tree.
#[derive(Default)]
pub(crate) struct Refs<'a> {
    pub type_decls: Vec<TypeDeclEntry<'a>>,
    pub pou_var_src: Vec<Vec<Option<VarSource<'a>>>>,
    pub global_src: Vec<VarSource<'a>>,
}

sema_state! {
    /// Inside the constant of a declared type (an array bound, a string
    /// length, a subrange limit): a top-level VAR_GLOBAL CONSTANT may be
    /// named there without VAR_EXTERNAL (see `const_int`).
    in_type_constant: bool,
    types: TypeTable,
    names: FxHashMap<Symbol, GlobalName>,
    pous: Vec<PouDef>,
    pou_var_state: Vec<Vec<State>>,
    pou_state: Vec<State>,
    fb_types: FxHashMap<PouId, TypeId>,
    globals: Vec<GlobalDef>,
    global_state: Vec<State>,
    /// Top-level VAR_GLOBAL lists.
    top_globals: Vec<GlobalId>,
    configs: Vec<ConfigDef>,
    expr_types: Vec<TypeId>,
    coercions: FxHashMap<ExprId, TypeId>,
    /// The arithmetic expressions on bit strings (W0113) with the index of
    /// the warning that covers each: a tree of them is reported once, at
    /// its outermost operation (the inner warnings are dropped, `dropped`).
    bit_arith: FxHashMap<ExprId, usize>,
    dropped: FxHashSet<usize>,
    /// The globals read without VAR_EXTERNAL (W0114), per POU.
    implicit_globals: FxHashSet<(PouId, stc_syntax::Symbol)>,
    resolutions: FxHashMap<ExprId, Res>,
    consts: FxHashMap<ExprId, Value>,
    calls: FxHashMap<ExprId, CallInfo>,
    diags: Vec<Diagnostic>,
    body: Body,
    /// Variables referenced anywhere (bodies and declarations).
    used: FxHashSet<(PouId, VarId)>,
    /// Every enumeration value by name: its type, index, and the POU of a
    /// local anonymous enumeration.
    enum_index: FxHashMap<Symbol, Vec<(TypeId, u32, Option<PouId>)>>,
    /// Calls between POUs, for the recursion check: (caller, callee, span).
    call_edges: Vec<(PouId, PouId, Span)>,
    /// The blocks some block EXTENDS (known before any body is checked).
    bases: FxHashSet<PouId>,
    /// Names of all global variables (for W0109).
    global_names: FxHashSet<Symbol>,
    /// The inner index expression of `a[i][j]`, which may index partially.
    partial_index_ok: Option<ExprId>,
    /// Names declared by constructs reported as not supported (an
    /// INTERFACE...): uses of them are not reported again.
    unsupported_names: FxHashSet<Symbol>,
    /// The names of the variables some `REF(...)` of the project refers to
    /// (at the root of its argument): their values are never propagated,
    /// since a write through a reference may change them anywhere.
    ref_taken: FxHashSet<Symbol>,
    /// `REF_TO T` met inside the declaration of the named type `T` (by
    /// index in `type_decls`): the reference type, completed when `T` is.
    pending_refs: FxHashMap<(usize, bool), TypeId>,
    /// Operands of IL `S`/`R` that name function block instances (the
    /// instruction sets that instance's input).
    il_fb_inputs: FxHashSet<ExprId>,
    /// The element types of the objects `ADR` points into, in the order
    /// first met (a pointer's object kind is its index, from 1).
    ptr_kinds: Vec<TypeId>,
    /// `ADR` calls of variables that live only during a call.
    short_adrs: FxHashSet<ExprId>,
    /// `0` and `NULL` standing for the null pointer.
    null_ptrs: FxHashSet<ExprId>,
    /// VAR_STAT variables: (POU, name) to the global that holds them.
    statics: FxHashMap<(PouId, Symbol), GlobalId>,
    /// VAR_INST variables: (function block, method name, name) to the
    /// block's variable that holds them.
    inst_vars: FxHashMap<(PouId, Symbol, Symbol), VarId>,
    /// `p^` of a pointer to an array not indexed with every dimension.
    whole_ptr_arrays: Vec<stc_diagnostics::Span>,
    /// The type of the current result at the end of an IL body of a
    /// chart's transition, by the place it is stored in.
    il_results: FxHashMap<ExprId, TypeId>,
    /// The project's namespaces and each item's scope.
    ns: crate::namespaces::Namespaces,
    /// Every name declared at the global level, in the order met (types,
    /// POUs, configurations, global variables, enumeration values): what
    /// a [`crate::Checkpoint`] compares with the names its part uses.
    declared: Vec<Symbol>,
}

impl<'a> Sema<'a> {
    pub fn new(
        ast: &'a Ast,
        interner: &'a mut Interner,
        sources: &'a SourceMap,
        prelude: Option<Span>,
        opts: Options,
    ) -> Sema<'a> {
        let ctx = Ctx {
            ast,
            interner,
            sources,
            prelude,
            opts,
        };
        Sema::upto(ctx, ast.exprs.len(), ast.unsupported_names.len())
    }

    /// An analyser of the part of the tree before `exprs` expressions and
    /// `unsupported` unsupported names.
    pub(crate) fn upto(ctx: Ctx<'a>, exprs: usize, unsupported: usize) -> Sema<'a> {
        let ast = ctx.ast;
        let o = Owned {
            expr_types: vec![TypeId::ERROR; exprs],
            unsupported_names: ast.unsupported_names[..unsupported]
                .iter()
                .map(|n| n.sym)
                .collect(),
            ref_taken: ref_taken_names(ast, 0..exprs, ctx.interner),
            ..Owned::default()
        };
        Sema::from_parts(ctx, o, Refs::default())
    }

    /// The items in the order they are analysed: the user's in order, then
    /// the prelude's (so a declaration of the user's comes first wherever
    /// the prelude sits in the tree).
    pub(crate) fn analysis_order(&self, items: std::ops::Range<usize>) -> Vec<usize> {
        let (mut user, mut std): (Vec<usize>, Vec<usize>) =
            items.partition(|&i| !self.in_prelude(self.ast.items[i].span()));
        user.append(&mut std);
        user
    }

    pub fn run(mut self) -> Analysis {
        let order = self.analysis_order(0..self.ast.items.len());
        self.analyse_items(&order);
        self.finish()
    }

    /// Declares the items (indices into the tree) and checks them: names,
    /// types, POU variables, globals, configurations, classes, bodies.
    /// Called once for a whole project, or once per part of it (a
    /// [`crate::Checkpoint`]), in order.
    pub(crate) fn analyse_items(&mut self, items: &[usize]) {
        let first_pou = self.pous.len();
        let first_type = self.type_decls.len();
        let first_global = self.globals.len();
        self.collect(items);
        self.link_classes(first_pou);
        for i in first_type..self.type_decls.len() {
            self.resolve_type_decl(i);
        }
        for p in first_pou..self.pous.len() {
            self.resolve_pou(PouId(p as u32));
        }
        for g in first_global..self.globals.len() {
            self.resolve_global(GlobalId(g as u32));
        }
        self.collect_configs(items);
        self.check_classes(first_pou);
        self.bases = self.pous.iter().filter_map(|d| d.base).collect();
        self.global_names = self.globals.iter().map(|g| g.var.name).collect();
        // A function block's methods before its own body, so that what
        // they use of the instance is known to its warnings.
        for id in first_pou..self.pous.len() {
            let id = PouId(id as u32);
            if self.pous[id.0 as usize].method_of.is_some() {
                continue;
            }
            for m in self.pous[id.0 as usize].methods.clone() {
                if let Some(src) = self.pou_ast(m) {
                    self.check_body(m, src);
                }
            }
            if let Some(p) = self.pou_ast(id) {
                self.check_body(id, p);
            }
        }
    }

    /// The checks of the whole project, after every item: externals,
    /// recursion, pointers; then the result.
    pub(crate) fn finish(mut self) -> Analysis {
        self.check_externals();
        self.check_recursion();
        if let Some(prelude) = self.prelude {
            // The prelude is the standard library: its warnings are not the
            // user's business (its errors would be a bug, and stay visible).
            self.diags
                .retain(|d| d.is_error() || !(prelude.lo <= d.span.lo && d.span.lo < prelude.hi));
        }
        let ptrs = self.finish_pointers();
        let mut implicit_used = FxHashSet::default();
        for (pi, pou) in self.pous.iter().enumerate() {
            for (vi, v) in pou.vars.iter().enumerate() {
                let key = (PouId(pi as u32), VarId(vi as u32));
                if v.implicit && self.used.contains(&key) {
                    implicit_used.insert(key);
                }
            }
        }
        Analysis {
            implicit_used,
            il_fb_inputs: self.il_fb_inputs,
            ptr_kinds: self.ptr_kinds,
            null_ptrs: self.null_ptrs,
            ptrs,
            il_results: self.il_results,
            types: self.types,
            pous: self.pous,
            globals: self.globals,
            configs: self.configs,
            expr_types: self.expr_types,
            coercions: self.coercions,
            resolutions: self.resolutions,
            consts: self.consts,
            calls: self.calls,
            diagnostics: self
                .diags
                .into_iter()
                .enumerate()
                .filter(|(i, _)| !self.dropped.contains(i))
                .map(|(_, d)| d)
                .collect(),
        }
    }

    // ----- diagnostics ----------------------------------------------------

    pub fn emit(&mut self, d: Diagnostic) {
        self.diags.push(d);
    }

    pub fn error(&mut self, code: Code, span: Span, msg: impl Into<String>) {
        self.diags.push(Diagnostic::new(code, span, msg));
    }

    pub fn in_prelude(&self, span: Span) -> bool {
        self.prelude
            .is_some_and(|p| p.lo <= span.lo && span.lo < p.hi)
    }

    /// A name as the user spelled it at `span` (or its first spelling).
    pub fn spelled(&self, sym: Symbol, span: Span) -> String {
        let s = self.sources.slice(span);
        if !s.is_empty() && s.eq_ignore_ascii_case(self.interner.key(sym)) {
            s.to_string()
        } else {
            self.interner.spelling(sym).to_string()
        }
    }

    pub fn sym_name(&self, sym: Symbol) -> String {
        self.interner.spelling(sym).to_string()
    }

    pub fn tname(&self, t: TypeId) -> String {
        self.types.display(t, self.interner)
    }

    pub fn intern(&mut self, s: &str) -> Symbol {
        self.interner.intern(s)
    }

    /// "did you mean `x`?" among candidate names.
    pub fn did_you_mean<'s>(
        &self,
        name: &str,
        candidates: impl Iterator<Item = &'s str>,
    ) -> Option<String> {
        let name_u = name.to_ascii_uppercase();
        let limit = (name.len() / 3).max(1);
        let mut best: Option<(usize, &str)> = None;
        // A name that abbreviates or spells out one candidate (`RESET` for
        // `R`, `PRESET` for `PV`'s `P`...): the only candidate it starts
        // with, or that starts with it.
        let mut affix: Vec<&str> = Vec::new();
        for c in candidates {
            let c_u = c.to_ascii_uppercase();
            let d = edit_distance(&name_u, &c_u);
            if d <= limit && d > 0 && best.is_none_or(|(bd, _)| d < bd) {
                best = Some((d, c));
            }
            if d > 0 && !c_u.is_empty() && (name_u.starts_with(&c_u) || c_u.starts_with(&name_u)) {
                affix.push(c);
            }
        }
        best.map(|(_, c)| c.to_string())
            .or_else(|| (affix.len() == 1).then(|| affix[0].to_string()))
    }

    /// The syntax of a POU.
    pub fn pou_ast(&self, p: PouId) -> Option<&'a stc_syntax::ast::Pou> {
        let def = self.pous.get(p.0 as usize)?;
        if let Some((owner, k)) = def.method_of {
            return self.pou_ast(owner)?.methods.get(k).map(|m| &m.pou);
        }
        match self.ast.items.get(def.item)? {
            Item::Pou(pou) => Some(pou),
            _ => None,
        }
    }

    /// Whether the members of a POU are not all known because a part of it
    /// was reported as not supported: an EXTENDS (inherited members), or a
    /// skipped ACTION, METHOD or PROPERTY of that name. Unknown names there
    /// are not reported again.
    pub fn member_may_be_unsupported(&self, p: PouId, name: Symbol) -> bool {
        // (In a METHOD: what its function block may inherit.)
        let p = self.pous[p.0 as usize].method_of.map_or(p, |(fb, _)| fb);
        self.pou_ast(p)
            .is_some_and(|_| self.is_skipped_member(p, name))
    }

    /// Whether a POU declared an ACTION, METHOD or PROPERTY of this name,
    /// skipped after its E0030.
    pub fn is_skipped_member(&self, p: PouId, name: Symbol) -> bool {
        self.pou_ast(p)
            .is_some_and(|a| a.skipped_members.iter().any(|m| m.sym == name))
    }

    pub fn set_type(&mut self, e: ExprId, t: TypeId) {
        if let Some(slot) = self.expr_types.get_mut(e.index()) {
            *slot = t;
        }
    }
}

/// Levenshtein distance (names are short).
fn edit_distance(a: &str, b: &str) -> usize {
    let b: Vec<char> = b.chars().collect();
    let mut prev: Vec<usize> = (0..=b.len()).collect();
    for (i, ca) in a.chars().enumerate() {
        let mut cur = vec![i + 1; b.len() + 1];
        for (j, &cb) in b.iter().enumerate() {
            let cost = usize::from(ca != cb);
            cur[j + 1] = (prev[j] + cost).min(prev[j + 1] + 1).min(cur[j] + 1);
        }
        prev = cur;
    }
    prev[b.len()]
}

/// The names at the root of every `REF(...)` argument among the
/// expressions `exprs`.
pub(crate) fn ref_taken_names(
    ast: &Ast,
    exprs: std::ops::Range<usize>,
    interner: &Interner,
) -> FxHashSet<Symbol> {
    use stc_syntax::ast::ExprKind;
    let mut out = FxHashSet::default();
    for e in &ast.exprs[exprs] {
        let ExprKind::Call { callee, args } = &e.kind else {
            continue;
        };
        let ExprKind::Name(id) = &ast.expr(*callee).kind else {
            continue;
        };
        if !matches!(interner.key(id.sym), "REF" | "ADR") {
            continue;
        }
        for a in args.iter() {
            let mut x = match &a.kind {
                stc_syntax::ast::ArgKind::Positional(v)
                | stc_syntax::ast::ArgKind::Input { value: v, .. } => *v,
                stc_syntax::ast::ArgKind::Output { target, .. } => *target,
            };
            loop {
                match &ast.expr(x).kind {
                    ExprKind::Paren(b) | ExprKind::Member { base: b, .. } => x = *b,
                    ExprKind::Index { base, .. } | ExprKind::PartialAccess { base, .. } => {
                        x = *base
                    }
                    ExprKind::Name(n) => {
                        out.insert(n.sym);
                        break;
                    }
                    _ => break,
                }
            }
        }
    }
    out
}
