//! Files, byte spans and line/column lookup.
//!
//! All files of a project live in one [`SourceMap`]. Each file occupies its
//! own range of a single 32-bit position space (with a one-byte gap between
//! files), so a [`Span`] is just two `u32`s and the file can be found from the
//! position. Lines and columns are computed on demand from a line index; the
//! hot phases never need them.

use std::fmt;

/// A byte range `lo..hi` in the position space of a [`SourceMap`].
#[derive(Clone, Copy, PartialEq, Eq, Hash, Default, PartialOrd, Ord)]
pub struct Span {
    pub lo: u32,
    pub hi: u32,
}

impl Span {
    pub const DUMMY: Span = Span { lo: 0, hi: 0 };

    pub fn new(lo: u32, hi: u32) -> Span {
        debug_assert!(lo <= hi);
        Span { lo, hi }
    }

    /// The smallest span covering both.
    pub fn to(self, other: Span) -> Span {
        Span {
            lo: self.lo.min(other.lo),
            hi: self.hi.max(other.hi),
        }
    }

    /// An empty span at the start of this one.
    pub fn shrink_to_lo(self) -> Span {
        Span {
            lo: self.lo,
            hi: self.lo,
        }
    }

    /// An empty span at the end of this one.
    pub fn shrink_to_hi(self) -> Span {
        Span {
            lo: self.hi,
            hi: self.hi,
        }
    }

    pub fn len(self) -> u32 {
        self.hi - self.lo
    }

    pub fn is_empty(self) -> bool {
        self.lo == self.hi
    }
}

impl fmt::Debug for Span {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}..{}", self.lo, self.hi)
    }
}

/// Index of a file in its [`SourceMap`].
#[derive(Clone, Copy, PartialEq, Eq, Hash, Debug, PartialOrd, Ord)]
pub struct FileId(pub u32);

/// A 1-based line and a 1-based column counted in characters.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
pub struct LineCol {
    pub line: u32,
    pub col: u32,
}

/// One source file: its name as the user gave it, its text (already decoded
/// to UTF-8) and where it starts in the position space.
pub struct SourceFile {
    pub name: String,
    pub text: String,
    pub base: u32,
    line_starts: Vec<u32>,
}

impl SourceFile {
    /// Whether the file is the standard library's (named `<...>`: the
    /// prelude), not one of the user's.
    pub fn is_library(&self) -> bool {
        self.name.starts_with('<')
    }

    /// Byte offsets (relative to the file) where each line starts.
    pub fn line_starts(&self) -> &[u32] {
        &self.line_starts
    }

    /// The span of the whole file.
    pub fn span(&self) -> Span {
        Span::new(self.base, self.base + self.text.len() as u32)
    }

    /// Line and column of an absolute position inside this file.
    pub fn line_col(&self, pos: u32) -> LineCol {
        let rel = pos.saturating_sub(self.base).min(self.text.len() as u32);
        let line = match self.line_starts.binary_search(&rel) {
            Ok(i) => i,
            Err(i) => i - 1,
        };
        let start = self.line_starts[line] as usize;
        let mut end = rel as usize;
        while !self.text.is_char_boundary(end) {
            end -= 1;
        }
        let col = self.text[start..end].chars().count() as u32 + 1;
        LineCol {
            line: line as u32 + 1,
            col,
        }
    }

    /// The text of a 1-based line, without its line terminator.
    pub fn line_text(&self, line: u32) -> &str {
        let i = (line as usize).saturating_sub(1);
        let Some(&start) = self.line_starts.get(i) else {
            return "";
        };
        let end = self
            .line_starts
            .get(i + 1)
            .map_or(self.text.len(), |&e| e as usize);
        self.text[start as usize..end].trim_end_matches(['\n', '\r'])
    }

    /// The source text under a span (which must lie in this file).
    pub fn slice(&self, span: Span) -> &str {
        let lo = (span.lo.saturating_sub(self.base) as usize).min(self.text.len());
        let hi = (span.hi.saturating_sub(self.base) as usize).clamp(lo, self.text.len());
        self.text.get(lo..hi).unwrap_or("")
    }
}

