//! Command-line parsing and the subcommands of spec/cli.md.

use std::ffi::OsString;
use std::io::Write;
use std::path::PathBuf;

use clap::{Args, Parser, Subcommand, ValueEnum};
use stc_diagnostics::Code;

use crate::driver::{self, MessageFormat, Options};
use crate::manifest::{self, Manifest};
use crate::sources;

/// Exit statuses (spec/cli.md).
pub const EXIT_OK: u8 = 0;
pub const EXIT_ERRORS: u8 = 1;
pub const EXIT_USAGE: u8 = 2;
/// A bug in stc: a panic, or an internal error a phase reported (spec/cli.md:
/// status 101 is always a bug).
pub const EXIT_INTERNAL: u8 = 101;

#[derive(Parser, Debug)]
#[command(
    name = "stc",
    version,
    about = "Compiler, analyser and runtime for IEC 61131-3 Structured Text"
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand, Debug)]
enum Command {
    /// Parse and analyse the sources.
    Check {
        #[command(flatten)]
        common: Common,
        /// Source files or directories (one project) [default: the
        /// project of stc.toml].
        files: Vec<PathBuf>,
    },
    /// Compile the sources to another form.
    Build {
        #[command(flatten)]
        common: Common,
        /// What to produce.
        #[arg(long, value_enum)]
        emit: Emit,
        /// Output file or directory (text kinds go to stdout without it).
        #[arg(short = 'o', long = "output")]
        output: Option<PathBuf>,
        /// `--emit netlist`: the CONFIGURATION to make a circuit of.
        #[arg(long, value_name = "NAME", conflicts_with = "program")]
        config: Option<String>,
        /// `--emit netlist`: the PROGRAM to make a circuit of [default: the
        /// only PROGRAM].
        #[arg(long, value_name = "TYPE")]
        program: Option<String>,
        /// Source files or directories [default: the project of stc.toml].
        files: Vec<PathBuf>,
    },
    /// Compile and execute the sources in simulated time (or real time).
    Run {
        #[command(flatten)]
        common: Common,
        #[command(flatten)]
        args: Box<crate::run::RunArgs>,
    },
    /// Format source files in place (canonical layout, comments kept).
    Fmt {
        /// Change nothing: list the files that would change and exit 1 if any.
        #[arg(long)]
        check: bool,
        /// How reserved words are spelled.
        #[arg(long = "keyword-case", value_enum, default_value_t = KeywordCase::Upper)]
        keyword_case: KeywordCase,
        /// Spaces per indentation level.
        #[arg(long = "indent", default_value_t = 4)]
        indent: usize,
        #[command(flatten)]
        common: Common,
        /// Source files or directories [default: the sources and tests of
        /// the project of stc.toml].
        files: Vec<PathBuf>,
    },
    /// Run the unit tests: the PROGRAMs named TEST_* (see the README).
    Test {
        #[command(flatten)]
        common: Common,
        /// Run only the tests whose name contains this text (any case).
        #[arg(long)]
        filter: Option<String>,
        /// Also write the results as JUnit XML to this file.
        #[arg(long, value_name = "FILE")]
        junit: Option<PathBuf>,
        /// Simulated time per cycle [default: the manifest's, else the
        /// GCD of the task intervals, or 10ms].
        #[arg(long, value_name = "DURATION")]
        tick: Option<String>,
        /// Watchdog: VM instructions allowed per test per cycle.
        #[arg(long = "max-steps", value_name = "N", default_value_t = stc_runtime::DEFAULT_MAX_STEPS)]
        max_steps: u64,
        /// Source files or directories [default: the sources and tests of
        /// the project of stc.toml].
        files: Vec<PathBuf>,
    },
    /// Run the language server on stdin/stdout (for editors).
    Lsp {
        /// Language edition [default: iec3].
        #[arg(long, value_enum)]
        std: Option<Std>,
    },
    /// Create a project: stc.toml, a first program and a test.
    Init {
        /// The project's folder (created if needed).
        #[arg(default_value = ".")]
        dir: PathBuf,
        /// The project's name [default: the folder's name].
        #[arg(long)]
        name: Option<String>,
    },
    /// Explain a diagnostic code.
    Explain {
        /// A code such as E0301.
        code: String,
    },
}

