//! Inputs that once crashed or misled the parser, each kept as a test.

use stc_diagnostics::{Code, SourceMap};
use stc_syntax::{parse_project, Interner};

fn codes(text: &str) -> Vec<Code> {
    let mut sm = SourceMap::new();
    sm.add("r.st", text.to_string());
    let mut interner = Interner::new();
    let (_, diags) = parse_project(&sm, &mut interner);
    diags.iter().map(|d| d.code).collect()
}

/// A missing THEN compared a token with itself for a line break, slicing
/// the source backwards (found by the property tests).
#[test]
fn missing_then_followed_by_a_statement() {
    assert_eq!(
        codes("PROGRAM p IF x y := 1; END_IF; END_PROGRAM"),
        vec![Code::E0020]
    );
}

/// A fraction of 25 digits on a large unit overflowed the i128 product in
/// `parse_duration` (found by the C runtime's differential tests); a
/// fraction with a second point was read as 0.
#[test]
fn long_and_malformed_duration_fractions() {
    assert_eq!(
        stc_syntax::literal::parse_duration("T#1.99999999999999999999999999d").ok(),
        Some(86_400_000_000_000 + 86_399_999_999_999)
    );
    assert!(codes(
        "PROGRAM p VAR t : TIME := T#1.99999999999999999999999999d; END_VAR END_PROGRAM"
    )
    .is_empty());
    assert!(stc_syntax::literal::parse_duration("T#1.2.3s").is_err());
}