/// Every file of a project, in one position space.
#[derive(Default)]
pub struct SourceMap {
    files: Vec<SourceFile>,
    next_base: u32,
}

impl SourceMap {
    pub fn new() -> SourceMap {
        SourceMap::default()
    }

    /// Adds a file. Positions are 32-bit; a project larger than 4 GiB in
    /// total is refused with `None`.
    pub fn add(&mut self, name: impl Into<String>, text: String) -> Option<FileId> {
        let len = u32::try_from(text.len()).ok()?;
        let base = self.next_base;
        let next = base.checked_add(len)?.checked_add(1)?;
        let mut line_starts = vec![0u32];
        for (i, b) in text.bytes().enumerate() {
            if b == b'\n' {
                line_starts.push(i as u32 + 1);
            }
        }
        let id = FileId(self.files.len() as u32);
        self.files.push(SourceFile {
            name: name.into(),
            text,
            base,
            line_starts,
        });
        self.next_base = next;
        Some(id)
    }

    /// Keeps the first `files` files and drops the others, so the next
    /// file added takes the position the first dropped one had (an editor
    /// re-reading its last file keeps every span of the files before it).
    pub fn truncate(&mut self, files: usize) {
        self.files.truncate(files);
        self.next_base = self
            .files
            .last()
            .map_or(0, |f| f.base + f.text.len() as u32 + 1);
    }

    pub fn file(&self, id: FileId) -> &SourceFile {
        &self.files[id.0 as usize]
    }

    pub fn files(&self) -> impl Iterator<Item = (FileId, &SourceFile)> {
        self.files
            .iter()
            .enumerate()
            .map(|(i, f)| (FileId(i as u32), f))
    }

    pub fn len(&self) -> usize {
        self.files.len()
    }

    pub fn is_empty(&self) -> bool {
        self.files.is_empty()
    }

    /// The file that contains a position (positions past a file's end, up to
    /// the gap byte, belong to it, so an end-of-file span has a file).
    pub fn file_of(&self, pos: u32) -> Option<FileId> {
        if self.files.is_empty() {
            return None;
        }
        let i = match self.files.binary_search_by_key(&pos, |f| f.base) {
            Ok(i) => i,
            Err(0) => return None,
            Err(i) => i - 1,
        };
        Some(FileId(i as u32))
    }

    /// The text under a span.
    pub fn slice(&self, span: Span) -> &str {
        match self.file_of(span.lo) {
            Some(f) => self.file(f).slice(span),
            None => "",
        }
    }

    /// File, line and column of the start of a span.
    pub fn locate(&self, pos: u32) -> Option<(&SourceFile, LineCol)> {
        let f = self.file(self.file_of(pos)?);
        Some((f, f.line_col(pos)))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn positions_map_back_to_files_lines_and_char_columns() {
        let mut sm = SourceMap::new();
        let a = sm.add("a.st", "ab\ncdé f\n".to_string()).unwrap();
        let b = sm.add("b.st", "x\ny".to_string()).unwrap();
        let fa = sm.file(a);
        assert_eq!(fa.line_col(fa.base), LineCol { line: 1, col: 1 });
        // 'f' is after the two-byte 'é': byte 6 of line 2, column 5.
        let pos = fa.base + 3 + "cdé ".len() as u32;
        assert_eq!(fa.line_col(pos), LineCol { line: 2, col: 5 });
        assert_eq!(fa.line_text(2), "cdé f");
        let fb = sm.file(b);
        assert_eq!(sm.file_of(fb.base + 2), Some(b));
        assert_eq!(sm.file_of(fa.base + 9), Some(a));
        assert_eq!(fb.line_col(fb.base + 2), LineCol { line: 2, col: 1 });
        assert_eq!(sm.slice(Span::new(fb.base, fb.base + 1)), "x");
    }
}
