//! VMASM: the bytecode as assembler text, and the assembler that reads it
//! back into the identical image.
//!
//! The code is written one instruction per line, POU by POU, with labels at
//! jump targets, the source position of each statement and the name of the
//! variable behind each instance or frame operand as comments. Operands are
//! `f12` (frame offset), `t4` (instance offset) or `@100` (absolute address);
//! jump targets are labels `L7`. The data tables (types, variables,
//! configurations, initial data) follow as a `.tables` block of hex, in the
//! binary format's own encoding, so nothing is lost in the round trip.

use std::collections::BTreeSet;
use std::fmt::Write;

use crate::format::{decode_tables, encode_tables, LoadError};
use crate::image::Image;
use crate::instr::{FieldKind, Instr, Op, Tgt, MNEMONICS, MODE_ABS, MODE_FRAME, MODE_THIS};

/// Writes an image as VMASM text.
pub fn disassemble(img: &Image) -> String {
    let mut out = String::from("; stc VMASM, bytecode format 1\n");
    let targets: BTreeSet<u32> = img
        .code
        .iter()
        .flat_map(|i| {
            let kinds = Instr::field_kinds(i.opcode()).unwrap_or(&[]);
            i.fields()
                .into_iter()
                .zip(kinds.iter())
                .filter(|(_, k)| **k == FieldKind::Target)
                .map(|(f, _)| f)
                .collect::<Vec<_>>()
        })
        .collect();
    let mut starts: Vec<(u32, usize)> = img
        .pous
        .iter()
        .enumerate()
        .map(|(i, p)| (p.entry, i))
        .collect();
    starts.sort();
    let mut line = 0;
    for (pc, ins) in img.code.iter().enumerate() {
        let pc = pc as u32;
        if let Some(&(_, pi)) = starts.iter().find(|(e, _)| *e == pc) {
            if let Some(p) = img.model.pous.get(pi) {
                let _ = writeln!(out, "\n.pou {}  ; {:?} {}", pi, p.kind, p.name);
            }
        }
        while line < img.lines.len() && img.lines[line].pc <= pc {
            let l = img.lines[line];
            if l.pc == pc {
                let file = img
                    .files
                    .get(l.file as usize)
                    .map(|s| s.as_str())
                    .unwrap_or("?");
                let _ = writeln!(out, "    ; {file}:{}:{}", l.line, l.col);
            }
            line += 1;
        }
        if targets.contains(&pc) {
            let _ = writeln!(out, "L{pc}:");
        }
        let kinds = Instr::field_kinds(ins.opcode()).unwrap_or(&[]);
        let args: Vec<String> = ins
            .fields()
            .into_iter()
            .zip(kinds.iter())
            .map(|(f, k)| match k {
                FieldKind::Op(_) => format!("{:?}", Op(f)),
                FieldKind::Target => format!("L{f}"),
                FieldKind::Imm => f.to_string(),
            })
            .collect();
        let comment = operand_names(img, &starts, pc, ins);
        let text = format!("    {} {}", ins.mnemonic(), args.join(", "));
        if comment.is_empty() {
            let _ = writeln!(out, "{}", text.trim_end());
        } else {
            let _ = writeln!(out, "{:<40} ; {comment}", text.trim_end());
        }
    }
    out.push_str("\n.tables\n");
    let tables = encode_tables(img);
    for chunk in tables.chunks(48) {
        out.push_str("    ");
        for b in chunk {
            let _ = write!(out, "{b:02x}");
        }
        out.push('\n');
    }
    out
}

