//! The C code of every operation against `stc_values`: for random and edge
//! operands of every elementary type, every operator, conversion and
//! standard function is emitted through `emit_op`, compiled with gcc
//! (strict warnings as errors, UBSan and ASan) together with the runtime,
//! run, and each result (value or fault kind) compared with what
//! `stc_values` computes. Many cases share one compiled program (one C
//! function per operation shape, tables of operands).

mod ops_support;

use ops_support::values::{text_for, Gen};
use ops_support::{check_shapes, expect_line, Shape, Types};
use stc_codegen_c::ops::Operation;
use stc_syntax::token::ElemType;
use stc_values::{
    binary, call, conversion_allowed, convert, unary, BinOp, Fault, Intrinsic, UnOp, Value,
};

use ElemType as E;

/// Capacity of string operands, and of the short string results that
/// check truncation.
const CAP: u32 = 80;
const SHORT: u32 = 4;

const INTS: &[ElemType] = &[
    E::Sint,
    E::Int,
    E::Dint,
    E::Lint,
    E::Usint,
    E::Uint,
    E::Udint,
    E::Ulint,
    E::Byte,
    E::Word,
    E::Dword,
    E::Lword,
];

fn types() -> Types {
    Types::new(&[CAP, SHORT])
}

/// What stc_values computes for an operation, as the expected line.
fn expected(op: Operation, elems: &[ElemType], args: &[Value], res: ElemType, cap: u32) -> String {
    let r: Result<Value, Fault> = match op {
        Operation::Unary(u) => unary(u, elems[0], &args[0]).map(|o| o.value),
        Operation::Binary(b) => {
            binary(b, elems[0], &args[0], elems[1], &args[1], res).map(|o| o.value)
        }
        Operation::Convert => convert(elems[0], res, &args[0]),
        Operation::Intrinsic(f) => call(f, elems, args, res).map(|o| o.value),
        Operation::Check { lo, hi } => match args[0].as_int() {
            Some(v) if v >= lo && v <= hi => Ok(args[0].clone()),
            _ => return "F3".into(),
        },
    };
    expect_line(res, cap, &r)
}

/// A shape with operands drawn for each argument type.
pub fn shape(
    t: &Types,
    g: &mut Gen,
    op: Operation,
    args: &[ElemType],
    res: ElemType,
    cap: u32,
    n: usize,
) -> Shape {
    let cols: Vec<Vec<Value>> = args.iter().map(|&a| g.values(a, n)).collect();
    let cases: Vec<Vec<Value>> = (0..n)
        .map(|i| cols.iter().map(|c| c[i].clone()).collect())
        .collect();
    shape_with(t, op, args, res, cap, cases)
}

fn shape_with(
    t: &Types,
    op: Operation,
    args: &[ElemType],
    res: ElemType,
    cap: u32,
    cases: Vec<Vec<Value>>,
) -> Shape {
    let expect = cases
        .iter()
        .map(|c| expected(op, args, c, res, cap))
        .collect();
    Shape {
        label: format!("{op:?} {args:?} -> {res:?}[{cap}]"),
        op,
        args: args.iter().map(|&a| (a, t.ty(a, CAP))).collect(),
        result: (res, t.ty(res, cap), cap),
        cases,
        expect,
        alias: None,
    }
}

