//! Inheritance and interfaces (docs/oop.md): method calls that dispatch on
//! the instance's type tag, a derived instance used as its base, an
//! instance as an interface value, and the assignment attempt `?=`.
//!
//! Nothing here needs a back end: a dynamic call is a `SWITCH` over the
//! hidden tag (variable 0 of every block taking part) whose arms are static
//! calls, with THIS bound to the instance seen as the implementing block's
//! type (a reference retyped: the same address, since a base instance is a
//! prefix of a derived one).

use stc_diagnostics::Span;
use stc_sema::{CallInfo, PouId, TypeId, TypeKind, VarId};
use stc_syntax::ast::{ClassKind, ExprId, ExprKind as AK};
use stc_syntax::Symbol;

use super::Lowerer;
use stc_values::BinOp;

use crate::{Expr, ExprKind, Place, Proj, Root, Stmt, StmtKind, Storage, SwitchArm};

impl<'a> Lowerer<'a> {
    /// The type of the instances of function block (class, interface) `p`.
    pub(super) fn fb_type(&self, p: PouId) -> TypeId {
        (0..self.a.types.len() as u32)
            .map(TypeId)
            .find(|t| matches!(self.a.types.kind(*t), TypeKind::Fb(q) if *q == p))
            .unwrap_or(TypeId::ERROR)
    }

    fn fb_of(&self, t: TypeId) -> Option<PouId> {
        match self.a.types.kind(t) {
            TypeKind::Fb(p) => Some(*p),
            _ => None,
        }
    }

    /// `r` as a reference to an instance of `p` (the same address).
    fn retype_ref(&self, r: Expr, p: PouId) -> Expr {
        let t = self.fb_type(p);
        let ty = self.a.types.find_ref(t).unwrap_or(r.ty);
        Expr { ty, ..r }
    }

    /// The instance `place` seen as an instance of its base (or of
    /// itself) `p`.
    pub(super) fn as_instance_of(&self, place: Place, p: PouId) -> Place {
        if self.fb_of(place.ty) == Some(p) || self.fb_of(place.ty).is_none() {
            return place;
        }
        let ty = self.fb_type(p);
        let r = Expr {
            ty: place.ty,
            kind: ExprKind::Ref(place),
        };
        Place {
            root: Root::Deref(Box::new(self.retype_ref(r, p))),
            proj: vec![],
            ty,
        }
    }

    /// A derived instance bound to a VAR_IN_OUT of its base's type.
    pub(super) fn fix_inouts(&self, callee: PouId, inouts: &mut [(VarId, Place)]) {
        let def = self.a.pou(callee);
        for (v, place) in inouts.iter_mut() {
            let Some(want) = self.fb_of(def.var(*v).ty) else {
                continue;
            };
            if self.fb_of(place.ty).is_some_and(|have| have != want) {
                let p = std::mem::replace(
                    place,
                    Place {
                        root: Root::Var(VarId(0)),
                        proj: vec![],
                        ty: TypeId::ERROR,
                    },
                );
                *place = self.as_instance_of(p, want);
            }
        }
    }

    /// Whether a place is an instance of exactly its declared type (a
    /// variable, member or element declared of that type), not one that
    /// may be of a derived type (a VAR_IN_OUT, `r^`, THIS).
    fn exact(&self, p: &Place) -> bool {
        match p.proj.last() {
            Some(Proj::FbVar(fb, v)) => self.a.pou(*fb).var(*v).section != stc_sema::Section::InOut,
            Some(_) => true,
            None => match &p.root {
                Root::Var(v) => {
                    let var = self.vars[*v].storage;
                    var != Storage::Ref
                }
                Root::Global(_) => true,
                _ => false,
            },
        }
    }

    /// The method an instance of exactly `d` runs for `name`.
    fn impl_of(&self, d: PouId, name: Symbol) -> Option<PouId> {
        let mut stack = vec![d];
        let mut seen = Vec::new();
        while let Some(p) = stack.pop() {
            if seen.contains(&p) {
                continue;
            }
            seen.push(p);
            let def = self.a.pou(p);
            if let Some(m) = def
                .methods
                .iter()
                .copied()
                .find(|m| self.a.pou(*m).name == name)
            {
                return Some(m);
            }
            stack.extend(def.interfaces.iter().rev().copied());
            stack.extend(def.base);
        }
        None
    }

    /// Whether `p` has instances: a block or class, not ABSTRACT, not an
    /// interface.
    fn instantiable(&self, p: PouId) -> bool {
        let def = self.a.pou(p);
        def.kind == stc_syntax::ast::PouKind::FunctionBlock
            && def.method_of.is_none()
            && def.class != Some(ClassKind::Interface)
            && !self
                .a
                .pou_syntax(self.ast, p)
                .is_some_and(|s| s.is_abstract)
    }

