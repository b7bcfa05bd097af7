//! The errors of setting up a run: everything here is a mistake in the
//! command line or its input files (`stc run` exits with status 2), never a
//! fault of the running program (that is a [`stc_vm::VmFault`]).

use thiserror::Error;

#[derive(Clone, Debug, PartialEq, Eq, Error)]
pub enum Error {
    /// Nothing, or more than one thing, could run; the message lists the
    /// candidates.
    #[error("{0}")]
    Selection(String),
    /// A variable path that does not parse or names nothing.
    #[error("{0}")]
    Path(String),
    /// A value that cannot be read as the variable's type.
    #[error("{0}")]
    Value(String),
    /// A malformed stimulus file: its name, the 1-based line, the problem.
    #[error("{file}:{line}: {message}")]
    Stimulus {
        file: String,
        line: usize,
        message: String,
    },
    /// A mistake in the allocation map (`--io-map`): its name, the 1-based
    /// line, the problem.
    #[error("{file}:{line}: {message}")]
    Map {
        file: String,
        line: usize,
        message: String,
    },
    /// Any other bad option (`--tick`, `--set` syntax, `--cycles`).
    #[error("{0}")]
    Option(String),
}

pub type Result<T, E = Error> = std::result::Result<T, E>;
