//! Tokens: what the lexer produces and the parser consumes.
//!
//! A token is a kind and a byte range (12 bytes, no allocation); its text is
//! read back from the source when needed. Keywords and elementary type names
//! are reserved words and get their own kinds; standard function names and
//! IL operators are ordinary identifiers (spec/semantics.md, Lexical).

use stc_diagnostics::Span;

#[derive(Clone, Copy, PartialEq, Eq, Debug)]
pub struct Token {
    pub kind: TokenKind,
    pub lo: u32,
    pub hi: u32,
}

impl Token {
    pub fn span(&self) -> Span {
        Span::new(self.lo, self.hi)
    }
}

#[derive(Clone, Copy, PartialEq, Eq, Debug, Hash)]
pub enum TokenKind {
    Eof,
    Ident,
    /// Decimal integer `123`, `1_000`.
    Int,
    /// `2#1010`, `8#17`, `16#FF`.
    BasedInt,
    /// `1.5`, `2.5E-3`.
    Real,
    /// `'single byte'`.
    SString,
    /// `"double byte"`.
    WString,
    /// `T#1s`, `TIME#...`, `LTIME#...` (the prefix is part of the token).
    Duration,
    /// `D#2024-01-31`, `DATE#...`, `LDATE#...`.
    Date,
    /// `TOD#12:00:00`, `TIME_OF_DAY#...`, `LTOD#...`.
    Tod,
    /// `DT#2024-01-31-12:00:00`, `DATE_AND_TIME#...`, `LDT#...`.
    Dt,
    /// `%IX0.1`, `%QW4`, `%I*`.
    Address,
    /// `%X3` after a dot: a bit (or byte, word...) of a bit string.
    PartialAccess,
    LParen,
    RParen,
    LBracket,
    RBracket,
    Comma,
    Semi,
    Colon,
    /// `:=`
    Assign,
    /// `=>`
    Arrow,
    Dot,
    DotDot,
    Hash,
    Plus,
    Minus,
    Star,
    StarStar,
    Slash,
    Amp,
    Eq,
    /// `<>`
    Ne,
    Lt,
    Le,
    Gt,
    Ge,
    /// `^` (pointer dereference, a dialect feature).
    Caret,
    /// `?=` (reference assignment attempt, a dialect feature).
    QuestionAssign,
    Elem(ElemType),
    Generic(GenericType),
    Kw(Keyword),
}

impl TokenKind {
    /// How the token kind is named in "expected ..., found ..." messages.
    pub fn describe(self) -> String {
        match self {
            TokenKind::Eof => "end of file".into(),
            TokenKind::Ident => "identifier".into(),
            TokenKind::Int | TokenKind::BasedInt => "integer literal".into(),
            TokenKind::Real => "real literal".into(),
            TokenKind::SString | TokenKind::WString => "string literal".into(),
            TokenKind::Duration => "duration literal".into(),
            TokenKind::Date => "date literal".into(),
            TokenKind::Tod => "time-of-day literal".into(),
            TokenKind::Dt => "date-and-time literal".into(),
            TokenKind::Address => "direct address".into(),
            TokenKind::PartialAccess => "partial access".into(),
            TokenKind::Elem(t) => format!("type name `{}`", t.name()),
            TokenKind::Generic(t) => format!("type name `{}`", t.name()),
            TokenKind::Kw(k) => format!("`{}`", k.text()),
            p => format!("`{}`", p.punct_text()),
        }
    }

