//! The circuit as a `NOB_FLAT` XML document (seed 004, listings 1.1 and
//! 5.2): [`write`] and [`read`], inverse of each other. The dialect's XSD is
//! `crates/stc_netlist/netlist.xsd`; docs/netlist.md describes it.
//!
//! A document is `<NOB_FLAT FileName=... Version="1.0">` with an empty
//! `<LIBRARY/>` and a `<DESIGN>` holding an empty `<BUSSTRUCTURE/>` and one
//! `<I>` per component, in an order where every combinational input is
//! driven by an earlier component (the reader does not rely on it: it sorts
//! the components itself). An `<I>` names its library component
//! (`Name="AF_ADD"`), has a unique `ID`, its parameters as `<A Key Value>`
//! and its pins as `<PIN Name Net>` with `PINDIR` (I or O), and for an
//! output pin the `PINTYPE` of the net it drives.
//! Nets are named `N1`, `N2`... in the order of their drivers. The same
//! circuit always gives the same bytes.

use quick_xml::events::{BytesStart, Event};
use quick_xml::Reader;
use rustc_hash::FxHashMap;
use stc_ir::FaultKind;
use stc_values::{ElemType, Value};

use crate::circuit::{Circuit, Component, Kind, NetId};
use crate::library::{self as lib, parse_value, pin_type, type_of_pin, value_text};

/// The version of the dialect written in `Version`.
pub const VERSION: &str = "1.0";

/// The parameters (`<A>`) of a component, in the order they are written.
fn params(k: &Kind) -> Vec<(&'static str, String)> {
    match k {
        Kind::Input {
            name,
            init,
            aliases,
        }
        | Kind::Register {
            name,
            init,
            aliases,
        } => {
            let mut v = vec![("V1", name.clone()), ("INIT", value_text(init))];
            v.extend(aliases.iter().map(|a| ("ALIAS", a.clone())));
            v
        }
        Kind::Const(v) => vec![("V1", value_text(v))],
        Kind::Output { name } => vec![("V1", name.clone())],
        Kind::Fault {
            instance,
            pou,
            file,
            line,
            col,
        } => vec![
            ("INSTANCE", instance.clone()),
            ("POU", pou.clone()),
            ("FILE", file.clone()),
            ("LINE", line.to_string()),
            ("COL", col.to_string()),
        ],
        Kind::Index { lo } => vec![("LO", lo.to_string())],
        Kind::Range { lo, hi, fault } => vec![
            ("LO", lo.to_string()),
            ("HI", hi.to_string()),
            ("FAULT", fault.code().to_string()),
        ],
        Kind::Call(f) => vec![("FUNC", lib::function_name(*f).unwrap_or("?").to_string())],
        Kind::PartGet { bits, pos } | Kind::PartSet { bits, pos } => {
            vec![("BITS", bits.to_string()), ("POS", pos.to_string())]
        }
        Kind::Clock | Kind::Switch | Kind::Binary(_) | Kind::Unary(_) | Kind::Convert => vec![],
    }
}

/// The document of a circuit.
///
/// Written as text directly (with `quick_xml`'s escaping of attribute
/// values): the document of a large program has millions of elements, and
/// an event writer's allocation per attribute tripled the time of the whole
/// command. [`read`] parses it with `quick_xml`'s reader.
pub fn write(c: &Circuit) -> String {
    use std::fmt::Write as _;
    let mut out = String::with_capacity(64 + c.components.len() * 320);
    let esc = |s: &str| quick_xml::escape::escape(s).into_owned();
    // (Writing into a String cannot fail.)
    let _ = write!(
        out,
        "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<NOB_FLAT FileName=\"{}\" Version=\"{VERSION}\" Generator=\"stc\">\n <LIBRARY/>\n <DESIGN>\n  <BUSSTRUCTURE/>\n",
        esc(&c.name)
    );
    for (i, comp) in c.components.iter().enumerate() {
        let _ = writeln!(
            out,
            "  <I Name=\"{}\" ID=\"U{}\">",
            lib::name_of(&comp.kind),
            i + 1
        );
        for (k, v) in params(&comp.kind) {
            let _ = writeln!(out, "   <A Key=\"{k}\" Value=\"{}\"/>", esc(&v));
        }
        for (j, n) in comp.inputs.iter().enumerate() {
            let _ = write!(
                out,
                "   <PIN Name=\"A{}\" Net=\"N{}\">\n    <A Key=\"PINDIR\" Value=\"I\"/>\n   </PIN>\n",
                j + 1,
                n.0 + 1
            );
        }
        for (j, n) in comp.outputs.iter().enumerate() {
            // A net's type is on its driver's pin (as in the seed).
            let ty = c.nets.get(n.index()).map(|t| pin_type(*t)).unwrap_or("?");
            let _ = write!(
                out,
                "   <PIN Name=\"{}\" Net=\"N{}\">\n    <A Key=\"PINDIR\" Value=\"O\"/>\n    <A Key=\"PINTYPE\" Value=\"{ty}\"/>\n   </PIN>\n",
                if j == 0 { "X1" } else { "F1" },
                n.0 + 1
            );
        }
        out.push_str("  </I>\n");
    }
    out.push_str(" </DESIGN>\n</NOB_FLAT>\n");
    out
}

