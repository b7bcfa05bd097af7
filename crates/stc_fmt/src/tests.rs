//! Layout cases, comments in awkward places first. Every case also goes
//! through the checks of [`format`] (same tree, same trivia, idempotent).

use super::*;

fn fmt(src: &str) -> String {
    match format(src, 0, &Options::default()) {
        Ok(s) => s,
        Err(e) => panic!("{e}\n--- input:\n{src}"),
    }
}

#[track_caller]
fn check(src: &str, expected: &str) {
    let got = fmt(src);
    assert_eq!(
        got, expected,
        "\n--- got:\n{got}\n--- expected:\n{expected}"
    );
}

#[test]
fn statements_one_per_line_with_operator_spacing() {
    check(
        "program p var x,y:int; end_var x:=1+2*y;y:=-x;IF x>1 THEN y:=x MOD 2;ELSIF x<0 THEN y:=0;ELSE y:=1;END_IF; end_program",
        "PROGRAM p\n    VAR\n        x, y : INT;\n    END_VAR\n    x := 1 + 2 * y;\n    y := -x;\n    IF x > 1 THEN\n        y := x MOD 2;\n    ELSIF x < 0 THEN\n        y := 0;\n    ELSE\n        y := 1;\n    END_IF;\nEND_PROGRAM\n",
    );
}

#[test]
fn case_labels_and_arms() {
    check(
        "PROGRAM p VAR c : INT; END_VAR\nCASE c OF 1,2: c:=3; 4..5: c := 6; c := 7; ELSE c:=0; END_CASE;\nEND_PROGRAM",
        "PROGRAM p\n    VAR\n        c : INT;\n    END_VAR\n    CASE c OF\n        1, 2:\n            c := 3;\n        4..5:\n            c := 6;\n            c := 7;\n        ELSE\n            c := 0;\n    END_CASE;\nEND_PROGRAM\n",
    );
}

#[test]
fn loops_calls_and_literals_keep_their_text() {
    check(
        "FUNCTION_BLOCK fb\nVAR t : TON; a : ARRAY[1..3] OF INT := [1,2,3]; END_VAR\nFOR i:=1 TO 3 BY 1 DO a[i] := 16#FF; END_FOR;\nWHILE FALSE DO EXIT; END_WHILE;\nREPEAT t(IN:=TRUE, PT:=T#1s); UNTIL t.Q END_REPEAT;\nEND_FUNCTION_BLOCK",
        "FUNCTION_BLOCK fb\n    VAR\n        t : TON;\n        a : ARRAY[1..3] OF INT := [1, 2, 3];\n    END_VAR\n    FOR i := 1 TO 3 BY 1 DO\n        a[i] := 16#FF;\n    END_FOR;\n    WHILE FALSE DO\n        EXIT;\n    END_WHILE;\n    REPEAT\n        t(IN := TRUE, PT := T#1s);\n    UNTIL t.Q\n    END_REPEAT;\nEND_FUNCTION_BLOCK\n",
    );
}

#[test]
fn trailing_comments_stay_on_their_line() {
    check(
        "PROGRAM p (* head *)\nVAR (* locals *)\n  x : INT; // the count\nEND_VAR\nx := 1; (* one *) x := 2; // two\nEND_PROGRAM\n",
        "PROGRAM p (* head *)\n    VAR (* locals *)\n        x : INT; // the count\n    END_VAR\n    x := 1; (* one *)\n    x := 2; // two\nEND_PROGRAM\n",
    );
}

#[test]
fn comments_on_their_own_line_take_the_indentation_of_what_follows() {
    check(
        "(* file header *)\n\n// doc for p\nPROGRAM p\n(* about the variables *)\nVAR\n// x\nx : INT;\nEND_VAR\nIF x = 0 THEN\n// nothing yet\nEND_IF;\n(* last *)\nEND_PROGRAM\n// trailer\n",
        "(* file header *)\n\n// doc for p\nPROGRAM p\n    (* about the variables *)\n    VAR\n        // x\n        x : INT;\n    END_VAR\n    IF x = 0 THEN\n        // nothing yet\n    END_IF;\n    (* last *)\nEND_PROGRAM\n// trailer\n",
    );
}

#[test]
fn comments_inside_expressions_and_between_tokens() {
    check(
        "PROGRAM p VAR x : INT; END_VAR\nx := (* a *) 1 + // b\n   2;\nx := f(1, (* c *)\n  2);\nEND_PROGRAM",
        "PROGRAM p\n    VAR\n        x : INT;\n    END_VAR\n    x := (* a *) 1 + // b\n        2;\n    x := f(1, (* c *)\n        2);\nEND_PROGRAM\n",
    );
}

#[test]
fn a_line_comment_before_a_semicolon_keeps_its_line_break() {
    let out = fmt("PROGRAM p VAR x : INT; END_VAR\nx := 1 // why\n;\nEND_PROGRAM");
    assert!(out.contains("x := 1 // why\n"), "{out}");
}

