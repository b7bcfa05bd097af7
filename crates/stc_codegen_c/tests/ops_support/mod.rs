//! Support for `ops_vs_values.rs`: a test implementation of [`Emit`], the
//! C test program (one function per operation shape, tables of operands,
//! one output line per case), compiling and running it with gcc and the
//! sanitizers, and the expected lines computed with `stc_values`.

#![allow(dead_code)]

pub mod values;

use stc_codegen_c::ops::{emit_op, Emit, Operation};
use stc_ir::Module;
use stc_sema::{TypeId, TypeKind, TypeTable};
use stc_syntax::token::ElemType;
use stc_values::{Fault, Value};
use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::OnceLock;

use ElemType as E;

/// The strict flags of the brief, for the runtime and every test program.
pub const CFLAGS: &[&str] = &[
    "-std=c99",
    "-pedantic",
    "-Wall",
    "-Wextra",
    "-Wconversion",
    "-Wshadow",
    "-Werror",
    "-fsanitize=undefined,address",
    "-fno-sanitize-recover=all",
];

pub fn runtime_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("runtime")
}

fn work_dir() -> PathBuf {
    let d = Path::new(env!("CARGO_TARGET_TMPDIR")).join("ops_vs_values");
    std::fs::create_dir_all(&d).expect("create the work directory");
    d
}

/// The runtime compiled once (per test process) with the sanitizers.
pub fn runtime_object() -> &'static Path {
    static OBJ: OnceLock<PathBuf> = OnceLock::new();
    OBJ.get_or_init(|| {
        let out = work_dir().join(format!("stc_rt_{}.o", std::process::id()));
        let src = runtime_dir().join("stc_rt.c");
        let st = Command::new("gcc")
            .args(CFLAGS)
            .arg("-c")
            .arg(&src)
            .arg("-o")
            .arg(&out)
            .output()
            .expect("run gcc (the C back end's tests need it)");
        assert!(
            st.status.success(),
            "stc_rt.c does not compile cleanly:\n{}",
            String::from_utf8_lossy(&st.stderr)
        );
        out
    })
}

/// Compiles `src` with the runtime and runs it; returns its stdout.
pub fn compile_and_run(name: &str, src: &str) -> String {
    let dir = work_dir();
    let c = dir.join(format!("{name}_{}.c", std::process::id()));
    let exe = dir.join(format!("{name}_{}", std::process::id()));
    std::fs::write(&c, src).expect("write the test program");
    let st = Command::new("gcc")
        .args(CFLAGS)
        .arg("-I")
        .arg(runtime_dir())
        .arg(&c)
        .arg(runtime_object())
        .arg("-o")
        .arg(&exe)
        .arg("-lm")
        .output()
        .expect("run gcc");
    assert!(
        st.status.success(),
        "{name}: the generated C does not compile cleanly ({}):\n{}",
        c.display(),
        String::from_utf8_lossy(&st.stderr)
    );
    let run = Command::new(&exe)
        .env("ASAN_OPTIONS", "detect_leaks=0")
        .output()
        .expect("run the test program");
    assert!(
        run.status.success(),
        "{name}: the test program failed ({}):\n{}",
        c.display(),
        String::from_utf8_lossy(&run.stderr)
    );
    // Kept for a look when something failed; removed when all went well.
    if std::env::var_os("STC_KEEP_C").is_none() {
        let _ = std::fs::remove_file(&c);
        let _ = std::fs::remove_file(&exe);
    }
    String::from_utf8(run.stdout).expect("ASCII output")
}

/// A module with every elementary type and the string types asked for.
pub struct Types {
    pub module: Module,
}

impl Types {
    pub fn new(string_caps: &[u32]) -> Types {
        let mut t = TypeTable::new();
        for &c in string_caps {
            t.string(false, c);
            t.string(true, c);
        }
        Types {
            module: Module {
                types: t,
                pous: Default::default(),
                globals: Default::default(),
                configs: Vec::new(),
                names: Vec::new(),
                spellings: Default::default(),
            },
        }
    }

    /// The type of an elementary type; STRING/WSTRING with capacity `cap`.
    pub fn ty(&self, e: ElemType, cap: u32) -> TypeId {
        match e {
            E::String | E::Wstring => {
                let wide = e == E::Wstring;
                (0..self.module.types.len() as u32)
                    .map(TypeId)
                    .find(|&t| {
                        matches!(self.module.types.kind(t),
                            TypeKind::String { wide: w, len } if *w == wide && *len == cap)
                    })
                    .unwrap_or_else(|| panic!("no string type of capacity {cap}"))
            }
            _ => self.module.types_elem(e),
        }
    }
}

