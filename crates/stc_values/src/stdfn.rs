//! The table of IEC 61131-3 standard functions: one [`Intrinsic`] id per
//! function for the back ends to dispatch on, and one signature per name
//! for the analyser to type calls with.
//!
//! Signatures use the standard's parameter names (`IN`, `IN1`.., `N`, `G`,
//! `K`, `MN`, `MX`, `L`, `P`, `Y`, `X`, `YEAR`...), since users call them
//! formally. Generic parameters are type variables ([`TyPat::Var`]): every
//! position with the same index takes the same concrete type, which must be
//! in the variable's family. A result variable that appears among no input
//! (TRUNC, LEN, FIND, DAY_OF_WEEK, `x_TO_BCD`) is resolved by the caller
//! from the context, like an untyped literal.
//!
//! Besides the fixed table ([`all`]), [`lookup`] knows every generated name:
//! `A_TO_B` for each pair [`conversion_allowed`] accepts, the 3rd-edition
//! generic `TO_B`, `TRUNC` and `A_TRUNC_B`, `BCD_TO_B` / `A_TO_BCD` (2nd
//! edition) and `A_BCD_TO_B` / `A_TO_BCD_B` (3rd edition), and the typed
//! forms of the overloaded functions (2nd edition 2.5.1.4, table 21:
//! `ADD_INT`, `LIMIT_REAL`, `SHL_BYTE`, `EQ_STRING`), see [`typed_forms`]. Generic forms
//! cannot know their argument type: their intrinsic carries a placeholder
//! (see [`Intrinsic::resolve`]); [`crate::call()`] always works from the
//! concrete argument and result types it is given.

use crate::convert::conversion_allowed;
use crate::types::{is_bit_string, is_integer, is_real};
use stc_syntax::token::{ElemType, GenericType};
use std::collections::HashMap;
use std::sync::OnceLock;

use ElemType as E;
use GenericType as G;

/// The standard functions, by what they compute. One id may serve several
/// names: the `L` variants of the time functions (`ADD_LTIME` is
/// `AddTime`, `CONCAT_LTOD` is `ConcatTod`) and the 2nd-edition spellings
/// (`MULTIME` is `MulTime`); [`crate::call()`] tells them apart by the types.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Intrinsic {
    // Numeric (IEC 61131-3 3rd ed. table 23).
    Abs,
    Sqrt,
    Ln,
    Log,
    Exp,
    Sin,
    Cos,
    Tan,
    Asin,
    Acos,
    Atan,
    Atan2,
    Expt,
    // Bit shift (table 26).
    Shl,
    Shr,
    Rol,
    Ror,
    // Selection (table 28).
    Sel,
    Max,
    Min,
    Limit,
    Mux,
    Move,
    // Strings (table 34).
    Len,
    Left,
    Right,
    Mid,
    Concat,
    Insert,
    Delete,
    Replace,
    Find,
    // Time and date (tables 35 and 36).
    AddTime,
    SubTime,
    MulTime,
    DivTime,
    AddTodTime,
    AddDtTime,
    SubTodTime,
    SubDtTime,
    SubDateDate,
    SubTodTod,
    SubDtDt,
    ConcatDateTod,
    ConcatDate,
    ConcatTod,
    ConcatDt,
    /// SPLIT_DATE, SPLIT_TOD, SPLIT_DT and their L variants return their
    /// fields through VAR_OUTPUT parameters, which a [`StdFunction`]
    /// signature cannot express: they are not in [`lookup`]; see
    /// [`crate::split_lookup`] and [`crate::split`].
    SplitDate,
    SplitTod,
    SplitDt,
    DayOfWeek,
    // Conversions (table 22).
    Convert {
        from: ElemType,
        to: ElemType,
    },
    Trunc {
        from: ElemType,
        to: Option<ElemType>,
    },
    BcdToInt {
        from: ElemType,
        to: ElemType,
    },
    IntToBcd {
        from: ElemType,
        to: ElemType,
    },
    // Operator functions: typed by the analyser exactly like the operators.
    Add,
    Sub,
    Mul,
    Div,
    Mod,
    And,
    Or,
    Xor,
    Not,
    Gt,
    Ge,
    Eq,
    Le,
    Lt,
    Ne,
}

