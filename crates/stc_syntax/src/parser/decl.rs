//! Declarations: POUs, variable sections, types, initial values,
//! configurations, resources and tasks.

use stc_diagnostics::{Code, Diagnostic, Span};

use super::{is_item_end, is_item_start, is_var_block_start, Parser};
use crate::ast::{
    Access, AccessDecl, AccessDirection, ArrayDim, ArrayInitElem, ClassKind, ConfigInit,
    Configuration, Edge, EnumMember, Init, InitKind, Item, Located, Method, Pou, PouKind,
    ProgramConfig, ProgramConn, PropertyPart, Resource, Retention, SfcBody, StructInitElem,
    TaskDecl, TypeDecl, TypeSpec, TypeSpecKind, VarBlock, VarBlockItems, VarDecl, VarKind,
};
use crate::literal;
use crate::token::{ElemType, Keyword, TokenKind};

/// Instruction List operators, to recognise an IL body.
const IL_OPERATORS: &[&str] = &[
    "LD", "LDN", "ST", "STN", "S", "R", "S1", "R1", "CLK", "CU", "CD", "PV", "IN", "PT", "ANDN",
    "ORN", "XORN", "ADD", "SUB", "MUL", "DIV", "GT", "GE", "EQ", "NE", "LE", "LT", "JMP", "JMPC",
    "JMPCN", "CAL", "CALC", "CALCN", "RET", "RETC", "RETCN",
];

fn class_word(c: ClassKind) -> &'static str {
    match c {
        ClassKind::Class => "CLASS",
        ClassKind::Interface => "INTERFACE",
    }
}

fn pou_end(kind: PouKind) -> Keyword {
    match kind {
        PouKind::Function => Keyword::EndFunction,
        PouKind::FunctionBlock => Keyword::EndFunctionBlock,
        PouKind::Program => Keyword::EndProgram,
    }
}

fn var_kind(k: TokenKind) -> Option<VarKind> {
    Some(match k {
        TokenKind::Kw(Keyword::Var) => VarKind::Var,
        TokenKind::Kw(Keyword::VarInput) => VarKind::Input,
        TokenKind::Kw(Keyword::VarOutput) => VarKind::Output,
        TokenKind::Kw(Keyword::VarInOut) => VarKind::InOut,
        TokenKind::Kw(Keyword::VarExternal) => VarKind::External,
        TokenKind::Kw(Keyword::VarGlobal) => VarKind::Global,
        TokenKind::Kw(Keyword::VarTemp) => VarKind::Temp,
        TokenKind::Kw(Keyword::VarAccess) => VarKind::Access,
        TokenKind::Kw(Keyword::VarConfig) => VarKind::Config,
        _ => return None,
    })
}

/// Where skipping a bad declaration stops (without consuming).
fn decl_sync(k: TokenKind) -> bool {
    matches!(
        k,
        TokenKind::Eof | TokenKind::Kw(Keyword::EndVar | Keyword::EndStruct | Keyword::EndType)
    ) || is_item_start(k)
        || is_item_end(k)
        || is_var_block_start(k)
}

