//! The differential driver: one generated program through `stc check`,
//! `stc run` on the bytecode VM (in-process, [`stc::cli::run_args`]) and
//! the C back end (`stc build --emit c -o DIR`, `make -C DIR sim`,
//! `DIR/sim` with the same options), comparing stdout, stderr and the exit
//! status byte for byte.
//!
//! The VM's stderr starts with the warnings of compiling the source, which
//! the simulation harness (a compiled program) cannot print: they are the
//! text `stc check` prints, and are removed before comparing.
//!
//! When `make` is missing, the C side reports [`CSide::Unavailable`] and
//! only the VM-side checks run; a failing `stc build --emit c` is always a
//! [`CSide::BuildFailed`].

use std::io::Read;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

use crate::{program, Generated, Size};

/// What a command printed and its exit status.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Output {
    pub stdout: String,
    pub stderr: String,
    /// The exit status (-1: killed by a signal or by the time limit).
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
    /// `make` is missing: the reason.
    Unavailable(String),
    /// `stc build --emit c` failed on a program the analyser accepted.
    BuildFailed(Output),
    /// `make -C DIR sim` failed.
    MakeFailed(Output),
    /// The simulation harness ran.
    Ran(Output),
}

/// Everything one program gave.
#[derive(Clone, Debug)]
pub struct Report {
    pub seed: u64,
    /// Where the source (and the C tree) are.
    pub dir: PathBuf,
    pub check: Output,
    /// `None` when `stc check` found errors.
    pub vm: Option<Output>,
    pub c: CSide,
    /// The cycles run, so the reports expected (`--trace`).
    pub cycles: u64,
    /// Wall time of the VM side (check and run).
    pub vm_time: Duration,
    /// Wall time of the C side (build, make, run).
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
        match &self.c {
            CSide::Skipped | CSide::Unavailable(_) => None,
            CSide::BuildFailed(o) => Some(format!(
                "`stc build --emit c` exits {}:\n{}{}",
                o.status, o.stdout, o.stderr
            )),
            CSide::MakeFailed(o) => Some(format!(
                "`make sim` exits {}:\n{}{}",
                o.status, o.stdout, o.stderr
            )),
            CSide::Ran(c) => {
                let vm_err = self.vm_runtime_stderr().unwrap_or_default();
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
                if vm_err != c.stderr {
                    diffs.push(format!(
                        "stderr differs:\n{}",
                        first_difference(vm_err, &c.stderr)
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
    /// The `make` program.
    pub make: String,
    /// Extra arguments for `make -C DIR sim`: the environment variable
    /// `STC_DIFF_MAKE_ARGS` (split at spaces) when set, else
    /// `CFLAGS=-std=c99 -O0`: the programs are small and run briefly, so
    /// compiling fast is what counts.
    pub make_args: Vec<String>,
    /// Time limit for one run of the simulation harness.
    pub sim_timeout: Duration,
    /// Keep the directories of programs that passed too (those with a
    /// problem are always kept).
    pub keep: bool,
    /// [`run_many`] starts no new program after this many problems (a
    /// back end that fails on everything fails fast).
    pub stop_after: usize,
    /// Compile the C trees through the caching compiler driver
    /// ([`crate::cc_cache`]), unless `make_args` set `CC` already.
    pub cc_cache: Option<CcCache>,
}

/// Where the caching compiler driver is and where it keeps objects.
#[derive(Clone, Debug)]
pub struct CcCache {
    /// The `stc-progen` binary (run as `stc-progen cc ...`).
    pub wrapper: PathBuf,
    pub dir: PathBuf,
}

impl Default for Options {
    fn default() -> Options {
        Options {
            c: true,
            make: "make".into(),
            make_args: match std::env::var("STC_DIFF_MAKE_ARGS") {
                Ok(s) => s.split_whitespace().map(String::from).collect(),
                Err(_) => vec!["CFLAGS=-std=c99 -O0".to_string()],
            },
            sim_timeout: Duration::from_secs(60),
            keep: false,
            stop_after: 20,
            cc_cache: None,
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
    let check = stc(&["stc", "check", file_s]);
    let mut report = Report {
        seed: g.seed,
        dir: dir.to_path_buf(),
        check,
        vm: None,
        c: CSide::Skipped,
        cycles: g.cycles,
        vm_time: Duration::ZERO,
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

    if opts.c {
        let t1 = Instant::now();
        report.c = c_side(&file, dir, &run_opts, opts)?;
        report.c_time = t1.elapsed();
    }
    Ok(report)
}

/// Builds and runs the C simulation harness of the program in `file`.
fn c_side(file: &Path, dir: &Path, run_opts: &[String], opts: &Options) -> Result<CSide, String> {
    let cdir = dir.join("c");
    let built = stc(&[
        "stc",
        "build",
        path_str(file)?,
        "--emit",
        "c",
        "-o",
        path_str(&cdir)?,
    ]);
    if built.status != 0 {
        return Ok(CSide::BuildFailed(built));
    }
    let mut make = Command::new(&opts.make);
    make.arg("-C").arg(&cdir).arg("sim").args(&opts.make_args);
    if let Some(c) = &opts.cc_cache {
        if !opts.make_args.iter().any(|a| a.starts_with("CC=")) {
            make.arg(format!("CC={} cc", c.wrapper.display()))
                .env(crate::cc_cache::CACHE_VAR, &c.dir);
        }
    }
    let made = match run_process(make, Duration::from_secs(600)) {
        Ok(o) => o,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => {
            return Ok(CSide::Unavailable(format!("`{}` not found", opts.make)))
        }
        Err(e) => return Err(format!("cannot run {}: {e}", opts.make)),
    };
    if made.status != 0 {
        return Ok(CSide::MakeFailed(made));
    }
    let mut sim = Command::new(cdir.join("sim"));
    sim.args(run_opts);
    let ran = run_process(sim, opts.sim_timeout)
        .map_err(|e| format!("cannot run {}: {e}", cdir.join("sim").display()))?;
    Ok(CSide::Ran(ran))
}

/// Runs a process to its end or the time limit (then kills it: status -1),
/// collecting both streams.
fn run_process(mut cmd: Command, limit: Duration) -> std::io::Result<Output> {
    cmd.stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped());
    let mut child = cmd.spawn()?;
    let mut out_pipe = child.stdout.take();
    let mut err_pipe = child.stderr.take();
    // Read both pipes on threads so that neither can fill up and block.
    let out_t = std::thread::spawn(move || {
        let mut v = Vec::new();
        if let Some(p) = out_pipe.as_mut() {
            let _ = p.read_to_end(&mut v);
        }
        v
    });
    let err_t = std::thread::spawn(move || {
        let mut v = Vec::new();
        if let Some(p) = err_pipe.as_mut() {
            let _ = p.read_to_end(&mut v);
        }
        v
    });
    let start = Instant::now();
    let status = loop {
        if let Some(s) = child.try_wait()? {
            break s.code().unwrap_or(-1);
        }
        if start.elapsed() > limit {
            let _ = child.kill();
            let _ = child.wait();
            break -1;
        }
        std::thread::sleep(Duration::from_millis(2));
    };
    let stdout = out_t.join().unwrap_or_default();
    let mut stderr = err_t.join().unwrap_or_default();
    if status == -1 && start.elapsed() > limit {
        stderr.extend_from_slice(format!("(killed after {limit:?})\n").as_bytes());
    }
    Ok(Output {
        stdout: String::from_utf8_lossy(&stdout).into_owned(),
        stderr: String::from_utf8_lossy(&stderr).into_owned(),
        status,
    })
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
    /// Why the C side was not available, if it was not.
    pub c_unavailable: Option<String>,
    /// Seeds with a problem, and the problem (errors, failed builds,
    /// differences).
    pub problems: Vec<(u64, String)>,
    /// Machinery errors (cannot write a file...).
    pub errors: Vec<(u64, String)>,
    pub vm_time: Duration,
    pub c_time: Duration,
    pub wall_time: Duration,
}

impl Summary {
    /// One paragraph for humans.
    pub fn text(&self) -> String {
        let n = self.programs.max(1) as f64;
        let mut s = format!(
            "{} programs: {} rejected by stc check, {} faulted on the VM ({:.1}%), {} compared with C, {} problems, {} errors; VM {:.1} ms/program, C {:.1} ms/program, wall {:.1} s",
            self.programs,
            self.check_failed.len(),
            self.vm_faulted,
            100.0 * self.vm_faulted as f64 / n,
            self.compared,
            self.problems.len(),
            self.errors.len(),
            self.vm_time.as_secs_f64() * 1000.0 / n,
            self.c_time.as_secs_f64() * 1000.0 / n,
            self.wall_time.as_secs_f64(),
        );
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
                        s.c_time += r.c_time;
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
            c,
            cycles: 2,
            vm_time: Duration::ZERO,
            c_time: Duration::ZERO,
        }
    }

    const WARN: &str = "w.st:1:1: warning[W0101]: ...\n";

    #[test]
    fn same_outputs_pass_and_warnings_are_not_compared() {
        let vm = out("{a}\n{b}\n", WARN, 0);
        let r = report(vm, CSide::Ran(out("{a}\n{b}\n", "", 0)));
        assert_eq!(r.problem(), None);
        let vm = out(
            "{a}\n",
            &format!("{WARN}fault: division by zero in Main at w.st:3:1\n"),
            3,
        );
        let c = out("{a}\n", "fault: division by zero in Main at w.st:3:1\n", 3);
        assert_eq!(report(vm, CSide::Ran(c)).problem(), None);
    }

    #[test]
    fn differences_are_reported() {
        let vm = out("{a}\n{b}\n", WARN, 0);
        let p = report(vm.clone(), CSide::Ran(out("{a}\n{c}\n", "", 0)))
            .problem()
            .unwrap();
        assert!(p.contains("stdout differs") && p.contains("line 2"), "{p}");
        let p = report(vm.clone(), CSide::Ran(out("{a}\n{b}\n", "", 3)))
            .problem()
            .unwrap();
        assert!(p.contains("exit status: VM 0, C 3"), "{p}");
        let p = report(vm, CSide::Ran(out("{a}\n{b}\n", "x\n", 0)))
            .problem()
            .unwrap();
        assert!(p.contains("stderr differs"), "{p}");
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

    #[cfg(unix)]
    #[test]
    fn processes_are_collected_and_timed_out() {
        let mut c = Command::new("sh");
        c.args(["-c", "echo out; echo err >&2; exit 3"]);
        let o = run_process(c, Duration::from_secs(20)).unwrap();
        assert_eq!(o, out("out\n", "err\n", 3));
        let mut c = Command::new("sh");
        c.args(["-c", "exec sleep 10"]);
        let o = run_process(c, Duration::from_millis(200)).unwrap();
        assert_eq!(o.status, -1);
        assert!(o.stderr.contains("killed"), "{}", o.stderr);
    }
}
