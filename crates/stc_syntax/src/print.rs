//! Writes a syntax tree back as Structured Text.
//!
//! The output parses back to the same tree (the round-trip property every
//! syntax test checks). Parentheses are printed where the tree has them and
//! wherever precedence requires them, so trees built by a program (not by
//! the parser) print correctly too. Layout is canonical: this is the seed of
//! the formatter.

use std::fmt::Write;

use stc_diagnostics::Span;

use crate::ast::*;
use crate::dump::literal_text;
use crate::intern::Interner;

/// Precedence of postfix expressions (calls, members, indexing) and primaries.
const POSTFIX: u8 = 10;

/// Prints the whole tree. `pragma_text` gives a pragma's source text from its
/// span, so pragmas are kept; pass `&|_| String::new()` to drop them.
pub fn print(ast: &Ast, interner: &Interner, pragma_text: &dyn Fn(Span) -> String) -> String {
    let mut p = Printer {
        ast,
        interner,
        pragma_text,
        out: String::new(),
        indent: 0,
    };
    for (i, item) in ast.items.iter().enumerate() {
        if i > 0 {
            p.out.push('\n');
        }
        p.item(item);
    }
    p.out
}

struct Printer<'a> {
    ast: &'a Ast,
    interner: &'a Interner,
    pragma_text: &'a dyn Fn(Span) -> String,
    out: String,
    indent: usize,
}

