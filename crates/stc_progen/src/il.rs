//! Instruction List bodies: FUNCTIONs and FUNCTION_BLOCKs written in IL,
//! so the differential run covers IL and the calls between the languages.
//!
//! An IL POU works on elementary variables of the types in [`IL_TYPES`]
//! (BOOL, integers, reals); it calls the functions and instances of the
//! function blocks generated before it, in ST or IL, and is registered like
//! an ST one, so what comes after (ST or IL) calls it. Every instruction
//! sequence keeps the current result typed (docs/il.md):
//! - a value starts with a load (or a function call whose first input is
//!   such a value) and goes on with operators whose operand has the
//!   current result's type; comparisons turn it into a BOOL;
//! - operands are variables or typed literals (`INT#5`), never negative,
//!   divisors are literals from 1 up, so nothing faults;
//! - jumps go forward over a block, or back to the head of a loop bounded
//!   by a hidden counter; the code after a label always loads first.

use stc_values::ElemType as E;

use crate::gen::Gen;
use crate::model::{class, Class, Fb, PouSig, Sect, Ty, Var};

/// The elementary types of IL variables, with how often each is picked.
const IL_TYPES: &[(E, u64)] = &[
    (E::Bool, 6),
    (E::Sint, 1),
    (E::Int, 4),
    (E::Dint, 4),
    (E::Lint, 1),
    (E::Usint, 1),
    (E::Uint, 1),
    (E::Udint, 2),
    (E::Real, 2),
    (E::Lreal, 2),
];

fn il_type(t: &Ty) -> Option<E> {
    match t {
        Ty::E(e) if IL_TYPES.iter().any(|(x, _)| x == e) => Some(*e),
        _ => None,
    }
}

/// A variable an IL body reads (and writes, if `writable`).
struct IlVar {
    name: String,
    ty: E,
    writable: bool,
}

/// The body being generated.
struct Il {
    vars: Vec<IlVar>,
    lines: Vec<String>,
    /// Functions 0..funcs may be called.
    funcs: usize,
    /// Instances of generated function blocks: name and type index.
    fbs: Vec<(String, usize)>,
    next_label: usize,
    /// Loop counters, declared in VAR after the others.
    counters: Vec<String>,
    /// How deep values are nested (parenthesised sequences, calls).
    depth: u32,
}

impl Il {
    fn emit(&mut self, s: String) {
        self.lines.push(format!("    {s}"));
    }

    fn label(&mut self) -> String {
        self.next_label += 1;
        format!("L{}", self.next_label)
    }
}

impl Gen {
    fn il_elem(&mut self) -> E {
        let w: Vec<u64> = IL_TYPES.iter().map(|(_, w)| *w).collect();
        IL_TYPES[self.rng.weighted(&w)].0
    }

    /// A typed literal of `e` that never faults as a divisor (from 1 up).
    fn il_lit(&mut self, e: E) -> String {
        match class(e) {
            Class::Bool => if self.rng.chance(50) { "TRUE" } else { "FALSE" }.into(),
            Class::Real => {
                let v = *self
                    .rng
                    .pick(&["0.5", "1.0", "1.5", "2.0", "0.25", "3.0", "10.0"]);
                format!("{}#{v}", e.name())
            }
            _ => {
                let v = if self.rng.chance(80) {
                    self.rng.range(1, 9)
                } else {
                    self.rng.range(10, 100)
                };
                format!("{}#{v}", e.name())
            }
        }
    }

    /// A variable of type `e` (or a literal).
    fn il_operand(&mut self, b: &Il, e: E) -> String {
        let vars: Vec<&IlVar> = b.vars.iter().filter(|v| v.ty == e).collect();
        if !vars.is_empty() && self.rng.chance(65) {
            return self.rng.pick(&vars).name.clone();
        }
        self.il_lit(e)
    }

    /// The functions that can be called from IL: every input and the
    /// result of an IL type, no in-outs.
    fn il_callable(&self, b: &Il, ret: E) -> Vec<usize> {
        (0..b.funcs)
            .filter(|&k| {
                let f = &self.funcs[k];
                f.inouts.is_empty()
                    && !f.inputs.is_empty()
                    && f.ret.as_ref().and_then(il_type) == Some(ret)
                    && f.inputs.iter().all(|(_, t)| il_type(t).is_some())
            })
            .collect()
    }

