//! Walks over IR bodies that every back end needs: the calls a body makes
//! (to order or select POUs) and the places it names (to find the process
//! image). One definition, so no back end misses a corner (a call inside
//! the index of an assignment target, an output target, an in-out).

use stc_sema::PouId;

use crate::{Expr, ExprKind, Place, Proj, Stmt, StmtKind};

/// Every expression of a body, in evaluation order, including those inside
/// places (indices) and nested calls, and every place named.
pub fn walk(stmts: &[Stmt], on_expr: &mut dyn FnMut(&Expr), on_place: &mut dyn FnMut(&Place)) {
    for s in stmts {
        match &s.kind {
            StmtKind::Assign { place: p, value } => {
                place(p, on_expr, on_place);
                expr(value, on_expr, on_place);
            }
            StmtKind::CallFb {
                instance,
                inputs,
                inouts,
                outputs,
                ..
            } => {
                place(instance, on_expr, on_place);
                inputs.iter().for_each(|(_, e)| expr(e, on_expr, on_place));
                inouts.iter().for_each(|(_, p)| place(p, on_expr, on_place));
                outputs
                    .iter()
                    .for_each(|o| place(&o.target, on_expr, on_place));
            }
            StmtKind::Eval(e) => expr(e, on_expr, on_place),
            StmtKind::If {
                cond,
                then_body,
                else_body,
            } => {
                expr(cond, on_expr, on_place);
                walk(then_body, on_expr, on_place);
                walk(else_body, on_expr, on_place);
            }
            StmtKind::Switch {
                selector,
                arms,
                default,
            } => {
                expr(selector, on_expr, on_place);
                for a in arms {
                    walk(&a.body, on_expr, on_place);
                }
                walk(default, on_expr, on_place);
            }
            StmtKind::Loop { body, latch } => {
                walk(body, on_expr, on_place);
                walk(latch, on_expr, on_place);
            }
            StmtKind::Break | StmtKind::Continue | StmtKind::Return | StmtKind::Fault(_) => {}
        }
    }
}

fn place(p: &Place, on_expr: &mut dyn FnMut(&Expr), on_place: &mut dyn FnMut(&Place)) {
    on_place(p);
    for pr in &p.proj {
        if let Proj::Index(idx) = pr {
            idx.iter().for_each(|(e, _, _)| expr(e, on_expr, on_place));
        }
    }
}

fn expr(e: &Expr, on_expr: &mut dyn FnMut(&Expr), on_place: &mut dyn FnMut(&Place)) {
    on_expr(e);
    match &e.kind {
        ExprKind::Load(p) => place(p, on_expr, on_place),
        ExprKind::Unary(_, x) | ExprKind::Convert(x) => expr(x, on_expr, on_place),
        ExprKind::Check { value, .. } => expr(value, on_expr, on_place),
        ExprKind::Binary(_, x, y) => {
            expr(x, on_expr, on_place);
            expr(y, on_expr, on_place);
        }
        ExprKind::Intrinsic { args, .. } => args.iter().for_each(|a| expr(a, on_expr, on_place)),
        ExprKind::CallFn {
            inputs,
            inouts,
            outputs,
            ..
        } => {
            inputs.iter().for_each(|(_, e)| expr(e, on_expr, on_place));
            inouts.iter().for_each(|(_, p)| place(p, on_expr, on_place));
            outputs
                .iter()
                .for_each(|o| place(&o.target, on_expr, on_place));
        }
        ExprKind::Const(_) | ExprKind::CurTime => {}
    }
}

/// Every POU a body calls (functions and function blocks), with repeats.
pub fn calls(stmts: &[Stmt], f: &mut dyn FnMut(PouId)) {
    fn fb_calls(stmts: &[Stmt], f: &mut dyn FnMut(PouId)) {
        for s in stmts {
            match &s.kind {
                StmtKind::CallFb { fb, .. } => f(*fb),
                StmtKind::If {
                    then_body,
                    else_body,
                    ..
                } => {
                    fb_calls(then_body, f);
                    fb_calls(else_body, f);
                }
                StmtKind::Switch { arms, default, .. } => {
                    for a in arms {
                        fb_calls(&a.body, f);
                    }
                    fb_calls(default, f);
                }
                StmtKind::Loop { body, latch } => {
                    fb_calls(body, f);
                    fb_calls(latch, f);
                }
                _ => {}
            }
        }
    }
    fb_calls(stmts, f);
    walk(
        stmts,
        &mut |e| {
            if let ExprKind::CallFn { func, .. } = &e.kind {
                f(*func);
            }
        },
        &mut |_| {},
    );
}

/// Every place a body names (roots of direct addresses included).
pub fn places(stmts: &[Stmt], f: &mut dyn FnMut(&Place)) {
    walk(stmts, &mut |_| {}, f);
}
