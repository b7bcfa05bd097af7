//! The rules of a Sequential Function Chart (docs/sfc.md, E1201-E1209,
//! W1201-W1202).
//!
//! The chart's meaning is ordinary ST (`stc_syntax::sfc`), checked by the
//! rest of the analyser; here are the rules about the chart as written:
//! its names, its initial step, which steps can be reached. What is wrong
//! here was left out of the meaning, so it is reported once.

use stc_diagnostics::{Code, Diagnostic};
use stc_syntax::ast::{
    ExprKind, IlInstr, IlSem, LitValue, Literal, Pou, PouKind, SfcBody, SfcElement, Stmt, StmtKind,
    TransitionCond,
};
use stc_syntax::sfc::{declared, ChartNames};
use stc_syntax::Symbol;

use crate::analyzer::{Scope, Sema};
use crate::types::TypeId;
use crate::PouId;

impl<'a> Sema<'a> {
    pub(crate) fn check_sfc(&mut self, p: PouId, pou: &'a Pou, sfc: &'a SfcBody) {
        if pou.kind == PouKind::Function {
            let d = Diagnostic::new(
                Code::E1201,
                sfc.span.shrink_to_lo(),
                "a Sequential Function Chart cannot be the body of a FUNCTION",
            )
            .with_label("a chart keeps state between calls")
            .with_help("make the POU a FUNCTION_BLOCK or a PROGRAM");
            self.emit(d);
            return;
        }
        let chart = ChartNames::of(sfc);
        let vars = declared(&pou.var_blocks[..pou.var_blocks.len() - sfc.generated_blocks]);

        // Names declared twice (steps, actions, named transitions).
        let mut seen: Vec<(Symbol, &'static str)> = Vec::new();
        for e in &sfc.elements {
            let (name, what) = match e {
                SfcElement::Step(s) => (Some(s.name), "step"),
                SfcElement::Action(a) => (Some(a.name), "action"),
                SfcElement::Transition(t) => (t.name, "transition"),
            };
            let Some(name) = name else { continue };
            let named_var = match e {
                SfcElement::Step(_) => true,
                SfcElement::Transition(t) => matches!(t.cond, TransitionCond::Body(_)),
                // An action's flags are a variable named like it.
                SfcElement::Action(_) => true,
            };
            if named_var && vars.contains(&name.sym) {
                self.body.partial = true;
                let shown = self.spelled(name.sym, name.span);
                self.emit(
                    Diagnostic::new(
                        Code::E1206,
                        name.span,
                        format!("`{shown}` is already a variable of this POU"),
                    )
                    .with_label(format!("declared again, as a {what}")),
                );
                continue;
            }
            if let Some(&(_, first)) = seen.iter().find(|(s, _)| *s == name.sym) {
                let shown = self.spelled(name.sym, name.span);
                self.emit(
                    Diagnostic::new(
                        Code::E1206,
                        name.span,
                        format!("`{shown}` is already the name of a {first} of this chart"),
                    )
                    .with_label(format!("second declaration, as a {what}")),
                );
            } else {
                seen.push((name.sym, what));
            }
        }

        // The initial step.
        let initial: Vec<_> = chart.steps.iter().filter(|s| s.initial).collect();
        if initial.is_empty() && !chart.steps.is_empty() {
            let first = chart.steps[0];
            self.emit(
                Diagnostic::new(
                    Code::E1202,
                    first.name.span,
                    "the chart has no initial step",
                )
                .with_label("no INITIAL_STEP in this chart")
                .with_help("declare the step the chart starts in with INITIAL_STEP"),
            );
        }
        for extra in initial.iter().skip(1) {
            let d = Diagnostic::new(
                Code::E1203,
                extra.name.span,
                "a chart has exactly one initial step",
            )
            .with_label("second INITIAL_STEP")
            .with_secondary(initial[0].name.span, "the first one");
            self.emit(d);
        }

        // Transitions.
        let mut unknown_step = false;
        for t in &chart.transitions {
            for n in t.from.iter().chain(&t.to) {
                if chart.step(n.sym).is_none() {
                    unknown_step = true;
                    self.body.partial = true;
                    let shown = self.spelled(n.sym, n.span);
                    self.emit(
                        Diagnostic::new(
                            Code::E1204,
                            n.span,
                            format!("`{shown}` is not a step of this chart"),
                        )
                        .with_label("unknown step"),
                    );
                }
            }
            if let Some(prio) = t.priority {
                let ok = matches!(&self.ast.expr(prio).kind, ExprKind::Error)
                    || matches!(
                        &self.ast.expr(prio).kind,
                        ExprKind::Literal(Literal {
                            value: LitValue::Int {
                                negative: false,
                                ..
                            },
                            prefix: None,
                        })
                    );
                if !ok {
                    // Its names still count as used.
                    self.check_expr(prio, Some(TypeId::ERROR), Scope::Pou(p));
                    self.emit(
                        Diagnostic::new(
                            Code::E1207,
                            self.ast.expr(prio).span,
                            "a transition PRIORITY must be a non-negative integer literal",
                        )
                        .with_label("not an integer literal"),
                    );
                }
            }
            if matches!(t.cond, TransitionCond::Body(_)) && t.name.is_none() {
                self.emit(
                    Diagnostic::new(
                        Code::E1209,
                        t.span.shrink_to_lo(),
                        "a transition with a body of statements needs a name",
                    )
                    .with_label("the body gives the condition by assigning the transition's name")
                    .with_help(
                        "write `TRANSITION name FROM ...`, or the condition as `:= expression;`",
                    ),
                );
            }
        }

        // Associations.
        let mut used: Vec<Symbol> = Vec::new();
        for s in &chart.steps {
            for a in &s.assocs {
                used.push(a.action.sym);
                for i in &a.indicators {
                    match self.pous[p.0 as usize].lookup(i.sym) {
                        Some(v) => {
                            self.used.insert((p, v));
                            self.resolve_pou(p);
                            let ty = self.pous[p.0 as usize].vars[v.0 as usize].ty;
                            if ty != TypeId::ERROR && !self.types.is_bool(ty) {
                                let shown = self.spelled(i.sym, i.span);
                                let tn = self.tname(ty);
                                self.emit(
                                    Diagnostic::new(
                                        Code::E1212,
                                        i.span,
                                        format!(
                                            "the indicator variable `{shown}` must be a BOOL, but it is {tn}"
                                        ),
                                    )
                                    .with_label("not a BOOL")
                                    .with_help("name a BOOL variable that the action's body sets"),
                                );
                            }
                        }
                        None => {
                            let shown = self.spelled(i.sym, i.span);
                            self.emit(
                                Diagnostic::new(
                                    Code::E0101,
                                    i.span,
                                    format!("undeclared variable `{shown}`"),
                                )
                                .with_label("not declared in this POU"),
                            );
                        }
                    }
                }
                if chart.action(a.action.sym).is_none() && !vars.contains(&a.action.sym) {
                    self.body.partial = true;
                    let shown = self.spelled(a.action.sym, a.action.span);
                    self.emit(
                        Diagnostic::new(
                            Code::E1205,
                            a.action.span,
                            format!("`{shown}` is neither an action of this chart nor a variable"),
                        )
                        .with_label("undefined action")
                        .with_help(format!(
                            "declare `ACTION {shown} : ... END_ACTION`, or a BOOL variable"
                        )),
                    );
                }
            }
        }
        for a in &chart.actions {
            if !used.contains(&a.name.sym) && !pou.partial {
                let shown = self.spelled(a.name.sym, a.name.span);
                self.emit(
                    Diagnostic::new(
                        Code::W1202,
                        a.name.span,
                        format!("the action `{shown}` is associated with no step"),
                    )
                    .with_label("never runs"),
                );
            }
        }

        // Step and action flags are read-only.
        let flags: Vec<(Symbol, bool)> = chart
            .steps
            .iter()
            .map(|s| (s.name.sym, true))
            .chain(chart.actions.iter().map(|a| (a.name.sym, false)))
            .filter(|(s, _)| !vars.contains(s))
            .collect();
        for e in &sfc.elements {
            match e {
                SfcElement::Action(a) => match &a.il {
                    Some(il) => self.il_flag_writes(&il.instrs, &flags),
                    None => self.step_writes(&a.body, &flags),
                },
                SfcElement::Transition(t) => match &t.cond {
                    TransitionCond::Body(b) => self.step_writes(b, &flags),
                    TransitionCond::Il(il) => self.il_flag_writes(&il.instrs, &flags),
                    TransitionCond::Expr(_) => {}
                },
                SfcElement::Step(_) => {}
            }
        }

        // Reachability from the initial step (of a chart whose transitions
        // are all known).
        if initial.len() == 1 && !unknown_step && !pou.partial {
            let mut reached: Vec<Symbol> = vec![initial[0].name.sym];
            loop {
                let before = reached.len();
                for t in &chart.transitions {
                    if chart.transition_valid(t) && t.from.iter().all(|f| reached.contains(&f.sym))
                    {
                        for n in &t.to {
                            if !reached.contains(&n.sym) {
                                reached.push(n.sym);
                            }
                        }
                    }
                }
                if reached.len() == before {
                    break;
                }
            }
            self.never_together(&chart, initial[0].name.sym);
            for s in &chart.steps {
                if !reached.contains(&s.name.sym) && !vars.contains(&s.name.sym) {
                    let shown = self.spelled(s.name.sym, s.name.span);
                    self.emit(
                        Diagnostic::new(
                            Code::W1201,
                            s.name.span,
                            format!("the step `{shown}` can never become active"),
                        )
                        .with_label("no transition leads here from the initial step"),
                    );
                }
            }
        }
    }

    /// W1203 for a transition from several steps (a convergence) that no
    /// reachable situation has all active: the sets of active steps are
    /// explored from the initial step, any enabled transition firing
    /// (conditions are not known); charts of more than 128 steps or 4096
    /// situations are not explored.
    fn never_together(&mut self, chart: &ChartNames<'_>, initial: Symbol) {
        if chart.steps.len() > 128 {
            return;
        }
        let bit = |sym: Symbol| -> u128 {
            chart
                .steps
                .iter()
                .position(|s| s.name.sym == sym)
                .map_or(0, |i| 1u128 << i)
        };
        let mask =
            |names: &[stc_syntax::ast::Ident]| names.iter().fold(0u128, |m, n| m | bit(n.sym));
        let transitions: Vec<(usize, u128, u128)> = chart
            .transitions
            .iter()
            .enumerate()
            .filter(|(_, t)| chart.transition_valid(t))
            .map(|(i, t)| (i, mask(&t.from), mask(&t.to)))
            .collect();
        let mut seen: Vec<u128> = vec![bit(initial)];
        let mut todo = seen.clone();
        // Transitions that can activate a step already active (W1204).
        let mut unsafe_at: Vec<usize> = Vec::new();
        let mut complete = true;
        'explore: while let Some(m) = todo.pop() {
            for &(i, from, to) in &transitions {
                if m & from == from {
                    let stays = m & !from;
                    if stays & to != 0 && !unsafe_at.contains(&i) {
                        unsafe_at.push(i);
                    }
                    let next = stays | to;
                    if !seen.contains(&next) {
                        if seen.len() >= 4096 {
                            complete = false;
                            break 'explore;
                        }
                        seen.push(next);
                        todo.push(next);
                    }
                }
            }
        }
        unsafe_at.sort_unstable();
        for i in unsafe_at {
            let t = &chart.transitions[i];
            let Some(first) = t.to.first() else { continue };
            self.emit(
                Diagnostic::new(
                    Code::W1204,
                    first.span,
                    "this transition can activate a step that is already active: the chart is unsafe",
                )
                .with_label("may already be active")
                .with_note(
                    "a step is active once: the second activation is lost (a branch of a simultaneous divergence leads into another branch, or back before it has converged)",
                ),
            );
        }
        if !complete {
            return;
        }
        for t in &chart.transitions {
            if t.from.len() < 2 || !chart.transition_valid(t) {
                continue;
            }
            let from = mask(&t.from);
            // Steps that are themselves never active are W1201's.
            let each = t
                .from
                .iter()
                .all(|f| seen.iter().any(|m| m & bit(f.sym) != 0));
            if each && !seen.iter().any(|m| m & from == from) {
                let first = t.from[0];
                self.emit(
                    Diagnostic::new(
                        Code::W1203,
                        first.span,
                        "these steps can never be active together: the transition never fires",
                    )
                    .with_label("never all active at once")
                    .with_note(
                        "a simultaneous convergence joins steps of branches started together by one transition",
                    ),
                );
            }
        }
    }