    /// Instructions that leave a value of type `e` in the current result.
    fn il_value(&mut self, b: &mut Il, e: E) {
        b.depth += 1;
        let calls = self.il_callable(b, e);
        if !calls.is_empty() && b.depth < 3 && self.rng.chance(20) {
            let f = self.funcs[*self.rng.pick(&calls)].clone();
            if self.rng.chance(50) {
                // Informal: the current result is the first input.
                let first = il_type(&f.inputs[0].1).unwrap_or(E::Int);
                self.il_value(b, first);
                let rest: Vec<String> = f.inputs[1..]
                    .iter()
                    .map(|(_, t)| {
                        let t = il_type(t).unwrap_or(E::Int);
                        self.il_operand(b, t)
                    })
                    .collect();
                let sep = if rest.is_empty() { "" } else { " " };
                b.emit(format!("{}{sep}{}", f.name, rest.join(", ")));
            } else {
                // Formal: no current result is passed.
                let args: Vec<String> = f
                    .inputs
                    .iter()
                    .map(|(n, t)| {
                        let t = il_type(t).unwrap_or(E::Int);
                        format!("{n} := {}", self.il_operand(b, t))
                    })
                    .collect();
                b.emit(format!("{}({})", f.name, args.join(", ")));
            }
        } else if class(e) == Class::Bool && self.rng.chance(45) {
            // A comparison.
            let t = loop {
                let t = self.il_elem();
                if t != E::Bool {
                    break t;
                }
            };
            self.il_value(b, t);
            let op = *self.rng.pick(&["GT", "GE", "EQ", "NE", "LE", "LT"]);
            let x = self.il_operand(b, t);
            b.emit(format!("{op} {x}"));
        } else {
            let x = self.il_operand(b, e);
            let ld = if class(e) == Class::Bool && self.rng.chance(20) {
                "LDN"
            } else {
                "LD"
            };
            b.emit(format!("{ld} {x}"));
        }
        for _ in 0..self.rng.range(0, 3) {
            self.il_operator(b, e);
        }
        b.depth -= 1;
    }

    /// One operator on a current result of type `e`, keeping its type.
    fn il_operator(&mut self, b: &mut Il, e: E) {
        let ops: &[&str] = match class(e) {
            Class::Bool => &["AND", "OR", "XOR", "ANDN", "ORN", "XORN", "&", "NOT"],
            Class::Real => &["ADD", "SUB", "MUL", "DIV"],
            _ => &["ADD", "SUB", "MUL", "DIV", "MOD"],
        };
        let op = *self.rng.pick(ops);
        if op == "NOT" {
            b.emit("NOT".into());
            return;
        }
        if matches!(op, "DIV" | "MOD") {
            let d = self.il_lit(e);
            b.emit(format!("{op} {d}"));
            return;
        }
        if b.depth < 3 && self.rng.chance(15) {
            // `ADD( x` ... `)`: the operator applied to a nested sequence.
            let x = self.il_operand(b, e);
            b.emit(format!("{op}( {x}"));
            b.depth += 1;
            let mut inner = Il {
                vars: Vec::new(),
                lines: Vec::new(),
                funcs: 0,
                fbs: Vec::new(),
                next_label: 0,
                counters: Vec::new(),
                depth: b.depth,
            };
            std::mem::swap(&mut inner.vars, &mut b.vars);
            for _ in 0..self.rng.range(1, 2) {
                self.il_operator(&mut inner, e);
            }
            std::mem::swap(&mut inner.vars, &mut b.vars);
            for l in inner.lines {
                b.lines.push(format!("    {l}"));
            }
            b.depth -= 1;
            b.emit(")".into());
            return;
        }
        let x = self.il_operand(b, e);
        b.emit(format!("{op} {x}"));
    }

    /// A value stored into a writable variable.
    fn il_assign(&mut self, b: &mut Il) {
        let targets: Vec<usize> = (0..b.vars.len()).filter(|&i| b.vars[i].writable).collect();
        if targets.is_empty() {
            return;
        }
        let t = *self.rng.pick(&targets);
        let (name, e) = (b.vars[t].name.clone(), b.vars[t].ty);
        self.il_value(b, e);
        let st = if e == E::Bool && self.rng.chance(15) {
            "STN"
        } else {
            "ST"
        };
        b.emit(format!("{st} {name}"));
        // `LD x` `ST a` `ST b`: the current result is kept by ST.
        let more: Vec<usize> = targets
            .into_iter()
            .filter(|&i| b.vars[i].ty == e && i != t)
            .collect();
        if !more.is_empty() && self.rng.chance(15) {
            let other = b.vars[*self.rng.pick(&more)].name.clone();
            b.emit(format!("ST {other}"));
        }
    }

