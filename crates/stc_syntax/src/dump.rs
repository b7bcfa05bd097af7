//! A readable, deterministic listing of the syntax tree (`stc build --emit
//! ast`, and the AST snapshots of the test suite). Declarations and
//! statements are indented lines; expressions are one-line S-expressions, so
//! precedence and associativity are visible at a glance: `a + b * c` is
//! `(+ a (* b c))`.

use std::fmt::Write;

use stc_diagnostics::Span;

use crate::ast::*;
use crate::intern::Interner;
use crate::literal;

/// How node positions are shown: a function from a span to text such as
/// `3:5`, or `None` for no positions.
pub type PosFn<'a> = Option<&'a dyn Fn(Span) -> String>;

pub fn dump(ast: &Ast, interner: &Interner, pos: PosFn<'_>) -> String {
    let mut d = Dumper {
        ast,
        interner,
        pos,
        out: String::new(),
        indent: 0,
    };
    for item in &ast.items {
        d.item(item);
    }
    d.out
}

struct Dumper<'a> {
    ast: &'a Ast,
    interner: &'a Interner,
    pos: PosFn<'a>,
    out: String,
    indent: usize,
}

impl Dumper<'_> {
    fn line(&mut self, span: Span, text: &str) {
        for _ in 0..self.indent {
            self.out.push_str("  ");
        }
        self.out.push_str(text);
        if let Some(p) = self.pos {
            let _ = write!(self.out, " @{}", p(span));
        }
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

    fn item(&mut self, item: &Item) {
        match item {
            Item::Types(decls, span) => {
                self.line(*span, "Types");
                self.nested(|d| {
                    for t in decls {
                        d.type_decl(t);
                    }
                });
            }
            Item::Pou(p) => self.pou(p),
            Item::Configuration(c) => self.configuration(c),
            Item::GlobalVars(b) => self.var_block(b),
            Item::Namespace(ns) => {
                self.pragmas(&ns.pragmas);
                let internal = if ns.internal { " INTERNAL" } else { "" };
                let text = format!("Namespace{internal} {}", self.name(ns.name));
                self.line(ns.span, &text);
                self.indent += 1;
            }
            Item::EndNamespace(span) => {
                self.indent = self.indent.saturating_sub(1);
                self.line(*span, "EndNamespace");
            }
            Item::Using(u) => {
                let text = format!("Using {}", self.names_text(&u.names));
                self.line(u.span, &text);
            }
        }
    }

    fn names_text(&self, names: &[Ident]) -> String {
        let names: Vec<&str> = names.iter().map(|n| self.name(*n)).collect();
        names.join(", ")
    }

    fn pragmas(&mut self, pragmas: &[Span]) {
        if !pragmas.is_empty() {
            let n = pragmas.len();
            self.line(pragmas[0], &format!("Pragmas {n}"));
        }
    }

    fn type_decl(&mut self, t: &TypeDecl) {
        self.pragmas(&t.pragmas);
        let mut text = format!(
            "TypeDecl {} : {}",
            self.name(t.name),
            self.type_text(&t.spec)
        );
        if let Some(i) = &t.init {
            let _ = write!(text, " := {}", self.init_text(i));
        }
        self.line(t.span, &text);
        self.struct_members(&t.spec);
    }

    /// Members of a STRUCT spec (possibly inside an array) as nested lines.
    fn struct_members(&mut self, spec: &TypeSpec) {
        match &spec.kind {
            TypeSpecKind::Struct { members } => self.nested(|d| {
                for m in members {
                    d.var_decl(m);
                }
            }),
            TypeSpecKind::Array { elem, .. } => self.struct_members(elem),
            _ => {}
        }
    }

    fn pou(&mut self, p: &Pou) {
        self.pragmas(&p.pragmas);
        let mut text = p.keyword().to_string();
        for (on, word) in [
            (p.is_abstract, " ABSTRACT"),
            (p.is_final, " FINAL"),
            (p.internal, " INTERNAL"),
        ] {
            if on {
                text.push_str(word);
            }
        }
        let _ = write!(text, " {}", self.name(p.name));
        if !p.usings.is_empty() {
            let _ = write!(text, " USING {}", self.names_text(&p.usings));
        }
        if let Some(b) = &p.extends {
            let _ = write!(text, " EXTENDS {}", self.name(*b));
        }
        if !p.implements.is_empty() {
            let word = if p.is_interface() {
                "EXTENDS"
            } else {
                "IMPLEMENTS"
            };
            let names: Vec<String> = p
                .implements
                .iter()
                .map(|i| self.name(*i).to_string())
                .collect();
            let _ = write!(text, " {word} {}", names.join(", "));
        }
        if let Some(r) = &p.return_type {
            let _ = write!(text, " : {}", self.type_text(r));
        }
        self.line(p.span, &text);
        self.nested(|d| {
            let shown = p.var_blocks.len() - p.sfc.as_ref().map_or(0, |s| s.generated_blocks);
            for b in &p.var_blocks[..shown] {
                d.var_block(b);
            }
            for m in &p.methods {
                let word = match m.property {
                    Some((crate::ast::PropertyPart::Get, _)) => "PropertyGet",
                    Some((crate::ast::PropertyPart::Set, _)) => "PropertySet",
                    None if m.is_action => "Action",
                    None => "Method",
                };
                let mut head = format!("{word}{} {}", m.modifiers(), d.name(m.pou.name));
                if let Some(r) = &m.pou.return_type {
                    let _ = write!(head, " : {}", d.type_text(r));
                }
                d.line(m.pou.span, &head);
                d.nested(|d| {
                    for b in &m.pou.var_blocks {
                        d.var_block(b);
                    }
                    d.line(m.pou.span, "Body");
                    d.nested(|d| d.stmts(&m.pou.body));
                });
            }
            if let Some(sfc) = &p.sfc {
                d.sfc(sfc);
            } else {
                d.line(p.span, "Body");
                d.nested(|d| d.stmts(&p.body));
            }
            if let Some(il) = &p.il {
                d.il(il);
            }
        });
    }

    fn il(&mut self, il: &IlBody) {
        self.line(il.span, "IlBody");
        let mut lines = Vec::new();
        crate::print::il_lines(&il.instrs, self.interner, &|e| self.expr(e), 0, &mut lines);
        self.nested(|d| {
            for l in lines {
                d.indent += l.depth;
                d.line(l.span, &l.text);
                d.indent -= l.depth;
            }
        });
    }

    fn var_block(&mut self, b: &VarBlock) {
        let mut text = format!("VarBlock {}", b.kind.keyword());
        if let Some(a) = b.access {
            text.push(' ');
            text.push_str(a.keyword());
        }
        if b.constant {
            text.push_str(" CONSTANT");
        }
        match b.retention {
            Some(Retention::Retain) => text.push_str(" RETAIN"),
            Some(Retention::NonRetain) => text.push_str(" NON_RETAIN"),
            None => {}
        }
        self.line(b.span, &text);
        self.nested(|d| match &b.items {
            VarBlockItems::Vars(vs) => {
                for v in vs {
                    d.var_decl(v);
                }
            }
            VarBlockItems::Access(a) => {
                for a in a {
                    let resource = a
                        .resource
                        .map(|r| format!("{}.", d.name(r)))
                        .unwrap_or_default();
                    let mut text = format!(
                        "Access {} : {resource}{} : {}",
                        d.name(a.name),
                        d.expr(a.path),
                        d.type_text(&a.ty)
                    );
                    match a.direction {
                        Some(AccessDirection::ReadOnly) => text.push_str(" READ_ONLY"),
                        Some(AccessDirection::ReadWrite) => text.push_str(" READ_WRITE"),
                        None => {}
                    }
                    d.line(a.span, &text);
                }
            }
            VarBlockItems::Config(c) => {
                for c in c {
                    let path: Vec<&str> = c.path.iter().map(|i| d.name(*i)).collect();
                    let mut text = format!("ConfigInit {}", path.join("."));
                    if let Some(l) = &c.location {
                        let _ = write!(text, " AT {}", l.address);
                    }
                    let _ = write!(text, " : {}", d.type_text(&c.ty));
                    if let Some(i) = &c.init {
                        let _ = write!(text, " := {}", d.init_text(i));
                    }
                    d.line(c.span, &text);
                }
            }
        });
    }

    fn var_decl(&mut self, v: &VarDecl) {
        self.pragmas(&v.pragmas);
        let names: Vec<&str> = v.names.iter().map(|i| self.name(*i)).collect();
        let mut text = format!("VarDecl {}", names.join(", "));
        if let Some(l) = &v.location {
            let _ = write!(text, " AT {}", l.address);
        }
        let _ = write!(text, " : {}", self.type_text(&v.ty));
        match v.edge {
            Some(Edge::Rising) => text.push_str(" R_EDGE"),
            Some(Edge::Falling) => text.push_str(" F_EDGE"),
            None => {}
        }
        if let Some(i) = &v.init {
            let _ = write!(text, " := {}", self.init_text(i));
        }
        self.line(v.span, &text);
        self.struct_members(&v.ty);
    }

    fn configuration(&mut self, c: &Configuration) {
        self.line(c.span, &format!("CONFIGURATION {}", self.name(c.name)));
        self.nested(|d| {
            for b in &c.var_blocks {
                d.var_block(b);
            }
            for r in &c.resources {
                let mut text = String::from("RESOURCE");
                if let Some(n) = r.name {
                    let _ = write!(text, " {}", d.name(n));
                }
                if let Some(on) = r.on {
                    let _ = write!(text, " ON {}", d.name(on));
                }
                d.line(r.span, &text);
                d.nested(|d| {
                    for b in &r.var_blocks {
                        d.var_block(b);
                    }
                    for t in &r.tasks {
                        let mut text = format!("TASK {}", d.name(t.name));
                        for (k, v) in [
                            ("SINGLE", t.single),
                            ("INTERVAL", t.interval),
                            ("PRIORITY", t.priority),
                        ] {
                            if let Some(v) = v {
                                let _ = write!(text, " {k}={}", d.expr(v));
                            }
                        }
                        d.line(t.span, &text);
                    }
                    for p in &r.programs {
                        let mut text = String::from("PROGRAM");
                        match p.retention {
                            Some(Retention::Retain) => text.push_str(" RETAIN"),
                            Some(Retention::NonRetain) => text.push_str(" NON_RETAIN"),
                            None => {}
                        }
                        let _ = write!(text, " {}", d.name(p.name));
                        if let Some(t) = p.task {
                            let _ = write!(text, " WITH {}", d.name(t));
                        }
                        let _ = write!(text, " : {}", d.name(p.type_name));
                        d.line(p.span, &text);
                        d.nested(|d| {
                            for c in &p.conns {
                                let text = match c {
                                    ProgramConn::Input { name, value } => {
                                        format!("Conn {} := {}", d.expr(*name), d.expr(*value))
                                    }
                                    ProgramConn::Output { name, target } => {
                                        format!("Conn {} => {}", d.expr(*name), d.expr(*target))
                                    }
                                    ProgramConn::FbTask { fb, task } => {
                                        format!("Conn {} WITH {}", d.expr(*fb), d.name(*task))
                                    }
                                };
                                d.line(p.span, &text);
                            }
                        });
                    }
                });
            }
        });
    }

    fn sfc(&mut self, sfc: &SfcBody) {
        self.line(sfc.span, "SfcBody");
        self.nested(|d| {
            for e in &sfc.elements {
                match e {
                    SfcElement::Step(st) => {
                        let kw = if st.initial { "InitialStep" } else { "Step" };
                        d.line(st.span, &format!("{kw} {}", d.name(st.name)));
                        d.nested(|d| {
                            for a in &st.assocs {
                                let text = crate::print::sfc_assoc(a, d.interner, &|e| d.expr(e));
                                d.line(a.span, &format!("Assoc {text}"));
                            }
                        });
                    }
                    SfcElement::Transition(t) => {
                        let head = crate::print::sfc_transition_head(t, d.interner, &|e| d.expr(e));
                        let head = head.replacen("TRANSITION", "Transition", 1);
                        match &t.cond {
                            TransitionCond::Expr(e) => {
                                let text = format!("{head} := {}", d.expr(*e));
                                d.line(t.span, &text);
                            }
                            TransitionCond::Body(body) => {
                                d.line(t.span, &format!("{head} :"));
                                d.nested(|d| d.stmts(body));
                            }
                            TransitionCond::Il(il) => {
                                d.line(t.span, &format!("{head} :"));
                                d.nested(|d| d.il(il));
                            }
                        }
                    }
                    SfcElement::Action(a) => {
                        d.line(a.span, &format!("Action {}", d.name(a.name)));
                        d.nested(|d| match &a.il {
                            Some(il) => d.il(il),
                            None => d.stmts(&a.body),
                        });
                    }
                }
            }
        });
    }

    fn stmts(&mut self, stmts: &[Stmt]) {
        for s in stmts {
            self.stmt(s);
        }
    }

    fn stmt(&mut self, s: &Stmt) {
        match &s.kind {
            StmtKind::Empty => self.line(s.span, "Empty"),
            StmtKind::Error => self.line(s.span, "Error"),
            StmtKind::Assign { target, value } => {
                let text = format!("Assign {} := {}", self.expr(*target), self.expr(*value));
                self.line(s.span, &text);
            }
            StmtKind::AssignAttempt { target, value } => {
                let text = format!(
                    "AssignAttempt {} ?= {}",
                    self.expr(*target),
                    self.expr(*value)
                );
                self.line(s.span, &text);
            }
            StmtKind::Call(e) => {
                let text = format!("Call {}", self.expr(*e));
                self.line(s.span, &text);
            }
            StmtKind::If {
                branches,
                else_body,
            } => {
                self.line(s.span, "If");
                self.nested(|d| {
                    for b in branches {
                        let text = format!("Branch {}", d.expr(b.cond));
                        d.line(s.span, &text);
                        d.nested(|d| d.stmts(&b.body));
                    }
                    if let Some(e) = else_body {
                        d.line(s.span, "Else");
                        d.nested(|d| d.stmts(e));
                    }
                });
            }
            StmtKind::Case {
                selector,
                arms,
                else_body,
            } => {
                let text = format!("Case {}", self.expr(*selector));
                self.line(s.span, &text);
                self.nested(|d| {
                    for a in arms {
                        let labels: Vec<String> = a
                            .labels
                            .iter()
                            .map(|l| match l {
                                CaseLabel::Value(v) => d.expr(*v),
                                CaseLabel::Range(lo, hi) => {
                                    format!("{}..{}", d.expr(*lo), d.expr(*hi))
                                }
                            })
                            .collect();
                        d.line(a.span, &format!("Arm {}", labels.join(", ")));
                        d.nested(|d| d.stmts(&a.body));
                    }
                    if let Some(e) = else_body {
                        d.line(s.span, "Else");
                        d.nested(|d| d.stmts(e));
                    }
                });
            }
            StmtKind::For {
                var,
                from,
                to,
                by,
                body,
            } => {
                let mut text = format!(
                    "For {} := {} TO {}",
                    self.name(*var),
                    self.expr(*from),
                    self.expr(*to)
                );
                if let Some(b) = by {
                    let _ = write!(text, " BY {}", self.expr(*b));
                }
                self.line(s.span, &text);
                self.nested(|d| d.stmts(body));
            }
            StmtKind::While { cond, body } => {
                let text = format!("While {}", self.expr(*cond));
                self.line(s.span, &text);
                self.nested(|d| d.stmts(body));
            }
            StmtKind::Repeat { body, until } => {
                self.line(s.span, "Repeat");
                self.nested(|d| d.stmts(body));
                let text = format!("Until {}", self.expr(*until));
                self.line(s.span, &text);
            }
            StmtKind::Exit => self.line(s.span, "Exit"),
            StmtKind::Continue => self.line(s.span, "Continue"),
            StmtKind::Return => self.line(s.span, "Return"),
            StmtKind::Il { body, .. } => self.il(body),
            StmtKind::Unsupported(exprs) => {
                let parts: Vec<String> = exprs.iter().map(|e| self.expr(*e)).collect();
                self.line(s.span, &format!("Unsupported {}", parts.join(" ")));
            }
        }
    }

    fn type_text(&self, t: &TypeSpec) -> String {
        match &t.kind {
            TypeSpecKind::Error => "<error>".into(),
            TypeSpecKind::Elementary(e) => e.name().into(),
            TypeSpecKind::Generic(g) => g.name().into(),
            TypeSpecKind::Named(n) => self.name(*n).into(),
            TypeSpecKind::String { wide, len } => {
                let kw = if *wide { "WSTRING" } else { "STRING" };
                match len {
                    Some(l) => format!("{kw}[{}]", self.expr(*l)),
                    None => kw.into(),
                }
            }
            TypeSpecKind::Subrange { base, lo, hi } => {
                format!(
                    "{} ({}..{})",
                    self.type_text(base),
                    self.expr(*lo),
                    self.expr(*hi)
                )
            }
            TypeSpecKind::Enum { values, base } => {
                let vs: Vec<String> = values
                    .iter()
                    .map(|m| match m.value {
                        Some(v) => format!("{} := {}", self.name(m.name), self.expr(v)),
                        None => self.name(m.name).into(),
                    })
                    .collect();
                match base {
                    Some(b) => format!("{} ({})", self.type_text(b), vs.join(", ")),
                    None => format!("({})", vs.join(", ")),
                }
            }
            TypeSpecKind::Array { dims, elem } => {
                let ds: Vec<String> = dims
                    .iter()
                    .map(|d| match d {
                        ArrayDim::Range { lo, hi } => {
                            format!("{}..{}", self.expr(*lo), self.expr(*hi))
                        }
                        ArrayDim::Star(_) => "*".into(),
                    })
                    .collect();
                format!("ARRAY[{}] OF {}", ds.join(", "), self.type_text(elem))
            }
            TypeSpecKind::Struct { members } => format!("STRUCT ({} members)", members.len()),
            TypeSpecKind::Ref(target) => format!("REF_TO {}", self.type_text(target)),
            TypeSpecKind::Pointer(target) => format!("POINTER TO {}", self.type_text(target)),
        }
    }

    fn init_text(&self, i: &Init) -> String {
        match &i.kind {
            InitKind::Expr(e) => self.expr(*e),
            InitKind::Array(elems) => {
                let es: Vec<String> = elems
                    .iter()
                    .map(|e| {
                        let vs: Vec<String> = e.values.iter().map(|v| self.init_text(v)).collect();
                        let v = vs.join(", ");
                        match e.repeat {
                            Some(n) => format!("{}({v})", self.expr(n)),
                            None => v,
                        }
                    })
                    .collect();
                format!("[{}]", es.join(", "))
            }
            InitKind::Struct(elems) => {
                let es: Vec<String> = elems
                    .iter()
                    .map(|e| format!("{} := {}", self.name(e.name), self.init_text(&e.value)))
                    .collect();
                format!("({})", es.join(", "))
            }
        }
    }

    fn expr(&self, id: ExprId) -> String {
        let e = self.ast.expr(id);
        match &e.kind {
            ExprKind::Error => "<error>".into(),
            ExprKind::Literal(l) => literal_text(l, self.interner),
            ExprKind::Name(n) => self.name(*n).into(),
            ExprKind::EnumValue { ty, value } => {
                format!("{}#{}", self.name(*ty), self.name(*value))
            }
            ExprKind::Address(a) => a.to_string(),
            ExprKind::Member { base, member } => {
                format!("(. {} {})", self.expr(*base), self.name(*member))
            }
            ExprKind::PartialAccess { base, size, index } => {
                format!("(.% {} {}{})", self.expr(*base), size.letter(), index)
            }
            ExprKind::Index { base, indices } => {
                let is: Vec<String> = indices.iter().map(|i| self.expr(*i)).collect();
                format!("([] {} {})", self.expr(*base), is.join(" "))
            }
            ExprKind::Call { callee, args } => {
                let mut s = format!("(call {}", self.expr(*callee));
                for a in args.iter() {
                    match &a.kind {
                        ArgKind::Positional(v) => {
                            let _ = write!(s, " {}", self.expr(*v));
                        }
                        ArgKind::Input { name, value } => {
                            let _ = write!(s, " (:= {} {})", self.name(*name), self.expr(*value));
                        }
                        ArgKind::Output {
                            name,
                            negated,
                            target,
                        } => {
                            let not = if *negated { "NOT " } else { "" };
                            let _ =
                                write!(s, " (=> {not}{} {})", self.name(*name), self.expr(*target));
                        }
                    }
                }
                s.push(')');
                s
            }
            ExprKind::Unary { op, operand } => {
                let o = match op {
                    UnaryOp::Neg => "neg",
                    UnaryOp::Plus => "plus",
                    UnaryOp::Not => "NOT",
                };
                format!("({o} {})", self.expr(*operand))
            }
            ExprKind::Binary { op, lhs, rhs } => {
                format!("({} {} {})", op.symbol(), self.expr(*lhs), self.expr(*rhs))
            }
            ExprKind::Paren(inner) => format!("(paren {})", self.expr(*inner)),
            ExprKind::Deref(base) => format!("(deref {})", self.expr(*base)),
            ExprKind::IlCr => "<CR>".into(),
        }
    }
}

