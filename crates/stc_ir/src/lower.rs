//! Lowering: the analysed syntax tree to the IR.

use stc_diagnostics::{SourceMap, Span};
use stc_sema::{Analysis, BoundArgKind, CallTarget, PouId, Res, Section, TypeId, TypeKind, VarId};
use stc_syntax::ast::{self as ast, Ast, ExprId, ExprKind as AK, Item, PouKind, StmtKind as SK};
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
    let mut declare = |sym: stc_syntax::Symbol, span: Span| {
        let s = sources.slice(span);
        if !s.is_empty() && s.eq_ignore_ascii_case(interner.key(sym)) {
            if let Some(slot) = names.get_mut(sym.0 as usize) {
                *slot = s.to_string();
            }
        }
    };
    for p in &analysis.pous {
        declare(p.name, p.name_span);
        for v in &p.vars {
            declare(v.name, v.span);
        }
    }
    for g in &analysis.globals {
        declare(g.var.name, g.var.span);
    }
    for c in &analysis.configs {
        for r in &c.resources {
            for i in &r.programs {
                if let Some(s) = sources.slice(i.span).split_whitespace().nth(1) {
                    let _ = s;
                }
            }
        }
    }
    for t in 0..analysis.types.len() {
        let info = analysis.types.get(TypeId(t as u32));
        if let (Some(n), Some(span)) = (info.name, info.span) {
            let text = sources.slice(span);
            let _ = text;
            let _ = n;
        }
        if let TypeKind::Enum { values, .. } = &info.kind {
            for v in values {
                declare(v.name, v.span);
            }
        }
        if let TypeKind::Struct { fields } = &info.kind {
            for f in fields {
                declare(f.name, f.span);
            }
        }
    }
    let mut pous = Vec::with_capacity(analysis.pous.len());
    for (i, def) in analysis.pous.iter().enumerate() {
        let Item::Pou(src) = &ast.items[def.item] else {
            continue;
        };
        let mut l = Lowerer {
            ast,
            a: &analysis,
            sources,
            pou: PouId(i as u32),
            vars: Vec::new(),
        };
        pous.push(l.pou(def, src));
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
        })
        .collect();
    Module {
        types: analysis.types,
        pous,
        globals,
        configs: analysis.configs,
        names,
    }
}

struct Lowerer<'a> {
    ast: &'a Ast,
    a: &'a Analysis,
    sources: &'a SourceMap,
    pou: PouId,
    vars: Vec<Var>,
}

