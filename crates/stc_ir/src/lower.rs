//! Lowering: the analysed syntax tree to the IR.

mod il;
mod oop;
mod pointers;
mod split;

use stc_diagnostics::{SourceMap, Span};
use stc_sema::idx::IdVec;
use stc_sema::{
    Analysis, BoundArgKind, CallInfo, CallTarget, InitValue, PouId, Res, Section, TypeId, TypeKind,
    VarId,
};
use stc_syntax::ast::{self as ast, Ast, ExprId, ExprKind as AK, PouKind, StmtKind as SK};
use stc_syntax::token::ElemType;
use stc_syntax::Interner;
use stc_values::{BinOp, Intrinsic, UnOp, Value};

use crate::{
    Expr, ExprKind, FaultKind, Global, Module, Output, Place, Pou, Proj, Root, Stmt, StmtKind,
    Storage, Var,
};

/// Lowers an analysed project (which must have no errors) to the IR.
pub fn lower(ast: &Ast, analysis: Analysis, interner: &Interner, sources: &SourceMap) -> Module {
    let mut names: Vec<String> = (0..interner.len())
        .map(|i| interner.spelling(stc_syntax::Symbol(i as u32)).to_string())
        .collect();
    // Outputs show a name as spelled at its declaration.
    let mut spellings = rustc_hash::FxHashMap::default();
    let mut declare = |sym: stc_syntax::Symbol, span: Span, rename: bool| {
        let s = sources.slice(span);
        if !s.is_empty() && s.eq_ignore_ascii_case(interner.key(sym)) {
            if let Some(slot) = names.get_mut(sym.0 as usize).filter(|_| rename) {
                *slot = s.to_string();
            }
            spellings.insert(span.lo, Box::<str>::from(s));
        }
    };
    for p in &analysis.pous {
        declare(p.name, p.name_span, true);
        for v in &p.vars {
            declare(v.name, v.span, true);
        }
    }
    for g in &analysis.globals {
        declare(g.var.name, g.var.span, true);
    }
    for c in &analysis.configs {
        for r in &c.resources {
            for i in &r.programs {
                // Only the spelling at the instance: the symbol's name
                // stays its POU's or variable's (`main WITH t : Main`).
                declare(i.name, i.name_span, false);
            }
            for t in &r.tasks {
                // A task is shown as spelled at its declaration, whatever
                // else has its name (a structure field `T`).
                declare(t.name, t.name_span, false);
            }
        }
    }
    for t in 0..analysis.types.len() {
        let info = analysis.types.get(TypeId(t as u32));
        if let (Some(n), Some(span)) = (info.name, info.name_span) {
            declare(n, span, true);
        }
        if let TypeKind::Enum { values, .. } = &info.kind {
            for v in values {
                declare(v.name, v.span, true);
            }
        }
        if let TypeKind::Struct { fields } = &info.kind {
            for f in fields {
                declare(f.name, f.span, true);
            }
        }
    }
    // The implicit EN and ENO of a POU get storage only when some code
    // refers to them (they come after every declared variable, so dropping
    // them keeps every other VarId).
    // (The blocks some block extends, once: asking each POU's question of
    // every other POU made lowering quadratic in the number of POUs.)
    let bases: rustc_hash::FxHashSet<PouId> = analysis.pous.iter().filter_map(|d| d.base).collect();
    let keeps: Vec<bool> = analysis
        .pous
        .iter()
        .enumerate()
        .map(|(i, p)| {
            // (A METHOD's hidden THIS is bound by every call.)
            // (A base's are also its derived blocks' hidden variables.)
            p.this.is_some()
                || bases.contains(&PouId(i as u32))
                || p.vars.iter().enumerate().any(|(v, var)| {
                    var.implicit
                        && analysis
                            .implicit_used
                            .contains(&(PouId(i as u32), VarId(v as u32)))
                })
        })
        .collect();
    let mut pous = Vec::with_capacity(analysis.pous.len());
    let mut helpers = pointers::Helpers::default();
    for (i, def) in analysis.pous.iter().enumerate() {
        // (Skipping one would shift the PouId of every later POU.)
        let Some(src) = analysis.pou_syntax(ast, PouId(i as u32)) else {
            panic!("internal error: POU {i} is not declared by a POU item");
        };
        let mut l = Lowerer {
            ast,
            a: &analysis,
            sources,
            pou: PouId(i as u32),
            vars: IdVec::new(),
            keeps: &keeps,
            pending: Vec::new(),
            post: Vec::new(),
            writing: false,
            cr_vars: rustc_hash::FxHashMap::default(),
            helpers: std::mem::take(&mut helpers),
        };
        pous.push(l.pou(def, src));
        helpers = std::mem::take(&mut l.helpers);
    }
    // The functions pointer dereferences call (after every POU: their
    // PouIds follow the analysis's).
    for (i, (h, v)) in helpers.list().iter().enumerate() {
        let name = stc_syntax::Symbol(names.len() as u32);
        names.push(format!("POINTER_{}_{}", h.word(), i));
        let mut l = Lowerer {
            ast,
            a: &analysis,
            sources,
            pou: PouId(0),
            vars: IdVec::new(),
            keeps: &keeps,
            pending: Vec::new(),
            post: Vec::new(),
            writing: false,
            cr_vars: rustc_hash::FxHashMap::default(),
            helpers: pointers::Helpers::default(),
        };
        pous.push(l.ptr_helper(*h, *v, name));
    }
    let globals = analysis
        .globals
        .iter()
        .map(|g| Global {
            name: g.var.name,
            ty: g.var.ty,
            init: g.var.init.clone(),
            constant: g.var.constant,
            retain: g.var.retain,
            location: g.var.location.clone(),
            span: g.var.span,
            library: sources
                .file_of(g.var.span.lo)
                .is_some_and(|f| sources.file(f).is_library()),
        })
        .collect();
    Module {
        types: analysis.types,
        pous: pous.into(),
        globals,
        configs: analysis.configs,
        names,
        spellings,
    }
}

struct Lowerer<'a> {
    ast: &'a Ast,
    a: &'a Analysis,
    sources: &'a SourceMap,
    pou: PouId,
    vars: IdVec<VarId, Var>,
    /// Per POU: whether its implicit EN and ENO have storage.
    keeps: &'a [bool],
    /// Statements that must run before the statement being lowered: calls
    /// with EN or ENO taken out of an expression (and the operands before
    /// them, so evaluation stays left to right).
    pending: Vec<Stmt>,
    /// Statements that must run after the statement being lowered (a
    /// byte written into a STRING through a pointer).
    post: Vec<Stmt>,
    /// Lowering a place that the statement writes.
    writing: bool,
    /// The pointer helper functions the POUs lowered so far call.
    helpers: pointers::Helpers,
    /// In an Instruction List body: the hidden variable of the current
    /// result for each type it takes.
    cr_vars: rustc_hash::FxHashMap<TypeId, VarId>,
}

