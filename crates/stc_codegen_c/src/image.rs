//! The process image arrays of the field I/O (seed 000 section IV.C,
//! Fig. 3).
//!
//! Seed 000 maps `%IX1.4` to `DV__I_X[1][4]` and `%QW2.5` to an element of
//! an output word array: one array per area and size, indexed by the parts
//! of the address. Here the arrays are `stc_img_I_X`, `stc_img_Q_W`, ...
//! with unsigned elements of the size's width (`X` and `B`: `uint8_t`,
//! `W`: `uint16_t`, `D`: `uint32_t`, `L`: `uint64_t`), as many dimensions as
//! the longest address of that area and size has parts (a shorter address
//! is padded with leading zeros: `%IW3` is `stc_img_I_W[0][3]` beside
//! `%IW1.4`), each as long as the largest index used. These arrays are the
//! integrator's side: `stc_io.c` fills the input arrays from the field and
//! drives the field from the output arrays, knowing nothing of ST types.
//!
//! The program's side stays one typed variable per address (`io_IW3`, what
//! the VM has): a located REAL, TIME or INT cannot be an element of an
//! unsigned array without type punning, and a program keeps its own view
//! of its inputs for the whole cycle. Generated `stc_image_read()` copies
//! every `%I` element into its variable (same bits: two's complement for
//! signed types, IEC 60559 for REAL/LREAL; a BOOL is TRUE for any non-zero
//! bit element) and `stc_image_write()` every `%Q` variable into its
//! element, around each task cycle in the real-time harness; `stc_init_all`
//! sets each input element to its variable's initial value, so with no
//! field connected an input keeps that value. An input whose
//! variable is a subrange or an enumeration and whose field value is not
//! one of its values is not copied (the variable keeps its value) and is a
//! subrange fault at the address, so no program ever sees a value outside
//! its type. `%M` addresses are memory, not field I/O: they have no image
//! array.

use std::fmt::Write as _;

use stc_ir::Module;
use stc_sema::TypeKind;
use stc_syntax::literal::{AddrArea, AddrSize, DirectAddress};
use stc_values::{ElemType, Value};

use crate::{names, Error};

/// More elements than this in one image array is refused (a typo such as
/// `%IW60000.1` would otherwise allocate megabytes).
const MAX_ELEMENTS: u64 = 1 << 20;

/// The declarations (for program.h) and definitions (for program.c) of
/// the image arrays, and `stc_image_read` and `stc_image_write` (declared in
/// stc_meta.h).
pub(crate) struct Image {
    pub header: String,
    pub source: String,
    /// Statements for the end of `stc_init_all`: every input element set to
    /// its variable's initial value, so that with no field connected an
    /// input keeps its declared initial value.
    pub init: Vec<String>,
}

/// A process-image slot: its address and the type of its C variable.
type Slot = (DirectAddress, stc_sema::TypeId);

/// The image of the process-image slots `io` (address and C variable
/// type); `site` registers a fault site for an address.
pub(crate) fn generate(
    m: &Module,
    io: &[Slot],
    site: &mut dyn FnMut(&DirectAddress) -> u32,
) -> Result<Image, Error> {
    // Groups by area and size, in a fixed order.
    let mut groups: Vec<(AddrArea, AddrSize, Vec<&Slot>)> = Vec::new();
    for slot in io {
        let a = &slot.0;
        if a.area == AddrArea::Memory || a.is_incomplete() {
            continue;
        }
        match groups
            .iter_mut()
            .find(|(ar, sz, _)| *ar == a.area && *sz == a.size)
        {
            Some(g) => g.2.push(slot),
            None => groups.push((a.area, a.size, vec![slot])),
        }
    }
    groups.sort_by_key(|(ar, sz, _)| (*ar != AddrArea::Input, *sz));
    let mut header = String::new();
    let mut source = String::new();
    let mut read = Vec::new();
    let mut write = Vec::new();
    let mut init = Vec::new();
    let mut clear = Vec::new();
    for (area, size, slots) in &groups {
        let name = array_name(*area, *size);
        let rank = slots.iter().map(|s| s.0.path.len()).max().unwrap_or(1);
        let mut dims = vec![0u64; rank];
        for s in slots {
            for (d, i) in padded(&s.0.path, rank).iter().enumerate() {
                dims[d] = dims[d].max(u64::from(*i) + 1);
            }
        }
        let count = dims.iter().try_fold(1u64, |n, &d| n.checked_mul(d));
        if count.is_none_or(|n| n > MAX_ELEMENTS) {
            return Err(Error::Unsupported(format!(
                "the process image {name}{}: more than {MAX_ELEMENTS} elements (addresses {})",
                dims.iter().map(|d| format!("[{d}]")).collect::<String>(),
                slots
                    .iter()
                    .map(|s| s.0.to_string())
                    .collect::<Vec<_>>()
                    .join(", ")
            )));
        }
        let elem = elem_c(*size);
        let shape: String = dims.iter().map(|d| format!("[{d}U]")).collect();
        let _ = writeln!(header, "extern {elem} {name}{shape};");
        let _ = writeln!(source, "{elem} {name}{shape};");
        clear.push(format!("    (void)memset({name}, 0, sizeof {name});"));
        for (a, ty) in slots.iter().map(|s| (&s.0, s.1)) {
            let el = format!(
                "{name}{}",
                padded(&a.path, rank)
                    .iter()
                    .map(|i| format!("[{i}U]"))
                    .collect::<String>()
            );
            let var = names::io_name(a);
            let Some(e) = m.types.scalar(ty) else {
                return Err(Error::Unsupported(format!(
                    "a located variable of a non-elementary type at {a}"
                )));
            };
            if *area == AddrArea::Input {
                read.push(read_one(m, a, ty, e, &el, &var, site)?);
                init.push(format!("    {el} = {};", bits_of(e, &var)));
            } else {
                write.push(format!("    {el} = {};", bits_of(e, &var)));
            }
        }
    }
    for (f, lines) in [("read", &read), ("write", &write)] {
        let _ = writeln!(source, "\nvoid stc_image_{f}(void)\n{{");
        for l in lines {
            let _ = writeln!(source, "{l}");
        }
        source.push_str("}\n");
    }
    clear.append(&mut init);
    let init = clear;
    Ok(Image {
        header,
        source,
        init,
    })
}

