//! Properties that must hold for every value: agreement with Rust's own
//! fixed-width arithmetic (which is C's), round trips through text and
//! through wider types, structural laws of the string functions, and no
//! panic on any input, well-typed or not.

use proptest::prelude::*;
use stc_values::{
    bcd_to_int, binary, call, common_type, conversion_may_fault, convert, int_range, int_to_bcd,
    is_integer, to_text, unary, wrap, BinOp, ElemType as E, Fault, Intrinsic, UnOp, Value,
};

const INT_TYPES: [E; 8] = [
    E::Sint,
    E::Int,
    E::Dint,
    E::Lint,
    E::Usint,
    E::Uint,
    E::Udint,
    E::Ulint,
];

/// Rust's `as` cast to each integer type, widened back to i128.
fn cast(t: E, v: i128) -> i128 {
    match t {
        E::Sint => (v as i8).into(),
        E::Int => (v as i16).into(),
        E::Dint => (v as i32).into(),
        E::Lint => (v as i64).into(),
        E::Usint | E::Byte => (v as u8).into(),
        E::Uint | E::Word => (v as u16).into(),
        E::Udint | E::Dword => (v as u32).into(),
        _ => (v as u64).into(),
    }
}

fn any_int_type() -> impl Strategy<Value = E> {
    proptest::sample::select(INT_TYPES.to_vec())
}

fn any_type() -> impl Strategy<Value = E> {
    proptest::sample::select(E::ALL.to_vec())
}

/// A value in `t`'s range.
fn value_of(t: E) -> BoxedStrategy<Value> {
    match t {
        E::Bool => any::<bool>().prop_map(Value::Bool).boxed(),
        E::Real => any::<f32>().prop_map(|x| Value::Real(x.into())).boxed(),
        E::Lreal => any::<f64>().prop_map(Value::Real).boxed(),
        E::String => proptest::collection::vec(any::<u8>(), 0..12)
            .prop_map(Value::Str)
            .boxed(),
        E::Wstring => proptest::collection::vec(any::<u16>(), 0..12)
            .prop_map(Value::WStr)
            .boxed(),
        E::Date | E::Ldate => (-200_000i128..200_000)
            .prop_map(|d| Value::Int(d * 86_400))
            .boxed(),
        _ => {
            let (lo, hi) = int_range(t).unwrap_or((0, 0));
            (lo..=hi).prop_map(Value::Int).boxed()
        }
    }
}

fn typed_value() -> impl Strategy<Value = (E, Value)> {
    any_type().prop_flat_map(|t| value_of(t).prop_map(move |v| (t, v)))
}

/// Any value at all, in range or not, of any kind.
fn wild_value() -> impl Strategy<Value = Value> {
    prop_oneof![
        any::<bool>().prop_map(Value::Bool),
        any::<i128>().prop_map(Value::Int),
        (-1000i128..1000).prop_map(Value::Int),
        any::<f64>().prop_map(Value::Real),
        proptest::collection::vec(any::<u8>(), 0..6).prop_map(Value::Str),
        proptest::collection::vec(any::<u16>(), 0..6).prop_map(Value::WStr),
    ]
}

fn same_real(a: &Value, b: &Value) -> bool {
    match (a, b) {
        (Value::Real(x), Value::Real(y)) => {
            (x.is_nan() && y.is_nan()) || x.to_bits() == y.to_bits()
        }
        _ => a == b,
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(4096))]
    /// A back end leaves out the fault check of a conversion that
    /// `conversion_may_fault` says cannot fault: it must never fault.
    #[test]
    fn conversion_may_fault_is_sound((from, v) in typed_value(), to in any_type()) {
        if convert(from, to, &v).is_err() {
            prop_assert!(conversion_may_fault(from, to), "{from:?} -> {to:?} faulted on {v:?}");
        }
        // The value's own text, as STRING, converted back (the parse path).
        let text = Value::Str(to_text(from, &v).into_bytes());
        if convert(E::String, to, &text).is_err() {
            prop_assert!(conversion_may_fault(E::String, to));
        }
    }
}