#[derive(Args, Debug)]
struct Common {
    /// Diagnostics format.
    #[arg(long = "message-format", value_enum, default_value_t = Format::Human)]
    message_format: Format,
    /// `-W error`: treat warnings as errors; `-W LINT`: report a lint
    /// (its name or code) as a warning.
    #[arg(short = 'W', value_name = "error|LINT")]
    warnings: Vec<String>,
    /// `-A LINT`: do not report a lint.
    #[arg(short = 'A', value_name = "LINT")]
    allow: Vec<String>,
    /// `-D LINT`: report a lint as an error.
    #[arg(short = 'D', value_name = "LINT")]
    deny: Vec<String>,
    /// Language edition [default: the manifest's, else iec3].
    #[arg(long, value_enum)]
    std: Option<Std>,
    /// The project manifest to use [default: stc.toml in this folder or
    /// above, when no source file is given].
    #[arg(long = "manifest-path", value_name = "PATH")]
    manifest_path: Option<PathBuf>,
}

#[derive(ValueEnum, Clone, Copy, Debug)]
enum Format {
    Human,
    Json,
    Sarif,
}

#[derive(ValueEnum, Clone, Copy, Debug)]
enum Std {
    Iec2,
    Iec3,
}

#[derive(ValueEnum, Clone, Copy, Debug)]
enum KeywordCase {
    Upper,
    Lower,
    Preserve,
}

#[derive(ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
enum Emit {
    Ast,
    Ir,
    Vmasm,
    Bytecode,
    C,
    Netlist,
}

impl Common {
    /// The options, from the command line and the manifest (the command
    /// line wins).
    fn options_with(&self, manifest: Option<&Manifest>) -> Result<Options, Outcome> {
        let mut opts = Options {
            format: match self.message_format {
                Format::Human => MessageFormat::Human,
                Format::Json => MessageFormat::Json,
                Format::Sarif => MessageFormat::Sarif,
            },
            warnings_as_errors: self.warnings.iter().any(|w| w == "error"),
            language: stc_pipeline::Options {
                iec2: match (self.std, manifest) {
                    (Some(s), _) => matches!(s, Std::Iec2),
                    (None, Some(m)) => m.edition == manifest::Edition::Iec2,
                    (None, None) => false,
                },
            },
            ..Options::default()
        };
        if let Some(m) = manifest {
            opts.warnings_as_errors |= m.warnings == manifest::WarningLevel::Deny;
            for &c in &m.allow {
                opts.allowed.insert(c);
            }
            for &c in &m.deny {
                opts.denied.insert(c);
            }
            opts.lints = m.lints;
        }
        // The command line wins over the manifest, the later option over
        // the earlier (as rustc's -A/-W/-D).
        let words = [
            (&self.allow, stc_lint::Level::Allow),
            (&self.warnings, stc_lint::Level::Warn),
            (&self.deny, stc_lint::Level::Deny),
        ];
        for (list, level) in words {
            for w in list.iter().filter(|w| *w != "error") {
                match stc_lint::find(w) {
                    Some(l) => opts.lints.set(l.code, level),
                    None => {
                        return Err(usage_error(format!(
                            "unknown lint `{w}` (the lints: {})",
                            stc_lint::LINTS
                                .iter()
                                .map(|l| l.name)
                                .collect::<Vec<_>>()
                                .join(", ")
                        )))
                    }
                }
            }
        }
        Ok(opts)
    }

    /// The manifest to use: the one named by `--manifest-path`, else, when
    /// no file is given, the nearest `stc.toml`.
    fn manifest(&self, files: &[PathBuf]) -> Result<Option<Manifest>, Outcome> {
        let path = match &self.manifest_path {
            Some(p) => p.clone(),
            None if files.is_empty() => {
                let cwd = std::env::current_dir().map_err(usage_error)?;
                match manifest::find(&cwd) {
                    Some(p) => p,
                    None => {
                        return Err(usage_error(
                            "no source files given, and no stc.toml in this folder or above (`stc init` makes one)",
                        ))
                    }
                }
            }
            None => return Ok(None),
        };
        manifest::load(&path).map(Some).map_err(usage_error)
    }

    /// The files of the project and the options: the files given, else the
    /// manifest's sources (and its tests with `tests`).
    fn project(
        &self,
        files: Vec<PathBuf>,
        tests: bool,
    ) -> Result<(Vec<PathBuf>, Options, Option<Manifest>), Outcome> {
        let manifest = self.manifest(&files)?;
        let opts = self.options_with(manifest.as_ref())?;
        let files = match (&manifest, files.is_empty()) {
            (Some(m), true) => m.files(tests).map_err(usage_error)?,
            _ => files,
        };
        Ok((files, opts, manifest))
    }
}

