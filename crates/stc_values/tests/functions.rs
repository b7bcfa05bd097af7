//! The standard functions through the public API, the way the analyser and
//! the VM use it: look the name up, resolve the types, call. Each table row
//! is one documented case (docs/semantics-notes.md).

use stc_values::{
    call, lookup, split, split_lookup, ElemType as E, Fault, Intrinsic as I, Outcome, Value,
};

fn i(n: i128) -> Value {
    Value::Int(n)
}

fn r(x: f64) -> Value {
    Value::Real(x)
}

fn s(x: &str) -> Value {
    Value::string(x)
}

fn w(x: &str) -> Value {
    Value::wstring(x)
}

fn b(x: bool) -> Value {
    Value::Bool(x)
}

const MS: i128 = 1_000_000;
const SEC: i128 = 1_000_000_000;
const DAY: i128 = 86_400 * SEC;

/// Calls `name` (looked up like the analyser does) and returns the value.
fn run(name: &str, args: &[(E, Value)], result: E) -> Result<Value, Fault> {
    run_full(name, args, result).map(|o| o.value)
}

fn run_full(name: &str, args: &[(E, Value)], result: E) -> Result<Outcome, Fault> {
    let f = lookup(name).unwrap_or_else(|| panic!("{name} is not a standard function"));
    assert!(
        f.accepts_count(args.len()),
        "{name} with {} inputs",
        args.len()
    );
    let types: Vec<E> = args.iter().map(|a| a.0).collect();
    let values: Vec<Value> = args.iter().map(|a| a.1.clone()).collect();
    call(f.intrinsic.resolve(&types, result), &types, &values, result)
}

#[test]
fn numeric_functions() {
    let lr = |x| (E::Lreal, r(x));
    assert_eq!(run("ABS", &[(E::Int, i(-5))], E::Int), Ok(i(5)));
    assert_eq!(run("ABS", &[(E::Usint, i(200))], E::Usint), Ok(i(200)));
    assert_eq!(
        run_full("ABS", &[(E::Int, i(-32768))], E::Int),
        Ok(Outcome {
            value: i(-32768),
            overflow: true
        })
    );
    assert_eq!(
        run_full("ABS", &[(E::Lint, i(i64::MIN as i128))], E::Lint).map(|o| o.overflow),
        Ok(true)
    );
    assert_eq!(run("ABS", &[(E::Real, r(-1.5))], E::Real), Ok(r(1.5)));
    assert_eq!(run("SQRT", &[lr(2.0)], E::Lreal), Ok(r(2f64.sqrt())));
    assert_eq!(
        run("SQRT", &[(E::Real, r(2.0))], E::Real),
        Ok(r(2f32.sqrt() as f64))
    );
    assert!(run("SQRT", &[lr(-1.0)], E::Lreal).is_ok_and(|v| v.as_real().is_some_and(f64::is_nan)));
    assert_eq!(run("LN", &[lr(1.0)], E::Lreal), Ok(r(0.0)));
    assert_eq!(run("LN", &[lr(0.0)], E::Lreal), Ok(r(f64::NEG_INFINITY)));
    assert_eq!(run("LOG", &[lr(1000.0)], E::Lreal), Ok(r(3.0)));
    assert_eq!(run("LOG", &[lr(100.0)], E::Lreal), Ok(r(2.0)));
    assert_eq!(run("EXP", &[lr(0.0)], E::Lreal), Ok(r(1.0)));
    assert_eq!(
        run("EXP", &[(E::Real, r(100.0))], E::Real),
        Ok(r(f64::INFINITY))
    );
    assert_eq!(run("SIN", &[lr(0.0)], E::Lreal), Ok(r(0.0)));
    assert_eq!(run("COS", &[lr(0.0)], E::Lreal), Ok(r(1.0)));
    assert_eq!(run("TAN", &[lr(1.0)], E::Lreal), Ok(r(1f64.tan())));
    assert_eq!(
        run("ASIN", &[lr(1.0)], E::Lreal),
        Ok(r(std::f64::consts::FRAC_PI_2))
    );
    assert_eq!(run("ACOS", &[lr(1.0)], E::Lreal), Ok(r(0.0)));
    assert!(run("ACOS", &[lr(2.0)], E::Lreal).is_ok_and(|v| v.as_real().is_some_and(f64::is_nan)));
    assert_eq!(
        run("ATAN", &[lr(1.0)], E::Lreal),
        Ok(r(std::f64::consts::FRAC_PI_4))
    );
    assert_eq!(
        run("ATAN", &[(E::Real, r(1.0))], E::Real),
        Ok(r(std::f64::consts::FRAC_PI_4 as f32 as f64))
    );
    assert_eq!(
        run("ATAN2", &[lr(1.0), lr(0.0)], E::Lreal),
        Ok(r(std::f64::consts::FRAC_PI_2))
    );
    assert_eq!(
        run("ATAN2", &[lr(0.0), lr(-1.0)], E::Lreal),
        Ok(r(std::f64::consts::PI))
    );
    assert_eq!(
        run("EXPT", &[lr(2.0), (E::Int, i(3))], E::Lreal),
        Ok(r(8.0))
    );
    assert_eq!(run("EXPT", &[lr(4.0), lr(0.5)], E::Lreal), Ok(r(2.0)));
    assert_eq!(
        run("EXPT", &[(E::Real, r(2.0)), (E::Dint, i(-1))], E::Real),
        Ok(r(0.5))
    );
    // Ill-typed requests answer a fault, never a panic.
    assert_eq!(
        run("SQRT", &[(E::Int, i(4))], E::Int),
        Err(Fault::Conversion)
    );
    assert_eq!(
        run("ABS", &[(E::String, s("x"))], E::String),
        Err(Fault::Conversion)
    );
}