    /// Whether the receiver expression is `SUPER^` (a static call).
    fn is_super_deref(&self, e: ExprId) -> bool {
        match &self.ast.expr(e).kind {
            AK::Paren(i) => self.is_super_deref(*i),
            AK::Deref(r) => {
                let mut r = *r;
                while let AK::Paren(i) = &self.ast.expr(r).kind {
                    r = *i;
                }
                matches!(self.a.resolutions.get(&r), Some(stc_sema::Res::Super))
            }
            _ => false,
        }
    }

    /// The receiver of a method call: its place (an interface value is
    /// dereferenced) and whether the call is static.
    fn receiver(&mut self, x: ExprId) -> (Place, bool) {
        let ty = self.a.expr_type(x);
        if let Some(t) = self.a.types.ref_target(ty) {
            // An interface value: the instance it refers to, checked
            // against NULL at the call.
            let at = self.line_col(self.ast.expr(x).span);
            let r = super::located(at, self.expr(x));
            let place = Place {
                root: Root::Deref(Box::new(r)),
                proj: vec![],
                ty: t,
            };
            return (place, false);
        }
        let place = self.place(x);
        let fixed = self.is_super_deref(x) || self.exact(&place);
        (place, fixed)
    }

    /// A method call: static when the instance's type is known, else a
    /// SWITCH over its tag (pushed to `self.pending`, the value in a hidden
    /// variable). Returns the call expression of a static call, or the
    /// value (`None` for a dynamic call without a result).
    pub(super) fn method_call(
        &mut self,
        e: ExprId,
        info: &'a CallInfo,
        method: PouId,
        this: Option<ExprId>,
        ty: TypeId,
    ) -> Result<ExprKind, Option<Expr>> {
        let (inputs, mut inouts, outputs) = self.bind(&info.args);
        self.fix_inouts(method, &mut inouts);
        let (target, fixed) = match this {
            Some(x) => self.receiver(x),
            None => (self.this_place(), false),
        };
        let def = self.a.pou(method);
        let name = def.name;
        let owner = def.method_of.map_or(method, |(fb, _)| fb);
        let stat = self.fb_of(target.ty).unwrap_or(owner);
        // The implementations of the types the instance may have.
        let mut arms: Vec<(PouId, Vec<u32>)> = Vec::new();
        if !fixed && self.a.pou(stat).tag.is_some() {
            for d in 0..self.a.pous.len() as u32 {
                let d = PouId(d);
                if !self.instantiable(d) || !self.a.types.is_subtype(d, stat) {
                    continue;
                }
                let Some(m) = self.impl_of(d, name) else {
                    continue;
                };
                let tag = stc_sema::PouDef::tag_value(d);
                match arms.iter_mut().find(|(x, _)| *x == m) {
                    Some((_, tags)) => tags.push(tag),
                    None => arms.push((m, vec![tag])),
                }
            }
        }
        let bind_this = |l: &Self, m: PouId, place: Place, inouts: &mut Vec<(VarId, Place)>| {
            let mdef = l.a.pou(m);
            let owner = mdef.method_of.map_or(m, |(fb, _)| fb);
            if let Some(tv) = mdef.this {
                inouts.push((tv, l.as_instance_of(place, owner)));
            }
        };
        let only_static = arms.len() <= 1 && arms.first().is_none_or(|(m, _)| *m == method);
        if only_static {
            bind_this(self, method, target, &mut inouts);
            return Ok(ExprKind::CallFn {
                func: method,
                inputs,
                inouts,
                outputs,
            });
        }
        let span = self.ast.expr(e).span;
        let stat_ty = self.fb_type(stat);
        let ref_ty = self.a.types.find_ref(stat_ty).unwrap_or(TypeId::ERROR);
        let obj = self.hidden(name, "instance", ref_ty, Storage::Frame, span);
        let set = StmtKind::Assign {
            place: self.var_place(obj, ref_ty),
            value: Expr {
                kind: ExprKind::Ref(target),
                ty: ref_ty,
            },
        };
        let set = self.stmt_at(span, set);
        self.pending.push(set);
        let result = (ty != TypeId::VOID && ty != TypeId::ERROR)
            .then(|| self.hidden(name, "result", ty, Storage::Frame, span));
        let load_obj = |l: &Self| Expr {
            kind: ExprKind::Load(l.var_place(obj, ref_ty)),
            ty: ref_ty,
        };
        let instance = |l: &Self| Place {
            root: Root::Deref(Box::new(load_obj(l))),
            proj: vec![],
            ty: stat_ty,
        };
        let udint = TypeId::of_elem(stc_syntax::token::ElemType::Udint);
        let mut tag_place = instance(self);
        tag_place.proj.push(Proj::FbVar(stat, VarId(0)));
        tag_place.ty = udint;
        let call = |l: &Self, m: PouId| {
            let mut ins = inouts.clone();
            bind_this(l, m, instance(l), &mut ins);
            let value = Expr {
                kind: ExprKind::CallFn {
                    func: m,
                    inputs: inputs.clone(),
                    inouts: ins,
                    outputs: outputs.clone(),
                },
                ty: if result.is_some() { ty } else { TypeId::VOID },
            };
            let kind = match result {
                Some(r) => StmtKind::Assign {
                    place: l.var_place(r, ty),
                    value,
                },
                None => StmtKind::Eval(value),
            };
            vec![l.stmt_at(span, kind)]
        };
        // The most common implementation is the default.
        let default_at = (0..arms.len())
            .max_by_key(|&i| (arms[i].1.len(), usize::MAX - i))
            .unwrap_or(0);
        let default = match arms.get(default_at) {
            Some((m, _)) => call(self, *m),
            None => call(self, method),
        };
        let switch_arms: Vec<SwitchArm> = arms
            .iter()
            .enumerate()
            .filter(|(i, _)| *i != default_at)
            .map(|(_, (m, tags))| SwitchArm {
                ranges: tags
                    .iter()
                    .map(|&t| (i128::from(t), i128::from(t)))
                    .collect(),
                body: call(self, *m),
            })
            .collect();
        let switch = StmtKind::Switch {
            selector: Expr {
                kind: ExprKind::Load(tag_place),
                ty: udint,
            },
            arms: switch_arms,
            default,
        };
        let switch = self.stmt_at(span, switch);
        self.pending.push(switch);
        Err(result.map(|r| Expr {
            kind: ExprKind::Load(self.var_place(r, ty)),
            ty,
        }))
    }