impl<'a> Lowerer<'a> {
    fn pou(&mut self, def: &stc_sema::PouDef, src: &'a ast::Pou) -> Pou {
        let function = def.kind == PouKind::Function;
        let keep = self.keeps[self.pou.0 as usize];
        self.vars = def
            .vars
            .iter()
            .filter(|v| keep || !v.implicit)
            .map(|v| Var {
                name: v.name,
                ty: v.ty,
                section: v.section,
                storage: match v.section {
                    Section::InOut | Section::External => Storage::Ref,
                    // A located variable is its process-image slot.
                    _ if v.location.as_ref().is_some_and(|l| !l.is_incomplete()) => Storage::Ref,
                    _ if function => Storage::Frame,
                    Section::Temp => Storage::Frame,
                    _ => Storage::Instance,
                },
                init: v.init.clone(),
                constant: v.constant,
                retain: v.retain,
                location: v.location.clone(),
                hidden: None,
                span: v.span,
            })
            .collect();
        for (i, v) in self.vars.iter_mut().enumerate() {
            let id = VarId(i as u32);
            if Some(id) == def.tag {
                v.hidden = Some("tag");
            } else if def.hidden_var(id) {
                v.hidden = Some("inherited");
            }
        }
        let mut body = Vec::new();
        let (line, col) = self.line_col(src.span);
        // ENO is TRUE at the start of every call.
        if let Some(eno) = def.eno.filter(|v| keep && def.var(*v).implicit) {
            let bool_ty = self.bool_ty();
            body.push(Stmt {
                kind: StmtKind::Assign {
                    place: Place {
                        root: Root::Var(eno),
                        proj: vec![],
                        ty: bool_ty,
                    },
                    value: Expr {
                        kind: ExprKind::Const(Value::Bool(true)),
                        ty: bool_ty,
                    },
                },
                line,
                col,
            });
        }
        // R_EDGE / F_EDGE inputs: the input is TRUE only on the edge.
        for (i, v) in def.vars.iter().enumerate() {
            let Some(edge) = v.edge else { continue };
            let input = VarId(i as u32);
            let bool_ty = self.bool_ty();
            let prev = self.hidden(v.name, "prev", bool_ty, Storage::Instance, v.span);
            let cur = self.hidden(v.name, "cur", bool_ty, Storage::Frame, v.span);
            let load = |v: VarId| Expr {
                kind: ExprKind::Load(Place {
                    root: Root::Var(v),
                    proj: vec![],
                    ty: bool_ty,
                }),
                ty: bool_ty,
            };
            let not = |e: Expr| Expr {
                kind: ExprKind::Unary(UnOp::Not, Box::new(e)),
                ty: bool_ty,
            };
            let and = |a: Expr, b: Expr| Expr {
                kind: ExprKind::Binary(BinOp::And, Box::new(a), Box::new(b)),
                ty: bool_ty,
            };
            let place = |v: VarId| Place {
                root: Root::Var(v),
                proj: vec![],
                ty: bool_ty,
            };
            let edge_value = match edge {
                ast::Edge::Rising => and(load(cur), not(load(prev))),
                ast::Edge::Falling => and(not(load(cur)), load(prev)),
            };
            for kind in [
                StmtKind::Assign {
                    place: place(cur),
                    value: load(input),
                },
                StmtKind::Assign {
                    place: place(input),
                    value: edge_value,
                },
                StmtKind::Assign {
                    place: place(prev),
                    value: load(cur),
                },
            ] {
                body.push(Stmt { kind, line, col });
            }
        }
        body.extend(self.stmts(&src.body));
        if let Some(il) = &src.il {
            let stmts = self.il_body(il);
            body.extend(stmts);
        }
        let (file, _) = self
            .sources
            .locate(def.span.lo)
            .map(|(f, _)| (f.name.clone(), 0))
            .unwrap_or_default();
        Pou {
            kind: def.kind,
            name: def.name,
            vars: std::mem::take(&mut self.vars),
            result: if function && def.return_type.is_some() {
                Some(VarId(0))
            } else {
                None
            },
            body,
            is_std: def.is_std,
            span: def.span,
            name_span: def.name_span,
            file,
        }
    }

    fn hidden(
        &mut self,
        name: stc_syntax::Symbol,
        role: &'static str,
        ty: TypeId,
        storage: Storage,
        span: Span,
    ) -> VarId {
        let id = VarId(self.vars.len() as u32);
        self.vars.push(Var {
            name,
            ty,
            section: if storage == Storage::Frame {
                Section::Temp
            } else {
                Section::Var
            },
            storage,
            init: None,
            constant: false,
            retain: false,
            location: None,
            hidden: Some(role),
            span,
        });
        id
    }

    fn bool_ty(&self) -> TypeId {
        self.elem_ty(ElemType::Bool)
    }

    /// The TypeId of an elementary type (the table pre-allocates them).
    fn elem_ty(&self, e: ElemType) -> TypeId {
        TypeId::of_elem(e)
    }

    fn line_col(&self, span: Span) -> (u32, u32) {
        self.sources
            .locate(span.lo)
            .map(|(_, lc)| (lc.line, lc.col))
            .unwrap_or((0, 0))
    }

    fn stmt_at(&self, span: Span, kind: StmtKind) -> Stmt {
        let (line, col) = self.line_col(span);
        Stmt { kind, line, col }
    }

    fn stmts(&mut self, list: &'a [ast::Stmt]) -> Vec<Stmt> {
        let mut out = Vec::with_capacity(list.len());
        for s in list {
            self.stmt(s, &mut out);
        }
        out
    }

    fn stmt(&mut self, s: &'a ast::Stmt, out: &mut Vec<Stmt>) {
        let at = |l: &Self, k| l.stmt_at(s.span, k);
        match &s.kind {
            SK::Empty | SK::Error | SK::Unsupported(_) => {}
            SK::Il { body, result } => {
                out.extend(self.il_body(body));
                if let Some(r) = result {
                    if let Some(&ty) = self.a.il_results.get(r) {
                        let place = self.place(*r);
                        let value = Expr {
                            kind: ExprKind::Load(self.cr_place(ty)),
                            ty,
                        };
                        out.push(at(self, StmtKind::Assign { place, value }));
                    }
                }
            }
            SK::AssignAttempt { target, value } => {
                let mut stmts = self.assignment_attempt(*target, *value, s.span);
                out.append(&mut self.pending);
                out.append(&mut stmts);
            }
            SK::Assign { target, value }
                if matches!(
                    self.a.calls.get(target).map(|c| &c.target),
                    Some(CallTarget::Method { .. })
                ) =>
            {
                // `inst.p := v`: the property's SET (docs/oop.md).
                let x = self.call_expr(*target, TypeId::VOID);
                out.append(&mut self.pending);
                // (A virtual call is all in the pending statements.)
                if !matches!(x.kind, ExprKind::Const(_)) {
                    out.push(at(self, StmtKind::Eval(x)));
                }
                out.append(&mut self.post);
            }
            SK::Assign { target, value } => {
                self.writing = true;
                let place = self.place(*target);
                self.writing = false;
                let mut v = self.expr(*value);
                out.append(&mut self.pending);
                if let TypeKind::Subrange { lo, hi, .. } = self.a.types.kind(place.ty) {
                    if !matches!(v.kind, ExprKind::Const(_)) {
                        v = Expr {
                            ty: place.ty,
                            kind: ExprKind::Check {
                                value: Box::new(v),
                                lo: *lo,
                                hi: *hi,
                            },
                        };
                        // The value that does not fit is where it faults.
                        if crate::faults::node_may_fault(&self.a.types, &v) {
                            v = located(self.line_col(self.ast.expr(*value).span), v);
                        }
                    }
                }
                out.push(at(self, StmtKind::Assign { place, value: v }));
                out.append(&mut self.post);
            }
            SK::Call(e) => {
                let k = self.call_stmt(*e);
                out.append(&mut self.pending);
                if let Some(k) = k {
                    out.push(at(self, k));
                }
                out.append(&mut self.post);
            }
            SK::If {
                branches,
                else_body,
            } => {
                let mut else_part = match else_body {
                    Some(b) => self.stmts(b),
                    None => Vec::new(),
                };
                for b in branches.iter().rev() {
                    let cond = self.expr(b.cond);
                    let mut pre = std::mem::take(&mut self.pending);
                    let then_body = self.stmts(&b.body);
                    let (line, col) = self.line_col(self.ast.expr(b.cond).span);
                    pre.push(Stmt {
                        kind: StmtKind::If {
                            cond,
                            then_body,
                            else_body: else_part,
                        },
                        line,
                        col,
                    });
                    else_part = pre;
                }
                out.extend(else_part);
            }
            SK::Case {
                selector,
                arms,
                else_body,
            } => {
                let sel = self.expr(*selector);
                out.append(&mut self.pending);
                let mut out_arms = Vec::new();
                for arm in arms {
                    let mut ranges = Vec::new();
                    for l in &arm.labels {
                        let (a, b) = match l {
                            ast::CaseLabel::Value(v) => (*v, *v),
                            ast::CaseLabel::Range(a, b) => (*a, *b),
                        };
                        if let (Some(Value::Int(x)), Some(Value::Int(y))) =
                            (self.a.consts.get(&a), self.a.consts.get(&b))
                        {
                            ranges.push(((*x).min(*y), (*x).max(*y)));
                        }
                    }
                    out_arms.push(crate::SwitchArm {
                        ranges,
                        body: self.stmts(&arm.body),
                    });
                }
                let default = match else_body {
                    Some(b) => self.stmts(b),
                    None => Vec::new(),
                };
                out.push(at(
                    self,
                    StmtKind::Switch {
                        selector: sel,
                        arms: out_arms,
                        default,
                    },
                ));
            }
            SK::For {
                var,
                from,
                to,
                by,
                body,
            } => self.for_loop(s, *var, *from, *to, *by, body, out),
            SK::While { cond, body } => {
                let c = self.expr(*cond);
                let mut b = std::mem::take(&mut self.pending);
                b.push(self.stmt_at(
                    self.ast.expr(*cond).span,
                    StmtKind::If {
                        cond: c,
                        then_body: Vec::new(),
                        else_body: vec![self.stmt_at(s.span, StmtKind::Break)],
                    },
                ));
                b.extend(self.stmts(body));
                out.push(at(
                    self,
                    StmtKind::Loop {
                        body: b,
                        latch: Vec::new(),
                    },
                ));
            }
            SK::Repeat { body, until } => {
                let b = self.stmts(body);
                let c = self.expr(*until);
                let mut latch = std::mem::take(&mut self.pending);
                latch.push(self.stmt_at(
                    self.ast.expr(*until).span,
                    StmtKind::If {
                        cond: c,
                        then_body: vec![self.stmt_at(s.span, StmtKind::Break)],
                        else_body: Vec::new(),
                    },
                ));
                out.push(at(self, StmtKind::Loop { body: b, latch }));
            }
            SK::Exit => out.push(at(self, StmtKind::Break)),
            SK::Continue => out.push(at(self, StmtKind::Continue)),
            SK::Return => out.push(at(self, StmtKind::Return)),
        }
    }