#[test]
fn shifts_and_rotations() {
    let cases: &[(&str, E, i128, i128, i128)] = &[
        ("SHL", E::Byte, 0x81, 1, 0x02),
        ("SHL", E::Word, 0x00FF, 8, 0xFF00),
        ("SHL", E::Byte, 0x45, 2, 0x14),
        ("SHL", E::Word, 0x0045, 2, 0x0114),
        ("SHL", E::Byte, 0xFF, 8, 0),
        ("SHL", E::Byte, 0xFF, 1000, 0),
        ("SHL", E::Lword, 1, 63, 1 << 63),
        ("SHL", E::Lword, 1, 64, 0),
        ("SHL", E::Byte, 0x80, -7, 0x01),
        ("SHR", E::Byte, 0x81, 1, 0x40),
        ("SHR", E::Dword, 0x8000_0000, 31, 1),
        ("SHR", E::Dword, 0x8000_0000, 32, 0),
        ("SHR", E::Byte, 0x01, -3, 0x08),
        ("SHR", E::Byte, 0x01, i128::MIN, 0),
        ("SHL", E::Byte, 0x01, i128::MAX, 0),
        ("ROL", E::Byte, 0x81, 1, 0x03),
        ("ROL", E::Byte, 0x81, 9, 0x03),
        ("ROL", E::Byte, 0x81, 8, 0x81),
        ("ROL", E::Byte, 0x81, -1, 0xC0),
        ("ROL", E::Word, 0x8001, 4, 0x0018),
        ("ROL", E::Lword, 1 << 63, 1, 1),
        ("ROR", E::Byte, 0x81, 1, 0xC0),
        ("ROR", E::Byte, 0x81, 17, 0xC0),
        ("ROR", E::Byte, 0x81, -1, 0x03),
        ("ROR", E::Dword, 1, 1, 0x8000_0000),
        ("ROR", E::Byte, 0x81, 0, 0x81),
        ("ROR", E::Byte, 0x81, i128::MIN, 0x81),
    ];
    for &(name, t, v, n, want) in cases {
        assert_eq!(
            run(name, &[(t, i(v)), (E::Int, i(n))], t),
            Ok(i(want)),
            "{name}({t:?}#{v:#x}, {n})"
        );
    }
    assert_eq!(
        run("SHL", &[(E::Bool, b(true)), (E::Int, i(1))], E::Bool),
        Ok(b(false))
    );
    assert_eq!(
        run("SHL", &[(E::Bool, b(true)), (E::Int, i(0))], E::Bool),
        Ok(b(true))
    );
    assert_eq!(
        run("ROL", &[(E::Bool, b(true)), (E::Int, i(5))], E::Bool),
        Ok(b(true))
    );
}