impl Intrinsic {
    /// The intrinsic with the concrete types of a resolved call filled in:
    /// conversions get `from` = the first argument's type and `to` = the
    /// result type (generic forms carry placeholders until then). Other
    /// intrinsics are returned unchanged.
    pub fn resolve(self, arg_types: &[ElemType], result: ElemType) -> Intrinsic {
        let Some(&from) = arg_types.first() else {
            return self;
        };
        match self {
            Intrinsic::Convert { .. } => Intrinsic::Convert { from, to: result },
            Intrinsic::Trunc { .. } => Intrinsic::Trunc {
                from,
                to: Some(result),
            },
            Intrinsic::BcdToInt { .. } => Intrinsic::BcdToInt { from, to: result },
            Intrinsic::IntToBcd { .. } => Intrinsic::IntToBcd { from, to: result },
            other => other,
        }
    }
}

/// Type of a parameter or result in a signature.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum TyPat {
    Elem(ElemType),
    /// A type variable: every position with the same index takes the same
    /// concrete type, in the family.
    Var(u8, GenericType),
}

/// One input of a standard function.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Param {
    pub name: &'static str,
    pub ty: TyPat,
}

/// The signature of one standard function name.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct StdFunction {
    pub name: &'static str,
    pub intrinsic: Intrinsic,
    pub params: Vec<Param>,
    pub ret: TyPat,
    /// The last param repeats: a call takes at least `params.len()` inputs,
    /// and the ones after the last param continue its `IN{n}` numbering
    /// (`CONCAT(IN1, IN2, IN3...)`, `MUX(K, IN0, IN1, IN2...)`); see
    /// [`StdFunction::input`].
    pub extensible: bool,
}

impl StdFunction {
    /// Name and type of the `i`-th input (0-based), extensible inputs
    /// included; `None` past the last input.
    pub fn input(&self, i: usize) -> Option<(String, TyPat)> {
        if let Some(p) = self.params.get(i) {
            return Some((p.name.to_string(), p.ty));
        }
        if !self.extensible {
            return None;
        }
        let last = self.params.last()?;
        let base: usize = last.name.strip_prefix("IN")?.parse().ok()?;
        let n = base.checked_add(i - (self.params.len() - 1))?;
        Some((format!("IN{n}"), last.ty))
    }

    /// Whether a call with `n` inputs has the right number of them.
    pub fn accepts_count(&self, n: usize) -> bool {
        if self.extensible {
            n >= self.params.len()
        } else {
            n == self.params.len()
        }
    }
}

fn p(name: &'static str, ty: TyPat) -> Param {
    Param { name, ty }
}

const fn v(i: u8, g: GenericType) -> TyPat {
    TyPat::Var(i, g)
}

const fn el(t: ElemType) -> TyPat {
    TyPat::Elem(t)
}

fn f(name: &'static str, intrinsic: Intrinsic, params: Vec<Param>, ret: TyPat) -> StdFunction {
    StdFunction {
        name,
        intrinsic,
        params,
        ret,
        extensible: false,
    }
}

fn ext(name: &'static str, intrinsic: Intrinsic, params: Vec<Param>, ret: TyPat) -> StdFunction {
    StdFunction {
        extensible: true,
        ..f(name, intrinsic, params, ret)
    }
}

