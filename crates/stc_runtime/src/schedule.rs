//! What runs and when (spec/cli.md, docs/runtime.md).
//!
//! [`choose`] picks a configuration or a standalone program; [`Plan`] lists
//! its program instances and tasks in the order they run within a cycle:
//! due tasks by PRIORITY (lower first), then declaration order over all
//! resources, each task's programs in declaration order, and after them
//! the program instances that have no task. Everything here is a pure
//! function of the image and the options, so schedules are unit-tested
//! without running any code.

use stc_ir::model::{Model, ProgramInst, Source};

use crate::error::{Error, Result};

/// The default tick when no periodic task gives one: 10 ms.
pub const DEFAULT_TICK_NS: i64 = 10_000_000;

/// What a run executes: a configuration or the standalone instance of a
/// program type (indices into [`Image::configs`] / [`Image::programs`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Chosen {
    Config(usize),
    Program(usize),
}

/// Picks what runs: `--config NAME`, `--program TYPE`, else the only
/// CONFIGURATION, else the only PROGRAM.
pub fn choose(model: &Model, config: Option<&str>, program: Option<&str>) -> Result<Chosen> {
    let config_names: Vec<&str> = model.configs.iter().map(|c| c.name.as_str()).collect();
    let program_names: Vec<&str> = model.programs.iter().map(|p| p.name.as_str()).collect();
    match (config, program) {
        (Some(_), Some(_)) => Err(Error::Option(
            "--config and --program cannot be used together".into(),
        )),
        (Some(n), None) => config_names
            .iter()
            .position(|c| c.eq_ignore_ascii_case(n))
            .map(Chosen::Config)
            .ok_or_else(|| {
                Error::Selection(format!(
                    "no configuration `{n}`: {}",
                    listing("configurations", &config_names, "CONFIGURATION")
                ))
            }),
        (None, Some(n)) => program_names
            .iter()
            .position(|p| p.eq_ignore_ascii_case(n))
            .map(Chosen::Program)
            .ok_or_else(|| {
                Error::Selection(format!(
                    "no program type `{n}`: {}",
                    listing("programs", &program_names, "PROGRAM")
                ))
            }),
        (None, None) => match (config_names.len(), program_names.len()) {
            (1, _) => Ok(Chosen::Config(0)),
            (_, 1) => Ok(Chosen::Program(0)),
            (0, 0) => Err(Error::Selection(
                "nothing to run: the sources declare no CONFIGURATION and no PROGRAM".into(),
            )),
            _ => {
                let mut what = Vec::new();
                if !config_names.is_empty() {
                    what.push(format!("configurations {}", config_names.join(", ")));
                }
                if !program_names.is_empty() {
                    what.push(format!("programs {}", program_names.join(", ")));
                }
                Err(Error::Selection(format!(
                    "several things could run; choose one with --config NAME or --program TYPE ({})",
                    what.join("; ")
                )))
            }
        },
    }
}

fn listing(plural: &str, names: &[&str], keyword: &str) -> String {
    if names.is_empty() {
        format!("the sources declare no {keyword}")
    } else {
        format!("the {plural} are {}", names.join(", "))
    }
}

/// A task of the chosen configuration, with its program instances.
#[derive(Clone, Debug, PartialEq)]
pub struct PlannedTask {
    pub name: String,
    pub interval_ns: Option<i64>,
    pub priority: u32,
    /// The BOOL whose rising edge triggers the task.
    pub single: Option<Source>,
    /// Indices into [`Plan::instances`], in declaration order.
    pub programs: Vec<usize>,
}

/// Everything that runs, in the order it runs.
#[derive(Clone, Debug, PartialEq)]
pub struct Plan {
    pub chosen: Chosen,
    /// The configuration chosen (for its globals), if any.
    pub config: Option<u32>,
    /// Every program instance, in configuration order (resource by
    /// resource, declaration order).
    pub instances: Vec<ProgramInst>,
    /// The tasks, sorted by priority then declaration order.
    pub tasks: Vec<PlannedTask>,
    /// Instances without a task, in declaration order: they run every
    /// cycle, after the tasks.
    pub free: Vec<usize>,
    pub tick_ns: i64,
}

