//! Source positions and diagnostics shared by every phase of stc.
//!
//! Every phase reports problems as [`Diagnostic`] values: data, never printed
//! by a library. The edge (the `stc` binary, a language server, a test) renders
//! them with [`render_human`] or [`render_json`]. Positions are [`Span`]s:
//! byte ranges in one [`SourceMap`] that holds every file of a project, so a
//! span needs no file handle and two spans compare cheaply.

mod codes;
mod diagnostic;
mod examples;
mod render;
mod sarif;
mod span;

pub use codes::{Code, CodeSeverity};
pub use diagnostic::{Diagnostic, Label, Severity};
pub use examples::{example, Example};
pub use render::{render_human, render_json};
pub use sarif::render_sarif;
pub use span::{FileId, LineCol, SourceFile, SourceMap, Span};
