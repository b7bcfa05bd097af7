//! Values of variables, in both directions: read out of memory as a
//! [`Shown`] tree that reports print, and read from ST literal text
//! (`--set`, stimulus cells) as a [`Value`] to store.
//!
//! Reading works on a plain byte slice (the machine's memory), so a report
//! never changes the program's state. The descriptors come from an image
//! that may have been loaded from a file: reading guards against types that
//! nest without end and arrays larger than the memory, and answers
//! [`Shown::Unreadable`] instead of failing.

use stc_ir::model::{Model, TypeDesc, TypeRef};
use stc_syntax::literal::decode_string;
use stc_syntax::token::ElemType;
use stc_values::{parse_value, Value};

use crate::engine::{read_value, Memory};
use crate::error::{Error, Result};
use crate::path::{describe, is_member, View};

/// A value as reports show it.
#[derive(Clone, Debug, PartialEq)]
pub enum Shown {
    /// A value of an elementary type other than STRING and WSTRING.
    Scalar(ElemType, Value),
    /// A STRING (`Value::Str`) or WSTRING (`Value::WStr`).
    Str(Value),
    /// An enumerated value: its type's name, the value's name when the
    /// integer is one of the type's values, and the integer.
    Enum {
        ty: String,
        name: Option<String>,
        value: i128,
    },
    /// An array, one item per element of the first dimension.
    List(Vec<Shown>),
    /// A structure or an instance, by member name.
    Record(Vec<(String, Shown)>),
    /// Memory the descriptors point outside of.
    Unreadable,
}

/// How deep types may nest before reading gives up (a well-formed image
/// never comes close; a corrupt one must not recurse forever).
const MAX_DEPTH: u32 = 64;

/// Reads what a place holds at `addr`.
pub fn read(model: &Model, mem: &dyn Memory, addr: u32, view: &View) -> Shown {
    match view {
        View::Type(t) => read_type(model, mem, addr, *t, 0),
        View::Slice { elem, dims, stride } => read_array(model, mem, addr, *elem, dims, *stride, 0),
    }
}

fn read_type(model: &Model, mem: &dyn Memory, addr: u32, ty: TypeRef, depth: u32) -> Shown {
    if depth > MAX_DEPTH {
        return Shown::Unreadable;
    }
    let Some(desc) = model.types.get(ty as usize) else {
        return Shown::Unreadable;
    };
    match desc {
        TypeDesc::Scalar(e) | TypeDesc::Subrange { base: e, .. } => {
            match read_value(mem, model, addr, ty) {
                Some(v) => Shown::Scalar(*e, v),
                None => Shown::Unreadable,
            }
        }
        TypeDesc::String { .. } => match read_value(mem, model, addr, ty) {
            Some(v) => Shown::Str(v),
            None => Shown::Unreadable,
        },
        TypeDesc::Enum { name, values, .. } => match read_value(mem, model, addr, ty) {
            Some(Value::Int(v)) => Shown::Enum {
                ty: name.clone(),
                name: values.iter().find(|x| x.1 == v).map(|x| x.0.clone()),
                value: v,
            },
            _ => Shown::Unreadable,
        },
        TypeDesc::Array { elem, dims, stride } => {
            read_array(model, mem, addr, *elem, dims, *stride, depth + 1)
        }
        TypeDesc::Struct { fields, .. } => Shown::Record(
            fields
                .iter()
                .map(|f| {
                    let v = match addr.checked_add(f.offset) {
                        Some(a) => read_type(model, mem, a, f.ty, depth + 1),
                        None => Shown::Unreadable,
                    };
                    (f.name.clone(), v)
                })
                .collect(),
        ),
        TypeDesc::Instance { pou } => {
            let Some(code) = model.pous.get(*pou as usize) else {
                return Shown::Unreadable;
            };
            Shown::Record(
                code.vars
                    .iter()
                    .filter(|v| is_member(v))
                    .map(|v| {
                        let mut a = addr.checked_add(v.offset);
                        if v.is_ref {
                            a = a.and_then(|a| mem.deref(a));
                        }
                        let shown = match a {
                            Some(a) => read_type(model, mem, a, v.ty, depth + 1),
                            None => Shown::Unreadable,
                        };
                        (v.name.clone(), shown)
                    })
                    .collect(),
            )
        }
    }
}

