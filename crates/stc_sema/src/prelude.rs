//! The standard function blocks, written in Structured Text.
//!
//! `stc_pipeline` parses this text together with the user's files (as the file
//! `<stdlib>`), so the blocks are ordinary POUs to every later phase: their
//! semantics (spec/semantics.md, "Standard function blocks") are written once
//! and every back end runs exactly this code. Timers read the task clock with
//! `CUR_TIME()`, which advances only between cycles.

/// The name the prelude file has in the source map.
pub const PRELUDE_NAME: &str = "<stdlib>";

/// The source text of the prelude.
pub fn source() -> String {
    let mut s = String::from(FIXED);
    for (suffix, ty, max, min) in [
        ("", "INT", "32767", "-32768"),
        ("_INT", "INT", "32767", "-32768"),
        ("_DINT", "DINT", "2147483647", "-2147483648"),
        (
            "_LINT",
            "LINT",
            "9223372036854775807",
            "-9223372036854775808",
        ),
        ("_UDINT", "UDINT", "4294967295", "0"),
        ("_ULINT", "ULINT", "18446744073709551615", "0"),
    ] {
        s.push_str(&counters(suffix, ty, max, min));
    }
    for (suffix, ty) in [("", "TIME"), ("_LTIME", "LTIME")] {
        s.push_str(&timers(suffix, ty));
    }
    s.push_str(VENDOR);
    s
}

/// Names of vendor system libraries that real code uses without declaring
/// them (TwinCAT's Tc2_System, which every TwinCAT project references):
/// *weak* declarations, which a declaration of the user's of the same name
/// replaces without a word ([`WEAK`]).
const VENDOR: &str = r#"
TYPE T_MaxString : STRING(255); END_TYPE
TYPE PVOID : POINTER TO BYTE; END_TYPE
VAR_GLOBAL CONSTANT MAX_STRING_LENGTH : UDINT := 255; END_VAR
"#;

/// The keys (upper case) of the prelude's weak declarations. (TwinCAT's
/// PVOID is an address-sized integer; here it is a checked pointer to the
/// bytes it points at, docs/oop.md "Pointers". Its globals are read
/// without VAR_EXTERNAL and without W0114, as a library's are.)
pub const WEAK: &[&str] = &["T_MAXSTRING", "PVOID", "MAX_STRING_LENGTH"];

const FIXED: &str = r#"
FUNCTION_BLOCK SR
VAR_INPUT S1 : BOOL; R : BOOL; END_VAR
VAR_OUTPUT Q1 : BOOL; END_VAR
    Q1 := S1 OR (NOT R AND Q1);
END_FUNCTION_BLOCK

FUNCTION_BLOCK RS
VAR_INPUT S : BOOL; R1 : BOOL; END_VAR
VAR_OUTPUT Q1 : BOOL; END_VAR
    Q1 := NOT R1 AND (S OR Q1);
END_FUNCTION_BLOCK

FUNCTION_BLOCK R_TRIG
VAR_INPUT CLK : BOOL; END_VAR
VAR_OUTPUT Q : BOOL; END_VAR
VAR M : BOOL; END_VAR
    Q := CLK AND NOT M;
    M := CLK;
END_FUNCTION_BLOCK

(* The standard's body: M (initially FALSE) remembers NOT CLK, so a first
   call with CLK = FALSE gives Q = TRUE (spec/semantics.md), as MatIEC and
   TwinCAT do; afterwards Q is TRUE for one call after CLK falls. *)
FUNCTION_BLOCK F_TRIG
VAR_INPUT CLK : BOOL; END_VAR
VAR_OUTPUT Q : BOOL; END_VAR
VAR M : BOOL; END_VAR
    Q := NOT CLK AND NOT M;
    M := NOT CLK;
END_FUNCTION_BLOCK

(* ACTION_CONTROL, the standard's action control (3rd edition: the inputs
   N, R, S0, L, D, P, P1, P0, SD, DS, SL and the duration T; the outputs Q
   and A; docs/sfc.md). A chart has one instance per action, each input the
   OR of the flags of the steps that associate the action with that
   qualifier; programs may use it directly. Q is the action's activity
   (the action-control output); A is TRUE while Q, once more in the call
   after Q falls (the final scan), and once at the rising edge of P1 and the
   falling edge of P0. R resets what S0, SD, DS and SL stored and wins over
   them. *)
