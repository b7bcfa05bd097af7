//! SPLIT_DATE, SPLIT_TOD and SPLIT_DT (and the L variants) as statements:
//! the input evaluated once (into a hidden variable unless it is a constant
//! or a variable), then each output given
//! `target := <its type>(intrinsic(input, k))`, field `k` of the input as a
//! LINT from `stc_values::call` (`stc_sema::split` says why), converted
//! as `LINT_TO_<type>` converts, and checked against the target's subrange.
//! No back end has a form of its own for them.

use stc_sema::{BoundArgKind, CallInfo, TypeKind};
use stc_syntax::ast::ExprId;
use stc_syntax::token::ElemType;
use stc_values::{Intrinsic, Value};

use super::{located, Lowerer};
use crate::{Expr, ExprKind, Stmt, StmtKind, Storage};

impl<'a> Lowerer<'a> {
    /// The statements of the SPLIT call `e`, added to the pending ones.
    pub(super) fn split_call(&mut self, e: ExprId, info: &CallInfo, f: Intrinsic) {
        let span = self.ast.expr(e).span;
        let (line, col) = self.line_col(span);
        let stmt = |kind| Stmt { kind, line, col };
        let Some(input) = info.args.iter().find_map(|a| match a.kind {
            BoundArgKind::Input(x) if a.param == 0 => Some(x),
            _ => None,
        }) else {
            return;
        };
        let mut x = self.expr(input);
        if !matches!(x.kind, ExprKind::Const(_) | ExprKind::Load(_)) {
            let name = self.a.pou(self.pou).name;
            let t = self.hidden(name, "split", x.ty, Storage::Frame, span);
            let place = self.var_place(t, x.ty);
            self.pending.push(stmt(StmtKind::Assign {
                place: place.clone(),
                value: x.clone(),
            }));
            x = Expr {
                ty: x.ty,
                kind: ExprKind::Load(place),
            };
        }
        let lint = self.elem_ty(ElemType::Lint);
        for a in &info.args {
            let BoundArgKind::Output { target, .. } = a.kind else {
                continue;
            };
            self.writing = true;
            let place = self.place(target);
            self.writing = false;
            let field = Expr {
                ty: lint,
                kind: ExprKind::Intrinsic {
                    func: f,
                    args: vec![
                        x.clone(),
                        Expr {
                            ty: lint,
                            kind: ExprKind::Const(Value::Int(i128::from(a.param) - 1)),
                        },
                    ],
                },
            };
            let mut value = if place.ty == lint {
                field
            } else {
                Expr {
                    ty: place.ty,
                    kind: ExprKind::Convert(Box::new(field)),
                }
            };
            if let TypeKind::Subrange { lo, hi, .. } = self.a.types.kind(place.ty) {
                value = Expr {
                    ty: place.ty,
                    kind: ExprKind::Check {
                        value: Box::new(value),
                        lo: *lo,
                        hi: *hi,
                    },
                };
            }
            if crate::faults::node_may_fault(&self.a.types, &value) {
                value = located((line, col), value);
            }
            self.pending.push(stmt(StmtKind::Assign { place, value }));
        }
    }
}
