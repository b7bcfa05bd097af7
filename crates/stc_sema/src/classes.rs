//! Inheritance (3rd edition, docs/oop.md): EXTENDS and IMPLEMENTS of
//! function blocks and classes, INTERFACEs, the hidden type tag, the
//! inherited variables, and the rules on overriding and implementing
//! methods.
//!
//! A derived block's variables start with a copy of its base's (all of
//! them, the base's hidden tag, EN and ENO included), so a base instance is
//! a prefix of a derived one: a derived instance is used where its base is
//! expected (a VAR_IN_OUT, a `REF_TO`, an interface) without any
//! conversion, and a base's methods and body run on it unchanged.

use stc_diagnostics::{Code, Diagnostic};
use stc_syntax::ast::{ClassKind, PouKind};
use stc_values::Value;

use crate::analyzer::{GlobalName, Sema, State};
use crate::types::{InitValue, TypeId};
use crate::{PouDef, PouId, Section, VarDef, VarId};

impl<'a> Sema<'a> {
    fn class_word(&self, p: PouId) -> &'static str {
        match self.pous[p.0 as usize].class {
            Some(ClassKind::Class) => "class",
            Some(ClassKind::Interface) => "interface",
            None => "function block",
        }
    }

    /// After every name is registered: resolves EXTENDS and IMPLEMENTS,
    /// refuses cycles, gives the tag and the inherited variables.
    pub(crate) fn link_classes(&mut self, first: usize) {
        let n = self.pous.len();
        let mut any = false;
        for p in first..n {
            let pid = PouId(p as u32);
            if self.pous[p].method_of.is_some() || self.pous[p].kind != PouKind::FunctionBlock {
                continue;
            }
            let Some(ast) = self.pou_ast(pid) else {
                continue;
            };
            let class = self.pous[p].class;
            if let Some(b) = ast.extends {
                any = true;
                let shown = self.spelled(b.sym, b.span);
                match self.global_name(b) {
                    Some(GlobalName::Pou(q)) if q == pid => {
                        self.emit(
                            Diagnostic::new(
                                Code::E1319,
                                b.span,
                                format!("`{shown}` extends itself"),
                            )
                            .with_label("a cycle of EXTENDS"),
                        );
                    }
                    Some(GlobalName::Pou(q))
                        if self.pous[q.0 as usize].kind == PouKind::FunctionBlock
                            && self.pous[q.0 as usize].class == class =>
                    {
                        if self.pou_ast(q).is_some_and(|a| a.is_final) {
                            let decl = self.pous[q.0 as usize].name_span;
                            self.emit(
                                Diagnostic::new(
                                    Code::E1320,
                                    b.span,
                                    format!("`{shown}` is FINAL and cannot be extended"),
                                )
                                .with_label("extends a FINAL block")
                                .with_secondary(decl, "declared FINAL here"),
                            );
                        } else {
                            self.pous[p].base = Some(q);
                        }
                    }
                    other => {
                        let what = match class {
                            Some(ClassKind::Class) => "a CLASS extends a CLASS",
                            _ => "a FUNCTION_BLOCK extends a FUNCTION_BLOCK",
                        };
                        let mut d = Diagnostic::new(
                            Code::E1317,
                            b.span,
                            match other {
                                Some(GlobalName::Pou(q)) => format!(
                                    "`{shown}` is {} and cannot be extended here",
                                    self.pou_kind_word(q)
                                ),
                                Some(_) => {
                                    format!("`{shown}` is a data type, not a function block")
                                }
                                None => format!("unknown base `{shown}`"),
                            },
                        )
                        .with_label("EXTENDS needs a base")
                        .with_help(what);
                        if let Some(GlobalName::Pou(q)) = other {
                            d = d
                                .with_secondary(self.pous[q.0 as usize].name_span, "declared here");
                        }
                        self.emit(d);
                    }
                }
            }
            for i in &ast.implements {
                any = true;
                let shown = self.spelled(i.sym, i.span);
                match self.global_name(*i) {
                    Some(GlobalName::Pou(q))
                        if q != pid
                            && self.pous[q.0 as usize].class == Some(ClassKind::Interface) =>
                    {
                        if !self.pous[p].interfaces.contains(&q) {
                            self.pous[p].interfaces.push(q);
                        }
                    }
                    Some(GlobalName::Pou(q)) if q == pid => {
                        self.emit(
                            Diagnostic::new(
                                Code::E1319,
                                i.span,
                                format!("`{shown}` extends itself"),
                            )
                            .with_label("a cycle of EXTENDS"),
                        );
                    }
                    other => {
                        let mut d = Diagnostic::new(
                            Code::E1317,
                            i.span,
                            match other {
                                Some(GlobalName::Pou(q)) => {
                                    format!(
                                        "`{shown}` is {}, not an INTERFACE",
                                        self.pou_kind_word(q)
                                    )
                                }
                                Some(_) => format!("`{shown}` is a data type, not an INTERFACE"),
                                None => format!("unknown interface `{shown}`"),
                            },
                        )
                        .with_label("an INTERFACE is expected here");
                        if let Some(GlobalName::Pou(q)) = other {
                            d = d
                                .with_secondary(self.pous[q.0 as usize].name_span, "declared here");
                        }
                        self.emit(d);
                    }
                }
            }
            if class.is_some() {
                any = true;
            }
        }
        if !any {
            return;
        }
        self.break_cycles(first);
        for p in first..n {
            if self.pous[p].class == Some(ClassKind::Interface) && self.pous[p].method_of.is_none()
            {
                self.types.add_interface(PouId(p as u32));
            }
            let sups: Vec<PouId> = self.pous[p]
                .base
                .iter()
                .chain(self.pous[p].interfaces.iter())
                .copied()
                .collect();
            for s in sups {
                self.types.add_super(PouId(p as u32), s);
            }
        }
        // Who takes part: a block or class with a base, extended, with
        // interfaces, any class and any interface.
        let mut part = vec![false; n];
        for p in first..n {
            let def = &self.pous[p];
            if def.class.is_some() || def.base.is_some() || !def.interfaces.is_empty() {
                part[p] = true;
            }
            if let Some(b) = def.base {
                part[b.0 as usize] = true;
            }
        }
        self.refuse_edges_in_bases();
        // The tag of every root, then the bases' variables, bases first.
        let tag_sym = self.intern("__TAG");
        let udint = self.types.elem(stc_syntax::token::ElemType::Udint);
        for (p, &on) in part.iter().enumerate() {
            if !on || self.pous[p].base.is_some() {
                continue;
            }
            let tag = VarDef {
                name: tag_sym,
                span: self.pous[p].name_span,
                section: Section::Var,
                ty: udint,
                init: Some(InitValue::Scalar(Value::Int(i128::from(
                    PouDef::tag_value(PouId(p as u32)),
                )))),
                constant: false,
                retain: false,
                location: None,
                edge: None,
                implicit: false,
            };
            self.prepend_vars(p, vec![tag], &[], State::Done);
            self.pous[p].tag = Some(VarId(0));
        }
        let mut order: Vec<(usize, usize)> = (first..n)
            .filter(|&p| self.pous[p].base.is_some())
            .map(|p| (self.depth(PouId(p as u32)), p))
            .collect();
        order.sort_unstable();
        for (_, p) in order {
            let Some(b) = self.pous[p].base else { continue };
            let base = &self.pous[b.0 as usize];
            let mut vars = base.vars.clone();
            for v in &mut vars {
                if v.implicit {
                    // The base's EN and ENO: storage, named by nothing.
                    v.implicit = false;
                    v.section = Section::Var;
                }
            }
            let named: Vec<(stc_syntax::Symbol, VarId)> = base
                .var_index
                .iter()
                .filter(|(_, v)| !base.vars[v.0 as usize].implicit)
                .map(|(s, v)| (*s, *v))
                .collect();
            let k = vars.len() as u32;
            self.prepend_vars(p, vars, &named, State::Todo);
            self.pous[p].inherited = k;
            self.pous[p].tag = Some(VarId(0));
            // Its own tag (the base's variables resolve from the base's).
            self.pous[p].vars[0].init = Some(InitValue::Scalar(Value::Int(i128::from(
                PouDef::tag_value(PouId(p as u32)),
            ))));
            self.pou_var_state[p][0] = State::Done;
        }
    }

    fn pou_kind_word(&self, q: PouId) -> &'static str {
        match self.pous[q.0 as usize].kind {
            PouKind::Function => "a function",
            PouKind::Program => "a program",
            PouKind::FunctionBlock => match self.pous[q.0 as usize].class {
                Some(ClassKind::Class) => "a class",
                Some(ClassKind::Interface) => "an interface",
                None => "a function block",
            },
        }
    }

    /// The number of bases above `p`.
    fn depth(&self, p: PouId) -> usize {
        let mut d = 0;
        let mut at = p;
        while let Some(b) = self.pous[at.0 as usize].base {
            d += 1;
            at = b;
            if d > self.pous.len() {
                break;
            }
        }
        d
    }

    /// E1319 for a cycle of EXTENDS (or of interfaces extending each
    /// other), once per cycle; the link closing it is dropped.
    fn break_cycles(&mut self, first: usize) {
        let n = self.pous.len();
        for p in first..n {
            let pid = PouId(p as u32);
            // Bases: a chain.
            let mut at = self.pous[p].base;
            let mut steps = 0;
            while let Some(q) = at {
                if q == pid {
                    self.report_cycle(pid);
                    self.pous[p].base = None;
                    break;
                }
                steps += 1;
                if steps > n {
                    break;
                }
                at = self.pous[q.0 as usize].base;
            }
            // Interfaces: a graph.
            let mut stack: Vec<PouId> = self.pous[p].interfaces.clone();
            let mut seen = rustc_hash::FxHashSet::default();
            let mut cycle = false;
            while let Some(q) = stack.pop() {
                if q == pid {
                    cycle = true;
                    break;
                }
                if seen.insert(q) {
                    stack.extend(self.pous[q.0 as usize].interfaces.iter().copied());
                }
            }
            if cycle {
                self.report_cycle(pid);
                self.pous[p].interfaces.clear();
            }
        }
    }

    fn report_cycle(&mut self, p: PouId) {
        let def = &self.pous[p.0 as usize];
        let shown = self.spelled(def.name, def.name_span);
        let span = self
            .pou_ast(p)
            .and_then(|a| a.extends.or_else(|| a.implements.first().copied()))
            .map_or(def.name_span, |i| i.span);
        self.emit(
            Diagnostic::new(
                Code::E1319,
                span,
                format!("`{shown}` extends itself through its bases"),
            )
            .with_label("this EXTENDS closes a cycle")
            .with_secondary(def.name_span, format!("`{shown}` declared here")),
        );
    }

    /// R_EDGE and F_EDGE inputs keep a hidden memory after the block's
    /// variables; in a block that is extended it would lie inside the
    /// derived block's own variables.
    fn refuse_edges_in_bases(&mut self) {
        let bases: Vec<PouId> = self.pous.iter().filter_map(|d| d.base).collect();
        let mut done = rustc_hash::FxHashSet::default();
        for b in bases {
            if !done.insert(b) {
                continue;
            }
            let spans: Vec<_> = self.pous[b.0 as usize]
                .vars
                .iter()
                .filter(|v| v.edge.is_some())
                .map(|v| v.span)
                .collect();
            for s in spans {
                self.emit(
                    Diagnostic::new(
                        Code::E0030,
                        s,
                        "an R_EDGE or F_EDGE input of a function block that is extended is not supported yet",
                    )
                    .with_help("detect the edge with an R_TRIG instance instead"),
                );
            }
            for v in &mut self.pous[b.0 as usize].vars {
                v.edge = None;
            }
        }
    }

    /// Puts `vars` before the variables of POU `p` (whose ids shift), and
    /// names `named` of them unless `p` declares the name itself (E0105).
    fn prepend_vars(
        &mut self,
        p: usize,
        vars: Vec<VarDef>,
        named: &[(stc_syntax::Symbol, VarId)],
        state: State,
    ) {
        let k = vars.len() as u32;
        let shift = |v: &mut Option<VarId>| {
            if let Some(x) = v {
                x.0 += k;
            }
        };
        let def = &mut self.pous[p];
        for v in def.var_index.values_mut() {
            v.0 += k;
        }
        shift(&mut def.en);
        shift(&mut def.eno);
        shift(&mut def.this);
        shift(&mut def.tag);
        let own = std::mem::replace(&mut def.vars, vars);
        let base_spans: Vec<_> = def.vars.iter().map(|v| v.span).collect();
        def.vars.extend(own);
        let mut clashes = Vec::new();
        for &(sym, v) in named {
            match def.var_index.get(&sym) {
                Some(&mine) => clashes.push((
                    def.vars[mine.0 as usize].span,
                    base_spans[v.0 as usize],
                    sym,
                )),
                None => {
                    def.var_index.insert(sym, v);
                }
            }
        }
        let src = &mut self.pou_var_src[p];
        src.splice(0..0, std::iter::repeat_n(None, k as usize));
        let st = &mut self.pou_var_state[p];
        st.splice(0..0, std::iter::repeat_n(state, k as usize));
        for (mine, theirs, sym) in clashes {
            let shown = self.spelled(sym, mine);
            self.emit(
                Diagnostic::new(
                    Code::E0105,
                    mine,
                    format!("`{shown}` is already a variable of the base"),
                )
                .with_label("declared again here")
                .with_secondary(theirs, "inherited from here"),
            );
        }
    }

    /// After the variables' types are resolved: overriding, FINAL,
    /// ABSTRACT and interface methods.
    pub(crate) fn check_classes(&mut self, first: usize) {
        let n = self.pous.len();
        // The reference types dispatch needs (lowering cannot add types).
        for p in first..n {
            if self.pous[p].tag.is_some() {
                let t = self.pou_type(PouId(p as u32));
                self.types.ref_to(t);
            }
        }
        for p in first..n {
            let pid = PouId(p as u32);
            if self.pous[p].method_of.is_some() || self.pous[p].kind != PouKind::FunctionBlock {
                continue;
            }
            self.check_class_shape(pid);
            if let Some(b) = self.pous[p].base {
                for m in self.pous[p].methods.clone() {
                    let name = self.pous[m.0 as usize].name;
                    let Some(bm) = self.find_method(b, name) else {
                        if self.method_ast(m).is_some_and(|a| a.is_override) {
                            let shown = self.sym_name(name);
                            let span = self.pous[m.0 as usize].name_span;
                            let bname = self.sym_name(self.pous[b.0 as usize].name);
                            self.emit(
                                Diagnostic::new(
                                    Code::E1309,
                                    span,
                                    format!("`{shown}` overrides no method: `{bname}` has none of that name"),
                                )
                                .with_help("remove OVERRIDE, or name a method of the base"),
                            );
                        }
                        continue;
                    };
                    self.check_override(m, bm);
                }
            }
            let is_abstract = self.pou_ast(pid).is_some_and(|a| a.is_abstract)
                || self.pous[p].class == Some(ClassKind::Interface);
            if !is_abstract {
                self.check_complete(pid);
            }
        }
    }

    fn method_ast(&self, m: PouId) -> Option<&'a stc_syntax::ast::Method> {
        let (owner, k) = self.pous[m.0 as usize].method_of?;
        self.pou_ast(owner)?.methods.get(k)
    }

    /// A CLASS has no inputs, outputs or in-outs; an INTERFACE has no
    /// variables and its methods no bodies.
    fn check_class_shape(&mut self, p: PouId) {
        let Some(class) = self.pous[p.0 as usize].class else {
            return;
        };
        let Some(ast) = self.pou_ast(p) else { return };
        for b in &ast.var_blocks {
            use stc_syntax::ast::VarKind;
            let bad = match class {
                ClassKind::Interface => true,
                ClassKind::Class => {
                    matches!(b.kind, VarKind::Input | VarKind::Output | VarKind::InOut)
                }
            };
            if bad {
                let what = if class == ClassKind::Interface {
                    "an INTERFACE declares no variables".to_string()
                } else {
                    format!("a CLASS has no {}", b.kind.keyword())
                };
                self.emit(
                    Diagnostic::new(Code::E1318, b.span, what)
                        .with_label("not allowed here")
                        .with_secondary(ast.name.span, format!("in this {}", self.class_word(p))),
                );
            }
        }
        if class == ClassKind::Interface {
            for m in &ast.methods {
                if !m.pou.body.is_empty()
                    || !m.pou.var_blocks.iter().all(|b| {
                        use stc_syntax::ast::VarKind;
                        matches!(b.kind, VarKind::Input | VarKind::Output | VarKind::InOut)
                    })
                {
                    self.emit(
                        Diagnostic::new(
                            Code::E1318,
                            m.pou.name.span,
                            "a METHOD of an INTERFACE is a prototype: parameters, no body and no local variables",
                        )
                        .with_label("has a body or local variables"),
                    );
                }
            }
        }
    }

    /// The parameters of a method (section, name, type) and its result.
    fn signature(&self, m: PouId) -> (Vec<(Section, stc_syntax::Symbol, TypeId)>, Option<TypeId>) {
        let def = &self.pous[m.0 as usize];
        let params = def
            .vars
            .iter()
            .enumerate()
            .filter(|(i, v)| {
                Some(VarId(*i as u32)) != def.this
                    && matches!(v.section, Section::Input | Section::Output | Section::InOut)
            })
            .map(|(_, v)| (v.section, v.name, v.ty))
            .collect();
        (params, def.return_type)
    }

    fn same_signature(&self, a: PouId, b: PouId) -> bool {
        let (pa, ra) = self.signature(a);
        let (pb, rb) = self.signature(b);
        let same = |x: TypeId, y: TypeId| {
            x == y
                || self.types.compat(x, y, false) == crate::Compat::Same
                    && self.types.compat(y, x, false) == crate::Compat::Same
        };
        let results = match (ra, rb) {
            (None, None) => true,
            (Some(x), Some(y)) => same(x, y),
            _ => false,
        };
        results
            && pa.len() == pb.len()
            && pa
                .iter()
                .zip(&pb)
                .all(|(x, y)| x.0 == y.0 && x.1 == y.1 && same(x.2, y.2))
    }

    fn check_override(&mut self, m: PouId, bm: PouId) {
        let span = self.pous[m.0 as usize].name_span;
        let bspan = self.pous[bm.0 as usize].name_span;
        let shown = self.sym_name(self.pous[m.0 as usize].name);
        if self.method_ast(bm).is_some_and(|a| a.is_final) {
            self.emit(
                Diagnostic::new(
                    Code::E1321,
                    span,
                    format!("`{shown}` overrides a FINAL method"),
                )
                .with_label("overrides the base's method")
                .with_secondary(bspan, "declared FINAL here"),
            );
            return;
        }
        if !self.same_signature(m, bm) {
            self.emit(
                Diagnostic::new(
                    Code::E1322,
                    span,
                    format!("`{shown}` overrides a method of another signature"),
                )
                .with_label("parameters or result differ from the base's")
                .with_secondary(bspan, "the base's method")
                .with_help("an overriding method has the same parameters (section, name, type, order) and result type"),
            );
            return;
        }
        if !self.method_ast(m).is_some_and(|a| a.is_override) {
            self.emit(
                Diagnostic::new(
                    Code::W1317,
                    span,
                    format!("`{shown}` overrides the base's method without OVERRIDE"),
                )
                .with_label("overrides")
                .with_secondary(bspan, "the base's method")
                .with_help("write `METHOD OVERRIDE`"),
            );
        }
    }

    /// Every ABSTRACT method of the bases and every method of the
    /// interfaces has an implementation in a block that is not ABSTRACT.
    fn check_complete(&mut self, p: PouId) {
        let span = self.pous[p.0 as usize].name_span;
        let shown = self.sym_name(self.pous[p.0 as usize].name);
        // ABSTRACT methods left without body.
        let mut chain = vec![p];
        let mut at = self.pous[p.0 as usize].base;
        while let Some(b) = at {
            if chain.contains(&b) {
                break;
            }
            chain.push(b);
            at = self.pous[b.0 as usize].base;
        }
        let mut reported = Vec::new();
        for &c in &chain[1..] {
            for m in self.pous[c.0 as usize].methods.clone() {
                let name = self.pous[m.0 as usize].name;
                if reported.contains(&name) {
                    continue;
                }
                let found = self.find_method(p, name);
                if found == Some(m) && self.method_ast(m).is_some_and(|a| a.is_abstract) {
                    reported.push(name);
                    let mshown = self.sym_name(name);
                    self.emit(
                        Diagnostic::new(
                            Code::E1323,
                            span,
                            format!("`{shown}` does not implement the ABSTRACT method `{mshown}`"),
                        )
                        .with_label("not ABSTRACT, so every method needs a body")
                        .with_secondary(self.pous[m.0 as usize].name_span, "the ABSTRACT method"),
                    );
                }
            }
        }
        // Interface methods.
        let mut itfs: Vec<PouId> = Vec::new();
        let mut stack: Vec<PouId> = chain
            .iter()
            .flat_map(|c| self.pous[c.0 as usize].interfaces.clone())
            .collect();
        while let Some(i) = stack.pop() {
            if !itfs.contains(&i) {
                itfs.push(i);
                stack.extend(self.pous[i.0 as usize].interfaces.iter().copied());
            }
        }
        for i in itfs {
            for im in self.pous[i.0 as usize].methods.clone() {
                let name = self.pous[im.0 as usize].name;
                if reported.contains(&name) {
                    continue;
                }
                let ishown = self.sym_name(self.pous[i.0 as usize].name);
                let mshown = self.sym_name(name);
                // (A prototype found through the interfaces is no
                // implementation.)
                let found = self.find_method(p, name).filter(|m| {
                    let owner = self.pous[m.0 as usize].method_of.map(|(o, _)| o);
                    owner
                        .is_none_or(|o| self.pous[o.0 as usize].class != Some(ClassKind::Interface))
                });
                match found {
                    None => {
                        reported.push(name);
                        self.emit(
                            Diagnostic::new(
                                Code::E1324,
                                span,
                                format!("`{shown}` does not implement `{ishown}.{mshown}`"),
                            )
                            .with_label(format!("implements `{ishown}`"))
                            .with_secondary(
                                self.pous[im.0 as usize].name_span,
                                "the interface's method",
                            ),
                        );
                    }
                    Some(m) if !self.same_signature(m, im) => {
                        reported.push(name);
                        self.emit(
                            Diagnostic::new(
                                Code::E1325,
                                self.pous[m.0 as usize].name_span,
                                format!(
                                    "`{mshown}` does not have the signature of `{ishown}.{mshown}`"
                                ),
                            )
                            .with_label("parameters or result differ")
                            .with_secondary(
                                self.pous[im.0 as usize].name_span,
                                "the interface's method",
                            ),
                        );
                    }
                    Some(_) => {}
                }
            }
        }
    }

    /// `target ?= value` (docs/oop.md): both interface values or
    /// references to blocks or classes whose instance may fit (E1327).
    pub(crate) fn assign_attempt(
        &mut self,
        target: stc_syntax::ast::ExprId,
        value: stc_syntax::ast::ExprId,
        p: PouId,
    ) {
        let scope = crate::analyzer::Scope::Pou(p);
        let tt = self.check_lvalue(target, scope, crate::calls::Write::Assign);
        let vt = self.check_expr(value, None, scope);
        if tt == TypeId::ERROR || vt == TypeId::ERROR {
            return;
        }
        let fb = |s: &Self, t: TypeId| match s.types.ref_target(t).map(|x| s.types.kind(x)) {
            Some(crate::types::TypeKind::Fb(q)) => Some(*q),
            _ => None,
        };
        let itf = |s: &Self, q: PouId| s.pous[q.0 as usize].class == Some(ClassKind::Interface);
        let fits = match (fb(self, tt), fb(self, vt)) {
            (Some(a), Some(b)) => {
                itf(self, a)
                    || itf(self, b)
                    || self.types.is_subtype(a, b)
                    || self.types.is_subtype(b, a)
            }
            _ => false,
        };
        if !fits {
            let (a, b) = (self.tname(tt), self.tname(vt));
            self.emit(
                Diagnostic::new(
                    Code::E1327,
                    self.ast.expr(value).span,
                    format!("`?=` cannot assign a value of type {b} to one of type {a}"),
                )
                .with_label(format!("this is {b}"))
                .with_secondary(self.ast.expr(target).span, format!("this is {a}"))
                .with_help("both sides are interface values or references to related function blocks or classes"),
            );
        }
    }
}
