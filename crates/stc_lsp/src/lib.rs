//! `stc lsp`: a language server for Structured Text over the Language
//! Server Protocol (lsp-server for the transport, lsp-types for the
//! messages).
//!
//! The server keeps the text of every document the editor opened plus the
//! project's other files (given by the caller, which does the file I/O) and,
//! after every change, analyses the project through `stc_pipeline` (the
//! same phases as `stc check`, so the same codes and spans, with the lints
//! at the project's levels) and publishes the diagnostics of the files
//! that changed. The analysis is incremental where it can be exact
//! (`workspace`): an edit re-parses only the edited file and the prelude.
//! Requests are answered from the last analysis's syntax tree and the
//! document's tokens (`navigate`): document symbols, go to definition,
//! find references, rename, hover (the declaration and the comment above
//! it), completion (names in scope, members after `.`, keywords), signature
//! help, semantic tokens, and formatting through `stc_fmt`.
//!
//! Robustness: the parser accepts any text, the phases run on a big stack,
//! and a position outside a document is answered with an `InvalidParams`
//! error, never a panic.
//!
//! **Invariant:** no file I/O: the caller gives the connection and the
//! workspace's files.

mod analysis;
mod navigate;
mod position;
mod workspace;

use std::collections::{BTreeMap, BTreeSet};
use std::error::Error;

use lsp_server::{Connection, ErrorCode, Message, Notification, Request, RequestId, Response};
use lsp_types::notification::{
    DidChangeTextDocument, DidCloseTextDocument, DidOpenTextDocument, Notification as _,
    PublishDiagnostics,
};
use lsp_types::request::{
    Completion, DocumentSymbolRequest, Formatting, GotoDefinition, HoverRequest,
    PrepareRenameRequest, References, Rename, Request as _, SemanticTokensFullRequest,
    SignatureHelpRequest,
};
use lsp_types::{
    CompletionOptions, HoverProviderCapability, InitializeParams, OneOf, RenameOptions,
    SemanticTokens, SemanticTokensFullOptions, SemanticTokensOptions,
    SemanticTokensServerCapabilities, ServerCapabilities, SignatureHelpOptions,
    TextDocumentSyncCapability, TextDocumentSyncKind, WorkDoneProgressOptions,
};

pub use analysis::Project;

pub use workspace::Workspace;

/// The capabilities the server announces.
pub fn capabilities() -> ServerCapabilities {
    ServerCapabilities {
        text_document_sync: Some(TextDocumentSyncCapability::Kind(TextDocumentSyncKind::FULL)),
        definition_provider: Some(OneOf::Left(true)),
        references_provider: Some(OneOf::Left(true)),
        rename_provider: Some(OneOf::Right(RenameOptions {
            prepare_provider: Some(true),
            work_done_progress_options: WorkDoneProgressOptions::default(),
        })),
        hover_provider: Some(HoverProviderCapability::Simple(true)),
        document_symbol_provider: Some(OneOf::Left(true)),
        document_formatting_provider: Some(OneOf::Left(true)),
        completion_provider: Some(CompletionOptions {
            trigger_characters: Some(vec![".".into()]),
            ..CompletionOptions::default()
        }),
        signature_help_provider: Some(SignatureHelpOptions {
            trigger_characters: Some(vec!["(".into(), ",".into()]),
            retrigger_characters: None,
            work_done_progress_options: WorkDoneProgressOptions::default(),
        }),
        semantic_tokens_provider: Some(SemanticTokensServerCapabilities::SemanticTokensOptions(
            SemanticTokensOptions {
                legend: navigate::legend(),
                full: Some(SemanticTokensFullOptions::Bool(true)),
                range: None,
                work_done_progress_options: WorkDoneProgressOptions::default(),
            },
        )),
        ..ServerCapabilities::default()
    }
}

/// The project the caller found for the editor's workspace.
#[derive(Default)]
pub struct Found {
    /// Its files (URI, text) that are not open in the editor.
    pub files: Vec<(String, String)>,
    /// The lints' levels of its manifest (each lint's default without one).
    pub lints: stc_lint::Levels,
}