    /// FOR, per spec/semantics.md: bounds and step evaluated once; the loop
    /// runs while `i <= end` (step > 0) or `i >= end` (step < 0); the control
    /// variable never overflows: when the next value would, the loop ends
    /// with the last value for which the body ran.
    #[allow(clippy::too_many_arguments)]
    fn for_loop(
        &mut self,
        s: &'a ast::Stmt,
        var: ast::Ident,
        from: ExprId,
        to: ExprId,
        by: Option<ExprId>,
        body: &'a [ast::Stmt],
        out: &mut Vec<Stmt>,
    ) {
        let Some(v) = self.a.pou(self.pou).lookup(var.sym) else {
            return;
        };
        let ty = self.vars[v].ty;
        let Some(elem) = self.a.types.numeric(ty) else {
            return;
        };
        let (min, max) = stc_values::int_range(elem).unwrap_or((0, 0));
        let place = |v: VarId| Place {
            root: Root::Var(v),
            proj: vec![],
            ty,
        };
        let load = |v: VarId| Expr {
            kind: ExprKind::Load(place(v)),
            ty,
        };
        let konst = |x: i128| Expr {
            kind: ExprKind::Const(Value::Int(x)),
            ty,
        };
        let bool_ty = self.bool_ty();
        let bin = |op: BinOp, a: Expr, b: Expr, t: TypeId| Expr {
            kind: ExprKind::Binary(op, Box::new(a), Box::new(b)),
            ty: t,
        };
        let at = |l: &Self, k| l.stmt_at(s.span, k);

        let start = self.expr(from);
        out.append(&mut self.pending);
        out.push(at(
            self,
            StmtKind::Assign {
                place: place(v),
                value: start,
            },
        ));
        let end_var = self.hidden(var.sym, "end", ty, Storage::Frame, var.span);
        let end = self.expr(to);
        out.append(&mut self.pending);
        out.push(at(
            self,
            StmtKind::Assign {
                place: place(end_var),
                value: end,
            },
        ));
        let step_const = match by {
            Some(b) => match self.a.consts.get(&b) {
                Some(Value::Int(x)) => Some(*x),
                _ => None,
            },
            None => Some(1),
        };
        let (test, overflow, step_expr) = match step_const {
            Some(st) if st > 0 => (
                bin(BinOp::Gt, load(v), load(end_var), bool_ty),
                bin(BinOp::Gt, load(v), konst(max - st), bool_ty),
                konst(st),
            ),
            Some(st) => (
                bin(BinOp::Lt, load(v), load(end_var), bool_ty),
                bin(BinOp::Lt, load(v), konst(min - st), bool_ty),
                konst(st),
            ),
            None => {
                let step_var = self.hidden(var.sym, "step", ty, Storage::Frame, var.span);
                let b = by.map(|b| self.expr(b)).unwrap_or_else(|| konst(1));
                out.append(&mut self.pending);
                out.push(at(
                    self,
                    StmtKind::Assign {
                        place: place(step_var),
                        value: b,
                    },
                ));
                out.push(at(
                    self,
                    StmtKind::If {
                        cond: bin(BinOp::Eq, load(step_var), konst(0), bool_ty),
                        then_body: vec![at(self, StmtKind::Fault(FaultKind::ForStepZero))],
                        else_body: Vec::new(),
                    },
                ));
                let up = bin(BinOp::Gt, load(step_var), konst(0), bool_ty);
                let test = if min < 0 {
                    let down = bin(BinOp::Lt, load(step_var), konst(0), bool_ty);
                    bin(
                        BinOp::Or,
                        bin(
                            BinOp::And,
                            up.clone(),
                            bin(BinOp::Gt, load(v), load(end_var), bool_ty),
                            bool_ty,
                        ),
                        bin(
                            BinOp::And,
                            down.clone(),
                            bin(BinOp::Lt, load(v), load(end_var), bool_ty),
                            bool_ty,
                        ),
                        bool_ty,
                    )
                } else {
                    bin(BinOp::Gt, load(v), load(end_var), bool_ty)
                };
                let overflow = if min < 0 {
                    let down = bin(BinOp::Lt, load(step_var), konst(0), bool_ty);
                    bin(
                        BinOp::Or,
                        bin(
                            BinOp::And,
                            up,
                            bin(
                                BinOp::Gt,
                                load(v),
                                bin(BinOp::Sub, konst(max), load(step_var), ty),
                                bool_ty,
                            ),
                            bool_ty,
                        ),
                        bin(
                            BinOp::And,
                            down,
                            bin(
                                BinOp::Lt,
                                load(v),
                                bin(BinOp::Sub, konst(min), load(step_var), ty),
                                bool_ty,
                            ),
                            bool_ty,
                        ),
                        bool_ty,
                    )
                } else {
                    bin(
                        BinOp::Gt,
                        load(v),
                        bin(BinOp::Sub, konst(max), load(step_var), ty),
                        bool_ty,
                    )
                };
                (test, overflow, load(step_var))
            }
        };
        let mut loop_body = vec![at(
            self,
            StmtKind::If {
                cond: test,
                then_body: vec![at(self, StmtKind::Break)],
                else_body: Vec::new(),
            },
        )];
        loop_body.extend(self.stmts(body));
        // With a constant step and a constant end the next value cannot
        // overflow when the end leaves room for one more step: in the latch
        // the control variable is at most the end (the body cannot change
        // it, E0306), so the overflow test is left out.
        let end_const = match self.a.consts.get(&to) {
            Some(Value::Int(e)) => Some(*e),
            _ => None,
        };
        let no_overflow = match (step_const, end_const) {
            (Some(st), Some(e)) if st > 0 => e <= max - st,
            (Some(st), Some(e)) if st < 0 => e >= min - st,
            _ => false,
        };
        let mut latch = Vec::new();
        if !no_overflow {
            latch.push(at(
                self,
                StmtKind::If {
                    cond: overflow,
                    then_body: vec![at(self, StmtKind::Break)],
                    else_body: Vec::new(),
                },
            ));
        }
        latch.push(at(
            self,
            StmtKind::Assign {
                place: place(v),
                value: bin(BinOp::Add, load(v), step_expr, ty),
            },
        ));
        out.push(at(
            self,
            StmtKind::Loop {
                body: loop_body,
                latch,
            },
        ));
    }