TYPE
    (* The flags of a step of a chart: active, and for how long. *)
    SFC_STEP : STRUCT
        X : BOOL;
        T : TIME;
    END_STRUCT;
    (* The flags of an action of a chart: its ACTION_CONTROL's Q and A. *)
    SFC_ACTION : STRUCT
        Q : BOOL;
        A : BOOL;
    END_STRUCT;
END_TYPE

FUNCTION_BLOCK ACTION_CONTROL
VAR_INPUT
    N, R, S0, L, D, P, P1, P0, SD, DS, SL : BOOL;
    T : TIME;
END_VAR
VAR_OUTPUT Q : BOOL; A : BOOL; END_VAR
VAR
    s_set, sd_set, ds_set, sl_set : BOOL;
    l_tmr, d_tmr, sd_tmr, ds_tmr, sl_tmr : TON;
    p_prev, p0_prev, p1_prev, q_prev : BOOL;
END_VAR
    s_set := NOT R AND (S0 OR s_set);
    sd_set := NOT R AND (SD OR sd_set);
    sd_tmr(IN := sd_set, PT := T);
    ds_tmr(IN := DS, PT := T);
    ds_set := NOT R AND (ds_tmr.Q OR ds_set);
    sl_set := NOT R AND (SL OR sl_set);
    sl_tmr(IN := sl_set, PT := T);
    l_tmr(IN := L, PT := T);
    d_tmr(IN := D, PT := T);
    Q := N OR (L AND NOT l_tmr.Q) OR d_tmr.Q OR (P AND NOT p_prev) OR s_set
        OR sd_tmr.Q OR ds_set OR (sl_set AND NOT sl_tmr.Q);
    A := Q OR q_prev OR (P1 AND NOT p1_prev) OR (p0_prev AND NOT P0);
    q_prev := Q;
    p_prev := P;
    p1_prev := P1;
    p0_prev := P0;
END_FUNCTION_BLOCK
"#;

/// CTU, CTD and CTUD for one counter type: counters saturate at the limits
/// of their type and never wrap.
fn counters(suffix: &str, ty: &str, max: &str, min: &str) -> String {
    format!(
        r#"
FUNCTION_BLOCK CTU{suffix}
VAR_INPUT CU : BOOL; R : BOOL; PV : {ty}; END_VAR
VAR_OUTPUT Q : BOOL; CV : {ty}; END_VAR
VAR cu_prev : BOOL; END_VAR
    IF R THEN
        CV := 0;
    ELSIF CU AND NOT cu_prev AND CV < {max} THEN
        CV := CV + 1;
    END_IF;
    cu_prev := CU;
    Q := CV >= PV;
END_FUNCTION_BLOCK

FUNCTION_BLOCK CTD{suffix}
VAR_INPUT CD : BOOL; LD : BOOL; PV : {ty}; END_VAR
VAR_OUTPUT Q : BOOL; CV : {ty}; END_VAR
VAR cd_prev : BOOL; END_VAR
    IF LD THEN
        CV := PV;
    ELSIF CD AND NOT cd_prev AND CV > {min} THEN
        CV := CV - 1;
    END_IF;
    cd_prev := CD;
    Q := CV <= 0;
END_FUNCTION_BLOCK

FUNCTION_BLOCK CTUD{suffix}
VAR_INPUT CU : BOOL; CD : BOOL; R : BOOL; LD : BOOL; PV : {ty}; END_VAR
VAR_OUTPUT QU : BOOL; QD : BOOL; CV : {ty}; END_VAR
VAR cu_prev : BOOL; cd_prev : BOOL; up : BOOL; down : BOOL; END_VAR
    up := CU AND NOT cu_prev;
    down := CD AND NOT cd_prev;
    cu_prev := CU;
    cd_prev := CD;
    IF R THEN
        CV := 0;
    ELSIF LD THEN
        CV := PV;
    ELSIF up AND NOT down THEN
        IF CV < {max} THEN
            CV := CV + 1;
        END_IF;
    ELSIF down AND NOT up THEN
        IF CV > {min} THEN
            CV := CV - 1;
        END_IF;
    END_IF;
    QU := CV >= PV;
    QD := CV <= 0;
END_FUNCTION_BLOCK
"#
    )
}

/// TP, TON and TOF for TIME or LTIME.
fn timers(suffix: &str, ty: &str) -> String {
    let zero = if ty == "LTIME" { "LTIME#0s" } else { "T#0s" };
    let now = if ty == "LTIME" {
        "TIME_TO_LTIME(CUR_TIME())"
    } else {
        "CUR_TIME()"
    };
    format!(
        r#"
FUNCTION_BLOCK TP{suffix}
VAR_INPUT IN : BOOL; PT : {ty}; END_VAR
VAR_OUTPUT Q : BOOL; ET : {ty}; END_VAR
VAR start : {ty}; pulsing : BOOL; in_prev : BOOL; END_VAR
    IF IN AND NOT in_prev AND NOT pulsing THEN
        start := {now};
        pulsing := TRUE;
    END_IF;
    IF pulsing THEN
        ET := {now} - start;
        IF ET >= PT THEN
            ET := PT;
            pulsing := FALSE;
        END_IF;
    END_IF;
    IF NOT pulsing AND NOT IN THEN
        ET := {zero};
    END_IF;
    Q := pulsing;
    in_prev := IN;
END_FUNCTION_BLOCK

FUNCTION_BLOCK TON{suffix}
VAR_INPUT IN : BOOL; PT : {ty}; END_VAR
VAR_OUTPUT Q : BOOL; ET : {ty}; END_VAR
VAR start : {ty}; in_prev : BOOL; END_VAR
    IF NOT IN THEN
        Q := FALSE;
        ET := {zero};
    ELSE
        IF NOT in_prev THEN
            start := {now};
        END_IF;
        ET := {now} - start;
        IF ET >= PT THEN
            ET := PT;
        END_IF;
        Q := ET >= PT;
    END_IF;
    in_prev := IN;
END_FUNCTION_BLOCK

FUNCTION_BLOCK TOF{suffix}
VAR_INPUT IN : BOOL; PT : {ty}; END_VAR
VAR_OUTPUT Q : BOOL; ET : {ty}; END_VAR
VAR start : {ty}; timing : BOOL; in_prev : BOOL; END_VAR
    IF IN THEN
        Q := TRUE;
        ET := {zero};
        timing := FALSE;
    ELSE
        IF in_prev THEN
            start := {now};
            timing := TRUE;
        END_IF;
        IF timing THEN
            ET := {now} - start;
            IF ET >= PT THEN
                ET := PT;
                timing := FALSE;
            END_IF;
            Q := ET < PT;
        END_IF;
    END_IF;
    in_prev := IN;
END_FUNCTION_BLOCK
"#
    )
}
