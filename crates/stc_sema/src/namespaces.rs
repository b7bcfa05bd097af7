//! Namespaces (IEC 61131-3 3rd edition): `NAMESPACE [INTERNAL] A.B ...
//! END_NAMESPACE`, `USING`, qualified names and INTERNAL elements.
//!
//! Shape. The tree keeps items flat (`Item::Namespace` and
//! `Item::EndNamespace` around the items they hold), so no pass that walks
//! items recurses. The analyser gives each element of a namespace its
//! qualified name (`Plant.Drives.Motor`) as its key in the one table of
//! global names: types, POUs, the IR and every back end then see one name
//! per element, and two elements of the same name in two namespaces are
//! two entries. What namespaces change is only how a name *written in the
//! source* is found: from where it is written. Each item (a POU with its
//! methods, a TYPE block, ...) gets a scope, a list of levels from the
//! innermost out, and a name is looked up by its span in the item that
//! contains it ([`Namespaces::scope_at`]), so no analysis needs to carry a
//! "current namespace" around.
//!
//! Lookup of an unqualified name `N` (docs/semantics-notes.md,
//! "Namespaces"), level by level, the first hit wins:
//! 1. the POU's own `USING` directives;
//! 2. each enclosing namespace, innermost first: its element `N`, then the
//!    namespaces named by the `USING` directives written in it;
//! 3. the global namespace: its element `N` (the user's global declarations
//!    and the standard library), then the file's top-level `USING`s.
//!
//! Within one level, two namespaces named by `USING` that both hold `N` make
//! `N` ambiguous (E1330). A dotted name `A.B.N` is element `N` of namespace
//! `A.B`, read relative to each enclosing namespace (innermost first), then
//! from the top. An element declared `INTERNAL` is found only from inside
//! its namespace (E1331 elsewhere). `NAMESPACE INTERNAL` restricts a
//! namespace to its project; a project is what stc compiles, so it changes
//! nothing here.

use rustc_hash::{FxHashMap, FxHashSet};
use stc_diagnostics::{Code, Diagnostic};
use stc_syntax::ast::{ExprId, ExprKind, Ident, Item, PouKind};
use stc_syntax::Symbol;

use crate::analyzer::{GlobalName, Scope, Sema};

/// The namespaces of a project and the scope of each of its items.
#[derive(Default, Clone)]
pub(crate) struct Namespaces {
    /// Whether the project declares or uses any namespace: if not, a name is
    /// simply its entry in the global table.
    pub active: bool,
    /// Every namespace by its qualified name (each prefix of `A.B.C` too).
    known: FxHashSet<Symbol>,
    /// Item spans in source order: `(lo, hi, scope)`.
    ranges: Vec<(u32, u32, u32)>,
    scopes: Vec<ScopeLevels>,
    /// INTERNAL elements: qualified name → their namespace.
    internal: FxHashMap<Symbol, Symbol>,
    /// Ambiguities and INTERNAL uses already reported, by span start.
    reported: FxHashSet<u32>,
}

#[derive(Clone, PartialEq)]
struct ScopeLevels {
    /// The innermost namespace of the item (`None` at the top).
    inner: Option<Symbol>,
    levels: Vec<Level>,
}

#[derive(Clone, PartialEq)]
struct Level {
    members: Members,
    usings: Vec<Symbol>,
}

#[derive(Clone, Copy, PartialEq)]
enum Members {
    /// A POU's own USING directives: a level with no elements.
    None,
    Namespace(Symbol),
    Global,
}

impl Namespaces {
    fn scope_at(&self, pos: u32) -> Option<&ScopeLevels> {
        let i = self.ranges.partition_point(|r| r.0 <= pos);
        let (lo, hi, s) = *self.ranges.get(i.checked_sub(1)?)?;
        (lo <= pos && pos < hi).then(|| &self.scopes[s as usize])
    }
}

/// What a name written somewhere denotes among the global elements.
pub(crate) struct Found {
    /// The element and its qualified name.
    pub hit: Option<(GlobalName, Symbol)>,
    /// The elements of the same name in several namespaces named by USING
    /// (the first is `hit`).
    pub ambiguous: Vec<Symbol>,
    /// The namespace of the INTERNAL element found, used from outside it.
    pub internal_to: Option<Symbol>,
    /// A dotted name whose qualifier names no namespace, found by its last
    /// part (W0117): the length of the qualifier.
    pub library_qualifier: Option<usize>,
}

