//! The front end of stc: IEC 61131-3 Structured Text source to a syntax tree.
//!
//! [`lexer`] turns text into tokens (comments and pragmas kept aside as
//! trivia), [`parser`] builds the [`ast`] with error recovery, [`print`]
//! writes a tree back as ST and [`dump`] as an indented debug listing. This
//! crate does no I/O: it is given text and positions and returns data and
//! diagnostics.

pub mod ast;
pub mod dump;
pub mod intern;
pub mod lexer;
pub mod literal;
pub mod parser;
pub mod print;
pub mod real;
pub mod sfc;
pub mod token;

pub use intern::{Interner, Symbol};
pub use parser::{
    parse_file, parse_file_in, parse_project, parse_project_in, parse_source_in, FileParse,
};