#[test]
fn operators() {
    let t = types();
    let mut g = Gen::default();
    let mut v = Vec::new();
    let n = 40;
    for &ty in INTS.iter().chain(&[E::Real, E::Lreal, E::Time, E::Ltime]) {
        v.push(shape(
            &t,
            &mut g,
            Operation::Unary(UnOp::Neg),
            &[ty],
            ty,
            0,
            n,
        ));
    }
    for &ty in INTS.iter().chain(&[E::Bool]) {
        v.push(shape(
            &t,
            &mut g,
            Operation::Unary(UnOp::Not),
            &[ty],
            ty,
            0,
            n,
        ));
    }
    let arith = [BinOp::Add, BinOp::Sub, BinOp::Mul, BinOp::Div, BinOp::Mod];
    for &ty in INTS {
        for op in arith {
            v.push(shape(
                &t,
                &mut g,
                Operation::Binary(op),
                &[ty, ty],
                ty,
                0,
                n,
            ));
        }
        for op in [BinOp::And, BinOp::Or, BinOp::Xor] {
            v.push(shape(
                &t,
                &mut g,
                Operation::Binary(op),
                &[ty, ty],
                ty,
                0,
                n,
            ));
        }
    }
    for op in [BinOp::And, BinOp::Or, BinOp::Xor] {
        v.push(shape(
            &t,
            &mut g,
            Operation::Binary(op),
            &[E::Bool, E::Bool],
            E::Bool,
            0,
            n,
        ));
    }
    for ty in [E::Real, E::Lreal] {
        for op in [BinOp::Add, BinOp::Sub, BinOp::Mul, BinOp::Div, BinOp::Pow] {
            v.push(shape(
                &t,
                &mut g,
                Operation::Binary(op),
                &[ty, ty],
                ty,
                0,
                n,
            ));
        }
        for ex in [E::Dint, E::Int, E::Ulint, E::Lint, E::Usint] {
            v.push(shape(
                &t,
                &mut g,
                Operation::Binary(BinOp::Pow),
                &[ty, ex],
                ty,
                0,
                n,
            ));
        }
    }
    v.push(shape(
        &t,
        &mut g,
        Operation::Binary(BinOp::Pow),
        &[E::Real, E::Lreal],
        E::Lreal,
        0,
        n,
    ));
    v.push(shape(
        &t,
        &mut g,
        Operation::Binary(BinOp::Add),
        &[E::Real, E::Lreal],
        E::Lreal,
        0,
        n,
    ));
    v.push(shape(
        &t,
        &mut g,
        Operation::Binary(BinOp::Mul),
        &[E::Lreal, E::Lreal],
        E::Real,
        0,
        n,
    ));
    let all_scalars: Vec<ElemType> = ElemType::ALL.to_vec();
    for &ty in &all_scalars {
        for op in [
            BinOp::Eq,
            BinOp::Ne,
            BinOp::Lt,
            BinOp::Le,
            BinOp::Gt,
            BinOp::Ge,
        ] {
            v.push(shape(
                &t,
                &mut g,
                Operation::Binary(op),
                &[ty, ty],
                E::Bool,
                0,
                24,
            ));
        }
    }
    // Time arithmetic, short and long forms.
    let time_ops: &[(BinOp, ElemType, ElemType, ElemType)] = &[
        (BinOp::Add, E::Time, E::Time, E::Time),
        (BinOp::Sub, E::Time, E::Time, E::Time),
        (BinOp::Add, E::Ltime, E::Ltime, E::Ltime),
        (BinOp::Sub, E::Ltime, E::Ltime, E::Ltime),
        (BinOp::Add, E::Tod, E::Time, E::Tod),
        (BinOp::Sub, E::Tod, E::Time, E::Tod),
        (BinOp::Add, E::Ltod, E::Ltime, E::Ltod),
        (BinOp::Add, E::Dt, E::Time, E::Dt),
        (BinOp::Sub, E::Dt, E::Time, E::Dt),
        (BinOp::Sub, E::Ldt, E::Ltime, E::Ldt),
        (BinOp::Sub, E::Date, E::Date, E::Time),
        (BinOp::Sub, E::Ldate, E::Ldate, E::Ltime),
        (BinOp::Sub, E::Tod, E::Tod, E::Time),
        (BinOp::Sub, E::Dt, E::Dt, E::Time),
        (BinOp::Sub, E::Ldt, E::Ldt, E::Ltime),
        (BinOp::Mul, E::Time, E::Int, E::Time),
        (BinOp::Mul, E::Time, E::Dint, E::Time),
        (BinOp::Mul, E::Time, E::Lint, E::Time),
        (BinOp::Mul, E::Time, E::Ulint, E::Time),
        (BinOp::Mul, E::Time, E::Usint, E::Time),
        (BinOp::Mul, E::Time, E::Real, E::Time),
        (BinOp::Mul, E::Time, E::Lreal, E::Time),
        (BinOp::Mul, E::Ltime, E::Udint, E::Ltime),
        (BinOp::Mul, E::Dint, E::Time, E::Time),
        (BinOp::Mul, E::Lreal, E::Time, E::Time),
        (BinOp::Div, E::Time, E::Int, E::Time),
        (BinOp::Div, E::Time, E::Dint, E::Time),
        (BinOp::Div, E::Time, E::Lint, E::Time),
        (BinOp::Div, E::Time, E::Ulint, E::Time),
        (BinOp::Div, E::Time, E::Real, E::Time),
        (BinOp::Div, E::Time, E::Lreal, E::Time),
        (BinOp::Div, E::Ltime, E::Sint, E::Ltime),
    ];
    for &(op, a, b, r) in time_ops {
        v.push(shape(&t, &mut g, Operation::Binary(op), &[a, b], r, 0, n));
    }
    // Operand and result types that differ (stc_values defines them).
    let mixed: &[(BinOp, ElemType, ElemType, ElemType)] = &[
        (BinOp::Add, E::Int, E::Int, E::Dint),
        (BinOp::Mul, E::Sint, E::Sint, E::Ulint),
        (BinOp::Div, E::Dint, E::Dint, E::Sint),
        (BinOp::Div, E::Int, E::Udint, E::Lint),
        (BinOp::Mod, E::Int, E::Udint, E::Lint),
        (BinOp::Div, E::Ulint, E::Sint, E::Lint),
        (BinOp::Mod, E::Lint, E::Ulint, E::Lint),
        (BinOp::Sub, E::Bool, E::Bool, E::Byte),
        (BinOp::And, E::Sint, E::Word, E::Dword),
        (BinOp::Xor, E::Lint, E::Ulint, E::Int),
        (BinOp::Lt, E::Int, E::Udint, E::Bool),
        (BinOp::Eq, E::Lint, E::Ulint, E::Bool),
        (BinOp::Ge, E::Real, E::Lreal, E::Bool),
        (BinOp::Gt, E::Time, E::Dint, E::Bool),
        (BinOp::Add, E::Time, E::Time, E::Ltime),
        // Requests stc_values refuses whatever the values: a fault.
        (BinOp::Add, E::Bool, E::Bool, E::Bool),
        (BinOp::Add, E::Real, E::Dint, E::Real),
        (BinOp::Pow, E::Dint, E::Dint, E::Lreal),
        (BinOp::Add, E::Date, E::Time, E::Date),
        (BinOp::Add, E::Time, E::Tod, E::Tod),
        (BinOp::Div, E::Int, E::Time, E::Time),
        (BinOp::Mul, E::Time, E::Bool, E::Time),
        (BinOp::Eq, E::Bool, E::Int, E::Bool),
        (BinOp::Lt, E::String, E::Wstring, E::Bool),
        (BinOp::And, E::Real, E::Real, E::Real),
        (BinOp::Mod, E::Real, E::Real, E::Real),
    ];
    for &(op, a, b, r) in mixed {
        v.push(shape(&t, &mut g, Operation::Binary(op), &[a, b], r, 0, 24));
    }
    for (op, ty) in [
        (UnOp::Neg, E::Bool),
        (UnOp::Not, E::Real),
        (UnOp::Neg, E::Date),
    ] {
        v.push(shape(&t, &mut g, Operation::Unary(op), &[ty], ty, 0, 8));
    }
    // Subrange checks.
    let checks: &[(ElemType, i128, i128)] = &[
        (E::Int, -10, 10),
        (E::Int, 0, 32767),
        (E::Usint, 1, 200),
        (E::Usint, 0, 255),
        (E::Dint, -5, 2_000_000_000),
        (E::Lint, i64::MIN as i128, 0),
        (E::Ulint, 5, u64::MAX as i128 - 1),
        (E::Sint, 100, -100),
        (E::Uint, -5, 5),
        (E::Udint, 70000, 70000),
    ];
    for &(ty, lo, hi) in checks {
        v.push(shape(
            &t,
            &mut g,
            Operation::Check { lo, hi },
            &[ty],
            ty,
            0,
            n,
        ));
    }
    let count = check_shapes("operators", &t.module, &v);
    assert!(count > 10_000, "{count} comparisons");
}

