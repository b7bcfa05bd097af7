//! Generated programs (issue "differential testing").
//!
//! 1. VM side: every program of a few hundred seeds passes `stc check`
//!    without an error, runs on the VM with a generous `--max-steps` and
//!    ends (its loops are bounded: no watchdog fault), printing one report
//!    per cycle; the fraction that faults at run time is small and printed.
//! 2. Differential: `STC_DIFF_PROGRAMS` programs (default 1000) run on the
//!    VM and on the C back end (`stc run --backend c`, in-process) must
//!    print byte-identical reports, stderr and exit statuses. Skipped, with
//!    a note, when no C compiler can be run.
//!
//! 3. The JIT: `STC_DIFF_JIT_PROGRAMS` small programs (default 300) and a
//!    third as many large ones run on the VM and with `stc run --backend
//!    jit` must print the same bytes (the C run of 2. compares the JIT
//!    too); the long run is `stc-progen run N --no-c`.
//!
//! 4. The netlist: `STC_DIFF_NETLIST_PROGRAMS` programs (default 150) of
//!    the generator's circuit mode (what a circuit can express) run on the
//!    VM and with `stc run --backend netlist` must print the same bytes;
//!    the long run is `stc-progen run N --circuit --no-c --no-jit`.
//!
//! `STC_DIFF_SEED` chooses the first seed of the differential run (default
//! a fixed one, so CI is reproducible); the long local run is
//! `cargo run --release -p stc_progen -- run N` (see the crate's README).

use std::path::PathBuf;

use stc_progen::diff::{self, CSide};
use stc_progen::{program, Size};

fn work(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join(name)
}

fn env_number(name: &str, default: u64) -> u64 {
    match std::env::var(name) {
        Ok(v) => v
            .trim()
            .parse()
            .unwrap_or_else(|_| panic!("{name} must be a number, not `{v}`")),
        Err(_) => default,
    }
}

#[test]
fn generated_programs_check_clean_and_end_on_the_vm() {
    let opts = diff::Options {
        c: false,
        jit: false,
        ..diff::Options::default()
    };
    let mut total = 0;
    let mut faulted = 0;
    for (size, name, count, first) in [
        (Size::small(), "small", 150u64, 0u64),
        (Size::medium(), "medium", 100, 10_000),
        (Size::large(), "large", 50, 20_000),
    ] {
        let seeds: Vec<u64> = (first..first + count).collect();
        let s = diff::run_many(&seeds, &size, 2, &work(&format!("vm-{name}")), &opts);
        eprintln!("{name}: {}", s.text());
        assert_eq!(s.programs as u64, count, "{name}: every program ran");
        assert!(s.errors.is_empty(), "{name}: {}", s.text());
        assert!(
            s.check_failed.is_empty(),
            "{name}: stc check rejected seeds {:?}\n{}",
            s.check_failed,
            s.text()
        );
        assert!(s.problems.is_empty(), "{name}: {}", s.text());
        total += s.programs;
        faulted += s.vm_faulted;
    }
    let fraction = faulted as f64 / total as f64;
    eprintln!(
        "{total} programs, {faulted} faulted at run time ({:.1}%)",
        100.0 * fraction
    );
    assert!(
        fraction < 0.2,
        "too many programs fault ({faulted} of {total}): most should run all their cycles"
    );
}

#[test]
fn generation_is_deterministic_and_varied() {
    let a = program(7, Size::default());
    let b = program(7, Size::default());
    assert_eq!(a.source, b.source);
    assert_eq!(a.run_options(), b.run_options());
    let c = program(8, Size::default());
    assert_ne!(a.source, c.source);
    // Every program watches something and runs several cycles.
    for seed in 0..50 {
        let g = program(seed, Size::small());
        assert!(!g.watch.is_empty(), "seed {seed} watches nothing");
        assert!(g.cycles >= 3, "seed {seed} runs {} cycles", g.cycles);
    }
    // Some programs have POUs in Instruction List (the informal call and
    // CAL forms too), so the differential runs cover IL.
    let il: Vec<String> = (0..100)
        .map(|seed| program(seed, Size::default()).source)
        .filter(|s| s.lines().any(|l| l.trim_start().starts_with("LD ")))
        .collect();
    assert!(il.len() > 20, "only {} of 100 programs have IL", il.len());
    assert!(il.iter().any(|s| s.contains("\n    CAL")));
    assert!(il.iter().any(|s| s.contains("\n    JMPC")));
}

