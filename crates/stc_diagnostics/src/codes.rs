//! The catalogue of diagnostic codes: the one source of truth for each code's
//! severity, title and the explanation `stc explain` prints.
//!
//! Codes are stable: a code is never reused for another meaning. `docs/
//! diagnostics.md` is the overview of the same table.

use std::fmt;

#[derive(Clone, Copy, PartialEq, Eq, Debug)]
pub enum CodeSeverity {
    Error,
    Warning,
}

macro_rules! codes {
    ($($name:ident $sev:ident $title:literal $explain:literal;)*) => {
        /// A stable diagnostic code.
        #[derive(Clone, Copy, PartialEq, Eq, Hash, Debug, PartialOrd, Ord)]
        pub enum Code { $($name,)* }

        impl Code {
            pub const ALL: &'static [Code] = &[$(Code::$name,)*];

            pub fn as_str(self) -> &'static str {
                match self { $(Code::$name => stringify!($name),)* }
            }

            pub fn severity(self) -> CodeSeverity {
                match self { $(Code::$name => CodeSeverity::$sev,)* }
            }

            /// A short description of the code.
            pub fn title(self) -> &'static str {
                match self { $(Code::$name => $title,)* }
            }

            /// The paragraph `stc explain` prints.
            pub fn explanation(self) -> &'static str {
                match self { $(Code::$name => $explain,)* }
            }

            /// Looks a code up by its name, case-insensitively (`e0301`).
            pub fn parse(name: &str) -> Option<Code> {
                Code::ALL.iter().copied().find(|c| c.as_str().eq_ignore_ascii_case(name))
            }
        }
    };
}

impl fmt::Display for Code {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.as_str())
    }
}

codes! {
    E0001 Error "invalid character"
"A character appears that cannot start any token of Structured Text, for
example `$`, `?` or a non-ASCII character outside a string or comment. Remove
it, or put text in a string literal ('...') or a comment (* ... *).";
    E0002 Error "unterminated comment"
"A comment was opened with `(*` or `/*` but never closed before the end of the
file. `(* ... *)` comments nest: every `(*` inside needs its own `*)`; a
comment that nesting leaves open is read again without nesting (W0003), and
only when no `*)` follows at all is it this error. The error points at where
the unclosed comment starts.";
    E0003 Error "unterminated string literal"
"A string literal was opened with ' or \" but not closed on the same line. A
quote inside a string is written `$'` (or `$\"` in a WSTRING), a line break
`$N`. The error points at where the string starts.";
    E0004 Error "unterminated pragma"
"A pragma `{ ...` was opened but never closed with `}` before the end of the file.";
    E0005 Error "invalid identifier"
"IEC 61131-3 identifiers consist of ASCII letters, digits and underscores;
a letter outside ASCII (`Drücken`, `温度`) is not allowed. Rename the
identifier, for example `Drücken` to `Druecken`. (Two underscores in a row or
a trailing underscore, which the standard forbids too, are accepted with
warning W0008, as every tool does.)";
    E0006 Error "malformed numeric literal"
"A number literal is not well formed: a digit that is not valid in its base
(`2#102`, `16#FG`), a base other than 2, 8 or 16, a missing digit after a
base, an exponent or an underscore, or letters glued to a number.";
    E0007 Error "literal out of range"
"A literal is too large to be represented: an integer beyond 64 bits, or a
duration beyond the range of TIME/LTIME (about 106 751 days as 64-bit
nanoseconds).";
    E0008 Error "malformed date or time literal"
"A duration, date, time-of-day or date-and-time literal is not well formed.
Durations are written `T#1d2h3m4s5ms6us7ns` with units in decreasing order,
a fraction only on the last unit (`T#1.5s`) and optional `_` between units;
dates `D#2024-01-31`; times of day `TOD#12:30:15.5`; date and time
`DT#2024-01-31-12:30:15`. Months run 1..12, days 1..31 (valid for the month),
hours 0..23, minutes and seconds 0..59.";
    E0009 Error "invalid escape in string literal"
"In a string literal `$` starts an escape: `$$` (dollar), `$'` (quote), `$\"`
(double quote), `$L` or `$N` (line feed), `$P` (form feed), `$R` (carriage
return), `$T` (tab), `$hh` (a character code in two hex digits in a STRING)
or `$hhhh` (four hex digits in a WSTRING). Anything else after `$` is an error.";
    E0010 Error "invalid direct address"
"A directly represented variable starts with `%`, then a location `I`
(input), `Q` (output) or `M` (memory), an optional size `X` (bit), `B` (byte),
`W` (word), `D` (double word) or `L` (long word), then one or more numbers
separated by dots: `%IX0.3`, `%QW4`, `%MD12`, `%IX1.2.3`. In an `AT` clause
of a function block or program, `%I*`, `%Q*` or `%M*` marks a location given
later in VAR_CONFIG.";
    E0020 Error "syntax error"
"The parser expected something else at this point. The message says what was
expected and what was found. Only the first error of a statement or
declaration is reported; the parser then resumes at the next statement or
declaration.";
    E0021 Error "mismatched END keyword"
"A block was closed by the END keyword of another kind of block, for example
an IF closed by END_WHILE. The secondary label shows the block that is open.";
    E0022 Error "reserved word used as a name"
"A keyword or an elementary type name (IF, END_VAR, INT, TIME, DT, ...) cannot
be used as the name of a variable, type or POU. Standard function names (MAX,
LEN) and IL operators (LD, ST, S, R) are not reserved and may be used. The
error is given once, where the name is declared: its uses then work as the
name, so rename the declaration and its uses together. A reserved word used
as a name that nothing declares is reported where it is used.";
    E0023 Error "nesting too deep"
"Expressions or statements are nested deeper than stc supports (for example
thousands of nested parentheses). Split the expression with intermediate
variables.";
    E0030 Error "not supported yet"
"The construct is valid in some IEC 61131-3 dialect but stc does not support
it yet: PROPERTY outside a function block, VAR_INST outside a METHOD,
chart elements after ST statements, the CODESYS REFERENCE TO, UNION types, variable-length arrays
(`ARRAY[*]`, `ARRAY[..]`), the `__` operators of CODESYS and TwinCAT
(`__TRY`, `__NEW`...) and logi.CAD UNIT files. The
construct is reported once and skipped (or given an unknown type), and
nothing that follows from it is reported again, so the rest of the file is
still checked.";
    W0001 Warning "source is not UTF-8"
"The file is not valid UTF-8, so it was read as Windows-1252, the encoding
most PLC tools export. If the text looks wrong, convert the file to UTF-8.";
    W0002 Warning "pragma ignored"
