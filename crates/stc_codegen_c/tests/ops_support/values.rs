//! Operand generators: proptest strategies for every elementary type,
//! biased toward the edges (type limits, ties of rounding, NaN and the
//! infinities, midnight, invalid UTF-16, Windows-1252's upper half), and
//! near-valid literal texts for the `STRING_TO_*` parsers.

use proptest::prelude::*;
use proptest::strategy::ValueTree;
use proptest::test_runner::TestRunner;
use stc_syntax::token::ElemType;
use stc_values::Value;

use ElemType as E;

/// Draws values from strategies, deterministically.
pub struct Gen {
    runner: TestRunner,
}

impl Default for Gen {
    fn default() -> Self {
        Gen {
            runner: TestRunner::deterministic(),
        }
    }
}

impl Gen {
    pub fn draw<S: Strategy>(&mut self, s: &S) -> S::Value {
        s.new_tree(&mut self.runner)
            .expect("a value from the strategy")
            .current()
    }

    /// `n` operands of type `e`.
    pub fn values(&mut self, e: ElemType, n: usize) -> Vec<Value> {
        let s = value(e);
        (0..n).map(|_| self.draw(&s)).collect()
    }
}

const NS_PER_D: i128 = 86_400_000_000_000;

fn ints(lo: i128, hi: i128) -> BoxedStrategy<Value> {
    let mut edges: Vec<i128> = vec![lo, hi, 0, 1, 2, 3, 7, 9, 10, 16, 100, 127, 128, 255, 256];
    edges.extend([
        lo + 1,
        hi - 1,
        hi / 2,
        lo / 2,
        1000,
        9999,
        10000,
        65535,
        65536,
    ]);
    edges.extend([-1, -2, -3, -7, -10, -100, -128, -129, -32768, 32767, 32768]);
    edges.extend([
        i128::from(i32::MAX),
        i128::from(u32::MAX),
        i128::from(i32::MIN),
    ]);
    edges.extend([
        i128::from(i64::MAX),
        i128::from(i64::MIN),
        86_400,
        1_000_000,
    ]);
    edges.retain(|v| (lo..=hi).contains(v));
    let span = (hi - lo) as u128;
    prop_oneof![
        3 => proptest::sample::select(edges),
        4 => any::<u64>().prop_map(move |x| lo + ((x as u128) % (span + 1)) as i128),
        3 => (-300i128..300).prop_map(move |x| x.clamp(lo, hi)),
    ]
    .prop_map(Value::Int)
    .boxed()
}

fn f32s() -> BoxedStrategy<f64> {
    let specials: Vec<f32> = vec![
        0.0,
        -0.0,
        1.0,
        -1.0,
        0.5,
        -0.5,
        1.5,
        2.5,
        -2.5,
        3.5,
        -1.5,
        0.1,
        1e-4,
        9.99e-5,
        1e16,
        9.9e15,
        127.5,
        128.0,
        -128.5,
        -128.6,
        255.5,
        255.4,
        32767.5,
        32767.4,
        -32768.5,
        65535.5,
        2147483648.0,
        -2147483648.0,
        4294967296.0,
        9.223372e18,
        -9.223372e18,
        1.8446743e19,
        1.8446744e19,
        f32::MAX,
        f32::MIN_POSITIVE,
        1e-45,
        f32::INFINITY,
        f32::NEG_INFINITY,
        f32::NAN,
        16777217.0,
        3.4028235e38,
        1e10,
        123.456,
    ];
    prop_oneof![
        3 => proptest::sample::select(specials).prop_map(f64::from),
        4 => any::<u32>().prop_map(|b| f64::from(f32::from_bits(b))),
        2 => (-2000i32..2000).prop_map(|k| f64::from(k as f32 / 2.0)),
        2 => (-1e6f64..1e6).prop_map(|x| (x as f32) as f64),
        1 => (-40i32..40, 1u32..100000).prop_map(|(e, m)| ((m as f64) * 10f64.powi(e)) as f32 as f64),
    ]
    .boxed()
}

