//! LSP positions (0-based line, UTF-16 code units) and byte offsets.

use lsp_types::Position;

/// The byte offset of `pos` in `text`; `Err` when the position is outside
/// the text (a line past the last, a character past the line's end).
pub fn offset(text: &str, pos: Position) -> Result<usize, String> {
    let mut start = 0usize;
    for _ in 0..pos.line {
        match text[start..].find('\n') {
            Some(i) => start += i + 1,
            None => {
                return Err(format!(
                    "line {} is outside the document ({} lines)",
                    pos.line,
                    text.lines().count()
                ))
            }
        }
    }
    let line = text[start..].split('\n').next().unwrap_or("");
    let line = line.strip_suffix('\r').unwrap_or(line);
    let mut units = 0u32;
    for (i, c) in line.char_indices() {
        if units >= pos.character {
            return Ok(start + i);
        }
        units += c.len_utf16() as u32;
    }
    if units >= pos.character {
        Ok(start + line.len())
    } else {
        Err(format!(
            "character {} is outside line {} ({} characters)",
            pos.character, pos.line, units
        ))
    }
}

/// The position of byte `offset` (clamped to the text).
pub fn position(text: &str, offset: usize) -> Position {
    let mut offset = offset.min(text.len());
    while !text.is_char_boundary(offset) {
        offset -= 1;
    }
    let before = &text[..offset];
    let line = before.bytes().filter(|&b| b == b'\n').count() as u32;
    let line_start = before.rfind('\n').map_or(0, |i| i + 1);
    let character = text[line_start..offset]
        .chars()
        .map(|c| c.len_utf16() as u32)
        .sum();
    Position::new(line, character)
}

/// The position just after the last character.
pub fn end_of(text: &str) -> Position {
    position(text, text.len())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn offsets_and_positions_round_trip_and_reject_outside() {
        let t = "ab\n\u{e9}\u{1F600}x\n";
        assert_eq!(offset(t, Position::new(0, 2)), Ok(2));
        assert_eq!(offset(t, Position::new(1, 3)), Ok(3 + 2 + 4));
        assert_eq!(position(t, 9), Position::new(1, 3));
        assert_eq!(offset(t, Position::new(2, 0)), Ok(t.len()));
        assert!(offset(t, Position::new(3, 0)).is_err());
        assert!(offset(t, Position::new(0, 3)).is_err());
    }
}