#[test]
fn selection() {
    let ints = |xs: &[i128]| xs.iter().map(|&x| (E::Int, i(x))).collect::<Vec<_>>();
    assert_eq!(
        run(
            "SEL",
            &[(E::Bool, b(false)), (E::Int, i(1)), (E::Int, i(2))],
            E::Int
        ),
        Ok(i(1))
    );
    assert_eq!(
        run(
            "SEL",
            &[(E::Bool, b(true)), (E::Int, i(1)), (E::Int, i(2))],
            E::Int
        ),
        Ok(i(2))
    );
    assert_eq!(run("MAX", &ints(&[3, 9, -2]), E::Int), Ok(i(9)));
    assert_eq!(run("MIN", &ints(&[3, 9, -2]), E::Int), Ok(i(-2)));
    assert_eq!(run("MAX", &ints(&[3, 3]), E::Int), Ok(i(3)));
    assert_eq!(
        run(
            "MAX",
            &[(E::String, s("abc")), (E::String, s("abd"))],
            E::String
        ),
        Ok(s("abd"))
    );
    assert_eq!(
        run("MIN", &[(E::Time, i(SEC)), (E::Time, i(-SEC))], E::Time),
        Ok(i(-SEC))
    );
    assert_eq!(
        run("MAX", &[(E::Bool, b(false)), (E::Bool, b(true))], E::Bool),
        Ok(b(true))
    );
    // A NaN stays where it is: like C's `b > a ? b : a`.
    let nan = f64::NAN;
    assert!(
        run("MAX", &[(E::Lreal, r(nan)), (E::Lreal, r(1.0))], E::Lreal)
            .is_ok_and(|v| v.as_real().is_some_and(f64::is_nan))
    );
    assert_eq!(
        run("MAX", &[(E::Lreal, r(1.0)), (E::Lreal, r(nan))], E::Lreal),
        Ok(r(1.0))
    );
    assert_eq!(
        run(
            "MIN",
            &[(E::Lreal, r(1.0)), (E::Lreal, r(nan)), (E::Lreal, r(0.5))],
            E::Lreal
        ),
        Ok(r(0.5))
    );
    let limit = |mn, x, mx| run("LIMIT", &ints(&[mn, x, mx]), E::Int);
    assert_eq!(limit(0, 5, 10), Ok(i(5)));
    assert_eq!(limit(0, -5, 10), Ok(i(0)));
    assert_eq!(limit(0, 15, 10), Ok(i(10)));
    assert_eq!(limit(10, 5, 0), Ok(i(0)));
    assert_eq!(limit(10, 50, 0), Ok(i(0)));
    let mux = |k: i128| {
        run(
            "MUX",
            &[
                (E::Int, i(k)),
                (E::String, s("a")),
                (E::String, s("b")),
                (E::String, s("c")),
            ],
            E::String,
        )
    };
    assert_eq!(mux(0), Ok(s("a")));
    assert_eq!(mux(2), Ok(s("c")));
    assert_eq!(mux(3), Err(Fault::MuxRange));
    assert_eq!(mux(-1), Err(Fault::MuxRange));
    assert_eq!(mux(i128::MAX), Err(Fault::MuxRange));
    assert_eq!(run("MOVE", &[(E::Wstring, w("x"))], E::Wstring), Ok(w("x")));
}

#[test]
fn string_lengths_and_ends() {
    assert_eq!(run("LEN", &[(E::String, s("hello"))], E::Int), Ok(i(5)));
    assert_eq!(run("LEN", &[(E::String, s(""))], E::Int), Ok(i(0)));
    assert_eq!(
        run("LEN", &[(E::Wstring, w("\u{20ac}x"))], E::Dint),
        Ok(i(2))
    );
    assert_eq!(
        run_full("LEN", &[(E::String, Value::Str(vec![b'x'; 300]))], E::Sint),
        Ok(Outcome {
            value: i(44),
            overflow: true
        })
    );
    let left = |x: &str, l: i128| run("LEFT", &[(E::String, s(x)), (E::Int, i(l))], E::String);
    assert_eq!(left("hello", 2), Ok(s("he")));
    assert_eq!(left("hello", 0), Ok(s("")));
    assert_eq!(left("hello", -3), Ok(s("")));
    assert_eq!(left("hello", 5), Ok(s("hello")));
    assert_eq!(left("hello", 99), Ok(s("hello")));
    assert_eq!(left("", 2), Ok(s("")));
    let right = |x: &str, l: i128| run("RIGHT", &[(E::String, s(x)), (E::Int, i(l))], E::String);
    assert_eq!(right("hello", 2), Ok(s("lo")));
    assert_eq!(right("hello", 0), Ok(s("")));
    assert_eq!(right("hello", -1), Ok(s("")));
    assert_eq!(right("hello", 99), Ok(s("hello")));
    assert_eq!(
        run(
            "RIGHT",
            &[(E::Wstring, w("abc")), (E::Lint, i(i64::MAX as i128))],
            E::Wstring
        ),
        Ok(w("abc"))
    );
}

#[test]
fn mid() {
    let mid = |x: &str, l: i128, p: i128| {
        run(
            "MID",
            &[(E::String, s(x)), (E::Int, i(l)), (E::Int, i(p))],
            E::String,
        )
    };
    let cases: &[(&str, i128, i128, &str)] = &[
        ("Informs", 4, 3, "form"),
        ("Informed", 8, 3, "formed"),
        ("", 1, 1, ""),
        ("abcde", 2, 1, "ab"),
        ("abcde", 2, 5, "e"),
        ("abcde", 2, 6, ""),
        ("abcde", 2, 0, "ab"),
        ("abcde", 2, -7, "ab"),
        ("abcde", 0, 2, ""),
        ("abcde", -1, 2, ""),
        ("abcde", 99, 2, "bcde"),
        ("abcde", i128::MAX, i128::MAX, ""),
        ("abcde", i128::MIN, i128::MIN, ""),
    ];
    for &(x, l, p, want) in cases {
        assert_eq!(mid(x, l, p), Ok(s(want)), "MID({x:?}, {l}, {p})");
    }
}

