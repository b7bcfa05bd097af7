//! The cycle-by-cycle simulator of a circuit: each [`Simulator::step`]
//! evaluates every component once, in the circuit's order (sources and
//! registers first, every other component after its inputs' drivers), with
//! [`crate::circuit::eval`]; then, unless a fault module fires, every
//! register takes the value at its input. What a register or an input holds
//! is the state between cycles, readable and writable by name (the
//! runtime's `--set` and `--stimulus` write it).

use rustc_hash::FxHashMap;
use stc_ir::FaultKind;
use stc_values::{ElemType, Value};

use crate::circuit::{default_of, eval, Circuit, Kind};

/// A run-time fault of the program, as its fault module says.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Fault {
    pub kind: FaultKind,
    /// The instance path (`Main`, `Main.tmr`), the POU, and where.
    pub instance: String,
    pub pou: String,
    pub file: String,
    pub line: u32,
    pub col: u32,
    /// For a range check (an index, a subrange): the value and the bounds.
    /// (Boxed: a fault is rare and the error stays small.)
    pub range: Option<Box<(i128, i128, i128)>>,
}

#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum StepError {
    #[error("fault: {} in {} ({}) at {}:{}:{}", .0.kind.text(), .0.instance, .0.pou, .0.file, .0.line, .0.col)]
    Fault(Fault),
    /// A component faulted that has no fault output: the circuit is not
    /// one stc wrote (or stc has a bug).
    #[error("component {0} faulted but has no fault output")]
    Unchecked(usize),
}

pub struct Simulator {
    c: Circuit,
    values: Vec<Value>,
    /// The state of each input and register component (by component).
    state: Vec<Option<Value>>,
    names: FxHashMap<String, usize>,
    cycles: u64,
}

impl Simulator {
    pub fn new(c: Circuit) -> Simulator {
        let values = c.nets.iter().map(|t| default_of(*t)).collect();
        let mut names = FxHashMap::default();
        let mut state = vec![None; c.components.len()];
        for (i, comp) in c.components.iter().enumerate() {
            match &comp.kind {
                Kind::Input {
                    name,
                    init,
                    aliases,
                }
                | Kind::Register {
                    name,
                    init,
                    aliases,
                } => {
                    state[i] = Some(init.clone());
                    names.insert(name.to_ascii_lowercase(), i);
                    for a in aliases {
                        names.insert(a.to_ascii_lowercase(), i);
                    }
                }
                _ => {}
            }
        }
        Simulator {
            c,
            values,
            state,
            names,
            cycles: 0,
        }
    }

    pub fn circuit(&self) -> &Circuit {
        &self.c
    }

    /// Completed cycles.
    pub fn cycles(&self) -> u64 {
        self.cycles
    }

    /// The value an input or register holds (case-insensitive name: a
    /// run-time path such as `Main.tmr.ET`).
    pub fn get(&self, name: &str) -> Option<&Value> {
        let i = *self.names.get(&name.to_ascii_lowercase())?;
        self.state[i].as_ref()
    }

    /// The type of an input or register.
    pub fn type_of(&self, name: &str) -> Option<ElemType> {
        let i = *self.names.get(&name.to_ascii_lowercase())?;
        self.c.components[i]
            .outputs
            .first()
            .map(|n| self.c.nets[n.index()])
    }

    /// Sets what an input or register holds; `false` when there is none of
    /// that name.
    pub fn set(&mut self, name: &str, v: Value) -> bool {
        match self.names.get(&name.to_ascii_lowercase()) {
            Some(&i) => {
                self.state[i] = Some(v);
                true
            }
            None => false,
        }
    }

    /// The names of the inputs and registers, in circuit order.
    pub fn names(&self) -> Vec<&str> {
        self.c
            .components
            .iter()
            .filter_map(|c| match &c.kind {
                Kind::Input { name, .. } | Kind::Register { name, .. } => Some(name.as_str()),
                _ => None,
            })
            .collect()
    }

