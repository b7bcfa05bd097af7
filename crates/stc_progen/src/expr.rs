//! Expressions: literals, reads, operators, standard functions, conversions
//! and calls of the generated functions, each of exactly the elementary type
//! asked for.
//!
//! Typing discipline (so the analyser accepts every expression):
//! - an expression generated for type T has type T; operands of an
//!   operator are both T (or the types the operator's table asks for);
//! - an untyped literal takes its type from its context, so where the
//!   context gives none (comparison operands, generic function inputs) the
//!   caller asks for an *anchored* expression: one with at least one
//!   non-literal leaf or a typed literal (`INT#5`);
//! - anything that could fault is guarded (divisors, indices, real to
//!   integer conversions, MUX selectors, subrange values) except in a few
//!   percent of the places, where only values the analyser cannot know by
//!   propagation are used unguarded (a guarded or proven fault is a compile
//!   time error, not a run-time one).

use stc_values::ElemType as E;

use crate::gen::{Body, Gen};
use crate::model::{class, is_signed, range, Access, Class, Step, Ty, BITS, INTS};

/// Characters of generated STRING literals (before escapes).
const PLAIN: &[&str] = &[
    "a", "b", "c", "x", "Y", "Z", "0", "1", "7", " ", "-", "_", "+", ".", "é", "€", "\"",
];

impl Gen {
    // ------------------------------------------------------------------
    // Literals.

    /// A literal of type `t`; `anchor` asks for one that carries its type.
    pub(crate) fn lit(&mut self, t: E, anchor: bool) -> String {
        match class(t) {
            Class::Bool => if self.rng.chance(50) { "TRUE" } else { "FALSE" }.into(),
            Class::Int | Class::Bits => {
                let v = self.int_value(t);
                self.int_lit(t, v, anchor)
            }
            Class::Real => self.real_lit(t, anchor),
            Class::Dur => self.dur_lit(t),
            Class::Date => {
                let (y, m, d) = self.ymd();
                let p = if t == E::Ldate { "LDATE" } else { "D" };
                format!("{p}#{y:04}-{m:02}-{d:02}")
            }
            Class::Tod => {
                let p = if t == E::Ltod { "LTOD" } else { "TOD" };
                format!("{p}#{}", self.hms(t == E::Ltod))
            }
            Class::Dt => {
                let (y, m, d) = self.ymd();
                let p = if t == E::Ldt { "LDT" } else { "DT" };
                format!("{p}#{y:04}-{m:02}-{d:02}-{}", self.hms(t == E::Ldt))
            }
            Class::Str => self.str_lit(t == E::Wstring),
            Class::Char => {
                let c = *self
                    .rng
                    .pick(&["a", "B", "z", "0", "9", " ", "#", "é", "x", "Q"]);
                if t == E::Char {
                    format!("CHAR#'{c}'")
                } else {
                    let c = if self.rng.chance(20) { "€" } else { c };
                    format!("WCHAR#\"{c}\"")
                }
            }
        }
    }

    /// A value of an integer or bit-string type: mostly small, sometimes
    /// anywhere in the range (never the most negative value, whose
    /// negation does not fit).
    pub(crate) fn int_value(&mut self, t: E) -> i128 {
        let (lo, hi) = range(t);
        let floor = if is_signed(t) { lo + 1 } else { lo };
        let (a, b) = match self.rng.below(10) {
            0..=5 => (-10, 20),
            6..=8 => (-1000, 1000),
            _ => (floor, hi),
        };
        self.rng.range(a.max(floor), b.min(hi))
    }

    pub(crate) fn int_lit(&mut self, t: E, v: i128, anchor: bool) -> String {
        let body = if v >= 0
            && self
                .rng
                .chance(if class(t) == Class::Bits { 40 } else { 10 })
        {
            format!("16#{v:X}")
        } else if v >= 0 && self.rng.chance(4) {
            format!("2#{v:b}")
        } else {
            v.to_string()
        };
        if anchor {
            format!("{}#{body}", t.name())
        } else if v < 0 {
            format!("({body})")
        } else {
            body
        }
    }

    fn real_lit(&mut self, t: E, anchor: bool) -> String {
        let text = match self.rng.below(8) {
            0 => "0.0".to_string(),
            1 => format!("{}.0", self.rng.range(-20, 20)),
            2 => format!("{}.5", self.rng.range(-9, 9)),
            3 => format!("{}.25", self.rng.range(-3, 3)),
            4 => format!("{}.0E{}", self.rng.range(1, 9), self.rng.range(-3, 4)),
            5 => format!("0.{}", self.rng.range(1, 999)),
            6 => format!("-0.{}", self.rng.range(1, 99)),
            _ => format!("{}.{}", self.rng.range(-300, 300), self.rng.range(0, 99)),
        };
        if anchor {
            format!("{}#{text}", t.name())
        } else if text.starts_with('-') {
            format!("({text})")
        } else {
            text
        }
    }

    fn dur_lit(&mut self, t: E) -> String {
        let prefix = if t == E::Ltime { "LTIME#" } else { "T#" };
        let neg = if self.rng.chance(5) { "-" } else { "" };
        let body = match self.rng.below(6) {
            0 => format!("{}ms", self.rng.range(0, 100) * 10),
            1 => format!("{}s{}ms", self.rng.range(0, 59), self.rng.range(0, 999)),
            2 => format!("{}m{}s", self.rng.range(0, 59), self.rng.range(0, 59)),
            3 => format!("{}h{}m", self.rng.range(0, 23), self.rng.range(0, 59)),
            4 if t == E::Ltime => {
                format!("{}us{}ns", self.rng.range(0, 999), self.rng.range(0, 999))
            }
            4 => format!("{}d{}h", self.rng.range(0, 3), self.rng.range(0, 23)),
            _ => format!("{}ms", self.rng.range(0, 50)),
        };
        format!("{prefix}{neg}{body}")
    }