#[test]
fn concat_insert_delete_replace() {
    let strs = |xs: &[&str]| xs.iter().map(|&x| (E::String, s(x))).collect::<Vec<_>>();
    assert_eq!(
        run("CONCAT", &strs(&["ab", "cd"]), E::String),
        Ok(s("abcd"))
    );
    assert_eq!(
        run("CONCAT", &strs(&["a", "", "b", "c"]), E::String),
        Ok(s("abc"))
    );
    assert_eq!(
        run(
            "CONCAT",
            &[(E::Wstring, w("\u{20ac}")), (E::Wstring, w("1"))],
            E::Wstring
        ),
        Ok(w("\u{20ac}1"))
    );
    assert_eq!(
        run(
            "CONCAT",
            &[(E::String, s("a")), (E::Wstring, w("b"))],
            E::String
        ),
        Err(Fault::Conversion)
    );

    let insert = |a: &str, x: &str, p: i128| {
        run(
            "INSERT",
            &[(E::String, s(a)), (E::String, s(x)), (E::Int, i(p))],
            E::String,
        )
    };
    assert_eq!(insert("AD", "BC", 1), Ok(s("ABCD")));
    assert_eq!(insert("abc", "X", 0), Ok(s("Xabc")));
    assert_eq!(insert("abc", "X", -4), Ok(s("Xabc")));
    assert_eq!(insert("abc", "X", 3), Ok(s("abcX")));
    assert_eq!(insert("abc", "X", 30), Ok(s("abcX")));
    assert_eq!(insert("", "X", 1), Ok(s("X")));
    assert_eq!(insert("abc", "", 1), Ok(s("abc")));

    let delete = |a: &str, l: i128, p: i128| {
        run(
            "DELETE",
            &[(E::String, s(a)), (E::Int, i(l)), (E::Int, i(p))],
            E::String,
        )
    };
    let cases: &[(&str, i128, i128, &str)] = &[
        ("abcde", 2, 2, "ade"),
        ("abcde", 1, 1, "bcde"),
        ("abcde", 2, 0, "cde"),
        ("abcde", 2, -3, "cde"),
        ("abcde", 9, 4, "abc"),
        ("abcde", 1, 5, "abcd"),
        ("abcde", 1, 6, "abcde"),
        ("abcde", 0, 2, "abcde"),
        ("abcde", -2, 2, "abcde"),
        ("", 1, 1, ""),
        ("abcde", i128::MAX, 1, ""),
    ];
    for &(a, l, p, want) in cases {
        assert_eq!(delete(a, l, p), Ok(s(want)), "DELETE({a:?}, {l}, {p})");
    }

    let replace = |a: &str, x: &str, l: i128, p: i128| {
        run(
            "REPLACE",
            &[
                (E::String, s(a)),
                (E::String, s(x)),
                (E::Int, i(l)),
                (E::Int, i(p)),
            ],
            E::String,
        )
    };
    let cases: &[(&str, &str, i128, i128, &str)] = &[
        ("Account", "*", 1, 2, "A*count"),
        ("Modbus", "icon", 3, 4, "Modicon"),
        ("Thing", "*", 3, 2, "T*g"),
        ("Abcdef", "*", 1, 1, "*bcdef"),
        ("Abcdef", "**", 1, 2, "A**cdef"),
        ("Abcdef", "***", 1, 4, "Abc***ef"),
        ("Abcdef", "*", 4, 2, "A*f"),
        ("abc", "X", 0, 2, "aXbc"),
        ("abc", "X", -5, 2, "aXbc"),
        ("abc", "X", 1, 0, "Xbc"),
        ("abc", "X", 1, -9, "Xbc"),
        ("abc", "X", 1, 4, "abcX"),
        ("abc", "X", 9, 2, "aX"),
        ("", "X", 1, 1, "X"),
        ("abc", "", 1, 2, "ac"),
    ];
    for &(a, x, l, p, want) in cases {
        assert_eq!(
            replace(a, x, l, p),
            Ok(s(want)),
            "REPLACE({a:?}, {x:?}, {l}, {p})"
        );
    }
    assert_eq!(
        run(
            "REPLACE",
            &[
                (E::Wstring, w("abc")),
                (E::Wstring, w("\u{20ac}")),
                (E::Int, i(1)),
                (E::Int, i(2))
            ],
            E::Wstring
        ),
        Ok(w("a\u{20ac}c"))
    );
}

#[test]
fn find() {
    let find = |a: &str, x: &str| run("FIND", &[(E::String, s(a)), (E::String, s(x))], E::Int);
    assert_eq!(find("abcabc", "bc"), Ok(i(2)));
    assert_eq!(find("abcabc", "abc"), Ok(i(1)));
    assert_eq!(find("abcabc", "cab"), Ok(i(3)));
    assert_eq!(find("abc", "x"), Ok(i(0)));
    assert_eq!(find("abc", "abcd"), Ok(i(0)));
    assert_eq!(find("abc", ""), Ok(i(0)));
    assert_eq!(find("", ""), Ok(i(0)));
    assert_eq!(find("", "a"), Ok(i(0)));
    assert_eq!(find("aaa", "aa"), Ok(i(1)));
    assert_eq!(
        run(
            "FIND",
            &[(E::Wstring, w("x\u{20ac}")), (E::Wstring, w("\u{20ac}"))],
            E::Int
        ),
        Ok(i(2))
    );
}