/// Serves one editor session on `conn`. `workspace` is called once with
/// the initialize parameters and returns the project's files and lint
/// levels. Returns after `shutdown` and `exit`.
pub fn serve(
    conn: &Connection,
    workspace: &dyn Fn(&InitializeParams) -> Found,
    opts: stc_pipeline::Options,
) -> Result<(), Box<dyn Error + Send + Sync>> {
    let (id, params) = conn.initialize_start()?;
    let init: InitializeParams = serde_json::from_value(params).unwrap_or_default();
    let result = serde_json::json!({
        "capabilities": capabilities(),
        "serverInfo": { "name": "stc", "version": env!("CARGO_PKG_VERSION") },
    });
    conn.initialize_finish(id, result)?;
    let found = workspace(&init);
    let mut server = Server {
        workspace: Workspace::new(found.files, opts, Some(found.lints)),
        opts,
        touched: BTreeSet::new(),
        published: BTreeMap::new(),
        analysed_once: false,
    };
    loop {
        // The rest of the last analysis (lowering, the memory layout's
        // E0901, freeing what is out of date) waits for a quiet moment: an
        // edit that comes while the user types is analysed first.
        let msg = if server.workspace.has_work() {
            match conn.receiver.recv_timeout(QUIET) {
                Ok(m) => m,
                Err(e) if e.is_timeout() => {
                    for m in server.finish_and_publish() {
                        conn.sender.send(Message::Notification(m))?;
                    }
                    continue;
                }
                Err(_) => break,
            }
        } else {
            match conn.receiver.recv() {
                Ok(m) => m,
                Err(_) => break,
            }
        };
        match msg {
            Message::Request(req) => {
                if conn.handle_shutdown(&req)? {
                    return Ok(());
                }
                let resp = server.request(req);
                conn.sender.send(Message::Response(resp))?;
            }
            Message::Notification(n) => {
                if server.notification(n) {
                    for m in server.analyse_and_publish() {
                        conn.sender.send(Message::Notification(m))?;
                    }
                }
            }
            Message::Response(_) => {}
        }
    }
    Ok(())
}

/// How long the server waits without a message before it finishes the
/// last analysis (about the pause between two keystrokes).
const QUIET: std::time::Duration = std::time::Duration::from_millis(150);

struct Server {
    /// Every file of the project: open documents (the editor's text) and
    /// the workspace's other files, with the last analysis.
    workspace: Workspace,
    opts: stc_pipeline::Options,
    /// Documents the editor changed (or opened) since the last publication:
    /// their diagnostics are published even when they did not change.
    touched: BTreeSet<String>,
    /// The diagnostics last published for each file that had some.
    published: BTreeMap<String, Vec<lsp_types::Diagnostic>>,
    /// Whether every file's diagnostics were published once.
    analysed_once: bool,
}

fn params<T: serde::de::DeserializeOwned>(v: serde_json::Value) -> Result<T, Response> {
    serde_json::from_value(v).map_err(|e| {
        Response::new_err(
            RequestId::from(0),
            ErrorCode::InvalidParams as i32,
            format!("bad parameters: {e}"),
        )
    })
}

impl Server {
    /// Applies a notification; whether the project changed.
    fn notification(&mut self, n: Notification) -> bool {
        match n.method.as_str() {
            DidOpenTextDocument::METHOD => {
                if let Ok(p) =
                    serde_json::from_value::<lsp_types::DidOpenTextDocumentParams>(n.params)
                {
                    let uri = p.text_document.uri.as_str().to_string();
                    self.touched.insert(uri.clone());
                    self.workspace.set(uri, p.text_document.text);
                    return true;
                }
            }
            DidChangeTextDocument::METHOD => {
                if let Ok(p) =
                    serde_json::from_value::<lsp_types::DidChangeTextDocumentParams>(n.params)
                {
                    // Full synchronisation: the last change is the whole text.
                    if let Some(c) = p.content_changes.into_iter().last() {
                        let uri = p.text_document.uri.as_str().to_string();
                        self.touched.insert(uri.clone());
                        self.workspace.set(uri, c.text);
                        return true;
                    }
                }
            }
            DidCloseTextDocument::METHOD => {}
            _ => {}
        }
        false
    }

