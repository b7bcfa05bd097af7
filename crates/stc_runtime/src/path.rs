//! Variable paths (spec/cli.md): `instance.var` followed by `.member`,
//! `[i,j]` or `[i][j]`, a global by its plain name, or a direct address
//! such as `%QX0.0`. Matching is case-insensitive; a resolved [`Place`]
//! carries the declared spelling for reports.
//!
//! A path resolves against the image's descriptors only, never its memory:
//! a reference on the way (VAR_EXTERNAL, VAR_IN_OUT, a located variable) is
//! a [`Step::Deref`] that [`Place::address`] follows each time the place is
//! read or written, so a place stays right when the reference changes.

use stc_ir::model::{Model, ProgramInst, TypeDesc, TypeRef, VarDesc, VarKind};
use stc_syntax::literal::{parse_address, parse_based_int, parse_int, DirectAddress};

use crate::engine::Memory;
use crate::error::{Error, Result};

/// A parsed path, before resolution.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct PathExpr {
    pub root: Root,
    pub segments: Vec<Segment>,
}

#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Root {
    /// A program instance or a global variable.
    Name(String),
    /// A direct address: the process image slot itself.
    Address(DirectAddress),
}

#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Segment {
    /// `.name`
    Member(String),
    /// `[i]` or `[i,j,...]`
    Index(Vec<i64>),
}

/// Parses the text of a path. Blanks are allowed inside brackets.
pub fn parse_path(text: &str) -> Result<PathExpr> {
    let bad = |why: &str| Error::Path(format!("invalid path `{text}`: {why}"));
    let t = text.trim();
    if t.is_empty() {
        return Err(bad("it is empty"));
    }
    if t.starts_with('%') {
        if !t.is_ascii() {
            return Err(bad("a direct address is written like %IX0.1 or %QW4"));
        }
        let addr = parse_address(t).map_err(|e| Error::Path(e.message))?;
        if addr.is_incomplete() {
            return Err(bad("`*` addresses have no storage"));
        }
        return Ok(PathExpr {
            root: Root::Address(addr),
            segments: Vec::new(),
        });
    }
    let mut rest = t;
    let root = take_name(&mut rest).ok_or_else(|| bad("expected a name at its start"))?;
    let mut segments = Vec::new();
    while let Some(c) = rest.chars().next() {
        match c {
            '.' => {
                rest = &rest[1..];
                let m = take_name(&mut rest).ok_or_else(|| bad("expected a name after `.`"))?;
                segments.push(Segment::Member(m));
            }
            '[' => {
                let close = rest.find(']').ok_or_else(|| bad("`[` is not closed"))?;
                let inner = &rest[1..close];
                rest = &rest[close + 1..];
                let mut indices = Vec::new();
                for part in inner.split(',') {
                    indices.push(parse_index(part.trim()).ok_or_else(|| {
                        bad(&format!("`{}` is not an integer index", part.trim()))
                    })?);
                }
                segments.push(Segment::Index(indices));
            }
            _ => return Err(bad(&format!("unexpected `{c}`"))),
        }
    }
    Ok(PathExpr {
        root: Root::Name(root),
        segments,
    })
}

fn take_name(rest: &mut &str) -> Option<String> {
    let s = *rest;
    let first = s.chars().next()?;
    if !(first.is_ascii_alphabetic() || first == '_') {
        return None;
    }
    let end = s
        .find(|c: char| !(c.is_ascii_alphanumeric() || c == '_'))
        .unwrap_or(s.len());
    *rest = &s[end..];
    Some(s[..end].to_string())
}

/// An index: decimal or `16#..`, with an optional sign and `_` separators.
fn parse_index(s: &str) -> Option<i64> {
    let (negative, digits) = match s.strip_prefix('-') {
        Some(d) => (true, d),
        None => (false, s.strip_prefix('+').unwrap_or(s)),
    };
    let magnitude = if digits.contains('#') {
        parse_based_int(digits).ok()?
    } else {
        parse_int(digits).ok()?
    };
    let v = i128::from(magnitude);
    i64::try_from(if negative { -v } else { v }).ok()
}