#[test]
fn time_functions() {
    let t = |ns| (E::Time, i(ns));
    assert_eq!(
        run("ADD_TIME", &[t(SEC), t(500 * MS)], E::Time),
        Ok(i(1500 * MS))
    );
    assert_eq!(
        run("ADD_LTIME", &[(E::Ltime, i(1)), (E::Ltime, i(2))], E::Ltime),
        Ok(i(3))
    );
    assert_eq!(
        run("SUB_TIME", &[t(SEC), t(3 * SEC)], E::Time),
        Ok(i(-2 * SEC))
    );
    assert_eq!(
        run("MUL_TIME", &[t(SEC), (E::Int, i(3))], E::Time),
        Ok(i(3 * SEC))
    );
    assert_eq!(
        run("MULTIME", &[t(SEC), (E::Lreal, r(0.25))], E::Time),
        Ok(i(250 * MS))
    );
    assert_eq!(
        run("DIV_TIME", &[t(SEC), (E::Int, i(4))], E::Time),
        Ok(i(250 * MS))
    );
    assert_eq!(
        run("DIVTIME", &[t(SEC), (E::Int, i(0))], E::Time),
        Err(Fault::DivisionByZero)
    );
    assert_eq!(
        run(
            "DIV_LTIME",
            &[(E::Ltime, i(10)), (E::Lreal, r(4.0))],
            E::Ltime
        ),
        Ok(i(2))
    );
    assert_eq!(
        run(
            "ADD_TOD_TIME",
            &[(E::Tod, i(DAY - SEC)), t(2 * SEC)],
            E::Tod
        ),
        Ok(i(SEC))
    );
    assert_eq!(
        run("SUB_TOD_TIME", &[(E::Tod, i(SEC)), t(2 * SEC)], E::Tod),
        Ok(i(DAY - SEC))
    );
    assert_eq!(
        run(
            "ADD_LTOD_LTIME",
            &[(E::Ltod, i(0)), (E::Ltime, i(-1))],
            E::Ltod
        ),
        Ok(i(DAY - 1))
    );
    assert_eq!(
        run("ADD_DT_TIME", &[(E::Dt, i(DAY)), t(SEC)], E::Dt),
        Ok(i(DAY + SEC))
    );
    assert_eq!(
        run("SUB_DT_TIME", &[(E::Dt, i(DAY)), t(SEC)], E::Dt),
        Ok(i(DAY - SEC))
    );
    assert_eq!(
        run(
            "SUB_DATE_DATE",
            &[(E::Date, i(2 * 86_400)), (E::Date, i(0))],
            E::Time
        ),
        Ok(i(2 * DAY))
    );
    assert_eq!(
        run(
            "SUB_TOD_TOD",
            &[(E::Tod, i(SEC)), (E::Tod, i(3 * SEC))],
            E::Time
        ),
        Ok(i(-2 * SEC))
    );
    assert_eq!(
        run("SUB_DT_DT", &[(E::Dt, i(DAY)), (E::Dt, i(0))], E::Time),
        Ok(i(DAY))
    );
    assert_eq!(
        run("SUB_LDT_LDT", &[(E::Ldt, i(5)), (E::Ldt, i(7))], E::Ltime),
        Ok(i(-2))
    );
    assert_eq!(
        run(
            "CONCAT_DATE_TOD",
            &[(E::Date, i(86_400)), (E::Tod, i(SEC + 5))],
            E::Dt
        ),
        Ok(i(DAY + SEC + 5))
    );
    assert_eq!(
        run(
            "CONCAT_DATE_TOD",
            &[(E::Date, i(1_000_000 * 86_400)), (E::Tod, i(0))],
            E::Dt
        ),
        Err(Fault::Conversion)
    );
    assert_eq!(
        run(
            "CONCAT_DATE_LTOD",
            &[(E::Date, i(0)), (E::Ltod, i(7))],
            E::Ldt
        ),
        Ok(i(7))
    );
}