fn read_array(
    model: &Model,
    mem: &dyn Memory,
    addr: u32,
    elem: TypeRef,
    dims: &[(i64, i64)],
    stride: u32,
    depth: u32,
) -> Shown {
    let Some(&(lo, hi)) = dims.first() else {
        return read_type(model, mem, addr, elem, depth + 1);
    };
    // Every element must lie in memory: this also bounds the work a
    // corrupt descriptor can ask for.
    let mut count: u128 = 1;
    for &(l, h) in dims {
        count = count.saturating_mul((h as i128 - l as i128 + 1).max(0) as u128);
    }
    let total = count.saturating_mul(stride.max(1) as u128);
    match u32::try_from(total) {
        Ok(n) if mem.bytes(addr, n).is_some() => {}
        _ => return Shown::Unreadable,
    }
    let len = (hi as i128 - lo as i128 + 1).max(0) as u64;
    let row = (count / u128::from(len.max(1))) as u64 * stride as u64;
    let mut items = Vec::with_capacity(len as usize);
    for i in 0..len {
        let a = addr as u64 + i * row;
        items.push(match u32::try_from(a) {
            Ok(a) => read_array(model, mem, a, elem, &dims[1..], stride, depth + 1),
            Err(_) => Shown::Unreadable,
        });
    }
    Shown::List(items)
}

/// Reads `text`, an ST literal, as a value of the place's type, for
/// `--set` and stimulus cells: `TRUE`, `42`, `-3.5`, `16#FF`, `T#1s`,
/// `D#2024-01-31`, `'text'` (or the bare text, as a shell leaves it),
/// `Color#Red` or `Red`.
pub fn parse_for(model: &Model, view: &View, text: &str) -> Result<Value> {
    let t = text.trim();
    let desc = match view {
        View::Type(ty) => model.types.get(*ty as usize),
        View::Slice { .. } => None,
    };
    let whole = |what: String| {
        Error::Value(format!(
            "cannot assign `{t}` to {what}: only elementary, string and enumerated variables take a value (name an element or a member)"
        ))
    };
    match desc {
        Some(TypeDesc::Scalar(e)) => parse_scalar(*e, t),
        Some(TypeDesc::Subrange { base, lo, hi }) => {
            let v = parse_scalar(*base, t)?;
            match v.as_int() {
                Some(i) if i < *lo || i > *hi => Err(Error::Value(format!(
                    "`{t}` is outside the subrange {lo}..{hi} of this variable"
                ))),
                _ => Ok(v),
            }
        }
        Some(TypeDesc::String { wide, .. }) => parse_string(*wide, t),
        Some(TypeDesc::Enum { name, values, .. }) => {
            let value_name = match t.split_once('#') {
                Some((ty, v)) if ty.eq_ignore_ascii_case(name) => v,
                Some((ty, _)) => {
                    return Err(Error::Value(format!(
                        "`{t}` is a value of `{ty}`, not of the enumerated type {name}"
                    )))
                }
                None => t,
            };
            values
                .iter()
                .find(|(n, _)| n.eq_ignore_ascii_case(value_name.trim()))
                .map(|&(_, v)| Value::Int(v))
                .ok_or_else(|| {
                    let names: Vec<&str> = values.iter().map(|(n, _)| n.as_str()).collect();
                    Error::Value(format!(
                        "`{t}` is not a value of {name} (its values: {})",
                        names.join(", ")
                    ))
                })
        }
        other => Err(whole(match view {
            View::Slice { .. } => "part of an ARRAY".to_string(),
            View::Type(_) => format!("a whole {}", describe(model, other)),
        })),
    }
}

