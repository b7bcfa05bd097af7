//! The project as the server sees it: the last analysis of every file, and
//! the questions requests ask of its syntax tree.

use std::collections::BTreeMap;

use lsp_types::{
    CompletionItem, CompletionItemKind, DiagnosticSeverity, DocumentSymbol, Hover, HoverContents,
    Location, MarkupContent, MarkupKind, NumberOrString, Position, Range, SymbolKind,
};
use stc_diagnostics::{Severity, SourceMap, Span};
use stc_syntax::ast::{
    Item, Pou, PouKind, TypeDecl, TypeSpecKind, VarBlock, VarBlockItems, VarDecl, VarKind,
};
use stc_syntax::lexer::{lex, TriviaKind};
use stc_syntax::token::{ElemType, Keyword};
use stc_syntax::Symbol;

use crate::position;

pub struct Project {
    analysed: stc_pipeline::Analysed,
}

/// A declaration found for a name.
#[derive(Clone, Copy)]
pub(crate) enum Decl<'a> {
    Var(&'a VarDecl, VarKind),
    Pou(&'a Pou),
    Type(&'a TypeDecl),
    EnumValue(&'a TypeDecl),
}

impl Project {
    /// Analyses the files (URI, text) as one project, in this order.
    pub fn analyse(files: Vec<(String, String)>, opts: stc_pipeline::Options) -> Project {
        Project::analyse_with(files, opts, None)
    }

    /// [`Project::analyse`] with the lints at `lints`: a full analysis,
    /// what the incremental one must equal.
    pub fn analyse_with(
        files: Vec<(String, String)>,
        opts: stc_pipeline::Options,
        lints: Option<stc_lint::Levels>,
    ) -> Project {
        let analysed = stc_pipeline::with_big_stack(move || {
            let (parsed, mark) = stc_pipeline::incremental::parse_all(files, &opts);
            stc_pipeline::analyse_parsed(parsed, mark.prelude(), &opts, lints.as_ref())
        });
        Project { analysed }
    }

    pub fn from_analysed(analysed: stc_pipeline::Analysed) -> Project {
        Project { analysed }
    }

    pub fn into_analysed(self) -> stc_pipeline::Analysed {
        self.analysed
    }

    pub(crate) fn analysed_mut(&mut self) -> &mut stc_pipeline::Analysed {
        &mut self.analysed
    }

    pub(crate) fn sources(&self) -> &SourceMap {
        &self.analysed.parsed.sources
    }

    /// Where the standard library prelude is (nothing in it is renamed).
    pub(crate) fn prelude(&self) -> Span {
        self.analysed.prelude
    }

    /// The file (URI) and LSP range of a span.
    pub(crate) fn range(&self, span: Span) -> Option<(String, Range)> {
        let sm = self.sources();
        let f = sm.file(sm.file_of(span.lo)?);
        Some((
            f.name.clone(),
            Range::new(lsp_position(f, span.lo), lsp_position(f, span.hi)),
        ))
    }

    /// The diagnostics of every file, as `stc check` gives them.
    pub fn diagnostics_by_uri(&self) -> BTreeMap<String, Vec<lsp_types::Diagnostic>> {
        let mut out: BTreeMap<String, Vec<lsp_types::Diagnostic>> = BTreeMap::new();
        for d in self.analysed.diagnostics() {
            let Some((uri, range)) = self.range(d.span) else {
                continue;
            };
            let mut message = d.message.clone();
            for n in &d.notes {
                message.push_str(&format!("\nnote: {n}"));
            }
            for h in &d.help {
                message.push_str(&format!("\nhelp: {h}"));
            }
            let related: Vec<lsp_types::DiagnosticRelatedInformation> = d
                .secondary
                .iter()
                .filter_map(|l| {
                    let (u, r) = self.range(l.span)?;
                    Some(lsp_types::DiagnosticRelatedInformation {
                        location: Location::new(u.parse().ok()?, r),
                        message: l.message.clone(),
                    })
                })
                .collect();
            out.entry(uri).or_default().push(lsp_types::Diagnostic {
                range,
                severity: Some(match d.severity {
                    Severity::Error => DiagnosticSeverity::ERROR,
                    Severity::Warning => DiagnosticSeverity::WARNING,
                }),
                code: Some(NumberOrString::String(d.code.as_str().into())),
                source: Some("stc".into()),
                message,
                related_information: (!related.is_empty()).then_some(related),
                ..lsp_types::Diagnostic::default()
            });
        }
        out
    }

    /// The position's absolute offset in the source map, and the file's text.
    pub(crate) fn locate(&self, uri: &str, pos: Position) -> Result<(u32, &str, u32), String> {
        let sm = self.sources();
        let f = sm
            .files()
            .map(|(_, f)| f)
            .find(|f| f.name == uri)
            .ok_or_else(|| format!("unknown document {uri}"))?;
        let off = position::offset(&f.text, pos)?;
        Ok((f.base + off as u32, &f.text, f.base))
    }

    pub(crate) fn items(&self) -> &[Item] {
        &self.analysed.parsed.ast.items
    }

    pub(crate) fn spelling(&self, s: Symbol) -> &str {
        self.analysed.parsed.interner.spelling(s)
    }

    pub(crate) fn sym(&self, name: &str) -> Option<Symbol> {
        self.analysed.parsed.interner.get(name)
    }

    /// The POU whose span contains `at`.
    pub(crate) fn pou_at(&self, at: u32) -> Option<&Pou> {
        self.items().iter().find_map(|it| match it {
            Item::Pou(p) if p.span.lo <= at && at <= p.span.hi => Some(p),
            _ => None,
        })
    }

    /// Every declaration visible at `at`: the enclosing POU's variables,
    /// then the global ones.
    fn visible(&self, at: u32) -> Vec<(Symbol, Span, Decl<'_>)> {
        let mut out = Vec::new();
        if let Some(p) = self.pou_at(at) {
            // Inside a METHOD: its own variables first, then the block's.
            for m in &p.methods {
                if m.pou.span.lo <= at && at <= m.pou.span.hi {
                    vars_of(&m.pou.var_blocks, &mut out);
                }
            }
            vars_of(&p.var_blocks, &mut out);
            // The state a chart's meaning declares (`SFC$$...`) is no
            // user's name.
            out.retain(|(s, _, _)| !self.spelling(*s).contains('$'));
            for m in &p.methods {
                out.push((m.pou.name.sym, m.pou.name.span, Decl::Pou(&m.pou)));
            }
        }
        for it in self.items() {
            match it {
                Item::Pou(p) => out.push((p.name.sym, p.name.span, Decl::Pou(p))),
                Item::Types(ts, _) => {
                    for t in ts {
                        out.push((t.name.sym, t.name.span, Decl::Type(t)));
                        if let TypeSpecKind::Enum { values, .. } = &t.spec.kind {
                            for v in values {
                                out.push((v.name.sym, v.name.span, Decl::EnumValue(t)));
                            }
                        }
                    }
                }
                Item::GlobalVars(b) => vars_of(std::slice::from_ref(b), &mut out),
                Item::Configuration(c) => {
                    vars_of(&c.var_blocks, &mut out);
                    for r in &c.resources {
                        vars_of(&r.var_blocks, &mut out);
                    }
                }
                // Their elements are listed by their own names (an
                // approximation: the language server does not scope them).
                Item::Namespace(_) | Item::EndNamespace(_) | Item::Using(_) => {}
            }
        }
        out
    }

    /// The members of the type of variable `base` visible at `at`.
    fn members(&self, base: &str, at: u32) -> Vec<(Symbol, Span, Decl<'_>)> {
        let Some(sym) = self.sym(base) else {
            return Vec::new();
        };
        let visible = self.visible(at);
        let Some(ty) = visible.iter().find_map(|(s, _, d)| match d {
            Decl::Var(v, ..) if *s == sym => match &v.ty.kind {
                TypeSpecKind::Named(n) => Some(n.sym),
                _ => None,
            },
            _ => None,
        }) else {
            return Vec::new();
        };
        let mut out = Vec::new();
        for it in self.items() {
            match it {
                Item::Pou(p) if p.name.sym == ty => {
                    let public: Vec<VarBlock> = p
                        .var_blocks
                        .iter()
                        .filter(|b| {
                            matches!(
                                b.kind,
                                VarKind::Input | VarKind::Output | VarKind::InOut | VarKind::Var
                            )
                        })
                        .cloned()
                        .collect();
                    let mut tmp = Vec::new();
                    vars_of(&public, &mut tmp);
                    tmp.retain(|(s, _, _)| !self.spelling(*s).contains('$'));
                    // Re-point to the POU's own blocks (borrowed from self).
                    for (s, sp, _) in tmp {
                        if let Some(d) = find_var(&p.var_blocks, s) {
                            out.push((s, sp, d));
                        }
                    }
                    for m in &p.methods {
                        out.push((m.pou.name.sym, m.pou.name.span, Decl::Pou(&m.pou)));
                    }
                }
                Item::Types(ts, _) => {
                    for t in ts.iter().filter(|t| t.name.sym == ty) {
                        if let TypeSpecKind::Struct { members } = &t.spec.kind {
                            for m in members {
                                for n in &m.names {
                                    out.push((n.sym, n.span, Decl::Var(m, VarKind::Var)));
                                }
                            }
                        }
                    }
                }
                _ => {}
            }
        }
        out
    }

    fn lookup(&self, uri: &str, pos: Position) -> Result<Option<(Span, Decl<'_>)>, String> {
        self.lookup_at(uri, pos)
    }

    pub fn definition(&self, uri: &str, pos: Position) -> Result<Option<Location>, String> {
        let Some((span, _)) = self.lookup(uri, pos)? else {
            return Ok(None);
        };
        Ok(self
            .range(span)
            .and_then(|(u, r)| Some(Location::new(u.parse().ok()?, r))))
    }

    pub fn hover(&self, uri: &str, pos: Position) -> Result<Option<Hover>, String> {
        let Some((_, decl)) = self.lookup(uri, pos)? else {
            return Ok(None);
        };
        let span = match decl {
            Decl::Var(v, ..) => v.span,
            Decl::Pou(p) => Span::new(p.span.lo, p.name.span.hi),
            Decl::Type(t) | Decl::EnumValue(t) => t.span,
        };
        let sm = self.sources();
        let text = sm.slice(span);
        let head = match decl {
            Decl::Pou(p) => {
                let mut h = text.to_string();
                if let Some(r) = &p.return_type {
                    h.push_str(&format!(" : {}", sm.slice(r.span)));
                }
                h
            }
            Decl::Var(_, kind) => format!("({}) {}", kind.keyword(), text.trim()),
            _ => text.trim().to_string(),
        };
        let doc = self.doc_comment(span);
        let mut value = format!("```iecst\n{head}\n```");
        if let Some(d) = doc {
            value.push_str(&format!("\n\n{d}"));
        }
        Ok(Some(Hover {
            contents: HoverContents::Markup(MarkupContent {
                kind: MarkupKind::Markdown,
                value,
            }),
            range: None,
        }))
    }

    /// The comment just above a declaration (only white space between), or
    /// after it on the same line.
    pub(crate) fn doc_comment(&self, span: Span) -> Option<String> {
        let sm = self.sources();
        let f = sm.file(sm.file_of(span.lo)?);
        let lexed = lex(&f.text, f.base);
        let comments = lexed
            .trivia
            .iter()
            .filter(|t| t.kind == TriviaKind::Comment);
        let mut best = None;
        for c in comments {
            let between = |lo: u32, hi: u32| {
                f.text
                    .get((lo - f.base) as usize..(hi - f.base) as usize)
                    .unwrap_or("x")
                    .to_string()
            };
            if c.span.hi <= span.lo {
                let gap = between(c.span.hi, span.lo);
                if gap.trim().is_empty() && gap.matches('\n').count() <= 1 {
                    best = Some(c.span);
                }
            } else if c.span.lo >= span.hi {
                let gap = between(span.hi, c.span.lo);
                if best.is_none()
                    && !gap.contains('\n')
                    && gap.trim().trim_start_matches(';').trim().is_empty()
                {
                    best = Some(c.span);
                }
                break;
            }
        }
        let text = sm.slice(best?);
        let inner = text
            .strip_prefix("(*")
            .and_then(|t| t.strip_suffix("*)"))
            .or_else(|| text.strip_prefix("/*").and_then(|t| t.strip_suffix("*/")))
            .or_else(|| text.strip_prefix("//"))
            .unwrap_or(text);
        Some(inner.trim().to_string())
    }

    pub fn completion(&self, uri: &str, pos: Position) -> Result<Vec<CompletionItem>, String> {
        let (at, text, base) = self.locate(uri, pos)?;
        // After `name.` (with or without the start of a member).
        let before = &text[..(at - base) as usize];
        let trimmed = before.trim_end_matches(|c: char| c.is_ascii_alphanumeric() || c == '_');
        if let Some(b) = trimmed.strip_suffix('.') {
            let start = b
                .rfind(|c: char| !(c.is_ascii_alphanumeric() || c == '_'))
                .map_or(0, |i| i + 1);
            let base_name = &b[start..];
            return Ok(self
                .members(base_name, at)
                .into_iter()
                .map(|(s, _, d)| self.item(s, d))
                .collect());
        }
        let mut items: Vec<CompletionItem> = Vec::new();
        let mut seen = std::collections::HashSet::new();
        for (s, _, d) in self.visible(at) {
            if seen.insert(s) {
                items.push(self.item(s, d));
            }
        }
        for (word, _) in Keyword::SPELLINGS {
            items.push(CompletionItem {
                label: word.to_string(),
                kind: Some(CompletionItemKind::KEYWORD),
                ..CompletionItem::default()
            });
        }
        for (word, _) in ElemType::SPELLINGS {
            items.push(CompletionItem {
                label: word.to_string(),
                kind: Some(CompletionItemKind::TYPE_PARAMETER),
                ..CompletionItem::default()
            });
        }
        Ok(items)
    }

    fn item(&self, s: Symbol, d: Decl<'_>) -> CompletionItem {
        let sm = self.sources();
        let (kind, detail) = match d {
            Decl::Var(v, k) => (
                if k == VarKind::Var {
                    CompletionItemKind::VARIABLE
                } else {
                    CompletionItemKind::FIELD
                },
                format!("{} : {}", k.keyword(), sm.slice(v.ty.span)),
            ),
            Decl::Pou(p) => (
                match p.kind {
                    PouKind::Function => CompletionItemKind::FUNCTION,
                    PouKind::FunctionBlock => CompletionItemKind::CLASS,
                    PouKind::Program => CompletionItemKind::MODULE,
                },
                p.kind.keyword().to_string(),
            ),
            Decl::Type(_) => (CompletionItemKind::STRUCT, "TYPE".into()),
            Decl::EnumValue(t) => (
                CompletionItemKind::ENUM_MEMBER,
                self.spelling(t.name.sym).to_string(),
            ),
        };
        CompletionItem {
            label: self.spelling(s).to_string(),
            kind: Some(kind),
            detail: Some(detail),
            ..CompletionItem::default()
        }
    }

    /// The outline of one document.
    #[allow(deprecated)]
    pub fn symbols(&self, uri: &str) -> Vec<DocumentSymbol> {
        let sm = self.sources();
        let Some(file) = sm.files().map(|(_, f)| f).find(|f| f.name == uri) else {
            return Vec::new();
        };
        let in_file = |s: Span| s.lo >= file.base && s.lo <= file.base + file.text.len() as u32;
        let sym = |name: String,
                   kind: SymbolKind,
                   span: Span,
                   sel: Span,
                   children: Vec<DocumentSymbol>| {
            let r = self.range(span).map(|(_, r)| r).unwrap_or_default();
            let s = self.range(sel).map(|(_, r)| r).unwrap_or(r);
            DocumentSymbol {
                name,
                detail: None,
                kind,
                tags: None,
                deprecated: None,
                range: r,
                selection_range: s,
                children: (!children.is_empty()).then_some(children),
            }
        };
        let vars = |blocks: &[VarBlock]| {
            let mut out = Vec::new();
            let mut tmp = Vec::new();
            vars_of(blocks, &mut tmp);
            tmp.retain(|(s, _, _)| !self.spelling(*s).contains('$'));
            for (s, sp, d) in tmp {
                let span = match d {
                    Decl::Var(v, ..) => v.span,
                    _ => sp,
                };
                out.push(sym(
                    self.spelling(s).into(),
                    SymbolKind::VARIABLE,
                    span,
                    sp,
                    Vec::new(),
                ));
            }
            out
        };
        let mut out = Vec::new();
        for it in self.items() {
            match it {
                Item::Pou(p) if in_file(p.span) => {
                    let kind = match p.kind {
                        PouKind::Function => SymbolKind::FUNCTION,
                        PouKind::FunctionBlock => SymbolKind::CLASS,
                        PouKind::Program => SymbolKind::MODULE,
                    };
                    out.push(sym(
                        self.spelling(p.name.sym).into(),
                        kind,
                        p.span,
                        p.name.span,
                        vars(&p.var_blocks),
                    ));
                }
                Item::Types(ts, _) => {
                    for t in ts.iter().filter(|t| in_file(t.span)) {
                        let kind = match t.spec.kind {
                            TypeSpecKind::Struct { .. } => SymbolKind::STRUCT,
                            TypeSpecKind::Enum { .. } => SymbolKind::ENUM,
                            _ => SymbolKind::TYPE_PARAMETER,
                        };
                        out.push(sym(
                            self.spelling(t.name.sym).into(),
                            kind,
                            t.span,
                            t.name.span,
                            Vec::new(),
                        ));
                    }
                }
                Item::GlobalVars(b) if in_file(b.span) => out.extend(vars(std::slice::from_ref(b))),
                Item::Configuration(c) if in_file(c.span) => {
                    out.push(sym(
                        self.spelling(c.name.sym).into(),
                        SymbolKind::NAMESPACE,
                        c.span,
                        c.name.span,
                        vars(&c.var_blocks),
                    ));
                }
                _ => {}
            }
        }
        out
    }
}

/// The LSP position (line, UTF-16 units) of an absolute position in a
/// file, through the file's line table (no scan from the file's start).
pub(crate) fn lsp_position(f: &stc_diagnostics::SourceFile, pos: u32) -> Position {
    let off = (pos.saturating_sub(f.base) as usize).min(f.text.len());
    let starts = f.line_starts();
    let line = starts
        .partition_point(|&s| s as usize <= off)
        .saturating_sub(1);
    let start = starts.get(line).map_or(0, |&s| s as usize).min(off);
    let mut end = off;
    while !f.text.is_char_boundary(end) {
        end -= 1;
    }
    let character = f
        .text
        .get(start..end)
        .unwrap_or("")
        .chars()
        .map(|c| c.len_utf16() as u32)
        .sum();
    Position::new(line as u32, character)
}

pub(crate) fn vars_of<'a>(blocks: &'a [VarBlock], out: &mut Vec<(Symbol, Span, Decl<'a>)>) {
    for b in blocks {
        if let VarBlockItems::Vars(vs) = &b.items {
            for v in vs {
                for n in &v.names {
                    out.push((n.sym, n.span, Decl::Var(v, b.kind)));
                }
            }
        }
    }
}

fn find_var(blocks: &[VarBlock], s: Symbol) -> Option<Decl<'_>> {
    let mut all = Vec::new();
    vars_of(blocks, &mut all);
    all.into_iter().find(|(x, _, _)| *x == s).map(|(_, _, d)| d)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn methods_complete_as_members_and_their_variables_inside_them() {
        let text = "FUNCTION_BLOCK Pump\nVAR speed : INT; END_VAR\nMETHOD Start\nVAR_INPUT rate : INT; END_VAR\n    speed := rate;\nEND_METHOD\nEND_FUNCTION_BLOCK\nPROGRAM Main\nVAR p : Pump; END_VAR\n    p.\nEND_PROGRAM\n";
        let uri = "file:///m.st".to_string();
        let project = Project::analyse(vec![(uri.clone(), text.into())], Default::default());
        let labels = |line: u32, character: u32| -> Vec<String> {
            project
                .completion(&uri, Position::new(line, character))
                .expect("completion")
                .into_iter()
                .map(|c| c.label)
                .collect()
        };
        let inside = labels(4, 4);
        assert!(inside.iter().any(|l| l == "rate"), "{inside:?}");
        assert!(inside.iter().any(|l| l == "speed"), "{inside:?}");
        let members = labels(9, 6);
        assert!(members.iter().any(|l| l == "Start"), "{members:?}");
    }
}