impl Printer<'_> {
    fn line(&mut self, text: &str) {
        for _ in 0..self.indent {
            self.out.push_str("    ");
        }
        self.out.push_str(text);
        self.out.push('\n');
    }

    fn nested(&mut self, f: impl FnOnce(&mut Self)) {
        self.indent += 1;
        f(self);
        self.indent -= 1;
    }

    fn name(&self, i: Ident) -> &str {
        self.interner.spelling(i.sym)
    }

    fn pragmas(&mut self, pragmas: &[Span]) {
        for &p in pragmas {
            let text = (self.pragma_text)(p);
            if !text.is_empty() {
                self.line(&text);
            }
        }
    }

    fn item(&mut self, item: &Item) {
        match item {
            Item::Types(decls, _) => {
                self.line("TYPE");
                self.nested(|p| {
                    for t in decls {
                        p.pragmas(&t.pragmas);
                        let head = format!("{} : ", p.name(t.name));
                        let init = t.init.as_ref().map(|i| p.init(i));
                        p.typed_line(&head, &t.spec, None, init.as_deref());
                    }
                });
                self.line("END_TYPE");
            }
            Item::Pou(pou) => self.pou(pou),
            Item::Configuration(c) => self.configuration(c),
            Item::GlobalVars(b) => self.var_block(b),
            Item::Namespace(ns) => {
                self.pragmas(&ns.pragmas);
                let internal = if ns.internal { " INTERNAL" } else { "" };
                self.line(&format!("NAMESPACE{internal} {}", self.name(ns.name)));
                self.indent += 1;
            }
            Item::EndNamespace(_) => {
                self.indent = self.indent.saturating_sub(1);
                self.line("END_NAMESPACE");
            }
            Item::Using(u) => {
                let line = self.using_line(&u.names);
                self.line(&line);
            }
        }
    }

    /// `USING A, B.C;`
    fn using_line(&self, names: &[Ident]) -> String {
        let names: Vec<&str> = names.iter().map(|n| self.name(*n)).collect();
        format!("USING {};", names.join(", "))
    }

    /// `head TYPE [suffix] [:= init];`, with STRUCT types spread over lines.
    fn typed_line(
        &mut self,
        head: &str,
        spec: &TypeSpec,
        suffix: Option<&str>,
        init: Option<&str>,
    ) {
        let tail = {
            let mut t = String::new();
            if let Some(s) = suffix {
                let _ = write!(t, " {s}");
            }
            if let Some(i) = init {
                let _ = write!(t, " := {i}");
            }
            t.push(';');
            t
        };
        match &spec.kind {
            TypeSpecKind::Struct { members } => {
                self.line(&format!("{head}STRUCT"));
                self.nested(|p| {
                    for m in members {
                        p.var_decl(m);
                    }
                });
                self.line(&format!("END_STRUCT{tail}"));
            }
            TypeSpecKind::Array { dims, elem } if contains_struct(elem) => {
                let head = format!("{head}ARRAY[{}] OF ", self.dims(dims));
                self.typed_line(&head, elem, suffix, init);
            }
            _ => {
                let t = self.type_text(spec);
                self.line(&format!("{head}{t}{tail}"));
            }
        }
    }

    fn pou(&mut self, pou: &Pou) {
        self.pragmas(&pou.pragmas);
        let mut head = pou.keyword().to_string();
        for (on, word) in [
            (pou.is_abstract, " ABSTRACT"),
            (pou.is_final, " FINAL"),
            (pou.internal, " INTERNAL"),
        ] {
            if on {
                head.push_str(word);
            }
        }
        let _ = write!(head, " {}", self.name(pou.name));
        if let Some(b) = &pou.extends {
            let _ = write!(head, " EXTENDS {}", self.name(*b));
        }
        if !pou.implements.is_empty() {
            let word = if pou.is_interface() {
                "EXTENDS"
            } else {
                "IMPLEMENTS"
            };
            let names: Vec<String> = pou
                .implements
                .iter()
                .map(|i| self.name(*i).to_string())
                .collect();
            let _ = write!(head, " {word} {}", names.join(", "));
        }
        if let Some(r) = &pou.return_type {
            let _ = write!(head, " : {}", self.type_text(r));
        }
        self.line(&head);
        self.nested(|p| {
            if !pou.usings.is_empty() {
                let line = p.using_line(&pou.usings);
                p.line(&line);
            }
            let shown = pou.var_blocks.len() - pou.sfc.as_ref().map_or(0, |s| s.generated_blocks);
            for b in &pou.var_blocks[..shown] {
                p.var_block(b);
            }
            let members: Vec<&crate::ast::Method> =
                pou.methods.iter().filter(|m| !m.is_action).collect();
            let mut i = 0;
            while i < members.len() {
                let m = members[i];
                match m.property {
                    Some((_, name)) => {
                        // The accessors of one property, written together.
                        let mut j = i + 1;
                        while j < members.len()
                            && members[j].property.is_some_and(|(_, n)| n.sym == name.sym)
                        {
                            j += 1;
                        }
                        p.property(&members[i..j]);
                        i = j;
                    }
                    None => {
                        p.method(m);
                        i += 1;
                    }
                }
            }
            if let Some(sfc) = &pou.sfc {
                p.sfc(sfc);
            } else {
                p.stmts(&pou.body);
            }
            for m in pou.methods.iter().filter(|m| m.is_action) {
                p.line(&format!("ACTION {}:", p.name(m.pou.name)));
                p.nested(|p| p.stmts(&m.pou.body));
                p.line("END_ACTION");
            }
            if let Some(il) = &pou.il {
                p.il(il);
            }
        });
        self.line(pou.end_keyword());
    }

    fn il(&mut self, il: &IlBody) {
        let mut lines = Vec::new();
        il_lines(
            &il.instrs,
            self.interner,
            &|e| self.expr(e, 0),
            0,
            &mut lines,
        );
        for l in lines {
            self.indent += l.depth;
            self.line(&l.text);
            self.indent -= l.depth;
        }
    }

    fn sfc(&mut self, sfc: &SfcBody) {
        for e in &sfc.elements {
            match e {
                SfcElement::Step(st) => {
                    let kw = if st.initial { "INITIAL_STEP" } else { "STEP" };
                    self.line(&format!("{kw} {} :", self.name(st.name)));
                    self.nested(|p| {
                        for a in &st.assocs {
                            let text = sfc_assoc(a, p.interner, &|e| p.expr(e, 0));
                            p.line(&format!("{text};"));
                        }
                    });
                    self.line("END_STEP");
                }
                SfcElement::Transition(t) => {
                    let head = sfc_transition_head(t, self.interner, &|e| self.expr(e, 0));
                    match &t.cond {
                        TransitionCond::Expr(e) => {
                            let text = format!("{head} := {};", self.expr(*e, 0));
                            self.line(&text);
                        }
                        TransitionCond::Body(body) => {
                            self.line(&format!("{head} :"));
                            self.nested(|p| p.stmts(body));
                        }
                        TransitionCond::Il(il) => {
                            self.line(&format!("{head} :"));
                            self.nested(|p| p.il(il));
                        }
                    }
                    self.line("END_TRANSITION");
                }
                SfcElement::Action(a) => {
                    self.line(&format!("ACTION {} :", self.name(a.name)));
                    self.nested(|p| match &a.il {
                        Some(il) => p.il(il),
                        None => p.stmts(&a.body),
                    });
                    self.line("END_ACTION");
                }
            }
        }
    }

    /// A PROPERTY from its accessors (see `ast::Method::property`).
    fn property(&mut self, parts: &[&crate::ast::Method]) {
        let Some(first) = parts.first() else {
            return;
        };
        let Some((_, name)) = first.property else {
            return;
        };
        let ty = first.pou.return_type.as_ref().or_else(|| {
            first.pou.var_blocks.first().and_then(|b| match &b.items {
                VarBlockItems::Vars(vs) => vs.first().map(|v| &v.ty),
                _ => None,
            })
        });
        let mut head = format!("PROPERTY{} {}", first.modifiers(), self.name(name));
        if let Some(t) = ty {
            let _ = write!(head, " : {}", self.type_text(t));
        }
        self.line(&head);
        self.nested(|p| {
            for m in parts {
                let set = matches!(m.property, Some((crate::ast::PropertyPart::Set, _)));
                p.line(if set { "SET" } else { "GET" });
                p.nested(|p| {
                    // (The setter's first block is the value, written by
                    // the PROPERTY line.)
                    for b in &m.pou.var_blocks[usize::from(set).min(m.pou.var_blocks.len())..] {
                        p.var_block(b);
                    }
                    p.stmts(&m.pou.body);
                });
                p.line(if set { "END_SET" } else { "END_GET" });
            }
        });
        self.line("END_PROPERTY");
    }

    fn method(&mut self, m: &crate::ast::Method) {
        let mut head = format!("METHOD{} {}", m.modifiers(), self.name(m.pou.name));
        if let Some(r) = &m.pou.return_type {
            let _ = write!(head, " : {}", self.type_text(r));
        }
        self.line(&head);
        self.nested(|p| {
            for b in &m.pou.var_blocks {
                p.var_block(b);
            }
            p.stmts(&m.pou.body);
        });
        self.line("END_METHOD");
    }

    fn var_block(&mut self, b: &VarBlock) {
        let mut head = b.kind.keyword().to_string();
        if let Some(a) = b.access {
            head.push(' ');
            head.push_str(a.keyword());
        }
        if b.constant {
            head.push_str(" CONSTANT");
        }
        match b.retention {
            Some(Retention::Retain) => head.push_str(" RETAIN"),
            Some(Retention::NonRetain) => head.push_str(" NON_RETAIN"),
            None => {}
        }
        self.line(&head);
        self.nested(|p| match &b.items {
            VarBlockItems::Vars(vs) => {
                for v in vs {
                    p.var_decl(v);
                }
            }
            VarBlockItems::Access(a) => {
                for a in a {
                    let resource = a
                        .resource
                        .map(|r| format!("{}.", p.name(r)))
                        .unwrap_or_default();
                    let mut text = format!(
                        "{} : {resource}{} : {}",
                        p.name(a.name),
                        p.expr(a.path, 0),
                        p.type_text(&a.ty)
                    );
                    match a.direction {
                        Some(AccessDirection::ReadOnly) => text.push_str(" READ_ONLY"),
                        Some(AccessDirection::ReadWrite) => text.push_str(" READ_WRITE"),
                        None => {}
                    }
                    text.push(';');
                    p.line(&text);
                }
            }
            VarBlockItems::Config(c) => {
                for c in c {
                    let path: Vec<&str> = c.path.iter().map(|i| p.name(*i)).collect();
                    let mut head = path.join(".");
                    if let Some(l) = &c.location {
                        let _ = write!(head, " AT {}", l.address);
                    }
                    head.push_str(" : ");
                    let init = c.init.as_ref().map(|i| p.init(i));
                    p.typed_line(&head, &c.ty, None, init.as_deref());
                }
            }
        });
        self.line("END_VAR");
    }

    fn var_decl(&mut self, v: &VarDecl) {
        self.pragmas(&v.pragmas);
        let names: Vec<&str> = v.names.iter().map(|i| self.name(*i)).collect();
        let mut head = names.join(", ");
        if let Some(l) = &v.location {
            if !head.is_empty() {
                head.push(' ');
            }
            let _ = write!(head, "AT {}", l.address);
        }
        head.push_str(" : ");
        let edge = match v.edge {
            Some(Edge::Rising) => Some("R_EDGE"),
            Some(Edge::Falling) => Some("F_EDGE"),
            None => None,
        };
        let init = v.init.as_ref().map(|i| self.init(i));
        self.typed_line(&head, &v.ty, edge, init.as_deref());
    }

    fn configuration(&mut self, c: &Configuration) {
        self.line(&format!("CONFIGURATION {}", self.name(c.name)));
        self.nested(|p| {
            for b in &c.var_blocks {
                p.var_block(b);
            }
            for r in &c.resources {
                match r.name {
                    Some(n) => {
                        let mut head = format!("RESOURCE {}", p.name(n));
                        if let Some(on) = r.on {
                            let _ = write!(head, " ON {}", p.name(on));
                        }
                        p.line(&head);
                        p.nested(|p| p.resource_body(r));
                        p.line("END_RESOURCE");
                    }
                    None => p.resource_body(r),
                }
            }
        });
        self.line("END_CONFIGURATION");
    }

    fn resource_body(&mut self, r: &Resource) {
        for b in &r.var_blocks {
            self.var_block(b);
        }
        for t in &r.tasks {
            let mut parts = Vec::new();
            for (k, v) in [
                ("SINGLE", t.single),
                ("INTERVAL", t.interval),
                ("PRIORITY", t.priority),
            ] {
                if let Some(v) = v {
                    parts.push(format!("{k} := {}", self.expr(v, 0)));
                }
            }
            let text = format!("TASK {} ({});", self.name(t.name), parts.join(", "));
            self.line(&text);
        }
        for prog in &r.programs {
            let mut text = String::from("PROGRAM ");
            match prog.retention {
                Some(Retention::Retain) => text.push_str("RETAIN "),
                Some(Retention::NonRetain) => text.push_str("NON_RETAIN "),
                None => {}
            }
            text.push_str(self.name(prog.name));
            if let Some(t) = prog.task {
                let _ = write!(text, " WITH {}", self.name(t));
            }
            let _ = write!(text, " : {}", self.name(prog.type_name));
            if !prog.conns.is_empty() {
                let conns: Vec<String> = prog
                    .conns
                    .iter()
                    .map(|c| match c {
                        ProgramConn::Input { name, value } => {
                            format!("{} := {}", self.expr(*name, 0), self.expr(*value, 0))
                        }
                        ProgramConn::Output { name, target } => {
                            format!("{} => {}", self.expr(*name, 0), self.expr(*target, 0))
                        }
                        ProgramConn::FbTask { fb, task } => {
                            format!("{} WITH {}", self.expr(*fb, 0), self.name(*task))
                        }
                    })
                    .collect();
                let _ = write!(text, " ({})", conns.join(", "));
            }
            text.push(';');
            self.line(&text);
        }
    }

    fn stmts(&mut self, stmts: &[Stmt]) {
        for s in stmts {
            self.stmt(s);
        }
    }

    fn stmt(&mut self, s: &Stmt) {
        match &s.kind {
            StmtKind::Empty => self.line(";"),
            StmtKind::Il { body, .. } => self.il(body),
            StmtKind::Error => self.line("(* unparsable statement *)"),
            StmtKind::Assign { target, value } => {
                let text = format!("{} := {};", self.expr(*target, 0), self.expr(*value, 0));
                self.line(&text);
            }
            StmtKind::AssignAttempt { target, value } => {
                let text = format!("{} ?= {};", self.expr(*target, 0), self.expr(*value, 0));
                self.line(&text);
            }
            StmtKind::Call(e) => {
                let text = format!("{};", self.expr(*e, 0));
                self.line(&text);
            }
            StmtKind::If {
                branches,
                else_body,
            } => {
                for (i, b) in branches.iter().enumerate() {
                    let kw = if i == 0 { "IF" } else { "ELSIF" };
                    let text = format!("{kw} {} THEN", self.expr(b.cond, 0));
                    self.line(&text);
                    self.nested(|p| p.stmts(&b.body));
                }
                if let Some(e) = else_body {
                    self.line("ELSE");
                    self.nested(|p| p.stmts(e));
                }
                self.line("END_IF;");
            }
            StmtKind::Case {
                selector,
                arms,
                else_body,
            } => {
                let text = format!("CASE {} OF", self.expr(*selector, 0));
                self.line(&text);
                self.nested(|p| {
                    for a in arms {
                        let labels: Vec<String> = a
                            .labels
                            .iter()
                            .map(|l| match l {
                                CaseLabel::Value(v) => p.expr(*v, 0),
                                CaseLabel::Range(lo, hi) => {
                                    format!("{}..{}", p.expr(*lo, 0), p.expr(*hi, 0))
                                }
                            })
                            .collect();
                        p.line(&format!("{}:", labels.join(", ")));
                        p.nested(|p| p.stmts(&a.body));
                    }
                    if let Some(e) = else_body {
                        p.line("ELSE");
                        p.nested(|p| p.stmts(e));
                    }
                });
                self.line("END_CASE;");
            }
            StmtKind::For {
                var,
                from,
                to,
                by,
                body,
            } => {
                let mut text = format!(
                    "FOR {} := {} TO {}",
                    self.name(*var),
                    self.expr(*from, 0),
                    self.expr(*to, 0)
                );
                if let Some(b) = by {
                    let _ = write!(text, " BY {}", self.expr(*b, 0));
                }
                text.push_str(" DO");
                self.line(&text);
                self.nested(|p| p.stmts(body));
                self.line("END_FOR;");
            }
            StmtKind::While { cond, body } => {
                let text = format!("WHILE {} DO", self.expr(*cond, 0));
                self.line(&text);
                self.nested(|p| p.stmts(body));
                self.line("END_WHILE;");
            }
            StmtKind::Repeat { body, until } => {
                self.line("REPEAT");
                self.nested(|p| p.stmts(body));
                let text = format!("UNTIL {}", self.expr(*until, 0));
                self.line(&text);
                self.line("END_REPEAT;");
            }
            StmtKind::Exit => self.line("EXIT;"),
            StmtKind::Continue => self.line("CONTINUE;"),
            StmtKind::Return => self.line("RETURN;"),
            StmtKind::Unsupported(_) => self.line("(* unsupported statement *)"),
        }
    }

    fn dims(&self, dims: &[ArrayDim]) -> String {
        let ds: Vec<String> = dims
            .iter()
            .map(|d| match d {
                ArrayDim::Range { lo, hi } => {
                    format!("{}..{}", self.expr(*lo, 0), self.expr(*hi, 0))
                }
                ArrayDim::Star(_) => "*".into(),
            })
            .collect();
        ds.join(", ")
    }

    fn type_text(&self, t: &TypeSpec) -> String {
        match &t.kind {
            TypeSpecKind::Error => "(* unparsable type *) INT".into(),
            TypeSpecKind::Elementary(e) => e.name().into(),
            TypeSpecKind::Generic(g) => g.name().into(),
            TypeSpecKind::Named(n) => self.name(*n).into(),
            TypeSpecKind::String { wide, len } => {
                let kw = if *wide { "WSTRING" } else { "STRING" };
                match len {
                    Some(l) => format!("{kw}[{}]", self.expr(*l, 0)),
                    None => kw.into(),
                }
            }
            TypeSpecKind::Subrange { base, lo, hi } => {
                format!(
                    "{} ({}..{})",
                    self.type_text(base),
                    self.expr(*lo, 0),
                    self.expr(*hi, 0)
                )
            }
            TypeSpecKind::Enum { values, base } => {
                let vs: Vec<String> = values
                    .iter()
                    .map(|m| match m.value {
                        Some(v) => format!("{} := {}", self.name(m.name), self.expr(v, 0)),
                        None => self.name(m.name).into(),
                    })
                    .collect();
                match base {
                    Some(b) => format!("{} ({})", self.type_text(b), vs.join(", ")),
                    None => format!("({})", vs.join(", ")),
                }
            }
            TypeSpecKind::Array { dims, elem } => {
                format!("ARRAY[{}] OF {}", self.dims(dims), self.type_text(elem))
            }
            // Inline structs only occur nested in arrays of arrays; print
            // them on one line.
            TypeSpecKind::Struct { members } => {
                let mut s = String::from("STRUCT ");
                for m in members {
                    let names: Vec<&str> = m.names.iter().map(|i| self.name(*i)).collect();
                    let _ = write!(s, "{} : {}", names.join(", "), self.type_text(&m.ty));
                    if let Some(i) = &m.init {
                        let _ = write!(s, " := {}", self.init(i));
                    }
                    s.push_str("; ");
                }
                s.push_str("END_STRUCT");
                s
            }
            TypeSpecKind::Ref(target) => format!("REF_TO {}", self.type_text(target)),
            TypeSpecKind::Pointer(target) => format!("POINTER TO {}", self.type_text(target)),
        }
    }

    fn init(&self, i: &Init) -> String {
        match &i.kind {
            InitKind::Expr(e) => self.expr(*e, 0),
            InitKind::Array(elems) => {
                let es: Vec<String> = elems
                    .iter()
                    .map(|e| {
                        let vs: Vec<String> = e.values.iter().map(|v| self.init(v)).collect();
                        let v = vs.join(", ");
                        match e.repeat {
                            Some(n) => format!("{}({v})", self.expr(n, POSTFIX)),
                            None => v,
                        }
                    })
                    .collect();
                format!("[{}]", es.join(", "))
            }
            InitKind::Struct(elems) => {
                let es: Vec<String> = elems
                    .iter()
                    .map(|e| format!("{} := {}", self.name(e.name), self.init(&e.value)))
                    .collect();
                format!("({})", es.join(", "))
            }
        }
    }

    /// An expression in a context that binds at `ctx` (0: anywhere).
    fn expr(&self, id: ExprId, ctx: u8) -> String {
        let e = self.ast.expr(id);
        let (text, prec) = match &e.kind {
            ExprKind::Error => ("(* error *) 0".into(), POSTFIX),
            ExprKind::Literal(l) => (literal_text(l, self.interner), POSTFIX),
            ExprKind::Name(n) => (self.name(*n).into(), POSTFIX),
            ExprKind::EnumValue { ty, value } => {
                (format!("{}#{}", self.name(*ty), self.name(*value)), POSTFIX)
            }
            ExprKind::Address(a) => (a.to_string(), POSTFIX),
            ExprKind::Member { base, member } => (
                format!("{}.{}", self.expr(*base, POSTFIX), self.name(*member)),
                POSTFIX,
            ),
            ExprKind::PartialAccess { base, size, index } => (
                format!("{}.%{}{index}", self.expr(*base, POSTFIX), size.letter()),
                POSTFIX,
            ),
            ExprKind::Index { base, indices } => {
                let is: Vec<String> = indices.iter().map(|i| self.expr(*i, 0)).collect();
                (
                    format!("{}[{}]", self.expr(*base, POSTFIX), is.join(", ")),
                    POSTFIX,
                )
            }
            ExprKind::Call { callee, args } => {
                let a: Vec<String> = args
                    .iter()
                    .map(|a| match &a.kind {
                        ArgKind::Positional(v) => self.expr(*v, 0),
                        ArgKind::Input { name, value } => {
                            format!("{} := {}", self.name(*name), self.expr(*value, 0))
                        }
                        ArgKind::Output {
                            name,
                            negated,
                            target,
                        } => {
                            let not = if *negated { "NOT " } else { "" };
                            format!("{not}{} => {}", self.name(*name), self.expr(*target, 0))
                        }
                    })
                    .collect();
                (
                    format!("{}({})", self.expr(*callee, POSTFIX), a.join(", ")),
                    POSTFIX,
                )
            }
            ExprKind::Unary { op, operand } => {
                let inner = self.expr(*operand, UNARY_PRECEDENCE);
                let text = match op {
                    UnaryOp::Not => format!("NOT {inner}"),
                    UnaryOp::Neg if inner.starts_with('-') => format!("- {inner}"),
                    UnaryOp::Neg => format!("-{inner}"),
                    UnaryOp::Plus if inner.starts_with('+') => format!("+ {inner}"),
                    UnaryOp::Plus => format!("+{inner}"),
                };
                (text, UNARY_PRECEDENCE)
            }
            ExprKind::Binary { op, lhs, rhs } => {
                let p = op.precedence();
                let (l, r) = if *op == BinaryOp::Pow {
                    let rhs_ctx = match self.ast.expr(*rhs).kind {
                        ExprKind::Unary { .. } => UNARY_PRECEDENCE,
                        _ => POSTFIX,
                    };
                    (self.expr(*lhs, p), self.expr(*rhs, rhs_ctx))
                } else {
                    (self.expr(*lhs, p), self.expr(*rhs, p + 1))
                };
                (format!("{l} {} {r}", op.symbol()), p)
            }
            ExprKind::Paren(inner) => (format!("({})", self.expr(*inner, 0)), POSTFIX),
            ExprKind::Deref(base) => (format!("{}^", self.expr(*base, POSTFIX)), POSTFIX),
            // (Only in the meaning of IL instructions, which print as IL.)
            ExprKind::IlCr => ("(* current result *) 0".into(), POSTFIX),
        };
        if prec < ctx {
            format!("({text})")
        } else {
            text
        }
    }
}