/// The C type of an elementary type's representation.
pub fn ctype(e: ElemType) -> &'static str {
    match e {
        E::Bool | E::Usint | E::Byte | E::Char => "uint8_t",
        E::Sint => "int8_t",
        E::Int => "int16_t",
        E::Dint => "int32_t",
        E::Uint | E::Word | E::Wchar => "uint16_t",
        E::Udint | E::Dword => "uint32_t",
        E::Ulint | E::Lword => "uint64_t",
        E::Real => "float",
        E::Lreal => "double",
        E::String => "const uint8_t *",
        E::Wstring => "const uint16_t *",
        _ => "int64_t",
    }
}

struct TestEmit<'m> {
    m: &'m Module,
    temps: Vec<(String, String)>,
    body: Vec<String>,
    site: u32,
}

impl Emit for TestEmit<'_> {
    fn module(&self) -> &Module {
        self.m
    }

    fn temp(&mut self, ty: TypeId) -> String {
        let name = format!("t{}", self.temps.len());
        let c = self.c_type(ty);
        self.temps.push((name.clone(), c));
        name
    }

    fn stmt(&mut self, s: String) {
        self.body.push(s);
    }

    fn fault_check(&mut self) {
        self.body
            .push("if (stc_fault_kind != 0U) { out_fault(); return; }".into());
    }

    fn site(&self) -> u32 {
        self.site
    }

    fn c_type(&self, ty: TypeId) -> String {
        match self.m.types.scalar(ty) {
            Some(E::String) | Some(E::Wstring) | None => "uint8_t".into(),
            Some(e) => ctype(e).into(),
        }
    }
}

/// One operation at fixed types, with its cases.
pub struct Shape {
    pub label: String,
    pub op: Operation,
    pub args: Vec<(ElemType, TypeId)>,
    pub result: (ElemType, TypeId, u32),
    pub cases: Vec<Vec<Value>>,
    /// The expected output line of each case.
    pub expect: Vec<String>,
    /// The destination is this argument itself (the operand variable is
    /// overwritten), to check that scalar operations allow it.
    pub alias: Option<usize>,
}

/// The expected output line of a result.
pub fn expect_line(res: ElemType, cap: u32, r: &Result<Value, Fault>) -> String {
    match r {
        Err(f) => format!("F{}", fault_code(*f)),
        Ok(v) => value_line(res, cap, v),
    }
}

pub fn fault_code(f: Fault) -> u32 {
    u32::from(stc_ir::FaultKind::from_value_fault(f).code())
}

/// A value as the test program prints a variable of type `res`.
pub fn value_line(res: ElemType, cap: u32, v: &Value) -> String {
    match (res, v) {
        (E::String, Value::Str(s)) => {
            let mut out = String::from("S");
            for b in s.iter().take(cap as usize) {
                let _ = write!(out, "{b:02x}");
            }
            out
        }
        (E::Wstring, Value::WStr(s)) => {
            let mut out = String::from("W");
            for u in s.iter().take(cap as usize) {
                let _ = write!(out, "{u:04x}");
            }
            out
        }
        (E::Real, Value::Real(x)) => {
            if x.is_nan() {
                "NAN".into()
            } else {
                format!("{:08x}", (*x as f32).to_bits())
            }
        }
        (E::Lreal, Value::Real(x)) => {
            if x.is_nan() {
                "NAN".into()
            } else {
                format!("{:016x}", x.to_bits())
            }
        }
        (_, Value::Bool(b)) => format!("{:x}", u8::from(*b)),
        (_, Value::Int(i)) => {
            let bits = match res {
                E::Bool | E::Sint | E::Usint | E::Byte | E::Char => 8,
                E::Int | E::Uint | E::Word | E::Wchar => 16,
                E::Dint | E::Udint | E::Dword => 32,
                _ => 64,
            };
            let mask: u128 = (1u128 << bits) - 1;
            format!("{:x}", (*i as u128) & mask)
        }
        _ => format!("BAD VALUE {v:?}"),
    }
}

