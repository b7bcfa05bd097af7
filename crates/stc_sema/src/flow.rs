//! Checks across a whole body or the whole project: unused variables, names
//! hiding globals, a function's result on every path, evaluation order of
//! arguments, externals against globals, and recursion.

use rustc_hash::{FxHashMap, FxHashSet};
use stc_diagnostics::{Code, Diagnostic, Span};
use stc_syntax::ast::{Arg, ArgKind, ExprId, ExprKind, Pou, PouKind, Stmt, StmtKind};

use crate::analyzer::{GlobalName, Scope, Sema};
use crate::types::TypeKind;
use crate::{BoundArgKind, PouId, Res, Section, VarId};

/// One access to a variable, for W0101: the variable and the path below it.
struct Access {
    var: VarId,
    path: Vec<Step>,
    /// The expression, to name the access in messages.
    expr: ExprId,
}

#[derive(PartialEq)]
enum Step {
    Field(stc_syntax::Symbol),
    /// Array indices, `None` where not constant.
    Index(Vec<Option<i128>>),
    /// A part of a bit string: bits `lo..hi`.
    Bits(u32, u32),
}

impl Access {
    /// Whether two accesses may touch the same memory: the same variable,
    /// and no step where they certainly part (another member, another
    /// constant index, other bits). A path and its prefix overlap.
    fn overlaps(&self, other: &Access) -> bool {
        self.var == other.var
            && self
                .path
                .iter()
                .zip(&other.path)
                .all(|(a, b)| match (a, b) {
                    (Step::Field(x), Step::Field(y)) => x == y,
                    (Step::Index(x), Step::Index(y)) => !x
                        .iter()
                        .zip(y)
                        .any(|(p, q)| matches!((p, q), (Some(p), Some(q)) if p != q)),
                    (Step::Bits(a0, a1), Step::Bits(b0, b1)) => a0 < b1 && b0 < a1,
                    _ => true,
                })
    }
}

/// What the warnings need of a variable.
struct Local {
    name: stc_syntax::Symbol,
    span: Span,
    section: Section,
}