fn contains_struct(t: &TypeSpec) -> bool {
    match &t.kind {
        TypeSpecKind::Struct { .. } => true,
        TypeSpecKind::Array { elem, .. } => contains_struct(elem),
        _ => false,
    }
}

/// One line of an Instruction List body as text: its nesting depth, the
/// text and the span of the instruction it comes from.
pub(crate) struct IlLine {
    pub depth: usize,
    pub text: String,
    pub span: Span,
}

/// The lines of an IL instruction list, with operands written by
/// `operand` (ST text for the printer, S-expressions for the dump).
pub(crate) fn il_lines(
    instrs: &[IlInstr],
    interner: &Interner,
    operand: &dyn Fn(ExprId) -> String,
    depth: usize,
    out: &mut Vec<IlLine>,
) {
    let name = |i: Ident| interner.spelling(i.sym).to_string();
    for ins in instrs {
        let label = ins
            .label
            .map(|l| format!("{}: ", name(l)))
            .unwrap_or_default();
        let mut line = |d: usize, text: String| {
            out.push(IlLine {
                depth: d,
                text,
                span: ins.span,
            })
        };
        match &ins.op {
            IlOp::None => line(depth, label.trim_end().to_string()),
            IlOp::Simple { op, operand: o, .. } => {
                let o = o.map(|o| format!(" {}", operand(o))).unwrap_or_default();
                line(depth, format!("{label}{}{o}", op.name()));
            }
            IlOp::Paren {
                op,
                operand: o,
                body,
                ..
            } => {
                let o = o.map(|o| format!(" {}", operand(o))).unwrap_or_default();
                line(depth, format!("{label}{}({o}", op.name()));
                il_lines(body, interner, operand, depth + 1, out);
                out.push(IlLine {
                    depth,
                    text: ")".into(),
                    span: ins.span,
                });
            }
            IlOp::Call { name: n, operands } => {
                let os: Vec<String> = operands.iter().map(|o| operand(*o)).collect();
                let sep = if os.is_empty() { "" } else { " " };
                line(depth, format!("{label}{}{sep}{}", name(*n), os.join(", ")));
            }
            IlOp::FormalCall { name: n, args } => {
                let head = format!("{label}{}", name(*n));
                il_formal_lines(head, args, interner, operand, depth, ins.span, out);
            }
            IlOp::Cal {
                op, callee, args, ..
            } => {
                let head = format!("{label}CAL{} {}", op.suffix(), operand(*callee));
                match args {
                    None => line(depth, head),
                    Some(IlCallArgs::Positional(list)) => {
                        let os: Vec<String> = list.iter().map(|o| operand(*o)).collect();
                        line(depth, format!("{head}({})", os.join(", ")));
                    }
                    Some(IlCallArgs::Formal(args)) => {
                        il_formal_lines(head, args, interner, operand, depth, ins.span, out)
                    }
                }
            }
            IlOp::Jump { op, target, .. } => line(
                depth,
                format!("{label}JMP{} {}", op.suffix(), name(*target)),
            ),
            IlOp::Ret { op, .. } => line(depth, format!("{label}RET{}", op.suffix())),
        }
    }
}

