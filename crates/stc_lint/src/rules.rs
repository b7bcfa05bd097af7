//! The rules, one function each. Each walks the user's POUs (never the
//! prelude's) and returns its findings as warnings; `check` then applies
//! the levels.

use rustc_hash::{FxHashMap, FxHashSet};
use stc_diagnostics::{Code, Diagnostic, Span};
use stc_sema::{PouDef, PouId, Res, Section, TypeKind, VarId};
use stc_syntax::ast::{
    ArgKind, BinaryOp, ClassKind, ExprId, ExprKind, LitValue, Pou, PouKind, Stmt, StmtKind,
    VarBlockItems,
};
use stc_syntax::lexer::{lex, TriviaKind};
use stc_syntax::token::ElemType;

use crate::walk;
use crate::{Input, Level, Levels};

/// A user POU with its syntax.
struct Unit<'a> {
    id: PouId,
    def: &'a PouDef,
    syn: &'a Pou,
}

pub fn run(input: &Input<'_>, levels: &Levels, within: &std::ops::Range<u32>) -> Vec<Diagnostic> {
    let on = |c: Code| levels.get(c) != Level::Allow;
    let units = units(input);
    let shared = Shared::new(input, &units);
    let mut out = Vec::new();
    for u in units.iter().filter(|u| within.contains(&u.syn.span.lo)) {
        if on(Code::L0001) || on(Code::L0002) || on(Code::L0007) {
            expression_rules(input, u, levels, &mut out);
        }
        if on(Code::L0003) {
            output_before_call(input, u, &mut out);
        }
        if on(Code::L0004) {
            shadowed_global(input, &shared, u, &mut out);
        }
        if on(Code::L0005) {
            unused_input(input, &shared, u, &units, &mut out);
        }
        if on(Code::L0006) {
            case_without_else(input, u, &mut out);
        }
        if on(Code::L0009) {
            assigned_on_some_paths(input, u, &mut out);
        }
    }
    if on(Code::L0008) {
        nested_comments(input, within, &mut out);
    }
    out
}

/// What several rules ask about the whole project, computed once.
struct Shared {
    /// The global variables by name (the first of a name).
    globals: FxHashMap<stc_syntax::Symbol, Span>,
    /// Where W0109 (a local name hides a global one) was reported.
    w0109: FxHashSet<Span>,
    /// The blocks some block EXTENDS.
    extended: FxHashSet<PouId>,
    /// For each function block, its methods (indices into the units).
    methods: FxHashMap<PouId, Vec<usize>>,
}

impl Shared {
    fn new(input: &Input<'_>, units: &[Unit<'_>]) -> Shared {
        let a = input.analysis;
        let mut globals = FxHashMap::default();
        for g in &a.globals {
            globals.entry(g.var.name).or_insert(g.var.span);
        }
        let mut methods: FxHashMap<PouId, Vec<usize>> = FxHashMap::default();
        for (i, u) in units.iter().enumerate() {
            if let Some((owner, _)) = u.def.method_of {
                methods.entry(owner).or_default().push(i);
            }
        }
        Shared {
            globals,
            w0109: input
                .diagnostics
                .iter()
                .filter(|d| d.code == Code::W0109)
                .map(|d| d.span)
                .collect(),
            extended: a.pous.iter().filter_map(|p| p.base).collect(),
            methods,
        }
    }
}

/// The user's POUs (methods included) that have a body to lint: not the
/// prelude's, not INTERFACEs and their prototypes.
fn units<'a>(input: &Input<'a>) -> Vec<Unit<'a>> {
    let a = input.analysis;
    let interface = |p: PouId| {
        a.pous
            .get(p.0 as usize)
            .is_some_and(|d| d.class == Some(ClassKind::Interface))
    };
    let mut out = Vec::new();
    for (i, def) in a.pous.iter().enumerate() {
        let id = PouId(i as u32);
        if def.is_std || interface(id) || def.method_of.is_some_and(|(o, _)| interface(o)) {
            continue;
        }
        let Some(syn) = a.pou_syntax(input.ast, id) else {
            continue;
        };
        if input.prelude.lo <= syn.span.lo && syn.span.lo < input.prelude.hi.max(1) {
            continue;
        }
        out.push(Unit { id, def, syn });
    }
    out
}

fn name<'a>(input: &Input<'a>, s: stc_syntax::Symbol) -> &'a str {
    input.interner.spelling(s)
}

