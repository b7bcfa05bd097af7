//! Property tests of the front end on random input: random token soup and
//! random mutations of real sources never panic, every diagnostic span lies
//! inside the file, and valid programs print and re-parse to the same tree.
//! (The long coverage-guided run is the `fuzz/` target; this is the part
//! that runs on every CI build.)

use proptest::prelude::*;
use stc_diagnostics::SourceMap;
use stc_syntax::{dump, parse_project, print, Interner};

const VOCAB: &[&str] = &[
    "PROGRAM",
    "END_PROGRAM",
    "FUNCTION_BLOCK",
    "END_FUNCTION_BLOCK",
    "FUNCTION",
    "END_FUNCTION",
    "VAR",
    "VAR_INPUT",
    "END_VAR",
    "TYPE",
    "END_TYPE",
    "STRUCT",
    "END_STRUCT",
    "IF",
    "THEN",
    "ELSIF",
    "ELSE",
    "END_IF",
    "CASE",
    "OF",
    "END_CASE",
    "FOR",
    "TO",
    "BY",
    "DO",
    "END_FOR",
    "WHILE",
    "END_WHILE",
    "REPEAT",
    "UNTIL",
    "END_REPEAT",
    "EXIT",
    "RETURN",
    "CONFIGURATION",
    "END_CONFIGURATION",
    "RESOURCE",
    "ON",
    "END_RESOURCE",
    "TASK",
    "WITH",
    "AT",
    "ARRAY",
    "INT",
    "BOOL",
    "STRING",
    "TIME",
    "x",
    "y",
    "MAX",
    "fb",
    "T#1s",
    "16#FF",
    "1.5E3",
    "'s$N'",
    "\"w\"",
    "%IX0.1",
    "%Q*",
    "42",
    "-",
    "+",
    "*",
    "**",
    "/",
    "MOD",
    "AND",
    "OR",
    "XOR",
    "NOT",
    "=",
    "<>",
    "<",
    "<=",
    ">",
    ">=",
    ":=",
    "=>",
    ":",
    ";",
    ",",
    ".",
    "..",
    "(",
    ")",
    "[",
    "]",
    "#",
    "(*",
    "*)",
    "{",
    "}",
    "//",
    "\n",
    "D#2024-01-01",
    "TOD#12:00:00",
    "INT#-5",
    "Color#Red",
    "$",
    "?",
    "__a",
];

fn parse(text: &str) -> (String, Vec<stc_diagnostics::Diagnostic>, usize) {
    let mut sm = SourceMap::new();
    sm.add("f.st", text.to_string());
    let mut interner = Interner::new();
    let (ast, diags) = parse_project(&sm, &mut interner);
    (dump::dump(&ast, &interner, None), diags, text.len())
}

fn check_spans(text: &str) {
    let (_, diags, len) = parse(text);
    for d in &diags {
        assert!(d.span.lo <= d.span.hi && d.span.hi as usize <= len, "{d:?}");
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 2000, ..ProptestConfig::default() })]

    #[test]
    fn token_soup_never_panics(words in prop::collection::vec(0..VOCAB.len(), 0..200)) {
        let text: Vec<&str> = words.iter().map(|&i| VOCAB[i]).collect();
        check_spans(&text.join(" "));
    }

    #[test]
    fn mutated_programs_never_panic(
        edits in prop::collection::vec((0usize..10_000, 0usize..4, any::<u8>()), 1..8)
    ) {
        let mut bytes = SAMPLE.as_bytes().to_vec();
        for (pos, op, b) in edits {
            let p = pos % (bytes.len() + 1);
            match op {
                0 => { bytes.insert(p, b); }
                1 if p < bytes.len() => { bytes.remove(p); }
                2 if p < bytes.len() => { bytes[p] = b; }
                _ => {
                    let q = (p + b as usize) % (bytes.len() + 1);
                    let (lo, hi) = (p.min(q), p.max(q));
                    bytes.drain(lo..hi);
                }
            }
        }
        check_spans(&String::from_utf8_lossy(&bytes));
    }

    #[test]
    fn integer_expressions_print_and_reparse_identically(e in expr_strategy()) {
        let src = format!("PROGRAM p\nx := {e};\nEND_PROGRAM\n");
        let (tree, diags, _) = parse(&src);
        prop_assert!(diags.is_empty(), "{src}: {diags:?}");
        let mut sm = SourceMap::new();
        sm.add("f.st", src.clone());
        let mut interner = Interner::new();
        let (ast, _) = parse_project(&sm, &mut interner);
        let printed = print::print(&ast, &interner, &|_| String::new());
        let (again, diags, _) = parse(&printed);
        prop_assert!(diags.is_empty());
        prop_assert_eq!(tree, again);
    }
}

fn expr_strategy() -> impl Strategy<Value = String> {
    let leaf = prop_oneof![
        (0u32..1000).prop_map(|n| n.to_string()),
        Just("x".to_string()),
        Just("a[1, i]".to_string()),
        Just("s.m".to_string()),
        Just("INT#-3".to_string()),
        Just("f(1, y)".to_string()),
    ];
    leaf.prop_recursive(6, 64, 4, |inner| {
        let ops = prop::sample::select(vec![
            "+", "-", "*", "/", "MOD", "**", "AND", "OR", "XOR", "=", "<>", "<", ">=", "&",
        ]);
        prop_oneof![
            (inner.clone(), ops, inner.clone()).prop_map(|(a, o, b)| format!("{a} {o} {b}")),
            inner.clone().prop_map(|a| format!("({a})")),
            inner.clone().prop_map(|a| format!("-{a}")),
            inner.prop_map(|a| format!("NOT {a}")),
        ]
    })
}

const SAMPLE: &str = r#"TYPE Color : (Red, Green := 5); P : STRUCT x : INT := 1; y : ARRAY[1..3] OF REAL; END_STRUCT; END_TYPE
FUNCTION_BLOCK Fb
VAR_INPUT a : INT; go : BOOL R_EDGE; END_VAR
VAR_OUTPUT q : BOOL; END_VAR
VAR t : TON; c : Color := Color#Red; s : STRING[10] := 'it$'s'; arr : ARRAY[0..3] OF INT := [1, 2(0), 3]; END_VAR
t(IN := go, PT := T#1s500ms, Q => q);
CASE a OF 1, 2..5: q := TRUE; MAX: a := -a ** 2; ELSE a := 0; END_CASE;
FOR a := 1 TO 10 BY 2 DO IF a > 3 THEN EXIT; END_IF; END_FOR;
WHILE NOT q DO q := t.Q OR a MOD 2 = 0; END_WHILE;
REPEAT a := a + 1; UNTIL a >= 5 END_REPEAT;
END_FUNCTION_BLOCK
CONFIGURATION C RESOURCE R ON PLC TASK t1 (INTERVAL := T#10ms, PRIORITY := 1);
PROGRAM p1 WITH t1 : Prog (i := 1, o => g); END_RESOURCE END_CONFIGURATION
"#;
