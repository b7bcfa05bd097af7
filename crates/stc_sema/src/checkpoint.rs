//! Analysing a project in two parts, keeping the first between edits.
//!
//! A language server analyses the same project again after every edit,
//! and an edit is almost always in one file. [`analyze_split`] analyses
//! the items before a split point (every file but the one being edited,
//! and the prelude) on their own, keeps the analyser's state at that
//! point in a [`Checkpoint`], then goes on with the last file's items;
//! after the next edit of that file, [`resume`] starts again from the
//! checkpoint, so only the edited file is declared and checked (the
//! project-wide checks of [`crate::analyzer::Sema::finish`] run again).
//!
//! **Exactness.** The result must be the diagnostics of a whole analysis
//! ([`crate::analyze`]), in which the first part's bodies are checked with
//! the last file's declarations already known. They are the same whenever
//! the last file cannot change what the first part means, which is
//! checked after the last file's part, from what it did, and otherwise
//! the whole analysis is made instead:
//! - no name the last file declares at the global level (a type, POU,
//!   configuration, global variable, enumeration value, a name it gives
//!   to `REF`/`ADR`, a name of an unsupported construct) is a word of the
//!   first part's text (its files and the prelude): so no lookup of the
//!   first part could have found it, nor a warning about a hidden global,
//!   nor constant propagation stopped for it;
//! - no POU of the last file extends or implements one of the first part
//!   (which changes the unused-variable warnings of a base and the
//!   overrides a method call may reach);
//! - neither part uses namespaces (whose scopes span items);
//! - the first part has no error whose suggestion is drawn from every
//!   global name ([`SUGGESTS_GLOBALS`]), which the last file's names could
//!   change.
//!
//! The analyser's state borrows the tree (declarations are resolved
//! lazily from their syntax); the checkpoint keeps it as positions in the
//! first part's items ([`Anchors`]), which an incremental re-parse leaves
//! as they were, and binds them again to the new tree.

use rustc_hash::{FxHashMap, FxHashSet};
use stc_diagnostics::{Code, SourceMap, Span};
use stc_syntax::ast::{Ast, Item, TypeDecl, VarBlock, VarBlockItems};
use stc_syntax::{Interner, Symbol};

use crate::analyzer::{ref_taken_names, Ctx, Owned, Refs, Sema, State, TypeDeclEntry, VarSource};
use crate::types::{InitValue, TypeId};
use crate::{Analysis, Options, PouId};

/// Errors whose "did you mean" is drawn from every global name: a name of
/// the last file could be a better suggestion for one in the first part.
pub const SUGGESTS_GLOBALS: [Code; 4] = [Code::E0101, Code::E0102, Code::E0103, Code::E0107];

/// Where the first part of a project ends: its files (the source map's),
/// items, expressions and unsupported names are a prefix of the tree's.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Split {
    pub files: usize,
    pub items: usize,
    pub exprs: usize,
    pub unsupported: usize,
}

impl Split {
    /// Whether the tree and the sources have a first part this long.
    fn fits(&self, ast: &Ast, sources: &SourceMap) -> bool {
        self.items <= ast.items.len()
            && self.exprs <= ast.exprs.len()
            && self.unsupported <= ast.unsupported_names.len()
            && self.files <= sources.len()
    }
}

/// The analyser's state after the first part of a project.
pub struct Checkpoint {
    owned: Owned,
    anchors: Anchors,
    split: Split,
    prelude: Option<Span>,
    iec2: bool,
    /// Every word of the first part's text.
    words: FxHashSet<Symbol>,
}

/// How a whole analysis was made.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Made {
    /// The last file's part, from the first part's checkpoint.
    Resumed,
    /// The whole project (the two parts could not be told apart, or there
    /// was no checkpoint).
    Whole,
}

/// The analyser's references into the first part's syntax, as positions
/// in the enumerations [`type_decls_of`] and [`var_blocks_of`].
struct Anchors {
    /// Per declared type: its declaration, name, state, type and value.
    types: Vec<(u32, Symbol, State, TypeId, Option<InitValue>)>,
    /// Per POU variable: (block, declaration in the block).
    pou_vars: Vec<Vec<Option<(u32, u32)>>>,
    globals: Vec<(u32, u32)>,
}

/// The type declarations of `items`, in a fixed order.
fn type_decls_of(ast: &Ast, items: std::ops::Range<usize>) -> Vec<&TypeDecl> {
    let mut out = Vec::new();
    for item in &ast.items[items] {
        if let Item::Types(decls, _) = item {
            out.extend(decls.iter());
        }
    }
    out
}

