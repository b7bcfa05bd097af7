//! `stc-bench`: times the phases of stc on generated projects and prints
//! lines per second, MB per second and memory per source byte.
//!
//! Usage: `cargo run --release -p stc_bench -- [LINES...]` (default 100000).
//! Memory is measured by a counting allocator: the peak of live heap bytes
//! while a phase runs, divided by the source size.

use std::alloc::{GlobalAlloc, Layout, System};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::time::{Duration, Instant};

mod vm;

struct Counting;

static LIVE: AtomicUsize = AtomicUsize::new(0);
static PEAK: AtomicUsize = AtomicUsize::new(0);

// SAFETY: every call is forwarded unchanged to the system allocator; the
// counters are only statistics.
unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        let live = LIVE.fetch_add(layout.size(), Ordering::Relaxed) + layout.size();
        PEAK.fetch_max(live, Ordering::Relaxed);
        // SAFETY: same layout, as the caller guarantees for `alloc`.
        unsafe { System.alloc(layout) }
    }

    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        LIVE.fetch_sub(layout.size(), Ordering::Relaxed);
        // SAFETY: `ptr` was allocated by `alloc` above with this layout.
        unsafe { System.dealloc(ptr, layout) }
    }

    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        if new_size > layout.size() {
            let live = LIVE.fetch_add(new_size - layout.size(), Ordering::Relaxed) + new_size
                - layout.size();
            PEAK.fetch_max(live, Ordering::Relaxed);
        } else {
            LIVE.fetch_sub(layout.size() - new_size, Ordering::Relaxed);
        }
        // SAFETY: forwarded with the caller's guarantees for `realloc`.
        unsafe { System.realloc(ptr, layout, new_size) }
    }
}

#[global_allocator]
static ALLOC: Counting = Counting;

/// Runs `f` repeatedly for at least `budget` and returns the best time and
/// the peak heap growth of one run.
fn measure<T>(budget: Duration, mut f: impl FnMut() -> T) -> (Duration, usize) {
    let mut best = Duration::MAX;
    let mut peak = 0;
    let start = Instant::now();
    let mut runs = 0;
    while runs < 3 || start.elapsed() < budget {
        let base = LIVE.load(Ordering::Relaxed);
        PEAK.store(base, Ordering::Relaxed);
        let t = Instant::now();
        let r = f();
        let dt = t.elapsed();
        peak = peak.max(PEAK.load(Ordering::Relaxed) - base);
        drop(r);
        best = best.min(dt);
        runs += 1;
    }
    (best, peak)
}

fn report(phase: &str, lines: usize, bytes: usize, time: Duration, peak: usize) {
    let secs = time.as_secs_f64();
    println!(
        "{phase:<14} {lines:>9} lines {:>8.2} MB {:>9.2} ms {:>10.0} lines/s {:>8.1} MB/s {:>6.1} B/src-byte",
        bytes as f64 / 1e6,
        secs * 1e3,
        lines as f64 / secs,
        bytes as f64 / 1e6 / secs,
        peak as f64 / bytes as f64
    );
}