    fn punct_text(self) -> &'static str {
        match self {
            TokenKind::LParen => "(",
            TokenKind::RParen => ")",
            TokenKind::LBracket => "[",
            TokenKind::RBracket => "]",
            TokenKind::Comma => ",",
            TokenKind::Semi => ";",
            TokenKind::Colon => ":",
            TokenKind::Assign => ":=",
            TokenKind::Arrow => "=>",
            TokenKind::Dot => ".",
            TokenKind::DotDot => "..",
            TokenKind::Hash => "#",
            TokenKind::Plus => "+",
            TokenKind::Minus => "-",
            TokenKind::Star => "*",
            TokenKind::StarStar => "**",
            TokenKind::Slash => "/",
            TokenKind::Amp => "&",
            TokenKind::Eq => "=",
            TokenKind::Ne => "<>",
            TokenKind::Lt => "<",
            TokenKind::Le => "<=",
            TokenKind::Gt => ">",
            TokenKind::Ge => ">=",
            TokenKind::Caret => "^",
            TokenKind::QuestionAssign => "?=",
            _ => "?",
        }
    }

    /// Keywords and reserved type names: words that cannot name anything.
    pub fn is_reserved_word(self) -> bool {
        matches!(
            self,
            TokenKind::Kw(_) | TokenKind::Elem(_) | TokenKind::Generic(_)
        )
    }
}

macro_rules! word_enum {
    ($(#[$m:meta])* $name:ident { $($variant:ident $(($code:literal))? = $text:literal $(| $alias:literal)*,)* }) => {
        $(#[$m])*
        #[derive(Clone, Copy, PartialEq, Eq, Debug, Hash, PartialOrd, Ord)]
        pub enum $name { $($variant $(= $code)?,)* }

        impl $name {
            pub const ALL: &'static [$name] = &[$($name::$variant,)*];

            /// Every spelling (aliases included) with its word.
            pub const SPELLINGS: &'static [(&'static str, $name)] =
                &[$(($text, $name::$variant), $(($alias, $name::$variant),)*)*];

            /// The canonical (upper-case) spelling.
            pub fn name(self) -> &'static str {
                match self { $($name::$variant => $text,)* }
            }

            /// Looks a word up by its spelling, case-insensitively.
            pub fn from_name(s: &str) -> Option<$name> {
                Self::SPELLINGS.iter().find(|(t, _)| t.eq_ignore_ascii_case(s)).map(|&(_, w)| w)
            }
        }
    };
}

word_enum! {
    /// The elementary data types (spec/semantics.md, Types).
    ///
    /// The explicit values are a file format and an ABI: the byte stored
    /// for an elementary type in `.stbc` files, the `STC_E_*` codes of the
    /// generated C (`stc_codes.h`), and the order of the elementary types
    /// in every type table (`stc_sema::types::elem_type_id`). Never
    /// renumber a type; a new one takes the next free value (and the
    /// `.stbc` version is bumped if the meaning of a byte changes).
    #[repr(u8)]
    ElemType {
        Bool(0) = "BOOL",
        Sint(1) = "SINT",
        Int(2) = "INT",
        Dint(3) = "DINT",
        Lint(4) = "LINT",
        Usint(5) = "USINT",
        Uint(6) = "UINT",
        Udint(7) = "UDINT",
        Ulint(8) = "ULINT",
        Real(9) = "REAL",
        Lreal(10) = "LREAL",
        Byte(11) = "BYTE",
        Word(12) = "WORD",
        Dword(13) = "DWORD",
        Lword(14) = "LWORD",
        Time(15) = "TIME",
        Ltime(16) = "LTIME",
        Date(17) = "DATE",
        Ldate(18) = "LDATE",
        Tod(19) = "TOD" | "TIME_OF_DAY",
        Ltod(20) = "LTOD" | "LTIME_OF_DAY",
        Dt(21) = "DT" | "DATE_AND_TIME",
        Ldt(22) = "LDT" | "LDATE_AND_TIME",
        String(23) = "STRING",
        Wstring(24) = "WSTRING",
        Char(25) = "CHAR",
        Wchar(26) = "WCHAR",
    }
}

impl ElemType {
    /// The type's stable code (see the type's documentation).
    pub const fn code(self) -> u8 {
        self as u8
    }