/// Operands for a conversion from `from` to `to`: for a text source,
/// texts of the target's literal forms and texts of its values too.
fn conversion_cases(g: &mut Gen, from: ElemType, to: ElemType, n: usize) -> Vec<Vec<Value>> {
    let text_source = matches!(from, E::String | E::Wstring);
    let mut out = Vec::new();
    for v in g.values(from, n) {
        out.push(vec![v]);
    }
    if text_source && !matches!(to, E::String | E::Wstring) {
        let texts = text_for(to);
        let mut add = |s: String| {
            out.push(vec![if from == E::String {
                Value::string(&s)
            } else {
                Value::wstring(&s)
            }]);
        };
        for _ in 0..n * 3 {
            add(g.draw(&texts));
        }
        for v in g.values(to, n) {
            add(stc_values::to_text(to, &v));
        }
    }
    out
}

#[test]
fn conversions() {
    let t = types();
    let mut g = Gen::default();
    let mut v = Vec::new();
    for &from in ElemType::ALL {
        for &to in ElemType::ALL {
            if !conversion_allowed(from, to) {
                // Refused pairs fault whatever the value (a few of them).
                if from < to && matches!(from, E::Bool | E::Date | E::Char) {
                    v.push(shape(&t, &mut g, Operation::Convert, &[from], to, CAP, 4));
                }
                continue;
            }
            let n = if matches!(from, E::Real | E::Lreal) && matches!(to, E::String | E::Wstring) {
                300
            } else {
                40
            };
            let caps: &[u32] = if matches!(to, E::String | E::Wstring) {
                &[CAP, SHORT]
            } else {
                &[CAP]
            };
            for &cap in caps {
                let cases = conversion_cases(&mut g, from, to, n);
                v.push(shape_with(&t, Operation::Convert, &[from], to, cap, cases));
            }
        }
    }
    // The same through the intrinsic (a generic TO_* call).
    for (from, to) in [(E::Lreal, E::Dint), (E::String, E::Time), (E::Dt, E::Date)] {
        let f = Intrinsic::Convert { from, to };
        let cases = conversion_cases(&mut g, from, to, 40);
        v.push(shape_with(
            &t,
            Operation::Intrinsic(f),
            &[from],
            to,
            CAP,
            cases,
        ));
    }
    let count = check_shapes("conversions", &t.module, &v);
    assert!(count > 30_000, "{count} comparisons");
}