    /// Analyses the project and publishes the diagnostics of the files the
    /// editor touched and of every file whose diagnostics changed (all of
    /// them the first time).
    fn analyse_and_publish(&mut self) -> Vec<Notification> {
        self.workspace.analyse();
        self.publish()
    }

    /// Finishes the last analysis; publishes what that changed.
    fn finish_and_publish(&mut self) -> Vec<Notification> {
        if self.workspace.finish() {
            self.publish()
        } else {
            Vec::new()
        }
    }

    fn publish(&mut self) -> Vec<Notification> {
        let Some(project) = self.workspace.project() else {
            return Vec::new();
        };
        let by_file = project.diagnostics_by_uri();
        let mut out = Vec::new();
        let touched = std::mem::take(&mut self.touched);
        let all = !self.analysed_once;
        self.analysed_once = true;
        let uris: BTreeSet<&String> = self.workspace.uris().chain(self.published.keys()).collect();
        let mut published = BTreeMap::new();
        for uri in uris {
            let diagnostics = by_file.get(uri).cloned().unwrap_or_default();
            let before = self.published.get(uri);
            let changed = before.map_or(!diagnostics.is_empty(), |b| *b != diagnostics);
            if !diagnostics.is_empty() {
                published.insert(uri.clone(), diagnostics.clone());
            }
            if !(all || changed || touched.contains(uri)) {
                continue;
            }
            let Ok(u) = uri.parse::<lsp_types::Uri>() else {
                continue;
            };
            let p = lsp_types::PublishDiagnosticsParams {
                uri: u,
                diagnostics,
                version: None,
            };
            out.push(Notification::new(PublishDiagnostics::METHOD.into(), p));
        }
        self.published = published;
        out
    }

    fn request(&mut self, req: Request) -> Response {
        let id = req.id.clone();
        let result = self.dispatch(req);
        match result {
            Ok(v) => Response::new_ok(id, v),
            Err(mut e) => {
                e.id = id;
                e
            }
        }
    }