#[test]
fn multi_line_block_comments_and_pragmas_are_kept_verbatim() {
    let src = "{version 1}\nPROGRAM p\n  (* line one\n     line two *)\n  VAR {some pragma} x : INT; END_VAR\nEND_PROGRAM\n";
    let out = fmt(src);
    assert!(out.contains("(* line one\n     line two *)"), "{out}");
    assert!(out.starts_with("{version 1}\nPROGRAM p\n"), "{out}");
    assert!(out.contains("{some pragma}"), "{out}");
}

#[test]
fn blank_lines_are_kept_once_and_items_are_separated() {
    check(
        "TYPE Color : (Red, Green); END_TYPE PROGRAM p VAR x : INT;\n\n\n\ny : INT; END_VAR END_PROGRAM",
        "TYPE\n    Color : (Red, Green);\nEND_TYPE\n\nPROGRAM p\n    VAR\n        x : INT;\n\n        y : INT;\n    END_VAR\nEND_PROGRAM\n",
    );
}

#[test]
fn keyword_case_is_configurable() {
    let src = "program p var x : int; end_var x := NOT TRUE; END_PROGRAM";
    let lower = format(
        src,
        0,
        &Options {
            keyword_case: KeywordCase::Lower,
            ..Options::default()
        },
    )
    .unwrap();
    assert!(
        lower.contains("x : int;") && lower.contains("x := not true;"),
        "{lower}"
    );
    let kept = format(
        src,
        0,
        &Options {
            keyword_case: KeywordCase::Preserve,
            ..Options::default()
        },
    )
    .unwrap();
    assert!(
        kept.starts_with("program p\n") && kept.ends_with("END_PROGRAM\n"),
        "{kept}"
    );
}

#[test]
fn unary_minus_typed_literals_and_ranges() {
    check(
        "PROGRAM p VAR x : INT (-5..5) := -1; e : Color := Color#Red; END_VAR x := INT#-3 - -x; x := a.b[1,2].%X3; END_PROGRAM",
        "PROGRAM p\n    VAR\n        x : INT (-5..5) := -1;\n        e : Color := Color#Red;\n    END_VAR\n    x := INT#-3 - -x;\n    x := a.b[1, 2].%X3;\nEND_PROGRAM\n",
    );
}

#[test]
fn configurations_resources_and_structs() {
    check(
        "TYPE S : STRUCT a : INT; b : BOOL; END_STRUCT; END_TYPE\nCONFIGURATION c\nRESOURCE r ON PLC\nTASK t (INTERVAL := T#10ms, PRIORITY := 1);\nPROGRAM i WITH t : p;\nEND_RESOURCE\nEND_CONFIGURATION",
        "TYPE\n    S : STRUCT\n        a : INT;\n        b : BOOL;\n    END_STRUCT;\nEND_TYPE\n\nCONFIGURATION c\n    RESOURCE r ON PLC\n        TASK t(INTERVAL := T#10ms, PRIORITY := 1);\n        PROGRAM i WITH t : p;\n    END_RESOURCE\nEND_CONFIGURATION\n",
    );
}

#[test]
fn a_file_with_syntax_errors_is_left_alone() {
    let e = format("PROGRAM p x := ; END_PROGRAM", 0, &Options::default());
    assert!(matches!(e, Err(FormatError::Syntax(_))), "{e:?}");
}

#[test]
fn empty_and_comment_only_files() {
    check("", "");
    check("\n\n", "");
    check("// only a comment\n", "// only a comment\n");
}

#[test]
fn sfc_elements_are_blocks() {
    check(
        "PROGRAM p VAR go, lamp : BOOL; END_VAR\nINITIAL_STEP s0: lamp(N); END_STEP\nSTEP s1: a(L,T#1s); END_STEP\nTRANSITION t(PRIORITY:=1) FROM s0 TO (s1) := go; END_TRANSITION\nTRANSITION u FROM s1 TO s0: u := NOT go; END_TRANSITION\nACTION a: go := FALSE; END_ACTION\nEND_PROGRAM",
        "PROGRAM p\n    VAR\n        go, lamp : BOOL;\n    END_VAR\n    INITIAL_STEP s0 :\n        lamp(N);\n    END_STEP\n    STEP s1 :\n        a(L, T#1s);\n    END_STEP\n    TRANSITION t (PRIORITY := 1) FROM s0 TO (s1) := go;\n    END_TRANSITION\n    TRANSITION u FROM s1 TO s0 :\n        u := NOT go;\n    END_TRANSITION\n    ACTION a :\n        go := FALSE;\n    END_ACTION\nEND_PROGRAM\n",
    );
}

