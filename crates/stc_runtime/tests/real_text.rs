//! The text of REAL and LREAL values (docs/semantics-notes.md): the
//! explicit formatter of `stc_syntax::real` reads back to the same value
//! and prints the same bytes as the implementations it replaced (Rust's
//! `Debug` rewritten to ST form for the text report, serde_json for the JSON
//! report), on edge values and many random bit patterns (subnormals, NaN,
//! the infinities and -0.0 included).

use proptest::prelude::*;
use stc_syntax::real;

/// The former `stc_syntax::literal::format_real`.
fn old_format_real(v: f64) -> String {
    let s = format!("{v:?}");
    match s.split_once('e') {
        Some((m, e)) => {
            let m = if m.contains('.') {
                m.to_string()
            } else {
                format!("{m}.0")
            };
            format!("{m}E{e}")
        }
        None => s,
    }
}

/// The former text of a REAL/LREAL in reports (`stc_values::to_text`).
fn old_text(x: f64, single: bool) -> String {
    if x.is_nan() {
        return "NaN".into();
    }
    if x.is_infinite() {
        return if x > 0.0 { "INF" } else { "-INF" }.into();
    }
    if single {
        let digits = format!("{:?}", x as f32);
        match digits.parse::<f64>() {
            Ok(y) => old_format_real(y),
            Err(_) => old_format_real(x),
        }
    } else {
        old_format_real(x)
    }
}

/// The former `json_real`.
fn old_json(x: f64, single: bool) -> String {
    if x.is_nan() {
        return "\"NaN\"".into();
    }
    if x.is_infinite() {
        return if x > 0.0 { "\"INF\"" } else { "\"-INF\"" }.into();
    }
    let text = if single {
        serde_json::to_string(&(x as f32))
    } else {
        serde_json::to_string(&x)
    };
    text.unwrap_or_else(|_| "null".into())
}

fn new_text(x: f64, single: bool) -> String {
    let e = if single {
        stc_values::ElemType::Real
    } else {
        stc_values::ElemType::Lreal
    };
    stc_values::to_text(e, &stc_values::Value::Real(x))
}

fn reads_back(text: &str, x: f64, single: bool) -> bool {
    let t = text.trim_matches('"').replace('E', "e");
    let t = match t.as_str() {
        "INF" => "inf".to_string(),
        "-INF" => "-inf".to_string(),
        _ => t,
    };
    if single {
        t.parse::<f32>().is_ok_and(|y| {
            let x = x as f32;
            y.to_bits() == x.to_bits() || (y.is_nan() && x.is_nan())
        })
    } else {
        t.parse::<f64>()
            .is_ok_and(|y| y.to_bits() == x.to_bits() || (y.is_nan() && x.is_nan()))
    }
}

fn check(x: f64, single: bool) -> Result<(), String> {
    let (t, j) = (new_text(x, single), real::json(x, single));
    let (ot, oj) = (old_text(x, single), old_json(x, single));
    if t != ot {
        return Err(format!("text of {x:e} (single {single}): {t} != {ot}"));
    }
    if j != oj {
        return Err(format!("json of {x:e} (single {single}): {j} != {oj}"));
    }
    if stc_syntax::literal::format_real(x) != old_format_real(x) {
        return Err(format!("format_real of {x:e}"));
    }
    if !reads_back(&t, x, single) || !reads_back(&j, x, single) {
        return Err(format!("{t} / {j} do not read back as {x:e}"));
    }
    Ok(())
}

fn check_both(x: f64) {
    check(x, false).unwrap();
    check(f64::from(x as f32), true).unwrap();
}

#[test]
fn edge_values() {
    let mut xs = vec![
        0.0,
        -0.0,
        1.0,
        -1.0,
        0.1,
        0.5,
        f64::NAN,
        -f64::NAN,
        f64::INFINITY,
        f64::NEG_INFINITY,
        f64::MIN_POSITIVE,
        f64::MAX,
        f64::MIN,
        f64::EPSILON,
        f64::from_bits(1),
        f64::from_bits(0x000f_ffff_ffff_ffff),
        f64::from(f32::MIN_POSITIVE),
        f64::from(f32::MAX),
        f64::from(f32::from_bits(1)),
        f64::from(f32::from_bits(0x007f_ffff)),
        9007199254740993.0,
        123456789012345680000.0,
    ];
    for e in -330..=310 {
        let p = format!("1e{e}").parse::<f64>().unwrap();
        for m in [1.0, 1.5, 9.999999, 2.5, 0.999999999999, 5.0, 7.25] {
            xs.push(p * m);
            xs.push(-p * m);
            xs.push(f64::from_bits((p * m).to_bits().wrapping_add(1)));
            xs.push(f64::from_bits((p * m).to_bits().wrapping_sub(1)));
        }
    }
    for k in 0..64 {
        xs.push(2f64.powi(k) + 0.5);
        xs.push(2f64.powi(k));
        xs.push(-(2f64.powi(-k)));
    }
    for x in xs {
        check_both(x);
    }
}

/// f32 values of every binade from 1.0 up, including those where two
/// shortest candidates tie (1048576.25 is halfway between 1048576.2 and
/// 1048576.3, both of which read back).
#[test]
fn f32_values_with_wide_intervals() {
    let x = f64::from(f32::from_bits(0x4980_0002));
    assert_eq!(x, 1_048_576.25);
    check(x, true).unwrap();
    assert_eq!(new_text(x, true), "1048576.3");
    assert_eq!(real::json(x, true), "1048576.2");
    let mut bits: u32 = 0x3f80_0000; // 1.0
    let mut ties = 0;
    while bits < 0x7f80_0000 {
        for k in 0..16 {
            let x = f64::from(f32::from_bits(bits + k));
            check(x, true).unwrap();
            check(-x, true).unwrap();
            let up = real::shortest(x, true, real::Ties::Up);
            ties += usize::from(up != real::shortest(x, true, real::Ties::Even));
        }
        bits += 0x0001_3579;
    }
    // The two rules differ on some of these values: both are exercised.
    assert!(ties > 0);
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(20_000))]

    #[test]
    fn random_f64_bits(bits in any::<u64>()) {
        let x = f64::from_bits(bits);
        prop_assert_eq!(check(x, false), Ok(()));
    }

    #[test]
    fn random_f32_bits(bits in any::<u32>()) {
        let x = f64::from(f32::from_bits(bits));
        prop_assert_eq!(check(x, true), Ok(()));
    }

    #[test]
    fn random_moderate_values(m in -1_000_000_000i64..1_000_000_000, e in -30i32..30) {
        let x = m as f64 * 10f64.powi(e);
        prop_assert_eq!(check(x, false), Ok(()));
        prop_assert_eq!(check(f64::from(x as f32), true), Ok(()));
    }
}
