//! The program generator: types, functions, function blocks, programs and
//! maybe a configuration, then the options to run them with.

use stc_values::ElemType as E;

use crate::model::{
    class, is_signed, range, tag, Access, ArrayDef, Class, EnumDef, Fb, PouSig, Reach, Sect, StdFb,
    Step, StructDef, SubDef, Ty, Types, Var, ELEMS, INTS,
};
use crate::rng::Rng;

/// How big the generated programs are.
#[derive(Clone, Debug)]
pub struct Size {
    /// At most this many TYPE declarations.
    pub types: usize,
    /// At most this many FUNCTIONs.
    pub functions: usize,
    /// At most this many FUNCTION_BLOCKs.
    pub function_blocks: usize,
    /// Statements at the top level of the main program's body (function
    /// and FB bodies get about half).
    pub statements: usize,
    /// Expression depth.
    pub depth: u32,
    /// At most this many cycles (at least 3).
    pub max_cycles: u64,
    /// Per mille of divisors, indices, MUX selectors and subrange values
    /// left unguarded (those may fault at run time: both back ends must
    /// agree on faults too, but a program that faults early tests little).
    pub unguarded: u64,
    /// Only programs a circuit can express (docs/netlist.md): no WHILE or
    /// REPEAT, FOR with constant bounds and step, no Instruction List (its
    /// backward jumps are loops). For the differential run with
    /// `--backend netlist`.
    pub circuit: bool,
}

impl Size {
    /// Small programs, quick to compile: for the CI differential run.
    pub fn small() -> Size {
        Size {
            types: 3,
            functions: 2,
            function_blocks: 2,
            statements: 10,
            depth: 3,
            max_cycles: 12,
            unguarded: 15,
            circuit: false,
        }
    }

    /// The default.
    pub fn medium() -> Size {
        Size {
            types: 5,
            functions: 3,
            function_blocks: 3,
            statements: 18,
            depth: 3,
            max_cycles: 16,
            unguarded: 8,
            circuit: false,
        }
    }

    /// Larger programs for long local runs.
    pub fn large() -> Size {
        Size {
            types: 8,
            functions: 5,
            function_blocks: 4,
            statements: 35,
            depth: 4,
            max_cycles: 20,
            unguarded: 3,
            circuit: false,
        }
    }

    /// The same size, generating only what a circuit can express.
    pub fn for_circuit(self) -> Size {
        Size {
            circuit: true,
            ..self
        }
    }
}

impl Default for Size {
    fn default() -> Size {
        Size::medium()
    }
}

/// A generated program and the options of `stc run` to run it with.
#[derive(Clone, Debug)]
pub struct Generated {
    pub seed: u64,
    /// The ST source text (one file).
    pub source: String,
    /// `--cycles`.
    pub cycles: u64,
    /// `--tick`, when not the default.
    pub tick: Option<String>,
    /// `--set PATH=VALUE` for the inputs.
    pub sets: Vec<String>,
    /// `--watch`: every variable worth comparing.
    pub watch: Vec<String>,
    /// `--max-steps`: generous, the loops are bounded.
    pub max_steps: u64,
}

impl Generated {
    /// A file name for the source, from the seed.
    pub fn file_name(&self) -> String {
        format!("p{:016x}.st", self.seed)
    }

    /// The options of `stc run` after the source file, the same for the VM
    /// and for the C simulation harness: JSON reports after every cycle.
    pub fn run_options(&self) -> Vec<String> {
        let mut o = vec![
            "--format".to_string(),
            "json".to_string(),
            "--trace".to_string(),
            "--cycles".to_string(),
            self.cycles.to_string(),
            "--max-steps".to_string(),
            self.max_steps.to_string(),
        ];
        if let Some(t) = &self.tick {
            o.push("--tick".into());
            o.push(t.clone());
        }
        for s in &self.sets {
            o.push("--set".into());
            o.push(s.clone());
        }
        if !self.watch.is_empty() {
            o.push("--watch".into());
            o.push(self.watch.join(","));
        }
        o
    }

    /// The `stc run` command line, quoted for a POSIX shell.
    pub fn command_line(&self, file: &str) -> String {
        let mut words = vec!["stc".to_string(), "run".to_string(), quote(file)];
        words.extend(self.run_options().iter().map(|w| quote(w)));
        words.join(" ")
    }
}

fn quote(w: &str) -> String {
    if !w.is_empty()
        && w.chars()
            .all(|c| c.is_ascii_alphanumeric() || "-_.,/=#:[]+".contains(c))
    {
        w.to_string()
    } else {
        format!("'{}'", w.replace('\'', "'\\''"))
    }
}

/// Generates the program of `seed`: the same seed and size always give the
/// same program.
pub fn program(seed: u64, size: Size) -> Generated {
    let mut g = Gen {
        rng: Rng::new(seed),
        size,
        types: Types::default(),
        funcs: Vec::new(),
        index_nesting: 0,
        event_global: None,
        next_address: 0,
    };
    g.build(seed)
}

/// The kind of POU whose body is generated.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Kind {
    Function,
    FunctionBlock,
    Program,
}

/// A FOR control variable while its loop body is generated, with the range
/// its values stay in.
pub(crate) struct LoopVar {
    pub name: String,
    pub ty: E,
    pub lo: i128,
    pub hi: i128,
}

/// The state of the body being generated.
pub(crate) struct Body {
    pub reach: Reach,
    pub loops: Vec<LoopVar>,
    /// Functions 0..funcs may be called (no recursion).
    pub funcs: usize,
    /// Loop counters and guards, declared in VAR after the others.
    pub hidden: Vec<Var>,
    pub next: usize,
    pub loop_depth: u32,
    pub max_loops: u32,
    pub nest: u32,
    /// A function's name and result type.
    pub result: Option<(String, E)>,
}

impl Body {
    fn fresh(&mut self, prefix: &str) -> String {
        self.next += 1;
        format!("{prefix}{}", self.next)
    }
}

pub(crate) struct Gen {
    pub(crate) rng: Rng,
    pub(crate) size: Size,
    pub(crate) types: Types,
    pub(crate) funcs: Vec<PouSig>,
    /// How many index expressions are being generated inside each other.
    pub(crate) index_nesting: u32,
    /// The global BOOL that triggers the event task, while Main is
    /// generated.
    event_global: Option<String>,
    /// The next free number of a direct address: every located variable
    /// gets its own address, so no two declarations share a slot.
    next_address: u32,
}

const WORDS: &[&str] = &[
    "idle", "run", "stop", "wait", "fault", "done", "low", "high", "open", "shut",
];

