//! The descriptor tables of a loaded library (`stc_meta.h`), read into the
//! runtime's program model.
//!
//! The `#[repr(C)]` structs below mirror `stc_meta.h` field for field; the
//! C back end writes the tables from the same IR the VM compiles, so the
//! model read here has the VM's names, types and structure, with the C
//! program's offsets and the addresses of [`crate::memory`].

use std::ffi::{c_char, c_void, CStr};

use stc_ir::model::{
    ConfigDesc, FieldDesc, GlobalDesc, IoSlot, Model, PouDesc, PouKind, ProgramInst, ResourceDesc,
    Source, TaskDesc, TypeDesc, TypeDescKind as K, TypeRef, VarDesc, VarKind,
};
use stc_syntax::literal::{parse_address, DirectAddress};
use stc_syntax::token::ElemType;

use crate::memory::{RegionBuilder, Regions};
use crate::Error;

#[repr(C)]
struct CEnumValue {
    name: *const c_char,
    value: i64,
}

#[repr(C)]
struct CDim {
    lo: i64,
    hi: i64,
}

#[repr(C)]
struct CMember {
    name: *const c_char,
    ty: u32,
    offset: usize,
    kind: u8,
    in_frame: u8,
    is_ref: u8,
    constant: u8,
    retain: u8,
    location: *const c_char,
}

#[repr(C)]
struct CType {
    kind: u8,
    elem: u8,
    wide: u8,
    cap: u32,
    name: *const c_char,
    count: u32,
    values: *const CEnumValue,
    members: *const CMember,
    dims: *const CDim,
    elem_type: u32,
    stride: usize,
    size: usize,
    lo: i64,
    hi: i64,
}

#[repr(C)]
struct CConn {
    inst_offset: usize,
    ty: u32,
    data: *mut c_void,
    data_type: u32,
}

pub(crate) type Body = unsafe extern "C" fn(*mut c_void);

#[repr(C)]
struct CProgram {
    name: *const c_char,
    ty: u32,
    data: *mut c_void,
    body: Option<Body>,
    task: i32,
    inputs: *const CConn,
    n_inputs: u32,
    outputs: *const CConn,
    n_outputs: u32,
}

#[repr(C)]
struct CTask {
    name: *const c_char,
    has_interval: u8,
    interval_ns: i64,
    priority: u32,
    single: *mut c_void,
    single_type: u32,
}

#[repr(C)]
struct CResource {
    name: *const c_char,
    tasks: *const CTask,
    n_tasks: u32,
    programs: *const CProgram,
    n_programs: u32,
}

#[repr(C)]
struct CConfig {
    name: *const c_char,
    resources: *const CResource,
    n_resources: u32,
}

#[repr(C)]
struct CGlobal {
    name: *const c_char,
    ty: u32,
    data: *mut c_void,
    config: i32,
    location: *const c_char,
    constant: u8,
    retain: u8,
}

#[repr(C)]
struct CIoSlot {
    address: *const c_char,
    data: *mut c_void,
    ty: u32,
}

#[repr(C)]
struct CSite {
    pou: *const c_char,
    file: *const c_char,
    line: u32,
    col: u32,
}

/// The tables of `stc_meta.h`, as slices of the library's memory.
pub(crate) struct Tables {
    types: &'static [CType],
    configs: &'static [CConfig],
    programs: &'static [CProgram],
    globals: &'static [CGlobal],
    io: &'static [CIoSlot],
    sites: &'static [CSite],
}

/// The model of a loaded program.
pub(crate) struct Loaded {
    pub model: Model,
    pub regions: Regions,
    pub bodies: Vec<(u32, Body, *mut c_void)>,
}

/// A table of `n` entries at `p` (empty for a null pointer).
///
/// # Safety
/// `p` points to `n` valid entries that live as long as the library (the
/// `'static` here is the library's lifetime: the engine keeps it loaded
/// while any of this is used).
unsafe fn table<'a, T>(p: *const T, n: u32) -> &'a [T] {
    if p.is_null() || n == 0 {
        &[]
    } else {
        std::slice::from_raw_parts(p, n as usize)
    }
}

/// # Safety
/// `p` is null or a NUL-terminated string of the library.
unsafe fn text(p: *const c_char) -> Option<String> {
    (!p.is_null()).then(|| CStr::from_ptr(p).to_string_lossy().into_owned())
}