    fn il_stmt(&mut self, b: &mut Il, lvl: u32) {
        let bools: Vec<String> = b
            .vars
            .iter()
            .filter(|v| v.writable && v.ty == E::Bool)
            .map(|v| v.name.clone())
            .collect();
        let w = [
            10,
            if bools.is_empty() { 0 } else { 2 },
            if lvl < 2 { 3 } else { 0 },
            if lvl < 1 { 2 } else { 0 },
            if b.fbs.is_empty() { 0 } else { 3 },
        ];
        match self.rng.weighted(&w) {
            0 => self.il_assign(b),
            1 => {
                self.il_value(b, E::Bool);
                let op = if self.rng.chance(50) { "S" } else { "R" };
                let v = self.rng.pick(&bools).clone();
                b.emit(format!("{op} {v}"));
            }
            2 => {
                // A forward jump over a block.
                let l = b.label();
                self.il_value(b, E::Bool);
                let op = *self.rng.pick(&["JMPC", "JMPCN"]);
                b.emit(format!("{op} {l}"));
                for _ in 0..self.rng.range(1, 3) {
                    self.il_stmt(b, lvl + 1);
                }
                b.lines.push(format!("{l}:"));
            }
            3 => {
                // A loop run 1..4 times, by a backward jump.
                let l = b.label();
                let c = format!("ilc{}", b.next_label);
                b.counters.push(c.clone());
                b.emit("LD DINT#0".into());
                b.emit(format!("ST {c}"));
                b.lines.push(format!("{l}:"));
                for _ in 0..self.rng.range(1, 2) {
                    self.il_stmt(b, lvl + 1);
                }
                let n = self.rng.range(1, 4);
                b.emit(format!("LD {c}"));
                b.emit("ADD DINT#1".into());
                b.emit(format!("ST {c}"));
                b.emit(format!("LT DINT#{n}"));
                b.emit(format!("JMPC {l}"));
            }
            _ => self.il_fb_call(b),
        }
    }

    /// `CAL inst(...)` of an instance of a generated block, then its
    /// outputs read into variables of their types.
    fn il_fb_call(&mut self, b: &mut Il) {
        let (inst, k) = self.rng.pick(&b.fbs).clone();
        let sig = self.types.fbs[k].clone();
        let mut args = Vec::new();
        for (n, t) in &sig.inputs {
            if let Some(e) = il_type(t) {
                if self.rng.chance(80) {
                    let x = self.il_operand(b, e);
                    args.push(format!("{n} := {x}"));
                }
            }
        }
        match self.rng.below(3) {
            0 if args.is_empty() => b.emit(format!("CAL {inst}")),
            0 | 1 => b.emit(format!("CAL {inst}({})", args.join(", "))),
            _ => {
                // A condition on the call.
                self.il_value(b, E::Bool);
                let op = *self.rng.pick(&["CALC", "CALCN"]);
                b.emit(format!("{op} {inst}({})", args.join(", ")));
            }
        }
        for (n, t) in &sig.outputs {
            let Some(e) = il_type(t) else { continue };
            let targets: Vec<String> = b
                .vars
                .iter()
                .filter(|v| v.writable && v.ty == e)
                .map(|v| v.name.clone())
                .collect();
            if !targets.is_empty() && self.rng.chance(70) {
                let v = self.rng.pick(&targets).clone();
                b.emit(format!("LD {inst}.{n}"));
                b.emit(format!("ST {v}"));
            }
        }
    }

    fn il_vars(&mut self, vars: &[Var], result: Option<(&str, E)>) -> Vec<IlVar> {
        let mut out: Vec<IlVar> = vars
            .iter()
            .filter_map(|v| {
                let e = il_type(&v.ty)?;
                Some(IlVar {
                    name: v.name.clone(),
                    ty: e,
                    writable: v.sect != Sect::Input,
                })
            })
            .collect();
        if let Some((name, e)) = result {
            out.push(IlVar {
                name: name.into(),
                ty: e,
                // Written, never read (a FUNCTION's result).
                writable: false,
            });
        }
        out
    }