/// Splits a `--watch` list at the commas that separate paths, not those
/// inside brackets (`Main.m[1,2],Main.x` is two paths). Empty items are
/// dropped.
pub fn split_list(text: &str) -> Vec<String> {
    let mut out = Vec::new();
    let mut depth = 0usize;
    let mut start = 0;
    for (i, c) in text.char_indices() {
        match c {
            '[' => depth += 1,
            ']' => depth = depth.saturating_sub(1),
            ',' if depth == 0 => {
                out.push(text[start..i].trim().to_string());
                start = i + 1;
            }
            _ => {}
        }
    }
    out.push(text[start..].trim().to_string());
    out.retain(|s| !s.is_empty());
    out
}

/// One step of an address computation.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Step {
    /// Move by this many bytes.
    Add(u32),
    /// Replace the address by the 4-byte address stored there.
    Deref,
}

/// How to find a variable in memory: a base address and steps.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Loc {
    pub base: u32,
    pub steps: Vec<Step>,
}

impl Loc {
    pub fn at(base: u32) -> Loc {
        Loc {
            base,
            steps: Vec::new(),
        }
    }

    fn add(&mut self, n: u32) {
        match self.steps.last_mut() {
            Some(Step::Add(m)) => *m = m.wrapping_add(n),
            Some(Step::Deref) => self.steps.push(Step::Add(n)),
            None => self.base = self.base.wrapping_add(n),
        }
    }

    fn deref(&mut self) {
        self.steps.push(Step::Deref);
    }

    /// The address now, following references through `mem`; `None` when a
    /// reference points outside it.
    pub fn address(&self, mem: &(impl Memory + ?Sized)) -> Option<u32> {
        let mut a = self.base;
        for s in &self.steps {
            match *s {
                Step::Add(n) => a = a.checked_add(n)?,
                Step::Deref => a = mem.deref(a)?,
            }
        }
        Some(a)
    }
}

/// What is at a place: a type of the image, or the rows of a
/// multi-dimensional array that one index (`m[2]` of `m[1..3, 1..4]`) left.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum View {
    Type(TypeRef),
    Slice {
        elem: TypeRef,
        dims: Vec<(i64, i64)>,
        stride: u32,
    },
}

/// A resolved variable (or part of one).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Place {
    /// The path with the declared spelling of every name.
    pub name: String,
    pub loc: Loc,
    pub view: View,
    /// A CONSTANT global: `--set` and stimuli may not write it.
    pub constant: bool,
}

/// Whether a variable of a POU is shown as a member of its instance:
/// the instance's own data (inputs, outputs, VAR, located variables), not
/// references to other data (VAR_IN_OUT, VAR_EXTERNAL), temporaries or
/// what the compiler added.
pub fn is_member(v: &VarDesc) -> bool {
    !v.in_frame
        && matches!(
            v.kind,
            VarKind::Input | VarKind::Output | VarKind::Var | VarKind::Global
        )
}

/// Whether the value of type `ty` at `base` holds the instance of `pou` at
/// `at`; if so, `out` is extended with the path from the value to it.
fn find_instance(
    model: &Model,
    ty: TypeRef,
    base: u32,
    at: u32,
    pou: u32,
    out: &mut String,
    depth: u32,
) -> bool {
    // Deeper than any program nests (a hostile table may cycle).
    if depth > 64 || at < base {
        return false;
    }
    // A member holding `at`: an empty instance still has its address.
    let holds =
        |start: u32, t: TypeRef| start <= at && u64::from(at - start) < model.type_size(t).max(1);
    let member = |out: &mut String, text: String, t: TypeRef, start: u32| {
        let len = out.len();
        out.push_str(&text);
        if find_instance(model, t, start, at, pou, out, depth + 1) {
            return true;
        }
        out.truncate(len);
        false
    };
    match model.types.get(ty as usize) {
        Some(TypeDesc::Instance { pou: p }) => {
            if base == at && *p == pou {
                return true;
            }
            let Some(d) = model.pous.get(*p as usize) else {
                return false;
            };
            d.vars.iter().any(|v| {
                let Some(start) = base.checked_add(v.offset) else {
                    return false;
                };
                !v.in_frame
                    && !v.is_ref
                    && holds(start, v.ty)
                    && member(out, format!(".{}", v.name), v.ty, start)
            })
        }
        Some(TypeDesc::Struct { fields, .. }) => fields.iter().any(|f| {
            let Some(start) = base.checked_add(f.offset) else {
                return false;
            };
            holds(start, f.ty) && member(out, format!(".{}", f.name), f.ty, start)
        }),
        Some(TypeDesc::Array { elem, dims, stride }) if *stride > 0 => {
            let k = (at - base) / stride;
            // Row-major: the last index varies fastest.
            let mut rest = i128::from(k);
            let mut index = Vec::with_capacity(dims.len());
            for (lo, hi) in dims.iter().rev() {
                let n = i128::from(*hi) - i128::from(*lo) + 1;
                if n <= 0 {
                    return false;
                }
                index.push(i128::from(*lo) + rest % n);
                rest /= n;
            }
            if rest != 0 {
                return false;
            }
            let text: Vec<String> = index.iter().rev().map(|i| i.to_string()).collect();
            member(
                out,
                format!("[{}]", text.join(",")),
                *elem,
                base + k * stride,
            )
        }
        _ => false,
    }
}