fn fixed_table() -> Vec<StdFunction> {
    use Intrinsic as I;
    let mut t = Vec::new();

    // Numeric functions.
    t.push(f(
        "ABS",
        I::Abs,
        vec![p("IN", v(0, G::AnyNum))],
        v(0, G::AnyNum),
    ));
    for (name, i) in [
        ("SQRT", I::Sqrt),
        ("LN", I::Ln),
        ("LOG", I::Log),
        ("EXP", I::Exp),
        ("SIN", I::Sin),
        ("COS", I::Cos),
        ("TAN", I::Tan),
        ("ASIN", I::Asin),
        ("ACOS", I::Acos),
        ("ATAN", I::Atan),
    ] {
        t.push(f(
            name,
            i,
            vec![p("IN", v(0, G::AnyReal))],
            v(0, G::AnyReal),
        ));
    }
    t.push(f(
        "ATAN2",
        I::Atan2,
        vec![p("Y", v(0, G::AnyReal)), p("X", v(0, G::AnyReal))],
        v(0, G::AnyReal),
    ));
    t.push(f(
        "EXPT",
        I::Expt,
        vec![p("IN1", v(0, G::AnyReal)), p("IN2", v(1, G::AnyNum))],
        v(0, G::AnyReal),
    ));

    // Operator functions.
    let two = |g| vec![p("IN1", v(0, g)), p("IN2", v(0, g))];
    t.push(ext(
        "ADD",
        I::Add,
        two(G::AnyMagnitude),
        v(0, G::AnyMagnitude),
    ));
    t.push(ext("MUL", I::Mul, two(G::AnyNum), v(0, G::AnyNum)));
    t.push(f(
        "SUB",
        I::Sub,
        two(G::AnyMagnitude),
        v(0, G::AnyMagnitude),
    ));
    t.push(f("DIV", I::Div, two(G::AnyNum), v(0, G::AnyNum)));
    t.push(f("MOD", I::Mod, two(G::AnyInt), v(0, G::AnyInt)));
    t.push(f(
        "MOVE",
        I::Move,
        vec![p("IN", v(0, G::Any))],
        v(0, G::Any),
    ));
    for (name, i) in [("AND", I::And), ("OR", I::Or), ("XOR", I::Xor)] {
        t.push(ext(name, i, two(G::AnyBit), v(0, G::AnyBit)));
    }
    t.push(f(
        "NOT",
        I::Not,
        vec![p("IN", v(0, G::AnyBit))],
        v(0, G::AnyBit),
    ));
    for (name, i) in [
        ("GT", I::Gt),
        ("GE", I::Ge),
        ("EQ", I::Eq),
        ("LE", I::Le),
        ("LT", I::Lt),
    ] {
        t.push(ext(name, i, two(G::AnyElementary), el(E::Bool)));
    }
    t.push(f("NE", I::Ne, two(G::AnyElementary), el(E::Bool)));

    // Bit shifts.
    for (name, i) in [
        ("SHL", I::Shl),
        ("SHR", I::Shr),
        ("ROL", I::Rol),
        ("ROR", I::Ror),
    ] {
        t.push(f(
            name,
            i,
            vec![p("IN", v(0, G::AnyBit)), p("N", v(1, G::AnyInt))],
            v(0, G::AnyBit),
        ));
    }

    // Selection.
    t.push(f(
        "SEL",
        I::Sel,
        vec![
            p("G", el(E::Bool)),
            p("IN0", v(0, G::Any)),
            p("IN1", v(0, G::Any)),
        ],
        v(0, G::Any),
    ));
    t.push(ext(
        "MAX",
        I::Max,
        two(G::AnyElementary),
        v(0, G::AnyElementary),
    ));
    t.push(ext(
        "MIN",
        I::Min,
        two(G::AnyElementary),
        v(0, G::AnyElementary),
    ));
    t.push(f(
        "LIMIT",
        I::Limit,
        vec![
            p("MN", v(0, G::AnyElementary)),
            p("IN", v(0, G::AnyElementary)),
            p("MX", v(0, G::AnyElementary)),
        ],
        v(0, G::AnyElementary),
    ));
    t.push(ext(
        "MUX",
        I::Mux,
        vec![
            p("K", v(0, G::AnyInt)),
            p("IN0", v(1, G::Any)),
            p("IN1", v(1, G::Any)),
        ],
        v(1, G::Any),
    ));

    // Strings.
    let s = v(0, G::AnyString);
    t.push(f("LEN", I::Len, vec![p("IN", s)], v(1, G::AnyInt)));
    t.push(f(
        "LEFT",
        I::Left,
        vec![p("IN", s), p("L", v(1, G::AnyInt))],
        s,
    ));
    t.push(f(
        "RIGHT",
        I::Right,
        vec![p("IN", s), p("L", v(1, G::AnyInt))],
        s,
    ));
    t.push(f(
        "MID",
        I::Mid,
        vec![p("IN", s), p("L", v(1, G::AnyInt)), p("P", v(2, G::AnyInt))],
        s,
    ));
    t.push(ext("CONCAT", I::Concat, vec![p("IN1", s), p("IN2", s)], s));
    t.push(f(
        "INSERT",
        I::Insert,
        vec![p("IN1", s), p("IN2", s), p("P", v(1, G::AnyInt))],
        s,
    ));
    t.push(f(
        "DELETE",
        I::Delete,
        vec![p("IN", s), p("L", v(1, G::AnyInt)), p("P", v(2, G::AnyInt))],
        s,
    ));
    t.push(f(
        "REPLACE",
        I::Replace,
        vec![
            p("IN1", s),
            p("IN2", s),
            p("L", v(1, G::AnyInt)),
            p("P", v(2, G::AnyInt)),
        ],
        s,
    ));
    t.push(f(
        "FIND",
        I::Find,
        vec![p("IN1", s), p("IN2", s)],
        v(1, G::AnyInt),
    ));

    // Time and date, in the short and long (L) variants.
    let pair = |a, b| vec![p("IN1", el(a)), p("IN2", el(b))];
    for (short, long, i, (a, b, r), (la, lb, lr)) in [
        (
            "ADD_TIME",
            "ADD_LTIME",
            I::AddTime,
            (E::Time, E::Time, E::Time),
            (E::Ltime, E::Ltime, E::Ltime),
        ),
        (
            "SUB_TIME",
            "SUB_LTIME",
            I::SubTime,
            (E::Time, E::Time, E::Time),
            (E::Ltime, E::Ltime, E::Ltime),
        ),
        (
            "ADD_TOD_TIME",
            "ADD_LTOD_LTIME",
            I::AddTodTime,
            (E::Tod, E::Time, E::Tod),
            (E::Ltod, E::Ltime, E::Ltod),
        ),
        (
            "ADD_DT_TIME",
            "ADD_LDT_LTIME",
            I::AddDtTime,
            (E::Dt, E::Time, E::Dt),
            (E::Ldt, E::Ltime, E::Ldt),
        ),
        (
            "SUB_TOD_TIME",
            "SUB_LTOD_LTIME",
            I::SubTodTime,
            (E::Tod, E::Time, E::Tod),
            (E::Ltod, E::Ltime, E::Ltod),
        ),
        (
            "SUB_DT_TIME",
            "SUB_LDT_LTIME",
            I::SubDtTime,
            (E::Dt, E::Time, E::Dt),
            (E::Ldt, E::Ltime, E::Ldt),
        ),
        (
            "SUB_DATE_DATE",
            "SUB_LDATE_LDATE",
            I::SubDateDate,
            (E::Date, E::Date, E::Time),
            (E::Ldate, E::Ldate, E::Ltime),
        ),
        (
            "SUB_TOD_TOD",
            "SUB_LTOD_LTOD",
            I::SubTodTod,
            (E::Tod, E::Tod, E::Time),
            (E::Ltod, E::Ltod, E::Ltime),
        ),
        (
            "SUB_DT_DT",
            "SUB_LDT_LDT",
            I::SubDtDt,
            (E::Dt, E::Dt, E::Time),
            (E::Ldt, E::Ldt, E::Ltime),
        ),
        (
            "CONCAT_DATE_TOD",
            "CONCAT_DATE_LTOD",
            I::ConcatDateTod,
            (E::Date, E::Tod, E::Dt),
            (E::Date, E::Ltod, E::Ldt),
        ),
    ] {
        t.push(f(short, i, pair(a, b), el(r)));
        t.push(f(long, i, pair(la, lb), el(lr)));
    }
    for (name, i, d) in [
        ("MUL_TIME", I::MulTime, E::Time),
        ("MULTIME", I::MulTime, E::Time),
        ("MUL_LTIME", I::MulTime, E::Ltime),
        ("DIV_TIME", I::DivTime, E::Time),
        ("DIVTIME", I::DivTime, E::Time),
        ("DIV_LTIME", I::DivTime, E::Ltime),
    ] {
        t.push(f(
            name,
            i,
            vec![p("IN1", el(d)), p("IN2", v(0, G::AnyNum))],
            el(d),
        ));
    }
    let fields = |names: &[&'static str]| -> Vec<Param> {
        names
            .iter()
            .zip(0u8..)
            .map(|(&n, k)| p(n, v(k, G::AnyInt)))
            .collect()
    };
    const DATE_FIELDS: [&str; 3] = ["YEAR", "MONTH", "DAY"];
    const TOD_FIELDS: [&str; 4] = ["HOUR", "MINUTE", "SECOND", "MILLISECOND"];
    const DT_FIELDS: [&str; 7] = [
        "YEAR",
        "MONTH",
        "DAY",
        "HOUR",
        "MINUTE",
        "SECOND",
        "MILLISECOND",
    ];
    t.push(f(
        "CONCAT_DATE",
        I::ConcatDate,
        fields(&DATE_FIELDS),
        el(E::Date),
    ));
    t.push(f(
        "CONCAT_TOD",
        I::ConcatTod,
        fields(&TOD_FIELDS),
        el(E::Tod),
    ));
    t.push(f(
        "CONCAT_LTOD",
        I::ConcatTod,
        fields(&TOD_FIELDS),
        el(E::Ltod),
    ));
    t.push(f("CONCAT_DT", I::ConcatDt, fields(&DT_FIELDS), el(E::Dt)));
    t.push(f("CONCAT_LDT", I::ConcatDt, fields(&DT_FIELDS), el(E::Ldt)));
    t.push(f(
        "DAY_OF_WEEK",
        I::DayOfWeek,
        vec![p("IN", el(E::Date))],
        v(0, G::AnyInt),
    ));
    t
}

