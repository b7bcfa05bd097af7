//! Lowering of Instruction List bodies.
//!
//! The meaning of every instruction is already ST over the current-result
//! leaf (`ast::IlSem`), so most of IL lowers with the ST code: the current
//! result lives in hidden frame variables, one per type it takes in the body
//! (an instruction that loads stores into the one of its type, a leaf reads
//! the one of its type), so every temporary keeps one type, as the back ends
//! want. Jumps are the one thing of IL's own. A body without jumps is a
//! straight sequence; a body with jumps becomes a loop around a switch over
//! a hidden state variable, one arm per block (the instructions from one
//! jump target to the next): a jump sets the state and continues the loop,
//! a block that runs to its end sets the state to the next block, and the
//! last one leaves the loop. So the back ends need nothing new, and a loop
//! written with a backward jump is watched by the step budget like any loop.

use rustc_hash::FxHashMap;
use stc_syntax::ast::{IlBody, IlInstr, IlSem};
use stc_syntax::token::ElemType;
use stc_syntax::Symbol;
use stc_values::Value;

use super::Lowerer;
use crate::{Expr, ExprKind, Place, Root, Stmt, StmtKind, Storage, SwitchArm};
use stc_sema::{TypeId, VarId};

/// Where jumps go: the block of each target label, and the state variable.
struct Blocks {
    of_label: FxHashMap<Symbol, usize>,
    state: VarId,
}

impl<'a> Lowerer<'a> {
    pub(super) fn il_body(&mut self, il: &'a IlBody) -> Vec<Stmt> {
        let labels: FxHashMap<Symbol, usize> = il
            .instrs
            .iter()
            .enumerate()
            .filter_map(|(i, x)| x.label.map(|l| (l.sym, i)))
            .collect();
        let mut starts: Vec<usize> = il
            .instrs
            .iter()
            .filter_map(|x| match &x.sem {
                IlSem::Jump { target, .. } => labels.get(&target.sym).copied(),
                _ => None,
            })
            .collect();
        let mut out = Vec::new();
        if starts.is_empty() {
            for ins in &il.instrs {
                self.il_instr(ins, None, &mut out);
            }
            return out;
        }
        starts.push(0);
        starts.sort_unstable();
        starts.dedup();
        let dint = self.elem_ty(ElemType::Dint);
        let name = self.a.pou(self.pou).name;
        let state = self.hidden(name, "il_state", dint, Storage::Frame, il.span);
        let mut of_label = FxHashMap::default();
        for (i, x) in il.instrs.iter().enumerate() {
            if let (Some(l), Ok(b)) = (x.label, starts.binary_search(&i)) {
                of_label.insert(l.sym, b);
            }
        }
        let blocks = Blocks { of_label, state };
        let mut arms = Vec::new();
        for (b, &start) in starts.iter().enumerate() {
            let end = starts.get(b + 1).copied().unwrap_or(il.instrs.len());
            let mut body = Vec::new();
            for ins in &il.instrs[start..end] {
                self.il_instr(ins, Some(&blocks), &mut body);
            }
            let span = il
                .instrs
                .get(end.saturating_sub(1))
                .map(|x| x.span)
                .unwrap_or(il.span);
            if b + 1 < starts.len() {
                body.push(self.stmt_at(span, self.il_set_state(state, b + 1)));
            } else {
                body.push(self.stmt_at(span, StmtKind::Break));
            }
            arms.push(SwitchArm {
                ranges: vec![(b as i128, b as i128)],
                body,
            });
        }
        out.push(self.stmt_at(il.span, self.il_set_state(state, 0)));
        let selector = Expr {
            kind: ExprKind::Load(self.var_place(state, dint)),
            ty: dint,
        };
        let switch = self.stmt_at(
            il.span,
            StmtKind::Switch {
                selector,
                arms,
                default: vec![self.stmt_at(il.span, StmtKind::Break)],
            },
        );
        out.push(self.stmt_at(
            il.span,
            StmtKind::Loop {
                body: vec![switch],
                latch: Vec::new(),
            },
        ));
        out
    }

    fn il_set_state(&self, state: VarId, b: usize) -> StmtKind {
        let dint = self.elem_ty(ElemType::Dint);
        StmtKind::Assign {
            place: self.var_place(state, dint),
            value: Expr {
                kind: ExprKind::Const(Value::Int(b as i128)),
                ty: dint,
            },
        }
    }

    fn il_instr(&mut self, ins: &'a IlInstr, blocks: Option<&Blocks>, out: &mut Vec<Stmt>) {
        match &ins.sem {
            IlSem::Nothing => {}
            IlSem::Load(v) => {
                let ty = self.a.expr_type(*v);
                let value = self.expr(*v);
                out.append(&mut self.pending);
                let place = self.cr_place(ty);
                out.push(self.stmt_at(ins.span, StmtKind::Assign { place, value }));
            }
            IlSem::Effect { stmts, .. } => {
                for s in stmts {
                    self.stmt(s, out);
                }
            }
            IlSem::SetReset {
                operand,
                bool_form,
                fb_form,
            } => {
                let form = if self.a.il_fb_inputs.contains(operand) {
                    fb_form
                } else {
                    bool_form
                };
                for s in form {
                    self.stmt(s, out);
                }
            }
            IlSem::Jump { cond, target } => {
                let Some(blocks) = blocks else { return };
                let Some(&b) = blocks.of_label.get(&target.sym) else {
                    return;
                };
                let jump = vec![
                    self.stmt_at(ins.span, self.il_set_state(blocks.state, b)),
                    self.stmt_at(ins.span, StmtKind::Continue),
                ];
                match cond {
                    None => out.extend(jump),
                    Some(c) => {
                        let cond = self.expr(*c);
                        out.append(&mut self.pending);
                        out.push(self.stmt_at(
                            ins.span,
                            StmtKind::If {
                                cond,
                                then_body: jump,
                                else_body: Vec::new(),
                            },
                        ));
                    }
                }
            }
        }
    }

    /// The hidden variable that holds the current result when it has type
    /// `ty`.
    pub(super) fn cr_place(&mut self, ty: TypeId) -> Place {
        let v = match self.cr_vars.get(&ty) {
            Some(&v) => v,
            None => {
                let def = self.a.pou(self.pou);
                let (name, span) = (def.name, def.span);
                let v = self.hidden(name, "cr", ty, Storage::Frame, span);
                self.cr_vars.insert(ty, v);
                v
            }
        };
        Place {
            root: Root::Var(v),
            proj: vec![],
            ty,
        }
    }
}