impl Tables {
    /// Reads the tables through `sym` (the address of a symbol).
    ///
    /// # Safety
    /// `sym` gives the addresses of the library's symbols, which have the
    /// types stc_meta.h declares.
    pub(crate) unsafe fn read(
        sym: &dyn Fn(&str) -> Result<*mut c_void, Error>,
    ) -> Result<Tables, Error> {
        let count = |name: &str| -> Result<u32, Error> { Ok(*sym(name)?.cast::<u32>()) };
        Ok(Tables {
            types: table(sym("stc_types")?.cast(), count("stc_n_types")?),
            configs: table(sym("stc_configs")?.cast(), count("stc_n_configs")?),
            programs: table(sym("stc_programs")?.cast(), count("stc_n_programs")?),
            globals: table(sym("stc_globals")?.cast(), count("stc_n_globals")?),
            io: table(sym("stc_io")?.cast(), count("stc_n_io")?),
            sites: table(sym("stc_sites")?.cast(), count("stc_n_sites")?),
        })
    }

    /// Where each fault site is: (POU, file, line, column).
    pub(crate) fn sites(&self) -> Vec<(String, String, u32, u32)> {
        self.sites
            .iter()
            .map(|s| {
                // SAFETY: the strings of stc_sites are the library's.
                let (pou, file) = unsafe { (text(s.pou), text(s.file)) };
                (
                    pou.unwrap_or_else(|| "?".into()),
                    file.unwrap_or_else(|| "?".into()),
                    s.line,
                    s.col,
                )
            })
            .collect()
    }

    fn size_of(&self, ty: u32) -> usize {
        self.types.get(ty as usize).map_or(0, |t| t.size)
    }

