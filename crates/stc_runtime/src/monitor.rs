//! Online monitoring and forcing (`stc run --realtime --monitor`): what
//! the monitor's server needs of the runtime, with no I/O.
//!
//! - [`variables`]: every variable a path can name (in the syntax of
//!   `--watch`), with its type, for the list a client chooses from;
//! - [`Forces`]: the forced variables and their values, written into the
//!   program's memory between cycles (docs/runtime.md, "Forcing");
//! - [`json_of`]: a value as JSON, as reports print it.
//!
//! Paths are resolved by [`Scope::resolve`], values read from text by
//! [`crate::value::parse_for`] and printed by [`crate::report`]: the
//! monitor has no path or value syntax of its own.

use stc_ir::model::{Model, TypeDesc, TypeRef};
use stc_syntax::literal::AddrArea;
use stc_values::Value;

use crate::engine::Memory;
use crate::error::{Error, Result};
use crate::path::{describe, is_member, Place, Scope, View};
use crate::report::json_value;
use crate::value::{parse_for, read, Shown};

/// A variable the monitor lists.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct VarInfo {
    /// Its path, declared spelling.
    pub path: String,
    /// Its type's name (`INT`, `STRING[80]`, `TON`, `ARRAY`).
    pub ty: String,
    /// Whether it can be forced: an elementary, string or enumerated
    /// variable that is not CONSTANT.
    pub forcible: bool,
}

/// Arrays with at most this many elements are listed element by element
/// too.
const MAX_LISTED_ELEMENTS: u64 = 64;
/// Deeper than any program nests its data (a hostile table may cycle).
const MAX_DEPTH: u32 = 16;

/// Every variable of what runs that a path names, at most `limit`: the
/// data of each program instance (inputs, outputs, VAR, located
/// variables) and of the function block instances and structures in it,
/// then the visible globals; arrays as a whole, and element by element
/// when they are small.
pub fn variables(scope: &Scope, limit: usize) -> Vec<VarInfo> {
    let model = scope.model;
    let mut out = Vec::new();
    for inst in scope.instances {
        let Some(pou) = model.pous.get(inst.pou as usize) else {
            continue;
        };
        for v in &pou.vars {
            if is_member(v) && v.kind != stc_ir::model::VarKind::Global {
                walk(
                    scope,
                    format!("{}.{}", inst.name, v.name),
                    0,
                    limit,
                    &mut out,
                );
            }
        }
    }
    let mut seen: Vec<String> = Vec::new();
    for g in &model.globals {
        let visible = g.config.is_none() || g.config == scope.config;
        if !visible
            || seen.iter().any(|s| s.eq_ignore_ascii_case(&g.name))
            || g.location
                .as_ref()
                .is_some_and(|l| l.area == AddrArea::Memory && g.name.starts_with('%'))
        {
            continue;
        }
        seen.push(g.name.clone());
        walk(scope, g.name.clone(), 0, limit, &mut out);
    }
    out
}

fn leaf(desc: Option<&TypeDesc>) -> bool {
    matches!(
        desc,
        Some(
            TypeDesc::Scalar(_)
                | TypeDesc::Subrange { .. }
                | TypeDesc::String { .. }
                | TypeDesc::Enum { .. }
        )
    )
}

fn walk(scope: &Scope, path: String, depth: u32, limit: usize, out: &mut Vec<VarInfo>) {
    if out.len() >= limit || depth > MAX_DEPTH {
        return;
    }
    let Ok(place) = scope.resolve(&path) else {
        return;
    };
    let model = scope.model;
    let ty: TypeRef = match place.view {
        View::Type(t) => t,
        View::Slice { .. } => return,
    };
    let desc = model.types.get(ty as usize);
    match desc {
        Some(TypeDesc::Struct { fields, .. }) => {
            for f in fields {
                walk(
                    scope,
                    format!("{}.{}", place.name, f.name),
                    depth + 1,
                    limit,
                    out,
                );
            }
        }
        Some(TypeDesc::Instance { pou }) => {
            let Some(p) = model.pous.get(*pou as usize) else {
                return;
            };
            for v in &p.vars {
                if is_member(v) {
                    walk(
                        scope,
                        format!("{}.{}", place.name, v.name),
                        depth + 1,
                        limit,
                        out,
                    );
                }
            }
        }
        Some(TypeDesc::Array { elem, dims, .. }) => {
            out.push(VarInfo {
                path: place.name.clone(),
                ty: format!(
                    "ARRAY [{}] OF {}",
                    dims.iter()
                        .map(|(lo, hi)| format!("{lo}..{hi}"))
                        .collect::<Vec<_>>()
                        .join(", "),
                    describe(model, model.types.get(*elem as usize))
                ),
                forcible: false,
            });
            let count = dims.iter().try_fold(1u64, |n, (lo, hi)| {
                n.checked_mul(u64::try_from(i128::from(*hi) - i128::from(*lo) + 1).ok()?)
            });
            if count.is_some_and(|n| n <= MAX_LISTED_ELEMENTS) {
                let mut index: Vec<i64> = dims.iter().map(|d| d.0).collect();
                'all: loop {
                    let text: Vec<String> = index.iter().map(|i| i.to_string()).collect();
                    walk(
                        scope,
                        format!("{}[{}]", place.name, text.join(",")),
                        depth + 1,
                        limit,
                        out,
                    );
                    // The next index, the last dimension fastest.
                    for d in (0..dims.len()).rev() {
                        if index[d] < dims[d].1 {
                            index[d] += 1;
                            continue 'all;
                        }
                        index[d] = dims[d].0;
                    }
                    break;
                }
            }
        }
        d => out.push(VarInfo {
            path: place.name.clone(),
            ty: describe(model, d),
            forcible: leaf(d) && !place.constant,
        }),
    }
}

