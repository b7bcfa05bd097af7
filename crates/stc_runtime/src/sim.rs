//! A simulation: the machine, the plan, the watched places and the inputs
//! (`--set`, stimulus rows), advanced one cycle at a time.
//!
//! One cycle k (1-based) at time (k - 1) * tick:
//! 1. the stimulus rows of cycle k are written;
//! 2. the SINGLE variables of event tasks are sampled (a task fires when
//!    its variable is TRUE now and was FALSE at the start of the previous
//!    cycle; before cycle 1 every SINGLE counts as FALSE);
//! 3. the due tasks run in plan order, then the program instances without
//!    a task; each program instance has its input connections copied in
//!    just before it runs and its output connections copied out just after.
//!
//! A fault stops the cycle where it happens. [`run`] then reports the last
//! completed cycle: as the simulation is deterministic, it replays the
//! cycles before the fault on a fresh machine rather than copying the
//! memory before every cycle, so a run without faults pays nothing for it.

use std::sync::Arc;

use stc_ir::model::{Model, ProgramInst, Source, TypeRef, VarKind};
use stc_ir::FaultKind;
use stc_syntax::literal::AddrArea;
use stc_values::{convert, Value};
use stc_vm::{Image, Machine, VmFault};

use crate::engine::{read_value, write_value, Engine, Memory};

use crate::error::{Error, Result};
use crate::path::{Place, Scope, View};
use crate::report::Report;
use crate::retain::{RetainError, Retained};
use crate::schedule::{choose, Plan};
use crate::stimulus::Stimulus;
use crate::value::{parse_for, read};

/// The default watchdog: VM instructions per program run.
pub const DEFAULT_MAX_STEPS: u64 = 100_000_000;

/// How to set a simulation up (the options of `stc run` that are not about
/// printing).
#[derive(Clone, Debug)]
pub struct Options {
    /// `--config NAME`
    pub config: Option<String>,
    /// `--program TYPE`
    pub program: Option<String>,
    /// `--tick`, in nanoseconds; `None`: the default of the plan.
    pub tick_ns: Option<i64>,
    /// `--set PATH=VALUE`, in order.
    pub sets: Vec<String>,
    /// `--watch` paths; `None`: the default list.
    pub watch: Option<Vec<String>>,
    /// `--max-steps`
    pub max_steps: u64,
}

impl Default for Options {
    fn default() -> Self {
        Options {
            config: None,
            program: None,
            tick_ns: None,
            sets: Vec::new(),
            watch: None,
            max_steps: DEFAULT_MAX_STEPS,
        }
    }
}

/// Writes to do before a cycle: the rows of one cycle of a stimulus file.
#[derive(Clone, Debug)]
struct Inputs {
    cycle: u64,
    writes: Vec<(Place, Value)>,
}

pub struct Simulation {
    /// The engine's program model (shared with it, read only).
    model: Arc<Model>,
    engine: Box<dyn Engine>,
    plan: Plan,
    watch: Vec<Place>,
    sets: Vec<(Place, Value)>,
    stimulus: Vec<Inputs>,
    next_input: usize,
    /// Per task of the plan: its SINGLE at the start of the previous cycle.
    single_prev: Vec<bool>,
    completed: u64,
    max_steps: u64,
    fired: Vec<bool>,
    order: Vec<usize>,
    /// Per instance of the plan: the task it runs in (its watchdog budget).
    task_of: Vec<Option<usize>>,
    /// The retained variables restored at a warm start, and their image:
    /// [`Simulation::restart`] restores them again.
    warm: Option<(Retained, Vec<u8>)>,
    /// Real time: a clock in nanoseconds that measures the tasks of each
    /// cycle ([`Simulation::measure_with`]); never set in simulation.
    timer: Option<Box<dyn FnMut() -> u64>>,
    times: CycleTimes,
}

/// When the programs of the last cycle ran, on the clock given to
/// [`Simulation::measure_with`] (nanoseconds).
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct CycleTimes {
    /// When the first program started and the last one ended.
    pub start: u64,
    pub end: u64,
    /// Per task of the plan: when its first program started and its last
    /// one ended in this cycle, `None` when it did not run.
    pub tasks: Vec<Option<(u64, u64)>>,
}