fn f64s() -> BoxedStrategy<f64> {
    let specials: Vec<f64> = vec![
        0.0,
        -0.0,
        1.0,
        -1.0,
        0.5,
        1.5,
        2.5,
        -2.5,
        -3.5,
        0.1,
        1e-4,
        9.999999999999999e-5,
        1e16,
        9999999999999998.0,
        127.5,
        128.0,
        -128.5,
        255.5,
        32767.5,
        -32768.5,
        -32768.51,
        65535.5,
        2147483647.5,
        2147483647.4,
        -2147483648.5,
        4294967295.5,
        i64::MAX as f64,
        i64::MIN as f64,
        9_223_372_036_854_774_784.0,
        u64::MAX as f64,
        18_446_744_073_709_549_568.0,
        f64::MAX,
        f64::MIN_POSITIVE,
        5e-324,
        f64::INFINITY,
        f64::NEG_INFINITY,
        f64::NAN,
        9007199254740993.0,
        1e300,
        1e-300,
        1e22,
        1e23,
        5e-7,
        1.5e-6,
        -2.5e-6,
        1e19,
    ];
    prop_oneof![
        3 => proptest::sample::select(specials),
        4 => any::<u64>().prop_map(f64::from_bits),
        2 => (-2000i32..2000).prop_map(|k| f64::from(k) / 2.0),
        2 => -1e12f64..1e12,
        1 => (-300i32..300, 1u64..1_000_000_000).prop_map(|(e, m)| (m as f64) * 10f64.powi(e)),
        1 => (0u64..1 << 20).prop_map(|k| ((1u64 << 60) + k * 128) as f64),
    ]
    .boxed()
}

/// Bytes of a STRING: ASCII, Windows-1252's upper half, anything.
fn bytes() -> BoxedStrategy<Vec<u8>> {
    let byte = prop_oneof![
        4 => b'a'..=b'e',
        2 => b'0'..=b'9',
        1 => proptest::sample::select(b" #._-+:ETe".to_vec()),
        1 => 0x80u8..=0x9f,
        1 => any::<u8>(),
    ];
    proptest::collection::vec(byte, 0..9).boxed()
}

/// Code units of a WSTRING, lone surrogates and pairs included.
fn units() -> BoxedStrategy<Vec<u16>> {
    let unit = prop_oneof![
        4 => u16::from(b'a')..=u16::from(b'e'),
        2 => u16::from(b'0')..=u16::from(b'9'),
        1 => proptest::sample::select(vec![0x20ac, 0xe9, 0x3a9, 0x80, 0x81, 0x178, 0xffff]),
        1 => 0xd800u16..0xe000,
        1 => any::<u16>(),
    ];
    let pair = (0xd800u16..0xdc00, 0xdc00u16..0xe000).prop_map(|(a, b)| vec![a, b]);
    prop_oneof![
        4 => proptest::collection::vec(unit, 0..9),
        1 => (proptest::collection::vec(u16::from(b'a')..u16::from(b'z'), 0..3), pair)
            .prop_map(|(mut a, p)| { a.extend(p); a }),
    ]
    .boxed()
}

