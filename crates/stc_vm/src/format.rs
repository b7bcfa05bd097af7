//! The `.stbc` file: a versioned binary form of an [`Image`].
//!
//! Layout: the magic `STBC`, a format version (u32), the payload length
//! (u32), a CRC-32 of the payload (u32), then the payload: every table of
//! the image in a fixed order, little-endian, with u32 counts before
//! sequences. [`decode`] checks the envelope, reads the payload without ever
//! trusting a length, then runs the [`crate::verify`]er: a file that loads
//! is safe to run.

use stc_syntax::literal::{AddrArea, AddrSize, DirectAddress};
use stc_syntax::token::ElemType;

use crate::image::*;
use crate::instr::{Instr, Op};

pub const MAGIC: &[u8; 4] = b"STBC";
/// The format version. 2: elementary types, variable, POU and type kinds,
/// scalar kinds and fault codes are stored by their explicit codes (faults
/// 1-based), standard functions by name. 3: a RETAIN flag after the
/// CONSTANT flag of every variable and global.
pub const VERSION: u32 = 3;

#[derive(Debug, thiserror::Error, PartialEq, Eq)]
pub enum LoadError {
    #[error("not a bytecode file: the magic number is missing")]
    Magic,
    #[error("bytecode format version {0} is not supported (this stc reads version {VERSION})")]
    Version(u32),
    #[error("the file is truncated or its length field is wrong")]
    Length,
    #[error("checksum mismatch: the file is corrupt")]
    Checksum,
    #[error("malformed bytecode at byte {offset}: {what}")]
    Malformed { offset: usize, what: String },
    #[error("invalid bytecode: {0}")]
    Invalid(String),
}

/// Serialises an image.
pub fn encode(img: &Image) -> Vec<u8> {
    let mut w = Writer(Vec::new());
    w.u32(img.code.len() as u32);
    for i in &img.code {
        w.u8(i.opcode());
        for f in i.fields() {
            w.u32(f);
        }
    }
    w.tables(img);
    let payload = w.0;
    let mut out = Vec::with_capacity(payload.len() + 16);
    out.extend_from_slice(MAGIC);
    out.extend_from_slice(&VERSION.to_le_bytes());
    out.extend_from_slice(&(payload.len() as u32).to_le_bytes());
    out.extend_from_slice(&crc32fast::hash(&payload).to_le_bytes());
    out.extend_from_slice(&payload);
    out
}

/// Every table of an image except its code, in the binary form (VMASM
/// carries them as hex).
pub fn encode_tables(img: &Image) -> Vec<u8> {
    let mut w = Writer(Vec::new());
    w.tables(img);
    w.0
}

/// The tables of [`encode_tables`] back, with the given code (not verified).
pub fn decode_tables(bytes: &[u8], code: Vec<crate::instr::Instr>) -> Result<Image, LoadError> {
    let mut r = Reader { b: bytes, pos: 0 };
    let img = r.tables(code)?;
    if r.pos != bytes.len() {
        return Err(r.err("trailing bytes after the last table"));
    }
    Ok(img)
}

/// Reads and verifies an image.
pub fn decode(bytes: &[u8]) -> Result<Image, LoadError> {
    if bytes.len() < 16 || &bytes[..4] != MAGIC {
        return Err(LoadError::Magic);
    }
    let word = |i: usize| u32::from_le_bytes([bytes[i], bytes[i + 1], bytes[i + 2], bytes[i + 3]]);
    let version = word(4);
    if version != VERSION {
        return Err(LoadError::Version(version));
    }
    let len = word(8) as usize;
    if bytes.len() - 16 != len {
        return Err(LoadError::Length);
    }
    let payload = &bytes[16..];
    if crc32fast::hash(payload) != word(12) {
        return Err(LoadError::Checksum);
    }
    let mut r = Reader { b: payload, pos: 0 };
    let img = r.image()?;
    if r.pos != payload.len() {
        return Err(r.err("trailing bytes after the last table"));
    }
    crate::verify::verify(&img).map_err(LoadError::Invalid)?;
    Ok(img)
}