impl Simulation {
    /// Chooses what runs, resolves every path, reads every value, and
    /// applies `--set`: all mistakes in the options are found here, before
    /// anything runs.
    pub fn new(
        image: Arc<Image>,
        opts: &Options,
        stimulus: Option<&Stimulus>,
    ) -> Result<Simulation> {
        Simulation::with_engine(Box::new(Machine::new(image)), opts, stimulus)
    }

    /// The same on any engine ([`crate::engine`]).
    pub fn with_engine(
        engine: Box<dyn Engine>,
        opts: &Options,
        stimulus: Option<&Stimulus>,
    ) -> Result<Simulation> {
        let model_arc = Arc::clone(engine.model());
        let model = &*model_arc;
        let chosen = choose(model, opts.config.as_deref(), opts.program.as_deref())?;
        let plan = Plan::new(model, chosen, opts.tick_ns)?;
        let scope = Scope {
            model,
            instances: &plan.instances,
            config: plan.config,
        };

        let mut sets = Vec::new();
        for s in &opts.sets {
            let (path, value) = s
                .split_once('=')
                .ok_or_else(|| Error::Option(format!("--set `{s}`: expected PATH=VALUE")))?;
            let place = writable(scope.resolve(path)?)?;
            let v = parse_for(model, &place.view, value)
                .map_err(|e| Error::Value(format!("--set {}: {e}", place.name)))?;
            sets.push((place, v));
        }

        let mut inputs: Vec<Inputs> = Vec::new();
        if let Some(st) = stimulus {
            let err = |line: usize, message: String| Error::Stimulus {
                file: st.file.clone(),
                line,
                message,
            };
            let mut columns = Vec::new();
            for c in &st.columns {
                let place = scope
                    .resolve(c)
                    .and_then(writable)
                    .map_err(|e| err(st.header_line, e.to_string()))?;
                columns.push(place);
            }
            for row in &st.rows {
                let cycle = row.at.cycle(plan.tick_ns).ok_or_else(|| {
                    let when = match row.at {
                        crate::stimulus::At::Time(t) => {
                            stc_syntax::literal::format_duration(t, false)
                        }
                        crate::stimulus::At::Cycle(c) => c.to_string(),
                    };
                    err(
                        row.line,
                        format!(
                            "{when} is not the time of a cycle with a tick of {}",
                            stc_syntax::literal::format_duration(plan.tick_ns, false)
                        ),
                    )
                })?;
                let mut writes = Vec::new();
                for (place, cell) in columns.iter().zip(&row.cells) {
                    let Some(text) = cell else { continue };
                    let v = parse_for(model, &place.view, text)
                        .map_err(|e| err(row.line, format!("{}: {e}", place.name)))?;
                    writes.push((place.clone(), v));
                }
                match inputs.last_mut() {
                    Some(last) if last.cycle == cycle => last.writes.extend(writes),
                    _ => inputs.push(Inputs { cycle, writes }),
                }
            }
        }

        let watch = match &opts.watch {
            Some(paths) => {
                let mut out: Vec<Place> = Vec::new();
                for p in paths {
                    let place = scope.resolve(p)?;
                    if !out.iter().any(|q| q.name == place.name) {
                        out.push(place);
                    }
                }
                out
            }
            None => default_watch(&scope),
        };

        let tasks = plan.tasks.len();
        let task_of = task_of(&plan);
        let mut sim = Simulation {
            model: Arc::clone(&model_arc),
            engine,
            plan,
            watch,
            sets,
            stimulus: inputs,
            next_input: 0,
            single_prev: vec![false; tasks],
            completed: 0,
            max_steps: opts.max_steps,
            fired: vec![false; tasks],
            order: Vec::new(),
            task_of,
            warm: None,
            timer: None,
            times: CycleTimes::default(),
        };
        sim.apply_sets()?;
        Ok(sim)
    }

    fn apply_sets(&mut self) -> Result<()> {
        for (place, v) in &self.sets {
            if !write(&self.model, self.engine.as_mut(), place, v) {
                return Err(Error::Value(format!(
                    "--set {}: the variable is outside the memory",
                    place.name
                )));
            }
        }
        Ok(())
    }