impl Gen {
    fn build(&mut self, seed: u64) -> Generated {
        self.gen_types();
        let mut pous = String::new();
        let nf = self.rng.range(0, self.size.functions as i128) as usize;
        for i in 0..nf {
            let text = if self.rng.chance(25) && !self.size.circuit {
                self.gen_il_function(i)
            } else {
                self.gen_function(i)
            };
            pous.push_str(&text);
        }
        let nfb = self.rng.range(0, self.size.function_blocks as i128) as usize;
        for i in 0..nfb {
            let text = if self.rng.chance(25) && !self.size.circuit {
                self.gen_il_fb(i)
            } else {
                self.gen_fb(i)
            };
            pous.push_str(&text);
        }

        let config = self.rng.chance(30);
        let mut globals = Vec::new();
        if config {
            for k in 0..self.rng.range(0, 3) {
                let e = self.elem();
                let init = if self.rng.chance(40) {
                    Some(self.init_lit(e))
                } else {
                    None
                };
                globals.push(Var {
                    name: format!("g{k}_{}", tag(e)),
                    ty: Ty::E(e),
                    sect: Sect::External,
                    init,
                    location: None,
                });
            }
        }
        // Sometimes an event task, triggered by a global BOOL that Main
        // sets.
        let event = config && self.rng.chance(30);
        if event {
            globals.push(Var {
                name: "g_event".into(),
                ty: Ty::E(E::Bool),
                sect: Sect::External,
                init: None,
                location: None,
            });
            self.event_global = Some("g_event".into());
        }
        let main = if event || !self.rng.chance(12) || self.size.circuit {
            self.gen_program("Main", self.size.statements, &globals)
        } else {
            let (text, vars) = self.gen_il_program("Main", &globals);
            Prog { text, vars }
        };
        self.event_global = None;
        pous.push_str(&main.text);
        let mut instances: Vec<(String, Vec<Var>)> = Vec::new();
        let mut config_text = String::new();
        let mut tick = None;
        if config {
            let with_aux = self.rng.chance(50);
            let aux = if with_aux {
                let a = if self.rng.chance(30) && !self.size.circuit {
                    let (text, vars) = self.gen_il_program("Aux", &globals);
                    Prog { text, vars }
                } else {
                    self.gen_program("Aux", self.size.statements / 2 + 1, &globals)
                };
                pous.push_str(&a.text);
                Some(a)
            } else {
                None
            };
            let slow = *self.rng.pick(&[20, 30, 50]);
            let two_tasks = self.rng.chance(60);
            let mut c = String::from("CONFIGURATION Cell\n");
            if !globals.is_empty() {
                c.push_str("    VAR_GLOBAL\n");
                for gv in &globals {
                    c.push_str(&format!("        {};\n", self.decl(gv)));
                }
                c.push_str("    END_VAR\n");
            }
            c.push_str("    RESOURCE Cpu ON PLC\n");
            c.push_str("        TASK fast (INTERVAL := T#10ms, PRIORITY := 1);\n");
            if two_tasks {
                let prio = if self.rng.chance(50) { 2 } else { 1 };
                c.push_str(&format!(
                    "        TASK slow (INTERVAL := T#{slow}ms, PRIORITY := {prio});\n"
                ));
            }
            if event {
                c.push_str("        TASK ev (SINGLE := g_event, PRIORITY := 3);\n");
            }
            let task = |g: &mut Gen| {
                if event && g.rng.chance(30) {
                    "ev"
                } else if two_tasks && g.rng.chance(50) {
                    "slow"
                } else {
                    "fast"
                }
            };
            let t = task(self);
            let conn = self.connections(&main.vars, &globals);
            c.push_str(&format!("        PROGRAM main1 WITH {t} : Main{conn};\n"));
            instances.push(("main1".into(), main.vars.clone()));
            if self.rng.chance(30) {
                let t = task(self);
                let conn = self.connections(&main.vars, &globals);
                c.push_str(&format!("        PROGRAM main2 WITH {t} : Main{conn};\n"));
                instances.push(("main2".into(), main.vars.clone()));
            }
            if let Some(a) = &aux {
                let conn = self.connections(&a.vars, &globals);
                if self.rng.chance(20) {
                    c.push_str(&format!("        PROGRAM aux1 : Aux{conn};\n"));
                } else {
                    let t = task(self);
                    c.push_str(&format!("        PROGRAM aux1 WITH {t} : Aux{conn};\n"));
                }
                instances.push(("aux1".into(), a.vars.clone()));
            }
            c.push_str("    END_RESOURCE\nEND_CONFIGURATION\n");
            config_text = c;
        } else {
            instances.push(("Main".into(), main.vars.clone()));
            if self.rng.chance(20) {
                tick = Some(self.rng.pick(&["5ms", "20ms", "T#100ms", "1s"]).to_string());
            }
        }

        // Options.
        let cycles = self.rng.range(3, self.size.max_cycles.max(3) as i128) as u64;
        let mut sets = Vec::new();
        let mut watch = Vec::new();
        for (inst, vars) in &instances {
            for v in vars {
                match v.sect {
                    Sect::Input => {
                        if let Ty::E(e) = v.ty {
                            if self.rng.chance(90) {
                                let val = self.set_value(e);
                                sets.push(format!("{inst}.{}={val}", v.name));
                            }
                        }
                        watch.push(format!("{inst}.{}", v.name));
                    }
                    Sect::Output | Sect::Local => watch.push(format!("{inst}.{}", v.name)),
                    _ => {}
                }
            }
        }
        for gv in &globals {
            if let Ty::E(e) = gv.ty {
                if self.rng.chance(30) {
                    let val = self.set_value(e);
                    sets.push(format!("{}={val}", gv.name));
                }
            }
            watch.push(gv.name.clone());
        }

        let mut source = String::new();
        let mut generated = Generated {
            seed,
            source: String::new(),
            cycles,
            tick,
            sets,
            watch,
            max_steps: 20_000_000,
        };
        source.push_str(&format!(
            "// Generated by stc_progen from seed {seed} (0x{seed:016x}).\n// {}\n\n",
            generated.command_line(&generated.file_name())
        ));
        source.push_str(&self.types_text());
        source.push_str(&pous);
        source.push_str(&config_text);
        generated.source = source;
        generated
    }

    /// Connections of a program instance to globals of the same types:
    /// ` (input := global, output => global)`, or nothing.
    fn connections(&mut self, vars: &[Var], globals: &[Var]) -> String {
        let mut parts = Vec::new();
        for v in vars {
            let sect = match v.sect {
                Sect::Input => ":=",
                Sect::Output => "=>",
                _ => continue,
            };
            let same: Vec<&Var> = globals.iter().filter(|g| g.ty == v.ty).collect();
            if !same.is_empty() && self.rng.chance(40) {
                let g = self.rng.pick(&same);
                parts.push(format!("{} {sect} {}", v.name, g.name));
            }
        }
        if parts.is_empty() {
            String::new()
        } else {
            format!(" ({})", parts.join(", "))
        }
    }

    // ------------------------------------------------------------------
    // Types.

    /// Whether values of `e` may be generated (a circuit has no strings).
    pub(crate) fn allowed(&self, e: E) -> bool {
        !(self.size.circuit && matches!(e, E::String | E::Wstring))
    }

    pub(crate) fn elem(&mut self) -> E {
        let w: Vec<u64> = ELEMS
            .iter()
            .map(|&(e, w)| if self.allowed(e) { w } else { 0 })
            .collect();
        ELEMS[self.rng.weighted(&w)].0
    }