    /// A call used as a statement; `None` when everything it does is in
    /// `self.pending` (a call with EN or ENO).
    fn call_stmt(&mut self, e: ExprId) -> Option<StmtKind> {
        let Some(info) = self.a.calls.get(&e) else {
            return Some(StmtKind::Eval(self.expr(e)));
        };
        if info.en.is_some() || info.eno.is_some() {
            let stmts = self.gated_call(e, info, false).0;
            self.pending.extend(stmts);
            return None;
        }
        match &info.target {
            CallTarget::FbInstance(fb) => {
                let AK::Call { callee, .. } = &self.ast.expr(e).kind else {
                    return Some(StmtKind::Eval(self.expr(e)));
                };
                let instance = self.place(*callee);
                let (inputs, mut inouts, outputs) = self.bind(&info.args);
                self.fix_inouts(*fb, &mut inouts);
                Some(StmtKind::CallFb {
                    instance,
                    fb: *fb,
                    inputs,
                    inouts,
                    outputs,
                })
            }
            CallTarget::Method { method, this } => {
                let ty = self.a.expr_type(e);
                match self.method_call(e, info, *method, *this, ty) {
                    Ok(kind) => Some(StmtKind::Eval(Expr { kind, ty })),
                    // (Its value, if any, is not used.)
                    Err(_) => None,
                }
            }
            CallTarget::Std {
                intrinsic: f @ (Intrinsic::SplitDate | Intrinsic::SplitTod | Intrinsic::SplitDt),
                ..
            } => {
                self.split_call(e, info, *f);
                None
            }
            _ => Some(StmtKind::Eval(self.expr(e))),
        }
    }

    /// Whether a POU's EN or ENO variable has storage (declared by the
    /// user, or implicit and referred to).
    fn control_var(&self, q: PouId, v: Option<VarId>) -> Option<VarId> {
        let v = v?;
        let def = self.a.pou(q);
        (!def.var(v).implicit || self.keeps[q.0 as usize]).then_some(v)
    }

    /// A call with EN or ENO (ed2 2.5.1.2), as ordinary statements so that
    /// back ends need nothing new:
    ///
    /// ```text
    /// IF en THEN [tmp :=] call(..., ENO => target); ELSE [tmp := default;] target := FALSE; END_IF
    /// ```
    ///
    /// When EN is FALSE no input is evaluated or assigned, the body does not
    /// run and no output is copied. A callee whose ENO has no storage (its
    /// body never sets it) gives TRUE. With `want`, the function's value is
    /// left in a temporary, which is returned.
    fn gated_call(
        &mut self,
        e: ExprId,
        info: &'a CallInfo,
        want: bool,
    ) -> (Vec<Stmt>, Option<Expr>) {
        let span = self.ast.expr(e).span;
        let ty = self.a.expr_type(e);
        let bool_ty = self.bool_ty();
        let konst_bool = |b: bool| Expr {
            kind: ExprKind::Const(Value::Bool(b)),
            ty: bool_ty,
        };
        let outer = std::mem::take(&mut self.pending);
        let cond = info.en.map(|c| self.expr(c));
        let mut out = std::mem::take(&mut self.pending);

        // The call, when EN is TRUE.
        let callee_name = match (&info.target, &self.ast.expr(e).kind) {
            (
                CallTarget::Function(q)
                | CallTarget::FbInstance(q)
                | CallTarget::Method { method: q, .. },
                _,
            ) => self.a.pou(*q).name,
            (_, AK::Call { callee, .. }) => match &self.ast.expr(*callee).kind {
                AK::Name(id) => id.sym,
                _ => self.a.pou(self.pou).name,
            },
            _ => self.a.pou(self.pou).name,
        };
        let result = (want && ty != TypeId::VOID && ty != TypeId::ERROR)
            .then(|| self.hidden(callee_name, "result", ty, Storage::Frame, span));
        let mut eno_const = info.eno.is_some();
        let mut else_resets: Vec<Place> = Vec::new();
        let call = match &info.target {
            CallTarget::Function(q) | CallTarget::FbInstance(q) => {
                let q = *q;
                let def = self.a.pou(q);
                let (mut inputs, mut inouts, mut outputs) = self.bind(&info.args);
                self.fix_inouts(q, &mut inouts);
                if let Some(en) = self.control_var(q, def.en) {
                    inputs.push((en, konst_bool(true)));
                }
                if let (Some(eno), Some((target, negated))) =
                    (self.control_var(q, def.eno), info.eno)
                {
                    eno_const = false;
                    outputs.push(crate::Output {
                        var: eno,
                        target: self.place(target),
                        negated,
                    });
                }
                match &info.target {
                    CallTarget::FbInstance(fb) => {
                        let AK::Call { callee, .. } = &self.ast.expr(e).kind else {
                            self.pending = outer;
                            return (Vec::new(), None);
                        };
                        let instance = self.place(*callee);
                        // When EN is FALSE the instance's own EN and ENO
                        // are FALSE.
                        for v in [def.en, def.eno] {
                            if let Some(v) = self.control_var(q, v) {
                                let mut p = instance.clone();
                                p.proj.push(Proj::FbVar(*fb, v));
                                p.ty = bool_ty;
                                else_resets.push(p);
                            }
                        }
                        StmtKind::CallFb {
                            instance,
                            fb: *fb,
                            inputs,
                            inouts,
                            outputs,
                        }
                    }
                    _ => {
                        let value = Expr {
                            kind: ExprKind::CallFn {
                                func: q,
                                inputs,
                                inouts,
                                outputs,
                            },
                            ty,
                        };
                        match result {
                            Some(r) => StmtKind::Assign {
                                place: self.var_place(r, ty),
                                value,
                            },
                            None => StmtKind::Eval(value),
                        }
                    }
                }
            }
            CallTarget::Std { intrinsic, .. } => {
                let values: Vec<ExprId> = info
                    .args
                    .iter()
                    .map(|a| match &a.kind {
                        BoundArgKind::Input(x)
                        | BoundArgKind::InOut(x)
                        | BoundArgKind::Output { target: x, .. } => *x,
                    })
                    .collect();
                let args = self.seq(&values);
                let value = self.intrinsic(*intrinsic, args, ty);
                match result {
                    Some(r) => StmtKind::Assign {
                        place: self.var_place(r, ty),
                        value,
                    },
                    None => StmtKind::Eval(value),
                }
            }
            CallTarget::CurTime | CallTarget::Ref | CallTarget::Adr | CallTarget::Method { .. } => {
                // (REF and method calls never have EN/ENO: the analyser
                // binds none, so they never come here.)
                let value = Expr {
                    kind: ExprKind::CurTime,
                    ty,
                };
                match result {
                    Some(r) => StmtKind::Assign {
                        place: self.var_place(r, ty),
                        value,
                    },
                    None => StmtKind::Eval(value),
                }
            }
        };
        let mut then_body = std::mem::take(&mut self.pending);
        then_body.push(self.stmt_at(span, call));
        let eno = info.eno;
        if let (true, Some((target, negated))) = (eno_const, eno) {
            let place = self.place(target);
            then_body.append(&mut self.pending);
            then_body.push(self.stmt_at(
                span,
                StmtKind::Assign {
                    place,
                    value: konst_bool(!negated),
                },
            ));
        }
        match cond {
            // No EN, or EN := TRUE: the call runs.
            None
            | Some(Expr {
                kind: ExprKind::Const(Value::Bool(true)),
                ..
            }) => out.extend(then_body),
            Some(cond) => {
                let mut else_body = Vec::new();
                if let Some(r) = result {
                    let default = self.default_of(e, ty, &info.target);
                    else_body.push(self.stmt_at(
                        span,
                        StmtKind::Assign {
                            place: self.var_place(r, ty),
                            value: default,
                        },
                    ));
                }
                for place in else_resets {
                    else_body.push(self.stmt_at(
                        span,
                        StmtKind::Assign {
                            place,
                            value: konst_bool(false),
                        },
                    ));
                }
                if let Some((target, negated)) = eno {
                    let place = self.place(target);
                    else_body.append(&mut self.pending);
                    else_body.push(self.stmt_at(
                        span,
                        StmtKind::Assign {
                            place,
                            value: konst_bool(negated),
                        },
                    ));
                }
                out.push(self.stmt_at(
                    span,
                    StmtKind::If {
                        cond,
                        then_body,
                        else_body,
                    },
                ));
            }
        }
        self.pending = outer;
        let value = result.map(|r| Expr {
            kind: ExprKind::Load(self.var_place(r, ty)),
            ty,
        });
        (out, value)
    }