    /// Back to the state before the first cycle (after a warm start's
    /// restore and `--set`).
    pub fn restart(&mut self) {
        self.engine.reset();
        self.next_input = 0;
        self.single_prev.fill(false);
        self.completed = 0;
        // The same writes succeeded on the same fresh memory before.
        if let Some((r, image)) = &self.warm {
            let _ = r.restore(self.engine.as_mut(), image);
        }
        let _ = self.apply_sets();
    }

    /// Real time: measures the programs of every cycle with `clock`
    /// (nanoseconds from any fixed start); see [`Simulation::times`].
    pub fn measure_with(&mut self, clock: Box<dyn FnMut() -> u64>) {
        self.times.tasks = vec![None; self.plan.tasks.len()];
        self.timer = Some(clock);
    }

    /// When the programs of the last cycle ran (all zero unless measured).
    pub fn times(&self) -> &CycleTimes {
        &self.times
    }

    /// The retained variables of what runs ([`crate::retain`]).
    pub fn retained(&self) -> Retained {
        Retained::new(&self.model, &self.plan)
    }

    /// The image of the retained variables `r` after the last completed
    /// cycle.
    pub fn save_retained(&self, r: &Retained) -> Option<Vec<u8>> {
        r.save(self.engine.as_ref(), self.completed)
    }

    /// A warm start, before the first cycle: restores the retained
    /// variables from `image` (checked whole first: on an error nothing is
    /// changed), then applies `--set` again so the command line wins.
    /// Returns the cycle the image was taken after.
    pub fn warm_start(&mut self, r: Retained, image: Vec<u8>) -> Result<u64, RetainError> {
        let cycle = r.restore(self.engine.as_mut(), &image)?;
        self.warm = Some((r, image));
        // The same writes succeeded on this memory before.
        let _ = self.apply_sets();
        Ok(cycle)
    }

    pub fn plan(&self) -> &Plan {
        &self.plan
    }

    /// The engine the program runs on.
    pub fn engine(&self) -> &dyn Engine {
        self.engine.as_ref()
    }

    /// The engine, to exchange the process image between cycles.
    pub fn engine_mut(&mut self) -> &mut dyn Engine {
        self.engine.as_mut()
    }

    /// The program model.
    pub fn model(&self) -> &Arc<Model> {
        &self.model
    }