/// An open namespace while items are walked.
struct Frame {
    ns: Symbol,
    usings: Vec<Symbol>,
}

impl<'a> Sema<'a> {
    /// Reads the namespaces of the project and gives each item its scope;
    /// returns each item's namespace (`None` at the top), whose qualified
    /// name prefixes the names the item declares.
    pub(crate) fn build_namespaces(&mut self) -> Vec<Option<Symbol>> {
        let ast = self.ast;
        let mut item_ns = vec![None; ast.items.len()];
        let active = ast.items.iter().any(|i| {
            matches!(i, Item::Namespace(_) | Item::Using(_))
                || matches!(i, Item::Pou(p) if !p.usings.is_empty() || p.internal)
        });
        if !active {
            return item_ns;
        }
        self.ns.active = true;
        // The namespaces first: a USING may name one declared further on.
        let mut stack: Vec<Symbol> = Vec::new();
        for (i, item) in ast.items.iter().enumerate() {
            match item {
                Item::Namespace(d) => {
                    let mut full = stack
                        .last()
                        .map(|s| self.interner.spelling(*s).to_string())
                        .unwrap_or_default();
                    let parts: Vec<String> = self
                        .interner
                        .spelling(d.name.sym)
                        .split('.')
                        .map(str::to_string)
                        .collect();
                    for part in &parts {
                        if !full.is_empty() {
                            full.push('.');
                        }
                        full.push_str(part);
                        let sym = self.interner.intern(&full);
                        self.ns.known.insert(sym);
                    }
                    stack.push(self.interner.intern(&full));
                }
                Item::EndNamespace(_) => {
                    stack.pop();
                }
                _ => item_ns[i] = stack.last().copied(),
            }
        }
        // Then the scopes.
        let mut frames: Vec<Frame> = Vec::new();
        let mut top_usings: Vec<Symbol> = Vec::new();
        let mut top_file = None;
        for (i, item) in ast.items.iter().enumerate() {
            let span = match item {
                Item::Namespace(d) => {
                    let ns = self.namespace_sym(frames.last().map(|f| f.ns), d.name);
                    frames.push(Frame {
                        ns,
                        usings: Vec::new(),
                    });
                    continue;
                }
                Item::EndNamespace(_) => {
                    frames.pop();
                    continue;
                }
                Item::Using(u) => {
                    let inner = frames.last().map(|f| f.ns);
                    let named: Vec<Symbol> = u
                        .names
                        .iter()
                        .filter_map(|n| self.using_target(inner, *n))
                        .collect();
                    match frames.last_mut() {
                        Some(f) => f.usings.extend(named),
                        None => {
                            let file = self.sources.file_of(u.span.lo);
                            if file != top_file {
                                top_usings.clear();
                                top_file = file;
                            }
                            top_usings.extend(named);
                        }
                    }
                    continue;
                }
                Item::Types(_, span) => *span,
                Item::Pou(p) => p.span,
                Item::Configuration(c) => c.span,
                Item::GlobalVars(b) => b.span,
            };
            if let Some(f) = frames.last() {
                let what = match item {
                    Item::Pou(p) if p.kind == PouKind::Program => Some(("a PROGRAM", p.name.span)),
                    Item::Configuration(c) => Some(("a CONFIGURATION", c.name.span)),
                    Item::GlobalVars(b) => Some(("a VAR_GLOBAL section", b.span)),
                    _ => None,
                };
                if let Some((what, at)) = what {
                    let ns = self.interner.spelling(f.ns).to_string();
                    self.emit(
                        Diagnostic::new(
                            Code::E1332,
                            at,
                            format!("{what} cannot be declared in a namespace"),
                        )
                        .with_label(format!("inside namespace `{ns}`"))
                        .with_help("a namespace holds data types, functions, function blocks, classes and interfaces: move this after END_NAMESPACE"),
                    );
                    // Read as if it stood outside the namespace.
                    item_ns[i] = None;
                }
            }
            let mut levels = Vec::new();
            if let Item::Pou(p) = item {
                if !p.usings.is_empty() {
                    let inner = frames.last().map(|f| f.ns);
                    let usings = p
                        .usings
                        .iter()
                        .filter_map(|n| self.using_target(inner, *n))
                        .collect();
                    levels.push(Level {
                        members: Members::None,
                        usings,
                    });
                }
            }
            if item_ns[i].is_some() {
                // The innermost namespace and every one around it (`A.B.C`
                // is inside `A.B` and `A`, written with one NAMESPACE or
                // several).
                let inner = frames.last().map(|f| f.ns);
                for ns in self.prefixes(inner) {
                    let usings = frames
                        .iter()
                        .filter(|f| f.ns == ns)
                        .flat_map(|f| f.usings.iter().copied())
                        .collect();
                    levels.push(Level {
                        members: Members::Namespace(ns),
                        usings,
                    });
                }
            }
            let file = self.sources.file_of(span.lo);
            levels.push(Level {
                members: Members::Global,
                usings: if file == top_file {
                    top_usings.clone()
                } else {
                    Vec::new()
                },
            });
            let scope = ScopeLevels {
                inner: item_ns[i],
                levels,
            };
            let id = match self.ns.scopes.last() {
                Some(last) if *last == scope => self.ns.scopes.len() - 1,
                _ => {
                    self.ns.scopes.push(scope);
                    self.ns.scopes.len() - 1
                }
            };
            self.ns.ranges.push((span.lo, span.hi, id as u32));
        }
        self.ns.ranges.sort_by_key(|r| r.0);
        item_ns
    }