    /// `target ?= value`: `target := value` when the instance `value`
    /// refers to is of `target`'s type (its tag is one of the types
    /// derived from or implementing it), else NULL. Checked against NULL
    /// first: NULL gives NULL.
    pub(super) fn assignment_attempt(
        &mut self,
        target: ExprId,
        value: ExprId,
        span: Span,
    ) -> Vec<Stmt> {
        let place = self.place(target);
        let v = self.expr(value);
        let null = Expr {
            kind: ExprKind::Null,
            ty: place.ty,
        };
        let set_null = self.stmt_at(
            span,
            StmtKind::Assign {
                place: place.clone(),
                value: null,
            },
        );
        let fb = |l: &Self, t: TypeId| l.a.types.ref_target(t).and_then(|x| l.fb_of(x));
        let (Some(want), Some(from)) = (fb(self, place.ty), fb(self, v.ty)) else {
            return vec![set_null];
        };
        let from_ty = self.fb_type(from);
        let ref_ty = self.a.types.find_ref(from_ty).unwrap_or(v.ty);
        let tmp = self.hidden(
            self.a.pou(from).name,
            "attempt",
            ref_ty,
            Storage::Frame,
            span,
        );
        let tmp_place = self.var_place(tmp, ref_ty);
        let load = Expr {
            kind: ExprKind::Load(tmp_place.clone()),
            ty: ref_ty,
        };
        let mut out = vec![
            self.stmt_at(
                span,
                StmtKind::Assign {
                    place: tmp_place,
                    value: Expr { ty: ref_ty, ..v },
                },
            ),
            set_null,
        ];
        let assign = self.stmt_at(
            span,
            StmtKind::Assign {
                place,
                value: self.retype_ref(load.clone(), want),
            },
        );
        let udint = TypeId::of_elem(stc_syntax::token::ElemType::Udint);
        let bool_ty = TypeId::of_elem(stc_syntax::token::ElemType::Bool);
        let check = if self.a.pou(from).tag.is_none() {
            // No tag: the instance is of exactly `from`.
            if !self.a.types.is_subtype(from, want) {
                return out;
            }
            assign
        } else {
            let tags: Vec<(i128, i128)> = (0..self.a.pous.len() as u32)
                .map(PouId)
                .filter(|&d| {
                    self.instantiable(d)
                        && self.a.types.is_subtype(d, want)
                        && self.a.types.is_subtype(d, from)
                })
                .map(|d| {
                    let t = i128::from(stc_sema::PouDef::tag_value(d));
                    (t, t)
                })
                .collect();
            if tags.is_empty() {
                return out;
            }
            let tag_place = Place {
                root: Root::Deref(Box::new(load.clone())),
                proj: vec![Proj::FbVar(from, VarId(0))],
                ty: udint,
            };
            self.stmt_at(
                span,
                StmtKind::Switch {
                    selector: Expr {
                        kind: ExprKind::Load(tag_place),
                        ty: udint,
                    },
                    arms: vec![SwitchArm {
                        ranges: tags,
                        body: vec![assign],
                    }],
                    default: Vec::new(),
                },
            )
        };
        let cond = Expr {
            kind: ExprKind::Binary(
                BinOp::Ne,
                Box::new(load),
                Box::new(Expr {
                    kind: ExprKind::Null,
                    ty: ref_ty,
                }),
            ),
            ty: bool_ty,
        };
        out.push(self.stmt_at(
            span,
            StmtKind::If {
                cond,
                then_body: vec![check],
                else_body: Vec::new(),
            },
        ));
        out
    }
}