    /// The value of a function call whose EN is FALSE: its result type's
    /// default (the initial value of the callee's result variable).
    fn default_of(&mut self, e: ExprId, ty: TypeId, target: &CallTarget) -> Expr {
        let init = match target {
            CallTarget::Function(q) => self
                .a
                .pou(*q)
                .vars
                .first()
                .filter(|v| v.section == Section::Result)
                .and_then(|v| v.init.clone()),
            _ => None,
        };
        match (init, self.a.types.scalar(ty)) {
            (Some(InitValue::Scalar(v)), _) => Expr {
                kind: ExprKind::Const(v),
                ty,
            },
            (None, Some(s)) if !matches!(self.a.types.kind(ty), TypeKind::Enum { .. }) => Expr {
                kind: ExprKind::Const(stc_values::default_value(s)),
                ty,
            },
            (init, _) => {
                // An array, a structure: a temporary that is never written
                // holds the default.
                let span = self.ast.expr(e).span;
                let name = self.a.pou(self.pou).name;
                let zero = self.hidden(name, "default", ty, Storage::Frame, span);
                if let Some(slot) = self.vars.get_mut(zero.0 as usize) {
                    slot.init = init;
                }
                Expr {
                    kind: ExprKind::Load(self.var_place(zero, ty)),
                    ty,
                }
            }
        }
    }

    fn var_place(&self, v: VarId, ty: TypeId) -> Place {
        Place {
            root: Root::Var(v),
            proj: vec![],
            ty,
        }
    }

    /// Lowers expressions in evaluation order. When one of them takes a
    /// call out into `self.pending` (a call with EN), the ones before it are
    /// stored in temporaries first, so they are still evaluated before it.
    fn seq(&mut self, es: &[ExprId]) -> Vec<Expr> {
        let mut done: Vec<Expr> = Vec::with_capacity(es.len());
        for &e in es {
            let mark = self.pending.len();
            let x = self.expr(e);
            if self.pending.len() > mark {
                self.spill(&mut done, mark);
            }
            done.push(x);
        }
        done
    }

    /// Stores the values computed so far in temporaries, with the
    /// assignments inserted into `self.pending` at `mark`.
    fn spill(&mut self, done: &mut [Expr], mut mark: usize) {
        for x in done.iter_mut() {
            let stable = match &x.kind {
                ExprKind::Const(_) => true,
                ExprKind::Load(Place {
                    root: Root::Var(v),
                    proj,
                    ..
                }) => {
                    proj.is_empty()
                        && self
                            .vars
                            .get(v.0 as usize)
                            .is_some_and(|v| v.hidden.is_some())
                }
                _ => false,
            };
            if stable {
                continue;
            }
            let ty = x.ty;
            let name = self.a.pou(self.pou).name;
            let span = self.a.pou(self.pou).span;
            let t = self.hidden(name, "spill", ty, Storage::Frame, span);
            let value = std::mem::replace(
                x,
                Expr {
                    kind: ExprKind::Load(self.var_place(t, ty)),
                    ty,
                },
            );
            let (line, col) = self
                .pending
                .get(mark)
                .map(|s| (s.line, s.col))
                .unwrap_or((0, 0));
            self.pending.insert(
                mark,
                Stmt {
                    kind: StmtKind::Assign {
                        place: self.var_place(t, ty),
                        value,
                    },
                    line,
                    col,
                },
            );
            mark += 1;
        }
    }

    #[allow(clippy::type_complexity)]
    fn bind(
        &mut self,
        args: &[stc_sema::BoundArg],
    ) -> (Vec<(VarId, Expr)>, Vec<(VarId, Place)>, Vec<Output>) {
        let mut inputs: Vec<(VarId, Expr)> = Vec::new();
        let mut inouts = Vec::new();
        let mut outputs = Vec::new();
        for a in args {
            let v = VarId(a.param);
            match &a.kind {
                BoundArgKind::Input(e) => {
                    let mark = self.pending.len();
                    let x = self.expr(*e);
                    if self.pending.len() > mark {
                        let mut done: Vec<Expr> = inputs.iter().map(|(_, x)| x.clone()).collect();
                        self.spill(&mut done, mark);
                        for ((_, slot), x) in inputs.iter_mut().zip(done) {
                            *slot = x;
                        }
                    }
                    inputs.push((v, x));
                }
                BoundArgKind::InOut(e) => {
                    self.writing = true;
                    let p = self.place(*e);
                    self.writing = false;
                    inouts.push((v, p))
                }
                BoundArgKind::Output { target, negated } => {
                    self.writing = true;
                    let target = self.place(*target);
                    self.writing = false;
                    outputs.push(Output {
                        var: v,
                        target,
                        negated: *negated,
                    })
                }
            }
        }
        (inputs, inouts, outputs)
    }

    fn expr(&mut self, e: ExprId) -> Expr {
        // (A value is read: a dereference inside it is not written.)
        let writing = std::mem::replace(&mut self.writing, false);
        let x = self.value(e);
        self.writing = writing;
        x
    }

    fn value(&mut self, e: ExprId) -> Expr {
        let ty = self.a.expr_type(e);
        if self.a.null_ptrs.contains(&e) {
            return self.null_ptr();
        }
        let base = match self.a.consts.get(&e) {
            Some(v) => Expr {
                kind: ExprKind::Const(v.clone()),
                ty,
            },
            None => self.expr_kind(e, ty),
        };
        let base = self.locate_fault(e, base);
        match self.a.coercions.get(&e) {
            // An instance as an interface value: the reference to it.
            Some(&t)
                if self.a.types.ref_target(t).is_some()
                    && matches!(self.a.types.kind(ty), TypeKind::Fb(_)) =>
            {
                Expr {
                    kind: ExprKind::Ref(self.place(e)),
                    ty: t,
                }
            }
            // References of the same target type (NULL's type to any):
            // the same value.
            Some(&t) if self.a.types.ref_target(t).is_some() => Expr { ty: t, ..base },
            Some(&t) if t != ty => {
                // Constants are converted right away.
                if let ExprKind::Const(v) = &base.kind {
                    if let (Some(f), Some(to)) = (self.a.types.scalar(ty), self.a.types.scalar(t)) {
                        if let Ok(c) = stc_values::convert(f, to, v) {
                            return Expr {
                                kind: ExprKind::Const(c),
                                ty: t,
                            };
                        }
                    }
                }
                let conv = Expr {
                    kind: ExprKind::Convert(Box::new(base)),
                    ty: t,
                };
                self.locate_fault(e, conv)
            }
            _ => base,
        }
    }

    /// `x`, lowered from AST expression `e`, in an [`ExprKind::Located`]
    /// at the position of `e`'s operation when `x` may fault at its own
    /// node (so the fault names the `/`, the conversion, the call).
    fn locate_fault(&self, e: ExprId, x: Expr) -> Expr {
        if !crate::faults::node_may_fault(&self.a.types, &x) {
            return x;
        }
        let at = self.op_position(e);
        located(at, x)
    }

    /// Where the operation of `e` is written: a binary operator's own
    /// token, else the start of the expression (a call's name, a unary
    /// operator).
    fn op_position(&self, e: ExprId) -> (u32, u32) {
        let node = self.ast.expr(e);
        if let AK::Binary { lhs, rhs, .. } = &node.kind {
            let (l, r) = (self.ast.expr(*lhs).span, self.ast.expr(*rhs).span);
            if l.hi <= r.lo {
                let between = self.sources.slice(Span::new(l.hi, r.lo));
                let skip = between.len() - between.trim_start().len();
                if skip < between.len() {
                    return self.line_col(Span::new(l.hi + skip as u32, r.lo));
                }
            }
        }
        self.line_col(node.span)
    }