fn main() {
    // `stc-bench write FILE LINES`: write a generated project, for timing
    // whole commands (`stc check FILE`).
    let args: Vec<String> = std::env::args().collect();
    if args.get(1).map(|s| s.as_str()) == Some("write") {
        let (Some(path), Some(lines)) = (
            args.get(2),
            args.get(3).and_then(|n| n.replace('_', "").parse().ok()),
        ) else {
            eprintln!("usage: stc-bench write FILE LINES");
            std::process::exit(2);
        };
        std::fs::write(path, stc_bench::generate(lines)).expect("cannot write the file");
        return;
    }
    // `stc-bench write-circuit FILE LINES`: a project the netlist back end
    // can express (`stc build --emit netlist FILE`).
    if args.get(1).map(|s| s.as_str()) == Some("write-circuit") {
        let (Some(path), Some(lines)) = (
            args.get(2),
            args.get(3).and_then(|n| n.replace('_', "").parse().ok()),
        ) else {
            eprintln!("usage: stc-bench write-circuit FILE LINES");
            std::process::exit(2);
        };
        std::fs::write(path, stc_bench::generate_circuit(lines)).expect("cannot write the file");
        return;
    }
    // `stc-bench netlist LINES`: the phases of `--emit netlist` on a
    // generated circuit-expressible project, and the circuit's size.
    if args.get(1).map(|s| s.as_str()) == Some("netlist") {
        let lines: usize = args
            .get(2)
            .and_then(|n| n.replace('_', "").parse().ok())
            .unwrap_or(100_000);
        netlist(lines);
        return;
    }
    // `stc-bench lsp LINES`: where the time of the language server's
    // analysis after an edit goes, phase by phase (docs/benchmarks.md).
    if args.get(1).map(|s| s.as_str()) == Some("lsp") {
        let lines: usize = args
            .get(2)
            .and_then(|n| n.replace('_', "").parse().ok())
            .unwrap_or(100_000);
        lsp_phases(lines);
        return;
    }
    if args.get(1).map(|s| s.as_str()) == Some("vm") {
        let cycles: u64 = args.get(2).and_then(|n| n.parse().ok()).unwrap_or(200);
        vm::run_kernels(cycles, args.get(3).map(|s| s.as_str()));
        return;
    }
    let sizes: Vec<usize> = std::env::args()
        .skip(1)
        .filter_map(|a| a.replace('_', "").parse().ok())
        .collect();
    let sizes = if sizes.is_empty() {
        vec![100_000]
    } else {
        sizes
    };
    for lines in sizes {
        let src = generate_checked(lines);
        let n = src.lines().count();
        let bytes = src.len();
        let (t, peak) = measure(Duration::from_secs(2), || stc_syntax::lexer::lex(&src, 0));
        report("lex", n, bytes, t, peak);
        let (t, peak) = measure(Duration::from_secs(2), || {
            let mut sm = stc_diagnostics::SourceMap::new();
            sm.add("gen.st", src.clone());
            let mut interner = stc_syntax::Interner::new();
            let r = stc_syntax::parse_project(&sm, &mut interner);
            (sm, interner, r)
        });
        // The copy of the text into the source map is part of the run but
        // not of the parser's memory.
        report("lex+parse", n, bytes, t, peak.saturating_sub(bytes));
        let (t, peak) = measure(Duration::from_secs(2), || {
            let mut sm = stc_diagnostics::SourceMap::new();
            sm.add("gen.st", src.clone());
            let a = stc_pipeline::analyse(sm, Vec::new(), &stc_pipeline::Options::default());
            assert!(
                a.diagnostics().next().is_none(),
                "{:?}",
                a.diagnostics().next()
            );
            a
        });
        report("check", n, bytes, t, peak.saturating_sub(bytes));
        // The back ends from the lowered module: the bytecode compiler and
        // the JIT (Cranelift, every POU to native code).
        let module = stc_pipeline::compile_text("gen.st", &src, &stc_pipeline::Options::default())
            .module
            .expect("the generated project compiles");
        let (t, peak) = measure(Duration::from_secs(2), || {
            stc_vm::compile(&module).expect("the VM compiles it")
        });
        report("vm compile", n, bytes, t, peak);
        let (t, peak) = measure(Duration::from_secs(2), || {
            stc_engine_jit::JitEngine::build(&module)
                .map_err(|e| e.to_string())
                .expect("the JIT compiles it")
        });
        report("jit compile", n, bytes, t, peak);
    }
}

fn generate_checked(lines: usize) -> String {
    let src = stc_bench::generate(lines);
    let mut sm = stc_diagnostics::SourceMap::new();
    sm.add("gen.st", src.clone());
    let mut interner = stc_syntax::Interner::new();
    let (_, diags) = stc_syntax::parse_project(&sm, &mut interner);
    assert!(
        diags.is_empty(),
        "the generated project has diagnostics: {:?}",
        diags.first()
    );
    src
}

