//! The lexer: source text to a flat vector of [`Token`]s.
//!
//! One pass over the bytes, no allocation per token. Comments and pragmas do
//! not reach the parser; they are kept in a separate trivia list (with their
//! spans) so a formatter or language server can put them back. The lexer
//! reports only what it alone can see: characters that start no token,
//! unterminated comments/strings/pragmas and malformed identifiers. The value
//! of a literal is checked where it is decoded, by the parser
//! ([`crate::literal`]), so each problem is reported exactly once.

use stc_diagnostics::{Code, Diagnostic, Span};

use crate::token::{classify_word, ElemType, Token, TokenKind};

#[derive(Clone, Copy, PartialEq, Eq, Debug)]
pub enum TriviaKind {
    /// `(* *)`, `/* */` or `//` comment.
    Comment,
    /// `{ ... }`.
    Pragma,
}

#[derive(Clone, Copy, PartialEq, Eq, Debug)]
pub struct Trivia {
    pub kind: TriviaKind,
    pub span: Span,
}

pub struct Lexed {
    /// The tokens, always ending with one `Eof` token.
    pub tokens: Vec<Token>,
    pub trivia: Vec<Trivia>,
    pub diagnostics: Vec<Diagnostic>,
}

/// Lexes one file whose first byte is at position `base`.
pub fn lex(text: &str, base: u32) -> Lexed {
    let mut lx = Lexer {
        src: text.as_bytes(),
        text,
        base,
        pos: 0,
        tokens: Vec::with_capacity(text.len() / 5 + 16),
        trivia: Vec::new(),
        diagnostics: Vec::new(),
        bad_idents: Vec::new(),
    };
    lx.run();
    Lexed {
        tokens: lx.tokens,
        trivia: lx.trivia,
        diagnostics: lx.diagnostics,
    }
}

struct Lexer<'a> {
    src: &'a [u8],
    text: &'a str,
    base: u32,
    pos: usize,
    tokens: Vec<Token>,
    trivia: Vec<Trivia>,
    diagnostics: Vec<Diagnostic>,
    /// Invalid identifiers already reported (E0005 once per name and file,
    /// at its first occurrence, usually its declaration).
    bad_idents: Vec<String>,
}

/// The position of the first occurrence of `needle` in `hay`.
fn find_bytes(hay: &[u8], needle: &[u8]) -> Option<usize> {
    hay.windows(needle.len()).position(|w| w == needle)
}

/// Whether a comment's text is the export marker `marker`, ignoring case and
/// white space (`@KEY@: DESCRIPTION`).
fn marker_is(text: &[u8], marker: &[u8]) -> bool {
    let mut it = text.iter().filter(|b| !b.is_ascii_whitespace());
    marker
        .iter()
        .all(|m| it.next().is_some_and(|b| b.eq_ignore_ascii_case(m)))
        && it.next().is_none()
}

fn is_ident_continue(b: u8) -> bool {
    b.is_ascii_alphanumeric() || b == b'_'
}

impl<'a> Lexer<'a> {
    fn peek(&self, ahead: usize) -> u8 {
        self.src.get(self.pos + ahead).copied().unwrap_or(0)
    }

    fn span(&self, lo: usize, hi: usize) -> Span {
        Span::new(self.base + lo as u32, self.base + hi as u32)
    }

    fn push(&mut self, kind: TokenKind, lo: usize) {
        self.tokens.push(Token {
            kind,
            lo: self.base + lo as u32,
            hi: self.base + self.pos as u32,
        });
    }

    fn error(&mut self, code: Code, lo: usize, hi: usize, msg: impl Into<String>) {
        let d = Diagnostic::new(code, self.span(lo, hi), msg);
        self.diagnostics.push(d);
    }

