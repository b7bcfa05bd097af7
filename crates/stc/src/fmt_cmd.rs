//! `stc fmt [--check] FILE...`: formats source files in place with
//! [`stc_fmt`], or (`--check`) lists the files that would change.
//!
//! A file the formatter refuses (syntax errors, or a layout it could not
//! prove safe) is left alone with an error, and the run exits 1. A file that
//! is not UTF-8 is left alone too: writing it back would change its encoding.

use std::path::{Path, PathBuf};

use stc_diagnostics::SourceMap;

use crate::cli::{Outcome, EXIT_ERRORS, EXIT_OK, EXIT_USAGE};
use crate::driver::{self, Options};
use crate::sources;

pub struct FmtArgs {
    pub files: Vec<PathBuf>,
    pub check: bool,
    pub format: stc_fmt::Options,
    pub diagnostics: Options,
}

/// Formats (or checks) every file; the outcome's stdout lists the files
/// that would change under `--check`.
pub fn run(args: &FmtArgs) -> Outcome {
    let files = match sources::expand(&args.files) {
        Ok(f) => f,
        Err(e) => {
            return Outcome {
                stderr: format!("error: {e}\n"),
                status: EXIT_USAGE,
                ..Outcome::default()
            }
        }
    };
    let mut o = Outcome::default();
    let mut failed = false;
    for path in &files {
        match format_file(path, args) {
            Ok(Change::Same) => {}
            Ok(Change::Changed(text)) => {
                if args.check {
                    o.stdout.push_str(&format!("{}\n", path.display()));
                    failed = true;
                } else if let Err(e) = write_atomically(path, &text) {
                    o.stderr
                        .push_str(&format!("error: cannot write {}: {e}\n", path.display()));
                    o.status = EXIT_USAGE;
                }
            }
            Err(FileError::Io(e)) => {
                o.stderr.push_str(&format!("error: {e}\n"));
                o.status = EXIT_USAGE;
            }
            Err(FileError::Refused(text)) => {
                o.stderr.push_str(&text);
                failed = true;
            }
        }
    }
    if o.status == EXIT_OK && failed {
        o.status = EXIT_ERRORS;
    }
    o
}

enum Change {
    Same,
    Changed(String),
}

enum FileError {
    Io(String),
    /// Left alone; the rendered reason.
    Refused(String),
}

fn format_file(path: &Path, args: &FmtArgs) -> Result<Change, FileError> {
    let name = path.display().to_string();
    let bytes =
        std::fs::read(path).map_err(|e| FileError::Io(format!("cannot read {name}: {e}")))?;
    let text = String::from_utf8(bytes).map_err(|_| {
        FileError::Refused(format!(
            "error: {name}: not valid UTF-8; left alone (writing it back would change its encoding)\n"
        ))
    })?;
    let mut sm = SourceMap::new();
    let Some(id) = sm.add(name.clone(), text) else {
        return Err(FileError::Io(format!("{name}: file larger than 4 GiB")));
    };
    let file = sm.file(id);
    match stc_fmt::format(&file.text, file.base, &args.format) {
        Ok(out) if out == file.text => Ok(Change::Same),
        Ok(out) => Ok(Change::Changed(out)),
        Err(stc_fmt::FormatError::Syntax(diags)) => {
            let mut text = driver::render(&diags, &sm, &args.diagnostics);
            text.push_str(&format!("error: {name}: has syntax errors; left alone\n"));
            Err(FileError::Refused(text))
        }
        Err(e) => Err(FileError::Refused(format!(
            "error: {name}: {e}; left alone\n"
        ))),
    }
}

/// Writes through a temporary file beside the target and a rename, so a
/// crash never leaves half a source file.
fn write_atomically(path: &Path, text: &str) -> std::io::Result<()> {
    let mut tmp = path.as_os_str().to_owned();
    tmp.push(".stc-fmt.tmp");
    let tmp = PathBuf::from(tmp);
    std::fs::write(&tmp, text)?;
    if let Ok(meta) = std::fs::metadata(path) {
        let _ = std::fs::set_permissions(&tmp, meta.permissions());
    }
    std::fs::rename(&tmp, path).inspect_err(|_| {
        let _ = std::fs::remove_file(&tmp);
    })
}