impl<'a> Sema<'a> {
    /// The warnings of one POU, after its body is checked.
    pub(crate) fn pou_warnings(&mut self, p: PouId, pou: &'a Pou) {
        if self.pous[p.0 as usize].is_std {
            return;
        }
        // An INTERFACE and its prototypes have no body: nothing is used.
        let owner = self.own_fb(p).unwrap_or(p);
        if self.pous[owner.0 as usize].class == Some(stc_syntax::ast::ClassKind::Interface) {
            return;
        }
        // A part reported as not supported (an IL or SFC body, a METHOD...)
        // may use any variable and assign the result: nothing is known.
        let partial = pou.partial || self.body.partial;
        // A block another block extends: its VAR variables may be used by
        // the derived blocks' bodies and methods (checked later or not at
        // all here), so none is called unused.
        let extended = self.bases.contains(&owner);
        let vars: Vec<(stc_syntax::Symbol, Span, Section, bool, crate::TypeId)> = self.pous
            [p.0 as usize]
            .vars
            .iter()
            .enumerate()
            .filter(|(_, v)| !v.implicit)
            .map(|(i, v)| {
                // A declaration whose type was already an error (an
                // unsupported or unknown type) is not reported again; nor
                // the tag and what is inherited (the base's business).
                let def = &self.pous[p.0 as usize];
                let quiet = v.location.is_some()
                    || (extended && v.section == Section::Var && p == owner)
                    || v.ty == crate::TypeId::ERROR
                    || (i as u32) < def.inherited
                    || def.tag == Some(VarId(i as u32));
                (v.name, v.span, v.section, quiet, v.ty)
            })
            .collect();
        for (i, &(name, span, section, quiet, ty)) in vars.iter().enumerate() {
            let v = Local {
                name,
                span,
                section,
            };
            let id = VarId(i as u32);
            let shown = self.spelled(v.name, v.span);
            // A located variable is part of the I/O map (its initial value
            // is the slot's): declaring it is a use.
            if matches!(v.section, Section::Var | Section::Temp)
                && !quiet
                && !self.used.contains(&(p, id))
                && !partial
            {
                self.emit(
                    Diagnostic::new(Code::W0104, v.span, format!("unused variable `{shown}`"))
                        .with_label("declared but never used"),
                );
            }
            if matches!(
                v.section,
                Section::External | Section::Result | Section::Global
            ) {
                continue;
            }
            // (Hiding a global is checked with the externals, once it is
            // known where the POU runs: `check_hidden_globals`.)
            // An instance or variable named after its own type (`T_PLC_MS :
            // T_PLC_MS;`, a PC WORX idiom) hides nothing it could mean.
            let global = self
                .find_global(stc_syntax::ast::Ident {
                    sym: v.name,
                    span: v.span,
                })
                .hit
                .map(|(g, _)| g);
            let own_type = match global {
                Some(GlobalName::Type(i)) => self.type_decls[i].ty == ty,
                Some(GlobalName::Pou(q)) => {
                    matches!(self.types.kind(ty), TypeKind::Fb(r) if *r == q)
                }
                _ => false,
            };
            let hidden = match global {
                _ if own_type => None,
                Some(GlobalName::Type(_)) => Some("a data type"),
                Some(GlobalName::Pou(q)) if !self.pous[q.0 as usize].is_std => {
                    Some(match self.pous[q.0 as usize].kind {
                        PouKind::Function => "a function",
                        PouKind::FunctionBlock => "a function block type",
                        PouKind::Program => "a program",
                    })
                }
                _ => None,
            };
            if let Some(what) = hidden {
                self.emit(
                    Diagnostic::new(
                        Code::W0109,
                        v.span,
                        format!("`{shown}` hides {what} of the same name"),
                    )
                    .with_label(format!("hides {what}")),
                );
            }
        }
        // (An ABSTRACT method has no body to assign its result.)
        let abstract_method = self.pous[p.0 as usize]
            .method_of
            .and_then(|(fb, k)| {
                let owner = self.pou_ast(fb)?;
                Some(owner.is_interface() || owner.methods.get(k)?.is_abstract)
            })
            .unwrap_or(false);
        let result_known = self.pous[p.0 as usize]
            .return_type
            .is_some_and(|t| t != crate::TypeId::ERROR)
            && !abstract_method;
        if pou.kind == PouKind::Function && result_known && !partial {
            let mut unassigned_return = false;
            let end = match &pou.il {
                Some(il) => self.il_assigns_result(p, il),
                None => self.assigns_result(&pou.body, p, false, &mut unassigned_return),
            };
            if !end || unassigned_return {
                let name = self.spelled(pou.name.sym, pou.name.span);
                self.emit(
                    Diagnostic::new(
                        Code::W0106,
                        pou.name.span,
                        format!("the result of `{name}` is not assigned on every path"),
                    )
                    .with_label("may return its type's initial value")
                    .with_help(format!(
                        "assign `{name} := ...` on every path, or before the first RETURN"
                    )),
                );
            }
        }
    }

    /// Whether the function result is assigned at the end of `list`, given
    /// that it is `assigned` at its start; sets `bad_return` if some RETURN
    /// is reached with the result unassigned.
    fn assigns_result(
        &self,
        list: &'a [Stmt],
        p: PouId,
        mut assigned: bool,
        bad_return: &mut bool,
    ) -> bool {
        for s in list {
            match &s.kind {
                StmtKind::Assign { target, .. } if self.is_result(p, *target) => assigned = true,
                StmtKind::Call(e) => {
                    if let Some(call) = self.calls.get(e) {
                        for a in &call.args {
                            match a.kind {
                                BoundArgKind::Output { target, .. }
                                | BoundArgKind::InOut(target)
                                    if self.is_result(p, target) =>
                                {
                                    assigned = true
                                }
                                _ => {}
                            }
                        }
                    }
                }
                StmtKind::If {
                    branches,
                    else_body,
                } => {
                    let mut all = else_body.is_some();
                    for b in branches {
                        all &= self.assigns_result(&b.body, p, assigned, bad_return);
                    }
                    if let Some(e) = else_body {
                        all &= self.assigns_result(e, p, assigned, bad_return);
                    }
                    assigned |= all;
                }
                StmtKind::Case {
                    arms, else_body, ..
                } => {
                    let mut all = else_body.is_some();
                    for a in arms {
                        all &= self.assigns_result(&a.body, p, assigned, bad_return);
                    }
                    if let Some(e) = else_body {
                        all &= self.assigns_result(e, p, assigned, bad_return);
                    }
                    assigned |= all;
                }
                StmtKind::For { body, .. } | StmtKind::While { body, .. } => {
                    self.assigns_result(body, p, assigned, bad_return);
                }
                StmtKind::Repeat { body, .. } => {
                    assigned = self.assigns_result(body, p, assigned, bad_return);
                }
                StmtKind::Return => {
                    if !assigned {
                        *bad_return = true;
                    }
                    return true;
                }
                StmtKind::Exit | StmtKind::Continue => return assigned,
                _ => {}
            }
        }
        assigned
    }

