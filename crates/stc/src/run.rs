//! `stc run` (spec/cli.md): compile the sources (or load one `.stbc` or `.vmasm`
//! file), set the runtime up from the options, run in simulated time or in
//! real time, and print the reports.
//!
//! The runtime itself is `stc_runtime`; this file is the I/O around it:
//! reading the stimulus file, the terminal, Ctrl-C, and the exit statuses
//! (0 success, 1 errors in the sources, 2 a bad option, path, value or
//! file, 3 a run-time fault).

use std::io::Write;
use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex};

use clap::{Args, ValueEnum};
use stc_engine_c::{CEngine, Toolchain};
use stc_runtime::iomap::{default_layout, Exchange, IoMap, ProcessImage, SimInputs};
use stc_runtime::path::split_list;
use stc_runtime::realtime::{RealTime, WallClock};
use stc_runtime::timing::{Stats, Timing};
use stc_runtime::{Between, Engine};
use stc_runtime::{Format, Renderer, Report, Simulation, Stimulus, Unpaced, DEFAULT_MAX_STEPS};
use stc_vm::Machine;

use crate::cli::{Outcome, EXIT_ERRORS, EXIT_OK, EXIT_USAGE};
use crate::controller::{All, RetainFile};
use crate::driver::{self, Options};
use crate::sources;

/// A run-time fault stopped the program.
pub const EXIT_FAULT: u8 = 3;

/// The options of `stc run` (spec/cli.md), after the diagnostics options.
#[derive(Args, Debug)]
pub struct RunArgs {
    /// Source files or directories (one project), or one `.stbc` file
    /// [default: the project of stc.toml].
    pub files: Vec<PathBuf>,
    /// Run this CONFIGURATION.
    #[arg(long, value_name = "NAME", conflicts_with = "program")]
    pub config: Option<String>,
    /// Run one instance of this PROGRAM type (named after the type).
    #[arg(long, value_name = "TYPE")]
    pub program: Option<String>,
    /// Cycles (base ticks) to run [default: 1; with --realtime, until Ctrl-C].
    #[arg(long, value_name = "N")]
    pub cycles: Option<u64>,
    /// Simulated time per cycle, `10ms` or `T#10ms` [default: the GCD of
    /// the periodic task intervals, or 10ms].
    #[arg(long, value_name = "DURATION")]
    pub tick: Option<String>,
    /// Assign a variable before cycle 1; VALUE in ST literal syntax.
    #[arg(long = "set", value_name = "PATH=VALUE")]
    pub set: Vec<String>,
    /// Assign variables before given cycles: a CSV file with the header
    /// `cycle,PATH,...`.
    #[arg(long, value_name = "FILE.csv")]
    pub stimulus: Option<PathBuf>,
    /// What to report [default: the outputs of every program instance and
    /// every %Q variable].
    #[arg(long, value_name = "PATH,...")]
    pub watch: Vec<String>,
    /// Report after every cycle, not only after the last.
    #[arg(long)]
    pub trace: bool,
    /// Report format.
    #[arg(long, value_enum, default_value_t = ReportFormat::Text)]
    pub format: ReportFormat,
    /// Watchdog: VM instructions allowed per program per cycle.
    #[arg(long = "max-steps", value_name = "N", default_value_t = DEFAULT_MAX_STEPS)]
    pub max_steps: u64,
    /// Pace the cycles with the wall clock (stop with Ctrl-C).
    #[arg(long)]
    pub realtime: bool,
    /// Real time: the hardware allocation map (TOML) binding variables to
    /// Modbus registers and simulated channels.
    #[arg(long = "io-map", value_name = "FILE", requires = "realtime")]
    pub io_map: Option<PathBuf>,
    /// Real time: serve the process image over Modbus TCP (OpenPLC's
    /// layout plus the allocation map).
    #[arg(long, value_name = "HOST:PORT", requires = "realtime")]
    pub modbus: Option<String>,
    /// Real time: serve the monitor (HTTP API, WebSocket stream and web
    /// page to watch and force variables and read task statistics) on
    /// HOST:PORT (a port alone binds loopback; port 0 chooses one).
    #[arg(long, value_name = "HOST:PORT", requires = "realtime")]
    pub monitor: Option<String>,
    /// The token forcing needs [default: a random one, printed at start].
    #[arg(long = "monitor-token", value_name = "TOKEN", requires = "monitor")]
    pub monitor_token: Option<String>,
    /// Real time: keep the RETAIN variables in FILE, restored at start
    /// (warm start) and saved crash-safely at cycle ends.
    #[arg(long, value_name = "FILE", requires = "realtime")]
    pub retain: Option<PathBuf>,
    /// How often the retained variables are saved, rounded up to whole
    /// ticks [default: after every cycle].
    #[arg(long = "retain-interval", value_name = "DURATION", requires = "retain")]
    pub retain_interval: Option<String>,
    /// Cold start: do not restore the retained variables (they are still
    /// saved).
    #[arg(long, requires = "retain")]
    pub cold: bool,
    /// What runs the program: the bytecode VM, native code compiled
    /// in-process (Cranelift), or the generated C built with the system C
    /// compiler (`$CC`, else `cc`) and loaded.
    #[arg(long, value_enum, default_value_t = Backend::Vm)]
    pub backend: Backend,
}