/// Runs the command line and returns the exit status.
pub fn main(args: Vec<OsString>) -> u8 {
    let cli = match Cli::try_parse_from(args) {
        Ok(c) => c,
        Err(e) => {
            let _ = e.print();
            return if e.use_stderr() { EXIT_USAGE } else { EXIT_OK };
        }
    };
    // The language server streams on stdin/stdout itself: it must run
    // before the streams are locked for the collected outcome.
    if let Command::Lsp { std } = &cli.command {
        return crate::lsp_cmd::run(stc_pipeline::Options {
            iec2: matches!(std, Some(Std::Iec2)),
        });
    }
    let mut out = std::io::stdout().lock();
    let mut err = std::io::stderr().lock();
    let outcome = stc_pipeline::with_big_stack(move || run(cli));
    let _ = out.write_all(outcome.stdout.as_bytes());
    let _ = err.write_all(outcome.stderr.as_bytes());
    if let Err(e) = write_outputs(&outcome) {
        let _ = writeln!(err, "error: {e}");
        return EXIT_USAGE;
    }
    outcome.status
}

/// Writes the file or directory tree a command produced.
fn write_outputs(outcome: &Outcome) -> Result<(), String> {
    if let Some((path, bytes)) = &outcome.file {
        crate::output::write_file(path, bytes)?;
    }
    if let Some(tree) = &outcome.tree {
        crate::output::write_tree(&tree.0, &tree.1)?;
    }
    Ok(())
}

/// Runs a command line in-process and returns what it would print (files
/// named by `-o` are written). For tests: the same path as the command.
pub fn run_args(args: &[&str]) -> Outcome {
    match Cli::try_parse_from(args) {
        Ok(cli) => {
            let outcome = stc_pipeline::with_big_stack(move || run(cli));
            if let Err(e) = write_outputs(&outcome) {
                return usage_error(e);
            }
            outcome
        }
        Err(e) => Outcome {
            stdout: if e.use_stderr() {
                String::new()
            } else {
                e.to_string()
            },
            stderr: if e.use_stderr() {
                e.to_string()
            } else {
                String::new()
            },
            file: None,
            tree: None,
            status: if e.use_stderr() { EXIT_USAGE } else { EXIT_OK },
        },
    }
}

/// A directory to write: its path and its files (name, contents).
pub type Tree = (PathBuf, Vec<(String, String)>);

/// What a command produced: text for the two streams, maybe a file, a status.
#[derive(Default, Debug)]
pub struct Outcome {
    pub stdout: String,
    pub stderr: String,
    pub file: Option<(PathBuf, Vec<u8>)>,
    /// A directory of files (`--emit c -o DIR`), written atomically.
    pub tree: Option<Box<Tree>>,
    pub status: u8,
}

fn usage_error(msg: impl std::fmt::Display) -> Outcome {
    Outcome {
        stderr: format!("error: {msg}\n"),
        status: EXIT_USAGE,
        ..Outcome::default()
    }
}

