//! The real-time runner (`stc run --realtime`): the only place of the
//! runtime that reads a clock.
//!
//! Cycles start on the wall clock, one tick apart; the programs still see
//! the nominal task time (k - 1) * tick, so what they compute is the same
//! as in simulation. A cycle that ends after the next one was due is an
//! overrun: it is reported through `warn`, and the schedule restarts from
//! that moment (the next cycle runs at once, the ones after it a tick
//! apart), so a slow cycle never causes a burst of catch-up cycles. The
//! clock is a trait so the pacing is tested without waiting.

use std::sync::atomic::{AtomicBool, Ordering};
use std::time::{Duration, Instant};

use stc_syntax::literal::format_duration;

use crate::sim::Pacer;

/// A source of time and a way to wait.
pub trait Clock {
    /// Time elapsed since some fixed start.
    fn now(&mut self) -> Duration;
    fn sleep(&mut self, d: Duration);
}

/// The host's monotonic clock.
#[derive(Clone, Copy, Debug)]
pub struct WallClock {
    start: Instant,
}

impl WallClock {
    pub fn new() -> WallClock {
        WallClock {
            start: Instant::now(),
        }
    }
}

impl Default for WallClock {
    fn default() -> Self {
        WallClock::new()
    }
}

impl Clock for WallClock {
    fn now(&mut self) -> Duration {
        self.start.elapsed()
    }
    fn sleep(&mut self, d: Duration) {
        std::thread::sleep(d);
    }
}

/// The longest single sleep, so a stop request is seen quickly.
const SLICE: Duration = Duration::from_millis(20);

/// Paces cycles on a clock until `stop` is set.
pub struct RealTime<'a, C: Clock> {
    clock: C,
    tick: Duration,
    stop: &'a AtomicBool,
    warn: &'a mut dyn FnMut(String),
    /// When the next cycle is due (set by the first cycle).
    due: Option<Duration>,
    /// When an overrun was last reported, and the overruns since then
    /// that were not (at most one warning a second).
    warned: Option<Duration>,
    unreported: u64,
}

/// The shortest time between two overrun warnings.
const WARN_EVERY: Duration = Duration::from_secs(1);

impl<'a, C: Clock> RealTime<'a, C> {
    pub fn new(
        clock: C,
        tick_ns: i64,
        stop: &'a AtomicBool,
        warn: &'a mut dyn FnMut(String),
    ) -> Self {
        RealTime {
            clock,
            tick: Duration::from_nanos(tick_ns.max(1) as u64),
            stop,
            warn,
            due: None,
            warned: None,
            unreported: 0,
        }
    }
}

fn shown(d: Duration) -> String {
    // Above a millisecond, microseconds are enough for a human reading
    // about an overrun.
    let mut ns = i64::try_from(d.as_nanos()).unwrap_or(i64::MAX);
    if ns >= 1_000_000 {
        ns -= ns % 1000;
    }
    format_duration(ns, false)
}

