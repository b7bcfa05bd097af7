//! Property test: the constant folder, the virtual machine and the JIT agree.
//!
//! A random typed expression is compiled twice: once with literal leaves,
//! which the analyser folds to a constant with `stc_values`, and once with
//! every leaf read from a variable initialised to that literal, which the VM
//! computes with its own instructions and the JIT (`stc_engine_jit`) with
//! native code. Both programs store the result in `r`; after one cycle the
//! values must be identical (bit for bit for reals) on both engines, and an
//! expression the folder rejects (division by zero, a failed conversion)
//! must fault on the VM and on the JIT, with the same fault kind.

use std::sync::Arc;

use proptest::prelude::*;
use proptest::test_runner::{Config, TestRunner};
use stc_pipeline::Options;
use stc_runtime::Engine;
use stc_values::Value;

/// The types expressions are built over.
const INTS: &[&str] = &[
    "SINT", "INT", "DINT", "LINT", "USINT", "UINT", "UDINT", "ULINT",
];
const BITS: &[&str] = &["BYTE", "WORD", "DWORD", "LWORD"];
const REALS: &[&str] = &["REAL", "LREAL"];

fn range(t: &str) -> (i128, i128) {
    match t {
        "SINT" => (i8::MIN as i128, i8::MAX as i128),
        "INT" => (i16::MIN as i128, i16::MAX as i128),
        "DINT" => (i32::MIN as i128, i32::MAX as i128),
        "LINT" => (i64::MIN as i128, i64::MAX as i128),
        "USINT" | "BYTE" => (0, u8::MAX as i128),
        "UINT" | "WORD" => (0, u16::MAX as i128),
        "UDINT" | "DWORD" => (0, u32::MAX as i128),
        _ => (0, u64::MAX as i128),
    }
}

/// A generated expression: its text with literal leaves, the same with
/// variable leaves, and the leaves' declarations.
#[derive(Clone, Debug)]
struct Gen {
    lit: String,
    var: String,
}

struct Builder {
    decls: Vec<String>,
}

impl Builder {
    fn leaf(&mut self, ty: &str, literal: String) -> Gen {
        let name = format!("v{}", self.decls.len());
        self.decls.push(format!("  {name} : {ty} := {literal};"));
        Gen {
            lit: literal,
            var: name,
        }
    }
}

/// A recipe for an expression, drawn by proptest and built by `build`.
#[derive(Clone, Debug)]
enum Recipe {
    /// A literal: for integers a value picked from `seed`, often an edge.
    Leaf(u64, u8),
    Unary(u8, Box<Recipe>),
    Binary(u8, Box<Recipe>, Box<Recipe>),
    /// A conversion from another type (by index).
    Convert(u8, Box<Recipe>),
    /// A comparison of two operands of another type (its result is BOOL).
    Compare(u8, u8, Box<Recipe>, Box<Recipe>),
    Call(u8, Vec<Recipe>),
}

fn recipe() -> impl Strategy<Value = Recipe> {
    let leaf = (any::<u64>(), any::<u8>()).prop_map(|(s, k)| Recipe::Leaf(s, k));
    leaf.prop_recursive(4, 24, 3, |inner| {
        prop_oneof![
            (any::<u8>(), inner.clone()).prop_map(|(o, a)| Recipe::Unary(o, Box::new(a))),
            (any::<u8>(), inner.clone(), inner.clone()).prop_map(|(o, a, b)| Recipe::Binary(
                o,
                Box::new(a),
                Box::new(b)
            )),
            (any::<u8>(), inner.clone()).prop_map(|(t, a)| Recipe::Convert(t, Box::new(a))),
            (any::<u8>(), any::<u8>(), inner.clone(), inner.clone())
                .prop_map(|(t, o, a, b)| Recipe::Compare(t, o, Box::new(a), Box::new(b))),
            (any::<u8>(), prop::collection::vec(inner, 1..4)).prop_map(|(f, a)| Recipe::Call(f, a)),
        ]
    })
}

fn all_types() -> Vec<&'static str> {
    let mut v: Vec<&str> = INTS.to_vec();
    v.extend_from_slice(BITS);
    v.extend_from_slice(REALS);
    v.push("BOOL");
    v.push("TIME");
    v
}

fn is_int(t: &str) -> bool {
    INTS.contains(&t)
}
fn is_bits(t: &str) -> bool {
    BITS.contains(&t)
}
fn is_real(t: &str) -> bool {
    REALS.contains(&t)
}

