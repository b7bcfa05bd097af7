//! The differential driver: one generated program through `stc check`,
//! then `stc run` on the bytecode VM, `stc run --backend jit` (native code
//! compiled in-process by Cranelift, `stc_engine_jit`) and `stc run
//! --backend c` (the C back end's output compiled by the system C compiler
//! into a shared library and loaded, `stc_engine_c`) with the same
//! options, all in-process through [`stc::cli::run_args`], comparing
//! stdout, stderr and the exit status of each with the VM's byte for byte.
//!
//! Both sides go through the same command-line path, so both print the
//! compile warnings first on stderr and their whole stderr is compared; the
//! VM's stderr must also start with the warnings `stc check` prints.
//!
//! The C side has no process and so no time limit: its loops are bounded by
//! the watchdog compiled into the C (`--max-steps`, the generator's limit),
//! as the VM's are. A crash of the generated C (a bug) would take the driver
//! down with it; the directory of the program being run is then left in the
//! work directory. The C compiler's flags are `stc_engine_c`'s
//! (`-std=c99 -O1 ...`, then `$STC_CFLAGS`); `stc-progen run` sets
//! `STC_CFLAGS=-O0` when it is unset (see `main.rs`). The C runtime object
//! is compiled once and cached by `stc_engine_c` itself.
//!
//! When no C compiler can be run, the C side reports
//! [`CSide::Unavailable`] and only the VM-side checks run.

use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

use crate::{program, Generated, Size};

/// What a command printed and its exit status.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Output {
    pub stdout: String,
    pub stderr: String,
    /// The exit status (101: `stc` panicked).
    pub status: i32,
}

impl From<stc::cli::Outcome> for Output {
    fn from(o: stc::cli::Outcome) -> Output {
        Output {
            stdout: o.stdout,
            stderr: o.stderr,
            status: i32::from(o.status),
        }
    }
}

/// The C side of one program.
#[derive(Clone, Debug)]
pub enum CSide {
    /// Not tried (the options said so, or the source has errors).
    Skipped,
    /// No C compiler can be run (`stc run --backend c` exits 2 with
    /// `error: --backend c: cannot run the C compiler ...`): the message.
    Unavailable(String),
    /// `stc run --backend c` could not set the program up although the
    /// analyser accepted it: the C back end does not translate it (exit 1,
    /// `... does not translate ...`), or the C compiler failed on the
    /// generated C or the library did not load (exit 2,
    /// `error: --backend c: ...`).
    BuildFailed(Output),
    /// The program ran on the C engine (whatever its exit status).
    Ran(Output),
}

/// Everything one program gave.
#[derive(Clone, Debug)]
pub struct Report {
    pub seed: u64,
    /// Where the source is.
    pub dir: PathBuf,
    pub check: Output,
    /// `None` when `stc check` found errors.
    pub vm: Option<Output>,
    /// The JIT's run (`None`: not tried).
    pub jit: Option<Output>,
    /// The netlist's run (`stc run --backend netlist`; `None`: not tried).
    pub netlist: Option<Output>,
    pub c: CSide,
    /// The cycles run, so the reports expected (`--trace`).
    pub cycles: u64,
    /// Wall time of the VM side (check and run).
    pub vm_time: Duration,
    /// Wall time of the JIT side (analysis, compilation, run).
    pub jit_time: Duration,
    /// Wall time of the netlist side (translation, document, simulation).
    pub netlist_time: Duration,
    /// Wall time of the C side (analysis, C generation, C compilation,
    /// run).
    pub c_time: Duration,
}

impl Report {
    /// Whether `stc check` reported errors (a generator bug, or an
    /// analyser bug).
    pub fn check_failed(&self) -> bool {
        self.check.status != 0
    }

    /// Whether the VM run stopped with a run-time fault (exit status 3).
    pub fn vm_faulted(&self) -> bool {
        self.vm.as_ref().is_some_and(|v| v.status == 3)
    }