#[test]
fn functions() {
    use Intrinsic as I;
    let t = types();
    let mut g = Gen::default();
    let mut v = Vec::new();
    let n = 40;
    let op = Operation::Intrinsic;
    for &ty in INTS.iter().chain(&[E::Real, E::Lreal]) {
        v.push(shape(&t, &mut g, op(I::Abs), &[ty], ty, 0, n));
    }
    v.push(shape(&t, &mut g, op(I::Abs), &[E::Int], E::Dint, 0, n));
    for ty in [E::Real, E::Lreal] {
        for f in [
            I::Sqrt,
            I::Ln,
            I::Log,
            I::Exp,
            I::Sin,
            I::Cos,
            I::Tan,
            I::Asin,
            I::Acos,
            I::Atan,
        ] {
            v.push(shape(&t, &mut g, op(f), &[ty], ty, 0, n));
        }
        v.push(shape(&t, &mut g, op(I::Atan2), &[ty, ty], ty, 0, n));
        v.push(shape(&t, &mut g, op(I::Expt), &[ty, E::Dint], ty, 0, n));
        v.push(shape(&t, &mut g, op(I::Expt), &[ty, ty], ty, 0, n));
    }
    v.push(shape(&t, &mut g, op(I::Sqrt), &[E::Dint], E::Lreal, 0, 4));
    // Shifts and rotations: every bit string and integer, several count types.
    for &ty in INTS.iter().chain(&[E::Bool]) {
        for f in [I::Shl, I::Shr, I::Rol, I::Ror] {
            for cnt in [E::Int, E::Sint, E::Ulint, E::Lint] {
                v.push(shape(&t, &mut g, op(f), &[ty, cnt], ty, 0, 24));
            }
        }
    }
    // Time and date functions.
    let tf: &[(Intrinsic, &[ElemType], ElemType)] = &[
        (I::AddTime, &[E::Time, E::Time], E::Time),
        (I::SubTime, &[E::Ltime, E::Ltime], E::Ltime),
        (I::AddTodTime, &[E::Tod, E::Time], E::Tod),
        (I::SubTodTime, &[E::Ltod, E::Ltime], E::Ltod),
        (I::AddDtTime, &[E::Dt, E::Time], E::Dt),
        (I::SubDtTime, &[E::Dt, E::Time], E::Dt),
        (I::SubDateDate, &[E::Date, E::Date], E::Time),
        (I::SubTodTod, &[E::Tod, E::Tod], E::Time),
        (I::SubDtDt, &[E::Ldt, E::Ldt], E::Ltime),
        (I::MulTime, &[E::Time, E::Dint], E::Time),
        (I::MulTime, &[E::Time, E::Lreal], E::Time),
        (I::DivTime, &[E::Ltime, E::Real], E::Ltime),
        (I::DivTime, &[E::Time, E::Usint], E::Time),
        (I::ConcatDateTod, &[E::Date, E::Tod], E::Dt),
        (I::ConcatDateTod, &[E::Date, E::Ltod], E::Ldt),
        (I::DayOfWeek, &[E::Date], E::Int),
        (I::DayOfWeek, &[E::Date], E::Usint),
        (I::SplitDate, &[E::Date], E::Int),
    ];
    for &(f, args, r) in tf {
        v.push(shape(&t, &mut g, op(f), args, r, 0, n));
    }
    for (f, k, r) in [
        (I::ConcatDate, 3, E::Date),
        (I::ConcatTod, 4, E::Tod),
        (I::ConcatTod, 4, E::Ltod),
        (I::ConcatDt, 7, E::Dt),
        (I::ConcatDt, 7, E::Ldt),
    ] {
        for it in [E::Int, E::Dint, E::Ulint] {
            v.push(shape_with(
                &t,
                op(f),
                &vec![it; k],
                r,
                0,
                date_fields(&mut g, k, it, 60),
            ));
        }
    }
    // Conversions that are functions: TRUNC and BCD.
    for from in [E::Real, E::Lreal] {
        for &to in INTS {
            let f = I::Trunc { from, to: Some(to) };
            v.push(shape(&t, &mut g, op(f), &[from], to, 0, n));
        }
    }
    let bits = [E::Byte, E::Word, E::Dword, E::Lword, E::Bool];
    for w in bits {
        for &i in INTS.iter().filter(|&&i| stc_values::is_integer(i)) {
            let f = I::BcdToInt { from: w, to: i };
            v.push(shape_with(&t, op(f), &[w], i, 0, bcd_cases(&mut g, w, 40)));
            let f = I::IntToBcd { from: i, to: w };
            v.push(shape(&t, &mut g, op(f), &[i], w, 0, n));
        }
    }
    // Operator functions (the IR lowers most to operators).
    v.push(shape(
        &t,
        &mut g,
        op(I::Add),
        &[E::Dint, E::Dint, E::Dint],
        E::Dint,
        0,
        n,
    ));
    v.push(shape(
        &t,
        &mut g,
        op(I::Mul),
        &[E::Int, E::Int, E::Int, E::Int],
        E::Int,
        0,
        n,
    ));
    v.push(shape(
        &t,
        &mut g,
        op(I::Add),
        &[E::Time, E::Time, E::Time],
        E::Time,
        0,
        n,
    ));
    v.push(shape(
        &t,
        &mut g,
        op(I::And),
        &[E::Word, E::Word, E::Word],
        E::Word,
        0,
        n,
    ));
    v.push(shape(
        &t,
        &mut g,
        op(I::Xor),
        &[E::Bool, E::Bool, E::Bool],
        E::Bool,
        0,
        n,
    ));
    v.push(shape(
        &t,
        &mut g,
        op(I::Sub),
        &[E::Lreal, E::Lreal],
        E::Lreal,
        0,
        n,
    ));
    v.push(shape(
        &t,
        &mut g,
        op(I::Div),
        &[E::Sint, E::Sint],
        E::Sint,
        0,
        n,
    ));
    v.push(shape(
        &t,
        &mut g,
        op(I::Mod),
        &[E::Ulint, E::Ulint],
        E::Ulint,
        0,
        n,
    ));
    v.push(shape(&t, &mut g, op(I::Not), &[E::Dword], E::Dword, 0, n));
    v.push(shape(
        &t,
        &mut g,
        op(I::Gt),
        &[E::Int, E::Int, E::Int],
        E::Bool,
        0,
        n,
    ));
    v.push(shape(
        &t,
        &mut g,
        op(I::Le),
        &[E::Real, E::Real, E::Real],
        E::Bool,
        0,
        n,
    ));
    v.push(shape(
        &t,
        &mut g,
        op(I::Eq),
        &[E::String, E::String],
        E::Bool,
        0,
        n,
    ));
    v.push(shape(
        &t,
        &mut g,
        op(I::Ne),
        &[E::Wstring, E::Wstring],
        E::Bool,
        0,
        n,
    ));
    // A scalar result may be written into one of its own operands.
    let aliased: &[(Operation, &[ElemType], ElemType)] = &[
        (op(I::Max), &[E::Dint, E::Dint, E::Dint], E::Dint),
        (op(I::Min), &[E::Lreal, E::Lreal], E::Lreal),
        (op(I::Limit), &[E::Int, E::Int, E::Int], E::Int),
        (op(I::Sel), &[E::Bool, E::Usint, E::Usint], E::Usint),
        (op(I::Mux), &[E::Dint, E::Dint, E::Dint], E::Dint),
        (op(I::Add), &[E::Sint, E::Sint, E::Sint], E::Sint),
        (Operation::Binary(BinOp::Div), &[E::Dint, E::Dint], E::Dint),
        (Operation::Binary(BinOp::Mul), &[E::Time, E::Lreal], E::Time),
        (Operation::Convert, &[E::Lreal], E::Lreal),
        (op(I::Shl), &[E::Word, E::Word], E::Word),
    ];
    for &(o, args, r) in aliased {
        for (k, &a) in args.iter().enumerate() {
            if a == r {
                let mut s = shape(&t, &mut g, o, args, r, 0, n);
                s.alias = Some(k);
                v.push(s);
            }
        }
    }
    let count = check_shapes("functions", &t.module, &v);
    assert!(count > 8_000, "{count} comparisons");
}