/// A place that may be forced: an elementary, string or enumerated
/// variable, not CONSTANT. An unknown variable is [`Error::Path`], one
/// that cannot be forced [`Error::Value`].
pub fn forcible(scope: &Scope, path: &str) -> Result<Place> {
    let place = scope.resolve(path)?;
    if place.constant {
        return Err(Error::Value(format!(
            "`{}` is a CONSTANT and cannot be forced",
            place.name
        )));
    }
    let desc = match place.view {
        View::Type(t) => scope.model.types.get(t as usize),
        View::Slice { .. } => None,
    };
    if !leaf(desc) {
        return Err(Error::Value(format!(
            "`{}` is {}: only an elementary, string or enumerated variable can be forced (name an element or a member)",
            place.name,
            match &place.view {
                View::Slice { .. } => "part of an array".to_string(),
                View::Type(_) => describe(scope.model, desc),
            }
        )));
    }
    Ok(place)
}

/// One forced variable.
#[derive(Clone, Debug, PartialEq)]
pub struct Force {
    pub place: Place,
    pub value: Value,
    /// The value as it was given (for the list of forces).
    pub text: String,
}

/// The forced variables, in the order they were forced.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Forces(pub Vec<Force>);

impl Forces {
    /// Forces `path` to `text` (an ST literal of its type), replacing an
    /// earlier force of the same variable; returns the variable's path.
    pub fn force(&mut self, scope: &Scope, path: &str, text: &str) -> Result<String> {
        let place = forcible(scope, path)?;
        let value = parse_for(scope.model, &place.view, text)
            .map_err(|e| Error::Value(format!("{}: {e}", place.name)))?;
        let name = place.name.clone();
        let f = Force {
            place,
            value,
            text: text.trim().to_string(),
        };
        match self.0.iter_mut().find(|g| g.place.name == name) {
            Some(g) => *g = f,
            None => self.0.push(f),
        }
        Ok(name)
    }

    /// Releases the force of `path`; `Ok(false)` when it was not forced.
    pub fn release(&mut self, scope: &Scope, path: &str) -> Result<bool> {
        let place = scope.resolve(path)?;
        let before = self.0.len();
        self.0.retain(|f| f.place.name != place.name);
        Ok(self.0.len() != before)
    }

    pub fn is_forced(&self, path: &str) -> bool {
        self.0.iter().any(|f| f.place.name == path)
    }

    /// Writes every forced value into memory.
    pub fn apply(&self, model: &Model, engine: &mut dyn Memory) {
        for f in &self.0 {
            crate::sim::write(model, engine, &f.place, &f.value);
        }
    }
}

/// The value at a place as JSON, as `--format json` prints it.
pub fn json_of(model: &Model, mem: &dyn Memory, place: &Place) -> String {
    let shown = match place.loc.address(mem) {
        Some(a) => read(model, mem, a, &place.view),
        None => Shown::Unreadable,
    };
    let mut out = String::new();
    json_value(&mut out, &shown);
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::schedule::{Chosen, Plan};
    use crate::testing::sample_model;

    #[test]
    fn variables_are_listed_by_their_paths_and_forces_take_st_literals() {
        let m = sample_model();
        let plan = Plan::new(&m, Chosen::Config(0), None).unwrap();
        let scope = Scope {
            model: &m,
            instances: &plan.instances,
            config: plan.config,
        };
        let vars = variables(&scope, 10_000);
        let find = |p: &str| vars.iter().find(|v| v.path == p);
        assert!(find("main.count").is_some_and(|v| v.ty == "INT" && v.forcible));
        assert!(find("main.m").is_some_and(|v| !v.forcible));
        assert!(find("main.m[2,1]").is_some());
        assert!(find("main.tmr.PT").is_some());
        assert!(find("K").is_some_and(|v| !v.forcible));
        assert_eq!(variables(&scope, 3).len(), 3);
        // Every listed path resolves to itself.
        for v in &vars {
            assert_eq!(scope.resolve(&v.path).unwrap().name, v.path);
        }

        let mut f = Forces::default();
        assert_eq!(f.force(&scope, "MAIN.count", "7").unwrap(), "main.count");
        assert!(f.is_forced("main.count"));
        f.force(&scope, "main.count", "8").unwrap();
        assert_eq!(f.0.len(), 1);
        assert!(f.force(&scope, "main.count", "abc").is_err());
        assert!(f
            .force(&scope, "K", "1")
            .unwrap_err()
            .to_string()
            .contains("CONSTANT"));
        assert!(f.force(&scope, "main.m", "1").is_err());
        assert!(f.force(&scope, "main.nope", "1").is_err());
        let mut mem = crate::testing::sample().init;
        f.apply(&m, &mut mem);
        let place = scope.resolve("main.count").unwrap();
        assert_eq!(json_of(&m, &mem, &place), "8");
        assert!(f.release(&scope, "main.count").unwrap());
        assert!(!f.release(&scope, "main.count").unwrap());
    }
}