#[test]
fn date_construction() {
    let ints = |xs: &[i128]| xs.iter().map(|&x| (E::Int, i(x))).collect::<Vec<_>>();
    let date = |y, m, d| run("CONCAT_DATE", &ints(&[y, m, d]), E::Date);
    assert_eq!(date(1970, 1, 2), Ok(i(86_400)));
    assert_eq!(date(2024, 2, 29), Ok(i(19_782 * 86_400)));
    assert_eq!(date(1969, 12, 31), Ok(i(-86_400)));
    assert_eq!(date(2023, 2, 29), Err(Fault::Conversion));
    assert_eq!(date(2024, 13, 1), Err(Fault::Conversion));
    assert_eq!(date(2024, 0, 1), Err(Fault::Conversion));
    assert_eq!(date(2024, 4, 31), Err(Fault::Conversion));
    assert_eq!(date(2024, 1, 0), Err(Fault::Conversion));
    assert_eq!(date(10_000, 1, 1), Err(Fault::Conversion));
    assert_eq!(date(-1, 1, 1), Err(Fault::Conversion));
    assert!(date(0, 1, 1).is_ok());
    assert!(date(2000, 2, 29).is_ok());
    assert_eq!(date(1900, 2, 29), Err(Fault::Conversion));
    let tod = |h, m, sec, ms| run("CONCAT_TOD", &ints(&[h, m, sec, ms]), E::Tod);
    assert_eq!(
        tod(12, 30, 15, 250),
        Ok(i((12 * 3600 + 30 * 60 + 15) * SEC + 250 * MS))
    );
    assert_eq!(tod(23, 59, 59, 999), Ok(i(DAY - MS)));
    assert_eq!(tod(24, 0, 0, 0), Err(Fault::Conversion));
    assert_eq!(tod(0, 60, 0, 0), Err(Fault::Conversion));
    assert_eq!(tod(0, 0, 60, 0), Err(Fault::Conversion));
    assert_eq!(tod(0, 0, 0, 1000), Err(Fault::Conversion));
    assert_eq!(tod(0, 0, 0, -1), Err(Fault::Conversion));
    assert_eq!(
        run("CONCAT_LTOD", &ints(&[0, 0, 1, 0]), E::Ltod),
        Ok(i(SEC))
    );
    let dt = |xs: &[i128]| run("CONCAT_DT", &ints(xs), E::Dt);
    assert_eq!(dt(&[1970, 1, 2, 0, 0, 1, 500]), Ok(i(DAY + 1500 * MS)));
    assert_eq!(
        dt(&[2262, 4, 11, 23, 47, 16, 854]),
        Ok(i(9_223_372_036_854_000_000))
    );
    assert_eq!(dt(&[2262, 4, 11, 23, 47, 16, 855]), Err(Fault::Conversion));
    assert_eq!(
        dt(&[1677, 9, 21, 0, 12, 43, 146]),
        Ok(i(-9_223_372_036_854_000_000))
    );
    assert_eq!(dt(&[1677, 9, 21, 0, 12, 43, 145]), Err(Fault::Conversion));
    assert_eq!(
        run("CONCAT_LDT", &ints(&[1970, 1, 1, 0, 0, 0, 1]), E::Ldt),
        Ok(i(MS))
    );
    let dow = |days: i128| run("DAY_OF_WEEK", &[(E::Date, i(days * 86_400))], E::Int);
    assert_eq!(dow(0), Ok(i(4)));
    assert_eq!(dow(3), Ok(i(0)));
    assert_eq!(dow(-1), Ok(i(3)));
    assert_eq!(dow(19_782), Ok(i(4))); // 2024-02-29, a Thursday
    assert_eq!(dow(-4), Ok(i(0)));
}

#[test]
fn splitting() {
    let (f, t, outs) = split_lookup("split_date").expect("SPLIT_DATE");
    assert_eq!(
        (f, t, outs),
        (I::SplitDate, E::Date, &["YEAR", "MONTH", "DAY"][..])
    );
    assert_eq!(
        split(f, E::Date, &i(19_782 * 86_400)),
        Ok(vec![2024, 2, 29])
    );
    assert_eq!(split(f, E::Date, &i(-86_400)), Ok(vec![1969, 12, 31]));
    let (f, _, outs) = split_lookup("SPLIT_TOD").expect("SPLIT_TOD");
    assert_eq!(outs.len(), 4);
    assert_eq!(
        split(f, E::Tod, &i((13 * 3600 + 5 * 60 + 7) * SEC + 8 * MS + 9)),
        Ok(vec![13, 5, 7, 8])
    );
    let (f, t, outs) = split_lookup("SPLIT_LDT").expect("SPLIT_LDT");
    assert_eq!((t, outs.len()), (E::Ldt, 7));
    assert_eq!(
        split(f, E::Ldt, &i(-MS)),
        Ok(vec![1969, 12, 31, 23, 59, 59, 999])
    );
    assert_eq!(split(I::SplitDate, E::Tod, &i(0)), Err(Fault::Conversion));
    assert_eq!(
        split(I::SplitDate, E::Date, &i(i128::MAX)),
        Err(Fault::Conversion)
    );
    assert!(split_lookup("SPLIT_X").is_none());
    assert_eq!(
        call(I::SplitDate, &[E::Date], &[i(0)], E::Int),
        Err(Fault::Conversion)
    );
}