    fn gen_types(&mut self) {
        let n = self.rng.range(0, self.size.types as i128) as usize;
        for k in 0..n {
            match self.rng.weighted(&[3, 3, 3, 2]) {
                0 => {
                    let count = self.rng.range(2, 5) as usize;
                    let start = self.rng.index(WORDS.len());
                    let values = (0..count)
                        .map(|j| format!("e{k}_{}", WORDS[(start + j) % WORDS.len()]))
                        .collect();
                    self.types.enums.push(EnumDef {
                        name: format!("Mode{k}"),
                        values,
                    });
                }
                1 => {
                    let count = self.rng.range(2, 4) as usize;
                    let mut fields = Vec::new();
                    let mut field_text = Vec::new();
                    for j in 0..count {
                        let ty = self.member_ty(2);
                        let name = format!("f{j}_{}", self.ty_tag(&ty));
                        let init = if self.rng.chance(30) {
                            self.init_text(&ty)
                        } else {
                            None
                        };
                        let mut text = self.types.text(&ty);
                        if let Some(i) = init {
                            text.push_str(&format!(" := {i}"));
                        }
                        field_text.push(text);
                        fields.push((name, ty));
                    }
                    self.types.structs.push(StructDef {
                        name: format!("Rec{k}"),
                        fields,
                        field_text,
                    });
                }
                2 => {
                    let elem = self.member_ty(1);
                    let i = self.new_array(elem, None);
                    self.types.arrays[i].name = Some(format!("Arr{k}"));
                }
                _ => {
                    let base = *self.rng.pick(INTS);
                    let (lo_t, hi_t) = range(base);
                    let lo = self.rng.range((-20).max(lo_t), 10.min(hi_t - 1));
                    let hi = self.rng.range(lo + 1, (lo + 100).min(hi_t));
                    self.types.subs.push(SubDef {
                        name: Some(format!("Lim{k}")),
                        base,
                        lo,
                        hi,
                    });
                }
            }
        }
    }

    /// A type for a struct member or array element.
    fn member_ty(&mut self, depth: u32) -> Ty {
        let w = [
            30,
            4,
            if self.types.enums.is_empty() { 0 } else { 5 },
            if self.types.structs.is_empty() || depth == 0 {
                0
            } else {
                4
            },
            if depth == 0 { 0 } else { 3 },
            if self.types.subs.is_empty() { 0 } else { 2 },
        ];
        match self.rng.weighted(&w) {
            0 => Ty::E(self.elem()),
            1 if self.size.circuit => Ty::E(self.elem()),
            1 => Ty::Str {
                wide: self.rng.chance(25),
                len: self.rng.range(1, 12) as u32,
            },
            2 => Ty::Enum(self.rng.index(self.types.enums.len())),
            3 => Ty::Struct(self.rng.index(self.types.structs.len())),
            4 => {
                let elem = Ty::E(self.elem());
                Ty::Array(self.new_array(elem, None))
            }
            _ => Ty::Sub(self.rng.index(self.types.subs.len())),
        }
    }

    /// A new anonymous array type; with `consts`, an upper bound may be
    /// one of those constants (name, value).
    fn new_array(&mut self, elem: Ty, consts: Option<&[(String, i128)]>) -> usize {
        let ndims = if self.rng.chance(25) { 2 } else { 1 };
        let mut dims = Vec::new();
        let mut dims_text = Vec::new();
        for _ in 0..ndims {
            let lo = if self.rng.chance(50) {
                self.rng.range(-3, 3)
            } else {
                *self.rng.pick(&[0, 1])
            };
            let len = self.rng.range(1, if ndims == 2 { 3 } else { 5 });
            let hi = lo + len - 1;
            let c = consts.and_then(|cs| cs.iter().find(|(_, v)| *v == hi));
            match c {
                Some((name, _)) if self.rng.chance(70) => dims_text.push(format!("{lo}..{name}")),
                _ => dims_text.push(format!("{lo}..{hi}")),
            }
            dims.push((lo, hi));
        }
        self.types.arrays.push(ArrayDef {
            name: None,
            dims,
            dims_text,
            elem,
        });
        self.types.arrays.len() - 1
    }

    fn ty_tag(&self, ty: &Ty) -> String {
        match ty {
            Ty::E(e) => tag(*e).into(),
            Ty::Str { wide: false, len } => format!("s{len}"),
            Ty::Str { wide: true, len } => format!("ws{len}"),
            Ty::Enum(_) => "mode".into(),
            Ty::Struct(_) => "rec".into(),
            Ty::Array(_) => "arr".into(),
            Ty::Sub(_) => "lim".into(),
            Ty::Fb(Fb::Std(f)) => f.name().to_lowercase(),
            Ty::Fb(Fb::User(i)) => format!("fb{i}"),
        }
    }

    fn types_text(&self) -> String {
        let mut lines = Vec::new();
        for e in &self.types.enums {
            lines.push(format!("    {} : ({});", e.name, e.values.join(", ")));
        }
        for s in &self.types.subs {
            if let Some(n) = &s.name {
                lines.push(format!("    {n} : {}({}..{});", s.base.name(), s.lo, s.hi));
            }
        }
        for s in &self.types.structs {
            lines.push(format!("    {} : STRUCT", s.name));
            for ((name, _), text) in s.fields.iter().zip(&s.field_text) {
                lines.push(format!("        {name} : {text};"));
            }
            lines.push("    END_STRUCT;".into());
        }
        for a in &self.types.arrays {
            if let Some(n) = &a.name {
                lines.push(format!(
                    "    {n} : ARRAY[{}] OF {};",
                    a.dims_text.join(", "),
                    self.types.text(&a.elem)
                ));
            }
        }
        if lines.is_empty() {
            return String::new();
        }
        format!("TYPE\n{}\nEND_TYPE\n\n", lines.join("\n"))
    }

    /// A literal for an initial value or `--set` (no parentheses).
    fn init_lit(&mut self, e: E) -> String {
        let s = self.lit(e, false);
        s.trim_start_matches('(').trim_end_matches(')').to_string()
    }

    /// An initial value for a variable of type `ty`, if it has one.
    fn init_text(&mut self, ty: &Ty) -> Option<String> {
        Some(match ty {
            Ty::E(e) => self.init_lit(*e),
            Ty::Str { wide, .. } => self.str_lit(*wide),
            Ty::Enum(i) => {
                let e = &self.types.enums[*i];
                e.values[self.rng.index(e.values.len())].clone()
            }
            Ty::Sub(i) => {
                let s = &self.types.subs[*i];
                let (lo, hi) = (s.lo, s.hi);
                self.rng.range(lo, hi).to_string()
            }
            Ty::Struct(i) => {
                let fields: Vec<(String, Ty)> = self.types.structs[*i]
                    .fields
                    .iter()
                    .filter(|(_, t)| matches!(t, Ty::E(_)))
                    .cloned()
                    .collect();
                if fields.is_empty() {
                    return None;
                }
                let mut parts = Vec::new();
                for (n, t) in fields {
                    if self.rng.chance(60) {
                        if let Ty::E(e) = t {
                            parts.push(format!("{n} := {}", self.init_lit(e)));
                        }
                    }
                }
                if parts.is_empty() {
                    return None;
                }
                format!("({})", parts.join(", "))
            }
            Ty::Array(i) => {
                let (len, elem) = {
                    let a = &self.types.arrays[*i];
                    (a.len(), a.elem.clone())
                };
                let Ty::E(e) = elem else {
                    return None;
                };
                let mut items = Vec::new();
                let mut left = len;
                while left > 0 {
                    let v = self.init_lit(e);
                    if left > 1 && self.rng.chance(25) {
                        let n = self.rng.range(2, left);
                        items.push(format!("{n}({v})"));
                        left -= n;
                    } else {
                        items.push(v);
                        left -= 1;
                    }
                    if self.rng.chance(20) {
                        break;
                    }
                }
                format!("[{}]", items.join(", "))
            }
            Ty::Fb(_) => return None,
        })
    }