/// The variable blocks of `items`, in a fixed order.
fn var_blocks_of(ast: &Ast, items: std::ops::Range<usize>) -> Vec<&VarBlock> {
    let mut out = Vec::new();
    for item in &ast.items[items] {
        match item {
            Item::Pou(p) => {
                out.extend(p.var_blocks.iter());
                for m in &p.methods {
                    out.extend(m.pou.var_blocks.iter());
                }
            }
            Item::GlobalVars(b) => out.push(b),
            Item::Configuration(c) => {
                out.extend(c.var_blocks.iter());
                for r in &c.resources {
                    out.extend(r.var_blocks.iter());
                }
            }
            Item::Types(..) | Item::Namespace(_) | Item::EndNamespace(_) | Item::Using(_) => {}
        }
    }
    out
}

fn decls_of(b: &VarBlock) -> &[stc_syntax::ast::VarDecl] {
    match &b.items {
        VarBlockItems::Vars(d) => d,
        _ => &[],
    }
}

impl Anchors {
    /// The positions of `refs`, all in `items` of `ast` (`None` if one is
    /// not).
    fn of(sema: &Sema<'_>, items: std::ops::Range<usize>) -> Option<Anchors> {
        let ast = sema.ast;
        let types: FxHashMap<*const TypeDecl, u32> = type_decls_of(ast, items.clone())
            .into_iter()
            .enumerate()
            .map(|(i, d)| (d as *const TypeDecl, i as u32))
            .collect();
        let blocks: FxHashMap<*const VarBlock, u32> = var_blocks_of(ast, items)
            .into_iter()
            .enumerate()
            .map(|(i, b)| (b as *const VarBlock, i as u32))
            .collect();
        let var = |s: &VarSource<'_>| -> Option<(u32, u32)> {
            let b = *blocks.get(&(s.block as *const VarBlock))?;
            let d = decls_of(s.block)
                .iter()
                .position(|d| std::ptr::eq(d, s.decl))?;
            Some((b, d as u32))
        };
        let mut out = Anchors {
            types: Vec::with_capacity(sema.type_decls.len()),
            pou_vars: Vec::with_capacity(sema.pou_var_src.len()),
            globals: Vec::with_capacity(sema.global_src.len()),
        };
        for t in &sema.type_decls {
            let i = *types.get(&(t.decl as *const TypeDecl))?;
            out.types.push((i, t.name, t.state, t.ty, t.init.clone()));
        }
        for vars in &sema.pou_var_src {
            let mut row = Vec::with_capacity(vars.len());
            for v in vars {
                row.push(match v {
                    Some(s) => Some(var(s)?),
                    None => None,
                });
            }
            out.pou_vars.push(row);
        }
        for g in &sema.global_src {
            out.globals.push(var(g)?);
        }
        Some(out)
    }

    /// The references again, into `items` of `ast` (`None` if the items
    /// are not those the anchors were taken from).
    fn bind<'a>(&self, ast: &'a Ast, items: std::ops::Range<usize>) -> Option<Refs<'a>> {
        let types = type_decls_of(ast, items.clone());
        let blocks = var_blocks_of(ast, items);
        let var = |&(b, d): &(u32, u32)| -> Option<VarSource<'a>> {
            let block = *blocks.get(b as usize)?;
            let decl = decls_of(block).get(d as usize)?;
            Some(VarSource { block, decl })
        };
        let mut refs = Refs::default();
        for (i, name, state, ty, init) in &self.types {
            refs.type_decls.push(TypeDeclEntry {
                decl: types.get(*i as usize)?,
                name: *name,
                state: *state,
                ty: *ty,
                init: init.clone(),
            });
        }
        for row in &self.pou_vars {
            let mut out = Vec::with_capacity(row.len());
            for v in row {
                out.push(match v {
                    Some(a) => Some(var(a)?),
                    None => None,
                });
            }
            refs.pou_var_src.push(out);
        }
        for g in &self.globals {
            refs.global_src.push(var(g)?);
        }
        Some(refs)
    }
}

/// Every identifier-like word of the first `files` files of `sources`
/// that names a symbol of `interner`.
fn words(sources: &SourceMap, files: usize, interner: &Interner) -> FxHashSet<Symbol> {
    let mut seen: FxHashSet<&str> = FxHashSet::default();
    for (_, f) in sources.files().take(files) {
        let b = f.text.as_bytes();
        let mut i = 0;
        while i < b.len() {
            if b[i].is_ascii_alphabetic() || b[i] == b'_' {
                let start = i;
                while i < b.len() && (b[i].is_ascii_alphanumeric() || b[i] == b'_') {
                    i += 1;
                }
                seen.insert(&f.text[start..i]);
            } else {
                i += 1;
            }
        }
    }
    seen.into_iter().filter_map(|w| interner.get(w)).collect()
}