    /// The type of a code; `None` for a value no type has.
    pub fn from_code(code: u8) -> Option<ElemType> {
        Self::ALL.iter().copied().find(|e| e.code() == code)
    }
}

word_enum! {
    /// The generic data types, used in the signatures of standard functions.
    GenericType {
        Any = "ANY",
        AnyDerived = "ANY_DERIVED",
        AnyElementary = "ANY_ELEMENTARY",
        AnyMagnitude = "ANY_MAGNITUDE",
        AnyNum = "ANY_NUM",
        AnyReal = "ANY_REAL",
        AnyInt = "ANY_INT",
        AnySigned = "ANY_SIGNED",
        AnyUnsigned = "ANY_UNSIGNED",
        AnyBit = "ANY_BIT",
        AnyString = "ANY_STRING",
        AnyChars = "ANY_CHARS",
        AnyChar = "ANY_CHAR",
        AnyDate = "ANY_DATE",
        AnyDuration = "ANY_DURATION",
    }
}

word_enum! {
    /// Reserved keywords of Structured Text. Words that only mean something
    /// in one place (PRIORITY, ON, READ_ONLY, the SFC and object-oriented
    /// words) stay identifiers and are recognised by the parser in context,
    /// so real code may use them as names.
    Keyword {
        And = "AND",
        Array = "ARRAY",
        At = "AT",
        By = "BY",
        Case = "CASE",
        Configuration = "CONFIGURATION",
        Constant = "CONSTANT",
        Continue = "CONTINUE",
        Do = "DO",
        Else = "ELSE",
        Elsif = "ELSIF",
        EndCase = "END_CASE",
        EndConfiguration = "END_CONFIGURATION",
        EndFor = "END_FOR",
        EndFunction = "END_FUNCTION",
        EndFunctionBlock = "END_FUNCTION_BLOCK",
        EndIf = "END_IF",
        EndProgram = "END_PROGRAM",
        EndRepeat = "END_REPEAT",
        EndResource = "END_RESOURCE",
        EndStruct = "END_STRUCT",
        EndType = "END_TYPE",
        EndVar = "END_VAR",
        EndWhile = "END_WHILE",
        Exit = "EXIT",
        FEdge = "F_EDGE",
        False = "FALSE",
        For = "FOR",
        Function = "FUNCTION",
        FunctionBlock = "FUNCTION_BLOCK",
        If = "IF",
        Mod = "MOD",
        NonRetain = "NON_RETAIN",
        Not = "NOT",
        Of = "OF",
        Or = "OR",
        Program = "PROGRAM",
        REdge = "R_EDGE",
        Repeat = "REPEAT",
        Resource = "RESOURCE",
        Retain = "RETAIN",
        Return = "RETURN",
        Struct = "STRUCT",
        Task = "TASK",
        Then = "THEN",
        To = "TO",
        True = "TRUE",
        Type = "TYPE",
        Until = "UNTIL",
        Var = "VAR",
        VarAccess = "VAR_ACCESS",
        VarConfig = "VAR_CONFIG",
        VarExternal = "VAR_EXTERNAL",
        VarGlobal = "VAR_GLOBAL",
        VarInOut = "VAR_IN_OUT",
        VarInput = "VAR_INPUT",
        VarOutput = "VAR_OUTPUT",
        VarTemp = "VAR_TEMP",
        While = "WHILE",
        With = "WITH",
        Xor = "XOR",
    }
}

impl Keyword {
    pub fn text(self) -> &'static str {
        self.name()
    }
}

impl ElemType {
    /// The prefixes that start a duration/date/time literal (`T#`, `DT#`...)
    /// and the literal kind each starts.
    pub fn time_literal_prefix(upper: &[u8]) -> Option<TokenKind> {
        Some(match upper {
            b"T" | b"TIME" | b"LT" | b"LTIME" => TokenKind::Duration,
            b"D" | b"DATE" | b"LD" | b"LDATE" => TokenKind::Date,
            b"TOD" | b"TIME_OF_DAY" | b"LTOD" | b"LTIME_OF_DAY" => TokenKind::Tod,
            b"DT" | b"DATE_AND_TIME" | b"LDT" | b"LDATE_AND_TIME" => TokenKind::Dt,
            _ => return None,
        })
    }
}