    pub(crate) fn is_result_pub(&self, p: PouId, target: ExprId) -> bool {
        self.is_result(p, target)
    }

    fn is_result(&self, p: PouId, target: ExprId) -> bool {
        self.root_var(target)
            .is_some_and(|v| self.pous[p.0 as usize].var(v).section == Section::Result)
    }

    /// W0101: a variable written by one argument (through `=>` or a
    /// VAR_IN_OUT of a nested call) and read by another. Accesses are
    /// compared as paths: `s.a` and `s.b` are apart, `s` and `s.a` overlap,
    /// `a[1]` and `a[2]` are apart, `a[i]` and `a[2]` may overlap.
    pub(crate) fn check_eval_order(&mut self, args: &[Arg], scope: Scope, span: Span) {
        if args.len() < 2 {
            return;
        }
        let mut effects = Vec::with_capacity(args.len());
        for a in args {
            let mut reads = Vec::new();
            let mut writes = Vec::new();
            match &a.kind {
                ArgKind::Positional(v) | ArgKind::Input { value: v, .. } => {
                    self.effects(*v, &mut reads, &mut writes)
                }
                // The call's own outputs are written after it returns.
                ArgKind::Output { .. } => {}
            }
            effects.push((reads, writes));
        }
        for (i, (_, w)) in effects.iter().enumerate() {
            for (j, (r, _)) in effects.iter().enumerate() {
                if i == j {
                    continue;
                }
                let Some(written) = w.iter().find(|w| r.iter().any(|r| w.overlaps(r))) else {
                    continue;
                };
                let text = self.sources.slice(self.ast.expr(written.expr).span);
                let name = match scope {
                    _ if !text.is_empty() && text.len() <= 40 => format!("`{text}`"),
                    Scope::Pou(p) => format!(
                        "`{}`",
                        self.sym_name(self.pous[p.0 as usize].var(written.var).name)
                    ),
                    _ => "a variable".into(),
                };
                self.emit(
                    Diagnostic::new(
                        Code::W0101,
                        span,
                        format!("the result of this call depends on the order its arguments are evaluated in: {name} is written by one and read by another"),
                    )
                    .with_secondary(args[i].span, format!("this argument writes {name}"))
                    .with_secondary(args[j].span, format!("this argument reads {name}"))
                    .with_note("stc evaluates arguments left to right; other tools may not")
                    .with_help(format!("store the output in another variable first, or read {name} in a separate statement")),
                );
                return;
            }
        }
    }

    /// The variable and the path an lvalue-shaped expression accesses.
    fn access_of(&self, mut e: ExprId) -> Option<Access> {
        let start = e;
        let mut path = Vec::new();
        loop {
            match &self.ast.expr(e).kind {
                ExprKind::Member { base, member } => {
                    path.push(Step::Field(member.sym));
                    e = *base;
                }
                ExprKind::Index { base, indices } => {
                    let known = indices
                        .iter()
                        .map(|i| match self.consts.get(i) {
                            Some(stc_values::Value::Int(v)) => Some(*v),
                            _ => None,
                        })
                        .collect();
                    path.push(Step::Index(known));
                    e = *base;
                }
                ExprKind::PartialAccess { base, size, index } => {
                    let lo = size.bits() * index;
                    path.push(Step::Bits(lo, lo + size.bits()));
                    e = *base;
                }
                ExprKind::Paren(i) => e = *i,
                ExprKind::Name(_) => {
                    let Some(Res::Var(v)) = self.resolutions.get(&e) else {
                        return None;
                    };
                    path.reverse();
                    return Some(Access {
                        var: *v,
                        path,
                        expr: start,
                    });
                }
                _ => return None,
            }
        }
    }