    /// The qualified name of namespace `name` declared inside `outer`.
    fn namespace_sym(&mut self, outer: Option<Symbol>, name: Ident) -> Symbol {
        match outer {
            Some(o) => {
                let full = format!(
                    "{}.{}",
                    self.interner.spelling(o),
                    self.interner.spelling(name.sym)
                );
                self.interner.intern(&full)
            }
            None => name.sym,
        }
    }

    /// `ns` and every namespace around it, innermost first.
    fn prefixes(&self, ns: Option<Symbol>) -> Vec<Symbol> {
        let Some(ns) = ns else {
            return Vec::new();
        };
        let key = self.interner.key(ns);
        let mut out = vec![ns];
        let mut end = key.len();
        while let Some(dot) = key[..end].rfind('.') {
            if let Some(s) = self.interner.get(&key[..dot]) {
                out.push(s);
            }
            end = dot;
        }
        out
    }

    /// The namespace a USING directive written inside `inner` names: read
    /// relative to `inner` and each namespace around it, then from the top.
    fn using_target(&mut self, inner: Option<Symbol>, name: Ident) -> Option<Symbol> {
        let written = self.interner.key(name.sym).to_string();
        for ns in self.prefixes(inner) {
            let cand = format!("{}.{written}", self.interner.key(ns));
            if let Some(s) = self
                .interner
                .get(&cand)
                .filter(|s| self.ns.known.contains(s))
            {
                return Some(s);
            }
        }
        if self.ns.known.contains(&name.sym) {
            return Some(name.sym);
        }
        let shown = self.spelled(name.sym, name.span);
        self.emit(
            Diagnostic::new(
                Code::E1329,
                name.span,
                format!("there is no namespace `{shown}`"),
            )
            .with_label("no NAMESPACE has this name"),
        );
        None
    }

    /// The qualified name of `name` declared in namespace `ns`.
    pub(crate) fn qualify(&mut self, name: Ident, ns: Option<Symbol>) -> Ident {
        match ns {
            None => name,
            Some(ns) => {
                let full = format!(
                    "{}.{}",
                    self.interner.spelling(ns),
                    self.interner.spelling(name.sym)
                );
                Ident {
                    sym: self.interner.intern(&full),
                    span: name.span,
                }
            }
        }
    }

    /// Records that the element named `qualified` is INTERNAL to `ns`.
    pub(crate) fn mark_internal(&mut self, qualified: Symbol, ns: Option<Symbol>) {
        if let Some(ns) = ns {
            self.ns.internal.insert(qualified, ns);
        }
    }