/// Classifies an identifier-shaped word (given in upper case).
///
/// Every identifier of a source goes through here, so the reserved words sit
/// in a small open-addressing table built once: one hash and usually one
/// comparison per word.
pub fn classify_word(upper: &[u8]) -> TokenKind {
    const MAX_WORD: usize = 18;
    // The longest reserved word is END_CONFIGURATION / END_FUNCTION_BLOCK.
    if upper.len() > MAX_WORD {
        return TokenKind::Ident;
    }
    let table = word_table();
    let mut i = word_hash(upper) & (WORD_TABLE_SIZE - 1);
    loop {
        match &table[i] {
            None => return TokenKind::Ident,
            Some((w, k)) if w.as_bytes() == upper => return *k,
            Some(_) => i = (i + 1) & (WORD_TABLE_SIZE - 1),
        }
    }
}

const WORD_TABLE_SIZE: usize = 512;

fn word_hash(w: &[u8]) -> usize {
    // FNV-1a: short keys, no setup cost.
    let mut h: u32 = 0x811c_9dc5;
    for &b in w {
        h ^= b as u32;
        h = h.wrapping_mul(0x0100_0193);
    }
    h as usize
}

type WordTable = [Option<(&'static str, TokenKind)>; WORD_TABLE_SIZE];

fn word_table() -> &'static WordTable {
    static TABLE: std::sync::OnceLock<Box<WordTable>> = std::sync::OnceLock::new();
    TABLE.get_or_init(|| {
        let mut t: Box<WordTable> = Box::new([None; WORD_TABLE_SIZE]);
        let words = Keyword::SPELLINGS
            .iter()
            .map(|&(s, k)| (s, TokenKind::Kw(k)))
            .chain(
                ElemType::SPELLINGS
                    .iter()
                    .map(|&(s, k)| (s, TokenKind::Elem(k))),
            )
            .chain(
                GenericType::SPELLINGS
                    .iter()
                    .map(|&(s, k)| (s, TokenKind::Generic(k))),
            );
        for (s, k) in words {
            let mut i = word_hash(s.as_bytes()) & (WORD_TABLE_SIZE - 1);
            while t[i].is_some() {
                i = (i + 1) & (WORD_TABLE_SIZE - 1);
            }
            t[i] = Some((s, k));
        }
        t
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The codes are dense and in the order of `ALL` (type tables put the
    /// elementary types at `first + code`), and read back.
    #[test]
    fn elem_codes_are_dense_and_read_back() {
        for (i, &e) in ElemType::ALL.iter().enumerate() {
            assert_eq!(usize::from(e.code()), i, "{e:?}");
            assert_eq!(ElemType::from_code(e.code()), Some(e));
        }
        assert_eq!(ElemType::from_code(ElemType::ALL.len() as u8), None);
        assert_eq!(ElemType::from_code(u8::MAX), None);
    }

    #[test]
    fn words_classify_by_upper_case_spelling() {
        assert_eq!(classify_word(b"END_IF"), TokenKind::Kw(Keyword::EndIf));
        assert_eq!(
            classify_word(b"TIME_OF_DAY"),
            TokenKind::Elem(ElemType::Tod)
        );
        assert_eq!(
            classify_word(b"ANY_NUM"),
            TokenKind::Generic(GenericType::AnyNum)
        );
        assert_eq!(classify_word(b"MAX"), TokenKind::Ident);
        assert_eq!(classify_word(b"PRIORITY"), TokenKind::Ident);
        for k in Keyword::ALL {
            assert_eq!(classify_word(k.name().as_bytes()), TokenKind::Kw(*k));
        }
    }
}
