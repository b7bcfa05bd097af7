//! RETAIN variables across a restart (`stc run --realtime --retain FILE`).
//!
//! [`Retained`] is the set of retained variables of what runs: the RETAIN
//! globals of the chosen configuration and of the top-level lists, and the
//! variables of its program instances declared in a RETAIN block (an FB
//! instance declared RETAIN keeps all its own variables, as IEC 61131-3
//! says; a variable declared RETAIN inside a function block is kept in
//! every instance of it). It turns their bytes into an image
//! ([`Retained::save`]) and an image back into memory
//! ([`Retained::restore`]); the `stc` crate writes and reads the file.
//!
//! The image is `STRT`, the format version, a fingerprint of the layout
//! of the retained variables (names, types, sizes, field offsets), the
//! cycle it was taken after, the payload length, the payload (each
//! variable's bytes in order) and a CRC-32 of everything before it. An
//! image is loaded only if every part checks, so a truncated, corrupted or
//! foreign file (another program, or this one changed) is refused whole:
//! nothing is written to memory before the whole image is checked.
//! References (VAR_IN_OUT, VAR_EXTERNAL, located variables) are never
//! saved: an address means nothing in another process.

use stc_ir::model::{Model, TypeDesc, TypeRef, VarKind};
use stc_syntax::literal::AddrArea;

use crate::engine::Memory;
use crate::schedule::Plan;

pub const MAGIC: &[u8; 4] = b"STRT";
/// The version of the image format.
pub const VERSION: u32 = 1;
const HEADER: usize = 4 + 4 + 8 + 8 + 8;

/// Why an image was not loaded.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum RetainError {
    #[error("not a retain file of stc")]
    Magic,
    #[error("retain format version {0} is not supported (this stc reads version {VERSION})")]
    Version(u32),
    #[error("the file is truncated ({0} bytes)")]
    Truncated(usize),
    #[error("the checksum does not match (the file is corrupted)")]
    Checksum,
    #[error("it was saved by another program (or by this one before it changed)")]
    Fingerprint,
    #[error("the variables' bytes cannot be written to the memory")]
    Memory,
}

/// One retained variable: its path and its bytes in the engine's memory.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Region {
    pub name: String,
    pub addr: u32,
    pub len: u32,
}

/// The retained variables of a plan; see the module documentation.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Retained {
    pub regions: Vec<Region>,
    fingerprint: u64,
    size: usize,
}

/// FNV-1a, 64 bits: the fingerprint needs to tell layouts apart, not to
/// resist an adversary (the CRC guards the bytes).
struct Fnv(u64);

impl Fnv {
    fn bytes(&mut self, b: &[u8]) {
        for &x in b {
            self.0 ^= u64::from(x);
            self.0 = self.0.wrapping_mul(0x0000_0100_0000_01b3);
        }
    }
    fn str(&mut self, s: &str) {
        self.bytes(s.to_ascii_lowercase().as_bytes());
        self.bytes(&[0xff]);
    }
    fn num(&mut self, n: i128) {
        self.bytes(&n.to_le_bytes());
    }
}

/// The deepest type nesting followed (a hostile table could loop).
const MAX_DEPTH: u32 = 64;

struct Collect<'a> {
    model: &'a Model,
    regions: Vec<Region>,
    hash: Fnv,
}