    fn effects(&self, e: ExprId, reads: &mut Vec<Access>, writes: &mut Vec<Access>) {
        match &self.ast.expr(e).kind {
            ExprKind::Name(_)
            | ExprKind::Member { .. }
            | ExprKind::Index { .. }
            | ExprKind::PartialAccess { .. } => {
                if let Some(a) = self.access_of(e) {
                    reads.push(a);
                }
                // The indices along the path are read too.
                let mut x = e;
                loop {
                    match &self.ast.expr(x).kind {
                        ExprKind::Member { base, .. } | ExprKind::PartialAccess { base, .. } => {
                            x = *base
                        }
                        ExprKind::Index { base, indices } => {
                            for i in indices.iter() {
                                self.effects(*i, reads, writes);
                            }
                            x = *base;
                        }
                        ExprKind::Paren(i) => x = *i,
                        ExprKind::Name(_) => break,
                        _ => {
                            self.effects(x, reads, writes);
                            break;
                        }
                    }
                }
            }
            ExprKind::Unary { operand, .. } => self.effects(*operand, reads, writes),
            ExprKind::Binary { lhs, rhs, .. } => {
                self.effects(*lhs, reads, writes);
                self.effects(*rhs, reads, writes);
            }
            ExprKind::Paren(i) | ExprKind::Deref(i) => self.effects(*i, reads, writes),
            ExprKind::Call { args, .. } => {
                let bound = self.calls.get(&e);
                for a in args.iter() {
                    match &a.kind {
                        ArgKind::Output { target, .. } => {
                            if let Some(w) = self.access_of(*target) {
                                writes.push(w);
                            }
                        }
                        ArgKind::Positional(v) | ArgKind::Input { value: v, .. } => {
                            let written = bound.is_some_and(|c| {
                                c.args.iter().any(|b| {
                                    matches!(b.kind, BoundArgKind::InOut(x) | BoundArgKind::Output { target: x, .. } if x == *v)
                                })
                            });
                            if written {
                                if let Some(w) = self.access_of(*v) {
                                    writes.push(w);
                                }
                            }
                            self.effects(*v, reads, writes);
                        }
                    }
                }
            }
            _ => {}
        }
    }

    /// Where each POU runs: for every POU, the (configuration, resource)
    /// pairs of the program instances whose program reaches it (through
    /// calls and function block instances), with the instance's span.
    fn pou_contexts(&self) -> Vec<Vec<(usize, usize, Span)>> {
        let n = self.pous.len();
        let succ = self.pou_successors();
        let mut out: Vec<Vec<(usize, usize, Span)>> = vec![Vec::new(); n];
        for (ci, c) in self.configs.iter().enumerate() {
            for (ri, r) in c.resources.iter().enumerate() {
                for inst in &r.programs {
                    let mut seen = vec![false; n];
                    let mut todo = vec![inst.pou.0 as usize];
                    while let Some(q) = todo.pop() {
                        if q >= n || std::mem::replace(&mut seen[q], true) {
                            continue;
                        }
                        if !out[q].iter().any(|&(c2, r2, _)| (c2, r2) == (ci, ri)) {
                            out[q].push((ci, ri, inst.span));
                        }
                        todo.extend(succ[q].iter().copied());
                    }
                }
            }
        }
        out
    }

    /// The POUs each POU reaches directly: those it calls and the types of
    /// its function block instances.
    fn pou_successors(&self) -> Vec<Vec<usize>> {
        let mut succ: Vec<Vec<usize>> = vec![Vec::new(); self.pous.len()];
        for &(a, b, _) in &self.call_edges {
            succ[a.0 as usize].push(b.0 as usize);
        }
        for (pou, out) in self.pous.iter().zip(succ.iter_mut()) {
            for v in &pou.vars {
                if v.section == Section::External || v.section == Section::InOut {
                    continue;
                }
                if let Some(q) = self.fb_in(v.ty) {
                    out.push(q.0 as usize);
                }
            }
        }
        succ
    }

    /// The function block type a variable of type `t` holds instances of
    /// (itself, or the elements of an array).
    fn fb_in(&self, t: crate::TypeId) -> Option<PouId> {
        match self.types.kind(t) {
            TypeKind::Fb(q) => Some(*q),
            TypeKind::Array { elem, .. } => self.fb_in(*elem),
            _ => None,
        }
    }