struct Writer(Vec<u8>);

impl Writer {
    fn tables(&mut self, img: &Image) {
        let w = self;
        w.bytes(&img.consts);
        w.u32(img.data_size);
        w.bytes(&img.init);
        w.u32(img.stack_size);
        let model = &*img.model;
        w.seq(&model.types, |w, t| w.type_desc(t));
        // A POU's model and code, together (the same bytes as before the
        // model moved to stc_ir: format version 2 is unchanged).
        let pous: Vec<(&PouDesc, &PouCode)> = model.pous.iter().zip(&img.pous).collect();
        w.seq(&pous, |w, (p, c)| {
            w.str(&p.name);
            w.u8(p.kind.code());
            w.u32(c.entry);
            w.u32(p.instance_size);
            w.u32(c.frame_size);
            w.u32(c.frame_init_at);
            w.u32(c.frame_template.0);
            w.u32(c.frame_template.1);
            w.u32(p.instance_type);
            w.seq(&p.vars, |w, v| {
                w.str(&v.name);
                w.u32(v.ty);
                w.u8(v.kind.code());
                w.u32(v.offset);
                w.u8(v.in_frame as u8);
                w.u8(v.is_ref as u8);
                w.opt(&v.location, |w, a| w.address(a));
                w.u8(v.constant as u8);
                w.u8(v.retain as u8);
            });
        });
        w.seq(&model.globals, |w, g| {
            w.str(&g.name);
            w.u32(g.ty);
            w.u32(g.offset);
            w.opt(&g.config, |w, c| w.u32(*c));
            w.opt(&g.location, |w, a| w.address(a));
            w.u8(g.constant as u8);
            w.u8(g.retain as u8);
        });
        w.seq(&model.configs, |w, c| {
            w.str(&c.name);
            w.seq(&c.resources, |w, r| {
                w.opt(&r.name, |w, n| w.str(n));
                w.seq(&r.tasks, |w, t| {
                    w.str(&t.name);
                    w.opt(&t.interval_ns, |w, i| w.u64(*i as u64));
                    w.u32(t.priority);
                    w.opt(&t.single, |w, s| w.source(s));
                });
                w.seq(&r.programs, |w, p| w.program(p));
            });
        });
        w.seq(&model.programs, |w, p| w.program(p));
        w.seq(&model.io, |w, s| {
            w.address(&s.address);
            w.u32(s.offset);
            w.u32(s.ty);
        });
        w.seq(&img.calls, |w, c| {
            w.std_op(&c.op);
            w.seq(&c.args, |w, a| w.std_arg(a));
            w.std_arg(&c.result);
        });
        w.seq(&img.elems, |w, e| {
            w.u64(e.lo as u64);
            w.u32(e.count);
            w.u32(e.stride);
            w.u8(e.num.code() as u8);
        });
        w.seq(&img.lines, |w, l| {
            w.u32(l.pc);
            w.u32(l.pou);
            w.u32(l.file);
            w.u32(l.line);
            w.u32(l.col);
        });
        w.seq(&img.files, |w, f| w.str(f));
    }