impl Collect<'_> {
    /// A variable of type `ty` at `addr`: all of it when `whole`, else only
    /// what is declared RETAIN inside it (instances are walked variable by
    /// variable so their reference slots are never saved).
    fn var(&mut self, name: String, ty: TypeRef, addr: u32, whole: bool, depth: u32) {
        if depth > MAX_DEPTH {
            return;
        }
        match self.model.types.get(ty as usize) {
            Some(TypeDesc::Instance { pou }) => {
                let Some(p) = self.model.pous.get(*pou as usize) else {
                    return;
                };
                for v in &p.vars {
                    let stateful = matches!(
                        v.kind,
                        VarKind::Input | VarKind::Output | VarKind::Var | VarKind::Hidden
                    );
                    if !stateful || v.in_frame || v.is_ref || v.constant {
                        continue;
                    }
                    self.var(
                        format!("{name}.{}", v.name),
                        v.ty,
                        addr.wrapping_add(v.offset),
                        whole || v.retain,
                        depth + 1,
                    );
                }
            }
            Some(TypeDesc::Array { elem, dims, stride })
                if matches!(
                    self.model.types.get(*elem as usize),
                    Some(TypeDesc::Instance { .. })
                ) =>
            {
                let n: i64 = dims.iter().map(|(l, h)| (h - l + 1).max(0)).product();
                for k in 0..n.min(1 << 20) as u32 {
                    self.var(
                        format!("{name}[#{k}]"),
                        *elem,
                        addr.wrapping_add(k.wrapping_mul(*stride)),
                        whole,
                        depth + 1,
                    );
                }
            }
            Some(_) if whole => {
                let len = self.model.type_size(ty);
                let Ok(len) = u32::try_from(len) else { return };
                self.hash.str(&name);
                self.ty(ty, 0);
                self.hash.num(i128::from(len));
                self.regions.push(Region { name, addr, len });
            }
            _ => {}
        }
    }

    /// Hashes the shape of a value type.
    fn ty(&mut self, ty: TypeRef, depth: u32) {
        if depth > MAX_DEPTH {
            return;
        }
        let Some(t) = self.model.types.get(ty as usize) else {
            return;
        };
        self.hash.bytes(&[t.kind().code()]);
        match t {
            TypeDesc::Scalar(e) => self.hash.bytes(&[e.code()]),
            TypeDesc::String { wide, cap } => {
                self.hash.bytes(&[*wide as u8]);
                self.hash.num(i128::from(*cap));
            }
            TypeDesc::Enum { base, values, .. } => {
                self.hash.bytes(&[base.code()]);
                for (n, v) in values {
                    self.hash.str(n);
                    self.hash.num(*v);
                }
            }
            TypeDesc::Array { elem, dims, stride } => {
                for (l, h) in dims {
                    self.hash.num(i128::from(*l));
                    self.hash.num(i128::from(*h));
                }
                self.hash.num(i128::from(*stride));
                self.ty(*elem, depth + 1);
            }
            TypeDesc::Struct { fields, .. } => {
                for f in fields {
                    self.hash.str(&f.name);
                    self.hash.num(i128::from(f.offset));
                    self.ty(f.ty, depth + 1);
                }
            }
            TypeDesc::Instance { pou } => {
                if let Some(p) = self.model.pous.get(*pou as usize) {
                    self.hash.str(&p.name);
                }
            }
            TypeDesc::Subrange { base, lo, hi } => {
                self.hash.bytes(&[base.code()]);
                self.hash.num(*lo);
                self.hash.num(*hi);
            }
        }
    }
}

impl Retained {
    /// The retained variables of what `plan` runs.
    pub fn new(model: &Model, plan: &Plan) -> Retained {
        let mut c = Collect {
            model,
            regions: Vec::new(),
            hash: Fnv(0xcbf2_9ce4_8422_2325),
        };
        for g in &model.globals {
            let mine = g.config.is_none() || g.config == plan.config;
            let input = g
                .location
                .as_ref()
                .is_some_and(|a| a.area == AddrArea::Input);
            if mine && g.retain && !g.constant && !input {
                c.var(g.name.clone(), g.ty, g.offset, true, 0);
            }
        }
        for inst in &plan.instances {
            if let Some(p) = model.pous.get(inst.pou as usize) {
                c.var(inst.name.clone(), p.instance_type, inst.offset, false, 0);
            }
        }
        let size = c.regions.iter().map(|r| r.len as usize).sum();
        Retained {
            regions: c.regions,
            fingerprint: c.hash.0,
            size,
        }
    }

    /// Whether nothing is retained.
    pub fn is_empty(&self) -> bool {
        self.regions.is_empty()
    }

    /// The layout fingerprint an image must carry.
    pub fn fingerprint(&self) -> u64 {
        self.fingerprint
    }

