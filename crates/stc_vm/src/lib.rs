//! The stc bytecode and its virtual machine.
//!
//! [`compile`] turns the IR into an [`Image`]; [`Machine`] runs it.

pub mod asm;
mod compile;
pub mod format;
pub mod image;
pub mod instr;
mod interp;
pub mod machine;
pub mod num;
pub mod verify;

pub use compile::{compile, CompileError};
pub use image::Image;
pub use machine::{range_flags, Machine, VmFault};