proptest! {
    #[test]
    fn wrap_agrees_with_as_casts(t in any_int_type(), v in any::<i128>()) {
        prop_assert_eq!(wrap(t, v), cast(t, v));
    }

    #[test]
    fn bit_strings_wrap_like_unsigned(v in any::<i128>()) {
        for t in [E::Byte, E::Word, E::Dword, E::Lword] {
            prop_assert_eq!(wrap(t, v), cast(t, v));
        }
    }

    #[test]
    fn integer_ops_agree_with_fixed_width_arithmetic(
        t in any_int_type(),
        a in any::<i128>(),
        b in any::<i128>(),
    ) {
        let (a, b) = (cast(t, a), cast(t, b));
        // (operation, exact result, result modulo 2^128)
        let ops: [(BinOp, Option<i128>, i128); 5] = [
            (BinOp::Add, a.checked_add(b), a.wrapping_add(b)),
            (BinOp::Sub, a.checked_sub(b), a.wrapping_sub(b)),
            (BinOp::Mul, a.checked_mul(b), a.wrapping_mul(b)),
            (BinOp::Div, a.checked_div(b), a.wrapping_div(if b == 0 { 1 } else { b })),
            (BinOp::Mod, a.checked_rem(b), a.wrapping_rem(if b == 0 { 1 } else { b })),
        ];
        for (op, exact, raw) in ops {
            let got = binary(op, t, &Value::Int(a), t, &Value::Int(b), t);
            if matches!(op, BinOp::Div | BinOp::Mod) && b == 0 {
                prop_assert_eq!(got, Err(Fault::DivisionByZero));
                continue;
            }
            let got = got.expect("well-typed integer operation");
            let want = cast(t, raw);
            prop_assert_eq!(&got.value, &Value::Int(want));
            prop_assert_eq!(got.overflow, exact != Some(want), "{:?} {:?} {} {}", op, t, a, b);
        }
    }

    #[test]
    fn div_and_mod_recompose_the_dividend(t in any_int_type(), a in any::<i128>(), b in any::<i128>()) {
        let (a, b) = (cast(t, a), cast(t, b));
        prop_assume!(b != 0);
        let q = binary(BinOp::Div, t, &Value::Int(a), t, &Value::Int(b), t).expect("div").value;
        let m = binary(BinOp::Mod, t, &Value::Int(a), t, &Value::Int(b), t).expect("mod").value;
        let (q, m) = (q.as_int().unwrap_or(0), m.as_int().unwrap_or(0));
        prop_assert_eq!(wrap(t, q.wrapping_mul(b).wrapping_add(m)), a);
        prop_assert!(m == 0 || (m < 0) == (a < 0));
        prop_assert!(m.abs() < b.abs());
    }

    #[test]
    fn negation_wraps(t in any_int_type(), a in any::<i128>()) {
        let a = cast(t, a);
        let o = unary(UnOp::Neg, t, &Value::Int(a)).expect("neg");
        prop_assert_eq!(&o.value, &Value::Int(cast(t, -a)));
        prop_assert_eq!(o.overflow, cast(t, -a) != -a);
    }

    #[test]
    fn real_ops_are_f32_arithmetic(a in any::<f32>(), b in any::<f32>()) {
        type Op32 = (BinOp, fn(f32, f32) -> f32);
        let ops: [Op32; 4] = [
            (BinOp::Add, |a, b| a + b),
            (BinOp::Sub, |a, b| a - b),
            (BinOp::Mul, |a, b| a * b),
            (BinOp::Div, |a, b| a / b),
        ];
        for (op, f) in ops {
            let got = binary(op, E::Real, &Value::Real(a.into()), E::Real, &Value::Real(b.into()), E::Real)
                .expect("real op").value;
            prop_assert!(same_real(&got, &Value::Real(f(a, b).into())), "{:?} {} {} = {:?}", op, a, b, got);
        }
        let sqrt = call(Intrinsic::Sqrt, &[E::Real], &[Value::Real(a.into())], E::Real).expect("sqrt").value;
        prop_assert!(same_real(&sqrt, &Value::Real(a.sqrt().into())));
    }

    #[test]
    fn lreal_ops_are_f64_arithmetic(a in any::<f64>(), b in any::<f64>()) {
        type Op64 = (BinOp, fn(f64, f64) -> f64);
        let ops: [Op64; 4] = [
            (BinOp::Add, |a, b| a + b),
            (BinOp::Sub, |a, b| a - b),
            (BinOp::Mul, |a, b| a * b),
            (BinOp::Div, |a, b| a / b),
        ];
        for (op, f) in ops {
            let got = binary(op, E::Lreal, &Value::Real(a), E::Lreal, &Value::Real(b), E::Lreal)
                .expect("lreal op").value;
            prop_assert!(same_real(&got, &Value::Real(f(a, b))));
        }
    }

    #[test]
    fn comparisons_agree_with_ieee(a in any::<f64>(), b in any::<f64>()) {
        let cmp = |op| binary(op, E::Lreal, &Value::Real(a), E::Lreal, &Value::Real(b), E::Bool)
            .expect("compare").value;
        prop_assert_eq!(cmp(BinOp::Lt), Value::Bool(a < b));
        prop_assert_eq!(cmp(BinOp::Le), Value::Bool(a <= b));
        prop_assert_eq!(cmp(BinOp::Eq), Value::Bool(a == b));
        prop_assert_eq!(cmp(BinOp::Ne), Value::Bool(a != b));
        prop_assert_eq!(cmp(BinOp::Ge), Value::Bool(a >= b));
    }

    #[test]
    fn widening_and_back_is_identity((from, v) in any_int_type().prop_flat_map(|t| value_of(t).prop_map(move |v| (t, v)))) {
        for to in INT_TYPES.iter().copied().chain([E::Lreal, E::Real]) {
            if stc_values::implicit_widening(from, to) {
                let wide = convert(from, to, &v).expect("widen");
                prop_assert_eq!(convert(to, from, &wide).expect("narrow"), v.clone(), "{:?} -> {:?}", from, to);
            }
        }
    }

    #[test]
    fn integer_conversions_are_c_casts(from in any_int_type(), to in any_int_type(), v in any::<i128>()) {
        let v = cast(from, v);
        prop_assert_eq!(convert(from, to, &Value::Int(v)), Ok(Value::Int(cast(to, v))));
    }

    #[test]
    fn real_to_int_rounds_half_even(x in any::<f64>(), t in any_int_type()) {
        let got = convert(E::Lreal, t, &Value::Real(x));
        let (lo, hi) = int_range(t).unwrap_or((0, 0));
        let r = x.round_ties_even();
        if x.is_finite() && r >= lo as f64 && r <= hi as f64 && (r as i128) <= hi {
            prop_assert_eq!(got, Ok(Value::Int(r as i128)));
        } else {
            prop_assert_eq!(got, Err(Fault::Conversion));
        }
    }

    #[test]
    fn int_to_real_rounds_once(v in any::<i64>()) {
        prop_assert_eq!(convert(E::Lint, E::Real, &Value::Int(v.into())), Ok(Value::Real((v as f32).into())));
        prop_assert_eq!(convert(E::Lint, E::Lreal, &Value::Int(v.into())), Ok(Value::Real(v as f64)));
    }

    #[test]
    fn text_round_trips((t, v) in typed_value()) {
        // What *_TO_STRING prints, STRING_TO_* reads back (CHAR reads the
        // first character, so it is its own case).
        prop_assume!(!matches!(t, E::String | E::Wstring | E::Char | E::Wchar));
        let text = convert(t, E::String, &v).expect("to string");
        let back = convert(E::String, t, &text);
        prop_assert!(back.as_ref().is_ok_and(|b| same_real(b, &v)), "{:?} {:?} -> {:?} -> {:?}", t, v, text, back);
        let wtext = convert(t, E::Wstring, &v).expect("to wstring");
        let wback = convert(E::Wstring, t, &wtext).expect("from wstring");
        prop_assert!(same_real(&wback, &v));
    }

    #[test]
    fn real_text_is_shortest(x in any::<f32>()) {
        prop_assume!(x.is_finite());
        let text = to_text(E::Real, &Value::Real(x.into()));
        let mantissa: String = text.split('E').next().unwrap_or("").chars().filter(char::is_ascii_digit).collect();
        let significant = mantissa.trim_start_matches('0').trim_end_matches('0').len();
        // Never more significant digits than an f32 needs (9).
        prop_assert!(significant <= 9, "{}", text);
        prop_assert_eq!(text.replace('E', "e").parse::<f32>().ok(), Some(x));
    }

    #[test]
    fn bcd_round_trips(n in 0i128..10_000_000_000_000_000) {
        let bcd = int_to_bcd(E::Ulint, E::Lword, &Value::Int(n)).expect("to bcd");
        prop_assert_eq!(bcd_to_int(E::Lword, E::Ulint, &bcd), Ok(Value::Int(n)));
    }

    #[test]
    fn date_time_parts_recompose(ns in any::<i64>()) {
        let dt = Value::Int(ns.into());
        let date = convert(E::Dt, E::Date, &dt).expect("date");
        let tod = convert(E::Dt, E::Tod, &dt).expect("tod");
        let back = call(Intrinsic::ConcatDateTod, &[E::Date, E::Tod], &[date, tod], E::Dt).expect("concat");
        prop_assert_eq!(back.value, dt);
    }

    #[test]
    fn common_type_is_symmetric(a in any_type(), b in any_type()) {
        prop_assert_eq!(common_type(a, b), common_type(b, a));
        if let Some(c) = common_type(a, b) {
            if is_integer(a) && is_integer(b) {
                prop_assert!(is_integer(c));
            }
        }
    }

    #[test]
    fn string_functions_obey_their_laws(
        a in proptest::collection::vec(any::<u8>(), 0..10),
        b in proptest::collection::vec(any::<u8>(), 0..4),
        l in -12i128..12,
        p in -12i128..12,
    ) {
        let s = |x: &[u8]| Value::Str(x.to_vec());
        let n = Value::Int;
        let str3 = [E::String, E::Int, E::Int];
        let len = a.len() as i128;
        let take = |v: Value| match v { Value::Str(x) => x, _ => Vec::new() };
        let f = |i, ts: &[E], args: &[Value]| take(call(i, ts, args, E::String).expect("string fn").value);

        let left = f(Intrinsic::Left, &str3[..2], &[s(&a), n(l)]);
        prop_assert_eq!(left.len() as i128, l.clamp(0, len));
        prop_assert!(a.starts_with(&left));
        let right = f(Intrinsic::Right, &str3[..2], &[s(&a), n(l)]);
        prop_assert!(a.ends_with(&right));
        let mid = f(Intrinsic::Mid, &str3, &[s(&a), n(l), n(p)]);
        prop_assert!(mid.len() as i128 <= l.max(0));
        let start = (p.max(1) - 1).min(len) as usize;
        prop_assert_eq!(&mid[..], &a[start..start + mid.len()]);

        let ins = f(Intrinsic::Insert, &[E::String, E::String, E::Int], &[s(&a), s(&b), n(p)]);
        prop_assert_eq!(ins.len(), a.len() + b.len());
        let del = f(Intrinsic::Delete, &str3, &[s(&a), n(l), n(p)]);
        prop_assert!(del.len() <= a.len());
        let rep = f(Intrinsic::Replace, &[E::String, E::String, E::Int, E::Int], &[s(&a), s(&b), n(l), n(p)]);
        // REPLACE is DELETE, then INSERT of IN2 after the character before P.
        let at = (p.max(1) - 1).min(del.len() as i128);
        let del_then_ins = f(Intrinsic::Insert, &[E::String, E::String, E::Int], &[s(&del), s(&b), n(at)]);
        prop_assert_eq!(rep, del_then_ins);

        let found = call(Intrinsic::Find, &[E::String, E::String], &[s(&a), s(&b)], E::Dint)
            .expect("find").value.as_int().unwrap_or(-1);
        if found > 0 {
            let at = f(Intrinsic::Mid, &str3, &[s(&a), n(b.len() as i128), n(found)]);
            prop_assert_eq!(&at, &b);
        } else {
            prop_assert!(b.is_empty() || !a.windows(b.len()).any(|w| w == &b[..]));
        }
    }

    #[test]
    fn nothing_panics_on_any_input(
        from in any_type(),
        to in any_type(),
        v in wild_value(),
        w in wild_value(),
        op in proptest::sample::select(vec![
            BinOp::Add, BinOp::Sub, BinOp::Mul, BinOp::Div, BinOp::Mod, BinOp::Pow, BinOp::And,
            BinOp::Or, BinOp::Xor, BinOp::Eq, BinOp::Ne, BinOp::Lt, BinOp::Le, BinOp::Gt, BinOp::Ge,
        ]),
    ) {
        let _ = convert(from, to, &v);
        let _ = stc_values::trunc(from, to, &v);
        let _ = bcd_to_int(from, to, &v);
        let _ = int_to_bcd(from, to, &v);
        let _ = binary(op, from, &v, to, &w, to);
        let _ = binary(op, from, &v, to, &w, from);
        let _ = unary(UnOp::Neg, from, &v);
        let _ = unary(UnOp::Not, from, &v);
        let _ = to_text(from, &v);
        let _ = stc_values::truncate(&v, 3);
        for f in stc_values::all() {
            let n = f.params.len();
            let types = vec![from; n];
            let mut args = vec![v.clone(); n];
            if let Some(last) = args.last_mut() {
                *last = w.clone();
            }
            let _ = call(f.intrinsic, &types, &args, to);
            let _ = call(f.intrinsic.resolve(&types, to), &types, &args, to);
        }
        for f in [Intrinsic::SplitDate, Intrinsic::SplitTod, Intrinsic::SplitDt] {
            let _ = stc_values::split(f, from, &v);
        }
    }

    #[test]
    fn well_typed_calls_of_every_function_never_panic(
        (t, v) in typed_value(),
        (u, w) in typed_value(),
        k in -3i128..5,
    ) {
        for f in stc_values::all() {
            let n = f.params.len();
            let mut types = vec![t; n];
            let mut args = vec![v.clone(); n];
            if n > 1 {
                types[n - 1] = u;
                args[n - 1] = w.clone();
                types[0] = E::Int;
                args[0] = Value::Int(k);
            }
            for result in [t, u, E::Int, E::Lreal, E::Bool, E::String] {
                let _ = call(f.intrinsic.resolve(&types, result), &types, &args, result);
            }
        }
    }
}