    /// E0505/E0506: every VAR_EXTERNAL has a matching VAR_GLOBAL where its
    /// POU runs: in each configuration (and resource) whose program
    /// instances reach the POU, the global it binds there; for a POU no
    /// configuration runs, the global outside configurations, if the
    /// project has one of that name, else (a project without
    /// configurations, whose programs run on their own) an error, and
    /// nothing for a POU of a library that nothing here runs.
    pub(crate) fn check_externals(&mut self) {
        let contexts = self.pou_contexts();
        let has_configs = !self.configs.is_empty();
        for (pi, ctx) in contexts.iter().enumerate() {
            if self.pous[pi].is_std {
                continue;
            }
            let p = PouId(pi as u32);
            let vars: Vec<(VarId, crate::VarDef)> = self.pous[pi]
                .vars
                .iter()
                .enumerate()
                .filter(|(_, v)| v.section == Section::External)
                .map(|(i, v)| (VarId(i as u32), v.clone()))
                .collect();
            for (_, v) in vars {
                let shown = self.sym_name(v.name);
                // The globals it binds, each with where.
                let mut bound: Vec<(crate::GlobalId, Option<Span>)> = Vec::new();
                let mut missing: Option<Span> = None;
                for &(ci, ri, span) in ctx {
                    match self.config_global(v.name, ci, Some(ri)) {
                        Some(g) => {
                            if !bound.iter().any(|(h, _)| *h == g) {
                                bound.push((g, Some(span)));
                            }
                        }
                        None => {
                            missing.get_or_insert(span);
                        }
                    }
                }
                if ctx.is_empty() {
                    let top = self.globals.iter().position(|g| {
                        g.owner == crate::GlobalOwner::TopLevel && g.var.name == v.name
                    });
                    match top {
                        Some(g) => bound.push((crate::GlobalId(g as u32), None)),
                        None if !has_configs && self.runs_alone(p) => {
                            self.emit(
                                Diagnostic::new(Code::E0505, v.span, format!("no VAR_GLOBAL declares `{shown}`"))
                                    .with_label("external without a global")
                                    .with_help(format!("declare `{shown}` in a VAR_GLOBAL, or in the configuration that runs this POU")),
                            );
                            continue;
                        }
                        None => {}
                    }
                }
                if let Some(span) = missing {
                    self.emit(
                        Diagnostic::new(Code::E0505, v.span, format!("no VAR_GLOBAL declares `{shown}` in the configuration that runs this POU"))
                            .with_secondary(span, "instantiated here"),
                    );
                }
                for (g, inst) in bound {
                    let gd = self.globals[g.0 as usize].var.clone();
                    let same = self.types.compat(gd.ty, v.ty, false) == crate::Compat::Same
                        && self.types.compat(v.ty, gd.ty, false) == crate::Compat::Same;
                    let msg = if !same {
                        format!(
                            "`{shown}` is declared {} here but {} in VAR_GLOBAL",
                            self.tname(v.ty),
                            self.tname(gd.ty)
                        )
                    } else if gd.constant && !v.constant {
                        format!(
                            "`{shown}` is a CONSTANT global: declare it in VAR_EXTERNAL CONSTANT"
                        )
                    } else {
                        continue;
                    };
                    let mut d = Diagnostic::new(Code::E0506, v.span, msg)
                        .with_secondary(gd.span, "the global");
                    if let Some(span) = inst {
                        d = d.with_secondary(span, "where it binds: this instance runs the POU");
                    }
                    self.emit(d);
                    break;
                }
            }
        }
        self.check_hidden_globals(&contexts);
    }

    /// Whether a POU runs in a project without configurations: a PROGRAM,
    /// or a POU some PROGRAM reaches.
    fn runs_alone(&self, p: PouId) -> bool {
        let n = self.pous.len();
        let succ = self.pou_successors();
        let mut seen = vec![false; n];
        let mut todo: Vec<usize> = (0..n)
            .filter(|&i| !self.pous[i].is_std && self.pous[i].kind == PouKind::Program)
            .collect();
        while let Some(q) = todo.pop() {
            if q >= n || std::mem::replace(&mut seen[q], true) {
                continue;
            }
            todo.extend(succ[q].iter().copied());
        }
        seen.get(p.0 as usize).copied().unwrap_or(false)
    }

    /// W0109 for a local variable named like a global that a VAR_EXTERNAL
    /// of its POU would bind where the POU runs (a global outside
    /// configurations, or one of a configuration that runs it): the local
    /// may have been meant as that external. Interface variables (inputs,
    /// outputs) are the POU's API and are not reported.
    fn check_hidden_globals(&mut self, contexts: &[Vec<(usize, usize, Span)>]) {
        for (pi, ctx) in contexts.iter().enumerate() {
            let partial = self
                .pou_ast(crate::PouId(pi as u32))
                .is_some_and(|a| a.partial);
            if self.pous[pi].is_std || partial {
                continue;
            }
            let locals: Vec<(stc_syntax::Symbol, Span)> = self.pous[pi]
                .vars
                .iter()
                .filter(|v| !v.implicit && matches!(v.section, Section::Var | Section::Temp))
                .map(|v| (v.name, v.span))
                .collect();
            for (name, span) in locals {
                if !self.global_names.contains(&name) {
                    continue;
                }
                let visible = self
                    .globals
                    .iter()
                    .any(|g| g.var.name == name && g.owner == crate::GlobalOwner::TopLevel)
                    || ctx
                        .iter()
                        .any(|&(ci, ri, _)| self.config_global(name, ci, Some(ri)).is_some());
                if visible {
                    let shown = self.spelled(name, span);
                    self.emit(
                        Diagnostic::new(
                            Code::W0109,
                            span,
                            format!("`{shown}` hides a global variable of the same name"),
                        )
                        .with_label("hides a global variable"),
                    );
                }
            }
        }
    }

