//! What a Sequential Function Chart means, in Structured Text.
//!
//! The parser reads a chart ([`SfcBody`]) and hands it here; [`lower`]
//! returns the variable blocks the chart's state needs and the ST
//! statements of one cycle of the evolution rules (docs/sfc.md). Every later
//! phase sees only ST: the analyser checks it with the ST rules, the IR lowers
//! it like any body, and no back end knows charts exist.
//!
//! The state, in the POU's instance:
//! - a variable per step, named like the step, of the prelude's structure
//!   `SFC_STEP` (`X : BOOL; T : TIME`: the step flag and the step time,
//!   `S1.X`, `S1.T`); an
//!   output of a FUNCTION_BLOCK, so `inst.S1.X` is readable from outside;
//! - `SFC$$last` (the clock at the last cycle) and `SFC$$run` (a cycle ran);
//! - per transition its condition value (`SFC$$c<i>`, or the transition's
//!   name for a transition with a body, which assigns it) and, where
//!   transitions compete for a step, whether it fires (`SFC$$f<i>`) and
//!   whether the step was already taken this cycle (`SFC$$k$$<step>`);
//! - per ACTION a variable of the prelude's structure `SFC_ACTION` (`Q, A :
//!   BOOL`), named like the action beside the steps (`act.Q`, `inst.act.A`),
//!   copied from its control after each call;
//! - per action an instance of the prelude's `ACTION_CONTROL`, the
//!   standard's block (`SFC$$a$$<action>`, `SFC$$v$$<variable>`).
//!
//! An action or transition body in IL is kept whole as one
//! `StmtKind::Il` statement (a transition's stores its final current result
//! in its condition variable).
//!
//! Names with `$` cannot be written by users. References the analyser will
//! report (an unknown step, an undefined action, a second declaration of a
//! name) are left out of the meaning, so each mistake is one diagnostic.

use stc_diagnostics::Span;

use crate::ast::*;
use crate::intern::{Interner, Symbol};
use crate::token::ElemType;

/// The prelude function block that implements the action qualifiers: the
/// standard's ACTION_CONTROL, which programs may use too.
pub const ACTION_CONTROL: &str = "ACTION_CONTROL";

/// The prelude structure of a step's flags, `X : BOOL; T : TIME`.
pub const STEP_TYPE: &str = "SFC_STEP";

/// The prelude structure of an action's flags, `Q : BOOL; A : BOOL`.
pub const ACTION_TYPE: &str = "SFC_ACTION";

/// The steps, actions and transitions of a chart, first declaration of each
/// name only.
pub struct ChartNames<'a> {
    pub steps: Vec<&'a SfcStep>,
    pub actions: Vec<&'a SfcAction>,
    pub transitions: Vec<&'a SfcTransition>,
}

impl<'a> ChartNames<'a> {
    /// The chart's names, leaving out steps, actions and named transitions
    /// with an ST body whose names are variables of the POU (`declared`: the analyser
    /// reports them).
    pub fn without(sfc: &'a SfcBody, declared: &[Symbol]) -> ChartNames<'a> {
        let mut names = ChartNames::of(sfc);
        names.steps.retain(|s| !declared.contains(&s.name.sym));
        names.actions.retain(|a| !declared.contains(&a.name.sym));
        names.transitions.retain(|t| {
            !matches!(t.cond, TransitionCond::Body(_))
                || t.name.is_none_or(|n| !declared.contains(&n.sym))
        });
        names
    }

    pub fn of(sfc: &'a SfcBody) -> ChartNames<'a> {
        let mut names = ChartNames {
            steps: Vec::new(),
            actions: Vec::new(),
            transitions: Vec::new(),
        };
        for e in &sfc.elements {
            match e {
                SfcElement::Step(s) => {
                    if !names.steps.iter().any(|o| o.name.sym == s.name.sym) {
                        names.steps.push(s);
                    }
                }
                SfcElement::Action(a) => {
                    if !names.actions.iter().any(|o| o.name.sym == a.name.sym) {
                        names.actions.push(a);
                    }
                }
                SfcElement::Transition(t) => names.transitions.push(t),
            }
        }
        names
    }

    pub fn step(&self, sym: Symbol) -> Option<&'a SfcStep> {
        self.steps.iter().copied().find(|s| s.name.sym == sym)
    }

    pub fn action(&self, sym: Symbol) -> Option<&'a SfcAction> {
        self.actions.iter().copied().find(|a| a.name.sym == sym)
    }