    /// The program model, its memory regions and its program bodies.
    ///
    /// # Safety
    /// The tables are the library's, as [`Tables::read`] found them.
    pub(crate) unsafe fn model(&self) -> Result<Loaded, Error> {
        let bad =
            |what: &str| Error::Build(format!("the library's tables are inconsistent: {what}"));

        // Every object the model names, then the address space.
        let mut rb = RegionBuilder::default();
        for g in self.globals {
            rb.add(g.data, self.size_of(g.ty), g.constant == 0);
        }
        for s in self.io {
            rb.add(s.data, self.size_of(s.ty), true);
        }
        let mut all_programs: Vec<&CProgram> = self.programs.iter().collect();
        for c in self.configs {
            for r in table(c.resources, c.n_resources) {
                for t in table(r.tasks, r.n_tasks) {
                    rb.add(t.single, self.size_of(t.single_type), true);
                }
                all_programs.extend(table(r.programs, r.n_programs));
            }
        }
        for p in &all_programs {
            rb.add(p.data, self.size_of(p.ty), true);
            for c in table(p.inputs, p.n_inputs)
                .iter()
                .chain(table(p.outputs, p.n_outputs))
            {
                rb.add(c.data, self.size_of(c.data_type), true);
            }
        }
        let regions = rb
            .finish()
            .ok_or_else(|| bad("the objects do not fit in 4 GiB"))?;
        let addr = |p: *const c_void| -> Result<u32, Error> {
            regions
                .model_addr(p as usize)
                .ok_or_else(|| bad("an object outside every region"))
        };

        // Types; an INSTANCE type is a POU (its kind in `elem`), in the
        // model's order of POUs.
        let mut types = Vec::with_capacity(self.types.len());
        let mut pous = Vec::new();
        for (i, t) in self.types.iter().enumerate() {
            let elem =
                || ElemType::from_code(t.elem).ok_or_else(|| bad("an unknown elementary type"));
            let u32_of = |n: usize| u32::try_from(n).map_err(|_| bad("a size over 4 GiB"));
            types.push(match K::from_code(t.kind) {
                Some(K::Scalar) => TypeDesc::Scalar(elem()?),
                Some(K::String) => TypeDesc::String {
                    wide: t.wide != 0,
                    cap: t.cap,
                },
                Some(K::Enum) => TypeDesc::Enum {
                    name: text(t.name).unwrap_or_default(),
                    base: elem()?,
                    values: table(t.values, t.count)
                        .iter()
                        .map(|v| (text(v.name).unwrap_or_default(), v.value as i128))
                        .collect(),
                },
                Some(K::Array) => TypeDesc::Array {
                    elem: t.elem_type,
                    dims: table(t.dims, t.count)
                        .iter()
                        .map(|d| (d.lo, d.hi))
                        .collect(),
                    stride: u32_of(t.stride)?,
                },
                Some(K::Struct) => TypeDesc::Struct {
                    name: text(t.name),
                    fields: table(t.members, t.count)
                        .iter()
                        .map(|m| {
                            Ok(FieldDesc {
                                name: text(m.name).unwrap_or_default(),
                                ty: m.ty,
                                offset: u32_of(m.offset)?,
                            })
                        })
                        .collect::<Result<_, Error>>()?,
                },
                Some(K::Instance) => {
                    let vars = table(t.members, t.count)
                        .iter()
                        .map(|m| var(m).ok_or_else(|| bad("a variable of an unknown kind")))
                        .collect::<Result<Vec<_>, Error>>()?;
                    let pou = pous.len() as u32;
                    pous.push(PouDesc {
                        name: text(t.name).unwrap_or_default(),
                        kind: PouKind::from_code(t.elem)
                            .ok_or_else(|| bad("an instance of an unknown kind of POU"))?,
                        instance_size: u32_of(t.size)?,
                        vars,
                        instance_type: i as TypeRef,
                    });
                    TypeDesc::Instance { pou }
                }
                Some(K::Subrange) => TypeDesc::Subrange {
                    base: elem()?,
                    lo: t.lo as i128,
                    hi: t.hi as i128,
                },
                None => return Err(bad("an unknown kind of type")),
            });
        }
        let pou_of = |ty: u32| -> Result<u32, Error> {
            match types.get(ty as usize) {
                Some(TypeDesc::Instance { pou }) => Ok(*pou),
                _ => Err(bad("a program instance whose type is not an instance")),
            }
        };

        let globals = self
            .globals
            .iter()
            .map(|g| {
                Ok(GlobalDesc {
                    name: text(g.name).unwrap_or_default(),
                    ty: g.ty,
                    offset: addr(g.data)?,
                    config: u32::try_from(g.config).ok(),
                    location: location(g.location),
                    constant: g.constant != 0,
                    retain: g.retain != 0,
                })
            })
            .collect::<Result<Vec<_>, Error>>()?;
        let io = self
            .io
            .iter()
            .filter_map(|s| {
                let address = location(s.address)?;
                Some(addr(s.data).map(|offset| IoSlot {
                    address,
                    offset,
                    ty: s.ty,
                }))
            })
            .collect::<Result<Vec<_>, Error>>()?;

        let mut bodies = Vec::new();
        let mut program = |p: &CProgram| -> Result<ProgramInst, Error> {
            let offset = addr(p.data)?;
            if let Some(body) = p.body {
                bodies.push((offset, body, p.data));
            }
            let conns = |list: &[CConn]| {
                list.iter()
                    .map(|c| {
                        Ok((
                            u32::try_from(c.inst_offset).map_err(|_| bad("an offset"))?,
                            c.ty,
                            Source::Addr {
                                offset: addr(c.data)?,
                                ty: c.data_type,
                            },
                        ))
                    })
                    .collect::<Result<Vec<_>, Error>>()
            };
            Ok(ProgramInst {
                name: text(p.name).unwrap_or_default(),
                pou: pou_of(p.ty)?,
                offset,
                task: u32::try_from(p.task).ok(),
                inputs: conns(table(p.inputs, p.n_inputs))?,
                outputs: conns(table(p.outputs, p.n_outputs))?,
            })
        };
        let mut configs = Vec::new();
        for c in self.configs {
            let mut resources = Vec::new();
            for r in table(c.resources, c.n_resources) {
                let tasks = table(r.tasks, r.n_tasks)
                    .iter()
                    .map(|t| {
                        Ok(TaskDesc {
                            name: text(t.name).unwrap_or_default(),
                            interval_ns: (t.has_interval != 0).then_some(t.interval_ns),
                            priority: t.priority,
                            single: if t.single.is_null() {
                                None
                            } else {
                                Some(Source::Addr {
                                    offset: addr(t.single)?,
                                    ty: t.single_type,
                                })
                            },
                        })
                    })
                    .collect::<Result<Vec<_>, Error>>()?;
                let programs = table(r.programs, r.n_programs)
                    .iter()
                    .map(&mut program)
                    .collect::<Result<Vec<_>, Error>>()?;
                resources.push(ResourceDesc {
                    name: text(r.name),
                    tasks,
                    programs,
                });
            }
            configs.push(ConfigDesc {
                name: text(c.name).unwrap_or_default(),
                resources,
            });
        }
        let programs = self
            .programs
            .iter()
            .map(&mut program)
            .collect::<Result<Vec<_>, Error>>()?;

        Ok(Loaded {
            model: Model {
                types,
                pous,
                globals,
                configs,
                programs,
                io,
            },
            regions,
            bodies,
        })
    }
}

/// A located variable's address (`"%QX0.0"`).
///
/// # Safety
/// `p` is null or a string of the library.
unsafe fn location(p: *const c_char) -> Option<DirectAddress> {
    parse_address(&text(p)?).ok()
}

/// A variable of an instance.
///
/// # Safety
/// The member's strings are the library's.
unsafe fn var(m: &CMember) -> Option<VarDesc> {
    let kind = VarKind::from_code(m.kind)?;
    Some(VarDesc {
        name: text(m.name).unwrap_or_default(),
        ty: m.ty,
        kind,
        offset: u32::try_from(m.offset).ok()?,
        in_frame: m.in_frame != 0,
        is_ref: m.is_ref != 0,
        location: location(m.location),
        constant: m.constant != 0,
        retain: m.retain != 0,
    })
}