/// Whether a path may name a variable of a POU at all.
fn is_nameable(v: &VarDesc) -> bool {
    v.kind != VarKind::Hidden
}

/// What paths are resolved against: the image, the program instances that
/// run, and the configuration chosen (for its globals).
#[derive(Clone, Copy)]
pub struct Scope<'a> {
    pub model: &'a Model,
    pub instances: &'a [ProgramInst],
    pub config: Option<u32>,
}

impl<'a> Scope<'a> {
    /// Resolves a path's text.
    pub fn resolve(&self, text: &str) -> Result<Place> {
        let p = parse_path(text)?;
        let mut place = match &p.root {
            Root::Address(a) => self.address(a, text)?,
            Root::Name(n) => self.root(n, text)?,
        };
        for seg in &p.segments {
            place = match seg {
                Segment::Member(m) => self.member(place, m, text)?,
                Segment::Index(ix) => self.index(place, ix, text)?,
            };
        }
        Ok(place)
    }

    /// The path (in this module's syntax, declared spelling) of the
    /// instance of POU `pou` at data address `at`: the inverse of
    /// [`Scope::resolve`] for function block and program instances, as a
    /// fault report names where it happened. Searched in the program
    /// instances, then the globals (an FB instance declared VAR_GLOBAL).
    pub fn instance_path(&self, at: u32, pou: u32) -> Option<String> {
        let roots = self
            .instances
            .iter()
            .filter_map(|i| {
                let ty = self.model.pous.get(i.pou as usize)?.instance_type;
                Some((i.name.as_str(), i.offset, ty))
            })
            .chain(
                self.model
                    .globals
                    .iter()
                    .map(|g| (g.name.as_str(), g.offset, g.ty)),
            );
        for (name, base, ty) in roots {
            let mut out = name.to_string();
            if find_instance(self.model, ty, base, at, pou, &mut out, 0) {
                return Some(out);
            }
        }
        None
    }

    /// The process image slot of a direct address.
    fn address(&self, a: &DirectAddress, text: &str) -> Result<Place> {
        let same = |x: &DirectAddress| x.area == a.area && x.size == a.size && x.path == a.path;
        let slot = self
            .model
            .io
            .iter()
            .find(|s| s.address == *a)
            .or_else(|| self.model.io.iter().find(|s| same(&s.address)))
            .ok_or_else(|| {
                Error::Path(format!(
                    "unknown address `{}`: the program uses no variable at {a}",
                    text.trim()
                ))
            })?;
        Ok(Place {
            name: a.to_string(),
            loc: Loc::at(slot.offset),
            view: View::Type(slot.ty),
            constant: false,
        })
    }

    /// A program instance or a global.
    fn root(&self, n: &str, text: &str) -> Result<Place> {
        if let Some(inst) = self
            .instances
            .iter()
            .find(|i| i.name.eq_ignore_ascii_case(n))
        {
            let pou = self.model.pous.get(inst.pou as usize).ok_or_else(|| {
                Error::Path(format!("program instance `{}` has no code", inst.name))
            })?;
            return Ok(Place {
                name: inst.name.clone(),
                loc: Loc::at(inst.offset),
                view: View::Type(pou.instance_type),
                constant: false,
            });
        }
        let named = |g: &&stc_ir::model::GlobalDesc| g.name.eq_ignore_ascii_case(n);
        let globals = &self.model.globals;
        let found = globals
            .iter()
            .filter(named)
            .find(|g| g.config.is_some() && g.config == self.config)
            .or_else(|| globals.iter().filter(named).find(|g| g.config.is_none()))
            .or_else(|| globals.iter().find(named));
        if let Some(g) = found {
            return Ok(Place {
                name: g.name.clone(),
                loc: Loc::at(g.offset),
                view: View::Type(g.ty),
                constant: g.constant,
            });
        }
        let names: Vec<&str> = self.instances.iter().map(|i| i.name.as_str()).collect();
        Err(Error::Path(format!(
            "unknown variable `{}`: `{n}` is neither a program instance ({}) nor a global variable",
            text.trim(),
            if names.is_empty() {
                "there are none".to_string()
            } else {
                names.join(", ")
            }
        )))
    }