    /// A value in ST literal syntax for `--set`.
    fn set_value(&mut self, e: E) -> String {
        match class(e) {
            Class::Int | Class::Bits => {
                let mut v = self.int_value(e);
                if v == 0 {
                    v = 1;
                }
                v.to_string()
            }
            Class::Str => {
                let n = self.rng.range(0, 6);
                let s: String = (0..n)
                    .map(|_| *self.rng.pick(&['a', 'b', 'Q', '1', ' ']))
                    .collect();
                if e == E::Wstring {
                    format!("\"{s}\"")
                } else {
                    format!("'{s}'")
                }
            }
            _ => self.init_lit(e),
        }
    }

    // ------------------------------------------------------------------
    // Variables.

    /// A type for a variable of a POU of `kind`.
    fn var_ty(&mut self, kind: Kind, fb_limit: usize) -> Ty {
        let fbs = kind != Kind::Function;
        let w = [
            60,
            4,
            if self.types.enums.is_empty() { 0 } else { 6 },
            if self.types.structs.is_empty() { 0 } else { 6 },
            if self.types.arrays.iter().any(|a| a.name.is_some()) {
                5
            } else {
                0
            },
            6,
            if self.types.subs.is_empty() { 0 } else { 3 },
            2,
            if fbs { 12 } else { 0 },
            if fbs && fb_limit > 0 { 8 } else { 0 },
            if fbs { 2 } else { 0 },
        ];
        match self.rng.weighted(&w) {
            0 => Ty::E(self.elem()),
            1 if self.size.circuit => Ty::E(self.elem()),
            1 => Ty::Str {
                wide: self.rng.chance(25),
                len: self.rng.range(1, 20) as u32,
            },
            2 => Ty::Enum(self.rng.index(self.types.enums.len())),
            3 => Ty::Struct(self.rng.index(self.types.structs.len())),
            4 => {
                let named: Vec<usize> = (0..self.types.arrays.len())
                    .filter(|&i| self.types.arrays[i].name.is_some())
                    .collect();
                Ty::Array(*self.rng.pick(&named))
            }
            5 => {
                let elem = self.member_ty(1);
                Ty::Array(self.new_array(elem, None))
            }
            6 => Ty::Sub(self.rng.index(self.types.subs.len())),
            7 => {
                let base = *self
                    .rng
                    .pick(&[E::Sint, E::Int, E::Dint, E::Usint, E::Uint]);
                let (lo_t, hi_t) = range(base);
                let lo = self.rng.range((-10).max(lo_t), 5);
                let hi = self.rng.range(lo + 1, (lo + 50).min(hi_t));
                self.types.subs.push(SubDef {
                    name: None,
                    base,
                    lo,
                    hi,
                });
                Ty::Sub(self.types.subs.len() - 1)
            }
            8 => Ty::Fb(Fb::Std(self.std_fb())),
            9 => Ty::Fb(Fb::User(self.rng.index(fb_limit))),
            _ => {
                let elem = Ty::Fb(Fb::Std(self.std_fb()));
                Ty::Array(self.new_array(elem, None))
            }
        }
    }

    fn std_fb(&mut self) -> StdFb {
        let timer = if self.rng.chance(85) {
            E::Time
        } else {
            E::Ltime
        };
        let counter =
            *self
                .rng
                .pick(&[E::Int, E::Int, E::Int, E::Dint, E::Lint, E::Udint, E::Ulint]);
        match self.rng.below(10) {
            0 => StdFb::Ton(timer),
            1 => StdFb::Tof(timer),
            2 => StdFb::Tp(timer),
            3 => StdFb::Ctu(counter),
            4 => StdFb::Ctd(counter),
            5 => StdFb::Ctud(counter),
            6 => StdFb::RTrig,
            7 => StdFb::FTrig,
            8 => StdFb::Sr,
            _ => StdFb::Rs,
        }
    }

    /// A type for an input, output or function result: elementary mostly.
    fn param_ty(&mut self) -> Ty {
        match self
            .rng
            .weighted(&[20, 1, if self.types.enums.is_empty() { 0 } else { 2 }])
        {
            0 => Ty::E(self.elem()),
            1 if self.size.circuit => Ty::E(self.elem()),
            1 => Ty::Str {
                wide: false,
                len: self.rng.range(4, 30) as u32,
            },
            _ => Ty::Enum(self.rng.index(self.types.enums.len())),
        }
    }

    /// A fresh direct address for a variable of type `e`: its size letter
    /// (X, B, W, D, L) fixed by the type, the area chosen at random.
    fn address_for(&mut self, e: E) -> Option<String> {
        let size = match e {
            E::Bool => 'X',
            E::Sint | E::Usint | E::Byte | E::Char => 'B',
            E::Int | E::Uint | E::Word | E::Wchar => 'W',
            E::Dint | E::Udint | E::Dword | E::Real => 'D',
            E::String | E::Wstring => return None,
            _ => 'L',
        };
        let mut area = ['I', 'Q', 'M'][self.rng.index(3)];
        if area == 'I' && self.size.circuit {
            // (A circuit's `%I` variables are its inputs: never written.)
            area = 'M';
        }
        let n = self.next_address;
        self.next_address += 1;
        Some(if size == 'X' {
            format!("%{area}X{}.{}", n / 8, n % 8)
        } else {
            format!("%{area}{size}{n}")
        })
    }

    fn decl(&self, v: &Var) -> String {
        let mut s = match &v.location {
            Some(a) => format!("{} AT {a} : {}", v.name, self.types.text(&v.ty)),
            None => format!("{} : {}", v.name, self.types.text(&v.ty)),
        };
        if let Some(i) = &v.init {
            s.push_str(&format!(" := {i}"));
        }
        s
    }

    fn var_blocks(&self, vars: &[Var], hidden: &[Var]) -> String {
        let mut out = String::new();
        for (sect, kw) in [
            (Sect::Input, "VAR_INPUT"),
            (Sect::Output, "VAR_OUTPUT"),
            (Sect::InOut, "VAR_IN_OUT"),
            (Sect::External, "VAR_EXTERNAL"),
            (Sect::Constant, "VAR CONSTANT"),
            (Sect::Local, "VAR"),
            (Sect::Temp, "VAR_TEMP"),
        ] {
            let mut list: Vec<&Var> = vars.iter().filter(|v| v.sect == sect).collect();
            if sect == Sect::Local {
                list.extend(hidden.iter());
            }
            if list.is_empty() {
                continue;
            }
            out.push_str(kw);
            out.push('\n');
            for v in list {
                out.push_str(&format!("    {};\n", self.decl(v)));
            }
            out.push_str("END_VAR\n");
        }
        out
    }