/// A strategy of operands of type `e`.
pub fn value(e: ElemType) -> BoxedStrategy<Value> {
    match e {
        E::Bool => any::<bool>().prop_map(Value::Bool).boxed(),
        E::Real => f32s().prop_map(Value::Real).boxed(),
        E::Lreal => f64s().prop_map(Value::Real).boxed(),
        E::Time | E::Ltime => prop_oneof![
            2 => ints(i64::MIN.into(), i64::MAX.into()),
            2 => (-100_000_000i128..100_000_000).prop_map(|ms| Value::Int(ms * 1_000_000)),
            1 => (-10_000i128..10_000).prop_map(Value::Int),
            1 => (-3i128..4).prop_map(|d| Value::Int(d * NS_PER_D)),
        ]
        .boxed(),
        E::Date | E::Ldate => prop_oneof![
            6 => (-800_000i128..3_000_000).prop_map(|d| Value::Int(d * 86_400)),
            1 => (-106_752i128..106_752).prop_map(|d| Value::Int(d * 86_400)),
            1 => any::<i64>().prop_map(|x| Value::Int(x.into())),
        ]
        .boxed(),
        E::Tod | E::Ltod => prop_oneof![
            3 => (0i128..NS_PER_D).prop_map(Value::Int),
            2 => (0i128..86_400_000).prop_map(|ms| Value::Int(ms * 1_000_000)),
            1 => proptest::sample::select(vec![0, 1, NS_PER_D - 1, 1_000_000, 500_000_000])
                .prop_map(Value::Int),
        ]
        .boxed(),
        E::Dt | E::Ldt => prop_oneof![
            2 => any::<i64>().prop_map(|x| Value::Int(x.into())),
            2 => (-9_000_000_000i128..9_000_000_000).prop_map(|s| Value::Int(s * 1_000_000_000)),
            1 => (-106_752i128..106_752).prop_map(|d| Value::Int(d * NS_PER_D)),
            1 => proptest::sample::select(vec![i64::MIN, i64::MAX, 0, -1, 1])
                .prop_map(|x| Value::Int(x.into())),
        ]
        .boxed(),
        E::String => prop_oneof![
            3 => bytes().prop_map(Value::Str),
            1 => text_any().prop_map(|t| Value::string(&t)),
        ]
        .boxed(),
        E::Wstring => prop_oneof![
            3 => units().prop_map(Value::WStr),
            1 => text_any().prop_map(|t| Value::wstring(&t)),
        ]
        .boxed(),
        _ => match stc_values::int_range(e) {
            Some((lo, hi)) => ints(lo, hi),
            None => Just(Value::Int(0)).boxed(),
        },
    }
}

/// Random literal-like texts of any kind.
fn text_any() -> BoxedStrategy<String> {
    prop_oneof![
        text_for(E::Dint),
        text_for(E::Lreal),
        text_for(E::Time),
        text_for(E::Date),
        text_for(E::Tod),
        text_for(E::Dt),
        text_for(E::Bool),
    ]
    .boxed()
}

fn digits(n: std::ops::Range<usize>) -> BoxedStrategy<String> {
    proptest::collection::vec(
        prop_oneof![9 => (b'0'..=b'9').prop_map(char::from), 1 => Just('_')],
        n,
    )
    .prop_map(|v| v.into_iter().collect())
    .boxed()
}

fn hex_digits() -> BoxedStrategy<String> {
    proptest::collection::vec(
        prop_oneof![
            6 => proptest::sample::select(b"0123456789abcdefABCDEF".to_vec()).prop_map(char::from),
            1 => Just('_'),
            1 => Just('g'),
        ],
        0..10,
    )
    .prop_map(|v| v.into_iter().collect())
    .boxed()
}

fn blank() -> BoxedStrategy<String> {
    prop_oneof![
        6 => Just(String::new()),
        1 => Just(" ".to_string()),
        1 => Just("\t \r\n".to_string()),
        1 => Just("\u{a0}".to_string()),
    ]
    .boxed()
}

fn sign() -> BoxedStrategy<String> {
    proptest::sample::select(vec!["", "", "", "-", "+", "--", "+-", "-+"])
        .prop_map(String::from)
        .boxed()
}

/// A type prefix: right, wrong or absent, in any case.
fn prefix(own: &'static str) -> BoxedStrategy<String> {
    let lower = own.to_ascii_lowercase();
    prop_oneof![
        8 => Just(String::new()),
        2 => Just(format!("{own}#")),
        1 => Just(format!("{lower}#")),
        1 => proptest::sample::select(vec!["INT#", "REAL#", "BOOL#", "T#", "X#", "#", "1#"])
            .prop_map(String::from),
    ]
    .boxed()
}