    /// The netlist's refusal (its first diagnostic line), when the
    /// netlist back end refused the program (exit 1, `error[E11..]`).
    pub fn netlist_refusal(&self) -> Option<String> {
        let n = self.netlist.as_ref()?;
        if n.status != 1 {
            return None;
        }
        n.stderr
            .lines()
            .find(|l| l.contains("error[E11"))
            .map(|l| l.to_string())
    }

    /// The VM's stderr without the compile warnings.
    pub fn vm_runtime_stderr(&self) -> Option<&str> {
        let v = self.vm.as_ref()?;
        Some(
            v.stderr
                .strip_prefix(self.check.stderr.as_str())
                .unwrap_or(&v.stderr),
        )
    }

    /// A description of what went wrong, if anything: errors in the source,
    /// a VM status other than 0 or 3, a C side that failed to build or run,
    /// or a difference between the two back ends.
    pub fn problem(&self) -> Option<String> {
        if self.check_failed() {
            let errors: Vec<&str> = self
                .check
                .stderr
                .lines()
                .filter(|l| l.contains("error") || l.starts_with("panic"))
                .collect();
            return Some(format!(
                "`stc check` exits {}:\n{}",
                self.check.status,
                errors.join("\n")
            ));
        }
        let vm = self.vm.as_ref()?;
        if vm.status != 0 && vm.status != 3 {
            return Some(format!("`stc run` exits {}:\n{}", vm.status, vm.stderr));
        }
        if !vm.stderr.starts_with(self.check.stderr.as_str()) {
            return Some(format!(
                "the stderr of `stc run` does not start with the warnings of `stc check`:\n{}",
                first_difference(&self.check.stderr, &vm.stderr)
            ));
        }
        let reports = vm.stdout.lines().count() as u64;
        if (vm.status == 0 && reports != self.cycles) || reports > self.cycles {
            return Some(format!(
                "`stc run` printed {reports} reports for {} cycles",
                self.cycles
            ));
        }
        if let Some(l) = self
            .vm_runtime_stderr()
            .and_then(|e| e.lines().find(|l| l.starts_with("fault: watchdog")))
        {
            return Some(format!("a loop did not end: {l}"));
        }
        if let Some(j) = &self.jit {
            let mut diffs = Vec::new();
            if vm.status != j.status {
                diffs.push(format!("exit status: VM {}, JIT {}", vm.status, j.status));
            }
            if vm.stdout != j.stdout {
                diffs.push(format!(
                    "JIT stdout differs:\n{}",
                    first_difference(&vm.stdout, &j.stdout)
                ));
            }
            if vm.stderr != j.stderr {
                diffs.push(format!(
                    "JIT stderr differs:\n{}",
                    first_difference(&vm.stderr, &j.stderr)
                ));
            }
            if !diffs.is_empty() {
                return Some(diffs.join("\n"));
            }
        }
        if let Some(n) = self
            .netlist
            .as_ref()
            .filter(|_| self.netlist_refusal().is_none())
        {
            let mut diffs = Vec::new();
            if vm.status != n.status {
                diffs.push(format!(
                    "exit status: VM {}, netlist {}
{}",
                    vm.status, n.status, n.stderr
                ));
            }
            if vm.stdout != n.stdout {
                diffs.push(format!(
                    "netlist stdout differs:\n{}",
                    first_difference(&vm.stdout, &n.stdout)
                ));
            }
            if vm.stderr != n.stderr {
                diffs.push(format!(
                    "netlist stderr differs:\n{}",
                    first_difference(&vm.stderr, &n.stderr)
                ));
            }
            if !diffs.is_empty() {
                return Some(diffs.join("\n"));
            }
        }
        match &self.c {
            CSide::Skipped | CSide::Unavailable(_) => None,
            CSide::BuildFailed(o) => Some(format!(
                "`stc run --backend c` could not build the program (exit {}):\n{}{}",
                o.status,
                o.stdout,
                // Its own message, without the warnings `stc check` printed.
                o.stderr
                    .strip_prefix(self.check.stderr.as_str())
                    .unwrap_or(&o.stderr)
            )),
            CSide::Ran(c) => {
                let mut diffs = Vec::new();
                if vm.status != c.status {
                    diffs.push(format!("exit status: VM {}, C {}", vm.status, c.status));
                }
                if vm.stdout != c.stdout {
                    diffs.push(format!(
                        "stdout differs:\n{}",
                        first_difference(&vm.stdout, &c.stdout)
                    ));
                }
                if vm.stderr != c.stderr {
                    diffs.push(format!(
                        "stderr differs:\n{}",
                        first_difference(&vm.stderr, &c.stderr)
                    ));
                }
                if diffs.is_empty() {
                    None
                } else {
                    Some(diffs.join("\n"))
                }
            }
        }
    }
}

