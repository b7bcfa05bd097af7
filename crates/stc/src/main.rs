//! The `stc` command (spec/cli.md). All the work is in the library; this only
//! parses arguments and turns the outcome into an exit status.

use std::process::ExitCode;

fn main() -> ExitCode {
    ExitCode::from(stc::cli::main(std::env::args_os().collect()))
}