impl Plan {
    /// The plan of `chosen`; `tick_ns` overrides the default tick.
    pub fn new(model: &Model, chosen: Chosen, tick_ns: Option<i64>) -> Result<Plan> {
        let mut instances = Vec::new();
        let mut tasks = Vec::new();
        let mut free = Vec::new();
        let config = match chosen {
            Chosen::Program(p) => {
                let inst = model.programs.get(p).ok_or_else(|| {
                    Error::Selection(format!("the model has no program number {p}"))
                })?;
                instances.push(inst.clone());
                free.push(0);
                None
            }
            Chosen::Config(c) => {
                let conf = model.configs.get(c).ok_or_else(|| {
                    Error::Selection(format!("the model has no configuration number {c}"))
                })?;
                for res in &conf.resources {
                    let first = tasks.len();
                    for t in &res.tasks {
                        tasks.push(PlannedTask {
                            name: t.name.clone(),
                            interval_ns: t.interval_ns.filter(|&i| i > 0),
                            priority: t.priority,
                            single: t.single.clone(),
                            programs: Vec::new(),
                        });
                    }
                    for p in &res.programs {
                        let i = instances.len();
                        instances.push(p.clone());
                        match p.task {
                            None => free.push(i),
                            Some(t) => {
                                let task = tasks[first..].get_mut(t as usize).ok_or_else(|| {
                                    Error::Selection(format!(
                                        "program instance `{}` names a task its resource does not have",
                                        p.name
                                    ))
                                })?;
                                task.programs.push(i);
                            }
                        }
                    }
                }
                // Stable: equal priorities keep declaration order.
                tasks.sort_by_key(|t| t.priority);
                Some(c as u32)
            }
        };
        let tick_ns = match tick_ns {
            Some(t) if t > 0 => t,
            Some(_) => return Err(Error::Option("the tick must be longer than zero".into())),
            None => default_tick(tasks.iter().filter_map(|t| t.interval_ns)),
        };
        Ok(Plan {
            chosen,
            config,
            instances,
            tasks,
            free,
            tick_ns,
        })
    }

    /// What the plan changes silently otherwise: a periodic task whose
    /// interval the tick does not divide runs at another rate (every
    /// least common multiple of the two), said here.
    pub fn warnings(&self) -> Vec<String> {
        let show = |ns: i128| match i64::try_from(ns) {
            Ok(ns) => stc_syntax::literal::format_duration(ns, false),
            Err(_) => "longer than the largest TIME".to_string(),
        };
        let mut out = Vec::new();
        for t in &self.tasks {
            let Some(interval) = t.interval_ns else {
                continue;
            };
            if interval % self.tick_ns != 0 {
                let (a, b) = (i128::from(interval), i128::from(self.tick_ns));
                let lcm = a / i128::from(gcd(interval, self.tick_ns)) * b;
                out.push(format!(
                    "warning: task `{}` has INTERVAL {}, which the tick {} does not divide: it runs every {}",
                    t.name,
                    show(a),
                    show(b),
                    show(lcm)
                ));
            }
        }
        out
    }

    /// The time of cycle `k` (1-based): (k - 1) * tick; `None` past the
    /// largest TIME.
    pub fn time_of(&self, cycle: u64) -> Option<i64> {
        let t = (cycle.saturating_sub(1) as i128) * self.tick_ns as i128;
        i64::try_from(t).ok()
    }

    /// Whether a periodic task is due in cycle `k`: (k - 1) * tick is a
    /// multiple of its interval.
    pub fn periodic_due(&self, interval_ns: i64, cycle: u64) -> bool {
        let t = (cycle.saturating_sub(1) as i128) * self.tick_ns as i128;
        interval_ns > 0 && t % interval_ns as i128 == 0
    }

    /// Whether task `t` runs in cycle `k`, given whether its event fired
    /// (`fired`: its SINGLE rose between the starts of the previous cycle
    /// and this one). A task with neither INTERVAL nor SINGLE runs every
    /// cycle.
    pub fn task_due(&self, t: &PlannedTask, cycle: u64, fired: bool) -> bool {
        match (t.interval_ns, &t.single) {
            (Some(i), _) => self.periodic_due(i, cycle) || fired,
            (None, Some(_)) => fired,
            (None, None) => true,
        }
    }

    /// The instances to run in cycle `k`, in order; `fired[i]` tells
    /// whether the event of task `i` fired.
    pub fn order(&self, cycle: u64, fired: &[bool]) -> Vec<usize> {
        let mut out = Vec::new();
        self.order_into(cycle, fired, &mut out);
        out
    }

    /// [`Plan::order`] into a buffer the caller reuses.
    pub fn order_into(&self, cycle: u64, fired: &[bool], out: &mut Vec<usize>) {
        out.clear();
        for (i, t) in self.tasks.iter().enumerate() {
            if self.task_due(t, cycle, fired.get(i).copied().unwrap_or(false)) {
                out.extend_from_slice(&t.programs);
            }
        }
        out.extend_from_slice(&self.free);
    }
}

/// The greatest common divisor of the periodic intervals, or 10 ms when
/// there are none.
pub fn default_tick(intervals: impl IntoIterator<Item = i64>) -> i64 {
    intervals
        .into_iter()
        .filter(|&i| i > 0)
        .reduce(gcd)
        .unwrap_or(DEFAULT_TICK_NS)
}

