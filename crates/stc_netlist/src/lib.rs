//! The netlist back end (seed 004, docs/netlist.md): a PROGRAM of the typed
//! IR as a synchronous circuit, written as an XML document in the
//! `NOB_FLAT` dialect, read back, and simulated cycle by cycle.
//!
//! - [`translate`] turns a program into a [`Circuit`] (static single
//!   assignment per body, selectors for IF/CASE, unrolled loops, inlined
//!   functions and function blocks, registers for state) or refuses it with
//!   a diagnostic naming what a circuit cannot express ([`Refusal`]);
//! - [`xml::write`] and [`xml::read`] are the document (its schema is
//!   `netlist.xsd` beside this crate's manifest, [`XSD`]);
//! - [`Simulator`] runs a circuit one cycle at a time.
//!
//! The component library and what each component computes are in
//! [`circuit`] and [`library`]; a folded constant and a simulated component
//! are computed by the same function, which calls `stc_values`, the one
//! definition of every operator of the language.
//!
//! No I/O: text in, text out.

pub mod build;
pub mod circuit;
pub mod library;
pub mod sim;
pub mod translate;
pub mod xml;

pub use circuit::{Circuit, Component, Kind, NetId};
pub use sim::{Fault, Simulator, StepError};
pub use translate::{enable_name, limits, translate, translate_config, Refusal};

/// The XML Schema of the dialect stc writes.
pub const XSD: &str = include_str!("../netlist.xsd");

/// The PROGRAM of a module a netlist is made of: the one named `name`
/// (case-insensitive), else the only one. `Err` says why there is none to
/// choose (for the command's usage error).
pub fn choose_program(m: &stc_ir::Module, name: Option<&str>) -> Result<stc_sema::PouId, String> {
    use stc_syntax::ast::PouKind;
    let programs: Vec<stc_sema::PouId> = m
        .pous
        .iter_enumerated()
        .filter(|(_, p)| p.kind == PouKind::Program && !p.is_std)
        .map(|(i, _)| i)
        .collect();
    let spelled = |i: stc_sema::PouId| m.spelled(m.pous[i].name, m.pous[i].name_span).to_string();
    match name {
        Some(n) => programs
            .iter()
            .copied()
            .find(|&i| spelled(i).eq_ignore_ascii_case(n))
            .ok_or_else(|| format!("no PROGRAM named `{n}`")),
        None => match programs.as_slice() {
            [one] => Ok(*one),
            [] => Err("the sources have no PROGRAM".to_string()),
            many => Err(format!(
                "several PROGRAMs: choose one with --program ({})",
                many.iter()
                    .map(|&i| spelled(i))
                    .collect::<Vec<_>>()
                    .join(", ")
            )),
        },
    }
}

/// What a netlist is made of: one PROGRAM, or a CONFIGURATION (an index
/// into the module's configurations).
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
pub enum Unit {
    Program(stc_sema::PouId),
    Config(usize),
}

/// The unit `stc run` would run (spec/cli.md): the configuration named
/// `config`, else the program named `program`, else the only
/// configuration, else the only program. `Err` says why there is none to
/// choose.
pub fn choose(
    m: &stc_ir::Module,
    config: Option<&str>,
    program: Option<&str>,
) -> Result<Unit, String> {
    let spelled = |c: &stc_sema::ConfigDef| m.spelled(c.name, c.span).to_string();
    if let Some(n) = config {
        return m
            .configs
            .iter()
            .position(|c| spelled(c).eq_ignore_ascii_case(n))
            .map(Unit::Config)
            .ok_or_else(|| format!("no CONFIGURATION named `{n}`"));
    }
    if program.is_some() {
        return choose_program(m, program).map(Unit::Program);
    }
    match m.configs.len() {
        0 => choose_program(m, None).map(Unit::Program),
        1 => Ok(Unit::Config(0)),
        _ => Err(format!(
            "several CONFIGURATIONs: choose one with --config ({})",
            m.configs.iter().map(spelled).collect::<Vec<_>>().join(", ")
        )),
    }
}

/// Translates a unit (see [`translate`] and [`translate_config`]).
pub fn translate_unit(m: &stc_ir::Module, unit: Unit) -> Result<Circuit, Box<Refusal>> {
    match unit {
        Unit::Program(p) => translate(m, p),
        Unit::Config(c) => translate_config(m, c),
    }
}