/// `head(a := x, q => y)`, spread over lines when a value is a sequence.
fn il_formal_lines(
    head: String,
    args: &[IlArg],
    interner: &Interner,
    operand: &dyn Fn(ExprId) -> String,
    depth: usize,
    span: Span,
    out: &mut Vec<IlLine>,
) {
    let name = |i: Ident| interner.spelling(i.sym).to_string();
    let simple = |a: &IlArg| match &a.kind {
        IlArgKind::Input {
            name: n,
            value: IlArgValue::Operand(v),
        } => Some(format!("{} := {}", name(*n), operand(*v))),
        IlArgKind::Output {
            name: n,
            negated,
            target,
        } => {
            let not = if *negated { "NOT " } else { "" };
            Some(format!("{not}{} => {}", name(*n), operand(*target)))
        }
        IlArgKind::Input { .. } => None,
    };
    if let Some(all) = args.iter().map(simple).collect::<Option<Vec<_>>>() {
        out.push(IlLine {
            depth,
            text: format!("{head}({})", all.join(", ")),
            span,
        });
        return;
    }
    out.push(IlLine {
        depth,
        text: format!("{head}("),
        span,
    });
    for (i, a) in args.iter().enumerate() {
        let comma = if i + 1 < args.len() { "," } else { "" };
        match (simple(a), &a.kind) {
            (Some(t), _) => out.push(IlLine {
                depth: depth + 1,
                text: format!("{t}{comma}"),
                span,
            }),
            (
                None,
                IlArgKind::Input {
                    name: n,
                    value: IlArgValue::List { body, .. },
                },
            ) => {
                out.push(IlLine {
                    depth: depth + 1,
                    text: format!("{} := (", name(*n)),
                    span,
                });
                il_lines(body, interner, operand, depth + 2, out);
                out.push(IlLine {
                    depth: depth + 1,
                    text: format!("){comma}"),
                    span,
                });
            }
            (None, _) => {}
        }
    }
    out.push(IlLine {
        depth,
        text: ")".into(),
        span,
    });
}