fn run(cli: Cli) -> Outcome {
    match cli.command {
        Command::Explain { code } => explain(&code),
        Command::Fmt {
            check,
            keyword_case,
            indent,
            common,
            files,
        } => {
            let (files, diagnostics, _) = match common.project(files, true) {
                Ok(p) => p,
                Err(o) => return o,
            };
            crate::fmt_cmd::run(&crate::fmt_cmd::FmtArgs {
                files,
                check,
                format: stc_fmt::Options {
                    keyword_case: match keyword_case {
                        KeywordCase::Upper => stc_fmt::KeywordCase::Upper,
                        KeywordCase::Lower => stc_fmt::KeywordCase::Lower,
                        KeywordCase::Preserve => stc_fmt::KeywordCase::Preserve,
                    },
                    indent_width: indent,
                    iec2: diagnostics.language.iec2,
                },
                diagnostics,
            })
        }
        Command::Test {
            common,
            filter,
            junit,
            tick,
            max_steps,
            files,
        } => {
            let (files, opts, manifest) = match common.project(files, true) {
                Ok(p) => p,
                Err(o) => return o,
            };
            let tick = tick.or_else(|| manifest.and_then(|m| m.run.tick));
            crate::test_cmd::run(
                &crate::test_cmd::TestArgs {
                    files,
                    filter,
                    junit,
                    tick,
                    max_steps,
                },
                &opts,
            )
        }
        Command::Lsp { .. } => usage_error("stc lsp serves on stdin/stdout: run it as a command"),
        Command::Init { dir, name } => match manifest::init(&dir, name.as_deref()) {
            Ok(msg) => Outcome {
                stdout: msg,
                ..Outcome::default()
            },
            Err(e) => usage_error(e),
        },
        Command::Run { common, mut args } => {
            let (files, opts, manifest) =
                match common.project(std::mem::take(&mut args.files), false) {
                    Ok(p) => p,
                    Err(o) => return o,
                };
            args.files = files;
            if let Some(m) = manifest {
                args.apply_manifest(&m.run);
            }
            crate::run::run(&opts, *args)
        }
        Command::Check { common, files } => {
            let (files, opts, _) = match common.project(files, false) {
                Ok(p) => p,
                Err(o) => return o,
            };
            match sources::load(&files) {
                Ok((sm, diags)) => {
                    let a =
                        stc_pipeline::analyse_linted(sm, diags, &opts.language, Some(&opts.lints));
                    let out = finish_with(
                        &a.all_diagnostics(),
                        &a.parsed.sources,
                        &opts,
                        String::new(),
                    );
                    // The process ends right after: freeing millions of tree
                    // nodes one by one would only cost time.
                    std::mem::forget(a);
                    out
                }
                Err(e) => usage_error(e),
            }
        }
        Command::Build {
            common,
            emit,
            output,
            config,
            program,
            files,
        } => {
            let (files, opts, _) = match common.project(files, false) {
                Ok(p) => p,
                Err(o) => return o,
            };
            if emit != Emit::Netlist && (config.is_some() || program.is_some()) {
                return usage_error("--config and --program choose what --emit netlist makes");
            }
            if emit == Emit::Ast {
                let parsed = match load_and_parse(&files, &opts) {
                    Ok(p) => p,
                    Err(e) => return usage_error(e),
                };
                if driver::failed(&parsed.diagnostics, &opts) {
                    return finish(&parsed, &opts, String::new());
                }
                let text = emit_ast(&parsed);
                let mut o = finish(&parsed, &opts, String::new());
                match output {
                    Some(path) => o.file = Some((path, text.into_bytes())),
                    None => o.stdout = text,
                }
                return o;
            }
            let (sm, diags) = match sources::load(&files) {
                Ok(x) => x,
                Err(e) => return usage_error(e),
            };
            let a = stc_pipeline::analyse(sm, diags, &opts.language);
            let all = a.all_diagnostics();
            let mut o = finish_with(&all, &a.parsed.sources, &opts, String::new());
            if driver::failed(&all, &opts) {
                return o;
            }
            let (module, sources) = stc_pipeline::lower_keeping_sources(a);
            let bytes = match emit {
                Emit::Ir => stc_ir::dump::dump(&module, false).into_bytes(),
                Emit::Vmasm | Emit::Bytecode => {
                    let image = match stc_vm::compile(&module) {
                        Ok(i) => i,
                        Err(e) => {
                            let (text, status) = vm_compile_error(&e, &sources, &opts);
                            o.stderr.push_str(&text);
                            o.status = status;
                            return o;
                        }
                    };
                    if emit == Emit::Vmasm {
                        stc_vm::asm::disassemble(&image).into_bytes()
                    } else {
                        if output.is_none() {
                            return usage_error(
                                "--emit bytecode writes a binary file: give it with -o FILE.stbc",
                            );
                        }
                        stc_vm::format::encode(&image)
                    }
                }
                Emit::C => {
                    let Some(dir) = output else {
                        return usage_error("--emit c writes a directory: give it with -o DIR");
                    };
                    let locate = |sp: stc_diagnostics::Span| {
                        sources
                            .locate(sp.lo)
                            .map(|(f, lc)| (f.name.clone(), lc.line, lc.col))
                    };
                    match stc_codegen_c::generate(&module, &locate) {
                        Ok(files) => o.tree = Some(Box::new((dir, files))),
                        Err(stc_codegen_c::Error::Diagnostics(d)) => {
                            o.stderr.push_str(&driver::render(&d, &sources, &opts));
                            o.status = EXIT_ERRORS;
                        }
                        Err(e) => {
                            o.stderr.push_str(&format!("{e}\n"));
                            o.status = EXIT_ERRORS;
                        }
                    }
                    return o;
                }
                Emit::Netlist => {
                    let unit =
                        match stc_netlist::choose(&module, config.as_deref(), program.as_deref()) {
                            Ok(u) => u,
                            Err(e) => return usage_error(e),
                        };
                    match stc_netlist::translate_unit(&module, unit) {
                        Ok(circuit) => {
                            let doc = stc_netlist::xml::write(&circuit).into_bytes();
                            // The process ends right after: freeing the
                            // circuit piece by piece would only cost time.
                            std::mem::forget(circuit);
                            doc
                        }
                        Err(r) => {
                            let d = r.to_diagnostic(&sources);
                            o.stderr.push_str(&driver::render(&[d], &sources, &opts));
                            o.status = EXIT_ERRORS;
                            return o;
                        }
                    }
                }
                other => {
                    return usage_error(
                        format!("--emit {other:?} is not implemented yet").to_lowercase(),
                    )
                }
            };
            if emit == Emit::Netlist {
                // (As for `stc check`: no point freeing the tree at exit.)
                std::mem::forget(module);
            }
            match output {
                Some(path) => o.file = Some((path, bytes)),
                None => o.stdout = String::from_utf8_lossy(&bytes).into_owned(),
            }
            o
        }
    }
}