    fn ymd(&mut self) -> (i128, i128, i128) {
        let y = if self.rng.chance(85) {
            self.rng.range(1970, 2100)
        } else {
            self.rng.range(1900, 1969)
        };
        let m = self.rng.range(1, 12);
        let d = if m == 2 && self.rng.chance(10) && y % 4 == 0 && y != 1900 && y != 2100 {
            29
        } else {
            self.rng.range(1, 28)
        };
        (y, m, d)
    }

    /// A time of day; `long`: maybe with nanoseconds.
    fn hms(&mut self, long: bool) -> String {
        let s = format!(
            "{:02}:{:02}:{:02}",
            self.rng.range(0, 23),
            self.rng.range(0, 59),
            self.rng.range(0, 59)
        );
        match self.rng.below(5) {
            0 => format!("{s}.{}", self.rng.range(1, 9)),
            1 => format!("{s}.{:03}", self.rng.range(1, 999)),
            2 if long => format!("{s}.{:09}", self.rng.range(1, 999_999_999)),
            _ => s,
        }
    }

    pub(crate) fn str_lit(&mut self, wide: bool) -> String {
        let q = if wide { '"' } else { '\'' };
        let n = self.rng.range(0, 8);
        let mut s = String::new();
        for _ in 0..n {
            match self.rng.below(14) {
                0 => s.push_str("$$"),
                1 => s.push_str(if wide { "$\"" } else { "$'" }),
                2 => s.push_str("$N"),
                3 => s.push_str("$T"),
                4 => s.push_str(if wide { "$0041" } else { "$41" }),
                _ => {
                    let c = *self.rng.pick(PLAIN);
                    if (c == "\"" && wide) || c == "'" {
                        continue;
                    }
                    s.push_str(c);
                }
            }
        }
        format!("{q}{s}{q}")
    }

    // ------------------------------------------------------------------
    // Reads.

    /// How an access is written, with fresh index expressions.
    pub(crate) fn render(&mut self, b: &Body, a: &Access, d: u32) -> String {
        let mut s = String::new();
        for step in &a.steps {
            match step {
                Step::Name(n) => s.push_str(n),
                Step::Field(f) => {
                    s.push('.');
                    s.push_str(f);
                }
                Step::Index(dims) => {
                    let idx: Vec<String> = dims
                        .iter()
                        .map(|&(lo, hi)| self.index(b, lo, hi, d))
                        .collect();
                    s.push('[');
                    s.push_str(&idx.join(", "));
                    s.push(']');
                }
            }
        }
        s
    }

    /// An index in `lo..=hi`: a literal, a loop variable known to be in
    /// range, a clamped expression, or rarely an unguarded read.
    fn index(&mut self, b: &Body, lo: i128, hi: i128, d: u32) -> String {
        // An index inside an index inside an index is a literal: reads in
        // index expressions render indices of their own.
        if self.index_nesting >= 2 {
            return self.rng.range(lo, hi).to_string();
        }
        self.index_nesting += 1;
        let s = self.index_inner(b, lo, hi, d);
        self.index_nesting -= 1;
        s
    }

    fn index_inner(&mut self, b: &Body, lo: i128, hi: i128, d: u32) -> String {
        let r = self.rng.below(100);
        if r < 35 {
            return self.rng.range(lo, hi).to_string();
        }
        if r < 60 {
            let fits: Vec<&String> = b
                .loops
                .iter()
                .filter(|l| l.lo >= lo && l.hi <= hi)
                .map(|l| &l.name)
                .collect();
            if !fits.is_empty() {
                return self.rng.pick(&fits).to_string();
            }
        }
        if self.unguarded() {
            let t = *self.rng.pick(INTS);
            if let Some(a) = self.read_access(b, t, true) {
                return self.render(b, &a, 0);
            }
        }
        let t = if lo >= -32768 && hi <= 32767 && self.rng.chance(30) {
            E::Int
        } else {
            E::Dint
        };
        let e = self.ex(b, t, d.min(2), true);
        format!("LIMIT({lo}, {e}, {hi})")
    }

    /// A readable access whose value has type `t` (`opaque`: only those
    /// the analyser cannot know).
    pub(crate) fn read_access(&mut self, b: &Body, t: E, opaque: bool) -> Option<Access> {
        let found: Vec<&Access> = b
            .reach
            .values
            .iter()
            .filter(|a| (!opaque || a.opaque) && a.ty.scalar(&self.types) == Some(t))
            .collect();
        if found.is_empty() {
            return None;
        }
        Some((*self.rng.pick(&found)).clone())
    }

    /// A writable access of exactly type `ty`.
    pub(crate) fn write_access(&mut self, b: &Body, ty: &Ty) -> Option<Access> {
        let found: Vec<&Access> = b
            .reach
            .values
            .iter()
            .filter(|a| a.writable && &a.ty == ty)
            .collect();
        if found.is_empty() {
            return None;
        }
        Some((*self.rng.pick(&found)).clone())
    }

    /// A read of a value of type `t` or a literal.
    pub(crate) fn leaf(&mut self, b: &Body, t: E, anchor: bool) -> String {
        if matches!(class(t), Class::Int) && self.rng.chance(20) {
            let ls: Vec<&String> = b
                .loops
                .iter()
                .filter(|l| l.ty == t)
                .map(|l| &l.name)
                .collect();
            if !ls.is_empty() {
                return self.rng.pick(&ls).to_string();
            }
        }
        if self.rng.chance(80) {
            if let Some(a) = self.read_access(b, t, false) {
                return self.render(b, &a, 1);
            }
        }
        self.lit(t, anchor)
    }

    /// A condition: a BOOL expression that is not a bare literal.
    pub(crate) fn cond(&mut self, b: &Body, d: u32) -> String {
        for _ in 0..4 {
            let c = self.ex(b, E::Bool, d, false);
            if c != "TRUE" && c != "FALSE" {
                return c;
            }
        }
        self.comparison(b, d.saturating_sub(1))
    }

    // ------------------------------------------------------------------
    // Expressions.

