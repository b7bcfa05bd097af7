//! The program's data and its descriptor tables: globals, process-image
//! slots and program instances as C objects, `stc_init_all`, and the
//! tables of `stc_meta.h` (types, variables, configurations, tasks,
//! programs, globals, process-image slots, fault sites) through which the
//! real-time harness and `stc run --backend c` see the program.

use super::*;
use stc_ir::model::{PouKind as ModelPouKind, TypeDesc};

impl Gen<'_> {
    // ----- data and descriptor tables ---------------------------------------

    /// Globals, process-image slots, program instances, the descriptor
    /// tables and `stc_init_all`.
    pub(super) fn data_and_tables(&mut self) -> Result<String, Error> {
        let m = self.m;
        // Process-image slots: the model's, one per direct address used.
        let io: Vec<DirectAddress> = self
            .model
            .model
            .io
            .iter()
            .map(|s| s.address.clone())
            .collect();
        self.f = Func {
            pou: PouId(0),
            depth: 1,
            ..Func::default()
        };
        let mut data = String::new();
        for a in &io {
            let t = self.io_type(a);
            self.define(t);
            let _ = writeln!(
                data,
                "static {} {};",
                names::type_name(m, t),
                names::io_name(a)
            );
        }
        for (gi, g) in m.globals.iter_enumerated() {
            self.define(g.ty);
            if g.location.as_ref().is_some_and(|a| !a.is_incomplete()) {
                // A located global is its process-image slot.
                continue;
            }
            let _ = writeln!(
                data,
                "static {} {};",
                names::type_name(m, g.ty),
                names::global_name(m, gi)
            );
        }
        // Program instances: those of the configurations, then one
        // standalone instance per PROGRAM type.
        let mut instances: Vec<(String, PouId, String)> = Vec::new();
        for (ci, c) in m.configs.iter().enumerate() {
            for (ri, r) in c.resources.iter().enumerate() {
                let ctx = self
                    .contexts
                    .iter()
                    .position(|&x| x == (ci, ri))
                    .map_or(0, |k| k + 1);
                for (pi, inst) in r.programs.iter().enumerate() {
                    let var = format!("prog_{ci}_{ri}_{pi}");
                    let _ = writeln!(data, "static {} {var};", names::pou_type_name(m, inst.pou));
                    instances.push((var, inst.pou, format!("{ctx}U")));
                }
            }
        }
        for (p, pou) in m.pous.iter_enumerated() {
            if pou.kind == PouKind::Program {
                let var = format!("prog_{p}");
                let _ = writeln!(data, "static {} {var};", names::pou_type_name(m, p));
                instances.push((var, p, "0U".into()));
            }
        }
        self.data.insert_str(0, &data);
        // stc_init_all: zero everything, constants, globals, instances.
        let mut init = Vec::new();
        for a in &io {
            let n = names::io_name(a);
            init.push(format!("(void)memset(&{n}, 0, sizeof {n});"));
        }
        for (gi, g) in m.globals.iter_enumerated() {
            if g.location.as_ref().is_some_and(|a| !a.is_incomplete()) {
                continue;
            }
            let n = names::global_name(m, gi);
            init.push(format!("(void)memset(&{n}, 0, sizeof {n});"));
        }
        for (var, _, _) in &instances {
            init.push(format!("(void)memset(&{var}, 0, sizeof {var});"));
        }
        let body_start = self.f.body.len();
        // Located variables' initial values, once per slot (stc_ir).
        for (a, t, init) in m.located_inits() {
            let n = self.io_access(&a, t)?;
            self.init_value(&n, t, init, Some("0U"), 0)?;
        }
        for (gi, g) in m.globals.iter_enumerated() {
            if g.location.as_ref().is_some_and(|a| !a.is_incomplete()) {
                continue;
            }
            let n = global_lvalue(m, gi);
            self.init_value(&n, g.ty, g.init.as_ref(), Some("0U"), 0)?;
        }
        for (var, p, ctx) in &instances {
            self.line(format!("{}(&{var}, {ctx});", names::init_name(m, *p)));
        }
        let inits: Vec<String> = self.f.body.drain(body_start..).collect();
        let decls = std::mem::take(&mut self.f.decls);

        // Descriptor tables.
        let mut t = String::new();
        let mut programs_out = Vec::new();
        let mut configs_out = Vec::new();
        let mut inst_iter = instances.iter();
        for (ci, c) in m.configs.iter().enumerate() {
            let mut res_names = Vec::new();
            for (ri, r) in c.resources.iter().enumerate() {
                let mut tasks = Vec::new();
                for task in &r.tasks {
                    let (single, sty) = match &task.single {
                        Some(d) => {
                            let (ptr, ty) = self.data_ref(d, m.types_bool(), &mut t)?;
                            (ptr, ty)
                        }
                        None => ("NULL".into(), 0),
                    };
                    tasks.push(format!(
                        "{{ {}, {}U, INT64_C({}), {}U, {single}, {sty}U }}",
                        c_str(m.name(task.name)),
                        task.interval.is_some() as u8,
                        task.interval.unwrap_or(0),
                        task.priority
                    ));
                }
                let mut progs = Vec::new();
                for (pi, inst) in r.programs.iter().enumerate() {
                    let Some((var, p, _)) = inst_iter.next() else {
                        return Err(Error::Unsupported("program instances out of order".into()));
                    };
                    let conns = |g: &mut Self,
                                 list: &[(VarId, DataRef)],
                                 tag: &str,
                                 t: &mut String|
                     -> Result<(String, usize), Error> {
                        let mut items = Vec::new();
                        for (v, d) in list {
                            let var_def = m.pous[*p].var(*v);
                            let vty = g.meta_type(var_def.ty)?;
                            let (ptr, dty) = g.data_ref(d, var_def.ty, t)?;
                            items.push(format!(
                                "{{ offsetof({}, {}), {vty}U, {ptr}, {dty}U }}",
                                names::pou_type_name(m, *p),
                                names::var_name(m, *v, var_def)
                            ));
                        }
                        let name = format!("conn_{tag}_{ci}_{ri}_{pi}");
                        if items.is_empty() {
                            return Ok(("NULL".into(), 0));
                        }
                        let _ = writeln!(
                            t,
                            "static const stc_conn {name}[] = {{\n    {}\n}};",
                            items.join(",\n    ")
                        );
                        Ok((name, items.len()))
                    };
                    let (ins, n_in) = conns(self, &inst.inputs, "in", &mut t)?;
                    let (outs, n_out) = conns(self, &inst.outputs, "out", &mut t)?;
                    let ty = self.meta_pou(*p)?;
                    progs.push(format!(
                        "{{ {}, {ty}U, &{var}, W{p}, {}, {ins}, {n_in}U, {outs}, {n_out}U }}",
                        c_str(m.spelled(inst.name, inst.name_span)),
                        inst.task.map_or(-1, |x| x as i64)
                    ));
                }
                let tn = format!("tasks_{ci}_{ri}");
                let pn = format!("progs_{ci}_{ri}");
                if !tasks.is_empty() {
                    let _ = writeln!(
                        t,
                        "static const stc_task {tn}[] = {{\n    {}\n}};",
                        tasks.join(",\n    ")
                    );
                }
                if !progs.is_empty() {
                    let _ = writeln!(
                        t,
                        "static const stc_program {pn}[] = {{\n    {}\n}};",
                        progs.join(",\n    ")
                    );
                }
                res_names.push(format!(
                    "{{ {}, {}, {}U, {}, {}U }}",
                    r.name.map_or("NULL".to_string(), |n| c_str(m.name(n))),
                    if tasks.is_empty() {
                        "NULL".to_string()
                    } else {
                        tn
                    },
                    tasks.len(),
                    if progs.is_empty() {
                        "NULL".to_string()
                    } else {
                        pn
                    },
                    progs.len()
                ));
            }
            let rn = format!("res_{ci}");
            if !res_names.is_empty() {
                let _ = writeln!(
                    t,
                    "static const stc_resource {rn}[] = {{\n    {}\n}};",
                    res_names.join(",\n    ")
                );
            }
            configs_out.push(format!(
                "{{ {}, {}, {}U }}",
                c_str(m.name(c.name)),
                if res_names.is_empty() {
                    "NULL".to_string()
                } else {
                    rn
                },
                res_names.len()
            ));
        }
        for (var, p, _) in inst_iter {
            let ty = self.meta_pou(*p)?;
            let pou = &m.pous[*p];
            programs_out.push(format!(
                "{{ {}, {ty}U, &{var}, W{p}, -1, NULL, 0U, NULL, 0U }}",
                c_str(m.spelled(pou.name, pou.name_span))
            ));
        }
        let mut globals_out = Vec::new();
        for (gi, g) in m.globals.iter_enumerated() {
            let ty = self.meta_type(g.ty)?;
            let config = m.config_of_global(gi).map_or(-1, |c| c as i64);
            globals_out.push(format!(
                "{{ {}, {ty}U, &{}, {config}, {}, {}U, {}U }}",
                c_str(m.spelled(g.name, g.span)),
                global_lvalue(m, gi),
                g.location
                    .as_ref()
                    .map_or("NULL".to_string(), |a| c_str(&a.to_string())),
                g.constant as u8,
                g.retain as u8
            ));
        }
        let mut io_out = Vec::new();
        for a in &io {
            let t = self.io_type(a);
            let ty = self.meta_type(t)?;
            io_out.push(format!(
                "{{ {}, &{}, {ty}U }}",
                c_str(&a.to_string()),
                names::io_name(a)
            ));
        }
        // Program body wrappers (the harness calls `void body(void *)`).
        let mut wrappers = String::new();
        for (p, pou) in m.pous.iter_enumerated() {
            if pou.kind == PouKind::Program {
                let tn = names::pou_type_name(m, p);
                let _ = writeln!(
                    wrappers,
                    "static void W{p}(void *self)\n{{\n    {}(({tn} *)self);\n}}\n",
                    names::body_name(m, p)
                );
            }
        }
        // Types last: everything above may have added to them.
        let types_out = self.meta_types()?;
        // The field's process image arrays (image.rs).
        let slots: Vec<(DirectAddress, TypeId)> =
            io.iter().map(|a| (a.clone(), self.io_type(a))).collect();
        let sites = &mut self.sites;
        let img = crate::image::generate(m, &slots, &mut |a: &DirectAddress| {
            sites.push((a.to_string(), "<process image>".into(), 0, 0));
            (sites.len() - 1) as u32
        })?;
        let sites: Vec<String> = self
            .sites
            .iter()
            .map(|(pou, file, line, col)| {
                format!("{{ {}, {}, {line}U, {col}U }}", c_str(pou), c_str(file))
            })
            .collect();
        let mut out = String::new();
        out.push_str(&wrappers);
        out.push_str(&t);
        let table = |out: &mut String, ty: &str, name: &str, items: &[String]| {
            if items.is_empty() {
                let _ = writeln!(out, "const {ty} {name}[1];");
            } else {
                let _ = writeln!(
                    out,
                    "const {ty} {name}[] = {{\n    {}\n}};",
                    items.join(",\n    ")
                );
            }
            let count = if name == "stc_io" {
                "stc_n_io".to_string()
            } else {
                format!("stc_n_{}", &name[4..])
            };
            let _ = writeln!(out, "const uint32_t {count} = {}U;\n", items.len());
        };
        table(&mut out, "stc_type", "stc_types", &types_out);
        table(&mut out, "stc_config", "stc_configs", &configs_out);
        table(&mut out, "stc_program", "stc_programs", &programs_out);
        table(&mut out, "stc_global", "stc_globals", &globals_out);
        table(&mut out, "stc_io_slot", "stc_io", &io_out);
        table(&mut out, "stc_site", "stc_sites", &sites);
        out.push_str("void stc_init_all(void)\n{\n");
        for d in &decls {
            let _ = writeln!(out, "    {d}");
        }
        for l in &init {
            let _ = writeln!(out, "    {l}");
        }
        for l in &self.const_init {
            let _ = writeln!(out, "    {l}");
        }
        for l in &inits {
            out.push_str(l);
            out.push('\n');
        }
        for l in &img.init {
            out.push_str(l);
            out.push('\n');
        }
        out.push_str("}\n");
        out.push_str("\n/* ---- process image ---- */\n");
        out.push_str(&img.source);
        self.image_header = img.header;
        Ok(out)
    }

    /// A configuration data reference: the address of its object and its
    /// descriptor type. Constants get a static object of type `ty`.
    pub(super) fn data_ref(
        &mut self,
        d: &DataRef,
        ty: TypeId,
        t: &mut String,
    ) -> Result<(String, u32), Error> {
        let m = self.m;
        Ok(match d {
            DataRef::Global(g) => {
                let gd = &m.globals[*g];
                (format!("&{}", global_lvalue(m, *g)), self.meta_type(gd.ty)?)
            }
            DataRef::Direct(a) => {
                let t = self.io_type(a);
                (format!("&{}", names::io_name(a)), self.meta_type(t)?)
            }
            DataRef::Const(v) => {
                let e = self.scalar(ty).ok_or_else(|| {
                    Error::Unsupported("a constant connection of a non-elementary type".into())
                })?;
                if matches!(e, ElemType::String | ElemType::Wstring) {
                    return Err(Error::Unsupported("a constant string connection".into()));
                }
                let n = format!("cconst_{}", self.f.next_temp);
                self.f.next_temp += 1;
                let _ = writeln!(t, "static {} {n} = {};", elem_c(e), literal(e, v));
                (format!("&{n}"), self.meta_type(ty)?)
            }
        })
    }

    /// The index of a type's descriptor: the program model's numbering
    /// (`stc_ir::model`), which the VM's image has too.
    pub(super) fn meta_type(&self, t: TypeId) -> Result<u32, Error> {
        self.model.type_refs.get(&t).copied().ok_or_else(|| {
            Error::Unsupported("internal error: a type the program model does not have".into())
        })
    }

    /// The index of the descriptor of POU `p`'s instances.
    pub(super) fn meta_pou(&self, p: PouId) -> Result<u32, Error> {
        self.model
            .model
            .pous
            .get(p.index())
            .map(|d| d.instance_type)
            .ok_or_else(|| Error::Unsupported("internal error: a POU without a model".into()))
    }

    /// The `stc_types` table: one row per type of the program model, in
    /// its order, with the C sizes and offsets.
    pub(super) fn meta_types(&mut self) -> Result<Vec<String>, Error> {
        let mut rows = Vec::new();
        for i in 0..self.model.model.types.len() {
            let row = self.meta_desc(i as u32)?;
            rows.push(row);
        }
        Ok(rows)
    }

    fn meta_desc(&mut self, i: u32) -> Result<String, Error> {
        let m = self.m;
        let row = |kind: &str,
                   elem: u32,
                   wide: u8,
                   cap: u32,
                   name: String,
                   count: usize,
                   values: String,
                   members: String,
                   dims: String,
                   et: u32,
                   stride: String,
                   size: String,
                   lo: i128,
                   hi: i128| {
            format!(
                "{{ {kind}, {elem}U, {wide}U, {cap}U, {name}, {count}U, {values}, {members}, {dims}, {et}U, {stride}, {size}, INT64_C({lo}), INT64_C({hi}) }}"
            )
        };
        let desc = self.model.model.types[i as usize].clone();
        let cname = match self.model.type_ids.get(i as usize).copied().flatten() {
            Some(t) if matches!(m.types.kind(t), TypeKind::Error | TypeKind::Void) => None,
            Some(t) => {
                self.define(t);
                Some((t, names::type_name(m, t)))
            }
            None => None,
        };
        let size = |cname: &Option<(TypeId, String)>| match cname {
            Some((_, tn)) => format!("sizeof({tn})"),
            None => "1U".to_string(),
        };
        Ok(match desc {
            TypeDesc::Instance { pou } => {
                let p = PouId(pou);
                let d = self.model.model.pous[p.index()].clone();
                // A function has no instance, and a POU the program never
                // uses has no C type: their descriptors keep the model's
                // variables with no place.
                let generated = d.kind != ModelPouKind::Function && self.defined_pous.contains(&p);
                let tn = names::pou_type_name(m, p);
                let mut members = Vec::new();
                for (vi, (v, var)) in d.vars.iter().zip(&m.pous[p].vars).enumerate() {
                    let off = if v.in_frame || !generated {
                        "0U".to_string()
                    } else {
                        format!(
                            "offsetof({tn}, {})",
                            names::var_name(m, VarId::new(vi), var)
                        )
                    };
                    members.push(format!(
                        "{{ {}, {}U, {off}, {}U, {}U, {}U, {}U, {}U, {} }}",
                        c_str(&v.name),
                        v.ty,
                        v.kind.code(),
                        v.in_frame as u8,
                        v.is_ref as u8,
                        v.constant as u8,
                        v.retain as u8,
                        v.location
                            .as_ref()
                            .map_or("NULL".to_string(), |a| c_str(&a.to_string()))
                    ));
                }
                let mn = self.member_table(i, &members);
                row(
                    "STC_TK_INSTANCE",
                    u32::from(d.kind.code()),
                    0,
                    0,
                    c_str(&d.name),
                    members.len(),
                    "NULL".into(),
                    mn,
                    "NULL".into(),
                    0,
                    "0U".into(),
                    if generated {
                        format!("sizeof({tn})")
                    } else {
                        "0U".into()
                    },
                    0,
                    0,
                )
            }
            TypeDesc::Scalar(e) => row(
                "STC_TK_SCALAR",
                elem_code(e),
                0,
                0,
                "NULL".into(),
                0,
                "NULL".into(),
                "NULL".into(),
                "NULL".into(),
                0,
                "0U".into(),
                size(&cname),
                0,
                0,
            ),
            TypeDesc::Subrange { base, lo, hi } => row(
                "STC_TK_SUBRANGE",
                elem_code(base),
                0,
                0,
                "NULL".into(),
                0,
                "NULL".into(),
                "NULL".into(),
                "NULL".into(),
                0,
                "0U".into(),
                size(&cname),
                lo,
                hi,
            ),
            TypeDesc::String { wide, cap } => row(
                "STC_TK_STRING",
                elem_code(if wide {
                    ElemType::Wstring
                } else {
                    ElemType::String
                }),
                wide as u8,
                cap,
                "NULL".into(),
                0,
                "NULL".into(),
                "NULL".into(),
                "NULL".into(),
                0,
                "0U".into(),
                size(&cname),
                0,
                0,
            ),
            TypeDesc::Enum { name, base, values } => {
                let vn = format!("meta_values_{i}");
                let list: Vec<String> = values
                    .iter()
                    .map(|(n, v)| format!("{{ {}, INT64_C({v}) }}", c_str(n)))
                    .collect();
                let _ = writeln!(
                    self.meta_extra,
                    "static const stc_enum_value {vn}[{}] = {{\n    {}\n}};",
                    list.len().max(1),
                    if list.is_empty() {
                        "{ NULL, 0 }".to_string()
                    } else {
                        list.join(",\n    ")
                    }
                );
                row(
                    "STC_TK_ENUM",
                    elem_code(base),
                    0,
                    0,
                    c_str(&name),
                    values.len(),
                    vn,
                    "NULL".into(),
                    "NULL".into(),
                    0,
                    "0U".into(),
                    size(&cname),
                    0,
                    0,
                )
            }
            TypeDesc::Array { elem, dims, .. } => {
                let dn = format!("meta_dims_{i}");
                let list: Vec<String> = dims
                    .iter()
                    .map(|(l, h)| format!("{{ INT64_C({l}), INT64_C({h}) }}"))
                    .collect();
                let _ = writeln!(
                    self.meta_extra,
                    "static const stc_dim {dn}[{}] = {{ {} }};",
                    list.len().max(1),
                    list.join(", ")
                );
                let stride = match cname.as_ref().map(|(t, _)| m.types.kind(*t)) {
                    Some(TypeKind::Array { elem, .. }) => {
                        format!("sizeof({})", names::type_name(m, *elem))
                    }
                    _ => "0U".into(),
                };
                row(
                    "STC_TK_ARRAY",
                    0,
                    0,
                    0,
                    "NULL".into(),
                    dims.len(),
                    "NULL".into(),
                    "NULL".into(),
                    dn,
                    elem,
                    stride,
                    size(&cname),
                    0,
                    0,
                )
            }
            TypeDesc::Struct { name, fields } => {
                let tn = cname.as_ref().map_or(String::new(), |(_, tn)| tn.clone());
                let mut members = Vec::new();
                for f in &fields {
                    members.push(format!(
                        "{{ {}, {}U, offsetof({tn}, m_{}), STC_VK_FIELD, 0U, 0U, 0U, 0U, NULL }}",
                        c_str(&f.name),
                        f.ty,
                        names::ident(&f.name)
                    ));
                }
                let mn = self.member_table(i, &members);
                row(
                    "STC_TK_STRUCT",
                    0,
                    0,
                    0,
                    name.as_deref().map_or("NULL".to_string(), c_str),
                    fields.len(),
                    "NULL".into(),
                    mn,
                    "NULL".into(),
                    0,
                    "0U".into(),
                    size(&cname),
                    0,
                    0,
                )
            }
        })
    }

    /// Writes the member table `meta_members_<i>` of a struct or instance
    /// type (one all-NULL entry when it has none: C has no empty arrays)
    /// and returns its name.
    pub(super) fn member_table(&mut self, i: u32, members: &[String]) -> String {
        let mn = format!("meta_members_{i}");
        let _ = writeln!(
            self.meta_extra,
            "static const stc_member {mn}[{}] = {{\n    {}\n}};",
            members.len().max(1),
            if members.is_empty() {
                "{ NULL, 0U, 0U, 0U, 0U, 0U, 0U, 0U, NULL }".to_string()
            } else {
                members.join(",\n    ")
            }
        );
        mn
    }
}