/// The first line where two texts differ, shown from both sides.
pub fn first_difference(vm: &str, c: &str) -> String {
    let (a, b): (Vec<&str>, Vec<&str>) = (vm.lines().collect(), c.lines().collect());
    for i in 0..a.len().max(b.len()) {
        let (x, y) = (a.get(i), b.get(i));
        if x != y {
            let show = |l: Option<&&str>| match l {
                Some(l) => shorten(l, 2000),
                None => "(no line)".to_string(),
            };
            return format!("  line {}:\n  VM: {}\n  C:  {}", i + 1, show(x), show(y));
        }
    }
    "  (the texts differ only in their line endings)".to_string()
}

/// At most about `max` bytes of `s`, cut at a character boundary.
fn shorten(s: &str, max: usize) -> String {
    if s.len() <= max {
        return s.to_string();
    }
    let mut i = max;
    while !s.is_char_boundary(i) {
        i -= 1;
    }
    format!("{}...", &s[..i])
}

/// How to run the differential test.
#[derive(Clone, Debug)]
pub struct Options {
    /// Try the C back end.
    pub c: bool,
    /// Try the JIT.
    pub jit: bool,
    /// Try the netlist (`--backend netlist`).
    pub netlist: bool,
    /// Keep the directories of programs that passed too (those with a
    /// problem are always kept).
    pub keep: bool,
    /// [`run_many`] starts no new program after this many problems (a
    /// back end that fails on everything fails fast).
    pub stop_after: usize,
}

impl Default for Options {
    fn default() -> Options {
        Options {
            c: true,
            jit: true,
            netlist: false,
            keep: false,
            stop_after: 20,
        }
    }
}

/// Runs an `stc` command line in-process; a panic (always a bug) becomes
/// exit status 101 with the panic's message on stderr.
pub fn stc(args: &[&str]) -> Output {
    match std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| stc::cli::run_args(args))) {
        Ok(o) => o.into(),
        Err(payload) => {
            let msg = payload
                .downcast_ref::<String>()
                .cloned()
                .or_else(|| payload.downcast_ref::<&str>().map(|s| s.to_string()))
                .unwrap_or_else(|| "(no message)".into());
            Output {
                stdout: String::new(),
                stderr: format!("panic: {msg}\n"),
                status: 101,
            }
        }
    }
}

/// Makes panics print one line (where and what) instead of the default
/// report with a backtrace: a run over a thousand programs whose compiler
/// panics on each would otherwise bury its summary. The panic message is
/// also in the [`Report`]. Installed once, for the whole process.
pub fn quiet_panics() {
    static ONCE: std::sync::Once = std::sync::Once::new();
    ONCE.call_once(|| {
        std::panic::set_hook(Box::new(|info| {
            let msg = info
                .payload()
                .downcast_ref::<String>()
                .cloned()
                .or_else(|| info.payload().downcast_ref::<&str>().map(|s| s.to_string()))
                .unwrap_or_default();
            let at = info
                .location()
                .map(|l| format!("{}:{}", l.file(), l.line()))
                .unwrap_or_default();
            eprintln!("panic at {at}: {msg}");
        }));
    });
}