"stc does not understand the content of this pragma `{ ... }` (or the
MatIEC `{{ ... }}` block of embedded C code) and ignores it.";
    W0003 Warning "nested comment not closed"
"`(* ... *)` comments nest, so every `(*` inside a comment needs its own `*)`.
This comment contains a `(*` (often in code that was commented out, or the
2nd-edition habit of writing `(*` inside a comment), and counting it, the
comment is never closed: it would run to the end of the file. stc read it
again without nesting: it ends at its first `*)`, as in IEC 61131-3 2nd
edition. Add the missing `*)`, or remove the inner `(*`.";
    W0004 Warning "missing `;` after an END keyword"
"IEC 61131-3 ends every statement and every type declaration with `;`, also
the compound ones: `END_IF;`, `END_CASE;`, `END_FOR;`, `END_WHILE;`,
`END_REPEAT;`, and `END_STRUCT;` before `END_TYPE`. CODESYS, TwinCAT and
RuSTy accept the `;` left out there, so a lot of real code omits it; stc reads
the code as if the `;` were there and warns. Add the `;` to be portable to
stricter tools (MatIEC rejects the form).";
    W0005 Warning "missing `;` before an END keyword"
"The last statement of a block (before `END_IF`, `ELSE`, `ELSIF`, `UNTIL`,
`END_CASE`, the END of a POU...), or the last declaration before `END_VAR`,
`END_STRUCT` or `END_TYPE`, has no `;`. IEC 61131-3 requires it; CODESYS,
TwinCAT and RuSTy accept it left out. stc reads the code as if the `;` were
there and warns. Add the `;` to be portable to stricter tools (MatIEC
rejects the form).";
    W0006 Warning "array initial value without brackets"
"An array's initial values are written without the brackets IEC 61131-3
requires: `a : ARRAY[1..5] OF INT := 2, 2, 3, 2, 2;` instead of
`:= [2, 2, 3, 2, 2];` (repetitions `3(0)` included). CODESYS 2.3 accepted
this form and old libraries (OSCAT) use it; stc reads it as the bracketed
list and warns. Add the brackets to be portable.";
    W0007 Warning "time of day without seconds"
"A time-of-day or date-and-time literal leaves out the seconds:
`TOD#09:00`, `TIME_OF_DAY#9:00`, `DT#2024-01-31-09:00`. IEC 61131-3 requires
hours, minutes and seconds; CODESYS and TwinCAT accept the short form, which
means zero seconds. stc reads it so and warns. Write `TOD#09:00:00` to be
portable.";
    W0008 Warning "identifier with a trailing or doubled underscore"
"IEC 61131-3 identifiers must not end with an underscore or contain two
underscores in a row (`x_`, `true_`, `a__b`, `__SYSTEM_UP_TIME`). CODESYS,
TwinCAT, RuSTy and MatIEC accept such names and real libraries use them, so
stc accepts them with this warning. Names differing only in underscores stay
different names. Rename to be strictly conforming.";
    W0009 Warning "3rd-edition word used as a name"
"A word that only the 3rd edition of IEC 61131-3 (2013) reserved (`CHAR`,
`WCHAR`, `LTIME`, `LDATE`, `LTOD`, `LDT`, `CONTINUE`), or an edge qualifier
(`R_EDGE`, `F_EDGE`), is declared as a name. Code written for the 2nd
edition (OSCAT, MatIEC and Beremiz projects, CODESYS 2.3) uses these words
freely, and every tool of that edition accepts them. stc accepts the name
with this warning; the name then works everywhere in the file, and the
3rd-edition meaning of the word is not available in it. Compile 2nd-edition
code with `--std iec2`, where these words are names without a warning.";

    E0101 Error "undeclared variable"
"The name is not declared as a variable of this POU. Inside a POU only its own
variables are visible: a global variable must be declared in VAR_EXTERNAL to
be used. Check the spelling, or declare the variable.";
    E0102 Error "unknown type"
"No data type, function block or elementary type has this name. Types are
declared in a TYPE ... END_TYPE block, function blocks with FUNCTION_BLOCK.";
    E0103 Error "unknown function or function block"
"No function, function block type or standard function has this name.";
    E0104 Error "no such member"
"The structure has no member, or the function block no input or output, with
this name. Only the inputs and outputs of a function block instance are
visible from outside it (and its implicit EN and ENO); its VAR, VAR_TEMP and
VAR_IN_OUT variables are not.";
    E0105 Error "duplicate declaration"
"The name is already declared in the same scope (a variable twice in one POU,
two POUs or types with the same name, two tasks of a resource). Names are
case-insensitive: `Speed` and `SPEED` are the same name.";
    E0106 Error "unknown task"
"A program instance or function block is associated WITH a task that is not
declared in the resource.";
    E0107 Error "unknown program type"
"A program instance in a configuration names a PROGRAM type that is not declared.";
    E0108 Error "ambiguous enumeration value"
"The value names a constant of several enumeration types and the context does
not decide which one is meant. Write it qualified: `Type#value`.";
    E0109 Error "no such enumeration value"
"The enumeration type does not declare a value with this name.";
    E0110 Error "not a variable"
"The name refers to a type, a function, a function block type or a program,
which cannot be used as a value here.";

    E0201 Error "operand types do not fit the operator"
"The operator is not defined for these operand types (for example `+` on BOOL,
AND on REAL, or two operands of unrelated types). Convert an operand
explicitly, for example with INT_TO_REAL.";
    E0202 Error "condition is not BOOL"
"The condition of IF, ELSIF, WHILE and REPEAT ... UNTIL must be of type BOOL.
Compare the value explicitly, for example `IF count <> 0 THEN`.";
    E0203 Error "CASE label of the wrong type"
"Every CASE label must have the type of the selector: integer labels for an
integer selector, values of the enumeration for an enumerated selector.";
    E0204 Error "FOR loop types"
"The FOR control variable must be a local integer variable, and the start,
end and step expressions must have its type (or a type that widens to it).";
    E0205 Error "array index is not an integer"
"Array subscripts must be integer expressions.";
    E0206 Error "not an array, or wrong number of indices"
"Only arrays can be indexed, with one index per dimension: `a[i, j]` or
`a[i][j]` for a two-dimensional array.";
    E0207 Error "value has no members"
"Member access `.name` applies to structures, function block instances and
programs only.";
    E0208 Error "initial value of the wrong type"
"The initial value does not have the declared type of the variable, member or
data type.";

    E0301 Error "incompatible types in assignment"