fn literal(ty: &str, seed: u64, k: u8) -> String {
    if ty == "BOOL" {
        return if seed & 1 == 1 { "TRUE" } else { "FALSE" }.into();
    }
    if is_real(ty) {
        let specials = [
            0.0, -0.0, 1.0, -1.0, 0.5, 2.5, -2.5, 1e10, -3.75, 1e-3, 123.456,
        ];
        let x = match k % 4 {
            0 => specials[(seed % specials.len() as u64) as usize],
            _ => ((seed % 2_000_001) as f64 - 1_000_000.0) / 64.0,
        };
        let s = format!("{x:?}");
        let s = if s.contains('.') || s.contains('e') {
            s
        } else {
            format!("{s}.0")
        };
        return format!("{ty}#{}", s.replace("e", "E"));
    }
    if ty == "TIME" {
        let ms = (seed % 2_000_000) as i64 - 1_000_000;
        return if ms < 0 {
            format!("T#-{}ms", -ms)
        } else {
            format!("T#{ms}ms")
        };
    }
    let (lo, hi) = range(ty);
    let v = match k % 5 {
        0 => lo,
        1 => hi,
        2 => 0,
        3 => (seed % 17) as i128 - if lo < 0 { 8 } else { 0 },
        _ => lo + (seed as i128).rem_euclid(hi - lo + 1),
    };
    let v = v.clamp(lo, hi);
    if is_bits(ty) {
        format!("{ty}#16#{v:X}")
    } else if v < 0 {
        format!("{ty}#-{}", -v)
    } else {
        format!("{ty}#{v}")
    }
}

/// Builds an expression of type `ty` from a recipe (choices adapt to the type).
fn build(b: &mut Builder, r: &Recipe, ty: &str) -> Gen {
    let types = all_types();
    match r {
        Recipe::Leaf(seed, k) => {
            let l = literal(ty, *seed, *k);
            b.leaf(ty, l)
        }
        Recipe::Unary(o, a) => {
            let x = build(b, a, ty);
            let op = match ty {
                "BOOL" => "NOT ",
                t if is_bits(t) => "NOT ",
                t if t.starts_with('U') => return x,
                _ if o % 2 == 0 => "-",
                _ => return x,
            };
            Gen {
                lit: format!("({op}{})", x.lit),
                var: format!("({op}{})", x.var),
            }
        }
        Recipe::Binary(o, a, c) => {
            let ops: &[&str] = match ty {
                "BOOL" => &["AND", "OR", "XOR", "=", "<>"],
                t if is_bits(t) => &["AND", "OR", "XOR"],
                t if is_real(t) => &["+", "-", "*", "/"],
                "TIME" => &["+", "-"],
                _ => &["+", "-", "*", "/", "MOD"],
            };
            let op = ops[*o as usize % ops.len()];
            let (x, y) = (build(b, a, ty), build(b, c, ty));
            Gen {
                lit: format!("({} {op} {})", x.lit, y.lit),
                var: format!("({} {op} {})", x.var, y.var),
            }
        }
        Recipe::Convert(t, a) => {
            let from = types[*t as usize % types.len()];
            let convertible = |f: &str, t: &str| {
                f != t
                    && !(f == "TIME" && t != "LINT" && t != "DINT")
                    && !(t == "TIME" && f != "LINT" && f != "DINT")
            };
            if !convertible(from, ty) {
                return build(b, a, ty);
            }
            let x = build(b, a, from);
            Gen {
                lit: format!("{from}_TO_{ty}({})", x.lit),
                var: format!("{from}_TO_{ty}({})", x.var),
            }
        }
        Recipe::Compare(t, o, a, c) if ty == "BOOL" => {
            let ot = types[*t as usize % types.len()];
            let ops = ["=", "<>", "<", "<=", ">", ">="];
            let op = ops[*o as usize % ops.len()];
            let (x, y) = (build(b, a, ot), build(b, c, ot));
            Gen {
                lit: format!("({} {op} {})", x.lit, y.lit),
                var: format!("({} {op} {})", x.var, y.var),
            }
        }
        Recipe::Compare(_, _, a, _) => build(b, a, ty),
        Recipe::Call(f, args) => {
            let num = is_int(ty) || is_real(ty);
            let (name, want): (&str, usize) = match f % 6 {
                0 if num || is_bits(ty) || ty == "TIME" => ("MAX", args.len().max(2)),
                1 if num || is_bits(ty) || ty == "TIME" => ("MIN", args.len().max(2)),
                2 if num || is_bits(ty) || ty == "TIME" => ("LIMIT", 3),
                3 if num && !ty.starts_with('U') => ("ABS", 1),
                4 if is_bits(ty) => (["SHL", "SHR", "ROL", "ROR"][(*f as usize / 6) % 4], 2),
                5 => ("SEL", 3),
                _ => return build(b, &args[0], ty),
            };
            let mut lits = Vec::new();
            let mut vars = Vec::new();
            for i in 0..want {
                let r = args.get(i).unwrap_or(&args[0]);
                let aty = match (name, i) {
                    ("SEL", 0) => "BOOL",
                    ("SHL" | "SHR" | "ROL" | "ROR", 1) => "USINT",
                    _ => ty,
                };
                let x = build(b, r, aty);
                lits.push(x.lit);
                vars.push(x.var);
            }
            Gen {
                lit: format!("{name}({})", lits.join(", ")),
                var: format!("{name}({})", vars.join(", ")),
            }
        }
    }
}