    fn il_var(&mut self, prefix: &str, sect: Sect, k: usize) -> Var {
        let e = self.il_elem();
        let init = if sect != Sect::Input && self.rng.chance(25) {
            Some(self.il_lit(e))
        } else {
            None
        };
        Var {
            name: format!("{prefix}{k}_{}", crate::model::tag(e)),
            ty: Ty::E(e),
            sect,
            init,
            location: None,
        }
    }

    fn il_body_text(&mut self, b: &mut Il, n: usize) -> String {
        for _ in 0..n {
            self.il_stmt(b, 0);
        }
        b.lines.join("\n")
    }

    fn counters_block(b: &Il) -> String {
        if b.counters.is_empty() {
            return String::new();
        }
        let mut s = String::from("VAR\n");
        for c in &b.counters {
            s.push_str(&format!("    {c} : DINT;\n"));
        }
        s.push_str("END_VAR\n");
        s
    }

    /// `FUNCTION calc<idx>` with an IL body.
    pub(crate) fn gen_il_function(&mut self, idx: usize) -> String {
        let name = format!("calc{idx}");
        let ret = self.il_elem();
        let mut vars = Vec::new();
        let mut k = 0;
        for _ in 0..self.rng.range(1, 3) {
            vars.push(self.il_var("a", Sect::Input, k));
            k += 1;
        }
        if self.rng.chance(30) {
            vars.push(self.il_var("o", Sect::Output, k));
            k += 1;
        }
        for _ in 0..self.rng.range(0, 3) {
            vars.push(self.il_var("t", Sect::Local, k));
            k += 1;
        }
        let mut b = Il {
            vars: self.il_vars(&vars, None),
            lines: Vec::new(),
            funcs: idx,
            fbs: Vec::new(),
            next_label: 0,
            counters: Vec::new(),
            depth: 0,
        };
        // The result first, so it is assigned on every path.
        self.il_value(&mut b, ret);
        b.emit(format!("ST {name}"));
        let n = self.rng.range(1, (self.size.statements / 2).max(2) as i128) as usize;
        let mut body = self.il_body_text(&mut b, n);
        if self.rng.chance(40) {
            // And maybe again at the end.
            let mut end = Il {
                vars: std::mem::take(&mut b.vars),
                lines: Vec::new(),
                funcs: idx,
                fbs: Vec::new(),
                next_label: b.next_label,
                counters: Vec::new(),
                depth: 0,
            };
            self.il_value(&mut end, ret);
            end.emit(format!("ST {name}"));
            body.push('\n');
            body.push_str(&end.lines.join("\n"));
        }
        self.funcs.push(PouSig {
            name: name.clone(),
            ret: Some(Ty::E(ret)),
            inputs: sect_list(&vars, Sect::Input),
            outputs: sect_list(&vars, Sect::Output),
            inouts: Vec::new(),
        });
        let blocks = self.il_var_blocks(&vars);
        format!(
            "FUNCTION {name} : {}\n{blocks}{}{body}\nEND_FUNCTION\n\n",
            ret.name(),
            Self::counters_block(&b)
        )
    }

    /// `FUNCTION_BLOCK Block<idx>` with an IL body, which may hold
    /// instances of the blocks before it.
    pub(crate) fn gen_il_fb(&mut self, idx: usize) -> String {
        let name = format!("Block{idx}");
        let mut vars = Vec::new();
        let mut k = 0;
        for _ in 0..self.rng.range(1, 3) {
            vars.push(self.il_var("in", Sect::Input, k));
            k += 1;
        }
        for _ in 0..self.rng.range(1, 3) {
            vars.push(self.il_var("out", Sect::Output, k));
            k += 1;
        }
        for _ in 0..self.rng.range(1, 3) {
            vars.push(self.il_var("s", Sect::Local, k));
            k += 1;
        }
        let mut fbs = Vec::new();
        let blocks: Vec<usize> = (0..idx)
            .filter(|&t| self.types.fbs[t].inouts.is_empty())
            .collect();
        if !blocks.is_empty() && self.rng.chance(50) {
            let t = *self.rng.pick(&blocks);
            let inst = format!("fb{k}");
            vars.push(Var {
                name: inst.clone(),
                ty: Ty::Fb(Fb::User(t)),
                sect: Sect::Local,
                init: None,
                location: None,
            });
            fbs.push((inst, t));
        }
        let mut b = Il {
            vars: self.il_vars(&vars, None),
            lines: Vec::new(),
            funcs: self.funcs.len(),
            fbs,
            next_label: 0,
            counters: Vec::new(),
            depth: 0,
        };
        let n = self.rng.range(2, (self.size.statements / 2).max(3) as i128) as usize;
        let body = self.il_body_text(&mut b, n);
        self.types.fbs.push(PouSig {
            name: name.clone(),
            ret: None,
            inputs: sect_list(&vars, Sect::Input),
            outputs: sect_list(&vars, Sect::Output),
            inouts: Vec::new(),
        });
        let blocks = self.il_var_blocks(&vars);
        format!(
            "FUNCTION_BLOCK {name}\n{blocks}{}{body}\nEND_FUNCTION_BLOCK\n\n",
            Self::counters_block(&b)
        )
    }