"The value has a type that cannot be stored in the target variable, and no
implicit conversion exists between them. IEC 61131-3 is strongly typed: use an
explicit conversion function such as BOOL_TO_INT or INT_TO_REAL.";
    E0302 Error "implicit conversion may lose information"
"A value would be converted implicitly where no implicit conversion exists:
either to a type that cannot represent all its values (DINT to INT, LREAL to
REAL, a signed to an unsigned type), or between a bit string and a number
(BYTE to INT, UINT to WORD), which loses nothing but is never implicit. Only
the widening conversions of the 3rd edition are implicit (SINT to INT, INT to
REAL, REAL to LREAL, BYTE to WORD, ...); with `--std iec2` no conversion is
implicit. The message says which case it is; use the explicit conversion
function named in the help. (Between integers and bit strings CODESYS
converts implicitly; stc accepts that with W0118 unless `--std iec2`.)";
    E0303 Error "literal out of range"
"The literal does not fit in the type it takes from its context, for example
`300` assigned to a SINT (-128..127) or `-1` to a UINT.";
    E0304 Error "assignment to a constant"
"The target is declared CONSTANT (VAR CONSTANT, VAR_GLOBAL CONSTANT or
VAR_EXTERNAL CONSTANT) and cannot be assigned.";
    E0305 Error "assignment to an output of an instance"
"The outputs of a function block instance are written only by the function
block itself. Read them after the call (`x := fb.Q;`) or with `=>` in the
call; to set a value, use an input.";
    E0306 Error "assignment to the FOR control variable"
"The control variable of a FOR loop must not be changed inside the loop: the
number of iterations is fixed when the loop starts. Use a WHILE loop if the
count changes.";
    E0307 Error "assignment target is not a variable"
"The left-hand side of `:=` (or the target of `=>`) must be a variable, an
array element or a member: not a literal, a function call, an expression or a
constant.";

    E0401 Error "unknown parameter"
"The function or function block has no parameter with this name.";
    E0402 Error "missing VAR_IN_OUT argument"
"Every VAR_IN_OUT parameter must be given a variable in each call, because it
is passed by reference.";
    E0403 Error "too many arguments"
"The call gives more positional arguments than the function or function block
has inputs.";
    E0404 Error "formal and positional arguments mixed"
"A call either names every argument (`f(a := 1, b := 2)`) or names none
(`f(1, 2)`); the two forms cannot be mixed in one call.";
    E0405 Error "not callable"
"Only functions and function block instances can be called.";
    E0406 Error "argument must be a variable"
"A VAR_IN_OUT parameter is passed by reference and the target of `=>`
receives a value, so both must be given a variable, not an expression or a
constant.";
    E0407 Error "argument of the wrong type"
"The argument's type does not fit the parameter's type and no implicit
conversion exists.";
    E0408 Error "parameter given twice"
"The same parameter is assigned twice in one call.";
    E0409 Error "function block type used as a function"
"A function block type cannot be called directly: declare an instance
(`t1 : TON;`) and call the instance (`t1(IN := x, PT := T#1s);`). An
instance itself is not a value either: use its outputs (`t1.Q`).";
    E0410 Error "missing argument"
"A call of a standard function must give every one of its inputs
(`LIMIT(MN, IN, MX)` needs all three; a user function's inputs that are not
given take their initial values). Give the missing input, positionally in
order or by name (`LIMIT(MN := 0.0, IN := r, MX := 100.0)`).";

    E0501 Error "function block instance in a FUNCTION"
"Functions have no memory between calls, so they cannot declare function block
instances (which keep state). Make the POU a FUNCTION_BLOCK.";
    E0502 Error "function block called in a FUNCTION"
"Functions cannot call function block instances, which keep state between
calls. Make the POU a FUNCTION_BLOCK.";
    E0503 Error "recursion"
"A POU calls itself, directly or through other POUs. IEC 61131-3 does not
allow recursion: PLC memory is allocated statically.";
    E0504 Error "PROGRAM instantiated outside a configuration"
"Programs are instantiated only in a CONFIGURATION or RESOURCE (`PROGRAM p1
WITH task : Main;`), never as a variable of another POU.";
    E0505 Error "VAR_EXTERNAL without VAR_GLOBAL"
"A VAR_EXTERNAL declaration refers to a global variable that no configuration
declares in VAR_GLOBAL.";
    E0506 Error "VAR_EXTERNAL does not match its VAR_GLOBAL"
"A VAR_EXTERNAL must have the same type as its VAR_GLOBAL, and must be
declared CONSTANT when the global is CONSTANT.";
    E0507 Error "variable section not allowed here"
"This kind of POU does not allow this variable section or qualifier:
functions have no VAR_GLOBAL, VAR_EXTERNAL of function blocks, or R_EDGE /
F_EDGE inputs; R_EDGE and F_EDGE apply to BOOL inputs only.";

    E0601 Error "EXIT or CONTINUE outside a loop"
"EXIT leaves, and CONTINUE restarts, the innermost FOR, WHILE or REPEAT loop;
outside a loop they have no meaning. Use RETURN to leave a POU.";
    E0602 Error "overlapping CASE labels"
"Two CASE labels select the same value, so the second can never be chosen.";
    E0603 Error "CASE label is not constant"
"CASE labels must be constants: literals, enumeration values, VAR CONSTANT
names or constant expressions of them.";
    E0604 Error "FOR step of zero"
"A FOR loop with a step of zero never ends.";

    E0701 Error "array index out of bounds"
"A constant index is outside the declared bounds of the array.";
    E0702 Error "value outside the subrange"
"A constant value is outside the limits of the subrange type it is assigned to.";
    E0703 Error "division by zero"
"The divisor of `/` or MOD is a constant zero (possibly after constant folding).";
    E0704 Error "located variable of the wrong size"
"The size of a direct address fixes the type of the variable located at it:
`%IX`/`%QX`/`%MX` (or no size letter) is one bit (BOOL), `B` 8 bits (BYTE,
SINT, USINT, CHAR), `W` 16 bits (WORD, INT, UINT, WCHAR), `D` 32 bits (DWORD,
DINT, UDINT, REAL, TIME-like 32-bit types), `L` 64 bits (LWORD, LINT, ULINT,
LREAL, LTIME, TIME, DT...).";
    E0705 Error "invalid bounds"
"Array bounds, subrange limits and string lengths must be constant
expressions, with the lower bound not greater than the upper one and a string
length of at least 1.";

    E0801 Error "task INTERVAL is not a TIME"
"The INTERVAL of a periodic task must be a TIME value, for example `INTERVAL := T#10ms`.";
    E0802 Error "task PRIORITY is not an integer"