/// `stc_img_I_X`, `stc_img_Q_W`, ...
fn array_name(area: AddrArea, size: AddrSize) -> String {
    let a = match area {
        AddrArea::Input => 'I',
        AddrArea::Output => 'Q',
        AddrArea::Memory => 'M',
    };
    format!("stc_img_{a}_{}", size.letter())
}

fn elem_c(size: AddrSize) -> &'static str {
    match size {
        AddrSize::Bit | AddrSize::Byte => "uint8_t",
        AddrSize::Word => "uint16_t",
        AddrSize::Dword => "uint32_t",
        AddrSize::Lword => "uint64_t",
    }
}

/// The parts of an address, padded with leading zeros to `rank`.
fn padded(path: &[u32], rank: usize) -> Vec<u32> {
    let mut v = vec![0; rank.saturating_sub(path.len())];
    v.extend_from_slice(path);
    v
}

/// The value of type `e` whose bits are the image element `el`.
fn of_bits(e: ElemType, el: &str) -> String {
    let c = names::elem_c(e);
    if e == ElemType::Bool {
        format!("(({el} != 0U) ? 1U : 0U)")
    } else if c == "float" {
        format!("stc_real_of_bits({el})")
    } else if c == "double" {
        format!("stc_lreal_of_bits({el})")
    } else if let Some(bits) = c.strip_prefix("int").and_then(|b| b.strip_suffix("_t")) {
        format!("stc_i{bits}_of({el})")
    } else {
        el.to_string()
    }
}

/// The image element bits of `var` of type `e`.
fn bits_of(e: ElemType, var: &str) -> String {
    let c = names::elem_c(e);
    if e == ElemType::Bool {
        format!("(({var} != 0U) ? 1U : 0U)")
    } else if c == "float" {
        format!("stc_bits_of_real({var})")
    } else if c == "double" {
        format!("stc_bits_of_lreal({var})")
    } else if let Some(bits) = c.strip_prefix("int").and_then(|b| b.strip_suffix("_t")) {
        format!("(uint{bits}_t){var}")
    } else {
        var.to_string()
    }
}

/// The statement that copies one input element into its variable.
fn read_one(
    m: &Module,
    a: &DirectAddress,
    ty: stc_sema::TypeId,
    e: ElemType,
    el: &str,
    var: &str,
    site: &mut dyn FnMut(&DirectAddress) -> u32,
) -> Result<String, Error> {
    let lit = |v: i128| names::literal(e, &Value::Int(v));
    let test = match m.types.kind(ty) {
        TypeKind::Subrange { lo, hi, .. } => {
            let unsigned = names::elem_c(e).starts_with('u');
            if unsigned && *lo == 0 {
                format!("(x <= {})", lit(*hi))
            } else {
                format!("((x >= {}) && (x <= {}))", lit(*lo), lit(*hi))
            }
        }
        TypeKind::Enum { values, .. } => {
            let mut vs: Vec<i128> = values.iter().map(|v| v.value).collect();
            vs.sort_unstable();
            vs.dedup();
            vs.iter()
                .map(|v| format!("(x == {})", lit(*v)))
                .collect::<Vec<_>>()
                .join(" || ")
        }
        _ => return Ok(format!("    {var} = {};", of_bits(e, el))),
    };
    let s = site(a);
    Ok(format!(
        "    {{\n        const {} x = {};\n        if ({test}) {{\n            {var} = x;\n        \
         }} else {{\n            stc_fault((uint32_t)STC_FAULT_SUBRANGE, {s}U);\n        }}\n    }}",
        names::elem_c(e),
        of_bits(e, el)
    ))
}