    /// An expression of type `t`, at most `d` levels deep.
    pub(crate) fn ex(&mut self, b: &Body, t: E, d: u32, anchor: bool) -> String {
        if d == 0 || self.rng.chance(20) {
            return self.leaf(b, t, anchor);
        }
        let d = d - 1;
        let form = match class(t) {
            Class::Int => self.ex_int(b, t, d, anchor),
            Class::Bits => self.ex_bits(b, t, d, anchor),
            Class::Bool => self.ex_bool(b, d),
            Class::Real => self.ex_real(b, t, d, anchor),
            Class::Dur => self.ex_dur(b, t, d),
            Class::Date => self.ex_date(b, t, d),
            Class::Tod => self.ex_tod(b, t, d),
            Class::Dt => self.ex_dt(b, t, d),
            Class::Str => self.ex_str(b, t, d),
            Class::Char => self.ex_char(b, t, d),
        };
        match form {
            Some(s) => s,
            None => self.leaf(b, t, anchor),
        }
    }

    /// `(l op r)` with one side anchored when `anchor` asks for it.
    fn bin(&mut self, b: &Body, t: E, op: &str, d: u32, anchor: bool) -> String {
        let left_anchor = anchor && self.rng.chance(50);
        let l = self.ex(b, t, d, left_anchor);
        let r = self.ex(b, t, d, anchor && !left_anchor);
        format!("({l} {op} {r})")
    }

    /// Whether this divisor, index, selector or subrange value is left
    /// unguarded ([`crate::Size::unguarded`] per mille).
    fn unguarded(&mut self) -> bool {
        self.rng.below(1000) < self.size.unguarded
    }

    /// A divisor of type `t` that is not zero, except rarely an unguarded
    /// read the analyser cannot know.
    fn divisor(&mut self, b: &Body, t: E, d: u32) -> String {
        if self.unguarded() {
            if let Some(a) = self.read_access(b, t, true) {
                return self.render(b, &a, 0);
            }
        }
        if self.rng.chance(50) {
            let (lo, hi) = range(t);
            let mut v = self.rng.range(lo.max(-9), hi.min(9));
            if v == 0 {
                v = 3;
            }
            return self.int_lit(t, v, false);
        }
        let e = self.ex(b, t, d, true);
        if is_signed(t) {
            format!("MAX(ABS({e}), 1)")
        } else {
            format!("MAX({e}, 1)")
        }
    }

    /// The forms every type has: MAX, MIN, LIMIT, SEL, MUX, MOVE.
    fn select(&mut self, b: &Body, t: E, d: u32) -> Option<String> {
        Some(match self.rng.below(6) {
            0 | 1 => {
                let f = if self.rng.chance(50) { "MAX" } else { "MIN" };
                let n = if self.rng.chance(25) { 3 } else { 2 };
                let k = self.rng.index(n);
                let args: Vec<String> = (0..n).map(|i| self.ex(b, t, d, i == k)).collect();
                format!("{f}({})", args.join(", "))
            }
            2 => {
                let (mn, mx) = match class(t) {
                    Class::Int | Class::Bits => {
                        let a = self.int_value(t);
                        let c = self.int_value(t);
                        let (a, c) = (a.min(c), a.max(c));
                        (self.int_lit(t, a, false), self.int_lit(t, c, false))
                    }
                    _ => (self.ex(b, t, 0, false), self.ex(b, t, 0, false)),
                };
                let x = self.ex(b, t, d, true);
                format!("LIMIT({mn}, {x}, {mx})")
            }
            3 => {
                let g = self.ex(b, E::Bool, d, true);
                let k = self.rng.chance(50);
                let x = self.ex(b, t, d, k);
                let y = self.ex(b, t, d, !k);
                format!("SEL({g}, {x}, {y})")
            }
            4 => {
                let n = self.rng.range(2, 4) as usize;
                let k = self.mux_selector(b, n, d);
                let a = self.rng.index(n);
                let args: Vec<String> = (0..n).map(|i| self.ex(b, t, d, i == a)).collect();
                format!("MUX({k}, {})", args.join(", "))
            }
            _ => format!("MOVE({})", self.ex(b, t, d, true)),
        })
    }

    fn mux_selector(&mut self, b: &Body, n: usize, d: u32) -> String {
        if self.unguarded() {
            let t = *self.rng.pick(INTS);
            if let Some(a) = self.read_access(b, t, true) {
                return self.render(b, &a, 0);
            }
        }
        if self.rng.chance(40) {
            return self.rng.range(0, n as i128 - 1).to_string();
        }
        let t = *self.rng.pick(&[E::Int, E::Dint, E::Usint, E::Udint]);
        let e = self.ex(b, t, d.min(1), true);
        format!("LIMIT(0, {e}, {})", n - 1)
    }