"The PRIORITY of a task must be a non-negative integer constant; lower numbers
run first.";
    E0803 Error "program connection of the wrong type"
"A program instance parameter is connected to a value or variable of another
type, or the name connected is not an input or output of the program.";
    E0804 Error "task SINGLE is not a BOOL"
"The SINGLE input of an event task must be a BOOL variable; the task runs
once each time it rises.";

    E0901 Error "too large for the memory model"
"A data type, a variable, the instance of a function block or program, the
frame of a call, or the data area (all globals and program instances
together) needs more than 1 GiB (1 073 741 824 bytes), the limit of the
memory model: the virtual machine addresses its whole memory (data,
constants and stack) with 30-bit offsets. The error is reported at the
declaration that is too large, once: the users of a type reported at its
declaration are not reported again. Make the arrays smaller, or split the
data over several variables.";

    E1001 Error "the current result is undefined here"
"An Instruction List instruction reads the current result (the accumulator
that LD sets and operators combine) where it has no value: at the start of
the body, after a CAL (a function block call leaves the current result
undefined), at a label reached with current results of different types (the
instruction before it and the jumps to it disagree), at a label reached only
by jumps written after it, or in a parenthesised sequence before its first
value. Start the instruction sequence with LD (or LDN). A jump written after
its label must bring the type the label already has when the instruction
after the label reads the current result.";
    E1002 Error "the current result is not BOOL"
"S, R, JMPC, JMPCN, CALC, CALCN, RETC and RETCN test the current result,
which must then be BOOL. Load a BOOL first, or compare (`GT 0`) to get one.";
    E1003 Error "jump to an undefined label"
"JMP, JMPC and JMPCN name a label that no instruction of the same body
carries (`label: instruction`). Labels are local to one POU body.";
    E1004 Error "label defined twice"
"Two instructions of one Instruction List body carry the same label, so a
jump to it would be ambiguous. Rename one of them.";
    E1101 Error "loop a circuit cannot unroll"
"The netlist back end (`stc build --emit netlist`) unrolls every loop into
copies of its body, which needs the number of iterations to be decided by
constants when compiling: a FOR with constant bounds and step (EXIT and
CONTINUE inside it are fine). A WHILE or REPEAT loop, or a FOR whose bounds
depend on run-time values, has no fixed number of copies, and so has no
circuit; neither has a loop of more than 4096 iterations. Rewrite the loop
with constant bounds (a bounded FOR with EXIT), or run the program on the
VM or the C back end.";
    E1102 Error "STRING in a circuit"
"A circuit's nets carry elementary values of fixed width (BOOL, integers,
bit strings, reals, times, dates); a STRING or WSTRING, and every
operation on one, has no component in the netlist library. The variable or
operation named cannot be translated; keep text out of the program the
circuit is made of.";
    E1103 Error "run-time selection a circuit cannot make"
"An array element chosen by a run-time index becomes a multiplexer (for a
read) or a demultiplexer (for a write) over every element; the netlist back
end builds them for at most 1024 elements to choose among (for an element
of an element both chosen at run time, `a[i][j]`, all the inner elements of
every outer one). A call of a function block instance chosen at run time
(`fbs[i](...)`) inlines every candidate, at most 64. Beyond those limits
there is no circuit: use constant indices, a smaller array, or a CASE over
the index.";
    E1104 Error "assignment to a circuit input"
"A program's VAR_INPUT variables and its `%I` variables are input modules of
the circuit: their values come from outside each cycle, and a circuit
cannot drive its own input. Copy the input into a VAR variable and change
that one.";
    E1105 Error "construct without a circuit component"
"The construct named has no component in the netlist library: a pointer or
a reference (`POINTER TO`, `ADR(x)`, `REF_TO`, `REF(x)`, `NULL`, `p^`: a
circuit has nets, not memory addresses), a method call (`THIS`), a program
VAR_IN_OUT, a POU other than a PROGRAM or a CONFIGURATION as the circuit.
The message says which, at the construct; docs/netlist.md lists what a
circuit expresses.";
    E1106 Error "circuit too large"
"Unrolling the loops and inlining the calls of the program would make a
circuit of more than 1 000 000 components. Make the loops shorter or the
program smaller.";
    E1201 Error "chart in a FUNCTION"
"A Sequential Function Chart keeps state from one call to the next (which
steps are active, how long, what each action stored), and a FUNCTION keeps
nothing between calls. Write the chart in a FUNCTION_BLOCK or a PROGRAM
(docs/sfc.md).";
    E1202 Error "chart without an initial step"
"A chart starts with exactly one step active, its INITIAL_STEP. A chart
without one would never do anything. Declare its first step with
`INITIAL_STEP name :` instead of `STEP name :`.";
    E1203 Error "second initial step"
"A chart has exactly one INITIAL_STEP (IEC 61131-3 2.6.2). To start several
branches at once, leave the initial step through a transition with several
target steps: `TRANSITION FROM Init TO (A, B) := TRUE; END_TRANSITION`.";
    E1204 Error "transition names an unknown step"
"Every step a transition leaves (FROM) or enters (TO) must be declared with
STEP or INITIAL_STEP in the same chart. Check the spelling, or declare the
step.";
    E1205 Error "action not defined"
"A step associates an action that is neither an ACTION of the same chart nor
a variable of the POU (a Boolean variable is set while the action is
active). Declare the action with `ACTION name : ... END_ACTION`, or the
variable.";
    E1206 Error "name declared twice in a chart"
"Steps, transitions and actions of one chart share the POU's names: two
steps, two actions or two transitions with the same name (or a step and an
action, a transition and a step...) would make `name.X` or an association
ambiguous. Rename one of them.";
    E1207 Error "transition PRIORITY not an integer literal"
"`TRANSITION t (PRIORITY := n)` orders the transitions that leave the same
step: the lowest value is tried first. The priority must be written as a
non-negative integer literal, so the order is known when compiling.";
    E1208 Error "step flag written"
"`step.X` (the step is active) and `step.T` (how long it has been) are kept
by the chart's evolution rules; the program may read them, never write them.
Change the chart's transitions instead, or keep your own variable.";
    E1209 Error "transition body without a name"