impl Parser<'_> {
    /// Skips the rest of a bad declaration, up to and including its `;`.
    fn skip_decl(&mut self) {
        while !decl_sync(self.kind()) {
            if self.bump().kind == TokenKind::Semi {
                return;
            }
        }
    }

    fn expect_decl_semi(&mut self) {
        if self.eat(TokenKind::Semi) {
            return;
        }
        if self.at_kw(Keyword::EndType) && self.prev().kind == TokenKind::Kw(Keyword::EndStruct) {
            // `END_STRUCT END_TYPE`: CODESYS and TwinCAT write no `;` there.
            let end = self.prev();
            let d = Diagnostic::new(Code::W0004, end.span(), "missing `;` after `END_STRUCT`")
                .with_label("`;` expected after this")
                .with_help("add `;`: IEC 61131-3 ends every type declaration with it");
            self.report_always(d);
            return;
        }
        if matches!(
            self.kind(),
            TokenKind::Kw(Keyword::EndType | Keyword::EndVar | Keyword::EndStruct)
        ) {
            self.missing_semi_before_end();
            return;
        }
        if self.newline_between(self.prev(), self.tok()) {
            // The `;` is missing at the end of a line: the next line is a
            // declaration of its own, read as one (skipping it would lose
            // it, and every use of it would be an error).
            if !self.after_unterminated_string() {
                let prev = self.prev().span().shrink_to_hi();
                let d = Diagnostic::new(
                    Code::E0020,
                    self.tok().span(),
                    format!("expected `;`, found {}", self.describe_current()),
                )
                .with_label("expected `;`")
                .with_secondary(prev, "the declaration before needs a `;` here");
                self.report(d);
            }
            return;
        }
        self.expected("`;`");
        self.skip_decl();
    }

    // ----- POUs -----------------------------------------------------------

    pub(crate) fn pou(&mut self, kind: PouKind, pragmas: Vec<Span>) -> Option<Pou> {
        self.pou_of(kind, None, pragmas)
    }

    /// A POU; `class` for a CLASS or an INTERFACE (kept as a POU of kind
    /// FUNCTION_BLOCK), whose opening and closing words are identifiers.
    pub(crate) fn pou_of(
        &mut self,
        kind: PouKind,
        class: Option<ClassKind>,
        pragmas: Vec<Span>,
    ) -> Option<Pou> {
        let opener = self.bump().span();
        let (mut is_abstract, mut is_final, mut internal) = (false, false, false);
        for modifier in [
            "ABSTRACT",
            "FINAL",
            "PUBLIC",
            "PRIVATE",
            "PROTECTED",
            "INTERNAL",
        ] {
            if self.at_word(modifier) && self.nth_kind(1) == TokenKind::Ident {
                let span = self.bump().span();
                match modifier {
                    "ABSTRACT" if kind == PouKind::FunctionBlock => is_abstract = true,
                    "FINAL" if kind == PouKind::FunctionBlock => is_final = true,
                    // A namespace's element is PUBLIC unless INTERNAL.
                    "INTERNAL" => internal = true,
                    "PUBLIC" => {}
                    _ => self.unsupported(span, "access modifiers of a POU are"),
                }
            }
        }
        let Some(name) = self.name("a name") else {
            self.skip_to_item();
            return None;
        };
        let mut usings = Vec::new();
        self.usings_into(&mut usings);
        self.pou_partial = false;
        self.pou_skipped.clear();
        self.late_methods.clear();
        self.pou_kind = Some(kind);
        let mut extends = None;
        let mut implements = Vec::new();
        if kind == PouKind::FunctionBlock {
            // `EXTENDS Base` names one base (an INTERFACE: a list),
            // `IMPLEMENTS I1, I2` a list: what follows is the POU's first
            // member. A qualified name keeps its last part.
            let interface = class == Some(ClassKind::Interface);
            for word in ["EXTENDS", "IMPLEMENTS"] {
                if self.at_word(word) {
                    let kw = self.bump().span();
                    if interface && word == "IMPLEMENTS" {
                        let d = Diagnostic::new(
                            Code::E1317,
                            kw,
                            "an INTERFACE implements nothing: it EXTENDS other interfaces",
                        )
                        .with_label("IMPLEMENTS in an INTERFACE");
                        self.report(d);
                    }
                    loop {
                        if self.kind() != TokenKind::Ident {
                            self.expected("a type name");
                            break;
                        }
                        let Some(id) = self.qualified_name("a type name") else {
                            break;
                        };
                        if word == "EXTENDS" && !interface {
                            extends = Some(id);
                            break;
                        }
                        implements.push(id);
                        if !self.eat(TokenKind::Comma) {
                            break;
                        }
                    }
                }
            }
        }
        let return_type = if kind == PouKind::Function && self.eat(TokenKind::Colon) {
            Some(self.type_spec())
        } else {
            None
        };
        self.usings_into(&mut usings);
        let mut var_blocks = Vec::new();
        self.var_blocks_into(&mut var_blocks);
        let mut methods = Vec::new();
        if kind == PouKind::FunctionBlock {
            while !self.aborted
                && (self.at_word("METHOD") || self.at_word("PROPERTY"))
                && self.nth_kind(1) == TokenKind::Ident
            {
                if self.at_word("PROPERTY") {
                    let mut parts = self.property();
                    methods.append(&mut parts);
                } else if let Some(m) = self.method() {
                    methods.push(m);
                }
                while self.eat(TokenKind::Semi) {}
            }
        }
        let mut body = Vec::new();
        let mut il = None;
        let mut sfc = None;
        if let Some(class) = class {
            // No body: what stands before the END word is reported once and
            // skipped.
            let end = if class == ClassKind::Class {
                "END_CLASS"
            } else {
                "END_INTERFACE"
            };
            if !self.at_word(end) && !self.at(TokenKind::Eof) {
                let start = self.tok().span();
                let what = if class == ClassKind::Class {
                    "a CLASS has no body: only variables and methods"
                } else {
                    "an INTERFACE has only METHOD prototypes"
                };
                let d = Diagnostic::new(Code::E1318, start, what)
                    .with_label("not a variable section or a METHOD")
                    .with_secondary(opener, format!("in this {}", class_word(class)));
                self.report(d);
                while !self.at(TokenKind::Eof) && !self.at_word(end) && !is_item_start(self.kind())
                {
                    self.bump();
                }
                self.pou_partial = true;
            }
            if self.at_word(end) {
                self.bump();
            } else {
                self.expected(&format!("`{end}`"));
            }
            return Some(Pou {
                kind,
                name,
                return_type,
                var_blocks,
                body,
                il,
                sfc,
                span: opener.to(self.prev().span()),
                pragmas,
                extends,
                implements,
                class: Some(class),
                skipped_members: std::mem::take(&mut self.pou_skipped),
                partial: std::mem::take(&mut self.pou_partial),
                methods,
                is_abstract,
                is_final,
                internal,
                usings,
            });
        }
        if self.at_sfc_body() {
            let (chart, meaning) = self.sfc_body(kind, &mut var_blocks);
            sfc = Some(chart);
            body = meaning;
            if kind == PouKind::Function {
                // E1201: the chart has no meaning; say nothing more.
                self.pou_partial = true;
            }
            if !self.at_kw(pou_end(kind))
                && !self.at(TokenKind::Eof)
                && !is_item_end(self.kind())
                && !is_item_start(self.kind())
                && !self.at_var_block_start()
            {
                // Statements after the chart: one E0030, skipped.
                let span = self.tok().span();
                self.unsupported(
                    span,
                    "Structured Text statements after a Sequential Function Chart are",
                );
                self.pou_partial = true;
                while !self.at(TokenKind::Eof)
                    && !is_item_end(self.kind())
                    && !is_item_start(self.kind())
                {
                    self.bump();
                }
                self.superseded.push(span.to(self.prev().span()));
            }
        } else if self.at_il_body() {
            il = Some(self.il_body());
        } else {
            body = self.stmt_list(false);
        }
        // The END keyword; what else stands here is reported and skipped.
        let end = pou_end(kind);
        loop {
            if self.eat_kw(end) || self.aborted {
                break;
            }
            let k = self.kind();
            if self.at_var_block_start() {
                let d = Diagnostic::new(
                    Code::E0020,
                    self.tok().span(),
                    "variable sections must come before the statements of the body",
                );
                self.report(d);
                if let Some(b) = self.var_block() {
                    // Before the blocks a chart's meaning declares.
                    let at =
                        var_blocks.len() - sfc.as_ref().map_or(0, |s: &SfcBody| s.generated_blocks);
                    var_blocks.insert(at, b);
                }
                body.extend(self.stmt_list(false));
                continue;
            }
            let found = self.describe_current();
            let code = match k {
                TokenKind::Kw(kw) if kw.name().starts_with("END_") => Code::E0021,
                _ => Code::E0020,
            };
            let d = Diagnostic::new(
                code,
                self.tok().span(),
                format!("expected `{}`, found {found}", end.name()),
            )
            .with_label(format!("expected `{}`", end.name()))
            .with_secondary(opener, format!("this {} is not closed", kind.keyword()));
            self.report(d);
            if k == TokenKind::Eof || is_item_start(k) || is_item_end(k) {
                break;
            }
            self.bump();
            self.eat(TokenKind::Semi);
            body.extend(self.stmt_list(false));
        }
        methods.append(&mut self.late_methods);
        self.pou_kind = None;
        Some(Pou {
            kind,
            name,
            return_type,
            var_blocks,
            body,
            il,
            sfc,
            span: opener.to(self.prev().span()),
            pragmas,
            extends,
            implements,
            class: None,
            skipped_members: std::mem::take(&mut self.pou_skipped),
            partial: std::mem::take(&mut self.pou_partial),
            methods,
            is_abstract,
            is_final,
            internal,
            usings,
        })
    }

    /// Variable sections (and stray `;`) up to what follows them.
    fn var_blocks_into(&mut self, var_blocks: &mut Vec<VarBlock>) {
        while !self.aborted {
            if self.at_var_block_start() {
                if let Some(b) = self.var_block() {
                    var_blocks.push(b);
                }
            } else if self.at(TokenKind::Semi) {
                self.bump();
            } else {
                break;
            }
        }
    }

    /// The words between METHOD or PROPERTY and its name: an access
    /// specifier, ABSTRACT, FINAL, OVERRIDE (each a modifier only when a
    /// name follows it).
    fn member_modifiers(&mut self) -> (Option<Access>, bool, bool, bool) {
        let mut access = None;
        let (mut is_abstract, mut is_final, mut is_override) = (false, false, false);
        while self.nth_kind(1) == TokenKind::Ident {
            let word = self.text_of(self.tok()).to_ascii_uppercase();
            match word.as_str() {
                "PUBLIC" => access = Some(Access::Public),
                "PRIVATE" => access = Some(Access::Private),
                "PROTECTED" => access = Some(Access::Protected),
                "INTERNAL" => access = Some(Access::Internal),
                "ABSTRACT" => is_abstract = true,
                "FINAL" => is_final = true,
                "OVERRIDE" => is_override = true,
                _ => break,
            }
            self.bump();
        }
        (access, is_abstract, is_final, is_override)
    }

    /// `METHOD [modifiers] name [: type] variables body END_METHOD`.
    pub(crate) fn method(&mut self) -> Option<Method> {
        let opener = self.bump().span();
        let (access, is_abstract, is_final, is_override) = self.member_modifiers();
        let Some(name) = self.name("a method name") else {
            self.skip_unsupported("END_METHOD", |k| is_item_end(k) || is_item_start(k));
            return None;
        };
        let return_type = if self.eat(TokenKind::Colon) {
            Some(self.type_spec())
        } else {
            None
        };
        let mut var_blocks = Vec::new();
        self.var_blocks_into(&mut var_blocks);
        let outer = std::mem::replace(&mut self.in_method, true);
        let body = self.stmt_list(false);
        self.in_method = outer;
        if self.at_word("END_METHOD") {
            self.bump();
        } else {
            self.expected("`END_METHOD`");
        }
        let span = opener.to(self.prev().span());
        Some(Method {
            pou: method_pou(name, return_type, var_blocks, body, span),
            access,
            is_abstract,
            is_final,
            is_override,
            is_action: false,
            property: None,
        })
    }

    /// `PROPERTY [access] name : T`, then `GET [variables] statements
    /// END_GET` and/or `SET [variables] statements END_SET`, then
    /// `END_PROPERTY`: one method per accessor (see [`Method::property`]).
    pub(crate) fn property(&mut self) -> Vec<Method> {
        let opener = self.bump().span();
        let (access, is_abstract, is_final, is_override) = self.member_modifiers();
        let Some(name) = self.name("a property name") else {
            self.skip_unsupported("END_PROPERTY", |k| is_item_end(k) || is_item_start(k));
            return Vec::new();
        };
        let ty = if self.eat(TokenKind::Colon) {
            self.type_spec()
        } else {
            self.expected("`:` and the property's type");
            TypeSpec {
                kind: TypeSpecKind::Error,
                span: name.span,
            }
        };
        let mut out = Vec::new();
        loop {
            while self.eat(TokenKind::Semi) {}
            let part = if self.at_word("GET") {
                PropertyPart::Get
            } else if self.at_word("SET") {
                PropertyPart::Set
            } else {
                break;
            };
            let start = self.bump().span();
            let end_word = if part == PropertyPart::Get {
                "END_GET"
            } else {
                "END_SET"
            };
            let mut var_blocks = Vec::new();
            if part == PropertyPart::Set {
                // The value being set, under the property's name.
                let decl = VarDecl {
                    names: vec![name],
                    location: None,
                    ty: ty.clone(),
                    edge: None,
                    init: None,
                    span: name.span,
                    pragmas: Vec::new(),
                };
                var_blocks.push(VarBlock {
                    kind: VarKind::Input,
                    access: None,
                    constant: false,
                    retention: None,
                    items: VarBlockItems::Vars(vec![decl]),
                    span: name.span,
                });
            }
            self.var_blocks_into(&mut var_blocks);
            let outer = std::mem::replace(&mut self.in_method, true);
            let outer_property = std::mem::replace(&mut self.in_property, true);
            let body = self.stmt_list(false);
            self.in_method = outer;
            self.in_property = outer_property;
            if self.at_word(end_word) {
                self.bump();
            } else {
                self.expected(&format!("`{end_word}`"));
            }
            let span = start.to(self.prev().span());
            let pou_name = match part {
                PropertyPart::Get => name,
                PropertyPart::Set => {
                    let key = format!("{}.SET", self.interner.spelling(name.sym).to_owned());
                    crate::ast::Ident {
                        sym: self.interner.intern(&key),
                        span: name.span,
                    }
                }
            };
            let return_type = (part == PropertyPart::Get).then(|| ty.clone());
            out.push(Method {
                pou: method_pou(pou_name, return_type, var_blocks, body, span),
                access,
                is_abstract,
                is_final,
                is_override,
                is_action: false,
                property: Some((part, name)),
            });
        }
        if self.at_word("END_PROPERTY") {
            self.bump();
        } else {
            self.expected("`GET`, `SET` or `END_PROPERTY`");
            self.skip_unsupported("END_PROPERTY", |k| is_item_end(k) || is_item_start(k));
        }
        if out.is_empty() {
            let span = opener.to(self.prev().span());
            self.report(
                Diagnostic::new(Code::E0020, span, "a PROPERTY needs a GET or a SET")
                    .with_label("no accessor"),
            );
        }
        out
    }

    /// `ACTION name [:] statements END_ACTION` after the body of a function
    /// block: a method without variables or result.
    pub(crate) fn action(&mut self) -> Option<Method> {
        let opener = self.bump().span();
        let Some(name) = self.name("an action name") else {
            self.skip_unsupported("END_ACTION", |k| is_item_end(k) || is_item_start(k));
            return None;
        };
        self.eat(TokenKind::Colon);
        let outer = std::mem::replace(&mut self.in_action, true);
        let body = self.stmt_list(false);
        self.in_action = outer;
        if self.at_word("END_ACTION") {
            self.bump();
        } else {
            self.expected("`END_ACTION`");
        }
        let span = opener.to(self.prev().span());
        Some(Method {
            pou: method_pou(name, None, Vec::new(), body, span),
            access: None,
            is_abstract: false,
            is_final: false,
            is_override: false,
            is_action: true,
            property: None,
        })
    }

    /// A variable section starts here: a VAR keyword, or the dialect
    /// sections VAR_STAT and VAR_INST (CODESYS).
    pub(crate) fn at_var_block_start(&self) -> bool {
        is_var_block_start(self.kind())
            || (self.at_word("VAR_STAT") || self.at_word("VAR_INST"))
                && !matches!(
                    self.nth_kind(1),
                    TokenKind::Assign | TokenKind::LParen | TokenKind::Dot | TokenKind::LBracket
                )
    }

    /// An IL body that starts with a formal call, `foo(\n a := 1\n)` with
    /// no `;` after the `)` and an IL operator with its operand on the next
    /// line (`ST x`), where ST would need the `;`.
    fn il_formal_call_first(&self) -> bool {
        let mut depth = 0usize;
        for n in 1..4096 {
            match self.nth_kind(n) {
                TokenKind::LParen => depth += 1,
                TokenKind::RParen => {
                    depth -= 1;
                    if depth == 0 {
                        let (close, op, operand) = (self.nth(n), self.nth(n + 1), self.nth(n + 2));
                        // The operator: a word of IL, or one of the
                        // operators ST reserves (AND OR XOR NOT MOD, `&`).
                        let il_word = match op.kind {
                            TokenKind::Ident => IL_OPERATORS
                                .iter()
                                .any(|w| w.eq_ignore_ascii_case(self.text_of(op))),
                            TokenKind::Amp
                            | TokenKind::Kw(
                                Keyword::And
                                | Keyword::Or
                                | Keyword::Xor
                                | Keyword::Not
                                | Keyword::Mod,
                            ) => true,
                            _ => false,
                        };
                        // Its operand on its line: a name, a literal, a
                        // typed literal, or the `(` of a sequence; NOT and
                        // RET stand alone.
                        let alone = op.kind == TokenKind::Kw(Keyword::Not)
                            || self.text_of(op).eq_ignore_ascii_case("RET");
                        return il_word
                            && self.newline_between(close, op)
                            && (if self.newline_between(op, operand) {
                                alone
                            } else {
                                matches!(
                                    operand.kind,
                                    TokenKind::Ident
                                        | TokenKind::Int
                                        | TokenKind::BasedInt
                                        | TokenKind::Real
                                        | TokenKind::Duration
                                        | TokenKind::Address
                                        | TokenKind::SString
                                        | TokenKind::WString
                                        | TokenKind::Elem(_)
                                        | TokenKind::Kw(Keyword::True | Keyword::False)
                                        | TokenKind::LParen
                                )
                            });
                    }
                }
                TokenKind::Eof | TokenKind::Semi => return false,
                _ => {}
            }
        }
        false
    }

    /// Whether the body that starts here is Instruction List: an IL operator
    /// with an operand, or a label, where ST would have `:=` or a call.
    pub(crate) fn at_il_body(&self) -> bool {
        match self.kind() {
            // `& x`, `&N x`: AND in IL; no ST statement starts with `&`.
            TokenKind::Amp => true,
            TokenKind::Kw(
                Keyword::And | Keyword::Or | Keyword::Xor | Keyword::Not | Keyword::Mod,
            ) => !matches!(self.nth_kind(1), TokenKind::LParen),
            TokenKind::Ident => {
                let word = self.text_of(self.tok());
                let next = self.nth_kind(1);
                if next == TokenKind::Colon {
                    return true;
                }
                if next == TokenKind::LParen && self.il_formal_call_first() {
                    return true;
                }
                let il_operator = IL_OPERATORS.iter().any(|op| op.eq_ignore_ascii_case(word))
                    && !matches!(
                        next,
                        TokenKind::Assign
                            | TokenKind::Dot
                            | TokenKind::LBracket
                            | TokenKind::LParen
                            | TokenKind::Semi
                            | TokenKind::Arrow
                            | TokenKind::QuestionAssign
                            | TokenKind::Caret
                    );
                // A name with an operand after it on the same line, where ST
                // needs `:=` or `(`: an IL call of a function (`Scale 10`).
                let ref_assign = self.nth_is_word(1, "REF") && self.nth_kind(2) == TokenKind::Eq;
                // Words that start another unsupported part of a body.
                let other = [
                    "METHOD",
                    "PROPERTY",
                    "ACTION",
                    "STEP",
                    "INITIAL_STEP",
                    "TRANSITION",
                ]
                .iter()
                .any(|w| w.eq_ignore_ascii_case(word));
                let il_call = !self.newline_between(self.tok(), self.nth(1))
                    && !ref_assign
                    && !other
                    && matches!(
                        next,
                        TokenKind::Ident
                            | TokenKind::Int
                            | TokenKind::BasedInt
                            | TokenKind::Real
                            | TokenKind::SString
                            | TokenKind::WString
                            | TokenKind::Duration
                            | TokenKind::Date
                            | TokenKind::Tod
                            | TokenKind::Dt
                            | TokenKind::Address
                            | TokenKind::Kw(Keyword::True | Keyword::False)
                    );
                il_operator || il_call
            }
            _ => false,
        }
    }

    // ----- variable sections ----------------------------------------------

    pub(crate) fn var_block(&mut self) -> Option<VarBlock> {
        let start = self.tok();
        let kind = if self.at_word("VAR_STAT") {
            VarKind::Stat
        } else if self.at_word("VAR_INST") {
            VarKind::Inst
        } else {
            var_kind(start.kind)?
        };
        self.bump();
        let mut constant = false;
        let mut retention = None;
        let mut access = None;
        loop {
            // `VAR NON_RETAIN : INT;`: a qualifier word followed by `:` or
            // `,` is a variable (E0022 at its declaration), not a qualifier
            // (`VAR RETAIN AT %QW1 : WORD;` is the qualifier and an unnamed
            // located variable).
            if matches!(self.nth_kind(1), TokenKind::Colon | TokenKind::Comma) {
                break;
            }
            let word = self.text_of(self.tok()).to_ascii_uppercase();
            let spec = match word.as_str() {
                "PUBLIC" => Some(Access::Public),
                "PRIVATE" => Some(Access::Private),
                "PROTECTED" => Some(Access::Protected),
                "INTERNAL" => Some(Access::Internal),
                _ => None,
            };
            if spec.is_some() && self.at(TokenKind::Ident) {
                self.bump();
                access = spec;
            } else if self.eat_kw(Keyword::Constant) {
                constant = true;
            } else if self.eat_kw(Keyword::Retain) {
                retention = Some(Retention::Retain);
            } else if self.eat_kw(Keyword::NonRetain) {
                retention = Some(Retention::NonRetain);
            } else if self.at_word("PERSISTENT") {
                // CODESYS's `VAR PERSISTENT` / `VAR RETAIN PERSISTENT`:
                // kept across restarts like RETAIN (docs/runtime.md says
                // what of CODESYS's meaning is not kept).
                self.bump();
                retention = Some(Retention::Retain);
            } else {
                break;
            }
        }
        let items = match kind {
            VarKind::Access => VarBlockItems::Access(self.decl_list(Self::access_decl)),
            VarKind::Config => VarBlockItems::Config(self.decl_list(Self::config_init)),
            _ => VarBlockItems::Vars(self.decl_list(|p| p.var_decl())),
        };
        if !self.eat_kw(Keyword::EndVar) {
            self.expected("`END_VAR`");
        }
        Some(VarBlock {
            kind,
            access,
            constant,
            retention,
            items,
            span: start.span().to(self.prev().span()),
        })
    }

    /// Declarations until END_VAR (or END_STRUCT), each parsed by `f`.
    fn decl_list<T>(&mut self, mut f: impl FnMut(&mut Self) -> Option<T>) -> Vec<T> {
        let mut out = Vec::new();
        while !self.aborted && !decl_sync(self.kind()) {
            if !self.at_decl_start() {
                // Most likely END_VAR is missing and the body begins here.
                break;
            }
            let before = self.pos;
            if let Some(d) = f(self) {
                out.push(d);
            }
            if self.pos == before {
                self.bump();
            }
        }
        out
    }

    /// A declaration starts with a name followed by `,`, `:`, AT or `.`
    /// (VAR_CONFIG paths), or with AT.
    fn at_decl_start(&self) -> bool {
        match self.kind() {
            TokenKind::Kw(Keyword::At) => true,
            // A name followed by a type (`enable BOOL;`) is a declaration
            // that lacks its colon.
            TokenKind::Ident => matches!(
                self.nth_kind(1),
                TokenKind::Colon
                    | TokenKind::Comma
                    | TokenKind::Dot
                    | TokenKind::Ident
                    | TokenKind::Elem(_)
                    | TokenKind::Kw(Keyword::At | Keyword::Array | Keyword::Struct)
            ),
            k if k.is_reserved_word() => {
                matches!(self.nth_kind(1), TokenKind::Colon | TokenKind::Comma)
            }
            _ => false,
        }
    }

    fn location(&mut self) -> Option<Located> {
        let t = self.tok();
        if t.kind != TokenKind::Address {
            self.expected("a direct address such as %IX0.0");
            return None;
        }
        self.bump();
        match literal::parse_address(self.text_of(t)) {
            Ok(address) => Some(Located {
                address,
                span: t.span(),
            }),
            Err(e) => {
                self.report_always(Diagnostic::new(e.code, t.span(), e.message));
                None
            }
        }
    }

    /// `a, b AT %IX0.0 : T R_EDGE := init;` (in a STRUCT: `member : T := init;`).
    pub(crate) fn var_decl(&mut self) -> Option<VarDecl> {
        let start = self.tok().span();
        let pragmas = self.take_pragmas(start.lo);
        let mut names = Vec::new();
        if !self.at_kw(Keyword::At) {
            loop {
                match self.name("a variable name") {
                    Some(n) => names.push(n),
                    None => {
                        self.skip_decl();
                        return None;
                    }
                }
                if !self.eat(TokenKind::Comma) {
                    break;
                }
            }
        }
        let mut location = None;
        if self.eat_kw(Keyword::At) {
            location = self.location();
            if location.is_none() {
                self.skip_decl();
                return None;
            }
        }
        if !self.expect(TokenKind::Colon)
            && !matches!(
                self.kind(),
                TokenKind::Ident
                    | TokenKind::Elem(_)
                    | TokenKind::Kw(Keyword::Array | Keyword::Struct)
            )
        {
            self.skip_decl();
            return None;
        }
        let ty = self.type_spec();
        let edge = if self.eat_kw(Keyword::REdge) {
            Some(Edge::Rising)
        } else if self.eat_kw(Keyword::FEdge) {
            Some(Edge::Falling)
        } else {
            None
        };
        let init = if self.eat(TokenKind::Assign) {
            Some(self.decl_init(&ty))
        } else {
            None
        };
        let span = start.to(self.prev().span());
        self.expect_decl_semi();
        Some(VarDecl {
            names,
            location,
            ty,
            edge,
            init,
            span,
            pragmas,
        })
    }

    /// `name : path : TYPE [READ_ONLY|READ_WRITE];`
    fn access_decl(&mut self) -> Option<AccessDecl> {
        let start = self.tok().span();
        let Some(name) = self.name("an access name") else {
            self.skip_decl();
            return None;
        };
        if !self.expect(TokenKind::Colon) {
            self.skip_decl();
            return None;
        }
        // `RES.%IX1.0`: a direct variable of a named resource.
        let mut resource = None;
        if self.at(TokenKind::Ident)
            && self.nth_kind(1) == TokenKind::Dot
            && self.nth_kind(2) == TokenKind::Address
        {
            resource = self.name("a resource name");
            self.bump();
        }
        let path = self.postfix();
        if !self.expect(TokenKind::Colon) {
            self.skip_decl();
            return None;
        }
        let ty = self.type_spec();
        let direction = if self.at_word("READ_ONLY") {
            self.bump();
            Some(AccessDirection::ReadOnly)
        } else if self.at_word("READ_WRITE") {
            self.bump();
            Some(AccessDirection::ReadWrite)
        } else {
            None
        };
        let span = start.to(self.prev().span());
        self.expect_decl_semi();
        Some(AccessDecl {
            name,
            resource,
            path,
            ty,
            direction,
            span,
        })
    }

    /// `res.prog.inst.var [AT %QX0.0] : TYPE [:= init];`
    fn config_init(&mut self) -> Option<ConfigInit> {
        let start = self.tok().span();
        let mut path = Vec::new();
        loop {
            match self.name("a variable path") {
                Some(n) => path.push(n),
                None => {
                    self.skip_decl();
                    return None;
                }
            }
            if !self.eat(TokenKind::Dot) {
                break;
            }
        }
        let location = if self.eat_kw(Keyword::At) {
            self.location()
        } else {
            None
        };
        if !self.expect(TokenKind::Colon) {
            self.skip_decl();
            return None;
        }
        let ty = self.type_spec();
        let init = if self.eat(TokenKind::Assign) {
            Some(self.decl_init(&ty))
        } else {
            None
        };
        let span = start.to(self.prev().span());
        self.expect_decl_semi();
        Some(ConfigInit {
            path,
            location,
            ty,
            init,
            span,
        })
    }

    // ----- types ------------------------------------------------------------

    pub(crate) fn type_spec(&mut self) -> TypeSpec {
        let t = self.tok();
        if !self.enter() {
            return TypeSpec {
                kind: TypeSpecKind::Error,
                span: t.span(),
            };
        }
        let kind = self.type_spec_kind();
        self.leave();
        TypeSpec {
            kind,
            span: t.span().to(self.prev().span()),
        }
    }

    fn type_spec_kind(&mut self) -> TypeSpecKind {
        let t = self.tok();
        match t.kind {
            TokenKind::Elem(e @ (ElemType::String | ElemType::Wstring)) => {
                self.bump();
                let wide = e == ElemType::Wstring;
                let close = match self.kind() {
                    TokenKind::LBracket => Some(TokenKind::RBracket),
                    TokenKind::LParen => Some(TokenKind::RParen),
                    _ => None,
                };
                let len = close.map(|close| {
                    self.bump();
                    let len = self.expr();
                    self.expect(close);
                    len
                });
                TypeSpecKind::String { wide, len }
            }
            TokenKind::Elem(e) => {
                self.bump();
                let base = TypeSpec {
                    kind: TypeSpecKind::Elementary(e),
                    span: t.span(),
                };
                if self.at(TokenKind::LParen) {
                    // `INT (0..100)` is a subrange, `INT (red := 1, ...)` an
                    // enumeration with named values and a base type.
                    let enum_like = self.nth_kind(1) == TokenKind::Ident
                        && matches!(
                            self.nth_kind(2),
                            TokenKind::Assign | TokenKind::Comma | TokenKind::RParen
                        );
                    if enum_like {
                        return match self.enum_spec() {
                            TypeSpecKind::Enum { values, .. } => TypeSpecKind::Enum {
                                values,
                                base: Some(Box::new(base)),
                            },
                            other => other,
                        };
                    }
                    return self.subrange(base);
                }
                base.kind
            }
            TokenKind::Generic(g) => {
                self.bump();
                TypeSpecKind::Generic(g)
            }
            TokenKind::Ident
                if self.at_word("POINTER") && self.nth_kind(1) == TokenKind::Kw(Keyword::To) =>
            {
                self.bump();
                self.bump();
                let target = self.type_spec();
                TypeSpecKind::Pointer(Box::new(target))
            }
            TokenKind::Ident
                if self.at_word("REFERENCE") && self.nth_kind(1) == TokenKind::Kw(Keyword::To) =>
            {
                let what = "`REFERENCE TO` (a CODESYS reference) is";
                self.bump();
                let to = self.bump();
                self.unsupported(t.span().to(to.span()), what);
                self.type_spec();
                TypeSpecKind::Error
            }
            TokenKind::Ident
                if self.at_word("REF_TO")
                    && matches!(
                        self.nth_kind(1),
                        TokenKind::Ident
                            | TokenKind::Elem(_)
                            | TokenKind::Kw(Keyword::Array | Keyword::Struct)
                    ) =>
            {
                self.bump();
                let target = self.type_spec();
                TypeSpecKind::Ref(Box::new(target))
            }
            // `UNION` followed by its first member (or its end), not a type
            // named Union.
            TokenKind::Ident
                if self.at_word("UNION")
                    && (self.nth_is_word(1, "END_UNION")
                        || self.nth_kind(1) == TokenKind::Ident
                            && matches!(self.nth_kind(2), TokenKind::Colon | TokenKind::Comma)) =>
            {
                self.bump();
                self.unsupported(t.span(), "UNION types are");
                // The members are declarations up to END_UNION.
                while !self.at(TokenKind::Eof)
                    && !self.at_word("END_UNION")
                    && !is_item_start(self.kind())
                    && !is_item_end(self.kind())
                    && !self.at_kw(Keyword::EndType)
                {
                    self.bump();
                }
                if self.at_word("END_UNION") {
                    self.bump();
                }
                TypeSpecKind::Error
            }
            TokenKind::Ident => match self.qualified_name("a type") {
                Some(name) => TypeSpecKind::Named(name),
                None => TypeSpecKind::Error,
            },
            TokenKind::LParen => self.enum_spec(),
            TokenKind::Kw(Keyword::Array) => self.array_spec(),
            TokenKind::Kw(Keyword::Struct) => {
                self.bump();
                let members = self.decl_list(|p| p.var_decl());
                if !self.eat_kw(Keyword::EndStruct) {
                    self.expected("`END_STRUCT`");
                }
                TypeSpecKind::Struct { members }
            }
            _ => {
                self.expected("a type");
                TypeSpecKind::Error
            }
        }
    }

    fn subrange(&mut self, base: TypeSpec) -> TypeSpecKind {
        self.bump(); // (
        let lo = self.expr();
        self.expect(TokenKind::DotDot);
        let hi = self.expr();
        self.expect(TokenKind::RParen);
        TypeSpecKind::Subrange {
            base: Box::new(base),
            lo,
            hi,
        }
    }

    fn enum_spec(&mut self) -> TypeSpecKind {
        self.bump(); // (
        let mut values = Vec::new();
        while let Some(name) = self.name("an enumeration value") {
            let value = if self.eat(TokenKind::Assign) {
                Some(self.expr())
            } else {
                None
            };
            values.push(EnumMember { name, value });
            if !self.eat(TokenKind::Comma) {
                break;
            }
        }
        self.expect(TokenKind::RParen);
        // A dialect form names the base type after the values: `(a, b) INT`.
        let base = match self.kind() {
            TokenKind::Elem(_) => Some(Box::new(self.type_spec())),
            _ => None,
        };
        TypeSpecKind::Enum { values, base }
    }

    fn array_spec(&mut self) -> TypeSpecKind {
        self.bump(); // ARRAY
        let mut dims = Vec::new();
        if self.expect(TokenKind::LBracket) {
            loop {
                if self.at(TokenKind::Star)
                    || self.at(TokenKind::DotDot)
                        && matches!(self.nth_kind(1), TokenKind::RBracket | TokenKind::Comma)
                {
                    // `*`, or `..` as logi.CAD writes it: a variable length.
                    let span = self.bump().span();
                    dims.push(ArrayDim::Star(span));
                } else {
                    let lo = self.expr();
                    self.expect(TokenKind::DotDot);
                    let hi = self.expr();
                    dims.push(ArrayDim::Range { lo, hi });
                }
                if !self.eat(TokenKind::Comma) {
                    break;
                }
            }
            self.expect(TokenKind::RBracket);
        }
        self.expect_kw(Keyword::Of);
        let elem = Box::new(self.type_spec());
        TypeSpecKind::Array { dims, elem }
    }

    // ----- initial values -------------------------------------------------

    pub(crate) fn init(&mut self) -> Init {
        let start = self.tok().span();
        if !self.enter() {
            let e = self.error_expr(start);
            return Init {
                kind: InitKind::Expr(e),
                span: start,
            };
        }
        let kind = if self.at(TokenKind::LBracket) {
            self.array_init()
        } else if self.at(TokenKind::LParen)
            && (self.nth_kind(1) == TokenKind::Ident || self.nth_kind(1).is_reserved_word())
            && self.nth_kind(2) == TokenKind::Assign
        {
            self.struct_init()
        } else {
            InitKind::Expr(self.expr())
        };
        self.leave();
        Init {
            kind,
            span: start.to(self.prev().span()),
        }
    }

    fn array_init(&mut self) -> InitKind {
        self.bump(); // [
        let elems = if self.at(TokenKind::RBracket) {
            Vec::new()
        } else {
            self.array_init_elems()
        };
        self.expect(TokenKind::RBracket);
        InitKind::Array(elems)
    }

    /// The initial value of a declaration of type `ty`. An array's values
    /// without brackets (`:= 2, 2, 3;`, CODESYS 2.3) are read as the
    /// bracketed list, with W0006.
    fn decl_init(&mut self, ty: &TypeSpec) -> Init {
        let is_array = matches!(ty.kind, TypeSpecKind::Array { .. });
        if !is_array || self.at(TokenKind::LBracket) {
            return self.init();
        }
        let start = self.tok().span();
        if !self.enter() {
            let e = self.error_expr(start);
            return Init {
                kind: InitKind::Expr(e),
                span: start,
            };
        }
        let mut elems = self.array_init_elems();
        self.leave();
        let span = start.to(self.prev().span());
        if elems.len() == 1 && elems[0].repeat.is_none() {
            // One value: an ordinary initial value (the analyser says
            // whether it fits an array).
            if let Some(value) = elems.pop().and_then(|e| e.values.into_iter().next()) {
                return value;
            }
        }
        let d = Diagnostic::new(Code::W0006, span, "array initial values without brackets")
            .with_label("read as `[...]`")
            .with_help("write the values in brackets: `:= [...]`");
        self.report_always(d);
        Init {
            kind: InitKind::Array(elems),
            span,
        }
    }

    /// The comma-separated elements of an array initial value, each a value
    /// or a repetition `n(values)`.
    fn array_init_elems(&mut self) -> Vec<ArrayInitElem> {
        let mut elems = Vec::new();
        {
            loop {
                let start = self.tok().span();
                if matches!(self.kind(), TokenKind::Int | TokenKind::BasedInt)
                    && self.nth_kind(1) == TokenKind::LParen
                {
                    let count = self.postfix_literal();
                    self.bump(); // (
                    let mut values = Vec::new();
                    if !self.at(TokenKind::RParen) {
                        loop {
                            values.push(self.init());
                            if !self.eat(TokenKind::Comma) || self.aborted {
                                break;
                            }
                        }
                    }
                    self.expect(TokenKind::RParen);
                    elems.push(ArrayInitElem {
                        repeat: Some(count),
                        values,
                        span: start.to(self.prev().span()),
                    });
                } else {
                    let value = self.init();
                    elems.push(ArrayInitElem {
                        repeat: None,
                        span: value.span,
                        values: vec![value],
                    });
                }
                if !self.eat(TokenKind::Comma) || self.aborted {
                    break;
                }
            }
        }
        elems
    }

    /// The repetition count of `3(0)`: just the integer literal.
    fn postfix_literal(&mut self) -> crate::ast::ExprId {
        let t = self.tok();
        let text = self.text_of(t);
        let value = if t.kind == TokenKind::Int {
            literal::parse_int(text)
        } else {
            literal::parse_based_int(text)
        };
        self.bump();
        match value {
            Ok(v) => self.mk(
                crate::ast::ExprKind::Literal(crate::ast::Literal {
                    value: crate::ast::LitValue::Int {
                        value: v,
                        negative: false,
                    },
                    prefix: None,
                }),
                t.span(),
                0,
            ),
            Err(e) => {
                self.report_always(Diagnostic::new(e.code, t.span(), e.message));
                self.error_expr(t.span())
            }
        }
    }

    fn struct_init(&mut self) -> InitKind {
        self.bump(); // (
        let mut elems = Vec::new();
        while let Some(name) = self.name_use("a member name") {
            self.expect(TokenKind::Assign);
            let value = self.init();
            elems.push(StructInitElem { name, value });
            if !self.eat(TokenKind::Comma) || self.aborted {
                break;
            }
        }
        self.expect(TokenKind::RParen);
        InitKind::Struct(elems)
    }

    // ----- TYPE blocks --------------------------------------------------------

    pub(crate) fn type_block(&mut self, pragmas: Vec<Span>) -> Option<Item> {
        let start = self.bump().span();
        let mut decls = Vec::new();
        let mut first_pragmas = Some(pragmas);
        while !self.aborted && !decl_sync(self.kind()) {
            let before = self.pos;
            let decl_start = self.tok().span();
            let mut pragmas = self.take_pragmas(decl_start.lo);
            if let Some(mut p) = first_pragmas.take() {
                p.append(&mut pragmas);
                pragmas = p;
            }
            if let Some(name) = self.name("a type name") {
                if self.expect(TokenKind::Colon) {
                    let spec = self.type_spec();
                    let init = if self.eat(TokenKind::Assign) {
                        Some(self.decl_init(&spec))
                    } else {
                        None
                    };
                    let span = decl_start.to(self.prev().span());
                    self.expect_decl_semi();
                    decls.push(TypeDecl {
                        name,
                        spec,
                        init,
                        span,
                        pragmas,
                    });
                } else {
                    self.skip_decl();
                }
            } else {
                self.skip_decl();
            }
            if self.pos == before {
                self.bump();
            }
        }
        if !self.eat_kw(Keyword::EndType) {
            self.expected("`END_TYPE`");
        }
        Some(Item::Types(decls, start.to(self.prev().span())))
    }

    // ----- configurations ---------------------------------------------------

    pub(crate) fn configuration(&mut self) -> Option<Configuration> {
        let opener = self.bump().span();
        let Some(name) = self.name("a configuration name") else {
            self.skip_to_item();
            return None;
        };
        let mut var_blocks = Vec::new();
        let mut resources = Vec::new();
        let mut implicit: Option<Resource> = None;
        loop {
            if self.aborted {
                break;
            }
            let t = self.tok();
            match t.kind {
                TokenKind::Kw(Keyword::EndConfiguration) => {
                    self.bump();
                    break;
                }
                k if is_var_block_start(k) => {
                    if let Some(b) = self.var_block() {
                        var_blocks.push(b);
                    }
                }
                TokenKind::Kw(Keyword::Resource) => {
                    if let Some(r) = self.resource() {
                        resources.push(r);
                    }
                }
                TokenKind::Kw(Keyword::Task) | TokenKind::Kw(Keyword::Program) => {
                    let r = implicit.get_or_insert_with(|| Resource {
                        name: None,
                        on: None,
                        var_blocks: Vec::new(),
                        tasks: Vec::new(),
                        programs: Vec::new(),
                        span: t.span(),
                    });
                    self.resource_element(r);
                    r.span = r.span.to(self.prev().span());
                }
                TokenKind::Semi => {
                    self.bump();
                }
                _ => {
                    let found = self.describe_current();
                    let code = if is_item_end(t.kind) {
                        Code::E0021
                    } else {
                        Code::E0020
                    };
                    let d = Diagnostic::new(
                        code,
                        t.span(),
                        format!("expected `END_CONFIGURATION`, found {found}"),
                    )
                    .with_label(
                        "expected RESOURCE, TASK, PROGRAM, a variable section or END_CONFIGURATION",
                    )
                    .with_secondary(opener, "this CONFIGURATION is not closed");
                    self.report(d);
                    if t.kind == TokenKind::Eof || is_item_start(t.kind) {
                        break;
                    }
                    self.bump();
                    self.skip_decl();
                }
            }
        }
        resources.extend(implicit);
        Some(Configuration {
            name,
            var_blocks,
            resources,
            span: opener.to(self.prev().span()),
        })
    }

    fn resource(&mut self) -> Option<Resource> {
        let opener = self.bump().span();
        let name = self.name("a resource name");
        let on = if self.at_word("ON") {
            self.bump();
            self.name("a resource type name")
        } else {
            self.expected("`ON`");
            None
        };
        let mut r = Resource {
            name,
            on,
            var_blocks: Vec::new(),
            tasks: Vec::new(),
            programs: Vec::new(),
            span: opener,
        };
        loop {
            if self.aborted {
                break;
            }
            let t = self.tok();
            match t.kind {
                TokenKind::Kw(Keyword::EndResource) => {
                    self.bump();
                    break;
                }
                k if is_var_block_start(k) => {
                    if let Some(b) = self.var_block() {
                        r.var_blocks.push(b);
                    }
                }
                TokenKind::Kw(Keyword::Task) | TokenKind::Kw(Keyword::Program) => {
                    self.resource_element(&mut r)
                }
                TokenKind::Semi => {
                    self.bump();
                }
                _ => {
                    let found = self.describe_current();
                    let code = if matches!(t.kind, TokenKind::Kw(Keyword::EndConfiguration))
                        || is_item_end(t.kind)
                    {
                        Code::E0021
                    } else {
                        Code::E0020
                    };
                    let d = Diagnostic::new(
                        code,
                        t.span(),
                        format!("expected `END_RESOURCE`, found {found}"),
                    )
                    .with_label("expected TASK, PROGRAM, VAR_GLOBAL or END_RESOURCE")
                    .with_secondary(opener, "this RESOURCE is not closed");
                    self.report(d);
                    if t.kind == TokenKind::Eof
                        || is_item_start(t.kind)
                        || matches!(
                            t.kind,
                            TokenKind::Kw(Keyword::EndConfiguration | Keyword::Resource)
                        )
                    {
                        break;
                    }
                    self.bump();
                    self.skip_decl();
                }
            }
        }
        r.span = opener.to(self.prev().span());
        Some(r)
    }

    /// A TASK or PROGRAM declaration inside a resource.
    fn resource_element(&mut self, r: &mut Resource) {
        if self.at_kw(Keyword::Task) {
            if let Some(t) = self.task() {
                r.tasks.push(t);
            }
        } else if let Some(p) = self.program_config() {
            r.programs.push(p);
        }
    }

    /// `TASK name (SINGLE := s, INTERVAL := t, PRIORITY := p);`
    fn task(&mut self) -> Option<TaskDecl> {
        let start = self.bump().span();
        let Some(name) = self.name("a task name") else {
            self.skip_decl();
            return None;
        };
        let mut task = TaskDecl {
            name,
            single: None,
            interval: None,
            priority: None,
            span: start,
        };
        if self.expect(TokenKind::LParen) {
            loop {
                if self.at(TokenKind::RParen) {
                    break;
                }
                let which = self.text_of(self.tok()).to_ascii_uppercase();
                if !matches!(which.as_str(), "SINGLE" | "INTERVAL" | "PRIORITY")
                    || self.kind() != TokenKind::Ident
                {
                    self.expected("SINGLE, INTERVAL or PRIORITY");
                    self.skip_decl();
                    return None;
                }
                self.bump();
                if !self.expect(TokenKind::Assign) {
                    self.skip_decl();
                    return None;
                }
                let value = self.expr();
                match which.as_str() {
                    "SINGLE" => task.single = Some(value),
                    "INTERVAL" => task.interval = Some(value),
                    _ => task.priority = Some(value),
                }
                if !self.eat(TokenKind::Comma) {
                    break;
                }
            }
            if !self.expect(TokenKind::RParen) {
                self.skip_decl();
                return None;
            }
        } else {
            self.skip_decl();
            return None;
        }
        task.span = start.to(self.prev().span());
        self.expect_decl_semi();
        Some(task)
    }

    /// `PROGRAM [RETAIN] name [WITH task] : Type [(conns)];`
    fn program_config(&mut self) -> Option<ProgramConfig> {
        let start = self.bump().span();
        let retention = if self.eat_kw(Keyword::Retain) {
            Some(Retention::Retain)
        } else if self.eat_kw(Keyword::NonRetain) {
            Some(Retention::NonRetain)
        } else {
            None
        };
        let Some(name) = self.name("a program instance name") else {
            self.skip_decl();
            return None;
        };
        let task = if self.eat_kw(Keyword::With) {
            self.name("a task name")
        } else {
            None
        };
        if !self.expect(TokenKind::Colon) {
            self.skip_decl();
            return None;
        }
        let Some(type_name) = self.qualified_name("a program type name") else {
            self.skip_decl();
            return None;
        };
        let mut conns = Vec::new();
        if self.eat(TokenKind::LParen) {
            if !self.at(TokenKind::RParen) {
                loop {
                    let lhs = self.postfix();
                    match self.kind() {
                        TokenKind::Assign => {
                            self.bump();
                            let value = self.expr();
                            conns.push(ProgramConn::Input { name: lhs, value });
                        }
                        TokenKind::Arrow => {
                            self.bump();
                            let target = self.postfix();
                            conns.push(ProgramConn::Output { name: lhs, target });
                        }
                        TokenKind::Kw(Keyword::With) => {
                            self.bump();
                            if let Some(task) = self.name("a task name") {
                                conns.push(ProgramConn::FbTask { fb: lhs, task });
                            }
                        }
                        _ => {
                            self.expected("`:=`, `=>` or WITH");
                            self.skip_decl();
                            return None;
                        }
                    }
                    if !self.eat(TokenKind::Comma) || self.aborted {
                        break;
                    }
                }
            }
            if !self.expect(TokenKind::RParen) {
                self.skip_decl();
                return None;
            }
        }
        let span = start.to(self.prev().span());
        self.expect_decl_semi();
        Some(ProgramConfig {
            name,
            retention,
            task,
            type_name,
            conns,
            span,
        })
    }
}

/// The FUNCTION a METHOD or ACTION is: its name, result, variables and
/// body.
fn method_pou(
    name: crate::ast::Ident,
    return_type: Option<TypeSpec>,
    var_blocks: Vec<VarBlock>,
    body: Vec<crate::ast::Stmt>,
    span: Span,
) -> Pou {
    Pou {
        kind: PouKind::Function,
        name,
        return_type,
        var_blocks,
        body,
        il: None,
        sfc: None,
        span,
        pragmas: Vec::new(),
        extends: None,
        implements: Vec::new(),
        class: None,
        skipped_members: Vec::new(),
        partial: false,
        methods: Vec::new(),
        is_abstract: false,
        is_final: false,
        internal: false,
        usings: Vec::new(),
    }
}