    fn ex_int(&mut self, b: &Body, t: E, d: u32, anchor: bool) -> Option<String> {
        let w = [14, 5, 3, 3, 8, 9, 3, 2, 2, 2];
        Some(match self.rng.weighted(&w) {
            0 => {
                let op = *self.rng.pick(&["+", "-", "*"]);
                self.bin(b, t, op, d, anchor)
            }
            1 => {
                let op = if self.rng.chance(50) { "/" } else { "MOD" };
                let l = self.ex(b, t, d, anchor);
                let r = self.divisor(b, t, d);
                format!("({l} {op} {r})")
            }
            2 if is_signed(t) => format!("(-{})", self.ex(b, t, d, anchor)),
            2 | 3 => format!("ABS({})", self.ex(b, t, d, true)),
            4 => return self.select(b, t, d),
            5 => return self.conv(b, t, d),
            6 => return self.call_expr(b, t, d),
            7 => {
                // Standard functions whose result type comes from the
                // context, DINT without one: only where T is DINT, or
                // converted to T (a context is not always there: the
                // operands of a comparison get none).
                let wide = self.rng.chance(25);
                let st = if wide { E::Wstring } else { E::String };
                let mut pick = self.rng.below(4);
                if self.size.circuit && pick < 2 {
                    // (No strings in a circuit.)
                    pick += 2;
                }
                let inner = match pick {
                    0 => format!("LEN({})", self.ex(b, st, d, false)),
                    1 => {
                        let x = self.ex(b, st, d, false);
                        let y = self.ex(b, st, d.min(1), false);
                        format!("FIND({x}, {y})")
                    }
                    2 => format!("DAY_OF_WEEK({})", self.ex(b, E::Date, d, false)),
                    _ => {
                        let (lo, hi) = range(t);
                        let src = *self.rng.pick(&[E::Real, E::Lreal]);
                        let x = self.real_guarded(b, src, lo.max(-1_000_000), hi.min(1_000_000));
                        if t == E::Dint && self.rng.chance(50) {
                            format!("TRUNC({x})")
                        } else {
                            return Some(format!("{}_TRUNC_{}({x})", src.name(), t.name()));
                        }
                    }
                };
                if t == E::Dint {
                    inner
                } else {
                    format!("DINT_TO_{}({inner})", t.name())
                }
            }
            8 if self.rng.chance(15) => {
                // BCD there and back: the value kept to the decimal digits
                // the bit string holds.
                let (bits, top) = match t {
                    E::Sint | E::Usint => (E::Byte, 99i128),
                    E::Int | E::Uint => (E::Word, 9999),
                    E::Dint | E::Udint => (E::Dword, 99_999_999),
                    _ => (E::Lword, 9_999_999_999_999_999),
                };
                let x = self.ex(b, t, d, true);
                format!(
                    "{bits}_BCD_TO_{t}({t}_TO_BCD_{bits}(LIMIT(0, {x}, {top})))",
                    bits = bits.name(),
                    t = t.name()
                )
            }
            8 => {
                let f = *self.rng.pick(&["ADD", "MUL", "SUB"]);
                let n = if f != "SUB" && self.rng.chance(30) {
                    3
                } else {
                    2
                };
                let k = self.rng.index(n);
                let args: Vec<String> = (0..n).map(|i| self.ex(b, t, d, i == k)).collect();
                format!("{f}({})", args.join(", "))
            }
            _ => {
                let f = if self.rng.chance(50) { "DIV" } else { "MOD" };
                let l = self.ex(b, t, d, true);
                let r = self.divisor(b, t, d);
                format!("{f}({l}, {r})")
            }
        })
    }

    fn shift_count(&mut self, b: &Body, d: u32) -> String {
        if self.rng.chance(70) {
            return self.rng.range(0, 70).to_string();
        }
        let t = *self.rng.pick(INTS);
        self.ex(b, t, d.min(1), true)
    }

    fn ex_bits(&mut self, b: &Body, t: E, d: u32, anchor: bool) -> Option<String> {
        let w = [12, 4, 8, 6, 8, 3, 2];
        Some(match self.rng.weighted(&w) {
            0 => {
                let op = *self.rng.pick(&["AND", "OR", "XOR"]);
                self.bin(b, t, op, d, anchor)
            }
            // NOT gives its operand no type: anchor it.
            1 => format!("(NOT {})", self.ex(b, t, d, true)),
            2 => {
                let f = *self.rng.pick(&["SHL", "SHR", "ROL", "ROR"]);
                let x = self.ex(b, t, d, true);
                let n = self.shift_count(b, d);
                format!("{f}({x}, {n})")
            }
            3 => return self.select(b, t, d),
            4 => return self.conv(b, t, d),
            5 => return self.call_expr(b, t, d),
            _ => {
                let f = *self.rng.pick(&["AND", "OR", "XOR"]);
                let n = self.rng.range(2, 3) as usize;
                let k = self.rng.index(n);
                let args: Vec<String> = (0..n).map(|i| self.ex(b, t, d, i == k)).collect();
                format!("{f}({})", args.join(", "))
            }
        })
    }

    /// A type whose values are compared: mostly one the body has
    /// variables of, so that comparisons read state rather than fold.
    fn comparable(&mut self, b: &Body) -> E {
        if self.rng.chance(75) {
            let have = self.readable_types(b);
            if !have.is_empty() {
                return *self.rng.pick(&have);
            }
        }
        let all: Vec<(E, u64)> = crate::model::ELEMS.to_vec();
        let w: Vec<u64> = all
            .iter()
            .map(|&(e, w)| if self.allowed(e) { w } else { 0 })
            .collect();
        all[self.rng.weighted(&w)].0
    }

    /// The elementary types the body can read values of.
    pub(crate) fn readable_types(&self, b: &Body) -> Vec<E> {
        let mut v: Vec<E> = Vec::new();
        for a in &b.reach.values {
            if let Some(e) = a.ty.scalar(&self.types) {
                if !v.contains(&e) {
                    v.push(e);
                }
            }
        }
        v
    }

    pub(crate) fn comparison(&mut self, b: &Body, d: u32) -> String {
        // An enumeration now and then: only = and <>.
        if self.rng.chance(8) {
            let enums: Vec<usize> = b
                .reach
                .values
                .iter()
                .filter_map(|a| match a.ty {
                    Ty::Enum(i) => Some(i),
                    _ => None,
                })
                .collect();
            if !enums.is_empty() {
                let i = *self.rng.pick(&enums);
                let l = self.enum_ex(b, i, d, true);
                let r = self.enum_ex(b, i, d, true);
                let op = if self.rng.chance(50) { "=" } else { "<>" };
                return format!("({l} {op} {r})");
            }
        }
        let t = self.comparable(b);
        let op = *self.rng.pick(&["=", "<>", "<", "<=", ">", ">="]);
        if self.rng.chance(6) {
            // The function forms, GT(a, b, c) being a chain.
            let f = match op {
                "=" => "EQ",
                "<>" => "NE",
                "<" => "LT",
                "<=" => "LE",
                ">" => "GT",
                _ => "GE",
            };
            let n = if f != "NE" && self.rng.chance(40) {
                3
            } else {
                2
            };
            let k = self.rng.index(n);
            let args: Vec<String> = (0..n).map(|i| self.ex(b, t, d, i == k)).collect();
            return format!("{f}({})", args.join(", "));
        }
        let left = self.rng.chance(50);
        let l = self.ex(b, t, d, left);
        let r = self.ex(b, t, d, !left);
        format!("({l} {op} {r})")
    }