/// `action(qualifier, duration, indicators)` of a step.
pub(crate) fn sfc_assoc(
    a: &ActionAssoc,
    interner: &Interner,
    expr: &dyn Fn(ExprId) -> String,
) -> String {
    let mut parts = Vec::new();
    if let Some((q, _)) = a.qualifier {
        parts.push(q.name().to_string());
    }
    if let Some(d) = a.duration {
        parts.push(expr(d));
    }
    for i in &a.indicators {
        parts.push(interner.spelling(i.sym).to_string());
    }
    format!("{}({})", interner.spelling(a.action.sym), parts.join(", "))
}

/// `TRANSITION [name] [(PRIORITY := n)] FROM steps TO steps`.
pub(crate) fn sfc_transition_head(
    t: &SfcTransition,
    interner: &Interner,
    expr: &dyn Fn(ExprId) -> String,
) -> String {
    let steps = |names: &[Ident], parens: bool| {
        let list: Vec<&str> = names.iter().map(|n| interner.spelling(n.sym)).collect();
        if parens || list.len() != 1 {
            format!("({})", list.join(", "))
        } else {
            list.join(", ")
        }
    };
    let mut head = String::from("TRANSITION");
    if let Some(n) = t.name {
        head.push(' ');
        head.push_str(interner.spelling(n.sym));
    }
    if let Some(p) = t.priority {
        let _ = write!(head, " (PRIORITY := {})", expr(p));
    }
    let _ = write!(
        head,
        " FROM {} TO {}",
        steps(&t.from, t.from_parens),
        steps(&t.to, t.to_parens)
    );
    head
}