/// How a failure of the bytecode compiler is reported (the same for
/// `build` and `run`): the rendered text for stderr and the exit status.
/// Errors in the program (diagnostics, constructs the VM does not support)
/// are status 1; an internal error is a bug in stc (status 101).
pub fn vm_compile_error(
    e: &stc_vm::CompileError,
    sm: &stc_diagnostics::SourceMap,
    opts: &Options,
) -> (String, u8) {
    match e {
        stc_vm::CompileError::Diagnostics(d) => (driver::render(d, sm, opts), EXIT_ERRORS),
        stc_vm::CompileError::Unsupported(_) => (
            format!("error: cannot compile for the VM: {e}\n"),
            EXIT_ERRORS,
        ),
        stc_vm::CompileError::Internal(_) => (
            format!("error: {e} (compiling for the VM; this is a bug in stc)\n"),
            EXIT_INTERNAL,
        ),
    }
}

fn load_and_parse(
    files: &[PathBuf],
    opts: &Options,
) -> Result<stc_pipeline::Parsed, sources::LoadError> {
    let (sm, diags) = sources::load(files)?;
    Ok(stc_pipeline::parse(sm, diags, &opts.language))
}

/// Renders the diagnostics and picks the exit status.
fn finish(parsed: &stc_pipeline::Parsed, opts: &Options, stdout: String) -> Outcome {
    finish_with(&parsed.diagnostics, &parsed.sources, opts, stdout)
}

fn finish_with(
    diags: &[stc_diagnostics::Diagnostic],
    sm: &stc_diagnostics::SourceMap,
    opts: &Options,
    stdout: String,
) -> Outcome {
    Outcome {
        stdout,
        stderr: driver::render(diags, sm, opts),
        file: None,
        tree: None,
        status: if driver::failed(diags, opts) {
            EXIT_ERRORS
        } else {
            EXIT_OK
        },
    }
}

fn emit_ast(parsed: &stc_pipeline::Parsed) -> String {
    let sm = &parsed.sources;
    let several = sm.len() > 1;
    let pos = |span: stc_diagnostics::Span| match sm.locate(span.lo) {
        Some((f, lc)) if several => format!("{}:{}:{}", f.name, lc.line, lc.col),
        Some((_, lc)) => format!("{}:{}", lc.line, lc.col),
        None => "?".into(),
    };
    stc_syntax::dump::dump(&parsed.ast, &parsed.interner, Some(&pos))
}

fn explain(code: &str) -> Outcome {
    match Code::parse(code) {
        Some(c) => Outcome {
            stdout: explanation(c),
            ..Outcome::default()
        },
        None => usage_error(format!("unknown diagnostic code `{code}`")),
    }
}

/// What `stc explain` prints: the title, the explanation, then the example
/// (the wrong source and the right one, indented), if the code has one.
pub fn explanation(c: Code) -> String {
    let mut out = format!("{c}: {}\n\n{}\n", c.title(), c.explanation());
    if let Some(ex) = stc_diagnostics::example(c) {
        out.push_str("\nFor example, this is wrong:\n\n");
        indent(&mut out, ex.wrong);
        out.push_str("\nand this is right:\n\n");
        indent(&mut out, ex.right);
    }
    out
}

/// Appends `text` indented by four spaces (blank lines stay empty).
fn indent(out: &mut String, text: &str) {
    for line in text.lines() {
        if !line.is_empty() {
            out.push_str("    ");
            out.push_str(line);
        }
        out.push('\n');
    }
}
