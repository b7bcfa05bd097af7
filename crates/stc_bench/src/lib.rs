//! Benchmark support: [`generate`] writes large, valid, realistic ST
//! projects (types, functions, function blocks with timers, CASE state
//! machines, loops, a program and a configuration), so every phase can be
//! timed on the same input at any size.

/// A generated project of about `lines` lines.
pub fn generate(lines: usize) -> String {
    let mut out = String::with_capacity(lines * 32);
    let mut i = 0;
    let mut count = 0;
    while count + 70 < lines.max(71) {
        let unit = unit(i);
        count += unit.lines().count();
        out.push_str(&unit);
        i += 1;
    }
    out.push_str(&program(i));
    out
}

fn unit(i: usize) -> String {
    format!(
        r#"TYPE
    Rec{i} : STRUCT
        a : INT := 1;
        b : REAL;
        flags : ARRAY[0..7] OF BOOL;
    END_STRUCT;
    Mode{i} : (Idle, Run, Stop);
END_TYPE

FUNCTION Scale{i} : REAL
VAR_INPUT
    raw : INT;
    gain : REAL;
END_VAR
    Scale{i} := INT_TO_REAL(raw) * gain + 0.5;
END_FUNCTION

(* Controller {i}: waits for enable, runs until its timer expires. *)
FUNCTION_BLOCK Ctrl{i}
VAR_INPUT
    enable : BOOL;
    setpoint : INT;
END_VAR
VAR_OUTPUT
    out : REAL;
    done : BOOL;
END_VAR
VAR
    state : Mode{i} := Mode{i}#Idle;
    rec : Rec{i};
    timer : TON;
    k : INT;
    acc : DINT;
END_VAR
    timer(IN := enable, PT := T#500ms);
    CASE state OF
        Mode{i}#Idle:
            IF enable AND NOT done THEN
                state := Mode{i}#Run;
            END_IF;
        Mode{i}#Run:
            acc := 0;
            FOR k := 0 TO 7 DO
                rec.flags[k] := (k MOD 2) = 0;
                acc := acc + INT_TO_DINT(k * setpoint);
            END_FOR;
            out := Scale{i}(raw := setpoint, gain := 1.5);
            IF timer.Q THEN
                state := Mode{i}#Stop;
            END_IF;
    ELSE
        done := TRUE;
        WHILE acc > 100 DO
            acc := acc / 2;
        END_WHILE;
    END_CASE;
END_FUNCTION_BLOCK

"#
    )
}

fn program(units: usize) -> String {
    let n = units.min(50);
    let mut decls = String::new();
    let mut calls = String::new();
    for i in 0..n {
        decls.push_str(&format!("    c{i} : Ctrl{i};\n"));
        calls.push_str(&format!(
            "    c{i}(enable := start, setpoint := {i});\n    total := total + c{i}.out;\n"
        ));
    }
    format!(
        "PROGRAM Main\nVAR_INPUT\n    start : BOOL;\nEND_VAR\nVAR_OUTPUT\n    total : REAL;\nEND_VAR\nVAR\n{decls}END_VAR\n    total := 0.0;\n{calls}END_PROGRAM\n\nCONFIGURATION Plant\n    RESOURCE Cpu ON PLC\n        TASK cyclic (INTERVAL := T#10ms, PRIORITY := 1);\n        PROGRAM main WITH cyclic : Main;\n    END_RESOURCE\nEND_CONFIGURATION\n"
    )
}

/// A generated project of about `lines` lines that a circuit can express
/// (the netlist back end's benchmark): per unit a FUNCTION with IF, CASE
/// and arithmetic, and a FUNCTION_BLOCK with a TON timer, a state machine
/// and a FOR loop with constant bounds; a PROGRAM with one instance of
/// every function block, called every cycle.
pub fn generate_circuit(lines: usize) -> String {
    let mut out = String::with_capacity(lines * 32);
    let mut i = 0;
    let mut count = 0;
    let mut units = Vec::new();
    while count + 12 < lines.max(13) {
        let unit = circuit_unit(i);
        // The program's declaration and call of the unit: 3 lines.
        count += unit.lines().count() + 3;
        out.push_str(&unit);
        units.push(i);
        i += 1;
    }
    let mut decls = String::new();
    let mut calls = String::new();
    for i in units {
        decls.push_str(&format!("    c{i} : Stage{i};\n"));
        calls.push_str(&format!(
            "    c{i}(run := start, level := level + {i});\n    total := total + c{i}.out;\n"
        ));
    }
    out.push_str(&format!(
        "PROGRAM Main\nVAR_INPUT\n    start : BOOL;\n    level : INT;\nEND_VAR\nVAR_OUTPUT\n    total : DINT;\nEND_VAR\nVAR\n{decls}END_VAR\n    total := 0;\n{calls}END_PROGRAM\n"
    ));
    out
}

fn circuit_unit(i: usize) -> String {
    format!(
        r#"FUNCTION Clamp{i} : INT
VAR_INPUT
    x : INT;
    mode : INT;
END_VAR
    CASE mode OF
        0: Clamp{i} := x;
        1: Clamp{i} := x * 2 - {i};
    ELSE
        Clamp{i} := -x;
    END_CASE;
    IF Clamp{i} > 1000 THEN
        Clamp{i} := 1000;
    ELSIF Clamp{i} < -1000 THEN
        Clamp{i} := -1000;
    END_IF;
END_FUNCTION

(* Stage {i}: counts while running, then rests for its timer. *)
FUNCTION_BLOCK Stage{i}
VAR_INPUT
    run : BOOL;
    level : INT;
END_VAR
VAR_OUTPUT
    out : DINT;
END_VAR
VAR
    state : INT;
    pause : TON;
    k : INT;
    sum : DINT;
END_VAR
    pause(IN := state = 2, PT := T#200ms);
    CASE state OF
        0:
            IF run THEN
                state := 1;
            END_IF;
        1:
            sum := 0;
            FOR k := 0 TO 3 DO
                sum := sum + INT_TO_DINT(Clamp{i}(x := level + k, mode := k MOD 3));
            END_FOR;
            out := out + sum;
            state := 2;
        2:
            IF pause.Q THEN
                state := 0;
            END_IF;
    END_CASE;
END_FUNCTION_BLOCK

"#
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn generated_projects_parse_without_diagnostics_at_the_requested_size() {
        let src = generate(5_000);
        let lines = src.lines().count();
        assert!((4_900..5_200).contains(&lines), "{lines}");
        let mut sm = stc_diagnostics::SourceMap::new();
        sm.add("gen.st", src);
        let mut interner = stc_syntax::Interner::new();
        let (ast, diags) = stc_syntax::parse_project(&sm, &mut interner);
        assert!(diags.is_empty(), "{:?}", &diags[..diags.len().min(3)]);
        assert!(ast.items.len() > 200);
    }

    #[test]
    fn generated_circuit_projects_parse_at_the_requested_size() {
        let src = generate_circuit(5_000);
        let lines = src.lines().count();
        assert!((4_900..5_200).contains(&lines), "{lines}");
        let mut sm = stc_diagnostics::SourceMap::new();
        sm.add("gen.st", src);
        let mut interner = stc_syntax::Interner::new();
        let (_, diags) = stc_syntax::parse_project(&sm, &mut interner);
        assert!(diags.is_empty(), "{:?}", &diags[..diags.len().min(3)]);
    }
}
