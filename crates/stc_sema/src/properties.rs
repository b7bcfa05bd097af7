//! PROPERTY (CODESYS, docs/oop.md "Properties"): reading `inst.p` calls its
//! GET accessor, `inst.p := v` its SET accessor with `v`. The accessors are
//! METHODs of the block (the parser made them: the getter named like the
//! property, the setter `p.SET`, whose one input is named like the
//! property), so access rules, inheritance and dispatch are the methods'.
//! Inside the block's own body and methods the property is also read and
//! written by its bare name (`p`, `THIS^.p`).

use stc_diagnostics::{Code, Diagnostic, Span};
use stc_syntax::ast::{ExprId, ExprKind, Ident, PropertyPart};

use crate::analyzer::{Scope, Sema};
use crate::expr::Ctx;
use crate::{BoundArg, BoundArgKind, CallInfo, CallTarget, PouId, TypeId, TypeKind};

impl Sema<'_> {
    /// The function block type of an instance expression `x` in POU `p`,
    /// read from declarations only: a variable (of `p`, or of its
    /// block in a method), `THIS^`, or a member of one of those.
    fn instance_type_of(&mut self, x: ExprId, p: PouId) -> Option<PouId> {
        let ty = match &self.ast.expr(x).kind {
            ExprKind::Paren(b) => return self.instance_type_of(*b, p),
            ExprKind::Name(id) => {
                if let Some(v) = self.pous[p.0 as usize].lookup(id.sym) {
                    self.ensure_var(p, v);
                    self.pous[p.0 as usize].var(v).ty
                } else {
                    let fb = self.own_instance(p)?;
                    let v = self.pous[fb.0 as usize].lookup(id.sym)?;
                    self.ensure_var(fb, v);
                    self.pous[fb.0 as usize].var(v).ty
                }
            }
            ExprKind::Deref(b) => {
                if matches!(&self.ast.expr(*b).kind, ExprKind::Name(id) if self.interner.key(id.sym) == "THIS")
                {
                    return self.own_instance(p);
                }
                return None;
            }
            ExprKind::Member { base, member } => {
                let fb = self.instance_type_of(*base, p)?;
                let v = self.pous[fb.0 as usize].lookup(member.sym)?;
                self.ensure_var(fb, v);
                self.pous[fb.0 as usize].var(v).ty
            }
            _ => return None,
        };
        match self.types.kind(ty) {
            TypeKind::Fb(fb) => Some(*fb),
            _ => None,
        }
    }

    /// Which accessor of a property method `m` is.
    pub(crate) fn property_part(&self, m: PouId) -> Option<PropertyPart> {
        let (owner, k) = self.pous.get(m.0 as usize)?.method_of?;
        let ast = self.pou_ast(owner)?;
        ast.methods.get(k)?.property.map(|(part, _)| part)
    }

    /// The accessor `part` of the property `name` of block `fb` (or of
    /// its bases).
    pub(crate) fn accessor(
        &mut self,
        fb: PouId,
        name: stc_syntax::Symbol,
        part: PropertyPart,
    ) -> Option<PouId> {
        let sym = match part {
            PropertyPart::Get => name,
            PropertyPart::Set => {
                let key = format!("{}.SET", self.interner.spelling(name).to_owned());
                self.interner.intern(&key)
            }
        };
        let m = self.find_method(fb, sym)?;
        (self.property_part(m) == Some(part)).then_some(m)
    }

    /// Whether block `fb` (or a base) has a property `name`, with either
    /// accessor.
    fn has_property(&mut self, fb: PouId, name: stc_syntax::Symbol) -> bool {
        self.accessor(fb, name, PropertyPart::Get).is_some()
            || self.accessor(fb, name, PropertyPart::Set).is_some()
    }

    /// `inst.p` read (`this` the instance expression, `None` for the
    /// running instance): a call of the getter recorded on `e`; `None`
    /// when `fb` has no property `p`.
    pub(crate) fn property_read(
        &mut self,
        e: ExprId,
        fb: PouId,
        this: Option<ExprId>,
        member: Ident,
        scope: Scope,
    ) -> Option<TypeId> {
        if !self.has_property(fb, member.sym) {
            return None;
        }
        let Some(get) = self.accessor(fb, member.sym, PropertyPart::Get) else {
            let shown = self.spelled(member.sym, member.span);
            self.emit(
                Diagnostic::new(
                    Code::E1328,
                    member.span,
                    format!("the property `{shown}` has no GET: it can only be written"),
                )
                .with_label("read here"),
            );
            return Some(TypeId::ERROR);
        };
        let span = self.ast.expr(e).span;
        Some(self.method_call(e, get, this, &[], scope, span, member.span))
    }

    /// `target := value` where `target` names a property (`inst.p`, or `p`
    /// in its block): the call of the setter with `value`, recorded on
    /// `target`. `None` when `target` is not a property.
    pub(crate) fn property_write(
        &mut self,
        target: ExprId,
        value: ExprId,
        scope: Scope,
    ) -> Option<()> {
        let Scope::Pou(p) = scope else {
            return None;
        };
        let (fb, this, member) = match &self.ast.expr(target).kind {
            ExprKind::Member { base, member } => {
                // (The base's type from its declaration: it is checked once,
                // by the call or by the ordinary assignment.)
                let fb = self.instance_type_of(*base, p)?;
                // (A variable of that name is the variable.)
                if self.pous[fb.0 as usize].lookup(member.sym).is_some() {
                    return None;
                }
                (fb, Some(*base), *member)
            }
            ExprKind::Name(id) => {
                if self.pous[p.0 as usize].lookup(id.sym).is_some() {
                    return None;
                }
                let fb = self.own_instance(p)?;
                if self.pous[fb.0 as usize].lookup(id.sym).is_some() {
                    return None;
                }
                (fb, None, *id)
            }
            _ => return None,
        };
        if !self.has_property(fb, member.sym) {
            return None;
        }
        if let Some(base) = this {
            // The instance, checked once (it is the call's receiver).
            self.check_expr(base, None, scope);
        }
        let shown = self.spelled(member.sym, member.span);
        let Some(set) = self.accessor(fb, member.sym, PropertyPart::Set) else {
            self.emit(
                Diagnostic::new(
                    Code::E1328,
                    member.span,
                    format!("the property `{shown}` has no SET: it can only be read"),
                )
                .with_label("written here"),
            );
            self.check_expr(value, None, scope);
            return Some(());
        };
        let Some(input) = self.pous[set.0 as usize].lookup(member.sym) else {
            return Some(());
        };
        let ty = self.pous[set.0 as usize].var(input).ty;
        let vt = self.check_expr(value, Some(ty), scope);
        if vt != TypeId::ERROR && ty != TypeId::ERROR {
            let what = format!("the property `{shown}`");
            if self.coerce(value, vt, ty, Ctx::Assign, &what) {
                let span = self.ast.expr(value).span;
                self.check_ptr_store(None, value, ty, span);
            }
        }
        // The access rules, the recursion check: those of the method.
        let span: Span = self.ast.expr(target).span;
        self.method_call(target, set, this, &[], scope, span, member.span);
        if let Some(info) = self.calls.get_mut(&target) {
            info.args = vec![BoundArg {
                param: input.0,
                kind: BoundArgKind::Input(value),
            }];
        } else {
            self.calls.insert(
                target,
                CallInfo {
                    target: CallTarget::Method { method: set, this },
                    args: vec![BoundArg {
                        param: input.0,
                        kind: BoundArgKind::Input(value),
                    }],
                    en: None,
                    eno: None,
                },
            );
        }
        self.set_type(target, ty);
        Some(())
    }
}