    fn u8(&mut self, v: u8) {
        self.0.push(v);
    }
    fn u32(&mut self, v: u32) {
        self.0.extend_from_slice(&v.to_le_bytes());
    }
    fn u64(&mut self, v: u64) {
        self.0.extend_from_slice(&v.to_le_bytes());
    }
    fn i128(&mut self, v: i128) {
        self.0.extend_from_slice(&v.to_le_bytes());
    }
    fn bytes(&mut self, b: &[u8]) {
        self.u32(b.len() as u32);
        self.0.extend_from_slice(b);
    }
    fn str(&mut self, s: &str) {
        self.bytes(s.as_bytes());
    }
    fn seq<T>(&mut self, items: &[T], mut f: impl FnMut(&mut Self, &T)) {
        self.u32(items.len() as u32);
        for i in items {
            f(self, i);
        }
    }
    fn opt<T>(&mut self, v: &Option<T>, f: impl FnOnce(&mut Self, &T)) {
        match v {
            Some(x) => {
                self.u8(1);
                f(self, x);
            }
            None => self.u8(0),
        }
    }
    fn elem(&mut self, e: ElemType) {
        self.u8(e.code());
    }
    fn type_desc(&mut self, t: &TypeDesc) {
        self.u8(t.kind().code());
        match t {
            TypeDesc::Scalar(e) => self.elem(*e),
            TypeDesc::String { wide, cap } => {
                self.u8(*wide as u8);
                self.u32(*cap);
            }
            TypeDesc::Enum { name, base, values } => {
                self.str(name);
                self.elem(*base);
                self.seq(values, |w, (n, v)| {
                    w.str(n);
                    w.i128(*v);
                });
            }
            TypeDesc::Array { elem, dims, stride } => {
                self.u32(*elem);
                self.seq(dims, |w, (l, h)| {
                    w.u64(*l as u64);
                    w.u64(*h as u64);
                });
                self.u32(*stride);
            }
            TypeDesc::Struct { name, fields } => {
                self.opt(name, |w, n| w.str(n));
                self.seq(fields, |w, f| {
                    w.str(&f.name);
                    w.u32(f.ty);
                    w.u32(f.offset);
                });
            }
            TypeDesc::Instance { pou } => {
                self.u32(*pou);
            }
            TypeDesc::Subrange { base, lo, hi } => {
                self.elem(*base);
                self.i128(*lo);
                self.i128(*hi);
            }
        }
    }
    fn address(&mut self, a: &DirectAddress) {
        self.u8(match a.area {
            AddrArea::Input => 0,
            AddrArea::Output => 1,
            AddrArea::Memory => 2,
        });
        self.u8(match a.size {
            AddrSize::Bit => 0,
            AddrSize::Byte => 1,
            AddrSize::Word => 2,
            AddrSize::Dword => 3,
            AddrSize::Lword => 4,
        });
        self.u8(a.explicit_size as u8);
        self.seq(&a.path, |w, n| w.u32(*n));
    }
    fn source(&mut self, s: &Source) {
        let Source::Addr { offset, ty } = s;
        self.u32(*offset);
        self.u32(*ty);
    }
    fn program(&mut self, p: &ProgramInst) {
        self.str(&p.name);
        self.u32(p.pou);
        self.u32(p.offset);
        self.opt(&p.task, |w, t| w.u32(*t));
        for list in [&p.inputs, &p.outputs] {
            self.seq(list, |w, (o, t, s)| {
                w.u32(*o);
                w.u32(*t);
                w.source(s);
            });
        }
    }
    fn std_op(&mut self, op: &StdOp) {
        match op {
            StdOp::Call(f) => {
                self.u8(0);
                let (name, a, b) = intrinsic_name(f);
                self.str(name);
                self.elem(a);
                self.opt(&b, |w, b| w.elem(*b));
            }
            StdOp::Binary(b) => {
                self.u8(1);
                self.u8(BINOPS.iter().position(|x| x == b).unwrap_or(0) as u8);
            }
            StdOp::Unary(u) => {
                self.u8(2);
                self.u8(matches!(u, stc_values::UnOp::Not) as u8);
            }
            StdOp::Convert => self.u8(3),
            StdOp::Trunc => self.u8(4),
        }
    }
    fn std_arg(&mut self, (op, e, cap): &(Op, ElemType, u32)) {
        self.u32(op.0);
        self.elem(*e);
        self.u32(*cap);
    }
}

const BINOPS: [stc_values::BinOp; 15] = {
    use stc_values::BinOp as B;
    [
        B::Add,
        B::Sub,
        B::Mul,
        B::Div,
        B::Mod,
        B::Pow,
        B::And,
        B::Or,
        B::Xor,
        B::Eq,
        B::Ne,
        B::Lt,
        B::Le,
        B::Gt,
        B::Ge,
    ]
};

