//! Configurations, resources, tasks and program instances.

use stc_diagnostics::{Code, Diagnostic};
use stc_syntax::ast::{
    Configuration, ExprId, ExprKind, Item, PouKind, ProgramConn, Resource, VarKind,
};
use stc_syntax::token::ElemType;
use stc_values::Value;

use crate::analyzer::{GlobalName, Scope, Sema};
use crate::types::TypeId;
use crate::{
    ConfigDef, DataRef, GlobalId, GlobalOwner, ProgramInstDef, Res, ResourceDef, Section, TaskDef,
};

impl<'a> Sema<'a> {
    pub(crate) fn collect_configs(&mut self, items: &[usize]) {
        let ast = self.ast;
        for &i in items {
            if let Item::Configuration(c) = &ast.items[i] {
                self.configuration(c);
            }
        }
    }

    fn add_scoped_globals(
        &mut self,
        blocks: &'a [stc_syntax::ast::VarBlock],
        owner: GlobalOwner,
    ) -> Vec<GlobalId> {
        let mut ids = Vec::new();
        for b in blocks {
            if b.kind == VarKind::Global {
                ids.extend(self.add_globals(b, owner));
            }
        }
        // Duplicates within one scope.
        for (k, &g) in ids.iter().enumerate() {
            let name = self.globals[g.0 as usize].var.name;
            if let Some(&first) = ids[..k]
                .iter()
                .find(|&&h| self.globals[h.0 as usize].var.name == name)
            {
                let span = self.globals[g.0 as usize].var.span;
                let prev = self.globals[first.0 as usize].var.span;
                let shown = self.sym_name(name);
                self.emit(
                    Diagnostic::new(
                        Code::E0105,
                        span,
                        format!("global `{shown}` is declared twice"),
                    )
                    .with_secondary(prev, "first declared here"),
                );
            }
        }
        for &g in &ids {
            self.resolve_global(g);
        }
        ids
    }

    fn configuration(&mut self, c: &'a Configuration) {
        let ci = self.configs.len();
        self.configs.push(ConfigDef {
            name: c.name.sym,
            span: c.span,
            globals: Vec::new(),
            resources: Vec::new(),
        });
        let globals = self.add_scoped_globals(&c.var_blocks, GlobalOwner::Config(ci));
        self.configs[ci].globals = globals;
        for (ri, r) in c.resources.iter().enumerate() {
            let def = self.resource(ci, ri, r);
            self.configs[ci].resources.push(def);
        }
    }

