//! Scan statistics of the real-time controller: how long each cycle and
//! each task took, how regularly the cycles started, the overruns and the
//! watchdog faults (docs/runtime.md, "Task timing").
//!
//! [`Timing`] is the [`Between`] that measures: it reads a [`Clock`] when
//! a cycle is about to run (before the inputs are exchanged) and when it
//! has completed (after the outputs), and takes the tasks' times from the
//! simulation, which it asks to measure them on the same clock. The
//! figures go into a [`Stats`] that the caller shares (the monitor serves
//! them as JSON). Nothing here sleeps or prints.

use std::sync::{Arc, Mutex};

use stc_ir::FaultKind;
use stc_vm::VmFault;

use crate::realtime::Clock;
use crate::schedule::Plan;
use crate::sim::{Between, CycleTimes, Simulation};

/// Minimum, mean and maximum of a series of durations (nanoseconds).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Summary {
    pub count: u64,
    pub min: u64,
    pub max: u64,
    pub sum: u128,
    pub last: u64,
}

impl Summary {
    pub fn add(&mut self, x: u64) {
        if self.count == 0 || x < self.min {
            self.min = x;
        }
        self.max = self.max.max(x);
        self.count += 1;
        self.sum += u128::from(x);
        self.last = x;
    }

    pub fn mean(&self) -> u64 {
        if self.count == 0 {
            0
        } else {
            (self.sum / u128::from(self.count)) as u64
        }
    }

    fn json(&self) -> String {
        format!(
            "{{\"count\":{},\"min_ns\":{},\"mean_ns\":{},\"max_ns\":{},\"last_ns\":{}}}",
            self.count,
            self.min,
            self.mean(),
            self.max,
            self.last
        )
    }
}

/// The buckets of the cycle time histogram: bucket 0 holds cycles under
/// 1 µs, bucket i (i ≥ 1) those from 2^(i-1) µs to under 2^i µs, the
/// last everything longer.
pub const BUCKETS: usize = 32;

/// The statistics of one task.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct TaskStats {
    pub name: String,
    /// `None` for an event task or a task without an interval.
    pub interval_ns: Option<i64>,
    /// Its programs' execution time, per run.
    pub exec: Summary,
    /// From the start of the cycle's programs to the end of its last
    /// program (it waits for the tasks of higher priority).
    pub response: Summary,
    /// How far the time between two of its starts was from its interval.
    pub jitter: Summary,
    /// Runs whose response time exceeded the interval.
    pub overruns: u64,
    pub watchdog_faults: u64,
    last_start: Option<u64>,
}

/// The statistics of a run.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Stats {
    pub tick_ns: i64,
    /// Completed cycles.
    pub cycles: u64,
    /// Whole cycles: inputs, forces, programs, outputs, retain save.
    pub cycle: Summary,
    /// The programs alone.
    pub programs: Summary,
    /// How far the time between two cycle starts was from the tick.
    pub jitter: Summary,
    /// Cycles that took longer than the tick.
    pub overruns: u64,
    pub watchdog_faults: u64,
    /// Cycle times, see [`BUCKETS`].
    pub histogram: [u64; BUCKETS],
    pub tasks: Vec<TaskStats>,
    /// The fault that stopped the run, as stderr shows it.
    pub fault: Option<String>,
    last_start: Option<u64>,
}

fn bucket(ns: u64) -> usize {
    let us = ns / 1000;
    if us == 0 {
        0
    } else {
        ((64 - us.leading_zeros()) as usize).min(BUCKETS - 1)
    }
}

fn opt_ns(x: Option<i64>) -> String {
    x.map_or("null".into(), |n| n.to_string())
}

impl Stats {
    pub fn new(plan: &Plan) -> Stats {
        Stats {
            tick_ns: plan.tick_ns,
            tasks: plan
                .tasks
                .iter()
                .map(|t| TaskStats {
                    name: t.name.clone(),
                    interval_ns: t.interval_ns,
                    ..TaskStats::default()
                })
                .collect(),
            ..Stats::default()
        }
    }