/// Every entry of the fixed table (not the generated conversion names), for
/// documentation and tests.
pub fn all() -> Vec<StdFunction> {
    table().fixed.clone()
}

/// Looks a standard function up by name (case-insensitively), including
/// every generated conversion name.
pub fn lookup(name: &str) -> Option<StdFunction> {
    let upper = name.to_ascii_uppercase();
    table().by_name.get(upper.as_str()).cloned()
}

struct Table {
    fixed: Vec<StdFunction>,
    by_name: HashMap<&'static str, StdFunction>,
}

fn table() -> &'static Table {
    static TABLE: OnceLock<Table> = OnceLock::new();
    TABLE.get_or_init(|| {
        let fixed = fixed_table();
        let mut by_name: HashMap<&'static str, StdFunction> = HashMap::new();
        // Typed forms first: a generated conversion or a fixed name of the
        // same spelling (`ADD_TIME`, `CONCAT_DATE`) is the one that counts.
        for t in typed_forms(&fixed) {
            by_name.insert(t.name, t);
        }
        for g in generated() {
            by_name.insert(g.name, g);
        }
        for e in &fixed {
            by_name.insert(e.name, e.clone());
        }
        Table { fixed, by_name }
    })
}

/// A generated name, made `'static` once: the set is finite (about two
/// thousand names) and built a single time, like a static table.
fn name(s: String) -> &'static str {
    Box::leak(s.into_boxed_str())
}

