//! The runtime around the bytecode VM: what `stc run` executes and how.
//!
//! It chooses what runs ([`schedule::choose`]: a configuration or a
//! standalone program), orders its tasks ([`schedule::Plan`]), resolves
//! variable paths ([`path`]), reads and writes values in ST literal syntax
//! ([`value`]), applies `--set` and stimulus files ([`stimulus`]), and
//! formats reports ([`report`]). [`sim::Simulation`] advances the program
//! one cycle at a time in simulated time; [`sim::run`] drives it and
//! reports the last completed cycle on a fault; [`realtime`] paces the same
//! loop with the wall clock. The decisions the contract leaves open are in
//! docs/runtime.md.
//!
//! Simulation is deterministic: the same image and options give the same
//! reports, byte for byte. No clock is read except by
//! [`realtime::WallClock`], and nothing here touches files or the terminal:
//! the caller reads stimulus files and prints reports.

pub mod engine;
pub mod error;
pub mod iomap;
pub mod monitor;
pub mod path;
pub mod realtime;
pub mod report;
pub mod retain;
pub mod schedule;
pub mod sim;
pub mod stimulus;
pub mod timing;
pub mod value;

#[cfg(test)]
mod testing;

pub use engine::{Engine, Memory};
pub use error::Error;
pub use report::{Format, Renderer, Report};
pub use schedule::{choose, Chosen, Plan};
pub use sim::{
    run, run_between, Between, Nothing, Options, Pacer, Simulation, Unpaced, DEFAULT_MAX_STEPS,
};
pub use stimulus::Stimulus;

/// Reads a `--tick` duration: `10ms` or `T#10ms`, longer than zero.
pub fn parse_tick(text: &str) -> Result<i64, Error> {
    let t = text.trim();
    match stc_values::parse_value(stc_syntax::token::ElemType::Time, t) {
        Ok(stc_values::Value::Int(ns)) if ns > 0 => Ok(ns as i64),
        Ok(_) => Err(Error::Option(format!(
            "--tick {t}: the tick must be longer than zero"
        ))),
        Err(_) => Err(Error::Option(format!(
            "--tick {t}: expected a duration such as 10ms or T#10ms"
        ))),
    }
}

#[cfg(test)]
mod robustness {
    //! Nothing a user types or a file holds makes the runtime panic.

    use proptest::prelude::*;

    use crate::path::{parse_path, split_list, Scope, View};
    use crate::schedule::{Chosen, Plan};
    use crate::stimulus::{split_record, Stimulus};
    use crate::testing::sample_model as sample;
    use crate::value::parse_for;

    proptest! {
        #[test]
        fn any_path_text_resolves_or_is_an_error(text in "[%A-Za-z_.0-9\\[\\], #*-]{0,24}") {
            let _ = parse_path(&text);
            let _ = split_list(&text);
            let img = sample();
            let plan = Plan::new(&img, Chosen::Config(0), None).unwrap();
            let scope = Scope { model: &img, instances: &plan.instances, config: plan.config };
            if let Ok(p) = scope.resolve(&text) {
                let _ = p.loc.address(&crate::testing::sample().init);
            }
        }

        #[test]
        fn any_value_text_parses_or_is_an_error(text in "\\PC{0,16}", ty in 0u32..17) {
            let _ = parse_for(&sample(), &View::Type(ty), &text);
            let _ = crate::parse_tick(&text);
        }

        #[test]
        fn any_csv_text_reads_or_is_an_error(text in "[a-z0-9,'\"$ \\n.#=-]{0,60}") {
            let _ = split_record(&text);
            let _ = Stimulus::parse("s.csv", &text);
        }
    }
}