"A transition whose condition is computed by statements (`TRANSITION t FROM a
TO b : t := ...; END_TRANSITION`) gives its condition by assigning its own
name, so it needs one. Name the transition, or write the condition as
`:= expression;`.";
    E1210 Error "transition in IL without a BOOL result"
"A transition whose condition is written in Instruction List (`TRANSITION
FROM a TO b : LD x GT 5 END_TRANSITION`) takes as its condition the current
result at the end of the body, so that result must be a BOOL: end the body
with a comparison or a BOOL load. After ST, CAL or at a label reached with
different types the current result is undefined and cannot be the
condition.";
    E1211 Error "action flag written"
"`action.Q` (the action control's output: the action is active) and
`action.A` (its body runs: while Q, and once more after Q falls) are kept
by the chart's action control; the program may read them, never write them.
Change the action's associations instead, or keep your own variable.";
    E1212 Error "indicator variable not BOOL"
"An indicator variable named in an action association (`act(N, done)`)
shows something the action does; the standard makes it a Boolean, which the
action's body sets. Name a BOOL variable of the POU.";
    E1213 Error "RET in an action or transition"
"The IL body of an action or a transition of a chart is a part of the
chart's cycle; RET, RETC and RETCN would leave the whole POU, skipping the
rest of the cycle (the other actions, the step times). Jump to a label at
the end of the body instead.";

    E1301 Error "dereference of something that is not a reference"
"The dereference `^` reads or writes the variable a reference refers to, so
its operand must be a reference (a value of a `REF_TO T` type); `NULL`
refers to no variable and cannot be dereferenced either. Declare the
variable `REF_TO T`, set it with `REF(x)`, and write `r^`.";
    E1302 Error "REF of something that is not a variable"
"`REF(x)` takes exactly one argument, and it must name a variable (or a
member or element of one, or what another reference refers to): the value
of an expression, a literal, an enumeration value, a bit of a bit string
(`w.3`) and a direct address (`%IW0`) have no address a reference could
hold.";
    E1303 Error "REF of a variable that does not outlive the call"
"A reference may only refer to memory that exists as long as the program:
globals, the variables of PROGRAM and FUNCTION_BLOCK instances, and what
another reference refers to. The variables of a FUNCTION or METHOD, a
VAR_TEMP and a VAR_IN_OUT (which may stand for such a variable of the
caller) live only during one call, so a reference to them could be used
after they are gone; stc refuses them when compiling, and only `NULL` needs
a check when the program runs (docs/oop.md). Keep the variable in a
FUNCTION_BLOCK or PROGRAM instance, or in a global.";
    E1304 Error "reference type mismatch"
"A reference of type `REF_TO T` holds `NULL` or a reference to a variable of
exactly type `T` (`REF(x)` has type `REF_TO` the type of `x`); there is no
conversion between references of different target types, nor between a
reference and a value of another type. Declare the reference with the
variable's type, or compare and assign references of the same type.";
    E1305 Error "REF of a constant"
"A CONSTANT variable cannot be changed, but a reference to it could be used
to write it (`r^ := ...`). Refer to a variable that is not CONSTANT, or
copy the constant into one.";
    E1306 Error "reference initialised with something other than NULL"
"A variable of a reference type starts as `NULL` (its default); it cannot
be given another initial value in its declaration, since the variables
that could be referred to are laid out only when the program is built.
Assign `r := REF(x);` in the body instead.";
    E1307 Error "operator not defined on references"
"References can only be compared with `=` and `<>` (to each other or to
`NULL`); they have no arithmetic, no order and no logic. Dereference them
(`r^ + 1`) to work on the variable they refer to.";
    E1308 Error "reference in a RETAIN variable"
"RETAIN variables keep their values over a warm restart, but the address a
reference holds does not stay valid when the program is loaded again (the
generated C places its variables anew). A RETAIN variable, or a RETAIN
instance, array or structure, cannot contain a reference. Declare the
reference in a VAR block without RETAIN and set it again after the
restart.";
    E1309 Error "OVERRIDE without a base method"
"A METHOD declared OVERRIDE replaces the method of the same name of the
function block it EXTENDS. This function block extends none (inheritance
is not supported yet), so there is nothing to override. Remove OVERRIDE.";
    E1310 Error "unknown method"
"`inst.m(...)` calls the METHOD `m` of the function block of `inst`, which
declares no method (and no instance variable) of that name. Check the
spelling, or declare the method inside the FUNCTION_BLOCK (after its
variables, before its body).";
    E1311 Error "method not accessible here"
"A METHOD declared PRIVATE (or PROTECTED, which without inheritance means
the same) can only be called from its own function block: from its body or
its other methods (`m()` or `THIS^.m()`). Call a PUBLIC method from
outside, or declare this one PUBLIC.";
    E1312 Error "THIS outside a function block"
"`THIS` is the reference to the instance of the FUNCTION_BLOCK whose body or
METHOD is running; a FUNCTION, a PROGRAM or a declaration has no instance.
Pass the instance (or a reference to it) as a parameter instead.";
    E1313 Error "SUPER without a base"
"`SUPER^` is the part of the instance that a function block inherits from
the one it EXTENDS. This function block extends none (inheritance is not
supported yet). Call the method of this block itself, `THIS^.m()`.";
    E1314 Error "ABSTRACT method in a function block that is not ABSTRACT"
"An ABSTRACT method is one a derived function block must implement, and
only an ABSTRACT function block (`FUNCTION_BLOCK ABSTRACT`, never
instantiated) may declare one. Declare the block ABSTRACT, or give the
method its body and remove ABSTRACT.";
    E1315 Error "method name already used"
"Two METHODs of one function block have the same name, or a method has the
name of one of the block's variables, so `inst.m` would be ambiguous.
Rename one of them.";
    E1316 Error "instance of an ABSTRACT function block"
"A FUNCTION_BLOCK declared ABSTRACT is incomplete (its ABSTRACT methods have
no body): it is meant to be extended, never instantiated. A variable,
global or array element of its type is refused; a VAR_IN_OUT or a
reference (`REF_TO`) of its type is allowed, since it only refers to an
instance. Instantiate a function block that is not ABSTRACT.";
    E1317 Error "EXTENDS or IMPLEMENTS names the wrong kind of POU"
"A FUNCTION_BLOCK EXTENDS a FUNCTION_BLOCK and a CLASS a CLASS; IMPLEMENTS
and the EXTENDS of an INTERFACE name INTERFACEs. The name here is unknown,
or a function, program, data type or POU of another kind; an INTERFACE
implements nothing (it EXTENDS its base interfaces). Name a POU of the right
kind.";
    E1318 Error "not allowed in a CLASS or INTERFACE"
"A CLASS has variables (VAR, VAR_TEMP...) and METHODs but no body and no
VAR_INPUT, VAR_OUTPUT or VAR_IN_OUT (its methods have parameters). An
INTERFACE has only METHOD prototypes: parameters and a result type, no
local variables and no body. Move the statements into a METHOD, or declare
a FUNCTION_BLOCK.";
    E1319 Error "cycle of EXTENDS"
"A function block, class or interface extends itself, directly or through
its bases, so its variables and methods would be its own. Remove the
EXTENDS that closes the cycle.";
    E1320 Error "extending a FINAL block"
"A FUNCTION_BLOCK or CLASS declared FINAL cannot be extended. Remove FINAL
from the base, or use an instance of it as a variable of the new block.";
    E1321 Error "overriding a FINAL method"
"A METHOD declared FINAL in a base cannot be overridden in a derived block.
Give the method of the derived block another name, or remove FINAL from the
base's method.";
    E1322 Error "override with another signature"
"A method of a derived block with the name of a method of its base overrides
it, and must have exactly its signature: the same parameters (section, name,
type, in the same order) and the same result type, so a call through the
base calls it correctly. Make the signatures the same, or rename the
method.";
    E1323 Error "ABSTRACT method not implemented"
"A FUNCTION_BLOCK or CLASS that is not ABSTRACT can be instantiated, so every
method it inherits must have a body: an ABSTRACT method of a base needs an
overriding method here. Implement the method, or declare the block
ABSTRACT.";
    E1324 Error "interface method not implemented"
"A block that IMPLEMENTS an INTERFACE (directly, through a base, or through
the interfaces the interface extends) must have every method of the
interface, since a call through an interface value may call any of them.
Add the method, or declare the block ABSTRACT.";
    E1325 Error "interface method with another signature"
"The method implementing a method of an INTERFACE must have exactly its
signature: the same parameters (section, name, type, in the same order) and
the same result type. Make the signatures the same.";
    E1326 Error "instance does not implement the interface"
"An interface value refers to an instance of a block that implements the
interface. The instance here is of a type that does not implement it (nor
do its bases). Add the interface to the block's IMPLEMENTS, or use an
interface it implements.";

    E1327 Error "assignment attempt needs references or interfaces"
"`a ?= b` assigns `b` to `a` when the instance `b` refers to is of `a`'s
type, else NULL. Both sides must be interface values or references to
function blocks or classes (the target a variable), and the instance could
fit: one type extends or implements the other, or one is an interface.
Use `:=` for other values.";

    E1328 Error "property without that accessor"
"A PROPERTY is read through its GET and written through its SET. This one
has no GET (it can only be written) or no SET (it can only be read). Add
the accessor to the PROPERTY, or use it the way it allows.";

    E1329 Error "unknown namespace"
"A `USING` directive names a namespace that no `NAMESPACE ... END_NAMESPACE`
of the project declares. The name is read relative to the namespaces around
the directive (innermost first), then from the top. Check its spelling, or
declare the namespace.";
    E1330 Error "ambiguous name from USING"
"The name is not declared in the namespaces around its use, and two
namespaces named by `USING` directives of the same level both declare it,
so which one is meant is not said. Write the name with its namespace
(`Drives.Motor`), or remove one of the `USING` directives.";
    E1331 Error "INTERNAL element outside its namespace"
"An element of a namespace declared `INTERNAL` (`FUNCTION_BLOCK INTERNAL
Helper`), and a METHOD declared `METHOD INTERNAL` of a block declared in a
namespace, can be used only inside that namespace and the namespaces nested
in it. Use it there, or remove INTERNAL from its declaration to make it
public. (A `VAR INTERNAL` variable is likewise visible from outside its
instance only inside the namespace: elsewhere it is an E0104.)";
    E1332 Error "not allowed in a namespace"
"A namespace holds data types, functions, function blocks, classes,
interfaces and other namespaces. PROGRAMs, CONFIGURATIONs and VAR_GLOBAL
sections are declared outside every namespace. stc reads this one as if it
stood after END_NAMESPACE.";

    E1401 Error "ADR needs a variable"
"`ADR(x)` is a pointer to the variable `x` (or a member or element of one,
or what a pointer or reference points at). It needs a variable that is not
CONSTANT, of a type a pointer can see: an elementary, string, array,
structure or function block type (not a reference, program or interface).
A literal, an expression, a bit `w.3` or a direct address has no address.";
    E1402 Error "pointer of the wrong type"
"A `POINTER TO T` (or `POINTER TO ARRAY[..] OF T`) holds `ADR(x)` of a
variable `x` of type `T` or an array of `T`, another pointer to the same
element type `T`, or `0`/`NULL`. A pointer to BYTE, USINT, SINT or CHAR may
also point at the bytes of a STRING (its characters then a NUL). stc does
not convert numbers to pointers or pointers to numbers, and does not view a
variable through a pointer of another type (a REAL through a POINTER TO
DWORD): the pointer could not be checked. Convert the value instead.";
    E1403 Error "operator not defined on pointers"
"Pointers have `p + n` and `p - n` (the pointer moved by `n` bytes, `n` an
integer), `p - q` (the distance in bytes between two pointers into one
variable, a DINT), `=`, `<>`, `<`, `<=`, `>`, `>=` between pointers of the
same type, and `=`/`<>` with `0`. `ADR(x)` has no pointer type of its own:
assign it to a POINTER TO variable before moving, comparing or
dereferencing it.";
    E1404 Error "pointer may outlive what it points at"
"A pointer into a FUNCTION's or METHOD's variables (or a VAR_TEMP, or a
VAR_IN_OUT, which may stand for such a variable of the caller) would point
at freed memory once the call returns. Such a pointer may be kept only in
that call's own variables (VAR, VAR_INPUT, VAR_TEMP) and passed to the
calls it makes; it cannot be stored in a global, an instance variable, a
function's result or outputs, or through another pointer. Point at a global
or an instance variable, or keep the pointer local.";
    E1405 Error "SIZEOF of something without a size"
"`SIZEOF(x)` is the size in bytes of the variable or type `x` in the byte
view of pointers: elementary types their natural size (TIME, DATE, TOD and
DT 8 bytes), STRING(n) n + 1 (the characters and the NUL), WSTRING(n)
2(n + 1), arrays the sum of their elements, structures the sum of their
members without padding, pointers 8. Function block instances and
references have no such size.";

    W0101 Warning "result depends on evaluation order"
"A variable is written by an output parameter (`=>`) or VAR_IN_OUT of one call
and read by another argument of the same enclosing call. IEC 61131-3 does not
fix the order in which arguments are evaluated, so other tools may compute a
different result (stc evaluates left to right). Store the output in a
separate variable first. Accesses are compared as paths: different members
of a structure, or array elements with different constant indices, do not
overlap.";
    W0102 Warning "local enumeration value hides a global one"
"A value of an anonymous enumeration declared in this POU has the same name as
a value of a global enumeration type. Inside the POU the unqualified name
means the local value, which other tools may treat as ambiguous.";
    W0103 Warning "assignment to an input"
"A VAR_INPUT is assigned inside its own POU. Inputs are set by the caller;
changing them inside hides the caller's value and is usually a mistake. Copy
the input to a local variable instead.";
    W0104 Warning "unused variable"
"The variable is declared but never read or written. Remove it, or use it;
inputs, outputs and globals are not reported.";
    W0105 Warning "unreachable statement"
"The statement comes after RETURN, EXIT or CONTINUE in the same block and can
never run; in Instruction List, the instruction comes after JMP or RET and
carries no label that a jump names.";
    W0106 Warning "function result may be unassigned"
"On some path through the FUNCTION its result (the variable named like the
function) is never assigned, so the function returns the type's initial value
there.";
    W0107 Warning "integer overflow in constant expression"
"Constant folding found an integer operation whose result does not fit its
type. The value wraps around in two's complement, as it would at run time.";
    W0108 Warning "constant condition"
"The condition is always TRUE or always FALSE, so one branch is dead code or
the loop never (or always) runs. The idiom of a loop left in the middle,
`WHILE TRUE DO ... EXIT ... END_WHILE` or `REPEAT ... UNTIL FALSE` with an
EXIT or RETURN in its body, is not reported.";
    W0109 Warning "local name hides a global one"
"A local variable has the same name as a global variable, a POU or a data
type, which it hides inside this POU.";
    W0110 Warning "function hides a standard function"
"A FUNCTION is declared with the name of a standard function (ABS, LIMIT,
CONCAT...). Every call of that name in the project then calls this function,
with its own parameter types, instead of the standard one; give it another
name unless that is what you want.";
    W0112 Warning "conversion not in the standard"
"`BOOL_TO_REAL`, `BOOL_TO_LREAL`, `REAL_TO_BOOL` and `LREAL_TO_BOOL` are not
among the conversions of IEC 61131-3 (Table 22 of the 3rd edition), but
MatIEC, Beremiz and CODESYS provide them and programs use them. stc accepts
them with this warning: BOOL gives 0.0 or 1.0; a REAL or LREAL gives TRUE
when it is not zero (NaN too). `BOOL_TO_INT` then `INT_TO_REAL` is the
portable spelling.";
    W0113 Warning "bit string used as a number"
"A bit string (BYTE, WORD, DWORD, LWORD) is used where IEC 61131-3 wants a
number: an operand of `+`, `-`, `*`, `/` or `MOD`, or an array index.
CODESYS, TwinCAT and OSCAT code do it, and stc accepts it with this
warning. Between bit strings and integers the operation is the unsigned
one of the wider operand's width, as a bit string (`DWORD + DWORD` is a
DWORD, wrapping modulo 2^32 with no overflow warning; an integer operand is
converted to that bit string); with a REAL or LREAL operand the bit
string's unsigned value takes part in the REAL operation; an index is the
bit string's unsigned value. The portable spelling converts first:
`UDINT_TO_DWORD(DWORD_TO_UDINT(a) + 1)`, `a[BYTE_TO_USINT(b)]`. `--std
iec2` refuses all of these.";
    W0114 Warning "global variable used without VAR_EXTERNAL"
"A POU reads or writes a global variable that it does not declare in a
VAR_EXTERNAL section. IEC 61131-3 requires the declaration; CODESYS and
TwinCAT make the variables of a global variable list visible everywhere, and
their libraries rely on it (OSCAT's `SETUP`, `MATH`, `LOG_CL`). stc accepts
it with this warning for globals declared outside every CONFIGURATION (a
configuration's globals are bound through VAR_EXTERNAL only), in function
blocks, programs, functions and methods alike: the name is the global
itself. Add `VAR_EXTERNAL name : type; END_VAR` to the POU to follow the
standard; `--std iec2` makes the declaration required.";
    W0115 Warning "in-out of an instance read from outside"
"A VAR_IN_OUT of a function block instance is read from outside it
(`out := rmp.RMP;`). The standard makes an in-out visible only inside
the instance; MatIEC accepts the read, and OSCAT code for OpenPLC relies
on it. stc reads it with this warning: it is the variable that the last
call of the instance passed (the in-out keeps that address between calls);
before the instance's first call it refers to nothing, and reading it is
the run-time fault `NULL dereference`. Writing it from outside stays an
error (E0104), and `--std iec2` refuses the read as well. Read the
variable the call passes instead.";
    W0116 Warning "shift of an integer"
"SHL, SHR, ROL and ROR take a bit string (`IN`) and an integer number of
bits (`N`). CODESYS also shifts integers and takes a bit string as `N`,
and libraries such as OSCAT rely on it (`SHR(x, 1)` of an INT). stc
accepts it with this warning: the integer's bits are shifted as the bit
string of its width (INT as WORD, DINT as DWORD...) and the result is of
the integer's type; SHR of a signed integer is an arithmetic shift (the
sign bit fills in, as CODESYS does), SHL, ROL and ROR work on the bits.
Convert explicitly (`WORD_TO_INT(SHR(INT_TO_WORD(x), 1))`) to follow the
standard; `--std iec2` refuses the form.";
    W0117 Warning "library qualifier read as the element's name"
"CODESYS and TwinCAT name an element of a library with the library's
namespace in front (`Tc2_Standard.TON`, `OSCAT_BASIC.CTRL_PI`). When the
part before the last dot names no namespace of the project, stc reads the
name as the element's own (`TON`), found as if written without the
qualifier, and says so with this warning: compiled with its library's
sources, the code means the same. Declare the namespace (`NAMESPACE
Tc2_Standard ... END_NAMESPACE`) or drop the qualifier; `--std iec2`
refuses the form.";
    W0118 Warning "implicit conversion between integers and bit strings"
"The 3rd edition converts implicitly only where no value can be lost
(INT to DINT, BYTE to WORD) and never between bit strings and numbers.
CODESYS and TwinCAT also convert implicitly from any integer or bit string
to any other (INT to UINT, DINT to INT, DWORD to UDINT, BYTE to INT), and
libraries such as OSCAT rely on it. stc accepts it with this warning and
converts as the explicit conversion does (`INT_TO_UINT`): the value's
low-order bits are kept, so -1 becomes 65535 and 70000 in an INT becomes
4464. Write the conversion (`INT_TO_UINT(x)`) to say it is meant; `--std
iec2` refuses the form (E0302).";
    W1201 Warning "step can never become active"
"No sequence of transitions leads from the initial step to this step: it
is never active and its actions never run by it. A step is reached when a
transition enters it whose source steps can all be reached. Add the
missing transition or remove the step.";
    W1202 Warning "action never used"
"An ACTION of a chart that no step associates never runs (its statements are
still checked). Associate it with a step (`name(N);`) or remove it.";
    W1203 Warning "steps never active together"
"A transition from several steps (a simultaneous convergence, `FROM (a,
b)`) fires only when all of them are active at once. Whatever the
conditions, no sequence of transitions from the initial step makes these
steps active together (they are on alternative branches, for example), so
the transition never fires. Converge alternative branches with one
transition from each step, and join with `FROM (a, b)` only the branches
one transition started together (`TO (a, b)`).";
    W1204 Warning "unsafe chart: a step activated while active"
"A step of a chart is active or not: it cannot be active twice. This
transition can fire while one of the steps it activates is already active
(and not one of the steps it deactivates), so that activation is lost and
the branches of the chart no longer match: typically a branch of a
simultaneous divergence (`TO (a, b)`) leads into another branch, or back
to a step before the branches have converged. The sets of active steps are
explored from the initial step, whatever the conditions. Join parallel
branches with one simultaneous convergence (`FROM (a, b)`) before going
back.";
    W1317 Warning "override without OVERRIDE"
"A method of a derived block has the name and signature of a method of its
base, so it overrides it (a call through the base runs this one), but it is
not declared OVERRIDE. Write `METHOD OVERRIDE name` to say so.";
    L0001 Warning "magic number (lint `magic-number`)"
"A numeric literal other than 0 and 1 in a POU's statements (CASE labels
are not counted). A number written in the logic says nothing about what it
is, and when it changes every copy must be found. Declare it once as a
named constant (`VAR CONSTANT max_level : INT := 950; END_VAR`) and use the
name (PLCopen coding guidelines). A lint: off by default (`allow`); turn it
on with `magic-number = \"warn\"` under `[lints]` in stc.toml, or `-W
magic-number`.";
    L0002 Warning "direct address in a body (lint `direct-address`)"
"A directly represented variable (`%IX0.3`, `%QW4`) used in a POU's
statements. The address says where the signal is wired, not what it
means, and rewiring means editing the logic. Declare a named variable at
the address (`start AT %IX0.3 : BOOL;`) and use the name (PLCopen coding
guidelines). A lint: `warn` by default; its level is set under `[lints]` in
stc.toml (`direct-address = \"allow\"`).";
    L0003 Warning "output read before the call (lint `output-before-call`)"
