//! The initial values of variables and instances: the statements of each
//! POU's init function (`I<k>_...`), nested instances and the binding of
//! VAR_EXTERNALs per configuration.

use super::*;

impl Gen<'_> {
    // ----- initial values ---------------------------------------------------

    /// Statements setting `lv` (of type `ty`) to its initial value (`init`,
    /// else the type's default); `ctx` binds VAR_EXTERNALs of instances.
    pub(super) fn init_value(
        &mut self,
        lv: &str,
        ty: TypeId,
        init: Option<&InitValue>,
        ctx: Option<&str>,
        depth: u32,
    ) -> Result<(), Error> {
        let m = self.m;
        self.define(ty);
        match m.types.kind(ty).clone() {
            TypeKind::Ref(_) | TypeKind::Ptr(_) => self.line(format!("{lv} = NULL;")),
            TypeKind::Elem(_) | TypeKind::Subrange { .. } | TypeKind::Enum { .. } => {
                let e = self.scalar(ty).unwrap_or(ElemType::Int);
                let v = match init {
                    Some(InitValue::Scalar(v)) => v.clone(),
                    _ => match m.types.kind(ty) {
                        TypeKind::Subrange { lo, .. } => Value::Int(*lo),
                        TypeKind::Enum { values, .. } => {
                            Value::Int(values.first().map_or(0, |v| v.value))
                        }
                        _ => stc_values::default_value(e),
                    },
                };
                let l = literal(e, &v);
                self.line(format!("{lv} = {l};"));
            }
            TypeKind::String { wide, len } => {
                let v = match init {
                    Some(InitValue::Scalar(v)) => v.clone(),
                    _ => {
                        if wide {
                            Value::WStr(Vec::new())
                        } else {
                            Value::Str(Vec::new())
                        }
                    }
                };
                let v = match (wide, v) {
                    (false, Value::WStr(_)) | (true, Value::Str(_)) => {
                        return Err(Error::Unsupported(
                            "a string initial value of the other width".into(),
                        ))
                    }
                    (_, v) => v,
                };
                let k = self.string_const(&v)?;
                if wide {
                    self.line(format!("stc_wstr_copy({lv}.s, {len}U, {k});"));
                } else {
                    self.line(format!("stc_str_copy({lv}.s, {len}U, {k});"));
                }
            }
            TypeKind::Array { dims, elem } => {
                let n = array_count(&dims);
                let list = match init {
                    Some(InitValue::Array(l)) => l.clone(),
                    _ => Vec::new(),
                };
                if list.iter().all(|v| v.is_none()) {
                    let k = format!("k{depth}");
                    if !self.f.decls.contains(&format!("uint32_t {k};")) {
                        self.f.decls.push(format!("uint32_t {k};"));
                    }
                    self.open(format!("for ({k} = 0U; {k} < {n}U; {k}++) {{"));
                    self.init_value(&format!("{lv}.a[{k}]"), elem, None, ctx, depth + 1)?;
                    self.close("}");
                } else {
                    for i in 0..n {
                        let v = list.get(i as usize).and_then(|v| v.as_ref());
                        self.init_value(&format!("{lv}.a[{i}]"), elem, v, ctx, depth + 1)?;
                    }
                }
            }
            TypeKind::Struct { fields } => {
                for f in &fields {
                    let given = match init {
                        Some(InitValue::Struct(l)) => {
                            l.iter().find(|(n, _)| *n == f.name).map(|(_, v)| v.clone())
                        }
                        _ => None,
                    };
                    let v = given.or_else(|| f.init.clone());
                    let flv = format!("{lv}.m_{}", names::ident(m.spelled(f.name, f.span)));
                    self.init_value(&flv, f.ty, v.as_ref(), ctx, depth + 1)?;
                }
            }
            TypeKind::Fb(p) | TypeKind::Program(p) => {
                let c = ctx.unwrap_or("0U");
                self.line(format!("{}(&{lv}, {c});", names::init_name(m, p)));
                if let Some(InitValue::Struct(list)) = init {
                    let pou = &m.pous[p];
                    for (n, v) in list {
                        if let Some((i, var)) =
                            pou.vars.iter_enumerated().find(|(_, x)| x.name == *n)
                        {
                            let vlv = format!("{lv}.{}", names::var_name(m, i, var));
                            self.init_value(&vlv, var.ty, Some(v), ctx, depth + 1)?;
                        }
                    }
                }
            }
            TypeKind::Error | TypeKind::Void => {}
        }
        Ok(())
    }

    /// The initialiser of an FB or program instance: every variable to its
    /// initial value, nested instances, located variables bound to their
    /// process-image slots and VAR_EXTERNALs to the globals of `ctx`.
    pub(super) fn init_fn(&mut self, p: PouId) -> Result<(), Error> {
        let m = self.m;
        let pou = &m.pous[p];
        self.f = Func {
            pou: p,
            function: false,
            depth: 1,
            ..Func::default()
        };
        self.line("(void)ctx;".into());
        for (i, v) in pou.vars.iter_enumerated() {
            if v.storage == Storage::Frame {
                continue;
            }
            let name = names::var_name(m, i, v);
            if v.storage == Storage::Ref {
                if let Some(a) = v.location.as_ref().filter(|a| !a.is_incomplete()) {
                    let slot =
                        self.io_access(a, v.ty)
                            .map_err(|e| match (e, (self.locate)(v.span)) {
                                (Error::Unsupported(w), Some((f, l, c))) => Error::At(f, l, c, w),
                                (e, _) => e,
                            })?;
                    self.line(format!("self->{name} = &{slot};"));
                } else if v.section == Section::External {
                    let mut first = true;
                    for (k, &(c, r)) in self.contexts.clone().iter().enumerate() {
                        // (A context whose global has another type does not run this
                        // POU: sema checks where it runs.)
                        if let Some(g) = m
                            .bind_global(v.name, v.ty, Some((c, r)))
                            .filter(|&g| m.same_type(m.globals[g].ty, v.ty))
                        {
                            let kw = if first { "if" } else { "} else if" };
                            if !first {
                                self.f.depth = self.f.depth.saturating_sub(1);
                            }
                            self.open(format!("{kw} (ctx == {}U) {{", k + 1));
                            self.line(format!("self->{name} = &{};", global_lvalue(m, g)));
                            first = false;
                        }
                    }
                    let top = m.bind_global(v.name, v.ty, None);
                    match (first, top) {
                        (true, Some(g)) => {
                            self.line(format!("self->{name} = &{};", global_lvalue(m, g)))
                        }
                        (true, None) => {
                            let cell = self.private_external(p, i, v.ty)?;
                            self.line(format!("self->{name} = &{cell};"));
                        }
                        (false, Some(g)) => {
                            self.f.depth = self.f.depth.saturating_sub(1);
                            self.open("} else {".into());
                            self.line(format!("self->{name} = &{};", global_lvalue(m, g)));
                            self.close("}");
                        }
                        (false, None) => {
                            self.f.depth = self.f.depth.saturating_sub(1);
                            self.open("} else {".into());
                            let cell = self.private_external(p, i, v.ty)?;
                            self.line(format!("self->{name} = &{cell};"));
                            self.close("}");
                        }
                    }
                } else {
                    self.line(format!("self->{name} = NULL;"));
                }
                continue;
            }
            self.init_value(
                &format!("self->{name}"),
                v.ty,
                v.init.as_ref(),
                Some("ctx"),
                0,
            )?;
        }
        let mut out = format!(
            "static void {}({} *const self, uint32_t ctx)\n{{\n",
            names::init_name(m, p),
            names::pou_type_name(m, p)
        );
        for d in &self.f.decls {
            let _ = writeln!(out, "    {d}");
        }
        // An instance with nothing to set (an empty FB) still takes it.
        if !self.init_uses_self(p) {
            out.push_str("    (void)self;\n");
        }
        self.finish_function(out);
        Ok(())
    }
}
