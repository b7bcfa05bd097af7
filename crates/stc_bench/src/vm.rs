//! `stc-bench vm [CYCLES] [KERNEL]`: the kernels of `bench/kernels`, each run on the
//! VM, on the JIT, as generated C and as hand-written C compiled with `gcc
//! -O2`; prints nanoseconds per cycle (best of 5 repetitions on the VM and
//! the JIT, of 20 in C, where a repetition costs less) and the ratios VM /
//! C, JIT / C and generated C / hand-written C. Every figure is CPU time
//! (of the thread, or of the C process), not wall time: the benchmark
//! machine is shared, and wall time measures its load.

use std::path::{Path, PathBuf};
use std::sync::Arc;

/// The CPU time of the calling thread, in nanoseconds.
fn cpu_ns() -> f64 {
    let mut ts = libc::timespec {
        tv_sec: 0,
        tv_nsec: 0,
    };
    // SAFETY: `ts` is a valid, writable timespec; the clock id is a
    // constant every Linux supports (the call cannot fail with it, and a
    // failure would leave 0, only spoiling a measurement).
    unsafe { libc::clock_gettime(libc::CLOCK_THREAD_CPUTIME_ID, &mut ts) };
    ts.tv_sec as f64 * 1e9 + ts.tv_nsec as f64
}

fn kernels_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../bench/kernels")
}

/// A kernel's source (UTF-8 text) as a source map.
fn load(st: &Path) -> Result<stc_diagnostics::SourceMap, String> {
    let text = std::fs::read_to_string(st).map_err(|e| format!("{}: {e}", st.display()))?;
    let mut sm = stc_diagnostics::SourceMap::new();
    sm.add(st.display().to_string(), text);
    Ok(sm)
}

/// Compiles a project to the IR, or gives its errors.
fn compile(
    sm: stc_diagnostics::SourceMap,
    diags: Vec<stc_diagnostics::Diagnostic>,
) -> Result<(stc_ir::Module, stc_diagnostics::SourceMap), String> {
    let c = stc_pipeline::compile(sm, diags, &stc_pipeline::Options::default());
    match c.module {
        Some(m) => Ok((m, c.sources)),
        None => Err(c
            .diagnostics
            .iter()
            .filter(|d| d.is_error())
            .map(|d| stc_diagnostics::render_human(d, &c.sources))
            .collect::<Vec<_>>()
            .join("\n")),
    }
}

/// Nanoseconds per cycle of a kernel on the VM.
fn vm_time(st: &Path, cycles: u64) -> Result<f64, String> {
    vm_time_of(load(st)?, Vec::new(), cycles, None)
}

/// Nanoseconds per cycle of the first program of some sources; `start`
/// names a BOOL input set to TRUE before the first cycle.
fn vm_time_of(
    sm: stc_diagnostics::SourceMap,
    diags: Vec<stc_diagnostics::Diagnostic>,
    cycles: u64,
    start: Option<&str>,
) -> Result<f64, String> {
    let (module, _) = compile(sm, diags)?;
    let image = Arc::new(stc_vm::compile(&module).map_err(|e| e.to_string())?);
    let inst = image.model.programs.first().ok_or("no program")?.clone();
    let mut best = f64::MAX;
    for _ in 0..5 {
        let mut m = stc_vm::Machine::new(image.clone());
        if let Some(name) = start {
            let pou = &image.model.pous[inst.pou as usize];
            let v = pou
                .vars
                .iter()
                .find(|v| v.name.eq_ignore_ascii_case(name))
                .ok_or("no start input")?;
            m.write_value(inst.offset + v.offset, v.ty, &stc_values::Value::Bool(true));
        }
        let t0 = cpu_ns();
        for k in 0..cycles {
            m.run_program(&inst, k as i64 * 10_000_000, u64::MAX)
                .map_err(|f| f.to_string())?;
        }
        best = best.min((cpu_ns() - t0) / cycles as f64);
    }
    Ok(best)
}