"An output of a function block instance (`tmr.Q`) is read before the body
calls the instance, in source order: the value read is the one of the
previous call (or the initial value in the first cycle), one cycle late.
Call the instance first, then read its outputs (PLCopen coding
guidelines). Only instances the POU declares and calls later in the same
body are checked; reading the instance's own output in its call's
arguments (`t(IN := NOT t.Q)`, the feedback idiom) is not reported. A
lint: `warn` by default (`output-before-call` under `[lints]`).";
    L0004 Warning "variable shadows a global (lint `shadowed-global`)"
"A variable of a POU (input, output, in-out, VAR or VAR_TEMP) has the name
of a global variable of the project, so inside the POU the name means the
local one and the global cannot be reached: a reader easily takes one for
the other. Rename the local variable (PLCopen coding guidelines). Where
W0109 already reports the name, this lint says nothing. A lint: `warn` by
default (`shadowed-global` under `[lints]`).";
    L0005 Warning "unused input (lint `unused-input`)"
"A VAR_INPUT of a FUNCTION, FUNCTION_BLOCK or PROGRAM that its body (and
the block's methods and actions) never refers to: callers give a value
that changes nothing. Remove the input or use it (PLCopen coding
guidelines). A block that another block EXTENDS, abstract blocks and
bodies stc skipped are not checked. A lint: `warn` by default
(`unused-input` under `[lints]`).";
    L0006 Warning "CASE without ELSE (lint `case-without-else`)"