impl<C: Clock> Pacer for RealTime<'_, C> {
    fn before(&mut self, _cycle: u64) -> bool {
        let due = match self.due {
            Some(d) => d,
            None => {
                let now = self.clock.now();
                self.due = Some(now);
                now
            }
        };
        loop {
            if self.stop.load(Ordering::SeqCst) {
                return false;
            }
            let now = self.clock.now();
            if now >= due {
                return true;
            }
            self.clock.sleep((due - now).min(SLICE));
        }
    }

    fn after(&mut self, cycle: u64) {
        let started = self.due.unwrap_or_default();
        let next = started + self.tick;
        let now = self.clock.now();
        if now > next {
            if self
                .warned
                .is_none_or(|w| now.saturating_sub(w) >= WARN_EVERY)
            {
                let more = match std::mem::take(&mut self.unreported) {
                    0 => String::new(),
                    1 => " (and 1 more overrun since the last warning)".into(),
                    n => format!(" (and {n} more overruns since the last warning)"),
                };
                (self.warn)(format!(
                    "warning: overrun: cycle {cycle} took {} with a tick of {}{more}",
                    shown(now - started),
                    shown(self.tick)
                ));
                self.warned = Some(now);
            } else {
                self.unreported += 1;
            }
            self.due = Some(now);
        } else {
            self.due = Some(next);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A clock that advances only when slept on, or by a fixed cost per
    /// reading after a cycle has run.
    struct FakeClock {
        now: Duration,
        slept: Vec<Duration>,
    }

    impl Clock for &mut FakeClock {
        fn now(&mut self) -> Duration {
            self.now
        }
        fn sleep(&mut self, d: Duration) {
            self.slept.push(d);
            self.now += d;
        }
    }

    const MS: Duration = Duration::from_millis(1);

    #[test]
    fn cycles_start_one_tick_apart_in_slices() {
        let stop = AtomicBool::new(false);
        let mut clock = FakeClock {
            now: 100 * MS,
            slept: Vec::new(),
        };
        let mut warnings = Vec::new();
        let mut warn = |w: String| warnings.push(w);
        let mut rt = RealTime::new(&mut clock, 50_000_000, &stop, &mut warn);
        assert!(rt.before(1));
        rt.clock.now += 5 * MS; // the cycle's work
        rt.after(1);
        assert!(rt.before(2));
        assert_eq!(rt.clock.now, 150 * MS);
        assert_eq!(rt.clock.slept, [20 * MS, 20 * MS, 5 * MS]);
        assert!(warnings.is_empty());
    }

    #[test]
    fn an_overrun_is_reported_and_the_schedule_restarts_from_it() {
        let stop = AtomicBool::new(false);
        let mut clock = FakeClock {
            now: Duration::ZERO,
            slept: Vec::new(),
        };
        let mut warnings = Vec::new();
        let mut warn = |w: String| warnings.push(w);
        let mut rt = RealTime::new(&mut clock, 10_000_000, &stop, &mut warn);
        assert!(rt.before(1));
        rt.clock.now += Duration::from_micros(13_250);
        rt.after(1);
        // The next cycle runs at once, the one after it a tick later.
        assert!(rt.before(2));
        assert!(rt.clock.slept.is_empty());
        rt.after(2);
        assert!(rt.before(3));
        assert_eq!(rt.clock.now, Duration::from_micros(23_250));
        assert_eq!(
            warnings,
            ["warning: overrun: cycle 1 took T#13ms250us with a tick of T#10ms"]
        );
    }

    #[test]
    fn overrun_warnings_are_at_most_one_a_second() {
        let stop = AtomicBool::new(false);
        let mut clock = FakeClock {
            now: Duration::ZERO,
            slept: Vec::new(),
        };
        let mut warnings = Vec::new();
        let mut warn = |w: String| warnings.push(w);
        let mut rt = RealTime::new(&mut clock, 10_000_000, &stop, &mut warn);
        // 200 cycles of 20 ms: 4 s, every one an overrun.
        for k in 1..=200 {
            assert!(rt.before(k));
            rt.clock.now += 20 * MS;
            rt.after(k);
        }
        assert_eq!(warnings.len(), 4, "{warnings:?}");
        assert!(warnings[1].ends_with("(and 49 more overruns since the last warning)"));
    }

    #[test]
    fn a_stop_request_ends_the_wait() {
        let stop = AtomicBool::new(false);
        let mut clock = FakeClock {
            now: Duration::ZERO,
            slept: Vec::new(),
        };
        let mut warn = |_: String| {};
        let mut rt = RealTime::new(&mut clock, 10_000_000, &stop, &mut warn);
        assert!(rt.before(1));
        rt.after(1);
        stop.store(true, Ordering::SeqCst);
        assert!(!rt.before(2));
    }

    #[test]
    fn overrun_durations_are_shown_to_the_microsecond() {
        assert_eq!(shown(Duration::from_nanos(13_250_123)), "T#13ms250us");
        assert_eq!(shown(Duration::from_nanos(1_500)), "T#1us500ns");
        assert_eq!(shown(Duration::ZERO), "T#0s");
    }

    #[test]
    fn the_wall_clock_moves_forward() {
        let mut c = WallClock::new();
        let a = c.now();
        c.sleep(Duration::from_millis(2));
        assert!(c.now() >= a + Duration::from_millis(2));
    }
}