    fn new_var(&mut self, prefix: &str, ty: Ty, sect: Sect, k: usize) -> Var {
        let init = if matches!(sect, Sect::Local | Sect::Output | Sect::Temp | Sect::Input)
            && self.rng.chance(25)
        {
            self.init_text(&ty)
        } else {
            None
        };
        Var {
            name: format!("{prefix}{k}_{}", self.ty_tag(&ty)),
            ty,
            sect,
            init,
            location: None,
        }
    }

    fn new_body(&self, kind: Kind, vars: &[Var], funcs: usize, next: usize) -> Body {
        Body {
            reach: Reach::of(vars, &self.types),
            loops: Vec::new(),
            funcs,
            hidden: Vec::new(),
            next,
            loop_depth: 0,
            max_loops: if kind == Kind::Program { 2 } else { 1 },
            nest: 0,
            result: None,
        }
    }

    // ------------------------------------------------------------------
    // POUs.

    fn gen_function(&mut self, idx: usize) -> String {
        let name = format!("calc{idx}");
        let ret = loop {
            let t = self.param_ty();
            if !matches!(t, Ty::Enum(_)) {
                break t;
            }
        };
        let ret_e = ret.scalar(&self.types).unwrap_or(E::Int);
        let mut vars = Vec::new();
        let mut k = 0;
        for _ in 0..self.rng.range(1, 3) {
            let t = self.param_ty();
            vars.push(self.new_var("a", t, Sect::Input, k));
            k += 1;
        }
        if self.rng.chance(35) {
            for _ in 0..self.rng.range(1, 2) {
                let t = self.param_ty();
                vars.push(self.new_var("o", t, Sect::Output, k));
                k += 1;
            }
        }
        if self.rng.chance(25) {
            let t = self.var_ty(Kind::Function, 0);
            vars.push(self.new_var("io", t, Sect::InOut, k));
            k += 1;
        }
        for _ in 0..self.rng.range(0, 3) {
            let t = self.var_ty(Kind::Function, 0);
            vars.push(self.new_var("t", t, Sect::Local, k));
            k += 1;
        }
        let mut b = self.new_body(Kind::Function, &vars, idx, k);
        b.result = Some((name.clone(), ret_e));
        let mut lines = Vec::new();
        let first = self.ex(&b, ret_e, self.size.depth, false);
        lines.push(format!("    {name} := {first};"));
        let n = self.rng.range(1, (self.size.statements / 2).max(2) as i128) as usize;
        self.block(&mut b, n, 1, &mut lines);
        let sig = PouSig {
            name: name.clone(),
            ret: Some(ret.clone()),
            inputs: sect_list(&vars, Sect::Input),
            outputs: sect_list(&vars, Sect::Output),
            inouts: sect_list(&vars, Sect::InOut),
        };
        self.funcs.push(sig);
        format!(
            "FUNCTION {name} : {}\n{}{}\nEND_FUNCTION\n\n",
            self.types.text(&ret),
            self.var_blocks(&vars, &b.hidden),
            lines.join("\n")
        )
    }

    fn gen_fb(&mut self, idx: usize) -> String {
        let name = format!("Block{idx}");
        let mut vars = Vec::new();
        let mut k = 0;
        for _ in 0..self.rng.range(1, 3) {
            let t = self.param_ty();
            vars.push(self.new_var("in", t, Sect::Input, k));
            k += 1;
        }
        for _ in 0..self.rng.range(1, 3) {
            let t = self.param_ty();
            vars.push(self.new_var("out", t, Sect::Output, k));
            k += 1;
        }
        if self.rng.chance(25) {
            let t = loop {
                let t = self.var_ty(Kind::Function, 0);
                if !t.is_fb(&self.types) {
                    break t;
                }
            };
            vars.push(self.new_var("io", t, Sect::InOut, k));
            k += 1;
        }
        for _ in 0..self.rng.range(1, 4) {
            let t = self.var_ty(Kind::FunctionBlock, idx);
            vars.push(self.new_var("s", t, Sect::Local, k));
            k += 1;
        }
        if self.rng.chance(20) {
            let t = Ty::E(self.elem());
            vars.push(self.new_var("tmp", t, Sect::Temp, k));
            k += 1;
        }
        let mut b = self.new_body(Kind::FunctionBlock, &vars, self.funcs.len(), k);
        let mut lines = Vec::new();
        let n = self.rng.range(2, (self.size.statements / 2).max(3) as i128) as usize;
        self.block(&mut b, n, 1, &mut lines);
        self.types.fbs.push(PouSig {
            name: name.clone(),
            ret: None,
            inputs: sect_list(&vars, Sect::Input),
            outputs: sect_list(&vars, Sect::Output),
            inouts: sect_list(&vars, Sect::InOut),
        });
        format!(
            "FUNCTION_BLOCK {name}\n{}{}\nEND_FUNCTION_BLOCK\n\n",
            self.var_blocks(&vars, &b.hidden),
            lines.join("\n")
        )
    }