fn gcd(mut a: i64, mut b: i64) -> i64 {
    while b != 0 {
        (a, b) = (b, a % b);
    }
    a
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::testing::{inst, sample_model, task};
    use stc_ir::model::{ConfigDesc, ResourceDesc};

    const MS: i64 = 1_000_000;

    fn config(name: &str, resources: Vec<ResourceDesc>) -> ConfigDesc {
        ConfigDesc {
            name: name.into(),
            resources,
        }
    }

    fn resource(tasks: Vec<stc_ir::model::TaskDesc>, programs: Vec<ProgramInst>) -> ResourceDesc {
        ResourceDesc {
            name: None,
            tasks,
            programs,
        }
    }

    #[test]
    fn the_only_configuration_is_chosen_before_the_only_program() {
        let img = sample_model();
        assert_eq!(choose(&img, None, None), Ok(Chosen::Config(0)));
        assert_eq!(choose(&img, Some("PLANT"), None), Ok(Chosen::Config(0)));
        assert_eq!(choose(&img, None, Some("other")), Ok(Chosen::Program(1)));
    }

    #[test]
    fn the_only_program_runs_without_configuration() {
        let img = Model {
            programs: vec![inst("Main", 0, 0, None)],
            ..Model::default()
        };
        assert_eq!(choose(&img, None, None), Ok(Chosen::Program(0)));
    }

    #[test]
    fn unknown_or_ambiguous_choices_list_the_candidates() {
        let img = sample_model();
        assert_eq!(
            choose(&img, Some("Line"), None),
            Err(Error::Selection(
                "no configuration `Line`: the configurations are Plant".into()
            ))
        );
        assert_eq!(
            choose(&img, None, Some("Pump")),
            Err(Error::Selection(
                "no program type `Pump`: the programs are Main, Other".into()
            ))
        );
        let mut two = sample_model();
        two.configs.push(config("Line", Vec::new()));
        assert_eq!(
            choose(&two, None, None),
            Err(Error::Selection(
                "several things could run; choose one with --config NAME or --program TYPE \
                 (configurations Plant, Line; programs Main, Other)"
                    .into()
            ))
        );
        assert_eq!(
            choose(&Model::default(), None, None),
            Err(Error::Selection(
                "nothing to run: the sources declare no CONFIGURATION and no PROGRAM".into()
            ))
        );
        assert_eq!(
            choose(&Model::default(), Some("X"), None),
            Err(Error::Selection(
                "no configuration `X`: the sources declare no CONFIGURATION".into()
            ))
        );
        assert_eq!(
            choose(&img, Some("Plant"), Some("Main")),
            Err(Error::Option(
                "--config and --program cannot be used together".into()
            ))
        );
    }

    #[test]
    fn a_tick_that_does_not_divide_an_interval_is_a_warning() {
        let img = sample_model();
        let plan = Plan::new(&img, Chosen::Config(0), Some(4 * MS)).unwrap();
        assert_eq!(
            plan.warnings(),
            vec![
                "warning: task `slow` has INTERVAL T#30ms, which the tick T#4ms does not divide: it runs every T#60ms".to_string(),
                "warning: task `fast` has INTERVAL T#10ms, which the tick T#4ms does not divide: it runs every T#20ms".to_string(),
            ]
        );
        let plan = Plan::new(&img, Chosen::Config(0), Some(5 * MS)).unwrap();
        assert!(plan.warnings().is_empty());
    }

    #[test]
    fn default_tick_is_the_gcd_of_the_periodic_intervals() {
        assert_eq!(default_tick([]), 10 * MS);
        assert_eq!(default_tick([20 * MS, 30 * MS]), 10 * MS);
        assert_eq!(default_tick([10 * MS, 25 * MS]), 5 * MS);
        assert_eq!(default_tick([100 * MS]), 100 * MS);
        assert_eq!(default_tick([7, 0, 21]), 7);
        let plan = Plan::new(&sample_model(), Chosen::Config(0), None).unwrap();
        assert_eq!(plan.tick_ns, 10 * MS);
        let plan = Plan::new(&sample_model(), Chosen::Program(0), None).unwrap();
        assert_eq!(plan.tick_ns, 10 * MS);
        let plan = Plan::new(&sample_model(), Chosen::Config(0), Some(5 * MS)).unwrap();
        assert_eq!(plan.tick_ns, 5 * MS);
        assert!(Plan::new(&sample_model(), Chosen::Config(0), Some(0)).is_err());
    }

    #[test]
    fn tasks_run_by_priority_then_declaration_order() {
        let plan = Plan::new(&sample_model(), Chosen::Config(0), None).unwrap();
        let names: Vec<&str> = plan.tasks.iter().map(|t| t.name.as_str()).collect();
        assert_eq!(names, ["ev", "slow", "fast"]);
        let inst: Vec<&str> = plan.instances.iter().map(|i| i.name.as_str()).collect();
        assert_eq!(inst, ["main", "p2", "p3"]);
        assert_eq!(plan.free, [2]);
        assert_eq!(plan.config, Some(0));
    }

    #[test]
    fn equal_priorities_keep_declaration_order_over_resources() {
        let mut img = Model::default();
        img.configs.push(config(
            "C",
            vec![
                resource(
                    vec![task("ta", Some(10), 2), task("tb", Some(10), 2)],
                    vec![inst("pa", 0, 0, Some(0)), inst("pb", 0, 0, Some(1))],
                ),
                resource(
                    vec![task("tc", Some(10), 1), task("td", Some(10), 2)],
                    vec![
                        inst("free", 0, 0, None),
                        inst("pd", 0, 0, Some(1)),
                        inst("pc", 0, 0, Some(0)),
                        inst("pc2", 0, 0, Some(0)),
                    ],
                ),
            ],
        ));
        let plan = Plan::new(&img, Chosen::Config(0), None).unwrap();
        let order: Vec<&str> = plan
            .order(1, &[])
            .into_iter()
            .map(|i| plan.instances[i].name.as_str())
            .collect();
        assert_eq!(order, ["pc", "pc2", "pa", "pb", "pd", "free"]);
    }

    #[test]
    fn periodic_tasks_run_when_the_cycle_time_is_a_multiple_of_their_interval() {
        let mut img = Model::default();
        img.configs.push(config(
            "C",
            vec![resource(
                vec![task("t10", Some(10), 1), task("t25", Some(25), 1)],
                vec![inst("p10", 0, 0, Some(0)), inst("p25", 0, 0, Some(1))],
            )],
        ));
        let plan = Plan::new(&img, Chosen::Config(0), None).unwrap();
        assert_eq!(plan.tick_ns, 5 * MS);
        let runs = |name: &str| -> Vec<u64> {
            (1..=11)
                .filter(|&k| {
                    plan.order(k, &[])
                        .iter()
                        .any(|&i| plan.instances[i].name == name)
                })
                .collect()
        };
        assert_eq!(runs("p10"), [1, 3, 5, 7, 9, 11]);
        assert_eq!(runs("p25"), [1, 6, 11]);
        // A tick that does not divide the interval: 3 ms and 10 ms meet
        // every 30 ms.
        let plan = Plan::new(&img, Chosen::Config(0), Some(3 * MS)).unwrap();
        let due: Vec<u64> = (1..=25)
            .filter(|&k| plan.periodic_due(10 * MS, k))
            .collect();
        assert_eq!(due, [1, 11, 21]);
        assert_eq!(plan.time_of(1), Some(0));
        assert_eq!(plan.time_of(4), Some(9 * MS));
    }

    #[test]
    fn event_tasks_run_only_when_fired_and_free_programs_always() {
        let plan = Plan::new(&sample_model(), Chosen::Config(0), None).unwrap();
        let names = |v: Vec<usize>| -> Vec<String> {
            v.into_iter()
                .map(|i| plan.instances[i].name.clone())
                .collect()
        };
        // ev, slow, fast: ev runs p2 only when fired.
        assert_eq!(names(plan.order(1, &[false, false, false])), ["main", "p3"]);
        assert_eq!(
            names(plan.order(2, &[true, false, false])),
            ["p2", "main", "p3"]
        );
        let ev = &plan.tasks[0];
        assert!(!plan.task_due(ev, 1, false));
        assert!(plan.task_due(ev, 1, true));
        // A task with both INTERVAL and SINGLE runs on either.
        let both = PlannedTask {
            interval_ns: Some(30 * MS),
            ..ev.clone()
        };
        assert!(plan.task_due(&both, 1, false));
        assert!(!plan.task_due(&both, 2, false));
        assert!(plan.task_due(&both, 2, true));
        // Neither: every cycle.
        let neither = PlannedTask {
            single: None,
            ..ev.clone()
        };
        assert!(plan.task_due(&neither, 2, false));
    }

    #[test]
    fn a_standalone_program_is_one_free_instance() {
        let plan = Plan::new(&sample_model(), Chosen::Program(1), None).unwrap();
        assert_eq!(plan.instances.len(), 1);
        assert_eq!(plan.instances[0].name, "Other");
        assert!(plan.tasks.is_empty());
        assert_eq!(plan.order(1, &[]), [0]);
        assert_eq!(plan.config, None);
    }

    #[test]
    fn a_task_index_outside_the_resource_is_an_error_not_a_panic() {
        let mut img = Model::default();
        img.configs.push(config(
            "C",
            vec![resource(vec![], vec![inst("p", 0, 0, Some(3))])],
        ));
        assert!(matches!(
            Plan::new(&img, Chosen::Config(0), None),
            Err(Error::Selection(_))
        ));
    }
}
