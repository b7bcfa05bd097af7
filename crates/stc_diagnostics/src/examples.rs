//! A short example for each diagnostic code, printed by `stc explain` after
//! the explanation (as `rustc --explain` does): a complete source file that
//! gives the code and the same file corrected.
//!
//! The texts are data, kept apart from the catalogue in `codes.rs`. In the
//! wrong text, the line the diagnostic points at ends with a `// CODE`
//! comment. `crates/stc/tests/explain.rs` compiles every example through the
//! real pipeline: the wrong text gives exactly its code there, the right text
//! no diagnostic at all; a code without an example is listed in that test
//! with the reason (it cannot be shown in one short source text).

use crate::Code;

/// An example of a diagnostic: source that triggers it, and the corrected
/// source.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
pub struct Example {
    /// A complete source file that gives the code, on the line marked with
    /// a `// CODE` comment.
    pub wrong: &'static str,
    /// The same file corrected: it gives no diagnostic.
    pub right: &'static str,
}

/// The example of a code, if it has one.
pub fn example(code: Code) -> Option<Example> {
    EXAMPLES
        .iter()
        .find(|(c, _, _)| *c == code)
        .map(|&(_, wrong, right)| Example { wrong, right })
}

/// (code, wrong, right).
const EXAMPLES: &[(Code, &str, &str)] = &[
    // Lexical and syntax.
    (
        Code::E0001,
        r"PROGRAM Heater
VAR_OUTPUT
    setpoint : REAL;
END_VAR
    setpoint := 55.0°;   // E0001
END_PROGRAM
",
        r"PROGRAM Heater
VAR_OUTPUT
    setpoint : REAL;
END_VAR
    setpoint := 55.0;   (* degrees Celsius *)
END_PROGRAM
",
    ),
    (
        Code::E0002,
        r"PROGRAM Pump
VAR_INPUT
    start : BOOL;
END_VAR
VAR_OUTPUT
    running : BOOL;
END_VAR
    running := start;
    (* disabled until commissioning:   // E0002
    running := start AND level_ok;
END_PROGRAM
",
        r"PROGRAM Pump
VAR_INPUT
    start : BOOL;
END_VAR
VAR_OUTPUT
    running : BOOL;
END_VAR
    running := start;
    (* disabled until commissioning:
    running := start AND level_ok; *)
END_PROGRAM
",
    ),
    (
        Code::E0003,
        r"PROGRAM Tank
VAR_OUTPUT
    message : STRING;
END_VAR
    message := 'Tank full   // E0003
    ;
END_PROGRAM
",
        r"PROGRAM Tank
VAR_OUTPUT
    message : STRING;
END_VAR
    message := 'Tank full';
END_PROGRAM
",
    ),
    (
        Code::E0004,
        r"PROGRAM Pump
VAR_OUTPUT
    running : BOOL;
END_VAR
    { hide_in_hmi   // E0004
    running := TRUE;
END_PROGRAM
",
        r"PROGRAM Pump
VAR_OUTPUT
    running : BOOL;
END_VAR
    (* hide_in_hmi *)
    running := TRUE;
END_PROGRAM
",
    ),
    (
        Code::E0005,
        r"PROGRAM Pump
VAR_INPUT
    start : BOOL;
END_VAR
VAR_OUTPUT
    motor_läuft : BOOL;   // E0005
END_VAR
    motor_läuft := start;
END_PROGRAM
",
        r"PROGRAM Pump
VAR_INPUT
    start : BOOL;
END_VAR
VAR_OUTPUT
    motor_laeuft : BOOL;
END_VAR
    motor_laeuft := start;
END_PROGRAM
",
    ),
    (
        Code::E0006,
        r"PROGRAM AlarmMask
VAR_INPUT
    status : BYTE;
END_VAR
VAR_OUTPUT
    alarms : BYTE;
END_VAR
    alarms := status AND 2#0000_0120;   // E0006
END_PROGRAM
",
        r"PROGRAM AlarmMask
VAR_INPUT
    status : BYTE;
END_VAR
VAR_OUTPUT
    alarms : BYTE;
END_VAR
    alarms := status AND 2#0000_0110;
END_PROGRAM
",
    ),
    (
        Code::E0007,
        r"PROGRAM Maintenance
VAR_INPUT
    hours_run : TIME;
END_VAR
VAR_OUTPUT
    service_due : BOOL;
END_VAR
    service_due := hours_run > T#200000d;   // E0007
END_PROGRAM
",
        r"PROGRAM Maintenance
VAR_INPUT
    hours_run : TIME;
END_VAR
VAR_OUTPUT
    service_due : BOOL;
END_VAR
    service_due := hours_run > T#200d;
END_PROGRAM
",
    ),
    (
        Code::E0008,
        r"PROGRAM Lights
VAR_INPUT
    now : TOD;
END_VAR
VAR_OUTPUT
    on : BOOL;
END_VAR
    on := now >= TOD#24:00:00;   // E0008
END_PROGRAM
",
        r"PROGRAM Lights
VAR_INPUT
    now : TOD;
END_VAR
VAR_OUTPUT
    on : BOOL;
END_VAR
    on := now >= TOD#23:00:00;
END_PROGRAM
",
    ),
    (
        Code::E0009,
        r"PROGRAM Display
VAR_OUTPUT
    line1 : STRING;
END_VAR
    line1 := 'Energy cost: $5 per hour';   // E0009
END_PROGRAM
",
        r"PROGRAM Display
VAR_OUTPUT
    line1 : STRING;
END_VAR
    line1 := 'Energy cost: $$5 per hour';
END_PROGRAM
",
    ),
    (
        Code::E0010,
        r"PROGRAM Pump
VAR_OUTPUT
    running : BOOL;
END_VAR
    running := %IX;   // E0010
END_PROGRAM
",
        r"PROGRAM Pump
VAR_OUTPUT
    running : BOOL;
END_VAR
    running := %IX0.0;
END_PROGRAM
",
    ),
    (
        Code::E0020,
        r"PROGRAM Tank
VAR_INPUT
    level : INT;
END_VAR
VAR_OUTPUT
    inlet_open : BOOL;
END_VAR
    inlet_open := level < 80
    IF level > 95 THEN   // E0020
        inlet_open := FALSE;
    END_IF;
END_PROGRAM
",
        r"PROGRAM Tank
VAR_INPUT
    level : INT;
END_VAR
VAR_OUTPUT
    inlet_open : BOOL;
END_VAR
    inlet_open := level < 80;
    IF level > 95 THEN
        inlet_open := FALSE;
    END_IF;
END_PROGRAM
",
    ),
    (
        Code::E0021,
        r"PROGRAM Tank
VAR_INPUT
    level : INT;
END_VAR
VAR_OUTPUT
    inlet_open : BOOL;
END_VAR
    IF level < 80 THEN
        inlet_open := TRUE;
    END_WHILE;   // E0021
END_PROGRAM
",
        r"PROGRAM Tank
VAR_INPUT
    level : INT;
END_VAR
VAR_OUTPUT
    inlet_open : BOOL;
END_VAR
    IF level < 80 THEN
        inlet_open := TRUE;
    END_IF;
END_PROGRAM
",
    ),
    (
        Code::E0022,
        r"PROGRAM Tank
VAR_INPUT
    inflow : REAL;
END_VAR
VAR_OUTPUT
    volume : REAL;
END_VAR
VAR
    dt : REAL := 0.1;   // E0022
END_VAR
    volume := volume + inflow * dt;
END_PROGRAM
",
        r"PROGRAM Tank
VAR_INPUT
    inflow : REAL;
END_VAR
VAR_OUTPUT
    volume : REAL;
END_VAR
VAR
    cycle_s : REAL := 0.1;
END_VAR
    volume := volume + inflow * cycle_s;
END_PROGRAM
",
    ),
    (
        Code::E0030,
        r"PROGRAM Tank
VAR_OUTPUT
    level : INT;
END_VAR
VAR
    p_level : REFERENCE TO INT;   // E0030
END_VAR
    level := 50;
END_PROGRAM
",
        r"PROGRAM Tank
VAR_OUTPUT
    level : INT;
END_VAR
    level := 50;
END_PROGRAM
",
    ),
    (
        Code::W0002,
        r"PROGRAM Pump
VAR_OUTPUT
    running : BOOL;
END_VAR
    { hide_in_hmi }   // W0002
    running := TRUE;
END_PROGRAM
",
        r"PROGRAM Pump
VAR_OUTPUT
    running : BOOL;
END_VAR
    (* hide_in_hmi *)
    running := TRUE;
END_PROGRAM
",
    ),
    (
        Code::W0003,
        r"PROGRAM Pump
VAR_INPUT
    start, stop : BOOL;
END_VAR
VAR_OUTPUT
    running : BOOL;
END_VAR
    running := start AND NOT stop;
    (* disabled:
       (* old interlock   // W0003
    running := running AND start; *)
END_PROGRAM
",
        r"PROGRAM Pump
VAR_INPUT
    start, stop : BOOL;
END_VAR
VAR_OUTPUT
    running : BOOL;
END_VAR
    running := start AND NOT stop;
    (* disabled:
       old interlock
    running := running AND start; *)
END_PROGRAM
",
    ),
    // Names.
    (
        Code::E0101,
        r"PROGRAM Tank
VAR_INPUT
    inflow : INT;
END_VAR
VAR_OUTPUT
    level : INT;
END_VAR
    level := level + inflw;   // E0101
END_PROGRAM
",
        r"PROGRAM Tank
VAR_INPUT
    inflow : INT;
END_VAR
VAR_OUTPUT
    level : INT;
END_VAR
    level := level + inflow;
END_PROGRAM
",
    ),
    (
        Code::E0102,
        r"PROGRAM Tank
VAR_INPUT
    inflow : INT;
END_VAR
VAR_OUTPUT
    level : INTEGER;   // E0102
END_VAR
    level := level + inflow;
END_PROGRAM
",
        r"PROGRAM Tank
VAR_INPUT
    inflow : INT;
END_VAR
VAR_OUTPUT
    level : INT;
END_VAR
    level := level + inflow;
END_PROGRAM
",
    ),
    (
        Code::E0103,
        r"PROGRAM Tank
VAR_INPUT
    raw : INT;
END_VAR
VAR_OUTPUT
    level : INT;
END_VAR
    level := CLAMP(0, raw, 100);   // E0103
END_PROGRAM
",
        r"PROGRAM Tank
VAR_INPUT
    raw : INT;
END_VAR
VAR_OUTPUT
    level : INT;
END_VAR
    level := LIMIT(0, raw, 100);
END_PROGRAM
",
    ),
    (
        Code::E0104,
        r"PROGRAM Pump
VAR_INPUT
    start : BOOL;
END_VAR
VAR_OUTPUT
    running : BOOL;
END_VAR
VAR
    delay : TON;
END_VAR
    delay(IN := start, PT := T#5s);
    running := delay.DONE;   // E0104
END_PROGRAM
",
        r"PROGRAM Pump
VAR_INPUT
    start : BOOL;
END_VAR
VAR_OUTPUT
    running : BOOL;
END_VAR
VAR
    delay : TON;
END_VAR
    delay(IN := start, PT := T#5s);
    running := delay.Q;
END_PROGRAM
",
    ),
    (
        Code::E0105,
        r"PROGRAM Tank
VAR_INPUT
    raw : INT;
END_VAR
VAR_OUTPUT
    level : INT;
    Level : REAL;   // E0105
END_VAR
    level := raw / 10;
END_PROGRAM
",
        r"PROGRAM Tank
VAR_INPUT
    raw : INT;
END_VAR
VAR_OUTPUT
    level : INT;
    level_percent : REAL;
END_VAR
    level := raw / 10;
    level_percent := INT_TO_REAL(raw) / 10.0;
END_PROGRAM
",
    ),
    (
        Code::E0106,
        r"CONFIGURATION Plant
    RESOURCE Cpu ON PLC
        TASK Fast (INTERVAL := T#10ms, PRIORITY := 1);
        PROGRAM pump1 WITH Fats : Pump;   // E0106
    END_RESOURCE
END_CONFIGURATION

PROGRAM Pump
VAR_OUTPUT
    cycles : DINT;
END_VAR
    cycles := cycles + 1;
END_PROGRAM
",
        r"CONFIGURATION Plant
    RESOURCE Cpu ON PLC
        TASK Fast (INTERVAL := T#10ms, PRIORITY := 1);
        PROGRAM pump1 WITH Fast : Pump;
    END_RESOURCE
END_CONFIGURATION

PROGRAM Pump
VAR_OUTPUT
    cycles : DINT;
END_VAR
    cycles := cycles + 1;
END_PROGRAM
",
    ),
    (
        Code::E0107,
        r"CONFIGURATION Plant
    RESOURCE Cpu ON PLC
        TASK Fast (INTERVAL := T#10ms, PRIORITY := 1);
        PROGRAM pump1 WITH Fast : PumpControl;   // E0107
    END_RESOURCE
END_CONFIGURATION

PROGRAM Pump
VAR_OUTPUT
    cycles : DINT;
END_VAR
    cycles := cycles + 1;
END_PROGRAM
",
        r"CONFIGURATION Plant
    RESOURCE Cpu ON PLC
        TASK Fast (INTERVAL := T#10ms, PRIORITY := 1);
        PROGRAM pump1 WITH Fast : Pump;
    END_RESOURCE
END_CONFIGURATION

PROGRAM Pump
VAR_OUTPUT
    cycles : DINT;
END_VAR
    cycles := cycles + 1;
END_PROGRAM
",
    ),
    (
        Code::E0108,
        r"TYPE
    PumpState : (Stopped, Running, Fault);
    ValveState : (Closed, Open, Fault);
END_TYPE

PROGRAM Station
VAR_OUTPUT
    pump : PumpState;
    any_fault : BOOL;
END_VAR
    any_fault := Fault = Fault;   // E0108
    pump := Running;
END_PROGRAM
",
        r"TYPE
    PumpState : (Stopped, Running, Fault);
    ValveState : (Closed, Open, Fault);
END_TYPE

PROGRAM Station
VAR_OUTPUT
    pump : PumpState;
    any_fault : BOOL;
END_VAR
    any_fault := pump = PumpState#Fault;
    pump := Running;
END_PROGRAM
",
    ),
    (
        Code::E0109,
        r"TYPE
    PumpState : (Stopped, Running, Fault);
END_TYPE

PROGRAM Pump
VAR_INPUT
    start : BOOL;
END_VAR
VAR_OUTPUT
    state : PumpState;
END_VAR
    IF start THEN
        state := PumpState#Started;   // E0109
    END_IF;
END_PROGRAM
",
        r"TYPE
    PumpState : (Stopped, Running, Fault);
END_TYPE

PROGRAM Pump
VAR_INPUT
    start : BOOL;
END_VAR
VAR_OUTPUT
    state : PumpState;
END_VAR
    IF start THEN
        state := PumpState#Running;
    END_IF;
END_PROGRAM
",
    ),
    (
        Code::E0110,
        r"FUNCTION Scale : REAL
VAR_INPUT
    raw : INT;
END_VAR
    Scale := INT_TO_REAL(raw) / 10.0;
END_FUNCTION

PROGRAM Tank
VAR_INPUT
    raw : INT;
END_VAR
VAR_OUTPUT
    level : REAL;
END_VAR
    level := Scale;   // E0110
END_PROGRAM
",
        r"FUNCTION Scale : REAL
VAR_INPUT
    raw : INT;
END_VAR
    Scale := INT_TO_REAL(raw) / 10.0;
END_FUNCTION

PROGRAM Tank
VAR_INPUT
    raw : INT;
END_VAR
VAR_OUTPUT
    level : REAL;
END_VAR
    level := Scale(raw);
END_PROGRAM
",
    ),
    // Types in expressions.
    (
        Code::E0201,
        r"PROGRAM Pump
VAR_INPUT
    start : BOOL;
END_VAR
VAR_OUTPUT
    starts : INT;
END_VAR
    starts := starts + start;   // E0201
END_PROGRAM
",
        r"PROGRAM Pump
VAR_INPUT
    start : BOOL;
END_VAR
VAR_OUTPUT
    starts : INT;
END_VAR
    IF start THEN
        starts := starts + 1;
    END_IF;
END_PROGRAM
",
    ),
    (
        Code::E0202,
        r"PROGRAM Tank
VAR_INPUT
    faults : INT;
END_VAR
VAR_OUTPUT
    alarm : BOOL;
END_VAR
    IF faults THEN   // E0202
        alarm := TRUE;
    END_IF;
END_PROGRAM
",
        r"PROGRAM Tank
VAR_INPUT
    faults : INT;
END_VAR
VAR_OUTPUT
    alarm : BOOL;
END_VAR
    IF faults <> 0 THEN
        alarm := TRUE;
    END_IF;
END_PROGRAM
",
    ),
    (
        Code::E0203,
        r"TYPE
    PumpState : (Stopped, Running, Fault);
END_TYPE

PROGRAM Pump
VAR_INPUT
    state : PumpState;
END_VAR
VAR_OUTPUT
    speed : INT;
END_VAR
    CASE state OF
        Stopped: speed := 0;
        1: speed := 1500;   // E0203
    END_CASE;
END_PROGRAM
",
        r"TYPE
    PumpState : (Stopped, Running, Fault);
END_TYPE

PROGRAM Pump
VAR_INPUT
    state : PumpState;
END_VAR
VAR_OUTPUT
    speed : INT;
END_VAR
    CASE state OF
        Stopped: speed := 0;
        Running: speed := 1500;
    END_CASE;
END_PROGRAM
",
    ),
    (
        Code::E0204,
        r"PROGRAM Tanks
VAR_INPUT
    levels : ARRAY[1..4] OF REAL;
END_VAR
VAR_OUTPUT
    total : REAL;
END_VAR
VAR
    i : REAL;
END_VAR
    total := 0.0;
    FOR i := 1 TO 4 DO   // E0204
        total := total + levels[1];
    END_FOR;
END_PROGRAM
",
        r"PROGRAM Tanks
VAR_INPUT
    levels : ARRAY[1..4] OF REAL;
END_VAR
VAR_OUTPUT
    total : REAL;
END_VAR
VAR
    i : INT;
END_VAR
    total := 0.0;
    FOR i := 1 TO 4 DO
        total := total + levels[i];
    END_FOR;
END_PROGRAM
",
    ),
    (
        Code::E0205,
        r"PROGRAM Valve
VAR_INPUT
    position : REAL;
    flow_table : ARRAY[0..10] OF REAL;
END_VAR
VAR_OUTPUT
    flow : REAL;
END_VAR
    flow := flow_table[position / 10.0];   // E0205
END_PROGRAM
",
        r"PROGRAM Valve
VAR_INPUT
    position : REAL;
    flow_table : ARRAY[0..10] OF REAL;
END_VAR
VAR_OUTPUT
    flow : REAL;
END_VAR
    flow := flow_table[LIMIT(0, REAL_TO_INT(position / 10.0), 10)];
END_PROGRAM
",
    ),
    (
        Code::E0206,
        r"PROGRAM Tanks
VAR_INPUT
    levels : ARRAY[1..4] OF INT;
END_VAR
VAR_OUTPUT
    first : INT;
END_VAR
    first := levels[1, 1];   // E0206
END_PROGRAM
",
        r"PROGRAM Tanks
VAR_INPUT
    levels : ARRAY[1..4] OF INT;
END_VAR
VAR_OUTPUT
    first : INT;
END_VAR
    first := levels[1];
END_PROGRAM
",
    ),
    (
        Code::E0207,
        r"TYPE
    Tank : STRUCT
        level : INT;
        full : BOOL;
    END_STRUCT;
END_TYPE

PROGRAM Station
VAR_INPUT
    tanks : ARRAY[1..4] OF Tank;
END_VAR
VAR_OUTPUT
    first_full : BOOL;
END_VAR
    first_full := tanks.full;   // E0207
END_PROGRAM
",
        r"TYPE
    Tank : STRUCT
        level : INT;
        full : BOOL;
    END_STRUCT;
END_TYPE

PROGRAM Station
VAR_INPUT
    tanks : ARRAY[1..4] OF Tank;
END_VAR
VAR_OUTPUT
    first_full : BOOL;
END_VAR
    first_full := tanks[1].full;
END_PROGRAM
",
    ),
    (
        Code::E0208,
        r"PROGRAM Pump
VAR_INPUT
    start : BOOL;
END_VAR
VAR_OUTPUT
    running : BOOL;
END_VAR
VAR
    delay : TON;
    delay_time : TIME := 5000;   // E0208
END_VAR
    delay(IN := start, PT := delay_time);
    running := delay.Q;
END_PROGRAM
",
        r"PROGRAM Pump
VAR_INPUT
    start : BOOL;
END_VAR
VAR_OUTPUT
    running : BOOL;
END_VAR
VAR
    delay : TON;
    delay_time : TIME := T#5s;
END_VAR
    delay(IN := start, PT := delay_time);
    running := delay.Q;
END_PROGRAM
",
    ),
    // Assignment.
    (
        Code::E0301,
        r"PROGRAM Pump
VAR_INPUT
    start : BOOL;
END_VAR
VAR_OUTPUT
    elapsed_ms : DINT;
END_VAR
VAR
    delay : TON;
END_VAR
    delay(IN := start, PT := T#5s);
    elapsed_ms := delay.ET;   // E0301
END_PROGRAM
",
        r"PROGRAM Pump
VAR_INPUT
    start : BOOL;
END_VAR
VAR_OUTPUT
    elapsed_ms : DINT;
END_VAR
VAR
    delay : TON;
END_VAR
    delay(IN := start, PT := T#5s);
    elapsed_ms := TIME_TO_DINT(delay.ET);
END_PROGRAM
",
    ),
    (
        Code::E0302,
        r"PROGRAM Tank
VAR_INPUT
    raw_level : LREAL;
END_VAR
VAR_OUTPUT
    level : REAL;
END_VAR
    level := raw_level;   // E0302
END_PROGRAM
",
        r"PROGRAM Tank
VAR_INPUT
    raw_level : LREAL;
END_VAR
VAR_OUTPUT
    level : REAL;
END_VAR
    level := LREAL_TO_REAL(raw_level);
END_PROGRAM
",
    ),
    (
        Code::E0303,
        r"PROGRAM Pump
VAR_INPUT
    start : BOOL;
END_VAR
VAR_OUTPUT
    speed_rpm : INT;
END_VAR
    IF start THEN
        speed_rpm := 40000;   // E0303
    END_IF;
END_PROGRAM
",
        r"PROGRAM Pump
VAR_INPUT
    start : BOOL;
END_VAR
VAR_OUTPUT
    speed_rpm : UINT;
END_VAR
    IF start THEN
        speed_rpm := 40000;
    END_IF;
END_PROGRAM
",
    ),
    (
        Code::E0304,
        r"PROGRAM Tank
VAR_INPUT
    level : INT;
END_VAR
VAR_OUTPUT
    alarm : BOOL;
END_VAR
VAR CONSTANT
    MAX_LEVEL : INT := 90;
END_VAR
    MAX_LEVEL := 95;   // E0304
    alarm := level > MAX_LEVEL;
END_PROGRAM
",
        r"PROGRAM Tank
VAR_INPUT
    level : INT;
END_VAR
VAR_OUTPUT
    alarm : BOOL;
END_VAR
VAR CONSTANT
    MAX_LEVEL : INT := 95;
END_VAR
    alarm := level > MAX_LEVEL;
END_PROGRAM
",
    ),
    (
        Code::E0305,
        r"PROGRAM Pump
VAR_INPUT
    start, reset : BOOL;
END_VAR
VAR_OUTPUT
    running : BOOL;
END_VAR
VAR
    delay : TON;
END_VAR
    delay(IN := start, PT := T#5s);
    IF reset THEN
        delay.Q := FALSE;   // E0305
    END_IF;
    running := delay.Q;
END_PROGRAM
",
        r"PROGRAM Pump
VAR_INPUT
    start, reset : BOOL;
END_VAR
VAR_OUTPUT
    running : BOOL;
END_VAR
VAR
    delay : TON;
END_VAR
    delay(IN := start AND NOT reset, PT := T#5s);
    running := delay.Q;
END_PROGRAM
",
    ),
    (
        Code::E0306,
        r"PROGRAM Tanks
VAR_INPUT
    levels : ARRAY[1..4] OF INT;
END_VAR
VAR_OUTPUT
    first_empty : INT;
END_VAR
VAR
    i : INT;
END_VAR
    first_empty := 0;
    FOR i := 1 TO 4 DO
        IF levels[i] = 0 THEN
            first_empty := i;
            i := 4;   // E0306
        END_IF;
    END_FOR;
END_PROGRAM
",
        r"PROGRAM Tanks
VAR_INPUT
    levels : ARRAY[1..4] OF INT;
END_VAR
VAR_OUTPUT
    first_empty : INT;
END_VAR
VAR
    i : INT;
END_VAR
    first_empty := 0;
    FOR i := 1 TO 4 DO
        IF levels[i] = 0 THEN
            first_empty := i;
            EXIT;
        END_IF;
    END_FOR;
END_PROGRAM
",
    ),
    (
        Code::E0307,
        r"TYPE
    PumpMode : (Manual, Automatic);
END_TYPE

PROGRAM Pump
VAR_INPUT
    auto_switch : BOOL;
END_VAR
VAR_OUTPUT
    mode : PumpMode;
END_VAR
    IF auto_switch THEN
        Automatic := mode;   // E0307
    END_IF;
END_PROGRAM
",
        r"TYPE
    PumpMode : (Manual, Automatic);
END_TYPE

PROGRAM Pump
VAR_INPUT
    auto_switch : BOOL;
END_VAR
VAR_OUTPUT
    mode : PumpMode;
END_VAR
    IF auto_switch THEN
        mode := Automatic;
    END_IF;
END_PROGRAM
",
    ),
    // Calls.
    (
        Code::E0401,
        r"PROGRAM Pump
VAR_INPUT
    start : BOOL;
END_VAR
VAR_OUTPUT
    running : BOOL;
END_VAR
VAR
    delay : TON;
END_VAR
    delay(IN := start, PRESET := T#5s);   // E0401
    running := delay.Q;
END_PROGRAM
",
        r"PROGRAM Pump
VAR_INPUT
    start : BOOL;
END_VAR
VAR_OUTPUT
    running : BOOL;
END_VAR
VAR
    delay : TON;
END_VAR
    delay(IN := start, PT := T#5s);
    running := delay.Q;
END_PROGRAM
",
    ),
    (
        Code::E0402,
        r"FUNCTION_BLOCK Totalizer
VAR_INPUT
    flow : REAL;
END_VAR
VAR_IN_OUT
    total : REAL;
END_VAR
    total := total + flow;
END_FUNCTION_BLOCK

PROGRAM Plant
VAR_INPUT
    flow : REAL;
END_VAR
VAR_OUTPUT
    volume : REAL;
END_VAR
VAR
    meter : Totalizer;
END_VAR
    meter(flow := flow);   // E0402
END_PROGRAM
",
        r"FUNCTION_BLOCK Totalizer
VAR_INPUT
    flow : REAL;
END_VAR
VAR_IN_OUT
    total : REAL;
END_VAR
    total := total + flow;
END_FUNCTION_BLOCK

PROGRAM Plant
VAR_INPUT
    flow : REAL;
END_VAR
VAR_OUTPUT
    volume : REAL;
END_VAR
VAR
    meter : Totalizer;
END_VAR
    meter(flow := flow, total := volume);
END_PROGRAM
",
    ),
    (
        Code::E0403,
        r"PROGRAM Crane
VAR_INPUT
    dx, dy : REAL;
END_VAR
VAR_OUTPUT
    distance : REAL;
END_VAR
    distance := SQRT(dx * dx, dy * dy);   // E0403
END_PROGRAM
",
        r"PROGRAM Crane
VAR_INPUT
    dx, dy : REAL;
END_VAR
VAR_OUTPUT
    distance : REAL;
END_VAR
    distance := SQRT(dx * dx + dy * dy);
END_PROGRAM
",
    ),
    (
        Code::E0404,
        r"PROGRAM Tank
VAR_INPUT
    raw : INT;
END_VAR
VAR_OUTPUT
    level : INT;
END_VAR
    level := LIMIT(MN := 0, raw, 100);   // E0404
END_PROGRAM
",
        r"PROGRAM Tank
VAR_INPUT
    raw : INT;
END_VAR
VAR_OUTPUT
    level : INT;
END_VAR
    level := LIMIT(MN := 0, IN := raw, MX := 100);
END_PROGRAM
",
    ),
    (
        Code::E0405,
        r"PROGRAM Tank
VAR_INPUT
    raw : REAL;
    scale : REAL;
END_VAR
VAR_OUTPUT
    level : REAL;
END_VAR
    level := scale(raw);   // E0405
END_PROGRAM
",
        r"PROGRAM Tank
VAR_INPUT
    raw : REAL;
    scale : REAL;
END_VAR
VAR_OUTPUT
    level : REAL;
END_VAR
    level := raw * scale;
END_PROGRAM
",
    ),
    (
        Code::E0406,
        r"FUNCTION_BLOCK Totalizer
VAR_INPUT
    flow : REAL;
END_VAR
VAR_IN_OUT
    total : REAL;
END_VAR
    total := total + flow;
END_FUNCTION_BLOCK

PROGRAM Plant
VAR_INPUT
    flow : REAL;
END_VAR
VAR_OUTPUT
    volume : REAL;
END_VAR
VAR
    meter : Totalizer;
END_VAR
    meter(flow := flow, total := volume * 1000.0);   // E0406
END_PROGRAM
",
        r"FUNCTION_BLOCK Totalizer
VAR_INPUT
    flow : REAL;
END_VAR
VAR_IN_OUT
    total : REAL;
END_VAR
    total := total + flow;
END_FUNCTION_BLOCK

PROGRAM Plant
VAR_INPUT
    flow : REAL;
END_VAR
VAR_OUTPUT
    volume : REAL;
END_VAR
VAR
    meter : Totalizer;
END_VAR
    meter(flow := flow / 1000.0, total := volume);
END_PROGRAM
",
    ),
    (
        Code::E0407,
        r"PROGRAM Pump
VAR_INPUT
    start : BOOL;
END_VAR
VAR_OUTPUT
    running : BOOL;
END_VAR
VAR
    delay : TON;
END_VAR
    delay(IN := start, PT := 5000);   // E0407
    running := delay.Q;
END_PROGRAM
",
        r"PROGRAM Pump
VAR_INPUT
    start : BOOL;
END_VAR
VAR_OUTPUT
    running : BOOL;
END_VAR
VAR
    delay : TON;
END_VAR
    delay(IN := start, PT := T#5s);
    running := delay.Q;
END_PROGRAM
",
    ),
    (
        Code::E0408,
        r"PROGRAM Tank
VAR_INPUT
    raw : INT;
END_VAR
VAR_OUTPUT
    level : INT;
END_VAR
    level := LIMIT(MN := 0, IN := raw, MN := 100);   // E0408
END_PROGRAM
",
        r"PROGRAM Tank
VAR_INPUT
    raw : INT;
END_VAR
VAR_OUTPUT
    level : INT;
END_VAR
    level := LIMIT(MN := 0, IN := raw, MX := 100);
END_PROGRAM
",
    ),
    (
        Code::E0409,
        r"PROGRAM Pump
VAR_INPUT
    start : BOOL;
END_VAR
VAR_OUTPUT
    running : BOOL;
END_VAR
    TON(IN := start, PT := T#5s);   // E0409
    running := start;
END_PROGRAM
",
        r"PROGRAM Pump
VAR_INPUT
    start : BOOL;
END_VAR
VAR_OUTPUT
    running : BOOL;
END_VAR
VAR
    delay : TON;
END_VAR
    delay(IN := start, PT := T#5s);
    running := delay.Q;
END_PROGRAM
",
    ),
    (
        Code::E0410,
        r"PROGRAM Tank
VAR_INPUT
    demand : REAL;
END_VAR
VAR_OUTPUT
    valve : REAL;
END_VAR
    valve := LIMIT(0.0, demand);   // E0410
END_PROGRAM
",
        r"PROGRAM Tank
VAR_INPUT
    demand : REAL;
END_VAR
VAR_OUTPUT
    valve : REAL;
END_VAR
    valve := LIMIT(0.0, demand, 100.0);
END_PROGRAM
",
    ),
    // Program organisation units.
    (
        Code::E0501,
        r"FUNCTION Debounce : BOOL
VAR_INPUT
    raw : BOOL;
END_VAR
VAR
    filter : TON;   // E0501
END_VAR
    filter(IN := raw, PT := T#50ms);
    Debounce := filter.Q;
END_FUNCTION
",
        r"FUNCTION_BLOCK Debounce
VAR_INPUT
    raw : BOOL;
END_VAR
VAR_OUTPUT
    stable : BOOL;
END_VAR
VAR
    filter : TON;
END_VAR
    filter(IN := raw, PT := T#50ms);
    stable := filter.Q;
END_FUNCTION_BLOCK
",
    ),
    (
        Code::E0502,
        r"FUNCTION Debounce : BOOL
VAR_INPUT
    raw : BOOL;
END_VAR
VAR_IN_OUT
    filter : TON;
END_VAR
    filter(IN := raw, PT := T#50ms);   // E0502
    Debounce := filter.Q;
END_FUNCTION
",
        r"FUNCTION_BLOCK Debounce
VAR_INPUT
    raw : BOOL;
END_VAR
VAR_OUTPUT
    stable : BOOL;
END_VAR
VAR
    filter : TON;
END_VAR
    filter(IN := raw, PT := T#50ms);
    stable := filter.Q;
END_FUNCTION_BLOCK
",
    ),
    (
        Code::E0503,
        r"FUNCTION TotalVolume : REAL
VAR_INPUT
    tanks : INT;
    volume_each : REAL;
END_VAR
    IF tanks <= 0 THEN
        TotalVolume := 0.0;
    ELSE
        TotalVolume := volume_each
            + TotalVolume(tanks - 1, volume_each);   // E0503
    END_IF;
END_FUNCTION
",
        r"FUNCTION TotalVolume : REAL
VAR_INPUT
    tanks : INT;
    volume_each : REAL;
END_VAR
VAR
    i : INT;
END_VAR
    TotalVolume := 0.0;
    FOR i := 1 TO tanks DO
        TotalVolume := TotalVolume + volume_each;
    END_FOR;
END_FUNCTION
",
    ),
    (
        Code::E0504,
        r"PROGRAM Pump
VAR_INPUT
    start : BOOL;
END_VAR
VAR_OUTPUT
    running : BOOL;
END_VAR
    running := start;
END_PROGRAM

PROGRAM Station
VAR_INPUT
    start : BOOL;
END_VAR
VAR_OUTPUT
    running : BOOL;
END_VAR
VAR
    pump1 : Pump;   // E0504
END_VAR
    pump1(start := start);
    running := pump1.running;
END_PROGRAM
",
        r"FUNCTION_BLOCK Pump
VAR_INPUT
    start : BOOL;
END_VAR
VAR_OUTPUT
    running : BOOL;
END_VAR
    running := start;
END_FUNCTION_BLOCK

PROGRAM Station
VAR_INPUT
    start : BOOL;
END_VAR
VAR_OUTPUT
    running : BOOL;
END_VAR
VAR
    pump1 : Pump;
END_VAR
    pump1(start := start);
    running := pump1.running;
END_PROGRAM
",
    ),
    (
        Code::E0505,
        r"CONFIGURATION Plant
    VAR_GLOBAL
        tank_level : INT;
    END_VAR
    RESOURCE Cpu ON PLC
        TASK Fast (INTERVAL := T#10ms, PRIORITY := 1);
        PROGRAM pump1 WITH Fast : Pump;
    END_RESOURCE
END_CONFIGURATION

PROGRAM Pump
VAR_EXTERNAL
    tank_level : INT;
    max_level : INT;   // E0505
END_VAR
VAR_OUTPUT
    running : BOOL;
END_VAR
    running := tank_level < max_level;
END_PROGRAM
",
        r"CONFIGURATION Plant
    VAR_GLOBAL
        tank_level : INT;
        max_level : INT := 90;
    END_VAR
    RESOURCE Cpu ON PLC
        TASK Fast (INTERVAL := T#10ms, PRIORITY := 1);
        PROGRAM pump1 WITH Fast : Pump;
    END_RESOURCE
END_CONFIGURATION

PROGRAM Pump
VAR_EXTERNAL
    tank_level : INT;
    max_level : INT;
END_VAR
VAR_OUTPUT
    running : BOOL;
END_VAR
    running := tank_level < max_level;
END_PROGRAM
",
    ),
    (
        Code::E0506,
        r"CONFIGURATION Plant
    VAR_GLOBAL
        tank_level : INT;
    END_VAR
    RESOURCE Cpu ON PLC
        TASK Fast (INTERVAL := T#10ms, PRIORITY := 1);
        PROGRAM pump1 WITH Fast : Pump;
    END_RESOURCE
END_CONFIGURATION

PROGRAM Pump
VAR_EXTERNAL
    tank_level : REAL;   // E0506
END_VAR
VAR_OUTPUT
    running : BOOL;
END_VAR
    running := tank_level < 90.0;
END_PROGRAM
",
        r"CONFIGURATION Plant
    VAR_GLOBAL
        tank_level : INT;
    END_VAR
    RESOURCE Cpu ON PLC
        TASK Fast (INTERVAL := T#10ms, PRIORITY := 1);
        PROGRAM pump1 WITH Fast : Pump;
    END_RESOURCE
END_CONFIGURATION

PROGRAM Pump
VAR_EXTERNAL
    tank_level : INT;
END_VAR
VAR_OUTPUT
    running : BOOL;
END_VAR
    running := tank_level < 90;
END_PROGRAM
",
    ),
    (
        Code::E0507,
        r"FUNCTION StartPressed : BOOL
VAR_INPUT
    button : BOOL R_EDGE;   // E0507
END_VAR
    StartPressed := button;
END_FUNCTION
",
        r"FUNCTION_BLOCK StartPressed
VAR_INPUT
    button : BOOL R_EDGE;
END_VAR
VAR_OUTPUT
    pressed : BOOL;
END_VAR
    pressed := button;
END_FUNCTION_BLOCK
",
    ),
    // Control flow.
    (
        Code::E0601,
        r"PROGRAM Pump
VAR_INPUT
    start, dry_run : BOOL;
END_VAR
VAR_OUTPUT
    running : BOOL;
END_VAR
    IF dry_run THEN
        running := FALSE;
        EXIT;   // E0601
    END_IF;
    running := start;
END_PROGRAM
",
        r"PROGRAM Pump
VAR_INPUT
    start, dry_run : BOOL;
END_VAR
VAR_OUTPUT
    running : BOOL;
END_VAR
    IF dry_run THEN
        running := FALSE;
        RETURN;
    END_IF;
    running := start;
END_PROGRAM
",
    ),
    (
        Code::E0602,
        r"PROGRAM Tank
VAR_INPUT
    level : INT;
END_VAR
VAR_OUTPUT
    inlet_speed : INT;
END_VAR
    CASE level OF
        0..50: inlet_speed := 100;
        50..90: inlet_speed := 30;   // E0602
    ELSE
        inlet_speed := 0;
    END_CASE;
END_PROGRAM
",
        r"PROGRAM Tank
VAR_INPUT
    level : INT;
END_VAR
VAR_OUTPUT
    inlet_speed : INT;
END_VAR
    CASE level OF
        0..49: inlet_speed := 100;
        50..90: inlet_speed := 30;
    ELSE
        inlet_speed := 0;
    END_CASE;
END_PROGRAM
",
    ),
    (
        Code::E0603,
        r"PROGRAM Tank
VAR_INPUT
    level : INT;
    max_level : INT;
END_VAR
VAR_OUTPUT
    inlet_open : BOOL;
END_VAR
    CASE level OF
        0..max_level: inlet_open := TRUE;   // E0603
    ELSE
        inlet_open := FALSE;
    END_CASE;
END_PROGRAM
",
        r"PROGRAM Tank
VAR_INPUT
    level : INT;
    max_level : INT;
END_VAR
VAR_OUTPUT
    inlet_open : BOOL;
END_VAR
    inlet_open := level >= 0 AND level <= max_level;
END_PROGRAM
",
    ),
    (
        Code::E0604,
        r"PROGRAM Tanks
VAR_INPUT
    levels : ARRAY[1..8] OF INT;
END_VAR
VAR_OUTPUT
    odd_total : INT;
END_VAR
VAR CONSTANT
    STRIDE : INT := 0;
END_VAR
VAR
    i : INT;
END_VAR
    odd_total := 0;
    FOR i := 1 TO 7 BY STRIDE DO   // E0604
        odd_total := odd_total + levels[i];
    END_FOR;
END_PROGRAM
",
        r"PROGRAM Tanks
VAR_INPUT
    levels : ARRAY[1..8] OF INT;
END_VAR
VAR_OUTPUT
    odd_total : INT;
END_VAR
VAR CONSTANT
    STRIDE : INT := 2;
END_VAR
VAR
    i : INT;
END_VAR
    odd_total := 0;
    FOR i := 1 TO 7 BY STRIDE DO
        odd_total := odd_total + levels[i];
    END_FOR;
END_PROGRAM
",
    ),
    // Constant checks.
    (
        Code::E0701,
        r"PROGRAM Tanks
VAR_INPUT
    levels : ARRAY[0..3] OF INT;
END_VAR
VAR_OUTPUT
    last : INT;
END_VAR
    last := levels[4];   // E0701
END_PROGRAM
",
        r"PROGRAM Tanks
VAR_INPUT
    levels : ARRAY[0..3] OF INT;
END_VAR
VAR_OUTPUT
    last : INT;
END_VAR
    last := levels[3];
END_PROGRAM
",
    ),
    (
        Code::E0702,
        r"TYPE
    Percent : INT (0..100);
END_TYPE

PROGRAM Valve
VAR_INPUT
    open_fully : BOOL;
END_VAR
VAR_OUTPUT
    opening : Percent;
END_VAR
    IF open_fully THEN
        opening := 110;   // E0702
    END_IF;
END_PROGRAM
",
        r"TYPE
    Percent : INT (0..100);
END_TYPE

PROGRAM Valve
VAR_INPUT
    open_fully : BOOL;
END_VAR
VAR_OUTPUT
    opening : Percent;
END_VAR
    IF open_fully THEN
        opening := 100;
    END_IF;
END_PROGRAM
",
    ),
    (
        Code::E0703,
        r"PROGRAM Tank
VAR_INPUT
    volume : REAL;
END_VAR
VAR_OUTPUT
    per_tank : INT;
END_VAR
VAR CONSTANT
    TANKS : INT := 0;
END_VAR
    per_tank := REAL_TO_INT(volume) / TANKS;   // E0703
END_PROGRAM
",
        r"PROGRAM Tank
VAR_INPUT
    volume : REAL;
END_VAR
VAR_OUTPUT
    per_tank : INT;
END_VAR
VAR CONSTANT
    TANKS : INT := 4;
END_VAR
    per_tank := REAL_TO_INT(volume) / TANKS;
END_PROGRAM
",
    ),
    (
        Code::E0704,
        r"PROGRAM Tank
VAR
    level AT %IX0.0 : INT;   // E0704
END_VAR
VAR_OUTPUT
    full : BOOL;
END_VAR
    full := level > 90;
END_PROGRAM
",
        r"PROGRAM Tank
VAR
    level AT %IW0 : INT;
END_VAR
VAR_OUTPUT
    full : BOOL;
END_VAR
    full := level > 90;
END_PROGRAM
",
    ),
    (
        Code::E0705,
        r"PROGRAM Tanks
VAR_INPUT
    levels : ARRAY[4..1] OF INT;   // E0705
END_VAR
VAR_OUTPUT
    first : INT;
END_VAR
    first := levels[1];
END_PROGRAM
",
        r"PROGRAM Tanks
VAR_INPUT
    levels : ARRAY[1..4] OF INT;
END_VAR
VAR_OUTPUT
    first : INT;
END_VAR
    first := levels[1];
END_PROGRAM
",
    ),
    // Configuration.
    (
        Code::E0801,
        r"CONFIGURATION Plant
    RESOURCE Cpu ON PLC
        TASK Fast (INTERVAL := 10, PRIORITY := 1);   // E0801
        PROGRAM pump1 WITH Fast : Pump;
    END_RESOURCE
END_CONFIGURATION

PROGRAM Pump
VAR_OUTPUT
    cycles : DINT;
END_VAR
    cycles := cycles + 1;
END_PROGRAM
",
        r"CONFIGURATION Plant
    RESOURCE Cpu ON PLC
        TASK Fast (INTERVAL := T#10ms, PRIORITY := 1);
        PROGRAM pump1 WITH Fast : Pump;
    END_RESOURCE
END_CONFIGURATION

PROGRAM Pump
VAR_OUTPUT
    cycles : DINT;
END_VAR
    cycles := cycles + 1;
END_PROGRAM
",
    ),
    (
        Code::E0802,
        r"CONFIGURATION Plant
    RESOURCE Cpu ON PLC
        TASK Fast (INTERVAL := T#10ms, PRIORITY := -1);   // E0802
        PROGRAM pump1 WITH Fast : Pump;
    END_RESOURCE
END_CONFIGURATION

PROGRAM Pump
VAR_OUTPUT
    cycles : DINT;
END_VAR
    cycles := cycles + 1;
END_PROGRAM
",
        r"CONFIGURATION Plant
    RESOURCE Cpu ON PLC
        TASK Fast (INTERVAL := T#10ms, PRIORITY := 0);
        PROGRAM pump1 WITH Fast : Pump;
    END_RESOURCE
END_CONFIGURATION

PROGRAM Pump
VAR_OUTPUT
    cycles : DINT;
END_VAR
    cycles := cycles + 1;
END_PROGRAM
",
    ),
    (
        Code::E0803,
        r"CONFIGURATION Plant
    VAR_GLOBAL
        start_button : BOOL;
        pump_speed : INT;
    END_VAR
    RESOURCE Cpu ON PLC
        TASK Fast (INTERVAL := T#10ms, PRIORITY := 1);
        PROGRAM pump1 WITH Fast : Pump (start := pump_speed);   // E0803
    END_RESOURCE
END_CONFIGURATION

PROGRAM Pump
VAR_INPUT
    start : BOOL;
END_VAR
VAR_OUTPUT
    running : BOOL;
END_VAR
    running := start;
END_PROGRAM
",
        r"CONFIGURATION Plant
    VAR_GLOBAL
        start_button : BOOL;
        pump_speed : INT;
    END_VAR
    RESOURCE Cpu ON PLC
        TASK Fast (INTERVAL := T#10ms, PRIORITY := 1);
        PROGRAM pump1 WITH Fast : Pump (start := start_button);
    END_RESOURCE
END_CONFIGURATION

PROGRAM Pump
VAR_INPUT
    start : BOOL;
END_VAR
VAR_OUTPUT
    running : BOOL;
END_VAR
    running := start;
END_PROGRAM
",
    ),
    (
        Code::E0804,
        r"CONFIGURATION Plant
    VAR_GLOBAL
        alarm_count : INT;
        alarm : BOOL;
    END_VAR
    RESOURCE Cpu ON PLC
        TASK OnAlarm (SINGLE := alarm_count, PRIORITY := 1);   // E0804
        PROGRAM logger WITH OnAlarm : Logger;
    END_RESOURCE
END_CONFIGURATION

PROGRAM Logger
VAR_OUTPUT
    events : DINT;
END_VAR
    events := events + 1;
END_PROGRAM
",
        r"CONFIGURATION Plant
    VAR_GLOBAL
        alarm_count : INT;
        alarm : BOOL;
    END_VAR
    RESOURCE Cpu ON PLC
        TASK OnAlarm (SINGLE := alarm, PRIORITY := 1);
        PROGRAM logger WITH OnAlarm : Logger;
    END_RESOURCE
END_CONFIGURATION

PROGRAM Logger
VAR_OUTPUT
    events : DINT;
END_VAR
    events := events + 1;
END_PROGRAM
",
    ),
    // Memory model.
    (
        Code::E0901,
        r"TYPE
    Trace : ARRAY[1..100000] OF LREAL;
END_TYPE

PROGRAM Logger
VAR_INPUT
    level : LREAL;
END_VAR
VAR
    history : ARRAY[1..2000] OF Trace;   // E0901
END_VAR
    history[1][1] := level;
END_PROGRAM
",
        r"TYPE
    Trace : ARRAY[1..100000] OF LREAL;
END_TYPE

PROGRAM Logger
VAR_INPUT
    level : LREAL;
END_VAR
VAR
    history : ARRAY[1..10] OF Trace;
END_VAR
    history[1][1] := level;
END_PROGRAM
",
    ),
    // Warnings.
    (
        Code::W0101,
        r"FUNCTION ReadLevel : INT
VAR_INPUT
    raw : INT;
END_VAR
VAR_OUTPUT
    fault : BOOL;
END_VAR
    fault := raw < 0;
    ReadLevel := raw / 10;
END_FUNCTION

PROGRAM Tank
VAR_INPUT
    raw : INT;
END_VAR
VAR_OUTPUT
    level : INT;
    fault : BOOL;
END_VAR
    level := SEL(fault, ReadLevel(raw := raw, fault => fault), 0);   // W0101
END_PROGRAM
",
        r"FUNCTION ReadLevel : INT
VAR_INPUT
    raw : INT;
END_VAR
VAR_OUTPUT
    fault : BOOL;
END_VAR
    fault := raw < 0;
    ReadLevel := raw / 10;
END_FUNCTION

PROGRAM Tank
VAR_INPUT
    raw : INT;
END_VAR
VAR_OUTPUT
    level : INT;
    fault : BOOL;
END_VAR
    level := ReadLevel(raw := raw, fault => fault);
    level := SEL(fault, level, 0);
END_PROGRAM
",
    ),
    (
        Code::W0102,
        r"TYPE
    PumpState : (Stopped, Running, Fault);
END_TYPE

PROGRAM Valve
VAR_INPUT
    open_cmd : BOOL;
END_VAR
VAR
    state : (Stopped, Opening, Open);
END_VAR
    IF open_cmd THEN
        state := Opening;
    ELSE
        state := Stopped;   // W0102
    END_IF;
END_PROGRAM
",
        r"TYPE
    PumpState : (Stopped, Running, Fault);
    ValveState : (Closed, Opening, Open);
END_TYPE

PROGRAM Valve
VAR_INPUT
    open_cmd : BOOL;
END_VAR
VAR
    state : ValveState;
END_VAR
    IF open_cmd THEN
        state := Opening;
    ELSE
        state := Closed;
    END_IF;
END_PROGRAM
",
    ),
    (
        Code::W0103,
        r"FUNCTION_BLOCK Heater
VAR_INPUT
    setpoint : REAL;
END_VAR
VAR_OUTPUT
    target : REAL;
END_VAR
    IF setpoint > 80.0 THEN
        setpoint := 80.0;   // W0103
    END_IF;
    target := setpoint;
END_FUNCTION_BLOCK
",
        r"FUNCTION_BLOCK Heater
VAR_INPUT
    setpoint : REAL;
END_VAR
VAR_OUTPUT
    target : REAL;
END_VAR
    target := MIN(setpoint, 80.0);
END_FUNCTION_BLOCK
",
    ),
    (
        Code::W0104,
        r"PROGRAM Tank
VAR_INPUT
    inflow : INT;
END_VAR
VAR_OUTPUT
    level : INT;
END_VAR
VAR
    old_level : INT;   // W0104
END_VAR
    level := level + inflow;
END_PROGRAM
",
        r"PROGRAM Tank
VAR_INPUT
    inflow : INT;
END_VAR
VAR_OUTPUT
    level : INT;
END_VAR
    level := level + inflow;
END_PROGRAM
",
    ),
    (
        Code::W0105,
        r"PROGRAM Pump
VAR_INPUT
    start, enable : BOOL;
END_VAR
VAR_OUTPUT
    running : BOOL;
END_VAR
    IF NOT enable THEN
        RETURN;
        running := FALSE;   // W0105
    END_IF;
    running := start;
END_PROGRAM
",
        r"PROGRAM Pump
VAR_INPUT
    start, enable : BOOL;
END_VAR
VAR_OUTPUT
    running : BOOL;
END_VAR
    IF NOT enable THEN
        running := FALSE;
        RETURN;
    END_IF;
    running := start;
END_PROGRAM
",
    ),
    (
        Code::W0106,
        r"FUNCTION FillPercent : INT   // W0106
VAR_INPUT
    level, capacity : INT;
END_VAR
    IF capacity > 0 THEN
        FillPercent := level * 100 / capacity;
    END_IF;
END_FUNCTION
",
        r"FUNCTION FillPercent : INT
VAR_INPUT
    level, capacity : INT;
END_VAR
    IF capacity > 0 THEN
        FillPercent := level * 100 / capacity;
    ELSE
        FillPercent := 0;
    END_IF;
END_FUNCTION
",
    ),
    (
        Code::W0107,
        r"PROGRAM Pump
VAR_INPUT
    run_ms : INT;
END_VAR
VAR_OUTPUT
    long_run : BOOL;
END_VAR
VAR CONSTANT
    ONE_MINUTE_MS : INT := 60 * 1000;   // W0107
END_VAR
    long_run := run_ms > ONE_MINUTE_MS;
END_PROGRAM
",
        r"PROGRAM Pump
VAR_INPUT
    run_ms : DINT;
END_VAR
VAR_OUTPUT
    long_run : BOOL;
END_VAR
VAR CONSTANT
    ONE_MINUTE_MS : DINT := 60 * 1000;
END_VAR
    long_run := run_ms > ONE_MINUTE_MS;
END_PROGRAM
",
    ),
    (
        Code::W0108,
        r"PROGRAM Tank
VAR_INPUT
    sensor_level : INT;
END_VAR
VAR_OUTPUT
    level : INT;
END_VAR
VAR CONSTANT
    SIMULATION : BOOL := FALSE;
END_VAR
    IF SIMULATION THEN   // W0108
        level := 50;
    ELSE
        level := sensor_level;
    END_IF;
END_PROGRAM
",
        r"PROGRAM Tank
VAR_INPUT
    sensor_level : INT;
    simulation : BOOL;
END_VAR
VAR_OUTPUT
    level : INT;
END_VAR
    IF simulation THEN
        level := 50;
    ELSE
        level := sensor_level;
    END_IF;
END_PROGRAM
",
    ),
    (
        Code::W0109,
        r"FUNCTION_BLOCK Valve
VAR_INPUT
    open_cmd : BOOL;
END_VAR
VAR_OUTPUT
    is_open : BOOL;
END_VAR
    is_open := open_cmd;
END_FUNCTION_BLOCK

PROGRAM Station
VAR_INPUT
    level : INT;
END_VAR
VAR_OUTPUT
    inlet_open : BOOL;
END_VAR
VAR
    valve : BOOL;   // W0109
END_VAR
    valve := level < 80;
    inlet_open := valve;
END_PROGRAM
",
        r"FUNCTION_BLOCK Valve
VAR_INPUT
    open_cmd : BOOL;
END_VAR
VAR_OUTPUT
    is_open : BOOL;
END_VAR
    is_open := open_cmd;
END_FUNCTION_BLOCK

PROGRAM Station
VAR_INPUT
    level : INT;
END_VAR
VAR_OUTPUT
    inlet_open : BOOL;
END_VAR
VAR
    inlet : Valve;
END_VAR
    inlet(open_cmd := level < 80);
    inlet_open := inlet.is_open;
END_PROGRAM
",
    ),
    (
        Code::W0110,
        r"FUNCTION LIMIT : REAL   // W0110
VAR_INPUT
    value, low, high : REAL;
END_VAR
    LIMIT := MIN(MAX(value, low), high);
END_FUNCTION

PROGRAM Tank
VAR_INPUT
    raw : REAL;
END_VAR
VAR_OUTPUT
    level : REAL;
END_VAR
    level := LIMIT(raw, 0.0, 100.0);
END_PROGRAM
",
        r"FUNCTION Clamp : REAL
VAR_INPUT
    value, low, high : REAL;
END_VAR
    Clamp := MIN(MAX(value, low), high);
END_FUNCTION

PROGRAM Tank
VAR_INPUT
    raw : REAL;
END_VAR
VAR_OUTPUT
    level : REAL;
END_VAR
    level := Clamp(raw, 0.0, 100.0);
END_PROGRAM
",
    ),
    (
        Code::W0004,
        r"PROGRAM Heater
VAR_INPUT
    cold : BOOL;
END_VAR
VAR_OUTPUT
    heat : BOOL;
END_VAR
    IF cold THEN
        heat := TRUE;
    END_IF   // W0004
    heat := heat AND cold;
END_PROGRAM
",
        r"PROGRAM Heater
VAR_INPUT
    cold : BOOL;
END_VAR
VAR_OUTPUT
    heat : BOOL;
END_VAR
    IF cold THEN
        heat := TRUE;
    END_IF;
    heat := heat AND cold;
END_PROGRAM
",
    ),
    (
        Code::W0005,
        r"PROGRAM Heater
VAR_INPUT
    cold : BOOL;
END_VAR
VAR_OUTPUT
    heat : BOOL;
END_VAR
    IF cold THEN
        heat := TRUE   // W0005
    ELSE
        heat := FALSE;
    END_IF;
END_PROGRAM
",
        r"PROGRAM Heater
VAR_INPUT
    cold : BOOL;
END_VAR
VAR_OUTPUT
    heat : BOOL;
END_VAR
    IF cold THEN
        heat := TRUE;
    ELSE
        heat := FALSE;
    END_IF;
END_PROGRAM
",
    ),
    (
        Code::W0006,
        r"PROGRAM Levels
VAR_OUTPUT
    total : INT;
END_VAR
VAR
    level : ARRAY[1..3] OF INT := 10, 20, 30;   // W0006
END_VAR
    total := level[1] + level[2] + level[3];
END_PROGRAM
",
        r"PROGRAM Levels
VAR_OUTPUT
    total : INT;
END_VAR
VAR
    level : ARRAY[1..3] OF INT := [10, 20, 30];
END_VAR
    total := level[1] + level[2] + level[3];
END_PROGRAM
",
    ),
    (
        Code::W0007,
        r"PROGRAM Shift
VAR_INPUT
    now : TOD;
END_VAR
VAR_OUTPUT
    day_shift : BOOL;
END_VAR
    day_shift := now >= TOD#06:30;   // W0007
END_PROGRAM
",
        r"PROGRAM Shift
VAR_INPUT
    now : TOD;
END_VAR
VAR_OUTPUT
    day_shift : BOOL;
END_VAR
    day_shift := now >= TOD#06:30:00;
END_PROGRAM
",
    ),
    (
        Code::W0008,
        r"PROGRAM Pump
VAR_INPUT
    start : BOOL;
END_VAR
VAR_OUTPUT
    running_ : BOOL;   // W0008
END_VAR
    running_ := start;
END_PROGRAM
",
        r"PROGRAM Pump
VAR_INPUT
    start : BOOL;
END_VAR
VAR_OUTPUT
    running : BOOL;
END_VAR
    running := start;
END_PROGRAM
",
    ),
    (
        Code::W0009,
        r"PROGRAM Display
VAR_INPUT
    code : BYTE;
END_VAR
VAR_OUTPUT
    char : BYTE;   // W0009
END_VAR
    char := code;
END_PROGRAM
",
        r"PROGRAM Display
VAR_INPUT
    code : BYTE;
END_VAR
VAR_OUTPUT
    shown : BYTE;
END_VAR
    shown := code;
END_PROGRAM
",
    ),
    (
        Code::W0113,
        r"PROGRAM Checksum
VAR_INPUT
    data : DWORD;
END_VAR
VAR_OUTPUT
    sum : DWORD;
END_VAR
    sum := sum + data;   // W0113
END_PROGRAM
",
        r"PROGRAM Checksum
VAR_INPUT
    data : DWORD;
END_VAR
VAR_OUTPUT
    sum : UDINT;
END_VAR
    sum := sum + DWORD_TO_UDINT(data);
END_PROGRAM
",
    ),
    (
        Code::W0114,
        r"VAR_GLOBAL
    level : REAL;
END_VAR
PROGRAM Tank
VAR_OUTPUT
    full : BOOL;
END_VAR
    full := level > 95.0;   // W0114
END_PROGRAM
",
        r"VAR_GLOBAL
    level : REAL;
END_VAR
PROGRAM Tank
VAR_EXTERNAL
    level : REAL;
END_VAR
VAR_OUTPUT
    full : BOOL;
END_VAR
    full := level > 95.0;
END_PROGRAM
",
    ),
    (
        Code::W0115,
        r"FUNCTION_BLOCK Ramp
VAR_IN_OUT
    level : REAL;
END_VAR
    level := level + 1.0;
END_FUNCTION_BLOCK
PROGRAM Main
VAR
    r : Ramp;
    x : REAL;
    y : REAL;
END_VAR
    r(level := x);
    y := r.level;   // W0115
END_PROGRAM
",
        r"FUNCTION_BLOCK Ramp
VAR_IN_OUT
    level : REAL;
END_VAR
    level := level + 1.0;
END_FUNCTION_BLOCK
PROGRAM Main
VAR
    r : Ramp;
    x : REAL;
    y : REAL;
END_VAR
    r(level := x);
    y := x;
END_PROGRAM
",
    ),
    (
        Code::W0112,
        r"PROGRAM Tank
VAR_INPUT
    full : BOOL;
END_VAR
VAR_OUTPUT
    level : REAL;
END_VAR
    level := BOOL_TO_REAL(full);   // W0112
END_PROGRAM
",
        r"PROGRAM Tank
VAR_INPUT
    full : BOOL;
END_VAR
VAR_OUTPUT
    level : REAL;
END_VAR
    level := SEL(full, 0.0, 1.0);
END_PROGRAM
",
    ),
    (
        Code::E1001,
        r"FUNCTION Double : INT
VAR_INPUT
    x : INT;
END_VAR
    ADD x   // E1001
    ST Double
END_FUNCTION
",
        r"FUNCTION Double : INT
VAR_INPUT
    x : INT;
END_VAR
    LD x
    ADD x
    ST Double
END_FUNCTION
",
    ),
    (
        Code::E1002,
        r"FUNCTION Clamp : INT
VAR_INPUT
    x : INT;
END_VAR
    LD x
    JMPCN positive   // E1002
    LD 0
    ST Clamp
    RET
positive:
    LD x
    ST Clamp
END_FUNCTION
",
        r"FUNCTION Clamp : INT
VAR_INPUT
    x : INT;
END_VAR
    LD x
    LT 0
    JMPCN positive
    LD 0
    ST Clamp
    RET
positive:
    LD x
    ST Clamp
END_FUNCTION
",
    ),
    (
        Code::E1003,
        r"FUNCTION Clamp : INT
VAR_INPUT
    x : INT;
END_VAR
    LD x
    ST Clamp
    LT 0
    JMPCN finish   // E1003
    LD 0
    ST Clamp
done:
    RET
END_FUNCTION
",
        r"FUNCTION Clamp : INT
VAR_INPUT
    x : INT;
END_VAR
    LD x
    ST Clamp
    LT 0
    JMPCN done
    LD 0
    ST Clamp
done:
    RET
END_FUNCTION
",
    ),
    (
        Code::E1004,
        r"FUNCTION Clamp : INT
VAR_INPUT
    x : INT;
END_VAR
    LD x
    LT 0
    JMPC done
    LD x
    ST Clamp
    RET
done:
    LD Clamp
done:   // E1004
    ST Clamp
END_FUNCTION
",
        r"FUNCTION Clamp : INT
VAR_INPUT
    x : INT;
END_VAR
    LD x
    ST Clamp
    LT 0
    JMPCN done
    LD 0
    ST Clamp
done:
    RET
END_FUNCTION
",
    ),
    // Sequential Function Chart.
    (
        Code::W1203,
        r"PROGRAM Press
VAR
    go : BOOL;
END_VAR
INITIAL_STEP Idle :
END_STEP
STEP Left :
END_STEP
STEP Right :
END_STEP
TRANSITION FROM Idle TO Left := go;
END_TRANSITION
TRANSITION FROM Idle TO Right := NOT go;
END_TRANSITION
TRANSITION FROM (Left, Right) TO Idle := TRUE;   // W1203
END_TRANSITION
END_PROGRAM
",
        r"PROGRAM Press
VAR
    go : BOOL;
END_VAR
INITIAL_STEP Idle :
END_STEP
STEP Left :
END_STEP
STEP Right :
END_STEP
TRANSITION FROM Idle TO (Left, Right) := go;
END_TRANSITION
TRANSITION FROM (Left, Right) TO Idle := TRUE;
END_TRANSITION
END_PROGRAM
",
    ),
    (
        Code::W1204,
        r"PROGRAM Press
VAR
    go : BOOL;
END_VAR
INITIAL_STEP Idle :
END_STEP
STEP A :
END_STEP
STEP B :
END_STEP
TRANSITION FROM Idle TO (A, B) := go;
END_TRANSITION
TRANSITION FROM A TO B := TRUE;   // W1204
END_TRANSITION
TRANSITION FROM (A, B) TO Idle := NOT go;
END_TRANSITION
END_PROGRAM
",
        r"PROGRAM Press
VAR
    go : BOOL;
END_VAR
INITIAL_STEP Idle :
END_STEP
STEP A :
END_STEP
STEP B :
END_STEP
TRANSITION FROM Idle TO (A, B) := go;
END_TRANSITION
TRANSITION FROM (A, B) TO Idle := NOT go;
END_TRANSITION
END_PROGRAM
",
    ),
    (
        Code::E1201,
        r"FUNCTION Next : INT
VAR_INPUT
    go : BOOL;
END_VAR
INITIAL_STEP Idle :   // E1201
END_STEP
STEP Run :
END_STEP
TRANSITION FROM Idle TO Run := go;
END_TRANSITION
END_FUNCTION
",
        r"FUNCTION_BLOCK Next
VAR_INPUT
    go : BOOL;
END_VAR
INITIAL_STEP Idle :
END_STEP
STEP Run :
END_STEP
TRANSITION FROM Idle TO Run := go;
END_TRANSITION
END_FUNCTION_BLOCK
",
    ),
    (
        Code::E1202,
        r"PROGRAM Press
VAR
    go : BOOL;
END_VAR
STEP Idle :   // E1202
END_STEP
STEP Run :
END_STEP
TRANSITION FROM Idle TO Run := go;
END_TRANSITION
END_PROGRAM
",
        r"PROGRAM Press
VAR
    go : BOOL;
END_VAR
INITIAL_STEP Idle :
END_STEP
STEP Run :
END_STEP
TRANSITION FROM Idle TO Run := go;
END_TRANSITION
END_PROGRAM
",
    ),
    (
        Code::E1203,
        r"PROGRAM Press
VAR
    go : BOOL;
END_VAR
INITIAL_STEP Idle :
END_STEP
INITIAL_STEP Run :   // E1203
END_STEP
TRANSITION FROM Idle TO Run := go;
END_TRANSITION
END_PROGRAM
",
        r"PROGRAM Press
VAR
    go : BOOL;
END_VAR
INITIAL_STEP Idle :
END_STEP
STEP Run :
END_STEP
TRANSITION FROM Idle TO Run := go;
END_TRANSITION
END_PROGRAM
",
    ),
    (
        Code::E1204,
        r"PROGRAM Press
VAR
    go : BOOL;
END_VAR
INITIAL_STEP Idle :
END_STEP
STEP Run :
END_STEP
TRANSITION FROM Idle TO Running := go;   // E1204
END_TRANSITION
END_PROGRAM
",
        r"PROGRAM Press
VAR
    go : BOOL;
END_VAR
INITIAL_STEP Idle :
END_STEP
STEP Run :
END_STEP
TRANSITION FROM Idle TO Run := go;
END_TRANSITION
END_PROGRAM
",
    ),
    (
        Code::E1205,
        r"PROGRAM Press
VAR
    go : BOOL;
END_VAR
INITIAL_STEP Idle :
END_STEP
STEP Run :
    Motor(N);   // E1205
END_STEP
TRANSITION FROM Idle TO Run := go;
END_TRANSITION
END_PROGRAM
",
        r"PROGRAM Press
VAR
    go : BOOL;
    Motor : BOOL;
END_VAR
INITIAL_STEP Idle :
END_STEP
STEP Run :
    Motor(N);
END_STEP
TRANSITION FROM Idle TO Run := go;
END_TRANSITION
END_PROGRAM
",
    ),
    (
        Code::E1206,
        r"PROGRAM Press
VAR
    go : BOOL;
END_VAR
INITIAL_STEP Idle :
END_STEP
STEP Run :
END_STEP
STEP Run :   // E1206
END_STEP
TRANSITION FROM Idle TO Run := go;
END_TRANSITION
END_PROGRAM
",
        r"PROGRAM Press
VAR
    go : BOOL;
END_VAR
INITIAL_STEP Idle :
END_STEP
STEP Run :
END_STEP
TRANSITION FROM Idle TO Run := go;
END_TRANSITION
END_PROGRAM
",
    ),
    (
        Code::E1207,
        r"PROGRAM Press
VAR
    go : BOOL;
END_VAR
INITIAL_STEP Idle :
END_STEP
STEP Run :
END_STEP
TRANSITION (PRIORITY := -1) FROM Idle TO Run := go;   // E1207
END_TRANSITION
END_PROGRAM
",
        r"PROGRAM Press
VAR
    go : BOOL;
END_VAR
INITIAL_STEP Idle :
END_STEP
STEP Run :
END_STEP
TRANSITION (PRIORITY := 1) FROM Idle TO Run := go;
END_TRANSITION
END_PROGRAM
",
    ),
    (
        Code::E1208,
        r"PROGRAM Press
VAR
    go : BOOL;
END_VAR
INITIAL_STEP Idle :
    Start(N);
END_STEP
STEP Run :
END_STEP
TRANSITION FROM Idle TO Run := go;
END_TRANSITION
ACTION Start :
    Run.X := go;   // E1208
END_ACTION
END_PROGRAM
",
        r"PROGRAM Press
VAR
    go : BOOL;
    started : BOOL;
END_VAR
INITIAL_STEP Idle :
    Start(N);
END_STEP
STEP Run :
END_STEP
TRANSITION FROM Idle TO Run := go;
END_TRANSITION
ACTION Start :
    started := go;
END_ACTION
END_PROGRAM
",
    ),
    (
        Code::E1209,
        r"PROGRAM Press
VAR
    level : INT;
END_VAR
INITIAL_STEP Idle :
END_STEP
STEP Run :
END_STEP
TRANSITION FROM Idle TO Run :   // E1209
    level := level + 1;
END_TRANSITION
END_PROGRAM
",
        r"PROGRAM Press
VAR
    level : INT;
END_VAR
INITIAL_STEP Idle :
END_STEP
STEP Run :
END_STEP
TRANSITION Full FROM Idle TO Run :
    level := level + 1;
    Full := level > 10;
END_TRANSITION
END_PROGRAM
",
    ),
    (
        Code::E1210,
        r"PROGRAM Press
VAR
    level : INT;
END_VAR
INITIAL_STEP Idle :
END_STEP
STEP Run :
END_STEP
TRANSITION FROM Idle TO Run :
    LD level
    ADD 1      // E1210
END_TRANSITION
END_PROGRAM
",
        r"PROGRAM Press
VAR
    level : INT;
END_VAR
INITIAL_STEP Idle :
END_STEP
STEP Run :
END_STEP
TRANSITION FROM Idle TO Run :
    LD level
    ADD 1
    GT 10
END_TRANSITION
END_PROGRAM
",
    ),
    (
        Code::E1211,
        r"PROGRAM Press
VAR
    go : BOOL;
END_VAR
INITIAL_STEP Idle :
    Start(N);
END_STEP
STEP Run :
END_STEP
TRANSITION FROM Idle TO Run := go;
END_TRANSITION
ACTION Start :
    Start.Q := go;   // E1211
END_ACTION
END_PROGRAM
",
        r"PROGRAM Press
VAR
    go : BOOL;
    last_scan : BOOL;
END_VAR
INITIAL_STEP Idle :
    Start(N);
END_STEP
STEP Run :
END_STEP
TRANSITION FROM Idle TO Run := go;
END_TRANSITION
ACTION Start :
    last_scan := NOT Start.Q;
END_ACTION
END_PROGRAM
",
    ),
    (
        Code::E1212,
        r"PROGRAM Press
VAR
    go : BOOL;
    count : INT;
END_VAR
INITIAL_STEP Idle :
    Start(N, count);   // E1212
END_STEP
STEP Run :
END_STEP
TRANSITION FROM Idle TO Run := go;
END_TRANSITION
ACTION Start :
    count := count + 1;
END_ACTION
END_PROGRAM
",
        r"PROGRAM Press
VAR
    go : BOOL;
    count : INT;
    counted : BOOL;
END_VAR
INITIAL_STEP Idle :
    Start(N, counted);
END_STEP
STEP Run :
END_STEP
TRANSITION FROM Idle TO Run := go;
END_TRANSITION
ACTION Start :
    count := count + 1;
    counted := TRUE;
END_ACTION
END_PROGRAM
",
    ),
    (
        Code::E1213,
        r"PROGRAM Press
VAR
    go, busy : BOOL;
END_VAR
INITIAL_STEP Idle :
    Start(N);
END_STEP
STEP Run :
END_STEP
TRANSITION FROM Idle TO Run := go;
END_TRANSITION
ACTION Start :
    LD busy
    RETC       // E1213
    LD go
    ST busy
END_ACTION
END_PROGRAM
",
        r"PROGRAM Press
VAR
    go, busy : BOOL;
END_VAR
INITIAL_STEP Idle :
    Start(N);
END_STEP
STEP Run :
END_STEP
TRANSITION FROM Idle TO Run := go;
END_TRANSITION
ACTION Start :
    LD busy
    JMPC done
    LD go
    ST busy
done:
END_ACTION
END_PROGRAM
",
    ),
    (
        Code::W1201,
        r"PROGRAM Press
VAR
    go : BOOL;
END_VAR
INITIAL_STEP Idle :
END_STEP
STEP Run :
END_STEP
STEP Stop :   // W1201
END_STEP
TRANSITION FROM Idle TO Run := go;
END_TRANSITION
END_PROGRAM
",
        r"PROGRAM Press
VAR
    go : BOOL;
END_VAR
INITIAL_STEP Idle :
END_STEP
STEP Run :
END_STEP
STEP Stop :
END_STEP
TRANSITION FROM Idle TO Run := go;
END_TRANSITION
TRANSITION FROM Run TO Stop := NOT go;
END_TRANSITION
END_PROGRAM
",
    ),
    (
        Code::W1202,
        r"PROGRAM Press
VAR
    go : BOOL;
    n : INT;
END_VAR
INITIAL_STEP Idle :
END_STEP
STEP Run :
END_STEP
TRANSITION FROM Idle TO Run := go;
END_TRANSITION
ACTION Count :   // W1202
    n := n + 1;
END_ACTION
END_PROGRAM
",
        r"PROGRAM Press
VAR
    go : BOOL;
    n : INT;
END_VAR
INITIAL_STEP Idle :
END_STEP
STEP Run :
    Count(N);
END_STEP
TRANSITION FROM Idle TO Run := go;
END_TRANSITION
ACTION Count :
    n := n + 1;
END_ACTION
END_PROGRAM
",
    ),
    // Object orientation and references.
    (
        Code::E1301,
        r"PROGRAM Main
VAR
    x : INT;
    y : INT;
END_VAR
    y := x^;   // E1301
END_PROGRAM
",
        r"PROGRAM Main
VAR
    x : INT;
    r : REF_TO INT;
    y : INT;
END_VAR
    r := REF(x);
    y := r^;
END_PROGRAM
",
    ),
    (
        Code::E1302,
        r"PROGRAM Main
VAR
    x : INT;
    r : REF_TO INT;
END_VAR
    r := REF(x + 1);   // E1302
    r^ := 0;
END_PROGRAM
",
        r"PROGRAM Main
VAR
    x : INT;
    r : REF_TO INT;
END_VAR
    r := REF(x);
    r^ := 0;
END_PROGRAM
",
    ),
    (
        Code::E1303,
        r"FUNCTION Scale : INT
VAR
    tmp : INT;
    r : REF_TO INT;
END_VAR
    r := REF(tmp);   // E1303
    Scale := r^;
END_FUNCTION
",
        r"FUNCTION_BLOCK Scale
VAR_OUTPUT
    out : INT;
END_VAR
VAR
    tmp : INT;
    r : REF_TO INT;
END_VAR
    r := REF(tmp);
    out := r^;
END_FUNCTION_BLOCK
",
    ),
    (
        Code::E1304,
        r"PROGRAM Main
VAR
    d : DINT;
    r : REF_TO INT;
END_VAR
    r := REF(d);   // E1304
    r^ := 1;
END_PROGRAM
",
        r"PROGRAM Main
VAR
    d : DINT;
    r : REF_TO DINT;
END_VAR
    r := REF(d);
    r^ := 1;
END_PROGRAM
",
    ),
    (
        Code::E1305,
        r"PROGRAM Main
VAR CONSTANT
    limit : INT := 10;
END_VAR
VAR
    r : REF_TO INT;
END_VAR
    r := REF(limit);   // E1305
    r^ := 0;
END_PROGRAM
",
        r"PROGRAM Main
VAR
    limit : INT := 10;
    r : REF_TO INT;
END_VAR
    r := REF(limit);
    r^ := 0;
END_PROGRAM
",
    ),
    (
        Code::E1306,
        r"PROGRAM Main
VAR
    x : INT;
    r : REF_TO INT := REF(x);   // E1306
END_VAR
    r^ := 1;
END_PROGRAM
",
        r"PROGRAM Main
VAR
    x : INT;
    r : REF_TO INT := NULL;
END_VAR
    r := REF(x);
    r^ := 1;
END_PROGRAM
",
    ),
    (
        Code::E1307,
        r"PROGRAM Main
VAR
    x : INT;
    r : REF_TO INT;
    y : INT;
END_VAR
    r := REF(x);
    y := r + 1;   // E1307
END_PROGRAM
",
        r"PROGRAM Main
VAR
    x : INT;
    r : REF_TO INT;
    y : INT;
END_VAR
    r := REF(x);
    y := r^ + 1;
END_PROGRAM
",
    ),
    (
        Code::E1308,
        r"PROGRAM Main
VAR RETAIN
    r : REF_TO INT;   // E1308
END_VAR
VAR
    x : INT;
END_VAR
    r := REF(x);
    r^ := 1;
END_PROGRAM
",
        r"PROGRAM Main
VAR
    r : REF_TO INT;
    x : INT;
END_VAR
    r := REF(x);
    r^ := 1;
END_PROGRAM
",
    ),
    (
        Code::E1309,
        r"FUNCTION_BLOCK Pump
VAR
    speed : INT;
END_VAR
METHOD OVERRIDE Stop   // E1309
    speed := 0;
END_METHOD
END_FUNCTION_BLOCK
",
        r"FUNCTION_BLOCK Pump
VAR
    speed : INT;
END_VAR
METHOD Stop
    speed := 0;
END_METHOD
END_FUNCTION_BLOCK
",
    ),
    (
        Code::E1310,
        r"FUNCTION_BLOCK Pump
METHOD Start
END_METHOD
END_FUNCTION_BLOCK

PROGRAM Main
VAR
    p : Pump;
END_VAR
    p.Launch();   // E1310
END_PROGRAM
",
        r"FUNCTION_BLOCK Pump
METHOD Start
END_METHOD
END_FUNCTION_BLOCK

PROGRAM Main
VAR
    p : Pump;
END_VAR
    p.Start();
END_PROGRAM
",
    ),
    (
        Code::E1311,
        r"FUNCTION_BLOCK Pump
METHOD PRIVATE Tune
END_METHOD
END_FUNCTION_BLOCK

PROGRAM Main
VAR
    p : Pump;
END_VAR
    p.Tune();   // E1311
END_PROGRAM
",
        r"FUNCTION_BLOCK Pump
METHOD PUBLIC Tune
END_METHOD
END_FUNCTION_BLOCK

PROGRAM Main
VAR
    p : Pump;
END_VAR
    p.Tune();
END_PROGRAM
",
    ),
    (
        Code::E1312,
        r"PROGRAM Main
VAR_OUTPUT
    x : INT;
END_VAR
    THIS^.x := 1;   // E1312
END_PROGRAM
",
        r"PROGRAM Main
VAR_OUTPUT
    x : INT;
END_VAR
    x := 1;
END_PROGRAM
",
    ),
    (
        Code::E1313,
        r"FUNCTION_BLOCK Pump
METHOD Start
END_METHOD
METHOD Restart
    SUPER^.Start();   // E1313
END_METHOD
END_FUNCTION_BLOCK
",
        r"FUNCTION_BLOCK Pump
METHOD Start
END_METHOD
METHOD Restart
    THIS^.Start();
END_METHOD
END_FUNCTION_BLOCK
",
    ),
    (
        Code::E1314,
        r"FUNCTION_BLOCK Pump
METHOD ABSTRACT Drain   // E1314
END_METHOD
END_FUNCTION_BLOCK
",
        r"FUNCTION_BLOCK Pump
METHOD Drain
END_METHOD
END_FUNCTION_BLOCK
",
    ),
    (
        Code::E1315,
        r"FUNCTION_BLOCK Pump
VAR_OUTPUT
    speed : INT;
END_VAR
METHOD speed   // E1315
END_METHOD
END_FUNCTION_BLOCK
",
        r"FUNCTION_BLOCK Pump
VAR
    speed : INT;
END_VAR
METHOD SetSpeed
    speed := 1;
END_METHOD
END_FUNCTION_BLOCK
",
    ),
    (
        Code::E1316,
        r"FUNCTION_BLOCK ABSTRACT Shape
METHOD ABSTRACT Area : REAL
END_METHOD
END_FUNCTION_BLOCK

PROGRAM Main
VAR
    s : Shape;   // E1316
    r : REF_TO Shape;
END_VAR
    r := REF(s);
END_PROGRAM
",
        r"FUNCTION_BLOCK Shape
METHOD Area : REAL
    Area := 1.0;
END_METHOD
END_FUNCTION_BLOCK

PROGRAM Main
VAR
    s : Shape;
    r : REF_TO Shape;
END_VAR
    r := REF(s);
END_PROGRAM
",
    ),
    (
        Code::E1317,
        r"FUNCTION Helper : INT
    Helper := 1;
END_FUNCTION

FUNCTION_BLOCK Motor EXTENDS Helper // E1317
END_FUNCTION_BLOCK
",
        r"FUNCTION_BLOCK Helper
END_FUNCTION_BLOCK

FUNCTION_BLOCK Motor EXTENDS Helper
END_FUNCTION_BLOCK
",
    ),
    (
        Code::E1318,
        r"CLASS Counter
VAR
    n : INT;
END_VAR
    n := n + 1; // E1318
END_CLASS
",
        r"CLASS Counter
VAR
    n : INT;
END_VAR
METHOD PUBLIC Step
    n := n + 1;
END_METHOD
END_CLASS
",
    ),
    (
        Code::E1319,
        r"FUNCTION_BLOCK A EXTENDS B // E1319
END_FUNCTION_BLOCK

FUNCTION_BLOCK B EXTENDS A
END_FUNCTION_BLOCK
",
        r"FUNCTION_BLOCK A
END_FUNCTION_BLOCK

FUNCTION_BLOCK B EXTENDS A
END_FUNCTION_BLOCK
",
    ),
    (
        Code::E1320,
        r"FUNCTION_BLOCK FINAL Base
END_FUNCTION_BLOCK

FUNCTION_BLOCK Derived EXTENDS Base // E1320
END_FUNCTION_BLOCK
",
        r"FUNCTION_BLOCK Base
END_FUNCTION_BLOCK

FUNCTION_BLOCK Derived EXTENDS Base
END_FUNCTION_BLOCK
",
    ),
    (
        Code::E1321,
        r"FUNCTION_BLOCK Base
METHOD FINAL Stop
END_METHOD
END_FUNCTION_BLOCK

FUNCTION_BLOCK Derived EXTENDS Base
METHOD OVERRIDE Stop // E1321
END_METHOD
END_FUNCTION_BLOCK
",
        r"FUNCTION_BLOCK Base
METHOD FINAL Stop
END_METHOD
END_FUNCTION_BLOCK

FUNCTION_BLOCK Derived EXTENDS Base
METHOD Halt
END_METHOD
END_FUNCTION_BLOCK
",
    ),
    (
        Code::E1322,
        r"FUNCTION_BLOCK Base
METHOD Scale : INT
VAR_INPUT k : INT; END_VAR
    Scale := k;
END_METHOD
END_FUNCTION_BLOCK

FUNCTION_BLOCK Derived EXTENDS Base
METHOD OVERRIDE Scale : INT // E1322
VAR_INPUT k : REAL; END_VAR
    Scale := 2;
END_METHOD
END_FUNCTION_BLOCK
",
        r"FUNCTION_BLOCK Base
METHOD Scale : INT
VAR_INPUT k : INT; END_VAR
    Scale := k;
END_METHOD
END_FUNCTION_BLOCK

FUNCTION_BLOCK Derived EXTENDS Base
METHOD OVERRIDE Scale : INT
VAR_INPUT k : INT; END_VAR
    Scale := 2 * k;
END_METHOD
END_FUNCTION_BLOCK
",
    ),
    (
        Code::E1323,
        r"FUNCTION_BLOCK ABSTRACT Shape
METHOD ABSTRACT Area : REAL
END_METHOD
END_FUNCTION_BLOCK

FUNCTION_BLOCK Square EXTENDS Shape // E1323
END_FUNCTION_BLOCK
",
        r"FUNCTION_BLOCK ABSTRACT Shape
METHOD ABSTRACT Area : REAL
END_METHOD
END_FUNCTION_BLOCK

FUNCTION_BLOCK Square EXTENDS Shape
METHOD OVERRIDE Area : REAL
    Area := 1.0;
END_METHOD
END_FUNCTION_BLOCK
",
    ),
    (
        Code::E1324,
        r"INTERFACE IRun
METHOD Go
END_METHOD
END_INTERFACE

FUNCTION_BLOCK Motor IMPLEMENTS IRun // E1324
END_FUNCTION_BLOCK
",
        r"INTERFACE IRun
METHOD Go
END_METHOD
END_INTERFACE

FUNCTION_BLOCK Motor IMPLEMENTS IRun
METHOD PUBLIC Go
END_METHOD
END_FUNCTION_BLOCK
",
    ),
    (
        Code::E1325,
        r"INTERFACE IRun
METHOD Go : INT
END_METHOD
END_INTERFACE

FUNCTION_BLOCK Motor IMPLEMENTS IRun
METHOD PUBLIC Go : BOOL // E1325
    Go := TRUE;
END_METHOD
END_FUNCTION_BLOCK
",
        r"INTERFACE IRun
METHOD Go : INT
END_METHOD
END_INTERFACE

FUNCTION_BLOCK Motor IMPLEMENTS IRun
METHOD PUBLIC Go : INT
    Go := 1;
END_METHOD
END_FUNCTION_BLOCK
",
    ),
    (
        Code::E1326,
        r"INTERFACE IRun
METHOD Go
END_METHOD
END_INTERFACE

FUNCTION_BLOCK Motor
METHOD PUBLIC Go
END_METHOD
END_FUNCTION_BLOCK

PROGRAM Main
VAR
    m : Motor;
    r : IRun;
END_VAR
    r := m; // E1326
    r.Go();
END_PROGRAM
",
        r"INTERFACE IRun
METHOD Go
END_METHOD
END_INTERFACE

FUNCTION_BLOCK Motor IMPLEMENTS IRun
METHOD PUBLIC Go
END_METHOD
END_FUNCTION_BLOCK

PROGRAM Main
VAR
    m : Motor;
    r : IRun;
END_VAR
    r := m;
    r.Go();
END_PROGRAM
",
    ),
    (
        Code::E1327,
        r"FUNCTION_BLOCK Motor
END_FUNCTION_BLOCK

PROGRAM Main
VAR
    n : INT;
    m : Motor;
    rn : REF_TO INT;
    rm : REF_TO Motor;
END_VAR
    rn := REF(n);
    rm ?= rn; // E1327
    m();
END_PROGRAM
",
        r"FUNCTION_BLOCK Motor
END_FUNCTION_BLOCK

PROGRAM Main
VAR
    n : INT;
    m : Motor;
    rn : REF_TO INT;
    rm : REF_TO Motor;
END_VAR
    rn := REF(n);
    rm := REF(m);
    m();
END_PROGRAM
",
    ),
    (
        Code::W0116,
        r"PROGRAM Main
VAR
    x : INT := -8;
    half : INT;
END_VAR
    half := SHR(x, 1); // W0116
END_PROGRAM
",
        r"PROGRAM Main
VAR
    x : INT := -8;
    half : INT;
END_VAR
    half := WORD_TO_INT(SHR(INT_TO_WORD(x), 1));
END_PROGRAM
",
    ),
    (
        Code::W0117,
        r"PROGRAM Main
    VAR
        t : Tc2_Standard.TON; // W0117
    END_VAR
    t(IN := TRUE, PT := T#1s);
END_PROGRAM
",
        r"PROGRAM Main
    VAR
        t : TON;
    END_VAR
    t(IN := TRUE, PT := T#1s);
END_PROGRAM
",
    ),
    (
        Code::W0118,
        r"PROGRAM Main
    VAR
        count : INT := -1;
        size : UINT;
    END_VAR
    size := count; // W0118
END_PROGRAM
",
        r"PROGRAM Main
    VAR
        count : INT := -1;
        size : UINT;
    END_VAR
    size := INT_TO_UINT(count);
END_PROGRAM
",
    ),
    (
        Code::E1328,
        r"FUNCTION_BLOCK Gauge
VAR level : INT := 3; END_VAR
PROPERTY Level2 : INT
GET
    Level2 := level * 2;
END_GET
END_PROPERTY
END_FUNCTION_BLOCK

PROGRAM Main
VAR g : Gauge; x : INT; END_VAR
    g.Level2 := 4; // E1328
    x := g.Level2;
END_PROGRAM
",
        r"FUNCTION_BLOCK Gauge
VAR level : INT := 3; END_VAR
PROPERTY Level2 : INT
GET
    Level2 := level * 2;
END_GET
END_PROPERTY
END_FUNCTION_BLOCK

PROGRAM Main
VAR g : Gauge; x : INT; END_VAR
    x := g.Level2;
END_PROGRAM
",
    ),
    (
        Code::E1329,
        r"NAMESPACE Drives
    FUNCTION Scale : INT
        VAR_INPUT x : INT; END_VAR
        Scale := x * 2;
    END_FUNCTION
END_NAMESPACE

PROGRAM Main
    USING Drive; // E1329
    VAR y : INT; END_VAR
    y := Drives.Scale(2);
END_PROGRAM
",
        r"NAMESPACE Drives
    FUNCTION Scale : INT
        VAR_INPUT x : INT; END_VAR
        Scale := x * 2;
    END_FUNCTION
END_NAMESPACE

PROGRAM Main
    USING Drives;
    VAR y : INT; END_VAR
    y := Scale(2);
END_PROGRAM
",
    ),
    (
        Code::E1330,
        r"NAMESPACE A
    FUNCTION F : INT
        F := 1;
    END_FUNCTION
END_NAMESPACE

NAMESPACE B
    FUNCTION F : INT
        F := 2;
    END_FUNCTION
END_NAMESPACE

PROGRAM Main
    USING A, B;
    VAR y : INT; END_VAR
    y := F(); // E1330
END_PROGRAM
",
        r"NAMESPACE A
    FUNCTION F : INT
        F := 1;
    END_FUNCTION
END_NAMESPACE

NAMESPACE B
    FUNCTION F : INT
        F := 2;
    END_FUNCTION
END_NAMESPACE

PROGRAM Main
    USING A, B;
    VAR y : INT; END_VAR
    y := B.F();
END_PROGRAM
",
    ),
    (
        Code::E1331,
        r"NAMESPACE Lib
    FUNCTION INTERNAL Helper : INT
        Helper := 7;
    END_FUNCTION
END_NAMESPACE

PROGRAM Main
    VAR y : INT; END_VAR
    y := Lib.Helper(); // E1331
END_PROGRAM
",
        r"NAMESPACE Lib
    FUNCTION INTERNAL Helper : INT
        Helper := 7;
    END_FUNCTION

    FUNCTION Value : INT
        Value := Helper();
    END_FUNCTION
END_NAMESPACE

PROGRAM Main
    VAR y : INT; END_VAR
    y := Lib.Value();
END_PROGRAM
",
    ),
    (
        Code::E1332,
        r"NAMESPACE Lib
    PROGRAM Main // E1332
        VAR y : INT; END_VAR
        y := 1;
    END_PROGRAM
END_NAMESPACE
",
        r"NAMESPACE Lib
    FUNCTION One : INT
        One := 1;
    END_FUNCTION
END_NAMESPACE

PROGRAM Main
    VAR y : INT; END_VAR
    y := Lib.One();
END_PROGRAM
",
    ),
    (
        Code::E1401,
        r"PROGRAM Main
VAR
    x : INT;
    p : POINTER TO INT;
END_VAR
    p := ADR(x + 1); // E1401
    x := p^;
END_PROGRAM
",
        r"PROGRAM Main
VAR
    x : INT;
    p : POINTER TO INT;
END_VAR
    p := ADR(x);
    x := p^ + 1;
END_PROGRAM
",
    ),
    (
        Code::E1402,
        r"PROGRAM Main
VAR
    r : REAL;
    d : DWORD;
    p : POINTER TO DWORD;
END_VAR
    p := ADR(r); // E1402
    d := p^;
END_PROGRAM
",
        r"PROGRAM Main
VAR
    r : REAL;
    d : DWORD;
    p : POINTER TO REAL;
END_VAR
    p := ADR(r);
    d := REAL_TO_DWORD(p^);
END_PROGRAM
",
    ),
    (
        Code::E1403,
        r"PROGRAM Main
VAR
    a : ARRAY[0..3] OF INT;
    p : POINTER TO INT;
END_VAR
    p := ADR(a);
    p := p * 2; // E1403
    a[0] := p^;
END_PROGRAM
",
        r"PROGRAM Main
VAR
    a : ARRAY[0..3] OF INT;
    p : POINTER TO INT;
END_VAR
    p := ADR(a);
    p := p + 2;
    a[0] := p^;
END_PROGRAM
",
    ),
    (
        Code::E1404,
        r"FUNCTION_BLOCK Keeper
VAR_TEMP t : INT; END_VAR
VAR p : POINTER TO INT; END_VAR
    p := ADR(t); // E1404
    t := p^;
END_FUNCTION_BLOCK

PROGRAM Main
VAR k : Keeper; END_VAR
    k();
END_PROGRAM
",
        r"FUNCTION_BLOCK Keeper
VAR t : INT; p : POINTER TO INT; END_VAR
    p := ADR(t);
    t := p^;
END_FUNCTION_BLOCK

PROGRAM Main
VAR k : Keeper; END_VAR
    k();
END_PROGRAM
",
    ),
    (
        Code::E1405,
        r"FUNCTION_BLOCK Motor
END_FUNCTION_BLOCK

PROGRAM Main
VAR
    m : Motor;
    n : UDINT;
END_VAR
    n := SIZEOF(m); // E1405
    m();
END_PROGRAM
",
        r"TYPE Setting : STRUCT speed : INT; limit : REAL; END_STRUCT; END_TYPE

PROGRAM Main
VAR
    s : Setting;
    n : UDINT;
END_VAR
    n := SIZEOF(s);
    s.speed := 1;
END_PROGRAM
",
    ),
    (
        Code::W1317,
        r"FUNCTION_BLOCK Base
METHOD Reset
END_METHOD
END_FUNCTION_BLOCK

FUNCTION_BLOCK Derived EXTENDS Base
METHOD Reset // W1317
END_METHOD
END_FUNCTION_BLOCK
",
        r"FUNCTION_BLOCK Base
METHOD Reset
END_METHOD
END_FUNCTION_BLOCK

FUNCTION_BLOCK Derived EXTENDS Base
METHOD OVERRIDE Reset
END_METHOD
END_FUNCTION_BLOCK
",
    ),
    // Lints (each shown with only its own lint on).
    (
        Code::L0001,
        r"PROGRAM Tank
VAR_INPUT
    level : INT;
END_VAR
VAR_OUTPUT
    full : BOOL;
END_VAR
    full := level > 950;   // L0001
END_PROGRAM
",
        r"PROGRAM Tank
VAR_INPUT
    level : INT;
END_VAR
VAR_OUTPUT
    full : BOOL;
END_VAR
VAR CONSTANT
    max_level : INT := 950;
END_VAR
    full := level > max_level;
END_PROGRAM
",
    ),
    (
        Code::L0002,
        r"PROGRAM Pump
VAR_OUTPUT
    running : BOOL;
END_VAR
    running := %IX0.3;   // L0002
END_PROGRAM
",
        r"PROGRAM Pump
VAR
    start AT %IX0.3 : BOOL;
END_VAR
VAR_OUTPUT
    running : BOOL;
END_VAR
    running := start;
END_PROGRAM
",
    ),
    (
        Code::L0003,
        r"PROGRAM Blink
VAR
    tmr : TON;
END_VAR
VAR_OUTPUT
    lamp : BOOL;
END_VAR
    lamp := tmr.Q;   // L0003
    tmr(IN := NOT lamp, PT := T#1s);
END_PROGRAM
",
        r"PROGRAM Blink
VAR
    tmr : TON;
END_VAR
VAR_OUTPUT
    lamp : BOOL;
END_VAR
    tmr(IN := NOT lamp, PT := T#1s);
    lamp := tmr.Q;
END_PROGRAM
",
    ),
    (
        Code::L0004,
        r"VAR_GLOBAL
    speed : INT;
END_VAR

FUNCTION Scale : INT
VAR_INPUT
    speed : INT;   // L0004
END_VAR
    Scale := speed * 2;
END_FUNCTION
",
        r"VAR_GLOBAL
    speed : INT;
END_VAR

FUNCTION Scale : INT
VAR_INPUT
    value : INT;
END_VAR
    Scale := value * 2;
END_FUNCTION
",
    ),
    (
        Code::L0005,
        r"FUNCTION_BLOCK Valve
VAR_INPUT
    open : BOOL;
    force : BOOL;   // L0005
END_VAR
VAR_OUTPUT
    opened : BOOL;
END_VAR
    opened := open;
END_FUNCTION_BLOCK
",
        r"FUNCTION_BLOCK Valve
VAR_INPUT
    open : BOOL;
    force : BOOL;
END_VAR
VAR_OUTPUT
    opened : BOOL;
END_VAR
    opened := open OR force;
END_FUNCTION_BLOCK
",
    ),
    (
        Code::L0006,
        r"PROGRAM Fan
VAR_INPUT
    mode : INT;
END_VAR
VAR_OUTPUT
    speed : INT;
END_VAR
    CASE mode OF   // L0006
        0: speed := 0;
        1: speed := 100;
    END_CASE;
END_PROGRAM
",
        r"PROGRAM Fan
VAR_INPUT
    mode : INT;
END_VAR
VAR_OUTPUT
    speed : INT;
END_VAR
    CASE mode OF
        0: speed := 0;
        1: speed := 100;
    ELSE
        speed := 0;
    END_CASE;
END_PROGRAM
",
    ),
    (
        Code::L0007,
        r"PROGRAM Compare
VAR_INPUT
    a, b : REAL;
END_VAR
VAR_OUTPUT
    same : BOOL;
END_VAR
    same := a = b;   // L0007
END_PROGRAM
",
        r"PROGRAM Compare
VAR_INPUT
    a, b : REAL;
END_VAR
VAR_OUTPUT
    same : BOOL;
END_VAR
    same := ABS(a - b) < 1.0E-6;
END_PROGRAM
",
    ),
    (
        Code::L0008,
        r"(* Pump control (* version 2 *) *)   // L0008
PROGRAM Pump
VAR_INPUT
    start : BOOL;
END_VAR
VAR_OUTPUT
    running : BOOL;
END_VAR
    running := start;
END_PROGRAM
",
        r"(* Pump control, version 2 *)
PROGRAM Pump
VAR_INPUT
    start : BOOL;
END_VAR
VAR_OUTPUT
    running : BOOL;
END_VAR
    running := start;
END_PROGRAM
",
    ),
    (
        Code::L0009,
        r"FUNCTION_BLOCK Heater
VAR_INPUT
    cold : BOOL;
END_VAR
VAR_OUTPUT
    power : INT;
END_VAR
VAR_TEMP
    level : INT;
END_VAR
    IF cold THEN
        level := 100;
    END_IF;
    power := level;   // L0009
END_FUNCTION_BLOCK
",
        r"FUNCTION_BLOCK Heater
VAR_INPUT
    cold : BOOL;
END_VAR
VAR_OUTPUT
    power : INT;
END_VAR
VAR_TEMP
    level : INT;
END_VAR
    level := 0;
    IF cold THEN
        level := 100;
    END_IF;
    power := level;
END_FUNCTION_BLOCK
",
    ),
];

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn examples_are_well_formed() {
        let mut seen = std::collections::BTreeSet::new();
        for &(code, wrong, right) in EXAMPLES {
            assert!(seen.insert(code), "{code}: two examples");
            assert_eq!(example(code), Some(Example { wrong, right }));
            assert_ne!(wrong, right, "{code}");
            let marker = format!("// {code}");
            assert_eq!(wrong.matches(&marker).count(), 1, "{code}: mark one line");
            assert!(!right.contains(&marker), "{code}: the right text is marked");
            for text in [wrong, right] {
                assert!(text.ends_with('\n') && !text.ends_with("\n\n"), "{code}");
                assert!(!text.contains('\t') && !text.contains('\r'), "{code}");
                assert!(text.lines().count() <= 40, "{code}: too long");
                assert!(
                    text.lines()
                        .all(|l| l.chars().count() <= 80 && l.trim_end() == l),
                    "{code}"
                );
            }
        }
    }
}