/// A document that is not a circuit stc can read.
#[derive(Debug, thiserror::Error, PartialEq, Eq)]
pub enum ReadError {
    #[error("malformed XML: {0}")]
    Xml(String),
    #[error("not a NOB_FLAT circuit: {0}")]
    Structure(String),
    #[error("the circuit has a combinational loop (through component {0})")]
    Loop(String),
}

struct RawPin {
    name: String,
    net: String,
    dir: String,
    ty: String,
}

struct RawInst {
    name: String,
    id: String,
    params: Vec<(String, String)>,
    pins: Vec<RawPin>,
}

fn attrs(e: &BytesStart<'_>) -> Result<Vec<(String, String)>, ReadError> {
    let mut out = Vec::new();
    for a in e.attributes() {
        let a = a.map_err(|e| ReadError::Xml(e.to_string()))?;
        let k = String::from_utf8_lossy(a.key.as_ref()).into_owned();
        let v = a
            .unescape_value()
            .map_err(|e| ReadError::Xml(e.to_string()))?
            .into_owned();
        out.push((k, v));
    }
    Ok(out)
}

fn get<'a>(list: &'a [(String, String)], key: &str) -> Option<&'a str> {
    list.iter().find(|(k, _)| k == key).map(|(_, v)| v.as_str())
}

fn structure(msg: impl Into<String>) -> ReadError {
    ReadError::Structure(msg.into())
}

/// Reads a document written by [`write`] (or by hand, in the same dialect)
/// back into a circuit, with its components sorted so that every
/// combinational input is computed before it is used.
pub fn read(text: &str) -> Result<Circuit, ReadError> {
    let mut r = Reader::from_str(text);
    r.config_mut().trim_text(true);
    let mut name = None;
    let mut insts: Vec<RawInst> = Vec::new();
    let mut cur: Option<RawInst> = None;
    let mut pin: Option<RawPin> = None;
    loop {
        let ev = r.read_event().map_err(|e| ReadError::Xml(e.to_string()))?;
        let (e, empty) = match ev {
            Event::Eof => break,
            Event::Start(e) => (e, false),
            Event::Empty(e) => (e, true),
            Event::End(e) => {
                match e.name().as_ref() {
                    b"PIN" => {
                        let p = pin
                            .take()
                            .ok_or_else(|| structure("</PIN> without <PIN>"))?;
                        cur.as_mut()
                            .ok_or_else(|| structure("<PIN> outside <I>"))?
                            .pins
                            .push(p);
                    }
                    b"I" => insts.push(cur.take().ok_or_else(|| structure("</I> without <I>"))?),
                    _ => {}
                }
                continue;
            }
            _ => continue,
        };
        let a = attrs(&e)?;
        match e.name().as_ref() {
            b"NOB_FLAT" => name = Some(get(&a, "FileName").unwrap_or("").to_string()),
            b"I" => {
                if cur.is_some() {
                    return Err(structure("<I> inside <I>"));
                }
                let inst = RawInst {
                    name: get(&a, "Name")
                        .ok_or_else(|| structure("<I> without Name"))?
                        .to_string(),
                    id: get(&a, "ID").unwrap_or("?").to_string(),
                    params: Vec::new(),
                    pins: Vec::new(),
                };
                if empty {
                    insts.push(inst);
                } else {
                    cur = Some(inst);
                }
            }
            b"PIN" => {
                let p = RawPin {
                    name: get(&a, "Name")
                        .ok_or_else(|| structure("<PIN> without Name"))?
                        .to_string(),
                    net: get(&a, "Net")
                        .ok_or_else(|| structure("<PIN> without Net"))?
                        .to_string(),
                    dir: String::new(),
                    ty: String::new(),
                };
                if empty {
                    return Err(structure(format!("pin {} without PINDIR", p.name)));
                }
                pin = Some(p);
            }
            b"A" => {
                let k = get(&a, "Key")
                    .ok_or_else(|| structure("<A> without Key"))?
                    .to_string();
                let v = get(&a, "Value").unwrap_or("").to_string();
                if let Some(p) = pin.as_mut() {
                    match k.as_str() {
                        "PINDIR" => p.dir = v,
                        "PINTYPE" => p.ty = v,
                        _ => {}
                    }
                } else if let Some(i) = cur.as_mut() {
                    i.params.push((k, v));
                }
            }
            _ => {}
        }
    }
    let name = name.ok_or_else(|| structure("no NOB_FLAT element"))?;
    build(name, insts)
}

