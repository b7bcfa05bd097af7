//! Random well-typed IEC 61131-3 programs (Structured Text, with some
//! FUNCTIONs and FUNCTION_BLOCKs in Instruction List, `il.rs`), and the
//! differential test that runs each on the bytecode VM (`stc run`) and on
//! the C back end (`stc run --backend c`: the generated C compiled into a
//! shared library and loaded), both in-process, which must print
//! byte-identical reports, messages and exit statuses.
//!
//! [`program`] turns a seed into a program (types, functions, function
//! blocks, one or two programs, sometimes a configuration) with the
//! options to run it; [`diff`] runs it on both back ends and compares.
//! What the generator covers and how it keeps programs well-typed
//! and terminating is in the README, `gen.rs` and `expr.rs`.

pub mod diff;
mod expr;
mod gen;
mod il;
mod model;
mod rng;

pub use gen::{program, Generated, Size};