    fn gen_program(&mut self, name: &str, statements: usize, globals: &[Var]) -> Prog {
        let mut vars: Vec<Var> = Vec::new();
        let mut k = 0;
        for _ in 0..self.rng.range(0, 3) {
            let e = loop {
                let e = self.elem();
                if class(e) != Class::Char {
                    break e;
                }
            };
            vars.push(self.new_var("in", Ty::E(e), Sect::Input, k));
            k += 1;
        }
        // Constants, some of them used as array bounds.
        let mut consts = Vec::new();
        for _ in 0..self.rng.range(0, 2) {
            let v = self.rng.range(1, 4);
            let cname = format!("N{k}");
            consts.push((cname.clone(), v));
            vars.push(Var {
                name: cname,
                ty: Ty::E(E::Dint),
                sect: Sect::Constant,
                init: Some(v.to_string()),
                location: None,
            });
            k += 1;
        }
        let fb_limit = self.types.fbs.len();
        // Function block instances, called in every cycle.
        for _ in 0..self.rng.range(1, 3) {
            let t = if fb_limit > 0 && self.rng.chance(50) {
                Ty::Fb(Fb::User(self.rng.index(fb_limit)))
            } else {
                Ty::Fb(Fb::Std(self.std_fb()))
            };
            vars.push(self.new_var("v", t, Sect::Local, k));
            k += 1;
        }
        for _ in 0..self.rng.range(2, 5) {
            let t = self.program_var_ty(fb_limit, &consts, false);
            vars.push(self.new_var("out", t, Sect::Output, k));
            k += 1;
        }
        let nlocal = self.rng.range(3, (3 + statements / 3) as i128);
        for _ in 0..nlocal {
            let t = self.program_var_ty(fb_limit, &consts, true);
            vars.push(self.new_var("v", t, Sect::Local, k));
            k += 1;
        }
        // Some elementary locals live in the process image (%I, %Q, %M),
        // with or without an initial value.
        for v in vars.iter_mut() {
            if v.sect == Sect::Local && self.rng.chance(20) {
                if let Ty::E(e) = v.ty {
                    v.location = self.address_for(e);
                }
            }
        }
        for g in globals {
            vars.push(Var {
                init: None,
                ..g.clone()
            });
        }
        let mut b = self.new_body(Kind::Program, &vars, self.funcs.len(), k);
        let mut lines = Vec::new();
        // Call each FB instance at least once, so state is exercised.
        let insts = b.reach.instances.clone();
        for (a, fb) in insts {
            if a.steps.len() == 1 || self.rng.chance(50) {
                self.fb_call(&mut b, &a, fb, 1, &mut lines);
            }
        }
        self.block(&mut b, statements, 1, &mut lines);
        // The trigger of the event task.
        if let Some(g) = self.event_global.clone() {
            let v = if self.rng.chance(50) {
                format!("NOT {g}")
            } else {
                self.cond(&b, 2)
            };
            lines.push(format!("    {g} := {v};"));
        }
        // And each function, where it can be called.
        for i in 0..b.funcs {
            if self.can_call(&b, i) && self.rng.chance(80) {
                let ret = self.funcs[i].ret.clone();
                let call = self.call_text(&b, i, self.size.depth, true);
                let target = ret.and_then(|r| self.write_access(&b, &r));
                match target {
                    Some(a) => {
                        let t = self.render(&b, &a, 1);
                        lines.push(format!("    {t} := {call};"));
                    }
                    None => lines.push(format!("    {call};")),
                }
            }
        }
        let text = format!(
            "PROGRAM {name}\n{}{}\nEND_PROGRAM\n\n",
            self.var_blocks(&vars, &b.hidden),
            lines.join("\n")
        );
        vars.extend(b.hidden);
        Prog { text, vars }
    }

    fn program_var_ty(&mut self, fb_limit: usize, consts: &[(String, i128)], fbs: bool) -> Ty {
        if !consts.is_empty() && self.rng.chance(15) {
            let elem = self.member_ty(1);
            return Ty::Array(self.new_array(elem, Some(consts)));
        }
        loop {
            let t = self.var_ty(Kind::Program, fb_limit);
            if fbs || !t.is_fb(&self.types) {
                return t;
            }
        }
    }

    // ------------------------------------------------------------------
    // Statements.

    fn block(&mut self, b: &mut Body, n: usize, lvl: usize, out: &mut Vec<String>) {
        for _ in 0..n.max(1) {
            self.stmt(b, lvl, out);
        }
    }

    fn inner(&mut self) -> usize {
        self.rng.range(1, 3) as usize
    }

    fn stmt(&mut self, b: &mut Body, lvl: usize, out: &mut Vec<String>) {
        let pad = "    ".repeat(lvl);
        let d = self.size.depth;
        let can_nest = b.nest < 3;
        let can_loop = can_nest && b.loop_depth < b.max_loops;
        // (A circuit unrolls loops: only FOR with constant bounds.)
        let can_while = can_loop && !self.size.circuit;
        let w = [
            40,
            if can_nest { 10 } else { 0 },
            if can_nest { 5 } else { 0 },
            if can_loop { 6 } else { 0 },
            if can_while { 3 } else { 0 },
            if can_while { 3 } else { 0 },
            if b.reach.instances.is_empty() { 0 } else { 12 },
            if b.funcs > 0 { 3 } else { 0 },
            if b.loop_depth > 0 { 4 } else { 0 },
            1,
        ];
        match self.rng.weighted(&w) {
            0 => self.assign(b, &pad, out),
            1 => {
                let c = self.cond(b, d);
                out.push(format!("{pad}IF {c} THEN"));
                b.nest += 1;
                let n = self.inner();
                self.block(b, n, lvl + 1, out);
                while self.rng.chance(30) {
                    let c = self.cond(b, d);
                    out.push(format!("{pad}ELSIF {c} THEN"));
                    let n = self.inner();
                    self.block(b, n, lvl + 1, out);
                }
                if self.rng.chance(50) {
                    out.push(format!("{pad}ELSE"));
                    let n = self.inner();
                    self.block(b, n, lvl + 1, out);
                }
                b.nest -= 1;
                out.push(format!("{pad}END_IF;"));
            }
            2 => self.case(b, lvl, out),
            3 => self.for_loop(b, lvl, out),
            4 | 5 => {
                let g = b.fresh("w");
                b.hidden.push(Var {
                    name: g.clone(),
                    ty: Ty::E(E::Int),
                    sect: Sect::Local,
                    init: None,
                    location: None,
                });
                let n = self.rng.range(1, 6);
                let c = self.cond(b, d.min(2));
                out.push(format!("{pad}{g} := 0;"));
                let repeat = self.rng.chance(50);
                if repeat {
                    out.push(format!("{pad}REPEAT"));
                } else {
                    out.push(format!("{pad}WHILE ({g} < {n}) AND {c} DO"));
                }
                out.push(format!("{pad}    {g} := {g} + 1;"));
                b.nest += 1;
                b.loop_depth += 1;
                let n2 = self.inner();
                self.block(b, n2, lvl + 1, out);
                b.loop_depth -= 1;
                b.nest -= 1;
                if repeat {
                    out.push(format!("{pad}UNTIL ({g} >= {n}) OR {c}"));
                    out.push(format!("{pad}END_REPEAT;"));
                } else {
                    out.push(format!("{pad}END_WHILE;"));
                }
            }
            6 => {
                let (a, fb) = {
                    let i = self.rng.index(b.reach.instances.len());
                    b.reach.instances[i].clone()
                };
                self.fb_call(b, &a, fb, lvl, out);
            }
            7 => {
                let cands: Vec<usize> = (0..b.funcs).filter(|&i| self.can_call(b, i)).collect();
                if cands.is_empty() {
                    return self.assign(b, &pad, out);
                }
                let i = *self.rng.pick(&cands);
                let call = self.call_text(b, i, d, true);
                out.push(format!("{pad}{call};"));
            }
            8 => {
                let c = self.cond(b, d.min(2));
                let word = if self.rng.chance(50) {
                    "EXIT"
                } else {
                    "CONTINUE"
                };
                out.push(format!("{pad}IF {c} THEN"));
                out.push(format!("{pad}    {word};"));
                out.push(format!("{pad}END_IF;"));
            }
            _ => {
                let c = self.cond(b, d.min(2));
                out.push(format!("{pad}IF {c} THEN"));
                out.push(format!("{pad}    RETURN;"));
                out.push(format!("{pad}END_IF;"));
            }
        }
    }