    /// The global element (type, POU, configuration) a name written at
    /// `id.span` denotes, reporting an ambiguity (E1330) or a use of an
    /// INTERNAL element from outside its namespace (E1331).
    pub(crate) fn global_name(&mut self, id: Ident) -> Option<GlobalName> {
        let found = self.find_global(id);
        if !found.ambiguous.is_empty() && self.ns.reported.insert(id.span.lo) {
            let shown = self.spelled(id.sym, id.span);
            let names: Vec<String> = found
                .ambiguous
                .iter()
                .map(|s| format!("`{}`", self.interner.spelling(*s)))
                .collect();
            self.emit(
                Diagnostic::new(
                    Code::E1330,
                    id.span,
                    format!("`{shown}` is ambiguous: {}", names.join(" and ")),
                )
                .with_label("found in more than one namespace named by USING")
                .with_help("write the name with its namespace"),
            );
        }
        if let Some(home) = found.internal_to {
            if self.ns.reported.insert(id.span.lo) {
                let shown = self.spelled(id.sym, id.span);
                let home = self.interner.spelling(home).to_string();
                self.emit(
                    Diagnostic::new(
                        Code::E1331,
                        id.span,
                        format!("`{shown}` is INTERNAL to namespace `{home}`"),
                    )
                    .with_label("used outside its namespace")
                    .with_help(format!(
                        "use it only inside `{home}`, or remove INTERNAL from its declaration"
                    )),
                );
            }
        }
        if let Some(dot) = found.library_qualifier {
            let shown = self.spelled(id.sym, id.span);
            let (qualifier, name) = (&shown[..dot.min(shown.len())], shown.get(dot + 1..));
            let name = name.unwrap_or_default();
            self.emit(
                Diagnostic::new(
                    Code::W0117,
                    id.span,
                    format!("`{qualifier}` names no namespace: `{shown}` is read as `{name}`"),
                )
                .with_label("a library's qualifier, as CODESYS and TwinCAT write it")
                .with_help(format!("write `{name}`, or declare NAMESPACE {qualifier}")),
            );
        }
        found.hit.map(|(g, _)| g)
    }

    /// Whether a name written at `id.span` denotes a global element, without
    /// a word about what may be wrong with the use.
    pub(crate) fn is_global_name(&self, id: Ident) -> bool {
        self.find_global(id).hit.is_some()
    }

    /// What a name written at `id.span` denotes among the global elements
    /// (see the module's documentation for the order).
    pub(crate) fn find_global(&self, id: Ident) -> Found {
        let plain = |hit| Found {
            hit,
            ambiguous: Vec::new(),
            internal_to: None,
            library_qualifier: None,
        };
        let written = self.interner.key(id.sym);
        let dotted = written.rfind('.');
        if !self.ns.active && dotted.is_none() {
            return plain(self.names.get(&id.sym).map(|g| (*g, id.sym)));
        }
        let scope = self.ns.scope_at(id.span.lo);
        let mut ambiguous = Vec::new();
        let mut found = None;
        if let Some(dot) = dotted {
            for level in scope.iter().flat_map(|s| &s.levels) {
                if let Members::Namespace(ns) = level.members {
                    found = self.element(&format!("{}.{written}", self.interner.key(ns)));
                    if found.is_some() {
                        break;
                    }
                }
            }
            found = found.or_else(|| self.names.get(&id.sym).map(|g| (*g, id.sym)));
            if found.is_none() && !self.opts.iec2 && !self.names_namespace(&written[..dot], scope) {
                // A library's qualifier (`Tc2_Standard.TON`): the element
                // by its own name, where the name is written.
                let last = self.interner.get(&written[dot + 1..]);
                if let Some(sym) = last {
                    let inner = self.find_global(Ident { sym, span: id.span });
                    return Found {
                        library_qualifier: inner.hit.map(|_| dot),
                        ..inner
                    };
                }
            }
        } else if let Some(scope) = scope {
            for level in &scope.levels {
                found = match level.members {
                    Members::None => None,
                    Members::Namespace(ns) => {
                        self.element(&format!("{}.{written}", self.interner.key(ns)))
                    }
                    Members::Global => self.names.get(&id.sym).map(|g| (*g, id.sym)),
                };
                if found.is_some() {
                    break;
                }
                let mut hits: Vec<(GlobalName, Symbol)> = Vec::new();
                for &u in &level.usings {
                    let hit = self.element(&format!("{}.{written}", self.interner.key(u)));
                    if let Some(hit) = hit.filter(|h| !hits.iter().any(|k| k.1 == h.1)) {
                        hits.push(hit);
                    }
                }
                if hits.len() > 1 {
                    ambiguous = hits.iter().map(|h| h.1).collect();
                }
                if let Some(hit) = hits.first() {
                    found = Some(*hit);
                    break;
                }
            }
        }
        let internal_to = found.and_then(|(_, sym)| {
            let home = *self.ns.internal.get(&sym)?;
            let inside = self.within(scope.and_then(|s| s.inner), self.interner.key(home));
            (!inside).then_some(home)
        });
        Found {
            hit: found,
            ambiguous,
            internal_to,
            library_qualifier: None,
        }
    }