#[test]
fn conversions_through_call() {
    assert_eq!(run("INT_TO_BYTE", &[(E::Int, i(300))], E::Byte), Ok(i(44)));
    assert_eq!(run("REAL_TO_INT", &[(E::Real, r(2.5))], E::Int), Ok(i(2)));
    assert_eq!(
        run("LREAL_TO_INT", &[(E::Lreal, r(-2.5))], E::Int),
        Ok(i(-2))
    );
    assert_eq!(
        run("TIME_TO_DINT", &[(E::Time, i(1500 * MS))], E::Dint),
        Ok(i(1500))
    );
    assert_eq!(
        run("TO_DINT", &[(E::Time, i(1500 * MS))], E::Dint),
        Ok(i(1500))
    );
    assert_eq!(
        run("TO_STRING", &[(E::Int, i(-42))], E::String),
        Ok(s("-42"))
    );
    assert_eq!(
        run("INT_TO_STRING", &[(E::Int, i(-42))], E::String),
        Ok(s("-42"))
    );
    assert_eq!(
        run("STRING_TO_INT", &[(E::String, s("x"))], E::Int),
        Err(Fault::Conversion)
    );
    assert_eq!(run("TRUNC", &[(E::Real, r(-1.6))], E::Dint), Ok(i(-1)));
    assert_eq!(
        run("LREAL_TRUNC_SINT", &[(E::Lreal, r(200.0))], E::Sint),
        Err(Fault::Conversion)
    );
    assert_eq!(
        run("BCD_TO_INT", &[(E::Word, i(0x1234))], E::Int),
        Ok(i(1234))
    );
    assert_eq!(
        run("WORD_BCD_TO_UINT", &[(E::Word, i(0x0369))], E::Uint),
        Ok(i(369))
    );
    assert_eq!(
        run("INT_TO_BCD", &[(E::Int, i(1234))], E::Word),
        Ok(i(0x1234))
    );
    assert_eq!(
        run("USINT_TO_BCD_BYTE", &[(E::Usint, i(25))], E::Byte),
        Ok(i(0x25))
    );
    assert_eq!(
        run("DT_TO_DATE", &[(E::Dt, i(DAY + 5))], E::Date),
        Ok(i(86_400))
    );
    assert_eq!(
        run(
            "DATE_AND_TIME_TO_TIME_OF_DAY",
            &[(E::Dt, i(DAY + 5))],
            E::Tod
        ),
        Ok(i(5))
    );
}

#[test]
fn operator_functions() {
    let ints = |t: E, xs: &[i128]| xs.iter().map(|&x| (t, i(x))).collect::<Vec<_>>();
    assert_eq!(run("ADD", &ints(E::Int, &[1, 2, 3, 4]), E::Int), Ok(i(10)));
    assert_eq!(
        run_full("ADD", &ints(E::Sint, &[100, 100, -100]), E::Sint),
        Ok(Outcome {
            value: i(100),
            overflow: true
        })
    );
    assert_eq!(run("MUL", &ints(E::Dint, &[2, 3, 4]), E::Dint), Ok(i(24)));
    assert_eq!(run("SUB", &ints(E::Int, &[1, 2]), E::Int), Ok(i(-1)));
    assert_eq!(run("DIV", &ints(E::Int, &[-7, 2]), E::Int), Ok(i(-3)));
    assert_eq!(run("MOD", &ints(E::Int, &[-7, 2]), E::Int), Ok(i(-1)));
    assert_eq!(
        run("MOD", &ints(E::Int, &[7, 0]), E::Int),
        Err(Fault::DivisionByZero)
    );
    assert_eq!(
        run("ADD", &[(E::Tod, i(DAY - 1)), (E::Time, i(2))], E::Tod),
        Ok(i(1))
    );
    assert_eq!(
        run("ADD", &[(E::Lreal, r(0.5)), (E::Lreal, r(0.25))], E::Lreal),
        Ok(r(0.75))
    );
    assert_eq!(
        run("AND", &ints(E::Byte, &[0xFF, 0x0F, 0x3C]), E::Byte),
        Ok(i(0x0C))
    );
    assert_eq!(
        run(
            "OR",
            &[(E::Bool, b(false)), (E::Bool, b(false)), (E::Bool, b(true))],
            E::Bool
        ),
        Ok(b(true))
    );
    assert_eq!(
        run(
            "XOR",
            &[(E::Bool, b(true)), (E::Bool, b(true)), (E::Bool, b(true))],
            E::Bool
        ),
        Ok(b(true))
    );
    assert_eq!(run("NOT", &[(E::Word, i(0x00FF))], E::Word), Ok(i(0xFF00)));
    assert_eq!(run("GT", &ints(E::Int, &[3, 2, 1]), E::Bool), Ok(b(true)));
    assert_eq!(run("GT", &ints(E::Int, &[3, 2, 2]), E::Bool), Ok(b(false)));
    assert_eq!(run("GE", &ints(E::Int, &[3, 2, 2]), E::Bool), Ok(b(true)));
    assert_eq!(run("EQ", &ints(E::Int, &[2, 2, 2]), E::Bool), Ok(b(true)));
    assert_eq!(run("EQ", &ints(E::Int, &[2, 2, 3]), E::Bool), Ok(b(false)));
    assert_eq!(run("LE", &ints(E::Int, &[1, 1, 2]), E::Bool), Ok(b(true)));
    assert_eq!(run("LT", &ints(E::Int, &[1, 1, 2]), E::Bool), Ok(b(false)));
    assert_eq!(run("NE", &ints(E::Int, &[1, 2]), E::Bool), Ok(b(true)));
    assert_eq!(
        run("LT", &[(E::String, s("a")), (E::String, s("b"))], E::Bool),
        Ok(b(true))
    );
}