    /// The image of the retained variables now, taken after `cycle`.
    /// `None` if a variable lies outside the memory (a broken model).
    pub fn save<M: Memory + ?Sized>(&self, mem: &M, cycle: u64) -> Option<Vec<u8>> {
        let mut out = Vec::with_capacity(HEADER + self.size + 4);
        out.extend_from_slice(MAGIC);
        out.extend_from_slice(&VERSION.to_le_bytes());
        out.extend_from_slice(&self.fingerprint.to_le_bytes());
        out.extend_from_slice(&cycle.to_le_bytes());
        out.extend_from_slice(&(self.size as u64).to_le_bytes());
        for r in &self.regions {
            out.extend_from_slice(mem.bytes(r.addr, r.len)?);
        }
        let crc = crc32fast::hash(&out);
        out.extend_from_slice(&crc.to_le_bytes());
        Some(out)
    }

    /// Checks an image whole, then writes it into memory; returns the
    /// cycle it was taken after. On an error nothing has been written.
    pub fn restore<M: Memory + ?Sized>(
        &self,
        mem: &mut M,
        image: &[u8],
    ) -> Result<u64, RetainError> {
        let payload = self.check(image)?;
        let cycle = u64::from_le_bytes(image[16..24].try_into().map_err(|_| RetainError::Magic)?);
        if self
            .regions
            .iter()
            .any(|r| mem.bytes(r.addr, r.len).is_none())
        {
            return Err(RetainError::Memory);
        }
        let mut at = 0usize;
        for r in &self.regions {
            let n = r.len as usize;
            let dst = mem.bytes_mut(r.addr, r.len).ok_or(RetainError::Memory)?;
            dst.copy_from_slice(&payload[at..at + n]);
            at += n;
        }
        Ok(cycle)
    }

    /// The payload of a valid image of this layout.
    fn check<'b>(&self, image: &'b [u8]) -> Result<&'b [u8], RetainError> {
        let word = |at: usize| -> u64 {
            let mut b = [0u8; 8];
            b.copy_from_slice(&image[at..at + 8]);
            u64::from_le_bytes(b)
        };
        if image.len() < 4 || &image[..4] != MAGIC {
            return Err(RetainError::Magic);
        }
        if image.len() < HEADER + 4 {
            return Err(RetainError::Truncated(image.len()));
        }
        // The checksum first: a damaged header is then reported as damage,
        // not as whatever its bytes happen to say.
        let (body, crc) = image.split_at(image.len() - 4);
        if crc32fast::hash(body).to_le_bytes() != crc {
            return Err(RetainError::Checksum);
        }
        let version = u32::from_le_bytes([image[4], image[5], image[6], image[7]]);
        if version != VERSION {
            return Err(RetainError::Version(version));
        }
        let len = word(24);
        if (image.len() - HEADER - 4) as u64 != len {
            return Err(RetainError::Truncated(image.len()));
        }
        if word(8) != self.fingerprint || len != self.size as u64 {
            return Err(RetainError::Fingerprint);
        }
        Ok(&body[HEADER..])
    }
}