/// An intrinsic is stored as the name of a standard function that calls it
/// (with the types of the conversion families), so the order of the
/// standard-function table is not part of the format.
fn intrinsic_name(f: &stc_values::Intrinsic) -> (&'static str, ElemType, Option<ElemType>) {
    use stc_values::Intrinsic as I;
    let (a, b) = match f {
        I::Convert { from, to } | I::BcdToInt { from, to } | I::IntToBcd { from, to } => {
            (*from, Some(*to))
        }
        I::Trunc { from, to } => (*from, *to),
        _ => (ElemType::Bool, None),
    };
    let same = |x: &stc_values::Intrinsic| std::mem::discriminant(x) == std::mem::discriminant(f);
    let name = stc_values::all()
        .into_iter()
        .find(|s| same(&s.intrinsic))
        .map(|s| s.name)
        .or_else(|| {
            ["INT_TO_REAL", "TRUNC", "BCD_TO_INT", "INT_TO_BCD"]
                .into_iter()
                .find(|n| stc_values::lookup(n).is_some_and(|s| same(&s.intrinsic)))
        })
        .or_else(|| {
            // The SPLIT functions are not in the signature table.
            ["SPLIT_DATE", "SPLIT_TOD", "SPLIT_DT"]
                .into_iter()
                .find(|n| stc_values::split_lookup(n).is_some_and(|s| same(&s.0)))
        })
        .unwrap_or("");
    (name, a, b)
}

fn intrinsic_from(name: &str, a: ElemType, b: Option<ElemType>) -> Option<stc_values::Intrinsic> {
    use stc_values::Intrinsic as I;
    if let Some((f, ..)) = stc_values::split_lookup(name) {
        return Some(f);
    }
    Some(match stc_values::lookup(name)?.intrinsic {
        I::Convert { .. } => I::Convert { from: a, to: b? },
        I::BcdToInt { .. } => I::BcdToInt { from: a, to: b? },
        I::IntToBcd { .. } => I::IntToBcd { from: a, to: b? },
        I::Trunc { .. } => I::Trunc { from: a, to: b },
        other => other,
    })
}

struct Reader<'a> {
    b: &'a [u8],
    pos: usize,
}