    /// What paths are resolved against in this run.
    pub fn scope(&self) -> Scope<'_> {
        Scope {
            model: &self.model,
            instances: &self.plan.instances,
            config: self.plan.config,
        }
    }

    /// The watched places, in report order.
    pub fn watch(&self) -> &[Place] {
        &self.watch
    }

    /// Cycles completed so far.
    pub fn completed(&self) -> u64 {
        self.completed
    }

    /// The last cycle whose time is a valid TIME.
    pub fn last_cycle(&self) -> u64 {
        (i64::MAX / self.plan.tick_ns) as u64 + 1
    }

    /// Runs the next cycle.
    pub fn run_cycle(&mut self) -> Result<(), VmFault> {
        let k = self.completed + 1;
        let now = self.plan.time_of(k).unwrap_or(i64::MAX);

        while let Some(inputs) = self.stimulus.get(self.next_input) {
            if inputs.cycle > k {
                break;
            }
            for (place, v) in &inputs.writes {
                write(&self.model, self.engine.as_mut(), place, v);
            }
            self.next_input += 1;
        }

        for (i, t) in self.plan.tasks.iter().enumerate() {
            self.fired[i] = false;
            if let Some(Source::Addr { offset, ty }) = &t.single {
                let v = read_value(self.engine.as_ref(), &self.model, *offset, *ty)
                    .and_then(|v| v.as_int())
                    .is_some_and(|i| i != 0);
                self.fired[i] = v && !self.single_prev[i];
                self.single_prev[i] = v;
            }
        }

        let mut order = std::mem::take(&mut self.order);
        self.plan.order_into(k, &self.fired, &mut order);
        let result = self.run_instances(&order, now);
        self.order = order;
        result?;
        self.completed = k;
        Ok(())
    }

    fn run_instances(&mut self, order: &[usize], now: i64) -> Result<(), VmFault> {
        // The watchdog budget is per task and cycle (a task-less program
        // has its own).
        let mut used = vec![0u64; self.plan.tasks.len()];
        if let Some(clock) = &mut self.timer {
            let t = clock();
            self.times.start = t;
            self.times.end = t;
            self.times.tasks.fill(None);
        }
        for &i in order {
            let started = self.timer.as_mut().map(|c| c());
            let task = self.task_of.get(i).copied().flatten();
            let budget = match task {
                Some(t) => self.max_steps.saturating_sub(used[t]),
                None => self.max_steps,
            };
            let inst = &self.plan.instances[i];
            for (off, ty, Source::Addr { offset, ty: sty }) in &inst.inputs {
                let dst = inst.offset.wrapping_add(*off);
                copy(&self.model, self.engine.as_mut(), *offset, *sty, dst, *ty)
                    .map_err(|k| connection_fault(&self.model, inst, k))?;
            }
            let n = match self.engine.run_program(inst, now, budget) {
                Ok(n) => n,
                Err(mut f) => {
                    if f.instance.is_none() {
                        f.instance = Some(
                            f.instance_at
                                .and_then(|(at, pou)| self.scope().instance_path(at, pou))
                                .unwrap_or_else(|| inst.name.clone()),
                        );
                    }
                    return Err(f);
                }
            };
            if let Some(t) = task {
                used[t] += n;
            }
            for (off, ty, Source::Addr { offset, ty: dty }) in &inst.outputs {
                let src = inst.offset.wrapping_add(*off);
                copy(&self.model, self.engine.as_mut(), src, *ty, *offset, *dty)
                    .map_err(|k| connection_fault(&self.model, inst, k))?;
            }
            if let (Some(clock), Some(s)) = (&mut self.timer, started) {
                let e = clock();
                self.times.end = e;
                if let Some(slot) = task.and_then(|t| self.times.tasks.get_mut(t)) {
                    *slot = Some(slot.map_or((s, e), |(s0, _)| (s0, e)));
                }
            }
        }
        Ok(())
    }

    /// The watched values now, as the report of the last completed cycle.
    pub fn report(&self) -> Report {
        let e = self.engine.as_ref();
        Report {
            cycle: self.completed,
            time_ns: if self.completed == 0 {
                0
            } else {
                self.plan.time_of(self.completed).unwrap_or(i64::MAX)
            },
            values: self
                .watch
                .iter()
                .map(|p| {
                    let v = match p.loc.address(e) {
                        Some(a) => read(&self.model, e, a, &p.view),
                        None => crate::value::Shown::Unreadable,
                    };
                    (p.name.clone(), v)
                })
                .collect(),
        }
    }
}

/// For each instance of a plan, the task it runs in.
fn task_of(plan: &Plan) -> Vec<Option<usize>> {
    let mut out = vec![None; plan.instances.len()];
    for (t, task) in plan.tasks.iter().enumerate() {
        for &i in &task.programs {
            if let Some(slot) = out.get_mut(i) {
                *slot = Some(t);
            }
        }
    }
    out
}

fn writable(place: Place) -> Result<Place> {
    if place.constant {
        Err(Error::Path(format!(
            "`{}` is a CONSTANT and cannot be assigned",
            place.name
        )))
    } else {
        Ok(place)
    }
}

/// Writes a value to a place; false when it is not in memory.
pub fn write(model: &Model, engine: &mut dyn Memory, place: &Place, v: &Value) -> bool {
    let (Some(addr), View::Type(ty)) = (place.loc.address(engine), &place.view) else {
        return false;
    };
    write_value(engine, model, addr, *ty, v)
}

/// Copies a connection: bytes when the types are the same, else the value
/// converted (a program input INT from a SINT global).
fn copy(
    model: &Model,
    m: &mut dyn Engine,
    src: u32,
    src_ty: TypeRef,
    dst: u32,
    dst_ty: TypeRef,
) -> Result<(), FaultKind> {
    let (Some(sd), Some(dd)) = (
        model.types.get(src_ty as usize),
        model.types.get(dst_ty as usize),
    ) else {
        return Ok(());
    };
    if src_ty == dst_ty || sd == dd {
        let n = model.type_size(src_ty).min(u32::MAX as u64) as u32;
        // Most connections are scalars: no allocation for them.
        let mut small = [0u8; 16];
        if let Some(b) = m.bytes(src, n) {
            if b.len() <= small.len() {
                small[..b.len()].copy_from_slice(b);
                if let Some(d) = m.bytes_mut(dst, n) {
                    d.copy_from_slice(&small[..n as usize]);
                }
            } else {
                let b = b.to_vec();
                if let Some(d) = m.bytes_mut(dst, n) {
                    d.copy_from_slice(&b);
                }
            }
        }
        return Ok(());
    }
    let elem = |t: TypeRef| model.scalar_of(t);
    let Some(v) = read_value(m, model, src, src_ty) else {
        return Ok(());
    };
    let v = match (elem(src_ty), elem(dst_ty)) {
        (Some(from), Some(to)) if from != to => {
            convert(from, to, &v).map_err(FaultKind::from_value_fault)?
        }
        _ => v,
    };
    write_value(m, model, dst, dst_ty, &v);
    Ok(())
}

