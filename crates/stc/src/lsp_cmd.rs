//! `stc lsp`: the language server ([`stc_lsp`]) on stdin/stdout. This side
//! does the I/O: the stdio transport and reading the workspace's files
//! (the sources of its stc.toml, else every `.st` file below its root).

use std::path::{Path, PathBuf};

use crate::manifest;

/// The `file://` URI of a path (absolute, `/` separated, spaces and other
/// reserved bytes percent-encoded, as editors write them).
pub fn file_uri(path: &Path) -> String {
    let abs = std::fs::canonicalize(path).unwrap_or_else(|_| path.to_path_buf());
    let mut out = String::from("file://");
    for b in abs.to_string_lossy().replace('\\', "/").bytes() {
        match b {
            b'A'..=b'Z' | b'a'..=b'z' | b'0'..=b'9' | b'-' | b'.' | b'_' | b'~' | b'/' => {
                out.push(b as char)
            }
            _ => out.push_str(&format!("%{b:02X}")),
        }
    }
    out
}

fn path_of(uri: &str) -> Option<PathBuf> {
    let rest = uri.strip_prefix("file://")?;
    let mut bytes = Vec::new();
    let b = rest.as_bytes();
    let mut i = 0;
    while i < b.len() {
        if b[i] == b'%' && i + 2 < b.len() {
            let hex = std::str::from_utf8(&b[i + 1..i + 3]).ok()?;
            bytes.push(u8::from_str_radix(hex, 16).ok()?);
            i += 3;
        } else {
            bytes.push(b[i]);
            i += 1;
        }
    }
    Some(PathBuf::from(String::from_utf8(bytes).ok()?))
}

/// The files of the workspace the editor opened, and the lint levels of
/// its manifest.
#[allow(deprecated)]
fn workspace(init: &lsp_types::InitializeParams) -> stc_lsp::Found {
    let root = init
        .workspace_folders
        .as_ref()
        .and_then(|f| f.first())
        .map(|f| f.uri.as_str().to_string())
        .or_else(|| init.root_uri.as_ref().map(|u| u.as_str().to_string()))
        .and_then(|u| path_of(&u));
    let Some(root) = root else {
        return stc_lsp::Found::default();
    };
    let manifest = manifest::find(&root).map(|m| manifest::load(&m));
    let lints = match &manifest {
        Some(Ok(m)) => m.lints,
        _ => stc_lint::Levels::default(),
    };
    let files = match &manifest {
        Some(Ok(m)) => m.files(true).unwrap_or_default(),
        _ => crate::sources::expand(&[root]).unwrap_or_default(),
    };
    let files = files
        .into_iter()
        .filter_map(|p| {
            let bytes = std::fs::read(&p).ok()?;
            Some((file_uri(&p), crate::sources::decode(bytes).0))
        })
        .collect();
    stc_lsp::Found { files, lints }
}

/// Serves on stdin/stdout until the editor shuts the server down.
pub fn run(opts: stc_pipeline::Options) -> u8 {
    let (conn, io) = lsp_server::Connection::stdio();
    let result = stc_lsp::serve(&conn, &workspace, opts);
    drop(conn);
    let joined = io.join();
    match (result, joined) {
        (Ok(()), Ok(())) => 0,
        (Err(e), _) => {
            eprintln!("stc lsp: {e}");
            1
        }
        (_, Err(e)) => {
            eprintln!("stc lsp: {e}");
            1
        }
    }
}