    fn ex_bool(&mut self, b: &Body, d: u32) -> Option<String> {
        let w = [20, 12, 4, 3, 4, 2, 2];
        Some(match self.rng.weighted(&w) {
            0 => self.comparison(b, d),
            1 => {
                let op = *self.rng.pick(&["AND", "OR", "XOR", "AND", "OR"]);
                self.bin(b, E::Bool, op, d, false)
            }
            2 => format!("(NOT {})", self.ex(b, E::Bool, d, false)),
            3 => return self.select(b, E::Bool, d),
            4 => return self.conv(b, E::Bool, d),
            5 => return self.call_expr(b, E::Bool, d),
            _ => {
                let f = *self.rng.pick(&["AND", "OR", "XOR"]);
                let n = self.rng.range(2, 4) as usize;
                let args: Vec<String> = (0..n).map(|_| self.ex(b, E::Bool, d, true)).collect();
                format!("{f}({})", args.join(", "))
            }
        })
    }

    fn ex_real(&mut self, b: &Body, t: E, d: u32, anchor: bool) -> Option<String> {
        let w = [14, 3, 9, 5, 3, 6, 5, 2];
        Some(match self.rng.weighted(&w) {
            0 => {
                let op = *self.rng.pick(&["+", "-", "*", "/"]);
                self.bin(b, t, op, d, anchor)
            }
            1 => format!("(-{})", self.ex(b, t, d, anchor)),
            2 => {
                let x = self.ex(b, t, d, true);
                match self.rng.below(12) {
                    0 => format!("ABS({x})"),
                    1 => format!("SQRT(ABS({x}))"),
                    2 => format!("LN(ABS({x}) + 1.0)"),
                    3 => format!("LOG(ABS({x}) + 1.0)"),
                    4 => format!("EXP(LIMIT(-20.0, {x}, 20.0))"),
                    5 => format!("SIN({x})"),
                    6 => format!("COS({x})"),
                    7 => format!("TAN({x})"),
                    8 => format!("ATAN({x})"),
                    9 => format!("ASIN(LIMIT(-1.0, {x}, 1.0))"),
                    10 => format!("ACOS(LIMIT(-1.0, {x}, 1.0))"),
                    _ => {
                        let y = self.ex(b, t, d, true);
                        format!("ATAN2({x}, {y})")
                    }
                }
            }
            3 => {
                // `**` needs a base with its own type.
                let x = self.ex(b, t, d, true);
                let e = match self.rng.below(4) {
                    0 => format!("{}.5", self.rng.range(0, 2)),
                    1 => {
                        let et = *self.rng.pick(&[E::Int, E::Sint, E::Real, E::Lreal]);
                        self.leaf(b, et, true)
                    }
                    _ => self.rng.range(0, 4).to_string(),
                };
                if self.rng.chance(30) {
                    format!("EXPT({x}, {e})")
                } else {
                    format!("({x} ** {e})")
                }
            }
            4 => {
                let f = *self.rng.pick(&["ADD", "MUL", "SUB", "DIV"]);
                let k = self.rng.chance(50);
                let x = self.ex(b, t, d, k);
                let y = self.ex(b, t, d, !k);
                format!("{f}({x}, {y})")
            }
            5 => return self.select(b, t, d),
            6 => return self.conv(b, t, d),
            _ => return self.call_expr(b, t, d),
        })
    }

    /// A small integer (or now and then a REAL) factor for durations.
    fn factor(&mut self, b: &Body, d: u32) -> String {
        match self.rng.below(6) {
            0 => format!("{}.5", self.rng.range(0, 3)),
            1 => {
                let t = *self.rng.pick(&[E::Sint, E::Int, E::Usint, E::Dint]);
                let x = self.ex(b, t, d.min(1), true);
                let lo = if is_signed(t) { -4 } else { 0 };
                format!("LIMIT({lo}, {x}, 4)")
            }
            _ => self.rng.range(0, 5).to_string(),
        }
    }

    fn ex_dur(&mut self, b: &Body, t: E, d: u32) -> Option<String> {
        let w = [12, 5, 4, 2, 6, 5, 4, 2, 4];
        let lt = t == E::Ltime;
        Some(match self.rng.weighted(&w) {
            0 => {
                let op = if self.rng.chance(50) { "+" } else { "-" };
                self.bin(b, t, op, d, false)
            }
            1 => {
                let x = self.ex(b, t, d, true);
                let n = self.factor(b, d);
                if self.rng.chance(25) {
                    format!("({n} * {x})")
                } else {
                    format!("({x} * {n})")
                }
            }
            2 => {
                let x = self.ex(b, t, d, true);
                let it = *self.rng.pick(&[E::Int, E::Dint, E::Usint]);
                let n = self.divisor(b, it, d);
                format!("({x} / {n})")
            }
            3 => format!("(-{})", self.ex(b, t, d, true)),
            4 => return self.select(b, t, d),
            5 => return self.conv(b, t, d),
            6 => {
                // Differences of dates and times of day.
                let choices: &[(E, &str)] = if lt {
                    &[
                        (E::Ldate, "SUB_LDATE_LDATE"),
                        (E::Ltod, "SUB_LTOD_LTOD"),
                        (E::Ldt, "SUB_LDT_LDT"),
                    ]
                } else {
                    &[
                        (E::Date, "SUB_DATE_DATE"),
                        (E::Tod, "SUB_TOD_TOD"),
                        (E::Dt, "SUB_DT_DT"),
                    ]
                };
                let (st, f) = *self.rng.pick(choices);
                let x = self.ex(b, st, d, true);
                let y = self.ex(b, st, d, true);
                if self.rng.chance(40) {
                    format!("{f}({x}, {y})")
                } else {
                    format!("({x} - {y})")
                }
            }
            7 => return self.call_expr(b, t, d),
            _ => {
                let sfx = if lt { "LTIME" } else { "TIME" };
                let x = self.ex(b, t, d, true);
                match self.rng.below(4) {
                    0 => format!("ADD_{sfx}({x}, {})", self.ex(b, t, d, true)),
                    1 => format!("SUB_{sfx}({x}, {})", self.ex(b, t, d, true)),
                    2 => format!("MUL_{sfx}({x}, {})", self.factor(b, d)),
                    _ => {
                        let n = self.divisor(b, E::Dint, d);
                        format!("DIV_{sfx}({x}, {n})")
                    }
                }
            }
        })
    }