#[derive(ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum Backend {
    Vm,
    Jit,
    C,
    Netlist,
}

#[derive(ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum ReportFormat {
    Text,
    Json,
    Csv,
}

impl RunArgs {
    /// Takes what the command line left open from the manifest's `[run]`.
    pub fn apply_manifest(&mut self, run: &crate::manifest::RunSettings) {
        if self.config.is_none() && self.program.is_none() {
            self.config = run.config.clone();
            self.program = run.program.clone();
        }
        if self.tick.is_none() {
            self.tick = run.tick.clone();
        }
        if self.cycles.is_none() {
            self.cycles = run.cycles;
        }
    }
}

fn usage_error(msg: impl std::fmt::Display) -> Outcome {
    Outcome {
        stderr: format!("error: {msg}\n"),
        status: EXIT_USAGE,
        ..Outcome::default()
    }
}

/// Runs `stc run`.
pub fn run(opts: &Options, args: RunArgs) -> Outcome {
    match load(
        &args.files,
        opts,
        args.backend,
        args.config.as_deref(),
        args.program.as_deref(),
    ) {
        Ok((engine, diagnostics)) => setup_and_run(engine, &args, diagnostics),
        Err(o) => o,
    }
}

/// The engine to run, and the rendered diagnostics (warnings) of compiling
/// the program; `Err` is the outcome to return at once.
fn load(
    files: &[PathBuf],
    opts: &Options,
    backend: Backend,
    config: Option<&str>,
    program: Option<&str>,
) -> Result<(Box<dyn Engine>, String), Outcome> {
    // Bytecode: a `.stbc` file, or its VMASM text (`--emit vmasm`), which
    // is assembled and verified like a loaded file.
    let bytecode_kind = |p: &Path| {
        p.extension().and_then(|e| {
            let e = e.to_ascii_lowercase();
            (e == "stbc" || e == "vmasm").then_some(e)
        })
    };
    if let Some(kind) = files.iter().find_map(|p| bytecode_kind(p)) {
        let [file] = files else {
            return Err(usage_error(format!(
                "a .{} file is run alone, without other files",
                kind.to_string_lossy()
            )));
        };
        let bytes = std::fs::read(file)
            .map_err(|e| usage_error(format!("cannot read {}: {e}", file.display())))?;
        if backend != Backend::Vm {
            return Err(usage_error(format!(
                "a .{} file is bytecode: it runs on the VM (--backend vm)",
                kind.to_string_lossy()
            )));
        }
        let image = if kind == "vmasm" {
            let text = String::from_utf8(bytes).map_err(|_| {
                usage_error(format!("cannot load {}: not UTF-8 text", file.display()))
            })?;
            stc_vm::asm::assemble(&text)
        } else {
            stc_vm::format::decode(&bytes)
        }
        .map_err(|e| usage_error(format!("cannot load {}: {e}", file.display())))?;
        return Ok((Box::new(Machine::new(Arc::new(image))), String::new()));
    }
    let (sm, diags) = sources::load(files).map_err(usage_error)?;
    let compiled = stc_pipeline::compile(sm, diags, &opts.language);
    let rendered = driver::render(&compiled.diagnostics, &compiled.sources, opts);
    let module = match compiled.module {
        Some(m) if !driver::failed(&compiled.diagnostics, opts) => m,
        _ => {
            return Err(Outcome {
                stderr: rendered,
                status: EXIT_ERRORS,
                ..Outcome::default()
            })
        }
    };
    let sources = compiled.sources;
    if backend == Backend::C {
        let locate = |sp: stc_diagnostics::Span| {
            sources
                .locate(sp.lo)
                .map(|(f, lc)| (f.name.clone(), lc.line, lc.col))
        };
        return match CEngine::build(&module, &locate, &Toolchain::default()) {
            Ok(engine) => Ok((Box::new(engine), rendered)),
            Err(e @ stc_engine_c::Error::Generate(_)) => Err(Outcome {
                stderr: format!("{rendered}{e}\n"),
                status: EXIT_ERRORS,
                ..Outcome::default()
            }),
            Err(e) => Err(Outcome {
                stderr: format!("{rendered}{e}\n"),
                status: EXIT_USAGE,
                ..Outcome::default()
            }),
        };
    }
    if backend == Backend::Netlist {
        return match stc_engine_netlist::NetlistEngine::build_unit(&module, config, program) {
            Ok(engine) => Ok((Box::new(engine), rendered)),
            Err(stc_engine_netlist::Error::Refused(r)) => Err(Outcome {
                stderr: format!(
                    "{rendered}{}",
                    driver::render(&[r.to_diagnostic(&sources)], &sources, opts)
                ),
                status: EXIT_ERRORS,
                ..Outcome::default()
            }),
            Err(e @ stc_engine_netlist::Error::Model(_)) => Err(Outcome {
                stderr: format!(
                    "{rendered}error: {e} (building the program model; a bug in stc)\n"
                ),
                status: crate::cli::EXIT_INTERNAL,
                ..Outcome::default()
            }),
            Err(e @ stc_engine_netlist::Error::Read(_)) => Err(Outcome {
                stderr: format!("{rendered}error: {e}\n"),
                status: crate::cli::EXIT_INTERNAL,
                ..Outcome::default()
            }),
            Err(e) => Err(usage_error(e)),
        };
    }
    let mut rendered = rendered;
    if backend == Backend::Jit {
        match stc_engine_jit::JitEngine::build(&module) {
            Ok(engine) => return Ok((Box::new(engine), rendered)),
            // Where the JIT cannot run, the VM runs the program: never a
            // failure (too large a program is reported by the VM below).
            Err(stc_engine_jit::Error::Unsupported(why)) => {
                rendered.push_str(&format!("note: --backend jit: {why}; running on the VM\n"));
            }
            Err(stc_engine_jit::Error::Diagnostics(_)) => {}
            Err(e @ stc_engine_jit::Error::Internal(_)) => {
                return Err(Outcome {
                    stderr: format!(
                        "{rendered}error: {e} (compiling for the JIT; this is a bug in stc)\n"
                    ),
                    status: crate::cli::EXIT_INTERNAL,
                    ..Outcome::default()
                })
            }
        }
    }
    match stc_vm::compile(&module) {
        Ok(image) => Ok((Box::new(Machine::new(Arc::new(image))), rendered)),
        Err(e) => {
            let (text, status) = crate::cli::vm_compile_error(&e, &sources, opts);
            Err(Outcome {
                stderr: format!("{rendered}{text}"),
                status,
                ..Outcome::default()
            })
        }
    }
}

