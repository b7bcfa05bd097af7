//! Coverage-guided fuzzing of the front end: any bytes, decoded the way the
//! driver decodes files, must lex and parse without panicking, and every
//! diagnostic must point inside the file.
//!
//! Run: `cargo fuzz run parse -- -max_total_time=600` (from the repo root;
//! seeds: `fuzz/seeds`).

#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let text = String::from_utf8_lossy(data).into_owned();
    let len = text.len();
    let mut sm = stc_diagnostics::SourceMap::new();
    sm.add("fuzz.st", text);
    let mut interner = stc_syntax::Interner::new();
    let (ast, diags) = stc_syntax::parse_project(&sm, &mut interner);
    for d in &diags {
        assert!(d.span.lo <= d.span.hi && d.span.hi as usize <= len);
    }
    // Printing and dumping walk the whole tree too.
    let _ = stc_syntax::dump::dump(&ast, &interner, None);
    let _ = stc_syntax::print::print(&ast, &interner, &|_| String::new());
});