/// A C literal for an operand table.
fn c_value(e: ElemType, v: &Value, pool: &mut Pool) -> String {
    match (e, v) {
        (E::Real, Value::Real(x)) => format!("0x{:08x}U", (*x as f32).to_bits()),
        (E::Lreal, Value::Real(x)) => format!("UINT64_C(0x{:016x})", x.to_bits()),
        (E::String, Value::Str(s)) => pool.string(s),
        (E::Wstring, Value::WStr(w)) => pool.wstring(w),
        (_, Value::Bool(b)) => format!("{}U", u8::from(*b)),
        (_, Value::Int(i)) => match ctype(e) {
            "int64_t" if *i == i64::MIN as i128 => "INT64_MIN".into(),
            "int64_t" => format!("INT64_C({i})"),
            "uint64_t" => format!("UINT64_C({i})"),
            "int8_t" | "int16_t" | "int32_t" if *i == i32::MIN as i128 => "INT32_MIN".into(),
            "int8_t" | "int16_t" | "int32_t" => format!("{i}"),
            _ => format!("{i}U"),
        },
        _ => panic!("no C literal for {e:?} {v:?}"),
    }
}

/// The element type of an operand table, and how a table entry becomes
/// the argument.
fn table_type(e: ElemType) -> (&'static str, &'static str) {
    match e {
        E::Real => ("uint32_t", "f32_of"),
        E::Lreal => ("uint64_t", "f64_of"),
        E::String => ("const uint8_t *", ""),
        E::Wstring => ("const uint16_t *", ""),
        _ => (ctype(e), ""),
    }
}

/// The string operands of a program.
#[derive(Default)]
pub struct Pool {
    decls: String,
    lens: Vec<(String, usize)>,
    n: usize,
    map: std::collections::HashMap<(bool, Vec<u16>), String>,
}

impl Pool {
    /// The declarations of the pool and the statement setting the lengths
    /// of its STRINGs (one loop over a table).
    fn parts(&self) -> (String, String) {
        if self.lens.is_empty() {
            return (self.decls.clone(), String::new());
        }
        let names: Vec<&str> = self.lens.iter().map(|(n, _)| n.as_str()).collect();
        let lens: Vec<String> = self.lens.iter().map(|(_, l)| format!("{l}U")).collect();
        let decls = format!(
            "{}static uint8_t *const pool[{n}] = {{ {} }};\nstatic const uint16_t pool_len[{n}] = {{ {} }};\n",
            self.decls,
            names.join(", "),
            lens.join(", "),
            n = names.len()
        );
        let init = format!(
            "    for (i = 0U; i < {}U; i++) {{ set_len(pool[i], pool_len[i]); }}\n",
            names.len()
        );
        (decls, init)
    }

    fn string(&mut self, s: &[u8]) -> String {
        let key = (false, s.iter().map(|&b| u16::from(b)).collect::<Vec<u16>>());
        if let Some(n) = self.map.get(&key) {
            return n.clone();
        }
        let name = format!("s{}", self.n);
        self.n += 1;
        let bytes: Vec<String> = s.iter().map(|b| format!("{b}U")).collect();
        let _ = writeln!(
            self.decls,
            "static uint8_t {name}[{}] = {{ 0U, 0U{}{} }};",
            s.len() + 2,
            if bytes.is_empty() { "" } else { ", " },
            bytes.join(", ")
        );
        self.lens.push((name.clone(), s.len()));
        self.map.insert(key, name.clone());
        name
    }

    fn wstring(&mut self, w: &[u16]) -> String {
        let key = (true, w.to_vec());
        if let Some(n) = self.map.get(&key) {
            return n.clone();
        }
        let name = format!("w{}", self.n);
        self.n += 1;
        let units: Vec<String> = w.iter().map(|u| format!("{u}U")).collect();
        let _ = writeln!(
            self.decls,
            "static const uint16_t {name}[{}] = {{ {}U{}{} }};",
            w.len() + 1,
            w.len(),
            if units.is_empty() { "" } else { ", " },
            units.join(", ")
        );
        self.map.insert(key, name.clone());
        name
    }
}

/// Marks every helper of the prelude used.
pub const USE_ALL: &str = "(void)set_len; (void)f32_of; (void)f64_of; (void)out_u; (void)out_f32; \
(void)out_f64; (void)out_str; (void)out_wstr; (void)out_fault;";

const PRELUDE: &str = r#"
#include <inttypes.h>
#include <math.h>
#include <stdio.h>
#include <string.h>
#include "stc_rt.h"

