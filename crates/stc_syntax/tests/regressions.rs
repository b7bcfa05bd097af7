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