fn var_name<'a>(input: &Input<'a>, def: &PouDef, v: VarId) -> &'a str {
    def.vars
        .get(v.0 as usize)
        .map_or("?", |var| name(input, var.name))
}

/// L0001 (literals other than 0 and 1), L0002 (direct addresses) and L0007
/// (REAL compared with `=` or `<>`): one look at every expression.
fn expression_rules(input: &Input<'_>, u: &Unit<'_>, levels: &Levels, out: &mut Vec<Diagnostic>) {
    let a = input.analysis;
    let ast = input.ast;
    let magic = levels.get(Code::L0001) != Level::Allow && u.syn.sfc.is_none();
    let direct = levels.get(Code::L0002) != Level::Allow;
    let real_eq = levels.get(Code::L0007) != Level::Allow;
    let is_real = |e: ExprId| {
        matches!(
            a.types.scalar(a.final_type(e)),
            Some(ElemType::Real | ElemType::Lreal)
        )
    };
    walk::body_exprs(
        ast,
        u.syn,
        &mut |e| {
            let Some(expr) = ast.exprs.get(e.index()) else {
                return;
            };
            match &expr.kind {
                ExprKind::Literal(l) if magic => {
                    let plain = match l.value {
                        LitValue::Int { value, .. } => value <= 1,
                        LitValue::Real(r) => r == 0.0 || r == 1.0,
                        _ => true,
                    };
                    if !plain {
                        let text = input.sources.slice(expr.span);
                        out.push(
                            Diagnostic::new(
                                Code::L0001,
                                expr.span,
                                format!("the literal `{text}` in logic"),
                            )
                            .with_label("a magic number")
                            .with_help(
                                "declare it as a named constant (VAR CONSTANT) and use the name",
                            ),
                        );
                    }
                }
                ExprKind::Address(_) if direct => {
                    let text = input.sources.slice(expr.span);
                    out.push(
                        Diagnostic::new(
                            Code::L0002,
                            expr.span,
                            format!("the direct address `{text}` used in a body"),
                        )
                        .with_label("a direct address")
                        .with_help(
                            "declare a named variable for it (`name AT %IX0.0 : BOOL;`) and use the name",
                        ),
                    );
                }
                ExprKind::Binary {
                    op: op @ (BinaryOp::Eq | BinaryOp::Ne),
                    lhs,
                    rhs,
                } if real_eq
                    && (is_real(*lhs) || is_real(*rhs))
                    && a.expr_type(*lhs) != stc_sema::TypeId::ERROR
                    && a.expr_type(*rhs) != stc_sema::TypeId::ERROR =>
                {
                    out.push(
                        Diagnostic::new(
                            Code::L0007,
                            expr.span,
                            format!("REAL values compared with `{}`", op.symbol()),
                        )
                        .with_label("exact comparison of floating-point values")
                        .with_help("compare the difference with a tolerance: `ABS(a - b) < eps`"),
                    );
                }
                _ => {}
            }
        },
        &mut |_| {},
    );
}

/// The local function block instance a call statement calls, if any.
fn called_instance(input: &Input<'_>, u: &Unit<'_>, e: ExprId) -> Option<VarId> {
    let a = input.analysis;
    let info = a.calls.get(&e)?;
    if !matches!(info.target, stc_sema::CallTarget::FbInstance(_)) {
        return None;
    }
    let ExprKind::Call { callee, .. } = &input.ast.exprs.get(e.index())?.kind else {
        return None;
    };
    match a.resolutions.get(callee) {
        Some(Res::Var(v)) if is_own_instance(input, u, *v) => Some(*v),
        _ => None,
    }
}

/// Whether variable `v` is an instance the POU owns (VAR or VAR_TEMP).
fn is_own_instance(input: &Input<'_>, u: &Unit<'_>, v: VarId) -> bool {
    u.def.vars.get(v.0 as usize).is_some_and(|var| {
        matches!(var.section, Section::Var | Section::Temp)
            && matches!(input.analysis.types.kind(var.ty), TypeKind::Fb(_))
    })
}

