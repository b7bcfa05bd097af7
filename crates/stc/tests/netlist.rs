//! The netlist back end (docs/netlist.md), through the same paths as the
//! command:
//!
//! - the seed's listings (`tests/netlist/seed`): the circuits of 5.1, 5.3,
//!   5.5 and 5.11 (snapshots of the documents, which `xmllint` validates
//!   against the XSD, and their behaviour when simulated), the diagnostics
//!   of 5.7 and 5.9 and no file;
//! - the refusals (`tests/netlist/refuse`): each case gives exactly its
//!   annotated diagnostics, exit status 1 and no file;
//! - the run conformance suite: every case the netlist can express is
//!   written, validated, read back and simulated with its options, and must
//!   give the values its `// expect:` lines give on the VM (and its fault);
//!   and `stc run --backend netlist` prints the same bytes as the VM on
//!   every case it can express; the cases refused or not simulated are
//!   listed with their reason in snapshots.

mod common;

use std::path::{Path, PathBuf};

use stc_netlist::{Simulator, StepError};
use stc_values::{ElemType, Value};

fn tmp_dir() -> PathBuf {
    let d = std::env::temp_dir().join(format!("stc-netlist-test-{}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// Validates a document with the real `xmllint` against the shipped XSD.
fn xmllint(doc: &Path) -> Result<(), String> {
    let xsd = Path::new(env!("CARGO_MANIFEST_DIR")).join("../stc_netlist/netlist.xsd");
    let out = std::process::Command::new("xmllint")
        .arg("--noout")
        .arg("--schema")
        .arg(&xsd)
        .arg(doc)
        .output()
        .map_err(|e| format!("cannot run xmllint (test.sh installs libxml2-utils): {e}"))?;
    if out.status.success() {
        Ok(())
    } else {
        Err(format!(
            "xmllint rejects {}:\n{}",
            doc.display(),
            String::from_utf8_lossy(&out.stderr)
        ))
    }
}

/// `stc build --emit netlist FILE -o OUT [extra]`: the outcome and the
/// document, when one was written.
fn build(files: &[PathBuf], out: &Path, extra: &[&str]) -> (stc::cli::Outcome, Option<String>) {
    let _ = std::fs::remove_file(out);
    let mut args: Vec<String> = vec![
        "stc".into(),
        "build".into(),
        "--emit".into(),
        "netlist".into(),
    ];
    args.extend(files.iter().map(|f| f.display().to_string()));
    args.extend(["-o".to_string(), out.display().to_string()]);
    args.extend(extra.iter().map(|s| s.to_string()));
    let refs: Vec<&str> = args.iter().map(|s| s.as_str()).collect();
    let o = stc::cli::run_args(&refs);
    let doc = std::fs::read_to_string(out).ok();
    (o, doc)
}

/// `--config` and `--program` choose what the circuit is of, as for `stc
/// run`; the circuit of a configuration has an enable input per program
/// instance, and one step with one enable TRUE runs that instance alone,
/// with its connections.
#[test]
fn a_configuration_becomes_one_circuit_with_an_enable_per_instance() {
    let dir = tmp_dir();
    let file = common::data_dir().join("netlist/config/two_tasks.st");
    let out = dir.join("config.xml");
    // The only configuration, by default and by name.
    for extra in [&[][..], &["--config", "c"][..]] {
        let (o, doc) = build(std::slice::from_ref(&file), &out, extra);
        assert_eq!(o.status, 0, "{}", o.stderr);
        let doc = doc.unwrap();
        for en in ["a$EN", "b$EN", "c$EN"] {
            assert!(doc.contains(&format!("Value=\"{en}\"")), "{en}");
        }
        assert!(doc.contains("Value=\"%QW0\""), "the located output");
        xmllint(&out).unwrap();
    }
    let (o, doc) = build(std::slice::from_ref(&file), &out, &["--config", "Nope"]);
    assert_eq!((o.status, doc), (2, None));
    assert!(
        o.stderr.contains("no CONFIGURATION named `Nope`"),
        "{}",
        o.stderr
    );
    // One PROGRAM on its own: no enables.
    let (o, doc) = build(std::slice::from_ref(&file), &out, &["--program", "P"]);
    assert_eq!(o.status, 0, "{}", o.stderr);
    assert!(!doc.unwrap().contains("$EN"));
    // Simulated: instance `a` (in := src, out => dst) runs alone.
    let (_, doc) = build(std::slice::from_ref(&file), &out, &[]);
    let mut sim = Simulator::new(stc_netlist::xml::read(&doc.unwrap()).unwrap());
    sim.set("a$EN", Value::Bool(true));
    sim.step(&[], 0).unwrap();
    // n = 0 + src (2), g = 1, out = n * 10 + g.
    assert_eq!(sim.get("a.out"), Some(&Value::Int(21)));
    assert_eq!(sim.get("dst"), Some(&Value::Int(21)));
    assert_eq!(sim.get("b.out"), Some(&Value::Int(0)));
    sim.set("a$EN", Value::Bool(false));
    sim.set("b$EN", Value::Bool(true));
    sim.step(&[], 10_000_000).unwrap();
    // b: in := 5 (a constant), g = 2.
    assert_eq!(sim.get("b.out"), Some(&Value::Int(52)));
    assert_eq!(sim.get("a.out"), Some(&Value::Int(21)), "a kept its state");
    assert_eq!(sim.get("g"), Some(&Value::Int(2)));
}

fn seed(name: &str) -> PathBuf {
    common::data_dir().join("netlist/seed").join(name)
}

#[test]
fn seed_listings_become_valid_circuits() {
    let dir = tmp_dir();
    for name in ["listing_5_1", "listing_5_3", "listing_5_5", "listing_5_11"] {
        let out = dir.join(format!("{name}.xml"));
        let (o, doc) = build(&[seed(&format!("{name}.st"))], &out, &[]);
        assert_eq!(o.status, 0, "{name}: {}", o.stderr);
        let doc = doc.expect("a document");
        xmllint(&out).unwrap();
        // Deterministic: the same bytes a second time.
        let (_, again) = build(&[seed(&format!("{name}.st"))], &out, &[]);
        assert_eq!(again.as_deref(), Some(doc.as_str()), "{name}");
        insta::assert_snapshot!(name, doc);
        // Read back, the same circuit.
        let c = stc_netlist::xml::read(&doc).unwrap();
        assert_eq!(
            stc_netlist::xml::write(&c),
            doc,
            "{name}: write(read(doc)) != doc"
        );
    }
}

#[test]
fn seed_listing_5_1_has_its_modules() {
    let dir = tmp_dir();
    let out = dir.join("l51.xml");
    let (_, doc) = build(&[seed("listing_5_1.st")], &out, &[]);
    let c = stc_netlist::xml::read(&doc.unwrap()).unwrap();
    let census = c.census();
    let count = |n: &str| {
        census
            .iter()
            .find(|(k, _)| *k == n)
            .map(|(_, c)| *c)
            .unwrap_or(0)
    };
    // Four input modules (two BOOL, two DINT as S32), two output modules.
    assert_eq!(count("IC_MODULE-IN-U1"), 4);
    assert_eq!(count("IC_MODULE-OUT"), 2);
    let inputs: Vec<(String, ElemType)> = c
        .components
        .iter()
        .filter_map(|k| match &k.kind {
            stc_netlist::Kind::Input { name, .. } => {
                Some((name.clone(), c.nets[k.outputs[0].index()]))
            }
            _ => None,
        })
        .collect();
    assert_eq!(
        inputs,
        vec![
            ("MainProgram.i_b_switch_1".to_string(), ElemType::Bool),
            ("MainProgram.i_b_switch_2".to_string(), ElemType::Bool),
            ("MainProgram.i_b_sensor_1".to_string(), ElemType::Dint),
            ("MainProgram.i_b_sensor_2".to_string(), ElemType::Dint),
        ]
    );
    assert_eq!(stc_netlist::library::pin_type(ElemType::Dint), "S32");
}

fn simulate(file: &str, inputs: &[(&str, Value)]) -> Vec<(String, Value)> {
    let dir = tmp_dir();
    let out = dir.join(format!("{file}.sim.xml"));
    let (o, doc) = build(&[seed(file)], &out, &[]);
    assert_eq!(o.status, 0, "{}", o.stderr);
    let c = stc_netlist::xml::read(&doc.unwrap()).unwrap();
    let mut sim = Simulator::new(c);
    sim.step(inputs, 0).unwrap()
}

#[test]
fn seed_listings_compute_what_the_programs_mean() {
    let out = simulate(
        "listing_5_3.st",
        &[("MainProgram.i_d_sensor_1", Value::Int(7))],
    );
    assert_eq!(
        out,
        vec![("MainProgram.o_d_valve_1".to_string(), Value::Int(57))]
    );
    let v = |out: &[(String, Value)], n: &str| {
        out.iter()
            .find(|(k, _)| k.ends_with(n))
            .map(|(_, v)| v.clone())
            .unwrap()
    };
    let out = simulate(
        "listing_5_5.st",
        &[("MainProgram.i_d_sensor_1", Value::Int(50))],
    );
    assert_eq!(v(&out, "valve_1"), Value::Bool(true));
    assert_eq!(v(&out, "valve_2"), Value::Bool(false));
    let out = simulate(
        "listing_5_5.st",
        &[("MainProgram.i_d_sensor_1", Value::Int(80))],
    );
    assert_eq!(v(&out, "valve_1"), Value::Bool(false));
    assert_eq!(v(&out, "valve_2"), Value::Bool(true));
    // Listing 5.11: IECC refuses two assignments to an output; the last
    // one is the output's value.
    let out = simulate(
        "listing_5_11.st",
        &[("MainProgram.i_d_sensor_1", Value::Bool(true))],
    );
    assert_eq!(v(&out, "valve_1"), Value::Bool(false));
}

#[test]
fn seed_listings_with_errors_give_diagnostics_and_no_file() {
    let dir = tmp_dir();
    for name in ["listing_5_7.st", "listing_5_9.st"] {
        let out = dir.join(format!("{name}.xml"));
        let (o, doc) = build(&[seed(name)], &out, &["--message-format", "json"]);
        assert_eq!(o.status, 1, "{name}: {}", o.stderr);
        assert!(doc.is_none(), "{name}: a file was written");
        check_annotations(&seed(name)).unwrap();
    }
}

/// The diagnostics of checking and translating a case against its
/// annotations.
fn check_annotations(case: &Path) -> Result<(), String> {
    let (sm, diags) = stc::sources::load(&common::case_files(case)).map_err(|e| e.to_string())?;
    let compiled = stc_pipeline::compile(sm, diags, &Default::default());
    let mut all = compiled.diagnostics.clone();
    if let Some(m) = &compiled.module {
        let p = stc_netlist::choose_program(m, None)?;
        if let Err(r) = stc_netlist::translate(m, p) {
            all.push(r.to_diagnostic(&compiled.sources));
        }
    }
    common::compare(&all, &compiled.sources)
}

#[test]
fn refusals_give_their_diagnostics_status_1_and_no_file() {
    let dir = tmp_dir();
    common::run_all(&common::data_dir().join("netlist/refuse"), |case| {
        check_annotations(case)?;
        let out = dir.join("refused.xml");
        let (o, doc) = build(&common::case_files(case), &out, &[]);
        if o.status != 1 || doc.is_some() {
            return Err(format!(
                "status {} (want 1), file written: {}",
                o.status,
                doc.is_some()
            ));
        }
        Ok(())
    });
}

#[test]
fn an_unwritable_output_is_status_2_and_leaves_nothing() {
    let dir = tmp_dir().join("no-such-dir");
    let out = dir.join("x.xml");
    let (o, doc) = build(&[seed("listing_5_3.st")], &out, &[]);
    assert_eq!(o.status, 2, "{}", o.stderr);
    assert!(o.stderr.contains("cannot write"), "{}", o.stderr);
    assert!(doc.is_none());
    assert!(!dir.exists());
}

// ---- the run conformance suite on the simulated circuit ----------------

struct Expect {
    cycle: Option<u64>,
    path: String,
    value: serde_json::Value,
}

struct Case {
    options: Vec<String>,
    expects: Vec<Expect>,
    fault: Option<(String, u32)>,
}

fn directives(case: &Path) -> Case {
    let mut c = Case {
        options: Vec::new(),
        expects: Vec::new(),
        fault: None,
    };
    for file in common::case_files(case) {
        let text = std::fs::read_to_string(&file).unwrap_or_default();
        for raw in text.lines() {
            let line = raw.trim();
            if let Some(rest) = line.strip_prefix("// run:") {
                c.options = shlex::split(rest).unwrap_or_default();
            } else if let Some(rest) = line.strip_prefix("// expect-fault:") {
                // `KIND @ LINE[:COL] [in INSTANCE (POU)]`: the kind and line.
                if let Some((k, l)) = rest.split_once('@') {
                    let l = l.trim();
                    let digits = l.find(|c: char| !c.is_ascii_digit()).unwrap_or(l.len());
                    c.fault = Some((k.trim().to_string(), l[..digits].parse().unwrap_or(0)));
                }
            } else if let Some(rest) = line.strip_prefix("// expect") {
                let (cycle, rest) = match rest.strip_prefix(" @") {
                    Some(r) => {
                        let (k, r) = r.split_once(':').unwrap_or(("0", ""));
                        (k.trim().parse().ok(), r)
                    }
                    None => (None, rest.strip_prefix(':').unwrap_or("")),
                };
                if let Some((p, v)) = rest.split_once('=') {
                    if let Ok(value) = serde_json::from_str(v.trim()) {
                        c.expects.push(Expect {
                            cycle,
                            path: p.trim().to_string(),
                            value,
                        });
                    }
                }
            }
        }
    }
    c
}

/// The JSON a report shows for a leaf value.
fn json_of(t: ElemType, v: &Value) -> serde_json::Value {
    let mut s = String::new();
    stc_runtime::report::json_value(&mut s, &stc_runtime::value::Shown::Scalar(t, v.clone()));
    serde_json::from_str(&s).unwrap_or(serde_json::Value::Null)
}

/// The integer of an enumerated value written `Type#Value`.
fn enum_value(m: &stc_ir::Module, text: &str) -> Option<i128> {
    let (ty, name) = text.split_once('#')?;
    for i in 0..m.types.len() {
        let t = stc_sema::TypeId(i as u32);
        if let stc_sema::TypeKind::Enum { values, .. } = m.types.kind(t) {
            if m.type_name(t).is_some_and(|n| n.eq_ignore_ascii_case(ty)) {
                if let Some(v) = values
                    .iter()
                    .find(|v| m.name(v.name).eq_ignore_ascii_case(name))
                {
                    return Some(v.value);
                }
            }
        }
    }
    None
}

/// Compares what the simulator holds at `path` with `want`.
fn compare_value(
    sim: &Simulator,
    m: &stc_ir::Module,
    names: &[String],
    path: &str,
    want: &serde_json::Value,
) -> Result<(), String> {
    use serde_json::Value as J;
    if let (Some(v), Some(t)) = (sim.get(path), sim.type_of(path)) {
        let got = json_of(t, v);
        let same = match (want, &got) {
            (J::Number(a), J::Number(b)) => a.as_f64() == b.as_f64(),
            (J::String(s), J::Number(_)) if s.contains('#') => {
                enum_value(m, s).map(Value::Int).as_ref() == Some(v)
            }
            _ => *want == got,
        };
        return if same {
            Ok(())
        } else {
            Err(format!("{path} = {got}, want {want}"))
        };
    }
    let lower = path.to_ascii_lowercase();
    match want {
        J::Object(members) => {
            for (k, w) in members {
                compare_value(sim, m, names, &format!("{path}.{k}"), w)?;
            }
            Ok(())
        }
        J::Array(items) => {
            // The elements of the first dimension, in order.
            let prefix = format!("{lower}[");
            let mut elems: Vec<String> = Vec::new();
            for n in names {
                let nl = n.to_ascii_lowercase();
                if let Some(rest) = nl.strip_prefix(&prefix) {
                    let Some(end) = rest.find(']') else { continue };
                    let first = rest[..end].split(',').next().unwrap_or("");
                    let e = format!("{path}[{first}");
                    let whole = rest[..end].contains(',');
                    let key = if whole {
                        format!("{e},")
                    } else {
                        format!("{e}]")
                    };
                    if !elems.contains(&key) {
                        elems.push(key);
                    }
                }
            }
            if elems.len() != items.len() {
                return Err(format!(
                    "{path}: {} elements, want {}",
                    elems.len(),
                    items.len()
                ));
            }
            for (e, w) in elems.iter().zip(items) {
                if let Some(base) = e.strip_suffix(']') {
                    compare_value(sim, m, names, &format!("{base}]"), w)?;
                } else {
                    // A row of a multi-dimensional array: its elements in order.
                    let row: Vec<&String> = names
                        .iter()
                        .filter(|n| n.to_ascii_lowercase().starts_with(&e.to_ascii_lowercase()))
                        .collect();
                    let J::Array(ws) = w else {
                        return Err(format!("{e}: not a row"));
                    };
                    if row.len() != ws.len() {
                        return Err(format!("{e}: {} elements, want {}", row.len(), ws.len()));
                    }
                    for (n, w) in row.iter().zip(ws) {
                        compare_value(sim, m, names, n, w)?;
                    }
                }
            }
            Ok(())
        }
        _ => Err(format!("{path}: the circuit has no such variable")),
    }
}

/// What happened to one run case on the netlist.
enum Outcome {
    Same,
    /// Not simulated: the reason.
    Skipped(String),
}

fn run_case(case: &Path, dir: &Path) -> Result<Outcome, String> {
    let d = directives(case);
    let mut cycles = 1u64;
    let mut tick: i128 = 10_000_000;
    let mut program = None;
    let mut sets = Vec::new();
    let mut stimulus: Option<PathBuf> = None;
    let mut it = d.options.iter();
    while let Some(o) = it.next() {
        let (k, v) = match o.split_once('=') {
            Some((k, v)) if k.starts_with("--") => (k.to_string(), Some(v.to_string())),
            _ => (o.clone(), None),
        };
        let mut val = || v.clone().or_else(|| it.next().cloned()).unwrap_or_default();
        match k.as_str() {
            "--cycles" => cycles = val().parse().map_err(|_| "bad --cycles")?,
            "--tick" => {
                let t = val();
                let t = if t.to_ascii_uppercase().starts_with("T#") {
                    t
                } else {
                    format!("T#{t}")
                };
                tick = stc_values::parse_value(ElemType::Time, &t)
                    .ok()
                    .and_then(|v| v.as_int())
                    .ok_or("bad --tick")?;
            }
            "--program" => program = Some(val()),
            "--set" => sets.push(val()),
            "--stimulus" => {
                let f = val();
                let base = if case.is_dir() {
                    case
                } else {
                    case.parent().unwrap_or(Path::new("."))
                };
                stimulus = Some(base.join(f));
            }
            "--max-steps" => {
                val();
            }
            other => return Ok(Outcome::Skipped(format!("option {other}"))),
        }
    }
    let files = common::case_files(case);
    let (sm, diags) = stc::sources::load(&files).map_err(|e| e.to_string())?;
    let compiled = stc_pipeline::compile(sm, diags, &Default::default());
    let Some(m) = compiled.module.as_ref() else {
        return Ok(Outcome::Skipped("errors".into()));
    };
    if program.is_none() && !m.configs.is_empty() {
        // The circuit of a configuration is written and valid; it runs
        // under the runtime's scheduler (one enable per step), which the
        // byte comparison with the VM exercises.
        let out = dir.join("case.xml");
        let (o, _) = build(&files, &out, &[]);
        if o.status == 0 {
            xmllint(&out)?;
        }
        return Ok(Outcome::Skipped(
            "a CONFIGURATION (written and validated; run by `stc run --backend netlist`)".into(),
        ));
    }
    let p = stc_netlist::choose_program(m, program.as_deref())?;
    if let Err(r) = stc_netlist::translate(m, p) {
        return Ok(Outcome::Skipped(format!(
            "refused: {} {}",
            r.code, r.message
        )));
    }
    // Through the command and the file, as `--backend netlist` will.
    let out = dir.join("case.xml");
    let mut extra = Vec::new();
    if let Some(p) = &program {
        extra.push("--program");
        extra.push(p.as_str());
    }
    let (o, doc) = build(&files, &out, &extra);
    if o.status != 0 {
        return Err(format!(
            "stc build --emit netlist: status {}: {}",
            o.status, o.stderr
        ));
    }
    xmllint(&out)?;
    let circuit = stc_netlist::xml::read(&doc.unwrap_or_default()).map_err(|e| e.to_string())?;
    let mut sim = Simulator::new(circuit);
    let names: Vec<String> = sim.names().iter().map(|s| s.to_string()).collect();
    let prefix = {
        let pou = m.pou(p);
        m.spelled(pou.name, pou.name_span).to_string()
    };
    for s in &sets {
        let (path, text) = s.split_once('=').ok_or("bad --set")?;
        let Some(t) = sim.type_of(path) else {
            return Ok(Outcome::Skipped(format!(
                "--set {path}: not an input or register"
            )));
        };
        let v = match stc_values::parse_value(t, text) {
            Ok(v) => v,
            Err(_) => match enum_value(m, text) {
                Some(i) => Value::Int(i),
                None => return Ok(Outcome::Skipped(format!("--set {s}"))),
            },
        };
        sim.set(path, v);
    }
    let _ = prefix;
    // `cycle,PATH,...` rows: values set just before their cycle.
    let mut rows: Vec<(u64, Vec<(String, Value)>)> = Vec::new();
    if let Some(f) = &stimulus {
        let text = std::fs::read_to_string(f).map_err(|e| format!("{}: {e}", f.display()))?;
        let mut lines = text.lines();
        let header: Vec<String> = lines
            .next()
            .unwrap_or("")
            .split(',')
            .map(|h| h.trim().to_string())
            .collect();
        for line in lines.filter(|l| !l.trim().is_empty()) {
            let cells: Vec<&str> = line.split(',').map(str::trim).collect();
            let k: u64 = cells
                .first()
                .and_then(|c| c.parse().ok())
                .ok_or("bad stimulus cycle")?;
            let mut vals = Vec::new();
            for (path, text) in header.iter().zip(&cells).skip(1) {
                if text.is_empty() {
                    continue;
                }
                let Some(t) = sim.type_of(path) else {
                    return Ok(Outcome::Skipped(format!(
                        "stimulus {path}: not an input or register"
                    )));
                };
                let v = match stc_values::parse_value(t, text) {
                    Ok(v) => v,
                    Err(_) => match enum_value(m, text) {
                        Some(i) => Value::Int(i),
                        None => return Ok(Outcome::Skipped(format!("stimulus value {text}"))),
                    },
                };
                vals.push((path.clone(), v));
            }
            rows.push((k, vals));
        }
    }
    let check = |sim: &Simulator, k: Option<u64>| -> Result<(), String> {
        for e in d.expects.iter().filter(|e| e.cycle == k) {
            compare_value(sim, m, &names, &e.path, &e.value)
                .map_err(|err| format!("after cycle {}: {err}", k.unwrap_or(cycles)))?;
        }
        Ok(())
    };
    for k in 1..=cycles {
        let now = (k as i128 - 1) * tick;
        for (_, vals) in rows.iter().filter(|(r, _)| *r == k) {
            for (p, v) in vals {
                sim.set(p, v.clone());
            }
        }
        match sim.step(&[], now) {
            Ok(_) => check(&sim, Some(k))?,
            Err(StepError::Fault(f)) => {
                let Some((kind, line)) = &d.fault else {
                    return Err(format!("unexpected fault {f:?} in cycle {k}"));
                };
                if f.kind.text() != kind || f.line != *line {
                    return Err(format!(
                        "fault {} @ {}, want {kind} @ {line}",
                        f.kind.text(),
                        f.line
                    ));
                }
                check(&sim, None)?;
                return Ok(Outcome::Same);
            }
            Err(e) => return Err(e.to_string()),
        }
    }
    if let Some((kind, line)) = &d.fault {
        return Err(format!("no fault, want {kind} @ {line}"));
    }
    check(&sim, None)?;
    Ok(Outcome::Same)
}

#[test]
fn run_cases_give_the_vm_values_on_the_simulated_circuit() {
    let dir = tmp_dir();
    let root = common::data_dir().join("conformance/run");
    let mut lines = Vec::new();
    let mut same = 0;
    let mut failures = Vec::new();
    for case in common::cases(&root) {
        let rel = case
            .strip_prefix(&root)
            .unwrap_or(&case)
            .display()
            .to_string();
        match std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| run_case(&case, &dir))) {
            Ok(Ok(Outcome::Same)) => same += 1,
            Ok(Ok(Outcome::Skipped(why))) => lines.push(format!("{rel}: {why}")),
            Ok(Err(e)) => failures.push(format!("{rel}: {e}")),
            Err(_) => failures.push(format!("{rel}: PANIC")),
        }
    }
    assert!(
        failures.is_empty(),
        "{} cases differ:\n{}",
        failures.len(),
        failures.join("\n")
    );
    lines.insert(
        0,
        format!("{same} cases give the VM's values on the circuit; not simulated:"),
    );
    insta::assert_snapshot!("run_cases_not_simulated", lines.join("\n"));
}

/// `stc run` on the VM and on the netlist (`--backend netlist`, which
/// writes the document, reads it back and simulates it): the same bytes
/// on stdout and stderr and the same status for every run case the
/// netlist can express, with every expected path watched and a report
/// after every cycle.
#[test]
fn run_cases_print_the_same_bytes_on_the_vm_and_the_netlist() {
    let root = common::data_dir().join("conformance/run");
    let mut same = 0;
    let mut other = Vec::new();
    let mut failures = Vec::new();
    for case in common::cases(&root) {
        let rel = case
            .strip_prefix(&root)
            .unwrap_or(&case)
            .display()
            .to_string();
        let d = directives(&case);
        let opts = common::run_options(&case)
            .ok()
            .flatten()
            .unwrap_or_default();
        let mut args: Vec<String> = vec!["stc".into(), "run".into()];
        args.extend(
            common::case_files(&case)
                .iter()
                .map(|f| f.display().to_string()),
        );
        args.extend(opts);
        args.extend(["--format".into(), "json".into(), "--trace".into()]);
        let mut paths: Vec<String> = d.expects.iter().map(|e| e.path.clone()).collect();
        paths.dedup();
        if !paths.is_empty() {
            args.push("--watch".into());
            args.push(paths.join(","));
        }
        let run = |backend: &str| {
            let mut a = args.clone();
            a.extend(["--backend".to_string(), backend.to_string()]);
            let refs: Vec<&str> = a.iter().map(|s| s.as_str()).collect();
            stc::cli::run_args(&refs)
        };
        let vm = run("vm");
        let nl = run("netlist");
        if nl.status == 1 && nl.stderr.contains("error[E11") {
            other.push(format!("{rel}: refused"));
            continue;
        }
        if nl.status == 2 && vm.status != 2 {
            other.push(format!("{rel}: {}", nl.stderr.trim()));
            continue;
        }
        if (vm.status, &vm.stdout, &vm.stderr) == (nl.status, &nl.stdout, &nl.stderr) {
            same += 1;
        } else {
            failures.push(format!(
                "{rel}: vm status {} / netlist {}\n--- vm\n{}{}\n--- netlist\n{}{}",
                vm.status, nl.status, vm.stdout, vm.stderr, nl.stdout, nl.stderr
            ));
        }
    }
    assert!(
        failures.is_empty(),
        "{} cases differ:\n{}",
        failures.len(),
        failures.join("\n")
    );
    other.insert(0, format!("{same} cases print the same bytes; the others:"));
    insta::assert_snapshot!("run_cases_vm_and_netlist", other.join("\n"));
}