/// Runs an engine; `diagnostics` (warnings) come first on stderr.
fn setup_and_run(image: Box<dyn Engine>, args: &RunArgs, diagnostics: String) -> Outcome {
    if args.realtime {
        // Reports stream from the first cycle on: the warnings go first.
        if let Some(mut e) = console::stderr() {
            let _ = e.write_all(diagnostics.as_bytes());
            return configure_and_run(image, args);
        }
    }
    let mut o = configure_and_run(image, args);
    o.stderr.insert_str(0, &diagnostics);
    o
}

fn configure_and_run(image: Box<dyn Engine>, args: &RunArgs) -> Outcome {
    let stimulus = match &args.stimulus {
        None => None,
        Some(path) => {
            let text = match std::fs::read(path) {
                Ok(bytes) => match String::from_utf8(bytes) {
                    Ok(t) => t,
                    Err(_) => return usage_error(format!("{} is not UTF-8 text", path.display())),
                },
                Err(e) => return usage_error(format!("cannot read {}: {e}", path.display())),
            };
            match Stimulus::parse(&path.display().to_string(), &text) {
                Ok(s) => Some(s),
                Err(e) => return usage_error(e),
            }
        }
    };
    let retain_interval = match args.retain_interval.as_deref().map(|t| {
        stc_runtime::parse_tick(t).map_err(|_| {
            format!(
                "--retain-interval {t}: expected a duration longer than zero such as 100ms or T#1s"
            )
        })
    }) {
        None => None,
        Some(Ok(ns)) => Some(ns),
        Some(Err(e)) => return usage_error(e),
    };
    let tick_ns = match args
        .tick
        .as_deref()
        .map(stc_runtime::parse_tick)
        .transpose()
    {
        Ok(t) => t,
        Err(e) => return usage_error(e),
    };
    let options = stc_runtime::Options {
        config: args.config.clone(),
        program: args.program.clone(),
        tick_ns,
        sets: args.set.clone(),
        watch: (!args.watch.is_empty())
            .then(|| args.watch.iter().flat_map(|w| split_list(w)).collect()),
        max_steps: args.max_steps,
    };
    let mut sim = match Simulation::with_engine(image, &options, stimulus.as_ref()) {
        Ok(s) => s,
        Err(e) => return usage_error(e),
    };
    let mut warnings: String = sim
        .plan()
        .warnings()
        .iter()
        .map(|w| format!("{w}\n"))
        .collect();
    if args.realtime && !warnings.is_empty() {
        // Reports stream from the first cycle on: the warnings go first.
        if let Some(mut e) = console::stderr() {
            let _ = e.write_all(warnings.as_bytes());
            warnings.clear();
        }
    }
    let cycles = match (args.cycles, args.realtime) {
        (Some(n), _) => Some(n),
        (None, false) => Some(1),
        (None, true) => None,
    };
    if let Some(n) = cycles {
        if n > sim.last_cycle() {
            return usage_error(format!(
                "--cycles {n}: with a tick of {}, cycles past {} would be later than the largest TIME",
                stc_syntax::literal::format_duration(sim.plan().tick_ns, false),
                sim.last_cycle()
            ));
        }
    }
    let format = match args.format {
        ReportFormat::Text => Format::Text,
        ReportFormat::Json => Format::Json,
        ReportFormat::Csv => Format::Csv,
    };
    if args.realtime {
        if let Some(t) = &args.monitor_token {
            if t.is_empty() || !t.bytes().all(|b| b.is_ascii_graphic()) {
                return usage_error(
                    "--monitor-token: a token is one or more printable characters without spaces",
                );
            }
        }
        let mut between = All(Vec::new());
        let stats = Arc::new(Mutex::new(Stats::new(sim.plan())));
        between.0.push(Box::new(Timing::new(
            &mut sim,
            WallClock::new(),
            Arc::clone(&stats),
        )));
        let map = match &args.io_map {
            None => None,
            Some(path) => {
                let text = match std::fs::read_to_string(path) {
                    Ok(t) => t,
                    Err(e) => return usage_error(format!("cannot read {}: {e}", path.display())),
                };
                match IoMap::parse(&path.display().to_string(), &text, &sim.scope()) {
                    Ok(m) => Some(m),
                    Err(e) => return usage_error(e),
                }
            }
        };
        let mut notes = console::stderr();
        if let Some(path) = &args.retain {
            let mut err = console::stderr();
            let warn = Box::new(move |w: String| {
                if let Some(f) = &mut err {
                    let _ = writeln!(f, "{w}");
                }
            });
            between.0.push(Box::new(RetainFile::open(
                &mut sim,
                path,
                retain_interval,
                args.cold,
                warn,
            )));
        }
        let (modbus_entries, sim_inputs, clients) = match map {
            Some(m) => (m.modbus, m.sim, m.clients),
            None => (default_layout(sim.model()), Vec::new(), Vec::new()),
        };
        if !sim_inputs.is_empty() {
            between.0.push(Box::new(SimInputs(sim_inputs)));
        }
        if let Some(addr) = &args.modbus {
            let mut image = ProcessImage::new(modbus_entries);
            image.refresh(sim.engine());
            let image = Arc::new(Mutex::new(image));
            match crate::modbus::start(addr, Arc::clone(&image)) {
                Ok(bound) => {
                    if let Some(f) = &mut notes {
                        let _ = writeln!(f, "note: modbus: listening on {bound}");
                    }
                }
                Err(e) => return usage_error(e),
            }
            between.0.push(Box::new(Exchange(image)));
        }
        if !clients.is_empty() {
            let err = Mutex::new(console::stderr());
            let warn = Arc::new(move |w: String| {
                if let Some(f) = &mut *err.lock().unwrap_or_else(|e| e.into_inner()) {
                    let _ = writeln!(f, "{w}");
                }
            });
            match crate::modbus_client::start(clients, warn) {
                Ok(c) => between.0.push(Box::new(c)),
                Err(e) => return usage_error(e),
            }
        }
        if let Some(addr) = &args.monitor {
            let (token, given) = match &args.monitor_token {
                Some(t) => (t.clone(), true),
                None => (crate::monitor::new_token(), false),
            };
            match crate::monitor::start(&sim, addr, token.clone(), Arc::clone(&stats)) {
                Ok((monitor, bound)) => {
                    if let Some(f) = &mut notes {
                        let _ = writeln!(f, "note: monitor: listening on http://{bound}/");
                        if !given {
                            let _ = writeln!(f, "note: monitor: token {token}");
                        }
                    }
                    between.0.push(Box::new(monitor));
                }
                Err(e) => return usage_error(e),
            }
        }
        let mut o = realtime(&mut sim, cycles, args.trace, format, &mut between);
        o.stderr.insert_str(0, &warnings);
        o
    } else {
        let mut stdout = String::new();
        let mut renderer = Renderer::new(format);
        let result = stc_runtime::run(&mut sim, cycles, args.trace, &mut Unpaced, &mut |r| {
            stdout.push_str(&renderer.render(r))
        });
        if let Err(f) = &result {
            stdout.push_str(&renderer.fault(f));
        }
        finish(stdout, warnings, result)
    }
}