/// L0003: `inst.out` read before the body calls `inst` (in source order).
fn output_before_call(input: &Input<'_>, u: &Unit<'_>, out: &mut Vec<Diagnostic>) {
    if u.syn.il.is_some() || u.syn.sfc.is_some() {
        return;
    }
    // The instances the body calls somewhere, with their first call.
    let mut first_call: FxHashMap<VarId, Span> = FxHashMap::default();
    walk::statements(&u.syn.body, &mut |s| {
        if let StmtKind::Call(e) = &s.kind {
            if let Some(v) = called_instance(input, u, *e) {
                first_call.entry(v).or_insert(s.span);
            }
        }
    });
    if first_call.is_empty() {
        return;
    }
    let mut called = FxHashSet::default();
    let mut reported = FxHashSet::default();
    in_order(
        input,
        u,
        &u.syn.body,
        &first_call,
        &mut called,
        &mut reported,
        out,
    );
}

#[allow(clippy::too_many_arguments)]
fn in_order(
    input: &Input<'_>,
    u: &Unit<'_>,
    list: &[Stmt],
    first_call: &FxHashMap<VarId, Span>,
    called: &mut FxHashSet<VarId>,
    reported: &mut FxHashSet<VarId>,
    out: &mut Vec<Diagnostic>,
) {
    let a = input.analysis;
    let ast = input.ast;
    let reads = |root: ExprId,
                 skip: Option<VarId>,
                 called: &FxHashSet<VarId>,
                 reported: &mut FxHashSet<VarId>,
                 out: &mut Vec<Diagnostic>| {
        walk::expr_tree(ast, root, &mut |e| {
            let Some(ExprKind::Member { base, member }) = ast.exprs.get(e.index()).map(|x| &x.kind)
            else {
                return;
            };
            let Some(Res::Var(v)) = a.resolutions.get(base) else {
                return;
            };
            let v = *v;
            if Some(v) == skip || called.contains(&v) || reported.contains(&v) {
                return;
            }
            let Some(call) = first_call.get(&v) else {
                return;
            };
            let Some(var) = u.def.vars.get(v.0 as usize) else {
                return;
            };
            let TypeKind::Fb(fb) = a.types.kind(var.ty) else {
                return;
            };
            let Some(fbdef) = a.pous.get(fb.0 as usize) else {
                return;
            };
            let is_output = fbdef
                .lookup(member.sym)
                .and_then(|m| fbdef.vars.get(m.0 as usize))
                .is_some_and(|m| m.section == Section::Output);
            if !is_output {
                return;
            }
            reported.insert(v);
            let inst = name(input, var.name);
            let span = ast.exprs.get(e.index()).map_or(member.span, |x| x.span);
            out.push(
                Diagnostic::new(
                    Code::L0003,
                    span,
                    format!(
                        "the output `{inst}.{}` is read before `{inst}` is called",
                        name(input, member.sym)
                    ),
                )
                .with_label("the value of the previous call (or the initial value)")
                .with_secondary(*call, "the instance is called here, later")
                .with_help("call the instance before reading its outputs"),
            );
        });
    };
    for s in list {
        match &s.kind {
            StmtKind::Call(e) => match called_instance(input, u, *e) {
                Some(v) => {
                    // The arguments are evaluated before the call; a read of
                    // the instance's own output among them (`t(IN := NOT
                    // t.Q)`) is the feedback idiom, not reported.
                    if let Some(ExprKind::Call { args, .. }) =
                        ast.exprs.get(e.index()).map(|x| &x.kind)
                    {
                        for arg in args.iter() {
                            let r = match &arg.kind {
                                ArgKind::Positional(x) | ArgKind::Input { value: x, .. } => *x,
                                ArgKind::Output { target, .. } => *target,
                            };
                            reads(r, Some(v), called, reported, out);
                        }
                    }
                    called.insert(v);
                }
                None => reads(*e, None, called, reported, out),
            },
            StmtKind::If {
                branches,
                else_body,
            } => {
                for b in branches {
                    reads(b.cond, None, called, reported, out);
                    in_order(input, u, &b.body, first_call, called, reported, out);
                }
                if let Some(e) = else_body {
                    in_order(input, u, e, first_call, called, reported, out);
                }
            }
            StmtKind::Repeat { body, until } => {
                in_order(input, u, body, first_call, called, reported, out);
                reads(*until, None, called, reported, out);
            }
            _ => {
                walk::own_exprs(
                    s,
                    &mut |e| reads(e, None, called, reported, out),
                    &mut |_| {},
                );
                for l in walk::nested(s) {
                    in_order(input, u, l, first_call, called, reported, out);
                }
            }
        }
    }
}