impl<'a> Lowerer<'a> {
    fn pou(&mut self, def: &stc_sema::PouDef, src: &'a ast::Pou) -> Pou {
        let function = def.kind == PouKind::Function;
        self.vars = def
            .vars
            .iter()
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
        let mut body = Vec::new();
        let (line, col) = self.line_col(src.span);
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
        let i = ElemType::ALL.iter().position(|&x| x == e).unwrap_or(0);
        TypeId(2 + i as u32)
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
            SK::Empty | SK::Error => {}
            SK::Assign { target, value } => {
                let place = self.place(*target);
                let mut v = self.expr(*value);
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
                    }
                }
                out.push(at(self, StmtKind::Assign { place, value: v }));
            }
            SK::Call(e) => {
                let k = self.call_stmt(*e);
                out.push(at(self, k));
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
                    let then_body = self.stmts(&b.body);
                    let (line, col) = self.line_col(self.ast.expr(b.cond).span);
                    else_part = vec![Stmt {
                        kind: StmtKind::If {
                            cond,
                            then_body,
                            else_body: else_part,
                        },
                        line,
                        col,
                    }];
                }
                out.extend(else_part);
            }
            SK::Case {
                selector,
                arms,
                else_body,
            } => {
                let sel = self.expr(*selector);
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
                let mut b = vec![self.stmt_at(
                    self.ast.expr(*cond).span,
                    StmtKind::If {
                        cond: c,
                        then_body: Vec::new(),
                        else_body: vec![self.stmt_at(s.span, StmtKind::Break)],
                    },
                )];
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
                let latch = vec![self.stmt_at(
                    self.ast.expr(*until).span,
                    StmtKind::If {
                        cond: c,
                        then_body: vec![self.stmt_at(s.span, StmtKind::Break)],
                        else_body: Vec::new(),
                    },
                )];
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
        let ty = self.vars[v.0 as usize].ty;
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
        out.push(at(
            self,
            StmtKind::Assign {
                place: place(v),
                value: start,
            },
        ));
        let end_var = self.hidden(var.sym, "end", ty, Storage::Frame, var.span);
        let end = self.expr(to);
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
        let latch = vec![
            at(
                self,
                StmtKind::If {
                    cond: overflow,
                    then_body: vec![at(self, StmtKind::Break)],
                    else_body: Vec::new(),
                },
            ),
            at(
                self,
                StmtKind::Assign {
                    place: place(v),
                    value: bin(BinOp::Add, load(v), step_expr, ty),
                },
            ),
        ];
        out.push(at(
            self,
            StmtKind::Loop {
                body: loop_body,
                latch,
            },
        ));
    }

    fn call_stmt(&mut self, e: ExprId) -> StmtKind {
        let Some(info) = self.a.calls.get(&e) else {
            return StmtKind::Eval(self.expr(e));
        };
        match &info.target {
            CallTarget::FbInstance(fb) => {
                let AK::Call { callee, .. } = &self.ast.expr(e).kind else {
                    return StmtKind::Eval(self.expr(e));
                };
                let instance = self.place(*callee);
                let (inputs, inouts, outputs) = self.bind(&info.args);
                StmtKind::CallFb {
                    instance,
                    fb: *fb,
                    inputs,
                    inouts,
                    outputs,
                }
            }
            _ => StmtKind::Eval(self.expr(e)),
        }
    }

    #[allow(clippy::type_complexity)]
    fn bind(
        &mut self,
        args: &[stc_sema::BoundArg],
    ) -> (Vec<(VarId, Expr)>, Vec<(VarId, Place)>, Vec<Output>) {
        let mut inputs = Vec::new();
        let mut inouts = Vec::new();
        let mut outputs = Vec::new();
        for a in args {
            let v = VarId(a.param);
            match &a.kind {
                BoundArgKind::Input(e) => inputs.push((v, self.expr(*e))),
                BoundArgKind::InOut(e) => inouts.push((v, self.place(*e))),
                BoundArgKind::Output { target, negated } => outputs.push(Output {
                    var: v,
                    target: self.place(*target),
                    negated: *negated,
                }),
            }
        }
        (inputs, inouts, outputs)
    }

    fn expr(&mut self, e: ExprId) -> Expr {
        let ty = self.a.expr_type(e);
        let base = match self.a.consts.get(&e) {
            Some(v) => Expr {
                kind: ExprKind::Const(v.clone()),
                ty,
            },
            None => self.expr_kind(e, ty),
        };
        match self.a.coercions.get(&e) {
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
                Expr {
                    kind: ExprKind::Convert(Box::new(base)),
                    ty: t,
                }
            }
            _ => base,
        }
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
            AK::Binary { op, lhs, rhs } => {
                let l = self.expr(*lhs);
                let r = self.expr(*rhs);
                ExprKind::Binary(bin_op(*op), Box::new(l), Box::new(r))
            }
            AK::Call { .. } => return self.call_expr(e, ty),
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
                _ => ExprKind::Load(self.place(e)),
            },
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
        let kind = match &info.target {
            CallTarget::Function(f) => {
                let (inputs, inouts, outputs) = self.bind(&info.args);
                ExprKind::CallFn {
                    func: *f,
                    inputs,
                    inouts,
                    outputs,
                }
            }
            CallTarget::CurTime => ExprKind::CurTime,
            CallTarget::FbInstance(_) => ExprKind::Const(Value::Int(0)),
            CallTarget::Std { intrinsic, .. } => {
                let args: Vec<Expr> = info
                    .args
                    .iter()
                    .map(|a| match &a.kind {
                        BoundArgKind::Input(x)
                        | BoundArgKind::InOut(x)
                        | BoundArgKind::Output { target: x, .. } => self.expr(*x),
                    })
                    .collect();
                return self.intrinsic(*intrinsic, args, ty);
            }
        };
        Expr { kind, ty }
    }

    /// Standard functions: operators in functional form become operators,
    /// conversions become conversions.
    fn intrinsic(&mut self, f: Intrinsic, mut args: Vec<Expr>, ty: TypeId) -> Expr {
        let bool_ty = self.bool_ty();
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

    fn place(&mut self, e: ExprId) -> Place {
        let ty = self.a.expr_type(e);
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
                _ => Place {
                    root: Root::Var(VarId(0)),
                    proj: vec![],
                    ty,
                },
            },
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
                let idx: Vec<(Expr, i128, i128)> = indices
                    .iter()
                    .zip(dims.iter())
                    .map(|(i, (lo, hi))| (self.expr(*i), *lo, *hi))
                    .collect();
                p.proj.push(Proj::Index(idx));
                p.ty = ty;
                p
            }
            AK::PartialAccess { base, size, index } => {
                let mut p = self.place(*base);
                p.proj.push(Proj::Part(*size, *index));
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