    fn run(&mut self) {
        // A UTF-8 byte order mark is not part of the program.
        if self.src.starts_with(&[0xEF, 0xBB, 0xBF]) {
            self.pos = 3;
        }
        while self.pos < self.src.len() {
            let start = self.pos;
            let b = self.src[self.pos];
            match b {
                b' ' | b'\t' | b'\n' | b'\r' | 0x0B | 0x0C => self.pos += 1,
                b'a'..=b'z' | b'A'..=b'Z' | b'_' => self.word(),
                b'0'..=b'9' => self.number(),
                b'(' if self.peek(1) == b'*' => self.nested_comment(),
                b'/' if self.peek(1) == b'/' => self.line_comment(),
                b'/' if self.peek(1) == b'*' => self.c_comment(),
                b'{' => self.pragma(),
                b'\'' => self.string(b'\'', TokenKind::SString),
                b'"' => self.string(b'"', TokenKind::WString),
                b'%' => self.address(),
                _ if b >= 0x80 => self.non_ascii(),
                _ => {
                    let (kind, len) = match (b, self.peek(1)) {
                        (b'(', _) => (TokenKind::LParen, 1),
                        (b')', _) => (TokenKind::RParen, 1),
                        (b'[', _) => (TokenKind::LBracket, 1),
                        (b']', _) => (TokenKind::RBracket, 1),
                        (b',', _) => (TokenKind::Comma, 1),
                        (b';', _) => (TokenKind::Semi, 1),
                        (b':', b'=') => (TokenKind::Assign, 2),
                        (b':', _) => (TokenKind::Colon, 1),
                        (b'=', b'>') => (TokenKind::Arrow, 2),
                        (b'=', _) => (TokenKind::Eq, 1),
                        (b'.', b'.') => (TokenKind::DotDot, 2),
                        (b'.', _) => (TokenKind::Dot, 1),
                        (b'#', _) => (TokenKind::Hash, 1),
                        (b'+', _) => (TokenKind::Plus, 1),
                        (b'-', _) => (TokenKind::Minus, 1),
                        (b'*', b'*') => (TokenKind::StarStar, 2),
                        (b'*', _) => (TokenKind::Star, 1),
                        (b'/', _) => (TokenKind::Slash, 1),
                        (b'&', _) => (TokenKind::Amp, 1),
                        (b'<', b'>') => (TokenKind::Ne, 2),
                        (b'<', b'=') => (TokenKind::Le, 2),
                        (b'<', _) => (TokenKind::Lt, 1),
                        (b'>', b'=') => (TokenKind::Ge, 2),
                        (b'>', _) => (TokenKind::Gt, 1),
                        (b'^', _) => (TokenKind::Caret, 1),
                        (b'?', b'=') => (TokenKind::QuestionAssign, 2),
                        _ => {
                            self.pos += 1;
                            let shown = if b.is_ascii_graphic() {
                                format!("`{}`", b as char)
                            } else {
                                format!("U+{b:04X}")
                            };
                            self.error(
                                Code::E0001,
                                start,
                                self.pos,
                                format!("invalid character {shown}"),
                            );
                            continue;
                        }
                    };
                    self.pos += len;
                    self.push(kind, start);
                }
            }
        }
        let end = self.src.len();
        self.tokens.push(Token {
            kind: TokenKind::Eof,
            lo: self.base + end as u32,
            hi: self.base + end as u32,
        });
    }

    /// A character of 0x80 and above outside strings and comments: a letter
    /// starts a (non-standard) identifier, a no-break space is white space,
    /// anything else is invalid.
    fn non_ascii(&mut self) {
        let start = self.pos;
        let c = self.text[start..].chars().next().unwrap_or('\u{FFFD}');
        if c.is_alphabetic() {
            self.word();
        } else {
            self.pos += c.len_utf8();
            if c != '\u{A0}' {
                self.error(
                    Code::E0001,
                    start,
                    self.pos,
                    format!("invalid character `{c}` (U+{:04X})", c as u32),
                );
            }
        }
    }

    /// An identifier, keyword, or a typed time literal such as `T#1s`.
    fn word(&mut self) {
        let start = self.pos;
        let mut non_ascii = false;
        while self.pos < self.src.len() {
            let b = self.src[self.pos];
            if is_ident_continue(b) {
                self.pos += 1;
            } else if b >= 0x80 {
                let c = self.text[self.pos..].chars().next().unwrap_or(' ');
                if c.is_alphanumeric() {
                    non_ascii = true;
                    self.pos += c.len_utf8();
                } else {
                    break;
                }
            } else {
                break;
            }
        }
        let word = &self.src[start..self.pos];
        let mut upper = [0u8; 20];
        let kind = if word.len() <= upper.len() && !non_ascii {
            for (u, &b) in upper.iter_mut().zip(word) {
                *u = b.to_ascii_uppercase();
            }
            let upper = &upper[..word.len()];
            if self.peek(0) == b'#' {
                if let Some(lit) = ElemType::time_literal_prefix(upper) {
                    self.pos += 1;
                    self.time_literal_body(lit);
                    self.push(lit, start);
                    return;
                }
            }
            classify_word(upper)
        } else {
            TokenKind::Ident
        };
        if kind == TokenKind::Ident {
            self.check_identifier(start, non_ascii);
        }
        self.push(kind, start);
    }