fn path_str(p: &Path) -> Result<&str, String> {
    p.to_str()
        .ok_or_else(|| format!("{} is not UTF-8", p.display()))
}

/// Runs one program on both back ends in `dir` (created; its previous
/// content is removed). Errors are failures of the test machinery itself
/// (cannot write a file, cannot start a process).
pub fn run_one(g: &Generated, dir: &Path, opts: &Options) -> Result<Report, String> {
    if dir.exists() {
        std::fs::remove_dir_all(dir).map_err(|e| format!("cannot clear {}: {e}", dir.display()))?;
    }
    std::fs::create_dir_all(dir).map_err(|e| format!("cannot create {}: {e}", dir.display()))?;
    let file = dir.join(g.file_name());
    std::fs::write(&file, &g.source)
        .map_err(|e| format!("cannot write {}: {e}", file.display()))?;
    let file_s = path_str(&file)?;
    let run_opts = g.run_options();

    let t0 = Instant::now();
    // (Every lint allowed: `stc run` runs none, and its stderr must start
    // with exactly the check's warnings.)
    let mut check_args = vec!["stc", "check"];
    for l in stc_lint::LINTS {
        check_args.extend(["-A", l.name]);
    }
    check_args.push(file_s);
    let check = stc(&check_args);
    let mut report = Report {
        seed: g.seed,
        dir: dir.to_path_buf(),
        check,
        vm: None,
        jit: None,
        netlist: None,
        c: CSide::Skipped,
        cycles: g.cycles,
        vm_time: Duration::ZERO,
        jit_time: Duration::ZERO,
        netlist_time: Duration::ZERO,
        c_time: Duration::ZERO,
    };
    if report.check_failed() {
        report.vm_time = t0.elapsed();
        return Ok(report);
    }
    let mut argv = vec!["stc", "run", file_s];
    argv.extend(run_opts.iter().map(String::as_str));
    report.vm = Some(stc(&argv));
    report.vm_time = t0.elapsed();

    if opts.jit {
        let t1 = Instant::now();
        let mut jit_argv = argv.clone();
        jit_argv.extend(["--backend", "jit"]);
        report.jit = Some(stc(&jit_argv));
        report.jit_time = t1.elapsed();
    }
    if opts.netlist {
        let t1 = Instant::now();
        let mut nl_argv = argv.clone();
        nl_argv.extend(["--backend", "netlist"]);
        report.netlist = Some(stc(&nl_argv));
        report.netlist_time = t1.elapsed();
    }
    if opts.c {
        let t1 = Instant::now();
        argv.extend(["--backend", "c"]);
        report.c = c_side(stc(&argv), &report.check.stderr);
        report.c_time = t1.elapsed();
    }
    Ok(report)
}

/// Classifies the outcome of `stc run ... --backend c`; `warnings` is what
/// `stc check` printed (the C side prints it before any message of its
/// own).
fn c_side(out: Output, warnings: &str) -> CSide {
    let own = out.stderr.strip_prefix(warnings).unwrap_or(&out.stderr);
    match out.status {
        2 if own.starts_with("error: --backend c: cannot run the C compiler") => {
            CSide::Unavailable(own.trim().to_string())
        }
        2 if own.starts_with("error: --backend c:") => CSide::BuildFailed(out),
        1 if own.contains("does not translate") => CSide::BuildFailed(out),
        _ => CSide::Ran(out),
    }
}