    fn assign(&mut self, b: &mut Body, pad: &str, out: &mut Vec<String>) {
        let d = self.size.depth;
        if let Some((name, t)) = b.result.clone() {
            if self.rng.chance(15) {
                let e = self.ex(b, t, d, false);
                out.push(format!("{pad}{name} := {e};"));
                return;
            }
        }
        // Targets: scalars, and structures and arrays that another
        // variable of the same type can be copied from.
        let root = |a: &Access| match a.steps.first() {
            Some(Step::Name(n)) => n.clone(),
            _ => String::new(),
        };
        let cands: Vec<Access> = b
            .reach
            .values
            .iter()
            .filter(|a| {
                a.writable
                    && match a.ty {
                        Ty::Struct(_) | Ty::Array(_) => b
                            .reach
                            .values
                            .iter()
                            .any(|o| o.ty == a.ty && root(o) != root(a)),
                        _ => self.has_value(b, &a.ty),
                    }
            })
            .cloned()
            .collect();
        if cands.is_empty() {
            if let Some((name, t)) = b.result.clone() {
                let e = self.ex(b, t, d, false);
                out.push(format!("{pad}{name} := {e};"));
            }
            return;
        }
        let a = self.rng.pick(&cands).clone();
        let target = self.render(b, &a, 1);
        let rhs = match &a.ty {
            Ty::E(_) | Ty::Str { .. } => {
                let e = a.ty.scalar(&self.types).unwrap_or(E::Int);
                match self.accumulate(b, &a, e, d) {
                    Some(r) => r,
                    None => self.scalar_rhs(b, e, d),
                }
            }
            Ty::Struct(_) | Ty::Array(_) => {
                let others: Vec<Access> = b
                    .reach
                    .values
                    .iter()
                    .filter(|o| o.ty == a.ty && root(o) != root(&a))
                    .cloned()
                    .collect();
                let o = self.rng.pick(&others).clone();
                self.render(b, &o, 1)
            }
            ty => self.value_of(b, ty, d),
        };
        out.push(format!("{pad}{target} := {rhs};"));
    }

    /// Now and then `x := x op e`: state that changes from cycle to cycle.
    fn accumulate(&mut self, b: &Body, a: &Access, e: E, d: u32) -> Option<String> {
        if !self.rng.chance(20) {
            return None;
        }
        let x = self.render(b, a, 1);
        let d = d.min(2);
        Some(match class(e) {
            Class::Int | Class::Real => {
                let op = *self.rng.pick(&["+", "-", "+", "*"]);
                let y = if op == "*" && class(e) == Class::Int {
                    "2".to_string()
                } else {
                    self.ex(b, e, d, false)
                };
                format!("{x} {op} {y}")
            }
            Class::Bits => {
                let op = *self.rng.pick(&["XOR", "OR", "AND"]);
                format!("{x} {op} {}", self.ex(b, e, d, false))
            }
            Class::Bool => format!("NOT {x}"),
            Class::Dur => format!("{x} + {}", self.ex(b, e, d, false)),
            Class::Str => format!("CONCAT({x}, {})", self.ex(b, e, d, false)),
            _ => return None,
        })
    }

    /// The right-hand side of an assignment to a variable of type `e`:
    /// sometimes a narrower variable (implicit widening) or a call with
    /// outputs and in-outs.
    fn scalar_rhs(&mut self, b: &Body, e: E, d: u32) -> String {
        if self.rng.chance(6) {
            let narrower: Vec<E> = ELEMS
                .iter()
                .map(|&(s, _)| s)
                .filter(|&s| self.allowed(s))
                .filter(|&s| stc_values::implicit_widening(s, e))
                .collect();
            if !narrower.is_empty() {
                let s = *self.rng.pick(&narrower);
                if let Some(a) = self.read_access(b, s, false) {
                    return self.render(b, &a, 1);
                }
            }
        }
        if self.rng.chance(8) {
            let cands: Vec<usize> = (0..b.funcs)
                .filter(|&i| {
                    self.funcs[i]
                        .ret
                        .as_ref()
                        .and_then(|r| r.scalar(&self.types))
                        == Some(e)
                        && self.can_call(b, i)
                })
                .collect();
            if !cands.is_empty() {
                let i = *self.rng.pick(&cands);
                return self.call_text(b, i, d, true);
            }
        }
        self.ex(b, e, d, false)
    }

    fn case(&mut self, b: &mut Body, lvl: usize, out: &mut Vec<String>) {
        let pad = "    ".repeat(lvl);
        let d = self.size.depth;
        let enums: Vec<usize> = b
            .reach
            .values
            .iter()
            .filter_map(|a| match a.ty {
                Ty::Enum(i) => Some(i),
                _ => None,
            })
            .collect();
        let mut arms: Vec<String> = Vec::new();
        let sel;
        if !enums.is_empty() && self.rng.chance(35) {
            let i = *self.rng.pick(&enums);
            sel = self.enum_ex(b, i, d.min(2), true);
            let mut values = self.types.enums[i].values.clone();
            // Shuffle, then group a prefix into arms.
            for j in (1..values.len()).rev() {
                let k = self.rng.index(j + 1);
                values.swap(j, k);
            }
            let used = self.rng.range(1, values.len() as i128) as usize;
            let mut rest = &values[..used];
            while !rest.is_empty() {
                let n = self.rng.range(1, rest.len().min(2) as i128) as usize;
                arms.push(rest[..n].join(", "));
                rest = &rest[n..];
            }
        } else {
            let types = Gen::selector_types();
            let t = if self.rng.chance(60) {
                *self.rng.pick(&[E::Int, E::Dint, E::Usint, E::Sint])
            } else {
                *self.rng.pick(&types)
            };
            let x = self.ex(b, t, d.min(2), true);
            let wrapped = self.rng.chance(40);
            let mut sel_text = if wrapped {
                if class(t) == Class::Bits {
                    format!("({x} AND 16#7)")
                } else {
                    format!("({x} MOD {})", self.rng.range(2, 9))
                }
            } else {
                x
            };
            let (lo_t, hi_t) = range(t);
            let (lo, hi) = (lo_t.max(-8), hi_t.min(24));
            let npts = self.rng.range(2, 8) as usize;
            let mut pts: Vec<i128> = (0..npts).map(|_| self.rng.range(lo, hi)).collect();
            // A bare selector may be a variable of a subrange of `t`, and a
            // label outside its range is an error (E0702): then the
            // selector is made an expression of `t` itself (no random draw,
            // so the rest of the program is what it was).
            if !wrapped && self.types.subs.iter().any(|s| s.base == t) {
                sel_text = if class(t) == Class::Bits {
                    format!("({sel_text} AND 16#FF)")
                } else {
                    format!("({sel_text} MOD 100)")
                };
            }
            sel = sel_text;
            pts.sort_unstable();
            pts.dedup();
            let mut rest = &pts[..];
            while !rest.is_empty() {
                let n = self.rng.range(1, rest.len().min(3) as i128) as usize;
                let group = &rest[..n];
                let label = if n >= 2 && self.rng.chance(50) {
                    format!("{}..{}", group[0], group[n - 1])
                } else {
                    group
                        .iter()
                        .map(|v| v.to_string())
                        .collect::<Vec<_>>()
                        .join(", ")
                };
                arms.push(label);
                rest = &rest[n..];
            }
        }
        out.push(format!("{pad}CASE {sel} OF"));
        b.nest += 1;
        for label in arms {
            out.push(format!("{pad}    {label}:"));
            let n = self.inner();
            self.block(b, n, lvl + 2, out);
        }
        if self.rng.chance(50) {
            out.push(format!("{pad}ELSE"));
            let n = self.inner();
            self.block(b, n, lvl + 1, out);
        }
        b.nest -= 1;
        out.push(format!("{pad}END_CASE;"));
    }

