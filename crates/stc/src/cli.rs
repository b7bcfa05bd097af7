//! Command-line parsing and the subcommands of spec/cli.md.

use std::ffi::OsString;
use std::io::Write;
use std::path::PathBuf;

use clap::{Args, Parser, Subcommand, ValueEnum};
use stc_diagnostics::Code;

use crate::driver::{self, MessageFormat, Options};
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
        /// Source files or directories (one project).
        #[arg(required = true)]
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
        #[arg(required = true)]
        files: Vec<PathBuf>,
    },
    /// Compile and execute the sources in simulated time (or real time).
    Run {
        #[command(flatten)]
        common: Common,
        #[command(flatten)]
        args: Box<crate::run::RunArgs>,
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
    /// `-W error`: treat warnings as errors.
    #[arg(short = 'W', value_enum, value_name = "error")]
    warnings: Vec<WarningLevel>,
    /// Language edition.
    #[arg(long, value_enum, default_value_t = Std::Iec3)]
    std: Std,
}

#[derive(ValueEnum, Clone, Copy, Debug)]
enum Format {
    Human,
    Json,
}

#[derive(ValueEnum, Clone, Copy, Debug)]
enum WarningLevel {
    Error,
}

#[derive(ValueEnum, Clone, Copy, Debug)]
enum Std {
    Iec2,
    Iec3,
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
    fn options(&self) -> Options {
        Options {
            format: match self.message_format {
                Format::Human => MessageFormat::Human,
                Format::Json => MessageFormat::Json,
            },
            warnings_as_errors: !self.warnings.is_empty(),
            language: stc_pipeline::Options {
                iec2: matches!(self.std, Std::Iec2),
            },
        }
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
        std::fs::write(path, bytes).map_err(|e| format!("cannot write {}: {e}", path.display()))?;
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
        Command::Run { common, args } => crate::run::run(&common.options(), *args),
        Command::Check { common, files } => {
            let opts = common.options();
            match sources::load(&files) {
                Ok((sm, diags)) => {
                    let a = stc_pipeline::analyse(sm, diags, &opts.language);
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
            files,
        } => {
            let opts = common.options();
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
                other => {
                    return usage_error(
                        format!("--emit {other:?} is not implemented yet").to_lowercase(),
                    )
                }
            };
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