/// Near-valid literal texts of type `e` (the forms parse_value accepts,
/// mutated).
pub fn text_for(e: ElemType) -> BoxedStrategy<String> {
    let core: BoxedStrategy<String> = match e {
        E::Bool => proptest::sample::select(vec![
            "TRUE", "true", "False", "FALSE", "1", "0", "2", "yes", "TRUE_", "T", "",
        ])
        .prop_map(String::from)
        .boxed(),
        E::Real | E::Lreal => prop_oneof![
            4 => (sign(), digits(1..6), proptest::option::of(digits(0..6)), proptest::option::of((sign(), digits(0..5))))
                .prop_map(|(s, i, f, x)| {
                    let mut t = s + &i;
                    if let Some(f) = f { t.push('.'); t.push_str(&f); }
                    if let Some((es, ed)) = x { t.push('E'); t.push_str(&es); t.push_str(&ed); }
                    t
                }),
            1 => proptest::sample::select(vec![
                "INF", "-INF", "inf", "NaN", "nan", "-NaN", "+NaN", "infinity", "1.", ".5", "1,5",
                "1.5E", "1e39", "3.4028236e38", "3.4028235e38", "1e-50", "1e-400", "1e309",
                "0.000000000000000000000000000000000000000000001", "2.4703282292062327e-324",
                "2.4703282292062328e-324", "1.7976931348623158e308", "0e99999999999999999999",
                "123456789012345678901234567890", "1_000.000_001", "16#FF", "1e0_1",
                "0.1000000000000000055511151231257827021181583404541015625",
                "0.1000000000000000055511151231257827021181583404541015626",
            ]).prop_map(String::from),
            1 => f64s().prop_map(|x| format!("{x:?}")),
            1 => f64s().prop_map(|x| format!("{x:e}")),
        ]
        .boxed(),
        E::Time | E::Ltime => prop_oneof![
            4 => (sign(), proptest::collection::vec((digits(1..4), proptest::sample::select(vec!["d", "h", "m", "s", "ms", "us", "ns", "MS", "x", ""]), any::<bool>()), 1..4), proptest::option::of(digits(1..22)))
                .prop_map(|(s, parts, frac)| {
                    let mut t = s;
                    let n = parts.len();
                    for (i, (num, unit, sep)) in parts.into_iter().enumerate() {
                        t.push_str(&num);
                        if i + 1 == n {
                            if let Some(f) = &frac { t.push('.'); t.push_str(f); }
                        }
                        t.push_str(unit);
                        if sep && i + 1 < n { t.push('_'); }
                    }
                    t
                }),
            1 => proptest::sample::select(vec![
                "1d2h3m4s5ms6us7ns", "25h", "1h61m", "1.5.2s", "1.2_3s", "1s_", "1s__2ms",
                "106751d23h47m16s854ms775us807ns", "106751d23h47m16s854ms775us808ns",
                "-106751d23h47m16s854ms775us807ns", "9223372036854775807ns",
                "9223372036854775808ns", "18446744073709551616ns", "1.999999999999999999999s",
                "0.5ms", "1ms1s", "1s1s", ".5s", "5", "-", "", "1m60s", "1m59s", "1h60m",
                "1h59m", "1d24h", "1d23h", "1s1000ms", "1s999ms", "1ms1000us", "1ms999us",
                "1us1000ns", "1us999ns", "0d25h", "1m59.5s", "1m60.5s", "1s_500ms",
            ]).prop_map(String::from),
        ]
        .boxed(),
        E::Date | E::Ldate => prop_oneof![
            1 => proptest::sample::select(vec![
                "2023-02-29", "2024-02-29", "2100-02-29", "2000-02-29", "9999-12-31",
                "10000-01-01", "0000-01-01", "1970-1-1", "1970-01-00", "1970-13-01",
                "1970-12-32", "1970-04-31", "1970-04-30", "2262-04-11", "1677-09-21",
                "1970_1-01-01",
            ]).prop_map(String::from),
            4 => date_core(),
        ]
        .boxed(),
        E::Tod | E::Ltod => prop_oneof![
            1 => proptest::sample::select(vec![
                "24:00:00", "23:59:59.999999999", "23:59:59.9999999999", "23:60:00",
                "23:59:60", "0:0:0", "00:00:00.", "00:00:00._5", "1_2:00:00", "12:00",
                "12:00:00:00", "12:00:00.5.5",
            ]).prop_map(String::from),
            4 => tod_core(),
        ]
        .boxed(),
        E::Dt | E::Ldt => prop_oneof![
            1 => proptest::sample::select(vec![
                "2262-04-11-23:47:16.854775807", "2262-04-11-23:47:16.854775808",
                "1677-09-21-00:12:43.145224192", "1677-09-21-00:12:43.145224191",
                "1970-01-01-24:00:00", "1970-01-01", "1970-01-01-00:00", "1970-01-01T00:00:00",
            ]).prop_map(String::from),
            4 => dt_core(),
        ]
        .boxed(),
        _ => int_core(),
    };
    with_affixes(e, core)
}

