//! Walks over IR bodies that every back end needs: the calls a body makes
//! (to order or select POUs), the places it names (to find the process
//! image), the variables it uses, whether an expression calls a function.
//! One definition, so no back end misses a corner (a call inside the index
//! of an assignment target, an output target, an in-out).

use stc_sema::{PouId, VarId};

use stc_sema::idx::Idx;
use stc_sema::TypeId;

use crate::{Expr, ExprKind, Module, Place, Proj, Root, Stmt, StmtKind, Storage};

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
    if let Root::Deref(r) = &p.root {
        expr(r, on_expr, on_place);
    }
    for pr in &p.proj {
        if let Proj::Index(idx) = pr {
            idx.iter().for_each(|(e, _, _)| expr(e, on_expr, on_place));
        }
    }
}

fn expr(e: &Expr, on_expr: &mut dyn FnMut(&Expr), on_place: &mut dyn FnMut(&Place)) {
    on_expr(e);
    match &e.kind {
        ExprKind::Load(p) | ExprKind::Ref(p) => place(p, on_expr, on_place),
        ExprKind::Unary(_, x) | ExprKind::Convert(x) => expr(x, on_expr, on_place),
        ExprKind::Check { value, .. } => expr(value, on_expr, on_place),
        ExprKind::Located { expr: x, .. } => expr(x, on_expr, on_place),
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
        ExprKind::Const(_) | ExprKind::CurTime | ExprKind::Null => {}
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

/// For each of the `n` variables of the POU whose body this is, whether the
/// body uses it (reads or writes it, as a whole or in part, binds it to an
/// in-out or calls it as an instance).
pub fn used_vars(stmts: &[Stmt], n: usize) -> Vec<bool> {
    let mut used = vec![false; n];
    places(stmts, &mut |p| {
        if let Root::Var(VarId(v)) = p.root {
            if let Some(u) = used.get_mut(v as usize) {
                *u = true;
            }
        }
    });
    used
}

/// Whether evaluating an expression calls a function (which could change
/// variables), in an index of a place it reads included.
pub fn has_call(e: &Expr) -> bool {
    match &e.kind {
        ExprKind::CallFn { .. } => true,
        ExprKind::Const(_) | ExprKind::CurTime | ExprKind::Null => false,
        ExprKind::Load(p) | ExprKind::Ref(p) => place_has_call(p),
        ExprKind::Unary(_, x) | ExprKind::Convert(x) => has_call(x),
        ExprKind::Check { value, .. } => has_call(value),
        ExprKind::Located { expr, .. } => has_call(expr),
        ExprKind::Binary(_, x, y) => has_call(x) || has_call(y),
        ExprKind::Intrinsic { args, .. } => args.iter().any(has_call),
    }
}

/// Whether an index of a place calls a function.
pub fn place_has_call(p: &Place) -> bool {
    if let Root::Deref(r) = &p.root {
        if has_call(r) {
            return true;
        }
    }
    p.proj.iter().any(|pr| match pr {
        Proj::Index(idx) => idx.iter().any(|(e, _, _)| has_call(e)),
        _ => false,
    })
}

/// Which variables of POU `p` a back end may hold in registers (SSA
/// values, C locals) inside one execution of its body, and which of those
/// the body assigns (what it must store back: before a call, at every
/// exit, the fault exits included). A variable qualifies when it is a
/// `scalar` stored in the instance or the frame (not through a reference)
/// and the body only reads it whole and assigns it whole, with a value
/// `same` says it can take as is: never indexes or selects a bit of it,
/// never takes its reference, binds it to an in-out or names it as an
/// output target. A body that dereferences anything, names `THIS` or uses
/// a reference variable (VAR_IN_OUT, VAR_EXTERNAL) keeps everything in
/// memory, since one of those might be an alias of its own variables.
/// Calls are the back end's to handle (store before, reload after: a
/// callee may reach the variables through a reference).
pub fn register_vars(
    m: &Module,
    p: PouId,
    scalar: &dyn Fn(TypeId) -> bool,
    same: &dyn Fn(TypeId, TypeId) -> bool,
) -> (Vec<bool>, Vec<bool>) {
    let pou = &m.pous[p];
    let n = pou.vars.len();
    let mut ok: Vec<bool> = pou
        .vars
        .ids()
        .map(|v| {
            let var = &pou.vars[v];
            var.storage != Storage::Ref && scalar(var.ty)
        })
        .collect();
    let mut written = vec![false; n];
    let mut aliased = false;
    let mut whole = vec![0usize; n];
    let mut named = vec![0usize; n];
    // Every place the body names; those read or assigned whole are
    // counted again below, so a variable named anywhere else is excluded.
    walk(
        &pou.body,
        &mut |e| {
            if let ExprKind::Load(pl) = &e.kind {
                if let (Root::Var(v), true) = (&pl.root, pl.proj.is_empty()) {
                    whole[v.index()] += 1;
                }
            }
        },
        &mut |pl| match &pl.root {
            Root::Var(v) => {
                named[v.index()] += 1;
                if pou.vars[*v].storage == Storage::Ref {
                    aliased = true;
                }
            }
            Root::Deref(_) | Root::This => aliased = true,
            Root::Global(_) | Root::Direct(_) => {}
        },
    );
    fn assigned(
        stmts: &[Stmt],
        same: &dyn Fn(TypeId, TypeId) -> bool,
        whole: &mut [usize],
        written: &mut [bool],
        ok: &mut [bool],
    ) {
        for s in stmts {
            match &s.kind {
                StmtKind::Assign { place, value } => {
                    if let (Root::Var(v), true) = (&place.root, place.proj.is_empty()) {
                        let i = v.index();
                        whole[i] += 1;
                        written[i] = true;
                        if !same(place.ty, value.ty) {
                            ok[i] = false;
                        }
                    }
                }
                StmtKind::If {
                    then_body,
                    else_body,
                    ..
                } => {
                    assigned(then_body, same, whole, written, ok);
                    assigned(else_body, same, whole, written, ok);
                }
                StmtKind::Switch { arms, default, .. } => {
                    for a in arms {
                        assigned(&a.body, same, whole, written, ok);
                    }
                    assigned(default, same, whole, written, ok);
                }
                StmtKind::Loop { body, latch } => {
                    assigned(body, same, whole, written, ok);
                    assigned(latch, same, whole, written, ok);
                }
                _ => {}
            }
        }
    }
    assigned(&pou.body, same, &mut whole, &mut written, &mut ok);
    for i in 0..n {
        if aliased || whole[i] != named[i] || named[i] == 0 {
            ok[i] = false;
        }
    }
    (ok, written)
}

#[cfg(test)]
mod tests {
    #[test]
    fn used_variables_are_those_the_body_names() {
        let m = crate::test_module(
            "FUNCTION_BLOCK F
VAR_INPUT i : INT; unused_in : INT; END_VAR
VAR_OUTPUT o : INT; END_VAR
VAR a : ARRAY[1..3] OF INT; k : INT; never : INT; END_VAR
  a[k] := i;
  F2(x := a[2], y => o);
END_FUNCTION_BLOCK
FUNCTION F2 : INT
VAR_INPUT x : INT; END_VAR
VAR_OUTPUT y : INT; END_VAR
  y := x;
  F2 := 0;
END_FUNCTION
PROGRAM P VAR f : F; END_VAR f(i := 1, unused_in := 2); END_PROGRAM",
        );
        let pou = m
            .pous
            .iter()
            .find(|p| m.name(p.name).eq_ignore_ascii_case("F"))
            .unwrap();
        let used = super::used_vars(&pou.body, pou.vars.len());
        let names: Vec<String> = pou
            .vars
            .iter()
            .zip(&used)
            .filter(|(_, &u)| u)
            .map(|(v, _)| m.name(v.name).to_ascii_lowercase())
            .collect();
        assert_eq!(names, ["i", "o", "a", "k"]);
    }
}