fn finish(stdout: String, mut stderr: String, result: Result<(), stc_vm::VmFault>) -> Outcome {
    let status = match result {
        Ok(()) => EXIT_OK,
        Err(fault) => {
            stderr.push_str(&format!("{fault}\n"));
            EXIT_FAULT
        }
    };
    Outcome {
        stdout,
        stderr,
        file: None,
        tree: None,
        status,
    }
}

/// Real time: reports and warnings are written as they happen, not
/// collected.
fn realtime(
    sim: &mut Simulation,
    cycles: Option<u64>,
    trace: bool,
    format: Format,
    between: &mut dyn Between,
) -> Outcome {
    let stop = sigint::install();
    let (mut stdout, mut stderr) = (String::new(), String::new());
    let (mut out_stream, mut err_stream) = (console::stdout(), console::stderr());
    let mut warn = |w: String| match &mut err_stream {
        Some(f) => {
            let _ = writeln!(f, "{w}");
        }
        None => {
            stderr.push_str(&w);
            stderr.push('\n');
        }
    };
    let mut pacer = RealTime::new(WallClock::new(), sim.plan().tick_ns, stop, &mut warn);
    let mut renderer = Renderer::new(format);
    let mut emit = |r: &Report| match &mut out_stream {
        Some(f) => {
            let _ = f.write_all(renderer.render(r).as_bytes());
            let _ = f.flush();
        }
        None => stdout.push_str(&renderer.render(r)),
    };
    let result = stc_runtime::run_between(sim, cycles, trace, &mut pacer, &mut emit, between);
    if let Err(f) = &result {
        let tail = renderer.fault(f);
        match &mut out_stream {
            Some(out) => {
                let _ = out.write_all(tail.as_bytes());
                let _ = out.flush();
            }
            None => stdout.push_str(&tail),
        }
    }
    finish(stdout, stderr, result)
}

