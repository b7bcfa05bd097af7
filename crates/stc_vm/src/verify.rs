//! The verifier: an image that passes can be run without any risk to the
//! host. It checks every table and every instruction against the memory
//! layout: jump targets stay inside their POU's code, operands stay inside
//! the area their mode addresses (the frame of the POU, the instance of a
//! function block, the data and constant areas), calls name POUs of the
//! right kind and reserve callee frames inside the caller's, standard-call
//! descriptors are well formed, and the call graph has no cycle, so the
//! stack needed is bounded by the largest program frame. Accesses through
//! computed addresses (`load`, `store`, `index`) cannot be proven statically;
//! the interpreter bounds-checks every access anyway.

use crate::image::*;
use crate::instr::{FieldKind, Instr, Op, MODE_ABS, MODE_FRAME, MODE_THIS};
use crate::num::Num;

/// The memory model's limit (one constant with the layout's).
const MAX_MEMORY: u64 = stc_ir::layout::MAX_SIZE;

pub fn verify(img: &Image) -> Result<(), String> {
    if img.pous.len() != img.model.pous.len() {
        return Err("the POUs' code and model do not match".into());
    }
    if img.init.len() as u64 != img.data_size as u64 {
        return Err("the initial data does not match the data size".into());
    }
    if img.memory_size() > MAX_MEMORY {
        return Err("the program needs more than 1 GiB of memory".into());
    }
    let code_len = img.code.len() as u32;
    // Types.
    for t in &img.model.types {
        match t {
            TypeDesc::Array { elem, .. } => type_ok(img, *elem)?,
            TypeDesc::Struct { fields, .. } => {
                for f in fields {
                    type_ok(img, f.ty)?;
                }
            }
            TypeDesc::Instance { pou } if *pou as usize >= img.pous.len() => {
                return Err("a type names an unknown POU".into())
            }
            TypeDesc::Subrange { base, lo, hi } => {
                let (min, max) =
                    stc_values::int_range(*base).ok_or("a subrange of a non-integer type")?;
                if lo > hi || *lo < min || *hi > max {
                    return Err("a subrange with invalid bounds".into());
                }
            }
            _ => {}
        }
    }
    // POUs and the code ranges they own.
    let mut ranges: Vec<(u32, usize)> = Vec::new();
    for (i, p) in (0..img.pous.len()).filter_map(|i| Some((i, img.pou(i)?))) {
        if p.entry >= code_len {
            return Err(format!("POU `{}` starts outside the code", p.name));
        }
        let (t0, tl) = p.frame_template;
        if t0 as u64 + tl as u64 > img.consts.len() as u64
            || p.frame_init_at as u64 + tl as u64 > p.frame_size as u64
        {
            return Err(format!("POU `{}` has an invalid frame template", p.name));
        }
        if p.kind == PouKind::Function && p.instance_size != 0 {
            return Err(format!("function `{}` has an instance", p.name));
        }
        type_ok(img, p.instance_type)?;
        for v in p.vars {
            type_ok(img, v.ty)?;
        }
        ranges.push((p.entry, i));
    }
    ranges.sort();
    if let Some(w) = ranges.windows(2).find(|w| w[0].0 == w[1].0) {
        return Err(format!(
            "two POUs share their first instruction ({})",
            w[0].0
        ));
    }
    if ranges.first().is_some_and(|r| r.0 != 0) && code_len > 0 {
        return Err("instructions before the first POU".into());
    }
    // Each instruction, in the context of the POU that owns it.
    let mut edges: Vec<Vec<usize>> = vec![Vec::new(); img.pous.len()];
    for (k, &(start, pi)) in ranges.iter().enumerate() {
        let end = ranges.get(k + 1).map_or(code_len, |r| r.0);
        let pou = &img.pou(pi).ok_or("a POU without code")?;
        for pc in start..end {
            let ins = &img.code[pc as usize];
            instr_ok(img, pou, ins, start, end, &mut edges[pi]).map_err(|e| {
                format!(
                    "instruction {pc} ({}) in `{}`: {e}",
                    ins.mnemonic(),
                    pou.name
                )
            })?;
        }
    }
    // No recursion: the call graph is acyclic.
    let mut state = vec![0u8; img.pous.len()];
    for s in 0..img.pous.len() {
        if state[s] != 0 {
            continue;
        }
        let mut stack = vec![(s, 0usize)];
        state[s] = 1;
        while let Some(&mut (v, ref mut i)) = stack.last_mut() {
            if let Some(&w) = edges[v].get(*i) {
                *i += 1;
                match state[w] {
                    0 => {
                        state[w] = 1;
                        stack.push((w, 0));
                    }
                    1 => return Err(format!("POU `{}` is recursive", img.model.pous[w].name)),
                    _ => {}
                }
            } else {
                state[v] = 2;
                stack.pop();
            }
        }
    }
    // Calls nest no deeper than the interpreter allows (longest chain in
    // the acyclic call graph, from its sinks up).
    let mut depth = vec![0usize; img.pous.len()];
    let mut done = vec![false; img.pous.len()];
    for s in 0..img.pous.len() {
        let mut stack = vec![(s, false)];
        while let Some((v, expanded)) = stack.pop() {
            if done[v] {
                continue;
            }
            if expanded {
                depth[v] = 1 + edges[v].iter().map(|&w| depth[w]).max().unwrap_or(0);
                done[v] = true;
            } else {
                stack.push((v, true));
                stack.extend(edges[v].iter().filter(|&&w| !done[w]).map(|&w| (w, false)));
            }
        }
    }
    if let Some(p) = depth
        .iter()
        .position(|&d| d > crate::interp::MAX_CALL_DEPTH)
    {
        return Err(format!(
            "calls from `{}` nest deeper than {} levels",
            img.model.pous[p].name,
            crate::interp::MAX_CALL_DEPTH
        ));
    }
    // Program instances, globals, the process image.
    let data = img.data_size as u64;
    let abs_end = data + img.consts.len() as u64;
    let programs = img.model.programs.iter().chain(
        img.model
            .configs
            .iter()
            .flat_map(|c| c.resources.iter().flat_map(|r| r.programs.iter())),
    );
    for p in programs {
        let pou = img
            .pou(p.pou as usize)
            .ok_or("a program instance names an unknown POU")?;
        if pou.kind != PouKind::Program {
            return Err(format!("program instance `{}` is not of a PROGRAM", p.name));
        }
        if p.offset as u64 + pou.instance_size as u64 > data {
            return Err(format!(
                "program instance `{}` lies outside the data area",
                p.name
            ));
        }
        if pou.frame_size > img.stack_size {
            return Err(format!("the stack is too small for program `{}`", pou.name));
        }
        for (off, ty, Source::Addr { offset, ty: sty }) in p.inputs.iter().chain(p.outputs.iter()) {
            type_ok(img, *ty)?;
            type_ok(img, *sty)?;
            if *off as u64 + value_size(img, *ty)? > pou.instance_size as u64
                || *offset as u64 + value_size(img, *sty)? > abs_end
            {
                return Err(format!("a connection of `{}` lies outside memory", p.name));
            }
        }
    }
    for c in &img.model.configs {
        for r in &c.resources {
            for t in &r.tasks {
                if let Some(Source::Addr { offset, ty }) = &t.single {
                    type_ok(img, *ty)?;
                    if *offset as u64 + 1 > abs_end {
                        return Err(format!(
                            "the SINGLE input of task `{}` lies outside memory",
                            t.name
                        ));
                    }
                }
            }
            for p in &r.programs {
                if p.task.is_some_and(|t| t as usize >= r.tasks.len()) {
                    return Err(format!(
                        "program instance `{}` names an unknown task",
                        p.name
                    ));
                }
            }
        }
    }
    for g in &img.model.globals {
        type_ok(img, g.ty)?;
        if g.offset as u64 + value_size(img, g.ty)? > data {
            return Err(format!("global `{}` lies outside the data area", g.name));
        }
    }
    for s in &img.model.io {
        type_ok(img, s.ty)?;
        if s.offset as u64 + value_size(img, s.ty)? > data {
            return Err(format!(
                "process image slot {} lies outside the data area",
                s.address
            ));
        }
    }
    let mut last = None;
    for l in &img.lines {
        if last.is_some_and(|p| l.pc < p)
            || l.pc > code_len
            || l.pou as usize >= img.pous.len()
            || l.file as usize >= img.files.len().max(1)
        {
            return Err("the line table is invalid".into());
        }
        last = Some(l.pc);
    }
    Ok(())
}

