//! Reading source files: directories expand to every `.st`/`.il` file below
//! them (sorted by path), and a file that is not UTF-8 is decoded as
//! Windows-1252 with a warning (spec/semantics.md, Lexical).

use std::path::{Path, PathBuf};

use stc_diagnostics::{Code, Diagnostic, SourceMap, Span};

/// A problem that stops before any source is analysed (exit status 2).
#[derive(Debug)]
pub struct LoadError(pub String);

impl std::fmt::Display for LoadError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.0)
    }
}

fn is_source(p: &Path) -> bool {
    matches!(
        p.extension()
            .and_then(|e| e.to_str())
            .map(|e| e.to_ascii_lowercase())
            .as_deref(),
        Some("st" | "il")
    )
}

fn collect(dir: &Path, out: &mut Vec<PathBuf>) -> Result<(), LoadError> {
    let entries = std::fs::read_dir(dir)
        .map_err(|e| LoadError(format!("cannot read directory {}: {e}", dir.display())))?;
    for entry in entries {
        let path = entry
            .map_err(|e| LoadError(format!("cannot read directory {}: {e}", dir.display())))?
            .path();
        if path.is_dir() {
            collect(&path, out)?;
        } else if is_source(&path) {
            out.push(path);
        }
    }
    Ok(())
}

/// The files named by the command line, directories expanded.
pub fn expand(paths: &[PathBuf]) -> Result<Vec<PathBuf>, LoadError> {
    let mut files = Vec::new();
    for p in paths {
        if p.is_dir() {
            let mut found = Vec::new();
            collect(p, &mut found)?;
            found.sort();
            files.extend(found);
        } else {
            files.push(p.clone());
        }
    }
    if files.is_empty() {
        return Err(LoadError("no source files given".into()));
    }
    Ok(files)
}

/// Decodes file contents: UTF-8, or Windows-1252 with the byte offset of the
/// first byte that is not UTF-8.
pub fn decode(bytes: Vec<u8>) -> (String, Option<usize>) {
    match String::from_utf8(bytes) {
        Ok(s) => (s, None),
        Err(e) => {
            let bad = e.utf8_error().valid_up_to();
            let bytes = e.into_bytes();
            let (text, _) = encoding_rs::WINDOWS_1252.decode_without_bom_handling(&bytes);
            // Windows-1252 decodes every byte to one character, so the first
            // bad byte is character number `bad` of the decoded text.
            let offset = text.char_indices().nth(bad).map_or(text.len(), |(i, _)| i);
            (text.into_owned(), Some(offset))
        }
    }
}

/// Loads files into a source map; the W0001 warnings for non-UTF-8 files come
/// back with it.
pub fn load(paths: &[PathBuf]) -> Result<(SourceMap, Vec<Diagnostic>), LoadError> {
    let mut sm = SourceMap::new();
    let mut diags = Vec::new();
    for path in expand(paths)? {
        let bytes = std::fs::read(&path)
            .map_err(|e| LoadError(format!("cannot read {}: {e}", path.display())))?;
        let (text, bad) = decode(bytes);
        let name = path.display().to_string();
        let id = sm
            .add(name.clone(), text)
            .ok_or_else(|| LoadError(format!("{name}: the project is larger than 4 GiB")))?;
        if let Some(offset) = bad {
            let pos = sm.file(id).base + offset as u32;
            diags.push(Diagnostic::new(
                Code::W0001,
                Span::new(pos, pos),
                "this file is not valid UTF-8; it was read as Windows-1252",
            ));
        }
    }
    Ok((sm, diags))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn windows_1252_is_decoded_and_the_first_bad_byte_located() {
        let (text, bad) = decode(b"x := 'Gr\xFC\xDFe';".to_vec());
        assert_eq!(text, "x := 'Grüße';");
        assert_eq!(bad, Some("x := 'Gr".len()));
        let (text, bad) = decode("ok é".as_bytes().to_vec());
        assert_eq!((text.as_str(), bad), ("ok é", None));
    }
}