static void set_len(uint8_t *s, uint16_t n) { (void)memcpy(s, &n, sizeof n); }
static float f32_of(uint32_t b) { float f; (void)memcpy(&f, &b, sizeof f); return f; }
static double f64_of(uint64_t b) { double f; (void)memcpy(&f, &b, sizeof f); return f; }
static void out_u(uint64_t v) { printf("%" PRIx64 "\n", v); }
static void out_f32(float f) {
    if (isnan(f)) { puts("NAN"); } else { uint32_t b; (void)memcpy(&b, &f, sizeof b); printf("%08" PRIx32 "\n", b); }
}
static void out_f64(double f) {
    if (isnan(f)) { puts("NAN"); } else { uint64_t b; (void)memcpy(&b, &f, sizeof b); printf("%016" PRIx64 "\n", b); }
}
static void out_str(const uint8_t *s) {
    uint16_t n; uint32_t i; (void)memcpy(&n, s, sizeof n);
    putchar('S'); for (i = 0U; i < n; i++) { printf("%02x", s[2U + i]); } putchar('\n');
}
static void out_wstr(const uint16_t *w) {
    uint32_t i; putchar('W'); for (i = 0U; i < w[0]; i++) { printf("%04x", w[1U + i]); } putchar('\n');
}
static void out_fault(void) { printf("F%" PRIu32 "\n", stc_fault_kind); }
"#;

/// The statement printing the destination `d` of type `res`.
fn out_stmt(res: ElemType, v: &str) -> String {
    match res {
        E::String => format!("out_str({v});"),
        E::Wstring => format!("out_wstr({v});"),
        E::Real => format!("out_f32({v});"),
        E::Lreal => format!("out_f64({v});"),
        E::Sint => format!("out_u((uint64_t)(uint8_t){v});"),
        E::Int => format!("out_u((uint64_t)(uint16_t){v});"),
        E::Dint => format!("out_u((uint64_t)(uint32_t){v});"),
        _ => format!("out_u((uint64_t){v});"),
    }
}

/// The whole test program of a set of shapes.
pub fn program(m: &Module, shapes: &[Shape]) -> String {
    let mut pool = Pool::default();
    let mut funcs = String::new();
    let mut tables = String::new();
    let mut main = String::new();
    for (k, s) in shapes.iter().enumerate() {
        let mut e = TestEmit {
            m,
            temps: Vec::new(),
            body: Vec::new(),
            site: 1000 + k as u32,
        };
        let args: Vec<(String, TypeId)> = s
            .args
            .iter()
            .enumerate()
            .map(|(i, (_, t))| (format!("a{i}"), *t))
            .collect();
        let dst = s.alias.map_or("d".to_string(), |k| format!("a{k}"));
        emit_op(&mut e, s.op, &args, s.result.1, &dst);
        let params: Vec<String> = s
            .args
            .iter()
            .enumerate()
            .map(|(i, (el, _))| format!("{} a{i}", ctype(*el)))
            .collect();
        let _ = writeln!(funcs, "/* {} */", s.label.replace("*/", "* /"));
        let _ = writeln!(
            funcs,
            "static void f{k}({}) {{",
            if params.is_empty() {
                "void".into()
            } else {
                params.join(", ")
            }
        );
        let (res, _, cap) = s.result;
        match res {
            E::String => {
                let _ = writeln!(funcs, "    uint8_t d[{}];", cap + 2);
            }
            E::Wstring => {
                let _ = writeln!(funcs, "    uint16_t d[{}];", cap + 1);
            }
            _ => {
                let _ = writeln!(funcs, "    {} d = 0;", ctype(res));
                let _ = writeln!(funcs, "    (void)d;");
            }
        }
        for (n, c) in &e.temps {
            let _ = writeln!(funcs, "    {c} {n};");
        }
        for i in 0..s.args.len() {
            let _ = writeln!(funcs, "    (void)a{i};");
        }
        let _ = writeln!(funcs, "    stc_fault_kind = 0U;");
        for l in &e.body {
            let _ = writeln!(funcs, "    {l}");
        }
        let _ = writeln!(
            funcs,
            "    if (stc_fault_kind != 0U) {{ puts(\"UNCHECKED FAULT\"); }} else {{ {} }}",
            out_stmt(res, &dst)
        );
        let _ = writeln!(funcs, "}}\n");
        // Operand tables and the loop over the cases.
        let n = s.cases.len();
        if n == 0 {
            continue;
        }
        let mut call_args = Vec::new();
        for (i, (el, _)) in s.args.iter().enumerate() {
            let (tt, conv) = table_type(*el);
            let items: Vec<String> = s
                .cases
                .iter()
                .map(|c| c_value(*el, &c[i], &mut pool))
                .collect();
            let _ = writeln!(
                tables,
                "static {tt} const x{k}_{i}[{n}] = {{ {} }};",
                items.join(", ")
            );
            call_args.push(format!("{conv}(x{k}_{i}[i])"));
        }
        let _ = writeln!(
            main,
            "    for (i = 0U; i < {n}U; i++) {{ f{k}({}); }}",
            call_args.join(", ")
        );
    }
    let (pool_decls, pool_init) = pool.parts();
    format!(
        "{PRELUDE}\n{}\n{tables}\n{funcs}\nint main(void)\n{{\n    uint32_t i = 0U;\n    {USE_ALL}\n{}{main}    return (int)i * 0;\n}}\n",
        pool_decls, pool_init
    )
}