    fn expr_kind(&mut self, e: ExprId, ty: TypeId) -> Expr {
        let kind = match &self.ast.expr(e).kind {
            AK::Paren(i) => return self.expr(*i),
            AK::Unary {
                op: ast::UnaryOp::Plus,
                operand,
            } => return self.expr(*operand),
            AK::Unary { op, operand } => {
                let o = self.expr(*operand);
                ExprKind::Unary(
                    if *op == ast::UnaryOp::Neg {
                        UnOp::Neg
                    } else {
                        UnOp::Not
                    },
                    Box::new(o),
                )
            }
            AK::Binary { op, lhs, rhs }
                if self.is_ptr(self.a.expr_type(*lhs)) || self.is_ptr(self.a.expr_type(*rhs)) =>
            {
                return self.ptr_binary(e, *op, *lhs, *rhs);
            }
            AK::Binary { op, lhs, rhs } => {
                let mut l = [self.expr(*lhs)];
                let mark = self.pending.len();
                let r = self.expr(*rhs);
                if self.pending.len() > mark {
                    self.spill(&mut l, mark);
                }
                let [l] = l;
                ExprKind::Binary(bin_op(*op), Box::new(l), Box::new(r))
            }
            AK::Call { .. } => return self.call_expr(e, ty),
            // A property read: its GET.
            AK::Name(_) | AK::Member { .. } if self.a.calls.contains_key(&e) => {
                return self.call_expr(e, ty)
            }
            AK::Name(_)
            | AK::Member { .. }
            | AK::Index { .. }
            | AK::PartialAccess { .. }
            | AK::Address(_) => match self.a.resolutions.get(&e) {
                Some(Res::EnumValue(t, i)) => {
                    let v = match self.a.types.kind(*t) {
                        TypeKind::Enum { values, .. } => {
                            values.get(*i as usize).map(|v| v.value).unwrap_or(0)
                        }
                        _ => 0,
                    };
                    ExprKind::Const(Value::Int(v))
                }
                None if self.a.types.ref_target(ty) == Some(TypeId::VOID) => ExprKind::Null,
                // (`SUPER`: the same reference, of the base's type.)
                Some(Res::This | Res::Super) => ExprKind::Ref(self.this_place()),
                _ => ExprKind::Load(self.place(e)),
            },
            AK::IlCr => ExprKind::Load(self.cr_place(ty)),
            AK::Deref(_) => ExprKind::Load(self.place(e)),
            AK::Literal(_) | AK::EnumValue { .. } | AK::Error => ExprKind::Const(Value::Int(0)),
        };
        Expr { kind, ty }
    }

    fn call_expr(&mut self, e: ExprId, ty: TypeId) -> Expr {
        let Some(info) = self.a.calls.get(&e) else {
            return Expr {
                kind: ExprKind::Const(Value::Int(0)),
                ty,
            };
        };
        if info.en.is_some() || info.eno.is_some() {
            let (stmts, value) = self.gated_call(e, info, true);
            self.pending.extend(stmts);
            return value.unwrap_or(Expr {
                kind: ExprKind::Const(Value::Int(0)),
                ty,
            });
        }
        let kind = match &info.target {
            CallTarget::Function(f) => {
                let (inputs, mut inouts, outputs) = self.bind(&info.args);
                self.fix_inouts(*f, &mut inouts);
                ExprKind::CallFn {
                    func: *f,
                    inputs,
                    inouts,
                    outputs,
                }
            }
            CallTarget::CurTime => ExprKind::CurTime,
            CallTarget::Method { method, this } => {
                match self.method_call(e, info, *method, *this, ty) {
                    Ok(kind) => kind,
                    Err(value) => {
                        return value.unwrap_or(Expr {
                            kind: ExprKind::Const(Value::Int(0)),
                            ty,
                        })
                    }
                }
            }
            CallTarget::Ref => match info.args.first().map(|a| &a.kind) {
                Some(BoundArgKind::Input(x)) => ExprKind::Ref(self.place(*x)),
                _ => ExprKind::Null,
            },
            CallTarget::Adr => match self.adr_arg(info) {
                Some(x) => return self.adr(e, x),
                None => ExprKind::Const(Value::Int(0)),
            },
            CallTarget::FbInstance(_) => ExprKind::Const(Value::Int(0)),
            CallTarget::Std { intrinsic, .. } => {
                let values: Vec<ExprId> = info
                    .args
                    .iter()
                    .map(|a| match &a.kind {
                        BoundArgKind::Input(x)
                        | BoundArgKind::InOut(x)
                        | BoundArgKind::Output { target: x, .. } => *x,
                    })
                    .collect();
                let args = self.seq(&values);
                return self.intrinsic(*intrinsic, args, ty);
            }
        };
        Expr { kind, ty }
    }

    /// Standard functions: operators in functional form become operators,
    /// conversions become conversions.
    fn intrinsic(&mut self, f: Intrinsic, mut args: Vec<Expr>, ty: TypeId) -> Expr {
        let bool_ty = self.bool_ty();
        if matches!(
            f,
            Intrinsic::Shl | Intrinsic::Shr | Intrinsic::Rol | Intrinsic::Ror
        ) && args.len() == 2
        {
            return self.shift(f, args, ty);
        }
        let op = match f {
            Intrinsic::Add => Some(BinOp::Add),
            Intrinsic::Sub => Some(BinOp::Sub),
            Intrinsic::Mul => Some(BinOp::Mul),
            Intrinsic::Div => Some(BinOp::Div),
            Intrinsic::Mod => Some(BinOp::Mod),
            Intrinsic::And => Some(BinOp::And),
            Intrinsic::Or => Some(BinOp::Or),
            Intrinsic::Xor => Some(BinOp::Xor),
            _ => None,
        };
        if let Some(op) = op {
            let mut it = args.into_iter();
            let first = it.next().unwrap_or(Expr {
                kind: ExprKind::Const(Value::Int(0)),
                ty,
            });
            return it.fold(first, |acc, x| Expr {
                kind: ExprKind::Binary(op, Box::new(acc), Box::new(x)),
                ty,
            });
        }
        let cmp = match f {
            Intrinsic::Gt => Some(BinOp::Gt),
            Intrinsic::Ge => Some(BinOp::Ge),
            Intrinsic::Eq => Some(BinOp::Eq),
            Intrinsic::Le => Some(BinOp::Le),
            Intrinsic::Lt => Some(BinOp::Lt),
            Intrinsic::Ne => Some(BinOp::Ne),
            _ => None,
        };
        if let Some(op) = cmp {
            // GT(a, b, c) is a > b AND b > c.
            let mut acc: Option<Expr> = None;
            for w in args.windows(2) {
                let c = Expr {
                    kind: ExprKind::Binary(op, Box::new(w[0].clone()), Box::new(w[1].clone())),
                    ty: bool_ty,
                };
                acc = Some(match acc {
                    None => c,
                    Some(a) => Expr {
                        kind: ExprKind::Binary(BinOp::And, Box::new(a), Box::new(c)),
                        ty: bool_ty,
                    },
                });
            }
            return acc.unwrap_or(Expr {
                kind: ExprKind::Const(Value::Bool(true)),
                ty: bool_ty,
            });
        }
        match f {
            Intrinsic::Not if args.len() == 1 => Expr {
                kind: ExprKind::Unary(UnOp::Not, Box::new(args.remove(0))),
                ty,
            },
            Intrinsic::Move if args.len() == 1 => args.remove(0),
            Intrinsic::Convert { .. } if args.len() == 1 => Expr {
                kind: ExprKind::Convert(Box::new(args.remove(0))),
                ty,
            },
            _ => Expr {
                kind: ExprKind::Intrinsic { func: f, args },
                ty,
            },
        }
    }