    fn dispatch(&mut self, req: Request) -> Result<serde_json::Value, Response> {
        let project = self.workspace.project();
        let none = || Ok(serde_json::Value::Null);
        match req.method.as_str() {
            GotoDefinition::METHOD => {
                let p: lsp_types::GotoDefinitionParams = params(req.params)?;
                let tp = p.text_document_position_params;
                let Some(project) = project else {
                    return none();
                };
                let loc = project
                    .definition(tp.text_document.uri.as_str(), tp.position)
                    .map_err(invalid)?;
                Ok(serde_json::to_value(loc).unwrap_or_default())
            }
            HoverRequest::METHOD => {
                let p: lsp_types::HoverParams = params(req.params)?;
                let tp = p.text_document_position_params;
                let Some(project) = project else {
                    return none();
                };
                let h = project
                    .hover(tp.text_document.uri.as_str(), tp.position)
                    .map_err(invalid)?;
                Ok(serde_json::to_value(h).unwrap_or_default())
            }
            Completion::METHOD => {
                let p: lsp_types::CompletionParams = params(req.params)?;
                let tp = p.text_document_position;
                let Some(project) = project else {
                    return none();
                };
                let items = project
                    .completion(tp.text_document.uri.as_str(), tp.position)
                    .map_err(invalid)?;
                Ok(serde_json::to_value(items).unwrap_or_default())
            }
            DocumentSymbolRequest::METHOD => {
                let p: lsp_types::DocumentSymbolParams = params(req.params)?;
                let Some(project) = project else {
                    return none();
                };
                let s = project.symbols(p.text_document.uri.as_str());
                Ok(serde_json::to_value(s).unwrap_or_default())
            }
            References::METHOD => {
                let p: lsp_types::ReferenceParams = params(req.params)?;
                let tp = p.text_document_position;
                let Some(project) = project else {
                    return none();
                };
                let locs = project
                    .references(
                        tp.text_document.uri.as_str(),
                        tp.position,
                        p.context.include_declaration,
                    )
                    .map_err(invalid)?;
                Ok(serde_json::to_value(locs).unwrap_or_default())
            }
            PrepareRenameRequest::METHOD => {
                let p: lsp_types::TextDocumentPositionParams = params(req.params)?;
                let Some(project) = project else {
                    return none();
                };
                let r = project
                    .prepare_rename(p.text_document.uri.as_str(), p.position)
                    .map_err(rename_error)?;
                Ok(serde_json::to_value(r).unwrap_or_default())
            }
            Rename::METHOD => {
                let p: lsp_types::RenameParams = params(req.params)?;
                let tp = p.text_document_position;
                let Some(project) = project else {
                    return none();
                };
                let edit = project
                    .rename(tp.text_document.uri.as_str(), tp.position, &p.new_name)
                    .map_err(rename_error)?;
                Ok(serde_json::to_value(edit).unwrap_or_default())
            }
            SemanticTokensFullRequest::METHOD => {
                let p: lsp_types::SemanticTokensParams = params(req.params)?;
                let Some(project) = project else {
                    return none();
                };
                let data = project
                    .semantic_tokens(p.text_document.uri.as_str())
                    .map_err(invalid)?;
                Ok(serde_json::to_value(SemanticTokens {
                    result_id: None,
                    data,
                })
                .unwrap_or_default())
            }
            SignatureHelpRequest::METHOD => {
                let p: lsp_types::SignatureHelpParams = params(req.params)?;
                let tp = p.text_document_position_params;
                let Some(project) = project else {
                    return none();
                };
                let h = project
                    .signature_help(tp.text_document.uri.as_str(), tp.position)
                    .map_err(invalid)?;
                Ok(serde_json::to_value(h).unwrap_or_default())
            }
            Formatting::METHOD => {
                let p: lsp_types::DocumentFormattingParams = params(req.params)?;
                let uri = p.text_document.uri.as_str();
                let Some(text) = self.workspace.text(uri) else {
                    return Err(invalid(format!("unknown document {uri}")));
                };
                let text = text.to_string();
                let fmt = stc_fmt::Options {
                    indent_width: p.options.tab_size.clamp(1, 16) as usize,
                    iec2: self.opts.iec2,
                    ..stc_fmt::Options::default()
                };
                let out = stc_pipeline::with_big_stack(move || {
                    stc_fmt::format(&text, 0, &fmt).map(|out| (out, text))
                });
                match out {
                    Ok((out, text)) if out == text => Ok(serde_json::json!([])),
                    Ok((out, text)) => {
                        let end = position::end_of(&text);
                        let edit = lsp_types::TextEdit {
                            range: lsp_types::Range::new(lsp_types::Position::new(0, 0), end),
                            new_text: out,
                        };
                        Ok(serde_json::to_value(vec![edit]).unwrap_or_default())
                    }
                    Err(e) => Err(Response::new_err(
                        RequestId::from(0),
                        ErrorCode::RequestFailed as i32,
                        format!("not formatted: {e}"),
                    )),
                }
            }
            _ => Err(Response::new_err(
                RequestId::from(0),
                ErrorCode::MethodNotFound as i32,
                format!("unknown method {}", req.method),
            )),
        }
    }
}

fn invalid(msg: impl std::fmt::Display) -> Response {
    Response::new_err(
        RequestId::from(0),
        ErrorCode::InvalidParams as i32,
        msg.to_string(),
    )
}

fn rename_error(e: navigate::RenameError) -> Response {
    match e {
        navigate::RenameError::Invalid(m) => invalid(m),
        navigate::RenameError::Refused(m) => {
            Response::new_err(RequestId::from(0), ErrorCode::RequestFailed as i32, m)
        }
    }
}