    fn check_identifier(&mut self, start: usize, non_ascii: bool) {
        let word = &self.text[start..self.pos];
        // Doubled and trailing underscores are forbidden by the standard but
        // accepted by every tool and common in real code: a warning.
        let problem = if non_ascii {
            Some((
                Code::E0005,
                "identifiers may contain only ASCII letters, digits and `_`",
            ))
        } else if word.contains("__") {
            Some((Code::W0008, "IEC 61131-3 forbids two underscores in a row"))
        } else if word.ends_with('_') {
            Some((Code::W0008, "IEC 61131-3 forbids a trailing underscore"))
        } else {
            None
        };
        if let Some((code, p)) = problem {
            let key = word.to_ascii_lowercase();
            if self.bad_idents.contains(&key) {
                return;
            }
            self.bad_idents.push(key);
            let message = if code == Code::E0005 {
                format!("invalid identifier `{word}`: {p}")
            } else {
                format!("identifier `{word}` accepted: {p}")
            };
            self.error(code, start, self.pos, message);
        }
    }

    fn eat_digits(&mut self) {
        while self.pos < self.src.len()
            && (self.src[self.pos].is_ascii_digit() || self.src[self.pos] == b'_')
        {
            self.pos += 1;
        }
    }

    /// After `T#`, `D#`, `TOD#`, `DT#`: the literal's body. Only the shape is
    /// scanned here; [`crate::literal`] checks and decodes it.
    fn time_literal_body(&mut self, kind: TokenKind) {
        if kind == TokenKind::Duration {
            if matches!(self.peek(0), b'-' | b'+') {
                self.pos += 1;
            }
            loop {
                if !self.peek(0).is_ascii_digit() {
                    break;
                }
                self.eat_digits();
                if self.peek(0) == b'.' && self.peek(1).is_ascii_digit() {
                    self.pos += 1;
                    self.eat_digits();
                }
                while self.peek(0).is_ascii_alphabetic() {
                    self.pos += 1;
                }
                if self.peek(0) == b'_' && self.peek(1).is_ascii_digit() {
                    self.pos += 1;
                }
            }
        } else {
            // Dates, times of day: digits separated by `-`, `:` and `.`.
            loop {
                self.eat_digits();
                if matches!(self.peek(0), b'-' | b':' | b'.') && self.peek(1).is_ascii_digit() {
                    self.pos += 1;
                } else {
                    break;
                }
            }
        }
    }

    fn number(&mut self) {
        let start = self.pos;
        self.eat_digits();
        let mut kind = TokenKind::Int;
        match self.peek(0) {
            b'#' => {
                self.pos += 1;
                while self.pos < self.src.len() && is_ident_continue(self.src[self.pos]) {
                    self.pos += 1;
                }
                kind = TokenKind::BasedInt;
            }
            b'.' if self.peek(1).is_ascii_digit() => {
                self.pos += 1;
                self.eat_digits();
                self.exponent();
                kind = TokenKind::Real;
            }
            b'e' | b'E' if self.exponent() => kind = TokenKind::Real,
            _ => {}
        }
        // Letters glued to a number (`12abc`) stay part of the token, so the
        // literal is reported once as malformed instead of as two tokens.
        while self.pos < self.src.len() && is_ident_continue(self.src[self.pos]) {
            self.pos += 1;
        }
        self.push(kind, start);
    }

    fn exponent(&mut self) -> bool {
        if !matches!(self.peek(0), b'e' | b'E') {
            return false;
        }
        let digit_at = if matches!(self.peek(1), b'+' | b'-') {
            2
        } else {
            1
        };
        if !self.peek(digit_at).is_ascii_digit() {
            return false;
        }
        self.pos += digit_at;
        self.eat_digits();
        true
    }