/// The standard streams as files of their own: `cli::main` holds the
/// locks of `std::io::stdout()` and `stderr()` while a command runs (it
/// prints the collected outcome afterwards), so a command that must print
/// as it goes writes to duplicates of the descriptors, which need no lock.
/// `None` where that is not possible: the output is then collected.
mod console {
    use std::fs::File;

    #[cfg(unix)]
    fn dup(s: impl std::os::fd::AsFd) -> Option<File> {
        s.as_fd().try_clone_to_owned().ok().map(File::from)
    }

    #[cfg(windows)]
    fn dup(s: impl std::os::windows::io::AsHandle) -> Option<File> {
        s.as_handle().try_clone_to_owned().ok().map(File::from)
    }

    #[cfg(not(any(unix, windows)))]
    fn dup<T>(_: T) -> Option<File> {
        None
    }

    pub fn stdout() -> Option<File> {
        dup(std::io::stdout())
    }

    pub fn stderr() -> Option<File> {
        dup(std::io::stderr())
    }
}

/// Ctrl-C (or SIGTERM, as a service manager stops a controller) in real
/// time: the first one stops the run after the current cycle (the last
/// report is still printed, the retained variables saved); a second one
/// ends the process at once, as an interrupted program would.
mod sigint {
    use std::sync::atomic::{AtomicBool, Ordering};