    /// An integer expression clamped into `lo..=hi`, of a type that holds
    /// both bounds.
    fn clamped_int(&mut self, b: &Body, lo: i128, hi: i128, d: u32) -> String {
        if self.rng.chance(50) {
            return self.rng.range(lo, hi).to_string();
        }
        let fits: Vec<E> = INTS
            .iter()
            .copied()
            .filter(|&t| {
                let (a, c) = range(t);
                a <= lo && hi <= c
            })
            .collect();
        let t = *self.rng.pick(&fits);
        let x = self.ex(b, t, d.min(1), true);
        format!("LIMIT({lo}, {x}, {hi})")
    }

    /// DATE or LDATE.
    fn ex_date(&mut self, b: &Body, t: E, d: u32) -> Option<String> {
        let long = t == E::Ldate;
        Some(match self.rng.below(5) {
            0 => {
                let y = self.clamped_int(b, 1970, 2100, d);
                let m = self.clamped_int(b, 1, 12, d);
                let dd = self.clamped_int(b, 1, 28, d);
                let c = format!("CONCAT_DATE({y}, {m}, {dd})");
                if long {
                    format!("DATE_TO_LDATE({c})")
                } else {
                    c
                }
            }
            1 => {
                let dt = if long { E::Ldt } else { E::Dt };
                format!(
                    "{}_TO_{}({})",
                    dt.name(),
                    t.name(),
                    self.ex(b, dt, d, false)
                )
            }
            2 => return self.select(b, t, d),
            3 => return self.conv(b, t, d),
            _ => return self.call_expr(b, t, d),
        })
    }

    /// TOD or LTOD.
    fn ex_tod(&mut self, b: &Body, t: E, d: u32) -> Option<String> {
        let long = t == E::Ltod;
        let dur = if long { E::Ltime } else { E::Time };
        Some(match self.rng.below(7) {
            0 | 1 => {
                let x = self.ex(b, t, d, true);
                let y = self.ex(b, dur, d, true);
                let op = if self.rng.chance(50) { "+" } else { "-" };
                if self.rng.chance(30) {
                    let f = if op == "+" { "ADD" } else { "SUB" };
                    format!("{f}_{}_{}({x}, {y})", t.name(), dur.name())
                } else {
                    format!("({x} {op} {y})")
                }
            }
            2 => {
                let h = self.clamped_int(b, 0, 23, d);
                let m = self.clamped_int(b, 0, 59, d);
                let s = self.clamped_int(b, 0, 59, d);
                let ms = self.clamped_int(b, 0, 999, d);
                format!("CONCAT_{}({h}, {m}, {s}, {ms})", t.name())
            }
            3 => {
                let dt = if long { E::Ldt } else { E::Dt };
                format!(
                    "{}_TO_{}({})",
                    dt.name(),
                    t.name(),
                    self.ex(b, dt, d, false)
                )
            }
            4 => return self.select(b, t, d),
            5 => return self.conv(b, t, d),
            _ => return self.call_expr(b, t, d),
        })
    }

    /// DT or LDT.
    fn ex_dt(&mut self, b: &Body, t: E, d: u32) -> Option<String> {
        let long = t == E::Ldt;
        let dur = if long { E::Ltime } else { E::Time };
        Some(match self.rng.below(7) {
            0 | 1 => {
                let x = self.ex(b, t, d, true);
                let y = self.ex(b, dur, d, true);
                let op = if self.rng.chance(50) { "+" } else { "-" };
                if self.rng.chance(30) {
                    let f = if op == "+" { "ADD" } else { "SUB" };
                    format!("{f}_{}_{}({x}, {y})", t.name(), dur.name())
                } else {
                    format!("({x} {op} {y})")
                }
            }
            2 => {
                // The date is a DATE in both forms.
                let tod = if long { E::Ltod } else { E::Tod };
                let x = self.ex(b, E::Date, d, false);
                let y = self.ex(b, tod, d, false);
                format!("CONCAT_DATE_{}({x}, {y})", tod.name())
            }
            3 => {
                let parts = [
                    self.clamped_int(b, 1970, 2100, d),
                    self.clamped_int(b, 1, 12, d),
                    self.clamped_int(b, 1, 28, d),
                    self.clamped_int(b, 0, 23, d),
                    self.clamped_int(b, 0, 59, d),
                    self.clamped_int(b, 0, 59, d),
                    self.clamped_int(b, 0, 999, d),
                ];
                format!("CONCAT_{}({})", t.name(), parts.join(", "))
            }
            4 => return self.select(b, t, d),
            5 => return self.conv(b, t, d),
            _ => return self.call_expr(b, t, d),
        })
    }

    /// A string length or position argument.
    fn str_count(&mut self, b: &Body, d: u32) -> String {
        if self.rng.chance(70) {
            return self.rng.range(0, 10).to_string();
        }
        let t = *self.rng.pick(&[E::Int, E::Sint, E::Dint, E::Usint]);
        self.ex(b, t, d.min(1), true)
    }