/// A whole analysis of the project, made in two parts at `split` when it
/// can be (see the module documentation), with the checkpoint after the
/// first part for [`resume`].
pub fn analyze_split(
    ast: &Ast,
    interner: &mut Interner,
    sources: &SourceMap,
    prelude: Option<Span>,
    opts: Options,
    split: Split,
) -> (Analysis, Option<Checkpoint>, Made) {
    if !split.fits(ast, sources) {
        let a = crate::analyze(ast, interner, sources, prelude, opts);
        return (a, None, Made::Whole);
    }
    let ctx = Ctx {
        ast,
        interner,
        sources,
        prelude,
        opts,
    };
    let mut sema = Sema::upto(ctx, split.exprs, split.unsupported);
    let order = sema.analysis_order(0..split.items);
    sema.analyse_items(&order);
    let checkpoint = save(&sema, split);
    let resumed = match &checkpoint {
        Some(cp) => go_on(sema, cp),
        None => {
            drop(sema);
            None
        }
    };
    match resumed {
        Some(a) => (a, checkpoint, Made::Resumed),
        None => {
            let a = crate::analyze(ast, interner, sources, prelude, opts);
            (a, checkpoint, Made::Whole)
        }
    }
}

/// A whole analysis of the project, whose first part is the checkpoint's
/// (the same items, expressions and files: the tree re-parsed after its
/// last file changed), made from the checkpoint when it can be.
pub fn resume(
    cp: &Checkpoint,
    ast: &Ast,
    interner: &mut Interner,
    sources: &SourceMap,
    prelude: Option<Span>,
    opts: Options,
) -> (Analysis, Made) {
    let same = cp.prelude == prelude && cp.iec2 == opts.iec2 && cp.split.fits(ast, sources);
    let refs = if same {
        cp.anchors.bind(ast, 0..cp.split.items)
    } else {
        None
    };
    if let Some(refs) = refs {
        let ctx = Ctx {
            ast,
            interner: &mut *interner,
            sources,
            prelude,
            opts,
        };
        let sema = Sema::from_parts(ctx, cp.owned.clone(), refs);
        if let Some(a) = go_on(sema, cp) {
            return (a, Made::Resumed);
        }
    }
    (
        crate::analyze(ast, interner, sources, prelude, opts),
        Made::Whole,
    )
}

/// The checkpoint of an analyser that has analysed the first part.
fn save(sema: &Sema<'_>, split: Split) -> Option<Checkpoint> {
    if sema.ns.active
        || sema
            .diags
            .iter()
            .any(|d| SUGGESTS_GLOBALS.contains(&d.code))
    {
        return None;
    }
    let anchors = Anchors::of(sema, 0..split.items)?;
    Some(Checkpoint {
        owned: sema.owned(),
        anchors,
        split,
        prelude: sema.prelude,
        iec2: sema.opts.iec2,
        words: words(sema.sources, split.files, sema.interner),
    })
}

/// Analyses the last file's items after the first part, and finishes the
/// analysis; `None` when the result could differ from a whole analysis.
fn go_on(mut sema: Sema<'_>, cp: &Checkpoint) -> Option<Analysis> {
    let ast = sema.ast;
    let split = cp.split;
    let first_pou = sema.pous.len();
    let declared = sema.declared.len();
    sema.expr_types.resize(ast.exprs.len(), TypeId::ERROR);
    let refs = ref_taken_names(ast, split.exprs..ast.exprs.len(), sema.interner);
    let unsupported: Vec<Symbol> = ast.unsupported_names[split.unsupported..]
        .iter()
        .map(|n| n.sym)
        .collect();
    if refs
        .iter()
        .chain(unsupported.iter())
        .any(|s| cp.words.contains(s))
    {
        return None;
    }
    sema.ref_taken.extend(refs);
    sema.unsupported_names.extend(unsupported);
    let order = sema.analysis_order(split.items..ast.items.len());
    sema.analyse_items(&order);
    let first = |p: &PouId| (p.0 as usize) < first_pou;
    let reaches_back = sema.pous[first_pou..]
        .iter()
        .any(|d| d.base.as_ref().is_some_and(first) || d.interfaces.iter().any(first));
    if sema.ns.active
        || reaches_back
        || sema.declared[declared..]
            .iter()
            .any(|s| cp.words.contains(s))
    {
        return None;
    }
    Some(sema.finish())
}