    fn for_loop(&mut self, b: &mut Body, lvl: usize, out: &mut Vec<String>) {
        let pad = "    ".repeat(lvl);
        let d = self.size.depth.min(2);
        let t = if self.rng.chance(70) {
            *self
                .rng
                .pick(&[E::Sint, E::Int, E::Dint, E::Lint, E::Int, E::Dint])
        } else {
            *self.rng.pick(INTS)
        };
        let (lo_t, hi_t) = range(t);
        let name = b.fresh("k");
        b.hidden.push(Var {
            name: name.clone(),
            ty: Ty::E(t),
            sect: Sect::Local,
            init: None,
            location: None,
        });
        let window = |g: &mut Gen| g.rng.range(lo_t.max(-10), hi_t.min(20));
        // Arrays whose index range the loop can walk.
        let arrays: Vec<(i128, i128)> = b
            .reach
            .values
            .iter()
            .filter_map(|a| match a.steps.last() {
                Some(Step::Index(dims)) => Some(dims.clone()),
                _ => None,
            })
            .flatten()
            .filter(|&(lo, hi)| lo >= lo_t && hi <= hi_t)
            .collect();
        // (Run-time bounds and steps, 5 and 6, are not for a circuit.)
        let mut pick = self.rng.below(8);
        if self.size.circuit && (pick == 5 || pick == 6) {
            pick = 7;
        }
        let (start, end, step, lo, hi) = match pick {
            0 | 1 if !arrays.is_empty() => {
                let (lo, hi) = *self.rng.pick(&arrays);
                if is_signed(t) && self.rng.chance(30) {
                    (
                        hi.to_string(),
                        lo.to_string(),
                        Some("-1".to_string()),
                        lo,
                        hi,
                    )
                } else {
                    (lo.to_string(), hi.to_string(), None, lo, hi)
                }
            }
            2 if is_signed(t) => {
                let s = window(self);
                let e = (s - self.rng.range(0, 10)).max(lo_t);
                let st = -self.rng.range(1, 3);
                (s.to_string(), e.to_string(), Some(st.to_string()), e, s)
            }
            3 => {
                // Up to the largest value of the type: must still end.
                let s = hi_t - self.rng.range(0, 6);
                let st = self.rng.range(1, 2);
                (
                    s.to_string(),
                    hi_t.to_string(),
                    Some(st.to_string()),
                    s,
                    hi_t,
                )
            }
            4 if is_signed(t) && t != E::Lint => {
                let s = lo_t + self.rng.range(0, 6);
                (
                    s.to_string(),
                    lo_t.to_string(),
                    Some("-1".to_string()),
                    lo_t,
                    s,
                )
            }
            5 => {
                let s = window(self);
                let a = window(self);
                let c = (a + 10).min(hi_t);
                let x = self.ex(b, t, d, true);
                (
                    s.to_string(),
                    format!("LIMIT({a}, {x}, {c})"),
                    None,
                    s.min(a),
                    c.max(s),
                )
            }
            6 => {
                let s = window(self);
                let e = (s + self.rng.range(0, 10)).min(hi_t);
                let x = self.ex(b, t, d.min(1), true);
                (
                    s.to_string(),
                    e.to_string(),
                    Some(format!("LIMIT(1, {x}, 3)")),
                    s,
                    e,
                )
            }
            _ => {
                let s = window(self);
                let e = (s + self.rng.range(-1, 10)).clamp(lo_t, hi_t);
                let st = if self.rng.chance(60) {
                    None
                } else {
                    Some(self.rng.range(1, 3).to_string())
                };
                (s.to_string(), e.to_string(), st, s, e.max(s))
            }
        };
        let by = step.map(|s| format!(" BY {s}")).unwrap_or_default();
        out.push(format!("{pad}FOR {name} := {start} TO {end}{by} DO"));
        b.loops.push(crate::gen::LoopVar {
            name,
            ty: t,
            lo,
            hi,
        });
        b.nest += 1;
        b.loop_depth += 1;
        let n = self.inner();
        self.block(b, n, lvl + 1, out);
        b.loop_depth -= 1;
        b.nest -= 1;
        b.loops.pop();
        out.push(format!("{pad}END_FOR;"));
    }

    /// A call of an FB instance with some of its inputs, its in-outs and
    /// some `=>` outputs.
    fn fb_call(&mut self, b: &mut Body, a: &Access, fb: Fb, lvl: usize, out: &mut Vec<String>) {
        let pad = "    ".repeat(lvl);
        let d = self.size.depth.min(2);
        let inouts = match fb {
            Fb::User(i) => self.types.fbs[i].inouts.clone(),
            Fb::Std(_) => Vec::new(),
        };
        let mut args = Vec::new();
        let en_eno = self.rng.chance(8);
        if en_eno {
            args.push(format!("EN := {}", self.cond(b, d)));
        }
        for (name, ty) in &inouts {
            match self.write_access(b, ty) {
                Some(p) => {
                    let p = self.render(b, &p, 1);
                    args.push(format!("{name} := {p}"));
                }
                None => return,
            }
        }
        let inputs = self.types.fb_inputs(fb);
        let k = self.rng.index(inputs.len());
        for (i, (name, ty)) in inputs.iter().enumerate() {
            if i != k && self.rng.chance(30) {
                continue;
            }
            let v = match (name.as_str(), ty) {
                ("PT", Ty::E(t)) if self.rng.chance(70) => {
                    let p = if *t == E::Ltime { "LTIME#" } else { "T#" };
                    format!("{p}{}ms", self.rng.range(0, 8) * 10)
                }
                ("PV", Ty::E(t)) if self.rng.chance(70) => {
                    let v = self.rng.range(0, 5);
                    self.int_lit(*t, v, false)
                }
                _ => self.value_of(b, ty, d),
            };
            args.push(format!("{name} := {v}"));
        }
        for (name, ty) in self.types.fb_outputs(fb) {
            if self.rng.chance(25) {
                if let Some(p) = self.write_access(b, &ty) {
                    let p = self.render(b, &p, 1);
                    args.push(format!("{name} => {p}"));
                }
            }
        }
        if en_eno {
            if let Some(p) = self.eno(b) {
                args.push(p);
            }
        }
        let inst = self.render(b, a, 1);
        out.push(format!("{pad}{inst}({});", args.join(", ")));
    }
}

/// A generated PROGRAM: its text and its variables (for the options).
struct Prog {
    text: String,
    vars: Vec<Var>,
}

fn sect_list(vars: &[Var], sect: Sect) -> Vec<(String, Ty)> {
    vars.iter()
        .filter(|v| v.sect == sect)
        .map(|v| (v.name.clone(), v.ty.clone()))
        .collect()
}