/// What one cycle of a program produced.
#[derive(Clone, Debug, PartialEq)]
enum Outcome {
    /// The analyser rejected the program (the error codes).
    Rejected(Vec<String>),
    Fault(String),
    Value(String),
}

/// Runs one cycle of `src` on the VM and on the JIT: both outcomes (the
/// same `Rejected` twice when the analyser rejects it).
fn run(src: String) -> (Outcome, Outcome) {
    let mut sm = stc_diagnostics::SourceMap::new();
    sm.add("p.st", src);
    let a = stc_pipeline::analyse(sm, Vec::new(), &Options::default());
    let diags = a.all_diagnostics();
    let errors: Vec<String> = diags
        .iter()
        .filter(|d| d.is_error())
        .map(|d| format!("{:?}: {}", d.code, d.message))
        .collect();
    if !errors.is_empty() {
        return (Outcome::Rejected(errors.clone()), Outcome::Rejected(errors));
    }
    let module = stc_pipeline::lower(a);
    let image = Arc::new(stc_vm::compile(&module).expect("the program compiles"));
    let vm = cycle(stc_vm::Machine::new(image.clone()));
    match stc_engine_jit::JitEngine::build(&module) {
        Ok(jit) => (vm, cycle(jit)),
        // A host Cranelift has no back end for: the VM alone.
        Err(stc_engine_jit::Error::Unsupported(_)) => (vm.clone(), vm),
        Err(e) => panic!("the JIT did not compile the program: {e}"),
    }
}

/// One cycle of the first program on an engine, and the value of `r`.
fn cycle(mut e: impl Engine) -> Outcome {
    let model = e.model().clone();
    let inst = model.programs[0].clone();
    if let Err(f) = e.run_program(&inst, 0, 1_000_000) {
        return Outcome::Fault(format!("{:?}", f.kind));
    }
    let pou = &model.pous[inst.pou as usize];
    let r = pou
        .vars
        .iter()
        .find(|v| v.name.eq_ignore_ascii_case("r"))
        .expect("r");
    let v = stc_runtime::engine::read_value(&e, &model, inst.offset + r.offset, r.ty)
        .expect("readable");
    Outcome::Value(match v {
        Value::Real(x) => format!("{:?} bits {:016x}", x, x.to_bits()),
        v => format!("{v:?}"),
    })
}

fn program(ty: &str, expr: &str, decls: &[String]) -> String {
    format!(
        "PROGRAM Main\nVAR_OUTPUT r : {ty}; END_VAR\nVAR\n{}\nEND_VAR\nr := {expr};\nEND_PROGRAM\n",
        decls.join("\n")
    )
}

#[test]
fn the_constant_folder_the_vm_and_the_jit_agree() {
    let cases: u32 = std::env::var("STC_FOLD_CASES")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(600);
    let mut runner = TestRunner::new(Config {
        cases,
        failure_persistence: None,
        ..Config::default()
    });
    let types = all_types();
    let compared = std::cell::Cell::new(0u32);
    let skipped = std::cell::Cell::new(0u32);
    let faults = std::cell::Cell::new(0u32);
    let result = runner.run(&(any::<u8>(), recipe()), |(t, r)| {
        let ty = types[t as usize % types.len()];
        let mut b = Builder { decls: Vec::new() };
        let g = build(&mut b, &r, ty);
        // The folded constant is the same program on both engines: its
        // VM outcome stands for it.
        let (folded, _) = run(program(ty, &g.lit, &[]));
        let (computed, jit) = run(program(ty, &g.var, &b.decls));
        prop_assert_eq!(
            &computed,
            &jit,
            "the VM and the JIT differ (VM left, JIT right): r := {}",
            g.var
        );
        match (&folded, &computed) {
            // An expression the language rejects (the generator does not
            // know every rule) is rejected in both forms.
            (Outcome::Rejected(_), Outcome::Rejected(_)) => {
                skipped.set(skipped.get() + 1);
                return Ok(());
            }
            // The variable form is rejected only when the literal form is.
            (_, Outcome::Rejected(codes)) => {
                prop_assert!(
                    false,
                    "the variable form was rejected ({codes:?}): r := {}",
                    g.var
                )
            }
            // A constant the folder rejects must fault at run time.
            (Outcome::Rejected(_), Outcome::Fault(_)) => faults.set(faults.get() + 1),
            (Outcome::Rejected(codes), Outcome::Value(v)) => prop_assert!(
                false,
                "folding failed with {codes:?} but the VM computed {v}: r := {}",
                g.lit
            ),
            (a, b) => {
                prop_assert_eq!(a, b, "r := {}   (variables: {})", g.lit, g.var);
            }
        }
        compared.set(compared.get() + 1);
        Ok(())
    });
    if let Err(e) = result {
        panic!("{e}");
    }
    eprintln!(
        "{} expressions compared ({} of them faults), {} rejected in both forms",
        compared.get(),
        faults.get(),
        skipped.get()
    );
    // Most generated programs are valid: the comparison is not vacuous.
    assert!(compared.get() > skipped.get());
}