fn connection_fault(model: &Model, inst: &ProgramInst, kind: FaultKind) -> VmFault {
    let mut f = VmFault::at(
        kind,
        model
            .pous
            .get(inst.pou as usize)
            .map_or("?", |p| p.name.as_str()),
        "<configuration>",
        0,
        0,
    );
    f.instance = Some(inst.name.clone());
    f
}

/// The default watch list: every VAR_OUTPUT of every program instance (in
/// configuration order, then declaration order), then every located output
/// variable (`%Q`): globals in declaration order, then those declared in
/// the program instances.
pub fn default_watch(scope: &Scope) -> Vec<Place> {
    let model = scope.model;
    let mut out: Vec<Place> = Vec::new();
    let add = |out: &mut Vec<Place>, path: String| {
        if let Ok(p) = scope.resolve(&path) {
            if !out.iter().any(|q| q.name.eq_ignore_ascii_case(&p.name)) {
                out.push(p);
            }
        }
    };
    for inst in scope.instances {
        let Some(pou) = model.pous.get(inst.pou as usize) else {
            continue;
        };
        for v in &pou.vars {
            if v.kind == VarKind::Output && !v.in_frame {
                add(&mut out, format!("{}.{}", inst.name, v.name));
            }
        }
    }
    for g in &model.globals {
        let visible = g.config.is_none() || g.config == scope.config;
        if visible
            && g.location
                .as_ref()
                .is_some_and(|l| l.area == AddrArea::Output)
        {
            add(&mut out, g.name.clone());
        }
    }
    for inst in scope.instances {
        let Some(pou) = model.pous.get(inst.pou as usize) else {
            continue;
        };
        for v in &pou.vars {
            if v.location
                .as_ref()
                .is_some_and(|l| l.area == AddrArea::Output)
            {
                add(&mut out, format!("{}.{}", inst.name, v.name));
            }
        }
    }
    out
}

/// Something that paces cycles: nothing in simulation, the wall clock in
/// real time ([`crate::realtime`]).
pub trait Pacer {
    /// Waits until cycle `k` is due; `false` stops the run before it.
    fn before(&mut self, cycle: u64) -> bool;
    /// Cycle `k` has run.
    fn after(&mut self, cycle: u64);
}

/// Simulated time: cycles run back to back.
pub struct Unpaced;

impl Pacer for Unpaced {
    fn before(&mut self, _cycle: u64) -> bool {
        true
    }
    fn after(&mut self, _cycle: u64) {}
}

/// What a controller does between cycles: exchange the process image with
/// the I/O before a cycle, save retained variables after one. Nothing in
/// simulation.
pub trait Between {
    /// Cycle `k` is due and about to run.
    fn before_cycle(&mut self, _sim: &mut Simulation, _k: u64) {}
    /// Cycle `k` has completed (not called for a cycle that faulted).
    fn after_cycle(&mut self, _sim: &mut Simulation, _k: u64) {}
    /// The run ends without a fault, after cycle `sim.completed()`.
    fn at_end(&mut self, _sim: &mut Simulation) {}
    /// Cycle `k` faulted and the run stops (the memory is that of the
    /// faulting cycle).
    fn faulted(&mut self, _sim: &mut Simulation, _k: u64, _fault: &VmFault) {}
}

/// Nothing between cycles.
pub struct Nothing;

impl Between for Nothing {}

