//! The `stc` driver: the only part of stc that touches files, the terminal
//! and the process. It loads sources into a [`stc_diagnostics::SourceMap`],
//! runs the phases ([`stc_pipeline`]), renders diagnostics and maps outcomes to the exit
//! statuses of spec/cli.md. The integration tests drive it in-process through
//! the same functions the command uses.

pub mod cli;
pub mod controller;
pub mod driver;
pub mod fmt_cmd;
pub mod lsp_cmd;
pub mod manifest;
pub mod modbus;
pub mod modbus_client;
pub mod monitor;
pub mod output;
pub mod run;
pub mod sources;
pub mod test_cmd;