    fn resource(&mut self, ci: usize, ri: usize, r: &'a Resource) -> ResourceDef {
        // Push first, so names in this resource resolve against its globals.
        let globals = self.add_scoped_globals(&r.var_blocks, GlobalOwner::Resource(ci, ri));
        let scope = Scope::Config(ci, Some(ri));
        let mut tasks: Vec<TaskDef> = Vec::new();
        for t in &r.tasks {
            if let Some(prev) = tasks.iter().find(|x| x.name == t.name.sym) {
                let shown = self.spelled(t.name.sym, t.name.span);
                self.emit(
                    Diagnostic::new(
                        Code::E0105,
                        t.name.span,
                        format!("task `{shown}` is declared twice"),
                    )
                    .with_secondary(prev.span, "first declared here"),
                );
                continue;
            }
            let single = t.single.and_then(|e| {
                let bool_ty = self.types.elem(ElemType::Bool);
                let ty = self.check_expr(e, Some(bool_ty), scope);
                let span = self.ast.expr(e).span;
                let r = self.data_ref(e);
                // A global, a direct variable or a constant (the
                // standard's data_source; a constant TRUE gives the task
                // one rising edge, at start).
                if ty != TypeId::ERROR && !self.types.is_bool(ty) {
                    let msg = format!("SINGLE needs a BOOL, not {}", self.tname(ty));
                    self.emit(Diagnostic::new(Code::E0804, span, msg));
                    return None;
                }
                if ty != TypeId::ERROR
                    && !matches!(
                        r,
                        Some(DataRef::Global(_) | DataRef::Direct(_) | DataRef::Const(_))
                    )
                {
                    let msg = "SINGLE needs a global BOOL variable, a direct address or a constant"
                        .to_string();
                    self.emit(Diagnostic::new(Code::E0804, span, msg));
                    return None;
                }
                r
            });
            let interval = t.interval.and_then(|e| {
                let time = self.types.elem(ElemType::Time);
                let ty = self.check_expr(e, Some(time), scope);
                let span = self.ast.expr(e).span;
                if ty == TypeId::ERROR {
                    return None;
                }
                match (self.types.scalar(ty), self.consts.get(&e)) {
                    (Some(ElemType::Time | ElemType::Ltime), Some(Value::Int(ns))) if *ns > 0 => {
                        Some(*ns as i64)
                    }
                    (Some(ElemType::Time | ElemType::Ltime), Some(_)) => {
                        self.error(
                            Code::E0801,
                            span,
                            "a task INTERVAL must be greater than zero",
                        );
                        None
                    }
                    (Some(ElemType::Time | ElemType::Ltime), None) => {
                        self.error(
                            Code::E0801,
                            span,
                            "a task INTERVAL must be a constant duration",
                        );
                        None
                    }
                    _ => {
                        let msg = format!(
                            "a task INTERVAL must be a TIME, such as T#10ms, not {}",
                            self.tname(ty)
                        );
                        self.emit(Diagnostic::new(Code::E0801, span, msg));
                        None
                    }
                }
            });
            let priority = match t.priority {
                Some(e) => {
                    let ty = self.check_expr(e, None, scope);
                    let span = self.ast.expr(e).span;
                    match self.consts.get(&e) {
                        Some(Value::Int(p))
                            if self.types.is_integer(ty) && (0..=u32::MAX as i128).contains(p) =>
                        {
                            *p as u32
                        }
                        _ if ty == TypeId::ERROR => 0,
                        _ => {
                            let msg = format!(
                                "a task PRIORITY must be a non-negative integer constant, not {}",
                                self.tname(ty)
                            );
                            self.emit(Diagnostic::new(Code::E0802, span, msg));
                            0
                        }
                    }
                }
                None => 0,
            };
            tasks.push(TaskDef {
                name: t.name.sym,
                name_span: t.name.span,
                span: t.span,
                single,
                interval,
                priority,
            });
        }
        let mut programs: Vec<ProgramInstDef> = Vec::new();
        for inst in &r.programs {
            if let Some(prev) = programs.iter().find(|x| x.name == inst.name.sym) {
                let shown = self.spelled(inst.name.sym, inst.name.span);
                self.emit(
                    Diagnostic::new(
                        Code::E0105,
                        inst.name.span,
                        format!("program instance `{shown}` is declared twice"),
                    )
                    .with_secondary(prev.span, "first declared here"),
                );
                continue;
            }
            let task = match inst.task {
                Some(t) => match tasks.iter().position(|x| x.name == t.sym) {
                    Some(i) => Some(i),
                    None => {
                        let shown = self.spelled(t.sym, t.span);
                        let names: Vec<String> =
                            tasks.iter().map(|x| self.sym_name(x.name)).collect();
                        let mut d =
                            Diagnostic::new(Code::E0106, t.span, format!("unknown task `{shown}`"))
                                .with_label("not a task of this resource");
                        if let Some(s) = self.did_you_mean(&shown, names.iter().map(|s| s.as_str()))
                        {
                            d = d.with_help(format!("did you mean `{s}`?"));
                        }
                        self.emit(d);
                        None
                    }
                },
                None => None,
            };
            let pou = match self.global_name(inst.type_name) {
                Some(GlobalName::Pou(p)) if self.pous[p.0 as usize].kind == PouKind::Program => p,
                other => {
                    let shown = self.spelled(inst.type_name.sym, inst.type_name.span);
                    let msg = match other {
                        Some(_) => format!("`{shown}` is not a PROGRAM"),
                        None => format!("unknown program type `{shown}`"),
                    };
                    let mut d = Diagnostic::new(Code::E0107, inst.type_name.span, msg);
                    let names: Vec<String> = self
                        .pous
                        .iter()
                        .filter(|p| p.kind == PouKind::Program)
                        .map(|p| self.sym_name(p.name))
                        .collect();
                    if let Some(s) = self.did_you_mean(&shown, names.iter().map(|s| s.as_str())) {
                        d = d.with_help(format!("did you mean `{s}`?"));
                    }
                    self.emit(d);
                    for c in &inst.conns {
                        if let ProgramConn::Input { value, .. } = c {
                            self.check_expr(*value, Some(TypeId::ERROR), scope);
                        }
                    }
                    continue;
                }
            };
            self.resolve_pou(pou);
            let mut def = ProgramInstDef {
                name: inst.name.sym,
                span: inst.span,
                name_span: inst.name.span,
                pou,
                task,
                inputs: Vec::new(),
                outputs: Vec::new(),
            };
            for c in &inst.conns {
                match c {
                    ProgramConn::Input { name, value } => {
                        let Some((v, pty)) =
                            self.program_param(pou, *name, &[Section::Input, Section::InOut])
                        else {
                            self.check_expr(*value, Some(TypeId::ERROR), scope);
                            continue;
                        };
                        let vt = self.check_expr(*value, Some(pty), scope);
                        if vt == TypeId::ERROR || pty == TypeId::ERROR {
                            continue;
                        }
                        if !self.conn_compatible(vt, pty) {
                            let span = self.ast.expr(*value).span;
                            let msg = format!(
                                "the program input needs {}, but this is {}",
                                self.tname(pty),
                                self.tname(vt)
                            );
                            self.emit(Diagnostic::new(Code::E0803, span, msg));
                            continue;
                        }
                        if vt != pty {
                            self.coercions.insert(*value, pty);
                        }
                        match self.data_ref(*value) {
                            Some(r) => def.inputs.push((v, r)),
                            None => {
                                let span = self.ast.expr(*value).span;
                                self.emit(Diagnostic::new(Code::E0803, span, "a program input is connected to a constant, a global variable or a direct address"));
                            }
                        }
                    }
                    ProgramConn::Output { name, target } => {
                        let Some((v, pty)) = self.program_param(pou, *name, &[Section::Output])
                        else {
                            self.check_expr(*target, Some(TypeId::ERROR), scope);
                            continue;
                        };
                        let tt = self.check_expr(*target, None, scope);
                        if tt == TypeId::ERROR || pty == TypeId::ERROR {
                            continue;
                        }
                        match self.data_ref(*target) {
                            Some(r @ (DataRef::Global(_) | DataRef::Direct(_))) => {
                                if !self.conn_compatible(pty, tt) {
                                    let span = self.ast.expr(*target).span;
                                    let msg = format!(
                                        "the program output is {}, which cannot be stored in {}",
                                        self.tname(pty),
                                        self.tname(tt)
                                    );
                                    self.emit(Diagnostic::new(Code::E0803, span, msg));
                                } else {
                                    def.outputs.push((v, r));
                                }
                            }
                            _ => {
                                let span = self.ast.expr(*target).span;
                                self.emit(Diagnostic::new(Code::E0803, span, "a program output is connected to a global variable or a direct address"));
                            }
                        }
                    }
                    ProgramConn::FbTask { .. } => {}
                }
            }
            programs.push(def);
        }
        ResourceDef {
            name: r.name.map(|n| n.sym),
            span: r.span,
            globals,
            tasks,
            programs,
        }
    }