"A CASE statement has no ELSE branch, so a selector value that no label
names does nothing, silently. Add an ELSE that handles or reports the other
values (PLCopen coding guidelines). A lint: off by default (`allow`),
since a CASE over an enumeration that names every value needs no ELSE; turn
it on with `case-without-else = \"warn\"` under `[lints]`.";
    L0007 Warning "REAL compared with = (lint `real-equality`)"
"Two REAL or LREAL values compared with `=` or `<>`. Floating-point results
are rounded, so values that are equal on paper (0.1 + 0.2 and 0.3) differ
in the last bit and the comparison is FALSE. Compare the difference with a
tolerance: `ABS(a - b) < 1.0E-6` (PLCopen coding guidelines). A lint:
`warn` by default (`real-equality` under `[lints]`).";
    L0008 Warning "nested comment (lint `nested-comment`)"
"A `(*` inside a `(* ... *)` comment. stc reads comments nested (each `(*`
needs its own `*)`), but many tools end the comment at the first `*)`, so
the same text means different programs in different tools, and a `*)` left
out hides code. Close the outer comment first or use `//` line comments
(PLCopen coding guidelines). A lint: `warn` by default (`nested-comment`
under `[lints]`).";
    L0009 Warning "assigned on some paths only (lint `assigned-on-some-paths`)"
"A temporary variable (a VAR_TEMP, or a VAR of a FUNCTION: both start from
their initial value at every call) is assigned in an IF without ELSE and
read after the IF before any assignment on every path: when no condition
holds, the read sees the initial value, which is rarely what was meant.
Assign the variable before the IF or in an ELSE branch too (PLCopen coding
guidelines). Variables that keep their value between cycles (VAR of a
FUNCTION_BLOCK or PROGRAM) are not checked: keeping the old value is
what such an IF means. A lint: `warn` by default (`assigned-on-some-paths`
under `[lints]`).";
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_code_has_a_well_formed_name_and_texts() {
        for &c in Code::ALL {
            let s = c.as_str();
            assert_eq!(s.len(), 5);
            let expected: &[char] = match c.severity() {
                CodeSeverity::Error => &['E'],
                // Lints (`L`) are warnings whose level a project sets.
                CodeSeverity::Warning => &['W', 'L'],
            };
            assert!(s.starts_with(expected), "{s}");
            assert!(!c.title().is_empty() && c.explanation().len() > 40, "{s}");
            assert_eq!(Code::parse(&s.to_lowercase()), Some(c));
        }
    }
}