/// The typed forms of the overloaded functions: `FUNC_TYPE` is `FUNC` with
/// one type variable bound to the elementary type `TYPE`. The variable is
/// the result's (`SHL_BYTE` binds the bit string, not the shift count;
/// `MUX_INT` the selected values, not the selector) or, for a result of a
/// fixed type, the one variable all inputs share (`EQ_STRING`, `GT_INT`).
/// A type outside the variable's family gives no name (`SUB_DATE`,
/// `SQRT_INT`). Every spelling of the type names counts (`MAX_TOD`,
/// `MAX_TIME_OF_DAY`).
fn typed_forms(fixed: &[StdFunction]) -> Vec<StdFunction> {
    let mut out = Vec::new();
    for f in fixed {
        let var = match f.ret {
            TyPat::Var(k, g) => Some((k, g)),
            TyPat::Elem(_) => match f.params.first().map(|p| p.ty) {
                Some(first @ TyPat::Var(k, g)) if f.params.iter().all(|p| p.ty == first) => {
                    Some((k, g))
                }
                _ => None,
            },
        };
        let Some((k, fam)) = var else { continue };
        for &(type_name, t) in ElemType::SPELLINGS {
            if !crate::types::in_family(fam, t) {
                continue;
            }
            let bind = |p: TyPat| match p {
                TyPat::Var(j, _) if j == k => TyPat::Elem(t),
                other => other,
            };
            out.push(StdFunction {
                name: name(format!("{}_{type_name}", f.name)),
                intrinsic: f.intrinsic,
                params: f
                    .params
                    .iter()
                    .map(|p| Param {
                        name: p.name,
                        ty: bind(p.ty),
                    })
                    .collect(),
                ret: bind(f.ret),
                extensible: f.extensible,
            });
        }
    }
    out
}

fn conv_entry(n: String, intrinsic: Intrinsic, input: TyPat, ret: TyPat) -> StdFunction {
    f(name(n), intrinsic, vec![p("IN", input)], ret)
}