    /// Whether all the steps a transition names exist.
    pub fn transition_valid(&self, t: &SfcTransition) -> bool {
        t.from
            .iter()
            .chain(&t.to)
            .all(|n| self.step(n.sym).is_some())
    }
}

/// The priority of a transition: its `PRIORITY` when it is an integer
/// literal (the analyser reports anything else), else 0.
pub fn priority(ast: &Ast, t: &SfcTransition) -> u64 {
    match t.priority.map(|p| &ast.expr(p).kind) {
        Some(ExprKind::Literal(Literal {
            value: LitValue::Int { value, .. },
            ..
        })) => *value,
        _ => 0,
    }
}

/// The names declared by the POU's variable blocks.
pub fn declared(var_blocks: &[VarBlock]) -> Vec<Symbol> {
    let mut out = Vec::new();
    for b in var_blocks {
        if let VarBlockItems::Vars(vs) = &b.items {
            for v in vs {
                out.extend(v.names.iter().map(|n| n.sym));
            }
        }
    }
    out
}

struct Gen<'a> {
    ast: &'a mut Ast,
    interner: &'a mut Interner,
}

impl Gen<'_> {
    fn sym(&mut self, s: &str) -> Symbol {
        self.interner.intern(s)
    }

    fn ident(&mut self, s: &str, span: Span) -> Ident {
        Ident {
            sym: self.sym(s),
            span,
        }
    }

    fn name(&mut self, id: Ident) -> ExprId {
        self.ast.alloc(ExprKind::Name(id), id.span)
    }

    fn hidden(&mut self, role: &str, span: Span) -> ExprId {
        let id = self.ident(&format!("SFC$${role}"), span);
        self.name(id)
    }

    fn member(&mut self, base: ExprId, m: &str, span: Span) -> ExprId {
        let member = self.ident(m, span);
        self.ast.alloc(ExprKind::Member { base, member }, span)
    }

    /// `step.X` or `step.T`, at the span of the name that refers to it.
    fn flag(&mut self, step: Ident, m: &str) -> ExprId {
        let base = self.name(step);
        self.member(base, m, step.span)
    }

    fn bool(&mut self, b: bool, span: Span) -> ExprId {
        self.lit(LitValue::Bool(b), span)
    }

    fn lit(&mut self, value: LitValue, span: Span) -> ExprId {
        self.ast.alloc(
            ExprKind::Literal(Literal {
                value,
                prefix: None,
            }),
            span,
        )
    }

    fn time0(&mut self, span: Span) -> ExprId {
        self.lit(LitValue::Duration { ns: 0, long: false }, span)
    }

    fn bin(&mut self, op: BinaryOp, lhs: ExprId, rhs: ExprId, span: Span) -> ExprId {
        self.ast.alloc(ExprKind::Binary { op, lhs, rhs }, span)
    }

    fn not(&mut self, operand: ExprId, span: Span) -> ExprId {
        self.ast.alloc(
            ExprKind::Unary {
                op: UnaryOp::Not,
                operand,
            },
            span,
        )
    }

    /// The operands joined by `op`, as a balanced tree (no deep chains).
    fn join(&mut self, op: BinaryOp, mut es: Vec<ExprId>, span: Span) -> ExprId {
        while es.len() > 1 {
            let mut next = Vec::with_capacity(es.len().div_ceil(2));
            let mut it = es.into_iter();
            while let Some(a) = it.next() {
                match it.next() {
                    Some(b) => next.push(self.bin(op, a, b, span)),
                    None => next.push(a),
                }
            }
            es = next;
        }
        es.pop().unwrap_or_else(|| self.bool(false, span))
    }

    fn cur_time(&mut self, span: Span) -> ExprId {
        let id = self.ident("CUR_TIME", span);
        let callee = self.name(id);
        self.ast.alloc(
            ExprKind::Call {
                callee,
                args: Box::new([]),
            },
            span,
        )
    }

    fn assign(&self, target: ExprId, value: ExprId, span: Span) -> Stmt {
        Stmt {
            kind: StmtKind::Assign { target, value },
            span,
        }
    }

    fn if_(&self, cond: ExprId, body: Vec<Stmt>, span: Span) -> Stmt {
        Stmt {
            kind: StmtKind::If {
                branches: vec![CondBranch { cond, body }],
                else_body: None,
            },
            span,
        }
    }

    fn decl(&mut self, name: Ident, kind: TypeSpecKind, init: Option<Init>) -> VarDecl {
        VarDecl {
            names: vec![name],
            location: None,
            ty: TypeSpec {
                kind,
                span: name.span,
            },
            edge: None,
            init,
            span: name.span,
            pragmas: Vec::new(),
        }
    }

    fn elem_decl(&mut self, role: &str, ty: ElemType, span: Span) -> VarDecl {
        let name = self.ident(&format!("SFC$${role}"), span);
        self.decl(name, TypeSpecKind::Elementary(ty), None)
    }
}