    fn member(&self, mut place: Place, m: &str, text: &str) -> Result<Place> {
        let no_member = |what: String| {
            Error::Path(format!(
                "unknown variable `{}`: {} has no member `{m}`",
                text.trim(),
                what
            ))
        };
        let ty = match &place.view {
            View::Type(t) => *t,
            View::Slice { .. } => return Err(no_member(format!("`{}` (ARRAY)", place.name))),
        };
        match self.model.types.get(ty as usize) {
            Some(TypeDesc::Struct { fields, .. }) => {
                let f = fields
                    .iter()
                    .find(|f| f.name.eq_ignore_ascii_case(m))
                    .ok_or_else(|| no_member(format!("`{}`", place.name)))?;
                place.name = format!("{}.{}", place.name, f.name);
                place.loc.add(f.offset);
                place.view = View::Type(f.ty);
                Ok(place)
            }
            Some(TypeDesc::Instance { pou }) => {
                let code = self.model.pous.get(*pou as usize);
                let v = code
                    .and_then(|c| {
                        c.vars
                            .iter()
                            .filter(|v| is_nameable(v))
                            .find(|v| v.name.eq_ignore_ascii_case(m))
                    })
                    .ok_or_else(|| no_member(format!("`{}`", place.name)))?;
                if v.in_frame {
                    return Err(Error::Path(format!(
                        "`{}.{}` is a temporary variable: it exists only while its POU runs",
                        place.name, v.name
                    )));
                }
                place.name = format!("{}.{}", place.name, v.name);
                place.loc.add(v.offset);
                if v.is_ref {
                    place.loc.deref();
                }
                place.view = View::Type(v.ty);
                place.constant |= v.constant;
                Ok(place)
            }
            other => Err(no_member(format!(
                "`{}` ({})",
                place.name,
                describe(self.model, other)
            ))),
        }
    }

    fn index(&self, mut place: Place, ix: &[i64], text: &str) -> Result<Place> {
        let mut shown = Vec::with_capacity(ix.len());
        let mut left = ix;
        while !left.is_empty() {
            let (elem, dims, stride) = match &place.view {
                View::Slice { elem, dims, stride } => (*elem, dims.clone(), *stride),
                View::Type(t) => match self.model.types.get(*t as usize) {
                    Some(TypeDesc::Array { elem, dims, stride }) => (*elem, dims.clone(), *stride),
                    other => {
                        return Err(Error::Path(format!(
                            "unknown variable `{}`: `{}` ({}) is not an array",
                            text.trim(),
                            place.name,
                            describe(self.model, other)
                        )))
                    }
                },
            };
            let n = left.len().min(dims.len());
            if n == 0 {
                return Err(Error::Path(format!(
                    "invalid path `{}`: an array without dimensions",
                    text.trim()
                )));
            }
            let mut flat: i128 = 0;
            for (d, &(lo, hi)) in dims.iter().enumerate() {
                let len = (hi as i128 - lo as i128 + 1).max(0);
                let i = if d < n { left[d] as i128 } else { lo as i128 };
                if d < n && !(lo as i128..=hi as i128).contains(&i) {
                    return Err(Error::Path(format!(
                        "index {i} of `{}` is outside its bounds {lo}..{hi}",
                        text.trim()
                    )));
                }
                flat = flat * len + (i - lo as i128);
            }
            let offset = u32::try_from(flat * stride as i128)
                .map_err(|_| Error::Path(format!("`{}` is outside the memory", text.trim())))?;
            place.loc.add(offset);
            shown.extend_from_slice(&left[..n]);
            place.view = if n < dims.len() {
                View::Slice {
                    elem,
                    dims: dims[n..].to_vec(),
                    stride,
                }
            } else {
                View::Type(elem)
            };
            left = &left[n..];
        }
        let list: Vec<String> = shown.iter().map(|i| i.to_string()).collect();
        place.name = format!("{}[{}]", place.name, list.join(","));
        Ok(place)
    }
}

