//! `stc lsp`: a language server for Structured Text over the Language
//! Server Protocol (lsp-server for the transport, lsp-types for the
//! messages).
//!
//! The server keeps the text of every document the editor opened plus the
//! project's other files (given by the caller, which does the file I/O) and,
//! after every change, analyses the whole project through `stc_pipeline`
//! (the same phases as `stc check`, so the same codes and spans) and
//! publishes the diagnostics of every file. Requests are answered from the
//! last analysis's syntax tree: document symbols, go to definition, hover
//! (the declaration and the comment above it), completion (names in scope,
//! members after `.`, keywords) and formatting through `stc_fmt`.
//!
//! Robustness: the parser accepts any text, the phases run on a big stack,
//! and a position outside a document is answered with an `InvalidParams`
//! error, never a panic.
//!
//! **Invariant:** no file I/O: the caller gives the connection and the
//! workspace's files.

mod analysis;
mod position;

use std::collections::BTreeMap;
use std::error::Error;

use lsp_server::{Connection, ErrorCode, Message, Notification, Request, RequestId, Response};
use lsp_types::notification::{
    DidChangeTextDocument, DidCloseTextDocument, DidOpenTextDocument, Notification as _,
    PublishDiagnostics,
};
use lsp_types::request::{
    Completion, DocumentSymbolRequest, Formatting, GotoDefinition, HoverRequest, Request as _,
};
use lsp_types::{
    CompletionOptions, HoverProviderCapability, InitializeParams, OneOf, ServerCapabilities,
    TextDocumentSyncCapability, TextDocumentSyncKind,
};

pub use analysis::Project;

/// The capabilities the server announces.
pub fn capabilities() -> ServerCapabilities {
    ServerCapabilities {
        text_document_sync: Some(TextDocumentSyncCapability::Kind(TextDocumentSyncKind::FULL)),
        definition_provider: Some(OneOf::Left(true)),
        hover_provider: Some(HoverProviderCapability::Simple(true)),
        document_symbol_provider: Some(OneOf::Left(true)),
        document_formatting_provider: Some(OneOf::Left(true)),
        completion_provider: Some(CompletionOptions {
            trigger_characters: Some(vec![".".into()]),
            ..CompletionOptions::default()
        }),
        ..ServerCapabilities::default()
    }
}

/// Serves one editor session on `conn`. `workspace` is called once with
/// the initialize parameters and returns the project's files (URI, text)
/// that are not open in the editor. Returns after `shutdown` and `exit`.
pub fn serve(
    conn: &Connection,
    workspace: &dyn Fn(&InitializeParams) -> Vec<(String, String)>,
    opts: stc_pipeline::Options,
) -> Result<(), Box<dyn Error + Send + Sync>> {
    let (id, params) = conn.initialize_start()?;
    let init: InitializeParams = serde_json::from_value(params).unwrap_or_default();
    let result = serde_json::json!({
        "capabilities": capabilities(),
        "serverInfo": { "name": "stc", "version": env!("CARGO_PKG_VERSION") },
    });
    conn.initialize_finish(id, result)?;
    let mut server = Server {
        files: workspace(&init).into_iter().collect(),
        project: None,
        opts,
        published: Vec::new(),
    };
    for msg in &conn.receiver {
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

struct Server {
    /// Every file of the project by URI: open documents (the editor's text)
    /// and the workspace's other files.
    files: BTreeMap<String, String>,
    project: Option<Project>,
    opts: stc_pipeline::Options,
    /// URIs that had diagnostics in the last publication (to clear them).
    published: Vec<String>,
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
                    self.files.insert(
                        p.text_document.uri.as_str().to_string(),
                        p.text_document.text,
                    );
                    return true;
                }
            }
            DidChangeTextDocument::METHOD => {
                if let Ok(p) =
                    serde_json::from_value::<lsp_types::DidChangeTextDocumentParams>(n.params)
                {
                    // Full synchronisation: the last change is the whole text.
                    if let Some(c) = p.content_changes.into_iter().last() {
                        self.files
                            .insert(p.text_document.uri.as_str().to_string(), c.text);
                        return true;
                    }
                }
            }
            DidCloseTextDocument::METHOD => {}
            _ => {}
        }
        false
    }

    fn analyse_and_publish(&mut self) -> Vec<Notification> {
        let files: Vec<(String, String)> = self
            .files
            .iter()
            .map(|(u, t)| (u.clone(), t.clone()))
            .collect();
        let project = Project::analyse(files, self.opts);
        let by_file = project.diagnostics_by_uri();
        let mut out = Vec::new();
        let mut published = Vec::new();
        let mut seen = std::collections::BTreeSet::new();
        // Every file, and the ones that had diagnostics before (to clear
        // them), once each.
        for uri in self.files.keys().chain(self.published.iter()) {
            if !seen.insert(uri) {
                continue;
            }
            let Ok(u) = uri.parse::<lsp_types::Uri>() else {
                continue;
            };
            let diagnostics = by_file.get(uri).cloned().unwrap_or_default();
            if !diagnostics.is_empty() {
                published.push(uri.clone());
            }
            let p = lsp_types::PublishDiagnosticsParams {
                uri: u,
                diagnostics,
                version: None,
            };
            out.push(Notification::new(PublishDiagnostics::METHOD.into(), p));
        }
        self.published = published;
        self.project = Some(project);
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
        let project = self.project.as_ref();
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
            Formatting::METHOD => {
                let p: lsp_types::DocumentFormattingParams = params(req.params)?;
                let uri = p.text_document.uri.as_str();
                let Some(text) = self.files.get(uri) else {
                    return Err(invalid(format!("unknown document {uri}")));
                };
                let text = text.clone();
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