/// Where an action's qualifier inputs come from.
struct Control<'a> {
    /// The action control instance's role name.
    role: String,
    span: Span,
    assocs: Vec<(&'a SfcStep, &'a ActionAssoc)>,
    /// The coded action, or `None` for a Boolean variable.
    body: Option<&'a SfcAction>,
    /// The Boolean variable an action that is not coded sets.
    var: Option<Ident>,
}

/// The variable blocks and the statements of one cycle of a chart (see
/// the module documentation). A FUNCTION cannot hold a chart's state: its
/// chart means nothing (the analyser reports it).
pub fn lower(
    ast: &mut Ast,
    interner: &mut Interner,
    kind: PouKind,
    var_blocks: &[VarBlock],
    sfc: &SfcBody,
) -> (Vec<VarBlock>, Vec<Stmt>) {
    if kind == PouKind::Function {
        return (Vec::new(), Vec::new());
    }
    let declared = declared(var_blocks);
    let chart = ChartNames::without(sfc, &declared);
    let span = sfc.span;
    let mut g = Gen { ast, interner };
    let mut step_decls = Vec::new();
    let mut decls = Vec::new();
    let mut body = Vec::new();

    // The steps.
    for s in &chart.steps {
        let x = g.ident("X", s.name.span);
        let ty = g.ident(STEP_TYPE, s.name.span);
        let init = if s.initial {
            let value = g.bool(true, s.name.span);
            Some(Init {
                kind: InitKind::Struct(vec![StructInitElem {
                    name: x,
                    value: Init {
                        kind: InitKind::Expr(value),
                        span: s.name.span,
                    },
                }]),
                span: s.name.span,
            })
        } else {
            None
        };
        step_decls.push(g.decl(s.name, TypeSpecKind::Named(ty), init));
    }

    // The flags of the coded actions, beside the steps'.
    for a in &chart.actions {
        let ty = g.ident(ACTION_TYPE, a.name.span);
        step_decls.push(g.decl(a.name, TypeSpecKind::Named(ty), None));
    }

    // (1) The clock: step times grow by the time since the last cycle.
    decls.push(g.elem_decl("last", ElemType::Time, span));
    decls.push(g.elem_decl("run", ElemType::Bool, span));
    decls.push(g.elem_decl("dt", ElemType::Time, span));
    {
        let dt = g.hidden("dt", span);
        let zero = g.time0(span);
        body.push(g.assign(dt, zero, span));
        let dt = g.hidden("dt", span);
        let now = g.cur_time(span);
        let last = g.hidden("last", span);
        let diff = g.bin(BinaryOp::Sub, now, last, span);
        let set = g.assign(dt, diff, span);
        let run = g.hidden("run", span);
        body.push(g.if_(run, vec![set], span));
        let run = g.hidden("run", span);
        let t = g.bool(true, span);
        body.push(g.assign(run, t, span));
        let last = g.hidden("last", span);
        let now = g.cur_time(span);
        body.push(g.assign(last, now, span));
        for s in &chart.steps {
            let cond = g.flag(s.name, "X");
            let target = g.flag(s.name, "T");
            let old = g.flag(s.name, "T");
            let dt = g.hidden("dt", s.name.span);
            let sum = g.bin(BinaryOp::Add, old, dt, s.name.span);
            let inc = g.assign(target, sum, s.name.span);
            body.push(g.if_(cond, vec![inc], s.span));
        }
    }

    // (2) Transition conditions, in textual order, where all the source
    // steps are active.
    let transitions: Vec<(usize, &SfcTransition)> = chart
        .transitions
        .iter()
        .copied()
        .enumerate()
        .filter(|(_, t)| chart.transition_valid(t))
        .collect();
    // The condition variable of each valid transition.
    let mut cond_var: Vec<Ident> = Vec::new();
    for &(i, t) in &transitions {
        let sp = t.span;
        let var = match (&t.cond, t.name) {
            (TransitionCond::Body(_), Some(n)) => n,
            _ => g.ident(&format!("SFC$$c{i}"), sp),
        };
        decls.push(g.decl(var, TypeSpecKind::Elementary(ElemType::Bool), None));
        cond_var.push(var);
        let target = g.name(var);
        let f = g.bool(false, sp);
        body.push(g.assign(target, f, sp));
        let active: Vec<ExprId> = t.from.iter().map(|s| g.flag(*s, "X")).collect();
        let active = g.join(BinaryOp::And, active, sp);
        let inner = match &t.cond {
            TransitionCond::Expr(e) => {
                let target = g.name(var);
                let espan = g.ast.expr(*e).span;
                vec![g.assign(target, *e, espan)]
            }
            TransitionCond::Body(stmts) => stmts.clone(),
            TransitionCond::Il(il) => {
                let result = Some(g.name(var));
                vec![Stmt {
                    kind: StmtKind::Il {
                        body: Box::new(il.clone()),
                        result,
                    },
                    span: il.span,
                }]
            }
        };
        body.push(g.if_(active, inner, sp));
    }

    // (3) Which transitions fire: where several leave one step, the one of
    // highest priority (lowest PRIORITY, then the first written) that can.
    let mut outgoing: Vec<(Symbol, usize)> = Vec::new();
    for &(_, t) in &transitions {
        for s in &t.from {
            match outgoing.iter_mut().find(|(o, _)| *o == s.sym) {
                Some(o) => o.1 += 1,
                None => outgoing.push((s.sym, 1)),
            }
        }
    }
    let contested = |sym: Symbol| outgoing.iter().any(|&(o, n)| o == sym && n > 1);
    let mut fire_var: Vec<Ident> = cond_var.clone();
    let mut order: Vec<usize> = (0..transitions.len()).collect();
    order.sort_by_key(|&k| (priority(g.ast, transitions[k].1), k));
    let mut taken_declared: Vec<Symbol> = Vec::new();
    let mut taken_reset = Vec::new();
    let mut resolve = Vec::new();
    for k in order {
        let (i, t) = transitions[k];
        let sp = t.span;
        let shared: Vec<Ident> = t
            .from
            .iter()
            .copied()
            .filter(|s| contested(s.sym))
            .collect();
        if shared.is_empty() {
            continue;
        }
        for s in &shared {
            if !taken_declared.contains(&s.sym) {
                taken_declared.push(s.sym);
                let role = format!("k$${}", g.interner.spelling(s.sym));
                decls.push(g.elem_decl(&role, ElemType::Bool, s.span));
                let target = g.hidden(&role, s.span);
                let f = g.bool(false, s.span);
                taken_reset.push(g.assign(target, f, s.span));
            }
        }
        let fv = g.ident(&format!("SFC$$f{i}"), sp);
        decls.push(g.decl(fv, TypeSpecKind::Elementary(ElemType::Bool), None));
        fire_var[k] = fv;
        let mut conds = vec![g.name(cond_var[k])];
        for s in &shared {
            let role = format!("k$${}", g.interner.spelling(s.sym));
            let taken = g.hidden(&role, s.span);
            conds.push(g.not(taken, s.span));
        }
        let cond = g.join(BinaryOp::And, conds, sp);
        let target = g.name(fv);
        resolve.push(g.assign(target, cond, sp));
        let mut takes = Vec::new();
        for s in &shared {
            let role = format!("k$${}", g.interner.spelling(s.sym));
            let target = g.hidden(&role, s.span);
            let t = g.bool(true, s.span);
            takes.push(g.assign(target, t, s.span));
        }
        let fired = g.name(fv);
        resolve.push(g.if_(fired, takes, sp));
    }
    body.extend(taken_reset);
    body.extend(resolve);

    // (4) Clearing: every firing transition deactivates its source steps,
    // then activates its target steps (step time from zero).
    for (k, &(_, t)) in transitions.iter().enumerate() {
        let mut off = Vec::new();
        for s in &t.from {
            let target = g.flag(*s, "X");
            let f = g.bool(false, s.span);
            off.push(g.assign(target, f, s.span));
        }
        let cond = g.name(fire_var[k]);
        body.push(g.if_(cond, off, t.span));
    }
    for (k, &(_, t)) in transitions.iter().enumerate() {
        let mut on = Vec::new();
        for s in &t.to {
            let target = g.flag(*s, "X");
            let tr = g.bool(true, s.span);
            on.push(g.assign(target, tr, s.span));
            let target = g.flag(*s, "T");
            let zero = g.time0(s.span);
            on.push(g.assign(target, zero, s.span));
        }
        let cond = g.name(fire_var[k]);
        body.push(g.if_(cond, on, t.span));
    }

    // (5) Action control: coded actions in textual order, then Boolean
    // variables in the order of their first association.
    let mut controls: Vec<Control> = chart
        .actions
        .iter()
        .map(|a| Control {
            role: format!("a$${}", g.interner.spelling(a.name.sym)),
            span: a.name.span,
            assocs: Vec::new(),
            body: Some(a),
            var: None,
        })
        .collect();
    for s in &chart.steps {
        for a in &s.assocs {
            let sym = a.action.sym;
            if let Some(c) = controls.iter_mut().find(|c| {
                c.body.is_some_and(|b| b.name.sym == sym) || c.var.is_some_and(|v| v.sym == sym)
            }) {
                c.assocs.push((s, a));
            } else if chart.action(sym).is_none() && declared.contains(&sym) {
                controls.push(Control {
                    role: format!("v$${}", g.interner.spelling(sym)),
                    span: a.action.span,
                    assocs: vec![(s, a)],
                    body: None,
                    var: Some(a.action),
                });
            }
        }
    }
    let ac_ty = g.ident(ACTION_CONTROL, span);
    for c in &controls {
        let name = g.ident(&format!("SFC$${}", c.role), c.span);
        decls.push(g.decl(name, TypeSpecKind::Named(ac_ty), None));
        // The duration (the block's one T): the first timed association (in
        // textual order) whose step is active sets it; it is kept while
        // none is.
        for &(s, a) in c.assocs.iter().rev() {
            let (Some(_), Some(d)) = (a.qualifier, a.duration) else {
                continue;
            };
            let inst = g.hidden(&c.role, a.span);
            let input = g.member(inst, "T", a.span);
            let dspan = g.ast.expr(d).span;
            let set = g.assign(input, d, dspan);
            let active = g.flag(s.name, "X");
            body.push(g.if_(active, vec![set], a.span));
        }
        let mut args = Vec::new();
        for q in Qualifier::ALL {
            let steps: Vec<Ident> = c
                .assocs
                .iter()
                .filter(|(_, a)| a.qualifier.map_or(Qualifier::N, |(q, _)| q) == q)
                .map(|(s, a)| Ident {
                    sym: s.name.sym,
                    span: a.span,
                })
                .collect();
            if steps.is_empty() {
                continue;
            }
            let value: Vec<ExprId> = steps.iter().map(|s| g.flag(*s, "X")).collect();
            let value = g.join(BinaryOp::Or, value, c.span);
            let name = g.ident(q.input(), c.span);
            args.push(Arg {
                kind: ArgKind::Input { name, value },
                span: c.span,
            });
        }
        let callee = g.hidden(&c.role, c.span);
        let call = g.ast.alloc(
            ExprKind::Call {
                callee,
                args: args.into_boxed_slice(),
            },
            c.span,
        );
        body.push(Stmt {
            kind: StmtKind::Call(call),
            span: c.span,
        });
        // A coded action's flags: `action.Q`, `action.A`.
        if let Some(a) = c.body {
            for flag in ["Q", "A"] {
                let target = g.flag(a.name, flag);
                let inst = g.hidden(&c.role, a.name.span);
                let value = g.member(inst, flag, a.name.span);
                body.push(g.assign(target, value, a.name.span));
            }
        }
    }
    // (6) Boolean variables take their action's Q; coded actions run while
    // their control's A is TRUE.
    for c in &controls {
        if let Some(v) = c.var {
            let target = g.name(v);
            let inst = g.hidden(&c.role, c.span);
            let q = g.member(inst, "Q", c.span);
            body.push(g.assign(target, q, c.span));
        }
    }
    for c in &controls {
        if let Some(a) = c.body {
            let run = g.flag(a.name, "A");
            let stmts = match &a.il {
                Some(il) => vec![Stmt {
                    kind: StmtKind::Il {
                        body: Box::new(il.clone()),
                        result: None,
                    },
                    span: il.span,
                }],
                None => a.body.clone(),
            };
            body.push(g.if_(run, stmts, a.span));
        }
    }

    let mut blocks = Vec::new();
    if !step_decls.is_empty() {
        blocks.push(VarBlock {
            access: None,
            kind: if kind == PouKind::FunctionBlock {
                VarKind::Output
            } else {
                VarKind::Var
            },
            constant: false,
            retention: None,
            items: VarBlockItems::Vars(step_decls),
            span,
        });
    }
    blocks.push(VarBlock {
        access: None,
        kind: VarKind::Var,
        constant: false,
        retention: None,
        items: VarBlockItems::Vars(decls),
        span,
    });
    (blocks, body)
}