    static STOP: AtomicBool = AtomicBool::new(false);

    #[cfg(unix)]
    mod sys {
        use std::os::raw::c_int;

        pub const SIGINT: c_int = 2;
        /// 15 on every Unix stc runs on (Linux, the BSDs, macOS).
        pub const SIGTERM: c_int = 15;

        extern "C" {
            /// `signal(2)`; the handler is passed as an address, which is
            /// how C's `sighandler_t` is represented on every Unix.
            pub fn signal(signum: c_int, handler: usize) -> usize;
            /// `_exit(2)`: async-signal-safe.
            pub fn _exit(status: c_int) -> !;
        }
    }

    #[cfg(unix)]
    extern "C" fn on_sigint(_: std::os::raw::c_int) {
        // Only async-signal-safe work: an atomic swap, maybe `_exit`.
        if STOP.swap(true, Ordering::SeqCst) {
            // SAFETY: `_exit` takes no locks and may be called from a
            // signal handler; 130 is the status of a process ended by SIGINT.
            unsafe { sys::_exit(130) }
        }
    }

    /// Installs the handler (once) and returns the flag it sets.
    pub fn install() -> &'static AtomicBool {
        #[cfg(unix)]
        {
            static INSTALLED: std::sync::Once = std::sync::Once::new();
            INSTALLED.call_once(|| {
                // SAFETY: the handler is an `extern "C" fn(c_int)` that only
                // touches an atomic (and `_exit`), which is what `signal`
                // requires of a handler.
                unsafe {
                    sys::signal(sys::SIGINT, on_sigint as extern "C" fn(_) as usize);
                    sys::signal(sys::SIGTERM, on_sigint as extern "C" fn(_) as usize);
                }
            });
        }
        &STOP
    }

    #[cfg(all(test, unix))]
    mod tests {
        use super::*;

        extern "C" {
            fn raise(sig: std::os::raw::c_int) -> std::os::raw::c_int;
        }

        #[test]
        fn the_first_interrupt_sets_the_stop_flag() {
            let stop = install();
            assert!(!stop.load(Ordering::SeqCst));
            // SAFETY: raising SIGINT runs the handler installed above, on
            // this thread, before `raise` returns.
            assert_eq!(unsafe { raise(sys::SIGINT) }, 0);
            assert!(stop.load(Ordering::SeqCst));
        }
    }
}