    /// E1208/E1211 for the stores of an IL body into flags.
    fn il_flag_writes(&mut self, instrs: &[IlInstr], flags: &[(Symbol, bool)]) {
        for ins in instrs {
            match &ins.sem {
                IlSem::Effect { stmts, .. } => self.step_writes(stmts, flags),
                IlSem::SetReset {
                    bool_form, fb_form, ..
                } => {
                    self.step_writes(bool_form, flags);
                    self.step_writes(fb_form, flags);
                }
                IlSem::Nothing | IlSem::Load(_) | IlSem::Jump { .. } => {}
            }
        }
    }

    /// E1208 for every assignment to `step.X` or `step.T` in `list`, E1211
    /// to `action.Q` or `action.A` (`flags`: the names, `true` for a step).
    fn step_writes(&mut self, list: &[Stmt], steps: &[(Symbol, bool)]) {
        for s in list {
            match &s.kind {
                StmtKind::Assign { target, .. } => {
                    let mut e = *target;
                    loop {
                        match &self.ast.expr(e).kind {
                            ExprKind::Member { base, .. } | ExprKind::Paren(base) => e = *base,
                            ExprKind::Index { base, .. } => e = *base,
                            ExprKind::PartialAccess { base, .. } => e = *base,
                            _ => break,
                        }
                    }
                    if let ExprKind::Name(n) = &self.ast.expr(e).kind {
                        let found = steps.iter().find(|(s, _)| *s == n.sym).map(|f| f.1);
                        if found == Some(false) {
                            let shown = self.spelled(n.sym, n.span);
                            self.emit(
                                Diagnostic::new(
                                    Code::E1211,
                                    self.ast.expr(*target).span,
                                    format!("the flags of the action `{shown}` cannot be written"),
                                )
                                .with_label("action flags are read-only")
                                .with_note("the action's ACTION_CONTROL sets `.Q` and `.A`"),
                            );
                        }
                        if found == Some(true) {
                            let shown = self.spelled(n.sym, n.span);
                            self.emit(
                                Diagnostic::new(
                                    Code::E1208,
                                    self.ast.expr(*target).span,
                                    format!("the flags of the step `{shown}` cannot be written"),
                                )
                                .with_label("step flags are read-only")
                                .with_note("the chart's evolution rules set `.X` and `.T`"),
                            );
                        }
                    }
                }
                StmtKind::If {
                    branches,
                    else_body,
                } => {
                    for b in branches {
                        self.step_writes(&b.body, steps);
                    }
                    if let Some(b) = else_body {
                        self.step_writes(b, steps);
                    }
                }
                StmtKind::Case {
                    arms, else_body, ..
                } => {
                    for a in arms {
                        self.step_writes(&a.body, steps);
                    }
                    if let Some(b) = else_body {
                        self.step_writes(b, steps);
                    }
                }
                StmtKind::For { body, .. }
                | StmtKind::While { body, .. }
                | StmtKind::Repeat { body, .. } => self.step_writes(body, steps),
                _ => {}
            }
        }
    }
}