impl Reader<'_> {
    fn err(&self, what: &str) -> LoadError {
        LoadError::Malformed {
            offset: self.pos + 16,
            what: what.to_string(),
        }
    }
    fn take(&mut self, n: usize) -> Result<&[u8], LoadError> {
        let end = self
            .pos
            .checked_add(n)
            .filter(|&e| e <= self.b.len())
            .ok_or_else(|| self.err("unexpected end of file"))?;
        let s = &self.b[self.pos..end];
        self.pos = end;
        Ok(s)
    }
    fn u8(&mut self) -> Result<u8, LoadError> {
        Ok(self.take(1)?[0])
    }
    fn u32(&mut self) -> Result<u32, LoadError> {
        let s = self.take(4)?;
        Ok(u32::from_le_bytes([s[0], s[1], s[2], s[3]]))
    }
    fn u64(&mut self) -> Result<u64, LoadError> {
        let s = self.take(8)?;
        let mut a = [0u8; 8];
        a.copy_from_slice(s);
        Ok(u64::from_le_bytes(a))
    }
    fn i128(&mut self) -> Result<i128, LoadError> {
        let s = self.take(16)?;
        let mut a = [0u8; 16];
        a.copy_from_slice(s);
        Ok(i128::from_le_bytes(a))
    }
    fn bool(&mut self) -> Result<bool, LoadError> {
        match self.u8()? {
            0 => Ok(false),
            1 => Ok(true),
            _ => Err(self.err("a flag that is neither 0 nor 1")),
        }
    }
    /// A count that cannot exceed the bytes left (each item takes at least one).
    fn count(&mut self) -> Result<usize, LoadError> {
        let n = self.u32()? as usize;
        if n > self.b.len() - self.pos {
            return Err(self.err("a count larger than the file"));
        }
        Ok(n)
    }
    fn bytes(&mut self) -> Result<Vec<u8>, LoadError> {
        let n = self.count()?;
        Ok(self.take(n)?.to_vec())
    }
    fn str(&mut self) -> Result<String, LoadError> {
        let b = self.bytes()?;
        String::from_utf8(b).map_err(|_| self.err("a name that is not UTF-8"))
    }
    fn seq<T>(
        &mut self,
        mut f: impl FnMut(&mut Self) -> Result<T, LoadError>,
    ) -> Result<Vec<T>, LoadError> {
        let n = self.count()?;
        let mut v = Vec::with_capacity(n.min(1 << 16));
        for _ in 0..n {
            v.push(f(self)?);
        }
        Ok(v)
    }
    fn opt<T>(
        &mut self,
        f: impl FnOnce(&mut Self) -> Result<T, LoadError>,
    ) -> Result<Option<T>, LoadError> {
        if self.bool()? {
            Ok(Some(f(self)?))
        } else {
            Ok(None)
        }
    }
    fn elem(&mut self) -> Result<ElemType, LoadError> {
        let c = self.u8()?;
        ElemType::from_code(c).ok_or_else(|| self.err("an unknown elementary type"))
    }
    fn type_desc(&mut self) -> Result<TypeDesc, LoadError> {
        let c = self.u8()?;
        let kind = TypeDescKind::from_code(c).ok_or_else(|| self.err("an unknown type kind"))?;
        Ok(match kind {
            TypeDescKind::Scalar => TypeDesc::Scalar(self.elem()?),
            TypeDescKind::String => TypeDesc::String {
                wide: self.bool()?,
                cap: self.u32()?,
            },
            TypeDescKind::Enum => TypeDesc::Enum {
                name: self.str()?,
                base: self.elem()?,
                values: self.seq(|r| Ok((r.str()?, r.i128()?)))?,
            },
            TypeDescKind::Array => TypeDesc::Array {
                elem: self.u32()?,
                dims: self.seq(|r| Ok((r.u64()? as i64, r.u64()? as i64)))?,
                stride: self.u32()?,
            },
            TypeDescKind::Struct => TypeDesc::Struct {
                name: self.opt(|r| r.str())?,
                fields: self.seq(|r| {
                    Ok(FieldDesc {
                        name: r.str()?,
                        ty: r.u32()?,
                        offset: r.u32()?,
                    })
                })?,
            },
            TypeDescKind::Instance => TypeDesc::Instance { pou: self.u32()? },
            TypeDescKind::Subrange => TypeDesc::Subrange {
                base: self.elem()?,
                lo: self.i128()?,
                hi: self.i128()?,
            },
        })
    }
    fn address(&mut self) -> Result<DirectAddress, LoadError> {
        let area = match self.u8()? {
            0 => AddrArea::Input,
            1 => AddrArea::Output,
            2 => AddrArea::Memory,
            _ => return Err(self.err("an unknown address area")),
        };
        let size = match self.u8()? {
            0 => AddrSize::Bit,
            1 => AddrSize::Byte,
            2 => AddrSize::Word,
            3 => AddrSize::Dword,
            4 => AddrSize::Lword,
            _ => return Err(self.err("an unknown address size")),
        };
        Ok(DirectAddress {
            area,
            size,
            explicit_size: self.bool()?,
            path: self.seq(|r| r.u32())?,
        })
    }
    fn source(&mut self) -> Result<Source, LoadError> {
        Ok(Source::Addr {
            offset: self.u32()?,
            ty: self.u32()?,
        })
    }
    fn program(&mut self) -> Result<ProgramInst, LoadError> {
        Ok(ProgramInst {
            name: self.str()?,
            pou: self.u32()?,
            offset: self.u32()?,
            task: self.opt(|r| r.u32())?,
            inputs: self.seq(|r| Ok((r.u32()?, r.u32()?, r.source()?)))?,
            outputs: self.seq(|r| Ok((r.u32()?, r.u32()?, r.source()?)))?,
        })
    }
    fn std_arg(&mut self) -> Result<(Op, ElemType, u32), LoadError> {
        Ok((Op(self.u32()?), self.elem()?, self.u32()?))
    }
    fn std_op(&mut self) -> Result<StdOp, LoadError> {
        Ok(match self.u8()? {
            0 => {
                let (name, a, b) = (self.str()?, self.elem()?, self.opt(|r| r.elem())?);
                StdOp::Call(
                    intrinsic_from(&name, a, b)
                        .ok_or_else(|| self.err("an unknown standard function"))?,
                )
            }
            1 => {
                let i = self.u8()?;
                StdOp::Binary(
                    *BINOPS
                        .get(i as usize)
                        .ok_or_else(|| self.err("an unknown operator"))?,
                )
            }
            2 => StdOp::Unary(if self.bool()? {
                stc_values::UnOp::Not
            } else {
                stc_values::UnOp::Neg
            }),
            3 => StdOp::Convert,
            4 => StdOp::Trunc,
            _ => return Err(self.err("an unknown operation kind")),
        })
    }
    fn image(&mut self) -> Result<Image, LoadError> {
        let code = self.code()?;
        self.tables(code)
    }

    fn code(&mut self) -> Result<Vec<Instr>, LoadError> {
        let n = self.count()?;
        let mut code = Vec::with_capacity(n.min(1 << 20));
        for _ in 0..n {
            let op = self.u8()?;
            let kinds = Instr::field_kinds(op).ok_or_else(|| self.err("an unknown opcode"))?;
            let mut fields = [0u32; 8];
            for f in fields.iter_mut().take(kinds.len()) {
                *f = self.u32()?;
            }
            let i = Instr::from_parts(op, &fields[..kinds.len()])
                .ok_or_else(|| self.err("a malformed instruction"))?;
            code.push(i);
        }
        Ok(code)
    }

    fn tables(&mut self, code: Vec<Instr>) -> Result<Image, LoadError> {
        let consts = self.bytes()?;
        let data_size = self.u32()?;
        let init = self.bytes()?;
        let stack_size = self.u32()?;
        let types = self.seq(|r| r.type_desc())?;
        let both = self.seq(|r| {
            let name = r.str()?;
            let kind = {
                let c = r.u8()?;
                PouKind::from_code(c).ok_or_else(|| r.err("an unknown POU kind"))?
            };
            let entry = r.u32()?;
            let instance_size = r.u32()?;
            let code = PouCode {
                entry,
                frame_size: r.u32()?,
                frame_init_at: r.u32()?,
                frame_template: (r.u32()?, r.u32()?),
            };
            let desc = PouDesc {
                name,
                kind,
                instance_size,
                instance_type: r.u32()?,
                vars: r.seq(|r| {
                    Ok(VarDesc {
                        name: r.str()?,
                        ty: r.u32()?,
                        kind: {
                            let c = r.u8()?;
                            VarKind::from_code(c)
                                .ok_or_else(|| r.err("an unknown variable kind"))?
                        },
                        offset: r.u32()?,
                        in_frame: r.bool()?,
                        is_ref: r.bool()?,
                        location: r.opt(|r| r.address())?,
                        constant: r.bool()?,
                        retain: r.bool()?,
                    })
                })?,
            };
            Ok((desc, code))
        })?;
        let (model_pous, pous): (Vec<PouDesc>, Vec<PouCode>) = both.into_iter().unzip();
        let globals = self.seq(|r| {
            Ok(GlobalDesc {
                name: r.str()?,
                ty: r.u32()?,
                offset: r.u32()?,
                config: r.opt(|r| r.u32())?,
                location: r.opt(|r| r.address())?,
                constant: r.bool()?,
                retain: r.bool()?,
            })
        })?;
        let configs = self.seq(|r| {
            Ok(ConfigDesc {
                name: r.str()?,
                resources: r.seq(|r| {
                    Ok(ResourceDesc {
                        name: r.opt(|r| r.str())?,
                        tasks: r.seq(|r| {
                            Ok(TaskDesc {
                                name: r.str()?,
                                interval_ns: r.opt(|r| Ok(r.u64()? as i64))?,
                                priority: r.u32()?,
                                single: r.opt(|r| r.source())?,
                            })
                        })?,
                        programs: r.seq(|r| r.program())?,
                    })
                })?,
            })
        })?;
        let programs = self.seq(|r| r.program())?;
        let io = self.seq(|r| {
            Ok(IoSlot {
                address: r.address()?,
                offset: r.u32()?,
                ty: r.u32()?,
            })
        })?;
        let calls = self.seq(|r| {
            Ok(StdCall {
                op: r.std_op()?,
                args: r.seq(|r| r.std_arg())?,
                result: r.std_arg()?,
            })
        })?;
        let elems = self.seq(|r| {
            Ok(ElemDesc {
                lo: r.u64()? as i64,
                count: r.u32()?,
                stride: r.u32()?,
                num: {
                    let c = r.u8()?;
                    crate::num::Num::from_code(c as u32)
                        .ok_or_else(|| r.err("unknown scalar kind of an array index"))?
                },
            })
        })?;
        let lines = self.seq(|r| {
            Ok(LineEntry {
                pc: r.u32()?,
                pou: r.u32()?,
                file: r.u32()?,
                line: r.u32()?,
                col: r.u32()?,
            })
        })?;
        let files = self.seq(|r| r.str())?;
        Ok(Image {
            code,
            consts,
            data_size,
            init,
            stack_size,
            model: std::sync::Arc::new(Model {
                types,
                pous: model_pous,
                globals,
                configs,
                programs,
                io,
            }),
            pous,
            calls,
            elems,
            lines,
            files,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_standard_function_round_trips_by_name() {
        for f in stc_values::all() {
            let (name, a, b) = intrinsic_name(&f.intrinsic);
            assert!(!name.is_empty(), "{}", f.name);
            assert_eq!(intrinsic_from(name, a, b), Some(f.intrinsic), "{}", f.name);
        }
        for n in [
            "INT_TO_REAL",
            "LREAL_TO_UDINT",
            "TRUNC",
            "BCD_TO_INT",
            "INT_TO_BCD",
        ] {
            let f = stc_values::lookup(n)
                .expect("a standard function")
                .intrinsic;
            let (name, a, b) = intrinsic_name(&f);
            assert_eq!(intrinsic_from(name, a, b), Some(f), "{n}");
        }
        assert_eq!(
            intrinsic_from("NO_SUCH_FUNCTION", ElemType::Bool, None),
            None
        );
    }

    #[test]
    fn coded_enums_read_back_and_reject_unknown_values() {
        for &k in VarKind::ALL {
            assert_eq!(VarKind::from_code(k.code()), Some(k));
        }
        for &k in PouKind::ALL {
            assert_eq!(PouKind::from_code(k.code()), Some(k));
        }
        for &k in TypeDescKind::ALL {
            assert_eq!(TypeDescKind::from_code(k.code()), Some(k));
        }
        assert_eq!(VarKind::from_code(VarKind::ALL.len() as u8), None);
        assert_eq!(PouKind::from_code(3), None);
        assert_eq!(TypeDescKind::from_code(7), None);
        for k in stc_ir::FaultKind::ALL {
            assert_eq!(stc_ir::FaultKind::from_code(u32::from(k.code())), Some(k));
        }
        assert_eq!(stc_ir::FaultKind::from_code(0), None);
        for n in crate::num::Num::ALL {
            assert_eq!(crate::num::Num::from_code(n.code()), Some(n));
        }
    }
}