fn build(name: String, insts: Vec<RawInst>) -> Result<Circuit, ReadError> {
    // Nets: named by their driver's pin.
    let mut nets: Vec<ElemType> = Vec::new();
    let mut by_name: FxHashMap<String, NetId> = FxHashMap::default();
    let mut driver: Vec<usize> = Vec::new();
    for (i, inst) in insts.iter().enumerate() {
        for p in inst.pins.iter().filter(|p| p.dir == "O") {
            let t = type_of_pin(&p.ty).ok_or_else(|| {
                structure(format!(
                    "{}: pin {} has the unknown PINTYPE `{}`",
                    inst.id, p.name, p.ty
                ))
            })?;
            let id = NetId(nets.len() as u32);
            if by_name.insert(p.net.clone(), id).is_some() {
                return Err(structure(format!("net {} has two drivers", p.net)));
            }
            nets.push(t);
            driver.push(i);
        }
    }
    let mut comps = Vec::with_capacity(insts.len());
    for inst in &insts {
        let mut inputs: Vec<(usize, NetId)> = Vec::new();
        let mut outputs: Vec<(usize, NetId)> = Vec::new();
        for p in &inst.pins {
            let net = *by_name
                .get(&p.net)
                .ok_or_else(|| structure(format!("net {} has no driver", p.net)))?;
            let num: usize = p.name.get(1..).and_then(|s| s.parse().ok()).unwrap_or(0);
            match (p.dir.as_str(), p.name.chars().next()) {
                ("I", Some('A')) if num >= 1 => inputs.push((num, net)),
                ("O", Some('X')) if num == 1 => outputs.push((0, net)),
                ("O", Some('F')) if num == 1 => outputs.push((1, net)),
                _ => {
                    return Err(structure(format!(
                        "{}: unexpected pin {} ({})",
                        inst.id, p.name, p.dir
                    )))
                }
            }
        }
        inputs.sort_by_key(|(k, _)| *k);
        outputs.sort_by_key(|(k, _)| *k);
        if inputs.iter().enumerate().any(|(j, (k, _))| *k != j + 1) {
            return Err(structure(format!("{}: input pins are not A1..An", inst.id)));
        }
        let inputs: crate::circuit::Pins = inputs.into_iter().map(|(_, n)| n).collect();
        let outputs: crate::circuit::Outs = outputs.into_iter().map(|(_, n)| n).collect();
        let kind = kind_of(inst, &inputs, &outputs, &nets)?;
        check_arity(inst, &kind, inputs.len(), outputs.len())?;
        comps.push(Component {
            kind,
            inputs,
            outputs,
        });
    }
    let order = topo(&comps, &driver, &insts)?;
    // Renumber so the circuit is in evaluation order, nets by driver.
    let mut renum = vec![NetId(0); nets.len()];
    let mut new_nets = Vec::with_capacity(nets.len());
    for &i in &order {
        for o in &comps[i].outputs {
            renum[o.index()] = NetId(new_nets.len() as u32);
            new_nets.push(nets[o.index()]);
        }
    }
    let mut slots: Vec<Option<Component>> = comps.into_iter().map(Some).collect();
    let mut components = Vec::with_capacity(slots.len());
    for i in order {
        if let Some(mut c) = slots[i].take() {
            for n in c.inputs.iter_mut().chain(c.outputs.iter_mut()) {
                *n = renum[n.index()];
            }
            components.push(c);
        }
    }
    Ok(Circuit {
        name,
        nets: new_nets,
        components,
    })
}