/// Every generated conversion name with its signature.
fn generated() -> Vec<StdFunction> {
    use Intrinsic as I;
    let mut out = Vec::new();
    let spellings = ElemType::SPELLINGS;
    for &(a_name, a) in spellings {
        for &(b_name, b) in spellings {
            if a != b && conversion_allowed(a, b) {
                out.push(conv_entry(
                    format!("{a_name}_TO_{b_name}"),
                    I::Convert { from: a, to: b },
                    el(a),
                    el(b),
                ));
            }
        }
    }
    for &(b_name, b) in spellings {
        // The target stands in for the argument type until resolved.
        out.push(conv_entry(
            format!("TO_{b_name}"),
            I::Convert { from: b, to: b },
            v(0, G::AnyElementary),
            el(b),
        ));
    }
    out.push(conv_entry(
        "TRUNC".into(),
        I::Trunc {
            from: E::Lreal,
            to: None,
        },
        v(0, G::AnyReal),
        v(1, G::AnyInt),
    ));
    let ints: Vec<ElemType> = ElemType::ALL
        .iter()
        .copied()
        .filter(|&t| is_integer(t))
        .collect();
    let words: Vec<ElemType> = ElemType::ALL
        .iter()
        .copied()
        .filter(|&t| is_bit_string(t) && t != E::Bool)
        .collect();
    let reals: Vec<ElemType> = ElemType::ALL
        .iter()
        .copied()
        .filter(|&t| is_real(t))
        .collect();
    for &a in &reals {
        for &b in &ints {
            out.push(conv_entry(
                format!("{}_TRUNC_{}", a.name(), b.name()),
                I::Trunc {
                    from: a,
                    to: Some(b),
                },
                el(a),
                el(b),
            ));
        }
    }
    // 3rd edition, overloaded on the input: TRUNC_<int> (any real in) and
    // TO_BCD_<bits> (any integer in).
    for &b in &ints {
        out.push(conv_entry(
            format!("TRUNC_{}", b.name()),
            I::Trunc {
                from: E::Lreal,
                to: Some(b),
            },
            v(0, G::AnyReal),
            el(b),
        ));
    }
    for &w in &words {
        out.push(conv_entry(
            format!("TO_BCD_{}", w.name()),
            I::IntToBcd {
                from: E::Ulint,
                to: w,
            },
            v(0, G::AnyInt),
            el(w),
        ));
    }
    for &b in &ints {
        out.push(conv_entry(
            format!("BCD_TO_{}", b.name()),
            I::BcdToInt {
                from: E::Word,
                to: b,
            },
            v(0, G::AnyBit),
            el(b),
        ));
        out.push(conv_entry(
            format!("{}_TO_BCD", b.name()),
            I::IntToBcd {
                from: b,
                to: E::Word,
            },
            el(b),
            v(0, G::AnyBit),
        ));
        for &w in &words {
            out.push(conv_entry(
                format!("{}_BCD_TO_{}", w.name(), b.name()),
                I::BcdToInt { from: w, to: b },
                el(w),
                el(b),
            ));
            out.push(conv_entry(
                format!("{}_TO_BCD_{}", b.name(), w.name()),
                I::IntToBcd { from: b, to: w },
                el(b),
                el(w),
            ));
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use Intrinsic as I;

    fn sig(name: &str) -> StdFunction {
        lookup(name).unwrap_or_else(|| panic!("{name} missing"))
    }

    fn names(f: &StdFunction) -> Vec<&'static str> {
        f.params.iter().map(|p| p.name).collect()
    }

    #[test]
    fn parameter_names_are_the_standards() {
        let cases: &[(&str, &[&str])] = &[
            ("ABS", &["IN"]),
            ("SQRT", &["IN"]),
            ("ATAN2", &["Y", "X"]),
            ("EXPT", &["IN1", "IN2"]),
            ("SHL", &["IN", "N"]),
            ("ROR", &["IN", "N"]),
            ("SEL", &["G", "IN0", "IN1"]),
            ("MAX", &["IN1", "IN2"]),
            ("LIMIT", &["MN", "IN", "MX"]),
            ("MUX", &["K", "IN0", "IN1"]),
            ("MOVE", &["IN"]),
            ("LEN", &["IN"]),
            ("LEFT", &["IN", "L"]),
            ("RIGHT", &["IN", "L"]),
            ("MID", &["IN", "L", "P"]),
            ("CONCAT", &["IN1", "IN2"]),
            ("INSERT", &["IN1", "IN2", "P"]),
            ("DELETE", &["IN", "L", "P"]),
            ("REPLACE", &["IN1", "IN2", "L", "P"]),
            ("FIND", &["IN1", "IN2"]),
            ("ADD_TOD_TIME", &["IN1", "IN2"]),
            ("MUL_TIME", &["IN1", "IN2"]),
            ("CONCAT_DATE", &["YEAR", "MONTH", "DAY"]),
            ("CONCAT_TOD", &["HOUR", "MINUTE", "SECOND", "MILLISECOND"]),
            (
                "CONCAT_DT",
                &[
                    "YEAR",
                    "MONTH",
                    "DAY",
                    "HOUR",
                    "MINUTE",
                    "SECOND",
                    "MILLISECOND",
                ],
            ),
            ("DAY_OF_WEEK", &["IN"]),
            ("INT_TO_REAL", &["IN"]),
            ("TRUNC", &["IN"]),
            ("NOT", &["IN"]),
            ("MOD", &["IN1", "IN2"]),
        ];
        for (name, want) in cases {
            assert_eq!(names(&sig(name)), *want, "{name}");
        }
    }

    #[test]
    fn generic_signatures() {
        let limit = sig("LIMIT");
        assert!(limit.params.iter().all(|p| p.ty == v(0, G::AnyElementary)));
        assert_eq!(limit.ret, v(0, G::AnyElementary));
        let mux = sig("MUX");
        assert!(mux.extensible);
        assert_eq!(mux.params[0].ty, v(0, G::AnyInt));
        assert_eq!(mux.ret, v(1, G::Any));
        let shl = sig("SHL");
        assert_eq!(shl.params[1].ty, v(1, G::AnyInt));
        assert_eq!(shl.ret, v(0, G::AnyBit));
        let len = sig("LEN");
        assert_eq!(len.ret, v(1, G::AnyInt));
        let expt = sig("EXPT");
        assert_eq!(expt.ret, v(0, G::AnyReal));
        assert_eq!(expt.params[1].ty, v(1, G::AnyNum));
        assert_eq!(sig("GT").ret, el(E::Bool));
        assert!(sig("GT").extensible);
        assert!(!sig("NE").extensible);
        assert!(sig("CONCAT").extensible);
        assert!(!sig("SEL").extensible);
        assert_eq!(sig("SUB_DATE_DATE").ret, el(E::Time));
        assert_eq!(sig("SUB_LDATE_LDATE").ret, el(E::Ltime));
        assert_eq!(sig("CONCAT_DATE_TOD").ret, el(E::Dt));
        assert_eq!(sig("CONCAT_LDT").ret, el(E::Ldt));
        assert_eq!(sig("MULTIME").intrinsic, I::MulTime);
        assert_eq!(sig("MUL_LTIME").params[0].ty, el(E::Ltime));
        assert_eq!(sig("ADD_LTIME").intrinsic, I::AddTime);
        assert_eq!(sig("DAY_OF_WEEK").ret, v(0, G::AnyInt));
    }

    #[test]
    fn extensible_inputs_continue_the_numbering() {
        let concat = sig("CONCAT");
        assert_eq!(concat.input(0).map(|x| x.0), Some("IN1".into()));
        assert_eq!(concat.input(2).map(|x| x.0), Some("IN3".into()));
        assert_eq!(concat.input(9).map(|x| x.0), Some("IN10".into()));
        let mux = sig("MUX");
        assert_eq!(mux.input(0).map(|x| x.0), Some("K".into()));
        assert_eq!(mux.input(3).map(|x| x.0), Some("IN2".into()));
        assert_eq!(mux.input(3).map(|x| x.1), Some(v(1, G::Any)));
        assert_eq!(sig("SEL").input(3), None);
        assert!(concat.accepts_count(5));
        assert!(!concat.accepts_count(1));
        assert!(sig("SEL").accepts_count(3));
        assert!(!sig("SEL").accepts_count(4));
    }

    #[test]
    fn conversion_names() {
        let c = sig("INT_TO_REAL");
        assert_eq!(
            c.intrinsic,
            I::Convert {
                from: E::Int,
                to: E::Real
            }
        );
        assert_eq!((c.params[0].ty, c.ret), (el(E::Int), el(E::Real)));
        assert_eq!(sig("int_to_real").name, "INT_TO_REAL");
        assert_eq!(
            sig("TIME_OF_DAY_TO_STRING").intrinsic,
            I::Convert {
                from: E::Tod,
                to: E::String
            }
        );
        assert_eq!(
            sig("DATE_AND_TIME_TO_DATE").intrinsic,
            I::Convert {
                from: E::Dt,
                to: E::Date
            }
        );
        assert_eq!(
            sig("DT_TO_TOD").intrinsic,
            I::Convert {
                from: E::Dt,
                to: E::Tod
            }
        );
        assert_eq!(
            sig("TOD_TO_TIME").intrinsic,
            I::Convert {
                from: E::Tod,
                to: E::Time
            }
        );
        assert_eq!(sig("DWORD_TO_REAL").ret, el(E::Real));
        assert_eq!(
            sig("WORD_TO_REAL").intrinsic,
            I::Convert {
                from: E::Word,
                to: E::Real
            }
        );
        assert_eq!(sig("REAL_TO_BYTE").ret, el(E::Byte));
        assert!(lookup("BOOL_TO_REAL").is_some());
        assert!(lookup("BOOL_TO_TIME").is_none());
        assert!(lookup("INT_TO_INT").is_none());
        assert!(lookup("DATE_TO_TOD").is_none());
        let to = sig("TO_INT");
        assert_eq!(to.params[0].ty, v(0, G::AnyElementary));
        assert_eq!(to.ret, el(E::Int));
        assert_eq!(
            to.intrinsic.resolve(&[E::Real], E::Int),
            I::Convert {
                from: E::Real,
                to: E::Int
            }
        );
        let t = sig("TRUNC");
        assert_eq!(t.ret, v(1, G::AnyInt));
        assert_eq!(
            t.intrinsic.resolve(&[E::Real], E::Dint),
            I::Trunc {
                from: E::Real,
                to: Some(E::Dint)
            }
        );
        assert_eq!(
            sig("REAL_TRUNC_INT").intrinsic,
            I::Trunc {
                from: E::Real,
                to: Some(E::Int)
            }
        );
        assert!(lookup("INT_TRUNC_REAL").is_none());
        assert_eq!(sig("BCD_TO_INT").params[0].ty, v(0, G::AnyBit));
        assert_eq!(sig("BCD_TO_INT").ret, el(E::Int));
        assert_eq!(sig("INT_TO_BCD").ret, v(0, G::AnyBit));
        assert_eq!(
            sig("WORD_BCD_TO_UINT").intrinsic,
            I::BcdToInt {
                from: E::Word,
                to: E::Uint
            }
        );
        assert_eq!(
            sig("USINT_TO_BCD_BYTE").intrinsic,
            I::IntToBcd {
                from: E::Usint,
                to: E::Byte
            }
        );
        assert!(lookup("BOOL_BCD_TO_INT").is_none());
        assert!(lookup("REAL_TO_BCD").is_none());
        assert!(lookup("SPLIT_DATE").is_none());
        assert!(lookup("NOPE").is_none());
        assert!(lookup("").is_none());
    }

    #[test]
    fn typed_forms_bind_one_type_variable() {
        let add = sig("ADD_INT");
        assert_eq!(add.intrinsic, I::Add);
        assert!(add.params.iter().all(|p| p.ty == el(E::Int)));
        assert_eq!(add.ret, el(E::Int));
        assert!(add.extensible);
        let limit = sig("limit_real");
        assert_eq!(names(&limit), ["MN", "IN", "MX"]);
        assert!(limit.params.iter().all(|p| p.ty == el(E::Real)));
        // SHL_BYTE: the bit string, not the count.
        let shl = sig("SHL_BYTE");
        assert_eq!(
            (shl.params[0].ty, shl.params[1].ty),
            (el(E::Byte), v(1, G::AnyInt))
        );
        assert_eq!(shl.ret, el(E::Byte));
        // MUX_INT: the selected values, not the selector.
        let mux = sig("MUX_INT");
        assert_eq!(mux.params[0].ty, v(0, G::AnyInt));
        assert_eq!(mux.params[1].ty, el(E::Int));
        assert_eq!(mux.ret, el(E::Int));
        let sel = sig("SEL_REAL");
        assert_eq!(sel.params[0].ty, el(E::Bool));
        assert_eq!(sel.ret, el(E::Real));
        // A fixed result: the inputs' shared variable.
        let eq = sig("EQ_STRING");
        assert!(eq.params.iter().all(|p| p.ty == el(E::String)));
        assert_eq!(eq.ret, el(E::Bool));
        assert_eq!(sig("MAX_TIME_OF_DAY").ret, el(E::Tod));
        assert_eq!(sig("MAX_TOD").ret, el(E::Tod));
        assert_eq!(sig("CONCAT_WSTRING").ret, el(E::Wstring));
        assert_eq!(sig("EXPT_REAL").params[1].ty, v(1, G::AnyNum));
        // Outside the family, or no variable to bind: no such name.
        assert!(lookup("SQRT_INT").is_none());
        assert!(lookup("SUB_DATE").is_none());
        assert!(lookup("AND_REAL").is_none());
        assert!(lookup("MUL_TIME_INT").is_none());
        // Fixed and conversion names keep their meaning.
        assert_eq!(sig("ADD_TIME").intrinsic, I::AddTime);
        assert_eq!(sig("CONCAT_DATE").intrinsic, I::ConcatDate);
        assert_eq!(sig("MUL_TIME").intrinsic, I::MulTime);
    }

    #[test]
    fn fixed_table_is_consistent() {
        let entries = all();
        let mut seen = std::collections::HashSet::new();
        for e in &entries {
            assert!(seen.insert(e.name), "duplicate {}", e.name);
            assert_eq!(lookup(e.name).as_ref(), Some(e));
            assert!(!e.params.is_empty(), "{}", e.name);
            // Parameter names are unique and upper case.
            let mut ps = std::collections::HashSet::new();
            for p in &e.params {
                assert!(ps.insert(p.name), "{}.{}", e.name, p.name);
                assert_eq!(p.name, p.name.to_ascii_uppercase());
            }
            // An extensible function's last input is numbered.
            if e.extensible {
                assert!(e.input(e.params.len()).is_some(), "{}", e.name);
            }
        }
        assert!(entries.len() > 75, "{}", entries.len());
    }
}
