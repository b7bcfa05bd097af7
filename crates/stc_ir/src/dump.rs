//! The IR as readable text (`stc build --emit ir`). Statements are indented
//! lines; expressions are S-expressions with the type of every operation, so
//! the implicit conversions and the lowering of FOR and CASE are visible.

use std::fmt::Write;

use stc_sema::{Section, TypeId};
use stc_values::{BinOp, UnOp, Value};

use crate::{Expr, ExprKind, Module, Place, Pou, Proj, Root, Stmt, StmtKind, Storage};

/// Dumps every user POU (`with_std`: the standard library prelude too).
pub fn dump(m: &Module, with_std: bool) -> String {
    let mut out = String::new();
    for p in &m.pous {
        if p.is_std && !with_std {
            continue;
        }
        let d = Dumper { m, pou: p };
        d.pou(&mut out);
        out.push('\n');
    }
    out
}

struct Dumper<'a> {
    m: &'a Module,
    pou: &'a Pou,
}

fn section_word(s: Section) -> &'static str {
    match s {
        Section::Input => "input",
        Section::Output => "output",
        Section::InOut => "in_out",
        Section::Var => "var",
        Section::Temp => "temp",
        Section::External => "external",
        Section::Global => "global",
        Section::Result => "result",
    }
}

impl Dumper<'_> {
    fn ty(&self, t: TypeId) -> String {
        let mut s = String::new();
        let info = self.m.types.get(t);
        match info.name {
            Some(_) => s.push_str(self.m.type_name(t).unwrap_or("?")),
            None => match &info.kind {
                stc_sema::TypeKind::Elem(e) => s.push_str(e.name()),
                stc_sema::TypeKind::String { wide, len } => {
                    let _ = write!(s, "{}[{len}]", if *wide { "WSTRING" } else { "STRING" });
                }
                stc_sema::TypeKind::Array { dims, elem } => {
                    let d: Vec<String> = dims.iter().map(|(l, h)| format!("{l}..{h}")).collect();
                    let _ = write!(s, "ARRAY[{}] OF {}", d.join(", "), self.ty(*elem));
                }
                stc_sema::TypeKind::Subrange { base, lo, hi } => {
                    let _ = write!(s, "{} ({lo}..{hi})", base.name());
                }
                stc_sema::TypeKind::Void => s.push_str("VOID"),
                stc_sema::TypeKind::Ref(t) if *t == TypeId::VOID => s.push_str("NULL"),
                stc_sema::TypeKind::Ref(t) => {
                    let _ = write!(s, "REF_TO {}", self.ty(*t));
                }
                stc_sema::TypeKind::Fb(p) | stc_sema::TypeKind::Program(p) => {
                    let pou = &self.m.pous[*p];
                    s.push_str(self.m.spelled(pou.name, pou.name_span));
                }
                _ => s.push('?'),
            },
        }
        s
    }

    fn var_name(&self, v: &crate::Var) -> String {
        match v.hidden {
            Some(role) => format!("{}${role}", self.m.spelled(v.name, v.span)),
            None => self.m.spelled(v.name, v.span).to_string(),
        }
    }

    fn pou(&self, out: &mut String) {
        let p = self.pou;
        let _ = writeln!(
            out,
            "{} {}{}",
            p.kind.keyword(),
            self.m.spelled(p.name, p.name_span),
            if p.is_std { " (standard)" } else { "" }
        );
        for v in &p.vars {
            let storage = match v.storage {
                Storage::Instance => "",
                Storage::Frame => " frame",
                Storage::Ref => " ref",
            };
            let _ = writeln!(
                out,
                "  {} {} : {}{storage}",
                section_word(v.section),
                self.var_name(v),
                self.ty(v.ty)
            );
        }
        self.block(out, &p.body, 1);
        let _ = writeln!(out, "{}", p.kind.end_keyword());
    }

    fn block(&self, out: &mut String, stmts: &[Stmt], depth: usize) {
        for s in stmts {
            self.stmt(out, s, depth);
        }
    }

    fn stmt(&self, out: &mut String, s: &Stmt, depth: usize) {
        let pad = "  ".repeat(depth);
        let at = format!("  @{}", s.line);
        match &s.kind {
            StmtKind::Assign { place, value } => {
                let _ = writeln!(
                    out,
                    "{pad}{} := {}{at}",
                    self.place(place),
                    self.expr(value)
                );
            }
            StmtKind::CallFb {
                instance,
                fb,
                inputs,
                inouts,
                outputs,
            } => {
                let fbp = &self.m.pous[*fb];
                let mut args: Vec<String> = inputs
                    .iter()
                    .map(|(v, e)| {
                        format!(
                            "{} := {}",
                            self.m.spelled(fbp.var(*v).name, fbp.var(*v).span),
                            self.expr(e)
                        )
                    })
                    .collect();
                args.extend(inouts.iter().map(|(v, p)| {
                    format!(
                        "{} <-> {}",
                        self.m.spelled(fbp.var(*v).name, fbp.var(*v).span),
                        self.place(p)
                    )
                }));
                args.extend(outputs.iter().map(|o| {
                    let not = if o.negated { "NOT " } else { "" };
                    format!(
                        "{not}{} => {}",
                        self.m.spelled(fbp.var(o.var).name, fbp.var(o.var).span),
                        self.place(&o.target)
                    )
                }));
                let _ = writeln!(
                    out,
                    "{pad}call {}({}) : {}{at}",
                    self.place(instance),
                    args.join(", "),
                    self.m.spelled(fbp.name, fbp.name_span)
                );
            }
            StmtKind::Eval(e) => {
                let _ = writeln!(out, "{pad}eval {}{at}", self.expr(e));
            }
            StmtKind::If {
                cond,
                then_body,
                else_body,
            } => {
                let _ = writeln!(out, "{pad}if {}{at}", self.expr(cond));
                self.block(out, then_body, depth + 1);
                if !else_body.is_empty() {
                    let _ = writeln!(out, "{pad}else");
                    self.block(out, else_body, depth + 1);
                }
                let _ = writeln!(out, "{pad}end");
            }
            StmtKind::Switch {
                selector,
                arms,
                default,
            } => {
                let _ = writeln!(out, "{pad}switch {}{at}", self.expr(selector));
                for a in arms {
                    let r: Vec<String> = a
                        .ranges
                        .iter()
                        .map(|(lo, hi)| {
                            if lo == hi {
                                lo.to_string()
                            } else {
                                format!("{lo}..{hi}")
                            }
                        })
                        .collect();
                    let _ = writeln!(out, "{pad}case {}", r.join(", "));
                    self.block(out, &a.body, depth + 1);
                }
                if !default.is_empty() {
                    let _ = writeln!(out, "{pad}default");
                    self.block(out, default, depth + 1);
                }
                let _ = writeln!(out, "{pad}end");
            }
            StmtKind::Loop { body, latch } => {
                let _ = writeln!(out, "{pad}loop{at}");
                self.block(out, body, depth + 1);
                if !latch.is_empty() {
                    let _ = writeln!(out, "{pad}latch");
                    self.block(out, latch, depth + 1);
                }
                let _ = writeln!(out, "{pad}end");
            }
            StmtKind::Break => {
                let _ = writeln!(out, "{pad}break{at}");
            }
            StmtKind::Continue => {
                let _ = writeln!(out, "{pad}continue{at}");
            }
            StmtKind::Return => {
                let _ = writeln!(out, "{pad}return{at}");
            }
            StmtKind::Fault(k) => {
                let _ = writeln!(out, "{pad}fault \"{}\"{at}", k.text());
            }
        }
    }

    fn place(&self, p: &Place) -> String {
        let mut s = match &p.root {
            Root::Var(v) => self.var_name(self.pou.var(*v)),
            Root::Global(g) => format!("global {}", {
                let g = &self.m.globals[*g];
                self.m.spelled(g.name, g.span)
            }),
            Root::Direct(a) => a.to_string(),
            Root::Deref(r) => format!("{}^", self.expr(r)),
            Root::This => "THIS^".to_string(),
        };
        for proj in &p.proj {
            match proj {
                Proj::Field(_) | Proj::FbVar(..) => {
                    let name = match proj {
                        Proj::FbVar(fb, v) => {
                            let var = self.m.pous[*fb].var(*v);
                            self.m.spelled(var.name, var.span).to_string()
                        }
                        Proj::Field(i) => format!("#{i}"),
                        _ => String::new(),
                    };
                    let _ = write!(s, ".{name}");
                }
                Proj::Index(idx) => {
                    let i: Vec<String> = idx
                        .iter()
                        .map(|(e, lo, hi)| format!("{} in {lo}..{hi}", self.expr(e)))
                        .collect();
                    let _ = write!(s, "[{}]", i.join(", "));
                }
                Proj::Part(size, n) => {
                    let _ = write!(s, ".%{}{n}", size.letter());
                }
            }
        }
        s
    }

    fn expr(&self, e: &Expr) -> String {
        let t = self.ty(e.ty);
        match &e.kind {
            ExprKind::Const(v) => format!("{}:{t}", value_text(v)),
            ExprKind::Load(p) => self.place(p),
            ExprKind::Ref(p) => format!("(ref:{t} {})", self.place(p)),
            ExprKind::Null => format!("null:{t}"),
            ExprKind::Unary(op, x) => {
                let o = match op {
                    UnOp::Neg => "neg",
                    UnOp::Not => "not",
                };
                format!("({o}:{t} {})", self.expr(x))
            }
            ExprKind::Binary(op, a, b) => {
                format!("({}:{t} {} {})", bin_name(*op), self.expr(a), self.expr(b))
            }
            ExprKind::Convert(x) => format!("(to {t} {})", self.expr(x)),
            ExprKind::Check { value, lo, hi } => format!("(check {lo}..{hi} {})", self.expr(value)),
            ExprKind::CallFn {
                func,
                inputs,
                inouts,
                outputs,
            } => {
                let f = &self.m.pous[*func];
                let mut args: Vec<String> = inputs
                    .iter()
                    .map(|(v, x)| {
                        format!(
                            "{} := {}",
                            self.m.spelled(f.var(*v).name, f.var(*v).span),
                            self.expr(x)
                        )
                    })
                    .collect();
                args.extend(inouts.iter().map(|(v, p)| {
                    format!(
                        "{} <-> {}",
                        self.m.spelled(f.var(*v).name, f.var(*v).span),
                        self.place(p)
                    )
                }));
                args.extend(outputs.iter().map(|o| {
                    format!(
                        "{} => {}",
                        self.m.spelled(f.var(o.var).name, f.var(o.var).span),
                        self.place(&o.target)
                    )
                }));
                format!(
                    "{}({}):{t}",
                    self.m.spelled(f.name, f.name_span),
                    args.join(", ")
                )
            }
            ExprKind::Intrinsic { func, args } => {
                let a: Vec<String> = args.iter().map(|x| self.expr(x)).collect();
                format!("{func:?}({}):{t}", a.join(", "))
            }
            ExprKind::CurTime => "CUR_TIME()".into(),
            // Where a fault is reported: not part of the meaning.
            ExprKind::Located { expr, .. } => self.expr(expr),
        }
    }
}

fn bin_name(op: BinOp) -> &'static str {
    match op {
        BinOp::Add => "add",
        BinOp::Sub => "sub",
        BinOp::Mul => "mul",
        BinOp::Div => "div",
        BinOp::Mod => "mod",
        BinOp::Pow => "pow",
        BinOp::And => "and",
        BinOp::Or => "or",
        BinOp::Xor => "xor",
        BinOp::Eq => "eq",
        BinOp::Ne => "ne",
        BinOp::Lt => "lt",
        BinOp::Le => "le",
        BinOp::Gt => "gt",
        BinOp::Ge => "ge",
    }
}

fn value_text(v: &Value) -> String {
    match v {
        Value::Bool(b) => if *b { "TRUE" } else { "FALSE" }.into(),
        Value::Int(i) => i.to_string(),
        Value::Real(r) => stc_syntax::literal::format_real(*r),
        Value::Str(s) => stc_syntax::literal::format_string(&String::from_utf8_lossy(s), false),
        Value::WStr(s) => stc_syntax::literal::format_string(&String::from_utf16_lossy(s), true),
    }
}