/// The totals of a run over many programs.
#[derive(Clone, Debug, Default)]
pub struct Summary {
    pub programs: usize,
    /// Seeds whose program `stc check` rejected.
    pub check_failed: Vec<u64>,
    /// Programs whose VM run faulted (exit status 3).
    pub vm_faulted: usize,
    /// The faults of those runs, by kind (`division by zero`...), sorted.
    pub faults: Vec<(String, usize)>,
    /// Programs compared with the C side.
    pub compared: usize,
    /// Programs compared with the JIT.
    pub jit_compared: usize,
    /// Programs compared with the netlist.
    pub netlist_compared: usize,
    /// Programs the netlist refused: the seed and the diagnostic.
    pub netlist_refused: Vec<(u64, String)>,
    /// Why the C side was not available, if it was not.
    pub c_unavailable: Option<String>,
    /// Seeds with a problem, and the problem (errors, failed builds,
    /// differences).
    pub problems: Vec<(u64, String)>,
    /// Machinery errors (cannot write a file...).
    pub errors: Vec<(u64, String)>,
    pub vm_time: Duration,
    pub jit_time: Duration,
    pub netlist_time: Duration,
    pub c_time: Duration,
    pub wall_time: Duration,
}

impl Summary {
    /// One paragraph for humans.
    pub fn text(&self) -> String {
        let n = self.programs.max(1) as f64;
        let mut s = format!(
            "{} programs: {} rejected by stc check, {} faulted on the VM ({:.1}%), {} compared with the JIT, {} compared with C, {} problems, {} errors; VM {:.1} ms/program, JIT {:.1} ms/program, C {:.1} ms/program, wall {:.1} s",
            self.programs,
            self.check_failed.len(),
            self.vm_faulted,
            100.0 * self.vm_faulted as f64 / n,
            self.jit_compared,
            self.compared,
            self.problems.len(),
            self.errors.len(),
            self.vm_time.as_secs_f64() * 1000.0 / n,
            self.jit_time.as_secs_f64() * 1000.0 / n,
            self.c_time.as_secs_f64() * 1000.0 / n,
            self.wall_time.as_secs_f64(),
        );
        if self.netlist_compared > 0 || !self.netlist_refused.is_empty() {
            s.push_str(&format!(
                "\nnetlist: {} compared, {} refused, {:.1} ms/program",
                self.netlist_compared,
                self.netlist_refused.len(),
                self.netlist_time.as_secs_f64() * 1000.0 / n,
            ));
            for (seed, why) in self.netlist_refused.iter().take(5) {
                s.push_str(&format!("\n  refused seed {seed}: {why}"));
            }
        }
        if !self.faults.is_empty() {
            let f: Vec<String> = self
                .faults
                .iter()
                .map(|(k, n)| format!("{k}: {n}"))
                .collect();
            s.push_str(&format!("\nVM faults: {}", f.join(", ")));
        }
        if let Some(why) = &self.c_unavailable {
            s.push_str(&format!("\nC back end unavailable: {why}"));
        }
        for (seed, p) in self.problems.iter().take(10) {
            s.push_str(&format!("\n--- seed {seed}: {}", last_lines(p, 30)));
        }
        if self.problems.len() > 10 {
            let rest: Vec<String> = self.problems[10..]
                .iter()
                .map(|(seed, _)| seed.to_string())
                .collect();
            s.push_str(&format!("\n--- and seeds {}", rest.join(", ")));
        }
        for (seed, e) in self.errors.iter().take(10) {
            s.push_str(&format!("\n--- seed {seed}: error: {e}"));
        }
        s
    }
}

/// The first line and the last `n` lines of a long text.
fn last_lines(text: &str, n: usize) -> String {
    let lines: Vec<&str> = text.lines().collect();
    if lines.len() <= n + 1 {
        return text.to_string();
    }
    format!(
        "{}\n  [...]\n{}",
        lines[0],
        lines[lines.len() - n..].join("\n")
    )
}

