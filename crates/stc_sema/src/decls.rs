//! Declarations: global names, data types, POU variables, globals, initial
//! values.

use rustc_hash::FxHashMap;
use stc_diagnostics::{Code, Diagnostic, Span};
use stc_syntax::ast::{
    ArrayDim, Edge, Ident, Init, InitKind, Item, PouKind, TypeSpec, TypeSpecKind, VarBlockItems,
    VarKind,
};
use stc_syntax::literal::AddrSize;
use stc_syntax::token::ElemType;
use stc_values::Value;

use crate::analyzer::{GlobalName, Scope, Sema, State, TypeDeclEntry, VarSource};
use crate::types::{EnumValue, Field, InitValue, TypeId, TypeKind};
use crate::{GlobalDef, GlobalId, GlobalOwner, PouDef, PouId, Section, VarDef, VarId};

fn section_of(kind: VarKind) -> Section {
    match kind {
        VarKind::Input => Section::Input,
        VarKind::Output => Section::Output,
        VarKind::InOut => Section::InOut,
        VarKind::External => Section::External,
        VarKind::Global => Section::Global,
        VarKind::Temp => Section::Temp,
        _ => Section::Var,
    }
}

impl<'a> Sema<'a> {
    /// Registers a global name, reporting a duplicate (E0105).
    fn register(&mut self, name: Ident, what: GlobalName) -> bool {
        self.declared.push(name.sym);
        if let Some(prev) = self.names.get(&name.sym).copied() {
            let prev_span = self.global_name_span(prev);
            if self.in_prelude(name.span)
                && crate::prelude::WEAK.contains(&self.interner.key(name.sym))
            {
                // A vendor library name the user declares: the user's.
                return false;
            }
            if let Some(user) = prev_span.filter(|_| self.in_prelude(name.span)) {
                // The user's declaration came first; the standard one is
                // not the user's to see: report the user's.
                let shown = self.spelled(name.sym, user);
                let kind = match what {
                    GlobalName::Pou(_) => "function block",
                    _ => "name",
                };
                self.emit(
                    Diagnostic::new(
                        Code::E0105,
                        user,
                        format!("`{shown}` is a standard {kind} and cannot be declared again"),
                    )
                    .with_label(format!("the standard {kind} `{shown}` is already declared"))
                    .with_help("give this declaration another name"),
                );
                // The name is the standard one's: the user's declaration
                // is dropped, and the standard library (whose charts call
                // TON) keeps its own.
                self.names.insert(name.sym, what);
                return true;
            }
            let shown = self.spelled(name.sym, name.span);
            let mut d = Diagnostic::new(
                Code::E0105,
                name.span,
                format!("`{shown}` is declared twice"),
            )
            .with_label("declared again here");
            if let Some(s) = prev_span {
                if self.in_prelude(s) {
                    d = d.with_note(format!("`{shown}` is a standard function block"));
                } else {
                    d = d.with_secondary(s, "first declared here");
                }
            }
            self.emit(d);
            return false;
        }
        self.names.insert(name.sym, what);
        true
    }

    fn global_name_span(&self, g: GlobalName) -> Option<Span> {
        Some(match g {
            GlobalName::Type(i) => self.type_decls[i].decl.name.span,
            GlobalName::Pou(p) => self.pous[p.0 as usize].name_span,
            GlobalName::Config(c) => match &self.ast.items[c] {
                Item::Configuration(c) => c.name.span,
                _ => return None,
            },
        })
    }

    pub(crate) fn collect(&mut self, items: &[usize]) {
        let ast = self.ast;
        let item_ns = self.build_namespaces();
        for &i in items {
            match &ast.items[i] {
                Item::Types(decls, _) => {
                    for d in decls {
                        let idx = self.type_decls.len();
                        let name = self.qualify(d.name, item_ns[i]);
                        if self.register(name, GlobalName::Type(idx)) {
                            self.type_decls.push(TypeDeclEntry {
                                decl: d,
                                name: name.sym,
                                state: State::Todo,
                                ty: TypeId::ERROR,
                                init: None,
                            });
                        }
                    }
                }
                Item::Pou(p) => {
                    let id = PouId(self.pous.len() as u32);
                    let name = self.qualify(p.name, item_ns[i]);
                    if !self.register(name, GlobalName::Pou(id)) {
                        continue;
                    }
                    if p.internal {
                        self.mark_internal(name.sym, item_ns[i]);
                    }
                    if p.kind == PouKind::Function && !self.in_prelude(p.name.span) {
                        let key = self.interner.key(p.name.sym);
                        let standard = stc_values::lookup(key).is_some()
                            || stc_values::split_lookup(key).is_some()
                            || matches!(key, "CUR_TIME" | "LOWER_BOUND" | "UPPER_BOUND");
                        if standard {
                            let shown = self.spelled(p.name.sym, p.name.span);
                            self.emit(
                                Diagnostic::new(
                                    Code::W0110,
                                    p.name.span,
                                    format!("`{shown}` hides the standard function of the same name"),
                                )
                                .with_label("calls of this name call this function")
                                .with_help("give it another name unless it is meant to replace the standard one"),
                            );
                        }
                    }
                    let fb = self.collect_pou(i, p, None);
                    self.pous[fb.0 as usize].name = name.sym;
                    for (k, m) in p.methods.iter().enumerate() {
                        self.collect_method(i, fb, k, m);
                    }
                }
                Item::Configuration(c) => {
                    self.register(c.name, GlobalName::Config(i));
                }
                Item::GlobalVars(block) => {
                    let ids = self.add_globals(block, GlobalOwner::TopLevel);
                    self.top_globals.extend(ids);
                }
                Item::Namespace(_) | Item::EndNamespace(_) | Item::Using(_) => {}
            }
        }
    }