/// Nanoseconds per cycle of a kernel on the JIT (compile time excluded).
fn jit_time(st: &Path, cycles: u64) -> Result<f64, String> {
    use stc_runtime::Engine;
    let (module, _) = compile(load(st)?, Vec::new())?;
    let mut e = stc_engine_jit::JitEngine::build(&module).map_err(|e| e.to_string())?;
    let inst = e.model().programs.first().ok_or("no program")?.clone();
    let mut best = f64::MAX;
    for _ in 0..5 {
        e.reset();
        let t0 = cpu_ns();
        for k in 0..cycles {
            e.run_program(&inst, k as i64 * 10_000_000, u64::MAX)
                .map_err(|f| f.to_string())?;
        }
        best = best.min((cpu_ns() - t0) / cycles as f64);
    }
    Ok(best)
}

/// Nanoseconds per cycle of the C version.
fn c_time(c: &Path, cycles: u64) -> Result<f64, String> {
    let exe = std::env::temp_dir().join(format!(
        "stc-bench-{}",
        c.file_stem().and_then(|s| s.to_str()).unwrap_or("k")
    ));
    let status = std::process::Command::new("gcc")
        .args(["-O2", "-o"])
        .arg(&exe)
        .arg(c)
        .status()
        .map_err(|e| format!("gcc: {e}"))?;
    if !status.success() {
        return Err("gcc failed".into());
    }
    let out = std::process::Command::new(&exe)
        .arg(cycles.to_string())
        .output()
        .map_err(|e| e.to_string())?;
    String::from_utf8_lossy(&out.stdout)
        .trim()
        .parse()
        .map_err(|_| "bad output from the C kernel".to_string())
}

/// The timing main of generated C: runs the first program `argv[1]`
/// cycles, 20 times, and prints the best nanoseconds per cycle. Like the
/// hand-written kernels' harness (`bench/kernels/harness.h`), the program's
/// state and clock carry on from one repetition to the next, so both go
/// through the same sequence of states.
const GEN_MAIN: &str = r#"
#include <stdio.h>
#include <stdlib.h>
#include <time.h>
#include "stc_meta.h"
#include "stc_rt.h"
static double now_ns(void) {
    struct timespec ts;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
    return (double)ts.tv_sec * 1e9 + (double)ts.tv_nsec;
}
int main(int argc, char **argv) {
    long cycles = argc > 1 ? atol(argv[1]) : 200;
    double best = 1e300;
    const stc_program *p = stc_n_configs > 0 ? &stc_configs[0].resources[0].programs[0] : &stc_programs[0];
    long n = 0;
    stc_init_all();
    for (int rep = 0; rep < 20; rep++) {
        double t0 = now_ns();
        for (long k = 0; k < cycles; k++, n++) {
            stc_clock = (int64_t)n * 10000000;
            stc_fault_kind = 0;
            p->body(p->data);
        }
        double dt = (now_ns() - t0) / (double)cycles;
        if (dt < best) best = dt;
    }
    printf("%.1f\n", best);
    return 0;
}
"#;

/// Nanoseconds per cycle of a kernel compiled by the C back end (gcc -O2).
fn gen_c_time(st: &Path, cycles: u64) -> Result<f64, String> {
    let stem = st.file_stem().and_then(|s| s.to_str()).unwrap_or("k");
    let dir = std::env::temp_dir().join(format!("stc-bench-gen-{stem}-{}", std::process::id()));
    let (module, sources) = compile(load(st)?, Vec::new())?;
    let locate = |sp: stc_diagnostics::Span| {
        sources
            .locate(sp.lo)
            .map(|(f, lc)| (f.name.clone(), lc.line, lc.col))
    };
    let files = stc_codegen_c::generate(&module, &locate).map_err(|e| e.to_string())?;
    std::fs::create_dir_all(&dir).map_err(|e| e.to_string())?;
    for (name, text) in files {
        std::fs::write(dir.join(name), text).map_err(|e| e.to_string())?;
    }
    std::fs::write(dir.join("bench_main.c"), GEN_MAIN).map_err(|e| e.to_string())?;
    let exe = dir.join("bench");
    let status = std::process::Command::new("gcc")
        .current_dir(&dir)
        .args(["-std=gnu99", "-O2", "-o"])
        .arg(&exe)
        .args(["program.c", "stc_rt.c", "bench_main.c", "-lm"])
        .status()
        .map_err(|e| format!("gcc: {e}"))?;
    if !status.success() {
        return Err("gcc failed on the generated C".into());
    }
    let run = std::process::Command::new(&exe)
        .arg(cycles.to_string())
        .output()
        .map_err(|e| e.to_string())?;
    let _ = std::fs::remove_dir_all(&dir);
    String::from_utf8_lossy(&run.stdout)
        .trim()
        .parse()
        .map_err(|_| "bad output from the generated C".to_string())
}