    /// E0503: a cycle of calls (or of instances containing themselves).
    pub(crate) fn check_recursion(&mut self) {
        let mut edges: FxHashMap<PouId, Vec<(PouId, Span)>> = FxHashMap::default();
        for &(a, b, s) in &self.call_edges {
            edges.entry(a).or_default().push((b, s));
        }
        for (pi, pou) in self.pous.iter().enumerate() {
            for v in &pou.vars {
                if v.section == Section::External || v.section == Section::InOut {
                    continue;
                }
                if let TypeKind::Fb(q) = self.types.kind(v.ty) {
                    edges
                        .entry(PouId(pi as u32))
                        .or_default()
                        .push((*q, v.span));
                }
            }
        }
        // Tarjan's strongly connected components.
        let n = self.pous.len();
        let mut index = vec![usize::MAX; n];
        let mut low = vec![0; n];
        let mut on_stack = vec![false; n];
        let mut stack = Vec::new();
        let mut next = 0;
        let mut sccs: Vec<Vec<usize>> = Vec::new();
        for start in 0..n {
            if index[start] != usize::MAX {
                continue;
            }
            // Iterative DFS: (node, next edge position).
            let mut dfs = vec![(start, 0usize)];
            index[start] = next;
            low[start] = next;
            next += 1;
            stack.push(start);
            on_stack[start] = true;
            while let Some(&mut (v, ref mut ei)) = dfs.last_mut() {
                let succ = edges
                    .get(&PouId(v as u32))
                    .map(|e| e.as_slice())
                    .unwrap_or(&[]);
                if *ei < succ.len() {
                    let w = succ[*ei].0 .0 as usize;
                    *ei += 1;
                    if index[w] == usize::MAX {
                        index[w] = next;
                        low[w] = next;
                        next += 1;
                        stack.push(w);
                        on_stack[w] = true;
                        dfs.push((w, 0));
                    } else if on_stack[w] {
                        low[v] = low[v].min(index[w]);
                    }
                } else {
                    dfs.pop();
                    if let Some(&(parent, _)) = dfs.last() {
                        low[parent] = low[parent].min(low[v]);
                    }
                    if low[v] == index[v] {
                        let mut comp = Vec::new();
                        while let Some(w) = stack.pop() {
                            on_stack[w] = false;
                            comp.push(w);
                            if w == v {
                                break;
                            }
                        }
                        sccs.push(comp);
                    }
                }
            }
        }
        for comp in sccs {
            let members: FxHashSet<usize> = comp.iter().copied().collect();
            let cyclic = comp.len() > 1
                || edges
                    .get(&PouId(comp[0] as u32))
                    .is_some_and(|e| e.iter().any(|(q, _)| q.0 as usize == comp[0]));
            if !cyclic {
                continue;
            }
            // Report once, in the POU that comes last in the sources.
            let last = *comp
                .iter()
                .max_by_key(|&&i| self.pous[i].span.lo)
                .unwrap_or(&comp[0]);
            let Some(&(_, span)) = edges
                .get(&PouId(last as u32))
                .and_then(|e| e.iter().find(|(q, _)| members.contains(&(q.0 as usize))))
            else {
                continue;
            };
            let names: Vec<String> = comp
                .iter()
                .rev()
                .map(|&i| format!("`{}`", self.sym_name(self.pous[i].name)))
                .collect();
            let msg = if comp.len() == 1 {
                format!("`{}` calls itself", self.sym_name(self.pous[last].name))
            } else {
                format!("recursion between {}", names.join(", "))
            };
            self.emit(
                Diagnostic::new(Code::E0503, span, msg)
                    .with_label("this closes the cycle")
                    .with_note(
                        "IEC 61131-3 does not allow recursion: memory is allocated statically",
                    ),
            );
        }
    }
}