/// Generates and runs the programs of `seeds` on `workers` threads, each
/// program in `work/<seed>` (removed when it passed, unless
/// `opts.keep`). The C side is tried once; when it is unavailable it is
/// not tried for the other programs. No new program starts after
/// `opts.stop_after` problems.
pub fn run_many(
    seeds: &[u64],
    size: &Size,
    workers: usize,
    work: &Path,
    opts: &Options,
) -> Summary {
    quiet_panics();
    let start = Instant::now();
    let next = AtomicUsize::new(0);
    let summary = Mutex::new(Summary::default());
    let opts_stop = opts.stop_after.max(1);
    let opts = Arc::new(Mutex::new(opts.clone()));
    std::thread::scope(|scope| {
        for _ in 0..workers.max(1) {
            scope.spawn(|| loop {
                let stop = summary
                    .lock()
                    .map(|s| s.problems.len() >= opts_stop)
                    .unwrap_or(true);
                if stop {
                    break;
                }
                let i = next.fetch_add(1, Ordering::SeqCst);
                let Some(&seed) = seeds.get(i) else {
                    break;
                };
                let g = program(seed, size.clone());
                let dir = work.join(format!("{seed}"));
                let o = opts.lock().map(|o| o.clone()).unwrap_or_default();
                let result = run_one(&g, &dir, &o);
                let mut s = match summary.lock() {
                    Ok(s) => s,
                    Err(p) => p.into_inner(),
                };
                s.programs += 1;
                match result {
                    Err(e) => s.errors.push((seed, e)),
                    Ok(r) => {
                        s.vm_time += r.vm_time;
                        s.jit_time += r.jit_time;
                        s.c_time += r.c_time;
                        if r.jit.is_some() {
                            s.jit_compared += 1;
                        }
                        s.netlist_time += r.netlist_time;
                        match r.netlist_refusal() {
                            Some(why) => s.netlist_refused.push((seed, why)),
                            None if r.netlist.is_some() && !r.check_failed() => {
                                s.netlist_compared += 1
                            }
                            None => {}
                        }
                        if r.check_failed() {
                            s.check_failed.push(seed);
                        }
                        if r.vm_faulted() {
                            s.vm_faulted += 1;
                            let kind = r
                                .vm_runtime_stderr()
                                .and_then(|e| e.lines().find_map(|l| l.strip_prefix("fault: ")))
                                .map(|l| l.split(" in ").next().unwrap_or(l).to_string())
                                .unwrap_or_else(|| "?".into());
                            match s.faults.iter_mut().find(|(k, _)| *k == kind) {
                                Some((_, n)) => *n += 1,
                                None => s.faults.push((kind, 1)),
                            }
                        }
                        match &r.c {
                            CSide::Unavailable(why) => {
                                s.c_unavailable = Some(why.clone());
                                if let Ok(mut o) = opts.lock() {
                                    o.c = false;
                                }
                            }
                            CSide::Ran(_) => s.compared += 1,
                            _ => {}
                        }
                        let problem = r.problem();
                        let passed = problem.is_none();
                        if let Some(p) = problem {
                            s.problems.push((seed, p));
                        }
                        if passed && !o.keep {
                            let _ = std::fs::remove_dir_all(&dir);
                        }
                    }
                }
            });
        }
    });
    let mut s = match summary.into_inner() {
        Ok(s) => s,
        Err(p) => p.into_inner(),
    };
    s.check_failed.sort_unstable();
    s.faults.sort_by(|a, b| b.1.cmp(&a.1).then(a.0.cmp(&b.0)));
    s.problems.sort_by_key(|(seed, _)| *seed);
    s.netlist_refused.sort_by_key(|(seed, _)| *seed);
    s.errors.sort_by_key(|(seed, _)| *seed);
    s.wall_time = start.elapsed();
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    fn out(stdout: &str, stderr: &str, status: i32) -> Output {
        Output {
            stdout: stdout.into(),
            stderr: stderr.into(),
            status,
        }
    }

    fn report(vm: Output, c: CSide) -> Report {
        Report {
            seed: 1,
            dir: PathBuf::new(),
            check: out("", "w.st:1:1: warning[W0101]: ...\n", 0),
            vm: Some(vm),
            jit: None,
            netlist: None,
            c,
            cycles: 2,
            vm_time: Duration::ZERO,
            jit_time: Duration::ZERO,
            netlist_time: Duration::ZERO,
            c_time: Duration::ZERO,
        }
    }

    const WARN: &str = "w.st:1:1: warning[W0101]: ...\n";

    #[test]
    fn same_outputs_pass_and_the_warnings_are_compared_too() {
        let vm = out("{a}\n{b}\n", WARN, 0);
        let r = report(vm.clone(), CSide::Ran(vm));
        assert_eq!(r.problem(), None);
        let err = format!("{WARN}fault: division by zero in Main at w.st:3:1\n");
        let vm = out("{a}\n", &err, 3);
        assert_eq!(report(vm.clone(), CSide::Ran(vm)).problem(), None);
        // The C side must print the warnings as well.
        let vm = out("{a}\n{b}\n", WARN, 0);
        let p = report(vm, CSide::Ran(out("{a}\n{b}\n", "", 0)))
            .problem()
            .unwrap();
        assert!(p.contains("stderr differs") && p.contains("line 1"), "{p}");
    }

    #[test]
    fn differences_are_reported() {
        let vm = out("{a}\n{b}\n", WARN, 0);
        let p = report(vm.clone(), CSide::Ran(out("{a}\n{c}\n", WARN, 0)))
            .problem()
            .unwrap();
        assert!(p.contains("stdout differs") && p.contains("line 2"), "{p}");
        let p = report(vm.clone(), CSide::Ran(out("{a}\n{b}\n", WARN, 3)))
            .problem()
            .unwrap();
        assert!(p.contains("exit status: VM 0, C 3"), "{p}");
        let p = report(
            vm.clone(),
            CSide::Ran(out("{a}\n{b}\n", &format!("{WARN}x\n"), 0)),
        )
        .problem()
        .unwrap();
        assert!(p.contains("stderr differs") && p.contains("line 2"), "{p}");
        let p = report(vm, CSide::BuildFailed(out("", "error: x\n", 2)))
            .problem()
            .unwrap();
        assert!(
            p.contains("could not build") && p.contains("error: x"),
            "{p}"
        );
    }

    #[test]
    fn the_c_side_is_classified() {
        let c = |stderr: &str, status| c_side(out("", stderr, status), WARN);
        let no_cc = format!(
            "{WARN}error: --backend c: cannot run the C compiler `nocc` (No such file); install one\n"
        );
        match c(&no_cc, 2) {
            CSide::Unavailable(why) => assert!(why.starts_with("error: --backend c: cannot run")),
            other => panic!("{other:?}"),
        }
        let cc_failed = format!(
            "{WARN}error: --backend c: `cc` failed on the generated C (exit status: 1):\n...\n"
        );
        assert!(matches!(c(&cc_failed, 2), CSide::BuildFailed(_)));
        let refused = format!("{WARN}w.st:3:1: error: the C back end does not translate x\n");
        assert!(matches!(c(&refused, 1), CSide::BuildFailed(_)));
        assert!(matches!(c(WARN, 0), CSide::Ran(_)));
        let fault = format!("{WARN}fault: division by zero in Main at w.st:3:1\n");
        assert!(matches!(c(&fault, 3), CSide::Ran(_)));
        // A panic is compared (and differs from the VM's status).
        assert!(matches!(c("panic: oops\n", 101), CSide::Ran(_)));
    }

    #[test]
    fn vm_side_problems_are_reported() {
        // A report missing: the run did not complete its cycles.
        let r = report(out("{a}\n", WARN, 0), CSide::Skipped);
        assert!(r.problem().unwrap().contains("1 reports for 2 cycles"));
        let r = report(
            out(
                "{a}\n",
                &format!("{WARN}fault: watchdog in Main at w.st:3:1\n"),
                3,
            ),
            CSide::Skipped,
        );
        assert!(r.problem().unwrap().contains("did not end"));
        let r = report(out("", "error: bad\n", 2), CSide::Skipped);
        assert!(r.problem().unwrap().contains("exits 2"));
        let r = report(out("{a}\n{b}\n", WARN, 0), CSide::Unavailable("no".into()));
        assert_eq!(r.problem(), None);
    }
}