/// How many cycles apart saves are: `interval_ns` rounded up to whole
/// ticks, at least one.
pub fn cycles_between_saves(interval_ns: Option<i64>, tick_ns: i64) -> u64 {
    match interval_ns {
        Some(i) if i > 0 && tick_ns > 0 => (i as u64).div_ceil(tick_ns as u64).max(1),
        _ => 1,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::schedule::{Chosen, Plan};
    use crate::testing::sample_model;

    /// The sample model with its global `g` and `Main`'s first variable
    /// declared RETAIN.
    fn model() -> Model {
        let mut m = sample_model();
        m.globals[0].retain = true;
        let main = m.configs[0].resources[0].programs[0].pou as usize;
        m.pous[main].vars[0].retain = true;
        m
    }

    fn retained(m: &Model) -> Retained {
        let plan = Plan::new(m, Chosen::Config(0), None).unwrap();
        Retained::new(m, &plan)
    }

    fn memory(m: &Model) -> Vec<u8> {
        let r = retained(m);
        let end = r.regions.iter().map(|r| r.addr + r.len).max().unwrap_or(0);
        (0..end + 8).map(|i| (i * 7 + 3) as u8).collect()
    }

    #[test]
    fn the_retained_variables_are_the_retain_globals_and_program_variables() {
        let m = model();
        let r = retained(&m);
        let names: Vec<&str> = r.regions.iter().map(|r| r.name.as_str()).collect();
        assert_eq!(names[0], "g");
        // `count` in every instance of Main, nothing else.
        assert!(names.len() >= 2, "{names:?}");
        assert!(
            names[1..].iter().all(|n| n.ends_with(".count")),
            "{names:?}"
        );
        let none = retained(&sample_model());
        assert!(none.is_empty());
    }

    #[test]
    fn an_image_round_trips() {
        let m = model();
        let r = retained(&m);
        let mem = memory(&m);
        let img = r.save(&mem, 42).unwrap();
        let mut other = vec![0u8; mem.len()];
        assert_eq!(r.restore(&mut other, &img), Ok(42));
        for reg in &r.regions {
            let (a, b) = (reg.addr as usize, (reg.addr + reg.len) as usize);
            assert_eq!(other[a..b], mem[a..b]);
        }
    }

    #[test]
    fn a_corrupted_byte_anywhere_is_refused_and_nothing_is_written() {
        let m = model();
        let r = retained(&m);
        let img = r.save(&memory(&m), 7).unwrap();
        for i in 0..img.len() {
            for bit in [0x01u8, 0x80] {
                let mut bad = img.clone();
                bad[i] ^= bit;
                let mut mem = vec![0u8; memory(&m).len()];
                assert!(r.restore(&mut mem, &bad).is_err(), "byte {i} bit {bit:#x}");
                assert!(mem.iter().all(|&b| b == 0), "written at byte {i}");
            }
        }
    }

    #[test]
    fn a_truncated_or_extended_image_is_refused() {
        let m = model();
        let r = retained(&m);
        let img = r.save(&memory(&m), 7).unwrap();
        let mut mem = memory(&m);
        for n in 0..img.len() {
            assert!(r.restore(&mut mem, &img[..n]).is_err(), "{n} bytes");
        }
        let mut longer = img.clone();
        longer.push(0);
        assert!(r.restore(&mut mem, &longer).is_err());
        assert!(r.restore(&mut mem, b"").is_err());
        assert_eq!(
            r.restore(&mut mem, b"hello, world").unwrap_err(),
            RetainError::Magic
        );
    }

    #[test]
    fn an_image_of_another_layout_is_foreign() {
        let m = model();
        let img = retained(&m).save(&memory(&m), 1).unwrap();
        // Another type for the same variable: same size, other layout.
        let mut changed = model();
        changed.globals[0].name = "renamed".into();
        let other = retained(&changed);
        let mut mem = memory(&m);
        assert_eq!(other.restore(&mut mem, &img), Err(RetainError::Fingerprint));
        // One variable more.
        let mut more = model();
        more.globals[1].retain = true;
        more.globals[1].constant = false;
        assert_eq!(
            retained(&more).restore(&mut mem, &img),
            Err(RetainError::Fingerprint)
        );
        // Another version of the format.
        let mut v2 = img.clone();
        v2[4] = 2;
        let crc = crc32fast::hash(&v2[..v2.len() - 4]).to_le_bytes();
        let n = v2.len();
        v2[n - 4..].copy_from_slice(&crc);
        assert_eq!(
            retained(&m).restore(&mut mem, &v2),
            Err(RetainError::Version(2))
        );
    }

    #[test]
    fn saves_are_whole_ticks_apart() {
        assert_eq!(cycles_between_saves(None, 10), 1);
        assert_eq!(cycles_between_saves(Some(5), 10), 1);
        assert_eq!(cycles_between_saves(Some(10), 10), 1);
        assert_eq!(cycles_between_saves(Some(25), 10), 3);
    }
}