/// The names of the variables an instruction's operands refer to.
fn operand_names(img: &Image, starts: &[(u32, usize)], pc: u32, ins: &Instr) -> String {
    let Some(&(_, pi)) = starts.iter().rev().find(|(e, _)| *e <= pc) else {
        return String::new();
    };
    let Some(pou) = img.model.pous.get(pi) else {
        return String::new();
    };
    let kinds = Instr::field_kinds(ins.opcode()).unwrap_or(&[]);
    let mut names = Vec::new();
    for (f, k) in ins.fields().into_iter().zip(kinds.iter()) {
        if !matches!(k, FieldKind::Op(_)) {
            continue;
        }
        let op = Op(f);
        let name = match op.mode() {
            MODE_THIS => pou
                .vars
                .iter()
                .find(|v| !v.in_frame && v.offset == op.offset())
                .map(|v| v.name.clone()),
            MODE_FRAME => pou
                .vars
                .iter()
                .find(|v| v.in_frame && v.offset == op.offset())
                .map(|v| v.name.clone()),
            MODE_ABS => img
                .model
                .globals
                .iter()
                .find(|g| g.offset == op.offset())
                .map(|g| g.name.clone()),
            _ => None,
        };
        if let Some(n) = name {
            names.push(format!("{op:?}={n}"));
        }
    }
    names.join(" ")
}

/// Reads VMASM text back into an image (verified, like a loaded file).
pub fn assemble(text: &str) -> Result<Image, LoadError> {
    let bad = |line: usize, what: &str| LoadError::Malformed {
        offset: line,
        what: format!("line {line}: {what}"),
    };
    let mut code: Vec<(usize, &str, Vec<&str>)> = Vec::new();
    let mut tables = String::new();
    let mut in_tables = false;
    for (n, raw) in text.lines().enumerate() {
        let line_no = n + 1;
        let line = raw.split(';').next().unwrap_or("").trim();
        if line.is_empty() || line.starts_with(".pou") {
            continue;
        }
        if line == ".tables" {
            in_tables = true;
            continue;
        }
        if in_tables {
            tables.push_str(line);
            continue;
        }
        if line.ends_with(':') && line.starts_with('L') {
            continue;
        }
        let (mn, rest) = line.split_once(char::is_whitespace).unwrap_or((line, ""));
        let args: Vec<&str> = rest
            .split(',')
            .map(|a| a.trim())
            .filter(|a| !a.is_empty())
            .collect();
        code.push((line_no, mn, args));
    }
    let mut instrs = Vec::with_capacity(code.len());
    for (line_no, mn, args) in code {
        let opcode = MNEMONICS
            .iter()
            .position(|m| *m == mn)
            .ok_or_else(|| bad(line_no, &format!("unknown mnemonic `{mn}`")))?
            as u8;
        let kinds = Instr::field_kinds(opcode).unwrap_or(&[]);
        if kinds.len() != args.len() {
            return Err(bad(
                line_no,
                &format!("`{mn}` takes {} operands", kinds.len()),
            ));
        }
        let mut fields = Vec::with_capacity(args.len());
        for (a, k) in args.iter().zip(kinds.iter()) {
            let v = match k {
                FieldKind::Op(_) => parse_op(a).map(|o| o.0),
                FieldKind::Target => a
                    .strip_prefix('L')
                    .and_then(|n| n.parse().ok())
                    .map(|t: u32| Tgt(t).0),
                FieldKind::Imm => a.parse().ok(),
            };
            fields.push(v.ok_or_else(|| bad(line_no, &format!("invalid operand `{a}`")))?);
        }
        instrs.push(
            Instr::from_parts(opcode, &fields)
                .ok_or_else(|| bad(line_no, "malformed instruction"))?,
        );
    }
    if !tables.len().is_multiple_of(2) {
        return Err(bad(0, "the .tables block has an odd number of hex digits"));
    }
    let bytes: Option<Vec<u8>> = (0..tables.len())
        .step_by(2)
        .map(|i| u8::from_str_radix(tables.get(i..i + 2)?, 16).ok())
        .collect();
    let bytes = bytes.ok_or_else(|| bad(0, "the .tables block is not hex"))?;
    let img = decode_tables(&bytes, instrs)?;
    crate::verify::verify(&img).map_err(LoadError::Invalid)?;
    Ok(img)
}

fn parse_op(a: &str) -> Option<Op> {
    let (mode, n) = match a.as_bytes().first()? {
        b'f' => (MODE_FRAME, &a[1..]),
        b't' => (MODE_THIS, &a[1..]),
        b'@' => (MODE_ABS, &a[1..]),
        _ => return None,
    };
    let off: u32 = n.parse().ok()?;
    Some(match mode {
        MODE_FRAME => Op::frame(off),
        MODE_THIS => Op::this(off),
        _ => Op::abs(off),
    })
}