fn type_ok(img: &Image, t: TypeRef) -> Result<(), String> {
    if (t as usize) < img.model.types.len() {
        Ok(())
    } else {
        Err(format!("type index {t} is out of range"))
    }
}

/// The size in bytes of a value of a type, at most the memory's (so
/// offsets plus sizes cannot overflow).
fn value_size(img: &Image, t: TypeRef) -> Result<u64, String> {
    img.checked_type_size(t)
        .filter(|&n| n <= MAX_MEMORY)
        .ok_or_else(|| format!("type {t} is larger than the memory"))
}

/// An operand of `size` bytes in the context of POU `pou`.
fn op_ok(img: &Image, pou: &PouView, op: Op, size: u64) -> Result<(), String> {
    let end = op.offset() as u64 + size;
    let ok = match op.mode() {
        MODE_FRAME => end <= pou.frame_size as u64,
        MODE_THIS => pou.kind != PouKind::Function && end <= pou.instance_size as u64,
        MODE_ABS => end <= img.data_size as u64 + img.consts.len() as u64,
        _ => false,
    };
    if ok {
        Ok(())
    } else {
        Err(format!(
            "operand {op:?} of {size} bytes is outside its area"
        ))
    }
}

fn instr_ok(
    img: &Image,
    pou: &PouView,
    ins: &Instr,
    start: u32,
    end: u32,
    edges: &mut Vec<usize>,
) -> Result<(), String> {
    let kinds = Instr::field_kinds(ins.opcode()).ok_or("unknown opcode")?;
    let fields = ins.fields();
    // A comparison writes a BOOL whatever the width of its operands.
    let mn = ins.mnemonic();
    let compares = ["eq.", "ne.", "lt.", "le."]
        .iter()
        .any(|p| mn.starts_with(p));
    // `lea` writes a 4-byte address of its operand, which may be smaller
    // (an INT at the end of an instance): only its start must be inside.
    let lea = matches!(ins, Instr::Lea { .. });
    for (i, (k, &f)) in kinds.iter().zip(fields.iter()).enumerate() {
        match k {
            FieldKind::Target if f < start || f >= end => {
                return Err(format!("jump to {f} leaves the POU"))
            }
            FieldKind::Op(n) if *n > 0 => {
                let size = if (compares && i == 0) || (lea && i == 1) {
                    if lea {
                        0
                    } else {
                        1
                    }
                } else {
                    *n as u64
                };
                op_ok(img, pou, Op(f), size)?
            }
            _ => {}
        }
    }
    let num = |c: u32| Num::from_code(c).ok_or_else(|| format!("unknown scalar code {c}"));
    match *ins {
        Instr::Copy { d, a, len } => {
            op_ok(img, pou, d, len as u64)?;
            op_ok(img, pou, a, len as u64)?;
        }
        Instr::StrCopy { d, a, cap, unit } => {
            if unit != 1 && unit != 2 {
                return Err("a string unit must be 1 or 2 bytes".into());
            }
            op_ok(img, pou, d, 2 + cap as u64 * unit as u64)?;
            op_ok(img, pou, a, 2)?;
        }
        Instr::Cvt { d, a, from, to } => {
            op_ok(img, pou, a, num(from)?.size() as u64)?;
            op_ok(img, pou, d, num(to)?.size() as u64)?;
        }
        Instr::Check { a, lo, hi, num: n } => {
            let s = num(n)?.size() as u64;
            op_ok(img, pou, a, s)?;
            op_ok(img, pou, lo, s)?;
            op_ok(img, pou, hi, s)?;
        }
        Instr::GetPart {
            d, a, width, part, ..
        }
        | Instr::SetPart {
            d, a, width, part, ..
        } => {
            if !matches!(width, 8 | 16 | 32 | 64) || !matches!(part, 1 | 8 | 16 | 32) {
                return Err("invalid part access widths".into());
            }
            let (dw, aw) = if matches!(ins, Instr::GetPart { .. }) {
                (part.max(8), width)
            } else {
                (width, part.max(8))
            };
            op_ok(img, pou, d, dw as u64 / 8)?;
            op_ok(img, pou, a, aw as u64 / 8)?;
        }
        Instr::Elem { d, a, idx, desc } | Instr::ElemP { d, p: a, idx, desc } => {
            let e = elem_ok(img, desc)?;
            op_ok(img, pou, d, 4)?;
            op_ok(img, pou, idx, e.num.size() as u64)?;
            let span = if matches!(ins, Instr::Elem { .. }) {
                elem_span(&e, 1)
            } else {
                4
            };
            op_ok(img, pou, a, span)?;
        }
        Instr::LdElem1 { d: v, a, idx, desc }
        | Instr::LdElem2 { d: v, a, idx, desc }
        | Instr::LdElem4 { d: v, a, idx, desc }
        | Instr::LdElem8 { d: v, a, idx, desc }
        | Instr::StElem1 { a, idx, v, desc }
        | Instr::StElem2 { a, idx, v, desc }
        | Instr::StElem4 { a, idx, v, desc }
        | Instr::StElem8 { a, idx, v, desc } => {
            let e = elem_ok(img, desc)?;
            let n = elem_width(ins);
            op_ok(img, pou, v, n)?;
            op_ok(img, pou, idx, e.num.size() as u64)?;
            op_ok(img, pou, a, elem_span(&e, n))?;
        }
        Instr::Ld1 { d: a, p, .. }
        | Instr::Ld2 { d: a, p, .. }
        | Instr::Ld4 { d: a, p, .. }
        | Instr::Ld8 { d: a, p, .. }
        | Instr::St1 { p, a, .. }
        | Instr::St2 { p, a, .. }
        | Instr::St4 { p, a, .. }
        | Instr::St8 { p, a, .. } => {
            op_ok(img, pou, a, elem_width(ins))?;
            op_ok(img, pou, p, 4)?;
        }
        Instr::Min { d, a, b, num: n } | Instr::Max { d, a, b, num: n } => {
            let s = num(n)?.size() as u64;
            for o in [d, a, b] {
                op_ok(img, pou, o, s)?;
            }
        }
        Instr::Limit {
            d,
            lo,
            a,
            hi,
            num: n,
        } => {
            let s = num(n)?.size() as u64;
            for o in [d, lo, a, hi] {
                op_ok(img, pou, o, s)?;
            }
        }
        Instr::Abs { d, a, num: n } => {
            let s = num(n)?.size() as u64;
            op_ok(img, pou, d, s)?;
            op_ok(img, pou, a, s)?;
        }
        Instr::Shift {
            d,
            a,
            n,
            op,
            num: k,
            nnum,
        } => {
            let (k, nk) = (num(k)?, num(nnum)?);
            if k.is_float() || nk.is_float() || op > 3 {
                return Err("invalid shift".into());
            }
            op_ok(img, pou, d, k.size() as u64)?;
            op_ok(img, pou, a, k.size() as u64)?;
            op_ok(img, pou, n, nk.size() as u64)?;
        }
        Instr::Sel { d, g, a, b, len } => {
            op_ok(img, pou, g, 1)?;
            for o in [d, a, b] {
                op_ok(img, pou, o, len as u64)?;
            }
        }
        Instr::Load { d, p, len, .. } => {
            op_ok(img, pou, d, len as u64)?;
            op_ok(img, pou, p, 4)?;
        }
        Instr::Store { p, a, len, .. } => {
            op_ok(img, pou, a, len as u64)?;
            op_ok(img, pou, p, 4)?;
        }
        Instr::CallFn { pou: callee, frame } => {
            let c = img.pou(callee as usize).ok_or("call of an unknown POU")?;
            if c.kind != PouKind::Function {
                return Err(format!("`{}` is not a function", c.name));
            }
            frame_ok(pou, &c, frame)?;
            edges.push(callee as usize);
        }
        Instr::CallFb {
            pou: callee,
            inst,
            frame,
        }
        | Instr::CallFbInd {
            pou: callee,
            inst,
            frame,
        } => {
            let c = img.pou(callee as usize).ok_or("call of an unknown POU")?;
            if c.kind == PouKind::Function {
                return Err(format!("`{}` is a function, not a function block", c.name));
            }
            if matches!(ins, Instr::CallFb { .. }) {
                op_ok(img, pou, inst, c.instance_size as u64)?;
            }
            frame_ok(pou, &c, frame)?;
            edges.push(callee as usize);
        }
        Instr::Std { call } => {
            let c = img
                .calls
                .get(call as usize)
                .ok_or("unknown standard call")?;
            for &(op, e, cap) in c.args.iter().chain(std::iter::once(&c.result)) {
                let size = match e {
                    stc_syntax::token::ElemType::String => 2 + cap as u64,
                    stc_syntax::token::ElemType::Wstring => 2 + 2 * cap as u64,
                    e => stc_ir::layout::elem_size(e) as u64,
                };
                op_ok(img, pou, op, size)?;
            }
        }
        Instr::Fault { kind } if stc_ir::FaultKind::from_code(kind).is_none() => {
            return Err("unknown fault kind".into())
        }
        _ => {}
    }
    Ok(())
}

fn elem_ok(img: &Image, desc: u32) -> Result<ElemDesc, String> {
    let e = *img
        .elems
        .get(desc as usize)
        .ok_or("unknown array dimension descriptor")?;
    if e.num.is_float() {
        return Err("an array index must be an integer".into());
    }
    Ok(e)
}

/// The bytes from an array's base that an access of `n` bytes may touch.
fn elem_span(e: &ElemDesc, n: u64) -> u64 {
    if e.count == 0 {
        0
    } else {
        (e.count as u64 - 1) * e.stride as u64 + n
    }
}

/// The width of a sized load or store.
fn elem_width(ins: &Instr) -> u64 {
    let mn = ins.mnemonic();
    mn.rsplit('.')
        .next()
        .and_then(|w| w.parse().ok())
        .unwrap_or(8)
}

/// A callee's frame must lie inside the caller's.
fn frame_ok(caller: &PouView, callee: &PouView, frame: u32) -> Result<(), String> {
    if frame as u64 + callee.frame_size as u64 <= caller.frame_size as u64 {
        Ok(())
    } else {
        Err(format!(
            "the frame of `{}` does not fit in the caller's",
            callee.name
        ))
    }
}
