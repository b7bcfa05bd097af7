//! Writing what a command produced: a file (`-o FILE`) or a directory tree
//! (`--emit c -o DIR`). A file is written to a temporary file beside it and
//! renamed over it, so it is written whole or not at all. A tree is written beside its destination and moved
//! into place at the end, so a failed build never leaves a half-written
//! tree that looks complete, and a directory that is not an earlier output
//! of stc is never replaced (nothing the user had is lost).

use std::path::Path;

/// The file that marks a directory as an stc C output.
pub const C_MARKER: &str = "stc_meta.h";

/// Writes `bytes` as the file `path`, whole or not at all (a temporary file
/// in the same directory, renamed into place).
pub fn write_file(path: &Path, bytes: &[u8]) -> Result<(), String> {
    let shown = path.display();
    if path.is_dir() {
        return Err(format!("cannot write {shown}: it is a directory"));
    }
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_else(|| "out".into());
    let parent = match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p.to_path_buf(),
        _ => Path::new(".").to_path_buf(),
    };
    let tmp = parent.join(format!(".{name}.stc-new-{}", std::process::id()));
    let result = std::fs::write(&tmp, bytes).and_then(|()| std::fs::rename(&tmp, path));
    if let Err(e) = result {
        let _ = std::fs::remove_file(&tmp);
        return Err(format!("cannot write {shown}: {e}"));
    }
    Ok(())
}

/// Writes `files` as the directory `dir`, replacing an earlier output.
pub fn write_tree(dir: &Path, files: &[(String, String)]) -> Result<(), String> {
    let shown = dir.display();
    if dir.exists() {
        if !dir.is_dir() {
            return Err(format!(
                "cannot write {shown}: it exists and is not a directory"
            ));
        }
        let empty = std::fs::read_dir(dir)
            .map_err(|e| format!("cannot read {shown}: {e}"))?
            .next()
            .is_none();
        if !empty && !dir.join(C_MARKER).exists() {
            return Err(format!(
                "cannot write {shown}: it exists and is not an output of stc (no {C_MARKER}); remove it or choose another directory"
            ));
        }
    }
    let name = dir
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_else(|| "out".into());
    let parent = match dir.parent() {
        Some(p) if !p.as_os_str().is_empty() => p.to_path_buf(),
        _ => Path::new(".").to_path_buf(),
    };
    let pid = std::process::id();
    let tmp = parent.join(format!(".{name}.stc-new-{pid}"));
    let old = parent.join(format!(".{name}.stc-old-{pid}"));
    let _ = std::fs::remove_dir_all(&tmp);
    let write = || -> std::io::Result<()> {
        std::fs::create_dir_all(&tmp)?;
        for (f, text) in files {
            std::fs::write(tmp.join(f), text)?;
        }
        Ok(())
    };
    if let Err(e) = write() {
        let _ = std::fs::remove_dir_all(&tmp);
        return Err(format!("cannot write {shown}: {e}"));
    }
    if dir.exists() {
        if let Err(e) = std::fs::rename(dir, &old) {
            let _ = std::fs::remove_dir_all(&tmp);
            return Err(format!("cannot replace {shown}: {e}"));
        }
        if let Err(e) = std::fs::rename(&tmp, dir) {
            let _ = std::fs::rename(&old, dir);
            let _ = std::fs::remove_dir_all(&tmp);
            return Err(format!("cannot replace {shown}: {e}"));
        }
        let _ = std::fs::remove_dir_all(&old);
    } else if let Err(e) = std::fs::rename(&tmp, dir) {
        let _ = std::fs::remove_dir_all(&tmp);
        return Err(format!("cannot write {shown}: {e}"));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn trees_replace_earlier_outputs_but_nothing_else() {
        let base = std::env::temp_dir().join(format!("stc-output-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&base);
        std::fs::create_dir_all(&base).unwrap();
        let dir = base.join("out");
        let files = vec![
            (C_MARKER.to_string(), "a".to_string()),
            ("x.c".into(), "1".into()),
        ];
        write_tree(&dir, &files).unwrap();
        assert_eq!(std::fs::read_to_string(dir.join("x.c")).unwrap(), "1");
        // An earlier output is replaced whole.
        std::fs::write(dir.join("stale.c"), "old").unwrap();
        let files2 = vec![(C_MARKER.to_string(), "b".to_string())];
        write_tree(&dir, &files2).unwrap();
        assert!(!dir.join("stale.c").exists());
        // A directory of the user's is left alone.
        let mine = base.join("mine");
        std::fs::create_dir_all(&mine).unwrap();
        std::fs::write(mine.join("notes.txt"), "keep").unwrap();
        let err = write_tree(&mine, &files).unwrap_err();
        assert!(err.contains("not an output of stc"), "{err}");
        assert_eq!(
            std::fs::read_to_string(mine.join("notes.txt")).unwrap(),
            "keep"
        );
        // No temporary directories are left behind.
        let left: Vec<_> = std::fs::read_dir(&base)
            .unwrap()
            .flatten()
            .map(|e| e.file_name())
            .collect();
        assert_eq!(left.len(), 2, "{left:?}");
        let _ = std::fs::remove_dir_all(&base);
    }
}
