//! `stc-progen`: writes generated programs for inspection, and runs the
//! differential test over many of them (the long local run).
//!
//! ```text
//! stc-progen write DIR N [SEED] [--size small|medium|large]
//! stc-progen run N [SEED] [--size S] [--workers W] [--work DIR] [--keep] [--no-c] [--no-jit] [--stop-after P] [--circuit]
//! stc-progen print SEED [--size S]
//! ```
//!
//! Programs are those of seeds SEED, SEED+1, ... (SEED 0 by default for
//! `write`; for `run`, a seed from the clock, printed first so a run can be
//! repeated). `write` puts each program in DIR/pSEED.st with its `stc run`
//! command line in the first lines.
//!
//! `run` compiles each program's C with `STC_CFLAGS=-O0` unless
//! `STC_CFLAGS` is set: `stc_engine_c` compiles with `-O1` by default, and
//! `-O0` (which overrides it) makes the C side of a medium program about 30%
//! quicker (300 instead of 430 ms a program on a loaded 2-core machine; no
//! difference on small programs). Set `STC_CFLAGS=-O1` (or other flags) to
//! test the optimised C.
//!
//! `--circuit` generates only programs a circuit can express (no WHILE or
//! REPEAT, FOR with constant bounds, no IL) and compares `stc run
//! --backend netlist` with the VM too (with `--no-c --no-jit`: the VM and
//! the netlist only); programs the netlist still refuses are counted and
//! listed, not failures.

use std::path::PathBuf;
use std::process::ExitCode;

use stc_progen::{diff, program, Size};

const USAGE: &str = "usage:
  stc-progen write DIR N [SEED] [--size small|medium|large]
  stc-progen run N [SEED] [--size S] [--workers W] [--work DIR] [--keep] [--no-c] [--no-jit] [--stop-after P] [--circuit]
  stc-progen print SEED [--size S] [--circuit]";

fn main() -> ExitCode {
    match real_main() {
        Ok(code) => code,
        Err(e) => {
            eprintln!("stc-progen: {e}\n{USAGE}");
            ExitCode::from(2)
        }
    }
}

struct Args {
    positional: Vec<String>,
    size: Size,
    workers: usize,
    work: Option<PathBuf>,
    keep: bool,
    c: bool,
    jit: bool,
    stop_after: usize,
    circuit: bool,
}

fn parse(args: &[String]) -> Result<Args, String> {
    let mut a = Args {
        positional: Vec::new(),
        size: Size::default(),
        workers: std::thread::available_parallelism().map_or(2, |n| n.get()),
        work: None,
        keep: false,
        c: true,
        jit: true,
        stop_after: 20,
        circuit: false,
    };
    let mut it = args.iter();
    while let Some(w) = it.next() {
        let mut value = || it.next().ok_or_else(|| format!("{w} needs a value"));
        match w.as_str() {
            "--size" => {
                a.size = match value()?.as_str() {
                    "small" => Size::small(),
                    "medium" => Size::medium(),
                    "large" => Size::large(),
                    s => return Err(format!("unknown size `{s}`")),
                }
            }
            "--workers" => {
                a.workers = value()?
                    .parse()
                    .map_err(|_| "--workers needs a number".to_string())?
            }
            "--work" => a.work = Some(PathBuf::from(value()?)),
            "--stop-after" => {
                a.stop_after = value()?
                    .parse()
                    .map_err(|_| "--stop-after needs a number".to_string())?
            }
            "--keep" => a.keep = true,
            "--no-c" => a.c = false,
            "--no-jit" => a.jit = false,
            "--circuit" => a.circuit = true,
            s if s.starts_with("--") => return Err(format!("unknown option `{s}`")),
            s => a.positional.push(s.to_string()),
        }
    }
    Ok(a)
}

fn number(s: Option<&String>, what: &str) -> Result<Option<u64>, String> {
    match s {
        None => Ok(None),
        Some(s) => {
            let parsed = match s.strip_prefix("0x") {
                Some(h) => u64::from_str_radix(h, 16),
                None => s.parse(),
            };
            parsed
                .map(Some)
                .map_err(|_| format!("{what} must be a number, not `{s}`"))
        }
    }
}

fn real_main() -> Result<ExitCode, String> {
    let all: Vec<String> = std::env::args().skip(1).collect();
    let Some((cmd, rest)) = all.split_first() else {
        return Err("no command".into());
    };
    let mut a = parse(rest)?;
    if a.circuit {
        a.size = a.size.for_circuit();
    }
    if cmd == "run" && std::env::var_os("STC_CFLAGS").is_none() {
        // Before any thread starts: see the module documentation.
        std::env::set_var("STC_CFLAGS", "-O0");
    }
    match cmd.as_str() {
        "write" => {
            let dir = PathBuf::from(a.positional.first().ok_or("write needs DIR")?);
            let n = number(a.positional.get(1), "N")?.ok_or("write needs N")?;
            let seed = number(a.positional.get(2), "SEED")?.unwrap_or(0);
            std::fs::create_dir_all(&dir)
                .map_err(|e| format!("cannot create {}: {e}", dir.display()))?;
            for s in seed..seed.saturating_add(n) {
                let g = program(s, a.size.clone());
                let path = dir.join(g.file_name());
                std::fs::write(&path, &g.source)
                    .map_err(|e| format!("cannot write {}: {e}", path.display()))?;
            }
            println!("wrote {n} programs to {}", dir.display());
            Ok(ExitCode::SUCCESS)
        }
        "print" => {
            let seed = number(a.positional.first(), "SEED")?.ok_or("print needs SEED")?;
            print!("{}", program(seed, a.size).source);
            Ok(ExitCode::SUCCESS)
        }
        "run" => {
            let n = number(a.positional.first(), "N")?.ok_or("run needs N")?;
            let seed = match number(a.positional.get(1), "SEED")? {
                Some(s) => s,
                None => std::time::SystemTime::now()
                    .duration_since(std::time::UNIX_EPOCH)
                    .map_or(0, |d| d.as_secs())
                    .wrapping_mul(1_000_003),
            };
            println!("seeds {seed}..{} ({n} programs)", seed.saturating_add(n));
            let work = a
                .work
                .unwrap_or_else(|| std::env::temp_dir().join(format!("stc-progen-{seed}")));
            let seeds: Vec<u64> = (seed..seed.saturating_add(n)).collect();
            let opts = diff::Options {
                c: a.c,
                jit: a.jit,
                netlist: a.circuit,
                keep: a.keep,
                stop_after: a.stop_after,
            };
            let s = diff::run_many(&seeds, &a.size, a.workers, &work, &opts);
            println!("{}", s.text());
            if !s.problems.is_empty() || !s.errors.is_empty() {
                println!("the programs with a problem are kept in {}", work.display());
                return Ok(ExitCode::from(1));
            }
            Ok(ExitCode::SUCCESS)
        }
        other => Err(format!("unknown command `{other}`")),
    }
}