    /// Registers METHOD `k` of function block `fb` as a POU of its own and
    /// checks its modifiers and name.
    fn collect_method(&mut self, i: usize, fb: PouId, k: usize, m: &'a stc_syntax::ast::Method) {
        let name = m.pou.name;
        let shown = self.spelled(name.sym, name.span);
        let what = if m.is_action { "action" } else { "method" };
        let clash = self.pous[fb.0 as usize]
            .methods
            .iter()
            .find(|q| self.pous[q.0 as usize].name == name.sym)
            .map(|q| self.pous[q.0 as usize].name_span);
        if let Some(first) = clash {
            self.emit(
                Diagnostic::new(
                    Code::E1315,
                    name.span,
                    format!("{what} `{shown}` is declared twice"),
                )
                .with_secondary(first, "first declared here"),
            );
        } else if let Some(v) = self.pous[fb.0 as usize].lookup(name.sym) {
            let first = self.pous[fb.0 as usize].var(v).span;
            self.emit(
                Diagnostic::new(
                    Code::E1315,
                    name.span,
                    format!("{what} `{shown}` has the name of a variable of its POU"),
                )
                .with_secondary(first, "the variable"),
            );
        }
        if m.is_override && self.pou_ast(fb).is_some_and(|a| a.extends.is_none()) {
            self.emit(
                Diagnostic::new(
                    Code::E1309,
                    name.span,
                    format!("`{shown}` overrides no method: its function block extends none"),
                )
                .with_help("remove OVERRIDE"),
            );
        }
        let fb_abstract = self.pou_ast(fb).is_some_and(|a| a.is_abstract);
        if m.is_abstract && !fb_abstract {
            self.emit(
                Diagnostic::new(
                    Code::E1314,
                    name.span,
                    format!("the ABSTRACT method `{shown}` belongs to a function block that is not ABSTRACT"),
                )
                .with_help("give the method a body and remove ABSTRACT"),
            );
        }
        // A method reaches its block's in-outs through their slots, NULL
        // until a call binds them: with a reference type in the program,
        // address 0 is never a variable's (docs/oop.md).
        let fb_type = self.pou_type(fb);
        self.types.ref_to(fb_type);
        let mid = self.collect_pou(i, &m.pou, Some((fb, k)));
        self.pous[mid.0 as usize].access = m.access;
        self.pous[fb.0 as usize].methods.push(mid);
    }