#[test]
fn methods_are_blocks_of_their_function_block_and_references_keep_their_caret() {
    check(
        "FUNCTION_BLOCK f VAR x : INT; r : REF_TO INT; END_VAR\nMETHOD PUBLIC m : INT VAR_INPUT n : INT; END_VAR m := n + THIS^.x; r^ := n; END_METHOD\nx := m(1); END_FUNCTION_BLOCK",
        "FUNCTION_BLOCK f\n    VAR\n        x : INT;\n        r : REF_TO INT;\n    END_VAR\n    METHOD PUBLIC m : INT\n        VAR_INPUT\n            n : INT;\n        END_VAR\n        m := n + THIS^.x;\n        r^ := n;\n    END_METHOD\n    x := m(1);\nEND_FUNCTION_BLOCK\n",
    );
}

#[test]
fn classes_and_interfaces_are_blocks() {
    check(
        "INTERFACE I EXTENDS J\nMETHOD m : INT\nEND_METHOD END_INTERFACE\nCLASS C EXTENDS B IMPLEMENTS I VAR x : INT; END_VAR\nMETHOD PUBLIC m : INT\nm := x; END_METHOD END_CLASS",
        "INTERFACE I EXTENDS J\n    METHOD m : INT\n    END_METHOD\nEND_INTERFACE\n\nCLASS C EXTENDS B IMPLEMENTS I\n    VAR\n        x : INT;\n    END_VAR\n    METHOD PUBLIC m : INT\n        m := x;\n    END_METHOD\nEND_CLASS\n",
    );
}

#[test]
fn properties_and_their_accessors_are_blocks() {
    check(
        "FUNCTION_BLOCK f VAR x : INT; p : POINTER TO INT; END_VAR\nPROPERTY PUBLIC v : INT GET VAR k : INT; END_VAR v := x + k; END_GET SET x := v; p^ := v; END_SET END_PROPERTY\nx := x + 1; END_FUNCTION_BLOCK",
        "FUNCTION_BLOCK f\n    VAR\n        x : INT;\n        p : POINTER TO INT;\n    END_VAR\n    PROPERTY PUBLIC v : INT\n        GET\n            VAR\n                k : INT;\n            END_VAR\n            v := x + k;\n        END_GET\n        SET\n            x := v;\n            p^ := v;\n        END_SET\n    END_PROPERTY\n    x := x + 1;\nEND_FUNCTION_BLOCK\n",
    );
}

#[test]
fn il_bodies_one_instruction_per_line_operators_upper_case() {
    check(
        "FUNCTION_BLOCK f VAR a, b : BOOL; i : INT; t : TON; END_VAR\n  ld a\n andn   b\nst a // kept\n\nstart:   ld i\nadd(   i\n  mul 2\n    )\nst i\n(* own line *)\n jmpc start\nend:\ncal t(IN := a,\n      PT := T#1s)\n&N b\nld -5\nEND_FUNCTION_BLOCK",
        "FUNCTION_BLOCK f\n    VAR\n        a, b : BOOL;\n        i : INT;\n        t : TON;\n    END_VAR\n    LD a\n    ANDN b\n    ST a // kept\n\n    start: LD i\n    ADD( i\n        MUL 2\n    )\n    ST i\n    (* own line *)\n    JMPC start\n    end:\n    CAL t(IN := a,\n        PT := T#1s)\n    &N b\n    LD -5\nEND_FUNCTION_BLOCK\n",
    );
}

#[test]
fn il_bodies_of_chart_actions_and_transitions() {
    check(
        "PROGRAM p VAR go, y : BOOL; END_VAR\nINITIAL_STEP s0: a(N); END_STEP\nSTEP s1: END_STEP\nTRANSITION FROM s0 TO s1:\nld go\n  and y\nEND_TRANSITION\nACTION a:\n ld go\n   st y\nEND_ACTION\nEND_PROGRAM",
        "PROGRAM p\n    VAR\n        go, y : BOOL;\n    END_VAR\n    INITIAL_STEP s0 :\n        a(N);\n    END_STEP\n    STEP s1 :\n    END_STEP\n    TRANSITION FROM s0 TO s1 :\n        LD go\n        AND y\n    END_TRANSITION\n    ACTION a :\n        LD go\n        ST y\n    END_ACTION\nEND_PROGRAM\n",
    );
}

#[test]
fn il_parameter_sequences_are_indented_inside_their_call() {
    check(
        "PROGRAM p VAR t : TON; a, b : BOOL; END_VAR\ncal t(\nIN := (ld a\nandn b\n),\nPT := T#1s)\nEND_PROGRAM",
        "PROGRAM p\n    VAR\n        t : TON;\n        a, b : BOOL;\n    END_VAR\n    CAL t(\n        IN := ( LD a\n            ANDN b\n        ),\n        PT := T#1s)\nEND_PROGRAM\n",
    );
}
