//! SPLIT_DATE, SPLIT_TOD, SPLIT_DT, SPLIT_LTOD and SPLIT_LDT (3rd edition,
//! Table 38): the standard functions that give their fields through
//! outputs (`YEAR`, `MONTH`, `DAY`, `HOUR`, `MINUTE`, `SECOND`,
//! `MILLISECOND`, each any integer variable) and have no result.
//!
//! A call is recorded as [`CallTarget::Std`] with the input's type as its
//! one argument type and VOID as its result, the input bound as parameter 0
//! and output `k` as parameter `k + 1`. The lowering evaluates the input
//! once and stores field `k` into each output through `stc_values::call`
//! of the intrinsic with the input and `k` (a LINT), converted to the
//! output's type as `LINT_TO_<type>` converts (an integer keeps its
//! low-order bits: a year in a SINT wraps, as spec/semantics.md has every
//! integer narrowing do; a subrange output is checked): one rule for every
//! engine.

use stc_diagnostics::{Code, Diagnostic, Span};
use stc_syntax::ast::{Arg, ArgKind, ExprId};
use stc_syntax::token::ElemType;
use stc_values::Intrinsic;

use crate::analyzer::{Scope, Sema};
use crate::calls::Write;
use crate::expr::Ctx;
use crate::{BoundArg, BoundArgKind, CallInfo, CallTarget, TypeId};

impl<'a> Sema<'a> {
    /// A call of SPLIT_DATE and its kin (`name` as written): `(IN, outputs
    /// in order)` positionally, or `IN := v` and `YEAR => y`... formally.
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn split_call(
        &mut self,
        e: ExprId,
        name: &str,
        split: (Intrinsic, ElemType, &'static [&'static str]),
        args: &'a [Arg],
        scope: Scope,
        span: Span,
        as_stmt: bool,
    ) -> TypeId {
        let (f, in_elem, outs) = split;
        let in_ty = self.types.elem(in_elem);
        if self.mixed_args(args, scope) {
            return TypeId::ERROR;
        }
        let params = || {
            std::iter::once("IN")
                .chain(outs.iter().copied())
                .collect::<Vec<_>>()
                .join(", ")
        };
        let mut given = vec![false; outs.len() + 1];
        let mut bound = Vec::new();
        for (i, a) in args.iter().enumerate() {
            let (slot, value, negated) = match &a.kind {
                ArgKind::Positional(v) => (i, *v, false),
                ArgKind::Input { name: p, value } => {
                    let key = self.interner.key(p.sym);
                    match outs.iter().position(|o| *o == key) {
                        _ if key == "IN" => (0, *value, false),
                        Some(_) => {
                            let shown = self.spelled(p.sym, p.span);
                            self.emit(
                                Diagnostic::new(
                                    Code::E0407,
                                    a.span,
                                    format!("`{shown}` is an output of {name}"),
                                )
                                .with_help(format!("write `{shown} => variable`")),
                            );
                            self.check_expr(*value, Some(TypeId::ERROR), scope);
                            continue;
                        }
                        None => {
                            self.unknown_split_param(p.sym, p.span, name, &params());
                            self.check_expr(*value, Some(TypeId::ERROR), scope);
                            continue;
                        }
                    }
                }
                ArgKind::Output {
                    name: p,
                    target,
                    negated,
                } => {
                    let key = self.interner.key(p.sym);
                    match outs.iter().position(|o| *o == key) {
                        Some(k) => (k + 1, *target, *negated),
                        None => {
                            self.unknown_split_param(p.sym, p.span, name, &params());
                            self.check_expr(*target, Some(TypeId::ERROR), scope);
                            continue;
                        }
                    }
                }
            };
            if slot > outs.len() {
                self.emit(
                    Diagnostic::new(
                        Code::E0403,
                        a.span,
                        format!("{name} takes {} arguments", outs.len() + 1),
                    )
                    .with_note(format!("its parameters are {}", params())),
                );
                self.check_expr(value, Some(TypeId::ERROR), scope);
                continue;
            }
            if std::mem::replace(&mut given[slot], true) {
                let what = if slot == 0 { "IN" } else { outs[slot - 1] };
                self.error(Code::E0408, a.span, format!("`{what}` is given twice"));
                self.check_expr(value, Some(TypeId::ERROR), scope);
                continue;
            }
            if slot == 0 {
                let vt = self.check_expr(value, Some(in_ty), scope);
                if vt != TypeId::ERROR {
                    self.coerce(value, vt, in_ty, Ctx::Arg, "input `IN`");
                }
                bound.push(BoundArg {
                    param: 0,
                    kind: BoundArgKind::Input(value),
                });
                continue;
            }
            let tt = self.check_lvalue(value, scope, Write::Output);
            if tt != TypeId::ERROR && (negated || !self.types.is_integer(tt)) {
                let msg = format!(
                    "output `{}` of {name} is an integer, which cannot be stored in {}",
                    outs[slot - 1],
                    if negated {
                        "a negated output".to_string()
                    } else {
                        self.tname(tt)
                    }
                );
                self.emit(Diagnostic::new(Code::E0407, self.ast.expr(value).span, msg));
                continue;
            }
            bound.push(BoundArg {
                param: slot as u32,
                kind: BoundArgKind::Output {
                    target: value,
                    negated: false,
                },
            });
        }
        if !given[0] {
            self.emit(
                Diagnostic::new(Code::E0403, span, format!("{name} needs its input `IN`"))
                    .with_note(format!("its parameters are {}", params())),
            );
        }
        self.calls.insert(
            e,
            CallInfo {
                target: CallTarget::Std {
                    intrinsic: f,
                    arg_types: vec![in_ty],
                    ret: TypeId::VOID,
                },
                args: bound,
                en: None,
                eno: None,
            },
        );
        if !as_stmt {
            self.emit(
                Diagnostic::new(Code::E0301, span, format!("{name} has no result"))
                    .with_label("used as a value here")
                    .with_help("call it as a statement and read its outputs"),
            );
            return TypeId::ERROR;
        }
        TypeId::VOID
    }

    fn unknown_split_param(&mut self, sym: stc_syntax::Symbol, at: Span, name: &str, params: &str) {
        let shown = self.spelled(sym, at);
        self.emit(
            Diagnostic::new(
                Code::E0401,
                at,
                format!("{name} has no parameter `{shown}`"),
            )
            .with_note(format!("its parameters are {params}")),
        );
    }
}
