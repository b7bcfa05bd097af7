//! Unit tests of the analyser's messages and of the facts it records for
//! later phases; the conformance suite (`tests/conformance/check`) checks
//! which diagnostics a program gets, these check what they say.

use stc_diagnostics::{Code, SourceMap};

use crate::{analyze, Analysis, Options, PouId, Section};

fn analyse_with(src: &str, opts: Options) -> Analysis {
    let mut sm = SourceMap::new();
    sm.add("t.st", src.to_string()).expect("small source");
    let mut interner = stc_syntax::Interner::new();
    let (ast, diags) = stc_syntax::parse_project(&sm, &mut interner);
    assert!(diags.iter().all(|d| !d.is_error()), "{diags:?}");
    analyze(&ast, &mut interner, &sm, None, opts)
}

fn messages(src: &str, opts: Options, code: Code) -> Vec<String> {
    analyse_with(src, opts)
        .diagnostics
        .iter()
        .filter(|d| d.code == code)
        .map(|d| d.message.clone())
        .collect()
}

const CONVERSIONS: &str = "PROGRAM P
VAR b : BYTE; i : INT; d : DINT; s : SINT; w : WORD; u : UINT; END_VAR
  i := b;
  i := d;
  d := i;
  w := u;
  s := i;
END_PROGRAM";

#[test]
fn e0302_says_why_the_conversion_is_not_implicit() {
    // Between integers and bit strings CODESYS converts implicitly: W0118
    // by default, E0302 (saying why) with --std iec2.
    let m = messages(CONVERSIONS, Options::default(), Code::W0118);
    assert_eq!(
        m,
        [
            "implicit conversion from BYTE to INT, as CODESYS converts",
            "implicit conversion from DINT to INT, as CODESYS converts",
            "implicit conversion from UINT to WORD, as CODESYS converts",
            "implicit conversion from INT to SINT, as CODESYS converts",
        ]
    );
    assert!(messages(CONVERSIONS, Options::default(), Code::E0302).is_empty());
    let m = messages(CONVERSIONS, Options { iec2: true }, Code::E0302);
    assert!(
        m.contains(
            &"implicit conversion from INT to DINT is not allowed with --std iec2".to_string()
        ),
        "{m:?}"
    );
    assert!(
        !m.iter().any(|s| s.contains("INT to DINT may lose")),
        "{m:?}"
    );
}

#[test]
fn e0302_of_an_output_target() {
    let m = messages(
        "FUNCTION F : INT VAR_OUTPUT o : BYTE; p : DINT; END_VAR F := 0; END_FUNCTION
PROGRAM P VAR i : INT; END_VAR
  i := F(o => i);
  i := F(p => i);
END_PROGRAM",
        // (Without --std iec2 these are W0118, as in assignments.)
        Options { iec2: true },
        Code::E0302,
    );
    assert_eq!(
        m,
        [
            "parameter `o` is BYTE, which does not convert implicitly to INT: bit strings and numbers convert only explicitly",
            "parameter `p` is DINT and would be narrowed into INT",
        ]
    );
}

#[test]
fn e0104_names_an_in_out_as_such() {
    let m = messages(
        "FUNCTION_BLOCK Fb VAR_IN_OUT io : INT; END_VAR VAR v : INT; END_VAR io := v; END_FUNCTION_BLOCK
PROGRAM P VAR f : Fb; n : INT; END_VAR
  f(io := n);
  n := f.io + f.v;
END_PROGRAM",
        // Without --std iec2 reading the in-out is W0115.
        Options { iec2: true },
        Code::E0104,
    );
    assert_eq!(
        m,
        [
            "`io` is an in-out of `Fb`, which is not visible from outside",
            "`v` is not an input or output of `Fb`",
        ]
    );
}

#[test]
fn en_and_eno_are_implicit_variables_after_the_declared_ones() {
    let a = analyse_with(
        "FUNCTION_BLOCK Fb VAR_INPUT x : INT; END_VAR VAR_OUTPUT y : INT; END_VAR
  y := x;
  ENO := x > 0;
END_FUNCTION_BLOCK
FUNCTION F : INT VAR_INPUT EN : BOOL; x : INT; END_VAR F := x; END_FUNCTION
PROGRAM P VAR inst : Fb; END_VAR inst(x := 1); END_PROGRAM",
        Options::default(),
    );
    assert!(a.diagnostics.is_empty(), "{:?}", a.diagnostics);
    let fb = a.pou(PouId(0));
    let names: Vec<(bool, Section)> = fb.vars.iter().map(|v| (v.implicit, v.section)).collect();
    assert_eq!(
        names,
        [
            (false, Section::Input),
            (false, Section::Output),
            (true, Section::Input),
            (true, Section::Output),
        ]
    );
    assert_eq!(
        (fb.en, fb.eno),
        (Some(crate::VarId(2)), Some(crate::VarId(3)))
    );
    assert!(a.implicit_used.contains(&(PouId(0), crate::VarId(3))));
    // A declared EN takes the implicit one's place; ENO is still implicit.
    let f = a.pou(PouId(1));
    assert_eq!(f.en, Some(crate::VarId(1)));
    assert!(f.var(f.eno.expect("ENO")).implicit);
    // Positional parameters: inputs, then outputs; never EN or ENO.
    assert_eq!(fb.positional_params(), [crate::VarId(0), crate::VarId(1)]);
    assert_eq!(f.positional_params(), [crate::VarId(2)]);
    // Programs have neither.
    assert_eq!(a.pou(PouId(2)).en, None);
}