#[test]
fn selection_and_strings() {
    use Intrinsic as I;
    let t = types();
    let mut g = Gen::default();
    let mut v = Vec::new();
    let n = 40;
    let op = Operation::Intrinsic;
    // Selection on scalars and strings.
    let sel_types = [
        E::Bool,
        E::Sint,
        E::Ulint,
        E::Real,
        E::Lreal,
        E::Time,
        E::Tod,
        E::Char,
        E::Wchar,
        E::String,
        E::Wstring,
    ];
    for ty in sel_types {
        let cap = if matches!(ty, E::String | E::Wstring) {
            SHORT
        } else {
            0
        };
        v.push(shape(
            &t,
            &mut g,
            op(I::Sel),
            &[E::Bool, ty, ty],
            ty,
            cap,
            n,
        ));
        v.push(shape(&t, &mut g, op(I::Move), &[ty], ty, cap, n));
        for k in 1..=4 {
            let args = vec![ty; k];
            v.push(shape(&t, &mut g, op(I::Max), &args, ty, cap, n));
            v.push(shape(&t, &mut g, op(I::Min), &args, ty, cap, n));
        }
        v.push(shape(&t, &mut g, op(I::Limit), &[ty, ty, ty], ty, cap, n));
        for kt in [E::Int, E::Usint, E::Ulint, E::Lint, E::Bool] {
            for k in 1..=4 {
                let mut args = vec![kt];
                args.extend(vec![ty; k]);
                v.push(shape_with(
                    &t,
                    op(I::Mux),
                    &args,
                    ty,
                    cap,
                    mux_cases(&mut g, &args, 24),
                ));
            }
        }
    }
    // Strings.
    for (s, w) in [(E::String, false), (E::Wstring, true)] {
        let _ = w;
        for cap in [CAP, SHORT] {
            for it in [E::Int, E::Dint, E::Ulint, E::Lint, E::Sint] {
                v.push(shape(&t, &mut g, op(I::Left), &[s, it], s, cap, n));
                v.push(shape(&t, &mut g, op(I::Right), &[s, it], s, cap, n));
                v.push(shape(&t, &mut g, op(I::Mid), &[s, it, it], s, cap, n));
                v.push(shape(&t, &mut g, op(I::Insert), &[s, s, it], s, cap, n));
                v.push(shape(&t, &mut g, op(I::Delete), &[s, it, it], s, cap, n));
                v.push(shape(
                    &t,
                    &mut g,
                    op(I::Replace),
                    &[s, s, it, it],
                    s,
                    cap,
                    n,
                ));
            }
            for k in 1..=4 {
                v.push(shape(&t, &mut g, op(I::Concat), &vec![s; k], s, cap, n));
            }
        }
        for rt in [E::Int, E::Sint, E::Usint, E::Ulint, E::Lint] {
            v.push(shape(&t, &mut g, op(I::Len), &[s], rt, 0, n));
            v.push(shape(&t, &mut g, op(I::Find), &[s, s], rt, 0, n));
        }
    }
    v.push(shape(
        &t,
        &mut g,
        op(I::Concat),
        &[E::String, E::Wstring],
        E::String,
        CAP,
        4,
    ));
    let count = check_shapes("selection_and_strings", &t.module, &v);
    assert!(count > 15_000, "{count} comparisons");
}