    /// Whether `prefix` (a dotted name's part before its last dot) names a
    /// namespace where `scope` is: relative to an enclosing one, or from
    /// the top.
    fn names_namespace(&self, prefix: &str, scope: Option<&ScopeLevels>) -> bool {
        let known = |key: &str| {
            self.interner
                .get(key)
                .is_some_and(|s| self.ns.known.contains(&s))
        };
        known(prefix)
            || scope.is_some_and(|s| {
                s.levels.iter().any(|l| match l.members {
                    Members::Namespace(ns) => known(&format!("{}.{prefix}", self.interner.key(ns))),
                    _ => false,
                })
            })
    }

    /// The namespace POU `p` is declared in (its qualified name's part
    /// before the last dot), as spelled.
    pub(crate) fn namespace_of(&self, p: crate::PouId) -> Option<String> {
        let name = self.interner.spelling(self.pous[p.0 as usize].name);
        name.rsplit_once('.').map(|(ns, _)| ns.to_string())
    }

    /// Whether a use at `at` is inside the namespace of POU `p` (or one
    /// nested in it): where its INTERNAL members are visible. A POU outside
    /// every namespace has the whole project as its namespace.
    pub(crate) fn in_namespace_of(&self, p: crate::PouId, at: stc_diagnostics::Span) -> bool {
        let Some(home) = self.namespace_of(p) else {
            return true;
        };
        let inner = self.ns.scope_at(at.lo).and_then(|s| s.inner);
        self.within(inner, &home.to_ascii_uppercase())
    }

    /// Whether a use whose innermost namespace is `inner` stands inside
    /// the namespace of key `home` (or one nested in it): where what is
    /// INTERNAL to `home` is visible.
    fn within(&self, inner: Option<Symbol>, home: &str) -> bool {
        inner.is_some_and(|inner| {
            let k = self.interner.key(inner);
            k.strip_prefix(home)
                .is_some_and(|rest| rest.is_empty() || rest.starts_with('.'))
        })
    }

    /// The global element of qualified name `key`, if one is declared.
    fn element(&self, key: &str) -> Option<(GlobalName, Symbol)> {
        let sym = self.interner.get(key)?;
        self.names.get(&sym).map(|g| (*g, sym))
    }

    /// `Drives.Scale(x)`: the callee `Drives.Scale`, a function named with
    /// its namespace, as one qualified name. `None` when the dotted
    /// expression starts with a variable (an instance's method) or with no
    /// namespace's name.
    pub(crate) fn qualified_callee(&mut self, callee: ExprId, scope: Scope) -> Option<Ident> {
        if !self.ns.active {
            return None;
        }
        let mut parts = Vec::new();
        let mut e = callee;
        let head = loop {
            match &self.ast.expr(e).kind {
                ExprKind::Member { base, member } => {
                    parts.push(*member);
                    e = *base;
                }
                ExprKind::Name(id) => break *id,
                _ => return None,
            }
        };
        if let Scope::Pou(p) = scope {
            let pou = &self.pous[p.0 as usize];
            let var = pou.lookup(head.sym).is_some()
                || pou
                    .method_of
                    .is_some_and(|(fb, _)| self.pous[fb.0 as usize].lookup(head.sym).is_some());
            if var {
                return None;
            }
        }
        if !self.namespace_prefix(head) {
            return None;
        }
        let mut text = self.spelled(head.sym, head.span);
        for m in parts.iter().rev() {
            text.push('.');
            text.push_str(&self.spelled(m.sym, m.span));
        }
        Some(Ident {
            sym: self.interner.intern(&text),
            span: self.ast.expr(callee).span,
        })
    }

    /// Whether `head` (the first name of a dotted expression `head.x.y`)
    /// names a namespace where it is written: one declared at the top, or
    /// inside a namespace around the use.
    fn namespace_prefix(&self, head: Ident) -> bool {
        if !self.ns.active {
            return false;
        }
        let written = self.interner.key(head.sym);
        if self.ns.known.contains(&head.sym) {
            return true;
        }
        let Some(scope) = self.ns.scope_at(head.span.lo) else {
            return false;
        };
        scope.levels.iter().any(|l| match l.members {
            Members::Namespace(ns) => {
                let cand = format!("{}.{written}", self.interner.key(ns));
                self.interner
                    .get(&cand)
                    .is_some_and(|s| self.ns.known.contains(&s))
            }
            _ => false,
        })
    }
}
