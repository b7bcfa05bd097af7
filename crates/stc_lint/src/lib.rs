//! Lints: findings beyond the errors and warnings of the analysis, from the
//! PLCopen coding guidelines that a static checker can decide (magic
//! numbers, direct addresses in bodies, outputs read before their instance
//! is called, shadowed globals, unused inputs, CASE without ELSE, REAL
//! compared with `=`, nested comments, a variable assigned on some paths of
//! an IF then read).
//!
//! Each lint has a stable code of the `L` family (`stc explain L0003`), a
//! name (`output-before-call`) and a default [`Level`]; a project sets the
//! levels in `stc.toml` (`[lints]`) or on the command line. The lints walk
//! the analysed program ([`stc_sema::Analysis`] and its syntax tree) after
//! the analysis, read-only: they add diagnostics, never change what a
//! program means, and are run only by the tools that show them (`stc check`
//! and the language server), so no other command's output changes.
//!
//! **Invariant:** no I/O; never panics on any analysed program (a project
//! with errors included: what the analysis could not type is skipped).

mod rules;
mod walk;

use stc_diagnostics::{Code, Diagnostic, Severity, SourceMap, Span};
use stc_sema::Analysis;
use stc_syntax::ast::Ast;
use stc_syntax::Interner;

/// What a lint's finding is: not reported, a warning, or an error.
#[derive(Clone, Copy, PartialEq, Eq, Debug, Default)]
pub enum Level {
    Allow,
    #[default]
    Warn,
    Deny,
}

impl Level {
    /// `allow`, `warn` or `deny`.
    pub fn parse(word: &str) -> Option<Level> {
        match word.to_ascii_lowercase().as_str() {
            "allow" => Some(Level::Allow),
            "warn" => Some(Level::Warn),
            "deny" => Some(Level::Deny),
            _ => None,
        }
    }

    pub fn as_str(self) -> &'static str {
        match self {
            Level::Allow => "allow",
            Level::Warn => "warn",
            Level::Deny => "deny",
        }
    }
}

/// One lint: its code, its name and its level when nothing sets one.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
pub struct Lint {
    pub code: Code,
    pub name: &'static str,
    pub default: Level,
}

/// Every lint, in code order. The defaults are what a careful team would
/// want on any project: a lint that flags code many good programs are
/// written with (every literal, a CASE over an enumeration that names every
/// value) is off until a project asks for it.
pub const LINTS: &[Lint] = &[
    Lint {
        code: Code::L0001,
        name: "magic-number",
        default: Level::Allow,
    },
    Lint {
        code: Code::L0002,
        name: "direct-address",
        default: Level::Warn,
    },
    Lint {
        code: Code::L0003,
        name: "output-before-call",
        default: Level::Warn,
    },
    Lint {
        code: Code::L0004,
        name: "shadowed-global",
        default: Level::Warn,
    },
    Lint {
        code: Code::L0005,
        name: "unused-input",
        default: Level::Warn,
    },
    Lint {
        code: Code::L0006,
        name: "case-without-else",
        default: Level::Allow,
    },
    Lint {
        code: Code::L0007,
        name: "real-equality",
        default: Level::Warn,
    },
    Lint {
        code: Code::L0008,
        name: "nested-comment",
        default: Level::Warn,
    },
    Lint {
        code: Code::L0009,
        name: "assigned-on-some-paths",
        default: Level::Warn,
    },
];

/// The number of lints.
pub const COUNT: usize = 9;

/// The lint with a name (`case-without-else`, also written with `_`) or a
/// code (`L0006`), case-insensitively.
pub fn find(name_or_code: &str) -> Option<Lint> {
    let key = name_or_code.trim().replace('_', "-");
    LINTS
        .iter()
        .copied()
        .find(|l| l.name.eq_ignore_ascii_case(&key) || l.code.as_str().eq_ignore_ascii_case(&key))
}

/// The lint of a code, when the code is a lint's.
pub fn of_code(code: Code) -> Option<Lint> {
    LINTS.iter().copied().find(|l| l.code == code)
}

/// The level of every lint.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
pub struct Levels([Level; COUNT]);

impl Default for Levels {
    /// Every lint at its default level.
    fn default() -> Levels {
        let mut l = [Level::Warn; COUNT];
        for (i, lint) in LINTS.iter().enumerate() {
            l[i] = lint.default;
        }
        Levels(l)
    }
}

impl Levels {
    /// Every lint at one level (tests, `stc explain`'s examples).
    pub fn all(level: Level) -> Levels {
        Levels([level; COUNT])
    }

    pub fn get(&self, code: Code) -> Level {
        LINTS
            .iter()
            .position(|l| l.code == code)
            .and_then(|i| self.0.get(i).copied())
            .unwrap_or(Level::Allow)
    }

    pub fn set(&mut self, code: Code, level: Level) {
        if let Some(i) = LINTS.iter().position(|l| l.code == code) {
            if let Some(slot) = self.0.get_mut(i) {
                *slot = level;
            }
        }
    }

    /// Whether no lint is on.
    pub fn none(&self) -> bool {
        self.0.iter().all(|l| *l == Level::Allow)
    }
}

/// What the lints read: the analysed project.
pub struct Input<'a> {
    pub ast: &'a Ast,
    pub analysis: &'a Analysis,
    pub interner: &'a Interner,
    pub sources: &'a SourceMap,
    /// The standard library prelude's file: nothing in it is linted.
    pub prelude: Span,
    /// The diagnostics the parser and the analyser gave: a lint says
    /// nothing where one of them already says the same.
    pub diagnostics: &'a [Diagnostic],
}

/// The findings of the lints that are on, in source order, each with the
/// severity its level gives (a warning, or an error for `deny`).
pub fn check(input: &Input<'_>, levels: &Levels) -> Vec<Diagnostic> {
    check_within(input, levels, 0..u32::MAX)
}

/// [`check`] of the POUs and files that begin at a position in `within`
/// only (what a language server lints again of a project whose other
/// files did not change: the findings of the rest are the same).
pub fn check_within(
    input: &Input<'_>,
    levels: &Levels,
    within: std::ops::Range<u32>,
) -> Vec<Diagnostic> {
    if levels.none() {
        return Vec::new();
    }
    let mut found = rules::run(input, levels, &within);
    found.retain(|d| levels.get(d.code) != Level::Allow);
    for d in &mut found {
        if levels.get(d.code) == Level::Deny {
            d.severity = Severity::Error;
        }
    }
    found.sort_by_key(|d| (d.span.lo, d.code));
    found.dedup_by(|a, b| a.span == b.span && a.code == b.code);
    found
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_catalogue_matches_the_codes() {
        assert_eq!(LINTS.len(), COUNT);
        for (i, l) in LINTS.iter().enumerate() {
            assert_eq!(l.code.as_str(), format!("L{:04}", i + 1));
            assert_eq!(find(l.name), Some(*l));
            assert_eq!(find(l.code.as_str()), Some(*l));
            assert_eq!(of_code(l.code), Some(*l));
        }
        let lint_codes = Code::ALL
            .iter()
            .filter(|c| c.as_str().starts_with('L'))
            .count();
        assert_eq!(lint_codes, COUNT, "every L code is a lint");
        assert_eq!(find("case_without_else").map(|l| l.code), Some(Code::L0006));
        assert!(find("no-such-lint").is_none());
        let mut levels = Levels::default();
        assert_eq!(levels.get(Code::L0001), Level::Allow);
        levels.set(Code::L0001, Level::Deny);
        assert_eq!(levels.get(Code::L0001), Level::Deny);
        assert_eq!(levels.get(Code::E0301), Level::Allow);
    }
}