/// Runs the shapes in one program and compares every line; returns the
/// number of comparisons.
pub fn check_shapes(name: &str, m: &Module, shapes: &[Shape]) -> usize {
    let src = program(m, shapes);
    let out = compile_and_run(name, &src);
    let mut lines = out.lines();
    let mut failures = Vec::new();
    let mut count = 0;
    for s in shapes {
        for (case, want) in s.cases.iter().zip(&s.expect) {
            let got = lines.next().unwrap_or("<missing>");
            count += 1;
            if got != want {
                failures.push(format!(
                    "{}: args {case:?}: expected {want}, got {got}",
                    s.label
                ));
            }
        }
    }
    assert!(lines.next().is_none(), "{name}: extra output");
    eprintln!("{name}: {count} results compared with stc_values");
    if !failures.is_empty() {
        let n = failures.len();
        failures.truncate(40);
        panic!(
            "{name}: {n} of {count} results differ from stc_values:\n{}",
            failures.join("\n")
        );
    }
    count
}

/// A C string literal of UTF-8 bytes (every byte escaped).
pub fn c_bytes(b: &[u8]) -> String {
    let mut s = String::from("\"");
    for x in b {
        let _ = write!(s, "\\x{x:02x}");
    }
    s.push('"');
    s
}

/// A program calling the harness functions `stc_convert_scalar` (every
/// pair of non-string types) and `stc_parse_value` (every type), and the
/// expected lines.
pub fn harness_program(
    conversions: &[(ElemType, ElemType, Vec<Value>)],
    splits: &[(stc_values::Intrinsic, ElemType, Vec<Value>)],
) -> (String, Vec<String>) {
    let mut pool = Pool::default();
    let mut body = String::new();
    let mut tables = String::new();
    let mut expect = Vec::new();
    for (k, (from, to, vals)) in conversions.iter().enumerate() {
        let (tt, conv) = table_type(*from);
        let items: Vec<String> = vals.iter().map(|v| c_value(*from, v, &mut pool)).collect();
        let _ = writeln!(
            tables,
            "static {tt} const c{k}[{}] = {{ {} }};",
            vals.len(),
            items.join(", ")
        );
        let _ = writeln!(
            body,
            "    for (i = 0U; i < {n}U; i++) {{ {ft} src = {conv}(c{k}[i]); {tt2} dst; uint32_t r; \
             (void)memset(&dst, 0xA5, sizeof dst); \
             r = stc_convert_scalar((uint8_t){fc}, &src, (uint8_t){tc}, &dst); \
             if (r != 0U) {{ printf(\"F%\" PRIu32 \"%s\\n\", r, unchanged(&dst, sizeof dst) ? \"\" : \" CHANGED\"); }} \
             else {{ {out} }} }}",
            n = vals.len(),
            ft = ctype(*from),
            tt2 = ctype(*to),
            fc = elem_code_name(*from),
            tc = elem_code_name(*to),
            out = out_stmt(*to, "dst"),
        );
        for v in vals {
            let r = stc_values::convert(*from, *to, v);
            expect.push(expect_line(*to, 0, &r));
        }
    }
    for (k, (f, elem, vals)) in splits.iter().enumerate() {
        let items: Vec<String> = vals.iter().map(|v| c_value(*elem, v, &mut pool)).collect();
        let _ = writeln!(
            tables,
            "static const int64_t q{k}[{}] = {{ {} }};",
            vals.len(),
            items.join(", ")
        );
        let (call, n) = match f {
            stc_values::Intrinsic::SplitDate => ("stc_split_date(q{k}[i], out, 7U)", 3),
            stc_values::Intrinsic::SplitTod => ("stc_split_tod(q{k}[i], out)", 4),
            _ => ("stc_split_dt(q{k}[i], out, 7U)", 7),
        };
        let _ = writeln!(
            body,
            "    for (i = 0U; i < {}U; i++) {{ int64_t out[7] = {{ 0, 0, 0, 0, 0, 0, 0 }}; uint32_t j; \
             stc_fault_kind = 0U; {}; if (stc_fault_kind != 0U) {{ out_fault(); }} else {{ \
             for (j = 0U; j < {n}U; j++) {{ printf(\"%\" PRId64 \" \", out[j]); }} putchar('\\n'); }} }}",
            vals.len(),
            call.replace("{k}", &k.to_string())
        );
        for v in vals {
            expect.push(match stc_values::split(*f, *elem, v) {
                Ok(fields) => fields.iter().map(|x| format!("{x} ")).collect(),
                Err(e) => format!("F{}", fault_code(e)),
            });
        }
    }
    let (pool_decls, pool_init) = pool.parts();
    let src = format!(
        "{PRELUDE}\nstatic int unchanged(const void *p, size_t n) {{ const uint8_t *b = (const uint8_t *)p; size_t k; \
         for (k = 0U; k < n; k++) {{ if (b[k] != 0xA5U) {{ return 0; }} }} return 1; }}\n{}\n{tables}\n\
         int main(void)\n{{\n    uint32_t i = 0U;\n    {USE_ALL}\n{}{body}    return (int)i * 0;\n}}\n",
        pool_decls, pool_init
    );
    (src, expect)
}

