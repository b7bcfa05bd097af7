//! Walking a body: the expressions of a tree, of a statement, of a list of
//! statements, of an Instruction List body, in source order.

use stc_syntax::ast::{ArgKind, Ast, CaseLabel, ExprId, ExprKind, IlSem, Pou, Stmt, StmtKind};

/// Calls `f` on `e` and every expression below it (pre-order: an
/// expression before its operands, operands left to right).
pub fn expr_tree(ast: &Ast, e: ExprId, f: &mut dyn FnMut(ExprId)) {
    let Some(expr) = ast.exprs.get(e.index()) else {
        return;
    };
    f(e);
    match &expr.kind {
        ExprKind::Member { base, .. } | ExprKind::PartialAccess { base, .. } => {
            expr_tree(ast, *base, f)
        }
        ExprKind::Index { base, indices } => {
            expr_tree(ast, *base, f);
            for i in indices.iter() {
                expr_tree(ast, *i, f);
            }
        }
        ExprKind::Call { callee, args } => {
            expr_tree(ast, *callee, f);
            for a in args.iter() {
                match &a.kind {
                    ArgKind::Positional(v) | ArgKind::Input { value: v, .. } => {
                        expr_tree(ast, *v, f)
                    }
                    ArgKind::Output { target, .. } => expr_tree(ast, *target, f),
                }
            }
        }
        ExprKind::Unary { operand, .. } => expr_tree(ast, *operand, f),
        ExprKind::Binary { lhs, rhs, .. } => {
            expr_tree(ast, *lhs, f);
            expr_tree(ast, *rhs, f);
        }
        ExprKind::Paren(i) | ExprKind::Deref(i) => expr_tree(ast, *i, f),
        ExprKind::Error
        | ExprKind::Literal(_)
        | ExprKind::Name(_)
        | ExprKind::EnumValue { .. }
        | ExprKind::Address(_)
        | ExprKind::IlCr => {}
    }
}

/// The expressions written in a statement itself (not in the statements
/// nested in it), in source order; CASE labels are given to `labels`.
pub fn own_exprs(s: &Stmt, f: &mut dyn FnMut(ExprId), labels: &mut dyn FnMut(ExprId)) {
    match &s.kind {
        StmtKind::Assign { target, value } | StmtKind::AssignAttempt { target, value } => {
            f(*target);
            f(*value);
        }
        StmtKind::Call(e) => f(*e),
        StmtKind::If { branches, .. } => {
            for b in branches {
                f(b.cond);
            }
        }
        StmtKind::Case { selector, arms, .. } => {
            f(*selector);
            for a in arms {
                for l in &a.labels {
                    match l {
                        CaseLabel::Value(v) => labels(*v),
                        CaseLabel::Range(lo, hi) => {
                            labels(*lo);
                            labels(*hi);
                        }
                    }
                }
            }
        }
        StmtKind::For { from, to, by, .. } => {
            f(*from);
            f(*to);
            if let Some(b) = by {
                f(*b);
            }
        }
        StmtKind::While { cond, .. } => f(*cond),
        StmtKind::Repeat { until, .. } => f(*until),
        StmtKind::Unsupported(es) => {
            for e in es {
                f(*e);
            }
        }
        // (An IL body inside a chart: its result; the lints read ST.)
        StmtKind::Il { result, .. } => {
            if let Some(r) = result {
                f(*r);
            }
        }
        StmtKind::Empty
        | StmtKind::Error
        | StmtKind::Exit
        | StmtKind::Continue
        | StmtKind::Return => {}
    }
}

/// The statement lists nested in a statement, in source order.
pub fn nested(s: &Stmt) -> Vec<&[Stmt]> {
    match &s.kind {
        StmtKind::If {
            branches,
            else_body,
        } => {
            let mut out: Vec<&[Stmt]> = branches.iter().map(|b| b.body.as_slice()).collect();
            if let Some(e) = else_body {
                out.push(e);
            }
            out
        }
        StmtKind::Case {
            arms, else_body, ..
        } => {
            let mut out: Vec<&[Stmt]> = arms.iter().map(|a| a.body.as_slice()).collect();
            if let Some(e) = else_body {
                out.push(e);
            }
            out
        }
        StmtKind::For { body, .. }
        | StmtKind::While { body, .. }
        | StmtKind::Repeat { body, .. } => vec![body.as_slice()],
        _ => Vec::new(),
    }
}

/// Calls `f` on every statement of `list` and below, pre-order.
pub fn statements<'a>(list: &'a [Stmt], f: &mut dyn FnMut(&'a Stmt)) {
    for s in list {
        f(s);
        for l in nested(s) {
            statements(l, f);
        }
    }
}

/// The statements of a POU's body: its ST statements, or the meaning of
/// its Instruction List instructions.
pub fn body_statements<'a>(pou: &'a Pou, f: &mut dyn FnMut(&'a Stmt)) {
    statements(&pou.body, f);
    if let Some(il) = &pou.il {
        for i in &il.instrs {
            match &i.sem {
                IlSem::Effect { stmts, .. } => statements(stmts, f),
                IlSem::SetReset {
                    bool_form, fb_form, ..
                } => {
                    statements(bool_form, f);
                    statements(fb_form, f);
                }
                IlSem::Nothing | IlSem::Load(_) | IlSem::Jump { .. } => {}
            }
        }
    }
}

/// Every expression of a POU's body (each tree whole), with the CASE
/// labels apart; the expressions an IL instruction loads or tests too.
pub fn body_exprs(ast: &Ast, pou: &Pou, f: &mut dyn FnMut(ExprId), labels: &mut dyn FnMut(ExprId)) {
    let mut roots = Vec::new();
    let mut label_roots = Vec::new();
    body_statements(pou, &mut |s| {
        own_exprs(s, &mut |e| roots.push(e), &mut |e| label_roots.push(e))
    });
    if let Some(il) = &pou.il {
        for i in &il.instrs {
            match &i.sem {
                IlSem::Load(e) => roots.push(*e),
                IlSem::SetReset { operand, .. } => roots.push(*operand),
                IlSem::Jump { cond: Some(c), .. } => roots.push(*c),
                _ => {}
            }
        }
    }
    if pou.il.is_none() {
        // ST: every expression is in one tree only.
        for r in roots {
            expr_tree(ast, r, f);
        }
        for r in label_roots {
            expr_tree(ast, r, labels);
        }
        return;
    }
    // The meanings of IL instructions may share an operand (`S x` holds
    // both forms): each expression once.
    let mut seen = rustc_hash::FxHashSet::default();
    for r in roots {
        expr_tree(ast, r, &mut |e| {
            if seen.insert(e) {
                f(e)
            }
        });
    }
    for r in label_roots {
        expr_tree(ast, r, &mut |e| {
            if seen.insert(e) {
                labels(e)
            }
        });
    }
}