    fn ex_str(&mut self, b: &Body, t: E, d: u32) -> Option<String> {
        let w = [10, 10, 6, 6, 3, 1];
        Some(match self.rng.weighted(&w) {
            0 => {
                let n = if self.rng.chance(25) { 3 } else { 2 };
                let args: Vec<String> = (0..n).map(|_| self.ex(b, t, d, false)).collect();
                format!("CONCAT({})", args.join(", "))
            }
            1 => {
                let s = self.ex(b, t, d, false);
                match self.rng.below(6) {
                    0 => format!("LEFT({s}, {})", self.str_count(b, d)),
                    1 => format!("RIGHT({s}, {})", self.str_count(b, d)),
                    2 => {
                        let l = self.str_count(b, d);
                        let p = self.str_count(b, d);
                        format!("MID({s}, {l}, {p})")
                    }
                    3 => {
                        let x = self.ex(b, t, d.min(1), false);
                        let p = self.str_count(b, d);
                        format!("INSERT({s}, {x}, {p})")
                    }
                    4 => {
                        let l = self.str_count(b, d);
                        let p = self.str_count(b, d);
                        format!("DELETE({s}, {l}, {p})")
                    }
                    _ => {
                        let x = self.ex(b, t, d.min(1), false);
                        let l = self.str_count(b, d);
                        let p = self.str_count(b, d);
                        format!("REPLACE({s}, {x}, {l}, {p})")
                    }
                }
            }
            2 => return self.conv(b, t, d),
            3 => return self.select(b, t, d),
            4 => return self.call_expr(b, t, d),
            _ => {
                let other = if t == E::String {
                    E::Wstring
                } else {
                    E::String
                };
                format!(
                    "{}_TO_{}({})",
                    other.name(),
                    t.name(),
                    self.ex(b, other, d, false)
                )
            }
        })
    }

    fn ex_char(&mut self, b: &Body, t: E, d: u32) -> Option<String> {
        Some(match self.rng.below(4) {
            0 => return self.select(b, t, d),
            1 if t == E::Wchar => format!("CHAR_TO_WCHAR({})", self.ex(b, E::Char, d, false)),
            1 => {
                // A WCHAR above 255 does not convert: keep it below.
                let w = self.ex(b, E::Wchar, d, true);
                format!("WCHAR_TO_CHAR(MIN({w}, WCHAR#\"ÿ\"))")
            }
            2 => return self.conv(b, t, d),
            _ => return self.call_expr(b, t, d),
        })
    }

    pub(crate) fn enum_ex(&mut self, b: &Body, i: usize, d: u32, qualified: bool) -> String {
        let ty = Ty::Enum(i);
        let r = self.rng.below(10);
        if r < 5 {
            let found: Vec<&Access> = b.reach.values.iter().filter(|a| a.ty == ty).collect();
            if !found.is_empty() {
                let a = (*self.rng.pick(&found)).clone();
                return self.render(b, &a, d.min(1));
            }
        }
        if r == 9 && d > 0 {
            let g = self.ex(b, E::Bool, d - 1, true);
            let x = self.enum_ex(b, i, d - 1, true);
            let y = self.enum_ex(b, i, d - 1, true);
            return format!("SEL({g}, {x}, {y})");
        }
        let e = &self.types.enums[i];
        let v = self.rng.pick(&e.values).clone();
        if qualified || self.rng.chance(50) {
            format!("{}#{v}", e.name)
        } else {
            v
        }
    }

    // ------------------------------------------------------------------
    // Conversions.

    /// A REAL/LREAL expression of type `src`, NaN replaced by 0 and clamped
    /// into `lo..=hi` (which must be exactly representable in `src`).
    pub(crate) fn real_guarded(&mut self, b: &Body, src: E, lo: i128, hi: i128) -> String {
        let x = match self.read_access(b, src, false) {
            Some(a) if self.rng.chance(80) => self.render(b, &a, 0),
            _ => self.real_lit(src, true),
        };
        format!("LIMIT({lo}.0, SEL({x} = {x}, 0.0, {x}), {hi}.0)")
    }

    /// `SRC_TO_T(...)` for some source type the standard converts from, with
    /// the argument guarded so that the conversion cannot fail.
    fn conv(&mut self, b: &Body, t: E, d: u32) -> Option<String> {
        let sources: Vec<E> = crate::model::ELEMS
            .iter()
            .map(|&(e, _)| e)
            .filter(|&s| s != t && stc_values::conversion_allowed(s, t) && self.allowed(s))
            .collect();
        if sources.is_empty() {
            return None;
        }
        // Mostly from a type the body has variables of.
        let have: Vec<E> = self
            .readable_types(b)
            .into_iter()
            .filter(|s| sources.contains(s))
            .collect();
        let s = if !have.is_empty() && self.rng.chance(60) {
            *self.rng.pick(&have)
        } else {
            *self.rng.pick(&sources)
        };
        let generic = self.rng.chance(10);
        let arg = self.conv_arg(b, s, t, d, generic);
        let name = if generic {
            format!("TO_{}", t.name())
        } else {
            format!("{}_TO_{}", s.name(), t.name())
        };
        Some(format!("{name}({arg})"))
    }