fn check_arity(inst: &RawInst, k: &Kind, ins: usize, outs: usize) -> Result<(), ReadError> {
    let (want_in, want_out): (Option<usize>, &[usize]) = match k {
        Kind::Input { .. } | Kind::Clock | Kind::Const(_) => (Some(0), &[1]),
        Kind::Register { .. } => (Some(1), &[1]),
        Kind::Output { .. } => (Some(1), &[0]),
        Kind::Fault { .. } => (Some(2), &[0]),
        Kind::Switch => (Some(3), &[1, 2]),
        Kind::Index { .. } => (None, &[1, 2]),
        Kind::Range { .. } => (Some(1), &[1, 2]),
        Kind::Binary(_) => (Some(2), &[1, 2]),
        Kind::Unary(_) | Kind::Convert => (Some(1), &[1, 2]),
        Kind::Call(_) => (None, &[1, 2]),
        Kind::PartGet { .. } => (Some(1), &[1]),
        Kind::PartSet { .. } => (Some(2), &[1]),
    };
    if want_in.is_some_and(|n| n != ins)
        || !want_out.contains(&outs)
        || (want_in.is_none() && ins == 0)
    {
        return Err(structure(format!(
            "{} ({}): {ins} inputs and {outs} outputs is not its shape",
            inst.id, inst.name
        )));
    }
    Ok(())
}

fn kind_of(
    inst: &RawInst,
    inputs: &[NetId],
    outputs: &[NetId],
    nets: &[ElemType],
) -> Result<Kind, ReadError> {
    let p = |k: &str| get(&inst.params, k);
    let need =
        |k: &str| p(k).ok_or_else(|| structure(format!("{} ({}) has no {k}", inst.id, inst.name)));
    let out_ty = outputs.first().map(|n| nets[n.index()]);
    let in_ty = inputs.first().map(|n| nets[n.index()]);
    let value = |k: &str| -> Result<Value, ReadError> {
        let t = out_ty.ok_or_else(|| structure(format!("{} has no output", inst.id)))?;
        parse_value(t, need(k)?).ok_or_else(|| structure(format!("{}: bad value for {k}", inst.id)))
    };
    let int = |k: &str| -> Result<i128, ReadError> {
        need(k)?
            .parse::<i128>()
            .map_err(|_| structure(format!("{}: {k} is not an integer", inst.id)))
    };
    let aliases = || {
        inst.params
            .iter()
            .filter(|(k, _)| k == "ALIAS")
            .map(|(_, v)| v.clone())
            .collect::<Vec<_>>()
    };
    let name = inst.name.as_str();
    Ok(match name {
        lib::INPUT => Kind::Input {
            name: need("V1")?.to_string(),
            init: value("INIT")?,
            aliases: aliases(),
        },
        lib::REGISTER => Kind::Register {
            name: need("V1")?.to_string(),
            init: value("INIT")?,
            aliases: aliases(),
        },
        lib::CLOCK => Kind::Clock,
        lib::CONST => Kind::Const(value("V1")?),
        lib::OUTPUT => Kind::Output {
            name: need("V1")?.to_string(),
        },
        lib::FAULT => Kind::Fault {
            instance: need("INSTANCE")?.to_string(),
            pou: need("POU")?.to_string(),
            file: need("FILE")?.to_string(),
            line: int("LINE")? as u32,
            col: int("COL")? as u32,
        },
        lib::SWITCH => Kind::Switch,
        lib::INDEX => Kind::Index { lo: int("LO")? },
        lib::RANGE => Kind::Range {
            lo: int("LO")?,
            hi: int("HI")?,
            fault: u32::try_from(int("FAULT")?)
                .ok()
                .and_then(FaultKind::from_code)
                .ok_or_else(|| structure(format!("{}: unknown FAULT", inst.id)))?,
        },
        lib::CONVERT => Kind::Convert,
        lib::PART_GET | lib::PART_SET => {
            let small = |k: &str| -> Result<u32, ReadError> {
                u32::try_from(int(k)?)
                    .ok()
                    .filter(|v| *v <= 64)
                    .ok_or_else(|| structure(format!("{}: {k} is out of range", inst.id)))
            };
            let (bits, pos) = (small("BITS")?, small("POS")?);
            if bits == 0 {
                return Err(structure(format!("{}: BITS is 0", inst.id)));
            }
            if name == lib::PART_GET {
                Kind::PartGet { bits, pos }
            } else {
                Kind::PartSet { bits, pos }
            }
        }
        lib::CALL => {
            let f = need("FUNC")?;
            let (Some(from), Some(to)) = (in_ty, out_ty) else {
                return Err(structure(format!("{}: a call needs pins", inst.id)));
            };
            Kind::Call(
                lib::function_of(f, from, to)
                    .ok_or_else(|| structure(format!("{}: unknown FUNC {f}", inst.id)))?,
            )
        }
        _ => {
            if let Some((op, _)) = lib::BINARY.iter().find(|(_, n)| *n == name) {
                Kind::Binary(*op)
            } else if let Some((op, _)) = lib::UNARY.iter().find(|(_, n)| *n == name) {
                Kind::Unary(*op)
            } else {
                return Err(structure(format!(
                    "{}: `{name}` is not a component of the library",
                    inst.id
                )));
            }
        }
    })
}