/// The name of a type, for messages.
pub fn describe(model: &Model, t: Option<&TypeDesc>) -> String {
    match t {
        Some(TypeDesc::Scalar(e)) => e.name().into(),
        Some(TypeDesc::Subrange { base, lo, hi }) => format!("{} ({lo}..{hi})", base.name()),
        Some(TypeDesc::String { wide: false, cap }) => format!("STRING[{cap}]"),
        Some(TypeDesc::String { wide: true, cap }) => format!("WSTRING[{cap}]"),
        Some(TypeDesc::Enum { name, .. }) => name.clone(),
        Some(TypeDesc::Array { .. }) => "ARRAY".into(),
        Some(TypeDesc::Struct { name: Some(n), .. }) => n.clone(),
        Some(TypeDesc::Struct { name: None, .. }) => "STRUCT".into(),
        Some(TypeDesc::Instance { pou }) => match model.pous.get(*pou as usize) {
            Some(p) => p.name.clone(),
            None => "an instance".into(),
        },
        None => "an unknown type".into(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::schedule::{Chosen, Plan};
    use crate::testing::*;

    fn name(s: &str) -> Segment {
        Segment::Member(s.into())
    }

    #[test]
    fn paths_parse_into_a_root_and_segments() {
        assert_eq!(
            parse_path("Main.tmr.Q").unwrap(),
            PathExpr {
                root: Root::Name("Main".into()),
                segments: vec![name("tmr"), name("Q")],
            }
        );
        assert_eq!(
            parse_path(" Main.m[1, -2][16#A].x ").unwrap(),
            PathExpr {
                root: Root::Name("Main".into()),
                segments: vec![
                    name("m"),
                    Segment::Index(vec![1, -2]),
                    Segment::Index(vec![10]),
                    name("x"),
                ],
            }
        );
        assert_eq!(parse_path("g_1").unwrap().root, Root::Name("g_1".into()));
        assert_eq!(
            parse_path("%QX0.1").unwrap().root,
            Root::Address(addr("%QX0.1"))
        );
    }

    #[test]
    fn malformed_paths_say_what_is_wrong() {
        let e = |t: &str| parse_path(t).unwrap_err().to_string();
        assert_eq!(e(""), "invalid path ``: it is empty");
        assert_eq!(
            e("Main..x"),
            "invalid path `Main..x`: expected a name after `.`"
        );
        assert_eq!(e("Main.a[1"), "invalid path `Main.a[1`: `[` is not closed");
        assert_eq!(
            e("Main.a[i]"),
            "invalid path `Main.a[i]`: `i` is not an integer index"
        );
        assert_eq!(
            e("Main.a[]"),
            "invalid path `Main.a[]`: `` is not an integer index"
        );
        assert_eq!(
            e("1abc"),
            "invalid path `1abc`: expected a name at its start"
        );
        assert_eq!(e("Main x"), "invalid path `Main x`: unexpected ` `");
        assert_eq!(
            e("Main.ä"),
            "invalid path `Main.ä`: expected a name after `.`"
        );
        assert!(e("%Z1").contains("I, Q or M"));
        assert_eq!(
            e("%I*"),
            "invalid path `%I*`: `*` addresses have no storage"
        );
    }

    #[test]
    fn watch_lists_split_at_commas_outside_brackets() {
        assert_eq!(split_list("Main.m[1,2],Main.x"), ["Main.m[1,2]", "Main.x"]);
        assert_eq!(split_list(" a , b ,,"), ["a", "b"]);
        assert!(split_list("").is_empty());
    }

    fn resolve(text: &str) -> Result<Place> {
        let img = sample_model();
        let plan = Plan::new(&img, Chosen::Config(0), None).unwrap();
        let scope = Scope {
            model: &img,
            instances: &plan.instances,
            config: plan.config,
        };
        scope.resolve(text)
    }

    fn at(text: &str) -> (String, u32, View) {
        let p = resolve(text).unwrap();
        let a = p.loc.address(&sample().init).unwrap();
        (p.name, a, p.view)
    }

    #[test]
    fn names_resolve_case_insensitively_with_the_declared_spelling() {
        assert_eq!(
            at("MAIN.COUNT"),
            ("main.count".into(), MAIN_AT, View::Type(T_INT))
        );
        assert_eq!(
            at("main.TMR.q"),
            ("main.tmr.Q".into(), MAIN_AT + 8 + 16, View::Type(T_BOOL))
        );
        assert_eq!(
            at("main.pt.Y"),
            ("main.pt.y".into(), MAIN_AT + 74 + 2, View::Type(T_INT))
        );
        assert_eq!(
            at("main.pts[1].y"),
            (
                "main.pts[1].y".into(),
                MAIN_AT + 120 + 4 + 2,
                View::Type(T_INT)
            )
        );
        assert_eq!(at("main"), ("main".into(), MAIN_AT, View::Type(T_MAIN)));
        assert_eq!(at("G"), ("g".into(), 0, View::Type(T_INT)));
        assert_eq!(at("Top"), ("top".into(), 6, View::Type(T_INT)));
        assert!(resolve("k").unwrap().constant);
    }

    #[test]
    fn array_indices_follow_the_bounds_row_major() {
        assert_eq!(
            at("main.arr[2]"),
            ("main.arr[2]".into(), MAIN_AT + 56 + 2, View::Type(T_INT))
        );
        // m : ARRAY[1..2, 1..3] OF INT: m[2,3] is the 6th element.
        assert_eq!(
            at("main.m[2,3]"),
            ("main.m[2,3]".into(), MAIN_AT + 62 + 10, View::Type(T_INT))
        );
        assert_eq!(
            at("main.m[2][3]"),
            ("main.m[2][3]".into(), MAIN_AT + 62 + 10, View::Type(T_INT))
        );
        assert_eq!(
            at("main.m[2]"),
            (
                "main.m[2]".into(),
                MAIN_AT + 62 + 6,
                View::Slice {
                    elem: T_INT,
                    dims: vec![(1, 3)],
                    stride: 2
                }
            )
        );
    }

    #[test]
    fn references_are_followed_when_the_place_is_read() {
        let p = resolve("main.g_ext").unwrap();
        assert_eq!(
            p.loc,
            Loc {
                base: MAIN_AT + 92,
                steps: vec![Step::Deref]
            }
        );
        let mut mem = sample().init;
        assert_eq!(p.loc.address(&mem), Some(0));
        mem[(MAIN_AT + 92) as usize] = 6;
        assert_eq!(p.loc.address(&mem), Some(6));
        assert_eq!(p.loc.address(&mem[..50]), None);
        assert_eq!(
            at("main.lamp_local"),
            ("main.lamp_local".into(), 160, View::Type(T_BOOL))
        );
    }

    #[test]
    fn direct_addresses_name_their_slot() {
        assert_eq!(at("%QX1.0"), ("%QX1.0".into(), 160, View::Type(T_BOOL)));
        assert_eq!(at("%ix0.0"), ("%IX0.0".into(), 161, View::Type(T_BOOL)));
        // Without the size letter, a bit address is the same slot.
        assert_eq!(at("%Q0.0").1, 4);
        assert_eq!(
            resolve("%QW7").unwrap_err().to_string(),
            "unknown address `%QW7`: the program uses no variable at %QW7"
        );
    }

    #[test]
    fn unknown_paths_are_clear_errors() {
        let e = |t: &str| resolve(t).unwrap_err().to_string();
        assert_eq!(
            e("nobody.x"),
            "unknown variable `nobody.x`: `nobody` is neither a program instance (main, p2, p3) nor a global variable"
        );
        assert_eq!(
            e("main.nope"),
            "unknown variable `main.nope`: `main` has no member `nope`"
        );
        assert_eq!(
            e("main._edge"),
            "unknown variable `main._edge`: `main` has no member `_edge`"
        );
        assert_eq!(
            e("main.tmr.edge"),
            "unknown variable `main.tmr.edge`: `main.tmr` has no member `edge`"
        );
        assert_eq!(
            e("main.tmp"),
            "`main.tmp` is a temporary variable: it exists only while its POU runs"
        );
        assert_eq!(
            e("main.count.x"),
            "unknown variable `main.count.x`: `main.count` (INT) has no member `x`"
        );
        assert_eq!(
            e("main.count[1]"),
            "unknown variable `main.count[1]`: `main.count` (INT) is not an array"
        );
        assert_eq!(
            e("main.arr[4]"),
            "index 4 of `main.arr[4]` is outside its bounds 1..3"
        );
        assert_eq!(
            e("main.m[0,1]"),
            "index 0 of `main.m[0,1]` is outside its bounds 1..2"
        );
        assert_eq!(
            e("main.m[1].x"),
            "unknown variable `main.m[1].x`: `main.m[1]` (ARRAY) has no member `x`"
        );
    }
}