/// Runs every kernel (or only `only`) and prints the table.
pub fn run_kernels(cycles: u64, only: Option<&str>) {
    let mut sts: Vec<PathBuf> = std::fs::read_dir(kernels_dir())
        .map(|d| {
            d.flatten()
                .map(|e| e.path())
                .filter(|p| p.extension().is_some_and(|x| x == "st"))
                .collect()
        })
        .unwrap_or_default();
    sts.sort();
    if let Some(k) = only {
        sts.retain(|p| p.file_stem().is_some_and(|s| s == k));
    }
    println!(
        "{:<10} {:>14} {:>14} {:>14} {:>14} {:>8} {:>8} {:>8}",
        "kernel",
        "VM ns/cycle",
        "JIT ns/cycle",
        "gen-C ns/cyc",
        "C ns/cycle",
        "VM/C",
        "JIT/C",
        "genC/C"
    );
    for st in sts {
        let name = st
            .file_stem()
            .and_then(|s| s.to_str())
            .unwrap_or("?")
            .to_string();
        let vm = vm_time(&st, cycles);
        let jit = jit_time(&st, cycles);
        let c = c_time(&st.with_extension("c"), cycles);
        let g = gen_c_time(&st, cycles);
        match (vm, c) {
            (Ok(v), Ok(c)) => {
                let (gs, gr) = match &g {
                    Ok(g) => (format!("{g:.0}"), format!("{:.2}", g / c)),
                    Err(e) => ("-".to_string(), format!("({e})")),
                };
                let (js, jr) = match &jit {
                    Ok(j) => (format!("{j:.0}"), format!("{:.2}", j / c)),
                    Err(e) => ("-".to_string(), format!("({e})")),
                };
                println!(
                    "{name:<10} {v:>14.0} {js:>14} {gs:>14} {c:>14.0} {:>8.1} {jr:>8} {gr:>8}",
                    v / c
                )
            }
            (Ok(v), Err(e)) => println!("{name:<10} {v:>14.0} {:>14} {:>8}  ({e})", "-", "-"),
            (Err(e), _) => println!("{name:<10} failed: {e}"),
        }
    }
    if only.is_none_or(|k| k == "scan") {
        // One scan of a mid-size program: the generated 5000-line project
        // (70 function blocks with timers, CASE, loops; 50 called per scan).
        let mut sm = stc_diagnostics::SourceMap::new();
        sm.add("scan.st", stc_bench::generate(5_000));
        match vm_time_of(sm, Vec::new(), cycles, Some("start")) {
            Ok(v) => println!("{:<10} {v:>14.0} {:>14} {:>8}", "scan", "-", "-"),
            Err(e) => println!("scan       failed: {e}"),
        }
    }
}

#[cfg(test)]
mod tests {
    /// The clock every VM and JIT figure is read from advances with work.
    #[test]
    fn cpu_time_advances() {
        let t0 = super::cpu_ns();
        let mut x = 0u64;
        for i in 0..2_000_000u64 {
            x = std::hint::black_box(x.wrapping_add(i.wrapping_mul(i)));
        }
        assert!(t0 > 0.0 && super::cpu_ns() > t0, "{x}");
    }
}