#[test]
fn ill_formed_calls_never_panic() {
    assert_eq!(call(I::Sel, &[], &[], E::Int), Err(Fault::Conversion));
    assert_eq!(
        call(I::Sel, &[E::Bool], &[b(true)], E::Int),
        Err(Fault::Conversion)
    );
    assert_eq!(
        call(I::Add, &[E::Int], &[i(1), i(2)], E::Int),
        Err(Fault::Conversion)
    );
    assert_eq!(
        call(I::Add, &[E::Int], &[i(1)], E::Int),
        Err(Fault::Conversion)
    );
    assert_eq!(
        call(
            I::Mid,
            &[E::Int, E::Int, E::Int],
            &[i(1), i(1), i(1)],
            E::String
        ),
        Err(Fault::Conversion)
    );
    assert_eq!(
        call(I::Left, &[E::String, E::Int], &[s("a"), r(1.0)], E::String),
        Err(Fault::Conversion)
    );
    assert_eq!(
        call(I::Shl, &[E::Real, E::Int], &[r(1.0), i(1)], E::Real),
        Err(Fault::Conversion)
    );
    assert_eq!(
        call(I::ConcatDt, &[E::Int; 3], &[i(1), i(1), i(1)], E::Dt),
        Err(Fault::Conversion)
    );
}

#[test]
fn every_conversion_name_matches_the_conversion_table() {
    use stc_values::{conversion_allowed, default_value};
    let mut names = 0;
    for &(a_name, a) in E::SPELLINGS {
        for &(b_name, b) in E::SPELLINGS {
            let name = format!("{a_name}_TO_{b_name}");
            let f = lookup(&name);
            assert_eq!(f.is_some(), a != b && conversion_allowed(a, b), "{name}");
            let Some(f) = f else { continue };
            names += 1;
            assert_eq!(f.intrinsic, I::Convert { from: a, to: b });
            // The initial value of every type converts, except an empty
            // string, which is no literal of a non-string type.
            let got = call(f.intrinsic, &[a], &[default_value(a)], b);
            let empty_text = matches!(a, E::String | E::Wstring)
                && !matches!(b, E::String | E::Wstring | E::Char | E::Wchar);
            assert_eq!(got.is_err(), empty_text, "{name}: {got:?}");
        }
    }
    assert!(names > 500, "{names}");
    for &(name, t) in E::SPELLINGS {
        let f = lookup(&format!("TO_{name}")).expect("generic TO_");
        assert_eq!(
            f.intrinsic.resolve(&[E::Int], t),
            I::Convert {
                from: E::Int,
                to: t
            }
        );
    }
}

#[test]
fn generic_intrinsics_resolve_to_the_call_types() {
    let bcd = lookup("BCD_TO_DINT").expect("BCD_TO_DINT");
    assert_eq!(
        bcd.intrinsic.resolve(&[E::Dword], E::Dint),
        I::BcdToInt {
            from: E::Dword,
            to: E::Dint
        }
    );
    let to_bcd = lookup("UDINT_TO_BCD").expect("UDINT_TO_BCD");
    assert_eq!(
        to_bcd.intrinsic.resolve(&[E::Udint], E::Lword),
        I::IntToBcd {
            from: E::Udint,
            to: E::Lword
        }
    );
    assert_eq!(I::Abs.resolve(&[E::Int], E::Int), I::Abs);
    assert_eq!(
        I::Trunc {
            from: E::Lreal,
            to: None
        }
        .resolve(&[], E::Int),
        I::Trunc {
            from: E::Lreal,
            to: None
        }
    );
    // call() uses the types it is given, not the placeholders.
    assert_eq!(
        call(bcd.intrinsic, &[E::Byte], &[i(0x42)], E::Dint),
        Ok(Outcome::exact(i(42)))
    );
}

#[test]
fn fault_texts_are_the_cli_contracts() {
    assert_eq!(Fault::DivisionByZero.kind(), "division by zero");
    assert_eq!(Fault::Conversion.kind(), "conversion failure");
    assert_eq!(Fault::MuxRange.kind(), "MUX selector out of range");
    assert_eq!(Fault::MuxRange.to_string(), "MUX selector out of range");
}