    fn conv_arg(&mut self, b: &Body, s: E, t: E, d: u32, anchor: bool) -> String {
        let (cs, ct) = (class(s), class(t));
        match (cs, ct) {
            (Class::Real, Class::Int | Class::Bits) => {
                let (lo, hi) = range(t);
                let lim: i128 = if s == E::Real {
                    1_000_000
                } else {
                    1_000_000_000
                };
                self.real_guarded(b, s, lo.max(-lim), hi.min(lim))
            }
            (Class::Real, Class::Dur) => self.real_guarded(b, s, -1_000_000, 1_000_000),
            (Class::Str, Class::Str) | (_, Class::Str) => self.ex(b, s, d, anchor),
            (Class::Str, _) => {
                // Text that converts back: the value's own text.
                let x = self.ex(b, t, d, false);
                format!("{}_TO_{}({x})", t.name(), s.name())
            }
            (Class::Dur, Class::Tod) => {
                let x = self.ex(b, s, d, true);
                let p = if s == E::Ltime { "LTIME#" } else { "T#" };
                format!("LIMIT({p}0s, {x}, {p}23h59m59s999ms)")
            }
            (Class::Int | Class::Bits, Class::Tod | Class::Date | Class::Dt) => {
                // TOD counts milliseconds, DATE and DT seconds, the long
                // types nanoseconds: keep to one day, or years 1970..2100.
                let (_, hi) = range(s);
                let long = matches!(t, E::Ltod | E::Ldate | E::Ldt);
                let top = match (ct == Class::Tod, long) {
                    (true, false) => 86_399_999,
                    (true, true) => 86_399_999_999_999,
                    (false, false) => 4_102_444_800,
                    (false, true) => 4_102_444_800_000_000_000,
                };
                let x = self.ex(b, s, d, true);
                format!("LIMIT(0, {x}, {})", hi.min(top))
            }
            (Class::Char, Class::Char) if s == E::Wchar => {
                let w = self.ex(b, s, d, true);
                format!("MIN({w}, WCHAR#\"ÿ\")")
            }
            _ => self.ex(b, s, d, anchor),
        }
    }

    // ------------------------------------------------------------------
    // Calls of the generated functions.

    /// A call of a generated function returning `t`, inputs only (a call
    /// inside an expression).
    fn call_expr(&mut self, b: &Body, t: E, d: u32) -> Option<String> {
        let cands: Vec<usize> = (0..b.funcs)
            .filter(|&i| {
                let f = &self.funcs[i];
                f.inouts.is_empty() && f.ret.as_ref().and_then(|r| r.scalar(&self.types)) == Some(t)
            })
            .collect();
        if cands.is_empty() {
            return None;
        }
        let i = *self.rng.pick(&cands);
        Some(self.call_text(b, i, d, false))
    }

    /// The text of a call of function `i`: every input (by name, or
    /// positionally now and then), the in-outs (the caller has made sure
    /// with [`Gen::can_call`] that each has a variable to take), and with
    /// `outputs` some `=>` outputs.
    pub(crate) fn call_text(&mut self, b: &Body, i: usize, d: u32, outputs: bool) -> String {
        let f = self.funcs[i].clone();
        let en_eno = outputs && self.rng.chance(15);
        let positional = !en_eno
            && f.inouts.is_empty()
            && (!outputs || f.outputs.is_empty())
            && self.rng.chance(30);
        let mut args = Vec::new();
        if en_eno {
            args.push(format!("EN := {}", self.cond(b, d.min(2))));
        }
        for (name, ty) in &f.inputs {
            let v = self.value_of(b, ty, d);
            if positional {
                args.push(v);
            } else {
                args.push(format!("{name} := {v}"));
            }
        }
        for (name, ty) in &f.inouts {
            if let Some(a) = self.write_access(b, ty) {
                let p = self.render(b, &a, 1);
                args.push(format!("{name} := {p}"));
            }
        }
        if en_eno {
            if let Some(p) = self.eno(b) {
                args.push(p);
            }
        }
        if outputs {
            for (name, ty) in &f.outputs {
                if self.rng.chance(50) {
                    if let Some(a) = self.write_access(b, ty) {
                        let p = self.render(b, &a, 1);
                        args.push(format!("{name} => {p}"));
                    }
                }
            }
        }
        format!("{}({})", f.name, args.join(", "))
    }

    /// `ENO => flag` for a writable BOOL, if there is one.
    pub(crate) fn eno(&mut self, b: &Body) -> Option<String> {
        let a = self.write_access(b, &Ty::E(E::Bool))?;
        Some(format!("ENO => {}", self.render(b, &a, 1)))
    }

    /// Whether every in-out of function `i` has a variable here.
    pub(crate) fn can_call(&self, b: &Body, i: usize) -> bool {
        self.funcs[i]
            .inouts
            .iter()
            .all(|(_, ty)| b.reach.values.iter().any(|a| a.writable && &a.ty == ty))
    }

    /// A value for a parameter or an assignment of type `ty`.
    pub(crate) fn value_of(&mut self, b: &Body, ty: &Ty, d: u32) -> String {
        match ty {
            Ty::E(e) => self.ex(b, *e, d, false),
            Ty::Str { wide, .. } => {
                let e = if *wide { E::Wstring } else { E::String };
                self.ex(b, e, d, false)
            }
            Ty::Enum(i) => self.enum_ex(b, *i, d, false),
            Ty::Sub(i) => {
                let (base, lo, hi) = {
                    let s = &self.types.subs[*i];
                    (s.base, s.lo, s.hi)
                };
                if self.unguarded() {
                    if let Some(a) = self.read_access(b, base, true) {
                        return self.render(b, &a, 0);
                    }
                }
                if self.rng.chance(25) {
                    return self.rng.range(lo, hi).to_string();
                }
                let x = self.ex(b, base, d, true);
                format!("LIMIT({lo}, {x}, {hi})")
            }
            _ => {
                // Structures and arrays: another variable of the type.
                let found: Vec<&Access> = b.reach.values.iter().filter(|a| &a.ty == ty).collect();
                let a = (*self.rng.pick(&found)).clone();
                self.render(b, &a, d.min(1))
            }
        }
    }

    /// Whether [`Gen::value_of`] can produce a value of `ty` in this body.
    pub(crate) fn has_value(&self, b: &Body, ty: &Ty) -> bool {
        match ty {
            Ty::E(_) | Ty::Str { .. } | Ty::Enum(_) | Ty::Sub(_) => true,
            Ty::Fb(_) => false,
            _ => b.reach.values.iter().any(|a| &a.ty == ty),
        }
    }

    /// The bit-string and integer types, for the statement generator.
    pub(crate) fn selector_types() -> Vec<E> {
        INTS.iter().chain(BITS.iter()).copied().collect()
    }
}