/// MUX operands: selectors mostly in range, some out.
fn mux_cases(g: &mut Gen, args: &[ElemType], n: usize) -> Vec<Vec<Value>> {
    let k_in = proptest::prelude::any::<u8>();
    (0..n)
        .map(|_| {
            let inputs = (args.len() - 1) as i128;
            let r = i128::from(g.draw(&k_in));
            let k = match args[0] {
                E::Bool => Value::Bool(r % 2 == 1),
                kt => {
                    let raw = if r < 200 { r % (inputs + 1) } else { r - 230 };
                    let (lo, hi) = stc_values::int_range(kt).unwrap_or((0, 0));
                    Value::Int(raw.clamp(lo, hi))
                }
            };
            let mut c = vec![k];
            for &a in &args[1..] {
                c.extend(g.values(a, 1));
            }
            c
        })
        .collect()
}

/// Date and time fields, mostly near their ranges.
fn date_fields(g: &mut Gen, k: usize, it: ElemType, n: usize) -> Vec<Vec<Value>> {
    let limits: &[i128] = match k {
        3 => &[10000, 13, 32],
        4 => &[24, 60, 60, 1000],
        _ => &[10000, 13, 32, 24, 60, 60, 1000],
    };
    let pick = proptest::prelude::any::<u16>();
    (0..n)
        .map(|_| {
            limits
                .iter()
                .enumerate()
                .map(|(i, &lim)| {
                    let r = i128::from(g.draw(&pick));
                    let mut x = r % (lim + 1);
                    if i == 0 && k != 4 && r % 3 == 0 {
                        // Years near the ends of the DT range.
                        x = 1670 + r % 600;
                    }
                    if r % 97 == 0 {
                        x = -x;
                    }
                    let (lo, hi) = stc_values::int_range(it).unwrap_or((0, 0));
                    Value::Int(x.clamp(lo, hi))
                })
                .collect()
        })
        .collect()
}