    /// One cycle at time `now` (nanoseconds of the task clock), after
    /// setting `inputs`: returns the output modules' values, or the first
    /// fault (then no register changes: the state is the last completed
    /// cycle's).
    pub fn step(
        &mut self,
        inputs: &[(&str, Value)],
        now: i128,
    ) -> Result<Vec<(String, Value)>, StepError> {
        for (n, v) in inputs {
            self.set(n, v.clone());
        }
        let mut tys: Vec<ElemType> = Vec::with_capacity(8);
        let mut ins: Vec<Value> = Vec::with_capacity(8);
        for (i, comp) in self.c.components.iter().enumerate() {
            let out = comp.outputs.first().copied();
            match &comp.kind {
                Kind::Input { .. } | Kind::Register { .. } => {
                    if let (Some(o), Some(v)) = (out, &self.state[i]) {
                        self.values[o.index()] = v.clone();
                    }
                }
                Kind::Const(v) => {
                    if let Some(o) = out {
                        self.values[o.index()] = v.clone();
                    }
                }
                Kind::Clock => {
                    if let Some(o) = out {
                        self.values[o.index()] = Value::Int(now);
                    }
                }
                Kind::Output { .. } | Kind::Fault { .. } => {}
                kind => {
                    let Some(o) = out else { continue };
                    tys.clear();
                    ins.clear();
                    for n in &comp.inputs {
                        tys.push(self.c.nets[n.index()]);
                        ins.push(self.values[n.index()].clone());
                    }
                    let (v, fault) = eval(kind, &tys, &ins, self.c.nets[o.index()]);
                    self.values[o.index()] = v;
                    match (comp.outputs.get(1), fault) {
                        (Some(f), k) => {
                            self.values[f.index()] =
                                Value::Int(k.map(|k| k.code() as i128).unwrap_or(0));
                        }
                        (None, Some(_)) => return Err(StepError::Unchecked(i)),
                        (None, None) => {}
                    }
                }
            }
        }
        // The first fault module that fires, in order, is the fault.
        for comp in &self.c.components {
            if let Kind::Fault {
                instance,
                pou,
                file,
                line,
                col,
            } = &comp.kind
            {
                let code = self.values[comp.inputs[0].index()].as_int().unwrap_or(0);
                let on = matches!(self.values[comp.inputs[1].index()], Value::Bool(true));
                if on && code != 0 {
                    let kind = u32::try_from(code)
                        .ok()
                        .and_then(FaultKind::from_code)
                        .unwrap_or(FaultKind::InvalidCode);
                    // The component whose fault output this is.
                    let range = self.c.components.iter().find_map(|d| match &d.kind {
                        Kind::Range { lo, hi, .. } if d.outputs.get(1) == Some(&comp.inputs[0]) => {
                            let v = self.values[d.inputs.first()?.index()].as_int()?;
                            Some(Box::new((v, *lo, *hi)))
                        }
                        _ => None,
                    });
                    return Err(StepError::Fault(Fault {
                        kind,
                        instance: instance.clone(),
                        pou: pou.clone(),
                        file: file.clone(),
                        line: *line,
                        col: *col,
                        range,
                    }));
                }
            }
        }
        let mut outputs = Vec::new();
        for (i, comp) in self.c.components.iter().enumerate() {
            match &comp.kind {
                Kind::Register { .. } => {
                    self.state[i] = Some(self.values[comp.inputs[0].index()].clone());
                }
                Kind::Output { name } => {
                    outputs.push((name.clone(), self.values[comp.inputs[0].index()].clone()));
                }
                _ => {}
            }
        }
        self.cycles += 1;
        Ok(outputs)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::build::Builder;
    use stc_values::BinOp;

    /// A counter: a register fed by itself plus the input, and a division
    /// by the input whose fault module is always enabled.
    fn counter() -> Circuit {
        let mut b = Builder::new("C".into());
        let step = b.add(
            Kind::Input {
                name: "C.step".into(),
                init: Value::Int(1),
                aliases: vec![],
            },
            &[],
            Some(ElemType::Dint),
        );
        let q = b.add(
            Kind::Register {
                name: "C.n".into(),
                init: Value::Int(0),
                aliases: vec![],
            },
            &[],
            Some(ElemType::Dint),
        );
        let reg = b.components() - 1;
        let (d, _) = b.op(Kind::Binary(BinOp::Add), &[q, step], ElemType::Dint);
        b.c.components[reg].inputs = crate::circuit::Pins::from_slice(&[d]);
        let (_, f) = b.op(Kind::Binary(BinOp::Div), &[q, step], ElemType::Dint);
        let on = b.bool(true);
        b.add(
            Kind::Fault {
                instance: "C".into(),
                pou: "C".into(),
                file: "c.st".into(),
                line: 3,
                col: 1,
            },
            &[f.unwrap(), on],
            None,
        );
        b.add(Kind::Output { name: "C.n".into() }, &[d], None);
        b.finish()
    }

    #[test]
    fn registers_carry_state_and_a_fault_keeps_the_last_cycle() {
        let mut sim = Simulator::new(counter());
        assert_eq!(
            sim.step(&[], 0).unwrap(),
            vec![("C.n".to_string(), Value::Int(1))]
        );
        assert_eq!(
            sim.step(&[("c.STEP", Value::Int(5))], 0).unwrap()[0].1,
            Value::Int(6)
        );
        assert_eq!(sim.get("C.n"), Some(&Value::Int(6)));
        let err = sim.step(&[("C.step", Value::Int(0))], 0).unwrap_err();
        let StepError::Fault(f) = err else {
            panic!("{err:?}")
        };
        assert_eq!((f.kind, f.line), (FaultKind::DivisionByZero, 3));
        assert_eq!(sim.get("C.n"), Some(&Value::Int(6)));
        assert_eq!(sim.cycles(), 2);
    }
}