    /// SHL, SHR, ROL, ROR; of an integer (W0116) on the bit string of its
    /// width, SHR of a signed one arithmetic (`NOT SHR(NOT x, n)` when it
    /// is negative); a bit-string N as the unsigned integer of its width.
    fn shift(&mut self, f: Intrinsic, mut args: Vec<Expr>, ty: TypeId) -> Expr {
        use stc_values::{is_bit_string, is_integer, is_signed};
        let bits_of = |size: u32| match size {
            1 => ElemType::Byte,
            2 => ElemType::Word,
            4 => ElemType::Dword,
            _ => ElemType::Lword,
        };
        let unsigned_of = |size: u32| match size {
            1 => ElemType::Usint,
            2 => ElemType::Uint,
            4 => ElemType::Udint,
            _ => ElemType::Ulint,
        };
        let convert = |x: Expr, to: TypeId| Expr {
            kind: ExprKind::Convert(Box::new(x)),
            ty: to,
        };
        let n = args.pop().unwrap_or(Expr {
            kind: ExprKind::Const(Value::Int(0)),
            ty,
        });
        let x = args.pop().unwrap_or(Expr {
            kind: ExprKind::Const(Value::Int(0)),
            ty,
        });
        let n = match self.a.types.scalar(n.ty) {
            Some(s) if is_bit_string(s) && s != ElemType::Bool => {
                let to = self.elem_ty(unsigned_of(crate::layout::elem_size(s)));
                convert(n, to)
            }
            _ => n,
        };
        let Some(s) = self.a.types.scalar(x.ty).filter(|s| is_integer(*s)) else {
            return Expr {
                kind: ExprKind::Intrinsic {
                    func: f,
                    args: vec![x, n],
                },
                ty,
            };
        };
        let b = self.elem_ty(bits_of(crate::layout::elem_size(s)));
        let int_ty = x.ty;
        let shift = |x: Expr, n: Expr| Expr {
            kind: ExprKind::Intrinsic {
                func: f,
                args: vec![x, n],
            },
            ty: b,
        };
        let not = |x: Expr| Expr {
            kind: ExprKind::Unary(UnOp::Not, Box::new(x)),
            ty: b,
        };
        let bits = if f == Intrinsic::Shr && is_signed(s) {
            // (x and n are read twice: they are spilled when not plain.)
            let mut done = [x, n];
            for v in done.iter_mut() {
                if !matches!(v.kind, ExprKind::Const(_) | ExprKind::Load(_)) {
                    let name = self.a.pou(self.pou).name;
                    let span = self.a.pou(self.pou).span;
                    let t = self.hidden(name, "shift", v.ty, Storage::Frame, span);
                    let value = std::mem::replace(
                        v,
                        Expr {
                            kind: ExprKind::Load(self.var_place(t, v.ty)),
                            ty: v.ty,
                        },
                    );
                    self.pending.push(Stmt {
                        kind: StmtKind::Assign {
                            place: self.var_place(t, value.ty),
                            value,
                        },
                        line: 0,
                        col: 0,
                    });
                }
            }
            let [x, n] = done;
            let negative = Expr {
                kind: ExprKind::Binary(
                    BinOp::Lt,
                    Box::new(x.clone()),
                    Box::new(Expr {
                        kind: ExprKind::Const(Value::Int(0)),
                        ty: int_ty,
                    }),
                ),
                ty: self.bool_ty(),
            };
            let plain = shift(convert(x.clone(), b), n.clone());
            let filled = not(shift(not(convert(x, b)), n));
            Expr {
                kind: ExprKind::Intrinsic {
                    func: Intrinsic::Sel,
                    args: vec![negative, plain, filled],
                },
                ty: b,
            }
        } else {
            shift(convert(x, b), n)
        };
        convert(bits, ty)
    }

    /// Whether an expression is `THIS` (in parentheses or not).
    fn is_this(&self, e: ExprId) -> bool {
        match &self.ast.expr(e).kind {
            AK::Paren(i) => self.is_this(*i),
            AK::Name(_) => matches!(self.a.resolutions.get(&e), Some(Res::This)),
            _ => false,
        }
    }

    /// The running function block instance: in a METHOD its hidden
    /// in-out, in the block's body the instance itself.
    fn this_place(&self) -> Place {
        let def = self.a.pou(self.pou);
        if let Some(t) = def.this {
            return Place {
                root: Root::Var(t),
                proj: vec![],
                ty: def.var(t).ty,
            };
        }
        let me = self.pou;
        let ty = (0..self.a.types.len() as u32)
            .map(TypeId)
            .find(|t| matches!(self.a.types.kind(*t), TypeKind::Fb(q) if *q == me))
            .unwrap_or(TypeId::ERROR);
        Place {
            root: Root::This,
            proj: vec![],
            ty,
        }
    }

    fn place(&mut self, e: ExprId) -> Place {
        let ty = self.a.expr_type(e);
        if let Some((p, indices)) = self.ptr_deref_parts(e) {
            return self.ptr_deref(e, p, indices, ty);
        }
        if matches!(self.ast.expr(e).kind, AK::Name(_) | AK::Member { .. })
            && self.a.calls.contains_key(&e)
        {
            // A property read where a variable could stand: its value in
            // a temporary.
            let x = self.call_expr(e, ty);
            let name = self.a.pou(self.pou).name;
            let span = self.ast.expr(e).span;
            let t = self.hidden(name, "property", ty, Storage::Frame, span);
            let set = self.stmt_at(
                span,
                StmtKind::Assign {
                    place: self.var_place(t, ty),
                    value: x,
                },
            );
            self.pending.push(set);
            return self.var_place(t, ty);
        }
        match &self.ast.expr(e).kind {
            AK::Paren(i) => self.place(*i),
            AK::Address(a) => Place {
                root: Root::Direct((**a).clone()),
                proj: vec![],
                ty,
            },
            AK::Name(_) => match self.a.resolutions.get(&e) {
                Some(Res::Var(v)) => Place {
                    root: Root::Var(*v),
                    proj: vec![],
                    ty,
                },
                Some(Res::Global(g)) => Place {
                    root: Root::Global(*g),
                    proj: vec![],
                    ty,
                },
                // In a METHOD: a variable of its instance.
                Some(Res::FbMember(fb, v)) => {
                    let mut p = self.this_place();
                    p.proj.push(Proj::FbVar(*fb, *v));
                    p.ty = ty;
                    p
                }
                _ => Place {
                    root: Root::Var(VarId(0)),
                    proj: vec![],
                    ty,
                },
            },
            // `THIS^`: the instance itself.
            AK::Deref(r) if self.is_this(*r) => {
                let mut p = self.this_place();
                p.ty = ty;
                p
            }
            AK::Deref(r) => {
                // The NULL check reports the `^` (the node's last byte).
                let hi = self.ast.expr(e).span.hi;
                let at = self.line_col(Span::new(hi.saturating_sub(1), hi));
                let r = located(at, self.expr(*r));
                Place {
                    root: Root::Deref(Box::new(r)),
                    proj: vec![],
                    ty,
                }
            }
            AK::Member { base, .. } => {
                let mut p = self.place(*base);
                match self.a.resolutions.get(&e) {
                    Some(Res::Field(i)) => p.proj.push(Proj::Field(*i)),
                    Some(Res::FbMember(fb, v)) => p.proj.push(Proj::FbVar(*fb, *v)),
                    _ => {}
                }
                p.ty = ty;
                p
            }
            AK::Index { base, indices } => {
                let mut p = self.place(*base);
                let dims = match self.a.types.kind(p.ty) {
                    TypeKind::Array { dims, .. } => dims.clone(),
                    _ => Vec::new(),
                };
                let values = self.seq(indices);
                // A checked index reports its own position.
                let idx: Vec<(Expr, i128, i128)> = values
                    .into_iter()
                    .zip(indices.iter())
                    .zip(dims.iter())
                    .map(|((i, &ie), (lo, hi))| {
                        let i = if matches!(i.kind, ExprKind::Const(_)) {
                            i
                        } else {
                            located(self.line_col(self.ast.expr(ie).span), i)
                        };
                        (i, *lo, *hi)
                    })
                    .collect();
                p.proj.push(Proj::Index(idx));
                p.ty = ty;
                p
            }
            AK::PartialAccess { base, size, index } => {
                let mut p = self.place(*base);
                // A part of a part (`w.%B1.%X1`) is one part of the whole
                // (`w.%X9`): back ends see at most one, at the end.
                let bits = |s: stc_syntax::literal::AddrSize| s.bits().max(1);
                match p.proj.last_mut() {
                    Some(Proj::Part(outer, at)) if bits(*size) <= bits(*outer) => {
                        let per = bits(*outer) / bits(*size);
                        *at = *at * per + *index;
                        *outer = *size;
                    }
                    _ => p.proj.push(Proj::Part(*size, *index)),
                }
                p.ty = ty;
                p
            }
            _ => Place {
                root: Root::Var(VarId(0)),
                proj: vec![],
                ty,
            },
        }
    }
}