/// BCD patterns: valid ones (digits 0..9) and some invalid.
fn bcd_cases(g: &mut Gen, w: ElemType, n: usize) -> Vec<Vec<Value>> {
    let digits = proptest::prelude::any::<u64>();
    let (_, hi) = stc_values::int_range(w).unwrap_or((0, 0));
    (0..n)
        .map(|i| {
            let r = g.draw(&digits);
            let v = if w == E::Bool {
                Value::Bool(r % 2 == 1)
            } else if i % 4 == 3 {
                Value::Int(i128::from(r) & hi)
            } else {
                let mut p: i128 = 0;
                let mut x = r;
                for k in 0..16 {
                    p |= i128::from(x % 10) << (4 * k);
                    x /= 10;
                }
                Value::Int(p & hi)
            };
            vec![v]
        })
        .collect()
}

/// The real-time harness's functions: `stc_convert_scalar` between every
/// pair of non-string types (refused pairs fault), and the SPLIT_* functions.
#[test]
fn harness_functions() {
    let mut g = Gen::default();
    let scalars: Vec<ElemType> = ElemType::ALL
        .iter()
        .copied()
        .filter(|&e| !matches!(e, E::String | E::Wstring))
        .collect();
    let mut conversions = Vec::new();
    for &from in &scalars {
        for &to in &scalars {
            let n = if conversion_allowed(from, to) { 24 } else { 2 };
            conversions.push((from, to, g.values(from, n)));
        }
    }
    let mut splits = Vec::new();
    for (f, e) in [
        (Intrinsic::SplitDate, E::Date),
        (Intrinsic::SplitTod, E::Tod),
        (Intrinsic::SplitTod, E::Ltod),
        (Intrinsic::SplitDt, E::Dt),
        (Intrinsic::SplitDt, E::Ldt),
    ] {
        splits.push((f, e, g.values(e, 200)));
    }
    let (src, expect) = ops_support::harness_program(&conversions, &splits);
    let out = ops_support::compile_and_run("harness_functions", &src);
    let got: Vec<&str> = out.lines().collect();
    assert_eq!(got.len(), expect.len(), "one line per case");
    let bad: Vec<String> = got
        .iter()
        .zip(&expect)
        .enumerate()
        .filter(|(_, (g, e))| *g != *e)
        .map(|(i, (g, e))| format!("case {i}: expected {e}, got {g}"))
        .take(30)
        .collect();
    assert!(bad.is_empty(), "{}", bad.join("\n"));
    eprintln!(
        "harness_functions: {} results compared with stc_values",
        expect.len()
    );
    assert!(expect.len() > 13_000, "{} comparisons", expect.len());
}

/// The hot path: `s := s + i * 3` (and friends) through `emit_op` compiles
/// with `gcc -O2` to exactly the instructions of hand-written C with
/// unsigned wrap-around casts.
#[test]
fn hot_path_compiles_like_hand_written_c() {
    let t = types();
    let cases: &[(ElemType, &str, &str, BinOp, BinOp)] = &[
        (
            E::Dint,
            "int32_t",
            "(int32_t)((uint32_t)s + (uint32_t)i * 3U)",
            BinOp::Mul,
            BinOp::Add,
        ),
        (
            E::Int,
            "int16_t",
            "(int16_t)(uint16_t)((uint32_t)(uint16_t)s + (uint32_t)(uint16_t)i * 3U)",
            BinOp::Mul,
            BinOp::Add,
        ),
        (
            E::Lint,
            "int64_t",
            "(int64_t)((uint64_t)s + (uint64_t)i * 3U)",
            BinOp::Mul,
            BinOp::Add,
        ),
        (E::Udint, "uint32_t", "s + i * 3U", BinOp::Mul, BinOp::Add),
        (
            E::Dint,
            "int32_t",
            "(int32_t)((uint32_t)s - (uint32_t)i * 3U)",
            BinOp::Mul,
            BinOp::Sub,
        ),
        (E::Dword, "uint32_t", "s ^ (i & 3U)", BinOp::And, BinOp::Xor),
    ];
    let mut src = String::from("#include \"stc_rt.h\"\n");
    for (k, &(ty, ct, hand, inner, outer)) in cases.iter().enumerate() {
        let dt = t.ty(ty, 0);
        let three = if stc_values::is_signed(ty) { "3" } else { "3U" };
        let mut body = ops_support::op_code(
            &t.module,
            Operation::Binary(inner),
            &[("i", dt), (three, dt)],
            dt,
            "t1",
        );
        body.extend(ops_support::op_code(
            &t.module,
            Operation::Binary(outer),
            &[("s", dt), ("t1", dt)],
            dt,
            "t2",
        ));
        src.push_str(&format!(
            "{ct} gen{k}({ct} s, {ct} i);\n{ct} gen{k}({ct} s, {ct} i) {{ {ct} t1; {ct} t2; {} return t2; }}\n",
            body.join(" ")
        ));
        src.push_str(&format!(
            "{ct} hand{k}({ct} s, {ct} i);\n{ct} hand{k}({ct} s, {ct} i) {{ return {hand}; }}\n"
        ));
    }
    let asm = ops_support::assemble("hot_path", &src);
    for (k, case) in cases.iter().enumerate() {
        let g = ops_support::function_body(&asm, &format!("gen{k}"));
        let h = ops_support::function_body(&asm, &format!("hand{k}"));
        assert!(!g.is_empty(), "no code for gen{k}");
        assert_eq!(
            g, h,
            "case {k} ({:?}): generated and hand-written C differ",
            case.0
        );
    }
}