fn date_core() -> BoxedStrategy<String> {
    (
        digits(1..6),
        digits(1..3),
        digits(1..3),
        proptest::sample::select(vec!["-", "-", "-", "/", ""]),
    )
        .prop_map(|(y, m, d, sep)| format!("{y}-{m}{sep}{d}"))
        .boxed()
}

fn tod_core() -> BoxedStrategy<String> {
    (
        digits(1..3),
        digits(1..3),
        digits(1..3),
        proptest::option::of(proptest::collection::vec(b'0'..=b'9', 0..12)),
    )
        .prop_map(|(h, m, s, f)| {
            let mut t = format!("{h}:{m}:{s}");
            if let Some(f) = f {
                t.push('.');
                t.extend(f.into_iter().map(char::from));
            }
            t
        })
        .boxed()
}

fn dt_core() -> BoxedStrategy<String> {
    (
        digits(4..5),
        digits(1..3),
        digits(1..3),
        digits(1..3),
        digits(1..3),
        digits(1..3),
    )
        .prop_map(|(y, mo, d, h, mi, s)| format!("{y}-{mo}-{d}-{h}:{mi}:{s}"))
        .boxed()
}

fn int_core() -> BoxedStrategy<String> {
    prop_oneof![
            3 => (sign(), digits(1..22)).prop_map(|(s, d)| s + &d),
            2 => (sign(), proptest::sample::select(vec!["16#", "2#", "8#", "16#", "+16#", "1_6#", "3#", "10#", "#", "016#"]), hex_digits())
                .prop_map(|(s, b, d)| s + b + &d),
            1 => proptest::sample::select(vec![
                "127", "128", "-128", "-129", "255", "256", "32767", "32768", "-32768", "65535",
                "65536", "2147483647", "2147483648", "-2147483648", "4294967295", "4294967296",
                "9223372036854775807", "9223372036854775808", "-9223372036854775808",
                "18446744073709551615", "18446744073709551616", "-0", "0", "1__0", "_1", "1_",
            ]).prop_map(String::from),
    ]
    .boxed()
}

fn with_affixes(e: ElemType, core: BoxedStrategy<String>) -> BoxedStrategy<String> {
    let name = e.name();
    let time_prefix: BoxedStrategy<String> = match e {
        E::Time | E::Ltime => proptest::sample::select(vec![
            "", "", "T#", "t#", "TIME#", "LT#", "LTIME#", "D#", "TOD#",
        ])
        .prop_map(String::from)
        .boxed(),
        E::Date | E::Ldate => proptest::sample::select(vec![
            "", "", "D#", "d#", "DATE#", "LD#", "LDATE#", "T#", "DT#",
        ])
        .prop_map(String::from)
        .boxed(),
        E::Tod | E::Ltod => proptest::sample::select(vec![
            "",
            "",
            "TOD#",
            "tod#",
            "TIME_OF_DAY#",
            "LTOD#",
            "LTIME_OF_DAY#",
            "T#",
        ])
        .prop_map(String::from)
        .boxed(),
        E::Dt | E::Ldt => proptest::sample::select(vec![
            "",
            "",
            "DT#",
            "dt#",
            "DATE_AND_TIME#",
            "LDT#",
            "LDATE_AND_TIME#",
            "D#",
        ])
        .prop_map(String::from)
        .boxed(),
        _ => prefix(name),
    };
    (blank(), time_prefix, core, blank())
        .prop_map(|(a, p, c, b)| format!("{a}{p}{c}{b}"))
        .boxed()
}