    /// A completed cycle that started at `start` and ended at `end` on
    /// the clock of `times`.
    pub fn record(&mut self, start: u64, end: u64, times: &CycleTimes) {
        self.cycles += 1;
        let took = end.saturating_sub(start);
        self.cycle.add(took);
        self.histogram[bucket(took)] += 1;
        if took > self.tick_ns.max(0) as u64 {
            self.overruns += 1;
        }
        if let Some(prev) = self.last_start {
            self.jitter.add(
                start
                    .saturating_sub(prev)
                    .abs_diff(self.tick_ns.max(0) as u64),
            );
        }
        self.last_start = Some(start);
        self.programs.add(times.end.saturating_sub(times.start));
        for (task, ran) in self.tasks.iter_mut().zip(&times.tasks) {
            let Some((s, e)) = *ran else { continue };
            task.exec.add(e.saturating_sub(s));
            let response = e.saturating_sub(times.start);
            task.response.add(response);
            if let Some(iv) = task.interval_ns {
                if response > iv.max(0) as u64 {
                    task.overruns += 1;
                }
                if let Some(prev) = task.last_start {
                    task.jitter
                        .add(start.saturating_sub(prev).abs_diff(iv.max(0) as u64));
                }
            }
            task.last_start = Some(start);
        }
    }

    /// The run stopped on `fault` in the task `task` (`None`: a program
    /// without a task).
    pub fn fault(&mut self, fault: &VmFault, task: Option<usize>) {
        if fault.kind == FaultKind::Watchdog {
            self.watchdog_faults += 1;
            if let Some(t) = task.and_then(|t| self.tasks.get_mut(t)) {
                t.watchdog_faults += 1;
            }
        }
        self.fault = Some(fault.to_string());
    }

    /// The statistics as a JSON object (docs/runtime.md, `/api/stats`).
    pub fn to_json(&self) -> String {
        let mut out = format!(
            "{{\"tick_ns\":{},\"cycles\":{},\"cycle\":{},\"programs\":{},\"jitter\":{},\"overruns\":{},\"watchdog_faults\":{},\"histogram\":{{\"unit\":\"us\",\"counts\":[",
            self.tick_ns,
            self.cycles,
            self.cycle.json(),
            self.programs.json(),
            self.jitter.json(),
            self.overruns,
            self.watchdog_faults,
        );
        for (i, c) in self.histogram.iter().enumerate() {
            if i > 0 {
                out.push(',');
            }
            out.push_str(&c.to_string());
        }
        out.push_str("]},\"tasks\":[");
        for (i, t) in self.tasks.iter().enumerate() {
            if i > 0 {
                out.push(',');
            }
            out.push_str(&format!(
                "{{\"name\":{},\"interval_ns\":{},\"runs\":{},\"exec\":{},\"response\":{},\"jitter\":{},\"overruns\":{},\"watchdog_faults\":{}}}",
                crate::report::json_string(&t.name),
                opt_ns(t.interval_ns),
                t.exec.count,
                t.exec.json(),
                t.response.json(),
                t.jitter.json(),
                t.overruns,
                t.watchdog_faults
            ));
        }
        out.push_str("],\"fault\":");
        match &self.fault {
            Some(f) => out.push_str(&crate::report::json_string(f)),
            None => out.push_str("null"),
        }
        out.push('}');
        out
    }
}

/// Measures every cycle into shared [`Stats`]. Put it first among the
/// things done between cycles, so its cycle is the whole one.
pub struct Timing<C: Clock> {
    clock: C,
    stats: Arc<Mutex<Stats>>,
    started: u64,
}

fn ns(d: std::time::Duration) -> u64 {
    u64::try_from(d.as_nanos()).unwrap_or(u64::MAX)
}

impl<C: Clock + Clone + 'static> Timing<C> {
    /// Measures `sim` with `clock` (the tasks too).
    pub fn new(sim: &mut Simulation, clock: C, stats: Arc<Mutex<Stats>>) -> Timing<C> {
        let mut c = clock.clone();
        sim.measure_with(Box::new(move || ns(c.now())));
        Timing {
            clock,
            stats,
            started: 0,
        }
    }

    fn stats(&self) -> std::sync::MutexGuard<'_, Stats> {
        self.stats.lock().unwrap_or_else(|e| e.into_inner())
    }
}