/// L0004: a variable of a POU named like a global variable.
fn shadowed_global(input: &Input<'_>, shared: &Shared, u: &Unit<'_>, out: &mut Vec<Diagnostic>) {
    let globals = &shared.globals;
    if globals.is_empty() {
        return;
    }
    let said = |span: Span| shared.w0109.contains(&span);
    for (i, var) in u.def.vars.iter().enumerate() {
        let v = VarId(i as u32);
        if var.implicit || u.def.hidden_var(v) || (i as u32) < u.def.inherited {
            continue;
        }
        if !matches!(
            var.section,
            Section::Input | Section::Output | Section::InOut | Section::Var | Section::Temp
        ) {
            continue;
        }
        let Some(&global) = globals.get(&var.name) else {
            continue;
        };
        if said(var.span) || global == var.span {
            continue;
        }
        let n = name(input, var.name);
        out.push(
            Diagnostic::new(
                Code::L0004,
                var.span,
                format!("`{n}` hides the global variable `{n}`"),
            )
            .with_label("this local variable")
            .with_secondary(global, "the global variable it hides")
            .with_help("rename the local variable"),
        );
    }
}

/// L0005: a VAR_INPUT of a FUNCTION, FUNCTION_BLOCK or PROGRAM that its
/// body (and, for a block, its methods) never refers to.
fn unused_input(
    input: &Input<'_>,
    shared: &Shared,
    u: &Unit<'_>,
    units: &[Unit<'_>],
    out: &mut Vec<Diagnostic>,
) {
    let a = input.analysis;
    if u.def.method_of.is_some() || u.syn.partial || u.syn.is_abstract || u.def.class.is_some() {
        return;
    }
    // A block some other block extends may leave its inputs to them.
    if shared.extended.contains(&u.id) {
        return;
    }
    let inputs: Vec<VarId> = u
        .def
        .vars
        .iter()
        .enumerate()
        .filter(|(i, var)| {
            var.section == Section::Input
                && !var.implicit
                && (*i as u32) >= u.def.inherited
                && Some(VarId(*i as u32)) != u.def.en
        })
        .map(|(i, _)| VarId(i as u32))
        .collect();
    if inputs.is_empty() {
        return;
    }
    // Only names refer to variables: the others need no look-up.
    let is_name = |e: ExprId| {
        matches!(
            input.ast.exprs.get(e.index()).map(|x| &x.kind),
            Some(ExprKind::Name(_))
        )
    };
    let mut exprs: Vec<(ExprId, bool)> = Vec::new();
    walk::body_exprs(
        input.ast,
        u.syn,
        &mut |e| {
            if is_name(e) {
                exprs.push((e, true))
            }
        },
        &mut |_| {},
    );
    for m in shared
        .methods
        .get(&u.id)
        .into_iter()
        .flatten()
        .filter_map(|&i| units.get(i))
    {
        walk::body_exprs(
            input.ast,
            m.syn,
            &mut |e| {
                if is_name(e) {
                    exprs.push((e, false))
                }
            },
            &mut |_| {},
        );
    }
    let mut used: FxHashSet<VarId> = FxHashSet::default();
    for (e, own) in exprs {
        match a.resolutions.get(&e) {
            Some(Res::Var(v)) if own => {
                used.insert(*v);
            }
            Some(Res::FbMember(p, v)) if *p == u.id => {
                used.insert(*v);
            }
            _ => {}
        }
    }
    for v in inputs {
        if used.contains(&v) {
            continue;
        }
        let Some(var) = u.def.vars.get(v.0 as usize) else {
            continue;
        };
        if var.ty == stc_sema::TypeId::ERROR {
            continue;
        }
        out.push(
            Diagnostic::new(
                Code::L0005,
                var.span,
                format!("the input `{}` is never used", var_name(input, u.def, v)),
            )
            .with_label("declared but never read")
            .with_help("remove the input, or use it"),
        );
    }
}

/// L0006: a CASE statement without ELSE.
fn case_without_else(input: &Input<'_>, u: &Unit<'_>, out: &mut Vec<Diagnostic>) {
    walk::body_statements(u.syn, &mut |s| {
        if let StmtKind::Case {
            selector,
            else_body: None,
            ..
        } = &s.kind
        {
            let hi = input
                .ast
                .exprs
                .get(selector.index())
                .map_or(s.span.hi, |e| e.span.hi);
            out.push(
                Diagnostic::new(Code::L0006, Span::new(s.span.lo, hi), "CASE without ELSE")
                    .with_label("no branch for the other values")
                    .with_help(
                        "add an ELSE branch that handles (or reports) the values no label names",
                    ),
            );
        }
    });
}

/// L0008: a `(*` comment inside another.
fn nested_comments(input: &Input<'_>, within: &std::ops::Range<u32>, out: &mut Vec<Diagnostic>) {
    for (_, f) in input.sources.files() {
        let span = f.span();
        if (span.lo == input.prelude.lo && span.hi == input.prelude.hi)
            || !within.contains(&span.lo)
        {
            continue;
        }
        if !may_nest(&f.text) {
            continue;
        }
        let lexed = lex(&f.text, f.base);
        for t in lexed
            .trivia
            .iter()
            .filter(|t| t.kind == TriviaKind::Comment)
        {
            let lo = (t.span.lo - f.base) as usize;
            let hi = (t.span.hi - f.base) as usize;
            let Some(text) = f.text.get(lo..hi) else {
                continue;
            };
            if !text.starts_with("(*") || text.len() < 4 {
                continue;
            }
            let inner = text.get(2..text.len() - 2).unwrap_or("");
            let Some(at) = inner.find("(*") else {
                continue;
            };
            let reported = input
                .diagnostics
                .iter()
                .any(|d| d.code == Code::W0003 && d.span.lo >= t.span.lo && d.span.lo < t.span.hi);
            if reported {
                continue;
            }
            let start = t.span.lo + 2 + at as u32;
            out.push(
                Diagnostic::new(
                    Code::L0008,
                    Span::new(start, start + 2),
                    "a comment inside a comment",
                )
                .with_label("a nested comment starts here")
                .with_secondary(Span::new(t.span.lo, t.span.lo + 2), "inside this comment")
                .with_help("close the outer comment first, or use `//` line comments"),
            );
        }
    }
}

/// L0009: a temporary variable (VAR_TEMP, or a FUNCTION's VAR, initialised
/// again at every call) assigned in an IF without ELSE and read after it
/// before any assignment on every path.
fn assigned_on_some_paths(input: &Input<'_>, u: &Unit<'_>, out: &mut Vec<Diagnostic>) {
    if u.syn.il.is_some() || u.syn.sfc.is_some() {
        return;
    }
    // The temporaries without an initial value of their own.
    let mut with_init: FxHashSet<Span> = FxHashSet::default();
    for b in &u.syn.var_blocks {
        if let VarBlockItems::Vars(vs) = &b.items {
            for d in vs.iter().filter(|d| d.init.is_some()) {
                with_init.extend(d.names.iter().map(|n| n.span));
            }
        }
    }
    let temps: FxHashSet<VarId> = u
        .def
        .vars
        .iter()
        .enumerate()
        .filter(|(_, v)| {
            !v.implicit
                && !with_init.contains(&v.span)
                && (v.section == Section::Temp
                    || (u.def.kind == PouKind::Function && v.section == Section::Var))
        })
        .map(|(i, _)| VarId(i as u32))
        .collect();
    if temps.is_empty() {
        return;
    }
    let mut reported = FxHashSet::default();
    let cx = Paths {
        input,
        temps: &temps,
    };
    cx.list(&u.syn.body, &FxHashSet::default(), &mut reported, out);
}

struct Paths<'a, 'b> {
    input: &'b Input<'a>,
    temps: &'b FxHashSet<VarId>,
}

impl Paths<'_, '_> {
    fn var_of(&self, e: ExprId) -> Option<VarId> {
        match self.input.ast.exprs.get(e.index()).map(|x| &x.kind) {
            Some(ExprKind::Name(_)) => match self.input.analysis.resolutions.get(&e) {
                Some(Res::Var(v)) if self.temps.contains(v) => Some(*v),
                _ => None,
            },
            _ => None,
        }
    }

    /// The temporaries a statement assigns whole (`v := ...`, `=> v`) at
    /// its top level.
    fn assigns_top(&self, s: &Stmt) -> Vec<VarId> {
        match &s.kind {
            StmtKind::Assign { target, .. } => self.var_of(*target).into_iter().collect(),
            StmtKind::Call(e) => self.output_targets(*e),
            _ => Vec::new(),
        }
    }

    fn output_targets(&self, e: ExprId) -> Vec<VarId> {
        let mut out = Vec::new();
        if let Some(ExprKind::Call { args, .. }) =
            self.input.ast.exprs.get(e.index()).map(|x| &x.kind)
        {
            for a in args.iter() {
                if let ArgKind::Output { target, .. } = &a.kind {
                    out.extend(self.var_of(*target));
                }
            }
        }
        out
    }

    /// The temporaries assigned anywhere in a list of statements.
    fn assigns_anywhere(&self, list: &[Stmt]) -> Vec<VarId> {
        let mut out = Vec::new();
        walk::statements(list, &mut |s| out.extend(self.assigns_top(s)));
        out
    }

    /// The first read of `v` in a statement (and those nested in it): a
    /// use other than as the whole target of an assignment or output.
    fn first_read(&self, s: &Stmt, v: VarId) -> Option<Span> {
        let ast = self.input.ast;
        let found: std::cell::Cell<Option<Span>> = std::cell::Cell::new(None);
        let look = |root: ExprId, skip_root: bool| {
            if skip_root && self.var_of(root) == Some(v) {
                // The whole target of an assignment or an output: a write.
                return;
            }
            walk::expr_tree(ast, root, &mut |e| {
                if found.get().is_none() && self.var_of(e) == Some(v) {
                    found.set(ast.exprs.get(e.index()).map(|x| x.span));
                }
            });
        };
        let mut stmts = Vec::new();
        walk::statements(std::slice::from_ref(s), &mut |x| stmts.push(x));
        for x in stmts {
            if found.get().is_some() {
                break;
            }
            match &x.kind {
                StmtKind::Assign { target, value } => {
                    look(*value, false);
                    look(*target, true);
                }
                StmtKind::Call(e) => {
                    if let Some(ExprKind::Call { callee, args }) =
                        ast.exprs.get(e.index()).map(|c| &c.kind)
                    {
                        look(*callee, false);
                        for a in args.iter() {
                            match &a.kind {
                                ArgKind::Positional(y) | ArgKind::Input { value: y, .. } => {
                                    look(*y, false)
                                }
                                ArgKind::Output { target, .. } => look(*target, true),
                            }
                        }
                    } else {
                        look(*e, false);
                    }
                }
                _ => walk::own_exprs(x, &mut |e| look(e, false), &mut |_| {}),
            }
        }
        found.get()
    }

    fn list(
        &self,
        list: &[Stmt],
        before: &FxHashSet<VarId>,
        reported: &mut FxHashSet<VarId>,
        out: &mut Vec<Diagnostic>,
    ) {
        let mut assigned = before.clone();
        for (i, s) in list.iter().enumerate() {
            if let StmtKind::If {
                branches,
                else_body: None,
            } = &s.kind
            {
                let mut some: Vec<VarId> = Vec::new();
                for b in branches {
                    some.extend(self.assigns_anywhere(&b.body));
                }
                some.sort();
                some.dedup();
                for v in some {
                    if assigned.contains(&v) || reported.contains(&v) {
                        continue;
                    }
                    for t in &list[i + 1..] {
                        if let Some(read) = self.first_read(t, v) {
                            reported.insert(v);
                            let n = self.input.sources.slice(read);
                            let if_head = Span::new(s.span.lo, s.span.lo + 2);
                            out.push(
                                Diagnostic::new(
                                    Code::L0009,
                                    read,
                                    format!(
                                        "`{n}` is read here but assigned only on some paths of the IF above"
                                    ),
                                )
                                .with_label("may still hold its initial value")
                                .with_secondary(if_head, "this IF has no ELSE")
                                .with_help(format!(
                                    "assign `{n}` before the IF, or in an ELSE branch too"
                                )),
                            );
                            break;
                        }
                        if self.assigns_top(t).contains(&v) {
                            break;
                        }
                    }
                }
            }
            for l in walk::nested(s) {
                self.list(l, &assigned, reported, out);
            }
            assigned.extend(self.assigns_top(s));
        }
    }
}

/// Whether a text may hold a nested `(*` comment: a quick scan that counts
/// `(*` and `*)` and ignores strings and other comments, so it may say yes
/// where the lexer finds none, never no where there is one.
fn may_nest(text: &str) -> bool {
    let b = text.as_bytes();
    let mut depth = 0u32;
    let mut i = 0;
    while i + 1 < b.len() {
        match (b[i], b[i + 1]) {
            (b'(', b'*') => {
                if depth > 0 {
                    return true;
                }
                depth += 1;
                i += 2;
            }
            (b'*', b')') if depth > 0 => {
                depth -= 1;
                i += 2;
            }
            _ => i += 1,
        }
    }
    false
}