fn parse_scalar(e: ElemType, t: &str) -> Result<Value> {
    let quoted = t.len() >= 2 && (t.starts_with('\'') || t.starts_with('"'));
    if matches!(e, ElemType::Char | ElemType::Wchar) && quoted {
        // A character literal: its first character (NUL when empty).
        let code = match parse_string(e == ElemType::Wchar, t)? {
            Value::Str(s) => s.first().map_or(0, |&b| i128::from(b)),
            Value::WStr(w) => w.first().map_or(0, |&u| i128::from(u)),
            _ => 0,
        };
        return Ok(Value::Int(code));
    }
    parse_value(e, t).map_err(|_| {
        Error::Value(format!(
            "`{t}` cannot be read as {} (expected an ST literal within the type's range)",
            e.name()
        ))
    })
}

/// A string literal (`'text'`, `"text"` for WSTRING, with `$` escapes), or
/// the bare text.
fn parse_string(wide: bool, t: &str) -> Result<Value> {
    let body = match t.split_once('#') {
        Some((p, rest))
            if p.eq_ignore_ascii_case(if wide { "WSTRING" } else { "STRING" })
                && (rest.starts_with('\'') || rest.starts_with('"')) =>
        {
            rest
        }
        _ => t,
    };
    let text = match body.chars().next() {
        Some(q @ ('\'' | '"')) => {
            if body.len() < 2 || !body.ends_with(q) {
                return Err(Error::Value(format!("the string `{t}` has no closing {q}")));
            }
            let (s, errors) = decode_string(body, wide);
            if let Some((_, _, msg)) = errors.first() {
                return Err(Error::Value(format!("in the string `{t}`: {msg}")));
            }
            s
        }
        _ => body.to_string(),
    };
    if wide {
        Ok(Value::wstring(&text))
    } else {
        // STRING is Windows-1252 (semantics.md).
        text.chars()
            .map(stc_syntax::literal::cp1252_encode)
            .collect::<Option<Vec<u8>>>()
            .map(Value::Str)
            .ok_or_else(|| {
                Error::Value(format!(
                    "`{t}` has characters a STRING cannot hold (use a WSTRING)"
                ))
            })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::testing::*;

    fn int(e: ElemType, v: i128) -> Shown {
        Shown::Scalar(e, Value::Int(v))
    }

    fn mem() -> Vec<u8> {
        let mut m = sample().init;
        let main = MAIN_AT as usize;
        m[main..main + 2].copy_from_slice(&(-5i16).to_le_bytes()); // count
        for (i, v) in [10i16, 20, 30].iter().enumerate() {
            m[main + 56 + 2 * i..main + 58 + 2 * i].copy_from_slice(&v.to_le_bytes());
        }
        for i in 0..6 {
            let v = (11 + (i / 3) * 10 + i % 3) as i16; // 11 12 13 21 22 23
            m[main + 62 + 2 * i..main + 64 + 2 * i].copy_from_slice(&v.to_le_bytes());
        }
        m[main + 74] = 1; // pt.x
        m[main + 76] = 2; // pt.y
        m[main + 78] = 2; // name: length 2
        m[main + 80] = b'h';
        m[main + 81] = 0xE9; // é in Latin-1
        m[main + 90] = 2; // color = Blue
        m[main + 8] = 1; // tmr.IN
        m[main + 16..main + 24].copy_from_slice(&1_500_000_000i64.to_le_bytes()); // tmr.PT
        m
    }

    fn read_path(path: &str) -> Shown {
        let img = sample_model();
        let plan =
            crate::schedule::Plan::new(&img, crate::schedule::Chosen::Config(0), None).unwrap();
        let scope = crate::path::Scope {
            model: &img,
            instances: &plan.instances,
            config: plan.config,
        };
        let p = scope.resolve(path).unwrap();
        let m = mem();
        read(&img, &m, p.loc.address(&m).unwrap(), &p.view)
    }

    #[test]
    fn scalars_strings_and_enumerations_are_read() {
        assert_eq!(read_path("main.count"), int(ElemType::Int, -5));
        assert_eq!(
            read_path("main.flag"),
            Shown::Scalar(ElemType::Bool, Value::Bool(false))
        );
        assert_eq!(
            read_path("main.name"),
            Shown::Str(Value::Str(vec![b'h', 0xE9]))
        );
        assert_eq!(
            read_path("main.color"),
            Shown::Enum {
                ty: "Color".into(),
                name: Some("Blue".into()),
                value: 2
            }
        );
        assert_eq!(read_path("main.tmr.PT"), int(ElemType::Time, 1_500_000_000));
    }

    #[test]
    fn arrays_read_as_nested_lists_in_row_major_order() {
        let i = |v| int(ElemType::Int, v);
        assert_eq!(
            read_path("main.arr"),
            Shown::List(vec![i(10), i(20), i(30)])
        );
        assert_eq!(
            read_path("main.m"),
            Shown::List(vec![
                Shown::List(vec![i(11), i(12), i(13)]),
                Shown::List(vec![i(21), i(22), i(23)]),
            ])
        );
        assert_eq!(
            read_path("main.m[2]"),
            Shown::List(vec![i(21), i(22), i(23)])
        );
    }

    #[test]
    fn structures_and_instances_read_as_records_of_their_own_members() {
        let i = |v| int(ElemType::Int, v);
        assert_eq!(
            read_path("main.pt"),
            Shown::Record(vec![("x".into(), i(1)), ("y".into(), i(2))])
        );
        // Hidden variables are left out.
        assert_eq!(
            read_path("main.tmr"),
            Shown::Record(vec![
                (
                    "IN".into(),
                    Shown::Scalar(ElemType::Bool, Value::Bool(true))
                ),
                ("PT".into(), int(ElemType::Time, 1_500_000_000)),
                (
                    "Q".into(),
                    Shown::Scalar(ElemType::Bool, Value::Bool(false))
                ),
                ("ET".into(), int(ElemType::Time, 0)),
                ("start".into(), int(ElemType::Time, 0)),
            ])
        );
        // A program instance: its own variables (located ones through
        // their reference), not VAR_EXTERNAL, VAR_TEMP or hidden ones.
        let Shown::Record(members) = read_path("main") else {
            panic!("a record")
        };
        let names: Vec<&str> = members.iter().map(|(n, _)| n.as_str()).collect();
        assert_eq!(
            names,
            [
                "count",
                "flag",
                "tmr",
                "arr",
                "m",
                "pt",
                "name",
                "color",
                "lamp_local",
                "sensor",
                "x",
                "lx",
                "pts",
                "w"
            ]
        );
    }

    #[test]
    fn memory_outside_the_machine_is_unreadable_not_a_panic() {
        let img = sample_model();
        let m = mem();
        assert_eq!(
            read(&img, &m, 10_000, &View::Type(T_INT)),
            Shown::Unreadable
        );
        assert_eq!(read(&img, &m, 166, &View::Type(T_ARR)), Shown::Unreadable);
        assert_eq!(read(&img, &m, 0, &View::Type(999)), Shown::Unreadable);
        // A corrupt array: 2^40 elements of stride 0.
        let mut bad = sample_model();
        bad.types.push(TypeDesc::Array {
            elem: T_INT,
            dims: vec![(0, 1 << 40)],
            stride: 0,
        });
        assert_eq!(read(&bad, &m, 0, &View::Type(16)), Shown::Unreadable);
        // A structure containing itself.
        bad.types.push(TypeDesc::Struct {
            name: None,
            fields: vec![stc_ir::model::FieldDesc {
                name: "me".into(),
                ty: 17,
                offset: 0,
            }],
        });
        let mut v = read(&bad, &m, 0, &View::Type(17));
        let mut depth = 0;
        while let Shown::Record(mut f) = v {
            v = f.remove(0).1;
            depth += 1;
        }
        assert_eq!((v, depth), (Shown::Unreadable, MAX_DEPTH + 1));
    }

    fn parse(ty: TypeRef, text: &str) -> Result<Value> {
        parse_for(&sample_model(), &View::Type(ty), text)
    }

    #[test]
    fn literals_are_read_for_the_variables_type() {
        assert_eq!(parse(T_INT, "42"), Ok(Value::Int(42)));
        assert_eq!(parse(T_INT, " -7 "), Ok(Value::Int(-7)));
        assert_eq!(parse(T_INT, "16#FF"), Ok(Value::Int(255)));
        assert_eq!(parse(T_INT, "INT#-3"), Ok(Value::Int(-3)));
        assert_eq!(parse(T_SINT, "-128"), Ok(Value::Int(-128)));
        assert_eq!(parse(T_BOOL, "TRUE"), Ok(Value::Bool(true)));
        assert_eq!(parse(T_BOOL, "false"), Ok(Value::Bool(false)));
        assert_eq!(parse(T_BOOL, "1"), Ok(Value::Bool(true)));
        assert_eq!(parse(T_REAL, "-3.5"), Ok(Value::Real(-3.5)));
        assert_eq!(parse(T_REAL, "2"), Ok(Value::Real(2.0)));
        assert_eq!(parse(T_LREAL, "0.1"), Ok(Value::Real(0.1)));
        assert_eq!(parse(T_TIME, "T#1.5s"), Ok(Value::Int(1_500_000_000)));
        assert_eq!(parse(T_TIME, "t#-2s"), Ok(Value::Int(-2_000_000_000)));
        assert_eq!(parse(T_TIME, "500ms"), Ok(Value::Int(500_000_000)));
    }

    #[test]
    fn strings_take_quoted_literals_or_bare_text() {
        assert_eq!(parse(T_STRING, "'it$'s'"), Ok(Value::Str(b"it's".to_vec())));
        assert_eq!(parse(T_STRING, "''"), Ok(Value::Str(Vec::new())));
        assert_eq!(
            parse(T_STRING, "abc def"),
            Ok(Value::Str(b"abc def".to_vec()))
        );
        assert_eq!(parse(T_STRING, "STRING#'x'"), Ok(Value::Str(b"x".to_vec())));
        assert_eq!(
            parse(T_STRING, "'caf\u{e9}'"),
            Ok(Value::Str(b"caf\xe9".to_vec()))
        );
        assert_eq!(
            parse(T_WSTRING, "\"\u{263a}\""),
            Ok(Value::WStr(vec![0x263a]))
        );
        assert_eq!(
            parse(T_STRING, "'abc"),
            Err(Error::Value("the string `'abc` has no closing '".into()))
        );
        assert_eq!(
            parse(T_STRING, "'\u{263a}'"),
            Err(Error::Value(
                "`'\u{263a}'` has characters a STRING cannot hold (use a WSTRING)".into()
            ))
        );
        assert!(
            matches!(parse(T_STRING, "'$Q'"), Err(Error::Value(m)) if m.contains("invalid escape"))
        );
    }

    #[test]
    fn enumerated_values_are_named_with_or_without_their_type() {
        assert_eq!(parse(T_COLOR, "Color#Green"), Ok(Value::Int(1)));
        assert_eq!(parse(T_COLOR, "green"), Ok(Value::Int(1)));
        assert_eq!(parse(T_COLOR, "COLOR#blue"), Ok(Value::Int(2)));
        assert_eq!(
            parse(T_COLOR, "Purple"),
            Err(Error::Value(
                "`Purple` is not a value of Color (its values: Red, Green, Blue)".into()
            ))
        );
        assert_eq!(
            parse(T_COLOR, "Shade#Red"),
            Err(Error::Value(
                "`Shade#Red` is a value of `Shade`, not of the enumerated type Color".into()
            ))
        );
    }

    #[test]
    fn bad_literals_and_whole_aggregates_are_refused() {
        assert_eq!(
            parse(T_SINT, "300"),
            Err(Error::Value(
                "`300` cannot be read as SINT (expected an ST literal within the type's range)"
                    .into()
            ))
        );
        assert!(parse(T_INT, "abc").is_err());
        assert!(parse(T_INT, "1.5").is_err());
        assert!(parse(T_BOOL, "yes").is_err());
        assert!(parse(T_TIME, "10").is_err());
        assert_eq!(
            parse(T_ARR, "1"),
            Err(Error::Value(
                "cannot assign `1` to a whole ARRAY: only elementary, string and enumerated variables take a value (name an element or a member)".into()
            ))
        );
        assert!(parse(T_POINT, "(x := 1)").is_err());
        assert!(parse(T_TIMER, "1").is_err());
    }
}