/// An evaluation order: registers, sources first; every other component
/// after the drivers of its inputs (Kahn's algorithm, stable by position).
fn topo(comps: &[Component], driver: &[usize], insts: &[RawInst]) -> Result<Vec<usize>, ReadError> {
    let n = comps.len();
    let mut pending = vec![0usize; n];
    let mut users: Vec<Vec<usize>> = vec![Vec::new(); n];
    for (i, c) in comps.iter().enumerate() {
        if matches!(c.kind, Kind::Register { .. }) {
            continue;
        }
        for net in &c.inputs {
            let d = driver[net.index()];
            pending[i] += 1;
            users[d].push(i);
        }
    }
    let mut ready: std::collections::BinaryHeap<std::cmp::Reverse<usize>> = (0..n)
        .filter(|&i| pending[i] == 0)
        .map(std::cmp::Reverse)
        .collect();
    let mut order = Vec::with_capacity(n);
    while let Some(std::cmp::Reverse(i)) = ready.pop() {
        order.push(i);
        for &u in &users[i] {
            pending[u] -= 1;
            if pending[u] == 0 {
                ready.push(std::cmp::Reverse(u));
            }
        }
    }
    if order.len() != n {
        let stuck = (0..n).find(|&i| pending[i] > 0).unwrap_or(0);
        return Err(ReadError::Loop(insts[stuck].id.clone()));
    }
    Ok(order)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn doc(body: &str) -> String {
        format!(
            "<?xml version=\"1.0\"?><NOB_FLAT FileName=\"T\" Version=\"1.0\"><LIBRARY/><DESIGN>{body}</DESIGN></NOB_FLAT>"
        )
    }

    fn pin(name: &str, net: &str, dir: &str, ty: Option<&str>) -> String {
        let t = ty
            .map(|t| format!("<A Key=\"PINTYPE\" Value=\"{t}\"/>"))
            .unwrap_or_default();
        format!("<PIN Name=\"{name}\" Net=\"{net}\"><A Key=\"PINDIR\" Value=\"{dir}\"/>{t}</PIN>")
    }

    #[test]
    fn a_written_circuit_reads_back_the_same() {
        let mut b = crate::build::Builder::new("M".into());
        let x = b.add(
            Kind::Input {
                name: "M.x".into(),
                init: Value::Int(3),
                aliases: vec![],
            },
            &[],
            Some(ElemType::Int),
        );
        let one = b.konst(ElemType::Int, Value::Int(1));
        let (s, _) = b.op(
            Kind::Binary(stc_values::BinOp::Add),
            &[x, one],
            ElemType::Int,
        );
        b.add(Kind::Output { name: "M.y".into() }, &[s], None);
        let c = b.finish();
        let text = write(&c);
        let back = read(&text).unwrap();
        assert_eq!(back, c);
        assert_eq!(write(&back), text);
    }

    #[test]
    fn combinational_loops_and_unknown_components_are_rejected() {
        let looped = doc(&format!(
            "<I Name=\"LG_NOT\" ID=\"U1\">{}{}</I>",
            pin("A1", "N1", "I", None),
            pin("X1", "N1", "O", Some("BOOL"))
        ));
        assert!(matches!(read(&looped), Err(ReadError::Loop(_))));
        let unknown = doc(&format!(
            "<I Name=\"XX_MAGIC\" ID=\"U1\">{}</I>",
            pin("X1", "N1", "O", Some("BOOL"))
        ));
        assert!(matches!(read(&unknown), Err(ReadError::Structure(_))));
        let undriven = doc(&format!(
            "<I Name=\"IC_MODULE-OUT\" ID=\"U1\"><A Key=\"V1\" Value=\"y\"/>{}</I>",
            pin("A1", "N9", "I", None)
        ));
        assert!(matches!(read(&undriven), Err(ReadError::Structure(_))));
        assert!(matches!(
            read("<NOB_FLAT"),
            Err(ReadError::Xml(_)) | Err(ReadError::Structure(_))
        ));
    }
}