fn bin_op(op: ast::BinaryOp) -> BinOp {
    use ast::BinaryOp as B;
    match op {
        B::Or => BinOp::Or,
        B::Xor => BinOp::Xor,
        B::And => BinOp::And,
        B::Eq => BinOp::Eq,
        B::Ne => BinOp::Ne,
        B::Lt => BinOp::Lt,
        B::Le => BinOp::Le,
        B::Gt => BinOp::Gt,
        B::Ge => BinOp::Ge,
        B::Add => BinOp::Add,
        B::Sub => BinOp::Sub,
        B::Mul => BinOp::Mul,
        B::Div => BinOp::Div,
        B::Mod => BinOp::Mod,
        B::Pow => BinOp::Pow,
    }
}

/// `x` in an [`ExprKind::Located`] at `(line, col)`.
fn located((line, col): (u32, u32), x: Expr) -> Expr {
    Expr {
        ty: x.ty,
        kind: ExprKind::Located {
            line,
            col,
            expr: Box::new(x),
        },
    }
}

#[cfg(test)]
mod tests {
    use stc_diagnostics::SourceMap;

    /// The IR dump of a valid program (no prelude).
    fn ir(src: &str) -> String {
        let mut sm = SourceMap::new();
        sm.add("t.st", src.to_string()).expect("small source");
        let mut interner = stc_syntax::Interner::new();
        let (ast, diags) = stc_syntax::parse_project(&sm, &mut interner);
        assert!(diags.is_empty(), "{diags:?}");
        let a = stc_sema::analyze(&ast, &mut interner, &sm, None, Default::default());
        assert!(a.diagnostics.is_empty(), "{:?}", a.diagnostics);
        let m = super::lower(&ast, a, &interner, &sm);
        crate::dump::dump(&m, false)
    }

    /// The dump without the `@line` markers, for comparing shapes.
    fn shape(src: &str) -> String {
        ir(src)
            .lines()
            .map(|l| l.split("  @").next().unwrap_or(l).trim_end())
            .collect::<Vec<_>>()
            .join("\n")
    }

    const HALF: &str = "FUNCTION Half : INT
VAR_INPUT x : INT; END_VAR
  Half := x / 2;
END_FUNCTION
";

    #[test]
    fn en_and_eno_cost_nothing_when_unused() {
        let out = shape(&format!(
            "{HALF}PROGRAM P VAR r : INT; END_VAR r := Half(x := 4); END_PROGRAM"
        ));
        assert!(
            !out.contains("input EN") && !out.contains("output ENO"),
            "{out}"
        );
        assert!(out.contains("r := Half(x := 4:INT):INT"), "{out}");
    }

    #[test]
    fn a_call_with_en_runs_only_when_en_is_true() {
        let out = shape(&format!(
            "{HALF}PROGRAM P VAR go : BOOL; ok : BOOL; r : INT; END_VAR
  r := Half(EN := go, x := 4, ENO => ok);
END_PROGRAM"
        ));
        let want = "  if go
    Half$result := Half(x := 4:INT):INT
    ok := TRUE:BOOL
  else
    Half$result := 0:INT
    ok := FALSE:BOOL
  end
  r := Half$result";
        assert!(out.contains(want), "{out}");
        // The callee never sets ENO: it needs no variable.
        assert!(!out.contains("output ENO"), "{out}");
    }

    #[test]
    fn eno_set_in_the_body_is_an_output_reset_every_call() {
        let out = shape(
            "FUNCTION_BLOCK Fb
VAR_INPUT x : INT; END_VAR
  IF x < 0 THEN ENO := FALSE; END_IF;
END_FUNCTION_BLOCK
PROGRAM P VAR f : Fb; go : BOOL; ok : BOOL; END_VAR
  f(EN := go, x := 1, ENO => ok);
END_PROGRAM",
        );
        assert!(
            out.contains("  output ENO : BOOL\n  ENO := TRUE:BOOL"),
            "{out}"
        );
        let want = "  if go
    call f(x := 1:INT, EN := TRUE:BOOL, ENO => ok) : Fb
  else
    f.EN := FALSE:BOOL
    f.ENO := FALSE:BOOL
    ok := FALSE:BOOL
  end";
        assert!(out.contains(want), "{out}");
    }

    #[test]
    fn standard_functions_take_en_and_eno_too() {
        let out = shape(
            "PROGRAM P VAR go : BOOL; ok : BOOL; r : INT; END_VAR
  r := ADD(EN := go, IN1 := r, IN2 := 1, ENO => ok);
  r := MAX(IN1 := r, IN2 := 3, ENO => ok);
END_PROGRAM",
        );
        assert!(out.contains("    ADD$result := (add:INT r 1:INT)\n    ok := TRUE:BOOL\n  else\n    ADD$result := 0:INT\n    ok := FALSE:BOOL"), "{out}");
        // Without EN there is nothing to test, and ENO is TRUE.
        assert!(
            out.contains("  MAX$result := Max(r, 3:INT):INT\n  ok := TRUE:BOOL\n  r := MAX$result"),
            "{out}"
        );
    }

    #[test]
    fn operands_before_a_gated_call_are_evaluated_first() {
        let out = shape(&format!(
            "{HALF}FUNCTION Bump : INT
VAR_IN_OUT n : INT; END_VAR
  n := n + 1;
  Bump := n;
END_FUNCTION
PROGRAM P VAR go : BOOL; n : INT; r : INT; END_VAR
  r := n + Half(EN := go, x := Bump(n := n));
END_PROGRAM"
        ));
        // `n` is read before the gated call (which writes it) runs.
        let spill = out
            .find("P$spill := n")
            .expect("the left operand is spilled");
        let call = out.find("if go").expect("the gated call");
        assert!(spill < call, "{out}");
        // The inputs are evaluated only when EN is TRUE.
        assert!(
            out.contains("  if go\n    P$result := Bump(n <-> n):INT")
                || out.contains("    Half$result := Half(x := Bump(n <-> n):INT):INT"),
            "{out}"
        );
        assert!(
            out.contains("  r := (add:INT P$spill Half$result)"),
            "{out}"
        );
    }

    #[test]
    fn gated_calls_in_loop_and_elsif_conditions_stay_inside() {
        let out = shape(&format!(
            "{HALF}PROGRAM P VAR go : BOOL; n : INT; END_VAR
  WHILE Half(EN := go, x := n) > 0 DO n := n - 1; END_WHILE;
  IF n = 1 THEN n := 2; ELSIF Half(EN := go, x := n) = 3 THEN n := 4; END_IF;
END_PROGRAM"
        ));
        // The call is evaluated on every iteration, before the test.
        assert!(
            out.contains("  loop\n    if go\n      Half$result := Half(x := n):INT"),
            "{out}"
        );
        // ... and for ELSIF only when the IF condition was FALSE.
        assert!(
            out.contains("  else\n    if go\n      Half$result := Half(x := n):INT"),
            "{out}"
        );
    }

    #[test]
    fn a_structured_result_defaults_from_a_variable() {
        let out = shape(
            "TYPE Pair : STRUCT a : INT := 5; b : INT; END_STRUCT; END_TYPE
FUNCTION Mk : Pair
  Mk.b := 1;
END_FUNCTION
PROGRAM P VAR go : BOOL; q : Pair; END_VAR
  q := Mk(EN := go);
END_PROGRAM",
        );
        assert!(out.contains("    Mk$result := P$default"), "{out}");
    }
}