    /// A PROGRAM with an IL body (`globals` are its VAR_EXTERNALs): its
    /// text and its variables.
    pub(crate) fn gen_il_program(&mut self, name: &str, globals: &[Var]) -> (String, Vec<Var>) {
        let mut vars = Vec::new();
        let mut k = 0;
        for _ in 0..self.rng.range(0, 2) {
            vars.push(self.il_var("in", Sect::Input, k));
            k += 1;
        }
        for _ in 0..self.rng.range(1, 3) {
            vars.push(self.il_var("out", Sect::Output, k));
            k += 1;
        }
        for _ in 0..self.rng.range(2, 4) {
            vars.push(self.il_var("v", Sect::Local, k));
            k += 1;
        }
        let mut fbs = Vec::new();
        let blocks: Vec<usize> = (0..self.types.fbs.len())
            .filter(|&t| self.types.fbs[t].inouts.is_empty())
            .collect();
        for _ in 0..self.rng.range(0, 2) {
            if blocks.is_empty() {
                break;
            }
            let t = *self.rng.pick(&blocks);
            let inst = format!("fb{k}");
            k += 1;
            vars.push(Var {
                name: inst.clone(),
                ty: Ty::Fb(Fb::User(t)),
                sect: Sect::Local,
                init: None,
                location: None,
            });
            fbs.push((inst, t));
        }
        let mut all = vars.clone();
        all.extend(globals.iter().cloned());
        let mut b = Il {
            vars: self.il_vars(&all, None),
            lines: Vec::new(),
            funcs: self.funcs.len(),
            fbs: fbs.clone(),
            next_label: 0,
            counters: Vec::new(),
            depth: 0,
        };
        // Every instance is called at least once.
        for (inst, _) in &fbs {
            b.emit(format!("CAL {inst}"));
        }
        let n = self.rng.range(3, (self.size.statements / 2).max(4) as i128) as usize;
        let body = self.il_body_text(&mut b, n);
        let mut blocks = self.il_var_blocks(&vars);
        if !globals.is_empty() {
            blocks.push_str("VAR_EXTERNAL\n");
            for g in globals {
                blocks.push_str(&format!("    {} : {};\n", g.name, self.types.text(&g.ty)));
            }
            blocks.push_str("END_VAR\n");
        }
        let text = format!(
            "PROGRAM {name}\n{blocks}{}{body}\nEND_PROGRAM\n\n",
            Self::counters_block(&b)
        );
        (text, vars)
    }

    fn il_var_blocks(&self, vars: &[Var]) -> String {
        let mut out = String::new();
        for (sect, kw) in [
            (Sect::Input, "VAR_INPUT"),
            (Sect::Output, "VAR_OUTPUT"),
            (Sect::Local, "VAR"),
        ] {
            let list: Vec<&Var> = vars.iter().filter(|v| v.sect == sect).collect();
            if list.is_empty() {
                continue;
            }
            out.push_str(kw);
            out.push('\n');
            for v in list {
                let mut d = format!("{} : {}", v.name, self.types.text(&v.ty));
                if let Some(i) = &v.init {
                    d.push_str(&format!(" := {i}"));
                }
                out.push_str(&format!("    {d};\n"));
            }
            out.push_str("END_VAR\n");
        }
        out
    }
}

fn sect_list(vars: &[Var], sect: Sect) -> Vec<(String, Ty)> {
    vars.iter()
        .filter(|v| v.sect == sect)
        .map(|v| (v.name.clone(), v.ty.clone()))
        .collect()
}