/// A literal as ST source text (shared with the printer).
pub(crate) fn literal_text(l: &Literal, interner: &Interner) -> String {
    let mut s = String::new();
    match l.prefix {
        Some(TypePrefix::Elem(e, _)) => {
            s.push_str(e.name());
            s.push('#');
        }
        Some(TypePrefix::Named(n)) => {
            s.push_str(interner.spelling(n.sym));
            s.push('#');
        }
        None => {}
    }
    match &l.value {
        LitValue::Int { value, negative } => {
            if *negative {
                s.push('-');
            }
            s.push_str(&value.to_string());
        }
        LitValue::Real(v) => s.push_str(&literal::format_real(*v)),
        LitValue::Bool(b) => s.push_str(if *b { "TRUE" } else { "FALSE" }),
        LitValue::String { value, wide } => s.push_str(&literal::format_string(value, *wide)),
        LitValue::Duration { ns, long } => s.push_str(&literal::format_duration(*ns, *long)),
        LitValue::Date { secs, long } => s.push_str(&literal::format_date(*secs, *long)),
        LitValue::Tod { ns, long } => s.push_str(&literal::format_tod(*ns, *long)),
        LitValue::Dt { ns, long } => s.push_str(&literal::format_dt(*ns, *long)),
    }
    s
}