/// Times, for edits of a small file next to a generated project, each
/// phase of what the language server does after an edit: the incremental
/// parse of the edited file and the prelude, the analysis, the lints, the
/// lowering and layout (for E0901, when there is no error), dropping the
/// previous lowered module.
fn lsp_phases(lines: usize) {
    use stc_pipeline::incremental;
    let big = stc_bench::generate(lines);
    let ok =
        "PROGRAM Edited\n    VAR\n        x : INT;\n    END_VAR\n    x := x + 1;\nEND_PROGRAM\n";
    let bad = ok.replace("x + 1", "'text'");
    let opts = stc_pipeline::Options::default();
    stc_pipeline::with_big_stack(move || {
        let levels = stc_lint::Levels::default();
        let t = Instant::now();
        let (parsed, mark) = incremental::parse_all(
            vec![("big.st".into(), big), ("edited.st".into(), ok.to_string())],
            &opts,
        );
        let t1 = Instant::now();
        let (a, _, mut kept, made) = incremental::check(parsed, mark, &opts, Some(&levels), None);
        println!(
            "full parse of {} lines: {:.1} ms; first analysis and lints (keeping the first part): {:.1} ms ({made:?})",
            lines,
            (t1 - t).as_secs_f64() * 1e3,
            t1.elapsed().as_secs_f64() * 1e3
        );
        let mut parsed = a.parsed;
        let mut old: Option<stc_ir::Module> = None;
        let ms = |a: Instant, b: Instant| (b - a).as_secs_f64() * 1e3;
        for i in 0..9 {
            let text = if i % 2 == 0 {
                bad.clone()
            } else {
                ok.to_string()
            };
            let t0 = Instant::now();
            let p = incremental::reparse_last(parsed, mark, "edited.st".into(), text, &opts);
            let t1 = Instant::now();
            let (mut a, pending, k, made) = incremental::check(p, mark, &opts, Some(&levels), kept);
            kept = k;
            let t2 = Instant::now();
            let clean = !a.has_errors();
            stc_pipeline::lay_out(&mut a, pending);
            let t3 = Instant::now();
            drop(std::mem::replace(&mut old, a.module.take()));
            let t4 = Instant::now();
            println!(
                "edit {i} ({}): reparse {:.1} ms, analyse and lint {:.1} ms ({made:?}, {} diagnostics), lower+layout {:.1} ms, drop old module {:.1} ms, to the diagnostics {:.1} ms",
                if clean { "valid" } else { "error" },
                ms(t0, t1),
                ms(t1, t2),
                a.diagnostics.len(),
                ms(t2, t3),
                ms(t3, t4),
                ms(t0, t2)
            );
            parsed = a.parsed;
        }
    });
}

/// Times the phases of `stc build --emit netlist` once each.
fn netlist(lines: usize) {
    let src = stc_bench::generate_circuit(lines);
    let n = src.lines().count();
    let t0 = Instant::now();
    let c = stc_pipeline::compile_text("gen.st", &src, &stc_pipeline::Options::default());
    let t1 = Instant::now();
    let m = c.module.expect("the generated project has errors");
    let p = stc_netlist::choose_program(&m, None).expect("one program");
    let circuit = stc_pipeline::with_big_stack(move || stc_netlist::translate(&m, p))
        .expect("the generated project is circuit-expressible");
    let t2 = Instant::now();
    let xml = stc_netlist::xml::write(&circuit);
    let t3 = Instant::now();
    println!(
        "{n} lines: front end {:.1} ms, translate {:.1} ms, write {:.1} ms; {} components, {} nets, {} MB of XML",
        (t1 - t0).as_secs_f64() * 1e3,
        (t2 - t1).as_secs_f64() * 1e3,
        (t3 - t2).as_secs_f64() * 1e3,
        circuit.components.len(),
        circuit.nets.len(),
        xml.len() / 1_000_000
    );
    for (name, count) in circuit.census() {
        println!("  {name}: {count}");
    }
}