    /// A `(* *)` comment. Comments nest (spec/semantics.md); one that nesting
    /// leaves open at the end of the file is read again without nesting, as
    /// the 2nd edition reads it (W0003 at the inner `(*` that caused it), and
    /// only one with no `*)` at all is unterminated (E0002).
    fn nested_comment(&mut self) {
        let start = self.pos;
        self.pos += 2;
        let mut depth = 1u32;
        while self.pos < self.src.len() {
            match (self.src[self.pos], self.peek(1)) {
                (b'(', b'*') => {
                    depth += 1;
                    self.pos += 2;
                }
                (b'*', b')') => {
                    depth -= 1;
                    self.pos += 2;
                    if depth == 0 {
                        self.skip_marked_description(start);
                        self.trivia(TriviaKind::Comment, start);
                        return;
                    }
                }
                _ => self.pos += 1,
            }
        }
        let body = start + 2;
        if let Some(close) = find_bytes(&self.src[body..], b"*)") {
            let end = body + close + 2;
            // Nesting left the comment open although a `*)` follows, so an
            // inner `(*` comes before that first `*)`.
            let inner = find_bytes(&self.src[body..end - 2], b"(*").map_or(start, |i| body + i);
            self.pos = end;
            let d = Diagnostic::new(
                Code::W0003,
                self.span(inner, inner + 2),
                "nested comment not closed; read as a non-nesting comment",
            )
            .with_label("a nested `(*`: counting it, the comment is never closed")
            .with_secondary(
                self.span(start, start + 2),
                "this comment is read as ending at its first `*)`",
            )
            .with_help("add the missing `*)`, or remove the inner `(*`");
            self.diagnostics.push(d);
            self.trivia(TriviaKind::Comment, start);
            return;
        }
        self.pos = self.src.len();
        self.error(Code::E0002, start, start + 2, "unterminated comment");
        self.trivia(TriviaKind::Comment, start);
    }

    /// After the comment `(*@KEY@:DESCRIPTION*)` of the PC WORX / MULTIPROG
    /// text export (the format OSCAT is distributed in), free text follows,
    /// outside any comment, up to `(*@KEY@:END_DESCRIPTION*)`: the whole
    /// region is a comment, as IronPLC reads it. Without the end marker the
    /// comment is an ordinary one.
    fn skip_marked_description(&mut self, start: usize) {
        if !marker_is(&self.src[start + 2..self.pos - 2], b"@KEY@:DESCRIPTION") {
            return;
        }
        let mut at = self.pos;
        while let Some(i) = find_bytes(&self.src[at..], b"(*") {
            let open = at + i;
            let Some(j) = find_bytes(&self.src[open + 2..], b"*)") else {
                return;
            };
            let close = open + 2 + j;
            if marker_is(&self.src[open + 2..close], b"@KEY@:END_DESCRIPTION") {
                self.pos = close + 2;
                return;
            }
            at = close + 2;
        }
    }

    fn c_comment(&mut self) {
        let start = self.pos;
        self.pos += 2;
        match self.text[self.pos..].find("*/") {
            Some(i) => self.pos += i + 2,
            None => {
                self.pos = self.src.len();
                self.error(Code::E0002, start, start + 2, "unterminated comment");
            }
        }
        self.trivia(TriviaKind::Comment, start);
    }

    fn line_comment(&mut self) {
        let start = self.pos;
        match self.src[self.pos..].iter().position(|&b| b == b'\n') {
            Some(i) => self.pos += i,
            None => self.pos = self.src.len(),
        }
        self.trivia(TriviaKind::Comment, start);
    }

    /// A pragma `{ ... }`, or the MatIEC block `{{ ... }}` of embedded C
    /// code, which may contain single braces.
    fn pragma(&mut self) {
        let start = self.pos;
        let (close, len): (&[u8], usize) = if self.peek(1) == b'{' {
            (b"}}", 2)
        } else {
            (b"}", 1)
        };
        match find_bytes(&self.src[self.pos + len..], close) {
            Some(i) => self.pos += len + i + close.len(),
            None => {
                self.pos = self.src.len();
                self.error(Code::E0004, start, start + len, "unterminated pragma");
            }
        }
        self.trivia(TriviaKind::Pragma, start);
    }

    fn trivia(&mut self, kind: TriviaKind, start: usize) {
        let span = self.span(start, self.pos);
        self.trivia.push(Trivia { kind, span });
    }

    /// A string literal. It must end on its line: a raw line break ends an
    /// unterminated string there, which keeps the rest of the file readable.
    fn string(&mut self, quote: u8, kind: TokenKind) {
        let start = self.pos;
        self.pos += 1;
        loop {
            match self.src.get(self.pos) {
                Some(&b) if b == quote => {
                    self.pos += 1;
                    break;
                }
                Some(b'$') if !matches!(self.peek(1), b'\n' | b'\r' | 0) => self.pos += 2,
                Some(b'\n') | Some(b'\r') | None => {
                    self.error(Code::E0003, start, start + 1, "unterminated string literal");
                    break;
                }
                Some(_) => self.pos += 1,
            }
        }
        // A `$` before a multi-byte character can leave pos inside it.
        while !self.text.is_char_boundary(self.pos) {
            self.pos += 1;
        }
        self.push(kind, start);
    }