fn elem_code_name(e: ElemType) -> String {
    format!("STC_E_{}", e.name())
}

/// The statements `emit_op` emits for one operation (no temporaries used
/// by the operations of the hot path).
pub fn op_code(
    m: &Module,
    op: Operation,
    args: &[(&str, TypeId)],
    result: TypeId,
    dst: &str,
) -> Vec<String> {
    let mut e = TestEmit {
        m,
        temps: Vec::new(),
        body: Vec::new(),
        site: 1,
    };
    let args: Vec<(String, TypeId)> = args.iter().map(|(x, t)| (x.to_string(), *t)).collect();
    emit_op(&mut e, op, &args, result, dst);
    assert!(e.temps.is_empty(), "the hot path needs no temporary");
    e.body
}

/// `gcc -O2 -S` of a C source (with the runtime's header).
pub fn assemble(name: &str, src: &str) -> String {
    let dir = work_dir();
    let c = dir.join(format!("{name}_{}.c", std::process::id()));
    let s = dir.join(format!("{name}_{}.s", std::process::id()));
    std::fs::write(&c, src).expect("write the source");
    let st = Command::new("gcc")
        .args([
            "-std=c99",
            "-pedantic",
            "-Wall",
            "-Wextra",
            "-Wconversion",
            "-Wshadow",
            "-Werror",
        ])
        .args(["-O2", "-S", "-fno-asynchronous-unwind-tables", "-I"])
        .arg(runtime_dir())
        .arg(&c)
        .arg("-o")
        .arg(&s)
        .output()
        .expect("run gcc");
    assert!(
        st.status.success(),
        "{name}: does not compile:\n{}",
        String::from_utf8_lossy(&st.stderr)
    );
    let asm = std::fs::read_to_string(&s).expect("read the assembly");
    let _ = std::fs::remove_file(&c);
    let _ = std::fs::remove_file(&s);
    asm
}

/// The instructions of a function in gcc's assembly output.
pub fn function_body(asm: &str, name: &str) -> Vec<String> {
    let mut out = Vec::new();
    let mut inside = false;
    for l in asm.lines() {
        if l == format!("{name}:") {
            inside = true;
            continue;
        }
        if inside {
            let t = l.trim();
            if t.starts_with(".size") || (t.ends_with(':') && !t.starts_with('.')) {
                break;
            }
            if !t.starts_with('.') && !t.is_empty() {
                out.push(t.to_string());
            }
        }
    }
    out
}