/// REAL/LREAL texts in depth: `*_TO_STRING` (shortest round-trip digits)
/// of many values of every class (subnormals, powers of two and their
/// neighbours, large integers where ties of the shortest digits occur),
/// and `STRING_TO_*` of exact and nearly exact midpoints between adjacent
/// values, beyond the 800 significant digits the runtime keeps.
#[test]
fn real_texts() {
    use proptest::prelude::*;
    let t = types();
    let mut g = Gen::default();
    let f32_class = prop_oneof![
        3 => any::<u32>().prop_map(f32::from_bits),
        1 => (0u32..0x80_0000).prop_map(f32::from_bits),
        1 => (0i32..254, -2i32..3).prop_map(|(e, d)| f32::from_bits(((e as u32 + 1) << 23).wrapping_add(d as u32))),
        2 => (1u64 << 24..1u64 << 40).prop_map(|x| x as f32),
    ];
    let f64_class = prop_oneof![
        3 => any::<u64>().prop_map(f64::from_bits),
        1 => (0u64..1 << 52).prop_map(f64::from_bits),
        1 => (0i64..2046, -2i64..3).prop_map(|(e, d)| f64::from_bits((((e + 1) as u64) << 52).wrapping_add(d as u64))),
        2 => (1u64 << 53..u64::MAX).prop_map(|x| x as f64),
    ];
    let n = 3000;
    let mut v = Vec::new();
    let reals: Vec<Vec<Value>> = (0..n)
        .map(|_| vec![Value::Real(f64::from(g.draw(&f32_class)))])
        .collect();
    let lreals: Vec<Vec<Value>> = (0..n)
        .map(|_| vec![Value::Real(g.draw(&f64_class))])
        .collect();
    for to in [E::String, E::Wstring] {
        v.push(shape_with(
            &t,
            Operation::Convert,
            &[E::Real],
            to,
            CAP,
            reals.clone(),
        ));
        v.push(shape_with(
            &t,
            Operation::Convert,
            &[E::Lreal],
            to,
            CAP,
            lreals.clone(),
        ));
    }
    // Texts for REAL: midpoints of adjacent f32 values are f64 values,
    // whose exact decimal expansion Rust prints.
    let mut real_texts = Vec::new();
    for _ in 0..n / 3 {
        let a = g.draw(&f32_class).abs();
        if !a.is_finite() || a == f32::MAX {
            continue;
        }
        let b = f32::from_bits(a.to_bits() + 1);
        let mid = (f64::from(a) + f64::from(b)) / 2.0;
        let exact = format!("{mid:.200e}");
        let (m, e) = exact.split_once('e').unwrap_or((&exact, "0"));
        let m = m.trim_end_matches('0');
        real_texts.push(format!("{m}e{e}"));
        real_texts.push(format!("{m}{}1e{e}", "0".repeat(900)));
        real_texts.push(format!("{m}{}e{e}", "0".repeat(900)));
        real_texts.push(stc_values::to_text(E::Real, &Value::Real(f64::from(a))));
    }
    // Texts for LREAL: a value's exact expansion with a far sticky digit,
    // and round trips of printed values.
    let mut lreal_texts = Vec::new();
    for _ in 0..n / 3 {
        let x = g.draw(&f64_class);
        if !x.is_finite() {
            continue;
        }
        let exact = format!("{x:.900e}");
        let (m, e) = exact.split_once('e').unwrap_or((&exact, "0"));
        lreal_texts.push(format!("{m}1e{e}"));
        lreal_texts.push(format!("{}e{e}", m.trim_end_matches('0')));
        lreal_texts.push(stc_values::to_text(E::Lreal, &Value::Real(x)));
    }
    for (to, texts) in [(E::Real, &real_texts), (E::Lreal, &lreal_texts)] {
        for from in [E::String, E::Wstring] {
            let cases: Vec<Vec<Value>> = texts
                .iter()
                .map(|s| {
                    vec![if from == E::String {
                        Value::string(s)
                    } else {
                        Value::wstring(s)
                    }]
                })
                .collect();
            v.push(shape_with(&t, Operation::Convert, &[from], to, 0, cases));
        }
    }
    let count = check_shapes("real_texts", &t.module, &v);
    assert!(count > 20_000, "{count} comparisons");
}