#[test]
fn vm_and_c_back_end_agree_on_generated_programs() {
    let n = env_number("STC_DIFF_PROGRAMS", 1000);
    if n == 0 {
        eprintln!("note: STC_DIFF_PROGRAMS=0: differential test skipped");
        return;
    }
    let first = env_number("STC_DIFF_SEED", 1_000_000);
    let opts = diff::Options::default();
    // One program first: is the C back end there at all?
    let probe = program(first, Size::small());
    let report = diff::run_one(&probe, &work("diff-probe"), &opts).expect("the probe runs");
    match &report.c {
        CSide::Unavailable(why) => {
            eprintln!(
                "note: differential test skipped, the C side cannot run: {}",
                why.lines().next().unwrap_or("")
            );
            return;
        }
        CSide::Skipped => panic!("the probe's C side was skipped: {:?}", report.problem()),
        _ => {}
    }
    let seeds: Vec<u64> = (first..first + n).collect();
    let s = diff::run_many(&seeds, &Size::small(), 2, &work("diff"), &opts);
    eprintln!("{}", s.text());
    assert!(s.errors.is_empty(), "{}", s.text());
    assert!(s.problems.is_empty(), "{}", s.text());
    assert_eq!(s.programs as u64, n);
    assert_eq!(s.compared as u64, n, "every program compared: {}", s.text());
}

#[test]
fn vm_and_jit_agree_on_generated_programs() {
    let n = env_number("STC_DIFF_JIT_PROGRAMS", 300);
    if n == 0 {
        eprintln!("note: STC_DIFF_JIT_PROGRAMS=0: JIT differential test skipped");
        return;
    }
    let first = env_number("STC_DIFF_SEED", 1_000_000) + 500_000;
    let opts = diff::Options {
        c: false,
        ..diff::Options::default()
    };
    let seeds: Vec<u64> = (first..first + n).collect();
    for (size, name, seeds) in [
        (Size::small(), "small", &seeds[..]),
        (Size::large(), "large", &seeds[..seeds.len() / 3]),
    ] {
        let n = seeds.len() as u64;
        let s = diff::run_many(seeds, &size, 2, &work(&format!("jit-{name}")), &opts);
        eprintln!("{name}: {}", s.text());
        assert!(s.errors.is_empty(), "{}", s.text());
        assert!(s.problems.is_empty(), "{}", s.text());
        assert_eq!(
            s.jit_compared as u64,
            n,
            "every program compared: {}",
            s.text()
        );
    }
}

#[test]
fn vm_and_netlist_agree_on_circuit_programs() {
    let n = env_number("STC_DIFF_NETLIST_PROGRAMS", 150);
    if n == 0 {
        eprintln!("note: STC_DIFF_NETLIST_PROGRAMS=0: netlist differential test skipped");
        return;
    }
    let first = env_number("STC_DIFF_SEED", 1_000_000) + 800_000;
    let opts = diff::Options {
        c: false,
        jit: false,
        netlist: true,
        ..diff::Options::default()
    };
    let seeds: Vec<u64> = (first..first + n).collect();
    let s = diff::run_many(
        &seeds,
        &Size::small().for_circuit(),
        2,
        &work("netlist"),
        &opts,
    );
    eprintln!("{}", s.text());
    assert!(s.errors.is_empty(), "{}", s.text());
    assert!(s.check_failed.is_empty(), "{}", s.text());
    assert!(s.problems.is_empty(), "{}", s.text());
    // Circuit mode generates what a circuit can express: (almost) every
    // program is compared, and the few refusals are listed.
    assert!(
        s.netlist_compared as u64 * 10 >= n * 9,
        "too few programs compared with the netlist: {}",
        s.text()
    );
}