    /// Registers the variables of a POU (or of a METHOD of function block
    /// `method_of`, which also gets its hidden THIS) as a new POU.
    fn collect_pou(
        &mut self,
        i: usize,
        p: &'a stc_syntax::ast::Pou,
        method_of: Option<(PouId, usize)>,
    ) -> PouId {
        let id = PouId(self.pous.len() as u32);
        let mut def = PouDef {
            kind: p.kind,
            name: p.name.sym,
            span: p.span,
            name_span: p.name.span,
            item: i,
            vars: Vec::new(),
            return_type: None,
            is_std: self.in_prelude(p.span),
            var_index: FxHashMap::default(),
            en: None,
            eno: None,
            method_of,
            this: None,
            access: None,
            methods: Vec::new(),
            class: if method_of.is_none() { p.class } else { None },
            base: None,
            interfaces: Vec::new(),
            inherited: 0,
            tag: None,
        };
        let mut src = Vec::new();
        if p.kind == PouKind::Function && p.return_type.is_some() {
            def.vars.push(VarDef {
                name: p.name.sym,
                span: p.name.span,
                section: Section::Result,
                ty: TypeId::ERROR,
                init: None,
                constant: false,
                retain: false,
                location: None,
                edge: None,
                implicit: false,
            });
            def.var_index.insert(p.name.sym, VarId(0));
            src.push(None);
        }
        // VAR_INST of a method: variables of its block (below); VAR_STAT:
        // globals of their own (docs/oop.md, "VAR_STAT and VAR_INST").
        let mut blocks: Vec<(&'a stc_syntax::ast::VarBlock, Option<stc_syntax::Symbol>)> =
            Vec::new();
        for block in &p.var_blocks {
            match block.kind {
                VarKind::Stat => {
                    for g in self.add_globals(block, GlobalOwner::TopLevel) {
                        let local = self.globals[g.0 as usize].var.name;
                        let key = format!(
                            "{}.{}",
                            self.interner.spelling(p.name.sym).to_owned(),
                            self.interner.spelling(local).to_owned()
                        );
                        let mangled = self.interner.intern(&key);
                        self.globals[g.0 as usize].var.name = mangled;
                        self.statics.insert((id, local), g);
                    }
                }
                VarKind::Inst if method_of.is_some() => {}
                VarKind::Inst => {
                    self.emit(
                        Diagnostic::new(
                            Code::E0030,
                            block.span,
                            "`VAR_INST` outside a METHOD is not supported",
                        )
                        .with_label("read as VAR")
                        .with_help("VAR_INST keeps a METHOD's variables in its instance; in a POU body, use VAR"),
                    );
                    blocks.push((block, None));
                }
                _ => blocks.push((block, None)),
            }
        }
        if p.kind == PouKind::FunctionBlock && method_of.is_none() {
            // The VAR_INST variables of its methods, named `method.name`.
            for m in &p.methods {
                for block in m.pou.var_blocks.iter().filter(|b| b.kind == VarKind::Inst) {
                    blocks.push((block, Some(m.pou.name.sym)));
                }
            }
        }
        for (block, method) in blocks {
            let VarBlockItems::Vars(decls) = &block.items else {
                continue;
            };
            for decl in decls {
                for name in &decl.names {
                    let v = VarId(def.vars.len() as u32);
                    let mut name = *name;
                    if let Some(m) = method {
                        let key = format!(
                            "{}.{}",
                            self.interner.spelling(m).to_owned(),
                            self.interner.spelling(name.sym).to_owned()
                        );
                        let local = name.sym;
                        name.sym = self.interner.intern(&key);
                        self.inst_vars.insert((id, m, local), v);
                    }
                    if let Some(prev) = def.var_index.get(&name.sym) {
                        let first = def.vars[prev.0 as usize].span;
                        let shown = self.spelled(name.sym, name.span);
                        let d = Diagnostic::new(
                            Code::E0105,
                            name.span,
                            format!(
                                "`{shown}` is declared twice in `{}`",
                                self.sym_name(p.name.sym)
                            ),
                        )
                        .with_label("declared again here")
                        .with_secondary(first, "first declared here");
                        self.emit(d);
                        continue;
                    }
                    def.var_index.insert(name.sym, v);
                    def.vars.push(VarDef {
                        name: name.sym,
                        span: name.span,
                        section: section_of(block.kind),
                        ty: TypeId::ERROR,
                        init: None,
                        constant: block.constant,
                        retain: block.retention == Some(stc_syntax::ast::Retention::Retain),
                        location: decl.location.as_ref().map(|l| l.address.clone()),
                        edge: decl.edge,
                        implicit: false,
                    });
                    src.push(Some(VarSource { block, decl }));
                }
            }
        }
        if let Some((fb, _)) = method_of {
            // The instance the method runs on: a reference, bound by every
            // call (no EN/ENO: a method call is not gated).
            let this = VarId(def.vars.len() as u32);
            let ty = self.pou_type(fb);
            let sym = self.intern("THIS");
            def.vars.push(VarDef {
                name: sym,
                span: def.name_span,
                section: Section::InOut,
                ty,
                init: None,
                constant: false,
                retain: false,
                location: None,
                edge: None,
                implicit: true,
            });
            def.this = Some(this);
            src.push(None);
        } else if matches!(p.kind, PouKind::Function | PouKind::FunctionBlock) {
            self.add_execution_control(&mut def, &mut src);
        }
        let n = def.vars.len();
        self.pous.push(def);
        self.pou_var_src.push(src);
        self.pou_var_state.push(vec![State::Todo; n]);
        self.pou_state.push(State::Todo);
        id
    }

    /// EN and ENO (ed2 2.5.1.2): every function and function block has the
    /// BOOL input EN and the BOOL output ENO, TRUE at the start of each
    /// call. A user's own VAR_INPUT EN or VAR_OUTPUT ENO takes their place.
    fn add_execution_control(&mut self, def: &mut PouDef, src: &mut Vec<Option<VarSource<'a>>>) {
        let bool_ty = self.types.elem(ElemType::Bool);
        for (word, section) in [("EN", Section::Input), ("ENO", Section::Output)] {
            let sym = self.intern(word);
            let v = match def.var_index.get(&sym) {
                Some(&v) if def.vars[v.0 as usize].section == section => v,
                Some(_) => continue,
                None => {
                    let v = VarId(def.vars.len() as u32);
                    def.vars.push(VarDef {
                        name: sym,
                        span: def.name_span,
                        section,
                        ty: bool_ty,
                        init: Some(InitValue::Scalar(Value::Bool(true))),
                        constant: false,
                        retain: false,
                        location: None,
                        edge: None,
                        implicit: true,
                    });
                    def.var_index.insert(sym, v);
                    src.push(None);
                    v
                }
            };
            match section {
                Section::Input => def.en = Some(v),
                _ => def.eno = Some(v),
            }
        }
    }

    /// Adds the variables of a VAR_GLOBAL block (resolved later).
    pub(crate) fn add_globals(
        &mut self,
        block: &'a stc_syntax::ast::VarBlock,
        owner: GlobalOwner,
    ) -> Vec<GlobalId> {
        let mut ids = Vec::new();
        let VarBlockItems::Vars(decls) = &block.items else {
            return ids;
        };
        for decl in decls {
            let mut names: Vec<(stc_syntax::Symbol, Span)> =
                decl.names.iter().map(|n| (n.sym, n.span)).collect();
            if names.is_empty() {
                // An unnamed located global (`AT %IX0.0 : BOOL;`).
                if let Some(l) = &decl.location {
                    let sym = self.intern(&l.address.to_string());
                    names.push((sym, l.span));
                }
            }
            for (sym, span) in names {
                let id = GlobalId(self.globals.len() as u32);
                self.globals.push(GlobalDef {
                    var: VarDef {
                        name: sym,
                        span,
                        section: Section::Global,
                        ty: TypeId::ERROR,
                        init: None,
                        constant: block.constant,
                        retain: block.retention == Some(stc_syntax::ast::Retention::Retain),
                        location: decl.location.as_ref().map(|l| l.address.clone()),
                        edge: None,
                        implicit: false,
                    },
                    owner,
                });
                self.global_src.push(VarSource { block, decl });
                self.declared.push(sym);
                self.global_state.push(State::Todo);
                ids.push(id);
            }
        }
        ids
    }

    // ----- data types -------------------------------------------------------

    pub(crate) fn resolve_type_decl(&mut self, i: usize) -> (TypeId, Option<InitValue>) {
        match self.type_decls[i].state {
            State::Done => return (self.type_decls[i].ty, self.type_decls[i].init.clone()),
            State::InProgress => {
                let d = self.type_decls[i].decl;
                let name = self.spelled(d.name.sym, d.name.span);
                self.error(
                    Code::E0102,
                    d.name.span,
                    format!("type `{name}` is defined in terms of itself"),
                );
                return (TypeId::ERROR, None);
            }
            State::Todo => {}
        }
        self.type_decls[i].state = State::InProgress;
        let decl = self.type_decls[i].decl;
        let name = self.type_decls[i].name;
        let (mut ty, mut init) = self.resolve_type_spec(&decl.spec, Scope::Global, Some(name));
        if self.types.get(ty).name == Some(name) {
            self.types.set_name_span(ty, decl.name.span);
        }
        if let Some(i) = &decl.init {
            init = self.init_value(i, ty, Scope::Global);
        }
        // `REF_TO` this type inside its own declaration (a linked list):
        // the reference made before the type existed now refers to it.
        for ptr in [false, true] {
            let Some(r) = self.pending_refs.remove(&(i, ptr)) else {
                continue;
            };
            let wrap = |t| {
                if ptr {
                    TypeKind::Ptr(t)
                } else {
                    TypeKind::Ref(t)
                }
            };
            if r == ty {
                // `TYPE R : REF_TO R;`: a reference to itself, no type.
                let name = self.spelled(decl.name.sym, decl.name.span);
                self.error(
                    Code::E0102,
                    decl.name.span,
                    format!("type `{name}` is defined in terms of itself"),
                );
                *self.types.kind_mut(r) = wrap(TypeId::ERROR);
                ty = TypeId::ERROR;
            } else {
                *self.types.kind_mut(r) = wrap(ty);
            }
        }
        let e = &mut self.type_decls[i];
        e.state = State::Done;
        e.ty = ty;
        e.init = init.clone();
        (ty, init)
    }

    /// The type of an FB or program used as a data type.
    pub(crate) fn pou_type(&mut self, p: PouId) -> TypeId {
        if let Some(&t) = self.fb_types.get(&p) {
            return t;
        }
        let pou = &self.pous[p.0 as usize];
        let kind = match pou.kind {
            PouKind::Program => TypeKind::Program(p),
            _ => TypeKind::Fb(p),
        };
        let t = self.types.add(kind, Some(pou.name), Some(pou.name_span));
        self.types.set_name_span(t, pou.name_span);
        self.fb_types.insert(p, t);
        t
    }

    /// A constant integer from an expression (array bounds, lengths...).
    pub(crate) fn const_int(
        &mut self,
        e: stc_syntax::ast::ExprId,
        scope: Scope,
        what: &str,
    ) -> Option<i128> {
        // A top-level VAR_GLOBAL CONSTANT may size a type inside a POU
        // without VAR_EXTERNAL (`STRING[STRING_LENGTH]`, as OSCAT and every
        // CODESYS library write it; a FUNCTION cannot even declare the
        // external): only its value is used, at compile time.
        let outer = std::mem::replace(&mut self.in_type_constant, true);
        let t = self.check_expr(e, None, scope);
        self.in_type_constant = outer;
        if t == TypeId::ERROR {
            return None;
        }
        match self.consts.get(&e) {
            Some(Value::Int(v)) if self.types.is_integer(t) => Some(*v),
            Some(_) | None => {
                let span = self.ast.expr(e).span;
                let msg = if self.consts.contains_key(&e) {
                    format!("{what} must be an integer constant")
                } else {
                    format!("{what} must be a constant expression")
                };
                self.error(Code::E0705, span, msg);
                None
            }
        }
    }

    /// Resolves a type written in a declaration; `name` names the new type
    /// when the spec is the body of a TYPE declaration.
    pub(crate) fn resolve_type_spec(
        &mut self,
        spec: &TypeSpec,
        scope: Scope,
        name: Option<stc_syntax::Symbol>,
    ) -> (TypeId, Option<InitValue>) {
        let span = Some(spec.span);
        match &spec.kind {
            TypeSpecKind::Error => (TypeId::ERROR, None),
            TypeSpecKind::Elementary(e) => (self.types.elem(*e), None),
            TypeSpecKind::Generic(g) => {
                self.error(
                    Code::E0102,
                    spec.span,
                    format!(
                        "the generic type `{}` can only be used by standard functions",
                        g.name()
                    ),
                );
                (TypeId::ERROR, None)
            }
            TypeSpecKind::Named(id) => self.named_type(*id),
            TypeSpecKind::String { wide, len } => {
                let n = match len {
                    Some(e) => match self.const_int(*e, scope, "a string length") {
                        Some(n) if (1..=65_535).contains(&n) => n as u32,
                        Some(n) => {
                            let s = self.ast.expr(*e).span;
                            self.error(
                                Code::E0705,
                                s,
                                format!("a string length must be 1..65535, not {n}"),
                            );
                            crate::types::DEFAULT_STRING_LEN
                        }
                        None => crate::types::DEFAULT_STRING_LEN,
                    },
                    None => crate::types::DEFAULT_STRING_LEN,
                };
                (self.types.string(*wide, n), None)
            }
            TypeSpecKind::Subrange { base, lo, hi } => {
                let (bt, _) = self.resolve_type_spec(base, scope, None);
                let Some(b) = self
                    .types
                    .numeric(bt)
                    .filter(|b| stc_values::is_integer(*b))
                else {
                    if bt != TypeId::ERROR {
                        self.error(
                            Code::E0705,
                            base.span,
                            "a subrange needs an integer base type",
                        );
                    }
                    return (TypeId::ERROR, None);
                };
                let l = self.const_int(*lo, scope, "a subrange limit");
                let h = self.const_int(*hi, scope, "a subrange limit");
                let (Some(l), Some(h)) = (l, h) else {
                    return (TypeId::ERROR, None);
                };
                let (min, max) = stc_values::int_range(b).unwrap_or((i128::MIN, i128::MAX));
                if l > h || l < min || h > max {
                    let s = self.ast.expr(*lo).span.to(self.ast.expr(*hi).span);
                    self.error(
                        Code::E0705,
                        s,
                        format!("invalid subrange {l}..{h} of {}", b.name()),
                    );
                    return (TypeId::ERROR, None);
                }
                let t = self.types.add(
                    TypeKind::Subrange {
                        base: b,
                        lo: l,
                        hi: h,
                    },
                    name,
                    span,
                );
                (t, Some(InitValue::Scalar(Value::Int(l))))
            }
            TypeSpecKind::Enum { values, base } => {
                let mut base_ty = ElemType::Int;
                if let Some(b) = base {
                    let (bt, _) = self.resolve_type_spec(b, scope, None);
                    match self.types.numeric(bt) {
                        Some(e)
                            if stc_values::is_integer(e)
                                || (stc_values::is_bit_string(e) && e != ElemType::Bool) =>
                        {
                            base_ty = e
                        }
                        _ if bt == TypeId::ERROR => {}
                        _ => self.error(
                            Code::E0705,
                            b.span,
                            "an enumeration's base type must be an integer or bit-string type",
                        ),
                    }
                }
                let mut out: Vec<EnumValue> = Vec::new();
                let mut next: i128 = 0;
                for m in values {
                    if let Some(prev) = out.iter().find(|v| v.name == m.name.sym) {
                        let shown = self.spelled(m.name.sym, m.name.span);
                        let d = Diagnostic::new(
                            Code::E0105,
                            m.name.span,
                            format!("enumeration value `{shown}` is declared twice"),
                        )
                        .with_secondary(prev.span, "first declared here");
                        self.emit(d);
                        continue;
                    }
                    let value = match m.value {
                        Some(e) => self
                            .const_int(e, scope, "an enumeration value")
                            .unwrap_or(next),
                        None => next,
                    };
                    next = value + 1;
                    out.push(EnumValue {
                        name: m.name.sym,
                        value,
                        span: m.name.span,
                    });
                }
                if base.is_none()
                    && out
                        .iter()
                        .any(|v| !(i16::MIN as i128..=i16::MAX as i128).contains(&v.value))
                {
                    base_ty = ElemType::Dint;
                }
                let first = out.first().map(|v| v.value).unwrap_or(0);
                let owner = match (name, scope) {
                    (None, Scope::Pou(p)) => Some(p),
                    _ => None,
                };
                let members: Vec<(stc_syntax::Symbol, Span)> =
                    out.iter().map(|v| (v.name, v.span)).collect();
                let t = self.types.add(
                    TypeKind::Enum {
                        values: out,
                        base: base_ty,
                    },
                    name,
                    span,
                );
                // A local value hiding a global one is W0102 at each use
                // (`warn_hidden_enum_value`).
                for (i, (sym, _)) in members.into_iter().enumerate() {
                    self.declared.push(sym);
                    self.enum_index
                        .entry(sym)
                        .or_default()
                        .push((t, i as u32, owner));
                }
                (t, Some(InitValue::Scalar(Value::Int(first))))
            }
            TypeSpecKind::Array { dims, elem } => {
                let mut out = Vec::new();
                let mut ok = true;
                for d in dims {
                    match d {
                        ArrayDim::Range { lo, hi } => {
                            let l = self.const_int(*lo, scope, "an array bound");
                            let h = self.const_int(*hi, scope, "an array bound");
                            match (l, h) {
                                (Some(l), Some(h)) if l <= h => out.push((l, h)),
                                (Some(l), Some(h)) => {
                                    let s = self.ast.expr(*lo).span.to(self.ast.expr(*hi).span);
                                    self.error(
                                        Code::E0705,
                                        s,
                                        format!("array bounds {l}..{h} are inverted"),
                                    );
                                    ok = false;
                                }
                                _ => ok = false,
                            }
                        }
                        ArrayDim::Star(s) => {
                            self.error(
                                Code::E0030,
                                *s,
                                "arrays of variable length (`*`) are not supported yet",
                            );
                            ok = false;
                        }
                    }
                }
                let (et, _) = self.resolve_type_spec(elem, scope, None);
                if !ok || et == TypeId::ERROR {
                    return (TypeId::ERROR, None);
                }
                // (Checked: many huge dimensions overflow even an i128.)
                let count = out
                    .iter()
                    .try_fold(1i128, |n, (l, h)| n.checked_mul(h - l + 1));
                if count.is_none_or(|c| c > 16 << 20) {
                    let count = match count {
                        Some(c) => c.to_string(),
                        None => format!("more than {}", i128::MAX),
                    };
                    self.error(
                        Code::E0705,
                        spec.span,
                        format!("an array of {count} elements is too large"),
                    );
                    return (TypeId::ERROR, None);
                }
                (
                    self.types.add(
                        TypeKind::Array {
                            dims: out,
                            elem: et,
                        },
                        name,
                        span,
                    ),
                    None,
                )
            }
            TypeSpecKind::Struct { members } => {
                let mut fields: Vec<Field> = Vec::new();
                for m in members {
                    let (ft, tinit) = self.resolve_type_spec(&m.ty, scope, None);
                    let init = match &m.init {
                        Some(i) => self.init_value(i, ft, scope),
                        None => tinit,
                    };
                    for n in &m.names {
                        if let Some(prev) = fields.iter().find(|f| f.name == n.sym) {
                            let shown = self.spelled(n.sym, n.span);
                            let d = Diagnostic::new(
                                Code::E0105,
                                n.span,
                                format!("member `{shown}` is declared twice"),
                            )
                            .with_secondary(prev.span, "first declared here");
                            self.emit(d);
                            continue;
                        }
                        fields.push(Field {
                            name: n.sym,
                            ty: ft,
                            init: init.clone(),
                            span: n.span,
                        });
                    }
                }
                (
                    self.types.add(TypeKind::Struct { fields }, name, span),
                    None,
                )
            }
            TypeSpecKind::Ref(target) | TypeSpecKind::Pointer(target) => {
                let ptr = matches!(spec.kind, TypeSpecKind::Pointer(_));
                // A reference to a named type being declared (`next :
                // REF_TO Node` inside Node) is completed when the type is.
                if let TypeSpecKind::Named(id) = &target.kind {
                    if let Some(GlobalName::Type(i)) = self.global_name(*id) {
                        if self.type_decls[i].state == State::InProgress {
                            if let Some(&r) = self.pending_refs.get(&(i, ptr)) {
                                return (r, None);
                            }
                            let kind = if ptr {
                                TypeKind::Ptr(TypeId::ERROR)
                            } else {
                                TypeKind::Ref(TypeId::ERROR)
                            };
                            let r = self.types.add(kind, None, None);
                            self.pending_refs.insert((i, ptr), r);
                            return (r, None);
                        }
                    }
                }
                let (t, _) = self.resolve_type_spec(target, scope, None);
                if t == TypeId::ERROR {
                    return (TypeId::ERROR, None);
                }
                if ptr {
                    (self.types.ptr_to(t), None)
                } else {
                    (self.types.ref_to(t), None)
                }
            }
        }
    }

    fn named_type(&mut self, id: Ident) -> (TypeId, Option<InitValue>) {
        match self.global_name(id) {
            Some(GlobalName::Type(i)) => self.resolve_type_decl(i),
            Some(GlobalName::Pou(p)) => match self.pous[p.0 as usize].kind {
                PouKind::Function => {
                    let shown = self.spelled(id.sym, id.span);
                    self.error(
                        Code::E0102,
                        id.span,
                        format!("`{shown}` is a function, not a type"),
                    );
                    (TypeId::ERROR, None)
                }
                // An interface value: a reference to an instance of a
                // block implementing it (NULL until assigned).
                _ if self.pous[p.0 as usize].class
                    == Some(stc_syntax::ast::ClassKind::Interface) =>
                {
                    let t = self.pou_type(p);
                    (self.types.ref_to(t), None)
                }
                _ => (self.pou_type(p), None),
            },
            // An INTERFACE or another construct already reported.
            _ if self.unsupported_names.contains(&id.sym) => (TypeId::ERROR, None),
            _ => {
                let shown = self.spelled(id.sym, id.span);
                let mut d =
                    Diagnostic::new(Code::E0102, id.span, format!("unknown type `{shown}`"))
                        .with_label("not a declared type");
                let candidates: Vec<String> = self
                    .names
                    .iter()
                    .filter(|(_, g)| !matches!(g, GlobalName::Config(_)))
                    .map(|(s, _)| self.sym_name(*s))
                    .chain(ElemType::ALL.iter().map(|e| e.name().to_string()))
                    .collect();
                if let Some(s) = self.did_you_mean(&shown, candidates.iter().map(|s| s.as_str())) {
                    d = d.with_help(format!("did you mean `{s}`?"));
                }
                self.emit(d);
                (TypeId::ERROR, None)
            }
        }
    }

    // ----- initial values ---------------------------------------------------

    /// Evaluates an initial value for a variable of type `ty`.
    pub(crate) fn init_value(
        &mut self,
        init: &Init,
        ty: TypeId,
        scope: Scope,
    ) -> Option<InitValue> {
        if ty == TypeId::ERROR {
            // Still check the expressions, for their own errors.
            if let InitKind::Expr(e) = &init.kind {
                self.check_expr(*e, None, scope);
            }
            return None;
        }
        if matches!(self.types.kind(ty), TypeKind::Ref(_)) {
            // A reference starts as NULL; no other initial value.
            let is_null = match &init.kind {
                InitKind::Expr(e) => {
                    let t = self.check_expr(*e, Some(ty), scope);
                    t == TypeId::ERROR || self.types.ref_target(t) == Some(TypeId::VOID)
                }
                _ => false,
            };
            if !is_null {
                self.emit(
                    Diagnostic::new(
                        Code::E1306,
                        init.span,
                        "a reference can only be initialised with NULL",
                    )
                    .with_help("assign `r := REF(x);` in the body"),
                );
            }
            return None;
        }
        match &init.kind {
            InitKind::Expr(e) => {
                if matches!(
                    self.types.kind(ty),
                    TypeKind::Array { .. }
                        | TypeKind::Struct { .. }
                        | TypeKind::Fb(_)
                        | TypeKind::Program(_)
                ) {
                    let t = self.check_expr(*e, None, scope);
                    if t != TypeId::ERROR {
                        let msg = format!(
                            "a value of type {} cannot initialise a variable of type {}",
                            self.tname(t),
                            self.tname(ty)
                        );
                        self.error(Code::E0208, init.span, msg);
                    }
                    return None;
                }
                let vt = self.check_expr(*e, Some(ty), scope);
                if vt == TypeId::ERROR || !self.coerce_init(*e, vt, ty) {
                    return None;
                }
                match self.consts.get(e).cloned() {
                    Some(v) => {
                        let v = self.convert_const(&v, vt, ty);
                        self.check_subrange(&v, ty, self.ast.expr(*e).span);
                        v.map(InitValue::Scalar)
                    }
                    None => {
                        self.error(
                            Code::E0208,
                            init.span,
                            "an initial value must be a constant expression",
                        );
                        None
                    }
                }
            }
            InitKind::Array(elems) => {
                let TypeKind::Array { dims, elem } = self.types.kind(ty).clone() else {
                    let msg = format!(
                        "an array initialiser cannot initialise a variable of type {}",
                        self.tname(ty)
                    );
                    self.error(Code::E0208, init.span, msg);
                    return None;
                };
                let total: i128 = dims.iter().map(|(l, h)| h - l + 1).product();
                let mut out: Vec<Option<InitValue>> = Vec::new();
                let mut reported = false;
                for el in elems {
                    let count = match el.repeat {
                        Some(r) => self
                            .const_int(r, scope, "a repetition count")
                            .unwrap_or(0)
                            .max(0),
                        None => 1,
                    };
                    let values: Vec<Option<InitValue>> = if el.values.is_empty() {
                        vec![None]
                    } else {
                        el.values
                            .iter()
                            .map(|v| self.init_value(v, elem, scope))
                            .collect()
                    };
                    for _ in 0..count {
                        for v in &values {
                            if (out.len() as i128) < total {
                                out.push(v.clone());
                            } else if !reported {
                                reported = true;
                                self.error(
                                    Code::E0208,
                                    el.span,
                                    format!(
                                        "too many initial values: the array has {total} elements"
                                    ),
                                );
                            }
                        }
                    }
                }
                Some(InitValue::Array(out))
            }
            InitKind::Struct(elems) => {
                let members: Vec<(stc_syntax::Symbol, TypeId)> = match self.types.kind(ty).clone() {
                    TypeKind::Struct { fields } => fields.iter().map(|f| (f.name, f.ty)).collect(),
                    TypeKind::Fb(p) => {
                        self.resolve_pou(p);
                        self.pous[p.0 as usize]
                            .vars
                            .iter()
                            .filter(|v| {
                                matches!(v.section, Section::Input | Section::Output | Section::Var)
                            })
                            .map(|v| (v.name, v.ty))
                            .collect()
                    }
                    _ => {
                        let msg = format!(
                            "a structure initialiser cannot initialise a variable of type {}",
                            self.tname(ty)
                        );
                        self.error(Code::E0208, init.span, msg);
                        return None;
                    }
                };
                let mut out = Vec::new();
                for el in elems {
                    let Some(&(_, mt)) = members.iter().find(|(n, _)| *n == el.name.sym) else {
                        let shown = self.spelled(el.name.sym, el.name.span);
                        let msg = format!("{} has no member `{shown}`", self.tname(ty));
                        self.error(Code::E0104, el.name.span, msg);
                        continue;
                    };
                    if out.iter().any(|(n, _)| *n == el.name.sym) {
                        let shown = self.spelled(el.name.sym, el.name.span);
                        self.error(
                            Code::E0408,
                            el.name.span,
                            format!("`{shown}` is initialised twice"),
                        );
                        continue;
                    }
                    if let Some(v) = self.init_value(&el.value, mt, scope) {
                        out.push((el.name.sym, v));
                    }
                }
                Some(InitValue::Struct(out))
            }
        }
    }

    // ----- POU variables ------------------------------------------------------

    /// Resolves every variable of a POU (types, initial values, checks).
    pub(crate) fn resolve_pou(&mut self, p: PouId) {
        if self.pou_state[p.0 as usize] != State::Todo {
            return;
        }
        self.pou_state[p.0 as usize] = State::InProgress;
        for v in 0..self.pous[p.0 as usize].vars.len() {
            self.ensure_var(p, VarId(v as u32));
        }
        self.pou_state[p.0 as usize] = State::Done;
    }

    pub(crate) fn ensure_var(&mut self, p: PouId, v: VarId) {
        let (pi, vi) = (p.0 as usize, v.0 as usize);
        match self.pou_var_state[pi][vi] {
            State::Done => return,
            State::InProgress => {
                let var = &self.pous[pi].vars[vi];
                let span = var.span;
                let name = self.sym_name(var.name);
                self.error(
                    Code::E0705,
                    span,
                    format!("the declaration of `{name}` depends on itself"),
                );
                self.pou_var_state[pi][vi] = State::Done;
                return;
            }
            State::Todo => {}
        }
        if let Some(b) = self.pous[pi]
            .base
            .filter(|_| (vi as u32) < self.pous[pi].inherited)
        {
            // Inherited: the base's type and initial value.
            self.pou_var_state[pi][vi] = State::InProgress;
            self.ensure_var(b, v);
            let bv = self.pous[b.0 as usize].vars[vi].clone();
            let var = &mut self.pous[pi].vars[vi];
            var.ty = bv.ty;
            var.init = bv.init;
            self.pou_var_state[pi][vi] = State::Done;
            return;
        }
        if self.pous[pi].vars[vi].implicit {
            // EN and ENO: BOOL, TRUE, nothing to resolve.
            self.pou_var_state[pi][vi] = State::Done;
            return;
        }
        self.pou_var_state[pi][vi] = State::InProgress;
        let scope = Scope::Pou(p);
        let Some(src) = self.pou_var_src[pi][vi] else {
            // A function's result variable.
            if let Some(pou) = self.pou_ast(p) {
                if let Some(rt) = &pou.return_type {
                    let (t, init) = self.resolve_type_spec(rt, scope, None);
                    if matches!(self.types.kind(t), TypeKind::Fb(_) | TypeKind::Program(_)) {
                        self.error(
                            Code::E0102,
                            rt.span,
                            "a function cannot return a function block",
                        );
                    }
                    let var = &mut self.pous[pi].vars[vi];
                    var.ty = t;
                    var.init = init;
                    self.pous[pi].return_type = Some(t);
                }
            }
            self.pou_var_state[pi][vi] = State::Done;
            return;
        };
        let (ty, type_init) = self.resolve_type_spec(&src.decl.ty, scope, None);
        let init = match &src.decl.init {
            Some(i) => self.init_value(i, ty, scope),
            None => type_init,
        };
        {
            let var = &mut self.pous[pi].vars[vi];
            var.ty = ty;
            var.init = init;
        }
        self.check_var_decl(p, v, src);
        self.pou_var_state[pi][vi] = State::Done;
    }

    /// The rules a variable declaration must follow in its POU.
    fn check_var_decl(&mut self, p: PouId, v: VarId, src: VarSource<'a>) {
        let pou_kind = self.pous[p.0 as usize].kind;
        let var = {
            let d = &self.pous[p.0 as usize].vars[v.0 as usize];
            VarDef {
                name: d.name,
                span: d.span,
                section: d.section,
                ty: d.ty,
                init: None,
                constant: d.constant,
                retain: d.retain,
                location: None,
                edge: d.edge,
                implicit: d.implicit,
            }
        };
        let name = self.spelled(var.name, var.span);
        let kind_word = match pou_kind {
            PouKind::Function => "a FUNCTION",
            PouKind::FunctionBlock => "a FUNCTION_BLOCK",
            PouKind::Program => "a PROGRAM",
        };
        let block_kw = src.block.kind.keyword();
        let section_ok = !matches!(
            (pou_kind, src.block.kind),
            (
                PouKind::Function,
                VarKind::Global | VarKind::External | VarKind::Access | VarKind::Config
            ) | (
                PouKind::FunctionBlock,
                VarKind::Global | VarKind::Access | VarKind::Config
            ) | (PouKind::Program, VarKind::Config)
        );
        if !section_ok && src.decl.names.first().is_some_and(|n| n.sym == var.name) {
            self.error(
                Code::E0507,
                src.block.span.shrink_to_lo().to(Span::new(
                    src.block.span.lo,
                    src.block.span.lo + block_kw.len() as u32,
                )),
                format!("{block_kw} is not allowed in {kind_word}"),
            );
        }
        if let Some(edge) = var.edge {
            let word = if edge == Edge::Rising {
                "R_EDGE"
            } else {
                "F_EDGE"
            };
            if src.block.kind != VarKind::Input || pou_kind == PouKind::Function {
                self.error(
                    Code::E0507,
                    var.span,
                    format!("{word} is only allowed on inputs of function blocks and programs"),
                );
            } else if !self.types.is_bool(var.ty) && var.ty != TypeId::ERROR {
                self.error(
                    Code::E0507,
                    var.span,
                    format!("{word} applies to BOOL inputs only"),
                );
            }
        }
        let owned = !matches!(var.section, Section::InOut | Section::External);
        if self.check_not_abstract(var.ty, owned, src.decl.ty.span) {
            // Reported once: uses of the variable stay silent.
            self.pous[p.0 as usize].vars[v.0 as usize].ty = TypeId::ERROR;
        }
        match self.types.kind(self.innermost_elem(var.ty)) {
            TypeKind::Fb(_) if pou_kind == PouKind::Function && owned => {
                self.emit(
                    Diagnostic::new(
                        Code::E0501,
                        src.decl.ty.span,
                        format!("function block instance `{name}` declared in a FUNCTION"),
                    )
                    .with_help("functions have no memory; make this POU a FUNCTION_BLOCK"),
                );
            }
            TypeKind::Program(_) => {
                self.emit(
                    Diagnostic::new(
                        Code::E0504,
                        src.decl.ty.span,
                        format!("`{name}` instantiates a PROGRAM outside a configuration"),
                    )
                    .with_help("programs are instantiated by a CONFIGURATION or RESOURCE"),
                );
                // Reported once: uses of the variable stay silent.
                self.pous[p.0 as usize].vars[v.0 as usize].ty = TypeId::ERROR;
            }
            _ => {}
        }
        if var.retain && self.type_has_ref(var.ty, 0) {
            self.retained_ref(var.span);
        }
        if let Some(loc) = &src.decl.location {
            if pou_kind == PouKind::Function {
                self.error(
                    Code::E0507,
                    loc.span,
                    "a FUNCTION cannot have located variables",
                );
            } else {
                self.check_location(loc.span, &loc.address, var.ty);
            }
        }
    }

    /// Whether a value of type `t` holds a reference (in an element, a
    /// member or a variable of an instance).
    pub(crate) fn type_has_ref(&mut self, t: TypeId, depth: u32) -> bool {
        if depth > 64 {
            return false;
        }
        match self.types.kind(t).clone() {
            TypeKind::Ref(_) | TypeKind::Ptr(_) => true,
            TypeKind::Array { elem, .. } => self.type_has_ref(elem, depth + 1),
            TypeKind::Struct { fields } => {
                fields.iter().any(|f| self.type_has_ref(f.ty, depth + 1))
            }
            TypeKind::Fb(q) => {
                let n = self.pous[q.0 as usize].vars.len();
                (0..n).any(|i| {
                    let v = crate::VarId(i as u32);
                    self.ensure_var(q, v);
                    let ty = self.pous[q.0 as usize].var(v).ty;
                    self.type_has_ref(ty, depth + 1)
                })
            }
            _ => false,
        }
    }

    /// E1316 where a variable of type `t` (or an array of them) would be
    /// an instance of an ABSTRACT function block (`owned`: not an in-out
    /// or external, which only refers to one).
    fn check_not_abstract(&mut self, t: TypeId, owned: bool, span: Span) -> bool {
        let TypeKind::Fb(fb) = *self.types.kind(self.innermost_elem(t)) else {
            return false;
        };
        if owned && self.pou_ast(fb).is_some_and(|a| a.is_abstract) {
            let name = self.sym_name(self.pous[fb.0 as usize].name);
            self.emit(
                Diagnostic::new(
                    Code::E1316,
                    span,
                    format!("`{name}` is ABSTRACT and cannot be instantiated"),
                )
                .with_help("declare a reference to it (`REF_TO`) instead, or remove ABSTRACT"),
            );
            return true;
        }
        false
    }

    /// E1308 at a RETAIN variable that holds a reference.
    fn retained_ref(&mut self, span: Span) {
        self.emit(
            Diagnostic::new(
                Code::E1308,
                span,
                "a RETAIN variable cannot hold a reference or a pointer",
            )
            .with_help(
                "an address does not survive a restart: keep references and pointers out of RETAIN variables",
            ),
        );
    }

    /// The element type of (nested) arrays.
    pub(crate) fn innermost_elem(&self, mut t: TypeId) -> TypeId {
        while let TypeKind::Array { elem, .. } = self.types.kind(t) {
            t = *elem;
        }
        t
    }

    /// E0704: the size prefix of an address fixes the size of its variable.
    pub(crate) fn check_location(
        &mut self,
        span: Span,
        addr: &stc_syntax::literal::DirectAddress,
        ty: TypeId,
    ) {
        if addr.is_incomplete() || ty == TypeId::ERROR {
            return;
        }
        let Some(e) = self.types.scalar(ty) else {
            let msg = format!(
                "a variable of type {} cannot be located at {addr}",
                self.tname(ty)
            );
            self.error(Code::E0704, span, msg);
            return;
        };
        let ok = match addr.size {
            AddrSize::Bit => e == ElemType::Bool,
            AddrSize::Byte => matches!(
                e,
                ElemType::Byte | ElemType::Sint | ElemType::Usint | ElemType::Char
            ),
            AddrSize::Word => matches!(
                e,
                ElemType::Word | ElemType::Int | ElemType::Uint | ElemType::Wchar
            ),
            AddrSize::Dword => matches!(
                e,
                ElemType::Dword | ElemType::Dint | ElemType::Udint | ElemType::Real
            ),
            AddrSize::Lword => matches!(
                e,
                ElemType::Lword
                    | ElemType::Lint
                    | ElemType::Ulint
                    | ElemType::Lreal
                    | ElemType::Time
                    | ElemType::Ltime
                    | ElemType::Date
                    | ElemType::Ldate
                    | ElemType::Tod
                    | ElemType::Ltod
                    | ElemType::Dt
                    | ElemType::Ldt
            ),
        };
        if !ok {
            let bits = addr.size.bits();
            let what = if bits == 1 {
                "a single bit (BOOL)".to_string()
            } else {
                format!("{bits} bits")
            };
            let msg = format!(
                "{addr} holds {what}, but the variable is {}",
                self.tname(ty)
            );
            self.emit(
                Diagnostic::new(Code::E0704, span, msg)
                    .with_label(format!("{}-bit location", bits)),
            );
        }
    }

    // ----- globals --------------------------------------------------------------

    pub(crate) fn resolve_global(&mut self, g: GlobalId) {
        let gi = g.0 as usize;
        match self.global_state[gi] {
            State::Done => return,
            State::InProgress => {
                let span = self.globals[gi].var.span;
                let name = self.sym_name(self.globals[gi].var.name);
                self.error(
                    Code::E0705,
                    span,
                    format!("the declaration of `{name}` depends on itself"),
                );
                self.global_state[gi] = State::Done;
                return;
            }
            State::Todo => {}
        }
        self.global_state[gi] = State::InProgress;
        let src = self.global_src[gi];
        let scope = match self.globals[gi].owner {
            GlobalOwner::TopLevel => Scope::Global,
            GlobalOwner::Config(c) => Scope::Config(c, None),
            GlobalOwner::Resource(c, r) => Scope::Config(c, Some(r)),
        };
        let (ty, type_init) = self.resolve_type_spec(&src.decl.ty, scope, None);
        let init = match &src.decl.init {
            Some(i) => self.init_value(i, ty, scope),
            None => type_init,
        };
        if matches!(self.types.kind(ty), TypeKind::Program(_)) {
            self.error(
                Code::E0504,
                src.decl.ty.span,
                "a PROGRAM cannot be the type of a global variable",
            );
        }
        if let Some(loc) = &src.decl.location {
            self.check_location(loc.span, &loc.address, ty);
        }
        let ty = if self.check_not_abstract(ty, true, src.decl.ty.span) {
            TypeId::ERROR
        } else {
            ty
        };
        if self.globals[gi].var.retain && self.type_has_ref(ty, 0) {
            self.retained_ref(self.globals[gi].var.span);
        }
        let var = &mut self.globals[gi].var;
        var.ty = ty;
        var.init = init;
        self.global_state[gi] = State::Done;
    }
}