impl<C: Clock + Clone + 'static> Between for Timing<C> {
    fn before_cycle(&mut self, _sim: &mut Simulation, _k: u64) {
        self.started = ns(self.clock.now());
    }

    fn after_cycle(&mut self, sim: &mut Simulation, _k: u64) {
        let end = ns(self.clock.now());
        let start = self.started;
        self.stats().record(start, end, sim.times());
    }

    fn faulted(&mut self, sim: &mut Simulation, _k: u64, fault: &VmFault) {
        let task = fault.instance.as_deref().and_then(|name| {
            let plan = sim.plan();
            let i = plan
                .instances
                .iter()
                .position(|p| name == p.name || name.starts_with(&format!("{}.", p.name)))?;
            plan.tasks.iter().position(|t| t.programs.contains(&i))
        });
        self.stats().fault(fault, task);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn stats(interval: Option<i64>) -> Stats {
        Stats {
            tick_ns: 10_000_000,
            tasks: vec![TaskStats {
                name: "fast".into(),
                interval_ns: interval,
                ..TaskStats::default()
            }],
            ..Stats::default()
        }
    }

    fn times(start: u64, task: Option<(u64, u64)>, end: u64) -> CycleTimes {
        CycleTimes {
            start,
            end,
            tasks: vec![task],
        }
    }

    #[test]
    fn cycles_tasks_overruns_and_jitter_are_counted() {
        let mut s = stats(Some(10_000_000));
        // A 2 ms cycle at 0, a 12 ms one at 11 ms (1 ms late), a task
        // that did not run at 30 ms.
        s.record(0, 2_000_000, &times(100, Some((100, 1_100)), 1_500));
        s.record(
            11_000_000,
            23_000_000,
            &times(11_000_000, Some((11_000_000, 22_000_000)), 22_500_000),
        );
        s.record(30_000_000, 30_000_500, &times(30_000_000, None, 30_000_100));
        assert_eq!(s.cycles, 3);
        assert_eq!((s.cycle.min, s.cycle.max), (500, 12_000_000));
        assert_eq!(s.overruns, 1);
        assert_eq!(s.jitter.count, 2);
        assert_eq!(s.jitter.max, 9_000_000);
        let t = &s.tasks[0];
        assert_eq!(t.exec.count, 2);
        assert_eq!((t.exec.min, t.exec.max), (1_000, 11_000_000));
        assert_eq!(t.overruns, 1);
        assert_eq!(t.jitter.last, 1_000_000);
        assert_eq!(s.histogram[0], 1);
        assert_eq!(s.histogram[bucket(2_000_000)], 1);
        let json: serde_json::Value = serde_json::from_str(&s.to_json()).unwrap();
        assert_eq!(json["tasks"][0]["name"], "fast");
        assert_eq!(json["tasks"][0]["overruns"], 1);
        assert_eq!(json["cycle"]["max_ns"], 12_000_000);
        assert_eq!(
            json["histogram"]["counts"].as_array().unwrap().len(),
            BUCKETS
        );
    }

    #[test]
    fn a_watchdog_fault_is_counted_for_its_task() {
        let mut s = stats(None);
        let f = VmFault::at(FaultKind::Watchdog, "Main", "m.st", 1, 1);
        s.fault(&f, Some(0));
        assert_eq!((s.watchdog_faults, s.tasks[0].watchdog_faults), (1, 1));
        assert!(s.fault.as_deref().unwrap().contains("watchdog"));
    }

    #[test]
    fn the_histogram_buckets_double() {
        assert_eq!(bucket(999), 0);
        assert_eq!(bucket(1_000), 1);
        assert_eq!(bucket(1_999), 1);
        assert_eq!(bucket(2_000), 2);
        assert_eq!(bucket(u64::MAX), BUCKETS - 1);
    }
}
