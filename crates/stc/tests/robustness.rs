//! Bad input never crashes anything (issue: the foundation). Each pathological
//! input goes through the same path as `stc check` and must end with exit
//! status 0 or 1 and, where it is invalid, a diagnostic.

use stc::cli::Outcome;

/// Runs `stc check` on a temporary file with the given bytes.
fn check_bytes(name: &str, bytes: &[u8]) -> Outcome {
    let dir = std::env::temp_dir().join(format!("stc-robustness-{}-{name}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("input.st");
    std::fs::write(&path, bytes).unwrap();
    let out = stc::cli::run_args(&["stc", "check", path.to_str().unwrap()]);
    let _ = std::fs::remove_dir_all(&dir);
    out
}

fn assert_rejected(name: &str, bytes: &[u8], code: &str) {
    let out = check_bytes(name, bytes);
    assert_eq!(out.status, 1, "{name}: {}", out.stderr);
    assert!(
        out.stderr.contains(code),
        "{name}: expected {code} in\n{}",
        out.stderr
    );
}

fn program(body: &str) -> String {
    format!("PROGRAM p\nVAR x : DINT; END_VAR\n{body}\nEND_PROGRAM\n")
}

#[test]
fn empty_and_comment_only_files_are_valid() {
    assert_eq!(check_bytes("empty", b"").status, 0);
    let out = check_bytes(
        "comments",
        b"(* nothing (* here *) *)\n// at all\n/* really */\n",
    );
    // Valid; the nested comment is only the lint's business (L0008).
    assert_eq!(out.status, 0, "{}", out.stderr);
    assert!(
        out.stderr.contains("warning[L0008]") && out.stderr.contains("1 warning"),
        "{}",
        out.stderr
    );
    let out = check_bytes(
        "flat-comments",
        b"(* nothing here *)\n// at all\n/* really */\n",
    );
    assert_eq!((out.status, out.stderr.as_str()), (0, ""));
}

#[test]
fn random_bytes_give_diagnostics_not_panics() {
    // A fixed pseudo-random sequence, so a failure reproduces.
    let mut state = 0x2545_F491_4F6C_DD1Du64;
    for round in 0..200 {
        let len = (round * 37) % 2000;
        let bytes: Vec<u8> = (0..len)
            .map(|_| {
                state ^= state << 13;
                state ^= state >> 7;
                state ^= state << 17;
                (state >> 24) as u8
            })
            .collect();
        let out = check_bytes(&format!("random{round}"), &bytes);
        assert!(out.status <= 1, "round {round}: status {}", out.status);
    }
}

#[test]
fn deeply_nested_parentheses_are_rejected_cleanly() {
    let n = 100_000;
    let body = format!("x := {}1{};", "(".repeat(n), ")".repeat(n));
    assert_rejected("parens", program(&body).as_bytes(), "E0023");
}

#[test]
fn deeply_nested_ifs_are_rejected_cleanly() {
    let n = 100_000;
    let body = format!(
        "{}x := 1;{}",
        "IF TRUE THEN ".repeat(n),
        " END_IF;".repeat(n)
    );
    assert_rejected("ifs", program(&body).as_bytes(), "E0023");
}

#[test]
fn very_long_operator_chains_are_bounded() {
    let body = format!("x := 1{};", " + 1".repeat(200_000));
    assert_rejected("chain", program(&body).as_bytes(), "E0023");
    // A long chain below the limit is fine.
    let body = format!("x := 1{};", " + 1".repeat(1_000));
    assert_eq!(check_bytes("chain_ok", program(&body).as_bytes()).status, 0);
}

#[test]
fn huge_literals_and_names() {
    let long_name = "a".repeat(10_000);
    let src =
        format!("PROGRAM p\nVAR {long_name} : DINT; END_VAR\n{long_name} := 1;\nEND_PROGRAM\n");
    assert_eq!(check_bytes("long_ident", src.as_bytes()).status, 0);
    assert_rejected(
        "big_int",
        program(&format!("x := {};", "9".repeat(400))).as_bytes(),
        "E0007",
    );
    assert_rejected(
        "big_time",
        program("x := T#99999999999d;").as_bytes(),
        "E0007",
    );
}

#[test]
fn a_fifty_megabyte_file_is_handled() {
    let unit = "FUNCTION_BLOCK fb\nVAR_INPUT a : INT; END_VAR\nVAR b : INT; END_VAR\nIF a > 0 THEN b := a * 2; ELSE b := -a; END_IF;\nEND_FUNCTION_BLOCK\n";
    let mut src = String::with_capacity(50 << 20);
    let mut i = 0;
    while src.len() < 50 << 20 {
        src.push_str(&unit.replace("fb\n", &format!("fb{i}\n")));
        i += 1;
    }
    let out = check_bytes("big", src.as_bytes());
    assert_eq!(
        out.status,
        0,
        "{}",
        &out.stderr[..out.stderr.len().min(2000)]
    );
}

#[test]
fn non_utf8_is_read_as_windows_1252_with_a_warning() {
    let out = check_bytes(
        "latin1",
        b"PROGRAM p\nVAR s : STRING; END_VAR\ns := 'Gr\xFC\xDFe';\nEND_PROGRAM\n",
    );
    assert_eq!(out.status, 0);
    assert!(
        out.stderr.contains("W0001") && out.stderr.contains(":3:9:"),
        "{}",
        out.stderr
    );
}