    fn conn_compatible(&self, from: TypeId, to: TypeId) -> bool {
        matches!(
            self.types.compat(from, to, self.opts.iec2),
            crate::Compat::Same | crate::Compat::Widen
        )
    }

    /// The input or output of a program named by a connection.
    fn program_param(
        &mut self,
        pou: crate::PouId,
        name: ExprId,
        sections: &[Section],
    ) -> Option<(crate::VarId, TypeId)> {
        let span = self.ast.expr(name).span;
        let ExprKind::Name(id) = &self.ast.expr(name).kind else {
            self.error(
                Code::E0803,
                span,
                "a connection names an input or output of the program",
            );
            return None;
        };
        let p = &self.pous[pou.0 as usize];
        let pname = self.sym_name(p.name);
        match p.lookup(id.sym) {
            Some(v) if sections.contains(&p.var(v).section) => Some((v, p.var(v).ty)),
            found => {
                let shown = self.spelled(id.sym, id.span);
                let what = if sections.contains(&Section::Output) {
                    "an output"
                } else {
                    "an input"
                };
                let msg = if found.is_some() {
                    format!("`{shown}` is not {what} of `{pname}`")
                } else {
                    format!("`{pname}` has no {} `{shown}`", &what[3..])
                };
                self.error(Code::E0803, id.span, msg);
                None
            }
        }
    }

    /// What a configuration expression refers to.
    fn data_ref(&self, e: ExprId) -> Option<DataRef> {
        match &self.ast.expr(e).kind {
            ExprKind::Address(a) => Some(DataRef::Direct((**a).clone())),
            ExprKind::Paren(i) => self.data_ref(*i),
            _ => match (self.resolutions.get(&e), self.consts.get(&e)) {
                (Some(Res::Global(g)), _) if !self.globals[g.0 as usize].var.constant => {
                    Some(DataRef::Global(*g))
                }
                (_, Some(v)) => Some(DataRef::Const(v.clone())),
                _ => None,
            },
        }
    }
}