    /// `%IX1.2`, `%QW4`, `%M*`, or (after a dot) `%X3`. Only the shape is
    /// scanned; the parser decodes and checks it.
    fn address(&mut self) {
        let start = self.pos;
        self.pos += 1;
        let kind = match self.peek(0).to_ascii_uppercase() {
            b'I' | b'Q' | b'M' => TokenKind::Address,
            b'X' | b'B' | b'W' | b'D' | b'L' if self.peek(1).is_ascii_digit() => {
                TokenKind::PartialAccess
            }
            _ => TokenKind::Address,
        };
        while self.pos < self.src.len() {
            let b = self.src[self.pos];
            // A partial access has one number (`w.%B1.1` is bit 1 of
            // byte 1: the `.1` is the next access, not part of this one).
            let more_parts = kind != TokenKind::PartialAccess;
            if b.is_ascii_alphanumeric()
                || b == b'*'
                || (more_parts && b == b'.' && self.peek(1).is_ascii_digit())
            {
                self.pos += 1;
            } else {
                break;
            }
        }
        self.push(kind, start);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::token::Keyword;

    fn kinds(src: &str) -> Vec<TokenKind> {
        let l = lex(src, 0);
        assert!(l.diagnostics.is_empty(), "{:?}", l.diagnostics);
        l.tokens.iter().map(|t| t.kind).collect()
    }

    #[test]
    fn punctuation_and_keywords() {
        use TokenKind::*;
        assert_eq!(
            kinds("IF a:=b<>c THEN x[1..2] => ** ; END_if"),
            vec![
                Kw(Keyword::If),
                Ident,
                Assign,
                Ident,
                Ne,
                Ident,
                Kw(Keyword::Then),
                Ident,
                LBracket,
                Int,
                DotDot,
                Int,
                RBracket,
                Arrow,
                StarStar,
                Semi,
                Kw(Keyword::EndIf),
                Eof
            ]
        );
    }

    #[test]
    fn literals_are_single_tokens() {
        use TokenKind::*;
        assert_eq!(
            kinds("16#FF 1_000 1.5E3 2.5e-4 T#1h_2m t#-250ms TOD#12:30:00.5 DT#2024-01-31-12:00:00 D#2024-01-31 %IX0.1 'a$'b' \"w\""),
            vec![BasedInt, Int, Real, Real, Duration, Duration, Tod, Dt, Date, Address, SString, WString, Eof]
        );
        assert_eq!(
            kinds("INT#-5"),
            vec![Elem(ElemType::Int), Hash, Minus, Int, Eof]
        );
        assert_eq!(kinds("x.%X3"), vec![Ident, Dot, PartialAccess, Eof]);
    }

    #[test]
    fn comments_nest_and_are_trivia() {
        let l = lex("a (* x (* y *) z *) b // c\n/* d */ {p} e", 0);
        assert!(l.diagnostics.is_empty());
        assert_eq!(l.tokens.len(), 4);
        assert_eq!(l.trivia.len(), 4);
        assert_eq!(l.trivia[3].kind, TriviaKind::Pragma);
    }

    #[test]
    fn unterminated_things_are_reported_where_they_start() {
        let l = lex("a (* never closed", 10);
        assert_eq!(l.diagnostics[0].code, Code::E0002);
        assert_eq!(l.diagnostics[0].span, Span::new(12, 14));
        let l = lex("x := 'abc\ny := 1;", 0);
        assert_eq!(l.diagnostics.len(), 1);
        assert_eq!(l.diagnostics[0].code, Code::E0003);
        assert_eq!(l.tokens.last().map(|t| t.kind), Some(TokenKind::Eof));
    }

    #[test]
    fn bad_identifiers_and_characters() {
        let l = lex("a__b c_ ? d", 0);
        let codes: Vec<_> = l.diagnostics.iter().map(|d| d.code).collect();
        assert_eq!(codes, vec![Code::W0008, Code::W0008, Code::E0001]);
        let l = lex("grüße := 1;", 0);
        assert_eq!(l.diagnostics.len(), 1);
        assert_eq!(l.tokens[0].kind, TokenKind::Ident);
    }
}