/// Runs up to `cycles` cycles (`None`: until the pacer stops), passing
/// each report to print to `emit`: with `trace` one after every cycle,
/// else one at the end. On a fault the last report is that of the last
/// completed cycle (cycle 0, the state before the first cycle, when the
/// first one faults), and the fault is returned.
pub fn run(
    sim: &mut Simulation,
    cycles: Option<u64>,
    trace: bool,
    pacer: &mut dyn Pacer,
    emit: &mut dyn FnMut(&Report),
) -> Result<(), VmFault> {
    run_between(sim, cycles, trace, pacer, emit, &mut Nothing)
}

/// [`run`], with `between` called around every cycle.
pub fn run_between(
    sim: &mut Simulation,
    cycles: Option<u64>,
    trace: bool,
    pacer: &mut dyn Pacer,
    emit: &mut dyn FnMut(&Report),
    between: &mut dyn Between,
) -> Result<(), VmFault> {
    let mut emitted_last = false;
    loop {
        let k = sim.completed() + 1;
        if cycles.is_some_and(|n| k > n) || k > sim.last_cycle() || !pacer.before(k) {
            break;
        }
        between.before_cycle(sim, k);
        match sim.run_cycle() {
            Ok(()) => {
                between.after_cycle(sim, k);
                pacer.after(k);
                emitted_last = trace;
                if trace {
                    emit(&sim.report());
                }
            }
            Err(fault) => {
                between.faulted(sim, k, &fault);
                if !emitted_last {
                    sim.restart();
                    for _ in 1..k {
                        if sim.run_cycle().is_err() {
                            break;
                        }
                    }
                    emit(&sim.report());
                }
                return Err(fault);
            }
        }
    }
    between.at_end(sim);
    if !emitted_last {
        emit(&sim.report());
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::report::Format;
    use crate::testing::*;

    fn sim(opts: Options, stimulus: Option<&str>) -> Result<Simulation> {
        let st = stimulus.map(|t| Stimulus::parse("s.csv", t).unwrap());
        Simulation::new(Arc::new(sample()), &opts, st.as_ref())
    }

    fn watching(paths: &[&str]) -> Options {
        Options {
            watch: Some(paths.iter().map(|s| s.to_string()).collect()),
            ..Options::default()
        }
    }

    fn json_run(s: &mut Simulation, cycles: u64, trace: bool) -> (String, Option<VmFault>) {
        let mut out = String::new();
        let r = run(s, Some(cycles), trace, &mut Unpaced, &mut |r: &Report| {
            out.push_str(&r.render(Format::Json))
        });
        (out, r.err())
    }

    #[test]
    fn the_default_watch_list_is_program_outputs_then_located_outputs() {
        let s = sim(Options::default(), None).unwrap();
        let names: Vec<&str> = s.watch().iter().map(|p| p.name.as_str()).collect();
        assert_eq!(
            names,
            [
                "main.count",
                "main.color",
                "main.x",
                "p2.n",
                "p3.n",
                "lamp",
                "main.lamp_local"
            ]
        );
        let s = sim(
            Options {
                program: Some("main".into()),
                ..Options::default()
            },
            None,
        )
        .unwrap();
        let names: Vec<&str> = s.watch().iter().map(|p| p.name.as_str()).collect();
        assert_eq!(
            names,
            ["Main.count", "Main.color", "Main.x", "Main.lamp_local"]
        );
    }

    #[test]
    fn set_writes_before_the_first_cycle_and_reports_follow_the_watch_order() {
        let mut s = sim(
            Options {
                sets: vec![
                    "main.name='hi'".into(),
                    "MAIN.color=Color#Green".into(),
                    "main.m[2,1]=-4".into(),
                    "%IX0.0=TRUE".into(),
                    "main.tmr.PT=T#2s".into(),
                ],
                ..watching(&[
                    "main.m[2]",
                    "main.color",
                    "main.name",
                    "main.sensor",
                    "main.tmr.pt",
                    "main.color",
                ])
            },
            None,
        )
        .unwrap();
        assert_eq!(
            s.report().to_json(),
            "{\"cycle\":0,\"time\":\"T#0s\",\"values\":{\"main.m[2]\":[-4,0,0],\
             \"main.color\":\"Color#Green\",\"main.name\":\"hi\",\"main.sensor\":true,\
             \"main.tmr.PT\":\"T#2s\"}}\n"
        );
        let (out, fault) = json_run(&mut s, 3, false);
        assert_eq!(fault, None);
        assert!(
            out.starts_with("{\"cycle\":3,\"time\":\"T#20ms\","),
            "{out}"
        );
        assert_eq!(out.lines().count(), 1);
    }

    #[test]
    fn bad_options_are_errors_before_anything_runs() {
        let e = |sets: &[&str]| {
            sim(
                Options {
                    sets: sets.iter().map(|s| s.to_string()).collect(),
                    ..Options::default()
                },
                None,
            )
            .err()
            .map(|e| e.to_string())
        };
        assert_eq!(e(&["g"]), Some("--set `g`: expected PATH=VALUE".into()));
        assert_eq!(
            e(&["K=1"]),
            Some("`K` is a CONSTANT and cannot be assigned".into())
        );
        assert_eq!(
            e(&["g=abc"]),
            Some("--set g: `abc` cannot be read as INT (expected an ST literal within the type's range)".into())
        );
        assert_eq!(
            e(&["nope=1"]),
            Some("unknown variable `nope`: `nope` is neither a program instance (main, p2, p3) nor a global variable".into())
        );
        assert_eq!(e(&["main.name='a=b'"]), None);
        let watch = sim(watching(&["main.zz"]), None)
            .err()
            .map(|e| e.to_string());
        assert_eq!(
            watch,
            Some("unknown variable `main.zz`: `main` has no member `zz`".into())
        );
        let stim = |text: &str| {
            sim(Options::default(), Some(text))
                .err()
                .map(|e| e.to_string())
        };
        assert_eq!(
            stim("cycle,main.zz\n1,2\n"),
            Some("s.csv:1: unknown variable `main.zz`: `main` has no member `zz`".into())
        );
        assert_eq!(
            stim("cycle,g\n1,2\n2,x\n"),
            Some("s.csv:3: g: `x` cannot be read as INT (expected an ST literal within the type's range)".into())
        );
        assert_eq!(
            stim("cycle,K\n"),
            Some("s.csv:1: `K` is a CONSTANT and cannot be assigned".into())
        );
    }

    #[test]
    fn stimuli_events_and_connections_follow_the_cycle_order() {
        // p2 runs on rising edges of trig (sampled at cycle start, after
        // the stimulus), copying g in; p3 runs every cycle, copying the
        // SINT g_sint into its INT input.
        let stimulus =
            "cycle,g,trig,g_sint\n1,1,FALSE,-1\n2,2,TRUE,-2\n3,3,,-3\n4,4,FALSE,\n5,5,TRUE,-5\n";
        let mut s = sim(watching(&["p2.inp", "p3.inp", "trig"]), Some(stimulus)).unwrap();
        let (out, fault) = json_run(&mut s, 6, true);
        assert_eq!(fault, None);
        assert_eq!(
            out,
            "{\"cycle\":1,\"time\":\"T#0s\",\"values\":{\"p2.inp\":0,\"p3.inp\":-1,\"trig\":false}}\n\
             {\"cycle\":2,\"time\":\"T#10ms\",\"values\":{\"p2.inp\":2,\"p3.inp\":-2,\"trig\":true}}\n\
             {\"cycle\":3,\"time\":\"T#20ms\",\"values\":{\"p2.inp\":2,\"p3.inp\":-3,\"trig\":true}}\n\
             {\"cycle\":4,\"time\":\"T#30ms\",\"values\":{\"p2.inp\":2,\"p3.inp\":-3,\"trig\":false}}\n\
             {\"cycle\":5,\"time\":\"T#40ms\",\"values\":{\"p2.inp\":5,\"p3.inp\":-5,\"trig\":true}}\n\
             {\"cycle\":6,\"time\":\"T#50ms\",\"values\":{\"p2.inp\":5,\"p3.inp\":-5,\"trig\":true}}\n"
        );
    }

    #[test]
    fn an_event_variable_true_from_the_start_fires_in_cycle_one() {
        let mut s = sim(
            Options {
                sets: vec!["trig=TRUE".into(), "g=9".into()],
                ..watching(&["p2.inp"])
            },
            None,
        )
        .unwrap();
        let (out, _) = json_run(&mut s, 2, true);
        assert_eq!(
            out,
            "{\"cycle\":1,\"time\":\"T#0s\",\"values\":{\"p2.inp\":9}}\n\
             {\"cycle\":2,\"time\":\"T#10ms\",\"values\":{\"p2.inp\":9}}\n"
        );
    }

    #[test]
    fn outputs_are_copied_out_after_the_program_runs() {
        let mut s = sim(
            Options {
                sets: vec!["p2.n=42".into(), "trig=TRUE".into()],
                ..watching(&["top"])
            },
            None,
        )
        .unwrap();
        assert_eq!(
            json_run(&mut s, 1, false).0,
            "{\"cycle\":1,\"time\":\"T#0s\",\"values\":{\"top\":42}}\n"
        );
    }

    #[test]
    fn a_fault_reports_the_last_completed_cycle() {
        let stimulus = "cycle,g,main.flag\n1,1,FALSE\n2,2,\n3,3,TRUE\n";
        let mut s = sim(watching(&["g"]), Some(stimulus)).unwrap();
        let (out, f) = json_run(&mut s, 5, false);
        let fault = f.expect("a fault");
        assert_eq!(
            (fault.kind, fault.instance.as_deref()),
            (FaultKind::DivisionByZero, Some("main"))
        );
        assert_eq!(
            fault.to_string(),
            "fault: division by zero in main (Main) at main.st:7:3\nnote: the divisor is 0"
        );
        assert_eq!(
            out,
            "{\"cycle\":2,\"time\":\"T#10ms\",\"values\":{\"g\":2}}\n"
        );
        // With --trace the reports before the fault are all there is.
        let mut s = sim(watching(&["g"]), Some(stimulus)).unwrap();
        let (out, f) = json_run(&mut s, 5, true);
        assert_eq!(f, Some(fault.clone()));
        assert_eq!(
            out,
            "{\"cycle\":1,\"time\":\"T#0s\",\"values\":{\"g\":1}}\n\
             {\"cycle\":2,\"time\":\"T#10ms\",\"values\":{\"g\":2}}\n"
        );
        // A fault in the first cycle reports the state before it.
        let mut s = sim(
            Options {
                sets: vec!["main.flag=TRUE".into(), "g=4".into()],
                ..watching(&["g"])
            },
            None,
        )
        .unwrap();
        let (out, f) = json_run(&mut s, 5, true);
        assert_eq!(f, Some(fault));
        assert_eq!(
            out,
            "{\"cycle\":0,\"time\":\"T#0s\",\"values\":{\"g\":4}}\n"
        );
    }

    #[test]
    fn zero_cycles_report_the_initial_state() {
        let mut s = sim(watching(&["K"]), None).unwrap();
        assert_eq!(
            json_run(&mut s, 0, false).0,
            "{\"cycle\":0,\"time\":\"T#0s\",\"values\":{\"K\":5}}\n"
        );
        assert_eq!(
            json_run(&mut s, 0, true).0,
            "{\"cycle\":0,\"time\":\"T#0s\",\"values\":{\"K\":5}}\n"
        );
    }

    #[test]
    fn the_same_inputs_give_the_same_output() {
        let stimulus = "cycle,g,trig\n1,1,TRUE\n3,7,FALSE\n4,,TRUE\n";
        let go = || {
            let mut s = sim(Options::default(), Some(stimulus)).unwrap();
            json_run(&mut s, 6, true).0
        };
        assert_eq!(go(), go());
    }

    #[test]
    fn the_last_cycle_keeps_time_in_range() {
        let s = sim(
            Options {
                tick_ns: Some(i64::MAX / 4),
                ..Options::default()
            },
            None,
        )
        .unwrap();
        assert_eq!(s.last_cycle(), 5);
        assert_eq!(s.plan().time_of(5), Some(i64::MAX / 4 * 4));
    }

    #[test]
    fn size_of_covers_every_type() {
        let img = sample();
        assert_eq!(img.type_size(T_INT), 2);
        assert_eq!(img.type_size(T_STRING), 12);
        assert_eq!(img.type_size(T_WSTRING), 10);
        assert_eq!(img.type_size(T_COLOR), 2);
        assert_eq!(img.type_size(T_MAT), 12);
        assert_eq!(img.type_size(T_POINT), 4);
        assert_eq!(img.type_size(T_PTS), 8);
        assert_eq!(img.type_size(T_TIMER), 48);
        assert_eq!(img.type_size(999), 0);
    }
}
